//! One case: solve it with each method the case asks for and gather a [`CaseReport`].
//!
//! ```text
//!   Case ──► run_mobility ─────► MethodResult (Mobility)  ─┐
//!        └─► run_rigorous ─────► MethodResult (Rigorous)  ─┼─► CaseReport ──► standard_writers()
//!            (one function: the rigorous inverse solver    │
//!             slots in here when it is on main)           ─┘   summary rows from both
//! ```
//!
//! Conventions are docs/conventions.md §1's: the case's load is the force on the journal in the bearing
//! frame; the reported orbit is the journal centre in that frame (m).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use jbearing_solvers::mobility::{
    BookerShortBearing, ExactShortBearing, MobilityError, MobilityMap, MobilityMapParams,
    MobilityModel, MobilityParams, OrbitInfo, OrbitParams, PeriodicLoad, solve_orbit,
};

use jbearing_solvers::closed_form::{ClosedFormFilm, ClosedFormModel, ClosedFormParams};
use jbearing_solvers::elastic::ElasticParams;
use jbearing_solvers::inverse::{
    InverseObserver, InverseParams, InversePhase, InverseProgress, InverseSolution, InverseStall,
    InverseStart, InverseWarning, ReynoldsFilm, solve_inverse_from,
};
use jbearing_solvers::load::LoadHistory;
use jbearing_solvers::reynolds::{
    GridParams, OperatingConditions, ReynoldsParams, ReynoldsSolver, SupplyModel,
};
use jbearing_solvers::squeeze_film::{ReynoldsSqueezeFilm, SqueezeFilmParams};
use jbearing_solvers::viscosity::ViscosityModel;
use ndarray::Array3;

use crate::budget::{self, BudgetError, Limits};
use crate::case::{Case, CaseError, CaseWarning, MobilityModelChoice, RigorousFilm};
use crate::output::{
    CaseReport, ClosedFormTable, ElasticReport, Field, FieldSnapshots, Method, MethodResult,
    OutputError, Parameter, ParameterValue, Reduction, ReportWarning, RunInfo, Series, SummaryRow,
    names, standard_writers,
};

/// Progress of one case, for progress bars and logs. Every method has a default that does
/// nothing, so an observer implements only what it shows.
pub trait RunObserver: Sync {
    /// A method starts on the case.
    fn method_started(&self, _case: &str, _method: Method) {}
    /// A cycle of a method ended, with its periodicity change (or solver residual).
    fn cycle_done(&self, _case: &str, _method: Method, _cycle: usize, _residual: f64) {}
    /// Within a cycle (cycle 0 = run-in): step of steps, with the step's residual.
    fn progress(
        &self,
        _case: &str,
        _method: Method,
        _cycle: usize,
        _step: usize,
        _steps: usize,
        _residual: f64,
    ) {
    }
    /// A method finished.
    fn method_done(&self, _case: &str, _method: Method) {}
    /// A warning about the case (before the solve).
    fn warning(&self, _case: &str, _warning: &CaseWarning) {}
    /// Asked after every time step of the rigorous method: `true` stops the case with an
    /// [`InverseError::Interrupted`](jbearing_solvers::inverse::InverseError::Interrupted)
    /// error naming the step (the Python package's Ctrl-C).
    fn stop_requested(&self) -> bool {
        false
    }
}

/// An observer that ignores everything.
pub struct Quiet;
impl RunObserver for Quiet {}

/// Why a case could not be run.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The case file is bad.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// The mobility method failed.
    #[error(
        "case '{case}': mobility method: {source}{}",
        leaving_the_map_hint(source)
    )]
    Mobility {
        /// Case name.
        case: String,
        /// The solver's error.
        #[source]
        source: MobilityError,
    },
    /// The mobility map could not be built.
    #[error("case '{case}': mobility map: {source}")]
    MobilityMap {
        /// Case name.
        case: String,
        /// What failed (shared: the map of one L/D is built once per process).
        #[source]
        source: std::sync::Arc<MapBuildError>,
    },
    /// Another case of the same batch has the same name (its output files would be
    /// overwritten).
    #[error(
        "{path}: case name '{case}' is already used by {other} in this batch: their output \
         files would overwrite each other (give each case its own name)"
    )]
    DuplicateName {
        /// Case name.
        case: String,
        /// This case file.
        path: String,
        /// The earlier case file with the same name.
        other: String,
    },
    /// The rigorous (inverse) method failed.
    #[error("case '{case}': rigorous method: {source}")]
    Rigorous {
        /// Case name.
        case: String,
        /// The solver's error, with its numbers.
        #[source]
        source: RigorousError,
    },
    /// The deformable (elastic) bearing's coupled solve failed.
    #[error("case '{case}': elastic bearing: {source}")]
    Elastic {
        /// Case name.
        case: String,
        /// The solver's error, with its numbers.
        #[source]
        source: jbearing_solvers::elastic::ElasticError,
    },
    /// The heat balance of a method did not close (or a solve inside it failed).
    #[error(
        "case '{case}': {method} method: {}",
        heat::error_chain_within(source.as_ref(), &format!("case '{case}': {method} method: "))
    )]
    HeatBalance {
        /// Case name.
        case: String,
        /// Which method.
        method: Method,
        /// The balance's error; a failed solve inside it is its source.
        #[source]
        source: Box<jbearing_solvers::heat_balance::HeatBalanceError<RunError>>,
    },
    /// Every method the case asked for failed.
    #[error("case '{case}': every method failed: {}", messages.join("; "))]
    AllMethodsFailed {
        /// Case name.
        case: String,
        /// Each method's error.
        messages: Vec<String>,
    },
    /// The case asks for no method (the case file's check refuses this; kept for callers that
    /// build a [`Case`] by hand).
    #[error(
        "case '{case}': no method requested (methods.rigorous and methods.mobility are both false)"
    )]
    NoMethod {
        /// Case name.
        case: String,
    },
    /// The case's estimated cost is above the limits.
    #[error(transparent)]
    Budget(#[from] BudgetError),
    /// A mechanism case of a batch failed.
    #[error(transparent)]
    Mechanism(#[from] Box<crate::mechanism::MechanismRunError>),
    /// Writing the results failed.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The output directory could not be made or written to.
    #[error("output directory '{}' is not usable: {source}", path.display())]
    OutputDir {
        /// The directory.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
}

/// Why the rigorous method failed: the film could not be set up, or the inverse solve failed.
#[derive(Debug, thiserror::Error)]
pub enum RigorousError {
    /// The Reynolds film's parameters are out of range.
    #[error("Reynolds film: {0}")]
    ReynoldsFilm(#[from] jbearing_solvers::reynolds::ReynoldsError),
    /// The closed-form film's parameters are out of range.
    #[error("closed-form film: {0}")]
    ClosedFormFilm(#[from] jbearing_solvers::closed_form::ClosedFormError),
    /// The inverse solve failed (collapse, Newton, film; with time, crank angle and ε).
    #[error(transparent)]
    Inverse(#[from] jbearing_solvers::inverse::InverseError),
    /// The elastic structure of the deformable film could not be built.
    #[error("elastic structure: {0}")]
    Elastic(#[from] jbearing_solvers::elastic::ElasticError),
}

/// Why the finite-length mobility map of an L/D could not be built.
#[derive(Debug, thiserror::Error)]
pub enum MapBuildError {
    /// The squeeze film of the map is out of range.
    #[error("squeeze film: {0}")]
    SqueezeFilm(#[from] jbearing_solvers::squeeze_film::SqueezeFilmError),
    /// A node of the map failed.
    #[error(transparent)]
    Map(#[from] jbearing_solvers::mobility::MobilityMapError),
}

/// What one case produced.
#[derive(Debug, Clone)]
pub struct CaseOutcome {
    /// The report (written already).
    pub report: CaseReport,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// The rigorous inverse solution of the case. This is the one place the rigorous method enters
/// the application:
///
/// ```text
///   Case ──► CaseHistory (LoadHistory: load, ω_j(t), ω_b(t), p_feed(t) per groove)
///        ──► film: ReynoldsFilm (JFO)        [default, solver.rigorous_film = "reynolds"]
///                  | ClosedFormFilm (moving short Gumbel) [solver.rigorous_film = "short_bearing"]
///        ──► solve_inverse(InverseParams from [solver]) ──► inverse_result ──► MethodResult
/// ```
pub fn run_rigorous(case: &Case, observer: &dyn RunObserver) -> Result<MethodResult, RunError> {
    run_rigorous_from(case, observer, None).map(|(result, _)| result)
}

/// Where a rigorous solve ended, to start the next solve of the same case from (a heat
/// balance's next viscosity): the journal and film state at the end of the last cycle.
#[derive(Debug, Clone)]
pub enum RigorousStart {
    /// The Reynolds (JFO) film's.
    Reynolds(Box<InverseStart<jbearing_solvers::reynolds::FilmState>>),
    /// The short-bearing film's.
    ShortBearing(InverseStart<jbearing_solvers::inverse::ClosedFormState>),
    /// The deformable Reynolds film's (a case with `[elastic]`).
    Elastic(Box<InverseStart<jbearing_solvers::elastic::ElasticFilmState>>),
}

/// [`run_rigorous`] started from where an earlier solve of the case ended (`start`, skipping
/// the run-in; a start of the other film model is ignored), returning where this one ended.
pub fn run_rigorous_from(
    case: &Case,
    observer: &dyn RunObserver,
    start: Option<&RigorousStart>,
) -> Result<(MethodResult, RigorousStart), RunError> {
    let params = inverse_params(case);
    let history = CaseHistory::new(case);
    let mut adapter = InverseAdapter::new(&case.name, observer);
    observer.method_started(&case.name, Method::Rigorous);
    let run = RigorousRun {
        case,
        params: &params,
        history: &history,
    };
    let (solution, end, description) = match case.solver.rigorous_film {
        RigorousFilm::Reynolds if case.elastic.is_some() => run.elastic(&mut adapter, start),
        RigorousFilm::Reynolds => run.reynolds(&mut adapter, start),
        RigorousFilm::ShortBearing => run.short_bearing(&mut adapter, start),
    }
    .map_err(|source| RunError::Rigorous {
        case: case.name.clone(),
        source,
    })?;
    observer.method_done(&case.name, Method::Rigorous);
    Ok((inverse_result(case, &solution, description), end))
}

/// What every film of a rigorous run shares: the case, the solver's settings and the case's
/// histories.
struct RigorousRun<'a> {
    case: &'a Case,
    params: &'a InverseParams,
    history: &'a CaseHistory<'a>,
}

/// A rigorous run's answer: the solution, where it ended, and the film's description.
type RigorousAnswer = (InverseSolution, RigorousStart, &'static str);

impl RigorousRun<'_> {
    /// The inverse solve with the deformable Reynolds film (a case with `[elastic]`).
    fn elastic(
        &self,
        adapter: &mut InverseAdapter<'_>,
        start: Option<&RigorousStart>,
    ) -> Result<RigorousAnswer, RigorousError> {
        let case = self.case;
        let elastic = case.elastic.clone().expect("a case with [elastic]");
        let bearing = jbearing_solvers::elastic::ElasticBearing::new(case.radius, elastic)?;
        let mut film =
            jbearing_solvers::elastic::ElasticFilm::new(reynolds_params(case), &bearing)?;
        let from = match start {
            Some(RigorousStart::Elastic(s)) => Some(InverseStart::clone(s)),
            _ => None,
        };
        let (solution, end) =
            solve_inverse_from(self.params, self.history, &mut film, adapter, from)?;
        Ok((
            solution,
            RigorousStart::Elastic(Box::new(end)),
            "inverse solver (Newton on eccentricity per time step) with the mass-conserving \
             universal Reynolds (Elrod-Vijayaraghavan, JFO) film and elastic shaft and \
             housing ([elastic]: plane-strain FE compliance, the gap g = C p solved \
             quasi-statically in every film step)",
        ))
    }

    /// The inverse solve with the rigid Reynolds (JFO) film.
    fn reynolds(
        &self,
        adapter: &mut InverseAdapter<'_>,
        start: Option<&RigorousStart>,
    ) -> Result<RigorousAnswer, RigorousError> {
        let mut film = ReynoldsFilm::new(reynolds_params(self.case))?;
        let from = match start {
            Some(RigorousStart::Reynolds(s)) => Some(InverseStart::clone(s)),
            _ => None,
        };
        let (solution, end) =
            solve_inverse_from(self.params, self.history, &mut film, adapter, from)?;
        Ok((
            solution,
            RigorousStart::Reynolds(Box::new(end)),
            "inverse solver (Newton on eccentricity per time step) with the mass-conserving \
             universal Reynolds (Elrod-Vijayaraghavan, JFO) film",
        ))
    }

    /// The inverse solve with the analytic moving short-bearing film.
    fn short_bearing(
        &self,
        adapter: &mut InverseAdapter<'_>,
        start: Option<&RigorousStart>,
    ) -> Result<RigorousAnswer, RigorousError> {
        let case = self.case;
        let mut film = ClosedFormFilm::new(
            ClosedFormModel::ShortGumbelMovingFilm,
            ClosedFormParams {
                radius: case.radius,
                length: case.length,
                radial_clearance: case.radial_clearance,
                viscosity: case.viscosity,
            },
            case.solver.time_scheme,
        )?;
        let from = match start {
            Some(RigorousStart::ShortBearing(s)) => Some(s.clone()),
            _ => None,
        };
        let (solution, end) =
            solve_inverse_from(self.params, self.history, &mut film, adapter, from)?;
        Ok((
            solution,
            RigorousStart::ShortBearing(end),
            "inverse solver with the analytic short-bearing film (Gumbel half film, moving \
             journal) - NOT the mass-conserving Reynolds film",
        ))
    }
}

/// Key of the report parameter that says why the rigorous method is missing (it failed).
pub const RIGOROUS_STATUS: &str = Method::Rigorous.failure_key();
/// Key of the report parameter that says why the elastic bearing is missing (it failed).
pub const ELASTIC_STATUS: &str = "elastic_status";
/// Key of the report parameter that says why the mobility method is missing (it failed).
pub const MOBILITY_STATUS: &str = Method::Mobility.failure_key();

/// The Reynolds (JFO) film parameters of the case, handed to [`ReynoldsFilm`] by
/// [`run_rigorous`].
pub fn reynolds_params(case: &Case) -> ReynoldsParams {
    ReynoldsParams {
        bulk_modulus: case.bulk_modulus,
        cavitation_pressure: case.cavitation_pressure,
        ambient_pressure: case.ambient_pressure,
        grooves: case.grooves.clone(),
        grid: GridParams {
            n_theta: case.n_theta,
            n_z: case.n_z,
        },
        time_scheme: case.solver.time_scheme,
        viscosity_model: case.viscosity_model,
        ..ReynoldsParams::plain(
            case.radius,
            case.length,
            case.radial_clearance,
            case.viscosity,
        )
    }
}

/// The deformable steady problem of a case with `[elastic]`: what [`run_elastic`] solves, and
/// what the JB1 deformable validation test (`validation/tests/elastic_seed003.rs`) loads, so
/// that the application and the validation run one configuration.
#[derive(Debug, Clone)]
pub struct ElasticProblem {
    /// The film: the case's Reynolds (JFO) parameters, with the axial supply line at h_max
    /// when the case has no groove ([`SupplyModel::AxialLineAtMaxGap`], \[Benasciutti2012\]'s
    /// supply), else the grooves at the case's feed pressure.
    pub film: ReynoldsParams,
    /// Shaft and housing.
    pub elastic: ElasticParams,
    /// The steady load on the journal, N (bearing frame).
    pub load: [f64; 2],
    /// Speeds and feed pressures (the case's constants).
    pub conditions: OperatingConditions,
}

/// The [`ElasticProblem`] of `case`, None without `[elastic]` or when the case is not steady
/// (one load point, constant speeds; a dynamic case takes the deformation in the rigorous
/// method instead).
pub fn elastic_problem(case: &Case) -> Option<ElasticProblem> {
    if !crate::closed_form_report::is_steady(case) {
        return None;
    }
    let elastic = case.elastic.clone()?;
    let mut film = reynolds_params(case);
    if case.grooves.is_empty() {
        film.supply = SupplyModel::AxialLineAtMaxGap;
    }
    let at0 = |s: &crate::case::Schedule| s.at(case.load_angles_deg[0], case.cycle_deg);
    Some(ElasticProblem {
        film,
        elastic,
        load: case.load_forces[0],
        conditions: OperatingConditions {
            journal_speed: at0(&case.journal_speed),
            bearing_speed: at0(&case.bearing_speed),
            feed_pressures: vec![at0(&case.feed_pressure); case.grooves.len()],
        },
    })
}

/// The deformable bearing of a case with `[elastic]` (None without): the coupled film–structure
/// steady-load solve (`jbearing_solvers::elastic::solve_steady_load`), beside it the rigid film
/// under the same load, and the report the writers store (`crate::output::elastic`).
pub fn run_elastic(case: &Case) -> Option<Result<ElasticReport, RunError>> {
    let problem = elastic_problem(case)?;
    let fail = |source| RunError::Elastic {
        case: case.name.clone(),
        source,
    };
    Some(solve_elastic(case, &problem).map_err(fail))
}

fn solve_elastic(
    case: &Case,
    problem: &ElasticProblem,
) -> Result<ElasticReport, jbearing_solvers::elastic::ElasticError> {
    use jbearing_solvers::elastic::{ElasticBearing, solve_steady_load};
    let t0 = Instant::now();
    let mut solver = ReynoldsSolver::new(problem.film.clone())?;
    let (rigid, rigid_info) = solver.solve_steady_load(problem.load, &problem.conditions)?;
    let bearing = ElasticBearing::new(case.radius, problem.elastic.clone())?;
    let (sol, info) = solve_steady_load(&mut solver, &bearing, problem.load, &problem.conditions)?;
    let c = case.radial_clearance;
    let eps = info.steady.eccentricity_ratio;
    let angle = bearing.surface_angles();
    let film_thickness: Vec<f64> = angle
        .iter()
        .zip(&sol.gap_change)
        .map(|(th, g)| c * (1.0 - eps[0] * th.cos() - eps[1] * th.sin()) + g)
        .collect();
    let body = |name: &str, b: &jbearing_solvers::elastic::ElasticBody, u: &[[f64; 2]]| {
        let stress = b.stresses(u);
        crate::output::BodyField {
            name: name.into(),
            points: b.mesh().nodes.clone(),
            cells: b.mesh().elements.clone(),
            displacement: u.to_vec(),
            stress: stress.iter().map(|s| [s.xx, s.yy, s.xy, s.zz]).collect(),
        }
    };
    let shaft = body("shaft", &bearing.shaft, &sol.shaft_displacement);
    let housing = body("housing", &bearing.housing, &sol.housing_displacement);
    let series = elastic_series(&bearing, &sol, film_thickness, &shaft, &housing);
    let scalars = elastic_scalars(c, &sol, &info, &rigid, &rigid_info, t0);
    Ok(ElasticReport {
        description: format!(
            "deformable bearing: plane-strain finite elements of shaft (hole {} m, held radially) \
             and square housing (half-width {} m, edges fixed), {} nodes around; film gap \
             h = c - e cos + g, g = C p (compliance), Aitken-relaxed fixed point on g around the \
             steady-load Newton (jbearing_solvers::elastic)",
            problem.elastic.hole_radius,
            match problem.elastic.housing {
                jbearing_solvers::elastic::HousingShape::Square { half_width } => half_width,
                jbearing_solvers::elastic::HousingShape::Circle { radius } => radius,
            },
            problem.elastic.n_theta
        ),
        scalars,
        angle,
        series,
        bodies: vec![shaft, housing],
    })
}

/// The surface series of a deformable-bearing answer: p̄, g, h, both bodies' radial
/// displacements, and σ_r, σ_θ, σ_z, von Mises on the bore and on the journal.
fn elastic_series(
    bearing: &jbearing_solvers::elastic::ElasticBearing,
    sol: &jbearing_solvers::elastic::ElasticSolution,
    film_thickness: Vec<f64>,
    shaft: &crate::output::BodyField,
    housing: &crate::output::BodyField,
) -> Vec<Series> {
    let mut series = vec![
        Series::new(
            "surface_pressure",
            "film pressure averaged over the length (the load on the structure)",
            "Pa",
            sol.surface_pressure.clone(),
        ),
        Series::new(
            "gap_change",
            "gap change g = housing minus shaft radial displacement",
            "m",
            sol.gap_change.clone(),
        ),
        Series::new(
            "film_thickness",
            "deformed film thickness h = c - e cos + g",
            "m",
            film_thickness,
        ),
        Series::new(
            "housing_radial_displacement",
            "radial displacement of the bore (outward positive)",
            "m",
            sol.housing_radial.clone(),
        ),
        Series::new(
            "shaft_radial_displacement",
            "radial displacement of the journal surface (outward positive)",
            "m",
            sol.shaft_radial.clone(),
        ),
    ];
    for (prefix, where_, b) in [
        ("bore", "housing bore", housing),
        ("journal", "journal surface", shaft),
    ] {
        let surface = if prefix == "bore" {
            &bearing.housing.mesh().surface
        } else {
            &bearing.shaft.mesh().surface
        };
        let polar: Vec<[f64; 2]> = surface.iter().map(|&k| b.polar_stress(k)).collect();
        series.push(Series::new(
            &format!("{prefix}_radial_stress"),
            &format!("radial stress on the {where_}"),
            "Pa",
            polar.iter().map(|s| s[0]).collect(),
        ));
        series.push(Series::new(
            &format!("{prefix}_hoop_stress"),
            &format!("hoop stress on the {where_}"),
            "Pa",
            polar.iter().map(|s| s[1]).collect(),
        ));
        series.push(Series::new(
            &format!("{prefix}_axial_stress"),
            &format!("axial stress (plane strain, nu (s_r + s_t)) on the {where_}"),
            "Pa",
            surface.iter().map(|&k| b.stress[k][3]).collect(),
        ));
        series.push(Series::new(
            &format!("{prefix}_von_mises_stress"),
            &format!("von Mises stress on the {where_}"),
            "Pa",
            surface.iter().map(|&k| b.von_mises(k)).collect(),
        ));
    }
    series
}

/// The scalars of a deformable-bearing answer beside the rigid film's under the same load,
/// and the coupled solve's statistics.
fn elastic_scalars(
    c: f64,
    sol: &jbearing_solvers::elastic::ElasticSolution,
    info: &jbearing_solvers::elastic::ElasticInfo,
    rigid: &jbearing_solvers::reynolds::FilmSolution,
    rigid_info: &jbearing_solvers::reynolds::SteadyLoadInfo,
    t0: Instant,
) -> Vec<Parameter> {
    let mut scalars = deformed_film_scalars(c, sol, info);
    scalars.extend(rigid_film_scalars(c, rigid, rigid_info));
    scalars.extend(coupling_scalars(info, t0));
    scalars
}

/// The deformed film's answer: eccentricity, attitude, peak pressure, h_min, force, power.
fn deformed_film_scalars(
    c: f64,
    sol: &jbearing_solvers::elastic::ElasticSolution,
    info: &jbearing_solvers::elastic::ElasticInfo,
) -> Vec<Parameter> {
    let eps = info.steady.eccentricity_ratio;
    let f = &sol.film;
    vec![
        Parameter::number(
            "eccentricity_ratio_x",
            eps[0],
            "1",
            "journal eccentricity e_x / c",
        ),
        Parameter::number(
            "eccentricity_ratio_y",
            eps[1],
            "1",
            "journal eccentricity e_y / c",
        ),
        Parameter::number(
            "eccentricity",
            c * eps[0].hypot(eps[1]),
            "m",
            "journal eccentricity |e| (may exceed c: the bore deforms)",
        ),
        Parameter::number(
            "attitude_angle",
            f.attitude_angle,
            "rad",
            "attitude angle, from the load line to the line of centres",
        ),
        Parameter::number("max_pressure", f.max_pressure, "Pa", "peak film pressure"),
        Parameter::number(
            "min_film_thickness",
            f.min_film_thickness,
            "m",
            "minimum film thickness of the deformed film",
        ),
        Parameter::number(
            "film_force_x",
            f.film_force[0],
            "N",
            "film force on the journal, x",
        ),
        Parameter::number(
            "film_force_y",
            f.film_force[1],
            "N",
            "film force on the journal, y",
        ),
        Parameter::number("power_loss", f.power_loss, "W", "friction power loss"),
    ]
}

/// The rigid film's eccentricity, peak pressure and h_min under the same load.
fn rigid_film_scalars(
    c: f64,
    rigid: &jbearing_solvers::reynolds::FilmSolution,
    rigid_info: &jbearing_solvers::reynolds::SteadyLoadInfo,
) -> Vec<Parameter> {
    let e_rigid = rigid_info.eccentricity_ratio;
    vec![
        Parameter::number(
            "rigid_eccentricity",
            c * e_rigid[0].hypot(e_rigid[1]),
            "m",
            "journal eccentricity of the rigid film under the same load",
        ),
        Parameter::number(
            "rigid_max_pressure",
            rigid.max_pressure,
            "Pa",
            "peak film pressure of the rigid film",
        ),
        Parameter::number(
            "rigid_min_film_thickness",
            rigid.min_film_thickness,
            "m",
            "minimum film thickness of the rigid film",
        ),
    ]
}

/// The coupled solve's statistics: iterations, gap residual, film solves, wall time since `t0`.
fn coupling_scalars(info: &jbearing_solvers::elastic::ElasticInfo, t0: Instant) -> Vec<Parameter> {
    vec![
        Parameter::integer(
            "coupling_iterations",
            info.iterations as i64,
            "outer (deformation) iterations of the coupled solve",
        ),
        Parameter::number(
            "gap_residual",
            info.gap_residual,
            "m",
            "max |C p - g| at convergence",
        ),
        Parameter::integer(
            "film_solves",
            info.film_solves as i64,
            "film solves over all steady-load Newton solves",
        ),
        Parameter::number(
            "wall_time",
            t0.elapsed().as_secs_f64(),
            "s",
            "wall time of the rigid and the coupled solve (meshing, factorization, compliance included)",
        ),
    ]
}

/// The inverse solver's settings from the case's `[solver]` and `[output]` tables.
pub fn inverse_params(case: &Case) -> InverseParams {
    let s = &case.solver;
    let steps = s.time_steps_per_cycle.max(4);
    InverseParams {
        step_deg: case.cycle_deg / steps as f64,
        tolerance: s.force_tolerance.max(1e-10),
        max_cycles: s.max_cycles,
        periodicity_tolerance: s.periodicity_tolerance,
        collapse_eccentricity: s.eccentricity_limit,
        step_error_tolerance: s.step_error_tolerance,
        cycle_extrapolation: s.cycle_extrapolation,
        field_stride: steps
            .checked_div(case.output.field_snapshots)
            .map_or(0, |k| k.max(1)),
        ..InverseParams::default()
    }
}

/// The case's histories as the inverse solver's [`LoadHistory`].
pub struct CaseHistory<'a> {
    case: &'a Case,
    load: jbearing_solvers::mobility::TabulatedLoad,
}

impl<'a> CaseHistory<'a> {
    /// Histories of `case`.
    pub fn new(case: &'a Case) -> Self {
        Self {
            case,
            load: case.load(),
        }
    }
    fn angle(&self, t: f64) -> f64 {
        (t * self.case.crank_speed).to_degrees()
    }
}

impl LoadHistory for CaseHistory<'_> {
    fn period(&self) -> f64 {
        self.case.period()
    }
    fn load(&self, t: f64) -> [f64; 2] {
        self.load.load_at_crank_angle(self.angle(t))
    }
    fn journal_speed(&self, t: f64) -> f64 {
        self.case
            .journal_speed
            .at(self.angle(t), self.case.cycle_deg)
    }
    fn bearing_speed(&self, t: f64) -> f64 {
        self.case
            .bearing_speed
            .at(self.angle(t), self.case.cycle_deg)
    }
    fn feed_pressures(&self, t: f64) -> Vec<f64> {
        let p = self
            .case
            .feed_pressure
            .at(self.angle(t), self.case.cycle_deg);
        vec![p; self.case.grooves.len()]
    }
    fn crank_angle_deg(&self, t: f64) -> f64 {
        self.angle(t)
    }
    fn cycle_deg(&self) -> f64 {
        self.case.cycle_deg
    }
}

/// Passes the inverse solver's progress on to a [`RunObserver`], and logs it: a summary per
/// cycle at `-v` (info: |Δε|, |Δφ|, steps, Newton iterations, worst residual), every step at
/// `-vv` (debug).
struct InverseAdapter<'a> {
    case: &'a str,
    observer: &'a dyn RunObserver,
    /// Newton iterations, steps and the largest step residual since the last cycle ended.
    newton_iterations: usize,
    steps: usize,
    worst_residual: f64,
    /// When progress was last passed on (at most every [`PROGRESS_INTERVAL`], and at each
    /// cycle's last step).
    last_progress: Option<Instant>,
}

/// The shortest interval between two per-step progress events of the rigorous method.
const PROGRESS_INTERVAL: Duration = Duration::from_millis(100);

impl<'a> InverseAdapter<'a> {
    fn new(case: &'a str, observer: &'a dyn RunObserver) -> Self {
        Self {
            case,
            observer,
            newton_iterations: 0,
            steps: 0,
            worst_residual: 0.0,
            last_progress: None,
        }
    }
}

impl InverseObserver for InverseAdapter<'_> {
    fn on_step(&mut self, p: &InverseProgress) {
        self.newton_iterations += p.newton_iterations;
        self.steps += 1;
        self.worst_residual = self.worst_residual.max(p.residual);
        let cycle = match p.phase {
            InversePhase::RunIn => 0,
            InversePhase::Cycle(k) => k,
        };
        tracing::debug!(
            case = self.case,
            "rigorous: {} step {}/{}, crank angle {:.1}°, ε = {:.4}, {} Newton iterations, \
             residual {:.2e}",
            if cycle == 0 {
                "run-in".to_string()
            } else {
                format!("cycle {cycle}")
            },
            p.step,
            p.steps,
            p.crank_angle_deg,
            p.eccentricity_ratio[0].hypot(p.eccentricity_ratio[1]),
            p.newton_iterations,
            p.residual
        );
        let due = self
            .last_progress
            .is_none_or(|t| t.elapsed() >= PROGRESS_INTERVAL);
        if due || p.step == p.steps {
            self.last_progress = Some(Instant::now());
            self.observer.progress(
                self.case,
                Method::Rigorous,
                cycle,
                p.step,
                p.steps,
                p.residual,
            );
        }
    }
    fn on_stall(&mut self, s: &InverseStall) {
        let film: Vec<String> = s.film.iter().map(|(k, v)| format!("{k} {v:.3e}")).collect();
        tracing::info!(
            case = self.case,
            "rigorous: stalled step, cycle {}, t = {:.6e} s, crank angle {:.1}°, dt = {:.3e} s: \
             residual {:.3e} (tolerance {:.1e}, scale {:.4e} N) after {} Newton iterations, \
             ε = ({:.6}, {:.6}); film: {}",
            s.cycle,
            s.time,
            s.crank_angle_deg,
            s.dt,
            s.residual,
            s.tolerance,
            s.scale,
            s.newton_iterations,
            s.eccentricity_ratio[0],
            s.eccentricity_ratio[1],
            film.join(", ")
        );
    }
    fn on_cycle(&mut self, cycle: usize, eccentricity_change: f64, film: f64) {
        tracing::info!(
            case = self.case,
            "rigorous: cycle {cycle}: |Δε| = {eccentricity_change:.2e}, |Δφ| = {film:.2e}, {} \
             steps, {} Newton iterations ({:.2} per step), worst step residual {:.2e}",
            self.steps,
            self.newton_iterations,
            self.newton_iterations as f64 / self.steps.max(1) as f64,
            self.worst_residual
        );
        self.newton_iterations = 0;
        self.steps = 0;
        self.worst_residual = 0.0;
        self.observer
            .cycle_done(self.case, Method::Rigorous, cycle, eccentricity_change);
    }
    fn on_extrapolation(&mut self, cycle: usize) {
        tracing::info!(
            case = self.case,
            "rigorous: after cycle {cycle} the march continues from the extrapolated cycle-start \
             state (minimal polynomial extrapolation); cycle {} is compared with none",
            cycle + 1
        );
    }
    fn stop_requested(&mut self) -> bool {
        self.observer.stop_requested()
    }
}

/// The inverse solution as the report's rigorous [`MethodResult`]: its series on the shared
/// crank grid, the field snapshots and the run statistics.
pub fn inverse_result(case: &Case, sol: &InverseSolution, film_name: &str) -> MethodResult {
    let (time, crank_angle, series) = inverse_series(case, sol);
    MethodResult {
        period: Some(case.period()),
        method: Method::Rigorous,
        time,
        crank_angle,
        series,
        fields: inverse_fields(case, sol),
        solver_info: inverse_solver_info(&sol.info, film_name),
    }
}

/// The final cycle's series (load, feed, orbit, h_min, p_max, flows, power, residual) on the
/// grid both methods share, with that grid's times and crank angles.
fn inverse_series(case: &Case, sol: &InverseSolution) -> (Vec<f64>, Vec<f64>, Vec<Series>) {
    let c = case.radial_clearance;
    let st = &sol.steps;
    // The solver's steps end at crank angles Δ, 2Δ, …, cycle; the file samples 0, Δ, …,
    // cycle − Δ (the grid both methods share, see `crank_grid`): the last step, at the end of
    // the periodic cycle, is the sample at 0.
    let n = st.len();
    let order: Vec<usize> = std::iter::once(n.saturating_sub(1))
        .chain(0..n.saturating_sub(1))
        .collect();
    let col = |f: &dyn Fn(&jbearing_solvers::inverse::InverseStep) -> f64| {
        order.iter().map(|&i| f(&st[i])).collect::<Vec<f64>>()
    };
    let (time, crank_angle) = crank_grid(case, n);
    let mut series = vec![
        Series::new(
            names::LOAD_X,
            "load on the journal, x",
            "N",
            col(&|s| s.load[0]),
        ),
        Series::new(
            names::LOAD_Y,
            "load on the journal, y",
            "N",
            col(&|s| s.load[1]),
        ),
        Series::new(
            names::FEED_PRESSURE,
            "feed pressure",
            "Pa",
            col(&|s| case.feed_pressure.at(s.crank_angle_deg, case.cycle_deg)),
        ),
        Series::new(
            names::ECCENTRICITY_X,
            "journal centre, x",
            "m",
            col(&|s| c * s.eccentricity_ratio[0]),
        ),
        Series::new(
            names::ECCENTRICITY_Y,
            "journal centre, y",
            "m",
            col(&|s| c * s.eccentricity_ratio[1]),
        ),
        Series::new(
            names::ECCENTRICITY_RATIO,
            "eccentricity ratio",
            "1",
            col(&|s| s.eccentricity_ratio[0].hypot(s.eccentricity_ratio[1])),
        ),
        Series::new(
            names::ATTITUDE_ANGLE,
            ATTITUDE_LONG_NAME,
            "rad",
            col(&|s| s.eccentricity_ratio[1].atan2(s.eccentricity_ratio[0])),
        ),
        Series::new(
            names::MIN_FILM_THICKNESS,
            "minimum film thickness",
            "m",
            col(&|s| s.min_film_thickness),
        ),
        Series::new(
            names::MAX_PRESSURE,
            "peak film pressure",
            "Pa",
            col(&|s| s.max_pressure),
        ),
        Series::new(
            names::CAVITATED_FRACTION,
            "cavitated fraction of the film area",
            "1",
            col(&|s| s.cavitated_fraction),
        ),
        Series::new(
            names::SIDE_LEAKAGE,
            "side leakage, both ends",
            "m3 s-1",
            col(&|s| s.side_leakage[0] + s.side_leakage[1]),
        ),
        Series::new(names::POWER_LOSS, "power loss", "W", col(&|s| s.power_loss)),
        Series::new(
            "force_residual",
            "Newton residual |F + W| / max(|W|, W_ref)",
            "1",
            col(&|s| s.residual),
        ),
    ];
    if !case.grooves.is_empty() && st.iter().all(|s| s.supply_flow.len() == case.grooves.len()) {
        series.push(Series::new(
            names::SUPPLY_FLOW,
            "supply flow, all grooves",
            "m3 s-1",
            col(&|s| s.supply_flow.iter().sum()),
        ));
        series.push(Series::new(
            names::RECIRCULATED_FLOW,
            "film oil arriving at the feed grooves (circumferential flow across their leading \
             edges)",
            "m3 s-1",
            col(&|s| s.recirculated_flow),
        ));
    }
    (time, crank_angle, series)
}

/// The run statistics and the warning as typed attributes of the rigorous group.
fn inverse_solver_info(
    info: &jbearing_solvers::inverse::InverseInfo,
    film_name: &str,
) -> Vec<(String, ParameterValue)> {
    vec![
        ("film_model".into(), ParameterValue::Text(film_name.into())),
        ("cycles".into(), ParameterValue::Integer(info.cycles as i64)),
        ("periodic".into(), ParameterValue::Flag(info.periodic)),
        // After a single cycle there is no previous one to compare with (the solver's
        // change is +∞): the attribute says so instead of holding a non-finite number.
        (
            "eccentricity_change".into(),
            if info.eccentricity_change.is_finite() {
                ParameterValue::Number(info.eccentricity_change)
            } else {
                ParameterValue::Text("not assessed: a single cycle was run".into())
            },
        ),
        (
            "film_state_change".into(),
            ParameterValue::Number(info.film_state_change),
        ),
        (
            "steps_per_cycle".into(),
            ParameterValue::Integer(info.steps_per_cycle as i64),
        ),
        (
            "newton_iterations".into(),
            ParameterValue::Integer(info.newton_iterations as i64),
        ),
        (
            "film_evaluations".into(),
            ParameterValue::Integer(info.film_evaluations as i64),
        ),
        (
            "jacobian_evaluations".into(),
            ParameterValue::Integer(info.jacobian_evaluations as i64),
        ),
        (
            "sweep_iterations".into(),
            ParameterValue::Integer(info.sweep_iterations as i64),
        ),
        // Steps accepted above the Newton tolerance (film-force jumps) and steps that
        // needed halving: how much to trust the orbit between the tolerance and
        // accept_tolerance.
        (
            "stalled_steps".into(),
            ParameterValue::Integer(info.stalled_steps as i64),
        ),
        (
            "max_stalled_residual".into(),
            ParameterValue::Number(info.max_stalled_residual),
        ),
        (
            "split_steps".into(),
            ParameterValue::Integer(info.split_steps as i64),
        ),
        // The local error control: steps of the cycle taken in substeps, most halvings.
        (
            "refined_steps".into(),
            ParameterValue::Integer(info.refined_steps as i64),
        ),
        (
            "max_refinement_level".into(),
            ParameterValue::Integer(info.max_refinement_level as i64),
        ),
        // Extrapolations of the cycle-to-cycle map (a slowly filling film).
        (
            "cycle_extrapolations".into(),
            ParameterValue::Integer(info.cycle_extrapolations as i64),
        ),
        // The warning as a typed value: a code ("" or "not_periodic"; the numbers are the
        // attributes above) and its message.
        (
            "warning".into(),
            ParameterValue::Text(
                match &info.warning {
                    None => "",
                    Some(InverseWarning::NotPeriodic { .. }) => "not_periodic",
                }
                .into(),
            ),
        ),
        (
            "warning_message".into(),
            ParameterValue::Text(
                info.warning
                    .as_ref()
                    .map_or_else(String::new, ToString::to_string),
            ),
        ),
    ]
}

/// Field snapshots of the final cycle on the case's grid (θ_i = 2π i / n_θ, z_j from −L/2 to
/// L/2), if the film returned fields of that shape.
fn inverse_fields(case: &Case, sol: &InverseSolution) -> Option<FieldSnapshots> {
    let snaps = &sol.fields;
    let first = snaps.first()?;
    let (nt, nz) = first.fields.pressure.dim();
    if snaps.iter().any(|s| s.fields.pressure.dim() != (nt, nz)) || nt < 3 || nz < 2 {
        return None;
    }
    // Each snapshot at its step's exact place on the crank grid (the step at the end of the cycle
    // is the instant at 0, see `inverse_result`), in crank order.
    let n = sol.steps.len();
    let (grid_time, grid_crank) = crank_grid(case, n);
    let place = |step: usize| (step + 1) % n.max(1);
    let mut snaps: Vec<&jbearing_solvers::inverse::FieldSnapshot> = snaps.iter().collect();
    snaps.sort_by_key(|s| place(s.step_index));
    let [pressure, content, thickness] = snapshot_arrays(case, sol, &snaps, (nt, nz))?;
    let mut fields = vec![
        Field {
            name: names::PRESSURE.into(),
            long_name: "film pressure, gauge".into(),
            units: "Pa".into(),
            values: pressure.clone(),
        },
        Field {
            name: names::FILM_THICKNESS.into(),
            long_name: "film thickness".into(),
            units: "m".into(),
            values: thickness,
        },
        Field {
            name: names::FILM_CONTENT.into(),
            long_name: "film content (density ratio / film fraction)".into(),
            units: "1".into(),
            values: content,
        },
    ];
    if let Some(model) = &case.viscosity_model {
        let time_of = |step: usize| grid_time[place(step)];
        fields.extend(thermal_fields(
            case, model, sol, &snaps, &pressure, time_of,
        )?);
    }
    Some(FieldSnapshots {
        time: snaps
            .iter()
            .map(|s| grid_time[place(s.step_index)])
            .collect(),
        crank_angle: snaps
            .iter()
            .map(|s| grid_crank[place(s.step_index)])
            .collect(),
        theta: (0..nt)
            .map(|i| std::f64::consts::TAU * i as f64 / nt as f64)
            .collect(),
        // The film grid's own rows: the end rows are the bearing ends, the inner rows the
        // centres of n_z − 2 equal cells (reynolds::grid), not n_z evenly spaced points.
        z: jbearing_solvers::reynolds::ReynoldsSolver::new(reynolds_params(case))
            .ok()
            .map(|s| s.z_nodes())
            .filter(|z| z.len() == nz)?,
        fields,
    })
}

/// The snapshots' film pressure, film content and film thickness as (instant, θ, z) arrays, in
/// the order of `snaps`; None when a snapshot's step is missing.
fn snapshot_arrays(
    case: &Case,
    sol: &InverseSolution,
    snaps: &[&jbearing_solvers::inverse::FieldSnapshot],
    (nt, nz): (usize, usize),
) -> Option<[Array3<f64>; 3]> {
    let k = snaps.len();
    let mut pressure = Array3::zeros((k, nt, nz));
    let mut content = Array3::zeros((k, nt, nz));
    // h(θ) = c (1 − ε_x cos θ − ε_y sin θ) (docs/conventions.md §1; reynolds/film.rs), the rigid journal's
    // gap at the snapshot's ε, the same along z.
    let mut thickness = Array3::zeros((k, nt, nz));
    for (i, s) in snaps.iter().enumerate() {
        let eps = sol.steps.get(s.step_index)?.eccentricity_ratio;
        for it in 0..nt {
            let th = std::f64::consts::TAU * it as f64 / nt as f64;
            let h = case.radial_clearance * (1.0 - eps[0] * th.cos() - eps[1] * th.sin());
            thickness.slice_mut(ndarray::s![i, it, ..]).fill(h);
        }
        pressure
            .index_axis_mut(ndarray::Axis(0), i)
            .assign(&s.fields.pressure);
        content
            .index_axis_mut(ndarray::Axis(0), i)
            .assign(&s.fields.film_fraction);
    }
    Some([pressure, content, thickness])
}

/// Film temperature and viscosity at each snapshot, as the Reynolds solver evaluates them per
/// node (reynolds `prepare`): T averaged over the node's cell, from the first groove's centre
/// (else h_max) in the direction of the surface motion; μ = μ₀(T) exp(α (p − p_cav)).
fn thermal_fields(
    case: &Case,
    model: &ViscosityModel,
    sol: &InverseSolution,
    snaps: &[&jbearing_solvers::inverse::FieldSnapshot],
    pressure: &Array3<f64>,
    time_of: impl Fn(usize) -> f64,
) -> Option<[Field; 2]> {
    let (k, nt, nz) = pressure.dim();
    let history = CaseHistory::new(case);
    let d_theta = std::f64::consts::TAU / nt as f64;
    let mut temperature = Array3::zeros((k, nt, nz));
    let mut viscosity = Array3::zeros((k, nt, nz));
    for (i, s) in snaps.iter().enumerate() {
        let t = time_of(s.step_index);
        let eps = sol.steps.get(s.step_index)?.eccentricity_ratio;
        let supply = case
            .grooves
            .first()
            .map_or((-eps[1]).atan2(-eps[0]), |g| g.center_angle);
        let sign = if history.journal_speed(t) - history.bearing_speed(t) < 0.0 {
            -1.0
        } else {
            1.0
        };
        for it in 0..nt {
            let th = d_theta * it as f64;
            let temp = model
                .temperature
                .cell_average(th, 0.5 * d_theta, supply, sign);
            for jz in 0..nz {
                temperature[[i, it, jz]] = temp;
                let p = pressure[[i, it, jz]] - case.cavitation_pressure;
                viscosity[[i, it, jz]] = model.at_cell(th, 0.5 * d_theta, supply, sign, p);
            }
        }
    }
    Some([
        Field {
            name: names::TEMPERATURE.into(),
            long_name: "film temperature (the case's temperature profile)".into(),
            units: "degC".into(),
            values: temperature,
        },
        Field {
            name: names::VISCOSITY.into(),
            long_name: "film viscosity mu0(T) exp(alpha (p - p_cav))".into(),
            units: "Pa s".into(),
            values: viscosity,
        },
    ])
}

/// The case's load, with the crank angle of its table, as the solvers' periodic load.
struct CaseLoad<'a>(&'a Case, jbearing_solvers::mobility::TabulatedLoad);

impl PeriodicLoad for CaseLoad<'_> {
    fn period(&self) -> f64 {
        self.0.period()
    }
    fn load(&self, t: f64) -> [f64; 2] {
        self.1.load_at_crank_angle(self.crank_angle_deg(t))
    }
    fn crank_angle_deg(&self, t: f64) -> f64 {
        (t * self.0.crank_speed).to_degrees()
    }
}

/// What a user can do when the mobility orbit left the model's range (the finite-length map
/// ends at ε = 0.99, the closed forms reach the collapse limit); empty for other errors.
fn leaving_the_map_hint(e: &MobilityError) -> &'static str {
    match e {
        MobilityError::OutsideModelRange { .. } => {
            "; solver.mobility_model = \"booker\" or \"exact_short\" follow the orbit to the \
             collapse limit"
        }
        _ => "",
    }
}

/// Booker's mobility method on the case.
///
/// The mobility ODE takes constant speeds; a case with speed histories (the connecting-rod
/// big end, whose ω_b oscillates with the rod) uses their cycle means, and the report says so.
pub fn run_mobility(case: &Case, observer: &dyn RunObserver) -> Result<MethodResult, RunError> {
    observer.method_started(&case.name, Method::Mobility);
    let err = |source| RunError::Mobility {
        case: case.name.clone(),
        source,
    };
    let bearing = MobilityParams {
        radius: case.radius,
        length: case.length,
        radial_clearance: case.radial_clearance,
        viscosity: case.viscosity,
        omega_journal: case.journal_speed.mean(case.cycle_deg),
        omega_bearing: case.bearing_speed.mean(case.cycle_deg),
    };
    let mut params = OrbitParams::new(bearing);
    params.initial_eccentricity = case.solver.initial_eccentricity;
    // With the rigorous method beside it, the mobility orbit is sampled on the same crank grid
    // (one sample per rigorous time step) so that the two compare sample by sample.
    params.samples_per_cycle = if case.methods.rigorous {
        case.solver.time_steps_per_cycle
    } else {
        case.output.samples_per_cycle
    };
    params.periodicity_tolerance = case.solver.periodicity_tolerance.min(1e-5);
    params.max_cycles = case.solver.max_cycles.max(2) * 5;
    params.eccentricity_limit = case.solver.eccentricity_limit.max(0.9995);
    let load = CaseLoad(case, case.load());
    let ld = bearing.length_to_diameter();
    let (orbit, model_name): (OrbitInfo, String) = match case.solver.mobility_model {
        MobilityModelChoice::Booker => (
            solve_orbit(
                &params,
                &BookerShortBearing {
                    length_to_diameter: ld,
                },
                &load,
            )
            .map_err(err)?,
            "Booker short-bearing closed form ([Flores2006] eqs. 28-35)".into(),
        ),
        MobilityModelChoice::ExactShort => (
            solve_orbit(
                &params,
                &ExactShortBearing {
                    length_to_diameter: ld,
                },
                &load,
            )
            .map_err(err)?,
            "exact short-bearing mobility (inverted squeeze integrals)".into(),
        ),
        MobilityModelChoice::Map => {
            // Finite-length mobility (docs/conventions.md §6, Goenka's construction): pure-squeeze
            // solutions of our own Reynolds-condition film over (ε, load angle) for this L/D.
            let map = mobility_map(ld).map_err(|source| RunError::MobilityMap {
                case: case.name.clone(),
                source,
            })?;
            let map: &MobilityMap = &map;
            check_model(map, ld);
            // The orbit stops at the map's edge by itself (reported as leaving the model's
            // range, not as a film collapse).
            let grid = MobilityMapParams::for_squeeze_film_solver();
            (
                solve_orbit(&params, map, &load).map_err(err)?,
                format!(
                    "finite-length mobility map: pure-squeeze Reynolds-condition film of this L/D \
                     (squeeze_film), {} x {} nodes up to eps = {}",
                    grid.eccentricity_nodes, grid.angle_nodes, grid.max_eccentricity
                ),
            )
        }
    };
    observer.cycle_done(
        &case.name,
        Method::Mobility,
        orbit.cycles,
        orbit.periodicity_change,
    );
    observer.method_done(&case.name, Method::Mobility);
    Ok(mobility_result(case, &orbit, &model_name, &bearing))
}

/// The finite-length mobility map of `ld` ([`MobilityMapParams::for_squeeze_film_solver`]), built once per
/// process and shared: it depends on L/D alone (the map is dimensionless), and a heat balance
/// or a batch of cases of one bearing asks for it many times.
fn mobility_map(ld: f64) -> Result<std::sync::Arc<MobilityMap>, std::sync::Arc<MapBuildError>> {
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex, OnceLock};
    type Built = Result<Arc<MobilityMap>, Arc<MapBuildError>>;
    type Cache = Mutex<HashMap<u64, Arc<OnceLock<Built>>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    // One cell per L/D: the first caller builds it, concurrent callers of the same L/D wait
    // for that build instead of repeating it; other L/D values build in parallel.
    let cell = CACHE
        .get_or_init(Default::default)
        .lock()
        .expect("mobility map cache poisoned")
        .entry(ld.to_bits())
        .or_default()
        .clone();
    cell.get_or_init(|| {
        let film = ReynoldsSqueezeFilm::new(SqueezeFilmParams::new(ld))
            .map_err(|e| Arc::new(MapBuildError::from(e)))?;
        MobilityMap::build(&film, &MobilityMapParams::for_squeeze_film_solver())
            .map(Arc::new)
            .map_err(|e| Arc::new(MapBuildError::from(e)))
    })
    .clone()
}

fn check_model(m: &dyn MobilityModel, ld: f64) {
    debug_assert!((m.length_to_diameter() - ld).abs() <= 1e-9 * ld);
}

/// The mobility method's result: its orbit's series on the crank grid, and its solver info.
fn mobility_result(
    case: &Case,
    orbit: &OrbitInfo,
    model_name: &str,
    bearing: &MobilityParams,
) -> MethodResult {
    // The orbit's samples run from 0 to the full cycle; the last repeats the first of the
    // periodic orbit and is dropped (the shared crank grid, see `crank_grid`).
    let n = orbit.time.len().saturating_sub(1).max(1);
    let (time, crank) = crank_grid(case, n);
    let series = mobility_series(case, orbit, &crank);
    MethodResult {
        period: Some(case.period()),
        method: Method::Mobility,
        time,
        crank_angle: crank,
        series,
        fields: None,
        solver_info: mobility_solver_info(orbit, model_name, bearing),
    }
}

/// Load, feed pressure, journal centre and the closed-form performance at the orbit's first
/// `crank.len()` samples.
fn mobility_series(case: &Case, orbit: &OrbitInfo, crank: &[f64]) -> Vec<Series> {
    let c = case.radial_clearance;
    let cycle = case.cycle_deg;
    let n = crank.len();
    let perf = &orbit.performance;
    let col = |f: &dyn Fn(usize) -> f64| (0..n).map(f).collect::<Vec<f64>>();
    vec![
        Series::new(
            names::LOAD_X,
            "load on the journal, x",
            "N",
            col(&|i| orbit.load[i][0]),
        ),
        Series::new(
            names::LOAD_Y,
            "load on the journal, y",
            "N",
            col(&|i| orbit.load[i][1]),
        ),
        Series::new(
            names::FEED_PRESSURE,
            "feed pressure (input; the mobility method ignores it)",
            "Pa",
            col(&|i| case.feed_pressure.at(crank[i], cycle)),
        ),
        Series::new(
            names::ECCENTRICITY_X,
            "journal centre, x",
            "m",
            col(&|i| c * orbit.eccentricity[i][0]),
        ),
        Series::new(
            names::ECCENTRICITY_Y,
            "journal centre, y",
            "m",
            col(&|i| c * orbit.eccentricity[i][1]),
        ),
        Series::new(
            names::ECCENTRICITY_RATIO,
            "eccentricity ratio",
            "1",
            col(&|i| perf[i].eccentricity_ratio),
        ),
        Series::new(
            names::ATTITUDE_ANGLE,
            ATTITUDE_LONG_NAME,
            "rad",
            col(&|i| orbit.eccentricity[i][1].atan2(orbit.eccentricity[i][0])),
        ),
        Series::new(
            names::MIN_FILM_THICKNESS,
            "minimum film thickness",
            "m",
            col(&|i| perf[i].min_film_thickness),
        ),
        Series::new(
            names::MAX_PRESSURE,
            "peak film pressure (short-bearing closed form)",
            "Pa",
            col(&|i| perf[i].peak_pressure),
        ),
        Series::new(
            names::SIDE_LEAKAGE,
            "side leakage (short-bearing closed form)",
            "m3 s-1",
            col(&|i| perf[i].side_flow),
        ),
        Series::new(
            names::POWER_LOSS,
            "power loss (shear + squeeze, closed forms)",
            "W",
            col(&|i| perf[i].power_loss),
        ),
    ]
}

/// Model, cycles, step counts, ω̄ and the speeds the orbit was solved with.
fn mobility_solver_info(
    orbit: &OrbitInfo,
    model_name: &str,
    bearing: &MobilityParams,
) -> Vec<(String, ParameterValue)> {
    vec![
        ("model".into(), ParameterValue::Text(model_name.into())),
        (
            "cycles".into(),
            ParameterValue::Integer(orbit.cycles as i64),
        ),
        (
            "periodicity_change".into(),
            ParameterValue::Number(orbit.periodicity_change),
        ),
        (
            "rhs_evaluations".into(),
            ParameterValue::Integer(orbit.rhs_evaluations as i64),
        ),
        (
            "accepted_steps".into(),
            ParameterValue::Integer(orbit.accepted_steps as i64),
        ),
        (
            "rejected_steps".into(),
            ParameterValue::Integer(orbit.rejected_steps as i64),
        ),
        (
            "omega_bar".into(),
            ParameterValue::Number(bearing.omega_bar()),
        ),
        (
            "speeds".into(),
            ParameterValue::Text(
                "constant: cycle means of the case's journal and bearing speeds".into(),
            ),
        ),
    ]
}

/// The one attitude angle of the result files, with its reference direction.
pub const ATTITUDE_LONG_NAME: &str = "attitude angle: polar angle of the journal centre, measured \
     from the bearing frame's +x axis towards +y, in (-pi, pi]";

/// The crank-angle grid of the result files, shared by both methods: n samples per cycle at
/// crank angles cycle·k/n (exact for whole degrees: 90, not 89.99999999999999) and times
/// period·k/n, k = 0 … n − 1; the periodic end point is not repeated.
pub fn crank_grid(case: &Case, n: usize) -> (Vec<f64>, Vec<f64>) {
    let n = n.max(1);
    let period = case.period();
    let time = (0..n).map(|k| period * k as f64 / n as f64).collect();
    let crank = (0..n)
        .map(|k| case.cycle_deg * k as f64 / n as f64)
        .collect();
    (time, crank)
}

/// The summary table of a report from its methods.
pub fn summary_rows(methods: &[MethodResult]) -> Vec<SummaryRow> {
    use Reduction::*;
    [
        (
            names::MIN_FILM_THICKNESS,
            Min,
            "min_film_thickness_min",
            "cycle minimum of the minimum film thickness",
        ),
        (
            names::ECCENTRICITY_RATIO,
            Max,
            "eccentricity_ratio_max",
            "cycle maximum of the eccentricity ratio",
        ),
        (
            names::ECCENTRICITY_RATIO,
            Mean,
            "eccentricity_ratio_mean",
            "cycle mean of the eccentricity ratio",
        ),
        (
            names::MAX_PRESSURE,
            Max,
            "max_pressure_max",
            "cycle maximum of the peak film pressure",
        ),
        (
            names::SIDE_LEAKAGE,
            Mean,
            "side_leakage_mean",
            "cycle mean of the side leakage",
        ),
        (
            names::SUPPLY_FLOW,
            Mean,
            "supply_flow_mean",
            "cycle mean of the supply flow",
        ),
        (
            names::POWER_LOSS,
            Mean,
            "power_loss_mean",
            "cycle mean of the power loss",
        ),
    ]
    .into_iter()
    .map(|(s, how, n, l)| SummaryRow::from_series(methods, s, how, n, l))
    .chain(
        [
            (
                heat::EFFECTIVE_TEMPERATURE,
                "degC",
                "effective oil temperature T_eff of the heat balance",
            ),
            (
                heat::EFFECTIVE_VISCOSITY,
                "Pa s",
                "effective viscosity mu(T_eff) the film was solved with",
            ),
            (
                heat::OUTLET_TEMPERATURE,
                "degC",
                "oil outlet temperature T_out of the heat balance (side leakage)",
            ),
        ]
        .into_iter()
        .map(|(key, units, long)| SummaryRow::from_info(methods, key, units, key, long)),
    )
    .filter(|r| r.rigorous.is_some() || r.mobility.is_some())
    .collect()
}

/// The heat balance of a case with `[lubricant.heat_balance]` around one method's solver.
///
/// ```text
///   T ──► case.at_film_temperature(T) ──► method ──► MethodResult ──► cycle means
///   ▲                                                  P̄ (power_loss), Q_s (side_leakage),
///   └──── solve_heat_balance (safeguarded secant) ◄─── Q_r (recirculated_flow; 0 if absent)
/// ```
///
/// The rigorous method starts from the mobility method's T_eff (cheap), so that it typically
/// needs two to four rigorous solves, each after the first started from the orbit and film
/// where the previous one ended; the converged temperature does not depend on the start (it
/// is the root within the tolerance).
pub mod heat {
    use super::*;
    use jbearing_solvers::heat_balance::{HeatBalanceInfo, HeatFlows, solve_heat_balance};

    /// Solver-info key: T_eff (°C).
    pub const EFFECTIVE_TEMPERATURE: &str = "effective_temperature";
    /// Solver-info key: μ(T_eff) (Pa·s).
    pub const EFFECTIVE_VISCOSITY: &str = "effective_viscosity";
    /// Solver-info key: T_out (°C).
    pub const OUTLET_TEMPERATURE: &str = "outlet_temperature";

    /// The cycle-mean flows of a method's result.
    pub fn flows(result: &MethodResult) -> HeatFlows {
        let mean = |name| result.reduce(name, Reduction::Mean);
        HeatFlows {
            power_loss: mean(names::POWER_LOSS).unwrap_or(f64::NAN),
            side_leakage: mean(names::SIDE_LEAKAGE).unwrap_or(f64::NAN),
            recirculated_flow: mean(names::RECIRCULATED_FLOW).unwrap_or(0.0),
        }
    }

    /// Run `solve` on the case, through the heat balance when the case has one.
    pub fn with_balance(
        case: &Case,
        observer: &dyn RunObserver,
        method: Method,
        start: Option<(f64, Option<f64>)>,
        mut solve: impl FnMut(&Case, &dyn RunObserver) -> Result<MethodResult, RunError>,
    ) -> Result<(MethodResult, Option<HeatBalanceInfo>), RunError> {
        let Some(h) = &case.heat_balance else {
            return solve(case, observer).map(|r| (r, None));
        };
        let (guess, slope) = start.unwrap_or((h.params.supply_temperature + 10.0, None));
        let (mut result, info) = solve_heat_balance(&h.params, guess, slope, |t| {
            let trial = case.at_film_temperature(t);
            solve(&trial, observer).map(|r| {
                let f = flows(&r);
                (r, f)
            })
        })
        .map_err(|e| RunError::HeatBalance {
            case: case.name.clone(),
            method,
            source: Box::new(e),
        })?;
        let t = info.effective_temperature;
        let history = info
            .iterates
            .iter()
            .map(|i| format!("{:.3}->{:.3}", i.temperature, i.balance.effective))
            .collect::<Vec<_>>()
            .join(", ");
        result.solver_info.extend([
            (EFFECTIVE_TEMPERATURE.into(), ParameterValue::Number(t)),
            (
                EFFECTIVE_VISCOSITY.into(),
                ParameterValue::Number(h.vogel.viscosity(t)),
            ),
            (
                OUTLET_TEMPERATURE.into(),
                ParameterValue::Number(info.balance.outlet),
            ),
            (
                "film_inlet_temperature".into(),
                ParameterValue::Number(info.balance.film_inlet),
            ),
            (
                "heat_balance_iterations".into(),
                ParameterValue::Integer(info.iterates.len() as i64),
            ),
            (
                "heat_balance_residual".into(),
                ParameterValue::Number(info.residual),
            ),
            (
                "heat_balance_history".into(),
                ParameterValue::Text(format!(
                    "trial T_eff -> balance T_eff (degC) per solve: {history}"
                )),
            ),
        ]);
        Ok((result, Some(info)))
    }

    /// The error and its sources, joined by ": ".
    /// `e` and its sources in one line, "outer: inner: …"; a source whose text the line
    /// already holds (errors that print their source in their own message) is not repeated.
    pub fn error_chain(e: &dyn std::error::Error) -> String {
        error_chain_within(e, "")
    }

    /// [`error_chain`] inside a message that already begins with `prefix` (the case and
    /// method): a source's own copy of that prefix is dropped, so the failed solve of a heat
    /// balance does not name its case and method twice.
    pub fn error_chain_within(e: &dyn std::error::Error, prefix: &str) -> String {
        let mut s = e.to_string();
        let mut src = e.source();
        while let Some(inner) = src {
            let full = inner.to_string();
            let text = full.strip_prefix(prefix).unwrap_or(&full);
            if !s.contains(text) {
                s.push_str(": ");
                s.push_str(text);
            }
            src = inner.source();
        }
        s
    }

    /// The rigorous method with its heat balance, started from the mobility method's.
    pub fn rigorous(case: &Case, observer: &dyn RunObserver) -> Result<MethodResult, RunError> {
        // Only the mobility method's T_eff: its slope does not carry over (on a starved
        // bearing the two balances differ by tens of kelvin, and a foreign slope overshoots).
        let start = case.heat_balance.as_ref().and_then(|_| {
            let (_, info) =
                with_balance(case, &Quiet, Method::Mobility, None, run_mobility).ok()?;
            Some((info?.effective_temperature, None))
        });
        // Each solve after the first starts from where the previous one ended (no run-in, and
        // the orbit of a nearby viscosity is close to periodic already).
        let mut warm: Option<RigorousStart> = None;
        let solve = |trial: &Case, obs: &dyn RunObserver| {
            let (result, end) = run_rigorous_from(trial, obs, warm.as_ref())?;
            warm = Some(end);
            Ok(result)
        };
        with_balance(case, observer, Method::Rigorous, start, solve).map(|(r, _)| r)
    }

    /// The mobility method with its heat balance.
    pub fn mobility(case: &Case, observer: &dyn RunObserver) -> Result<MethodResult, RunError> {
        with_balance(case, observer, Method::Mobility, None, run_mobility).map(|(r, _)| r)
    }
}

/// Solve the case with the methods it asks for and build its report (nothing is written).
///
/// Each method's result survives the other's failure: a failed method leaves a
/// [`RIGOROUS_STATUS`] / [`MOBILITY_STATUS`] parameter ("failed: …") in the report, and the
/// case fails only when every method it asked for failed.
pub fn solve_case(case: &Case, observer: &dyn RunObserver) -> Result<CaseReport, RunError> {
    solve_case_with(case, observer, heat::rigorous, heat::mobility)
}

/// A method's solver, as [`solve_case_with`] calls it.
type MethodSolver = fn(&Case, &dyn RunObserver) -> Result<MethodResult, RunError>;

/// [`solve_case`] with the two methods' solvers given (tests inject failures here).
fn solve_case_with(
    case: &Case,
    observer: &dyn RunObserver,
    rigorous: MethodSolver,
    mobility: MethodSolver,
) -> Result<CaseReport, RunError> {
    let started = now_utc();
    let t0 = Instant::now();
    let mut failures = Vec::new();
    let mut parameters = case.parameters();
    let methods = run_methods(
        case,
        observer,
        rigorous,
        mobility,
        &mut parameters,
        &mut failures,
    );
    // The deformable bearing beside the methods; a case that asks only for it fails with it.
    let elastic = match run_elastic(case) {
        None => None,
        Some(Ok(r)) => Some(r),
        Some(Err(err)) if methods.is_empty() && failures.is_empty() => return Err(err),
        Some(Err(err)) => {
            tracing::error!(case = %case.name, "elastic bearing failed: {err}");
            parameters.push(Parameter::text(
                ELASTIC_STATUS,
                &format!("failed: {err}"),
                "why the elastic group is absent from this file",
            ));
            failures.push(err);
            None
        }
    };
    if methods.is_empty() && elastic.is_none() {
        return Err(match failures.len() {
            0 => RunError::NoMethod {
                case: case.name.clone(),
            },
            1 => failures.remove(0),
            _ => RunError::AllMethodsFailed {
                case: case.name.clone(),
                messages: failures.iter().map(ToString::to_string).collect(),
            },
        });
    }
    let summary = summary_rows(&methods);
    let closed_form = closed_form_table(case, &methods);
    Ok(CaseReport {
        case_name: case.name.clone(),
        case_text: case.text.clone(),
        // Absolute, so that the file says where the case was wherever the command ran.
        case_path: case
            .path
            .as_ref()
            .map(|p| std::fs::canonicalize(p).unwrap_or_else(|_| p.clone())),
        input_files: case.input_files.clone(),
        geometry: case.geometry(),
        parameters,
        run: RunInfo::for_this_build(t0.elapsed().as_secs_f64(), &started),
        methods,
        summary,
        closed_form,
        elastic,
        warnings: Vec::new(),
    })
}

/// The rigorous and mobility methods the case asks for, each solved by its solver; a failed
/// one is logged, its error kept in `failures` and its status added to `parameters`.
fn run_methods(
    case: &Case,
    observer: &dyn RunObserver,
    rigorous: MethodSolver,
    mobility: MethodSolver,
    parameters: &mut Vec<Parameter>,
    failures: &mut Vec<RunError>,
) -> Vec<MethodResult> {
    let mut methods = Vec::new();
    let requested = [
        (
            case.methods.rigorous,
            rigorous,
            RIGOROUS_STATUS,
            Method::Rigorous,
        ),
        (
            case.methods.mobility,
            mobility,
            MOBILITY_STATUS,
            Method::Mobility,
        ),
    ];
    for (asked, solve, status_key, method) in requested {
        if !asked {
            continue;
        }
        match solve(case, observer) {
            Ok(r) => methods.push(r),
            Err(err) => {
                // Keep what the other method found, and say in the file (and the summaries)
                // why this one is missing.
                tracing::error!(case = %case.name, "{method} method failed: {err}");
                parameters.push(Parameter::text(
                    status_key,
                    &format!("failed: {err}"),
                    &format!("why the {method} method is absent from this file"),
                ));
                failures.push(err);
            }
        }
    }
    methods
}

/// The closed-form table of the report (when the case asks for closed forms).
fn closed_form_table(case: &Case, methods: &[MethodResult]) -> Option<ClosedFormTable> {
    // With a heat balance the closed forms take the effective temperature the methods found
    // (the rigorous one's when it ran), not the supply temperature.
    let balanced = case.heat_balance.as_ref().and_then(|_| {
        [Method::Rigorous, Method::Mobility].iter().find_map(|m| {
            methods
                .iter()
                .find(|r| r.method == *m)
                .and_then(|r| r.info_number(heat::EFFECTIVE_TEMPERATURE))
        })
    });
    match balanced {
        Some(t) => crate::closed_form_report::report_table(&case.at_film_temperature(t), methods),
        None => crate::closed_form_report::report_table(case, methods),
    }
}

/// Read, solve and write one case into `out_dir` (created if missing). The case is refused
/// before the solve if its estimated cost is above `limits`; its warnings (implausible values,
/// cost above the soft budget) go to the observer and into the result file.
pub fn run_case_file(
    path: &Path,
    out_dir: &Path,
    limits: &Limits,
    observer: &dyn RunObserver,
) -> Result<CaseOutcome, RunError> {
    run_case(&Case::from_file(path)?, out_dir, limits, observer)
}

/// [`run_case_file`] for a case already read (a sweep point, `crate::sweep`).
pub fn run_case(
    case: &Case,
    out_dir: &Path,
    limits: &Limits,
    observer: &dyn RunObserver,
) -> Result<CaseOutcome, RunError> {
    let case = case.clone();
    let warnings = checked_warnings(&case, limits, observer)?;
    // The output directory is made and tried for writing before the solve, not found
    // unusable after it.
    let unusable = |source| RunError::OutputDir {
        path: out_dir.to_path_buf(),
        source,
    };
    std::fs::create_dir_all(out_dir).map_err(unusable)?;
    tempfile::NamedTempFile::new_in(out_dir).map_err(unusable)?;
    for stale in crate::output::remove_stale_temporaries(out_dir) {
        tracing::warn!("removed {}, left by a run that was killed", stale.display());
    }
    let report = solve_case_warned(&case, &warnings, observer)?;
    let mut files = Vec::new();
    for w in standard_writers() {
        if !case.output.plots && w.name() == "plots" {
            continue;
        }
        files.extend(w.write(&report, out_dir)?);
    }
    Ok(CaseOutcome { report, files })
}

/// What [`run_case`] computes, without writing anything: the case refused above `limits`, its
/// warnings to the observer and into the report, then [`solve_case`]. The Python package's
/// `run_case` goes through here, so its datasets hold the numbers of the CLI's files.
pub fn solve_case_checked(
    case: &Case,
    limits: &Limits,
    observer: &dyn RunObserver,
) -> Result<CaseReport, RunError> {
    let warnings = checked_warnings(case, limits, observer)?;
    solve_case_warned(case, &warnings, observer)
}

/// The case's warnings and its budget's (refused above `limits`), told to the observer.
fn checked_warnings(
    case: &Case,
    limits: &Limits,
    observer: &dyn RunObserver,
) -> Result<Vec<CaseWarning>, RunError> {
    let mut warnings = case.warnings.clone();
    warnings.extend(budget::check(case, limits)?);
    for w in &warnings {
        observer.warning(&case.name, w);
    }
    Ok(warnings)
}

/// [`solve_case`] with `warnings` kept in the report.
fn solve_case_warned(
    case: &Case,
    warnings: &[CaseWarning],
    observer: &dyn RunObserver,
) -> Result<CaseReport, RunError> {
    let mut report = solve_case(case, observer)?;
    report.warnings = warnings
        .iter()
        .map(|w| ReportWarning {
            kind: w.kind.as_str().into(),
            message: w.to_string(),
        })
        .collect();
    Ok(report)
}

/// Current time as ISO 8601 UTC, to the second.
pub fn now_utc() -> String {
    jiff::Timestamp::now()
        .strftime("%Y-%m-%dT%H:%M:%SZ")
        .to_string()
}

#[cfg(test)]
mod timestamp_tests {
    /// ISO 8601 UTC to the second: `YYYY-MM-DDTHH:MM:SSZ`, parseable back.
    #[test]
    fn now_utc_is_iso8601_to_the_second() {
        let s = super::now_utc();
        assert_eq!(s.len(), 20, "{s}");
        assert!(s.ends_with('Z') && s.as_bytes()[10] == b'T', "{s}");
        assert!(s.parse::<jiff::Timestamp>().is_ok(), "{s}");
    }
}

#[cfg(test)]
mod heat_balance_error_tests {
    use super::*;
    use jbearing_solvers::heat_balance::HeatBalanceError;
    use jbearing_solvers::mobility::MobilityError;

    /// A solve that fails inside a heat balance is reported once with its case and method
    /// (the solve's own error names them too) and with all its numbers.
    #[test]
    fn a_failed_solve_inside_a_heat_balance_names_its_case_once() {
        let solve = RunError::Mobility {
            case: "main".into(),
            source: MobilityError::FilmCollapse {
                time: 0.03,
                crank_angle_deg: 322.13,
                cycle: 1,
                eccentricity: 0.9995,
                limit: 0.9995,
            },
        };
        let e = RunError::HeatBalance {
            case: "main".into(),
            method: Method::Mobility,
            source: Box::new(HeatBalanceError::Solve {
                iteration: 1,
                temperature: 70.0,
                source: solve,
            }),
        };
        let text = e.to_string();
        assert_eq!(text.matches("case 'main'").count(), 1, "{text}");
        assert_eq!(text.matches("mobility method").count(), 1, "{text}");
        assert!(
            text.starts_with(
                "case 'main': mobility method: heat balance: the solve at T = 70.00 °C \
                 (iteration 1) failed: film collapse: |ε| reached 0.999500"
            ),
            "{text}"
        );
        assert!(text.contains("crank angle 322.13° (cycle 1)"), "{text}");
        assert!(!text.contains("mobility_model"), "{text}");
    }

    /// An orbit that leaves the map says so and names the keys that follow it further.
    #[test]
    fn leaving_the_map_names_the_models_that_go_further() {
        let e = RunError::Mobility {
            case: "heavy".into(),
            source: MobilityError::OutsideModelRange {
                time: 0.03,
                crank_angle_deg: 322.13,
                cycle: 1,
                eccentricity: 0.99,
                model_limit: 0.99,
                collapse_limit: 0.9995,
            },
        };
        let text = e.to_string();
        assert!(
            text.starts_with(
                "case 'heavy': mobility method: the orbit left the mobility model's range"
            ),
            "{text}"
        );
        assert!(
            text.ends_with(
                "(cycle 1); solver.mobility_model = \"booker\" or \"exact_short\" follow the \
                 orbit to the collapse limit"
            ),
            "{text}"
        );
    }
}

#[cfg(test)]
mod method_failure_tests {
    //! Each method's result survives the other's failure (issue 12, item 9): the solvers are
    //! injected so that one fails on demand; the surviving result and the failure's message
    //! are both in the report.
    use super::*;

    const LOAD: &str =
        "crank_angle_deg = [0.0, 180.0]\nx_n = [-1500.0, -900.0]\ny_n = [0.0, 200.0]";

    fn case() -> Case {
        let text = crate::case::test_case_text(
            "two_methods",
            LOAD,
            "[solver]\nrigorous_film = \"short_bearing\"\n",
        );
        Case::from_text(&text, Path::new("two_methods.toml")).expect("valid case")
    }

    /// An inverse failure as the solver reports it (its text names the injected quantity).
    fn failing(case: &Case, _: &dyn RunObserver) -> Result<MethodResult, RunError> {
        Err(RunError::Rigorous {
            case: case.name.clone(),
            source: RigorousError::Inverse(
                jbearing_solvers::inverse::InverseError::NonFiniteLoad {
                    quantity: "injected failure",
                    time: 0.5,
                },
            ),
        })
    }

    fn failing_mobility(case: &Case, _: &dyn RunObserver) -> Result<MethodResult, RunError> {
        Err(RunError::MobilityMap {
            case: case.name.clone(),
            source: std::sync::Arc::new(MapBuildError::Map(
                jbearing_solvers::mobility::MobilityMapError::InvalidParameter {
                    name: "injected failure",
                    value: 2.0,
                },
            )),
        })
    }

    const RIGOROUS_FAILURE: &str = "case 'two_methods': rigorous method: non-finite injected \
                                    failure in the load history at t = 5.000000e-1 s";
    const MOBILITY_FAILURE: &str =
        "case 'two_methods': mobility map: invalid map parameter injected failure = 2";

    fn status(report: &CaseReport, key: &str) -> Option<String> {
        report
            .parameters
            .iter()
            .find(|p| p.key == key)
            .map(|p| match &p.value {
                ParameterValue::Text(t) => t.clone(),
                other => panic!("{key} is not text: {other:?}"),
            })
    }

    #[test]
    fn a_mobility_failure_keeps_the_rigorous_result() {
        let report =
            solve_case_with(&case(), &Quiet, run_rigorous, failing_mobility).expect("report");
        assert!(report.method(Method::Rigorous).is_some());
        assert!(report.method(Method::Mobility).is_none());
        assert_eq!(
            status(&report, MOBILITY_STATUS).as_deref(),
            Some(format!("failed: {MOBILITY_FAILURE}").as_str())
        );
        assert_eq!(status(&report, RIGOROUS_STATUS), None);
        // The summary rows carry the rigorous values alone.
        assert!(report.summary.iter().all(|r| r.mobility.is_none()));
        assert!(report.summary.iter().any(|r| r.rigorous.is_some()));
        report.validate().expect("a writable report");
    }

    #[test]
    fn a_rigorous_failure_keeps_the_mobility_result() {
        let report = solve_case_with(&case(), &Quiet, failing, run_mobility).expect("report");
        assert!(report.method(Method::Mobility).is_some());
        assert_eq!(
            status(&report, RIGOROUS_STATUS).as_deref(),
            Some(format!("failed: {RIGOROUS_FAILURE}").as_str())
        );
    }

    #[test]
    fn the_case_fails_only_when_every_method_failed() {
        let err = solve_case_with(&case(), &Quiet, failing, failing_mobility)
            .expect_err("nothing to report");
        assert_eq!(
            err.to_string(),
            format!(
                "case 'two_methods': every method failed: {RIGOROUS_FAILURE}; {MOBILITY_FAILURE}"
            )
        );
        // The typed source survives for callers that match on it.
        let source = std::error::Error::source(&failing(&case(), &Quiet).unwrap_err())
            .map(|s| s.to_string());
        assert_eq!(
            source.as_deref(),
            Some("non-finite injected failure in the load history at t = 5.000000e-1 s")
        );
    }
}

#[cfg(test)]
mod field_tests {
    //! The rigorous fields written to CASE.h5 on a coarse grid: the film-thickness field's
    //! minimum at each stored instant is the solver's own minimum film thickness at that step
    //! (computed independently in the film model), and its maximum is c (1 + |ε|).
    use super::*;

    #[test]
    fn film_thickness_field_matches_the_solvers_minimum() {
        let text = crate::case::test_case_text(
            "coarse",
            "crank_angle_deg = [0.0, 180.0]\nx_n = [-1500.0, -900.0]\ny_n = [0.0, 200.0]",
            "[grid]\nn_theta = 24\nn_z = 7\n[solver]\ntime_steps_per_cycle = 36\nmax_cycles = 1\n\
             [output]\nfield_snapshots = 6\n[methods]\nmobility = false\n",
        );
        let case = Case::from_text(&text, Path::new("coarse.toml")).expect("valid case");
        let result = run_rigorous(&case, &Quiet).expect("the coarse case solves");
        let fields = result.fields.as_ref().expect("fields");
        let h = fields
            .fields
            .iter()
            .find(|f| f.name == names::FILM_THICKNESS)
            .expect("film_thickness field");
        let h_min = result.series(names::MIN_FILM_THICKNESS).unwrap();
        let eps = result.series(names::ECCENTRICITY_RATIO).unwrap();
        assert_eq!(fields.time.len(), 6);
        for (i, t) in fields.time.iter().enumerate() {
            let step = result
                .time
                .iter()
                .position(|s| (s - t).abs() <= 1e-12 * t.abs().max(1.0))
                .expect("a stored instant is a step");
            let slice = h.values.index_axis(ndarray::Axis(0), i);
            let lo = slice.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = slice.iter().copied().fold(0.0, f64::max);
            // The grid samples θ every 15°: the sampled minimum lies within
            // c ε (1 − cos 7.5°) of the true one, above it.
            let c = case.radial_clearance;
            let tol = c * eps.values[step] * (1.0 - 7.5f64.to_radians().cos()) + 1e-15;
            assert!(
                lo >= h_min.values[step] - 1e-15 && lo <= h_min.values[step] + tol,
                "instant {i}: field min {lo} vs solver h_min {}",
                h_min.values[step]
            );
            assert!(hi <= c * (1.0 + eps.values[step]) + 1e-15);
        }
    }
}
