//! Step-to-step smoothness of a sampled periodic series (issue 11, item 8: "no step-to-step
//! saw-tooth in supply or side leakage").
//!
//! For samples x_0 … x_{N−1} of one period (x_N = x_0), first and second differences
//!
//! ```text
//!   d_i = x_{i+1} − x_i ,        d²_i = x_{i+1} − 2 x_i + x_{i−1} = d_i − d_{i−1}
//! ```
//!
//! and three measures, each relative to the range R = max x − min x:
//!
//! - **largest second difference** max |d²_i| / R: the sharpest bend of the sampled series. A
//!   smooth signal gives O(Δt²), a kink O(Δt), a jump of size J within one step J / R — so it
//!   measures the sharpness of the events as much as any ringing: a load or feed that changes
//!   within a step has a large one itself (the same measure of the drive says how large);
//! - **zigzag amplitude** max over i of min(|d_{i−1}|, |d_i|, |d_{i+1}|) where the three
//!   alternate in sign (d_{i−1} d_i < 0 and d_i d_{i+1} < 0: a local maximum and a local minimum
//!   one step apart), else 0 — the step-to-step oscillation itself. A saw-tooth of amplitude a
//!   (x_i = s(t_i) + a (−1)^i on a slowly varying s) gives ≈ 2a; a monotone jump, a kink or a
//!   single overshoot give 0; a smooth extremum gives 0 (its neighbours' differences do not
//!   alternate twice);
//! - **sign changes** of d over the period: ~N for a saw-tooth all along, a few per extremum for
//!   a smooth signal.

/// The measures of one series (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Smoothness {
    /// max |d²_i| / R.
    pub max_second_difference: f64,
    /// The sample index i of that second difference.
    pub max_second_difference_at: usize,
    /// The zigzag amplitude / R.
    pub zigzag: f64,
    /// The sample index of the largest zigzag (0 when there is none).
    pub zigzag_at: usize,
    /// Sign changes of the first difference over the period.
    pub sign_changes: usize,
}

/// The measures of one period of samples `x` (at least 3); None for a constant series (R = 0)
/// or one with a non-finite sample.
pub fn smoothness(x: &[f64]) -> Option<Smoothness> {
    let n = x.len();
    if n < 3 || x.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let range = hi - lo;
    if range <= 0.0 {
        return None;
    }
    let d: Vec<f64> = (0..n).map(|i| x[(i + 1) % n] - x[i]).collect();
    let before = |i: usize| d[(i + n - 1) % n];
    let mut out = Smoothness {
        max_second_difference: 0.0,
        max_second_difference_at: 0,
        zigzag: 0.0,
        zigzag_at: 0,
        sign_changes: 0,
    };
    for i in 0..n {
        let (dm, d0, dp) = (before(i), d[i], d[(i + 1) % n]);
        let second = (d0 - dm).abs() / range;
        if second > out.max_second_difference {
            out.max_second_difference = second;
            out.max_second_difference_at = i;
        }
        if dm * d0 < 0.0 {
            out.sign_changes += 1;
            if d0 * dp < 0.0 {
                let zigzag = dm.abs().min(d0.abs()).min(dp.abs()) / range;
                if zigzag > out.zigzag {
                    out.zigzag = zigzag;
                    out.zigzag_at = i;
                }
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// A sine sampled at N points: the largest second difference is (2π/N)² of the amplitude,
    /// i.e. (2π/N)²/2 of the range; no zigzag; two sign changes.
    #[test]
    fn a_smooth_series_has_an_order_two_second_difference_and_no_zigzag() {
        let n = 180;
        let x: Vec<f64> = (0..n).map(|i| (TAU * i as f64 / n as f64).sin()).collect();
        let s = smoothness(&x).unwrap();
        let expected = 2.0 * (1.0 - (TAU / n as f64).cos()) / 2.0;
        assert!(
            (s.max_second_difference / expected - 1.0).abs() < 1e-9,
            "{s:?}"
        );
        assert_eq!(s.zigzag, 0.0);
        assert_eq!(s.sign_changes, 2);
    }

    /// A jump within one step: the second difference is the whole range, the zigzag 0.
    #[test]
    fn a_jump_is_a_large_second_difference_but_no_zigzag() {
        let x: Vec<f64> = (0..180).map(|i| if i < 90 { 0.0 } else { 1.0 }).collect();
        let s = smoothness(&x).unwrap();
        assert_eq!(s.max_second_difference, 1.0);
        assert_eq!(s.zigzag, 0.0);
        assert_eq!(s.sign_changes, 0);
    }

    /// A saw-tooth of amplitude a on a sine: zigzag ≈ 2a / range, a sign change at every step.
    #[test]
    fn a_saw_tooth_is_measured_by_its_amplitude() {
        let (n, a) = (180, 0.05);
        let x: Vec<f64> = (0..n)
            .map(|i| (TAU * i as f64 / n as f64).sin() + a * if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let s = smoothness(&x).unwrap();
        let range = 2.0 + 2.0 * a;
        // The sine's own step (≤ 2π/180 ≈ 0.035) moves the smallest of three differences by
        // at most that much from 2a.
        assert!((s.zigzag * range - 2.0 * a).abs() < 0.035, "{s:?}");
        assert!(s.sign_changes >= n - 4, "{s:?}");
    }

    #[test]
    fn constant_or_non_finite_series_have_no_measure() {
        assert!(smoothness(&[1.0; 10]).is_none());
        assert!(smoothness(&[0.0, f64::NAN, 1.0]).is_none());
        assert!(smoothness(&[0.0, 1.0]).is_none());
    }
}
