//! What a case will cost before it runs: its memory and time estimated from the grid, the time
//! steps, the cycles and the outputs. `check`, `run` and `batch` refuse a case whose estimate is
//! above the hard limits ([`Limits`], raised with `--max-memory-gb` / `--max-hours`) and warn
//! above the soft ones ([`SOFT_MEMORY_BYTES`], [`SOFT_SECONDS`]).
//!
//! The estimates are models fitted to measurements (release build, AMD EPYC, 2 cores,
//! 2026-11-24, peak resident memory by `/usr/bin/time -f %M`, the compressor main bearing):
//!
//! ```text
//!   grid        nodes n   steps   peak memory   wall time
//!   120 × 31     3 720      72       22 MB        2.0 s
//!   240 × 61    14 640      72       43 MB       18.3 s
//!   480 × 121   58 080      72      134 MB      314 s
//!   mobility only, 200 000 samples per cycle:       79 MB        0.9 s
//! ```
//!
//! memory ≈ 20 MB + n (1 kB + 32 B · snapshots) + 1 kB · steps per cycle
//!          + 400 B · samples per cycle;
//! time   ≈ steps · 6 ms · (n / 3720)^2 (rigorous Reynolds film; the measured exponent is
//!          1.6–2.0) + steps · 20 µs (short-bearing film) + samples · cycles · 20 µs (mobility)
//!          + 1 s (the finite-length mobility map: `mobility/map_build_reynolds`, 1.19 s on
//!          the same machine, 2026-11-28; 10 s before that day's faster map build),
//! where steps = steps per cycle × (max cycles + 1 run-in); with a heat balance
//! (`[lubricant.heat_balance]`) the rigorous time × 3 and the mobility orbits × 5 (solves a
//! balance typically takes: 2–3 rigorous from the mobility method's start, 3–5 mobility; the
//! map is built once). Memory is estimated within a factor
//! of about 1.5; time within a factor of about 5 (it depends on the load and the machine), which
//! is enough to catch a case that would take days or a terabyte before it starts.

use crate::case::{Case, CaseWarning, MobilityModelChoice, RigorousFilm, WarningKind};

/// Warn when a case is estimated to need more memory than this (1 GiB).
pub const SOFT_MEMORY_BYTES: f64 = 1024.0 * 1024.0 * 1024.0;
/// Warn when a case is estimated to take longer than this (1 hour).
pub const SOFT_SECONDS: f64 = 3600.0;

/// Hard limits: a case estimated above either is refused before the solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest estimated memory of one case (bytes); default 8 GiB.
    pub max_memory_bytes: f64,
    /// Largest estimated time of one case (s); default 24 hours.
    pub max_seconds: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_memory_bytes: 8.0 * SOFT_MEMORY_BYTES,
            max_seconds: 24.0 * 3600.0,
        }
    }
}

impl Limits {
    /// Limits from the command line's `--max-memory-gb` (GiB) and `--max-hours`.
    pub fn from_gib_hours(memory_gib: f64, hours: f64) -> Self {
        Self {
            max_memory_bytes: memory_gib * SOFT_MEMORY_BYTES,
            max_seconds: hours * 3600.0,
        }
    }
}

/// A case's estimated cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Peak memory (bytes).
    pub memory_bytes: f64,
    /// Wall time on one core (s).
    pub seconds: f64,
}

/// A case whose estimate is above a hard limit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BudgetError {
    /// Too much memory.
    #[error(
        "{file}: case '{case}' would need about {} of memory ({why}), above the limit of {}: \
         reduce it, or raise the limit with --max-memory-gb",
        human_bytes(*estimate), human_bytes(*limit)
    )]
    Memory {
        /// The case file.
        file: String,
        /// Case name.
        case: String,
        /// What makes it large.
        why: String,
        /// Estimated bytes.
        estimate: f64,
        /// The limit (bytes).
        limit: f64,
    },
    /// Too much time.
    #[error(
        "{file}: case '{case}' would take about {} ({why}), above the limit of {}: reduce it, \
         or raise the limit with --max-hours",
        human_seconds(*estimate), human_seconds(*limit)
    )]
    Time {
        /// The case file.
        file: String,
        /// Case name.
        case: String,
        /// What makes it long.
        why: String,
        /// Estimated seconds.
        estimate: f64,
        /// The limit (s).
        limit: f64,
    },
}

/// The estimated memory and time of `case` (see the module docs for the model).
pub fn estimate(case: &Case) -> Estimate {
    let nodes = case.n_theta as f64 * case.n_z as f64;
    let steps_per_cycle = case.solver.time_steps_per_cycle as f64;
    let cycles = case.solver.max_cycles as f64 + 1.0;
    let samples = case.output.samples_per_cycle as f64;
    // Solves per method of a heat balance (module docs).
    let (rigorous_solves, mobility_solves) = if case.heat_balance.is_some() {
        (3.0, 5.0)
    } else {
        (1.0, 1.0)
    };
    let mut memory = 20e6;
    let mut seconds = 0.0;
    if case.methods.rigorous {
        memory += 1e3 * steps_per_cycle;
        match case.solver.rigorous_film {
            RigorousFilm::Reynolds => {
                let snapshots = case.output.field_snapshots as f64;
                memory += nodes * (1e3 + 32.0 * snapshots);
                seconds +=
                    rigorous_solves * steps_per_cycle * cycles * 6e-3 * (nodes / 3720.0).powi(2);
            }
            RigorousFilm::ShortBearing => {
                seconds += rigorous_solves * steps_per_cycle * cycles * 20e-6
            }
        }
    }
    if case.methods.mobility {
        memory += 400.0 * samples;
        // The mobility method runs up to 5 × max cycles (at least 10).
        seconds += mobility_solves * samples * (5.0 * case.solver.max_cycles.max(2) as f64) * 20e-6;
        if case.solver.mobility_model == MobilityModelChoice::Map {
            seconds += 1.0;
        }
    }
    Estimate {
        memory_bytes: memory,
        seconds,
    }
}

/// What dominates a case's cost, for the messages.
fn cost_drivers(case: &Case) -> String {
    let mut parts = Vec::new();
    if case.methods.rigorous {
        if case.solver.rigorous_film == RigorousFilm::Reynolds {
            parts.push(format!("grid {} × {}", case.n_theta, case.n_z));
            parts.push(format!("{} field snapshots", case.output.field_snapshots));
        }
        parts.push(format!(
            "{} time steps per cycle × up to {} cycles",
            case.solver.time_steps_per_cycle, case.solver.max_cycles
        ));
    }
    if case.methods.mobility {
        parts.push(format!(
            "{} mobility samples per cycle",
            case.output.samples_per_cycle
        ));
    }
    if case.heat_balance.is_some() {
        parts.push("a heat balance (about 3 rigorous and 5 mobility solves)".into());
    }
    parts.join(", ")
}

/// Check `case` against `limits`: an error above a hard limit, warnings above the soft ones.
pub fn check(case: &Case, limits: &Limits) -> Result<Vec<CaseWarning>, BudgetError> {
    let e = estimate(case);
    let file = case
        .path
        .as_ref()
        .map_or_else(|| case.name.clone(), |p| p.display().to_string());
    let why = cost_drivers(case);
    if e.memory_bytes > limits.max_memory_bytes {
        return Err(BudgetError::Memory {
            file,
            case: case.name.clone(),
            why,
            estimate: e.memory_bytes,
            limit: limits.max_memory_bytes,
        });
    }
    if e.seconds > limits.max_seconds {
        return Err(BudgetError::Time {
            file,
            case: case.name.clone(),
            why,
            estimate: e.seconds,
            limit: limits.max_seconds,
        });
    }
    let mut warnings = Vec::new();
    let warn = |message: String| CaseWarning {
        file: case.path.clone().unwrap_or_default(),
        line: 1,
        key: "(case)".into(),
        kind: WarningKind::Budget,
        message,
    };
    if e.memory_bytes > SOFT_MEMORY_BYTES {
        warnings.push(warn(format!(
            "estimated memory {} ({why}) is above {}",
            human_bytes(e.memory_bytes),
            human_bytes(SOFT_MEMORY_BYTES)
        )));
    }
    if e.seconds > SOFT_SECONDS {
        warnings.push(warn(format!(
            "estimated time {} ({why}) is above {}",
            human_seconds(e.seconds),
            human_seconds(SOFT_SECONDS)
        )));
    }
    Ok(warnings)
}

/// Bytes as "12 MB", "3.4 GB" (decimal units, two significant figures or more).
pub fn human_bytes(b: f64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB"];
    let mut v = b;
    let mut u = 0;
    while v >= 1000.0 && u + 1 < units.len() {
        v /= 1000.0;
        u += 1;
    }
    if v < 10.0 {
        format!("{v:.1} {}", units[u])
    } else {
        format!("{v:.0} {}", units[u])
    }
}

/// Seconds as "40 s", "12 min", "3.5 h", "21 days".
pub fn human_seconds(s: f64) -> String {
    if s < 90.0 {
        format!("{s:.0} s")
    } else if s < 5400.0 {
        format!("{:.0} min", s / 60.0)
    } else if s < 48.0 * 3600.0 {
        format!("{:.1} h", s / 3600.0)
    } else if s < 3650.0 * 86400.0 {
        format!("{:.0} days", s / 86400.0)
    } else {
        format!("{:.1e} years", s / (365.25 * 86400.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn human_units() {
        assert_eq!(human_bytes(22e6), "22 MB");
        assert_eq!(human_bytes(8.0 * 1024.0 * 1024.0 * 1024.0), "8.6 GB");
        assert_eq!(human_seconds(40.0), "40 s");
        assert_eq!(human_seconds(600.0), "10 min");
        assert_eq!(human_seconds(86400.0), "24.0 h");
        assert_eq!(human_seconds(30.0 * 86400.0), "30 days");
    }
}
