//! Michell's series solution of a plane-strain annulus r_i ≤ r ≤ r_o held fixed on r_o (u = 0)
//! and loaded by a normal pressure p(θ) on its bore r_i: the closed-form reference for the
//! housing's bore stresses (the finite elements of this module are checked against it in the
//! tests; docs/validation.md, "Deformable bearing").
//!
//! ```text
//!   p(θ) = Σ_n a_n cos nθ + b_n sin nθ,
//!   u_r = U_n(r) cos nθ,  u_θ = V_n(r) sin nθ  per cosine mode (the sine modes rotated by π/2n),
//!   σ_r(r_i) = −a_n,  τ_rθ(r_i) = 0,  U_n(r_o) = V_n(r_o) = 0.
//! ```
//!
//! Per mode, Navier's equations in polar coordinates have the solutions U, V ∝ r^s with
//! s = n + 1, 1 − n, n − 1, −n − 1: the displacements of Michell's stress-function terms
//! r^{n+2}, r^{2−n}, r^n, r^{−n} cos nθ (\[Michell1899\]; \[Barber2010\] ch. 8, the Michell
//! solution, and ch. 9, its displacements), each with the ratio V/U that makes it an
//! equilibrium field. Mode n = 1 has s = ±2, the translation (U, V) = (1, −1), and, for the
//! double root s = 0, the logarithmic solution U = ln r, V = −ln r − (λ + μ)/(λ + 3μ) (Michell's r ln r cos θ and r θ sin θ pair, which
//! carries the net force to the outer boundary); mode 0 is Lamé's U = A r + B/r, V = 0.
//! Four (two for n = 0) boundary conditions give the four coefficients, a 4 × 4 solve per mode.
//! On the bore σ_r = −p and τ_rθ = 0 hold exactly, so the series is needed only for σ_θ;
//! σ_z = ν (σ_r + σ_θ) (plane strain).
//!
//! Powers are scaled, (r/r_o)^s for s > 0 and (r/r_i)^s otherwise, so that thousands of modes
//! neither overflow nor lose the system's conditioning.

use super::Material;
use std::f64::consts::PI;

/// The annulus: Lamé constants (plane strain) and radii.
#[derive(Debug, Clone, Copy)]
pub struct MichellAnnulus {
    lambda: f64,
    mu: f64,
    r_i: f64,
    r_o: f64,
}

/// One solution of a mode: U(r), V(r), σ_r, σ_θ (cos nθ amplitudes) and τ_rθ (sin nθ).
type Field = [f64; 5];

impl MichellAnnulus {
    /// The annulus r_i … r_o of `material` (plane strain); None unless 0 < r_i < r_o and the
    /// material is an elastic solid (E > 0, 0 ≤ ν < 0.5).
    pub fn new(material: Material, r_i: f64, r_o: f64) -> Option<Self> {
        let (e, nu) = (material.youngs_modulus, material.poisson_ratio);
        if !(e > 0.0 && (0.0..0.5).contains(&nu) && r_i > 0.0 && r_o > r_i && r_o.is_finite()) {
            return None;
        }
        Some(Self {
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: e / (2.0 * (1.0 + nu)),
            r_i,
            r_o,
        })
    }

    /// σ_θ on the bore per unit bore pressure of mode n (cos nθ; the sine mode's the same).
    pub fn hoop_per_pressure(&self, n: usize) -> f64 {
        let sols = self.solutions(n);
        let at = |r: f64| -> Vec<Field> { sols.iter().map(|f| f(r)).collect() };
        let (inner, outer) = (at(self.r_i), at(self.r_o));
        if n == 0 {
            // σ_r(r_i) = −1, U(r_o) = 0.
            let a = [[inner[0][2], inner[1][2]], [outer[0][0], outer[1][0]]];
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            let c = [-a[1][1] / det, a[1][0] / det];
            return c[0] * inner[0][3] + c[1] * inner[1][3];
        }
        let mut a = [[0.0; 4]; 4];
        for (j, (i, o)) in inner.iter().zip(&outer).enumerate() {
            a[0][j] = i[2];
            a[1][j] = i[4];
            a[2][j] = o[0];
            a[3][j] = o[1];
        }
        let c = solve4(a, [-1.0, 0.0, 0.0, 0.0]);
        c.iter().zip(&inner).map(|(c, f)| c * f[3]).sum()
    }

    /// (σ_r, σ_θ, τ_rθ) on the bore at the angles `theta` under p(θ) = Σ_{n<N} a_n cos nθ +
    /// b_n sin nθ (`cos` = a, `sin` = b, b_0 unused; N their length).
    pub fn bore_stresses(&self, cos: &[f64], sin: &[f64], theta: &[f64]) -> Vec<[f64; 3]> {
        let hoop: Vec<f64> = (0..cos.len()).map(|n| self.hoop_per_pressure(n)).collect();
        theta
            .iter()
            .map(|&t| {
                let (mut p, mut s) = (0.0, 0.0);
                for (n, ((a, b), k)) in cos.iter().zip(sin).zip(&hoop).enumerate() {
                    let (sn, cn) = (n as f64 * t).sin_cos();
                    let pn = a * cn + if n == 0 { 0.0 } else { b * sn };
                    p += pn;
                    s += k * pn;
                }
                [-p, s, 0.0]
            })
            .collect()
    }

    /// The mode's independent solutions as functions of r.
    fn solutions(&self, n: usize) -> Vec<Box<dyn Fn(f64) -> Field + '_>> {
        let (l, m) = (self.lambda, self.mu);
        let nf = n as f64;
        let powers: Vec<f64> = match n {
            0 => vec![1.0, -1.0],
            1 => vec![2.0, -2.0],
            _ => vec![nf + 1.0, 1.0 - nf, nf - 1.0, -nf - 1.0],
        };
        let mut out: Vec<Box<dyn Fn(f64) -> Field + '_>> = Vec::new();
        for s in powers {
            // Stress rows per (a, b) for U = a ρ^s, V = b ρ^s, times ρ^s / r.
            let sr = [(l + 2.0 * m) * s + l, l * nf];
            let st = [l * s + l + 2.0 * m, (l + 2.0 * m) * nf];
            let t = [-m * nf, m * (s - 1.0)];
            let v = if n == 0 {
                [1.0, 0.0]
            } else {
                null_vector(
                    [s * sr[0] + nf * t[0] - st[0], s * sr[1] + nf * t[1] - st[1]],
                    [(s + 1.0) * t[0] - nf * st[0], (s + 1.0) * t[1] - nf * st[1]],
                )
            };
            let scale = if s > 0.0 { self.r_o } else { self.r_i };
            let dot = |row: [f64; 2]| row[0] * v[0] + row[1] * v[1];
            let (ksr, kst, kt) = (dot(sr), dot(st), dot(t));
            out.push(Box::new(move |r: f64| {
                let w = (r / scale).powf(s);
                [v[0] * w, v[1] * w, ksr * w / r, kst * w / r, kt * w / r]
            }));
        }
        if n == 1 {
            out.push(Box::new(|_| [1.0, -1.0, 0.0, 0.0, 0.0]));
            let d = -(l + m) / (l + 3.0 * m);
            let r_i = self.r_i;
            out.push(Box::new(move |r: f64| {
                let ln = (r / r_i).ln();
                // ε_r = 1/r, ε_θ = (U + V)/r = d/r, γ = (−U + r V' − V)/r = (−1 − d)/r.
                [
                    ln,
                    -ln + d,
                    ((l + 2.0 * m) + l * d) / r,
                    (l + (l + 2.0 * m) * d) / r,
                    m * (-1.0 - d) / r,
                ]
            }));
        }
        out
    }
}

/// The null vector of the singular 2 × 2 matrix with rows `a`, `b` (from its larger row).
fn null_vector(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let row = if a[0].hypot(a[1]) >= b[0].hypot(b[1]) {
        a
    } else {
        b
    };
    let norm = row[0].hypot(row[1]);
    [row[1] / norm, -row[0] / norm]
}

/// Gaussian elimination with partial pivoting of a 4 × 4 system.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> [f64; 4] {
    for k in 0..4 {
        let p = (k..4)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .expect("rows left");
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..4 {
            let f = a[i][k] / a[k][k];
            for j in k..4 {
                a[i][j] -= f * a[k][j];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = [0.0; 4];
    for k in (0..4).rev() {
        let s: f64 = (k + 1..4).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    x
}

/// Fourier coefficients (a_n, b_n), n < `modes`, of the pressure linear between `nodal`
/// values at θ_k = 2πk/N (the film-surface nodes, what the finite elements load): the discrete
/// transform times the hat function's (sin(nΔ/2)/(nΔ/2))².
pub fn fourier_of_nodal(nodal: &[f64], modes: usize) -> (Vec<f64>, Vec<f64>) {
    let count = nodal.len() as f64;
    let step = 2.0 * PI / count;
    (0..modes)
        .map(|n| {
            let (mut re, mut im) = (0.0, 0.0);
            for (k, p) in nodal.iter().enumerate() {
                let (s, c) = (n as f64 * step * k as f64).sin_cos();
                re += p * c;
                im += p * s;
            }
            let x = 0.5 * n as f64 * step;
            let hat = if n == 0 { 1.0 } else { (x.sin() / x).powi(2) };
            let f = if n == 0 { 1.0 } else { 2.0 } * hat / count;
            (f * re, f * im)
        })
        .unzip()
}
