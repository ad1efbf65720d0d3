//! Mechanism case files: the slider-crank of \[Flores2009\] with its rod–slider
//! joint ideal or lubricated, in TOML. A file is a mechanism case when it has a `[mechanism]`
//! table ([`is_mechanism_text`]); every other file is a bearing case ([`super::Case`]).
//!
//! ```text
//!   case.toml ──toml+serde (deny_unknown_fields)──► MechanismCaseFile (as written, units in keys)
//!            ──resolve (units, defaults, checks)──► MechanismCase (MechanismParams, SI)
//! ```
//!
//! Every key is documented in `cases/README.md` ("Mechanism cases"). Errors name the file, the
//! key and the line, as for bearing cases ([`CaseError`]).

use std::path::{Path, PathBuf};

use jbearing_solvers::closed_form::{ClosedFormError, ClosedFormModel};
use jbearing_solvers::mechanism::{
    ContactParams, Integrator, JointFilm, Link, LubricatedJointParams, MechanismParams,
    RodSliderJoint, SliderCrankParams,
};
use serde::Deserialize;

use super::units::{deg_to_rad, rpm_to_rad_s};
use super::{CaseError, Ctx};

/// Name of the table that makes a file a mechanism case.
pub const MECHANISM_TABLE: &str = "mechanism";

/// Whether the TOML `text` is a mechanism case: it parses and has a `[mechanism]` table. Text
/// that does not parse is read as a bearing case (whose reader reports the syntax error).
pub fn is_mechanism_text(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key(MECHANISM_TABLE))
}

/// Whether the file at `path` is a mechanism case ([`is_mechanism_text`]; false when it cannot
/// be read).
pub fn is_mechanism_file(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| is_mechanism_text(&t))
}

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MechanismCaseFile {
    /// Format version; this program reads 1.
    pub version: i64,
    /// Case name (default: the file's stem).
    pub name: Option<String>,
    /// One line of description.
    pub description: Option<String>,
    /// The mechanism.
    pub mechanism: MechanismSection,
    /// A parameter sweep (expanded by `batch`; refused by `run`).
    pub sweep: Option<toml::Table>,
}

/// `[mechanism]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MechanismSection {
    /// Constant crank speed (rpm, counter-clockwise positive).
    pub crank_speed_rpm: f64,
    /// Crank angle at t = 0 (deg from +x).
    #[serde(default)]
    pub initial_crank_angle_deg: f64,
    /// Gravity (m/s², fixed frame, y up).
    #[serde(default = "default_gravity")]
    pub gravity_m_s2: [f64; 2],
    /// Crank turns from t = 0.
    #[serde(default = "default_turns")]
    pub turns: usize,
    /// Output samples per turn.
    #[serde(default = "default_samples_per_turn")]
    pub samples_per_turn: usize,
    /// Write the PNG plots.
    #[serde(default = "default_true")]
    pub plots: bool,
    /// Film field snapshots over the last turn (Reynolds film; default 24, 0: none).
    pub field_snapshots: Option<usize>,
    /// Run the ideal mechanism too, as the reference of the lubricated one.
    #[serde(default = "default_true")]
    pub ideal_reference: bool,
    /// Crank (body 2).
    pub crank: LinkSection,
    /// Connecting rod (body 3).
    pub rod: LinkSection,
    /// Slider (body 4).
    pub slider: SliderSection,
    /// The rod–slider joint.
    pub joint: JointSection,
    /// Dry contact and the transition to it (lubricated joint).
    pub contact: Option<ContactSection>,
    /// Time integration (lubricated joint).
    pub integrator: Option<IntegratorSection>,
}

/// `[mechanism.crank]`, `[mechanism.rod]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkSection {
    pub length_m: f64,
    pub mass_kg: f64,
    pub inertia_kg_m2: f64,
    /// Default: half the length.
    pub center_of_mass_m: Option<f64>,
}

/// `[mechanism.slider]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SliderSection {
    pub mass_kg: f64,
}

/// `[mechanism.joint]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSection {
    /// `"ideal"` or `"lubricated"`.
    #[serde(rename = "type")]
    pub kind: String,
    pub bearing_radius_m: Option<f64>,
    pub journal_radius_m: Option<f64>,
    pub length_m: Option<f64>,
    pub viscosity_pa_s: Option<f64>,
    /// A closed-form model name or `"reynolds"`.
    pub film: Option<String>,
    /// Reynolds grid.
    pub n_theta: Option<usize>,
    pub n_z: Option<usize>,
    /// The film's friction torque on the journal in the rod's moment equation (default false,
    /// as \[Flores2009\]).
    pub film_torque: Option<bool>,
}

/// `[mechanism.contact]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    pub journal_youngs_modulus_pa: Option<f64>,
    pub journal_poisson_ratio: Option<f64>,
    pub bearing_youngs_modulus_pa: Option<f64>,
    pub bearing_poisson_ratio: Option<f64>,
    pub restitution: Option<f64>,
    pub boundary_layer_m: Option<f64>,
    pub blend_width_m: Option<f64>,
    pub min_impact_speed_m_s: Option<f64>,
    /// Coulomb friction coefficient of the dry contact (default 0).
    pub friction_coefficient: Option<f64>,
    /// Regularisation speed of the friction law (m/s).
    pub friction_speed_m_s: Option<f64>,
}

/// `[mechanism.integrator]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSection {
    /// `"radau5"` or `"bdf2"`; default: radau5 for a closed-form film, bdf2 for reynolds.
    pub method: Option<String>,
    pub relative_tolerance: Option<f64>,
    pub absolute_tolerance: Option<f64>,
    pub steps_per_turn: Option<usize>,
    /// BDF2 local error tolerance (in ε): error control with steps of at most one turn /
    /// `steps_per_turn` (default `DEFAULT_BDF2_ERROR_TOLERANCE`).
    pub error_tolerance: Option<f64>,
    /// BDF2 with fixed steps of one turn / `steps_per_turn` instead of error control.
    pub fixed_steps: Option<bool>,
    pub newton_tolerance: Option<f64>,
    pub max_newton_iterations: Option<usize>,
}

fn default_gravity() -> [f64; 2] {
    [0.0, -9.81]
}
fn default_turns() -> usize {
    2
}
fn default_samples_per_turn() -> usize {
    360
}
fn default_true() -> bool {
    true
}

/// A validated mechanism case.
#[derive(Debug, Clone)]
pub struct MechanismCase {
    /// Name (output files are named after it).
    pub name: String,
    /// One line of description.
    pub description: String,
    /// The case file.
    pub path: PathBuf,
    /// The TOML text as given.
    pub text: String,
    /// The run (its joint as the file says).
    pub params: MechanismParams,
    /// Also run the ideal mechanism (lubricated joints only; an ideal case is its own
    /// reference).
    pub ideal_reference: bool,
    /// Write the PNG plots.
    pub plots: bool,
    /// Film name as given (`pinkus_sternlicht`, …, `reynolds`), empty for the ideal joint.
    pub film_name: String,
    /// Integrator name (`radau5`, `bdf2`), empty for the ideal joint.
    pub integrator_name: String,
}

impl MechanismCase {
    /// Read and resolve the mechanism case file at `path`.
    pub fn from_file(path: &Path) -> Result<Self, CaseError> {
        let text = std::fs::read_to_string(path).map_err(|source| CaseError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        Self::from_text(&text, path)
    }

    /// Resolve a mechanism case from its TOML `text`; `path` names it in messages.
    pub fn from_text(text: &str, path: &Path) -> Result<Self, CaseError> {
        let ctx = Ctx::new(text, path);
        let raw: MechanismCaseFile = ctx.parse()?;
        resolve(raw, &ctx)
    }

    /// One line for `jbearing check`: the joint, film, integrator and the run's length.
    pub fn describe(&self) -> String {
        let p = &self.params;
        match self.lubricated_joint() {
            Some(j) => format!(
                "mechanism case '{}', lubricated joint c = {:.4} mm, film {}, {}, {} turns × {} \
                 samples{}",
                self.name,
                j.radial_clearance() * 1e3,
                self.film_name,
                self.integrator_name,
                p.turns,
                p.samples_per_turn,
                if self.ideal_reference {
                    ", with the ideal reference"
                } else {
                    ""
                }
            ),
            None => format!(
                "mechanism case '{}', ideal joint, {} turns × {} samples",
                self.name, p.turns, p.samples_per_turn
            ),
        }
    }

    /// The same mechanism with the rod–slider joint ideal (the reference run).
    pub fn ideal_params(&self) -> MechanismParams {
        MechanismParams {
            joint: RodSliderJoint::Ideal,
            ..self.params.clone()
        }
    }

    /// The lubricated joint, if the case has one.
    pub fn lubricated_joint(&self) -> Option<&LubricatedJointParams> {
        match &self.params.joint {
            RodSliderJoint::Lubricated(j) => Some(j),
            RodSliderJoint::Ideal => None,
        }
    }
}

fn link(ctx: &Ctx<'_>, key: &str, l: &LinkSection) -> Result<Link, CaseError> {
    let k = |s: &str| format!("mechanism.{key}.{s}");
    let length = ctx.positive(&k("length_m"), l.length_m)?;
    let mass = ctx.positive(&k("mass_kg"), l.mass_kg)?;
    let inertia = ctx.finite(&k("inertia_kg_m2"), l.inertia_kg_m2)?;
    if inertia < 0.0 {
        return Err(ctx.err(&k("inertia_kg_m2"), format!("must be ≥ 0, got {inertia}")));
    }
    let center_of_mass = match l.center_of_mass_m {
        Some(v) => ctx.finite(&k("center_of_mass_m"), v)?,
        None => 0.5 * length,
    };
    Ok(Link {
        length,
        mass,
        inertia,
        center_of_mass,
    })
}

/// Resolve a parsed mechanism case: the stages below, in the order their errors are reported
/// (bodies, joint, the rod's length against both, integrator, film fields).
fn resolve(raw: MechanismCaseFile, ctx: &Ctx<'_>) -> Result<MechanismCase, CaseError> {
    if raw.sweep.is_some() {
        return Err(ctx.err(
            crate::sweep::SWEEP_TABLE,
            "this file is a sweep, one case per point: run it with `jbearing batch` (which \
             expands it; `jbearing check` prints the expansion)",
        ));
    }
    if raw.version != 1 {
        return Err(ctx.err(
            "version",
            format!(
                "this jbearing reads case files of version 1, not {}",
                raw.version
            ),
        ));
    }
    let name = super::case_name(raw.name.as_deref(), ctx)?;
    let m = &raw.mechanism;
    let mechanism = resolve_bodies(m, ctx)?;
    let (joint, film_name) = resolve_joint(m, ctx)?;
    let (rod, crank) = (mechanism.rod, mechanism.crank);
    if rod.length <= crank.length + 2.0 * lubricated_clearance(&joint) {
        return Err(ctx.err(
            "mechanism.rod.length_m",
            format!(
                "the rod ({} m) must be longer than the crank ({} m) (plus the clearance), or \
                 the slider cannot follow",
                rod.length, crank.length
            ),
        ));
    }
    let mut params = MechanismParams::new(mechanism, joint);
    params.turns = m.turns;
    params.samples_per_turn = m.samples_per_turn;
    let integrator_name = resolve_integrator(m, &mut params, ctx)?;
    resolve_field_snapshots(m, &mut params, ctx)?;
    Ok(MechanismCase {
        name,
        description: raw.description.clone().unwrap_or_default(),
        path: ctx.file.clone(),
        text: ctx.text.to_string(),
        ideal_reference: m.ideal_reference,
        plots: m.plots,
        film_name,
        integrator_name,
        params,
    })
}

/// `[mechanism]`'s drive and run keys and the three bodies.
fn resolve_bodies(m: &MechanismSection, ctx: &Ctx<'_>) -> Result<SliderCrankParams, CaseError> {
    let speed_rpm = ctx.finite("mechanism.crank_speed_rpm", m.crank_speed_rpm)?;
    if speed_rpm == 0.0 {
        return Err(ctx.err("mechanism.crank_speed_rpm", "must not be 0"));
    }
    let initial = ctx.finite(
        "mechanism.initial_crank_angle_deg",
        m.initial_crank_angle_deg,
    )?;
    for v in m.gravity_m_s2 {
        ctx.finite("mechanism.gravity_m_s2", v)?;
    }
    if m.turns == 0 {
        return Err(ctx.err("mechanism.turns", "must be at least 1"));
    }
    if m.samples_per_turn < 4 {
        return Err(ctx.err(
            "mechanism.samples_per_turn",
            format!("must be at least 4, got {}", m.samples_per_turn),
        ));
    }
    let crank = link(ctx, "crank", &m.crank)?;
    let rod = link(ctx, "rod", &m.rod)?;
    let slider_mass = ctx.positive("mechanism.slider.mass_kg", m.slider.mass_kg)?;
    let mechanism = SliderCrankParams {
        crank,
        rod,
        slider_mass,
        crank_speed: rpm_to_rad_s(speed_rpm),
        initial_crank_angle: deg_to_rad(initial),
        gravity: m.gravity_m_s2,
    };
    Ok(mechanism)
}

/// `[mechanism.joint]` (and `[mechanism.contact]`): the joint and the film's name as given.
fn resolve_joint(
    m: &MechanismSection,
    ctx: &Ctx<'_>,
) -> Result<(RodSliderJoint, String), CaseError> {
    match m.joint.kind.as_str() {
        "ideal" => {
            ideal_joint_keys(m, ctx)?;
            Ok((RodSliderJoint::Ideal, String::new()))
        }
        "lubricated" => lubricated_joint(m, ctx),
        other => Err(ctx.err(
            "mechanism.joint.type",
            format!("unknown joint type \"{other}\": \"ideal\" or \"lubricated\""),
        )),
    }
}

/// An ideal joint has no clearance, film, contact or integrator: any of those keys is an error.
fn ideal_joint_keys(m: &MechanismSection, ctx: &Ctx<'_>) -> Result<(), CaseError> {
    let j = &m.joint;
    let jk = |s: &str| format!("mechanism.joint.{s}");
    for (key, given) in [
        ("bearing_radius_m", j.bearing_radius_m.is_some()),
        ("journal_radius_m", j.journal_radius_m.is_some()),
        ("length_m", j.length_m.is_some()),
        ("viscosity_pa_s", j.viscosity_pa_s.is_some()),
        ("film", j.film.is_some()),
        ("n_theta", j.n_theta.is_some()),
        ("n_z", j.n_z.is_some()),
        ("film_torque", j.film_torque.is_some()),
    ] {
        if given {
            return Err(ctx.err(
                &jk(key),
                "an ideal joint has no clearance or film: remove the key, or set \
                 type = \"lubricated\"",
            ));
        }
    }
    for (table, given) in [
        ("mechanism.contact", m.contact.is_some()),
        ("mechanism.integrator", m.integrator.is_some()),
    ] {
        if given {
            return Err(ctx.err(
                table,
                "an ideal joint is solved in closed form: remove the table, or set \
                 joint.type = \"lubricated\"",
            ));
        }
    }
    Ok(())
}

/// The lubricated joint: geometry, film, contact.
fn lubricated_joint(
    m: &MechanismSection,
    ctx: &Ctx<'_>,
) -> Result<(RodSliderJoint, String), CaseError> {
    let j = &m.joint;
    let jk = |s: &str| format!("mechanism.joint.{s}");
    let need = |key: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            ctx.err(
                &jk(key),
                format!("missing: a lubricated joint needs `{key}`"),
            )
        })
        .and_then(|v| ctx.positive(&jk(key), v))
    };
    let bearing_radius = need("bearing_radius_m", j.bearing_radius_m)?;
    let journal_radius = need("journal_radius_m", j.journal_radius_m)?;
    let length = need("length_m", j.length_m)?;
    let viscosity = need("viscosity_pa_s", j.viscosity_pa_s)?;
    if journal_radius >= bearing_radius {
        return Err(ctx.err(
            &jk("journal_radius_m"),
            format!(
                "the journal ({journal_radius} m) must be smaller than the bearing \
                 ({bearing_radius} m): the radial clearance is their difference"
            ),
        ));
    }
    let c = bearing_radius - journal_radius;
    if c >= 0.1 * bearing_radius {
        return Err(ctx.err(
            &jk("journal_radius_m"),
            format!(
                "radial clearance {c:.6e} m is not small against the radius \
                 {bearing_radius} m (c/R must be < 0.1)"
            ),
        ));
    }
    let film_name = j
        .film
        .clone()
        .unwrap_or_else(|| ClosedFormModel::PinkusSternlicht.name().to_string());
    let mut joint = LubricatedJointParams {
        bearing_radius,
        journal_radius,
        length,
        viscosity,
        film: JointFilm::ClosedForm(ClosedFormModel::PinkusSternlicht),
        contact: ContactParams::default(),
        film_torque: j.film_torque.unwrap_or(false),
    };
    joint.film = joint_film(j, &joint, &film_name, ctx)?;
    if let Some(s) = &m.contact {
        joint.contact = contact(s, ctx)?;
    }
    if joint.contact.boundary_layer >= c {
        return Err(ctx.err(
            "mechanism.contact.boundary_layer_m",
            format!(
                "the boundary layer h_b = {:e} m must be smaller than the radial \
                 clearance {c:e} m",
                joint.contact.boundary_layer
            ),
        ));
    }
    Ok((RodSliderJoint::Lubricated(joint), film_name))
}

/// The film model named by `joint.film` (`"reynolds"` with its grid, or a closed form).
fn joint_film(
    j: &JointSection,
    joint: &LubricatedJointParams,
    film_name: &str,
    ctx: &Ctx<'_>,
) -> Result<JointFilm, CaseError> {
    let jk = |s: &str| format!("mechanism.joint.{s}");
    Ok(if film_name == "reynolds" {
        let mut p = joint.reynolds_params();
        if let Some(n) = j.n_theta {
            if n < 8 {
                return Err(ctx.err(&jk("n_theta"), format!("must be ≥ 8, got {n}")));
            }
            p.grid.n_theta = n;
        }
        if let Some(n) = j.n_z {
            if n < 3 {
                return Err(ctx.err(&jk("n_z"), format!("must be ≥ 3, got {n}")));
            }
            p.grid.n_z = n;
        }
        JointFilm::Reynolds(Box::new(p))
    } else {
        let model: ClosedFormModel = film_name.parse().map_err(|e: ClosedFormError| {
            ctx.err(
                &jk("film"),
                format!("{e}, or \"reynolds\" (the mass-conserving Reynolds film)"),
            )
        })?;
        for (key, given) in [("n_theta", j.n_theta), ("n_z", j.n_z)] {
            if given.is_some() {
                return Err(ctx.err(
                    &jk(key),
                    format!(
                        "a grid is for film = \"reynolds\"; the closed form \
                         \"{film_name}\" has none"
                    ),
                ));
            }
        }
        JointFilm::ClosedForm(model)
    })
}

/// `[mechanism.contact]`: every key defaulted from [`ContactParams::default`] and checked.
fn contact(s: &ContactSection, ctx: &Ctx<'_>) -> Result<ContactParams, CaseError> {
    let d = ContactParams::default();
    let ck = |s: &str| format!("mechanism.contact.{s}");
    let pos = |key: &str, v: Option<f64>, default: f64| match v {
        Some(v) => ctx.positive(&ck(key), v),
        None => Ok(default),
    };
    let ratio = |key: &str, v: Option<f64>, default: f64| match v {
        Some(v) if !(v.is_finite() && (0.0..0.5).contains(&v)) => Err(ctx.err(
            &ck(key),
            format!("a Poisson's ratio must be in [0, 0.5), got {v}"),
        )),
        Some(v) => Ok(v),
        None => Ok(default),
    };
    let joint_contact = ContactParams {
        journal_youngs_modulus: pos(
            "journal_youngs_modulus_pa",
            s.journal_youngs_modulus_pa,
            d.journal_youngs_modulus,
        )?,
        journal_poisson_ratio: ratio(
            "journal_poisson_ratio",
            s.journal_poisson_ratio,
            d.journal_poisson_ratio,
        )?,
        bearing_youngs_modulus: pos(
            "bearing_youngs_modulus_pa",
            s.bearing_youngs_modulus_pa,
            d.bearing_youngs_modulus,
        )?,
        bearing_poisson_ratio: ratio(
            "bearing_poisson_ratio",
            s.bearing_poisson_ratio,
            d.bearing_poisson_ratio,
        )?,
        restitution: match s.restitution {
            Some(v) if !(v > 0.0 && v <= 1.0) => {
                return Err(ctx.err(
                    &ck("restitution"),
                    format!("the coefficient of restitution must be in (0, 1], got {v}"),
                ));
            }
            Some(v) => v,
            None => d.restitution,
        },
        boundary_layer: pos("boundary_layer_m", s.boundary_layer_m, d.boundary_layer)?,
        blend_width: pos("blend_width_m", s.blend_width_m, d.blend_width)?,
        min_impact_speed: pos(
            "min_impact_speed_m_s",
            s.min_impact_speed_m_s,
            d.min_impact_speed,
        )?,
        friction_coefficient: match s.friction_coefficient {
            Some(v) if !(v.is_finite() && v >= 0.0) => {
                return Err(ctx.err(
                    &ck("friction_coefficient"),
                    format!("a friction coefficient must be ≥ 0, got {v}"),
                ));
            }
            Some(v) => v,
            None => d.friction_coefficient,
        },
        friction_speed: pos("friction_speed_m_s", s.friction_speed_m_s, d.friction_speed)?,
    };
    check_blend_band(&joint_contact, s, ctx)?;
    Ok(joint_contact)
}

/// The film-to-contact blend inside the boundary layer, e₀ < h_b; the error names the key
/// (the blend width when the file gives it, else the boundary layer).
fn check_blend_band(
    cc: &ContactParams,
    s: &ContactSection,
    ctx: &Ctx<'_>,
) -> Result<(), CaseError> {
    if cc.blend_width >= cc.boundary_layer {
        return Err(ctx.err(
            &format!(
                "mechanism.contact.{}",
                if s.blend_width_m.is_some() {
                    "blend_width_m"
                } else {
                    "boundary_layer_m"
                }
            ),
            format!(
                "the blend width e₀ = {:e} m must be smaller than the boundary layer \
                 h_b = {:e} m",
                cc.blend_width, cc.boundary_layer
            ),
        ));
    }
    Ok(())
}

/// `[mechanism.integrator]`: the method (default by film) and its settings; returns its name.
fn resolve_integrator(
    m: &MechanismSection,
    params: &mut MechanismParams,
    ctx: &Ctx<'_>,
) -> Result<String, CaseError> {
    let RodSliderJoint::Lubricated(jp) = &params.joint else {
        return Ok(String::new());
    };
    let reynolds = matches!(jp.film, JointFilm::Reynolds(_));
    let s = m.integrator.as_ref();
    let method = s
        .and_then(|s| s.method.clone())
        .unwrap_or_else(|| if reynolds { "bdf2" } else { "radau5" }.to_string());
    params.integrator = match method.as_str() {
        "radau5" => radau5_integrator(s, reynolds, ctx)?,
        "bdf2" => bdf2_integrator(s, m, ctx)?,
        other => {
            return Err(ctx.err(
                "mechanism.integrator.method",
                format!("unknown integrator \"{other}\": \"radau5\" or \"bdf2\""),
            ));
        }
    };
    Ok(method)
}

/// `method = "radau5"`: its tolerances; a BDF2 key or a Reynolds film is an error.
fn radau5_integrator(
    s: Option<&IntegratorSection>,
    reynolds: bool,
    ctx: &Ctx<'_>,
) -> Result<Integrator, CaseError> {
    let ik = |s: &str| format!("mechanism.integrator.{s}");
    let given = |f: fn(&IntegratorSection) -> bool| s.is_some_and(f);
    if reynolds {
        return Err(ctx.err(
            &ik("method"),
            "the Reynolds film needs method = \"bdf2\" (its film state advances \
             step by step)",
        ));
    }
    for (key, bad) in [
        ("steps_per_turn", given(|s| s.steps_per_turn.is_some())),
        ("error_tolerance", given(|s| s.error_tolerance.is_some())),
        ("fixed_steps", given(|s| s.fixed_steps.is_some())),
        ("newton_tolerance", given(|s| s.newton_tolerance.is_some())),
        (
            "max_newton_iterations",
            given(|s| s.max_newton_iterations.is_some()),
        ),
    ] {
        if bad {
            return Err(ctx.err(&ik(key), "is a setting of method = \"bdf2\""));
        }
    }
    let Integrator::Radau5 {
        relative_tolerance,
        absolute_tolerance,
    } = Integrator::radau5_default()
    else {
        unreachable!("radau5_default is Radau5")
    };
    let tol = |key: &str, v: Option<f64>, d: f64| match v {
        Some(v) => ctx.positive(&ik(key), v),
        None => Ok(d),
    };
    Ok(Integrator::Radau5 {
        relative_tolerance: tol(
            "relative_tolerance",
            s.and_then(|s| s.relative_tolerance),
            relative_tolerance,
        )?,
        absolute_tolerance: tol(
            "absolute_tolerance",
            s.and_then(|s| s.absolute_tolerance),
            absolute_tolerance,
        )?,
    })
}

/// `method = "bdf2"`: steps, error control or fixed steps, Newton settings.
fn bdf2_integrator(
    s: Option<&IntegratorSection>,
    m: &MechanismSection,
    ctx: &Ctx<'_>,
) -> Result<Integrator, CaseError> {
    let ik = |s: &str| format!("mechanism.integrator.{s}");
    let given = |f: fn(&IntegratorSection) -> bool| s.is_some_and(f);
    for (key, bad) in [
        (
            "relative_tolerance",
            given(|s| s.relative_tolerance.is_some()),
        ),
        (
            "absolute_tolerance",
            given(|s| s.absolute_tolerance.is_some()),
        ),
    ] {
        if bad {
            return Err(ctx.err(&ik(key), "is a setting of method = \"radau5\""));
        }
    }
    let Integrator::Bdf2 {
        steps_per_turn,
        error_tolerance,
        newton_tolerance,
        max_newton_iterations,
    } = Integrator::bdf2_controlled()
    else {
        unreachable!("bdf2_controlled is Bdf2")
    };
    let steps = s.and_then(|s| s.steps_per_turn).unwrap_or(steps_per_turn);
    if steps == 0 || !steps.is_multiple_of(m.samples_per_turn) {
        return Err(ctx.err(
            if s.and_then(|s| s.steps_per_turn).is_some() {
                "mechanism.integrator.steps_per_turn"
            } else {
                "mechanism.samples_per_turn"
            },
            format!(
                "steps_per_turn ({steps}) must be a positive multiple of \
                 samples_per_turn ({})",
                m.samples_per_turn
            ),
        ));
    }
    let iterations = s
        .and_then(|s| s.max_newton_iterations)
        .unwrap_or(max_newton_iterations);
    if iterations == 0 {
        return Err(ctx.err(&ik("max_newton_iterations"), "must be at least 1"));
    }
    let error_tolerance = match (
        s.and_then(|s| s.error_tolerance),
        s.and_then(|s| s.fixed_steps).unwrap_or(false),
    ) {
        (Some(_), true) => {
            return Err(ctx.err(
                &ik("error_tolerance"),
                "fixed_steps = true has no error control: remove one of the two",
            ));
        }
        (Some(v), false) => Some(ctx.positive(&ik("error_tolerance"), v)?),
        (None, true) => None,
        (None, false) => error_tolerance,
    };
    Ok(Integrator::Bdf2 {
        steps_per_turn: steps,
        error_tolerance,
        newton_tolerance: match s.and_then(|s| s.newton_tolerance) {
            Some(v) => ctx.positive(&ik("newton_tolerance"), v)?,
            None => newton_tolerance,
        },
        max_newton_iterations: iterations,
    })
}

/// `field_snapshots`: Reynolds film only, at most one per BDF2 step.
fn resolve_field_snapshots(
    m: &MechanismSection,
    params: &mut MechanismParams,
    ctx: &Ctx<'_>,
) -> Result<(), CaseError> {
    if let Some(n) = m.field_snapshots {
        let reynolds = matches!(
            &params.joint,
            RodSliderJoint::Lubricated(LubricatedJointParams {
                film: JointFilm::Reynolds(_),
                ..
            })
        );
        if n > 0 && !reynolds {
            return Err(ctx.err(
                "mechanism.field_snapshots",
                "film fields exist for joint.film = \"reynolds\" only",
            ));
        }
        if let Integrator::Bdf2 { steps_per_turn, .. } = params.integrator
            && n > steps_per_turn
        {
            return Err(ctx.err(
                "mechanism.field_snapshots",
                format!("at most steps_per_turn ({steps_per_turn}) instants"),
            ));
        }
        params.field_snapshots = n;
    } else if let Integrator::Bdf2 { steps_per_turn, .. } = params.integrator {
        // The default, on a coarser time grid: one snapshot per step.
        params.field_snapshots = params.field_snapshots.min(steps_per_turn);
    }
    Ok(())
}

fn lubricated_clearance(joint: &RodSliderJoint) -> f64 {
    match joint {
        RodSliderJoint::Ideal => 0.0,
        RodSliderJoint::Lubricated(j) => j.radial_clearance(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped case resolves to the solvers' own Flores et al. 2009 parameters.
    #[test]
    fn shipped_case_is_the_papers_case() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/flores2009_slider_crank.toml");
        let case = MechanismCase::from_file(&path).expect("valid case");
        let want = MechanismParams::flores2009();
        let p = &case.params;
        assert_eq!(p.turns, want.turns);
        assert_eq!(p.samples_per_turn, want.samples_per_turn);
        assert_eq!(p.integrator, want.integrator);
        let (a, b) = (&p.mechanism, &want.mechanism);
        assert_eq!(a.crank, b.crank);
        assert_eq!(a.rod, b.rod);
        assert_eq!(a.slider_mass, b.slider_mass);
        assert_eq!(a.gravity, b.gravity);
        assert!((a.crank_speed - b.crank_speed).abs() < 1e-12 * b.crank_speed);
        let (RodSliderJoint::Lubricated(ja), RodSliderJoint::Lubricated(jb)) =
            (&p.joint, &want.joint)
        else {
            panic!("lubricated joints")
        };
        assert!((ja.radial_clearance() - 0.2e-3).abs() < 1e-15);
        assert_eq!(ja.viscosity, 0.4);
        assert_eq!(ja.film, jb.film);
        assert_eq!(ja.contact, jb.contact);
        assert_eq!(ja.length, jb.length);
        assert!(case.ideal_reference && case.plots);
    }

    /// BDF2 runs under error control unless the file asks for fixed steps; asking for both is
    /// an error naming the key.
    #[test]
    fn bdf2_is_error_controlled_unless_fixed_steps_are_asked_for() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/flores2009_slider_crank.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let with = |integrator: &str| {
            text.replace(
                "method = \"radau5\"",
                &format!("method = \"bdf2\"\n{integrator}"),
            )
        };
        let tol = |case: MechanismCase| match case.params.integrator {
            Integrator::Bdf2 {
                error_tolerance, ..
            } => error_tolerance,
            other => panic!("{other:?}"),
        };
        let default = MechanismCase::from_text(&with(""), &path).unwrap();
        assert_eq!(default.params.integrator, Integrator::bdf2_controlled());
        let fixed = MechanismCase::from_text(&with("fixed_steps = true"), &path).unwrap();
        assert_eq!(tol(fixed), None);
        let given = MechanismCase::from_text(&with("error_tolerance = 1e-6"), &path).unwrap();
        assert_eq!(tol(given), Some(1e-6));
        let both = with("fixed_steps = true\nerror_tolerance = 1e-6");
        let err = MechanismCase::from_text(&both, &path)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("mechanism.integrator.error_tolerance"),
            "{err}"
        );
    }

    /// The friction switches: off by default (as \[Flores2009\]), read when given, a negative
    /// coefficient refused naming its key.
    #[test]
    fn friction_switches_are_read_and_checked() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/flores2009_slider_crank.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let joint = |case: &MechanismCase| case.lubricated_joint().unwrap().clone();
        let default = MechanismCase::from_text(&text, &path).unwrap();
        assert!(!joint(&default).film_torque);
        assert_eq!(joint(&default).contact.friction_coefficient, 0.0);
        let on = text.replace(
            "film = \"pinkus_sternlicht\"",
            "film = \"pinkus_sternlicht\"\nfilm_torque = true\n\n[mechanism.contact]\nfriction_coefficient = 0.1\nfriction_speed_m_s = 0.01",
        );
        let case = MechanismCase::from_text(&on, &path).unwrap();
        let j = joint(&case);
        assert!(j.film_torque);
        assert_eq!(j.contact.friction_coefficient, 0.1);
        assert_eq!(j.contact.friction_speed, 0.01);
        let bad = on.replace("friction_coefficient = 0.1", "friction_coefficient = -0.1");
        let err = MechanismCase::from_text(&bad, &path)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("mechanism.contact.friction_coefficient"),
            "{err}"
        );
    }

    #[test]
    fn mechanism_files_are_told_from_bearing_files() {
        assert!(is_mechanism_text("version = 1\n[mechanism]\nturns = 2\n"));
        assert!(!is_mechanism_text(
            "version = 1\n[bearing]\nradius_m = 0.1\n"
        ));
        assert!(!is_mechanism_text("version = 1\n[mechanism\n"));
    }
}
