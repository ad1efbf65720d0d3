//! The iterative solve of one frozen-switch system: a restarted flexible GMRES, preconditioned
//! by ADI line sweeps with a coarse line-aggregate correction (this module) or by the multigrid
//! V-cycle of [`super::multigrid`] (the default; chosen by [`Preconditioner`]).
//!
//! # Why not plain ADI sweeps
//!
//! With the physical bulk modulus the full-film rows are a stiff, nearly incompressible pressure
//! (Poisson-type) operator. A line sweep solves its own direction exactly but lags the other
//! one; for an error mode that is smooth in both θ and z the lagged part is almost all of the
//! operator, so stationary ADI sweeps converge like 1 − O(Δ²) per sweep (docs/conventions.md §3: "a
//! single ADI pass per time step is not a converged solution"). Two remedies, both cheap:
//!
//! 1. **Coarse correction (additive correction, \[SettariAziz1973\]).** Aggregate each axial
//!    line's unknowns into one: restriction R sums the rows of line i, prolongation P puts a
//!    constant on the line's unknowns (0 on Dirichlet nodes). The Galerkin operator R A P of the
//!    five-point stencil couples line i with i ± 1 only and is periodic in θ:
//!
//!    ```text
//!      C_i δ_i + C^w_i δ_{i−1} + C^e_i δ_{i+1} = Σ_j r_ij
//!      C_i  = Σ_j s_ij (p_ij s_ij + s_ij^S s_{i,j−1} + n_ij s_{i,j+1}),
//!      C^w_i = Σ_j s_ij w_ij s_{i−1,j},   C^e_i = Σ_j s_ij e_ij s_{i+1,j}
//!    ```
//!
//!    a cyclic tridiagonal line solved with Yu & Sawicki's modified Thomas kernel.
//! 2. **Krylov acceleration.** One application of the preconditioner M⁻¹ r is
//!
//!    ```text
//!      x  = P C⁻¹ R r                        (coarse)
//!      x += A_θ⁻¹ (r − A x)                  (all circumferential lines, cyclic kernel,
//!                                             batched across lines; z-neighbours lagged)
//!      x += A_z⁻¹ (r − A x)                  (all axial lines, Thomas; θ-neighbours lagged)
//!      x += A_θ⁻¹ (r − A x)                  (circumferential lines again: symmetric order,
//!                                             −30 % Krylov iterations for +25 % work)
//!    ```
//!
//!    The line matrices do not change during a solve: they are factored once
//!    ([`InterleavedFactors`]), and each sweep is a forward and a back substitution, vectorized
//!    across lines (bit for bit the one-shot line solvers' result).
//!
//!    Restarted flexible GMRES \[Saad1993\] iterates on A M⁻¹ until the discrete mass
//!    residual max_k |r_k| is below `tolerance ×` the flux scale (max over rows of Σ|A_kl ψ_l|).
//!
//! The switch g is frozen during this solve and updated in the outer loop (`mod.rs`), which
//! repeats until no node changes state. Every pivot is checked by the line kernels; a failure
//! is an error naming the line, never a NaN.

use super::ReynoldsError;
use super::discretization::Stencil;
use super::grid::{Grid, NodeKind};
use super::multigrid::{Hierarchy, Multigrid};
use crate::tridiagonal::{InterleavedFactors, LineWorkspace, cyclic_thomas_solve};

/// The preconditioner of the flexible GMRES.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Preconditioner {
    /// ADI line sweeps with the line-aggregate coarse correction (this module).
    Adi,
    /// A V-cycle of θ-semi-coarsening multigrid with zebra axial-line smoothing
    /// ([`super::multigrid`]).
    Multigrid,
}

/// Krylov subspace size before a restart.
const RESTART: usize = 48;

/// Scratch memory of the ADI-Krylov solve, reused across solves (no allocation when warm).
#[derive(Debug, Clone, Default)]
pub(crate) struct AdiWorkspace {
    r: Vec<f64>,
    t: Vec<f64>,
    y: Vec<f64>,
    v: Vec<Vec<f64>>,
    z: Vec<Vec<f64>>,
    hess: Vec<f64>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    gvec: Vec<f64>,
    mask: Vec<f64>,
    coarse: [Vec<f64>; 5],
    /// The axial lines interleaved for the batched Thomas kernel (unknown j of line i at
    /// `j · n_θ + i`): sub, diag, sup (to factor), rhs, solution.
    axial: [Vec<f64>; 5],
    /// Factors of the circumferential and of the axial lines of the frozen system.
    circumferential_factors: InterleavedFactors,
    axial_factors: InterleavedFactors,
    line: LineWorkspace,
    pub(crate) multigrid: Multigrid,
}

/// Krylov iterations after which a solve preconditioned by a multigrid hierarchy kept from a
/// nearby matrix ([`Multigrid::setup`]) rebuilds it for its own matrix. A fresh hierarchy
/// solves the default grid's frozen systems to 1e-10 in 6–12 iterations (the multigrid module
/// docs); a kept one that has needed 12 no longer pays for the setup it saved.
pub(crate) const STALE_REBUILD_ITERATIONS: usize = 12;

/// Result of one frozen-switch iterative solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KrylovInfo {
    pub iterations: usize,
    /// max_k |r_k| of the returned x (what the stopping test saw).
    pub residual: f64,
    /// The flux scale of that test (`flux_scale`, or the stencil's own).
    pub scale: f64,
}

impl AdiWorkspace {
    fn ensure(&mut self, n: usize, nt: usize) {
        if self.r.len() != n {
            self.r = vec![0.0; n];
            self.t = vec![0.0; n];
            self.y = vec![0.0; n];
            self.mask = vec![0.0; n];
            self.v = vec![vec![0.0; n]; RESTART + 1];
            self.z = vec![vec![0.0; n]; RESTART];
            for a in &mut self.axial {
                *a = vec![0.0; n];
            }
        }
        if self.coarse[0].len() != nt {
            for c in &mut self.coarse {
                *c = vec![0.0; nt];
            }
        }
        if self.hess.len() != (RESTART + 1) * RESTART {
            self.hess = vec![0.0; (RESTART + 1) * RESTART];
            self.cs = vec![0.0; RESTART];
            self.sn = vec![0.0; RESTART];
            self.gvec = vec![0.0; RESTART + 1];
        }
    }
}

fn line_error(direction: &'static str, e: crate::tridiagonal::TridiagonalError) -> ReynoldsError {
    ReynoldsError::LinearSolve {
        solver: "ADI line sweep",
        detail: format!("{direction} line: {e}"),
    }
}

/// Builds the coarse (line-aggregate) operator into `ws.coarse[0..3]` = (w, diag, e).
fn build_coarse(grid: &Grid, st: &Stencil, ws: &mut AdiWorkspace) {
    let (nt, nz) = (grid.n_theta, grid.n_z);
    for k in 0..grid.len() {
        ws.mask[k] = if grid.kind[k] == NodeKind::Unknown {
            1.0
        } else {
            0.0
        };
    }
    let m = &ws.mask;
    for i in 0..nt {
        let iw = if i == 0 { nt - 1 } else { i - 1 };
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        let (mut cw, mut cd, mut ce) = (0.0, 0.0, 0.0);
        for j in 1..nz - 1 {
            let k = i * nz + j;
            if m[k] == 0.0 {
                continue;
            }
            cd += st.p[k] + st.s[k] * m[k - 1] + st.n[k] * m[k + 1];
            cw += st.w[k] * m[iw * nz + j];
            ce += st.e[k] * m[ie * nz + j];
        }
        if cd == 0.0 && cw == 0.0 && ce == 0.0 {
            cd = 1.0;
        }
        ws.coarse[0][i] = cw;
        ws.coarse[1][i] = cd;
        ws.coarse[2][i] = ce;
    }
}

/// Factors the line matrices of the frozen system once for all sweeps of the solve: the
/// circumferential lines as stored (line j, unknown i at i·n_z + j), the axial lines from an
/// interleaved copy of s, p, n (line i, unknown j at j·n_θ + i).
fn factor_lines(grid: &Grid, st: &Stencil, ws: &mut AdiWorkspace) -> Result<(), ReynoldsError> {
    let (nt, nz) = (grid.n_theta, grid.n_z);
    ws.circumferential_factors
        .factor_periodic(nt, nz, &st.w, &st.p, &st.e)
        .map_err(|e| line_error("circumferential (line = z index)", e))?;
    let [sub, diag, sup, _, _] = &mut ws.axial;
    for i in 0..nt {
        for j in 0..nz {
            let (k, t) = (i * nz + j, j * nt + i);
            sub[t] = st.s[k];
            diag[t] = st.p[k];
            sup[t] = st.n[k];
        }
    }
    ws.axial_factors
        .factor_dirichlet(nz, nt, sub, diag, sup)
        .map_err(|e| line_error("axial (line = θ index)", e))
}

/// x = M⁻¹ r (see the module docs). Uses `ws.t`, `ws.y`, `ws.coarse[3..5]`, `ws.axial[3..5]`
/// and the line factors set by [`factor_lines`].
fn precondition(
    grid: &Grid,
    st: &Stencil,
    r: &[f64],
    x: &mut [f64],
    ws: &mut AdiWorkspace,
) -> Result<(), ReynoldsError> {
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let n = grid.len();
    // Coarse: δ = C⁻¹ R r, x = P δ.
    {
        let [cw, cd, ce, crhs, cx] = &mut ws.coarse;
        for i in 0..nt {
            let mut s = 0.0;
            for j in 1..nz - 1 {
                let k = i * nz + j;
                s += ws.mask[k] * r[k];
            }
            crhs[i] = s;
        }
        cyclic_thomas_solve(cw, cd, ce, crhs, cx, &mut ws.line)
            .map_err(|e| line_error("coarse (line-aggregate)", e))?;
        for i in 0..nt {
            for j in 0..nz {
                let k = i * nz + j;
                x[k] = ws.mask[k] * cx[i];
            }
        }
    }
    // Circumferential lines (interleaved: line j, unknown i at i·n_z + j).
    st.defect(grid, x, r, &mut ws.t);
    ws.circumferential_factors
        .solve(&ws.t, &mut ws.y)
        .map_err(|e| line_error("circumferential (line = z index)", e))?;
    for k in 0..n {
        x[k] += ws.y[k];
    }
    // Axial lines: stored contiguously (line i, unknown j at i·n_z + j), solved all at once by
    // the batched Thomas kernel on their interleaved copy (the same arithmetic per line as the
    // single-line Thomas solve, bit for bit; the batch vectorizes across lines).
    st.defect(grid, x, r, &mut ws.t);
    {
        let [_, _, _, rhs, y] = &mut ws.axial;
        for i in 0..nt {
            for j in 0..nz {
                rhs[j * nt + i] = ws.t[i * nz + j];
            }
        }
        ws.axial_factors
            .solve(rhs, y)
            .map_err(|e| line_error("axial (line = θ index)", e))?;
        for i in 0..nt {
            for j in 0..nz {
                x[i * nz + j] += y[j * nt + i];
            }
        }
    }
    // Second circumferential pass (symmetric ADI ordering).
    st.defect(grid, x, r, &mut ws.t);
    ws.circumferential_factors
        .solve(&ws.t, &mut ws.y)
        .map_err(|e| line_error("circumferential (line = z index)", e))?;
    for k in 0..n {
        x[k] += ws.y[k];
    }
    Ok(())
}

/// a · b with eight partial sums (k mod 8), added pairwise at the end. A single running sum is
/// one serial chain of additions that cannot vectorize (Rust keeps the written order of
/// floating-point operations); it was ~40 % of the Krylov solve's own time (perf, 120 × 31).
/// The eight chains vectorize and are, if anything, more accurate (the error bound of
/// blocked summation). The order is fixed, so the result does not depend on the machine.
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    debug_assert_eq!(a.len(), b.len());
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for l in 0..8 {
            acc[l] += x[l] * y[l];
        }
    }
    for (l, (x, y)) in ra.iter().zip(rb).enumerate() {
        acc[l] += x * y;
    }
    sum_of_partials(&acc)
}

/// The eight partial sums of [`dot`] added in their fixed pairwise order.
#[inline(always)]
fn sum_of_partials(acc: &[f64; 8]) -> f64 {
    ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]))
}

/// w ← w − h v, then returns w · u (or w · w when `u` is None) of the updated w: the same
/// operations, partial sums and order as the update followed by [`dot`], in one pass.
fn subtract_and_dot(w: &mut [f64], h: f64, v: &[f64], u: Option<&[f64]>) -> f64 {
    debug_assert_eq!(w.len(), v.len());
    let mut acc = [0.0f64; 8];
    let n8 = w.len() / 8 * 8;
    let (wc, wr) = w.split_at_mut(n8);
    let (vc, vr) = v.split_at(n8);
    match u {
        Some(u) => {
            let (uc, ur) = u.split_at(n8);
            for ((w, v), u) in wc
                .chunks_exact_mut(8)
                .zip(vc.chunks_exact(8))
                .zip(uc.chunks_exact(8))
            {
                for l in 0..8 {
                    w[l] -= h * v[l];
                    acc[l] += w[l] * u[l];
                }
            }
            for (l, ((w, v), u)) in wr.iter_mut().zip(vr).zip(ur).enumerate() {
                *w -= h * v;
                acc[l] += *w * u;
            }
        }
        None => {
            for (w, v) in wc.chunks_exact_mut(8).zip(vc.chunks_exact(8)) {
                for l in 0..8 {
                    w[l] -= h * v[l];
                    acc[l] += w[l] * w[l];
                }
            }
            for (l, (w, v)) in wr.iter_mut().zip(vr).enumerate() {
                *w -= h * v;
                acc[l] += *w * *w;
            }
        }
    }
    sum_of_partials(&acc)
}

/// When [`solve_krylov`] stops.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KrylovStop {
    /// max |r| ≤ `tolerance` × flux scale.
    pub tolerance: f64,
    /// The flux scale of that test (the semismooth Newton passes the scale of its nonlinear
    /// residual, which a pseudo-time shift must not inflate); None: the stencil's own
    /// ([`Stencil::residual`]).
    pub flux_scale: Option<f64>,
    /// Krylov iterations allowed.
    pub max_iterations: usize,
    /// A semismooth Newton step's look at its answer on the way (`mod.rs`, module docs): once
    /// the residual is below the first of these relative levels, the iterate's switch H(x) is
    /// compared with the frozen `switch` after every iteration; at the first disagreement the
    /// solve stops (the switch is wrong: an accurate answer of this system would be wasted).
    /// Once the switch agrees at or below the second level the checks end and the solve goes
    /// on to `tolerance` in the same Krylov space.
    pub switch_check: Option<[f64; 2]>,
}

/// Solves A x = rhs for the frozen switch, starting from the `x` given (warm start), as `stop`
/// says. `preconditioner` chooses the ADI sweeps or the multigrid V-cycle; `switch` (g of the
/// frozen system) lets the multigrid keep the cavitated nodes out of its coarse space
/// (`multigrid` module docs; the ADI ignores it) and is what `stop.switch_check` compares with.
/// With AVX2 when the CPU has it: the same operations in the same order on wider vectors (no
/// fused multiply-add is enabled), so both copies give the same bits, as the V-cycle's
/// ([`crate::reynolds::multigrid`]) and the line solves' ([`crate::tridiagonal`]).
pub(crate) fn solve_krylov(
    grid: &Grid,
    st: &Stencil,
    x: &mut [f64],
    stop: KrylovStop,
    preconditioner: Preconditioner,
    switch: Option<&[f64]>,
    ws: &mut AdiWorkspace,
) -> Result<KrylovInfo, ReynoldsError> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of calling
        // a function compiled with `target_feature(enable = "avx2")`.
        return unsafe { solve_krylov_avx2(grid, st, x, stop, preconditioner, switch, ws) };
    }
    solve_krylov_generic(grid, st, x, stop, preconditioner, switch, ws)
}

/// [`solve_krylov_generic`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn solve_krylov_avx2(
    grid: &Grid,
    st: &Stencil,
    x: &mut [f64],
    stop: KrylovStop,
    preconditioner: Preconditioner,
    switch: Option<&[f64]>,
    ws: &mut AdiWorkspace,
) -> Result<KrylovInfo, ReynoldsError> {
    solve_krylov_generic(grid, st, x, stop, preconditioner, switch, ws)
}

/// [`solve_krylov`] for any CPU.
#[inline(always)]
pub(crate) fn solve_krylov_generic(
    grid: &Grid,
    st: &Stencil,
    x: &mut [f64],
    stop: KrylovStop,
    preconditioner: Preconditioner,
    switch: Option<&[f64]>,
    ws: &mut AdiWorkspace,
) -> Result<KrylovInfo, ReynoldsError> {
    let n = grid.len();
    ws.ensure(n, grid.n_theta);
    // A multigrid hierarchy kept from a nearby matrix (`Hierarchy::Kept { stale: true }`).
    let mut stale = false;
    match preconditioner {
        Preconditioner::Adi => {
            build_coarse(grid, st, ws);
            factor_lines(grid, st, ws)?;
        }
        Preconditioner::Multigrid => {
            stale = ws.multigrid.setup(grid, st, switch)? == Hierarchy::Kept { stale: true };
        }
    }
    // The switch checks still to make: their levels and the switch they compare with.
    let mut check = stop.switch_check.zip(switch);
    let mut iterations = 0;
    loop {
        let mut r = std::mem::take(&mut ws.r);
        let (rmax, own_scale) = st.residual(grid, x, &mut r);
        let scale = stop.flux_scale.unwrap_or(own_scale);
        if !rmax.is_finite() {
            ws.r = r;
            return Err(ReynoldsError::LinearSolve {
                solver: "ADI-Krylov",
                detail: format!("residual not finite after {iterations} iterations"),
            });
        }
        let target = stop.tolerance * scale;
        let done = KrylovInfo {
            iterations,
            residual: rmax,
            scale,
        };
        if rmax <= target || scale == 0.0 {
            ws.r = r;
            return Ok(done);
        }
        if let Some(([first, last], g)) = check
            && rmax <= first * scale
        {
            if switch_disagrees(grid, x, g) {
                ws.r = r;
                return Ok(done);
            }
            if rmax <= last * scale {
                check = None;
            }
        }
        if iterations >= stop.max_iterations {
            ws.r = r;
            return Err(ReynoldsError::LinearNotConverged {
                iterations,
                residual: rmax / scale,
                tolerance: stop.tolerance,
            });
        }
        let cycle = gmres_cycle(
            grid,
            st,
            (x, r),
            Targets {
                residual: target,
                check: check.map(|([first, last], g)| ([first * scale, last * scale], g)),
                max_iterations: stop.max_iterations,
            },
            preconditioner,
            switch,
            &mut stale,
            &mut iterations,
            ws,
        )?;
        match cycle {
            Cycle::Ended { used, switch_held } => {
                if switch_held {
                    check = None;
                }
                add_correction(ws, used, x);
            }
            Cycle::SwitchWrong => {
                // The iterate at the check, which `gmres_cycle` left in `ws.t`.
                x.copy_from_slice(&ws.t);
                let (rmax, own_scale) = st.residual(grid, x, &mut ws.r);
                return Ok(KrylovInfo {
                    iterations,
                    residual: rmax,
                    scale: stop.flux_scale.unwrap_or(own_scale),
                });
            }
        }
    }
}

/// Whether H(x) differs from the switch `g` at an unknown node (H = 1 where x ≥ 0, else 0:
/// the semismooth Newton's `set_switch`).
#[inline(always)]
fn switch_disagrees(grid: &Grid, x: &[f64], g: &[f64]) -> bool {
    x.iter()
        .zip(g)
        .zip(&grid.kind)
        .any(|((&x, &g), &kind)| kind == NodeKind::Unknown && (x >= 0.0) != (g == 1.0))
}

/// What a [`gmres_cycle`] aims at: the residual target, the switch checks still to make (their
/// absolute levels and the switch; [`KrylovStop::switch_check`]) and the iteration limit.
struct Targets<'a> {
    residual: f64,
    check: Option<([f64; 2], &'a [f64])>,
    max_iterations: usize,
}

/// How a [`gmres_cycle`] ended.
enum Cycle {
    /// At its target, its restart length or the iteration limit; its correction uses `used`
    /// directions. `switch_held`: a check at or below its last level found the switch right.
    Ended { used: usize, switch_held: bool },
    /// At a check whose iterate's switch differs from the frozen one: the iterate is in `ws.t`.
    SwitchWrong,
}

/// One cycle of flexible GMRES for [`solve_krylov`] from its iterate x and residual r
/// (`start`): up to `RESTART` Arnoldi steps on the right-preconditioned operator (rebuilding a
/// stale multigrid hierarchy at `STALE_REBUILD_ITERATIONS`), ended early once the 2-norm
/// estimate of the residual is below half the target or the iteration limit is reached. While
/// switch checks are due, the iterate of every step whose estimate is below half the first
/// check level is formed (in `ws.t`) and its switch compared with the frozen one (the checks
/// end once it agrees below half the last level). Counts the iterations.
// Crate-internal, called once by `solve_krylov` with its own state.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn gmres_cycle(
    grid: &Grid,
    st: &Stencil,
    start: (&[f64], Vec<f64>),
    targets: Targets,
    preconditioner: Preconditioner,
    switch: Option<&[f64]>,
    stale: &mut bool,
    iterations: &mut usize,
    ws: &mut AdiWorkspace,
) -> Result<Cycle, ReynoldsError> {
    let (x, r) = start;
    let mut check = targets.check;
    let mut switch_held = false;
    let beta = dot(&r, &r).sqrt();
    for (vk, rk) in ws.v[0].iter_mut().zip(&r) {
        *vk = rk / beta;
    }
    ws.r = r;
    ws.gvec.iter_mut().for_each(|g| *g = 0.0);
    ws.gvec[0] = beta;
    let mut used = 0;
    for jj in 0..RESTART {
        let mut zj = std::mem::take(&mut ws.z[jj]);
        let vj = std::mem::take(&mut ws.v[jj]);
        if *stale && *iterations == STALE_REBUILD_ITERATIONS {
            // Flexible GMRES keeps every preconditioned direction z_j, so the
            // preconditioner may change between iterations: rebuild for this matrix.
            ws.multigrid.rebuild(grid, st, switch)?;
            *stale = false;
        }
        match preconditioner {
            Preconditioner::Adi => precondition(grid, st, &vj, &mut zj, ws)?,
            Preconditioner::Multigrid => ws.multigrid.apply(&vj, &mut zj)?,
        }
        ws.v[jj] = vj;
        let mut w = std::mem::take(&mut ws.v[jj + 1]);
        st.apply(grid, &zj, &mut w);
        ws.z[jj] = zj;
        let hnorm = arnoldi_column(ws, jj, w);
        rotate_column(ws, jj);
        used = jj + 1;
        *iterations += 1;
        let estimate = ws.gvec[jj + 1].abs();
        if !estimate.is_finite() {
            return Err(ReynoldsError::LinearSolve {
                solver: "ADI-Krylov",
                detail: format!("Krylov residual not finite at iteration {iterations}"),
            });
        }
        // ‖r‖∞ ≤ ‖r‖₂: stop the cycle once the 2-norm estimate is below the target.
        if estimate <= 0.5 * targets.residual || hnorm == 0.0 {
            break;
        }
        if let Some(([first, last], g)) = check
            && estimate <= 0.5 * first
        {
            let mut trial = std::mem::take(&mut ws.t);
            trial.copy_from_slice(x);
            add_correction(ws, used, &mut trial);
            let wrong = switch_disagrees(grid, &trial, g);
            ws.t = trial;
            if wrong {
                return Ok(Cycle::SwitchWrong);
            }
            if estimate <= 0.5 * last {
                check = None;
                switch_held = true;
            }
        }
        if *iterations >= targets.max_iterations {
            break;
        }
    }
    Ok(Cycle::Ended { used, switch_held })
}

/// Column j of the Arnoldi process: w = A z_j orthogonalised against v_0 … v_j by modified
/// Gram–Schmidt (one pass over w per basis vector: the update by v_i and the dot product with
/// the next vector, or w · w after the last, share the pass), H_{i,j} and H_{j+1,j} = ‖w‖
/// stored, w / ‖w‖ kept as v_{j+1}. Returns ‖w‖ (0: the Krylov space is exhausted).
#[inline(always)]
fn arnoldi_column(ws: &mut AdiWorkspace, jj: usize, mut w: Vec<f64>) -> f64 {
    let mut hij = dot(&w, &ws.v[0]);
    for ii in 0..=jj {
        ws.hess[ii * RESTART + jj] = hij;
        let next = if ii < jj {
            Some(ws.v[ii + 1].as_slice())
        } else {
            None
        };
        hij = subtract_and_dot(&mut w, hij, &ws.v[ii], next);
    }
    let hnorm = hij.sqrt();
    ws.hess[(jj + 1) * RESTART + jj] = hnorm;
    if hnorm > 0.0 {
        let inv = 1.0 / hnorm;
        for wk in w.iter_mut() {
            *wk *= inv;
        }
    }
    ws.v[jj + 1] = w;
    hnorm
}

/// Column j of H brought to upper-triangular form: the earlier Givens rotations applied, a new
/// one zeroing H_{j+1,j}, and the same rotation applied to the residual vector g (whose
/// |g_{j+1}| is the new residual 2-norm).
#[inline(always)]
fn rotate_column(ws: &mut AdiWorkspace, jj: usize) {
    for ii in 0..jj {
        let (a, b) = (ws.hess[ii * RESTART + jj], ws.hess[(ii + 1) * RESTART + jj]);
        ws.hess[ii * RESTART + jj] = ws.cs[ii] * a + ws.sn[ii] * b;
        ws.hess[(ii + 1) * RESTART + jj] = -ws.sn[ii] * a + ws.cs[ii] * b;
    }
    let (a, b) = (ws.hess[jj * RESTART + jj], ws.hess[(jj + 1) * RESTART + jj]);
    let d = a.hypot(b);
    let (c, s) = if d == 0.0 { (1.0, 0.0) } else { (a / d, b / d) };
    ws.cs[jj] = c;
    ws.sn[jj] = s;
    ws.hess[jj * RESTART + jj] = d;
    ws.hess[(jj + 1) * RESTART + jj] = 0.0;
    ws.gvec[jj + 1] = -s * ws.gvec[jj];
    ws.gvec[jj] *= c;
}

/// The end of a GMRES cycle of `used` columns: back substitution R y = g, then x += Z y
/// (right preconditioning: the preconditioned directions z_i).
#[inline(always)]
fn add_correction(ws: &AdiWorkspace, used: usize, x: &mut [f64]) {
    let mut yv = [0.0; RESTART];
    for ii in (0..used).rev() {
        let mut s = ws.gvec[ii];
        for kk in ii + 1..used {
            s -= ws.hess[ii * RESTART + kk] * yv[kk];
        }
        yv[ii] = s / ws.hess[ii * RESTART + ii];
    }
    for (ii, &yi) in yv.iter().enumerate().take(used) {
        for (xk, zk) in x.iter_mut().zip(&ws.z[ii]) {
            *xk += yi * zk;
        }
    }
}
