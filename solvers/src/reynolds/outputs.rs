//! What a solve returns (docs/conventions.md §5), from the converged discrete film.
//!
//! * Pressure p = p_cav + g β ψ at unknowns; p_amb at ends and on the supply line; p_feed (or
//!   p_cav when cut off) in grooves.
//! * Film force F = −Σ w_k (p_k − p_amb) (cos θ_i, sin θ_i), w_k = R Δθ Δz on the cells (the
//!   end rows are boundary points): the midpoint rule, spectrally accurate in θ and second order
//!   in z.
//! * h_min = c (1 − |ε|) at θ = atan2(ε_y, ε_x), z = 0 (aligned journal: exact, not gridded);
//!   p_max and its place are the largest nodal pressure.
//! * Flows from the face fluxes of the scheme itself: a face between two regions (unknowns,
//!   end z = −L/2, end z = +L/2, groove g, supply line) moves its flux from one region to the
//!   other. Side leakage = net inflow into each end; supply flow = net outflow of each groove.
//!   Because the same fluxes make the discrete balances, Σ supply − Σ leakage = the rate of
//!   change of the film content, to round-off (0 at steady state).
//! * Recirculated flow: the θ-flux across the leading edge of each groove (every non-end row),
//!   the film oil that arrives back at the feed (the heat balance's Q_r).
//! * Film content Σ V h φ over the unknown nodes (m³ at cavitation density): its rate of change
//!   closes the balance supply − leakage of a time step.
//! * Shear (velocity profile u(y) = (1/2μ) p_x (y² − y h) + U (1 − y/h), journal at y = 0):
//!   stress on the journal −μU f/h − (h/2) p_x, on the bearing +μU f/h − (h/2) p_x, f = 1 in full
//!   film and φ in a cavity (only the oil fraction shears, docs/conventions.md §5). Torques about +z are
//!   R ∫∫ stress dA, with p_x by central differences.
//! * Power loss = ∫∫ μU² f / h dA + Σ_faces (h_f³/12μ) (Δp/Δs)² A_face (the dissipation
//!   integral of docs/conventions.md §5, its pressure part evaluated on the faces of the scheme).
//! * A Crank–Nicolson step evaluates the torques and the power loss with the pressure of its
//!   midpoint, ½ (pⁿ + pⁿ⁺¹) ([`Friction::AtMidpoint`]): the scheme is not L-stable, and the
//!   stiff pressure modes an event excites ring with an amplification near −1 per step. They
//!   are force-neutral (the inverse Newton balances the load at every level), but the
//!   dissipation is quadratic in p: at pⁿ⁺¹ each ringing mode adds its own positive share, step
//!   after step (the Flores feed-hole case: a cycle-mean power of 44.3 W against BDF2's
//!   39.1 W), while in the midpoint pressure, the level Crank–Nicolson's fluxes are centred on,
//!   it cancels (39.05 W).

use ndarray::Array2;
use std::f64::consts::TAU;

use super::grid::{FlowRegion, Grid, NodeKind};
use super::{Core, FilmSolution, FilmState, OperatingConditions, ReynoldsParams};

/// Which pressure the torques and the power loss of [`film_solution`] are evaluated with.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Friction<'a> {
    /// Not evaluated (NaN): a relaxed trial (`ReynoldsSolver::solve_trial_step_to`).
    Skip,
    /// The solved level's pressure (steady solves, backward Euler and BDF2 steps).
    AtNewLevel,
    /// ½ (pⁿ + pⁿ⁺¹) with the old level's nodal pressure given ([`state_pressure`]): a
    /// Crank–Nicolson step (module docs).
    AtMidpoint(&'a [f64]),
}

pub(crate) fn film_solution(
    params: &ReynoldsParams,
    conditions: &OperatingConditions,
    eps: [f64; 2],
    core: &Core,
    mu: &[f64],
    friction: Friction<'_>,
    fields: bool,
) -> FilmSolution {
    let grid = &core.grid;
    let nt = grid.n_theta;
    let speed = params.radius * (conditions.journal_speed - conditions.bearing_speed);
    let pressure = nodal_pressure(params, core);
    let integrals = PressureIntegrals::new(params, core, &pressure);
    let force = integrals.force;
    let attitude_angle = {
        let load_dir = (-force[1]).atan2(-force[0]);
        let ecc_dir = eps[1].atan2(eps[0]);
        let a = super::grid::wrap_angle(ecc_dir - load_dir);
        if speed < 0.0 { -a } else { a }
    };
    let emag = eps[0].hypot(eps[1]);
    let flows = BoundaryFlows::new(params, core);
    let shear = match friction {
        Friction::AtNewLevel => Shear::new(params, core, mu, &pressure, speed),
        Friction::AtMidpoint(old) => {
            // `ReynoldsSolver::check_step` holds the state to this grid.
            debug_assert_eq!(old.len(), pressure.len(), "old level of another grid");
            let midpoint: Vec<f64> = pressure
                .iter()
                .zip(old)
                .map(|(p, q)| 0.5 * (p + q))
                .collect();
            Shear::new(params, core, mu, &midpoint, speed)
        }
        Friction::Skip => Shear {
            torque_journal: f64::NAN,
            torque_bearing: f64::NAN,
            power_loss: f64::NAN,
        },
    };

    // On a half grid (mirror symmetry, `grid` module docs) the integrals are the half
    // bearing's: the whole bearing has twice each, the same leakage through both ends, and
    // the fields are the half's and their mirror image.
    let two = grid.mirror_factor();
    let side_leakage = match grid.mirror {
        Some(_) => [flows.side_leakage[0]; 2],
        None => flows.side_leakage,
    };
    let [pressure, density_ratio, film_fraction, switch] = if fields {
        let shape = (nt, params.grid.n_z);
        let to_arr =
            |v: Vec<f64>| Array2::from_shape_vec(shape, grid.unfold(&v)).expect("grid shape");
        let density: Vec<f64> = core.psi.iter().map(|p| 1.0 + p).collect();
        let fraction: Vec<f64> = density
            .iter()
            .zip(&core.g)
            .map(|(&d, &g)| if g > 0.5 { 1.0 } else { d })
            .collect();
        [
            to_arr(pressure),
            to_arr(density),
            to_arr(fraction),
            to_arr(core.g.clone()),
        ]
    } else {
        std::array::from_fn(|_| Array2::zeros((0, 0)))
    };
    let force = [two * force[0], two * force[1]];
    FilmSolution {
        film_force: force,
        load_capacity: force[0].hypot(force[1]),
        attitude_angle,
        min_film_thickness: params.clearance * (1.0 - emag),
        min_film_location: [eps[1].atan2(eps[0]).rem_euclid(TAU), 0.0],
        max_pressure: integrals.max_pressure,
        max_pressure_location: integrals.max_pressure_location,
        cavitated_fraction: integrals.cavitated_fraction,
        film_content: two * integrals.film_content,
        side_leakage,
        supply_flow: flows.supply.iter().map(|q| two * q).collect(),
        supply_line_flow: two * flows.supply_line,
        recirculated_flow: two * recirculated_flow(params, core, speed),
        friction_torque_journal: two * shear.torque_journal,
        friction_torque_bearing: two * shear.torque_bearing,
        power_loss: two * shear.power_loss,
        iterations: core.iterations,
        single_pivots: core.single_pivots,
        linear_iterations: core.linear_iterations,
        residual: core.residual,
        theta: (0..nt).map(|i| grid.theta(i)).collect(),
        z: (0..params.grid.n_z).map(|j| grid.whole_z(j)).collect(),
        pressure,
        density_ratio,
        film_fraction,
        switch,
    }
}

/// The nodal pressure of a stored time level, as [`nodal_pressure`] gives it for a solved
/// one: p_amb at the ends and on the supply line, p_cav + β (φ − 1) where the film is full, p_cav
/// where it is cavitated.
pub(crate) fn state_pressure(params: &ReynoldsParams, grid: &Grid, state: &FilmState) -> Vec<f64> {
    let (beta, pcav) = (params.bulk_modulus, params.cavitation_pressure);
    state
        .density_ratio
        .iter()
        .zip(state.full_film.iter())
        .enumerate()
        .map(|(k, (&phi, &full))| match grid.kind[k] {
            NodeKind::End | NodeKind::SupplyLine => params.ambient_pressure,
            _ if full => pcav + beta * (phi - 1.0),
            _ => pcav,
        })
        .collect()
}

/// p = p_cav + g β ψ at unknowns (and grooves, whose ψ holds the feed), p_amb at the ends and
/// on the supply line.
fn nodal_pressure(params: &ReynoldsParams, core: &Core) -> Vec<f64> {
    let (beta, pcav) = (params.bulk_modulus, params.cavitation_pressure);
    (0..core.grid.len())
        .map(|k| match core.grid.kind[k] {
            NodeKind::End | NodeKind::SupplyLine => params.ambient_pressure,
            _ => pcav + core.g[k] * beta * core.psi[k],
        })
        .collect()
}

/// The pressure field's integrals: film force, peak pressure and its place, cavitated area
/// fraction, film content.
struct PressureIntegrals {
    force: [f64; 2],
    max_pressure: f64,
    max_pressure_location: [f64; 2],
    cavitated_fraction: f64,
    film_content: f64,
}

impl PressureIntegrals {
    fn new(params: &ReynoldsParams, core: &Core, pressure: &[f64]) -> Self {
        let grid = &core.grid;
        let nz = grid.n_z;
        let pamb = params.ambient_pressure;
        let mut out = Self {
            force: [0.0, 0.0],
            max_pressure: f64::NEG_INFINITY,
            max_pressure_location: [0.0, 0.0],
            cavitated_fraction: 0.0,
            film_content: 0.0,
        };
        let (mut cav_area, mut area) = (0.0, 0.0);
        for i in 0..grid.n_theta {
            let th = grid.theta(i);
            let (c, s) = (grid.column_trig[i].cos, grid.column_trig[i].sin);
            for j in 0..nz {
                let k = i * nz + j;
                let w = grid.area_weight[k];
                let dp = pressure[k] - pamb;
                out.force[0] -= w * dp * c;
                out.force[1] -= w * dp * s;
                if pressure[k] > out.max_pressure {
                    out.max_pressure = pressure[k];
                    out.max_pressure_location = [th.rem_euclid(TAU), grid.z(j)];
                }
                area += w;
                if grid.kind[k] == NodeKind::Unknown {
                    out.film_content += grid.cell_area(j) * core.h[k] * (1.0 + core.psi[k]);
                }
                if core.g[k] < 0.5 {
                    cav_area += w;
                }
            }
        }
        out.cavitated_fraction = cav_area / area;
        out
    }
}

/// Side leakage into each end, supply flow out of each groove and out of the supply line:
/// every face flux between two regions moved from one to the other.
struct BoundaryFlows {
    side_leakage: [f64; 2],
    supply: Vec<f64>,
    supply_line: f64,
}

impl BoundaryFlows {
    fn new(params: &ReynoldsParams, core: &Core) -> Self {
        let mut flows = Self {
            side_leakage: [0.0, 0.0],
            supply: vec![0.0; params.grooves.len()],
            supply_line: 0.0,
        };
        // Only the faces between two regions book a flux (`Grid::region_faces`, in the order
        // of the face loop over the grid).
        for face in &core.grid.region_faces {
            let f = if face.z_face {
                core.flux_z[face.k]
            } else {
                core.flux_theta[face.k]
            };
            flows.account(face.from, face.to, f);
        }
        flows
    }

    /// The flux `f` through a face from region `from` to region `to` (two different ones).
    fn account(&mut self, from: FlowRegion, to: FlowRegion, f: f64) {
        for (region, sign) in [(from, 1.0), (to, -1.0)] {
            match region {
                FlowRegion::Groove(g) => self.supply[g as usize] += sign * f,
                FlowRegion::Line => self.supply_line += sign * f,
                FlowRegion::EndLow => self.side_leakage[0] -= sign * f,
                FlowRegion::EndHigh => self.side_leakage[1] -= sign * f,
                FlowRegion::Unknown => {}
            }
        }
    }
}

/// Recirculated flow: the θ-flux across each groove's leading edge, every non-end row.
fn recirculated_flow(params: &ReynoldsParams, core: &Core, speed: f64) -> f64 {
    let grid = &core.grid;
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let mut recirculated = 0.0;
    for g in 0..params.grooves.len() {
        let in_groove =
            |i: usize| (0..nz).any(|j| grid.kind[i * nz + j] == NodeKind::Groove(g as u16));
        for i in 0..nt {
            if !in_groove(i) {
                continue;
            }
            // flux_theta[k] runs from column i to column i + 1.
            let (upstream, face, sign) = if speed >= 0.0 {
                let iw = (i + nt - 1) % nt;
                (iw, iw, 1.0)
            } else {
                let ie = (i + 1) % nt;
                (ie, i, -1.0)
            };
            if in_groove(upstream) {
                continue;
            }
            for j in 1..nz.saturating_sub(1) {
                recirculated += sign * core.flux_theta[face * nz + j];
            }
        }
    }
    recirculated
}

/// Friction torques on journal and bearing and the dissipated power (module docs).
struct Shear {
    torque_journal: f64,
    torque_bearing: f64,
    power_loss: f64,
}

impl Shear {
    fn new(params: &ReynoldsParams, core: &Core, mu: &[f64], pressure: &[f64], speed: f64) -> Self {
        let grid = &core.grid;
        let (nt, nz) = (grid.n_theta, grid.n_z);
        let dx = grid.radius * grid.d_theta;
        let mut out = Self {
            torque_journal: 0.0,
            torque_bearing: 0.0,
            power_loss: 0.0,
        };
        for i in 0..nt {
            let iw = (i + nt - 1) % nt;
            let ie = (i + 1) % nt;
            for j in 0..nz {
                let k = i * nz + j;
                let w = grid.area_weight[k];
                let h = core.h[k];
                let f = if core.g[k] > 0.5 {
                    1.0
                } else {
                    (1.0 + core.psi[k]).clamp(0.0, 1.0)
                };
                let couette = mu[k] * speed * f / h;
                let px = (pressure[ie * nz + j] - pressure[iw * nz + j]) / (2.0 * dx);
                out.torque_journal += params.radius * w * (-couette - 0.5 * h * px);
                out.torque_bearing += params.radius * w * (couette - 0.5 * h * px);
                out.power_loss += w * couette * speed;
                // Pressure dissipation on the east and north faces.
                let ke = ie * nz + j;
                let hf = 0.5 * (h + core.h[ke]);
                let muf = 0.5 * (mu[k] + mu[ke]);
                let gp = (pressure[ke] - pressure[k]) / dx;
                let face_area = dx * grid.row_width(j);
                out.power_loss +=
                    grid.theta_face_factor[k] * hf.powi(3) / (12.0 * muf) * gp * gp * face_area;
                if j + 1 < nz {
                    let hf = 0.5 * (h + core.h[k + 1]);
                    let muf = 0.5 * (mu[k] + mu[k + 1]);
                    let gap = grid.z_gap(j);
                    let gp = (pressure[k + 1] - pressure[k]) / gap;
                    out.power_loss +=
                        grid.z_face_factor[k] * hf.powi(3) / (12.0 * muf) * gp * gp * dx * gap;
                }
            }
        }
        out
    }
}
