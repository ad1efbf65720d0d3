//! Periodic loads for the mobility orbit.
//!
//! The load tables now live in the shared module [`crate::load`] (used by the mobility method
//! and the inverse solver alike); this module re-exports them so that
//! `mobility::load::TabulatedLoad` and friends keep working.

pub use crate::load::{LoadInterpolation, LoadTableError, PeriodicLoad, TabulatedLoad};
