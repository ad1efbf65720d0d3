//! Timing report of the inverse solver with the mass-conserving Reynolds film (issue 4, item 6):
//! one load cycle of a bearing the size of the compressor main bearing, where the time goes,
//! and how it scales with grid size and step count.
//!
//! Bearing (docs/conventions.md §7): L = 18.288 mm, R = 27.43 mm, c = 48.9 µm, partial groove
//! 24.9 × 3.81 mm at θ = 90° fed at 0.2068 MPa, 1800 rpm, μ = 0.02 Pa·s (assumed). Load: the
//! synthetic compressor-like cycle of the inverse benches (a 4 kN pulse once per turn on 0.8 kN,
//! plus a 0.6 kN second-order side load). Each run is the run-in (a quarter cycle) plus one
//! cycle (`max_cycles = 1`; the run-in's cost is reported apart).
//!
//! Times are CPU time of this thread (`CLOCK_THREAD_CPUTIME_ID`), so other processes on a
//! shared machine do not inflate them; one core, release build. "Film" is the time inside
//! `FilmModel::step` (one Reynolds time step: assembly, switch loop with ADI-Krylov solves,
//! outputs); "Newton" is everything else (the 2 × 2 Newton/Broyden algebra, bookkeeping,
//! recording). Rows:
//!
//! - the default grid 120 × 31 at the default step 1°: the benchmark;
//! - grid scaling at 1°: 60 × 15, 120 × 31, 240 × 61;
//! - step scaling at 120 × 31: 2°, 1°, 0.5°.
//!
//! Usage: `cargo run --release -p jbearing-validation --bin inverse_timing [-- [--quick |
//! --default | --grids] [--repeat N] [--jacobian exact|broyden|differences]
//! [--linear adi|multigrid|lu] [--whole-length] [--write-docs]]`
//! (`--quick`: the 60 × 15 rows only, to check that it runs; `--default`: the 120 × 31, 1° row
//! only, for before/after comparisons of a change; `--grids`: the three grid-scaling rows at 1°;
//! `--linear`: the frozen-switch linear solver, default the film's default (multigrid-Krylov);
//! `--whole-length`: solve the film on the whole grid although the bearing is symmetric about
//! its mid-plane (the default solves the half grid: `reynolds::grid` docs, "Mirror symmetry");
//! `--repeat N`: run every row N times and
//! report the run with the median time, for a machine shared with other jobs; `--jacobian`:
//! the inverse Newton's Jacobian, default exact; `--write-docs`: also put the report into
//! docs/performance.md in place of the block `<!-- BEGIN generated: COMMAND -->` …
//! `<!-- END generated -->`, COMMAND being this command line without `--write-docs`). "ms per film step" includes the exact
//! Jacobian's two linear solves; "Krylov iterations per film step" counts the film solves only.

use anyhow::{Context, Result};
use jbearing_solvers::inverse::{
    FilmModel, FilmModelError, FilmResponse, InverseParams, InverseSolution, JacobianMethod,
    NoObserver, OperatingConditions, RelaxedStep, ReynoldsFilm, solve_inverse,
};
use jbearing_solvers::load::{FnLoad, OperatingHistory};
use jbearing_solvers::reynolds::{FilmState, LinearSolver, ReynoldsSolver, TimeScheme};
use jbearing_validation::compressor_main::{FEED, OMEGA, pulse_load, reynolds_params};
use jbearing_validation::generated_docs::{docs_page, machine, take_report, write_generated_block};
use jbearing_validation::report;
use std::f64::consts::TAU;

fn thread_cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec; CLOCK_THREAD_CPUTIME_ID is supported by every
    // Linux kernel since 2.6.12.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}

/// The Reynolds film with a stopwatch around each step.
struct TimedFilm {
    inner: ReynoldsFilm,
    film_seconds: f64,
    krylov_iterations: usize,
}

impl FilmModel for TimedFilm {
    type State = FilmState;

    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> FilmState {
        self.inner.initial_state(eccentricity_ratio)
    }

    fn step(
        &mut self,
        state: &FilmState,
        eccentricity_ratio: [f64; 2],
        dt: f64,
        conditions: &OperatingConditions,
    ) -> Result<(FilmResponse, FilmState), FilmModelError> {
        let t0 = thread_cpu_seconds();
        let out = self.inner.step(state, eccentricity_ratio, dt, conditions);
        self.film_seconds += thread_cpu_seconds() - t0;
        if let Ok((resp, _)) = &out {
            self.krylov_iterations += resp.sweep_iterations;
        }
        out
    }

    fn state_change(&self, a: &FilmState, b: &FilmState) -> f64 {
        self.inner.state_change(a, b)
    }

    fn set_capture_fields(&mut self, capture: bool) {
        self.inner.set_capture_fields(capture);
    }

    fn relax_next_step(&mut self, relax: RelaxedStep) {
        self.inner.relax_next_step(relax);
    }

    fn last_step_relaxed(&self) -> bool {
        self.inner.last_step_relaxed()
    }

    // The local error control and the cycle extrapolation need these: without them the timed
    // film would run a configuration the application does not.
    fn time_scheme(&self) -> Option<TimeScheme> {
        self.inner.time_scheme()
    }

    fn state_vector(&self, state: &FilmState) -> Option<Vec<f64>> {
        self.inner.state_vector(state)
    }

    fn join_substeps(&self, start: &FilmState, end: &mut FilmState, dt: f64) {
        self.inner.join_substeps(start, end, dt)
    }

    fn boundary_volumes(&self, state: &FilmState) -> Option<Vec<f64>> {
        self.inner.boundary_volumes(state)
    }

    fn state_from_vector(
        &self,
        template: &FilmState,
        eccentricity_ratio: [f64; 2],
        vector: &[f64],
    ) -> Option<FilmState> {
        self.inner
            .state_from_vector(template, eccentricity_ratio, vector)
    }

    /// The exact Jacobian's two linear solves are film time too.
    fn force_jacobian(&mut self) -> Option<Result<[[f64; 2]; 2], FilmModelError>> {
        let t0 = thread_cpu_seconds();
        let out = self.inner.force_jacobian();
        self.film_seconds += thread_cpu_seconds() - t0;
        out
    }
}

struct Row {
    grid: (usize, usize),
    step_deg: f64,
    total: f64,
    film: f64,
    krylov: usize,
    solution: InverseSolution,
}

fn run(
    n_theta: usize,
    n_z: usize,
    step_deg: f64,
    jacobian: JacobianMethod,
    linear: LinearSolver,
    whole_length: bool,
) -> Result<Row> {
    let load = OperatingHistory {
        load: FnLoad {
            period: TAU / OMEGA,
            load: pulse_load,
        },
        journal_speed: OMEGA,
        bearing_speed: 0.0,
        feed_pressures: vec![FEED],
    };
    let mut reynolds = reynolds_params(TimeScheme::default(), n_theta, n_z);
    reynolds.linear_solver = linear;
    // The groove is centred on the mid-plane: the film is solved on its half grid unless
    // `whole_length` (`reynolds::grid` docs, "Mirror symmetry").
    let inner = if whole_length {
        ReynoldsFilm::from(ReynoldsSolver::new_whole_length(reynolds)?)
    } else {
        ReynoldsFilm::new(reynolds)?
    };
    let mut film = TimedFilm {
        inner,
        film_seconds: 0.0,
        krylov_iterations: 0,
    };
    let params = InverseParams {
        step_deg,
        max_cycles: 1,
        jacobian,
        ..Default::default()
    };
    let t0 = thread_cpu_seconds();
    let solution = solve_inverse(&params, &load, &mut film, &mut NoObserver)
        .with_context(|| format!("{n_theta} × {n_z}, {step_deg}°"))?;
    let total = thread_cpu_seconds() - t0;
    Ok(Row {
        grid: (n_theta, n_z),
        step_deg,
        total,
        film: film.film_seconds,
        krylov: film.krylov_iterations,
        solution,
    })
}

/// The command line: which rows, how often, with which Jacobian and linear solver, and
/// whether to write the docs block (`args` is the command line without `--write-docs`).
struct Options {
    args: Vec<String>,
    write_docs: bool,
    quick: bool,
    default_only: bool,
    grids_only: bool,
    linear: LinearSolver,
    repeat: usize,
    jacobian: JacobianMethod,
    whole_length: bool,
}

impl Options {
    /// The options of this process's command line; an unknown argument or a bad value is an
    /// error naming what was expected.
    fn parse() -> Result<Self> {
        let mut args: Vec<String> = std::env::args().skip(1).collect();
        let write_docs = args.iter().any(|a| a == "--write-docs");
        args.retain(|a| a != "--write-docs");
        let mut rest = args.iter();
        while let Some(a) = rest.next() {
            match a.as_str() {
                "--quick" | "--default" | "--grids" | "--whole-length" => {}
                "--repeat" | "--jacobian" | "--linear" => {
                    rest.next();
                }
                other => anyhow::bail!(
                    "unknown argument {other:?} (expected --quick, --default, --grids, --repeat N, \
                     --jacobian exact|broyden|differences, --linear adi|multigrid|lu, \
                     --whole-length, --write-docs)"
                ),
            }
        }
        let quick = args.iter().any(|a| a == "--quick");
        let default_only = args.iter().any(|a| a == "--default");
        let grids_only = args.iter().any(|a| a == "--grids");
        let whole_length = args.iter().any(|a| a == "--whole-length");
        let linear = match args.iter().position(|a| a == "--linear") {
            Some(i) => match args.get(i + 1).map(String::as_str) {
                Some("adi") => LinearSolver::AdiKrylov,
                Some("multigrid") => LinearSolver::MultigridKrylov,
                Some("lu") => LinearSolver::SparseLu,
                other => anyhow::bail!("--linear {other:?}: expected adi, multigrid or lu"),
            },
            None => LinearSolver::default(),
        };
        let repeat: usize = match args.iter().position(|a| a == "--repeat") {
            Some(i) => args
                .get(i + 1)
                .and_then(|v| v.parse().ok())
                .filter(|&n: &usize| n >= 1)
                .context("--repeat needs a positive count")?,
            None => 1,
        };
        let jacobian = match args.iter().position(|a| a == "--jacobian") {
            Some(i) => match args.get(i + 1).map(String::as_str) {
                Some("exact") => JacobianMethod::Exact,
                Some("broyden") => JacobianMethod::Broyden,
                Some("differences") => JacobianMethod::FiniteDifference,
                other => {
                    anyhow::bail!("--jacobian {other:?}: expected exact, broyden or differences")
                }
            },
            None => JacobianMethod::default(),
        };
        Ok(Self {
            args,
            write_docs,
            quick,
            default_only,
            grids_only,
            linear,
            repeat,
            jacobian,
            whole_length,
        })
    }

    /// The rows to measure: (n_θ, n_z, step in degrees).
    fn plan(&self) -> Vec<(usize, usize, f64)> {
        if self.quick {
            vec![(60, 15, 2.0), (60, 15, 1.0)]
        } else if self.default_only {
            vec![(120, 31, 1.0)]
        } else if self.grids_only {
            vec![(60, 15, 1.0), (120, 31, 1.0), (240, 61, 1.0)]
        } else {
            vec![
                (120, 31, 1.0),
                (60, 15, 1.0),
                (240, 61, 1.0),
                (120, 31, 2.0),
                (120, 31, 0.5),
            ]
        }
    }
}

fn main() -> Result<()> {
    let opts = Options::parse()?;
    report!(
        "Machine: {}. Measured: {}. Thread CPU time, one core, release build; {:?} Jacobian; \
         {:?} linear solver; {}{}.\n",
        machine(),
        jiff::Timestamp::now().strftime("%Y-%m-%d %H:%M UTC"),
        opts.jacobian,
        opts.linear,
        if opts.whole_length {
            "the whole grid (--whole-length)"
        } else {
            "the half grid of the mid-plane symmetry"
        },
        if opts.repeat > 1 {
            format!("; each row the median of {} runs", opts.repeat)
        } else {
            String::new()
        }
    );
    report!(
        "| grid | step | run-in + cycle (s) | per cycle (s) | film / Newton share | film steps per time step | ms per film step | Krylov iterations per film step | stalled / split steps | cycle min h_min (µm) | mean power (W) |"
    );
    report!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (nt, nz, step) in opts.plan() {
        let mut runs = (0..opts.repeat)
            .map(|_| run(nt, nz, step, opts.jacobian, opts.linear, opts.whole_length))
            .collect::<Result<Vec<_>>>()?;
        runs.sort_by(|a, b| a.total.total_cmp(&b.total));
        report_row(&runs.swap_remove(opts.repeat / 2));
    }
    report!(
        "\n\"per cycle\" scales the run-in + cycle time by (cycle steps) / (run-in + cycle steps)."
    );
    if opts.write_docs {
        // The block is named by the command that measured it, --write-docs left out.
        let mut command =
            "cargo run --release -p jbearing-validation --bin inverse_timing".to_string();
        if !opts.args.is_empty() {
            command = format!("{command} -- {}", opts.args.join(" "));
        }
        let page = docs_page("performance.md");
        write_generated_block(&page, &command, &take_report())?;
        eprintln!("wrote the block of {command:?} in {}", page.display());
    }
    Ok(())
}

/// One row of the table: a run's grid, step, times, shares, film-step statistics and answer.
fn report_row(r: &Row) {
    let info = &r.solution.info;
    let steps = info.run_in_steps + info.steps_per_cycle;
    let per_cycle = r.total * info.steps_per_cycle as f64 / steps as f64;
    let evals = info.film_evaluations as f64;
    report!(
        "| {} × {} | {}° | {:.2} | {:.2} | {:.1} % / {:.1} % | {:.2} | {:.2} | {:.1} | {} / {} | {:.3} | {:.2} |",
        r.grid.0,
        r.grid.1,
        r.step_deg,
        r.total,
        per_cycle,
        100.0 * r.film / r.total,
        100.0 * (r.total - r.film) / r.total,
        evals / steps as f64,
        1e3 * r.film / evals,
        r.krylov as f64 / evals,
        info.stalled_steps,
        info.split_steps,
        1e6 * r.solution.summary.min_film_thickness,
        r.solution.summary.mean_power_loss,
    );
}
