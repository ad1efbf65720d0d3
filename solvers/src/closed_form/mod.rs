//! Closed-form film models of \[Flores2006\] and \[Flores2009\] for a moving journal: the infinitely short and the
//! infinitely long bearing under Sommerfeld's (full film) and Gumbel's (half film) conditions,
//! the short bearing with the moving positive-pressure half film, and the Pinkus–Sternlicht
//! dynamic forces of the long bearing; their static equilibrium under a given load.
//!
//! # Frame and state
//!
//! Bearing frame of docs/conventions.md §1: θ from +x towards +y, journal centre e = c ε (cos γ, sin γ),
//! film h = c − e·n, n = (cos θ, sin θ). The papers measure their angle from the **maximum** film
//! (h = c(1 + ε cos ψ)); here that angle is
//!
//! ```text
//!   ψ = θ − γ − π,      h = c (1 + ε cos ψ),      ψ = 0: h_max,  ψ = π: h_min
//! ```
//!
//! The state of the journal is [`JournalMotion`]: ε, ε̇, γ, γ̇ and the relative surface speed
//! ω = ω_j − ω_b (bearing frame). In the line-of-centres frame the Reynolds equation reads
//! (docs/conventions.md §2 with U = Rω, ∂h/∂t = c ε̇ cos ψ + c ε γ̇ sin ψ):
//!
//! ```text
//!   (1/R²) ∂/∂ψ (h³ ∂p/∂ψ) + ∂/∂z (h³ ∂p/∂z) = 12 μ c [ε̇ cos ψ − ½ (ω − 2γ̇) ε sin ψ]
//! ```
//!
//! so the wedge always enters through ω' = ω − 2γ̇ (\[Flores2009\] eqs. 3–18; \[Flores2006\] eq. 16 with
//! ω̄ = ω/2 and φ̇ = γ̇).
//!
//! # Forces
//!
//! The film force on the journal F = −∫∫ p n R dθ dz has the components (\[Flores2009\] Fig. 2, eq. 19)
//!
//! ```text
//!   F_r = F·ê = R ∫∫ p cos ψ dψ dz     (along the line of centres, bearing → journal)
//!   F_t = F·t̂ = R ∫∫ p sin ψ dψ dz     (t̂ = ê turned 90° counter-clockwise)
//!   F_x = F_r cos γ − F_t sin γ,   F_y = F_r sin γ + F_t cos γ                ([Flores2009] eq. 19)
//! ```
//!
//! # Models ([`ClosedFormModel`])
//!
//! ```text
//!   model                    pressure                           region        forces
//!   ShortSommerfeld          [Flores2009] eq. 3 / [Flores2006] eq. 18    0 … 2π        [Flores2009] eqs. 6–7
//!   ShortGumbel              [Flores2009] eq. 3                      0 … π         [Flores2009] eqs. 8–9
//!   ShortGumbelMovingFilm    [Flores2006] eq. 18                     ψ_i … ψ_i+π   [Flores2006] eqs. 21–22, 36–37
//!   LongSommerfeld           [Flores2009] eq. 5 / [Flores2006] eq. 20    0 … 2π        [Flores2009] eqs. 10–11
//!   LongGumbel               eq. 5 with p(0) = p(π) = 0          0 … π         [Flores2009] eqs. 12–13
//!   PinkusSternlicht         (not given)                         moving π film [Flores2009] eqs. 14–18
//! ```
//!
//! Misprints found by integrating the pressures (tests in [`short`], [`long`]) and how they are
//! corrected here:
//! - \[Flores2009\] eq. 6 prints (1 − ε²)^{3/2}; the integral of eq. 3 over 2π gives (1 − ε²)^{5/2}
//!   (also twice the squeeze part of eq. 8, as it must be for a symmetric squeeze pressure).
//! - \[Flores2009\] eq. 3 omits the factor c in "2 ε̇ cos θ" (dimensions; c ε̇ = ė).
//! - The Gumbel long bearing of eqs. 12–13 is **not** eq. 5 set to zero on π … 2π: eq. 5's
//!   squeeze term is not zero at ψ = π. Eqs. 12–13 are the forces of the long-bearing film on
//!   0 … π with p(0) = p(π) = 0 (Ritz's "hypothesis III", \[Antonic2004\] eq. 3a), whose squeeze part
//!   carries an extra term −8 ε̇ √(1−ε²)/(π(2+ε²)) · ∫₀^ψ dt/(1+ε cos t)³ (see [`long`]).
//! - \[Flores2009\] eq. 15 prints (1 − ε²)^{3/2}, eq. 17 (1 − ε²)^{1/2}; only the latter tends to the
//!   Gumbel force eq. 13 as ε̇ → 0 (k → ∞). Both use ^{1/2} here.
//! - \[Flores2009\] eq. 16 as printed has a prefactor ε̇ (< 0) that flips the sign of the wedge term
//!   4kε²: F_r would jump from −12ε²ω'/((2+ε²)(1−ε²)) to its negative as ε̇ crosses 0. Read with
//!   |ε̇| (as the two cases ε̇ > 0 / ε̇ < 0 suggest) the force is continuous and the squeeze part
//!   opposes the motion in both cases; that reading is used (see [`pinkus_sternlicht`]).
//!
//! [`ClosedFormFilm`] wraps any model as a film of the inverse solver (load history → orbit).
//!
//! Fixed-region Gumbel models (ShortGumbel, LongGumbel) keep the papers' region 0 … π, which is
//! the converging half only for ω' > 0; [`static_equilibrium`] mirrors the problem for ω < 0.

pub mod equilibrium;
pub mod film_model;
pub mod long;
pub mod pinkus_sternlicht;
pub mod quadrature;
pub mod short;

pub use equilibrium::{EquilibriumSolution, static_equilibrium};
pub use film_model::{ClosedFormFilm, ClosedFormState};

use std::f64::consts::{PI, TAU};
use thiserror::Error;

/// Geometry and lubricant of the bearing, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedFormParams {
    /// Journal radius R (m) (\[Flores2009\] uses R_j).
    pub radius: f64,
    /// Bearing length L (m).
    pub length: f64,
    /// Radial clearance c (m).
    pub radial_clearance: f64,
    /// Dynamic viscosity μ (Pa·s).
    pub viscosity: f64,
}

impl ClosedFormParams {
    /// Check that every parameter is finite and positive, and c < R.
    pub fn validate(&self) -> Result<(), ClosedFormError> {
        for (name, value) in [
            ("radius", self.radius),
            ("length", self.length),
            ("radial_clearance", self.radial_clearance),
            ("viscosity", self.viscosity),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ClosedFormError::InvalidParameter { name, value });
            }
        }
        if self.radial_clearance >= self.radius {
            return Err(ClosedFormError::InvalidParameter {
                name: "radial_clearance (must be < radius)",
                value: self.radial_clearance,
            });
        }
        Ok(())
    }

    /// Force scale of the short bearing, μ R L³ / c² (N·s).
    pub fn short_scale(&self) -> f64 {
        let c = self.radial_clearance;
        self.viscosity * self.radius * self.length.powi(3) / (c * c)
    }

    /// Force scale of the long bearing, μ L R³ / c² (N·s).
    pub fn long_scale(&self) -> f64 {
        let c = self.radial_clearance;
        self.viscosity * self.length * self.radius.powi(3) / (c * c)
    }
}

/// The journal's position and velocity in the bearing frame (\[Flores2009\] §5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalMotion {
    /// Eccentricity ratio ε = e/c, 0 ≤ ε < 1.
    pub eccentricity_ratio: f64,
    /// ε̇ (1/s).
    pub eccentricity_ratio_rate: f64,
    /// γ: angle of the line of centres (bearing centre → journal centre) from +x (rad).
    pub line_of_centres_angle: f64,
    /// γ̇ (rad/s).
    pub line_of_centres_rate: f64,
    /// ω = ω_j − ω_b, the journal's angular speed relative to the bearing (rad/s).
    pub relative_speed: f64,
}

impl JournalMotion {
    /// A journal at rest in the bearing frame (steady operation) at ε, γ.
    pub fn steady(
        eccentricity_ratio: f64,
        line_of_centres_angle: f64,
        relative_speed: f64,
    ) -> Self {
        Self {
            eccentricity_ratio,
            eccentricity_ratio_rate: 0.0,
            line_of_centres_angle,
            line_of_centres_rate: 0.0,
            relative_speed,
        }
    }

    /// From the eccentricity-ratio vector ε = (ε_x, ε_y) and its rate (\[Flores2009\] eqs. 25–32).
    /// At ε = 0 the line of centres is taken along ε̇ (or +x when ε̇ = 0) and γ̇ = 0.
    pub fn from_cartesian(eps: [f64; 2], eps_rate: [f64; 2], relative_speed: f64) -> Self {
        let e = eps[0].hypot(eps[1]);
        if e > 0.0 {
            Self {
                eccentricity_ratio: e,
                eccentricity_ratio_rate: (eps[0] * eps_rate[0] + eps[1] * eps_rate[1]) / e,
                line_of_centres_angle: eps[1].atan2(eps[0]),
                line_of_centres_rate: (eps[0] * eps_rate[1] - eps[1] * eps_rate[0]) / (e * e),
                relative_speed,
            }
        } else {
            let r = eps_rate[0].hypot(eps_rate[1]);
            Self {
                eccentricity_ratio: 0.0,
                eccentricity_ratio_rate: r,
                line_of_centres_angle: if r > 0.0 {
                    eps_rate[1].atan2(eps_rate[0])
                } else {
                    0.0
                },
                line_of_centres_rate: 0.0,
                relative_speed,
            }
        }
    }

    /// ω' = ω − 2γ̇, the effective wedge speed.
    pub fn wedge_speed(&self) -> f64 {
        self.relative_speed - 2.0 * self.line_of_centres_rate
    }

    /// The papers' angle ψ ∈ [0, 2π) from the maximum film for the bearing-frame angle θ.
    pub fn angle_from_max_film(&self, theta: f64) -> f64 {
        (theta - self.line_of_centres_angle - PI).rem_euclid(TAU)
    }

    /// Check the state: finite values, 0 ≤ ε < 1.
    pub fn validate(&self) -> Result<(), ClosedFormError> {
        for (name, value) in [
            ("eccentricity_ratio_rate", self.eccentricity_ratio_rate),
            ("line_of_centres_angle", self.line_of_centres_angle),
            ("line_of_centres_rate", self.line_of_centres_rate),
            ("relative_speed", self.relative_speed),
        ] {
            if !value.is_finite() {
                return Err(ClosedFormError::InvalidParameter { name, value });
            }
        }
        let e = self.eccentricity_ratio;
        if !(e.is_finite() && (0.0..1.0).contains(&e)) {
            return Err(ClosedFormError::EccentricityOutOfRange { value: e });
        }
        Ok(())
    }
}

/// Film force on the journal (N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmForce {
    /// F_r along the line of centres (bearing centre → journal centre).
    pub radial: f64,
    /// F_t perpendicular to it (ê turned 90° counter-clockwise).
    pub tangential: f64,
    /// (F_x, F_y) in the bearing frame (\[Flores2009\] eq. 19).
    pub cartesian: [f64; 2],
}

impl FilmForce {
    fn from_components(radial: f64, tangential: f64, gamma: f64) -> Self {
        let (s, c) = gamma.sin_cos();
        Self {
            radial,
            tangential,
            cartesian: [radial * c - tangential * s, radial * s + tangential * c],
        }
    }
}

/// The closed-form film models (see the module docs for equations and regions).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClosedFormModel {
    /// Infinitely short bearing, full film (Sommerfeld conditions), \[Flores2009\] eqs. 3, 6–7.
    ShortSommerfeld,
    /// Infinitely short bearing, half film on ψ ∈ (0, π) (Gumbel), \[Flores2009\] eqs. 3, 8–9.
    ShortGumbel,
    /// Infinitely short bearing, positive-pressure half film ψ ∈ (ψ_i, ψ_i + π) that moves with
    /// the squeeze velocity, \[Flores2006\] eqs. 18, 36–37.
    ShortGumbelMovingFilm,
    /// Infinitely long bearing, full film (Sommerfeld), \[Flores2009\] eqs. 5, 10–11.
    LongSommerfeld,
    /// Infinitely long bearing, film on ψ ∈ (0, π), p = 0 at both ends (Gumbel), eqs. 12–13.
    LongGumbel,
    /// Pinkus & Sternlicht's long bearing with moving film ends, \[Flores2009\] eqs. 14–18.
    PinkusSternlicht,
}

impl ClosedFormModel {
    /// All models, in the order of \[Flores2009\] Fig. 9 (plus the moving short film).
    pub const ALL: [ClosedFormModel; 6] = [
        ClosedFormModel::LongSommerfeld,
        ClosedFormModel::LongGumbel,
        ClosedFormModel::ShortSommerfeld,
        ClosedFormModel::ShortGumbel,
        ClosedFormModel::ShortGumbelMovingFilm,
        ClosedFormModel::PinkusSternlicht,
    ];

    /// A short name for tables and output groups.
    pub fn name(&self) -> &'static str {
        match self {
            ClosedFormModel::ShortSommerfeld => "short_sommerfeld",
            ClosedFormModel::ShortGumbel => "short_gumbel",
            ClosedFormModel::ShortGumbelMovingFilm => "short_gumbel_moving_film",
            ClosedFormModel::LongSommerfeld => "long_sommerfeld",
            ClosedFormModel::LongGumbel => "long_gumbel",
            ClosedFormModel::PinkusSternlicht => "pinkus_sternlicht",
        }
    }
}

impl std::fmt::Display for ClosedFormModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ClosedFormModel {
    type Err = ClosedFormError;

    /// Parse a model from its [`ClosedFormModel::name`] (for case files and the CLI).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ClosedFormModel::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| ClosedFormError::UnknownModel {
                name: s.to_string(),
            })
    }
}

/// What can go wrong in the closed-form models.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ClosedFormError {
    /// A parameter is not finite or out of its range.
    #[error("invalid parameter {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
    /// ε outside [0, 1).
    #[error("eccentricity ratio {value} outside [0, 1)")]
    EccentricityOutOfRange { value: f64 },
    /// The model has no pressure distribution (only forces are published).
    #[error("model {model} gives forces only, no pressure distribution")]
    NoPressureDistribution { model: &'static str },
    /// A result is not finite.
    #[error("non-finite {quantity} in model {model} at ε = {eccentricity_ratio}")]
    NonFinite {
        quantity: &'static str,
        model: &'static str,
        eccentricity_ratio: f64,
    },
    /// A model name that is not one of [`ClosedFormModel::name`].
    #[error(
        "unknown closed-form model '{name}' (known: long_sommerfeld, long_gumbel, short_sommerfeld, short_gumbel, short_gumbel_moving_film, pinkus_sternlicht)"
    )]
    UnknownModel { name: String },
    /// No load capacity: the film cannot carry a load (ω = 0 in a steady state).
    #[error("no load capacity for a steady journal: relative speed ω = {relative_speed} rad/s")]
    NoLoadCapacity { relative_speed: f64 },
    /// The load needs ε beyond the limit: the film collapses.
    #[error(
        "model {model}: load {load} N needs ε > {limit} (capacity there {capacity} N): film collapse"
    )]
    FilmCollapse {
        model: &'static str,
        load: f64,
        limit: f64,
        capacity: f64,
    },
}

/// The film force of `model` for the journal state `motion`.
///
/// ```
/// use jbearing_solvers::closed_form::{film_force, ClosedFormModel, ClosedFormParams, JournalMotion};
/// use std::f64::consts::PI;
///
/// let params = ClosedFormParams { radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02 };
/// let (eps, omega) = (0.6, 300.0);
/// let steady = JournalMotion::steady(eps, 0.0, omega);
/// // Ocvirk's short bearing (half film): |F| = μUL³/(4c²) ε √(16ε² + π²(1−ε²)) / (1−ε²)², U = Rω.
/// let gumbel = film_force(ClosedFormModel::ShortGumbel, &params, &steady)?;
/// let s = 1.0 - eps * eps;
/// let ocvirk = params.viscosity * params.radius * omega * params.length.powi(3)
///     / (4.0 * 40e-6f64.powi(2)) * eps * (16.0 * eps * eps + PI * PI * s).sqrt() / (s * s);
/// assert!((gumbel.radial.hypot(gumbel.tangential) - ocvirk).abs() < 1e-9 * ocvirk);
/// // The full (Sommerfeld) short film: no radial force, twice the half film's tangential one.
/// let full = film_force(ClosedFormModel::ShortSommerfeld, &params, &steady)?;
/// assert!(full.radial.abs() < 1e-9 * full.tangential.abs());
/// assert!((full.tangential - 2.0 * gumbel.tangential).abs() < 1e-9 * full.tangential.abs());
/// # Ok::<(), jbearing_solvers::closed_form::ClosedFormError>(())
/// ```
pub fn film_force(
    model: ClosedFormModel,
    params: &ClosedFormParams,
    motion: &JournalMotion,
) -> Result<FilmForce, ClosedFormError> {
    params.validate()?;
    motion.validate()?;
    let [fr, ft] = match model {
        ClosedFormModel::ShortSommerfeld => short::full_film_force(params, motion),
        ClosedFormModel::ShortGumbel => short::half_film_force(params, motion),
        ClosedFormModel::ShortGumbelMovingFilm => short::moving_half_film_force(params, motion),
        ClosedFormModel::LongSommerfeld => long::full_film_force(params, motion),
        ClosedFormModel::LongGumbel => long::half_film_force(params, motion),
        ClosedFormModel::PinkusSternlicht => pinkus_sternlicht::film_force(params, motion),
    };
    if !(fr.is_finite() && ft.is_finite()) {
        return Err(ClosedFormError::NonFinite {
            quantity: "film force",
            model: model.name(),
            eccentricity_ratio: motion.eccentricity_ratio,
        });
    }
    Ok(FilmForce::from_components(
        fr,
        ft,
        motion.line_of_centres_angle,
    ))
}

/// Gauge pressure (Pa) of `model` at the bearing-frame angle θ (rad) and axial position z (m,
/// −L/2 … L/2); zero in the cavitated part of the half-film models. The long bearing does not
/// depend on z.
pub fn pressure(
    model: ClosedFormModel,
    params: &ClosedFormParams,
    motion: &JournalMotion,
    theta: f64,
    z: f64,
) -> Result<f64, ClosedFormError> {
    params.validate()?;
    motion.validate()?;
    let psi = motion.angle_from_max_film(theta);
    let p = match model {
        ClosedFormModel::ShortSommerfeld => short::pressure(params, motion, psi, z),
        ClosedFormModel::ShortGumbel => {
            if psi <= PI {
                short::pressure(params, motion, psi, z)
            } else {
                0.0
            }
        }
        ClosedFormModel::ShortGumbelMovingFilm => short::pressure(params, motion, psi, z).max(0.0),
        ClosedFormModel::LongSommerfeld => long::full_film_pressure(params, motion, psi),
        ClosedFormModel::LongGumbel => long::half_film_pressure(params, motion, psi),
        ClosedFormModel::PinkusSternlicht => {
            return Err(ClosedFormError::NoPressureDistribution {
                model: model.name(),
            });
        }
    };
    if !p.is_finite() {
        return Err(ClosedFormError::NonFinite {
            quantity: "pressure",
            model: model.name(),
            eccentricity_ratio: motion.eccentricity_ratio,
        });
    }
    Ok(p)
}

/// ∫₀^ψ dt / (1 + ε cos t)³ for ψ ∈ [0, 2π], exactly, by Sommerfeld's substitution
/// 1 + ε cos t = (1 − ε²)/(1 − ε cos g), tan(g/2) = √((1−ε)/(1+ε)) tan(t/2):
///
/// ```text
///   ∫ dt/(1+ε cos t)³ = (1−ε²)^{−5/2} [ g (1 + ε²/2) − 2ε sin g + ε² sin 2g / 4 ]
/// ```
pub(crate) fn sommerfeld_integral_3(eps: f64, psi: f64) -> f64 {
    let s = 1.0 - eps * eps;
    let half = 0.5 * psi;
    // g continuous and increasing with ψ, g(π) = π, g(2π) = 2π.
    let g = 2.0 * ((1.0 - eps).sqrt() * half.sin()).atan2((1.0 + eps).sqrt() * half.cos());
    let g = if g < 0.0 { g + TAU } else { g };
    let g = if psi >= TAU { TAU } else { g };
    (g * (1.0 + 0.5 * eps * eps) - 2.0 * eps * g.sin() + 0.25 * eps * eps * (2.0 * g).sin())
        / (s * s * s.sqrt())
}

#[cfg(test)]
pub(crate) mod test_support {
    /// Composite Simpson rule on [a, b] with n (even) panels — the independent quadrature of the
    /// tests (no Sommerfeld substitution, no Gauss nodes).
    pub fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let n = n + n % 2;
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for i in 1..n {
            let x = a + i as f64 * h;
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(x);
        }
        s * h / 3.0
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::simpson;
    use super::*;

    #[test]
    fn sommerfeld_integral_matches_simpson() {
        for &eps in &[0.0, 0.2, 0.6, 0.9] {
            for &psi in &[0.3, 1.5, PI, 4.0, TAU] {
                let exact = sommerfeld_integral_3(eps, psi);
                let q = simpson(|t| (1.0 + eps * t.cos()).powi(-3), 0.0, psi, 20_000);
                // Simpson error ~ h⁴ f''''/180: < 1e-10 relative at this resolution for ε ≤ 0.9.
                assert!(
                    (exact - q).abs() < 1e-9 * q,
                    "ε {eps} ψ {psi}: {exact} vs {q}"
                );
            }
        }
    }

    #[test]
    fn cartesian_state_round_trip() {
        let m = JournalMotion::from_cartesian([0.3, -0.4], [0.2, 0.1], 50.0);
        assert!((m.eccentricity_ratio - 0.5).abs() < 1e-15);
        // ε̇ = ε·ε̇/|ε|, γ̇ = (ε × ε̇)/|ε|² ([Flores2009] eqs. 29, 32).
        assert!((m.eccentricity_ratio_rate - (0.06 - 0.04) / 0.5).abs() < 1e-15);
        assert!((m.line_of_centres_rate - (0.3 * 0.1 + 0.4 * 0.2) / 0.25).abs() < 1e-14);
        // h_min lies along ε: ψ = π there.
        let psi = m.angle_from_max_film(m.line_of_centres_angle);
        assert!((psi - PI).abs() < 1e-14);
    }

    #[test]
    fn forces_turn_with_the_line_of_centres_and_mirror_with_the_rotation() {
        let p = ClosedFormParams {
            radius: 0.01,
            length: 0.02,
            radial_clearance: 1e-4,
            viscosity: 0.1,
        };
        let base = JournalMotion {
            eccentricity_ratio: 0.55,
            eccentricity_ratio_rate: -2.0,
            line_of_centres_angle: 0.3,
            line_of_centres_rate: 7.0,
            relative_speed: 40.0,
        };
        for model in ClosedFormModel::ALL {
            let f0 = film_force(model, &p, &base).unwrap();
            let scale = f0.radial.hypot(f0.tangential);
            // Rotation invariance: turning γ by α turns (F_x, F_y) by α, (F_r, F_t) unchanged.
            let a = 1.9;
            let turned = JournalMotion {
                line_of_centres_angle: base.line_of_centres_angle + a,
                ..base
            };
            let f1 = film_force(model, &p, &turned).unwrap();
            let (s, c) = a.sin_cos();
            let want = [
                c * f0.cartesian[0] - s * f0.cartesian[1],
                s * f0.cartesian[0] + c * f0.cartesian[1],
            ];
            for (got, want) in f1.cartesian.iter().zip(want) {
                assert!((got - want).abs() < 1e-12 * scale, "{model:?}");
            }
            // Mirror y → −y (γ, γ̇, ω change sign): F_r stays, F_t changes sign — for the
            // models whose film region follows the motion (not the fixed 0 … π Gumbel films).
            if matches!(
                model,
                ClosedFormModel::ShortGumbel | ClosedFormModel::LongGumbel
            ) {
                continue;
            }
            let mirrored = JournalMotion {
                line_of_centres_angle: -base.line_of_centres_angle,
                line_of_centres_rate: -base.line_of_centres_rate,
                relative_speed: -base.relative_speed,
                ..base
            };
            let f2 = film_force(model, &p, &mirrored).unwrap();
            assert!((f2.radial - f0.radial).abs() < 1e-12 * scale, "{model:?}");
            assert!(
                (f2.tangential + f0.tangential).abs() < 1e-12 * scale,
                "{model:?}"
            );
            assert!((f2.cartesian[0] - f0.cartesian[0]).abs() < 1e-12 * scale);
            assert!((f2.cartesian[1] + f0.cartesian[1]).abs() < 1e-12 * scale);
        }
    }

    #[test]
    fn model_names_round_trip() {
        for m in ClosedFormModel::ALL {
            assert_eq!(m.to_string().parse::<ClosedFormModel>().unwrap(), m);
        }
        assert!(matches!(
            "ocvirk".parse::<ClosedFormModel>(),
            Err(ClosedFormError::UnknownModel { .. })
        ));
    }

    #[test]
    fn bad_inputs_are_errors() {
        let p = ClosedFormParams {
            radius: 0.01,
            length: 0.02,
            radial_clearance: 1e-4,
            viscosity: 0.1,
        };
        let m = JournalMotion::steady(1.0, 0.0, 10.0);
        assert!(matches!(
            film_force(ClosedFormModel::ShortGumbel, &p, &m),
            Err(ClosedFormError::EccentricityOutOfRange { .. })
        ));
        let m = JournalMotion::steady(0.5, 0.0, f64::NAN);
        assert!(film_force(ClosedFormModel::LongGumbel, &p, &m).is_err());
        let bad = ClosedFormParams {
            viscosity: -1.0,
            ..p
        };
        let m = JournalMotion::steady(0.5, 0.0, 1.0);
        assert!(film_force(ClosedFormModel::LongGumbel, &bad, &m).is_err());
        assert!(matches!(
            pressure(ClosedFormModel::PinkusSternlicht, &p, &m, 0.0, 0.0),
            Err(ClosedFormError::NoPressureDistribution { .. })
        ));
    }
}
