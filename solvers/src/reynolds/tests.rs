//! Unit tests: discrete mass balance, ADI-Krylov against the sparse-LU oracle, error paths.

use super::*;

fn grooved(solver: LinearSolver) -> ReynoldsParams {
    let mut p = ReynoldsParams::plain(0.025, 0.025, 50e-6, 0.03);
    p.grid = GridParams {
        n_theta: 72,
        n_z: 17,
    };
    p.linear_solver = solver;
    p.grooves = vec![Groove {
        center_angle: std::f64::consts::FRAC_PI_2,
        center_z: 0.0,
        angular_width: 0.2,
        axial_width: 0.008,
        cutoff_film_fraction: 0.01,
    }];
    p
}

fn conditions(feed: f64) -> OperatingConditions {
    OperatingConditions {
        journal_speed: 300.0,
        bearing_speed: 0.0,
        feed_pressures: vec![feed],
    }
}

/// Mass balance of a steady grooved bearing: the scheme is conservative, so supply = side
/// leakage up to the solve tolerance (1e-10 on the residual; 1e-8 relative asked).
#[test]
fn steady_grooved_mass_balance() {
    for solver in [LinearSolver::AdiKrylov, LinearSolver::SparseLu] {
        let mut s = ReynoldsSolver::new(grooved(solver)).unwrap();
        let sol = s.solve_steady([0.6, -0.3], &conditions(2e5)).unwrap();
        let supply: f64 = sol.supply_flow.iter().sum();
        let leak = sol.side_leakage[0] + sol.side_leakage[1];
        assert!(supply > 0.0 && leak > 0.0);
        assert!(
            ((supply - leak) / leak).abs() <= 1e-8,
            "{solver:?}: supply {supply:e} leak {leak:e}"
        );
        assert!(sol.cavitated_fraction > 0.05, "{}", sol.cavitated_fraction);
        // Symmetric about the mid-plane.
        assert!(((sol.side_leakage[0] - sol.side_leakage[1]) / leak).abs() < 1e-8);
    }
}

/// The ADI-Krylov answer matches the sparse-LU oracle (same discrete system).
#[test]
fn adi_matches_lu_oracle() {
    let mut a = ReynoldsSolver::new(grooved(LinearSolver::AdiKrylov)).unwrap();
    let mut b = ReynoldsSolver::new(grooved(LinearSolver::SparseLu)).unwrap();
    let c = conditions(2e5);
    let sa = a.solve_steady([0.5, 0.4], &c).unwrap();
    let sb = b.solve_steady([0.5, 0.4], &c).unwrap();
    let pmax = sb.max_pressure;
    let diff = sa
        .pressure
        .iter()
        .zip(sb.pressure.iter())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(diff / pmax < 1e-7, "max |Δp|/p_max = {:e}", diff / pmax);
    assert_eq!(sa.switch, sb.switch);
    // A time step too.
    let st = a.initial_state([0.5, 0.4]);
    let input = StepInput {
        eccentricity_ratio: [0.52, 0.4],
        dt: 1e-4,
        conditions: c.clone(),
    };
    let (ta, _) = a.solve_step(&st, &input).unwrap();
    let (tb, _) = b.solve_step(&st, &input).unwrap();
    let diff = ta
        .pressure
        .iter()
        .zip(tb.pressure.iter())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        diff / tb.max_pressure < 1e-7,
        "{:e}",
        diff / tb.max_pressure
    );
}

#[test]
fn no_supply_is_rejected() {
    let p = ReynoldsParams::plain(0.025, 0.025, 50e-6, 0.03);
    assert!(matches!(
        ReynoldsSolver::new(p),
        Err(ReynoldsError::NoSupply { .. })
    ));
}

/// Crank–Nicolson steps of a whirling journal: each step closes the trapezoidal balance
/// Δcontent/Δt = ½ (supply − leakage)ⁿ⁺¹ + ½ (supply − leakage)ⁿ to the solve tolerance.
#[test]
fn crank_nicolson_steps_balance_mass() {
    let mut p = grooved(LinearSolver::AdiKrylov);
    p.time_scheme = TimeScheme::CrankNicolson;
    let mut s = ReynoldsSolver::new(p).unwrap();
    let c = conditions(2e5);
    let whirl = 150.0;
    let dt = 2.0 * std::f64::consts::PI / whirl / 60.0;
    let eps = |n: usize| {
        let a = whirl * dt * n as f64;
        [0.5 * a.cos(), 0.5 * a.sin()]
    };
    let mut state = s.initial_state(eps(0));
    let mut prev: Option<(f64, f64)> = None;
    let mut worst: f64 = 0.0;
    for n in 1..=40 {
        let input = StepInput {
            eccentricity_ratio: eps(n),
            dt,
            conditions: c.clone(),
        };
        let (sol, next) = s.solve_step(&state, &input).unwrap();
        let net = sol.supply_flow.iter().sum::<f64>() - sol.side_leakage[0] - sol.side_leakage[1];
        // From step 2 on, both levels are CN levels (the first step falls back to BE).
        if let Some((content, old_net)) = prev.filter(|_| n > 2) {
            let rate = (sol.film_content - content) / dt;
            let scale = sol.side_leakage[0] + sol.side_leakage[1];
            worst = worst.max(((rate - 0.5 * (net + old_net)) / scale).abs());
        }
        prev = Some((sol.film_content, net));
        state = next;
    }
    assert!(worst < 1e-8, "worst CN step balance {worst:e}");
}

/// A step started from a nearby answer (`solve_step_from`, as the inverse solver's Newton
/// iterates do) reaches the same discrete solution as a start from the old state: the switch
/// field agrees node for node and the film force to the solve tolerance. (What it saves is
/// measured by the inverse benchmarks, not here.)
#[test]
fn a_step_started_from_a_nearby_answer_gives_the_same_film() {
    let mut s = ReynoldsSolver::new(grooved(LinearSolver::AdiKrylov)).unwrap();
    let c = conditions(2e5);
    let dt = 1e-4;
    // A film whirling at ε = 0.6 for 30 steps, then one step to two nearby trial positions.
    let mut state = s.initial_state([0.6, 0.0]);
    for n in 1..=30 {
        let a = 0.02 * n as f64;
        let input = StepInput {
            eccentricity_ratio: [0.6 * a.cos(), 0.6 * a.sin()],
            dt,
            conditions: c.clone(),
        };
        state = s.solve_step(&state, &input).unwrap().1;
    }
    let a: f64 = 0.62;
    let trial = |d: f64| StepInput {
        eccentricity_ratio: [(0.6 + d) * a.cos(), (0.6 + d) * a.sin()],
        dt,
        conditions: c.clone(),
    };
    let (_, nearby) = s.solve_step(&state, &trial(0.0)).unwrap();
    let (cold, cold_state) = s.solve_step(&state, &trial(1e-3)).unwrap();
    let (warm, warm_state) = s
        .solve_step_from(&state, &trial(1e-3), Some(&nearby))
        .unwrap();
    assert_eq!(cold_state.full_film, warm_state.full_film);
    let f = cold.load_capacity;
    for k in 0..2 {
        assert!(
            (cold.film_force[k] - warm.film_force[k]).abs() < 1e-8 * f,
            "force {:?} vs {:?}",
            cold.film_force,
            warm.film_force
        );
    }
    // A start of another grid is an error, not a panic.
    let mut small = grooved(LinearSolver::AdiKrylov);
    small.grid = GridParams {
        n_theta: 36,
        n_z: 9,
    };
    let other = ReynoldsSolver::new(small)
        .unwrap()
        .initial_state([0.0, 0.0]);
    assert!(matches!(
        s.solve_step_from(&state, &trial(1e-3), Some(&other)),
        Err(ReynoldsError::InvalidParameter { name: "start", .. })
    ));
}
