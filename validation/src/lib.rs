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

/// The example of Flores et al. (2006), seed `000_…` §5 and Table 1: L = 25.4 mm, D = 63.5 mm,
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
