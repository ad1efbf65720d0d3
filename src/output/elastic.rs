//! The deformable (elastic) bearing's results: what the coupled film–structure solve
//! (`jbearing_solvers::elastic::solve_steady_load`) found, as the writers store it.
//!
//! In `CASE.h5`:
//!
//! ```text
//! elastic/               attrs: description, solver information (iterations, gap residual, …)
//! │  <scalar> []                              eccentricity, max_pressure, rigid_* (the same film
//! │                                           without deformation), each with units
//! │  angle(angle) [rad]                       θ_k of the film-surface nodes (bearing frame)
//! │  <series>(angle)                          surface_pressure, gap_change, film_thickness,
//! │                                           housing/shaft radial displacement, bore_* and
//! │                                           journal_* stresses (σ_r, σ_θ, σ_z, von Mises)
//! VTKHDF/                shaft and housing as one UnstructuredGrid of quads (see `vtkhdf`):
//!                        points undeformed (z = 0), PointData displacement (3-vector),
//!                        stress_xx/yy/xy/zz, von_mises, radial/hoop stress; CellData body
//!                        (0 shaft, 1 housing)
//! ```
//!
//! Stresses are the nodal stresses the solver recovers (Gauss points extrapolated and
//! averaged); σ_r and σ_θ are taken in each node's polar frame about the bore centre.

use super::Parameter;
use super::Series;

/// One body's mesh and fields (plane strain: 2-D points, quads).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyField {
    /// "shaft" or "housing".
    pub name: String,
    /// Node coordinates (x, y), m, undeformed.
    pub points: Vec<[f64; 2]>,
    /// Quadrilaterals, four node indices anticlockwise.
    pub cells: Vec<[usize; 4]>,
    /// Displacement (x, y) of every node, m.
    pub displacement: Vec<[f64; 2]>,
    /// Nodal stresses (σ_xx, σ_yy, σ_xy, σ_zz), Pa.
    pub stress: Vec<[f64; 4]>,
}

impl BodyField {
    /// von Mises stress of node `k`, Pa (all four components).
    pub fn von_mises(&self, k: usize) -> f64 {
        let [xx, yy, xy, zz] = self.stress[k];
        let (a, b, c) = (xx - yy, yy - zz, zz - xx);
        (0.5 * (a * a + b * b + c * c) + 3.0 * xy * xy).sqrt()
    }

    /// (σ_r, σ_θ) of node `k` in its polar frame, Pa.
    pub fn polar_stress(&self, k: usize) -> [f64; 2] {
        let [x, y] = self.points[k];
        let (s, c) = y.atan2(x).sin_cos();
        let [xx, yy, xy, _] = self.stress[k];
        [
            xx * c * c + yy * s * s + 2.0 * xy * s * c,
            xx * s * s + yy * c * c - 2.0 * xy * s * c,
        ]
    }
}

/// The deformable bearing's answer.
#[derive(Debug, Clone, PartialEq)]
pub struct ElasticReport {
    /// What was solved, in words.
    pub description: String,
    /// Scalars of the answer (eccentricity, p_max, the rigid film's, the coupling's counts).
    pub scalars: Vec<Parameter>,
    /// θ_k of the film-surface nodes, rad (bearing frame).
    pub angle: Vec<f64>,
    /// Quantities along the film surface, one value per `angle`.
    pub series: Vec<Series>,
    /// Shaft and housing meshes with displacement and stress.
    pub bodies: Vec<BodyField>,
}

impl ElasticReport {
    /// The series named `name`.
    pub fn series(&self, name: &str) -> Option<&Series> {
        self.series.iter().find(|s| s.name == name)
    }

    /// The scalar named `key`, if a number.
    pub fn number(&self, key: &str) -> Option<f64> {
        self.scalars
            .iter()
            .find(|p| p.key == key)
            .and_then(|p| match p.value {
                super::ParameterValue::Number(v) => Some(v),
                super::ParameterValue::Integer(v) => Some(v as f64),
                _ => None,
            })
    }
}

impl ElasticReport {
    /// The answer in a few lines for the terminal: deformable against rigid, the bore stresses,
    /// the coupling's effort.
    pub fn format_summary(&self) -> String {
        let n = |k: &str| self.number(k).unwrap_or(f64::NAN);
        let max_abs = |name: &str| {
            self.series(name).map_or(f64::NAN, |s| {
                s.values.iter().fold(0.0f64, |m, v| m.max(v.abs()))
            })
        };
        format!(
            "elastic bearing: e {:.4} mm (rigid {:.4}), p_max {:.2} MPa (rigid {:.2}), h_min \
             {:.4} mm (rigid {:.4})\n  bore: max |sigma_r| {:.2} MPa, max von Mises {:.2} MPa; \
             {} coupling iterations, {} film solves, {:.1} s\n",
            n("eccentricity") * 1e3,
            n("rigid_eccentricity") * 1e3,
            n("max_pressure") * 1e-6,
            n("rigid_max_pressure") * 1e-6,
            n("min_film_thickness") * 1e3,
            n("rigid_min_film_thickness") * 1e3,
            max_abs("bore_radial_stress") * 1e-6,
            max_abs("bore_von_mises_stress") * 1e-6,
            n("coupling_iterations"),
            n("film_solves"),
            n("wall_time"),
        )
    }
}
