//! Extrapolation of the cycle-to-cycle map: a periodic orbit in fewer marched cycles.
//!
//! # What it solves
//!
//! Marching cycle after cycle is the fixed-point iteration x_{j+1} = G(x_j) of the cycle map G:
//! x is the state at the start of a cycle (the journal's last three positions and the film's
//! state, [`super::FilmModel::state_vector`]) and G marches one load cycle from it. Near the
//! periodic orbit x* the error falls with the eigenvalues of G's linearization; a starved film
//! fills slowly (the compressor rod: two modes of about ±0.6 per cycle, docs/results.md), so
//! the plain iteration needs ~15 cycles for |Δε| ≤ 1e-3.
//!
//! Minimal polynomial extrapolation (MPE; \[CabayJackson1976\], \[Sidi2017\] chs. 1–2)
//! removes the k slowest modes from k + 2 successive states x_0 … x_{k+1} of plain cycles,
//! u_j = x_{j+1} − x_j:
//!
//! ```text
//!   min ‖Σ_j c_j u_j‖₂  subject to  Σ_j c_j = 1      (j = 0 … k)
//!     ⇔  c = G⁻¹1 / (1ᵀG⁻¹1),  G_ij = u_i · u_j       (the (k+1)² Gram matrix)
//!   s = Σ_j c_j x_{j+1}
//! ```
//!
//! exact when G is linear with k + 1 modes. The march continues from s; the cycle after the
//! jump is never periodic (the test compares two marched cycles: the jump's cycle and the next),
//! so the answer is a marched periodic cycle as without extrapolation, and the same one to the
//! periodicity tolerance.
//!
//! # When
//!
//! With the changes of a cycle measured in units of the periodicity tolerances, m_ε = |Δε|/tol_ε
//! and m_φ = |Δφ|/tol_φ (the test holds when both are ≤ 1): after a plain cycle c that is not
//! periodic, when the window holds k + 2 = 4 states of plain cycles (k = 2), 5 < max(m_ε, m_φ)
//! ≤ 100 (above the noise of the Newton and film tolerances, and near the map's linear regime:
//! |Δε| ≤ 0.1 at the default tolerance) and the plain iteration would still need more than 3.5
//! cycles by one of the measures at its observed contraction r = m_c / m_{c−1}: ln(1/m_c) / ln r
//! (r ≥ 1 counts as more). An extrapolation costs two cycles at least (the jump's cycle, never
//! compared, and the comparison), and the contraction seen early overstates what is left. The
//! flooded main bearing (periodic after 5 cycles) is not extrapolated; the starved rod is, twice
//! (docs/results.md).
//!
//! ```text
//!   x_0 ─G─> x_1 ─G─> x_2 ─G─> x_3      window of plain cycles (4 states)
//!                                └─ MPE ─> s ─G─> G(s) ─G─> …  (window restarts at s)
//! ```

use faer::prelude::Solve;

/// Polynomial degree k of the extrapolation (modes removed − 1 … the window holds k + 2).
const DEGREE: usize = 2;
/// Largest change of the last cycle, in units of the periodicity tolerances, for which the map
/// is treated as linear (100: |Δε| 0.1 at the default tolerance 1e-3).
const LINEAR_REGIME: f64 = 100.0;
/// Cycles the plain iteration must still need for an extrapolation: it costs two at least (the
/// jump's cycle, never compared, and the comparison), and the contraction seen early in a run
/// overstates what is left (the flooded main bearing after cycle 3: 3.2 cycles estimated from
/// |Δφ|, two needed).
const MIN_CYCLES_SAVED: f64 = 3.5;
/// Smallest change of the last cycle, in units of the tolerances, worth an extrapolation: near
/// the tolerance the cycle-to-cycle differences are the Newton's and the film solver's noise as
/// much as the map's modes, and an extrapolation from them costs cycles (measured on the rod:
/// a jump at 1.2 × the tolerance was followed by three cycles at 1.7 ×).
const NOISE_FLOOR: f64 = 5.0;

/// The window of cycle-start states and the rule of the module docs.
pub(super) struct CycleExtrapolation {
    /// States of successive plain cycles (the first the start of the window).
    states: Vec<Vec<f64>>,
    /// The changes of each plain cycle of the window, [|Δε|/tol_ε, |Δφ|/tol_φ] (∞ where not
    /// assessed).
    changes: Vec<[f64; 2]>,
    /// Extrapolations made.
    pub(super) count: usize,
}

impl CycleExtrapolation {
    pub(super) fn new() -> Self {
        Self {
            states: Vec::new(),
            changes: Vec::new(),
            count: 0,
        }
    }

    /// Start the window at `state` (the start of the next cycle, after a jump or at the first
    /// cycle).
    pub(super) fn restart(&mut self, state: Vec<f64>) {
        self.states = vec![state];
        self.changes.clear();
    }

    /// The end of a plain cycle, with its changes [|Δε|/tol_ε, |Δφ|/tol_φ] (the periodicity
    /// test holds when both are ≤ 1), and — by the rule of the module docs — the extrapolated
    /// state to continue from, if any. A state whose length differs from the
    /// window's (the film changed its layout) restarts the window.
    pub(super) fn push(&mut self, state: Vec<f64>, changes: [f64; 2]) -> Option<Vec<f64>> {
        if self.states.first().is_some_and(|s| s.len() != state.len()) {
            self.restart(state);
            return None;
        }
        self.states.push(state);
        self.changes.push(changes);
        if self.states.len() > DEGREE + 2 {
            self.states.remove(0);
            self.changes.remove(0);
        }
        if self.states.len() < DEGREE + 2 || !self.worth_it() {
            return None;
        }
        let s = mpe(&self.states)?;
        self.count += 1;
        Some(s)
    }

    /// The rule: near-linear and slow enough that an extrapolation saves cycles.
    fn worth_it(&self) -> bool {
        let n = self.changes.len();
        let (last, before) = (self.changes[n - 1], self.changes[n - 2]);
        let m = last[0].max(last[1]);
        if !(m.is_finite() && m <= LINEAR_REGIME && m > NOISE_FLOOR) {
            return false;
        }
        // Cycles the plain iteration still needs, per measure, at its observed contraction.
        let remaining = |k: usize| {
            let (l, b) = (last[k], before[k]);
            if l <= 1.0 {
                0.0
            } else if !(b.is_finite() && b > 0.0) || l >= b {
                f64::INFINITY
            } else {
                (1.0 / l).ln() / (l / b).ln()
            }
        };
        remaining(0).max(remaining(1)) > MIN_CYCLES_SAVED
    }
}

/// MPE of the module docs from the states x_0 … x_{k+1}; None when the Gram system is
/// singular or the answer is not finite.
fn mpe(states: &[Vec<f64>]) -> Option<Vec<f64>> {
    let k1 = states.len() - 1;
    let diffs: Vec<Vec<f64>> = states
        .windows(2)
        .map(|w| w[1].iter().zip(&w[0]).map(|(a, b)| a - b).collect())
        .collect();
    let mut gram = faer::Mat::<f64>::zeros(k1, k1);
    for i in 0..k1 {
        for j in 0..=i {
            let g: f64 = diffs[i].iter().zip(&diffs[j]).map(|(a, b)| a * b).sum();
            gram[(i, j)] = g;
            gram[(j, i)] = g;
        }
    }
    // A tiny Tikhonov shift keeps nearly dependent differences solvable (it changes c by a
    // relative 1e-12).
    let shift = 1e-12 * (0..k1).map(|i| gram[(i, i)]).sum::<f64>();
    for i in 0..k1 {
        gram[(i, i)] += shift;
    }
    let y = gram
        .partial_piv_lu()
        .solve(&faer::Mat::<f64>::from_fn(k1, 1, |_, _| 1.0));
    let y: Vec<f64> = (0..k1).map(|i| y[(i, 0)]).collect();
    let sum: f64 = y.iter().sum();
    if !(sum.is_finite() && sum.abs() > 0.0) {
        return None;
    }
    let c: Vec<f64> = y.iter().map(|v| v / sum).collect();
    let n = states[0].len();
    let s: Vec<f64> = (0..n)
        .map(|m| {
            c.iter()
                .enumerate()
                .map(|(j, cj)| cj * states[j + 1][m])
                .sum()
        })
        .collect();
    s.iter().all(|v| v.is_finite()).then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear map with two modes (+0.6 and −0.6, as the rod's fill) and a fixed point: MPE of
    /// degree 2 from four successive states lands on the fixed point to round-off.
    #[test]
    fn mpe_removes_two_modes_of_a_linear_map() {
        let fixed = [0.3, -0.2, 0.7, 1.1];
        // x_{j+1} − x* = A (x_j − x*), A with eigenvalues 0.6 and −0.6 on a rotated basis and 0
        // elsewhere.
        let g = |x: &[f64]| -> Vec<f64> {
            let d: Vec<f64> = x.iter().zip(&fixed).map(|(a, b)| a - b).collect();
            let a = 0.6 * (d[0] + d[1]) / 2.0;
            let b = -0.6 * (d[0] - d[1]) / 2.0;
            vec![fixed[0] + a + b, fixed[1] + a - b, fixed[2], fixed[3]]
        };
        let mut x = vec![vec![1.0, 0.5, 0.0, 0.0]];
        for _ in 0..3 {
            let next = g(x.last().unwrap());
            x.push(next);
        }
        let s = mpe(&x).unwrap();
        for (a, b) in s.iter().zip(&fixed) {
            assert!((a - b).abs() < 1e-9, "{s:?}");
        }
    }

    /// The rule (changes in units of the tolerances): no extrapolation far from linear, none
    /// for a fast map, one for a slow one.
    #[test]
    fn extrapolates_only_slow_near_linear_maps() {
        let mut e = CycleExtrapolation::new();
        e.restart(vec![0.0, 0.0]);
        let inf = f64::INFINITY;
        assert!(e.push(vec![1.0, 0.0], [inf, 900.0]).is_none());
        assert!(e.push(vec![1.5, 0.1], [500.0, 300.0]).is_none());
        // 4 states, but the change 300 is outside the linear regime.
        assert!(e.push(vec![1.7, 0.1], [300.0, 200.0]).is_none());
        // fast: 10 after 300 and 8 after 200: one more cycle reaches 1.
        assert!(e.push(vec![1.71, 0.1], [10.0, 8.0]).is_none());
        // The main bearing after cycle 3: ε 20.8 after 195, φ 58 after 206 (3.2 cycles left).
        let mut e = CycleExtrapolation::new();
        e.restart(vec![0.0, 0.0]);
        e.push(vec![1.0, 0.0], [inf, 811.0]);
        e.push(vec![1.2, 0.1], [195.0, 206.0]);
        assert!(e.push(vec![1.22, 0.1], [20.8, 58.0]).is_none());
        // slow: ε 50 after 83 → ln(1/50)/ln(0.6) = 7.7 cycles.
        let mut e = CycleExtrapolation::new();
        e.restart(vec![0.0, 0.0]);
        e.push(vec![0.1, 0.02], [inf, 100.0]);
        e.push(vec![0.16, 0.01], [83.0, 20.0]);
        assert!(e.push(vec![0.196, 0.016], [50.0, 10.0]).is_some());
        assert_eq!(e.count, 1);
    }
}
