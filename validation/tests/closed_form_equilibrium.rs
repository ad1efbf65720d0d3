//! The simple journal bearing of Flores et al. 2009 (seed `004_cbd349ddb6ca28f9`, §7, Table 1,
//! Figs. 9–11): equilibrium of each closed-form model, side by side.
//!
//! Table 1: external load 30 N, bearing radius 10.0 mm, journal radius 9.8 mm, radial clearance
//! 0.2 mm, length 40.0 mm, journal mass 0.13 kg, 500 rpm, 400 cP. The load acts downwards (Fig. 8)
//! and the journal's weight adds to it; the paper states the fluid force converges to
//! F_X = 0 (Fig. 10) and F_Y = 31.275 N (Fig. 11) = 30 N + 0.13 kg · 9.81 m/s². The forces use
//! the journal radius R_j (seed 004 eqs. 6–17). The paper gives the equilibrium positions only
//! as plotted orbits (Fig. 9), so the test checks the force balance it states, the independent
//! textbook attitude of the half-film models, the relations between the models, and prints the
//! table quoted in the README.

use jbearing_solvers::closed_form::{
    ClosedFormModel, ClosedFormParams, EquilibriumSolution, static_equilibrium,
};
use std::f64::consts::PI;

const EQUILIBRIUM_FORCE: f64 = 31.275; // N, seed 004 §7 text on Fig. 11

fn params() -> ClosedFormParams {
    ClosedFormParams {
        radius: 9.8e-3,
        length: 40e-3,
        radial_clearance: 0.2e-3,
        viscosity: 0.4,
    }
}

fn omega() -> f64 {
    500.0 * 2.0 * PI / 60.0
}

fn solve(model: ClosedFormModel) -> EquilibriumSolution {
    static_equilibrium(model, &params(), [0.0, -EQUILIBRIUM_FORCE], omega()).unwrap()
}

#[test]
fn flores_simple_bearing_equilibrium_of_every_model() {
    // The stated equilibrium force is the load plus the journal's weight (to the 3 decimals
    // printed: 30 + 0.13 · 9.81 = 31.2753).
    assert!((30.0 + 0.13 * 9.81 - EQUILIBRIUM_FORCE).abs() < 5e-4);

    println!("| model | ε | attitude φ (°) | h_min (µm) | F_X (N) | F_Y (N) |");
    println!("|---|---|---|---|---|---|");
    let mut sol = std::collections::HashMap::new();
    for model in ClosedFormModel::ALL {
        let s = solve(model);
        println!(
            "| {} | {:.4} | {:.2} | {:.1} | {:.1e} | {:.4} |",
            model.name(),
            s.eccentricity_ratio,
            s.attitude_angle.to_degrees(),
            s.min_film_thickness * 1e6,
            s.film_force[0],
            s.film_force[1]
        );
        // Figs. 10–11: F_X → 0, F_Y → 31.275 N (bisection to 1e-15 in ε: balance to ~1e-9).
        assert!(
            s.film_force[0].abs() < 1e-8 * EQUILIBRIUM_FORCE,
            "{model:?}"
        );
        assert!((s.film_force[1] - EQUILIBRIUM_FORCE).abs() < 1e-8 * EQUILIBRIUM_FORCE);
        assert!(s.eccentricity_ratio > 0.0 && s.eccentricity_ratio < 1.0);
        // The journal (ω > 0, counter-clockwise) sits below and to the right of the centre.
        assert!(s.eccentricity_ratio_vector[0] > 0.0 && s.eccentricity_ratio_vector[1] <= 0.0);
        sol.insert(model, s);
    }
    use ClosedFormModel::*;
    // Full films carry the load with the force at right angles: φ = 90°.
    for m in [ShortSommerfeld, LongSommerfeld] {
        assert!((sol[&m].attitude_angle - 0.5 * PI).abs() < 1e-12);
    }
    // Half films: textbook attitudes, an independent statement of the same models —
    // short (Ocvirk): tan φ = π√(1−ε²)/(4ε); long (half Sommerfeld): tan φ = π√(1−ε²)/(2ε).
    for (m, k) in [(ShortGumbel, 4.0), (LongGumbel, 2.0)] {
        let e = sol[&m].eccentricity_ratio;
        let want = (PI * (1.0 - e * e).sqrt() / (k * e)).atan();
        assert!((sol[&m].attitude_angle - want).abs() < 1e-10, "{m:?}");
    }
    // At rest the moving short film is the fixed half film, and Pinkus–Sternlicht is the
    // Gumbel long bearing (k → ∞ in seed 004 eqs. 14–17).
    for (a, b) in [
        (ShortGumbelMovingFilm, ShortGumbel),
        (PinkusSternlicht, LongGumbel),
    ] {
        assert!((sol[&a].eccentricity_ratio - sol[&b].eccentricity_ratio).abs() < 1e-12);
        assert!((sol[&a].attitude_angle - sol[&b].attitude_angle).abs() < 1e-10);
    }
    // L/D = 2.04: the short-bearing theory (force ∝ L³R) overrates this bearing's capacity
    // relative to the long one (∝ LR³) by ~(L/R)²/12·…, so it predicts the smaller ε; half
    // films carry less than full films, so they sit deeper.
    assert!(sol[&ShortGumbel].eccentricity_ratio < sol[&LongGumbel].eccentricity_ratio);
    assert!(sol[&ShortSommerfeld].eccentricity_ratio < sol[&LongSommerfeld].eccentricity_ratio);
    assert!(sol[&LongSommerfeld].eccentricity_ratio < sol[&LongGumbel].eccentricity_ratio);
    assert!(sol[&ShortSommerfeld].eccentricity_ratio < sol[&ShortGumbel].eccentricity_ratio);
}
