//! Batch runs: many cases in parallel (rayon), progress on stderr — a spinner line per case
//! (indicatif) on a terminal, plain timestamped lines per method and cycle elsewhere (logs, CI,
//! Slurm) — and a summary table at the end (printed and as CSV).
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
use std::time::{Duration, Instant};

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::budget::Limits;
use crate::case::CaseWarning;
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

/// How a batch shows its progress on stderr.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// Nothing but warnings (`--no-progress`, `--quiet`).
    Hidden,
    /// One live spinner line per case (stderr is a terminal).
    Bars,
    /// Plain lines, one per method start, cycle and end, with the elapsed time: for logs, CI,
    /// `nohup` and Slurm, where a progress bar cannot draw.
    Lines,
}

impl Progress {
    /// Bars on a terminal, lines otherwise, nothing when `show` is false.
    pub fn for_stderr(show: bool) -> Self {
        use std::io::IsTerminal;
        match (show, std::io::stderr().is_terminal()) {
            (false, _) => Progress::Hidden,
            (true, true) => Progress::Bars,
            (true, false) => Progress::Lines,
        }
    }
}

/// The batch's [`RunObserver`]: updates the case's bar, or prints a line, and prints warnings
/// (above the bars when they are drawn).
struct ProgressObserver {
    mode: Progress,
    multi: MultiProgress,
    started: Instant,
    bars: Mutex<Vec<(String, ProgressBar)>>,
}

impl ProgressObserver {
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

    /// Show `message` for `case`: on its bar, or as a line with the elapsed time.
    fn event(&self, case: &str, message: String) {
        match self.mode {
            Progress::Hidden => {}
            Progress::Bars => self.with_bar(case, |b| b.set_message(message)),
            Progress::Lines => eprintln!(
                "[{:>7.1} s] {case}: {message}",
                self.started.elapsed().as_secs_f64()
            ),
        }
    }
}

impl RunObserver for ProgressObserver {
    fn method_started(&self, case: &str, method: Method) {
        self.event(case, format!("{method}: started"));
    }
    fn cycle_done(&self, case: &str, method: Method, cycle: usize, residual: f64) {
        let what = match method {
            Method::Rigorous => "|Δε| from the previous cycle",
            Method::Mobility => "periodicity change",
        };
        let message = if residual.is_finite() {
            format!("{method}: cycle {cycle} done, {what} {residual:.2e}")
        } else {
            format!("{method}: cycle {cycle} done")
        };
        self.event(case, message);
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
        // Per-step news only on a bar (a line per step would flood a log; -vv logs them).
        if self.mode == Progress::Bars {
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
    }
    fn method_done(&self, case: &str, method: Method) {
        self.event(case, format!("{method}: done"));
    }
    fn warning(&self, _case: &str, warning: &CaseWarning) {
        let line = format!("warning: {warning}");
        if self.mode == Progress::Bars {
            self.multi.suspend(|| eprintln!("{line}"));
        } else {
            eprintln!("{line}");
        }
    }
}

/// Run every case in `paths` with up to `jobs` threads (0 = all cores), writing into `out_dir`.
/// More threads than cases (or than cores, when `jobs` asks for more) would only wait: the
/// pool gets at most min(cases, cores) threads, whatever `jobs` says. Cases estimated above
/// `limits` fail before their solve. Progress goes to stderr as `progress` says; warnings
/// always do. Returns one entry per case, in order.
pub fn run_batch(
    paths: &[PathBuf],
    out_dir: &Path,
    jobs: usize,
    progress: Progress,
    limits: &Limits,
) -> Vec<BatchEntry> {
    let multi = MultiProgress::with_draw_target(if progress == Progress::Bars {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    });
    let style = ProgressStyle::with_template("{spinner} {prefix:24} {elapsed:>4} {wide_msg}")
        .expect("static template");
    let observer = ProgressObserver {
        mode: progress,
        multi: multi.clone(),
        started: Instant::now(),
        bars: Mutex::new(Vec::new()),
    };
    // The name each case goes by in the progress (its `name`, or its file stem when the file
    // cannot be read), and which cases repeat an earlier case's name: those would overwrite its
    // files, so they fail before any solve, naming the earlier file.
    let names: Vec<Option<String>> = paths
        .iter()
        .map(|p| crate::case::Case::from_file(p).ok().map(|c| c.name))
        .collect();
    let mut first_with_name: std::collections::HashMap<&str, &PathBuf> =
        std::collections::HashMap::new();
    let duplicate_of: Vec<Option<(String, PathBuf)>> = paths
        .iter()
        .zip(&names)
        .map(|(p, name)| {
            let name = name.as_deref()?;
            match first_with_name.get(name) {
                Some(other) => Some((name.to_string(), (*other).clone())),
                None => {
                    first_with_name.insert(name, p);
                    None
                }
            }
        })
        .collect();
    let mut bars = Vec::new();
    for (p, name) in paths.iter().zip(&names) {
        let name = name.clone().unwrap_or_else(|| case_stem(p));
        let bar = multi.add(ProgressBar::new_spinner());
        bar.set_style(style.clone());
        bar.set_prefix(name.clone());
        bar.set_message("queued");
        if progress == Progress::Bars {
            bar.enable_steady_tick(Duration::from_millis(200));
        }
        bars.push((name.clone(), bar.clone()));
        observer
            .bars
            .lock()
            .expect("progress bars")
            .push((name, bar));
    }
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
            .map(|((p, (name, bar)), duplicate)| {
                bar.set_message("reading the case");
                let result = match duplicate {
                    Some((name, other)) => Err(RunError::DuplicateName {
                        case: name.clone(),
                        path: p.display().to_string(),
                        other: other.display().to_string(),
                    }),
                    None => run_case_file(p, out_dir, limits, &observer),
                };
                match &result {
                    Ok(o) => {
                        let message = format!("done, {} files", o.files.len());
                        observer.event(name, message.clone());
                        bar.finish_with_message(message);
                    }
                    Err(e) => {
                        let message = format!("FAILED: {e}");
                        observer.event(name, message.clone());
                        bar.finish_with_message(message);
                    }
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

/// The summary as CSV text (RFC 4180, through the `csv` crate): one row per case and method,
/// failed cases and failed methods with their message.
pub fn summary_csv(entries: &[BatchEntry]) -> String {
    let mut w = csv::Writer::from_writer(Vec::new());
    let header = [
        "case",
        "status",
        "method",
        "min_film_thickness_min_m",
        "side_leakage_mean_m3_s",
        "power_loss_mean_w",
        "eccentricity_ratio_max",
        "message",
    ];
    // Writing into a Vec cannot fail; a failure here would be a bug in the csv crate.
    let mut row = |cells: Vec<String>| w.write_record(&cells).expect("CSV into memory");
    row(header.iter().map(|h| h.to_string()).collect());
    for e in entries {
        match &e.result {
            Err(err) => {
                let mut cells = vec![case_stem(&e.path), "failed".into()];
                cells.extend(std::iter::repeat_n(String::new(), 5));
                cells.push(err.to_string());
                row(cells);
            }
            Ok(o) => {
                for m in &o.report.methods {
                    let mut cells = vec![
                        o.report.case_name.clone(),
                        method_status(m),
                        m.method.to_string(),
                    ];
                    for (col, _) in COLUMNS {
                        let v = o
                            .report
                            .summary
                            .iter()
                            .find(|r| r.name == col)
                            .and_then(|r| r.value(m.method));
                        cells.push(v.map(|v| format!("{v:.6e}")).unwrap_or_default());
                    }
                    cells.push(String::new());
                    row(cells);
                }
                for (method, message) in method_failures(&o.report) {
                    let mut cells =
                        vec![o.report.case_name.clone(), "failed".into(), method.into()];
                    cells.extend(std::iter::repeat_n(String::new(), 4));
                    cells.push(message.to_string());
                    row(cells);
                }
            }
        }
    }
    String::from_utf8(w.into_inner().expect("CSV into memory")).expect("UTF-8 in, UTF-8 out")
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
                for (method, message) in method_failures(&o.report) {
                    let _ = writeln!(
                        s,
                        "{:<26} {:<10} {:<14} {message}",
                        o.report.case_name, method, "FAILED"
                    );
                }
            }
        }
    }
    s
}

/// The status of one method's result (see [`crate::output::MethodResult::status`]).
pub fn method_status(m: &crate::output::MethodResult) -> String {
    m.status()
}

/// Whether a report lacks a method that its case asked for (the method failed).
pub fn has_failed_method(report: &crate::output::CaseReport) -> bool {
    !method_failures(report).is_empty()
}

/// The methods missing from a report because they failed, with the failure's message.
pub fn method_failures(report: &crate::output::CaseReport) -> Vec<(&'static str, &str)> {
    Method::ALL
        .into_iter()
        .filter_map(|m| report.failure(m).map(|why| (m.as_str(), why)))
        .collect()
}
