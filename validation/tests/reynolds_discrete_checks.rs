//! Discrete checks of the Reynolds solver through its public API, measured for
//! docs/validation.md (the unit tests in `solvers/src/reynolds/tests.rs` assert the same bounds
//! but, the solvers crate being pure numerics, write no files; these tests re-measure the
//! quantities a reader sees in the table and write them after their assertions):
//! - the discrete mass balance of a steady grooved bearing: the scheme is conservative, so the
//!   supply equals the side leakage to the solve tolerance, with either linear solver;
//! - the ADI-Krylov answer against the sparse-LU oracle on the same discrete system (a steady
//!   film and a time step): the same pressures and the same switch field;
//! - the energy identity of a steady grooved film (shaft + feed power = viscous dissipation),
//!   exact in the continuum, closing as the grid is refined;
//! - the side leakage of a groove round the whole circumference at ε = 0 against its closed
//!   form on grids whose rows fall anywhere across the groove's edges (the grid module docs,
//!   "Groove edges").

use jbearing_solvers::reynolds::{
    GridParams, Groove, LinearSolver, OperatingConditions, ReynoldsParams, ReynoldsSolver,
    StepInput,
};
use jbearing_validation::generated_docs::{sci, write_if_requested};

fn command(name: &str) -> String {
    format!(
        "cargo test --release -p jbearing-validation --test reynolds_discrete_checks -- --nocapture {name}"
    )
}

/// The header of the Reynolds-solver tables of docs/validation.md.
const HEADER: &str = "| case | reference | ours | error |\n|---|---|---|---|\n";

/// The unit tests' grooved bearing: R 25 mm, L 25 mm, c 50 µm, 30 mPa s, one 0.2 rad × 8 mm
/// groove at 90°, 72 × 17 nodes.
fn grooved(solver: LinearSolver, n_theta: usize, n_z: usize) -> ReynoldsParams {
    let mut p = ReynoldsParams::plain(0.025, 0.025, 50e-6, 0.03);
    p.grid = GridParams { n_theta, n_z };
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

/// 300 rad/s, the groove fed at 2 bar.
fn conditions() -> OperatingConditions {
    OperatingConditions {
        journal_speed: 300.0,
        bearing_speed: 0.0,
        feed_pressures: vec![2e5],
    }
}

#[test]
fn steady_grooved_bearing_balances_mass() {
    let mut worst: f64 = 0.0;
    for solver in [LinearSolver::AdiKrylov, LinearSolver::SparseLu] {
        let mut s = ReynoldsSolver::new(grooved(solver, 72, 17)).unwrap();
        let sol = s.solve_steady([0.6, -0.3], &conditions()).unwrap();
        let supply: f64 = sol.supply_flow.iter().sum();
        let leak = sol.side_leakage[0] + sol.side_leakage[1];
        assert!(supply > 0.0 && leak > 0.0);
        assert!(sol.cavitated_fraction > 0.05, "a cavitating film");
        let rel = ((supply - leak) / leak).abs();
        println!("{solver:?}: supply {supply:e} m³/s, leakage {leak:e} m³/s, relative {rel:.1e}");
        // The solve stops at 1e-10 on the residual; 1e-8 relative is the balance asked.
        assert!(rel <= 1e-8, "{solver:?}: {rel:e}");
        worst = worst.max(rel);
    }
    let table = format!(
        "{HEADER}| discrete mass balance, steady grooved bearing (72 × 17, ε (0.6, −0.3), both linear solvers) | supply = side leakage | worst {} relative | ≤ 1e-8 asked |\n",
        sci(worst, 1)
    );
    print!("{table}");
    let name = "steady_grooved_bearing_balances_mass";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// max |Δp| / p_max between two pressure fields.
fn relative_difference<'a>(
    a: impl IntoIterator<Item = &'a f64>,
    b: impl IntoIterator<Item = &'a f64>,
    p_max: f64,
) -> f64 {
    a.into_iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / p_max
}

#[test]
fn adi_krylov_matches_the_sparse_lu_oracle() {
    let mut a = ReynoldsSolver::new(grooved(LinearSolver::AdiKrylov, 72, 17)).unwrap();
    let mut b = ReynoldsSolver::new(grooved(LinearSolver::SparseLu, 72, 17)).unwrap();
    let c = conditions();
    let sa = a.solve_steady([0.5, 0.4], &c).unwrap();
    let sb = b.solve_steady([0.5, 0.4], &c).unwrap();
    let steady = relative_difference(&sa.pressure, &sb.pressure, sb.max_pressure);
    // Same discrete system, the Krylov solve to its tolerance: 1e-7 of p_max, and not one node
    // on the other side of the cavitation switch.
    assert!(steady < 1e-7, "steady: {steady:e}");
    assert_eq!(sa.switch, sb.switch, "steady switch fields");
    let st = a.initial_state([0.5, 0.4]);
    let input = StepInput {
        eccentricity_ratio: [0.52, 0.4],
        dt: 1e-4,
        conditions: c.clone(),
    };
    let (ta, _) = a.solve_step(&st, &input).unwrap();
    let (tb, _) = b.solve_step(&st, &input).unwrap();
    let step = relative_difference(&ta.pressure, &tb.pressure, tb.max_pressure);
    assert!(step < 1e-7, "time step: {step:e}");
    assert_eq!(ta.switch, tb.switch, "time-step switch fields");
    let table = format!(
        "{HEADER}| ADI-Krylov vs sparse-LU oracle (same discrete system, 72 × 17), a steady film and a 0.1 ms time step | LU answer | max \\|Δp\\|/p_max {} (steady), {} (step); identical switch fields | < 1e-7 |\n",
        sci(steady, 1),
        sci(step, 1)
    );
    print!("{table}");
    let name = "adi_krylov_matches_the_sparse_lu_oracle";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// Shaft + feed power = dissipation: −T_journal ω_j − T_bearing ω_b + p_feed Q_feed (the ends at
/// p_amb = 0 take no pressure work) against ∫∫ [μU²f/h + h³|∇p|²/(12μ)] dA. The torques and the
/// dissipation are different quadratures of the film, so the identity closes only as the grid
/// is refined: asserted to fall with every refinement and to be below 5e-4 on the finest grid
/// (the unit test's bound).
#[test]
fn energy_identity_closes_with_the_grid() {
    let mut last = f64::INFINITY;
    let mut measured = Vec::new();
    for (nt, nz) in [(60, 9), (120, 17), (240, 33)] {
        let mut s = ReynoldsSolver::new(grooved(LinearSolver::AdiKrylov, nt, nz)).unwrap();
        let c = conditions();
        let sol = s.solve_steady([0.6, -0.3], &c).unwrap();
        assert!(sol.cavitated_fraction > 0.05, "a cavitating film");
        let input = -sol.friction_torque_journal * c.journal_speed
            - sol.friction_torque_bearing * c.bearing_speed
            + c.feed_pressures[0] * sol.supply_flow[0];
        let mismatch = (input / sol.power_loss - 1.0).abs();
        println!(
            "{nt} × {nz}: input {input:.4} W, dissipation {:.4} W, mismatch {mismatch:.2e}",
            sol.power_loss
        );
        assert!(mismatch < last, "{nt} × {nz}: {mismatch:e} after {last:e}");
        last = mismatch;
        measured.push(sci(mismatch, 1));
    }
    assert!(last < 5e-4, "{last:e}");
    let table = format!(
        "{HEADER}| energy identity, steady grooved film: shaft + feed power = dissipation | exact in the continuum | mismatch {} at 60 × 9 / 120 × 17 / 240 × 33 (two quadratures converging) | falls with the grid, < 5e-4 |\n",
        measured.join(" / ")
    );
    print!("{table}");
    let name = "energy_identity_closes_with_the_grid";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// A groove round the whole circumference at ε = 0: the film is uniform (h = c), so the pressure
/// falls linearly across each land from p_feed at the groove's edge to ambient at the end, and
/// the side leakage is the Poiseuille flow of the two lands, Q = 2 · 2πR c³ p_feed / (12 μ l),
/// l = (L − b)/2 (the unit test `circumferential_groove_leakage_is_exact_on_every_grid` asserts
/// the same, with off-centre grooves too). The groove's edges fall anywhere between the rows of
/// these grids; the first generation, which put the groove's pressure on the outermost row inside
/// it, was off by −6.4 % (60 × 15), −0.18 % (120 × 31), −5.0 % (120 × 32) and −2.7 % (120 × 45).
#[test]
fn circumferential_groove_leakage_matches_its_closed_form_on_every_grid() {
    let (radius, length, clearance, mu, feed, width): (f64, f64, f64, f64, f64, f64) =
        (0.02743, 0.018288, 48.9e-6, 0.0268, 2e5, 3.81e-3);
    let land = 0.5 * (length - width);
    let exact =
        2.0 * std::f64::consts::TAU * radius * clearance.powi(3) * feed / (12.0 * mu * land);
    let grids = [(60, 15), (120, 31), (120, 32), (120, 45), (240, 61)];
    let mut worst: f64 = 0.0;
    for (n_theta, n_z) in grids {
        let mut p = ReynoldsParams::plain(radius, length, clearance, mu);
        p.grid = GridParams { n_theta, n_z };
        p.grooves = vec![Groove {
            center_angle: 0.3,
            center_z: 0.0,
            angular_width: std::f64::consts::TAU,
            axial_width: width,
            cutoff_film_fraction: 0.01,
        }];
        let mut s = ReynoldsSolver::new(p).unwrap();
        let c = OperatingConditions {
            journal_speed: 188.5,
            bearing_speed: 0.0,
            feed_pressures: vec![feed],
        };
        let sol = s.solve_steady([0.0, 0.0], &c).unwrap();
        let q = sol.side_leakage[0] + sol.side_leakage[1];
        let rel = (q / exact - 1.0).abs();
        println!(
            "{n_theta} × {n_z}: leakage {q:e} m³/s, closed form {exact:e}, relative {rel:.1e}"
        );
        // The solve stops at 1e-10 of the flux scale; 1e-9 relative asked.
        assert!(rel <= 1e-9, "{n_theta} × {n_z}: {rel:e}");
        worst = worst.max(rel);
    }
    let table = format!(
        "{HEADER}| side leakage of a circumferential groove (3.81 mm wide, ε = 0), 60 × 15, 120 × 31, 120 × 32, 120 × 45, 240 × 61 | closed form 2 · 2πR c³ p_feed / (12 μ l) | worst {} relative | ≤ 1e-9 asked |\n",
        sci(worst, 1)
    );
    print!("{table}");
    let name = "circumferential_groove_leakage_matches_its_closed_form_on_every_grid";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}
