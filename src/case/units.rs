//! Units: the one place where case-file numbers become SI.
//!
//! Case-file keys name their unit as a suffix (`radius_m`, `viscosity_pa_s`, `speed_rpm`,
//! `center_angle_deg`), and every key is in SI except the two units the field always uses for
//! machine data: revolutions per minute for speeds and degrees for angles. CSV tables name the
//! unit of each column the same way (`crank_angle_deg`, `load_x_n`, `load_kN`,
//! `feed_pressure_pa`, `journal_speed_rpm`); the suffix is matched without regard to case.
//!
//! ```text
//!   quantity   suffix → factor to SI
//!   force      n → 1            kn → 1e3
//!   pressure   pa → 1           kpa → 1e3      mpa → 1e6     bar → 1e5
//!   speed      rad_s → 1        rpm → 2π/60
//!   angle      deg → π/180      rad → 1
//! ```

use std::f64::consts::PI;

/// Revolutions per minute → rad/s.
pub fn rpm_to_rad_s(rpm: f64) -> f64 {
    rpm * 2.0 * PI / 60.0
}

/// rad/s → revolutions per minute.
pub fn rad_s_to_rpm(w: f64) -> f64 {
    w * 60.0 / (2.0 * PI)
}

/// Degrees → radians.
pub fn deg_to_rad(deg: f64) -> f64 {
    deg.to_radians()
}

/// A physical quantity a CSV column may hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Force (SI: N).
    Force,
    /// Pressure (SI: Pa).
    Pressure,
    /// Angular speed (SI: rad/s).
    Speed,
    /// Angle (SI: rad; crank angles are kept in degrees, see [`Quantity::Angle`] users).
    Angle,
}

impl Quantity {
    /// Units accepted for this quantity, as (suffix, factor to SI).
    pub fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Quantity::Force => &[("n", 1.0), ("kn", 1e3)],
            Quantity::Pressure => &[("pa", 1.0), ("kpa", 1e3), ("mpa", 1e6), ("bar", 1e5)],
            Quantity::Speed => &[("rad_s", 1.0), ("rpm", 2.0 * PI / 60.0)],
            Quantity::Angle => &[("deg", PI / 180.0), ("rad", 1.0)],
        }
    }

    /// The accepted suffixes, for messages: `"n, kn"`.
    pub fn unit_list(self) -> String {
        self.units()
            .iter()
            .map(|(s, _)| *s)
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// If `header` is `base` followed by `_` and a unit of `quantity` (case-insensitive), the factor
/// that turns the column into SI.
pub fn column_factor(header: &str, base: &str, quantity: Quantity) -> Option<f64> {
    let h = header.trim().to_ascii_lowercase();
    let rest = h.strip_prefix(base)?.strip_prefix('_')?;
    quantity
        .units()
        .iter()
        .find(|(s, _)| *s == rest)
        .map(|(_, f)| *f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_matched_with_their_units() {
        assert_eq!(column_factor("load_kN", "load", Quantity::Force), Some(1e3));
        assert_eq!(
            column_factor("load_x_n", "load_x", Quantity::Force),
            Some(1.0)
        );
        assert_eq!(column_factor("load_x_n", "load", Quantity::Force), None);
        assert_eq!(
            column_factor("feed_pressure_MPa", "feed_pressure", Quantity::Pressure),
            Some(1e6)
        );
        assert!((rpm_to_rad_s(60.0) - 2.0 * PI).abs() < 1e-15);
        assert!((rad_s_to_rpm(rpm_to_rad_s(1800.0)) - 1800.0).abs() < 1e-9);
    }
}
