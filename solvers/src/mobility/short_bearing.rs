//! Short-bearing (Ocvirk) pure-squeeze film under Gumbel's half-film condition: the squeeze
//! force in closed form, Booker's closed-form mobility and the exact short-bearing mobility.
//!
//! # Pure squeeze of the short bearing
//!
//! Dropping the circumferential pressure flow (Dubois & Ocvirk; \[Flores2006\] eq. 17) and writing the
//! right-hand side as a pure squeeze with velocity v (see [`super`]):
//!
//! ```text
//!   ∂/∂z (h³/12μ ∂p/∂z) = −v·n   ⇒   p(θ, z) = 6μ (v·n)/h³ · (L²/4 − z²)      ([Flores2006] eq. 18)
//! ```
//!
//! Gumbel: p = 0 where v·n < 0 (the half of the film that opens). The film force on the journal,
//! F = −∫∫ p n R dθ dz (\[Flores2006\] eqs. 21–22), is with h = c(1 − ε·n) and u = v/c
//!
//! ```text
//!   F = −(μ R L³ / c²) · J(u),   J(u) = ∫_{u·n > 0} (u·n) n / (1 − ε·n)³ dθ
//! ```
//!
//! In the frame of ε (θ' from the line of centres, ε = |ε|) J is the 2×2 matrix of Booker's
//! integrals I₃^{lm} (\[Flores2006\] eq. 27) over the half range θ' ∈ (α − π/2, α + π/2), α the
//! direction of u:
//!
//! ```text
//!   J' = | I₃^{02}  I₃^{11} | u'      I₃^{02} = ∫cos²/w³,  I₃^{11} = ∫sin cos/w³,  I₃^{20} = ∫sin²/w³
//!        | I₃^{11}  I₃^{20} |         w = 1 − ε cos θ'
//! ```
//!
//! They are evaluated exactly with Sommerfeld's substitution 1 − ε cos θ' = (1 − ε²)/(1 + ε cos γ),
//! tan(θ'/2) = √((1−ε)/(1+ε)) tan(γ/2), which turns each integrand into a trigonometric
//! polynomial of degree 2 in γ (s = 1 − ε²):
//!
//! ```text
//!   I₃^{02} = s^{-5/2} ∫ (cos γ + ε)² dγ = s^{-5/2} [γ/2 + sin 2γ/4 + 2ε sin γ + ε² γ]
//!   I₃^{11} = s^{-2}   ∫ sin γ (cos γ + ε) dγ = s^{-2} [sin² γ/2 − ε cos γ]
//!   I₃^{20} = s^{-3/2} ∫ sin² γ dγ = s^{-3/2} [γ/2 − sin 2γ/4]
//! ```
//!
//! No cancellation at small ε and no resolution problem near ε → 1 (the substitution stretches
//! the thin-film peak).
//!
//! # Mobility
//!
//! The applied load balances the film force, W = −F = (μRL³/c²) J(u). With
//! u = |W|(c/R)²/(μLD) · M this gives, for a load along ζ,
//!
//! ```text
//!   M = û / (2 (L/D)² |J(û)|)     with the direction û chosen so that J(û) ∥ ζ̂
//! ```
//!
//! (the factor 2(L/D)² of \[Flores2006\] eqs. 25–26). [`ExactShortBearing`] finds û by Newton's method
//! on the cross-load component of J, started from Booker's direction, with the analytic
//! derivative and the bracket α ∈ (−π/2, π/2) of the load frame as safeguard (J·û > 0 always,
//! so the root lies inside it). [`BookerShortBearing`] is Booker's
//! (1971) closed-form approximation as printed in \[Flores2006\], eqs. 28–29:
//!
//! ```text
//!   M^ζ = (1 − ζ)^{5/2} / (π (L/D)²),     M^κ = −4 κ (1 − ζ)^{3/2} / (π² (L/D)²)
//! ```
//!
//! It is exact at ε = 0 and within a few per cent elsewhere (the validation test quantifies it);
//! it is what Flores et al. integrate in their example.

use super::MobilityModel;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Booker's closed-form short-bearing mobility (\[Flores2006\], eqs. 28–29, load frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BookerShortBearing {
    /// L/D of the bearing.
    pub length_to_diameter: f64,
}

impl MobilityModel for BookerShortBearing {
    fn length_to_diameter(&self) -> f64 {
        self.length_to_diameter
    }

    fn mobility(&self, zeta: f64, kappa: f64) -> [f64; 2] {
        let ld2 = self.length_to_diameter * self.length_to_diameter;
        // 1 − ζ > 0 whenever |ε| < 1; clamp at 0 so that a trial state on the wall gives zero
        // mobility along the load rather than NaN.
        let one_minus = (1.0 - zeta).max(0.0);
        let sq = one_minus.sqrt();
        let m_zeta = one_minus * one_minus * sq / (PI * ld2);
        let m_kappa = -4.0 * kappa * one_minus * sq / (PI * PI * ld2);
        [m_zeta, m_kappa]
    }
}

/// The exact short-bearing Gumbel mobility: inverse of [`short_bearing_squeeze_integral`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactShortBearing {
    /// L/D of the bearing.
    pub length_to_diameter: f64,
}

impl MobilityModel for ExactShortBearing {
    fn length_to_diameter(&self) -> f64 {
        self.length_to_diameter
    }

    fn mobility(&self, zeta: f64, kappa: f64) -> [f64; 2] {
        let ld2 = self.length_to_diameter * self.length_to_diameter;
        let (u, j) = exact_inversion(zeta, kappa);
        let scale = 1.0 / (2.0 * ld2 * j);
        [u[0] * scale, u[1] * scale]
    }
}

/// The squeeze matrix K(α) in the load frame: J(û) = K û for every û in the half plane of the
/// film region fixed by the direction α (K holds Booker's integrals over α ± π/2).
fn squeeze_matrix(eps: [f64; 2], alpha: f64) -> [[f64; 2]; 2] {
    let e = eps[0].hypot(eps[1]);
    let (cx, sx) = if e > 0.0 {
        (eps[0] / e, eps[1] / e)
    } else {
        (1.0, 0.0)
    };
    let a_rel = alpha - sx.atan2(cx);
    let [i02, i11, i20] = booker_integrals(e, a_rel - FRAC_PI_2, a_rel + FRAC_PI_2);
    // Rotate the symmetric matrix [[i02, i11], [i11, i20]] from the ε frame to the load frame.
    let (c2, s2, cs) = (cx * cx, sx * sx, cx * sx);
    let kxx = c2 * i02 - 2.0 * cs * i11 + s2 * i20;
    let kyy = s2 * i02 + 2.0 * cs * i11 + c2 * i20;
    let kxy = cs * (i02 - i20) + (c2 - s2) * i11;
    [[kxx, kxy], [kxy, kyy]]
}

/// Exact inversion for the short bearing: Newton on f(α) = J_y(û(α)) with the analytic
/// derivative f'(α) = (K û⊥)_y — the boundary terms of the moving film region vanish because
/// the integrand (û·n) is zero there — started from Booker's direction and safeguarded by the
/// bracket (−π/2, π/2) with bisection. Returns (û, J_x(û)).
fn exact_inversion(zeta: f64, kappa: f64) -> ([f64; 2], f64) {
    let eps = [zeta, kappa];
    let mb = BookerShortBearing {
        length_to_diameter: 1.0,
    }
    .mobility(zeta, kappa);
    let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
    let mut a = mb[1].atan2(mb[0]).clamp(lo + 1e-9, hi - 1e-9);
    for _ in 0..100 {
        let k = squeeze_matrix(eps, a);
        let (c, s) = (a.cos(), a.sin());
        let f = k[1][0] * c + k[1][1] * s;
        let df = -k[1][0] * s + k[1][1] * c;
        if f == 0.0 {
            break;
        }
        if f < 0.0 {
            lo = a;
        } else {
            hi = a;
        }
        let mut next = a - f / df;
        if !(next.is_finite() && next >= lo && next <= hi) {
            next = 0.5 * (lo + hi);
        }
        let done = (next - a).abs() < 1e-14;
        a = next;
        if done || hi - lo < 1e-15 {
            break;
        }
    }
    let u = [a.cos(), a.sin()];
    let k = squeeze_matrix(eps, a);
    (u, k[0][0] * u[0] + k[0][1] * u[1])
}

/// Find the unit velocity û (load frame, load along +x) whose squeeze load J(û) (or Z(û)) is
/// parallel to +x, for a provider that may fail (a numerical film solver); returns (û, J_x(û)).
/// The provider must satisfy J(û)·û > 0 (true for every pure-squeeze film), which brackets the
/// root in α ∈ (−π/2, π/2): J_y < 0 at α = −π/2 and > 0 at α = π/2.
pub(crate) fn invert_squeeze_fallible<E>(
    mut squeeze: impl FnMut([f64; 2]) -> Result<[f64; 2], E>,
) -> Result<([f64; 2], f64), E> {
    let dir = |a: f64| [a.cos(), a.sin()];
    let (mut a0, mut a1) = (-FRAC_PI_2, FRAC_PI_2);
    let mut f0 = squeeze(dir(a0))?[1];
    let mut f1 = squeeze(dir(a1))?[1];
    // Illinois regula falsi with a bisection safeguard: superlinear on this smooth function,
    // never leaves the bracket.
    let mut side = 0i8;
    let mut a = 0.0;
    for _ in 0..200 {
        let mut trial = (a0 * f1 - a1 * f0) / (f1 - f0);
        if !(trial.is_finite() && trial > a0 && trial < a1) {
            trial = 0.5 * (a0 + a1);
        }
        a = trial;
        let f = squeeze(dir(a))?[1];
        if f == 0.0 {
            break;
        }
        if (f < 0.0) == (f0 < 0.0) {
            a0 = a;
            f0 = f;
            if side == -1 {
                f1 *= 0.5;
            }
            side = -1;
        } else {
            a1 = a;
            f1 = f;
            if side == 1 {
                f0 *= 0.5;
            }
            side = 1;
        }
        if a1 - a0 < 1e-14 {
            a = 0.5 * (a0 + a1);
            break;
        }
    }
    let u = dir(a);
    let j = squeeze(u)?;
    Ok((u, j[0]))
}

/// Map θ' (any real) to Sommerfeld's γ, continuous and increasing, γ(θ' + 2πk) = γ(θ') + 2πk.
fn sommerfeld_gamma(theta: f64, eps: f64) -> f64 {
    let k = (theta / TAU).round();
    let r = theta - TAU * k; // in [−π, π]
    let half = 0.5 * r;
    2.0 * ((1.0 + eps).sqrt() * half.sin()).atan2((1.0 - eps).sqrt() * half.cos()) + TAU * k
}

/// Booker's integrals (I₃^{02}, I₃^{11}, I₃^{20}) over θ' ∈ [θ1, θ2] (θ1 < θ2 ≤ θ1 + 2π) in the
/// frame of ε, exactly (Sommerfeld substitution, see the module docs).
///
/// ```
/// use jbearing_solvers::mobility::short_bearing::booker_integrals;
/// use std::f64::consts::{PI, TAU};
///
/// // Over a whole turn: ∫ sin²/(1 + ε cos)³ = π/(1 − ε²)^{3/2}, ∫ sin cos/(…)³ = 0,
/// // ∫ cos²/(1 + ε cos)³ = π (1 + 2ε²)/(1 − ε²)^{5/2}.
/// let eps = 0.8;
/// let s = 1.0 - eps * eps;
/// let [i02, i11, i20] = booker_integrals(eps, 0.3, 0.3 + TAU);
/// assert!((i20 - PI / s.powf(1.5)).abs() < 1e-12 * i20);
/// assert!(i11.abs() < 1e-12 * i20);
/// assert!((i02 - PI * (1.0 + 2.0 * eps * eps) / s.powf(2.5)).abs() < 1e-12 * i02);
/// ```
pub fn booker_integrals(eps: f64, theta1: f64, theta2: f64) -> [f64; 3] {
    let s = 1.0 - eps * eps;
    let g1 = sommerfeld_gamma(theta1, eps);
    let g2 = sommerfeld_gamma(theta2, eps);
    let p02 = |g: f64| 0.5 * g + 0.25 * (2.0 * g).sin() + 2.0 * eps * g.sin() + eps * eps * g;
    let p11 = |g: f64| 0.5 * g.sin() * g.sin() - eps * g.cos();
    let p20 = |g: f64| 0.5 * g - 0.25 * (2.0 * g).sin();
    let ss = s.sqrt();
    [
        (p02(g2) - p02(g1)) / (s * s * ss),
        (p11(g2) - p11(g1)) / (s * s),
        (p20(g2) - p20(g1)) / (s * ss),
    ]
}

/// The dimensionless short-bearing Gumbel squeeze-force integral
/// J(u) = ∫_{u·n>0} (u·n) n / (1 − ε·n)³ dθ for eccentricity ratio vector `eps` (|ε| < 1) and
/// squeeze rate `u` = v/c (any frame, same for both; the result is in that frame).
///
/// The film force on the journal is F = −(μ R L³/c²) J(v/c); the load it carries is W = −F.
pub fn short_bearing_squeeze_integral(eps: [f64; 2], u: [f64; 2]) -> [f64; 2] {
    let e = eps[0].hypot(eps[1]);
    // Frame of ε: x' along ε (any axis when ε = 0).
    let (cx, sx) = if e > 0.0 {
        (eps[0] / e, eps[1] / e)
    } else {
        (1.0, 0.0)
    };
    let a = u[0] * cx + u[1] * sx;
    let b = -u[0] * sx + u[1] * cx;
    if a == 0.0 && b == 0.0 {
        return [0.0, 0.0];
    }
    let alpha = b.atan2(a);
    let [i02, i11, i20] = booker_integrals(e, alpha - FRAC_PI_2, alpha + FRAC_PI_2);
    let jx = a * i02 + b * i11;
    let jy = a * i11 + b * i20;
    [jx * cx - jy * sx, jx * sx + jy * cx]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Plain midpoint quadrature of the integrals in θ (fine grid) — a second route to
    /// `booker_integrals` that does not use the substitution.
    fn quad(eps: f64, t1: f64, t2: f64) -> [f64; 3] {
        let n = 200_000;
        let d = (t2 - t1) / n as f64;
        let mut acc = [0.0; 3];
        for i in 0..n {
            let t = t1 + (i as f64 + 0.5) * d;
            let w = 1.0 - eps * t.cos();
            let w3 = w * w * w;
            acc[0] += t.cos() * t.cos() / w3 * d;
            acc[1] += t.sin() * t.cos() / w3 * d;
            acc[2] += t.sin() * t.sin() / w3 * d;
        }
        acc
    }

    #[test]
    fn booker_integrals_match_quadrature() {
        for &eps in &[0.0, 0.3, 0.7, 0.9] {
            for &(t1, t2) in &[(-1.2, 1.9), (2.0, 2.0 + PI), (-4.0, -0.5), (-PI, PI)] {
                let exact = booker_integrals(eps, t1, t2);
                let q = quad(eps, t1, t2);
                for k in 0..3 {
                    // Midpoint rule error ~ (Δθ)² f''/24 ≪ 1e-8 relative at this resolution.
                    assert!(
                        (exact[k] - q[k]).abs() <= 1e-8 * (1.0 + q[k].abs()),
                        "eps {eps} [{t1},{t2}] k {k}: {} vs {}",
                        exact[k],
                        q[k]
                    );
                }
            }
        }
    }

    #[test]
    fn mobility_at_concentric_position_is_isotropic() {
        // ε = 0: J(ζ̂) = ∫_{-π/2}^{π/2} cos² = π/2, M = 1/(π (L/D)²) for both models.
        for ld in [0.25, 0.4, 1.0] {
            let b = BookerShortBearing {
                length_to_diameter: ld,
            }
            .mobility(0.0, 0.0);
            let e = ExactShortBearing {
                length_to_diameter: ld,
            }
            .mobility(0.0, 0.0);
            let m0 = 1.0 / (PI * ld * ld);
            assert!((b[0] - m0).abs() < 1e-14 * m0 && b[1] == 0.0);
            assert!((e[0] - m0).abs() < 1e-12 * m0 && e[1].abs() < 1e-12 * m0);
        }
    }
}
