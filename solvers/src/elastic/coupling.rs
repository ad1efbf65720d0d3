//! The deformable bearing under a steady load: the film and the elastic shaft and housing
//! solved together (\[Benasciutti2012\] Fig. 4).
//!
//! ```text
//!   h(θ) = c − e_x cos θ − e_y sin θ + g(θ),      g = C p̄(ε, g)       (C: [`Compliance`])
//!   F_film(ε, g) + W = 0                                                (steady-load Newton)
//! ```
//!
//! p̄(θ) = (1/L) ∫ (p − p_amb) dz is the film's pressure averaged over the length, the load per
//! unit length and angle that the plane-strain structure carries (for the paper's plane film
//! the mid-plane pressure itself); it is interpolated linearly from the film's θ nodes (turned
//! with the supply line) to the structure's surface nodes θ_k = 2πk/n, and g back from θ_k to
//! the film's nodes and faces ([`FilmDeformation`]).
//!
//! # The iteration: Newton on ε inside, relaxed fixed point on g outside
//!
//! Outer iteration k: the steady-load Newton of the film with g_k fixed gives ε_k and p̄_k
//! (load balance exact at every k), then
//!
//! ```text
//!   r_k = C p̄_k − g_k,     g_{k+1} = g_k + ω_k r_k,
//!   ω_k = −ω_{k−1} r_{k−1}·(r_k − r_{k−1}) / |r_k − r_{k−1}|²   (Aitken, clamped to [ω_min, 1])
//! ```
//!
//! — the paper's under-relaxed fixed point with the relaxation factor chosen by Aitken's Δ²
//! rule as in fluid–structure partitioned solvers \[KuttlerWall2008\]. Why not Newton on (ε, g)
//! together: its Jacobian needs ∂p̄/∂g, an n × n film sensitivity (n linearized film solves
//! per step, against three film solves per Newton step on ε); the compliance here is large
//! (a 40 MPa peak moves the surfaces by ~0.1 mm against a 10 μm film), so the plain fixed
//! point (ω = 1) diverges and a fixed small ω converges slowly; Aitken's ω adapts to the
//! dominant contraction and converges in tens of outer iterations, each a warm-started
//! steady-load Newton of a few film solves. Converged when max_k |r_k| ≤ `gap_tolerance` · c:
//! the film then sees the deformation its own pressure causes to that accuracy.

use super::{Compliance, ElasticBody, ElasticError, HousingShape, Material, Mesh, square_layers};
use crate::reynolds::{
    FilmDeformation, FilmSolution, OperatingConditions, ReynoldsSolver, SteadyLoadInfo,
};

/// The elastic model of the bearing and the coupled iteration's controls (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct ElasticParams {
    pub shaft_material: Material,
    pub housing_material: Material,
    /// Radius of the shaft's central hole, held radially (the plane model's support of the
    /// load, \[Benasciutti2012\] Fig. 5 and its text), m.
    pub hole_radius: f64,
    /// Outline of the housing, fixed there.
    pub housing: HousingShape,
    /// Nodes around the film surface (both bodies), the mesh density: a multiple of 8 puts
    /// nodes on a square housing's corners.
    pub n_theta: usize,
    /// Element layers [shaft, housing]; None: nearly square elements ([`square_layers`]).
    pub layers: Option<[usize; 2]>,
    /// Converged when the gap change the film's pressure causes differs from the one it saw
    /// by at most this fraction of the clearance at every node: the steady solve
    /// ([`solve_steady_load`]).
    pub gap_tolerance: f64,
    /// The same for every trial film step of the dynamic (inverse) solver's Newton
    /// ([`super::ElasticFilm`]): [`ElasticParams::dynamic_gap_tolerance_for`] its force
    /// tolerance, far tighter than the steady one (the dynamic module's docs say why).
    pub dynamic_gap_tolerance: f64,
    /// Most outer (deformation) iterations.
    pub max_iterations: usize,
    /// ω of the first relaxed update.
    pub initial_relaxation: f64,
    /// Smallest ω Aitken's rule may choose.
    pub min_relaxation: f64,
}

impl ElasticParams {
    /// Steel shaft and housing, the shaft hole at 0.4 R, a square housing of half-width 2R,
    /// 240 nodes around; tolerance 1e-5 c (2.5 nm for c = 0.25 mm) for the steady solve and
    /// 1e-8 c for the dynamic film (what a Newton force tolerance of 1e-6 needs — the
    /// application's default `solver.force_tolerance`; [`crate::inverse::InverseParams`]
    /// defaults to 1e-4, for which it is tighter than needed:
    /// [`ElasticParams::dynamic_gap_tolerance_for`]), at most 200 iterations, ω₀ = 0.1,
    /// ω ≥ 0.005.
    pub fn steel(radius: f64) -> Self {
        Self {
            shaft_material: Material::STEEL,
            housing_material: Material::STEEL,
            hole_radius: 0.4 * radius,
            housing: HousingShape::Square {
                half_width: 2.0 * radius,
            },
            n_theta: 240,
            layers: None,
            gap_tolerance: 1e-5,
            dynamic_gap_tolerance: Self::dynamic_gap_tolerance_for(1e-6),
            max_iterations: 200,
            initial_relaxation: 0.1,
            min_relaxation: 0.005,
        }
    }

    /// The thinnest film, as a fraction of the clearance, that
    /// [`ElasticParams::dynamic_gap_tolerance_for`] is meant for (the compressor rod bearing
    /// runs at h_min ≈ 0.16 c).
    pub const DYNAMIC_THINNEST_FILM: f64 = 0.1;

    /// The gap tolerance (fraction of c) a dynamic run needs under a Newton force tolerance
    /// `force_tolerance` (fraction of the load): a gap error δ moves a film of thickness h_min
    /// by δ/h_min, so δ ≤ 0.1 · force_tolerance · h_min, with h_min =
    /// [`ElasticParams::DYNAMIC_THINNEST_FILM`] c — 1e-8 c at the application's default 1e-6,
    /// the value the compressor rod's dynamic run validates (docs/validation.md).
    pub fn dynamic_gap_tolerance_for(force_tolerance: f64) -> f64 {
        0.1 * force_tolerance * Self::DYNAMIC_THINNEST_FILM
    }
}

/// Shaft, housing (factorized) and their gap compliance.
#[derive(Debug)]
pub struct ElasticBearing {
    pub params: ElasticParams,
    pub shaft: ElasticBody,
    pub housing: ElasticBody,
    pub compliance: Compliance,
}

impl ElasticBearing {
    /// Meshes both bodies around the film surface of radius `radius` (the film's R), factorizes
    /// them and computes the compliance.
    pub fn new(radius: f64, params: ElasticParams) -> Result<Self, ElasticError> {
        let invalid = |name, value, reason| ElasticError::InvalidParameter {
            name,
            value,
            reason,
        };
        if !(params.hole_radius > 0.0 && params.hole_radius < radius) {
            return Err(invalid(
                "hole_radius",
                params.hole_radius,
                "must lie between 0 and the shaft radius",
            ));
        }
        let outer_min = match params.housing {
            HousingShape::Square { half_width } => half_width,
            HousingShape::Circle { radius } => radius,
        };
        if !(outer_min > radius && outer_min.is_finite()) {
            return Err(invalid(
                "housing",
                outer_min,
                "the housing outline must lie outside the bore",
            ));
        }
        if params.n_theta < 8 {
            return Err(invalid(
                "n_theta",
                params.n_theta as f64,
                "needs at least 8 nodes around",
            ));
        }
        for (name, v) in [
            ("gap_tolerance", params.gap_tolerance),
            ("dynamic_gap_tolerance", params.dynamic_gap_tolerance),
            ("initial_relaxation", params.initial_relaxation),
            ("min_relaxation", params.min_relaxation),
        ] {
            if !(v > 0.0 && v <= 1.0) {
                return Err(invalid(name, v, "must lie in (0, 1]"));
            }
        }
        let n = params.n_theta;
        let [ls, lh] = params.layers.unwrap_or([
            square_layers(params.hole_radius, radius, n),
            square_layers(radius, outer_min, n),
        ]);
        let shaft = ElasticBody::new(
            Mesh::shaft(params.hole_radius, radius, n, ls),
            params.shaft_material,
        )?;
        let housing = ElasticBody::new(
            Mesh::housing(radius, params.housing, n, lh),
            params.housing_material,
        )?;
        let compliance = Compliance::new(&shaft, &housing)?;
        Ok(Self {
            params,
            shaft,
            housing,
            compliance,
        })
    }

    /// Angles θ_k of the surface nodes, rad.
    pub fn surface_angles(&self) -> Vec<f64> {
        let n = self.params.n_theta;
        (0..n)
            .map(|k| 2.0 * std::f64::consts::PI * k as f64 / n as f64)
            .collect()
    }
}

/// The coupled answer.
#[derive(Debug, Clone)]
pub struct ElasticSolution {
    /// The film at the converged eccentricity and deformation.
    pub film: FilmSolution,
    /// Gap change g(θ_k) at the surface nodes, m.
    pub gap_change: Vec<f64>,
    /// Length-averaged film pressure p̄(θ_k) that loads the structure, Pa.
    pub surface_pressure: Vec<f64>,
    /// Radial displacement (outward positive) of the shaft and housing surfaces at θ_k, m.
    pub shaft_radial: Vec<f64>,
    pub housing_radial: Vec<f64>,
    /// Nodal displacements of the shaft and the housing meshes under p̄, m.
    pub shaft_displacement: Vec<[f64; 2]>,
    pub housing_displacement: Vec<[f64; 2]>,
}

/// How the coupled solve went.
#[derive(Debug, Clone, PartialEq)]
pub struct ElasticInfo {
    /// Outer (deformation) iterations.
    pub iterations: usize,
    /// max_k |C p̄ − g| of the last iteration, m.
    pub gap_residual: f64,
    /// The last relaxation factor.
    pub relaxation: f64,
    /// Film solves over all steady-load Newton solves.
    pub film_solves: usize,
    /// The last steady-load Newton solve.
    pub steady: SteadyLoadInfo,
}

/// Linear periodic interpolation of values at θ_i = θ_0 + 2πi/n.
fn periodic_interpolation(theta0: f64, values: &[f64], theta: f64) -> f64 {
    let n = values.len();
    let s = (theta - theta0).rem_euclid(2.0 * std::f64::consts::PI) / (2.0 * std::f64::consts::PI)
        * n as f64;
    let i = (s.floor() as usize).min(n - 1);
    let t = s - i as f64;
    (1.0 - t) * values[i] + t * values[(i + 1) % n]
}

/// p̄ at the structure's surface nodes from a film solution (module docs).
fn surface_pressure(film: &FilmSolution, ambient: f64, angles: &[f64]) -> Vec<f64> {
    length_mean_at(&film.pressure, film.theta[0], ambient, angles)
}

/// p̄ at `angles` from a film pressure field `pressure[[i, j]]` at θ_i = θ_0 + 2πi/n_θ.
pub(crate) fn length_mean_at(
    pressure: &ndarray::Array2<f64>,
    theta0: f64,
    ambient: f64,
    angles: &[f64],
) -> Vec<f64> {
    let (nt, nz) = pressure.dim();
    // Interior rows are the equal cells tiling the length; the end rows are boundary points.
    let mean: Vec<f64> = (0..nt)
        .map(|i| (1..nz - 1).map(|j| pressure[[i, j]] - ambient).sum::<f64>() / (nz - 2) as f64)
        .collect();
    angles
        .iter()
        .map(|&th| periodic_interpolation(theta0, &mean, th))
        .collect()
}

/// Aitken's relaxation factor from the last two residuals (module docs), unclamped; `omega`
/// when the residual did not change.
pub(crate) fn aitken(omega: f64, previous: &[f64], residual: &[f64]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (a, b) in previous.iter().zip(residual) {
        num += a * (b - a);
        den += (b - a) * (b - a);
    }
    if den > 0.0 { -omega * num / den } else { omega }
}

/// The steady load `load` (N, on the journal) carried by the deformable bearing: the film of
/// `solver` (its parameters: geometry, viscosity, supply) coupled to `bearing` (module docs).
///
/// ```
/// use jbearing_solvers::elastic::{solve_steady_load, ElasticBearing, ElasticParams};
/// use jbearing_solvers::prelude::*;
///
/// // A heavily loaded steel bearing (8 MPa mean pressure): the elastic gap spreads the film,
/// // so the peak pressure falls and the journal sits further out than in the rigid bearing
/// // (the trend of [Benasciutti2012]'s JB1: 83 → 43 MPa, e 0.239 → 0.295 mm at 24 MPa).
/// let (r, c) = (0.05, 50e-6);
/// let mut film = ReynoldsParams::plain(r, 0.05, c, 0.05);
/// film.supply = SupplyModel::AxialLineAtMaxGap;
/// film.grid = GridParams { n_theta: 64, n_z: 9 };
/// let conditions = OperatingConditions { journal_speed: 100.0, bearing_speed: 0.0, feed_pressures: vec![] };
/// let load = [0.0, -40e3];
/// let mut solver = ReynoldsSolver::new(film)?;
/// let (rigid, rigid_info) = solver.solve_steady_load(load, &conditions)?;
/// let bearing = ElasticBearing::new(r, ElasticParams { n_theta: 64, ..ElasticParams::steel(r) })?;
/// let (elastic, info) = solve_steady_load(&mut solver, &bearing, load, &conditions)?;
/// let e = |x: [f64; 2]| x[0].hypot(x[1]);
/// assert!(elastic.film.max_pressure < rigid.max_pressure);
/// assert!(e(info.steady.eccentricity_ratio) > e(rigid_info.eccentricity_ratio));
/// // Converged to the stated tolerance, and the film carries the load.
/// assert!(info.gap_residual <= bearing.params.gap_tolerance * c);
/// assert!((elastic.film.load_capacity - 40e3).abs() < 1e-3 * 40e3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_steady_load(
    solver: &mut ReynoldsSolver,
    bearing: &ElasticBearing,
    load: [f64; 2],
    conditions: &OperatingConditions,
) -> Result<(ElasticSolution, ElasticInfo), ElasticError> {
    let p = &bearing.params;
    let n = p.n_theta;
    let angles = bearing.surface_angles();
    let ambient = solver.params().ambient_pressure;
    let tolerance = p.gap_tolerance * solver.params().clearance;
    let mut g = vec![0.0; n];
    let mut omega = p.initial_relaxation;
    let mut previous_residual: Option<Vec<f64>> = None;
    let mut eps: Option<[f64; 2]> = None;
    let mut film_solves = 0;
    let mut last_residual = f64::INFINITY;
    for it in 0..p.max_iterations {
        solver.set_deformation(Some(FilmDeformation::new(g.clone())?));
        let (film, info) = match eps {
            None => solver.solve_steady_load(load, conditions)?,
            Some(start) => solver.solve_steady_load_from(load, conditions, start)?,
        };
        film_solves += info.film_solves;
        eps = Some(info.eccentricity_ratio);
        let pbar = surface_pressure(&film, ambient, &angles);
        let target = bearing.compliance.gap(&pbar);
        let r: Vec<f64> = target.iter().zip(&g).map(|(t, g)| t - g).collect();
        last_residual = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !last_residual.is_finite() {
            return Err(ElasticError::NonFinite {
                what: "gap residual",
                node: r.iter().position(|v| !v.is_finite()).unwrap_or(0),
            });
        }
        if last_residual <= tolerance {
            let solution = finish(bearing, film, g, pbar)?;
            return Ok((
                solution,
                ElasticInfo {
                    iterations: it,
                    gap_residual: last_residual,
                    relaxation: omega,
                    film_solves,
                    steady: info,
                },
            ));
        }
        if let Some(prev) = &previous_residual {
            omega = aitken(omega, prev, &r).clamp(p.min_relaxation, 1.0);
        }
        for (gk, rk) in g.iter_mut().zip(&r) {
            *gk += omega * rk;
        }
        previous_residual = Some(r);
    }
    Err(ElasticError::NotConverged {
        iterations: p.max_iterations,
        gap_residual: last_residual,
        tolerance,
    })
}

/// Displacements of both bodies under the converged p̄.
fn finish(
    bearing: &ElasticBearing,
    film: FilmSolution,
    gap_change: Vec<f64>,
    surface_pressure: Vec<f64>,
) -> Result<ElasticSolution, ElasticError> {
    let shaft_displacement = bearing
        .shaft
        .solve(&bearing.shaft.surface_load(&surface_pressure)?)?;
    let housing_displacement = bearing
        .housing
        .solve(&bearing.housing.surface_load(&surface_pressure)?)?;
    Ok(ElasticSolution {
        film,
        shaft_radial: bearing.shaft.surface_radial(&shaft_displacement),
        housing_radial: bearing.housing.surface_radial(&housing_displacement),
        gap_change,
        surface_pressure,
        shaft_displacement,
        housing_displacement,
    })
}
