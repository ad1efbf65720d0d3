//! The closed-form models and the Ritz pressure against the finite-difference Reynolds solver
//! ([`jbearing_solvers::reynolds`]) in the limits where they are exact or comparable:
//! - infinitely short bearing, Gumbel film, as L/D → 0 (FD: Reynolds/JFO rupture, film starting
//!   at the widest gap, docs/conventions.md §8) — the difference must fall like (L/D)²;
//! - infinitely long bearing, full film (Sommerfeld), as L/D → ∞ (FD: cavitation suppressed by a
//!   high ambient pressure, gauge-shifted back) — the mid-plane pressure must approach eq. 5;
//! - the Ritz pressure of \[Antonic2004\] eq. 14 against FD under the same assumptions (film on
//!   θ = 0 … π from the widest gap, P = 0 on both film edges and both bearing ends): the
//!   difference is the 4-term trial function's error, stated here;
//! - the \[Flores2009\] Table 1 bearing: the FD equilibrium beside the closed forms'.

use jbearing_solvers::closed_form::{
    ClosedFormModel, ClosedFormParams, JournalMotion, film_force, pressure, static_equilibrium,
};
use jbearing_solvers::reynolds::{
    GridParams, Groove, OperatingConditions, ReynoldsParams, ReynoldsSolver, SupplyModel,
};
use jbearing_solvers::ritz::{RitzParams, solve_ritz};
use jbearing_validation::generated_docs::{fixed, sci, sig, signed, write_if_requested};
use std::f64::consts::PI;
use std::fmt::Write;

/// The command that reproduces the block of docs/validation.md written by the test `name`.
fn command(name: &str) -> String {
    format!(
        "cargo test --release -p jbearing-validation --test closed_form_vs_reynolds -- --nocapture {name}"
    )
}

/// The header of the two limit tables of docs/validation.md.
const LIMIT_HEADER: &str = "| limit | case | FD vs closed form |\n|---|---|---|\n";

const R: f64 = 0.02;
const C: f64 = 40e-6;
const MU: f64 = 0.02;

fn rotation(omega: f64, feeds: usize, p_feed: f64) -> OperatingConditions {
    OperatingConditions {
        journal_speed: omega,
        bearing_speed: 0.0,
        feed_pressures: vec![p_feed; feeds],
    }
}

fn closed(l: f64) -> ClosedFormParams {
    ClosedFormParams {
        radius: R,
        length: l,
        radial_clearance: C,
        viscosity: MU,
    }
}

#[test]
fn short_bearing_gumbel_is_the_limit_of_the_fd_film_as_l_over_d_goes_to_zero() {
    let omega = 100.0;
    let mut table = String::from(LIMIT_HEADER);
    for eps in [0.3, 0.7] {
        let mut errs = Vec::new();
        let mut measured = Vec::new();
        for ld in [0.5, 0.25, 0.125, 0.0625] {
            let l = ld * 2.0 * R;
            let mut p = ReynoldsParams::plain(R, l, C, MU);
            p.supply = SupplyModel::AxialLineAtMaxGap;
            p.grid = GridParams {
                n_theta: 180,
                n_z: 22,
            };
            let mut s = ReynoldsSolver::new(p).unwrap();
            let fd = s
                .solve_steady([eps, 0.0], &rotation(omega, 0, 0.0))
                .unwrap();
            let cf = film_force(
                ClosedFormModel::ShortGumbel,
                &closed(l),
                &JournalMotion::steady(eps, 0.0, omega),
            )
            .unwrap()
            .cartesian;
            let (wf, wc) = (fd.film_force[0].hypot(fd.film_force[1]), cf[0].hypot(cf[1]));
            let dang = (fd.film_force[1].atan2(fd.film_force[0]) - cf[1].atan2(cf[0])).to_degrees();
            let err = (wf - wc) / wc;
            println!(
                "short ε={eps} L/D={ld}: |F| FD {wf:.5e} N, closed {wc:.5e} N, {:+.2} %, direction {dang:+.2}°",
                100.0 * err
            );
            errs.push((err.abs(), dang.abs()));
            measured.push((100.0 * err, dang));
        }
        let joined = |f: &dyn Fn(&(f64, f64)) -> String| {
            measured.iter().map(f).collect::<Vec<_>>().join(" / ")
        };
        let _ = writeln!(
            table,
            "| short bearing, Gumbel vs JFO rupture, L/D → 0 (180 × 22) | ε = {eps}, L/D = 0.5 / 0.25 / 0.125 / 0.0625 | force magnitude {} %, direction {}° |",
            joined(&|e| signed(e.0, 2)),
            joined(&|e| signed(e.1, 2)),
        );
        // The short-bearing theory drops the circumferential pressure flow, an O((L/D)²)
        // effect: the error must shrink by ≳ 2.5× per halving of L/D (4× asymptotically, less
        // where the grid error of ~0.1 % starts to show) and be below 1 % at L/D = 1/16.
        for w in errs.windows(2) {
            assert!(w[1].0 < w[0].0 / 2.5 || w[1].0 < 0.01, "ε {eps}: {errs:?}");
        }
        assert!(errs[3].0 < 0.01 && errs[3].1 < 0.1, "ε {eps}: {errs:?}");
    }
    print!("{table}");
    let name = "short_bearing_gumbel_is_the_limit_of_the_fd_film_as_l_over_d_goes_to_zero";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

#[test]
fn long_bearing_sommerfeld_is_the_limit_of_the_full_fd_film_as_l_over_d_grows() {
    let omega = 20.0;
    let p_amb = 2e7; // well above the film's ± pressures: no cavitation (checked)
    let eps = 0.6;
    let mut errs = Vec::new();
    for ld in [1.0, 4.0, 16.0] {
        let l = ld * 2.0 * R;
        let mut p = ReynoldsParams::plain(R, l, C, MU);
        p.ambient_pressure = p_amb;
        p.grid = GridParams {
            n_theta: 120,
            n_z: 42,
        };
        let mut s = ReynoldsSolver::new(p).unwrap();
        let fd = s
            .solve_steady([eps, 0.0], &rotation(omega, 0, 0.0))
            .unwrap();
        assert_eq!(fd.cavitated_fraction, 0.0);
        // Mid-plane pressure relative to its value at h_max (θ = π here) against eq. 5, whose
        // zero is at h_max (p(ψ = 0) = 0).
        let (nt, nz) = fd.pressure.dim();
        let j = nz / 2;
        let motion = JournalMotion::steady(eps, 0.0, omega);
        let i_max = nt / 2; // θ = π
        let p0 = fd.pressure[[i_max, j]];
        let mut dmax: f64 = 0.0;
        let mut pmax: f64 = 0.0;
        for i in 0..nt {
            let th = fd.theta[i];
            let pc = pressure(
                ClosedFormModel::LongSommerfeld,
                &closed(l),
                &motion,
                th,
                0.0,
            )
            .unwrap();
            dmax = dmax.max((fd.pressure[[i, j]] - p0 - pc).abs());
            pmax = pmax.max(pc.abs());
        }
        let cf = film_force(ClosedFormModel::LongSommerfeld, &closed(l), &motion)
            .unwrap()
            .cartesian;
        let ratio = fd.film_force[0].hypot(fd.film_force[1]) / cf[0].hypot(cf[1]);
        println!(
            "long ε={eps} L/D={ld}: mid-plane max |Δp|/p_max {:.3} %, total force FD/closed {ratio:.4}",
            100.0 * dmax / pmax
        );
        errs.push((dmax / pmax, ratio));
    }
    // The total force approaches the long-bearing force from below (end leakage ∝ D/L); the
    // mid-plane pressure shape is within 2 % of eq. 5 once L/D ≥ 4 (the remainder did not
    // change with a finer axial grid or the sparse-LU oracle: it is not a solver error).
    for w in errs.windows(2) {
        assert!(w[1].1 > w[0].1, "{errs:?}");
    }
    assert!((1.0 - errs[2].1).abs() < 0.05, "{errs:?}");
    assert!(errs[1].0 < 0.02 && errs[2].0 < 0.02, "{errs:?}");
    let mut table = String::from(LIMIT_HEADER);
    let _ = writeln!(
        table,
        "| long bearing, Sommerfeld vs full film (cavitation suppressed), L/D → ∞ (120 × 42) | ε = {eps}, L/D = 1 / 4 / 16 | total force ratio {}; mid-plane pressure vs eq. 5: {} % of p_max |",
        errs.iter()
            .map(|e| fixed(e.1, 3))
            .collect::<Vec<_>>()
            .join(" / "),
        errs.iter()
            .map(|e| sig(100.0 * e.0, 2))
            .collect::<Vec<_>>()
            .join(" / "),
    );
    print!("{table}");
    let name = "long_bearing_sommerfeld_is_the_limit_of_the_full_fd_film_as_l_over_d_grows";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

#[test]
fn ritz_pressure_against_fd_on_the_same_half_film() {
    let omega = 50.0;
    let p_line = 2e7; // film edges and ends at p_line, far above p_cav: no cavitation anywhere
    // (ε, λ, bound on max |Δp|/p_max): the bounds are the measured differences (1.5, 7.5, 6.9,
    // 33.9, 30.0 %) with margin — the statement of how far eq. 14 is from the exact film.
    let mut table = String::from(
        "| ε | λ = r/l | max abs(p_Ritz − p_FD) / p_max | ∫p, Ritz vs FD | work ∫ε sin θ P, Ritz/FD |\n|---|---|---|---|---|\n",
    );
    for (eps, lambda, bound) in [
        (0.3, 1.0, 0.03),
        (0.3, 0.25, 0.10),
        (0.5, 0.5, 0.10),
        (0.7, 1.0, 0.40),
        (0.7, 0.25, 0.40),
    ] {
        let l = R / lambda;
        let mut p = ReynoldsParams::plain(R, l, C, MU);
        p.ambient_pressure = p_line;
        let nt = 240;
        p.grid = GridParams {
            n_theta: nt,
            n_z: 42,
        };
        // Two full-length lines held at p_line on h_max (θ = 0) and h_min (θ = π): the journal
        // sits at ε along −x, so h = c (1 + ε cos θ) as in [Antonic2004].
        let line = |th: f64| Groove {
            center_angle: th,
            center_z: 0.0,
            angular_width: 0.5 * 2.0 * PI / nt as f64,
            axial_width: 2.0 * l,
            cutoff_film_fraction: 0.5, // unused: the feed is far above p_cav
        };
        p.grooves = vec![line(0.0), line(PI)];
        let mut s = ReynoldsSolver::new(p).unwrap();
        let fd = s
            .solve_steady([-eps, 0.0], &rotation(omega, 2, p_line))
            .unwrap();
        let ritz = solve_ritz(&RitzParams::new(eps, lambda)).unwrap();
        let scale = 6.0 * MU * omega * R * R / (C * C); // p = p₀ P, Λ p₀ = 6ηωr²/c²
        let (nth, nz) = fd.pressure.dim();
        let (mut dmax, mut pmax, mut load_fd, mut load_ritz) = (0.0f64, 0.0f64, 0.0, 0.0);
        // Energy norm check: at the Ritz minimum I = −½ Λ Cᵀr = −½ ∫∫ Λ ε sin θ P, and I_Ritz ≥
        // I_exact, so the work ∫∫ ε sin θ P of the Ritz pressure cannot exceed the exact one.
        let (mut work_fd, mut work_ritz) = (0.0, 0.0);
        for i in 0..nth {
            let th = fd.theta[i].rem_euclid(2.0 * PI);
            if th > PI {
                continue;
            }
            for j in 0..nz {
                let z = fd.z[j] / l;
                let pf = fd.pressure[[i, j]] - p_line;
                let pr = scale * ritz.pressure(th, z);
                dmax = dmax.max((pf - pr).abs());
                pmax = pmax.max(pf.abs());
                load_fd += pf;
                load_ritz += pr;
                let wgt = if j == 0 || j + 1 == nz { 0.0 } else { th.sin() };
                work_fd += wgt * pf;
                work_ritz += wgt * pr;
            }
        }
        let dload = (load_ritz - load_fd) / load_fd;
        println!(
            "Ritz ε={eps} λ={lambda}: max |p_Ritz − p_FD| / p_max,FD = {:.2} %, ∫p Ritz vs FD {:+.2} %",
            100.0 * dmax / pmax,
            100.0 * dload
        );
        let work = work_ritz / work_fd;
        println!("   work ratio Ritz/FD {work:.4}");
        let _ = writeln!(
            table,
            "| {eps} | {lambda} | {} % | {} % | {} |",
            fixed(100.0 * dmax / pmax, 1),
            signed(100.0 * dload, 1),
            fixed(work, 3)
        );
        // Rayleigh–Ritz bound, up to the FD grid error (~0.5 %).
        assert!(work < 1.005, "ε {eps} λ {lambda}: {work}");
        // The 4-term sine series and the parabolic axial profile: good at small ε and short
        // bearings (λ = 1), poor at ε = 0.7 and for the flat axial profile of L/D = 2 (λ = 0.25).
        assert!(dmax / pmax < bound, "ε {eps} λ {lambda}: {}", dmax / pmax);
    }
    print!("{table}");
    let name = "ritz_pressure_against_fd_on_the_same_half_film";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}

#[test]
fn seed_004_bearing_fd_equilibrium_beside_the_closed_forms() {
    let params = ClosedFormParams {
        radius: 9.8e-3,
        length: 40e-3,
        radial_clearance: 0.2e-3,
        viscosity: 0.4,
    };
    let omega = 500.0 * 2.0 * PI / 60.0;
    let load = [0.0, -31.275];
    let mut p = ReynoldsParams::plain(
        params.radius,
        params.length,
        params.radial_clearance,
        params.viscosity,
    );
    p.supply = SupplyModel::AxialLineAtMaxGap;
    let mut s = ReynoldsSolver::new(p).unwrap();
    let (fd, info) = s.solve_steady_load(load, &rotation(omega, 0, 0.0)).unwrap();
    let e = info.eccentricity_ratio;
    let eps = e[0].hypot(e[1]);
    let att = (e[1].atan2(e[0]) - load[1].atan2(load[0])).to_degrees();
    let table = format!(
        "| model | ε | attitude φ (°) | h_min (µm) | F_X (N) | F_Y (N) |\n|---|---|---|---|---|---|\n\
         | finite difference (120 × 31, JFO, supply line at h_max) | {} | {} | {} | {} | {} |\n",
        fixed(eps, 4),
        fixed(att, 2),
        fixed(fd.min_film_thickness * 1e6, 1),
        sci(fd.film_force[0], 0),
        fixed(fd.film_force[1], 4)
    );
    print!("{table}");
    // The load is carried (Newton to 1e-8 |W|).
    assert!(fd.film_force[0].abs() < 1e-6 * 31.275);
    assert!((fd.film_force[1] - 31.275).abs() < 1e-6 * 31.275);
    // The finite bearing (L/D = 2.04) loses pressure to side leakage, so it needs a larger ε
    // than the infinitely long bearing, and Reynolds rupture turns the force towards the line
    // of centres relative to the half-Sommerfeld film: a smaller attitude.
    let gl = static_equilibrium(ClosedFormModel::LongGumbel, &params, load, omega).unwrap();
    println!(
        "long Gumbel ε {:.4} φ {:.2}°",
        gl.eccentricity_ratio,
        gl.attitude_angle.to_degrees()
    );
    assert!(eps > gl.eccentricity_ratio);
    assert!(att > 0.0 && att < gl.attitude_angle.to_degrees());
    let name = "seed_004_bearing_fd_equilibrium_beside_the_closed_forms";
    write_if_requested("validation.md", &command(name), &table).expect("docs block");
}
