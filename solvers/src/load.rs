//! Load histories: periodic loads on the journal and the operating history around them.
//!
//! Shared by the mobility method ([`crate::mobility`]) and the inverse solver
//! ([`crate::inverse`]).
//!
//! The load is the force the machine applies to the journal (docs/conventions.md §1), in the bearing
//! frame, in newtons, periodic in time with period τ. Two traits:
//!
//! * [`PeriodicLoad`]: W(t) alone (what the mobility orbit needs).
//! * [`LoadHistory`]: everything the inverse solver needs over one cycle — W(t), the journal and
//!   bearing speeds ω_j(t), ω_b(t) (rad/s, fixed frame, counter-clockwise positive) and the feed
//!   pressures p_feed(t) of the grooves (Pa, gauge). Cases synthesise it (a slider-crank
//!   compressor, a rotating test load, …); [`OperatingHistory`] wraps any [`PeriodicLoad`] with
//!   constant speeds and feed pressures.
//!
//! A table is given over crank angle φ_c (degrees) with a cycle length (720° for a four-stroke
//! engine, 360° for a compressor) and the crank speed Ω (rad/s): t = φ_c / Ω (φ_c in radians).
//! Between the points it is interpolated periodically:
//!
//! ```text
//!   φ_c:  a_0   a_1   …   a_{n-1}   a_0 + cycle
//!   F:    F_0   F_1   …   F_{n-1}   F_0            (the table wraps onto itself)
//! ```
//!
//! * [`LoadInterpolation::Linear`]: piecewise linear (no overshoot; the default).
//! * [`LoadInterpolation::CatmullRom`]: periodic cubic Hermite with centred-difference slopes
//!   (C¹, smoother for the adaptive integrator, may overshoot slightly between sparse points).
//!
//! Synthetic loads for tests and studies: [`ConstantLoad`] (a fixed vector, any period) and
//! [`RotatingLoad`] (a vector of fixed magnitude turning at a given angular speed, e.g. at half
//! the journal speed — the classic load that a plain bearing cannot carry, since ω̄ − ω_W = 0
//! leaves no wedge in the frame of the load).

use thiserror::Error;

/// A periodic load history.
pub trait PeriodicLoad {
    /// Period τ (s).
    fn period(&self) -> f64;
    /// Force on the journal in the bearing frame (N) at time t (s); periodic in t.
    fn load(&self, t: f64) -> [f64; 2];
    /// Crank angle (degrees) at time t, for reports and error messages. Default: 360° t/τ.
    fn crank_angle_deg(&self, t: f64) -> f64 {
        360.0 * t / self.period()
    }
}

/// Interpolation of a load table between its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LoadInterpolation {
    /// Piecewise linear.
    #[default]
    Linear,
    /// Periodic cubic Hermite with centred-difference (Catmull–Rom) slopes.
    CatmullRom,
}

/// Problems with a load table.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LoadTableError {
    #[error("load table needs at least 2 points, has {points}")]
    TooFewPoints { points: usize },
    #[error("load table columns differ in length: {angles} angles, {forces} forces")]
    LengthMismatch { angles: usize, forces: usize },
    #[error("load table row {row}: non-finite value")]
    NonFinite { row: usize },
    #[error("load table row {row}: crank angle {angle}° not increasing")]
    NotIncreasing { row: usize, angle: f64 },
    #[error("load table spans {span}° which does not fit in one cycle of {cycle}°")]
    SpanExceedsCycle { span: f64, cycle: f64 },
    #[error("invalid {name} = {value}")]
    InvalidParameter { name: &'static str, value: f64 },
}

/// A load given as a table over crank angle, periodic over `cycle_deg`.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedLoad {
    angles_deg: Vec<f64>,
    fx: Vec<f64>,
    fy: Vec<f64>,
    cycle_deg: f64,
    crank_speed: f64,
    interpolation: LoadInterpolation,
}

impl TabulatedLoad {
    /// A table of force vectors (N, bearing frame) at increasing crank angles (deg) spanning less
    /// than one cycle; `crank_speed` Ω in rad/s (> 0).
    ///
    /// ```
    /// use jbearing_solvers::load::{LoadInterpolation, PeriodicLoad, TabulatedLoad};
    ///
    /// // Four points over a 360° cycle at 1500 rpm, wrapped periodically.
    /// let speed = 1500.0 * std::f64::consts::TAU / 60.0;
    /// let table = TabulatedLoad::new(
    ///     vec![0.0, 90.0, 180.0, 270.0],
    ///     vec![[0.0, -1000.0], [500.0, 0.0], [0.0, 1000.0], [-500.0, 0.0]],
    ///     360.0, speed, LoadInterpolation::Linear,
    /// )?;
    /// assert_eq!(table.load_at_crank_angle(45.0), [250.0, -500.0]);
    /// assert_eq!(table.load_at_crank_angle(315.0), [-250.0, -500.0]); // between 270° and 360° = 0°
    /// assert!((table.period() - 60.0 / 1500.0).abs() < 1e-15);
    /// # Ok::<(), jbearing_solvers::load::LoadTableError>(())
    /// ```
    pub fn new(
        angles_deg: Vec<f64>,
        forces: Vec<[f64; 2]>,
        cycle_deg: f64,
        crank_speed: f64,
        interpolation: LoadInterpolation,
    ) -> Result<Self, LoadTableError> {
        if angles_deg.len() != forces.len() {
            return Err(LoadTableError::LengthMismatch {
                angles: angles_deg.len(),
                forces: forces.len(),
            });
        }
        if angles_deg.len() < 2 {
            return Err(LoadTableError::TooFewPoints {
                points: angles_deg.len(),
            });
        }
        if !(cycle_deg.is_finite() && cycle_deg > 0.0) {
            return Err(LoadTableError::InvalidParameter {
                name: "cycle_deg",
                value: cycle_deg,
            });
        }
        if !(crank_speed.is_finite() && crank_speed > 0.0) {
            return Err(LoadTableError::InvalidParameter {
                name: "crank_speed",
                value: crank_speed,
            });
        }
        for (row, (a, f)) in angles_deg.iter().zip(&forces).enumerate() {
            if !(a.is_finite() && f[0].is_finite() && f[1].is_finite()) {
                return Err(LoadTableError::NonFinite { row });
            }
            if row > 0 && *a <= angles_deg[row - 1] {
                return Err(LoadTableError::NotIncreasing { row, angle: *a });
            }
        }
        let span = angles_deg[angles_deg.len() - 1] - angles_deg[0];
        if span >= cycle_deg {
            return Err(LoadTableError::SpanExceedsCycle {
                span,
                cycle: cycle_deg,
            });
        }
        Ok(Self {
            fx: forces.iter().map(|f| f[0]).collect(),
            fy: forces.iter().map(|f| f[1]).collect(),
            angles_deg,
            cycle_deg,
            crank_speed,
            interpolation,
        })
    }

    /// A unidirectional load: signed magnitudes (N) along the fixed unit `direction` (a positive
    /// value pushes the journal along `direction`).
    pub fn unidirectional(
        angles_deg: Vec<f64>,
        magnitudes: &[f64],
        direction: [f64; 2],
        cycle_deg: f64,
        crank_speed: f64,
        interpolation: LoadInterpolation,
    ) -> Result<Self, LoadTableError> {
        let norm = direction[0].hypot(direction[1]);
        if !(norm.is_finite() && norm > 0.0) {
            return Err(LoadTableError::InvalidParameter {
                name: "direction length",
                value: norm,
            });
        }
        let d = [direction[0] / norm, direction[1] / norm];
        let forces = magnitudes.iter().map(|m| [m * d[0], m * d[1]]).collect();
        Self::new(angles_deg, forces, cycle_deg, crank_speed, interpolation)
    }

    /// Load at crank angle φ_c (deg).
    pub fn load_at_crank_angle(&self, angle_deg: f64) -> [f64; 2] {
        let n = self.angles_deg.len();
        let a0 = self.angles_deg[0];
        let cyc = self.cycle_deg;
        let x = a0 + (angle_deg - a0).rem_euclid(cyc);
        // Segment i: [a_i, a_{i+1}] with a_n = a_0 + cycle (wrap).
        let knot = |k: isize| -> f64 {
            let m = k.rem_euclid(n as isize) as usize;
            let wraps = k.div_euclid(n as isize) as f64;
            self.angles_deg[m] + wraps * cyc
        };
        let i = match self.angles_deg.partition_point(|&a| a <= x) {
            0 => n - 1, // cannot happen (x ≥ a0) but keep the index valid
            p => p - 1,
        } as isize;
        let (xa, xb) = (knot(i), knot(i + 1));
        let h = xb - xa;
        let t = ((x - xa) / h).clamp(0.0, 1.0);
        let val = |col: &[f64], k: isize| col[k.rem_euclid(n as isize) as usize];
        let interp = |col: &[f64]| -> f64 {
            let (ya, yb) = (val(col, i), val(col, i + 1));
            match self.interpolation {
                LoadInterpolation::Linear => ya + t * (yb - ya),
                LoadInterpolation::CatmullRom => {
                    // Slopes dy/dx by centred differences over the neighbouring knots.
                    let ma = (yb - val(col, i - 1)) / (xb - knot(i - 1));
                    let mb = (val(col, i + 2) - ya) / (knot(i + 2) - xa);
                    let t2 = t * t;
                    let t3 = t2 * t;
                    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
                    let h10 = t3 - 2.0 * t2 + t;
                    let h01 = -2.0 * t3 + 3.0 * t2;
                    let h11 = t3 - t2;
                    h00 * ya + h10 * h * ma + h01 * yb + h11 * h * mb
                }
            }
        };
        [interp(&self.fx), interp(&self.fy)]
    }

    /// Cycle length in crank degrees.
    pub fn cycle_deg(&self) -> f64 {
        self.cycle_deg
    }

    /// Crank speed Ω (rad/s).
    pub fn crank_speed(&self) -> f64 {
        self.crank_speed
    }
}

impl PeriodicLoad for TabulatedLoad {
    fn period(&self) -> f64 {
        self.cycle_deg.to_radians() / self.crank_speed
    }

    fn load(&self, t: f64) -> [f64; 2] {
        self.load_at_crank_angle(self.crank_angle_deg(t))
    }

    fn crank_angle_deg(&self, t: f64) -> f64 {
        (self.crank_speed * t).to_degrees()
    }
}

/// A constant load vector, treated as periodic with an arbitrary period (one crank turn, say).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantLoad {
    /// Force on the journal (N, bearing frame).
    pub load: [f64; 2],
    /// Period τ (s) used to cut the run into cycles.
    pub period: f64,
}

impl PeriodicLoad for ConstantLoad {
    fn period(&self) -> f64 {
        self.period
    }
    fn load(&self, _t: f64) -> [f64; 2] {
        self.load
    }
}

/// A load of constant magnitude turning at `angular_speed` (rad/s, counter-clockwise positive)
/// in the bearing frame: W(t) = |W| (cos(ω_W t + α₀), sin(ω_W t + α₀)). Period 2π/|ω_W|.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotatingLoad {
    /// |W| (N).
    pub magnitude: f64,
    /// ω_W (rad/s), non-zero.
    pub angular_speed: f64,
    /// α₀ (rad): direction at t = 0.
    pub phase: f64,
}

impl PeriodicLoad for RotatingLoad {
    fn period(&self) -> f64 {
        std::f64::consts::TAU / self.angular_speed.abs()
    }
    fn load(&self, t: f64) -> [f64; 2] {
        let a = self.angular_speed * t + self.phase;
        [self.magnitude * a.cos(), self.magnitude * a.sin()]
    }
}

/// A periodic load given by a closure W(t) with period τ (for synthesised histories).
#[derive(Clone)]
pub struct FnLoad<F: Fn(f64) -> [f64; 2]> {
    /// Period τ (s).
    pub period: f64,
    /// W(t) (N, bearing frame).
    pub load: F,
}

impl<F: Fn(f64) -> [f64; 2]> PeriodicLoad for FnLoad<F> {
    fn period(&self) -> f64 {
        self.period
    }
    fn load(&self, t: f64) -> [f64; 2] {
        (self.load)(t)
    }
}

/// Everything the inverse solver needs over one load cycle: load, speeds, feed pressures.
///
/// All functions are periodic in t with period τ = [`LoadHistory::period`].
pub trait LoadHistory {
    /// Period τ (s) of one load cycle.
    fn period(&self) -> f64;
    /// Force the machine applies to the journal, bearing frame (N).
    fn load(&self, t: f64) -> [f64; 2];
    /// Journal angular speed ω_j (rad/s, fixed frame).
    fn journal_speed(&self, t: f64) -> f64;
    /// Bearing (sleeve) angular speed ω_b (rad/s, fixed frame); 0 for a main bearing.
    fn bearing_speed(&self, _t: f64) -> f64 {
        0.0
    }
    /// Feed pressure of each groove (Pa, gauge), in the film model's groove order.
    fn feed_pressures(&self, _t: f64) -> Vec<f64> {
        Vec::new()
    }
    /// Crank angle (deg) at time t, for reports and error messages. Default 360° t/τ.
    fn crank_angle_deg(&self, t: f64) -> f64 {
        360.0 * t / self.period()
    }
    /// Crank angle covered by one cycle (deg): 360 for a compressor, 720 for a four-stroke.
    fn cycle_deg(&self) -> f64 {
        self.crank_angle_deg(self.period()) - self.crank_angle_deg(0.0)
    }
}

/// A [`PeriodicLoad`] with constant speeds and constant feed pressures.
#[derive(Debug, Clone, PartialEq)]
pub struct OperatingHistory<L> {
    /// The load W(t).
    pub load: L,
    /// ω_j (rad/s).
    pub journal_speed: f64,
    /// ω_b (rad/s).
    pub bearing_speed: f64,
    /// p_feed of each groove (Pa, gauge).
    pub feed_pressures: Vec<f64>,
}

impl<L: PeriodicLoad> LoadHistory for OperatingHistory<L> {
    fn period(&self) -> f64 {
        self.load.period()
    }
    fn load(&self, t: f64) -> [f64; 2] {
        self.load.load(t)
    }
    fn journal_speed(&self, _t: f64) -> f64 {
        self.journal_speed
    }
    fn bearing_speed(&self, _t: f64) -> f64 {
        self.bearing_speed
    }
    fn feed_pressures(&self, _t: f64) -> Vec<f64> {
        self.feed_pressures.clone()
    }
    fn crank_angle_deg(&self, t: f64) -> f64 {
        self.load.crank_angle_deg(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_table_hits_its_points_and_wraps() {
        let l = TabulatedLoad::unidirectional(
            vec![0.0, 90.0, 180.0],
            &[1.0, 3.0, -1.0],
            [0.0, -2.0],
            360.0,
            10.0,
            LoadInterpolation::Linear,
        )
        .unwrap();
        assert_eq!(l.load_at_crank_angle(90.0), [0.0, -3.0]);
        // Halfway between 180° (−1) and 360° ≡ 0° (+1): zero.
        assert!(l.load_at_crank_angle(270.0)[1].abs() < 1e-15);
        assert!((l.load_at_crank_angle(45.0 + 720.0)[1] + 2.0).abs() < 1e-15);
        assert!((l.load_at_crank_angle(-90.0)[1]).abs() < 1e-15);
    }

    #[test]
    fn catmull_rom_reproduces_a_periodic_sine_closely() {
        let n = 72;
        let ang: Vec<f64> = (0..n).map(|i| i as f64 * 5.0).collect();
        let mag: Vec<f64> = ang.iter().map(|a| a.to_radians().sin()).collect();
        let l = TabulatedLoad::unidirectional(
            ang,
            &mag,
            [1.0, 0.0],
            360.0,
            1.0,
            LoadInterpolation::CatmullRom,
        )
        .unwrap();
        for k in 0..1000 {
            let a = k as f64 * 0.731;
            let f = l.load_at_crank_angle(a)[0];
            // Catmull–Rom is third-order accurate in h = 5° = 0.087 rad: error ≲ h³/10 ≈ 7e-5.
            assert!((f - a.to_radians().sin()).abs() < 1e-4, "{a}: {f}");
        }
    }

    #[test]
    fn bad_tables_are_rejected() {
        assert!(matches!(
            TabulatedLoad::new(
                vec![0.0, 0.0],
                vec![[0.0; 2]; 2],
                360.0,
                1.0,
                LoadInterpolation::Linear
            ),
            Err(LoadTableError::NotIncreasing { row: 1, .. })
        ));
        assert!(matches!(
            TabulatedLoad::new(
                vec![0.0, 400.0],
                vec![[0.0; 2]; 2],
                360.0,
                1.0,
                LoadInterpolation::Linear
            ),
            Err(LoadTableError::SpanExceedsCycle { .. })
        ));
    }
}
