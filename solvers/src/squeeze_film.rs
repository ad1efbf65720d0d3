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

use crate::mobility::PureSqueezeFilm;
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
    /// The last converged active set and the ε it belongs to: the mobility inversion asks for
    /// ~10–20 squeeze directions at one ε, whose cavities differ little, so the next solve
    /// starts from it (a start guess only: the answer does not depend on it).
    last_active: Mutex<Option<([u64; 2], Vec<bool>)>>,
}

impl Clone for ReynoldsSqueezeFilm {
    fn clone(&self) -> Self {
        Self {
            params: self.params,
            symbolic: self.symbolic.clone(),
            last_active: Mutex::new(None),
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
        // Z = 1/(4 L/D) ∫∫ P n dθ dξ over ξ ∈ [−L/D, L/D] = 2 × the half domain.
        let (m, ld) = (grid.xi.len(), self.params.length_to_diameter);
        let mut load = [0.0; 2];
        let mut wet = 0.0;
        for (i, theta) in grid.theta.iter().enumerate() {
            let (st, ct) = theta.sin_cos();
            for j in 0..m {
                let da = grid.cell[i] * grid.width(j);
                let pk = p[i * m + j];
                load[0] += pk * ct * da;
                load[1] += pk * st * da;
                if pk > 0.0 {
                    wet += da;
                }
            }
        }
        let scale = 2.0 / (4.0 * ld);
        Ok(SqueezeFilmSolution {
            load: [load[0] * scale, load[1] * scale],
            pressure: p,
            theta: grid.theta,
            xi: grid.xi,
            pressurised_fraction: wet / (TAU * ld),
            passes,
        })
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
            // Symmetric system on the free nodes: active rows and columns become identity rows
            // and zero columns (P_A = 0), keeping the pattern for the cached symbolic factor.
            let mut trip = Vec::with_capacity(nn * 5);
            let mut b = Mat::<f64>::zeros(nn, 1);
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
                if !active[k] {
                    b[(k, 0)] = rhs[k];
                }
            }
            let factor = |reason: String| SqueezeFilmError::Factorization {
                pass: passes,
                reason,
            };
            let mat = SparseColMat::<usize, f64>::try_new_from_triplets(nn, nn, &trip)
                .map_err(|e| factor(format!("{e:?}")))?;
            let lu = Llt::try_new_with_symbolic(self.symbolic.clone(), mat.as_ref(), Side::Lower)
                .map_err(|e| factor(format!("{e:?}")))?;
            let x = lu.solve(&b);
            for k in 0..nn {
                p[k] = if active[k] { 0.0 } else { x[(k, 0)] };
                if !p[k].is_finite() {
                    return Err(SqueezeFilmError::NonFinitePressure { i: k / m, j: k % m });
                }
            }
            // Re-sort: free nodes with P < 0 become active; active nodes whose multiplier
            // λ = (A P − f) is negative (the film there wants positive pressure) become free.
            let mut changed = 0;
            for k in 0..nn {
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
