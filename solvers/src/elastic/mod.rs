//! Plane-strain linear elasticity of the shaft and the housing of a journal bearing, loaded by
//! the film pressure, and the compliance that turns a film pressure into a gap change.
//!
//! # What is solved
//!
//! ```text
//!   ∇·σ = 0,  σ = D ε(u)  (plane strain, docs: element),    u = 0 on supported components,
//!   σ n = −p n  on the film surface (the film pushes the surface away from itself),
//! ```
//!
//! by the standard displacement finite-element method with bilinear quadrilaterals
//! (\[Zienkiewicz2005\]): K u = f, K assembled from 2 × 2 Gauss element stiffnesses
//! (`element`), supports applied in each supported node's polar frame (the node's two
//! displacement unknowns rotated to (u_r, u_θ), the held ones removed), and the symmetric
//! positive definite reduced K factorized once by faer's sparse Cholesky (LLᵀ). The film load
//! is the consistent nodal load of a pressure linear between the surface nodes on straight
//! edges. Stresses are recovered at the Gauss points, extrapolated to the nodes and averaged
//! over the elements that share a node; σ_zz = ν(σ_xx + σ_yy) (plane strain).
//!
//! The coupling to the film (\[Benasciutti2012\] Fig. 4 and its text): the gap change of film-surface
//! node k is g_k = u_r,housing(θ_k) − u_r,shaft(θ_k) (radial displacements, outward positive:
//! the paper's g(θ) with the sign that opens the gap under pressure), added to the rigid film
//! h = c − e cos θ. [`Compliance`] is the matrix g = C p (film-surface pressures → gap
//! changes), computed once from the factorized stiffnesses of both bodies; `coupling` solves
//! the coupled film–structure steady-load problem with it, and [`ElasticFilm`] puts the same
//! compliance into the inverse solver's time steps (quasi-static, `dynamic`).
//!
//! Checked in the tests here against the patch test (any linear displacement field exactly on
//! a distorted mesh) and Lamé's thick cylinder (\[TimoshenkoGoodier1970\]) with its measured
//! convergence order, and the compliance against Maxwell–Betti reciprocity.

// Assembly indexes element matrices and nodal arrays by the same local numbers.
#![allow(clippy::needless_range_loop)]

mod coupling;
mod dynamic;
mod element;
mod mesh;
mod michell;

use faer::sparse::linalg::solvers::Llt;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use thiserror::Error;

pub use coupling::{
    ElasticBearing, ElasticInfo, ElasticParams, ElasticSolution, solve_steady_load,
};
pub use dynamic::{ElasticFilm, ElasticFilmState};
pub use element::Material;
pub use mesh::{FluidSide, HousingShape, Mesh, Support, square_layers};
pub use michell::{MichellAnnulus, fourier_of_nodal};

/// Why an elastic model failed; variants carry the numbers.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ElasticError {
    #[error("invalid parameter {name} = {value:e}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    #[error("element {element} is inverted or degenerate (det J ≤ 0 at a Gauss point)")]
    BadElement { element: usize },
    #[error(
        "stiffness factorization failed ({detail}): the supports do not remove every rigid-body motion, or the mesh is disconnected"
    )]
    Factorization { detail: String },
    #[error("{what}: {got} values given for {expected} nodes")]
    Length {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    #[error("{what} not finite at node {node}")]
    NonFinite { what: &'static str, node: usize },
    /// The film solve inside the coupled iteration failed.
    #[error(transparent)]
    Film(#[from] crate::reynolds::ReynoldsError),
    #[error(
        "deformable bearing not converged after {iterations} iterations: gap residual \
         {gap_residual:e} m > tolerance {tolerance:e} m"
    )]
    NotConverged {
        iterations: usize,
        gap_residual: f64,
        tolerance: f64,
    },
    #[error("the two bodies' film surfaces differ: {shaft} shaft nodes, {housing} housing nodes")]
    SurfaceMismatch { shaft: usize, housing: usize },
}

/// Stress at a node, Pa: in-plane Cartesian components and σ_zz (plane strain).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stress {
    pub xx: f64,
    pub yy: f64,
    pub xy: f64,
    pub zz: f64,
}

impl Stress {
    /// (σ_r, σ_θ, τ_rθ) in the polar frame at angle θ.
    pub fn polar(&self, theta: f64) -> [f64; 3] {
        let (s, c) = theta.sin_cos();
        [
            self.xx * c * c + self.yy * s * s + 2.0 * self.xy * s * c,
            self.xx * s * s + self.yy * c * c - 2.0 * self.xy * s * c,
            (self.yy - self.xx) * s * c + self.xy * (c * c - s * s),
        ]
    }

    /// von Mises equivalent stress (all four components).
    pub fn von_mises(&self) -> f64 {
        let (a, b, c) = (self.xx - self.yy, self.yy - self.zz, self.zz - self.xx);
        (0.5 * (a * a + b * b + c * c) + 3.0 * self.xy * self.xy).sqrt()
    }
}

/// One body: mesh, material and its factorized stiffness.
#[derive(Debug)]
pub struct ElasticBody {
    mesh: Mesh,
    material: Material,
    /// Per node: the polar angle when the node's unknowns are (u_r, u_θ), else None (u_x, u_y).
    frame: Vec<Option<f64>>,
    /// Reduced unknown of (node, component), None when held.
    dof: Vec<Option<usize>>,
    n_free: usize,
    llt: Llt<usize, f64>,
}

impl ElasticBody {
    /// Assembles and factorizes the stiffness.
    pub fn new(mesh: Mesh, material: Material) -> Result<Self, ElasticError> {
        let (e, nu) = (material.youngs_modulus, material.poisson_ratio);
        if !(e > 0.0 && e.is_finite()) {
            return Err(ElasticError::InvalidParameter {
                name: "youngs_modulus",
                value: e,
                reason: "must be positive and finite",
            });
        }
        if !((0.0..0.5).contains(&nu)) {
            return Err(ElasticError::InvalidParameter {
                name: "poisson_ratio",
                value: nu,
                reason: "must lie in [0, 0.5)",
            });
        }
        let (frame, dof, n_free) = Self::supported_unknowns(&mesh);
        let trip = Self::stiffness_triplets(&mesh, &material, &frame, &dof)?;
        let mat = SparseColMat::<usize, f64>::try_new_from_triplets(n_free, n_free, &trip)
            .map_err(|e| ElasticError::Factorization {
                detail: format!("assembly: {e:?}"),
            })?;
        let llt = mat
            .sp_cholesky(Side::Lower)
            .map_err(|e| ElasticError::Factorization {
                detail: format!("{e:?}"),
            })?;
        Ok(Self {
            mesh,
            material,
            frame,
            dof,
            n_free,
            llt,
        })
    }

    /// The supports applied (module docs): per node the polar angle of a node with a radial or
    /// tangential support (its unknowns are (u_r, u_θ)), the reduced unknown of each (node,
    /// component) that is not held, and their number.
    fn supported_unknowns(mesh: &Mesh) -> (Vec<Option<f64>>, Vec<Option<usize>>, usize) {
        let n_nodes = mesh.nodes.len();
        let mut frame = vec![None; n_nodes];
        let mut held = vec![[false; 2]; n_nodes];
        for &(node, support) in &mesh.supports {
            let [x, y] = mesh.nodes[node];
            match support {
                Support::Radial => {
                    frame[node] = Some(y.atan2(x));
                    held[node][0] = true;
                }
                Support::Tangential => {
                    frame[node] = Some(y.atan2(x));
                    held[node][1] = true;
                }
                Support::Fixed => held[node] = [true, true],
            }
        }
        let mut dof = vec![None; 2 * n_nodes];
        let mut n_free = 0;
        for node in 0..n_nodes {
            for c in 0..2 {
                if !held[node][c] {
                    dof[2 * node + c] = Some(n_free);
                    n_free += 1;
                }
            }
        }
        (frame, dof, n_free)
    }

    /// The lower triangle of the reduced stiffness K as triplets: each element's 2 × 2 Gauss
    /// stiffness (`element`), rotated into its nodes' polar frames, the held rows and columns
    /// left out.
    fn stiffness_triplets(
        mesh: &Mesh,
        material: &Material,
        frame: &[Option<f64>],
        dof: &[Option<usize>],
    ) -> Result<Vec<Triplet<usize, usize, f64>>, ElasticError> {
        let d = material.plane_strain();
        let mut trip = Vec::with_capacity(mesh.elements.len() * 36);
        for (ie, el) in mesh.elements.iter().enumerate() {
            let xy = el.map(|n| mesh.nodes[n]);
            let mut k =
                element::stiffness(&xy, &d).ok_or(ElasticError::BadElement { element: ie })?;
            // Rotate the rows and columns of nodes in a polar frame: K' = Tᵀ K T.
            for (a, &node) in el.iter().enumerate() {
                if let Some(th) = frame[node] {
                    let (s, c) = th.sin_cos();
                    for r in 0..8 {
                        let (kx, ky) = (k[r][2 * a], k[r][2 * a + 1]);
                        k[r][2 * a] = c * kx + s * ky;
                        k[r][2 * a + 1] = -s * kx + c * ky;
                    }
                    for col in 0..8 {
                        let (kx, ky) = (k[2 * a][col], k[2 * a + 1][col]);
                        k[2 * a][col] = c * kx + s * ky;
                        k[2 * a + 1][col] = -s * kx + c * ky;
                    }
                }
            }
            for r in 0..8 {
                let Some(gr) = dof[2 * el[r / 2] + r % 2] else {
                    continue;
                };
                for c in 0..8 {
                    if let Some(gc) = dof[2 * el[c / 2] + c % 2]
                        && gr >= gc
                    {
                        trip.push(Triplet::new(gr, gc, k[r][c]));
                    }
                }
            }
        }
        Ok(trip)
    }

    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    pub fn material(&self) -> Material {
        self.material
    }

    /// Number of unknowns after the supports.
    pub fn unknowns(&self) -> usize {
        self.n_free
    }

    /// Reduced right-hand side of nodal forces (x, y).
    fn reduce(&self, forces: &[[f64; 2]], out: &mut [f64]) {
        for (node, f) in forces.iter().enumerate() {
            let local = match self.frame[node] {
                Some(th) => {
                    let (s, c) = th.sin_cos();
                    [c * f[0] + s * f[1], -s * f[0] + c * f[1]]
                }
                None => *f,
            };
            for comp in 0..2 {
                if let Some(g) = self.dof[2 * node + comp] {
                    out[g] = local[comp];
                }
            }
        }
    }

    /// Nodal displacements (x, y) from a reduced solution.
    fn expand(&self, x: impl Fn(usize) -> f64) -> Vec<[f64; 2]> {
        (0..self.mesh.nodes.len())
            .map(|node| {
                let l: [f64; 2] = std::array::from_fn(|c| self.dof[2 * node + c].map_or(0.0, &x));
                match self.frame[node] {
                    Some(th) => {
                        let (s, c) = th.sin_cos();
                        [c * l[0] - s * l[1], s * l[0] + c * l[1]]
                    }
                    None => l,
                }
            })
            .collect()
    }

    /// Displacements (x, y), m, of every node under nodal forces (x, y), N per metre of
    /// length (a support's reaction replaces the force given at a held component).
    pub fn solve(&self, forces: &[[f64; 2]]) -> Result<Vec<[f64; 2]>, ElasticError> {
        if forces.len() != self.mesh.nodes.len() {
            return Err(ElasticError::Length {
                what: "nodal forces",
                expected: self.mesh.nodes.len(),
                got: forces.len(),
            });
        }
        let mut rhs = Mat::<f64>::zeros(self.n_free, 1);
        let mut b = vec![0.0; self.n_free];
        self.reduce(forces, &mut b);
        for (i, v) in b.iter().enumerate() {
            rhs[(i, 0)] = *v;
        }
        let x = faer::linalg::solvers::Solve::solve(&self.llt, &rhs);
        let u = self.expand(|i| x[(i, 0)]);
        if let Some(node) = u
            .iter()
            .position(|d| !(d[0].is_finite() && d[1].is_finite()))
        {
            return Err(ElasticError::NonFinite {
                what: "displacement",
                node,
            });
        }
        Ok(u)
    }

    /// Consistent nodal forces of the film pressure `pressure[k]` (Pa, gauge) at the surface
    /// nodes, linear along each straight surface edge: edge (a, b) of length L_e gives
    /// f_a = L_e (2p_a + p_b)/6 · d, f_b = L_e (p_a + 2p_b)/6 · d, d the unit normal pointing
    /// from the film into the body. (The resultant moment about the centre is zero: each
    /// edge contributes L_e (p_a − p_b)/6 · (x_a × d), the same lever for every edge of the
    /// regular polygon, and Σ (p_a − p_b) = 0 around the ring.)
    pub fn surface_load(&self, pressure: &[f64]) -> Result<Vec<[f64; 2]>, ElasticError> {
        let s = &self.mesh.surface;
        if pressure.len() != s.len() {
            return Err(ElasticError::Length {
                what: "surface pressures",
                expected: s.len(),
                got: pressure.len(),
            });
        }
        let mut f = vec![[0.0; 2]; self.mesh.nodes.len()];
        let n = s.len();
        for k in 0..n {
            let (a, b) = (s[k], s[(k + 1) % n]);
            let (xa, xb) = (self.mesh.nodes[a], self.mesh.nodes[b]);
            let t = [xb[0] - xa[0], xb[1] - xa[1]];
            let len = t[0].hypot(t[1]);
            // Outward from the centre at the edge's midpoint: (t_y, −t_x)/L for an
            // anticlockwise ring.
            let out = [t[1] / len, -t[0] / len];
            let d = match self.mesh.fluid {
                FluidSide::Outside => [-out[0], -out[1]],
                FluidSide::Inside => out,
            };
            let (pa, pb) = (pressure[k], pressure[(k + 1) % n]);
            for c in 0..2 {
                f[a][c] += len * (2.0 * pa + pb) / 6.0 * d[c];
                f[b][c] += len * (pa + 2.0 * pb) / 6.0 * d[c];
            }
        }
        Ok(f)
    }

    /// Radial displacement (outward positive) of the surface nodes.
    pub fn surface_radial(&self, u: &[[f64; 2]]) -> Vec<f64> {
        self.mesh
            .surface
            .iter()
            .map(|&node| {
                let [x, y] = self.mesh.nodes[node];
                let r = x.hypot(y);
                (u[node][0] * x + u[node][1] * y) / r
            })
            .collect()
    }

    /// Nodal stresses: Gauss-point stresses extrapolated to each element's corners and
    /// averaged over the elements sharing the node.
    pub fn stresses(&self, u: &[[f64; 2]]) -> Vec<Stress> {
        let d = self.material.plane_strain();
        let nu = self.material.poisson_ratio;
        let n = self.mesh.nodes.len();
        let mut sum = vec![[0.0; 3]; n];
        let mut count = vec![0usize; n];
        for el in &self.mesh.elements {
            let xy = el.map(|node| self.mesh.nodes[node]);
            let ue: [f64; 8] = std::array::from_fn(|c| u[el[c / 2]][c % 2]);
            let g = element::gauss_stresses(&xy, &d, &ue);
            for comp in 0..3 {
                let nodal = element::extrapolate_to_nodes(g.map(|s| s[comp]));
                for (a, &node) in el.iter().enumerate() {
                    sum[node][comp] += nodal[a];
                }
            }
            for &node in el {
                count[node] += 1;
            }
        }
        sum.iter()
            .zip(&count)
            .map(|(s, &c)| {
                let m = 1.0 / c.max(1) as f64;
                let (xx, yy, xy) = (s[0] * m, s[1] * m, s[2] * m);
                Stress {
                    xx,
                    yy,
                    xy,
                    zz: nu * (xx + yy),
                }
            })
            .collect()
    }

    /// Radial surface displacements for each load of `loads` (one full nodal force vector
    /// each), solved in blocks of 64 right-hand sides (bounded memory on fine meshes).
    fn surface_radial_many(&self, loads: &[Vec<[f64; 2]>]) -> Vec<Vec<f64>> {
        let mut out = Vec::with_capacity(loads.len());
        let mut b = vec![0.0; self.n_free];
        for block in loads.chunks(64) {
            let mut rhs = Mat::<f64>::zeros(self.n_free, block.len());
            for (j, f) in block.iter().enumerate() {
                b.iter_mut().for_each(|v| *v = 0.0);
                self.reduce(f, &mut b);
                for (i, v) in b.iter().enumerate() {
                    rhs[(i, j)] = *v;
                }
            }
            let x = faer::linalg::solvers::Solve::solve(&self.llt, &rhs);
            out.extend((0..block.len()).map(|j| self.surface_radial(&self.expand(|i| x[(i, j)]))));
        }
        out
    }

    /// Surface compliance: column j is the radial surface displacement (outward positive)
    /// for a unit pressure at surface node j alone (the hat function of the linear pressure
    /// interpolation); `(n × n)`, entry `[i][j]`.
    pub fn pressure_compliance(&self) -> Result<Vec<Vec<f64>>, ElasticError> {
        let n = self.mesh.surface.len();
        let loads = (0..n)
            .map(|j| {
                let mut p = vec![0.0; n];
                p[j] = 1.0;
                self.surface_load(&p)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let cols = self.surface_radial_many(&loads);
        transpose_checked(cols)
    }

    /// Point-force compliance: entry `[i][j]` is the radial displacement of surface node i
    /// under a unit outward radial force (N/m) at surface node j. Maxwell–Betti: symmetric.
    pub fn radial_force_compliance(&self) -> Result<Vec<Vec<f64>>, ElasticError> {
        let n = self.mesh.surface.len();
        let loads: Vec<Vec<[f64; 2]>> = (0..n)
            .map(|j| {
                let mut f = vec![[0.0; 2]; self.mesh.nodes.len()];
                let node = self.mesh.surface[j];
                let [x, y] = self.mesh.nodes[node];
                let r = x.hypot(y);
                f[node] = [x / r, y / r];
                f
            })
            .collect();
        transpose_checked(self.surface_radial_many(&loads))
    }
}

/// Columns → rows `[i][j]`, refusing non-finite entries.
fn transpose_checked(cols: Vec<Vec<f64>>) -> Result<Vec<Vec<f64>>, ElasticError> {
    let n = cols.len();
    let m = cols.first().map_or(0, Vec::len);
    let mut rows = vec![vec![0.0; n]; m];
    for (j, col) in cols.iter().enumerate() {
        for (i, &v) in col.iter().enumerate() {
            if !v.is_finite() {
                return Err(ElasticError::NonFinite {
                    what: "compliance",
                    node: i,
                });
            }
            rows[i][j] = v;
        }
    }
    Ok(rows)
}

/// The film-gap compliance of a shaft and a housing whose film surfaces share the nodes
/// θ_k = 2πk/n: gap change g = C p, C = C_housing − C_shaft (radial compliances, outward
/// positive), m per Pa.
#[derive(Debug, Clone, PartialEq)]
pub struct Compliance {
    /// `[i][j]`: gap change at θ_i per unit pressure at θ_j (hat function).
    pub matrix: Vec<Vec<f64>>,
}

impl Compliance {
    pub fn new(shaft: &ElasticBody, housing: &ElasticBody) -> Result<Self, ElasticError> {
        let (ns, nh) = (shaft.mesh.surface.len(), housing.mesh.surface.len());
        if ns != nh {
            return Err(ElasticError::SurfaceMismatch {
                shaft: ns,
                housing: nh,
            });
        }
        let cs = shaft.pressure_compliance()?;
        let ch = housing.pressure_compliance()?;
        let matrix = ch
            .iter()
            .zip(&cs)
            .map(|(h, s)| h.iter().zip(s).map(|(a, b)| a - b).collect())
            .collect();
        Ok(Self { matrix })
    }

    /// Number of surface nodes.
    pub fn len(&self) -> usize {
        self.matrix.len()
    }

    pub fn is_empty(&self) -> bool {
        self.matrix.is_empty()
    }

    /// g = C p.
    pub fn gap(&self, pressure: &[f64]) -> Vec<f64> {
        self.matrix
            .iter()
            .map(|row| row.iter().zip(pressure).map(|(a, b)| a * b).sum())
            .collect()
    }
}

#[cfg(test)]
mod tests;
