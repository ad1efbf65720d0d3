//! The inverse cycle of a bearing with a feed groove: the load history in, the journal orbit out,
//! with the mass-conserving (JFO) Reynolds film.
//!
//! The compressor main bearing of Yu & Sawicki (R = 27.43 mm, L = 18.288 mm, c = 48.9 µm,
//! 1800 rpm, μ = 0.02 Pa s) with its axial feed groove at θ = 90° fed at 0.207 MPa, under a load
//! table over the crank angle (a pulse of 4.8 kN at 180° on a 0.8 kN base). `solve_inverse`
//! marches the run-in, then whole cycles until the orbit repeats; an observer prints the
//! progress of each cycle.
//!
//! Run: `cargo run --release --example inverse_cycle`

use jbearing_solvers::prelude::*;
use std::f64::consts::{PI, TAU};

/// Prints one line per load cycle: how far the orbit moved since the previous one.
struct CycleReport;

impl InverseObserver for CycleReport {
    fn on_cycle(&mut self, cycle: usize, eccentricity_change: f64, film_state_change: f64) {
        if eccentricity_change.is_finite() {
            println!(
                "  cycle {cycle}: max |Δε| = {eccentricity_change:.2e}, max |Δφ| = {film_state_change:.2e}"
            );
        } else {
            println!("  cycle {cycle}: the first (nothing to compare with yet)");
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let speed = 1800.0 * TAU / 60.0; // journal = crank speed, rad/s

    // The bearing and its groove (SI; the groove's width around is an angle).
    let mut params = ReynoldsParams::plain(27.43e-3, 18.288e-3, 48.9e-6, 0.02);
    params.grooves = vec![Groove {
        center_angle: 0.5 * PI,
        center_z: 0.0,
        angular_width: 24.9e-3 / 27.43e-3,
        axial_width: 3.81e-3,
        cutoff_film_fraction: 0.01,
    }];
    let mut film = ReynoldsFilm::new(params)?;

    // The load table: every 10° of crank angle, force on the journal in the bearing frame (N).
    let angles: Vec<f64> = (0..36).map(|k| 10.0 * k as f64).collect();
    let forces: Vec<[f64; 2]> = angles
        .iter()
        .map(|a| {
            let a = a.to_radians();
            [
                600.0 * (2.0 * a).sin(),
                -800.0 - 4000.0 * (0.5 * (1.0 - a.cos())).powi(4),
            ]
        })
        .collect();
    let load = TabulatedLoad::new(angles, forces, 360.0, speed, LoadInterpolation::Linear)?;
    let history = OperatingHistory {
        load,
        journal_speed: speed,
        bearing_speed: 0.0,
        feed_pressures: vec![0.2068e6],
    };

    // The application's defaults: 1° steps, BDF2, the exact film-force Jacobian.
    let settings = InverseParams::default();
    println!("inverse cycle, compressor main bearing (Reynolds/JFO film, 120 × 31, 1° steps)");
    let solution = solve_inverse(&settings, &history, &mut film, &mut CycleReport)?;

    println!(
        "{:>8} {:>8} {:>10} {:>10} {:>12}",
        "crank°", "|ε|", "h_min µm", "p_max MPa", "supply cm³/s"
    );
    for step in solution.steps.iter().filter(|s| {
        let whole = s.crank_angle_deg.round();
        (s.crank_angle_deg - whole).abs() < 1e-6 && whole as i64 % 30 == 0
    }) {
        println!(
            "{:>8.0} {:>8.4} {:>10.2} {:>10.2} {:>12.3}",
            step.crank_angle_deg,
            step.eccentricity,
            step.min_film_thickness * 1e6,
            step.max_pressure * 1e-6,
            step.supply_flow.iter().sum::<f64>() * 1e6
        );
    }
    let s = &solution.summary;
    println!(
        "h_min {:.2} µm at {:.0}°, p_max {:.2} MPa at {:.0}°, mean power loss {:.1} W, periodic: {}",
        s.min_film_thickness * 1e6,
        s.min_film_thickness_crank_angle_deg,
        s.max_pressure * 1e-6,
        s.max_pressure_crank_angle_deg,
        s.mean_power_loss,
        solution.info.periodic
    );

    // Over a periodic cycle the film content returns to its start: what the groove supplies
    // leaves through the ends (mass conservation of the JFO film), here to 2 %.
    let supplied = s.mean_total_supply_flow;
    let leaked = s.mean_total_side_leakage;
    println!(
        "mean supply {:.4} cm³/s, mean side leakage {:.4} cm³/s",
        supplied * 1e6,
        leaked * 1e6
    );
    assert!(solution.info.periodic);
    assert!((supplied - leaked).abs() <= 0.02 * leaked);
    Ok(())
}
