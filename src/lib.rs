//! jbearing, the application: case files, batch runs, result output (HDF5 for xarray and
//! pyvista, PNG plots, CSV summaries). The numerics live in the `jbearing-solvers` crate.

pub mod output;
