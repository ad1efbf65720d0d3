//! Gauss–Legendre quadrature (nodes and weights by Newton's method on the Legendre recurrence),
//! used by the Ritz assembly ([`crate::ritz`]) and available to callers who integrate the
//! closed-form pressures.
//!
//! ```text
//!   ∫_a^b f(x) dx ≈ Σ_k w_k f(x_k),  exact for polynomials of degree ≤ 2n − 1
//!   P_0 = 1, P_1 = x, (j+1) P_{j+1} = (2j+1) x P_j − j P_{j−1};  P_n'(x) = n (x P_n − P_{n−1})/(x² − 1)
//!   w_k = 2 / ((1 − x_k²) P_n'(x_k)²)   on [−1, 1]
//! ```

/// n-point Gauss–Legendre nodes and weights on [a, b] (n ≥ 1).
///
/// ```
/// use jbearing_solvers::closed_form::quadrature::gauss_legendre;
///
/// // Three points integrate x⁵ exactly (degree ≤ 2n − 1): ∫₀¹ x⁵ dx = 1/6.
/// let (x, w) = gauss_legendre(3, 0.0, 1.0);
/// let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(5)).sum();
/// assert!((integral - 1.0 / 6.0).abs() < 1e-15);
/// // And converge exponentially on smooth integrands: ∫₀^π sin x dx = 2.
/// let (x, w) = gauss_legendre(10, 0.0, std::f64::consts::PI);
/// let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.sin()).sum();
/// assert!((integral - 2.0).abs() < 1e-13);
/// ```
pub fn gauss_legendre(n: usize, a: f64, b: f64) -> (Vec<f64>, Vec<f64>) {
    let n = n.max(1);
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let half = 0.5 * (b - a);
    let mid = 0.5 * (b + a);
    for k in 0..n.div_ceil(2) {
        // Tricomi's initial guess for the k-th root (descending).
        let mut t = (std::f64::consts::PI * (k as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, t);
            for j in 1..n {
                let p2 = ((2 * j + 1) as f64 * t * p1 - j as f64 * p0) / (j + 1) as f64;
                p0 = p1;
                p1 = p2;
            }
            let (pn, pn1) = if n == 1 { (t, 1.0) } else { (p1, p0) };
            dp = n as f64 * (t * pn - pn1) / (t * t - 1.0);
            let dt = pn / dp;
            t -= dt;
            if dt.abs() < 1e-16 {
                break;
            }
        }
        let wk = 2.0 / ((1.0 - t * t) * dp * dp);
        x[k] = mid - half * t;
        x[n - 1 - k] = mid + half * t;
        w[k] = half * wk;
        w[n - 1 - k] = half * wk;
    }
    (x, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_polynomials_exactly_and_smooth_functions_spectrally() {
        for n in 1..12 {
            let (x, w) = gauss_legendre(n, -1.0, 2.0);
            // ∫_{-1}^{2} x^{2n-1} dx = (2^{2n} − 1)/(2n).
            let d = 2 * n - 1;
            let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(d as i32)).sum();
            let exact = (2f64.powi(d as i32 + 1) - 1.0) / (d + 1) as f64;
            assert!((q - exact).abs() < 1e-12 * exact.abs().max(1.0), "n {n}");
        }
        let (x, w) = gauss_legendre(40, 0.0, std::f64::consts::PI);
        let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.sin()).sum();
        assert!((q - 2.0).abs() < 1e-14);
    }
}
