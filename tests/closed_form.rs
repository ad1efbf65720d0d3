//! The closed-form static-equilibrium table in the report and in `CASE.h5`: the \[Flores2009\] simple
//! bearing (`cases/flores2009_simple_bearing.toml`) solved in this process, its HDF5 file read
//! back with hdf5-metno. The CLI side is in `tests/cli.rs`.
//!
//! Every test here holds [`SERIAL`] for its whole run: a child process forked while another
//! thread has an HDF5 file open inherits its descriptor and flock lock, so a parallel
//! `File::open` fails with EAGAIN. (`solve_case` no longer forks — the commit is recorded at
//! build time — but the lock keeps these tests safe from any child a future change adds.)

use std::path::PathBuf;

use hdf5_metno as h5;
use hdf5_metno::types::VarLenUnicode;
use jbearing::case::Case;
use jbearing::output::{Hdf5Writer, OutputWriter};
use jbearing::run::{Quiet, solve_case};

/// Serialises the tests of this binary (see the module docs).
static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn serial() -> std::sync::MutexGuard<'static, ()> {
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

fn flores_case() -> Case {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/flores2009_simple_bearing.toml");
    Case::from_file(&p).unwrap()
}

/// docs/validation.md "Closed-form models and Ritz", \[Flores2009\] Table 1 simple bearing table: ε per model from
/// the published closed forms (\[Flores2009\] eqs. 6–13; \[Flores2006\] eqs. 36–37), printed to 4 decimals.
const README_EPS: [(&str, f64); 5] = [
    ("long_sommerfeld", 0.0842),
    ("long_gumbel", 0.1673),
    ("short_sommerfeld", 0.0603),
    ("short_gumbel", 0.1174),
    ("short_gumbel_moving_film", 0.1174),
];

#[test]
fn closed_form_group_reads_back_with_model_dimension_and_units() {
    let _serial = serial();
    let case = flores_case();
    let report = solve_case(&case, &Quiet).unwrap();
    let table = report
        .closed_form
        .as_ref()
        .expect("[closed_form] asks for it");
    assert_eq!(table.rows.len(), 6, "models = \"all\": six models");
    let dir = tempfile::tempdir().unwrap();
    let files = Hdf5Writer::new().write(&report, dir.path()).unwrap();
    let f = h5::File::open(&files[0]).unwrap();
    let g = f.group("closed_form").unwrap();

    let models: Vec<VarLenUnicode> = g.dataset("model").unwrap().read_raw().unwrap();
    let models: Vec<String> = models.iter().map(|m| m.as_str().to_string()).collect();
    let eps: Vec<f64> = g.dataset("eccentricity_ratio").unwrap().read_raw().unwrap();
    let h_min: Vec<f64> = g.dataset("min_film_thickness").unwrap().read_raw().unwrap();
    let fy: Vec<f64> = g.dataset("film_force_y").unwrap().read_raw().unwrap();
    let resid: Vec<f64> = g.dataset("force_residual").unwrap().read_raw().unwrap();
    let status: Vec<VarLenUnicode> = g.dataset("status").unwrap().read_raw().unwrap();
    assert_eq!(models.len(), 6);
    for (name, want) in README_EPS {
        let k = models
            .iter()
            .position(|m| m == name)
            .unwrap_or_else(|| panic!("{name}"));
        // docs/validation.md prints 4 decimals: half a unit in the last place.
        assert!(
            (eps[k] - want).abs() <= 0.5e-4,
            "{name}: ε {} vs {want}",
            eps[k]
        );
        // h_min = c (1 − ε), [Flores2009] eq. 42, c = 0.2 mm.
        assert!((h_min[k] - 2.0e-4 * (1.0 - eps[k])).abs() < 1e-15);
        // Force balance: F_y = −W_y = 31.275 N ([Flores2009] §7: converged F_Y = 31.275 N).
        assert!((fy[k] - 31.275).abs() < 1e-9, "{name}: F_y {}", fy[k]);
        assert!(resid[k] < 1e-9);
        assert_eq!(status[k].as_str(), "ok");
    }

    // netCDF-4 dimension: `model` is a dimension scale, variables carry DIMENSION_LIST and units.
    let model = g.dataset("model").unwrap();
    let class: h5::types::FixedAscii<16> = model.attr("CLASS").unwrap().read_scalar().unwrap();
    assert_eq!(class.as_str(), "DIMENSION_SCALE");
    for (var, units) in [
        ("eccentricity_ratio", "1"),
        ("attitude_angle", "rad"),
        ("min_film_thickness", "m"),
        ("film_force_x", "N"),
        ("sommerfeld_number", "1"),
    ] {
        let ds = g.dataset(var).unwrap();
        assert_eq!(ds.shape(), vec![6], "{var}");
        let u: VarLenUnicode = ds.attr("units").unwrap().read_scalar().unwrap();
        assert_eq!(u.as_str(), units, "{var}");
        assert!(
            ds.attr_names()
                .unwrap()
                .contains(&"DIMENSION_LIST".to_string()),
            "{var}"
        );
    }
    let att: Vec<f64> = g.dataset("attitude_angle").unwrap().read_raw().unwrap();
    let k = models.iter().position(|m| m == "long_sommerfeld").unwrap();
    // The full-film long bearing sits at 90° to the load (Sommerfeld), docs/validation.md table 90.00°.
    assert!((att[k].to_degrees() - 90.0).abs() < 1e-6);
    let wy: f64 = g.attr("load_y").unwrap().read_scalar().unwrap();
    assert_eq!(wy, -31.275);
}

#[test]
fn no_closed_form_table_unless_asked() {
    let _serial = serial();
    let case = flores_case();
    let text = case.text.replace("[closed_form]\nmodels = \"all\"\n", "");
    assert_ne!(text, case.text);
    let case = Case::from_text(&text, case.path.as_ref().unwrap()).unwrap();
    assert!(case.closed_form_models.is_empty());
    let report = solve_case(&case, &Quiet).unwrap();
    assert!(report.closed_form.is_none());
    let dir = tempfile::tempdir().unwrap();
    let files = Hdf5Writer::new().write(&report, dir.path()).unwrap();
    let f = h5::File::open(&files[0]).unwrap();
    assert!(f.group("closed_form").is_err());
}

#[test]
fn model_list_and_unknown_model() {
    let _serial = serial();
    let case = flores_case();
    let path = case.path.clone().unwrap();
    let two = case.text.replace(
        "models = \"all\"",
        "models = [\"short_gumbel\", \"long_sommerfeld\", \"short_gumbel\"]",
    );
    let c = Case::from_text(&two, &path).unwrap();
    let names: Vec<&str> = c.closed_form_models.iter().map(|m| m.name()).collect();
    assert_eq!(names, ["short_gumbel", "long_sommerfeld"]);
    let bad = case
        .text
        .replace("models = \"all\"", "models = [\"short_gumbl\"]");
    let e = Case::from_text(&bad, &path).unwrap_err().to_string();
    assert!(
        e.contains("closed_form.models") && e.contains("short_gumbl"),
        "{e}"
    );
}

/// The `fd_reynolds` row of a steady case comes from the rigorous method's journal-centre
/// series: a journal held at ε = 0.5, γ = −30° under the load along −y (ω > 0) sits 60° from the
/// load line in the direction of rotation (hand geometry: φ = γ − angle(W) = −30° − (−90°)).
#[test]
fn fd_reynolds_row_from_a_steady_rigorous_result() {
    let _serial = serial();
    use jbearing::closed_form_report::{FD_ROW, report_table};
    use jbearing::output::{Method, MethodResult, Series, names};
    let case = flores_case();
    let c = case.radial_clearance;
    let gamma = (-30.0f64).to_radians();
    let n = 5;
    let constant = |v: f64| vec![v; n];
    let rig = MethodResult {
        period: None,
        method: Method::Rigorous,
        time: (0..n).map(|k| k as f64 * 0.01).collect(),
        crank_angle: (0..n).map(|k| k as f64 * 30.0).collect(),
        series: vec![
            Series::new(
                names::ECCENTRICITY_X,
                "e_x",
                "m",
                constant(0.5 * c * gamma.cos()),
            ),
            Series::new(
                names::ECCENTRICITY_Y,
                "e_y",
                "m",
                constant(0.5 * c * gamma.sin()),
            ),
            Series::new(names::MIN_FILM_THICKNESS, "h_min", "m", constant(0.5 * c)),
        ],
        fields: None,
        solver_info: Vec::new(),
    };
    let t = report_table(&case, &[rig]).unwrap();
    assert_eq!(t.rows.len(), 7);
    let fd = t.rows.last().unwrap();
    assert_eq!(fd.model, FD_ROW);
    assert!((fd.eccentricity_ratio - 0.5).abs() < 1e-12);
    assert!((fd.attitude_angle.to_degrees() - 60.0).abs() < 1e-9);
    assert!((fd.min_film_thickness - 0.5 * c).abs() < 1e-15);
    assert!(fd.film_force[0].is_nan() && fd.force_residual.is_nan());
    // The same Sommerfeld number as the closed-form rows (same load, speed, geometry).
    assert!((fd.sommerfeld_number - t.rows[0].sommerfeld_number).abs() < 1e-12);
    // Written with NaN as the fill value, it passes the report checks.
    let mut report = solve_case(&case, &Quiet).unwrap();
    report.closed_form = Some(t);
    let dir = tempfile::tempdir().unwrap();
    let files = Hdf5Writer::new().write(&report, dir.path()).unwrap();
    let f = h5::File::open(&files[0]).unwrap();
    let fx: Vec<f64> = f
        .dataset("closed_form/film_force_x")
        .unwrap()
        .read_raw()
        .unwrap();
    assert_eq!(fx.len(), 7);
    assert!(fx[6].is_nan());
}

/// A dynamic case balances the cycle-mean load: for the compressor main bearing's linear,
/// 1°-spaced periodic table the mean of the piecewise-linear history is the trapezoidal mean of
/// the table points (exact for linear pieces; the 3600-sample mean of the code differs from it
/// by the sampling of each piece, below 1e-9 of the peak for 10 samples per 1° piece).
#[test]
fn dynamic_case_uses_the_cycle_mean_load() {
    let _serial = serial();
    use jbearing::closed_form_report::{equilibrium_load, is_steady, table};
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/compressor_main.toml");
    let case = Case::from_file(&p).unwrap();
    assert!(!is_steady(&case));
    let a = &case.load_angles_deg;
    let w = &case.load_forces;
    let n = a.len();
    let mut mean = [0.0; 2];
    let mut peak: f64 = 0.0;
    for k in 0..n {
        let (a1, w1) = if k + 1 < n {
            (a[k + 1], w[k + 1])
        } else {
            (a[0] + case.cycle_deg, w[0])
        };
        for i in 0..2 {
            mean[i] += 0.5 * (w[k][i] + w1[i]) * (a1 - a[k]) / case.cycle_deg;
        }
        peak = peak.max(w[k][0].hypot(w[k][1]));
    }
    let got = equilibrium_load(&case);
    for i in 0..2 {
        assert!(
            (got[i] - mean[i]).abs() < 1e-9 * peak,
            "{i}: {got:?} vs {mean:?}"
        );
    }
    let t = table(&case, &jbearing_solvers::closed_form::ClosedFormModel::ALL);
    assert_eq!(t.load_basis, "cycle-mean load");
    for r in &t.rows {
        assert_eq!(r.status, "ok", "{}", r.model);
        // Force balance of the bisection (1e-15 in ε): far below a micro-newton here.
        assert!(
            r.force_residual < 1e-6 * peak,
            "{}: {}",
            r.model,
            r.force_residual
        );
    }
}
