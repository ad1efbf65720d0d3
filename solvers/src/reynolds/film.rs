//! Film thickness of the rigid, aligned journal bearing (docs/conventions.md §1).
//!
//! ```text
//!   h(θ) = c − e_x cos θ − e_y sin θ = c (1 − ε_x cos θ − ε_y sin θ)
//! ```
//!
//! at the nodes θ_i and at the θ-faces θ_{i+½} (the pressure-flow coefficient h³ is taken at the
//! face itself, which keeps the five-point scheme second order). The film does not depend on z
//! (aligned journal); the arrays are still per node so that a misaligned journal or a bearing
//! profile can be added later without touching the discretization.

use super::grid::Grid;

/// Film thickness at the nodes and at the east θ-face of every node, both `[i · n_z + j]`.
#[derive(Debug, Clone)]
pub(crate) struct FilmThickness {
    pub node: Vec<f64>,
    pub face_theta: Vec<f64>,
}

impl FilmThickness {
    pub fn new(grid: &Grid, clearance: f64, eccentricity_ratio: [f64; 2]) -> Self {
        let n = grid.len();
        let mut node = vec![0.0; n];
        let mut face_theta = vec![0.0; n];
        let [ex, ey] = eccentricity_ratio;
        for i in 0..grid.n_theta {
            let th = grid.theta(i);
            let thf = th + 0.5 * grid.d_theta;
            let h = clearance * (1.0 - ex * th.cos() - ey * th.sin());
            let hf = clearance * (1.0 - ex * thf.cos() - ey * thf.sin());
            for j in 0..grid.n_z {
                node[i * grid.n_z + j] = h;
                face_theta[i * grid.n_z + j] = hf;
            }
        }
        Self { node, face_theta }
    }
}
