//! Analytic film for the inverse solver: Ocvirk's short bearing with Gumbel's half film and a
//! moving journal.
//!
//! # The film
//!
//! Short-bearing Reynolds equation with wedge and squeeze (\[Flores2006\] eq. 17, Dubois & Ocvirk),
//! bearing frame, surface speed U = R(ω_j − ω_b), ω̄ = (ω_j − ω_b)/2:
//!
//! ```text
//!   ∂/∂z (h³/12μ ∂p/∂z) = (U/2R) ∂h/∂θ + ∂h/∂t = −v·n,    v = ė − ω̄ × e,  n = (cos θ, sin θ)
//!   p(θ, z) = 6μ (v·n)/h³ · (L²/4 − z²)       where v·n > 0, else 0 (Gumbel)  ([Flores2006] eq. 18)
//!   F_film = −∫∫ p n R dθ dz = −(μ R L³/c²) J(ε, u),   u = v/c = ε̇ − ω̄ × ε   ([Flores2006] eq. 20–22)
//! ```
//!
//! J is the closed-form squeeze integral of [`crate::mobility::short_bearing_squeeze_integral`]
//! (Booker's integrals, exact by Sommerfeld's substitution). For steady rotation (ε̇ = 0) this
//! is Ocvirk's steady short bearing, W = (μ U L³/4c²) ε √(16ε² + π²(1−ε²)) / (1−ε²)², attitude
//! tan φ = π √(1−ε²) / (4ε) — the closed form the constant-load test checks against.
//!
//! # Time discretisation (the journal velocity)
//!
//! The state ([`JournalMotion`]) holds ε^n, ε̇^n and ε^{n−1}. A step to the trial ε^{n+1} takes
//! ε̇^{n+1} from the crate's one [`TimeScheme`] (backward Euler, BDF2 — the default — or the
//! trapezoidal rule; formulas in [`JournalMotion::advance`]).
//!
//! Backward Euler's chord of a whirling orbit points inside the circle by half the step angle,
//! an inward squeeze velocity of order |ε| ω² dt that the film answers with a load capacity it
//! does not have: a load turning with the journal at half its speed (ω̄ − ω_W = 0) gets carried
//! on a finite orbit. The trapezoidal rule's end-point velocities are tangent to such an orbit,
//! so it has no radial bias; BDF2's radial error is of third order in the step angle
//! (3/2 − 2e^{−iα} + ½e^{−2iα} = iα + iα³/3 + α⁴/4 + …), so it has no such load capacity either.

//! # Outputs
//!
//! h_min = c(1 − |ε|) at θ = arg ε, z = 0. Peak pressure: maximum over θ of the mid-plane
//! pressure (3μL²/2c²)(u·n)/(1 − ε·n)³ (720 samples, parabolic refinement). Side leakage: the
//! axial flux at z = ±L/2 is (v·n) L/2 per unit circumference over the pressurised half, so each
//! end passes R L c |u| (Q = 2RLc|u| in total). Cavitated fraction: the unpressurised half of
//! Gumbel's film, 1/2 when v ≠ 0. No grooves (empty supply flow). Power loss (docs/conventions.md §5):
//! Couette part 2π μ R³ L (ω_j − ω_b)²/(c √(1−ε²)) over the full 360° plus the squeeze part
//! W·v = −F·(c u) \[Booker1965\]. Friction torques (shear stress −μU/h ∓ (h/2)∂p/∂x on the
//! journal/bearing surface, pressure term integrated by parts):
//!
//! ```text
//!   T_s = 2π μ R³ L (ω_j − ω_b) / (c √(1−ε²))
//!   T_journal = −T_s − ½ (e × F)_z,     T_bearing = T_s − ½ (e × F)_z
//! ```
//!
//! (T_journal + T_bearing + (e × F)_z = 0: the film carries no moment.)

use super::{FilmConditions, FilmModel, FilmModelError, FilmResponse};
use crate::mobility::short_bearing_squeeze_integral;
use std::f64::consts::{PI, TAU};

pub use crate::time_scheme::{JournalMotion, TimeScheme};

/// Geometry and lubricant of the short bearing, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShortBearingParams {
    /// Journal radius R (m).
    pub radius: f64,
    /// Bearing length L (m).
    pub length: f64,
    /// Radial clearance c (m).
    pub radial_clearance: f64,
    /// Dynamic viscosity μ (Pa·s).
    pub viscosity: f64,
    /// Time discretisation.
    pub scheme: TimeScheme,
}

/// The analytic short-bearing film.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShortBearingFilm {
    params: ShortBearingParams,
}

/// State of the analytic film at t^n: position, velocity and history of the journal centre.
pub type ShortBearingState = JournalMotion;

impl ShortBearingFilm {
    /// A film with the given parameters; `Err` names the first invalid one.
    pub fn new(params: ShortBearingParams) -> Result<Self, FilmModelError> {
        for (name, v) in [
            ("radius", params.radius),
            ("length", params.length),
            ("radial_clearance", params.radial_clearance),
            ("viscosity", params.viscosity),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(FilmModelError::Solver(format!(
                    "short bearing: invalid {name} = {v}"
                )));
            }
        }
        Ok(Self { params })
    }

    /// The parameters.
    pub fn params(&self) -> &ShortBearingParams {
        &self.params
    }

    /// Ocvirk's steady short-bearing load (N) at eccentricity ratio ε for the surface speed
    /// ω_j − ω_b (rad/s): W = (μ U L³/4c²) ε √(16ε² + π²(1−ε²)) / (1−ε²)², U = R(ω_j − ω_b).
    pub fn steady_load(&self, eccentricity: f64, relative_speed: f64) -> f64 {
        let p = &self.params;
        let e2 = eccentricity * eccentricity;
        let u = p.radius * relative_speed.abs();
        p.viscosity * u * p.length.powi(3) / (4.0 * p.radial_clearance.powi(2))
            * eccentricity
            * (16.0 * e2 + PI * PI * (1.0 - e2)).sqrt()
            / ((1.0 - e2) * (1.0 - e2))
    }

    /// Ocvirk's steady attitude angle (rad), tan φ = π √(1−ε²) / (4ε).
    pub fn steady_attitude(eccentricity: f64) -> f64 {
        (PI * (1.0 - eccentricity * eccentricity).sqrt()).atan2(4.0 * eccentricity)
    }
}

impl FilmModel for ShortBearingFilm {
    type State = ShortBearingState;

    fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> ShortBearingState {
        JournalMotion::at_rest(eccentricity_ratio)
    }

    fn step(
        &mut self,
        state: &ShortBearingState,
        eps: [f64; 2],
        dt: f64,
        conditions: &FilmConditions,
    ) -> Result<(FilmResponse, ShortBearingState), FilmModelError> {
        let p = &self.params;
        let e = eps[0].hypot(eps[1]);
        if e.is_nan() || e >= 1.0 {
            return Err(FilmModelError::OutsideClearance { eccentricity: e });
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(FilmModelError::Solver(format!(
                "short bearing: time step {dt} s"
            )));
        }
        let next = state.advance(p.scheme, eps, dt);
        let rate = next.eccentricity_rate;
        let dw = conditions.journal_speed - conditions.bearing_speed;
        let wbar = 0.5 * dw;
        // u = ε̇ − ω̄ × ε (1/s).
        let u = [rate[0] + wbar * eps[1], rate[1] - wbar * eps[0]];
        let c = p.radial_clearance;
        let (r, l, mu) = (p.radius, p.length, p.viscosity);
        let k = mu * r * l.powi(3) / (c * c);
        let j = short_bearing_squeeze_integral(eps, u);
        let force = [-k * j[0], -k * j[1]];

        let (p_max, p_angle) = peak_pressure(eps, u, 1.5 * mu * l * l / (c * c));
        let umag = u[0].hypot(u[1]);
        let root = (1.0 - e * e).sqrt();
        let shear_torque = TAU * mu * r.powi(3) * l * dw / (c * root);
        let e_cross_f = c * (eps[0] * force[1] - eps[1] * force[0]);
        let squeeze_power = -c * (force[0] * u[0] + force[1] * u[1]);
        let end_flow = r * l * c * umag;
        let response = FilmResponse {
            film_force: force,
            min_film_thickness: c * (1.0 - e),
            min_film_location: [if e > 0.0 { eps[1].atan2(eps[0]) } else { 0.0 }, 0.0],
            max_pressure: p_max,
            max_pressure_location: [p_angle, 0.0],
            cavitated_fraction: if umag > 0.0 { 0.5 } else { 0.0 },
            side_leakage: [end_flow, end_flow],
            supply_flow: Vec::new(),
            recirculated_flow: 0.0,
            friction_torque_journal: -shear_torque - 0.5 * e_cross_f,
            friction_torque_bearing: shear_torque - 0.5 * e_cross_f,
            power_loss: shear_torque * dw + squeeze_power,
            sweep_iterations: 0,
            fields: None,
        };
        let finite = force.iter().all(|v| v.is_finite())
            && response.power_loss.is_finite()
            && response.max_pressure.is_finite();
        if !finite {
            return Err(FilmModelError::NonFinite {
                quantity: "short-bearing film force or outputs",
            });
        }
        Ok((response, next))
    }
}

/// Peak of the mid-plane pressure scale·(u·n)/(1 − ε·n)³ over θ (Pa) and its angle (rad).
fn peak_pressure(eps: [f64; 2], u: [f64; 2], scale: f64) -> (f64, f64) {
    let f = |t: f64| {
        let (c, s) = (t.cos(), t.sin());
        let un = u[0] * c + u[1] * s;
        let w = 1.0 - eps[0] * c - eps[1] * s;
        if un > 0.0 {
            scale * un / (w * w * w)
        } else {
            0.0
        }
    };
    const N: usize = 720;
    let dth = TAU / N as f64;
    let (mut best, mut best_i) = (0.0, 0usize);
    for i in 0..N {
        let v = f(i as f64 * dth);
        if v > best {
            best = v;
            best_i = i;
        }
    }
    if best <= 0.0 {
        return (0.0, 0.0);
    }
    // Parabola through the best sample and its neighbours.
    let t0 = best_i as f64 * dth;
    let (fm, fp) = (f(t0 - dth), f(t0 + dth));
    let denom = fm - 2.0 * best + fp;
    let shift = if denom < 0.0 {
        (0.5 * (fm - fp) / denom).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    let t = t0 + shift * dth;
    let v = f(t).max(best);
    (v, t.rem_euclid(TAU))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn film(scheme: TimeScheme) -> ShortBearingFilm {
        ShortBearingFilm::new(ShortBearingParams {
            radius: 0.02,
            length: 0.01,
            radial_clearance: 40e-6,
            viscosity: 0.02,
            scheme,
        })
        .unwrap()
    }

    #[test]
    fn steady_rotation_matches_ocvirk_closed_form() {
        // A journal at rest (ε̇ = 0) in a rotating bearing: the film force must be Ocvirk's
        // steady load, with the journal φ ahead of the load line (counter-clockwise rotation).
        let mut f = film(TimeScheme::BackwardEuler);
        let omega = 300.0;
        let cond = FilmConditions {
            journal_speed: omega,
            ..Default::default()
        };
        for &e in &[0.1, 0.5, 0.8, 0.95] {
            let eps = [0.0, -e];
            let st = f.initial_state(eps);
            let (r, _) = f.step(&st, eps, 1e-4, &cond).unwrap();
            let w = [-r.film_force[0], -r.film_force[1]];
            let w_mag = w[0].hypot(w[1]);
            let expected = f.steady_load(e, omega);
            // Two independent closed forms of the same integral: round-off only.
            assert!(
                (w_mag - expected).abs() < 1e-10 * expected,
                "{w_mag} {expected}"
            );
            let att = (eps[1].atan2(eps[0]) - w[1].atan2(w[0])).rem_euclid(TAU);
            let phi = ShortBearingFilm::steady_attitude(e);
            assert!((att - phi).abs() < 1e-10, "ε {e}: {att} vs {phi}");
            // Dissipation = journal torque × speed for a journal at rest (no squeeze work).
            assert!((r.power_loss + r.friction_torque_journal * omega).abs() < 1e-9 * r.power_loss);
            // Moment balance of the film.
            let exf = 40e-6 * (eps[0] * r.film_force[1] - eps[1] * r.film_force[0]);
            let sum = r.friction_torque_journal + r.friction_torque_bearing + exf;
            assert!(sum.abs() < 1e-12 * r.friction_torque_bearing.abs());
        }
    }

    #[test]
    fn crank_nicolson_velocity_is_the_trapezoidal_rule() {
        let mut f = film(TimeScheme::CrankNicolson);
        let st = ShortBearingState {
            eccentricity_ratio: [0.1, 0.2],
            eccentricity_rate: [3.0, -1.0],
            previous: None,
        };
        let (_, next) = f
            .step(&st, [0.1005, 0.1990], 1e-4, &FilmConditions::default())
            .unwrap();
        // ε^{n+1} − ε^n = dt/2 (ε̇^n + ε̇^{n+1})
        for k in 0..2 {
            let lhs = next.eccentricity_ratio[k] - st.eccentricity_ratio[k];
            let rhs = 0.5e-4 * (st.eccentricity_rate[k] + next.eccentricity_rate[k]);
            assert!((lhs - rhs).abs() < 1e-15, "{lhs} {rhs}");
        }
    }

    #[test]
    fn outside_clearance_is_an_error_not_nan() {
        let mut f = film(TimeScheme::CrankNicolson);
        let st = f.initial_state([0.0, 0.0]);
        assert!(matches!(
            f.step(&st, [0.8, 0.7], 1e-4, &FilmConditions::default()),
            Err(FilmModelError::OutsideClearance { .. })
        ));
    }
}
