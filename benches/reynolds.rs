//! Reynolds-solver benches (one core).
//!
//! - `reynolds/cold_steady/<preconditioner>/<grid>`: a steady film from a cold start (full film
//!   at ambient) at the default grid 120 × 31 (29 axial cells) and at 2× (240 × 60) refinement
//!   in each direction (the 4× grid, 480 × 118, is left out so that the CI run stays short):
//!   L/D = 1, ε = 0.6, the Butenschön problem (supply line at h_max), with the multigrid
//!   preconditioner (the default) and the ADI one, measured in one run so that their ratio
//!   compares.
//! - `reynolds/cold_steady_lu/120x31`: the same with the sparse-LU oracle, for comparison.
//! - `reynolds/viscosity/{constant,vogel_linear}/120x31`: the cold steady film of the first
//!   bench (multigrid) with a constant viscosity and with \[Benasciutti2012\]'s Vogel oil under a linear
//!   temperature rise 40 → 80 °C over the converging half (a viscosity field, α = 0), in one
//!   run: issue 14 asks the field to cost ≤ 1.5× the constant.
//! - `reynolds/warm_step/120x31`: one BDF2 step (the default scheme) of a grooved bearing whirling at
//!   ε = 0.6 (1° of whirl per step), warm-started from the previous step's film (the default
//!   linear solver, multigrid-Krylov). The groove is centred on the mid-plane, so the solver
//!   works on the half grid (`reynolds::grid` docs, "Mirror symmetry"); `warm_step_whole_length`
//!   is the same step on the whole grid (`ReynoldsSolver::new_whole_length`), in one run.
use criterion::Criterion;
use jbearing_solvers::reynolds::{
    GridParams, Groove, LinearSolver, OperatingConditions, ReynoldsParams, ReynoldsSolver,
    StepInput, SupplyModel,
};
use jbearing_solvers::viscosity::{Temperature, ViscosityModel, Vogel};
use std::hint::black_box;

fn steady_solver(grid: GridParams, linear: LinearSolver) -> ReynoldsSolver {
    let mut p = ReynoldsParams::plain(0.05, 0.1, 50e-6, 0.01);
    p.supply = SupplyModel::AxialLineAtMaxGap;
    p.grid = grid;
    p.linear_solver = linear;
    ReynoldsSolver::new(p).expect("params")
}

pub fn bench(c: &mut Criterion) {
    let cond = OperatingConditions {
        journal_speed: 100.0,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    };
    let mut group = c.benchmark_group("reynolds");
    // Solves take 0.03–1.5 s: ten samples keep the run (and the CI run) short.
    group.sample_size(10);
    let preconditioners = [
        ("multigrid", LinearSolver::MultigridKrylov),
        ("adi", LinearSolver::AdiKrylov),
    ];
    for ((name, linear), (nt, nz)) in preconditioners
        .into_iter()
        .flat_map(|l| [(120, 31), (240, 60)].map(move |g| (l, g)))
    {
        let mut s = steady_solver(
            GridParams {
                n_theta: nt,
                n_z: nz,
            },
            linear,
        );
        group.bench_function(format!("cold_steady/{name}/{nt}x{nz}"), |b| {
            b.iter(|| {
                black_box(
                    s.solve_steady(black_box([0.6, 0.0]), &cond)
                        .expect("steady"),
                )
            })
        });
    }
    let mut s = steady_solver(GridParams::default(), LinearSolver::SparseLu);
    group.bench_function("cold_steady_lu/120x31", |b| {
        b.iter(|| {
            black_box(
                s.solve_steady(black_box([0.6, 0.0]), &cond)
                    .expect("steady"),
            )
        })
    });

    // Constant against a temperature field (α = 0), same film.
    for (name, model) in [
        ("constant", None),
        (
            "vogel_linear",
            Some(ViscosityModel {
                vogel: Vogel::seed003_iso_vg_680(),
                temperature: Temperature::LinearOverSpan {
                    inlet: 40.0,
                    outlet: 80.0,
                    span: std::f64::consts::PI,
                },
                pressure_coefficient: 0.0,
            }),
        ),
    ] {
        let mut p = ReynoldsParams::plain(0.05, 0.1, 50e-6, 0.01);
        p.supply = SupplyModel::AxialLineAtMaxGap;
        p.viscosity_model = model;
        let mut s = ReynoldsSolver::new(p).expect("params");
        group.bench_function(format!("viscosity/{name}/120x31"), |b| {
            b.iter(|| {
                black_box(
                    s.solve_steady(black_box([0.6, 0.0]), &cond)
                        .expect("steady"),
                )
            })
        });
    }

    // Warm step: grooved bearing, whirl at ε = 0.6, 1° of whirl per step.
    let mut p = ReynoldsParams::plain(0.05, 0.1, 50e-6, 0.01);
    p.grooves = vec![Groove {
        center_angle: std::f64::consts::PI,
        center_z: 0.0,
        angular_width: 0.2,
        axial_width: 0.03,
        cutoff_film_fraction: 0.01,
    }];
    // The groove is centred on the mid-plane: the solver works on the half grid (the
    // default); the whole-length solve of the same step beside it.
    let solvers = [
        ("warm_step/120x31", ReynoldsSolver::new(p.clone())),
        (
            "warm_step_whole_length/120x31",
            ReynoldsSolver::new_whole_length(p),
        ),
    ];
    let cond = OperatingConditions {
        journal_speed: 100.0,
        bearing_speed: 0.0,
        feed_pressures: vec![2e5],
    };
    let whirl = 30.0;
    let dt = 1f64.to_radians() / whirl;
    let eps = |n: usize| {
        let a = whirl * dt * n as f64;
        [0.6 * a.cos(), 0.6 * a.sin()]
    };
    for (name, s) in solvers {
        let mut s = s.expect("params");
        let mut state = s.initial_state(eps(0));
        for n in 1..=360 {
            let input = StepInput {
                eccentricity_ratio: eps(n),
                dt,
                conditions: cond.clone(),
            };
            state = s.solve_step(&state, &input).expect("run-in").1;
        }
        let input = StepInput {
            eccentricity_ratio: eps(361),
            dt,
            conditions: cond.clone(),
        };
        group.bench_function(name, |b| {
            b.iter(|| black_box(s.solve_step(black_box(&state), &input).expect("step")))
        });
    }
    group.finish();
}
