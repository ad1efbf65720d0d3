//! The deformable bearing under a dynamic load: the elastic gap change in the inverse solver's
//! time steps, quasi-statically.
//!
//! ```text
//!   h^{n+1}(θ) = c − e_x^{n+1} cos θ − e_y^{n+1} sin θ + g^{n+1}(θ),
//!   g^{n+1} = C p̄^{n+1}(ε^{n+1}, g^{n+1})     to  max_k |C p̄ − g| ≤ tolerance · c
//! ```
//!
//! with the compliance C of the steady model ([`super::Compliance`], computed once) and p̄ the
//! film pressure averaged over the length at the structure's surface nodes (`coupling`).
//! Quasi-static: the structure's inertia is left out (the lowest natural frequency of a steel
//! bearing ring is in the kHz, the load's harmonics are at multiples of the crank speed) and so
//! is structural damping; the film's own squeeze term sees the deformation's rate through the
//! content h φ of the old and new levels, each with its own g (the time step of
//! [`crate::reynolds::ReynoldsSolver::solve_step`] with a deformation).
//!
//! Every trial film step of the inverse solver's Newton on ε solves its g by the steady
//! solve's Aitken-relaxed fixed point (`coupling`), started from the g of the last trial from
//! the same state (else from the state's own g, C p̄ of the level before). Why not lag g one step
//! (g^{n+1} = C p̄^n, one film solve per trial): the squeeze pressure of a gap change over one
//! step is ∝ Δg/Δt, so the explicit map g ↦ C p̄ amplifies by ~ C·S/Δt, which grows as the step
//! shrinks — measured on the unit test's bearing (steel, 48 nodes), the lagged film's force is
//! within 1 % of the iterated one at Δt = 1 ms but points the wrong way (a spurious state, ~10 %
//! of the load) at 0.1 ms: the partitioned "added-mass" instability of fluid–structure coupling
//! \[KuttlerWall2008\]. The iterated coupling is implicit and has no such limit.
//!
//! The inverse solver's Newton on ε sees F(ε, g(ε)): it takes forward differences of the
//! coupled step (the film's exact ∂F/∂ε at fixed g misses ∂F/∂g · dg/dε). The gap tolerance
//! must then keep the force noise below the Newton tolerance (1e-6 of the peak load by default):
//! a gap error δ moves a film of thickness h_min by δ/h_min, so δ ≈ 1e-7 c (2.5 pm on the
//! compressor rod bearing) — at 1e-4 c the rod's Newton stalls in its second cycle, measured.

use super::{Compliance, ElasticBearing, ElasticError};
use crate::inverse::{FilmModel, FilmModelError, FilmResponse, ReynoldsFilm};
use crate::reynolds::{
    FilmDeformation, FilmState, OperatingConditions, ReynoldsError, ReynoldsParams, SupplyModel,
};
use ndarray::Array2;

/// The film state of the deformable bearing: the Reynolds film's state (with the gap it had,
/// [`FilmState::deformation`]) and that gap at the structure's surface nodes.
#[derive(Debug, Clone)]
pub struct ElasticFilmState {
    pub film: FilmState,
    /// g of this level at the structure's surface nodes θ_k = 2πk/n, m (C p̄ to the tolerance).
    pub gap: Vec<f64>,
}

/// The mass-conserving Reynolds film with elastic shaft and housing, as a [`FilmModel`] of the
/// inverse solver (module docs).
#[derive(Debug)]
pub struct ElasticFilm {
    inner: ReynoldsFilm,
    compliance: Compliance,
    angles: Vec<f64>,
    ambient: f64,
    pub(crate) tolerance: f64,
    max_iterations: usize,
    min_relaxation: f64,
    capture: bool,
    /// The converged g of the last trial and the ε of the state it started from.
    last: Option<([f64; 2], Vec<f64>)>,
    /// Film solves so far (the fixed-point iterations of every trial).
    film_solves: usize,
}

impl ElasticFilm {
    /// The film of `params` (grooved supply: the time-stepping film's) coupled to `bearing`
    /// (meshed around the film's radius); g converged to `bearing.params.gap_tolerance` · c in
    /// at most `bearing.params.max_iterations` film solves per trial.
    pub fn new(params: ReynoldsParams, bearing: &ElasticBearing) -> Result<Self, ElasticError> {
        if params.supply != SupplyModel::Grooves {
            return Err(ElasticError::Film(ReynoldsError::Unsupported {
                what: "the dynamic deformable film steps the grooved film (SupplyModel::Grooves)",
            }));
        }
        let (ambient, clearance) = (params.ambient_pressure, params.clearance);
        Ok(Self {
            inner: ReynoldsFilm::new(params)?,
            compliance: bearing.compliance.clone(),
            angles: bearing.surface_angles(),
            ambient,
            tolerance: bearing.params.gap_tolerance * clearance,
            max_iterations: bearing.params.max_iterations,
            min_relaxation: bearing.params.min_relaxation,
            capture: false,
            last: None,
            film_solves: 0,
        })
    }

    /// Film solves so far.
    pub fn film_solves(&self) -> usize {
        self.film_solves
    }

    /// C p̄ of a film's pressure field (θ rows from θ = 0, the grooved film's grid).
    pub(crate) fn gap_of(&self, pressure: &Array2<f64>) -> Vec<f64> {
        let pbar = super::coupling::length_mean_at(pressure, 0.0, self.ambient, &self.angles);
        self.compliance.gap(&pbar)
    }
}

impl FilmModel for ElasticFilm {
    type State = ElasticFilmState;

    /// The film at rest: ambient pressure, no deformation.
    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> ElasticFilmState {
        let mut film = self.inner.initial_state(eccentricity_ratio);
        let gap = vec![0.0; self.compliance.len()];
        film.deformation = Some(FilmDeformation::new(gap.clone()).expect("zeros are finite"));
        ElasticFilmState { film, gap }
    }

    fn step(
        &mut self,
        state: &ElasticFilmState,
        eccentricity_ratio: [f64; 2],
        dt: f64,
        conditions: &OperatingConditions,
    ) -> Result<(FilmResponse, ElasticFilmState), FilmModelError> {
        self.inner.set_capture_fields(true);
        let from = state.film.eccentricity_ratio;
        let mut g = match &self.last {
            Some((eps, g)) if *eps == from => g.clone(),
            _ => state.gap.clone(),
        };
        let mut omega = 1.0;
        let mut previous: Option<Vec<f64>> = None;
        let mut last = f64::INFINITY;
        for _ in 0..self.max_iterations {
            self.inner
                .solver_mut()
                .set_deformation(Some(FilmDeformation::new(g.clone())?));
            let (mut response, film) =
                self.inner
                    .step(&state.film, eccentricity_ratio, dt, conditions)?;
            self.film_solves += 1;
            let target = self.gap_of(
                &response
                    .fields
                    .as_ref()
                    .expect("the inner film captures its fields")
                    .pressure,
            );
            let r: Vec<f64> = target.iter().zip(&g).map(|(t, g)| t - g).collect();
            last = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if !last.is_finite() {
                return Err(FilmModelError::NonFinite {
                    quantity: "elastic gap residual",
                });
            }
            if last <= self.tolerance {
                if !self.capture {
                    response.fields = None;
                }
                self.last = Some((from, g.clone()));
                return Ok((response, ElasticFilmState { film, gap: g }));
            }
            if let Some(prev) = &previous {
                omega = super::coupling::aitken(omega, prev, &r).clamp(self.min_relaxation, 1.0);
            }
            for (gk, rk) in g.iter_mut().zip(&r) {
                *gk += omega * rk;
            }
            previous = Some(r);
        }
        Err(FilmModelError::NotConverged {
            what: "elastic gap change",
            iterations: self.max_iterations,
            residual: last,
            tolerance: self.tolerance,
        })
    }

    fn state_change(&self, a: &ElasticFilmState, b: &ElasticFilmState) -> f64 {
        self.inner.state_change(&a.film, &b.film)
    }

    fn set_capture_fields(&mut self, capture: bool) {
        self.capture = capture;
    }

    /// None: the inverse solver takes forward differences of the coupled step, whose g moves
    /// with ε (the film's exact ∂F/∂ε at fixed g is not the coupled Jacobian).
    fn force_jacobian(&mut self) -> Option<Result<[[f64; 2]; 2], FilmModelError>> {
        None
    }
}
