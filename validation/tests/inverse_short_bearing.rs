//! Inverse solver with the analytic short-bearing film (Ocvirk + Gumbel, moving journal):
//! constant load vs the closed-form steady solution, half-speed whirl load → collapse,
//! symmetry, time-step convergence.
//!
//! Bearing: the compressor main bearing of Yu & Sawicki (docs/conventions.md §7): L = 18.288 mm,
//! R = 27.43 mm, c = 48.9 µm, 1800 rpm; μ = 0.02 Pa·s assumed (docs/conventions.md §7: not given).
//! L/D = 1/3, inside the short-bearing range.

use jbearing_solvers::closed_form::short::{ocvirk_attitude, ocvirk_steady_load};
use jbearing_solvers::closed_form::{ClosedFormModel, ClosedFormParams};
use jbearing_solvers::inverse::{
    ClosedFormFilm, InverseError, InverseParams, NoObserver, TimeScheme, solve_inverse,
};
use jbearing_solvers::load::{ConstantLoad, FnLoad, OperatingHistory, RotatingLoad};
use jbearing_validation::generated_docs::{fixed, sci, write_if_requested};
use std::f64::consts::{PI, TAU};

const OMEGA: f64 = 1800.0 * TAU / 60.0;

/// Writes the one-row table `| test | reference | result |` of the test `name` into its block of
/// docs/validation.md (and prints it).
fn write_row(name: &str, test: &str, reference: &str, result: &str) {
    let table = format!(
        "| test | reference | result |\n|---|---|---|\n| {test} | {reference} | {result} |\n"
    );
    print!("{table}");
    let command = format!(
        "cargo test --release -p jbearing-validation --test inverse_short_bearing -- --nocapture {name}"
    );
    write_if_requested("validation.md", &command, &table).expect("docs block");
}

fn film(scheme: TimeScheme) -> ClosedFormFilm {
    let params = ClosedFormParams {
        radius: 27.43e-3,
        length: 18.288e-3,
        radial_clearance: 48.9e-6,
        viscosity: 0.02,
    };
    ClosedFormFilm::new(ClosedFormModel::ShortGumbelMovingFilm, params, scheme).unwrap()
}

fn history<L>(load: L) -> OperatingHistory<L> {
    OperatingHistory {
        load,
        journal_speed: OMEGA,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    }
}

/// Invert Ocvirk's closed-form steady load W(ε) by bisection (W is increasing in ε).
fn ocvirk_eccentricity(f: &ClosedFormFilm, w: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0 - 1e-12);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ocvirk_steady_load(&f.params, mid, OMEGA) < w {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn constant_load_reproduces_steady_ocvirk_solution() {
    // Per case: (|W|, ε_ref, attitude_ref, worst |Δε|, worst |Δ attitude|).
    let mut cases = Vec::new();
    for (w, scheme) in [
        ([0.0, -3000.0], TimeScheme::default()),
        ([1200.0, 500.0], TimeScheme::default()),
        ([0.0, -3000.0], TimeScheme::BackwardEuler),
        ([0.0, -3000.0], TimeScheme::CrankNicolson),
    ] {
        let mut f = film(scheme);
        let load = history(ConstantLoad {
            load: w,
            period: TAU / OMEGA,
        });
        // Newton tolerance below the default so that the step-to-step noise it leaves in ε
        // (≈ tolerance / (dlnW/dε)) stays under the periodicity tolerance.
        let params = InverseParams {
            tolerance: 1e-8,
            periodicity_tolerance: 1e-6,
            ..Default::default()
        };
        let sol = solve_inverse(&params, &load, &mut f, &mut NoObserver).unwrap();
        assert!(sol.info.periodic, "{:?}", sol.info.warning);
        let wm = w[0].hypot(w[1]);
        let e_ref = ocvirk_eccentricity(&f, wm);
        let att_ref = ocvirk_attitude(e_ref);
        let (mut de, mut da) = (0.0f64, 0.0f64);
        for s in &sol.steps {
            de = de.max((s.eccentricity - e_ref).abs());
            da = da.max((s.attitude_angle - att_ref).abs());
            // Exact steady state of the time-discrete film is the closed form; what is left is the
            // Newton and periodicity tolerance (≲ 1e-6 in ε); the issue asks for 1e-3.
            assert!(
                (s.eccentricity - e_ref).abs() < 1e-3,
                "{} vs {e_ref}",
                s.eccentricity
            );
            assert!(
                (s.attitude_angle - att_ref).abs() < 1e-3,
                "{} vs {att_ref}",
                s.attitude_angle
            );
        }
        // At rest the dissipation is the journal torque times speed and is ≥ Petroff's.
        let s = &sol.steps[0];
        assert!((s.power_loss + s.friction_torque_journal * OMEGA).abs() < 1e-3 * s.power_loss);
        cases.push((wm, e_ref, att_ref, de, da));
    }
    let (a, b) = (cases[0], cases[1]);
    let worst_e = cases.iter().map(|c| c.3).fold(0.0, f64::max);
    let worst_a = cases.iter().map(|c| c.4).fold(0.0, f64::max);
    write_row(
        "constant_load_reproduces_steady_ocvirk_solution",
        &format!(
            "constant load {} kN (and {} kN oblique), BDF2, BE and CN",
            fixed(a.0 / 1e3, 1),
            fixed(b.0 / 1e3, 1)
        ),
        &format!(
            "Ocvirk closed-form steady ε = {} / {}, attitude {}° / {}°",
            fixed(a.1, 5),
            fixed(b.1, 5),
            fixed(a.2.to_degrees(), 2),
            fixed(b.2.to_degrees(), 2)
        ),
        &format!(
            "worst \\|Δε\\| {}, \\|Δ attitude\\| {} rad over every step (asserted < 1e-3)",
            sci(worst_e, 1),
            sci(worst_a, 1)
        ),
    );
}

/// A load turning with the journal at half its speed leaves no wedge in its own frame
/// (ω̄ − ω_W = 0): only squeeze carries it, the journal spirals towards the wall. The run must
/// end in a reported collapse with finite numbers.
#[test]
fn half_speed_whirl_load_collapses() {
    let mut rows = Vec::new();
    for (scheme, name) in [
        (TimeScheme::default(), "BDF2"),
        (TimeScheme::CrankNicolson, "CN"),
    ] {
        let mut f = film(scheme);
        let load = history(RotatingLoad {
            magnitude: 3000.0,
            angular_speed: 0.5 * OMEGA,
            phase: -0.5 * PI,
        });
        // h_min floor 1 µm: the film is gone at the surface-roughness scale (ε = 0.98 here).
        let params = InverseParams {
            min_film_floor: 1e-6,
            ..Default::default()
        };
        match solve_inverse(&params, &load, &mut f, &mut NoObserver) {
            Err(InverseError::Collapse {
                time,
                crank_angle_deg,
                eccentricity,
                min_film_thickness,
                residual,
                eccentricity_ratio,
                ..
            }) => {
                for v in [
                    time,
                    crank_angle_deg,
                    eccentricity,
                    min_film_thickness,
                    residual,
                ] {
                    assert!(v.is_finite());
                }
                assert!(eccentricity_ratio.iter().all(|v| v.is_finite()));
                eprintln!(
                    "whirl ({name}): collapse at t = {time:.4} s, crank {crank_angle_deg:.0}°, |ε| {eccentricity:.4}"
                );
                assert!(eccentricity > 0.97 && eccentricity < 1.0, "{eccentricity}");
                assert!(min_film_thickness < 1e-6);
                rows.push(format!(
                    "{name}: t = {} s, {}°, ε = {}",
                    fixed(time, 4),
                    fixed(crank_angle_deg, 0),
                    fixed(eccentricity, 4)
                ));
            }
            other => panic!("{name}: expected collapse, got {other:?}"),
        }
    }
    write_row(
        "half_speed_whirl_load_collapses",
        "half-speed whirl load 3 kN (ω_W = ω_j/2, ω̄ − ω_W = 0), BDF2 and CN",
        "must not be carried",
        &format!("`Collapse` at h_min < 1 µm floor: {}", rows.join("; ")),
    );
}

/// The trap BDF2 (the default) and Crank–Nicolson avoid: backward Euler's chord of the whirl
/// orbit is an inward squeeze velocity ≈ |ε| ω_W (ω_W dt)/2, and the film answers it with load capacity. The
/// same whirl load is then "carried" on an orbit that stays above the 1 µm floor.
#[test]
fn backward_euler_invents_load_capacity_for_the_whirl_load() {
    let mut f = film(TimeScheme::BackwardEuler);
    let load = history(RotatingLoad {
        magnitude: 3000.0,
        angular_speed: 0.5 * OMEGA,
        phase: -0.5 * PI,
    });
    let params = InverseParams {
        min_film_floor: 1e-6,
        ..Default::default()
    };
    let sol = solve_inverse(&params, &load, &mut f, &mut NoObserver).unwrap();
    assert!(sol.summary.min_film_thickness > 1e-6);
    write_row(
        "backward_euler_invents_load_capacity_for_the_whirl_load",
        "same with backward Euler",
        "(the trap)",
        &format!(
            "\"carried\" at h_min = {} µm, ε = {} — BE's chord is an inward squeeze",
            fixed(sol.summary.min_film_thickness * 1e6, 2),
            fixed(sol.summary.max_eccentricity, 3)
        ),
    );
}

/// W(t + τ/2) = −W(t) and a film invariant under a half turn (no grooves) ⇒ the periodic orbit
/// has ε(t + τ/2) = −ε(t).
#[test]
fn half_wave_symmetric_load_gives_point_symmetric_orbit() {
    let mut f = film(TimeScheme::default());
    let tau = TAU / OMEGA;
    let load = history(FnLoad {
        period: tau,
        load: move |t: f64| {
            let a = OMEGA * t;
            [
                2500.0 * a.cos() + 600.0 * (3.0 * a).cos(),
                1500.0 * a.sin() - 400.0 * (3.0 * a).sin(),
            ]
        },
    });
    let params = InverseParams {
        tolerance: 1e-8,
        periodicity_tolerance: 1e-6,
        ..Default::default()
    };
    let sol = solve_inverse(&params, &load, &mut f, &mut NoObserver).unwrap();
    assert!(sol.info.periodic);
    let n = sol.steps.len();
    assert_eq!(n % 2, 0);
    let mut worst: f64 = 0.0;
    for i in 0..n / 2 {
        let a = sol.steps[i].eccentricity_ratio;
        let b = sol.steps[i + n / 2].eccentricity_ratio;
        worst = worst.max((a[0] + b[0]).hypot(a[1] + b[1]));
    }
    // Newton tolerance 1e-8 on the force ⇒ ε errors ~1e-8 per step; the periodicity tolerance
    // 1e-6 bounds what is left of the transient; 1e-5 has margin for both.
    assert!(worst < 1e-5, "asymmetry {worst}");
    assert!(
        sol.summary.max_eccentricity > 0.3,
        "the test needs a real orbit"
    );
    write_row(
        "half_wave_symmetric_load_gives_point_symmetric_orbit",
        "W(t + τ/2) = −W(t)",
        "orbit ε(t + τ/2) = −ε(t)",
        &format!("{} (asserted < 1e-5)", sci(worst, 1)),
    );
}

/// Mirror symmetry: reversing the rotation and mirroring the load in the x axis mirrors the
/// orbit (θ → −θ maps the film onto itself).
#[test]
fn mirrored_load_and_rotation_give_mirrored_orbit() {
    let tau = TAU / OMEGA;
    let w = |t: f64| {
        let a = OMEGA * t;
        [800.0 * a.sin(), -2000.0 - 1500.0 * a.cos()]
    };
    let run = |sign: f64| {
        let mut f = film(TimeScheme::default());
        let load = OperatingHistory {
            load: FnLoad {
                period: tau,
                load: move |t: f64| {
                    let v = w(t);
                    [v[0], sign * v[1]]
                },
            },
            journal_speed: sign * OMEGA,
            bearing_speed: 0.0,
            feed_pressures: vec![],
        };
        // Newton tolerance below the default so that the step-to-step noise it leaves in ε
        // (≈ tolerance / (dlnW/dε)) stays under the periodicity tolerance.
        let params = InverseParams {
            tolerance: 1e-8,
            periodicity_tolerance: 1e-6,
            ..Default::default()
        };
        solve_inverse(&params, &load, &mut f, &mut NoObserver).unwrap()
    };
    let a = run(1.0);
    let b = run(-1.0);
    let mut worst: f64 = 0.0;
    for (p, q) in a.steps.iter().zip(&b.steps) {
        let (x, y) = (p.eccentricity_ratio, q.eccentricity_ratio);
        assert!(
            (x[0] - y[0]).abs() < 1e-4 && (x[1] + y[1]).abs() < 1e-4,
            "{x:?} {y:?}"
        );
        worst = worst.max((x[0] - y[0]).abs()).max((x[1] + y[1]).abs());
    }
    write_row(
        "mirrored_load_and_rotation_give_mirrored_orbit",
        "mirrored load, reversed rotation",
        "mirrored orbit",
        &format!("{} (asserted < 1e-4)", sci(worst, 1)),
    );
}

/// Halving the 1° default step changes the cycle-minimum h_min and the mean power loss by less
/// than 1 % with each second-order scheme (BDF2, the default, and Crank–Nicolson).
#[test]
fn halving_the_time_step_changes_h_min_and_power_loss_below_one_percent() {
    let tau = TAU / OMEGA;
    let load = history(FnLoad {
        period: tau,
        load: move |t: f64| {
            let a = OMEGA * t;
            // A compressor-like main-bearing load: a strong pulse once per turn plus inertia.
            let pulse = 4000.0 * (0.5 * (1.0 - a.cos())).powi(4);
            [600.0 * (2.0 * a).sin(), -800.0 - pulse]
        },
    });
    let run = |step_deg: f64, scheme: TimeScheme| {
        let mut f = film(scheme);
        let params = InverseParams {
            step_deg,
            tolerance: 1e-6,
            periodicity_tolerance: 1e-6,
            ..Default::default()
        };
        solve_inverse(&params, &load, &mut f, &mut NoObserver).unwrap()
    };
    let mut rows = Vec::new();
    for (scheme, name) in [
        (TimeScheme::default(), "BDF2"),
        (TimeScheme::CrankNicolson, "CN"),
    ] {
        let a = run(1.0, scheme);
        let b = run(0.5, scheme);
        assert!(a.info.periodic && b.info.periodic);
        let dh = (a.summary.min_film_thickness / b.summary.min_film_thickness - 1.0).abs();
        let dp = (a.summary.mean_power_loss / b.summary.mean_power_loss - 1.0).abs();
        eprintln!(
            "{name} 1° / 0.5°: h_min {:.5} / {:.5} µm, mean power {:.4} / {:.4} W; changes {dh:.1e} / {dp:.1e}",
            1e6 * a.summary.min_film_thickness,
            1e6 * b.summary.min_film_thickness,
            a.summary.mean_power_loss,
            b.summary.mean_power_loss
        );
        assert!(dh < 0.01, "{name}: h_min change {dh}");
        assert!(dp < 0.01, "{name}: power loss change {dp}");
        rows.push(format!(
            "{name}: h_min {} / {} µm; mean power {} / {} W (changes {}, {})",
            fixed(1e6 * a.summary.min_film_thickness, 5),
            fixed(1e6 * b.summary.min_film_thickness, 5),
            fixed(a.summary.mean_power_loss, 4),
            fixed(b.summary.mean_power_loss, 4),
            sci(dh, 1),
            sci(dp, 1)
        ));
    }
    write_row(
        "halving_the_time_step_changes_h_min_and_power_loss_below_one_percent",
        "time step 1° / 0.5°, synthetic pulse load (peak 4.8 kN), BDF2 and CN",
        "halving changes < 1 %",
        &rows.join("; "),
    );
}
