//! Time discretization shared by every film of the crate: the Reynolds film
//! ([`crate::reynolds::ReynoldsSolver::solve_step`]) and the analytic short-bearing film of the
//! inverse solver ([`crate::closed_form::ClosedFormFilm`]). One enum and one default (BDF2),
//! used alike by the library, the application's case files and the validation tests.

/// How a film advances from t^n to t^{n+1} = t^n + Δt_n.
///
/// For the Reynolds film, with content c = h φ and net outflow D(c) of a node (docs/conventions.md §2)
/// (the short-bearing film applies the same difference formulas to ε, giving ε̇^{n+1}):
///
/// ```text
///   backward Euler:  (c^{n+1} − c^n)/Δt + D^{n+1} = 0
///   BDF2:            (a₀ c^{n+1} − a₁ c^n + a₂ c^{n−1})/Δt_n + D^{n+1} = 0,
///                    ω = Δt_n/Δt_{n−1}, a₀ = (1+2ω)/(1+ω), a₁ = 1+ω, a₂ = ω²/(1+ω)
///   Crank–Nicolson:  (c^{n+1} − c^n)/Δt + ½ (D^{n+1} + D^n) = 0
/// ```
///
/// BDF2 with variable steps (Hairer, Nørsett & Wanner, *Solving ODEs I*, §III.5) is
/// backward Euler with Δt_eff = Δt_n/a₀ and the old content (a₁ c^n − a₂ c^{n−1})/a₀: the same
/// frozen-switch systems and M-matrices. It starts with a backward-Euler step (no c^{n−1}) and
/// falls back to one where its answer would have a negative film content (BDF2 does not
/// preserve positivity). Crank–Nicolson is not L-stable: on the stiff Elrod pressure modes its
/// amplification tends to −1 and the film rings from step to step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TimeScheme {
    /// Backward Euler: first order, L-stable.
    BackwardEuler,
    /// Variable-step BDF2: second order, L-stable at constant steps (zero-stable for step ratios
    /// ω < 1 + √2, \[Grigorieff1983\]).
    #[default]
    Bdf2,
    /// Crank–Nicolson (trapezoidal): second order, A- but not L-stable.
    CrankNicolson,
}

impl TimeScheme {
    /// Coefficients (a₀, a₁, a₂) of variable-step BDF2,
    /// y'(t^{n+1}) ≈ (a₀ y^{n+1} − a₁ y^n + a₂ y^{n−1}) / Δt_n, for the step ratio
    /// ω = Δt_n / Δt_{n−1} (Hairer, Nørsett & Wanner, *Solving ODEs I*, §III.5).
    pub fn bdf2_coefficients(step_ratio: f64) -> (f64, f64, f64) {
        let w = step_ratio;
        ((1.0 + 2.0 * w) / (1.0 + w), 1.0 + w, w * w / (1.0 + w))
    }

    /// The name used in case files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            TimeScheme::BackwardEuler => "backward_euler",
            TimeScheme::Bdf2 => "bdf2",
            TimeScheme::CrankNicolson => "crank_nicolson",
        }
    }
}

/// The state of an analytic film at t^n: the journal centre's position, velocity and the
/// level before (what BDF2 needs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JournalMotion {
    /// ε^n.
    pub eccentricity_ratio: [f64; 2],
    /// dε/dt at t^n (1/s).
    pub eccentricity_rate: [f64; 2],
    /// ε^{n−1} and the step from t^{n−1} to t^n (None at the start: the first BDF2 step is a
    /// backward-Euler step).
    pub previous: Option<([f64; 2], f64)>,
}

impl JournalMotion {
    /// At ε, at rest, with no history.
    pub fn at_rest(eccentricity_ratio: [f64; 2]) -> Self {
        Self {
            eccentricity_ratio,
            eccentricity_rate: [0.0; 2],
            previous: None,
        }
    }

    /// The state at t^{n+1} = t^n + dt with ε^{n+1} = `eccentricity_ratio`: its velocity
    /// ε̇^{n+1} by the scheme's difference formula,
    ///
    /// ```text
    ///   backward Euler:  ε̇^{n+1} = (ε^{n+1} − ε^n)/Δt
    ///   BDF2:            ε̇^{n+1} = (a₀ ε^{n+1} − a₁ ε^n + a₂ ε^{n−1})/Δt
    ///   Crank–Nicolson:  ε̇^{n+1} = 2 (ε^{n+1} − ε^n)/Δt − ε̇^n   (trapezoidal rule on ε)
    /// ```
    pub fn advance(&self, scheme: TimeScheme, eccentricity_ratio: [f64; 2], dt: f64) -> Self {
        let (e1, e0) = (eccentricity_ratio, self.eccentricity_ratio);
        let d = [(e1[0] - e0[0]) / dt, (e1[1] - e0[1]) / dt];
        let rate = match (scheme, self.previous) {
            (TimeScheme::CrankNicolson, _) => [
                2.0 * d[0] - self.eccentricity_rate[0],
                2.0 * d[1] - self.eccentricity_rate[1],
            ],
            (TimeScheme::Bdf2, Some((em, dt_prev))) => {
                let (a0, a1, a2) = TimeScheme::bdf2_coefficients(dt / dt_prev);
                [
                    (a0 * e1[0] - a1 * e0[0] + a2 * em[0]) / dt,
                    (a0 * e1[1] - a1 * e0[1] + a2 * em[1]) / dt,
                ]
            }
            (TimeScheme::BackwardEuler | TimeScheme::Bdf2, _) => d,
        };
        Self {
            eccentricity_ratio,
            eccentricity_rate: rate,
            previous: Some((e0, dt)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{JournalMotion, TimeScheme};

    /// The journal velocity on a circular whirl, started from the exact orbit: step halving
    /// gives the observed order of the velocity error: at least 1 (backward Euler), 2 (BDF2)
    /// and 2 (Crank–Nicolson; after an even number of steps its alternating error cancels to
    /// third order here), less 0.15.
    #[test]
    fn journal_velocity_orders_on_a_whirl() {
        let (r, w) = (0.5, 3.0);
        let pos = |t: f64| [r * (w * t).cos(), r * (w * t).sin()];
        let vel = |t: f64| [-r * w * (w * t).sin(), r * w * (w * t).cos()];
        for (scheme, order) in [
            (TimeScheme::BackwardEuler, 1.0),
            (TimeScheme::Bdf2, 2.0),
            (TimeScheme::CrankNicolson, 2.0),
        ] {
            let err = |dt: f64| {
                // Start exactly (rate and history from the exact orbit), then 8 steps.
                let mut m = JournalMotion {
                    eccentricity_ratio: pos(0.0),
                    eccentricity_rate: vel(0.0),
                    previous: Some((pos(-dt), dt)),
                };
                for n in 1..=8 {
                    m = m.advance(scheme, pos(n as f64 * dt), dt);
                }
                let v = vel(8.0 * dt);
                (m.eccentricity_rate[0] - v[0]).hypot(m.eccentricity_rate[1] - v[1])
            };
            let observed = (err(0.02) / err(0.01)).log2();
            assert!(
                observed > order - 0.15,
                "{scheme:?}: observed order {observed}, expected at least {order}"
            );
        }
    }

    /// BDF2's weights differentiate quadratics exactly for any step ratio.
    #[test]
    fn bdf2_is_exact_for_quadratics() {
        for w in [0.25, 0.5, 1.0, 1.7, 2.4] {
            let (a0, a1, a2) = TimeScheme::bdf2_coefficients(w);
            let (dt, dt_prev) = (0.3 * w, 0.3);
            let y = |t: f64| 2.0 - 0.7 * t + 1.3 * t * t;
            let dy = |t: f64| -0.7 + 2.6 * t;
            let t1 = 1.0;
            let approx = (a0 * y(t1) - a1 * y(t1 - dt) + a2 * y(t1 - dt - dt_prev)) / dt;
            assert!(
                (approx - dy(t1)).abs() < 1e-12,
                "ω = {w}: {approx} vs {}",
                dy(t1)
            );
        }
    }
}
