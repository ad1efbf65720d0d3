//! The 4-node isoparametric (bilinear) quadrilateral in plane strain.
//!
//! ```text
//!   x(ξ, η) = Σ N_a(ξ, η) x_a,   N_a = ¼ (1 + ξ_a ξ)(1 + η_a η),   (ξ_a, η_a) = (∓1, ∓1) anticlockwise
//!   ε = B u_e,   σ = D ε,   K_e = ∫ Bᵀ D B dA  (2 × 2 Gauss points, unit thickness)
//!
//!        E        ┌ 1 − ν    ν      0      ┐
//!   D = ───────── │   ν    1 − ν    0      │      σ = (σ_xx, σ_yy, τ_xy),  σ_zz = ν (σ_xx + σ_yy)
//!       (1+ν)(1−2ν) └   0      0   (1 − 2ν)/2 ┘
//! ```
//!
//! \[Zienkiewicz2005\] (isoparametric elements, Gauss quadrature, the plane-strain elasticity
//! matrix); \[TimoshenkoGoodier1970\] (σ_zz in plane strain). Full 2 × 2
//! integration is exact for the stiffness of a parallelogram and passes the patch test on any
//! convex quadrilateral (tests below).

// Element matrices are indexed by local node and component numbers, as written in the formulas.
#![allow(clippy::needless_range_loop)]

/// Isotropic linear-elastic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio ν (0 ≤ ν < ½).
    pub poisson_ratio: f64,
}

impl Material {
    /// Structural steel: E = 210 GPa, ν = 0.3 (the paper's "properties typical of a structural
    /// steel", \[Benasciutti2012\] Fig. 5 and its text, without numbers).
    pub const STEEL: Material = Material {
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
    };

    /// The plane-strain elasticity matrix D (Voigt order xx, yy, xy with engineering shear).
    pub fn plane_strain(&self) -> [[f64; 3]; 3] {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        let f = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        [
            [f * (1.0 - nu), f * nu, 0.0],
            [f * nu, f * (1.0 - nu), 0.0],
            [0.0, 0.0, f * (1.0 - 2.0 * nu) / 2.0],
        ]
    }
}

/// Natural coordinates of the nodes, anticlockwise.
const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// The Gauss points ±1/√3 in the corner order (so that Gauss point a sits nearest node a).
pub(crate) fn gauss_points() -> [[f64; 2]; 4] {
    let g = 1.0 / 3f64.sqrt();
    CORNERS.map(|[a, b]| [a * g, b * g])
}

/// B (3 × 8, columns u_x1, u_y1, u_x2, …) and det J at natural point (ξ, η).
pub(crate) fn strain_matrix(xy: &[[f64; 2]; 4], xi: f64, eta: f64) -> ([[f64; 8]; 3], f64) {
    let mut dn = [[0.0; 2]; 4];
    for (a, &[xa, ea]) in CORNERS.iter().enumerate() {
        dn[a] = [0.25 * xa * (1.0 + ea * eta), 0.25 * ea * (1.0 + xa * xi)];
    }
    // J = ∂(x, y)/∂(ξ, η).
    let mut j = [[0.0; 2]; 2];
    for a in 0..4 {
        for r in 0..2 {
            for c in 0..2 {
                j[r][c] += dn[a][c] * xy[a][r];
            }
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    // ∂N/∂x = J⁻ᵀ ∂N/∂ξ.
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut b = [[0.0; 8]; 3];
    for a in 0..4 {
        let dx = dn[a][0] * inv[0][0] + dn[a][1] * inv[1][0];
        let dy = dn[a][0] * inv[0][1] + dn[a][1] * inv[1][1];
        b[0][2 * a] = dx;
        b[1][2 * a + 1] = dy;
        b[2][2 * a] = dy;
        b[2][2 * a + 1] = dx;
    }
    (b, det)
}

/// Element stiffness K_e (8 × 8, unit thickness); None if the element is inverted or
/// degenerate (det J ≤ 0 at a Gauss point).
pub(crate) fn stiffness(xy: &[[f64; 2]; 4], d: &[[f64; 3]; 3]) -> Option<[[f64; 8]; 8]> {
    let mut k = [[0.0; 8]; 8];
    for [xi, eta] in gauss_points() {
        let (b, det) = strain_matrix(xy, xi, eta);
        if det.is_nan() || det <= 0.0 {
            return None;
        }
        // D B.
        let mut db = [[0.0; 8]; 3];
        for r in 0..3 {
            for c in 0..8 {
                db[r][c] = (0..3).map(|m| d[r][m] * b[m][c]).sum();
            }
        }
        for r in 0..8 {
            for c in 0..8 {
                k[r][c] += det * (0..3).map(|m| b[m][r] * db[m][c]).sum::<f64>();
            }
        }
    }
    Some(k)
}

/// Stresses (σ_xx, σ_yy, τ_xy) at the four Gauss points (corner order) for element
/// displacements `u` (u_x1, u_y1, …).
pub(crate) fn gauss_stresses(xy: &[[f64; 2]; 4], d: &[[f64; 3]; 3], u: &[f64; 8]) -> [[f64; 3]; 4] {
    gauss_points().map(|[xi, eta]| {
        let (b, _) = strain_matrix(xy, xi, eta);
        let eps: [f64; 3] = std::array::from_fn(|r| (0..8).map(|c| b[r][c] * u[c]).sum());
        std::array::from_fn(|r| (0..3).map(|m| d[r][m] * eps[m]).sum())
    })
}

/// Values at the four nodes of the bilinear field through four Gauss-point values (corner
/// order): the field evaluated at (ξ, η) = ±√3, i.e. the Gauss-point interpolant extrapolated
/// to the corners (\[Zienkiewicz2005\], stress recovery).
pub(crate) fn extrapolate_to_nodes(v: [f64; 4]) -> [f64; 4] {
    let s = 3f64.sqrt();
    CORNERS.map(|[xa, ea]| {
        let (xi, eta) = (xa * s, ea * s);
        CORNERS
            .iter()
            .zip(v)
            .map(|([xb, eb], vb)| 0.25 * (1.0 + xb * xi) * (1.0 + eb * eta) * vb)
            .sum()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rigid-body motion (two translations and a small rotation) strains nothing: K_e times
    /// it is zero to round-off relative to K_e's scale.
    #[test]
    fn rigid_body_modes_are_stress_free() {
        let xy = [[0.0, 0.0], [2.0, 0.3], [1.7, 1.9], [-0.2, 1.1]];
        let d = Material::STEEL.plane_strain();
        let k = stiffness(&xy, &d).unwrap();
        let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for mode in 0..3 {
            let u: [f64; 8] = std::array::from_fn(|c| {
                let (x, y) = (xy[c / 2][0], xy[c / 2][1]);
                match (mode, c % 2) {
                    (0, 0) | (1, 1) => 1.0,
                    (0, 1) | (1, 0) => 0.0,
                    (_, 0) => -y,
                    _ => x,
                }
            });
            for row in &k {
                let f: f64 = row.iter().zip(&u).map(|(a, b)| a * b).sum();
                assert!(f.abs() < 1e-12 * scale, "mode {mode}: {f}");
            }
        }
    }

    /// K_e is symmetric, and its strain energy for a uniform strain equals ½ εᵀ D ε × area
    /// (the shoelace area of the quadrilateral).
    #[test]
    fn uniform_strain_energy() {
        let xy = [[0.0, 0.0], [2.0, 0.3], [1.7, 1.9], [-0.2, 1.1]];
        let d = Material::STEEL.plane_strain();
        let k = stiffness(&xy, &d).unwrap();
        for r in 0..8 {
            for c in 0..8 {
                assert!((k[r][c] - k[c][r]).abs() <= 1e-12 * k[r][r].abs());
            }
        }
        let area = 0.5
            * (0..4)
                .map(|a| {
                    let b = (a + 1) % 4;
                    xy[a][0] * xy[b][1] - xy[b][0] * xy[a][1]
                })
                .sum::<f64>();
        let (exx, eyy, gxy) = (1e-3, -4e-4, 6e-4);
        let u: [f64; 8] = std::array::from_fn(|c| {
            let (x, y) = (xy[c / 2][0], xy[c / 2][1]);
            if c % 2 == 0 {
                exx * x + 0.5 * gxy * y
            } else {
                eyy * y + 0.5 * gxy * x
            }
        });
        let energy: f64 = 0.5
            * (0..8)
                .map(|r| (0..8).map(|c| u[r] * k[r][c] * u[c]).sum::<f64>())
                .sum::<f64>();
        let eps = [exx, eyy, gxy];
        let exact: f64 = 0.5
            * area
            * (0..3)
                .map(|r| (0..3).map(|c| eps[r] * d[r][c] * eps[c]).sum::<f64>())
                .sum::<f64>();
        assert!((energy / exact - 1.0).abs() < 1e-12, "{energy} vs {exact}");
    }

    /// Extrapolating a bilinear field's Gauss values reproduces its nodal values.
    #[test]
    fn extrapolation_is_exact_for_bilinear_fields() {
        let f = |xi: f64, eta: f64| 1.0 + 2.0 * xi - 3.0 * eta + 0.5 * xi * eta;
        let v = gauss_points().map(|[a, b]| f(a, b));
        let nodal = extrapolate_to_nodes(v);
        for (a, [xa, ea]) in CORNERS.iter().enumerate() {
            assert!((nodal[a] - f(*xa, *ea)).abs() < 1e-13);
        }
    }

    #[test]
    fn inverted_element_is_refused() {
        let xy = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        assert!(stiffness(&xy, &Material::STEEL.plane_strain()).is_none());
    }
}
