//! Batch runs: many cases in parallel (rayon), progress on stderr — a spinner line per case
//! (indicatif) on a terminal, plain timestamped lines per method and cycle elsewhere (logs, CI,
//! Slurm) — and a summary table at the end (printed and as CSV).
//! A failing case is reported in the table and does not stop the others. Mechanism cases
//! (a `[mechanism]` table, [`crate::mechanism`]) are jobs of the same list: same pool, shards,
//! resume and manifest; their rows carry h_min and ε_max in the bearing columns and the peak
//! joint force, crank moment and contact onsets in the message.
//!
//! ```text
//!   [FILES | DIR/*.toml] ──rayon par_iter──► run_case / run_mechanism_case (one per case)
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
use crate::mechanism::{MechanismOutcome, SummaryRow, run_mechanism_case};
use crate::output::Method;
use crate::run::{CaseOutcome, RunError, RunObserver, run_case};
use crate::sweep::CaseJob;

/// Outcome of one case in a batch.
#[derive(Debug)]
pub struct BatchEntry {
    /// The case file.
    pub path: PathBuf,
    /// The case's name (a sweep point's own).
    pub name: String,
    /// Its report and files, or why it failed.
    pub result: Result<JobOutcome, RunError>,
}

/// What a case of a batch produced.
#[derive(Debug)]
pub enum JobOutcome {
    /// A bearing case.
    Bearing(Box<CaseOutcome>),
    /// A mechanism case.
    Mechanism(Box<MechanismOutcome>),
}

impl JobOutcome {
    /// The bearing case's outcome (None for a mechanism case).
    pub fn bearing(&self) -> Option<&CaseOutcome> {
        match self {
            JobOutcome::Bearing(o) => Some(o),
            JobOutcome::Mechanism(_) => None,
        }
    }

    /// Files written.
    pub fn files(&self) -> &[PathBuf] {
        match self {
            JobOutcome::Bearing(o) => &o.files,
            JobOutcome::Mechanism(o) => &o.files,
        }
    }

    /// Whether a bearing case lacks a method it asked for.
    pub fn has_failed_method(&self) -> bool {
        self.bearing().is_some_and(|o| has_failed_method(&o.report))
    }
}

/// One shard of a batch: `index` of `count` (0-based, as Slurm's array task ids).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 0 … count − 1.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole batch as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// `I/N` as given on the command line.
    pub fn parse(text: &str) -> Result<Self, String> {
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| format!("--shard takes I/N (e.g. 0/4), got {text:?}"))?;
        let index: usize = i
            .trim()
            .parse()
            .map_err(|_| format!("--shard {text}: I is not a number"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| format!("--shard {text}: N is not a number"))?;
        if count == 0 || index >= count {
            return Err(format!(
                "--shard {text}: need 0 ≤ I < N (shards are numbered from 0, as Slurm array \
                 task ids)"
            ));
        }
        Ok(Self { index, count })
    }

    /// Whether the case named `name` belongs to this shard ([`crate::sweep::shard_of`]).
    pub fn holds(&self, name: &str) -> bool {
        crate::sweep::shard_of(name, self.count) == self.index
    }

    /// File name of this shard's manifest: `shard_I_of_N.json`.
    pub fn manifest_name(&self) -> String {
        format!("shard_{}_of_{}.json", self.index, self.count)
    }

    /// File name of this shard's summary: `batch_summary.csv` for a whole batch, else
    /// `shard_I_of_N_summary.csv`.
    pub fn summary_name(&self) -> String {
        if self.count == 1 {
            "batch_summary.csv".into()
        } else {
            format!("shard_{}_of_{}_summary.csv", self.index, self.count)
        }
    }
}

/// How a batch runs.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// Where the cases' files go.
    pub out_dir: PathBuf,
    /// Cases solved at once (0 = one per core).
    pub jobs: usize,
    /// Progress display.
    pub progress: Progress,
    /// Cost limits per case.
    pub limits: Limits,
    /// Which part of the batch to run.
    pub shard: Shard,
    /// Recompute cases whose output file exists (else they are skipped: resume).
    pub force: bool,
}

/// What a batch did.
#[derive(Debug)]
pub struct BatchRun {
    /// The cases it solved (or failed to).
    pub entries: Vec<BatchEntry>,
    /// The cases of this shard it skipped because their complete output exists (written
    /// atomically: an existing CASE.h5 is a whole one).
    pub skipped: Vec<CaseJob>,
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
pub fn run_batch(all: &[CaseJob], options: &BatchOptions) -> BatchRun {
    let BatchOptions {
        out_dir,
        jobs,
        progress,
        limits,
        shard,
        force,
    } = options;
    let (jobs, progress) = (*jobs, *progress);
    // This shard's cases, minus those whose output is there already (unless forced).
    let mine: Vec<(usize, &CaseJob)> = all
        .iter()
        .enumerate()
        .filter(|(_, j)| shard.holds(&j.name))
        .collect();
    type Indexed<'a> = Vec<(usize, &'a CaseJob)>;
    let (todo, skipped): (Indexed, Indexed) = mine
        .into_iter()
        .partition(|(_, j)| *force || !out_dir.join(format!("{}.h5", j.name)).is_file());
    let multi = MultiProgress::with_draw_target(if progress == Progress::Bars {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    });
    let observer = ProgressObserver {
        mode: progress,
        multi: multi.clone(),
        started: Instant::now(),
        bars: Mutex::new(Vec::new()),
    };
    let duplicate = duplicate_names(all);
    let bars = start_bars(&todo, &multi, progress, &observer);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = if jobs == 0 { cores } else { jobs.min(cores) };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.min(todo.len()).max(1))
        .build()
        .expect("a thread pool of at most as many threads as cores");
    let entries: Vec<BatchEntry> = pool.install(|| {
        todo.par_iter()
            .zip(bars.par_iter())
            .map(|((k, job), bar)| {
                bar.set_message("reading the case");
                let result = run_job(job, duplicate.get(k), out_dir, limits, &observer);
                match &result {
                    Ok(o) => {
                        let message = format!("done, {} files", o.files().len());
                        observer.event(&job.name, message.clone());
                        bar.finish_with_message(message);
                    }
                    Err(e) => {
                        let message = format!("FAILED: {e}");
                        observer.event(&job.name, message.clone());
                        bar.finish_with_message(message);
                    }
                }
                BatchEntry {
                    path: job.path.clone(),
                    name: job.name.clone(),
                    result,
                }
            })
            .collect()
    });
    multi.clear().ok();
    BatchRun {
        entries,
        skipped: skipped.into_iter().map(|(_, j)| j.clone()).collect(),
    }
}

/// The jobs that repeat an earlier job's name, by index, with the earlier job's file.
fn duplicate_names(all: &[CaseJob]) -> std::collections::HashMap<usize, PathBuf> {
    // Cases that repeat an earlier case's name (over the whole batch, every shard) would
    // overwrite its files, so they fail before any solve, naming the earlier file.
    let mut first_with_name: std::collections::HashMap<&str, &PathBuf> =
        std::collections::HashMap::new();
    let mut duplicate: std::collections::HashMap<usize, PathBuf> = std::collections::HashMap::new();
    for (k, j) in all.iter().enumerate() {
        match first_with_name.get(j.name.as_str()) {
            Some(other) => {
                duplicate.insert(k, (*other).clone());
            }
            None => {
                first_with_name.insert(&j.name, &j.path);
            }
        }
    }
    duplicate
}

/// A spinner per job to do, in the observer's list too (ticking only when bars are drawn).
fn start_bars(
    todo: &[(usize, &CaseJob)],
    multi: &MultiProgress,
    progress: Progress,
    observer: &ProgressObserver,
) -> Vec<ProgressBar> {
    let style = ProgressStyle::with_template("{spinner} {prefix:24} {elapsed:>4} {wide_msg}")
        .expect("static template");
    let mut bars = Vec::new();
    for (_, j) in todo {
        let bar = multi.add(ProgressBar::new_spinner());
        bar.set_style(style.clone());
        bar.set_prefix(j.name.clone());
        bar.set_message("queued");
        if progress == Progress::Bars {
            bar.enable_steady_tick(Duration::from_millis(200));
        }
        bars.push(bar.clone());
        observer
            .bars
            .lock()
            .expect("progress bars")
            .push((j.name.clone(), bar));
    }
    bars
}

/// One job: a duplicate name fails before any solve; a mechanism case or a bearing case runs.
fn run_job(
    job: &CaseJob,
    duplicate: Option<&PathBuf>,
    out_dir: &Path,
    limits: &Limits,
    observer: &ProgressObserver,
) -> Result<JobOutcome, RunError> {
    match duplicate {
        Some(other) => Err(RunError::DuplicateName {
            case: job.name.clone(),
            path: job.path.display().to_string(),
            other: other.display().to_string(),
        }),
        None => match crate::mechanism::job_case(job) {
            Some(case) => {
                let progress = |m: &str| observer.event(&job.name, m.to_string());
                case.map_err(RunError::from).and_then(|case| {
                    run_mechanism_case(&case, out_dir, &progress)
                        .map(|o| JobOutcome::Mechanism(Box::new(o)))
                        .map_err(|e| RunError::Mechanism(Box::new(e)))
                })
            }
            None => job
                .case()
                .map_err(RunError::from)
                .and_then(|case| run_case(&case, out_dir, limits, observer))
                .map(|o| JobOutcome::Bearing(Box::new(o))),
        },
    }
}

/// One case in a shard manifest.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ManifestCase {
    /// Case name.
    pub name: String,
    /// The case file.
    pub file: String,
    /// The shard it belongs to.
    pub shard: usize,
    /// Swept keys and values (empty for a plain case).
    pub parameters: Vec<(String, f64)>,
    /// `bearing` or `mechanism` ("" in manifests written before mechanism cases joined
    /// batches: bearing).
    #[serde(default)]
    pub kind: String,
    /// `ok`, `skipped` (its output existed), `failed`, or `other shard`.
    pub status: String,
    /// Why it failed ("" otherwise).
    pub message: String,
}

/// What a shard ran: every case of the whole batch with its shard, and this shard's outcome
/// for each of its own (`jbearing merge` reads it to know which cases to expect).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Manifest {
    /// This shard.
    pub shard: usize,
    /// Number of shards.
    pub shards: usize,
    /// Every case of the batch.
    pub cases: Vec<ManifestCase>,
}

impl Manifest {
    /// The manifest of `run`, a run of `shard` over the batch `all`.
    pub fn of(all: &[CaseJob], shard: Shard, run: &BatchRun) -> Self {
        let cases = all
            .iter()
            .map(|j| {
                let (status, message) = if !shard.holds(&j.name) {
                    ("other shard".to_string(), String::new())
                } else if run.skipped.iter().any(|s| s.name == j.name) {
                    ("skipped".into(), String::new())
                } else {
                    match run.entries.iter().find(|e| e.name == j.name) {
                        Some(BatchEntry {
                            result: Ok(JobOutcome::Bearing(o)),
                            ..
                        }) if has_failed_method(&o.report) => (
                            "ok".into(),
                            method_failures(&o.report)
                                .iter()
                                .map(|(m, why)| format!("{m}: {why}"))
                                .collect::<Vec<_>>()
                                .join("; "),
                        ),
                        Some(BatchEntry { result: Ok(_), .. }) => ("ok".into(), String::new()),
                        Some(BatchEntry { result: Err(e), .. }) => ("failed".into(), e.to_string()),
                        None => ("failed".into(), "not run".into()),
                    }
                };
                ManifestCase {
                    name: j.name.clone(),
                    file: j.path.display().to_string(),
                    shard: crate::sweep::shard_of(&j.name, shard.count),
                    parameters: j
                        .parameters
                        .iter()
                        .map(|p| (p.key.clone(), p.value))
                        .collect(),
                    kind: if crate::mechanism::is_mechanism_job(j) {
                        KIND_MECHANISM
                    } else {
                        KIND_BEARING
                    }
                    .into(),
                    status,
                    message,
                }
            })
            .collect();
        Self {
            shard: shard.index,
            shards: shard.count,
            cases,
        }
    }
}

/// [`ManifestCase::kind`] of a bearing case.
pub const KIND_BEARING: &str = "bearing";
/// [`ManifestCase::kind`] of a mechanism case.
pub const KIND_MECHANISM: &str = "mechanism";

/// A mechanism case's rows: (method column, status, values of [`COLUMNS`], message with the
/// peak joint force, crank moment and contact onsets), one per run (lubricated, ideal).
fn mechanism_rows(o: &MechanismOutcome) -> Vec<(String, Vec<Option<f64>>, String)> {
    let rows = crate::mechanism::summary_rows(&o.results);
    let get = |n: &str| rows.iter().find(|r| r.name == n);
    o.results
        .runs()
        .into_iter()
        .map(|(run, _)| {
            let pick = |r: &SummaryRow| {
                if run == crate::mechanism::LUBRICATED {
                    r.lubricated
                } else {
                    r.ideal
                }
            };
            let v = |n: &str| get(n).and_then(pick);
            let values = COLUMNS
                .iter()
                .map(|(col, _)| match *col {
                    "min_film_thickness_min" | "eccentricity_ratio_max" => v(col),
                    _ => None,
                })
                .collect();
            let f = |x: Option<f64>| x.map_or("-".to_string(), |x| format!("{x:.6e}"));
            let mut message = format!(
                "mechanism: joint_force_max {} N, crank_moment_max {} N m",
                f(v("joint_force_max")),
                f(v("crank_moment_max"))
            );
            if let Some(n) = v("contact_onsets") {
                let _ = write!(message, ", contact_onsets {n:.0}");
            }
            (format!("mechanism:{run}"), values, message)
        })
        .collect()
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
                let mut cells = vec![e.name.clone(), "failed".into()];
                cells.extend(std::iter::repeat_n(String::new(), 5));
                cells.push(err.to_string());
                row(cells);
            }
            Ok(JobOutcome::Mechanism(o)) => {
                for (method, values, message) in mechanism_rows(o) {
                    let mut cells = vec![e.name.clone(), "ok".into(), method];
                    cells.extend(
                        values
                            .iter()
                            .map(|v| v.map(|v| format!("{v:.6e}")).unwrap_or_default()),
                    );
                    cells.push(message);
                    row(cells);
                }
            }
            Ok(JobOutcome::Bearing(o)) => {
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
        let name = &e.name;
        match &e.result {
            Err(err) => {
                let _ = writeln!(s, "{name:<26} {:<10} {:<14} {err}", "-", "FAILED");
            }
            Ok(JobOutcome::Mechanism(o)) => {
                for (method, values, message) in mechanism_rows(o) {
                    let _ = write!(s, "{name:<26} {method:<10} {:<14}", "ok");
                    for ((col, _), v) in COLUMNS.iter().zip(values) {
                        match v {
                            Some(v) => {
                                let _ = write!(s, " {:>20.4}", v * scale(col));
                            }
                            None => {
                                let _ = write!(s, " {:>20}", "–");
                            }
                        }
                    }
                    let _ = writeln!(s, "  {message}");
                }
            }
            Ok(JobOutcome::Bearing(o)) => {
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
