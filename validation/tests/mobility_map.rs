//! The finite-length mobility map used in a real orbit: a map tabulated from the short-bearing
//! squeeze film (the provider that a Reynolds-based film will replace) must reproduce the orbit
//! of the exact short-bearing mobility on the Flores et al. example (seed 000 §5).
//!
//! The map is within ~1e-4 of the exact mobility (unit test in `solvers/src/mobility/map.rs`).
//! Near the load line M^ζ ∝ (1 − ζ)^{5/2}, so a relative mobility error δ moves the film 1 − ζ by
//! about (2/5) δ: the cycle-minimum film of the two orbits must agree to 1e-3 relative, and the
//! orbits themselves to 1e-3 in ε (the cycle-to-cycle periodicity tolerance is 1e-6).

use jbearing_solvers::mobility::{
    ExactShortBearing, LoadInterpolation, MobilityMap, MobilityMapParams, MobilityParams,
    OrbitParams, ShortBearingSqueeze, TabulatedLoad, solve_orbit,
};
use std::f64::consts::TAU;
use std::path::Path;

#[test]
fn short_bearing_map_reproduces_the_exact_short_bearing_orbit() {
    let omega = 2000.0 * TAU / 60.0;
    let bearing = MobilityParams {
        radius: 0.5 * 63.5e-3,
        length: 25.4e-3,
        radial_clearance: 35.56e-6,
        viscosity: 4.16e-3,
        omega_journal: omega,
        omega_bearing: 0.0,
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/reference/flores2006_load.csv");
    let text = std::fs::read_to_string(path).expect("flores2006_load.csv");
    let (mut a, mut f) = (Vec::new(), Vec::new());
    for line in text.lines().skip(1) {
        let mut c = line
            .split(',')
            .map(|x| x.trim().parse::<f64>().expect("number"));
        a.push(c.next().expect("angle"));
        f.push(c.next().expect("load") * 1e3);
    }
    let load =
        TabulatedLoad::unidirectional(a, &f, [0.0, -1.0], 720.0, omega, LoadInterpolation::Linear)
            .expect("load");
    let mut p = OrbitParams::new(bearing);
    p.initial_eccentricity = [0.1 * 1.5f64.sin(), -0.1 * 1.5f64.cos()];

    let ld = bearing.length_to_diameter();
    let map = MobilityMap::build(
        &ShortBearingSqueeze {
            length_to_diameter: ld,
        },
        &MobilityMapParams::default(),
    )
    .expect("map");
    let by_map = solve_orbit(&p, &map, &load).expect("orbit with the map");
    let exact = solve_orbit(
        &p,
        &ExactShortBearing {
            length_to_diameter: ld,
        },
        &load,
    )
    .expect("exact orbit");
    let (hm, he) = (
        by_map.summary.min_film_thickness,
        exact.summary.min_film_thickness,
    );
    assert!(
        (hm - he).abs() < 1e-3 * he,
        "h_min: map {:.4} µm, exact {:.4} µm",
        hm * 1e6,
        he * 1e6
    );
    let d = by_map
        .eccentricity
        .iter()
        .zip(&exact.eccentricity)
        .map(|(x, y)| (x[0] - y[0]).hypot(x[1] - y[1]))
        .fold(0.0, f64::max);
    assert!(d < 1e-3, "orbits differ by {d:e} in ε");
}
