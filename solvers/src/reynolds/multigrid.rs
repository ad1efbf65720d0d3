//! A geometric multigrid V-cycle (semi-coarsening in θ, zebra axial-line and cyclic
//! circumferential-line smoothing, Galerkin coarse operators) as the preconditioner of the
//! flexible GMRES of a frozen-switch Reynolds system.
//!
//! # What it solves
//!
//! One Newton step of the complementarity solve (`mod.rs`) freezes the switch g and solves the
//! linear system A(g) y = b of the five-point conservative stencil ([`super::discretization`]):
//!
//! ```text
//!   p_P y_P + w_P y_W + e_P y_E + s_P y_S + n_P y_N = b_P      (unknown nodes, periodic in θ)
//!   y_P = ψ_D                                                   (ends, grooves, supply line)
//! ```
//!
//! with p > 0 and w, e, s, n ≤ 0 (a column-dominant M-matrix: the pressure flux β h³/12μ of the
//! full-film nodes, the upwind Couette transport (U/2) h φ of every node, the time term
//! V h/Δt). The full-film part is a stiff, variable-coefficient Poisson operator; in the cavity
//! the rows are the θ-transport of the film content. The ADI preconditioner of [`super::adi`]
//! removes the smooth error only through its one-dimensional line-aggregate coarse problem, so
//! its Krylov count grows with the grid (17 / 38 / 80 on 60×15 / 120×31 / 240×61). This V-cycle
//! treats every θ-wavelength on a level where it is short.
//!
//! # Grid hierarchy and transfers
//!
//! Semi-coarsening in θ only (\[VennerLubrecht2000\]; \[Trottenberg2001\],
//! ch. 5 on anisotropic operators): the coarse ring keeps the even fine columns,
//! n_c = ⌈n_θ/2⌉, level after level until n_θ ≤ [`COARSEST_THETA`] (120 → 60 → 30 → 15 → 8 → 4 on
//! the default grid). The z-lines stay whole on every level, so the axial line solve is exact
//! across z however strongly the operator couples z (the semi-coarsened levels are increasingly
//! z-dominated: the coupling ratio (Δx/Δz)² grows 4× per level).
//!
//! ```text
//!   level l          i:  0   1   2   3   4   5   …  n_θ−1 | 0     (periodic)
//!                        ●   ○   ●   ○   ●   ○       ○
//!                        │ ╲ │ ╱ │ ╲ │ ╱ │            ╲ ╱
//!   level l+1        I:  0       1       2   …  n_c−1 | 0         (n_c = ⌈n_θ/2⌉)
//!
//!   prolongation P (linear in θ, identity in z, per axial row j):
//!     e_f(2I)   = m_f(2I)   · e_c(I)
//!     e_f(2I+1) = m_f(2I+1) · ½ (e_c(I) + e_c(I+1 mod n_c))
//!   restriction R = Pᵀ:  r_c(I) = m_c(I) [½ m r(2I−1) + m r(2I) + ½ m r(2I+1)]
//!   coarse operator (Galerkin): A_c = R A P  — 3 × 3 (nine-point) stencil on every coarse level
//! ```
//!
//! For odd n_θ the last fine column n_θ−1 is even, i.e. a coarse node, and the coarse interval
//! from it to column 0 is one fine step long: a non-uniform coarse ring, which the Galerkin
//! product handles without special cases (and no odd column has to wrap).
//!
//! **Masks.** m_f is 1 on the *full-film* unknowns and 0 on Dirichlet nodes (ends, grooves,
//! supply line) and on cavitated nodes; m_c(I) = m_f(2I). So a correction never changes a
//! Dirichlet value, no Dirichlet residual is restricted, every active column of P owns a node
//! of weight 1 that no other column touches (the columns are independent: a coarse node fed by
//! a single odd fine node shared with its neighbour would duplicate a row — a singular coarse
//! line, seen on the real films before this rule), and inactive coarse nodes get identity rows.
//!
//! **Why the cavity stays on the fine level.** A cavitated row is the θ-transport of film
//! content (its diagonal is the Couette outflow (U/2) h Δz) plus the β-sized pressure flux
//! from its full neighbours. Galerkin-coarsened together with the pressure rows it degrades:
//! upwind transport [−1 1] becomes [−¾ 1 ¼], and on the real cavitating films the coarse
//! operators with cavitated rows were unstable (a stationary V-cycle diverging by 5e3 per cycle
//! at 240 × 61 with the real steady switch, though FGMRES still converged); widening the coarse
//! space to the cavitated nodes next to full ones was worse (×118 per cycle). With the cavity
//! masked out, the coarse problems are the pressure block with the cavity as a zero-correction
//! boundary (a no-flux one at reformation fronts, next section), whose Galerkin operators
//! behave (the θ-mass of the z-part, [¼ 3/2 ¼] ⊗ A_z, makes them not M-matrices, but their
//! symmetric part stays positive definite), and the cavity is relaxed by the circumferential
//! line sweep, which solves the θ-transport of each line exactly. Without a switch (`None`) every unknown is coarsened.
//!
//! # Reformation fronts
//!
//! Where the cavity ends upstream of a full node — a reformation front, the cavitated node m
//! just upstream (in the Couette direction) of the full node k — the two rows couple both
//! ways with very different weights: row k takes the Couette inflow of m's content,
//! A\[k,m\] = −(U/2) h Δz (a Couette-sized entry), and row m takes the pressure flux of k,
//! A\[m,k\] = −β h³ Δz/(12 μ Δx) (a β-sized entry), against m's Couette-sized diagonal A\[m,m\]
//! = (U/2) h Δz (+ V h/Δt in a time step). Eliminating m (row m solved for y_m) leaves on k
//!
//! ```text
//!   A'[k,k] = A[k,k] − A[k,m] A[m,k] / A[m,m]  ≥  A[k,k] − |A[m,k]|
//! ```
//!
//! — in a steady film exactly the pressure coupling of the face k–m taken off k's diagonal: a
//! pressure perturbation of k pushes film into the cavitated cell m, which carries it straight
//! back into k. For the pressure block the front is a *no-flux* boundary, not the zero-pressure
//! one that masking m out suggests. Two places of the cycle use that:
//!
//! - **Smoother.** Each such m is *attached* to its k ([`MgLevel::attached_to`]: the θ-neighbour
//!   with A\[k,m\] A\[m,k\] ≠ 0; the Couette direction gives at most one) and the zebra sweep of
//!   k's axial lines solves the block of the line and its attached nodes: the line factors hold
//!   A'\[k,k\], the line's right-hand side t_k − (A\[k,m\]/A\[m,m\]) t_m, then y_m += (t_m −
//!   A\[m,k\] δy_k)/A\[m,m\]. Row k is then exact after the sweep, as every row of a solved line
//!   (so the defect after the zebra stays zero on the odd lines); row m is exact against its
//!   other neighbours' values before the sweep. Across the seam of an odd ring, where k and m
//!   are both even columns of one half, nothing is attached.
//! - **Coarse space.** The first coarse level is the Galerkin product of the finest operator
//!   with A'\[k,k\] on those diagonals ([`MgLevel::eliminate_attached`]), so the coarse
//!   problems see the front as the no-flux boundary it is.
//!
//! A'\[k,k\] stays ≥ the sum of k's other off-diagonals (A\[m,m\] ≥ |A\[k,m\]|: the same face's
//! Couette flux, plus the time term), so the attached lines stay diagonally dominant M-matrix
//! lines. Found by the error the old cycle left (the dominant eigenvector of the stationary
//! V-cycle at the converged steady cavity of the ε = 0.8 compressor film): all of it on the
//! strip of full columns between a reformation front and the feed groove's upstream edge
//! (1 / 2 / 3 columns on 60 × 15 / 120 × 31 / 240 × 61), its contraction 0.09 / 0.53 / 0.55
//! per cycle; with the smoother only 0.09 / 0.10 / 0.48; with both 0.091 / 0.102 / 0.108
//! (tests `v_cycle_contraction_at_the_converged_cavity_is_grid_independent`,
//! `attached_cavitated_nodes_are_solved_with_their_axial_line`). Tried before on the same
//! slow mode and dropped: the full nodes next to the cavity masked out of the coarse space
//! (steady 8 / 10 / 13 iterations — it moves the zero-pressure boundary, the wrong condition,
//! by a cell); more smoothing (a second circumferential sweep, V(2,2)), which lowered the
//! counts by one or two but not their growth, at 20–60 % more work per cycle.
//!
//! A vanishing line pivot or a singular coarsest matrix is reported as
//! [`ReynoldsError::LinearSolve`], a non-finite coarsest solution as
//! [`ReynoldsError::NonFinite`], never as a NaN; the FGMRES residual check guards the answer.
//!
//! # One V(1,1)-cycle (the preconditioner application z = M⁻¹ r)
//!
//! ```text
//!   level l < coarsest:  x_l = 0
//!                        S_pre :  circumferential lines (cyclic, θ exact, z-neighbours lagged;
//!                                 finest level only)
//!                                 axial lines, even i then odd i (zebra; θ-neighbours lagged)
//!                                 (on a coarse level x_l = 0 before the even lines: their
//!                                 defect is b_l itself, not computed)
//!                        b_{l+1} = R (b_l − A_l x_l)   (zero on the odd lines after their
//!                                 exact solve: only the even lines' defect is formed, and
//!                                 R reduces to r_c(I) = m_c(I) m_f(2I) r(2I))
//!   coarsest level:      x_L = A_L⁻¹ b_L          (banded LU; n_θ ≤ 4, whole z-lines)
//!   back up:             x_l += P x_{l+1}
//!                        S_post:  axial lines odd i then even i, circumferential lines
//!                                 (finest level only)
//! ```
//!
//! The circumferential sweeps belong to the finest level: the cavity, whose θ-transport they
//! carry, is masked out of every coarse level, and the coarse pressure operators are
//! z-dominated (the coupling ratio (Δx/Δz)² grows 4× per level), which the zebra axial lines
//! smooth on their own. Sweeping circumferential lines on the coarse levels too changed no
//! Krylov count in the inverse timing case (6.2 per film step on 60 × 15) for 5 % more
//! instructions in the whole cycle (callgrind).
//!
//! The axial (z) line relaxation in zebra order is the smoother that semi-coarsening in θ
//! needs (it damps every error mode that oscillates in θ, for any z-coupling strength); the
//! circumferential cyclic line sweep adds what the zebra lines cannot do: it carries the
//! θ-transport of the cavitated rows exactly (the modified Thomas kernel of
//! [`crate::tridiagonal`], as in the ADI preconditioner; without it, in an early variant, a
//! steady cavitated solve took 46 instead of 5 Krylov iterations per solve on 60 × 15). All
//! line matrices are fixed
//! during a Krylov solve: they are factored once per frozen system ([`InterleavedFactors`])
//! and every sweep is a batched forward and back substitution. Measured alternatives: an
//! extra circumferential sweep per smoothing step cut the iterations by 10 % but cost 7 % more
//! time per film step (120 × 31); V(2,2) cut them by ~25 % (not timed); a W-cycle changed
//! nothing (the remaining slow mode is not a coarse-solve accuracy problem); freezing the
//! full nodes pinned by a cavitated neighbour in the line sweeps made it worse.
//!
//! # Precision
//!
//! The V-cycle runs in single precision ([`Work`] = `f32`): the level operators, masks,
//! vectors, defects, transfers and the line substitutions. The hierarchy is *built* in `f64`
//! — the Galerkin products, the line factorizations with their pivot checks, the coarsest LU
//! — and rounded value by value (relative 2⁻²⁴) to the cycle's copies; the coarsest solve
//! stays `f64`. A preconditioner of flexible GMRES only has to cluster the spectrum (one
//! V-cycle reduces the error by ~0.1, far above the 6e-8 of single precision): the Krylov
//! vectors, A z, the residuals and the stopping test stay `f64`, so the solves still reach
//! 1e-10 of the flux scale and agree with the sparse-LU oracle as before (`multigrid/tests.rs`),
//! and the Krylov iterations per film step of the inverse timing case did not change
//! (6.1 on 120 × 31). This is the inner–outer scheme of mixed-precision iterative refinement
//! (\[Saad1993\]: an inexact, even varying, preconditioner is what FGMRES allows). The pivots
//! are checked in `f64` exactly as before (64 ε_f64 of the row scale), so every line that
//! factors in `f64` still factors; only the stored reciprocal pivots and multipliers are
//! rounded, a relative perturbation of 2⁻²⁴ per factor, which the substitutions of these
//! column-dominant M-matrix lines (multipliers ≤ 1) do not amplify. The stiff rows — β-sized
//! pressure couplings of a full node, a cavitated node's Couette-sized diagonal next to them —
//! are SI magnitudes far inside the range of `f32` (1e-38 … 3e38); a reciprocal pivot that
//! would still round to 0 or ∞ is an error ([`InterleavedFactors::round_from`]), not an
//! infinity. The right-hand side is scaled by a power of two to max |r| ≈ 1 before rounding
//! (exact, undone on the way out), and its entries below 2⁻⁶⁰ of the largest are dropped, so
//! no value of the cycle comes near the subnormal range (slow on x86). Half the memory
//! traffic and twice the lanes per vector, with the cycle compiled for AVX2 as well (run-time
//! dispatch, as the line kernels): 12 % fewer instructions and ~12 % less time per film step
//! on the 120 × 31 inverse cycle (docs/performance.md, "Fifth pass").
//!
//! # Convergence (measured; tests in `multigrid/tests.rs`)
//!
//! Stationary V-cycle contraction ≈ 0.1 per cycle on the full film, independent of the grid.
//! FGMRES iterations for a 1e-10 solve from the Dirichlet start, ε = 0.8 compressor bearing,
//! 60×15 / 120×31 / 240×61: steady full film 7 / 7 / 7; 1° step, full 7 / 7 / 8; 1° step with
//! the diverging half cavitated 7 / 7 / 7; a 1° step at its converged cavity 7 / 7 / 8; the
//! steady film at its converged cavity 7 / 7 / 7 (7 / 8 / 9 and 7 / 9 / 12 before the
//! reformation-front coupling above). Inside the inverse solver (inverse_timing, Krylov
//! iterations per film step, several solves of mixed tolerance each, most of them loose):
//! 3.7 / 4.7 / 6.2 (3.7 / 4.8 / 6.6 before) against the ADI preconditioner's 17.1 / 38.4 /
//! 80.4 (measured 2026-11-24, before the later passes over the film step).
//!
//! References: A. A. Lubrecht, W. E. ten Napel, R. Bosma, "Multigrid, an alternative method for
//! calculating film thickness and pressure profiles in elastohydrodynamically lubricated line
//! contacts", J. Tribol. 108 (1986) 551–556; C. H. Venner, A. A. Lubrecht, *Multilevel Methods
//! in Lubrication*, Elsevier 2000; C. M. Woods, D. E. Brewe, "The solution of the Elrod
//! algorithm for a dynamically loaded journal bearing using multigrid techniques", J. Tribol.
//! 111 (1989) 302–308; U. Trottenberg, C. W. Oosterlee, A. Schüller, *Multigrid*, Academic
//! Press 2001 (semi-coarsening with line relaxation, Galerkin coarsening); Y. Saad, "A flexible
//! inner-outer preconditioned GMRES algorithm", SIAM J. Sci. Comput. 14 (1993) 461–469.

use super::ReynoldsError;
use super::discretization::Stencil;
use super::grid::{Grid, NodeKind};
use crate::banded::BandedLu;
use crate::tridiagonal::{InterleavedFactors, Real};

/// The precision of the V-cycle's vectors, operators and line substitutions (module docs,
/// "Precision"). The hierarchy is built in `f64` and rounded to it.
pub(crate) type Work = f32;

/// Coarsening stops at the first level with n_θ ≤ this; that level is solved by banded LU
/// (n_θ · n_z ≤ 4 · n_z unknowns: 4 × 31 on the default grid; bandwidth 2 n_θ − 1 ≤ 7).
pub(crate) const COARSEST_THETA: usize = 4;

/// The largest change of a frozen matrix, per row and relative to that row of the matrix the
/// hierarchy was built for (Σ_l |Δa_kl| / Σ_l |a_kl|: a cavitated row next to full nodes has a
/// Couette-sized diagonal and β-sized off-diagonals), up to which [`Multigrid::setup`] keeps the
/// hierarchy. A 1° time step at ε = 0.8 changes h by a few per cent and the pressure flux ∝ h³
/// by up to ~10 %: within it, the film's next Newton and time steps reuse one hierarchy until a
/// node switches. The preconditioner of a flexible GMRES may differ from A⁻¹ (it only has to
/// cluster the spectrum); the Krylov solve rebuilds a kept hierarchy that has not converged
/// after [`STALE_REBUILD_ITERATIONS`](super::adi::STALE_REBUILD_ITERATIONS) iterations. Measured on the compressor-size
/// inverse cycle (inverse_timing, 120 × 31, 1°): Krylov iterations per film step 7.1 → 7.4,
/// the same h_min and power to the last printed digit, the setups cut by more than half (1832 →
/// 721 per run-in + cycle, counted with a per-row diagonal measure of the drift; the row-sum
/// measure kept here reuses at least as often).
pub(crate) const MAX_REUSE_DRIFT: f64 = 0.25;

/// Entries of the scaled right-hand side of [`Multigrid::apply`] (max |r| ≈ 1) below this
/// (2⁻⁶⁰ ≈ 8.7e-19, 2⁻³⁶ below the single-precision rounding) are dropped.
const DROP_BELOW: f64 = 1.0 / (1u64 << 60) as f64;

/// What [`Multigrid::setup`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Hierarchy {
    /// Built for this matrix.
    Built,
    /// The previous hierarchy kept: built for this very matrix (`stale: false`) or for a nearby
    /// one with the same coarse space (`stale: true`).
    Kept { stale: bool },
}

/// Index of the stencil entry of offset (dθ, dz) ∈ {−1, 0, 1}²: `3 (dθ + 1) + (dz + 1)`.
const fn at(di: isize, dj: isize) -> usize {
    (3 * (di + 1) + (dj + 1)) as usize
}
const C: usize = at(0, 0);
const W: usize = at(-1, 0);
const E: usize = at(1, 0);
const S: usize = at(0, -1);
const N: usize = at(0, 1);

/// A nine-point periodic-in-θ stencil on an n_θ × n_z level, `c[o][i · n_z + j]`, o = [`at`].
/// Entries that would reach past z = ends are zero. Built in `f64`; the V-cycle applies its
/// rounding to [`Work`].
#[derive(Debug, Clone, Default)]
pub(crate) struct Stencil9<T: Real = f64> {
    pub nt: usize,
    pub nz: usize,
    pub c: [Vec<T>; 9],
    /// The corners are zero (the fine level): the defect skips them.
    five: bool,
}

impl Stencil9 {
    fn reset(&mut self, nt: usize, nz: usize) {
        self.nt = nt;
        self.nz = nz;
        self.five = false;
        for v in &mut self.c {
            v.clear();
            v.resize(nt * nz, 0.0);
        }
    }

    /// The five-point fine stencil as a nine-point one (zero corners).
    fn assign_five(&mut self, grid: &Grid, st: &Stencil) {
        self.reset(grid.n_theta, grid.n_z);
        self.c[C].copy_from_slice(&st.p);
        self.c[W].copy_from_slice(&st.w);
        self.c[E].copy_from_slice(&st.e);
        self.c[S].copy_from_slice(&st.s);
        self.c[N].copy_from_slice(&st.n);
        self.five = true;
    }
}

impl<T: Real> Stencil9<T> {
    /// This stencil becomes `a` rounded to `T` (no allocation when the size is unchanged).
    fn round_from(&mut self, a: &Stencil9) {
        self.nt = a.nt;
        self.nz = a.nz;
        self.five = a.five;
        for (dst, src) in self.c.iter_mut().zip(&a.c) {
            dst.clear();
            dst.extend(src.iter().map(|&v| T::from_f64(v)));
        }
    }

    /// y = b − A x on axial line i (the n_z rows i · n_z + j).
    #[inline(always)]
    fn defect_line(&self, i: usize, x: &[T], b: &[T], y: &mut [T]) {
        let (nt, nz) = (self.nt, self.nz);
        let iw = if i == 0 { nt - 1 } else { i - 1 };
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        let base = i * nz;
        let xl = [
            &x[iw * nz..(iw + 1) * nz],
            &x[base..base + nz],
            &x[ie * nz..(ie + 1) * nz],
        ];
        let c = |o: usize| &self.c[o][base..base + nz];
        let last = nz - 1;
        let (bl, yl) = (&b[base..base + nz], &mut y[base..base + nz]);
        // End rows (no neighbour beyond the end).
        for j in [0, last] {
            let mut s = T::ZERO;
            for d in 0..3 {
                if j > 0 {
                    s += c(3 * d)[j] * xl[d][j - 1];
                }
                s += c(3 * d + 1)[j] * xl[d][j];
                if j < last {
                    s += c(3 * d + 2)[j] * xl[d][j + 1];
                }
            }
            yl[j] = bl[j] - s;
        }
        // Interior rows j = 1 … n_z − 2 as slices of one length m (row j at index j − 1; the
        // neighbour j ∓ 1 at the slice shifted by one): no bounds checks in the loop, which
        // LLVM vectorizes. Same operations in the same order as row by row.
        if nz < 3 {
            return;
        }
        let m = nz - 2;
        fn inner<T>(v: &[T], m: usize) -> &[T] {
            &v[1..1 + m]
        }
        fn below<T>(v: &[T], m: usize) -> &[T] {
            &v[..m]
        }
        fn above<T>(v: &[T], m: usize) -> &[T] {
            &v[2..2 + m]
        }
        let (xw, xp, xe) = (inner(xl[0], m), inner(xl[1], m), inner(xl[2], m));
        let (xp_s, xp_n) = (below(xl[1], m), above(xl[1], m));
        let (xw_s, xw_n) = (below(xl[0], m), above(xl[0], m));
        let (xe_s, xe_n) = (below(xl[2], m), above(xl[2], m));
        defect_run(
            std::array::from_fn(|o| inner(c(o), m)),
            [xw_s, xw, xw_n, xp_s, xp, xp_n, xe_s, xe, xe_n],
            &bl[1..1 + m],
            &mut yl[1..1 + m],
            self.five,
        );
    }

    /// y = b − A x on the columns of `parity` (every column with None): one flat pass over
    /// the interior of the ring for all columns, then the columns' end rows and the two seam
    /// columns 0 and n_θ − 1 as [`Stencil9::defect_line`] computes them. The same values as
    /// `defect_line` column by column (each row's terms in the same order), in one loop long
    /// enough to vectorize: the per-column loops over a short axial line (17 rows on the half
    /// grid: one 8-wide block, seven scalar rows and two end rows each) were a fifth of the
    /// inverse cycle's time (perf). Rows of the other parity's columns are left with
    /// whatever the flat pass gave them (their interior rows are right, their end rows not).
    #[inline(always)]
    fn defect_columns(&self, x: &[T], b: &[T], y: &mut [T], parity: Option<usize>) {
        let (nt, nz) = (self.nt, self.nz);
        let wanted = |i: usize| parity.is_none_or(|p| i % 2 == p);
        if nt < 3 || nz < 3 {
            for i in (0..nt).filter(|&i| wanted(i)) {
                self.defect_line(i, x, b, y);
            }
            return;
        }
        // Interior: node k of columns 1 … n_θ − 2 with all eight neighbours at k ± 1, k ± n_z,
        // k ± n_z ± 1 (the end rows among them get the interior formula here, which reaches
        // across a column boundary, and are redone below).
        let (lo, hi) = (nz + 1, (nt - 1) * nz - 1);
        fn shifted<T>(v: &[T], lo: usize, len: usize, d: isize) -> &[T] {
            let from = (lo as isize + d) as usize;
            &v[from..from + len]
        }
        let at_shift = |v, d| shifted(v, lo, hi - lo, d);
        let n = nz as isize;
        defect_run(
            std::array::from_fn(|o| &self.c[o][lo..hi]),
            // Offset o = 3 (dθ + 1) + (dz + 1) ([`at`]) is at k + n_z dθ + dz.
            std::array::from_fn(|o| at_shift(x, n * (o as isize / 3 - 1) + (o as isize % 3 - 1))),
            &b[lo..hi],
            &mut y[lo..hi],
            self.five,
        );
        // The seam columns whole, the other wanted columns' end rows.
        for i in (0..nt).filter(|&i| wanted(i)) {
            if i == 0 || i == nt - 1 {
                self.defect_line(i, x, b, y);
            } else {
                self.defect_end_rows(i, x, b, y);
            }
        }
    }

    /// Rows 0 and n_z − 1 of [`Stencil9::defect_line`] on axial line i (no neighbour beyond the
    /// end; the terms in `defect_line`'s order).
    #[inline(always)]
    fn defect_end_rows(&self, i: usize, x: &[T], b: &[T], y: &mut [T]) {
        let nz = self.nz;
        let base = i * nz;
        let (w, p, e) = (base - nz, base, base + nz);
        let c = |o: usize, k: usize| self.c[o][k];
        // Row 0: per column W, P, E the terms of rows 0 and 1 (3 d + 1, 3 d + 2).
        let mut s = T::ZERO;
        for (d, col) in [w, p, e].into_iter().enumerate() {
            s += c(3 * d + 1, base) * x[col];
            s += c(3 * d + 2, base) * x[col + 1];
        }
        y[base] = b[base] - s;
        // Row n_z − 1: the terms of rows n_z − 2 and n_z − 1 (3 d, 3 d + 1).
        let (k, last) = (base + nz - 1, nz - 1);
        let mut s = T::ZERO;
        for (d, col) in [w, p, e].into_iter().enumerate() {
            s += c(3 * d, k) * x[col + last - 1];
            s += c(3 * d + 1, k) * x[col + last];
        }
        y[k] = b[k] - s;
    }

    /// b_k − (A x)_k of the single row k.
    fn defect_at(&self, k: usize, x: &[T], b: &[T]) -> T {
        let (nt, nz) = (self.nt, self.nz);
        let (i, j) = (k / nz, k % nz);
        let mut s = T::ZERO;
        for di in -1..=1isize {
            let base = wrap(i, di, nt) * nz;
            for dj in -1..=1isize {
                let jj = j as isize + dj;
                if (0..nz as isize).contains(&jj) {
                    s += self.c[at(di, dj)][k] * x[base + jj as usize];
                }
            }
        }
        b[k] - s
    }

    #[inline(always)]
    fn defect(&self, x: &[T], b: &[T], y: &mut [T]) {
        self.defect_columns(x, b, y, None);
    }
}

/// y = b − Σ_o c_o x_o over one run of rows (every slice of y's length; `c[o]` the entries and
/// `x[o]` the values of stencil offset o = [`at`] for those rows): the five-point terms, then
/// (not `five`) the corners, in this one fixed order — the interior rows of
/// [`Stencil9::defect_line`] and of [`Stencil9::defect_columns`], which must give the same bits.
/// One loop without bounds checks, which LLVM vectorizes.
#[inline(always)]
fn defect_run<T: Real>(c: [&[T]; 9], x: [&[T]; 9], b: &[T], y: &mut [T], five: bool) {
    let m = y.len();
    let c: [&[T]; 9] = c.map(|v| &v[..m]);
    let x: [&[T]; 9] = x.map(|v| &v[..m]);
    let b = &b[..m];
    let [c0, c1, c2, c3, c4, c5, c6, c7, c8] = c;
    let [xw_s, xw, xw_n, xp_s, xp, xp_n, xe_s, xe, xe_n] = x;
    if five {
        for j in 0..m {
            let s =
                c4[j] * xp[j] + c1[j] * xw[j] + c7[j] * xe[j] + c3[j] * xp_s[j] + c5[j] * xp_n[j];
            y[j] = b[j] - s;
        }
        return;
    }
    for j in 0..m {
        let s = c4[j] * xp[j]
            + c1[j] * xw[j]
            + c7[j] * xe[j]
            + c3[j] * xp_s[j]
            + c5[j] * xp_n[j]
            + c0[j] * xw_s[j]
            + c2[j] * xw_n[j]
            + c6[j] * xe_s[j]
            + c8[j] * xe_n[j];
        y[j] = b[j] - s;
    }
}

/// Index of fine node `i + d` on a periodic ring of `n` (|d| ≤ 1).
#[inline(always)]
fn wrap(i: usize, d: isize, n: usize) -> usize {
    ((i + n) as isize + d) as usize % n
}

/// Number of coarse columns of a fine ring of `nt`: the even fine columns.
#[inline(always)]
pub(crate) fn coarse_len(nt: usize) -> usize {
    nt.div_ceil(2)
}

/// The coarse parents of fine column f and their interpolation weights (the second is unused
/// when the count is 1). Even f is coarse column f/2; odd f lies between (f−1)/2 and
/// (f+1)/2 (mod n_c). For odd n_θ the last fine column n_θ−1 is even, and the coarse interval
/// from it to column 0 is one fine step long (a non-uniform coarse ring; Galerkin does not
/// mind).
#[inline(always)]
fn parents(f: usize, nt: usize) -> ([(usize, f64); 2], usize) {
    let nc = coarse_len(nt);
    if f.is_multiple_of(2) {
        ([(f / 2, 1.0), (0, 0.0)], 1)
    } else {
        ([((f - 1) / 2, 0.5), (f.div_ceil(2) % nc, 0.5)], 2)
    }
}

/// The fine children of coarse column I (the nonzeros of column I of P) and their weights.
#[inline(always)]
fn children(ic: usize, nt: usize) -> ([(usize, f64); 3], usize) {
    let mut out = [(2 * ic, 1.0), (0, 0.0), (0, 0.0)];
    let mut count = 1;
    if ic >= 1 {
        out[count] = (2 * ic - 1, 0.5);
        count += 1;
    } else if nt.is_multiple_of(2) {
        out[count] = (nt - 1, 0.5);
        count += 1;
    }
    if 2 * ic + 1 < nt {
        out[count] = (2 * ic + 1, 0.5);
        count += 1;
    }
    (out, count)
}

/// The coarse activity mask: coarse column I is active where its own fine node 2I is (so
/// every active column of P has a node of weight 1 that no other column touches, and the
/// columns of P are independent).
fn coarse_mask(nt: usize, nz: usize, fmask: &[f64], cmask: &mut Vec<f64>) {
    let nc = coarse_len(nt);
    cmask.clear();
    cmask.resize(nc * nz, 0.0);
    for ic in 0..nc {
        for j in 0..nz {
            cmask[ic * nz + j] = fmask[2 * ic * nz + j];
        }
    }
}

/// Galerkin coarse operator A_c = R A P of the module docs (`fmask`, `cmask`: activity of the
/// fine and coarse nodes). Needs n_c = ⌈n_θ/2⌉ ≥ 3.
pub(crate) fn galerkin(fine: &Stencil9, fmask: &[f64], cmask: &[f64], coarse: &mut Stencil9) {
    let nc = coarse_len(fine.nt);
    debug_assert!(nc >= 3);
    coarse.reset(nc, fine.nz);
    for ic in 0..nc {
        galerkin_column(fine, fmask, cmask, coarse, ic);
    }
}

/// Column `ic` of the Galerkin operator into a coarse stencil whose column `ic` is zero: every
/// entry of coarse column ic is written here and nowhere else, so recomputing one column (after
/// zeroing it) gives the bits of the whole product.
#[inline(always)]
fn galerkin_column(
    fine: &Stencil9,
    fmask: &[f64],
    cmask: &[f64],
    coarse: &mut Stencil9,
    ic: usize,
) {
    let (nt, nz) = (fine.nt, fine.nz);
    let nc = coarse_len(nt);
    let (kids, nk) = children(ic, nt);
    // Coarse offset of parent ig from ic: 0, +1 or −1 (mod n_c).
    let offset = |ig: usize| -> isize {
        let off = (ig + nc - ic) % nc;
        debug_assert!(off == 0 || off == 1 || off == nc - 1);
        match off {
            0 => 0,
            1 => 1,
            _ => -1,
        }
    };
    // The θ-structure (children, neighbours, parents, coarse offsets) is the same on every
    // row j: work it out once per coarse column, then run down the column.
    for &(f, wr) in &kids[..nk] {
        for di in -1isize..=1 {
            let g = wrap(f, di, nt);
            let (par, np) = parents(g, nt);
            for &(ig, w) in &par[..np] {
                let dc = offset(ig);
                let weight = wr * w;
                for dj in -1isize..=1 {
                    if fine.five && di != 0 && dj != 0 {
                        // The five-point fine level's corners are zero: nothing to add.
                        continue;
                    }
                    let src = &fine.c[at(di, dj)];
                    let dst = &mut coarse.c[at(dc, dj)];
                    // Rows j0..j1 of the column; their neighbours jj = j + dj.
                    let (j0, j1) = (usize::from(dj < 0), nz - usize::from(dj > 0));
                    let len = j1 - j0;
                    let jn = (j0 as isize + dj) as usize;
                    let row = f * nz + j0..f * nz + j0 + len;
                    let d = &mut dst[ic * nz + j0..ic * nz + j0 + len];
                    let cr = &cmask[ic * nz + j0..ic * nz + j0 + len];
                    let fg = &fmask[g * nz + jn..g * nz + jn + len];
                    let cc = &cmask[ig * nz + jn..ig * nz + jn + len];
                    // Row active (R) × column active (P) × coarse column active.
                    for ((((d, a), fr), (fg, cc)), cr) in d
                        .iter_mut()
                        .zip(&src[row.clone()])
                        .zip(&fmask[row])
                        .zip(fg.iter().zip(cc))
                        .zip(cr)
                    {
                        *d += weight * (fr * fg * cc * cr) * a;
                    }
                }
            }
        }
    }
    for j in 0..nz {
        let kc = ic * nz + j;
        if cmask[kc] == 0.0 {
            coarse.c[C][kc] = 1.0;
        }
    }
}

/// [`restrict`] of a fine defect that is zero on the odd columns (the defect after the zebra
/// sweep, [`MgLevel::defect_after_zebra`], whose odd lines are not even read): the odd
/// children add nothing, so r_c(I) = m_c(I) · m_f(2I) r_f(2I) — the same values as the whole
/// restriction of such a defect, bit for bit (test `restriction_after_zebra_is_the_restriction`).
#[inline(always)]
pub(crate) fn restrict_after_zebra<T: Real>(
    nt: usize,
    nz: usize,
    fmask: &[T],
    cmask: &[T],
    rf: &[T],
    rc: &mut [T],
) {
    let one = T::from_f64(1.0);
    for ic in 0..coarse_len(nt) {
        let (f, c) = (2 * ic * nz..(2 * ic + 1) * nz, ic * nz..(ic + 1) * nz);
        for (((d, c), m), r) in rc[c.clone()]
            .iter_mut()
            .zip(&cmask[c])
            .zip(&fmask[f.clone()])
            .zip(&rf[f])
        {
            // The whole restriction's operations on the one nonzero child: 0 + 1 · m · r.
            *d = *c * (T::ZERO + one * *m * *r);
        }
    }
}

/// r_c = R r_f = Pᵀ r_f (module docs). Column by column: each fine child's whole z-line at
/// once (contiguous, vectorized), the children in their fixed order. The V-cycle restricts only
/// defects whose odd columns are zero, [`restrict_after_zebra`]; the tests hold it to this.
#[cfg(test)]
pub(crate) fn restrict<T: Real>(
    nt: usize,
    nz: usize,
    fmask: &[T],
    cmask: &[T],
    rf: &[T],
    rc: &mut [T],
) {
    for ic in 0..coarse_len(nt) {
        let (kids, nk) = children(ic, nt);
        let dst = &mut rc[ic * nz..(ic + 1) * nz];
        dst.fill(T::ZERO);
        for &(f, w) in &kids[..nk] {
            let w = T::from_f64(w);
            let (m, r) = (&fmask[f * nz..(f + 1) * nz], &rf[f * nz..(f + 1) * nz]);
            for ((d, m), r) in dst.iter_mut().zip(m).zip(r) {
                *d += w * *m * *r;
            }
        }
        for (d, c) in dst.iter_mut().zip(&cmask[ic * nz..(ic + 1) * nz]) {
            *d = *c * *d;
        }
    }
}

/// x_f += P x_c (module docs), a whole z-line of fine column f at once.
#[inline(always)]
pub(crate) fn prolong_add<T: Real>(nt: usize, nz: usize, fmask: &[T], xc: &[T], xf: &mut [T]) {
    for f in 0..nt {
        let (par, np) = parents(f, nt);
        let dst = &mut xf[f * nz..(f + 1) * nz];
        let m = &fmask[f * nz..(f + 1) * nz];
        let (i0, w0) = par[0];
        let c0 = &xc[i0 * nz..(i0 + 1) * nz];
        let w0 = T::from_f64(w0);
        if np == 1 {
            for ((d, m), c0) in dst.iter_mut().zip(m).zip(c0) {
                *d += *m * (w0 * *c0);
            }
        } else {
            let (i1, w1) = par[1];
            let c1 = &xc[i1 * nz..(i1 + 1) * nz];
            let w1 = T::from_f64(w1);
            for (((d, m), c0), c1) in dst.iter_mut().zip(m).zip(c0).zip(c1) {
                *d += *m * (w0 * *c0 + w1 * *c1);
            }
        }
    }
}

/// One level of the hierarchy: its operator, activity mask and factored line matrices, built
/// in `f64`, their rounding to [`Work`] that the V-cycle uses, and its scratch vectors.
#[derive(Debug, Clone, Default)]
struct MgLevel {
    a: Stencil9,
    mask: Vec<f64>,
    /// The line factorizations in `f64` (pivots checked there), before rounding.
    circumferential64: InterleavedFactors,
    axial64: [InterleavedFactors; 2],
    /// The cycle's operator, mask and line factors ([`Work`]).
    aw: Stencil9<Work>,
    maskw: Vec<Work>,
    circumferential: InterleavedFactors<Work>,
    /// Axial lines of even and of odd i (zebra), line l = i div 2 at `j · lines + l`.
    axial: [InterleavedFactors<Work>; 2],
    x: Vec<Work>,
    b: Vec<Work>,
    t: Vec<Work>,
    y: Vec<Work>,
    line_rhs: Vec<Work>,
    line_sol: Vec<Work>,
    /// Finest level: the cavitated nodes attached to a full node of each zebra half's axial
    /// lines (module docs, "Reformation fronts"), and their defects during a sweep.
    attached: [Vec<Attached>; 2],
    attached_defect: Vec<Work>,
    /// The diagonals [`MgLevel::eliminate_attached`] changed, to restore.
    saved_diagonals: Vec<(usize, f64)>,
    /// The axial lines' coefficients staged for their factorization (sub-, main and
    /// super-diagonal, interleaved; kept between set-ups to save the allocations).
    staging: [Vec<f64>; 3],
}

/// A cavitated node m whose row couples it to the full node k of an axial line in both
/// directions (the Couette inflow A[k,m] of a reformation front and the β-sized pressure flux
/// A[m,k]): the zebra sweep solves m with k's line (module docs, "Reformation fronts").
#[derive(Debug, Clone, Copy)]
struct Attached {
    k: usize,
    m: usize,
    /// The slot of k in its zebra half's interleaved line staging.
    slot: usize,
    /// A[k,m] A[m,k] / A[m,m], taken off k's diagonal (f64, as the line factors are built).
    schur: f64,
    /// A[k,m] / A[m,m].
    km_over_mm: Work,
    /// A[m,k].
    mk: Work,
    /// 1 / A[m,m].
    inv_mm: Work,
}

fn line_error(level: usize, what: &str, e: crate::tridiagonal::TridiagonalError) -> ReynoldsError {
    ReynoldsError::LinearSolve {
        solver: "multigrid smoother",
        detail: format!("level {level}, {what} line: {e}"),
    }
}

impl MgLevel {
    fn lines_of(&self, parity: usize) -> usize {
        (self.a.nt - parity).div_ceil(2)
    }

    /// Factors the circumferential lines and both zebra halves of the axial lines (in `f64`,
    /// then rounded to [`Work`]) and rounds the operator and the mask.
    fn factor(&mut self, level: usize) -> Result<(), ReynoldsError> {
        let (nt, nz) = (self.a.nt, self.a.nz);
        let n = nt * nz;
        for v in [&mut self.x, &mut self.b, &mut self.t, &mut self.y] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.round_operator();
        if level == 0 {
            // Only the finest level sweeps circumferential lines (module docs).
            self.circumferential64
                .factor_periodic(nt, nz, &self.a.c[W], &self.a.c[C], &self.a.c[E])
                .and_then(|()| self.circumferential.round_from(&self.circumferential64))
                .map_err(|e| line_error(level, "circumferential", e))?;
        }
        let half = nt.div_ceil(2) * nz;
        let [mut sub, mut diag, mut sup] = std::mem::take(&mut self.staging);
        for v in [&mut sub, &mut diag, &mut sup] {
            v.resize(half, 0.0);
        }
        for parity in 0..2 {
            let lines = self.lines_of(parity);
            self.stage_axial(level, parity, 0..lines, &mut sub, &mut diag, &mut sup);
            let m = lines * nz;
            let factored = self.axial64[parity]
                .factor_dirichlet(nz, lines, &sub[..m], &diag[..m], &sup[..m])
                .and_then(|()| self.axial[parity].round_from(&self.axial64[parity]))
                .map_err(|e| line_error(level, "axial", e));
            if factored.is_err() {
                self.staging = [sub, diag, sup];
                return factored;
            }
        }
        self.staging = [sub, diag, sup];
        self.line_rhs.clear();
        self.line_rhs.resize(half, 0.0);
        self.line_sol.clear();
        self.line_sol.resize(half, 0.0);
        Ok(())
    }

    /// The axial lines `lanes` of one zebra `parity` (line l is column i = 2 l + parity) into
    /// the interleaved staging of the line factorization (row j of line l at j · lines + l).
    /// On the finest level a node's diagonal carries the Schur complement of the cavitated
    /// nodes attached to it (module docs, "Reformation fronts").
    fn stage_axial(
        &self,
        level: usize,
        parity: usize,
        lanes: impl Iterator<Item = usize>,
        sub: &mut [f64],
        diag: &mut [f64],
        sup: &mut [f64],
    ) {
        let (nz, lines) = (self.a.nz, self.lines_of(parity));
        let mut staged = vec![false; if level == 0 { lines } else { 0 }];
        for l in lanes {
            let i = 2 * l + parity;
            for j in 0..nz {
                let (k, t) = (i * nz + j, j * lines + l);
                sub[t] = self.a.c[S][k];
                diag[t] = self.a.c[C][k];
                sup[t] = self.a.c[N][k];
            }
            if level == 0 {
                staged[l] = true;
            }
        }
        if level == 0 {
            for at in &self.attached[parity] {
                if staged[at.slot % lines] {
                    diag[at.slot] -= at.schur;
                }
            }
        }
    }

    /// The full node of another zebra half that the cavitated node m is attached to: its
    /// θ-neighbour k with A[k,m] A[m,k] ≠ 0 (the Couette inflow from m into k and the pressure
    /// flux from k into m: k is m's downstream neighbour at a reformation front). None for a
    /// full or Dirichlet node, or when both θ-neighbours qualify (which one direction of the
    /// Couette flow excludes), or across the seam of an odd ring (both columns even). With k:
    /// the stencil entries of row k for m and of row m for k.
    fn attached_to(&self, m: usize) -> Option<(usize, usize, usize)> {
        let (nt, nz) = (self.a.nt, self.a.nz);
        if self.mask[m] != 0.0 || self.a.c[C][m].is_nan() || self.a.c[C][m] <= 0.0 {
            return None;
        }
        let (i, j) = (m / nz, m % nz);
        let mut found = None;
        // (direction from m to k, row m's entry for it, row k's entry for m)
        for (d, o_mk, o_km) in [(-1isize, W, E), (1, E, W)] {
            let ik = wrap(i, d, nt);
            let k = ik * nz + j;
            if ik % 2 == i % 2 || self.mask[k] != 1.0 {
                continue;
            }
            if self.a.c[o_mk][m] * self.a.c[o_km][k] != 0.0 {
                if found.is_some() {
                    return None;
                }
                found = Some((k, o_km, o_mk));
            }
        }
        found
    }

    /// The finest operator with every attached cavitated node eliminated into its full node's
    /// diagonal, A'\[k,k\] = A\[k,k\] − A\[k,m\] A\[m,k\] / A\[m,m\] (module docs, "Reformation
    /// fronts"): what the first coarse level is built from. In place; undone, to the bit, by
    /// [`MgLevel::restore_attached`].
    fn eliminate_attached(&mut self) {
        self.saved_diagonals.clear();
        for at in self.attached.iter().flatten() {
            self.saved_diagonals.push((at.k, self.a.c[C][at.k]));
            self.a.c[C][at.k] -= at.schur;
        }
    }

    /// Undoes [`MgLevel::eliminate_attached`].
    fn restore_attached(&mut self) {
        for &(k, v) in self.saved_diagonals.iter().rev() {
            self.a.c[C][k] = v;
        }
        self.saved_diagonals.clear();
    }

    /// The finest level's attachments, per zebra half of k (from `a` and `mask`).
    fn collect_attached(&mut self) {
        let (nt, nz) = (self.a.nt, self.a.nz);
        for v in &mut self.attached {
            v.clear();
        }
        for m in 0..nt * nz {
            // Full and Dirichlet nodes (most of them) leave at its first test.
            let Some((k, o_km, o_mk)) = self.attached_to(m) else {
                continue;
            };
            let (ik, j) = (k / nz, k % nz);
            let parity = ik % 2;
            let mm = self.a.c[C][m];
            let slot = j * self.lines_of(parity) + ik / 2;
            self.attached[parity].push(Attached {
                k,
                m,
                slot,
                schur: self.a.c[o_km][k] * self.a.c[o_mk][m] / mm,
                km_over_mm: Work::from_f64(self.a.c[o_km][k] / mm),
                mk: Work::from_f64(self.a.c[o_mk][m]),
                inv_mm: Work::from_f64(1.0 / mm),
            });
        }
        let most = self.attached[0].len().max(self.attached[1].len());
        self.attached_defect.clear();
        self.attached_defect.resize(most, 0.0);
    }

    /// [`MgLevel::factor`] for a level whose operator and mask changed only in the θ-columns
    /// `columns` (and, on the finest level, in the circumferential lines `rows`, the z-rows
    /// whose W, C or E entries changed): the rounding of those columns, their axial lines and
    /// those circumferential lines are redone, each by the same operations as in a full
    /// factorization (the same bits). The level's vectors keep their size.
    fn refactor_columns(
        &mut self,
        level: usize,
        columns: &[bool],
        rows: &[usize],
    ) -> Result<(), ReynoldsError> {
        let (nt, nz) = (self.a.nt, self.a.nz);
        for i in (0..nt).filter(|&i| columns[i]) {
            for (dst, src) in self.aw.c.iter_mut().zip(&self.a.c) {
                for k in i * nz..(i + 1) * nz {
                    dst[k] = Work::from_f64(src[k]);
                }
            }
            for k in i * nz..(i + 1) * nz {
                self.maskw[k] = Work::from_f64(self.mask[k]);
            }
        }
        if level == 0 && !rows.is_empty() {
            self.circumferential64
                .refactor_lanes(&self.a.c[W], &self.a.c[C], &self.a.c[E], rows)
                .and_then(|()| {
                    self.circumferential
                        .round_lanes_from(&self.circumferential64, rows)
                })
                .map_err(|e| line_error(level, "circumferential", e))?;
        }
        let half = nt.div_ceil(2) * nz;
        let [mut sub, mut diag, mut sup] = std::mem::take(&mut self.staging);
        for v in [&mut sub, &mut diag, &mut sup] {
            v.resize(half, 0.0);
        }
        let mut lanes = Vec::new();
        let mut refactored = Ok(());
        for parity in 0..2 {
            let lines = self.lines_of(parity);
            lanes.clear();
            lanes.extend((0..lines).filter(|&l| columns[2 * l + parity]));
            if lanes.is_empty() {
                continue;
            }
            // Only the staged lanes are read (`refactor_lanes`): the others' old values in the
            // kept staging do not matter.
            self.stage_axial(
                level,
                parity,
                lanes.iter().copied(),
                &mut sub,
                &mut diag,
                &mut sup,
            );
            let m = lines * nz;
            refactored = self.axial64[parity]
                .refactor_lanes(&sub[..m], &diag[..m], &sup[..m], &lanes)
                .and_then(|()| self.axial[parity].round_lanes_from(&self.axial64[parity], &lanes))
                .map_err(|e| line_error(level, "axial", e));
            if refactored.is_err() {
                break;
            }
        }
        self.staging = [sub, diag, sup];
        refactored
    }

    /// The cycle's operator and mask: `a` and `mask` rounded to [`Work`].
    fn round_operator(&mut self) {
        self.aw.round_from(&self.a);
        self.maskw.clear();
        self.maskw
            .extend(self.mask.iter().map(|&m| Work::from_f64(m)));
    }

    /// x += A_θ⁻¹ (b − A x): every circumferential line at once (z-neighbours lagged).
    /// `x_is_zero`: x = 0 on entry, so the defect is b itself.
    #[inline(always)]
    fn circumferential_sweep(
        &mut self,
        level: usize,
        x_is_zero: bool,
    ) -> Result<(), ReynoldsError> {
        if x_is_zero {
            // x = A_θ⁻¹ b: solved in place, no defect and no sum.
            return self
                .circumferential
                .solve(&self.b, &mut self.x)
                .map_err(|e| line_error(level, "circumferential", e));
        }
        self.aw.defect(&self.x, &self.b, &mut self.t);
        self.circumferential
            .solve(&self.t, &mut self.y)
            .map_err(|e| line_error(level, "circumferential", e))?;
        for (x, y) in self.x.iter_mut().zip(&self.y) {
            *x += y;
        }
        Ok(())
    }

    /// t = b − A x on the even lines right after the odd axial lines were solved (the odd
    /// lines' defect is 0: each odd line was solved exactly against its θ-neighbours, which are
    /// even lines and have not changed since; for odd n_θ the lines n_θ − 1 and 0 are both
    /// even, and every odd line's neighbours are still even). The odd lines of t are left as
    /// they are: [`restrict_after_zebra`] reads the even ones only. Half a defect pass saved
    /// per cycle and level.
    #[inline(always)]
    fn defect_after_zebra(&mut self) {
        self.aw
            .defect_columns(&self.x, &self.b, &mut self.t, Some(0));
    }

    /// x += A_z⁻¹ (b − A x) on the axial lines of one parity (θ-neighbours lagged; the lines of
    /// the other parity are the only neighbours, so the two halves are Gauss–Seidel ordered).
    /// `x_is_zero`: x = 0 on entry (a coarse level's first sweep), so the defect is b itself
    /// and is not computed (the same values: b − A · 0 = b).
    #[inline(always)]
    fn axial_sweep(
        &mut self,
        level: usize,
        parity: usize,
        x_is_zero: bool,
    ) -> Result<(), ReynoldsError> {
        let (nt, nz) = (self.a.nt, self.a.nz);
        let lines = self.lines_of(parity);
        let m = lines * nz;
        // The fields borrowed apart: the transposing loops below then keep their slices in
        // registers (through `self` every store could alias them, and they were reloaded and
        // bounds-checked per element: the scalar gather and scatter were a tenth of the cycle).
        let Self {
            aw,
            x,
            b,
            t,
            line_rhs,
            line_sol,
            attached,
            attached_defect,
            axial,
            ..
        } = self;
        let (line_rhs, line_sol) = (&mut line_rhs[..m], &mut line_sol[..m]);
        if !x_is_zero {
            // The defect of this parity's lines (their neighbours are the other parity's:
            // every line's defect is of x before the sweep).
            aw.defect_columns(x, b, t, Some(parity));
        }
        for l in 0..lines {
            let i = 2 * l + parity;
            let column = if x_is_zero {
                &b[i * nz..(i + 1) * nz]
            } else {
                &t[i * nz..(i + 1) * nz]
            };
            for (row, &v) in line_rhs.chunks_exact_mut(lines).zip(column) {
                row[l] = v;
            }
        }
        // The attached cavitated nodes eliminated into their lines (block Gauss–Seidel of the
        // line with them; module docs, "Reformation fronts").
        for (q, at) in attached[parity].iter().enumerate() {
            let t = if x_is_zero {
                b[at.m]
            } else {
                aw.defect_at(at.m, x, b)
            };
            attached_defect[q] = t;
            line_rhs[at.slot] -= at.km_over_mm * t;
        }
        axial[parity]
            .solve(line_rhs, line_sol)
            .map_err(|e| line_error(level, "axial", e))?;
        for l in 0..lines {
            let i = 2 * l + parity;
            let column = &mut x[i * nz..(i + 1) * nz];
            for (xv, row) in column.iter_mut().zip(line_sol.chunks_exact(lines)) {
                *xv += row[l];
            }
        }
        for (q, at) in attached[parity].iter().enumerate() {
            let dk = line_sol[at.slot];
            x[at.m] += (attached_defect[q] - at.mk * dk) * at.inv_mm;
        }
        debug_assert!(nt >= 2);
        Ok(())
    }
}

/// The multigrid hierarchy of one frozen system (rebuilt by [`Multigrid::setup`]). The level
/// vectors, the line-factor staging and the coarsest banded LU's storage are reused.
#[derive(Default)]
pub(crate) struct Multigrid {
    levels: Vec<MgLevel>,
    coarsest: CoarsestLu,
    /// Tests: the next [`Multigrid::setup`] keeps the hierarchy as stale whatever it was built
    /// for (to exercise the rebuild inside the Krylov solve).
    #[cfg(test)]
    pub(crate) planted: bool,
}

impl std::fmt::Debug for Multigrid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Multigrid")
            .field("levels", &self.levels.len())
            .finish()
    }
}

impl Clone for Multigrid {
    /// A clone is an empty hierarchy: it holds nothing but the factors of the last frozen
    /// system, which the next [`Multigrid::setup`] replaces anyway.
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// The fine level's coarse-space mask at node k: 1 on the full-film unknowns, 0 on Dirichlet
/// and cavitated nodes (module docs, "Masks"); without a switch every unknown is full.
#[inline(always)]
/// Whether `mask` is the finest level's mask of `grid` with `switch` ([`fine_mask`] at every
/// node; a loop without early exit).
fn same_mask(grid: &Grid, switch: Option<&[f64]>, mask: &[f64]) -> bool {
    same_mask_at(grid, switch, mask, 0..mask.len())
}

/// [`same_mask`] on the nodes `nodes` only.
fn same_mask_at(
    grid: &Grid,
    switch: Option<&[f64]>,
    mask: &[f64],
    nodes: std::ops::Range<usize>,
) -> bool {
    let (mask, kind) = (&mask[nodes.clone()], &grid.kind[nodes.clone()]);
    let mut same = true;
    match switch {
        None => {
            for (&m, &kind) in mask.iter().zip(kind) {
                same &= m == f64::from(u8::from(kind == NodeKind::Unknown));
            }
        }
        Some(g) => {
            for ((&m, &kind), &g) in mask.iter().zip(kind).zip(&g[nodes]) {
                same &= m == f64::from(u8::from(kind == NodeKind::Unknown && g > 0.5));
            }
        }
    }
    same
}

fn fine_mask(grid: &Grid, switch: Option<&[f64]>, k: usize) -> f64 {
    let full = switch.is_none_or(|g| g[k] > 0.5);
    if grid.kind[k] == NodeKind::Unknown && full {
        1.0
    } else {
        0.0
    }
}

/// The coarsest level's direct solve: a banded LU with partial pivoting
/// ([`crate::banded::BandedLu`]) of the nine-point operator with its unknowns numbered z outer,
/// θ inner (k' = j n_θ + i):
///
/// ```text
///   j+1:   ○ ○ ○ ○ ○ ○ ○ ○        (i, j) couples to (i±1 mod n_θ, j) and (i±1 mod n_θ, j±1):
///   j  :   ● ○ ○ ○ ○ ○ ○ ●         |k'(row) − k'(col)| ≤ n_θ + (n_θ − 1) = 2 n_θ − 1
///   j−1:   ○ ○ ○ ○ ○ ○ ○ ○        (the periodic wrap i = 0 ↔ n_θ − 1 is n_θ − 1 apart)
/// ```
///
/// so kl = ku = 2 n_θ − 1 ≤ 7 (n_θ ≤ [`COARSEST_THETA`]) whatever n_z is: about
/// 2 n · 7 · 14 flops to factor (n = n_θ n_z, 124 on the default grid) and 2 n · 21 per solve.
/// It replaced faer's sparse LU of an 8 × n_z coarsest level, whose symbolic analysis had to
/// be redone whenever the coarse space (the full-film mask) changed the nonzero pattern.
/// Measured (callgrind, compressor-size inverse cycle of the timing report, 120 × 31, 1°;
/// and the warm-step bench): with n_θ ≤ 8 the banded LU (band 15, filled where the sparse LU
/// skipped the cavity's identity rows) was dearer than the sparse one — +1.8 % instructions of
/// the cycle, its solves 3× the sparse solves; one level more, down to n_θ ≤ 4, makes the band
/// 7 and the factor and solve together < 1.5 % of the cycle: −1.0 % instructions of the cycle
/// (Krylov iterations per film step unchanged), −2.2 % of the warm step (whose coarsest
/// factor had been 11 % of its instructions).
#[derive(Default)]
struct CoarsestLu {
    lu: BandedLu,
    /// The right-hand side and solution of a coarsest solve (in place, z-outer order).
    rhs: Vec<f64>,
}

impl CoarsestLu {
    /// Forget the factorization (a setup under way).
    fn clear(&mut self) {
        self.lu.reset(0, 0, 0);
    }

    /// Whether a factorization is in hand.
    fn is_ready(&self) -> bool {
        self.lu.is_factored() && !self.lu.is_empty()
    }

    /// Factor the nine-point level `a` (row k = i n_z + j holds c[(dθ, dz)][k] for the node
    /// (i + dθ mod n_θ, j + dz)); two offsets that meet in one entry when n_θ ≤ 2 are summed.
    fn factor(&mut self, a: &Stencil9) -> Result<(), ReynoldsError> {
        let (nt, nz) = (a.nt, a.nz);
        let n = nt * nz;
        let band = (2 * nt - 1).min(n - 1);
        self.lu.reset(n, band, band);
        let band_error = |e: crate::banded::BandedError| ReynoldsError::LinearSolve {
            solver: "multigrid coarsest level",
            detail: format!("{e} ({nt} × {nz} coarsest level)"),
        };
        for i in 0..nt {
            for j in 0..nz {
                let k = i * nz + j;
                let row = j * nt + i;
                for di in -1isize..=1 {
                    let ic = wrap(i, di, nt);
                    for dj in -1isize..=1 {
                        let jc = j as isize + dj;
                        if jc < 0 || jc >= nz as isize {
                            continue;
                        }
                        let v = a.c[at(di, dj)][k];
                        if v != 0.0 {
                            self.lu
                                .add(row, jc as usize * nt + ic, v)
                                .map_err(band_error)?;
                        }
                    }
                }
            }
        }
        self.lu.factor().map_err(band_error)
    }
}

impl Multigrid {
    /// Builds the hierarchy for the frozen system `st`: masks, Galerkin operators, line factors
    /// and the coarsest LU.
    ///
    /// The hierarchy of the previous setup is kept when it was built for the same coarse space
    /// (the same full-film mask: no node switched) and a matrix within [`MAX_REUSE_DRIFT`] of
    /// this one ([`Multigrid::fit`]); the answer tells which, so that the Krylov solve can
    /// [`rebuild`](Multigrid::rebuild) a stale hierarchy that stops paying its way. A
    /// hierarchy built for a matrix that differs from this one in at most a quarter of the
    /// θ-columns and nowhere else (a Newton step that switched a few nodes) is updated in those
    /// columns ([`Multigrid::update_columns`]): the rebuilt hierarchy, bit for bit, at a
    /// fraction of the cost (compressor-size inverse cycle: 346 of 790 rebuilds, −4.2 %
    /// instructions of the run). With AVX2 when the CPU has it (the same bits, as
    /// [`Multigrid::vcycle`]).
    pub(crate) fn setup(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Result<Hierarchy, ReynoldsError> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of
            // calling a function compiled with `target_feature(enable = "avx2")`.
            return unsafe { self.setup_avx2(grid, st, switch) };
        }
        self.setup_generic(grid, st, switch)
    }

    /// [`Multigrid::setup_generic`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn setup_avx2(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Result<Hierarchy, ReynoldsError> {
        self.setup_generic(grid, st, switch)
    }

    /// [`Multigrid::setup`] for any CPU.
    #[inline(always)]
    fn setup_generic(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Result<Hierarchy, ReynoldsError> {
        #[cfg(test)]
        if std::mem::take(&mut self.planted) {
            return Ok(Hierarchy::Kept { stale: true });
        }
        let fit = self.fit(grid, st, switch);
        if fit == Hierarchy::Built {
            match self.changed_columns(grid, st, switch) {
                Some(columns) => self.update_columns(grid, st, switch, &columns)?,
                None => self.rebuild_generic(grid, st, switch)?,
            }
        }
        Ok(fit)
    }

    /// The θ-columns of the finest level in which the frozen system `st` with `switch` differs
    /// from the one the hierarchy in hand was built for (any of the five entries of a row, to
    /// the bit, or the mask), when they are at least one and at most a quarter of the columns:
    /// a Newton step of one film step that switched a few nodes at the cavity edges, whose
    /// matrix differs in the rows of those nodes and of their neighbours only
    /// ([`Multigrid::update_columns`]). None otherwise (nothing built, another grid, or a matrix
    /// that changed elsewhere too: a new time level or Newton iterate of ε).
    fn changed_columns(
        &self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Option<Vec<bool>> {
        let (Some(fine), Some(_)) = (self.levels.first(), self.coarsest.is_ready().then_some(()))
        else {
            return None;
        };
        let a = &fine.a;
        let (nt, nz) = (grid.n_theta, grid.n_z);
        if !(a.five && a.nt == nt && a.nz == nz && fine.mask.len() == grid.len()) {
            return None;
        }
        let n = nt * nz;
        let old = [&a.c[C], &a.c[W], &a.c[E], &a.c[S], &a.c[N]].map(|v| &v[..n]);
        let new = [&st.p, &st.w, &st.e, &st.s, &st.n].map(|v| &v[..n]);
        let mut columns = vec![false; nt];
        let mut count = 0;
        for (i, column) in columns.iter_mut().enumerate() {
            // Any row of the column (a loop without early exit).
            let rows = i * nz..(i + 1) * nz;
            let mut differs = !same_mask_at(grid, switch, &fine.mask, rows.clone());
            for k in rows {
                differs |= (old[0][k].to_bits() != new[0][k].to_bits())
                    | (old[1][k].to_bits() != new[1][k].to_bits())
                    | (old[2][k].to_bits() != new[2][k].to_bits())
                    | (old[3][k].to_bits() != new[3][k].to_bits())
                    | (old[4][k].to_bits() != new[4][k].to_bits());
            }
            *column = differs;
            count += usize::from(differs);
        }
        (count > 0 && 4 * count <= nt).then_some(columns)
    }

    /// Brings the hierarchy to the frozen system `st` with `switch`, which differs from the one
    /// it was built for only in the finest-level θ-columns `columns`
    /// ([`Multigrid::changed_columns`]): the finest rows and mask of those columns, then on
    /// each coarser level the columns whose Galerkin entries can see them — coarse column I
    /// reads the fine columns 2I − 2 … 2I + 2 (its children, their θ-neighbours and the masks
    /// of both) and the coarse masks at I − 1 … I + 1, which are the fine masks at 2I − 2 …
    /// 2I + 2 — so a coarse column within three fine columns of a changed one (on the ring)
    /// is recomputed; the rounding and line factors of the changed columns and of the
    /// circumferential lines whose rows changed; the coarsest LU anew. Every recomputed value
    /// comes from the same operations on the same inputs as in [`Multigrid::rebuild`], and
    /// every kept one had its inputs unchanged: the hierarchy is the rebuilt one bit for bit
    /// (tested), at the cost of the changed columns instead of all.
    #[inline(always)]
    fn update_columns(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
        columns: &[bool],
    ) -> Result<(), ReynoldsError> {
        // An update that fails half way must not look like a finished hierarchy to `fit`.
        self.coarsest.clear();
        let (nt, nz) = (grid.n_theta, grid.n_z);
        let depth = self.levels.len();
        let mut rows = Vec::new();
        {
            let f = &mut self.levels[0];
            let mut row_changed = vec![false; nz];
            let new = [(C, &st.p), (W, &st.w), (E, &st.e), (S, &st.s), (N, &st.n)];
            for i in (0..nt).filter(|&i| columns[i]) {
                for j in 0..nz {
                    let k = i * nz + j;
                    for &(o, src) in &new {
                        if f.a.c[o][k].to_bits() != src[k].to_bits() {
                            row_changed[j] |= o == C || o == W || o == E;
                            f.a.c[o][k] = src[k];
                        }
                    }
                    f.mask[k] = fine_mask(grid, switch, k);
                }
            }
            rows.extend((0..nz).filter(|&j| row_changed[j]));
            f.collect_attached();
        }
        // A finest column's line diagonals and coarsening operator read the attachments of its
        // θ-neighbours (`MgLevel::stage_axial`, `MgLevel::eliminate_attached`): the columns
        // next to a changed one are refactored and coarsened again too.
        let mut changed0 = columns.to_vec();
        for i in (0..nt).filter(|&i| columns[i]) {
            changed0[wrap(i, -1, nt)] = true;
            changed0[wrap(i, 1, nt)] = true;
        }
        let mut changed = vec![changed0];
        self.levels[0].eliminate_attached();
        for l in 1..depth {
            let (fine, coarse) = self.levels.split_at_mut(l);
            let (f, c) = (&fine[l - 1], &mut coarse[0]);
            let fnt = f.a.nt;
            let cnt = coarse_len(fnt);
            let fine_changed = &changed[l - 1];
            let mut coarse_changed = vec![false; cnt];
            for fc in (0..fnt).filter(|&fc| fine_changed[fc]) {
                for d in 0..=3 {
                    for g in [(fc + d) % fnt, (fc + fnt - d) % fnt] {
                        if g % 2 == 0 {
                            coarse_changed[g / 2] = true;
                        }
                    }
                }
            }
            for ic in (0..cnt).filter(|&ic| coarse_changed[ic]) {
                for j in 0..nz {
                    c.mask[ic * nz + j] = f.mask[2 * ic * nz + j];
                }
            }
            for ic in (0..cnt).filter(|&ic| coarse_changed[ic]) {
                for v in &mut c.a.c {
                    v[ic * nz..(ic + 1) * nz].fill(0.0);
                }
            }
            for ic in (0..cnt).filter(|&ic| coarse_changed[ic]) {
                galerkin_column(&f.a, &f.mask, &c.mask, &mut c.a, ic);
            }
            if l == 1 {
                fine[0].restore_attached();
            }
            changed.push(coarse_changed);
        }
        self.levels[0].restore_attached();
        for l in 0..depth - 1 {
            let level_rows: &[usize] = if l == 0 { &rows } else { &[] };
            self.levels[l].refactor_columns(l, &changed[l], level_rows)?;
        }
        let last = &mut self.levels[depth - 1];
        last.round_operator();
        self.coarsest.factor(&last.a)?;
        Ok(())
    }

    /// Builds the hierarchy for `st` whatever the previous one was (with AVX2 when the CPU has
    /// it, the same bits).
    pub(crate) fn rebuild(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Result<(), ReynoldsError> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of
            // calling a function compiled with `target_feature(enable = "avx2")`.
            return unsafe { self.rebuild_avx2(grid, st, switch) };
        }
        self.rebuild_generic(grid, st, switch)
    }

    /// [`Multigrid::rebuild_generic`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn rebuild_avx2(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Result<(), ReynoldsError> {
        self.rebuild_generic(grid, st, switch)
    }

    /// [`Multigrid::rebuild`] for any CPU.
    #[inline(always)]
    fn rebuild_generic(
        &mut self,
        grid: &Grid,
        st: &Stencil,
        switch: Option<&[f64]>,
    ) -> Result<(), ReynoldsError> {
        // A rebuild that fails half way must not look like a finished one to `fit`.
        self.coarsest.clear();
        let mut depth = 1;
        let mut nt = grid.n_theta;
        while nt > COARSEST_THETA {
            nt = coarse_len(nt);
            depth += 1;
        }
        self.levels.resize_with(depth, MgLevel::default);
        self.levels[0].a.assign_five(grid, st);
        let mask = &mut self.levels[0].mask;
        mask.clear();
        mask.extend((0..grid.len()).map(|k| fine_mask(grid, switch, k)));
        self.levels[0].collect_attached();
        // The first coarse level from the operator with the attached nodes eliminated.
        self.levels[0].eliminate_attached();
        for l in 1..depth {
            let (fine, coarse) = self.levels.split_at_mut(l);
            let (f, c) = (&fine[l - 1], &mut coarse[0]);
            coarse_mask(f.a.nt, f.a.nz, &f.mask, &mut c.mask);
            galerkin(&f.a, &f.mask, &c.mask, &mut c.a);
            if l == 1 {
                fine[0].restore_attached();
            }
        }
        // (A single-level hierarchy has no Galerkin product: nothing was restored yet.)
        self.levels[0].restore_attached();
        for l in 0..depth - 1 {
            self.levels[l].factor(l)?;
        }
        let last = &mut self.levels[depth - 1];
        let n = last.a.nt * last.a.nz;
        for v in [&mut last.x, &mut last.b] {
            v.clear();
            v.resize(n, 0.0);
        }
        last.round_operator();
        self.coarsest.factor(&last.a)?;
        Ok(())
    }

    /// Whether the hierarchy in hand serves the frozen system `st` with `switch`: built for
    /// exactly this matrix (the second Newton step of a film step whose switch did not change;
    /// the film-force Jacobian's right-hand sides, which have the step's last matrix), or for
    /// the same coarse space and a matrix that differs by at most [`MAX_REUSE_DRIFT`] in every
    /// row, measured as Σ_l |Δa_kl| / Σ_l |a_kl| (the next Newton step or time step of a film whose
    /// switch stayed put). Otherwise [`Hierarchy::Built`]: a node switched (its row changes by
    /// orders of magnitude between the β-sized pressure flux and the Couette transport, and the
    /// coarse space with it), or the film moved too far.
    fn fit(&self, grid: &Grid, st: &Stencil, switch: Option<&[f64]>) -> Hierarchy {
        let (Some(fine), Some(_)) = (self.levels.first(), self.coarsest.is_ready().then_some(()))
        else {
            return Hierarchy::Built;
        };
        let a = &fine.a;
        let n = grid.len();
        let same_space = a.five
            && a.nt == grid.n_theta
            && a.nz == grid.n_z
            && fine.mask.len() == n
            && same_mask(grid, switch, &fine.mask);
        if !same_space {
            return Hierarchy::Built;
        }
        let old = [&a.c[C], &a.c[W], &a.c[E], &a.c[S], &a.c[N]].map(|v| &v[..n]);
        let new = [&st.p, &st.w, &st.e, &st.s, &st.n].map(|v| &v[..n]);
        if old == new {
            return Hierarchy::Kept { stale: false };
        }
        // Every row within the drift bound (a loop without early exit: it vectorizes, and
        // most hierarchies asked are within it).
        let mut within = true;
        for k in 0..n {
            let change = (new[0][k] - old[0][k]).abs()
                + (new[1][k] - old[1][k]).abs()
                + (new[2][k] - old[2][k]).abs()
                + (new[3][k] - old[3][k]).abs()
                + (new[4][k] - old[4][k]).abs();
            let size = old[0][k].abs()
                + old[1][k].abs()
                + old[2][k].abs()
                + old[3][k].abs()
                + old[4][k].abs();
            within &= change <= MAX_REUSE_DRIFT * size;
        }
        if within {
            Hierarchy::Kept { stale: true }
        } else {
            Hierarchy::Built
        }
    }

    /// z = M⁻¹ r: one cycle from z = 0 (module docs), in [`Work`] precision. r is scaled by
    /// the power of two nearest to 1 / max|r| on the way in and z back on the way out (both
    /// exact), so the cycle's values sit near 1 whatever the size of r; entries below
    /// [`DROP_BELOW`] of max|r| are dropped (they could reach the subnormal range of `f32`,
    /// which x86 cores compute slowly, and lie far below the cycle's own rounding).
    #[inline(always)]
    pub(crate) fn apply(&mut self, r: &[f64], z: &mut [f64]) -> Result<(), ReynoldsError> {
        let rmax = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if rmax == 0.0 {
            z.fill(0.0);
            return Ok(());
        }
        if !rmax.is_finite() {
            return Err(ReynoldsError::LinearSolve {
                solver: "multigrid",
                detail: "non-finite right-hand side of the V-cycle".into(),
            });
        }
        // 2^k ≈ 1 / rmax, |k| ≤ 1000: exact in f64, and r · 2^k is exact.
        let k = (-rmax.log2().round()).clamp(-1000.0, 1000.0) as i32;
        let (down, up) = (2f64.powi(k), 2f64.powi(-k));
        for (b, &v) in self.levels[0].b.iter_mut().zip(r) {
            let v = v * down;
            *b = if v.abs() < DROP_BELOW {
                0.0
            } else {
                Work::from_f64(v)
            };
        }
        self.vcycle()?;
        for (zk, &x) in z.iter_mut().zip(&self.levels[0].x) {
            *zk = x.to_f64() * up;
        }
        Ok(())
    }

    /// The V-cycle from x = 0 on every level, with AVX2 when the CPU has it (the same
    /// operations in the same order, wider vectors: no fused multiply-add is enabled, so both
    /// copies give the same bits; as in [`crate::tridiagonal`]).
    fn vcycle(&mut self) -> Result<(), ReynoldsError> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of
            // calling a function compiled with `target_feature(enable = "avx2")`.
            return unsafe { self.vcycle_avx2() };
        }
        self.vcycle_generic()
    }

    /// [`Multigrid::vcycle_generic`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn vcycle_avx2(&mut self) -> Result<(), ReynoldsError> {
        self.vcycle_generic()
    }

    /// x_0 ≈ A_0⁻¹ b_0 from x_0 = 0: one V(1, 1)-cycle (module docs), level by level down to
    /// the coarsest and back up.
    #[inline(always)]
    fn vcycle_generic(&mut self) -> Result<(), ReynoldsError> {
        let depth = self.levels.len();
        for l in 0..depth - 1 {
            // Pre-smoothing: circumferential lines (from x = 0 the defect is b), then the
            // axial lines, even i before odd i; the defect restricted to the next level.
            let (fine, coarse) = self.levels.split_at_mut(l + 1);
            let f = &mut fine[l];
            if l == 0 {
                f.circumferential_sweep(l, true)?;
            } else {
                f.x.fill(0.0);
            }
            f.axial_sweep(l, 0, l > 0)?;
            f.axial_sweep(l, 1, false)?;
            f.defect_after_zebra();
            restrict_after_zebra(
                f.a.nt,
                f.a.nz,
                &f.maskw,
                &coarse[0].maskw,
                &f.t,
                &mut coarse[0].b,
            );
        }
        self.solve_coarsest()?;
        for l in (0..depth - 1).rev() {
            let (fine, coarse) = self.levels.split_at_mut(l + 1);
            let f = &mut fine[l];
            prolong_add(f.a.nt, f.a.nz, &f.maskw, &coarse[0].x, &mut f.x);
            // Post-smoothing in the reverse order.
            f.axial_sweep(l, 1, false)?;
            f.axial_sweep(l, 0, false)?;
            if l == 0 {
                f.circumferential_sweep(l, false)?;
            }
        }
        Ok(())
    }

    fn solve_coarsest(&mut self) -> Result<(), ReynoldsError> {
        let last = self.levels.last_mut().expect("at least one level");
        let coarsest = &mut self.coarsest;
        if !coarsest.is_ready() {
            return Err(ReynoldsError::LinearSolve {
                solver: "multigrid coarsest level",
                detail: "no factorization (setup failed or not run)".into(),
            });
        }
        let (nt, nz) = (last.a.nt, last.a.nz);
        let n = nt * nz;
        // Level order k = i n_z + j → the factorization's z-outer order j n_θ + i and back.
        let rhs = &mut coarsest.rhs;
        rhs.clear();
        rhs.resize(n, 0.0);
        for i in 0..nt {
            for j in 0..nz {
                rhs[j * nt + i] = last.b[i * nz + j].to_f64();
            }
        }
        coarsest.lu.solve_in_place(rhs);
        for i in 0..nt {
            for j in 0..nz {
                let v = Work::from_f64(rhs[j * nt + i]);
                if !v.is_finite() {
                    return Err(ReynoldsError::NonFinite {
                        what: "multigrid coarsest-level solution",
                        theta_index: i,
                        z_index: j,
                        iteration: 0,
                    });
                }
                last.x[i * nz + j] = v;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
