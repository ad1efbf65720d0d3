//! The finite-length mobility map used in a real orbit: a map tabulated from the short-bearing
//! squeeze film (the provider that a Reynolds-based film will replace) must reproduce the orbit
//! of the exact short-bearing mobility on the Flores et al. example (\[Flores2006\] §5).
//!
//! The map is within ~1e-4 of the exact mobility (unit test in `solvers/src/mobility/map.rs`).
//! Near the load line M^ζ ∝ (1 − ζ)^{5/2}, so a relative mobility error δ moves the film 1 − ζ by
//! about (2/5) δ: the cycle-minimum film of the two orbits must agree to 1e-3 relative, and the
//! orbits themselves to 1e-3 in ε (the cycle-to-cycle periodicity tolerance is 1e-6).

use jbearing_solvers::mobility::{
    ExactShortBearing, MobilityMap, MobilityMapParams, ShortBearingSqueeze, solve_orbit,
};
use jbearing_validation::flores2006;

#[test]
fn short_bearing_map_reproduces_the_exact_short_bearing_orbit() {
    let (bearing, load, p) = (
        flores2006::bearing(),
        flores2006::load(),
        flores2006::orbit_params(),
    );

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
