//! \[Benasciutti2012\] Figs. 4–7 (section "Effect of component elastic deformation"): the JB1 bearing (Table 1; α = 0, T rising
//! linearly 40 → 80 °C) with elastic shaft and housing. The paper reports, against its rigid
//! row (e = 0.2392 mm, p_max = 83.17 MPa):
//!
//! * p_max falls to 43 MPa (−48 %) and e rises to 0.2953 mm (> c: the deformed bore lets the
//!   journal centre move beyond the clearance circle), the attitude angle grows (Fig. 6);
//! * on the housing bore (Fig. 7c) all stresses are compressive, |σ_r|max = 43 MPa = p_max,
//!   σ_θ ≈ σ_z = ν(σ_r + σ_θ), von Mises 21 MPa (partly hydrostatic), 35 MPa underneath.
//!
//! The paper does not state the material numbers ("typical of a structural steel"), the
//! shaft's hole radius (chosen by a sensitivity study it does not report) nor the housing's
//! size (Fig. 5b: a block with a bore, outer edges fixed). Ours: steel E = 210 GPa, ν = 0.3,
//! hole r_h = 0.4 R = 100 mm, square housing of half-width H = 2R = 500 mm; the sensitivity
//! table below varies H, r_h and E.
//!
//! The configuration is the case file `cases/benasciutti_jb1_elastic.toml`, loaded here through
//! the application's own reader (`jbearing::run::elastic_problem`), so that what `jbearing run`
//! solves is what this test checks. The film is the plane model of `reynolds_seed003.rs` (a
//! bearing 100 diameters long with the same load per length, β = 1.5e13 Pa), on 240 × 5 nodes:
//! 3 cells of 16.7 m along, whose z-flux to the ends is (R/L)² ≈ 1e-4 of the circumferential
//! one, so every row carries the plane solution (checked: the rigid row on this grid against the
//! 240 × 101 grid's e and p_max).

use std::path::Path;

use jbearing::case::Case;
use jbearing::run::{ElasticProblem, elastic_problem};
use jbearing_solvers::elastic::{
    ElasticBearing, ElasticParams, ElasticSolution, HousingShape, Material, solve_steady_load,
};
use jbearing_solvers::reynolds::{GridParams, OperatingConditions, ReynoldsSolver, SupplyModel};
use jbearing_solvers::viscosity::{Temperature, Vogel};
use jbearing_validation::generated_docs::{fixed, signed, write_if_requested};
use std::fmt::Write;

/// The command that reproduces the two JB1 tables of docs/validation.md.
const COMMAND: &str = "cargo test --release -p jbearing-validation --test elastic_seed003 -- --nocapture jb1_deformable_against_the_paper";

const R: f64 = 0.25;
const C: f64 = 0.25e-3;

/// The shipped case file's deformable problem.
fn problem() -> ElasticProblem {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/benasciutti_jb1_elastic.toml");
    let case = Case::from_file(&path).unwrap();
    elastic_problem(&case).expect("the case has [elastic]")
}

/// The case's film on `n_theta` × `n_z` nodes.
fn film(n_theta: usize, n_z: usize) -> ReynoldsSolver {
    let mut p = problem().film;
    p.grid = GridParams { n_theta, n_z };
    ReynoldsSolver::new(p).unwrap()
}

fn conditions() -> OperatingConditions {
    problem().conditions
}

fn load(_solver: &ReynoldsSolver) -> [f64; 2] {
    problem().load
}

/// The case file is the paper's JB1 as the module docs describe it: the plane model (L = 100 D,
/// 3600 kN per 0.3 m), the Vogel curve through Table 2's points, T linear 40 → 80 °C over 180°,
/// the axial supply line, 65 rpm, and the documented baseline structure (steel, hole 0.4 R,
/// square housing H = 2 R, `ElasticParams::steel`).
#[test]
fn the_case_file_is_the_documented_configuration() {
    let p = problem();
    let f = &p.film;
    assert_eq!((f.radius, f.clearance), (R, C));
    assert_eq!(f.length, 100.0 * 2.0 * R);
    assert!((p.load[1] / (-3.6e6 / 0.3 * f.length) - 1.0).abs() < 1e-12);
    assert_eq!(p.load[0], 0.0);
    assert_eq!(f.supply, SupplyModel::AxialLineAtMaxGap);
    assert_eq!(
        f.grid,
        GridParams {
            n_theta: 240,
            n_z: 5
        }
    );
    assert_eq!(f.bulk_modulus, 1.5e13);
    let m = f.viscosity_model.expect("a Vogel law");
    let v = Vogel::seed003_iso_vg_680();
    for t in [40.0, 60.0, 80.0] {
        assert!(
            (m.vogel.viscosity(t) / v.viscosity(t) - 1.0).abs() < 1e-12,
            "{t} °C"
        );
    }
    assert_eq!(m.pressure_coefficient, 0.0);
    match m.temperature {
        Temperature::LinearOverSpan {
            inlet,
            outlet,
            span,
        } => {
            assert_eq!((inlet, outlet), (40.0, 80.0));
            assert!((span - std::f64::consts::PI).abs() < 1e-15);
        }
        other => panic!("temperature {other:?}"),
    }
    assert!(
        (p.conditions.journal_speed / (65.0 * std::f64::consts::TAU / 60.0) - 1.0).abs() < 1e-15
    );
    assert_eq!(p.conditions.bearing_speed, 0.0);
    assert_eq!(p.elastic, ElasticParams::steel(R));
}

fn wrap_deg(a: f64) -> f64 {
    let x = a.to_degrees().rem_euclid(360.0);
    if x > 180.0 { x - 360.0 } else { x }
}

/// What the paper reports of one coupled solve.
#[derive(Debug, Clone, Copy)]
struct Answer {
    /// Eccentricity, m.
    e: f64,
    p_max: f64,
    /// Angle of p_max from the load line in the direction of rotation, deg.
    p_angle: f64,
    h_min: f64,
    /// Attitude angle (from the load line to the eccentricity), deg.
    attitude: f64,
    /// Largest |σ_r| and von Mises on the housing bore, Pa; largest von Mises anywhere in the
    /// housing, Pa; largest |σ_r + p̄| on the bore (the traction condition), Pa.
    sr_max: f64,
    vm_bore: f64,
    vm_housing: f64,
    traction_error: f64,
    iterations: usize,
    film_solves: usize,
}

/// The coupled solve of JB1 with `params`.
fn deformable(params: ElasticParams) -> (Answer, ElasticBearing, ElasticSolution) {
    deformable_on(params, 240)
}

/// The coupled solve on a film of `n_theta` × 5 nodes.
fn deformable_on(
    params: ElasticParams,
    n_theta: usize,
) -> (Answer, ElasticBearing, ElasticSolution) {
    let mut solver = film(n_theta, 5);
    let w = load(&solver);
    let bearing = ElasticBearing::new(R, params).unwrap();
    let (sol, info) = solve_steady_load(&mut solver, &bearing, w, &conditions()).unwrap();
    let eps = info.steady.eccentricity_ratio;
    let stresses = bearing.housing.stresses(&sol.housing_displacement);
    let mesh = bearing.housing.mesh();
    let (mut sr_max, mut vm_bore, mut traction_error) = (0.0f64, 0.0f64, 0.0f64);
    for (k, &node) in mesh.surface.iter().enumerate() {
        let [x, y] = mesh.nodes[node];
        let [sr, _, _] = stresses[node].polar(y.atan2(x));
        sr_max = sr_max.max(-sr);
        vm_bore = vm_bore.max(stresses[node].von_mises());
        traction_error = traction_error.max((sr + sol.surface_pressure[k]).abs());
    }
    let vm_housing = stresses.iter().map(|s| s.von_mises()).fold(0.0, f64::max);
    let f = &sol.film;
    let load_dir = w[1].atan2(w[0]);
    let answer = Answer {
        e: C * eps[0].hypot(eps[1]),
        p_max: f.max_pressure,
        p_angle: wrap_deg(f.max_pressure_location[0] - load_dir),
        h_min: f.min_film_thickness,
        attitude: f.attitude_angle.to_degrees(),
        sr_max,
        vm_bore,
        vm_housing,
        traction_error,
        iterations: info.iterations,
        film_solves: info.film_solves,
    };
    (answer, bearing, sol)
}

/// The rigid JB1 row on the same film grid (no deformation set): (e, p_max, attitude deg,
/// angle of p_max from the load line deg).
fn rigid(n_z: usize) -> (f64, f64, f64, f64) {
    let mut solver = film(240, n_z);
    let w = load(&solver);
    let (sol, info) = solver.solve_steady_load(w, &conditions()).unwrap();
    let eps = info.eccentricity_ratio;
    (
        C * eps[0].hypot(eps[1]),
        sol.max_pressure,
        sol.attitude_angle.to_degrees(),
        wrap_deg(sol.max_pressure_location[0] - w[1].atan2(w[0])),
    )
}

/// Film thickness of the deformed bearing at the structure's surface nodes,
/// h = c − e_x cos θ − e_y sin θ + g(θ), and the rigid film at `rigid_eps`.
fn meatus(
    bearing: &ElasticBearing,
    sol: &ElasticSolution,
    eps: [f64; 2],
    rigid_eps: [f64; 2],
) -> Vec<(f64, f64, f64)> {
    bearing
        .surface_angles()
        .iter()
        .zip(&sol.gap_change)
        .map(|(&th, &g)| {
            let rigid = C * (1.0 - rigid_eps[0] * th.cos() - rigid_eps[1] * th.sin());
            let deformed = C * (1.0 - eps[0] * th.cos() - eps[1] * th.sin()) + g;
            (th, rigid, deformed)
        })
        .collect()
}

/// JB1 with elastic shaft and housing against the paper (module docs), with the sensitivity
/// of the answer to what the paper does not state.
///
/// Tolerances. The film grid first: the rigid row on 240 × 5 within 0.3 % (e) and 1 % (p_max)
/// of the 240 × 101 grid's (the plane-model argument of the module docs). Then the paper's
/// deformable numbers depend on a geometry it does not give; the assertions are therefore
/// (a) what holds whatever the geometry — the load balanced, σ_r = −p̄ on the bore to the
/// O(h) stress-recovery error measured on Lamé's cylinder (2.5 % of p at 256 nodes around,
/// so 4 % of p_max here, where p̄ varies along the bore), max |σ_r| = p_max to the same
/// accuracy, the bore's von Mises stress below max |σ_r| (the paper's "partly hydrostatic"
/// state), the deformed film thicker at its thinnest than the rigid one and e > c; and
/// (b) the paper's p_max (as its ratio to the rigid p_max, see below) and e inside the range
/// our plausible geometries span (the sensitivity table: housing half-width 1.1R … 3R, hole
/// 0.2R … 0.6R, E 190 … 230 GPa),
/// widened by that range's own half-width for the geometries we did not try — i.e. each
/// published number within [min − s/2, max + s/2] of our rows, s = max − min.
#[test]
fn jb1_deformable_against_the_paper() {
    let t = std::time::Instant::now();
    let (e_fine, p_fine, _, _) = rigid(101);
    let (e_rigid, p_rigid, att_rigid, p_angle_rigid) = rigid(5);
    eprintln!(
        "rigid JB1 linear-T α=0: 240×5 e {:.4} mm p_max {:.2} MPa attitude {att_rigid:.2}° | 240×101 e {:.4} mm p_max {:.2} MPa | paper 0.2392 mm, 83.17 MPa",
        e_rigid * 1e3,
        p_rigid / 1e6,
        e_fine * 1e3,
        p_fine / 1e6
    );
    assert!((e_rigid / e_fine - 1.0).abs() < 0.003);
    assert!((p_rigid / p_fine - 1.0).abs() < 0.01);

    let base = problem().elastic;
    let (a, bearing, sol) = deformable(base.clone());
    eprintln!(
        "deformable (steel, hole 0.4R, square housing H = 2R, 240 around): e {:.4} mm (paper 0.2953), p_max {:.2} MPa (43) at {:.2}° from the load line, h_min {:.4} mm, attitude {:.2}°; |σ_r|max {:.2} MPa, bore von Mises max {:.2} MPa (21), housing von Mises max {:.2} MPa (35), |σ_r + p̄| ≤ {:.2} MPa; {} iterations, {} film solves, {:.1} s",
        a.e * 1e3,
        a.p_max / 1e6,
        a.p_angle,
        a.h_min * 1e3,
        a.attitude,
        a.sr_max / 1e6,
        a.vm_bore / 1e6,
        a.vm_housing / 1e6,
        a.traction_error / 1e6,
        a.iterations,
        a.film_solves,
        t.elapsed().as_secs_f64()
    );
    // Load balance of the last film solve (the coupled iteration keeps it at every step).
    let w = 3.6e6 / 0.3 * 100.0 * 2.0 * R;
    let f = sol.film.film_force;
    assert!((f[0].hypot(f[1]) / w - 1.0).abs() < 1e-6);
    assert!(
        a.traction_error < 0.04 * a.p_max,
        "σ_r + p̄: {}",
        a.traction_error
    );
    assert!((a.sr_max / a.p_max - 1.0).abs() < 0.04);
    assert!(a.vm_bore < a.sr_max);
    assert!(a.e > C && a.e > e_rigid);
    assert!(a.h_min > C - e_rigid);
    assert!(a.p_max < 0.7 * p_rigid);

    // Stresses along the bore (Fig. 7c) and the meatus (Fig. 6b), every 15° of the loaded arc.
    let stresses = bearing.housing.stresses(&sol.housing_displacement);
    let mesh = bearing.housing.mesh();
    let w_dir = -std::f64::consts::FRAC_PI_2;
    eprintln!("bore: θ from the load line [°], p̄, σ_r, σ_θ, σ_z, von Mises [MPa]");
    for (k, &node) in mesh.surface.iter().enumerate() {
        let [x, y] = mesh.nodes[node];
        let th = y.atan2(x);
        let rel = wrap_deg(th - w_dir);
        let [sr, st, _] = stresses[node].polar(th);
        if k % 10 == 0 && sol.surface_pressure[k] > 0.0 {
            eprintln!(
                "  {rel:7.1} {:7.2} {:7.2} {:7.2} {:7.2} {:7.2}",
                sol.surface_pressure[k] / 1e6,
                sr / 1e6,
                st / 1e6,
                stresses[node].zz / 1e6,
                stresses[node].von_mises() / 1e6
            );
        }
    }
    let eps = [
        a.e / C * (a.attitude.to_radians() + w_dir).cos(),
        a.e / C * (a.attitude.to_radians() + w_dir).sin(),
    ];
    let rigid_eps = [
        e_rigid / C * (att_rigid.to_radians() + w_dir).cos(),
        e_rigid / C * (att_rigid.to_radians() + w_dir).sin(),
    ];
    let m = meatus(&bearing, &sol, eps, rigid_eps);
    let (k_min, _) =
        m.iter().enumerate().fold(
            (0, f64::INFINITY),
            |b, (k, v)| if v.2 < b.1 { (k, v.2) } else { b },
        );
    eprintln!("meatus: θ from the deformed h_min [°], h rigid, h deformed [mm]");
    for step in (-180..=180).step_by(30) {
        let k = (k_min as i64 + step * 240 / 360).rem_euclid(240) as usize;
        eprintln!("  {step:5} {:.4} {:.4}", m[k].1 * 1e3, m[k].2 * 1e3);
    }

    // Sensitivity to what the paper leaves unstated.
    let mut rows: Vec<(String, Answer)> = vec![("baseline".into(), a)];
    let variants: Vec<(String, ElasticParams)> = vec![
        (
            "housing H = 1.1R".into(),
            ElasticParams {
                housing: HousingShape::Square {
                    half_width: 1.1 * R,
                },
                ..base.clone()
            },
        ),
        (
            "housing H = 1.2R".into(),
            ElasticParams {
                housing: HousingShape::Square {
                    half_width: 1.2 * R,
                },
                ..base.clone()
            },
        ),
        (
            "housing H = 1.5R".into(),
            ElasticParams {
                housing: HousingShape::Square {
                    half_width: 1.5 * R,
                },
                ..base.clone()
            },
        ),
        (
            "housing H = 3R".into(),
            ElasticParams {
                housing: HousingShape::Square {
                    half_width: 3.0 * R,
                },
                ..base.clone()
            },
        ),
        (
            "hole 0.2R".into(),
            ElasticParams {
                hole_radius: 0.2 * R,
                ..base.clone()
            },
        ),
        (
            "hole 0.6R".into(),
            ElasticParams {
                hole_radius: 0.6 * R,
                ..base.clone()
            },
        ),
        (
            "E = 190 GPa".into(),
            ElasticParams {
                shaft_material: Material {
                    youngs_modulus: 190e9,
                    poisson_ratio: 0.3,
                },
                housing_material: Material {
                    youngs_modulus: 190e9,
                    poisson_ratio: 0.3,
                },
                ..base.clone()
            },
        ),
        (
            "E = 230 GPa".into(),
            ElasticParams {
                shaft_material: Material {
                    youngs_modulus: 230e9,
                    poisson_ratio: 0.3,
                },
                housing_material: Material {
                    youngs_modulus: 230e9,
                    poisson_ratio: 0.3,
                },
                ..base.clone()
            },
        ),
        (
            "mesh: FE 120 around".into(),
            ElasticParams {
                n_theta: 120,
                ..base.clone()
            },
        ),
        (
            "mesh: FE 360 around".into(),
            ElasticParams {
                n_theta: 360,
                ..base.clone()
            },
        ),
    ];
    for (name, params) in variants {
        rows.push((name, deformable(params).0));
    }
    // Film grid: 480 around (0.75° spacing) against the baseline's 240 (1.5°): the deformed
    // peak is flat (no faster than the rigid one, whose 1.5° sampling costs < 2 % of p_max in
    // `reynolds_seed003.rs`), so e within 0.5 % and p_max within 2 %.
    let fine = deformable_on(base.clone(), 480).0;
    assert!((fine.e / a.e - 1.0).abs() < 0.005, "film 480: e {}", fine.e);
    assert!(
        (fine.p_max / a.p_max - 1.0).abs() < 0.02,
        "film 480: p_max {}",
        fine.p_max
    );
    rows.push(("mesh: film 480 around (FE 240)".into(), fine));
    let mut variants_table = String::from(
        "| variant | e [mm] | p_max [MPa] | θ_pmax [°] | h_min [mm] | max \\|σ_r\\| bore [MPa] | von Mises bore [MPa] | outer iterations |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for (name, r) in &rows {
        let name = if name == "baseline" {
            "baseline (H = 2R, r_h = 0.4R, E = 210 GPa)"
        } else {
            name
        };
        let _ = writeln!(
            variants_table,
            "| {name} | {:.4} | {:.2} | {:.1} | {:.4} | {:.2} | {:.2} | {} |",
            r.e * 1e3,
            r.p_max / 1e6,
            r.p_angle,
            r.h_min * 1e3,
            r.sr_max / 1e6,
            r.vm_bore / 1e6,
            r.iterations
        );
    }
    eprint!("{variants_table}");
    // (b): the paper's numbers inside our geometries' envelope (mesh rows excluded: they
    // are the discretization check, reported). p_max as its ratio to the rigid row's: our
    // rigid p_max on this row is 7 % above the paper's (88.8 against 83.17 MPa: the unstated
    // shape of the temperature rise, `reynolds_seed003.rs`), an offset the deformable film
    // inherits; the paper's own ratio is 43/83.17 = 0.517.
    let geometry: Vec<&Answer> = rows
        .iter()
        .filter(|(n, _)| !n.starts_with("mesh"))
        .map(|(_, r)| r)
        .collect();
    for (what, paper, get) in [
        (
            "p_max / rigid p_max",
            43.0 / 83.17,
            Box::new(move |r: &Answer| r.p_max / p_rigid) as Box<dyn Fn(&Answer) -> f64>,
        ),
        ("e", 0.2953e-3, Box::new(|r: &Answer| r.e)),
    ] {
        let lo = geometry
            .iter()
            .map(|r| get(r))
            .fold(f64::INFINITY, f64::min);
        let hi = geometry
            .iter()
            .map(|r| get(r))
            .fold(f64::NEG_INFINITY, f64::max);
        let s = hi - lo;
        eprintln!("{what}: our geometries span {lo:e} … {hi:e}, paper {paper:e}");
        assert!(
            paper >= lo - 0.5 * s && paper <= hi + 0.5 * s,
            "{what}: paper {paper} outside [{lo}, {hi}] ± s/2"
        );
    }
    // The paper's numbers against ours (the rows the assertions above are about).
    let housing_at = if (a.vm_housing - a.vm_bore).abs() <= 1e-9 * a.vm_housing {
        "on the bore"
    } else {
        "below the bore"
    };
    let paper_table = format!(
        "| quantity | paper rigid → deformable | ours rigid → deformable | asserted |\n\
         |---|---|---|---|\n\
         | e [mm] | 0.2392 → 0.2953 | {} → {} ({} % vs paper) | e > c; paper inside our geometries' range ± half its width |\n\
         | p_max [MPa] | 83.17 → 43 (ratio 0.517) | {} → {} (ratio {}) | p_max < 0.7 × rigid; paper's ratio inside our range ± half width |\n\
         | h_min [mm] | 0.0108 → (Fig. 6b) | {} → {} | deformed > rigid |\n\
         | θ_pmax from the load line [°] | 22.82 → – | {} → {} | reported |\n\
         | max \\|σ_r\\| on the bore [MPa] | 43 (= p_max) | {} (p_max {}) | within 4 % of p_max; \\|σ_r + p̄\\| ≤ {} MPa everywhere (≤ 4 % of p_max) |\n\
         | von Mises on the bore, max [MPa] | 21 | {} | below max \\|σ_r\\| (asserted); **not reproduced** |\n\
         | von Mises in the housing, max [MPa] | 35 (underneath the bore) | {} ({housing_at}) | reported |\n",
        fixed(e_rigid * 1e3, 4),
        fixed(a.e * 1e3, 4),
        signed(100.0 * (a.e / 0.2953e-3 - 1.0), 1),
        fixed(p_rigid / 1e6, 2),
        fixed(a.p_max / 1e6, 2),
        fixed(a.p_max / p_rigid, 3),
        fixed((C - e_rigid) * 1e3, 4),
        fixed(a.h_min * 1e3, 4),
        fixed(p_angle_rigid, 2),
        fixed(a.p_angle, 1),
        fixed(a.sr_max / 1e6, 2),
        fixed(a.p_max / 1e6, 2),
        fixed(a.traction_error / 1e6, 2),
        fixed(a.vm_bore / 1e6, 2),
        fixed(a.vm_housing / 1e6, 2),
    );
    print!("{paper_table}");
    write_if_requested(
        "validation.md",
        COMMAND,
        &format!("{paper_table}\nSensitivity to what the paper does not state (steel, 240 around unless named):\n\n{variants_table}"),
    )
    .expect("docs block");
}
