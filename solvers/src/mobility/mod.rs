//! Booker's mobility method: the quick answer beside the rigorous (JFO) solution.
//!
//! # The equation
//!
//! For a rigid plain journal bearing the Reynolds equation with surface speed U = R(ω_j − ω_b)
//! (bearing frame, docs/conventions.md §1) and film h = c − e·n, n = (cos θ, sin θ), reads
//!
//! ```text
//!   ∇·(h³/12μ ∇p) = (U/2R) ∂h/∂θ + ∂h/∂t = −(v·n),     v = ė − ω̄ × e,   ω̄ = (ω_j − ω_b)/2
//! ```
//!
//! i.e. wedge plus squeeze is a **pure squeeze** with the effective velocity v \[Booker1965\].
//! ω̄ = (ω_j − ω_b)/2 is the bearing-frame form of Booker's fixed-frame ω̄ = (ω_j + ω_b)/2: in a
//! fixed frame ė_fixed = v + ω̄_fixed × e, and the bearing frame turns at ω_b, so
//! ė = ė_fixed − ω_b × e = v + ((ω_j + ω_b)/2 − ω_b) × e. For a fixed bearing ω̄ = ω_j/2 (taking
//! ω_j instead doubles the Sommerfeld number — \[Flores2006\]'s nomenclature gives ω̄ = ω/2).
//!
//! The pure-squeeze solution is linear in v for a fixed film-rupture line, so the load
//! W (the force the machine applies to the journal, docs/conventions.md §1) fixes v through the
//! dimensionless **mobility** M (\[Flores2006\], eqs. 23–24, written as one vector equation):
//!
//! ```text
//!   dε/dt = |W| (c/R)² / (μ L D) · M(ε, Ŵ, L/D) + ω̄ × ε
//! ```
//!
//! M is evaluated in the **frame of the load**: ζ along W, κ 90° ahead of it (counter-clockwise,
//! the θ direction), ζ = ε·Ŵ, κ = ε·(ẑ × Ŵ). A "negative" unidirectional load is a positive load
//! along the reversed direction, so one formula covers both signs (\[Flores2006\] eqs. 28–31 are the
//! two halves of it: eqs. 30–31 are eqs. 28–29 with ζ → −ζ, κ → −κ).
//!
//! ```text
//!            κ (ẑ × Ŵ)
//!            ↑
//!            |    • ε = (ζ, κ)
//!            |   /
//!            |  /
//!            | /
//!   ─────────o──────────→ ζ  (Ŵ, along the load)
//! ```
//!
//! # Modules
//! - [`short_bearing`]: the short-bearing (Ocvirk) pure-squeeze film under Gumbel's half-film
//!   condition — Booker's closed-form mobility (\[Flores2006\] eqs. 28–35) and the exact short-bearing
//!   mobility obtained by inverting the closed-form squeeze-force integrals (\[Flores2006\] eqs. 25–27).
//! - [`map`]: the finite-length mobility map, tabulated over (ε, load angle) per L/D from any
//!   pure-squeeze force provider, interpolated smoothly; the Reynolds-based provider plugs in
//!   here.
//! - [`load`]: periodic loads (the small trait the orbit needs and a crank-angle table).
//! - [`performance`]: h_min, p_max, side flow and power loss of the mobility answer, by stated
//!   closed forms.
//! - [`orbit`]: adaptive Dormand–Prince integration of the orbit to a periodic cycle.
//! - [`compare`]: cycle metrics (mean ε, minimum h_min, mean flow, mean power loss) and the
//!   mobility answer's deviation in % from a reference answer (Yu & Sawicki's comparison).

pub mod compare;
pub mod load;
pub mod map;
pub mod orbit;
pub mod performance;
pub mod short_bearing;

pub use compare::{
    CycleMetrics, CycleSeries, DeviationReport, OrbitColumns, compare_cycles, cycle_metrics,
};
pub use load::{LoadInterpolation, LoadTableError, PeriodicLoad, TabulatedLoad};
pub use map::{
    MobilityMap, MobilityMapCache, MobilityMapError, MobilityMapParams, PureSqueezeFilm,
    ShortBearingSqueeze,
};
pub use orbit::{OrbitInfo, OrbitParams, OrbitSummary, solve_orbit};
pub use performance::{PerformancePoint, performance_at};
pub use short_bearing::{BookerShortBearing, ExactShortBearing, short_bearing_squeeze_integral};

use thiserror::Error;

/// A mobility model: the dimensionless pure-squeeze mobility in the frame of the load.
///
/// `mobility(ζ, κ)` returns (M^ζ, M^κ) for a unit load along +ζ, with the journal at
/// ε = (ζ, κ), ζ² + κ² < 1. The model fixes L/D.
pub trait MobilityModel {
    /// Length-to-diameter ratio L/D the model was built for.
    fn length_to_diameter(&self) -> f64;
    /// Largest eccentricity ratio at which the model is valid (1 for closed forms, the table's
    /// edge for a tabulated map).
    fn max_eccentricity(&self) -> f64 {
        1.0
    }
    /// (M^ζ, M^κ) at ε = (ζ, κ) in the load frame. Callers guarantee |ε| < `max_eccentricity`.
    fn mobility(&self, zeta: f64, kappa: f64) -> [f64; 2];
}

/// Geometry, lubricant and speeds of the bearing, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MobilityParams {
    /// Journal radius R (m); D = 2R.
    pub radius: f64,
    /// Bearing length L (m).
    pub length: f64,
    /// Radial clearance c (m).
    pub radial_clearance: f64,
    /// Dynamic viscosity μ (Pa·s).
    pub viscosity: f64,
    /// Journal angular velocity ω_j in a fixed frame (rad/s), positive counter-clockwise (θ).
    pub omega_journal: f64,
    /// Bearing angular velocity ω_b in a fixed frame (rad/s); 0 for a fixed bearing.
    pub omega_bearing: f64,
}

impl MobilityParams {
    /// L/D.
    pub fn length_to_diameter(&self) -> f64 {
        self.length / (2.0 * self.radius)
    }

    /// Booker's ω̄ in the bearing frame: (ω_j − ω_b)/2 (rad/s).
    pub fn omega_bar(&self) -> f64 {
        0.5 * (self.omega_journal - self.omega_bearing)
    }

    /// The bearing's geometry and lubricant as the closed forms take them.
    pub fn closed_form(&self) -> crate::closed_form::ClosedFormParams {
        crate::closed_form::ClosedFormParams {
            radius: self.radius,
            length: self.length,
            radial_clearance: self.radial_clearance,
            viscosity: self.viscosity,
        }
    }

    /// The load-to-squeeze-rate scale (c/R)²/(μ L D) in 1/(N·s): dε/dt = |W| · scale · M + ω̄ × ε.
    pub fn mobility_scale(&self) -> f64 {
        let cr = self.radial_clearance / self.radius;
        cr * cr / (self.viscosity * self.length * 2.0 * self.radius)
    }

    /// Check that every parameter is finite and positive where it must be.
    pub fn validate(&self) -> Result<(), MobilityError> {
        let positive = [
            ("radius", self.radius),
            ("length", self.length),
            ("radial_clearance", self.radial_clearance),
            ("viscosity", self.viscosity),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(MobilityError::InvalidParameter { name, value });
            }
        }
        for (name, value) in [
            ("omega_journal", self.omega_journal),
            ("omega_bearing", self.omega_bearing),
        ] {
            if !value.is_finite() {
                return Err(MobilityError::InvalidParameter { name, value });
            }
        }
        if self.radial_clearance >= self.radius {
            return Err(MobilityError::InvalidParameter {
                name: "radial_clearance (must be << radius)",
                value: self.radial_clearance,
            });
        }
        Ok(())
    }
}

/// What can go wrong in the mobility method.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MobilityError {
    /// A parameter is not finite or out of its range.
    #[error("invalid parameter {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
    /// The mobility model was built for another L/D than the bearing's.
    #[error("mobility model is for L/D = {model}, the bearing has L/D = {bearing}")]
    LengthToDiameterMismatch { model: f64, bearing: f64 },
    /// The eccentricity ratio reached the collapse limit: the film is gone.
    #[error(
        "film collapse: |ε| reached {eccentricity:.6} (limit {limit}) at t = {time:.6e} s, crank angle {crank_angle_deg:.2}° (cycle {cycle})"
    )]
    FilmCollapse {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
        eccentricity: f64,
        limit: f64,
    },
    /// The orbit reached the edge of the mobility model's range (a tabulated map's largest ε),
    /// which lies below the collapse limit: the model cannot say what the film does beyond it.
    #[error(
        "the orbit left the mobility model's range: |ε| reached {eccentricity:.6}, the model covers |ε| < {model_limit} (not a film collapse: the collapse limit is {collapse_limit}) at t = {time:.6e} s, crank angle {crank_angle_deg:.2}° (cycle {cycle})"
    )]
    OutsideModelRange {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
        eccentricity: f64,
        model_limit: f64,
        collapse_limit: f64,
    },
    /// The ODE integrator stopped (step size underflow, too many steps, stiffness).
    #[error(
        "orbit integration failed at t = {time:.6e} s, crank angle {crank_angle_deg:.2}° (cycle {cycle}): {reason}"
    )]
    Integration {
        time: f64,
        crank_angle_deg: f64,
        cycle: usize,
        reason: String,
    },
    /// A non-finite value appeared in the orbit or its outputs.
    #[error("non-finite {quantity} at t = {time:.6e} s, crank angle {crank_angle_deg:.2}°")]
    NonFinite {
        quantity: &'static str,
        time: f64,
        crank_angle_deg: f64,
    },
    /// A sample of a series handed in for comparison is not finite.
    #[error("non-finite {quantity} at sample {index}: {value}")]
    NonFiniteSample {
        quantity: &'static str,
        index: usize,
        value: f64,
    },
    /// The orbit did not become periodic within the allowed number of cycles.
    #[error(
        "orbit not periodic after {cycles} cycles: max |ε(t) − ε(t − τ)| = {change:.3e} > tolerance {tolerance:.3e}"
    )]
    NotPeriodic {
        cycles: usize,
        change: f64,
        tolerance: f64,
    },
}
