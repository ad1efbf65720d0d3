//! Batch runs: many cases in parallel (rayon), a progress bar per case (indicatif) showing the
//! method, the cycle and the residual, and a summary table at the end (printed and as CSV).
//! A failing case is reported in the table and does not stop the others.
//!
//! ```text
//!   [FILES | DIR/*.toml] ──rayon par_iter──► run_case_file (one per case, own bar)
//!                                           ├─ Ok  → row: h_min, mean flow, mean power loss, …
//!                                           └─ Err → row: status "failed: <message>"
//!   ──► batch_summary.csv in --out, and the same table on stdout
//! ```

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Duration;

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::output::Method;
use crate::run::{CaseOutcome, RunError, RunObserver, run_case_file};

/// Outcome of one case in a batch.
#[derive(Debug)]
pub struct BatchEntry {
    /// The case file.
    pub path: PathBuf,
    /// Its report and files, or why it failed.
    pub result: Result<CaseOutcome, RunError>,
}

/// The name a case goes by before its file is read (progress bars, failed rows): the file stem.
fn case_stem(path: &std::path::Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Expand directories into their `*.toml` files (sorted), keep files as given.
pub fn collect_cases(inputs: &[PathBuf]) -> std::io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let mut v: Vec<PathBuf> = std::fs::read_dir(p)?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.extension().is_some_and(|x| x == "toml"))
                .collect();
            v.sort();
            out.extend(v);
        } else {
            out.push(p.clone());
        }
    }
    Ok(out)
}

struct BarObserver {
    bars: Mutex<Vec<(String, ProgressBar)>>,
}

impl BarObserver {
    fn with_bar(&self, case: &str, f: impl FnOnce(&ProgressBar)) {
        if let Some((_, b)) = self
            .bars
            .lock()
            .expect("progress bars")
            .iter()
            .find(|(n, _)| n == case)
        {
            f(b);
        }
    }
}

impl RunObserver for BarObserver {
    fn method_started(&self, case: &str, method: Method) {
        self.with_bar(case, |b| b.set_message(format!("{method}: starting")));
    }
    fn cycle_done(&self, case: &str, method: Method, cycle: usize, residual: f64) {
        self.with_bar(case, |b| {
            b.set_message(format!("{method}: cycle {cycle}, residual {residual:.2e}"))
        });
    }
    fn progress(
        &self,
        case: &str,
        method: Method,
        cycle: usize,
        step: usize,
        steps: usize,
        residual: f64,
    ) {
        let phase = if cycle == 0 {
            "run-in".to_string()
        } else {
            format!("cycle {cycle}")
        };
        self.with_bar(case, |b| {
            b.set_message(format!(
                "{method}: {phase}, step {step}/{steps}, residual {residual:.2e}"
            ))
        });
    }
    fn method_done(&self, case: &str, method: Method) {
        self.with_bar(case, |b| b.set_message(format!("{method}: done")));
    }
}

/// Run every case in `paths` with up to `jobs` threads (0 = all cores), writing into `out_dir`.
/// More threads than cases (or than cores, when `jobs` asks for more) would only wait: the
/// pool gets at most min(cases, cores) threads, whatever `jobs` says.
/// Progress bars go to stderr when `progress` is true. Returns one entry per case, in order.
pub fn run_batch(
    paths: &[PathBuf],
    out_dir: &Path,
    jobs: usize,
    progress: bool,
) -> Vec<BatchEntry> {
    let multi = MultiProgress::with_draw_target(if progress {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    });
    let style = ProgressStyle::with_template("{spinner} {prefix:24} {elapsed:>4} {wide_msg}")
        .expect("static template");
    let observer = BarObserver {
        bars: Mutex::new(Vec::new()),
    };
    let mut bars = Vec::new();
    for p in paths {
        let name = case_stem(p);
        let bar = multi.add(ProgressBar::new_spinner());
        bar.set_style(style.clone());
        bar.set_prefix(name.clone());
        bar.set_message("queued");
        bar.enable_steady_tick(Duration::from_millis(200));
        bars.push(bar.clone());
        observer
            .bars
            .lock()
            .expect("progress bars")
            .push((name, bar));
    }
    // Cases whose name an earlier case of the batch already has would overwrite its files:
    // they fail before any solve, naming the earlier file (a case file that cannot be read
    // fails later with its own error).
    let mut first_with_name: std::collections::HashMap<String, &PathBuf> =
        std::collections::HashMap::new();
    let duplicate_of: Vec<Option<(String, PathBuf)>> = paths
        .iter()
        .map(|p| {
            let name = crate::case::Case::from_file(p).ok()?.name;
            match first_with_name.get(&name) {
                Some(other) => Some((name, (*other).clone())),
                None => {
                    first_with_name.insert(name, p);
                    None
                }
            }
        })
        .collect();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = if jobs == 0 { cores } else { jobs.min(cores) };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.min(paths.len()).max(1))
        .build()
        .expect("a thread pool of at most as many threads as cores");
    let entries: Vec<BatchEntry> = pool.install(|| {
        paths
            .par_iter()
            .zip(bars.par_iter())
            .zip(duplicate_of.par_iter())
            .map(|((p, bar), duplicate)| {
                bar.set_message("reading the case");
                let result = match duplicate {
                    Some((name, other)) => Err(RunError::DuplicateName {
                        case: name.clone(),
                        path: p.display().to_string(),
                        other: other.display().to_string(),
                    }),
                    None => run_case_file(p, out_dir, &observer),
                };
                match &result {
                    Ok(o) => bar.finish_with_message(format!("done, {} files", o.files.len())),
                    Err(e) => bar.finish_with_message(format!("FAILED: {e}")),
                }
                BatchEntry {
                    path: p.clone(),
                    result,
                }
            })
            .collect()
    });
    multi.clear().ok();
    entries
}

/// Columns of the summary table: (summary row, header with display units).
const COLUMNS: [(&str, &str); 4] = [
    ("min_film_thickness_min", "h_min,min [µm]"),
    ("side_leakage_mean", "Q_side,mean [cm³/s]"),
    ("power_loss_mean", "P_loss,mean [W]"),
    ("eccentricity_ratio_max", "ε_max [-]"),
];

fn scale(name: &str) -> f64 {
    match name {
        "min_film_thickness_min" => 1e6,
        "side_leakage_mean" => 1e6,
        _ => 1.0,
    }
}

/// The summary as CSV text: one row per case and method, failed cases with their message.
pub fn summary_csv(entries: &[BatchEntry]) -> String {
    let mut s = String::from(
        "case,status,method,min_film_thickness_min_m,side_leakage_mean_m3_s,power_loss_mean_w,\
         eccentricity_ratio_max,message\n",
    );
    for e in entries {
        let name = case_stem(&e.path);
        match &e.result {
            Err(err) => {
                let msg = err.to_string().replace('"', "'");
                let _ = writeln!(s, "{name},failed,,,,,,\"{msg}\"");
            }
            Ok(o) => {
                for m in &o.report.methods {
                    let _ = write!(
                        s,
                        "{},{},{}",
                        o.report.case_name,
                        method_status(m),
                        m.method
                    );
                    for (col, _) in COLUMNS {
                        let v = o
                            .report
                            .summary
                            .iter()
                            .find(|r| r.name == col)
                            .and_then(|r| r.value(m.method));
                        let _ = write!(s, ",{}", v.map(|v| format!("{v:.6e}")).unwrap_or_default());
                    }
                    let note = rigorous_status(&o.report)
                        .map(|m| format!("rigorous {}", m.replace('"', "'")))
                        .unwrap_or_default();
                    let _ = writeln!(s, ",\"{note}\"");
                }
            }
        }
    }
    s
}

/// The summary as a fixed-width text table.
pub fn summary_table(entries: &[BatchEntry]) -> String {
    let mut s = format!("{:<26} {:<10} {:<14}", "case", "method", "status");
    for (_, h) in COLUMNS {
        let _ = write!(s, " {h:>20}");
    }
    s.push('\n');
    for e in entries {
        let name = case_stem(&e.path);
        match &e.result {
            Err(err) => {
                let _ = writeln!(s, "{name:<26} {:<10} {:<14} {err}", "-", "FAILED");
            }
            Ok(o) => {
                for m in &o.report.methods {
                    let _ = write!(
                        s,
                        "{:<26} {:<10} {:<14}",
                        o.report.case_name,
                        m.method.as_str(),
                        method_status(m)
                    );
                    for (col, _) in COLUMNS {
                        let v = o
                            .report
                            .summary
                            .iter()
                            .find(|r| r.name == col)
                            .and_then(|r| r.value(m.method));
                        match v {
                            Some(v) => {
                                let _ = write!(s, " {:>20.4}", v * scale(col));
                            }
                            None => {
                                let _ = write!(s, " {:>20}", "–");
                            }
                        }
                    }
                    s.push('\n');
                }
                if let Some(m) = rigorous_status(&o.report) {
                    let _ = writeln!(
                        s,
                        "{:<26} {:<10} {:<14} {m}",
                        o.report.case_name, "rigorous", "FAILED"
                    );
                }
            }
        }
    }
    s
}

/// The status of one method's result: "ok", or what a user must know before trusting it —
/// "not periodic" (the cycle limit was reached), "N stalled" (steps accepted above the Newton
/// tolerance).
pub fn method_status(m: &crate::output::MethodResult) -> String {
    use crate::output::ParameterValue;
    let info = |key: &str| m.solver_info.iter().find(|(k, _)| k == key).map(|(_, v)| v);
    let mut notes = Vec::new();
    if let Some(ParameterValue::Flag(false)) = info("periodic") {
        notes.push("not periodic".to_string());
    }
    if let Some(ParameterValue::Integer(n)) = info("stalled_steps")
        && *n > 0
    {
        notes.push(format!("{n} stalled"));
    }
    if notes.is_empty() {
        "ok".into()
    } else {
        notes.join(", ")
    }
}

/// Whether a report lacks a method that its case asked for (the method failed).
pub fn has_failed_method(report: &crate::output::CaseReport) -> bool {
    rigorous_status(report).is_some()
}

/// Why the rigorous method is missing from a report, if it failed.
fn rigorous_status(report: &crate::output::CaseReport) -> Option<&str> {
    report
        .parameters
        .iter()
        .find(|p| p.key == crate::run::RIGOROUS_STATUS)
        .and_then(|p| match &p.value {
            crate::output::ParameterValue::Text(t) => Some(t.as_str()),
            _ => None,
        })
}
