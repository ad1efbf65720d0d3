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
//!
//! # Groove edges
//!
//! A groove is a rectangle θ_g ± w/2, z_g ± b/2 fixed in the bearing frame, whose edges fall
//! anywhere between the nodes. Its feed pressure (or its cut-off film fraction) is imposed on
//! the nodes within half a spacing of the rectangle (Dirichlet nodes G), so every unknown node P
//! lies more than half a spacing outside it. On a face between P and G the pressure flux is the
//! one across the distance d from P to the groove's *true* edge, not to G, over the share s of
//! the face that borders the groove (the overlap of the face's cell with the groove's extent
//! along the edge) — the Shortley–Weller treatment of a Dirichlet boundary that lies between
//! nodes \[ShortleyWeller1938\]:
//!
//! ```text
//!      P ·-----------|-----· G        flux P→G = s k (p_P − p_G) / d      (k = h³/(12 μ) per width)
//!        <---- d ---->  edge             face factor s Δ / d,  Δ/2 < d ≤ 3Δ/2,  0 < s ≤ 1
//!        <-------- Δ -------->
//! ```
//!
//! The factor multiplies the face's pressure coefficient ([`Grid::theta_face_factor`],
//! [`Grid::z_face_factor`]), so the stencil, the face fluxes (supply and side leakage), the
//! force Jacobian and the dissipation all carry it. A pressure that is linear between the edge
//! and the next node is reproduced exactly: a groove round the whole circumference at ε = 0
//! gives the closed-form side leakage 2 · 2πR c³ p_feed / (12 μ l) (l the land width) to
//! round-off on every grid (test `circumferential_groove_leakage_is_exact_on_every_grid`).
//! The first generation's rule (the nodes inside the rectangle, the groove's pressure at the
//! outermost of them) shrank the groove by up to a spacing on each side, by an amount that
//! depends on where its edges fall: that leakage was −6.4 %, −0.18 % and −5.0 % off on 60 × 15,
//! 120 × 31 and 120 × 32, and the leakage of a 52° × 3.8 mm feed groove at ε = 0 moved by 4.3 %
//! on 120 × 31 when the groove was turned by fractions of a cell (now 1.4 %), 2.1 % on 240 × 61
//! (now 0.46 %). The Couette transport out of a groove node still carries the node's film
//! fraction across the whole face of its cell (the groove's oil, φ = 1 — exact where the film
//! beside the groove is full, a first-order error at the groove's corners where it is not).
//!
//! # Mirror symmetry
//!
//! The film thickness and the viscosity depend on θ only (aligned journal; the elastic gap
//! change and the thermal viscosity are functions of θ), both ends are at the one ambient
//! pressure and the supply line runs the whole length; so when every groove is centred on the
//! mid-plane ([`mirror_symmetric`]) the discrete problem maps onto itself under z → −z, and so
//! does its (unique: M-matrix, `discretization` module docs) solution. The solver then works
//! on the half z ≤ 0 ([`Grid::new_half`]) and mirrors the answer — the same discrete film on
//! 17 rows instead of 31 (the default grid), in about two thirds of the time (docs/performance.md,
//! "Fifteenth look"):
//!
//! ```text
//!   whole, n_z odd (31)          half (17 rows)              whole, n_z even (32)     half (17)
//!   j = 30  E  (z = +L/2)                                    j = 31  E
//!   ...                                                      ...
//!   j = 16  ·                    j = 16  X closed row        j = 16  ·                j = 16 X
//!   j = 15  ·  z = 0 (mid row)   j = 15  · half cell Δz/2    ----------- z = 0 (a face) ------
//!   j = 14  ·                    j = 14  ·                   j = 15  ·                j = 15 ·
//!   ...                          ...                         ...                      ...
//!   j = 0   E  (z = −L/2)        j = 0   E                   j = 0   E                j = 0  E
//! ```
//!
//! The mid-plane is a line of symmetry: no flux crosses it. With n_z odd the mid row's cell
//! straddles it; the half grid owns the lower half of that cell (width Δz/2 in its θ-fluxes,
//! its time term and its area weight, [`Grid::row_width`], [`Grid::cell_area`]): its mass
//! balance is half the whole cell's, whose north and south z-fluxes are equal by symmetry.
//! With n_z even the mid-plane is the face between two rows and the half grid ends at it.
//! Either way the last row X is a closed Dirichlet row whose z-face carries no flux (its face
//! factor is 0), so every loop over the grid stays as it is, at one row's extra cost. The
//! integrals of the half (force, flows, content, torques, power) are doubled, the side leakage
//! through z = +L/2 is that through z = −L/2, and fields and states are mirrored to the whole
//! grid on the way out ([`Grid::unfold`]) and folded on the way in ([`Grid::fold`]; the net
//! outflow of a node, a quantity of its cell, with the mid row's half:
//! [`Grid::fold_per_cell`]). Test: `the_half_grid_of_a_symmetric_bearing_is_the_whole_grids_film`
//! (every output and state of steady films and of five steps of each time scheme, both
//! parities, equal to the whole grid's to < 1e-9 of their scale).

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
    /// Per node k, the pressure-flux factor of its east θ-face and of its north z-face: the
    /// node spacing over the distance across which the face's pressure difference acts — 1,
    /// except on a face between an unknown node and a groove node, where the groove's
    /// pressure holds at the groove's true edge, not at the groove node (module docs,
    /// "Groove edges").
    pub theta_face_factor: Vec<f64>,
    pub z_face_factor: Vec<f64>,
    /// The mid-plane reduction (module docs, "Mirror symmetry"): None for the whole length.
    pub mirror: Option<Mirror>,
    /// Per column i: cos and sin of θ_i and of its east face θ_i + Δθ/2, evaluated once for
    /// the grid (the film thickness, its ε-derivative and the force sums of every solve read
    /// them; as `sin_cos` per solve they were 2 % of the inverse cycle's time).
    pub column_trig: Vec<ColumnTrig>,
    /// The faces between two flow regions ([`FlowRegion`]) in the order of the grid's face loop
    /// (column i, row j: the east θ-face of node k, then its north z-face), without the θ-faces
    /// between two end nodes: the only faces whose flux reaches the side leakage or a supply
    /// flow. Set once the node kinds are, so that a solve's boundary flows visit these few
    /// hundred faces instead of classifying every node (2.5 % of the inverse cycle's time).
    pub region_faces: Vec<RegionFace>,
}

/// Where a node's flux is booked in the boundary flows: the unknowns, the low or the high end
/// (z = −L/2 / +L/2; on a half grid the closed mid-plane row counts as the high end, its face
/// carries no flux), a groove, the supply line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FlowRegion {
    Unknown,
    EndLow,
    EndHigh,
    Groove(u16),
    Line,
}

/// A face between two flow regions, [`Grid::region_faces`]: the flux of node k's east θ-face
/// (`z_face` false) or north z-face (true) runs from region `from` to region `to`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RegionFace {
    pub k: usize,
    pub z_face: bool,
    pub from: FlowRegion,
    pub to: FlowRegion,
}

/// cos and sin of a column's angle θ_i and of its east θ-face's, [`Grid::column_trig`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ColumnTrig {
    pub cos: f64,
    pub sin: f64,
    pub cos_face: f64,
    pub sin_face: f64,
}

/// How a half grid ([`Grid::new_half`]) maps onto the whole one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Mirror {
    /// n_z of the whole grid.
    pub full_n_z: usize,
    /// The row on the mid-plane, whose cell the half grid owns half of (odd `full_n_z`); None
    /// when the mid-plane is the face between two rows (even `full_n_z`).
    pub mid_row: Option<usize>,
}

impl Grid {
    pub fn new(params: &ReynoldsParams, theta0: f64) -> Result<Self, ReynoldsError> {
        Self::build(params, theta0, false)
    }

    /// The half grid z ≤ 0 of a bearing that is symmetric about its mid-plane (module docs,
    /// "Mirror symmetry"; [`mirror_symmetric`] says when).
    pub fn new_half(params: &ReynoldsParams, theta0: f64) -> Result<Self, ReynoldsError> {
        Self::build(params, theta0, true)
    }

    fn build(params: &ReynoldsParams, theta0: f64, half: bool) -> Result<Self, ReynoldsError> {
        let n_theta = params.grid.n_theta;
        let full_n_z = params.grid.n_z;
        if n_theta < 8 || full_n_z < 3 {
            return Err(ReynoldsError::InvalidParameter {
                name: "grid",
                value: (n_theta * 1000 + full_n_z) as f64,
                reason: "needs n_theta ≥ 8 and n_z ≥ 3 (value shown as n_theta·1000 + n_z)",
            });
        }
        let d_theta = 2.0 * PI / n_theta as f64;
        let dz = params.length / (full_n_z - 2) as f64;
        // The half grid: the rows of z ≤ 0 (the mid row among them when n_z is odd), then one
        // closed row standing for the mid-plane (module docs, "Mirror symmetry").
        let (n_z, mirror) = if half && full_n_z >= 4 {
            let mid_row = (full_n_z % 2 == 1).then_some((full_n_z - 1) / 2);
            (
                full_n_z / 2 + 1 + usize::from(mid_row.is_some()),
                Some(Mirror { full_n_z, mid_row }),
            )
        } else {
            (full_n_z, None)
        };
        let mut kind = vec![NodeKind::Unknown; n_theta * n_z];
        let mut area_weight = vec![params.radius * d_theta * dz; n_theta * n_z];
        for i in 0..n_theta {
            for j in [0, n_z - 1] {
                kind[i * n_z + j] = NodeKind::End;
                area_weight[i * n_z + j] = 0.0;
            }
            if let Some(Mirror {
                mid_row: Some(c), ..
            }) = mirror
            {
                area_weight[i * n_z + c] *= 0.5;
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
            theta_face_factor: vec![1.0; n_theta * n_z],
            z_face_factor: vec![1.0; n_theta * n_z],
            mirror,
            column_trig: Vec::new(),
            region_faces: Vec::new(),
        };
        grid.column_trig = (0..n_theta)
            .map(|i| {
                let th = grid.theta(i);
                let thf = th + 0.5 * d_theta;
                ColumnTrig {
                    cos: th.cos(),
                    sin: th.sin(),
                    cos_face: thf.cos(),
                    sin_face: thf.sin(),
                }
            })
            .collect();
        for (g, groove) in params.grooves.iter().enumerate() {
            grid.mark_groove(g, groove);
        }
        if params.supply == SupplyModel::AxialLineAtMaxGap {
            for j in 1..n_z - 1 {
                grid.kind[j] = NodeKind::SupplyLine;
            }
        }
        // After the supply line, which holds ambient pressure at its own nodes even where it
        // crosses a groove: only faces between a groove node and an unknown one get a factor.
        grid.set_groove_edge_factors(&params.grooves);
        if grid.mirror.is_some() {
            // No flux through the mid-plane: the closed row's face carries nothing.
            for i in 0..n_theta {
                grid.z_face_factor[i * n_z + n_z - 2] = 0.0;
            }
        }
        grid.set_residual_weights();
        grid.set_region_faces();
        Ok(grid)
    }

    /// The flow region of node k ([`FlowRegion`]).
    pub fn flow_region(&self, k: usize) -> FlowRegion {
        match self.kind[k] {
            NodeKind::Unknown => FlowRegion::Unknown,
            NodeKind::End if k.is_multiple_of(self.n_z) => FlowRegion::EndLow,
            NodeKind::End => FlowRegion::EndHigh,
            NodeKind::Groove(g) => FlowRegion::Groove(g),
            NodeKind::SupplyLine => FlowRegion::Line,
        }
    }

    /// [`Grid::region_faces`] from the node kinds.
    fn set_region_faces(&mut self) {
        let (nt, nz) = (self.n_theta, self.n_z);
        let is_end = |r: FlowRegion| matches!(r, FlowRegion::EndLow | FlowRegion::EndHigh);
        let mut faces = Vec::new();
        for i in 0..nt {
            let ie = (i + 1) % nt;
            for j in 0..nz {
                let k = i * nz + j;
                let (from, east) = (self.flow_region(k), self.flow_region(ie * nz + j));
                // θ-faces between two end nodes belong to no balance.
                if from != east && !(is_end(from) && is_end(east)) {
                    faces.push(RegionFace {
                        k,
                        z_face: false,
                        from,
                        to: east,
                    });
                }
                if j + 1 < nz {
                    let north = self.flow_region(k + 1);
                    if from != north {
                        faces.push(RegionFace {
                            k,
                            z_face: true,
                            from,
                            to: north,
                        });
                    }
                }
            }
        }
        self.region_faces = faces;
    }

    /// A field of the whole grid (`[i · n_z + j]`, `full.len()` = n_θ × full n_z) on this
    /// half grid: rows j ≤ the mid-plane as they are, the closed row from the whole grid's
    /// last row (an end row: its Dirichlet value). Without a mirror a copy.
    pub fn fold<T: Copy>(&self, full: &[T]) -> Vec<T> {
        let Some(m) = self.mirror else {
            return full.to_vec();
        };
        let (nz, fz) = (self.n_z, m.full_n_z);
        let mut out = Vec::with_capacity(self.len());
        for i in 0..self.n_theta {
            out.extend_from_slice(&full[i * fz..i * fz + nz - 1]);
            out.push(full[i * fz + fz - 1]);
        }
        out
    }

    /// A field of this grid on the whole grid: row j of the whole grid is row
    /// min(j, n_z − 1 − j) of the half (its mirror image; the closed row is never read).
    /// Without a mirror a copy.
    pub fn unfold<T: Copy>(&self, half: &[T]) -> Vec<T> {
        let Some(m) = self.mirror else {
            return half.to_vec();
        };
        let (nz, fz) = (self.n_z, m.full_n_z);
        // Rows j ≤ (fz − 1)/2 are the half's rows 0 …, the rows above them its rows back down
        // to 0: a copy and a reversed copy per column (no per-element index arithmetic).
        let lower = fz.div_ceil(2);
        let mut out = Vec::with_capacity(self.n_theta * fz);
        for column in half.chunks_exact(nz) {
            out.extend_from_slice(&column[..lower]);
            out.extend(column[..fz - lower].iter().rev());
        }
        out
    }

    /// [`Self::fold`] for a quantity of a node's cell (a flow), of which the half grid's mid
    /// row owns half.
    pub fn fold_per_cell(&self, full: &[f64]) -> Vec<f64> {
        let mut out = self.fold(full);
        self.scale_mid_row(&mut out, 0.5);
        out
    }

    /// [`Self::unfold`] for a quantity of a node's cell (the inverse of [`Self::fold_per_cell`]).
    pub fn unfold_per_cell(&self, half: &[f64]) -> Vec<f64> {
        let mut h = half.to_vec();
        self.scale_mid_row(&mut h, 2.0);
        self.unfold(&h)
    }

    fn scale_mid_row(&self, v: &mut [f64], factor: f64) {
        if let Some(Mirror {
            mid_row: Some(c), ..
        }) = self.mirror
        {
            for i in 0..self.n_theta {
                v[i * self.n_z + c] *= factor;
            }
        }
    }

    /// The factor from this grid's integrals (force, flows, power, content) to the whole
    /// bearing's: 2 on a half grid, else 1.
    #[inline]
    pub fn mirror_factor(&self) -> f64 {
        if self.mirror.is_some() { 2.0 } else { 1.0 }
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
        if self.mirror.is_some() && j + 1 == self.n_z {
            0.0 // a half grid's closed row stands for the mid-plane
        } else {
            self.whole_z(j)
        }
    }

    /// z of row j of the whole grid (of which a half grid holds the rows z ≤ 0).
    pub fn whole_z(&self, j: usize) -> f64 {
        let n_z = self.mirror.map_or(self.n_z, |m| m.full_n_z);
        if j == 0 {
            -0.5 * self.length
        } else if j + 1 == n_z {
            0.5 * self.length
        } else {
            -0.5 * self.length + (j as f64 - 0.5) * self.dz
        }
    }

    /// Axial width of the cells of row j (0 on the end rows, which are boundary points, and
    /// on a half grid's closed row; Δz/2 on its mid row).
    #[inline]
    pub fn row_width(&self, j: usize) -> f64 {
        if j == 0 || j + 1 == self.n_z {
            0.0
        } else if self.is_mid_row(j) {
            0.5 * self.dz
        } else {
            self.dz
        }
    }

    /// The volume per unit film thickness of a node's cell in row j, R Δθ Δz (half that on a
    /// half grid's mid row): what the time term multiplies h φ by. (The end rows keep R Δθ Δz:
    /// their rows are Dirichlet rows, overwritten.)
    #[inline]
    pub fn cell_area(&self, j: usize) -> f64 {
        let a = self.radius * self.d_theta * self.dz;
        if self.is_mid_row(j) { 0.5 * a } else { a }
    }

    #[inline]
    fn is_mid_row(&self, j: usize) -> bool {
        matches!(self.mirror, Some(Mirror { mid_row: Some(c), .. }) if c == j)
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

    /// Marks the interior nodes within half a node spacing of the groove's rectangle (module
    /// docs, "Groove edges"); if that catches no node (in effect only for a groove centred
    /// beyond the bearing's ends: the rows' cells tile the length, the columns' the circle), the node nearest to
    /// its centre.
    fn mark_groove(&mut self, g: usize, groove: &Groove) {
        let mut any = false;
        let tol = 1e-9;
        let mut best = (f64::INFINITY, 0usize);
        let half_theta = 0.5 * groove.angular_width + 0.5 * self.d_theta * (1.0 - tol);
        let half_z = 0.5 * groove.axial_width + 0.5 * self.dz * (1.0 - tol);
        for i in 0..self.n_theta {
            let dth = wrap_angle(self.theta(i) - groove.center_angle).abs();
            for j in 1..self.n_z - 1 {
                let dzz = (self.z(j) - groove.center_z).abs();
                let dist = (dth * self.radius).hypot(dzz);
                if dist < best.0 {
                    best = (dist, i * self.n_z + j);
                }
                if dth < half_theta && dzz < half_z {
                    self.kind[i * self.n_z + j] = NodeKind::Groove(g as u16);
                    any = true;
                }
            }
        }
        if !any {
            self.kind[best.1] = NodeKind::Groove(g as u16);
        }
    }

    /// [`Grid::theta_face_factor`] and [`Grid::z_face_factor`] on the faces between an unknown
    /// node and a groove node: the spacing over the distance d from the unknown node to the
    /// groove's edge (module docs, "Groove edges"), times the share of the face that borders
    /// the groove. d lies between half and three halves of a spacing by the marking rule of
    /// [`Grid::mark_groove`] (a quarter is the floor for the nearest-node fallback) and the
    /// share in (0, 1], so the factor lies in (0, 2] (at most 4 with the fallback).
    fn set_groove_edge_factors(&mut self, grooves: &[Groove]) {
        let (nt, nz) = (self.n_theta, self.n_z);
        let dx = self.radius * self.d_theta;
        let groove_of = |kind: NodeKind| match kind {
            NodeKind::Groove(g) => Some(&grooves[g as usize]),
            _ => None,
        };
        for i in 0..nt {
            let ie = (i + 1) % nt;
            for j in 1..nz - 1 {
                let k = i * nz + j;
                // East θ-face: (k, ke).
                let ke = ie * nz + j;
                let pair = match (self.kind[k], self.kind[ke]) {
                    (NodeKind::Unknown, other) => groove_of(other).map(|g| (i, g)),
                    (other, NodeKind::Unknown) => groove_of(other).map(|g| (ie, g)),
                    _ => None,
                };
                if let Some((iu, g)) = pair {
                    let dth = wrap_angle(self.theta(iu) - g.center_angle).abs();
                    let d = (self.radius * (dth - 0.5 * g.angular_width)).max(0.25 * dx);
                    // The share of the face's axial width that borders the groove.
                    let share = overlap(self.z(j) - g.center_z, self.dz, g.axial_width);
                    self.theta_face_factor[k] = share * dx / d;
                }
                // North z-face: (k, k + 1), both interior.
                if j + 2 < nz {
                    let pair = match (self.kind[k], self.kind[k + 1]) {
                        (NodeKind::Unknown, other) => groove_of(other).map(|g| (j, g)),
                        (other, NodeKind::Unknown) => groove_of(other).map(|g| (j + 1, g)),
                        _ => None,
                    };
                    if let Some((ju, g)) = pair {
                        let dzz = (self.z(ju) - g.center_z).abs();
                        let d = (dzz - 0.5 * g.axial_width).max(0.25 * self.dz);
                        // The share of the face's circumferential width that borders the
                        // groove (a groove round the whole circumference borders all of it).
                        let share = if g.angular_width >= 2.0 * PI - self.d_theta {
                            1.0
                        } else {
                            let dth = wrap_angle(self.theta(i) - g.center_angle);
                            overlap(dth, self.d_theta, g.angular_width)
                        };
                        self.z_face_factor[k] = share * self.dz / d;
                    }
                }
            }
        }
    }
}

/// The fraction of a cell of width `cell`, centred at `offset` from a groove's centre, that
/// lies within the groove's extent `width` (centred at 0).
fn overlap(offset: f64, cell: f64, width: f64) -> f64 {
    let lo = (offset - 0.5 * cell).max(-0.5 * width);
    let hi = (offset + 0.5 * cell).min(0.5 * width);
    ((hi - lo) / cell).clamp(0.0, 1.0)
}

/// Whether the bearing is symmetric about its mid-plane z = 0, so that the film of a time
/// step or a steady solve is too (module docs, "Mirror symmetry"): the film thickness and the
/// viscosity depend on θ only (aligned journal, [`super::FilmDeformation`] is a function of θ),
/// both ends are at the one ambient pressure, the supply line runs the whole length, and every
/// groove is centred on the mid-plane (exactly: `center_z == 0`).
pub(crate) fn mirror_symmetric(params: &ReynoldsParams) -> bool {
    params.grooves.iter().all(|g| g.center_z == 0.0)
}

/// Wraps an angle into (−π, π].
pub(crate) fn wrap_angle(a: f64) -> f64 {
    let mut x = a.rem_euclid(2.0 * PI);
    if x > PI {
        x -= 2.0 * PI;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reynolds::GridParams;

    /// The per-column trig table is cos and sin of the node and face angles, to the bit, on a
    /// grid turned by θ_0 as on the plain one.
    #[test]
    fn region_faces_are_the_faces_between_two_regions() {
        // Supply line on column 0 (rows 1 … n_z − 2), ends on rows 0 and n_z − 1. Faces between
        // two regions, counted by hand: the supply line's θ-faces to columns 1 and n_θ − 1
        // (n_z − 2 each), the z-faces from the low end row and into the high one in every
        // column (on column 0 they join the ends to the line). The θ-faces along the end rows
        // join two ends and belong to no balance.
        let g = Grid::new(&params(Vec::new(), SupplyModel::AxialLineAtMaxGap), 0.0).unwrap();
        let (nt, nz) = (g.n_theta, g.n_z);
        assert_eq!(g.region_faces.len(), 2 * (nz - 2) + 2 * nt);
        let line_faces = g
            .region_faces
            .iter()
            .filter(|f| f.from == FlowRegion::Line || f.to == FlowRegion::Line)
            .count();
        assert_eq!(line_faces, 2 * (nz - 2) + 2);
        for f in &g.region_faces {
            assert_ne!(f.from, f.to);
            let (i, j) = (f.k / nz, f.k % nz);
            let other = if f.z_face {
                f.k + 1
            } else {
                (i + 1) % nt * nz + j
            };
            assert_eq!((f.from, f.to), (g.flow_region(f.k), g.flow_region(other)));
        }
        // In the order of the face loop (node k, its θ-face before its z-face).
        assert!(
            g.region_faces
                .windows(2)
                .all(|w| (w[0].k, w[0].z_face) < (w[1].k, w[1].z_face))
        );
        // Neither a supply line nor a groove: only the end rows' z-faces.
        let g = Grid::new(&params(Vec::new(), SupplyModel::Grooves), 0.0).unwrap();
        assert_eq!(g.region_faces.len(), 2 * g.n_theta);
    }

    #[test]
    fn column_trig_is_the_angles_cos_and_sin() {
        for theta0 in [0.0, 1.234] {
            let g = Grid::new(&params(Vec::new(), SupplyModel::AxialLineAtMaxGap), theta0).unwrap();
            assert_eq!(g.column_trig.len(), g.n_theta);
            for (i, t) in g.column_trig.iter().enumerate() {
                let (th, thf) = (g.theta(i), g.theta(i) + 0.5 * g.d_theta);
                assert_eq!([t.cos, t.sin], [th.cos(), th.sin()], "column {i}");
                assert_eq!([t.cos_face, t.sin_face], [thf.cos(), thf.sin()], "face {i}");
            }
        }
    }

    fn params(grooves: Vec<Groove>, supply: SupplyModel) -> ReynoldsParams {
        let mut p = ReynoldsParams::plain(0.025, 0.02, 40e-6, 0.02);
        p.grid = GridParams {
            n_theta: 72,
            n_z: 22,
        };
        p.grooves = grooves;
        p.supply = supply;
        p
    }

    fn groove(center_angle: f64, center_z: f64, angular_width: f64, axial_width: f64) -> Groove {
        Groove {
            center_angle,
            center_z,
            angular_width,
            axial_width,
            cutoff_film_fraction: 0.01,
        }
    }

    /// Every face between an unknown node and a groove node carries share · spacing / d, with
    /// d the distance from the unknown node to the groove's edge and the share the overlap of
    /// the face with the groove along the edge, both measured here from the node coordinates
    /// and the rectangle; every other face carries 1; every unknown lies more than half a
    /// spacing outside the rectangle and every groove node less.
    #[test]
    fn groove_edge_factors_follow_the_rectangle() {
        // Edges at arbitrary places between the nodes (5° spacing, 1 mm cells).
        let g = groove(0.7, 0.0013, 0.43, 0.0071);
        let grid = Grid::new(&params(vec![g.clone()], SupplyModel::Grooves), 0.0).unwrap();
        let (nt, nz) = (grid.n_theta, grid.n_z);
        let dx = grid.radius * grid.d_theta;
        let outside = |k: usize| {
            let dth = wrap_angle(grid.theta(k / nz) - g.center_angle).abs();
            let dzz = (grid.z(k % nz) - g.center_z).abs();
            (dth - 0.5 * g.angular_width, dzz - 0.5 * g.axial_width)
        };
        let mut edge_faces = 0;
        for i in 0..nt {
            let ie = (i + 1) % nt;
            for j in 1..nz - 1 {
                let k = i * nz + j;
                let (ot, oz) = outside(k);
                match grid.kind[k] {
                    NodeKind::Groove(_) => {
                        assert!(ot < 0.5 * grid.d_theta && oz < 0.5 * grid.dz, "node {k}")
                    }
                    NodeKind::Unknown => {
                        assert!(ot > 0.5 * grid.d_theta - 1e-12 || oz > 0.5 * grid.dz - 1e-12)
                    }
                    _ => {}
                }
                // East face.
                let ke = ie * nz + j;
                let expect = match (grid.kind[k], grid.kind[ke]) {
                    (NodeKind::Unknown, NodeKind::Groove(_))
                    | (NodeKind::Groove(_), NodeKind::Unknown) => {
                        let ku = if grid.kind[k] == NodeKind::Unknown {
                            k
                        } else {
                            ke
                        };
                        let d = grid.radius * outside(ku).0;
                        let (lo, hi) = (grid.z(j) - 0.5 * grid.dz, grid.z(j) + 0.5 * grid.dz);
                        let (glo, ghi) = (
                            g.center_z - 0.5 * g.axial_width,
                            g.center_z + 0.5 * g.axial_width,
                        );
                        let share = ((hi.min(ghi) - lo.max(glo)) / grid.dz).clamp(0.0, 1.0);
                        edge_faces += 1;
                        share * dx / d
                    }
                    _ => 1.0,
                };
                assert!(
                    (grid.theta_face_factor[k] - expect).abs() <= 1e-12 * expect,
                    "east face of ({i}, {j}): {} against {expect}",
                    grid.theta_face_factor[k]
                );
                // North face.
                if j + 2 < nz {
                    let expect = match (grid.kind[k], grid.kind[k + 1]) {
                        (NodeKind::Unknown, NodeKind::Groove(_))
                        | (NodeKind::Groove(_), NodeKind::Unknown) => {
                            let ku = if grid.kind[k] == NodeKind::Unknown {
                                k
                            } else {
                                k + 1
                            };
                            let d = outside(ku).1;
                            let th = wrap_angle(grid.theta(i) - g.center_angle);
                            let (lo, hi) = (th - 0.5 * grid.d_theta, th + 0.5 * grid.d_theta);
                            let (glo, ghi) = (-0.5 * g.angular_width, 0.5 * g.angular_width);
                            let share =
                                ((hi.min(ghi) - lo.max(glo)) / grid.d_theta).clamp(0.0, 1.0);
                            edge_faces += 1;
                            share * grid.dz / d
                        }
                        _ => 1.0,
                    };
                    assert!(
                        (grid.z_face_factor[k] - expect).abs() <= 1e-12 * expect,
                        "north face of ({i}, {j}): {} against {expect}",
                        grid.z_face_factor[k]
                    );
                }
            }
        }
        assert!(edge_faces > 20, "the groove has edges ({edge_faces} faces)");
        // Between half and three halves of a spacing from the edge: factors in (0, 2].
        for f in grid.theta_face_factor.iter().chain(&grid.z_face_factor) {
            assert!(*f > 0.0 && *f <= 2.0 + 1e-12, "{f}");
        }
    }

    /// A supply line through a groove holds ambient pressure at its own nodes: no face of a
    /// supply-line node carries a groove factor (the factors are set after the line).
    #[test]
    fn a_supply_line_through_a_groove_takes_no_groove_factor() {
        let g = groove(0.0, 0.0, 0.43, 0.0071);
        let grid = Grid::new(&params(vec![g], SupplyModel::AxialLineAtMaxGap), 0.0).unwrap();
        let (nt, nz) = (grid.n_theta, grid.n_z);
        for j in 1..nz - 1 {
            assert_eq!(grid.kind[j], NodeKind::SupplyLine);
            // Column 0's east face, column nt − 1's east face (into column 0), its north face.
            for k in [j, (nt - 1) * nz + j] {
                assert_eq!(grid.theta_face_factor[k], 1.0, "row {j}");
            }
            assert_eq!(grid.z_face_factor[j], 1.0, "row {j}");
        }
    }

    /// The half grid's unfold puts on row j of the whole grid the half's row min(j, n_z − 1 − j)
    /// (its mirror image about the mid-plane), for odd and even whole n_z; fold takes the rows
    /// z ≤ 0 back (and the closed row from the whole grid's end row).
    #[test]
    fn unfold_mirrors_the_half_and_fold_takes_it_back() {
        for full_nz in [31, 22, 5, 4] {
            let mut p = params(vec![groove(1.0, 0.0, 0.3, 0.004)], SupplyModel::Grooves);
            p.grid.n_z = full_nz;
            let grid = Grid::new_half(&p, 0.0).unwrap();
            let (nt, nz) = (grid.n_theta, grid.n_z);
            assert_eq!(grid.mirror.unwrap().full_n_z, full_nz);
            let half: Vec<f64> = (0..nt * nz).map(|k| (k as f64).sqrt()).collect();
            let whole = grid.unfold(&half);
            assert_eq!(whole.len(), nt * full_nz);
            for i in 0..nt {
                for j in 0..full_nz {
                    let from = j.min(full_nz - 1 - j);
                    assert!(from + 1 < nz, "the closed row is never read");
                    assert_eq!(
                        whole[i * full_nz + j],
                        half[i * nz + from],
                        "n_z {full_nz}, ({i}, {j})"
                    );
                }
            }
            let back = grid.fold(&whole);
            for i in 0..nt {
                for j in 0..nz - 1 {
                    assert_eq!(back[i * nz + j], half[i * nz + j]);
                }
                assert_eq!(back[i * nz + nz - 1], whole[i * full_nz + full_nz - 1]);
            }
        }
    }
}
