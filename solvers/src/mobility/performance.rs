//! Performance of the mobility answer at one instant: h_min, p_max, side flow, power loss.
//!
//! Given the journal position ε and the load W, the mobility model gives the squeeze rate
//! u = v/c = |W| (c/R)²/(μLD) · M (bearing frame, 1/s), and from it, by the short-bearing
//! Gumbel film of [`super::short_bearing`]:
//!
//! * **Minimum film** h_min = c (1 − |ε|), in the direction of ε (\[Flores2006\] eq. 38).
//! * **Peak pressure** in the mid-plane z = 0 of the short-bearing pressure (\[Flores2006\] eq. 18):
//!   p(θ) = (3 μ L² / 2c²) (u·n) / (1 − ε·n)³, maximised over θ by
//!   [`crate::closed_form::short::moving_film_peak_pressure`] (Sommerfeld's substitution, Newton).
//! * **Side flow** out of both ends of the pressurised half film (the short-bearing flow
//!   integral): the axial flow per unit circumference at z = ±L/2 is
//!   −(h³/12μ) ∂p/∂z = (v·n) L/2, so Q = 2 · ∫_{v·n>0} (v·n) L/2 · R dθ = 2 R L |v| = 2 R L c |u|.
//!   For steady rotation (v = −ω̄ × e) this is Q = ε c U L, Ocvirk's short-bearing side flow.
//! * **Power loss**: the dissipation integral of docs/conventions.md §5,
//!   ∫∫ [μ U² f / h + (h³/12μ) |∇p|²] dA, in closed form for the short bearing:
//!   - Couette part with f = 1 over the whole 360° (the usual mobility-method assumption —
//!     the Gumbel film carries no film-fraction information): ∫₀^{2π} dθ/(1 − ε cos θ) =
//!     2π/√(1 − ε²), so P_shear = 2π μ R³ L (ω_j − ω_b)² / (c √(1 − ε²)) (Petroff with the
//!     eccentricity factor).
//!   - Pressure part: with p from eq. 18, (h³/12μ)(∂p/∂z)² integrated over z gives
//!     μ (v·n)² L³/h³ per unit circumference, whose integral over the pressurised half is
//!     exactly W·v (\[Booker1965\]: the squeeze dissipation is the load times the squeeze
//!     velocity). P_squeeze = W·v ≥ 0.
//!
//! These are closed forms of the short-bearing film; with a finite-length mobility map the
//! velocity is that of the map and the flow and pressure remain the short-bearing estimates.

use super::{MobilityModel, MobilityParams};
use crate::closed_form::short::couette_shear_torque;

/// Performance of the mobility answer at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerformancePoint {
    /// |ε|.
    pub eccentricity_ratio: f64,
    /// Minimum film thickness c(1 − |ε|) (m).
    pub min_film_thickness: f64,
    /// Bearing-frame angle θ of the minimum film (rad, the direction of ε).
    pub min_film_angle: f64,
    /// Squeeze rate u = (ė − ω̄ × e)/c in the bearing frame (1/s).
    pub squeeze_rate: [f64; 2],
    /// dε/dt = u + ω̄ × ε (1/s).
    pub eccentricity_rate: [f64; 2],
    /// Peak mid-plane pressure of the short-bearing Gumbel film (Pa, gauge).
    pub peak_pressure: f64,
    /// Bearing-frame angle θ of the peak pressure (rad).
    pub peak_pressure_angle: f64,
    /// Side leakage out of both ends of the pressurised film (m³/s).
    pub side_flow: f64,
    /// Couette (shear) dissipation over the full film (W).
    pub shear_power: f64,
    /// Pressure-flow (squeeze) dissipation W·v (W).
    pub squeeze_power: f64,
    /// shear_power + squeeze_power (W).
    pub power_loss: f64,
}

/// Evaluate the performance at eccentricity ratio vector `eps` (bearing frame, |ε| < 1) under
/// the load `load` (N, force on the journal, bearing frame).
///
/// ```
/// use jbearing_solvers::mobility::{performance_at, BookerShortBearing, MobilityParams};
/// use std::f64::consts::PI;
///
/// // A centred journal without rotation under W: the short film's squeeze force is
/// // (π/2) μ R L³ v / c³ along v, so it sinks along W at v = 2 W c³ / (π μ R L³), dissipating
/// // W·v, with both ends together leaking 2 R L v.
/// let params = MobilityParams {
///     radius: 0.02, length: 0.01, radial_clearance: 40e-6, viscosity: 0.02,
///     omega_journal: 0.0, omega_bearing: 0.0,
/// };
/// let model = BookerShortBearing { length_to_diameter: params.length_to_diameter() };
/// let w = 1000.0;
/// let point = performance_at(&params, &model, [0.0, 0.0], [0.0, -w]);
/// let c = params.radial_clearance;
/// let v = 2.0 * w * c.powi(3) / (PI * params.viscosity * params.radius * params.length.powi(3));
/// let [ux, uy] = point.squeeze_rate;
/// assert!(ux.abs() < 1e-9 * v / c && (uy * c + v).abs() < 1e-9 * v);
/// assert!(point.shear_power == 0.0 && (point.power_loss - w * v).abs() < 1e-9 * w * v);
/// assert!((point.side_flow - 2.0 * params.radius * params.length * v).abs() < 1e-9 * point.side_flow);
/// ```
pub fn performance_at<M: MobilityModel + ?Sized>(
    params: &MobilityParams,
    model: &M,
    eps: [f64; 2],
    load: [f64; 2],
) -> PerformancePoint {
    let e = eps[0].hypot(eps[1]);
    let c = params.radial_clearance;
    let u = squeeze_rate(params, model, eps, load);
    let wbar = params.omega_bar();
    let eps_dot = [u[0] - wbar * eps[1], u[1] + wbar * eps[0]];
    let (p_max, p_angle) = peak_pressure(params, eps, u);
    let umag = u[0].hypot(u[1]);
    let dw = params.omega_journal - params.omega_bearing;
    let r = params.radius;
    let shear = couette_shear_torque(&params.closed_form(), e, dw) * dw;
    let squeeze = c * (load[0] * u[0] + load[1] * u[1]);
    PerformancePoint {
        eccentricity_ratio: e,
        min_film_thickness: c * (1.0 - e),
        min_film_angle: if e > 0.0 { eps[1].atan2(eps[0]) } else { 0.0 },
        squeeze_rate: u,
        eccentricity_rate: eps_dot,
        peak_pressure: p_max,
        peak_pressure_angle: p_angle,
        side_flow: 2.0 * r * params.length * c * umag,
        shear_power: shear,
        squeeze_power: squeeze,
        power_loss: shear + squeeze,
    }
}

/// u = |W| (c/R)²/(μLD) · M, rotated from the load frame to the bearing frame (1/s).
pub(crate) fn squeeze_rate<M: MobilityModel + ?Sized>(
    params: &MobilityParams,
    model: &M,
    eps: [f64; 2],
    load: [f64; 2],
) -> [f64; 2] {
    let wm = load[0].hypot(load[1]);
    if wm == 0.0 {
        return [0.0, 0.0];
    }
    let (wx, wy) = (load[0] / wm, load[1] / wm);
    let zeta = eps[0] * wx + eps[1] * wy;
    let kappa = -eps[0] * wy + eps[1] * wx;
    let [mz, mk] = model.mobility(zeta, kappa);
    let s = wm * params.mobility_scale();
    [s * (mz * wx - mk * wy), s * (mz * wy + mk * wx)]
}

/// Peak mid-plane pressure (Pa) and its angle θ (rad) of the short-bearing Gumbel film.
fn peak_pressure(params: &MobilityParams, eps: [f64; 2], u: [f64; 2]) -> (f64, f64) {
    crate::closed_form::short::moving_film_peak_pressure(&params.closed_form(), eps, u)
}

#[cfg(test)]
mod tests {
    use super::super::ExactShortBearing;
    use super::*;
    use std::f64::consts::TAU;

    fn params() -> MobilityParams {
        MobilityParams {
            radius: 0.03,
            length: 0.02,
            radial_clearance: 30e-6,
            viscosity: 0.01,
            omega_journal: 300.0,
            omega_bearing: 0.0,
        }
    }

    /// Brute-force maximum of the mid-plane pressure over θ on a fine grid.
    fn brute_peak(p: &MobilityParams, eps: [f64; 2], u: [f64; 2]) -> (f64, f64) {
        let mut best = (0.0, 0.0);
        let n = 400_000;
        for k in 0..n {
            let t = k as f64 * TAU / n as f64;
            let (ct, st) = (t.cos(), t.sin());
            let w = 1.0 - eps[0] * ct - eps[1] * st;
            let val = 1.5 * p.viscosity * p.length * p.length
                / (p.radial_clearance * p.radial_clearance)
                * (u[0] * ct + u[1] * st)
                / (w * w * w);
            if val > best.0 {
                best = (val, t);
            }
        }
        best
    }

    #[test]
    fn peak_pressure_matches_brute_force() {
        let p = params();
        for &(eps, u) in &[
            ([0.3, 0.1], [100.0, -40.0]),
            ([-0.6, 0.5], [-10.0, 30.0]),
            ([0.0, 0.95], [5.0, 1.0]),
            ([0.0, 0.0], [0.0, 7.0]),
        ] {
            let (pm, ang) = peak_pressure(&p, eps, u);
            let (pb, tb) = brute_peak(&p, eps, u);
            // The grid step 1.6e-5 rad puts the brute maximum within ~1e-9 relative of the true one
            // (quadratic peak); the angle agrees to the grid step.
            assert!((pm - pb).abs() < 1e-7 * pb, "{eps:?}: {pm} vs {pb}");
            let d = (ang - tb).rem_euclid(TAU);
            assert!(d.min(TAU - d) < 1e-3, "{eps:?}: angle {ang} vs {tb}");
        }
    }

    #[test]
    fn steady_rotation_gives_ocvirk_side_flow() {
        // Steady state: dε/dt = 0 ⇒ u = −ω̄ × ε, |u| = ω̄ ε, Q = 2RLc ω̄ ε = ε c U L (Ocvirk).
        let p = params();
        let model = ExactShortBearing {
            length_to_diameter: p.length_to_diameter(),
        };
        // Load that holds ε = (0.5, 0) steady: W = (μRL³/c²) J(u) with u = −ω̄ ẑ×ε.
        let eps = [0.5, 0.0];
        let wb = p.omega_bar();
        let u = [wb * eps[1], -wb * eps[0]];
        let j = super::super::short_bearing_squeeze_integral(eps, u);
        let k = p.viscosity * p.radius * p.length.powi(3) / p.radial_clearance.powi(2);
        let w = [k * j[0], k * j[1]];
        let perf = performance_at(&p, &model, eps, w);
        assert!(perf.eccentricity_rate[0].hypot(perf.eccentricity_rate[1]) < 1e-9 * wb);
        let q_ocvirk = 0.5 * p.radial_clearance * p.omega_journal * p.radius * p.length;
        assert!((perf.side_flow - q_ocvirk).abs() < 1e-9 * q_ocvirk);
    }
}
