//! `CASE.h5` of a mechanism case: netCDF-4 style (dimension scales; `units` and `long_name` on
//! every variable), the writer helpers of [`crate::output::hdf5`].
//!
//! ```text
//! /                      attrs: Conventions, title, source, history, case_name, case_text,
//! │                             case_path, case_kind = "mechanism", description, jbearing_version,
//! │                             git_commit, wall_time_s, started_utc, runs
//! ├── parameters/        scalars: crank_length, …, slider_mass, crank_speed, and for a
//! │                      lubricated joint bearing_radius, journal_radius, radial_clearance,
//! │                      joint_length, viscosity, contact_*; attrs joint, film, integrator
//! ├── lubricated/        attrs: joint, film, integrator, the run's info (steps, rejected_steps,
//! │   │                  evaluations, film_steps, max_joint_force, max_crank_moment,
//! │   │                  max_eccentricity_ratio, min_film_thickness, min_film_crank_angle,
//! │   │                  periodicity_change; NaN where not defined), contact_onsets
//! │   │  time(time) [s]                     coordinate, from 0 over all turns
//! │   │  crank_angle(time) [degree]         auxiliary coordinate, not wrapped
//! │   │  body(body)                         "crank", "rod", "slider"
//! │   │  body_position_x/y(time, body) [m], body_angle(time, body) [rad],
//! │   │  body_velocity_x/y(time, body) [m s-1], body_angular_velocity(time, body) [rad s-1]
//! │   │  joint_force_x/y/magnitude(time) [N]        rod–slider joint, force on the rod
//! │   │  crank_pin_force_x/y, ground_pivot_force_x/y, guide_normal_force (time) [N]
//! │   │  crank_moment(time) [N m]                   driving moment
//! │   │  rod_slider_torque(time) [N m]              joint moment on the rod (friction)
//! │   │  eccentricity_x/y(time) [m], eccentricity_ratio(time) [1]   journal orbit
//! │   │  eccentricity_rate_x/y(time) [m s-1]
//! │   │  min_film_thickness(time) [m], contact_weight(time) [1]
//! │   │  contact_event(contact_event)       index (may be empty)
//! │   │  contact_event_time [s], contact_event_crank_angle [degree],
//! │   │  contact_event_kind ("onset"/"release"), contact_event_radial_velocity [m s-1]
//! │   └── fields/        Reynolds film only, `field_snapshots` instants of the last turn
//! │      field_crank_angle(field_crank_angle) [degree]  dimension, not wrapped
//! │      field_time(field_crank_angle) [s]              auxiliary coordinate
//! │      theta(theta) [rad], z(z) [m]                   the film grid
//! │      pressure(field_crank_angle, theta, z) [Pa]     gauge, p ≥ p_cav
//! │      film_content(field_crank_angle, theta, z) [1] density ratio / film fraction
//! └── ideal/             as lubricated/ without the orbit, film and contact variables
//! ```
//!
//! The `fields/` group is the one bearing cases write (`FileWriter::write_fields`).

use std::path::Path;

use hdf5_metno as h5;
use jbearing_solvers::mechanism::{
    ContactEvent, ContactEventKind, ContactParams, JointFilm, LubricatedJointParams,
    MechanismParams, MechanismSolution, RodSliderJoint,
};
use ndarray::{Array2, Array3};

use super::{IDEAL, LUBRICATED, MechanismResults};
use crate::output::hdf5::FileWriter;
use crate::output::{Field, FieldSnapshots, OutputError, names, write_atomically};

type Res<T> = Result<T, OutputError>;

/// Write the results to `path` atomically.
pub fn write_file(r: &MechanismResults, path: &Path) -> Res<()> {
    write_atomically(path, |tmp| {
        let file = h5::File::create(tmp).map_err(|source| OutputError::Hdf5 {
            path: path.to_path_buf(),
            context: "creating the file".into(),
            source,
        })?;
        let mut w = FileWriter::new(path);
        write_root(&mut w, &file, r)?;
        write_parameters(&mut w, &file, r)?;
        for (name, s) in r.runs() {
            write_run(&mut w, &file, r, name, s)?;
        }
        file.close().map_err(w.err("closing the file"))
    })
}

fn int_attr(w: &FileWriter, loc: &h5::Location, name: &str, v: i64) -> Res<()> {
    loc.new_attr::<i64>()
        .shape(())
        .create(name)
        .and_then(|a| a.write_scalar(&v))
        .map_err(w.err(format!("attribute {name}")))
}

fn write_root(w: &mut FileWriter, file: &h5::File, r: &MechanismResults) -> Res<()> {
    let run = crate::output::RunInfo::for_this_build(r.wall_time, &r.started_utc);
    let c = &r.case;
    w.str_attr(
        file,
        "title",
        &format!("jbearing mechanism results for case '{}'", c.name),
    )?;
    w.str_attr(file, "Conventions", crate::output::layout::CONVENTIONS)?;
    w.str_attr(
        file,
        "source",
        &format!(
            "jbearing {} (commit {}), jbearing_solvers::mechanism::solve_mechanism",
            run.jbearing_version, run.git_commit
        ),
    )?;
    w.str_attr(
        file,
        "history",
        &format!("{} jbearing run of case '{}'", run.started_utc, c.name),
    )?;
    w.str_attr(file, "case_name", &c.name)?;
    w.str_attr(file, "case_kind", "mechanism")?;
    w.str_attr(file, "description", &c.description)?;
    w.str_attr(file, "case_text", &c.text)?;
    let abs = std::fs::canonicalize(&c.path).unwrap_or_else(|_| c.path.clone());
    w.str_attr(file, "case_path", &abs.display().to_string())?;
    w.str_attr(file, "jbearing_version", &run.jbearing_version)?;
    w.str_attr(file, "git_commit", &run.git_commit)?;
    w.f64_attr(file, "wall_time_s", run.wall_time)?;
    w.str_attr(file, "started_utc", &run.started_utc)?;
    let runs: Vec<&str> = r.runs().iter().map(|(n, _)| *n).collect();
    w.str_attr(file, "runs", &runs.join(" "))?;
    w.str_attr(
        file,
        "film_fields",
        "not stored: the mechanism solver keeps no film fields",
    )
}

/// The `parameters/` group: the mechanism's and the joint's inputs as scalars, the joint, film
/// and integrator names as attributes.
fn write_parameters(w: &mut FileWriter, file: &h5::File, r: &MechanismResults) -> Res<()> {
    let g = file
        .create_group("parameters")
        .map_err(w.err("group parameters"))?;
    let p = &r.case.params;
    let mut values = mechanism_parameters(p);
    if let RodSliderJoint::Lubricated(j) = &p.joint {
        values.extend(joint_parameters(j));
    }
    for (name, v, units, long) in values {
        w.scalar(&g, name, v, units, long)?;
    }
    let joint = if r.case.lubricated_joint().is_some() {
        LUBRICATED
    } else {
        IDEAL
    };
    w.str_attr(&g, "joint", joint)?;
    w.str_attr(&g, "film", &r.case.film_name)?;
    w.str_attr(&g, "integrator", &r.case.integrator_name)
}

/// A scalar of `parameters/`: name, value, units, long name.
type Parameter = (&'static str, f64, &'static str, &'static str);

/// The bodies, the crank drive, gravity and the output sampling.
fn mechanism_parameters(p: &MechanismParams) -> Vec<Parameter> {
    let m = &p.mechanism;
    vec![
        ("crank_length", m.crank.length, "m", "crank length O-A"),
        ("crank_mass", m.crank.mass, "kg", "crank mass"),
        (
            "crank_inertia",
            m.crank.inertia,
            "kg m2",
            "crank moment of inertia about its centre of mass",
        ),
        (
            "crank_center_of_mass",
            m.crank.center_of_mass,
            "m",
            "crank centre of mass from the ground pivot O",
        ),
        ("rod_length", m.rod.length, "m", "connecting rod length A-B"),
        ("rod_mass", m.rod.mass, "kg", "connecting rod mass"),
        (
            "rod_inertia",
            m.rod.inertia,
            "kg m2",
            "rod moment of inertia about its centre of mass",
        ),
        (
            "rod_center_of_mass",
            m.rod.center_of_mass,
            "m",
            "rod centre of mass from the crank pin A",
        ),
        ("slider_mass", m.slider_mass, "kg", "slider mass"),
        (
            "crank_speed",
            m.crank_speed,
            "rad s-1",
            "constant crank speed",
        ),
        (
            "initial_crank_angle",
            m.initial_crank_angle,
            "rad",
            "crank angle at t = 0",
        ),
        ("gravity_x", m.gravity[0], "m s-2", "gravity, x"),
        ("gravity_y", m.gravity[1], "m s-2", "gravity, y"),
        ("turns", p.turns as f64, "1", "crank turns simulated"),
        (
            "samples_per_turn",
            p.samples_per_turn as f64,
            "1",
            "output samples per turn",
        ),
    ]
}

/// The lubricated joint's geometry and viscosity, its contact law and the grid of a Reynolds
/// film.
fn joint_parameters(j: &LubricatedJointParams) -> Vec<Parameter> {
    let mut values: Vec<Parameter> = vec![
        (
            "bearing_radius",
            j.bearing_radius,
            "m",
            "joint bearing radius R_b",
        ),
        (
            "journal_radius",
            j.journal_radius,
            "m",
            "joint journal radius R_j",
        ),
        (
            "radial_clearance",
            j.radial_clearance(),
            "m",
            "joint radial clearance c = R_b - R_j",
        ),
        ("joint_length", j.length, "m", "joint length L"),
        ("viscosity", j.viscosity, "Pa s", "dynamic viscosity"),
    ];
    values.extend(contact_parameters(&j.contact));
    if let JointFilm::Reynolds(rp) = &j.film {
        values.extend([
            (
                "grid_n_theta",
                rp.grid.n_theta as f64,
                "1",
                "Reynolds grid nodes around",
            ),
            (
                "grid_n_z",
                rp.grid.n_z as f64,
                "1",
                "Reynolds grid nodes along",
            ),
        ]);
    }
    values
}

/// The dry-contact law of the lubricated joint: elastic constants, restitution, boundary layer
/// and blend.
fn contact_parameters(cp: &ContactParams) -> Vec<Parameter> {
    vec![
        (
            "contact_journal_youngs_modulus",
            cp.journal_youngs_modulus,
            "Pa",
            "Young's modulus of the journal",
        ),
        (
            "contact_journal_poisson_ratio",
            cp.journal_poisson_ratio,
            "1",
            "Poisson's ratio of the journal",
        ),
        (
            "contact_bearing_youngs_modulus",
            cp.bearing_youngs_modulus,
            "Pa",
            "Young's modulus of the bearing",
        ),
        (
            "contact_bearing_poisson_ratio",
            cp.bearing_poisson_ratio,
            "1",
            "Poisson's ratio of the bearing",
        ),
        (
            "contact_restitution",
            cp.restitution,
            "1",
            "coefficient of restitution",
        ),
        (
            "contact_boundary_layer",
            cp.boundary_layer,
            "m",
            "boundary layer h_b: dry contact starts when h_min falls below it",
        ),
        (
            "contact_blend_width",
            cp.blend_width,
            "m",
            "width e0 of the film-to-contact blend",
        ),
        (
            "contact_min_impact_speed",
            cp.min_impact_speed,
            "m s-1",
            "floor on the impact velocity",
        ),
    ]
}

/// One run's group: its attributes, the time coordinates, the body states and the loads, and for
/// the lubricated joint the journal orbit, the contact events and the film fields.
fn write_run(
    w: &mut FileWriter,
    file: &h5::File,
    r: &MechanismResults,
    name: &str,
    s: &MechanismSolution,
) -> Res<()> {
    let g = file
        .create_group(name)
        .map_err(w.err(format!("group {name}")))?;
    let lubricated = name == LUBRICATED;
    write_run_attributes(w, &g, r, name, s)?;
    let time = w.coordinate(&g, "time", &s.time, "s", "time from the start of the run")?;
    let crank = w.variable(&g, "crank_angle", &s.crank_angle_deg, &[&time])?;
    w.str_attr(&crank, "units", "degree")?;
    w.str_attr(&crank, "long_name", "crank angle (from +x, not wrapped)")?;
    let series = Series { g: &g, time: &time };
    write_body_states(w, &series, s)?;
    write_loads(w, &series, s, lubricated)?;
    if !lubricated {
        return Ok(());
    }
    write_orbit(w, &series, r, s)?;
    write_contact_events(w, &g, &s.contact_events)?;
    if let Some(ff) = &s.film_fields {
        w.write_fields(&g, name, &field_snapshots(ff))?;
    }
    Ok(())
}

/// The run group's attributes: joint, film and integrator names and the run's info (NaN where
/// not defined), with the count of contact onsets.
fn write_run_attributes(
    w: &mut FileWriter,
    g: &h5::Group,
    r: &MechanismResults,
    name: &str,
    s: &MechanismSolution,
) -> Res<()> {
    let lubricated = name == LUBRICATED;
    w.str_attr(g, "joint", name)?;
    w.str_attr(g, "film", if lubricated { &r.case.film_name } else { "" })?;
    w.str_attr(
        g,
        "integrator",
        if lubricated {
            &r.case.integrator_name
        } else {
            "closed-form kinematics and inverse dynamics"
        },
    )?;
    let info = &s.info;
    int_attr(w, g, "steps", info.steps as i64)?;
    int_attr(w, g, "rejected_steps", info.rejected_steps as i64)?;
    int_attr(w, g, "evaluations", info.evaluations as i64)?;
    int_attr(w, g, "film_steps", info.film_steps as i64)?;
    w.f64_attr(g, "max_joint_force", info.max_joint_force)?;
    w.f64_attr(g, "max_crank_moment", info.max_crank_moment)?;
    w.f64_attr(g, "max_eccentricity_ratio", info.max_eccentricity_ratio)?;
    w.f64_attr(
        g,
        "min_film_thickness",
        info.min_film_thickness.unwrap_or(f64::NAN),
    )?;
    w.f64_attr(
        g,
        "min_film_crank_angle",
        info.min_film_crank_angle_deg.unwrap_or(f64::NAN),
    )?;
    w.f64_attr(
        g,
        "periodicity_change",
        info.periodicity_change.unwrap_or(f64::NAN),
    )?;
    let onsets = s
        .contact_events
        .iter()
        .filter(|e| e.kind == ContactEventKind::Onset)
        .count();
    int_attr(w, g, "contact_onsets", onsets as i64)
}

/// A run group with its time coordinate: where the `(time)` series go.
struct Series<'a> {
    g: &'a h5::Group,
    time: &'a h5::Dataset,
}

impl Series<'_> {
    /// One variable along time, with its units, long name and the crank angle as coordinate.
    fn write(
        &self,
        w: &mut FileWriter,
        vname: &str,
        v: &[f64],
        units: &str,
        long: &str,
    ) -> Res<()> {
        let ds = w.variable(self.g, vname, v, &[self.time])?;
        w.str_attr(&ds, "units", units)?;
        w.str_attr(&ds, "long_name", long)?;
        w.str_attr(&ds, "coordinates", "crank_angle")
    }
}

/// `f(i)` at every output sample `i < n`.
fn column(n: usize, f: impl Fn(usize) -> f64) -> Vec<f64> {
    (0..n).map(f).collect()
}

/// The three bodies' positions, angles and velocities along `(time, body)`.
fn write_body_states(w: &mut FileWriter, series: &Series, s: &MechanismSolution) -> Res<()> {
    let bodies = ["crank".to_string(), "rod".into(), "slider".into()];
    let body = w.string_coordinate(series.g, "body", &bodies, "body of the mechanism")?;
    let n = s.time.len();
    type BodyGet = fn(&jbearing_solvers::mechanism::BodyState) -> f64;
    let body_vars: [(&str, &str, &str, BodyGet); 6] = [
        ("body_position_x", "m", "centre of mass, x", |b| {
            b.position[0]
        }),
        ("body_position_y", "m", "centre of mass, y", |b| {
            b.position[1]
        }),
        ("body_angle", "rad", "angle of the body axis from +x", |b| {
            b.angle
        }),
        (
            "body_velocity_x",
            "m s-1",
            "velocity of the centre of mass, x",
            |b| b.velocity[0],
        ),
        (
            "body_velocity_y",
            "m s-1",
            "velocity of the centre of mass, y",
            |b| b.velocity[1],
        ),
        (
            "body_angular_velocity",
            "rad s-1",
            "angular velocity",
            |b| b.angular_velocity,
        ),
    ];
    for (vname, units, long, get) in body_vars {
        let a = Array2::from_shape_fn((n, 3), |(i, k)| get(&s.bodies[i][k]));
        let ds = w.variable_2d(series.g, vname, &a, [series.time, &body], units, long)?;
        w.str_attr(&ds, "coordinates", "crank_angle")?;
    }
    Ok(())
}

/// The joint, pin, pivot and guide forces and the crank moment along time; for the lubricated
/// joint also the joint's moment on the rod.
fn write_loads(
    w: &mut FileWriter,
    series: &Series,
    s: &MechanismSolution,
    lubricated: bool,
) -> Res<()> {
    let n = s.time.len();
    let l = &s.loads;
    write_joint_force(w, series, s, lubricated)?;
    for (vname, k, long) in [
        (
            "crank_pin_force_x",
            0,
            "crank pin A: force on the rod from the crank, x",
        ),
        (
            "crank_pin_force_y",
            1,
            "crank pin A: force on the rod from the crank, y",
        ),
    ] {
        series.write(w, vname, &column(n, |i| l[i].crank_pin[k]), "N", long)?;
    }
    for (vname, k, long) in [
        (
            "ground_pivot_force_x",
            0,
            "ground pivot O: force on the crank, x",
        ),
        (
            "ground_pivot_force_y",
            1,
            "ground pivot O: force on the crank, y",
        ),
    ] {
        series.write(w, vname, &column(n, |i| l[i].ground_pivot[k]), "N", long)?;
    }
    series.write(
        w,
        "guide_normal_force",
        &column(n, |i| l[i].guide_normal),
        "N",
        "guide: normal force on the slider, y",
    )?;
    series.write(
        w,
        "crank_moment",
        &column(n, |i| l[i].crank_moment),
        "N m",
        "driving moment on the crank (counter-clockwise)",
    )?;
    if !lubricated {
        return Ok(());
    }
    series.write(
        w,
        "rod_slider_torque",
        &column(n, |i| l[i].rod_slider_torque),
        "N m",
        "rod–slider joint: moment on the rod about the journal centre (film friction torque and \
         dry-contact friction moment where switched on, else 0; counter-clockwise)",
    )
}

/// The rod-slider joint's force on the rod along time: components and magnitude.
fn write_joint_force(
    w: &mut FileWriter,
    series: &Series,
    s: &MechanismSolution,
    lubricated: bool,
) -> Res<()> {
    let n = s.time.len();
    let l = &s.loads;
    let joint_long = if lubricated {
        "rod-slider joint force on the rod (journal): film and contact"
    } else {
        "rod-slider joint reaction on the rod"
    };
    series.write(
        w,
        "joint_force_x",
        &column(n, |i| l[i].rod_slider[0]),
        "N",
        &format!("{joint_long}, x"),
    )?;
    series.write(
        w,
        "joint_force_y",
        &column(n, |i| l[i].rod_slider[1]),
        "N",
        &format!("{joint_long}, y"),
    )?;
    series.write(
        w,
        "joint_force_magnitude",
        &column(n, |i| l[i].rod_slider[0].hypot(l[i].rod_slider[1])),
        "N",
        &format!("{joint_long}, magnitude"),
    )
}

/// The journal orbit of the lubricated joint along time: eccentricity, its ratio and rate, the
/// minimum film thickness and the contact blend weight.
fn write_orbit(
    w: &mut FileWriter,
    series: &Series,
    r: &MechanismResults,
    s: &MechanismSolution,
) -> Res<()> {
    let n = s.time.len();
    let c = r
        .case
        .lubricated_joint()
        .map_or(f64::NAN, |j| j.radial_clearance());
    let e = &s.eccentricity;
    let er = &s.eccentricity_rate;
    series.write(
        w,
        "eccentricity_x",
        &column(n, |i| e[i][0]),
        "m",
        "journal centre relative to the bearing centre, x (journal orbit)",
    )?;
    series.write(
        w,
        "eccentricity_y",
        &column(n, |i| e[i][1]),
        "m",
        "journal centre relative to the bearing centre, y (journal orbit)",
    )?;
    series.write(
        w,
        "eccentricity_ratio",
        &column(n, |i| e[i][0].hypot(e[i][1]) / c),
        "1",
        "eccentricity ratio |e| / c",
    )?;
    series.write(
        w,
        "eccentricity_rate_x",
        &column(n, |i| er[i][0]),
        "m s-1",
        "journal centre velocity relative to the bearing, x",
    )?;
    series.write(
        w,
        "eccentricity_rate_y",
        &column(n, |i| er[i][1]),
        "m s-1",
        "journal centre velocity relative to the bearing, y",
    )?;
    series.write(
        w,
        "min_film_thickness",
        &s.min_film_thickness,
        "m",
        "minimum film thickness h_min = c - |e| (negative: penetration)",
    )?;
    series.write(
        w,
        "contact_weight",
        &s.contact_weight,
        "1",
        "blend weight of the dry contact force (0: film only, 1: contact only)",
    )
}

/// The contact onsets and releases along their own `contact_event` dimension (may be empty).
fn write_contact_events(w: &mut FileWriter, g: &h5::Group, ev: &[ContactEvent]) -> Res<()> {
    let index: Vec<f64> = (0..ev.len()).map(|k| k as f64).collect();
    let dim = w.coordinate(
        g,
        "contact_event",
        &index,
        "1",
        "contact event number, in time order",
    )?;
    for (vname, units, long, values) in [
        (
            "contact_event_time",
            "s",
            "time of the contact onset or release",
            ev.iter().map(|e| e.time).collect::<Vec<_>>(),
        ),
        (
            "contact_event_crank_angle",
            "degree",
            "crank angle of the contact onset or release (not wrapped)",
            ev.iter().map(|e| e.crank_angle_deg).collect(),
        ),
        (
            "contact_event_radial_velocity",
            "m s-1",
            "radial velocity of the journal towards the wall (impact velocity at an onset)",
            ev.iter().map(|e| e.radial_velocity).collect(),
        ),
    ] {
        let ds = w.variable(g, vname, &values, &[&dim])?;
        w.str_attr(&ds, "units", units)?;
        w.str_attr(&ds, "long_name", long)?;
    }
    let kinds: Vec<String> = ev
        .iter()
        .map(|e| match e.kind {
            ContactEventKind::Onset => "onset".to_string(),
            ContactEventKind::Release => "release".to_string(),
        })
        .collect();
    w.string_variable(
        g,
        "contact_event_kind",
        &kinds,
        &dim,
        "onset (h_min fell to the boundary layer) or release",
    )?;
    Ok(())
}

/// The solver's film snapshots as the bearing cases' [`FieldSnapshots`].
fn field_snapshots(ff: &jbearing_solvers::mechanism::MechanismFilmFields) -> FieldSnapshots {
    let (nt, nth, nz) = (ff.fields.len(), ff.theta.len(), ff.z.len());
    let stack = |get: fn(&jbearing_solvers::inverse::FilmFields) -> &Array2<f64>| {
        Array3::from_shape_fn((nt, nth, nz), |(k, i, j)| get(&ff.fields[k])[[i, j]])
    };
    FieldSnapshots {
        time: ff.time.clone(),
        crank_angle: ff.crank_angle_deg.clone(),
        theta: ff.theta.clone(),
        z: ff.z.clone(),
        fields: vec![
            Field {
                name: names::PRESSURE.into(),
                long_name: "film pressure of the rod-slider joint, gauge".into(),
                units: "Pa".into(),
                values: stack(|f| &f.pressure),
            },
            Field {
                name: names::FILM_CONTENT.into(),
                long_name: "film content (density ratio / film fraction)".into(),
                units: "1".into(),
                values: stack(|f| &f.film_fraction),
            },
        ],
    }
}
