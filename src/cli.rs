//! The `jbearing` command line (clap derive). `main.rs` only calls [`main_with`].

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::batch::{collect_cases, run_batch, summary_csv, summary_table};
use crate::case::Case;
use crate::case::compressor::Compressor;
use crate::run::{Quiet, run_case_file};

/// Dynamically loaded journal bearings with mass-conserving (JFO) cavitation.
///
/// A case file (TOML, see cases/README.md) describes one bearing, its lubricant and its load,
/// speed and feed-pressure histories. `jbearing run` solves it and writes CASE.h5 (open it with
/// xarray or pyvista), CASE_cycle.png, CASE_orbit.png and CASE_summary.csv.
///
/// Examples:
///   jbearing check cases/compressor_main.toml
///   jbearing run cases/flores2006_mobility.toml --out results/
///   jbearing batch cases/ --jobs 2 --out results/
///   jbearing synth-loads cases/machine/compressor.toml
///   jbearing closed-form cases/flores2009_simple_bearing.toml
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
    /// Check case files without solving (errors name the file, key and line).
    Check {
        /// Case files to check.
        #[arg(required = true)]
        cases: Vec<PathBuf>,
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

/// `jbearing run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The case file (TOML).
    pub case: PathBuf,
    /// Output directory (created if missing).
    #[arg(short, long, default_value = "results")]
    pub out: PathBuf,
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
    /// No progress bars.
    #[arg(long)]
    pub no_progress: bool,
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
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .try_init();
}

/// Parse the arguments and run; the process exit code.
pub fn main_with(cli: Cli) -> ExitCode {
    init_logging(cli.verbose, cli.quiet);
    match cli.command {
        Command::Check { cases } => {
            let mut bad = 0;
            for c in &cases {
                match Case::from_file(c) {
                    Ok(case) => println!(
                        "{}: ok (case '{}', {} groove(s), grid {} × {})",
                        c.display(),
                        case.name,
                        case.grooves.len(),
                        case.n_theta,
                        case.n_z
                    ),
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
        Command::Run(a) => match run_case_file(&a.case, &a.out, &Quiet) {
            Ok(o) => {
                for f in &o.files {
                    println!("wrote {}", f.display());
                }
                let method_failed = crate::batch::has_failed_method(&o.report);
                let closed_form = o.report.closed_form.clone();
                print!(
                    "{}",
                    summary_table(&[crate::batch::BatchEntry {
                        path: a.case.clone(),
                        result: Ok(o),
                    }])
                );
                if let Some(t) = &closed_form {
                    print!("{}", crate::closed_form_report::format_table(t));
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
        },
        Command::Batch(a) => {
            let paths = match collect_cases(&a.inputs) {
                Ok(p) if !p.is_empty() => p,
                Ok(_) => {
                    eprintln!("error: no case files (*.toml) in {:?}", a.inputs);
                    return ExitCode::FAILURE;
                }
                Err(e) => {
                    eprintln!("error: listing {:?}: {e}", a.inputs);
                    return ExitCode::FAILURE;
                }
            };
            let entries = run_batch(&paths, &a.out, a.jobs, !a.no_progress && !cli.quiet);
            print!("{}", summary_table(&entries));
            let csv = a.out.join("batch_summary.csv");
            if let Err(e) = std::fs::create_dir_all(&a.out)
                .and_then(|_| std::fs::write(&csv, summary_csv(&entries)))
            {
                eprintln!("error: writing {}: {e}", csv.display());
                return ExitCode::FAILURE;
            }
            println!("summary: {}", csv.display());
            let failed = entries.iter().filter(|e| e.result.is_err()).count();
            let method_failed = entries
                .iter()
                .filter(|e| {
                    e.result
                        .as_ref()
                        .is_ok_and(|o| crate::batch::has_failed_method(&o.report))
                })
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
        Command::ClosedForm { case } => match Case::from_file(&case) {
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
        },
        Command::Validate { cases_dir, out } => crate::validate::run(&cases_dir, &out),
        Command::SynthLoads { machine } => match Compressor::from_file(&machine) {
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
        },
    }
}
