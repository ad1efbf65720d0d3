//! The universal Reynolds equation (Elrod–Adams / Vijayaraghavan, mass-conserving JFO
//! cavitation) for a rigid journal bearing: pressure, cavitation, load, flows and power loss for
//! a given journal position, velocity, speeds and feed.
//!
//! # What is solved
//!
//! ```text
//!   ∂(hφ)/∂t + ∂/∂x [ U h φ / 2 − (β h³/12μ) ∂(g(φ−1))/∂x ] + ∂/∂z [ −(β h³/12μ) ∂(g(φ−1))/∂z ] = 0
//!   p = p_cav + g β (φ − 1),   g = 1 (φ ≥ 1, full film) | 0 (φ < 1, film fraction φ)
//! ```
//!
//! (docs/conventions.md §2; \[Elrod1981\]; \[VijayaraghavanKeith1989\]; \[YuSawicki2002\] eq. 3 with g
//! inside the derivative), x = Rθ, U = R(ω_j − ω_b), h = c − e_x cos θ − e_y sin θ
//! (docs/conventions.md §1), periodic in θ, p = p_amb at z = ±L/2, grooves fixed in the bearing frame held
//! at their feed pressure or, when p_feed ≤ p_cav, at a cavitated state of given film fraction
//! (supply cut-off, Yu & Sawicki Fig. 4 use φ = 0.01).
//!
//! # Modules
//! - `grid`: θ × z nodes, storage `k = i·n_z + j`, node classes (diagram there).
//! - `film`: h at nodes and faces.
//! - `discretization`: the conservative five-point scheme, its face
//!   fluxes (Couette type differencing, pressure flux through gψ) and the frozen-switch
//!   linear system.
//! - `adi`: the flexible GMRES of a frozen-switch system, and ADI line sweeps (cyclic kernel
//!   on circumferential lines, Thomas on axial lines) + line-aggregate coarse correction as
//!   one of its preconditioners.
//! - `multigrid`: the default preconditioner, a θ-semi-coarsening multigrid V-cycle with
//!   zebra axial-line and cyclic circumferential-line smoothing and Galerkin coarse levels
//!   (Krylov iterations per solve nearly independent of the grid).
//! - `oracle`: the sparse-LU (faer) solve of the same system, g frozen.
//! - `outputs`: force, attitude, h_min, p_max, cavitated fraction, side
//!   leakage, supply flow, friction torques, power loss.
//! - `steady_load`: Newton on the two eccentricity components for a
//!   constant load.
//!
//! # The complementarity problem and its semismooth Newton solve
//!
//! The discrete equations of `discretization` are, per unknown node k (ψ = φ − 1),
//!
//! ```text
//!   R_k(ψ) = Σ_l C_kl ψ_l + Σ_l P_kl max(ψ_l, 0) − b_k = 0
//! ```
//!
//! C: time and upwind Couette terms (linear in φ = 1 + ψ), P: the pressure flux (through
//! g ψ = max(ψ, 0)). This *is* the JFO complementarity problem: with u = max(ψ, 0) (pressure
//! p − p_cav = βu) and v = max(−ψ, 0) (void fraction v = 1 − φ), u ≥ 0, v ≥ 0, u·v = 0 on every
//! node (full: ψ ≥ 0, g = 1, p ≥ p_cav; cavitated: ψ < 0, p = p_cav, 0 ≤ φ < 1; Giacopini et al.
//! 2010 write the same as an LCP). R is continuous and piecewise linear, and for every switch
//! pattern g its slope A(g) = C + P diag(g) is an M-matrix (`discretization`, module docs).
//!
//! Semismooth Newton on the complementarity system in (u, v),
//!
//! ```text
//!   R_mass(u, v) = C (u − v) + P u − b = 0,      min(u_k, v_k) = 0  (every unknown k),
//! ```
//!
//! is the primal–dual active-set method \[HintermullerItoKunisch2002\] and, for an LCP,
//! block principal pivoting \[JudicePires1994\]: the min-function's generalized derivative
//! picks u_k = 0 (cavitated) or v_k = 0 (full) according to the switch g; with g fixed the
//! linearized system is exactly the frozen-switch system A(g) y = b, A(g) = C + P diag(g) (the
//! mass balance is linear), whose solution y gives the next point (u, v) = (g y, −(1 − g) y).
//! A node is *infeasible* when the sign of y disagrees with g (a full node with y < 0, a
//! cavitated one with y > 0). A piecewise-linear problem is solved exactly once no node is
//! infeasible (finite termination). Each iteration
//!
//! 1. solves A(g) y = b by the iterative solver of `adi`, started from the last y (a node the
//!    last pivot turned full from ψ = 0, step 3), to
//!    `tolerance` — but looks at its iterate on the way: from a residual of 1e-3 on
//!    (`SWITCH_CHECK_FROM` × the loose level 10⁵ × `tolerance`, at most 1e-5) it compares the
//!    iterate's switch H(y) with g after every Krylov iteration and stops at the first
//!    disagreement, until the switch agrees at the loose level; from there the solve goes on to
//!    `tolerance` in the same Krylov space (inexact Newton: a step whose switch pattern is still
//!    wrong needs no accurate solve, and the one whose pattern is right is not restarted).
//!    Measured on the compressor-size inverse cycle of the timing report (120 × 31, 1°): the
//!    loose level 1e-6 → 1e-5 of separate loose solves took the Krylov iterations per film step
//!    5.2 → 4.7 and the instructions −3.4 %; 1e-4 saved less, −2.2 %, as more switch decisions
//!    went wrong. The checks inside one solve (2026-11-29, callgrind): −4.4 % instructions of
//!    that cycle (4.6 → 4.4 Krylov iterations per film step) and −9.6 % of the warm-step bench's
//!    step (three Newton steps of 3 + 3 + 3 Krylov iterations → two of 2 + 6), the answers the
//!    same to the tolerance;
//! 2. stops if the nonlinear residual at y, with y's own switch H(y), is below the tolerance;
//! 3. else changes the switch of every infeasible node (a block pivot: the full Newton step) —
//!    unless `BLOCK_TRIES` block pivots in a row have not lowered the smallest number of
//!    infeasible nodes seen, in which case it changes only the infeasible node of least index,
//!    with a tight solve (Murty's single pivot), until the count falls below that smallest
//!    number again. This is Júdice & Pires' safeguarded block pivoting: Murty's least-index
//!    rule terminates finitely for every P-matrix LCP \[Murty1974\], and the discrete JFO
//!    problem of a time step is one (every switch pattern gives an M-matrix), so the iteration
//!    cannot cycle. (A backtracking line search on a merit function in (u, v) was tried first
//!    and dropped: the full step, which briefly raises the complementarity violation of nodes
//!    about to switch, was cut into small steps and the solve stalled — on the compressor rod
//!    bearing 100 iterations without convergence, against ≤ 15 with full steps.) A node that
//!    turns full starts the next solve at ψ = 0, where its two equations agree (p = p_cav and
//!    φ = 1), not at its y, which is of the other meaning: a cavitated node's y = φ − 1 of a
//!    few 10⁻³ (on the warm-step bench up to 0.006) read as a pressure is β y of several MPa
//!    (9 MPa at β = 1.5 GPa). A node that turns cavitated keeps its y, a small negative
//!    pressure that is a φ just below 1 (zeroing it too, whose H(0) is "full", made the next
//!    solve's switch checks see it as wrong: +5 % instructions on the inverse cycle). This
//!    changes only where the next Krylov solve starts (and a steady solve's pseudo-time
//!    anchor), not the system it solves. Measured (callgrind, 2026-11-29): the warm-step
//!    bench's start residual after the pivot fell 120× (1.5 → 0.013 of the flux scale), its
//!    step took 7 Krylov iterations instead of 8 (−6.5 % instructions); a 360-step march of
//!    that film 7.7 instead of 9.6 per step; the timing report's default inverse cycle 4.0
//!    instead of 4.4 per film step (−4.5 % instructions).
//!
//! At the returned ψ, g = H(ψ) and max_k |R_k(ψ)| ≤ `tolerance` × the flux scale (the largest
//! driving flux of a row, `Stencil::residual`): every discrete mass balance holds to the
//! tolerance and complementarity holds exactly on every node — p = p_cav + β max(ψ, 0) ≥ p_cav
//! on full nodes and φ = 1 + ψ < 1 on cavitated ones (φ ≥ 0 checked). No node is ever locked,
//! and the answer is the solution of R(ψ) = 0, not a product of the iteration path. Warm
//! starts (the previous time step, or a nearby Newton iterate of the inverse solver) need one
//! to three iterations.
//!
//! A steady film (no time term) has a singular A(g) for a switch pattern with a closed, fully
//! cavitated circumferential ring (its content only circulates), which early iterates can
//! have. Steady solves therefore add a pseudo-time term to the Newton matrix only —
//! (A(g) + D) ψ⁺ = b + D ψ, D_k = σ (|U|/2) h_k Δz_k (σ times the cell's Couette outflow),
//! σ = 0.01 · max|R(ψ)| / max|R(ψ⁰)| (switched evolution relaxation, \[MulderVanLeer1985\];
//! pseudo-transient continuation, \[KelleyKeyes1998\]) — which vanishes as the residual does:
//! the residual itself, and so the answer, are untouched. (σ₀ = 1 made the cold steady solves
//! of the tables take 10–16 iterations, σ₀ = 0.01 takes 6–8.)
//!
//! # Supply models (docs/conventions.md §8)
//!
//! [`SupplyModel::Grooves`] uses the grooves only. [`SupplyModel::AxialLineAtMaxGap`] adds a
//! full-length axial line at ambient pressure on the h_max line (opposite the eccentricity),
//! which is the problem behind the Raimondi–Boyd and Butenschön tables ("the film starts at
//! the widest gap"); the grid is turned so that node column 0 lies on that line. It is a steady
//! model: [`ReynoldsSolver::solve_step`] rejects it.

// Stencil code indexes several arrays by the same node number; iterator chains would hide the
// index maps documented above.
#![allow(clippy::needless_range_loop)]

mod adi;
mod discretization;
mod film;
mod grid;
mod multigrid;
mod oracle;
mod outputs;
mod steady_load;

use ndarray::Array2;
use thiserror::Error;

pub use crate::time_scheme::TimeScheme;
use crate::viscosity::ViscosityModel;

pub use steady_load::SteadyLoadInfo;

use adi::AdiWorkspace;
use discretization::{Level, Stencil, TimeTerm};
use film::FilmThickness;
use grid::{Grid, NodeKind};

/// A rectangular feed groove or hole, fixed in the bearing frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Groove {
    /// Angle of its centre, rad (θ from +x towards +y).
    pub center_angle: f64,
    /// Axial position of its centre, m (0 = mid-plane).
    pub center_z: f64,
    /// Circumferential extent, rad.
    pub angular_width: f64,
    /// Axial extent, m.
    pub axial_width: f64,
    /// Film fraction held in the groove when its feed pressure is ≤ p_cav (supply cut-off).
    pub cutoff_film_fraction: f64,
}

/// Where the oil comes from besides the grooves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SupplyModel {
    /// Grooves (and the ends, if p_amb > p_cav) only.
    #[default]
    Grooves,
    /// A full-length axial line at ambient pressure on the h_max line (steady solves only):
    /// the Raimondi–Boyd / Butenschön problem (docs/conventions.md §8).
    AxialLineAtMaxGap,
}

/// Linear solver of the frozen-switch systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LinearSolver {
    /// ADI line sweeps + line-aggregate coarse correction preconditioning FGMRES.
    AdiKrylov,
    /// Sparse LU (faer), the test oracle.
    SparseLu,
    /// θ-semi-coarsening multigrid V-cycle (zebra axial lines + circumferential cyclic lines,
    /// Galerkin coarse levels) preconditioning FGMRES (default): Krylov iterations per solve
    /// nearly independent of the grid (`multigrid` module docs); 17 % less time per film step
    /// than [`AdiKrylov`](Self::AdiKrylov) on the default grid, 2.2× less on 240 × 61.
    #[default]
    MultigridKrylov,
}

impl LinearSolver {
    /// The FGMRES preconditioner of an iterative choice (None for the direct oracle).
    fn preconditioner(self) -> Option<adi::Preconditioner> {
        match self {
            LinearSolver::AdiKrylov => Some(adi::Preconditioner::Adi),
            LinearSolver::MultigridKrylov => Some(adi::Preconditioner::Multigrid),
            LinearSolver::SparseLu => None,
        }
    }
}

/// Grid size: n_theta nodes around (periodic), n_z nodes along including both ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GridParams {
    pub n_theta: usize,
    pub n_z: usize,
}

impl Default for GridParams {
    /// The default grid of bearings with L/D ≥ 1/4, 120 × 31 (justified by the
    /// grid-convergence tests in `validation/`); [`GridParams::for_length_ratio`] is the
    /// default for any L/D, and what [`ReynoldsParams::plain`] and the case files use.
    fn default() -> Self {
        Self {
            n_theta: 120,
            n_z: 31,
        }
    }
}

impl GridParams {
    /// Length ratio L/D below which the default grid trades axial for circumferential nodes.
    pub const SHORT_BEARING_LENGTH_RATIO: f64 = 0.25;

    /// The validated default grid of a bearing with length ratio L/D (= B/d):
    ///
    /// ```text
    ///   L/D ≥ 1/4:  120 × 31   (n_theta × n_z)
    ///   L/D < 1/4:  160 × 23   (the same ~3 700 nodes)
    /// ```
    ///
    /// Why: at high eccentricity the pressure peak of a short bearing narrows like (1 − ε)
    /// around the thinnest film — 0.01 rad at ε = 0.99 against Δθ = 0.052 rad at 120 nodes —
    /// while its axial profile stays a parabola that few nodes resolve. Measured against
    /// 960 × 61 (Butenschön's problem, `cargo test --release -p jbearing-validation --test
    /// reynolds_tables -- --nocapture short_bearings`, written to docs/validation.md): 120 × 31
    /// is within 1.33 % in the Sommerfeld number for L/D ≥ 1/4 up to ε = 0.99, but +2.2 % at
    /// L/D 1/8 and ε 0.99 with the thinnest film on a node (−1.5 % half-way between nodes);
    /// 160 × 23 keeps L/D from 1/10 to 1/4 within 1.3 % at either position, at the same cost.
    /// Non-finite or non-positive ratios get the [`Default`] grid (the solver's parameter
    /// check rejects the length itself).
    pub fn for_length_ratio(length_over_diameter: f64) -> Self {
        if length_over_diameter > 0.0 && length_over_diameter < Self::SHORT_BEARING_LENGTH_RATIO {
            Self {
                n_theta: 160,
                n_z: 23,
            }
        } else {
            Self::default()
        }
    }
}

/// Parameters of a [`ReynoldsSolver`] (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct ReynoldsParams {
    /// Journal radius R, m.
    pub radius: f64,
    /// Bearing length L, m.
    pub length: f64,
    /// Radial clearance c, m.
    pub clearance: f64,
    /// Dynamic viscosity μ, Pa·s (constant; stored per node inside, see `viscosity_field`).
    pub viscosity: f64,
    /// Bulk modulus β, Pa (default 1.5 GPa).
    pub bulk_modulus: f64,
    /// Cavitation pressure (gauge), Pa.
    pub cavitation_pressure: f64,
    /// Ambient pressure at both ends (gauge), Pa; must be ≥ p_cav.
    pub ambient_pressure: f64,
    /// Feed grooves / holes.
    pub grooves: Vec<Groove>,
    /// Supply model.
    pub supply: SupplyModel,
    pub grid: GridParams,
    pub time_scheme: TimeScheme,
    pub linear_solver: LinearSolver,
    /// Relative tolerance of the discrete mass residual (max |r| / flux scale).
    pub tolerance: f64,
    /// Maximum semismooth Newton iterations per solve.
    pub max_newton_iterations: usize,
    /// Maximum Krylov iterations per frozen-switch solve.
    pub max_linear_iterations: usize,
    /// Viscosity that varies with temperature along the film and with pressure (Vogel–Barus,
    /// \[Benasciutti2012\]; [`crate::viscosity`]); `None`: the constant [`Self::viscosity`]. With a
    /// pressure coefficient α > 0 a steady solve iterates the viscosity field (Picard) until no
    /// node's μ changes by more than [`VISCOSITY_PICARD_TOLERANCE`]; time steps support
    /// α = 0 only.
    pub viscosity_model: Option<ViscosityModel>,
}

/// Relative change of the node viscosities below which the Picard iteration of a
/// pressure-dependent viscosity stops: μ enters the pressure flux linearly, so the film's
/// pressure is then consistent with its viscosity to about this relative accuracy.
pub const VISCOSITY_PICARD_TOLERANCE: f64 = 1e-8;
/// Most Picard iterations of a pressure-dependent viscosity per steady solve.
pub const VISCOSITY_PICARD_MAX: usize = 200;

impl ReynoldsParams {
    /// A plain bearing with the defaults: β = 1.5 GPa, p_amb = p_cav = 0, no grooves, the
    /// default grid of its L/D ([`GridParams::for_length_ratio`]), BDF2 (backward-Euler start),
    /// multigrid-Krylov, tolerance 1e-10.
    pub fn plain(radius: f64, length: f64, clearance: f64, viscosity: f64) -> Self {
        Self {
            radius,
            length,
            clearance,
            viscosity,
            bulk_modulus: 1.5e9,
            cavitation_pressure: 0.0,
            ambient_pressure: 0.0,
            grooves: Vec::new(),
            supply: SupplyModel::Grooves,
            grid: GridParams::for_length_ratio(length / (2.0 * radius)),
            time_scheme: TimeScheme::default(),
            linear_solver: LinearSolver::default(),
            tolerance: 1e-10,
            max_newton_iterations: 100,
            max_linear_iterations: 400,
            viscosity_model: None,
        }
    }
}

/// Speeds and feed of one instant: what every film (Reynolds, closed forms, the inverse and
/// mechanism film models) needs besides the journal position. One type for the whole crate
/// (re-exported as `inverse::OperatingConditions`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct OperatingConditions {
    /// Journal angular speed ω_j, rad/s (fixed frame, counter-clockwise positive).
    pub journal_speed: f64,
    /// Bearing (sleeve) angular speed ω_b, rad/s (fixed frame, counter-clockwise positive).
    pub bearing_speed: f64,
    /// Feed pressure per groove (gauge), Pa, in the order of `ReynoldsParams::grooves`.
    pub feed_pressures: Vec<f64>,
}

/// One time step: the new eccentricity, the step length and the conditions at the new time.
#[derive(Debug, Clone, PartialEq)]
pub struct StepInput {
    pub eccentricity_ratio: [f64; 2],
    pub dt: f64,
    pub conditions: OperatingConditions,
}

/// The film at one time level: eccentricity and the φ / g fields (`[n_theta, n_z]`).
#[derive(Debug, Clone, PartialEq)]
pub struct FilmState {
    pub eccentricity_ratio: [f64; 2],
    /// φ = ρ/ρ_c (full film, ≥ 1) or film fraction (cavitated, < 1).
    pub density_ratio: Array2<f64>,
    /// g: true where the film is full.
    pub full_film: Array2<bool>,
    /// Net outflow of each node at this level, m³/s (Crank–Nicolson needs it; None: the next
    /// step falls back to backward Euler once).
    pub net_outflow: Option<Array2<f64>>,
    /// Content h φ of each node at the level before this one and the step from there to this
    /// one, s (BDF2 needs them; None: the next step is a backward-Euler step).
    pub previous_level: Option<(Array2<f64>, f64)>,
    /// The gap change the film had at this level ([`ReynoldsSolver::set_deformation`] when the
    /// step was solved; None: rigid). The next step's old content h φ takes it, so that the
    /// squeeze term sees the deformation's rate.
    pub deformation: Option<FilmDeformation>,
    /// The boundary flows at this level, m³/s: side leakage at z = −L/2 and +L/2, then the
    /// supply of each groove ([`FilmSolution::side_leakage`], [`FilmSolution::supply_flow`];
    /// empty at a start state). Crank–Nicolson's next volume takes them.
    pub boundary_flow: Vec<f64>,
    /// The volume of oil that has left through each end and entered through each groove since
    /// the start state (m³, the layout of `boundary_flow`), integrated by the time scheme of
    /// each step — the same discrete time integral the scheme applies to the film content:
    ///
    /// ```text
    ///   backward Euler   Y^{n+1} = Y^n + Δt q^{n+1}
    ///   Crank–Nicolson   Y^{n+1} = Y^n + Δt (q^{n+1} + q^n)/2
    ///   BDF2             a₀ Y^{n+1} − a₁ Y^n + a₂ Y^{n−1} = Δt q^{n+1}
    /// ```
    ///
    /// so that over any steps the content's change equals the volume in minus the volume out
    /// to the film's mass balance, whatever the step lengths (variable-step BDF2 does not sum
    /// Δt q to the content's change where the step length changes: with Y it does, Y being
    /// integrated exactly as the content is). Y^{n+1} − Y^n is the step's volume: divided by
    /// Δt, the step's mean flow (for BDF2 and Crank–Nicolson ≈ the flow at mid-step).
    pub boundary_volume: Vec<f64>,
    /// `boundary_volume` at the level before (what BDF2 needs with `previous_level`).
    pub previous_boundary_volume: Option<Vec<f64>>,
}

impl FilmState {
    /// A state that is a film only: ε, φ and the switch, with no level before, no net outflow,
    /// no deformation and no boundary volumes — a run's first state
    /// ([`ReynoldsSolver::initial_state`]) or a step's start, of which the solver reads these
    /// three alone ([`ReynoldsSolver::solve_step_from`]).
    pub(crate) fn film_only(
        eccentricity_ratio: [f64; 2],
        density_ratio: Array2<f64>,
        full_film: Array2<bool>,
    ) -> Self {
        Self {
            eccentricity_ratio,
            density_ratio,
            full_film,
            net_outflow: None,
            previous_level: None,
            deformation: None,
            boundary_flow: Vec::new(),
            boundary_volume: Vec::new(),
            previous_boundary_volume: None,
        }
    }
}

/// Everything a solve returns (SI units; angles in rad; locations as (θ, z)).
#[derive(Debug, Clone, PartialEq)]
pub struct FilmSolution {
    /// Film force on the journal F = −∫∫ (p − p_amb) n R dθ dz, N (the load W = −F).
    pub film_force: [f64; 2],
    /// |F|, N.
    pub load_capacity: f64,
    /// The classical attitude angle φ (rad, (−π, π]): from the load W = −F to the eccentricity,
    /// positive in the direction of the surface motion U (Raimondi & Boyd's φ, Butenschön's β;
    /// docs/conventions.md §1).
    pub attitude_angle: f64,
    pub min_film_thickness: f64,
    pub min_film_location: [f64; 2],
    /// Largest gauge pressure, Pa.
    pub max_pressure: f64,
    pub max_pressure_location: [f64; 2],
    /// Area fraction of cavitated nodes.
    pub cavitated_fraction: f64,
    /// Oil in the film, Σ V h φ over the unknown nodes, m³ (at cavitation density).
    pub film_content: f64,
    /// Outflow at z = −L/2 and z = +L/2, m³/s (mass flux / ρ_c; positive = out).
    pub side_leakage: [f64; 2],
    /// Net flow out of each groove into the film, m³/s (negative: back-flow).
    pub supply_flow: Vec<f64>,
    /// Net flow out of the axial supply line (AxialLineAtMaxGap), else 0, m³/s.
    pub supply_line_flow: f64,
    /// Film oil arriving at the feed grooves, m³/s: the circumferential flow across each
    /// groove's leading edge (the first groove column in the direction of the surface motion),
    /// over the whole width (into the groove and past it beside it), summed over the grooves;
    /// 0 without grooves. The recirculated flow of the heat balance
    /// ([`crate::heat_balance`]).
    pub recirculated_flow: f64,
    /// Torque of the film on the journal about +z, N·m (negative: resists U > 0).
    pub friction_torque_journal: f64,
    /// Torque of the film on the bearing about +z, N·m.
    pub friction_torque_bearing: f64,
    /// Viscous dissipation ∫∫ [μU²f/h + h³/(12μ)|∇p|²] dA, W (docs/conventions.md §5).
    pub power_loss: f64,
    /// Semismooth Newton iterations of the complementarity solve (one frozen-switch linear
    /// solve each).
    pub iterations: usize,
    /// Of these, single (Murty) pivots taken by the safeguard (0 in a plain active-set run).
    pub single_pivots: usize,
    /// Krylov iterations summed over the Newton iterations.
    pub linear_iterations: usize,
    /// Final relative discrete mass residual.
    pub residual: f64,
    /// θ of the grid columns (rad) and z of the rows (m).
    pub theta: Vec<f64>,
    pub z: Vec<f64>,
    /// Gauge pressure, Pa.
    pub pressure: Array2<f64>,
    /// φ (density ratio where full, film fraction where cavitated).
    pub density_ratio: Array2<f64>,
    /// Film fraction: 1 where full, φ where cavitated.
    pub film_fraction: Array2<f64>,
    /// Switch g (1 full, 0 cavitated).
    pub switch: Array2<f64>,
}

/// Why a solve failed; variants carry the numbers.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ReynoldsError {
    #[error("invalid parameter {name} = {value:e}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    #[error(
        "mass-conserving film without any supply: p_amb = {ambient_pressure:e} Pa ≤ p_cav = \
         {cavitation_pressure:e} Pa and no groove or supply line (the film would be empty)"
    )]
    NoSupply {
        ambient_pressure: f64,
        cavitation_pressure: f64,
    },
    #[error("{got} feed pressures given for {expected} grooves")]
    FeedPressureCount { expected: usize, got: usize },
    #[error("eccentricity ratio |ε| = {magnitude} is outside [0, 1)")]
    EccentricityOutOfRange { magnitude: f64 },
    #[error("{what}")]
    Unsupported { what: &'static str },
    /// The viscosity model is unusable.
    #[error(transparent)]
    Viscosity(#[from] crate::viscosity::ViscosityError),
    /// The Picard iteration of a pressure-dependent viscosity did not converge.
    #[error(
        "pressure-dependent viscosity: Picard iteration not converged after {iterations} iterations (largest relative change of μ {change:.3e}, tolerance {tolerance:.1e})"
    )]
    ViscosityNotConverged {
        iterations: usize,
        change: f64,
        tolerance: f64,
    },
    #[error("{solver}: {detail}")]
    LinearSolve {
        solver: &'static str,
        detail: String,
    },
    #[error(
        "frozen-switch solve not converged after {iterations} Krylov iterations: residual \
         {residual:e} > tolerance {tolerance:e}"
    )]
    LinearNotConverged {
        iterations: usize,
        residual: f64,
        tolerance: f64,
    },
    #[error(
        "complementarity (JFO switch) not converged after {iterations} semismooth Newton \
         iterations: relative mass residual {residual:e} > tolerance {tolerance:e}; \
         {switched_last} of {n_unknown} nodes were infeasible in the last step"
    )]
    ComplementarityNotConverged {
        iterations: usize,
        residual: f64,
        tolerance: f64,
        switched_last: usize,
        n_unknown: usize,
    },
    #[error(
        "{what} not finite at θ index {theta_index}, z index {z_index} (iteration {iteration})"
    )]
    NonFinite {
        what: &'static str,
        theta_index: usize,
        z_index: usize,
        iteration: usize,
    },
    #[error(
        "negative film content φ = {value} at θ index {theta_index}, z index {z_index} (time step \
         too long for the squeeze, or a starved film)"
    )]
    NegativeFilmFraction {
        value: f64,
        theta_index: usize,
        z_index: usize,
    },
    /// A deformed film (a [`FilmDeformation`] added to the rigid gap) is not open everywhere.
    #[error("film closed: thickness {thickness:e} m at θ = {theta} rad (deformed film)")]
    FilmClosed { thickness: f64, theta: f64 },
    #[error(
        "steady load solve not converged after {iterations} Newton iterations: force residual \
         {force_residual:e} N at ε = ({eps_x}, {eps_y})",
        eps_x = eccentricity_ratio[0], eps_y = eccentricity_ratio[1]
    )]
    SteadyLoadNotConverged {
        iterations: usize,
        force_residual: f64,
        eccentricity_ratio: [f64; 2],
    },
}

/// The iteration-independent part of a solve ([`ReynoldsSolver::prepare`]).
pub(crate) struct Prepared {
    h: FilmThickness,
    psi: Vec<f64>,
    g: Vec<f64>,
    speed: f64,
}

/// The converged discrete film of one solve (crate internal).
/// The boundary volumes Y^{n+1} ([`FilmState::boundary_volume`]) after a step of length `dt`
/// from `state` with boundary flows `flows` at the new level, by the scheme the step took
/// (`scheme`: BDF2 only when it had the level before and kept it — not its backward-Euler start
/// or positivity fallback —, Crank–Nicolson only with the old level's net outflow). A start
/// state without volumes counts from zero; a Crank–Nicolson step from a state without flows
/// takes the new level's.
fn boundary_volume_after(
    state: &FilmState,
    dt: f64,
    flows: &[f64],
    scheme: TimeScheme,
) -> Vec<f64> {
    let n = flows.len();
    let fits = |v: &[f64]| v.len() == n;
    let old: Vec<f64> = if fits(&state.boundary_volume) {
        state.boundary_volume.clone()
    } else {
        vec![0.0; n]
    };
    match (
        scheme,
        &state.previous_level,
        &state.previous_boundary_volume,
    ) {
        (TimeScheme::Bdf2, Some((_, dt_prev)), Some(before)) if fits(before) => {
            let (a0, a1, a2) = TimeScheme::bdf2_coefficients(dt / dt_prev);
            (0..n)
                .map(|k| (dt * flows[k] + a1 * old[k] - a2 * before[k]) / a0)
                .collect()
        }
        (TimeScheme::CrankNicolson, ..) if fits(&state.boundary_flow) => (0..n)
            .map(|k| old[k] + 0.5 * dt * (flows[k] + state.boundary_flow[k]))
            .collect(),
        _ => (0..n).map(|k| old[k] + dt * flows[k]).collect(),
    }
}

pub(crate) struct Core {
    /// The solver's grid, shared, not copied per solve.
    grid: std::sync::Arc<Grid>,
    h: Vec<f64>,
    psi: Vec<f64>,
    g: Vec<f64>,
    flux_theta: Vec<f64>,
    flux_z: Vec<f64>,
    iterations: usize,
    single_pivots: usize,
    linear_iterations: usize,
    residual: f64,
}

/// The solver: parameters plus reusable workspaces (grid, stencil, Krylov/multigrid scratch).
#[derive(Debug, Clone)]
pub struct ReynoldsSolver {
    params: ReynoldsParams,
    grid: std::sync::Arc<Grid>,
    stencil: Stencil,
    ws: AdiWorkspace,
    /// μ per node: the constant viscosity, or the viscosity model at each node's temperature
    /// and at `viscosity_pressure` (set in `prepare`).
    viscosity_field: Vec<f64>,
    /// Film pressure above p_cav per node at which a pressure-dependent viscosity is evaluated
    /// (the last Picard iterate; empty: zero).
    viscosity_pressure: Vec<f64>,
    k_theta: Vec<f64>,
    k_z: Vec<f64>,
    dirichlet: Vec<f64>,
    /// The converged film of the last solve, for [`film_force_jacobian`](Self::film_force_jacobian).
    last: Option<Linearization>,
    /// ∂ψ/∂ε_x and ∂ψ/∂ε_y of the last Jacobian (the start of the next one's solves, and
    /// the first-order prediction of a nearby step's start: [`ReynoldsSolver::solve_step_from`]).
    sensitivity: [Vec<f64>; 2],
    /// The grid angle and effective time step the sensitivities were computed for (None: none
    /// computed, or a steady film's).
    sensitivity_for: Option<(f64, f64)>,
    /// Gap change of elastic surfaces added to the rigid film (steady solves and time steps;
    /// a step's old level takes the gap its state carries).
    deformation: Option<FilmDeformation>,
    /// The tolerance of the solve under way when [`ReynoldsSolver::solve_step_to`] loosened
    /// it (None: `params.tolerance`).
    step_tolerance: Option<f64>,
    /// The step under way is a trial ([`ReynoldsSolver::solve_trial_step_to`]): its friction
    /// outputs are not evaluated.
    trial: bool,
    /// A caller that reads no fields of a step's solution ([`crate::inverse::ReynoldsFilm`]
    /// when it does not capture them): the solution's `pressure`, `density_ratio`,
    /// `film_fraction` and `switch` are left empty (0 × 0) instead of built and unfolded
    /// onto the whole grid for nothing ([`ReynoldsSolver::set_step_fields`]).
    skip_step_fields: bool,
    /// Solve the half z ≤ 0 of a bearing symmetric about its mid-plane (`grid` module docs,
    /// "Mirror symmetry"): set by [`ReynoldsSolver::new`] when the parameters are.
    half: bool,
}

/// The deformed film's thinnest node (the rigid c(1 − |ε|) of `film_solution` is no longer it).
fn deformed_min_film(sol: &mut FilmSolution, core: &Core) {
    let (k, h) =
        core.h.iter().enumerate().fold(
            (0, f64::INFINITY),
            |m, (k, &h)| if h < m.1 { (k, h) } else { m },
        );
    let nz = core.grid.n_z;
    sol.min_film_thickness = h;
    sol.min_film_location = [
        core.grid
            .theta(k / nz)
            .rem_euclid(2.0 * std::f64::consts::PI),
        core.grid.z(k % nz),
    ];
}

/// A gap change g(θ) added to the rigid film thickness, h = c − e cos(θ − ψ) + g(θ) (the
/// same at every z: a plane deformation model, \[Benasciutti2012\] Fig. 5 and its text). Given by its values
/// at n equally spaced angles θ_k = 2πk/n of the bearing frame (θ from +x towards +y),
/// interpolated linearly and periodically in between. Positive g opens the gap.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmDeformation {
    values: Vec<f64>,
}

impl FilmDeformation {
    /// g at θ_k = 2πk/n, m; at least 3 finite values.
    pub fn new(values: Vec<f64>) -> Result<Self, ReynoldsError> {
        if values.len() < 3 {
            return Err(ReynoldsError::InvalidParameter {
                name: "deformation",
                value: values.len() as f64,
                reason: "needs at least 3 samples around",
            });
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(ReynoldsError::InvalidParameter {
                name: "deformation",
                value: *v,
                reason: "must be finite",
            });
        }
        Ok(Self { values })
    }

    /// The samples g(θ_k).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// g(θ), linear between the samples, periodic.
    pub fn at(&self, theta: f64) -> f64 {
        let n = self.values.len();
        let s =
            theta.rem_euclid(2.0 * std::f64::consts::PI) / (2.0 * std::f64::consts::PI) * n as f64;
        let i = (s.floor() as usize).min(n - 1);
        let t = s - i as f64;
        (1.0 - t) * self.values[i] + t * self.values[(i + 1) % n]
    }
}

/// A film-thickness change whose linear response [`ReynoldsSolver::thickness_responses`] gives.
#[derive(Debug, Clone, PartialEq)]
pub enum ThicknessChange {
    /// ∂h/∂ε_x (0) or ∂h/∂ε_y (1): −c cos θ, −c sin θ.
    Eccentricity(usize),
    /// A gap change δg, samples as in [`FilmDeformation`] (linear between them, periodic).
    Gap(FilmDeformation),
}

/// The film's linear response to a [`ThicknessChange`].
#[derive(Debug, Clone)]
pub struct ThicknessResponse {
    /// δF, N per unit of the change.
    pub film_force: [f64; 2],
    /// δp at the nodes `[[i, j]]` of the last solve's grid (zero where the pressure is
    /// imposed), Pa per unit of the change.
    pub pressure: Array2<f64>,
}

/// What the film-force Jacobian needs of the last converged solve.
#[derive(Debug, Clone)]
struct Linearization {
    eccentricity_ratio: [f64; 2],
    conditions: OperatingConditions,
    psi: Vec<f64>,
    g: Vec<f64>,
    /// Effective step of the time term (None: steady).
    dt: Option<f64>,
    /// ½ for Crank–Nicolson, else 1.
    flux_weight: f64,
}

impl ReynoldsSolver {
    /// A solver for `params`. A bearing symmetric about its mid-plane (every groove centred on
    /// it: the film is then symmetric too) is solved on the half z ≤ 0 of its grid and the
    /// answer mirrored (`grid` module docs, "Mirror symmetry"): the same discrete solution, in
    /// about two thirds of the time. Every field and integral a solve returns, and every state
    /// it takes and gives, is the whole grid's; a state given to such a solver is read on its
    /// rows z ≤ 0 (the states the solver gives are symmetric; one made by hand that is not
    /// needs [`Self::new_whole_length`]).
    pub fn new(params: ReynoldsParams) -> Result<Self, ReynoldsError> {
        let half = grid::mirror_symmetric(&params);
        Self::build(params, half)
    }

    /// [`Self::new`] solving the whole length even for a symmetric bearing (what the mirror
    /// reduction is checked against).
    pub fn new_whole_length(params: ReynoldsParams) -> Result<Self, ReynoldsError> {
        Self::build(params, false)
    }

    fn build(params: ReynoldsParams, half: bool) -> Result<Self, ReynoldsError> {
        let positive = [
            ("radius", params.radius),
            ("length", params.length),
            ("clearance", params.clearance),
            ("viscosity", params.viscosity),
            ("bulk_modulus", params.bulk_modulus),
            ("tolerance", params.tolerance),
        ];
        for (name, value) in positive {
            if !(value > 0.0 && value.is_finite()) {
                return Err(ReynoldsError::InvalidParameter {
                    name,
                    value,
                    reason: "must be positive and finite",
                });
            }
        }
        if params.ambient_pressure < params.cavitation_pressure || params.ambient_pressure.is_nan()
        {
            return Err(ReynoldsError::InvalidParameter {
                name: "ambient_pressure",
                value: params.ambient_pressure,
                reason: "must be ≥ cavitation_pressure",
            });
        }
        for g in &params.grooves {
            if !(g.cutoff_film_fraction > 0.0 && g.cutoff_film_fraction < 1.0) {
                return Err(ReynoldsError::InvalidParameter {
                    name: "cutoff_film_fraction",
                    value: g.cutoff_film_fraction,
                    reason: "must lie in (0, 1)",
                });
            }
        }
        if params.ambient_pressure <= params.cavitation_pressure
            && params.grooves.is_empty()
            && params.supply == SupplyModel::Grooves
        {
            return Err(ReynoldsError::NoSupply {
                ambient_pressure: params.ambient_pressure,
                cavitation_pressure: params.cavitation_pressure,
            });
        }
        if let Some(m) = &params.viscosity_model {
            m.validate()?;
        }
        let grid = std::sync::Arc::new(if half {
            Grid::new_half(&params, 0.0)?
        } else {
            Grid::new(&params, 0.0)?
        });
        let n = grid.len();
        Ok(Self {
            viscosity_field: vec![params.viscosity; n],
            viscosity_pressure: Vec::new(),
            params,
            grid,
            stencil: Stencil::default(),
            ws: AdiWorkspace::default(),
            k_theta: vec![0.0; n],
            k_z: vec![0.0; n],
            dirichlet: vec![0.0; n],
            last: None,
            sensitivity: [Vec::new(), Vec::new()],
            sensitivity_for: None,
            deformation: None,
            step_tolerance: None,
            trial: false,
            skip_step_fields: false,
            half,
        })
    }

    /// `state` on the solver's grid: itself, or folded onto the half grid (its rows z ≤ 0).
    fn internal_state<'a>(&self, state: &'a FilmState) -> std::borrow::Cow<'a, FilmState> {
        let grid = &self.grid;
        if grid.mirror.is_none() {
            return std::borrow::Cow::Borrowed(state);
        }
        std::borrow::Cow::Owned(remap_state(
            state,
            (grid.n_theta, grid.n_z),
            &|v| grid.fold(v),
            &|v| grid.fold(v),
            &|v| grid.fold_per_cell(v),
        ))
    }

    /// The Newton start ψ⁰ = φ − 1, g⁰ of a step on the solver's grid: the `start` film's when
    /// given (a whole-grid state, its size checked against the state's where the step begins;
    /// only its φ and switch are read, folded onto a half grid), else the old level's (`state`,
    /// already on the solver's grid).
    fn start_fields(&self, state: &FilmState, start: Option<&FilmState>) -> (Vec<f64>, Vec<f64>) {
        let on_grid = |phi: &[f64], full: &[bool]| -> (Vec<f64>, Vec<f64>) {
            (
                phi.iter().map(|phi| phi - 1.0).collect(),
                full.iter().map(|&f| if f { 1.0 } else { 0.0 }).collect(),
            )
        };
        match start {
            None => on_grid(&flat(&state.density_ratio), &flat(&state.full_film)),
            Some(f) if self.grid.mirror.is_none() => {
                on_grid(&flat(&f.density_ratio), &flat(&f.full_film))
            }
            Some(f) => on_grid(
                &self.grid.fold(&flat(&f.density_ratio)),
                &self.grid.fold(&flat(&f.full_film)),
            ),
        }
    }

    /// A state of the solver's grid on the whole grid (the inverse of
    /// [`Self::internal_state`]).
    fn external_state(&self, state: FilmState) -> FilmState {
        let grid = &self.grid;
        if grid.mirror.is_none() {
            return state;
        }
        remap_state(
            &state,
            (self.params.grid.n_theta, self.params.grid.n_z),
            &|v| grid.unfold(v),
            &|v| grid.unfold(v),
            &|v| grid.unfold_per_cell(v),
        )
    }

    /// Adds a gap change to the film of the following solves (None: the rigid film). With a
    /// deformation the eccentricity ratio may exceed 1 as long as the film stays open (a
    /// deformed bore can let the journal centre move beyond the nominal clearance,
    /// \[Benasciutti2012\] Fig. 6b). A time step solves its new level with this gap and takes
    /// its old level's from the state ([`FilmState::deformation`]), which it returns set to
    /// this one.
    pub fn set_deformation(&mut self, deformation: Option<FilmDeformation>) {
        self.deformation = deformation;
    }

    /// The gap change set by [`Self::set_deformation`].
    pub fn deformation(&self) -> Option<&FilmDeformation> {
        self.deformation.as_ref()
    }

    pub fn params(&self) -> &ReynoldsParams {
        &self.params
    }

    /// θ of the grid columns for the grid of time-stepped solves (θ_0 = 0).
    pub fn theta_nodes(&self) -> Vec<f64> {
        (0..self.params.grid.n_theta)
            .map(|i| i as f64 * 2.0 * std::f64::consts::PI / self.params.grid.n_theta as f64)
            .collect()
    }

    /// z of the grid rows (m, from the mid-plane): the end rows are the bearing ends, the
    /// others the centres of their cells.
    pub fn z_nodes(&self) -> Vec<f64> {
        (0..self.params.grid.n_z)
            .map(|j| self.grid.whole_z(j))
            .collect()
    }

    /// A full film at ambient pressure (φ = 1 + (p_amb − p_cav)/β, g = 1) at ε.
    pub fn initial_state(&self, eccentricity_ratio: [f64; 2]) -> FilmState {
        let GridParams { n_theta, n_z } = self.params.grid;
        let psi = (self.params.ambient_pressure - self.params.cavitation_pressure)
            / self.params.bulk_modulus;
        FilmState::film_only(
            eccentricity_ratio,
            Array2::from_elem((n_theta, n_z), 1.0 + psi),
            Array2::from_elem((n_theta, n_z), true),
        )
    }

    /// One implicit time step from `state` (ε and φ at t_n) to `input.eccentricity_ratio` at
    /// t_n + dt. The squeeze enters through h at both levels (docs/conventions.md §2). The iterations
    /// start from `state`'s φ and g.
    ///
    /// ```
    /// use jbearing_solvers::prelude::*;
    /// use jbearing_solvers::reynolds::StepInput;
    ///
    /// // A journal moving straight towards the wall with no rotation: the squeeze film pushes
    /// // back, against the motion.
    /// let mut params = ReynoldsParams::plain(0.02, 0.02, 20e-6, 0.02);
    /// params.grid = GridParams { n_theta: 48, n_z: 11 };
    /// params.ambient_pressure = 1e5; // the ends feed the film
    /// let mut film = ReynoldsSolver::new(params)?;
    /// let state = film.initial_state([0.0, -0.3]);
    /// let input = StepInput {
    ///     eccentricity_ratio: [0.0, -0.31],
    ///     dt: 1e-4,
    ///     conditions: OperatingConditions::default(),
    /// };
    /// let (solution, _next) = film.solve_step(&state, &input)?;
    /// assert!(solution.film_force[1] > 0.0);
    /// # Ok::<(), ReynoldsError>(())
    /// ```
    pub fn solve_step(
        &mut self,
        state: &FilmState,
        input: &StepInput,
    ) -> Result<(FilmSolution, FilmState), ReynoldsError> {
        self.solve_step_from(state, input, None)
    }

    /// [`solve_step`](Self::solve_step) with the iterations started from `start`'s φ and g
    /// instead of `state`'s: the answer of a nearby step from the same `state` (a previous
    /// Newton iterate of the inverse solver) needs fewer switch and Krylov iterations. The
    /// answer is the same discrete solution to `tolerance`; `start` must be of the same grid.
    pub fn solve_step_from(
        &mut self,
        state: &FilmState,
        input: &StepInput,
        start: Option<&FilmState>,
    ) -> Result<(FilmSolution, FilmState), ReynoldsError> {
        self.solve_step_to(state, input, start, self.params.tolerance)
    }

    /// [`solve_step_from`](Self::solve_step_from) to a looser relative mass residual
    /// `tolerance` (≥ [`ReynoldsParams::tolerance`], which a smaller or non-finite value
    /// means), for a caller that needs this step's answer only roughly (the inverse solver's
    /// Newton iterates far from their answer, [`crate::inverse::ReynoldsFilm`]). Every
    /// semismooth Newton solve of the step, and its convergence test, then use `tolerance`;
    /// the force Jacobian of the step is the derivative at that answer.
    pub fn solve_step_to(
        &mut self,
        state: &FilmState,
        input: &StepInput,
        start: Option<&FilmState>,
        tolerance: f64,
    ) -> Result<(FilmSolution, FilmState), ReynoldsError> {
        let loose = tolerance > self.params.tolerance && tolerance.is_finite();
        self.step_tolerance = loose.then_some(tolerance);
        let answer = self.solve_step_relaxed(state, input, start);
        self.step_tolerance = None;
        answer
    }

    /// [`solve_step_to`](Self::solve_step_to) for a trial whose friction torques and power
    /// loss nobody will read: an iterate of the inverse solver's Newton that is still far from
    /// its answer ([`crate::inverse::ReynoldsFilm`]'s relaxed steps, which the inverse solver
    /// never accepts). They are NaN in the solution — the dissipation sum over every face is
    /// 3.7 % of the instructions of the compressor-size inverse cycle when evaluated for every
    /// film step. Everything else is the same solution, bit for bit.
    pub(crate) fn solve_trial_step_to(
        &mut self,
        state: &FilmState,
        input: &StepInput,
        start: Option<&FilmState>,
        tolerance: f64,
    ) -> Result<(FilmSolution, FilmState), ReynoldsError> {
        self.trial = true;
        let answer = self.solve_step_to(state, input, start, tolerance);
        self.trial = false;
        answer
    }

    /// Whether the time steps' solutions carry their fields (`pressure`, `density_ratio`,
    /// `film_fraction`, `switch`; the default) or leave them empty (0 × 0) for a caller that
    /// reads only the integrals: the inverse adapter between captured steps. Steady solves
    /// always carry them.
    pub(crate) fn set_step_fields(&mut self, wanted: bool) {
        self.skip_step_fields = !wanted;
    }

    /// [`solve_step_to`](Self::solve_step_to) with its tolerance set.
    fn solve_step_relaxed(
        &mut self,
        state: &FilmState,
        input: &StepInput,
        start: Option<&FilmState>,
    ) -> Result<(FilmSolution, FilmState), ReynoldsError> {
        self.check_step(state, input)?;
        self.set_grid(0.0)?;
        // A start of another grid (checked before the fold, which assumes the whole grid).
        if let Some(f) = start
            && (f.density_ratio.len() != state.density_ratio.len()
                || f.full_film.len() != state.full_film.len())
        {
            return Err(ReynoldsError::InvalidParameter {
                name: "start",
                value: f.density_ratio.len() as f64,
                reason: "start fields do not match the grid size",
            });
        }
        let state = &*self.internal_state(state);
        let old = self.old_time_level(state, input);
        let (mut psi0, g0) = self.start_fields(state, start);
        let backward_euler = TimeTerm::Step {
            dt: input.dt,
            old_content: &old.content,
            old_outflow: old.outflow.as_deref(),
        };
        let bdf2 = old.bdf2.as_ref();
        if let Some(start) = start {
            let dt = bdf2.map_or(input.dt, |(dt_eff, _)| *dt_eff);
            self.predict_start(&mut psi0, start.eccentricity_ratio, input, dt);
        }
        let alpha = self
            .params
            .viscosity_model
            .map_or(0.0, |m| m.pressure_coefficient);
        let (core, used_bdf2) = if alpha > 0.0 {
            // Picard on the viscosity field, as in steady solves, started from the pressure of
            // the start film (the previous step's or Newton iterate's film, close to this one:
            // the low, physical branch of p ∝ μ₀ exp(α p)).
            let beta = self.params.bulk_modulus;
            self.viscosity_pressure = psi0
                .iter()
                .zip(&g0)
                .map(|(psi, g)| g * beta * psi.max(0.0))
                .collect();
            let mut warm = (psi0, g0);
            let mut change = f64::INFINITY;
            let mut converged = None;
            for _ in 0..VISCOSITY_PICARD_MAX {
                let (core, used_bdf2) =
                    self.step_core(input, bdf2, backward_euler, warm.clone())?;
                change = self.update_viscosity_pressure(&core, alpha);
                if change <= VISCOSITY_PICARD_TOLERANCE {
                    converged = Some((core, used_bdf2));
                    break;
                }
                warm = (core.psi.clone(), core.g.clone());
            }
            converged.ok_or(ReynoldsError::ViscosityNotConverged {
                iterations: VISCOSITY_PICARD_MAX,
                change,
                tolerance: VISCOSITY_PICARD_TOLERANCE,
            })?
        } else {
            self.step_core(input, bdf2, backward_euler, (psi0, g0))?
        };
        // A Crank–Nicolson step (its old level has a net outflow) reports its friction at the
        // step's midpoint (outputs module docs).
        let old_pressure = (old.outflow.is_some() && !self.trial)
            .then(|| outputs::state_pressure(&self.params, &self.grid, state));
        let friction = match &old_pressure {
            _ if self.trial => outputs::Friction::Skip,
            Some(p) => outputs::Friction::AtMidpoint(p),
            None => outputs::Friction::AtNewLevel,
        };
        let mut sol = outputs::film_solution(
            &self.params,
            &input.conditions,
            input.eccentricity_ratio,
            &core,
            &self.viscosity_field,
            friction,
            !self.skip_step_fields,
        );
        if self.deformation.is_some() {
            deformed_min_film(&mut sol, &core);
        }
        let mut new_state = self.state_after(&core, input, old.content);
        let flows: Vec<f64> = sol
            .side_leakage
            .iter()
            .chain(sol.supply_flow.iter())
            .copied()
            .collect();
        let scheme = if used_bdf2 {
            TimeScheme::Bdf2
        } else if old.outflow.is_some() {
            TimeScheme::CrankNicolson
        } else {
            TimeScheme::BackwardEuler
        };
        new_state.boundary_volume = boundary_volume_after(state, input.dt, &flows, scheme);
        new_state.previous_boundary_volume = Some(state.boundary_volume.clone());
        new_state.boundary_flow = flows;
        Ok((sol, self.external_state(new_state)))
    }

    /// A time step needs the groove supply model, a positive finite Δt, a state of this grid
    /// and |ε| < 1 at the old level (unless the old level was deformed).
    fn check_step(&self, state: &FilmState, input: &StepInput) -> Result<(), ReynoldsError> {
        if self.params.supply != SupplyModel::Grooves {
            return Err(ReynoldsError::Unsupported {
                what: "solve_step: the axial supply line at h_max is a steady model (use SupplyModel::Grooves)",
            });
        }
        if !(input.dt > 0.0 && input.dt.is_finite()) {
            return Err(ReynoldsError::InvalidParameter {
                name: "dt",
                value: input.dt,
                reason: "must be positive and finite",
            });
        }
        self.check_state_size(state)?;
        // A deformed film may carry the journal beyond the rigid clearance circle (its own
        // closure is checked where h is built).
        match state.deformation {
            None => check_eps(state.eccentricity_ratio),
            Some(_) => Ok(()),
        }
    }

    /// A state of this solver's grid (the whole grid's n_θ × n_z fields), else
    /// [`ReynoldsError::InvalidParameter`] naming the state.
    fn check_state_size(&self, state: &FilmState) -> Result<(), ReynoldsError> {
        let n = self.params.grid.n_theta * self.params.grid.n_z;
        if state.density_ratio.len() != n || state.full_film.len() != n {
            return Err(ReynoldsError::InvalidParameter {
                name: "state",
                value: state.density_ratio.len() as f64,
                reason: "state fields do not match the grid size",
            });
        }
        Ok(())
    }

    /// The film content h φ of `state` at its nodes (m; h with the state's deformation): what
    /// a BDF2 step takes as the level before ([`FilmState::previous_level`]). A state of
    /// another grid is an error.
    pub fn film_content(&self, state: &FilmState) -> Result<Array2<f64>, ReynoldsError> {
        self.check_state_size(state)?;
        let shape = state.density_ratio.dim();
        let state = &*self.internal_state(state);
        let h = FilmThickness::new(
            &self.grid,
            self.params.clearance,
            state.eccentricity_ratio,
            state.deformation.as_ref(),
        );
        let content = h
            .node
            .iter()
            .zip(state.density_ratio.iter())
            .map(|(h, phi)| h * phi)
            .collect::<Vec<f64>>();
        Ok(Array2::from_shape_vec(shape, self.grid.unfold(&content)).expect("grid shape"))
    }

    /// What the time scheme takes from the old level: the content hⁿφⁿ, the net outflow Dⁿ
    /// (Crank–Nicolson), and for BDF2 with a previous level the equivalent backward-Euler
    /// step Δt/a₀ with old content (a₁ cⁿ − a₂ cⁿ⁻¹)/a₀ ([`TimeScheme::bdf2_coefficients`]).
    fn old_time_level(&self, state: &FilmState, input: &StepInput) -> OldLevel {
        let n = self.grid.len();
        let old_h = FilmThickness::new(
            &self.grid,
            self.params.clearance,
            state.eccentricity_ratio,
            state.deformation.as_ref(),
        );
        let content: Vec<f64> = old_h
            .node
            .iter()
            .zip(state.density_ratio.iter())
            .map(|(h, phi)| h * phi)
            .collect();
        let outflow = match self.params.time_scheme {
            TimeScheme::CrankNicolson => state
                .net_outflow
                .as_ref()
                .map(|a| a.iter().copied().collect()),
            TimeScheme::BackwardEuler | TimeScheme::Bdf2 => None,
        };
        let bdf2 = match (&self.params.time_scheme, &state.previous_level) {
            (TimeScheme::Bdf2, Some((previous, dt_prev)))
                if previous.len() == n && *dt_prev > 0.0 && dt_prev.is_finite() =>
            {
                let (a0, a1, a2) = TimeScheme::bdf2_coefficients(input.dt / dt_prev);
                let history = content
                    .iter()
                    .zip(previous.iter())
                    .map(|(c, cp)| (a1 * c - a2 * cp) / a0)
                    .collect();
                Some((input.dt / a0, history))
            }
            _ => None,
        };
        OldLevel {
            content,
            outflow,
            bdf2,
        }
    }

    /// The start `start_eps`'s film moved to first order to the step's ε, on the nodes full
    /// in the start: ψ⁰ = max(0, ψ_start + Σ_c (∂ψ/∂ε_c) (ε_c − ε_start,c)), with the
    /// sensitivities of the last film-force Jacobian (the linearization the caller's Newton
    /// steps with: the start becomes its Newton prediction of the film). Only where they
    /// belong to this grid and effective time step (within 1e-12): the sensitivities solve the
    /// step's matrix, whose time term scales with 1/Δt. A start only shortens the switch and
    /// Krylov iterations; the answer is the same discrete solution to `tolerance`.
    ///
    /// Cavitated nodes keep their φ and the start's switch is kept (the prediction never
    /// crosses ψ = 0): moving them too, with sensitivities of an older switch, made the
    /// iterations longer, not shorter (compressor-size inverse row, 120 × 31, 1°: Krylov
    /// iterations per repeated step 5.3 → 6.9 with every node moved, 5.3 → 5.1 with the full
    /// ones only). Measured on the slider-crank with the Reynolds film (\[Flores2009\], two
    /// turns, 120 × 31, a fresh Jacobian every step): Krylov iterations per repeated step
    /// 4.60 → 2.81, 16 % fewer in all, 12 % less time (paired runs 11.5 / 13.1 / 12.8 s →
    /// 10.4 / 11.4 / 10.7 s); the inverse cycle's chord Jacobian is older, there it saves 1 %.
    fn predict_start(&self, psi0: &mut [f64], start_eps: [f64; 2], input: &StepInput, dt: f64) {
        let Some((theta0, dt_sens)) = self.sensitivity_for else {
            return;
        };
        let theta0_now = match self.params.supply {
            SupplyModel::Grooves => 0.0,
            SupplyModel::AxialLineAtMaxGap => return,
        };
        let n = psi0.len();
        if theta0 != theta0_now
            || (dt - dt_sens).abs() > 1e-12 * dt
            || self.sensitivity.iter().any(|s| s.len() != n)
        {
            return;
        }
        let d = [
            input.eccentricity_ratio[0] - start_eps[0],
            input.eccentricity_ratio[1] - start_eps[1],
        ];
        if d == [0.0, 0.0] || !(d[0].is_finite() && d[1].is_finite()) {
            return;
        }
        for (k, x) in psi0.iter_mut().enumerate() {
            if self.grid.kind[k] == NodeKind::Unknown && *x >= 0.0 {
                *x = (*x + self.sensitivity[0][k] * d[0] + self.sensitivity[1][k] * d[1]).max(0.0);
            }
        }
    }

    /// The film state after a step: φ and g of the converged core, its net outflow (the next
    /// Crank–Nicolson step's Dⁿ) and this step's old content (the next BDF2 step's cⁿ⁻¹); the
    /// boundary flows and volumes are set by the caller from the step's outputs.
    fn state_after(&self, core: &Core, input: &StepInput, old_content: Vec<f64>) -> FilmState {
        let mut out = vec![0.0; self.grid.len()];
        discretization::net_outflow(&core.grid, &core.flux_theta, &core.flux_z, &mut out);
        // The solver's grid (the half grid's, which the caller unfolds).
        let shape = (self.grid.n_theta, self.grid.n_z);
        let field = |v: Vec<f64>| Array2::from_shape_vec(shape, v).expect("grid shape");
        FilmState {
            eccentricity_ratio: input.eccentricity_ratio,
            density_ratio: field(core.psi.iter().map(|p| 1.0 + p).collect()),
            full_film: Array2::from_shape_vec(shape, core.g.iter().map(|&g| g > 0.5).collect())
                .expect("grid shape"),
            net_outflow: Some(field(out)),
            previous_level: Some((field(old_content), input.dt)),
            deformation: self.deformation.clone(),
            // The boundary flows and volumes need the film's outputs: the caller's.
            boundary_flow: Vec::new(),
            boundary_volume: Vec::new(),
            previous_boundary_volume: None,
        }
    }

    /// The exact Jacobian ∂F/∂ε of the film force of the last solve (a step or a steady film),
    /// N per unit eccentricity ratio, `[[∂F_x/∂ε_x, ∂F_x/∂ε_y], [∂F_y/∂ε_x, ∂F_y/∂ε_y]]`, from
    /// the converged linearization (docs/conventions.md §4):
    ///
    /// ```text
    ///   R(ψ, ε) = 0  ⇒  A(g) ∂ψ/∂ε_c = −∂R/∂ε_c |_ψ            (two right-hand sides, c = x, y)
    ///   ∂F/∂ε_c = −Σ_k w_k β g_k (∂ψ_k/∂ε_c) (cos θ_k, sin θ_k)
    /// ```
    ///
    /// A(g) is the frozen-switch matrix of the converged switch g (the generalized Jacobian of
    /// the piecewise-linear residual; exact wherever no node sits on ψ = 0), ∂R/∂ε at fixed ψ
    /// from ∂h/∂ε_x = −c cos θ, ∂h/∂ε_y = −c sin θ in the Couette flux, the pressure-flux
    /// coefficients and the time term (`discretization::residual_eccentricity_derivative`); the
    /// old level is fixed. Each right-hand side is
    /// solved by the film's own linear solver to 1e-5 of its largest entry (or `tolerance`, if
    /// looser), started from zero: Newton on ε needs the Jacobian to a few digits, not to
    /// round-off. (The previous call's ∂ψ/∂ε is no start: on the compressor-size cycle its
    /// residual was 60 … 6e4 times the zero start's — the cavity moves between calls, and
    /// an O(1) film-fraction sensitivity on a node now full weighs β-sized pressure fluxes —
    /// and the solves took 5.4 Krylov iterations from it against 5.1 from zero.) Across a
    /// switch the discrete force is continuous but only piecewise smooth: this is the
    /// derivative of the piece the answer lies on — what finite differences across a switching
    /// film cannot give.
    pub fn film_force_jacobian(&mut self) -> Result<[[f64; 2]; 2], ReynoldsError> {
        self.film_force_jacobian_to(JACOBIAN_TOLERANCE)
    }

    /// [`Self::film_force_jacobian`] with its two linear solves to `relative_tolerance` of
    /// their largest right-hand side (or the film's `tolerance`, if looser) instead of 1e-5:
    /// for a Newton iteration that needs fewer digits of its Jacobian (the inverse and
    /// slider-crank Newtons on ε take 1e-2, [`crate::inverse::ReynoldsFilm`]). The error in
    /// ∂F/∂ε is of the order of `relative_tolerance` times its size; `relative_tolerance` must
    /// lie in (0, 1).
    pub fn film_force_jacobian_to(
        &mut self,
        relative_tolerance: f64,
    ) -> Result<[[f64; 2]; 2], ReynoldsError> {
        if !(relative_tolerance > 0.0 && relative_tolerance < 1.0) {
            return Err(ReynoldsError::InvalidParameter {
                name: "film_force_jacobian_to: relative_tolerance",
                value: relative_tolerance,
                reason: "the linear solves' relative tolerance lies in (0, 1)",
            });
        }
        let responses = self.responses_to(
            &[
                ThicknessChange::Eccentricity(0),
                ThicknessChange::Eccentricity(1),
            ],
            relative_tolerance,
        )?;
        let mut jacobian = [[0.0; 2]; 2];
        for (c, r) in responses.iter().enumerate() {
            jacobian[0][c] = r.film_force[0];
            jacobian[1][c] = r.film_force[1];
        }
        Ok(jacobian)
    }

    /// The linear response of the last solve's film (a step or a steady film) to film-thickness
    /// changes δh: for each, the node pressures' and the film force's derivatives,
    ///
    /// ```text
    ///   A(g) δψ = −∂R/∂h · δh,   δp_k = β g_k δψ_k,   δF = −Σ_k w_k δp_k (cos θ_k, sin θ_k)
    /// ```
    ///
    /// on the converged switch g and the old level fixed — the linearization of
    /// [`Self::film_force_jacobian`] (which is this with δh = ∂h/∂ε_x, ∂h/∂ε_y), for any δh. A
    /// gap change δg ([`ThicknessChange::Gap`]) enters the film exactly as h does (h = c −
    /// e cos(θ − ψ) + g), so this is ∂p/∂g · δg of the deformable film. One linear solve per
    /// change, to 1e-5 of its largest right-hand side (as the Jacobian's), from zero.
    pub fn thickness_responses(
        &mut self,
        changes: &[ThicknessChange],
    ) -> Result<Vec<ThicknessResponse>, ReynoldsError> {
        self.responses_to(changes, JACOBIAN_TOLERANCE)
    }

    /// [`Self::thickness_responses`] with its linear solves to `relative_tolerance`.
    fn responses_to(
        &mut self,
        changes: &[ThicknessChange],
        relative_tolerance: f64,
    ) -> Result<Vec<ThicknessResponse>, ReynoldsError> {
        let lin = self.last.clone().ok_or(ReynoldsError::Unsupported {
            what: "film_force_jacobian: no film has been solved yet",
        })?;
        if let Some(ThicknessChange::Eccentricity(c)) = changes
            .iter()
            .find(|c| matches!(c, ThicknessChange::Eccentricity(k) if *k > 1))
        {
            return Err(ReynoldsError::InvalidParameter {
                name: "ThicknessChange::Eccentricity",
                value: *c as f64,
                reason: "the direction is 0 (x) or 1 (y)",
            });
        }
        // The sensitivities are the predictor's only when both directions are of this film (a
        // call with gap changes only leaves them alone).
        if changes
            .iter()
            .any(|c| matches!(c, ThicknessChange::Eccentricity(_)))
        {
            self.sensitivity_for = None;
        }
        let prep = self.prepare(lin.eccentricity_ratio, &lin.conditions, None)?;
        let n = self.grid.len();
        let zeros = vec![0.0; n];
        let pressure: Vec<f64> = lin.psi.iter().zip(&lin.g).map(|(x, g)| x * g).collect();
        let mut out = Vec::with_capacity(changes.len());
        let mut dh_node = vec![0.0; n];
        let mut dh_face = vec![0.0; n];
        let mut d_res = vec![0.0; n];
        for change in changes {
            thickness_change(
                &self.grid,
                self.params.clearance,
                change,
                &mut dh_node,
                &mut dh_face,
            );
            self.assemble_response(
                &lin,
                &prep,
                [&dh_node, &dh_face],
                &pressure,
                &zeros,
                &mut d_res,
            );
            let x = self.solve_response(change, &lin, relative_tolerance)?;
            let (force, dp) = self.reduce_response(&lin.g, &x);
            if let ThicknessChange::Eccentricity(c) = change {
                self.sensitivity[*c] = x;
            }
            if force.iter().any(|v| !v.is_finite()) {
                return Err(ReynoldsError::NonFinite {
                    what: "film-force Jacobian",
                    theta_index: 0,
                    z_index: 0,
                    iteration: 0,
                });
            }
            out.push(ThicknessResponse {
                film_force: force,
                pressure: dp,
            });
        }
        if [0, 1].iter().all(|d| {
            changes
                .iter()
                .any(|c| matches!(c, ThicknessChange::Eccentricity(k) if k == d))
        }) {
            self.sensitivity_for = lin.dt.map(|dt| (self.grid.theta0, dt));
        }
        Ok(out)
    }

    /// Stage of [`Self::thickness_responses`]: the right-hand side −∂R/∂h · δh of its first
    /// equation into `d_res` and the stencil's, and the matrix A(g) on the converged switch
    /// with the old level fixed (zero) into the stencil; `dh` is δh at the nodes and at their
    /// east θ-faces, `pressure` the converged ψ g.
    fn assemble_response(
        &mut self,
        lin: &Linearization,
        prep: &Prepared,
        dh: [&[f64]; 2],
        pressure: &[f64],
        zeros: &[f64],
        d_res: &mut [f64],
    ) {
        let [dh_node, dh_face] = dh;
        let level = Level {
            grid: &self.grid,
            h: &prep.h.node,
            h_face: &prep.h.face_theta,
            k_theta: &self.k_theta,
            k_z: &self.k_z,
            speed: prep.speed,
        };
        let time = match lin.dt {
            None => TimeTerm::Steady,
            Some(dt) => TimeTerm::Step {
                dt,
                old_content: zeros,
                old_outflow: (lin.flux_weight < 1.0).then_some(zeros),
            },
        };
        discretization::residual_eccentricity_derivative(
            &level,
            dh_node,
            dh_face,
            &lin.psi,
            pressure,
            lin.flux_weight,
            lin.dt,
            d_res,
        );
        discretization::assemble(&level, &lin.g, zeros, time, &mut self.stencil);
        for k in 0..self.grid.len() {
            self.stencil.rhs[k] = -d_res[k];
        }
    }

    /// Stage of [`Self::thickness_responses`]: solves A(g) δψ = −∂R/∂h · δh (assembled by
    /// [`Self::assemble_response`]) to `relative_tolerance` (1e-5 for the public responses) of
    /// its largest right-hand side, from zero.
    fn solve_response(
        &mut self,
        change: &ThicknessChange,
        lin: &Linearization,
        relative_tolerance: f64,
    ) -> Result<Vec<f64>, ReynoldsError> {
        let p = &self.params;
        let mut x = match change {
            // The old sensitivity's memory, not its values (the doc of `film_force_jacobian`).
            ThicknessChange::Eccentricity(c) => std::mem::take(&mut self.sensitivity[*c]),
            ThicknessChange::Gap(_) => Vec::new(),
        };
        x.clear();
        x.resize(self.grid.len(), 0.0);
        match p.linear_solver.preconditioner() {
            Some(pc) => {
                adi::solve_krylov(
                    &self.grid,
                    &self.stencil,
                    &mut x,
                    adi::KrylovStop {
                        tolerance: relative_tolerance.max(p.tolerance),
                        flux_scale: None,
                        max_iterations: p.max_linear_iterations,
                        switch_check: None,
                    },
                    pc,
                    Some(&lin.g),
                    &mut self.ws,
                )?;
            }
            None => oracle::solve_lu(&self.grid, &self.stencil, &mut x)?,
        }
        Ok(x)
    }

    /// Stage of [`Self::thickness_responses`]: δp_k = β g_k δψ_k at the unknown nodes and
    /// δF = −Σ_k w_k δp_k (cos θ_k, sin θ_k), its last two equations.
    fn reduce_response(&self, g: &[f64], x: &[f64]) -> ([f64; 2], Array2<f64>) {
        let grid = &self.grid;
        let nz = grid.n_z;
        let mut force = [0.0; 2];
        let mut dp = vec![0.0; grid.len()];
        for i in 0..grid.n_theta {
            let trig = grid.column_trig[i];
            for j in 0..nz {
                let k = i * nz + j;
                if grid.kind[k] == NodeKind::Unknown {
                    let d = self.params.bulk_modulus * g[k] * x[k];
                    force[0] -= grid.area_weight[k] * d * trig.cos;
                    force[1] -= grid.area_weight[k] * d * trig.sin;
                    dp[k] = d;
                }
            }
        }
        let two = grid.mirror_factor();
        let shape = (self.params.grid.n_theta, self.params.grid.n_z);
        let dp = Array2::from_shape_vec(shape, grid.unfold(&dp)).expect("grid shape");
        ([two * force[0], two * force[1]], dp)
    }

    /// The steady film (no squeeze) at ε, from a cold start.
    ///
    /// ```
    /// use jbearing_solvers::prelude::*;
    ///
    /// let mut params = ReynoldsParams::plain(0.02, 0.02, 20e-6, 0.02);
    /// params.grid = GridParams { n_theta: 48, n_z: 11 };
    /// params.supply = SupplyModel::AxialLineAtMaxGap;
    /// let mut film = ReynoldsSolver::new(params)?;
    /// let rotation = OperatingConditions { journal_speed: 300.0, ..Default::default() };
    /// let solution = film.solve_steady([0.0, -0.6], &rotation)?;
    /// // Counter-clockwise rotation: the load line lies behind the journal, 0 < φ < 90°, and the
    /// // film cavitates in the diverging gap.
    /// let phi = solution.attitude_angle.to_degrees();
    /// assert!(phi > 0.0 && phi < 90.0 && solution.cavitated_fraction > 0.2);
    /// # Ok::<(), ReynoldsError>(())
    /// ```
    pub fn solve_steady(
        &mut self,
        eccentricity_ratio: [f64; 2],
        conditions: &OperatingConditions,
    ) -> Result<FilmSolution, ReynoldsError> {
        let core = self.steady_core(eccentricity_ratio, conditions)?;
        let mut sol = outputs::film_solution(
            &self.params,
            conditions,
            eccentricity_ratio,
            &core,
            &self.viscosity_field,
            outputs::Friction::AtNewLevel,
            true,
        );
        if self.deformation.is_some() {
            deformed_min_film(&mut sol, &core);
        }
        Ok(sol)
    }

    /// [`Self::solve_steady_load`] started from `start` (ε) instead of the default start
    /// (a previous answer of a nearby problem, e.g. the last deformation's).
    pub fn solve_steady_load_from(
        &mut self,
        load: [f64; 2],
        conditions: &OperatingConditions,
        start: [f64; 2],
    ) -> Result<(FilmSolution, SteadyLoadInfo), ReynoldsError> {
        steady_load::solve_from(self, load, conditions, Some(start))
    }

    /// The steady eccentricity that carries the constant load `load` (the force the machine
    /// applies to the journal, N), by Newton on (ε_x, ε_y).
    ///
    /// ```
    /// use jbearing_solvers::prelude::*;
    ///
    /// let mut params = ReynoldsParams::plain(0.02, 0.02, 20e-6, 0.02);
    /// params.grid = GridParams { n_theta: 48, n_z: 11 };
    /// params.supply = SupplyModel::AxialLineAtMaxGap;
    /// let mut film = ReynoldsSolver::new(params)?;
    /// let rotation = OperatingConditions { journal_speed: 300.0, ..Default::default() };
    /// let (light, _) = film.solve_steady_load([0.0, -500.0], &rotation)?;
    /// let (heavy, info) = film.solve_steady_load([0.0, -5000.0], &rotation)?;
    /// // More load, thinner film; the film carries the load to the tolerance.
    /// assert!(heavy.min_film_thickness < light.min_film_thickness);
    /// assert!(info.force_residual < 1e-6 * 5000.0);
    /// # Ok::<(), ReynoldsError>(())
    /// ```
    pub fn solve_steady_load(
        &mut self,
        load: [f64; 2],
        conditions: &OperatingConditions,
    ) -> Result<(FilmSolution, SteadyLoadInfo), ReynoldsError> {
        steady_load::solve(self, load, conditions)
    }

    /// One time step's discrete problem at the current viscosity field: BDF2 when the state
    /// has a previous level (`bdf2`: Δt/a₀ and the history), with backward Euler as the
    /// positivity fallback; backward Euler (or Crank–Nicolson) otherwise. Returns the core and
    /// whether it is a BDF2 step.
    fn step_core(
        &mut self,
        input: &StepInput,
        bdf2: Option<&(f64, Vec<f64>)>,
        backward_euler: TimeTerm<'_>,
        start: (Vec<f64>, Vec<f64>),
    ) -> Result<(Core, bool), ReynoldsError> {
        if let Some((dt_eff, history)) = bdf2 {
            let time = TimeTerm::Step {
                dt: *dt_eff,
                old_content: history,
                old_outflow: None,
            };
            match self.solve_core(
                input.eccentricity_ratio,
                &input.conditions,
                time,
                Some(start.clone()),
            ) {
                // Positivity fallback: the same step by backward Euler, below.
                Err(ReynoldsError::NegativeFilmFraction { .. }) => {}
                other => return other.map(|core| (core, true)),
            }
        }
        self.solve_core(
            input.eccentricity_ratio,
            &input.conditions,
            backward_euler,
            Some(start),
        )
        .map(|core| (core, false))
    }

    /// One Picard update of the viscosity field's pressure: the pressures above p_cav of the
    /// film `core` become the pressures μ is evaluated at; returns the largest factor
    /// |exp(α Δp) − 1| by which a node's μ changes with them.
    fn update_viscosity_pressure(&mut self, core: &Core, alpha: f64) -> f64 {
        let beta = self.params.bulk_modulus;
        let change = core
            .psi
            .iter()
            .zip(&self.viscosity_pressure)
            .map(|(psi, p_old)| (alpha * (beta * psi.max(0.0) - p_old)).exp_m1().abs())
            .fold(0.0, f64::max);
        self.viscosity_pressure = core.psi.iter().map(|psi| beta * psi.max(0.0)).collect();
        change
    }

    fn steady_core(
        &mut self,
        eccentricity_ratio: [f64; 2],
        conditions: &OperatingConditions,
    ) -> Result<Core, ReynoldsError> {
        let speed = self.params.radius * (conditions.journal_speed - conditions.bearing_speed);
        if speed == 0.0 || !speed.is_finite() {
            return Err(ReynoldsError::InvalidParameter {
                name: "journal_speed − bearing_speed",
                value: speed,
                reason: "a steady film needs a surface speed (a pure squeeze has no steady state)",
            });
        }
        let alpha = self
            .params
            .viscosity_model
            .map_or(0.0, |m| m.pressure_coefficient);
        if alpha == 0.0 {
            return self.solve_core(eccentricity_ratio, conditions, TimeTerm::Steady, None);
        }
        // Picard on the viscosity field: solve with μ at the last pressure, re-evaluate μ at the
        // new pressure, until no node's μ moves by more than the tolerance. Every solve starts
        // from the ambient-pressure viscosity μ₀(T): from below, Picard climbs monotonically to
        // the low (physical) fixed point of p ∝ μ₀ exp(α p); a start from another film's
        // pressure (the grid turns with ε under the supply line) could lie above the unstable
        // high branch and run away.
        let n = self.grid.len();
        self.viscosity_pressure = vec![0.0; n];
        let mut warm = None;
        let mut change = f64::INFINITY;
        for _ in 0..VISCOSITY_PICARD_MAX {
            let core = self.solve_core(eccentricity_ratio, conditions, TimeTerm::Steady, warm)?;
            change = self.update_viscosity_pressure(&core, alpha);
            if change <= VISCOSITY_PICARD_TOLERANCE {
                return Ok(core);
            }
            warm = Some((core.psi.clone(), core.g.clone()));
        }
        Err(ReynoldsError::ViscosityNotConverged {
            iterations: VISCOSITY_PICARD_MAX,
            change,
            tolerance: VISCOSITY_PICARD_TOLERANCE,
        })
    }

    fn set_grid(&mut self, theta0: f64) -> Result<(), ReynoldsError> {
        if self.grid.theta0 != theta0 {
            self.grid = std::sync::Arc::new(if self.half {
                Grid::new_half(&self.params, theta0)?
            } else {
                Grid::new(&self.params, theta0)?
            });
        }
        Ok(())
    }

    /// The semismooth Newton solve of the complementarity problem (module docs).
    /// Everything of a solve that does not depend on the iteration: the grid (turned for the
    /// supply line), h at nodes and faces, the face coefficients β h³/(12μ), the Dirichlet
    /// values, and the start (ψ, g) — `warm`'s, or a full film at ambient — with its Dirichlet
    /// entries set.
    fn prepare(
        &mut self,
        eps: [f64; 2],
        conditions: &OperatingConditions,
        warm: Option<(Vec<f64>, Vec<f64>)>,
    ) -> Result<Prepared, ReynoldsError> {
        self.check_conditions(eps, conditions)?;
        let p = &self.params;
        let theta0 = match p.supply {
            SupplyModel::Grooves => 0.0,
            SupplyModel::AxialLineAtMaxGap => {
                if eps[0] == 0.0 && eps[1] == 0.0 {
                    0.0
                } else {
                    (-eps[1]).atan2(-eps[0])
                }
            }
        };
        self.set_grid(theta0)?;
        let h = FilmThickness::new(
            &self.grid,
            self.params.clearance,
            eps,
            self.deformation.as_ref(),
        );
        if self.deformation.is_some() {
            h.check_positive(&self.grid)?;
        }
        self.set_viscosity_field(eps, conditions);
        self.set_face_coefficients(&h);
        let (psi, g) = self.boundary_values(conditions, warm);
        let speed = self.params.radius * (conditions.journal_speed - conditions.bearing_speed);
        Ok(Prepared { h, psi, g, speed })
    }

    /// |ε| < 1 (any finite ε with a deformation, whose gap is checked instead), one finite feed
    /// pressure per groove.
    fn check_conditions(
        &self,
        eps: [f64; 2],
        conditions: &OperatingConditions,
    ) -> Result<(), ReynoldsError> {
        match &self.deformation {
            None => check_eps(eps)?,
            Some(_) if !(eps[0].is_finite() && eps[1].is_finite()) => {
                return Err(ReynoldsError::EccentricityOutOfRange {
                    magnitude: eps[0].hypot(eps[1]),
                });
            }
            Some(_) => {}
        }
        let p = &self.params;
        if conditions.feed_pressures.len() != p.grooves.len() {
            return Err(ReynoldsError::FeedPressureCount {
                expected: p.grooves.len(),
                got: conditions.feed_pressures.len(),
            });
        }
        for &pf in &conditions.feed_pressures {
            if !pf.is_finite() {
                return Err(ReynoldsError::InvalidParameter {
                    name: "feed_pressures",
                    value: pf,
                    reason: "must be finite",
                });
            }
        }
        Ok(())
    }

    /// μ per node from the viscosity model (when there is one): its temperature at the node's
    /// angle from the supply in the direction of the surface motion (the supply line at h_max,
    /// else the first groove's centre, else — fed from the ends — h_max), at the last Picard
    /// pressure.
    fn set_viscosity_field(&mut self, eps: [f64; 2], conditions: &OperatingConditions) {
        let p = &self.params;
        let Some(model) = &p.viscosity_model else {
            return;
        };
        let grid = &self.grid;
        let nz = grid.n_z;
        let supply = match (p.supply, p.grooves.first()) {
            (SupplyModel::AxialLineAtMaxGap, _) | (SupplyModel::Grooves, None) => {
                (-eps[1]).atan2(-eps[0])
            }
            (SupplyModel::Grooves, Some(g)) => g.center_angle,
        };
        let sign = if conditions.journal_speed - conditions.bearing_speed < 0.0 {
            -1.0
        } else {
            1.0
        };
        for k in 0..grid.len() {
            let pressure = self.viscosity_pressure.get(k).copied().unwrap_or(0.0);
            self.viscosity_field[k] = model.at_cell(
                grid.theta(k / nz),
                0.5 * grid.d_theta,
                supply,
                sign,
                pressure,
            );
        }
    }

    /// The pressure-flux coefficients β h³/(12 μ) at the east θ-faces (exact face h) and the
    /// north z-faces (mean h), μ the mean of the two nodes'.
    fn set_face_coefficients(&mut self, h: &FilmThickness) {
        let grid = &self.grid;
        let (beta, nz) = (self.params.bulk_modulus, grid.n_z);
        let mu = &self.viscosity_field;
        let nt = grid.n_theta;
        for i in 0..nt {
            let ie = if i + 1 == nt { 0 } else { i + 1 };
            for j in 0..nz {
                let k = i * nz + j;
                let mu_e = 0.5 * (mu[k] + mu[ie * nz + j]);
                self.k_theta[k] =
                    grid.theta_face_factor[k] * beta * h.face_theta[k].powi(3) / (12.0 * mu_e);
                if j + 1 < nz {
                    let hf = 0.5 * (h.node[k] + h.node[k + 1]);
                    let mu_n = 0.5 * (mu[k] + mu[k + 1]);
                    self.k_z[k] = grid.z_face_factor[k] * beta * hf.powi(3) / (12.0 * mu_n);
                } else {
                    self.k_z[k] = 0.0;
                }
            }
        }
    }

    /// The Dirichlet values ψ and switch g: ambient at the ends and on the supply line; the
    /// feed pressure in a groove, or its cut-off film fraction when the feed is below p_cav.
    /// The Newton start is `warm` (ψ, g) or a full film at ambient, with these values imposed.
    fn boundary_values(
        &mut self,
        conditions: &OperatingConditions,
        warm: Option<(Vec<f64>, Vec<f64>)>,
    ) -> (Vec<f64>, Vec<f64>) {
        let p = &self.params;
        let (grid, beta) = (&self.grid, p.bulk_modulus);
        let n = grid.len();
        let psi_amb = (p.ambient_pressure - p.cavitation_pressure) / beta;
        let (mut psi, mut g) = match warm {
            Some((psi, g)) => (psi, g),
            None => (vec![psi_amb.max(0.0); n], vec![1.0; n]),
        };
        for k in 0..n {
            match grid.kind[k] {
                NodeKind::Unknown => {}
                NodeKind::End | NodeKind::SupplyLine => {
                    self.dirichlet[k] = psi_amb;
                    psi[k] = psi_amb;
                    g[k] = 1.0;
                }
                NodeKind::Groove(gi) => {
                    let pf = conditions.feed_pressures[gi as usize];
                    if pf > p.cavitation_pressure {
                        self.dirichlet[k] = (pf - p.cavitation_pressure) / beta;
                        g[k] = 1.0;
                    } else {
                        self.dirichlet[k] = p.grooves[gi as usize].cutoff_film_fraction - 1.0;
                        g[k] = 0.0;
                    }
                    psi[k] = self.dirichlet[k];
                }
            }
        }
        (psi, g)
    }

    /// The complementarity problem of one solve (module docs): the prepared film, the
    /// semismooth Newton on the switch ([`ReynoldsSolver::complementarity_newton`]), the check
    /// φ ≥ 0, the face fluxes, and the converged linearization kept for the force Jacobian.
    fn solve_core(
        &mut self,
        eps: [f64; 2],
        conditions: &OperatingConditions,
        time: TimeTerm,
        warm: Option<(Vec<f64>, Vec<f64>)>,
    ) -> Result<Core, ReynoldsError> {
        let Prepared { h, psi, g, speed } = self.prepare(eps, conditions, warm)?;
        let (psi, g, newton, residual) = self.complementarity_newton(&h, speed, psi, g, time)?;
        let grid = &self.grid;
        let (n, nz) = (grid.len(), grid.n_z);
        // φ ≥ 0 (up to the solve tolerance).
        if let Some(k) = (0..n).find(|&k| psi[k] < -1.0 - 1e-9) {
            return Err(ReynoldsError::NegativeFilmFraction {
                value: 1.0 + psi[k],
                theta_index: k / nz,
                z_index: k % nz,
            });
        }
        let level = Level {
            grid,
            h: &h.node,
            h_face: &h.face_theta,
            k_theta: &self.k_theta,
            k_z: &self.k_z,
            speed,
        };
        let mut flux_theta = vec![0.0; n];
        let mut flux_z = vec![0.0; n];
        discretization::face_fluxes(&level, &g, &psi, &mut flux_theta, &mut flux_z);
        self.last = Some(Linearization {
            eccentricity_ratio: eps,
            conditions: conditions.clone(),
            psi: psi.clone(),
            g: g.clone(),
            dt: match time {
                TimeTerm::Steady => None,
                TimeTerm::Step { dt, .. } => Some(dt),
            },
            flux_weight: match time {
                TimeTerm::Step {
                    old_outflow: Some(_),
                    ..
                } => 0.5,
                _ => 1.0,
            },
        });
        Ok(Core {
            grid: std::sync::Arc::clone(&self.grid),
            h: h.node,
            psi,
            g,
            flux_theta,
            flux_z,
            iterations: newton.iterations,
            single_pivots: newton.single_pivots,
            linear_iterations: newton.linear_iterations,
            residual,
        })
    }

    /// Semismooth Newton = primal–dual active set = block principal pivoting on the switch g,
    /// with Murty's single pivots as the safeguard (module docs): each step solves the
    /// frozen-switch system ([`FrozenSwitch::solve`]), resets g = H(y), and stops when the
    /// nonlinear residual at y with its own switch is below the tolerance. Returns ψ, g, the
    /// counts and the final scaled residual.
    fn complementarity_newton(
        &mut self,
        h: &FilmThickness,
        speed: f64,
        mut psi: Vec<f64>,
        mut g: Vec<f64>,
        time: TimeTerm,
    ) -> Result<(Vec<f64>, Vec<f64>, NewtonCounts, f64), ReynoldsError> {
        let tolerance = self.step_tolerance.unwrap_or(self.params.tolerance);
        let mut frozen = self.frozen_switch(h, speed, time);
        let p = frozen.params;
        let grid = frozen.level.grid;
        let n_unknown = grid
            .kind
            .iter()
            .filter(|&&k| k == NodeKind::Unknown)
            .count();
        let mut newton = NewtonCounts::default();
        set_switch(grid, &psi, &mut g);
        let loose = (tolerance * 1e5).min(1e-5).max(tolerance);
        let always_tight = p.linear_solver == LinearSolver::SparseLu;
        let mut tight = always_tight;
        let mut g_new = g.clone();
        let mut last_residual = f64::NAN;
        let mut rule = PivotRule {
            fewest_infeasible: usize::MAX,
            block_tries: BLOCK_TRIES,
        };
        let residual = loop {
            if newton.iterations >= p.max_newton_iterations {
                return Err(ReynoldsError::ComplementarityNotConverged {
                    iterations: newton.iterations,
                    residual: last_residual,
                    tolerance,
                    switched_last: newton.switched_last,
                    n_unknown,
                });
            }
            newton.iterations += 1;
            // To the tolerance; unless a single pivot asked for an exact solve, stopped on the
            // way at the loose level if the switch is wrong there (module docs).
            let switch_check = (!tight).then_some([SWITCH_CHECK_FROM * loose, loose]);
            let (y, scale) = frozen.solve(&g, &psi, tolerance, switch_check, &mut newton)?;
            // The infeasible nodes: where the sign of y disagrees with g.
            g_new.copy_from_slice(&g);
            let infeasible = set_switch(grid, &y, &mut g_new);
            newton.switched_last = infeasible;
            // The nonlinear residual at y with its own switch H(y): converged if small (also
            // when nodes with |ψ| at round-off level flip between equally valid states).
            let rmax = frozen.residual(&g_new, &y);
            last_residual = if scale > 0.0 { rmax / scale } else { 0.0 };
            psi = y;
            if rmax <= tolerance * scale || scale == 0.0 {
                g.copy_from_slice(&g_new);
                break last_residual;
            }
            if infeasible == 0 {
                // The switch is right: solve it tightly (one more Newton step, same g).
                tight = true;
                continue;
            }
            tight = rule.pivot(infeasible, &mut g, &g_new, &mut psi, &mut newton) || always_tight;
        };
        Ok((psi, g, newton, residual))
    }

    /// The frozen-switch system of [`Self::complementarity_newton`] on the level of film
    /// thickness `h`, surface speed `speed` and time term `time`, borrowing the solver's
    /// stencil and workspace.
    fn frozen_switch<'a>(
        &'a mut self,
        h: &'a FilmThickness,
        speed: f64,
        time: TimeTerm<'a>,
    ) -> FrozenSwitch<'a> {
        let Self {
            params,
            grid,
            stencil,
            ws,
            k_theta,
            k_z,
            dirichlet,
            ..
        } = self;
        FrozenSwitch {
            level: Level {
                grid,
                h: &h.node,
                h_face: &h.face_theta,
                k_theta,
                k_z,
                speed,
            },
            params,
            dirichlet,
            time,
            stencil,
            ws,
            r: vec![0.0; grid.len()],
            first_residual: f64::NAN,
            assembled_for: Vec::new(),
            solved_residual: None,
            changed_columns: Vec::new(),
        }
    }
}

/// One Newton step's frozen-switch system A(g) y = b and its residual, with the solver's
/// stencil and workspace borrowed.
struct FrozenSwitch<'a> {
    level: Level<'a>,
    params: &'a ReynoldsParams,
    dirichlet: &'a [f64],
    time: TimeTerm<'a>,
    stencil: &'a mut Stencil,
    ws: &'a mut AdiWorkspace,
    /// Residual scratch.
    r: Vec<f64>,
    /// The first step's residual, the reference of the steady solves' shift.
    first_residual: f64,
    /// The switch the stencil holds A(g) of, unshifted (empty: none, or shifted). The Newton
    /// loop assembles A(H(y)) for the residual at y and, after a block pivot or an unchanged
    /// switch, solves the next step with that very matrix: assembled once, not twice.
    assembled_for: Vec<f64>,
    /// max|r| of the last Krylov solve's answer under the (unshifted) matrix of
    /// `assembled_for`, which [`FrozenSwitch::residual`] at that answer and switch would
    /// recompute.
    solved_residual: Option<f64>,
    /// Scratch of [`FrozenSwitch::assemble`]: the θ-columns to re-assemble.
    changed_columns: Vec<bool>,
}

impl FrozenSwitch<'_> {
    /// Assemble A(g) at ψ, add the steady solves' pseudo-transient shift (A + D) y = b + D ψ
    /// (module docs), and solve to `linear_tolerance` (Krylov with the configured
    /// preconditioner, or the sparse-LU oracle). Returns y and the residual scale; a non-finite
    /// y is an error naming the node and the Newton step.
    fn solve(
        &mut self,
        g: &[f64],
        psi: &[f64],
        linear_tolerance: f64,
        switch_check: Option<[f64; 2]>,
        newton: &mut NewtonCounts,
    ) -> Result<(Vec<f64>, f64), ReynoldsError> {
        let (grid, speed) = (self.level.grid, self.level.speed);
        let (n, nz) = (grid.len(), grid.n_z);
        self.assemble(g);
        let p = self.params;
        let steady = matches!(self.time, TimeTerm::Steady);
        // The residual scale at ψ: a time step's Krylov solve measures it itself, at its start
        // (the unshifted matrix, from ψ: the same number; its residual there is the first
        // thing it computes, which this would compute twice); a steady solve's shift needs the
        // residual first, and the sparse-LU oracle measures none.
        let (mut rmax_now, mut scale) = (f64::NAN, f64::NAN);
        if steady || p.linear_solver.preconditioner().is_none() {
            (rmax_now, scale) = self.stencil.residual(grid, psi, &mut self.r);
            if !self.first_residual.is_finite() {
                self.first_residual = rmax_now.max(f64::MIN_POSITIVE);
            }
        }
        if steady {
            self.assembled_for.clear();
            let sigma = STEADY_SHIFT * (rmax_now / self.first_residual).min(1.0);
            for k in 0..n {
                if grid.kind[k] == NodeKind::Unknown {
                    let d = sigma * 0.5 * speed.abs() * self.level.h[k] * grid.row_width(k % nz);
                    self.stencil.p[k] += d;
                    self.stencil.rhs[k] += d * psi[k];
                }
            }
        }
        let mut y = psi.to_vec();
        match p.linear_solver.preconditioner() {
            Some(pc) => {
                let info = adi::solve_krylov(
                    grid,
                    self.stencil,
                    &mut y,
                    adi::KrylovStop {
                        tolerance: linear_tolerance,
                        flux_scale: steady.then_some(scale),
                        max_iterations: p.max_linear_iterations,
                        switch_check,
                    },
                    pc,
                    Some(g),
                    self.ws,
                )?;
                scale = info.scale;
                newton.linear_iterations += info.iterations;
                self.solved_residual = (!self.assembled_for.is_empty()).then_some(info.residual);
            }
            None => {
                self.solved_residual = None;
                oracle::solve_lu(grid, self.stencil, &mut y)?;
            }
        }
        if let Some(k) = y.iter().position(|x| !x.is_finite()) {
            return Err(ReynoldsError::NonFinite {
                what: "ψ = φ − 1",
                theta_index: k / nz,
                z_index: k % nz,
                iteration: newton.iterations,
            });
        }
        Ok((y, scale))
    }

    /// The nonlinear residual's max norm at `y`, the answer of the last [`FrozenSwitch::solve`],
    /// with switch `g`: the Krylov solve's own final residual when g is the switch it solved
    /// with (nothing switched), else A(g) y − b assembled anew.
    fn residual(&mut self, g: &[f64], y: &[f64]) -> f64 {
        let solved = self.solved_residual.take();
        if let Some(rmax) = solved.filter(|_| self.assembled_for == g) {
            return rmax;
        }
        self.assemble(g);
        self.stencil.residual(self.level.grid, y, &mut self.r).0
    }

    /// The stencil ← A(g) (unshifted), unless it holds that already. When it holds A(g') of
    /// another switch, only the θ-columns around the nodes where g and g' differ are
    /// re-assembled ([`discretization::assemble_changed_columns`]: the same matrix bit for bit;
    /// a Newton step switches a few nodes at the cavity edges, so this is a fraction of a full
    /// assembly), unless they are more than half of the columns.
    fn assemble(&mut self, g: &[f64]) {
        if self.assembled_for == g {
            return;
        }
        self.solved_residual = None;
        let grid = self.level.grid;
        let (nt, nz) = (grid.n_theta, grid.n_z);
        let mut columns = std::mem::take(&mut self.changed_columns);
        columns.clear();
        columns.resize(nt, false);
        let mut marked = 0;
        if self.assembled_for.len() == g.len() {
            for (k, _) in g
                .iter()
                .zip(&self.assembled_for)
                .enumerate()
                .filter(|(_, (a, b))| a != b)
            {
                let i = k / nz;
                for c in [if i == 0 { nt - 1 } else { i - 1 }, i, (i + 1) % nt] {
                    marked += usize::from(!columns[c]);
                    columns[c] = true;
                }
            }
        }
        if marked > 0 && 2 * marked <= nt {
            discretization::assemble_changed_columns(
                &self.level,
                g,
                self.dirichlet,
                self.time,
                self.stencil,
                &columns,
            );
        } else {
            discretization::assemble(&self.level, g, self.dirichlet, self.time, self.stencil);
        }
        self.changed_columns = columns;
        self.assembled_for.clear();
        self.assembled_for.extend_from_slice(g);
    }
}

/// The thickness change δh of a [`ThicknessChange`] at the nodes (`dh_node`) and at their east
/// θ-faces (`dh_face`), the same at every z: −c cos θ, −c sin θ for ε_x, ε_y; δg(θ) for a gap.
fn thickness_change(
    grid: &Grid,
    clearance: f64,
    change: &ThicknessChange,
    dh_node: &mut [f64],
    dh_face: &mut [f64],
) {
    let nz = grid.n_z;
    for (i, t) in grid.column_trig.iter().enumerate() {
        let (dn, df) = match change {
            ThicknessChange::Eccentricity(0) => (-clearance * t.cos, -clearance * t.cos_face),
            ThicknessChange::Eccentricity(_) => {
                // 1 (checked by the caller)
                (-clearance * t.sin, -clearance * t.sin_face)
            }
            ThicknessChange::Gap(d) => {
                let th = grid.theta(i);
                (d.at(th), d.at(th + 0.5 * grid.d_theta))
            }
        };
        for j in 0..nz {
            dh_node[i * nz + j] = dn;
            dh_face[i * nz + j] = df;
        }
    }
}

/// The pivoting rule of \[JudicePires1994\]: the fewest infeasible nodes so far, and how many
/// more block steps may fail to lower it before a single (Murty) pivot is taken.
struct PivotRule {
    fewest_infeasible: usize,
    block_tries: usize,
}

/// What the next switch is.
enum Pivot {
    /// Every infeasible node changes state.
    Block,
    /// Only this node (the least index whose state differs) changes.
    Single(usize),
}

impl PivotRule {
    /// The active-set update of a Newton step whose answer's switch `g_new` differs from `g`
    /// at `infeasible` nodes: a block pivot (every infeasible node changes state, the full
    /// semismooth Newton step) or Murty's least-index single pivot (module docs). A node that
    /// turns full starts the next solve at ψ = 0 in `psi` (module docs, step 3). Returns true
    /// after a single pivot, whose next solve must be tight.
    fn pivot(
        &mut self,
        infeasible: usize,
        g: &mut [f64],
        g_new: &[f64],
        psi: &mut [f64],
        newton: &mut NewtonCounts,
    ) -> bool {
        match self.choose(infeasible, g, g_new) {
            Pivot::Block => {
                for ((x, g), g_new) in psi.iter_mut().zip(g.iter_mut()).zip(g_new) {
                    if *g != *g_new {
                        if *g_new == 1.0 {
                            *x = 0.0;
                        }
                        *g = *g_new;
                    }
                }
                false
            }
            Pivot::Single(k) => {
                if g_new[k] == 1.0 {
                    psi[k] = 0.0;
                }
                g[k] = g_new[k];
                newton.single_pivots += 1;
                true
            }
        }
    }

    fn choose(&mut self, infeasible: usize, g: &[f64], g_new: &[f64]) -> Pivot {
        if infeasible < self.fewest_infeasible {
            self.fewest_infeasible = infeasible;
            self.block_tries = BLOCK_TRIES;
            Pivot::Block
        } else if self.block_tries > 0 {
            self.block_tries -= 1;
            Pivot::Block
        } else {
            let k = (0..g.len()).find(|&k| g_new[k] != g[k]);
            Pivot::Single(k.expect("infeasible > 0"))
        }
    }
}

/// The old time level of a step ([`ReynoldsSolver::old_time_level`]).
struct OldLevel {
    /// hⁿ φⁿ per node.
    content: Vec<f64>,
    /// Dⁿ (Crank–Nicolson only).
    outflow: Option<Vec<f64>>,
    /// BDF2's (Δt/a₀, (a₁ cⁿ − a₂ cⁿ⁻¹)/a₀) when a previous level exists.
    bdf2: Option<(f64, Vec<f64>)>,
}

/// `state` with its fields carried to another grid of `shape` by `field` (φ and the content
/// of the level before), `flags` (the switch) and `per_cell` (the net outflow, a quantity of a
/// node's cell): the fold onto a half grid or the unfold from it.
fn remap_state(
    state: &FilmState,
    shape: (usize, usize),
    field: &dyn Fn(&[f64]) -> Vec<f64>,
    flags: &dyn Fn(&[bool]) -> Vec<bool>,
    per_cell: &dyn Fn(&[f64]) -> Vec<f64>,
) -> FilmState {
    let array = |v| Array2::from_shape_vec(shape, v).expect("grid shape");
    FilmState {
        eccentricity_ratio: state.eccentricity_ratio,
        density_ratio: array(field(&flat(&state.density_ratio))),
        full_film: Array2::from_shape_vec(shape, flags(&flat(&state.full_film)))
            .expect("grid shape"),
        net_outflow: state
            .net_outflow
            .as_ref()
            .map(|a| array(per_cell(&flat(a)))),
        previous_level: (state.previous_level.as_ref())
            .map(|(a, dt)| (array(field(&flat(a))), *dt)),
        deformation: state.deformation.clone(),
        boundary_flow: state.boundary_flow.clone(),
        boundary_volume: state.boundary_volume.clone(),
        previous_boundary_volume: state.previous_boundary_volume.clone(),
    }
}

/// The elements of a field in its logical order (θ-major, `[i · n_z + j]`), without a copy
/// when it is stored that way.
fn flat<T: Copy>(a: &Array2<T>) -> std::borrow::Cow<'_, [T]> {
    match a.as_slice() {
        Some(s) => std::borrow::Cow::Borrowed(s),
        None => std::borrow::Cow::Owned(a.iter().copied().collect()),
    }
}

/// σ₀ of the steady solves' pseudo-time shift (module docs).
const STEADY_SHIFT: f64 = 0.01;

/// Relative tolerance of the film-force Jacobian's two linear solves: the Jacobian to four or
/// five digits, which Newton on ε converges with as with an exact one. Measured on the
/// slider-crank with the Reynolds film (two turns, 120 × 31, where every BDF2 step refreshes
/// the Jacobian): 3530 film solves for 1358 steps at 1e-7, 1e-5, 1e-4 and 1e-3 alike, the same
/// orbit and forces to the printed digit; Krylov iterations per Jacobian solve 6.2 at 1e-7,
/// 5.0 at 1e-5. This is the public Jacobian's and the thickness responses' (the elastic
/// coupling's); the inverse and slider-crank Newtons ask for 1e-2 through
/// [`ReynoldsSolver::film_force_jacobian_to`] (`inverse::ReynoldsFilm`, measured there).
const JACOBIAN_TOLERANCE: f64 = 1e-5;

/// The semismooth Newton's switch checks inside a solve (`adi::KrylovStop::switch_check`)
/// begin at this multiple of the loose level (1e-3 for the default 1e-5) and end when the switch
/// agrees at the loose level. Measured (callgrind, 2026-11-29) against checking at the loose
/// level only (×1): the compressor-size inverse cycle of the timing report (120 × 31, 1°)
/// 11.20e9 instructions at ×1, 11.05e9 at ×10, 10.97e9 at ×100, 11.31e9 at ×1000 (switches
/// judged too early: more pivots); the warm-step bench's step 14.7e6 / 13.9e6 / 13.9e6 /
/// 14.3e6. Before the checks (separate loose and tight solves) 11.48e9 and 15.3e6.
const SWITCH_CHECK_FROM: f64 = 100.0;

/// Block pivots allowed without lowering the number of infeasible nodes before a single
/// (Murty) pivot is taken (\[JudicePires1994\] use 3 … 10).
const BLOCK_TRIES: usize = 5;

/// Counters of one semismooth Newton solve.
#[derive(Debug, Clone, Copy, Default)]
struct NewtonCounts {
    iterations: usize,
    linear_iterations: usize,
    /// Infeasible unknowns (sign of the frozen solution against the switch) of the last step.
    switched_last: usize,
    /// Single (Murty) pivots taken.
    single_pivots: usize,
}

/// g = H(ψ) (1 where ψ ≥ 0, else 0) on the unknowns; Dirichlet nodes keep theirs. Returns how
/// many unknowns changed state.
fn set_switch(grid: &Grid, psi: &[f64], g: &mut [f64]) -> usize {
    let mut changed = 0;
    for k in 0..psi.len() {
        if grid.kind[k] == NodeKind::Unknown {
            let new_g = if psi[k] >= 0.0 { 1.0 } else { 0.0 };
            if new_g != g[k] {
                changed += 1;
                g[k] = new_g;
            }
        }
    }
    changed
}

fn check_eps(eps: [f64; 2]) -> Result<(), ReynoldsError> {
    let m = eps[0].hypot(eps[1]);
    if m >= 1.0 || m.is_nan() {
        return Err(ReynoldsError::EccentricityOutOfRange { magnitude: m });
    }
    Ok(())
}

#[cfg(test)]
mod tests;
