//! The closed-form models as a [`FilmModel`] of the inverse solver
//! ([`crate::inverse::solve_inverse`]), so that a load history can be run through any of them
//! (the case option of the application). With [`ClosedFormModel::ShortGumbelMovingFilm`] this is
//! the inverse solver's analytic film: Ocvirk's short bearing with Gumbel's moving half film
//! (\[Flores2006\] eqs. 18–22, 36–37), whose force is Booker's squeeze integral in closed form
//! (see [`super::short`]).
//!
//! # Journal velocity (time discretisation)
//!
//! The state ([`JournalMotion`](crate::time_scheme::JournalMotion)) holds ε^n, ε̇^n and ε^{n−1}.
//! A step to the trial ε^{n+1} takes ε̇^{n+1} from the crate's one [`TimeScheme`] (backward
//! Euler, BDF2 — the default — or the trapezoidal rule; formulas in
//! [`crate::time_scheme::JournalMotion::advance`]). The [`super::JournalMotion`] of the papers
//! follows from (ε, ε̇) by \[Flores2009\] eqs. 25–32 with ω = ω_j − ω_b.
//!
//! Backward Euler's chord of a whirling orbit points inside the circle by half the step angle,
//! an inward squeeze velocity of order |ε| ω² dt that the film answers with a load capacity it
//! does not have: a load turning with the journal at half its speed (ω̄ − ω_W = 0) gets carried
//! on a finite orbit. The trapezoidal rule's end-point velocities are tangent to such an orbit,
//! so it has no radial bias; BDF2's radial error is of third order in the step angle
//! (3/2 − 2e^{−iα} + ½e^{−2iα} = iα + iα³/3 + α⁴/4 + …), so it has no such load capacity either.
//!
//! # Outputs
//!
//! - film force: [`super::film_force`];
//! - h_min = c(1 − ε) along ε;
//! - peak pressure: the moving Gumbel film by [`super::short::moving_film_peak_pressure`]
//!   (analytic, Newton-polished); the other models the maximum of [`super::pressure`] at z = 0
//!   over 720 angles. Pinkus–Sternlicht publishes no pressure: its peak is reported as 0
//!   (documented, not a NaN);
//! - cavitated fraction: 0 for the full films, ½ for the half films;
//! - side leakage: short models, the axial flux at z = ±L/2 of the pressure of \[Flores2009\] eq. 3
//!   over the film region, (c L R/4) ∫ [ω' ε sin ψ − 2ε̇ cos ψ] dψ per end (signed, net; the
//!   moving half film passes R L c |u| per end, u = ε̇ − ω̄ × ε); long models and
//!   Pinkus–Sternlicht have no axial flow (0);
//! - friction torques and power loss (docs/conventions.md §5): the Couette torque T_s of
//!   [`super::short::couette_shear_torque`] (shear over 360°), T_journal = −T_s − ½ (e × F)_z,
//!   T_bearing = T_s − ½ (e × F)_z (T_journal + T_bearing + (e × F)_z = 0: the film carries no
//!   moment), power = T_s ω + W·v with the squeeze velocity v = c(ε̇ − ω̄ × ε), ω̄ = ω/2
//!   (\[Booker1965\]: the squeeze dissipation is the load times the squeeze velocity).

use super::short::{couette_shear_torque, moving_film_peak_pressure};
use super::{
    ClosedFormError, ClosedFormModel, ClosedFormParams, JournalMotion, film_force, pressure,
};
use crate::inverse::{FilmModel, FilmModelError, FilmResponse, OperatingConditions, TimeScheme};
use std::f64::consts::TAU;

/// A closed-form film for the inverse solver.
///
/// ```
/// use jbearing_solvers::closed_form::{ClosedFormFilm, ClosedFormModel, ClosedFormParams};
/// use jbearing_solvers::inverse::{FilmModel, OperatingConditions, TimeScheme};
///
/// let params = ClosedFormParams { radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02 };
/// let mut film = ClosedFormFilm::new(ClosedFormModel::ShortGumbelMovingFilm, params, TimeScheme::Bdf2)?;
/// let rotation = OperatingConditions { journal_speed: 300.0, ..Default::default() };
/// let at_rest = film.initial_state([0.0, -0.5]);
/// let (response, _next) = film.step(&at_rest, [0.0, -0.5], 1e-4, &rotation)?;
/// // A journal at rest in a rotating bearing carries Ocvirk's steady load.
/// let load = response.film_force[0].hypot(response.film_force[1]);
/// let ocvirk = jbearing_solvers::closed_form::short::ocvirk_steady_load(&params, 0.5, 300.0);
/// assert!((load - ocvirk).abs() < 1e-10 * ocvirk);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedFormFilm {
    /// The model.
    pub model: ClosedFormModel,
    /// Geometry and lubricant.
    pub params: ClosedFormParams,
    /// Time discretisation of the journal velocity.
    pub scheme: TimeScheme,
}

/// State at t^n: position, velocity and history of the journal centre.
pub type ClosedFormState = crate::time_scheme::JournalMotion;

impl ClosedFormFilm {
    /// A film of `model` with checked parameters; `Err` names the first invalid one.
    pub fn new(
        model: ClosedFormModel,
        params: ClosedFormParams,
        scheme: TimeScheme,
    ) -> Result<Self, ClosedFormError> {
        params.validate()?;
        Ok(Self {
            model,
            params,
            scheme,
        })
    }

    /// The film response for a journal at `eps` moving with `rate` (dε/dt).
    pub fn response(
        &self,
        eps: [f64; 2],
        rate: [f64; 2],
        conditions: &OperatingConditions,
    ) -> Result<FilmResponse, FilmModelError> {
        let e = eps[0].hypot(eps[1]);
        if e.is_nan() || e >= 1.0 {
            return Err(FilmModelError::OutsideClearance { eccentricity: e });
        }
        let p = &self.params;
        let omega = conditions.journal_speed - conditions.bearing_speed;
        let motion = JournalMotion::from_cartesian(eps, rate, omega);
        let force = film_force(self.model, p, &motion)?.cartesian;
        let c = p.radial_clearance;
        let wbar = 0.5 * omega;
        // Squeeze velocity u = v/c = ε̇ − ω̄ × ε (1/s).
        let u = [rate[0] + wbar * eps[1], rate[1] - wbar * eps[0]];
        let (p_max, p_at) = self.peak_pressure(eps, u, &motion)?;
        let half = !matches!(
            self.model,
            ClosedFormModel::ShortSommerfeld | ClosedFormModel::LongSommerfeld
        );
        let end_flow = self.end_flow(&motion);
        let shear = couette_shear_torque(p, e, omega);
        let e_cross_f = c * (eps[0] * force[1] - eps[1] * force[0]);
        let squeeze_power = -c * (force[0] * u[0] + force[1] * u[1]);
        let response = FilmResponse {
            film_force: force,
            min_film_thickness: c * (1.0 - e),
            min_film_location: [if e > 0.0 { eps[1].atan2(eps[0]) } else { 0.0 }, 0.0],
            max_pressure: p_max,
            max_pressure_location: [p_at, 0.0],
            cavitated_fraction: match self.model {
                // The moving half film exists only while the journal moves relative to the film.
                ClosedFormModel::ShortGumbelMovingFilm if u == [0.0, 0.0] => 0.0,
                _ if half => 0.5,
                _ => 0.0,
            },
            side_leakage: [end_flow, end_flow],
            supply_flow: Vec::new(),
            recirculated_flow: 0.0,
            friction_torque_journal: -shear - 0.5 * e_cross_f,
            friction_torque_bearing: shear - 0.5 * e_cross_f,
            power_loss: shear * omega + squeeze_power,
            sweep_iterations: 0,
            fields: None,
        };
        let finite = force.iter().all(|v| v.is_finite())
            && response.power_loss.is_finite()
            && response.max_pressure.is_finite()
            && end_flow.is_finite();
        if !finite {
            return Err(FilmModelError::NonFinite {
                quantity: "closed-form film force or outputs",
            });
        }
        Ok(response)
    }

    /// The peak pressure and its angle (module docs, Outputs): the moving Gumbel film's
    /// analytic peak at squeeze velocity `u`, the other models' maximum over 720 angles at
    /// z = 0, 0 for Pinkus–Sternlicht.
    fn peak_pressure(
        &self,
        eps: [f64; 2],
        u: [f64; 2],
        motion: &JournalMotion,
    ) -> Result<(f64, f64), FilmModelError> {
        let p = &self.params;
        let (mut p_max, mut p_at) = (0.0f64, 0.0);
        match self.model {
            ClosedFormModel::PinkusSternlicht => {}
            ClosedFormModel::ShortGumbelMovingFilm => {
                (p_max, p_at) = moving_film_peak_pressure(p, eps, u);
            }
            _ => {
                for i in 0..720 {
                    let th = i as f64 * TAU / 720.0;
                    let v = pressure(self.model, p, motion, th, 0.0)?;
                    if v > p_max {
                        p_max = v;
                        p_at = th;
                    }
                }
            }
        }
        Ok((p_max, p_at))
    }

    /// The side leakage per end (module docs, Outputs): (c L R/4) ∫ [ω' ε sin ψ − 2ε̇ cos ψ] dψ
    /// over the film region of the short models (\[Flores2009\] eq. 3), 0 for the others.
    fn end_flow(&self, motion: &JournalMotion) -> f64 {
        let p = &self.params;
        let (r, l, c) = (p.radius, p.length, p.radial_clearance);
        let (a, b) = (
            motion.wedge_speed() * motion.eccentricity_ratio,
            -2.0 * motion.eccentricity_ratio_rate,
        );
        let region_integral = match self.model {
            ClosedFormModel::ShortSommerfeld => 0.0,
            ClosedFormModel::ShortGumbel => 2.0 * a, // ∫_0^π: 2a + 0·b
            ClosedFormModel::ShortGumbelMovingFilm => 2.0 * a.hypot(b),
            _ => 0.0,
        };
        0.25 * c * l * r * region_integral
    }
}

impl FilmModel for ClosedFormFilm {
    type State = ClosedFormState;

    fn time_scheme(&self) -> Option<TimeScheme> {
        Some(self.scheme)
    }

    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> ClosedFormState {
        ClosedFormState::at_rest(eccentricity_ratio)
    }

    /// BDF2's level before becomes ε at `start`, one step `dt` back (the trait's docs).
    fn join_substeps(&self, start: &ClosedFormState, end: &mut ClosedFormState, dt: f64) {
        if end.previous.is_some() {
            end.previous = Some((start.eccentricity_ratio, dt));
        }
    }

    fn step(
        &mut self,
        state: &ClosedFormState,
        eccentricity_ratio: [f64; 2],
        dt: f64,
        conditions: &OperatingConditions,
    ) -> Result<(FilmResponse, ClosedFormState), FilmModelError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(FilmModelError::InvalidTimeStep { dt });
        }
        let next = state.advance(self.scheme, eccentricity_ratio, dt);
        let rate = next.eccentricity_rate;
        let r = self.response(eccentricity_ratio, rate, conditions)?;
        Ok((r, next))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    fn moving_film(scheme: TimeScheme) -> ClosedFormFilm {
        let params = ClosedFormParams {
            radius: 0.02,
            length: 0.01,
            radial_clearance: 40e-6,
            viscosity: 0.02,
        };
        ClosedFormFilm::new(ClosedFormModel::ShortGumbelMovingFilm, params, scheme).unwrap()
    }

    #[test]
    fn steady_rotation_matches_ocvirk_closed_form() {
        // A journal at rest (ε̇ = 0) in a rotating bearing: the film force (Booker's squeeze
        // integral) must be Ocvirk's steady load, with the journal φ ahead of the load line
        // (counter-clockwise rotation).
        let mut f = moving_film(TimeScheme::BackwardEuler);
        let omega = 300.0;
        let cond = OperatingConditions {
            journal_speed: omega,
            ..Default::default()
        };
        for &e in &[0.1, 0.5, 0.8, 0.95] {
            let eps = [0.0, -e];
            let st = f.initial_state(eps);
            let (r, _) = f.step(&st, eps, 1e-4, &cond).unwrap();
            let w = [-r.film_force[0], -r.film_force[1]];
            let w_mag = w[0].hypot(w[1]);
            let expected = super::super::short::ocvirk_steady_load(&f.params, e, omega);
            // Two independent closed forms of the same integral: round-off only.
            assert!(
                (w_mag - expected).abs() < 1e-10 * expected,
                "{w_mag} {expected}"
            );
            let att = (eps[1].atan2(eps[0]) - w[1].atan2(w[0])).rem_euclid(TAU);
            let phi = super::super::short::ocvirk_attitude(e);
            assert!((att - phi).abs() < 1e-10, "ε {e}: {att} vs {phi}");
            // Dissipation = journal torque × speed for a journal at rest (no squeeze work).
            assert!((r.power_loss + r.friction_torque_journal * omega).abs() < 1e-9 * r.power_loss);
            // Moment balance of the film.
            let exf = 40e-6 * (eps[0] * r.film_force[1] - eps[1] * r.film_force[0]);
            let sum = r.friction_torque_journal + r.friction_torque_bearing + exf;
            assert!(sum.abs() < 1e-12 * r.friction_torque_bearing.abs());
            // Side leakage: Ocvirk's Q = ε c U L in total, half out of each end.
            let q = e * 40e-6 * 0.02 * omega * 0.01;
            assert!((r.side_leakage[0] + r.side_leakage[1] - q).abs() < 1e-12 * q);
        }
    }

    #[test]
    fn moving_film_peak_is_the_maximum_of_the_sampled_pressure() {
        // The analytic peak (Sommerfeld's substitution + Newton) against 720 samples of the
        // papers' pressure formula, [Flores2009] eq. 3 at z = 0, clipped to the film region: the
        // samples lie at most 0.25° from the peak, O(1e-5) below it for these orbits.
        let mut f = moving_film(TimeScheme::BackwardEuler);
        let cond = OperatingConditions {
            journal_speed: 300.0,
            bearing_speed: 20.0,
            ..Default::default()
        };
        let s0 = f.initial_state([0.3, -0.4]);
        for next in [[0.31, -0.41], [0.2, -0.5], [0.5, 0.1], [0.0, -0.9]] {
            let (r, st) = f.step(&s0, next, 1e-4, &cond).unwrap();
            let motion = JournalMotion::from_cartesian(next, st.eccentricity_rate, 280.0);
            let sampled = (0..720)
                .map(|i| {
                    pressure(f.model, &f.params, &motion, i as f64 * TAU / 720.0, 0.0).unwrap()
                })
                .fold(0.0f64, f64::max);
            assert!(r.max_pressure >= sampled * (1.0 - 1e-12));
            assert!(
                r.max_pressure - sampled < 1e-3 * sampled,
                "{} {sampled}",
                r.max_pressure
            );
        }
    }

    #[test]
    fn crank_nicolson_velocity_is_the_trapezoidal_rule() {
        let mut f = moving_film(TimeScheme::CrankNicolson);
        let st = ClosedFormState {
            eccentricity_ratio: [0.1, 0.2],
            eccentricity_rate: [3.0, -1.0],
            previous: None,
        };
        let (_, next) = f
            .step(&st, [0.1005, 0.1990], 1e-4, &OperatingConditions::default())
            .unwrap();
        // ε^{n+1} − ε^n = dt/2 (ε̇^n + ε̇^{n+1})
        for k in 0..2 {
            let lhs = next.eccentricity_ratio[k] - st.eccentricity_ratio[k];
            let rhs = 0.5e-4 * (st.eccentricity_rate[k] + next.eccentricity_rate[k]);
            assert!((lhs - rhs).abs() < 1e-15, "{lhs} {rhs}");
        }
    }

    #[test]
    fn bad_input_is_an_error_not_nan() {
        let mut f = moving_film(TimeScheme::CrankNicolson);
        let st = f.initial_state([0.0, 0.0]);
        let cond = OperatingConditions::default();
        assert!(matches!(
            f.step(&st, [0.8, 0.7], 1e-4, &cond),
            Err(FilmModelError::OutsideClearance { .. })
        ));
        assert!(matches!(
            f.step(&st, [0.1, 0.0], 0.0, &cond),
            Err(FilmModelError::InvalidTimeStep { dt }) if dt == 0.0
        ));
        let mut bad = f.params;
        bad.viscosity = -1.0;
        assert!(matches!(
            ClosedFormFilm::new(f.model, bad, f.scheme),
            Err(ClosedFormError::InvalidParameter {
                name: "viscosity",
                ..
            })
        ));
    }

    #[test]
    fn journal_at_static_equilibrium_carries_the_load_in_every_model() {
        let params = ClosedFormParams {
            radius: 9.8e-3,
            length: 40e-3,
            radial_clearance: 0.2e-3,
            viscosity: 0.4,
        };
        let omega = 52.36;
        let cond = OperatingConditions {
            journal_speed: omega,
            bearing_speed: 0.0,
            feed_pressures: vec![],
        };
        for model in ClosedFormModel::ALL {
            let eq =
                super::super::static_equilibrium(model, &params, [0.0, -31.275], omega).unwrap();
            let mut film = ClosedFormFilm {
                model,
                params,
                scheme: TimeScheme::BackwardEuler,
            };
            let e = eq.eccentricity_ratio_vector;
            let st = film.initial_state(e);
            let (r, _) = film.step(&st, e, 1e-4, &cond).unwrap();
            assert!(r.film_force[0].abs() < 1e-8 && (r.film_force[1] - 31.275).abs() < 1e-7);
            assert!(r.power_loss > 0.0);
            assert!(film.step(&st, [1.0, 0.0], 1e-4, &cond).is_err());
        }
    }
}
