//! jbearing, the application: case files, batch runs, result output (HDF5 for xarray and
//! pyvista, PNG plots, CSV summaries). The numerics live in the `jbearing-solvers` crate.
//!
//! - [`case`]: TOML case files (schema, units, histories from CSV, errors with file/key/line),
//!   and the compressor machine file behind `jbearing synth-loads`.
//! - [`run`]: one case through each method into a [`output::CaseReport`].
//! - [`batch`]: many cases in parallel with progress (bars or lines) and a summary table.
//! - [`budget`]: a case's estimated memory and time, against the limits.
//! - [`cli`]: the `jbearing` command line.
//! - [`closed_form_report`]: the closed-form static-equilibrium table of a case.
//! - [`mechanism`]: `jbearing run` of a mechanism case (the slider-crank of seed 004): solves,
//!   HDF5, summary, plots.
//! - [`merge`]: `jbearing merge`, a batch's results in one netCDF dataset along `case`.
//! - [`output`]: the writers (HDF5, plots, CSV summary).
//! - [`sweep`]: `[sweep]` tables expanded into named cases, and the shard of a case.
//! - [`validate`]: `jbearing validate`, the validation cases against their published values.

pub mod batch;
pub mod budget;
pub mod case;
pub mod cli;
pub mod closed_form_report;
pub mod mechanism;
pub mod merge;
pub mod output;
pub mod run;
pub mod sweep;
pub mod validate;
