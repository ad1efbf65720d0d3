//! `jbearing run`, `check` and `batch` of a mechanism case (the slider-crank of \[Flores2009\])
//! end to end: the binary runs the shipped case, and its HDF5 file holds the numbers
//! `solve_mechanism` gives when called directly on the paper's parameters
//! (`MechanismParams::flores2009()`, built without the case reader), with units on every
//! variable; the summary CSV holds the direct run's extremes; the figures show the curves and
//! the reference lines. Bad mechanism case files are in `tests/bad_cases/` (`tests/cli.rs`).

use hdf5_metno as h5;
use jbearing_solvers::mechanism::{
    MechanismParams, MechanismSolution, RodSliderJoint, solve_mechanism,
};

const CASE: &str = "cases/flores2009_slider_crank.toml";
const NAME: &str = "flores2009_slider_crank";

mod common;
use common::{count_color, jbearing, png_pixels, root, text};

fn read(f: &h5::File, path: &str) -> Vec<f64> {
    f.dataset(path)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .read_raw::<f64>()
        .unwrap()
}

fn attr(ds: &h5::Dataset, name: &str) -> Option<String> {
    ds.attr(name)
        .ok()?
        .read_scalar::<h5::types::VarLenUnicode>()
        .ok()
        .map(|s| s.as_str().to_string())
}

/// `a` equals `b` to 1e-12 of b's largest magnitude (the same run, read back).
fn assert_same(what: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{what}: length");
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= 1e-12 * scale,
            "{what}[{i}]: file {x}, direct {y}"
        );
    }
}

fn direct() -> (MechanismSolution, MechanismSolution) {
    let p = MechanismParams::flores2009();
    let lubricated = solve_mechanism(&p).expect("lubricated run");
    let ideal = solve_mechanism(&MechanismParams {
        joint: RodSliderJoint::Ideal,
        ..p
    })
    .expect("ideal run");
    (lubricated, ideal)
}

#[test]
fn run_writes_the_slider_crank_files_with_the_solvers_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let out = jbearing(&["run", CASE, "--out", dir.path().to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    for suffix in [
        ".h5",
        "_summary.csv",
        "_forces.png",
        "_orbit.png",
        "_film.png",
    ] {
        let p = dir.path().join(format!("{NAME}{suffix}"));
        let len = std::fs::metadata(&p)
            .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
            .len();
        assert!(len > 100, "{} is only {len} bytes", p.display());
        assert!(
            stdout.contains(&format!("wrote {}", p.display())),
            "{stdout}"
        );
    }

    let (lub, ideal) = direct();
    let f = h5::File::open(dir.path().join(format!("{NAME}.h5"))).unwrap();
    let n = lub.time.len();
    assert_eq!(n, 2 * 360 + 1, "two turns, 360 samples per turn, both ends");
    assert_same("time", &read(&f, "lubricated/time"), &lub.time);
    assert_same(
        "crank_angle",
        &read(&f, "lubricated/crank_angle"),
        &lub.crank_angle_deg,
    );
    let col = |s: &MechanismSolution, g: &dyn Fn(usize) -> f64| -> Vec<f64> {
        (0..s.time.len()).map(g).collect()
    };
    assert_same(
        "lubricated joint_force_x",
        &read(&f, "lubricated/joint_force_x"),
        &col(&lub, &|i| lub.loads[i].rod_slider[0]),
    );
    assert_same(
        "lubricated joint_force_y",
        &read(&f, "lubricated/joint_force_y"),
        &col(&lub, &|i| lub.loads[i].rod_slider[1]),
    );
    assert_same(
        "lubricated crank_moment",
        &read(&f, "lubricated/crank_moment"),
        &col(&lub, &|i| lub.loads[i].crank_moment),
    );
    assert_same(
        "lubricated rod_slider_torque",
        &read(&f, "lubricated/rod_slider_torque"),
        &col(&lub, &|i| lub.loads[i].rod_slider_torque),
    );
    assert_same(
        "eccentricity_y",
        &read(&f, "lubricated/eccentricity_y"),
        &col(&lub, &|i| lub.eccentricity[i][1]),
    );
    assert_same(
        "min_film_thickness",
        &read(&f, "lubricated/min_film_thickness"),
        &lub.min_film_thickness,
    );
    assert_same(
        "ideal joint_force_x",
        &read(&f, "ideal/joint_force_x"),
        &col(&ideal, &|i| ideal.loads[i].rod_slider[0]),
    );
    assert_same(
        "ideal crank_moment",
        &read(&f, "ideal/crank_moment"),
        &col(&ideal, &|i| ideal.loads[i].crank_moment),
    );
    // (time, body): the slider's x and the rod's angle.
    let px = f
        .dataset("lubricated/body_position_x")
        .unwrap()
        .read_2d::<f64>()
        .unwrap();
    assert_eq!(px.dim(), (n, 3));
    assert_same(
        "slider x",
        &px.column(2).to_vec(),
        &col(&lub, &|i| lub.bodies[i][2].position[0]),
    );
    // Units and long names on every numeric variable of both runs; text variables (body,
    // contact_event_kind) have a long name.
    for g in ["lubricated", "ideal"] {
        let group = f.group(g).unwrap();
        for name in group.member_names().unwrap() {
            let ds = group.dataset(&name).unwrap();
            assert!(attr(&ds, "long_name").is_some(), "{g}/{name}: long_name");
            if !matches!(name.as_str(), "body" | "contact_event_kind") {
                assert!(attr(&ds, "units").is_some(), "{g}/{name}: units");
            }
        }
    }
    for (path, units) in [
        ("lubricated/time", "s"),
        ("lubricated/crank_angle", "degree"),
        ("lubricated/joint_force_magnitude", "N"),
        ("lubricated/crank_moment", "N m"),
        ("lubricated/eccentricity_x", "m"),
        ("lubricated/eccentricity_ratio", "1"),
        ("lubricated/min_film_thickness", "m"),
        ("lubricated/body_angle", "rad"),
        ("ideal/joint_force_y", "N"),
        ("parameters/viscosity", "Pa s"),
    ] {
        let ds = f.dataset(path).unwrap();
        assert_eq!(attr(&ds, "units").as_deref(), Some(units), "{path}");
    }
    // The journal orbit only in the lubricated run; no contact at c 0.2 mm, 400 cP ([Flores2009] §8).
    assert!(f.dataset("ideal/eccentricity_x").is_err());
    assert_eq!(read(&f, "lubricated/contact_event_time").len(), 0);
    let onsets: i64 = f
        .group("lubricated")
        .unwrap()
        .attr("contact_onsets")
        .unwrap()
        .read_scalar()
        .unwrap();
    assert_eq!(onsets, 0);
    drop(f);

    // The summary CSV: the direct run's extremes.
    let mut rdr = csv::Reader::from_path(dir.path().join(format!("{NAME}_summary.csv"))).unwrap();
    let rows: Vec<csv::StringRecord> = rdr.records().map(|r| r.unwrap()).collect();
    let value = |name: &str, column: usize| -> f64 {
        rows.iter()
            .find(|r| &r[0] == name)
            .unwrap_or_else(|| panic!("row {name}"))[column]
            .parse()
            .unwrap()
    };
    let peak = |s: &MechanismSolution| {
        s.loads
            .iter()
            .map(|l| l.rod_slider[0].hypot(l.rod_slider[1]))
            .fold(0.0f64, f64::max)
    };
    assert!((value("joint_force_max", 3) - peak(&lub)).abs() < 1e-9 * peak(&lub));
    assert!((value("joint_force_max", 4) - peak(&ideal)).abs() < 1e-9 * peak(&ideal));
    let h_min = lub
        .min_film_thickness
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    assert!((value("min_film_thickness_min", 3) - h_min).abs() < 1e-15);
    assert_eq!(value("contact_onsets", 3), 0.0);
    // [Flores2009] §8: at c 0.2 mm, 400 cP the lubricated joint behaves almost as the ideal one
    // (docs/slider-crank.md: peaks 2726 N against 2719 N); the journal stays off the wall.
    let dev = value("joint_force_max", 5);
    assert!(dev > 0.0 && dev < 1.0, "peak force deviation {dev} %");
    assert!(h_min > 50e-6, "h_min {h_min}");

    // Figures: the lubricated curve (blue) in both panels of the force figure; the safe-film
    // (orange) and contact (red) lines under the h_min curve; the orbit drawn.
    const BLUE: [u8; 3] = [31, 87, 180];
    const ORANGE: [u8; 3] = [230, 140, 0];
    const RED: [u8; 3] = [200, 20, 20];
    let png = |s: &str| dir.path().join(format!("{NAME}_{s}.png"));
    let (_, h, _) = png_pixels(&png("forces"));
    assert!(count_color(&png("forces"), BLUE, 100..h / 2) > 2000);
    assert!(count_color(&png("forces"), BLUE, h / 2..h) > 2000);
    let (_, h, _) = png_pixels(&png("film"));
    assert!(count_color(&png("film"), BLUE, 100..h) > 2000);
    assert!(count_color(&png("film"), ORANGE, 100..h) > 500);
    assert!(count_color(&png("film"), RED, 100..h) > 500);
    assert!(count_color(&png("orbit"), BLUE, 60..1000) > 2000);
}

#[test]
fn check_accepts_the_shipped_mechanism_case() {
    let out = jbearing(&["check", CASE, "cases/flores2006_mobility.toml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains(&format!(
            "{CASE}: ok (mechanism case '{NAME}', lubricated joint c = 0.2000 mm, film \
             pinkus_sternlicht, radau5, 2 turns × 360 samples, with the ideal reference)"
        )),
        "{stdout}"
    );
    assert_eq!(stdout.lines().count(), 2);
}

#[test]
fn batch_runs_a_directory_of_both_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let cases = dir.path().join("cases");
    std::fs::create_dir(&cases).unwrap();
    for f in [
        "flores2009_slider_crank.toml",
        "benasciutti_jb1_steady.toml",
    ] {
        std::fs::copy(root().join("cases").join(f), cases.join(f)).unwrap();
    }
    // An ideal-joint variant: one run, no orbit or film figure.
    let ideal = std::fs::read_to_string(root().join(CASE))
        .unwrap()
        .replace(
            "name = \"flores2009_slider_crank\"",
            "name = \"ideal_crank\"",
        )
        .replace("type = \"lubricated\"", "type = \"ideal\"");
    let ideal: String = ideal
        .lines()
        .filter(|l| {
            ![
                "bearing_radius_m",
                "journal_radius_m",
                "length_m = 0.040",
                "viscosity_pa_s",
                "film =",
                "[mechanism.integrator]",
                "method =",
            ]
            .iter()
            .any(|k| l.starts_with(k))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(cases.join("ideal_crank.toml"), ideal).unwrap();
    let out_dir = dir.path().join("out");
    let out = jbearing(&[
        "batch",
        cases.to_str().unwrap(),
        "--no-progress",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}\n{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains(&format!("{NAME:<26} mechanism:lubricated ok")),
        "{stdout}"
    );
    assert!(
        stdout.contains(&format!("{:<26} mechanism:ideal ok", "ideal_crank")),
        "{stdout}"
    );
    for f in [
        "flores2009_slider_crank.h5",
        "flores2009_slider_crank_orbit.png",
        "ideal_crank.h5",
        "ideal_crank_forces.png",
        "benasciutti_jb1_steady.h5",
        "batch_summary.csv",
    ] {
        assert!(out_dir.join(f).is_file(), "{f} missing: {stdout}");
    }
    assert!(!out_dir.join("ideal_crank_orbit.png").exists());
    // The ideal case's file has the ideal run only, equal to the direct ideal run.
    let f = h5::File::open(out_dir.join("ideal_crank.h5")).unwrap();
    assert!(f.group("lubricated").is_err());
    let (_, ideal) = direct();
    assert_same(
        "ideal crank_moment",
        &read(&f, "ideal/crank_moment"),
        &ideal
            .loads
            .iter()
            .map(|l| l.crank_moment)
            .collect::<Vec<_>>(),
    );
}

/// The shipped case with c 0.5 mm and 40 cP (docs/slider-crank.md study table: dry contact, two onsets): the
/// contact events in the file are the direct run's, kind by kind, and the figures shade where
/// the contact acts.
#[test]
fn contact_events_reach_the_file_and_the_figures() {
    let dir = tempfile::tempdir().unwrap();
    let case_text = std::fs::read_to_string(root().join(CASE))
        .unwrap()
        .replace("name = \"flores2009_slider_crank\"", "name = \"contact\"")
        .replace("journal_radius_m = 9.8e-3", "journal_radius_m = 9.5e-3")
        .replace("viscosity_pa_s = 0.4", "viscosity_pa_s = 0.04");
    let case = dir.path().join("contact.toml");
    std::fs::write(&case, case_text).unwrap();
    let out = jbearing(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        dir.path().to_str().unwrap(),
        "--no-progress",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let p = MechanismParams {
        joint: RodSliderJoint::Lubricated(
            jbearing_solvers::mechanism::LubricatedJointParams::with_clearance(0.5e-3, 0.04),
        ),
        ..MechanismParams::flores2009()
    };
    let direct = solve_mechanism(&p).unwrap();
    assert!(
        direct.contact_events.len() >= 2,
        "{:?}",
        direct.contact_events
    );
    let f = h5::File::open(dir.path().join("contact.h5")).unwrap();
    assert_same(
        "contact_event_time",
        &read(&f, "lubricated/contact_event_time"),
        &direct
            .contact_events
            .iter()
            .map(|e| e.time)
            .collect::<Vec<_>>(),
    );
    assert_same(
        "contact_event_radial_velocity",
        &read(&f, "lubricated/contact_event_radial_velocity"),
        &direct
            .contact_events
            .iter()
            .map(|e| e.radial_velocity)
            .collect::<Vec<_>>(),
    );
    let kinds: Vec<String> = f
        .dataset("lubricated/contact_event_kind")
        .unwrap()
        .read_raw::<h5::types::VarLenUnicode>()
        .unwrap()
        .iter()
        .map(|s| s.as_str().to_string())
        .collect();
    let want: Vec<&str> = direct
        .contact_events
        .iter()
        .map(|e| match e.kind {
            jbearing_solvers::mechanism::ContactEventKind::Onset => "onset",
            jbearing_solvers::mechanism::ContactEventKind::Release => "release",
        })
        .collect();
    assert_eq!(kinds, want);
    assert_same(
        "contact_weight",
        &read(&f, "lubricated/contact_weight"),
        &direct.contact_weight,
    );
    drop(f);
    const SHADE: [u8; 3] = [255, 215, 215];
    let film = dir.path().join("contact_film.png");
    let (_, h, _) = png_pixels(&film);
    assert!(count_color(&film, SHADE, 120..h) > 20_000);
    // No contact, no shade: the shipped case.
    let ok = tempfile::tempdir().unwrap();
    let out = jbearing(&[
        "run",
        CASE,
        "--out",
        ok.path().to_str().unwrap(),
        "--no-progress",
    ]);
    assert!(out.status.success());
    let film = ok.path().join(format!("{NAME}_film.png"));
    assert_eq!(count_color(&film, SHADE, 0..h), 0);
}

/// The Reynolds film through the case file (a coarse grid, one turn, BDF2 by default) gives the
/// direct run's numbers; a sweep over a mechanism key is checked and named per point.
#[test]
fn reynolds_film_and_sweeps_of_mechanism_cases() {
    let dir = tempfile::tempdir().unwrap();
    let case_text = std::fs::read_to_string(root().join(CASE))
        .unwrap()
        .replace("name = \"flores2009_slider_crank\"", "name = \"reynolds\"")
        .replace("turns = 2", "turns = 1")
        .replace(
            "film = \"pinkus_sternlicht\"",
            "film = \"reynolds\"\nn_theta = 40\nn_z = 9",
        )
        .replace("[mechanism.integrator]\nmethod = \"radau5\"\n", "");
    let case = dir.path().join("reynolds.toml");
    std::fs::write(&case, &case_text).unwrap();
    let out = jbearing(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        dir.path().to_str().unwrap(),
        "--no-progress",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let mut p = MechanismParams::flores2009();
    p.turns = 1;
    let RodSliderJoint::Lubricated(j) = &mut p.joint else {
        unreachable!()
    };
    let mut film = j.reynolds_params();
    film.grid.n_theta = 40;
    film.grid.n_z = 9;
    let p_cav = film.cavitation_pressure;
    j.film = jbearing_solvers::mechanism::JointFilm::Reynolds(Box::new(film));
    p.integrator = jbearing_solvers::mechanism::Integrator::bdf2_controlled();
    p.field_snapshots = jbearing_solvers::mechanism::DEFAULT_FIELD_SNAPSHOTS;
    let direct = solve_mechanism(&p).unwrap();
    assert!(direct.info.film_steps > 0);
    let f = h5::File::open(dir.path().join("reynolds.h5")).unwrap();
    assert_same(
        "min_film_thickness",
        &read(&f, "lubricated/min_film_thickness"),
        &direct.min_film_thickness,
    );
    let film_steps: i64 = f
        .group("lubricated")
        .unwrap()
        .attr("film_steps")
        .unwrap()
        .read_scalar()
        .unwrap();
    assert_eq!(film_steps as usize, direct.info.film_steps);

    // Film fields: 24 instants of the (last) turn on the 40 × 9 grid, the direct run's
    // snapshots, with units, long names and dimension scales; p ≥ p_cav everywhere.
    let snaps = direct
        .film_fields
        .as_ref()
        .expect("Reynolds film snapshots");
    assert_eq!(snaps.fields.len(), 24);
    let tau = 60.0 / 5000.0;
    assert!((snaps.time[23] - tau).abs() < 1e-12 && (snaps.time[0] - tau / 24.0).abs() < 1e-12);
    assert_same(
        "field_time",
        &read(&f, "lubricated/fields/field_time"),
        &snaps.time,
    );
    assert_same(
        "field_crank_angle",
        &read(&f, "lubricated/fields/field_crank_angle"),
        &snaps.crank_angle_deg,
    );
    assert_same("theta", &read(&f, "lubricated/fields/theta"), &snaps.theta);
    assert_same("z", &read(&f, "lubricated/fields/z"), &snaps.z);
    assert_eq!(snaps.theta.len(), 40);
    assert_eq!(snaps.z.len(), 9);
    for (name, units, get) in [
        (
            "pressure",
            "Pa",
            (|x| &x.pressure)
                as fn(&jbearing_solvers::inverse::FilmFields) -> &ndarray::Array2<f64>,
        ),
        ("film_content", "1", |x| &x.film_fraction),
    ] {
        let ds = f.dataset(&format!("lubricated/fields/{name}")).unwrap();
        assert_eq!(ds.shape(), vec![24, 40, 9], "{name}");
        assert_eq!(attr(&ds, "units").as_deref(), Some(units), "{name}");
        assert!(attr(&ds, "long_name").is_some_and(|l| !l.is_empty()));
        assert!(
            ds.attr("DIMENSION_LIST").is_ok(),
            "{name}: no dimension scales"
        );
        let want: Vec<f64> = snaps
            .fields
            .iter()
            .flat_map(|fl| get(fl).iter().copied().collect::<Vec<_>>())
            .collect();
        let got = ds.read_raw::<f64>().unwrap();
        assert_same(name, &got, &want);
        if name == "pressure" {
            assert!(got.iter().all(|&v| v >= p_cav), "p < p_cav");
            // The film carries the load: a real pressure peak at every instant.
            for k in 0..24 {
                let peak = got[k * 360..(k + 1) * 360]
                    .iter()
                    .fold(0.0f64, |m, &v| m.max(v));
                assert!(peak > 1e5, "instant {k}: peak {peak} Pa");
            }
        }
    }
    drop(f);

    let sweep = dir.path().join("sweep.toml");
    std::fs::write(
        &sweep,
        std::fs::read_to_string(root().join(CASE)).unwrap()
            + "\n[sweep.values]\n\"mechanism.joint.viscosity_pa_s\" = [0.4, 0.04]\n",
    )
    .unwrap();
    let out = jbearing(&["check", sweep.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stdout).trim(),
        format!(
            "{}: sweep of 2 mechanism cases over mechanism.joint.viscosity_pa_s (2 ok)",
            sweep.display()
        )
    );
    let out = jbearing(&["run", sweep.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("this file is a sweep"),
        "{}",
        text(&out.stderr)
    );
}
