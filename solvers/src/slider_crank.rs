//! A single-cylinder slider-crank compressor: the loads on its main and connecting-rod bearings,
//! the rod's angular velocity and the rod bearing's oil feed through the crank drilling.
//!
//! Yu & Sawicki \[YuSawicki2002\] (Table II) give the two bearings of a commercial
//! reciprocating air compressor but draw the load and feed histories only as figures (Figs. 3a–b,
//! 4a–b). This module synthesizes those histories from the physics of the machine
//! (docs/conventions.md §7), so that the compressor cases are reproducible from stated numbers.
//!
//! # Kinematics (machine frame)
//!
//! ```text
//!         Y ↑                       cylinder head
//!           |      crank pin P          ┃
//!           |     •  (r cos φ, r sin φ) ┃
//!           |   r/  \ l (rod)           ┃
//!           |  / φ    \                 ┃
//!   ────────O───────────•───────────────┃──→ X
//!      crank axis    piston pin S = (s, 0)
//! ```
//!
//! φ is the crank angle from top dead centre (TDC, pin towards the cylinder), counter-clockwise,
//! φ = Ω t. With λ = r / l and the rod angle β (sin β = λ sin φ, the rod leaning below X when the
//! pin is above it):
//!
//! ```text
//!   s(φ)  = r cos φ + l cos β                          piston pin position
//!   x(φ)  = r + l − s(φ)                               piston travel from TDC
//!   β̇     = Ω λ cos φ / cos β                         rod angular velocity
//!   ṡ     = −r Ω sin φ − l β̇ sin β
//!   s̈     = −r Ω² cos φ − l (β̈ sin β + β̇² cos β),  β̈ = (l β̇² sin β − r Ω² sin φ) / (l cos β)
//! ```
//!
//! # Cylinder pressure (ideal single-stage cycle, polytropic)
//!
//! Swept volume V_s = A·2r, clearance volume V_c = κ V_s, V(φ) = V_c + A x(φ). From TDC the
//! cylinder expands the clearance gas (p V^n = p_d V_c^n) until it reaches the suction pressure,
//! draws in at p_s until BDC, compresses (p V^n = p_s V_bdc^n) until it reaches the discharge
//! pressure and discharges at p_d until TDC:
//!
//! ```text
//!   0 ≤ φ < π  (down-stroke):  p = max(p_s, p_d (V_c / V)^n)      expansion, then suction
//!   π ≤ φ < 2π (up-stroke):    p = min(p_d, p_s (V_bdc / V)^n)    compression, then discharge
//! ```
//!
//! # Forces (two-mass rod, quasi-static crank at constant Ω)
//!
//! The rod is replaced by its classical two-mass equivalent: a share at the small end (added to
//! the piston's reciprocating mass m_rec) and a share at the big end (the rotating mass m_rot at
//! the crank pin); the link between them is massless and carries the axial force S (compression
//! positive). With the gas force F_g = (p − p_case) A on the piston (towards the crank) and the
//! rod unit vector u = (cos β, −sin β) from big end to small end:
//!
//! ```text
//!   piston, along X:  m_rec s̈ = −F_g + S cos β     ⇒   S = (F_g + m_rec s̈) / cos β
//!   wall side force:  N = S sin β
//!   rod bearing (journal = crank pin, bearing = big end), machine frame; the film carries the
//!   rod thrust and the big end's inertia:
//!       W_rod = S u − m_rot a_P,  a_P = −r Ω² (cos φ, sin φ)
//!   main bearing (journal = main journal, bearing fixed), machine frame, one of n_main equal
//!   bearings sharing the crank's forces; the counterweight balances the rotating masses and a
//!   fraction α of the reciprocating mass (the usual single-cylinder compromise):
//!       W_main = (1/n_main) [ −S u − α m_rec r Ω² (cos φ, sin φ) ]
//! ```
//!
//! Derivation of the signs: the gas pushes the piston towards the crank (−X), so
//! S = F_g/cos β is positive near TDC. The link pushes the piston along +u and the big end along −u; the film of the rod
//! bearing therefore pushes the crank pin along −u (plus the big end's inertia), and the load on
//! the journal, the force that balances the film (docs/conventions.md §1: F_film + W = 0), is +S u. The crank
//! pin passes −S u on to the crankshaft, whose main bearings hold it together with the
//! unbalanced centrifugal force of crank, big end and counterweight, (m_rot r + U_crank − U_cw) Ω²
//! = −α m_rec r Ω² along the crank.
//!
//! The rod bearing's own frame turns with the rod: its x axis is u (big end → small end), frame
//! angle ψ = −β, angular velocity ω_b = ψ̇ = −β̇; the journal (crank pin) turns at ω_j = Ω. Its
//! load in that frame is W_rod rotated by −ψ.
//!
//! # Rod-bearing feed through the crank drilling
//!
//! A straight drilling runs from the main journal's surface (inlet at angle φ + δ_in in the
//! machine frame, radius R_main from the crank axis) to the crank pin surface. Its inlet passes
//! under the main bearing's partial groove (centre θ_g, arc length b_g on R_main) once a
//! revolution. The open fraction f ∈ [0, 1] is the overlap of the inlet hole (diameter d_h) with the
//! groove arc, and while open the pressure at the outlet is the main feed pressure plus the
//! centrifugal head of the oil column between the radii r_in = R_main and r_out (outlet's distance
//! from the crank axis):
//!
//! ```text
//!   p_rod = p_cav + f · (p_main + ½ ρ Ω² (r_out² − r_in²) − p_cav)
//! ```
//!
//! While closed (f = 0) the rod film drains the drilling and its pressure falls to the cavitation
//! pressure: the rod bearing's feed is cut off and it runs starved (docs/conventions.md §2, the solver then
//! holds the groove cavitated at a given film fraction, 0.01 in Yu & Sawicki's Fig. 4).
//! The overlap is linear in the covered length of the hole's diameter (a rectangular hole of the
//! same width), a first-order model of a round hole's overlap area.
//!
//! Sources: slider-crank kinematics and the two-mass rod, e.g. Taylor, *The Internal-Combustion
//! Engine in Theory and Practice*, Vol. 2, ch. 8; the ideal compressor cycle, e.g. Bloch,
//! *A Practical Guide to Compressor Technology*, ch. 3.

use std::f64::consts::{PI, TAU};

use thiserror::Error;

/// The compressor, SI units (pressures absolute where stated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankParams {
    /// Cylinder bore (m).
    pub bore: f64,
    /// Stroke = 2 r (m).
    pub stroke: f64,
    /// Rod length l, centre to centre (m).
    pub rod_length: f64,
    /// Crank speed Ω (rad/s), > 0 (counter-clockwise).
    pub crank_speed: f64,
    /// Reciprocating mass m_rec: piston, rings, pin and the rod's small-end share (kg).
    pub reciprocating_mass: f64,
    /// Rotating mass m_rot: the rod's big-end share, carried by the rod-bearing film (kg).
    pub rotating_mass: f64,
    /// Fraction α of the reciprocating mass balanced by the counterweight (0 … 1).
    pub counterweight_fraction: f64,
    /// Number of main bearings sharing the crank's forces equally (≥ 1).
    pub main_bearing_count: f64,
    /// Suction pressure, absolute (Pa).
    pub suction_pressure: f64,
    /// Discharge pressure, absolute (Pa), > suction.
    pub discharge_pressure: f64,
    /// Crankcase pressure, absolute (Pa): acts on the piston's underside.
    pub crankcase_pressure: f64,
    /// Clearance volume as a fraction κ of the swept volume (> 0).
    pub clearance_volume_fraction: f64,
    /// Polytropic exponent n of compression and re-expansion (≥ 1).
    pub polytropic_exponent: f64,
    /// Crank drilling and main groove, for the rod bearing's feed pressure.
    pub drilling: CrankDrilling,
}

/// The oil path from the main bearing's groove to the rod bearing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrankDrilling {
    /// Main journal radius R_main (m): the drilling inlet's distance from the crank axis.
    pub main_journal_radius: f64,
    /// Inlet angle δ_in ahead of the crank pin direction (rad).
    pub inlet_angle: f64,
    /// Drilling diameter d_h (m).
    pub hole_diameter: f64,
    /// Centre of the main bearing's groove, machine frame (rad).
    pub groove_center: f64,
    /// Circumferential length of the main groove on R_main (m).
    pub groove_length: f64,
    /// Outlet's distance from the crank axis r_out (m).
    pub outlet_radius: f64,
    /// Main bearing feed pressure, gauge (Pa).
    pub main_feed_pressure: f64,
    /// Oil density ρ (kg/m³).
    pub oil_density: f64,
    /// Cavitation pressure, gauge (Pa): the drilling's pressure while closed.
    pub cavitation_pressure: f64,
}

/// Bad compressor data.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SliderCrankError {
    /// A parameter is non-finite or out of its range; `requirement` says what it must satisfy.
    #[error("slider-crank parameter {name} = {value} must be {requirement}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        requirement: &'static str,
    },
}

/// Everything the model gives at one crank angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankState {
    /// Crank angle φ from TDC (rad).
    pub crank_angle: f64,
    /// Piston travel from TDC x (m).
    pub piston_travel: f64,
    /// Piston pin velocity ṡ along X (m/s).
    pub piston_velocity: f64,
    /// Piston pin acceleration s̈ along X (m/s²).
    pub piston_acceleration: f64,
    /// Rod angle β (rad).
    pub rod_angle: f64,
    /// Rod angular velocity β̇ (rad/s).
    pub rod_angular_velocity: f64,
    /// Cylinder pressure, absolute (Pa).
    pub cylinder_pressure: f64,
    /// Gas force on the piston towards the crank (N).
    pub gas_force: f64,
    /// Axial rod force S, compression positive (N).
    pub rod_force: f64,
    /// Drive torque the motor must supply at constant Ω (N·m, counter-clockwise positive):
    /// minus the torque about the crank axis of the rod bearing's force on the crank pin.
    pub drive_torque: f64,
    /// Load on the main journal, machine (= bearing) frame (N).
    pub main_load: [f64; 2],
    /// Load on the crank pin (rod bearing journal), machine frame (N).
    pub rod_load_machine: [f64; 2],
    /// Load on the crank pin in the rod bearing's own (rotating) frame (N).
    pub rod_load: [f64; 2],
    /// Rod bearing frame angle ψ = −β (rad).
    pub rod_frame_angle: f64,
    /// Rod bearing (big end) angular velocity ω_b = −β̇ (rad/s).
    pub rod_bearing_speed: f64,
    /// Open fraction of the crank drilling's inlet (0 … 1).
    pub drilling_open_fraction: f64,
    /// Feed pressure at the rod bearing, gauge (Pa).
    pub rod_feed_pressure: f64,
}

impl SliderCrankParams {
    /// Crank radius r = stroke / 2 (m).
    pub fn crank_radius(&self) -> f64 {
        0.5 * self.stroke
    }

    /// Piston area A (m²).
    pub fn piston_area(&self) -> f64 {
        0.25 * PI * self.bore * self.bore
    }

    /// Checks every parameter; the error names the first bad one.
    pub fn validate(&self) -> Result<(), SliderCrankError> {
        let bad = |name, value, requirement| {
            Err(SliderCrankError::InvalidParameter {
                name,
                value,
                requirement,
            })
        };
        let d = &self.drilling;
        for (name, v) in [
            ("bore", self.bore),
            ("stroke", self.stroke),
            ("rod_length", self.rod_length),
            ("crank_speed", self.crank_speed),
            ("suction_pressure", self.suction_pressure),
            ("discharge_pressure", self.discharge_pressure),
            ("clearance_volume_fraction", self.clearance_volume_fraction),
            ("main_journal_radius", d.main_journal_radius),
            ("hole_diameter", d.hole_diameter),
            ("groove_length", d.groove_length),
            ("outlet_radius", d.outlet_radius),
            ("oil_density", d.oil_density),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(name, v, "finite and > 0");
            }
        }
        for (name, v) in [
            ("reciprocating_mass", self.reciprocating_mass),
            ("rotating_mass", self.rotating_mass),
            ("crankcase_pressure", self.crankcase_pressure),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(name, v, "finite and ≥ 0");
            }
        }
        for (name, v) in [
            ("inlet_angle", d.inlet_angle),
            ("groove_center", d.groove_center),
            ("main_feed_pressure", d.main_feed_pressure),
            ("cavitation_pressure", d.cavitation_pressure),
        ] {
            if !v.is_finite() {
                return bad(name, v, "finite");
            }
        }
        if !(0.0..=1.0).contains(&self.counterweight_fraction) {
            return bad(
                "counterweight_fraction",
                self.counterweight_fraction,
                "in [0, 1]",
            );
        }
        if !(self.main_bearing_count >= 1.0 && self.main_bearing_count.is_finite()) {
            return bad("main_bearing_count", self.main_bearing_count, "≥ 1");
        }
        if self.rod_length <= self.crank_radius() {
            return bad(
                "rod_length",
                self.rod_length,
                "longer than the crank radius (stroke / 2)",
            );
        }
        if self.discharge_pressure <= self.suction_pressure {
            return bad(
                "discharge_pressure",
                self.discharge_pressure,
                "above the suction pressure",
            );
        }
        if !(self.polytropic_exponent.is_finite() && self.polytropic_exponent >= 1.0) {
            return bad("polytropic_exponent", self.polytropic_exponent, "≥ 1");
        }
        if d.groove_length >= TAU * d.main_journal_radius {
            return bad(
                "groove_length",
                d.groove_length,
                "shorter than the main journal's circumference",
            );
        }
        Ok(())
    }

    /// Cylinder volume at crank angle φ (m³).
    pub fn cylinder_volume(&self, crank_angle: f64) -> f64 {
        let a = self.piston_area();
        self.clearance_volume_fraction * a * self.stroke + a * self.piston_travel(crank_angle)
    }

    /// Piston travel from TDC x(φ) (m).
    pub fn piston_travel(&self, crank_angle: f64) -> f64 {
        let (r, l) = (self.crank_radius(), self.rod_length);
        let sin_b = r / l * crank_angle.sin();
        r + l - (r * crank_angle.cos() + l * (1.0 - sin_b * sin_b).sqrt())
    }

    /// Cylinder pressure, absolute, of the ideal polytropic cycle (Pa).
    pub fn cylinder_pressure(&self, crank_angle: f64) -> f64 {
        let phi = crank_angle.rem_euclid(TAU);
        let v = self.cylinder_volume(phi);
        let n = self.polytropic_exponent;
        let (ps, pd) = (self.suction_pressure, self.discharge_pressure);
        if phi < PI {
            let vc = self.cylinder_volume(0.0);
            ps.max(pd * (vc / v).powf(n))
        } else {
            let vb = self.cylinder_volume(PI);
            pd.min(ps * (vb / v).powf(n))
        }
    }

    /// Open fraction of the crank drilling's inlet under the main groove at crank angle φ.
    pub fn drilling_open_fraction(&self, crank_angle: f64) -> f64 {
        let d = &self.drilling;
        let inlet = crank_angle + d.inlet_angle;
        // Arc distance (on R_main) from the groove centre to the inlet's centre, in (−πR, πR].
        let rel = (inlet - d.groove_center + PI).rem_euclid(TAU) - PI;
        let dist = rel.abs() * d.main_journal_radius;
        // Covered length of the hole's diameter: the part of [dist − d/2, dist + d/2] inside
        // [−b/2, b/2].
        let half_groove = 0.5 * d.groove_length;
        let lo = dist - 0.5 * d.hole_diameter;
        let hi = dist + 0.5 * d.hole_diameter;
        let covered = (hi.min(half_groove) - lo.max(-half_groove)).max(0.0);
        (covered / d.hole_diameter).clamp(0.0, 1.0)
    }

    /// The rod bearing's feed pressure, gauge, at crank angle φ (Pa).
    pub fn rod_feed_pressure(&self, crank_angle: f64) -> f64 {
        let d = &self.drilling;
        let f = self.drilling_open_fraction(crank_angle);
        let omega = self.crank_speed;
        let centrifugal = 0.5
            * d.oil_density
            * omega
            * omega
            * (d.outlet_radius * d.outlet_radius - d.main_journal_radius * d.main_journal_radius);
        let open = d.main_feed_pressure + centrifugal;
        d.cavitation_pressure + f * (open - d.cavitation_pressure)
    }

    /// Kinematics, pressures and bearing loads at crank angle φ (rad). Call
    /// [`SliderCrankParams::validate`] first; this function does not check.
    pub fn state(&self, crank_angle: f64) -> SliderCrankState {
        let phi = crank_angle;
        let (r, l, w) = (self.crank_radius(), self.rod_length, self.crank_speed);
        let lambda = r / l;
        let (sp, cp) = phi.sin_cos();
        let sin_b = lambda * sp;
        let cos_b = (1.0 - sin_b * sin_b).sqrt();
        let beta = sin_b.asin();
        let beta_dot = w * lambda * cp / cos_b;
        let beta_ddot = (l * beta_dot * beta_dot * sin_b - r * w * w * sp) / (l * cos_b);
        let s_dot = -r * w * sp - l * beta_dot * sin_b;
        let s_ddot = -r * w * w * cp - l * (beta_ddot * sin_b + beta_dot * beta_dot * cos_b);

        let p = self.cylinder_pressure(phi);
        let gas_force = (p - self.crankcase_pressure) * self.piston_area();
        // Piston along X: m_rec s̈ = −F_g + S cos β.
        let rod_force = (self.reciprocating_mass * s_ddot + gas_force) / cos_b;
        let u = [cos_b, -sin_b];
        let radial = [cp, sp];
        let a_pin = [-r * w * w * cp, -r * w * w * sp];
        let rod_load_machine = [
            rod_force * u[0] - self.rotating_mass * a_pin[0],
            rod_force * u[1] - self.rotating_mass * a_pin[1],
        ];
        let unbalance = self.counterweight_fraction * self.reciprocating_mass * r * w * w;
        let main_load = [
            (-rod_force * u[0] - unbalance * radial[0]) / self.main_bearing_count,
            (-rod_force * u[1] - unbalance * radial[1]) / self.main_bearing_count,
        ];
        // Force of the rod (through the film) on the pin is −S u − m_rot a_pin; its torque about
        // the crank axis, r_P × F, resists the rotation; the drive supplies the opposite.
        let f_on_pin = [-rod_load_machine[0], -rod_load_machine[1]];
        let torque_on_pin = r * cp * f_on_pin[1] - r * sp * f_on_pin[0];
        let psi = -beta;
        let (s_psi, c_psi) = psi.sin_cos();
        // Rotate the machine-frame load by −ψ into the rod frame.
        let rod_load = [
            c_psi * rod_load_machine[0] + s_psi * rod_load_machine[1],
            -s_psi * rod_load_machine[0] + c_psi * rod_load_machine[1],
        ];
        SliderCrankState {
            crank_angle: phi,
            piston_travel: self.piston_travel(phi),
            piston_velocity: s_dot,
            piston_acceleration: s_ddot,
            rod_angle: beta,
            rod_angular_velocity: beta_dot,
            cylinder_pressure: p,
            gas_force,
            rod_force,
            drive_torque: -torque_on_pin,
            main_load,
            rod_load_machine,
            rod_load,
            rod_frame_angle: psi,
            rod_bearing_speed: -beta_dot,
            drilling_open_fraction: self.drilling_open_fraction(phi),
            rod_feed_pressure: self.rod_feed_pressure(phi),
        }
    }

    /// States at `n` equally spaced crank angles 0, 360°/n, … over one revolution (after
    /// validating the parameters).
    pub fn tabulate(&self, n: usize) -> Result<Vec<SliderCrankState>, SliderCrankError> {
        self.validate()?;
        if n < 4 {
            return Err(SliderCrankError::InvalidParameter {
                name: "points per revolution",
                value: n as f64,
                requirement: "≥ 4",
            });
        }
        Ok((0..n)
            .map(|k| self.state(TAU * k as f64 / n as f64))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> SliderCrankParams {
        SliderCrankParams {
            bore: 0.0762,
            stroke: 0.0635,
            rod_length: 0.127,
            crank_speed: 1800.0 * TAU / 60.0,
            reciprocating_mass: 0.75,
            rotating_mass: 0.27,
            counterweight_fraction: 0.5,
            main_bearing_count: 2.0,
            suction_pressure: 101_325.0,
            discharge_pressure: 901_325.0,
            crankcase_pressure: 101_325.0,
            clearance_volume_fraction: 0.05,
            polytropic_exponent: 1.3,
            drilling: CrankDrilling {
                main_journal_radius: 0.02743,
                inlet_angle: 0.0,
                hole_diameter: 0.004,
                groove_center: PI,
                groove_length: 0.0249,
                outlet_radius: 0.0175,
                main_feed_pressure: 206_800.0,
                oil_density: 860.0,
                cavitation_pressure: 0.0,
            },
        }
    }

    /// Central difference of f at x with step h: error O(h²) ≈ f''' h² / 6.
    fn derivative(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
        (f(x + h) - f(x - h)) / (2.0 * h)
    }

    #[test]
    fn piston_travel_is_zero_at_tdc_and_the_stroke_at_bdc() {
        let p = params();
        assert!(p.piston_travel(0.0).abs() < 1e-15);
        assert!((p.piston_travel(PI) - p.stroke).abs() < 1e-15);
        // The rod keeps its length: |S − P| = l at any angle.
        for k in 0..36 {
            let phi = k as f64 * TAU / 36.0;
            let s = p.crank_radius() + p.rod_length - p.piston_travel(phi);
            let (px, py) = (p.crank_radius() * phi.cos(), p.crank_radius() * phi.sin());
            let len = (s - px).hypot(py);
            assert!((len - p.rod_length).abs() < 1e-14, "φ = {phi}: {len}");
        }
    }

    #[test]
    fn velocities_and_accelerations_are_the_derivatives_of_the_positions() {
        // Independent check: central differences of the closed-form positions (h = 1e-5 rad of
        // crank angle → truncation ~1e-10 relative; the tolerance 1e-6 leaves room for the
        // cancellation error ~ 1e-16 / h² of the second difference).
        let p = params();
        let w = p.crank_speed;
        let h = 1e-4;
        for k in 0..24 {
            let phi = 0.1 + k as f64 * TAU / 24.0;
            let st = p.state(phi);
            let s = |a: f64| -p.piston_travel(a);
            let v_fd = w * derivative(s, phi, h);
            let a_fd = w * w * (s(phi + h) - 2.0 * s(phi) + s(phi - h)) / (h * h);
            let scale_v = p.crank_radius() * w;
            let scale_a = p.crank_radius() * w * w;
            assert!(
                (st.piston_velocity - v_fd).abs() < 1e-7 * scale_v,
                "v at φ = {phi}"
            );
            assert!(
                (st.piston_acceleration - a_fd).abs() < 1e-5 * scale_a,
                "a at φ = {phi}"
            );
            let beta = |a: f64| (p.crank_radius() / p.rod_length * a.sin()).asin();
            let bd_fd = w * derivative(beta, phi, h);
            assert!(
                (st.rod_angular_velocity - bd_fd).abs() < 1e-7 * w,
                "β̇ at φ = {phi}"
            );
            assert_eq!(st.rod_bearing_speed, -st.rod_angular_velocity);
        }
        // At TDC the classical result s̈ = −r Ω² (1 + λ).
        let st = p.state(0.0);
        let lambda = p.crank_radius() / p.rod_length;
        let want = -p.crank_radius() * w * w * (1.0 + lambda);
        assert!((st.piston_acceleration - want).abs() < 1e-12 * want.abs());
        assert!((st.rod_angular_velocity - w * lambda).abs() < 1e-12 * w);
    }

    #[test]
    fn cylinder_pressure_follows_the_ideal_cycle() {
        let p = params();
        assert_eq!(p.cylinder_pressure(0.0), p.discharge_pressure);
        assert!((p.cylinder_pressure(PI) - p.suction_pressure).abs() < 1e-9);
        let n = p.polytropic_exponent;
        // Compression: p V^n constant from BDC to the discharge point.
        let pv_bdc = p.suction_pressure * p.cylinder_volume(PI).powf(n);
        let v_disc =
            p.cylinder_volume(PI) * (p.suction_pressure / p.discharge_pressure).powf(1.0 / n);
        for k in 1..100 {
            let phi = PI + k as f64 * PI / 100.0;
            let v = p.cylinder_volume(phi);
            let pc = p.cylinder_pressure(phi);
            if v > v_disc {
                assert!((pc * v.powf(n) / pv_bdc - 1.0).abs() < 1e-12);
            } else {
                assert_eq!(pc, p.discharge_pressure);
            }
        }
        // Re-expansion: the suction starts where p_d V_c^n = p_s V^n.
        let v_suc =
            p.cylinder_volume(0.0) * (p.discharge_pressure / p.suction_pressure).powf(1.0 / n);
        for k in 1..100 {
            let phi = k as f64 * PI / 100.0;
            let v = p.cylinder_volume(phi);
            let pc = p.cylinder_pressure(phi);
            if v > v_suc {
                assert_eq!(pc, p.suction_pressure);
            } else {
                assert!(pc >= p.suction_pressure && pc <= p.discharge_pressure);
            }
        }
    }

    #[test]
    fn drive_work_per_revolution_equals_the_indicated_work() {
        // Energy balance: at constant Ω the inertia forces do no net work over a revolution, so
        // ∮ T dφ = ∮ (p − p_case) dV (the indicated work of the cycle). Independent of the force
        // path: the right side uses only the volume and pressure. Both integrals by the
        // trapezoidal rule on 20 000 points; the pressure has kinks, so the error is O(1/n²) of the
        // work, ~1e-6 relative; tolerance 1e-4.
        let p = params();
        let n = 20_000;
        let (mut torque_work, mut pv_work) = (0.0, 0.0);
        let dphi = TAU / n as f64;
        for k in 0..n {
            let (a, b) = (k as f64 * dphi, (k + 1) as f64 * dphi);
            let (sa, sb) = (p.state(a), p.state(b));
            torque_work += 0.5 * (sa.drive_torque + sb.drive_torque) * dphi;
            let dv = p.cylinder_volume(b) - p.cylinder_volume(a);
            pv_work -= 0.5
                * (sa.cylinder_pressure + sb.cylinder_pressure - 2.0 * p.crankcase_pressure)
                * dv;
        }
        assert!(pv_work > 0.0, "a compressor takes work");
        assert!(
            (torque_work - pv_work).abs() < 1e-4 * pv_work,
            "{torque_work} vs {pv_work}"
        );
    }

    #[test]
    fn massless_mechanism_carries_the_gas_force_along_the_rod() {
        // With no masses the rod force is F_g / cos β, the rod-frame load lies along the rod
        // (x of the rod frame), and the two main bearings share the reaction equally.
        let mut p = params();
        p.reciprocating_mass = 0.0;
        p.rotating_mass = 0.0;
        for k in 0..36 {
            let phi = k as f64 * TAU / 36.0;
            let st = p.state(phi);
            let fg = st.gas_force;
            assert!((st.rod_force - fg / st.rod_angle.cos()).abs() < 1e-9 * fg.abs().max(1.0));
            assert!((st.rod_load[0] - st.rod_force).abs() < 1e-9 * fg.abs().max(1.0));
            assert!(st.rod_load[1].abs() < 1e-9 * fg.abs().max(1.0));
            for i in 0..2 {
                let sum = st.main_load[i] * p.main_bearing_count + st.rod_load_machine[i];
                assert!(sum.abs() < 1e-9 * fg.abs().max(1.0));
            }
        }
    }

    #[test]
    fn feed_is_open_only_under_the_groove() {
        let p = params();
        let d = p.drilling;
        let half_arc = 0.5 * d.groove_length / d.main_journal_radius;
        let half_hole = 0.5 * d.hole_diameter / d.main_journal_radius;
        // Fully open at the groove centre, closed beyond the groove plus the hole's half width.
        assert_eq!(p.drilling_open_fraction(d.groove_center), 1.0);
        assert_eq!(
            p.drilling_open_fraction(d.groove_center + half_arc + half_hole + 1e-6),
            0.0
        );
        assert_eq!(
            p.drilling_open_fraction(d.groove_center - half_arc - half_hole - 1e-6),
            0.0
        );
        // Half open when the hole's centre is on the groove edge.
        assert!((p.drilling_open_fraction(d.groove_center + half_arc) - 0.5).abs() < 1e-9);
        // Closed: the drilling falls to the cavitation pressure (starvation).
        assert_eq!(p.rod_feed_pressure(0.0), d.cavitation_pressure);
        let centrifugal = 0.5
            * d.oil_density
            * p.crank_speed.powi(2)
            * (d.outlet_radius.powi(2) - d.main_journal_radius.powi(2));
        let open = p.rod_feed_pressure(d.groove_center);
        assert!((open - (d.main_feed_pressure + centrifugal)).abs() < 1e-9);
    }

    #[test]
    fn bad_parameters_are_named() {
        let mut p = params();
        p.rod_length = 0.01;
        match p.validate() {
            Err(SliderCrankError::InvalidParameter { name, .. }) => assert_eq!(name, "rod_length"),
            other => panic!("{other:?}"),
        }
        let mut p = params();
        p.bore = f64::NAN;
        assert!(p.tabulate(36).is_err());
    }
}
