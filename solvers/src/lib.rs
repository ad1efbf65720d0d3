//! # jbearing-solvers
//!
//! The numerics of jbearing: dynamically loaded journal bearings with mass-conserving
//! (Jakobsson–Floberg–Olsson) cavitation, after Yu & Sawicki (2002), the core seed paper.
//!
//! This crate is pure numerics: SI units in, typed results out, no files and no printing.
//! Parameters, results and errors follow one pattern: `XxxParams` in, `XxxInfo` out, `XxxError`
//! (a `thiserror` enum whose variants carry the numbers) when something fails. Progress of long
//! runs reaches the caller through observer traits, never through a print.
//!
//! Modules
//! - [`tridiagonal`]: the line kernels of the ADI sweeps: Thomas for Dirichlet lines and Yu &
//!   Sawicki's modified Thomas for periodic (circumferential) lines.
//! - [`mobility`]: Booker's mobility method (short-bearing closed forms, finite-length mobility
//!   map, adaptive orbit integration to a periodic cycle, h_min / p_max / flow / power loss).
//! - [`reynolds`]: the universal (Elrod–Vijayaraghavan, mass-conserving) Reynolds equation on a
//!   θ × z grid: steady and time-stepped films, grooves and supply cut-off, ADI-preconditioned
//!   Krylov solve with a sparse-LU oracle, outputs (force, h_min, p_max, flows, power loss) and
//!   the steady load → eccentricity Newton solve.

pub mod mobility;
pub mod reynolds;
pub mod tridiagonal;
