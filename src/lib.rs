//! jbearing, the application: case files, batch runs, result output (HDF5 for xarray and
//! pyvista, PNG plots, CSV summaries). The numerics live in the `jbearing-solvers` crate.
//!
//! - [`case`]: TOML case files (schema, units, histories from CSV, errors with file/key/line),
//!   and the compressor machine file behind `jbearing synth-loads`.
//! - [`run`]: one case through each method into a [`output::CaseReport`].
//! - [`batch`]: many cases in parallel with progress bars and a summary table.
//! - [`cli`]: the `jbearing` command line.
//! - [`output`]: the writers (HDF5, plots, CSV summary).
//! - [`validate`]: `jbearing validate`, the validation cases against their published values.

pub mod batch;
pub mod case;
pub mod cli;
pub mod output;
pub mod run;
pub mod validate;
