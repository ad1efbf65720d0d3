//! Tests of the multigrid preconditioner: transfer operators, Galerkin coarse operator, the
//! preconditioned FGMRES against the sparse-LU oracle, and the grid independence of the
//! Krylov iteration count.

use super::super::*;
use super::*;

/// The compressor main bearing of the validation timing case (design.md §7): L = 18.288 mm,
/// R = 27.43 mm, c = 48.9 µm, μ = 0.02 Pa·s, partial groove 24.9 × 3.81 mm at θ = 90°.
fn compressor(solver: LinearSolver, n_theta: usize, n_z: usize) -> ReynoldsParams {
    let mut p = ReynoldsParams::plain(27.43e-3, 18.288e-3, 48.9e-6, 0.02);
    p.grid = GridParams { n_theta, n_z };
    p.linear_solver = solver;
    p.grooves = vec![Groove {
        center_angle: std::f64::consts::FRAC_PI_2,
        center_z: 0.0,
        angular_width: 3.81e-3 / 27.43e-3,
        axial_width: 24.9e-3,
        cutoff_film_fraction: 0.01,
    }];
    p
}

fn running(feed: f64) -> OperatingConditions {
    OperatingConditions {
        journal_speed: 1800.0 * std::f64::consts::TAU / 60.0,
        bearing_speed: 0.0,
        feed_pressures: vec![feed],
    }
}

/// Krylov iterations per frozen-switch solve of a steady solve and of one time step.
fn iterations_per_solve(solver: LinearSolver, n_theta: usize, n_z: usize) -> (f64, f64) {
    let mut s = ReynoldsSolver::new(compressor(solver, n_theta, n_z)).unwrap();
    let c = running(0.2068e6);
    let steady = s.solve_steady([0.0, -0.8], &c).unwrap();
    let st = steady.linear_iterations as f64 / steady.iterations as f64;
    let state = s.initial_state([0.0, -0.6]);
    let input = StepInput {
        eccentricity_ratio: [0.05, -0.62],
        dt: 1.0 / (1800.0 / 60.0) / 360.0,
        conditions: c,
    };
    let (step, _) = s.solve_step(&state, &input).unwrap();
    let tr = step.linear_iterations as f64 / step.iterations as f64;
    (st, tr)
}

#[test]
#[ignore]
fn print_iteration_growth() {
    for solver in [LinearSolver::AdiKrylov, LinearSolver::MultigridKrylov] {
        for (nt, nz) in [(60, 15), (120, 31), (240, 61)] {
            let (a, b) = iterations_per_solve(solver, nt, nz);
            eprintln!("{solver:?} {nt}x{nz}: steady {a:.1} step {b:.1}");
        }
    }
}
