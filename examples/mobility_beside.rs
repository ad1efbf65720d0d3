//! The mobility answer beside the rigorous one: the same bearing and load cycle through Booker's
//! mobility method (short-bearing mobility, milliseconds) and through the inverse solver with
//! the mass-conserving Reynolds film (seconds).
//!
//! The compressor main bearing of Yu & Sawicki under a pulse load (see `inverse_cycle.rs`). The
//! rigorous film is fed through the bearing's groove (a mass-conserving film needs a supply);
//! the mobility method has no feed and no groove — one of the differences it is blind to.
//!
//! Run: `cargo run --release --example mobility_beside`

use jbearing_solvers::inverse::CycleSummary;
use jbearing_solvers::load::FnLoad;
use jbearing_solvers::mobility::OrbitSummary;
use jbearing_solvers::prelude::*;
use std::f64::consts::TAU;
use std::time::{Duration, Instant};

/// The bearing: radius, length and radial clearance (m), viscosity (Pa s).
const RADIUS: f64 = 27.43e-3;
const LENGTH: f64 = 18.288e-3;
const CLEARANCE: f64 = 48.9e-6;
const VISCOSITY: f64 = 0.02;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let speed = 1800.0 * TAU / 60.0;
    let pulse = pulse_load(speed);

    let start = Instant::now();
    let orbit = mobility_orbit(speed, &pulse)?;
    let mobility_time = start.elapsed();

    let start = Instant::now();
    let rigorous = rigorous_cycle(speed, &pulse)?;
    let rigorous_time = start.elapsed();

    let (m, r) = (&orbit.summary, &rigorous.summary);
    print_table(m, r, mobility_time, rigorous_time);

    // Both answers carry the same load on a film of the same bearing: the minimum films must be
    // of the same order (the short-bearing mobility at L/D = 1/3 is within tens of percent).
    let ratio = m.min_film_thickness / r.min_film_thickness;
    assert!(ratio > 0.5 && ratio < 2.0, "h_min ratio {ratio}");
    Ok(())
}

/// The load cycle of one crank turn at `speed` (rad/s): a 4000 N pulse on an 800 N base load
/// along −y, and a ±600 N sideways load at twice the crank frequency (N, bearing frame).
fn pulse_load(speed: f64) -> FnLoad<impl Fn(f64) -> [f64; 2] + Clone> {
    FnLoad {
        period: TAU / speed,
        load: move |t: f64| {
            let a = speed * t;
            [
                600.0 * (2.0 * a).sin(),
                -800.0 - 4000.0 * (0.5 * (1.0 - a.cos())).powi(4),
            ]
        },
    }
}

/// Mobility method: the journal velocity from the load by Booker's short-bearing mobility,
/// integrated with an adaptive Runge–Kutta method until the orbit repeats.
fn mobility_orbit(speed: f64, load: &impl PeriodicLoad) -> Result<OrbitInfo, MobilityError> {
    let bearing = MobilityParams {
        radius: RADIUS,
        length: LENGTH,
        radial_clearance: CLEARANCE,
        viscosity: VISCOSITY,
        omega_journal: speed,
        omega_bearing: 0.0,
    };
    let mobility = ExactShortBearing {
        length_to_diameter: bearing.length_to_diameter(),
    };
    solve_orbit(&OrbitParams::new(bearing), &mobility, load)
}

/// Rigorous: the inverse solver with the Reynolds/JFO film (application defaults), fed at
/// 0.2068 MPa through the bearing's groove at 90°.
fn rigorous_cycle(
    speed: f64,
    load: &FnLoad<impl Fn(f64) -> [f64; 2] + Clone>,
) -> Result<InverseSolution, Box<dyn std::error::Error>> {
    let mut params = ReynoldsParams::plain(RADIUS, LENGTH, CLEARANCE, VISCOSITY);
    params.grooves = vec![Groove {
        center_angle: 0.5 * std::f64::consts::PI,
        center_z: 0.0,
        angular_width: 24.9e-3 / RADIUS,
        axial_width: 3.81e-3,
        cutoff_film_fraction: 0.01,
    }];
    let mut film = ReynoldsFilm::new(params)?;
    let history = OperatingHistory {
        load: load.clone(),
        journal_speed: speed,
        bearing_speed: 0.0,
        feed_pressures: vec![0.2068e6],
    };
    let rigorous = solve_inverse(
        &InverseParams::default(),
        &history,
        &mut film,
        &mut NoObserver,
    )?;
    Ok(rigorous)
}

/// The two answers side by side, with their run times.
fn print_table(m: &OrbitSummary, r: &CycleSummary, mobility: Duration, rigorous: Duration) {
    println!("{:<26} {:>12} {:>12}", "", "mobility", "Reynolds/JFO");
    println!(
        "{:<26} {:>12.2} {:>12.2}",
        "h_min (µm)",
        m.min_film_thickness * 1e6,
        r.min_film_thickness * 1e6
    );
    println!(
        "{:<26} {:>12.0} {:>12.0}",
        "crank angle of h_min (°)",
        m.min_film_crank_angle_deg,
        r.min_film_thickness_crank_angle_deg
    );
    println!(
        "{:<26} {:>12.4} {:>12.4}",
        "max |ε|", m.max_eccentricity_ratio, r.max_eccentricity
    );
    println!(
        "{:<26} {:>12.2} {:>12.2}",
        "p_max (MPa)",
        m.max_peak_pressure * 1e-6,
        r.max_pressure * 1e-6
    );
    println!(
        "{:<26} {:>12.1} {:>12.1}",
        "mean power loss (W)", m.mean_power_loss, r.mean_power_loss
    );
    println!(
        "{:<26} {:>12.3} {:>12.3}",
        "run time (s)",
        mobility.as_secs_f64(),
        rigorous.as_secs_f64()
    );
}
