//! `solve_inverse`: run-in, Newton per time step, cycles to a periodic orbit, time series.
//!
//! See the module docs of [`super`] for the equations. Index map of one cycle (N steps):
//!
//! ```text
//!   state:   S_0 ──step 1──> S_1 ──step 2──> … ──step N──> S_N  (= S_0 of the next cycle)
//!   time:    t_c            t_c+dt           …             t_c+τ
//!   record:                 steps[0]         …             steps[N−1]  (crank angle Δφ … 360°)
//! ```
//!
//! Cycle numbering in errors and progress: 0 is the run-in, 1, 2, … the load cycles.

use super::cycle_map::CycleExtrapolation;
use super::error_control::{ErrorControl, extrapolate, quadratic};
use super::types::*;
use super::{FilmFields, FilmModel, FilmModelError, FilmResponse, OperatingConditions};
use crate::load::LoadHistory;
use std::time::Instant;

/// Where a step is, for error messages.
#[derive(Clone, Copy)]
struct Where {
    time: f64,
    crank_angle_deg: f64,
    cycle: usize,
}

impl Where {
    /// The film model failed at the trial `eps` of this step.
    fn film_error(self, eccentricity_ratio: [f64; 2], source: FilmModelError) -> InverseError {
        InverseError::Film {
            time: self.time,
            crank_angle_deg: self.crank_angle_deg,
            cycle: self.cycle,
            eccentricity_ratio,
            source,
        }
    }

    /// [`InverseError::Interrupted`] here when the observer asks to stop.
    fn stop_if_requested<O: InverseObserver + ?Sized>(
        self,
        observer: &mut O,
    ) -> Result<(), InverseError> {
        if observer.stop_requested() {
            return Err(InverseError::Interrupted {
                time: self.time,
                crank_angle_deg: self.crank_angle_deg,
                cycle: self.cycle,
            });
        }
        Ok(())
    }

    /// Newton could not converge this step; `last` is its last iterate.
    fn newton_failed<S>(self, iterations: usize, last: &Iterate<S>) -> InverseError {
        InverseError::NewtonFailed {
            time: self.time,
            crank_angle_deg: self.crank_angle_deg,
            cycle: self.cycle,
            iterations,
            residual: last.res,
            eccentricity_ratio: last.eps,
            cavitated_fraction: last.response.cavitated_fraction,
        }
    }
}

/// Counters shared by all steps.
#[derive(Default)]
struct Stats {
    newton: usize,
    max_newton: usize,
    evaluations: usize,
    jacobians: usize,
    sweeps: usize,
    stalled: usize,
    max_stalled: f64,
    split: usize,
    /// Halvings on Newton failure at any depth (substeps included).
    halvings: usize,
}

/// The Jacobian ∂F/∂ε carried across steps.
struct Jacobian {
    m: [[f64; 2]; 2],
    valid: bool,
}

/// An accepted step.
struct Accepted<S> {
    eps: [f64; 2],
    response: FilmResponse,
    state: S,
    residual: f64,
    iterations: usize,
}

/// The film's rate outputs of a step taken in parts (substeps of the error control, halves of
/// a split step): their mean over the step, each part weighted by its share of the step —
/// side leakage, supply and recirculated flow, friction torques and power loss are flows of
/// the step, whose time integrals the step's parts add up (a part's rates are its own: those
/// of the implicit step that ends it). The state outputs (force, h_min, p_max, cavitated
/// fraction) stay those of the step's end, `last`.
fn step_mean_rates(last: &FilmResponse, parts: &[(f64, FilmResponse)]) -> FilmResponse {
    let mut mean = last.clone();
    let weighted = |f: &dyn Fn(&FilmResponse) -> f64| parts.iter().map(|(w, r)| w * f(r)).sum();
    mean.side_leakage = [
        weighted(&|r| r.side_leakage[0]),
        weighted(&|r| r.side_leakage[1]),
    ];
    for (g, q) in mean.supply_flow.iter_mut().enumerate() {
        *q = weighted(&|r| r.supply_flow.get(g).copied().unwrap_or(0.0));
    }
    mean.recirculated_flow = weighted(&|r| r.recirculated_flow);
    mean.friction_torque_journal = weighted(&|r| r.friction_torque_journal);
    mean.friction_torque_bearing = weighted(&|r| r.friction_torque_bearing);
    mean.power_loss = weighted(&|r| r.power_loss);
    mean
}

/// The step's side leakage and supply flows as its boundary volumes (`start` → `end`,
/// [`FilmModel::boundary_volumes`]) over its length `dt`, where the film model has them in the
/// layout of `response` (two ends, then each groove); else `response` as it is.
fn step_flows_from_volumes(
    response: &mut FilmResponse,
    start: Option<Vec<f64>>,
    end: Option<Vec<f64>>,
    dt: f64,
) {
    let (Some(y0), Some(y1)) = (start, end) else {
        return;
    };
    if y0.len() != y1.len() || y1.len() != 2 + response.supply_flow.len() {
        return;
    }
    let flow = |k: usize| (y1[k] - y0[k]) / dt;
    response.side_leakage = [flow(0), flow(1)];
    for (g, q) in response.supply_flow.iter_mut().enumerate() {
        *q = flow(2 + g);
    }
}

/// More chord steps than this still to take (at the last step's rate) and the exact Jacobian is
/// refreshed at the next iterate: a refresh — two linear solves on the step's multigrid
/// hierarchy — costs about half a film step, and a fresh Newton step gains 100–4000× where a
/// carried Jacobian gains 4–6× (docs/performance.md, "Sixth look"). Matters at tight force
/// tolerances: the application's 1e-6 took 8–10 chord steps from a 0.1–1 residual.
const CHORD_STEPS_WORTH_A_REFRESH: f64 = 2.0;

/// Chord steps still to take after one that took the residual from `before` to `after`, were
/// each to gain as much (linear convergence at the rate after / before), until `tolerance`.
fn chord_steps_left(after: f64, before: f64, tolerance: f64) -> f64 {
    if after <= tolerance {
        return 0.0;
    }
    let rate = after / before;
    if rate >= 1.0 {
        return f64::INFINITY;
    }
    (after / tolerance).ln() / (1.0 / rate).ln()
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// Solve the inverse problem for `load` with `film`; progress goes to `observer`.
///
/// Returns the periodic solution (or the last cycle with [`InverseInfo::warning`] set when the
/// cycle limit is reached), or an error: [`InverseError::Collapse`] when the film cannot carry
/// the load, [`InverseError::NewtonFailed`] / [`InverseError::Film`] when a step fails.
///
/// ```
/// use jbearing_solvers::prelude::*;
/// use std::f64::consts::TAU;
///
/// // Under a constant load the orbit settles on Ocvirk's steady short-bearing position.
/// let params = ClosedFormParams { radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02 };
/// let mut film = ClosedFormFilm::new(ClosedFormModel::ShortGumbelMovingFilm, params, TimeScheme::Bdf2)?;
/// let omega = 300.0;
/// let history = OperatingHistory {
///     load: ConstantLoad { load: [0.0, -1000.0], period: TAU / omega },
///     journal_speed: omega,
///     bearing_speed: 0.0,
///     feed_pressures: vec![],
/// };
/// let settings = InverseParams { step_deg: 5.0, ..Default::default() };
/// let solution = solve_inverse(&settings, &history, &mut film, &mut NoObserver)?;
/// let e = solution.steps.last().unwrap().eccentricity;
/// let ocvirk = jbearing_solvers::closed_form::short::ocvirk_steady_load(&params, e, omega);
/// assert!(solution.info.periodic && (ocvirk - 1000.0).abs() < 1.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_inverse<F, L, O>(
    params: &InverseParams,
    load: &L,
    film: &mut F,
    observer: &mut O,
) -> Result<InverseSolution, InverseError>
where
    F: FilmModel + ?Sized,
    L: LoadHistory + ?Sized,
    O: InverseObserver + ?Sized,
{
    solve_inverse_from(params, load, film, observer, None).map(|(solution, _)| solution)
}

/// [`solve_inverse`] started from `start` — the journal and film at the end of a cycle of an
/// earlier solve of a nearby problem (the same bearing at another viscosity, in a heat
/// balance) — instead of the run-in from ε = 0; `None` runs the run-in. Also returns where
/// this solve ended, to start the next one from. The periodic answer does not depend on the
/// start (the cycles continue until the periodicity test holds; the first cycle is never
/// periodic), only the number of cycles does. The start must come from the same film model,
/// grid and time step.
///
/// ```
/// use jbearing_solvers::prelude::*;
/// use jbearing_solvers::inverse::solve_inverse_from;
/// use jbearing_solvers::load::FnLoad;
/// use std::f64::consts::TAU;
///
/// // A rotating load; then the same bearing with an oil 10 % thinner, started where the first
/// // solve ended: no run-in, and the periodic orbit in no more cycles than from the centre.
/// let omega = 300.0;
/// let history = OperatingHistory {
///     load: FnLoad {
///         period: TAU / omega,
///         load: |t: f64| [-800.0 * (omega * t).cos(), -800.0 * (omega * t).sin() - 400.0],
///     },
///     journal_speed: omega,
///     bearing_speed: 0.0,
///     feed_pressures: vec![],
/// };
/// let settings = InverseParams { step_deg: 5.0, ..Default::default() };
/// let film = |mu| {
///     let params = ClosedFormParams { radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: mu };
///     ClosedFormFilm::new(ClosedFormModel::ShortGumbelMovingFilm, params, TimeScheme::Bdf2)
/// };
/// let (_, end) = solve_inverse_from(&settings, &history, &mut film(0.02)?, &mut NoObserver, None)?;
/// let (warm, _) = solve_inverse_from(&settings, &history, &mut film(0.018)?, &mut NoObserver, Some(end))?;
/// let (cold, _) = solve_inverse_from(&settings, &history, &mut film(0.018)?, &mut NoObserver, None)?;
/// assert!(warm.info.periodic && warm.info.run_in_steps == 0);
/// assert!(warm.info.cycles <= cold.info.cycles);
/// // The periodic answer does not depend on the start (to the periodicity tolerance).
/// let (a, b) = (warm.summary.max_eccentricity, cold.summary.max_eccentricity);
/// assert!((a - b).abs() < 10.0 * settings.periodicity_tolerance, "{a} vs {b}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_inverse_from<F, L, O>(
    params: &InverseParams,
    load: &L,
    film: &mut F,
    observer: &mut O,
    start_from: Option<InverseStart<F::State>>,
) -> Result<(InverseSolution, InverseStart<F::State>), InverseError>
where
    F: FilmModel + ?Sized,
    L: LoadHistory + ?Sized,
    O: InverseObserver + ?Sized,
{
    let start = Instant::now();
    validate(params)?;
    let warm = start_from.is_some();
    let grid = CycleGrid::new(params, load, warm)?;
    let mut stepper = Stepper {
        params,
        w_ref: reference_load(params, load, &grid)?,
        jac: Jacobian {
            m: [[0.0; 2]; 2],
            valid: false,
        },
        stats: Stats::default(),
        stalls: Vec::new(),
        control: film.time_scheme().and_then(|scheme| {
            ErrorControl::new(
                scheme,
                params.step_error_tolerance,
                params.max_step_splits,
                grid.steps,
            )
        }),
    };
    if let (Some(control), Some(start)) = (stepper.control.as_mut(), start_from.as_ref()) {
        control.start_from(&start.step_levels);
    }
    let mut orbit = Orbit::starting(start_from, &*film);
    orbit.run_in(&mut stepper, film, load, &grid, observer)?;
    let outcome = orbit.cycles_until_periodic(&mut stepper, film, load, &grid, observer)?;

    let info = inverse_info(params, &grid, &stepper, &outcome, start);
    let end = InverseStart {
        eccentricity_ratio: orbit.eps,
        previous: [orbit.prev, orbit.prev2],
        state: orbit.state,
        step_levels: stepper
            .control
            .as_ref()
            .map_or_else(Vec::new, |c| c.levels().to_vec()),
    };
    let solution = InverseSolution {
        summary: summarize(&outcome.records),
        steps: outcome.records,
        fields: outcome.snapshots,
        info,
    };
    Ok((solution, end))
}

/// The record of one solve: its time grid, the periodicity test's outcome (a warning when it
/// failed), the reference load, the step statistics and the wall time since `start`.
fn inverse_info(
    params: &InverseParams,
    grid: &CycleGrid,
    stepper: &Stepper<'_>,
    outcome: &CyclesOutcome,
    start: Instant,
) -> InverseInfo {
    let warning = (!outcome.periodic).then_some(InverseWarning::NotPeriodic {
        cycles: outcome.cycles,
        eccentricity_change: outcome.eccentricity_change,
        eccentricity_tolerance: params.periodicity_tolerance,
        film_state_change: outcome.film_state_change,
        film_state_tolerance: params.film_state_tolerance,
    });
    let stats = &stepper.stats;
    let (refined_steps, max_refinement_level) = stepper
        .control
        .as_ref()
        .map_or((0, 0), ErrorControl::refined);
    InverseInfo {
        steps_per_cycle: grid.steps,
        time_step: grid.dt,
        period: grid.period,
        cycle_deg: grid.cycle_deg,
        run_in_steps: grid.run_in,
        cycles: outcome.cycles,
        periodic: outcome.periodic,
        eccentricity_change: outcome.eccentricity_change,
        film_state_change: outcome.film_state_change,
        warning,
        reference_load: stepper.w_ref,
        newton_iterations: stats.newton,
        max_newton_iterations_per_step: stats.max_newton,
        film_evaluations: stats.evaluations,
        jacobian_evaluations: stats.jacobians,
        sweep_iterations: stats.sweeps,
        stalled_steps: stats.stalled,
        max_stalled_residual: stats.max_stalled,
        split_steps: stats.split,
        refined_steps,
        max_refinement_level,
        cycle_extrapolations: outcome.extrapolations,
        wall_time: start.elapsed().as_secs_f64(),
    }
}

/// The time grid of one solve: N steps of Δt per load cycle and the run-in length.
struct CycleGrid {
    /// Load period τ [s].
    period: f64,
    /// Crank angle of one load cycle [°] (720 for a four-stroke cycle).
    cycle_deg: f64,
    /// Steps per cycle N.
    steps: usize,
    /// Δt = τ / N [s].
    dt: f64,
    /// Run-in steps (0 from a given start).
    run_in: usize,
}

impl CycleGrid {
    /// N = cycle_deg / step_deg rounded (at least 4); run-in N/4 steps (at least 8) unless
    /// given, none when the solve starts from an earlier one.
    fn new<L: LoadHistory + ?Sized>(
        params: &InverseParams,
        load: &L,
        warm: bool,
    ) -> Result<Self, InverseError> {
        let period = load.period();
        if !(period.is_finite() && period > 0.0) {
            return Err(InverseError::InvalidParameter {
                name: "load period",
                value: period,
            });
        }
        let cycle_deg = load.cycle_deg();
        if !(cycle_deg.is_finite() && cycle_deg > 0.0) {
            return Err(InverseError::InvalidParameter {
                name: "cycle_deg",
                value: cycle_deg,
            });
        }
        let steps = ((cycle_deg / params.step_deg).round() as usize).max(4);
        let run_in = match (warm, params.run_in_steps) {
            (true, _) => 0,
            (false, 0) => (steps / 4).max(8),
            (false, given) => given,
        };
        Ok(Self {
            period,
            cycle_deg,
            steps,
            dt: period / steps as f64,
            run_in,
        })
    }
}

/// The reference load W_ref of the residual scale: [`InverseParams::reference_load`], or 1 % of
/// the peak load over the cycle when that is 0. Refuses a load that is not finite at a step.
fn reference_load<L: LoadHistory + ?Sized>(
    params: &InverseParams,
    load: &L,
    grid: &CycleGrid,
) -> Result<f64, InverseError> {
    let mut peak: f64 = 0.0;
    for i in 0..grid.steps {
        let t = i as f64 * grid.dt;
        let w = load.load(t);
        if !(w[0].is_finite() && w[1].is_finite()) {
            return Err(InverseError::NonFiniteLoad {
                quantity: "load",
                time: t,
            });
        }
        peak = peak.max(norm(w));
    }
    let w_ref = if params.reference_load > 0.0 {
        params.reference_load
    } else {
        1e-2 * peak
    };
    if w_ref.is_nan() || w_ref <= 0.0 {
        return Err(InverseError::InvalidParameter {
            name: "reference_load (the load is zero over the whole cycle)",
            value: w_ref,
        });
    }
    Ok(w_ref)
}

/// Speeds and feed pressures at `t`, refused when not finite.
fn conditions_at<L: LoadHistory + ?Sized>(
    load: &L,
    t: f64,
) -> Result<OperatingConditions, InverseError> {
    let c = OperatingConditions {
        journal_speed: load.journal_speed(t),
        bearing_speed: load.bearing_speed(t),
        feed_pressures: load.feed_pressures(t),
    };
    if !(c.journal_speed.is_finite()
        && c.bearing_speed.is_finite()
        && c.feed_pressures.iter().all(|p| p.is_finite()))
    {
        return Err(InverseError::NonFiniteLoad {
            quantity: "speed or feed pressure",
            time: t,
        });
    }
    Ok(c)
}

/// Load and conditions of the load cycle at `t` (the [`Drive`] of the cycles).
fn drive_at<L: LoadHistory + ?Sized>(
    load: &L,
    t: f64,
) -> Result<([f64; 2], OperatingConditions), InverseError> {
    let w = load.load(t);
    if !(w[0].is_finite() && w[1].is_finite()) {
        return Err(InverseError::NonFiniteLoad {
            quantity: "load",
            time: t,
        });
    }
    Ok((w, conditions_at(load, t)?))
}

/// What the cycles of one solve produced: the last cycle's records and snapshots, and the
/// periodicity test's numbers.
struct CyclesOutcome {
    records: Vec<InverseStep>,
    snapshots: Vec<FieldSnapshot>,
    cycles: usize,
    periodic: bool,
    eccentricity_change: f64,
    film_state_change: f64,
    /// Extrapolations of the cycle map made.
    extrapolations: usize,
}

/// max_i |ε_i − ε_i(previous cycle)| over the cycle's steps; ∞ for the first cycle.
fn orbit_change(previous: Option<&[[f64; 2]]>, current: &[[f64; 2]]) -> f64 {
    match previous {
        Some(p) => p
            .iter()
            .zip(current)
            .map(|(a, b)| norm([a[0] - b[0], a[1] - b[1]]))
            .fold(0.0, f64::max),
        None => f64::INFINITY,
    }
}

/// The periodicity test (module docs of [`super`]): the orbit and the film state both repeat
/// from one cycle to the next within their tolerances.
fn is_periodic(params: &InverseParams, orbit_change: f64, film_state_change: f64) -> bool {
    orbit_change <= params.periodicity_tolerance && film_state_change <= params.film_state_tolerance
}

fn validate(p: &InverseParams) -> Result<(), InverseError> {
    let positive = [
        ("step_deg", p.step_deg),
        ("tolerance", p.tolerance),
        ("fd_step", p.fd_step),
        ("accept_tolerance", p.accept_tolerance),
        ("max_newton_step", p.max_newton_step),
        ("periodicity_tolerance", p.periodicity_tolerance),
        ("film_state_tolerance", p.film_state_tolerance),
    ];
    for (name, value) in positive {
        if !(value.is_finite() && value > 0.0) {
            return Err(InverseError::InvalidParameter { name, value });
        }
    }
    if !(p.reference_load.is_finite() && p.reference_load >= 0.0) {
        return Err(InverseError::InvalidParameter {
            name: "reference_load",
            value: p.reference_load,
        });
    }
    if !(p.min_film_floor.is_finite() && p.min_film_floor >= 0.0) {
        return Err(InverseError::InvalidParameter {
            name: "min_film_floor",
            value: p.min_film_floor,
        });
    }
    if !(p.collapse_eccentricity > 0.0 && p.collapse_eccentricity < 1.0) {
        return Err(InverseError::InvalidParameter {
            name: "collapse_eccentricity",
            value: p.collapse_eccentricity,
        });
    }
    if !(p.step_error_tolerance.is_finite() && p.step_error_tolerance >= 0.0) {
        return Err(InverseError::InvalidParameter {
            name: "step_error_tolerance",
            value: p.step_error_tolerance,
        });
    }
    if p.max_cycles == 0 {
        return Err(InverseError::InvalidParameter {
            name: "max_cycles",
            value: 0.0,
        });
    }
    if p.max_newton_iterations == 0 {
        return Err(InverseError::InvalidParameter {
            name: "max_newton_iterations",
            value: 0.0,
        });
    }
    Ok(())
}

/// Linear extrapolation of the orbit, pulled back to ε^n if it would close more than half of
/// the gap to the wall.
fn predict(eps: [f64; 2], prev: [f64; 2]) -> [f64; 2] {
    let g = [2.0 * eps[0] - prev[0], 2.0 * eps[1] - prev[1]];
    pull_back(eps, g)
}

/// Quadratic extrapolation ε^{n+1} ≈ 3ε^n − 3ε^{n−1} + ε^{n−2} (error O(Δt³) against the linear
/// one's O(Δt²)), with the same pull-back.
fn predict_quadratic(eps: [f64; 2], prev: [f64; 2], prev2: [f64; 2]) -> [f64; 2] {
    pull_back(eps, quadratic(eps, prev, prev2))
}

fn pull_back(eps: [f64; 2], g: [f64; 2]) -> [f64; 2] {
    let e = norm(eps);
    if norm(g) < e + 0.5 * (1.0 - e) {
        g
    } else {
        eps
    }
}

fn record<S>(acc: &Accepted<S>, w: [f64; 2], time: f64, crank: f64) -> InverseStep {
    let r = &acc.response;
    let e = norm(acc.eps);
    let attitude = if e > 0.0 && norm(w) > 0.0 {
        let a = acc.eps[1].atan2(acc.eps[0]) - w[1].atan2(w[0]);
        // Wrap to (−π, π].
        let wrapped = a.rem_euclid(std::f64::consts::TAU);
        if wrapped > std::f64::consts::PI {
            wrapped - std::f64::consts::TAU
        } else {
            wrapped
        }
    } else {
        0.0
    };
    InverseStep {
        time,
        crank_angle_deg: crank,
        load: w,
        film_force: r.film_force,
        residual: acc.residual,
        eccentricity_ratio: acc.eps,
        eccentricity: e,
        attitude_angle: attitude,
        min_film_thickness: r.min_film_thickness,
        min_film_location: r.min_film_location,
        max_pressure: r.max_pressure,
        max_pressure_location: r.max_pressure_location,
        cavitated_fraction: r.cavitated_fraction,
        side_leakage: r.side_leakage,
        supply_flow: r.supply_flow.clone(),
        recirculated_flow: r.recirculated_flow,
        power_loss: r.power_loss,
        friction_torque_journal: r.friction_torque_journal,
        friction_torque_bearing: r.friction_torque_bearing,
        newton_iterations: acc.iterations,
        sweep_iterations: r.sweep_iterations,
    }
}

fn summarize(steps: &[InverseStep]) -> CycleSummary {
    let n = steps.len().max(1) as f64;
    let mean = |f: &dyn Fn(&InverseStep) -> f64| steps.iter().map(f).sum::<f64>() / n;
    let argmax =
        |f: &dyn Fn(&InverseStep) -> f64| {
            steps.iter().map(|s| (f(s), s.crank_angle_deg)).fold(
                (f64::NEG_INFINITY, 0.0),
                |a, b| if b.0 > a.0 { b } else { a },
            )
        };
    let (max_e, max_e_at) = argmax(&|s| s.eccentricity);
    let (neg_h, h_at) = argmax(&|s| -s.min_film_thickness);
    let (max_p, p_at) = argmax(&|s| s.max_pressure);
    let groups = steps.first().map_or(0, |s| s.supply_flow.len());
    let mean_supply: Vec<f64> = (0..groups)
        .map(|g| mean(&|s| s.supply_flow.get(g).copied().unwrap_or(0.0)))
        .collect();
    CycleSummary {
        mean_eccentricity: mean(&|s| s.eccentricity),
        max_eccentricity: max_e,
        max_eccentricity_crank_angle_deg: max_e_at,
        min_film_thickness: -neg_h,
        min_film_thickness_crank_angle_deg: h_at,
        max_pressure: max_p,
        max_pressure_crank_angle_deg: p_at,
        mean_cavitated_fraction: mean(&|s| s.cavitated_fraction),
        max_cavitated_fraction: argmax(&|s| s.cavitated_fraction).0,
        mean_side_leakage: [mean(&|s| s.side_leakage[0]), mean(&|s| s.side_leakage[1])],
        mean_total_side_leakage: mean(&|s| s.side_leakage[0] + s.side_leakage[1]),
        max_total_side_leakage: argmax(&|s| s.side_leakage[0] + s.side_leakage[1]).0,
        mean_total_supply_flow: mean_supply.iter().sum(),
        mean_supply_flow: mean_supply,
        mean_power_loss: mean(&|s| s.power_loss),
        max_power_loss: argmax(&|s| s.power_loss).0,
        mean_friction_torque_journal: mean(&|s| s.friction_torque_journal),
        mean_friction_torque_bearing: mean(&|s| s.friction_torque_bearing),
    }
}

/// Load and film conditions at a time, for [`Stepper::advance`].
type Drive<'a> = dyn Fn(f64) -> Result<([f64; 2], OperatingConditions), InverseError> + 'a;

/// What every step of one inverse solve shares: the parameters, the reference load W_ref, the
/// Jacobian carried across steps and the run statistics.
struct Stepper<'p> {
    params: &'p InverseParams,
    w_ref: f64,
    jac: Jacobian,
    stats: Stats,
    /// Steps accepted as stalls since the observer last heard of them.
    stalls: Vec<InverseStall>,
    /// The local error control of the cycle steps (None: off, or a film without a scheme).
    control: Option<ErrorControl>,
}

/// One step to take: from ε at `t_end − dt` to `t_end`, Newton started at `guess`.
#[derive(Clone, Copy)]
struct Leg {
    eps: [f64; 2],
    guess: [f64; 2],
    t_end: f64,
    dt: f64,
    at: Where,
}

/// Where an inverse solve starts or ended ([`solve_inverse_from`]): the journal's position
/// ε at the end of a cycle, its two positions before (for the Newton's first guesses), and
/// the film model's state there.
#[derive(Debug, Clone)]
pub struct InverseStart<S> {
    /// ε at the start (t = 0 of the cycle).
    pub eccentricity_ratio: [f64; 2],
    /// ε one and two steps before.
    pub previous: [[f64; 2]; 2],
    /// The film state at the start.
    pub state: S,
    /// The level of the local error control each step of the cycle took
    /// ([`InverseParams::step_error_tolerance`]; empty: none yet): a solve started here takes
    /// each step with at least as many substeps.
    pub step_levels: Vec<usize>,
}

/// The journal's last three accepted positions (the quadratic predictor's data) and the film
/// state at the last one: what the march carries from step to step, in the run-in and in the
/// cycles alike.
struct Orbit<S> {
    eps: [f64; 2],
    prev: [f64; 2],
    prev2: [f64; 2],
    state: S,
}

/// A step taken by [`Orbit::march_step`].
struct Marched {
    accepted: Accepted<()>,
    /// The step's fields, when asked for.
    fields: Option<FilmFields>,
}

impl<S> Orbit<S> {
    /// The orbit at the start of a solve: where an earlier one ended, else the centre with
    /// the film's initial state there.
    fn starting<F: FilmModel<State = S> + ?Sized>(
        start_from: Option<InverseStart<S>>,
        film: &F,
    ) -> Self {
        match start_from {
            Some(s) => Orbit {
                eps: s.eccentricity_ratio,
                prev: s.previous[0],
                prev2: s.previous[1],
                state: s.state,
            },
            None => Orbit {
                eps: [0.0; 2],
                prev: [0.0; 2],
                prev2: [0.0; 2],
                state: film.initial_state([0.0; 2]),
            },
        }
    }
}

impl<S: Clone> Orbit<S> {
    /// The run-in: from the orbit's start (ε = 0, full film), `grid.run_in` steps ending at
    /// t = 0 under a quasi-load ramped smoothly from 0 to W(0), at the conditions of t = 0.
    /// Errors give the crank angle within the cycle.
    fn run_in<F, L, O>(
        &mut self,
        stepper: &mut Stepper<'_>,
        film: &mut F,
        load: &L,
        grid: &CycleGrid,
        observer: &mut O,
    ) -> Result<(), InverseError>
    where
        F: FilmModel<State = S> + ?Sized,
        L: LoadHistory + ?Sized,
        O: InverseObserver + ?Sized,
    {
        let (run_in, dt) = (grid.run_in, grid.dt);
        if run_in == 0 {
            return Ok(());
        }
        let w0 = load.load(0.0);
        let cond0 = conditions_at(load, 0.0)?;
        // The ramp as a function of time (also at the midpoints of split steps).
        let ramp = |tt: f64| {
            let s = smoothstep(((run_in as f64 + tt / dt) / run_in as f64).clamp(0.0, 1.0));
            Ok(([s * w0[0], s * w0[1]], cond0.clone()))
        };
        for k in 1..=run_in {
            let t = -((run_in - k) as f64) * dt;
            let at = Where {
                time: t,
                crank_angle_deg: load.crank_angle_deg(t).rem_euclid(grid.cycle_deg),
                cycle: 0,
            };
            let step = self.march_step(stepper, film, (t, dt), &ramp, at, false, None)?;
            for stall in stepper.stalls.drain(..) {
                observer.on_stall(&stall);
            }
            observer.on_step(&InverseProgress {
                phase: InversePhase::RunIn,
                step: k,
                steps: run_in,
                max_cycles: stepper.params.max_cycles,
                time: t,
                crank_angle_deg: at.crank_angle_deg,
                eccentricity_ratio: self.eps,
                residual: step.accepted.residual,
                newton_iterations: step.accepted.iterations,
            });
            at.stop_if_requested(observer)?;
        }
        Ok(())
    }

    /// Load cycles 1, 2, … until the periodicity test holds or `max_cycles` is reached.
    fn cycles_until_periodic<F, L, O>(
        &mut self,
        stepper: &mut Stepper<'_>,
        film: &mut F,
        load: &L,
        grid: &CycleGrid,
        observer: &mut O,
    ) -> Result<CyclesOutcome, InverseError>
    where
        F: FilmModel<State = S> + ?Sized,
        L: LoadHistory + ?Sized,
        O: InverseObserver + ?Sized,
    {
        let params = stepper.params;
        let mut outcome = CyclesOutcome {
            records: Vec::new(),
            snapshots: Vec::new(),
            cycles: 0,
            periodic: false,
            eccentricity_change: f64::INFINITY,
            film_state_change: 0.0,
            extrapolations: 0,
        };
        let mut previous: Option<Vec<[f64; 2]>> = None;
        let mut extrapolation = params
            .cycle_extrapolation
            .then(CycleExtrapolation::new)
            .filter(|_| self.vector(film).is_some());
        if let (Some(e), Some(v)) = (extrapolation.as_mut(), self.vector(film)) {
            e.restart(v);
        }
        for cycle in 1..=params.max_cycles {
            outcome.cycles = cycle;
            let state_start = self.state.clone();
            (outcome.records, outcome.snapshots) =
                self.march_cycle(stepper, film, load, grid, cycle, observer)?;
            let current: Vec<[f64; 2]> = outcome
                .records
                .iter()
                .map(|r| r.eccentricity_ratio)
                .collect();
            outcome.eccentricity_change = orbit_change(previous.as_deref(), &current);
            outcome.film_state_change = film.state_change(&state_start, &self.state);
            observer.on_cycle(
                cycle,
                outcome.eccentricity_change,
                outcome.film_state_change,
            );
            previous = Some(current);
            if is_periodic(
                params,
                outcome.eccentricity_change,
                outcome.film_state_change,
            ) {
                outcome.periodic = true;
                break;
            }
            if let Some(e) = extrapolation.as_mut() {
                let jumped = self.vector(film).and_then(|v| {
                    // The two periodicity measures, in units of their tolerances.
                    let changes = [
                        outcome.eccentricity_change / params.periodicity_tolerance,
                        outcome.film_state_change / params.film_state_tolerance,
                    ];
                    let s = e.push(v, changes)?;
                    self.set_vector(film, &s).then_some(s)
                });
                if let Some(s) = jumped {
                    // The next cycle starts elsewhere: it is compared with none.
                    e.restart(s);
                    previous = None;
                    stepper.jac.valid = false;
                    observer.on_extrapolation(cycle);
                }
            }
        }
        outcome.extrapolations = extrapolation.map_or(0, |e| e.count);
        Ok(outcome)
    }

    /// The cycle-start state as a vector ([`super::cycle_map`]): ε^n, ε^{n−1}, ε^{n−2}, then the
    /// film's [`FilmModel::state_vector`].
    fn vector<F: FilmModel<State = S> + ?Sized>(&self, film: &F) -> Option<Vec<f64>> {
        let mut v = vec![
            self.eps[0],
            self.eps[1],
            self.prev[0],
            self.prev[1],
            self.prev2[0],
            self.prev2[1],
        ];
        v.extend(film.state_vector(&self.state)?);
        Some(v)
    }

    /// Move the orbit to the state of `vector` ([`Orbit::vector`]'s layout); false (and the
    /// orbit unchanged) when it is no state: a journal position not inside the clearance, or
    /// one the film refuses.
    fn set_vector<F: FilmModel<State = S> + ?Sized>(&mut self, film: &F, vector: &[f64]) -> bool {
        let [e0, e1, p0, p1, q0, q1] = vector[..6] else {
            return false;
        };
        let (eps, prev, prev2) = ([e0, e1], [p0, p1], [q0, q1]);
        if [eps, prev, prev2]
            .iter()
            .any(|e| norm(*e).is_nan() || norm(*e) >= 1.0)
        {
            return false;
        }
        match film.state_from_vector(&self.state, eps, &vector[6..]) {
            Some(state) => {
                (self.eps, self.prev, self.prev2, self.state) = (eps, prev, prev2, state);
                true
            }
            None => false,
        }
    }

    /// One load cycle: N steps from t_c = (cycle − 1)·τ; their records and (every
    /// `field_stride` steps) field snapshots.
    fn march_cycle<F, L, O>(
        &mut self,
        stepper: &mut Stepper<'_>,
        film: &mut F,
        load: &L,
        grid: &CycleGrid,
        cycle: usize,
        observer: &mut O,
    ) -> Result<(Vec<InverseStep>, Vec<FieldSnapshot>), InverseError>
    where
        F: FilmModel<State = S> + ?Sized,
        L: LoadHistory + ?Sized,
        O: InverseObserver + ?Sized,
    {
        let params = stepper.params;
        let drive = |tt: f64| drive_at(load, tt);
        let mut records = Vec::with_capacity(grid.steps);
        let mut snapshots = Vec::new();
        let t_c = (cycle - 1) as f64 * grid.period;
        for i in 0..grid.steps {
            let tau = (i + 1) as f64 * grid.dt;
            let t = t_c + tau;
            // The histories are periodic: the drive is evaluated at the time within the cycle,
            // so that a step and its substeps see the same load and feed in every cycle to the
            // bit (from the absolute time t_c + τ the crank angle carries the rounding of t_c,
            // and a substep ending where the feed falls to p_cav — the rod's drilling closing
            // at 31° — would find the groove fed in one cycle and starved in the next).
            let (w, _) = drive(tau)?;
            let crank = load.crank_angle_deg(tau);
            let at = Where {
                time: t,
                crank_angle_deg: crank,
                cycle,
            };
            // Steps end at crank angles (i + 1)·Δ: capturing at the ends of strides puts the
            // snapshots at stride·Δ, 2·stride·Δ, …, including the cycle's end (= its start).
            let capture = params.field_stride > 0 && (i + 1) % params.field_stride == 0;
            let step =
                self.march_step(stepper, film, (tau, grid.dt), &drive, at, capture, Some(i))?;
            for stall in stepper.stalls.drain(..) {
                observer.on_stall(&stall);
            }
            if let Some(fields) = step.fields {
                snapshots.push(FieldSnapshot {
                    step_index: i,
                    time: tau,
                    crank_angle_deg: crank,
                    fields,
                });
            }
            records.push(record(&step.accepted, w, tau, crank));
            observer.on_step(&InverseProgress {
                phase: InversePhase::Cycle(cycle),
                step: i + 1,
                steps: grid.steps,
                max_cycles: params.max_cycles,
                time: t,
                crank_angle_deg: crank,
                eccentricity_ratio: self.eps,
                residual: step.accepted.residual,
                newton_iterations: step.accepted.iterations,
            });
            at.stop_if_requested(observer)?;
        }
        Ok((records, snapshots))
    }

    /// One time step of the march (run-in and cycles alike) of length `dt` ending at `t`, the
    /// time `drive` takes (within the cycle for the cycles; `at` names the step in messages):
    /// the quadratic predictor's guess, [`Stepper::advance`] (halving the step where Newton fails) — for
    /// step `cycle_step` of a cycle under the local error control, [`Orbit::controlled_step`] —,
    /// with `capture_fields` the fields of the accepted film (of the last substep of a refined
    /// step: the film the recorded answer ends on; every trial of the step captures them, which
    /// costs array copies, not a film solve), and the orbit moved on.
    #[allow(clippy::too_many_arguments)]
    fn march_step<F: FilmModel<State = S> + ?Sized>(
        &mut self,
        stepper: &mut Stepper<'_>,
        film: &mut F,
        (t, dt): (f64, f64),
        drive: &Drive<'_>,
        at: Where,
        capture_fields: bool,
        cycle_step: Option<usize>,
    ) -> Result<Marched, InverseError> {
        let leg = Leg {
            eps: self.eps,
            guess: predict_quadratic(self.eps, self.prev, self.prev2),
            t_end: t,
            dt,
            at,
        };
        if capture_fields {
            film.set_capture_fields(true);
        }
        let taken = match cycle_step.filter(|_| stepper.control.is_some()) {
            Some(i) => self.controlled_step(stepper, film, leg, drive, i),
            None => stepper.advance(film, &self.state, leg, drive, 0),
        };
        if capture_fields {
            film.set_capture_fields(false);
        }
        let mut acc = taken?;
        let fields = acc.response.fields.take();
        let mut response = acc.response;
        step_flows_from_volumes(
            &mut response,
            film.boundary_volumes(&self.state),
            film.boundary_volumes(&acc.state),
            dt,
        );
        self.prev2 = self.prev;
        self.prev = self.eps;
        self.eps = acc.eps;
        self.state = acc.state;
        Ok(Marched {
            accepted: Accepted {
                eps: acc.eps,
                response,
                state: (),
                residual: acc.residual,
                iterations: acc.iterations,
            },
            fields,
        })
    }
}

impl<S: Clone> Orbit<S> {
    /// Step `i` of a cycle under the local error control ([`super::error_control`]): at the
    /// level the step took before (a full step at level 0), then again in more substeps while
    /// the error estimate asks for them; the level is remembered for the later cycles. A step
    /// whose Newton had to halve a (sub)step ([`Stepper::advance`]) is taken again at one level
    /// more, so that the halving on failure — which may happen in one cycle and not in the
    /// next — does not decide the answer.
    fn controlled_step<F: FilmModel<State = S> + ?Sized>(
        &self,
        stepper: &mut Stepper<'_>,
        film: &mut F,
        leg: Leg,
        drive: &Drive<'_>,
        i: usize,
    ) -> Result<Accepted<S>, InverseError> {
        let history = [self.eps, self.prev, self.prev2];
        let control = stepper.control.as_ref().expect("controlled step");
        let (mut level, max_level) = (control.level(i), control.max_level());
        loop {
            let halvings_before = stepper.stats.halvings;
            let acc = stepper.substeps(film, &self.state, history, leg, drive, level)?;
            let halved = stepper.stats.halvings > halvings_before;
            let control = stepper.control.as_ref().expect("controlled step");
            let estimate = control.estimate(acc.eps, history, level > 0 || halved);
            let mut needed = control.level_for(estimate);
            if halved {
                needed = needed.max((level + 1).min(max_level));
            }
            if needed <= level {
                stepper
                    .control
                    .as_mut()
                    .expect("controlled step")
                    .raise(i, level.max(usize::from(halved)));
                return Ok(acc);
            }
            level = needed;
        }
    }
}

impl Stepper<'_> {
    /// The step `leg` from `state` in 2^`level` equal substeps (level 0: the step itself), each
    /// by [`Stepper::advance`] with the splits left below `max_step_splits`; Newton's guess for
    /// each substep is the quadratic through the last three positions (`history` = ε at the
    /// step's start and the two full steps before). Returns the end with the Newton iterations
    /// of all substeps, the substeps' mean rates ([`step_mean_rates`]) and the film history of
    /// one step from `state` ([`FilmModel::join_substeps`]).
    fn substeps<F: FilmModel + ?Sized>(
        &mut self,
        film: &mut F,
        state: &F::State,
        history: [[f64; 2]; 3],
        leg: Leg,
        drive: &Drive<'_>,
        level: usize,
    ) -> Result<Accepted<F::State>, InverseError> {
        if level == 0 {
            return self.advance(film, state, leg, drive, 0);
        }
        let n = 1usize << level;
        let h = leg.dt / n as f64;
        let t0 = leg.t_end - leg.dt;
        let mut points = vec![
            (t0 - 2.0 * leg.dt, history[2]),
            (t0 - leg.dt, history[1]),
            (t0, history[0]),
        ];
        self.jac.valid = false;
        let mut iterations = 0;
        let mut last: Option<Accepted<F::State>> = None;
        let mut parts = Vec::with_capacity(n);
        for j in 1..=n {
            let t = if j == n { leg.t_end } else { t0 + j as f64 * h };
            let (eps, from) = match &last {
                Some(a) => (a.eps, &a.state),
                None => (leg.eps, state),
            };
            let sub = Leg {
                eps,
                guess: pull_back(eps, extrapolate(&points, t)),
                t_end: t,
                dt: h,
                at: Where {
                    time: leg.at.time - (leg.t_end - t),
                    ..leg.at
                },
            };
            let acc = self.advance(film, from, sub, drive, level)?;
            iterations += acc.iterations;
            points.push((t, acc.eps));
            parts.push((1.0 / n as f64, acc.response.clone()));
            last = Some(acc);
        }
        self.jac.valid = false;
        let mut acc = last.expect("at least two substeps");
        acc.iterations = iterations;
        acc.response = step_mean_rates(&acc.response, &parts);
        film.join_substeps(state, &mut acc.state, leg.dt);
        Ok(acc)
    }

    /// One time step `leg` from `state`. When Newton fails the step is retried as two half
    /// steps (the load and conditions of the midpoint from `drive`, the film state carried
    /// through it), recursively up to [`InverseParams::max_step_splits`] halvings. The Jacobian
    /// is refreshed at every change of step length (the squeeze term scales with 1/dt).
    /// Collapse and film errors are not retried: a smaller step cannot cure them.
    fn advance<F: FilmModel + ?Sized>(
        &mut self,
        film: &mut F,
        state: &F::State,
        leg: Leg,
        drive: &Drive<'_>,
        depth: usize,
    ) -> Result<Accepted<F::State>, InverseError> {
        let (w, cond) = drive(leg.t_end)?;
        let target = Target {
            dt: leg.dt,
            cond: &cond,
            w,
            at: leg.at,
            may_split: depth < self.params.max_step_splits,
            start: leg.eps,
        };
        match self.newton(film, state, leg.guess, target) {
            Err(InverseError::NewtonFailed { .. }) if depth < self.params.max_step_splits => {
                if depth == 0 {
                    self.stats.split += 1;
                }
                self.stats.halvings += 1;
                let Leg {
                    eps, guess, t_end, ..
                } = leg;
                let half = 0.5 * leg.dt;
                let t_mid = t_end - half;
                self.jac.valid = false;
                let mid_guess = predict(eps, [2.0 * eps[0] - guess[0], 2.0 * eps[1] - guess[1]]);
                let first = self.advance(
                    film,
                    state,
                    Leg {
                        eps,
                        guess: [0.5 * (eps[0] + mid_guess[0]), 0.5 * (eps[1] + mid_guess[1])],
                        t_end: t_mid,
                        dt: half,
                        at: Where {
                            time: leg.at.time - half,
                            ..leg.at
                        },
                    },
                    drive,
                    depth + 1,
                )?;
                let mut last = self.advance(
                    film,
                    &first.state,
                    Leg {
                        eps: first.eps,
                        guess: predict(first.eps, eps),
                        t_end,
                        dt: half,
                        at: leg.at,
                    },
                    drive,
                    depth + 1,
                )?;
                self.jac.valid = false;
                last.response = step_mean_rates(
                    &last.response,
                    &[(0.5, first.response), (0.5, last.response.clone())],
                );
                film.join_substeps(state, &mut last.state, leg.dt);
                Ok(last)
            }
            other => other,
        }
    }
    /// Newton on r(ε) = F_film(ε) + W for one step; see the module docs of [`super`]. Each
    /// iteration: the collapse and convergence tests, a Jacobian refresh where it is stale
    /// ([`Stepper::refresh_jacobian`]), the Newton direction, and a backtracking line search
    /// ([`Stepper::line_search`]). Newton that cannot reach `tolerance` (iteration limit, or no
    /// descent on a fresh Jacobian) ends in [`Stepper::give_up`].
    fn newton<F: FilmModel + ?Sized>(
        &mut self,
        film: &mut F,
        state: &F::State,
        guess: [f64; 2],
        target: Target<'_>,
    ) -> Result<Accepted<F::State>, InverseError> {
        let params = self.params;
        let problem = StepProblem {
            state,
            target,
            scale: norm(target.w).max(self.w_ref),
        };
        // Inexact outer Newton (module docs of `super`): a trial needs its film force only to
        // FORCING × the residual it starts from (the guess: × the scale), and an iterate that
        // can be accepted is always a film solved to its own tolerance. A trial from within
        // TIGHT_BELOW × tolerance is likely the answer (a chord step reduces |r| ≥ 4×): solved
        // tightly from the start. Only with the exact Jacobian: difference and secant
        // Jacobians take differences of film forces.
        const FORCING: f64 = 0.1;
        const TIGHT_BELOW: f64 = 10.0;
        let relax = params.jacobian == JacobianMethod::Exact;
        let relaxed = |res: f64| super::RelaxedStep {
            accuracy: FORCING * res,
            load: target.w,
            finish_within: 2.0 * params.tolerance * problem.scale,
        };
        if relax {
            film.relax_next_step(relaxed(1.0));
        }
        let mut cur = problem.evaluate(film, guess, &mut self.stats)?;
        let mut loose = film.last_step_relaxed();
        // Where the film model was last solved (its exact Jacobian is that point's).
        let mut last_solved = guess;
        let mut iterations = 0;
        let mut fresh = false;
        // After a stall on a fresh Jacobian, one retry with a secant over a 100× wider difference
        // step (≥ 1e-3): it averages over the small force jumps of a switching JFO film.
        let mut wide_tried = false;
        // Newton restarted once from the step's start (below), and the iteration count at which
        // it gives up (the restart gets a full count of its own).
        let mut restarted = false;
        let mut limit = params.max_newton_iterations;
        let mut fd_h = params.fd_step;
        // Where Newton from the guess fails — a singular fresh Jacobian, no descent on a fresh
        // one, or the iteration limit — it starts once more from where the step starts (ε of
        // the step's start: no squeeze velocity over the step). The guess is the predictor's
        // extrapolation of the orbit, which near a sharp turn (a load reversal that sends the
        // journal across the clearance) can land in another piece of the piecewise smooth JFO
        // force, where the exact Jacobian of that piece leads Newton to a local minimum of
        // |r| (the Flores feed-hole case at 173.25° of its first cycle: residual 8.8e-2 of
        // the load, no descent, at the deepest split; from the step's start it converges), or
        // into a region the squeeze suction cavitates entirely (F = 0, ∂F/∂ε = 0: the rod
        // bearing at 4° steps). From the start the line search only moves downhill. Before a
        // split: a restart costs a few film solves, a split at least two Newton solves.
        macro_rules! restart_from_start {
            () => {{
                restarted = true;
                limit = iterations + params.max_newton_iterations;
                if relax {
                    film.relax_next_step(relaxed(1.0));
                }
                cur = problem.evaluate(film, target.start, &mut self.stats)?;
                loose = film.last_step_relaxed();
                last_solved = target.start;
                self.jac.valid = false;
                fresh = false;
            }};
        }
        let can_restart =
            |restarted: bool, cur: &Iterate<F::State>| !restarted && cur.eps != target.start;
        loop {
            let converged = cur.res <= params.tolerance;
            if norm(cur.eps) >= params.collapse_eccentricity
                || (converged && cur.response.min_film_thickness < params.min_film_floor)
            {
                return Err(problem.collapse(&cur));
            }
            if loose && (converged || iterations >= limit) {
                // A relaxed film outside the film's finishing band: solve it tightly first.
                cur = problem.evaluate(film, cur.eps, &mut self.stats)?;
                last_solved = cur.eps;
                loose = false;
                continue;
            }
            if converged {
                problem.check_outputs(&cur)?;
                return Ok(self.accept(cur, iterations));
            }
            if iterations >= limit {
                if can_restart(restarted, &cur) {
                    restart_from_start!();
                    continue;
                }
                return self.give_up(&problem, cur, iterations, film);
            }
            iterations += 1;
            if self.refresh_jacobian(film, &problem, &cur, &mut last_solved, &mut fd_h)? {
                fresh = true;
            }
            let Some(delta) = self.newton_direction(&cur) else {
                if fresh && can_restart(restarted, &cur) {
                    // A singular fresh Jacobian: the film force does not move with ε here
                    // (splitting the step would keep the speed and the flat region).
                    restart_from_start!();
                    continue;
                }
                if fresh {
                    return Err(target.at.newton_failed(iterations, &cur));
                }
                self.jac.valid = false;
                continue;
            };
            if relax && cur.res > TIGHT_BELOW * params.tolerance {
                film.relax_next_step(relaxed(cur.res));
            }
            match self.line_search(film, &problem, &cur, delta, fresh, &mut last_solved)? {
                Some(better) => {
                    cur = better;
                    loose = film.last_step_relaxed();
                    fresh = false;
                }
                None if fresh && !wide_tried && params.jacobian != JacobianMethod::Exact => {
                    wide_tried = true;
                    fd_h = (100.0 * params.fd_step).max(1e-3);
                    self.jac.valid = false;
                }
                None if fresh && loose => {
                    // No descent from a relaxed iterate: its force is known only to the
                    // relaxed accuracy, which near the tolerance may be all of its residual.
                    // Solved tightly, it is accepted, or Newton goes on from it (and gives up
                    // only on a tightly solved iterate, see above).
                    cur = problem.evaluate(film, cur.eps, &mut self.stats)?;
                    last_solved = cur.eps;
                    loose = false;
                }
                None if fresh && can_restart(restarted, &cur) => restart_from_start!(),
                None if fresh => return self.give_up(&problem, cur, iterations, film),
                None => self.jac.valid = false,
            }
        }
    }

    /// Refresh ∂F/∂ε at the iterate where the carried Jacobian is stale (at every iteration
    /// for [`JacobianMethod::FiniteDifference`]): the film's exact Jacobian (the film solved at
    /// the iterate first if its last solve was elsewhere), else forward differences of step
    /// `fd_h`, which is then reset to `fd_step`. Returns whether the Jacobian was refreshed.
    fn refresh_jacobian<F: FilmModel + ?Sized>(
        &mut self,
        film: &mut F,
        problem: &StepProblem<'_, F::State>,
        cur: &Iterate<F::State>,
        last_solved: &mut [f64; 2],
        fd_h: &mut f64,
    ) -> Result<bool, InverseError> {
        let params = self.params;
        let exact = match params.jacobian {
            JacobianMethod::Exact if !self.jac.valid => {
                if *last_solved != cur.eps {
                    problem.evaluate(film, cur.eps, &mut self.stats)?;
                    *last_solved = cur.eps;
                }
                film.force_jacobian()
            }
            _ => None,
        };
        if let Some(m) = exact {
            self.stats.jacobians += 1;
            self.jac.m = m.map_err(|source| problem.target.at.film_error(cur.eps, source))?;
            self.jac.valid = true;
            return Ok(true);
        }
        if !self.jac.valid || params.jacobian == JacobianMethod::FiniteDifference {
            let mut residual_at =
                |e: [f64; 2], stats: &mut Stats| problem.evaluate(film, e, stats).map(|it| it.r);
            let (force, w) = (cur.response.film_force, problem.target.w);
            self.jac.m = fd_jacobian(&mut residual_at, cur.eps, force, w, *fd_h, &mut self.stats)?;
            *last_solved = [f64::NAN; 2];
            *fd_h = params.fd_step;
            self.jac.valid = true;
            return Ok(true);
        }
        Ok(false)
    }

    /// The Newton direction Δ from J Δ = −r, shortened to `max_newton_step`; `None` when the
    /// Jacobian is singular or the direction not finite.
    fn newton_direction<S>(&self, cur: &Iterate<S>) -> Option<[f64; 2]> {
        let (m, r) = (self.jac.m, cur.r);
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let delta = [
            (-r[0] * m[1][1] + r[1] * m[0][1]) / det,
            (-r[1] * m[0][0] + r[0] * m[1][0]) / det,
        ];
        if !(det != 0.0 && delta[0].is_finite() && delta[1].is_finite()) {
            return None;
        }
        let dn = norm(delta);
        if dn > self.params.max_newton_step {
            let s = self.params.max_newton_step / dn;
            return Some([delta[0] * s, delta[1] * s]);
        }
        Some(delta)
    }

    /// Backtracking on |r| along `delta`, first shortened to close at most half of the gap to
    /// the wall; up to 8 halvings on a fresh Jacobian, none on a carried one (which is refreshed
    /// instead). On descent the Jacobian is updated: Broyden's update, or for the exact
    /// Jacobian marked stale when the residual fell by less than 4× or more than
    /// [`CHORD_STEPS_WORTH_A_REFRESH`] chord steps at this rate are still ahead (chord steps
    /// otherwise).
    fn line_search<F: FilmModel + ?Sized>(
        &mut self,
        film: &mut F,
        problem: &StepProblem<'_, F::State>,
        cur: &Iterate<F::State>,
        delta: [f64; 2],
        fresh: bool,
        last_solved: &mut [f64; 2],
    ) -> Result<Option<Iterate<F::State>>, InverseError> {
        let eps = cur.eps;
        let along = |lambda: f64| [eps[0] + lambda * delta[0], eps[1] + lambda * delta[1]];
        let e = norm(eps);
        let limit = e + 0.5 * (1.0 - e);
        let mut lambda = 1.0;
        while norm(along(lambda)) > limit {
            lambda *= 0.5;
        }
        for _ in 0..8 {
            let trial = problem.evaluate(film, along(lambda), &mut self.stats)?;
            *last_solved = trial.eps;
            if trial.res < cur.res {
                let s = [trial.eps[0] - eps[0], trial.eps[1] - eps[1]];
                match self.params.jacobian {
                    JacobianMethod::Broyden => {
                        let y = [trial.r[0] - cur.r[0], trial.r[1] - cur.r[1]];
                        broyden(&mut self.jac.m, s, y);
                    }
                    JacobianMethod::Exact
                        if trial.res > 0.25 * cur.res
                            || chord_steps_left(trial.res, cur.res, self.params.tolerance)
                                > CHORD_STEPS_WORTH_A_REFRESH =>
                    {
                        self.jac.valid = false
                    }
                    _ => {}
                }
                return Ok(Some(trial));
            }
            if !fresh {
                break;
            }
            lambda *= 0.5;
        }
        Ok(None)
    }

    /// A converged iterate, counted.
    fn accept<S>(&mut self, cur: Iterate<S>, iterations: usize) -> Accepted<S> {
        self.stats.newton += iterations;
        self.stats.max_newton = self.stats.max_newton.max(iterations);
        cur.accepted(iterations)
    }

    /// Newton could not reach `tolerance`: the step fails if it can still be split
    /// ([`Target::may_split`]: two half steps come before a stall) or its residual exceeds
    /// `accept_tolerance`; else the best point is accepted as a stall. (|ε| below the collapse
    /// limit was checked at the top of the iteration that produced it.) A stall is kept for the
    /// observer ([`InverseObserver::on_stall`]) with the film's diagnostics of its last step.
    fn give_up<F: FilmModel + ?Sized>(
        &mut self,
        problem: &StepProblem<'_, F::State>,
        cur: Iterate<F::State>,
        iterations: usize,
        film: &F,
    ) -> Result<Accepted<F::State>, InverseError> {
        let params = self.params;
        self.stats.newton += iterations;
        if problem.target.may_split || cur.res > params.accept_tolerance {
            return Err(problem.target.at.newton_failed(iterations, &cur));
        }
        problem.check_outputs(&cur)?;
        self.stats.stalled += 1;
        self.stats.max_stalled = self.stats.max_stalled.max(cur.res);
        self.stats.max_newton = self.stats.max_newton.max(iterations);
        if cur.response.min_film_thickness < params.min_film_floor {
            return Err(problem.collapse(&cur));
        }
        let at = problem.target.at;
        self.stalls.push(InverseStall {
            time: at.time,
            crank_angle_deg: at.crank_angle_deg,
            cycle: at.cycle,
            dt: problem.target.dt,
            residual: cur.res,
            tolerance: params.tolerance,
            scale: problem.scale,
            newton_iterations: iterations,
            eccentricity_ratio: cur.eps,
            film: film.step_diagnostics(),
        });
        Ok(cur.accepted(iterations))
    }
}

/// What one Newton solve aims at: the step length, the conditions and load at its end, and
/// where it is (for errors).
#[derive(Clone, Copy)]
struct Target<'c> {
    dt: f64,
    cond: &'c OperatingConditions,
    w: [f64; 2],
    at: Where,
    /// A failed Newton is retried as two half steps ([`Stepper::advance`]): a stall is then
    /// not accepted but reported as [`InverseError::NewtonFailed`], so that splitting comes
    /// first and the stall is the last resort, at the deepest split.
    may_split: bool,
    /// ε at the start of the step: Newton's second start where the fresh Jacobian at an
    /// iterate is singular ([`Stepper::newton`]).
    start: [f64; 2],
}

/// What stays fixed during one step's Newton: the film state the step starts from, its
/// target and the residual scale max(|W|, W_ref).
struct StepProblem<'a, S> {
    state: &'a S,
    target: Target<'a>,
    scale: f64,
}

/// One Newton iterate: ε, the film's response and state there, the residual r = F_film + W
/// and its scaled norm |r| / scale.
struct Iterate<S> {
    eps: [f64; 2],
    response: FilmResponse,
    state: S,
    r: [f64; 2],
    res: f64,
}

impl<S> Iterate<S> {
    /// The iterate as the step's answer.
    fn accepted(self, iterations: usize) -> Accepted<S> {
        Accepted {
            eps: self.eps,
            response: self.response,
            state: self.state,
            residual: self.res,
            iterations,
        }
    }
}

impl<S> StepProblem<'_, S> {
    /// Solve the film at `eps` and form the residual; a non-finite film force is an error
    /// naming the trial.
    fn evaluate<F: FilmModel<State = S> + ?Sized>(
        &self,
        film: &mut F,
        eps: [f64; 2],
        stats: &mut Stats,
    ) -> Result<Iterate<S>, InverseError> {
        let Target {
            dt, cond, w, at, ..
        } = self.target;
        stats.evaluations += 1;
        let (response, state) = film
            .step(self.state, eps, dt, cond)
            .map_err(|source| at.film_error(eps, source))?;
        stats.sweeps += response.sweep_iterations;
        let r = [response.film_force[0] + w[0], response.film_force[1] + w[1]];
        if !(r[0].is_finite() && r[1].is_finite()) {
            let source = FilmModelError::NonFinite {
                quantity: "film force",
            };
            return Err(at.film_error(eps, source));
        }
        Ok(Iterate {
            eps,
            response,
            state,
            r,
            res: norm(r) / self.scale,
        })
    }

    /// An iterate about to be accepted has finite friction outputs: a film model's relaxed
    /// trial leaves them out (NaN, [`super::ReynoldsFilm`]) and is never accepted — this
    /// says so, naming the step, should that ever break.
    fn check_outputs(&self, cur: &Iterate<S>) -> Result<(), InverseError> {
        let r = &cur.response;
        for (quantity, v) in [
            ("power loss", r.power_loss),
            ("journal friction torque", r.friction_torque_journal),
            ("bearing friction torque", r.friction_torque_bearing),
        ] {
            if !v.is_finite() {
                let source = FilmModelError::NonFinite { quantity };
                return Err(self.target.at.film_error(cur.eps, source));
            }
        }
        Ok(())
    }

    /// The film cannot carry the load at this iterate.
    fn collapse(&self, cur: &Iterate<S>) -> InverseError {
        let at = self.target.at;
        InverseError::Collapse {
            time: at.time,
            crank_angle_deg: at.crank_angle_deg,
            cycle: at.cycle,
            eccentricity_ratio: cur.eps,
            eccentricity: norm(cur.eps),
            min_film_thickness: cur.response.min_film_thickness,
            residual: cur.res,
        }
    }
}

/// The residual r(ε) at a trial, for [`fd_jacobian`].
type ResidualAt<'a> = dyn FnMut([f64; 2], &mut Stats) -> Result<[f64; 2], InverseError> + 'a;

/// Forward-difference ∂F/∂ε at ε (column k from a step h along ε_k, taken inwards when the
/// forward point would leave the clearance).
fn fd_jacobian(
    residual_at: &mut ResidualAt<'_>,
    eps: [f64; 2],
    force: [f64; 2],
    w: [f64; 2],
    h: f64,
    stats: &mut Stats,
) -> Result<[[f64; 2]; 2], InverseError> {
    stats.jacobians += 1;
    let mut m = [[0.0; 2]; 2];
    for k in 0..2 {
        let mut p = eps;
        p[k] += h;
        let mut hk = h;
        if norm(p) >= 1.0 {
            p[k] = eps[k] - h;
            hk = -h;
        }
        let r = residual_at(p, stats)?;
        for i in 0..2 {
            m[i][k] = (r[i] - w[i] - force[i]) / hk;
        }
    }
    Ok(m)
}

/// Broyden's good update J ← J + (y − J s) sᵀ / (sᵀ s).
fn broyden(m: &mut [[f64; 2]; 2], s: [f64; 2], y: [f64; 2]) {
    let ss = s[0] * s[0] + s[1] * s[1];
    if ss == 0.0 {
        return;
    }
    for i in 0..2 {
        let js = m[i][0] * s[0] + m[i][1] * s[1];
        let d = (y[i] - js) / ss;
        m[i][0] += d * s[0];
        m[i][1] += d * s[1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::{ConstantLoad, FnLoad, OperatingHistory};
    use std::f64::consts::TAU;

    /// Linear convergence at rate q from r reaches tol after log(r/tol)/log(1/q) more steps:
    /// 1e-2 at rate 0.1 needs 4 more to 1e-6 (refresh), at rate 1e-3 four thirds (keep);
    /// at or below the tolerance none; no descent, never.
    #[test]
    fn chord_steps_left_is_the_linear_convergence_count() {
        assert!((chord_steps_left(1e-2, 1e-1, 1e-6) - 4.0).abs() < 1e-12);
        assert!((chord_steps_left(1e-2, 10.0, 1e-6) - 4.0 / 3.0).abs() < 1e-12);
        assert!(chord_steps_left(1e-2, 1e-1, 1e-6) > CHORD_STEPS_WORTH_A_REFRESH);
        assert!(chord_steps_left(1e-2, 10.0, 1e-6) <= CHORD_STEPS_WORTH_A_REFRESH);
        assert_eq!(chord_steps_left(1e-6, 1e-1, 1e-6), 0.0);
        assert_eq!(chord_steps_left(1e-2, 1e-2, 1e-6), f64::INFINITY);
    }

    /// What the toy films below return: the force, h_min = 1 − |ε| (clearance units), unit
    /// power loss.
    fn toy_response(film_force: [f64; 2], e: [f64; 2]) -> FilmResponse {
        FilmResponse {
            film_force,
            min_film_thickness: 1.0 - norm(e),
            power_loss: 1.0,
            // A stand-in that differs from iterate to iterate (the error of a failed step must
            // report its last iterate's).
            cavitated_fraction: norm(e).min(1.0),
            ..Default::default()
        }
    }

    /// A linear spring–damper film: F = −k ε − d ε̇ (backward Euler velocity), optionally
    /// saturating or poisoned with NaN.
    #[derive(Clone)]
    struct Spring {
        k: f64,
        d: f64,
        nan_beyond: f64,
    }

    impl FilmModel for Spring {
        type State = [f64; 2];
        fn initial_state(&self, e: [f64; 2]) -> [f64; 2] {
            e
        }
        fn step(
            &mut self,
            s: &[f64; 2],
            e: [f64; 2],
            dt: f64,
            _c: &OperatingConditions,
        ) -> Result<(FilmResponse, [f64; 2]), FilmModelError> {
            let mut f = [0.0; 2];
            for i in 0..2 {
                f[i] = -self.k * e[i] - self.d * (e[i] - s[i]) / dt;
            }
            if norm(e) > self.nan_beyond {
                f[0] = f64::NAN;
            }
            Ok((toy_response(f, e), e))
        }
    }

    /// A film whose responses lack their friction outputs (as a relaxed trial of the Reynolds
    /// film does): accepting one is an error naming the quantity, never a NaN in the results.
    #[test]
    fn an_accepted_response_without_friction_outputs_is_an_error() {
        struct NoFriction(Spring);
        impl FilmModel for NoFriction {
            type State = [f64; 2];
            fn initial_state(&self, e: [f64; 2]) -> [f64; 2] {
                e
            }
            fn step(
                &mut self,
                s: &[f64; 2],
                e: [f64; 2],
                dt: f64,
                c: &OperatingConditions,
            ) -> Result<(FilmResponse, [f64; 2]), FilmModelError> {
                let (mut r, next) = self.0.step(s, e, dt, c)?;
                r.power_loss = f64::NAN;
                Ok((r, next))
            }
        }
        let mut film = NoFriction(Spring {
            k: 100.0,
            d: 0.0,
            nan_beyond: 2.0,
        });
        let err = solve_inverse(
            &InverseParams::default(),
            &history([50.0, 0.0]),
            &mut film,
            &mut NoObserver,
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                InverseError::Film {
                    source: FilmModelError::NonFinite {
                        quantity: "power loss"
                    },
                    ..
                }
            ),
            "{err:?}"
        );
    }

    fn history(w: [f64; 2]) -> OperatingHistory<ConstantLoad> {
        OperatingHistory {
            load: ConstantLoad {
                load: w,
                period: 1.0,
            },
            journal_speed: 1.0,
            bearing_speed: 0.0,
            feed_pressures: vec![],
        }
    }

    struct Count(usize, usize);
    impl InverseObserver for Count {
        fn on_step(&mut self, p: &InverseProgress) {
            assert!(p.residual.is_finite());
            self.0 += 1;
        }
        fn on_cycle(&mut self, _c: usize, _e: f64, _f: f64) {
            self.1 += 1;
        }
    }

    #[test]
    fn spring_equilibrium_by_both_jacobians() {
        for jacobian in [JacobianMethod::FiniteDifference, JacobianMethod::Broyden] {
            let mut film = Spring {
                k: 100.0,
                d: 0.1,
                nan_beyond: 2.0,
            };
            let params = InverseParams {
                jacobian,
                step_deg: 10.0,
                tolerance: 1e-10,
                periodicity_tolerance: 1e-9,
                ..Default::default()
            };
            let mut obs = Count(0, 0);
            let sol = solve_inverse(&params, &history([30.0, -40.0]), &mut film, &mut obs).unwrap();
            // F + W = 0 ⇔ ε = W/k = (0.3, −0.4) at rest; residual tolerance 1e-10.
            let e = sol.steps.last().unwrap().eccentricity_ratio;
            assert!(
                (e[0] - 0.3).abs() < 1e-9 && (e[1] + 0.4).abs() < 1e-9,
                "{e:?}"
            );
            assert!(sol.info.periodic);
            assert_eq!(obs.0, sol.info.run_in_steps + 36 * sol.info.cycles);
            assert_eq!(obs.1, sol.info.cycles);
            assert_eq!(sol.steps.len(), 36);
            assert!((sol.steps[35].crank_angle_deg - 360.0).abs() < 1e-9);
        }
    }

    /// Asks to stop after `after` steps.
    struct StopAfter {
        after: usize,
        seen: usize,
    }
    impl InverseObserver for StopAfter {
        fn on_step(&mut self, _p: &InverseProgress) {
            self.seen += 1;
        }
        fn stop_requested(&mut self) -> bool {
            self.seen >= self.after
        }
    }

    #[test]
    fn a_stop_request_ends_the_solve_after_that_step_naming_it() {
        let mut film = Spring {
            k: 100.0,
            d: 0.1,
            nan_beyond: 2.0,
        };
        let params = InverseParams {
            step_deg: 10.0,
            run_in_steps: 8,
            ..Default::default()
        };
        // In the run-in (step 5 of 8 ends 3 steps of 10° before the first cycle) …
        let mut obs = StopAfter { after: 5, seen: 0 };
        let err = solve_inverse(&params, &history([30.0, -40.0]), &mut film, &mut obs);
        match err {
            Err(InverseError::Interrupted {
                cycle,
                crank_angle_deg,
                ..
            }) => {
                assert_eq!(cycle, 0);
                assert!((crank_angle_deg - 330.0).abs() < 1e-9, "{crank_angle_deg}");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(obs.seen, 5, "no step after the request");
        // … and in a cycle: step 4 of cycle 2 ends at 40° of it.
        let mut obs = StopAfter {
            after: 8 + 36 + 4,
            seen: 0,
        };
        match solve_inverse(&params, &history([30.0, -40.0]), &mut film, &mut obs) {
            Err(InverseError::Interrupted {
                cycle,
                crank_angle_deg,
                time,
            }) => {
                assert_eq!(cycle, 2);
                assert!((crank_angle_deg - 40.0).abs() < 1e-9, "{crank_angle_deg}");
                assert!((time - (1.0 + 4.0 / 36.0)).abs() < 1e-12, "{time}");
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_load_beyond_the_film_is_collapse_with_numbers() {
        // The spring carries at most k·1 = 100 N; 150 N pushes the journal to the wall.
        let mut film = Spring {
            k: 100.0,
            d: 0.0,
            nan_beyond: 2.0,
        };
        let err = solve_inverse(
            &InverseParams::default(),
            &history([150.0, 0.0]),
            &mut film,
            &mut NoObserver,
        )
        .unwrap_err();
        match err {
            InverseError::Collapse {
                eccentricity,
                residual,
                time,
                ..
            } => {
                assert!((0.999..1.0).contains(&eccentricity));
                assert!(residual.is_finite() && time.is_finite());
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_nan_film_force_is_an_error_naming_the_trial() {
        let mut film = Spring {
            k: 100.0,
            d: 0.0,
            nan_beyond: 0.2,
        };
        let err = solve_inverse(
            &InverseParams::default(),
            &history([50.0, 0.0]),
            &mut film,
            &mut NoObserver,
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                InverseError::Film {
                    source: FilmModelError::NonFinite { .. },
                    ..
                }
            ),
            "{err:?}"
        );
    }

    #[test]
    fn cycle_limit_gives_a_warning_not_an_error() {
        // A spring with a long time constant (d/k = 10 periods) cannot settle in 2 cycles.
        let mut film = Spring {
            k: 100.0,
            d: 1000.0,
            nan_beyond: 2.0,
        };
        let load = OperatingHistory {
            load: FnLoad {
                period: 1.0,
                load: |t: f64| [30.0 * (TAU * t).cos(), 0.0],
            },
            journal_speed: 1.0,
            bearing_speed: 0.0,
            feed_pressures: vec![],
        };
        let params = InverseParams {
            max_cycles: 2,
            step_deg: 10.0,
            tolerance: 1e-10,
            periodicity_tolerance: 1e-8,
            ..Default::default()
        };
        let sol = solve_inverse(&params, &load, &mut film, &mut NoObserver).unwrap();
        assert!(!sol.info.periodic);
        assert!(matches!(
            sol.info.warning,
            Some(InverseWarning::NotPeriodic { cycles: 2, .. })
        ));
        assert!((sol.summary.mean_power_loss - 1.0).abs() < 1e-12);
    }

    /// A toy film given by its force law F(ε_old, ε, Δt), whose state is ε itself: the films
    /// of the step tests below.
    struct ToyFilm<L>(L);

    impl<L: FnMut(&[f64; 2], [f64; 2], f64) -> [f64; 2]> FilmModel for ToyFilm<L> {
        type State = [f64; 2];
        fn initial_state(&self, e: [f64; 2]) -> [f64; 2] {
            e
        }
        fn step(
            &mut self,
            s: &[f64; 2],
            e: [f64; 2],
            dt: f64,
            _c: &OperatingConditions,
        ) -> Result<(FilmResponse, [f64; 2]), FilmModelError> {
            Ok((toy_response((self.0)(s, e, dt), e), e))
        }
    }

    /// The force law of a [`ToyFilm`].
    trait ForceLaw: FnMut(&[f64; 2], [f64; 2], f64) -> [f64; 2] {}
    impl<L: FnMut(&[f64; 2], [f64; 2], f64) -> [f64; 2]> ForceLaw for L {}

    /// A film that can only move a short way in one step: beyond |ε − ε_old| = `reach` it
    /// pushes back with a force larger than any load, so a step whose equilibrium lies further
    /// has no root at all (a stand-in for a JFO film whose cavity collapses within a step).
    fn short_reach(k: f64, reach: f64) -> ToyFilm<impl ForceLaw> {
        ToyFilm(move |s: &[f64; 2], e: [f64; 2], _dt: f64| {
            let d = [e[0] - s[0], e[1] - s[1]];
            let mut f = [-k * e[0], -k * e[1]];
            if norm(d) > reach {
                let g = 10.0 * k / norm(d);
                f = [f[0] - g * d[0], f[1] - g * d[1]];
            }
            f
        })
    }

    type SineLoad = OperatingHistory<FnLoad<fn(f64) -> [f64; 2]>>;

    /// W(t) = (−60 sin 2πt, 0) N, period 1 s, unit journal speed: the load of the toy films'
    /// step tests below (their equilibria swing through ±0.6 of the clearance at k = 100).
    fn sine_load() -> SineLoad {
        OperatingHistory {
            load: FnLoad {
                period: 1.0,
                load: |t: f64| [-60.0 * (TAU * t).sin(), 0.0],
            },
            journal_speed: 1.0,
            bearing_speed: 0.0,
            feed_pressures: vec![],
        }
    }

    /// A stiffening spring, F = −k (1 + b |ε|²) ε: no damping, so each step is the static
    /// root of k (1 + b |ε|²) ε = W(t), which Newton reaches quadratically from the predictor.
    fn stiffening(k: f64, b: f64) -> ToyFilm<impl ForceLaw> {
        ToyFilm(move |_s: &[f64; 2], e: [f64; 2], _dt: f64| {
            let g = -k * (1.0 + b * (e[0] * e[0] + e[1] * e[1]));
            [g * e[0], g * e[1]]
        })
    }

    #[test]
    fn a_stalling_step_is_split_before_a_stall_is_accepted() {
        // Three Newton iterations per step: from the predictor of a 45° step the residual stays
        // above the 1e-10 tolerance (below the 1e-2 accept_tolerance), from the closer
        // predictor of a split step it does not. A stall is the last resort: with splitting
        // available none is accepted; with splitting off the same steps are stalls, reported.
        let load = sine_load();
        let params = InverseParams {
            step_deg: 45.0,
            tolerance: 1e-10,
            jacobian: JacobianMethod::FiniteDifference,
            max_newton_iterations: 3,
            max_cycles: 2,
            ..Default::default()
        };
        let (k, b) = (100.0, 2.0);
        let sol = solve_inverse(&params, &load, &mut stiffening(k, b), &mut NoObserver).unwrap();
        assert_eq!(sol.info.stalled_steps, 0);
        assert!(sol.info.split_steps > 0);
        for st in &sol.steps {
            let e = st.eccentricity_ratio[0];
            let want = -0.6 * (TAU * st.time).sin();
            assert!((e * (1.0 + b * e * e) - want).abs() < 1e-9, "{st:?}");
        }
        let unsplit = InverseParams {
            max_step_splits: 0,
            ..params
        };
        let sol = solve_inverse(&unsplit, &load, &mut stiffening(k, b), &mut NoObserver).unwrap();
        assert!(sol.info.stalled_steps > 0);
        assert!(sol.info.max_stalled_residual <= unsplit.accept_tolerance);
    }

    /// A spring–damper film (F = −k ε − d ε̇, backward Euler) that carries nothing above the
    /// speed `v_max` (F = 0 and ∂F/∂ε = 0 there): the stand-in for a JFO film whose whole
    /// film the squeeze suction of a journal leaving the wall fast cavitates.
    fn flat_when_fast(k: f64, d: f64, v_max: f64) -> ToyFilm<impl ForceLaw> {
        ToyFilm(move |s: &[f64; 2], e: [f64; 2], dt: f64| {
            let v = [(e[0] - s[0]) / dt, (e[1] - s[1]) / dt];
            if norm(v) > v_max {
                [0.0; 2]
            } else {
                [-k * e[0] - d * v[0], -k * e[1] - d * v[1]]
            }
        })
    }

    #[test]
    fn a_guess_where_the_film_carries_nothing_restarts_from_the_step_start() {
        // 45° steps: the predictor's guess overshoots the orbit's speed (≤ 3.2 per unit time
        // here) near its turning points, into the region above v_max = 3.5 where the film
        // force and its Jacobian vanish. Without splits, Newton must restart from the step's
        // start ε (zero speed) and reach the root there.
        let load = sine_load();
        let params = InverseParams {
            step_deg: 45.0,
            tolerance: 1e-10,
            jacobian: JacobianMethod::FiniteDifference,
            max_step_splits: 0,
            max_cycles: 2,
            ..Default::default()
        };
        let (k, d) = (100.0, 10.0);
        let mut film = flat_when_fast(k, d, 3.5);
        let sol = solve_inverse(&params, &load, &mut film, &mut NoObserver).unwrap();
        assert_eq!(sol.info.stalled_steps, 0);
        let dt = 1.0 / 8.0;
        for pair in sol.steps.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            let e = b.eccentricity_ratio[0];
            let v = (e - a.eccentricity_ratio[0]) / dt;
            let want = -60.0 * (TAU * b.time).sin();
            assert!(v.abs() <= 3.5, "{b:?}");
            assert!((k * e + d * v - want).abs() < 1e-7, "{b:?}");
        }
    }

    /// A static snap-through spring along x, F_x = −k a (u³ − 2u) with u = ε_x / a (and
    /// F_y = −k ε_y): under the load W = (−2 k a, 0) the residual is −k a (u³ − 2u + 2), whose
    /// one root is u ≈ −1.769 and whose |r| has a local minimum of 0.911 k a at u = √(2/3) —
    /// Newton's classic trap, the stand-in for a JFO force whose extrapolated guess lies in
    /// another piece of the force.
    fn snap_through(k: f64, a: f64) -> ToyFilm<impl ForceLaw> {
        ToyFilm(move |_s: &[f64; 2], e: [f64; 2], _dt: f64| {
            let u = e[0] / a;
            [-k * a * (u * u * u - 2.0 * u), -k * e[1]]
        })
    }

    #[test]
    fn a_guess_in_a_local_minimum_of_the_residual_restarts_from_the_step_start() {
        // From the guess u = 1.5 Newton descends towards the local minimum of |r| at u = 0.816
        // (residual 0.46 of the load, far above the 1e-2 a stall may have) and, without a split
        // left, would fail (measured on the code before the restart: NewtonFailed); from the
        // step's start u = −1.5 it converges to the root.
        let (k, a) = (100.0, 0.4);
        let params = InverseParams {
            tolerance: 1e-10,
            jacobian: JacobianMethod::FiniteDifference,
            max_step_splits: 0,
            ..Default::default()
        };
        let mut stepper = Stepper {
            params: &params,
            w_ref: 1.0,
            jac: Jacobian {
                m: [[0.0; 2]; 2],
                valid: false,
            },
            stats: Stats::default(),
            stalls: Vec::new(),
            control: None,
        };
        let cond = OperatingConditions {
            journal_speed: 1.0,
            bearing_speed: 0.0,
            feed_pressures: vec![],
        };
        let start = [-1.5 * a, 0.0];
        let target = Target {
            dt: 0.01,
            cond: &cond,
            w: [-2.0 * k * a, 0.0],
            at: Where {
                time: 0.01,
                crank_angle_deg: 3.6,
                cycle: 1,
            },
            may_split: false,
            start,
        };
        let mut film = snap_through(k, a);
        let acc = stepper
            .newton(&mut film, &start, [1.5 * a, 0.0], target)
            .expect("restarted from the step's start");
        let u = acc.eps[0] / a;
        assert!((u * u * u - 2.0 * u + 2.0).abs() < 1e-9, "u = {u}");
        assert!(u < -1.7, "the root, not the local minimum: u = {u}");
        assert_eq!(stepper.stats.stalled, 0);
    }

    #[test]
    fn a_step_newton_cannot_take_is_split_until_it_can() {
        // Equilibrium ε = W/k = (−0.6 sin 2πt, 0): 8 steps per cycle move it by up to 0.42, the
        // film reaches 0.2 per step: halves (0.21) still fail somewhere, quarters (0.11) pass.
        let load = sine_load();
        let params = InverseParams {
            step_deg: 45.0,
            tolerance: 1e-10,
            jacobian: JacobianMethod::FiniteDifference,
            max_cycles: 2,
            ..Default::default()
        };
        let mut film = short_reach(100.0, 0.2);
        let sol = solve_inverse(&params, &load, &mut film, &mut NoObserver).unwrap();
        assert!(sol.info.split_steps > 0);
        for st in &sol.steps {
            let want = -0.6 * (TAU * st.time).sin();
            assert!((st.eccentricity_ratio[0] - want).abs() < 1e-9, "{st:?}");
        }
        // Without splitting the same run is a Newton failure naming the step, not NaN.
        let strict = InverseParams {
            max_step_splits: 0,
            ..params
        };
        let mut film = short_reach(100.0, 0.2);
        let err = solve_inverse(&strict, &load, &mut film, &mut NoObserver).unwrap_err();
        let InverseError::NewtonFailed {
            eccentricity_ratio,
            cavitated_fraction,
            ..
        } = err
        else {
            panic!("not a Newton failure: {err}");
        };
        // The film's state where Newton stopped, for the diagnosis (a starved film: methods.md).
        assert_eq!(
            cavitated_fraction,
            norm(eccentricity_ratio).min(1.0),
            "{err}"
        );
        assert!(err.to_string().contains(&format!(
            "where {:.1} % of the film area is cavitated",
            100.0 * cavitated_fraction
        )));
    }
}
