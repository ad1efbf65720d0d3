//! The infinitely long bearing (Sommerfeld) for a moving journal.
//!
//! Without the axial flow term the Reynolds equation of [`super`] integrates once to
//!
//! ```text
//!   ∂p/∂ψ = (12 μ R²/c²) [ε̇ sin ψ + ½ ω' ε cos ψ + K] / (1 + ε cos ψ)³
//! ```
//!
//! **Full film** (Sommerfeld, ψ ∈ 0 … 2π, p periodic and p(0) = 0; \[Flores2009\] eq. 5, \[Flores2006\]
//! eq. 20 with φ̇ − ω̄ = −ω'/2):
//!
//! ```text
//!   p = (6 μ R²/c²) { ω' ε sin ψ (2 + ε cos ψ) / ((2 + ε²)(1 + ε cos ψ)²)
//!                     + (ε̇/ε) [1/(1 + ε cos ψ)² − 1/(1 + ε)²] }
//! ```
//!
//! the squeeze bracket evaluated as ε̇ (1 − cos ψ)(2 + ε + ε cos ψ)/((1 + ε cos ψ)²(1 + ε)²),
//! which has no 1/ε and is exact at ε = 0.
//!
//! **Half film** (Gumbel, ψ ∈ 0 … π with p(0) = p(π) = 0, p = 0 on π … 2π). The wedge part of
//! eq. 5 already vanishes at ψ = π; the squeeze part does not (it is 4ε̇/(1 − ε²)² there), and
//! the constant K that makes it vanish adds
//!
//! ```text
//!   − (8 ε̇ √(1 − ε²) / (π (2 + ε²))) · ∫₀^ψ dt/(1 + ε cos t)³      (Sommerfeld substitution)
//! ```
//!
//! This film is the one whose forces \[Flores2009\] prints as eqs. 12–13 (the test integrates it).
//!
//! Forces in units of μ L R³ / c²:
//!
//! ```text
//!   full ([Flores2009] eqs. 10–11):  F_r = −12 π ε̇ / (1 − ε²)^{3/2}
//!                                F_t =  12 π ε ω' / ((2 + ε²)(1 − ε²)^{1/2})
//!   half ([Flores2009] eqs. 12–13):  F_r = −12 [ε² ω' / ((2 + ε²)(1 − ε²))
//!                                          + ε̇ (π/2 − 8/(π (2 + ε²))) / (1 − ε²)^{3/2}]
//!                                F_t =  12 [π ε ω' / (2 (2 + ε²)(1 − ε²)^{1/2})
//!                                          + 2 ε ε̇ / ((2 + ε²)(1 − ε²))]
//! ```

use super::{ClosedFormParams, JournalMotion, sommerfeld_integral_3};
use std::f64::consts::PI;

/// Dimensionless full-film pressure P = p c²/(6 μ R²) at ψ.
fn full_film_dimensionless(motion: &JournalMotion, psi: f64) -> f64 {
    let eps = motion.eccentricity_ratio;
    let (s, c) = psi.sin_cos();
    let w = 1.0 + eps * c;
    let wedge = motion.wedge_speed() * eps * s * (2.0 + eps * c) / ((2.0 + eps * eps) * w * w);
    let squeeze = motion.eccentricity_ratio_rate * (1.0 - c) * (2.0 + eps + eps * c)
        / (w * w * (1.0 + eps) * (1.0 + eps));
    wedge + squeeze
}

fn pressure_scale(params: &ClosedFormParams) -> f64 {
    let rc = params.radius / params.radial_clearance;
    6.0 * params.viscosity * rc * rc
}

/// Full-film pressure (Pa) at the papers' angle ψ (\[Flores2009\] eq. 5).
pub fn full_film_pressure(params: &ClosedFormParams, motion: &JournalMotion, psi: f64) -> f64 {
    pressure_scale(params) * full_film_dimensionless(motion, psi)
}

/// Half-film pressure (Pa) at ψ: the film on 0 … π with p(0) = p(π) = 0, zero beyond π.
pub fn half_film_pressure(params: &ClosedFormParams, motion: &JournalMotion, psi: f64) -> f64 {
    let psi = psi.rem_euclid(std::f64::consts::TAU);
    if psi > PI {
        return 0.0;
    }
    let eps = motion.eccentricity_ratio;
    let k =
        -8.0 * motion.eccentricity_ratio_rate * (1.0 - eps * eps).sqrt() / (PI * (2.0 + eps * eps));
    pressure_scale(params)
        * (full_film_dimensionless(motion, psi) + k * sommerfeld_integral_3(eps, psi))
}

/// (F_r, F_t) of the full film (\[Flores2009\] eqs. 10–11).
///
/// ```
/// use jbearing_solvers::closed_form::{long, ClosedFormParams, JournalMotion};
/// use std::f64::consts::PI;
///
/// // Sommerfeld's long bearing: S = μN/P (R/c)² = (2 + ε²)√(1 − ε²) / (12π²ε), load along the
/// // tangent only (N in rev/s, P = W/(LD)).
/// let params = ClosedFormParams { radius: 0.05, length: 0.2, radial_clearance: 50e-6, viscosity: 0.01 };
/// let (eps, omega) = (0.5, 200.0);
/// let [fr, ft] = long::full_film_force(&params, &JournalMotion::steady(eps, 0.0, omega));
/// let p = ft.abs() / (params.length * 2.0 * params.radius);
/// let sommerfeld = params.viscosity * omega / (2.0 * PI) / p * (0.05f64 / 50e-6).powi(2);
/// let expected = (2.0 + eps * eps) * (1.0 - eps * eps).sqrt() / (12.0 * PI * PI * eps);
/// assert!(fr == 0.0 && (sommerfeld - expected).abs() < 1e-12 * expected);
/// ```
pub fn full_film_force(params: &ClosedFormParams, motion: &JournalMotion) -> [f64; 2] {
    let eps = motion.eccentricity_ratio;
    let s = 1.0 - eps * eps;
    let scale = params.long_scale();
    [
        -scale * 12.0 * PI * motion.eccentricity_ratio_rate / (s * s.sqrt()),
        scale * 12.0 * PI * eps * motion.wedge_speed() / ((2.0 + eps * eps) * s.sqrt()),
    ]
}

/// (F_r, F_t) of the half film (\[Flores2009\] eqs. 12–13).
pub fn half_film_force(params: &ClosedFormParams, motion: &JournalMotion) -> [f64; 2] {
    let eps = motion.eccentricity_ratio;
    let ed = motion.eccentricity_ratio_rate;
    let wp = motion.wedge_speed();
    let s = 1.0 - eps * eps;
    let a = 2.0 + eps * eps;
    let scale = 12.0 * params.long_scale();
    [
        -scale * (eps * eps * wp / (a * s) + ed * (0.5 * PI - 8.0 / (PI * a)) / (s * s.sqrt())),
        scale * (PI * eps * wp / (2.0 * a * s.sqrt()) + 2.0 * eps * ed / (a * s)),
    ]
}

#[cfg(test)]
mod tests {
    use super::super::test_support::simpson;
    use super::super::{ClosedFormModel, film_force, pressure};
    use super::*;
    use std::f64::consts::TAU;

    fn params() -> ClosedFormParams {
        ClosedFormParams {
            radius: 10e-3,
            length: 40e-3,
            radial_clearance: 0.2e-3,
            viscosity: 0.4,
        }
    }

    fn motions() -> Vec<JournalMotion> {
        let mut v = Vec::new();
        for &eps in &[0.0, 0.3, 0.6, 0.85] {
            for &(ed, gd) in &[(0.0, 0.0), (3.0, 5.0), (-7.0, -40.0), (20.0, 30.0)] {
                v.push(JournalMotion {
                    eccentricity_ratio: eps,
                    eccentricity_ratio_rate: ed,
                    line_of_centres_angle: -1.1,
                    line_of_centres_rate: gd,
                    relative_speed: 52.36,
                });
            }
        }
        v
    }

    #[test]
    fn forces_match_the_integrated_pressure() {
        let p = params();
        for m in motions() {
            for (model, end) in [
                (ClosedFormModel::LongSommerfeld, TAU),
                (ClosedFormModel::LongGumbel, PI),
            ] {
                let closed = film_force(model, &p, &m).unwrap();
                let g = m.line_of_centres_angle;
                // F = −∫ p n R L dθ in the bearing frame (θ = γ + π + ψ), Simpson with 8000
                // panels over the film: smooth integrand, error ≪ 1e-9 relative for ε ≤ 0.85.
                let q: Vec<f64> = (0..2)
                    .map(|k| {
                        simpson(
                            |psi| {
                                let th = g + PI + psi;
                                let proj = if k == 0 {
                                    (th - g).cos()
                                } else {
                                    (th - g).sin()
                                };
                                -pressure(model, &p, &m, th, 0.0).unwrap()
                                    * proj
                                    * p.radius
                                    * p.length
                            },
                            0.0,
                            end,
                            8000,
                        )
                    })
                    .collect();
                let scale = closed.radial.hypot(closed.tangential).max(1e-3);
                for (a, b) in [(closed.radial, q[0]), (closed.tangential, q[1])] {
                    assert!(
                        (a - b).abs() < 1e-8 * scale,
                        "{model:?} {m:?}: closed {a} vs quadrature {b}"
                    );
                }
            }
        }
    }

    #[test]
    fn pressures_solve_the_long_bearing_equation_with_their_boundary_values() {
        // (1/R²) d/dψ (h³ dp/dψ) = 12 μ c [ε̇ cos ψ − ½ ω' ε sin ψ], checked by central
        // differences (step 1e-3: truncation ~1e-6 relative).
        let p = params();
        for m in motions() {
            let c = p.radial_clearance;
            let eps = m.eccentricity_ratio;
            for (f, name) in [
                (full_film_pressure as fn(&_, &_, f64) -> f64, "full"),
                (half_film_pressure, "half"),
            ] {
                assert!(f(&p, &m, 0.0).abs() < 1e-6, "{name} p(0)");
                if name == "half" {
                    assert!(f(&p, &m, PI).abs() < 1e-6 * pressure_scale(&p), "p(π)");
                } else {
                    let d = f(&p, &m, 0.0) - f(&p, &m, TAU);
                    assert!(d.abs() < 1e-6, "periodic");
                }
                for &psi in &[0.5, 1.7, 2.9] {
                    let d = 1e-3;
                    let flux = |x: f64| {
                        let h = c * (1.0 + eps * x.cos());
                        h * h * h * (f(&p, &m, x + 0.5 * d) - f(&p, &m, x - 0.5 * d)) / d
                    };
                    let lhs =
                        (flux(psi + 0.5 * d) - flux(psi - 0.5 * d)) / d / (p.radius * p.radius);
                    let rhs = 12.0
                        * p.viscosity
                        * c
                        * (m.eccentricity_ratio_rate * psi.cos()
                            - 0.5 * m.wedge_speed() * eps * psi.sin());
                    let scale = 12.0
                        * p.viscosity
                        * c
                        * (m.eccentricity_ratio_rate.abs() + m.wedge_speed().abs());
                    assert!(
                        (lhs - rhs).abs() < 1e-5 * scale,
                        "{name} {m:?} ψ {psi}: {lhs} vs {rhs}"
                    );
                }
            }
        }
    }

    #[test]
    fn sommerfeld_attitude_is_ninety_degrees_and_gumbel_below() {
        let m = JournalMotion::steady(0.6, 0.0, 50.0);
        let full = full_film_force(&params(), &m);
        assert_eq!(full[0], 0.0);
        let half = half_film_force(&params(), &m);
        // Half Sommerfeld: tan φ = π √(1−ε²) / (2ε) (F_t/(−F_r) from eqs. 12–13 at ε̇ = 0).
        let phi = half[1].atan2(-half[0]);
        assert!((phi.tan() - PI * 0.64f64.sqrt() / 1.2).abs() < 1e-12);
        // The half film carries the full film's tangential force halved.
        assert!((2.0 * half[1] - full[1]).abs() < 1e-12 * full[1]);
    }
}
