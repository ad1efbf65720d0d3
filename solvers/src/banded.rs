//! Banded LU factorization with partial pivoting: the direct solve of a small linear system
//! A x = b whose nonzeros lie within kl diagonals below and ku above the main diagonal
//! (|row − column| bounded), as the multigrid's coarsest level is once its unknowns are
//! numbered with z outer and θ inner (`reynolds::multigrid`).
//!
//! # Method (Golub & Van Loan 2013, §4.3.5; LAPACK's `dgbtrf` / `dgbtrs`)
//!
//! Gaussian elimination with row interchanges, column by column: at column c the pivot is the
//! entry of largest magnitude among rows c … c + kl (no nonzero lies lower), rows c and p swap
//! their entries in columns c … n−1, and rows c+1 … c+kl lose l_r = a_rc / a_cc times row c.
//! An interchange moves an upper entry at most kl columns to the right, so U has upper
//! bandwidth kl + ku and L (unit lower, stored in place of the eliminated entries) kl:
//!
//! ```text
//!   row r holds columns r − kl … r + kl + ku  (width 2 kl + ku + 1):
//!
//!             r−kl        r        r+ku      r+kl+ku
//!   row r:    [ a … a  |  d  |  u … u  |  fill … fill ]
//!              ‾‾‾‾‾‾‾                   ‾‾‾‾‾‾‾‾‾‾‾‾
//!              eliminated (zeroed)       room for the interchanges' fill
//! ```
//!
//! The multipliers of column c are kept apart, column by column (a later interchange at
//! column c' > c swaps columns ≥ c' only and never touches them), so the solve applies, for
//! c = 0 … n−1, the interchange of c and then its multipliers to b (forward, a contiguous
//! axpy), and back-substitutes with U. Work: about
//! 2 n kl (kl + ku) flops to factor and 2 n (2 kl + ku) per solve, against n³/3 dense.
//!
//! A pivot that is zero, non-finite or below n · 2⁻⁵² of its column's largest entry (before
//! elimination; rows of very different scales, as identity rows beside SI flux rows, are fine) is
//! reported as [`BandedError::SingularPivot`] naming the column; no NaN is returned silently.

use thiserror::Error;

/// Why a banded factorization failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BandedError {
    /// Every candidate pivot of `column` is (numerically) zero or not finite.
    #[error(
        "banded LU: pivot {pivot:e} in column {column} of {n} is zero, non-finite or below \
         {threshold:e} (n · 2⁻⁵² of the column's largest entry): the matrix is singular"
    )]
    SingularPivot {
        column: usize,
        n: usize,
        pivot: f64,
        threshold: f64,
    },
    /// An entry outside the band, or outside the matrix, was added.
    #[error("banded LU: entry ({row}, {col}) lies outside the {n} × {n} band kl = {kl}, ku = {ku}")]
    OutsideBand {
        row: usize,
        col: usize,
        n: usize,
        kl: usize,
        ku: usize,
    },
}

/// A banded matrix and, after [`BandedLu::factor`], its LU factors with partial pivoting.
///
/// ```
/// use jbearing_solvers::banded::BandedLu;
/// // The 3 × 3 matrix [[4, 1, 0], [2, 5, 1], [0, 3, 6]] (kl = ku = 1).
/// let mut lu = BandedLu::default();
/// lu.reset(3, 1, 1);
/// for (r, c, v) in [(0, 0, 4.0), (0, 1, 1.0), (1, 0, 2.0), (1, 1, 5.0), (1, 2, 1.0),
///                   (2, 1, 3.0), (2, 2, 6.0)] {
///     lu.add(r, c, v).unwrap();
/// }
/// lu.factor().unwrap();
/// let mut b = vec![5.0, 8.0, 9.0]; // A · [1, 1, 1]
/// lu.solve_in_place(&mut b);
/// assert!(b.iter().all(|x| (x - 1.0).abs() < 1e-14));
/// ```
#[derive(Debug, Clone, Default)]
pub struct BandedLu {
    n: usize,
    kl: usize,
    ku: usize,
    /// Row r's entries of columns r − kl … r + kl + ku, row after row (width `width()`); after
    /// factoring, U in columns r … r + kl + ku.
    rows: Vec<f64>,
    /// Column c's multipliers l_r (rows c+1 … c+kl), column after column (kl each).
    lower: Vec<f64>,
    /// The row swapped with row c at column c.
    pivots: Vec<usize>,
    /// Scratch of [`BandedLu::factor`]: each column's largest magnitude.
    column_max: Vec<f64>,
    factored: bool,
}

impl BandedLu {
    /// An n × n zero matrix of lower bandwidth `kl` and upper bandwidth `ku`, reusing the
    /// storage.
    pub fn reset(&mut self, n: usize, kl: usize, ku: usize) {
        self.n = n;
        self.kl = kl;
        self.ku = ku;
        self.rows.clear();
        self.rows.resize(n * self.width(), 0.0);
        self.pivots.clear();
        self.pivots.resize(n, 0);
        self.lower.clear();
        self.lower.resize(n * kl, 0.0);
        self.factored = false;
    }

    /// The order n.
    pub fn len(&self) -> usize {
        self.n
    }

    /// True for the 0 × 0 matrix.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// True once [`BandedLu::factor`] has succeeded (and no entry was added since).
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    fn width(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    /// Index of entry (r, c) in `rows` (c within r − kl … r + kl + ku).
    #[inline(always)]
    fn at(&self, r: usize, c: usize) -> usize {
        r * self.width() + (c + self.kl - r)
    }

    /// A[row, col] += v (before factoring).
    pub fn add(&mut self, row: usize, col: usize, v: f64) -> Result<(), BandedError> {
        if row >= self.n || col >= self.n || row > col + self.kl || col > row + self.ku {
            return Err(BandedError::OutsideBand {
                row,
                col,
                n: self.n,
                kl: self.kl,
                ku: self.ku,
            });
        }
        let k = self.at(row, col);
        self.rows[k] += v;
        self.factored = false;
        Ok(())
    }

    /// Factor P A = L U in place (module docs).
    pub fn factor(&mut self) -> Result<(), BandedError> {
        let (n, kl) = (self.n, self.kl);
        let reach = kl + self.ku;
        // Each column's largest entry before elimination: the scale of its pivot test.
        let mut column_max = std::mem::take(&mut self.column_max);
        column_max.clear();
        column_max.resize(n, 0.0f64);
        for r in 0..n {
            let first = r.saturating_sub(kl);
            let last = (r + self.ku).min(n - 1);
            let row = &self.rows[self.at(r, first)..=self.at(r, last)];
            for (m, v) in column_max[first..=last].iter_mut().zip(row) {
                *m = m.max(v.abs());
            }
        }
        for c in 0..n {
            let threshold = n as f64 * f64::EPSILON * column_max[c];
            let last_row = (c + kl).min(n - 1);
            let last_col = (c + reach).min(n - 1);
            let mut p = c;
            let mut best = self.rows[self.at(c, c)].abs();
            for r in c + 1..=last_row {
                let v = self.rows[self.at(r, c)].abs();
                if v > best {
                    best = v;
                    p = r;
                }
            }
            // NaN never compares greater: a NaN column keeps p = c and fails the test below.
            let pivot = self.rows[self.at(p, c)];
            let usable = pivot.is_finite() && pivot.abs() > threshold;
            if !usable {
                self.factored = false;
                self.column_max = column_max;
                return Err(BandedError::SingularPivot {
                    column: c,
                    n,
                    pivot,
                    threshold,
                });
            }
            self.pivots[c] = p;
            if p != c {
                for col in c..=last_col {
                    let (a, b) = (self.at(c, col), self.at(p, col));
                    self.rows.swap(a, b);
                }
            }
            let inv = 1.0 / pivot;
            let w = self.width();
            let (head, tail) = self.rows.split_at_mut((c + 1) * w);
            let pivot_row = &head[c * w + kl..c * w + kl + (last_col - c) + 1];
            let lower = &mut self.lower[c * kl..(c + 1) * kl];
            lower.fill(0.0);
            for r in c + 1..=last_row {
                let row = &mut tail[(r - c - 1) * w..(r - c) * w];
                let off = c + kl - r;
                let l = row[off] * inv;
                row[off] = 0.0;
                lower[r - c - 1] = l;
                if l != 0.0 {
                    for (x, &u) in row[off + 1..=off + (last_col - c)]
                        .iter_mut()
                        .zip(&pivot_row[1..])
                    {
                        *x -= l * u;
                    }
                }
            }
        }
        self.column_max = column_max;
        self.factored = true;
        Ok(())
    }

    /// b ← A⁻¹ b with the factors of [`BandedLu::factor`].
    ///
    /// # Panics
    /// If the matrix is not factored or `b` is not of length n.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        assert!(self.factored, "banded LU: solve before a successful factor");
        assert_eq!(b.len(), self.n, "banded LU: right-hand side length");
        let (n, kl) = (self.n, self.kl);
        let reach = kl + self.ku;
        for c in 0..n {
            b.swap(c, self.pivots[c]);
            let bc = b[c];
            let m = kl.min(n - 1 - c);
            if bc != 0.0 {
                for (x, l) in b[c + 1..=c + m].iter_mut().zip(&self.lower[c * kl..]) {
                    *x -= l * bc;
                }
            }
        }
        for c in (0..n).rev() {
            let start = self.at(c, c);
            let last_col = (c + reach).min(n - 1);
            let row = &self.rows[start..=start + (last_col - c)];
            let mut s = b[c];
            for (u, x) in row[1..].iter().zip(&b[c + 1..=last_col]) {
                s -= u * x;
            }
            b[c] = s / row[0];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;

    /// A random banded matrix (dense copy and banded form), diagonally weak enough that
    /// pivoting happens: off-diagonal entries of size up to 2, diagonal up to 1.
    fn banded(n: usize, kl: usize, ku: usize, values: &[f64]) -> (DMatrix<f64>, BandedLu) {
        let mut dense = DMatrix::zeros(n, n);
        let mut lu = BandedLu::default();
        lu.reset(n, kl, ku);
        let mut it = values.iter().cycle();
        for r in 0..n {
            for c in r.saturating_sub(kl)..=(r + ku).min(n - 1) {
                let v = *it.next().unwrap() * if r == c { 1.0 } else { 2.0 };
                dense[(r, c)] = v;
                lu.add(r, c, v).unwrap();
            }
        }
        (dense, lu)
    }

    proptest! {
        /// The banded solve agrees with nalgebra's dense LU (full pivoting) to round-off
        /// times the condition number, on matrices that need row interchanges.
        #[test]
        fn agrees_with_dense_lu(
            n in 1usize..40,
            kl in 0usize..6,
            ku in 0usize..6,
            values in proptest::collection::vec(-1.0f64..1.0, 64),
            rhs in proptest::collection::vec(-1.0f64..1.0, 40),
        ) {
            let (dense, mut lu) = banded(n, kl, ku, &values);
            let dense_lu = dense.clone().full_piv_lu();
            let b = DVector::from_iterator(n, rhs.iter().copied().take(n));
            let Some(x_ref) = dense_lu.solve(&b) else { return Ok(()); };
            // Skip the (rare) numerically singular draws: their answer is not defined.
            let cond = dense.norm() * dense.clone().try_inverse().map_or(f64::INFINITY, |i| i.norm());
            prop_assume!(cond < 1e8);
            lu.factor().unwrap();
            let mut x = b.as_slice().to_vec();
            lu.solve_in_place(&mut x);
            let scale = x_ref.amax().max(1.0);
            for k in 0..n {
                prop_assert!((x[k] - x_ref[k]).abs() <= 1e-15 * cond * scale * n as f64,
                    "x[{k}] {} vs dense {} (cond {cond:e})", x[k], x_ref[k]);
            }
        }
    }

    #[test]
    fn pivoting_is_needed_and_done() {
        // [[0, 1], [1, 0]]: no LU without an interchange.
        let mut lu = BandedLu::default();
        lu.reset(2, 1, 1);
        lu.add(0, 1, 1.0).unwrap();
        lu.add(1, 0, 1.0).unwrap();
        lu.factor().unwrap();
        let mut b = vec![3.0, 7.0];
        lu.solve_in_place(&mut b);
        assert_eq!(b, vec![7.0, 3.0]);
    }

    #[test]
    fn singular_and_nan_matrices_are_errors() {
        let mut lu = BandedLu::default();
        lu.reset(3, 1, 1);
        // Rows 0 and 1 equal: singular at column 1.
        for (r, c, v) in [
            (0, 0, 1.0),
            (0, 1, 2.0),
            (1, 0, 1.0),
            (1, 1, 2.0),
            (2, 2, 1.0),
        ] {
            lu.add(r, c, v).unwrap();
        }
        let err = lu.factor().unwrap_err();
        assert!(
            matches!(err, BandedError::SingularPivot { column: 1, .. }),
            "{err}"
        );
        assert!(!lu.is_factored());
        lu.reset(2, 0, 0);
        lu.add(0, 0, f64::NAN).unwrap();
        lu.add(1, 1, 1.0).unwrap();
        assert!(matches!(
            lu.factor().unwrap_err(),
            BandedError::SingularPivot { column: 0, .. }
        ));
        assert!(matches!(
            lu.add(0, 1, 1.0).unwrap_err(),
            BandedError::OutsideBand { row: 0, col: 1, .. }
        ));
    }
}
