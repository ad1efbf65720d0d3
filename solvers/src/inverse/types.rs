//! The inverse solver's public types: its parameters ([`InverseParams`], [`JacobianMethod`]),
//! what it returns ([`InverseSolution`]: per-step series [`InverseStep`], field snapshots,
//! the cycle summary, run statistics [`InverseInfo`] and warnings), its progress reports and
//! observer, and its errors ([`InverseError`], every variant with the time, crank angle and
//! numbers of the failure). The algorithm is in `solve.rs`.

use super::{FilmFields, FilmModelError};
use thiserror::Error;

/// How the 2×2 Jacobian ∂F/∂ε is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JacobianMethod {
    /// The film model's exact Jacobian from its converged linearization
    /// ([`super::FilmModel::force_jacobian`]), kept across iterates and steps while each
    /// Newton iterate along it reduces |r| at least 4× and, at that rate, at most two more
    /// would reach the tolerance (chord steps), taken afresh at the current iterate otherwise
    /// and whenever a step along it finds no descent; forward differences for a model that has
    /// none (counted in
    /// [`InverseInfo::jacobian_evaluations`] either way).
    #[default]
    Exact,
    /// Forward differences at every Newton iteration (2 extra film steps per iteration).
    FiniteDifference,
    /// Broyden's (good) rank-one updates, carried across time steps; refreshed by forward
    /// differences when an update stops reducing the residual.
    Broyden,
}

/// Parameters of the inverse solve.
#[derive(Debug, Clone, PartialEq)]
pub struct InverseParams {
    /// Time step in crank degrees (default 1°). Rounded so that a whole number of steps fills
    /// the cycle.
    pub step_deg: f64,
    /// Newton tolerance on |F + W| / max(|W|, W_ref) (default 1e-4).
    pub tolerance: f64,
    /// W_ref (N) for the tolerance when the load passes near zero; 0 (default) takes 1 % of the
    /// cycle's peak load.
    pub reference_load: f64,
    /// Jacobian: exact (default), differences or Broyden updates.
    pub jacobian: JacobianMethod,
    /// Difference step in ε for the Jacobian (default 1e-6).
    pub fd_step: f64,
    /// A step whose Newton stalls — a fresh Jacobian gives no descent even after halving, or
    /// the iteration limit is reached — is first retried as two half steps
    /// (`max_step_splits`); only where it can be split no further is it accepted at its best
    /// point if the residual is ≤ `accept_tolerance` (default 1e-2), and counted in
    /// [`InverseInfo::stalled_steps`]; above it the step fails. Why: a fallback, reported, for
    /// a film force that Newton cannot resolve at the shortest step (the difference and secant
    /// Jacobians across a switching film; the exact Jacobian's film is continuous but only
    /// piecewise smooth in ε). Set it equal to `tolerance` for a strict run.
    pub accept_tolerance: f64,
    /// Newton iterations allowed per time step (default 40).
    pub max_newton_iterations: usize,
    /// A time step whose Newton fails is retried as two half steps (the film state carried
    /// through the midpoint, the load and conditions taken there), recursively, up to this many
    /// halvings (default 4: down to 1/16 of the step). Only the step's end enters the results.
    /// Why: when the film changes fast (a cavity collapsing, the feed cut off) the end-of-step
    /// root can lie outside Newton's reach from the extrapolated guess; a shorter step moves
    /// the guess and the squeeze term closer. 0 disables it.
    pub max_step_splits: usize,
    /// Local error tolerance of a cycle step, in ε (default 1e-3, the periodicity tolerance:
    /// 0.1 % of the clearance). A step whose error estimate (the difference between its answer
    /// and the predictor's, Milne's device) exceeds it is taken in 2^k equal substeps, k ≤
    /// `max_step_splits`, and so in every later cycle ([`super::error_control`]). Why: at 2°
    /// steps the compressor rod's discharge event (ε 0.77 → 0.63 in 5° of crank) is 0.02 off
    /// in ε, and a step split only when its Newton fails is split in some cycles and not in
    /// others. 0 disables the control; it needs the film's time scheme
    /// ([`super::FilmModel::time_scheme`]).
    pub step_error_tolerance: f64,
    /// Largest |Δε| of one Newton update (default 0.2).
    pub max_newton_step: f64,
    /// |ε| at or beyond which the film has collapsed (default 0.999).
    pub collapse_eccentricity: f64,
    /// h_min (m) below which the film has collapsed (default 0: only the ε criterion).
    pub min_film_floor: f64,
    /// Steps of the run-in ramp; 0 (default) takes a quarter cycle (at least 8 steps).
    pub run_in_steps: usize,
    /// Cycle limit (default 20).
    pub max_cycles: usize,
    /// Periodicity tolerance on max_i |ε_i − ε_i(previous cycle)| (default 1e-3, i.e. 0.1 % of
    /// the clearance: the Newton tolerance 1e-4 leaves step-to-step noise of order 1e-5…1e-4 in
    /// ε, so a tighter periodicity test needs a tighter Newton tolerance too).
    pub periodicity_tolerance: f64,
    /// Periodicity tolerance on the change of the film field over a cycle (max |Δφ|, default
    /// 1e-3).
    pub film_state_tolerance: f64,
    /// Extrapolate the cycle-to-cycle map when it converges slowly (default true): minimal
    /// polynomial extrapolation of the cycle-start states over its two slowest modes
    /// ([`super::cycle_map`]); the periodicity test is still made between two marched cycles.
    /// Needs a film with [`super::FilmModel::state_vector`].
    pub cycle_extrapolation: bool,
    /// Keep the fields of the final cycle every `field_stride` steps (0 = none, default): after
    /// steps field_stride, 2·field_stride, … (the last step of the cycle among them when the
    /// stride divides the steps per cycle).
    pub field_stride: usize,
}

impl Default for InverseParams {
    fn default() -> Self {
        Self {
            step_deg: 1.0,
            tolerance: 1e-4,
            reference_load: 0.0,
            jacobian: JacobianMethod::Exact,
            fd_step: 1e-6,
            accept_tolerance: 1e-2,
            max_newton_iterations: 40,
            max_step_splits: 4,
            step_error_tolerance: 1e-3,
            max_newton_step: 0.2,
            collapse_eccentricity: 0.999,
            min_film_floor: 0.0,
            run_in_steps: 0,
            max_cycles: 20,
            periodicity_tolerance: 1e-3,
            film_state_tolerance: 1e-3,
            cycle_extrapolation: true,
            field_stride: 0,
        }
    }
}

/// Phase of the run, for progress reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InversePhase {
    /// The ramp from ε = 0 to the load at t = 0.
    RunIn,
    /// Load cycle number (1, 2, …).
    Cycle(usize),
}

/// One progress report (after every accepted step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseProgress {
    /// Run-in or cycle.
    pub phase: InversePhase,
    /// Step within the phase (1-based).
    pub step: usize,
    /// Steps in the phase.
    pub steps: usize,
    /// Largest number of cycles the run may take.
    pub max_cycles: usize,
    /// Time (s); negative during the run-in.
    pub time: f64,
    /// Crank angle within the cycle (deg).
    pub crank_angle_deg: f64,
    /// ε after the step.
    pub eccentricity_ratio: [f64; 2],
    /// Final normalised residual of the step.
    pub residual: f64,
    /// Newton iterations of the step.
    pub newton_iterations: usize,
}

/// Progress observer (a progress bar, a log).
pub trait InverseObserver {
    /// After every accepted time step.
    fn on_step(&mut self, _progress: &InverseProgress) {}
    /// After every load cycle, with the periodicity measures of that cycle.
    fn on_cycle(&mut self, _cycle: usize, _eccentricity_change: f64, _film_state_change: f64) {}
    /// A step accepted as a stall ([`InverseParams::accept_tolerance`]), before its
    /// [`InverseObserver::on_step`].
    fn on_stall(&mut self, _stall: &InverseStall) {}
    /// After load cycle `cycle`, when the march continues from the extrapolated cycle-start
    /// state ([`InverseParams::cycle_extrapolation`]) instead of that cycle's end.
    fn on_extrapolation(&mut self, _cycle: usize) {}
    /// Asked after every accepted time step: `true` stops the solve with
    /// [`InverseError::Interrupted`] (a user's Ctrl-C, a time budget).
    fn stop_requested(&mut self) -> bool {
        false
    }
}

/// A time step whose Newton stalled above [`InverseParams::tolerance`] and was accepted at
/// its best point ([`InverseInfo::stalled_steps`]): where, how far, and what the film model
/// reports of its last step ([`super::FilmModel::step_diagnostics`]).
#[derive(Debug, Clone, PartialEq)]
pub struct InverseStall {
    /// End of the step (s; negative during the run-in) and its crank angle (deg).
    pub time: f64,
    pub crank_angle_deg: f64,
    /// Load cycle (0: the run-in).
    pub cycle: usize,
    /// Length of the step (s; shorter than the cycle's step inside a halved step).
    pub dt: f64,
    /// |F + W| / max(|W|, W_ref) at the accepted point, and the tolerance it missed.
    pub residual: f64,
    pub tolerance: f64,
    /// max(|W|, W_ref) of the step (N).
    pub scale: f64,
    /// Newton iterations taken.
    pub newton_iterations: usize,
    /// ε accepted.
    pub eccentricity_ratio: [f64; 2],
    /// The film model's measures of its last step (the last trial solved, which need not be
    /// the accepted one).
    pub film: Vec<(&'static str, f64)>,
}

/// An observer that ignores everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl InverseObserver for NoObserver {}

/// One time step of the final cycle.
///
/// The state outputs (ε, film force, h_min, p_max, cavitated fraction) are those at the step's
/// end. The flows and power are the step's:
/// - side leakage and supply flow: for a film model with boundary volumes
///   ([`super::FilmModel::boundary_volumes`], the Reynolds film) the volume of the step over
///   its length, integrated by the scheme of each (sub)step exactly as the film content is —
///   so the cycle means balance (mean supply = mean side leakage over a periodic cycle) to the
///   film's mass balance for every scheme and step pattern; for BDF2 and Crank–Nicolson this
///   is ≈ the flow at mid-step, for backward Euler the flow at the step's end. Without
///   volumes: the flow at the end, or the mean of the parts' for a step taken in parts;
/// - recirculated flow, friction torques, power loss: at the step's end, or for a step the
///   local error control took in substeps (or a Newton failure split in halves) the mean of
///   its parts' weighted by their lengths.
#[derive(Debug, Clone, PartialEq)]
pub struct InverseStep {
    /// Time within the final cycle (s), in (0, τ].
    pub time: f64,
    /// Crank angle within the cycle (deg), in (0, cycle].
    pub crank_angle_deg: f64,
    /// Load on the journal (N, bearing frame).
    pub load: [f64; 2],
    /// Film force on the journal (N, bearing frame).
    pub film_force: [f64; 2],
    /// |F + W| / max(|W|, W_ref) at the accepted ε.
    pub residual: f64,
    /// ε vector (bearing frame).
    pub eccentricity_ratio: [f64; 2],
    /// |ε|.
    pub eccentricity: f64,
    /// Attitude angle (rad, (−π, π]): from the load direction W to ε, counter-clockwise (the θ
    /// sense) positive whatever the sense of rotation — the classical φ (positive in the
    /// direction of U, [`crate::reynolds::FilmSolution::attitude_angle`]) for ω_j − ω_b > 0, its
    /// negative for ω_j − ω_b < 0 (docs/conventions.md §1).
    pub attitude_angle: f64,
    /// h_min (m).
    pub min_film_thickness: f64,
    /// (θ, z) of h_min.
    pub min_film_location: [f64; 2],
    /// p_max (Pa).
    pub max_pressure: f64,
    /// (θ, z) of p_max.
    pub max_pressure_location: [f64; 2],
    /// Cavitated area fraction.
    pub cavitated_fraction: f64,
    /// Side leakage at z = −L/2 and +L/2 (m³/s).
    pub side_leakage: [f64; 2],
    /// Supply flow per groove (m³/s, signed).
    pub supply_flow: Vec<f64>,
    /// Film oil arriving at the feed grooves (m³/s, [`super::FilmResponse::recirculated_flow`]).
    pub recirculated_flow: f64,
    /// Power loss (W).
    pub power_loss: f64,
    /// Friction torque on the journal (N·m).
    pub friction_torque_journal: f64,
    /// Friction torque on the bearing (N·m).
    pub friction_torque_bearing: f64,
    /// Newton iterations of this step.
    pub newton_iterations: usize,
    /// Film-solver sweeps of the accepted film step.
    pub sweep_iterations: usize,
}

/// Fields of the final cycle at one step.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldSnapshot {
    /// Index into [`InverseSolution::steps`].
    pub step_index: usize,
    /// Time within the cycle (s).
    pub time: f64,
    /// Crank angle (deg).
    pub crank_angle_deg: f64,
    /// p, φ, g.
    pub fields: FilmFields,
}

/// Averages (time means over the N equally spaced steps of the periodic cycle — the trapezoidal
/// rule for periodic data) and extremes of the final cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct CycleSummary {
    /// Mean |ε|.
    pub mean_eccentricity: f64,
    /// Max |ε| and its crank angle (deg).
    pub max_eccentricity: f64,
    pub max_eccentricity_crank_angle_deg: f64,
    /// Min h_min (m) and its crank angle (deg).
    pub min_film_thickness: f64,
    pub min_film_thickness_crank_angle_deg: f64,
    /// Max p_max (Pa) and its crank angle (deg).
    pub max_pressure: f64,
    pub max_pressure_crank_angle_deg: f64,
    /// Mean and max cavitated fraction.
    pub mean_cavitated_fraction: f64,
    pub max_cavitated_fraction: f64,
    /// Mean side leakage per end (m³/s).
    pub mean_side_leakage: [f64; 2],
    /// Mean and max total side leakage (m³/s).
    pub mean_total_side_leakage: f64,
    pub max_total_side_leakage: f64,
    /// Mean supply flow per groove and in total (m³/s).
    pub mean_supply_flow: Vec<f64>,
    pub mean_total_supply_flow: f64,
    /// Mean and max power loss (W).
    pub mean_power_loss: f64,
    pub max_power_loss: f64,
    /// Mean friction torques (N·m).
    pub mean_friction_torque_journal: f64,
    pub mean_friction_torque_bearing: f64,
}

/// A result that is usable but not what was asked for.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InverseWarning {
    /// The cycle limit was reached before the orbit became periodic.
    #[error(
        "not periodic after {cycles} cycles: max |Δε| = {eccentricity_change:.3e} (tolerance {eccentricity_tolerance:.1e}), max |Δφ| = {film_state_change:.3e} (tolerance {film_state_tolerance:.1e})"
    )]
    NotPeriodic {
        cycles: usize,
        eccentricity_change: f64,
        eccentricity_tolerance: f64,
        film_state_change: f64,
        film_state_tolerance: f64,
    },
}

/// Run statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct InverseInfo {
    /// Steps per cycle N and step dt (s).
    pub steps_per_cycle: usize,
    pub time_step: f64,
    /// Period τ (s) and cycle length (crank degrees).
    pub period: f64,
    pub cycle_deg: f64,
    /// Run-in steps.
    pub run_in_steps: usize,
    /// Load cycles computed (the last one is the result).
    pub cycles: usize,
    /// Whether the periodicity tolerances were met.
    pub periodic: bool,
    /// max_i |ε_i − ε_i(previous cycle)| of the last cycle (∞ after a single cycle).
    pub eccentricity_change: f64,
    /// Film field change over the last cycle (max |Δφ|).
    pub film_state_change: f64,
    /// Set when the result is not periodic.
    pub warning: Option<InverseWarning>,
    /// W_ref used in the tolerance (N).
    pub reference_load: f64,
    /// Newton iterations in total and the most in one step.
    pub newton_iterations: usize,
    pub max_newton_iterations_per_step: usize,
    /// Film steps evaluated (Newton, Jacobian, fields).
    pub film_evaluations: usize,
    /// Finite-difference Jacobians computed.
    pub jacobian_evaluations: usize,
    /// Film-solver sweeps summed over all film evaluations.
    pub sweep_iterations: usize,
    /// Steps accepted after a Newton stall with tolerance < residual ≤ accept_tolerance, and
    /// the largest such residual (0 if none).
    pub stalled_steps: usize,
    pub max_stalled_residual: f64,
    /// Time steps that needed halving ([`InverseParams::max_step_splits`]) to converge.
    pub split_steps: usize,
    /// Steps of the cycle taken in substeps by the local error control
    /// ([`InverseParams::step_error_tolerance`]) at the end, and the most halvings of one.
    pub refined_steps: usize,
    pub max_refinement_level: usize,
    /// Extrapolations of the cycle-to-cycle map made ([`InverseParams::cycle_extrapolation`]).
    pub cycle_extrapolations: usize,
    /// Wall-clock time of the whole run (s).
    pub wall_time: f64,
}

/// The periodic solution: the final cycle's time series, fields, summary and run statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct InverseSolution {
    /// One record per step of the final cycle.
    pub steps: Vec<InverseStep>,
    /// Fields of the final cycle every `field_stride` steps.
    pub fields: Vec<FieldSnapshot>,
    /// Averages and extremes.
    pub summary: CycleSummary,
    /// Statistics.
    pub info: InverseInfo,
}

/// Why the inverse solve stopped.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InverseError {
    /// A parameter or the load history is unusable.
    #[error("invalid parameter {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
    /// The observer asked to stop ([`InverseObserver::stop_requested`]) after the step that
    /// ended here.
    #[error("interrupted at {when}", when = When(*time, *crank_angle_deg, *cycle))]
    Interrupted {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
    },
    /// The film cannot carry the load: the journal reached the wall.
    #[error(
        "film collapse at {when}: |ε| = {eccentricity:.6}, ε = ({:.6}, {:.6}), h_min = {min_film_thickness:.3e} m, residual {residual:.3e}",
        eccentricity_ratio[0], eccentricity_ratio[1], when = When(*time, *crank_angle_deg, *cycle)
    )]
    Collapse {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
        eccentricity_ratio: [f64; 2],
        eccentricity: f64,
        min_film_thickness: f64,
        residual: f64,
    },
    /// Newton did not converge in the step. `cavitated_fraction` is the cavitated share of the
    /// film area at the last iterate (the film model's [`super::FilmResponse`]): a film close
    /// to empty there (a starved film, e.g. at a load reversal) cannot hold a massless journal,
    /// and the quasi-static inverse problem has no solution at a bounded journal speed
    /// (docs/methods.md, "Inverse solver with the Reynolds film").
    #[error(
        "Newton did not converge at {when} after {iterations} iterations: residual {residual:.3e}, last ε = ({:.6}, {:.6}), where {:.1} % of the film area is cavitated",
        eccentricity_ratio[0], eccentricity_ratio[1], 100.0 * cavitated_fraction, when = When(*time, *crank_angle_deg, *cycle)
    )]
    NewtonFailed {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
        iterations: usize,
        residual: f64,
        eccentricity_ratio: [f64; 2],
        cavitated_fraction: f64,
    },
    /// The film model failed at a trial ε.
    #[error(
        "film model failed at {when}, trial ε = ({:.6}, {:.6}): {source}",
        eccentricity_ratio[0], eccentricity_ratio[1], when = When(*time, *crank_angle_deg, *cycle)
    )]
    Film {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
        eccentricity_ratio: [f64; 2],
        source: FilmModelError,
    },
    /// The load history returned a non-finite value.
    #[error("non-finite {quantity} in the load history at t = {time:.6e} s")]
    NonFiniteLoad { quantity: &'static str, time: f64 },
}

/// How an error names the moment of the run: in load cycle k, the time and crank angle; in the
/// run-in (cycle 0, solver times t < 0 before the first load cycle, the quasi-load still
/// ramping up), the crank angle within the cycle (the solver wraps it into [0, cycle)) and how
/// long before the first cycle — never a negative time or angle.
struct When(f64, f64, usize);

impl std::fmt::Display for When {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let When(time, crank, cycle) = *self;
        match cycle {
            0 => write!(
                f,
                "crank angle {crank:.2}° of the run-in ({:.6e} s before the first cycle, \
                 quasi-load ramping up)",
                -time
            ),
            k => write!(f, "t = {time:.6e} s, crank angle {crank:.2}° (cycle {k})"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An error of the run-in says so, with the time before the first cycle and the crank
    /// angle within the cycle, never a negative time or angle.
    #[test]
    fn errors_name_the_run_in() {
        let at = |cycle| InverseError::NewtonFailed {
            time: if cycle == 0 { -8.24e-3 } else { 8.24e-3 },
            crank_angle_deg: 271.0,
            cycle,
            iterations: 3,
            residual: 0.5,
            eccentricity_ratio: [0.1, 0.2],
            cavitated_fraction: 0.9713,
        };
        assert_eq!(
            at(0).to_string(),
            "Newton did not converge at crank angle 271.00° of the run-in (8.240000e-3 s before \
             the first cycle, quasi-load ramping up) after 3 iterations: residual 5.000e-1, last \
             ε = (0.100000, 0.200000), where 97.1 % of the film area is cavitated"
        );
        assert!(
            at(2)
                .to_string()
                .contains("at t = 8.240000e-3 s, crank angle 271.00° (cycle 2) after"),
            "{}",
            at(2)
        );
    }
}
