//! Finite-length pure-squeeze film under the Reynolds (Swift–Stieber) condition: the film a
//! mobility map is tabulated from.
//!
//! # What it solves
//!
//! A plain 360° journal bearing (no grooves, ambient pressure at both ends, p_amb = p_cav = 0),
//! journal moving without rotation (ω̄ = 0) with squeeze velocity v = c u, u = dε/dt. The
//! Reynolds equation (docs/conventions.md §2 with g = 1, incompressible) in θ and ξ = z/R:
//!
//! ```text
//!   ∂/∂θ (H³ ∂P/∂θ) + ∂/∂ξ (H³ ∂P/∂ξ) = −12 û·n(θ),      H = h/c = 1 − ε·n(θ),
//!   n(θ) = (cos θ, sin θ),  p = μ |u| (R/c)² P,  ξ ∈ [−L/D, L/D]  (ξ = ±L/D are the ends),
//! ```
//!
//! with P = 0 at the ends and the Reynolds condition P ≥ 0, (flow balance) where P > 0: a linear
//! complementarity problem. A single instant has no film history, which the mass-conserving JFO
//! model needs; mobility methods assume exactly this condition (\[Booker1965\]; \[Goenka1984\] tabulated
//! finite-element solutions of it). In the short-bearing limit the θ-lines decouple and the
//! condition reduces to Gumbel's half film: P = 6 (û·n)⁺ ((L/D)² − ξ²)/H³ (\[Flores2006\], eq. 18
//! with ω̄ = 0), which the tests use as the oracle.
//!
//! The dimensionless load (the load that balances the film, W = −F_film) is
//!
//! ```text
//!   Z = W (c/R)² / (μ L D |u|) = 1/(4 L/D) ∫∫ P n dθ dξ,
//! ```
//!
//! the quantity [`crate::mobility::PureSqueezeFilm`] asks for (short bearing: Z = 2 (L/D)² J).
//!
//! # Grid and stencil
//!
//! Symmetric in ξ, so only ξ ∈ [0, L/D] is solved (zero flux through ξ = 0). θ is periodic and
//! clustered at the thinnest film, where the pressure peak narrows like (1 − ε)^{1/2}:
//! θ(s) = θ_ε + s − a sin s, s uniform on [0, 2π), a = [`SqueezeFilmParams::clustering`] (spacing
//! 1 − a times the uniform one at h_min, 1 + a opposite).
//!
//! ```text
//!   ξ = L/D  ── P = 0 (ambient) ──────────────────────────────  row j = m (not unknown)
//!              │        │        │
//!   ξ_j      ──●────────●────────●──   cell of node (i, j): θ ∈ [θ_{i−½}, θ_{i+½}],
//!              │  (i,j) │        │                            ξ ∈ [ξ_j − Δξ/2, ξ_j + Δξ/2]
//!   ξ = 0    ──●────────●────────●──   row j = 0: half cell, zero flux through ξ = 0
//!            θ_{i−1}   θ_i     θ_{i+1}  (periodic: i = n ≡ 0)
//!
//!   flux through the θ face i+½ = H³(θ_{i+½}) (P_{i+1,j} − P_{i,j}) / (θ_{i+1} − θ_i) · Δξ_j
//!   flux through the ξ face j+½ = H³(θ_i) (P_{i,j+1} − P_{i,j}) / Δξ · Δθ_i
//! ```
//!
//! Faces take the exact film thickness, so the scheme is conservative and second order on the
//! smooth (uncavitated) part. The right-hand side is −12 (û·n_i) Δθ_i Δξ_j per cell.
//!
//! # The complementarity solve
//!
//! With A the (symmetric positive definite, M-matrix) negative of the flux operator and f the
//! right-hand side: P ≥ 0, A P − f ≥ 0, P·(A P − f) = 0. The primal–dual active-set method
//! \[HintermullerItoKunisch2002\] solves it exactly in a few sparse LU solves (faer): nodes
//! with P = 0 are "active"; each pass solves the free rows and re-sorts nodes by the sign of P
//! (free nodes) or of the multiplier A P − f (active nodes). For an M-matrix it terminates in
//! finitely many passes; a pass limit guards the loop.
//!
//! A map node asks for the squeeze direction whose load lies along one axis (the balanced
//! squeeze, [`PureSqueezeFilm::balanced_squeeze`]). For a fixed active set P and the load are
//! linear in û, so each active-set pass solves the free rows for û = x̂ and ŷ (one factor, two
//! right-hand sides), takes the direction that balances that linear load exactly, and re-sorts:
//! 5–6 factorizations per node (L/D 1/8 … 1, starting from the previous node's cavity) instead
//! of a root search over ~17 complementarity solves of ~4 each (`ReynoldsSqueezeFilm::balanced`;
//! the same node to round-off, tested against the search).

use crate::mobility::PureSqueezeFilm;
use crate::mobility::short_bearing::invert_squeeze_fallible;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use std::f64::consts::TAU;
use std::sync::Mutex;
use thiserror::Error;

/// Grid of the pure-squeeze film solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqueezeFilmParams {
    /// Bearing length over diameter, L/D.
    pub length_to_diameter: f64,
    /// Nodes around the circumference (≥ 8).
    pub circumferential_nodes: usize,
    /// Cells across the half length ξ ∈ [0, L/D] (≥ 2); the end node is the boundary.
    pub axial_cells: usize,
    /// Clustering a ∈ [0, 1) of the θ nodes at the thinnest film (0: uniform).
    pub clustering: f64,
}

impl SqueezeFilmParams {
    /// The default grid for an L/D: 144 × 12, clustering 0.8 (spacing 0.9° at h_min, 4.5°
    /// opposite). `validation/tests/mobility_finite_length.rs` shows the load within 0.5 % of a
    /// grid twice as fine up to ε = 0.95.
    pub fn new(length_to_diameter: f64) -> Self {
        Self {
            length_to_diameter,
            circumferential_nodes: 144,
            axial_cells: 12,
            clustering: 0.8,
        }
    }
}

/// What went wrong in a pure-squeeze solve.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SqueezeFilmError {
    #[error("invalid squeeze-film parameter {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
    #[error("eccentricity ratio |ε| = {eccentricity} outside [0, 1)")]
    EccentricityOutOfRange { eccentricity: f64 },
    #[error("squeeze direction ({ux}, {uy}) is not a unit vector")]
    BadDirection { ux: f64, uy: f64 },
    #[error("sparse LU of the squeeze-film system failed at active-set pass {pass}: {reason}")]
    Factorization { pass: usize, reason: String },
    #[error(
        "active set did not settle after {passes} passes at ε = ({ex}, {ey}) ({changed} nodes still switching)"
    )]
    ActiveSetNotConverged {
        passes: usize,
        ex: f64,
        ey: f64,
        changed: usize,
    },
    #[error("non-finite pressure at node (θ index {i}, ξ index {j})")]
    NonFinitePressure { i: usize, j: usize },
}

/// A pure-squeeze solution.
#[derive(Debug, Clone, PartialEq)]
pub struct SqueezeFilmSolution {
    /// Z = W (c/R)² / (μ L D |u|): the dimensionless load balancing the film (x, y).
    pub load: [f64; 2],
    /// Dimensionless pressure P = p / (μ |u| (R/c)²), index i * (axial_cells) + j, half domain.
    pub pressure: Vec<f64>,
    /// θ of the nodes (rad).
    pub theta: Vec<f64>,
    /// ξ = z/R of the node rows (0 … L/D − Δξ).
    pub xi: Vec<f64>,
    /// Fraction of the (half) film area where P > 0.
    pub pressurised_fraction: f64,
    /// Active-set passes (sparse LU solves).
    pub passes: usize,
}

/// The finite-difference pure-squeeze film (see the module docs); implements
/// [`PureSqueezeFilm`] for the finite-length mobility map.
#[derive(Debug)]
pub struct ReynoldsSqueezeFilm {
    params: SqueezeFilmParams,
    /// Symbolic Cholesky of the grid's 5-point pattern (the same for every ε, û and active
    /// set: active nodes keep their pattern entries with zero values), computed once.
    symbolic: SymbolicLlt<usize>,
    /// The last converged active set and the ε it belongs to: a bracketed inversion over
    /// [`Self::solve`] (the fallback of [`Self::balanced`], or a caller of `squeeze_load`) asks
    /// for ~10–20 squeeze directions at one ε, whose cavities differ little, so the next solve
    /// starts from it (a start guess only: the answer does not depend on it).
    last_active: Mutex<Option<([u64; 2], Vec<bool>)>>,
    /// The active set of the last balanced squeeze ([`Self::balanced`]'s start guess).
    last_balanced: Mutex<Option<Vec<bool>>>,
}

impl Clone for ReynoldsSqueezeFilm {
    fn clone(&self) -> Self {
        Self {
            params: self.params,
            symbolic: self.symbolic.clone(),
            last_active: Mutex::new(None),
            last_balanced: Mutex::new(None),
        }
    }
}

const MAX_PASSES: usize = 60;

impl ReynoldsSqueezeFilm {
    /// Checks the grid.
    pub fn new(params: SqueezeFilmParams) -> Result<Self, SqueezeFilmError> {
        let bad = |name, value| Err(SqueezeFilmError::InvalidParameter { name, value });
        let ld = params.length_to_diameter;
        if !(ld.is_finite() && ld > 0.0) {
            return bad("length_to_diameter", ld);
        }
        if params.circumferential_nodes < 8 {
            return bad("circumferential_nodes", params.circumferential_nodes as f64);
        }
        if params.axial_cells < 2 {
            return bad("axial_cells", params.axial_cells as f64);
        }
        if !(params.clustering >= 0.0 && params.clustering < 1.0) {
            return bad("clustering", params.clustering);
        }
        let (n, m) = (params.circumferential_nodes, params.axial_cells);
        let pattern = stencil_pattern(n, m);
        let trip: Vec<_> = pattern
            .iter()
            .map(|&(r, c)| Triplet::new(r, c, 1.0))
            .collect();
        let symbolic = SparseColMat::<usize, f64>::try_new_from_triplets(n * m, n * m, &trip)
            .map_err(|e| format!("{e:?}"))
            .and_then(|mat| {
                SymbolicLlt::try_new(mat.symbolic(), Side::Lower).map_err(|e| format!("{e:?}"))
            })
            .map_err(|reason| SqueezeFilmError::Factorization { pass: 0, reason })?;
        Ok(Self {
            params,
            symbolic,
            last_active: Mutex::new(None),
            last_balanced: Mutex::new(None),
        })
    }

    /// The grid.
    pub fn params(&self) -> &SqueezeFilmParams {
        &self.params
    }

    /// Solves the pure-squeeze film at eccentricity ratio `eps` for the unit squeeze direction
    /// `u_dir` (same frame).
    pub fn solve(
        &self,
        eps: [f64; 2],
        u_dir: [f64; 2],
    ) -> Result<SqueezeFilmSolution, SqueezeFilmError> {
        let e = eps[0].hypot(eps[1]);
        if !(e.is_finite() && e < 1.0) {
            return Err(SqueezeFilmError::EccentricityOutOfRange { eccentricity: e });
        }
        let un = u_dir[0].hypot(u_dir[1]);
        if !(un.is_finite() && (un - 1.0).abs() < 1e-9) {
            return Err(SqueezeFilmError::BadDirection {
                ux: u_dir[0],
                uy: u_dir[1],
            });
        }
        let grid = SqueezeGrid::new(&self.params, eps);
        let (rows, rhs) = grid.assemble(u_dir);
        // Primal–dual active set. Start: the last active set at this ε, else the nodes where
        // the squeeze pulls (f ≤ 0).
        let key = [eps[0].to_bits(), eps[1].to_bits()];
        let cached = self.last_active.lock().ok().and_then(|g| {
            g.as_ref()
                .filter(|(k, _)| *k == key)
                .map(|(_, a)| a.clone())
        });
        let mut active: Vec<bool> =
            cached.unwrap_or_else(|| rhs.iter().map(|&f| f <= 0.0).collect());
        let (p, passes) = self.active_set(&rows, &rhs, &mut active, eps)?;
        if let Ok(mut g) = self.last_active.lock() {
            *g = Some((key, active));
        }
        let ld = self.params.length_to_diameter;
        let (load, wet) = grid.load(&p, ld);
        Ok(SqueezeFilmSolution {
            load,
            pressure: p,
            theta: grid.theta,
            xi: grid.xi,
            pressurised_fraction: wet / (TAU * ld),
            passes,
        })
    }

    /// The balanced squeeze of a map node ([`PureSqueezeFilm::balanced_squeeze`]): the
    /// direction û = (cos a, sin a), |a| < π/2, whose load has no y-component, and its Z_x.
    ///
    /// For a fixed active set (cavity) the pressure and the load are linear in û: with
    /// P = cos a P_x + sin a P_y (P_x, P_y the free-node solutions for û = (1, 0) and (0, 1),
    /// one Cholesky factor, two right-hand sides) the load's y-component
    /// Z_y(a) = cos a Z_y(P_x) + sin a Z_y(P_y) vanishes at a = atan(−Z_y(P_x)/Z_y(P_y)), the only
    /// root in (−π/2, π/2). Each pass takes that root, re-sorts the active set by P and its
    /// multiplier as [`solve`](Self::solve) does, and stops when no node changes: then P is the
    /// complementarity solution for that û and its load has no y-component — the node the
    /// bracketed root search over [`solve`](Self::solve) finds, in ~6 factorizations instead of
    /// ~68 (17 solves of ~4 passes each, measured on the compressor main bearing's map). `None`
    /// when a pass has no root (Z_y(P_y) = 0 or not finite) or the passes do not settle: the
    /// caller then takes the bracketed search.
    fn balanced(&self, eps: [f64; 2]) -> Result<Option<([f64; 2], f64)>, SqueezeFilmError> {
        let e = eps[0].hypot(eps[1]);
        if !(e.is_finite() && e < 1.0) {
            return Err(SqueezeFilmError::EccentricityOutOfRange { eccentricity: e });
        }
        let ld = self.params.length_to_diameter;
        let m = self.params.axial_cells;
        let grid = SqueezeGrid::new(&self.params, eps);
        let (rows, fx) = grid.assemble([1.0, 0.0]);
        let (_, fy) = grid.assemble([0.0, 1.0]);
        let nn = rows.len();
        // Start: the last balanced node's cavity (a map asks for its nodes in order: the next
        // ψ or ε), else where the squeeze along x pulls. A start guess only.
        let mut active: Vec<bool> = self
            .last_balanced
            .lock()
            .ok()
            .and_then(|g| g.clone())
            .filter(|a| a.len() == nn)
            .unwrap_or_else(|| fx.iter().map(|&f| f <= 0.0).collect());
        let (mut px, mut py, mut p, mut f) =
            (vec![0.0; nn], vec![0.0; nn], vec![0.0; nn], vec![0.0; nn]);
        for pass in 1..=MAX_PASSES {
            let llt = self.factor_free(&rows, &active, pass)?;
            let mut b = Mat::<f64>::zeros(nn, 2);
            for k in 0..nn {
                if !active[k] {
                    b[(k, 0)] = fx[k];
                    b[(k, 1)] = fy[k];
                }
            }
            let x = llt.solve(&b);
            for k in 0..nn {
                (px[k], py[k]) = if active[k] {
                    (0.0, 0.0)
                } else {
                    (x[(k, 0)], x[(k, 1)])
                };
                if !(px[k].is_finite() && py[k].is_finite()) {
                    return Err(SqueezeFilmError::NonFinitePressure { i: k / m, j: k % m });
                }
            }
            let (zx, _) = grid.load(&px, ld);
            let (zy, _) = grid.load(&py, ld);
            if !(zy[1] != 0.0 && zy[1].is_finite() && zx[1].is_finite()) {
                return Ok(None);
            }
            let a = (-zx[1] / zy[1]).atan();
            let (sa, ca) = a.sin_cos();
            for k in 0..nn {
                p[k] = ca * px[k] + sa * py[k];
                f[k] = ca * fx[k] + sa * fy[k];
            }
            if resort(&rows, &f, &p, &mut active) == 0 {
                if let Ok(mut g) = self.last_balanced.lock() {
                    *g = Some(active);
                }
                return Ok(Some(([ca, sa], ca * zx[0] + sa * zy[0])));
            }
        }
        Ok(None)
    }

    /// The Cholesky factor of the free-node system of an active set: active rows and columns
    /// become identity rows and zero columns (P_A = 0), keeping the pattern of the cached
    /// symbolic factor. `pass` names the active-set pass in an error.
    fn factor_free(
        &self,
        rows: &[Vec<(usize, f64)>],
        active: &[bool],
        pass: usize,
    ) -> Result<Llt<usize, f64>, SqueezeFilmError> {
        let nn = rows.len();
        let mut trip = Vec::with_capacity(nn * 5);
        for k in 0..nn {
            for &(c, v) in &rows[k] {
                let val = if c == k {
                    if active[k] { 1.0 } else { v }
                } else if active[k] || active[c] {
                    0.0
                } else {
                    v
                };
                trip.push(Triplet::new(k, c, val));
            }
        }
        let factor = |reason: String| SqueezeFilmError::Factorization { pass, reason };
        let mat = SparseColMat::<usize, f64>::try_new_from_triplets(nn, nn, &trip)
            .map_err(|e| factor(format!("{e:?}")))?;
        Llt::try_new_with_symbolic(self.symbolic.clone(), mat.as_ref(), Side::Lower)
            .map_err(|e| factor(format!("{e:?}")))
    }

    /// The primal–dual active-set passes (module docs) on the operator `rows` and right-hand
    /// side `rhs` from the start set `active` (updated to the final one). Returns P and the
    /// number of passes.
    fn active_set(
        &self,
        rows: &[Vec<(usize, f64)>],
        rhs: &[f64],
        active: &mut [bool],
        eps: [f64; 2],
    ) -> Result<(Vec<f64>, usize), SqueezeFilmError> {
        let nn = rows.len();
        let m = self.params.axial_cells;
        let mut p = vec![0.0; nn];
        let mut passes = 0;
        loop {
            passes += 1;
            // Symmetric system on the free nodes (P_A = 0).
            let llt = self.factor_free(rows, active, passes)?;
            let mut b = Mat::<f64>::zeros(nn, 1);
            for k in 0..nn {
                if !active[k] {
                    b[(k, 0)] = rhs[k];
                }
            }
            let x = llt.solve(&b);
            for k in 0..nn {
                p[k] = if active[k] { 0.0 } else { x[(k, 0)] };
                if !p[k].is_finite() {
                    return Err(SqueezeFilmError::NonFinitePressure { i: k / m, j: k % m });
                }
            }
            let changed = resort(rows, rhs, &p, active);
            if changed == 0 {
                return Ok((p, passes));
            }
            if passes >= MAX_PASSES {
                return Err(SqueezeFilmError::ActiveSetNotConverged {
                    passes,
                    ex: eps[0],
                    ey: eps[1],
                    changed,
                });
            }
        }
    }
}

/// The clustered grid of one ε (module docs): node angles, cell widths, node spacings, H³ at
/// the θ-faces and nodes, and the ξ rows.
struct SqueezeGrid {
    theta: Vec<f64>,
    /// Δθ_i of each cell.
    cell: Vec<f64>,
    /// θ_{i+1} − θ_i (periodic).
    gap: Vec<f64>,
    /// H³ at θ_{i+½}.
    face_h3: Vec<f64>,
    /// H³ at θ_i.
    node_h3: Vec<f64>,
    xi: Vec<f64>,
    dxi: f64,
}

impl SqueezeGrid {
    fn new(params: &SqueezeFilmParams, eps: [f64; 2]) -> Self {
        let SqueezeFilmParams {
            length_to_diameter: ld,
            circumferential_nodes: n,
            axial_cells: m,
            clustering: a,
        } = *params;
        let e = eps[0].hypot(eps[1]);
        let theta_eps = if e > 0.0 { eps[1].atan2(eps[0]) } else { 0.0 };
        let ds = TAU / n as f64;
        let theta_of = |s: f64| theta_eps + s - a * s.sin();
        let film = |t: f64| 1.0 - eps[0] * t.cos() - eps[1] * t.sin();
        let theta: Vec<f64> = (0..n).map(|i| theta_of(i as f64 * ds)).collect();
        let cell = (0..n)
            .map(|i| {
                let s = i as f64 * ds;
                theta_of(s + 0.5 * ds) - theta_of(s - 0.5 * ds)
            })
            .collect();
        let gap = (0..n)
            .map(|i| {
                let s = i as f64 * ds;
                theta_of(s + ds) - theta_of(s)
            })
            .collect();
        let face_h3 = (0..n)
            .map(|i| film(theta_of((i as f64 + 0.5) * ds)).powi(3))
            .collect();
        let node_h3 = theta.iter().map(|&t| film(t).powi(3)).collect();
        let dxi = ld / m as f64;
        Self {
            theta,
            cell,
            gap,
            face_h3,
            node_h3,
            xi: (0..m).map(|j| j as f64 * dxi).collect(),
            dxi,
        }
    }

    /// The load Z = 1/(4 L/D) ∫∫ P n dθ dξ over ξ ∈ [−L/D, L/D] (twice the half domain) of the
    /// half-domain pressure `p`, and the half-domain area where P > 0.
    fn load(&self, p: &[f64], ld: f64) -> ([f64; 2], f64) {
        let m = self.xi.len();
        let mut load = [0.0; 2];
        let mut wet = 0.0;
        for (i, theta) in self.theta.iter().enumerate() {
            let (st, ct) = theta.sin_cos();
            for j in 0..m {
                let da = self.cell[i] * self.width(j);
                let pk = p[i * m + j];
                load[0] += pk * ct * da;
                load[1] += pk * st * da;
                if pk > 0.0 {
                    wet += da;
                }
            }
        }
        let scale = 2.0 / (4.0 * ld);
        ([load[0] * scale, load[1] * scale], wet)
    }

    /// Δξ_j: half a cell on the symmetry row j = 0.
    fn width(&self, j: usize) -> f64 {
        if j == 0 { 0.5 * self.dxi } else { self.dxi }
    }

    /// The operator A (negative flux operator) per row as (column, value), and the right-hand
    /// side f = −12 (û·n_i) Δθ_i Δξ_j (module docs' stencil).
    fn assemble(&self, u_dir: [f64; 2]) -> (Vec<Vec<(usize, f64)>>, Vec<f64>) {
        let (n, m, dxi) = (self.theta.len(), self.xi.len(), self.dxi);
        let idx = |i: usize, j: usize| i * m + j;
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::with_capacity(5); n * m];
        let mut rhs = vec![0.0; n * m];
        for i in 0..n {
            let ip = (i + 1) % n;
            let im = (i + n - 1) % n;
            let ct = [self.theta[i].cos(), self.theta[i].sin()];
            let source = 12.0 * (u_dir[0] * ct[0] + u_dir[1] * ct[1]);
            for j in 0..m {
                let k = idx(i, j);
                let wj = self.width(j);
                let east = self.face_h3[i] / self.gap[i] * wj;
                let west = self.face_h3[im] / self.gap[im] * wj;
                // ξ faces: north (towards the end) always; south only for j > 0 (mirror at 0).
                let north = self.node_h3[i] / dxi * self.cell[i];
                let south = if j > 0 {
                    self.node_h3[i] / dxi * self.cell[i]
                } else {
                    0.0
                };
                let diag = east + west + north + south;
                let row = &mut rows[k];
                row.push((idx(ip, j), -east));
                row.push((idx(im, j), -west));
                if j + 1 < m {
                    row.push((idx(i, j + 1), -north));
                } // else the neighbour is the end row, P = 0: only the diagonal term stays.
                if j > 0 {
                    row.push((idx(i, j - 1), -south));
                }
                row.push((k, diag));
                rhs[k] = source * self.cell[i] * wj;
            }
        }
        (rows, rhs)
    }
}

/// The active-set re-sort of one pass: free nodes with P < 0 become active; active nodes whose
/// multiplier λ = (A P − f) is negative (the film there wants positive pressure) become free.
/// Returns the number of nodes that changed.
fn resort(rows: &[Vec<(usize, f64)>], rhs: &[f64], p: &[f64], active: &mut [bool]) -> usize {
    let mut changed = 0;
    for k in 0..rows.len() {
        let now = if active[k] {
            let ap: f64 = rows[k].iter().map(|&(c, v)| v * p[c]).sum();
            ap - rhs[k] >= 0.0
        } else {
            p[k] < 0.0
        };
        if now != active[k] {
            changed += 1;
            active[k] = now;
        }
    }
    changed
}

/// The (row, column) pairs of the 5-point stencil, in the row order the solver assembles them.
fn stencil_pattern(n: usize, m: usize) -> Vec<(usize, usize)> {
    let mut out = Vec::with_capacity(n * m * 5);
    for i in 0..n {
        let (ip, im) = ((i + 1) % n, (i + n - 1) % n);
        for j in 0..m {
            let k = i * m + j;
            out.push((k, ip * m + j));
            out.push((k, im * m + j));
            if j + 1 < m {
                out.push((k, k + 1));
            }
            if j > 0 {
                out.push((k, k - 1));
            }
            out.push((k, k));
        }
    }
    out
}

impl PureSqueezeFilm for ReynoldsSqueezeFilm {
    fn length_to_diameter(&self) -> f64 {
        self.params.length_to_diameter
    }

    fn squeeze_load(
        &self,
        eps: [f64; 2],
        u_dir: [f64; 2],
    ) -> Result<[f64; 2], Box<dyn std::error::Error + Send + Sync>> {
        Ok(self.solve(eps, u_dir)?.load)
    }

    fn balanced_squeeze(
        &self,
        eps: [f64; 2],
    ) -> Result<([f64; 2], f64), Box<dyn std::error::Error + Send + Sync>> {
        match self.balanced(eps)? {
            Some(node) => Ok(node),
            None => invert_squeeze_fallible(|u| self.squeeze_load(eps, u)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mobility::short_bearing_squeeze_integral;

    fn film(ld: f64, n: usize, m: usize) -> ReynoldsSqueezeFilm {
        ReynoldsSqueezeFilm::new(SqueezeFilmParams {
            length_to_diameter: ld,
            circumferential_nodes: n,
            axial_cells: m,
            clustering: 0.8,
        })
        .unwrap()
    }

    #[test]
    fn concentric_squeeze_balances_the_load_along_the_motion() {
        // At ε = 0 the film is axisymmetric: the load must be parallel to û (no y component for
        // û = x̂) and positive. Round-off level for the cross component.
        let s = film(0.5, 96, 8).solve([0.0, 0.0], [1.0, 0.0]).unwrap();
        assert!(s.load[0] > 0.0);
        assert!(s.load[1].abs() < 1e-10 * s.load[0], "{:?}", s.load);
    }

    /// The balanced squeeze of a map node by the linear-in-û active-set passes is the node the
    /// bracketed root search over [`ReynoldsSqueezeFilm::solve`] finds (the independent route
    /// the map used before), on the default grid for short, medium and long bearings, from the
    /// concentric film to the map's edge ε = 0.99, with ε on, across and against the load line.
    /// Both solve the same complementarity problem with its root in a; they differ by the root
    /// search's end (a bracket of 1e-14) and round-off: 1e-10 relative. The node must come from
    /// the passes, not the bracketed fallback, and its load must have no y-component.
    #[test]
    fn balanced_squeeze_is_the_bracketed_root() {
        for ld in [0.125, 1.0 / 3.0, 1.0] {
            let f = ReynoldsSqueezeFilm::new(SqueezeFilmParams::new(ld)).unwrap();
            for (e, psi_deg) in [
                (0.0, 0.0),
                (0.3, 90.0),
                (0.6, 10.0),
                (0.8, 170.0),
                (0.9, 45.0),
                (0.97, 2.0),
                (0.97, 120.0),
                (0.99, 30.0),
            ] {
                let psi = f64::to_radians(psi_deg);
                let eps = [e * psi.cos(), -e * psi.sin()];
                let (u, zx) = f
                    .balanced(eps)
                    .unwrap()
                    .unwrap_or_else(|| panic!("L/D {ld}, ε {eps:?}: the passes did not settle"));
                let (u_ref, zx_ref) = invert_squeeze_fallible(|u| f.squeeze_load(eps, u)).unwrap();
                let what = format!("L/D {ld}, ε {eps:?}: {u:?} {zx} vs {u_ref:?} {zx_ref}");
                assert!(zx > 0.0 && (zx - zx_ref).abs() <= 1e-10 * zx_ref, "{what}");
                assert!((u[0] - u_ref[0]).hypot(u[1] - u_ref[1]) <= 1e-10, "{what}");
                let load = f.solve(eps, u).unwrap().load;
                assert!(load[1].abs() <= 1e-10 * load[0], "{what}: load {load:?}");
            }
        }
    }

    #[test]
    fn mirror_symmetry_of_the_film() {
        // Mirroring ε and û in the x axis mirrors the load (a plain bearing has no preferred
        // side). Different grids (the clustering follows ε) so agreement is to discretisation
        // level only if the code mixes up signs; both are the same grid mirrored: tight.
        let f = film(0.5, 96, 8);
        let a = f.solve([0.6, 0.3], [0.8, 0.6]).unwrap().load;
        let b = f.solve([0.6, -0.3], [0.8, -0.6]).unwrap().load;
        assert!((a[0] - b[0]).abs() < 1e-9 * a[0].abs(), "{a:?} {b:?}");
        assert!((a[1] + b[1]).abs() < 1e-9 * a[0].abs(), "{a:?} {b:?}");
    }

    #[test]
    fn short_bearing_limit_is_gumbel() {
        // L/D = 0.05: the axial terms dominate by (D/L)² = 400, so the FD answer must approach
        // the short-bearing Gumbel closed form Z = 2 (L/D)² J ([Flores2006] eqs. 18, 23–27); the
        // remaining difference is O((L/D)²) from the θ-flux plus the θ discretisation.
        let ld = 0.05;
        let f = film(ld, 288, 8);
        for (eps, u) in [
            ([0.5, 0.0], [1.0, 0.0]),
            ([0.3, 0.4], [0.0, 1.0]),
            ([0.8, 0.0], [0.6, 0.8]),
        ] {
            let z = f.solve(eps, u).unwrap().load;
            let j = short_bearing_squeeze_integral(eps, u);
            let k = 2.0 * ld * ld;
            let zs = [k * j[0], k * j[1]];
            let err = (z[0] - zs[0]).hypot(z[1] - zs[1]) / zs[0].hypot(zs[1]);
            assert!(
                err < 0.02,
                "ε {eps:?} û {u:?}: FD {z:?} vs short {zs:?} ({err})"
            );
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(ReynoldsSqueezeFilm::new(SqueezeFilmParams::new(-1.0)).is_err());
        let f = film(0.5, 32, 4);
        assert!(matches!(
            f.solve([1.0, 0.0], [1.0, 0.0]),
            Err(SqueezeFilmError::EccentricityOutOfRange { .. })
        ));
        assert!(matches!(
            f.solve([0.1, 0.0], [2.0, 0.0]),
            Err(SqueezeFilmError::BadDirection { .. })
        ));
    }
}
