//! Orbit of the journal by the mobility method, integrated to a periodic cycle.
//!
//! The state is the eccentricity ratio vector ε = e/c in the bearing frame; the ODE is
//! (\[Flores2006\] eqs. 23–24 in vector form, see [`super`])
//!
//! ```text
//!   dε/dt = |W(t)| (c/R)² / (μ L D) · R(Ŵ) M(ζ, κ) + ω̄ ẑ × ε,     ζ = ε·Ŵ, κ = ε·(ẑ × Ŵ)
//! ```
//!
//! with R(Ŵ) the rotation from the load frame to the bearing frame. It is integrated with the
//! adaptive Dormand–Prince 5(4) pair of the `differential-equations` crate (error-controlled
//! steps, dense output for the samples), not with a fixed-step Euler loop (\[Flores2006\] §4.2 notes
//! most authors used Euler). Steps are capped at one sample interval τ/N so that the dense
//! output between steps (not error-controlled itself) stays at the integrator's accuracy.
//!
//! Cycle by cycle, τ the load period:
//!
//! ```text
//!   cycle k: t ∈ [kτ, (k+1)τ], outputs at t = kτ + iτ/N, i = 0 … N
//!   change_k = max_i |ε_k(i) − ε_{k−1}(i)|        stop when change_k < periodicity_tolerance
//! ```
//!
//! The last cycle is reported, with times measured from its start (so crank angles follow the
//! load's own convention). The film collapses when |ε| reaches `eccentricity_limit` (< 1): an
//! event of the integrator stops the run and [`MobilityError::FilmCollapse`] names the time,
//! crank angle and cycle. A model whose range ends below that limit (a tabulated map) stops the
//! orbit at its edge instead, reported as [`MobilityError::OutsideModelRange`]: the film has not
//! collapsed there, the model just cannot follow it further. Within a trial Runge–Kutta stage
//! beyond the model's range the mobility is evaluated at the radially clamped position; such
//! stages never reach the output because the limit event ends the run first.

use super::performance::{performance_at, squeeze_rate};
use super::{MobilityError, MobilityModel, MobilityParams, PerformancePoint, PeriodicLoad};
use differential_equations::prelude::{
    CrossingDirection, Event, EventConfig, ExplicitRungeKutta, IVP, ODE, Solution, Status,
};

/// Settings of an orbit computation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitParams {
    /// The bearing.
    pub bearing: MobilityParams,
    /// ε at t = 0 (bearing frame).
    pub initial_eccentricity: [f64; 2],
    /// Output samples per cycle N (the reported cycle has N + 1 points, both ends included).
    pub samples_per_cycle: usize,
    /// Relative tolerance of the adaptive integrator.
    pub relative_tolerance: f64,
    /// Absolute tolerance of the adaptive integrator (ε is O(1)).
    pub absolute_tolerance: f64,
    /// Periodicity: max_t |ε(t) − ε(t − τ)| below this ends the run. `f64::INFINITY` switches
    /// the check off: exactly `max_cycles` cycles are integrated and the last one is reported
    /// (a fixed-length run, e.g. the paper's single simulated cycle, or a benchmark).
    pub periodicity_tolerance: f64,
    /// At most this many cycles (≥ 2 with a periodicity check, ≥ 1 without).
    pub max_cycles: usize,
    /// Film collapse threshold on |ε| (< 1).
    pub eccentricity_limit: f64,
}

impl OrbitParams {
    /// Defaults: start at ε = 0, 720 samples per cycle, rtol 1e-9, atol 1e-11, periodicity
    /// 1e-6 (the cycle-to-cycle noise floor of the integration at these tolerances is ~1e-7),
    /// at most 100 cycles, collapse at |ε| = 0.9995.
    pub fn new(bearing: MobilityParams) -> Self {
        Self {
            bearing,
            initial_eccentricity: [0.0, 0.0],
            samples_per_cycle: 720,
            relative_tolerance: 1e-9,
            absolute_tolerance: 1e-11,
            periodicity_tolerance: 1e-6,
            max_cycles: 100,
            eccentricity_limit: 0.9995,
        }
    }

    fn validate(&self) -> Result<(), MobilityError> {
        self.bearing.validate()?;
        let bad = |name: &'static str, value: f64| MobilityError::InvalidParameter { name, value };
        let e0 = self.initial_eccentricity[0].hypot(self.initial_eccentricity[1]);
        if !(e0.is_finite() && e0 < self.eccentricity_limit) {
            return Err(bad("initial_eccentricity |ε|", e0));
        }
        if self.samples_per_cycle < 4 {
            return Err(bad("samples_per_cycle", self.samples_per_cycle as f64));
        }
        for (n, v) in [
            ("relative_tolerance", self.relative_tolerance),
            ("absolute_tolerance", self.absolute_tolerance),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(n, v));
            }
        }
        let fixed_length = self.periodicity_tolerance == f64::INFINITY;
        if self.periodicity_tolerance.is_nan() || self.periodicity_tolerance <= 0.0 {
            return Err(bad("periodicity_tolerance", self.periodicity_tolerance));
        }
        if self.max_cycles < if fixed_length { 1 } else { 2 } {
            return Err(bad("max_cycles", self.max_cycles as f64));
        }
        if !(self.eccentricity_limit > 0.0 && self.eccentricity_limit < 1.0) {
            return Err(bad("eccentricity_limit", self.eccentricity_limit));
        }
        Ok(())
    }
}

/// Cycle extremes and averages of the reported (periodic) cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitSummary {
    /// Smallest h_min over the cycle (m) and the crank angle (deg) where it occurs.
    pub min_film_thickness: f64,
    pub min_film_crank_angle_deg: f64,
    /// Largest |ε| over the cycle.
    pub max_eccentricity_ratio: f64,
    /// Time average of |ε|.
    pub mean_eccentricity_ratio: f64,
    /// Largest peak pressure (Pa) and the crank angle (deg) where it occurs.
    pub max_peak_pressure: f64,
    pub max_peak_pressure_crank_angle_deg: f64,
    /// Time average of the side flow (m³/s).
    pub mean_side_flow: f64,
    /// Time average of the power loss (W).
    pub mean_power_loss: f64,
}

/// The periodic orbit and its performance, sampled over the last cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct OrbitInfo {
    /// Time from the start of the reported cycle (s), 0 … τ.
    pub time: Vec<f64>,
    /// Crank angle (deg) of each sample, by the load's convention.
    pub crank_angle_deg: Vec<f64>,
    /// ε (bearing frame).
    pub eccentricity: Vec<[f64; 2]>,
    /// Load on the journal (N, bearing frame).
    pub load: Vec<[f64; 2]>,
    /// Attitude angle (rad): from the load direction to ε, counter-clockwise (θ sense), in
    /// (−π, π], as [`crate::inverse::InverseStep::attitude_angle`] (the classical φ for
    /// ω_j − ω_b > 0). Where the load is zero the last non-zero load direction is used.
    pub attitude_angle: Vec<f64>,
    /// h_min, p_max, side flow, power loss, rates at each sample.
    pub performance: Vec<PerformancePoint>,
    /// Cycle extremes and averages.
    pub summary: OrbitSummary,
    /// Cycles integrated (including the reported one).
    pub cycles: usize,
    /// ε at the same sample times in every integrated cycle, first to last (the run-in from the
    /// initial position; the last entry equals `eccentricity`).
    pub cycle_history: Vec<Vec<[f64; 2]>>,
    /// max_t |ε(t) − ε(t − τ)| between the last two cycles.
    pub periodicity_change: f64,
    /// Right-hand-side evaluations, accepted and rejected steps over all cycles.
    pub rhs_evaluations: usize,
    pub accepted_steps: usize,
    pub rejected_steps: usize,
}

struct OrbitOde<'a, M: ?Sized, L: ?Sized> {
    params: &'a MobilityParams,
    model: &'a M,
    load: &'a L,
    limit: f64,
    model_max: f64,
}

impl<M: MobilityModel + ?Sized, L: PeriodicLoad + ?Sized> ODE<f64, [f64; 2]>
    for OrbitOde<'_, M, L>
{
    fn diff(&self, t: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        let w = self.load.load(t);
        let e = y[0].hypot(y[1]);
        // Trial stages beyond the model's range: evaluate the mobility at the clamped radius.
        let cap = self.model_max * (1.0 - 1e-12);
        let ye = if e > cap {
            [y[0] * cap / e, y[1] * cap / e]
        } else {
            *y
        };
        let u = squeeze_rate(self.params, self.model, ye, w);
        let wbar = self.params.omega_bar();
        dydt[0] = u[0] - wbar * y[1];
        dydt[1] = u[1] + wbar * y[0];
    }
}

impl<M: ?Sized, L: ?Sized> Event<f64, [f64; 2]> for OrbitOde<'_, M, L> {
    fn config(&self) -> EventConfig {
        EventConfig::new(CrossingDirection::Positive, Some(1))
    }

    fn event(&self, _t: f64, y: &[f64; 2]) -> f64 {
        y[0].hypot(y[1]) - self.limit
    }
}

/// Integrate the mobility orbit under the periodic `load` until it is periodic.
///
/// ```
/// use jbearing_solvers::prelude::*;
/// use std::f64::consts::TAU;
///
/// let bearing = MobilityParams {
///     radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02,
///     omega_journal: 300.0, omega_bearing: 0.0,
/// };
/// let model = ExactShortBearing { length_to_diameter: bearing.length_to_diameter() };
/// let load = ConstantLoad { load: [0.0, -1000.0], period: TAU / 300.0 };
/// let orbit = solve_orbit(&OrbitParams::new(bearing), &model, &load)?;
/// // A constant load: the journal settles where the film carries it (Ocvirk's steady bearing).
/// let e = orbit.summary.mean_eccentricity_ratio;
/// let ocvirk = jbearing_solvers::closed_form::short::ocvirk_steady_load(&bearing.closed_form(), e, 300.0);
/// assert!((ocvirk - 1000.0).abs() < 1e-3 * 1000.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_orbit<M: MobilityModel + ?Sized, L: PeriodicLoad + ?Sized>(
    params: &OrbitParams,
    model: &M,
    load: &L,
) -> Result<OrbitInfo, MobilityError> {
    params.validate()?;
    let ld = params.bearing.length_to_diameter();
    let mld = model.length_to_diameter();
    if (ld - mld).abs() > 1e-9 * ld {
        return Err(MobilityError::LengthToDiameterMismatch {
            model: mld,
            bearing: ld,
        });
    }
    let tau = load.period();
    if !(tau.is_finite() && tau > 0.0) {
        return Err(MobilityError::InvalidParameter {
            name: "load period",
            value: tau,
        });
    }
    let ode = OrbitOde {
        params: &params.bearing,
        model,
        load,
        limit: params.eccentricity_limit.min(model.max_eccentricity()),
        model_max: model.max_eccentricity(),
    };
    let mut y0 = params.initial_eccentricity;
    let mut history: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut counts = (0usize, 0usize, 0usize);
    let mut change = f64::INFINITY;
    for cycle in 1..=params.max_cycles {
        let t0 = (cycle - 1) as f64 * tau;
        let samples = integrate_cycle(&ode, params, cycle, tau, y0)?;
        counts.0 += samples.evaluations;
        counts.1 += samples.accepted;
        counts.2 += samples.rejected;
        y0 = samples.y[params.samples_per_cycle];
        if let Some(prev) = history.last() {
            change = prev
                .iter()
                .zip(&samples.y)
                .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
                .fold(0.0, f64::max);
        }
        let converged = if params.periodicity_tolerance == f64::INFINITY {
            cycle == params.max_cycles // fixed-length run
        } else {
            change < params.periodicity_tolerance
        };
        if converged || cycle == params.max_cycles {
            if !converged {
                return Err(MobilityError::NotPeriodic {
                    cycles: cycle,
                    change,
                    tolerance: params.periodicity_tolerance,
                });
            }
            let rel: Vec<f64> = samples.t.iter().map(|t| t - t0).collect();
            history.push(samples.y.clone());
            return assemble(params, model, load, rel, samples.y, history, change, counts);
        }
        history.push(samples.y);
    }
    unreachable!("the loop returns at max_cycles")
}

/// One load cycle of the orbit ODE, sampled at `samples_per_cycle` + 1 equal times.
struct CycleSamples {
    t: Vec<f64>,
    y: Vec<[f64; 2]>,
    evaluations: usize,
    accepted: usize,
    rejected: usize,
}

/// Integrate cycle `cycle` (from t₀ = (cycle − 1) τ at ε = `y0`) with DOPRI5 at the tolerances
/// and sample spacing of `params`. The collapse event, missing samples, a solver failure and a
/// non-finite ε are errors naming the crank angle and cycle.
fn integrate_cycle<M: MobilityModel + ?Sized, L: PeriodicLoad + ?Sized>(
    ode: &OrbitOde<'_, M, L>,
    params: &OrbitParams,
    cycle: usize,
    tau: f64,
    y0: [f64; 2],
) -> Result<CycleSamples, MobilityError> {
    let (n, load, limit) = (params.samples_per_cycle, ode.load, ode.limit);
    let t0 = (cycle - 1) as f64 * tau;
    let tf = cycle as f64 * tau;
    let times: Vec<f64> = (0..=n)
        .map(|i| {
            if i == n {
                tf
            } else {
                t0 + tau * i as f64 / n as f64
            }
        })
        .collect();
    let method = ExplicitRungeKutta::dopri5()
        .rtol(params.relative_tolerance)
        .atol(params.absolute_tolerance)
        .h_max(tau / n as f64)
        .max_steps(1_000_000);
    // Integrate a hair past tf: the solver's final time may round to just below tf, and the
    // sample at tf must still be emitted.
    let sol = IVP::ode(ode, t0, tf + 1e-9 * tau, y0)
        .t_eval(&times)
        .event(ode)
        .method(method)
        .solve()
        .map_err(|err| {
            let (time, reason) = describe_error(&err, t0);
            MobilityError::Integration {
                time: time - t0,
                crank_angle_deg: load.crank_angle_deg(time - t0),
                cycle,
                reason,
            }
        })?;
    if matches!(sol.status, Status::Interrupted) || sol.t.len() != n + 1 {
        let limits = Limits {
            orbit: limit,
            collapse: params.eccentricity_limit,
        };
        return Err(incomplete_cycle(&sol, t0, y0, n, load, limits, cycle));
    }
    for (t, y) in sol.t.iter().zip(&sol.y) {
        if !(y[0].is_finite() && y[1].is_finite()) {
            return Err(MobilityError::NonFinite {
                quantity: "eccentricity",
                time: t - t0,
                crank_angle_deg: load.crank_angle_deg(t - t0),
            });
        }
    }
    Ok(CycleSamples {
        evaluations: sol.evals.function,
        accepted: sol.steps.accepted,
        rejected: sol.steps.rejected,
        t: sol.t,
        y: sol.y,
    })
}

/// The |ε| at which an orbit stops: `orbit` = min(`collapse`, the model's largest ε).
#[derive(Debug, Clone, Copy)]
struct Limits {
    orbit: f64,
    collapse: f64,
}

/// The error of a cycle that the limit event interrupted or that is missing output samples
/// (of `n` + 1), at the produced sample where |ε| is largest (the start `y0` at `t0` when none
/// was): when the event fired or |ε| reached the orbit's limit, a film collapse — or, if the
/// model's range ends below the collapse limit, the orbit leaving that range; else an
/// integration error counting the samples.
fn incomplete_cycle<L: PeriodicLoad + ?Sized>(
    sol: &Solution<f64, [f64; 2]>,
    t0: f64,
    y0: [f64; 2],
    n: usize,
    load: &L,
    limits: Limits,
    cycle: usize,
) -> MobilityError {
    let limit = limits.orbit;
    let (t_end, y_end) = sol
        .t
        .iter()
        .zip(&sol.y)
        .max_by(|a, b| a.1[0].hypot(a.1[1]).total_cmp(&b.1[0].hypot(b.1[1])))
        .map(|(t, y)| (*t, *y))
        .unwrap_or((t0, y0));
    let e = y_end[0].hypot(y_end[1]);
    if (matches!(sol.status, Status::Interrupted) || e >= limit) && limit < limits.collapse {
        return MobilityError::OutsideModelRange {
            time: t_end - t0,
            crank_angle_deg: load.crank_angle_deg(t_end - t0),
            cycle,
            eccentricity: e,
            model_limit: limit,
            collapse_limit: limits.collapse,
        };
    }
    if matches!(sol.status, Status::Interrupted) || e >= limit {
        return MobilityError::FilmCollapse {
            time: t_end - t0,
            crank_angle_deg: load.crank_angle_deg(t_end - t0),
            cycle,
            eccentricity: e,
            limit,
        };
    }
    MobilityError::Integration {
        time: t_end - t0,
        crank_angle_deg: load.crank_angle_deg(t_end - t0),
        cycle,
        reason: format!("{} of {} output samples produced", sol.t.len(), n + 1),
    }
}

fn describe_error(
    err: &differential_equations::prelude::Error<f64, [f64; 2]>,
    t0: f64,
) -> (f64, String) {
    use differential_equations::prelude::Error as E;
    match err {
        E::MaxSteps { t, .. } => (*t, "maximum number of steps reached".into()),
        E::StepSize { t, .. } => (*t, "step size underflow".into()),
        E::Stiffness { t, .. } => (*t, "problem became stiff".into()),
        E::BadInput { msg } => (t0, format!("bad input: {msg}")),
        other => (t0, format!("{other:?}")),
    }
}

/// The reported (last) cycle: its loads and crank angles, the performance, attitude angles and
/// summary at its samples, with the cycle history and the integrator's counts.
#[allow(clippy::too_many_arguments)]
fn assemble<M: MobilityModel + ?Sized, L: PeriodicLoad + ?Sized>(
    params: &OrbitParams,
    model: &M,
    load: &L,
    time: Vec<f64>,
    eccentricity: Vec<[f64; 2]>,
    history: Vec<Vec<[f64; 2]>>,
    change: f64,
    (evals, accepted, rejected): (usize, usize, usize),
) -> Result<OrbitInfo, MobilityError> {
    let loads: Vec<[f64; 2]> = time.iter().map(|&t| load.load(t)).collect();
    let crank: Vec<f64> = time.iter().map(|&t| load.crank_angle_deg(t)).collect();
    let performance = performance_along(params, model, &time, &eccentricity, &loads, &crank)?;
    let attitude = attitude_angles(&loads, &eccentricity);
    let summary = cycle_summary(&time, &crank, &performance);
    Ok(OrbitInfo {
        time,
        crank_angle_deg: crank,
        eccentricity,
        load: loads,
        attitude_angle: attitude,
        performance,
        summary,
        cycles: history.len(),
        cycle_history: history,
        periodicity_change: change,
        rhs_evaluations: evals,
        accepted_steps: accepted,
        rejected_steps: rejected,
    })
}

/// The closed-form performance (p_max, flows, power, h_min) at each sample of the cycle; a
/// non-finite one is an error naming its time and crank angle.
fn performance_along<M: MobilityModel + ?Sized>(
    params: &OrbitParams,
    model: &M,
    time: &[f64],
    eccentricity: &[[f64; 2]],
    loads: &[[f64; 2]],
    crank: &[f64],
) -> Result<Vec<PerformancePoint>, MobilityError> {
    let n = time.len();
    let mut performance = Vec::with_capacity(n);
    for i in 0..n {
        let p = performance_at(&params.bearing, model, eccentricity[i], loads[i]);
        let finite = [
            p.peak_pressure,
            p.side_flow,
            p.power_loss,
            p.min_film_thickness,
        ]
        .iter()
        .all(|v| v.is_finite());
        if !finite {
            return Err(MobilityError::NonFinite {
                quantity: "performance (p_max, flow or power)",
                time: time[i],
                crank_angle_deg: crank[i],
            });
        }
        performance.push(p);
    }
    Ok(performance)
}

/// The attitude angle of ε against the load direction, wrapped to (−π, π]; zero loads borrow
/// the last non-zero direction (or the first one of the cycle).
fn attitude_angles(loads: &[[f64; 2]], eccentricity: &[[f64; 2]]) -> Vec<f64> {
    let mut dir = loads
        .iter()
        .find(|w| w[0] != 0.0 || w[1] != 0.0)
        .map(|w| w[1].atan2(w[0]))
        .unwrap_or(0.0);
    let mut attitude = Vec::with_capacity(loads.len());
    for (w, e) in loads.iter().zip(eccentricity) {
        if w[0] != 0.0 || w[1] != 0.0 {
            dir = w[1].atan2(w[0]);
        }
        let a = e[1].atan2(e[0]) - dir;
        attitude.push(wrap_pi(a));
    }
    attitude
}

/// The cycle's extremes (thinnest film, highest peak pressure, with their crank angles) and
/// trapezoidal time averages.
fn cycle_summary(time: &[f64], crank: &[f64], performance: &[PerformancePoint]) -> OrbitSummary {
    let n = time.len();
    let mut imin = 0;
    let mut ipmax = 0;
    for i in 0..n {
        if performance[i].min_film_thickness < performance[imin].min_film_thickness {
            imin = i;
        }
        if performance[i].peak_pressure > performance[ipmax].peak_pressure {
            ipmax = i;
        }
    }
    let span = time[n - 1] - time[0];
    let mean = |f: &dyn Fn(&PerformancePoint) -> f64| -> f64 {
        let mut acc = 0.0;
        for i in 1..n {
            acc += 0.5 * (f(&performance[i]) + f(&performance[i - 1])) * (time[i] - time[i - 1]);
        }
        acc / span
    };
    OrbitSummary {
        min_film_thickness: performance[imin].min_film_thickness,
        min_film_crank_angle_deg: crank[imin],
        max_eccentricity_ratio: performance[imin].eccentricity_ratio,
        mean_eccentricity_ratio: mean(&|p| p.eccentricity_ratio),
        max_peak_pressure: performance[ipmax].peak_pressure,
        max_peak_pressure_crank_angle_deg: crank[ipmax],
        mean_side_flow: mean(&|p| p.side_flow),
        mean_power_loss: mean(&|p| p.power_loss),
    }
}

fn wrap_pi(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = (a + PI).rem_euclid(TAU) - PI;
    if r <= -PI { r + TAU } else { r }
}
