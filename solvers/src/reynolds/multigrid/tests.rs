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

/// A frozen-switch system of the real discretization at ε (steady or one time step), with
/// the switch `g_of(θ)` on the unknown nodes.
fn frozen_system_g(
    n_theta: usize,
    n_z: usize,
    eps: [f64; 2],
    dt: Option<f64>,
    g_of: &dyn Fn(f64, f64) -> f64,
) -> (ReynoldsSolver, Stencil, Vec<f64>) {
    let mut s = ReynoldsSolver::new(compressor(LinearSolver::MultigridKrylov, n_theta, n_z)).unwrap();
    let c = running(0.2068e6);
    let prep = s.prepare(eps, &c, None).unwrap();
    let grid = &s.grid;
    let level = discretization::Level {
        grid,
        h: &prep.h.node,
        h_face: &prep.h.face_theta,
        k_theta: &s.k_theta,
        k_z: &s.k_z,
        speed: prep.speed,
    };
    let mut g = prep.g.clone();
    for k in 0..grid.len() {
        if grid.kind[k] == NodeKind::Unknown {
            g[k] = g_of(grid.theta(k / n_z), grid.z(k % n_z));
        }
    }
    let old: Vec<f64> = prep.h.node.iter().map(|h| 0.9 * h).collect();
    let time = match dt {
        None => TimeTerm::Steady,
        Some(dt) => TimeTerm::Step {
            dt,
            old_content: &old,
            old_outflow: None,
        },
    };
    let mut st = Stencil::default();
    discretization::assemble(&level, &g, &s.dirichlet, time, &mut st);
    (s, st, g)
}

#[test]
#[ignore]
fn print_frozen_iterations() {
    let dt = 1.0 / 30.0 / 360.0;
    let cases: [(&str, Option<f64>, &dyn Fn(f64, f64) -> f64); 4] = [
        ("full steady", None, &|_, _| 1.0),
        ("full step", Some(dt), &|_, _| 1.0),
        ("cav steady", None, &|th: f64, _| if th.sin() > 0.3 { 1.0 } else { 0.0 }),
        ("cav step", Some(dt), &|th: f64, _| if th.sin() > 0.3 { 1.0 } else { 0.0 }),
    ];
    for (name, dt, g) in cases {
        for pc in [adi::Preconditioner::Adi, adi::Preconditioner::Multigrid] {
            let mut line = String::new();
            for (nt, nz) in [(60, 15), (120, 31), (240, 61)] {
                let (s, st, g) = frozen_system_g(nt, nz, [0.0, -0.8], dt, g);
                let mut x: Vec<f64> = (0..s.grid.len())
                    .map(|k| if s.grid.kind[k] == NodeKind::Unknown { 0.0 } else { st.rhs[k] })
                    .collect();
                let mut ws = adi::AdiWorkspace::default();
                let r = adi::solve_krylov(&s.grid, &st, &mut x, 1e-10, None, 400, pc, Some(&g), &mut ws);
                line += &format!(" {nt}x{nz}: {:?}", r.map(|i| i.iterations));
            }
            eprintln!("{name} {pc:?}:{line}");
        }
    }
}

#[test]
#[ignore]
fn print_stationary_rates() {
    let dt = 1.0 / 30.0 / 360.0;
    let cases: [(&str, Option<f64>, &dyn Fn(f64, f64) -> f64); 4] = [
        ("full steady", None, &|_, _| 1.0),
        ("full step", Some(dt), &|_, _| 1.0),
        ("cav steady", None, &|th: f64, _| if th.sin() > 0.3 { 1.0 } else { 0.0 }),
        ("cav step", Some(dt), &|th: f64, _| if th.sin() > 0.3 { 1.0 } else { 0.0 }),
    ];
    for (name, dt, g) in cases {
        for (nt, nz) in [(60, 15), (120, 31), (240, 61)] {
            let (s, st, g) = frozen_system_g(nt, nz, [0.0, -0.8], dt, g);
            let n = s.grid.len();
            let mut mg = Multigrid::default();
            mg.setup(&s.grid, &st, Some(&g)).unwrap();
            let mut x = vec![0.0; n];
            let mut r = vec![0.0; n];
            let mut z = vec![0.0; n];
            let mut hist = Vec::new();
            for _ in 0..12 {
                let (rmax, _) = st.residual(&s.grid, &x, &mut r);
                hist.push(rmax);
                mg.apply(&r, &mut z).unwrap();
                for k in 0..n {
                    x[k] += z[k];
                }
            }
            let rates: Vec<String> = hist.windows(2).map(|w| format!("{:.2}", w[1] / w[0])).collect();
            eprintln!("{name} {nt}x{nz} depth {}: {}", mg.depth(), rates.join(" "));
        }
    }
}

#[test]
#[ignore]
fn print_real_switch() {
    for (nt, nz) in [(60, 15), (120, 31), (240, 61)] {
        let mut s = ReynoldsSolver::new(compressor(LinearSolver::SparseLu, nt, nz)).unwrap();
        let sol = s.solve_steady([0.0, -0.8], &running(0.2068e6)).unwrap();
        let sw: Vec<f64> = sol.switch.iter().copied().collect();
        let (s, st, g) = frozen_system_g(nt, nz, [0.0, -0.8], None, &|_, _| 1.0);
        let g: Vec<f64> = (0..g.len())
            .map(|k| if s.grid.kind[k] == NodeKind::Unknown { sw[k] } else { g[k] })
            .collect();
        let (s, st) = {
            let mut s2 = s;
            let c = running(0.2068e6);
            let prep = s2.prepare([0.0, -0.8], &c, None).unwrap();
            let level = discretization::Level {
                grid: &s2.grid,
                h: &prep.h.node,
                h_face: &prep.h.face_theta,
                k_theta: &s2.k_theta,
                k_z: &s2.k_z,
                speed: prep.speed,
            };
            let mut st2 = st;
            discretization::assemble(&level, &g, &s2.dirichlet, TimeTerm::Steady, &mut st2);
            (s2, st2)
        };
        let n = s.grid.len();
        let mut mg = Multigrid::default();
        mg.setup(&s.grid, &st, Some(&g)).unwrap();
        let mut x: Vec<f64> = (0..n)
            .map(|k| if s.grid.kind[k] == NodeKind::Unknown { 0.0 } else { st.rhs[k] })
            .collect();
        let x0 = x.clone();
        let mut r = vec![0.0; n];
        let mut z = vec![0.0; n];
        let mut hist = Vec::new();
        for _ in 0..12 {
            let (rmax, _) = st.residual(&s.grid, &x, &mut r);
            hist.push(rmax);
            mg.apply(&r, &mut z).unwrap();
            for k in 0..n {
                x[k] += z[k];
            }
        }
        let rates: Vec<String> = hist.windows(2).map(|w| format!("{:.2}", w[1] / w[0])).collect();
        {
            let mut idx: Vec<usize> = (0..n).collect();
            idx.sort_by(|&a, &b| r[b].abs().partial_cmp(&r[a].abs()).unwrap());
            for &k in idx.iter().take(8) {
                let (i, j) = (k / nz, k % nz);
                eprintln!(
                    "  r {:.2e} at ({i},{j}) g {} gW {} gE {} gS {} gN {} p {:.2e} w {:.2e} e {:.2e}",
                    r[k], g[k], g[(i + nt - 1) % nt * nz + j], g[(i + 1) % nt * nz + j], g[k - 1], g[k + 1], st.p[k], st.w[k], st.e[k]
                );
            }
        }
        let cav = g.iter().filter(|&&v| v < 0.5).count();
        let mut x = x0;
        let mut ws = adi::AdiWorkspace::default();
        let it = adi::solve_krylov(&s.grid, &st, &mut x, 1e-10, None, 400, adi::Preconditioner::Multigrid, Some(&g), &mut ws);
        eprintln!("real switch {nt}x{nz} cav {cav}: fgmres {:?} rates {}", it.map(|i| i.iterations), rates.join(" "));
    }
}
