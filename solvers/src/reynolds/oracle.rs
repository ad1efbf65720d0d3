//! The test oracle: a sparse direct (faer LU, partial pivoting) solve of the same five-point
//! system with the switch g frozen.
//!
//! The matrix is built from the [`Stencil`] row by row (diagonal, W, E, S, N; the periodic
//! neighbours wrap around) — the very numbers the ADI solve works on, so any difference between
//! the two answers is the iterative solver's, not the discretization's.

use faer::prelude::*;
use faer::sparse::{SparseColMat, Triplet};

use super::ReynoldsError;
use super::discretization::Stencil;
use super::grid::Grid;

/// Solves A x = rhs by sparse LU; `x` receives the solution.
pub(crate) fn solve_lu(grid: &Grid, st: &Stencil, x: &mut [f64]) -> Result<(), ReynoldsError> {
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let n = grid.len();
    let mut trip = Vec::with_capacity(5 * n);
    for i in 0..nt {
        let iw = if i == 0 { nt - 1 } else { i - 1 };
        let ie = if i + 1 == nt { 0 } else { i + 1 };
        for j in 0..nz {
            let k = i * nz + j;
            trip.push(Triplet::new(k, k, st.p[k]));
            if st.w[k] != 0.0 {
                trip.push(Triplet::new(k, iw * nz + j, st.w[k]));
            }
            if st.e[k] != 0.0 {
                trip.push(Triplet::new(k, ie * nz + j, st.e[k]));
            }
            if j > 0 && st.s[k] != 0.0 {
                trip.push(Triplet::new(k, k - 1, st.s[k]));
            }
            if j + 1 < nz && st.n[k] != 0.0 {
                trip.push(Triplet::new(k, k + 1, st.n[k]));
            }
        }
    }
    let mat = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trip).map_err(|e| {
        ReynoldsError::LinearSolve {
            solver: "sparse LU",
            detail: format!("matrix assembly failed: {e:?}"),
        }
    })?;
    let lu = mat.sp_lu().map_err(|e| ReynoldsError::LinearSolve {
        solver: "sparse LU",
        detail: format!("factorization failed: {e:?}"),
    })?;
    let rhs = Col::<f64>::from_fn(n, |k| st.rhs[k]);
    let sol = lu.solve(&rhs);
    for k in 0..n {
        let v = sol[k];
        if !v.is_finite() {
            return Err(ReynoldsError::NonFinite {
                what: "sparse LU solution",
                theta_index: k / nz,
                z_index: k % nz,
                iteration: 0,
            });
        }
        x[k] = v;
    }
    Ok(())
}
