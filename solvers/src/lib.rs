//! # jbearing-solvers
//!
//! The numerics of jbearing: dynamically loaded journal bearings with mass-conserving
//! (Jakobsson–Floberg–Olsson) cavitation, after Yu & Sawicki \[YuSawicki2002\], the core paper of the project (references:
//! `docs/REFERENCES.md`; conventions: `docs/conventions.md`).
//!
//! This crate is pure numerics: SI units in, typed results out, no files and no printing.
//! Parameters, results and errors follow one pattern: `XxxParams` in, `XxxInfo` out, `XxxError`
//! (a `thiserror` enum whose variants carry the numbers) when something fails. Progress of long
//! runs reaches the caller through observer traits, never through a print.
//!
//! # In ten lines
//!
//! A steady load to the eccentricity that carries it, with the mass-conserving Reynolds film
//! (`use jbearing_solvers::prelude::*` brings the types of the everyday jobs):
//!
//! ```
//! use jbearing_solvers::prelude::*;
//!
//! // R = 20 mm, L = 20 mm, c = 20 µm, μ = 0.02 Pa s; a coarse grid keeps the doctest quick.
//! let mut params = ReynoldsParams::plain(0.02, 0.02, 20e-6, 0.02);
//! params.grid = GridParams { n_theta: 48, n_z: 11 };
//! // Oil at ambient pressure along the widest gap (Raimondi & Boyd's steady bearing).
//! params.supply = SupplyModel::AxialLineAtMaxGap;
//! let mut film = ReynoldsSolver::new(params)?;
//! let rotation = OperatingConditions { journal_speed: 300.0, ..Default::default() };
//! let (solution, info) = film.solve_steady_load([0.0, -2000.0], &rotation)?;
//! let eps = info.eccentricity_ratio[0].hypot(info.eccentricity_ratio[1]);
//! assert!(eps > 0.0 && eps < 1.0 && solution.min_film_thickness < 20e-6);
//! # Ok::<(), ReynoldsError>(())
//! ```
//!
//! The runnable programs in the repository's `examples/` (steady bearing, inverse cycle of a
//! grooved bearing, the mobility answer beside it) show the three everyday jobs end to end.
//!
//! Modules
//! - [`banded`]: banded LU with partial pivoting (the multigrid's coarsest-level solve).
//! - [`closed_form`]: the closed-form film models of \[Flores2006\] and \[Flores2009\] for a moving journal (short and long
//!   bearing, Sommerfeld and Gumbel films, Pinkus–Sternlicht) and their static equilibrium.
//! - [`tridiagonal`]: the line kernels of the ADI sweeps: Thomas for Dirichlet lines and Yu &
//!   Sawicki's modified Thomas for periodic (circumferential) lines.
//! - [`load`]: load histories shared by the mobility method and the inverse solver: periodic
//!   load tables, synthetic loads, and the [`load::LoadHistory`] trait (W(t), ω_j, ω_b, p_feed).
//! - [`elastic`]: plane-strain finite elements of the shaft and the housing (bilinear
//!   quadrilaterals, faer sparse Cholesky), their film-gap compliance, and the deformable
//!   bearing under a steady load (film and structure coupled, \[Benasciutti2012\]).
//! - [`inverse`]: the inverse dynamic-load problem (load history → journal orbit): Newton on the
//!   eccentricity per time step, run-in, cycles to a periodic solution, per-step time series.
//! - [`mechanism`]: the planar slider-crank of \[Flores2009\] with a lubricated
//!   rod–slider joint (closed-form or Reynolds film, Lankarani–Nikravesh contact when the film
//!   breaks down), integrated in minimal coordinates; and its ideal-joint inverse dynamics.
//! - [`mobility`]: Booker's mobility method (short-bearing closed forms, finite-length mobility
//!   map, adaptive orbit integration to a periodic cycle, h_min / p_max / flow / power loss).
//! - [`ritz`]: the Ritz method of \[Antonic2004\] for the finite bearing with a film on 0 … π.
//! - [`slider_crank`]: a single-cylinder slider-crank compressor (polytropic cylinder cycle,
//!   two-mass rod) giving the main- and rod-bearing loads, the rod's angular velocity and the rod
//!   bearing's feed pressure through the crank drilling (the compressor cases of Yu & Sawicki).
//! - [`squeeze_film`]: the finite-length pure-squeeze film under the Reynolds condition
//!   (finite differences + active set), the source of the finite-length mobility map.
//! - [`reynolds`]: the universal (Elrod–Vijayaraghavan, mass-conserving) Reynolds equation on a
//!   θ × z grid: steady and time-stepped films, grooves and supply cut-off, ADI-preconditioned
//!   Krylov solve with a sparse-LU oracle, outputs (force, h_min, p_max, flows, power loss) and
//!   the steady load → eccentricity Newton solve.

pub mod banded;
pub mod closed_form;
pub mod elastic;
pub mod heat_balance;
pub mod inverse;
pub mod load;
pub mod mechanism;
pub mod mobility;
pub mod prelude;
pub mod reynolds;
pub mod ritz;
pub mod slider_crank;
pub mod squeeze_film;
pub mod time_scheme;
pub mod tridiagonal;
pub mod viscosity;
