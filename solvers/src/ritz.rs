//! The Ritz method of Antonić, Nikolić & Torović \[Antonic2004\] for the finite
//! journal bearing whose film extends over θ = 0 … π (their "hypothesis III").
//!
//! # Problem
//!
//! Dimensionless Reynolds equation (\[Antonic2004\] eq. 2, θ from the **maximum** film,
//! H = 1 + ε cos θ, Z = z/l ∈ [−½, ½], λ = r/l, Λ = 6ηωr²/(p₀c²)):
//!
//! ```text
//!   ∂/∂θ (H³ ∂P/∂θ) + λ² ∂/∂Z (H³ ∂P/∂Z) = Λ dH/dθ = −Λ ε sin θ
//!   P(0, Z) = P(π, Z) = 0,   P(θ, ±½) = 0                                (eqs. 3a, 3b)
//! ```
//!
//! It is the Euler–Lagrange equation of the action integral (eq. 9; the print has λ where Λ is
//! meant in the source term — with λ the coefficients could not scale with Λ as the tables say,
//! and eq. 8 has Λ)
//!
//! ```text
//!   I[P] = ∫_{−½}^{½} ∫_0^π { ½ H³ (∂P/∂θ)² + ½ λ² H³ (∂P/∂Z)² − Λ ε P sin θ } dθ dZ      (eq. 9)
//! ```
//!
//! # Ritz approximation
//!
//! Trial function (eq. 10), φ_i = (¼ − Z²) sin iθ, i = 1 … 4:
//!
//! ```text
//!   P = Σ C_i φ_i      ⇒   I(C) = ½ Cᵀ K C − Λ Cᵀ r
//!   K_ij = ∫∫ H³ [ ∂_θφ_i ∂_θφ_j + λ² ∂_Zφ_i ∂_Zφ_j ] dθ dZ,   r_i = ∫∫ ε sin θ φ_i dθ dZ
//!   ∂I/∂C_i = 0   ⇔   K C = Λ r                                                   (eq. 12)
//! ```
//!
//! K and r are assembled by tensor Gauss–Legendre quadrature ([`crate::closed_form::quadrature`]):
//! 64 points in θ (the integrands are trigonometric polynomials of degree ≤ 11: converged to
//! round-off) and 4 in Z (polynomials of degree ≤ 4: exact). K is symmetric positive definite
//! for 0 ≤ ε < 1; the 4×4 system is solved by Gaussian elimination with partial pivoting, a
//! vanishing pivot being an error. The pressure is eq. 14, P = (¼ − Z²) Σ C_i sin iθ; results
//! are given per unit Λ (C_i/Λ, P/Λ) as in the tables T1–T5.
//!
//! ```text
//!   unknowns:  C = [C_1, C_2, C_3, C_4]          K: 4×4 dense, symmetric
//!   grid:      θ_a (64 GL nodes on 0…π) × Z_b (4 GL nodes on −½…½)
//! ```

use crate::closed_form::quadrature::gauss_legendre;
use thiserror::Error;

/// Number of trial functions of eq. 10.
pub const RITZ_TERMS: usize = 4;

/// Inputs of the Ritz solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RitzParams {
    /// ε, 0 ≤ ε < 1.
    pub eccentricity_ratio: f64,
    /// λ = r/l (0 gives the long-bearing limit of the same trial function).
    pub radius_to_length: f64,
    /// Gauss–Legendre points in θ (64 is converged; at least 8).
    pub theta_points: usize,
}

impl RitzParams {
    /// Defaults for the quadrature: 64 points in θ.
    pub fn new(eccentricity_ratio: f64, radius_to_length: f64) -> Self {
        Self {
            eccentricity_ratio,
            radius_to_length,
            theta_points: 64,
        }
    }
}

/// The Ritz coefficients and the assembled system.
#[derive(Debug, Clone, PartialEq)]
pub struct RitzSolution {
    /// The inputs.
    pub params: RitzParams,
    /// C_i / Λ, i = 1 … 4 (eq. 13).
    pub coefficients: [f64; RITZ_TERMS],
    /// K of eq. 12 (per unit Λ on the right-hand side).
    pub stiffness: [[f64; RITZ_TERMS]; RITZ_TERMS],
    /// r of eq. 12.
    pub load_vector: [f64; RITZ_TERMS],
}

impl RitzSolution {
    /// P/Λ of eq. 14 at θ (rad, from the maximum film, 0 … π) and Z = z/l (−½ … ½); zero
    /// outside the film.
    pub fn pressure(&self, theta: f64, z: f64) -> f64 {
        if !(0.0..=std::f64::consts::PI).contains(&theta) || z.abs() > 0.5 {
            return 0.0;
        }
        let s: f64 = (0..RITZ_TERMS)
            .map(|i| self.coefficients[i] * ((i + 1) as f64 * theta).sin())
            .sum();
        (0.25 - z * z) * s
    }

    /// The action integral I(C)/Λ² of eq. 9 at the solution: ½ CᵀKC − Cᵀr = −½ Cᵀr.
    pub fn action(&self) -> f64 {
        -0.5 * (0..RITZ_TERMS)
            .map(|i| self.coefficients[i] * self.load_vector[i])
            .sum::<f64>()
    }
}

/// What can go wrong in the Ritz solution.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RitzError {
    /// A parameter is out of range.
    #[error("invalid parameter {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
    /// The 4×4 system is singular (a vanishing pivot).
    #[error("singular Ritz system: pivot {pivot:e} in column {column}")]
    SingularSystem { column: usize, pivot: f64 },
    /// A coefficient came out non-finite.
    #[error("non-finite Ritz coefficient C_{index}")]
    NonFinite { index: usize },
}

/// Assemble and solve eq. 12 for the coefficients C_i/Λ.
///
/// ```
/// use jbearing_solvers::ritz::{RitzParams, solve_ritz};
///
/// let solution = solve_ritz(&RitzParams::new(0.6, 1.0))?;
/// // The Ritz pressure vanishes at the bearing's ends and is positive inside the film.
/// assert!(solution.pressure(1.0, 0.5).abs() < 1e-12);
/// assert!(solution.pressure(1.0, 0.0) > 0.0);
/// # Ok::<(), jbearing_solvers::ritz::RitzError>(())
/// ```
pub fn solve_ritz(params: &RitzParams) -> Result<RitzSolution, RitzError> {
    let eps = params.eccentricity_ratio;
    let lam = params.radius_to_length;
    if !(eps.is_finite() && (0.0..1.0).contains(&eps)) {
        return Err(RitzError::InvalidParameter {
            name: "eccentricity_ratio",
            value: eps,
        });
    }
    if !(lam.is_finite() && lam >= 0.0) {
        return Err(RitzError::InvalidParameter {
            name: "radius_to_length",
            value: lam,
        });
    }
    if params.theta_points < 8 {
        return Err(RitzError::InvalidParameter {
            name: "theta_points",
            value: params.theta_points as f64,
        });
    }
    let (tx, tw) = gauss_legendre(params.theta_points, 0.0, std::f64::consts::PI);
    let (zx, zw) = gauss_legendre(4, -0.5, 0.5);
    let mut k = [[0.0; RITZ_TERMS]; RITZ_TERMS];
    let mut r = [0.0; RITZ_TERMS];
    for (&t, &wt) in tx.iter().zip(&tw) {
        let h = 1.0 + eps * t.cos();
        let h3 = h * h * h;
        let sn: [f64; RITZ_TERMS] = std::array::from_fn(|i| ((i + 1) as f64 * t).sin());
        let cs: [f64; RITZ_TERMS] =
            std::array::from_fn(|i| (i + 1) as f64 * ((i + 1) as f64 * t).cos());
        for (&z, &wz) in zx.iter().zip(&zw) {
            let f = 0.25 - z * z;
            let df = -2.0 * z;
            let w = wt * wz;
            for i in 0..RITZ_TERMS {
                // ∂_θφ_i = f · i cos iθ,  ∂_Zφ_i = f' · sin iθ
                let (ti, zi) = (f * cs[i], df * sn[i]);
                for j in 0..RITZ_TERMS {
                    k[i][j] += w * h3 * (ti * f * cs[j] + lam * lam * zi * df * sn[j]);
                }
                r[i] += w * eps * t.sin() * f * sn[i];
            }
        }
    }
    let c = solve_dense(k, r)?;
    for (index, v) in c.iter().enumerate() {
        if !v.is_finite() {
            return Err(RitzError::NonFinite { index: index + 1 });
        }
    }
    Ok(RitzSolution {
        params: *params,
        coefficients: c,
        stiffness: k,
        load_vector: r,
    })
}

/// Gaussian elimination with partial pivoting on the 4×4 system.
fn solve_dense(
    mut a: [[f64; RITZ_TERMS]; RITZ_TERMS],
    mut b: [f64; RITZ_TERMS],
) -> Result<[f64; RITZ_TERMS], RitzError> {
    let n = RITZ_TERMS;
    let norm = a
        .iter()
        .flat_map(|row| row.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for col in 0..n {
        let p = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap_or(col);
        let pivot = a[p][col].abs();
        if pivot.is_nan() || pivot <= 1e-14 * norm {
            return Err(RitzError::SingularSystem {
                column: col,
                pivot: a[p][col],
            });
        }
        a.swap(col, p);
        b.swap(col, p);
        let pivot_row = a[col];
        for row in col + 1..n {
            let m = a[row][col] / pivot_row[col];
            for (x, y) in a[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= m * y;
            }
            b[row] -= m * b[col];
        }
    }
    let mut x = [0.0; RITZ_TERMS];
    for row in (0..n).rev() {
        let s: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The same system with the Z integrals done by hand (∫f² = 1/30, ∫f'² = 1/3, ∫f = 1/6)
    /// and the θ integrals by the trapezoidal rule over the full period (the integrands are even,
    /// 2π-periodic trigonometric polynomials of degree ≤ 11, so 64 points are exact).
    #[allow(clippy::needless_range_loop)] // index algebra mirrors K_ij
    fn reference(eps: f64, lam: f64) -> [f64; 4] {
        let n = 64;
        let mut a = [[0.0; 4]; 4];
        let mut b = [0.0; 4];
        for m in 0..n {
            let t = 2.0 * PI * m as f64 / n as f64;
            let w = PI / n as f64; // ∫_0^π = ½ ∫_{−π}^{π}
            let h3 = (1.0 + eps * t.cos()).powi(3);
            for i in 0..4 {
                let (fi, gi) = ((i + 1) as f64, ((i + 1) as f64 * t));
                for j in 0..4 {
                    let (fj, gj) = ((j + 1) as f64, ((j + 1) as f64 * t));
                    a[i][j] += w
                        * h3
                        * (fi * fj * gi.cos() * gj.cos() / 30.0
                            + lam * lam * gi.sin() * gj.sin() / 3.0);
                }
                b[i] += w * eps * t.sin() * gi.sin() / 6.0;
            }
        }
        solve_dense(a, b).unwrap()
    }

    #[test]
    fn quadrature_assembly_matches_the_hand_integrated_system() {
        for &eps in &[0.0, 0.3, 0.7, 0.95] {
            for &lam in &[0.0, 0.25, 1.0, 3.0] {
                let s = solve_ritz(&RitzParams::new(eps, lam)).unwrap();
                let r = reference(eps, lam);
                for i in 0..4 {
                    assert!(
                        (s.coefficients[i] - r[i]).abs() < 1e-12 * (1.0 + r[0].abs()),
                        "ε {eps} λ {lam} C{}: {} vs {}",
                        i + 1,
                        s.coefficients[i],
                        r[i]
                    );
                }
            }
        }
    }

    #[test]
    fn solution_makes_the_action_stationary() {
        // I(C) of eq. 9 by an independent midpoint rule in θ and Z (800 × 200 cells: relative error
        // ~ (Δ)²/24 · 24 ≈ 3e-5, from the λ² term); its finite-difference
        // gradient at the solution must vanish (the discretisation error of I is ~1e-7, the
        // gradient of a quadratic by central differences is exact up to that).
        let eps = 0.6;
        let lam = 0.5;
        let s = solve_ritz(&RitzParams::new(eps, lam)).unwrap();
        let action = |c: [f64; 4]| {
            let (nt, nz) = (800, 200);
            let mut acc = 0.0;
            for a in 0..nt {
                let t = PI * (a as f64 + 0.5) / nt as f64;
                let h3 = (1.0 + eps * t.cos()).powi(3);
                for b in 0..nz {
                    let z = -0.5 + (b as f64 + 0.5) / nz as f64;
                    let f = 0.25 - z * z;
                    let (mut p, mut pt, mut pz) = (0.0, 0.0, 0.0);
                    for (i, ci) in c.iter().enumerate() {
                        let k = (i + 1) as f64;
                        p += ci * f * (k * t).sin();
                        pt += ci * f * k * (k * t).cos();
                        pz += ci * (-2.0 * z) * (k * t).sin();
                    }
                    acc += 0.5 * h3 * pt * pt + 0.5 * lam * lam * h3 * pz * pz - eps * p * t.sin();
                }
            }
            acc * (PI / nt as f64) / nz as f64
        };
        let i0 = action(s.coefficients);
        assert!(
            (i0 - s.action()).abs() < 1e-4 * i0.abs(),
            "{i0} vs {}",
            s.action()
        );
        for i in 0..4 {
            let d = 1e-3;
            let mut cp = s.coefficients;
            let mut cm = s.coefficients;
            cp[i] += d;
            cm[i] -= d;
            let g = (action(cp) - action(cm)) / (2.0 * d);
            // Scale: a unit change of C_i changes I by ~ r_i ~ 0.1.
            assert!(g.abs() < 1e-4, "∂I/∂C{} = {g}", i + 1);
        }
    }

    #[test]
    fn pressure_is_eq_14_and_vanishes_on_the_boundary() {
        let s = solve_ritz(&RitzParams::new(0.5, 0.5)).unwrap();
        let c = s.coefficients;
        let t: f64 = 1.1;
        let want = 0.25
            * (c[0] * t.sin()
                + c[1] * (2.0 * t).sin()
                + c[2] * (3.0 * t).sin()
                + c[3] * (4.0 * t).sin());
        assert!((s.pressure(t, 0.0) - want).abs() < 1e-15);
        assert!(s.pressure(0.0, 0.1).abs() < 1e-15 && s.pressure(PI, 0.1).abs() < 1e-12);
        assert_eq!(s.pressure(1.0, 0.5), 0.0);
    }

    #[test]
    fn bad_inputs_are_errors() {
        assert!(solve_ritz(&RitzParams::new(1.0, 0.5)).is_err());
        assert!(solve_ritz(&RitzParams::new(0.5, f64::NAN)).is_err());
    }
}
