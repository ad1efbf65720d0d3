//! Validation of jbearing: reference data with provenance (`data/reference/`) and the loaders
//! the validation tests in `tests/` use.

use std::path::Path;

/// Reads a numeric CSV from `data/reference/` (header line skipped): one `Vec<f64>` per row.
/// Panics with the file and row on a malformed entry (tests only).
pub fn read_reference_csv(name: &str) -> Vec<Vec<f64>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/reference")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .enumerate()
        .map(|(row, l)| {
            l.split(',')
                .map(|v| {
                    v.trim()
                        .parse::<f64>()
                        .unwrap_or_else(|e| panic!("{name} row {row}: {v:?}: {e}"))
                })
                .collect()
        })
        .collect()
}

/// The example of Flores et al. \[Flores2006\] (§5 and Table 1): L = 25.4 mm, D = 63.5 mm,
/// c = 35.56 µm (the table's "mm" is a unit slip), μ = 4.16 cP, 2000 rpm, fixed bearing, the
/// Bouldin & Berker engine load of `data/reference/flores2006_load.csv` (720° cycle, along −Y),
/// start ε⁰ = 0.1 at φ⁰ = 1.5 rad.
pub mod flores2006 {
    use jbearing_solvers::mobility::{
        LoadInterpolation, MobilityParams, OrbitParams, TabulatedLoad,
    };
    use std::f64::consts::TAU;

    /// Crank (= journal) speed, rad/s.
    pub fn omega() -> f64 {
        2000.0 * TAU / 60.0
    }

    /// The bearing of Table 1.
    pub fn bearing() -> MobilityParams {
        MobilityParams {
            radius: 0.5 * 63.5e-3,
            length: 25.4e-3,
            radial_clearance: 35.56e-6,
            viscosity: 4.16e-3,
            omega_journal: omega(),
            omega_bearing: 0.0,
        }
    }

    /// The load of Fig. 6 (kN in the file), linear between the digitised points.
    pub fn load() -> TabulatedLoad {
        let rows = super::read_reference_csv("flores2006_load.csv");
        let angle: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        let force: Vec<f64> = rows.iter().map(|r| r[1] * 1e3).collect();
        TabulatedLoad::unidirectional(
            angle,
            &force,
            [0.0, -1.0],
            720.0,
            omega(),
            LoadInterpolation::Linear,
        )
        .expect("flores2006_load.csv is a valid load table")
    }

    /// Orbit parameters with the paper's start.
    pub fn orbit_params() -> OrbitParams {
        let mut p = OrbitParams::new(bearing());
        p.initial_eccentricity = [0.1 * 1.5f64.sin(), -0.1 * 1.5f64.cos()];
        p
    }
}

/// The compressor main bearing of Yu & Sawicki \[YuSawicki2002\] Table II (docs/conventions.md §7) as used by the
/// inverse-solver tests and the inverse timing report: L = 18.288 mm, R = 27.43 mm,
/// c = 48.9 µm, a partial groove 24.9 × 3.81 mm at θ = 90° (top, unloaded side) fed at
/// 0.2068 MPa, 1800 rpm; μ = 0.02 Pa·s assumed. The synthetic compressor-like load: a 4 kN
/// pulse once per turn on 0.8 kN, plus a 0.6 kN second-order side load.
pub mod compressor_main {
    use jbearing_solvers::reynolds::{GridParams, Groove, ReynoldsParams, TimeScheme};
    use std::f64::consts::{PI, TAU};

    /// Crank (= journal) speed, rad/s.
    pub const OMEGA: f64 = 1800.0 * TAU / 60.0;
    /// Groove feed pressure (gauge), Pa.
    pub const FEED: f64 = 0.2068e6;

    /// The Reynolds-solver parameters on an n_θ × n_z grid with the given time scheme.
    pub fn reynolds_params(scheme: TimeScheme, n_theta: usize, n_z: usize) -> ReynoldsParams {
        let mut p = ReynoldsParams::plain(27.43e-3, 18.288e-3, 48.9e-6, 0.02);
        p.grid = GridParams { n_theta, n_z };
        p.time_scheme = scheme;
        p.grooves = vec![Groove {
            center_angle: 0.5 * PI,
            center_z: 0.0,
            angular_width: 24.9e-3 / 27.43e-3,
            axial_width: 3.81e-3,
            cutoff_film_fraction: 0.01,
        }];
        p
    }

    /// The synthetic load (N, bearing frame) at time t.
    pub fn pulse_load(t: f64) -> [f64; 2] {
        let a = OMEGA * t;
        [
            600.0 * (2.0 * a).sin(),
            -800.0 - 4000.0 * (0.5 * (1.0 - a.cos())).powi(4),
        ]
    }
}
