//! The universal Reynolds film (mass-conserving, [`crate::reynolds`]) as a [`FilmModel`].
//!
//! A thin adapter: one film step is one [`ReynoldsSolver::solve_step`] from the state at t^n to
//! the trial ε^{n+1}; the state is the solver's [`FilmState`] (ε, φ and g fields, the net
//! outflow Crank–Nicolson needs and the level before that BDF2 needs). The time discretisation
//! is the solver's ([`crate::reynolds::TimeScheme`]: BDF2 by default — second order and
//! L-stable; backward Euler gives a whirling film artificial load capacity, see
//! [`super::ClosedFormFilm`]'s docs, and Crank–Nicolson rings). The exact film-force Jacobian
//! of the last step ([`FilmModel::force_jacobian`]) is
//! [`ReynoldsSolver::film_force_jacobian`].
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
//! Sweep iterations reported per step: the Krylov (ADI-preconditioned) iterations summed over
//! the switch iterations of the accepted solve.

use super::{FilmFields, FilmModel, FilmModelError, FilmResponse};
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
}

impl ReynoldsFilm {
    /// A film for the given Reynolds parameters.
    pub fn new(params: ReynoldsParams) -> Result<Self, ReynoldsError> {
        Ok(Self {
            solver: ReynoldsSolver::new(params)?,
            capture: false,
            last: None,
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
        let start = self
            .last
            .as_ref()
            .filter(|(from, _)| *from == state.eccentricity_ratio)
            .map(|(_, s)| s);
        let (sol, next) = self.solver.solve_step_from(state, &input, start)?;
        self.last = Some((state.eccentricity_ratio, next.clone()));
        Ok((film_response(sol, self.capture), next))
    }

    fn state_change(&self, a: &FilmState, b: &FilmState) -> f64 {
        a.density_ratio
            .iter()
            .zip(b.density_ratio.iter())
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    fn set_capture_fields(&mut self, capture: bool) {
        self.capture = capture;
    }

    /// [`ReynoldsSolver::film_force_jacobian`]: two extra linear solves on the converged
    /// switch of the last step.
    fn force_jacobian(&mut self) -> Option<Result<[[f64; 2]; 2], FilmModelError>> {
        Some(
            self.solver
                .film_force_jacobian()
                .map_err(FilmModelError::from),
        )
    }
}
