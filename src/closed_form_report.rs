//! The closed-form static-equilibrium table of a case (`[closed_form]` in the case file,
//! `jbearing closed-form CASE` on the command line).
//!
//! Each closed-form film model of `jbearing_solvers::closed_form` (\[Flores2009\] eqs. 3, 5–18;
//! \[Flores2006\] eqs. 18, 20, 36–37) is put in static equilibrium F(ε, γ) + W = 0 (docs/conventions.md §1)
//! under one constant load:
//!
//! ```text
//!   steady case (one load point, constant speeds):  W = the load,            ω = ω_j − ω_b
//!   otherwise:                                      W = cycle mean of W(t),  ω = mean ω_j − mean ω_b
//!   each model ──static_equilibrium(model, R L c μ, W, ω)──► ε, φ, γ, h_min = c(1−ε), F, S
//! ```
//!
//! For a steady case whose rigorous (finite-difference Reynolds, JFO) method ran, its answer is
//! the row `fd_reynolds`: ε and γ from the cycle mean of the journal-centre series, h_min the
//! cycle mean of its minimum film thickness. Its film force is not reported (NaN): the inverse
//! solver balances the load to its own force tolerance.

use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;

use jbearing_solvers::closed_form::{ClosedFormModel, ClosedFormParams, static_equilibrium};

use crate::case::{Case, Schedule};
use crate::output::{ClosedFormRow, ClosedFormTable, Method, MethodResult, Reduction, names};

/// Row name of the finite-difference Reynolds answer.
pub const FD_ROW: &str = "fd_reynolds";

/// One load point and constant journal and bearing speeds.
pub fn is_steady(case: &Case) -> bool {
    let first = case.load_forces[0];
    case.load_forces.iter().all(|f| *f == first)
        && matches!(case.journal_speed, Schedule::Constant(_))
        && matches!(case.bearing_speed, Schedule::Constant(_))
}

/// The load every row balances: the load of a steady case, else its cycle mean (3600 samples of
/// the interpolated table over one cycle) (N).
pub fn equilibrium_load(case: &Case) -> [f64; 2] {
    if is_steady(case) {
        return case.load_forces[0];
    }
    let load = case.load();
    let n = 3600;
    let mut sum = [0.0; 2];
    for k in 0..n {
        let w = load
            .load_at_crank_angle(case.load_angles_deg[0] + k as f64 * case.cycle_deg / n as f64);
        sum[0] += w[0];
        sum[1] += w[1];
    }
    [sum[0] / n as f64, sum[1] / n as f64]
}

/// Relative speed ω = ω_j − ω_b (cycle means) (rad/s).
pub fn relative_speed(case: &Case) -> f64 {
    case.journal_speed.mean(case.cycle_deg) - case.bearing_speed.mean(case.cycle_deg)
}

/// The closed-form rows for `models` (a model without equilibrium gets its error as status and
/// NaN values).
pub fn table(case: &Case, models: &[ClosedFormModel]) -> ClosedFormTable {
    let params = ClosedFormParams {
        radius: case.radius,
        length: case.length,
        radial_clearance: case.radial_clearance,
        viscosity: case.viscosity,
    };
    let load = equilibrium_load(case);
    let omega = relative_speed(case);
    let rows = models
        .iter()
        .map(|&m| match static_equilibrium(m, &params, load, omega) {
            Ok(s) => ClosedFormRow {
                model: m.name().into(),
                status: "ok".into(),
                eccentricity_ratio: s.eccentricity_ratio,
                attitude_angle: s.attitude_angle,
                line_of_centres_angle: s.line_of_centres_angle,
                min_film_thickness: s.min_film_thickness,
                film_force: s.film_force,
                force_residual: (s.film_force[0] + load[0]).hypot(s.film_force[1] + load[1]),
                sommerfeld_number: finite_or_nan(s.sommerfeld_number),
            },
            Err(e) => ClosedFormRow {
                model: m.name().into(),
                status: e.to_string(),
                ..nan_row()
            },
        })
        .collect();
    ClosedFormTable {
        load,
        relative_speed: omega,
        load_basis: if is_steady(case) {
            "constant load of a steady case".into()
        } else {
            "cycle-mean load".into()
        },
        rows,
    }
}

/// The table `solve_case` puts into the report: `None` unless the case asks for it; with the
/// `fd_reynolds` row for a steady case whose rigorous method ran.
pub fn report_table(case: &Case, methods: &[MethodResult]) -> Option<ClosedFormTable> {
    if case.closed_form_models.is_empty() {
        return None;
    }
    let mut t = table(case, &case.closed_form_models);
    if is_steady(case)
        && let Some(rig) = methods.iter().find(|m| m.method == Method::Rigorous)
        && let Some(row) = fd_row(case, &t, rig)
    {
        t.rows.push(row);
    }
    Some(t)
}

/// The finite-difference answer from the rigorous method's series (see the module docs).
pub fn fd_row(case: &Case, t: &ClosedFormTable, rig: &MethodResult) -> Option<ClosedFormRow> {
    let ex = rig.reduce(names::ECCENTRICITY_X, Reduction::Mean)?;
    let ey = rig.reduce(names::ECCENTRICITY_Y, Reduction::Mean)?;
    let c = case.radial_clearance;
    let gamma = ey.atan2(ex);
    let load_angle = t.load[1].atan2(t.load[0]);
    let sign = if t.relative_speed < 0.0 { -1.0 } else { 1.0 };
    let eps = ex.hypot(ey) / c;
    let h_min = rig
        .reduce(names::MIN_FILM_THICKNESS, Reduction::Mean)
        .unwrap_or(c * (1.0 - eps));
    let w = t.load[0].hypot(t.load[1]);
    let rc = case.radius / c;
    let s = case.viscosity * (t.relative_speed.abs() / TAU) * case.length * 2.0 * case.radius / w
        * rc
        * rc;
    Some(ClosedFormRow {
        model: FD_ROW.into(),
        status: "ok".into(),
        eccentricity_ratio: eps,
        attitude_angle: wrap((gamma - load_angle) * sign),
        line_of_centres_angle: gamma,
        min_film_thickness: h_min,
        sommerfeld_number: finite_or_nan(s),
        ..nan_row()
    })
}

/// The table as text: one line per model, angles in degrees, h_min in µm.
pub fn format_table(t: &ClosedFormTable) -> String {
    let mut s = format!(
        "closed-form static equilibrium ({}: W = ({:.6e}, {:.6e}) N, ω = {:.6} rad/s)\n",
        t.load_basis, t.load[0], t.load[1], t.relative_speed
    );
    let _ = writeln!(
        s,
        "{:<26} {:>10} {:>12} {:>14} {:>14} {:>14} {:>12} {:>10}",
        "model", "ε", "attitude_deg", "h_min_um", "F_x_N", "F_y_N", "|F+W|_N", "S"
    );
    for r in &t.rows {
        if r.status != "ok" {
            let _ = writeln!(s, "{:<26} {}", r.model, r.status);
            continue;
        }
        let _ = writeln!(
            s,
            "{:<26} {:>10.4} {:>12.2} {:>14.2} {:>14.6e} {:>14.6e} {:>12.3e} {:>10.4}",
            r.model,
            r.eccentricity_ratio,
            r.attitude_angle.to_degrees(),
            r.min_film_thickness * 1e6,
            r.film_force[0],
            r.film_force[1],
            r.force_residual,
            r.sommerfeld_number
        );
    }
    s
}

fn nan_row() -> ClosedFormRow {
    ClosedFormRow {
        model: String::new(),
        status: String::new(),
        eccentricity_ratio: f64::NAN,
        attitude_angle: f64::NAN,
        line_of_centres_angle: f64::NAN,
        min_film_thickness: f64::NAN,
        film_force: [f64::NAN; 2],
        force_residual: f64::NAN,
        sommerfeld_number: f64::NAN,
    }
}

fn finite_or_nan(v: f64) -> f64 {
    if v.is_finite() { v } else { f64::NAN }
}

/// Angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(TAU);
    if r > PI { r - TAU } else { r }
}
