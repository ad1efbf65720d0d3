//! Mobility-method benches: the Flores et al. example (\[Flores2006\], L/D = 0.4, 720° load cycle).
//!
//! - `mobility/flores_cycle_booker`: one 720° load cycle (721 samples with their performance)
//!   from the start of the periodic orbit, Booker's closed-form mobility: the "mobility cycle".
//! - `mobility/flores_periodic_booker`: the whole periodic solve (run-in from ε⁰ = 0.1 until the
//!   cycle-to-cycle change is < 1e-6; 4 load cycles) with Booker's closed-form mobility,
//!   including the 721 performance samples (h_min, p_max, flow, power) of the reported cycle.
//! - `mobility/flores_periodic_exact`: the same with the exact short-bearing mobility (a root
//!   search per right-hand side).
//! - `mobility/flores_periodic_map`: the same with the tabulated mobility map.
//! - `mobility/map_build_short_bearing`: building the default 41 × 37 map from the short-bearing
//!   squeeze film (the once-per-L/D cost, before a Reynolds-based film replaces it).
//! - `mobility/map_build_reynolds`: building the application's map (`mobility_model = "map"`:
//!   27 × 19 nodes up to ε = 0.99) from the finite-difference Reynolds-condition squeeze film
//!   for the compressor main bearing's L/D = 1/3 — the once-per-L/D cost a case with the map
//!   pays before its mobility orbit.
use criterion::Criterion;
use jbearing_solvers::mobility::{
    BookerShortBearing, ExactShortBearing, LoadInterpolation, MobilityMap, MobilityMapParams,
    MobilityParams, OrbitParams, ShortBearingSqueeze, TabulatedLoad, solve_orbit,
};
use jbearing_solvers::squeeze_film::{ReynoldsSqueezeFilm, SqueezeFilmParams};
use std::f64::consts::TAU;
use std::hint::black_box;

fn flores() -> (OrbitParams, TabulatedLoad) {
    let omega = 2000.0 * TAU / 60.0;
    let bearing = MobilityParams {
        radius: 0.5 * 63.5e-3,
        length: 25.4e-3,
        radial_clearance: 35.56e-6,
        viscosity: 4.16e-3,
        omega_journal: omega,
        omega_bearing: 0.0,
    };
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/validation/data/reference/flores2006_load.csv"
    );
    let text = std::fs::read_to_string(path).expect("Flores load table");
    let (mut a, mut f) = (Vec::new(), Vec::new());
    for line in text.lines().skip(1) {
        let mut c = line.split(',');
        a.push(c.next().unwrap().trim().parse::<f64>().unwrap());
        f.push(c.next().unwrap().trim().parse::<f64>().unwrap() * 1e3);
    }
    let load =
        TabulatedLoad::unidirectional(a, &f, [0.0, -1.0], 720.0, omega, LoadInterpolation::Linear)
            .unwrap();
    let mut p = OrbitParams::new(bearing);
    p.initial_eccentricity = [0.1 * 1.5f64.sin(), -0.1 * 1.5f64.cos()];
    (p, load)
}

pub fn bench(c: &mut Criterion) {
    let (params, load) = flores();
    let mut g = c.benchmark_group("mobility");
    let booker = BookerShortBearing {
        length_to_diameter: 0.4,
    };
    // Start of the periodic orbit, then exactly one cycle.
    let periodic = solve_orbit(&params, &booker, &load).unwrap();
    let mut one = params;
    one.initial_eccentricity = periodic.eccentricity[0];
    one.periodicity_tolerance = f64::INFINITY;
    one.max_cycles = 1;
    g.bench_function("flores_cycle_booker", |b| {
        b.iter(|| solve_orbit(black_box(&one), &booker, &load).unwrap())
    });
    g.bench_function("flores_periodic_booker", |b| {
        b.iter(|| solve_orbit(black_box(&params), &booker, &load).unwrap())
    });
    let exact = ExactShortBearing {
        length_to_diameter: 0.4,
    };
    g.bench_function("flores_periodic_exact", |b| {
        b.iter(|| solve_orbit(black_box(&params), &exact, &load).unwrap())
    });
    let film = ShortBearingSqueeze {
        length_to_diameter: 0.4,
    };
    let map = MobilityMap::build(&film, &MobilityMapParams::default()).unwrap();
    g.bench_function("flores_periodic_map", |b| {
        b.iter(|| solve_orbit(black_box(&params), &map, &load).unwrap())
    });
    g.bench_function("map_build_short_bearing", |b| {
        b.iter(|| MobilityMap::build(black_box(&film), &MobilityMapParams::default()).unwrap())
    });
    g.finish();
    // About a second per build: ten samples.
    let mut g = c.benchmark_group("mobility");
    g.sample_size(10);
    let ld = 0.018288 / (2.0 * 0.02743);
    let reynolds = ReynoldsSqueezeFilm::new(SqueezeFilmParams::new(ld)).unwrap();
    let app_map = MobilityMapParams::for_squeeze_film_solver();
    g.bench_function("map_build_reynolds", |b| {
        b.iter(|| MobilityMap::build(black_box(&reynolds), &app_map).unwrap())
    });
    g.finish();
}
