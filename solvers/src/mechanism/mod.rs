//! Planar slider-crank with a lubricated revolute joint (\[Flores2009\] §§3–8):
//! the forward problem — the crank is driven at constant speed, the journal of the rod–slider
//! joint moves in its clearance under the film (and, when the film breaks down, the contact)
//! force, and the joint forces, the driving moment, the journal orbit and h_min come out.
//!
//! # The mechanism (\[Flores2009\] Fig. 12, Table 2)
//!
//! ```text
//!            A (ideal pin, crank ↔ rod)
//!           ╱ ╲
//!   crank 2╱   ╲ rod 3
//!         ╱     ╲            B: lubricated joint — journal on the rod, bearing in the slider
//!   O ───●       ◎══[ slider 4 ]══   x (ideal translational joint along x through O)
//!   ground pivot (ideal), θ = ω t + θ₀ (driving constraint)
//! ```
//!
//! Journal centre on the rod B_j = A + L₃ u, u = (cos φ₃, sin φ₃); bearing centre in the slider
//! B_b = (x₄, 0). The slider does not rotate, so the bearing frame is the fixed frame and the
//! journal's speed relative to the bearing is ω = φ̇₃ (the journal could as well be the pin in the
//! slider: the closed forms depend on ω − 2γ̇ only, \[Flores2009\] eqs. 3–18, which is the same either
//! way). Eccentricity (\[Flores2009\] eqs. 21–32): e = B_j − B_b, ε = e/c.
//!
//! # Formulation: minimal coordinates instead of Cartesian coordinates with Baumgarte
//!
//! \[Flores2009\] §6 writes each body in Cartesian coordinates, keeps the ideal joints as algebraic
//! constraints with Lagrange multipliers (eq. 39) and stabilises their drift with Baumgarte's
//! feedback (eq. 41, with constants α, β to be tuned). With a driven crank, two ideal pins, a
//! translational joint and one clearance joint the mechanism has exactly two degrees of freedom
//! — the two components of the journal eccentricity — so we integrate those, e = (e_x, e_y),
//! directly. The ideal joints then hold *exactly* at every instant (no drift, no α/β to tune,
//! no index-3 DAE), the integrator sees the variables whose accuracy matters (e is 10⁻³ of the
//! mechanism's size; a Cartesian integration would have to resolve it as the difference of two
//! large coordinates), and the state is the one the film models take (ε, ε̇). (The paper's
//! formulation — 9 Cartesian coordinates, 7 constraints, eq. 41 — integrated independently in
//! `validation/tests/slider_crank_flores2009.rs` gives the same orbit to 1e-11 m.) The
//! mechanism's coordinates follow from e and t:
//!
//! ```text
//!   A(t) = r (cos θ, sin θ),  θ = θ₀ + ω t
//!   sin φ₃ = (e_y − A_y)/L₃,  cos φ₃ = +√(1 − sin² φ₃),  x₄ = A_x + L₃ cos φ₃ − e_x
//!   φ̇₃ = (ė_y − Ȧ_y)/(L₃ cos φ₃),  ẋ₄ = Ȧ_x − L₃ sin φ₃ φ̇₃ − ė_x
//! ```
//!
//! # Equations of motion
//!
//! With F the joint force on the rod (journal) at B_j — the slider (bearing) gets −F — and the
//! rod's centre of mass at d₃ from A (J_A = J₃ + m₃ d₃²; a × b = a_x b_y − a_y b_x), and T the
//! joint's moment on the rod about B_j (film friction torque and contact friction, both off by
//! default; the slider's guide takes −T):
//!
//! ```text
//!   (M1)  J_A φ̈₃ = L₃ u × F + T + m₃ d₃ u × (g − Ä)      rod, moments about the moving pin A
//!   (M2)  m₄ ẍ₄  = −F_x + m₄ g_x                          slider along the guide
//!   ë_x = Ä_x − L₃ (sin φ₃ φ̈₃ + cos φ₃ φ̇₃²) − ẍ₄,   ë_y = Ä_y + L₃ (cos φ₃ φ̈₃ − sin φ₃ φ̇₃²)
//! ```
//!
//! (the generalized forces of F are (∂e/∂q)ᵀ F, the transport of \[Flores2009\] eqs. 33–34). The
//! reactions follow from Newton–Euler on each body:
//!
//! ```text
//!   (R1)  F_A = m₃ a_G3 − F − m₃ g                   crank pin, force on the rod
//!   (R2)  F_O = m₂ a_G2 + F_A − m₂ g                 ground pivot, force on the crank
//!   (R3)  N   = F_y − m₄ g_y                         guide, normal force on the slider
//!   (R4)  M   = r_A × F_A − r_G2 × m₂ g              driving moment (θ̈ = 0)
//! ```
//!
//! With ideal joints (e ≡ 0) the mechanism has no degree of freedom: φ₃, x₄ and their rates are
//! the closed-form kinematics and F follows from (M1)–(M2) solved for F (inverse dynamics):
//!
//! ```text
//!   (I1)  F_x = m₄ (g_x − ẍ₄),   u × F = [J_A φ̈₃ − m₃ d₃ u × (g − Ä)] / L₃
//! ```
//!
//! # Joint force
//!
//! - film: any closed form of [`crate::closed_form`] (default Pinkus–Sternlicht, the model of
//!   \[Flores2009\] §8; eqs. 6–19) with ω = φ̇₃, or the mass-conserving Reynolds film
//!   [`crate::reynolds`] through [`crate::inverse::ReynoldsFilm`];
//! - dry contact and the transition: [`contact`] (Lankarani–Nikravesh, \[Flores2009\] eq. 20).
//!
//! Left out by default, as in \[Flores2009\] (eqs. 33–34 transport the film force only; its
//! contact law has no friction), and available as switches: the film's friction torque on the
//! journal ([`LubricatedJointParams::film_torque`]; closed forms: −2πμR³Lφ̇₃/(c√(1−ε²)) − ½ (e × F)
//! of [`crate::closed_form::ClosedFormFilm`], ≈ 0.1 N m for Table 3 against a driving moment of
//! 139 N m; the Reynolds film: its own shear torque), and Coulomb friction in the dry contact
//! ([`ContactParams::friction_coefficient`], [`contact`]).
//!
//! # Integration
//!
//! The film makes the equations stiff: its damping ∂F/∂ė ≈ 12π μ L R³/c³ (1−ε²)^{−3/2} is
//! 7·10⁴ N s/m at ε = 0 for Table 3 and grows without bound towards the wall, against a
//! mass of 0.07–0.14 kg: time constants of 10⁻⁶ s and below, against a crank period of 12 ms.
//! An explicit method would be held to steps of ~10⁻⁷ s by stability alone. So:
//!
//! - closed-form film: [`Integrator::Radau5`] — the 3-stage Radau IIA of the
//!   `differential-equations` crate (order 5, L-stable and stiffly accurate, adaptive steps with
//!   error control, dense output for the samples), on y = (ε, ε̇); its Newton uses a
//!   finite-difference Jacobian (four extra right-hand sides of a closed form: cheap). Contact
//!   onsets and releases are events of the integrator (onset: h_min falls to h_b; release: h_min
//!   rises above h_b + e₀/10, a small hysteresis so that a journal grazing the boundary layer
//!   does not stop the integrator at every crossing): the run stops there, the impact velocity
//!   δ̇⁻ of the Lankarani–Nikravesh law is taken and the integration restarts — the law has a
//!   memory that a right-hand side cannot carry. (The crate's event detection does not look
//!   inside the first step of a run: every run starts with a step of 10⁻⁸ of a turn, so a
//!   crossing there would need the journal to cover e₀/10 in 10⁻¹⁰ s.)
//! - Reynolds film (or any film for a cross-check): [`Integrator::Bdf2`] — by default steps
//!   under error control (`error_tolerance`) of at most one turn / `steps_per_turn` (1°) ending
//!   on that grid, or (`error_tolerance` None) fixed steps of that length; the
//!   journal's (ε, ε̇, ε̈) by the same BDF2 difference formulas the Reynolds film uses for its
//!   squeeze term ([`crate::reynolds::TimeScheme::Bdf2`], backward-Euler start), and per step a
//!   Newton iteration on ε^{n+1} of
//!
//!   ```text
//!     r(ε^{n+1}) = ε̈_BDF2(ε^{n+1}) − ë(t^{n+1}, ε^{n+1}, ε̇_BDF2(ε^{n+1}), F(ε^{n+1})) / c = 0
//!     J = (a₀/Δt)² I − ∂g/∂ε − (a₀/Δt) ∂g/∂ε̇ − ∂g/∂F · (1 − s) ∂F_film/∂ε
//!   ```
//!
//!   each iterate one film step from the film state at t^n to the trial ε^{n+1} (as in the
//!   inverse solver, [`crate::inverse`]); ∂F_film/∂ε is the film's own exact Jacobian
//!   ([`crate::inverse::FilmModel::force_jacobian`]: two extra linear solves on the converged
//!   switch field), the mechanism's parts by differences of the (analytic) mechanism equations.
//!   The Jacobian is kept while the Newton updates contract at least 3× (chord steps) and taken
//!   afresh otherwise; an iterate is accepted when the update it asks for is below the
//!   tolerance (so the film state kept is the one solved at the accepted ε).
//!   The accepted iterate's film state becomes the film at t^{n+1}. Implicit in the stiff film
//!   force, A-stable, second order. Newton updates are limited to 0.05 in ε and halved until
//!   the residual falls; a step whose Newton still fails (hard dry contact: the Hertz law with
//!   its hysteresis is stiff and kinked, an impact lasts ~0.1 ms ≈ 3° at 5000 rpm) is split
//!   in two, recursively up to 2⁶ parts, with the variable-step BDF2 coefficients — the
//!   Reynolds film's own variable-step BDF2 follows the same steps. In dry contact (s = 1) the film is still stepped (its state
//!   must follow) at the eccentricity clamped to the end of the blend band.
//!
//!   Error control (`error_tolerance`, default [`DEFAULT_BDF2_ERROR_TOLERANCE`], the default
//!   integrator of the Reynolds film): BDF2 has the local error −(2/9) h³ ε‴ (constant steps);
//!   the predictor through ε^{n−1}, ε^n with the slope ε̇^n has h²(h + h_p) ε‴/6, so Milne's
//!   device gives LTE ≈ 0.4 |ε_c − ε_p| (h = h_p). A step is accepted when LTE ≤ tol; the next
//!   is h · 0.9 (tol / LTE)^{1/3}, between 0.2 h and 2 h (BDF2's variable-step formulas stay
//!   zero-stable below a ratio of 1 + √2), never past the next grid point, so that samples
//!   and film snapshots fall on step ends; a rejected step or a failed Newton is retried
//!   shorter (the film state is that of t^n until a step is accepted: each trial steps the
//!   film from it). The estimate is on the position ε only. An estimate on ε̇ as well (tried:
//!   the ε̇ error per radian of crank beside the ε error) made the Reynolds film take ~2900
//!   steps per turn with a third of them rejected (40 × 11 grid, c = 0.2 mm, 400 cP; ~430
//!   with the Pinkus–Sternlicht film), and did not finish two turns at 120 × 31 in 2.5 CPU
//!   minutes (tolerance 1e-4): the discrete film's force is continuous in ε but its slope jumps whenever a grid
//!   node switches between full and cavitated film, so ε̈ has a kink and the ε̇ estimate (a
//!   difference of ε̈) a spike at every switch — erratic estimates of 1e-5 … 1e-3 on
//!   successive steps of 0.05°, more steps on finer grids (20 × 5: 2083, 80 × 21: 2935 per
//!   turn). The position is one integration further from those kinks: with the estimate on ε
//!   the same run takes 477 steps per turn (15 rejected) at 1e-4, 798 (86) at the default
//!   1e-5, and at 120 × 31 679 (46) at 1e-5. The Newton tolerance is tightened on short steps to 1 % of tol · min(1, h|ω|):
//!   its error enters ε̇ as a₀ δε / h. Without error control an impact's peak force depends on
//!   where the step grid falls (c = 0.5 mm, 40 cP: 9.8, 11.4, 11.2, 10.6 kN at 360 … 2880 steps
//!   per turn); with it the peak converges as the tolerance falls (validation tests
//!   `bdf2_error_control_makes_the_impact_peak_converge`,
//!   `reynolds_film_under_error_control_converges`).
//!
//! # Results
//!
//! [`MechanismSolution`]: time series of the bodies, the joint forces, the driving moment, the
//! journal orbit, h_min and the blend weight, and the contact events; [`MechanismInfo`]: step
//! counts, extremes and the periodicity change between the last two turns. The run starts at
//! t = 0 with the journal in the bearing centre and the bodies moving as in the ideal mechanism
//! (\[Flores2009\] §7: "initially, the journal and bearing centres coincide").

pub mod contact;
mod slider_crank;
mod solve;

pub use contact::ContactParams;
pub use slider_crank::{BodyState, JointLoads, Link, SliderCrankParams};
pub use solve::solve_mechanism;

use crate::closed_form::{ClosedFormModel, ClosedFormParams};
use crate::reynolds::ReynoldsParams;
use thiserror::Error;

/// The film of a lubricated joint.
#[derive(Debug, Clone, PartialEq)]
pub enum JointFilm {
    /// A closed-form film ([`crate::closed_form::film_force`]).
    ClosedForm(ClosedFormModel),
    /// The mass-conserving Reynolds film; radius, length, clearance and viscosity must be the
    /// joint's (make it with [`LubricatedJointParams::reynolds_params`]).
    Reynolds(Box<ReynoldsParams>),
}

/// A lubricated revolute joint (\[Flores2009\] Table 3).
#[derive(Debug, Clone, PartialEq)]
pub struct LubricatedJointParams {
    /// Bearing radius R_b (m).
    pub bearing_radius: f64,
    /// Journal radius R_j (m); the radial clearance is c = R_b − R_j.
    pub journal_radius: f64,
    /// Bearing length L (m).
    pub length: f64,
    /// Dynamic viscosity μ (Pa s).
    pub viscosity: f64,
    /// The film model.
    pub film: JointFilm,
    /// Dry contact and the transition to it.
    pub contact: ContactParams,
    /// Put the film's friction torque on the journal ([`crate::inverse::FilmResponse::
    /// friction_torque_journal`]: Couette and pressure-flow shear) into the rod's moment
    /// equation. Default false, as \[Flores2009\] (its eqs. 33–34 transport the film force only).
    pub film_torque: bool,
}

impl LubricatedJointParams {
    /// \[Flores2009\] Table 3: R_b 10.0 mm, R_j 9.8 mm (c 0.2 mm), L 40 mm, μ 400 cP, with the
    /// Pinkus–Sternlicht film of §8 and the default contact settings.
    pub fn flores2009() -> Self {
        Self::with_clearance(0.2e-3, 0.4)
    }

    /// The Table 3 joint with another clearance and viscosity (the study of \[Flores2009\] Figs.
    /// 16–21): the bearing radius stays 10.0 mm, the journal radius is 10.0 mm − c (assumed:
    /// the paper does not say which radius it changed).
    pub fn with_clearance(radial_clearance: f64, viscosity: f64) -> Self {
        Self {
            bearing_radius: 10.0e-3,
            journal_radius: 10.0e-3 - radial_clearance,
            length: 40.0e-3,
            viscosity,
            film: JointFilm::ClosedForm(ClosedFormModel::PinkusSternlicht),
            contact: ContactParams::default(),
            film_torque: false,
        }
    }

    /// Radial clearance c = R_b − R_j (m).
    pub fn radial_clearance(&self) -> f64 {
        self.bearing_radius - self.journal_radius
    }

    /// The closed-form parameters of the joint (R = R_j, as \[Flores2009\] eqs. 6–17).
    pub fn closed_form_params(&self) -> ClosedFormParams {
        ClosedFormParams {
            radius: self.journal_radius,
            length: self.length,
            radial_clearance: self.radial_clearance(),
            viscosity: self.viscosity,
        }
    }

    /// A Reynolds film for this joint, with the film's defaults (120 × 31 grid, BDF2, β = 1.5
    /// GPa) and, since the joint has no groove, a flooded joint: the ends at ambient pressure
    /// (gauge 0) and the cavitation pressure at absolute vacuum (−101 325 Pa gauge), so oil enters
    /// from the ends where the film needs it (a gudgeon pin in the crankcase oil mist). The
    /// closed forms instead assume a film always full where they need it.
    pub fn reynolds_params(&self) -> ReynoldsParams {
        let mut p = ReynoldsParams::plain(
            self.journal_radius,
            self.length,
            self.radial_clearance(),
            self.viscosity,
        );
        p.cavitation_pressure = -101_325.0;
        p.ambient_pressure = 0.0;
        p
    }

    /// Check the geometry, viscosity, contact settings and (Reynolds) the film's geometry.
    pub fn validate(&self) -> Result<(), MechanismError> {
        let bad = |name: &'static str, value: f64| MechanismError::InvalidParameter { name, value };
        for (name, v) in [
            ("joint.bearing_radius", self.bearing_radius),
            ("joint.journal_radius", self.journal_radius),
            ("joint.length", self.length),
            ("joint.viscosity", self.viscosity),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(name, v));
            }
        }
        let c = self.radial_clearance();
        if c.is_nan() || c <= 0.0 {
            return Err(bad("joint radial clearance R_b − R_j", c));
        }
        self.contact.validate(c)?;
        if let JointFilm::Reynolds(p) = &self.film {
            for (name, film, joint) in [
                (
                    "Reynolds film radius (must equal R_j)",
                    p.radius,
                    self.journal_radius,
                ),
                ("Reynolds film length", p.length, self.length),
                ("Reynolds film clearance", p.clearance, c),
                ("Reynolds film viscosity", p.viscosity, self.viscosity),
            ] {
                if (film - joint).abs() > 1e-12 * joint {
                    return Err(bad(name, film));
                }
            }
        }
        Ok(())
    }
}

/// The rod–slider joint.
#[derive(Debug, Clone, PartialEq)]
pub enum RodSliderJoint {
    /// Ideal revolute joint (no clearance): closed-form kinematics and inverse dynamics.
    Ideal,
    /// Lubricated revolute joint with clearance.
    Lubricated(LubricatedJointParams),
}

/// Time integration of the lubricated mechanism (module docs, "Integration").
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Adaptive Radau IIA (order 5) of the `differential-equations` crate; closed-form films
    /// only.
    Radau5 {
        /// Relative tolerance.
        relative_tolerance: f64,
        /// Absolute tolerance on ε (dimensionless); on ε̇ it is this times the crank speed.
        absolute_tolerance: f64,
    },
    /// BDF2 with Newton on ε^{n+1} per step; any film. Fixed steps of one turn /
    /// `steps_per_turn`, or, with `error_tolerance`, steps chosen by a local error estimate
    /// with that grid as the ceiling (module docs, "Integration").
    Bdf2 {
        /// Time steps per crank turn (a multiple of `samples_per_turn`); with
        /// `error_tolerance`, the longest step (each grid point is a step end).
        steps_per_turn: usize,
        /// Local error tolerance (absolute, in ε; on ε̇ it is this times the crank speed);
        /// None: fixed steps.
        error_tolerance: Option<f64>,
        /// Newton converged when |Δε| ≤ this.
        newton_tolerance: f64,
        /// Newton iterations per step at most.
        max_newton_iterations: usize,
    },
}

impl Integrator {
    /// Radau5 with rtol = 1e-8, atol(ε) = 1e-9 (h to 2·10⁻¹³ m at c = 0.2 mm).
    pub const fn radau5_default() -> Self {
        Integrator::Radau5 {
            relative_tolerance: 1e-8,
            absolute_tolerance: 1e-9,
        }
    }

    /// BDF2 with fixed steps, 360 per turn (1°), |Δε| ≤ 1e-7, at most 30 Newton iterations. On
    /// the paper's case (\[Flores2009\] §8) with the Pinkus–Sternlicht film the orbit is then
    /// within 0.04 µm and the joint force within 0.3 N of Radau5's (second-order convergence:
    /// 0.01 µm at 720 steps); |Δε| ≤ 1e-7 is 0.02 nm at c = 0.2 mm, far below that. Impact
    /// peaks depend on where the step grid falls: the default is [`Integrator::bdf2_controlled`].
    pub const fn bdf2_fixed() -> Self {
        Integrator::Bdf2 {
            steps_per_turn: 360,
            error_tolerance: None,
            newton_tolerance: 1e-7,
            max_newton_iterations: 30,
        }
    }

    /// BDF2 with error control, the default of the Reynolds film: local error ≤
    /// [`DEFAULT_BDF2_ERROR_TOLERANCE`] in ε, steps of at most 1° (360 per turn), Newton as
    /// [`Integrator::bdf2_fixed`].
    pub const fn bdf2_controlled() -> Self {
        Integrator::Bdf2 {
            steps_per_turn: 360,
            error_tolerance: Some(DEFAULT_BDF2_ERROR_TOLERANCE),
            newton_tolerance: 1e-7,
            max_newton_iterations: 30,
        }
    }
}

/// Local error tolerance of [`Integrator::bdf2_controlled`] (absolute, in ε; validation tests
/// `bdf2_error_control_makes_the_impact_peak_converge` and
/// `reynolds_film_under_error_control_converges` measure what it buys).
pub const DEFAULT_BDF2_ERROR_TOLERANCE: f64 = 1e-5;

/// Film field snapshots per run of a Reynolds film by default (every 15° of the last turn).
pub const DEFAULT_FIELD_SNAPSHOTS: usize = 24;

/// Everything a mechanism run needs.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismParams {
    /// Bodies, masses, crank speed, gravity.
    pub mechanism: SliderCrankParams,
    /// The rod–slider joint.
    pub joint: RodSliderJoint,
    /// Crank turns to simulate from t = 0 (\[Flores2009\]: two).
    pub turns: usize,
    /// Output samples per turn (both ends of the run included).
    pub samples_per_turn: usize,
    /// Time integration (ignored for the ideal joint).
    pub integrator: Integrator,
    /// Film field snapshots over the last turn ([`MechanismSolution::film_fields`]): this many
    /// instants, evenly spaced in time and ending at the end of the run (each on the nearest
    /// time step). Reynolds film only (ignored for closed forms and the ideal joint); 0: none.
    /// At most the BDF2 `steps_per_turn`.
    pub field_snapshots: usize,
}

impl MechanismParams {
    /// Two turns, 360 samples per turn, and the integrator that suits the joint: Radau5 for a
    /// closed-form film, BDF2 under error control (steps of at most 1°) for the Reynolds film.
    pub fn new(mechanism: SliderCrankParams, joint: RodSliderJoint) -> Self {
        let (integrator, field_snapshots) = match &joint {
            RodSliderJoint::Lubricated(LubricatedJointParams {
                film: JointFilm::Reynolds(_),
                ..
            }) => (Integrator::bdf2_controlled(), DEFAULT_FIELD_SNAPSHOTS),
            _ => (Integrator::radau5_default(), 0),
        };
        Self {
            mechanism,
            joint,
            turns: 2,
            samples_per_turn: 360,
            integrator,
            field_snapshots,
        }
    }

    /// \[Flores2009\] §8: Table 2 mechanism, Table 3 joint with the Pinkus–Sternlicht film.
    pub fn flores2009() -> Self {
        Self::new(
            SliderCrankParams::flores2009(),
            RodSliderJoint::Lubricated(LubricatedJointParams::flores2009()),
        )
    }
}

/// Contact onset or release.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactEventKind {
    /// h_min fell to the boundary layer h_b: dry contact starts (blend weight leaves 0).
    Onset,
    /// h_min rose above h_b + e₀/10 again: the film carries alone.
    Release,
}

/// One contact event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// Time (s).
    pub time: f64,
    /// Crank angle (deg, from the start of the run, not wrapped).
    pub crank_angle_deg: f64,
    /// Onset or release.
    pub kind: ContactEventKind,
    /// Radial velocity of the journal towards the wall, ė·ê (m/s): the impact velocity δ̇⁻ at
    /// an onset (before the floor `min_impact_speed`).
    pub radial_velocity: f64,
}

/// Counters and extremes of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MechanismInfo {
    /// Accepted time steps, split steps counted in their parts (0 for the ideal joint).
    pub steps: usize,
    /// Rejected steps (Radau5; BDF2 under error control: steps retried shorter) — 0 for
    /// fixed-step BDF2.
    pub rejected_steps: usize,
    /// Right-hand-side evaluations (Radau5) or residual evaluations of the BDF2 Newton (for
    /// the Reynolds film each is one film step, see `film_steps`).
    pub evaluations: usize,
    /// Reynolds film steps (including the Newton iterates), 0 for closed forms.
    pub film_steps: usize,
    /// Smallest h_min over the samples of the run (m) and the crank angle (deg) where it
    /// occurs; None for the ideal joint (no clearance).
    pub min_film_thickness: Option<f64>,
    pub min_film_crank_angle_deg: Option<f64>,
    /// Largest |F| of the rod–slider joint (N).
    pub max_joint_force: f64,
    /// Largest |M| of the driving moment (N m).
    pub max_crank_moment: f64,
    /// Largest |ε| over the run.
    pub max_eccentricity_ratio: f64,
    /// max over the last turn of |e(t) − e(t − T)| / c (0 … 2); None with fewer than two turns
    /// or for the ideal joint.
    pub periodicity_change: Option<f64>,
}

/// The time series of a run, sampled at `samples_per_turn` points per turn.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MechanismSolution {
    /// Time (s), from 0.
    pub time: Vec<f64>,
    /// Crank angle (deg, not wrapped).
    pub crank_angle_deg: Vec<f64>,
    /// Crank, rod, slider.
    pub bodies: Vec<[BodyState; 3]>,
    /// Joint forces and the driving moment.
    pub loads: Vec<JointLoads>,
    /// Journal centre relative to the bearing centre e (m, fixed = bearing frame): the orbit.
    pub eccentricity: Vec<[f64; 2]>,
    /// ė (m/s).
    pub eccentricity_rate: Vec<[f64; 2]>,
    /// h_min = c − |e| (m); c − |e| may be negative in dry contact (penetration). Empty for
    /// the ideal joint.
    pub min_film_thickness: Vec<f64>,
    /// Blend weight s of the dry contact force (0: film only, 1: contact only). Empty for the
    /// ideal joint.
    pub contact_weight: Vec<f64>,
    /// Contact onsets and releases, in time order.
    pub contact_events: Vec<ContactEvent>,
    /// Counters and extremes.
    pub info: MechanismInfo,
    /// Fields of the Reynolds film at [`MechanismParams::field_snapshots`] instants of the last
    /// turn; None for closed-form films, the ideal joint and `field_snapshots = 0`.
    pub film_fields: Option<MechanismFilmFields>,
}

/// Snapshots of the Reynolds film of the joint: the fields of the accepted film step at each
/// instant (in dry contact the film's ε is clamped to the end of the blend band).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MechanismFilmFields {
    /// Time of each instant (s, from the start of the run).
    pub time: Vec<f64>,
    /// Crank angle of each instant (deg, not wrapped).
    pub crank_angle_deg: Vec<f64>,
    /// θ of the grid columns (rad, bearing frame, from +x).
    pub theta: Vec<f64>,
    /// z of the grid rows (m, from the mid-plane; the end rows are the bearing ends).
    pub z: Vec<f64>,
    /// The fields of each instant, indexed [i_θ, i_z].
    pub fields: Vec<crate::inverse::FilmFields>,
}

/// What can go wrong in a mechanism run.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MechanismError {
    /// A parameter is not finite or out of range.
    #[error("invalid parameter {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
    /// A combination that is not supported.
    #[error("unsupported: {what}")]
    Unsupported { what: &'static str },
    /// A non-finite value appeared.
    #[error("non-finite {quantity} at t = {time} s")]
    NonFinite { quantity: &'static str, time: f64 },
    /// The film model failed.
    #[error(
        "film failed at t = {time} s (crank {crank_angle_deg:.2}°, ε = {eccentricity_ratio}): {reason}"
    )]
    Film {
        time: f64,
        crank_angle_deg: f64,
        eccentricity_ratio: f64,
        reason: String,
    },
    /// The adaptive integrator failed.
    #[error("integration failed at t = {time} s (crank {crank_angle_deg:.2}°): {reason}")]
    Integration {
        time: f64,
        crank_angle_deg: f64,
        reason: String,
    },
    /// A BDF2 step's Newton iteration did not converge.
    #[error(
        "Newton did not converge at t = {time} s (crank {crank_angle_deg:.2}°): |Δε| = {update} after {iterations} iterations"
    )]
    NewtonFailed {
        time: f64,
        crank_angle_deg: f64,
        update: f64,
        iterations: usize,
    },
}
