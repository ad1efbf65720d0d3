//! Results of one case, in memory and on disk.
//!
//! The solvers return their own typed results; the application gathers what a user wants to see
//! of one case into a [`CaseReport`], which knows nothing about how it was computed. Writers turn
//! a report into files, all behind one trait, [`OutputWriter`]:
//!
//! ```text
//!   jbearing_solvers results ──(app fills)──► CaseReport ──► Hdf5Writer        CASE.h5
//!                                                        ├──► PlotWriter        CASE_*.png
//!                                                        └──► CsvSummaryWriter  CASE_summary.csv
//! ```
//!
//! What a report holds:
//!
//! ```text
//! CaseReport
//! ├── case_name, case_text            the case file exactly as given (TOML text)
//! ├── input_files: [InputFile]        load / feed tables it refers to, verbatim
//! ├── geometry                        R, L, c of the bearing (m): the surface and the clearance circle
//! ├── parameters: [Parameter]         resolved parameters, key = value [units]
//! ├── run: RunInfo                    jbearing version, git commit, wall time, start time
//! ├── methods: [MethodResult]         one per method (Rigorous, Mobility)
//! │   ├── time [s], crank_angle [deg] the sampling of the stored cycle
//! │   ├── series: [Series]            named time series, e.g. names::MIN_FILM_THICKNESS
//! │   └── fields: Option<FieldSnapshots>  2-D fields on (θ, z) at a set of instants
//! ├── summary: [SummaryRow]           cycle figures per method (min h_min, mean flow, …)
//! └── closed_form: Option<ClosedFormTable>  static equilibrium per closed-form model
//! ```
//!
//! Conventions follow `docs/conventions.md` §1: SI units everywhere except the crank angle, which is
//! stored in degrees because that is how every plot and table in the field shows it; θ in radians
//! from +x towards +y in the bearing frame; z from −L/2 to L/2; gauge pressures. The journal
//! orbit is the pair of series [`names::ECCENTRICITY_X`], [`names::ECCENTRICITY_Y`] (journal
//! centre relative to the bearing centre, m).
//!
//! Every writer first calls [`CaseReport::validate`], so a report with mismatched lengths, a
//! duplicate name or a non-finite number never reaches disk; and every file is written
//! atomically (see [`write_atomically`]): a temporary file in the target directory, renamed into
//! place only when complete, removed on any error.

pub mod closed_form;
pub mod csv_summary;
pub mod elastic;
pub mod hdf5;
pub mod layout;
pub mod plots;
pub mod vtkhdf;

pub use self::closed_form::{ClosedFormRow, ClosedFormTable};
pub use self::csv_summary::CsvSummaryWriter;
pub use self::elastic::{BodyField, ElasticReport};
pub use self::hdf5::Hdf5Writer;
pub use self::plots::{ORBIT_LEGEND_WIDTH, PlotWriter, feed_windows, label_indices};

use std::collections::HashSet;
use std::fmt;
use std::path::{Path, PathBuf};

use ndarray::Array3;

/// Standard series, field and summary names. The plots look series up by these names, and the
/// Python example reads them; a solver result that has the quantity should use the name here.
pub mod names {
    /// Load on the journal (force the machine applies to it), bearing-frame x component \[N\].
    pub const LOAD_X: &str = "load_x";
    /// Load on the journal, bearing-frame y component \[N\].
    pub const LOAD_Y: &str = "load_y";
    /// Oil feed (supply) pressure, gauge \[Pa\].
    pub const FEED_PRESSURE: &str = "feed_pressure";
    /// Journal centre relative to the bearing centre, x component \[m\].
    pub const ECCENTRICITY_X: &str = "eccentricity_x";
    /// Journal centre relative to the bearing centre, y component \[m\].
    pub const ECCENTRICITY_Y: &str = "eccentricity_y";
    /// Eccentricity ratio ε = |e| / c \[1\].
    pub const ECCENTRICITY_RATIO: &str = "eccentricity_ratio";
    /// Attitude angle of the journal centre, from +x towards +y \[rad\].
    pub const ATTITUDE_ANGLE: &str = "attitude_angle";
    /// Minimum film thickness h_min \[m\].
    pub const MIN_FILM_THICKNESS: &str = "min_film_thickness";
    /// Peak film pressure, gauge \[Pa\].
    pub const MAX_PRESSURE: &str = "max_pressure";
    /// Supply flow: net oil volume flux out of the feed region into the film \[m³/s\].
    pub const SUPPLY_FLOW: &str = "supply_flow";
    /// Side leakage: oil volume flux out of both bearing ends \[m³/s\].
    pub const SIDE_LEAKAGE: &str = "side_leakage";
    /// Viscous power loss in the film \[W\].
    pub const POWER_LOSS: &str = "power_loss";
    /// Film oil arriving back at the feed grooves (the heat balance's recirculated flow)
    /// \[m³/s\].
    pub const RECIRCULATED_FLOW: &str = "recirculated_flow";
    /// Cavitated fraction of the film area \[1\].
    pub const CAVITATED_FRACTION: &str = "cavitated_fraction";

    /// Field: film pressure, gauge \[Pa\].
    pub const PRESSURE: &str = "pressure";
    /// Field: film thickness \[m\].
    pub const FILM_THICKNESS: &str = "film_thickness";
    /// Field: film temperature \[°C\].
    pub const TEMPERATURE: &str = "temperature";
    /// Field: film viscosity \[Pa·s\].
    pub const VISCOSITY: &str = "viscosity";
    /// Field: film content φ (density ratio where full, film fraction where cavitated) \[1\].
    pub const FILM_CONTENT: &str = "film_content";
}

/// Which solution a result belongs to. The HDF5 group of a method is [`Method::as_str`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// The mass-conserving (JFO) finite-difference solution of the inverse problem.
    Rigorous,
    /// Booker's mobility method on the same case.
    Mobility,
}

impl Method {
    /// Both methods, in the order they are written and tabulated.
    pub const ALL: [Method; 2] = [Method::Rigorous, Method::Mobility];

    /// Group and column name: `"rigorous"` or `"mobility"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Rigorous => "rigorous",
            Method::Mobility => "mobility",
        }
    }

    /// Key of the report parameter that says why this method is missing from a report (it
    /// failed): `"rigorous_status"` or `"mobility_status"`, text `"failed: …"`.
    pub const fn failure_key(self) -> &'static str {
        match self {
            Method::Rigorous => "rigorous_status",
            Method::Mobility => "mobility_status",
        }
    }

    /// One line for humans, written as the group's `description` attribute. It holds for every
    /// configuration of the method; the film or mobility model the case chose is named in the
    /// group's `film_model` (rigorous) or `model` (mobility) attribute.
    pub fn description(self) -> &'static str {
        match self {
            Method::Rigorous => {
                "inverse solver: in each time step, Newton's method on the journal eccentricity \
                 until the film force balances the load (the film: attribute film_model)"
            }
            Method::Mobility => {
                "mobility method (Booker): the journal velocity from the film's mobility vector \
                 under the load, integrated over the cycle (the mobility model: attribute model)"
            }
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Bearing dimensions the writers need for geometry: the VTK surface (R, L) and the clearance
/// circle of the orbit plot (c).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Bearing (journal) radius R \[m\].
    pub radius: f64,
    /// Bearing length L \[m\]; z runs from −L/2 to L/2.
    pub length: f64,
    /// Radial clearance c \[m\].
    pub radial_clearance: f64,
}

/// Value of one resolved parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum ParameterValue {
    /// A real number in the parameter's units.
    Number(f64),
    /// A count or an index.
    Integer(i64),
    /// A yes/no option.
    Flag(bool),
    /// A choice or a name (e.g. the cavitation model).
    Text(String),
}

/// One resolved parameter of the case: what the solver actually used, defaults filled in.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Key, as a valid variable name (letters, digits, underscores), e.g. `"radial_clearance"`.
    pub key: String,
    /// The value.
    pub value: ParameterValue,
    /// UDUNITS-style units ("m", "Pa s", "rad/s", "1"); empty for text and flags.
    pub units: String,
    /// What it is, in words.
    pub long_name: String,
}

impl Parameter {
    /// A real-valued parameter.
    pub fn number(key: &str, value: f64, units: &str, long_name: &str) -> Self {
        Self {
            key: key.into(),
            value: ParameterValue::Number(value),
            units: units.into(),
            long_name: long_name.into(),
        }
    }

    /// An integer parameter (counts carry units "1").
    pub fn integer(key: &str, value: i64, long_name: &str) -> Self {
        Self {
            key: key.into(),
            value: ParameterValue::Integer(value),
            units: "1".into(),
            long_name: long_name.into(),
        }
    }

    /// A text parameter.
    pub fn text(key: &str, value: &str, long_name: &str) -> Self {
        Self {
            key: key.into(),
            value: ParameterValue::Text(value.into()),
            units: String::new(),
            long_name: long_name.into(),
        }
    }

    /// A flag.
    pub fn flag(key: &str, value: bool, long_name: &str) -> Self {
        Self {
            key: key.into(),
            value: ParameterValue::Flag(value),
            units: String::new(),
            long_name: long_name.into(),
        }
    }
}

/// Where and how the results were made.
#[derive(Debug, Clone, PartialEq)]
pub struct RunInfo {
    /// Version of jbearing that computed the results.
    pub jbearing_version: String,
    /// `git describe --always --dirty` of the source tree, or `"unknown"`.
    pub git_commit: String,
    /// Wall-clock time of the whole case (both methods) \[s\].
    pub wall_time: f64,
    /// Start of the run, ISO 8601 UTC (e.g. `2026-11-22T05:00:00Z`), or empty if unknown.
    pub started_utc: String,
}

impl RunInfo {
    /// Run information for this build: version from Cargo, commit recorded when the binary was
    /// built (`git describe` at build time; `"unknown"` outside a git checkout).
    pub fn for_this_build(wall_time: f64, started_utc: &str) -> Self {
        Self {
            jbearing_version: env!("CARGO_PKG_VERSION").to_string(),
            git_commit: build_commit().to_string(),
            wall_time,
            started_utc: started_utc.into(),
        }
    }
}

/// The commit this binary was built from: `git describe --always --dirty --abbrev=40` run at
/// build time (the `git-version` crate, which also makes cargo rebuild when HEAD or the index
/// changes), `"unknown"` when the source was not a git checkout or git was missing. No git
/// process runs when the binary runs.
fn build_commit() -> &'static str {
    git_version::git_version!(
        args = ["--always", "--dirty", "--abbrev=40"],
        fallback = "unknown"
    )
}

/// A named quantity over the stored cycle of one method, sampled at the method's `time`.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Variable name; use [`names`] where one fits.
    pub name: String,
    /// What it is, in words (the plots' axis labels and xarray's `long_name`).
    pub long_name: String,
    /// UDUNITS-style units ("N", "Pa", "m", "m3 s-1", "W", "1").
    pub units: String,
    /// One value per time sample.
    pub values: Vec<f64>,
}

impl Series {
    /// A series from its parts.
    pub fn new(name: &str, long_name: &str, units: &str, values: Vec<f64>) -> Self {
        Self {
            name: name.into(),
            long_name: long_name.into(),
            units: units.into(),
            values,
        }
    }
}

/// A field on the (θ, z) grid at every stored instant: `values[[k, i, j]]` is the value at
/// instant k, θ_i, z_j.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Variable name; use [`names`] where one fits.
    pub name: String,
    /// What it is, in words.
    pub long_name: String,
    /// UDUNITS-style units.
    pub units: String,
    /// Shape (instants, n_θ, n_z).
    pub values: Array3<f64>,
}

/// 2-D fields on the bearing surface at a set of stored instants (for example every 10° of crank
/// angle of the final cycle).
///
/// ```text
///   θ_i, i = 0 … n_θ−1, periodic (θ_{n_θ} ≡ θ_0 + 2π is not stored), strictly increasing in [0, 2π)
///   z_j, j = 0 … n_z−1, strictly increasing in [−L/2, L/2] (ends included if the solver has them)
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FieldSnapshots {
    /// Times of the instants \[s\].
    pub time: Vec<f64>,
    /// Crank angles of the instants \[deg\].
    pub crank_angle: Vec<f64>,
    /// Circumferential node angles \[rad\].
    pub theta: Vec<f64>,
    /// Axial node positions \[m\].
    pub z: Vec<f64>,
    /// The fields; [`names::PRESSURE`] is the one shown on the VTK surface first.
    pub fields: Vec<Field>,
}

/// What one method computed for the case.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodResult {
    /// Which method.
    pub method: Method,
    /// Sample times of the stored cycle \[s\].
    pub time: Vec<f64>,
    /// Crank angle at each sample \[deg\] (may run past 360 if the cycle does not start at 0).
    pub crank_angle: Vec<f64>,
    /// Named series, each with one value per sample.
    pub series: Vec<Series>,
    /// Fields on the surface, if the method has them (the mobility method does not).
    pub fields: Option<FieldSnapshots>,
    /// Numbers that describe the solve (cycles to periodicity, Newton iterations, …); written
    /// as attributes of the method's group.
    pub solver_info: Vec<(String, ParameterValue)>,
    /// The load cycle's period τ (s) when the samples are a periodic cycle with the end point
    /// not repeated (what `jbearing run` writes: crank angles 0, Δ, …, cycle − Δ); `None` for
    /// samples that are not periodic.
    pub period: Option<f64>,
}

impl MethodResult {
    /// The status a user must read before trusting this result: `"ok"`, or what is wrong —
    /// `"not periodic"` (the cycle limit was reached first), `"N stalled"` (steps accepted above
    /// the Newton tolerance), joined by ", ".
    pub fn status(&self) -> String {
        let info = |key: &str| {
            self.solver_info
                .iter()
                .find(|(k, _)| k == key)
                .map(|(_, v)| v)
        };
        let mut notes = Vec::new();
        if let Some(ParameterValue::Flag(false)) = info("periodic") {
            notes.push("not periodic".to_string());
        }
        if let Some(ParameterValue::Integer(n)) = info("stalled_steps")
            && *n > 0
        {
            notes.push(format!("{n} stalled"));
        }
        if notes.is_empty() {
            "ok".into()
        } else {
            notes.join(", ")
        }
    }

    /// The number `key` of the solver info, if present.
    pub fn info_number(&self, key: &str) -> Option<f64> {
        self.solver_info.iter().find_map(|(k, v)| match v {
            ParameterValue::Number(x) if k == key => Some(*x),
            _ => None,
        })
    }

    /// The series named `name`, if present.
    pub fn series(&self, name: &str) -> Option<&Series> {
        self.series.iter().find(|s| s.name == name)
    }

    /// A cycle figure of the series `name`: its minimum, maximum, or time mean. The mean is
    /// the trapezoidal integral divided by the time it covers, so that non-uniform sampling is
    /// weighted correctly: over the whole period for a periodic cycle ([`Self::period`]: the
    /// interval from the last sample back to the first, one period later, included — on a
    /// uniform grid this is the plain average, exact for trigonometric polynomials of degree
    /// below the number of samples), over the stored span otherwise; a single sample is its
    /// own mean. `None` if the series is absent.
    pub fn reduce(&self, name: &str, how: Reduction) -> Option<f64> {
        let v = &self.series(name)?.values;
        if v.is_empty() {
            return None;
        }
        Some(match how {
            Reduction::Min => v.iter().copied().fold(f64::INFINITY, f64::min),
            Reduction::Max => v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            Reduction::Mean => {
                let t = &self.time;
                let span = t[t.len() - 1] - t[0];
                if v.len() < 2 || span <= 0.0 {
                    v[0]
                } else {
                    let mut integral: f64 = t
                        .windows(2)
                        .zip(v.windows(2))
                        .map(|(tw, vw)| 0.5 * (vw[0] + vw[1]) * (tw[1] - tw[0]))
                        .sum();
                    let mut covered = span;
                    if let Some(period) = self.period.filter(|p| *p > span) {
                        let wrap = period - span;
                        integral += 0.5 * (v[v.len() - 1] + v[0]) * wrap;
                        covered = period;
                    }
                    integral / covered
                }
            }
        })
    }
}

/// How a series is reduced to one cycle figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reduction {
    /// Smallest value (e.g. the cycle minimum of h_min).
    Min,
    /// Largest value (e.g. peak pressure, maximum ε).
    Max,
    /// Time mean over the stored span (trapezoidal rule).
    Mean,
}

/// One row of the summary table: a cycle figure for each method.
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryRow {
    /// Variable name, e.g. `"min_film_thickness_min"`.
    pub name: String,
    /// What it is, in words, e.g. `"cycle minimum of the minimum film thickness"`.
    pub long_name: String,
    /// UDUNITS-style units.
    pub units: String,
    /// Rigorous value, if computed.
    pub rigorous: Option<f64>,
    /// Mobility value, if computed.
    pub mobility: Option<f64>,
}

impl SummaryRow {
    /// Value of one method.
    pub fn value(&self, method: Method) -> Option<f64> {
        match method {
            Method::Rigorous => self.rigorous,
            Method::Mobility => self.mobility,
        }
    }

    /// A row from the series `series` of each method in `methods`, reduced by `how`; units
    /// are the series' units. Methods without the series get `None`.
    pub fn from_series(
        methods: &[MethodResult],
        series: &str,
        how: Reduction,
        name: &str,
        long_name: &str,
    ) -> Self {
        let of = |m: Method| {
            methods
                .iter()
                .find(|r| r.method == m)
                .and_then(|r| r.reduce(series, how))
        };
        let units = methods
            .iter()
            .find_map(|r| r.series(series))
            .map(|s| s.units.clone())
            .unwrap_or_default();
        Self {
            name: name.into(),
            long_name: long_name.into(),
            units,
            rigorous: of(Method::Rigorous),
            mobility: of(Method::Mobility),
        }
    }

    /// A row from the number `key` of each method's solver info (a scalar the method found,
    /// such as the effective temperature of its heat balance); `None` for methods without it.
    pub fn from_info(
        methods: &[MethodResult],
        key: &str,
        units: &str,
        name: &str,
        long_name: &str,
    ) -> Self {
        let of = |m: Method| {
            methods
                .iter()
                .find(|r| r.method == m)
                .and_then(|r| r.info_number(key))
        };
        Self {
            name: name.into(),
            long_name: long_name.into(),
            units: units.into(),
            rigorous: of(Method::Rigorous),
            mobility: of(Method::Mobility),
        }
    }

    /// Deviation of the mobility value from the rigorous one, (mobility − rigorous) / |rigorous|,
    /// as a fraction; `None` if either is missing or the rigorous value is zero.
    pub fn mobility_deviation(&self) -> Option<f64> {
        match (self.rigorous, self.mobility) {
            (Some(r), Some(m)) if r != 0.0 => Some((m - r) / r.abs()),
            _ => None,
        }
    }
}

/// An input file of the case, kept verbatim.
#[derive(Debug, Clone, PartialEq)]
pub struct InputFile {
    /// The path as the case file refers to it (e.g. `"loads/main_bearing.csv"`).
    pub path: String,
    /// Its contents.
    pub text: String,
}

/// Everything written for one case.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseReport {
    /// Case name; output files are named after it (a valid file-name stem).
    pub case_name: String,
    /// The case file exactly as given.
    pub case_text: String,
    /// Where the case file was read from, if from a file.
    pub case_path: Option<PathBuf>,
    /// Other input files the case refers to (load or feed-pressure tables in CSV), exactly as
    /// read, so that the result file alone reproduces the run.
    pub input_files: Vec<InputFile>,
    /// Bearing dimensions.
    pub geometry: Geometry,
    /// Resolved parameters.
    pub parameters: Vec<Parameter>,
    /// Version, commit and timing.
    pub run: RunInfo,
    /// One entry per method that was run, at most one per method.
    pub methods: Vec<MethodResult>,
    /// The summary table.
    pub summary: Vec<SummaryRow>,
    /// The closed-form static-equilibrium table, when the case asks for it.
    pub closed_form: Option<ClosedFormTable>,
    /// The deformable bearing (elastic shaft and housing), when the case has `[elastic]`.
    pub elastic: Option<ElasticReport>,
    /// Warnings about the case (implausible values, cost above the soft budget), written as
    /// the file's `warnings` / `warning_kinds` attributes.
    pub warnings: Vec<ReportWarning>,
}

/// A warning about the case, kept in the result file: its kind (`"implausible"`, `"budget"`)
/// and the message with file, line and key.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportWarning {
    /// Kind, a lowercase word.
    pub kind: String,
    /// The message as printed.
    pub message: String,
}

/// Why a report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The report is inconsistent; `what` says where (method, series, index).
    #[error("case '{case}': invalid result data: {what}")]
    InvalidReport {
        /// Case name.
        case: String,
        /// What is wrong.
        what: String,
    },
    /// A file-system operation failed.
    #[error("{action} '{path}': {source}")]
    Io {
        /// What was being done.
        action: &'static str,
        /// On which path.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The HDF5 library reported an error.
    #[error("writing HDF5 '{path}' ({context}): {source}")]
    Hdf5 {
        /// The file being written.
        path: PathBuf,
        /// Which object was being written.
        context: String,
        /// The library's error.
        #[source]
        source: hdf5_metno::Error,
    },
    /// Drawing a plot failed.
    #[error("drawing plot '{path}': {message}")]
    Plot {
        /// The PNG being drawn.
        path: PathBuf,
        /// The backend's message.
        message: String,
    },
    /// Writing CSV failed.
    #[error("writing CSV '{path}': {source}")]
    Csv {
        /// The CSV file.
        path: PathBuf,
        /// The csv crate's error.
        #[source]
        source: csv::Error,
    },
}

/// A way of writing a [`CaseReport`] to files.
///
/// Implementations validate the report, write every file atomically (complete or not at all)
/// and return the paths they wrote. They must be usable from several threads at once (batch
/// runs write cases in parallel), hence `Send + Sync`.
pub trait OutputWriter: Send + Sync {
    /// Short name for logs and `--help` ("hdf5", "plots", "csv-summary").
    fn name(&self) -> &'static str;

    /// Write the report's files into `dir` (which must exist), named after
    /// [`CaseReport::case_name`]; returns the paths written.
    fn write(&self, report: &CaseReport, dir: &Path) -> Result<Vec<PathBuf>, OutputError>;
}

/// The writers `jbearing run` uses: HDF5 (with the VTKHDF surface), PNG plots, CSV summary.
pub fn standard_writers() -> Vec<Box<dyn OutputWriter>> {
    vec![
        Box::new(Hdf5Writer::new()),
        Box::new(PlotWriter::default()),
        Box::new(CsvSummaryWriter),
    ]
}

/// The tag in the names of [`write_atomically`]'s temporary files, followed by the writer's
/// process id.
const TEMP_TAG: &str = "jbearing-";

/// Remove the temporary files that killed runs left in `dir` and return their paths: hidden
/// files named by [`write_atomically`] (`.NAME.jbearing-PID.XXXXXX.tmp[.ext]`) whose process
/// is gone. A file whose process may still be running (its PID is alive, or `/proc` cannot
/// tell and the file is less than a day old) is kept. Errors (a file removed meanwhile, a
/// directory that cannot be listed) are not errors of the run and are ignored.
pub fn remove_stale_temporaries(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let proc_fs = Path::new("/proc/self").exists();
    let mut removed = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = temporary_owner(&name) else {
            continue;
        };
        if pid == std::process::id() {
            continue;
        }
        let stale = if proc_fs {
            !Path::new("/proc").join(pid.to_string()).exists()
        } else {
            entry
                .metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age.as_secs() > 86_400)
        };
        if stale && std::fs::remove_file(entry.path()).is_ok() {
            removed.push(entry.path());
        }
    }
    removed
}

/// The writer's process id, if `name` is one of [`write_atomically`]'s temporary files.
fn temporary_owner(name: &str) -> Option<u32> {
    if !name.starts_with('.') || !(name.ends_with(".tmp") || name.contains(".tmp.")) {
        return None;
    }
    let after = &name[name.find(&format!(".{TEMP_TAG}"))? + 1 + TEMP_TAG.len()..];
    let pid = &after[..after.find('.')?];
    pid.parse().ok()
}

/// Runs `write` on a fresh temporary path in the directory of `target` and renames the result to
/// `target` when `write` succeeds. On error (or panic) the temporary file is removed and `target`
/// is untouched: an old `target` stays as it was, a missing one stays missing. Rename within one
/// directory is atomic on POSIX file systems, so a reader sees the old file or the complete new
/// one, never a half-written one.
pub fn write_atomically<F>(target: &Path, write: F) -> Result<(), OutputError>
where
    F: FnOnce(&Path) -> Result<(), OutputError>,
{
    let dir = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let stem = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    // The temporary file is hidden, carries the final name and this process's id
    // (`.CASE.h5.jbearing-PID.XXXXXX.tmp.h5`), so a killed run leaves an obvious leftover, never
    // a plausible-looking result, and a later run recognises it safely
    // ([`remove_stale_temporaries`]). Keep the extension last: some encoders (the PNG one)
    // choose the format by extension.
    let suffix = match target.extension() {
        Some(ext) => format!(".tmp.{}", ext.to_string_lossy()),
        None => ".tmp".to_string(),
    };
    let prefix = format!(".{stem}.{TEMP_TAG}{}.", std::process::id());
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(&suffix);
    // tempfile creates 0600 files; results are ordinary files (0644 less the umask).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let temp = builder
        .tempfile_in(&dir)
        .map_err(|source| OutputError::Io {
            action: "creating a temporary file in",
            path: dir.clone(),
            source,
        })?
        .into_temp_path();
    // `temp` deletes the file when dropped, which covers every early return below.
    write(&temp)?;
    // Data on disk before the rename: after a power loss the target is the old file or the
    // complete new one, not an empty file under the new name.
    std::fs::File::open(&temp)
        .and_then(|f| f.sync_all())
        .map_err(|source| OutputError::Io {
            action: "flushing to disk",
            path: target.to_path_buf(),
            source,
        })?;
    temp.persist(target).map_err(|e| OutputError::Io {
        action: "renaming the finished temporary file to",
        path: target.to_path_buf(),
        source: e.error,
    })?;
    // The rename itself on disk (best effort: not every platform can sync a directory).
    if let Ok(d) = std::fs::File::open(&dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

impl CaseReport {
    /// Why `method` is missing from this report, if the case asked for it and it failed (the
    /// text after "failed: ").
    pub fn failure(&self, method: Method) -> Option<&str> {
        self.parameters
            .iter()
            .find(|p| p.key == method.failure_key())
            .and_then(|p| match &p.value {
                ParameterValue::Text(t) => Some(t.strip_prefix("failed: ").unwrap_or(t)),
                _ => None,
            })
    }

    /// The status of `method` in this report: its result's [`MethodResult::status`],
    /// `"failed: …"` if it failed, `None` if the case did not ask for it.
    pub fn status(&self, method: Method) -> Option<String> {
        match (self.method(method), self.failure(method)) {
            (Some(m), _) => Some(m.status()),
            (None, Some(why)) => Some(format!("failed: {why}")),
            (None, None) => None,
        }
    }

    /// The closed-form table's row of `model` (a `ClosedFormModel::name()`, or "fd_reynolds"),
    /// if the case asked for the table; its `status` says whether the equilibrium was found.
    pub fn closed_form_row(&self, model: &str) -> Option<&ClosedFormRow> {
        self.closed_form
            .as_ref()?
            .rows
            .iter()
            .find(|r| r.model == model)
    }

    /// The result of `method`, if it was run.
    pub fn method(&self, method: Method) -> Option<&MethodResult> {
        self.methods.iter().find(|m| m.method == method)
    }

    /// Checks everything the writers rely on: names are usable as variable names and unique,
    /// every series has one value per sample, coordinates are finite and strictly increasing
    /// where they must be, field shapes match their grids, no value is NaN or infinite.
    pub fn validate(&self) -> Result<(), OutputError> {
        let bad = |what: String| OutputError::InvalidReport {
            case: self.case_name.clone(),
            what,
        };
        if self.case_name.is_empty()
            || self.case_name.contains(['/', '\\', '\0'])
            || self.case_name.starts_with('.')
        {
            return Err(bad(format!(
                "case name '{}' is not usable as a file name",
                self.case_name
            )));
        }
        let g = self.geometry;
        for (name, v) in [
            ("radius", g.radius),
            ("length", g.length),
            ("radial_clearance", g.radial_clearance),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(format!(
                    "geometry {name} = {v} m must be finite and > 0"
                )));
            }
        }
        let mut keys = HashSet::new();
        for p in &self.parameters {
            check_name(&p.key).map_err(|e| bad(format!("parameter: {e}")))?;
            if !keys.insert(p.key.as_str()) {
                return Err(bad(format!("parameter '{}' appears twice", p.key)));
            }
            if let ParameterValue::Number(v) = p.value
                && !v.is_finite()
            {
                return Err(bad(format!("parameter '{}' = {v} is not finite", p.key)));
            }
        }
        let mut seen = HashSet::new();
        for m in &self.methods {
            if !seen.insert(m.method) {
                return Err(bad(format!("method {} appears twice", m.method)));
            }
            validate_method(m).map_err(|e| bad(format!("{}: {e}", m.method)))?;
        }
        let mut rows = HashSet::new();
        for r in &self.summary {
            check_name(&r.name).map_err(|e| bad(format!("summary: {e}")))?;
            if !rows.insert(r.name.as_str()) {
                return Err(bad(format!("summary row '{}' appears twice", r.name)));
            }
            for m in Method::ALL {
                if let Some(v) = r.value(m)
                    && !v.is_finite()
                {
                    return Err(bad(format!("summary '{}' {m} = {v} is not finite", r.name)));
                }
            }
        }
        if let Some(t) = &self.closed_form {
            t.validate().map_err(bad)?;
        }
        Ok(())
    }
}

/// Names become HDF5 dataset names and Python identifiers; keep them plain.
fn check_name(name: &str) -> Result<(), String> {
    let ok = !name.is_empty()
        && name
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else {
        Err(format!(
            "name '{name}' must start with a letter or '_' and contain only letters, digits and '_'"
        ))
    }
}

/// Reserved because they are coordinates in the method group.
const COORDINATE_NAMES: [&str; 4] = ["time", "crank_angle", "theta", "z"];

fn finite_all(what: &str, values: &[f64]) -> Result<(), String> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(format!("{what}[{i}] = {} is not finite", values[i])),
        None => Ok(()),
    }
}

fn strictly_increasing(what: &str, values: &[f64]) -> Result<(), String> {
    finite_all(what, values)?;
    match values.windows(2).position(|w| w[1] <= w[0]) {
        Some(i) => Err(format!(
            "{what} must increase strictly: {what}[{}] = {} follows {}",
            i + 1,
            values[i + 1],
            values[i]
        )),
        None => Ok(()),
    }
}

/// A method's result: its time and crank-angle samples, then its series, fields and solver
/// attributes, each checked by its own stage (the first error found is returned).
fn validate_method(m: &MethodResult) -> Result<(), String> {
    let n = m.time.len();
    if n == 0 {
        return Err("no time samples".into());
    }
    strictly_increasing("time", &m.time)?;
    if m.crank_angle.len() != n {
        return Err(format!(
            "crank_angle has {} values for {n} time samples",
            m.crank_angle.len()
        ));
    }
    finite_all("crank_angle", &m.crank_angle)?;
    validate_series(&m.series, n)?;
    if let Some(f) = &m.fields {
        validate_fields(f)?;
    }
    validate_solver_info(&m.solver_info)
}

/// Series: valid names that are not coordinates and appear once, `n` finite values each.
fn validate_series(series: &[Series], n: usize) -> Result<(), String> {
    let mut names = HashSet::new();
    for s in series {
        check_name(&s.name)?;
        if COORDINATE_NAMES.contains(&s.name.as_str()) {
            return Err(format!(
                "series name '{}' is reserved for a coordinate",
                s.name
            ));
        }
        if !names.insert(s.name.as_str()) {
            return Err(format!("series '{}' appears twice", s.name));
        }
        if s.values.len() != n {
            return Err(format!(
                "series '{}' has {} values for {n} time samples",
                s.name,
                s.values.len()
            ));
        }
        finite_all(&s.name, &s.values)?;
    }
    Ok(())
}

/// Field snapshots: increasing finite instants, a periodic θ grid in [0, 2π) and a z grid,
/// fields with valid unique names, the (instants, n_θ, n_z) shape and finite values.
fn validate_fields(f: &FieldSnapshots) -> Result<(), String> {
    let nt = f.time.len();
    if nt == 0 {
        return Err("fields: no instants".into());
    }
    strictly_increasing("fields.time", &f.time)?;
    if f.crank_angle.len() != nt {
        return Err(format!(
            "fields.crank_angle has {} values for {nt} instants",
            f.crank_angle.len()
        ));
    }
    finite_all("fields.crank_angle", &f.crank_angle)?;
    if f.theta.len() < 3 || f.z.len() < 2 {
        return Err(format!(
            "fields grid {} × {} is too small (need n_θ ≥ 3, n_z ≥ 2)",
            f.theta.len(),
            f.z.len()
        ));
    }
    strictly_increasing("theta", &f.theta)?;
    strictly_increasing("z", &f.z)?;
    let (t0, t1) = (f.theta[0], f.theta[f.theta.len() - 1]);
    if t0 < 0.0 || t1 >= std::f64::consts::TAU {
        return Err(format!(
            "theta must lie in [0, 2π) (periodic, last node not repeated): got {t0} … {t1}"
        ));
    }
    let mut fnames = HashSet::new();
    for fld in &f.fields {
        check_name(&fld.name)?;
        if COORDINATE_NAMES.contains(&fld.name.as_str()) {
            return Err(format!(
                "field name '{}' is reserved for a coordinate",
                fld.name
            ));
        }
        if !fnames.insert(fld.name.as_str()) {
            return Err(format!("field '{}' appears twice", fld.name));
        }
        let want = (nt, f.theta.len(), f.z.len());
        if fld.values.dim() != want {
            return Err(format!(
                "field '{}' has shape {:?}, expected (instants, n_θ, n_z) = {want:?}",
                fld.name,
                fld.values.dim()
            ));
        }
        if let Some((idx, v)) = fld.values.indexed_iter().find(|(_, v)| !v.is_finite()) {
            return Err(format!("field '{}'{idx:?} = {v} is not finite", fld.name));
        }
    }
    Ok(())
}

/// Solver attributes: valid keys other than the group's own `method` and `description`, finite
/// numbers.
fn validate_solver_info(info: &[(String, ParameterValue)]) -> Result<(), String> {
    for (k, v) in info {
        check_name(k)?;
        if k == "method" || k == "description" {
            return Err(format!(
                "solver_info key '{k}' is reserved for the group's own attribute"
            ));
        }
        if let ParameterValue::Number(x) = v
            && !x.is_finite()
        {
            return Err(format!("solver_info '{k}' = {x} is not finite"));
        }
    }
    Ok(())
}
