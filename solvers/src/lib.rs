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
//! - [`closed_form`]: the seeds' closed-form film models for a moving journal (short and long
//!   bearing, Sommerfeld and Gumbel films, Pinkus–Sternlicht) and their static equilibrium.
//! - [`tridiagonal`]: the line kernels of the ADI sweeps: Thomas for Dirichlet lines and Yu &
//!   Sawicki's modified Thomas for periodic (circumferential) lines.
//! - [`mobility`]: Booker's mobility method (short-bearing closed forms, finite-length mobility
//!   map, adaptive orbit integration to a periodic cycle, h_min / p_max / flow / power loss).
//! - [`ritz`]: the Ritz method of seed 001 for the finite bearing with a film on 0 … π.

pub mod closed_form;
pub mod mobility;
pub mod ritz;
pub mod tridiagonal;
