//! Pinkus & Sternlicht's dynamic forces of the infinitely long bearing with a moving film
//! (\[Flores2009\] eqs. 14–18, after \[PinkusSternlicht1961\]).
//!
//! For a journal moving radially the film ends are not at ψ = 0 and π; Pinkus & Sternlicht find
//! them and give the forces in closed form with
//!
//! ```text
//!   k² = (1 − ε²) [ (ω'/(2ε̇))² + 1/ε² ]                                    (eq. 18)
//!
//!   ε̇ > 0:  F_r = −(μLR³/c²) 6|ε̇| / ((2+ε²)(1−ε²)^{3/2}) [4kε² + (2+ε²) π (k+3)/(k+3/2)]   (14)
//!           F_t =  (μLR³/c²) 6π ε ω' / ((2+ε²)(1−ε²)^{1/2}) (k+3)/(k+3/2)                (15)
//!   ε̇ < 0:  F_r = −(μLR³/c²) 6|ε̇| / ((2+ε²)(1−ε²)^{3/2}) [4kε² − (2+ε²) π k/(k+3/2)]       (16)
//!           F_t =  (μLR³/c²) 6π ε ω' / ((2+ε²)(1−ε²)^{1/2}) k/(k+3/2)                    (17)
//! ```
//!
//! Two corrections to the print (see the tests):
//! - eq. 15 prints (1 − ε²)^{3/2}; with it F_t would not tend to the Gumbel force of eq. 13 as
//!   ε̇ → 0⁺ (k → ∞), while eq. 17 with ^{1/2} does. ^{1/2} in both.
//! - eqs. 14/16 print the prefactor ε̇. For ε̇ < 0 that flips the wedge term 6ε̇·4kε² (k ε̇ →
//!   ±√(1−ε²)|ω'|/2 as ε̇ → 0±) and F_r would jump between ∓12ε²|ω'|/((2+ε²)(1−ε²)) as ε̇
//!   changes sign. With |ε̇| the force is continuous, equals the Gumbel long bearing at ε̇ = 0,
//!   and the squeeze part opposes the motion in both cases (it damps); that reading is used.
//!
//! Evaluated without dividing by ε or ε̇: with q = ε k |ε̇| = √(1−ε²) √(ε²ω'²/4 + ε̇²),
//! 4kε²|ε̇| = 4εq and (k+3)/(k+3/2) = (q + 3ε|ε̇|)/(q + 1.5ε|ε̇|), k/(k+3/2) = q/(q + 1.5ε|ε̇|);
//! at ε̇ = 0 (k = ∞) both ratios are 1.

use super::{ClosedFormParams, JournalMotion};
use std::f64::consts::PI;

/// The parameter k of eq. 18 (∞ when ε̇ = 0 or ε = 0).
pub fn k_parameter(motion: &JournalMotion) -> f64 {
    let eps = motion.eccentricity_ratio;
    let ed = motion.eccentricity_ratio_rate;
    let wp = motion.wedge_speed();
    if ed == 0.0 || eps == 0.0 {
        return f64::INFINITY;
    }
    ((1.0 - eps * eps) * ((wp / (2.0 * ed)).powi(2) + 1.0 / (eps * eps))).sqrt()
}

/// (F_r, F_t) of \[Flores2009\] eqs. 14–17 (with the corrections of the module docs).
///
/// ```
/// use jbearing_solvers::closed_form::{long, pinkus_sternlicht, ClosedFormParams, JournalMotion};
///
/// let params = ClosedFormParams { radius: 0.01, length: 0.04, radial_clearance: 0.2e-3, viscosity: 0.4 };
/// let at_rest = JournalMotion::steady(0.7, 1.0, 500.0);
/// // At ε̇ = 0 the moving film ends sit at the Gumbel ends: the long half film's force.
/// let [fr, ft] = pinkus_sternlicht::film_force(&params, &at_rest);
/// let [gr, gt] = long::half_film_force(&params, &at_rest);
/// assert!((fr - gr).abs() < 1e-9 * gr.abs() && (ft - gt).abs() < 1e-9 * gt.abs());
/// // The squeeze part opposes the motion: moving outwards (ε̇ > 0) adds an inward force.
/// let outwards = JournalMotion { eccentricity_ratio_rate: 50.0, ..at_rest };
/// assert!(pinkus_sternlicht::film_force(&params, &outwards)[0] < fr);
/// ```
pub fn film_force(params: &ClosedFormParams, motion: &JournalMotion) -> [f64; 2] {
    let eps = motion.eccentricity_ratio;
    let ed = motion.eccentricity_ratio_rate;
    let wp = motion.wedge_speed();
    let s = 1.0 - eps * eps;
    let a = 2.0 + eps * eps;
    let q = s.sqrt() * (0.25 * eps * eps * wp * wp + ed * ed).sqrt();
    let m = eps * ed.abs();
    let ratio = |num: f64| {
        let den = q + 1.5 * m;
        if den > 0.0 { num / den } else { 1.0 }
    };
    let scale = params.long_scale();
    let (squeeze, r) = if ed > 0.0 {
        let r = ratio(q + 3.0 * m);
        (a * PI * ed * r, r)
    } else {
        let r = ratio(q);
        (-a * PI * ed.abs() * r, r)
    };
    [
        -scale * 6.0 / (a * s * s.sqrt()) * (4.0 * eps * q + squeeze),
        scale * 6.0 * PI * eps * wp / (a * s.sqrt()) * r,
    ]
}

#[cfg(test)]
mod tests {
    use super::super::long;
    use super::*;

    fn params() -> ClosedFormParams {
        ClosedFormParams {
            radius: 9.8e-3,
            length: 40e-3,
            radial_clearance: 0.2e-3,
            viscosity: 0.4,
        }
    }

    fn motion(eps: f64, ed: f64) -> JournalMotion {
        JournalMotion {
            eccentricity_ratio: eps,
            eccentricity_ratio_rate: ed,
            line_of_centres_angle: 0.0,
            line_of_centres_rate: 3.0,
            relative_speed: 52.36,
        }
    }

    /// The printed formulas with k from eq. 18 for ε̇ > 0 (eq. 14 and eq. 15 with ^{1/2}).
    fn printed_positive(eps: f64, ed: f64, wp: f64) -> [f64; 2] {
        let k = ((1.0 - eps * eps) * ((wp / (2.0 * ed)).powi(2) + 1.0 / (eps * eps))).sqrt();
        let a = 2.0 + eps * eps;
        let s = 1.0 - eps * eps;
        [
            -6.0 * ed / (a * s.powf(1.5)) * (4.0 * k * eps * eps + a * PI * (k + 3.0) / (k + 1.5)),
            6.0 * PI * eps * wp / (a * s.sqrt()) * (k + 3.0) / (k + 1.5),
        ]
    }

    #[test]
    fn agrees_with_the_printed_form_for_positive_rate() {
        let p = params();
        for &eps in &[0.1, 0.4, 0.8] {
            for &ed in &[1e-3, 0.5, 7.0] {
                let m = motion(eps, ed);
                let f = film_force(&p, &m);
                let r = printed_positive(eps, ed, m.wedge_speed());
                for k in 0..2 {
                    let want = r[k] * p.long_scale();
                    assert!((f[k] - want).abs() < 1e-12 * want.abs(), "{eps} {ed} {k}");
                }
            }
        }
    }

    #[test]
    fn tends_to_the_gumbel_long_bearing_from_both_sides_and_damps() {
        let p = params();
        for &eps in &[0.05, 0.4, 0.8, 0.95] {
            let rest = motion(eps, 0.0);
            let g = long::half_film_force(
                &p,
                &JournalMotion {
                    eccentricity_ratio_rate: 0.0,
                    ..rest
                },
            );
            let at_rest = film_force(&p, &rest);
            // Wedge part of eq. 12 and eq. 13 at ε̇ = 0.
            for k in 0..2 {
                assert!((at_rest[k] - g[k]).abs() < 1e-12 * g[0].hypot(g[1]));
            }
            for &ed in &[1e-7, -1e-7] {
                let f = film_force(&p, &motion(eps, ed));
                for k in 0..2 {
                    assert!((f[k] - g[k]).abs() < 1e-5 * g[0].hypot(g[1]), "{eps} {ed}");
                }
            }
            // The squeeze part opposes the radial motion: F_r(ε̇) − F_r(0) has the sign of −ε̇.
            for &ed in &[0.3, -0.3] {
                let f = film_force(&p, &motion(eps, ed));
                assert!((f[0] - at_rest[0]) * ed < 0.0, "{eps} {ed}");
            }
        }
    }

    #[test]
    fn k_parameter_follows_eq_18() {
        let m = motion(0.5, 0.3);
        let wp = m.wedge_speed();
        let k = k_parameter(&m);
        assert!((k * k - 0.75 * ((wp / 0.6).powi(2) + 4.0)).abs() < 1e-10 * k * k);
        assert!(k_parameter(&motion(0.5, 0.0)).is_infinite());
    }
}
