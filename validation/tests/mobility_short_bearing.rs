//! Short-bearing mobility against an independent integration of the short-bearing pressure, and
//! against Ocvirk's steady closed form.
//!
//! Oracle: the film force of the short-bearing pure-squeeze pressure (\[Flores2006\] eq. 18)
//!
//! ```text
//!   p(θ, z) = max(0, 6 μ (v·n) (L²/4 − z²) / h³),   h = c (1 − ε·n),  F_film = −∫∫ p n R dθ dz
//! ```
//!
//! integrated numerically in physical units — midpoint rule in θ over the whole circle with the
//! Gumbel cut-off applied pointwise, Simpson in z — without the Sommerfeld substitution, the
//! half-range bookkeeping or the root search of the code under test.

use jbearing_solvers::mobility::{
    BookerShortBearing, ExactShortBearing, MobilityModel, MobilityParams, OrbitParams,
    PeriodicLoad, solve_orbit,
};
use std::f64::consts::{PI, TAU};

fn bearing(length: f64) -> MobilityParams {
    MobilityParams {
        radius: 0.03,
        length,
        radial_clearance: 30e-6,
        viscosity: 0.01,
        omega_journal: 300.0,
        omega_bearing: 40.0,
    }
}

/// Film force on the journal (N) for squeeze velocity v (m/s) at eccentricity ratio ε.
fn film_force_by_quadrature(b: &MobilityParams, eps: [f64; 2], v: [f64; 2]) -> [f64; 2] {
    let n_theta = 200_000;
    let dth = TAU / n_theta as f64;
    let l = b.length;
    // Simpson in z on [−L/2, L/2] with 3 nodes (exact for the quadratic z-profile).
    let zs = [-0.5 * l, 0.0, 0.5 * l];
    let wz = [l / 6.0, 4.0 * l / 6.0, l / 6.0];
    let mut f = [0.0, 0.0];
    for k in 0..n_theta {
        let th = (k as f64 + 0.5) * dth;
        let (ct, st) = (th.cos(), th.sin());
        let h = b.radial_clearance * (1.0 - eps[0] * ct - eps[1] * st);
        let vn = v[0] * ct + v[1] * st;
        let mut pz = 0.0;
        for (z, w) in zs.iter().zip(wz) {
            let p = 6.0 * b.viscosity * vn * (0.25 * l * l - z * z) / (h * h * h);
            pz += w * p.max(0.0);
        }
        f[0] -= pz * ct * b.radius * dth;
        f[1] -= pz * st * b.radius * dth;
    }
    f
}

/// Squeeze velocity v (m/s) that the mobility model gives for load W at ε (bearing frame).
fn squeeze_velocity<M: MobilityModel>(
    b: &MobilityParams,
    m: &M,
    eps: [f64; 2],
    w: [f64; 2],
) -> [f64; 2] {
    let wm = w[0].hypot(w[1]);
    let (wx, wy) = (w[0] / wm, w[1] / wm);
    let zeta = eps[0] * wx + eps[1] * wy;
    let kappa = -eps[0] * wy + eps[1] * wx;
    let [mz, mk] = m.mobility(zeta, kappa);
    let s = wm * b.mobility_scale() * b.radial_clearance;
    [s * (mz * wx - mk * wy), s * (mz * wy + mk * wx)]
}

/// Relative residual |F_film + W| / |W| over a grid of ε, position angles and load directions.
fn worst_residual<M: MobilityModel>(b: &MobilityParams, m: &M) -> f64 {
    let mut worst: f64 = 0.0;
    for &e in &[0.0, 0.2, 0.5, 0.8, 0.95] {
        for k in 0..8 {
            // Load direction and the position of ε relative to it both sweep the circle.
            let load_dir = 0.3 + k as f64 * TAU / 8.0;
            let rel = -PI + (k as f64 + 0.37) * TAU / 8.0;
            let w = [1500.0 * load_dir.cos(), 1500.0 * load_dir.sin()];
            let eps = [e * (load_dir + rel).cos(), e * (load_dir + rel).sin()];
            let v = squeeze_velocity(b, m, eps, w);
            let f = film_force_by_quadrature(b, eps, v);
            let r = (f[0] + w[0]).hypot(f[1] + w[1]) / 1500.0;
            worst = worst.max(r);
        }
    }
    worst
}

#[test]
fn exact_short_bearing_mobility_inverts_the_integrated_squeeze_force() {
    for length in [0.012, 0.024, 0.036] {
        let b = bearing(length);
        let m = ExactShortBearing {
            length_to_diameter: b.length_to_diameter(),
        };
        // force → velocity (mobility) → force (quadrature): the midpoint rule with 2e5 points and
        // the Gumbel kink is accurate to ~1e-8 relative (h² with h = 3e-5 rad, peak width
        // ≥ √(1 − 0.95) ≈ 0.2 rad); the root search is converged to 1e-14 in angle.
        let r = worst_residual(&b, &m);
        assert!(r < 1e-6, "L = {length}: worst |F + W|/|W| = {r:e}");
    }
}

#[test]
fn booker_closed_form_is_an_approximation_of_the_short_bearing_film() {
    let b = bearing(0.024);
    let ld = b.length_to_diameter();
    let booker = BookerShortBearing {
        length_to_diameter: ld,
    };
    let exact = ExactShortBearing {
        length_to_diameter: ld,
    };
    // Near the wall on the load line (δ = 1 − ζ → 0) the exact squeeze integral is dominated by
    // θ ≈ 0: ∫ cos²θ/(δ + θ²/2)³ dθ → (3π√2/8) δ^{-5/2}, so M_exact → 4δ^{5/2}/(3√2 π (L/D)²)
    // while Booker writes δ^{5/2}/(π (L/D)²): the ratio tends to 3√2/4 = 1.0607. The next term
    // is O(δ): at δ = 1e-4 agreement to 1e-3 is expected.
    let d = 1e-4;
    let ratio = booker.mobility(1.0 - d, 0.0)[0] / exact.mobility(1.0 - d, 0.0)[0];
    assert!(
        (ratio - 3.0 * 2f64.sqrt() / 4.0).abs() < 1e-3,
        "Booker/exact on the load line at ε = 1 − 1e-4: {ratio}"
    );
    // Booker's form is exact at ε = 0 and is not exact elsewhere: the force it implies misses
    // the load by a visible amount somewhere on the grid (this is what the exact model is for).
    let r = worst_residual(&b, &booker);
    assert!(
        r > 1e-3,
        "Booker closed form unexpectedly exact: worst residual {r:e}"
    );
}

/// A constant load as a periodic load.
struct Constant {
    w: [f64; 2],
}

impl PeriodicLoad for Constant {
    fn period(&self) -> f64 {
        0.02
    }
    fn load(&self, _t: f64) -> [f64; 2] {
        self.w
    }
}

#[test]
fn constant_load_reproduces_ocvirk_steady_solution() {
    // Ocvirk's short bearing, half-Sommerfeld (π) film, steady rotation U = R (ω_j − ω_b):
    //   W = μ U L³ / (4 c²) · ε / (1 − ε²)² · √(π² (1 − ε²) + 16 ε²),  tan φ = π √(1 − ε²) / (4ε).
    // The exact short-bearing mobility is the same film (Gumbel cut at v·n = 0 is the π film of
    // the converging half), so the orbit's fixed point must be Ocvirk's (ε, φ).
    let b = bearing(0.024);
    let m = ExactShortBearing {
        length_to_diameter: b.length_to_diameter(),
    };
    let u = b.radius * (b.omega_journal - b.omega_bearing);
    for &e in &[0.3, 0.6, 0.85] {
        let w = b.viscosity * u * b.length.powi(3) / (4.0 * b.radial_clearance.powi(2)) * e
            / (1.0 - e * e).powi(2)
            * (PI * PI * (1.0 - e * e) + 16.0 * e * e).sqrt();
        let phi = (PI * (1.0 - e * e).sqrt() / (4.0 * e)).atan();
        // Load along −y; the journal settles at attitude φ ahead of the load in the sense of
        // rotation (counter-clockwise).
        let load = Constant { w: [0.0, -w] };
        let mut p = OrbitParams::new(b);
        p.samples_per_cycle = 64;
        p.max_cycles = 400;
        p.periodicity_tolerance = 1e-10;
        p.relative_tolerance = 1e-11;
        p.absolute_tolerance = 1e-13;
        let orbit = solve_orbit(&p, &m, &load).expect("steady orbit");
        let last = *orbit.eccentricity.last().unwrap();
        let got_e = last[0].hypot(last[1]);
        let got_phi = *orbit.attitude_angle.last().unwrap();
        // The fixed point is reached to the periodicity tolerance (1e-10 per cycle of 0.02 s, a
        // strongly damped approach); 1e-7 leaves room for the integrator's tolerance.
        assert!((got_e - e).abs() < 1e-7, "ε: {got_e} vs Ocvirk {e}");
        assert!(
            (got_phi - phi).abs() < 1e-6,
            "φ: {} vs Ocvirk {}",
            got_phi.to_degrees(),
            phi.to_degrees()
        );
    }
}
