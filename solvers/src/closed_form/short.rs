//! The infinitely short bearing (Dubois & Ocvirk) for a moving journal.
//!
//! Dropping the circumferential flow term of the Reynolds equation (see [`super`]) and taking
//! p = 0 at z = ±L/2 (\[Flores2009\] eq. 3 with the missing c restored; \[Flores2006\] eq. 18):
//!
//! ```text
//!   p(ψ, z) = 3 μ (L²/4 − z²) / (c² (1 + ε cos ψ)³) · [ ω' ε sin ψ − 2 ε̇ cos ψ ],   ω' = ω − 2γ̇
//! ```
//!
//! Forces on the journal, in units of μ R L³ / c² (F_r along ê, F_t along t̂, see [`super`]):
//!
//! ```text
//!   Sommerfeld, ψ ∈ (0, 2π)  ([Flores2009] eqs. 6–7, eq. 6 with the exponent 5/2):
//!     F_r = −π ε̇ (1 + 2ε²) / (1 − ε²)^{5/2}
//!     F_t =  π ε ω' / (2 (1 − ε²)^{3/2})
//!   Gumbel, ψ ∈ (0, π)  ([Flores2009] eqs. 8–9):
//!     F_r = −[π ε̇ (1 + 2ε²)/(1 − ε²)^{1/2} + 2 ε² ω'] / (2 (1 − ε²)²)
//!     F_t =  ε [4 ε̇ + (π/2) ω' (1 − ε²)^{1/2}] / (2 (1 − ε²)²)
//! ```
//!
//! Gumbel with the moving half film (\[Flores2006\] eqs. 36–37): the bracket is A sin(ψ − ψ_i) with
//! ψ_i = atan2(2ε̇, ε ω'), so p > 0 exactly on ψ ∈ (ψ_i, ψ_i + π). Wedge plus squeeze is then
//! Booker's pure squeeze with the velocity u = v/c = (ε̇, −ε ω'/2) in the frame of ε, and the
//! force is F = −(μ R L³/c²) J(u) with the exact integrals J of
//! [`crate::mobility::short_bearing::short_bearing_squeeze_integral`] (reused, not duplicated).

use super::{ClosedFormParams, JournalMotion};
use crate::mobility::short_bearing_squeeze_integral;
use std::f64::consts::PI;

/// Pressure (Pa) at the papers' angle ψ (from the maximum film) and z, unclipped (full film).
pub fn pressure(params: &ClosedFormParams, motion: &JournalMotion, psi: f64, z: f64) -> f64 {
    let eps = motion.eccentricity_ratio;
    let c = params.radial_clearance;
    let w = 1.0 + eps * psi.cos();
    let axial = 0.25 * params.length * params.length - z * z;
    let bracket =
        motion.wedge_speed() * eps * psi.sin() - 2.0 * motion.eccentricity_ratio_rate * psi.cos();
    3.0 * params.viscosity * axial * bracket / (c * c * w * w * w)
}

/// (F_r, F_t) of the full film (\[Flores2009\] eqs. 6–7).
pub fn full_film_force(params: &ClosedFormParams, motion: &JournalMotion) -> [f64; 2] {
    let eps = motion.eccentricity_ratio;
    let s = 1.0 - eps * eps;
    let ss = s.sqrt();
    let scale = params.short_scale();
    [
        -scale * PI * motion.eccentricity_ratio_rate * (1.0 + 2.0 * eps * eps) / (s * s * ss),
        scale * PI * eps * motion.wedge_speed() / (2.0 * s * ss),
    ]
}

/// (F_r, F_t) of the half film ψ ∈ (0, π) (\[Flores2009\] eqs. 8–9).
pub fn half_film_force(params: &ClosedFormParams, motion: &JournalMotion) -> [f64; 2] {
    let eps = motion.eccentricity_ratio;
    let ed = motion.eccentricity_ratio_rate;
    let wp = motion.wedge_speed();
    let s = 1.0 - eps * eps;
    let ss = s.sqrt();
    let scale = params.short_scale() / (2.0 * s * s);
    [
        -scale * (PI * ed * (1.0 + 2.0 * eps * eps) / ss + 2.0 * eps * eps * wp),
        scale * eps * (4.0 * ed + 0.5 * PI * wp * ss),
    ]
}

/// (F_r, F_t) of the moving positive-pressure half film (\[Flores2006\] eqs. 18, 21–22, 36–37).
pub fn moving_half_film_force(params: &ClosedFormParams, motion: &JournalMotion) -> [f64; 2] {
    let eps = motion.eccentricity_ratio;
    let u = [
        motion.eccentricity_ratio_rate,
        -0.5 * eps * motion.wedge_speed(),
    ];
    let j = short_bearing_squeeze_integral([eps, 0.0], u);
    let scale = params.short_scale();
    [-scale * j[0], -scale * j[1]]
}

/// The start ψ_i of the positive-pressure half film (\[Flores2006\] eq. 36, quadrant-correct), in
/// [0, 2π); the film ends at ψ_i + π (eq. 37).
pub fn moving_film_start(motion: &JournalMotion) -> f64 {
    (2.0 * motion.eccentricity_ratio_rate)
        .atan2(motion.eccentricity_ratio * motion.wedge_speed())
        .rem_euclid(std::f64::consts::TAU)
}

#[cfg(test)]
mod tests {
    use super::super::test_support::simpson;
    use super::super::{ClosedFormModel, film_force, pressure as model_pressure};
    use super::*;
    use std::f64::consts::TAU;

    fn params() -> ClosedFormParams {
        ClosedFormParams {
            radius: 9.8e-3,
            length: 8e-3,
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
                    line_of_centres_angle: 0.7,
                    line_of_centres_rate: gd,
                    relative_speed: 52.36,
                });
            }
        }
        v
    }

    /// F = −∫∫ p n R dθ dz by Simpson in θ (bearing frame, 4000 panels per piece, split at the
    /// film ends where the clipped pressure jumps) and Simpson in z, projected on ê, t̂.
    fn integrate(model: ClosedFormModel, m: &JournalMotion, breaks: &[f64]) -> [f64; 2] {
        let p = params();
        let l = p.length;
        let g = m.line_of_centres_angle;
        let mut f = [0.0; 2];
        let mut pts = vec![0.0];
        pts.extend(breaks.iter().map(|b| b.rem_euclid(TAU)));
        pts.push(TAU);
        pts.sort_by(f64::total_cmp);
        for (k, fk) in f.iter_mut().enumerate() {
            for w in pts.windows(2).filter(|w| w[1] - w[0] > 1e-9) {
                // θ = γ + π + ψ; integrate in ψ over the windows.
                // One-sided limits at the window ends (the clipped pressure jumps there when
                // ε̇ ≠ 0): evaluate a hair inside the window.
                let (a, b) = (w[0] + 1e-12, w[1] - 1e-12);
                *fk += simpson(
                    |psi| {
                        let th = g + PI + psi.clamp(a, b);
                        let proj = if k == 0 {
                            (th - g).cos()
                        } else {
                            (th - g).sin()
                        };
                        let pz = simpson(
                            |z| model_pressure(model, &p, m, th, z).unwrap(),
                            -0.5 * l,
                            0.5 * l,
                            2,
                        );
                        -pz * proj * p.radius
                    },
                    w[0],
                    w[1],
                    4000,
                );
            }
        }
        f
    }

    #[test]
    fn forces_match_the_integrated_pressure() {
        for m in motions() {
            let cases = [
                (ClosedFormModel::ShortSommerfeld, vec![]),
                (ClosedFormModel::ShortGumbel, vec![PI]),
                (
                    ClosedFormModel::ShortGumbelMovingFilm,
                    vec![moving_film_start(&m), moving_film_start(&m) + PI],
                ),
            ];
            for (model, breaks) in cases {
                let closed = film_force(model, &params(), &m).unwrap();
                let q = integrate(model, &m, &breaks);
                let scale = closed.radial.hypot(closed.tangential).max(1e-3);
                // Simpson in z is exact (quadratic); in ψ, 4000 panels per piece of a smooth
                // integrand: error ≪ 1e-8 relative up to ε = 0.85.
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
    fn full_film_wedge_force_is_twice_the_half_film_and_perpendicular() {
        let m = JournalMotion::steady(0.5, 0.0, 100.0);
        let full = full_film_force(&params(), &m);
        let half = half_film_force(&params(), &m);
        assert_eq!(full[0], 0.0);
        assert!((full[1] - 2.0 * half[1]).abs() < 1e-12 * full[1]);
        // Ocvirk's half film: tan φ = π √(1−ε²)/(4ε) (attitude between load and line of centres).
        let phi = half[1].atan2(-half[0]);
        assert!((phi.tan() - PI * 0.75f64.sqrt() / 2.0).abs() < 1e-12);
    }

    #[test]
    fn moving_film_equals_fixed_half_film_for_a_journal_at_rest() {
        let m = JournalMotion::steady(0.7, 1.0, 80.0);
        let a = half_film_force(&params(), &m);
        let b = moving_half_film_force(&params(), &m);
        for k in 0..2 {
            assert!((a[k] - b[k]).abs() < 1e-10 * a[0].hypot(a[1]));
        }
        assert!(moving_film_start(&m).abs() < 1e-15);
    }

    #[test]
    fn pressure_solves_the_short_bearing_reynolds_equation() {
        // h³ ∂²p/∂z² = 12 μ c [ε̇ cos ψ − ½ ω' ε sin ψ] (module docs of super), by a central
        // second difference in z (exact for the quadratic profile up to round-off).
        let p = params();
        for m in motions() {
            for &psi in &[0.4, 2.0, 4.0] {
                let dz = 1e-4;
                let f = |z: f64| pressure(&p, &m, psi, z);
                let d2 = (f(dz) - 2.0 * f(0.0) + f(-dz)) / (dz * dz);
                let h = p.radial_clearance * (1.0 + m.eccentricity_ratio * psi.cos());
                let lhs = h * h * h * d2;
                let rhs = 12.0
                    * p.viscosity
                    * p.radial_clearance
                    * (m.eccentricity_ratio_rate * psi.cos()
                        - 0.5 * m.wedge_speed() * m.eccentricity_ratio * psi.sin());
                assert!(
                    (lhs - rhs).abs() < 1e-6 * rhs.abs().max(1e-9),
                    "{lhs} vs {rhs}"
                );
                assert!(pressure(&p, &m, psi, 0.5 * p.length).abs() < 1e-9);
            }
        }
    }
}
