//! The slider-crank of \[Flores2009\] §8 (Fig. 12) in minimal coordinates: closed-form kinematics of
//! the ideal mechanism, its inverse dynamics, and the equations of motion with a clearance joint
//! between rod and slider (see the parent module docs for the equations).

use super::MechanismError;

/// One link: length, mass, moment of inertia about its centre of mass, and where that is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    /// Length between the two joint centres (m).
    pub length: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Moment of inertia about the centre of mass (kg m²).
    pub inertia: f64,
    /// Distance of the centre of mass from the link's first joint (crank: the ground pivot O;
    /// rod: the crank pin A), along the link (m).
    pub center_of_mass: f64,
}

/// The mechanism: crank O–A driven at constant speed, rod A–B, slider at B on the x axis through
/// O (no offset).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankParams {
    /// Crank (body 2).
    pub crank: Link,
    /// Connecting rod (body 3).
    pub rod: Link,
    /// Slider mass (body 4, kg); its centre of mass is the joint centre B.
    pub slider_mass: f64,
    /// Constant crank speed ω (rad/s, counter-clockwise positive).
    pub crank_speed: f64,
    /// Crank angle at t = 0 (rad, from +x).
    pub initial_crank_angle: f64,
    /// Gravity acceleration (m/s², fixed frame; y up).
    pub gravity: [f64; 2],
}

impl SliderCrankParams {
    /// \[Flores2009\] Table 2 at 5000 rpm: crank 0.05 m, 0.30 kg, 1.0e-4 kg m²; rod 0.12 m, 0.21 kg,
    /// 2.5e-4 kg m²; slider 0.14 kg. Not in the paper (assumed): centres of mass at mid-length,
    /// crank angle 0 at t = 0, gravity 9.81 m/s² along −y (the mechanism in a vertical plane;
    /// 0.07 % of the slider's peak acceleration, so the choice hardly shows).
    pub fn flores2009() -> Self {
        Self {
            crank: Link {
                length: 0.05,
                mass: 0.30,
                inertia: 1.0e-4,
                center_of_mass: 0.025,
            },
            rod: Link {
                length: 0.12,
                mass: 0.21,
                inertia: 2.5e-4,
                center_of_mass: 0.06,
            },
            slider_mass: 0.14,
            crank_speed: 5000.0 * std::f64::consts::TAU / 60.0,
            initial_crank_angle: 0.0,
            gravity: [0.0, -9.81],
        }
    }

    /// Check every value: positive lengths and masses, rod longer than crank (plus clearance
    /// margin: `margin` m), finite speed and gravity.
    pub fn validate(&self, margin: f64) -> Result<(), MechanismError> {
        let bad = |name: &'static str, value: f64| MechanismError::InvalidParameter { name, value };
        for (name, v) in [
            ("crank.length", self.crank.length),
            ("crank.mass", self.crank.mass),
            ("rod.length", self.rod.length),
            ("rod.mass", self.rod.mass),
            ("slider_mass", self.slider_mass),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(name, v));
            }
        }
        for (name, v) in [
            ("crank.inertia", self.crank.inertia),
            ("rod.inertia", self.rod.inertia),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(bad(name, v));
            }
        }
        for (name, v) in [
            ("crank.center_of_mass", self.crank.center_of_mass),
            ("rod.center_of_mass", self.rod.center_of_mass),
            ("crank_speed", self.crank_speed),
            ("initial_crank_angle", self.initial_crank_angle),
            ("gravity x", self.gravity[0]),
            ("gravity y", self.gravity[1]),
        ] {
            if !v.is_finite() {
                return Err(bad(name, v));
            }
        }
        if self.crank_speed == 0.0 {
            return Err(bad("crank_speed", 0.0));
        }
        if self.rod.length <= self.crank.length + margin {
            return Err(bad(
                "rod.length (must exceed crank length + clearance)",
                self.rod.length,
            ));
        }
        Ok(())
    }

    /// Time of one crank turn (s).
    pub fn period(&self) -> f64 {
        std::f64::consts::TAU / self.crank_speed.abs()
    }

    /// Crank angle θ(t) (rad, not wrapped).
    pub fn crank_angle(&self, t: f64) -> f64 {
        self.initial_crank_angle + self.crank_speed * t
    }

    /// Crank pin A: position, velocity, acceleration at time t.
    pub(crate) fn crank_pin(&self, t: f64) -> [[f64; 2]; 3] {
        let (s, c) = self.crank_angle(t).sin_cos();
        let (r, w) = (self.crank.length, self.crank_speed);
        [
            [r * c, r * s],
            [-r * w * s, r * w * c],
            [-r * w * w * c, -r * w * w * s],
        ]
    }
}

/// Position, angle and velocities of one body (fixed frame).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodyState {
    /// Centre of mass (m).
    pub position: [f64; 2],
    /// Angle of the body axis from +x (rad).
    pub angle: f64,
    /// Velocity of the centre of mass (m/s).
    pub velocity: [f64; 2],
    /// Angular velocity (rad/s).
    pub angular_velocity: f64,
}

/// Forces and moments of the joints at one instant (fixed frame, N and N m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointLoads {
    /// Rod–slider joint: force on the rod (journal) from the slider (bearing). For the
    /// lubricated joint, the film (and contact) force; for the ideal joint, the reaction.
    pub rod_slider: [f64; 2],
    /// Crank pin A: force on the rod from the crank.
    pub crank_pin: [f64; 2],
    /// Main pivot O: force on the crank from the ground.
    pub ground_pivot: [f64; 2],
    /// Guide: normal force on the slider from the ground (along y).
    pub guide_normal: f64,
    /// Driving moment on the crank that keeps its speed constant (N m, counter-clockwise).
    pub crank_moment: f64,
    /// Moment of the rod–slider joint on the rod (journal) about the journal centre, N m
    /// (counter-clockwise positive): the film's friction torque and the dry contact's friction
    /// moment where those are switched on, else 0; the slider's guide takes the opposite
    /// moment (the slider does not rotate).
    pub rod_slider_torque: f64,
}

/// The mechanism's configuration at one instant, from the crank angle and the journal
/// eccentricity (rod angle φ₃, slider position x₄ and their rates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Configuration {
    pub t: f64,
    pub pin: [[f64; 2]; 3],
    /// (cos φ₃, sin φ₃)
    pub u: [f64; 2],
    pub rod_rate: f64,
    pub slider_x: f64,
    pub slider_rate: f64,
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl SliderCrankParams {
    /// Configuration for the journal eccentricity e = B_rod − B_slider (m) and its rate ė:
    /// e_y = A_y + L₃ sin φ₃ fixes φ₃ (cos φ₃ > 0: the slider to the right of the crank pin,
    /// which the assembled mechanism keeps), then x₄ = A_x + L₃ cos φ₃ − e_x.
    pub(crate) fn configuration(
        &self,
        t: f64,
        e: [f64; 2],
        e_rate: [f64; 2],
    ) -> Result<Configuration, MechanismError> {
        let pin = self.crank_pin(t);
        let l = self.rod.length;
        let s = (e[1] - pin[0][1]) / l;
        if s.is_nan() || s.abs() >= 1.0 {
            return Err(MechanismError::NonFinite {
                quantity: "rod angle (sin φ₃ outside (−1, 1))",
                time: t,
            });
        }
        let c = (1.0 - s * s).sqrt();
        let rod_rate = (e_rate[1] - pin[1][1]) / (l * c);
        Ok(Configuration {
            t,
            pin,
            u: [c, s],
            rod_rate,
            slider_x: pin[0][0] + l * c - e[0],
            slider_rate: pin[1][0] - l * s * rod_rate - e_rate[0],
        })
    }

    /// Rod and slider accelerations (φ̈₃, ẍ₄) for the joint force `f` on the rod at B and the
    /// joint's moment `torque` on the rod (minimal-coordinate equations of motion, module docs
    /// eqs. M1–M2).
    pub(crate) fn accelerations(&self, k: &Configuration, f: [f64; 2], torque: f64) -> [f64; 2] {
        let rod = &self.rod;
        let ja = rod.inertia + rod.mass * rod.center_of_mass * rod.center_of_mass;
        let g = self.gravity;
        let rel = [g[0] - k.pin[2][0], g[1] - k.pin[2][1]];
        let phi_dd =
            (rod.length * cross(k.u, f) + torque + rod.mass * rod.center_of_mass * cross(k.u, rel))
                / ja;
        let x_dd = (-f[0] + self.slider_mass * g[0]) / self.slider_mass;
        [phi_dd, x_dd]
    }

    /// ë of the journal eccentricity for the accelerations (φ̈₃, ẍ₄).
    pub(crate) fn eccentricity_acceleration(&self, k: &Configuration, acc: [f64; 2]) -> [f64; 2] {
        let l = self.rod.length;
        let [c, s] = k.u;
        let w2 = k.rod_rate * k.rod_rate;
        [
            k.pin[2][0] - l * (s * acc[0] + c * w2) - acc[1],
            k.pin[2][1] + l * (c * acc[0] - s * w2),
        ]
    }

    /// Bodies (crank, rod, slider) of a configuration.
    pub(crate) fn bodies(&self, k: &Configuration) -> [BodyState; 3] {
        let th = self.crank_angle(k.t);
        let (s2, c2) = th.sin_cos();
        let (d2, w) = (self.crank.center_of_mass, self.crank_speed);
        let d3 = self.rod.center_of_mass;
        let [c, s] = k.u;
        [
            BodyState {
                position: [d2 * c2, d2 * s2],
                angle: th,
                velocity: [-d2 * w * s2, d2 * w * c2],
                angular_velocity: w,
            },
            BodyState {
                position: [k.pin[0][0] + d3 * c, k.pin[0][1] + d3 * s],
                angle: s.atan2(c),
                velocity: [
                    k.pin[1][0] - d3 * s * k.rod_rate,
                    k.pin[1][1] + d3 * c * k.rod_rate,
                ],
                angular_velocity: k.rod_rate,
            },
            BodyState {
                position: [k.slider_x, 0.0],
                angle: 0.0,
                velocity: [k.slider_rate, 0.0],
                angular_velocity: 0.0,
            },
        ]
    }

    /// Joint loads for the configuration, its accelerations, the rod–slider force `f` and
    /// moment `torque` on the rod (module docs eqs. R1–R4).
    pub(crate) fn joint_loads(
        &self,
        k: &Configuration,
        acc: [f64; 2],
        f: [f64; 2],
        torque: f64,
    ) -> JointLoads {
        let (m2, m3, m4) = (self.crank.mass, self.rod.mass, self.slider_mass);
        let g = self.gravity;
        let d3 = self.rod.center_of_mass;
        let [c, s] = k.u;
        let w2 = k.rod_rate * k.rod_rate;
        let a3 = [
            k.pin[2][0] + d3 * (-s * acc[0] - c * w2),
            k.pin[2][1] + d3 * (c * acc[0] - s * w2),
        ];
        // Rod: m₃ a_G3 = F_A + F + m₃ g.
        let fa = [m3 * a3[0] - f[0] - m3 * g[0], m3 * a3[1] - f[1] - m3 * g[1]];
        // Crank (constant speed): m₂ a_G2 = F_O − F_A + m₂ g, M + r_A × (−F_A) + r_G2 × m₂ g = 0.
        let th = self.crank_angle(k.t);
        let (s2, c2) = th.sin_cos();
        let (d2, w) = (self.crank.center_of_mass, self.crank_speed);
        let a2 = [-d2 * w * w * c2, -d2 * w * w * s2];
        let fo = [
            m2 * a2[0] + fa[0] - m2 * g[0],
            m2 * a2[1] + fa[1] - m2 * g[1],
        ];
        let rg2 = [d2 * c2, d2 * s2];
        let moment = cross(k.pin[0], fa) - cross(rg2, [m2 * g[0], m2 * g[1]]);
        JointLoads {
            rod_slider: f,
            crank_pin: fa,
            ground_pivot: fo,
            guide_normal: f[1] - m4 * g[1],
            crank_moment: moment,
            rod_slider_torque: torque,
        }
    }

    /// The ideal mechanism (all joints ideal) at time t, in closed form: configuration with
    /// e = 0, accelerations, and the joint force at B from the inverse dynamics (module docs
    /// eq. I1).
    pub(crate) fn ideal(
        &self,
        t: f64,
    ) -> Result<(Configuration, [f64; 2], [f64; 2]), MechanismError> {
        let pin = self.crank_pin(t);
        let l = self.rod.length;
        // sin φ₃ = −A_y/L₃; φ̇₃ = −Ȧ_y/(L₃ cos φ₃); φ̈₃ = (−Ä_y + L₃ sin φ₃ φ̇₃²)/(L₃ cos φ₃).
        let k = self.configuration(t, [0.0, 0.0], [0.0, 0.0])?;
        let [c, s] = k.u;
        let phi_dd = (-pin[2][1] + l * s * k.rod_rate * k.rod_rate) / (l * c);
        let x_dd = pin[2][0] - l * (s * phi_dd + c * k.rod_rate * k.rod_rate);
        let acc = [phi_dd, x_dd];
        // Slider: m₄ ẍ₄ = −F_x + m₄ g_x. Rod: L₃ u × F = J_A φ̈₃ − m₃ d₃ u × (g − a_A).
        let m4 = self.slider_mass;
        let fx = m4 * (self.gravity[0] - x_dd);
        let rod = &self.rod;
        let ja = rod.inertia + rod.mass * rod.center_of_mass * rod.center_of_mass;
        let rel = [self.gravity[0] - pin[2][0], self.gravity[1] - pin[2][1]];
        let uxf = (ja * phi_dd - rod.mass * rod.center_of_mass * cross(k.u, rel)) / l;
        let fy = (uxf + s * fx) / c;
        Ok((k, acc, [fx, fy]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed-form ideal kinematics against central differences of the positions.
    #[test]
    fn ideal_kinematics_match_differences_of_the_positions() {
        let p = SliderCrankParams::flores2009();
        let h = 1e-7;
        for i in 0..12 {
            let t = i as f64 * p.period() / 12.0 + 1.3e-4;
            let pos = |t: f64| {
                let k = p.configuration(t, [0.0; 2], [0.0; 2]).unwrap();
                [k.u[1].atan2(k.u[0]), k.slider_x]
            };
            let (k, acc, _) = p.ideal(t).unwrap();
            let (a, b, m) = (pos(t - h), pos(t + h), pos(t));
            let vel = [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)];
            // Velocities are exact in configuration(e = 0, ė = 0): the journal follows the slider.
            assert!(
                (vel[0] - k.rod_rate).abs() < 1e-6 * 300.0,
                "{vel:?} {}",
                k.rod_rate
            );
            assert!((vel[1] - k.slider_rate).abs() < 1e-6 * 30.0);
            let h2 = 1e-5;
            let (a, b) = (pos(t - h2), pos(t + h2));
            for j in 0..2 {
                let fd = (b[j] - 2.0 * m[j] + a[j]) / (h2 * h2);
                // Second difference: truncation ~ h² f⁗/12 ≈ 1e-10 · ω⁴ · scale; round-off
                // ~ 1e-16 · 0.2 / 1e-10 ≈ 2e-7 · … : 1e-4 relative to ω² r.
                let scale = [p.crank_speed.powi(2), p.crank_speed.powi(2) * 0.05][j];
                assert!(
                    (fd - acc[j]).abs() < 1e-4 * scale,
                    "t {t} j {j}: {fd} vs {}",
                    acc[j]
                );
            }
        }
    }

    /// The ideal joint force, put back into the clearance-joint equations of motion, gives back
    /// the ideal accelerations: the two sets of equations are consistent.
    #[test]
    fn ideal_force_reproduces_ideal_accelerations() {
        let p = SliderCrankParams::flores2009();
        for i in 0..8 {
            let t = i as f64 * p.period() / 8.0 + 2e-5;
            let (k, acc, f) = p.ideal(t).unwrap();
            let back = p.accelerations(&k, f, 0.0);
            assert!((back[0] - acc[0]).abs() < 1e-9 * acc[0].abs().max(1e3));
            assert!((back[1] - acc[1]).abs() < 1e-9 * acc[1].abs().max(1e2));
            // ë = 0: the journal stays in the bearing centre.
            let ea = p.eccentricity_acceleration(&k, acc);
            assert!(ea[0].abs() < 1e-8 && ea[1].abs() < 1e-8, "{ea:?}");
        }
    }
}
