//! The `jbearing` command line (clap derive). `main.rs` only calls [`main_with`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use std::io::IsTerminal;

use clap::{Args, Parser, Subcommand};

use crate::batch::{
    BatchOptions, BatchRun, Manifest, Progress, Shard, collect_cases, run_batch, summary_csv,
    summary_table,
};
use crate::budget::{Estimate, Limits, estimate, human_bytes, human_seconds};
use crate::case::compressor::Compressor;
use crate::case::mechanism::MechanismCase;
use crate::case::{Case, CaseError};
use crate::sweep::CaseJob;

/// Dynamically loaded journal bearings with mass-conserving (JFO) cavitation.
///
/// A case file (TOML, see cases/README.md) describes one bearing, its lubricant and its load,
/// speed and feed-pressure histories. `jbearing run` solves it and writes CASE.h5 (open it with
/// xarray or pyvista), CASE_cycle.png, CASE_orbit.png, CASE_load.png (and CASE_film.png with
/// rigorous fields) and CASE_summary.csv. A mechanism case (a `[mechanism]` table: the
/// slider-crank of Flores et al. 2009 with its rod-slider joint ideal or lubricated) writes
/// CASE.h5, CASE_summary.csv, CASE_forces.png, CASE_orbit.png and CASE_film.png.
///
/// Examples:
///   jbearing check cases/compressor_main.toml
///   jbearing run cases/flores2006_mobility.toml --out results/
///   jbearing batch cases/ --jobs 2 --out results/
///   jbearing synth-loads cases/machine/compressor.toml
///   jbearing closed-form cases/flores2009_simple_bearing.toml
///   jbearing run cases/flores2009_slider_crank.toml --out results/
#[derive(Debug, Parser)]
#[command(name = "jbearing", version, about, long_about, verbatim_doc_comment)]
pub struct Cli {
    /// More log output (-v info, -vv debug, -vvv trace). RUST_LOG overrides.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Only errors.
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    pub quiet: bool,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Solve one case and write its HDF5 file, plots and summary.
    Run(RunArgs),
    /// Solve many cases in parallel; a failing case does not stop the others.
    Batch(BatchArgs),
    /// Check case files without solving: every key, table and precondition (errors name the
    /// file, key and line), the estimated memory and time against the limits, duplicate case
    /// names, and with --out the output directory.
    Check {
        /// Case files to check.
        #[arg(required = true)]
        cases: Vec<PathBuf>,
        /// Also make this output directory and try writing into it.
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Limits on the estimated cost of a case.
        #[command(flatten)]
        budget: BudgetArgs,
    },
    /// Merge the results of a batch (all its shards' output directories) into one netCDF
    /// dataset along a `case` dimension, the swept keys as coordinates; missing and failed
    /// cases are listed (and exit non-zero), never dropped.
    Merge {
        /// Output directories of the batch (each with its shard_I_of_N.json).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// The merged file.
        #[arg(short, long)]
        out: PathBuf,
    },
    /// Print the static equilibrium of the closed-form film models (short / long bearing,
    /// Sommerfeld / Gumbel, Pinkus–Sternlicht) under the case's constant or cycle-mean load,
    /// without running the mobility or rigorous solvers. Models: the case's `[closed_form]`
    /// list, else all.
    ClosedForm {
        /// The case file (TOML).
        case: PathBuf,
    },
    /// Run the validation cases and print their table against published values.
    Validate {
        /// Directory of the case files.
        #[arg(long, default_value = "cases")]
        cases_dir: PathBuf,
        /// Where to write the validation cases' results.
        #[arg(long, default_value = "results/validation")]
        out: PathBuf,
    },
    /// Regenerate the compressor cases' load, speed and feed tables (CSV) from the slider-crank
    /// model described in the machine file.
    SynthLoads {
        /// The compressor machine file.
        #[arg(default_value = "cases/machine/compressor.toml")]
        machine: PathBuf,
    },
}

/// Limits on the estimated cost of one case (see `jbearing::budget`): a case estimated above
/// either is refused before its solve; above 1 GB or 1 hour it gets a warning.
#[derive(Debug, Clone, Copy, Args)]
pub struct BudgetArgs {
    /// Refuse a case estimated to need more memory than this (GiB).
    #[arg(long, default_value_t = 8.0, value_name = "GIB")]
    pub max_memory_gb: f64,
    /// Refuse a case estimated to take longer than this (hours, one core).
    #[arg(long, default_value_t = 24.0, value_name = "HOURS")]
    pub max_hours: f64,
}

impl BudgetArgs {
    fn limits(&self) -> Limits {
        Limits::from_gib_hours(self.max_memory_gb, self.max_hours)
    }
}

/// `jbearing run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The case file (TOML).
    pub case: PathBuf,
    /// Output directory (created if missing).
    #[arg(short, long, default_value = "results")]
    pub out: PathBuf,
    /// No progress on stderr (warnings and errors are still printed).
    #[arg(long)]
    pub no_progress: bool,
    /// Limits on the estimated cost of the case.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

/// `jbearing batch`.
#[derive(Debug, Args)]
pub struct BatchArgs {
    /// Case files, or directories whose *.toml files are all run.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Cases solved at once (0 = one per CPU core).
    #[arg(short, long, default_value_t = 0)]
    pub jobs: usize,
    /// Output directory (created if missing); the summary goes to OUT/batch_summary.csv.
    #[arg(short, long, default_value = "results")]
    pub out: PathBuf,
    /// No progress on stderr (warnings and errors are still printed).
    #[arg(long)]
    pub no_progress: bool,
    /// Limits on the estimated cost of each case.
    #[command(flatten)]
    pub budget: BudgetArgs,
    /// Run only shard I of N (0 ≤ I < N): the cases whose name hashes to I (stable: a case
    /// always lands in the same shard, whatever the order of the files). Writes
    /// OUT/shard_I_of_N_summary.csv and OUT/shard_I_of_N.json (for `jbearing merge`).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Recompute cases whose OUT/CASE.h5 exists (by default they are skipped: a re-run resumes).
    #[arg(long)]
    pub force: bool,
}

fn init_logging(verbose: u8, quiet: bool) {
    let level = if quiet {
        "error"
    } else {
        match verbose {
            0 => "warn",
            1 => "info",
            2 => "debug",
            _ => "trace",
        }
    };
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new(level));
    // Colour only on a terminal, and never with NO_COLOR set (https://no-color.org).
    let ansi = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_ansi(ansi)
        .with_writer(std::io::stderr)
        .try_init();
}

/// Parse the arguments and run; the process exit code.
pub fn main_with(cli: Cli) -> ExitCode {
    init_logging(cli.verbose, cli.quiet);
    match cli.command {
        Command::Check { cases, out, budget } => check(&cases, out.as_deref(), &budget.limits()),
        Command::Run(a) => run_command(&a, cli.quiet),
        Command::Batch(a) => batch_command(&a, cli.quiet),
        Command::Merge { dirs, out } => merge_command(&dirs, &out),
        Command::ClosedForm { case } => closed_form_command(&case),
        Command::Validate { cases_dir, out } => crate::validate::run(&cases_dir, &out),
        Command::SynthLoads { machine } => synth_loads_command(&machine),
    }
}

/// `jbearing run CASE`: one case as a batch of one (the same progress, warnings and outputs),
/// its summary table printed; a mechanism case goes to its own runner.
fn run_command(a: &RunArgs, quiet: bool) -> ExitCode {
    // The same progress and warnings as a batch of one.
    let progress = Progress::for_stderr(!a.no_progress && !quiet);
    // A mechanism case (a `[mechanism]` table) has its own runner and outputs.
    if crate::case::mechanism::is_mechanism_file(&a.case) {
        return crate::mechanism::run_cli(&a.case, &a.out, progress);
    }
    // One case as given (a sweep file is refused by the case reader: `batch` runs it).
    let job = crate::sweep::CaseJob {
        path: a.case.clone(),
        name: crate::case::Case::from_file(&a.case).map_or_else(
            |_| {
                a.case
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            },
            |c| c.name,
        ),
        text: None,
        parameters: Vec::new(),
    };
    let mut run = run_batch(
        std::slice::from_ref(&job),
        &BatchOptions {
            out_dir: a.out.clone(),
            jobs: 1,
            progress,
            limits: a.budget.limits(),
            shard: Shard::ALL,
            force: true,
        },
    );
    let entry = run.entries.remove(0);
    match entry.result {
        Ok(crate::batch::JobOutcome::Mechanism(o)) => {
            // Not reached (mechanism files take the branch above); said honestly.
            for f in &o.files {
                println!("wrote {}", f.display());
            }
            ExitCode::SUCCESS
        }
        Ok(crate::batch::JobOutcome::Bearing(o)) => {
            for f in &o.files {
                println!("wrote {}", f.display());
            }
            let method_failed = crate::batch::has_failed_method(&o.report);
            let closed_form = o.report.closed_form.clone();
            let elastic = o.report.elastic.as_ref().map(|e| e.format_summary());
            // A case that asks only for the deformable bearing has no method rows.
            let methods_ran = !o.report.methods.is_empty();
            let table = summary_table(&[crate::batch::BatchEntry {
                path: a.case.clone(),
                name: job.name.clone(),
                result: Ok(crate::batch::JobOutcome::Bearing(o)),
            }]);
            if methods_ran || elastic.is_none() {
                print!("{table}");
            }
            if let Some(t) = &closed_form {
                print!("{}", crate::closed_form_report::format_table(t));
            }
            if let Some(e) = &elastic {
                print!("{e}");
            }
            if method_failed {
                eprintln!("a requested method failed (the FAILED row above)");
                ExitCode::FAILURE
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `jbearing batch INPUTS…`: every case (sweeps expanded) of this shard, the summary CSV and
/// the manifest written atomically; failure when a case or a method failed.
fn batch_command(a: &BatchArgs, quiet: bool) -> ExitCode {
    let Some((all, shard)) = batch_jobs(a) else {
        return ExitCode::FAILURE;
    };
    let progress = Progress::for_stderr(!a.no_progress && !quiet);
    // Mechanism cases are jobs of the same list (pool, shards, resume, manifest, rows).
    let run = run_batch(
        &all,
        &BatchOptions {
            out_dir: a.out.clone(),
            jobs: a.jobs,
            progress,
            limits: a.budget.limits(),
            shard,
            force: a.force,
        },
    );
    let entries = &run.entries;
    print!("{}", summary_table(entries));
    for j in &run.skipped {
        println!(
            "{:<26} skipped: {}.h5 exists (--force recomputes)",
            j.name, j.name
        );
    }
    let Some(csv) = write_batch_files(&a.out, &all, shard, &run) else {
        return ExitCode::FAILURE;
    };
    println!("summary: {}", csv.display());
    let failed = entries.iter().filter(|e| e.result.is_err()).count();
    let method_failed = entries
        .iter()
        .filter(|e| e.result.as_ref().is_ok_and(|o| o.has_failed_method()))
        .count();
    if failed > 0 || method_failed > 0 {
        eprintln!(
            "{failed} of {} case(s) failed, {method_failed} more with a failed method",
            entries.len()
        );
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// The cases of `jbearing batch` (case files listed, sweeps expanded) and the shard to run;
/// `None` when an error was reported.
fn batch_jobs(a: &BatchArgs) -> Option<(Vec<CaseJob>, Shard)> {
    let paths = match collect_cases(&a.inputs) {
        Ok(p) if !p.is_empty() => p,
        Ok(_) => {
            eprintln!("error: no case files (*.toml) in {:?}", a.inputs);
            return None;
        }
        Err(e) => {
            eprintln!("error: listing {:?}: {e}", a.inputs);
            return None;
        }
    };
    let all = match crate::sweep::expand_all(&paths) {
        Ok(all) => all,
        Err(e) => {
            eprintln!("error: {e}");
            return None;
        }
    };
    let shard = match a.shard.as_deref().map(Shard::parse).transpose() {
        Ok(s) => s.unwrap_or(Shard::ALL),
        Err(e) => {
            eprintln!("error: {e}");
            return None;
        }
    };
    Some((all, shard))
}

/// The shard's summary CSV and manifest, each written atomically: the CSV's path, or `None` when
/// an error was reported.
fn write_batch_files(out: &Path, all: &[CaseJob], shard: Shard, run: &BatchRun) -> Option<PathBuf> {
    let csv = out.join(shard.summary_name());
    let manifest_path = out.join(shard.manifest_name());
    let manifest = Manifest::of(all, shard, run);
    let write_text = |path: &std::path::Path, text: String| {
        crate::output::write_atomically(path, |tmp| {
            std::fs::write(tmp, &text).map_err(|source| crate::output::OutputError::Io {
                action: "writing",
                path: path.to_path_buf(),
                source,
            })
        })
        .map_err(|e| e.to_string())
    };
    let written = std::fs::create_dir_all(out)
        .map_err(|e| e.to_string())
        .and_then(|_| write_text(&csv, summary_csv(&run.entries)))
        .and_then(|_| {
            write_text(
                &manifest_path,
                serde_json::to_string_pretty(&manifest).expect("a manifest serialises"),
            )
        });
    if let Err(e) = written {
        eprintln!(
            "error: writing {} / {}: {e}",
            csv.display(),
            manifest_path.display()
        );
        return None;
    }
    Some(csv)
}

/// `jbearing merge DIRS… --out FILE`.
fn merge_command(dirs: &[PathBuf], out: &Path) -> ExitCode {
    match crate::merge::merge(dirs, out) {
        Ok(info) => {
            let incomplete = info.incomplete();
            println!(
                "wrote {} ({} cases, {} ok)",
                out.display(),
                info.cases.len(),
                info.cases.len() - incomplete.len()
            );
            for (name, status) in &incomplete {
                eprintln!("{name}: {status}");
            }
            if incomplete.is_empty() {
                ExitCode::SUCCESS
            } else {
                eprintln!(
                    "{} of {} cases missing or failed (listed above; NaN in the file)",
                    incomplete.len(),
                    info.cases.len()
                );
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `jbearing closed-form CASE`: the closed-form equilibria table.
fn closed_form_command(case: &Path) -> ExitCode {
    match Case::from_file(case) {
        Ok(c) => {
            let models = if c.closed_form_models.is_empty() {
                jbearing_solvers::closed_form::ClosedFormModel::ALL.to_vec()
            } else {
                c.closed_form_models.clone()
            };
            let t = crate::closed_form_report::table(&c, &models);
            print!("{}", crate::closed_form_report::format_table(&t));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `jbearing synth-loads MACHINE`: the load tables of a compressor description.
fn synth_loads_command(machine: &Path) -> ExitCode {
    match Compressor::from_file(machine) {
        Ok(c) => match c.write_tables() {
            Ok(paths) => {
                for p in paths {
                    println!("wrote {}", p.display());
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: writing the tables: {e}");
                ExitCode::FAILURE
            }
        },
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `jbearing check`: every case read and checked as `run` would before its solve; the estimated
/// cost printed beside each; duplicate names, and the output directory when given.
fn check(cases: &[PathBuf], out: Option<&std::path::Path>, limits: &Limits) -> ExitCode {
    let mut bad = out.map_or(0, check_out_dir);
    let mut seen: HashMap<String, PathBuf> = HashMap::new();
    for c in cases {
        match crate::sweep::expand_file(c) {
            Ok(jobs) => bad += check_file(c, &jobs, &mut seen, limits),
            Err(e) => {
                eprintln!("error: {e}");
                bad += 1;
            }
        }
    }
    if bad > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// The output directory can be created and written in: the number of errors reported (0 or 1).
fn check_out_dir(dir: &Path) -> usize {
    let usable =
        std::fs::create_dir_all(dir).and_then(|_| tempfile::NamedTempFile::new_in(dir).map(drop));
    if let Err(e) = usable {
        eprintln!(
            "error: output directory '{}' is not usable: {e}",
            dir.display()
        );
        return 1;
    }
    0
}

/// One case file's cases (each point of a sweep) checked, a line printed per case or one per
/// sweep: the number of errors reported.
fn check_file(
    c: &Path,
    jobs: &[CaseJob],
    seen: &mut HashMap<String, PathBuf>,
    limits: &Limits,
) -> usize {
    let sweep = jobs.iter().any(|j| j.text.is_some());
    let (mut memory, mut seconds, mut ok, mut bad) = (0.0f64, 0.0, 0usize, 0usize);
    let mut mechanism = false;
    for job in jobs {
        if let Some(m) = crate::mechanism::job_case(job) {
            mechanism = true;
            if check_mechanism_case(c, m, seen, sweep) {
                ok += 1;
            } else {
                bad += 1;
            }
            continue;
        }
        match check_case(c, job, seen, limits, sweep) {
            Some(e) => {
                memory = memory.max(e.memory_bytes);
                seconds += e.seconds;
                ok += 1;
            }
            None => bad += 1,
        }
    }
    if sweep && mechanism {
        let keys: Vec<&str> = jobs[0].parameters.iter().map(|p| p.key.as_str()).collect();
        println!(
            "{}: sweep of {} mechanism cases over {} ({ok} ok)",
            c.display(),
            jobs.len(),
            keys.join(", ")
        );
    } else if sweep {
        let keys: Vec<&str> = jobs[0].parameters.iter().map(|p| p.key.as_str()).collect();
        println!(
            "{}: sweep of {} cases over {} ({ok} ok; estimated {} each at most, {} in all \
             on one core)",
            c.display(),
            jobs.len(),
            keys.join(", "),
            human_bytes(memory),
            human_seconds(seconds)
        );
    }
    bad
}

/// A mechanism case: read, and its name not used by an earlier case; `true` when it is good.
fn check_mechanism_case(
    c: &Path,
    m: Result<MechanismCase, CaseError>,
    seen: &mut HashMap<String, PathBuf>,
    sweep: bool,
) -> bool {
    match m {
        Ok(case) if seen.contains_key(&case.name) => {
            eprintln!(
                "error: {}: case name '{}' is already used by {}: their output files \
                 would overwrite each other in one batch (give each case its own name)",
                c.display(),
                case.name,
                seen[&case.name].display()
            );
            false
        }
        Ok(case) => {
            seen.insert(case.name.clone(), c.to_path_buf());
            if !sweep {
                println!("{}: ok ({})", c.display(), case.describe());
            }
            true
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}

/// A bearing case: read, its name not used by an earlier case, within the budget; its warnings
/// printed; its estimated cost when it is good.
fn check_case(
    c: &Path,
    job: &CaseJob,
    seen: &mut HashMap<String, PathBuf>,
    limits: &Limits,
    sweep: bool,
) -> Option<Estimate> {
    let case = match job.case() {
        Ok(case) => case,
        Err(e) => {
            eprintln!("error: {e}");
            return None;
        }
    };
    if let Some(other) = seen.get(&case.name) {
        eprintln!(
            "error: {}: case name '{}' is already used by {}: their output files would \
             overwrite each other in one batch (give each case its own name)",
            c.display(),
            case.name,
            other.display()
        );
        return None;
    }
    seen.insert(case.name.clone(), c.to_path_buf());
    let budget = match crate::budget::check(&case, limits) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("error: {e}");
            return None;
        }
    };
    for w in case.warnings.iter().chain(&budget) {
        eprintln!("warning: {w}");
    }
    let e = estimate(&case);
    if !sweep {
        println!(
            "{}: ok (case '{}', {} groove(s), grid {} × {}; estimated {}, {})",
            c.display(),
            case.name,
            case.grooves.len(),
            case.n_theta,
            case.n_z,
            human_bytes(e.memory_bytes),
            human_seconds(e.seconds)
        );
    }
    Some(e)
}
