//! The types of the everyday jobs in one import: `use jbearing_solvers::prelude::*;`.
//!
//! - a steady bearing: [`ReynoldsSolver`] ([`ReynoldsParams`], [`GridParams`], [`Groove`],
//!   [`OperatingConditions`]) → [`FilmSolution`], [`SteadyLoadInfo`];
//! - the inverse cycle (load history in, journal orbit out): [`solve_inverse`] with a
//!   [`FilmModel`] ([`ReynoldsFilm`] or a [`ClosedFormFilm`]) and a [`LoadHistory`]
//!   ([`OperatingHistory`] of a [`TabulatedLoad`], [`ConstantLoad`] …) → [`InverseSolution`];
//! - the mobility method beside it: [`solve_orbit`] with a [`MobilityModel`]
//!   ([`ExactShortBearing`], [`BookerShortBearing`], a [`MobilityMap`]) → [`OrbitInfo`];
//! - the closed forms: [`ClosedFormModel`], [`ClosedFormParams`], [`static_equilibrium`];
//! - one [`TimeScheme`] for every time-stepped film (BDF2 by default) and the
//!   [`ViscosityModel`] of the lubricant.
//!
//! Each error type is here too, so that `?` works in a function returning
//! `Result<_, Box<dyn std::error::Error>>` without further imports.

pub use crate::closed_form::{
    ClosedFormError, ClosedFormFilm, ClosedFormModel, ClosedFormParams, static_equilibrium,
};
pub use crate::inverse::{
    FilmModel, FilmModelError, FilmResponse, InverseError, InverseInfo, InverseObserver,
    InverseParams, InverseSolution, InverseStep, NoObserver, ReynoldsFilm, solve_inverse,
};
pub use crate::load::{
    ConstantLoad, LoadHistory, LoadInterpolation, OperatingHistory, PeriodicLoad, RotatingLoad,
    TabulatedLoad,
};
pub use crate::mobility::{
    BookerShortBearing, ExactShortBearing, MobilityError, MobilityMap, MobilityMapParams,
    MobilityModel, MobilityParams, OrbitInfo, OrbitParams, solve_orbit,
};
pub use crate::reynolds::{
    FilmSolution, GridParams, Groove, OperatingConditions, ReynoldsError, ReynoldsParams,
    ReynoldsSolver, SteadyLoadInfo, SupplyModel,
};
pub use crate::time_scheme::TimeScheme;
pub use crate::viscosity::{IsoViscosityGrade, ViscosityModel};
