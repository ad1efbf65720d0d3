//! The inverse dynamic-load problem: the load history is given, the journal orbit is sought.
//!
//! # The equation
//!
//! The journal is massless (docs/conventions.md §1): at every instant the film force balances the load
//! that the machine applies to the journal,
//!
//! ```text
//!   r(ε^{n+1}) = F_film(ε^{n+1}; film history up to t^n) + W(t^{n+1}) = 0        (docs/conventions.md §4)
//! ```
//!
//! The film force depends on ε^{n+1} directly (film thickness h = c − e·n) and through the time
//! derivative of the film content (squeeze), so each time step is a 2×2 nonlinear system in the
//! eccentricity ratio vector ε = e/c. Yu & Sawicki \[YuSawicki2002\] ("inverse solution": Newton on
//! the journal centre position per time step) solve it by Newton's method; so do we:
//!
//! ```text
//!   J Δε = −r(ε_k),   J = ∂F_film/∂ε  (2×2: exact, from the film's converged linearization —
//!                                       FilmModel::force_jacobian; forward differences for a
//!                                       film without one; Broyden updates as an option)
//!   ε_{k+1} = ε_k + λ Δε,  λ ≤ 1 limits |λΔε| ≤ max_newton_step and keeps |ε| < 1 by never
//!                          closing more than half of the remaining gap 1 − |ε_k| in one update
//!   converged when |r| / max(|W|, W_ref) ≤ tol                     (default tol = 1e-4)
//! ```
//!
//! The Newton is inexact in the film (Eisenstat–Walker forcing at the level of the inverse
//! problem): an iterate far from its answer needs its film force only
//! to a fraction of its residual, so the film step of the guess and of each trial from
//! |r_k|/scale > 10·tol (from closer, a chord step reducing |r| at least 4× likely gives the
//! answer: solved tightly) is relaxed ([`FilmModel::relax_next_step`]) to a force accuracy
//! η·|r_k|/scale, η = 0.1 (the guess, whose residual is not known yet: η), and a film with an
//! inner tolerance solves it that loosely —
//! unless its force then lands within 2·tol·scale of balancing the load, when it finishes the
//! same step to its own tolerance. An iterate is accepted (and its state carried on) only from
//! a film solved to its own tolerance; one that passes the test from a relaxed film is solved
//! again first. The exact Jacobian of an iterate is the derivative at its film as solved (at a
//! relaxed film it moves by the film's tolerance; measured on the compressor cycle, 120 × 31,
//! 1°: 1.48 Newton iterations per step and 66 refreshes in the run-in + cycle, against 1.50
//! and 66 with tight films). For [`ReynoldsFilm`] a relaxed step is one whose semismooth Newton stops at the switch pattern
//! of its loose solves (1e-6 of the flux scale) instead of adding the tight solve.
//!
//! The exact Jacobian is kept across iterates and time steps while each iterate along it
//! reduces |r| at least 4× and, at that rate, at most two more chord steps would reach the
//! tolerance (chord steps); it is taken afresh at the current iterate otherwise
//! (docs/conventions.md §4: finite differences across a switching film are meaningless). The discrete
//! JFO film of the second generation is continuous in ε (`crate::reynolds`, module docs), so
//! Newton converges to the tolerance on every step of the validation and compressor cases.
//! Where Newton from the predictor's guess fails — a singular fresh Jacobian, no descent on a
//! fresh one, or the iteration limit — it starts once more from the step's start ε (no
//! squeeze velocity over the step), from which the line search only moves downhill. Near a
//! sharp turn of the orbit the extrapolated guess can lie in another piece of the piecewise
//! smooth JFO force: where the squeeze suction of a journal extrapolated away from the wall
//! cavitates the whole film (F = 0 and ∂F/∂ε = 0 all around it, so a split step, which keeps
//! the speed, lands there again), or where the exact Jacobian of that piece leads Newton into
//! a local minimum of |r|. (Found 2026-11-28: the compressor rod bearing at 4° steps failed in
//! its third cycle in the step to 88° crank, "residual 1.000e0 after 1 iterations"; with the
//! restart it runs, h_min 3.829 µm against 3.835 µm at the case's 2°. And the shipped Flores
//! feed-hole case had failed in its first cycle since the error control of the cycle steps
//! (2026-11-27): a load reversal at 173.25° crank, residual 8.8e-2 of the load and no descent
//! at the deepest split, from a guess 0.07 of the clearance ahead; restarted, it is periodic
//! after 5 cycles with no stalled step — `tests/cli.rs`.)
//! A step that still cannot (iteration limit, or no descent on a fresh Jacobian, after the
//! restart) is taken as two half steps, recursively up to `max_step_splits` halvings, and only
//! at the deepest split accepted at its best point if |r|/max(|W|, W_ref) ≤ `accept_tolerance` (default 1e-2),
//! counted in [`InverseInfo::stalled_steps`] and reported; above that it is an error. (Until
//! 2026-11-28 a stall was accepted before the split: the Flores feed-hole case with
//! Crank–Nicolson accepted one at 174° of its first cycle, residual 1.3e-5 against 1e-6, after
//! 40 iterations on fresh Jacobians while the journal crossed 0.55 of the clearance in one
//! step; split first, it converges.)
//!
//! # Time marching
//!
//! ```text
//!   run-in  t ∈ [−T_r, 0]:  ε = 0, φ = 1 (full film), quasi-load s(t)·W(0), s: 0 → 1 smoothstep
//!   cycle k t ∈ [kτ, (k+1)τ]: N = cycle_deg / Δφ_c steps of dt = τ/N
//!   stop when max_i |ε_i^{(k)} − ε_i^{(k−1)}| ≤ tol_ε  and  |Δφ field over the cycle| ≤ tol_φ
//!   or at max_cycles (the result then carries a warning)
//! ```
//!
//! # Collapse
//!
//! A film that cannot carry the load lets the journal approach the wall: |ε| → 1, h_min → 0.
//! This is a physical outcome, not a numerical failure: when a converged step has
//! |ε| ≥ `collapse_eccentricity` or h_min below `min_film_floor`, or when Newton can only reduce
//! the residual by moving towards the wall beyond `collapse_eccentricity`, the run ends with
//! [`InverseError::Collapse`] naming time, crank angle, residual and ε. A step that fails for
//! any other reason is [`InverseError::NewtonFailed`] with the same numbers. No NaN leaves.
//!
//! # Film models
//!
//! [`FilmModel`] is the one thing the inverse solver needs from a film: step from a state at t^n
//! to a trial ε^{n+1} and return the film force and the outputs. Two implementations:
//! - [`ClosedFormFilm`]: any closed form of [`crate::closed_form`]; with
//!   [`ClosedFormModel::ShortGumbelMovingFilm`](crate::closed_form::ClosedFormModel) it is Ocvirk's
//!   short bearing with Gumbel's moving half film (\[Flores2006\] eqs. 18–22, 36–37), analytic,
//!   with the crate's [`TimeScheme`] (BDF2 default) discretisation of the journal velocity.
//! - [`ReynoldsFilm`]: the universal (mass-conserving) Reynolds solver [`crate::reynolds`].

pub mod cycle_map;
pub mod error_control;
mod reynolds_film;
mod solve;
mod types;

pub use reynolds_film::{ReynoldsFilm, film_response};

pub use crate::closed_form::{ClosedFormFilm, ClosedFormState};
pub use crate::time_scheme::{JournalMotion, TimeScheme};
pub use solve::{InverseStart, solve_inverse, solve_inverse_from};
pub use types::{
    CycleSummary, FieldSnapshot, InverseError, InverseInfo, InverseObserver, InverseParams,
    InversePhase, InverseProgress, InverseSolution, InverseStall, InverseStep, InverseWarning,
    JacobianMethod, NoObserver,
};

pub use crate::reynolds::OperatingConditions;
use ndarray::Array2;
use thiserror::Error;

/// Fields of one film solution on the film model's grid, indexed [i_θ, i_z].
#[derive(Debug, Clone, PartialEq)]
pub struct FilmFields {
    /// Gauge pressure p (Pa).
    pub pressure: Array2<f64>,
    /// φ: density ratio (full film, ≥ 1) or film fraction (cavitated, < 1).
    pub film_fraction: Array2<f64>,
    /// Switch function g (1 full film, 0 cavitated).
    pub switch: Array2<f64>,
}

/// What a film model returns for one step to a trial ε.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FilmResponse {
    /// Film force on the journal (N, bearing frame).
    pub film_force: [f64; 2],
    /// Minimum film thickness (m).
    pub min_film_thickness: f64,
    /// Where it is: (θ (rad), z (m)).
    pub min_film_location: [f64; 2],
    /// Peak gauge pressure (Pa).
    pub max_pressure: f64,
    /// Where it is: (θ (rad), z (m)).
    pub max_pressure_location: [f64; 2],
    /// Cavitated fraction of the film area (0…1).
    pub cavitated_fraction: f64,
    /// Oil volume flux out of the ends z = −L/2 and z = +L/2 (m³/s, outflow positive).
    pub side_leakage: [f64; 2],
    /// Net flux out of each feed groove into the film (m³/s, signed; negative = back-flow).
    pub supply_flow: Vec<f64>,
    /// Film oil arriving at the feed grooves (m³/s): the circumferential flow across their
    /// leading edges, summed; 0 for models without a film field or grooves.
    pub recirculated_flow: f64,
    /// Friction torque of the film on the journal (N·m, counter-clockwise positive).
    pub friction_torque_journal: f64,
    /// Friction torque of the film on the bearing (N·m, counter-clockwise positive).
    pub friction_torque_bearing: f64,
    /// Viscous dissipation (W).
    pub power_loss: f64,
    /// Inner iterations of the film solve (ADI sweeps); 0 for closed forms.
    pub sweep_iterations: usize,
    /// Fields, when the model was asked to capture them ([`FilmModel::set_capture_fields`]).
    pub fields: Option<FilmFields>,
}

/// A film model failed to step.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FilmModelError {
    /// The trial eccentricity is on or beyond the wall.
    #[error("trial eccentricity ratio |ε| = {eccentricity} is not inside the clearance")]
    OutsideClearance { eccentricity: f64 },
    /// A non-finite value appeared in the film solution.
    #[error("non-finite {quantity} in the film solution")]
    NonFinite { quantity: &'static str },
    /// The time step is not a finite positive number.
    #[error("time step dt = {dt} s is not finite and positive")]
    InvalidTimeStep { dt: f64 },
    /// A closed-form film failed (its parameters or the journal motion are out of range).
    #[error("closed-form film: {0}")]
    ClosedForm(#[from] crate::closed_form::ClosedFormError),
    /// The Reynolds film solver failed.
    #[error("Reynolds film: {0}")]
    Reynolds(#[from] crate::reynolds::ReynoldsError),
    /// A quantity the film model iterates within a step (the elastic gap of
    /// `crate::elastic::ElasticFilm`) did not converge.
    #[error(
        "{what} not converged within the step after {iterations} iterations: residual \
         {residual:e} > tolerance {tolerance:e}"
    )]
    NotConverged {
        what: &'static str,
        iterations: usize,
        residual: f64,
        tolerance: f64,
    },
}

/// What a Newton iterate far from its answer needs of the next film step
/// ([`FilmModel::relax_next_step`]): the film force to `accuracy` × the residual scale
/// (relative), unless the force then lands within `finish_within` of balancing `load` — an
/// iterate the caller may accept, which the model then solves to its own tolerance in the same
/// step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxedStep {
    /// Relative accuracy of the film force wanted (a fraction of the residual scale).
    pub accuracy: f64,
    /// The load W the film force balances (N): the residual is F_film + W.
    pub load: [f64; 2],
    /// |F_film + W| (N) below which the step is finished to the model's own tolerance.
    pub finish_within: f64,
}

/// A film that can be stepped from its state at t^n to a trial eccentricity at t^n + dt.
///
/// `step` must not change the model's physics between calls: the inverse solver calls it
/// several times from the same `state` with different trial ε (Newton iterations and the
/// finite-difference Jacobian) and keeps only the state of the accepted trial.
pub trait FilmModel {
    /// The film history the next step needs (ε at t^n, film fraction field, journal velocity…).
    type State: Clone;

    /// The state of a film at rest at eccentricity ratio `eccentricity_ratio` (full film, φ = 1).
    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> Self::State;

    /// One time step from `state` (at t^n) to the trial `eccentricity_ratio` at t^n + dt.
    fn step(
        &mut self,
        state: &Self::State,
        eccentricity_ratio: [f64; 2],
        dt: f64,
        conditions: &OperatingConditions,
    ) -> Result<(FilmResponse, Self::State), FilmModelError>;

    /// Largest change between two states' film fields (max |Δφ|) — the φ part of the
    /// periodicity test. Default 0 (a model without a film field).
    fn state_change(&self, _a: &Self::State, _b: &Self::State) -> f64 {
        0.0
    }

    /// Ask the model to return (or stop returning) fields in [`FilmResponse::fields`].
    fn set_capture_fields(&mut self, _capture: bool) {}

    /// The exact Jacobian ∂F_film/∂ε (N per unit ε, `[[∂F_x/∂ε_x, ∂F_x/∂ε_y], [∂F_y/∂ε_x,
    /// ∂F_y/∂ε_y]]`) of the last step this model solved, from its own linearization; None for
    /// a model that has none (the inverse solver then takes forward differences).
    fn force_jacobian(&mut self) -> Option<Result<[[f64; 2]; 2], FilmModelError>> {
        None
    }

    /// Let the next [`step`](Self::step), and that one only, be solved less accurately
    /// ([`RelaxedStep`]: the caller is a Newton iterate far from its answer). Default: ignored
    /// (closed forms are exact; a model with an inner tolerance may loosen it, never tighten
    /// it).
    fn relax_next_step(&mut self, _relax: RelaxedStep) {}

    /// Whether the last [`step`](Self::step) was solved looser than the model's own tolerance
    /// (after [`relax_next_step`](Self::relax_next_step)). Default false.
    fn last_step_relaxed(&self) -> bool {
        false
    }

    /// The state as a vector of numbers, for the extrapolation of the cycle-to-cycle map
    /// (`cycle_map`, [`InverseParams::cycle_extrapolation`]): the quantities of the state that
    /// evolve from cycle to cycle, in a fixed layout. None (default): the model's states are
    /// not extrapolated.
    fn state_vector(&self, _state: &Self::State) -> Option<Vec<f64>> {
        None
    }

    /// The inverse of [`FilmModel::state_vector`]: the state shaped like `template` whose
    /// vector is `vector` at eccentricity ratio `eccentricity_ratio`, with whatever the vector
    /// does not hold derived from it (a film fraction kept in its range, the switch from the
    /// sign of ψ); None when the vector is no state of this model (then the solver does not
    /// extrapolate).
    fn state_from_vector(
        &self,
        _template: &Self::State,
        _eccentricity_ratio: [f64; 2],
        _vector: &[f64],
    ) -> Option<Self::State> {
        None
    }

    /// The end `end` of a step of length `dt` that the caller took in parts (substeps of the
    /// local error control, halves of a split step) from `start`: make its multistep history
    /// that of one step from `start`, so that the next step, of length `dt` again, continues
    /// with a step ratio of 1. Variable-step BDF2 is zero-stable only for step ratios below
    /// 1 + √2 \[Grigorieff1983\] — the step after 2^k substeps would have the ratio 2^k —,
    /// and over a periodic cycle its flows sum to the change of content only where the ratio
    /// is 1 (`InverseStep`'s docs). Default: nothing (one-step schemes, models without a
    /// history).
    fn join_substeps(&self, _start: &Self::State, _end: &mut Self::State, _dt: f64) {}

    /// The volumes of oil (m³) that have left the film through its two ends and entered it
    /// through each groove up to `state`, integrated in time by the model's own scheme — the
    /// time integral the scheme applies to the film content, so that between any two states
    /// the content's change is the volume in minus the volume out, whatever the step lengths
    /// (`crate::reynolds::FilmState::boundary_volume`): `[end z = −L/2, end z = +L/2, groove
    /// 1, …]`. The inverse solver records a step's flows as its volumes over its length. None
    /// (default): the step's flows are those of its end (the mean of its parts' for a step
    /// taken in parts).
    fn boundary_volumes(&self, _state: &Self::State) -> Option<Vec<f64>> {
        None
    }

    /// The time scheme the model steps with, for the inverse solver's local error control
    /// ([`InverseParams::step_error_tolerance`]); None (default) for a model without one: no
    /// control.
    fn time_scheme(&self) -> Option<TimeScheme> {
        None
    }

    /// Named measures of the last step this model solved (its inner iterations, what changed
    /// between them), for the report of a stalled Newton ([`InverseStall::film`]). Default
    /// none.
    fn step_diagnostics(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }
}
