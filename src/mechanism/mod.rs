//! `jbearing run` of a mechanism case (the slider-crank of \[Flores2009\] with its rod–slider joint
//! ideal or lubricated, [`crate::case::mechanism`]): the solves, the HDF5 file, the summary and
//! the plots.
//!
//! ```text
//!   MechanismCase ──► solve_mechanism(lubricated)  ─┐
//!                 └─► solve_mechanism(ideal joint) ─┴─► CASE.h5            (hdf5)
//!                                                       CASE_summary.csv   (summary_rows)
//!                                                       CASE_forces.png, CASE_orbit.png,
//!                                                       CASE_film.png      (plots; film: lubricated)
//! ```
//!
//! A lubricated case runs the ideal mechanism too (unless `ideal_reference = false`): the paper
//! compares the two (Figs. 13–15). An ideal case runs once.

pub mod hdf5;
pub mod plots;

use std::path::{Path, PathBuf};
use std::time::Instant;

use jbearing_solvers::mechanism::{
    ContactEventKind, MechanismError, MechanismSolution, RodSliderJoint, solve_mechanism,
};

use crate::batch::Progress;
use crate::case::CaseError;
use crate::case::mechanism::{MechanismCase, is_mechanism_text};
use crate::output::{OutputError, write_atomically};
use crate::sweep::CaseJob;

/// Name of the lubricated run's group and column.
pub const LUBRICATED: &str = "lubricated";
/// Name of the ideal run's group and column.
pub const IDEAL: &str = "ideal";

/// What can go wrong in a mechanism run.
#[derive(Debug, thiserror::Error)]
pub enum MechanismRunError {
    /// The case file is bad.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A solve failed.
    #[error("case '{case}': the {joint} run failed: {source}")]
    Solve {
        /// Case name.
        case: String,
        /// `lubricated` or `ideal`.
        joint: &'static str,
        /// The solver's error.
        #[source]
        source: MechanismError,
    },
    /// The output directory cannot be made or written.
    #[error("output directory '{}' is not usable: {source}", path.display())]
    OutputDir {
        /// The directory.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// Writing a file failed.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// The runs of one mechanism case.
#[derive(Debug, Clone)]
pub struct MechanismResults {
    /// The case.
    pub case: MechanismCase,
    /// The lubricated run (lubricated cases).
    pub lubricated: Option<MechanismSolution>,
    /// The ideal run (ideal cases, and the reference of lubricated ones).
    pub ideal: Option<MechanismSolution>,
    /// Wall-clock time of the solves (s).
    pub wall_time: f64,
    /// Start, ISO 8601 UTC.
    pub started_utc: String,
}

impl MechanismResults {
    /// The runs with their group names, lubricated first.
    pub fn runs(&self) -> Vec<(&'static str, &MechanismSolution)> {
        let mut v = Vec::new();
        if let Some(s) = &self.lubricated {
            v.push((LUBRICATED, s));
        }
        if let Some(s) = &self.ideal {
            v.push((IDEAL, s));
        }
        v
    }
}

/// What a run wrote.
#[derive(Debug, Clone)]
pub struct MechanismOutcome {
    /// The results.
    pub results: MechanismResults,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// Solve the case: the joint as given, and the ideal reference of a lubricated joint.
/// `progress` gets one line per run start and end.
pub fn solve(
    case: &MechanismCase,
    progress: &dyn Fn(&str),
) -> Result<MechanismResults, MechanismRunError> {
    let started = Instant::now();
    let started_utc = crate::run::now_utc();
    let run = |joint: &'static str, params| {
        let what = match case.lubricated_joint() {
            Some(_) if joint == LUBRICATED => format!(
                "{joint} joint ({} film, {}, {} turns)",
                case.film_name, case.integrator_name, case.params.turns
            ),
            _ => format!("{joint} joint ({} turns)", case.params.turns),
        };
        progress(&format!("{what}: started"));
        let t = Instant::now();
        let sol = solve_mechanism(params).map_err(|source| MechanismRunError::Solve {
            case: case.name.clone(),
            joint,
            source,
        })?;
        progress(&format!(
            "{joint} joint: done in {:.2} s, {} steps",
            t.elapsed().as_secs_f64(),
            sol.info.steps
        ));
        Ok::<_, MechanismRunError>(sol)
    };
    let (lubricated, ideal) = match &case.params.joint {
        RodSliderJoint::Lubricated(_) => {
            let l = run(LUBRICATED, &case.params)?;
            let i = if case.ideal_reference {
                Some(run(IDEAL, &case.ideal_params())?)
            } else {
                None
            };
            (Some(l), i)
        }
        RodSliderJoint::Ideal => (None, Some(run(IDEAL, &case.params)?)),
    };
    Ok(MechanismResults {
        case: case.clone(),
        lubricated,
        ideal,
        wall_time: started.elapsed().as_secs_f64(),
        started_utc,
    })
}

/// Run the case and write `CASE.h5`, `CASE_summary.csv` and (with `plots`) the PNG figures
/// into `out_dir`. The directory is made and tried for writing before the solve.
pub fn run_mechanism_case(
    case: &MechanismCase,
    out_dir: &Path,
    progress: &dyn Fn(&str),
) -> Result<MechanismOutcome, MechanismRunError> {
    let unusable = |source| MechanismRunError::OutputDir {
        path: out_dir.to_path_buf(),
        source,
    };
    std::fs::create_dir_all(out_dir).map_err(unusable)?;
    tempfile::NamedTempFile::new_in(out_dir).map_err(unusable)?;
    for stale in crate::output::remove_stale_temporaries(out_dir) {
        tracing::warn!("removed {}, left by a run that was killed", stale.display());
    }
    let results = solve(case, progress)?;
    let mut files = Vec::new();
    let h5 = out_dir.join(format!("{}.h5", case.name));
    hdf5::write_file(&results, &h5)?;
    files.push(h5);
    let csv = out_dir.join(format!("{}_summary.csv", case.name));
    write_summary_csv(&results, &csv)?;
    files.push(csv);
    if case.plots {
        files.extend(plots::write_plots(&results, out_dir)?);
    }
    Ok(MechanismOutcome { results, files })
}

/// One row of the summary: a figure of each run.
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryRow {
    /// Variable-style name.
    pub name: &'static str,
    /// Units (UDUNITS).
    pub units: &'static str,
    /// What it is.
    pub long_name: &'static str,
    /// Lubricated run's value.
    pub lubricated: Option<f64>,
    /// Ideal run's value.
    pub ideal: Option<f64>,
}

impl SummaryRow {
    /// (lubricated − ideal) / |ideal| in percent, when both are there and ideal ≠ 0.
    pub fn deviation_percent(&self) -> Option<f64> {
        match (self.lubricated, self.ideal) {
            (Some(l), Some(i)) if i != 0.0 => Some(100.0 * (l - i) / i.abs()),
            _ => None,
        }
    }
}

fn onsets(s: &MechanismSolution) -> usize {
    s.contact_events
        .iter()
        .filter(|e| e.kind == ContactEventKind::Onset)
        .count()
}

/// The figures of each run: peaks of the joint force and the crank moment, h_min and where,
/// ε max, contact onsets, periodicity, step counts.
pub fn summary_rows(r: &MechanismResults) -> Vec<SummaryRow> {
    type Get = fn(&MechanismSolution) -> Option<f64>;
    let rows: [(&str, &str, &str, Get); 11] = [
        (
            "joint_force_max",
            "N",
            "largest |F| of the rod-slider joint over the run",
            |s| Some(s.info.max_joint_force),
        ),
        (
            "crank_moment_max",
            "N m",
            "largest |M| of the driving moment over the run",
            |s| Some(s.info.max_crank_moment),
        ),
        (
            "min_film_thickness_min",
            "m",
            "smallest minimum film thickness h_min over the run (negative: penetration)",
            |s| s.info.min_film_thickness,
        ),
        (
            "min_film_crank_angle",
            "degree",
            "crank angle of the smallest h_min (from the start, not wrapped)",
            |s| s.info.min_film_crank_angle_deg,
        ),
        (
            "eccentricity_ratio_max",
            "1",
            "largest journal eccentricity ratio |e|/c over the run",
            |s| (!s.min_film_thickness.is_empty()).then_some(s.info.max_eccentricity_ratio),
        ),
        (
            "contact_onsets",
            "1",
            "number of dry-contact onsets (h_min below the boundary layer)",
            |s| (!s.min_film_thickness.is_empty()).then_some(onsets(s) as f64),
        ),
        (
            "periodicity_change",
            "1",
            "max over the last turn of |e(t) - e(t - T)| / c",
            |s| s.info.periodicity_change,
        ),
        ("steps", "1", "accepted time steps", |s| {
            Some(s.info.steps as f64)
        }),
        ("rejected_steps", "1", "rejected time steps (Radau5)", |s| {
            Some(s.info.rejected_steps as f64)
        }),
        (
            "evaluations",
            "1",
            "right-hand-side (Radau5) or residual (BDF2) evaluations",
            |s| Some(s.info.evaluations as f64),
        ),
        ("film_steps", "1", "Reynolds film steps", |s| {
            Some(s.info.film_steps as f64)
        }),
    ];
    rows.into_iter()
        .map(|(name, units, long_name, get)| SummaryRow {
            name,
            units,
            long_name,
            lubricated: r.lubricated.as_ref().and_then(get),
            ideal: r.ideal.as_ref().and_then(get),
        })
        .collect()
}

/// `CASE_summary.csv`: `quantity,units,long_name,lubricated,ideal,lubricated_vs_ideal_percent`,
/// empty cells where a run lacks the figure (numbers in Rust's shortest round-trip form).
pub fn write_summary_csv(r: &MechanismResults, path: &Path) -> Result<(), OutputError> {
    let cell = |v: Option<f64>| v.map(|x| x.to_string()).unwrap_or_default();
    write_atomically(path, |tmp| {
        let csv_err = |source| OutputError::Csv {
            path: path.to_path_buf(),
            source,
        };
        let mut w = csv::Writer::from_path(tmp).map_err(csv_err)?;
        w.write_record([
            "quantity",
            "units",
            "long_name",
            LUBRICATED,
            IDEAL,
            "lubricated_vs_ideal_percent",
        ])
        .map_err(csv_err)?;
        for row in summary_rows(r) {
            w.write_record([
                row.name.to_string(),
                row.units.to_string(),
                row.long_name.to_string(),
                cell(row.lubricated),
                cell(row.ideal),
                cell(row.deviation_percent()),
            ])
            .map_err(csv_err)?;
        }
        w.flush().map_err(|source| OutputError::Io {
            action: "flushing",
            path: path.to_path_buf(),
            source,
        })
    })
}

/// The summary as a text table for the terminal.
pub fn summary_table(r: &MechanismResults) -> String {
    use std::fmt::Write as _;
    let mut s = format!(
        "{:<30} {:>16} {:>16} {:>10}\n",
        format!("case {}", r.case.name),
        LUBRICATED,
        IDEAL,
        "Δ %"
    );
    for row in summary_rows(r) {
        if matches!(row.name, "rejected_steps" | "evaluations" | "film_steps") {
            continue;
        }
        let (scale, unit) = match row.units {
            "m" => (1e6, "µm"),
            u => (1.0, u),
        };
        let count = matches!(row.name, "contact_onsets" | "steps");
        let f = |v: Option<f64>| {
            v.map_or("–".to_string(), |v| {
                if count {
                    format!("{v:.0}")
                } else {
                    format!("{:.4}", v * scale)
                }
            })
        };
        let line = format!(
            "{:<30} {:>16} {:>16} {:>10}",
            format!("{} [{unit}]", row.name),
            f(row.lubricated),
            f(row.ideal),
            row.deviation_percent()
                .map_or("".to_string(), |d| format!("{d:+.2}"))
        );
        let _ = writeln!(s, "{}", line.trim_end());
    }
    s
}

/// The mechanism case of a batch job, or `None` when the job is a bearing case (no
/// `[mechanism]` table). A sweep point's error names the point at the file's sweep table, as
/// [`crate::sweep::CaseJob::case`] does for bearing cases.
pub fn job_case(job: &CaseJob) -> Option<Result<MechanismCase, CaseError>> {
    let text = match &job.text {
        Some(t) => t.clone(),
        None => std::fs::read_to_string(&job.path).ok()?,
    };
    if !is_mechanism_text(&text) {
        return None;
    }
    Some(match &job.text {
        None => MechanismCase::from_text(&text, &job.path),
        Some(_) => MechanismCase::from_text(&text, &job.path).map_err(|e| {
            let original = std::fs::read_to_string(&job.path).unwrap_or_default();
            let line = original
                .lines()
                .position(|l| l.contains(&format!("[{}", crate::sweep::SWEEP_TABLE)))
                .map_or(1, |i| i + 1);
            CaseError::Key {
                file: job.path.clone(),
                line,
                key: format!("{} point '{}'", crate::sweep::SWEEP_TABLE, job.name),
                message: e.to_string(),
            }
        }),
    })
}

/// Whether a batch job is a mechanism case (its text has a `[mechanism]` table; false when
/// the file cannot be read).
pub fn is_mechanism_job(job: &CaseJob) -> bool {
    match &job.text {
        Some(t) => is_mechanism_text(t),
        None => crate::case::mechanism::is_mechanism_file(&job.path),
    }
}

/// A progress printer for `run` and `batch`: plain lines `[elapsed] CASE: message` on stderr
/// (the solver reports no steps, so a terminal gets the same lines), nothing when hidden.
pub fn progress_printer(progress: Progress, case: &str) -> impl Fn(&str) + use<> {
    let started = Instant::now();
    let case = case.to_string();
    move |message: &str| {
        if progress != Progress::Hidden {
            eprintln!(
                "[{:>7.1} s] {case}: {message}",
                started.elapsed().as_secs_f64()
            );
        }
    }
}

/// `jbearing run` of a mechanism case file: run it, print the files and the summary. Exit
/// status: failure when the case is bad or a solve or a write fails.
pub fn run_cli(path: &Path, out_dir: &Path, progress: Progress) -> std::process::ExitCode {
    let case = match MechanismCase::from_file(path) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let printer = progress_printer(progress, &case.name);
    match run_mechanism_case(&case, out_dir, &printer) {
        Ok(o) => {
            for f in &o.files {
                println!("wrote {}", f.display());
            }
            print!("{}", summary_table(&o.results));
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
