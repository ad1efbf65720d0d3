//! Dry contact of the journal on the bearing wall and the lubricated → dry transition
//! (\[Flores2009\] §4, eq. 20; the contact law of its ref. 3, Flores & Ambrósio 2004).
//!
//! # Contact law \[LankaraniNikravesh1990\]
//!
//! With the penetration δ (m) and its rate δ̇, and δ̇⁻ the penetration rate at the onset of the
//! contact (the impact velocity):
//!
//! ```text
//!   F_N = K δ^n [1 + 3(1 − c_e²)/4 · δ̇/δ̇⁻],   n = 3/2,   F_N ≥ 0 (no adhesion)
//!   K   = 4 / (3(σ_b + σ_j)) · [R_b R_j / (R_b − R_j)]^{1/2},   σ_k = (1 − ν_k²)/E_k
//! ```
//!
//! c_e is the coefficient of restitution; the hysteresis term dissipates the energy lost in an
//! impact with that c_e. K is the stiffness Flores & Ambrósio use for a revolute clearance joint
//! (the sphere-in-sphere Hertz constant with the two radii of the joint); n = 3/2 likewise.
//! F_N acts on the journal towards the bearing centre (−ê).
//!
//! # Friction (not in \[Flores2009\]: off by default)
//!
//! Coulomb friction with a regularised sliding velocity (Flores & Ambrósio's joints use the same
//! kind of law; \[Flores2009\]'s example is lubricated and has none): with the tangent
//! t̂ = (−ê_y, ê_x) and the sliding velocity of the journal's contact point on the bearing
//! v_t = ė·t̂ + φ̇₃ R_j (the bearing, in the slider, does not rotate),
//!
//! ```text
//!   F_T = −μ_f F_N v_t / √(v_t² + v₀²)   along t̂,   moment on the journal about its centre R_j F_T
//! ```
//!
//! μ_f = `friction_coefficient` (default 0), v₀ = `friction_speed` (default 1 mm/s, against
//! sliding speeds φ̇₃ R_j of ~1 m/s here). Its power −F_T v_t ≥ 0 is dissipated.
//!
//! # Transition (\[Flores2009\] eq. 20, in film-thickness terms)
//!
//! \[Flores2009\] blends the lubricated force into the dry one over an eccentricity band e₀ once the
//! film reaches the "boundary layer", and evaluates the lubricated force with a clearance
//! enlarged by e₁ so that it stays finite in the band. Here the film model uses the true
//! clearance c (so the lubricated results do not depend on the contact settings), and the dry
//! contact starts when the minimum film h_min = c − e reaches the boundary-layer thickness h_b:
//!
//! ```text
//!   δ = e − (c − h_b)                       (penetration of the boundary layer)
//!   s = clamp(δ / e₀, 0, 1)                 (blend weight, e₀ < h_b)
//!   F = (1 − s) F_film + s F_dry            ([Flores2009] eq. 20 with c_seed = c − h_b, e₁ = h_b)
//! ```
//!
//! F is continuous in e (F_dry(0) = 0, and s is continuous); the film is evaluated only for
//! s < 1, where ε = e/c ≤ 1 − (h_b − e₀)/c < 1. This is eq. 20 with the paper's contact clearance
//! c − h_b and its e₁ = h_b.

use super::MechanismError;

/// Dry-contact and transition settings of a lubricated joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactParams {
    /// Young's modulus of the journal E_j (Pa).
    pub journal_youngs_modulus: f64,
    /// Poisson's ratio of the journal ν_j.
    pub journal_poisson_ratio: f64,
    /// Young's modulus of the bearing E_b (Pa).
    pub bearing_youngs_modulus: f64,
    /// Poisson's ratio of the bearing ν_b.
    pub bearing_poisson_ratio: f64,
    /// Coefficient of restitution c_e (0 < c_e ≤ 1).
    pub restitution: f64,
    /// Boundary-layer thickness h_b (m): the dry contact starts when h_min falls below it.
    pub boundary_layer: f64,
    /// Width e₀ of the blend band (m), 0 < e₀ < h_b.
    pub blend_width: f64,
    /// Floor on the impact velocity δ̇⁻ (m/s): a contact entered with a smaller (or no) rate
    /// uses this one, so the hysteresis damping stays finite.
    pub min_impact_speed: f64,
    /// Coulomb friction coefficient μ_f of the dry contact (0: none, as \[Flores2009\]).
    pub friction_coefficient: f64,
    /// Regularisation speed v₀ of the friction law (m/s).
    pub friction_speed: f64,
}

impl Default for ContactParams {
    /// Steel on steel (E = 207 GPa, ν = 0.3, the values of Flores & Ambrósio 2004), c_e = 0.9,
    /// h_b = 1 µm (a ground pin and a honed eye: composite roughness well below the paper's
    /// "safe" film of ≈ 3 µm), e₀ = 0.5 µm, δ̇⁻ ≥ 1 mm/s. \[Flores2009\] gives no values for e₀, e₁
    /// ("must be chosen carefully"): these are assumptions.
    fn default() -> Self {
        Self {
            journal_youngs_modulus: 207e9,
            journal_poisson_ratio: 0.3,
            bearing_youngs_modulus: 207e9,
            bearing_poisson_ratio: 0.3,
            restitution: 0.9,
            boundary_layer: 1e-6,
            blend_width: 0.5e-6,
            min_impact_speed: 1e-3,
            friction_coefficient: 0.0,
            friction_speed: 1e-3,
        }
    }
}

impl ContactParams {
    /// Check every value; `radial_clearance` is the joint's c (h_b must be smaller).
    pub fn validate(&self, radial_clearance: f64) -> Result<(), MechanismError> {
        let bad = |name: &'static str, value: f64| MechanismError::InvalidParameter { name, value };
        for (name, v) in [
            (
                "contact.journal_youngs_modulus",
                self.journal_youngs_modulus,
            ),
            (
                "contact.bearing_youngs_modulus",
                self.bearing_youngs_modulus,
            ),
            ("contact.min_impact_speed", self.min_impact_speed),
            ("contact.friction_speed", self.friction_speed),
            ("contact.boundary_layer", self.boundary_layer),
            ("contact.blend_width", self.blend_width),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(name, v));
            }
        }
        for (name, v) in [
            ("contact.journal_poisson_ratio", self.journal_poisson_ratio),
            ("contact.bearing_poisson_ratio", self.bearing_poisson_ratio),
        ] {
            if !(v.is_finite() && (0.0..0.5).contains(&v)) {
                return Err(bad(name, v));
            }
        }
        if !(self.friction_coefficient.is_finite() && self.friction_coefficient >= 0.0) {
            return Err(bad(
                "contact.friction_coefficient (≥ 0)",
                self.friction_coefficient,
            ));
        }
        if !(self.restitution > 0.0 && self.restitution <= 1.0) {
            return Err(bad("contact.restitution (0 < c_e ≤ 1)", self.restitution));
        }
        if self.blend_width >= self.boundary_layer {
            return Err(bad(
                "contact.blend_width (must be < boundary_layer)",
                self.blend_width,
            ));
        }
        if self.boundary_layer >= radial_clearance {
            return Err(bad(
                "contact.boundary_layer (must be < radial clearance)",
                self.boundary_layer,
            ));
        }
        Ok(())
    }

    /// Hertz stiffness K (N/m^{3/2}) for a journal of radius `journal_radius` in a bearing of
    /// radius `bearing_radius`.
    pub fn stiffness(&self, bearing_radius: f64, journal_radius: f64) -> f64 {
        let s = |e: f64, nu: f64| (1.0 - nu * nu) / e;
        let sigma = s(self.journal_youngs_modulus, self.journal_poisson_ratio)
            + s(self.bearing_youngs_modulus, self.bearing_poisson_ratio);
        4.0 / (3.0 * sigma)
            * (bearing_radius * journal_radius / (bearing_radius - journal_radius)).sqrt()
    }
}

/// Lankarani–Nikravesh normal force (N, ≥ 0) for penetration δ, rate δ̇ and impact velocity
/// δ̇⁻ (> 0); zero for δ ≤ 0.
pub fn lankarani_nikravesh(
    stiffness: f64,
    restitution: f64,
    penetration: f64,
    penetration_rate: f64,
    impact_speed: f64,
) -> f64 {
    if penetration <= 0.0 {
        return 0.0;
    }
    let damping = 0.75 * (1.0 - restitution * restitution) / impact_speed;
    (stiffness * penetration.powf(1.5) * (1.0 + damping * penetration_rate)).max(0.0)
}

/// Blend weight s = clamp(δ/e₀, 0, 1) of \[Flores2009\] eq. 20.
pub fn blend_weight(penetration: f64, blend_width: f64) -> f64 {
    (penetration / blend_width).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One impact of a mass m on the Lankarani–Nikravesh spring–damper, integrated with a fine
    /// RK4: the rebound speed over the impact speed must be c_e — to O(1 − c_e²) accuracy, which
    /// is the law's own design assumption (it is derived for c_e near 1): within 2 % at c_e =
    /// 0.9, and exactly 1 at c_e = 1 (elastic: energy conserved to RK4 accuracy).
    #[test]
    fn lankarani_nikravesh_restitution() {
        let k = ContactParams::default().stiffness(10e-3, 9.8e-3);
        for ce in [1.0, 0.95, 0.9] {
            let (m, v0) = (0.1, 0.5);
            let (mut x, mut v) = (0.0f64, v0);
            let dt = 1e-9;
            let acc = |x: f64, v: f64| -lankarani_nikravesh(k, ce, x, v, v0) / m;
            let mut steps = 0;
            loop {
                let (k1x, k1v) = (v, acc(x, v));
                let (k2x, k2v) = (
                    v + 0.5 * dt * k1v,
                    acc(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v),
                );
                let (k3x, k3v) = (
                    v + 0.5 * dt * k2v,
                    acc(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v),
                );
                let (k4x, k4v) = (v + dt * k3v, acc(x + dt * k3x, v + dt * k3v));
                x += dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
                v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
                steps += 1;
                if x < 0.0 || steps > 10_000_000 {
                    break;
                }
            }
            let ratio = -v / v0;
            if ce == 1.0 {
                assert!((ratio - 1.0).abs() < 1e-6, "elastic: {ratio}");
            } else {
                assert!((ratio - ce).abs() < 0.02, "c_e {ce}: rebound ratio {ratio}");
            }
        }
    }

    #[test]
    fn hertz_stiffness_of_the_flores_pin() {
        // σ = (1 − 0.09)/207e9 = 4.396e-12 per body; √(R_b R_j/c) = √(0.49 m) = 0.7 m^{1/2}.
        let k = ContactParams::default().stiffness(10e-3, 9.8e-3);
        let want = 4.0 / (3.0 * 2.0 * 0.91 / 207e9) * 0.7;
        assert!((k - want).abs() < 1e-9 * want, "{k} vs {want}");
        // Static: F = K δ^{3/2} with no rate.
        let f = lankarani_nikravesh(k, 0.9, 1e-6, 0.0, 1.0);
        assert!((f - k * 1e-9).abs() < 1e-9 * f);
        // No adhesion: a fast separation gives 0, not a pull.
        assert_eq!(lankarani_nikravesh(k, 0.5, 1e-6, -1e3, 1e-3), 0.0);
        assert_eq!(lankarani_nikravesh(k, 0.5, -1e-6, 1.0, 1.0), 0.0);
    }

    #[test]
    fn blend_is_continuous_and_saturates() {
        let e0 = 0.5e-6;
        assert_eq!(blend_weight(-1e-9, e0), 0.0);
        assert_eq!(blend_weight(0.0, e0), 0.0);
        assert!((blend_weight(0.25e-6, e0) - 0.5).abs() < 1e-15);
        assert_eq!(blend_weight(e0, e0), 1.0);
        assert_eq!(blend_weight(2.0 * e0, e0), 1.0);
        // Continuity across both ends of the band: tiny steps give tiny changes.
        for x in [0.0, e0] {
            let d = blend_weight(x + 1e-15, e0) - blend_weight(x - 1e-15, e0);
            assert!(d.abs() < 1e-8);
        }
    }

    #[test]
    fn bad_settings_are_errors() {
        let c = 0.2e-3;
        assert!(ContactParams::default().validate(c).is_ok());
        let p = ContactParams {
            blend_width: 2e-6,
            ..Default::default()
        };
        assert!(p.validate(c).is_err());
        let p = ContactParams {
            restitution: 0.0,
            ..Default::default()
        };
        assert!(p.validate(c).is_err());
        let p = ContactParams {
            friction_coefficient: -0.1,
            ..Default::default()
        };
        assert!(p.validate(c).is_err());
        let p = ContactParams {
            friction_speed: 0.0,
            ..Default::default()
        };
        assert!(p.validate(c).is_err());
        let p = ContactParams {
            boundary_layer: 1e-3,
            blend_width: 1e-4,
            ..Default::default()
        };
        assert!(p.validate(c).is_err());
    }
}
