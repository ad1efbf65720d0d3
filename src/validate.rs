//! `jbearing validate`: the validation cases of `cases/` against the published values they come
//! with, as one table. The full validation ladder (docs/conventions.md §8) is the test suite of the
//! `validation/` crate (`bash scripts/test.sh`); this command is the quick look a user can run
//! from an installed binary.
//!
//! | case | quantity | reference (provenance) |
//! |---|---|---|
//! | flores2006_mobility | cycle-minimum h_min | ≥ 1.5 × 2.5 µm: the paper's safe-film rule (\[Flores2006\] §5, Fig. 9) |
//! | flores2006_mobility | max ε | < 1: "within the bearing boundaries" (\[Flores2006\] Fig. 7a) |
//! | benasciutti_jb1_steady | e, h_0, p_max | \[Benasciutti2012\] Table 2, JB1 T_m const., α = 0 |

use std::path::Path;
use std::process::ExitCode;

use crate::output::{Method, Reduction, names};
use crate::run::{Quiet, run_case_file};

struct Row {
    case: &'static str,
    quantity: &'static str,
    method: &'static str,
    computed: f64,
    reference: f64,
    /// `Some(true)` pass, `Some(false)` fail, `None` reported only (no acceptance bound: the
    /// method is not expected to reproduce the reference, e.g. a short-bearing mobility on a
    /// L/D = 0.6 steady bearing).
    pass: Option<bool>,
    note: &'static str,
}

/// Run the validation cases from `cases_dir`, write their results into `out`, print the table.
pub fn run(cases_dir: &Path, out: &Path) -> ExitCode {
    let mut rows = Vec::new();
    let mut failed = false;
    for (file, check) in [
        (
            "flores2006_mobility.toml",
            flores as fn(&crate::output::CaseReport, &mut Vec<Row>),
        ),
        ("benasciutti_jb1_steady.toml", jb1),
    ] {
        let path = cases_dir.join(file);
        match run_case_file(&path, out, &crate::budget::Limits::default(), &Quiet) {
            Ok(o) => check(&o.report, &mut rows),
            Err(e) => {
                eprintln!("error: {e}");
                failed = true;
            }
        }
    }
    println!(
        "{:<24} {:<28} {:<9} {:>12} {:>12} {:>9}  result",
        "case", "quantity", "method", "computed", "reference", "dev %"
    );
    for r in &rows {
        let dev = 100.0 * (r.computed - r.reference) / r.reference.abs();
        let result = match r.pass {
            Some(true) => "pass",
            Some(false) => {
                failed = true;
                "FAIL"
            }
            None => "reported",
        };
        println!(
            "{:<24} {:<28} {:<9} {:>12.5} {:>12.5} {:>9.2}  {result} {}",
            r.case, r.quantity, r.method, r.computed, r.reference, dev, r.note
        );
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn flores(report: &crate::output::CaseReport, rows: &mut Vec<Row>) {
    let Some(m) = report.method(Method::Mobility) else {
        return;
    };
    if let Some(h) = m.reduce(names::MIN_FILM_THICKNESS, Reduction::Min) {
        rows.push(Row {
            case: "flores2006_mobility",
            quantity: "h_min,min [µm]",
            method: "mobility",
            computed: h * 1e6,
            reference: 3.75,
            pass: Some(h * 1e6 >= 3.75),
            note: "bound: ≥ 1.5 × 2.5 µm ([Flores2006] §5)",
        });
    }
    if let Some(e) = m.reduce(names::ECCENTRICITY_RATIO, Reduction::Max) {
        rows.push(Row {
            case: "flores2006_mobility",
            quantity: "ε_max [-]",
            method: "mobility",
            computed: e,
            reference: 1.0,
            pass: Some(e < 1.0),
            note: "bound: < 1 ([Flores2006] Fig. 7a)",
        });
    }
}

fn jb1(report: &crate::output::CaseReport, rows: &mut Vec<Row>) {
    let c = report.geometry.radial_clearance;
    // The closed-form static equilibria ([Flores2009] models): reported, no bound — JB1 has
    // L/D = 0.6, neither short nor long.
    for model in ["short_gumbel", "long_gumbel", "pinkus_sternlicht"] {
        if let Some(e) = report
            .closed_form_row(model)
            .filter(|r| r.status == "ok")
            .map(|r| r.eccentricity_ratio)
        {
            rows.push(Row {
                case: "benasciutti_jb1_steady",
                quantity: match model {
                    "short_gumbel" => "e [mm], short Gumbel",
                    "long_gumbel" => "e [mm], long Gumbel",
                    _ => "e [mm], Pinkus-Sternlicht",
                },
                method: "closed",
                computed: e * c * 1e3,
                reference: 0.2335,
                pass: None,
                note: "closed form, [Benasciutti2012] Table 2",
            });
        }
    }
    for method in Method::ALL {
        let Some(m) = report.method(method) else {
            continue;
        };
        let pass = |dev: f64, tol: f64| match method {
            Method::Rigorous => Some(dev.abs() <= tol),
            Method::Mobility => None,
        };
        if let Some(e) = m.reduce(names::ECCENTRICITY_RATIO, Reduction::Mean) {
            let v = e * c * 1e3;
            rows.push(Row {
                case: "benasciutti_jb1_steady",
                quantity: "e [mm]",
                method: method.as_str(),
                computed: v,
                reference: 0.2335,
                pass: pass((v - 0.2335) / 0.2335, 0.01),
                note: "[Benasciutti2012] Table 2",
            });
        }
        if let Some(h) = m.reduce(names::MIN_FILM_THICKNESS, Reduction::Mean) {
            rows.push(Row {
                case: "benasciutti_jb1_steady",
                quantity: "h_0 [mm]",
                method: method.as_str(),
                computed: h * 1e3,
                reference: 0.0165,
                pass: pass((h * 1e3 - 0.0165) / 0.0165, 0.05),
                note: "[Benasciutti2012] Table 2",
            });
        }
        if let Some(p) = m.reduce(names::MAX_PRESSURE, Reduction::Mean) {
            rows.push(Row {
                case: "benasciutti_jb1_steady",
                quantity: "p_max [MPa]",
                method: method.as_str(),
                computed: p * 1e-6,
                reference: 82.26,
                pass: pass((p * 1e-6 - 82.26) / 82.26, 0.02),
                note: "[Benasciutti2012] Table 2",
            });
        }
    }
}
