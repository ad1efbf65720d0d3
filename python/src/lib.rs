//! `jbearing._jbearing`: the Rust side of the jbearing Python package.
//!
//! The functions here take plain Python values (numbers, strings, lists) and return dicts of
//! numbers, lists and little-endian `f64` byte buffers; the pure-Python layer
//! (`python/jbearing/__init__.py`) turns them into numpy arrays and xarray datasets with the
//! names, units and dimensions of the CLI's `CASE.h5` (`jbearing::output::hdf5`).
//!
//! ```text
//!   run_case_file(path)   ─┐
//!   solve_case_text(toml) ─┴─► Case ──► jbearing::run::solve_case_checked ──► CaseReport ──► dict
//!   closed_form_text(toml) ──► Case ──► jbearing::closed_form_report::table ──► dict
//!   steady(R, L, c, μ, W, ω, grid, …) ──► ReynoldsSolver::solve_steady_load ──► dict
//! ```
//!
//! The case paths are the CLI's own (`jbearing run` solves through the same
//! `solve_case_checked`), so Python and the CLI give the same numbers for the same case file.
//! Every solve runs with the GIL released; progress reaches an optional Python callable with the
//! GIL taken back for the call. Errors become `JbearingError` subclasses carrying the Rust error's
//! variant name, message and `Debug` form, from which the Python layer sets the variant's fields
//! (the numbers) as attributes.

use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use jbearing::budget::Limits;
use jbearing::case::{Case, CaseError, CaseWarning};
use jbearing::output::{CaseReport, Method, MethodResult, ParameterValue};
use jbearing::run::{RunError, RunObserver};
use jbearing_solvers::reynolds::{
    FilmSolution, GridParams, Groove, OperatingConditions, ReynoldsError, ReynoldsParams,
    ReynoldsSolver, SteadyLoadInfo, SupplyModel,
};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

create_exception!(
    _jbearing,
    JbearingError,
    PyException,
    "Base class of jbearing's errors."
);
create_exception!(
    _jbearing,
    CaseError_,
    JbearingError,
    "A case is invalid (file, line, key and what is wrong)."
);
create_exception!(
    _jbearing,
    SolverError,
    JbearingError,
    "A solve failed; the attributes carry the solver error's numbers."
);
create_exception!(
    _jbearing,
    BudgetError,
    JbearingError,
    "A case's estimated memory or time is above the limits."
);
create_exception!(
    _jbearing,
    OutputError,
    JbearingError,
    "Results could not be written."
);

/// The variant name of a `Debug` form: the identifier it starts with.
fn variant_name(debug: &str) -> String {
    debug
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// A Python exception of class `E` for a Rust error: message = its `Display`, attributes
/// `kind` (the variant), `debug` (its `Debug` form, which the Python layer parses into
/// attributes) and `causes` (the `Display` of each `source()` below it).
fn py_error<E: std::error::Error + std::fmt::Debug>(
    class: Bound<'_, pyo3::types::PyType>,
    err: &E,
) -> PyErr {
    let debug = format!("{err:?}");
    let mut causes = Vec::new();
    let mut src = err.source();
    while let Some(s) = src {
        causes.push(s.to_string());
        src = s.source();
    }
    let made = (|| -> PyResult<PyErr> {
        let exc = class.call1((err.to_string(),))?;
        exc.setattr("kind", variant_name(&debug))?;
        exc.setattr("debug", debug)?;
        exc.setattr("causes", causes)?;
        Ok(PyErr::from_value(exc))
    })();
    made.unwrap_or_else(|e| e)
}

fn case_error(py: Python<'_>, err: &CaseError) -> PyErr {
    py_error(py.get_type::<CaseError_>(), err)
}

fn run_error(py: Python<'_>, err: &RunError) -> PyErr {
    let class = match err {
        RunError::Case(e) => return case_error(py, e),
        RunError::Budget(_) => py.get_type::<BudgetError>(),
        RunError::Output(_) | RunError::OutputDir { .. } => py.get_type::<OutputError>(),
        RunError::DuplicateName { .. } => py.get_type::<CaseError_>(),
        _ => py.get_type::<SolverError>(),
    };
    py_error(class, err)
}

fn reynolds_error(py: Python<'_>, err: &ReynoldsError) -> PyErr {
    let class = match err {
        ReynoldsError::InvalidParameter { .. }
        | ReynoldsError::FeedPressureCount { .. }
        | ReynoldsError::EccentricityOutOfRange { .. } => {
            py.get_type::<pyo3::exceptions::PyValueError>()
        }
        _ => py.get_type::<SolverError>(),
    };
    py_error(class, err)
}

/// Progress of a case to an optional Python callable, called (with the GIL taken back) with one
/// dict per event: `{"event": "step" | "cycle" | "method_started" | "method_done" | "warning",
/// "case", "method", "cycle", "step", "steps", "residual", "message"}`. An exception raised by
/// the callable is kept, stops the rigorous method after its current step, and is raised when
/// the solve returns. Between steps the solve also runs Python's signal handlers (at most every
/// [`SIGNAL_INTERVAL`]), so Ctrl-C stops it with `KeyboardInterrupt`.
struct PyProgress {
    callback: Option<Py<PyAny>>,
    error: Mutex<Option<PyErr>>,
    /// Set once an exception is kept: the solve is asked to stop.
    stop: AtomicBool,
    /// When the signal handlers last ran.
    signals_checked: Mutex<Instant>,
}

/// How often a running solve lets Python handle signals (Ctrl-C).
const SIGNAL_INTERVAL: Duration = Duration::from_millis(50);

impl PyProgress {
    fn new(callback: Option<Py<PyAny>>) -> Self {
        Self {
            callback,
            error: Mutex::new(None),
            stop: AtomicBool::new(false),
            signals_checked: Mutex::new(Instant::now()),
        }
    }

    /// Keep the first exception and ask the solve to stop.
    fn keep(&self, slot: &mut Option<PyErr>, err: PyErr) {
        if slot.is_none() {
            *slot = Some(err);
        }
        self.stop.store(true, Ordering::Relaxed);
    }

    fn send(&self, fill: impl FnOnce(&Bound<'_, PyDict>) -> PyResult<()>) {
        let Some(cb) = &self.callback else {
            return;
        };
        let mut slot = self.error.lock().unwrap_or_else(|p| p.into_inner());
        if slot.is_some() {
            return;
        }
        Python::attach(|py| {
            let r = (|| {
                let d = PyDict::new(py);
                fill(&d)?;
                cb.call1(py, (d,))?;
                Ok::<_, PyErr>(())
            })();
            if let Err(e) = r {
                self.keep(&mut slot, e);
            }
        });
    }

    /// The callable's first exception, if any.
    fn take_error(self) -> PyResult<()> {
        match self.error.into_inner().unwrap_or_else(|p| p.into_inner()) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl RunObserver for PyProgress {
    fn stop_requested(&self) -> bool {
        if self.stop.load(Ordering::Relaxed) {
            return true;
        }
        let mut checked = self
            .signals_checked
            .lock()
            .unwrap_or_else(|p| p.into_inner());
        if checked.elapsed() < SIGNAL_INTERVAL {
            return false;
        }
        *checked = Instant::now();
        // The handlers run on the main thread only (elsewhere this is a no-op).
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            let mut slot = self.error.lock().unwrap_or_else(|p| p.into_inner());
            self.keep(&mut slot, e);
        }
        self.stop.load(Ordering::Relaxed)
    }
    fn method_started(&self, case: &str, method: Method) {
        self.send(|d| {
            d.set_item("event", "method_started")?;
            d.set_item("case", case)?;
            d.set_item("method", method.as_str())
        });
    }
    fn cycle_done(&self, case: &str, method: Method, cycle: usize, residual: f64) {
        self.send(|d| {
            d.set_item("event", "cycle")?;
            d.set_item("case", case)?;
            d.set_item("method", method.as_str())?;
            d.set_item("cycle", cycle)?;
            d.set_item("residual", residual)
        });
    }
    fn progress(
        &self,
        case: &str,
        method: Method,
        cycle: usize,
        step: usize,
        steps: usize,
        residual: f64,
    ) {
        self.send(|d| {
            d.set_item("event", "step")?;
            d.set_item("case", case)?;
            d.set_item("method", method.as_str())?;
            d.set_item("cycle", cycle)?;
            d.set_item("step", step)?;
            d.set_item("steps", steps)?;
            d.set_item("residual", residual)
        });
    }
    fn method_done(&self, case: &str, method: Method) {
        self.send(|d| {
            d.set_item("event", "method_done")?;
            d.set_item("case", case)?;
            d.set_item("method", method.as_str())
        });
    }
    fn warning(&self, case: &str, warning: &CaseWarning) {
        self.send(|d| {
            d.set_item("event", "warning")?;
            d.set_item("case", case)?;
            d.set_item("kind", warning.kind.as_str())?;
            d.set_item("message", warning.to_string())
        });
    }
}

/// `f64` values as a little-endian byte buffer (numpy's `frombuffer(..., "<f8")`): exact.
fn f64_bytes<'py>(py: Python<'py>, values: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    PyBytes::new(py, &bytes)
}

fn parameter_value<'py>(py: Python<'py>, v: &ParameterValue) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        ParameterValue::Number(x) => x.into_pyobject(py)?.into_any(),
        ParameterValue::Integer(x) => x.into_pyobject(py)?.into_any(),
        ParameterValue::Flag(x) => x.into_pyobject(py)?.to_owned().into_any(),
        ParameterValue::Text(x) => x.into_pyobject(py)?.into_any(),
    })
}

fn method_dict<'py>(py: Python<'py>, m: &MethodResult) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("method", m.method.as_str())?;
    d.set_item("description", m.method.description())?;
    d.set_item("time", f64_bytes(py, m.time.iter().copied()))?;
    d.set_item("crank_angle", f64_bytes(py, m.crank_angle.iter().copied()))?;
    let series = PyList::empty(py);
    for s in &m.series {
        series.append((
            &s.name,
            &s.long_name,
            &s.units,
            f64_bytes(py, s.values.iter().copied()),
        ))?;
    }
    d.set_item("series", series)?;
    let info = PyList::empty(py);
    for (k, v) in &m.solver_info {
        info.append((k, parameter_value(py, v)?))?;
    }
    d.set_item("solver_info", info)?;
    if let Some(f) = &m.fields {
        let fd = PyDict::new(py);
        fd.set_item("time", f64_bytes(py, f.time.iter().copied()))?;
        fd.set_item("crank_angle", f64_bytes(py, f.crank_angle.iter().copied()))?;
        fd.set_item("theta", f64_bytes(py, f.theta.iter().copied()))?;
        fd.set_item("z", f64_bytes(py, f.z.iter().copied()))?;
        let fields = PyList::empty(py);
        for fld in &f.fields {
            let (a, b, c) = fld.values.dim();
            fields.append((
                &fld.name,
                &fld.long_name,
                &fld.units,
                // Row-major (C order) whatever the array's own layout.
                f64_bytes(py, fld.values.iter().copied()),
                (a, b, c),
            ))?;
        }
        fd.set_item("fields", fields)?;
        d.set_item("fields", fd)?;
    }
    Ok(d)
}

fn closed_form_dict<'py>(
    py: Python<'py>,
    t: &jbearing::output::ClosedFormTable,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("load_basis", &t.load_basis)?;
    d.set_item("load", (t.load[0], t.load[1]))?;
    d.set_item("relative_speed", t.relative_speed)?;
    let rows = PyList::empty(py);
    for r in &t.rows {
        let cols: Vec<_> = r.columns().into_iter().collect();
        rows.append((&r.model, &r.status, cols))?;
    }
    d.set_item("rows", rows)?;
    Ok(d)
}

fn report_dict<'py>(py: Python<'py>, r: &CaseReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("case_name", &r.case_name)?;
    d.set_item("case_text", &r.case_text)?;
    d.set_item(
        "case_path",
        r.case_path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_default(),
    )?;
    d.set_item(
        "input_files",
        r.input_files
            .iter()
            .map(|f| (f.path.clone(), f.text.clone()))
            .collect::<Vec<_>>(),
    )?;
    let g = r.geometry;
    d.set_item("geometry", (g.radius, g.length, g.radial_clearance))?;
    let params = PyList::empty(py);
    for p in &r.parameters {
        let kind = match p.value {
            ParameterValue::Number(_) => "number",
            ParameterValue::Integer(_) => "integer",
            ParameterValue::Flag(_) => "flag",
            ParameterValue::Text(_) => "text",
        };
        params.append((
            &p.key,
            parameter_value(py, &p.value)?,
            &p.units,
            &p.long_name,
            kind,
        ))?;
    }
    d.set_item("parameters", params)?;
    let run = PyDict::new(py);
    run.set_item("jbearing_version", &r.run.jbearing_version)?;
    run.set_item("git_commit", &r.run.git_commit)?;
    run.set_item("wall_time", r.run.wall_time)?;
    run.set_item("started_utc", &r.run.started_utc)?;
    d.set_item("run", run)?;
    let methods = PyList::empty(py);
    for m in &r.methods {
        methods.append(method_dict(py, m)?)?;
    }
    d.set_item("methods", methods)?;
    d.set_item(
        "method_names",
        Method::ALL.iter().map(|m| m.as_str()).collect::<Vec<_>>(),
    )?;
    let summary = PyList::empty(py);
    for row in &r.summary {
        summary.append((
            &row.name,
            &row.long_name,
            &row.units,
            Method::ALL
                .iter()
                .map(|m| row.value(*m).unwrap_or(f64::NAN))
                .collect::<Vec<_>>(),
        ))?;
    }
    d.set_item("summary", summary)?;
    match &r.closed_form {
        Some(t) => d.set_item("closed_form", closed_form_dict(py, t)?)?,
        None => d.set_item("closed_form", py.None())?,
    }
    d.set_item(
        "warnings",
        r.warnings
            .iter()
            .map(|w| (w.kind.clone(), w.message.clone()))
            .collect::<Vec<_>>(),
    )?;
    Ok(d)
}

/// Solve `case` as `jbearing run` does (budget check, warnings, both methods), GIL released.
fn solve<'py>(
    py: Python<'py>,
    case: Case,
    limits: Limits,
    progress: Option<Py<PyAny>>,
    out_dir: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let observer = PyProgress::new(progress);
    let result = py.detach(|| match &out_dir {
        Some(dir) => jbearing::run::run_case(&case, dir, &limits, &observer).map(|o| o.report),
        None => jbearing::run::solve_case_checked(&case, &limits, &observer),
    });
    observer.take_error()?;
    let report = result.map_err(|e| run_error(py, &e))?;
    report_dict(py, &report)
}

fn limits(max_memory_gib: f64, max_hours: f64) -> Limits {
    Limits::from_gib_hours(max_memory_gib, max_hours)
}

/// Run the case file at `path` exactly as `jbearing run` does and return its report; with
/// `out_dir`, the CLI's files (CASE.h5, CSV summary, plots) are written there too.
#[pyfunction]
#[pyo3(signature = (path, *, out_dir=None, progress=None, max_memory_gib=8.0, max_hours=24.0))]
fn run_case_file<'py>(
    py: Python<'py>,
    path: PathBuf,
    out_dir: Option<PathBuf>,
    progress: Option<Py<PyAny>>,
    max_memory_gib: f64,
    max_hours: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let case = Case::from_file(&path).map_err(|e| case_error(py, &e))?;
    solve(
        py,
        case,
        limits(max_memory_gib, max_hours),
        progress,
        out_dir,
    )
}

/// Resolve the TOML case `text` (`path` names it in messages and anchors relative CSV paths)
/// and solve it as [`run_case_file`] does.
#[pyfunction]
#[pyo3(signature = (text, path, *, out_dir=None, progress=None, max_memory_gib=8.0, max_hours=24.0))]
fn solve_case_text<'py>(
    py: Python<'py>,
    text: &str,
    path: PathBuf,
    out_dir: Option<PathBuf>,
    progress: Option<Py<PyAny>>,
    max_memory_gib: f64,
    max_hours: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let case = Case::from_text(text, &path).map_err(|e| case_error(py, &e))?;
    solve(
        py,
        case,
        limits(max_memory_gib, max_hours),
        progress,
        out_dir,
    )
}

/// The closed-form static-equilibrium table of the TOML case `text` (`jbearing closed-form`):
/// the models of its `[closed_form]` table, or every model when it has none.
#[pyfunction]
fn closed_form_text<'py>(
    py: Python<'py>,
    text: &str,
    path: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let case = Case::from_text(text, &path).map_err(|e| case_error(py, &e))?;
    let models = if case.closed_form_models.is_empty() {
        jbearing_solvers::closed_form::ClosedFormModel::ALL.to_vec()
    } else {
        case.closed_form_models.clone()
    };
    let table = py.detach(|| jbearing::closed_form_report::table(&case, &models));
    closed_form_dict(py, &table)
}

/// The steady film of a rigid bearing under a constant load: Newton on the eccentricity
/// (`ReynoldsSolver::solve_steady_load`) with the mass-conserving (JFO) film. Grooves are
/// `(center_angle [rad], center_z [m], angular_width [rad], axial_width [m])`, each fed at
/// `feed_pressure`; without grooves the film is fed along the axial line at the widest gap.
/// `n_theta`/`n_z` left out (None) take the library's default grid of this L/D.
#[pyfunction]
#[pyo3(signature = (*, radius, length, clearance, viscosity, load_x, load_y, journal_speed,
    bearing_speed, n_theta, n_z, grooves, feed_pressure, bulk_modulus, cavitation_pressure,
    ambient_pressure, supply_line))]
#[allow(clippy::too_many_arguments)]
fn steady<'py>(
    py: Python<'py>,
    radius: f64,
    length: f64,
    clearance: f64,
    viscosity: f64,
    load_x: f64,
    load_y: f64,
    journal_speed: f64,
    bearing_speed: f64,
    n_theta: Option<usize>,
    n_z: Option<usize>,
    grooves: Vec<(f64, f64, f64, f64)>,
    feed_pressure: f64,
    bulk_modulus: f64,
    cavitation_pressure: f64,
    ambient_pressure: f64,
    supply_line: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let n_grooves = grooves.len();
    let grid = {
        let default = GridParams::for_length_ratio(length / (2.0 * radius));
        GridParams {
            n_theta: n_theta.unwrap_or(default.n_theta),
            n_z: n_z.unwrap_or(default.n_z),
        }
    };
    let params = ReynoldsParams {
        bulk_modulus,
        cavitation_pressure,
        ambient_pressure,
        grooves: steady_grooves(grooves),
        supply: if supply_line {
            SupplyModel::AxialLineAtMaxGap
        } else {
            SupplyModel::Grooves
        },
        grid,
        ..ReynoldsParams::plain(radius, length, clearance, viscosity)
    };
    let conditions = OperatingConditions {
        journal_speed,
        bearing_speed,
        feed_pressures: vec![feed_pressure; n_grooves],
    };
    let result = py.detach(|| {
        let mut solver = ReynoldsSolver::new(params)?;
        solver.solve_steady_load([load_x, load_y], &conditions)
    });
    let (sol, info) = result.map_err(|e| reynolds_error(py, &e))?;
    steady_dict(py, &sol, &info, clearance)
}

/// The steady solve's grooves from `(center_angle [rad], center_z [m], angular_width [rad],
/// axial_width [m])` tuples, each with the library's 1 % cut-off film fraction.
fn steady_grooves(grooves: Vec<(f64, f64, f64, f64)>) -> Vec<Groove> {
    grooves
        .into_iter()
        .map(
            |(center_angle, center_z, angular_width, axial_width)| Groove {
                center_angle,
                center_z,
                angular_width,
                axial_width,
                cutoff_film_fraction: 0.01,
            },
        )
        .collect()
}

/// The steady solve's answer as the dict `steady` returns: the Newton's report, the film's
/// scalars and its (θ, z) fields as little-endian f64 bytes.
fn steady_dict<'py>(
    py: Python<'py>,
    sol: &FilmSolution,
    info: &SteadyLoadInfo,
    clearance: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let eps = info.eccentricity_ratio;
    d.set_item("eccentricity_ratio", (eps[0], eps[1]))?;
    d.set_item("newton_iterations", info.iterations)?;
    d.set_item("force_residual", info.force_residual)?;
    d.set_item("film_solves", info.film_solves)?;
    d.set_item("film_force", (sol.film_force[0], sol.film_force[1]))?;
    d.set_item("attitude_angle", sol.attitude_angle)?;
    d.set_item("min_film_thickness", sol.min_film_thickness)?;
    d.set_item("max_pressure", sol.max_pressure)?;
    d.set_item("cavitated_fraction", sol.cavitated_fraction)?;
    d.set_item("side_leakage", sol.side_leakage[0] + sol.side_leakage[1])?;
    d.set_item(
        "supply_flow",
        sol.supply_flow.iter().sum::<f64>() + sol.supply_line_flow,
    )?;
    d.set_item("recirculated_flow", sol.recirculated_flow)?;
    d.set_item("power_loss", sol.power_loss)?;
    d.set_item("friction_torque_journal", sol.friction_torque_journal)?;
    d.set_item("friction_torque_bearing", sol.friction_torque_bearing)?;
    d.set_item("theta", f64_bytes(py, sol.theta.iter().copied()))?;
    d.set_item("z", f64_bytes(py, sol.z.iter().copied()))?;
    let (nt, nz) = sol.pressure.dim();
    d.set_item("shape", (nt, nz))?;
    d.set_item("pressure", f64_bytes(py, sol.pressure.iter().copied()))?;
    d.set_item(
        "film_content",
        f64_bytes(py, sol.film_fraction.iter().copied()),
    )?;
    // h(θ) = c (1 − ε_x cos θ − ε_y sin θ) (docs/conventions.md §1), the same along z; the
    // app's field snapshots use the same expression.
    let h = sol.theta.iter().flat_map(|th| {
        let v = clearance * (1.0 - eps[0] * th.cos() - eps[1] * th.sin());
        std::iter::repeat_n(v, nz)
    });
    d.set_item("film_thickness", f64_bytes(py, h))?;
    Ok(d)
}

/// The CASE.h5 layout table the HDF5 writer uses (`jbearing::output::layout`): `{"variables":
/// {name: (units, long_name)}, "texts": {key: text}}`, so the Python tree spells the coordinates,
/// geometry scalars and group descriptions as the file does.
#[pyfunction]
fn layout(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    use jbearing::output::layout::{TEXTS, VARIABLES};
    let variables = PyDict::new(py);
    for v in VARIABLES {
        variables.set_item(v.name, (v.units, v.long_name))?;
    }
    let texts = PyDict::new(py);
    for (key, text) in TEXTS {
        texts.set_item(key, text)?;
    }
    let d = PyDict::new(py);
    d.set_item("variables", variables)?;
    d.set_item("texts", texts)?;
    Ok(d)
}

#[pymodule]
fn _jbearing(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("JbearingError", py.get_type::<JbearingError>())?;
    m.add("CaseError", py.get_type::<CaseError_>())?;
    m.add("SolverError", py.get_type::<SolverError>())?;
    m.add("BudgetError", py.get_type::<BudgetError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(run_case_file, m)?)?;
    m.add_function(wrap_pyfunction!(solve_case_text, m)?)?;
    m.add_function(wrap_pyfunction!(closed_form_text, m)?)?;
    m.add_function(wrap_pyfunction!(steady, m)?)?;
    m.add_function(wrap_pyfunction!(layout, m)?)?;
    Ok(())
}
