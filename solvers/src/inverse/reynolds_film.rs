//! The universal Reynolds film (mass-conserving, [`crate::reynolds`]) as a [`FilmModel`].
//!
//! A thin adapter: one film step is one [`ReynoldsSolver::solve_step`] from the state at t^n to
//! the trial ε^{n+1}; the state is the solver's [`FilmState`] (ε, φ and g fields, the net
//! outflow Crank–Nicolson needs and the level before that BDF2 needs). The time discretisation
//! is the solver's ([`crate::reynolds::TimeScheme`]: BDF2 by default — second order and
//! L-stable; backward Euler gives a whirling film artificial load capacity, see
//! [`super::ClosedFormFilm`]'s docs, and Crank–Nicolson rings). The exact film-force Jacobian
//! of the last step ([`FilmModel::force_jacobian`]) is
//! [`ReynoldsSolver::film_force_jacobian_to`] 1e-2 (`NEWTON_JACOBIAN_TOLERANCE`: the two digits
//! Newton on ε needs; the public [`ReynoldsSolver::film_force_jacobian`] solves to 1e-5).
//!
//! Periodicity of the film field: [`FilmModel::state_change`] is max |Δφ| over the grid
//! (φ = density ratio in full film, film fraction in cavitated film).
//!
//! Newton iterates of one time step all start from the same state at t^n; each film step after
//! the first starts its switch and Krylov iterations from the previous iterate's answer
//! ([`ReynoldsSolver::solve_step_from`]) instead of from the old state: the same discrete
//! solution (to the solver tolerance) in fewer iterations (constant-load test 9.4 s → 5.5 s,
//! periodic mass-balance run at 120 × 31 150 s → 57 s).
//!
//! The first film step from a new state (the first Newton iterate of a time step) starts from
//! the film extrapolated linearly in time through the last two states stepped from,
//!
//! ```text
//!   φ⁰ = max(0, φⁿ + (Δt / Δt_prev) (φⁿ − φⁿ⁻¹)),   g⁰ = [φ⁰ ≥ 1]
//! ```
//!
//! instead of from φⁿ itself ([`ReynoldsSolver::solve_step_from`]; the answer is the same
//! discrete solution to the solver's tolerance, the complementarity problem of a step having
//! one solution). On the compressor-size cycle (120 × 31, 1°, timing report) the first film
//! steps of the time steps took 8.4 Krylov iterations each from φⁿ; the extrapolation brings
//! the mean over all film steps from 6.1 to 5.2 and the instructions of the run from 23.45e9
//! to 22.02e9 (−6 %). A quadratic extrapolation through three states was worse (6.1 Krylov
//! iterations per film step: the film fraction is not smooth in time where a node switches),
//! and so were the weights 0.5, 0.8 and 1.2 on the linear term (5.8, 5.6, 5.9).
//!
//! A relaxed step ([`FilmModel::relax_next_step`], the inverse solver's iterates far from
//! their answer) is [`ReynoldsSolver::solve_step_to`] a relative mass residual of
//! min(0.1 × the force accuracy asked, 1e-6) (`MASS_PER_FORCE`, `RELAXED_CAP`): its
//! semismooth Newton stops once its loose solves have the switch pattern, without the tight
//! solve (on the compressor-size cycle, 120 × 31, 1°: Krylov iterations per time step 18.0 →
//! 14.9). When the loose force balances the load within the caller's band, the step goes on
//! from the loose answer to the solver's tolerance (one step: the same answer as a tight
//! solve), so the iterate the caller accepts is never a loose film. A step left loose is a
//! trial (`ReynoldsSolver::solve_trial_step_to`): its friction torques and power loss are NaN,
//! never read (the inverse solver accepts only tightly solved iterates, and refuses, naming
//! the step, an accepted response whose friction outputs are not finite); the dissipation sum
//! they skip was 3.7 % of the instructions of the compressor-size cycle when evaluated for
//! every film step.
//!
//! Sweep iterations reported per step: the Krylov (ADI-preconditioned) iterations summed over
//! the switch iterations of the accepted solve.

use super::{FilmFields, FilmModel, FilmModelError, FilmResponse, RelaxedStep};
use crate::reynolds::{
    FilmSolution, FilmState, OperatingConditions, ReynoldsError, ReynoldsParams, ReynoldsSolver,
    StepInput,
};

/// [`ReynoldsSolver`] behind the [`FilmModel`] interface.
#[derive(Debug)]
pub struct ReynoldsFilm {
    solver: ReynoldsSolver,
    capture: bool,
    /// The last step's answer and the ε of the state it started from: the next step from the
    /// same state (the next Newton iterate) starts its iterations there.
    last: Option<([f64; 2], FilmState)>,
    /// The next step's relaxation ([`FilmModel::relax_next_step`]).
    relax: Option<RelaxedStep>,
    /// Whether the last step was left at a relaxed tolerance.
    last_relaxed: bool,
    /// The state the steps start from now and the one before it (the last two time levels),
    /// for the extrapolated start of a new state's first step (module docs).
    history: StepHistory,
}

/// A time level the film has been stepped from: ε, φ, its boundary volumes (which a state
/// stepped from it records as its `previous_boundary_volume`: the link that says it is this
/// level's successor), and the Δt of the last step taken from it.
#[derive(Debug, Clone)]
struct SteppedFrom {
    eccentricity_ratio: [f64; 2],
    density_ratio: ndarray::Array2<f64>,
    boundary_volume: Vec<f64>,
    dt: f64,
}

/// The last two levels stepped from ([`ReynoldsFilm`]'s extrapolated start).
#[derive(Debug, Clone, Default)]
struct StepHistory {
    now: Option<SteppedFrom>,
    before: Option<SteppedFrom>,
}

impl StepHistory {
    /// Record a step of length `dt` from `state`: a state other than the current one (by ε)
    /// becomes the current one and the current one the level before.
    fn record(&mut self, state: &FilmState, dt: f64) {
        match &mut self.now {
            Some(now) if now.eccentricity_ratio == state.eccentricity_ratio => now.dt = dt,
            _ => {
                self.before = self.now.take();
                self.now = Some(SteppedFrom {
                    eccentricity_ratio: state.eccentricity_ratio,
                    density_ratio: state.density_ratio.clone(),
                    boundary_volume: state.boundary_volume.clone(),
                    dt,
                });
            }
        }
    }

    /// The start of a step of length `dt` to `eccentricity_ratio` from `state` (the current
    /// level): φ extrapolated linearly in time from the level before through `state`, the
    /// switch full where φ ≥ 1 (module docs). None when there is no level before of this grid,
    /// when `state` was not stepped from it (its `previous_boundary_volume` is not that
    /// level's boundary volume: a new run's start, a state from elsewhere), when `state` is
    /// deformed (its gap is not part of φ), when the step that left the level before is not
    /// the one BDF2 says led to `state`, or when Δt / Δt_prev is outside (0, 2] (a restart
    /// after a step-length cut: φⁿ itself).
    fn extrapolated_start(
        &self,
        state: &FilmState,
        eccentricity_ratio: [f64; 2],
        dt: f64,
    ) -> Option<FilmState> {
        let before = self.before.as_ref()?;
        if state.deformation.is_some()
            || before.density_ratio.dim() != state.density_ratio.dim()
            || state.previous_boundary_volume.as_ref() != Some(&before.boundary_volume)
        {
            return None;
        }
        if let Some((_, dt_led)) = &state.previous_level
            && (dt_led - before.dt).abs() > 1e-9 * before.dt
        {
            return None;
        }
        let ratio = dt / before.dt;
        if !(ratio > 0.0 && ratio <= 2.0) {
            return None;
        }
        let mut density_ratio = state.density_ratio.clone();
        ndarray::Zip::from(&mut density_ratio)
            .and(&before.density_ratio)
            .for_each(|phi, &phi_before| {
                *phi = (*phi + ratio * (*phi - phi_before)).max(0.0);
            });
        if density_ratio.iter().any(|phi| !phi.is_finite()) {
            return None;
        }
        let full_film = density_ratio.mapv(|phi| phi >= 1.0);
        // At the step's own ε: the start is a guess of this very step, which the solver's
        // sensitivity prediction (for an iterate of another ε) must not move.
        // Only ε, φ and the switch: the solver reads nothing else of a start.
        Some(FilmState::film_only(
            eccentricity_ratio,
            density_ratio,
            full_film,
        ))
    }
}

impl ReynoldsFilm {
    /// A film for the given Reynolds parameters.
    pub fn new(params: ReynoldsParams) -> Result<Self, ReynoldsError> {
        Ok(Self {
            solver: ReynoldsSolver::new(params)?,
            capture: false,
            last: None,
            relax: None,
            last_relaxed: false,
            history: StepHistory::default(),
        })
    }

    /// The underlying solver (for steady solves beside the inverse run).
    pub fn solver_mut(&mut self) -> &mut ReynoldsSolver {
        &mut self.solver
    }
}

impl From<ReynoldsSolver> for ReynoldsFilm {
    fn from(solver: ReynoldsSolver) -> Self {
        Self {
            solver,
            capture: false,
            last: None,
            relax: None,
            last_relaxed: false,
            history: StepHistory::default(),
        }
    }
}

/// The inverse solver's view of a Reynolds solution.
pub fn film_response(sol: FilmSolution, capture: bool) -> FilmResponse {
    let fields = capture.then(|| FilmFields {
        pressure: sol.pressure.clone(),
        film_fraction: sol.film_fraction.clone(),
        switch: sol.switch.clone(),
    });
    FilmResponse {
        film_force: sol.film_force,
        min_film_thickness: sol.min_film_thickness,
        min_film_location: sol.min_film_location,
        max_pressure: sol.max_pressure,
        max_pressure_location: sol.max_pressure_location,
        cavitated_fraction: sol.cavitated_fraction,
        side_leakage: sol.side_leakage,
        supply_flow: sol.supply_flow,
        recirculated_flow: sol.recirculated_flow,
        friction_torque_journal: sol.friction_torque_journal,
        friction_torque_bearing: sol.friction_torque_bearing,
        power_loss: sol.power_loss,
        sweep_iterations: sol.linear_iterations,
        fields,
    }
}

impl FilmModel for ReynoldsFilm {
    type State = FilmState;

    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> FilmState {
        self.solver.initial_state(eccentricity_ratio)
    }

    fn step(
        &mut self,
        state: &FilmState,
        eccentricity_ratio: [f64; 2],
        dt: f64,
        conditions: &OperatingConditions,
    ) -> Result<(FilmResponse, FilmState), FilmModelError> {
        let e = eccentricity_ratio[0].hypot(eccentricity_ratio[1]);
        if e.is_nan() || e >= 1.0 {
            return Err(FilmModelError::OutsideClearance { eccentricity: e });
        }
        let input = StepInput {
            eccentricity_ratio,
            dt,
            conditions: conditions.clone(),
        };
        self.history.record(state, dt);
        let extrapolated;
        let start = match self
            .last
            .as_ref()
            .filter(|(from, _)| *from == state.eccentricity_ratio)
        {
            Some((_, previous_iterate)) => Some(previous_iterate),
            None => {
                extrapolated = self
                    .history
                    .extrapolated_start(state, eccentricity_ratio, dt);
                extrapolated.as_ref()
            }
        };
        self.last_relaxed = false;
        let own = self.solver.params().tolerance;
        let relaxed = self.relax.take().and_then(|r| {
            let tolerance = (MASS_PER_FORCE * r.accuracy).min(RELAXED_CAP);
            (tolerance > own).then_some((r, tolerance))
        });
        // Fields only for a captured step (`film_response` drops them otherwise); the solver
        // is handed back with its default (fields) whatever the outcome.
        self.solver.set_step_fields(self.capture);
        let solved = (|| match relaxed {
            None => self.solver.solve_step_from(state, &input, start),
            Some((r, tolerance)) => {
                let (loose, next) = self
                    .solver
                    .solve_trial_step_to(state, &input, start, tolerance)?;
                let miss = (loose.film_force[0] + r.load[0]).hypot(loose.film_force[1] + r.load[1]);
                if miss <= r.finish_within {
                    // An iterate the caller may accept: finish it from the loose answer.
                    let (mut sol, next) =
                        self.solver.solve_step_from(state, &input, Some(&next))?;
                    sol.linear_iterations += loose.linear_iterations;
                    Ok((sol, next))
                } else {
                    self.last_relaxed = true;
                    Ok((loose, next))
                }
            }
        })();
        self.solver.set_step_fields(true);
        let (sol, next) = solved?;
        self.last = Some((
            state.eccentricity_ratio,
            // A start for the next trial: the solver reads only ε, φ and the switch of it, so
            // the rest of the state (three more whole-grid arrays) is neither copied nor kept.
            FilmState::film_only(
                next.eccentricity_ratio,
                next.density_ratio.clone(),
                next.full_film.clone(),
            ),
        ));
        Ok((film_response(sol, self.capture), next))
    }

    fn state_change(&self, a: &FilmState, b: &FilmState) -> f64 {
        a.density_ratio
            .iter()
            .zip(b.density_ratio.iter())
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    /// φ, then the BDF2 level before (content h φ) and the net outflow (Crank–Nicolson's Dⁿ)
    /// where the state has them. The gap change of an elastic film is not part of it (None:
    /// such states are not extrapolated).
    fn state_vector(&self, state: &FilmState) -> Option<Vec<f64>> {
        if state.deformation.is_some() {
            return None;
        }
        let mut v: Vec<f64> = state.density_ratio.iter().copied().collect();
        if let Some((content, _)) = &state.previous_level {
            v.extend(content.iter());
        }
        if let Some(outflow) = &state.net_outflow {
            v.extend(outflow.iter());
        }
        Some(v)
    }

    /// φ ≥ 0 (a film fraction cannot be negative), the switch full where ψ = φ − 1 ≥ 0, the
    /// old content ≥ 0; the BDF2 step length of `template`.
    fn state_from_vector(
        &self,
        template: &FilmState,
        eccentricity_ratio: [f64; 2],
        vector: &[f64],
    ) -> Option<FilmState> {
        let n = template.density_ratio.len();
        let expected = n
            * (1 + usize::from(template.previous_level.is_some())
                + usize::from(template.net_outflow.is_some()));
        if vector.len() != expected || template.deformation.is_some() {
            return None;
        }
        let shape = template.density_ratio.dim();
        let field = |part: &[f64], floor: f64| {
            ndarray::Array2::from_shape_vec(shape, part.iter().map(|v| v.max(floor)).collect()).ok()
        };
        let mut parts = vector.chunks(n);
        let density_ratio = field(parts.next()?, 0.0)?;
        let previous_level = match &template.previous_level {
            Some((_, dt)) => Some((field(parts.next()?, 0.0)?, *dt)),
            None => None,
        };
        let net_outflow = match &template.net_outflow {
            Some(_) => Some(field(parts.next()?, f64::NEG_INFINITY)?),
            None => None,
        };
        Some(FilmState {
            eccentricity_ratio,
            full_film: density_ratio.mapv(|phi| phi >= 1.0),
            density_ratio,
            net_outflow,
            previous_level,
            deformation: None,
            // The volumes count from the start of the solve and are not periodic: the
            // template's (the last state before the extrapolation) carry on.
            boundary_flow: template.boundary_flow.clone(),
            boundary_volume: template.boundary_volume.clone(),
            previous_boundary_volume: template.previous_boundary_volume.clone(),
        })
    }

    /// BDF2's level before becomes the content and the boundary volumes at `start`, one step
    /// `dt` back (the trait's docs); the other schemes keep no level before.
    fn join_substeps(&self, start: &FilmState, end: &mut FilmState, dt: f64) {
        if end.previous_level.is_some() {
            // `start` is a state of this film's solver (the substeps' start).
            let content = self.solver.film_content(start);
            end.previous_level = Some((content.expect("a state of the film's own grid"), dt));
            end.previous_boundary_volume = Some(start.boundary_volume.clone());
        }
    }

    /// [`FilmState::boundary_volume`]: the side leakage at both ends and the supply of each
    /// groove integrated by the scheme of each step.
    fn boundary_volumes(&self, state: &FilmState) -> Option<Vec<f64>> {
        (!state.boundary_volume.is_empty()).then(|| state.boundary_volume.clone())
    }

    fn set_capture_fields(&mut self, capture: bool) {
        self.capture = capture;
    }

    /// The next step's relative mass residual tolerance becomes min(0.1 × `accuracy`, 1e-6)
    /// when that is looser than the solver's own (module docs).
    fn relax_next_step(&mut self, relax: RelaxedStep) {
        self.relax = Some(relax);
    }

    fn last_step_relaxed(&self) -> bool {
        self.last_relaxed
    }

    fn time_scheme(&self) -> Option<crate::time_scheme::TimeScheme> {
        Some(self.solver.params().time_scheme)
    }

    /// [`ReynoldsSolver::film_force_jacobian_to`] `NEWTON_JACOBIAN_TOLERANCE`: two extra
    /// linear solves on the converged switch of the last step, to the two digits a Newton
    /// iteration on ε needs.
    fn force_jacobian(&mut self) -> Option<Result<[[f64; 2]; 2], FilmModelError>> {
        Some(
            self.solver
                .film_force_jacobian_to(NEWTON_JACOBIAN_TOLERANCE)
                .map_err(FilmModelError::from),
        )
    }
}

/// Relative tolerance of the film-force Jacobian's two linear solves for the Newton iterations
/// on ε (the inverse cycle's and the slider-crank's, [`FilmModel::force_jacobian`]). A Jacobian
/// that errs by a relative δ turns Newton's quadratic convergence into a linear one of rate
/// ~δ (‖e₊‖ ≤ K(‖e‖² + δ ‖e‖), \[Kelley1995\] §5.4): at δ = 1e-2 each Newton step still
/// gains two digits. Measured on the compressor-size inverse cycle
/// (120 × 31, 1°, `inverse_timing --default`, callgrind): 1e-5 / 1e-3 / 1e-2 gave the same
/// 2.46 film steps per time step, 4.7 Krylov iterations per film step, h_min and power loss,
/// and 17.45e9 / 17.22e9 / 17.05e9 instructions (−2.3 % at 1e-2); every validation block
/// regenerated at 1e-2 moved at most in its last printed digit. The public
/// [`ReynoldsSolver::film_force_jacobian`] keeps 1e-5 (four or five digits).
const NEWTON_JACOBIAN_TOLERANCE: f64 = 1e-2;

/// The film tolerance (relative mass residual) of a relaxed step per unit of the force accuracy
/// asked: measured on the compressor-size inverse cycle (120 × 31, 1°), the film force of a
/// step solved to 1e-6 differed from the same step solved to 1e-10 by at most 8.5e-6 of the
/// residual scale (median 9e-8, 451 steps): the force error is below ~10 × the mass tolerance.
const MASS_PER_FORCE: f64 = 0.1;

/// The loosest film tolerance of a relaxed step: its force then errs by at most ~1e-5 of the
/// scale (`MASS_PER_FORCE`). A cap of 1e-4 left force errors up to 7.6e-4 of the scale and
/// stalled steps (11 on the same cycle). (The semismooth Newton's own loose level, 1e-5 since
/// 2026-11-28, is for its infeasible steps only: a relaxed step still ends with a solve to
/// this tolerance once its switch is right.)
const RELAXED_CAP: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reynolds::{GridParams, Groove, ReynoldsParams};

    fn film() -> ReynoldsFilm {
        let mut p = ReynoldsParams::plain(0.025, 0.025, 50e-6, 0.03);
        p.grid = GridParams {
            n_theta: 48,
            n_z: 13,
        };
        p.grooves = vec![Groove {
            center_angle: std::f64::consts::FRAC_PI_2,
            center_z: 0.0,
            angular_width: 0.2,
            axial_width: 0.008,
            cutoff_film_fraction: 0.01,
        }];
        ReynoldsFilm::new(p).unwrap()
    }

    /// The extrapolated start: φⁿ + (Δt/Δt_prev)(φⁿ − φⁿ⁻¹) clipped at 0, full where ≥ 1, at
    /// the step's ε; none without a level before, for a state not stepped from it, a deformed
    /// state, a step-length ratio outside (0, 2], or a BDF2 state not led to by the recorded
    /// step.
    #[test]
    fn the_start_is_the_film_extrapolated_in_time() {
        let m = film();
        let mut before = m.initial_state([0.1, 0.0]);
        before.density_ratio.fill(0.9);
        before.density_ratio[[3, 4]] = 1.2;
        before.boundary_volume = vec![1e-9, 2e-9, -3e-9];
        let mut now = m.initial_state([0.2, 0.0]);
        now.density_ratio.fill(1.0);
        now.density_ratio[[3, 4]] = 0.1;
        now.previous_boundary_volume = Some(before.boundary_volume.clone());
        let mut history = StepHistory::default();
        history.record(&before, 2e-4);
        history.record(&before, 1e-4); // a second iterate from the same level: Δt updated
        history.record(&now, 5e-5);
        assert!(
            StepHistory::default()
                .extrapolated_start(&now, [0.3, 0.0], 5e-5)
                .is_none()
        );
        let start = history.extrapolated_start(&now, [0.3, 0.0], 5e-5).unwrap();
        assert_eq!(start.eccentricity_ratio, [0.3, 0.0]);
        // Ratio 0.5: 1 + 0.5 (1 − 0.9) = 1.05 (full); 0.1 + 0.5 (0.1 − 1.2) < 0 → 0.
        assert!((start.density_ratio[[0, 0]] - 1.05).abs() < 1e-15);
        assert!(start.full_film[[0, 0]]);
        assert_eq!(start.density_ratio[[3, 4]], 0.0);
        assert!(!start.full_film[[3, 4]]);
        // Ratio 2 is allowed, beyond it not.
        assert!(history.extrapolated_start(&now, [0.3, 0.0], 2e-4).is_some());
        assert!(
            history
                .extrapolated_start(&now, [0.3, 0.0], 2.1e-4)
                .is_none()
        );
        // A BDF2 state says which step led to it: not the recorded one → no extrapolation.
        let mut led = now.clone();
        led.previous_level = Some((now.density_ratio.clone(), 5e-5));
        assert!(history.extrapolated_start(&led, [0.3, 0.0], 5e-5).is_none());
        led.previous_level = Some((now.density_ratio.clone(), 1e-4));
        assert!(history.extrapolated_start(&led, [0.3, 0.0], 5e-5).is_some());
        // A state not stepped from the level before (a new run's start, say): none.
        let mut elsewhere = now.clone();
        elsewhere.previous_boundary_volume = Some(vec![0.0; 3]);
        assert!(
            history
                .extrapolated_start(&elsewhere, [0.3, 0.0], 5e-5)
                .is_none()
        );
        elsewhere.previous_boundary_volume = None;
        assert!(
            history
                .extrapolated_start(&elsewhere, [0.3, 0.0], 5e-5)
                .is_none()
        );
        // A deformed state's gap is not part of φ.
        let mut deformed = now.clone();
        deformed.deformation = Some(crate::reynolds::FilmDeformation::new(vec![0.0; 8]).unwrap());
        assert!(
            history
                .extrapolated_start(&deformed, [0.3, 0.0], 5e-5)
                .is_none()
        );
    }

    /// A first step started from the extrapolated film is the same discrete solution as the
    /// step from φⁿ (the solver's tolerance): switch and force, on a squeezing film whose
    /// cavity moves from step to step.
    #[test]
    fn an_extrapolated_start_gives_the_same_step() {
        let cond = OperatingConditions {
            journal_speed: 300.0,
            bearing_speed: 0.0,
            feed_pressures: vec![0.2e5],
        };
        let dt = 2e-4;
        let path = [[0.50, -0.20], [0.55, -0.10], [0.58, 0.02], [0.60, 0.15]];
        let mut with_history = film();
        let mut state = with_history.initial_state(path[0]);
        for eps in &path[1..3] {
            state = with_history.step(&state, *eps, dt, &cond).unwrap().1;
        }
        // What `step` does first: the state stepped from becomes the current level.
        let mut history = with_history.history.clone();
        history.record(&state, dt);
        let start = history.extrapolated_start(&state, path[3], dt).unwrap();
        let moved = start
            .density_ratio
            .iter()
            .zip(&state.density_ratio)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(moved > 1e-2, "the film moves between steps: {moved}");
        let (extrapolated, extrapolated_state) =
            with_history.step(&state, path[3], dt, &cond).unwrap();
        let (plain, plain_state) = film().step(&state, path[3], dt, &cond).unwrap();
        assert_eq!(extrapolated_state.full_film, plain_state.full_film);
        assert_ne!(plain_state.full_film, state.full_film, "the cavity moves");
        let f = plain.film_force[0].hypot(plain.film_force[1]);
        for k in 0..2 {
            assert!(
                (extrapolated.film_force[k] - plain.film_force[k]).abs() < 1e-8 * f,
                "{:?} vs {:?}",
                extrapolated.film_force,
                plain.film_force
            );
        }
    }

    /// A relaxed step whose force misses the load is left loose (and says so); one whose force
    /// balances the load to within `finish_within` is finished in the same step to the
    /// solver's tolerance: the tight film's force and switch, not a loose answer.
    #[test]
    fn a_relaxed_step_is_finished_only_when_it_may_be_accepted() {
        let cond = OperatingConditions {
            journal_speed: 300.0,
            bearing_speed: 0.0,
            feed_pressures: vec![2e5],
        };
        let dt = 1e-4;
        let eps = [0.5, -0.3];
        let mut m = film();
        let state = m.initial_state([0.49, -0.3]);
        let (tight, tight_state) = m.step(&state, eps, dt, &cond).unwrap();
        assert!(!m.last_step_relaxed());
        let f = tight.film_force[0].hypot(tight.film_force[1]);
        let relax = |load: [f64; 2]| RelaxedStep {
            accuracy: 0.1,
            load,
            finish_within: 1e-4 * f,
        };
        // Far from balancing: loose.
        let mut m = film();
        m.relax_next_step(relax([0.0, 0.0]));
        let (loose, _) = m.step(&state, eps, dt, &cond).unwrap();
        assert!(m.last_step_relaxed());
        assert!(loose.sweep_iterations < tight.sweep_iterations);
        // The relaxation is for one step only.
        m.step(&state, eps, dt, &cond).unwrap();
        assert!(!m.last_step_relaxed());
        // Balancing the load: finished.
        let mut m = film();
        m.relax_next_step(relax([-tight.film_force[0], -tight.film_force[1]]));
        let (finished, finished_state) = m.step(&state, eps, dt, &cond).unwrap();
        assert!(!m.last_step_relaxed());
        assert_eq!(finished_state.full_film, tight_state.full_film);
        for k in 0..2 {
            assert!(
                (finished.film_force[k] - tight.film_force[k]).abs() < 1e-8 * f,
                "{:?} vs {:?}",
                finished.film_force,
                tight.film_force
            );
        }
    }

    /// A step the adapter does not capture builds no fields (the solver skips them: the same
    /// step otherwise), a captured one has them, and the solver is handed back with its fields
    /// on: a direct `solve_step` on it after an uncaptured step has them too.
    #[test]
    fn fields_are_built_only_for_captured_steps() {
        let cond = OperatingConditions {
            journal_speed: 300.0,
            bearing_speed: 0.0,
            feed_pressures: vec![2e5],
        };
        let (dt, eps) = (1e-4, [0.5, -0.3]);
        let mut m = film();
        let state = m.initial_state([0.49, -0.3]);
        m.set_capture_fields(false);
        let (bare, bare_next) = m.step(&state, eps, dt, &cond).unwrap();
        assert!(bare.fields.is_none());
        let input = StepInput {
            eccentricity_ratio: eps,
            dt,
            conditions: cond.clone(),
        };
        let (direct, direct_next) = m.solver_mut().solve_step(&state, &input).unwrap();
        assert!(
            !direct.pressure.is_empty(),
            "the solver keeps its fields on"
        );
        assert_eq!(direct_next, bare_next);
        assert_eq!(direct.film_force, bare.film_force);
        let mut m = film();
        m.set_capture_fields(true);
        let (captured, _) = m.step(&state, eps, dt, &cond).unwrap();
        let fields = captured.fields.expect("captured");
        assert_eq!(fields.pressure, direct.pressure);
        assert_eq!(fields.switch, direct.switch);
    }
}
