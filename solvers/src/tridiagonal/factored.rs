//! Factor once, solve many: batches of lines whose matrix stays fixed while the right-hand side
//! changes.
//!
//! In the ADI preconditioner of a frozen-switch Reynolds solve (`reynolds::adi`) the line
//! matrices are fixed for the whole Krylov solve, while every preconditioner application solves
//! them with a new right-hand side (the circumferential lines twice per application). The plain
//! batched kernels ([`super::batch`]) recompute each pivot, its check and its reciprocal every
//! time. Here the elimination is split into its two halves:
//!
//! ```text
//!   factor (once per matrix)            solve (per right-hand side, vectorized across lines)
//!   ─────────────────────────           ───────────────────────────────────────────────────
//!   r_i = 1 / d'_i   (pivot checked)    y_0 = c_0 r_0,  y_i = (c_i − b_i y_{i−1}) r_i
//!   u_i = a_i r_i                       x_i = y_i − u_i x_{i+1}                 (Dirichlet)
//!   f_i, carried A_i, d*  (periodic)    c* = c_{m−1} − Σ A_i y_i,  x_{m−1} = c* / d*,
//!                                       x_i = (y_i − u_i x_{i+1}) − f_i x_{m−1}  (periodic)
//! ```
//!
//! (notation and derivation of the periodic recurrences: the module docs of `tridiagonal`).
//!
//! ## Bit for bit
//!
//! Every quantity is computed by the same IEEE operations in the same order as in
//! [`thomas_solve`](super::thomas_solve) and [`cyclic_thomas_solve`](super::cyclic_thomas_solve)
//! (and their batched twins): the factor phase runs the coefficient-only part of those
//! recurrences, the solve phase the right-hand-side part, with the stored values in place of
//! the recomputed ones. So a factored solve returns, bit for bit, what the one-shot solvers
//! return (tested with `==` on the bits). The solve phase uses the chunk-of-lanes scheme and
//! the run-time AVX2 choice of [`super::batch`]; neither changes a bit. The factor phase of a
//! whole batch runs row by row with the lines innermost (a contiguous run per row, so the
//! divisions of different lines overlap instead of each line waiting on its own chain); each
//! line still does its operations in its own order. Re-factoring a few lines
//! ([`InterleavedFactors::refactor_lanes`]) goes line by line.
//!
//! ## Errors
//!
//! A vanishing pivot is found by the factor phase and named by line and row
//! ([`TridiagonalError::ZeroPivotInLine`], the first failing line, as the batch kernels report
//! it). The solve phase reports the first non-finite unknown
//! ([`TridiagonalError::NonFiniteSolutionInLine`]). Periodic lines need m ≥ 3 (the ADI lines
//! have at least 8 nodes); shorter ones are rejected ([`TridiagonalError::BatchSizeMismatch`]).

use super::batch::{lanes, load, store};
use super::{FLUSH_RTOL, Real, TridiagonalError, flush, pivot_ok};

/// Which line kind a factorization holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Kind {
    #[default]
    Dirichlet,
    Periodic,
}

/// The factors of a batch of `lines` lines of `m` unknowns, stored interleaved like the batch
/// kernels' inputs (row i of line l at `i · lines + l`). Reusable: a new factorization
/// overwrites the old one without allocating when the size is unchanged.
///
/// The factorization is always computed in `f64` (`InterleavedFactors<f64>`, the default
/// type); [`round_from`](Self::round_from) rounds it to `InterleavedFactors<f32>`, whose
/// solves run in single precision (the multigrid smoother, `reynolds::multigrid`): half the
/// memory traffic and twice the lanes per vector, with the pivots checked in `f64`. An `f32`
/// solve is not bit for bit the `f64` one: every stored factor carries a relative rounding of
/// 2⁻²⁴, and the substitutions round at 2⁻²⁴ too.
#[derive(Debug, Clone, Default)]
pub struct InterleavedFactors<T: Real = f64> {
    kind: Kind,
    m: usize,
    lines: usize,
    /// b_i (row i ≥ 1; row 0 unused).
    sub: Vec<T>,
    /// r_i = 1 / d'_i (periodic: rows 0 … m−2).
    recip: Vec<T>,
    /// u_i = a_i r_i (periodic: rows 0 … m−3).
    upper: Vec<T>,
    /// Periodic: fill-in f_i (rows 0 … m−2).
    fill: Vec<T>,
    /// Periodic: the entry A_i of the last row that row i removes (rows 0 … m−2).
    carried: Vec<T>,
    /// Periodic: the last row's final diagonal d*, per line.
    d_star: Vec<T>,
}

/// Checks the slice lengths (m · lines each) and m ≥ `min_m` (m = 0 is [`TridiagonalError::Empty`]).
fn sizes_ok(
    m: usize,
    lines: usize,
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    min_m: usize,
) -> Result<usize, TridiagonalError> {
    let n = m.checked_mul(lines);
    let fits = |s: &[f64]| Some(s.len()) == n;
    if m == 0 && fits(sub) && fits(diag) && fits(sup) {
        return Err(TridiagonalError::Empty);
    }
    if !(fits(sub) && fits(diag) && fits(sup)) || m < min_m {
        return Err(TridiagonalError::BatchSizeMismatch {
            m,
            lines,
            sub: sub.len(),
            diag: diag.len(),
            sup: sup.len(),
            rhs: n.unwrap_or(0),
            x: n.unwrap_or(0),
        });
    }
    Ok(m * lines)
}

fn zero_pivot(line: usize, row: usize, pivot: f64, scale: f64) -> TridiagonalError {
    TridiagonalError::ZeroPivotInLine {
        line,
        row,
        pivot,
        scale,
    }
}

impl<T: Real> InterleavedFactors<T> {
    fn resize(&mut self, kind: Kind, m: usize, lines: usize, n: usize) {
        self.kind = kind;
        self.m = m;
        self.lines = lines;
        for v in [
            &mut self.sub,
            &mut self.recip,
            &mut self.upper,
            &mut self.fill,
            &mut self.carried,
        ] {
            v.resize(n, T::ZERO);
        }
        self.d_star.resize(lines, T::ZERO);
    }

    /// Forgets the factorization (shape 0 × 0).
    fn invalidate(&mut self) {
        self.m = 0;
        self.lines = 0;
    }

    /// Number of unknowns per line and number of lines of the current factorization.
    pub fn shape(&self) -> (usize, usize) {
        (self.m, self.lines)
    }

    /// This factorization becomes `f` rounded to `T` (round to nearest, value by value; no
    /// allocation when the size is unchanged). The pivots were checked in `f64` when `f` was
    /// factored; a reciprocal pivot or d* that rounds to 0 or ∞ in `T` (|value| beyond the
    /// range of `T`) is an error here, naming its line and row, so that a solve never divides
    /// by or multiplies with a value the `f64` factorization did not have.
    pub fn round_from(&mut self, f: &InterleavedFactors) -> Result<(), TridiagonalError> {
        let n = f.m * f.lines;
        self.resize(f.kind, f.m, f.lines, n);
        self.round_all_from(f)
    }

    /// Every factor of `f` (of this shape) rounded into this factorization, then checked:
    /// flat passes that vectorize; only when a check fails are the lines checked one by one,
    /// for the error of the first failing line and row (as [`check_rounded_lane`] in line
    /// order gives it).
    ///
    /// [`check_rounded_lane`]: Self::check_rounded_lane
    fn round_all_from(&mut self, f: &InterleavedFactors) -> Result<(), TridiagonalError> {
        let round = |dst: &mut [T], src: &[f64]| {
            for (d, s) in dst.iter_mut().zip(src) {
                *d = T::from_f64(*s);
            }
        };
        round(&mut self.sub, &f.sub);
        round(&mut self.recip, &f.recip);
        round(&mut self.upper, &f.upper);
        round(&mut self.fill, &f.fill);
        round(&mut self.carried, &f.carried);
        round(&mut self.d_star, &f.d_star);
        let periodic = f.kind == Kind::Periodic;
        let rows = if periodic { f.m - 1 } else { f.m };
        let usable = |v: T| (v != T::ZERO) & v.finite();
        let mut ok = true;
        for &r in &self.recip[..rows * f.lines] {
            ok &= usable(r);
        }
        if periodic {
            for &d in &self.d_star[..f.lines] {
                ok &= usable(d);
            }
        }
        if !ok {
            for l in 0..f.lines {
                self.check_rounded_lane(f, l)?;
            }
        }
        Ok(())
    }

    /// After rounding line `l` of `f`: a reciprocal pivot or d* that rounded to 0 or ∞ is an
    /// error naming its line and row, and leaves the factorization empty.
    fn check_rounded_lane(
        &mut self,
        f: &InterleavedFactors,
        l: usize,
    ) -> Result<(), TridiagonalError> {
        let rows = if f.kind == Kind::Periodic {
            f.m - 1
        } else {
            f.m
        };
        for i in 0..rows {
            let k = i * f.lines + l;
            let r = self.recip[k];
            if r == T::ZERO || !r.finite() {
                self.invalidate();
                return Err(zero_pivot(l, i, 1.0 / f.recip[k], f64::NAN));
            }
        }
        if f.kind == Kind::Periodic {
            let d = self.d_star[l];
            if d == T::ZERO || !d.finite() {
                self.invalidate();
                return Err(zero_pivot(l, f.m - 1, f.d_star[l], f64::NAN));
            }
        }
        Ok(())
    }
}

impl<T: Real> InterleavedFactors<T> {
    /// The lines `lanes` of this rounded factorization become those of `f` rounded to `T`, as
    /// [`round_from`](Self::round_from) rounds them (the same checks); the other lines keep
    /// their values, provided they are still those of `f` this factorization was last rounded
    /// from (`f` refactored in `lanes` only since, as [`refactor_lanes`] does): they are
    /// rounded again, to the same bits. `f` must have this factorization's kind and shape
    /// (else, or on a check that fails, the factorization is empty and this is an error).
    ///
    /// [`refactor_lanes`]: InterleavedFactors::refactor_lanes
    pub fn round_lanes_from(
        &mut self,
        f: &InterleavedFactors,
        lanes: &[usize],
    ) -> Result<(), TridiagonalError> {
        if (f.kind, f.m, f.lines) != (self.kind, self.m, self.lines)
            || self.sub.len() < f.m * f.lines
            || lanes.iter().any(|&l| l >= f.lines)
        {
            let (m, lines) = (f.m, f.lines);
            self.invalidate();
            return Err(TridiagonalError::BatchSizeMismatch {
                m,
                lines,
                sub: self.sub.len(),
                diag: 0,
                sup: 0,
                rhs: 0,
                x: 0,
            });
        }
        if 2 * lanes.len() >= f.lines {
            // The other lines' factors are those this factorization was rounded from last:
            // rounded again they give the same values, so when half the lines or more are
            // asked for (the circumferential lines of a hierarchy update), one flat pass over
            // every line, which vectorizes, is cheaper than the strided per-line loops.
            return self.round_all_from(f);
        }
        for &l in lanes {
            for i in 0..f.m {
                let k = i * f.lines + l;
                self.sub[k] = T::from_f64(f.sub[k]);
                self.recip[k] = T::from_f64(f.recip[k]);
                self.upper[k] = T::from_f64(f.upper[k]);
                self.fill[k] = T::from_f64(f.fill[k]);
                self.carried[k] = T::from_f64(f.carried[k]);
            }
            self.d_star[l] = T::from_f64(f.d_star[l]);
            self.check_rounded_lane(f, l)?;
        }
        Ok(())
    }
}

impl InterleavedFactors {
    /// Factors `lines` Dirichlet lines (Thomas; `sub` of row 0 and `sup` of row m−1 ignored).
    /// On an error the factorization is empty: a later [`solve`](Self::solve) is an error, not
    /// a solve with half-overwritten factors.
    pub fn factor_dirichlet(
        &mut self,
        m: usize,
        lines: usize,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
    ) -> Result<(), TridiagonalError> {
        let out = self.factor_dirichlet_lines(m, lines, sub, diag, sup);
        if out.is_err() {
            self.invalidate();
        }
        out
    }

    fn factor_dirichlet_lines(
        &mut self,
        m: usize,
        lines: usize,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
    ) -> Result<(), TridiagonalError> {
        let n = sizes_ok(m, lines, sub, diag, sup, 1)?;
        self.resize(Kind::Dirichlet, m, lines, n);
        self.sub.copy_from_slice(sub);
        if self.factor_dirichlet_batched(sub, diag, sup) {
            return Ok(());
        }
        // A pivot failed: the error of the first failing line and row, line by line.
        for l in 0..lines {
            self.factor_dirichlet_lane(l, sub, diag, sup)?;
        }
        Ok(())
    }

    /// Every line of a Dirichlet factorization of this shape at once, row by row with the
    /// lines innermost (the interleaved storage: one contiguous run per row, which vectorizes,
    /// and the rows' divisions of different lines overlap instead of waiting on each other).
    /// Each line does the operations of [`factor_dirichlet_lane`](Self::factor_dirichlet_lane)
    /// in its order (the same bits); returns whether every pivot passed its check (if not, the
    /// factors are garbage and the caller reports the error line by line).
    fn factor_dirichlet_batched(&mut self, sub: &[f64], diag: &[f64], sup: &[f64]) -> bool {
        let (m, lines) = (self.m, self.lines);
        let mut ok = true;
        for l in 0..lines {
            let a0 = if m > 1 { sup[l] } else { 0.0 };
            let d0 = diag[l];
            ok &= pivot_ok(d0, d0.abs() + a0.abs());
            let r = 1.0 / d0;
            self.recip[l] = r;
            self.upper[l] = a0 * r;
        }
        for i in 1..m {
            let row = i * lines..(i + 1) * lines;
            let (done, rest) = self.upper.split_at_mut(i * lines);
            let (u_prev, upper) = (&done[(i - 1) * lines..], &mut rest[..lines]);
            let recip = &mut self.recip[row.clone()];
            let (b, d) = (&sub[row.clone()], &diag[row.clone()]);
            let a = &sup[row];
            let last_row = i + 1 == m;
            for l in 0..lines {
                // The last row has no super-diagonal (its `sup` entry is not read).
                let a = if last_row { 0.0 } else { a[l] };
                let pivot = d[l] - b[l] * u_prev[l];
                ok &= pivot_ok(pivot, b[l].abs() + d[l].abs() + a.abs());
                let r = 1.0 / pivot;
                recip[l] = r;
                upper[l] = a * r;
            }
        }
        ok
    }

    /// Line `l` of a Dirichlet factorization of this shape, from the interleaved coefficients.
    fn factor_dirichlet_lane(
        &mut self,
        l: usize,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
    ) -> Result<(), TridiagonalError> {
        let (m, lines) = (self.m, self.lines);
        // As `thomas_solve`, coefficient part only.
        let a0 = if m > 1 { sup[l] } else { 0.0 };
        let d0 = diag[l];
        let scale = d0.abs() + a0.abs();
        if !pivot_ok(d0, scale) {
            return Err(zero_pivot(l, 0, d0, scale));
        }
        let r = 1.0 / d0;
        self.recip[l] = r;
        let mut u_prev = a0 * r;
        self.upper[l] = u_prev;
        for i in 1..m {
            let k = i * lines + l;
            let a = if i + 1 < m { sup[k] } else { 0.0 };
            let b = sub[k];
            let pivot = diag[k] - b * u_prev;
            let scale = b.abs() + diag[k].abs() + a.abs();
            if !pivot_ok(pivot, scale) {
                return Err(zero_pivot(l, i, pivot, scale));
            }
            let r = 1.0 / pivot;
            self.recip[k] = r;
            u_prev = a * r;
            self.upper[k] = u_prev;
        }
        Ok(())
    }

    /// Re-factors only the lines `lanes` of the factorization in hand (same kind, m and line
    /// count), from interleaved coefficients of which only those lines are read: the others
    /// keep their factors. Each line is factored by the same operations as in
    /// [`factor_dirichlet`](Self::factor_dirichlet) / [`factor_periodic`](Self::factor_periodic),
    /// so the result is bit for bit a full factorization of coefficients that differ from the
    /// last ones only on these lines. On an error (a vanishing pivot, or a shape that does not
    /// match) the factorization is empty.
    pub fn refactor_lanes(
        &mut self,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
        lanes: &[usize],
    ) -> Result<(), TridiagonalError> {
        let (m, lines, kind) = (self.m, self.lines, self.kind);
        let min_m = if kind == Kind::Periodic { 3 } else { 1 };
        let out = sizes_ok(m, lines, sub, diag, sup, min_m).and_then(|_| {
            for &l in lanes {
                if l >= lines {
                    return Err(TridiagonalError::BatchSizeMismatch {
                        m,
                        lines,
                        sub: sub.len(),
                        diag: diag.len(),
                        sup: sup.len(),
                        rhs: l,
                        x: l,
                    });
                }
                for i in 0..m {
                    self.sub[i * lines + l] = sub[i * lines + l];
                }
                match kind {
                    Kind::Dirichlet => self.factor_dirichlet_lane(l, sub, diag, sup)?,
                    Kind::Periodic => self.factor_periodic_lane(l, sub, diag, sup)?,
                }
            }
            Ok(())
        });
        if out.is_err() {
            self.invalidate();
        }
        out
    }

    /// Factors `lines` periodic lines (modified Thomas; `sub` of row 0 and `sup` of row m−1
    /// are the corner entries), m ≥ 3. On an error the factorization is empty, as for
    /// [`factor_dirichlet`](Self::factor_dirichlet).
    pub fn factor_periodic(
        &mut self,
        m: usize,
        lines: usize,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
    ) -> Result<(), TridiagonalError> {
        let out = self.factor_periodic_lines(m, lines, sub, diag, sup);
        if out.is_err() {
            self.invalidate();
        }
        out
    }

    fn factor_periodic_lines(
        &mut self,
        m: usize,
        lines: usize,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
    ) -> Result<(), TridiagonalError> {
        let n = sizes_ok(m, lines, sub, diag, sup, 3)?;
        self.resize(Kind::Periodic, m, lines, n);
        self.sub.copy_from_slice(sub);
        if self.factor_periodic_batched(sub, diag, sup) {
            return Ok(());
        }
        // A pivot failed: the error of the first failing line and row, line by line.
        for l in 0..lines {
            self.factor_periodic_lane(l, sub, diag, sup)?;
        }
        Ok(())
    }

    /// Every line of a periodic factorization of this shape (m ≥ 3) at once, rows outermost and
    /// lines innermost, as [`factor_dirichlet_batched`](Self::factor_dirichlet_batched); each
    /// line does the operations of [`factor_periodic_lane`](Self::factor_periodic_lane) in its
    /// order (the same bits). Returns whether every pivot passed its check.
    fn factor_periodic_batched(&mut self, sub: &[f64], diag: &[f64], sup: &[f64]) -> bool {
        let (m, lines) = (self.m, self.lines);
        let last = m - 1;
        let last_row = last * lines..m * lines;
        let (b_last, d_last, a_last) = (
            &sub[last_row.clone()],
            &diag[last_row.clone()],
            &sup[last_row],
        );
        let mut ok = true;
        // Per line: the last row's scale and flush level, the running carried entry and d*.
        let mut scale_last = vec![0.0; lines];
        let mut carried_tol = vec![0.0; lines];
        let mut carried = vec![0.0; lines];
        for l in 0..lines {
            let (b, d, a) = (sub[l], diag[l], sup[l]);
            ok &= pivot_ok(d, b.abs() + d.abs() + a.abs());
            let r = 1.0 / d;
            let (u, f) = (a * r, b * r);
            self.recip[l] = r;
            self.upper[l] = u;
            self.fill[l] = f;
            scale_last[l] = b_last[l].abs() + d_last[l].abs() + a_last[l].abs();
            carried_tol[l] = FLUSH_RTOL * scale_last[l];
            self.carried[l] = a_last[l];
            self.d_star[l] = d_last[l] - a_last[l] * f;
            carried[l] = flush(-a_last[l] * u, carried_tol[l]);
        }
        for i in 1..last {
            let row = i * lines..(i + 1) * lines;
            let (b, d, a) = (&sub[row.clone()], &diag[row.clone()], &sup[row.clone()]);
            let (done_u, rest_u) = self.upper.split_at_mut(i * lines);
            let (u_prev, upper) = (&done_u[(i - 1) * lines..], &mut rest_u[..lines]);
            let (done_f, rest_f) = self.fill.split_at_mut(i * lines);
            let (f_prev, fill) = (&done_f[(i - 1) * lines..], &mut rest_f[..lines]);
            let recip = &mut self.recip[row.clone()];
            let carried_row = &mut self.carried[row];
            let d_star = &mut self.d_star[..lines];
            if i < last - 1 {
                for l in 0..lines {
                    let pivot = d[l] - b[l] * u_prev[l];
                    ok &= pivot_ok(pivot, b[l].abs() + d[l].abs() + a[l].abs());
                    let r = 1.0 / pivot;
                    let u = a[l] * r;
                    let f = flush(-(b[l] * f_prev[l]) * r, FLUSH_RTOL);
                    recip[l] = r;
                    upper[l] = u;
                    fill[l] = f;
                    carried_row[l] = carried[l];
                    d_star[l] -= carried[l] * f;
                    carried[l] = flush(-carried[l] * u, carried_tol[l]);
                }
            } else {
                // Row m − 2: its fill-in joins the super-diagonal entry of the last column.
                for l in 0..lines {
                    let pivot = d[l] - b[l] * u_prev[l];
                    ok &= pivot_ok(pivot, b[l].abs() + d[l].abs() + a[l].abs());
                    let r = 1.0 / pivot;
                    let f_m2 = (a[l] - b[l] * f_prev[l]) * r;
                    recip[l] = r;
                    upper[l] = 0.0;
                    fill[l] = f_m2;
                    carried[l] += b_last[l];
                    carried_row[l] = carried[l];
                    d_star[l] -= carried[l] * f_m2;
                    ok &= pivot_ok(d_star[l], scale_last[l]);
                }
            }
        }
        ok
    }

    /// Line `l` of a periodic factorization of this shape (m ≥ 3), from the interleaved
    /// coefficients.
    fn factor_periodic_lane(
        &mut self,
        l: usize,
        sub: &[f64],
        diag: &[f64],
        sup: &[f64],
    ) -> Result<(), TridiagonalError> {
        let (m, lines) = (self.m, self.lines);
        let last = m - 1;
        // As `cyclic_thomas_solve` (m ≥ 3), coefficient part only.
        let at = |i: usize| i * lines + l;
        let (b, d, a) = (sub[l], diag[l], sup[l]);
        let scale = b.abs() + d.abs() + a.abs();
        if !pivot_ok(d, scale) {
            return Err(zero_pivot(l, 0, d, scale));
        }
        let r = 1.0 / d;
        let mut u_prev = a * r;
        let mut f_prev = b * r;
        self.recip[l] = r;
        self.upper[l] = u_prev;
        self.fill[l] = f_prev;
        let (b_last, d_last, a_last) = (sub[at(last)], diag[at(last)], sup[at(last)]);
        let scale_last = b_last.abs() + d_last.abs() + a_last.abs();
        let carried_tol = FLUSH_RTOL * scale_last;
        let mut carried = a_last;
        self.carried[l] = carried;
        let mut d_star = d_last - carried * f_prev;
        carried = flush(-carried * u_prev, carried_tol);
        for i in 1..last - 1 {
            let k = at(i);
            let (b, d, a) = (sub[k], diag[k], sup[k]);
            let pivot = d - b * u_prev;
            let scale = b.abs() + d.abs() + a.abs();
            if !pivot_ok(pivot, scale) {
                return Err(zero_pivot(l, i, pivot, scale));
            }
            let r = 1.0 / pivot;
            u_prev = a * r;
            f_prev = flush(-(b * f_prev) * r, FLUSH_RTOL);
            self.recip[k] = r;
            self.upper[k] = u_prev;
            self.fill[k] = f_prev;
            self.carried[k] = carried;
            d_star -= carried * f_prev;
            carried = flush(-carried * u_prev, carried_tol);
        }
        let i = last - 1;
        let k = at(i);
        let (b, d, a) = (sub[k], diag[k], sup[k]);
        let pivot = d - b * u_prev;
        let scale = b.abs() + d.abs() + a.abs();
        if !pivot_ok(pivot, scale) {
            return Err(zero_pivot(l, i, pivot, scale));
        }
        let r = 1.0 / pivot;
        let f_m2 = (a - b * f_prev) * r;
        self.recip[k] = r;
        self.upper[k] = 0.0;
        self.fill[k] = f_m2;
        carried += b_last;
        self.carried[k] = carried;
        d_star -= carried * f_m2;
        if !pivot_ok(d_star, scale_last) {
            return Err(zero_pivot(l, last, d_star, scale_last));
        }
        self.d_star[l] = d_star;
        Ok(())
    }
}

impl<T: Real> InterleavedFactors<T> {
    /// Solves every line of the factorization for `rhs` (interleaved, `m · lines` values) into
    /// `x`. For `f64` the result is bit for bit that of the one-shot solver of the same lines.
    pub fn solve(&self, rhs: &[T], x: &mut [T]) -> Result<(), TridiagonalError> {
        let n = self.m * self.lines;
        if rhs.len() != n || x.len() != n {
            return Err(TridiagonalError::BatchSizeMismatch {
                m: self.m,
                lines: self.lines,
                sub: n,
                diag: n,
                sup: n,
                rhs: rhs.len(),
                x: x.len(),
            });
        }
        if n == 0 {
            return if self.m == 0 {
                Err(TridiagonalError::Empty)
            } else {
                Ok(())
            };
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of
            // calling a function compiled with `target_feature(enable = "avx2")`.
            return unsafe { self.solve_all_avx2(rhs, x) };
        }
        self.solve_all(rhs, x)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_all_avx2(&self, rhs: &[T], x: &mut [T]) -> Result<(), TridiagonalError> {
        self.solve_all(rhs, x)
    }

    #[inline(always)]
    fn solve_all(&self, rhs: &[T], x: &mut [T]) -> Result<(), TridiagonalError> {
        const LANES: usize = super::LANES;
        let lines = self.lines;
        let mut l0 = 0;
        let mut finite = true;
        while l0 + LANES <= lines {
            finite &= self.chunk::<LANES>(l0, rhs, x);
            l0 += LANES;
        }
        if lines - l0 >= 4 {
            finite &= self.chunk::<4>(l0, rhs, x);
            l0 += 4;
        }
        if lines - l0 >= 2 {
            finite &= self.chunk::<2>(l0, rhs, x);
            l0 += 2;
        }
        if lines - l0 >= 1 {
            finite &= self.chunk::<1>(l0, rhs, x);
        }
        if finite {
            return Ok(());
        }
        // The first line (then row) with a non-finite unknown.
        let (line, row) = (0..lines)
            .find_map(|l| {
                (0..self.m)
                    .find(|&i| !x[i * lines + l].finite())
                    .map(|i| (l, i))
            })
            .unwrap_or((0, 0));
        Err(TridiagonalError::NonFiniteSolutionInLine {
            line,
            row,
            value: x[row * lines + line].to_f64(),
        })
    }

    /// Lanes l0 … l0+L−1; returns whether every unknown is finite.
    #[inline(always)]
    fn chunk<const L: usize>(&self, l0: usize, rhs: &[T], x: &mut [T]) -> bool {
        match self.kind {
            Kind::Dirichlet => self.chunk_dirichlet::<L>(l0, rhs, x),
            Kind::Periodic => self.chunk_periodic::<L>(l0, rhs, x),
        }
    }

    #[inline(always)]
    fn chunk_dirichlet<const L: usize>(&self, l0: usize, rhs: &[T], x: &mut [T]) -> bool {
        let (m, lines) = (self.m, self.lines);
        let c: [T; L] = load(rhs, l0);
        let r: [T; L] = load(&self.recip, l0);
        let mut y_prev = lanes::<T, L>(|k| c[k] * r[k]);
        store(x, l0, &y_prev);
        for i in 1..m {
            let at = i * lines + l0;
            let (b, c, r): ([T; L], [T; L], [T; L]) =
                (load(&self.sub, at), load(rhs, at), load(&self.recip, at));
            y_prev = lanes::<T, L>(|k| (c[k] - b[k] * y_prev[k]) * r[k]);
            store(x, at, &y_prev);
        }
        let mut x_next = y_prev;
        let mut finite = x_next.map(T::finite);
        for i in (0..m - 1).rev() {
            let at = i * lines + l0;
            let (y, u): ([T; L], [T; L]) = (load(x, at), load(&self.upper, at));
            x_next = lanes::<T, L>(|k| y[k] - u[k] * x_next[k]);
            for k in 0..L {
                finite[k] &= x_next[k].finite();
            }
            store(x, at, &x_next);
        }
        !finite.contains(&false)
    }

    #[inline(always)]
    fn chunk_periodic<const L: usize>(&self, l0: usize, rhs: &[T], x: &mut [T]) -> bool {
        let (m, lines) = (self.m, self.lines);
        let last = m - 1;
        // Row 0 and the fused last row.
        let c: [T; L] = load(rhs, l0);
        let r: [T; L] = load(&self.recip, l0);
        let mut y_prev = lanes::<T, L>(|k| c[k] * r[k]);
        store(x, l0, &y_prev);
        let c_last: [T; L] = load(rhs, last * lines + l0);
        let carried: [T; L] = load(&self.carried, l0);
        let mut c_star = lanes::<T, L>(|k| c_last[k] - carried[k] * y_prev[k]);
        // Rows 1 … m-2.
        for i in 1..last {
            let at = i * lines + l0;
            let (b, c, r, carried): ([T; L], [T; L], [T; L], [T; L]) = (
                load(&self.sub, at),
                load(rhs, at),
                load(&self.recip, at),
                load(&self.carried, at),
            );
            y_prev = lanes::<T, L>(|k| (c[k] - b[k] * y_prev[k]) * r[k]);
            store(x, at, &y_prev);
            c_star = lanes::<T, L>(|k| c_star[k] - carried[k] * y_prev[k]);
        }
        // Back substitution.
        let d_star: [T; L] = load(&self.d_star, l0);
        let x_last = lanes::<T, L>(|k| c_star[k] / d_star[k]);
        store(x, last * lines + l0, &x_last);
        let i = last - 1;
        let f_m2: [T; L] = load(&self.fill, i * lines + l0);
        let mut x_next = lanes::<T, L>(|k| y_prev[k] - f_m2[k] * x_last[k]);
        store(x, i * lines + l0, &x_next);
        let mut finite: [bool; L] =
            std::array::from_fn(|k| x_last[k].finite() & x_next[k].finite());
        for i in (0..last - 1).rev() {
            let at = i * lines + l0;
            let (y, u, f): ([T; L], [T; L], [T; L]) =
                (load(x, at), load(&self.upper, at), load(&self.fill, at));
            x_next = lanes::<T, L>(|k| (y[k] - u[k] * x_next[k]) - f[k] * x_last[k]);
            for k in 0..L {
                finite[k] &= x_next[k].finite();
            }
            store(x, at, &x_next);
        }
        !finite.contains(&false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tridiagonal::{
        BatchWorkspace, cyclic_thomas_solve_interleaved, thomas_solve_interleaved,
    };

    /// xorshift64*: deterministic values in [-1, 1).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let v = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
            (v >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// Lines like the Reynolds rows: some diagonally dominant, some upwind (lower bidiagonal
    /// plus diagonal, not dominant by rows), with a spread of magnitudes.
    fn lines(m: usize, lines: usize, rng: &mut Rng) -> [Vec<f64>; 4] {
        let n = m * lines;
        let (mut b, mut d, mut a, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for k in 0..n {
            let mag = 10f64.powf(3.0 * rng.next());
            b[k] = mag * rng.next();
            a[k] = if k % 5 == 0 { 0.0 } else { mag * rng.next() };
            d[k] = mag * (2.5 + rng.next()) * if k % 7 == 0 { -1.0 } else { 1.0 };
            c[k] = rng.next() * 1e3;
        }
        [b, d, a, c]
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn factored_solves_equal_the_one_shot_batch_solvers_bit_for_bit() {
        // Every remainder of the 8-lane chunks (lines 1 … 19) and short and long lines; three
        // right-hand sides per factorization (the factors must not change between solves).
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut fac = InterleavedFactors::default();
        let mut work = BatchWorkspace::default();
        for m in [3usize, 4, 5, 8, 31, 120] {
            for nl in 1..=19 {
                let [b, d, a, _] = lines(m, nl, &mut rng);
                fac.factor_periodic(m, nl, &b, &d, &a).unwrap();
                for _ in 0..3 {
                    let c: Vec<f64> = (0..m * nl).map(|_| rng.next() * 1e3).collect();
                    let (mut x1, mut x2) = (vec![0.0; m * nl], vec![0.0; m * nl]);
                    cyclic_thomas_solve_interleaved(m, nl, &b, &d, &a, &c, &mut x1, &mut work)
                        .unwrap();
                    fac.solve(&c, &mut x2).unwrap();
                    assert_eq!(bits(&x1), bits(&x2), "periodic m = {m}, lines = {nl}");
                }
                fac.factor_dirichlet(m, nl, &b, &d, &a).unwrap();
                for _ in 0..3 {
                    let c: Vec<f64> = (0..m * nl).map(|_| rng.next() * 1e3).collect();
                    let (mut x1, mut x2) = (vec![0.0; m * nl], vec![0.0; m * nl]);
                    thomas_solve_interleaved(m, nl, &b, &d, &a, &c, &mut x1, &mut work).unwrap();
                    fac.solve(&c, &mut x2).unwrap();
                    assert_eq!(bits(&x1), bits(&x2), "Dirichlet m = {m}, lines = {nl}");
                }
            }
        }
    }

    #[test]
    fn a_vanishing_pivot_is_named_as_the_batch_solver_names_it() {
        // Line 5 of 11 gets a zero pivot in row 3 (d_3 = b_3 u_2 exactly: u_2 = 0 because
        // a_2 = 0, so d_3 = 0 makes the pivot 0).
        let (m, nl) = (9, 11);
        let mut rng = Rng(7);
        let [mut b, mut d, mut a, c] = lines(m, nl, &mut rng);
        a[2 * nl + 5] = 0.0;
        d[3 * nl + 5] = 0.0;
        let mut work = BatchWorkspace::default();
        let mut x = vec![0.0; m * nl];
        let mut fac = InterleavedFactors::default();
        for periodic in [false, true] {
            let (one_shot, factored) = if periodic {
                (
                    cyclic_thomas_solve_interleaved(m, nl, &b, &d, &a, &c, &mut x, &mut work),
                    fac.factor_periodic(m, nl, &b, &d, &a),
                )
            } else {
                (
                    thomas_solve_interleaved(m, nl, &b, &d, &a, &c, &mut x, &mut work),
                    fac.factor_dirichlet(m, nl, &b, &d, &a),
                )
            };
            let e = factored.unwrap_err();
            assert_eq!(one_shot.unwrap_err(), e);
            assert!(
                matches!(
                    e,
                    TridiagonalError::ZeroPivotInLine {
                        line: 5,
                        row: 3,
                        ..
                    }
                ),
                "{e}"
            );
        }
        // A failed factorization leaves nothing to solve with.
        assert_eq!(fac.shape(), (0, 0));
        assert!(
            fac.solve(&c, &mut x).is_err(),
            "solve after a failed factorization"
        );
        // Sizes: mismatched slices and too-short periodic lines are errors, not panics.
        b.pop();
        assert!(fac.factor_dirichlet(m, nl, &b, &d, &a).is_err());
        d.truncate(2 * nl);
        assert!(
            fac.factor_periodic(2, nl, &d, &d, &d).is_err(),
            "periodic lines need m ≥ 3"
        );
    }

    /// The factors rounded to `f32` solve the same lines to single precision: for these
    /// lines (pivots ≥ 1.5 of the row's magnitude, so every |u_i|, |f_i| < 1 and the
    /// substitutions do not amplify errors beyond a few roundings per row), the `f32` solution
    /// is within 1e-5 of the largest `f64` unknown (2⁻²⁴ ≈ 6e-8 per rounding, ~30 roundings per
    /// line of 31 rows and a margin). A reciprocal pivot beyond the range of `f32` is an error
    /// naming its line, not an infinity.
    #[test]
    fn factors_rounded_to_single_precision_solve_to_single_precision() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut fac = InterleavedFactors::default();
        let mut fac32 = InterleavedFactors::<f32>::default();
        for m in [3usize, 8, 31, 120] {
            for nl in [1usize, 7, 16, 31, 37] {
                let n = m * nl;
                let (mut b, mut d, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                for k in 0..n {
                    let mag = 10f64.powf(3.0 * rng.next());
                    b[k] = 0.5 * mag * rng.next();
                    a[k] = 0.5 * mag * rng.next();
                    d[k] = mag * (2.5 + rng.next());
                }
                for periodic in [false, true] {
                    if periodic {
                        fac.factor_periodic(m, nl, &b, &d, &a).unwrap();
                    } else {
                        fac.factor_dirichlet(m, nl, &b, &d, &a).unwrap();
                    }
                    fac32.round_from(&fac).unwrap();
                    let c: Vec<f64> = (0..n).map(|_| rng.next() * 1e3).collect();
                    let c32: Vec<f32> = c.iter().map(|&v| v as f32).collect();
                    let (mut x, mut x32) = (vec![0.0; n], vec![0.0f32; n]);
                    fac.solve(&c, &mut x).unwrap();
                    fac32.solve(&c32, &mut x32).unwrap();
                    let xmax = x.iter().fold(0.0f64, |s, v| s.max(v.abs()));
                    let err = x
                        .iter()
                        .zip(&x32)
                        .fold(0.0f64, |s, (v, w)| s.max((v - f64::from(*w)).abs()));
                    assert!(
                        err <= 1e-5 * xmax,
                        "m = {m}, lines = {nl}, periodic {periodic}: {err:e} of {xmax:e}"
                    );
                }
            }
        }
        // Line 2 of 4 has tiny rows (a pivot of 1e-300 is sound in f64 against its row's
        // scale of the same size), whose reciprocal overflows f32.
        let (m, nl) = (5, 4);
        let mut d = vec![1.0; m * nl];
        for i in 0..m {
            d[i * nl + 2] = 1e-300;
        }
        let zero = vec![0.0; m * nl];
        fac.factor_dirichlet(m, nl, &zero, &d, &zero).unwrap();
        let e = fac32.round_from(&fac).unwrap_err();
        assert!(
            matches!(
                e,
                TridiagonalError::ZeroPivotInLine {
                    line: 2,
                    row: 0,
                    ..
                }
            ),
            "{e}"
        );
        assert_eq!(fac32.shape(), (0, 0), "nothing left to solve with");
    }

    #[test]
    fn a_non_finite_right_hand_side_is_reported_with_its_line() {
        let (m, nl) = (12, 10);
        let mut rng = Rng(11);
        let [b, d, a, mut c] = lines(m, nl, &mut rng);
        c[4 * nl + 6] = f64::NAN;
        let mut fac = InterleavedFactors::default();
        let mut x = vec![0.0; m * nl];
        fac.factor_periodic(m, nl, &b, &d, &a).unwrap();
        let e = fac.solve(&c, &mut x).unwrap_err();
        assert!(
            matches!(e, TridiagonalError::NonFiniteSolutionInLine { line: 6, .. }),
            "{e}"
        );
        assert!(fac.solve(&c[1..], &mut x).is_err(), "short right-hand side");
    }
}
