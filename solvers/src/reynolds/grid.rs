//! The θ × z grid of the Reynolds solver and the node classes (unknown, end, groove, supply line).
//!
//! ```text
//!   z = +L/2  j = n_z-1   E  E  E  E  E  E  E  E      E: end node, p = p_amb (Dirichlet)
//!             j = n_z-2   ·  ·  G  G  ·  ·  ·  ·      G: groove node, p = p_feed or a cavitated
//!               ...       ·  ·  G  G  ·  ·  ·  ·         state of given film fraction (cut-off)
//!             j = 1       ·  ·  ·  ·  ·  ·  ·  ·      ·: unknown ψ = φ − 1 (one mass balance)
//!   z = −L/2  j = 0       E  E  E  E  E  E  E  E
//!                        i=0 1  2  …            n_θ-1   (periodic: i = n_θ-1 neighbours i = 0)
//! ```
//!
//! The z-direction is **cell-centred**: the n_z − 2 interior rows are the centres of equal cells
//! of width Δz = L/(n_z − 2) that tile the whole length, z_j = −L/2 + (j − ½) Δz, and the two end
//! rows j = 0, n_z − 1 are the boundary points z = ∓L/2 themselves, half a cell from the first
//! interior row. So Couette transport and supply cover the full length L, and the side leakage
//! is the flux through the bearing edge itself (a node-centred grid whose end nodes own half
//! cells would lose the Couette transport of those half cells and under-predict the side flow
//! at first order). θ is node-centred and periodic: θ_i = θ_0 + i Δθ, Δθ = 2π/n_θ.
//!
//! ```text
//!   z:  −L/2    z_1       z_2     …     z_{n_z−2}     +L/2
//!        E |----·----|----·----|  …  |----·----| E
//!          <Δz/2>  <-- Δz -->                 <Δz/2>
//! ```
//!
//! Storage is θ-major: `k = i · n_z + j`, so the unknowns of one axial line are contiguous and the
//! circumferential lines are interleaved with stride n_z — exactly the layout of
//! [`crate::tridiagonal::cyclic_thomas_solve_interleaved`] (line j, unknown i at `i · n_z + j`).
//!
//! θ_0 is 0 unless the supply is the full-length axial line on the h_max line
//! ([`super::SupplyModel::AxialLineAtMaxGap`]): then the grid is turned so that node column 0
//! lies exactly on that line (no snapping error in the attitude angle).

use std::f64::consts::PI;

use super::{Groove, ReynoldsError, ReynoldsParams, SupplyModel};

/// What a node is in the discrete system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NodeKind {
    /// An unknown with its own mass balance.
    Unknown,
    /// Bearing end (z = ±L/2): ambient pressure.
    End,
    /// Inside groove number `.0` (fixed in the bearing frame).
    Groove(u16),
    /// On the full-length axial supply line at ambient pressure.
    SupplyLine,
}

/// Grid geometry and node classes for one angular offset θ_0.
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    pub n_theta: usize,
    pub n_z: usize,
    pub d_theta: f64,
    pub dz: f64,
    pub radius: f64,
    pub length: f64,
    pub theta0: f64,
    pub kind: Vec<NodeKind>,
    /// Weight of node (i, j) in area integrals (midpoint rule): R Δθ Δz inside, 0 on the end rows.
    pub area_weight: Vec<f64>,
    /// 1 on the unknown nodes, 0 on the Dirichlet ones; and, per unknown node, 1 where its
    /// west / east / south / north neighbour is a Dirichlet node (else 0): the weights of the
    /// flux scale in [`super::discretization::Stencil::residual`], set once the node kinds are.
    pub unknown_weight: Vec<f64>,
    pub dirichlet_neighbour: [Vec<f64>; 4],
}

impl Grid {
    pub fn new(params: &ReynoldsParams, theta0: f64) -> Result<Self, ReynoldsError> {
        let n_theta = params.grid.n_theta;
        let n_z = params.grid.n_z;
        if n_theta < 8 || n_z < 3 {
            return Err(ReynoldsError::InvalidParameter {
                name: "grid",
                value: (n_theta * 1000 + n_z) as f64,
                reason: "needs n_theta ≥ 8 and n_z ≥ 3 (value shown as n_theta·1000 + n_z)",
            });
        }
        let d_theta = 2.0 * PI / n_theta as f64;
        let dz = params.length / (n_z - 2) as f64;
        let mut kind = vec![NodeKind::Unknown; n_theta * n_z];
        let mut area_weight = vec![params.radius * d_theta * dz; n_theta * n_z];
        for i in 0..n_theta {
            for j in [0, n_z - 1] {
                kind[i * n_z + j] = NodeKind::End;
                area_weight[i * n_z + j] = 0.0;
            }
        }
        let mut grid = Self {
            n_theta,
            n_z,
            d_theta,
            dz,
            radius: params.radius,
            length: params.length,
            theta0,
            kind,
            area_weight,
            unknown_weight: Vec::new(),
            dirichlet_neighbour: Default::default(),
        };
        for (g, groove) in params.grooves.iter().enumerate() {
            grid.mark_groove(g, groove);
        }
        if params.supply == SupplyModel::AxialLineAtMaxGap {
            for j in 1..n_z - 1 {
                grid.kind[j] = NodeKind::SupplyLine;
            }
        }
        grid.set_residual_weights();
        Ok(grid)
    }

    /// [`Grid::unknown_weight`] and [`Grid::dirichlet_neighbour`] from the node kinds.
    fn set_residual_weights(&mut self) {
        let (nt, nz) = (self.n_theta, self.n_z);
        let dirichlet = |k: usize| self.kind[k] != NodeKind::Unknown;
        let mut unknown = vec![0.0; nt * nz];
        let mut nbr: [Vec<f64>; 4] = std::array::from_fn(|_| vec![0.0; nt * nz]);
        for i in 0..nt {
            let iw = if i == 0 { nt - 1 } else { i - 1 };
            let ie = if i + 1 == nt { 0 } else { i + 1 };
            for j in 0..nz {
                let k = i * nz + j;
                if dirichlet(k) {
                    continue;
                }
                unknown[k] = 1.0;
                // Unknown nodes are interior in z (the end rows are Dirichlet), so j ± 1 exist.
                let flags = [
                    dirichlet(iw * nz + j),
                    dirichlet(ie * nz + j),
                    dirichlet(k - 1),
                    dirichlet(k + 1),
                ];
                for (w, f) in nbr.iter_mut().zip(flags) {
                    w[k] = if f { 1.0 } else { 0.0 };
                }
            }
        }
        self.unknown_weight = unknown;
        self.dirichlet_neighbour = nbr;
    }

    #[inline]
    pub fn len(&self) -> usize {
        self.n_theta * self.n_z
    }

    #[inline]
    pub fn theta(&self, i: usize) -> f64 {
        self.theta0 + i as f64 * self.d_theta
    }

    #[inline]
    pub fn z(&self, j: usize) -> f64 {
        if j == 0 {
            -0.5 * self.length
        } else if j + 1 == self.n_z {
            0.5 * self.length
        } else {
            -0.5 * self.length + (j as f64 - 0.5) * self.dz
        }
    }

    /// Axial width of the cells of row j (0 on the end rows, which are boundary points).
    #[inline]
    pub fn row_width(&self, j: usize) -> f64 {
        if j == 0 || j + 1 == self.n_z {
            0.0
        } else {
            self.dz
        }
    }

    /// Distance from row j to row j + 1 (Δz/2 next to an end).
    #[inline]
    pub fn z_gap(&self, j: usize) -> f64 {
        if j == 0 || j + 2 == self.n_z {
            0.5 * self.dz
        } else {
            self.dz
        }
    }

    /// Marks the interior nodes inside the groove's rectangle; if the rectangle catches no node
    /// (narrower than the grid), the node nearest to its centre.
    fn mark_groove(&mut self, g: usize, groove: &Groove) {
        let mut any = false;
        let tol = 1e-9;
        let mut best = (f64::INFINITY, 0usize);
        for i in 0..self.n_theta {
            let dth = wrap_angle(self.theta(i) - groove.center_angle).abs();
            for j in 1..self.n_z - 1 {
                let dzz = (self.z(j) - groove.center_z).abs();
                let dist = (dth * self.radius).hypot(dzz);
                if dist < best.0 {
                    best = (dist, i * self.n_z + j);
                }
                if dth <= 0.5 * groove.angular_width * (1.0 + tol) + tol
                    && dzz <= 0.5 * groove.axial_width * (1.0 + tol) + tol * self.length
                {
                    self.kind[i * self.n_z + j] = NodeKind::Groove(g as u16);
                    any = true;
                }
            }
        }
        if !any {
            self.kind[best.1] = NodeKind::Groove(g as u16);
        }
    }
}

/// Wraps an angle into (−π, π].
pub(crate) fn wrap_angle(a: f64) -> f64 {
    let mut x = a.rem_euclid(2.0 * PI);
    if x > PI {
        x -= 2.0 * PI;
    }
    x
}
