//! Local error control of the cycle steps: which steps of the load cycle are taken in
//! substeps, and how many.
//!
//! # The estimate (Milne's device)
//!
//! The march records the journal at the ends of N equal steps of Δt per cycle; its three last
//! positions ε^n, ε^{n−1}, ε^{n−2} give a predictor for ε^{n+1}, and the difference between the
//! step's converged answer and that prediction estimates the step's local error
//! (\[HairerNorsettWanner1993\] §III.7, "Milne's device"). With y''' (y'') the third
//! (second) time derivative of ε:
//!
//! ```text
//!   scheme          predictor                       ε^{n+1} − exact         ε^{n+1} − predictor
//!   BDF2            P₂ = 3ε^n − 3ε^{n−1} + ε^{n−2}   (2/9)  Δt³ y'''         (11/9)  Δt³ y'''
//!   Crank–Nicolson  P₂                              (1/12) Δt³ y'''         (13/12) Δt³ y'''
//!   backward Euler  P₁ = 2ε^n − ε^{n−1}              (1/2)  Δt² y''          (3/2)   Δt² y''
//!
//!   local error of the step:  est = C/(1+C) · |ε^{n+1} − P|     C = 2/9, 1/12, 1/2
//! ```
//!
//! (Each row: the scheme applied to y' = f(t) with exact past values, Taylor-expanded about
//! t^{n+1}; the extrapolation error of P₂ is Δt³ y''' and of P₁ Δt² y''.) When the step was
//! taken in substeps its end is close to the exact value, and the same full-step error is
//! est = C · |ε^{n+1} − P|.
//!
//! Crank–Nicolson is not controlled. It is not L-stable: after a sharp event its stiff film
//! modes ring with an amplification near −1 per step whatever the step, so the predictor
//! difference measures the ringing, and substeps do not reduce it (measured on the sharp-load
//! validation test, 48 × 13, 4° steps against 0.25°: the orbit off by 7.5e-3 uncontrolled and
//! 1.1e-2 with substeps). Its estimate constant stays in the table for the record.
//!
//! # The rule
//!
//! A step whose estimate exceeds the tolerance tol (in ε, [`super::InverseParams::step_error_tolerance`])
//! is taken again from its start in 2^k equal substeps, k the least level with
//! est / 2^{k·p} ≤ tol (p = 2 for BDF2 and Crank–Nicolson, 1 for backward Euler: the error of
//! the 2^k substeps together, each est/2^{k(p+1)}), at most
//! [`super::InverseParams::max_step_splits`]. Only the step's end enters the results.
//!
//! Each step of the cycle remembers its level, and a later cycle never takes that step with
//! fewer substeps: the cycle-to-cycle map is then one fixed discrete map once the levels have
//! settled, so the periodicity test compares like with like. Without the memory a step whose
//! estimate lies near a threshold is refined in one cycle and not in the next, and the orbit
//! jumps by the step's own error (the compressor rod's discharge step, 0.03 in ε at 2°: the
//! measurement in docs/results.md).
//!
//! ```text
//!   cycle step i:  level[i] = 0 ──full step──> est ≤ tol ? accept : level[i] = k(est), substeps
//!                  level[i] = k > 0 ──2^k substeps──> est from the end; k(est) > k ? raise, redo
//! ```

use super::TimeScheme;

/// The error control of one inverse solve (cycle steps only; the run-in ramp is not
/// controlled: only where it ends matters).
pub(super) struct ErrorControl {
    scheme: TimeScheme,
    tolerance: f64,
    max_level: usize,
    /// The level (halvings) each step of the cycle took in the cycles so far; never lowered.
    levels: Vec<usize>,
}

impl ErrorControl {
    /// Control for a film of `scheme`, `steps` steps per cycle, tolerance `tolerance` (in ε) and
    /// at most `max_level` halvings; None when the tolerance is 0 (control off) and for
    /// Crank–Nicolson (module docs: its error at a sharp event is ringing, which substeps do not
    /// reduce).
    pub(super) fn new(
        scheme: TimeScheme,
        tolerance: f64,
        max_level: usize,
        steps: usize,
    ) -> Option<Self> {
        (tolerance > 0.0 && scheme != TimeScheme::CrankNicolson).then(|| Self {
            scheme,
            tolerance,
            max_level,
            levels: vec![0; steps],
        })
    }

    /// The level step `i` of the cycle took last time.
    pub(super) fn level(&self, i: usize) -> usize {
        self.levels[i]
    }

    /// Levels from an earlier solve of the same grid (ignored when the grid differs).
    pub(super) fn start_from(&mut self, levels: &[usize]) {
        if levels.len() == self.levels.len() {
            for (mine, &theirs) in self.levels.iter_mut().zip(levels) {
                *mine = theirs.min(self.max_level);
            }
        }
    }

    /// The levels of the cycle's steps.
    pub(super) fn levels(&self) -> &[usize] {
        &self.levels
    }

    /// The most halvings of a step.
    pub(super) fn max_level(&self) -> usize {
        self.max_level
    }

    /// Remember that step `i` was taken at `level` (never lowered).
    pub(super) fn raise(&mut self, i: usize, level: usize) {
        self.levels[i] = self.levels[i].max(level);
    }

    /// The estimate of the full step's local error (in ε) from its end `eps_end` and the three
    /// positions before it, `history = [ε^n, ε^{n−1}, ε^{n−2}]` at equal steps; `substepped`
    /// says whether `eps_end` came from substeps (module docs).
    pub(super) fn estimate(
        &self,
        eps_end: [f64; 2],
        history: [[f64; 2]; 3],
        substepped: bool,
    ) -> f64 {
        local_error(self.scheme, eps_end, history, substepped)
    }

    /// The least level k with est / 2^{k·p} ≤ tolerance, at most the maximum.
    pub(super) fn level_for(&self, estimate: f64) -> usize {
        let p = match self.scheme {
            TimeScheme::BackwardEuler => 1,
            TimeScheme::Bdf2 | TimeScheme::CrankNicolson => 2,
        };
        let mut k = 0;
        while k < self.max_level && estimate / f64::powi(2.0, (k * p) as i32) > self.tolerance {
            k += 1;
        }
        k
    }

    /// Steps of the cycle taken in substeps now, and the largest level.
    pub(super) fn refined(&self) -> (usize, usize) {
        let n = self.levels.iter().filter(|&&k| k > 0).count();
        (n, self.levels.iter().copied().max().unwrap_or(0))
    }
}

/// Milne's estimate of the local error of a full step of `scheme` (module docs).
fn local_error(
    scheme: TimeScheme,
    eps_end: [f64; 2],
    history: [[f64; 2]; 3],
    substepped: bool,
) -> f64 {
    let [e0, e1, e2] = history;
    let (prediction, c) = match scheme {
        TimeScheme::Bdf2 => (quadratic(e0, e1, e2), 2.0 / 9.0),
        TimeScheme::CrankNicolson => (quadratic(e0, e1, e2), 1.0 / 12.0),
        TimeScheme::BackwardEuler => ([2.0 * e0[0] - e1[0], 2.0 * e0[1] - e1[1]], 0.5),
    };
    let d = (eps_end[0] - prediction[0]).hypot(eps_end[1] - prediction[1]);
    if substepped { c * d } else { c / (1.0 + c) * d }
}

/// The quadratic extrapolation 3ε^n − 3ε^{n−1} + ε^{n−2} of three equally spaced positions
/// (the march's predictor before its pull-back from the wall, and Milne's P₂).
pub(super) fn quadratic(e0: [f64; 2], e1: [f64; 2], e2: [f64; 2]) -> [f64; 2] {
    [3.0 * (e0[0] - e1[0]) + e2[0], 3.0 * (e0[1] - e1[1]) + e2[1]]
}

/// ε at time `t` from the quadratic (linear with two points) through the last points `(t_k,
/// ε_k)` of `points` (Lagrange form): the Newton guess of a substep.
pub(super) fn extrapolate(points: &[(f64, [f64; 2])], t: f64) -> [f64; 2] {
    let pts = &points[points.len().saturating_sub(3)..];
    let mut out = [0.0; 2];
    for (j, &(tj, ej)) in pts.iter().enumerate() {
        let mut w = 1.0;
        for (k, &(tk, _)) in pts.iter().enumerate() {
            if k != j {
                w *= (t - tk) / (tj - tk);
            }
        }
        out[0] += w * ej[0];
        out[1] += w * ej[1];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Milne's constants: applied to the exact scheme on y' = f(t) with a cubic (quadratic for
    /// backward Euler) solution, the estimate equals the true local error.
    #[test]
    fn the_estimate_is_the_local_error_on_polynomials() {
        let h = 0.1;
        // y = t³ along ε_x (y''' = 6), the step ending at t = 1.
        let y = |t: f64| t * t * t;
        let dy = |t: f64| 3.0 * t * t;
        let hist = [
            [y(1.0 - h), 0.0],
            [y(1.0 - 2.0 * h), 0.0],
            [y(1.0 - 3.0 * h), 0.0],
        ];
        // BDF2: (3/2 y1 − 2 y0 + 1/2 y−1)/h = f(1)
        let bdf2 = (h * dy(1.0) + 2.0 * hist[0][0] - 0.5 * hist[1][0]) / 1.5;
        // CN: y1 = y0 + h/2 (f(1) + f(1 − h))
        let cn = hist[0][0] + 0.5 * h * (dy(1.0) + dy(1.0 - h));
        for (scheme, num) in [(TimeScheme::Bdf2, bdf2), (TimeScheme::CrankNicolson, cn)] {
            let est = local_error(scheme, [num, 0.0], hist, false);
            let truth = (num - y(1.0)).abs();
            assert!(
                (est - truth).abs() < 1e-12 * truth.max(1.0),
                "{scheme:?}: {est} vs {truth}"
            );
            // From the exact end (a well-substepped step) the same error.
            let est = local_error(scheme, [y(1.0), 0.0], hist, true);
            assert!((est - truth).abs() < 1e-12, "{scheme:?}: {est} vs {truth}");
        }
        // backward Euler on y = t² (y'' = 2).
        let y = |t: f64| t * t;
        let hist = [[y(1.0 - h), 0.0], [y(1.0 - 2.0 * h), 0.0], [0.0, 0.0]];
        let be = hist[0][0] + h * 2.0;
        let truth = (be - y(1.0)).abs();
        let est = local_error(TimeScheme::BackwardEuler, [be, 0.0], hist, false);
        assert!((est - truth).abs() < 1e-12, "{est} vs {truth}");
    }

    /// Levels: the least k with est/2^{kp} ≤ tol, capped.
    #[test]
    fn levels_follow_the_order_of_the_scheme() {
        let c = ErrorControl::new(TimeScheme::Bdf2, 1e-3, 4, 3).unwrap();
        assert_eq!(c.level_for(1e-3), 0);
        assert_eq!(c.level_for(3.9e-3), 1);
        assert_eq!(c.level_for(4.1e-3), 2);
        assert_eq!(c.level_for(0.0285), 3);
        assert_eq!(c.level_for(1.0), 4);
        let c = ErrorControl::new(TimeScheme::BackwardEuler, 1e-3, 4, 3).unwrap();
        assert_eq!(c.level_for(1.9e-3), 1);
        assert_eq!(c.level_for(2.1e-3), 2);
        assert!(ErrorControl::new(TimeScheme::Bdf2, 0.0, 4, 3).is_none());
        assert!(ErrorControl::new(TimeScheme::CrankNicolson, 1e-3, 4, 3).is_none());
        let mut c = c;
        c.raise(1, 2);
        c.raise(1, 1);
        assert_eq!((c.level(1), c.refined()), (2, (1, 2)));
    }

    /// The substep guess reproduces quadratics from unequal points.
    #[test]
    fn substep_guess_is_exact_for_quadratics() {
        let f = |t: f64| [1.0 + 2.0 * t - 3.0 * t * t, -t * t];
        let pts: Vec<_> = [0.0, 0.5, 0.75, 0.875].iter().map(|&t| (t, f(t))).collect();
        let g = extrapolate(&pts, 1.0);
        assert!((g[0] - f(1.0)[0]).abs() < 1e-12 && (g[1] - f(1.0)[1]).abs() < 1e-12);
    }
}
