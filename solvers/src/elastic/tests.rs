//! Patch test, Lamé's thick cylinder with measured convergence orders, Maxwell–Betti.

use super::*;

/// Plane-strain Lamé constants (λ, μ).
fn lame(m: Material) -> (f64, f64) {
    let (e, nu) = (m.youngs_modulus, m.poisson_ratio);
    (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    )
}

/// The patch test (\[Zienkiewicz2005\]): a square patch of nine distorted quadrilaterals
/// under the boundary tractions of a constant stress state, held only against rigid motion
/// (node (0,0) fixed, node (1,0) held in y), must give the exact linear displacement at every
/// node and the constant stress in every element — to round-off, since the exact field lies
/// in the element space.
#[test]
fn patch_test_constant_stress_on_distorted_mesh() {
    // 4 × 4 nodes on [0, 1]², interior nodes moved off the grid.
    let mut nodes = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            let (mut x, mut y) = (i as f64 / 3.0, j as f64 / 3.0);
            if (1..3).contains(&i) && (1..3).contains(&j) {
                x += 0.07 * (1.0 + i as f64 * 0.5) * if j == 1 { 1.0 } else { -1.0 };
                y += 0.05 * (i as f64 - 1.5) * 2.0;
            }
            nodes.push([x, y]);
        }
    }
    let id = |i: usize, j: usize| j * 4 + i;
    let mut elements = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            elements.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = Mesh {
        nodes: nodes.clone(),
        elements,
        surface: Vec::new(),
        fluid: FluidSide::Inside,
        supports: vec![(id(0, 0), Support::Fixed), (id(3, 0), Support::Tangential)],
        nodes_per_ray: 4,
    };
    let m = Material::STEEL;
    let body = ElasticBody::new(mesh, m).unwrap();
    let (sxx, syy, sxy) = (30e6, -12e6, 7e6);
    // Tractions σ n on the four straight sides, consistent loads (half an edge per node).
    let mut f = vec![[0.0; 2]; nodes.len()];
    let h = 1.0 / 3.0;
    for k in 0..3 {
        for (a, b, n) in [
            (id(k, 0), id(k + 1, 0), [0.0, -1.0]),
            (id(3, k), id(3, k + 1), [1.0, 0.0]),
            (id(k, 3), id(k + 1, 3), [0.0, 1.0]),
            (id(0, k), id(0, k + 1), [-1.0, 0.0]),
        ] {
            let t = [sxx * n[0] + sxy * n[1], sxy * n[0] + syy * n[1]];
            for node in [a, b] {
                f[node][0] += 0.5 * h * t[0];
                f[node][1] += 0.5 * h * t[1];
            }
        }
    }
    let u = body.solve(&f).unwrap();
    // Exact strains ε = D⁻¹σ (plane strain): ε_xx = ((1−ν²)σ_xx − ν(1+ν)σ_yy)/E, …
    let (e, nu) = (m.youngs_modulus, m.poisson_ratio);
    let exx = ((1.0 - nu * nu) * sxx - nu * (1.0 + nu) * syy) / e;
    let eyy = ((1.0 - nu * nu) * syy - nu * (1.0 + nu) * sxx) / e;
    let gxy = sxy / lame(m).1;
    // u(0,0) = 0 and u_y(1,0) = 0 fix the rotation: u = (ε_xx x + γ y, ε_yy y).
    let scale = exx.abs().max(eyy.abs()).max(gxy.abs());
    for (node, &[x, y]) in nodes.iter().enumerate() {
        let exact = [exx * x + gxy * y, eyy * y];
        for c in 0..2 {
            assert!(
                (u[node][c] - exact[c]).abs() < 1e-12 * scale,
                "node {node} comp {c}: {} vs {}",
                u[node][c],
                exact[c]
            );
        }
    }
    for s in body.stresses(&u) {
        for (got, want) in [
            (s.xx, sxx),
            (s.yy, syy),
            (s.xy, sxy),
            (s.zz, nu * (sxx + syy)),
        ] {
            assert!((got - want).abs() < 1e-8 * 30e6, "{got} vs {want}");
        }
    }
}

/// Plane-strain thick cylinder a ≤ r ≤ b, u = A r + B/r (\[TimoshenkoGoodier1970\]):
/// σ_r = 2(λ+μ)A − 2μB/r², σ_θ = 2(λ+μ)A + 2μB/r².
struct Cylinder {
    a: f64,
    b: f64,
    lam: f64,
    mu: f64,
}

impl Cylinder {
    fn u(&self, r: f64) -> f64 {
        self.a * r + self.b / r
    }
    fn sr(&self, r: f64) -> f64 {
        2.0 * (self.lam + self.mu) * self.a - 2.0 * self.mu * self.b / (r * r)
    }
    fn st(&self, r: f64) -> f64 {
        2.0 * (self.lam + self.mu) * self.a + 2.0 * self.mu * self.b / (r * r)
    }
}

/// (max u_r error / max |u_r|, max σ_r error / p, max σ_θ error / p) on the film surface.
fn cylinder_errors(body: &ElasticBody, p: f64, exact: &Cylinder, r_surface: f64) -> [f64; 3] {
    let n = body.mesh().surface.len();
    let u = body
        .solve(&body.surface_load(&vec![p; n]).unwrap())
        .unwrap();
    let ur = body.surface_radial(&u);
    let stresses = body.stresses(&u);
    let mut err = [0.0f64; 3];
    for (k, &node) in body.mesh().surface.iter().enumerate() {
        let [x, y] = body.mesh().nodes[node];
        let [sr, st, _] = stresses[node].polar(y.atan2(x));
        err[0] = err[0].max((ur[k] - exact.u(r_surface)).abs() / exact.u(r_surface).abs());
        err[1] = err[1].max((sr - exact.sr(r_surface)).abs() / p);
        err[2] = err[2].max((st - exact.st(r_surface)).abs() / p);
    }
    err
}

/// The two bodies of the bearing model as Lamé cylinders under a uniform film pressure
/// p = 40 MPa, refined 32 → 64 → 128 → 256 nodes around (square elements):
/// * housing, bore a = 0.25 m, fixed outer circle b = 0.5 m: u(b) = 0, σ_r(a) = −p;
/// * shaft, journal b = 0.25 m, hole a = 0.1 m held radially: u(a) = 0, σ_r(b) = −p.
///
/// Asserted: σ_r = −p on the loaded surface and the closed-form u_r, σ_θ; the measured
/// orders of the last refinement are those of bilinear elements, ≥ 1.8 for the nodal u_r
/// (O(h²), \[Zienkiewicz2005\]) and ≥ 0.85 for the recovered surface stresses (O(h):
/// Gauss-point values extrapolated to a node of the polygonal boundary, whose normal turns by
/// Δθ at every node); errors on the finest mesh below 2e-4 (u_r) and 3 % of p (stresses:
/// the n = 32 error, 17 %, divided by 2³ at order 1 is 2.2 %). Measured (2026-11-26): housing
/// u_r 1.3e-4, σ_r 2.5 %, σ_θ 1.1 % of p at n = 256, orders 1.92 / 0.94 / 0.90. The bearing
/// model's 240 nodes around carry this O(h) recovery error in its bore stresses.
#[test]
fn lame_cylinders_converge_at_the_element_orders() {
    let m = Material::STEEL;
    let (lam, mu) = lame(m);
    let p = 40e6;
    // Housing: B = −A b², 2(λ+μ)A + 2μA b²/a² = −p.
    let (ha, hb) = (0.25, 0.5);
    let a_h = -p / (2.0 * (lam + mu) + 2.0 * mu * hb * hb / (ha * ha));
    let housing_exact = Cylinder {
        a: a_h,
        b: -a_h * hb * hb,
        lam,
        mu,
    };
    // Shaft: B = −A a², 2(λ+μ)A + 2μA a²/b² = −p at r = b.
    let (sa, sb) = (0.1, 0.25);
    let a_s = -p / (2.0 * (lam + mu) + 2.0 * mu * sa * sa / (sb * sb));
    let shaft_exact = Cylinder {
        a: a_s,
        b: -a_s * sa * sa,
        lam,
        mu,
    };
    assert!((housing_exact.sr(ha) + p).abs() < 1e-6 && (shaft_exact.sr(sb) + p).abs() < 1e-6);
    for (name, exact, r_surface) in [("housing", &housing_exact, ha), ("shaft", &shaft_exact, sb)] {
        let mut errors = Vec::new();
        for n in [32, 64, 128, 256] {
            let mesh = if name == "housing" {
                Mesh::housing(
                    ha,
                    HousingShape::Circle { radius: hb },
                    n,
                    square_layers(ha, hb, n),
                )
            } else {
                Mesh::shaft(sa, sb, n, square_layers(sa, sb, n))
            };
            let body = ElasticBody::new(mesh, m).unwrap();
            errors.push(cylinder_errors(&body, p, exact, r_surface));
        }
        let order = |c: usize, i: usize| (errors[i][c] / errors[i + 1][c]).log2();
        for (i, e) in errors.iter().enumerate() {
            eprintln!(
                "{name} n = {}: u_r {:.3e}, σ_r {:.3e}, σ_θ {:.3e}{}",
                32 << i,
                e[0],
                e[1],
                e[2],
                if i > 0 {
                    format!(
                        "  orders {:.2} {:.2} {:.2}",
                        order(0, i - 1),
                        order(1, i - 1),
                        order(2, i - 1)
                    )
                } else {
                    String::new()
                }
            );
        }
        let last = errors.len() - 2;
        assert!(
            order(0, last) >= 1.8,
            "{name}: u_r order {}",
            order(0, last)
        );
        assert!(
            order(1, last) >= 0.85,
            "{name}: σ_r order {}",
            order(1, last)
        );
        assert!(
            order(2, last) >= 0.85,
            "{name}: σ_θ order {}",
            order(2, last)
        );
        let fine = errors.last().unwrap();
        assert!(
            fine[0] < 2e-4 && fine[1] < 0.03 && fine[2] < 0.03,
            "{name}: {fine:?}"
        );
    }
}

/// Maxwell–Betti: the radial displacement at node i under a unit radial force at node j
/// equals that at j under the force at i, for both bodies (the housing's square outline and
/// the shaft's one tangential support break the rotational symmetry, so this is not a
/// property of a circulant matrix). Round-off of the sparse Cholesky solves: 1e-10 of the
/// largest entry.
#[test]
fn compliance_is_reciprocal() {
    let m = Material::STEEL;
    for body in [
        ElasticBody::new(Mesh::shaft(0.1, 0.25, 48, square_layers(0.1, 0.25, 48)), m).unwrap(),
        ElasticBody::new(
            Mesh::housing(0.25, HousingShape::Square { half_width: 0.5 }, 48, 10),
            m,
        )
        .unwrap(),
    ] {
        let g = body.radial_force_compliance().unwrap();
        let big = g.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(big > 0.0);
        for i in 0..g.len() {
            for j in 0..i {
                assert!((g[i][j] - g[j][i]).abs() < 1e-10 * big, "{i} {j}");
            }
        }
        // The film pressure pushes each surface away from the film: the diagonal is
        // positive (housing, outward) or negative (shaft, inward).
        let c = body.pressure_compliance().unwrap();
        let sign = match body.mesh().fluid {
            FluidSide::Inside => 1.0,
            FluidSide::Outside => -1.0,
        };
        assert!((0..c.len()).all(|i| sign * c[i][i] > 0.0));
    }
}

/// The gap compliance of the pair equals the two Lamé solutions combined for a uniform
/// pressure (u_housing − u_shaft at the film surface), within 0.2 % on 128 nodes around (the
/// u_r errors of the Lamé test at that mesh are below 1e-3).
#[test]
fn gap_compliance_of_uniform_pressure() {
    let m = Material::STEEL;
    let (lam, mu) = lame(m);
    let n = 128;
    let shaft =
        ElasticBody::new(Mesh::shaft(0.1, 0.25, n, square_layers(0.1, 0.25, n)), m).unwrap();
    let housing = ElasticBody::new(
        Mesh::housing(
            0.25,
            HousingShape::Circle { radius: 0.5 },
            n,
            square_layers(0.25, 0.5, n),
        ),
        m,
    )
    .unwrap();
    let c = Compliance::new(&shaft, &housing).unwrap();
    let g = c.gap(&vec![1e6; n]);
    let p = 1e6;
    // As in the Lamé test: housing u(0.5) = 0, shaft u(0.1) = 0, σ_r = −p at r = 0.25.
    let a_h = -p / (2.0 * (lam + mu) + 2.0 * mu * 4.0);
    let housing = Cylinder {
        a: a_h,
        b: -a_h * 0.25,
        lam,
        mu,
    };
    let a_s = -p / (2.0 * (lam + mu) + 2.0 * mu * 0.16);
    let shaft = Cylinder {
        a: a_s,
        b: -a_s * 0.01,
        lam,
        mu,
    };
    assert!((housing.sr(0.25) + p).abs() < 1e-6 && (shaft.sr(0.25) + p).abs() < 1e-6);
    let exact = housing.u(0.25) - shaft.u(0.25);
    assert!(exact > 0.0);
    for v in g {
        assert!((v / exact - 1.0).abs() < 2e-3, "{v} vs {exact}");
    }
}

/// The coupled steady-load solve between its limits, on a small plane-model bearing (JB1's
/// geometry and load per length, μ = 0.1678 Pa·s, 120 × 5 film, 64 nodes around): a
/// structure 10⁴ times stiffer than steel gives the rigid answer — its gap change is ~1e-4 of
/// steel's, ~1e-3 of the thinnest film, so e within 2e-3 and p_max within 1 % — and softer
/// structures (steel, half-steel) give monotonically larger e and lower p_max. Every answer
/// balances the load and satisfies g = C p̄ to its tolerance.
#[test]
fn coupled_solve_between_rigid_and_soft() {
    use crate::reynolds::{GridParams, OperatingConditions, ReynoldsParams, SupplyModel};
    let (r, c) = (0.25, 0.25e-3);
    let l = 100.0 * 2.0 * r;
    let mut p = ReynoldsParams::plain(r, l, c, 0.1678);
    p.supply = SupplyModel::AxialLineAtMaxGap;
    p.grid = GridParams {
        n_theta: 120,
        n_z: 5,
    };
    p.bulk_modulus = 1.5e13;
    let cond = OperatingConditions {
        journal_speed: 65.0 * 2.0 * std::f64::consts::PI / 60.0,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    };
    let load = [0.0, -3.6e6 / 0.3 * l];
    let mut solver = crate::reynolds::ReynoldsSolver::new(p).unwrap();
    let (rigid, info) = solver.solve_steady_load(load, &cond).unwrap();
    let e_rigid = c * info.eccentricity_ratio[0].hypot(info.eccentricity_ratio[1]);
    let mut last = (e_rigid, rigid.max_pressure);
    for (k, scale) in [1e4, 1.0, 0.5].into_iter().enumerate() {
        let m = Material {
            youngs_modulus: 210e9 * scale,
            poisson_ratio: 0.3,
        };
        let params = ElasticParams {
            shaft_material: m,
            housing_material: m,
            n_theta: 64,
            ..ElasticParams::steel(r)
        };
        let bearing = ElasticBearing::new(r, params).unwrap();
        let (sol, info) = solve_steady_load(&mut solver, &bearing, load, &cond).unwrap();
        let eps = info.steady.eccentricity_ratio;
        let e = c * eps[0].hypot(eps[1]);
        let f = sol.film.film_force;
        assert!((f[0] + load[0]).hypot(f[1] + load[1]) <= 1e-8 * load[1].abs());
        let resid = bearing
            .compliance
            .gap(&sol.surface_pressure)
            .iter()
            .zip(&sol.gap_change)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(resid <= 1e-5 * c, "g residual {resid}");
        if k == 0 {
            assert!(
                (e / e_rigid - 1.0).abs() < 2e-3,
                "stiff e {e} vs rigid {e_rigid}"
            );
            assert!((sol.film.max_pressure / rigid.max_pressure - 1.0).abs() < 0.01);
        } else {
            assert!(
                e > last.0 && sol.film.max_pressure < last.1,
                "not monotone at {scale}"
            );
        }
        last = (e, sol.film.max_pressure);
    }
}

/// A grooved bearing (R = L = 25 mm, c = 50 μm, μ = 0.03 Pa·s, 300 rad/s, 0.2 MPa feed) on a
/// small grid, and a structure of modulus `e` around it (hole 0.4 R, square housing 2R, 48
/// nodes around).
fn dynamic_setup(e: f64) -> (crate::reynolds::ReynoldsParams, ElasticBearing) {
    use crate::reynolds::{GridParams, Groove, ReynoldsParams};
    let r = 0.025;
    let mut p = ReynoldsParams::plain(r, r, 50e-6, 0.03);
    p.grid = GridParams {
        n_theta: 48,
        n_z: 9,
    };
    p.grooves = vec![Groove {
        center_angle: std::f64::consts::FRAC_PI_2,
        center_z: 0.0,
        angular_width: 0.3,
        axial_width: 0.008,
        cutoff_film_fraction: 0.01,
    }];
    let material = Material {
        youngs_modulus: e,
        poisson_ratio: 0.3,
    };
    let params = ElasticParams {
        shaft_material: material,
        housing_material: material,
        n_theta: 48,
        ..ElasticParams::steel(r)
    };
    (p, ElasticBearing::new(r, params).unwrap())
}

fn dynamic_conditions() -> crate::reynolds::OperatingConditions {
    crate::reynolds::OperatingConditions {
        journal_speed: 300.0,
        bearing_speed: 0.0,
        feed_pressures: vec![2e5],
    }
}

/// The dynamic deformable film between its limits and in time.
///
/// (a) The stiff-structure limit: structures 1e4 and 1e5 times stiffer than steel (gaps
/// ~4e-11 and ~4e-12 m against a 50 μm clearance, solved to 1e-12 c so that the gap's own
/// tolerance is 1e-5 of the smaller one) step as the rigid film, and at every step — the onset
/// included — their differences from it are first order in the compliance: the 1e5 structure's
/// force difference is a tenth of the 1e4 structure's (measured 0.0999–0.1004 per component
/// over 20 steps; asserted to 2 % of the vector). From the fifth step on the 1e4 structure's
/// forces agree with the rigid film's to 1e-5 of the load (the static gap's effect, 2.05e-6
/// measured). The first steps carry more, the squeeze of the deformation's onset — from the
/// film at rest the rigid pressure rises within the first step, so g jumps from 0 to C p̄
/// (~3.4e-11 m in 0.1 ms) and the rigid film's own early transient moves it on: 1.3e-4 of the
/// load at step 1, 2.0e-5 / 1.2e-5 / 7.9e-6 at steps 2–4 — and that part is ∝ C as well
/// (the ratio above), so it is the coupled physics of this start, not an error that does not
/// vanish with the compliance.
///
/// (b) A steel structure, the journal held at ε from a film at rest: the coupled step converges in
/// Δt at second order. The film at rest is loaded within a relaxation time τ (of the order of 12 μ
/// C L²/h³, C the compliance per pressure) of the structure and the film's squeeze (measured: the
/// difference of the force from its 4 ms value falls 446 → 177 → 80 → 35 N over successive 0.2 ms,
/// τ ≈ 0.24 ms), and the force at 3 ms (12 τ) carries the scheme's error of that decay, which is
/// asymptotic only for Δt ≪ τ: the differences between Δt = 0.1, 0.05, 0.025 ms (gap to 1e-10 c,
/// below their size: the default 1e-8 c leaves ~1e-4 N of noise) are 5.86e-3 and 1.44e-3 N of 1721
/// N, ratio 4.06 (asserted > 3). With Δt = 0.2 ms (Δt/τ ≈ 0.8) the ratio was 2.2 — what issue 15
/// had recorded as "first order"; backward Euler's ratios over the same four steps are 4.28 / 3.24,
/// not yet its asymptotic 2 either, while the rigid film (no τ) falls by 6.1 / 3.8. Every accepted
/// state's gap is C p̄ of its own pressure to the tolerance.
#[test]
fn dynamic_film_between_its_limits_and_in_time() {
    use crate::inverse::{FilmModel, ReynoldsFilm};
    let eps = [0.5, -0.4];
    let mut differences = Vec::new();
    for scale in [1e4, 1e5] {
        let (p, stiff) = dynamic_setup(210e9 * scale);
        let mut rigid = ReynoldsFilm::new(p.clone()).unwrap();
        let mut s = rigid.initial_state(eps);
        let mut elastic = ElasticFilm::new(p.clone(), &stiff).unwrap();
        elastic.tolerance = 1e-12 * p.clearance;
        let mut es = elastic.initial_state(eps);
        let mut per_step = Vec::new();
        for step in 0..20 {
            let (r, n) = rigid.step(&s, eps, 1e-4, &dynamic_conditions()).unwrap();
            let (e, m) = elastic.step(&es, eps, 1e-4, &dynamic_conditions()).unwrap();
            let w = r.film_force[0].hypot(r.film_force[1]);
            let d = [
                (e.film_force[0] - r.film_force[0]) / w,
                (e.film_force[1] - r.film_force[1]) / w,
            ];
            if scale == 1e4 && step >= 4 {
                assert!(d[0].hypot(d[1]) < 1e-5, "step {step}: {d:?} of the load");
            }
            per_step.push(d);
            (s, es) = (n, m);
        }
        differences.push(per_step);
    }
    for (step, (d4, d5)) in differences[0].iter().zip(&differences[1]).enumerate() {
        let off = (d5[0] - 0.1 * d4[0]).hypot(d5[1] - 0.1 * d4[1]);
        assert!(
            off <= 0.02 * 0.1 * d4[0].hypot(d4[1]),
            "step {step}: 1e5 x steel {d5:?}, 1e4 x steel {d4:?}"
        );
    }
    let (p, steel) = dynamic_setup(210e9);
    let mut at_end = Vec::new();
    for dt in [1e-4f64, 5e-5, 2.5e-5] {
        let mut film = ElasticFilm::new(p.clone(), &steel).unwrap();
        film.tolerance = 1e-10 * p.clearance;
        film.set_capture_fields(true);
        let mut state = film.initial_state(eps);
        let mut force = [0.0; 2];
        for _ in 0..(3e-3 / dt).round() as usize {
            let (resp, next) = film.step(&state, eps, dt, &dynamic_conditions()).unwrap();
            let target = film.gap_of(&resp.fields.as_ref().unwrap().pressure);
            let worst = target
                .iter()
                .zip(&next.gap)
                .map(|(t, g)| (t - g).abs())
                .fold(0.0, f64::max);
            assert!(worst <= film.tolerance, "{worst}");
            force = resp.film_force;
            state = next;
        }
        at_end.push(force);
    }
    let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let (e1, e2) = (d(at_end[0], at_end[1]), d(at_end[1], at_end[2]));
    eprintln!(
        "forces at 3 ms: {at_end:?}; differences {e1:e}, {e2:e}, ratio {}",
        e1 / e2
    );
    assert!(e1 / e2 > 3.0, "{e1} / {e2}");
}

/// The content of each old level carries that level's own gap, under the same difference
/// formula (what the coupled BDF2 step's squeeze term needs): a film stepped by variable BDF2
/// steps (±30 %) under a prescribed moving gap g(θ, t) = 2 μm (1 + cos(θ − 1)) sin(3000 t),
/// journal held at ε, closes its own discrete balance
/// (a₀ cⁿ⁺¹ − a₁ cⁿ + a₂ cⁿ⁻¹)/Δt = supply − leakage, with c = ∫ (h₀ + gⁿ) φ, to the solve
/// tolerance from the second step on (measured 6.9e-11 of the leakage; asserted 1e-8 as the
/// rigid film's `bdf2_steps_balance_mass_with_variable_steps`). A gap missing from an old level
/// (or entering by another formula) would leave a residual of the order of its content's rate,
/// which here reaches 0.97 of the leakage (asserted > 0.1).
#[test]
fn bdf2_balance_holds_with_a_moving_gap() {
    use crate::reynolds::{FilmDeformation, ReynoldsSolver, StepInput, TimeScheme};
    let eps = [0.5, -0.4];
    let (mut p, _) = dynamic_setup(210e9);
    p.time_scheme = TimeScheme::Bdf2;
    let mut s = ReynoldsSolver::new(p).unwrap();
    let gap = |t: f64| {
        let v = (0..48)
            .map(|k| {
                let th = k as f64 * std::f64::consts::TAU / 48.0;
                2e-6 * (1.0 + (th - 1.0).cos()) * (3000.0 * t).sin()
            })
            .collect();
        FilmDeformation::new(v).unwrap()
    };
    let mut state = s.initial_state(eps);
    state.deformation = Some(gap(0.0));
    let mut history: Vec<(f64, f64)> = Vec::new(); // (content, dt)
    let (mut t, mut worst, mut moved) = (0.0, 0.0f64, 0.0f64);
    for n in 1..=40 {
        let dt = 5e-5 * [1.0, 1.3, 0.7, 1.0][n % 4];
        t += dt;
        s.set_deformation(Some(gap(t)));
        let input = StepInput {
            eccentricity_ratio: eps,
            dt,
            conditions: dynamic_conditions(),
        };
        let (sol, next) = s.solve_step(&state, &input).unwrap();
        let net = sol.supply_flow.iter().sum::<f64>() - sol.side_leakage[0] - sol.side_leakage[1];
        let scale = sol.side_leakage[0] + sol.side_leakage[1];
        if let [.., (c_prev, _), (c_now, dt_prev)] = history[..] {
            let (a0, a1, a2) = TimeScheme::bdf2_coefficients(dt / dt_prev);
            let rate = (a0 * sol.film_content - a1 * c_now + a2 * c_prev) / dt;
            worst = worst.max(((rate - net) / scale).abs());
        }
        if let [.., (c_now, _)] = history[..] {
            moved = moved.max(((sol.film_content - c_now) / dt / scale).abs());
        }
        history.push((sol.film_content, dt));
        state = next;
    }
    assert!(moved > 0.1, "the gap must move the content: {moved:e}");
    eprintln!("moved {moved:e} worst {worst:e}");
    assert!(worst < 1e-8, "worst BDF2 step balance {worst:e}");
}

/// Step halving on the coupled film, each scheme, as the rigid film's
/// `step_halving_gives_each_schemes_order_on_the_reynolds_film`: a journal whirling and
/// breathing (ε = 0.5 + 0.1 sin 2ωt at ω = 100 rad/s, from the film at rest), steel structure
/// at the default gap tolerance 1e-8 c, the force after a quarter whirl (15.7 ms, 65 times the
/// structure's relaxation time τ ≈ 0.24 ms of the test above, so the start has decayed) with
/// Δt, Δt/2, Δt/4. The observed order log₂(|F_Δt − F_Δt/2| / |F_Δt/2 − F_Δt/4|) is the
/// scheme's: backward Euler 1 and BDF2 2 within 0.35 (40 / 80 / 160 steps: measured 0.90 and
/// 1.95; 80 / 160 / 320: 0.99 and 2.05), Crank–Nicolson at least 2 − 0.35 (80 / 160 / 320
/// steps: 1.86; at 40 / 80 / 160 it is 1.70 and the rigid film's own 1.48 — its
/// pre-asymptotic ringing, as in the rigid test). Measured at 1e-10 c the orders are the same
/// to the printed digits. Here the deformation moves the force by 0.34 N of 147 N, so this test
/// guards each scheme's path through the coupled step; the coupling's own time error is the
/// dominant one in the held-ε test above (the structure's relaxation, 35 N of 1721 N).
#[test]
fn coupled_step_halving_gives_each_schemes_order() {
    use crate::inverse::FilmModel;
    use crate::reynolds::TimeScheme;
    let whirl = 100.0;
    let t_end = 2.0 * std::f64::consts::PI / whirl / 4.0;
    let eps = |t: f64| {
        let m = 0.5 + 0.1 * (2.0 * whirl * t).sin();
        [m * (whirl * t).cos(), m * (whirl * t).sin()]
    };
    let (p0, steel) = dynamic_setup(210e9);
    for (scheme, order, steps) in [
        (TimeScheme::BackwardEuler, 1.0, 40),
        (TimeScheme::Bdf2, 2.0, 40),
        (TimeScheme::CrankNicolson, 2.0, 80),
    ] {
        let mut p = p0.clone();
        p.time_scheme = scheme;
        let force = |steps: usize| {
            let mut film = ElasticFilm::new(p.clone(), &steel).unwrap();
            let mut state = film.initial_state(eps(0.0));
            let dt = t_end / steps as f64;
            let mut f = [0.0; 2];
            for n in 1..=steps {
                let (r, next) = film
                    .step(&state, eps(n as f64 * dt), dt, &dynamic_conditions())
                    .unwrap();
                f = r.film_force;
                state = next;
            }
            f
        };
        let (f1, f2, f4) = (force(steps), force(2 * steps), force(4 * steps));
        let d12 = (f1[0] - f2[0]).hypot(f1[1] - f2[1]);
        let d24 = (f2[0] - f4[0]).hypot(f2[1] - f4[1]);
        let observed = (d12 / d24).log2();
        eprintln!(
            "{scheme:?}: |F| {:.2} N, observed order {observed:.2}",
            f4[0].hypot(f4[1])
        );
        let in_range = match scheme {
            TimeScheme::CrankNicolson => observed > order - 0.35,
            _ => (observed - order).abs() < 0.35,
        };
        assert!(
            in_range,
            "{scheme:?}: observed order {observed}, expected {order}"
        );
    }
}

/// The coupled film's exact dF/dε ([`ElasticFilm`]'s force Jacobian: the film's ∂F/∂ε at fixed
/// g plus ∂F/∂g · dg/dε through the compliance) against central differences of the converged
/// coupled step, on a cavitating step of backward Euler and of BDF2 (two steps of history, so
/// BDF2 uses its own formula), steel structure. The gap is converged to 1e-10 c so that its
/// noise (1e-10 c over a difference h c = 1e-5 c: 1e-5 relative) is below the comparison.
/// Differences with h = 1e-5 are trusted only where they agree with h = 3e-6 to 1e-4 of the
/// Jacobian's norm (no switch crossed); there the exact Jacobian must agree to 1e-4 (the film's
/// linear solves and the GMRES on the gap are to 1e-5 of their right-hand sides; measured
/// 1.3e-6 for BE, 1.8e-6 for BDF2). The gap term must matter: the fixed-g Jacobian is off by
/// 2.2 (BE) and 2.8 (BDF2) times the coupled one's norm here, asserted > 0.05.
#[test]
fn coupled_force_jacobian_matches_differences() {
    use crate::inverse::FilmModel;
    use crate::reynolds::TimeScheme;
    let norm = |m: [[f64; 2]; 2]| m.iter().flatten().map(|v| v * v).sum::<f64>().sqrt();
    let diff = |a: [[f64; 2]; 2], b: [[f64; 2]; 2]| {
        norm([
            [a[0][0] - b[0][0], a[0][1] - b[0][1]],
            [a[1][0] - b[1][0], a[1][1] - b[1][1]],
        ])
    };
    let mut compared = 0;
    for scheme in [TimeScheme::BackwardEuler, TimeScheme::Bdf2] {
        let (mut p, steel) = dynamic_setup(210e9);
        p.time_scheme = scheme;
        let mut film = ElasticFilm::new(p.clone(), &steel).unwrap();
        film.tolerance = 1e-10 * p.clearance;
        let c = dynamic_conditions();
        let dt = 1e-4;
        let mut state = film.initial_state([0.5, -0.4]);
        for e in [[0.51, -0.41], [0.52, -0.42]] {
            state = film.step(&state, e, dt, &c).unwrap().1;
        }
        let e0 = [0.53, -0.43];
        let force = |film: &mut ElasticFilm, e: [f64; 2]| {
            film.step(&state, e, dt, &c).unwrap().0.film_force
        };
        force(&mut film, e0);
        let exact = film.force_jacobian().unwrap().unwrap();
        let fixed_gap = film.inner.solver_mut().film_force_jacobian().unwrap();
        let mut central = |h: f64| {
            let mut m = [[0.0; 2]; 2];
            for k in 0..2 {
                let (mut ep, mut em) = (e0, e0);
                ep[k] += h;
                em[k] -= h;
                let (fp, fm) = (force(&mut film, ep), force(&mut film, em));
                for i in 0..2 {
                    m[i][k] = (fp[i] - fm[i]) / (2.0 * h);
                }
            }
            m
        };
        let (d1, d2) = (central(1e-5), central(3e-6));
        let scale = norm(exact);
        eprintln!(
            "{scheme:?}: exact {exact:?}, differences {d1:?} / {d2:?}, fixed g {fixed_gap:?}; \
             exact − differences {:.2e}, differences between h {:.2e}, gap term {:.2e} (of the norm)",
            diff(exact, d1) / scale,
            diff(d1, d2) / scale,
            diff(exact, fixed_gap) / scale
        );
        assert!(
            diff(exact, fixed_gap) > 0.05 * scale,
            "the gap term is too small to test"
        );
        if diff(d1, d2) <= 1e-4 * scale {
            compared += 1;
            assert!(
                diff(exact, d1) <= 1e-4 * scale,
                "{scheme:?}: exact {exact:?} vs differences {d1:?}"
            );
        }
    }
    assert_eq!(compared, 2, "a switch was crossed: move the test point");
}

/// The housing's bore stresses against Michell's series ([`super::MichellAnnulus`],
/// \[Michell1899\], \[Barber2010\] ch. 8–9): a steel annulus R_i = 0.25 m … R_o = 0.5 m (JB1's
/// bore, its outer boundary at the square housing's half-width) fixed on R_o, loaded on the bore
/// by p(θ) = p0 cos²(θ − 20°) where that cosine is positive, else 0 (a one-sided film-like
/// load: the n = 1 mode carries its net force, and the 20° turn needs the sine modes). Series:
/// the load's exact Fourier coefficients (∝ n⁻³), converged — 1000 against 4000 modes
/// differ by < 1e-6 p0. FE: the housing mesh with a circular outline, nearly square elements,
/// 60 / 120 / 240 nodes around; σ_r, σ_θ and von Mises at the bore nodes. The FE must converge
/// to the series: the largest error over the bore falls by at least 1.6× per halving of the
/// element size for σ_θ and von Mises (first order, the nodal stresses extrapolated from the
/// Gauss points; measured ratios in the output), and at 240 around stays below 2 % of p0.
/// σ_r = −p at the bore is the traction condition (the series has it exactly).
#[test]
fn housing_bore_stresses_converge_to_michells_series() {
    use std::f64::consts::PI;
    let (r_i, r_o, p0, turn) = (0.25, 0.5, 1e7, 20f64.to_radians());
    let material = Material::STEEL;
    let annulus = MichellAnnulus::new(material, r_i, r_o).unwrap();
    let load = |t: f64| p0 * (t - turn).cos().max(0.0).powi(2);
    // ∫_{−π/2}^{π/2} cos mθ dθ, and p's coefficients before the turn (a cosine series).
    let integral = |m: f64| {
        if m == 0.0 {
            PI
        } else {
            2.0 * (m * PI / 2.0).sin() / m
        }
    };
    let coefficients = |modes: usize| -> (Vec<f64>, Vec<f64>) {
        (0..modes)
            .map(|n| {
                let m = n as f64;
                let v = 0.5 * integral(m) + 0.25 * (integral(m + 2.0) + integral((m - 2.0).abs()));
                let a = p0 * v / if n == 0 { 2.0 * PI } else { PI };
                let (s, c) = (m * turn).sin_cos();
                (a * c, a * s)
            })
            .unzip()
    };
    let von_mises = |s: [f64; 3]| {
        let z = material.poisson_ratio * (s[0] + s[1]);
        let (a, b, c) = (s[0] - s[1], s[1] - z, z - s[0]);
        (0.5 * (a * a + b * b + c * c) + 3.0 * s[2] * s[2]).sqrt()
    };
    let worst = |a: &[[f64; 3]], b: &[[f64; 3]], f: &dyn Fn([f64; 3]) -> f64| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (f(*x) - f(*y)).abs())
            .fold(0.0, f64::max)
    };
    let mut errors = Vec::new();
    for n in [60usize, 120, 240] {
        let theta: Vec<f64> = (0..n).map(|k| 2.0 * PI * k as f64 / n as f64).collect();
        let series = |modes| {
            let (a, b) = coefficients(modes);
            annulus.bore_stresses(&a, &b, &theta)
        };
        let exact = series(4000);
        let truncation = worst(&series(1000), &exact, &|s| s[1]);
        assert!(
            truncation < 1e-6 * p0,
            "series not converged: {truncation:e}"
        );
        let mesh = Mesh::housing(
            r_i,
            HousingShape::Circle { radius: r_o },
            n,
            square_layers(r_i, r_o, n),
        );
        let body = ElasticBody::new(mesh, material).unwrap();
        let pressure: Vec<f64> = theta.iter().map(|&t| load(t)).collect();
        let u = body.solve(&body.surface_load(&pressure).unwrap()).unwrap();
        let stresses = body.stresses(&u);
        let fe: Vec<[f64; 3]> = body
            .mesh()
            .surface
            .iter()
            .zip(&theta)
            .map(|(&node, &t)| stresses[node].polar(t))
            .collect();
        let e = [
            worst(&fe, &exact, &|s| s[0]) / p0,
            worst(&fe, &exact, &|s| s[1]) / p0,
            worst(&fe, &exact, &|s| von_mises(s)) / p0,
        ];
        let peak = exact.iter().map(|s| von_mises(*s)).fold(0.0, f64::max) / p0;
        let fe_peak = fe.iter().map(|s| von_mises(*s)).fold(0.0, f64::max) / p0;
        eprintln!(
            "{n} around: max error / p0 σ_r {:.2e}, σ_θ {:.2e}, von Mises {:.2e}; bore von \
             Mises max / p0: series {peak:.4}, FE {fe_peak:.4}; series truncation 1000 vs 4000 \
             modes {:.1e} p0",
            e[0],
            e[1],
            e[2],
            truncation / p0
        );
        errors.push(e);
    }
    for w in errors.windows(2) {
        let ratios = [w[0][1] / w[1][1], w[0][2] / w[1][2]];
        eprintln!(
            "error ratio per halving: σ_θ {:.2}, von Mises {:.2}",
            ratios[0], ratios[1]
        );
        assert!(ratios.iter().all(|r| *r > 1.6), "{ratios:?}");
    }
    assert!(errors[2].iter().all(|e| *e < 0.02), "{:?}", errors[2]);
    // The series alone: the bore von Mises maximum of p0 cos²(kθ) on |θ| < 90°/k falls with the
    // load's width towards the half-plane's (1 − 2ν) p0 = 0.4 p0 (σ_θ = σ_r = −p under a normal
    // load on a half-plane's surface, plane strain).
    let theta: Vec<f64> = (0..=720).map(|k| PI * k as f64 / 720.0).collect();
    let mut peaks = Vec::new();
    for k in [1.0, 1.5, 2.0, 3.0, 6.0] {
        let w = PI / (2.0 * k);
        let integral = |m: f64| {
            if m == 0.0 {
                2.0 * w
            } else {
                2.0 * (m * w).sin() / m
            }
        };
        let a: Vec<f64> = (0..2000)
            .map(|n| {
                let m = n as f64;
                let v = 0.5 * integral(m)
                    + 0.25 * (integral(m + 2.0 * k) + integral((m - 2.0 * k).abs()));
                v / if n == 0 { 2.0 * PI } else { PI }
            })
            .collect();
        let b = vec![0.0; a.len()];
        let peak = annulus
            .bore_stresses(&a, &b, &theta)
            .into_iter()
            .map(von_mises)
            .fold(0.0, f64::max);
        eprintln!(
            "load half-width {:.0}°: bore von Mises max / p0 {peak:.3}",
            90.0 / k
        );
        peaks.push(peak);
    }
    assert!(peaks.windows(2).all(|w| w[1] < w[0]), "{peaks:?}");
    assert!((peaks[4] - 0.4).abs() < 0.05, "{peaks:?}");
}

/// A trial from the same state starts its gap along the coupled Jacobian's dg/dε (module docs
/// of `dynamic`), so the force the inverse solver's Newton sees follows ε through the gap even
/// when the start already meets the gap tolerance. Steel, BDF2 step of 0.1 ms from a moving
/// film, gap tolerance 1e-6 c, an ε change of 1e-6: the force change F(ε₁) − F(ε₀) of a film
/// that evaluated its Jacobian at ε₀ is accepted after one film solve and matches the change
/// at 1e-10 c (the converged coupling) to 5 % of it (2.7e-5 measured); the same film without
/// the Jacobian (the gap kept from ε₀) misses it by more than 10 % (0.27 measured, after 3 gap
/// iterations: the loose tolerance lets the force lag its gap).
#[test]
fn trial_gap_starts_along_the_gap_sensitivity() {
    use crate::inverse::FilmModel;
    let (p, steel) = dynamic_setup(210e9);
    let c = dynamic_conditions();
    let dt = 1e-4;
    let film = |tolerance: f64| {
        let mut f = ElasticFilm::new(p.clone(), &steel).unwrap();
        f.tolerance = tolerance * p.clearance;
        f
    };
    let mut tight = film(1e-10);
    let mut state = tight.initial_state([0.5, -0.4]);
    for e in [[0.51, -0.41], [0.52, -0.42]] {
        state = tight.step(&state, e, dt, &c).unwrap().1;
    }
    let (e0, e1) = ([0.53, -0.43], [0.53 + 1e-6, -0.43]);
    let change = |film: &mut ElasticFilm, jacobian: bool| {
        let f0 = film.step(&state, e0, dt, &c).unwrap().0.film_force;
        if jacobian {
            film.force_jacobian().unwrap().unwrap();
        }
        let f1 = film.step(&state, e1, dt, &c).unwrap().0.film_force;
        let iterations = film.step_diagnostics()[0].1;
        ([f1[0] - f0[0], f1[1] - f0[1]], iterations)
    };
    let (exact, _) = change(&mut tight, false);
    let (along, along_iterations) = change(&mut film(1e-6), true);
    let (frozen, frozen_iterations) = change(&mut film(1e-6), false);
    let miss = |d: [f64; 2]| (d[0] - exact[0]).hypot(d[1] - exact[1]) / exact[0].hypot(exact[1]);
    eprintln!(
        "force change {exact:?}; started along dg/dε {along:?} (miss {:.2e}, {along_iterations} \
         gap iterations), gap kept {frozen:?} (miss {:.2e}, {frozen_iterations})",
        miss(along),
        miss(frozen)
    );
    assert_eq!(along_iterations, 1.0);
    assert!(miss(along) < 0.05, "{}", miss(along));
    assert!(miss(frozen) > 0.1, "{}", miss(frozen));
}
