//! Case files: one bearing, its lubricant, its load / speed / feed histories, the grid, the
//! solver settings and the outputs, in TOML.
//!
//! ```text
//!   case.toml ──toml+serde (deny_unknown_fields)──► schema::CaseFile (as written, units in keys)
//!            ──resolve (units::, CSV tables, checks)──► Case (SI, defaults filled in, validated)
//! ```
//!
//! Every key is documented in `cases/README.md`. Errors name the file, the key and the line
//! ([`CaseError`]). Histories are periodic over the cycle (`operation.cycle_deg`) and given
//! against crank angle in degrees, inline or from a CSV file whose path is relative to the case
//! file.

pub mod compressor;
pub mod error;
pub mod mechanism;
pub mod schema;
pub mod units;
pub use error::{CaseWarning, WarningKind};
#[cfg(test)]
mod csv_tests;
#[cfg(test)]
mod elastic_tests;
#[cfg(test)]
mod lubricant_tests;

/// A valid case text for unit tests: the compressor main bearing's geometry (Yu & Sawicki
/// Table II) with one groove and a 0.2068 MPa feed, named `name`, with the `[load]` body `load`
/// and the extra tables `extra` appended. `[load]` is on line 21, its first key on line 22.
#[cfg(test)]
pub(crate) fn test_case_text(name: &str, load: &str, extra: &str) -> String {
    format!(
        r#"version = 1
name = "{name}"

[bearing]
radius_m = 0.02743
length_m = 0.018288
radial_clearance_m = 4.89e-5

[[grooves]]
center_angle_deg = 0.0
axial_center_m = 0.0
circumferential_length_m = 0.0249
axial_width_m = 0.00381

[lubricant]
viscosity_pa_s = 0.02

[operation]
cycle_deg = 360.0
crank_speed_rpm = 1800.0
[load]
{load}

[feed]
pressure_pa = 2.068e5
{extra}"#
    )
}

use std::path::{Path, PathBuf};

use jbearing_solvers::closed_form::{ClosedFormError, ClosedFormModel};
use jbearing_solvers::elastic::{ElasticParams, HousingShape, Material, square_layers};
use jbearing_solvers::heat_balance::HeatBalanceParams;
use jbearing_solvers::mobility::{LoadInterpolation, TabulatedLoad};
use jbearing_solvers::reynolds::GridParams;
use jbearing_solvers::time_scheme::TimeScheme;
use jbearing_solvers::viscosity::{IsoViscosityGrade, Temperature, ViscosityModel, Vogel};

pub use self::error::{CaseError, Locator};
use self::schema::*;
use self::units::{Quantity, column_factor, deg_to_rad, rpm_to_rad_s};
use crate::output::{Geometry, InputFile, Parameter};
/// The feed groove of the film model, SI (one type for the case and the solver).
pub use jbearing_solvers::reynolds::Groove;

/// A periodic history over crank angle: a constant or a table, linearly interpolated and wrapped.
#[derive(Debug, Clone, PartialEq)]
pub enum Schedule {
    /// The same value at all times.
    Constant(f64),
    /// Values at increasing crank angles (deg) spanning less than one cycle.
    Table {
        /// Crank angles (deg).
        angles_deg: Vec<f64>,
        /// Values, SI.
        values: Vec<f64>,
    },
}

impl Schedule {
    /// Value at crank angle `angle_deg` for a cycle of `cycle_deg`.
    pub fn at(&self, angle_deg: f64, cycle_deg: f64) -> f64 {
        match self {
            Schedule::Constant(v) => *v,
            Schedule::Table { angles_deg, values } => {
                let n = angles_deg.len();
                if n == 1 {
                    return values[0];
                }
                let a0 = angles_deg[0];
                let x = a0 + (angle_deg - a0).rem_euclid(cycle_deg);
                let i = angles_deg.partition_point(|&a| a <= x).max(1) - 1;
                let (xa, ya) = (angles_deg[i], values[i]);
                let (xb, yb) = if i + 1 < n {
                    (angles_deg[i + 1], values[i + 1])
                } else {
                    (a0 + cycle_deg, values[0])
                };
                ya + (yb - ya) * ((x - xa) / (xb - xa)).clamp(0.0, 1.0)
            }
        }
    }

    /// Time mean over one cycle (trapezoidal on the wrapped table).
    pub fn mean(&self, cycle_deg: f64) -> f64 {
        match self {
            Schedule::Constant(v) => *v,
            Schedule::Table { .. } => {
                let n = 3600;
                (0..n)
                    .map(|k| self.at(k as f64 * cycle_deg / n as f64, cycle_deg))
                    .sum::<f64>()
                    / n as f64
            }
        }
    }
}

/// What to compute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Methods {
    /// Booker's mobility method.
    pub mobility: bool,
    /// The rigorous (JFO) inverse solution.
    pub rigorous: bool,
    /// Static-equilibrium table of the closed-form models.
    pub closed_form: bool,
}

/// Which mobility model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MobilityModelChoice {
    /// Booker's closed-form short-bearing mobility (\[Flores2006\] eqs. 28–35).
    Booker,
    /// The exact short-bearing mobility (inverted squeeze integrals).
    ExactShort,
    /// The finite-length map tabulated from pure-squeeze solutions.
    Map,
}

/// Which film the inverse ("rigorous") solver steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RigorousFilm {
    /// The mass-conserving universal Reynolds (JFO) film: the rigorous method proper.
    Reynolds,
    /// The analytic short-bearing film (Gumbel half film, moving journal): the inverse solver's
    /// closed-form film, not mass-conserving; for comparisons and quick checks.
    ShortBearing,
}

/// Solver settings, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverOptions {
    /// Time steps per cycle of the rigorous solver.
    pub time_steps_per_cycle: usize,
    /// Most cycles before giving up on periodicity.
    pub max_cycles: usize,
    /// Periodicity tolerance on ε (max over the cycle of |ε(t) − ε(t − τ)|).
    pub periodicity_tolerance: f64,
    /// Newton tolerance on the force residual, relative to the peak load.
    pub force_tolerance: f64,
    /// Film-collapse limit on |ε|.
    pub eccentricity_limit: f64,
    /// Time discretization of the rigorous film (the solvers crate's one scheme and default).
    pub time_scheme: TimeScheme,
    /// Mobility model.
    pub mobility_model: MobilityModelChoice,
    /// ε at the start.
    pub initial_eccentricity: [f64; 2],
    /// Film of the inverse solver.
    pub rigorous_film: RigorousFilm,
    /// Local error tolerance of a rigorous step in ε (0: no error control).
    pub step_error_tolerance: f64,
    /// Extrapolate the cycle-to-cycle map of the rigorous solver when it converges slowly.
    pub cycle_extrapolation: bool,
}

/// Output settings, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputOptions {
    /// Samples of the stored cycle.
    pub samples_per_cycle: usize,
    /// Field snapshots of the final cycle.
    pub field_snapshots: usize,
    /// Write the PNG plots.
    pub plots: bool,
}

/// The heat balance of a case: the oil's Vogel curve and the balance's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CaseHeatBalance {
    /// μ₀(T) of the oil.
    pub vogel: Vogel,
    /// T_in, ρ c_p, the share to housing and shaft, tolerance.
    pub params: HeatBalanceParams,
    /// Barus α (1/Pa) of the rigorous film at T_eff (0: none).
    pub pressure_coefficient: f64,
}

/// A validated case in SI units.
#[derive(Debug, Clone)]
pub struct Case {
    /// Name (output files are named after it).
    pub name: String,
    /// One line of description.
    pub description: String,
    /// The case file, if read from one.
    pub path: Option<PathBuf>,
    /// The TOML text as given.
    pub text: String,
    /// CSV tables it refers to, verbatim.
    pub input_files: Vec<InputFile>,
    /// Bearing radius R (m).
    pub radius: f64,
    /// Bearing length L (m).
    pub length: f64,
    /// Radial clearance c (m).
    pub radial_clearance: f64,
    /// Feed grooves.
    pub grooves: Vec<Groove>,
    /// Viscosity μ (Pa·s): the constant, or μ₀ at the mean film temperature when
    /// `viscosity_model` is given (what the mobility method and the closed forms use).
    pub viscosity: f64,
    /// Temperature-dependent viscosity of the rigorous film (`[lubricant.vogel]`,
    /// `[lubricant.temperature]`, `pressure_viscosity_coefficient_per_pa`).
    pub viscosity_model: Option<ViscosityModel>,
    /// The named oil (`lubricant.oil`), if one was given.
    pub oil: Option<String>,
    /// The effective-temperature heat balance (`[lubricant.heat_balance]`): each method
    /// iterates its film at μ(T_eff) until the balance closes ([`Case::at_film_temperature`]).
    pub heat_balance: Option<CaseHeatBalance>,
    /// Bulk modulus β (Pa).
    pub bulk_modulus: f64,
    /// Cavitation pressure, gauge (Pa).
    pub cavitation_pressure: f64,
    /// Ambient pressure, gauge (Pa).
    pub ambient_pressure: f64,
    /// Film fraction held in a groove whose feed is cut off.
    pub starved_film_fraction: f64,
    /// Cycle length (crank degrees).
    pub cycle_deg: f64,
    /// Crank speed Ω (rad/s).
    pub crank_speed: f64,
    /// Journal speed ω_j (rad/s), fixed frame.
    pub journal_speed: Schedule,
    /// Bearing speed ω_b (rad/s), fixed frame.
    pub bearing_speed: Schedule,
    /// Load on the journal in the bearing frame: crank angles (deg) and forces (N).
    pub load_angles_deg: Vec<f64>,
    /// Forces (N) at `load_angles_deg`.
    pub load_forces: Vec<[f64; 2]>,
    /// Interpolation of the load table.
    pub load_interpolation: LoadInterpolation,
    /// Feed pressure, gauge (Pa), the same at every groove.
    pub feed_pressure: Schedule,
    /// Grid nodes around (periodic).
    pub n_theta: usize,
    /// Grid nodes along (ends included).
    pub n_z: usize,
    /// Solver settings.
    pub solver: SolverOptions,
    /// Output settings.
    pub output: OutputOptions,
    /// What to compute.
    pub methods: Methods,
    /// Closed-form models of the static-equilibrium table (empty: no table).
    pub closed_form_models: Vec<ClosedFormModel>,
    /// Elastic shaft and housing (`[elastic]`): on a steady case the deformable steady-load
    /// solve (`jbearing_solvers::elastic::solve_steady_load`) runs beside the methods; the
    /// rigorous method steps the deformable film (`jbearing_solvers::elastic::ElasticFilm`).
    pub elastic: Option<ElasticParams>,
    /// Values far outside what journal bearings have (the ranges: [`PLAUSIBLE_CLEARANCE_RATIO`]).
    pub warnings: Vec<CaseWarning>,
}

impl Case {
    /// Read and resolve the case file at `path`.
    pub fn from_file(path: &Path) -> Result<Self, CaseError> {
        let text = std::fs::read_to_string(path).map_err(|source| CaseError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        Self::from_text(&text, path)
    }

    /// Resolve a case from its TOML `text`; `path` names it in messages and anchors CSV paths.
    pub fn from_text(text: &str, path: &Path) -> Result<Self, CaseError> {
        let ctx = Ctx::new(text, path);
        let raw: CaseFile = ctx.parse()?;
        resolve(raw, &ctx)
    }

    /// Geometry for the writers.
    pub fn geometry(&self) -> Geometry {
        Geometry {
            radius: self.radius,
            length: self.length,
            radial_clearance: self.radial_clearance,
        }
    }

    /// Period of one cycle τ (s).
    pub fn period(&self) -> f64 {
        deg_to_rad(self.cycle_deg) / self.crank_speed
    }

    /// The case with its film at the uniform temperature `temperature` (°C): viscosity μ₀(T)
    /// of the heat balance's oil, no temperature field. One trial of the heat balance; the case
    /// itself when it has none.
    pub fn at_film_temperature(&self, temperature: f64) -> Case {
        let mut case = self.clone();
        if let Some(h) = &self.heat_balance {
            case.viscosity = h.vogel.viscosity(temperature);
            case.viscosity_model = (h.pressure_coefficient > 0.0).then_some(ViscosityModel {
                vogel: h.vogel,
                temperature: Temperature::Constant(temperature),
                pressure_coefficient: h.pressure_coefficient,
            });
        }
        case
    }

    /// The load table as the solvers take it.
    pub fn load(&self) -> TabulatedLoad {
        TabulatedLoad::new(
            self.load_angles_deg.clone(),
            self.load_forces.clone(),
            self.cycle_deg,
            self.crank_speed,
            self.load_interpolation,
        )
        .expect("validated when the case was resolved")
    }

    /// Resolved parameters, for the report.
    pub fn parameters(&self) -> Vec<Parameter> {
        let mut p = self.bearing_parameters();
        p.extend(self.solver_parameters());
        self.push_viscosity_origin(&mut p);
        self.push_grooves(&mut p);
        if let Some(e) = &self.elastic {
            push_elastic(&mut p, e, self.radius);
        }
        p
    }

    /// Geometry, lubricant constants, the cycle and the mean speeds.
    fn bearing_parameters(&self) -> Vec<Parameter> {
        vec![
            Parameter::number("radius", self.radius, "m", "bearing (journal) radius R"),
            Parameter::number("length", self.length, "m", "bearing length L"),
            Parameter::number(
                "radial_clearance",
                self.radial_clearance,
                "m",
                "radial clearance c",
            ),
            Parameter::number(
                "viscosity",
                self.viscosity,
                "Pa s",
                "dynamic viscosity (with a Vogel law: at the mean film temperature; with a heat \
             balance: at the supply temperature, each method reporting its own \
             effective_viscosity)",
            ),
            Parameter::number(
                "bulk_modulus",
                self.bulk_modulus,
                "Pa",
                "lubricant bulk modulus",
            ),
            Parameter::number(
                "cavitation_pressure",
                self.cavitation_pressure,
                "Pa",
                "cavitation pressure, gauge",
            ),
            Parameter::number(
                "ambient_pressure",
                self.ambient_pressure,
                "Pa",
                "ambient pressure, gauge",
            ),
            Parameter::number(
                "starved_film_fraction",
                self.starved_film_fraction,
                "1",
                "film fraction of a groove whose feed is cut off",
            ),
            Parameter::number(
                "cycle",
                self.cycle_deg,
                "degree",
                "cycle length in crank angle",
            ),
            Parameter::number("crank_speed", self.crank_speed, "rad/s", "crank speed"),
            Parameter::number(
                "journal_speed_mean",
                self.journal_speed.mean(self.cycle_deg),
                "rad/s",
                "cycle mean of the journal speed (fixed frame)",
            ),
            Parameter::number(
                "bearing_speed_mean",
                self.bearing_speed.mean(self.cycle_deg),
                "rad/s",
                "cycle mean of the bearing speed (fixed frame)",
            ),
        ]
    }

    /// Grid and solver options.
    fn solver_parameters(&self) -> Vec<Parameter> {
        vec![
            Parameter::integer("n_theta", self.n_theta as i64, "grid nodes around"),
            Parameter::integer("n_z", self.n_z as i64, "grid nodes along"),
            Parameter::integer(
                "time_steps_per_cycle",
                self.solver.time_steps_per_cycle as i64,
                "time steps per cycle (rigorous)",
            ),
            Parameter::integer("max_cycles", self.solver.max_cycles as i64, "most cycles"),
            Parameter::number(
                "periodicity_tolerance",
                self.solver.periodicity_tolerance,
                "1",
                "periodicity tolerance on the eccentricity ratio",
            ),
            Parameter::number(
                "force_tolerance",
                self.solver.force_tolerance,
                "1",
                "Newton tolerance on the force residual, relative to the peak load",
            ),
            Parameter::text(
                "mobility_model",
                match self.solver.mobility_model {
                    MobilityModelChoice::Booker => "booker",
                    MobilityModelChoice::ExactShort => "exact_short",
                    MobilityModelChoice::Map => "map",
                },
                "mobility model",
            ),
            Parameter::text(
                "rigorous_film",
                match self.solver.rigorous_film {
                    RigorousFilm::Reynolds => "reynolds",
                    RigorousFilm::ShortBearing => "short_bearing",
                },
                "film model of the inverse solver",
            ),
            Parameter::text(
                "time_scheme",
                self.solver.time_scheme.name(),
                "time discretization of the rigorous film (bdf2, backward_euler, crank_nicolson)",
            ),
            Parameter::number(
                "step_error_tolerance",
                self.solver.step_error_tolerance,
                "1",
                "local error tolerance of a rigorous step in the eccentricity ratio (0: none)",
            ),
            Parameter::text(
                "cycle_extrapolation",
                if self.solver.cycle_extrapolation {
                    "true"
                } else {
                    "false"
                },
                "extrapolation of the rigorous cycle-to-cycle map",
            ),
        ]
    }

    /// Where the viscosity comes from: a named oil, a heat balance or a Vogel law with its
    /// film temperatures.
    fn push_viscosity_origin(&self, p: &mut Vec<Parameter>) {
        if let Some(oil) = &self.oil {
            p.push(Parameter::text(
                "oil",
                oil,
                "named oil: ISO 3448 grade, Vogel curve from Walther through 40 and 100 degC",
            ));
        }
        if let Some(h) = &self.heat_balance {
            push_heat_balance(p, h);
        }
        if let Some(m) = &self.viscosity_model {
            push_vogel(p, &m.vogel);
            p.push(Parameter::number(
                "pressure_viscosity_coefficient",
                m.pressure_coefficient,
                "Pa-1",
                "Barus alpha of the rigorous film (the mobility method and closed forms take the \
                 mean-temperature viscosity)",
            ));
            match m.temperature {
                Temperature::Constant(t) => p.push(Parameter::number(
                    "film_temperature",
                    t,
                    "degC",
                    "film temperature (constant)",
                )),
                Temperature::Linear { inlet, outlet }
                | Temperature::LinearOverSpan { inlet, outlet, .. } => {
                    p.push(Parameter::number(
                        "inlet_temperature",
                        inlet,
                        "degC",
                        "film temperature at the supply",
                    ));
                    p.push(Parameter::number(
                        "outlet_temperature",
                        outlet,
                        "degC",
                        "film temperature at the end of the rise",
                    ));
                }
            }
        }
    }

    /// Centre, length and width of each groove.
    fn push_grooves(&self, p: &mut Vec<Parameter>) {
        for (i, g) in self.grooves.iter().enumerate() {
            p.push(Parameter::number(
                &format!("groove{i}_center_angle"),
                g.center_angle,
                "rad",
                "groove centre angle, bearing frame",
            ));
            p.push(Parameter::number(
                &format!("groove{i}_axial_center"),
                g.center_z,
                "m",
                "groove centre, axial",
            ));
            p.push(Parameter::number(
                &format!("groove{i}_circumferential_length"),
                g.angular_width * self.radius,
                "m",
                "groove length around",
            ));
            p.push(Parameter::number(
                &format!("groove{i}_axial_width"),
                g.axial_width,
                "m",
                "groove width along",
            ));
        }
    }
}

/// The `[heat_balance]` parameters: the Vogel law and the balance's constants.
fn push_heat_balance(p: &mut Vec<Parameter>, h: &CaseHeatBalance) {
    let hp = &h.params;
    push_vogel(p, &h.vogel);
    p.push(Parameter::number(
        "supply_temperature",
        hp.supply_temperature,
        "degC",
        "oil supply temperature T_in of the heat balance",
    ));
    p.push(Parameter::number(
        "heat_to_housing_and_shaft",
        hp.heat_to_structure,
        "1",
        "share of the power loss conducted away through housing and shaft",
    ));
    p.push(Parameter::number(
        "volumetric_heat_capacity",
        hp.volumetric_heat_capacity,
        "J m-3 K-1",
        "rho c_p of the oil",
    ));
    p.push(Parameter::number(
        "pressure_viscosity_coefficient",
        h.pressure_coefficient,
        "Pa-1",
        "Barus alpha of the rigorous film (the mobility method and closed forms take mu(T_eff))",
    ));
    p.push(Parameter::number(
        "heat_balance_tolerance",
        hp.tolerance,
        "K",
        "tolerance on |T_balance - T_eff|",
    ));
}

/// The `[elastic]` parameters as resolved (the layer counts the mesh gets).
fn push_elastic(p: &mut Vec<Parameter>, e: &ElasticParams, radius: f64) {
    let HousingShape::Square { half_width } = e.housing else {
        unreachable!("case files make square housings")
    };
    let [shaft_layers, housing_layers] = e.layers.unwrap_or([
        square_layers(e.hole_radius, radius, e.n_theta),
        square_layers(radius, half_width, e.n_theta),
    ]);
    p.push(Parameter::number(
        "elastic_youngs_modulus",
        e.shaft_material.youngs_modulus,
        "Pa",
        "Young's modulus of shaft and housing",
    ));
    p.push(Parameter::number(
        "elastic_poisson_ratio",
        e.shaft_material.poisson_ratio,
        "1",
        "Poisson's ratio of shaft and housing",
    ));
    p.push(Parameter::number(
        "elastic_shaft_hole_radius",
        e.hole_radius,
        "m",
        "radius of the shaft's central hole (held radially)",
    ));
    p.push(Parameter::number(
        "elastic_housing_half_width",
        half_width,
        "m",
        "half-width of the square housing (outer edges fixed)",
    ));
    p.push(Parameter::integer(
        "elastic_n_theta",
        e.n_theta as i64,
        "finite-element nodes around the film surface (both bodies)",
    ));
    p.push(Parameter::integer(
        "elastic_shaft_layers",
        shaft_layers as i64,
        "element layers of the shaft, journal surface to hole",
    ));
    p.push(Parameter::integer(
        "elastic_housing_layers",
        housing_layers as i64,
        "element layers of the housing, bore to outer edges",
    ));
    p.push(Parameter::number(
        "elastic_gap_tolerance",
        e.gap_tolerance,
        "1",
        "steady coupling converged when |C p - g| <= this times the clearance",
    ));
    p.push(Parameter::number(
        "elastic_dynamic_gap_tolerance",
        e.dynamic_gap_tolerance,
        "1",
        "the same in every film step of the rigorous (dynamic) method",
    ));
    p.push(Parameter::integer(
        "elastic_max_iterations",
        e.max_iterations as i64,
        "most coupling iterations",
    ));
}

/// Parsing context: the file, its text and the key locator.
pub(crate) struct Ctx<'a> {
    pub(crate) file: PathBuf,
    pub(crate) text: &'a str,
    pub(crate) locator: Locator<'a>,
}

impl<'a> Ctx<'a> {
    pub(crate) fn new(text: &'a str, path: &Path) -> Self {
        Self {
            file: path.to_path_buf(),
            text,
            locator: Locator::new(text),
        }
    }

    /// Deserialize the schema `T`, mapping toml's errors to [`CaseError`]s with the key named.
    pub(crate) fn parse<T: serde::de::DeserializeOwned>(&self) -> Result<T, CaseError> {
        if let Err(e) = toml::de::DeTable::parse(self.text) {
            let (line, column) = e
                .span()
                .map_or((1, 1), |s| error::line_column(self.text, s.start));
            let key = self
                .text
                .lines()
                .nth(line - 1)
                .map(|l| l.split('=').next().unwrap_or(l).trim().to_string())
                .unwrap_or_default();
            return Err(CaseError::Syntax {
                file: self.file.clone(),
                key,
                line,
                column,
                message: e.message().trim().to_string(),
            });
        }
        toml::from_str(self.text).map_err(|e| {
            let message = e.message().trim().to_string();
            let span = e.span();
            let mut key = span
                .as_ref()
                .and_then(|s| self.locator.key_at(s))
                .unwrap_or_default();
            // "missing field `x`": the span is the enclosing table; name the missing key.
            if let Some(missing) = message
                .strip_prefix("missing field `")
                .and_then(|m| m.split('`').next())
            {
                key = if key.is_empty() {
                    missing.to_string()
                } else {
                    format!("{key}.{missing}")
                };
            }
            // "unknown field `x`, expected …": the span is the key itself already.
            let line = span.map_or_else(
                || self.locator.line_of(&key),
                |s| error::line_column(self.text, s.start).0,
            );
            CaseError::Key {
                file: self.file.clone(),
                line,
                key: if key.is_empty() {
                    "(top level)".into()
                } else {
                    key
                },
                message,
            }
        })
    }

    /// An error about `key` (dotted path).
    pub(crate) fn err(&self, key: &str, message: impl Into<String>) -> CaseError {
        CaseError::Key {
            file: self.file.clone(),
            line: self.locator.line_of(key),
            key: key.to_string(),
            message: message.into(),
        }
    }

    /// A positive, finite number.
    pub(crate) fn positive(&self, key: &str, v: f64) -> Result<f64, CaseError> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be a finite number > 0, got {v}")))
        }
    }

    /// A finite number.
    pub(crate) fn finite(&self, key: &str, v: f64) -> Result<f64, CaseError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be a finite number, got {v}")))
        }
    }

    /// Path of a CSV file named by `key`, relative to the case file's directory.
    pub(crate) fn relative(&self, rel: &str) -> PathBuf {
        let dir = self.file.parent().unwrap_or(Path::new("."));
        dir.join(rel)
    }

    /// Read a CSV table: the first column `crank_angle_deg`, then one column per `wanted`
    /// (base name, quantity), each with a unit suffix. Returns the file's text and the columns
    /// in SI (angles in degrees).
    pub(crate) fn read_table(
        &self,
        key: &str,
        rel: &str,
        wanted: &[(&str, Quantity)],
    ) -> Result<CsvTable, CaseError> {
        let csv_path = self.relative(rel);
        let csv_err = |csv_line: usize, message: String| CaseError::Csv {
            csv: csv_path.clone(),
            csv_line,
            message,
            file: self.file.clone(),
            key: key.to_string(),
            line: self.locator.line_of(key),
        };
        let text = std::fs::read_to_string(&csv_path).map_err(|e| {
            self.err(
                key,
                format!("cannot read the CSV file '{}': {e}", csv_path.display()),
            )
        })?;
        // RFC 4180 through the `csv` crate: quoted fields, CRLF, a UTF-8 byte-order mark (the
        // reader strips it), '#' comment lines and blank lines skipped; cells trimmed. Lines are
        // the file's own 1-based line numbers (`Position::line`), whatever was skipped.
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .flexible(true)
            .from_reader(text.as_bytes());
        let mut records = reader.records().filter(|r| {
            // A line of only commas / spaces is blank, not a row of empty cells.
            !matches!(r, Ok(rec) if rec.iter().all(str::is_empty))
        });
        let read_err = |e: csv::Error| {
            let line = e.position().map_or(1, |p| p.line().max(1) as usize);
            csv_err(line, format!("not a valid CSV row: {e}"))
        };
        let header = match records.next() {
            None => return Err(csv_err(1, "the CSV file is empty (no header row)".into())),
            Some(r) => r.map_err(read_err)?,
        };
        let hline = record_line(&header);
        let headers: Vec<String> = header.iter().map(str::to_string).collect();
        let index = column_index(&headers, wanted, |message| csv_err(hline, message))?;
        let (angles, cols) = read_rows(records, &headers, &index, &csv_err, &read_err)?;
        if angles.is_empty() {
            return Err(csv_err(hline, "the table has a header but no rows".into()));
        }
        Ok((text, angles, cols))
    }
}

/// A CSV table as read: the file's text, the crank angles (deg) and the wanted columns (SI).
pub(crate) type CsvTable = (String, Vec<f64>, Vec<Vec<f64>>);

/// 1-based line of a CSV record in its file.
fn record_line(r: &csv::StringRecord) -> usize {
    r.position().map_or(1, |p| p.line() as usize)
}

/// The column of each wanted quantity and its factor to SI, after checking that the first
/// column is `crank_angle_deg`.
fn column_index(
    headers: &[String],
    wanted: &[(&str, Quantity)],
    header_err: impl Fn(String) -> CaseError,
) -> Result<Vec<(usize, f64)>, CaseError> {
    if column_factor(&headers[0], "crank_angle", Quantity::Angle) != Some(deg_to_rad(1.0)) {
        return Err(header_err(format!(
            "the first column must be 'crank_angle_deg', found '{}'",
            headers[0].escape_debug()
        )));
    }
    let mut index = Vec::new();
    for (base, q) in wanted {
        let found = headers
            .iter()
            .enumerate()
            .skip(1)
            .find_map(|(i, h)| column_factor(h, base, *q).map(|f| (i, f)));
        match found {
            Some(x) => index.push(x),
            None => {
                return Err(header_err(format!(
                    "no column '{base}_<unit>' (unit one of: {}) among {:?}",
                    q.unit_list(),
                    headers
                )));
            }
        }
    }
    Ok(index)
}

/// The table's rows: every cell a finite number, crank angles increasing, the wanted columns
/// scaled to SI.
fn read_rows(
    records: impl Iterator<Item = csv::Result<csv::StringRecord>>,
    headers: &[String],
    index: &[(usize, f64)],
    csv_err: &impl Fn(usize, String) -> CaseError,
    read_err: &impl Fn(csv::Error) -> CaseError,
) -> Result<(Vec<f64>, Vec<Vec<f64>>), CaseError> {
    let mut angles = Vec::new();
    let mut cols = vec![Vec::new(); index.len()];
    for record in records {
        let record = record.map_err(read_err)?;
        let line = record_line(&record);
        if record.len() != headers.len() {
            return Err(csv_err(
                line,
                format!(
                    "row has {} cells, the header has {}",
                    record.len(),
                    headers.len()
                ),
            ));
        }
        let num = |c: usize| -> Result<f64, CaseError> {
            match record[c].parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(csv_err(
                    line,
                    format!(
                        "column '{}': '{}' is not a finite number",
                        headers[c],
                        record[c].escape_debug()
                    ),
                )),
            }
        };
        let a = num(0)?;
        if let Some(&prev) = angles.last()
            && a <= prev
        {
            return Err(csv_err(
                line,
                format!("crank angle {a}° does not increase (previous row {prev}°)"),
            ));
        }
        angles.push(a);
        for (k, (c, f)) in index.iter().enumerate() {
            cols[k].push(num(*c)? * f);
        }
    }
    Ok((angles, cols))
}

/// A periodic history table must span less than one cycle (the load table's rule, applied to
/// the feed and speed tables too: a longer table would be cut off silently).
fn check_span(ctx: &Ctx<'_>, key: &str, angles: &[f64], cycle_deg: f64) -> Result<(), CaseError> {
    if let (Some(first), Some(last)) = (angles.first(), angles.last()) {
        let span = last - first;
        if span >= cycle_deg {
            return Err(ctx.err(
                key,
                format!(
                    "table spans {span}° (from {first}° to {last}°) which does not fit in one \
                     cycle of {cycle_deg}°"
                ),
            ));
        }
    }
    Ok(())
}

/// Check an inline table's angles: finite, increasing, non-empty, lengths match.
fn check_inline(
    ctx: &Ctx<'_>,
    angle_key: &str,
    angles: &[f64],
    columns: &[(&str, &[f64])],
) -> Result<(), CaseError> {
    if angles.is_empty() {
        return Err(ctx.err(angle_key, "the table is empty: give at least one point"));
    }
    for (i, a) in angles.iter().enumerate() {
        if !a.is_finite() {
            return Err(ctx.err(angle_key, format!("entry {i} is {a}, not a finite number")));
        }
        if i > 0 && *a <= angles[i - 1] {
            return Err(ctx.err(
                angle_key,
                format!(
                    "entry {i} ({a}°) does not increase (previous {}°)",
                    angles[i - 1]
                ),
            ));
        }
    }
    for (key, col) in columns {
        if col.len() != angles.len() {
            return Err(ctx.err(
                key,
                format!(
                    "has {} entries, {angle_key} has {}",
                    col.len(),
                    angles.len()
                ),
            ));
        }
        if let Some((i, v)) = col.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(ctx.err(key, format!("entry {i} is {v}, not a finite number")));
        }
    }
    Ok(())
}

fn schedule(
    ctx: &Ctx<'_>,
    inputs: &mut Vec<InputFile>,
    section: &str,
    constant: Option<(&str, f64)>,
    file: Option<&str>,
    inline: Option<(&[f64], &str, &[f64])>,
    column: (&str, Quantity),
) -> Result<Option<Schedule>, CaseError> {
    let given = constant.is_some() as u8 + file.is_some() as u8 + inline.is_some() as u8;
    if given > 1 {
        return Err(ctx.err(
            section,
            "give only one of: a constant, `file`, or an inline table",
        ));
    }
    if let Some((key, v)) = constant {
        return Ok(Some(Schedule::Constant(
            ctx.finite(&format!("{section}.{key}"), v)?,
        )));
    }
    if let Some(rel) = file {
        let key = format!("{section}.file");
        let (text, angles, cols) = ctx.read_table(&key, rel, &[column])?;
        inputs.push(InputFile {
            path: rel.to_string(),
            text,
        });
        return Ok(Some(Schedule::Table {
            angles_deg: angles,
            values: cols.into_iter().next().unwrap_or_default(),
        }));
    }
    if let Some((angles, key, values)) = inline {
        let akey = format!("{section}.crank_angle_deg");
        let vkey = format!("{section}.{key}");
        check_inline(ctx, &akey, angles, &[(&vkey, values)])?;
        return Ok(Some(Schedule::Table {
            angles_deg: angles.to_vec(),
            values: values.to_vec(),
        }));
    }
    Ok(None)
}

/// The case's name: `name` as given, else the file's stem; it names the output files, so it
/// must be usable as a file name.
pub(crate) fn case_name(given: Option<&str>, ctx: &Ctx<'_>) -> Result<String, CaseError> {
    let name = match given {
        Some(n) => n.to_string(),
        None => ctx
            .file
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "case".into()),
    };
    if name.is_empty()
        || name.starts_with('.')
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c))
    {
        return Err(ctx.err(
            "name",
            format!("'{name}' is not usable as a file name (letters, digits, '_', '-', '.')"),
        ));
    }
    Ok(name)
}

/// The case file's sections resolved in file order, each stage checking its own keys.
fn resolve(raw: CaseFile, ctx: &Ctx<'_>) -> Result<Case, CaseError> {
    check_kind_and_version(&raw, ctx)?;
    let name = case_name(raw.name.as_deref(), ctx)?;
    let (radius, length, radial_clearance) = resolve_bearing(&raw.bearing, ctx)?;
    let (grooves, starved_film_fraction) = resolve_grooves(&raw, radius, length, ctx)?;

    let l = &raw.lubricant;
    let ResolvedViscosity {
        viscosity,
        model: viscosity_model,
        oil,
        heat_balance,
    } = resolve_viscosity(l, ctx)?;
    let (bulk_modulus, cavitation_pressure, ambient_pressure) = resolve_pressures(l, ctx)?;

    let o = &raw.operation;
    let cycle_deg = ctx.positive("operation.cycle_deg", o.cycle_deg)?;
    let crank_speed = rpm_to_rad_s(ctx.positive("operation.crank_speed_rpm", o.crank_speed_rpm)?);
    let mut input_files = Vec::new();
    let (journal_speed, bearing_speed) = resolve_speeds(o, cycle_deg, &mut input_files, ctx)?;

    let LoadTable {
        angles_deg: load_angles_deg,
        forces: load_forces,
        interpolation: interp,
    } = resolve_load(&raw.load, cycle_deg, crank_speed, &mut input_files, ctx)?;

    let feed_pressure = resolve_feed(
        &raw.feed,
        &grooves,
        ambient_pressure,
        cycle_deg,
        &mut input_files,
        ctx,
    )?;

    let g = raw.grid.resolve(length / (2.0 * radius));
    check_grid(&g, length, &grooves, ctx)?;

    let solver = resolve_solver(&raw.solver, ctx)?;
    let output = resolve_output(&raw.output, ctx)?;
    let steady = load_forces.iter().all(|f| *f == load_forces[0])
        && matches!(journal_speed, Schedule::Constant(_))
        && matches!(bearing_speed, Schedule::Constant(_));
    let (methods, closed_form_models, elastic) =
        resolve_methods(&raw, radius, steady, &solver, ctx)?;

    let mut case = Case {
        name,
        description: raw.description.clone().unwrap_or_default(),
        path: Some(ctx.file.clone()),
        text: ctx.text.to_string(),
        input_files,
        radius,
        length,
        radial_clearance,
        grooves,
        viscosity,
        viscosity_model,
        oil,
        heat_balance,
        bulk_modulus,
        cavitation_pressure,
        ambient_pressure,
        starved_film_fraction,
        cycle_deg,
        crank_speed,
        journal_speed,
        bearing_speed,
        load_angles_deg,
        load_forces,
        load_interpolation: interp,
        feed_pressure,
        n_theta: g.n_theta,
        n_z: g.n_z,
        solver,
        output,
        methods,
        closed_form_models,
        elastic,
        warnings: Vec::new(),
    };
    check_oil_supply(&case, ctx)?;
    case.warnings = plausibility_warnings(&case, ctx);
    Ok(case)
}

/// A single case of a known version (a sweep is a batch of cases).
fn check_kind_and_version(raw: &CaseFile, ctx: &Ctx<'_>) -> Result<(), CaseError> {
    if raw.sweep.is_some() {
        return Err(ctx.err(
            crate::sweep::SWEEP_TABLE,
            "this file is a sweep, one case per point: run it with `jbearing batch` (which \
             expands it; `jbearing check` prints the expansion)",
        ));
    }
    if raw.version != 1 {
        return Err(ctx.err(
            "version",
            format!(
                "this jbearing reads case files of version 1, not {}",
                raw.version
            ),
        ));
    }
    Ok(())
}

/// `[lubricant]` bulk modulus, cavitation and ambient pressures (p_cav at most p_amb).
fn resolve_pressures(l: &LubricantSection, ctx: &Ctx<'_>) -> Result<(f64, f64, f64), CaseError> {
    let bulk_modulus = ctx.positive("lubricant.bulk_modulus_pa", l.bulk_modulus_pa)?;
    let cavitation_pressure =
        ctx.finite("lubricant.cavitation_pressure_pa", l.cavitation_pressure_pa)?;
    let ambient_pressure = ctx.finite("lubricant.ambient_pressure_pa", l.ambient_pressure_pa)?;
    if cavitation_pressure > ambient_pressure {
        return Err(ctx.err(
            "lubricant.cavitation_pressure_pa",
            format!("{cavitation_pressure} Pa is above the ambient pressure {ambient_pressure} Pa"),
        ));
    }
    Ok((bulk_modulus, cavitation_pressure, ambient_pressure))
}

/// `[output]`: samples per cycle (at least 8), snapshots and plots.
fn resolve_output(out: &OutputSection, ctx: &Ctx<'_>) -> Result<OutputOptions, CaseError> {
    if out.samples_per_cycle < 8 {
        return Err(ctx.err(
            "output.samples_per_cycle",
            format!("{} is too few (at least 8)", out.samples_per_cycle),
        ));
    }
    Ok(OutputOptions {
        samples_per_cycle: out.samples_per_cycle,
        field_snapshots: out.field_snapshots,
        plots: out.plots,
    })
}

/// `[methods]`, `[closed_form]` and `[elastic]`: what to compute, refusing a case with nothing
/// to compute.
fn resolve_methods(
    raw: &CaseFile,
    radius: f64,
    steady: bool,
    solver: &SolverOptions,
    ctx: &Ctx<'_>,
) -> Result<(Methods, Vec<ClosedFormModel>, Option<ElasticParams>), CaseError> {
    let m = &raw.methods;
    let closed_form_models = resolve_closed_form(raw.closed_form.as_ref(), m.closed_form, ctx)?;
    // A dynamic case takes the deformation in the rigorous (inverse) method's Reynolds film.
    let dynamic_ok = m.rigorous && solver.rigorous_film == RigorousFilm::Reynolds;
    let elastic = raw
        .elastic
        .as_ref()
        .map(|e| resolve_elastic(e, radius, steady || dynamic_ok, solver.force_tolerance, ctx))
        .transpose()?;
    if !(m.mobility || m.rigorous || !closed_form_models.is_empty() || elastic.is_some()) {
        return Err(ctx.err(
            "methods",
            "every method is switched off: nothing to compute",
        ));
    }
    let methods = Methods {
        mobility: m.mobility,
        rigorous: m.rigorous,
        closed_form: !closed_form_models.is_empty(),
    };
    Ok((methods, closed_form_models, elastic))
}

/// The mass-conserving film needs oil from somewhere: a groove, or ends above p_cav (the
/// solver would refuse it only after the other methods had run).
fn check_oil_supply(case: &Case, ctx: &Ctx<'_>) -> Result<(), CaseError> {
    let (ambient_pressure, cavitation_pressure) = (case.ambient_pressure, case.cavitation_pressure);
    if case.methods.rigorous
        && case.solver.rigorous_film == RigorousFilm::Reynolds
        && case.grooves.is_empty()
        && ambient_pressure <= cavitation_pressure
    {
        return Err(ctx.err(
            "methods.rigorous",
            format!(
                "the mass-conserving (JFO) film has no oil supply: no [[grooves]] and the ends at \
                 p_amb = {ambient_pressure} Pa ≤ p_cav = {cavitation_pressure} Pa (add a feed \
                 groove, raise lubricant.ambient_pressure_pa, or set rigorous = false)"
            ),
        ));
    }
    Ok(())
}

/// `[elastic]`: the solver's elastic model of shaft and housing, checked here so that each
/// bad value is named by its key (the solver would refuse it only after the other methods ran).
fn resolve_elastic(
    e: &ElasticSection,
    radius: f64,
    solvable: bool,
    force_tolerance: f64,
    ctx: &Ctx<'_>,
) -> Result<ElasticParams, CaseError> {
    if !solvable {
        return Err(ctx.err(
            "elastic",
            "a dynamically loaded case takes the elastic deformation in the rigorous method's \
             Reynolds film: set methods.rigorous = true (with solver.rigorous_film = \
             \"reynolds\"), or make the case steady (one load point, constant speeds)",
        ));
    }
    let material = elastic_material(e, ctx)?;
    let (hole, half_width) = elastic_bodies(e, radius, ctx)?;
    if e.n_theta < 8 {
        return Err(ctx.err(
            "elastic.n_theta",
            format!("needs at least 8 nodes around, got {}", e.n_theta),
        ));
    }
    for (key, layers) in [
        ("elastic.shaft_layers", e.shaft_layers),
        ("elastic.housing_layers", e.housing_layers),
    ] {
        if layers == Some(0) {
            return Err(ctx.err(key, "must be at least 1 element layer, got 0"));
        }
    }
    let defaults = ElasticParams::steel(radius);
    // Absent: the steady solve's and the dynamic film's validated defaults, each its own.
    let (tol, dynamic_tol) = match e.gap_tolerance {
        Some(t) => (t, t),
        None => (
            defaults.gap_tolerance,
            ElasticParams::dynamic_gap_tolerance_for(force_tolerance),
        ),
    };
    if !(tol > 0.0 && tol <= 1.0) {
        return Err(ctx.err(
            "elastic.gap_tolerance",
            format!("must lie in (0, 1] (a fraction of the clearance), got {tol}"),
        ));
    }
    if e.max_iterations == 0 {
        return Err(ctx.err("elastic.max_iterations", "must be at least 1, got 0"));
    }
    let layers = match (e.shaft_layers, e.housing_layers) {
        (None, None) => None,
        (s, h) => Some([
            s.unwrap_or_else(|| square_layers(hole, radius, e.n_theta)),
            h.unwrap_or_else(|| square_layers(radius, half_width, e.n_theta)),
        ]),
    };
    Ok(ElasticParams {
        shaft_material: material,
        housing_material: material,
        hole_radius: hole,
        housing: HousingShape::Square { half_width },
        n_theta: e.n_theta,
        layers,
        gap_tolerance: tol,
        dynamic_gap_tolerance: dynamic_tol,
        max_iterations: e.max_iterations,
        ..defaults
    })
}

/// One material for shaft and housing: Young's modulus and a compressible Poisson's ratio.
fn elastic_material(e: &ElasticSection, ctx: &Ctx<'_>) -> Result<Material, CaseError> {
    let youngs_modulus = ctx.positive("elastic.youngs_modulus_pa", e.youngs_modulus_pa)?;
    let nu = e.poisson_ratio;
    if !(0.0..0.5).contains(&nu) {
        return Err(ctx.err(
            "elastic.poisson_ratio",
            format!(
                "must lie in [0, 0.5) (0.5 is incompressible, which the plane-strain \
                 displacement elements cannot represent), got {nu}"
            ),
        ));
    }
    Ok(Material {
        youngs_modulus,
        poisson_ratio: nu,
    })
}

/// The shaft's hole radius and the square housing's half width around a bore of `radius`.
fn elastic_bodies(e: &ElasticSection, radius: f64, ctx: &Ctx<'_>) -> Result<(f64, f64), CaseError> {
    let hole = ctx.positive("elastic.shaft_hole_radius_m", e.shaft_hole_radius_m)?;
    if hole >= radius {
        return Err(ctx.err(
            "elastic.shaft_hole_radius_m",
            format!(
                "the shaft's hole ({hole} m) must be smaller than the journal radius {radius} m"
            ),
        ));
    }
    let half_width = ctx.positive("elastic.housing_half_width_m", e.housing_half_width_m)?;
    if half_width <= radius {
        return Err(ctx.err(
            "elastic.housing_half_width_m",
            format!(
                "the housing's outer edges ({half_width} m from the centre) must lie outside the \
                 bore (radius {radius} m)"
            ),
        ));
    }
    Ok((hole, half_width))
}

/// The bearing section: (R, L, c) in m.
fn resolve_bearing(b: &BearingSection, ctx: &Ctx<'_>) -> Result<(f64, f64, f64), CaseError> {
    let radius = ctx.positive("bearing.radius_m", b.radius_m)?;
    let length = ctx.positive("bearing.length_m", b.length_m)?;
    let radial_clearance = ctx.positive("bearing.radial_clearance_m", b.radial_clearance_m)?;
    if radial_clearance >= 0.1 * radius {
        return Err(ctx.err(
            "bearing.radial_clearance_m",
            format!(
                "{radial_clearance} m is not small against the radius {radius} m (c/R must be < 0.1; \
                 is it in µm?)"
            ),
        ));
    }
    Ok((radius, length, radial_clearance))
}

/// The feed grooves (SI, the solver's [`Groove`]) and the film fraction a groove holds when
/// its feed is cut off.
fn resolve_grooves(
    raw: &CaseFile,
    radius: f64,
    length: f64,
    ctx: &Ctx<'_>,
) -> Result<(Vec<Groove>, f64), CaseError> {
    // The film fraction a groove holds when its feed is cut off: the solver needs it in (0, 1)
    // (φ = 1 would be a full film at p_cav, not a starved groove).
    let starved_film_fraction = raw.lubricant.starved_film_fraction;
    if !(starved_film_fraction > 0.0 && starved_film_fraction < 1.0) {
        return Err(ctx.err(
            "lubricant.starved_film_fraction",
            format!("must lie in (0, 1), got {starved_film_fraction}"),
        ));
    }
    let mut grooves = Vec::new();
    for (i, g) in raw.grooves.iter().enumerate() {
        let k = |s: &str| format!("grooves[{i}].{s}");
        let center = ctx.finite(&k("center_angle_deg"), g.center_angle_deg)?;
        let axial = ctx.finite(&k("axial_center_m"), g.axial_center_m)?;
        let circ = ctx.positive(&k("circumferential_length_m"), g.circumferential_length_m)?;
        let width = ctx.positive(&k("axial_width_m"), g.axial_width_m)?;
        if circ >= std::f64::consts::TAU * radius {
            return Err(ctx.err(
                &k("circumferential_length_m"),
                format!(
                    "{circ} m is longer than the bearing's circumference 2πR = {:.6} m",
                    std::f64::consts::TAU * radius
                ),
            ));
        }
        if axial.abs() + 0.5 * width > 0.5 * length + 1e-12 * length {
            return Err(ctx.err(
                &k("axial_width_m"),
                format!(
                    "the groove (centre {axial} m, width {width} m) reaches outside the bearing \
                     (z from {} to {} m)",
                    -0.5 * length,
                    0.5 * length
                ),
            ));
        }
        grooves.push(Groove {
            center_angle: deg_to_rad(center),
            center_z: axial,
            angular_width: circ / radius,
            axial_width: width,
            cutoff_film_fraction: starved_film_fraction,
        });
    }
    Ok((grooves, starved_film_fraction))
}

/// Journal and bearing speeds (rad/s): constants, or a speed table over the crank angle
/// (recorded in `input_files`).
fn resolve_speeds(
    o: &OperationSection,
    cycle_deg: f64,
    input_files: &mut Vec<InputFile>,
    ctx: &Ctx<'_>,
) -> Result<(Schedule, Schedule), CaseError> {
    let journal_speed = if let Some(rel) = &o.speed_file {
        if o.journal_speed_rpm.is_some() || o.bearing_speed_rpm.is_some() {
            return Err(ctx.err(
                "operation.speed_file",
                "give either speed_file or journal_speed_rpm / bearing_speed_rpm, not both",
            ));
        }
        None.or(Some(rel.clone()))
    } else {
        None
    };
    let (journal_speed, bearing_speed) = match journal_speed {
        Some(rel) => {
            let (text, angles, cols) = ctx.read_table(
                "operation.speed_file",
                &rel,
                &[
                    ("journal_speed", Quantity::Speed),
                    ("bearing_speed", Quantity::Speed),
                ],
            )?;
            input_files.push(InputFile { path: rel, text });
            check_span(ctx, "operation.speed_file", &angles, cycle_deg)?;
            (
                Schedule::Table {
                    angles_deg: angles.clone(),
                    values: cols[0].clone(),
                },
                Schedule::Table {
                    angles_deg: angles,
                    values: cols[1].clone(),
                },
            )
        }
        None => (
            Schedule::Constant(rpm_to_rad_s(ctx.finite(
                "operation.journal_speed_rpm",
                o.journal_speed_rpm.unwrap_or(o.crank_speed_rpm),
            )?)),
            Schedule::Constant(rpm_to_rad_s(ctx.finite(
                "operation.bearing_speed_rpm",
                o.bearing_speed_rpm.unwrap_or(0.0),
            )?)),
        ),
    };
    Ok((journal_speed, bearing_speed))
}

/// A resolved load table.
struct LoadTable {
    /// Crank angles (deg), increasing, spanning less than a cycle.
    angles_deg: Vec<f64>,
    /// Force on the journal (N, bearing frame) at each angle.
    forces: Vec<[f64; 2]>,
    interpolation: LoadInterpolation,
}

/// The load table (crank angles in deg, forces in N on the journal, bearing frame) and its
/// interpolation, checked by building the solvers' [`TabulatedLoad`] once.
fn resolve_load(
    ld: &LoadSection,
    cycle_deg: f64,
    crank_speed: f64,
    input_files: &mut Vec<InputFile>,
    ctx: &Ctx<'_>,
) -> Result<LoadTable, CaseError> {
    let interp = match ld.interpolation.as_str() {
        "linear" => LoadInterpolation::Linear,
        "catmull_rom" => LoadInterpolation::CatmullRom,
        other => {
            return Err(ctx.err(
                "load.interpolation",
                format!("'{other}' is not one of: linear, catmull_rom"),
            ));
        }
    };
    let direction = load_direction(ld, ctx)?;
    let (load_angles_deg, load_forces) = match (&ld.file, &ld.crank_angle_deg) {
        (Some(_), Some(_)) => {
            return Err(ctx.err(
                "load",
                "give either `file` or the inline table `crank_angle_deg`, not both",
            ));
        }
        (None, None) => {
            return Err(ctx.err(
                "load",
                "no load: give `file = \"table.csv\"` or the inline `crank_angle_deg` with \
                 `x_n`, `y_n` (or `magnitude_n` and `direction`)",
            ));
        }
        (Some(rel), None) => load_from_file(rel, direction, input_files, ctx)?,
        (None, Some(angles)) => inline_load(ld, angles, direction, ctx)?,
    };
    let (load_angles_deg, load_forces) = if load_angles_deg.len() == 1 {
        // A constant load: the solvers' tables need two points.
        (
            vec![load_angles_deg[0], load_angles_deg[0] + 0.5 * cycle_deg],
            vec![load_forces[0], load_forces[0]],
        )
    } else {
        (load_angles_deg, load_forces)
    };
    let load_key = if ld.file.is_some() {
        "load.file"
    } else {
        "load.crank_angle_deg"
    };
    if load_forces.iter().all(|f| f[0] == 0.0 && f[1] == 0.0) {
        return Err(ctx.err(load_key, "the load is zero throughout the cycle"));
    }
    TabulatedLoad::new(
        load_angles_deg.clone(),
        load_forces.clone(),
        cycle_deg,
        crank_speed,
        interp,
    )
    .map_err(|e| ctx.err(load_key, e.to_string()))?;
    Ok(LoadTable {
        angles_deg: load_angles_deg,
        forces: load_forces,
        interpolation: interp,
    })
}

/// `load.direction` as a unit vector, if given.
fn load_direction(ld: &LoadSection, ctx: &Ctx<'_>) -> Result<Option<[f64; 2]>, CaseError> {
    let Some(d) = ld.direction else {
        return Ok(None);
    };
    let n = d[0].hypot(d[1]);
    if !(n.is_finite() && n > 0.0) {
        return Err(ctx.err(
            "load.direction",
            format!("{d:?} is not a usable direction (zero or not finite)"),
        ));
    }
    Ok(Some([d[0] / n, d[1] / n]))
}

/// A load table from a CSV file (`load` along `direction`, or `load_x` and `load_y`), kept
/// among the input files.
fn load_from_file(
    rel: &str,
    direction: Option<[f64; 2]>,
    input_files: &mut Vec<InputFile>,
    ctx: &Ctx<'_>,
) -> Result<(Vec<f64>, Vec<[f64; 2]>), CaseError> {
    let (text, angles, forces) = if let Some(d) = direction {
        let (text, a, cols) = ctx.read_table("load.file", rel, &[("load", Quantity::Force)])?;
        let f = cols[0].iter().map(|m| [m * d[0], m * d[1]]).collect();
        (text, a, f)
    } else {
        let (text, a, cols) = ctx.read_table(
            "load.file",
            rel,
            &[("load_x", Quantity::Force), ("load_y", Quantity::Force)],
        )?;
        let f = cols[0]
            .iter()
            .zip(&cols[1])
            .map(|(x, y)| [*x, *y])
            .collect();
        (text, a, f)
    };
    input_files.push(InputFile {
        path: rel.to_string(),
        text,
    });
    Ok((angles, forces))
}

/// An inline load table: `x_n` and `y_n`, or `magnitude_n` along `direction`.
fn inline_load(
    ld: &LoadSection,
    angles: &[f64],
    direction: Option<[f64; 2]>,
    ctx: &Ctx<'_>,
) -> Result<(Vec<f64>, Vec<[f64; 2]>), CaseError> {
    let akey = "load.crank_angle_deg";
    if let Some(d) = direction {
        let Some(m) = &ld.magnitude_n else {
            return Err(ctx.err(
                "load.magnitude_n",
                "missing: a load with `direction` needs `magnitude_n`",
            ));
        };
        check_inline(ctx, akey, angles, &[("load.magnitude_n", m)])?;
        Ok((
            angles.to_vec(),
            m.iter().map(|v| [v * d[0], v * d[1]]).collect(),
        ))
    } else {
        let (Some(x), Some(y)) = (&ld.x_n, &ld.y_n) else {
            return Err(ctx.err(
                if ld.x_n.is_none() {
                    "load.x_n"
                } else {
                    "load.y_n"
                },
                "missing: an inline load needs both `x_n` and `y_n` (or `magnitude_n` \
                 with `direction`)",
            ));
        };
        check_inline(ctx, akey, angles, &[("load.x_n", x), ("load.y_n", y)])?;
        Ok((
            angles.to_vec(),
            x.iter().zip(y).map(|(a, b)| [*a, *b]).collect(),
        ))
    }
}

/// The groove feed pressure (gauge, Pa): a constant or a table over the crank angle; ambient
/// when not given.
fn resolve_feed(
    f: &FeedSection,
    grooves: &[Groove],
    ambient_pressure: f64,
    cycle_deg: f64,
    input_files: &mut Vec<InputFile>,
    ctx: &Ctx<'_>,
) -> Result<Schedule, CaseError> {
    let feed_pressure = schedule(
        ctx,
        input_files,
        "feed",
        f.pressure_pa.map(|v| ("pressure_pa", v)),
        f.file.as_deref(),
        match (&f.crank_angle_deg, &f.pressure_history_pa) {
            (Some(a), Some(v)) => Some((a.as_slice(), "pressure_history_pa", v.as_slice())),
            (Some(_), None) => {
                return Err(ctx.err(
                    "feed.pressure_history_pa",
                    "missing: an inline feed table needs `pressure_history_pa`",
                ));
            }
            (None, Some(_)) => {
                return Err(ctx.err(
                    "feed.crank_angle_deg",
                    "missing: an inline feed table needs `crank_angle_deg`",
                ));
            }
            (None, None) => None,
        },
        ("feed_pressure", Quantity::Pressure),
    )?
    .unwrap_or(Schedule::Constant(ambient_pressure));
    if let Schedule::Table { angles_deg, .. } = &feed_pressure {
        let key = if f.file.is_some() {
            "feed.file"
        } else {
            "feed.crank_angle_deg"
        };
        check_span(ctx, key, angles_deg, cycle_deg)?;
    }
    if grooves.is_empty()
        && !matches!(feed_pressure, Schedule::Constant(p) if p == ambient_pressure)
    {
        return Err(ctx.err(
            "feed",
            "a feed pressure is given but the bearing has no [[grooves]] to feed",
        ));
    }
    Ok(feed_pressure)
}

/// The film grid: enough nodes, and every groove wide enough to hold some.
fn check_grid(
    g: &GridParams,
    length: f64,
    grooves: &[Groove],
    ctx: &Ctx<'_>,
) -> Result<(), CaseError> {
    if g.n_theta < 8 {
        return Err(ctx.err(
            "grid.n_theta",
            format!("{} nodes around is too few (at least 8)", g.n_theta),
        ));
    }
    if g.n_z < 3 {
        return Err(ctx.err(
            "grid.n_z",
            format!(
                "{} nodes along is too few (at least 3, the ends included)",
                g.n_z
            ),
        ));
    }
    let dtheta = std::f64::consts::TAU / g.n_theta as f64;
    // The film's cell-centred axial spacing (n_z − 2 cells between the end rows).
    let dz = length / (g.n_z - 2) as f64;
    for (i, gr) in grooves.iter().enumerate() {
        let arc = gr.angular_width;
        if arc < dtheta {
            return Err(ctx.err(
                "grid.n_theta",
                format!(
                    "n_theta = {} gives a node spacing of {:.2}°, wider than groove {i} \
                     ({:.2}° around): the grid does not resolve it; use n_theta ≥ {}",
                    g.n_theta,
                    dtheta.to_degrees(),
                    arc.to_degrees(),
                    (std::f64::consts::TAU / arc).ceil() as usize
                ),
            ));
        }
        if gr.axial_width < dz {
            return Err(ctx.err(
                "grid.n_z",
                format!(
                    "n_z = {} gives an axial spacing of {:.3} mm, wider than groove {i} ({:.3} mm \
                     wide): the grid does not resolve it; use n_z ≥ {}",
                    g.n_z,
                    dz * 1e3,
                    gr.axial_width * 1e3,
                    ((length / gr.axial_width).ceil() as usize).saturating_add(2)
                ),
            ));
        }
    }
    Ok(())
}

/// The solver settings.
fn resolve_solver(s: &SolverSection, ctx: &Ctx<'_>) -> Result<SolverOptions, CaseError> {
    if s.time_steps_per_cycle < 8 {
        return Err(ctx.err(
            "solver.time_steps_per_cycle",
            format!("{} is too few (at least 8)", s.time_steps_per_cycle),
        ));
    }
    if s.max_cycles < 1 {
        return Err(ctx.err("solver.max_cycles", "must be at least 1"));
    }
    let periodicity_tolerance =
        ctx.positive("solver.periodicity_tolerance", s.periodicity_tolerance)?;
    let force_tolerance = ctx.positive("solver.force_tolerance", s.force_tolerance)?;
    if !(s.step_error_tolerance.is_finite() && s.step_error_tolerance >= 0.0) {
        return Err(ctx.err(
            "solver.step_error_tolerance",
            format!(
                "must be a finite number ≥ 0 (0: no error control), got {}",
                s.step_error_tolerance
            ),
        ));
    }
    if !(s.eccentricity_limit > 0.0 && s.eccentricity_limit < 1.0) {
        return Err(ctx.err(
            "solver.eccentricity_limit",
            format!("must lie in (0, 1), got {}", s.eccentricity_limit),
        ));
    }
    let e0 = s.initial_eccentricity[0].hypot(s.initial_eccentricity[1]);
    if !(e0.is_finite() && e0 < s.eccentricity_limit) {
        return Err(ctx.err(
            "solver.initial_eccentricity",
            format!("|ε| = {e0} must be finite and below the eccentricity limit"),
        ));
    }
    let mobility_model = match s.mobility_model.as_str() {
        "booker" => MobilityModelChoice::Booker,
        "exact_short" => MobilityModelChoice::ExactShort,
        "map" => MobilityModelChoice::Map,
        other => {
            return Err(ctx.err(
                "solver.mobility_model",
                format!("'{other}' is not one of: booker, exact_short, map"),
            ));
        }
    };
    let time_scheme = match s.time_scheme.as_str() {
        "bdf2" => TimeScheme::Bdf2,
        "backward_euler" => TimeScheme::BackwardEuler,
        "crank_nicolson" => TimeScheme::CrankNicolson,
        other => {
            return Err(ctx.err(
                "solver.time_scheme",
                format!("'{other}' is not one of: bdf2, backward_euler, crank_nicolson"),
            ));
        }
    };
    let rigorous_film = match s.rigorous_film.as_str() {
        "reynolds" => RigorousFilm::Reynolds,
        "short_bearing" => RigorousFilm::ShortBearing,
        other => {
            return Err(ctx.err(
                "solver.rigorous_film",
                format!("'{other}' is not one of: reynolds, short_bearing"),
            ));
        }
    };
    Ok(SolverOptions {
        time_steps_per_cycle: s.time_steps_per_cycle,
        max_cycles: s.max_cycles,
        periodicity_tolerance,
        force_tolerance,
        eccentricity_limit: s.eccentricity_limit,
        time_scheme,
        mobility_model,
        initial_eccentricity: s.initial_eccentricity,
        rigorous_film,
        step_error_tolerance: s.step_error_tolerance,
        cycle_extrapolation: s.cycle_extrapolation,
    })
}

/// Ranges outside which a value is flagged as implausible (a unit or typing error, most
/// likely). Each is about an order of magnitude beyond what journal bearings have:
/// - clearance ratio c/R: usually 5e-4 … 3e-3 in machine bearings (Khonsari & Booser, *Applied
///   Tribology*, 3rd ed., §8: "c/R ≈ 0.001"), up to 2e-2 in the clearance joints of mechanisms
///   (\[Flores2009\] Table 1); flagged outside 1e-5 … 5e-2, which still catches
///   a length typed in mm for m (× 1000) and the other way round;
/// - width ratio L/D: 0.2 … 1.5 in practice; flagged outside 0.05 … 3;
/// - dynamic viscosity: 2e-3 (light oils hot) … 1 Pa·s (ISO VG 680 cold); flagged outside
///   1e-4 … 10 Pa·s;
/// - peak specific load max|W| / (2 R L): engine bearings carry up to ~60 MPa; flagged above
///   200 MPa;
/// - sliding speed ω R: flagged above 200 m/s (turbomachinery reaches ~100 m/s);
/// - bulk modulus: mineral oils 1.2 … 2 GPa; flagged outside 1e8 … 1e11 Pa.
pub const PLAUSIBLE_CLEARANCE_RATIO: (f64, f64) = (1e-5, 5e-2);
/// See [`PLAUSIBLE_CLEARANCE_RATIO`].
pub const PLAUSIBLE_WIDTH_RATIO: (f64, f64) = (0.05, 3.0);
/// See [`PLAUSIBLE_CLEARANCE_RATIO`] (Pa·s).
pub const PLAUSIBLE_VISCOSITY: (f64, f64) = (1e-4, 10.0);
/// See [`PLAUSIBLE_CLEARANCE_RATIO`] (Pa).
pub const PLAUSIBLE_SPECIFIC_LOAD: f64 = 200e6;
/// See [`PLAUSIBLE_CLEARANCE_RATIO`] (m/s).
pub const PLAUSIBLE_SLIDING_SPEED: f64 = 200.0;
/// See [`PLAUSIBLE_CLEARANCE_RATIO`] (Pa).
pub const PLAUSIBLE_BULK_MODULUS: (f64, f64) = (1e8, 1e11);

/// Warnings for values of a valid case far outside journal-bearing practice (ranges at
/// [`PLAUSIBLE_CLEARANCE_RATIO`]): the bearing and lubricant first, then the operation.
fn plausibility_warnings(case: &Case, ctx: &Ctx<'_>) -> Vec<CaseWarning> {
    let mut found = implausible_properties(case);
    found.extend(implausible_operation(case));
    found
        .into_iter()
        .map(|(key, message)| CaseWarning {
            file: ctx.file.clone(),
            line: ctx.locator.line_of(key),
            key: key.to_string(),
            kind: WarningKind::Implausible,
            message,
        })
        .collect()
}

/// The bearing's clearance ratio and width ratio, the lubricant's viscosity and bulk modulus
/// outside their plausible ranges: (key, message).
fn implausible_properties(case: &Case) -> Vec<(&'static str, String)> {
    let mut out = Vec::new();
    let outside = |v: f64, (lo, hi): (f64, f64)| v < lo || v > hi;
    let ratio = case.radial_clearance / case.radius;
    if outside(ratio, PLAUSIBLE_CLEARANCE_RATIO) {
        out.push((
            "bearing.radial_clearance_m",
            format!(
                "clearance ratio c/R = {ratio:.3e} is far outside journal-bearing practice \
                 (5e-4 … 3e-3, clearance joints of mechanisms 2e-2; warned outside {:e} … {:e}): check the value and its unit (m)",
                PLAUSIBLE_CLEARANCE_RATIO.0, PLAUSIBLE_CLEARANCE_RATIO.1
            ),
        ));
    }
    let ld = case.length / (2.0 * case.radius);
    if outside(ld, PLAUSIBLE_WIDTH_RATIO) {
        out.push((
            "bearing.length_m",
            format!(
                "width ratio L/D = {ld:.3} is far outside journal-bearing practice (0.2 … 1.5; \
                 warned outside {} … {}): check the value and its unit (m)",
                PLAUSIBLE_WIDTH_RATIO.0, PLAUSIBLE_WIDTH_RATIO.1
            ),
        ));
    }
    if outside(case.viscosity, PLAUSIBLE_VISCOSITY) {
        out.push((
            "lubricant.viscosity_pa_s",
            format!(
                "viscosity {:.3e} Pa·s is far outside lubricating oils (2e-3 … 1 Pa·s; warned \
                 outside {:e} … {} Pa·s): check the unit (Pa·s, not cP or mPa·s)",
                case.viscosity, PLAUSIBLE_VISCOSITY.0, PLAUSIBLE_VISCOSITY.1
            ),
        ));
    }
    if outside(case.bulk_modulus, PLAUSIBLE_BULK_MODULUS) {
        out.push((
            "lubricant.bulk_modulus_pa",
            format!(
                "bulk modulus {:.3e} Pa is far outside mineral oils (1.2e9 … 2e9 Pa; warned \
                 outside {:e} … {:e} Pa)",
                case.bulk_modulus, PLAUSIBLE_BULK_MODULUS.0, PLAUSIBLE_BULK_MODULUS.1
            ),
        ));
    }
    out
}

/// A peak specific load or a sliding speed above its plausible limit, or a dynamic elastic gap
/// tolerance looser than the Newton needs: (key, message).
fn implausible_operation(case: &Case) -> Vec<(&'static str, String)> {
    let mut out = Vec::new();
    let peak = case
        .load_forces
        .iter()
        .map(|f| f[0].hypot(f[1]))
        .fold(0.0, f64::max);
    let specific = peak / (2.0 * case.radius * case.length);
    if specific > PLAUSIBLE_SPECIFIC_LOAD {
        out.push((
            "load",
            format!(
                "peak specific load max|W| / (2 R L) = {:.1} MPa is above {} MPa, far beyond \
                 what journal bearings carry (engine bearings ≲ 60 MPa): check the load's unit (N)",
                specific / 1e6,
                PLAUSIBLE_SPECIFIC_LOAD / 1e6
            ),
        ));
    }
    let cycle = case.cycle_deg;
    let fastest = (0..=72)
        .map(|i| {
            let a = cycle * i as f64 / 72.0;
            (case.journal_speed.at(a, cycle) - case.bearing_speed.at(a, cycle)).abs()
        })
        .fold(0.0, f64::max);
    let sliding = fastest * case.radius;
    if sliding > PLAUSIBLE_SLIDING_SPEED {
        out.push((
            "operation",
            format!(
                "sliding speed |ω_j − ω_b| R = {sliding:.0} m/s is above {} m/s: check the \
                 speeds (rpm) and the radius (m)",
                PLAUSIBLE_SLIDING_SPEED
            ),
        ));
    }
    if let Some(message) = loose_dynamic_gap(case) {
        out.push(("elastic.gap_tolerance", message));
    }
    out
}

/// Why the deformable film the rigorous method steps has a gap tolerance looser than its
/// Newton needs (`ElasticParams::dynamic_gap_tolerance_for` the force tolerance), if it has.
fn loose_dynamic_gap(case: &Case) -> Option<String> {
    let e = case.elastic.as_ref()?;
    let stepped = case.methods.rigorous && case.solver.rigorous_film == RigorousFilm::Reynolds;
    let needed = ElasticParams::dynamic_gap_tolerance_for(case.solver.force_tolerance);
    (stepped && e.dynamic_gap_tolerance > needed).then(|| {
        format!(
            "{:e} c is looser than the {needed:e} c the rigorous method's Newton needs at \
             solver.force_tolerance = {:e} (a tenth of the force tolerance times a film of \
             0.1 c), and a dynamic run at it is not validated (the compressor rod stalled 65 \
             steps at 1e-7 c before the trial gaps started along dg/deps); leave the key out \
             for the validated default",
            e.dynamic_gap_tolerance, case.solver.force_tolerance
        )
    })
}

/// The Vogel law's a, b, c as report parameters.
fn push_vogel(p: &mut Vec<Parameter>, v: &Vogel) {
    p.push(Parameter::number(
        "vogel_a",
        v.a,
        "Pa s",
        "Vogel viscosity law mu0(T) = a exp(b / (T - c)): a",
    ));
    p.push(Parameter::number("vogel_b", v.b, "K", "Vogel b"));
    p.push(Parameter::number("vogel_c", v.c, "degC", "Vogel c"));
}

/// What `[lubricant]` says about the viscosity, resolved.
struct ResolvedViscosity {
    viscosity: f64,
    model: Option<ViscosityModel>,
    oil: Option<String>,
    heat_balance: Option<CaseHeatBalance>,
}

/// The constant viscosity, or a Vogel law (`[lubricant.vogel]` or a named `oil`) with the film
/// temperature given (`[lubricant.temperature]`: the model for the rigorous film and μ₀ at the
/// mean temperature, T_m or (T_in + T_out)/2 as \[Benasciutti2012\] defines it, for the methods that take
/// one viscosity) or found by a heat balance (`[lubricant.heat_balance]`: μ at the supply
/// temperature until the balance replaces it by μ(T_eff)).
fn resolve_viscosity(l: &LubricantSection, ctx: &Ctx<'_>) -> Result<ResolvedViscosity, CaseError> {
    let alpha = l.pressure_viscosity_coefficient_per_pa;
    if !(alpha >= 0.0 && alpha.is_finite()) {
        return Err(ctx.err(
            "lubricant.pressure_viscosity_coefficient_per_pa",
            format!("must be ≥ 0 and finite (1/Pa; oils: 1e-8 … 3e-8), got {alpha}"),
        ));
    }
    let (vogel, oil) = match (&l.viscosity_pa_s, &l.vogel, &l.oil) {
        (Some(mu), None, None) => return constant_viscosity(l, *mu, alpha, ctx),
        (None, None, None) => {
            return Err(ctx.err(
                "lubricant.viscosity_pa_s",
                "missing: give viscosity_pa_s, or a viscosity–temperature law ([lubricant.vogel] \
                 or oil) with [lubricant.temperature] or [lubricant.heat_balance]",
            ));
        }
        (None, Some(v), None) => (
            Vogel {
                a: ctx.positive("lubricant.vogel.a_pa_s", v.a_pa_s)?,
                b: ctx.finite("lubricant.vogel.b_c", v.b_c)?,
                c: ctx.finite("lubricant.vogel.c_c", v.c_c)?,
            },
            None,
        ),
        (None, None, Some(name)) => named_oil(name, ctx)?,
        _ => {
            return Err(ctx.err(
                if l.oil.is_some() {
                    "lubricant.oil"
                } else {
                    "lubricant.vogel"
                },
                "give one of viscosity_pa_s, [lubricant.vogel] or oil (each sets the viscosity), \
                 not several",
            ));
        }
    };
    match (&l.temperature, &l.heat_balance) {
        (Some(_), Some(_)) => Err(ctx.err(
            "lubricant.heat_balance",
            "give the film temperature ([lubricant.temperature]) or find it by a heat balance \
             ([lubricant.heat_balance]), not both",
        )),
        (None, None) => Err(ctx.err(
            "lubricant.temperature",
            "a viscosity–temperature law needs [lubricant.temperature] (mean_c, or inlet_c and \
             outlet_c) or [lubricant.heat_balance] (supply_temperature_c)",
        )),
        (None, Some(h)) => resolve_heat_balance(h, vogel, oil, alpha, ctx),
        (Some(t), None) => resolve_film_temperature(t, vogel, oil, alpha, ctx),
    }
}

/// A constant `viscosity_pa_s`: no pressure coefficient, no film temperature.
fn constant_viscosity(
    l: &LubricantSection,
    mu: f64,
    alpha: f64,
    ctx: &Ctx<'_>,
) -> Result<ResolvedViscosity, CaseError> {
    if alpha > 0.0 {
        return Err(ctx.err(
            "lubricant.pressure_viscosity_coefficient_per_pa",
            "a pressure-dependent viscosity needs a viscosity–temperature law \
             ([lubricant.vogel] or oil) with its temperature",
        ));
    }
    if l.temperature.is_some() || l.heat_balance.is_some() {
        let key = if l.temperature.is_some() {
            "lubricant.temperature"
        } else {
            "lubricant.heat_balance"
        };
        return Err(ctx.err(
            key,
            "a film temperature needs a viscosity–temperature law ([lubricant.vogel] or \
             oil), not a constant viscosity_pa_s",
        ));
    }
    Ok(ResolvedViscosity {
        viscosity: ctx.positive("lubricant.viscosity_pa_s", mu)?,
        model: None,
        oil: None,
        heat_balance: None,
    })
}

/// The Vogel law of a named ISO 3448 oil, with its name.
fn named_oil(name: &str, ctx: &Ctx<'_>) -> Result<(Vogel, Option<String>), CaseError> {
    let grade = IsoViscosityGrade::from_name(name).ok_or_else(|| {
        ctx.err(
            "lubricant.oil",
            format!(
                "unknown oil {name:?}: the named oils are {}",
                IsoViscosityGrade::ALL
                    .iter()
                    .map(|g| format!("{:?}", g.name()))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        )
    })?;
    Ok((grade.vogel(), Some(grade.name())))
}

/// μ₀(t) of the Vogel law, if it is a positive finite viscosity above the law's pole.
fn vogel_viscosity_at(vogel: &Vogel, t: f64, ctx: &Ctx<'_>) -> Result<f64, CaseError> {
    let mu = vogel.viscosity(t);
    if mu > 0.0 && mu.is_finite() && t > vogel.c {
        Ok(mu)
    } else {
        Err(ctx.err(
            "lubricant.vogel",
            format!("gives μ₀({t} °C) = {mu} Pa·s, not a positive finite viscosity"),
        ))
    }
}

/// `[lubricant.heat_balance]`: the balance's constants, μ at the supply temperature to start.
fn resolve_heat_balance(
    h: &HeatBalanceSection,
    vogel: Vogel,
    oil: Option<String>,
    alpha: f64,
    ctx: &Ctx<'_>,
) -> Result<ResolvedViscosity, CaseError> {
    let params = HeatBalanceParams {
        supply_temperature: ctx.finite(
            "lubricant.heat_balance.supply_temperature_c",
            h.supply_temperature_c,
        )?,
        volumetric_heat_capacity: ctx.positive(
            "lubricant.heat_balance.volumetric_heat_capacity_j_m3_k",
            h.volumetric_heat_capacity_j_m3_k,
        )?,
        heat_to_structure: h.heat_to_housing_and_shaft,
        tolerance: ctx.positive("lubricant.heat_balance.tolerance_k", h.tolerance_k)?,
        max_iterations: h.max_iterations,
    };
    if !(0.0..1.0).contains(&params.heat_to_structure) {
        return Err(ctx.err(
            "lubricant.heat_balance.heat_to_housing_and_shaft",
            format!(
                "must lie in [0, 1) (the share of the power loss conducted away), got {}",
                params.heat_to_structure
            ),
        ));
    }
    if params.max_iterations < 2 {
        return Err(ctx.err(
            "lubricant.heat_balance.max_iterations",
            format!("must be at least 2, got {}", params.max_iterations),
        ));
    }
    let viscosity = vogel_viscosity_at(&vogel, params.supply_temperature, ctx)?;
    Ok(ResolvedViscosity {
        viscosity,
        model: None,
        oil,
        heat_balance: Some(CaseHeatBalance {
            vogel,
            params,
            pressure_coefficient: alpha,
        }),
    })
}

/// `[lubricant.temperature]`: a constant or linearly rising film temperature, μ₀ at its mean.
fn resolve_film_temperature(
    t: &TemperatureSection,
    vogel: Vogel,
    oil: Option<String>,
    alpha: f64,
    ctx: &Ctx<'_>,
) -> Result<ResolvedViscosity, CaseError> {
    let (temperature, mean) = match (t.mean_c, t.inlet_c, t.outlet_c) {
        (Some(m), None, None) => {
            let m = ctx.finite("lubricant.temperature.mean_c", m)?;
            (Temperature::Constant(m), m)
        }
        (None, Some(i), Some(o)) => {
            let i = ctx.finite("lubricant.temperature.inlet_c", i)?;
            let o = ctx.finite("lubricant.temperature.outlet_c", o)?;
            let span = t.rise_span_deg;
            if !(span > 0.0 && span <= 360.0) {
                return Err(ctx.err(
                    "lubricant.temperature.rise_span_deg",
                    format!("must lie in (0, 360], got {span}"),
                ));
            }
            (
                Temperature::LinearOverSpan {
                    inlet: i,
                    outlet: o,
                    span: span.to_radians(),
                },
                0.5 * (i + o),
            )
        }
        _ => {
            return Err(ctx.err(
                "lubricant.temperature",
                "give mean_c, or inlet_c and outlet_c (not both, not one of the pair)",
            ));
        }
    };
    let model = ViscosityModel {
        vogel,
        temperature,
        pressure_coefficient: alpha,
    };
    if let Err(e) = model.validate() {
        return Err(ctx.err("lubricant.temperature", e.to_string()));
    }
    let viscosity = vogel_viscosity_at(&model.vogel, mean, ctx)?;
    Ok(ResolvedViscosity {
        viscosity,
        model: Some(model),
        oil,
        heat_balance: None,
    })
}

/// `[closed_form] models` (or `methods.closed_form = true`, meaning every model).
fn resolve_closed_form(
    section: Option<&ClosedFormSection>,
    flag: bool,
    ctx: &Ctx,
) -> Result<Vec<ClosedFormModel>, CaseError> {
    let names: Vec<String> = match section.map(|s| &s.models) {
        None if flag => vec!["all".into()],
        None => return Ok(Vec::new()),
        Some(ClosedFormModels::One(n)) => vec![n.clone()],
        Some(ClosedFormModels::List(l)) => l.clone(),
    };
    if names.is_empty() {
        return Err(ctx.err(
            "closed_form.models",
            "the list is empty (give \"all\" or model names)",
        ));
    }
    let mut models: Vec<ClosedFormModel> = Vec::new();
    for n in &names {
        let add: Vec<ClosedFormModel> = if n == "all" {
            ClosedFormModel::ALL.to_vec()
        } else {
            vec![
                n.parse()
                    .map_err(|e: ClosedFormError| ctx.err("closed_form.models", e.to_string()))?,
            ]
        };
        for a in add {
            if !models.contains(&a) {
                models.push(a);
            }
        }
    }
    Ok(models)
}
