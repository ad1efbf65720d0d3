//! The CSV tables a case refers to, read through the `csv` crate: what a spreadsheet writes
//! (a UTF-8 byte-order mark, CRLF line ends, RFC 4180 quoted fields) is accepted, and every
//! rejection names the CSV file's own 1-based line.

use super::{Case, CaseError};

/// A valid case whose load comes from `load.csv` beside it (`load.file` on line 22).
fn case_text() -> String {
    super::test_case_text("csv_reader", "file = \"load.csv\"", "")
}

/// Parse [`case_text`] with `csv` as its load table (written to a fresh directory).
fn with_table(csv: &[u8]) -> (tempfile::TempDir, Result<Case, CaseError>) {
    let dir = tempfile::tempdir().expect("temporary directory");
    std::fs::write(dir.path().join("load.csv"), csv).expect("write the table");
    let case_path = dir.path().join("case.toml");
    let result = Case::from_text(&case_text(), &case_path);
    (dir, result)
}

fn load_table(case: &Case) -> (Vec<f64>, Vec<[f64; 2]>) {
    let load = case.load();
    let angles = vec![0.0, 90.0, 180.0];
    let values = angles
        .iter()
        .map(|&a| load.load_at_crank_angle(a))
        .collect();
    (angles, values)
}

#[test]
fn a_byte_order_mark_crlf_and_quoted_fields_are_read() {
    let plain = b"crank_angle_deg,load_x_n,load_y_n\n0,-1500,0\n90,-300,200\n180,-900,-200\n";
    let spreadsheet = b"\xEF\xBB\xBF\"crank_angle_deg\",\"load_x_n\",\"load_y_n\"\r\n\
                        \"0\",\"-1500\",0\r\n90,\" -300 \",200\r\n180,-900,\"-200\"\r\n";
    let (_d1, a) = with_table(plain);
    let (_d2, b) = with_table(spreadsheet);
    let (a, b) = (a.expect("plain table"), b.expect("spreadsheet table"));
    let (angles, va) = load_table(&a);
    let (_, vb) = load_table(&b);
    assert_eq!(va, vb, "same loads at {angles:?}");
    assert_eq!(va[0], [-1500.0, 0.0]);
}

#[test]
fn rejections_name_the_file_line_one_based_past_comments_and_blank_lines() {
    // Line 1 comment, 2 header, 3 blank, 4 and 5 rows, 6 the bad row.
    let csv = b"# loads from the test bench\ncrank_angle_deg,load_x_n,load_y_n\n\n0,-1500,0\n90,-300,200\n180,x1,0\n";
    let (dir, r) = with_table(csv);
    let message = r.expect_err("a bad cell").to_string();
    let expected = format!(
        "{}:6: column 'load_x_n': 'x1' is not a finite number (table given by load.file at {}:22)",
        dir.path().join("load.csv").display(),
        dir.path().join("case.toml").display()
    );
    assert_eq!(message, expected);
}

#[test]
fn a_header_error_shows_invisible_characters_and_its_line() {
    // A zero-width space glued to the first header (pasted from a web page): invisible when
    // printed as is, so the message shows it escaped.
    let csv = "\u{200b}crank_angle_deg,load_x_n,load_y_n\n0,-1500,0\n".as_bytes();
    let (dir, r) = with_table(csv);
    let message = r.expect_err("a bad header").to_string();
    let prefix = format!(
        "{}:1: the first column must be",
        dir.path().join("load.csv").display()
    );
    assert!(message.starts_with(&prefix), "{message}");
    assert!(
        message.contains("found '\\u{200b}crank_angle_deg'"),
        "{message}"
    );
}

#[test]
fn an_unterminated_quote_and_a_short_row_are_named() {
    let (dir, r) = with_table(b"crank_angle_deg,load_x_n,load_y_n\n0,-1500,0\n90,-300\n");
    let message = r.expect_err("a short row").to_string();
    assert!(
        message.starts_with(&format!(
            "{}:3: row has 2 cells, the header has 3",
            dir.path().join("load.csv").display()
        )),
        "{message}"
    );
    let (dir, r) = with_table(b"crank_angle_deg,load_x_n,load_y_n\n0,-1500,0\n90,\"-300,200\n");
    let message = r.expect_err("an open quote").to_string();
    assert!(
        message.starts_with(&format!("{}:3:", dir.path().join("load.csv").display())),
        "{message}"
    );
}

/// `[lubricant.vogel]` with a film temperature: the rigorous film gets the Vogel model, every
/// other method μ₀ at the mean temperature (\[Benasciutti2012\]'s T_m = (T_in + T_out)/2 for a linear
/// rise), and the rise spans the converging half of the film unless `rise_span_deg` says
/// otherwise.
#[test]
fn a_vogel_law_sets_the_viscosity_from_the_temperature() {
    use jbearing_solvers::viscosity::{Temperature, Vogel};
    let vogel = "\n[lubricant.vogel]\na_pa_s = 1.446e-4\nb_c = 917.1\nc_c = -70.0\n";
    let text = |temperature: &str| {
        case_text()
            .replace("viscosity_pa_s = 0.02\n", "")
            .replace("[operation]", &format!("{vogel}{temperature}\n[operation]"))
    };
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("load.csv"),
        "crank_angle_deg,load_x_n,load_y_n\n0,-1500,0\n180,-900,200\n",
    )
    .unwrap();
    let path = dir.path().join("case.toml");
    let law = Vogel {
        a: 1.446e-4,
        b: 917.1,
        c: -70.0,
    };
    let mean = Case::from_text(&text("[lubricant.temperature]\nmean_c = 60.0\n"), &path)
        .expect("a Vogel case");
    assert_eq!(mean.viscosity, law.viscosity(60.0));
    let m = mean.viscosity_model.expect("model");
    assert_eq!(m.temperature, Temperature::Constant(60.0));
    assert_eq!(m.pressure_coefficient, 0.0);
    assert_eq!(
        crate::run::reynolds_params(&mean).viscosity_model,
        mean.viscosity_model
    );
    let rise = Case::from_text(
        &text("[lubricant.temperature]\ninlet_c = 40.0\noutlet_c = 80.0\n"),
        &path,
    )
    .expect("a linear rise");
    assert_eq!(rise.viscosity, law.viscosity(60.0));
    assert_eq!(
        rise.viscosity_model.unwrap().temperature,
        Temperature::LinearOverSpan {
            inlet: 40.0,
            outlet: 80.0,
            span: std::f64::consts::PI
        }
    );
    let cold = Case::from_text(&text("[lubricant.temperature]\nmean_c = -80.0\n"), &path)
        .expect_err("below Vogel's c");
    assert!(
        cold.to_string()
            .contains("lubricant.temperature: viscosity model: temperature = -80"),
        "{cold}"
    );
}
