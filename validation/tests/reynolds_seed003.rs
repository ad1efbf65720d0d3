//! Seed `003_aa488eb78871ee6c` Table 2, rigid case "JB1 T_m const., α = 0": the steady load
//! → eccentricity solve (Newton) for the bearing of its Table 1.
//!
//! Table 1: shaft d = 500 mm, support D = 500.5 mm (c = 0.25 mm), L = 300 mm, F = 3600 kN,
//! N = 65 rpm; Table 2: μ = 0.1678 Pa·s (constant T_m, α = 0) → e = 0.2335 mm,
//! p_max = 82.26 MPa at θ_pmax = 15.62°, h_0 = 0.0165 mm at θ_h0 = 26.29° (angles from the load
//! line). The paper sets negative pressures to zero (Reynolds / Swift–Stieber film with the film
//! starting at the widest gap): our supply line at h_max with JFO cavitation is the same problem
//! (design.md §8). The paper's film is a *plane model* p(θ) (its eq. 1; its results sit next to
//! R&B's L/D → ∞ row, e = 0.2352 mm): the finite L = 300 mm bearing gives e ≈ 0.240 mm
//! (ε ≈ 0.96, as the Raimondi–Boyd L/D = 1/2 and 1 tables bracket at S = 0.0076). So the plane
//! model is reproduced as a bearing 100 diameters long carrying the same load per unit length
//! (3600 kN / 0.3 m): the end zones (≈ one radius each) cost ≈ 1 % of the load there, which
//! moves e by ≈ 0.1 %.
//!
//! Tolerances (the issue's): e within 1.5 %, p_max within 5 %, its angle within 2°.

use jbearing_solvers::reynolds::{
    GridParams, OperatingConditions, ReynoldsParams, ReynoldsSolver, SteadyLoadInfo, SupplyModel,
};

/// The paper's film is incompressible; with the physical bulk modulus (1.5 GPa) the Elrod
/// film compresses by p/β ≈ 5 % at the 80 MPa peak, which lowers the load capacity at a given ε.
/// The comparison therefore runs with β = 1.5e13 Pa (ψ = p/β ≈ 5e-6: incompressible to the
/// table's digits); the physical-β answer is printed beside it.
#[test]
fn jb1_rigid_constant_viscosity() {
    let c = 0.25e-3;
    let physical = jb1(1.5e9);
    let (e, p_max, p_angle, att, info) = jb1(1.5e13);
    let h0 = c - e;
    eprintln!(
        "JB1 (β = 1.5e13): e {:.4} mm (0.2335), p_max {:.2} MPa (82.26) at {p_angle:.2}° (15.62), h_0 {:.4} mm (0.0165), attitude {att:.2}° (26.29); Newton {} iterations, {} film solves, force residual {:.2e} N",
        e * 1e3,
        p_max / 1e6,
        h0 * 1e3,
        info.iterations,
        info.film_solves,
        info.force_residual
    );
    eprintln!(
        "JB1 (β = 1.5 GPa, physical): e {:.4} mm, p_max {:.2} MPa at {:.2}°, attitude {:.2}°",
        physical.0 * 1e3,
        physical.1 / 1e6,
        physical.2,
        physical.3
    );
    assert!(((e - 0.2335e-3) / 0.2335e-3).abs() < 0.015, "e = {e}");
    assert!(
        ((p_max - 82.26e6) / 82.26e6).abs() < 0.05,
        "p_max = {p_max}"
    );
    assert!((p_angle - 15.62).abs() < 2.0, "θ_pmax = {p_angle}");
    // Film force balances the load.
    assert!(info.force_residual < 1e-6 * 3.6e6 / 0.3 * 50.0);
}

/// (e, p_max, angle of p_max from the load line in the direction of rotation (deg), attitude
/// (deg), Newton info).
fn jb1(bulk_modulus: f64) -> (f64, f64, f64, f64, SteadyLoadInfo) {
    let (r, c, mu) = (0.25, 0.25e-3, 0.1678);
    let l = 100.0 * 2.0 * r;
    let mut p = ReynoldsParams::plain(r, l, c, mu);
    p.supply = SupplyModel::AxialLineAtMaxGap;
    // 240 around (1.5°, so the p_max angle is resolved well inside the 2° asked), 99 axial
    // cells of about one diameter.
    p.grid = GridParams {
        n_theta: 240,
        n_z: 101,
    };
    p.bulk_modulus = bulk_modulus;
    let mut s = ReynoldsSolver::new(p).unwrap();
    let cond = OperatingConditions {
        journal_speed: 65.0 * 2.0 * std::f64::consts::PI / 60.0,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    };
    let load = [0.0, -3.6e6 / 0.3 * l];
    let (sol, info) = s.solve_steady_load(load, &cond).unwrap();
    let eps = info.eccentricity_ratio;
    let e = c * eps[0].hypot(eps[1]);
    let load_dir = load[1].atan2(load[0]);
    let p_angle = jbearing_wrap(sol.max_pressure_location[0] - load_dir).to_degrees();
    (
        e,
        sol.max_pressure,
        p_angle,
        sol.attitude_angle.to_degrees(),
        info,
    )
}

fn jbearing_wrap(a: f64) -> f64 {
    let x = a.rem_euclid(2.0 * std::f64::consts::PI);
    if x > std::f64::consts::PI {
        x - 2.0 * std::f64::consts::PI
    } else {
        x
    }
}
