//! The closed-form models as a [`FilmModel`] of the inverse solver
//! ([`crate::inverse::solve_inverse`]), so that a load history can be run through any of them
//! (the case option of the application).
//!
//! # Journal velocity
//!
//! As in [`crate::inverse::ShortBearingFilm`]: the state holds ε^n and ε̇^n; a step to the trial
//! ε^{n+1} takes ε̇^{n+1} = (ε^{n+1} − ε^n)/dt (backward Euler) or 2(ε^{n+1} − ε^n)/dt − ε̇^n
//! (Crank–Nicolson, the default). The [`JournalMotion`] follows from (ε, ε̇) by \[Flores2009\]
//! eqs. 25–32 with ω = ω_j − ω_b.
//!
//! # Outputs
//!
//! - film force: [`super::film_force`];
//! - h_min = c(1 − ε) along ε;
//! - peak pressure: maximum of [`super::pressure`] at z = 0 over 720 angles. Pinkus–Sternlicht
//!   publishes no pressure: its peak is reported as 0 (documented, not a NaN);
//! - cavitated fraction: 0 for the full films, ½ for the half films;
//! - side leakage: short models, the axial flux at z = ±L/2 of the pressure of \[Flores2009\] eq. 3
//!   over the film region, (c L R/4) ∫ [ω' ε sin ψ − 2ε̇ cos ψ] dψ per end (signed, net); long
//!   models and Pinkus–Sternlicht have no axial flow (0);
//! - friction torques and power loss as for the inverse solver's analytic film:
//!   T_s = 2π μ R³ L ω / (c √(1−ε²)) (Couette shear over 360°), T_journal = −T_s − ½ (e × F)_z,
//!   T_bearing = T_s − ½ (e × F)_z, power = T_s ω + W·v with the squeeze velocity
//!   v = c(ε̇ − ω̄ × ε), ω̄ = ω/2 \[Booker1965\].

use super::{ClosedFormModel, ClosedFormParams, JournalMotion, film_force, pressure};
use crate::inverse::{FilmConditions, FilmModel, FilmModelError, FilmResponse, TimeScheme};
use std::f64::consts::TAU;

/// A closed-form film for the inverse solver.
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
    /// The film response for a journal at `eps` moving with `rate` (dε/dt).
    pub fn response(
        &self,
        eps: [f64; 2],
        rate: [f64; 2],
        conditions: &FilmConditions,
    ) -> Result<FilmResponse, FilmModelError> {
        let e = eps[0].hypot(eps[1]);
        if e.is_nan() || e >= 1.0 {
            return Err(FilmModelError::OutsideClearance { eccentricity: e });
        }
        let p = &self.params;
        let omega = conditions.journal_speed - conditions.bearing_speed;
        let motion = JournalMotion::from_cartesian(eps, rate, omega);
        let err = |e: super::ClosedFormError| FilmModelError::Solver(e.to_string());
        let force = film_force(self.model, p, &motion).map_err(err)?.cartesian;
        let (mut p_max, mut p_at) = (0.0f64, 0.0);
        if self.model != ClosedFormModel::PinkusSternlicht {
            for i in 0..720 {
                let th = i as f64 * TAU / 720.0;
                let v = pressure(self.model, p, &motion, th, 0.0).map_err(err)?;
                if v > p_max {
                    p_max = v;
                    p_at = th;
                }
            }
        }
        let half = !matches!(
            self.model,
            ClosedFormModel::ShortSommerfeld | ClosedFormModel::LongSommerfeld
        );
        let c = p.radial_clearance;
        let (r, l, mu) = (p.radius, p.length, p.viscosity);
        // ∫ [ω' ε sin ψ − 2ε̇ cos ψ] dψ over the film region of the short models.
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
        let end_flow = 0.25 * c * l * r * region_integral;
        let shear = TAU * mu * r.powi(3) * l * omega / (c * (1.0 - e * e).sqrt());
        let e_cross_f = c * (eps[0] * force[1] - eps[1] * force[0]);
        let wbar = 0.5 * omega;
        let v = [c * (rate[0] + wbar * eps[1]), c * (rate[1] - wbar * eps[0])];
        let squeeze_power = -(force[0] * v[0] + force[1] * v[1]);
        let response = FilmResponse {
            film_force: force,
            min_film_thickness: c * (1.0 - e),
            min_film_location: [if e > 0.0 { eps[1].atan2(eps[0]) } else { 0.0 }, 0.0],
            max_pressure: p_max,
            max_pressure_location: [p_at, 0.0],
            cavitated_fraction: if half { 0.5 } else { 0.0 },
            side_leakage: [end_flow, end_flow],
            supply_flow: Vec::new(),
            recirculated_flow: 0.0,
            friction_torque_journal: -shear - 0.5 * e_cross_f,
            friction_torque_bearing: shear - 0.5 * e_cross_f,
            power_loss: shear * omega + squeeze_power,
            sweep_iterations: 0,
            fields: None,
        };
        if !(response.power_loss.is_finite() && end_flow.is_finite()) {
            return Err(FilmModelError::NonFinite {
                quantity: "closed-form film outputs",
            });
        }
        Ok(response)
    }
}

impl FilmModel for ClosedFormFilm {
    type State = ClosedFormState;

    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> ClosedFormState {
        ClosedFormState::at_rest(eccentricity_ratio)
    }

    fn step(
        &mut self,
        state: &ClosedFormState,
        eccentricity_ratio: [f64; 2],
        dt: f64,
        conditions: &FilmConditions,
    ) -> Result<(FilmResponse, ClosedFormState), FilmModelError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(FilmModelError::Solver(format!(
                "closed-form film: time step {dt} s"
            )));
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
    use crate::inverse::{ShortBearingFilm, ShortBearingParams};

    /// The moving short half film is the inverse solver's analytic film (\[Flores2006\] eqs. 18, 36–37):
    /// two implementations of the same physics must agree on every output.
    #[test]
    fn moving_short_film_matches_the_inverse_solvers_analytic_film() {
        let params = ClosedFormParams {
            radius: 0.02,
            length: 0.01,
            radial_clearance: 40e-6,
            viscosity: 0.02,
        };
        let mut ours = ClosedFormFilm {
            model: ClosedFormModel::ShortGumbelMovingFilm,
            params,
            scheme: TimeScheme::CrankNicolson,
        };
        let mut theirs = ShortBearingFilm::new(ShortBearingParams {
            radius: params.radius,
            length: params.length,
            radial_clearance: params.radial_clearance,
            viscosity: params.viscosity,
            scheme: TimeScheme::CrankNicolson,
        })
        .unwrap();
        let cond = FilmConditions {
            journal_speed: 300.0,
            bearing_speed: 20.0,
            feed_pressures: vec![],
        };
        let s0 = ours.initial_state([0.3, -0.4]);
        let t0 = theirs.initial_state([0.3, -0.4]);
        for next in [[0.31, -0.41], [0.2, -0.5], [0.5, 0.1]] {
            let (a, _) = ours.step(&s0, next, 1e-4, &cond).unwrap();
            let (b, _) = theirs.step(&t0, next, 1e-4, &cond).unwrap();
            let scale = b.film_force[0].hypot(b.film_force[1]);
            for k in 0..2 {
                assert!((a.film_force[k] - b.film_force[k]).abs() < 1e-9 * scale);
                assert!(
                    (a.side_leakage[k] - b.side_leakage[k]).abs() < 1e-9 * b.side_leakage[k].abs()
                );
            }
            // Peak: same 720 samples, theirs refined by a parabola (≤ 1e-4 relative).
            assert!((a.max_pressure - b.max_pressure).abs() < 1e-3 * b.max_pressure);
            assert!((a.power_loss - b.power_loss).abs() < 1e-9 * b.power_loss.abs());
            assert!(
                (a.friction_torque_journal - b.friction_torque_journal).abs()
                    < 1e-9 * b.friction_torque_journal.abs()
            );
            assert_eq!(a.cavitated_fraction, b.cavitated_fraction);
        }
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
        let cond = FilmConditions {
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
