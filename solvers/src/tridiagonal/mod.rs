//! Tridiagonal line solvers: the kernels of the ADI sweeps.
//!
//! One grid line of the discrete universal Reynolds equation (Yu & Sawicki 2002, eq. 12) reads
//!
//! ```text
//!     b_i x_{i-1} + d_i x_i + a_i x_{i+1} = c_i,        i = 0 … m-1
//! ```
//!
//! * An **axial line** (fixed θ) ends at the two bearing edges, where the unknown is given
//!   (Dirichlet). Its matrix is tridiagonal: [`thomas_solve`].
//! * A **circumferential line** (fixed z) closes on itself: θ is periodic, so row 0 couples to
//!   x_{m-1} through `b_0` and row m-1 couples to x_0 through `a_{m-1}` (Yu & Sawicki eq. 15).
//!   [`cyclic_thomas_solve`] is their "modified Thomas" algorithm (eqs. 15–17), re-derived below
//!   because the printed recurrences have index slips.
//!
//! ## Storage convention
//!
//! Every line is four slices of length m: `sub` = b (sub-diagonal), `diag` = d, `sup` = a
//! (super-diagonal), `rhs` = c. For a Dirichlet line `sub[0]` and `sup[m-1]` are ignored. For a
//! periodic line they are the corner entries:
//!
//! ```text
//!     | d0  a0                  b0  |   row 0 :  b0 sits in column m-1
//!     | b1  d1  a1                  |
//!     |     b2  d2  a2              |
//!     |          ·   ·   ·          |
//!     |           b_{m-2} d_{m-2} a_{m-2} |
//!     | a_{m-1}        b_{m-1} d_{m-1} |   row m-1 : a_{m-1} sits in column 0
//! ```
//!
//! No symmetry and no diagonal dominance are assumed: cavitated rows are upwind
//! (a lower bidiagonal plus diagonal). A zero, vanishing or non-finite pivot is reported as
//! [`TridiagonalError::ZeroPivot`] naming the row; NaN is never returned silently.
//!
//! ## Derivation of the modified Thomas algorithm (periodic line, m ≥ 3)
//!
//! *Forward elimination of the sub-diagonal.* Row 0 has d₀ on the diagonal, a₀ in column 1 and
//! the corner b₀ in column m-1; call the last-column entry e₀ = b₀. For i = 1 … m-2, subtract
//! l_i = b_i / d'_{i-1} times the (already reduced) row i-1 from row i. Row i-1 holds d'_{i-1}
//! (column i-1), a_{i-1} (column i) and e_{i-1} (column m-1), so
//!
//! ```text
//!     d'_i = d_i − l_i a_{i-1}
//!     c'_i = c_i − l_i c'_{i-1}
//!     e_i  = −l_i e_{i-1}                 for i < m-2
//!     e_i  = a_{m-2} − l_i e_{m-3}        for i = m-2   (a_{m-2} itself lies in column m-1)
//! ```
//!
//! This is Yu & Sawicki's first step; there the special case is printed at i = m-1 but it
//! belongs to the last row that is *reduced* by this sweep, row m-2 (0-based), whose
//! super-diagonal entry is in the fill-in column. After it, rows 0 … m-2 are upper triangular
//! apart from the fill-in column e (their eq. 16).
//!
//! *Elimination along the last row.* Row m-1 holds a_{m-1} in column 0, b_{m-1} in column m-2 and
//! d_{m-1} on the diagonal. Carry the entry A_j that currently stands in column j, starting with
//! A_0 = a_{m-1}, and remove it with the reduced row j (l = A_j / d'_j):
//!
//! ```text
//!     A_{j+1} = −l a_j  (+ b_{m-1} when j+1 = m-2)     column j+1
//!     d*      ← d* − l e_j                              the last row's diagonal
//!     c*      ← c* − l c'_j                             its right-hand side
//! ```
//!
//! for j = 0 … m-2. At j = m-2 the reduced row has no a-entry left (it was merged into
//! e_{m-2}), so only d* and c* change. In the paper this is the second step; there the
//! right-hand sides use d_i where the pivot of the row doing the eliminating (d'_{i}) is meant,
//! and the d* update is mislabelled e_m. The result is their eq. 17: an upper triangular
//! system plus the last column.
//!
//! *Back substitution.*
//!
//! ```text
//!     x_{m-1} = c* / d*
//!     x_{m-2} = (c'_{m-2} − e_{m-2} x_{m-1}) / d'_{m-2}
//!     x_i     = (c'_i − a_i x_{i+1} − e_i x_{m-1}) / d'_i          i = m-3 … 0
//! ```
//!
//! Cost: about 2× plain Thomas in flops, one extra vector (e) of memory, no pivoting. Like
//! Thomas it is stable without pivoting for diagonally dominant rows; for other rows every
//! pivot is checked.
//!
//! Sizes 1 and 2 of a periodic line are degenerate (the neighbours coincide): m = 1 solves
//! (b₀ + d₀ + a₀) x₀ = c₀ and m = 2 solves the 2×2 system with the off-diagonal entries of each
//! row summed. Both follow from the same wrap-around stencil and are handled exactly.

use thiserror::Error;

/// Why a line solve failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TridiagonalError {
    /// The pivot of a row vanished (or is not finite) during elimination.
    #[error(
        "tridiagonal solve: pivot {pivot:e} of row {row} vanishes against the row's scale {scale:e} \
         (singular or not diagonally dominant line)"
    )]
    ZeroPivot {
        /// Row (0-based) whose pivot vanished.
        row: usize,
        /// The pivot value after elimination.
        pivot: f64,
        /// Sum of the magnitudes of the row's original entries.
        scale: f64,
    },
    /// The slices of a line do not have the same length.
    #[error(
        "tridiagonal solve: slice lengths differ (sub {sub}, diag {diag}, sup {sup}, rhs {rhs}, solution {x})"
    )]
    SizeMismatch {
        sub: usize,
        diag: usize,
        sup: usize,
        rhs: usize,
        x: usize,
    },
    /// A line with no unknowns.
    #[error("tridiagonal solve: empty line (m = 0)")]
    Empty,
}

/// Relative size below which a pivot counts as vanished: all digits lost to cancellation.
const PIVOT_RTOL: f64 = 64.0 * f64::EPSILON;

#[inline(always)]
fn check_pivot(pivot: f64, row: usize, scale: f64) -> Result<(), TridiagonalError> {
    // A NaN pivot fails `is_finite`; a vanished one fails the relative test.
    if !pivot.is_finite() || pivot.abs() <= PIVOT_RTOL * scale {
        return Err(TridiagonalError::ZeroPivot { row, pivot, scale });
    }
    Ok(())
}

fn check_sizes(
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    rhs: &[f64],
    x: &[f64],
) -> Result<usize, TridiagonalError> {
    let m = diag.len();
    if sub.len() != m || sup.len() != m || rhs.len() != m || x.len() != m {
        return Err(TridiagonalError::SizeMismatch {
            sub: sub.len(),
            diag: m,
            sup: sup.len(),
            rhs: rhs.len(),
            x: x.len(),
        });
    }
    if m == 0 {
        return Err(TridiagonalError::Empty);
    }
    Ok(m)
}

/// Reusable scratch memory of the line solvers, so that a solve allocates nothing.
///
/// One workspace serves lines of any length up to the largest it has seen; it grows on demand
/// (the only allocation) and never shrinks.
#[derive(Debug, Clone, Default)]
pub struct LineWorkspace {
    pivots: Vec<f64>,
    fill: Vec<f64>,
}

impl LineWorkspace {
    /// A workspace already sized for lines of `m` unknowns.
    pub fn with_len(m: usize) -> Self {
        Self {
            pivots: vec![0.0; m],
            fill: vec![0.0; m],
        }
    }

    fn ensure(&mut self, m: usize) {
        if self.pivots.len() < m {
            self.pivots.resize(m, 0.0);
            self.fill.resize(m, 0.0);
        }
    }
}

/// Solves a Dirichlet (non-periodic) tridiagonal line by the Thomas algorithm.
///
/// `sub[0]` and `sup[m-1]` are ignored. The solution goes to `x`; the inputs are not modified.
pub fn thomas_solve(
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    rhs: &[f64],
    x: &mut [f64],
    work: &mut LineWorkspace,
) -> Result<(), TridiagonalError> {
    let m = check_sizes(sub, diag, sup, rhs, x)?;
    work.ensure(m);
    // cp[i] = a_i / d'_i (normalised super-diagonal), x[i] = c'_i / d'_i during the sweep.
    let cp = &mut work.pivots[..m];
    let scale0 = diag[0].abs() + if m > 1 { sup[0].abs() } else { 0.0 };
    check_pivot(diag[0], 0, scale0)?;
    let mut inv = 1.0 / diag[0];
    cp[0] = if m > 1 { sup[0] * inv } else { 0.0 };
    x[0] = rhs[0] * inv;
    for i in 1..m {
        let a = if i + 1 < m { sup[i] } else { 0.0 };
        let pivot = diag[i] - sub[i] * cp[i - 1];
        check_pivot(pivot, i, sub[i].abs() + diag[i].abs() + a.abs())?;
        inv = 1.0 / pivot;
        cp[i] = a * inv;
        x[i] = (rhs[i] - sub[i] * x[i - 1]) * inv;
    }
    for i in (0..m - 1).rev() {
        x[i] -= cp[i] * x[i + 1];
    }
    Ok(())
}

/// Solves a periodic (cyclic) tridiagonal line by Yu & Sawicki's modified Thomas algorithm.
///
/// `sub[0]` is the corner entry of row 0 (column m-1) and `sup[m-1]` the corner entry of row
/// m-1 (column 0). The derivation is in the module documentation. The solution goes to `x`;
/// the inputs are not modified.
pub fn cyclic_thomas_solve(
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    rhs: &[f64],
    x: &mut [f64],
    work: &mut LineWorkspace,
) -> Result<(), TridiagonalError> {
    let m = check_sizes(sub, diag, sup, rhs, x)?;
    match m {
        1 => {
            let pivot = sub[0] + diag[0] + sup[0];
            check_pivot(pivot, 0, sub[0].abs() + diag[0].abs() + sup[0].abs())?;
            x[0] = rhs[0] / pivot;
            return Ok(());
        }
        2 => {
            // Row 0: d0 x0 + (a0 + b0) x1 = c0 ; row 1: (a1 + b1) x0 + d1 x1 = c1.
            let (p, q) = (diag[0], sup[0] + sub[0]);
            let (r, s) = (sup[1] + sub[1], diag[1]);
            check_pivot(p, 0, p.abs() + q.abs())?;
            let l = r / p;
            let pivot = s - l * q;
            check_pivot(pivot, 1, r.abs() + s.abs())?;
            x[1] = (rhs[1] - l * rhs[0]) / pivot;
            x[0] = (rhs[0] - q * x[1]) / p;
            return Ok(());
        }
        _ => {}
    }
    work.ensure(m);
    let dp = &mut work.pivots[..m]; // d'_i
    let e = &mut work.fill[..m]; // fill-in column m-1 of rows 0 … m-2
    let last = m - 1;

    // Forward elimination of the sub-diagonal in rows 1 … m-2; x holds c'.
    check_pivot(diag[0], 0, sub[0].abs() + diag[0].abs() + sup[0].abs())?;
    dp[0] = diag[0];
    x[0] = rhs[0];
    e[0] = sub[0];
    for i in 1..last {
        let l = sub[i] / dp[i - 1];
        let pivot = diag[i] - l * sup[i - 1];
        check_pivot(pivot, i, sub[i].abs() + diag[i].abs() + sup[i].abs())?;
        dp[i] = pivot;
        x[i] = rhs[i] - l * x[i - 1];
        e[i] = -l * e[i - 1];
    }
    // Row m-2: its super-diagonal entry lies in the fill-in column.
    e[last - 1] += sup[last - 1];

    // Elimination along the last row.
    let mut carried = sup[last]; // entry in column j, starting at column 0
    let mut d_star = diag[last];
    let mut c_star = rhs[last];
    for j in 0..last - 1 {
        let l = carried / dp[j];
        d_star -= l * e[j];
        c_star -= l * x[j];
        carried = -l * sup[j];
    }
    carried += sub[last]; // column m-2 also holds b_{m-1}
    let l = carried / dp[last - 1];
    d_star -= l * e[last - 1];
    c_star -= l * x[last - 1];
    check_pivot(
        d_star,
        last,
        sub[last].abs() + diag[last].abs() + sup[last].abs(),
    )?;

    // Back substitution.
    let x_last = c_star / d_star;
    x[last] = x_last;
    x[last - 1] = (x[last - 1] - e[last - 1] * x_last) / dp[last - 1];
    for i in (0..last - 1).rev() {
        x[i] = (x[i] - sup[i] * x[i + 1] - e[i] * x_last) / dp[i];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense matrix of a line, for the reference solve.
    fn dense(sub: &[f64], diag: &[f64], sup: &[f64], periodic: bool) -> Vec<Vec<f64>> {
        let m = diag.len();
        let mut a = vec![vec![0.0; m]; m];
        for i in 0..m {
            a[i][i] += diag[i];
            if i > 0 {
                a[i][i - 1] += sub[i];
            } else if periodic {
                a[0][m - 1] += sub[0];
            }
            if i + 1 < m {
                a[i][i + 1] += sup[i];
            } else if periodic {
                a[m - 1][0] += sup[m - 1];
            }
        }
        a
    }

    fn residual(a: &[Vec<f64>], x: &[f64], c: &[f64]) -> f64 {
        let mut worst: f64 = 0.0;
        for (row, ci) in a.iter().zip(c) {
            let ax: f64 = row.iter().zip(x).map(|(aij, xj)| aij * xj).sum();
            worst = worst.max((ax - ci).abs());
        }
        worst
    }

    #[test]
    fn thomas_solves_a_small_dirichlet_line() {
        let sub = [0.0, -1.0, -1.0, -1.0];
        let diag = [2.0, 2.0, 2.0, 2.0];
        let sup = [-1.0, -1.0, -1.0, 0.0];
        let rhs = [1.0, 0.0, 0.0, 1.0];
        let mut x = [0.0; 4];
        thomas_solve(
            &sub,
            &diag,
            &sup,
            &rhs,
            &mut x,
            &mut LineWorkspace::default(),
        )
        .unwrap();
        // The exact solution of this discrete Laplacian is x = 1 everywhere.
        for xi in x {
            assert!((xi - 1.0).abs() < 1e-14, "{x:?}");
        }
    }

    #[test]
    fn cyclic_matches_dense_residual_for_every_small_size() {
        for m in 1..12 {
            let sub: Vec<f64> = (0..m).map(|i| -1.0 - 0.1 * i as f64).collect();
            let sup: Vec<f64> = (0..m).map(|i| -0.5 + 0.03 * i as f64).collect();
            let diag: Vec<f64> = (0..m).map(|i| 4.0 + 0.2 * (i % 3) as f64).collect();
            let rhs: Vec<f64> = (0..m).map(|i| (i as f64 * 0.7).sin() + 1.0).collect();
            let mut x = vec![0.0; m];
            cyclic_thomas_solve(
                &sub,
                &diag,
                &sup,
                &rhs,
                &mut x,
                &mut LineWorkspace::default(),
            )
            .unwrap();
            let r = residual(&dense(&sub, &diag, &sup, true), &x, &rhs);
            assert!(r < 1e-13, "m = {m}: residual {r}");
        }
    }

    #[test]
    fn zero_pivot_is_an_error_naming_the_row() {
        // Row 2 duplicates row 1 of a singular Dirichlet line.
        let sub = [0.0, 1.0, 1.0];
        let diag = [1.0, 1.0, 1.0];
        let sup = [1.0, 1.0, 0.0];
        let rhs = [1.0, 1.0, 1.0];
        let mut x = [0.0; 3];
        let err = thomas_solve(
            &sub,
            &diag,
            &sup,
            &rhs,
            &mut x,
            &mut LineWorkspace::default(),
        )
        .unwrap_err();
        assert!(
            matches!(err, TridiagonalError::ZeroPivot { row: 1, .. }),
            "{err}"
        );
        // A periodic line of constant rows with zero row sums is singular (constants in the kernel).
        let m = 6;
        let (sub, diag, sup) = (vec![-1.0; m], vec![2.0; m], vec![-1.0; m]);
        let mut x = vec![0.0; m];
        let err = cyclic_thomas_solve(
            &sub,
            &diag,
            &sup,
            &vec![0.0; m],
            &mut x,
            &mut LineWorkspace::default(),
        )
        .unwrap_err();
        assert!(
            matches!(err, TridiagonalError::ZeroPivot { row: 5, .. }),
            "{err}"
        );
    }

    #[test]
    fn mismatched_and_empty_lines_are_rejected() {
        let mut x = [0.0; 2];
        let mut w = LineWorkspace::default();
        assert!(matches!(
            thomas_solve(&[0.0; 3], &[1.0; 2], &[0.0; 2], &[1.0; 2], &mut x, &mut w),
            Err(TridiagonalError::SizeMismatch { sub: 3, .. })
        ));
        assert_eq!(
            cyclic_thomas_solve(&[], &[], &[], &[], &mut [], &mut w),
            Err(TridiagonalError::Empty)
        );
    }
}
