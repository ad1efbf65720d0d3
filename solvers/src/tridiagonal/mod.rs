//! Tridiagonal line solvers: the kernels of the ADI sweeps.
//!
//! One grid line of the discrete universal Reynolds equation (\[YuSawicki2002\], eq. 12) reads
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
//! ## How the code evaluates it (one division per row)
//!
//! Written as above, every row costs three divisions (l_i in the forward sweep, l in the
//! last-row sweep, d'_i in the back substitution), and divisions sit on the critical path of a
//! recurrence. The code therefore normalises each reduced row by its pivot once, as Thomas does:
//!
//! ```text
//!     r_i = 1 / d'_i,   u_i = a_i r_i,   f_i = e_i r_i,   y_i = c'_i r_i
//! ```
//!
//! so that l_i = b_i / d'_{i-1} disappears (l_i a_{i-1} = b_i u_{i-1}, l_i c'_{i-1} = b_i y_{i-1},
//! l_i e_{i-1} = b_i f_{i-1}) and the sweeps read
//!
//! ```text
//!     forward   d'_i = d_i − b_i u_{i-1}
//!               y_i  = (c_i − b_i y_{i-1}) r_i
//!               u_i  = a_i r_i,   f_i = −(b_i f_{i-1}) r_i            1 ≤ i < m-2
//!               u_i  = 0,         f_i = (a_i − b_i f_{i-1}) r_i        i = m-2
//!     last row  d* ← d* − A_j f_j,   c* ← c* − A_j y_j,   A_{j+1} = −A_j u_j (+ b_{m-1} at j+1 = m-2)
//!     back      x_{m-1} = c* / d*,   x_i = (y_i − u_i x_{i+1}) − f_i x_{m-1}
//! ```
//!
//! (row 0: d'_0 = d_0, u_0 = a_0 r_0, f_0 = b_0 r_0 (the corner), y_0 = c_0 r_0). The last-row
//! sweep needs row j only once it is reduced, so it runs fused into the forward sweep. Per
//! unknown this is plain Thomas plus the fill-in recurrence f, the three multiply-adds of the
//! last row and one more multiply-add in the back substitution; the extra work is off the
//! division's critical path. Memory: one vector (f) more than Thomas; y lives in the solution.
//!
//! Like Thomas the algorithm does not pivot. It is stable for diagonally dominant rows (the
//! multipliers |u_i| < 1, so the fill-in f and the carried A_j decay geometrically); for other
//! rows every pivot is checked.
//!
//! ## Decaying fill-in (no subnormal numbers)
//!
//! For diagonally dominant rows the fill-in f_i (∝ Π b_k / d'_k) and the carried entry A_j of the
//! last row (∝ Π u_k) decay geometrically along the line. Left alone they pass through the
//! subnormal range (|v| < 2⁻¹⁰²² ≈ 2.2e-308) after a few hundred to a thousand rows, and x86
//! cores take a slow path for subnormal operands and results: a 1024-unknown line measured
//! 1.34 × plain Thomas instead of 1.06 × (docs/performance.md, "Line kernels"). The code
//! therefore drops them once they are negligible: f_i is set to 0 when |f_i| < 2⁻⁶⁰ and A_j when
//! |A_j| < 2⁻⁶⁰ (|b_{m-1}| + |d_{m-1}| + |a_{m-1}|) (`FLUSH_RTOL`); once zero they stay zero and
//! the remaining rows are plain Thomas plus exact zeros. Dropping f_i perturbs the reduced row i
//! by less than 2⁻⁶⁰ of its pivot, and dropping A_j the last row by less than 2⁻⁶⁰ of its scale,
//! i.e. a backward error 2⁷ times smaller than the round-off u = 2⁻⁵³ already committed in every
//! row. The batched kernels drop exactly the same terms, so the bit-for-bit agreement holds.
//!
//! ## Errors instead of NaN
//!
//! Every pivot d'_i (and d*) is tested against the sum of the magnitudes of its row's original
//! entries: |d'_i| ≤ 64 ε (|b_i| + |d_i| + |a_i|), or a non-finite pivot, is
//! [`TridiagonalError::ZeroPivot`] naming the row. A non-finite right-hand side or an overflow
//! can still produce a non-finite unknown with healthy pivots; the back substitution checks
//! every unknown and reports the first one as [`TridiagonalError::NonFiniteSolution`]. On an
//! error the contents of `x` are unspecified.
//!
//! ## Small periodic lines
//!
//! Sizes 1 and 2 of a periodic line are degenerate (the neighbours coincide): m = 1 solves
//! (b₀ + d₀ + a₀) x₀ = c₀ and m = 2 solves the 2×2 system with the off-diagonal entries of each
//! row summed (row 0: d₀ x₀ + (a₀ + b₀) x₁ = c₀, row 1: (a₁ + b₁) x₀ + d₁ x₁ = c₁). Both are
//! what the wrap-around stencil means on such a line (the discrete operator of a periodic
//! coordinate with one or two nodes) and are solved exactly, with the same pivot checks.
//!
//! ## Many lines at once
//!
//! [`thomas_solve_interleaved`] and [`cyclic_thomas_solve_interleaved`] (module `batch`) solve
//! many independent lines stored interleaved, vectorized across lines, with the same
//! arithmetic as the single-line functions here (results agree bit for bit).
//! [`InterleavedFactors`] (module `factored`) splits the same elimination into a factor phase
//! (pivots, checks, reciprocals: once per matrix) and a solve phase (per right-hand side), for
//! the ADI sweeps, whose line matrices stay fixed during a Krylov solve; again bit for bit.

use thiserror::Error;

mod batch;
mod factored;

pub use batch::{BatchWorkspace, LANES, cyclic_thomas_solve_interleaved, thomas_solve_interleaved};
pub use factored::InterleavedFactors;

/// The floating-point types the factored line solves run in: `f64` (every factorization, and
/// the solves of the ADI preconditioner) and `f32` (the solves of the multigrid V-cycle, from
/// factors computed in `f64` and rounded, [`InterleavedFactors::round_from`]).
pub trait Real:
    Copy
    + Default
    + PartialEq
    + PartialOrd
    + std::fmt::Debug
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::AddAssign
    + private::Sealed
    + 'static
{
    /// 0.
    const ZERO: Self;
    /// The nearest value of this type (`as`: round to nearest).
    fn from_f64(v: f64) -> Self;
    /// The value as `f64` (exact).
    fn to_f64(self) -> f64;
    /// Neither infinite nor NaN.
    fn finite(self) -> bool;
    /// |v|.
    fn magnitude(self) -> Self;
}

mod private {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

impl Real for f64 {
    const ZERO: Self = 0.0;
    #[inline(always)]
    fn from_f64(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline(always)]
    fn magnitude(self) -> Self {
        self.abs()
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    #[inline(always)]
    fn from_f64(v: f64) -> Self {
        v as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn finite(self) -> bool {
        self.is_finite()
    }
    #[inline(always)]
    fn magnitude(self) -> Self {
        self.abs()
    }
}

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
    /// The pivot of a row of one line of a batch vanished (or is not finite).
    #[error(
        "tridiagonal batch solve: pivot {pivot:e} of row {row} of line {line} vanishes against \
         the row's scale {scale:e} (singular or not diagonally dominant line)"
    )]
    ZeroPivotInLine {
        /// Line (0-based) of the batch; the first failing line is reported.
        line: usize,
        /// Row (0-based) within that line whose pivot vanished; the first one.
        row: usize,
        /// The pivot value after elimination.
        pivot: f64,
        /// Sum of the magnitudes of the row's original entries.
        scale: f64,
    },
    /// All pivots were sound but an unknown came out non-finite (a non-finite right-hand side
    /// or an overflow).
    #[error("tridiagonal solve: unknown {row} is not finite ({value}) although every pivot was")]
    NonFiniteSolution {
        /// First row (0-based) whose unknown is not finite.
        row: usize,
        /// Its value.
        value: f64,
    },
    /// As [`TridiagonalError::NonFiniteSolution`], for one line of a batch.
    #[error(
        "tridiagonal batch solve: unknown {row} of line {line} is not finite ({value}) although \
         every pivot was"
    )]
    NonFiniteSolutionInLine {
        /// Line (0-based) of the batch; the first failing line is reported.
        line: usize,
        /// First row (0-based) of that line whose unknown is not finite.
        row: usize,
        /// Its value.
        value: f64,
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
    /// The slices of a batch do not all hold m × lines values (or m × lines overflows).
    #[error(
        "tridiagonal batch solve: {m} rows × {lines} lines need {m}·{lines} values per slice, got \
         sub {sub}, diag {diag}, sup {sup}, rhs {rhs}, solution {x}"
    )]
    BatchSizeMismatch {
        m: usize,
        lines: usize,
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
pub(crate) const PIVOT_RTOL: f64 = 64.0 * f64::EPSILON;

/// Relative size below which the decaying terms of the periodic elimination are dropped
/// (2⁻⁶⁰ ≈ 8.7e-19, far below the round-off u = 2⁻⁵³): the fill-in f_i (relative to the pivot,
/// it is already normalised) and the carried last-row entry A_j (relative to the last row's
/// scale |b_{m-1}| + |d_{m-1}| + |a_{m-1}|). See "Decaying fill-in" in the module docs.
pub(crate) const FLUSH_RTOL: f64 = 1.0 / (1u64 << 60) as f64;

/// `v`, or 0 when |v| < `tol`. NaN and ±∞ pass unchanged (the comparison is false), and it
/// vectorizes (a compare and a blend, no branch).
#[inline(always)]
pub(crate) fn flush(v: f64, tol: f64) -> f64 {
    if v.abs() < tol { 0.0 } else { v }
}

/// True when `pivot` is sound against the row scale. Written so that a NaN pivot fails (every
/// comparison with NaN is false) and so that it vectorizes (no branch, no `is_finite` call).
#[inline(always)]
pub(crate) fn pivot_ok(pivot: f64, scale: f64) -> bool {
    let a = pivot.abs();
    (a > PIVOT_RTOL * scale) & (a < f64::INFINITY)
}

#[inline(always)]
fn check_pivot(pivot: f64, row: usize, scale: f64) -> Result<(), TridiagonalError> {
    if !pivot_ok(pivot, scale) {
        return Err(TridiagonalError::ZeroPivot { row, pivot, scale });
    }
    Ok(())
}

/// Finds the first non-finite unknown (called only when the sweep flagged one).
#[cold]
fn non_finite(x: &[f64]) -> TridiagonalError {
    let row = x.iter().position(|v| !v.is_finite()).unwrap_or(0);
    TridiagonalError::NonFiniteSolution {
        row,
        value: x.get(row).copied().unwrap_or(f64::NAN),
    }
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
    /// u_i = a_i / d'_i, the normalised super-diagonal.
    upper: Vec<f64>,
    /// f_i = e_i / d'_i, the normalised fill-in column (periodic lines only).
    fill: Vec<f64>,
}

impl LineWorkspace {
    /// A workspace already sized for lines of `m` unknowns.
    pub fn with_len(m: usize) -> Self {
        Self {
            upper: vec![0.0; m],
            fill: vec![0.0; m],
        }
    }

    fn ensure(&mut self, m: usize) {
        if self.upper.len() < m {
            self.upper.resize(m, 0.0);
            self.fill.resize(m, 0.0);
        }
    }
}

/// Solves a Dirichlet (non-periodic) tridiagonal line by the Thomas algorithm.
///
/// `sub[0]` and `sup[m-1]` are ignored. The solution goes to `x`; the inputs are not modified.
/// Every pivot d'_i = d_i − b_i u_{i-1} is checked (see the module docs); a non-finite unknown
/// is reported, never returned.
///
/// ```
/// use jbearing_solvers::tridiagonal::{thomas_solve, LineWorkspace};
///
/// // −x_{i−1} + 4 x_i − x_{i+1} = b_i with the solution x = (1, 2, 3, 4) built into b.
/// let (sub, diag, sup) = ([0.0, -1.0, -1.0, -1.0], [4.0; 4], [-1.0, -1.0, -1.0, 0.0]);
/// let rhs = [4.0 - 2.0, -1.0 + 8.0 - 3.0, -2.0 + 12.0 - 4.0, -3.0 + 16.0];
/// let mut x = [0.0; 4];
/// thomas_solve(&sub, &diag, &sup, &rhs, &mut x, &mut LineWorkspace::with_len(4))?;
/// assert!(x.iter().zip([1.0, 2.0, 3.0, 4.0]).all(|(a, b)| (a - b).abs() < 1e-14));
/// # Ok::<(), jbearing_solvers::tridiagonal::TridiagonalError>(())
/// ```
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
    // u[i] = a_i / d'_i (normalised super-diagonal), x[i] = c'_i / d'_i during the sweep.
    let u = &mut work.upper[..m];
    let a0 = if m > 1 { sup[0] } else { 0.0 };
    check_pivot(diag[0], 0, diag[0].abs() + a0.abs())?;
    let r = 1.0 / diag[0];
    u[0] = a0 * r;
    x[0] = rhs[0] * r;
    for i in 1..m {
        let a = if i + 1 < m { sup[i] } else { 0.0 };
        let pivot = diag[i] - sub[i] * u[i - 1];
        check_pivot(pivot, i, sub[i].abs() + diag[i].abs() + a.abs())?;
        let r = 1.0 / pivot;
        u[i] = a * r;
        x[i] = (rhs[i] - sub[i] * x[i - 1]) * r;
    }
    let mut finite = x[m - 1].is_finite();
    for i in (0..m - 1).rev() {
        x[i] -= u[i] * x[i + 1];
        finite &= x[i].is_finite();
    }
    if !finite {
        return Err(non_finite(x));
    }
    Ok(())
}

/// Solves a periodic (cyclic) tridiagonal line by Yu & Sawicki's modified Thomas algorithm.
///
/// `sub[0]` is the corner entry of row 0 (column m-1) and `sup[m-1]` the corner entry of row
/// m-1 (column 0). The derivation and the evaluation order are in the module documentation.
/// The solution goes to `x`; the inputs are not modified.
///
/// ```
/// use jbearing_solvers::tridiagonal::{cyclic_thomas_solve, LineWorkspace};
///
/// // The periodic line −x_{i−1} + 3 x_i − x_{i+1} = b_i (indices mod 5), x = (1, −1, 2, 0, 5).
/// let want = [1.0, -1.0, 2.0, 0.0, 5.0];
/// let m = want.len();
/// let rhs: Vec<f64> = (0..m).map(|i| 3.0 * want[i] - want[(i + m - 1) % m] - want[(i + 1) % m]).collect();
/// let mut x = vec![0.0; m];
/// cyclic_thomas_solve(&[-1.0; 5], &[3.0; 5], &[-1.0; 5], &rhs, &mut x, &mut LineWorkspace::with_len(m))?;
/// assert!(x.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-13));
/// # Ok::<(), jbearing_solvers::tridiagonal::TridiagonalError>(())
/// ```
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
        }
        2 => {
            // Row 0: d0 x0 + (a0 + b0) x1 = c0 ; row 1: (a1 + b1) x0 + d1 x1 = c1.
            let (p, q) = (diag[0], sup[0] + sub[0]);
            let (r, s) = (sup[1] + sub[1], diag[1]);
            check_pivot(p, 0, diag[0].abs() + sup[0].abs() + sub[0].abs())?;
            let l = r / p;
            let pivot = s - l * q;
            check_pivot(pivot, 1, sub[1].abs() + diag[1].abs() + sup[1].abs())?;
            x[1] = (rhs[1] - l * rhs[0]) / pivot;
            x[0] = (rhs[0] - q * x[1]) / p;
        }
        _ => {
            work.ensure(m);
            return cyclic_sweeps(
                sub,
                diag,
                sup,
                rhs,
                x,
                &mut work.upper[..m],
                &mut work.fill[..m],
            );
        }
    }
    if x[..m].iter().any(|v| !v.is_finite()) {
        return Err(non_finite(x));
    }
    Ok(())
}

/// The m ≥ 3 periodic solve of [`cyclic_thomas_solve`]; `u`, `f` have length m.
#[inline(always)]
fn cyclic_sweeps(
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    rhs: &[f64],
    x: &mut [f64],
    u: &mut [f64],
    f: &mut [f64],
) -> Result<(), TridiagonalError> {
    let m = diag.len();
    let last = m - 1;
    let (sub, sup, rhs, x, u, f) = (
        &sub[..m],
        &sup[..m],
        &rhs[..m],
        &mut x[..m],
        &mut u[..m],
        &mut f[..m],
    );

    // Row 0: pivot d_0; its fill-in entry is the corner b_0.
    check_pivot(diag[0], 0, sub[0].abs() + diag[0].abs() + sup[0].abs())?;
    let r = 1.0 / diag[0];
    u[0] = sup[0] * r;
    f[0] = sub[0] * r;
    x[0] = rhs[0] * r;
    // Last row, fused: remove its column-0 entry A_0 = a_{m-1} with row 0.
    let scale_last = sub[last].abs() + diag[last].abs() + sup[last].abs();
    let carried_tol = FLUSH_RTOL * scale_last;
    let mut carried = sup[last];
    let mut d_star = diag[last] - carried * f[0];
    let mut c_star = rhs[last] - carried * x[0];
    carried = flush(-carried * u[0], carried_tol);

    // Rows 1 … m-3.
    for i in 1..last - 1 {
        let b = sub[i];
        let pivot = diag[i] - b * u[i - 1];
        check_pivot(pivot, i, b.abs() + diag[i].abs() + sup[i].abs())?;
        let r = 1.0 / pivot;
        u[i] = sup[i] * r;
        f[i] = flush(-(b * f[i - 1]) * r, FLUSH_RTOL);
        x[i] = (rhs[i] - b * x[i - 1]) * r;
        d_star -= carried * f[i];
        c_star -= carried * x[i];
        carried = flush(-carried * u[i], carried_tol);
    }

    // Row m-2: its super-diagonal entry lies in the fill-in column m-1.
    let i = last - 1;
    let b = sub[i];
    let pivot = diag[i] - b * u[i - 1];
    check_pivot(pivot, i, b.abs() + diag[i].abs() + sup[i].abs())?;
    let r = 1.0 / pivot;
    u[i] = 0.0;
    f[i] = (sup[i] - b * f[i - 1]) * r;
    x[i] = (rhs[i] - b * x[i - 1]) * r;
    // The last row's column m-2 holds b_{m-1} besides the carried entry.
    carried += sub[last];
    d_star -= carried * f[i];
    c_star -= carried * x[i];
    check_pivot(d_star, last, scale_last)?;

    // Back substitution.
    let x_last = c_star / d_star;
    x[last] = x_last;
    x[i] -= f[i] * x_last;
    let mut finite = x_last.is_finite() & x[i].is_finite();
    for i in (0..last - 1).rev() {
        x[i] = (x[i] - u[i] * x[i + 1]) - f[i] * x_last;
        finite &= x[i].is_finite();
    }
    if !finite {
        return Err(non_finite(x));
    }
    Ok(())
}

#[cfg(test)]
mod reference_tests;

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
