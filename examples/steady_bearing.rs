//! A steady bearing from load to eccentricity: the mass-conserving Reynolds film beside the
//! closed forms.
//!
//! A plain bearing (R = 25 mm, L/D = 1/2, c = 50 µm, μ = 0.02 Pa s at 3000 rpm) under 5 kN.
//! `ReynoldsSolver::solve_steady_load` finds the journal position whose film carries the load
//! (Newton on ε); the short-bearing closed form (Ocvirk, Gumbel's half film) is printed beside
//! it for comparison — at L/D = 1/2 it overestimates the load capacity, so its eccentricity is
//! lower.
//!
//! Run: `cargo run --release --example steady_bearing`

use jbearing_solvers::prelude::*;
use std::f64::consts::TAU;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (radius, length, clearance, viscosity) = (25e-3, 25e-3, 50e-6, 0.02);
    let speed = 3000.0 * TAU / 60.0; // rad/s
    let load = [0.0, -5000.0]; // N, on the journal, bearing frame (−y: downwards)

    // The rigorous film on the application's default grid (120 × 31).
    // Oil enters at ambient pressure along the widest gap (Raimondi & Boyd's steady bearing;
    // the mass-conserving film needs a supply: a groove, or this line).
    let mut params = ReynoldsParams::plain(radius, length, clearance, viscosity);
    params.supply = SupplyModel::AxialLineAtMaxGap;
    let mut film = ReynoldsSolver::new(params)?;
    let rotation = OperatingConditions {
        journal_speed: speed,
        ..Default::default()
    };
    let (solution, info) = film.solve_steady_load(load, &rotation)?;
    let eps = info.eccentricity_ratio[0].hypot(info.eccentricity_ratio[1]);

    // The short-bearing closed form at the same load.
    let closed = ClosedFormParams {
        radius,
        length,
        radial_clearance: clearance,
        viscosity,
    };
    let short = static_equilibrium(ClosedFormModel::ShortGumbel, &closed, load, speed)?;

    println!("steady bearing: W = 5 kN, 3000 rpm, L/D = 1/2");
    println!("{:<28} {:>12} {:>14}", "", "Reynolds/JFO", "short Gumbel");
    println!(
        "{:<28} {:>12.4} {:>14.4}",
        "eccentricity ratio ε", eps, short.eccentricity_ratio
    );
    println!(
        "{:<28} {:>12.2} {:>14.2}",
        "attitude angle φ (deg)",
        solution.attitude_angle.to_degrees(),
        short.attitude_angle.to_degrees()
    );
    println!(
        "{:<28} {:>12.2} {:>14.2}",
        "h_min (µm)",
        solution.min_film_thickness * 1e6,
        clearance * (1.0 - short.eccentricity_ratio) * 1e6
    );
    println!(
        "{:<28} {:>12.2} {:>14}",
        "p_max (MPa)",
        solution.max_pressure * 1e-6,
        "-"
    );
    println!(
        "{:<28} {:>12.1} {:>14}",
        "power loss (W)", solution.power_loss, "-"
    );
    println!(
        "Newton: {} iterations, {} film solves, |F + W| = {:.2e} N",
        info.iterations, info.film_solves, info.force_residual
    );

    // What must hold whatever the numbers: the film carries the load, and the short-bearing
    // theory (no circumferential pressure flow) carries more at a given ε, so it sits lower.
    assert!(info.force_residual <= 1e-6 * 5000.0);
    assert!(eps > short.eccentricity_ratio && eps < 1.0);
    Ok(())
}
