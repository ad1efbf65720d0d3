//! Many independent lines in one call, vectorized across lines.
//!
//! An ADI half sweep solves one tridiagonal (or periodic tridiagonal) system per grid line, all
//! of the same length m and all independent. Each single-line recurrence is serial (row i needs
//! row i-1) and its critical path runs through one division per row, so a single line cannot
//! use SIMD and waits on the divider. Across lines there is no dependency at all: the kernels
//! here run the *same* recurrences as [`thomas_solve`](super::thomas_solve) and
//! [`cyclic_thomas_solve`](super::cyclic_thomas_solve) on [`LANES`] lines at once, one SIMD lane
//! per line, which both fills the vector units and overlaps the divisions of different lines.
//!
//! ## Layout (structure of arrays, lines interleaved)
//!
//! Unknown i of line l is at index `i * lines + l` of each of `sub`, `diag`, `sup`, `rhs`, `x`:
//!
//! ```text
//!               line 0   line 1   …   line L-1
//!     row 0   [   0        1      …    L-1     ]
//!     row 1   [   L       L+1     …   2L-1     ]
//!       ⋮
//!     row m-1 [ (m-1)L     …           mL-1    ]
//! ```
//!
//! This is the layout of the circumferential lines (fixed z, periodic in θ) of a grid stored
//! θ-major with z fastest: `field[iθ * nz + iz]` *is* line iz, unknown iθ, with `lines = nz`.
//! The matrix conventions per line are those of the single-line API (`sub` of row 0 and `sup`
//! of row m-1 are the corner entries of a periodic line and are ignored on a Dirichlet line).
//!
//! ## Chunks of lanes
//!
//! The lines are processed in chunks of [`LANES`] = 8 consecutive lines. For one chunk, row i of
//! every input is one contiguous run of 8 values (64 bytes, a cache line when aligned), loaded
//! into fixed-size arrays `[f64; 8]`; every operation of the recurrence is a loop of fixed trip
//! count over those arrays, which LLVM turns into straight-line SIMD code (4 SSE2 or 2 AVX
//! vectors, independent of each other). A remainder of `lines % 8` lines is handled by the same
//! generic code instantiated for chunks of 4, 2 and 1 lanes. The workspace holds the normalised
//! super-diagonal u and fill-in f of one chunk: 2 · m · 8 values, independent of `lines`.
//!
//! ## Instruction sets
//!
//! The default x86-64 target only guarantees SSE2 (2 doubles per vector). On x86-64 the chunk
//! loop is compiled twice, for that baseline and with AVX2 enabled (4 doubles per vector), and
//! the AVX2 copy is chosen at run time when the CPU has it (`is_x86_feature_detected!`). Only the
//! width of the vectors differs: the same IEEE operations in the same order (AVX2 code contains
//! no fused multiply-add unless asked for, and nothing here asks), so both copies give the same
//! bits as the single-line functions.
//!
//! ## Pivot checks without branches
//!
//! Each lane accumulates a flag `ok &= pivot_ok(pivot, scale)` (a compare and an and, no branch)
//! over the forward sweep of its chunk; the chunk's flags are inspected once, before the back
//! substitution. Only when one is false is the first failing line of the chunk re-run alone,
//! with the identical arithmetic and a check after every row, to name the row, the pivot and
//! the scale in [`TridiagonalError::ZeroPivotInLine`]. The back substitution accumulates a
//! finiteness flag the same way ([`TridiagonalError::NonFiniteSolutionInLine`]).
//!
//! Errors stop the solve at the first chunk that fails; within it a vanishing pivot is reported
//! in preference to a non-finite unknown, for the lowest line of the chunk that has one. On an
//! error the contents of `x` are unspecified.
//!
//! ## Bit-for-bit agreement with the single-line API
//!
//! The result of a batched solve equals, **bit for bit**, what the single-line function returns
//! for each line. Reason: per lane, the batched kernels perform exactly the same IEEE-754
//! operations in exactly the same order as the single-line code (the same normalised
//! recurrences of the module `tridiagonal`, one `1/pivot` then multiplications, no `mul_add`).
//! Rust does not reassociate floating-point arithmetic or contract a·b + c into a fused
//! multiply-add on its own, and SIMD lanes round exactly like scalar operations, so
//! vectorization cannot change a bit. The tests assert equality with `==` on the bit patterns.
//! (This would break only under a target whose scalar and vector arithmetic differ, such as x87,
//! which Rust's x86-64 targets do not use.)

use super::{FLUSH_RTOL, LineWorkspace, TridiagonalError, cyclic_thomas_solve, flush, pivot_ok};

/// Number of lines solved together in one chunk (SIMD lanes of the batched kernels).
pub const LANES: usize = 8;

/// Reusable scratch memory of the batched line solvers: no allocation per solve.
///
/// Holds the normalised super-diagonal and fill-in column of one chunk of [`LANES`] lines, so
/// its size depends on the line length m only. It grows on demand if a longer line comes (the
/// only allocation) and never shrinks.
#[derive(Debug, Clone, Default)]
pub struct BatchWorkspace {
    /// u of one chunk: row i, lane k at `i * L + k`.
    upper: Vec<f64>,
    /// f of one chunk, same layout.
    fill: Vec<f64>,
}

impl BatchWorkspace {
    /// A workspace sized for batches of lines of `m` unknowns. `lines` does not change the size
    /// (the kernels work through the lines in chunks of [`LANES`]); it is part of the signature
    /// so that a caller states the batch it is preparing for.
    pub fn new(m: usize, lines: usize) -> Self {
        let _ = lines;
        let mut w = Self::default();
        w.ensure(m);
        w
    }

    fn ensure(&mut self, m: usize) {
        let n = m.saturating_mul(LANES);
        if self.upper.len() < n {
            self.upper.resize(n, 0.0);
            self.fill.resize(n, 0.0);
        }
    }
}

/// Solves `lines` independent Dirichlet lines of `m` unknowns, stored interleaved (unknown i of
/// line l at `i * lines + l`), by the Thomas algorithm vectorized across lines.
///
/// Per line this is exactly [`thomas_solve`](super::thomas_solve) (same result, bit for bit);
/// see the module documentation for layout, errors and the agreement. Every slice must hold
/// `m * lines` values. `lines = 0` is an empty batch and succeeds.
#[allow(clippy::too_many_arguments)]
pub fn thomas_solve_interleaved(
    m: usize,
    lines: usize,
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    rhs: &[f64],
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> Result<(), TridiagonalError> {
    let batch = Batch::new(m, lines, sub, diag, sup, rhs, x)?;
    work.ensure(m);
    solve_all(&Dirichlet(batch), x, work)
}

/// Solves `lines` independent periodic lines of `m` unknowns, stored interleaved (unknown i of
/// line l at `i * lines + l`), by Yu & Sawicki's modified Thomas algorithm vectorized across
/// lines.
///
/// Per line this is exactly [`cyclic_thomas_solve`] (same result, bit for bit), including the
/// degenerate sizes m = 1 and 2; see the module documentation for layout, errors and the
/// agreement. Every slice must hold `m * lines` values. `lines = 0` is an empty batch and
/// succeeds.
#[allow(clippy::too_many_arguments)]
pub fn cyclic_thomas_solve_interleaved(
    m: usize,
    lines: usize,
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    rhs: &[f64],
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> Result<(), TridiagonalError> {
    let batch = Batch::new(m, lines, sub, diag, sup, rhs, x)?;
    if m <= 2 {
        return small_periodic_lines(&batch, x);
    }
    work.ensure(m);
    solve_all(&Periodic(batch), x, work)
}

/// The inputs of a batch, sizes checked.
struct Batch<'a> {
    m: usize,
    lines: usize,
    sub: &'a [f64],
    diag: &'a [f64],
    sup: &'a [f64],
    rhs: &'a [f64],
}

impl<'a> Batch<'a> {
    fn new(
        m: usize,
        lines: usize,
        sub: &'a [f64],
        diag: &'a [f64],
        sup: &'a [f64],
        rhs: &'a [f64],
        x: &[f64],
    ) -> Result<Self, TridiagonalError> {
        let n = m.checked_mul(lines);
        let fits = |s: &[f64]| Some(s.len()) == n;
        if !(fits(sub) && fits(diag) && fits(sup) && fits(rhs) && fits(x)) {
            return Err(TridiagonalError::BatchSizeMismatch {
                m,
                lines,
                sub: sub.len(),
                diag: diag.len(),
                sup: sup.len(),
                rhs: rhs.len(),
                x: x.len(),
            });
        }
        if m == 0 {
            return Err(TridiagonalError::Empty);
        }
        Ok(Self {
            m,
            lines,
            sub,
            diag,
            sup,
            rhs,
        })
    }

    /// Row i of lanes l0 … l0+L-1 of `s`.
    #[inline(always)]
    fn row<const L: usize>(&self, s: &[f64], i: usize, l0: usize) -> [f64; L] {
        load(s, i * self.lines + l0)
    }
}

#[inline(always)]
pub(super) fn load<T: Copy, const L: usize>(s: &[T], at: usize) -> [T; L] {
    let c = &s[at..at + L];
    std::array::from_fn(|k| c[k])
}

#[inline(always)]
pub(super) fn store<T: Copy, const L: usize>(s: &mut [T], at: usize, v: &[T; L]) {
    s[at..at + L].copy_from_slice(v);
}

/// Elementwise map of lane arrays (a fixed-trip-count loop that LLVM vectorizes).
#[inline(always)]
pub(super) fn lanes<T, const L: usize>(f: impl FnMut(usize) -> T) -> [T; L] {
    std::array::from_fn(f)
}

/// `ok[k] &= pivot sound`; in `LOCATE` mode (one lane) stop at the first failing row.
#[inline(always)]
fn check<const L: usize, const LOCATE: bool>(
    ok: &mut [bool; L],
    pivot: &[f64; L],
    scale: &[f64; L],
    line: usize,
    row: usize,
) -> Result<(), ChunkError<L>> {
    for k in 0..L {
        ok[k] &= pivot_ok(pivot[k], scale[k]);
    }
    if LOCATE && !ok[0] {
        return Err(ChunkError::Located(TridiagonalError::ZeroPivotInLine {
            line,
            row,
            pivot: pivot[0],
            scale: scale[0],
        }));
    }
    Ok(())
}

/// How a chunk failed: per-lane flags (true = failed), or, in `LOCATE` mode, the error itself.
enum ChunkError<const L: usize> {
    Pivot([bool; L]),
    NonFinite([bool; L]),
    Located(TridiagonalError),
}

/// One of the two line kinds, solved for a chunk of `L` lanes starting at line `l0`.
trait ChunkKernel {
    fn batch(&self) -> &Batch<'_>;
    /// `u`, `f`: workspace of `m * L` values. With `LOCATE` (only used with `L = 1`) the first
    /// vanishing pivot returns [`ChunkError::Located`] at once.
    fn chunk<const L: usize, const LOCATE: bool>(
        &self,
        l0: usize,
        x: &mut [f64],
        u: &mut [f64],
        f: &mut [f64],
    ) -> Result<(), ChunkError<L>>;
}

/// Runs the chunks, with AVX2 when the CPU has it (see "Instruction sets" in the module docs).
fn solve_all<K: ChunkKernel>(
    kernel: &K,
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> Result<(), TridiagonalError> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of calling
        // a function compiled with `target_feature(enable = "avx2")`.
        return unsafe { solve_all_avx2(kernel, x, work) };
    }
    solve_all_generic(kernel, x, work)
}

/// [`solve_all_generic`] compiled for AVX2 (4 doubles per vector instead of SSE2's 2).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn solve_all_avx2<K: ChunkKernel>(
    kernel: &K,
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> Result<(), TridiagonalError> {
    solve_all_generic(kernel, x, work)
}

#[inline(always)]
fn solve_all_generic<K: ChunkKernel>(
    kernel: &K,
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> Result<(), TridiagonalError> {
    let lines = kernel.batch().lines;
    let mut l0 = 0;
    while l0 + LANES <= lines {
        solve_chunk::<K, LANES>(kernel, l0, x, work)?;
        l0 += LANES;
    }
    // Remainder: chunks of 4, 2, 1 lanes (at most one of each since LANES = 8).
    if lines - l0 >= 4 {
        solve_chunk::<K, 4>(kernel, l0, x, work)?;
        l0 += 4;
    }
    if lines - l0 >= 2 {
        solve_chunk::<K, 2>(kernel, l0, x, work)?;
        l0 += 2;
    }
    if lines - l0 >= 1 {
        solve_chunk::<K, 1>(kernel, l0, x, work)?;
    }
    Ok(())
}

#[inline(always)]
fn solve_chunk<K: ChunkKernel, const L: usize>(
    kernel: &K,
    l0: usize,
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> Result<(), TridiagonalError> {
    let b = kernel.batch();
    let (m, lines) = (b.m, b.lines);
    let (u, f) = (&mut work.upper[..m * L], &mut work.fill[..m * L]);
    match kernel.chunk::<L, false>(l0, x, u, f) {
        Ok(()) => Ok(()),
        Err(ChunkError::Located(e)) => Err(e),
        Err(ChunkError::Pivot(bad)) => Err(locate_pivot(kernel, l0, &bad, x, work)),
        Err(ChunkError::NonFinite(bad)) => {
            let lane = bad.iter().position(|&b| b).unwrap_or(0);
            let line = l0 + lane;
            let row = (0..m)
                .find(|&i| !x[i * lines + line].is_finite())
                .unwrap_or(0);
            Err(TridiagonalError::NonFiniteSolutionInLine {
                line,
                row,
                value: x[row * lines + line],
            })
        }
    }
}

/// Re-runs the first failing lane alone, checking after every row, to name row and pivot.
#[cold]
#[inline(never)]
fn locate_pivot<K: ChunkKernel, const L: usize>(
    kernel: &K,
    l0: usize,
    bad: &[bool; L],
    x: &mut [f64],
    work: &mut BatchWorkspace,
) -> TridiagonalError {
    let m = kernel.batch().m;
    let line = l0 + bad.iter().position(|&b| b).unwrap_or(0);
    let (u, f) = (&mut work.upper[..m], &mut work.fill[..m]);
    match kernel.chunk::<1, true>(line, x, u, f) {
        Err(ChunkError::Located(e)) => e,
        // Unreachable: the re-run performs the identical operations, so it fails at the same
        // pivot. Reported conservatively rather than panicking.
        _ => TridiagonalError::ZeroPivotInLine {
            line,
            row: m - 1,
            pivot: f64::NAN,
            scale: f64::NAN,
        },
    }
}

/// Dirichlet lines: Thomas, operation for operation as in `thomas_solve`.
struct Dirichlet<'a>(Batch<'a>);

impl ChunkKernel for Dirichlet<'_> {
    fn batch(&self) -> &Batch<'_> {
        &self.0
    }

    #[inline(always)]
    fn chunk<const L: usize, const LOCATE: bool>(
        &self,
        l0: usize,
        x: &mut [f64],
        u: &mut [f64],
        _f: &mut [f64],
    ) -> Result<(), ChunkError<L>> {
        let bt = &self.0;
        let (m, lines) = (bt.m, bt.lines);
        let mut ok = [true; L];

        // Row 0.
        let a: [f64; L] = if m > 1 {
            bt.row(bt.sup, 0, l0)
        } else {
            [0.0; L]
        };
        let d: [f64; L] = bt.row(bt.diag, 0, l0);
        let c: [f64; L] = bt.row(bt.rhs, 0, l0);
        let scale = lanes::<f64, L>(|k| d[k].abs() + a[k].abs());
        check::<L, LOCATE>(&mut ok, &d, &scale, l0, 0)?;
        let r = lanes::<f64, L>(|k| 1.0 / d[k]);
        let mut u_prev = lanes::<f64, L>(|k| a[k] * r[k]);
        let mut y_prev = lanes::<f64, L>(|k| c[k] * r[k]);
        store(u, 0, &u_prev);
        store(x, l0, &y_prev);

        // Rows 1 … m-1 (the last one has no super-diagonal).
        for i in 1..m {
            let a: [f64; L] = if i + 1 < m {
                bt.row(bt.sup, i, l0)
            } else {
                [0.0; L]
            };
            let b: [f64; L] = bt.row(bt.sub, i, l0);
            let d: [f64; L] = bt.row(bt.diag, i, l0);
            let c: [f64; L] = bt.row(bt.rhs, i, l0);
            let pivot = lanes::<f64, L>(|k| d[k] - b[k] * u_prev[k]);
            let scale = lanes::<f64, L>(|k| b[k].abs() + d[k].abs() + a[k].abs());
            check::<L, LOCATE>(&mut ok, &pivot, &scale, l0, i)?;
            let r = lanes::<f64, L>(|k| 1.0 / pivot[k]);
            u_prev = lanes::<f64, L>(|k| a[k] * r[k]);
            y_prev = lanes::<f64, L>(|k| (c[k] - b[k] * y_prev[k]) * r[k]);
            store(u, i * L, &u_prev);
            store(x, i * lines + l0, &y_prev);
        }
        if ok.contains(&false) {
            return Err(ChunkError::Pivot(ok.map(|o| !o)));
        }

        // Back substitution; y_prev holds x_{m-1}.
        let mut x_next = y_prev;
        let mut finite = x_next.map(f64::is_finite);
        for i in (0..m - 1).rev() {
            let at = i * lines + l0;
            let y: [f64; L] = load(x, at);
            let ui: [f64; L] = load(u, i * L);
            x_next = lanes::<f64, L>(|k| y[k] - ui[k] * x_next[k]);
            for k in 0..L {
                finite[k] &= x_next[k].is_finite();
            }
            store(x, at, &x_next);
        }
        if finite.contains(&false) {
            return Err(ChunkError::NonFinite(finite.map(|o| !o)));
        }
        Ok(())
    }
}

/// Periodic lines with m ≥ 3: modified Thomas, operation for operation as in
/// `cyclic_thomas_solve` (see the module `tridiagonal` for the derivation).
struct Periodic<'a>(Batch<'a>);

impl ChunkKernel for Periodic<'_> {
    fn batch(&self) -> &Batch<'_> {
        &self.0
    }

    #[inline(always)]
    fn chunk<const L: usize, const LOCATE: bool>(
        &self,
        l0: usize,
        x: &mut [f64],
        u: &mut [f64],
        f: &mut [f64],
    ) -> Result<(), ChunkError<L>> {
        let bt = &self.0;
        let (m, lines) = (bt.m, bt.lines);
        let last = m - 1;
        let mut ok = [true; L];

        // Row 0: pivot d_0; its fill-in entry is the corner b_0.
        let b: [f64; L] = bt.row(bt.sub, 0, l0);
        let d: [f64; L] = bt.row(bt.diag, 0, l0);
        let a: [f64; L] = bt.row(bt.sup, 0, l0);
        let c: [f64; L] = bt.row(bt.rhs, 0, l0);
        let scale = lanes::<f64, L>(|k| b[k].abs() + d[k].abs() + a[k].abs());
        check::<L, LOCATE>(&mut ok, &d, &scale, l0, 0)?;
        let r = lanes::<f64, L>(|k| 1.0 / d[k]);
        let mut u_prev = lanes::<f64, L>(|k| a[k] * r[k]);
        let mut f_prev = lanes::<f64, L>(|k| b[k] * r[k]);
        let mut y_prev = lanes::<f64, L>(|k| c[k] * r[k]);
        store(u, 0, &u_prev);
        store(f, 0, &f_prev);
        store(x, l0, &y_prev);
        // Last row, fused: remove its column-0 entry A_0 = a_{m-1} with row 0.
        let b_last: [f64; L] = bt.row(bt.sub, last, l0);
        let d_last: [f64; L] = bt.row(bt.diag, last, l0);
        let a_last: [f64; L] = bt.row(bt.sup, last, l0);
        let c_last: [f64; L] = bt.row(bt.rhs, last, l0);
        let scale_last = lanes::<f64, L>(|k| b_last[k].abs() + d_last[k].abs() + a_last[k].abs());
        let carried_tol = lanes::<f64, L>(|k| FLUSH_RTOL * scale_last[k]);
        let mut carried = a_last;
        let mut d_star = lanes::<f64, L>(|k| d_last[k] - carried[k] * f_prev[k]);
        let mut c_star = lanes::<f64, L>(|k| c_last[k] - carried[k] * y_prev[k]);
        carried = lanes::<f64, L>(|k| flush(-carried[k] * u_prev[k], carried_tol[k]));

        // Rows 1 … m-3.
        for i in 1..last - 1 {
            let b: [f64; L] = bt.row(bt.sub, i, l0);
            let d: [f64; L] = bt.row(bt.diag, i, l0);
            let a: [f64; L] = bt.row(bt.sup, i, l0);
            let c: [f64; L] = bt.row(bt.rhs, i, l0);
            let pivot = lanes::<f64, L>(|k| d[k] - b[k] * u_prev[k]);
            let scale = lanes::<f64, L>(|k| b[k].abs() + d[k].abs() + a[k].abs());
            check::<L, LOCATE>(&mut ok, &pivot, &scale, l0, i)?;
            let r = lanes::<f64, L>(|k| 1.0 / pivot[k]);
            u_prev = lanes::<f64, L>(|k| a[k] * r[k]);
            f_prev = lanes::<f64, L>(|k| flush(-(b[k] * f_prev[k]) * r[k], FLUSH_RTOL));
            y_prev = lanes::<f64, L>(|k| (c[k] - b[k] * y_prev[k]) * r[k]);
            store(u, i * L, &u_prev);
            store(f, i * L, &f_prev);
            store(x, i * lines + l0, &y_prev);
            d_star = lanes::<f64, L>(|k| d_star[k] - carried[k] * f_prev[k]);
            c_star = lanes::<f64, L>(|k| c_star[k] - carried[k] * y_prev[k]);
            carried = lanes::<f64, L>(|k| flush(-carried[k] * u_prev[k], carried_tol[k]));
        }

        // Row m-2: its super-diagonal entry lies in the fill-in column m-1.
        let i = last - 1;
        let b: [f64; L] = bt.row(bt.sub, i, l0);
        let d: [f64; L] = bt.row(bt.diag, i, l0);
        let a: [f64; L] = bt.row(bt.sup, i, l0);
        let c: [f64; L] = bt.row(bt.rhs, i, l0);
        let pivot = lanes::<f64, L>(|k| d[k] - b[k] * u_prev[k]);
        let scale = lanes::<f64, L>(|k| b[k].abs() + d[k].abs() + a[k].abs());
        check::<L, LOCATE>(&mut ok, &pivot, &scale, l0, i)?;
        let r = lanes::<f64, L>(|k| 1.0 / pivot[k]);
        let f_m2 = lanes::<f64, L>(|k| (a[k] - b[k] * f_prev[k]) * r[k]);
        let y_m2 = lanes::<f64, L>(|k| (c[k] - b[k] * y_prev[k]) * r[k]);
        // The last row's column m-2 holds b_{m-1} besides the carried entry.
        carried = lanes::<f64, L>(|k| carried[k] + b_last[k]);
        d_star = lanes::<f64, L>(|k| d_star[k] - carried[k] * f_m2[k]);
        c_star = lanes::<f64, L>(|k| c_star[k] - carried[k] * y_m2[k]);
        check::<L, LOCATE>(&mut ok, &d_star, &scale_last, l0, last)?;
        if ok.contains(&false) {
            return Err(ChunkError::Pivot(ok.map(|o| !o)));
        }

        // Back substitution.
        let x_last = lanes::<f64, L>(|k| c_star[k] / d_star[k]);
        store(x, last * lines + l0, &x_last);
        let mut x_next = lanes::<f64, L>(|k| y_m2[k] - f_m2[k] * x_last[k]);
        store(x, i * lines + l0, &x_next);
        let mut finite: [bool; L] =
            std::array::from_fn(|k| x_last[k].is_finite() & x_next[k].is_finite());
        for i in (0..last - 1).rev() {
            let at = i * lines + l0;
            let y: [f64; L] = load(x, at);
            let ui: [f64; L] = load(u, i * L);
            let fi: [f64; L] = load(f, i * L);
            x_next = lanes::<f64, L>(|k| (y[k] - ui[k] * x_next[k]) - fi[k] * x_last[k]);
            for k in 0..L {
                finite[k] &= x_next[k].is_finite();
            }
            store(x, at, &x_next);
        }
        if finite.contains(&false) {
            return Err(ChunkError::NonFinite(finite.map(|o| !o)));
        }
        Ok(())
    }
}

/// Periodic lines of 1 or 2 unknowns: per line exactly the single-line formulas, through the
/// single-line function on a copy of the line (at most 2 values; no allocation).
fn small_periodic_lines(bt: &Batch<'_>, x: &mut [f64]) -> Result<(), TridiagonalError> {
    let (m, lines) = (bt.m, bt.lines);
    let mut work = LineWorkspace::default(); // never grows: m ≤ 2 needs no scratch
    for line in 0..lines {
        let gather = |s: &[f64]| -> [f64; 2] {
            std::array::from_fn(|i| if i < m { s[i * lines + line] } else { 0.0 })
        };
        let (b, d, a, c) = (
            gather(bt.sub),
            gather(bt.diag),
            gather(bt.sup),
            gather(bt.rhs),
        );
        let mut xl = [0.0; 2];
        cyclic_thomas_solve(&b[..m], &d[..m], &a[..m], &c[..m], &mut xl[..m], &mut work).map_err(
            |e| match e {
                TridiagonalError::ZeroPivot { row, pivot, scale } => {
                    TridiagonalError::ZeroPivotInLine {
                        line,
                        row,
                        pivot,
                        scale,
                    }
                }
                TridiagonalError::NonFiniteSolution { row, value } => {
                    TridiagonalError::NonFiniteSolutionInLine { line, row, value }
                }
                other => other,
            },
        )?;
        for (i, v) in xl[..m].iter().enumerate() {
            x[i * lines + line] = *v;
        }
    }
    Ok(())
}
