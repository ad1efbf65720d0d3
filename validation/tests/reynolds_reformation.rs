//! Film reformation with mass balance (docs/conventions.md §8 rung 1, issue item 6):
//! - steady: a feed groove downstream of a cavity, where the film re-forms; supply = side
//!   leakage to 1e-8;
//! - dynamic: a journal squeezing away from the wall and back (backward Euler steps): the film
//!   fraction field is non-trivial, nodes re-form, and every step closes its balance
//!   (content change)/Δt = supply − leakage.

use std::f64::consts::PI;

use jbearing_solvers::reynolds::{
    GridParams, Groove, OperatingConditions, ReynoldsParams, ReynoldsSolver, StepInput, TimeScheme,
};
use jbearing_validation::generated_docs::{sci, write_if_requested};

/// The command that reproduces the block of docs/validation.md written by the test `name`.
fn command(name: &str) -> String {
    format!(
        "cargo test --release -p jbearing-validation --test reynolds_reformation -- --nocapture {name}"
    )
}

/// The header of the Reynolds-solver tables of docs/validation.md.
const HEADER: &str = "| case | reference | ours | error |\n|---|---|---|---|\n";

fn params() -> ReynoldsParams {
    let mut p = ReynoldsParams::plain(0.025, 0.025, 40e-6, 0.02);
    p.grid = GridParams {
        n_theta: 96,
        n_z: 21,
    };
    p.grooves = vec![Groove {
        center_angle: 0.5 * PI,
        center_z: 0.0,
        angular_width: 0.25,
        axial_width: 0.01,
        cutoff_film_fraction: 0.01,
    }];
    p
}

fn cond(omega: f64) -> OperatingConditions {
    OperatingConditions {
        journal_speed: omega,
        bearing_speed: 0.0,
        feed_pressures: vec![1e5],
    }
}

/// ε along +x: h_min at θ = 0, the divergent film θ ∈ (0, π) cavitates from θ ≈ 0 up to the
/// groove at θ = 90°, where the film re-forms.
#[test]
fn steady_reformation_at_groove_balances_mass() {
    let mut s = ReynoldsSolver::new(params()).unwrap();
    let sol = s.solve_steady([0.7, 0.0], &cond(300.0)).unwrap();
    let supply: f64 = sol.supply_flow.iter().sum();
    let leak = sol.side_leakage[0] + sol.side_leakage[1];
    let (nt, nz) = sol.pressure.dim();
    // Reformation: a cavitated node whose downstream neighbour (direction of U) is full.
    let mut reforming = 0;
    let mut partial = 0;
    for i in 0..nt {
        for j in 1..nz - 1 {
            let f = sol.film_fraction[[i, j]];
            if f < 1.0 && sol.switch[[(i + 1) % nt, j]] > 0.5 {
                reforming += 1;
            }
            if f > 0.05 && f < 0.95 {
                partial += 1;
            }
        }
    }
    eprintln!(
        "steady reformation: supply {supply:.6e} leak {leak:.6e} rel {:.2e}; cavitated {:.3}; reforming nodes {reforming}; partial-film nodes {partial}; iterations {} residual {:.1e}",
        (supply - leak) / leak,
        sol.cavitated_fraction,
        sol.iterations,
        sol.residual
    );
    assert!(((supply - leak) / leak).abs() < 1e-8);
    assert!(reforming > 0 && partial > 10);
    let table = format!(
        "{HEADER}| reformation: groove downstream of a cavity (steady, 96 × 21) | supply = leakage | {} relative, {reforming} re-forming nodes | ≤ 1e-8 |\n",
        sci(((supply - leak) / leak).abs(), 1)
    );
    print!("{table}");
    let name = "steady_reformation_at_groove_balances_mass";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// A journal moving on a circle of radius 0.6 at a quarter of the shaft speed and 20 % in
/// and out of the wall, stepped with the default time scheme (BDF2): per step the scheme's
/// content rate (1.5 cⁿ⁺¹ − 2 cⁿ + 0.5 cⁿ⁻¹)/Δt equals supply minus leakage to 1e-8 of the
/// flows (from the third step on: the first is a backward-Euler step, the second's cⁿ⁻¹ is the
/// initial film), and film re-forms (cavitated → full) between steps.
#[test]
fn dynamic_squeeze_reformation_balances_mass() {
    let mut s = ReynoldsSolver::new(params()).unwrap();
    let omega = 300.0;
    let whirl = 0.25 * omega;
    let steps = 80;
    let dt = 2.0 * PI / whirl / steps as f64;
    let eps_at = |t: f64| {
        let m = 0.6 + 0.2 * (2.0 * whirl * t).sin();
        [m * (whirl * t).cos(), m * (whirl * t).sin()]
    };
    let mut state = s.initial_state(eps_at(0.0));
    assert_eq!(s.params().time_scheme, TimeScheme::Bdf2);
    let mut prev: Option<(f64, ndarray_like::Switch)> = None;
    let mut before_prev: Option<f64> = None;
    let mut reformed = 0usize;
    let mut worst: f64 = 0.0;
    let mut max_iter = 0;
    let mut min_p_rel: f64 = 0.0;
    for n in 1..=steps {
        let input = StepInput {
            eccentricity_ratio: eps_at(n as f64 * dt),
            dt,
            conditions: cond(omega),
        };
        let (sol, next) = s.solve_step(&state, &input).unwrap();
        max_iter = max_iter.max(sol.iterations);
        let pmin = sol.pressure.iter().copied().fold(f64::INFINITY, f64::min);
        min_p_rel = min_p_rel.min(pmin / sol.max_pressure);
        let switch: Vec<f64> = sol.switch.iter().copied().collect();
        if let Some((content, old_switch)) = &prev {
            let supply: f64 = sol.supply_flow.iter().sum();
            let leak = sol.side_leakage[0] + sol.side_leakage[1];
            if let Some(older) = before_prev {
                let rate = (1.5 * sol.film_content - 2.0 * content + 0.5 * older) / dt;
                let scale = supply.abs().max(leak.abs());
                let err = (rate - (supply - leak)) / scale;
                worst = worst.max(err.abs());
            }
            reformed += old_switch
                .iter()
                .zip(&switch)
                .filter(|(a, b)| **a < 0.5 && **b > 0.5)
                .count();
        }
        before_prev = prev.as_ref().map(|(c, _)| *c);
        prev = Some((sol.film_content, switch));
        state = next;
    }
    eprintln!(
        "dynamic: worst step balance {worst:.2e}, re-formed node events {reformed}, max switch iterations {max_iter}, lowest p / p_max {min_p_rel:.2e}"
    );
    assert!(worst < 1e-8, "{worst}");
    assert!(reformed > 0);
    let table = format!(
        "{HEADER}| reformation: squeezing / whirling journal, {steps} BDF2 steps (96 × 21) | BDF2 content rate = supply − leakage | worst step {}; {reformed} cavitated → full events; lowest p / p_max {} | ≤ 1e-8 |\n",
        sci(worst, 1),
        sci(min_p_rel, 1)
    );
    print!("{table}");
    let name = "dynamic_squeeze_reformation_balances_mass";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

mod ndarray_like {
    pub type Switch = Vec<f64>;
}
