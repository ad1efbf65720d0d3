//! Output writers end to end: the plots, the CSV summary, atomic writes, report validation and
//! parallel writes read back through the HDF5 library. The Python read-back is in
//! `output_python.rs` (its own process, see there why).
//! The data is the writer test fixture of `common` (closed forms, not solver output).

mod common;

use std::path::Path;

use common::{count_color, png_pixels};

use jbearing::output::{
    CaseReport, CsvSummaryWriter, Hdf5Writer, Method, ORBIT_LEGEND_WIDTH, OutputError,
    OutputWriter, ParameterValue, PlotWriter, Reduction, SummaryRow, names, standard_writers,
    write_atomically,
};

/// Width and height from a PNG's IHDR chunk.
fn png_size(path: &Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert!(
        b.starts_with(b"\x89PNG\r\n\x1a\n"),
        "{} is not a PNG",
        path.display()
    );
    let be = |i: usize| u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    (be(16), be(20))
}

#[test]
fn plots_and_csv_summary_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let report = common::report("plots");
    let writer = PlotWriter::default();
    let paths = writer.write(&report, dir.path()).unwrap();
    assert_eq!(paths, PlotWriter::file_paths(&report, dir.path()));
    assert_eq!(paths.len(), 4, "cycle, orbit, load diagram, film map");
    assert_eq!(png_size(&paths[0]), writer.cycle_size);
    // The orbit and the load diagram: a square chart under a 50 px title (no warning), the
    // orbit with its legend strip beside it.
    assert_eq!(
        png_size(&paths[1]),
        (
            writer.orbit_size + ORBIT_LEGEND_WIDTH,
            writer.orbit_size + 50
        )
    );
    assert_eq!(
        png_size(&paths[2]),
        (writer.orbit_size, writer.orbit_size + 50)
    );
    assert_eq!(png_size(&paths[3]), writer.film_size);

    let csv_paths = CsvSummaryWriter.write(&report, dir.path()).unwrap();
    let mut rdr = csv::Reader::from_path(&csv_paths[0]).unwrap();
    let mut rows: Vec<csv::StringRecord> = rdr.records().map(|r| r.unwrap()).collect();
    // The first row is each method's status, before any number.
    let status = rows.remove(0);
    assert_eq!(
        (&status[0], &status[3], &status[4]),
        (
            "status",
            report.method(Method::Rigorous).unwrap().status().as_str(),
            "ok"
        )
    );
    assert_eq!(rows.len(), report.summary.len());
    for (row, want) in rows.iter().zip(&report.summary) {
        assert_eq!(&row[0], want.name);
        assert_eq!(row[3].parse::<f64>().ok(), want.rigorous);
        assert_eq!(row[4].parse::<f64>().ok(), want.mobility);
    }
    // The fixture's mobility h_min is the closed form at 0.9 ε: h = c (1 − 0.9 ε) against
    // c (1 − ε), a positive deviation that the CSV states in percent.
    let dev: f64 = rows[0][5].parse().unwrap();
    let (r, m) = (
        report.summary[0].rigorous.unwrap(),
        report.summary[0].mobility.unwrap(),
    );
    assert!((dev - 100.0 * (m - r) / r).abs() < 1e-9 && dev > 0.0);
    assert_eq!(&rows[3][4], "", "a value a method lacks is an empty cell");

    // Only the finished files are in the directory: no temporaries left behind.
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "plots_cycle.png",
            "plots_film.png",
            "plots_load.png",
            "plots_orbit.png",
            "plots_summary.csv"
        ]
    );
}

#[test]
fn failed_write_leaves_no_file_and_keeps_the_old_one() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("case.h5");
    std::fs::write(&target, b"previous result").unwrap();
    let err = write_atomically(&target, |tmp| {
        std::fs::write(tmp, b"half a file").unwrap();
        Err(OutputError::InvalidReport {
            case: "case".into(),
            what: "simulated failure half-way".into(),
        })
    })
    .unwrap_err();
    assert!(err.to_string().contains("simulated failure"), "{err}");
    assert_eq!(std::fs::read(&target).unwrap(), b"previous result");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "temporary file removed"
    );

    // An HDF5 write that fails inside the library (a series name HDF5 accepts twice is
    // impossible after validation, so use a directory that vanishes) leaves nothing either.
    let gone = dir.path().join("gone");
    let err = Hdf5Writer::new()
        .write(&common::report("x"), &gone)
        .unwrap_err();
    assert!(matches!(err, OutputError::Io { .. }), "{err}");
    assert!(!gone.exists());
}

#[test]
fn invalid_reports_are_rejected_with_the_place_named() {
    let dir = tempfile::tempdir().unwrap();
    type Spoil = Box<dyn Fn(&mut CaseReport)>;
    let cases: Vec<(Spoil, &str)> = vec![
        (
            Box::new(|r| r.methods[0].series[2].values.pop().map(|_| ()).unwrap()),
            "rigorous: series 'feed_pressure' has 72 values for 73 time samples",
        ),
        (
            Box::new(|r| r.methods[1].series[6].values[5] = f64::NAN),
            "mobility: min_film_thickness[5] = NaN is not finite",
        ),
        (
            Box::new(|r| r.methods[0].time[3] = r.methods[0].time[2]),
            "rigorous: time must increase strictly: time[3]",
        ),
        (
            Box::new(|r| r.methods[0].fields.as_mut().unwrap().theta[0] = -0.1),
            "theta must lie in [0, 2π)",
        ),
        (
            Box::new(|r| r.methods[0].series[0].name = "load x".into()),
            "name 'load x' must start with a letter",
        ),
        (
            Box::new(|r| r.geometry.radial_clearance = 0.0),
            "geometry radial_clearance = 0 m must be finite and > 0",
        ),
        (
            Box::new(|r| r.methods[1].method = Method::Rigorous),
            "method rigorous appears twice",
        ),
    ];
    for (spoil, message) in cases {
        let mut r = common::report("bad");
        spoil(&mut r);
        let err = Hdf5Writer::new().write(&r, dir.path()).unwrap_err();
        assert!(
            matches!(err, OutputError::InvalidReport { .. }) && err.to_string().contains(message),
            "expected '{message}', got '{err}'"
        );
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn writers_behind_one_trait() {
    let dir = tempfile::tempdir().unwrap();
    let report = common::report("all");
    let writers = standard_writers();
    assert_eq!(
        writers.iter().map(|w| w.name()).collect::<Vec<_>>(),
        ["hdf5", "plots", "csv-summary"]
    );
    let mut written = Vec::new();
    for w in &writers {
        written.extend(w.write(&report, dir.path()).unwrap());
    }
    // CASE.h5, four figures (cycle, orbit, load diagram, film map), CASE_summary.csv.
    assert_eq!(written.len(), 6);
    assert!(written.iter().all(|p| p.exists()));
    // A second run over the same directory replaces the files (rename over the old ones).
    for w in &writers {
        w.write(&report, dir.path()).unwrap();
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 6);
}

#[test]
fn batch_threads_write_cases_in_parallel() {
    // Batch runs write several cases at once; the HDF5 library is serialised behind one lock
    // (hdf5-metno's, which the dimension-scale calls take too). Every file must come out whole.
    let dir = tempfile::tempdir().unwrap();
    std::thread::scope(|s| {
        for k in 0..4 {
            let dir = dir.path();
            s.spawn(move || {
                for w in standard_writers() {
                    w.write(&common::report(&format!("case{k}")), dir).unwrap();
                }
            });
        }
    });
    for k in 0..4 {
        let f = hdf5_metno::File::open(dir.path().join(format!("case{k}.h5"))).unwrap();
        let p = f.dataset("rigorous/fields/pressure").unwrap();
        assert_eq!(
            p.shape(),
            [common::N_INSTANTS, common::N_THETA, common::N_Z]
        );
        let back: Vec<f64> = f
            .dataset("rigorous/min_film_thickness")
            .unwrap()
            .read_raw()
            .unwrap();
        let want = &common::report("x").methods[0]
            .series(jbearing::output::names::MIN_FILM_THICKNESS)
            .unwrap()
            .values
            .clone();
        assert_eq!(&back, want);
    }
    // Four cases × (CASE.h5, four figures, CASE_summary.csv).
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 24);
}

#[test]
fn cycle_mean_is_time_weighted() {
    // f(t) = 2 + 3 t on [0, 1] has mean 3.5. The trapezoidal rule is exact for a linear f on
    // any sampling, while the plain average of these clustered samples would be 2.78.
    let mut m = common::report("mean").methods.remove(1);
    m.time = vec![0.0, 0.05, 0.1, 0.15, 1.0];
    m.crank_angle = m.time.iter().map(|t| 360.0 * t).collect();
    m.series = vec![jbearing::output::Series::new(
        "power_loss",
        "power loss",
        "W",
        m.time.iter().map(|t| 2.0 + 3.0 * t).collect(),
    )];
    assert!((m.reduce("power_loss", Reduction::Mean).unwrap() - 3.5).abs() < 1e-14);
    assert_eq!(m.reduce("power_loss", Reduction::Min), Some(2.0));
    assert_eq!(m.reduce("power_loss", Reduction::Max), Some(5.0));
    assert_eq!(m.reduce("absent", Reduction::Max), None);
    let row = SummaryRow::from_series(&[m], "power_loss", Reduction::Mean, "p", "mean power");
    assert_eq!((row.units.as_str(), row.rigorous), ("W", None));
    assert!((row.mobility.unwrap() - 3.5).abs() < 1e-14);
}

/// On a periodic cycle (the end point not repeated) the mean covers the whole period: for
/// samples of 2 + cos(2πt/τ) + 0.5 sin(4πt/τ) at 8 equally spaced instants the trapezoidal rule
/// is exact (a trigonometric polynomial of degree below 8), so the mean is 2; without the wrap
/// interval (the samples taken as an open span) it is (16 − (v₀ + v₇)/2)/7 = 1.9138.
#[test]
fn cycle_mean_of_a_periodic_cycle_covers_the_period() {
    use std::f64::consts::TAU;
    let tau = 0.04;
    let mut m = common::report("mean").methods.remove(1);
    m.time = (0..8).map(|k| tau * k as f64 / 8.0).collect();
    m.crank_angle = (0..8).map(|k| 45.0 * k as f64).collect();
    m.series = vec![jbearing::output::Series::new(
        "power_loss",
        "power loss",
        "W",
        m.time
            .iter()
            .map(|t| 2.0 + (TAU * t / tau).cos() + 0.5 * (2.0 * TAU * t / tau).sin())
            .collect(),
    )];
    m.period = Some(tau);
    assert!((m.reduce("power_loss", Reduction::Mean).unwrap() - 2.0).abs() < 1e-14);
    m.period = None;
    let open = m.reduce("power_loss", Reduction::Mean).unwrap();
    let v7 = 2.0 + (7.0 * TAU / 8.0).cos() + 0.5 * (7.0 * TAU / 4.0).sin();
    assert!(
        (open - (16.0 - 0.5 * (3.0 + v7)) / 7.0).abs() < 1e-12,
        "{open}"
    );
}

#[test]
fn a_steady_single_method_report_is_written_too() {
    // The steady JB1 case: rigorous only, one sample, no fields. Every writer copes: the HDF5
    // file has no mobility group and no VTKHDF surface, the plots mark the single point and
    // say "not computed" where nothing is there.
    let dir = tempfile::tempdir().unwrap();
    let mut r = common::report("steady");
    r.methods.truncate(1);
    let m = &mut r.methods[0];
    m.fields = None;
    m.time.truncate(1);
    m.crank_angle.truncate(1);
    m.series.retain(|s| s.name != "power_loss");
    for s in &mut m.series {
        s.values.truncate(1);
    }
    for w in standard_writers() {
        w.write(&r, dir.path()).unwrap();
    }
    let f = hdf5_metno::File::open(dir.path().join("steady.h5")).unwrap();
    let mut groups = f.member_names().unwrap();
    groups.sort();
    assert_eq!(
        groups,
        [
            "input_files",
            "length",
            "parameters",
            "radial_clearance",
            "radius",
            "rigorous",
            "summary"
        ]
    );
    let h: Vec<f64> = f
        .dataset("rigorous/min_film_thickness")
        .unwrap()
        .read_raw()
        .unwrap();
    assert_eq!(h, r.methods[0].series("min_film_thickness").unwrap().values);
    assert_eq!(
        png_size(&dir.path().join("steady_cycle.png")),
        PlotWriter::default().cycle_size
    );
}

#[test]
fn large_case_text_is_kept_whole() {
    // A case with a long inline load table: text far beyond HDF5's 64 KiB compact-attribute
    // limit must still round-trip (variable-length strings live in the global heap).
    let dir = tempfile::tempdir().unwrap();
    let mut r = common::report("big");
    r.case_text = (0..40_000).map(|k| format!("{k},{}\n", k * 7)).collect();
    assert!(r.case_text.len() > 400_000);
    Hdf5Writer::new().write(&r, dir.path()).unwrap();
    let f = hdf5_metno::File::open(dir.path().join("big.h5")).unwrap();
    let back: hdf5_metno::types::VarLenUnicode =
        f.attr("case_text").unwrap().read_scalar().unwrap();
    assert_eq!(back.as_str(), r.case_text);
}

/// What the viewer must know is in the picture: a result that is not periodic puts a red
/// CAUTION line under the title of every figure (none for a periodic one); an intermittent feed
/// shades its window in every panel of the cycle figure (none for a constant feed); the orbit
/// and load diagrams have the title block's height on top of a square chart.
#[test]
fn plots_mark_what_the_viewer_must_know() {
    const WARN_RED: [u8; 3] = [200, 20, 20];
    const FEED_SHADE: [u8; 3] = [255, 236, 200];
    let dir = tempfile::tempdir().unwrap();
    let writer = PlotWriter::default();
    let ok = common::report("ok");
    let paths = writer.write(&ok, dir.path()).unwrap();
    for p in &paths {
        assert_eq!(count_color(p, WARN_RED, 0..90), 0, "{}", p.display());
    }
    assert_eq!(
        count_color(&paths[0], FEED_SHADE, 0..writer.cycle_size.1),
        0
    );

    let mut bad = common::report("bad");
    bad.methods[0]
        .solver_info
        .push(("periodic".into(), ParameterValue::Flag(false)));
    // The feed is open for the first quarter of the cycle only.
    let m = &mut bad.methods[0];
    let crank = m.crank_angle.clone();
    let feed = m
        .series
        .iter_mut()
        .find(|s| s.name == names::FEED_PRESSURE)
        .unwrap();
    for (v, c) in feed.values.iter_mut().zip(&crank) {
        *v = if *c < 90.0 { 2e5 } else { 0.0 };
    }
    let paths = writer.write(&bad, dir.path()).unwrap();
    for p in &paths {
        let red = count_color(p, WARN_RED, 0..90);
        assert!(
            red > 100,
            "{}: {red} red pixels in the title block",
            p.display()
        );
    }
    let (w, h, _) = png_pixels(&paths[1]);
    assert_eq!(
        (w, h),
        (
            writer.orbit_size + ORBIT_LEGEND_WIDTH,
            writer.orbit_size + 84
        )
    );
    let shade = count_color(&paths[0], FEED_SHADE, 0..writer.cycle_size.1);
    // Six panels minus the feed panel's own curve area: each shades a quarter of ~600 × 330 px.
    assert!(shade > 5 * 20_000, "{shade} shaded pixels");
}
