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
//! Time accuracy: the coupled step is the film's scheme (backward Euler, BDF2 or Crank–Nicolson,
//! [`crate::reynolds::TimeScheme`]) applied to the content (h₀ + g) φ, each old level with its own
//! g, and has the scheme's order (tests `bdf2_balance_holds_with_a_moving_gap`: the variable-step
//! BDF2 balance of a film under a prescribed moving gap closes to 6.9e-11 of the leakage;
//! `coupled_step_halving_gives_each_schemes_order`: observed orders 0.90 / 1.95 / 1.86 on a
//! whirling journal). The gap adds a time scale of its own: a pressure change is taken up by the
//! structure and the film's squeeze together within τ, of the order of 12 μ C L²/h³ (C the
//! compliance per pressure, h the film; 0.24 ms on the unit tests' steel bearing, measured from the
//! decay of a film loaded from rest), and the order shows only for Δt well below τ — the ratio 2.06
//! (2.2 with the gap to 1e-10 c) of the force differences at Δt = 0.2 / 0.1 / 0.05 ms (Δt/τ ≈ 0.8
//! at the coarsest), recorded in issue 15 as first order, is 4.06 at 0.1 / 0.05 / 0.025 ms
//! (`dynamic_film_between_its_limits_and_in_time`).
//!
//! Every trial film step of the inverse solver's Newton on ε solves its g by the steady
//! solve's Aitken-relaxed fixed point (`coupling`), started from the g of the last trial from
//! the same state moved along the tangent, g₀ = g_last + dg/dε · (ε − ε_last), with the dg/dε
//! of the coupled Jacobian's last evaluation from this state (below; without one, the last
//! trial's g; for a new state, the state's own g, C p̄ of the level before). Why not lag g one step
//! (g^{n+1} = C p̄^n, one film solve per trial): the squeeze pressure of a gap change over one
//! step is ∝ Δg/Δt, so the explicit map g ↦ C p̄ amplifies by ~ C·S/Δt, which grows as the step
//! shrinks — measured on the unit test's bearing (steel, 48 nodes), the lagged film's force is
//! within 1 % of the iterated one at Δt = 1 ms but points the wrong way (a spurious state, ~10 %
//! of the load) at 0.1 ms: the partitioned "added-mass" instability of fluid–structure coupling
//! \[KuttlerWall2008\]. The iterated coupling is implicit and has no such limit.
//!
//! The inverse solver's Newton on ε sees F(ε, g(ε)), and this film gives it the exact
//! Jacobian of that coupled map ([`FilmModel::force_jacobian`]), by the implicit function
//! theorem at the converged gap g = C p̄(ε, g):
//!
//! ```text
//!   dF/dε = ∂F/∂ε + ∂F/∂g · dg/dε,      (I − C ∂p̄/∂g) dg/dε = C ∂p̄/∂ε
//! ```
//!
//! ∂F/∂ε, ∂p̄/∂ε at fixed g are the film's own linearization (two linear solves on the
//! converged switch, as the rigid film's Jacobian); a gap change enters the film exactly as a
//! film-thickness change, so ∂p̄/∂g · v is one more linear solve on the same matrix
//! ([`crate::reynolds::ReynoldsSolver::thickness_responses`]). The n × n system (n structure
//! nodes around) is solved matrix-free by GMRES to 1e-5 (its operator is known to that), one
//! film linear solve per iteration; the force responses of the Krylov basis are kept, so
//! ∂F/∂g · dg/dε costs no extra solve. Why GMRES and not a fixed point on dg/dε: the fixed
//! point converges at the coupled iteration's rate (which needs Aitken relaxation from
//! ω₀ = 0.1 on steel), GMRES in as many iterations as C ∂p̄/∂g has significant eigenvalues,
//! and it does not need the coupling to contract. Why not Newton on (ε, g) per step: it would
//! replace the Aitken gap iteration as well, a larger change to the inverse solver's step
//! (n + 2 unknowns), for the same linear algebra; the Newton on ε with the exact Jacobian
//! converges without the stalls the forward differences of an iterated map gave (issue 15:
//! 581 of 2700 steps on the compressor rod). The test `coupled_force_jacobian_matches_differences`
//! checks this Jacobian against central differences of the converged coupled step (BE and
//! BDF2: 1.3e-6 and 1.8e-6 of its norm; the fixed-g Jacobian is off by 2–3 times its norm).
//!
//! The gap tolerance bounds the force noise the Newton sees, and it must sit well below what
//! the Newton needs: a gap error δ moves a film of thickness h_min by δ/h_min, so the Newton
//! tolerance (1e-6 of the load, the application's default) at h_min ≈ 0.16 c needs
//! δ ≲ 1.6e-7 c, and a tenth of that, 1e-8 c, is the tolerance to use. Why a tenth, measured on the compressor rod
//! ([`FilmModel::step_diagnostics`] of every stalled step, logged by the application): a trial
//! starts from the gap of the Newton's previous trial, and near the root the Newton's
//! corrections move ε so little that this gap already satisfies the tolerance — the trial is
//! accepted after one film solve with the old gap, so the force the Newton sees is frozen in g
//! at the scale of its last corrections and jumps by up to ∂F/∂g · δ between them. At 1e-7 c
//! every one of the 65 stalled steps of 12 cycles (residual up to 7.2e-6 of the load) ended on
//! such a one-solve trial (gap residual 7e-9 … 9.9e-8 c), with no node switching between the
//! trials or within the gap iteration; at 1e-8 c no step stalls, on the same orbit, and the
//! Newton needs fewer iterations (4.0 against 5.1 per step), which pays for the gap iterations.
//!
//! Two changes followed (2026-11-27). The start along dg/dε keeps the force of an accepted
//! one-solve trial consistent with the Newton's Jacobian to second order in its correction
//! (`trial_gap_starts_along_the_gap_sensitivity`: the force change of an ε step of 1e-6 at a
//! loose 1e-6 c matches the converged one to 2.7e-5, the kept gap misses it by 0.27). And the
//! tolerance is its own parameter, [`super::ElasticParams::dynamic_gap_tolerance`], by default
//! [`super::ElasticParams::dynamic_gap_tolerance_for`] the Newton's force tolerance (1e-8 c at
//! 1e-6), separate from the steady solve's 1e-5 c: the application runs it when a case leaves
//! `gap_tolerance` out, and the compressor rod's validated run is that default (0 stalled
//! steps, docs/validation.md).

use super::{Compliance, ElasticBearing, ElasticError};
use crate::inverse::{FilmModel, FilmModelError, FilmResponse, ReynoldsFilm};
use crate::reynolds::{
    FilmDeformation, FilmState, OperatingConditions, ReynoldsError, ReynoldsParams, SupplyModel,
    ThicknessChange,
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
    pub(crate) inner: ReynoldsFilm,
    compliance: Compliance,
    angles: Vec<f64>,
    ambient: f64,
    pub(crate) tolerance: f64,
    /// c (m), the scale of the gap tolerance.
    clearance: f64,
    max_iterations: usize,
    min_relaxation: f64,
    capture: bool,
    /// The ε of the state the last trial started from, the trial's ε and its converged g.
    last: Option<([f64; 2], [f64; 2], Vec<f64>)>,
    /// dg/dε (the two columns, m per unit ε) of the coupled Jacobian's last evaluation and the
    /// ε of the state its trial started from: the tangent along which the next trial from
    /// the same state starts its gap.
    tangent: Option<([f64; 2], [Vec<f64>; 2])>,
    /// Film solves so far (the fixed-point iterations of every trial).
    film_solves: usize,
    /// The last trial's start ε, switch field and force: what the next trial from the same
    /// state is compared with in [`FilmModel::step_diagnostics`].
    last_trial: Option<([f64; 2], Array2<bool>, [f64; 2])>,
    /// [`FilmModel::step_diagnostics`] of the last step.
    diagnostics: Vec<(&'static str, f64)>,
}

impl ElasticFilm {
    /// The film of `params` (grooved supply: the time-stepping film's) coupled to `bearing`
    /// (meshed around the film's radius); g converged to `bearing.params.dynamic_gap_tolerance` · c in
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
            tolerance: bearing.params.dynamic_gap_tolerance * clearance,
            clearance,
            max_iterations: bearing.params.max_iterations,
            min_relaxation: bearing.params.min_relaxation,
            capture: false,
            last: None,
            tangent: None,
            film_solves: 0,
            last_trial: None,
            diagnostics: Vec::new(),
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

/// The coupled film reports no time scheme and no state vector, so the inverse solver's local
/// error control and cycle extrapolation (`crate::inverse::error_control`,
/// `crate::inverse::cycle_map`) leave it as its dynamic row was measured (docs/validation.md);
/// bringing it under both, and re-running that row, is the next step.
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
        let mut g = self.start_gap(state, eccentricity_ratio);
        let mut omega = 1.0;
        let mut previous: Option<Vec<f64>> = None;
        let mut last = f64::INFINITY;
        // The last gap iterate's switch field and force, for the diagnostics.
        let mut before: Option<(Array2<bool>, [f64; 2])> = None;
        for iteration in 1..=self.max_iterations {
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
                self.note_step(from, iteration, last, before.as_ref(), &film, &response);
                if !self.capture {
                    response.fields = None;
                }
                self.last = Some((from, eccentricity_ratio, g.clone()));
                return Ok((response, ElasticFilmState { film, gap: g }));
            }
            before = Some((film.full_film, response.film_force));
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

    /// The coupled film's exact dF/dε (module docs): the film's own linearization and a
    /// matrix-free GMRES on the gap sensitivity.
    fn force_jacobian(&mut self) -> Option<Result<[[f64; 2]; 2], FilmModelError>> {
        Some(self.coupled_jacobian())
    }

    /// Of the last converged step: its gap iterations, the final gap residual max |C p̄ − g|
    /// relative to c, and what the last gap iteration changed — nodes that switched between
    /// full and cavitated and |ΔF| (N) — and the same against the trial before it from the
    /// same state (the Newton's previous iterate; NaN for the first trial).
    fn step_diagnostics(&self) -> Vec<(&'static str, f64)> {
        self.diagnostics.clone()
    }
}

/// Nodes whose switch (full or cavitated) differs between two fields.
fn switched(a: &Array2<bool>, b: &Array2<bool>) -> f64 {
    a.iter().zip(b.iter()).filter(|(x, y)| x != y).count() as f64
}

fn force_change(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

impl ElasticFilm {
    /// The gap a trial at ε from `state` starts from: the last trial's from the same state
    /// moved along the coupled Jacobian's dg/dε when it was evaluated from this state,
    /// g₀ = g_last + dg/dε · (ε − ε_last) (module docs), else the last trial's g, else the
    /// state's own.
    fn start_gap(&self, state: &ElasticFilmState, eps: [f64; 2]) -> Vec<f64> {
        let from = state.film.eccentricity_ratio;
        let Some((_, at, g)) = self.last.as_ref().filter(|(f, _, _)| *f == from) else {
            return state.gap.clone();
        };
        let mut g = g.clone();
        if let Some((_, [tx, ty])) = self.tangent.as_ref().filter(|(f, _)| *f == from) {
            let (dx, dy) = (eps[0] - at[0], eps[1] - at[1]);
            for ((gk, a), b) in g.iter_mut().zip(tx).zip(ty) {
                *gk += a * dx + b * dy;
            }
        }
        g
    }

    /// Record [`FilmModel::step_diagnostics`] of a converged step from `from`.
    fn note_step(
        &mut self,
        from: [f64; 2],
        iterations: usize,
        residual: f64,
        before: Option<&(Array2<bool>, [f64; 2])>,
        film: &FilmState,
        response: &FilmResponse,
    ) {
        let clearance = self.clearance;
        let (gap_switched, gap_force) = before.map_or((0.0, 0.0), |(s, f)| {
            (
                switched(s, &film.full_film),
                force_change(*f, response.film_force),
            )
        });
        let (trial_switched, trial_force) = match &self.last_trial {
            Some((eps, s, f)) if *eps == from => (
                switched(s, &film.full_film),
                force_change(*f, response.film_force),
            ),
            _ => (f64::NAN, f64::NAN),
        };
        self.diagnostics = vec![
            ("gap iterations", iterations as f64),
            ("gap residual / c", residual / clearance),
            ("nodes switched in the last gap iteration", gap_switched),
            ("|dF| of the last gap iteration (N)", gap_force),
            ("nodes switched against the previous trial", trial_switched),
            ("|dF| against the previous trial (N)", trial_force),
        ];
        self.last_trial = Some((from, film.full_film.clone(), response.film_force));
    }
}

/// Relative residual to which GMRES solves (I − C ∂p̄/∂g) dg/dε = C ∂p̄/∂ε: the film's
/// responses inside the operator are solved to 1e-5 of their right-hand sides, so the operator
/// itself is known to about that; the Newton on ε needs the Jacobian to a few digits.
const GAP_SENSITIVITY_TOLERANCE: f64 = 1e-5;

impl ElasticFilm {
    /// dF/dε of the last step's coupled film (module docs): ∂F/∂ε at fixed g from the film's
    /// linearization, plus ∂F/∂g · dg/dε with dg/dε from GMRES.
    pub(crate) fn coupled_jacobian(&mut self) -> Result<[[f64; 2]; 2], FilmModelError> {
        let direct = self.inner.solver_mut().thickness_responses(&[
            ThicknessChange::Eccentricity(0),
            ThicknessChange::Eccentricity(1),
        ])?;
        let mut jacobian = [[0.0; 2]; 2];
        let mut tangent: [Vec<f64>; 2] = Default::default();
        for (c, r) in direct.iter().enumerate() {
            let rhs = self.gap_of_change(&r.pressure);
            let (through_gap, dg) = self.gap_sensitivity_force(&rhs)?;
            jacobian[0][c] = r.film_force[0] + through_gap[0];
            jacobian[1][c] = r.film_force[1] + through_gap[1];
            tangent[c] = dg;
        }
        if jacobian.iter().flatten().any(|v| !v.is_finite()) {
            return Err(FilmModelError::NonFinite {
                quantity: "elastic film-force Jacobian",
            });
        }
        // The gap's dg/dε, of the state the last trial started from.
        self.tangent = self.last.as_ref().map(|(from, _, _)| (*from, tangent));
        Ok(jacobian)
    }

    /// C δp̄ of a pressure change field (no ambient: a change).
    fn gap_of_change(&self, pressure: &Array2<f64>) -> Vec<f64> {
        let pbar = super::coupling::length_mean_at(pressure, 0.0, 0.0, &self.angles);
        self.compliance.gap(&pbar)
    }

    /// The film's response to a gap change v: (A v = v − C δp̄(v), δF(v)).
    fn gap_operator(&mut self, v: &[f64]) -> Result<(Vec<f64>, [f64; 2]), FilmModelError> {
        let change = ThicknessChange::Gap(FilmDeformation::new(v.to_vec())?);
        let r = self
            .inner
            .solver_mut()
            .thickness_responses(std::slice::from_ref(&change))?
            .pop()
            .expect("one response per change");
        let cp = self.gap_of_change(&r.pressure);
        let av = v.iter().zip(&cp).map(|(v, c)| v - c).collect();
        Ok((av, r.film_force))
    }

    /// ∂F/∂g · y and y for the y that solves (I − C ∂p̄/∂g) y = b, by GMRES (no restart; the
    /// Krylov basis's force responses are kept, so ∂F/∂g · y costs no extra film solve).
    fn gap_sensitivity_force(&mut self, b: &[f64]) -> Result<([f64; 2], Vec<f64>), FilmModelError> {
        let n = b.len();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let beta = norm(b);
        if beta == 0.0 {
            return Ok(([0.0; 2], vec![0.0; n]));
        }
        let max_iterations = n.min(200);
        let mut basis: Vec<Vec<f64>> = vec![b.iter().map(|x| x / beta).collect()];
        let mut forces: Vec<[f64; 2]> = Vec::new();
        // Hessenberg columns after Givens rotations (upper triangular R), the rotations, and
        // the rotated right-hand side β e_1.
        let mut r: Vec<Vec<f64>> = Vec::new();
        let mut rotations: Vec<(f64, f64)> = Vec::new();
        let mut rhs = vec![beta];
        let mut residual = beta;
        for j in 0..max_iterations {
            let (mut w, force) = self.gap_operator(&basis[j])?;
            forces.push(force);
            let mut h = vec![0.0; j + 2];
            for (i, v) in basis.iter().enumerate() {
                let d: f64 = w.iter().zip(v).map(|(a, b)| a * b).sum();
                h[i] = d;
                for (wk, vk) in w.iter_mut().zip(v) {
                    *wk -= d * vk;
                }
            }
            let subdiagonal = norm(&w);
            h[j + 1] = subdiagonal;
            for (i, &(cs, sn)) in rotations.iter().enumerate() {
                let (a, b) = (h[i], h[i + 1]);
                h[i] = cs * a + sn * b;
                h[i + 1] = -sn * a + cs * b;
            }
            let d = h[j].hypot(h[j + 1]);
            if !(d > 0.0 && d.is_finite()) {
                return Err(FilmModelError::NonFinite {
                    quantity: "elastic gap-sensitivity GMRES",
                });
            }
            let (cs, sn) = (h[j] / d, h[j + 1] / d);
            h[j] = d;
            h[j + 1] = 0.0;
            rotations.push((cs, sn));
            rhs.push(-sn * rhs[j]);
            rhs[j] *= cs;
            residual = rhs[j + 1].abs();
            r.push(h);
            if residual <= GAP_SENSITIVITY_TOLERANCE * beta || subdiagonal == 0.0 {
                // Back substitution R α = rhs, then ∂F/∂g · y = Σ α_i δF(v_i).
                let m = j + 1;
                let mut alpha = vec![0.0; m];
                for i in (0..m).rev() {
                    let mut s = rhs[i];
                    for k in i + 1..m {
                        s -= r[k][i] * alpha[k];
                    }
                    alpha[i] = s / r[i][i];
                }
                let mut out = [0.0; 2];
                let mut y = vec![0.0; n];
                for ((a, f), v) in alpha.iter().zip(&forces).zip(&basis) {
                    out[0] += a * f[0];
                    out[1] += a * f[1];
                    for (yk, vk) in y.iter_mut().zip(v) {
                        *yk += a * vk;
                    }
                }
                return Ok((out, y));
            }
            basis.push(w.iter().map(|x| x / subdiagonal).collect());
        }
        Err(FilmModelError::NotConverged {
            what: "elastic gap sensitivity (GMRES)",
            iterations: max_iterations,
            residual: residual / beta,
            tolerance: GAP_SENSITIVITY_TOLERANCE,
        })
    }
}
