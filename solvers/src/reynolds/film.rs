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
//!
//! With a [`FilmDeformation`] (elastic surfaces, \[Benasciutti2012\] Fig. 5 and its text) the gap change
//! g(θ) is added: h = c − e_x cos θ − e_y sin θ + g(θ), g interpolated linearly in θ from its
//! samples at the nodes and faces. Without one the rigid expression above is evaluated as it
//! always was (bit for bit).

use super::grid::Grid;
use super::{FilmDeformation, ReynoldsError};

/// Film thickness at the nodes and at the east θ-face of every node, both `[i · n_z + j]`.
#[derive(Debug, Clone)]
pub(crate) struct FilmThickness {
    pub node: Vec<f64>,
    pub face_theta: Vec<f64>,
}

impl FilmThickness {
    pub fn new(
        grid: &Grid,
        clearance: f64,
        eccentricity_ratio: [f64; 2],
        deformation: Option<&FilmDeformation>,
    ) -> Self {
        let n = grid.len();
        let mut node = vec![0.0; n];
        let mut face_theta = vec![0.0; n];
        let [ex, ey] = eccentricity_ratio;
        for (i, t) in grid.column_trig.iter().enumerate() {
            let mut h = clearance * (1.0 - ex * t.cos - ey * t.sin);
            let mut hf = clearance * (1.0 - ex * t.cos_face - ey * t.sin_face);
            if let Some(d) = deformation {
                let th = grid.theta(i);
                h += d.at(th);
                hf += d.at(th + 0.5 * grid.d_theta);
            }
            for j in 0..grid.n_z {
                node[i * grid.n_z + j] = h;
                face_theta[i * grid.n_z + j] = hf;
            }
        }
        Self { node, face_theta }
    }
}

impl FilmThickness {
    /// The smallest node and face thickness must be positive (a deformed film can close
    /// anywhere, not only on the eccentricity line).
    pub fn check_positive(&self, grid: &Grid) -> Result<(), ReynoldsError> {
        for (k, (&h, &hf)) in self.node.iter().zip(&self.face_theta).enumerate() {
            let m = h.min(hf);
            if m.is_nan() || m <= 0.0 {
                return Err(ReynoldsError::FilmClosed {
                    thickness: m,
                    theta: grid.theta(k / grid.n_z),
                });
            }
        }
        Ok(())
    }
}
