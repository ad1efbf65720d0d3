//! The HDF5 file read back by xarray (h5netcdf) and pyvista in a fresh virtualenv, and the
//! Python plotting example run on it. The data is the writer test fixture of `common`.
//!
//! These tests spawn Python processes, so they live in their own test binary: a child forked
//! while another test thread has an HDF5 file open inherits that descriptor and its `flock`
//! lock (HDF5 does not open with `O_CLOEXEC`), and a later open of the same file in this
//! process then fails with EAGAIN. That race made CI fail once when the writers' tests shared
//! a binary with these.

mod common;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::Instant;

use jbearing::output::{CaseReport, Hdf5Writer, Method, OutputWriter};

/// Values the checker compares with what it reads, one line each: `key v1 v2 …`. f64 `Display`
/// is the shortest string that parses back to the same f64, so the comparison can be exact.
fn expected_values(r: &CaseReport) -> String {
    let mut out = String::new();
    let line = |out: &mut String, key: &str, v: &mut dyn Iterator<Item = f64>| {
        out.push_str(key);
        for x in v {
            write!(out, " {x}").unwrap();
        }
        out.push('\n');
    };
    for m in &r.methods {
        let g = m.method.as_str();
        line(&mut out, &format!("{g}/time"), &mut m.time.iter().copied());
        line(
            &mut out,
            &format!("{g}/crank_angle"),
            &mut m.crank_angle.iter().copied(),
        );
        for s in &m.series {
            line(
                &mut out,
                &format!("{g}/{}", s.name),
                &mut s.values.iter().copied(),
            );
        }
        if let Some(f) = &m.fields {
            line(
                &mut out,
                &format!("{g}/fields/field_time"),
                &mut f.time.iter().copied(),
            );
            line(
                &mut out,
                &format!("{g}/fields/field_crank_angle"),
                &mut f.crank_angle.iter().copied(),
            );
            line(
                &mut out,
                &format!("{g}/fields/theta"),
                &mut f.theta.iter().copied(),
            );
            line(&mut out, &format!("{g}/fields/z"), &mut f.z.iter().copied());
            for fld in &f.fields {
                line(
                    &mut out,
                    &format!("{g}/fields/{}", fld.name),
                    &mut fld.values.iter().copied(),
                );
            }
        }
    }
    for row in &r.summary {
        let v = Method::ALL.map(|m| row.value(m).unwrap_or(f64::NAN));
        line(
            &mut out,
            &format!("summary/{}", row.name),
            &mut v.into_iter(),
        );
    }
    out
}

fn fixture_file(dir: &Path, name: &str) -> (CaseReport, PathBuf) {
    let report = common::report(name);
    let written = Hdf5Writer::new().write(&report, dir).expect("HDF5 written");
    assert_eq!(written, vec![dir.join(format!("{name}.h5"))]);
    (report, written[0].clone())
}

/// A virtualenv with examples/python/requirements.txt, created once per requirements content
/// under the target directory (a clean clone gets a fresh one; reruns reuse it). The Python
/// interpreter is `python3` from PATH, or `$JBEARING_PYTHON`.
fn python_env() -> PathBuf {
    static VENV: OnceLock<PathBuf> = OnceLock::new();
    VENV.get_or_init(|| {
        let start = Instant::now();
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let requirements = root.join("examples/python/requirements.txt");
        let wanted = std::fs::read_to_string(&requirements).expect("requirements.txt");
        let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-venv");
        let stamp = venv.join("jbearing-requirements.txt");
        let python = venv.join("bin/python");
        if std::fs::read_to_string(&stamp).ok().as_deref() == Some(wanted.as_str())
            && python.exists()
        {
            return python;
        }
        let _ = std::fs::remove_dir_all(&venv);
        let base = std::env::var("JBEARING_PYTHON").unwrap_or_else(|_| "python3".into());
        run(
            Command::new(&base).args(["-m", "venv"]).arg(&venv),
            "python3 -m venv",
        );
        run(
            Command::new(&python)
                .args([
                    "-m",
                    "pip",
                    "install",
                    "--quiet",
                    "--disable-pip-version-check",
                    "-r",
                ])
                .arg(&requirements),
            "pip install -r examples/python/requirements.txt",
        );
        std::fs::write(&stamp, wanted).unwrap();
        eprintln!(
            "python virtualenv created in {:.1} s: {}",
            start.elapsed().as_secs_f64(),
            venv.display()
        );
        python
    })
    .clone()
}

fn run(cmd: &mut Command, what: &str) -> String {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start: {e} (run scripts/deps.sh)"));
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{what} failed ({}):\n--- stdout\n{stdout}\n--- stderr\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

#[test]
fn hdf5_file_reads_back_in_xarray_and_pyvista() {
    let python = python_env();
    let dir = tempfile::tempdir().unwrap();
    let (report, path) = fixture_file(dir.path(), "short_bearing_fixture");
    let expected = dir.path().join("expected.txt");
    std::fs::write(&expected, expected_values(&report)).unwrap();
    let checker = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/check_output.py");
    let start = Instant::now();
    let out = run(
        Command::new(&python)
            // Readers only: h5py, h5netcdf and VTK's own HDF5 open the same file in one process;
            // HDF5's advisory file locks make those opens race (errno 11).
            .env("HDF5_USE_FILE_LOCKING", "FALSE")
            .arg(&checker)
            .arg(&path)
            .arg(&expected),
        "tests/python/check_output.py",
    );
    eprintln!("checker ran in {:.1} s", start.elapsed().as_secs_f64());
    assert!(out.contains("all checks passed"), "{out}");
}

#[test]
fn python_example_plots_from_the_file() {
    let python = python_env();
    let dir = tempfile::tempdir().unwrap();
    let (_, path) = fixture_file(dir.path(), "example");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/python/plot_case.py");
    let out = run(
        Command::new(&python)
            .env("HDF5_USE_FILE_LOCKING", "FALSE")
            .args(["-W", "error"])
            .arg(&script)
            .arg(&path)
            .arg("--out")
            .arg(dir.path()),
        "examples/python/plot_case.py",
    );
    for png in ["example_series.png", "example_pressure.png"] {
        let bytes = std::fs::read(dir.path().join(png)).unwrap_or_else(|e| panic!("{png}: {e}"));
        assert!(
            bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
            "{png} is not a PNG"
        );
    }
    // The example prints the surface it read through pyvista: one point per (θ, z) node.
    let points = common::N_THETA * common::N_Z;
    assert!(out.contains(&format!("surface: {points} points")), "{out}");
}

/// The `closed_form` group opens in xarray with `model` as its dimension and string coordinate
/// (the \[Flores2009\] simple bearing's table on the writer fixture).
#[test]
fn closed_form_group_opens_in_xarray() {
    let python = python_env();
    let dir = tempfile::tempdir().unwrap();
    let case = jbearing::case::Case::from_file(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/flores2009_simple_bearing.toml"),
    )
    .unwrap();
    let mut report = common::report("closed_form_fixture");
    report.closed_form = jbearing::closed_form_report::report_table(&case, &[]);
    let table = report.closed_form.clone().expect("the case asks for it");
    let path = Hdf5Writer::new().write(&report, dir.path()).unwrap()[0].clone();
    let script = "import sys, xarray as xr\n\
        d = xr.open_dataset(sys.argv[1], engine='h5netcdf', group='closed_form')\n\
        print('dims', dict(d.sizes))\n\
        print('eccentricity_ratio dims', d.eccentricity_ratio.dims, d.eccentricity_ratio.attrs['units'])\n\
        print('min_film_thickness units', d.min_film_thickness.attrs['units'])\n\
        for m in d.model.values:\n\
        \x20   print('row', m, repr(float(d.eccentricity_ratio.sel(model=m))))\n";
    let out = run(
        Command::new(&python)
            .env("HDF5_USE_FILE_LOCKING", "FALSE")
            .args(["-c", script])
            .arg(&path),
        "xarray closed_form",
    );
    assert!(out.contains("dims {'model': 6}"), "{out}");
    assert!(
        out.contains("eccentricity_ratio dims ('model',) 1"),
        "{out}"
    );
    assert!(out.contains("min_film_thickness units m"), "{out}");
    for r in &table.rows {
        // Python's repr of a float is the shortest round-trip string, as Rust's Display.
        let line = format!("row {} {}", r.model, r.eccentricity_ratio);
        assert!(out.contains(&line), "{line} not in\n{out}");
    }
}

/// A merged sweep (`jbearing batch` + `jbearing merge` on the cheap 3 × 2 sweep of the sweep
/// tests) opens in xarray with the swept keys as coordinates of `case`: the heat-map example
/// selects by a key's value, unstacks the factorial sweep into a grid and plots it.
#[test]
fn merged_sweep_selects_by_swept_key_and_plots() {
    let python = python_env();
    let dir = tempfile::tempdir().unwrap();
    let case = common::sweep_case(dir.path());
    let out_dir = dir.path().join("out");
    let merged = dir.path().join("sweep.nc");
    for args in [
        vec![
            "batch",
            case.to_str().unwrap(),
            "--no-progress",
            "--out",
            out_dir.to_str().unwrap(),
        ],
        vec![
            "merge",
            out_dir.to_str().unwrap(),
            "--out",
            merged.to_str().unwrap(),
        ],
    ] {
        run(
            Command::new(env!("CARGO_BIN_EXE_jbearing")).args(&args),
            &format!("jbearing {}", args[0]),
        );
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/python/sweep_heatmap.py");
    let png = dir.path().join("heat.png");
    let out = run(
        Command::new(&python)
            .env("HDF5_USE_FILE_LOCKING", "FALSE")
            .arg(&script)
            .arg(&merged)
            .arg("--out")
            .arg(&png),
        "examples/python/sweep_heatmap.py",
    );
    // Selecting clearance 30 µm leaves that clearance's two viscosities.
    assert!(out.contains("radial_clearance_m = 3e-05: 2 cases"), "{out}");
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
}

/// The deformable bearing's file (`cases/benasciutti_jb1_elastic.toml` run by the application)
/// opens in pyvista as one unstructured grid of both bodies — the shaft annulus and the square
/// housing, whose quads tile the section exactly: the bore's 240-gon is both bodies' edge and
/// cancels, the housing's corners are nodes (240 is a multiple of 8), so the total area is the
/// square's (2H)² less the hole's inscribed 240-gon, (n/2) r_h² sin(2π/n), to rounding (a
/// missing or doubled cell would change it by at least the smallest cell, 7e-6 m²) — and the
/// `elastic` group opens in xarray along its `angle` dimension.
#[test]
fn elastic_file_reads_back_in_pyvista_and_xarray() {
    let python = python_env();
    let dir = tempfile::tempdir().unwrap();
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/benasciutti_jb1_elastic.toml");
    let out = jbearing::run::run_case_file(
        &case,
        dir.path(),
        &jbearing::budget::Limits::default(),
        &jbearing::run::Quiet,
    )
    .unwrap();
    let path = dir.path().join("benasciutti_jb1_elastic.h5");
    let bodies = &out.report.elastic.as_ref().unwrap().bodies;
    let n_points: usize = bodies.iter().map(|b| b.points.len()).sum();
    let script = "import sys, numpy as np, pyvista as pv, xarray as xr\n\
        m = pv.read(sys.argv[1], force_ext='.vtkhdf')\n\
        print('grid', type(m).__name__, m.n_points)\n\
        area = m.compute_cell_sizes(length=False, volume=False).cell_data['Area']\n\
        print('area', repr(float(area.sum())), 'min', repr(float(area.min())))\n\
        print('bodies', sorted(set(int(b) for b in m.cell_data['body'])))\n\
        print('point data', sorted(m.point_data.keys()))\n\
        print('displacement finite', bool(np.isfinite(m.point_data['displacement']).all()))\n\
        d = xr.open_dataset(sys.argv[1], engine='h5netcdf', group='elastic')\n\
        print('bore dims', d.bore_von_mises_stress.dims, d.bore_von_mises_stress.attrs['units'])\n";
    let printed = run(
        Command::new(&python)
            .env("HDF5_USE_FILE_LOCKING", "FALSE")
            .args(["-c", script])
            .arg(&path),
        "pyvista elastic",
    );
    assert!(
        printed.contains(&format!("grid UnstructuredGrid {n_points}")),
        "{printed}"
    );
    let area: f64 = printed
        .lines()
        .find_map(|l| l.strip_prefix("area "))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no area in {printed}"));
    let (h, r_h, n) = (0.5, 0.1, 240.0);
    let exact = 4.0 * h * h - 0.5 * n * r_h * r_h * (std::f64::consts::TAU / n).sin();
    assert!((area - exact).abs() < 1e-9, "area {area} vs {exact}");
    assert!(printed.contains("bodies [0, 1]"), "{printed}");
    assert!(printed.contains("'displacement'") && printed.contains("'von_mises_stress'"));
    assert!(printed.contains("displacement finite True"), "{printed}");
    assert!(printed.contains("bore dims ('angle',) Pa"), "{printed}");
}
