//! Reynolds solver against the finite-bearing tables (docs/conventions.md §8 rung 3): Butenschön \[Butenschoen1976\]
//! rotation tables for B/d = 1, 1/2, 1/3 and Raimondi & Boyd \[RaimondiBoyd1958\] for L/D = 1, 1/2
//! (`data/reference/*.csv`, provenance in the `.md` beside each). Both tables solve the problem
//! "the film starts at the widest gap": a full-length axial supply line at ambient pressure on
//! the h_max line ([`SupplyModel::AxialLineAtMaxGap`]).
//!
//! Tolerances (the issue's): Sommerfeld number 3 %, attitude 1.5°, side-flow number 5 %, at the
//! default grid; `default_grid_is_converged` shows the grid convergence that justifies it.

use std::f64::consts::PI;

use jbearing_solvers::reynolds::{
    FilmSolution, GridParams, OperatingConditions, ReynoldsParams, ReynoldsSolver, SupplyModel,
};
use jbearing_validation::generated_docs::{fixed, signed, write_if_requested};
use jbearing_validation::read_reference_csv;
use std::fmt::Write;

/// The command that reproduces the block of docs/validation.md written by the test `name`.
fn command(name: &str) -> String {
    format!(
        "cargo test --release -p jbearing-validation --test reynolds_tables -- --nocapture {name}"
    )
}

/// The header of the Reynolds-solver tables of docs/validation.md.
const HEADER: &str = "| case | reference | ours | error |\n|---|---|---|---|\n";

/// B/d as the docs write it.
fn ratio(bd: f64) -> &'static str {
    match bd {
        x if (x - 1.0).abs() < 1e-9 => "1",
        x if (x - 0.5).abs() < 1e-9 => "1/2",
        x if (x - 1.0 / 3.0).abs() < 1e-9 => "1/3",
        _ => "?",
    }
}

const R: f64 = 0.05;
const C: f64 = 50e-6;
// Low μω keeps film pressures small against the physical bulk modulus, so that compressibility
// (and the upwinded Couette flux's artificial diffusion, 3μUΔx/(βh²) of the pressure flux —
// both O(p/β)) adds nothing the incompressible tables do not have. Measured at ε = 0.99, B/d 1,
// 120 × 31: So +2.42 % against the table with μω = 0.04 Pa (p_max ≈ 30 MPa), +1.40 % with
// β × 100, the incompressible limit; μω = 0.004 Pa brings the film to that limit.
const MU: f64 = 0.002;
const OMEGA: f64 = 2.0;

fn solver(l_over_d: f64, grid: GridParams) -> ReynoldsSolver {
    let mut p = ReynoldsParams::plain(R, l_over_d * 2.0 * R, C, MU);
    p.supply = SupplyModel::AxialLineAtMaxGap;
    p.grid = grid;
    ReynoldsSolver::new(p).unwrap()
}

fn solve(s: &mut ReynoldsSolver, eps: f64) -> FilmSolution {
    let c = OperatingConditions {
        journal_speed: OMEGA,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    };
    s.solve_steady([eps, 0.0], &c).unwrap()
}

/// The Couette shear force μU(1 − φ)/h dA that the film fractions φ < 1 of the cavitated
/// cells leave out of our journal torque (ε along +x: h = c(1 − ε cos θ); the end rows are
/// boundary points without area).
fn unsheared_shear_force(sol: &FilmSolution, eps: f64) -> f64 {
    let dth = sol.theta[1] - sol.theta[0];
    let dz = sol.z[2] - sol.z[1];
    let mut force = 0.0;
    for (i, th) in sol.theta.iter().enumerate() {
        let h = C * (1.0 - eps * th.cos());
        for j in 1..sol.z.len() - 1 {
            force += MU * R * OMEGA * (1.0 - sol.film_fraction[[i, j]]) / h * R * dth * dz;
        }
    }
    force
}

/// (So, β in degrees, Q) in Butenschön's definitions.
fn butenschoen_numbers(sol: &FilmSolution, b_over_d: f64) -> (f64, f64, f64) {
    let l = b_over_d * 2.0 * R;
    let psi = C / R;
    let pm = sol.load_capacity / (l * 2.0 * R);
    let so = pm * psi * psi / (MU * OMEGA);
    let q = (sol.side_leakage[0] + sol.side_leakage[1]) / (R * R * C * OMEGA);
    (so, sol.attitude_angle.to_degrees(), q)
}

#[test]
fn butenschoen_rotation_table() {
    let rows = read_reference_csv("butenschoen_rotation.csv");
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    let mut table = String::from(HEADER);
    for bd in [1.0, 0.5, 1.0 / 3.0] {
        let mut s = solver(bd, GridParams::for_length_ratio(bd));
        let mut worst_bd = (0.0f64, 0.0f64, 0.0f64);
        for row in rows
            .iter()
            .filter(|r| (r[0] - bd).abs() < 1e-3 && r[1] <= 0.9 + 1e-9)
        {
            let (eps, so_ref, beta_ref, q_ref) = (row[1], row[2], row[3], row[4]);
            let sol = solve(&mut s, eps);
            let (so, beta, q) = butenschoen_numbers(&sol, bd);
            let (e_so, e_b, e_q) = ((so - so_ref) / so_ref, beta - beta_ref, (q - q_ref) / q_ref);
            eprintln!(
                "Butenschön B/d={bd:.3} ε={eps}: So {so:.4} ({so_ref}) {:+.2} %, β {beta:.2}° ({beta_ref}) {e_b:+.2}°, Q {q:.4} ({q_ref}) {:+.2} % [switch {} krylov {}]",
                100.0 * e_so,
                100.0 * e_q,
                sol.iterations,
                sol.linear_iterations
            );
            worst = (
                worst.0.max(e_so.abs()),
                worst.1.max(e_b.abs()),
                worst.2.max(e_q.abs()),
            );
            worst_bd = (
                worst_bd.0.max(e_so.abs()),
                worst_bd.1.max(e_b.abs()),
                worst_bd.2.max(e_q.abs()),
            );
            assert!(e_so.abs() < 0.03, "B/d {bd} ε {eps}: So {so} vs {so_ref}");
            assert!(e_b.abs() < 1.5, "B/d {bd} ε {eps}: β {beta} vs {beta_ref}");
            assert!(e_q.abs() < 0.05, "B/d {bd} ε {eps}: Q {q} vs {q_ref}");
        }
        let _ = writeln!(
            table,
            "| Butenschön B/d = {}, ε = 0.1 … 0.9 | table | worst So {} %, β {}°, Q {} % | 3 %, 1.5°, 5 % |",
            ratio(bd),
            fixed(100.0 * worst_bd.0, 2),
            fixed(worst_bd.1, 2),
            fixed(100.0 * worst_bd.2, 2),
        );
    }
    eprintln!(
        "Butenschön worst: So {:.2} %, β {:.2}°, Q {:.2} %",
        100.0 * worst.0,
        worst.1,
        100.0 * worst.2
    );
    print!("{table}");
    let name = "butenschoen_rotation_table";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

#[test]
fn raimondi_boyd_table() {
    let rows = read_reference_csv("raimondi_boyd_full.csv");
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    let mut worst_friction = 0.0f64;
    let mut table = String::from(HEADER);
    for ld in [1.0, 0.5] {
        let l = ld * 2.0 * R;
        let mut s = solver(ld, GridParams::for_length_ratio(ld));
        // Worst S, φ, Qs and (R/c)f of this L/D.
        let mut worst_ld = [0.0f64; 4];
        for row in rows
            .iter()
            .filter(|r| (r[0] - ld).abs() < 1e-6 && r[1] <= 0.9 + 1e-9)
        {
            let (eps, s_ref, phi_ref, q_ref, qs_frac) = (row[1], row[2], row[3], row[5], row[6]);
            let sol = solve(&mut s, eps);
            let n = OMEGA / (2.0 * PI);
            let pm = sol.load_capacity / (l * 2.0 * R);
            let som = (R / C).powi(2) * MU * n / pm;
            let phi = sol.attitude_angle.to_degrees();
            let qs = (sol.side_leakage[0] + sol.side_leakage[1]) / (R * C * n * l);
            // Friction variable (R/c) f, f = (|T_journal| / R) / W. Our torque shears only the
            // oil fraction φ of a cavitated cell (docs/conventions.md §5); Raimondi & Boyd shear the full
            // film over 360°, so their convention adds μU(1 − φ)/h over the cavitated cells.
            let rcf_oil = (R / C) * (sol.friction_torque_journal.abs() / R) / sol.load_capacity;
            let rcf = (R / C)
                * ((sol.friction_torque_journal.abs() + R * unsheared_shear_force(&sol, eps)) / R)
                / sol.load_capacity;
            let e_f = (rcf - row[4]) / row[4];
            eprintln!(
                "   (R/c)f {rcf:.4} ({}) {:+.2} % (oil fraction only: {rcf_oil:.4})",
                row[4],
                100.0 * e_f
            );
            worst_friction = worst_friction.max(e_f.abs());
            // Worst measured 1.0 % (L/D 1/2, ε 0.6); the table prints three digits.
            assert!(
                e_f.abs() < 0.02,
                "L/D {ld} ε {eps}: (R/c)f {rcf} vs {}",
                row[4]
            );
            assert!(rcf_oil < rcf);
            let qs_ref = q_ref * qs_frac;
            let (e_s, e_p, e_q) = ((som - s_ref) / s_ref, phi - phi_ref, (qs - qs_ref) / qs_ref);
            eprintln!(
                "Raimondi–Boyd L/D={ld} ε={eps}: S {som:.4} ({s_ref}) {:+.2} %, φ {phi:.2}° ({phi_ref}) {e_p:+.2}°, Qs/(RcNL) {qs:.4} ({qs_ref:.4}) {:+.2} %",
                100.0 * e_s,
                100.0 * e_q
            );
            worst = (
                worst.0.max(e_s.abs()),
                worst.1.max(e_p.abs()),
                worst.2.max(e_q.abs()),
            );
            // Same tolerances; the table's three printed digits add up to 0.5 % at ε = 0.9.
            assert!(e_s.abs() < 0.03, "L/D {ld} ε {eps}: S {som} vs {s_ref}");
            assert!(e_p.abs() < 1.5, "L/D {ld} ε {eps}: φ {phi} vs {phi_ref}");
            assert!(e_q.abs() < 0.05, "L/D {ld} ε {eps}: Qs {qs} vs {qs_ref}");
            for (w, e) in worst_ld.iter_mut().zip([e_s, e_p, e_q, e_f]) {
                *w = w.max(e.abs());
            }
        }
        let _ = writeln!(
            table,
            "| Raimondi–Boyd L/D = {}, ε = 0.1 … 0.9 | table | worst S {} %, φ {}°, Qs {} %, (R/c)f {} % | 3 %, 1.5°, 5 %, 2 % |",
            ratio(ld),
            fixed(100.0 * worst_ld[0], 2),
            fixed(worst_ld[1], 2),
            fixed(100.0 * worst_ld[2], 2),
            fixed(100.0 * worst_ld[3], 2),
        );
    }
    eprintln!(
        "Raimondi–Boyd worst: S {:.2} %, φ {:.2}°, Qs {:.2} %, (R/c)f {:.2} %",
        100.0 * worst.0,
        worst.1,
        100.0 * worst.2,
        100.0 * worst_friction
    );
    print!("{table}");
    let name = "raimondi_boyd_table";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// Grid convergence behind the default grid (120 × 31): at B/d = 1, ε = 0.6 and 0.9 the
/// default grid's So, β, Q against a 2× finer grid (240 × 60: 58 axial cells) and a coarser one
/// (60 × 16: 14 cells):
/// the differences shrink with refinement and the default grid is within 1 % (So, Q) and 0.3°
/// (β) of the fine grid — a third of the table tolerances.
#[test]
fn default_grid_is_converged() {
    let grid_names = ["60 × 16", "120 × 31 (default)", "240 × 60"];
    // cells[grid][ε]: "So, β°, Q"; the last row is Butenschön's table.
    let mut cells = vec![Vec::new(); 4];
    let table_rows = read_reference_csv("butenschoen_rotation.csv");
    for eps in [0.6, 0.9] {
        let mut res = Vec::new();
        for grid in [
            GridParams {
                n_theta: 60,
                n_z: 16,
            },
            GridParams::for_length_ratio(1.0),
            GridParams {
                n_theta: 240,
                n_z: 60,
            },
        ] {
            let mut s = solver(1.0, grid);
            let sol = solve(&mut s, eps);
            let v = butenschoen_numbers(&sol, 1.0);
            eprintln!(
                "grid {}×{} ε={eps}: So {:.5} β {:.3}° Q {:.5}",
                grid.n_theta, grid.n_z, v.0, v.1, v.2
            );
            res.push(v);
        }
        for (k, v) in res.iter().enumerate() {
            cells[k].push(format!(
                "{}, {}°, {}",
                fixed(v.0, 4),
                fixed(v.1, 2),
                fixed(v.2, 4)
            ));
        }
        let r = table_rows
            .iter()
            .find(|r| (r[0] - 1.0).abs() < 1e-3 && (r[1] - eps).abs() < 1e-9)
            .expect("the table has B/d 1 at this ε");
        cells[3].push(format!(
            "{}, {}°, {}",
            fixed(r[2], 4),
            fixed(r[3], 2),
            fixed(r[4], 4)
        ));
        let (c, d, f) = (res[0], res[1], res[2]);
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(d.0, f.0) < 0.01 && rel(d.2, f.2) < 0.01 && (d.1 - f.1).abs() < 0.3);
        assert!(rel(d.0, f.0) < rel(c.0, f.0));
        assert!(rel(d.2, f.2) < rel(c.2, f.2));
    }
    let mut table = String::from("| grid | ε = 0.6 | ε = 0.9 |\n|---|---|---|\n");
    for (name, row) in grid_names.iter().chain(&["table"]).zip(&cells) {
        let _ = writeln!(table, "| {name} | {} |", row.join(" | "));
    }
    print!("{table}");
    let name = "default_grid_is_converged";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// Butenschön's rows at ε = 0.95 … 0.99 (B/d = 1, 1/2, 1/3) at the default grid, against the
/// tolerances the product promises up to ε = 0.99 (issue 11 item 6): So 2 %, β 0.5°, Q 2 %.
/// These were out of reach of the first-generation film (node-averaged h in the Couette flux:
/// +2.2 … +10 % in So at ε 0.95–0.99).
#[test]
fn butenschoen_rotation_table_high_eccentricity() {
    let rows = read_reference_csv("butenschoen_rotation.csv");
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    // Where the worst So lies: (B/d, ε).
    let mut worst_at = (0.0, 0.0);
    for bd in [1.0, 0.5, 1.0 / 3.0] {
        let mut s = solver(bd, GridParams::for_length_ratio(bd));
        for row in rows
            .iter()
            .filter(|r| (r[0] - bd).abs() < 1e-3 && r[1] > 0.9 + 1e-9)
        {
            let (eps, so_ref, beta_ref, q_ref) = (row[1], row[2], row[3], row[4]);
            let sol = solve(&mut s, eps);
            let (so, beta, q) = butenschoen_numbers(&sol, bd);
            let (e_so, e_b, e_q) = ((so - so_ref) / so_ref, beta - beta_ref, (q - q_ref) / q_ref);
            eprintln!(
                "Butenschön B/d={bd:.3} ε={eps}: So {so:.4} ({so_ref}) {:+.2} %, β {beta:.2}° ({beta_ref}) {e_b:+.2}°, Q {q:.4} ({q_ref}) {:+.2} %",
                100.0 * e_so,
                100.0 * e_q,
            );
            if e_so.abs() > worst.0 {
                worst_at = (bd, eps);
            }
            worst = (
                worst.0.max(e_so.abs()),
                worst.1.max(e_b.abs()),
                worst.2.max(e_q.abs()),
            );
        }
    }
    eprintln!(
        "Butenschön ε > 0.9 worst: So {:.2} %, β {:.2}°, Q {:.2} %",
        100.0 * worst.0,
        worst.1,
        100.0 * worst.2
    );
    assert!(worst.0 < 0.02, "So {:.2} %", 100.0 * worst.0);
    assert!(worst.1 < 0.5, "β {:.2}°", worst.1);
    assert!(worst.2 < 0.02, "Q {:.2} %", 100.0 * worst.2);
    let table = format!(
        "{HEADER}| Butenschön B/d = 1, 1/2, 1/3, ε = 0.95 … 0.99 | table | worst So {} % (B/d {}, ε {}), β {}°, Q {} % | 2 %, 0.5°, 2 % |\n",
        fixed(100.0 * worst.0, 2),
        ratio(worst_at.0),
        worst_at.1,
        fixed(worst.1, 2),
        fixed(100.0 * worst.2, 2),
    );
    print!("{table}");
    let name = "butenschoen_rotation_table_high_eccentricity";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

/// Below the tables' B/d = 1/3: B/d = 1/10 … 1/4 have no published rows here, so the default
/// grid of each B/d ([`GridParams::for_length_ratio`]: 160 × 23 below B/d 1/4, 120 × 31 from
/// it) is checked against an independent answer of the same equations, the solution on 960 × 61
/// nodes (its own error is bounded by its distance to 480 × 61, asserted below 0.3 % in So at
/// ε 0.99 where it is largest; second order leaves a third of that). Asserted: the product's
/// tolerances at ε = 0.95 and 0.99 (issue 11 item 6: So 2 %, β 0.5°, Q 2 %; at ε ≤ 0.9 the
/// peak spans several cells and the default grid is within 0.5 %), twice — with the
/// thinnest film on a node (the default grid; Butenschön's problem turns the grid so that its
/// supply line, opposite the thinnest film, lies on node 0) and half-way between two nodes (one
/// node more around), since at ε 0.99 the pressure peak is narrower than a cell (width ~ 1 − ε
/// = 0.01 rad against Δθ = 0.04 rad) and the error depends on where it falls. The old default
/// 120 × 31 is printed beside it: +2.2 % / −1.5 % at B/d 1/8, ε 0.99.
#[test]
fn short_bearings_default_grid_against_a_fine_grid() {
    let reference_grid = GridParams {
        n_theta: 960,
        n_z: 61,
    };
    let mut table = String::from(
        "| B/d | ε | default grid | So: film on a node / between nodes | β | Q | 120 × 31 (the old default): So on a node / between |\n|---|---|---|---|---|---|---|\n",
    );
    let rel = |a: f64, b: f64| (a - b) / b;
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    for (bd, bd_name) in [(0.1, "1/10"), (0.125, "1/8"), (0.2, "1/5"), (0.25, "1/4")] {
        let default = GridParams::for_length_ratio(bd);
        let between = GridParams {
            n_theta: default.n_theta + 1,
            ..default
        };
        let old = GridParams::default();
        let old_between = GridParams {
            n_theta: old.n_theta + 1,
            ..old
        };
        for eps in [0.95, 0.99] {
            let numbers = |g: GridParams| butenschoen_numbers(&solve(&mut solver(bd, g), eps), bd);
            let fine = numbers(reference_grid);
            if eps == 0.99 {
                // The reference's own error, where it is largest.
                let half = numbers(GridParams {
                    n_theta: 480,
                    ..reference_grid
                });
                assert!(
                    rel(half.0, fine.0).abs() < 3e-3,
                    "reference not converged: 480 vs 960 around {:+.3} %",
                    100.0 * rel(half.0, fine.0)
                );
            }
            let [d, b, o, ob] = [default, between, old, old_between].map(numbers);
            let so = [rel(d.0, fine.0), rel(b.0, fine.0)];
            let beta = (d.1 - fine.1).abs().max((b.1 - fine.1).abs());
            let q = rel(d.2, fine.2).abs().max(rel(b.2, fine.2).abs());
            eprintln!(
                "B/d={bd} ε={eps} {}×{}: So {:+.2} % / {:+.2} % (120×31: {:+.2} % / {:+.2} %), β ±{beta:.3}°, Q ±{:.3} %",
                default.n_theta,
                default.n_z,
                100.0 * so[0],
                100.0 * so[1],
                100.0 * rel(o.0, fine.0),
                100.0 * rel(ob.0, fine.0),
                100.0 * q
            );
            worst = (
                worst.0.max(so[0].abs()).max(so[1].abs()),
                worst.1.max(beta),
                worst.2.max(q),
            );
            let _ = writeln!(
                table,
                "| {bd_name} | {eps} | {} × {} | {} % / {} % | ±{}° | ±{} % | {} % / {} % |",
                default.n_theta,
                default.n_z,
                signed(100.0 * so[0], 2),
                signed(100.0 * so[1], 2),
                fixed(beta, 3),
                fixed(100.0 * q, 3),
                signed(100.0 * rel(o.0, fine.0), 2),
                signed(100.0 * rel(ob.0, fine.0), 2),
            );
        }
    }
    print!("{table}");
    assert!(worst.0 < 0.02, "So {:.2} %", 100.0 * worst.0);
    assert!(worst.1 < 0.5, "β {:.2}°", worst.1);
    assert!(worst.2 < 0.02, "Q {:.2} %", 100.0 * worst.2);
    let name = "short_bearings_default_grid_against_a_fine_grid";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}
