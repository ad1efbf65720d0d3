//! The discrete universal Reynolds equation in conservative flux form.
//!
//! # Equation (design.md §2; Elrod 1981; Vijayaraghavan & Keith 1989)
//!
//! Unknown ψ = φ − 1 at every node, φ = ρ/ρ_c; switch g = 1 (full film, ψ ≥ 0) or 0 (cavitated,
//! film fraction φ = 1 + ψ < 1); Elrod's linear law p = p_cav + g β ψ. Mass per unit area (ρ_c
//! factored out), x = R θ:
//!
//! ```text
//!   ∂(hφ)/∂t + ∂q_x/∂x + ∂q_z/∂z = 0
//!   q_x = U h φ / 2 − (β h³ / 12μ) ∂(gψ)/∂x ,    q_z = −(β h³ / 12μ) ∂(gψ)/∂z
//! ```
//!
//! # Control volume of node P = (i, j) and its four faces
//!
//! ```text
//!                 N (i, j+1)
//!                    |  F_n
//!     W (i−1, j) —F_w— P —F_e— E (i+1, j)       V = R Δθ Δz,  Δx = R Δθ
//!                    |  F_s
//!                 S (i, j−1)
//!
//!   V (h_P φ_P − h_P^n φ_P^n) / Δt + (F_e − F_w) + (F_n − F_s) = 0        (backward Euler)
//!   V (h_P φ_P − h_P^n φ_P^n) / Δt + ½ (F_e − F_w + F_n − F_s) + ½ D^n_P = 0   (Crank–Nicolson)
//! ```
//!
//! with D^n_P the net outflow of the old level. A face flux between a left node L and a right
//! node R (R = east or north neighbour) is, with k = β h_f³ / (12 μ_f) at the face:
//!
//! ```text
//!   θ-face:  F = Δz [ (U/2) (α_L h_L φ_L + α_R h_R φ_R) − (k/Δx) (g_R ψ_R − g_L ψ_L) ]
//!   z-face:  F = Δx [ − (k/δz) (g_R ψ_R − g_L ψ_L) ]
//! ```
//!
//! (Δz: the cell width, 0 on the end rows, which are boundary points; δz: the distance between
//! the two rows, Δz/2 next to an end — see [`super::grid`].)
//!
//! The Couette weights α carry the "type differencing" of Vijayaraghavan & Keith (1989): between
//! two full-film nodes the content hφ is central-differenced (α_L = α_R = ½, second order);
//! on any face that touches a cavitated node it is upwinded in the direction of U (α = 1 on the
//! upstream node, 0 downstream), so a cavity is carried by the surface (striated flow). The
//! upwind side follows the sign of U = R(ω_j − ω_b). (VK write the same as central for g·hφ plus
//! upwind for (1−g)·hφ; the two agree everywhere except on the face at a cavity boundary,
//! where ours carries the whole content across — a choice, first order either way.)
//! The pressure-driven part uses the difference of g ψ (design.md §2: it vanishes between
//! cavitated nodes and sees p_cav at a cavity edge).
//!
//! Every flux is written once per face and subtracted from one node and added to the other, so
//! the discrete mass balance closes to round-off: summed over all unknowns, the time terms
//! equal the net inflow from the Dirichlet nodes (ends, grooves, supply line).
//!
//! # Linear system for a frozen switch
//!
//! With g frozen every F is affine in ψ: F = a_L ψ_L + a_R ψ_R + f_0. Collecting the rows gives a
//! five-point system (`p` diagonal, `w e s n` neighbours, `rhs`) in the storage of
//! [`super::grid`]; Dirichlet nodes get identity rows ψ = ψ_D. Not symmetric and not
//! diagonally dominant by rows (a cavitated row's own diagonal is only the Couette outflow while
//! its full neighbours enter with β h³/12μ), but column-dominant, so elimination without pivoting
//! is stable (ADI lines) and the sparse LU oracle pivots anyway.

use super::grid::{Grid, NodeKind};

/// The five-point system of one frozen-switch linear solve, `[i · n_z + j]`.
#[derive(Debug, Clone, Default)]
pub(crate) struct Stencil {
    pub p: Vec<f64>,
    pub w: Vec<f64>,
    pub e: Vec<f64>,
    pub s: Vec<f64>,
    pub n: Vec<f64>,
    pub rhs: Vec<f64>,
}

impl Stencil {
    pub fn resize(&mut self, n: usize) {
        for v in [
            &mut self.p,
            &mut self.w,
            &mut self.e,
            &mut self.s,
            &mut self.n,
            &mut self.rhs,
        ] {
            v.clear();
            v.resize(n, 0.0);
        }
    }

    /// y = A x.
    ///
    /// Per row the sum is ((p x_P + w x_W) + e x_E) + s x_S + n x_N, left to right, the two end
    /// rows of an axial line without their missing neighbour. The end rows are peeled off so
    /// that the interior loop has no branch and vectorizes; the order of the operations, and so
    /// every bit of y, is that of the plain loop (Rust contracts nothing into fused multiply-adds).
    pub fn apply(&self, grid: &Grid, x: &[f64], y: &mut [f64]) {
        self.product::<false>(grid, x, &[], y);
    }

    /// y = b − A x in one pass (the defect of a preconditioner sweep); per row exactly
    /// `b_k − (A x)_k` with (A x)_k as in [`apply`](Self::apply).
    pub fn defect(&self, grid: &Grid, x: &[f64], b: &[f64], y: &mut [f64]) {
        self.product::<true>(grid, x, b, y);
    }

    #[inline(always)]
    fn product<const DEFECT: bool>(&self, grid: &Grid, x: &[f64], b: &[f64], y: &mut [f64]) {
        let (nt, nz) = (grid.n_theta, grid.n_z);
        debug_assert!(nz >= 3, "the grid has at least 3 axial nodes");
        for i in 0..nt {
            let iw = if i == 0 { nt - 1 } else { i - 1 };
            let ie = if i + 1 == nt { 0 } else { i + 1 };
            let line = i * nz..(i + 1) * nz;
            let (p, w, e) = (
                &self.p[line.clone()],
                &self.w[line.clone()],
                &self.e[line.clone()],
            );
            let (s, n) = (&self.s[line.clone()], &self.n[line.clone()]);
            let xp = &x[line.clone()];
            let xw = &x[iw * nz..(iw + 1) * nz];
            let xe = &x[ie * nz..(ie + 1) * nz];
            let bl = if DEFECT { &b[line.clone()] } else { &[][..] };
            let yl = &mut y[line];
            let out = |j: usize, v: f64| if DEFECT { bl[j] - v } else { v };
            let last = nz - 1;
            yl[0] = out(0, p[0] * xp[0] + w[0] * xw[0] + e[0] * xe[0] + n[0] * xp[1]);
            for j in 1..last {
                yl[j] = out(
                    j,
                    p[j] * xp[j]
                        + w[j] * xw[j]
                        + e[j] * xe[j]
                        + s[j] * xp[j - 1]
                        + n[j] * xp[j + 1],
                );
            }
            yl[last] = out(
                last,
                p[last] * xp[last]
                    + w[last] * xw[last]
                    + e[last] * xe[last]
                    + s[last] * xp[last - 1],
            );
        }
    }

    /// r = rhs − A x; returns (max |r|, flux scale). The flux scale is the largest driving
    /// flux of an unknown row: |rhs_k| (Couette and time terms) plus the magnitudes of its
    /// couplings to Dirichlet nodes (supply and ambient). It is independent of the stiff
    /// β-sized internal couplings, so `max |r| ≤ tol · scale` bounds the mass error of every
    /// node against the flows that actually pass through the film.
    pub fn residual(&self, grid: &Grid, x: &[f64], r: &mut [f64]) -> (f64, f64) {
        let (nt, nz) = (grid.n_theta, grid.n_z);
        let mut rmax: f64 = 0.0;
        let mut scale: f64 = 0.0;
        let dir = |k: usize| grid.kind[k] != NodeKind::Unknown;
        for i in 0..nt {
            let iw = if i == 0 { nt - 1 } else { i - 1 };
            let ie = if i + 1 == nt { 0 } else { i + 1 };
            let (b, bw, be) = (i * nz, iw * nz, ie * nz);
            for j in 0..nz {
                let k = b + j;
                if dir(k) {
                    r[k] = self.rhs[k] - x[k];
                    rmax = rmax.max(r[k].abs());
                    continue;
                }
                let t = [
                    self.w[k] * x[bw + j],
                    self.e[k] * x[be + j],
                    self.s[k] * x[k - 1],
                    self.n[k] * x[k + 1],
                ];
                let v = self.rhs[k] - (self.p[k] * x[k] + t[0] + t[1] + t[2] + t[3]);
                r[k] = v;
                rmax = rmax.max(v.abs());
                let mut sc = self.rhs[k].abs();
                for (l, tl) in [bw + j, be + j, k - 1, k + 1].into_iter().zip(t) {
                    if dir(l) {
                        sc += tl.abs();
                    }
                }
                scale = scale.max(sc);
            }
        }
        (rmax, scale)
    }
}

/// Everything that fixes the discrete operator at the new time level, except g and ψ.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Level<'a> {
    pub grid: &'a Grid,
    /// h at the nodes.
    pub h: &'a [f64],
    /// β h³/(12 μ) at the east θ-face of each node.
    pub k_theta: &'a [f64],
    /// β h³/(12 μ) at the north z-face of each node (unused at j = n_z − 1).
    pub k_z: &'a [f64],
    /// Surface speed U = R (ω_j − ω_b).
    pub speed: f64,
}

/// Time discretization of one solve.
#[derive(Debug, Clone, Copy)]
pub(crate) enum TimeTerm<'a> {
    /// No time derivative (steady film).
    Steady,
    /// Implicit step of length `dt` from old content h^n φ^n; `old_outflow` = Some(D^n) makes
    /// it Crank–Nicolson, None backward Euler.
    Step {
        dt: f64,
        old_content: &'a [f64],
        old_outflow: Option<&'a [f64]>,
    },
}

/// Coefficients (a_L, a_R, f_0) of the θ-face east of node k (L = k, R = ke).
#[inline(always)]
fn theta_face(lv: &Level, g: &[f64], k: usize, ke: usize) -> (f64, f64, f64) {
    let grid = lv.grid;
    let dx = grid.radius * grid.d_theta;
    let (gl, gr) = (g[k], g[ke]);
    let (al, ar) = if gl > 0.5 && gr > 0.5 {
        (0.5, 0.5)
    } else if lv.speed >= 0.0 {
        (1.0, 0.0)
    } else {
        (0.0, 1.0)
    };
    let half_u = 0.5 * lv.speed;
    let kd = lv.k_theta[k] / dx;
    let (hl, hr) = (lv.h[k], lv.h[ke]);
    let width = grid.row_width(k % grid.n_z);
    (
        width * (half_u * al * hl + kd * gl),
        width * (half_u * ar * hr - kd * gr),
        width * half_u * (al * hl + ar * hr),
    )
}

/// Coefficients (a_L, a_R) of the z-face north of node k.
#[inline(always)]
fn z_face(lv: &Level, g: &[f64], k: usize) -> (f64, f64) {
    let grid = lv.grid;
    let c = grid.radius * grid.d_theta * lv.k_z[k] / grid.z_gap(k % grid.n_z);
    (c * g[k], -c * g[k + 1])
}

/// Assembles the frozen-switch system. `dirichlet[k]` is ψ_D at Dirichlet nodes.
pub(crate) fn assemble(lv: &Level, g: &[f64], dirichlet: &[f64], time: TimeTerm, st: &mut Stencil) {
    let grid = lv.grid;
    let (nt, nz) = (grid.n_theta, grid.n_z);
    st.resize(grid.len());
    let weight = match time {
        TimeTerm::Step {
            old_outflow: Some(_),
            ..
        } => 0.5,
        _ => 1.0,
    };
    for i in 0..nt {
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        for j in 0..nz {
            let k = i * nz + j;
            let ke = ie * nz + j;
            let (al, ar, f0) = theta_face(lv, g, k, ke);
            st.p[k] += weight * al;
            st.e[k] += weight * ar;
            st.rhs[k] -= weight * f0;
            st.p[ke] -= weight * ar;
            st.w[ke] -= weight * al;
            st.rhs[ke] += weight * f0;
            if j + 1 < nz {
                let (al, ar) = z_face(lv, g, k);
                st.p[k] += weight * al;
                st.n[k] += weight * ar;
                st.p[k + 1] -= weight * ar;
                st.s[k + 1] -= weight * al;
            }
        }
    }
    if let TimeTerm::Step {
        dt,
        old_content,
        old_outflow,
    } = time
    {
        let v = grid.radius * grid.d_theta * grid.dz;
        for k in 0..grid.len() {
            let c = v / dt;
            st.p[k] += c * lv.h[k];
            st.rhs[k] += c * (old_content[k] - lv.h[k]);
            if let Some(d) = old_outflow {
                st.rhs[k] -= 0.5 * d[k];
            }
        }
    }
    for k in 0..grid.len() {
        if grid.kind[k] != NodeKind::Unknown {
            st.p[k] = 1.0;
            st.w[k] = 0.0;
            st.e[k] = 0.0;
            st.s[k] = 0.0;
            st.n[k] = 0.0;
            st.rhs[k] = dirichlet[k];
        }
    }
}

/// Face fluxes of a solution: `theta[k]` from node k to its east neighbour, `z[k]` from node k
/// to its north neighbour (0 at j = n_z − 1), both in m³/s (mass flux / ρ_c).
pub(crate) fn face_fluxes(lv: &Level, g: &[f64], psi: &[f64], theta: &mut [f64], z: &mut [f64]) {
    let grid = lv.grid;
    let (nt, nz) = (grid.n_theta, grid.n_z);
    for i in 0..nt {
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        for j in 0..nz {
            let k = i * nz + j;
            let ke = ie * nz + j;
            let (al, ar, f0) = theta_face(lv, g, k, ke);
            theta[k] = al * psi[k] + ar * psi[ke] + f0;
            z[k] = if j + 1 < nz {
                let (al, ar) = z_face(lv, g, k);
                al * psi[k] + ar * psi[k + 1]
            } else {
                0.0
            };
        }
    }
}

/// Net outflow of every node from face fluxes.
pub(crate) fn net_outflow(grid: &Grid, theta: &[f64], z: &[f64], out: &mut [f64]) {
    let (nt, nz) = (grid.n_theta, grid.n_z);
    for i in 0..nt {
        let iw = if i == 0 { nt - 1 } else { i - 1 };
        for j in 0..nz {
            let k = i * nz + j;
            let mut v = theta[k] - theta[iw * nz + j];
            if j + 1 < nz {
                v += z[k];
            }
            if j > 0 {
                v -= z[k - 1];
            }
            out[k] = v;
        }
    }
}
