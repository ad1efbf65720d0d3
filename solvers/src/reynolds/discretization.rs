//! The discrete universal Reynolds equation in conservative flux form.
//!
//! # Equation (docs/conventions.md §2; \[Elrod1981\]; \[VijayaraghavanKeith1989\])
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
//!   θ-face:  F = Δz [ (U/2) h_f φ_up − (k/Δx) (g_R ψ_R − g_L ψ_L) ]      φ_up = 1 + ψ_up
//!   z-face:  F = Δx [ − (k/δz) (g_R ψ_R − g_L ψ_L) ]
//! ```
//!
//! (Δz: the cell width, 0 on the end rows, which are boundary points; δz: the distance between
//! the two rows, Δz/2 next to an end — see [`super::grid`]; h_f: the exact film thickness at the
//! face θ_{i+½}, the same value whose cube the pressure flux uses.)
//!
//! **Couette flux: upwind φ, face h, on every face** (docs/conventions.md §2). φ_up is the
//! density ratio / film fraction of the upstream node in the direction of U = R(ω_j − ω_b)
//! (L for U ≥ 0, R for U < 0), whatever the switch states of L and R. The flux is then one
//! affine function of ψ on every face, and the pressure flux depends on ψ only through
//! g ψ = max(ψ, 0): the discrete residual is a *continuous*, piecewise-linear function of ψ
//! (and smooth in ε), so a node that switches changes no flux. (Vijayaraghavan & Keith's type
//! differencing — central for g·hφ, upwind for (1 − g)·hφ — changes the form of the face flux
//! with the switch: the residual jumps, the switch iteration flip-flops and the film force
//! jumps; that was this module's first generation.) In a cavity the content is carried by the
//! surface (striated flow): JFO rupture and reformation.
//!
//! Cost of upwinding in the full film: φ = 1 + ψ, ψ = (p − p_cav)/β, so the upwinded Couette
//! flux differs from the central one by −(U h_f Δx / 4) ∂φ/∂x, an artificial diffusion of the
//! pressure with coefficient U h Δx / (4β) against the physical h³/(12μ): relative size
//!
//! ```text
//!   δ = 3 μ U Δx / (β h²)
//! ```
//!
//! At the thinnest film of the cases shipped (β = 1.5 GPa, default grid 120 around): compressor
//! main bearing (μ 0.02 Pa·s, R 22.5 mm, U ≈ 5.9 m/s, Δx 1.18 mm, h_min 10 µm) δ ≈ 2.8e-3;
//! rod bearing (R 16 mm, U ≈ 4.2 m/s, Δx 0.84 mm, h_min 4.9 µm) δ ≈ 5.9e-3; the Butenschön and
//! Raimondi–Boyd table problems at ε = 0.99 (dimensionless: δ = 3 μ U Δx / (β c² (1 − ε)²), with
//! the tables' So-scaled pressure 6 μ U R/c² ≈ a few MPa ≪ β) δ ≈ 1e-3 … 1e-2 at h_min only,
//! ≤ 1e-5 over the rest of the film. Measured: every validation table moved by less than its
//! tolerance (docs/validation.md, "Reynolds solver"). With h at the face the scheme stays second order in h; the
//! node-averaged h of the first generation was first order and the dominant error at ε ≥ 0.95.
//!
//! **Every frozen-switch matrix is an M-matrix.** For a frozen g (any g ∈ {0, 1}ⁿ; the Newton
//! matrix of the complementarity solve in `mod.rs`) write the unknown block A_uu:
//! (a) signs: per face, the upstream node's row gets +(U/2)h_f Δz on its diagonal and the
//! downstream row −(U/2)h_f Δz on the upstream column; the pressure part adds +kΔz/Δx · g on a
//! row's own column and −kΔz/Δx · g on the neighbour's column. Diagonals are positive,
//! off-diagonals ≤ 0: a Z-matrix. (b) column sums: every face flux is added to one row and
//! subtracted from the other, so each face contributes 0 to every column sum; a column of an
//! unknown next to a Dirichlet node loses its (≤ 0) entry in the Dirichlet row and so has a
//! sum ≥ 0; the time term adds V h_P / Δt > 0 to the diagonal. Hence A_uu is strictly column
//! diagonally dominant with a positive diagonal for a time step (its transpose a strictly row
//! dominant Z-matrix): a nonsingular M-matrix, A_uu⁻¹ ≥ 0. A steady film is weakly column
//! dominant; it is nonsingular when every node is connected to an end, a groove or the supply
//! line through the flux graph (a closed, fully cavitated circumferential ring with no full
//! node anywhere on it has an undetermined content — the steady problem's own indeterminacy).
//! The full matrix with identity Dirichlet rows is block triangular with these two M-matrix
//! blocks. Consequences: elimination without pivoting is stable (ADI lines), and the
//! piecewise-linear residual is an M-function, which is what the semismooth Newton of
//! `mod.rs` relies on.
//!
//! The pressure-driven part uses the difference of g ψ (docs/conventions.md §2: it vanishes between
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
    /// rows of an axial line without their missing neighbour. The θ-columns 1 … n_θ − 2 run as
    /// one flat loop without branches, which vectorizes; their end rows and the seam columns
    /// 0 and n_θ − 1 are then redone row by row. The order of the operations, and so every bit
    /// of y, is that of the plain loop (Rust contracts nothing into fused multiply-adds; test
    /// `flat_matrix_product_is_the_row_by_row_product`).
    #[inline(always)]
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
        if nt < 3 {
            for i in 0..nt {
                self.product_line::<DEFECT>(nt, nz, i, x, b, y);
            }
            return;
        }
        // Columns 1 … n_θ − 2 in one flat pass (node k with its neighbours at k ± n_z, k ± 1):
        // a loop long enough to vectorize, where the per-column loops over a short axial line
        // (16 rows on the half grid) spent most of their time entering and leaving. The end
        // rows among them get a term that reaches across the column boundary here and are
        // redone below, as are the seam columns 0 and n_θ − 1.
        let (lo, hi) = (nz, (nt - 1) * nz);
        let len = hi - lo;
        fn span(v: &[f64], from: usize, len: usize) -> &[f64] {
            &v[from..from + len]
        }
        let (p, w, e, s, n) = (
            span(&self.p, lo, len),
            span(&self.w, lo, len),
            span(&self.e, lo, len),
            span(&self.s, lo, len),
            span(&self.n, lo, len),
        );
        let (xp, xw, xe, xs, xn) = (
            span(x, lo, len),
            span(x, lo - nz, len),
            span(x, lo + nz, len),
            span(x, lo - 1, len),
            span(x, lo + 1, len),
        );
        let yl = &mut y[lo..hi];
        if DEFECT {
            let bl = span(b, lo, len);
            for k in 0..len {
                yl[k] = bl[k]
                    - (p[k] * xp[k] + w[k] * xw[k] + e[k] * xe[k] + s[k] * xs[k] + n[k] * xn[k]);
            }
        } else {
            for k in 0..len {
                yl[k] = p[k] * xp[k] + w[k] * xw[k] + e[k] * xe[k] + s[k] * xs[k] + n[k] * xn[k];
            }
        }
        for i in 1..nt - 1 {
            self.product_end_rows::<DEFECT>(nz, i, x, b, y);
        }
        for i in [0, nt - 1] {
            self.product_line::<DEFECT>(nt, nz, i, x, b, y);
        }
    }

    /// The rows 0 and n_z − 1 of axial line i (1 ≤ i ≤ n_θ − 2) of [`Stencil::product_line`].
    #[inline(always)]
    fn product_end_rows<const DEFECT: bool>(
        &self,
        nz: usize,
        i: usize,
        x: &[f64],
        b: &[f64],
        y: &mut [f64],
    ) {
        let k = i * nz;
        let v =
            self.p[k] * x[k] + self.w[k] * x[k - nz] + self.e[k] * x[k + nz] + self.n[k] * x[k + 1];
        y[k] = if DEFECT { b[k] - v } else { v };
        let k = k + nz - 1;
        let v =
            self.p[k] * x[k] + self.w[k] * x[k - nz] + self.e[k] * x[k + nz] + self.s[k] * x[k - 1];
        y[k] = if DEFECT { b[k] - v } else { v };
    }

    /// Axial line i of y = A x (or b − A x): per row ((p x_P + w x_W) + e x_E) + s x_S + n x_N,
    /// the two end rows without their missing neighbour.
    #[inline(always)]
    fn product_line<const DEFECT: bool>(
        &self,
        nt: usize,
        nz: usize,
        i: usize,
        x: &[f64],
        b: &[f64],
        y: &mut [f64],
    ) {
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
                p[j] * xp[j] + w[j] * xw[j] + e[j] * xe[j] + s[j] * xp[j - 1] + n[j] * xp[j + 1],
            );
        }
        yl[last] = out(
            last,
            p[last] * xp[last] + w[last] * xw[last] + e[last] * xe[last] + s[last] * xp[last - 1],
        );
    }

    /// r = rhs − A x; returns (max |r|, flux scale). The flux scale is the largest driving
    /// flux of an unknown row: |rhs_k| (Couette and time terms) plus the magnitudes of its
    /// couplings to Dirichlet nodes (supply and ambient). It is independent of the stiff
    /// β-sized internal couplings, so `max |r| ≤ tol · scale` bounds the mass error of every
    /// node against the flows that actually pass through the film.
    #[inline(always)]
    pub fn residual(&self, grid: &Grid, x: &[f64], r: &mut [f64]) -> (f64, f64) {
        let (nt, nz) = (grid.n_theta, grid.n_z);
        let mut rmax: f64 = 0.0;
        let mut scale: f64 = 0.0;
        // The end rows j = 0, n_z − 1 are Dirichlet (grid module): r = rhs − x there, which the
        // five-point row below also gives (p = 1, neighbours 0), but it would reach past the
        // ends. The rows j = 1 … n_z − 2 of each axial line are slices of one length m, so the
        // loop has no branch and no bounds check: a Dirichlet row among them (groove, supply
        // line) has p = 1 and zero neighbours, and weight 0 in the scale.
        let m = nz - 2;
        for i in 0..nt {
            let iw = if i == 0 { nt - 1 } else { i - 1 };
            let ie = if i + 1 == nt { 0 } else { i + 1 };
            let (b, bw, be) = (i * nz, iw * nz, ie * nz);
            for k in [b, b + nz - 1] {
                r[k] = self.rhs[k] - x[k];
                rmax = rmax.max(r[k].abs());
            }
            fn span(v: &[f64], from: usize, m: usize) -> &[f64] {
                &v[from..from + m]
            }
            let row = |v| span(v, b + 1, m);
            let (p, w, e, s, n, rhs) = (
                row(&self.p),
                row(&self.w),
                row(&self.e),
                row(&self.s),
                row(&self.n),
                row(&self.rhs),
            );
            let (xp, xw, xe) = (row(x), &x[bw + 1..bw + 1 + m], &x[be + 1..be + 1 + m]);
            let (xs, xn) = (&x[b..b + m], &x[b + 2..b + 2 + m]);
            let u = row(&grid.unknown_weight);
            let [dw, de, ds, dn] = &grid.dirichlet_neighbour;
            let (dw, de, ds, dn) = (row(dw), row(de), row(ds), row(dn));
            let rl = &mut r[b + 1..b + 1 + m];
            for j in 0..m {
                let t = [w[j] * xw[j], e[j] * xe[j], s[j] * xs[j], n[j] * xn[j]];
                let v = rhs[j] - (p[j] * xp[j] + t[0] + t[1] + t[2] + t[3]);
                rl[j] = v;
                rmax = rmax.max(v.abs());
                let sc = rhs[j].abs()
                    + dw[j] * t[0].abs()
                    + de[j] * t[1].abs()
                    + ds[j] * t[2].abs()
                    + dn[j] * t[3].abs();
                scale = scale.max(u[j] * sc);
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
    /// h at the east θ-face of each node.
    pub h_face: &'a [f64],
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

/// Coefficients (a_L, a_R, f_0) of the θ-face east of node k in row j (L = k, R = ke):
/// F = a_L ψ_L + a_R ψ_R + f_0 with the Couette part (U/2) h_f (1 + ψ_up) upwind in the
/// direction of U on every face (module docs).
#[inline(always)]
fn theta_face(lv: &Level, g: &[f64], k: usize, ke: usize, j: usize) -> (f64, f64, f64) {
    let grid = lv.grid;
    let dx = grid.radius * grid.d_theta;
    let (gl, gr) = (g[k], g[ke]);
    let couette = 0.5 * lv.speed * lv.h_face[k];
    let (cl, cr) = if lv.speed >= 0.0 {
        (couette, 0.0)
    } else {
        (0.0, couette)
    };
    let kd = lv.k_theta[k] / dx;
    debug_assert_eq!(j, k % grid.n_z);
    let width = grid.row_width(j);
    (
        width * (cl + kd * gl),
        width * (cr - kd * gr),
        width * couette,
    )
}

/// Coefficients (a_L, a_R) of the z-face north of node k (row j).
#[inline(always)]
fn z_face(lv: &Level, g: &[f64], k: usize, j: usize) -> (f64, f64) {
    let grid = lv.grid;
    debug_assert_eq!(j, k % grid.n_z);
    let c = grid.radius * grid.d_theta * lv.k_z[k] / grid.z_gap(j);
    (c * g[k], -c * g[k + 1])
}

/// Assembles the frozen-switch system. `dirichlet[k]` is ψ_D at Dirichlet nodes.
pub(crate) fn assemble(lv: &Level, g: &[f64], dirichlet: &[f64], time: TimeTerm, st: &mut Stencil) {
    st.resize(lv.grid.len());
    assemble_columns(lv, g, dirichlet, time, st, None);
}

/// Re-assembles the rows of the θ-columns marked in `columns` (`columns[i]`: column i) of a
/// stencil that holds this level's system for another switch, leaving the other rows as they
/// are. A switch change at node k alters only the coefficients on ψ_k, i.e. the rows of k and
/// of its four neighbours, so after a change at the nodes K the columns of K and their two
/// θ-neighbours are the ones to mark; the result is then the full [`assemble`] for the new
/// switch, bit for bit: each marked row is zeroed and receives the same face contributions in
/// the same order (faces in the same (i, j) loop order, the time term, the Dirichlet rows).
///
/// ```text
///   column:   i−1        i         i+1
///   rows of i get the east faces of i−1 (W), their own east faces (E) and z-faces (S, N):
///              ●──W──▶   ●──E──▶   ●
///                        │N
///                        ●
/// ```
pub(crate) fn assemble_changed_columns(
    lv: &Level,
    g: &[f64],
    dirichlet: &[f64],
    time: TimeTerm,
    st: &mut Stencil,
    columns: &[bool],
) {
    let nz = lv.grid.n_z;
    for (i, _) in columns.iter().enumerate().filter(|(_, c)| **c) {
        for v in [
            &mut st.p,
            &mut st.w,
            &mut st.e,
            &mut st.s,
            &mut st.n,
            &mut st.rhs,
        ] {
            v[i * nz..(i + 1) * nz].fill(0.0);
        }
    }
    assemble_columns(lv, g, dirichlet, time, st, Some(columns));
}

/// The accumulation of [`assemble`] into a zeroed stencil, restricted to the rows of the
/// marked columns (all with `None`).
#[inline(always)]
fn assemble_columns(
    lv: &Level,
    g: &[f64],
    dirichlet: &[f64],
    time: TimeTerm,
    st: &mut Stencil,
    columns: Option<&[bool]>,
) {
    let grid = lv.grid;
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let marked = |i: usize| columns.is_none_or(|c| c[i]);
    let weight = match time {
        TimeTerm::Step {
            old_outflow: Some(_),
            ..
        } => 0.5,
        _ => 1.0,
    };
    for i in 0..nt {
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        let (own, east) = (marked(i), marked(ie));
        if !(own || east) {
            continue;
        }
        for j in 0..nz {
            let k = i * nz + j;
            let ke = ie * nz + j;
            let (al, ar, f0) = theta_face(lv, g, k, ke, j);
            if own {
                st.p[k] += weight * al;
                st.e[k] += weight * ar;
                st.rhs[k] -= weight * f0;
            }
            if east {
                st.p[ke] -= weight * ar;
                st.w[ke] -= weight * al;
                st.rhs[ke] += weight * f0;
            }
            if own && j + 1 < nz {
                let (al, ar) = z_face(lv, g, k, j);
                st.p[k] += weight * al;
                st.n[k] += weight * ar;
                st.p[k + 1] -= weight * ar;
                st.s[k + 1] -= weight * al;
            }
        }
    }
    for i in (0..nt).filter(|&i| marked(i)) {
        let rows = i * nz..(i + 1) * nz;
        if let TimeTerm::Step {
            dt,
            old_content,
            old_outflow,
        } = time
        {
            for (j, k) in rows.clone().enumerate() {
                let c = grid.cell_area(j) / dt;
                st.p[k] += c * lv.h[k];
                st.rhs[k] += c * (old_content[k] - lv.h[k]);
                if let Some(d) = old_outflow {
                    st.rhs[k] -= 0.5 * d[k];
                }
            }
        }
        for k in rows {
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
            let (al, ar, f0) = theta_face(lv, g, k, ke, j);
            theta[k] = al * psi[k] + ar * psi[ke] + f0;
            z[k] = if j + 1 < nz {
                let (al, ar) = z_face(lv, g, k, j);
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

/// The mass residual R_k of every unknown node for a film given by its content variable
/// `content` (ψ_c, φ = 1 + ψ_c: what the Couette and time terms carry) and its pressure
/// variable `pressure` (g ψ ≥ 0 where full: what the pressure flux sees), written out from the
/// face fluxes of the module docs — independently of [`assemble`]. At a complementary point
/// (content = ψ, pressure = max(ψ, 0)) it is A(H(ψ)) ψ − b, the residual of the solve. The
/// LCP oracle test probes the discrete problem through it, column by column. Dirichlet rows
/// get 0. Returns ‖R‖₂ over the unknowns.
#[cfg(test)]
pub(crate) fn mass_residual(
    lv: &Level,
    content: &[f64],
    pressure: &[f64],
    time: TimeTerm,
    out: &mut [f64],
) -> f64 {
    let grid = lv.grid;
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let dx = grid.radius * grid.d_theta;
    out.iter_mut().for_each(|o| *o = 0.0);
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
            let up = if lv.speed >= 0.0 { k } else { ke };
            let f = grid.row_width(j)
                * (0.5 * lv.speed * lv.h_face[k] * (1.0 + content[up])
                    - lv.k_theta[k] / dx * (pressure[ke] - pressure[k]));
            out[k] += weight * f;
            out[ke] -= weight * f;
            if j + 1 < nz {
                let f = -dx * lv.k_z[k] / grid.z_gap(j) * (pressure[k + 1] - pressure[k]);
                out[k] += weight * f;
                out[k + 1] -= weight * f;
            }
        }
    }
    if let TimeTerm::Step {
        dt,
        old_content,
        old_outflow,
    } = time
    {
        for (k, j) in (0..grid.n_theta).flat_map(|_| 0..nz).enumerate() {
            let v = grid.cell_area(j);
            out[k] += v / dt * (lv.h[k] * (1.0 + content[k]) - old_content[k]);
            if let Some(d) = old_outflow {
                out[k] += 0.5 * d[k];
            }
        }
    }
    let mut norm = 0.0;
    for k in 0..grid.len() {
        if grid.kind[k] == NodeKind::Unknown {
            norm += out[k] * out[k];
        } else {
            out[k] = 0.0;
        }
    }
    norm.sqrt()
}

/// ∂R_k/∂ε_c at fixed ψ for every unknown node (0 on Dirichlet rows): the derivative of
/// [`mass_residual`] along a change of the film thickness `dh_node` / `dh_face` (∂h/∂ε_c at the
/// nodes and east θ-faces; for ε_x: −c cos θ, for ε_y: −c sin θ). h enters the Couette flux
/// (U/2) h_f φ_up, the pressure-flux coefficients k = β h³/(12μ) (dk = 3 k dh/h, with the
/// z-face thickness the mean of its two nodes) and the time term V h φ/Δt; `flux_weight` is ½
/// for Crank–Nicolson, else 1, and `dt` the (effective) step of the time term, None when
/// steady. `content` is ψ, `pressure` g ψ of the converged film.
#[allow(clippy::too_many_arguments)]
pub(crate) fn residual_eccentricity_derivative(
    lv: &Level,
    dh_node: &[f64],
    dh_face: &[f64],
    content: &[f64],
    pressure: &[f64],
    flux_weight: f64,
    dt: Option<f64>,
    out: &mut [f64],
) {
    let grid = lv.grid;
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let dx = grid.radius * grid.d_theta;
    out.iter_mut().for_each(|o| *o = 0.0);
    for i in 0..nt {
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        for j in 0..nz {
            let k = i * nz + j;
            let ke = ie * nz + j;
            let up = if lv.speed >= 0.0 { k } else { ke };
            let dk = 3.0 * lv.k_theta[k] / lv.h_face[k] * dh_face[k];
            let df = grid.row_width(j)
                * (0.5 * lv.speed * dh_face[k] * (1.0 + content[up])
                    - dk / dx * (pressure[ke] - pressure[k]));
            out[k] += flux_weight * df;
            out[ke] -= flux_weight * df;
            if j + 1 < nz {
                let hz = 0.5 * (lv.h[k] + lv.h[k + 1]);
                let dkz = 3.0 * lv.k_z[k] / hz * 0.5 * (dh_node[k] + dh_node[k + 1]);
                let df = -dx * dkz / grid.z_gap(j) * (pressure[k + 1] - pressure[k]);
                out[k] += flux_weight * df;
                out[k + 1] -= flux_weight * df;
            }
        }
    }
    if let Some(dt) = dt {
        for (k, j) in (0..nt).flat_map(|_| 0..nz).enumerate() {
            let v = grid.cell_area(j);
            out[k] += v / dt * dh_node[k] * (1.0 + content[k]);
        }
    }
    for k in 0..grid.len() {
        if grid.kind[k] != NodeKind::Unknown {
            out[k] = 0.0;
        }
    }
}
