//! The run: ideal joint in closed form, lubricated joint by Radau5 (closed-form film) or by
//! BDF2 with Newton, fixed steps or under error control (any film). See the module docs of
//! [`super`].

use super::contact::{blend_weight, lankarani_nikravesh};
use super::slider_crank::{Configuration, SliderCrankParams};
use super::{
    ContactEvent, ContactEventKind, Integrator, JointFilm, LubricatedJointParams, MechanismError,
    MechanismFilmFields, MechanismInfo, MechanismParams, MechanismSolution, RodSliderJoint,
};
use crate::closed_form::short::couette_shear_torque;
use crate::closed_form::{ClosedFormModel, ClosedFormParams, JournalMotion, film_force};
use crate::inverse::{FilmFields, FilmModel, OperatingConditions, ReynoldsFilm};
use crate::reynolds::FilmState;
use differential_equations::prelude::{
    CrossingDirection, Event, EventConfig, IVP, ImplicitRungeKutta, ODE, Solution, Status,
};
use std::cell::RefCell;

/// Run the mechanism for `params.turns` crank turns from t = 0.
///
/// ```
/// use jbearing_solvers::mechanism::{
///     solve_mechanism, MechanismParams, MechanismSolution, RodSliderJoint, SliderCrankParams,
/// };
///
/// // [Flores2009] §8: with the 0.2 mm, 400 cP gudgeon pin the film is never broken (no dry
/// // contact, the journal stays inside the clearance), and the joint force is of the ideal
/// // joint's order: the two peaks within 10 %.
/// let lubricated = solve_mechanism(&MechanismParams::flores2009())?;
/// assert!(lubricated.contact_events.is_empty());
/// assert!(lubricated.eccentricity.iter().all(|e| e[0].hypot(e[1]) < 0.2e-3));
/// let ideal = solve_mechanism(&MechanismParams::new(SliderCrankParams::flores2009(), RodSliderJoint::Ideal))?;
/// let peak = |s: &MechanismSolution| {
///     s.loads.iter().map(|l| l.rod_slider[0].hypot(l.rod_slider[1])).fold(0.0, f64::max)
/// };
/// assert!((peak(&lubricated) / peak(&ideal) - 1.0).abs() < 0.1);
/// # Ok::<(), jbearing_solvers::mechanism::MechanismError>(())
/// ```
pub fn solve_mechanism(params: &MechanismParams) -> Result<MechanismSolution, MechanismError> {
    if params.turns == 0 {
        return Err(bad("turns", 0.0));
    }
    if params.samples_per_turn < 4 {
        return Err(bad("samples_per_turn", params.samples_per_turn as f64));
    }
    match &params.joint {
        RodSliderJoint::Ideal => {
            params.mechanism.validate(0.0)?;
            solve_ideal(params)
        }
        RodSliderJoint::Lubricated(joint) => {
            joint.validate()?;
            params.mechanism.validate(joint.radial_clearance())?;
            solve_lubricated(params, joint)
        }
    }
}

/// The error of a run setting out of its range.
fn bad(name: &'static str, value: f64) -> MechanismError {
    MechanismError::InvalidParameter { name, value }
}

/// The lubricated joint by its integrator, the integrator's settings checked: Radau5 for a
/// closed-form film, BDF2 for any film.
fn solve_lubricated(
    params: &MechanismParams,
    joint: &LubricatedJointParams,
) -> Result<MechanismSolution, MechanismError> {
    let model = JointModel::new(&params.mechanism, joint);
    match (params.integrator, &joint.film) {
        (
            Integrator::Radau5 {
                relative_tolerance,
                absolute_tolerance,
            },
            JointFilm::ClosedForm(m),
        ) => {
            for (n, v) in [
                ("relative_tolerance", relative_tolerance),
                ("absolute_tolerance", absolute_tolerance),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(bad(n, v));
                }
            }
            solve_radau(params, &model, *m, relative_tolerance, absolute_tolerance)
        }
        (Integrator::Radau5 { .. }, JointFilm::Reynolds(_)) => Err(MechanismError::Unsupported {
            what: "the Reynolds film needs the BDF2 integrator (its film state advances step by step)",
        }),
        (
            Integrator::Bdf2 {
                steps_per_turn,
                error_tolerance,
                newton_tolerance,
                max_newton_iterations,
            },
            film,
        ) => {
            if let Some(tol) = error_tolerance
                && !(tol.is_finite() && tol > 0.0)
            {
                return Err(bad("error_tolerance", tol));
            }
            if steps_per_turn == 0 || steps_per_turn % params.samples_per_turn != 0 {
                return Err(bad(
                    "steps_per_turn (a multiple of samples_per_turn)",
                    steps_per_turn as f64,
                ));
            }
            if !(newton_tolerance.is_finite() && newton_tolerance > 0.0) {
                return Err(bad("newton_tolerance", newton_tolerance));
            }
            if max_newton_iterations == 0 {
                return Err(bad("max_newton_iterations", 0.0));
            }
            let newton = NewtonSettings {
                tol: newton_tolerance,
                max_iter: max_newton_iterations,
            };
            let mut film = Film::new(film, params)?;
            solve_bdf2(
                params,
                &model,
                &mut film,
                steps_per_turn,
                error_tolerance,
                newton,
            )
        }
    }
}

fn sample_times(params: &MechanismParams) -> Vec<f64> {
    let n = params.turns * params.samples_per_turn;
    let tau = params.mechanism.period();
    (0..=n)
        .map(|i| tau * i as f64 / params.samples_per_turn as f64)
        .collect()
}

fn solve_ideal(params: &MechanismParams) -> Result<MechanismSolution, MechanismError> {
    let mech = &params.mechanism;
    let mut out = MechanismSolution::default();
    for t in sample_times(params) {
        let (k, acc, f) = mech.ideal(t)?;
        out.push_sample(mech, &k, acc, (f, 0.0), [0.0; 2], [0.0; 2]);
    }
    out.check_finite()?;
    out.finish(None, None);
    Ok(out)
}

impl MechanismSolution {
    fn push_sample(
        &mut self,
        mech: &SliderCrankParams,
        k: &Configuration,
        acc: [f64; 2],
        (f, torque): ([f64; 2], f64),
        e: [f64; 2],
        e_rate: [f64; 2],
    ) {
        self.time.push(k.t);
        self.crank_angle_deg
            .push(mech.crank_angle(k.t).to_degrees());
        self.bodies.push(mech.bodies(k));
        self.loads.push(mech.joint_loads(k, acc, f, torque));
        self.eccentricity.push(e);
        self.eccentricity_rate.push(e_rate);
    }

    fn check_finite(&self) -> Result<(), MechanismError> {
        for (i, l) in self.loads.iter().enumerate() {
            let vals = [
                l.rod_slider[0],
                l.rod_slider[1],
                l.crank_pin[0],
                l.crank_pin[1],
                l.ground_pivot[0],
                l.ground_pivot[1],
                l.guide_normal,
                l.crank_moment,
                self.eccentricity[i][0],
                self.eccentricity[i][1],
            ];
            if vals.iter().any(|v| !v.is_finite()) {
                return Err(MechanismError::NonFinite {
                    quantity: "joint loads or eccentricity",
                    time: self.time[i],
                });
            }
        }
        Ok(())
    }

    /// Extremes and periodicity; `clearance` None for the ideal joint.
    fn finish(&mut self, clearance: Option<f64>, samples_per_turn: Option<usize>) {
        let info = &mut self.info;
        info.max_joint_force = self
            .loads
            .iter()
            .map(|l| l.rod_slider[0].hypot(l.rod_slider[1]))
            .fold(0.0, f64::max);
        info.max_crank_moment = self
            .loads
            .iter()
            .map(|l| l.crank_moment.abs())
            .fold(0.0, f64::max);
        if let Some(c) = clearance {
            let (i, h) = self
                .min_film_thickness
                .iter()
                .copied()
                .enumerate()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((0, c));
            info.min_film_thickness = Some(h);
            info.min_film_crank_angle_deg = Some(self.crank_angle_deg[i]);
            info.max_eccentricity_ratio = self
                .eccentricity
                .iter()
                .map(|e| e[0].hypot(e[1]) / c)
                .fold(0.0, f64::max);
            if let Some(n) = samples_per_turn {
                let len = self.eccentricity.len();
                if len > 2 * n {
                    let last = &self.eccentricity[len - 1 - n..];
                    let prev = &self.eccentricity[len - 1 - 2 * n..len - 1 - n];
                    info.periodicity_change = Some(
                        last.iter()
                            .zip(prev)
                            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]) / c)
                            .fold(0.0, f64::max),
                    );
                }
            }
        }
    }
}

impl MechanismSolution {
    /// A lubricated run's solution from its samples: h_min at each, the contact weights, events
    /// and counts, checked finite, with the extremes and periodicity (shared by both integrators).
    fn finish_lubricated(
        mut self,
        c: f64,
        samples_per_turn: usize,
        weights: Vec<f64>,
        events: Vec<ContactEvent>,
        info: MechanismInfo,
    ) -> Result<Self, MechanismError> {
        self.min_film_thickness = self
            .eccentricity
            .iter()
            .map(|e| c - e[0].hypot(e[1]))
            .collect();
        self.contact_weight = weights;
        self.contact_events = events;
        self.info = info;
        self.check_finite()?;
        self.finish(Some(c), Some(samples_per_turn));
        Ok(self)
    }
}

/// The lubricated joint's force law (film + contact blend).
struct JointModel<'a> {
    mech: &'a SliderCrankParams,
    joint: &'a LubricatedJointParams,
    c: f64,
    cf: ClosedFormParams,
    stiffness: f64,
    /// |e| where the contact starts, c − h_b (m).
    contact_radius: f64,
    /// Largest ε at which the film is evaluated: (c − h_b + e₀)/c.
    film_limit: f64,
    /// |e| below which a contact is over: c − h_b − e₀/10 (hysteresis, so that a journal
    /// grazing the boundary layer does not stop the integrator at every crossing).
    release_radius: f64,
}

/// Longest Newton update of ε in one BDF2 iteration (0.05 c).
const MAX_NEWTON_STEP: f64 = 0.05;

/// A run with more contact events than this is stopped with an error.
const MAX_CONTACT_EVENTS: usize = 100_000;

/// Force and moment on the journal and their parts at one state.
#[derive(Debug, Clone, Copy)]
struct JointForce {
    total: [f64; 2],
    /// Moment on the journal about its centre (film torque where switched on, contact
    /// friction), blended.
    torque: f64,
    /// The film's force and torque before the blend (0 where not evaluated, s = 1).
    film: [f64; 2],
    film_torque: f64,
    weight: f64,
}

impl<'a> JointModel<'a> {
    fn new(mech: &'a SliderCrankParams, joint: &'a LubricatedJointParams) -> Self {
        let c = joint.radial_clearance();
        let k = &joint.contact;
        Self {
            mech,
            joint,
            c,
            cf: joint.closed_form_params(),
            stiffness: k.stiffness(joint.bearing_radius, joint.journal_radius),
            contact_radius: c - k.boundary_layer,
            film_limit: (c - k.boundary_layer + k.blend_width) / c,
            release_radius: c - k.boundary_layer - 0.1 * k.blend_width,
        }
    }

    /// Blend weight s, the dry force on the journal and its moment about the journal centre
    /// (Coulomb friction, [`super::contact`]) for e, ė and the journal's spin φ̇₃.
    fn dry(
        &self,
        e: [f64; 2],
        e_rate: [f64; 2],
        rod_rate: f64,
        impact_speed: f64,
    ) -> (f64, [f64; 2], f64) {
        let r = e[0].hypot(e[1]);
        let delta = r - self.contact_radius;
        if delta <= 0.0 {
            return (0.0, [0.0; 2], 0.0);
        }
        let n = [e[0] / r, e[1] / r];
        let rate = n[0] * e_rate[0] + n[1] * e_rate[1];
        let k = &self.joint.contact;
        let fnorm = lankarani_nikravesh(self.stiffness, k.restitution, delta, rate, impact_speed);
        let (mut force, mut torque) = ([-fnorm * n[0], -fnorm * n[1]], 0.0);
        if k.friction_coefficient > 0.0 {
            let t = [-n[1], n[0]];
            let slip = e_rate[0] * t[0] + e_rate[1] * t[1] + rod_rate * self.joint.journal_radius;
            let ft = -k.friction_coefficient * fnorm * slip / slip.hypot(k.friction_speed);
            force = [force[0] + ft * t[0], force[1] + ft * t[1]];
            torque = self.joint.journal_radius * ft;
        }
        (blend_weight(delta, k.blend_width), force, torque)
    }

    /// Blend a film force and torque (evaluated only when s < 1; the torque counted where
    /// [`LubricatedJointParams::film_torque`] asks for it) with the dry force and moment.
    fn blend(
        &self,
        e: [f64; 2],
        e_rate: [f64; 2],
        rod_rate: f64,
        impact_speed: f64,
        film: impl FnOnce() -> Result<([f64; 2], f64), String>,
    ) -> Result<JointForce, String> {
        let (s, dry, dry_torque) = self.dry(e, e_rate, rod_rate, impact_speed);
        let (film, film_torque) = if s < 1.0 { film()? } else { ([0.0; 2], 0.0) };
        let film_torque = if self.joint.film_torque {
            film_torque
        } else {
            0.0
        };
        Ok(JointForce {
            total: [
                (1.0 - s) * film[0] + s * dry[0],
                (1.0 - s) * film[1] + s * dry[1],
            ],
            torque: (1.0 - s) * film_torque + s * dry_torque,
            film,
            film_torque,
            weight: s,
        })
    }

    /// A closed-form film's force and its friction torque on the journal, −T_s − ½ (e × F)
    /// (Couette and pressure-flow shear, as [`crate::closed_form::ClosedFormFilm`]).
    fn closed_film(
        &self,
        model: ClosedFormModel,
        eps: [f64; 2],
        eps_rate: [f64; 2],
        omega: f64,
    ) -> Result<([f64; 2], f64), String> {
        let motion = JournalMotion::from_cartesian(eps, eps_rate, omega);
        let f = film_force(model, &self.cf, &motion)
            .map(|f| f.cartesian)
            .map_err(|e| e.to_string())?;
        let torque = if self.joint.film_torque {
            let shear = couette_shear_torque(&self.cf, eps[0].hypot(eps[1]), omega);
            -shear - 0.5 * self.c * (eps[0] * f[1] - eps[1] * f[0])
        } else {
            0.0
        };
        Ok((f, torque))
    }

    /// ε̈ for the state (ε, ε̇) at t and the joint force law `force`, with the configuration.
    fn eps_acceleration(
        &self,
        t: f64,
        eps: [f64; 2],
        eps_rate: [f64; 2],
        force: impl FnOnce(&Configuration) -> Result<JointForce, String>,
    ) -> Result<([f64; 2], Configuration, [f64; 2], JointForce), MechanismError> {
        let c = self.c;
        let e = [c * eps[0], c * eps[1]];
        let ed = [c * eps_rate[0], c * eps_rate[1]];
        let k = self.mech.configuration(t, e, ed)?;
        let f = force(&k).map_err(|reason| MechanismError::Film {
            time: t,
            crank_angle_deg: self.mech.crank_angle(t).to_degrees(),
            eccentricity_ratio: eps[0].hypot(eps[1]),
            reason,
        })?;
        let acc = self.mech.accelerations(&k, f.total, f.torque);
        let ea = self.mech.eccentricity_acceleration(&k, acc);
        Ok(([ea[0] / c, ea[1] / c], k, acc, f))
    }

    fn crank_deg(&self, t: f64) -> f64 {
        self.mech.crank_angle(t).to_degrees()
    }
}

// ---------------------------------------------------------------------------------------------
// Radau5 (closed-form film)

struct RadauOde<'m, 'a> {
    model: &'m JointModel<'a>,
    film: ClosedFormModel,
    impact_speed: f64,
    error: RefCell<Option<MechanismError>>,
    /// |ε| of the event: the contact radius (onset, crossed outwards) or the release radius
    /// (in contact, crossed inwards).
    event_level: f64,
    in_contact: bool,
}

impl RadauOde<'_, '_> {
    fn evaluate(
        &self,
        t: f64,
        y: &[f64; 4],
    ) -> Result<([f64; 2], Configuration, [f64; 2], JointForce), MechanismError> {
        let m = self.model;
        let (eps, rate) = ([y[0], y[1]], [y[2], y[3]]);
        let c = m.c;
        m.eps_acceleration(t, eps, rate, |k| {
            m.blend(
                [c * eps[0], c * eps[1]],
                [c * rate[0], c * rate[1]],
                k.rod_rate,
                self.impact_speed,
                || m.closed_film(self.film, eps, rate, k.rod_rate),
            )
        })
    }
}

impl ODE<f64, [f64; 4]> for RadauOde<'_, '_> {
    fn diff(&self, t: f64, y: &[f64; 4], dydt: &mut [f64; 4]) {
        match self.evaluate(t, y) {
            Ok((a, ..)) => *dydt = [y[2], y[3], a[0], a[1]],
            Err(err) => {
                // Keep the first error; the derivative is zero so the integrator stays finite.
                // The run reports the error after the solve (no NaN leaves).
                self.error.borrow_mut().get_or_insert(err);
                *dydt = [0.0; 4];
            }
        }
    }
}

impl Event<f64, [f64; 4]> for RadauOde<'_, '_> {
    fn config(&self) -> EventConfig {
        let dir = if self.in_contact {
            CrossingDirection::Negative
        } else {
            CrossingDirection::Positive
        };
        EventConfig::new(dir, Some(1))
    }

    fn event(&self, _t: f64, y: &[f64; 4]) -> f64 {
        y[0].hypot(y[1]) - self.event_level
    }
}

/// Radau5 with the contact events: integrate to the next onset or release (or the end), record
/// the output samples passed, switch the contact mode at the event and restart from it.
fn solve_radau(
    params: &MechanismParams,
    model: &JointModel<'_>,
    film: ClosedFormModel,
    rtol: f64,
    atol: f64,
) -> Result<MechanismSolution, MechanismError> {
    let times = sample_times(params);
    let tf = *times.last().expect("at least 5 samples");
    let mut run = RadauRun::new(model, times.len());
    loop {
        let ode = run.ode(model, film);
        let sol = run.integrate(params, &ode, tf, &times[run.next..], rtol, atol)?;
        let t_event = if matches!(sol.status, Status::Interrupted) {
            sol.t.last().copied()
        } else {
            None
        };
        run.record_samples(params, &ode, &sol, &times, t_event)?;
        match t_event {
            Some(te) if run.next < times.len() => {
                run.switch_contact(model, te, *sol.y.last().expect("event point"))?;
                if te >= tf {
                    break;
                }
            }
            _ => break,
        }
    }
    run.finish(params, model, times.len())
}

/// What a Radau5 run carries across its restarts at contact events.
struct RadauRun {
    /// Start of the next segment: time and state (ε, dε/dt).
    t0: f64,
    y0: [f64; 4],
    /// Impact velocity of the current contact (the floor outside contact).
    impact: f64,
    in_contact: bool,
    /// Index of the next output sample to record.
    next: usize,
    info: MechanismInfo,
    events: Vec<ContactEvent>,
    out: MechanismSolution,
    weights: Vec<f64>,
}

impl RadauRun {
    /// Centred journal at rest at t = 0, out of contact.
    fn new(model: &JointModel<'_>, samples: usize) -> Self {
        Self {
            t0: 0.0,
            y0: [0.0; 4],
            impact: model.joint.contact.min_impact_speed,
            in_contact: false,
            next: 0,
            info: MechanismInfo::default(),
            events: Vec::new(),
            out: MechanismSolution::default(),
            weights: Vec::with_capacity(samples),
        }
    }

    /// The equations of the next segment, with the event of the current contact mode.
    fn ode<'m, 'a>(&self, model: &'m JointModel<'a>, film: ClosedFormModel) -> RadauOde<'m, 'a> {
        RadauOde {
            model,
            film,
            impact_speed: self.impact,
            error: RefCell::new(None),
            event_level: if self.in_contact {
                model.release_radius / model.c
            } else {
                model.contact_radius / model.c
            },
            in_contact: self.in_contact,
        }
    }

    /// One segment from `t0` to the end or the first event, sampled at `pending`; counts its
    /// steps and evaluations. A film error or an integrator failure ends the run.
    fn integrate(
        &mut self,
        params: &MechanismParams,
        ode: &RadauOde<'_, '_>,
        tf: f64,
        pending: &[f64],
        rtol: f64,
        atol: f64,
    ) -> Result<Solution<f64, [f64; 4]>, MechanismError> {
        let tau = params.mechanism.period();
        let w = params.mechanism.crank_speed.abs();
        let method = ImplicitRungeKutta::radau5()
            .rtol(rtol)
            .atol([atol, atol, atol * w, atol * w])
            .h_max(tau / params.samples_per_turn as f64)
            .h0(1e-8 * tau)
            .max_steps(10_000_000);
        let result = IVP::ode(ode, self.t0, tf + 1e-9 * tau, self.y0)
            .t_eval(pending)
            .event(ode)
            .method(method)
            .solve();
        if let Some(err) = ode.error.borrow_mut().take() {
            return Err(err);
        }
        let t0 = self.t0;
        let sol = result.map_err(|err| {
            use differential_equations::prelude::Error as E;
            let (time, reason) = match &err {
                E::MaxSteps { t, .. } => (*t, "maximum number of steps reached".to_string()),
                E::StepSize { t, .. } => (*t, "step size underflow".to_string()),
                E::Stiffness { t, .. } => (*t, "stiffness detected".to_string()),
                other => (t0, format!("{other:?}")),
            };
            MechanismError::Integration {
                time,
                crank_angle_deg: ode.model.crank_deg(time),
                reason,
            }
        })?;
        self.info.steps += sol.steps.accepted;
        self.info.rejected_steps += sol.steps.rejected;
        self.info.evaluations += sol.evals.function;
        Ok(sol)
    }

    /// The output samples the segment passed before its event (those after it are redone after
    /// the restart), with the loads and the contact weight at each.
    fn record_samples(
        &mut self,
        params: &MechanismParams,
        ode: &RadauOde<'_, '_>,
        sol: &Solution<f64, [f64; 4]>,
        times: &[f64],
        t_event: Option<f64>,
    ) -> Result<(), MechanismError> {
        let tau = params.mechanism.period();
        let c = ode.model.c;
        let n_points = sol.t.len();
        for (i, (t, y)) in sol.t.iter().zip(&sol.y).enumerate() {
            if t_event.is_some() && i + 1 == n_points {
                break; // the event point
            }
            if self.next >= times.len() {
                break;
            }
            if let Some(te) = t_event
                && *t >= te
            {
                break; // samples past the event are redone after the restart
            }
            if (t - times[self.next]).abs() > 1e-9 * tau {
                continue;
            }
            let (_, k, acc, f) = ode.evaluate(times[self.next], y)?;
            self.out.push_sample(
                &params.mechanism,
                &k,
                acc,
                (f.total, f.torque),
                [c * y[0], c * y[1]],
                [c * y[2], c * y[3]],
            );
            self.weights.push(f.weight);
            self.next += 1;
        }
        Ok(())
    }

    /// At the event time `te` with state `y`: record the onset (its impact velocity, floored)
    /// or the release, switch the contact mode and restart from there. Chattering contact
    /// (more than [`MAX_CONTACT_EVENTS`]) is an error.
    fn switch_contact(
        &mut self,
        model: &JointModel<'_>,
        te: f64,
        y: [f64; 4],
    ) -> Result<(), MechanismError> {
        let c = model.c;
        let e = y[0].hypot(y[1]).max(f64::MIN_POSITIVE);
        let radial = c * (y[0] * y[2] + y[1] * y[3]) / e;
        let kind = if self.in_contact {
            ContactEventKind::Release
        } else {
            self.impact = radial.max(model.joint.contact.min_impact_speed);
            ContactEventKind::Onset
        };
        self.in_contact = !self.in_contact;
        if self.events.len() >= MAX_CONTACT_EVENTS {
            return Err(MechanismError::Integration {
                time: te,
                crank_angle_deg: model.crank_deg(te),
                reason: format!(
                    "more than {MAX_CONTACT_EVENTS} contact events (chattering contact)"
                ),
            });
        }
        self.events.push(ContactEvent {
            time: te,
            crank_angle_deg: model.crank_deg(te),
            kind,
            radial_velocity: radial,
        });
        self.t0 = te;
        self.y0 = y;
        Ok(())
    }

    /// The solution: every sample produced (else an error), h_min, contact weights, events and
    /// counts, checked finite.
    fn finish(
        self,
        params: &MechanismParams,
        model: &JointModel<'_>,
        samples: usize,
    ) -> Result<MechanismSolution, MechanismError> {
        let Self {
            out,
            next,
            weights,
            events,
            info,
            ..
        } = self;
        if next != samples {
            return Err(MechanismError::Integration {
                time: out.time.last().copied().unwrap_or(0.0),
                crank_angle_deg: model.crank_deg(out.time.last().copied().unwrap_or(0.0)),
                reason: format!("{next} of {samples} output samples produced"),
            });
        }
        out.finish_lubricated(model.c, params.samples_per_turn, weights, events, info)
    }
}

// ---------------------------------------------------------------------------------------------
// BDF2 (any film), fixed steps or under error control

enum Film {
    Closed(ClosedFormModel),
    /// The film, its state at t^n, the number of feed grooves.
    Reynolds(Box<(ReynoldsFilm, FilmState, usize)>),
}

impl Film {
    /// The joint's film for BDF2: a closed form, or the Reynolds film from the centred journal.
    fn new(film: &JointFilm, params: &MechanismParams) -> Result<Self, MechanismError> {
        Ok(match film {
            JointFilm::ClosedForm(m) => Film::Closed(*m),
            JointFilm::Reynolds(p) => {
                let f = ReynoldsFilm::new((**p).clone()).map_err(|e| MechanismError::Film {
                    time: 0.0,
                    crank_angle_deg: params.mechanism.initial_crank_angle.to_degrees(),
                    eccentricity_ratio: 0.0,
                    reason: e.to_string(),
                })?;
                let state = f.initial_state([0.0, 0.0]);
                let feeds = p.grooves.len();
                Film::Reynolds(Box::new((f, state, feeds)))
            }
        })
    }
}

/// One evaluation of the step residual at a trial ε^{n+1}.
struct Trial {
    residual: [f64; 2],
    rate: [f64; 2],
    /// ε̈ by the BDF2 formula.
    eps_acc: [f64; 2],
    acc: [f64; 2],
    k: Configuration,
    force: JointForce,
    /// ∂F_film/∂ε (Reynolds: the film's exact Jacobian; closed form: None, differences of the
    /// whole residual are used).
    film_jacobian: Option<[[f64; 2]; 2]>,
    film_state: Option<FilmState>,
    /// The film's fields (Reynolds film asked to capture them).
    film_fields: Option<FilmFields>,
}

fn solve2(j: [[f64; 2]; 2], r: [f64; 2]) -> Option<[f64; 2]> {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if !(det.is_finite() && det != 0.0) {
        return None;
    }
    Some([
        (j[1][1] * r[0] - j[0][1] * r[1]) / det,
        (j[0][0] * r[1] - j[1][0] * r[0]) / det,
    ])
}

/// The journal's history for the BDF2 formulas, and the contact state.
#[derive(Debug, Clone, Copy)]
struct History {
    t: f64,
    /// ε^n, ε^{n−1}
    eps: [[f64; 2]; 2],
    /// ε̇^n, ε̇^{n−1}
    rate: [[f64; 2]; 2],
    /// ε̈^n (predictor)
    acc: [f64; 2],
    /// Δt of the step that reached t^n (None before the first step: backward Euler).
    last_dt: Option<f64>,
    in_contact: bool,
    impact: f64,
}

/// Settings of the BDF2 Newton.
#[derive(Debug, Clone, Copy)]
struct NewtonSettings {
    tol: f64,
    max_iter: usize,
}

/// Most halvings of a BDF2 step whose Newton fails (a step is split into up to 2⁶ parts).
const MAX_STEP_SPLITS: usize = 6;

/// BDF2 over the turns: a step (or, under error control, as many as it asks for) to each point
/// of the grid of one turn / `steps_per_turn`, the film fields captured at the snapshot steps,
/// every `steps_per_turn / samples_per_turn`-th grid point recorded as an output sample.
fn solve_bdf2(
    params: &MechanismParams,
    model: &JointModel<'_>,
    film: &mut Film,
    steps_per_turn: usize,
    error_tolerance: Option<f64>,
    newton: NewtonSettings,
) -> Result<MechanismSolution, MechanismError> {
    let dt = params.mechanism.period() / steps_per_turn as f64;
    let stride = steps_per_turn / params.samples_per_turn;
    let mut control = error_tolerance.map(|tol| StepControl::new(&params.mechanism, dt, tol));
    let mut run = Bdf2Run::new(params, model, film, steps_per_turn)?;
    for n in 0..params.turns * steps_per_turn {
        let t1 = (n + 1) as f64 * dt;
        let trial = run.step_to(model, film, n + 1, t1, control.as_mut(), newton)?;
        if (n + 1) % stride == 0 {
            run.record(&params.mechanism, model, &trial);
        }
    }
    run.finish(params, model)
}

/// What a BDF2 run carries from step to step.
struct Bdf2Run {
    hist: History,
    snapshots: Option<FieldSnapshots>,
    info: MechanismInfo,
    events: Vec<ContactEvent>,
    out: MechanismSolution,
    weights: Vec<f64>,
}

impl Bdf2Run {
    /// Centred journal at rest at t = 0, out of contact, its sample recorded (the ideal
    /// configuration, no film force).
    fn new(
        params: &MechanismParams,
        model: &JointModel<'_>,
        film: &mut Film,
        steps_per_turn: usize,
    ) -> Result<Self, MechanismError> {
        let mech = &params.mechanism;
        let hist = History {
            t: 0.0,
            eps: [[0.0; 2]; 2],
            rate: [[0.0; 2]; 2],
            acc: [0.0; 2],
            last_dt: None,
            in_contact: false,
            impact: model.joint.contact.min_impact_speed,
        };
        let snapshots = FieldSnapshots::new(params, film, steps_per_turn)?;
        let mut out = MechanismSolution::default();
        let k = mech.configuration(0.0, [0.0; 2], [0.0; 2])?;
        let acc = mech.accelerations(&k, [0.0; 2], 0.0);
        out.push_sample(mech, &k, acc, ([0.0; 2], 0.0), [0.0; 2], [0.0; 2]);
        Ok(Self {
            hist,
            snapshots,
            info: MechanismInfo::default(),
            events: Vec::new(),
            out,
            weights: vec![0.0],
        })
    }

    /// Advance to the grid point `step` at t1, fixed or under error control, capturing the film
    /// fields when it is a snapshot step. Returns the trial accepted at t1.
    fn step_to(
        &mut self,
        model: &JointModel<'_>,
        film: &mut Film,
        step: usize,
        t1: f64,
        control: Option<&mut StepControl>,
        newton: NewtonSettings,
    ) -> Result<Trial, MechanismError> {
        let snapshot = self
            .snapshots
            .as_ref()
            .is_some_and(|s| s.capture_at(film, step));
        let mut trial = match control {
            None => self.advance(model, film, t1, 0, newton)?,
            Some(ctl) => self.advance_controlled(model, film, t1, ctl, newton)?,
        };
        if let (true, Some(s)) = (snapshot, self.snapshots.as_mut()) {
            s.take(model, film, t1, &mut trial)?;
        }
        Ok(trial)
    }

    /// Advance the history to t1 by one BDF2 step, or — when its Newton fails — by two halves
    /// (recursively, at most [`MAX_STEP_SPLITS`] deep). Returns the trial accepted at t1.
    fn advance(
        &mut self,
        model: &JointModel<'_>,
        film: &mut Film,
        t1: f64,
        depth: usize,
        newton: NewtonSettings,
    ) -> Result<Trial, MechanismError> {
        match bdf2_step(model, film, &self.hist, t1, newton, &mut self.info) {
            Ok((trial, eps)) => {
                self.accept(model, film, t1, eps, &trial);
                Ok(trial)
            }
            Err(MechanismError::NewtonFailed { .. }) if depth < MAX_STEP_SPLITS => {
                let mid = 0.5 * (self.hist.t + t1);
                self.advance(model, film, mid, depth + 1, newton)?;
                self.advance(model, film, t1, depth + 1, newton)
            }
            Err(e) => Err(e),
        }
    }

    /// Advance the history to t1 (a grid point) by as many BDF2 steps as the error control asks
    /// for: a step is accepted when its local error estimate is within the tolerance, and the
    /// next step is h · 0.9 (tol/err)^{1/3} (between 0.2 h and 2 h; third power: the estimate is
    /// O(h³)); a rejected step or a failed Newton is retried shorter. Returns the trial at t1.
    fn advance_controlled(
        &mut self,
        model: &JointModel<'_>,
        film: &mut Film,
        t1: f64,
        ctl: &mut StepControl,
        newton: NewtonSettings,
    ) -> Result<Trial, MechanismError> {
        loop {
            let (h, ta, last) = ctl.next_step(self.hist.t, t1);
            let step_newton = ctl.newton_for(h, newton);
            match bdf2_step(model, film, &self.hist, ta, step_newton, &mut self.info) {
                Ok((trial, eps)) => {
                    let err = local_error(&self.hist, h, eps).unwrap_or(0.0);
                    if !ctl.judge(model, ta, h, err)? {
                        self.info.rejected_steps += 1;
                        continue;
                    }
                    self.accept(model, film, ta, eps, &trial);
                    if last {
                        return Ok(trial);
                    }
                }
                Err(MechanismError::NewtonFailed { .. }) if h > ctl.min => {
                    self.info.rejected_steps += 1;
                    ctl.next = (0.25 * h).max(ctl.min);
                }
                Err(e) => return Err(e),
            }
        }
    }

    /// Take the accepted step to t1 into the history: the film state, the contact state (an
    /// onset or release recorded as an event), the step counted.
    fn accept(
        &mut self,
        model: &JointModel<'_>,
        film: &mut Film,
        t1: f64,
        eps: [f64; 2],
        trial: &Trial,
    ) {
        let hist = &mut self.hist;
        let c = model.c;
        if let (Film::Reynolds(b), Some(state)) = (&mut *film, trial.film_state.clone()) {
            b.1 = state;
        }
        let step_impact = step_impact(model, hist);
        hist.last_dt = Some(t1 - hist.t);
        hist.t = t1;
        hist.eps = [eps, hist.eps[0]];
        hist.rate = [trial.rate, hist.rate[0]];
        hist.acc = trial.eps_acc;
        let r_now = eps[0].hypot(eps[1]) * c;
        let now_contact = if hist.in_contact {
            r_now > model.release_radius
        } else {
            r_now > model.contact_radius
        };
        if now_contact != hist.in_contact {
            let e = eps[0].hypot(eps[1]);
            let radial = c * (eps[0] * trial.rate[0] + eps[1] * trial.rate[1]) / e;
            self.events.push(ContactEvent {
                time: t1,
                crank_angle_deg: model.crank_deg(t1),
                kind: if now_contact {
                    ContactEventKind::Onset
                } else {
                    ContactEventKind::Release
                },
                radial_velocity: radial,
            });
            if now_contact {
                hist.impact = step_impact;
            }
            hist.in_contact = now_contact;
        }
        self.info.steps += 1;
    }

    /// The output sample at the grid point just reached: loads, ε and ε̇, the contact weight.
    fn record(&mut self, mech: &SliderCrankParams, model: &JointModel<'_>, trial: &Trial) {
        let c = model.c;
        let eps = self.hist.eps[0];
        let rate = self.hist.rate[0];
        self.out.push_sample(
            mech,
            &trial.k,
            trial.acc,
            (trial.force.total, trial.force.torque),
            [c * eps[0], c * eps[1]],
            [c * rate[0], c * rate[1]],
        );
        self.weights.push(trial.force.weight);
    }

    /// The solution, with the film field snapshots when they were taken.
    fn finish(
        self,
        params: &MechanismParams,
        model: &JointModel<'_>,
    ) -> Result<MechanismSolution, MechanismError> {
        let mut out = self.out;
        out.film_fields = self.snapshots.map(|s| s.fields);
        out.finish_lubricated(
            model.c,
            params.samples_per_turn,
            self.weights,
            self.events,
            self.info,
        )
    }
}

/// The Reynolds film's field snapshots over the last turn: the steps base + round(k ·
/// steps_per_turn / N), k = 1 … N (distinct for N ≤ steps_per_turn), and the fields taken.
struct FieldSnapshots {
    steps: Vec<usize>,
    fields: MechanismFilmFields,
}

impl FieldSnapshots {
    /// The snapshot steps and the film's grid (None for a closed form or no snapshots); more
    /// snapshots than steps per turn is an error.
    fn new(
        params: &MechanismParams,
        film: &mut Film,
        steps_per_turn: usize,
    ) -> Result<Option<Self>, MechanismError> {
        let n_fields = match film {
            Film::Reynolds(_) => params.field_snapshots,
            Film::Closed(_) => 0,
        };
        if n_fields > steps_per_turn {
            return Err(MechanismError::InvalidParameter {
                name: "field_snapshots (at most steps_per_turn)",
                value: n_fields as f64,
            });
        }
        let Film::Reynolds(b) = film else {
            return Ok(None);
        };
        if n_fields == 0 {
            return Ok(None);
        }
        let base = (params.turns - 1) * steps_per_turn;
        let solver = b.0.solver_mut();
        Ok(Some(Self {
            steps: (1..=n_fields)
                .map(|k| base + (k * steps_per_turn + n_fields / 2) / n_fields)
                .collect(),
            fields: MechanismFilmFields {
                theta: solver.theta_nodes(),
                z: solver.z_nodes(),
                ..Default::default()
            },
        }))
    }

    /// Whether `step` is a snapshot step; if so the film is asked to capture its fields.
    fn capture_at(&self, film: &mut Film, step: usize) -> bool {
        let snapshot = self.steps.binary_search(&step).is_ok();
        if let (true, Film::Reynolds(b)) = (snapshot, film) {
            b.0.set_capture_fields(true);
        }
        snapshot
    }

    /// The fields of the trial accepted at t1 (a snapshot step), the capture switched off.
    fn take(
        &mut self,
        model: &JointModel<'_>,
        film: &mut Film,
        t1: f64,
        trial: &mut Trial,
    ) -> Result<(), MechanismError> {
        let Film::Reynolds(b) = film else {
            return Ok(());
        };
        b.0.set_capture_fields(false);
        let fields = trial
            .film_fields
            .take()
            .ok_or(MechanismError::Unsupported {
                what: "the Reynolds film returned no fields at a snapshot",
            })?;
        self.fields.time.push(t1);
        self.fields.crank_angle_deg.push(model.crank_deg(t1));
        self.fields.fields.push(fields);
        Ok(())
    }
}

/// The BDF2 step-size controller (module docs, "Integration").
#[derive(Debug, Clone, Copy)]
struct StepControl {
    /// Local error tolerance (in ε).
    tol: f64,
    /// |ω|: the Newton tolerance is tightened on steps shorter than a radian of crank.
    rate_scale: f64,
    /// Proposed length of the next step (s).
    next: f64,
    /// Shortest step allowed (s).
    min: f64,
}

impl StepControl {
    /// The controller of a run on the grid `dt`: the first step, backward Euler from rest, is
    /// short (the start transient has time constants of microseconds).
    fn new(mech: &SliderCrankParams, dt: f64, tol: f64) -> Self {
        Self {
            tol,
            rate_scale: mech.crank_speed.abs(),
            next: 1e-3 * dt,
            min: 1e-9 * dt,
        }
    }

    /// The next step from t towards the grid point t1: its length h, its end and whether it
    /// reaches t1. It ends on t1 when the proposed step reaches it (or nearly: no sliver
    /// steps), else covers at most half the rest when it covers more than half of it (two even
    /// steps, not a long one and a sliver).
    fn next_step(&self, t: f64, t1: f64) -> (f64, f64, bool) {
        let remaining = t1 - t;
        let (h, last) = if self.next >= remaining * (1.0 - 1e-9) {
            (remaining, true)
        } else if self.next > 0.5 * remaining {
            (0.5 * remaining, false)
        } else {
            (self.next, false)
        };
        (h, if last { t1 } else { t + h }, last)
    }

    /// The Newton settings of a step of length h: the Newton error δε enters ε̇ as a₀ δε / h,
    /// so on short steps it is kept smaller, that the velocity (and the film's squeeze term) it
    /// perturbs stays within 1 % of the tolerance per radian of crank (floored at round-off).
    fn newton_for(&self, h: f64, newton: NewtonSettings) -> NewtonSettings {
        NewtonSettings {
            tol: newton
                .tol
                .min((0.01 * self.tol * (h * self.rate_scale).min(1.0)).max(1e-14)),
            ..newton
        }
    }

    /// Judge a converged step of length h ending at `ta` by its local error estimate: accepted
    /// (true) or rejected (false), the next step proposed either way; a step of the shortest
    /// length still above the tolerance is an error.
    fn judge(
        &mut self,
        model: &JointModel<'_>,
        ta: f64,
        h: f64,
        err: f64,
    ) -> Result<bool, MechanismError> {
        let ratio = if err > 0.0 {
            0.9 * (self.tol / err).cbrt()
        } else {
            2.0
        };
        if err <= self.tol || h <= self.min {
            if err > self.tol {
                return Err(MechanismError::Integration {
                    time: ta,
                    crank_angle_deg: model.crank_deg(ta),
                    reason: format!(
                        "BDF2 step size underflow: local error {err:.3e} > tolerance {:.3e} at a step of {h:.3e} s",
                        self.tol
                    ),
                });
            }
            self.next = (h * ratio.clamp(0.2, 2.0)).max(self.min);
            Ok(true)
        } else {
            self.next = (h * ratio.clamp(0.2, 0.9)).max(self.min);
            Ok(false)
        }
    }
}

/// Local error estimate of a BDF2 step of length h (Milne's device) from the history at t^n to
/// the corrected ε^{n+1}: the predictor is the quadratic through ε^{n−1}, ε^n with slope ε̇^n,
/// whose error is h²(h + h_p) ε‴/6, against BDF2's −(2/9) h³ ε‴ (constant steps); so LTE ≈
/// (2/9) / (1/3 + 2/9) · |ε_c − ε_p| = 0.4 |ε_c − ε_p| at h = h_p (the constant-step factor is
/// kept for unequal steps), the larger of the two components. Position only: ε̇ is the BDF2
/// derivative of ε, and its own estimate (through ε̈^n) reacts to every kink of the film force —
/// the Reynolds film's force is continuous in ε but its slope jumps whenever a grid node
/// switches between full and cavitated film, so ε⁗ is a train of spikes (module docs,
/// "Integration"). None for the first step (no ε^{n−1}).
fn local_error(hist: &History, h: f64, eps: [f64; 2]) -> Option<f64> {
    let hp = hist.last_dt?;
    let (e, e_prev, slope) = (hist.eps[0], hist.eps[1], hist.rate[0]);
    let mut err: f64 = 0.0;
    for i in 0..2 {
        let q = (e_prev[i] - e[i] + hp * slope[i]) / (hp * hp);
        let predicted = e[i] + h * slope[i] + h * h * q;
        err = err.max((eps[i] - predicted).abs());
    }
    Some(0.4 * err)
}

/// Impact velocity for a step from the history: frozen during a contact, the approach speed
/// at t^n otherwise (floored).
fn step_impact(model: &JointModel<'_>, hist: &History) -> f64 {
    let floor = model.joint.contact.min_impact_speed;
    if hist.in_contact {
        return hist.impact;
    }
    let (e, r) = (hist.eps[0], hist.rate[0]);
    let m = e[0].hypot(e[1]);
    if m > 0.0 {
        (model.c * (e[0] * r[0] + e[1] * r[1]) / m).max(floor)
    } else {
        floor
    }
}

/// One BDF2 step from the history to t1: the predictor, then Newton on ε^{n+1}. Returns the
/// accepted trial and ε.
fn bdf2_step(
    model: &JointModel<'_>,
    film: &mut Film,
    hist: &History,
    t1: f64,
    newton: NewtonSettings,
    info: &mut MechanismInfo,
) -> Result<(Trial, [f64; 2]), MechanismError> {
    let step = Bdf2Step::new(model, hist, t1);
    let eps = step.predict(hist);
    step.newton(film, eps, newton, info)
}

/// The equation of one BDF2 step to t1: ε̈^{n+1} by the BDF2 formulas equals the mechanism's
/// ε̈ at (ε^{n+1}, ε̇^{n+1}) under the joint force with the step's impact velocity.
struct Bdf2Step<'m, 'a> {
    model: &'m JointModel<'a>,
    t1: f64,
    dt: f64,
    /// Variable-step BDF2 (backward Euler on the first step): ẏ^{n+1} = (a₀ y^{n+1} − h)/Δt,
    /// h = a₁ y^n − a₂ y^{n−1} (crate::time_scheme::TimeScheme::bdf2_coefficients), for
    /// y = ε (`hist_e`) and y = ε̇ (`hist_r`).
    a0: f64,
    hist_e: [f64; 2],
    hist_r: [f64; 2],
    impact: f64,
}

impl<'m, 'a> Bdf2Step<'m, 'a> {
    /// The step's BDF2 coefficients from the history and its impact velocity.
    fn new(model: &'m JointModel<'a>, hist: &History, t1: f64) -> Self {
        let dt = t1 - hist.t;
        let [e_n, e_nm1] = hist.eps;
        let [r_n, r_nm1] = hist.rate;
        let (a0, hist_e, hist_r) = match hist.last_dt {
            None => (1.0, e_n, r_n),
            Some(prev) => {
                let (a0, a1, a2) = crate::time_scheme::TimeScheme::bdf2_coefficients(dt / prev);
                (
                    a0,
                    [a1 * e_n[0] - a2 * e_nm1[0], a1 * e_n[1] - a2 * e_nm1[1]],
                    [a1 * r_n[0] - a2 * r_nm1[0], a1 * r_n[1] - a2 * r_nm1[1]],
                )
            }
        };
        Self {
            model,
            t1,
            dt,
            a0,
            hist_e,
            hist_r,
            impact: step_impact(model, hist),
        }
    }

    /// Predictor: second-order extrapolation from ε^n, ε̇^n, ε̈^n.
    fn predict(&self, hist: &History) -> [f64; 2] {
        let (e_n, r_n, a_n, dt) = (hist.eps[0], hist.rate[0], hist.acc, self.dt);
        [
            e_n[0] + dt * r_n[0] + 0.5 * dt * dt * a_n[0],
            e_n[1] + dt * r_n[1] + 0.5 * dt * dt * a_n[1],
        ]
    }

    /// ε̇^{n+1} and ε̈^{n+1} of a trial ε^{n+1} by the BDF2 formulas.
    fn rates(&self, eps: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let (a0, dt) = (self.a0, self.dt);
        let rate = [
            (a0 * eps[0] - self.hist_e[0]) / dt,
            (a0 * eps[1] - self.hist_e[1]) / dt,
        ];
        let acc_bdf = [
            (a0 * rate[0] - self.hist_r[0]) / dt,
            (a0 * rate[1] - self.hist_r[1]) / dt,
        ];
        (rate, acc_bdf)
    }

    /// Newton on ε^{n+1} from `eps`, with the Jacobian kept while the updates contract (chord
    /// steps) and taken afresh when they do not; the evaluated iterate is accepted once the next
    /// update is below the tolerance (its film state then belongs to it). Globalised for the
    /// stiff, kinked contact law by [`Self::line_search`]; when that finds no descent, a fresh
    /// Jacobian, or failure.
    fn newton(
        &self,
        film: &mut Film,
        mut eps: [f64; 2],
        settings: NewtonSettings,
        info: &mut MechanismInfo,
    ) -> Result<(Trial, [f64; 2]), MechanismError> {
        let NewtonSettings { tol, max_iter } = settings;
        let failed = |update, iterations| MechanismError::NewtonFailed {
            time: self.t1,
            crank_angle_deg: self.model.crank_deg(self.t1),
            update,
            iterations,
        };
        let mut trial = self.evaluate(film, eps, true, info)?;
        let mut jac: Option<[[f64; 2]; 2]> = None;
        let mut fresh = false;
        let mut prev_update = f64::INFINITY;
        let mut last_update = f64::INFINITY;
        for iter in 1..=max_iter {
            let j = match jac {
                Some(j) => j,
                None => {
                    let j = self.fresh_jacobian(film, eps, &mut trial, info)?;
                    jac = Some(j);
                    fresh = true;
                    j
                }
            };
            let Some(d) = solve2(j, trial.residual) else {
                return Err(failed(f64::INFINITY, iter));
            };
            last_update = d[0].hypot(d[1]);
            if last_update <= tol {
                return Ok((trial, eps));
            }
            let r0 = trial.residual[0].hypot(trial.residual[1]);
            match self.line_search(film, eps, d, last_update, r0, tol, info)? {
                Some((cand, t, lam)) => {
                    eps = cand;
                    trial = t;
                    if !fresh && last_update > 0.3 * prev_update {
                        jac = None;
                    }
                    fresh = false;
                    prev_update = lam * last_update;
                }
                None if !fresh => {
                    jac = None; // retry from ε with a fresh Jacobian
                    prev_update = f64::INFINITY;
                }
                None => break,
            }
        }
        Err(failed(last_update, max_iter))
    }

    /// The Jacobian at ε taken afresh; the Reynolds film's Jacobian belongs to its last solve,
    /// so a trial without one is solved at ε again first.
    fn fresh_jacobian(
        &self,
        film: &mut Film,
        eps: [f64; 2],
        trial: &mut Trial,
        info: &mut MechanismInfo,
    ) -> Result<[[f64; 2]; 2], MechanismError> {
        if trial.film_jacobian.is_none() && matches!(film, Film::Reynolds(_)) {
            *trial = self.evaluate(film, eps, true, info)?;
        }
        self.jacobian(film, eps, trial)
    }

    /// The damped update ε − λ d: λ at most [`MAX_NEWTON_STEP`] / |d| (and 1), halved until the
    /// residual falls below `r0` or the step is within 10 × the tolerance (at most 8 halvings).
    /// Returns the new ε, its trial and λ; None when no halving decreased the residual.
    #[allow(clippy::too_many_arguments)]
    fn line_search(
        &self,
        film: &mut Film,
        eps: [f64; 2],
        d: [f64; 2],
        update: f64,
        r0: f64,
        tol: f64,
        info: &mut MechanismInfo,
    ) -> Result<Option<([f64; 2], Trial, f64)>, MechanismError> {
        let mut lam = (MAX_NEWTON_STEP / update).min(1.0);
        for _ in 0..=8 {
            let cand = [eps[0] - lam * d[0], eps[1] - lam * d[1]];
            let t = self.evaluate(film, cand, false, info)?;
            let rn = t.residual[0].hypot(t.residual[1]);
            if rn < r0 || lam * update <= 10.0 * tol {
                return Ok(Some((cand, t, lam)));
            }
            lam *= 0.5;
        }
        Ok(None)
    }

    /// The residual of the step at the trial ε (one film step for the Reynolds film), counted
    /// as an evaluation; with the film's Jacobian when `want_jacobian`.
    fn evaluate(
        &self,
        film: &mut Film,
        eps: [f64; 2],
        want_jacobian: bool,
        info: &mut MechanismInfo,
    ) -> Result<Trial, MechanismError> {
        info.evaluations += 1;
        let model = self.model;
        let c = model.c;
        let (rate, acc_bdf) = self.rates(eps);
        let e = [c * eps[0], c * eps[1]];
        let ed = [c * rate[0], c * rate[1]];
        let mut film_step = FilmStep::default();
        let (g, k, acc, force) = match film {
            Film::Closed(m) => {
                let m = *m;
                model.eps_acceleration(self.t1, eps, rate, |k| {
                    model.blend(e, ed, k.rod_rate, self.impact, || {
                        model.closed_film(m, eps, rate, k.rod_rate)
                    })
                })?
            }
            Film::Reynolds(b) => {
                self.reynolds_force(b, eps, rate, want_jacobian, &mut film_step, info)?
            }
        };
        Ok(Trial {
            residual: [acc_bdf[0] - g[0], acc_bdf[1] - g[1]],
            rate,
            eps_acc: acc_bdf,
            acc,
            k,
            force,
            film_jacobian: film_step.jacobian,
            film_state: film_step.state,
            film_fields: film_step.fields,
        })
    }

    /// The mechanism's ε̈ at (ε, ε̇) under the Reynolds film's force (one film step over Δt from
    /// its state at t^n, the journal clamped to the end of the blend band in dry contact),
    /// blended with the contact; the film's next state, fields and Jacobian into `out`.
    #[allow(clippy::type_complexity)]
    fn reynolds_force(
        &self,
        b: &mut (ReynoldsFilm, FilmState, usize),
        eps: [f64; 2],
        rate: [f64; 2],
        want_jacobian: bool,
        out: &mut FilmStep,
        info: &mut MechanismInfo,
    ) -> Result<([f64; 2], Configuration, [f64; 2], JointForce), MechanismError> {
        let (model, t, c) = (self.model, self.t1, self.model.c);
        let (rf, state, feeds) = b;
        let e = [c * eps[0], c * eps[1]];
        let ed = [c * rate[0], c * rate[1]];
        let r = eps[0].hypot(eps[1]);
        let fe = if r > model.film_limit {
            [eps[0] * model.film_limit / r, eps[1] * model.film_limit / r]
        } else {
            eps
        };
        let feeds = *feeds;
        let mut jac_slot = None;
        let res = model.eps_acceleration(t, eps, rate, |k| {
            let cond = OperatingConditions {
                journal_speed: k.rod_rate,
                bearing_speed: 0.0,
                feed_pressures: vec![0.0; feeds],
            };
            info.film_steps += 1;
            let (resp, next) = rf
                .step(state, fe, self.dt, &cond)
                .map_err(|e| e.to_string())?;
            out.state = Some(next);
            out.fields = resp.fields;
            let (f, torque) = (resp.film_force, resp.friction_torque_journal);
            let blended = model.blend(e, ed, k.rod_rate, self.impact, || Ok((f, torque)))?;
            if want_jacobian && blended.weight < 1.0 {
                jac_slot = rf.force_jacobian().map(|j| j.map_err(|e| e.to_string()));
            }
            Ok(blended)
        })?;
        if let Some(j) = jac_slot {
            out.jacobian = Some(j.map_err(|reason| MechanismError::Film {
                time: t,
                crank_angle_deg: model.crank_deg(t),
                eccentricity_ratio: r,
                reason,
            })?);
        }
        Ok(res)
    }

    /// Jacobian of the step's residual with respect to ε^{n+1} (module docs): differences of the
    /// residual with the Reynolds film's force frozen (the closed form evaluated), plus the
    /// film's exact ∂F/∂ε through ∂g/∂F.
    fn jacobian(
        &self,
        film: &Film,
        eps: [f64; 2],
        trial: &Trial,
    ) -> Result<[[f64; 2]; 2], MechanismError> {
        // The trial's film force and torque before the blend, for the frozen evaluation.
        let frozen = match film {
            Film::Closed(_) => None,
            Film::Reynolds(_) => Some((trial.force.film, trial.force.film_torque)),
        };
        let r0 = self.residual(film, eps, frozen)?;
        let mut jac = [[0.0; 2]; 2];
        for j in 0..2 {
            let h = 1e-7 * eps[0].hypot(eps[1]).max(1e-3);
            let mut ep = eps;
            ep[j] += h;
            let r1 = self.residual(film, ep, frozen)?;
            for i in 0..2 {
                jac[i][j] = (r1[i] - r0[i]) / h;
            }
        }
        if let (Some(jf), Some((f0, torque0))) = (trial.film_jacobian, frozen) {
            // − ∂g/∂F · (1 − s) ∂F_film/∂ε; ∂g/∂F by differences (g is linear in F).
            let scale = f0[0].hypot(f0[1]).max(1.0);
            let mut dgdf = [[0.0; 2]; 2];
            for j in 0..2 {
                let mut f1 = f0;
                f1[j] += scale * 1e-6;
                let r1 = self.residual(film, eps, Some((f1, torque0)))?;
                for i in 0..2 {
                    // r = acc − g: ∂r/∂F = −∂g/∂F (the blend's (1 − s) is inside).
                    dgdf[i][j] = (r1[i] - r0[i]) / (scale * 1e-6);
                }
            }
            for i in 0..2 {
                for j in 0..2 {
                    jac[i][j] += dgdf[i][0] * jf[0][j] + dgdf[i][1] * jf[1][j];
                }
            }
        }
        Ok(jac)
    }

    /// The residual at ε with the film force and torque given (frozen) or the closed form
    /// evaluated, for the Jacobian's differences.
    fn residual(
        &self,
        film: &Film,
        eps: [f64; 2],
        frozen: Option<([f64; 2], f64)>,
    ) -> Result<[f64; 2], MechanismError> {
        let (model, c, impact) = (self.model, self.model.c, self.impact);
        let (rate, acc_bdf) = self.rates(eps);
        let e = [c * eps[0], c * eps[1]];
        let ed = [c * rate[0], c * rate[1]];
        let (g, ..) = model.eps_acceleration(self.t1, eps, rate, |k| match (film, frozen) {
            (_, Some(f)) => model.blend(e, ed, k.rod_rate, impact, || Ok(f)),
            (Film::Closed(m), None) => model.blend(e, ed, k.rod_rate, impact, || {
                model.closed_film(*m, eps, rate, k.rod_rate)
            }),
            (Film::Reynolds(_), None) => Err("Reynolds film needs a frozen force".to_string()),
        })?;
        Ok([acc_bdf[0] - g[0], acc_bdf[1] - g[1]])
    }
}

/// What one Reynolds film step of a trial leaves besides its force: the film's state at t1, its
/// fields (when captured) and its Jacobian (when asked for and the film acts).
#[derive(Default)]
struct FilmStep {
    state: Option<FilmState>,
    fields: Option<FilmFields>,
    jacobian: Option<[[f64; 2]; 2]>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::ContactParams;

    #[test]
    fn joint_force_is_continuous_across_the_blend_band() {
        let mech = SliderCrankParams::flores2009();
        let joint = LubricatedJointParams::flores2009();
        let m = JointModel::new(&mech, &joint);
        let c = m.c;
        let dir = [0.6f64, -0.8];
        let rate = [0.3 * c * 100.0, -0.1 * c * 100.0]; // ė (m/s), towards the wall and across
        let force = |r: f64| {
            let e = [r * dir[0], r * dir[1]];
            let eps = [e[0] / c, e[1] / c];
            let er = [rate[0] / c, rate[1] / c];
            m.blend(e, rate, 200.0, 0.05, || {
                m.closed_film(ClosedFormModel::PinkusSternlicht, eps, er, 200.0)
            })
            .unwrap()
        };
        let k = joint.contact;
        for edge in [m.contact_radius, m.contact_radius + k.blend_width] {
            let (a, b) = (force(edge - 1e-13), force(edge + 1e-13));
            let scale = norm(a.total).max(norm(b.total));
            let jump = norm([a.total[0] - b.total[0], a.total[1] - b.total[1]]);
            // 2e-13 m across the edge: a continuous force changes by its slope × 2e-13 m; the
            // film's stiffness there is < 1e13 N/m, so a jump above 1 % of F is a discontinuity.
            assert!(jump < 0.01 * scale, "edge {edge}: {a:?} vs {b:?}");
        }
        // Inside the band the weight is linear in the penetration.
        let mid = force(m.contact_radius + 0.5 * k.blend_width);
        assert!((mid.weight - 0.5).abs() < 1e-6);
        // Beyond the band: dry only (film not evaluated even past ε = 1).
        let dry = m
            .blend(
                [1.01 * c * dir[0], 1.01 * c * dir[1]],
                rate,
                200.0,
                0.05,
                || Err("film must not be evaluated".into()),
            )
            .unwrap();
        assert_eq!(dry.weight, 1.0);
        assert!(
            dry.total[0] * dir[0] + dry.total[1] * dir[1] < 0.0,
            "pushes the journal back"
        );
    }

    fn norm(v: [f64; 2]) -> f64 {
        v[0].hypot(v[1])
    }

    #[test]
    fn bad_inputs_are_errors() {
        let mut p = MechanismParams::flores2009();
        p.turns = 0;
        assert!(matches!(
            solve_mechanism(&p),
            Err(MechanismError::InvalidParameter { name: "turns", .. })
        ));
        let mut p = MechanismParams::flores2009();
        p.integrator = Integrator::Bdf2 {
            steps_per_turn: 500,
            error_tolerance: None,
            newton_tolerance: 1e-9,
            max_newton_iterations: 10,
        };
        assert!(solve_mechanism(&p).is_err());
        let mut joint = LubricatedJointParams::flores2009();
        joint.film = JointFilm::Reynolds(Box::new(joint.reynolds_params()));
        let mut p = MechanismParams::flores2009();
        p.joint = RodSliderJoint::Lubricated(joint.clone());
        assert!(matches!(
            solve_mechanism(&p),
            Err(MechanismError::Unsupported { .. })
        ));
        // A Reynolds film of another bearing.
        let mut other = joint.reynolds_params();
        other.clearance *= 2.0;
        joint.film = JointFilm::Reynolds(Box::new(other));
        p.joint = RodSliderJoint::Lubricated(joint);
        p.integrator = Integrator::bdf2_fixed();
        assert!(matches!(
            solve_mechanism(&p),
            Err(MechanismError::InvalidParameter { .. })
        ));
        let mut joint = LubricatedJointParams::flores2009();
        joint.contact = ContactParams {
            blend_width: 2.0 * joint.contact.boundary_layer,
            ..joint.contact
        };
        p.joint = RodSliderJoint::Lubricated(joint);
        assert!(solve_mechanism(&p).is_err());
        let mut p = MechanismParams::flores2009();
        p.mechanism.rod.length = 0.04;
        assert!(solve_mechanism(&p).is_err());
    }

    /// The ideal run reproduces the closed-form inverse dynamics at every sample, and its
    /// driving work over a turn is zero (a conservative mechanism at constant speed).
    #[test]
    fn ideal_run_has_zero_net_drive_work_per_turn() {
        let mut p = MechanismParams::flores2009();
        p.joint = RodSliderJoint::Ideal;
        p.turns = 1;
        p.samples_per_turn = 3600;
        let s = solve_mechanism(&p).unwrap();
        let w = p.mechanism.crank_speed;
        let (mut net, mut abs) = (0.0, 0.0);
        for i in 1..s.time.len() {
            let dt = s.time[i] - s.time[i - 1];
            let (a, b) = (s.loads[i].crank_moment * w, s.loads[i - 1].crank_moment * w);
            net += 0.5 * (a + b) * dt;
            abs += 0.5 * (a.abs() + b.abs()) * dt;
        }
        // Trapezoid over a periodic smooth integrand: spectrally accurate; round-off ~1e-13.
        assert!(net.abs() < 1e-9 * abs, "{net} of {abs}");
        assert!(s.info.min_film_thickness.is_none() && s.min_film_thickness.is_empty());
    }
}
