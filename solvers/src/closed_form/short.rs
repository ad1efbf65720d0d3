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
use std::f64::consts::{PI, TAU};

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

/// Ocvirk's steady short-bearing load (N) at eccentricity ratio ε for the relative speed
/// ω = ω_j − ω_b (rad/s), the half (Gumbel) film of a journal at rest (\[Flores2009\] eqs. 8–9
/// with ε̇ = 0):
///
/// ```text
///   W = (μ U L³ / 4c²) ε √(16ε² + π²(1 − ε²)) / (1 − ε²)²,   U = R |ω|
/// ```
///
/// ```
/// use jbearing_solvers::closed_form::{ClosedFormParams, short};
/// let p = ClosedFormParams { radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02 };
/// // The load grows without bound towards the wall.
/// assert!(short::ocvirk_steady_load(&p, 0.9, 300.0) > 10.0 * short::ocvirk_steady_load(&p, 0.3, 300.0));
/// ```
pub fn ocvirk_steady_load(
    params: &ClosedFormParams,
    eccentricity: f64,
    relative_speed: f64,
) -> f64 {
    let e2 = eccentricity * eccentricity;
    let u = params.radius * relative_speed.abs();
    params.viscosity * u * params.length.powi(3) / (4.0 * params.radial_clearance.powi(2))
        * eccentricity
        * (16.0 * e2 + PI * PI * (1.0 - e2)).sqrt()
        / ((1.0 - e2) * (1.0 - e2))
}

/// Ocvirk's steady attitude angle φ (rad) between the load line and the line of centres,
/// tan φ = π √(1 − ε²) / (4ε) (the journal lies φ ahead of the load in the direction of U).
pub fn ocvirk_attitude(eccentricity: f64) -> f64 {
    (PI * (1.0 - eccentricity * eccentricity).sqrt()).atan2(4.0 * eccentricity)
}

/// Couette shear torque of a full 360° film, T_s = 2π μ R³ L ω / (c √(1 − ε²)) (N·m), ω = ω_j − ω_b
/// (Petroff's torque with the eccentricity factor ∫₀^{2π} dθ/(1 − ε cos θ) = 2π/√(1 − ε²)).
///
/// The short-bearing films (mobility, closed forms) carry no film-fraction field, so the shear
/// acts over the whole circumference (docs/conventions.md §5); the film's friction torques are
/// T_journal = −T_s − ½ (e × F)_z and T_bearing = T_s − ½ (e × F)_z, and its Couette
/// dissipation T_s ω.
pub fn couette_shear_torque(
    params: &ClosedFormParams,
    eccentricity: f64,
    relative_speed: f64,
) -> f64 {
    let r = params.radius;
    TAU * params.viscosity * r * r * r * params.length * relative_speed
        / (params.radial_clearance * (1.0 - eccentricity * eccentricity).sqrt())
}

/// Peak of the moving Gumbel film's mid-plane pressure (\[Flores2006\] eq. 18 at z = 0)
///
/// ```text
///   p(θ) = (3 μ L² / 2c²) (u·n) / (1 − ε·n)³   where u·n > 0,   n = (cos θ, sin θ)
/// ```
///
/// for the journal at `eps` (bearing frame) with the squeeze velocity u = v/c = ε̇ − ω̄ × ε (1/s):
/// returns (p_max (Pa, ≥ 0), its angle θ (rad) in [0, 2π)); (0, 0) for u = 0.
///
/// With Sommerfeld's substitution (1 − ε cos θ' = s/(1 + ε cos γ), s = 1 − ε², θ' from ε) the
/// function is the trigonometric polynomial (1 + ε cos γ)² [u'_x (cos γ + ε) + u'_y √s sin γ] / s³
/// in γ, smooth even as ε → 1: 24 samples locate its global maximum (degree 3: at most three
/// maxima, each O(1) wide in γ) and a safeguarded Newton iteration on its derivative polishes it.
///
/// ```
/// use jbearing_solvers::closed_form::{ClosedFormParams, short};
/// let p = ClosedFormParams { radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02 };
/// // Pure squeeze towards +x at ε = 0: the peak is 3μL²|u|/(2c²), at θ = 0.
/// let (p_max, at) = short::moving_film_peak_pressure(&p, [0.0, 0.0], [10.0, 0.0]);
/// assert!((p_max - 1.5 * 0.02 * 1e-4 * 10.0 / 1.6e-9).abs() < 1e-9 * p_max);
/// assert!(at.min(std::f64::consts::TAU - at) < 1e-9);
/// ```
pub fn moving_film_peak_pressure(
    params: &ClosedFormParams,
    eps: [f64; 2],
    u: [f64; 2],
) -> (f64, f64) {
    let e = eps[0].hypot(eps[1]);
    if u[0] == 0.0 && u[1] == 0.0 {
        return (0.0, 0.0);
    }
    let (cx, sx) = if e > 0.0 {
        (eps[0] / e, eps[1] / e)
    } else {
        (1.0, 0.0)
    };
    let a = u[0] * cx + u[1] * sx;
    let b = -u[0] * sx + u[1] * cx;
    let s = 1.0 - e * e;
    let rs = s.sqrt();
    // f(γ) = q² g with q = 1 + ε cos γ, g = a (cos γ + ε) + b √s sin γ; f' and f'' analytic.
    let derivs = |x: f64| {
        let (sn, cs) = x.sin_cos();
        let q = 1.0 + e * cs;
        let (q1, q2) = (-e * sn, -e * cs);
        let g = a * (cs + e) + b * rs * sn;
        let g1 = -a * sn + b * rs * cs;
        let g2 = -a * cs - b * rs * sn;
        let f = q * q * g;
        let f1 = 2.0 * q * q1 * g + q * q * g1;
        let f2 = 2.0 * (q1 * q1 + q * q2) * g + 4.0 * q * q1 * g1 + q * q * g2;
        (f, f1, f2)
    };
    const N: usize = 24;
    let dg = TAU / N as f64;
    let (mut best_g, mut best_f) = (0.0, f64::NEG_INFINITY);
    for k in 0..N {
        let g = -PI + k as f64 * dg;
        let v = derivs(g).0;
        if v > best_f {
            best_f = v;
            best_g = g;
        }
    }
    let (lo, hi) = (best_g - dg, best_g + dg);
    let mut g = best_g;
    for _ in 0..50 {
        let (_, f1, f2) = derivs(g);
        // Newton step when f'' < 0 (a maximum ahead); otherwise a gradient step of dg/4.
        let step = if f2 < 0.0 {
            -f1 / f2
        } else {
            0.25 * dg * f1.signum()
        };
        let next = (g + step).clamp(lo, hi);
        let done = (next - g).abs() < 1e-13;
        g = next;
        if done {
            break;
        }
    }
    if derivs(g).0 < best_f {
        g = best_g;
    }
    let fmax = derivs(g).0.max(best_f) / (s * s * s);
    let c = params.radial_clearance;
    let p = 1.5 * params.viscosity * params.length * params.length / (c * c) * fmax;
    // Back from γ to θ' (inverse Sommerfeld map), then to the bearing frame.
    let half = 0.5 * g;
    let theta_p = 2.0 * ((1.0 - e).sqrt() * half.sin()).atan2((1.0 + e).sqrt() * half.cos());
    let ang = (theta_p + sx.atan2(cx)).rem_euclid(TAU);
    (p.max(0.0), ang)
}

#[cfg(test)]
mod tests {
    use super::super::test_support::simpson;
    use super::super::{ClosedFormModel, film_force, pressure as model_pressure};
    use super::*;

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
