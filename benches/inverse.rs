//! Inverse-solver benches: one load cycle of a bearing the size of the compressor main bearing
//! (docs/conventions.md §7: L = 18.288 mm, R = 27.43 mm, c = 48.9 µm, 1800 rpm; μ = 0.02 Pa·s assumed)
//! under a synthetic compressor-like load (a 4 kN pulse once per turn on an 0.8 kN base, plus a
//! 0.6 kN second-order side load), at the default step of 1° crank.
//!
//! - `inverse/one_cycle_short_bearing`: run-in of 8 steps + one 360-step cycle with the analytic
//!   short-bearing film (default time scheme, BDF2): the cost of the Newton machinery alone.
//! - `inverse/periodic_short_bearing`: the whole solve to a periodic orbit (default tolerances).
use criterion::Criterion;
use jbearing_solvers::closed_form::{ClosedFormModel, ClosedFormParams};
use jbearing_solvers::inverse::{
    ClosedFormFilm, InverseParams, NoObserver, TimeScheme, solve_inverse,
};
use jbearing_solvers::load::{FnLoad, OperatingHistory};
use std::f64::consts::TAU;
use std::hint::black_box;

/// Crank speed (rad/s).
pub const OMEGA: f64 = 1800.0 * TAU / 60.0;

/// The synthetic main-bearing load (N, bearing frame) at time t.
pub fn main_bearing_load(t: f64) -> [f64; 2] {
    let a = OMEGA * t;
    let pulse = 4000.0 * (0.5 * (1.0 - a.cos())).powi(4);
    [600.0 * (2.0 * a).sin(), -800.0 - pulse]
}

/// The bench's load history: the synthetic load at constant speed, no feed.
type MainBearingHistory = OperatingHistory<FnLoad<fn(f64) -> [f64; 2]>>;

fn history() -> MainBearingHistory {
    OperatingHistory {
        load: FnLoad {
            period: TAU / OMEGA,
            load: main_bearing_load as fn(f64) -> [f64; 2],
        },
        journal_speed: OMEGA,
        bearing_speed: 0.0,
        feed_pressures: vec![],
    }
}

fn short_film() -> ClosedFormFilm {
    let params = ClosedFormParams {
        radius: 27.43e-3,
        length: 18.288e-3,
        radial_clearance: 48.9e-6,
        viscosity: 0.02,
    };
    ClosedFormFilm::new(
        ClosedFormModel::ShortGumbelMovingFilm,
        params,
        TimeScheme::default(),
    )
    .unwrap()
}

pub fn bench(c: &mut Criterion) {
    let load = history();
    let mut g = c.benchmark_group("inverse");
    let one = InverseParams {
        max_cycles: 1,
        run_in_steps: 8,
        ..Default::default()
    };
    g.bench_function("one_cycle_short_bearing", |b| {
        b.iter(|| {
            let mut f = short_film();
            black_box(solve_inverse(&one, &load, &mut f, &mut NoObserver).unwrap())
        })
    });
    let full = InverseParams::default();
    g.bench_function("periodic_short_bearing", |b| {
        b.iter(|| {
            let mut f = short_film();
            black_box(solve_inverse(&full, &load, &mut f, &mut NoObserver).unwrap())
        })
    });
    g.finish();
}
