//! Static equilibrium of the closed-form models: the journal position at which the film force
//! of a journal at rest (ε̇ = γ̇ = 0) balances a constant load, F(ε, γ) + W = 0 (docs/conventions.md §1).
//!
//! At rest every model gives F_r = −a(ε)|ω|, F_t = b(ε)ω in the line-of-centres frame, so the
//! magnitude |F|(ε) depends on ε only and the direction on γ only:
//!
//! ```text
//!   1. solve |F|(ε) = |W| for ε ∈ (0, 1 − 1e-12) by bisection (|F| rises from 0 to ∞)
//!   2. β = atan2(F_t, F_r), the direction of F from ê;  γ = angle(−W) − β
//!   3. attitude angle φ = γ − angle(W), from the load line to the line of centres, positive
//!      in the direction of rotation
//! ```
//!
//! The fixed-region Gumbel models assume ω' > 0 (film on ψ ∈ 0 … π, the converging half). For
//! ω < 0 the problem is solved mirrored (y → −y) and mirrored back, so that every model puts the
//! journal in the converging half for either direction of rotation.

use super::{ClosedFormError, ClosedFormModel, ClosedFormParams, JournalMotion, film_force};
use std::f64::consts::{PI, TAU};

/// Largest eccentricity ratio the equilibrium search may return.
pub const MAX_ECCENTRICITY: f64 = 1.0 - 1e-12;

/// The steady equilibrium of one model under one load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EquilibriumSolution {
    /// The model.
    pub model: ClosedFormModel,
    /// ε.
    pub eccentricity_ratio: f64,
    /// φ: angle from the load direction to the line of centres, positive in the direction of
    /// rotation (rad).
    pub attitude_angle: f64,
    /// γ: angle of the line of centres from +x (rad).
    pub line_of_centres_angle: f64,
    /// ε as a vector in the bearing frame.
    pub eccentricity_ratio_vector: [f64; 2],
    /// Film force on the journal at the solution (N); equals −W to the solver tolerance. For
    /// ω < 0 it is the mirrored model's force (see the module docs).
    pub film_force: [f64; 2],
    /// h_min = c (1 − ε) (m) (\[Flores2009\] eq. 42).
    pub min_film_thickness: f64,
    /// Sommerfeld number S = μ N L D / |W| (R/c)², N = |ω|/2π (rev/s).
    pub sommerfeld_number: f64,
    /// Bisection steps taken.
    pub iterations: usize,
}

/// The static equilibrium of `model` under the load `load` = W (N, the force the machine applies
/// to the journal, bearing frame) at relative speed ω = ω_j − ω_b (rad/s).
///
/// ```
/// use jbearing_solvers::closed_form::{ClosedFormModel, ClosedFormParams, static_equilibrium};
///
/// let params = ClosedFormParams { radius: 9.8e-3, length: 40e-3, radial_clearance: 0.2e-3, viscosity: 0.4 };
/// let eq = static_equilibrium(ClosedFormModel::LongSommerfeld, &params, [0.0, -31.275], 52.36)?;
/// // The full Sommerfeld film puts the journal 90° from the load.
/// assert!((eq.attitude_angle.to_degrees() - 90.0).abs() < 1e-9);
/// # Ok::<(), jbearing_solvers::closed_form::ClosedFormError>(())
/// ```
pub fn static_equilibrium(
    model: ClosedFormModel,
    params: &ClosedFormParams,
    load: [f64; 2],
    relative_speed: f64,
) -> Result<EquilibriumSolution, ClosedFormError> {
    params.validate()?;
    for (name, value) in [
        ("load[0]", load[0]),
        ("load[1]", load[1]),
        ("relative_speed", relative_speed),
    ] {
        if !value.is_finite() {
            return Err(ClosedFormError::InvalidParameter { name, value });
        }
    }
    let w = load[0].hypot(load[1]);
    if relative_speed == 0.0 {
        return Err(ClosedFormError::NoLoadCapacity { relative_speed });
    }
    let omega = relative_speed.abs();
    let mirror = relative_speed < 0.0;
    let (eps, iterations) = eccentricity_for_load(model, params, w, omega)?;
    // Steps 2 and 3, the direction: solve in the (possibly mirrored) frame where ω > 0.
    let wm = if mirror { [load[0], -load[1]] } else { load };
    let f0 = film_force(
        model,
        params,
        &JournalMotion::steady(eps.max(1e-300), 0.0, omega),
    )?;
    let beta = f0.tangential.atan2(f0.radial);
    let load_angle = wm[1].atan2(wm[0]);
    let gamma_m = load_angle + PI - beta;
    let (gamma, load_angle_true) = if mirror {
        (-gamma_m, load[1].atan2(load[0]))
    } else {
        (gamma_m, load_angle)
    };
    let gamma = wrap(gamma);
    let attitude = wrap((gamma - load_angle_true) * relative_speed.signum());
    // The film force at the solution, from the (mirrored) model and mirrored back.
    let fm = film_force(model, params, &JournalMotion::steady(eps, gamma_m, omega))?.cartesian;
    let force = if mirror { [fm[0], -fm[1]] } else { fm };
    let rc = params.radius / params.radial_clearance;
    let sommerfeld_number = if w > 0.0 {
        params.viscosity * (omega / TAU) * params.length * 2.0 * params.radius / w * rc * rc
    } else {
        f64::INFINITY
    };
    Ok(EquilibriumSolution {
        model,
        eccentricity_ratio: eps,
        attitude_angle: attitude,
        line_of_centres_angle: gamma,
        eccentricity_ratio_vector: [eps * gamma.cos(), eps * gamma.sin()],
        film_force: force,
        min_film_thickness: params.radial_clearance * (1.0 - eps),
        sommerfeld_number,
        iterations,
    })
}

/// Step 1 of the module docs: ε ∈ [0, [`MAX_ECCENTRICITY`]] with |F|(ε) = `w` at rest at speed
/// `omega` > 0, by bisection to 1e-15 (at most 200 steps), with the steps taken; a load above
/// the film's capacity at the limit is a film collapse.
fn eccentricity_for_load(
    model: ClosedFormModel,
    params: &ClosedFormParams,
    w: f64,
    omega: f64,
) -> Result<(f64, usize), ClosedFormError> {
    let magnitude = |eps: f64| -> Result<f64, ClosedFormError> {
        let f = film_force(model, params, &JournalMotion::steady(eps, 0.0, omega))?;
        Ok(f.radial.hypot(f.tangential))
    };
    let (mut lo, mut hi) = (0.0, MAX_ECCENTRICITY);
    let capacity = magnitude(hi)?;
    if capacity < w {
        return Err(ClosedFormError::FilmCollapse {
            model: model.name(),
            load: w,
            limit: MAX_ECCENTRICITY,
            capacity,
        });
    }
    let mut iterations = 0;
    if w == 0.0 {
        return Ok((0.0, iterations));
    }
    while hi - lo > 1e-15 && iterations < 200 {
        iterations += 1;
        let mid = 0.5 * (lo + hi);
        if magnitude(mid)? < w {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((0.5 * (lo + hi), iterations))
}

/// Angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(TAU);
    if r > PI { r - TAU } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> ClosedFormParams {
        ClosedFormParams {
            radius: 9.8e-3,
            length: 40e-3,
            radial_clearance: 0.2e-3,
            viscosity: 0.4,
        }
    }

    #[test]
    fn every_model_balances_the_load_for_both_rotations() {
        for model in ClosedFormModel::ALL {
            for &omega in &[52.36, -52.36] {
                for load in [[0.0, -31.275], [12.0, 5.0], [-300.0, 80.0]] {
                    let s = static_equilibrium(model, &params(), load, omega).unwrap();
                    let wn = load[0].hypot(load[1]);
                    for k in 0..2 {
                        // Bisection to 1e-15 in ε: the force balance closes to ~1e-9 relative.
                        assert!(
                            (s.film_force[k] + load[k]).abs() < 1e-8 * wn,
                            "{model:?} ω {omega} {load:?}: {:?}",
                            s.film_force
                        );
                    }
                    // The journal sits in the converging half: 0 < φ ≤ 90° in the rotation sense.
                    assert!(
                        s.attitude_angle > 0.0 && s.attitude_angle <= 0.5 * PI + 1e-9,
                        "{model:?} ω {omega}: φ {}",
                        s.attitude_angle
                    );
                }
            }
        }
    }

    #[test]
    fn ocvirk_half_film_equilibrium_matches_the_textbook_closed_form() {
        // Ocvirk (half film): W c² / (μ ω R L³) = ε √(π²(1−ε²) + 16ε²) / (4 (1−ε²)²) and
        // tan φ = π √(1−ε²) / (4ε) — an independent statement of the same model.
        let p = params();
        let omega = 52.36;
        for &eps in &[0.2, 0.5, 0.9] {
            let s2 = 1.0 - eps * eps;
            let w = p.short_scale() * omega * eps * (PI * PI * s2 + 16.0 * eps * eps).sqrt()
                / (4.0 * s2 * s2);
            let sol =
                static_equilibrium(ClosedFormModel::ShortGumbel, &p, [0.0, -w], omega).unwrap();
            assert!((sol.eccentricity_ratio - eps).abs() < 1e-12);
            let phi = (PI * s2.sqrt() / (4.0 * eps)).atan();
            assert!((sol.attitude_angle - phi).abs() < 1e-12);
        }
    }

    #[test]
    fn sommerfeld_models_sit_at_ninety_degrees() {
        for model in [
            ClosedFormModel::ShortSommerfeld,
            ClosedFormModel::LongSommerfeld,
        ] {
            let s = static_equilibrium(model, &params(), [0.0, -31.275], 52.36).unwrap();
            assert!((s.attitude_angle - 0.5 * PI).abs() < 1e-12);
        }
    }

    #[test]
    fn impossible_requests_are_errors() {
        assert!(matches!(
            static_equilibrium(ClosedFormModel::LongGumbel, &params(), [0.0, -1.0], 0.0),
            Err(ClosedFormError::NoLoadCapacity { .. })
        ));
        assert!(
            static_equilibrium(ClosedFormModel::LongGumbel, &params(), [f64::NAN, 1.0], 1.0)
                .is_err()
        );
    }
}
