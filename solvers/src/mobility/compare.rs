//! Cycle metrics of a bearing answer and the deviation of the mobility answer from a reference
//! (the rigorous JFO solution), as in Yu & Sawicki's discussion (\[YuSawicki2002\]: cycle-average
//! eccentricity, minimum film, mean flow and mean power loss, deviations in %).
//!
//! Each answer is a sampled cycle (its own time grid); means are trapezoidal time averages over
//! the sampled span, the minimum film is the smallest sample:
//!
//! ```text
//!   mean(f) = Σ_k (f_k + f_{k+1})/2 · (t_{k+1} − t_k) / (t_last − t_first)
//!   deviation % = 100 · (mobility − reference) / |reference|
//! ```

use super::{MobilityError, OrbitInfo};

/// One sampled cycle of a bearing answer (SI units, all slices of equal length).
#[derive(Debug, Clone, Copy)]
pub struct CycleSeries<'a> {
    /// Sample times (s), increasing.
    pub time: &'a [f64],
    /// |ε|.
    pub eccentricity_ratio: &'a [f64],
    /// h_min (m).
    pub min_film_thickness: &'a [f64],
    /// Oil flow compared (m³/s): side leakage of the film.
    pub flow: &'a [f64],
    /// Power loss (W).
    pub power_loss: &'a [f64],
}

/// Cycle metrics of one answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleMetrics {
    /// Time-averaged |ε|.
    pub mean_eccentricity_ratio: f64,
    /// Smallest h_min over the cycle (m).
    pub min_film_thickness: f64,
    /// Time-averaged flow (m³/s).
    pub mean_flow: f64,
    /// Time-averaged power loss (W).
    pub mean_power_loss: f64,
}

/// The two answers' metrics and the mobility method's deviation in per cent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeviationReport {
    pub reference: CycleMetrics,
    pub mobility: CycleMetrics,
    /// 100 (mobility − reference)/|reference| for each metric.
    pub deviation_percent: CycleMetrics,
}

/// Metrics of one sampled cycle.
pub fn cycle_metrics(series: &CycleSeries<'_>) -> Result<CycleMetrics, MobilityError> {
    let n = series.time.len();
    let bad = |name: &'static str, value: f64| MobilityError::InvalidParameter { name, value };
    if n < 2 {
        return Err(bad("cycle samples", n as f64));
    }
    for (name, col) in [
        ("eccentricity_ratio length", series.eccentricity_ratio),
        ("min_film_thickness length", series.min_film_thickness),
        ("flow length", series.flow),
        ("power_loss length", series.power_loss),
    ] {
        if col.len() != n {
            return Err(bad(name, col.len() as f64));
        }
    }
    for (name, col) in [
        ("time", series.time),
        ("eccentricity_ratio", series.eccentricity_ratio),
        ("min_film_thickness", series.min_film_thickness),
        ("flow", series.flow),
        ("power_loss", series.power_loss),
    ] {
        if let Some((index, v)) = col.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(MobilityError::NonFiniteSample {
                quantity: name,
                index,
                value: *v,
            });
        }
    }
    let span = series.time[n - 1] - series.time[0];
    if series.time.windows(2).any(|w| w[1] <= w[0]) {
        return Err(bad("time (not increasing), span", span));
    }
    let mean = |f: &[f64]| {
        let mut acc = 0.0;
        for k in 1..n {
            acc += 0.5 * (f[k] + f[k - 1]) * (series.time[k] - series.time[k - 1]);
        }
        acc / span
    };
    Ok(CycleMetrics {
        mean_eccentricity_ratio: mean(series.eccentricity_ratio),
        min_film_thickness: series
            .min_film_thickness
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min),
        mean_flow: mean(series.flow),
        mean_power_loss: mean(series.power_loss),
    })
}

/// Deviation of the mobility answer from the reference answer.
pub fn compare_cycles(
    reference: &CycleSeries<'_>,
    mobility: &CycleSeries<'_>,
) -> Result<DeviationReport, MobilityError> {
    let r = cycle_metrics(reference)?;
    let m = cycle_metrics(mobility)?;
    let pct = |name: &'static str, a: f64, b: f64| {
        if b == 0.0 {
            Err(MobilityError::InvalidParameter { name, value: b })
        } else {
            Ok(100.0 * (a - b) / b.abs())
        }
    };
    Ok(DeviationReport {
        reference: r,
        mobility: m,
        deviation_percent: CycleMetrics {
            mean_eccentricity_ratio: pct(
                "reference mean eccentricity ratio",
                m.mean_eccentricity_ratio,
                r.mean_eccentricity_ratio,
            )?,
            min_film_thickness: pct(
                "reference minimum film",
                m.min_film_thickness,
                r.min_film_thickness,
            )?,
            mean_flow: pct("reference mean flow", m.mean_flow, r.mean_flow)?,
            mean_power_loss: pct(
                "reference mean power loss",
                m.mean_power_loss,
                r.mean_power_loss,
            )?,
        },
    })
}

/// Owned columns of an orbit's cycle, ready for [`CycleSeries`].
#[derive(Debug, Clone, PartialEq)]
pub struct OrbitColumns {
    pub time: Vec<f64>,
    pub eccentricity_ratio: Vec<f64>,
    pub min_film_thickness: Vec<f64>,
    pub flow: Vec<f64>,
    pub power_loss: Vec<f64>,
}

impl OrbitColumns {
    /// The columns of a mobility orbit's reported cycle.
    pub fn from_orbit(orbit: &OrbitInfo) -> Self {
        let p = &orbit.performance;
        Self {
            time: orbit.time.clone(),
            eccentricity_ratio: p.iter().map(|q| q.eccentricity_ratio).collect(),
            min_film_thickness: p.iter().map(|q| q.min_film_thickness).collect(),
            flow: p.iter().map(|q| q.side_flow).collect(),
            power_loss: p.iter().map(|q| q.power_loss).collect(),
        }
    }

    /// Borrow as a [`CycleSeries`].
    pub fn series(&self) -> CycleSeries<'_> {
        CycleSeries {
            time: &self.time,
            eccentricity_ratio: &self.eccentricity_ratio,
            min_film_thickness: &self.min_film_thickness,
            flow: &self.flow,
            power_loss: &self.power_loss,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn trapezoidal_means_and_percent_deviations() {
        // Over one period of sin, the mean of a + b sin(2πt) is a; trapezoid on a uniform grid
        // integrates the full period of a trigonometric polynomial exactly (to round-off).
        let n = 65;
        let t: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
        let wave =
            |a: f64, b: f64| -> Vec<f64> { t.iter().map(|x| a + b * (TAU * x).sin()).collect() };
        let (e1, h1, q1, p1) = (
            wave(0.5, 0.2),
            wave(10e-6, 4e-6),
            wave(2e-6, 1e-6),
            wave(40.0, 5.0),
        );
        let (e2, h2, q2, p2) = (
            wave(0.45, 0.2),
            wave(11e-6, 4e-6),
            wave(1.5e-6, 1e-6),
            wave(36.0, 5.0),
        );
        let r = CycleSeries {
            time: &t,
            eccentricity_ratio: &e1,
            min_film_thickness: &h1,
            flow: &q1,
            power_loss: &p1,
        };
        let m = CycleSeries {
            time: &t,
            eccentricity_ratio: &e2,
            min_film_thickness: &h2,
            flow: &q2,
            power_loss: &p2,
        };
        let d = compare_cycles(&r, &m).unwrap();
        assert!((d.reference.mean_eccentricity_ratio - 0.5).abs() < 1e-14);
        // Minimum of 10 + 4 sin(2πt): the sample at t = 3/4 hits it exactly (64 intervals).
        assert!((d.reference.min_film_thickness - 6e-6).abs() < 1e-18);
        assert!((d.deviation_percent.mean_eccentricity_ratio + 10.0).abs() < 1e-10);
        assert!((d.deviation_percent.min_film_thickness - 100.0 * 1e-6 / 6e-6).abs() < 1e-9);
        assert!((d.deviation_percent.mean_flow + 25.0).abs() < 1e-9);
        assert!((d.deviation_percent.mean_power_loss + 10.0).abs() < 1e-10);
    }

    #[test]
    fn ragged_or_non_finite_series_are_rejected() {
        let t = [0.0, 1.0, 2.0];
        let ok = [1.0, 1.0, 1.0];
        let short = [1.0, 1.0];
        let nan = [1.0, f64::NAN, 1.0];
        let ragged = CycleSeries {
            time: &t,
            eccentricity_ratio: &short,
            min_film_thickness: &ok,
            flow: &ok,
            power_loss: &ok,
        };
        assert!(cycle_metrics(&ragged).is_err());
        let bad = CycleSeries {
            time: &t,
            eccentricity_ratio: &ok,
            min_film_thickness: &ok,
            flow: &nan,
            power_loss: &ok,
        };
        assert!(matches!(
            cycle_metrics(&bad),
            Err(MobilityError::NonFiniteSample {
                quantity: "flow",
                index: 1,
                ..
            })
        ));
    }
}
