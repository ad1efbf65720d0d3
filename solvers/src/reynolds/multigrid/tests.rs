//! Tests of the multigrid preconditioner: the transfer operators (R = Pᵀ, exact interpolation
//! of constant and linear fields), the Galerkin operator of a known stencil, the preconditioned
//! FGMRES against the sparse-LU oracle on frozen-switch systems of the real discretization, the
//! coarsest level's banded solve against a dense LU, and the grid independence of the Krylov
//! iteration count.

use super::super::*;
use super::*;

/// xorshift64: reproducible pseudo-random numbers in [0, 1).
fn rng(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The compressor main bearing of the validation timing case (docs/conventions.md §7): L = 18.288 mm,
/// R = 27.43 mm, c = 48.9 µm, μ = 0.02 Pa·s, a full-length feed groove 3.81 mm wide at θ = 90°
/// (its 24.9 mm axial extent covers the whole length), fed at 0.2068 MPa, 1800 rpm.
fn compressor(solver: LinearSolver, n_theta: usize, n_z: usize) -> ReynoldsParams {
    let mut p = ReynoldsParams::plain(27.43e-3, 18.288e-3, 48.9e-6, 0.02);
    p.grid = GridParams { n_theta, n_z };
    p.linear_solver = solver;
    p.grooves = vec![Groove {
        center_angle: std::f64::consts::FRAC_PI_2,
        center_z: 0.0,
        angular_width: 3.81e-3 / 27.43e-3,
        axial_width: 24.9e-3,
        cutoff_film_fraction: 0.01,
    }];
    p
}

fn running() -> OperatingConditions {
    OperatingConditions {
        journal_speed: 1800.0 * std::f64::consts::TAU / 60.0,
        bearing_speed: 0.0,
        feed_pressures: vec![0.2068e6],
    }
}

/// One crank degree at 1800 rpm, the inverse solver's default step.
const STEP: f64 = 1.0 / 30.0 / 360.0;

/// The frozen-switch system of the real discretization at ε: steady (`dt` None) or one
/// backward-Euler step from the old content 0.9 h (a squeezing film), with the switch
/// `switch(grid, k)` on the unknown nodes. Returns the solver (grid, Dirichlet values), the
/// stencil and the full switch vector.
fn frozen_system(
    params: ReynoldsParams,
    eps: [f64; 2],
    dt: Option<f64>,
    switch: &dyn Fn(&Grid, usize) -> f64,
) -> (ReynoldsSolver, Stencil, Vec<f64>) {
    let mut s = ReynoldsSolver::new(params).unwrap();
    let prep = s.prepare(eps, &running(), None).unwrap();
    let grid = &s.grid;
    let level = discretization::Level {
        grid,
        h: &prep.h.node,
        h_face: &prep.h.face_theta,
        k_theta: &s.k_theta,
        k_z: &s.k_z,
        speed: prep.speed,
    };
    let mut g = prep.g.clone();
    for k in 0..grid.len() {
        if grid.kind[k] == NodeKind::Unknown {
            g[k] = switch(grid, k);
        }
    }
    let old: Vec<f64> = prep.h.node.iter().map(|h| 0.9 * h).collect();
    let time = match dt {
        None => TimeTerm::Steady,
        Some(dt) => TimeTerm::Step {
            dt,
            old_content: &old,
            old_outflow: None,
        },
    };
    let mut st = Stencil::default();
    discretization::assemble(&level, &g, &s.dirichlet, time, &mut st);
    (s, st, g)
}

/// The start of a frozen solve as the Newton loop gives it: Dirichlet values in place, 0 on
/// the unknowns.
fn dirichlet_start(grid: &Grid, st: &Stencil) -> Vec<f64> {
    (0..grid.len())
        .map(|k| {
            if grid.kind[k] == NodeKind::Unknown {
                0.0
            } else {
                st.rhs[k]
            }
        })
        .collect()
}

/// FGMRES + multigrid from the Dirichlet start to max|r| ≤ `tol` × flux scale: the solution
/// and the iteration count.
fn solve_mg(grid: &Grid, st: &Stencil, g: &[f64], tol: f64) -> (Vec<f64>, usize) {
    let (x, info) = krylov_from_dirichlet(grid, st, g, tol, None, &mut Default::default());
    (x, info.iterations)
}

/// FGMRES + multigrid from the Dirichlet start to max|r| ≤ `tol` × flux scale with the switch
/// checks `check` (`adi::KrylovStop::switch_check`), on the workspace `ws`: the solution and
/// the solve's report.
fn krylov_from_dirichlet(
    grid: &Grid,
    st: &Stencil,
    g: &[f64],
    tol: f64,
    check: Option<[f64; 2]>,
    ws: &mut adi::AdiWorkspace,
) -> (Vec<f64>, adi::KrylovInfo) {
    let mut x = dirichlet_start(grid, st);
    let info = adi::solve_krylov(
        grid,
        st,
        &mut x,
        adi::KrylovStop {
            tolerance: tol,
            flux_scale: None,
            max_iterations: 400,
            switch_check: check,
        },
        adi::Preconditioner::Multigrid,
        Some(g),
        ws,
    )
    .unwrap();
    (x, info)
}

// ------------------------------------------------------------------ transfer operators

/// P and R as dense matrices, column by column (P e_I and R e_f).
fn dense_transfers(nt: usize, nz: usize, fmask: &[f64]) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let mut cmask = Vec::new();
    coarse_mask(nt, nz, fmask, &mut cmask);
    let (nf, nc) = (nt * nz, coarse_len(nt) * nz);
    let mut p = vec![vec![0.0; nc]; nf];
    let mut r = vec![vec![0.0; nf]; nc];
    for c in 0..nc {
        let mut e = vec![0.0; nc];
        e[c] = cmask[c];
        let mut col = vec![0.0; nf];
        prolong_add(nt, nz, fmask, &e, &mut col);
        for f in 0..nf {
            p[f][c] = col[f];
        }
    }
    for f in 0..nf {
        let mut e = vec![0.0; nf];
        e[f] = 1.0;
        let mut col = vec![0.0; nc];
        restrict(nt, nz, fmask, &cmask, &e, &mut col);
        for c in 0..nc {
            r[c][f] = col[c];
        }
    }
    (p, r)
}

/// The flat defect of a whole level (or of one zebra parity's columns) is the column-by-column
/// defect bit for bit, five- and nine-point, even and odd rings, short and long lines.
#[test]
fn flat_defect_is_the_line_by_line_defect() {
    let mut u = rng(0x2545_f491_4f6c_dd1d);
    for (nt, nz) in [(3, 3), (8, 17), (11, 7), (15, 17), (60, 17), (4, 31)] {
        for five in [true, false] {
            let n = nt * nz;
            let mut a = Stencil9::<Work> {
                nt,
                nz,
                c: std::array::from_fn(|_| (0..n).map(|_| (2.0 * u() - 1.0) as Work).collect()),
                five,
            };
            if five {
                for o in [0, 2, 6, 8] {
                    a.c[o].fill(0.0);
                }
            }
            let x: Vec<Work> = (0..n).map(|_| (2.0 * u() - 1.0) as Work).collect();
            let b: Vec<Work> = (0..n).map(|_| (2.0 * u() - 1.0) as Work).collect();
            let mut by_line = vec![0.0; n];
            for i in 0..nt {
                a.defect_line(i, &x, &b, &mut by_line);
            }
            let bits = |v: &[Work]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let mut flat = vec![Work::NAN; n];
            a.defect_columns(&x, &b, &mut flat, None);
            assert_eq!(bits(&flat), bits(&by_line), "{nt} x {nz}, five {five}");
            for parity in 0..2 {
                let mut half = vec![Work::NAN; n];
                a.defect_columns(&x, &b, &mut half, Some(parity));
                for i in (parity..nt).step_by(2) {
                    let col = i * nz..(i + 1) * nz;
                    assert_eq!(
                        bits(&half[col.clone()]),
                        bits(&by_line[col]),
                        "{nt} x {nz}, five {five}, column {i}"
                    );
                }
            }
        }
    }
}

/// The V-cycle's restriction of a defect that is zero on the odd columns (after the zebra
/// sweep) gives the whole restriction's values bit for bit, whatever the odd columns hold
/// (it does not read them), for even and odd rings with Dirichlet and cavitated nodes.
#[test]
fn restriction_after_zebra_is_the_restriction() {
    let mut u = rng(0x51ed_270b_a3c9_4e17);
    for nt in [8, 11, 12, 15] {
        let nz = 7;
        let fmask: Vec<Work> = (0..nt * nz)
            .map(|k| {
                if k % nz == 0 || k % nz == nz - 1 || u() < 0.2 {
                    0.0
                } else {
                    1.0
                }
            })
            .collect();
        let mut cmask = Vec::new();
        coarse_mask(
            nt,
            nz,
            &fmask.iter().map(|&m| m as f64).collect::<Vec<_>>(),
            &mut cmask,
        );
        let cmask: Vec<Work> = cmask.iter().map(|&m| m as Work).collect();
        let nc = coarse_len(nt) * nz;
        let even: Vec<Work> = (0..nt * nz)
            .map(|k| {
                if (k / nz) % 2 == 0 {
                    (2.0 * u() - 1.0) as Work
                } else {
                    0.0
                }
            })
            .collect();
        let mut whole = vec![0.0; nc];
        restrict(nt, nz, &fmask, &cmask, &even, &mut whole);
        // Odd columns filled with garbage: not read.
        let garbage: Vec<Work> = even
            .iter()
            .enumerate()
            .map(|(k, &v)| if (k / nz) % 2 == 1 { Work::NAN } else { v })
            .collect();
        let mut after = vec![1.0; nc];
        restrict_after_zebra(nt, nz, &fmask, &cmask, &garbage, &mut after);
        let bits = |v: &[Work]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&after), bits(&whole), "n_theta = {nt}");
    }
}

/// R = Pᵀ exactly (P restricted to the active coarse columns), for even and odd rings, with
/// Dirichlet nodes scattered in; the weights are 0, ½ or 1 and no Dirichlet node is corrected.
#[test]
fn restriction_is_the_transpose_of_prolongation() {
    let mut u = rng(0x9e37_79b9_7f4a_7c15);
    for nt in [8, 11, 12, 15] {
        let nz = 5;
        let fmask: Vec<f64> = (0..nt * nz)
            .map(|k| {
                let j = k % nz;
                if j == 0 || j + 1 == nz || u() < 0.2 {
                    0.0
                } else {
                    1.0
                }
            })
            .collect();
        let (p, r) = dense_transfers(nt, nz, &fmask);
        let nc = coarse_len(nt) * nz;
        for f in 0..nt * nz {
            for c in 0..nc {
                assert_eq!(r[c][f], p[f][c], "n_θ {nt}: R[{c}][{f}] ≠ P[{f}][{c}]");
                assert!([0.0, 0.5, 1.0].contains(&p[f][c]), "weight {}", p[f][c]);
                if fmask[f] == 0.0 {
                    assert_eq!(p[f][c], 0.0, "a Dirichlet node must not be corrected");
                }
            }
        }
    }
}

/// Linear interpolation reproduces constant fields everywhere and linear fields in θ on every
/// interval of the coarse ring but the one that wraps around (where a linear function of θ is
/// not periodic), for even and odd n_θ (odd: non-uniform last interval).
#[test]
fn prolongation_is_exact_for_constant_and_linear_fields() {
    for nt in [12, 15] {
        let nz = 4;
        let fmask = vec![1.0; nt * nz];
        let nc = coarse_len(nt);
        // Coarse column I sits at fine column 2I.
        let constant = vec![2.5; nc * nz];
        let mut xf = vec![0.0; nt * nz];
        prolong_add(nt, nz, &fmask, &constant, &mut xf);
        assert!(xf.iter().all(|&v| v == 2.5), "n_θ {nt}: {xf:?}");
        let linear: Vec<f64> = (0..nc * nz)
            .map(|k| 0.3 + 1.7 * (2 * (k / nz)) as f64 - 0.2 * (k % nz) as f64)
            .collect();
        let mut xf = vec![0.0; nt * nz];
        prolong_add(nt, nz, &fmask, &linear, &mut xf);
        let last_interior = 2 * (nc - 1);
        for f in 0..=last_interior {
            for j in 0..nz {
                let want = 0.3 + 1.7 * f as f64 - 0.2 * j as f64;
                let got = xf[f * nz + j];
                assert!(
                    (got - want).abs() < 1e-13,
                    "n_θ {nt} ({f}, {j}): {got} vs {want}"
                );
            }
        }
    }
}

/// The Galerkin operator of the constant-coefficient five-point stencil
/// p = 2a + 2c, w = e = −a, s = n = −c with linear interpolation in θ is, in the interior,
///
/// ```text
///   [ −c/4      −3c/2     −c/4   ]      (a-part: the θ-Laplacian (a/2)[−1 2 −1];
///   [ (c−a)/2   a + 3c   (c−a)/2 ]       c-part: the θ-mass [¼ 3/2 ¼] ⊗ [−c 2c −c])
///   [ −c/4      −3c/2     −c/4   ]
/// ```
///
/// (worked out by hand from R A P; rows dz = +1, 0, −1; columns dθ = −1, 0, +1). Checked on an
/// even ring, with zero row sums as in the fine rows, and identity rows at the ends.
#[test]
fn galerkin_operator_of_the_five_point_laplacian() {
    let (nt, nz) = (12, 7);
    let (a, c) = (1.3, 4.1);
    let mut fine = Stencil9::default();
    fine.reset(nt, nz);
    let mut fmask = vec![0.0; nt * nz];
    for i in 0..nt {
        for j in 0..nz {
            let k = i * nz + j;
            if j == 0 || j + 1 == nz {
                fine.c[C][k] = 1.0;
                continue;
            }
            fmask[k] = 1.0;
            fine.c[C][k] = 2.0 * a + 2.0 * c;
            fine.c[W][k] = -a;
            fine.c[E][k] = -a;
            fine.c[S][k] = -c;
            fine.c[N][k] = -c;
        }
    }
    let mut cmask = Vec::new();
    coarse_mask(nt, nz, &fmask, &mut cmask);
    let mut coarse = Stencil9::default();
    galerkin(&fine, &fmask, &cmask, &mut coarse);
    let want = |di: isize, dj: isize| -> f64 {
        match (di, dj) {
            (0, 0) => a + 3.0 * c,
            (_, 0) => 0.5 * (c - a),
            (0, _) => -1.5 * c,
            _ => -0.25 * c,
        }
    };
    for ic in 0..coarse_len(nt) {
        for j in 2..nz - 2 {
            let k = ic * nz + j;
            let mut sum = 0.0;
            for di in -1..=1 {
                for dj in -1..=1 {
                    let got = coarse.c[at(di, dj)][k];
                    sum += got;
                    assert!(
                        (got - want(di, dj)).abs() < 1e-13,
                        "({ic}, {j}) offset ({di}, {dj}): {got} vs {}",
                        want(di, dj)
                    );
                }
            }
            assert!(sum.abs() < 1e-13, "row sum {sum}");
        }
        assert_eq!(coarse.c[C][ic * nz], 1.0);
        assert_eq!(coarse.c[C][ic * nz + nz - 1], 1.0);
    }
}

/// The Galerkin operator is R A P: checked entry by entry against the dense triple product on
/// an odd ring (non-uniform coarse ring) with scattered Dirichlet nodes and a random
/// nine-point fine stencil.
#[test]
fn galerkin_operator_equals_the_dense_triple_product() {
    let mut u = rng(0x2545_f491_4f6c_dd1d);
    let (nt, nz) = (11, 6);
    let n = nt * nz;
    let mut fine = Stencil9::default();
    fine.reset(nt, nz);
    let fmask: Vec<f64> = (0..n)
        .map(|k| {
            let j = k % nz;
            if j == 0 || j + 1 == nz || u() < 0.15 {
                0.0
            } else {
                1.0
            }
        })
        .collect();
    for k in 0..n {
        let j = k % nz;
        for di in -1isize..=1 {
            for dj in -1isize..=1 {
                let jj = j as isize + dj;
                if jj >= 0 && jj < nz as isize {
                    fine.c[at(di, dj)][k] = u() - 0.5;
                }
            }
        }
    }
    let mut dense = vec![vec![0.0; n]; n];
    for i in 0..nt {
        for j in 0..nz {
            let k = i * nz + j;
            for di in -1isize..=1 {
                for dj in -1isize..=1 {
                    let jj = j as isize + dj;
                    if jj >= 0 && jj < nz as isize {
                        dense[k][wrap(i, di, nt) * nz + jj as usize] += fine.c[at(di, dj)][k];
                    }
                }
            }
        }
    }
    let (p, r) = dense_transfers(nt, nz, &fmask);
    let mut cmask = Vec::new();
    coarse_mask(nt, nz, &fmask, &mut cmask);
    let mut coarse = Stencil9::default();
    galerkin(&fine, &fmask, &cmask, &mut coarse);
    let ncz = coarse_len(nt) * nz;
    let mut ap = vec![vec![0.0; ncz]; n];
    for f in 0..n {
        for g in 0..n {
            if dense[f][g] != 0.0 {
                for c in 0..ncz {
                    ap[f][c] += dense[f][g] * p[g][c];
                }
            }
        }
    }
    let nc = coarse_len(nt);
    for ic in 0..nc {
        for j in 0..nz {
            let kc = ic * nz + j;
            let mut row = vec![0.0; ncz];
            for f in 0..n {
                if r[kc][f] != 0.0 {
                    for c in 0..ncz {
                        row[c] += r[kc][f] * ap[f][c];
                    }
                }
            }
            if cmask[kc] == 0.0 {
                assert!(row.iter().all(|&v| v == 0.0));
                assert_eq!(coarse.c[C][kc], 1.0, "inactive coarse node: identity row");
                continue;
            }
            let mut got = vec![0.0; ncz];
            for di in -1isize..=1 {
                for dj in -1isize..=1 {
                    let jj = j as isize + dj;
                    if jj >= 0 && jj < nz as isize {
                        got[wrap(ic, di, nc) * nz + jj as usize] += coarse.c[at(di, dj)][kc];
                    }
                }
            }
            for c in 0..ncz {
                assert!(
                    (got[c] - row[c]).abs() < 1e-14,
                    "coarse row {kc} column {c}: {} vs R A P {}",
                    got[c],
                    row[c]
                );
            }
        }
    }
}

// ------------------------------------------------------------------ against the oracle

/// Multigrid-preconditioned FGMRES agrees with the sparse-LU oracle on random frozen-switch
/// systems of the real discretization: steady and time step, full film and cavitated (a random
/// cavity arc plus random single flipped nodes), random ε, even and odd n_θ (odd rings coarsen
/// into non-uniform coarse rings).
///
/// Tolerance: FGMRES stops at max|r| ≤ 1e-10 × flux scale (checked here again with the
/// stencil's own residual, independently of the solver's stopping test). The error is A⁻¹ r;
/// relative to max|ψ| it was measured at ≤ 3e-12 over these cases. The bound asked, 1e-8 of
/// max|ψ_LU|, leaves the margin of the conditioning of the stiff pressure block and still
/// fails for any solve that stalled or converged to something else.
#[test]
fn multigrid_krylov_matches_the_lu_oracle() {
    let mut u = rng(0x5851_f42d_4c95_7f2d);
    let grids = [(48, 9), (45, 11), (64, 13), (30, 7)];
    let mut cavitated_seen = 0;
    for case in 0..16 {
        let (nt, nz) = grids[case % grids.len()];
        let steady = case % 2 == 0;
        let cavitated = case % 4 >= 2;
        let e = 0.3 + 0.6 * u();
        let a = std::f64::consts::TAU * u();
        let eps = [e * a.cos(), e * a.sin()];
        let arc0 = std::f64::consts::TAU * u();
        let arc = 1.0 + 2.0 * u();
        let flips: Vec<f64> = (0..nt * nz).map(|_| u()).collect();
        let switch = move |grid: &Grid, k: usize| -> f64 {
            if !cavitated {
                return 1.0;
            }
            let th = (grid.theta(k / grid.n_z) - arc0).rem_euclid(std::f64::consts::TAU);
            // A cavity arc (every ring keeps full nodes outside it, so a steady system stays
            // nonsingular), with random single nodes flipped inside and out.
            let inside = th < arc;
            let flip = flips[k] < 0.05;
            if inside != flip { 0.0 } else { 1.0 }
        };
        let (s, st, g) = frozen_system(
            compressor(LinearSolver::MultigridKrylov, nt, nz),
            eps,
            (!steady).then_some(STEP * (0.5 + u())),
            &switch,
        );
        cavitated_seen += g.iter().filter(|&&v| v == 0.0).count();
        let (x, _) = solve_mg(&s.grid, &st, &g, 1e-10);
        let mut r = vec![0.0; s.grid.len()];
        let (rmax, scale) = st.residual(&s.grid, &x, &mut r);
        assert!(
            rmax <= 1e-10 * scale,
            "case {case}: residual {rmax:e} scale {scale:e}"
        );
        let mut y = vec![0.0; s.grid.len()];
        oracle::solve_lu(&s.grid, &st, &mut y).unwrap();
        let ymax = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = x
            .iter()
            .zip(&y)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            err <= 1e-8 * ymax,
            "case {case} ({nt} × {nz}, steady {steady}, cavitated {cavitated}): \
             max|x − x_LU| = {err:e}, max|x_LU| = {ymax:e}"
        );
    }
    assert!(
        cavitated_seen > 500,
        "the cases must cavitate: {cavitated_seen}"
    );
}

/// The hierarchy kept between frozen systems (`Multigrid::setup`): the same matrix keeps it as
/// is, a time step later (ε moved as by 1° of a whirl, the switch unchanged) keeps it stale and
/// still solves to the oracle's answer within a few iterations of a fresh hierarchy, a switched
/// node or a large change rebuilds it; a stale hierarchy that stops converging is rebuilt
/// inside the Krylov solve (a hierarchy of another film entirely, forced in, still gives the
/// oracle's answer).
#[test]
fn kept_hierarchy_is_reused_only_where_it_serves() {
    use super::super::adi::STALE_REBUILD_ITERATIONS;
    let half = |grid: &Grid, k: usize| diverging_half(grid, k);
    let params = || compressor(LinearSolver::MultigridKrylov, 60, 15);
    let (s, st0, g0) = frozen_system(params(), [0.0, -0.8], Some(STEP), &half);
    let grid = &s.grid;
    let mut mg = Multigrid::default();
    assert_eq!(mg.setup(grid, &st0, Some(&g0)).unwrap(), Hierarchy::Built);
    assert_eq!(
        mg.setup(grid, &st0, Some(&g0)).unwrap(),
        Hierarchy::Kept { stale: false }
    );
    // One degree of whirl later: ε rotated by 1°, the same switch.
    let a = (-90.0f64 + 1.0).to_radians();
    let (_, st1, _) = frozen_system(params(), [0.8 * a.cos(), 0.8 * a.sin()], Some(STEP), &half);
    assert_eq!(
        mg.setup(grid, &st1, Some(&g0)).unwrap(),
        Hierarchy::Kept { stale: true }
    );
    // One node switched: rebuilt.
    let mut g1 = g0.clone();
    let k = (0..grid.len())
        .find(|&k| grid.kind[k] == NodeKind::Unknown && g0[k] == 1.0)
        .unwrap();
    g1[k] = 0.0;
    assert_eq!(mg.setup(grid, &st0, Some(&g1)).unwrap(), Hierarchy::Built);
    // A matrix 40 % stiffer: rebuilt.
    let mut stiff = st0.clone();
    for v in [
        &mut stiff.p,
        &mut stiff.w,
        &mut stiff.e,
        &mut stiff.s,
        &mut stiff.n,
    ] {
        v.iter_mut().for_each(|a| *a *= 1.4);
    }
    assert_eq!(mg.setup(grid, &stiff, Some(&g1)).unwrap(), Hierarchy::Built);

    // Solves with a kept hierarchy: the oracle's answer, and about a fresh hierarchy's count.
    let solve_with = |ws: &mut adi::AdiWorkspace, st: &Stencil| {
        let (x, info) = krylov_from_dirichlet(grid, st, &g0, 1e-10, None, ws);
        let mut y = vec![0.0; grid.len()];
        oracle::solve_lu(grid, st, &mut y).unwrap();
        let ymax = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = x
            .iter()
            .zip(&y)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err <= 1e-8 * ymax, "max|x − x_LU| = {err:e} of {ymax:e}");
        info.iterations
    };
    let mut ws = adi::AdiWorkspace::default();
    let fresh0 = solve_with(&mut ws, &st0);
    let kept = solve_with(&mut ws, &st1);
    let fresh1 = solve_mg(grid, &st1, &g0, 1e-10).1;
    // Measured 7 / 7 / 7 at this size: a kept hierarchy may cost an iteration or two, not
    // the rebuild threshold.
    assert!(
        kept <= fresh1 + 2 && kept < STALE_REBUILD_ITERATIONS,
        "kept {kept}, fresh {fresh1} (first {fresh0})"
    );
    // A hierarchy of a different film (steady, centred more, another cavity) forced in as if
    // kept: the solve rebuilds it and still converges to the oracle.
    let (_, far, _) = frozen_system(params(), [0.3, 0.1], None, &|_, _| 1.0);
    let mut ws = adi::AdiWorkspace::default();
    ws.multigrid.rebuild(grid, &far, None).unwrap();
    ws.multigrid.planted = true;
    let forced = solve_with(&mut ws, &st1);
    println!("kept hierarchy: fresh {fresh0}, kept {kept}, fresh {fresh1}, forced {forced}");
    // Measured 19: the planted hierarchy runs out its 12 iterations (so the rebuild path ran),
    // then the fresh one converges in about its own count.
    assert!(
        forced > STALE_REBUILD_ITERATIONS && forced <= STALE_REBUILD_ITERATIONS + fresh1 + 2,
        "forced stale hierarchy: {forced} iterations"
    );
}

/// The reuse test's mask comparison (a loop without early exit) agrees with [`fine_mask`]
/// node by node, with and without a switch.
#[test]
fn same_mask_is_the_fine_mask_at_every_node() {
    let half = |grid: &Grid, k: usize| diverging_half(grid, k);
    let (s, _, g0) = frozen_system(
        compressor(LinearSolver::MultigridKrylov, 60, 15),
        [0.0, -0.8],
        Some(STEP),
        &half,
    );
    let grid = &s.grid;
    let n = grid.len();
    let with: Vec<f64> = (0..n).map(|k| fine_mask(grid, Some(&g0), k)).collect();
    let without: Vec<f64> = (0..n).map(|k| fine_mask(grid, None, k)).collect();
    assert!(same_mask(grid, Some(&g0), &with));
    assert!(same_mask(grid, None, &without));
    // The cavitated unknowns tell the two apart.
    assert_ne!(with, without);
    assert!(!same_mask(grid, None, &with));
    assert!(!same_mask(grid, Some(&g0), &without));
    // One node switched anywhere (the last full unknown: the loop must not stop early).
    let k = (0..n)
        .rev()
        .find(|&k| grid.kind[k] == NodeKind::Unknown && g0[k] == 1.0)
        .unwrap();
    let mut g1 = g0.clone();
    g1[k] = 0.0;
    assert!(!same_mask(grid, Some(&g1), &with));
}

/// The same answer as the oracle through the whole semismooth Newton solve (steady and a time
/// step, both cavitating): the multigrid film equals the LU film (same switch, pressures to
/// 1e-7 of p_max: both stop at a mass residual of 1e-10 of the flux scale).
#[test]
fn multigrid_film_matches_the_lu_film() {
    let mut films = Vec::new();
    for solver in [LinearSolver::MultigridKrylov, LinearSolver::SparseLu] {
        let mut s = ReynoldsSolver::new(compressor(solver, 60, 15)).unwrap();
        let steady = s.solve_steady([0.0, -0.8], &running()).unwrap();
        let state = s.initial_state([0.1, -0.6]);
        let input = StepInput {
            eccentricity_ratio: [0.12, -0.63],
            dt: STEP,
            conditions: running(),
        };
        let (step, _) = s.solve_step(&state, &input).unwrap();
        assert!(steady.cavitated_fraction > 0.1 && step.cavitated_fraction > 0.05);
        films.push((steady, step));
    }
    for (a, b) in [(&films[0].0, &films[1].0), (&films[0].1, &films[1].1)] {
        assert_eq!(a.switch, b.switch, "same cavity");
        let pmax = b.max_pressure;
        let dp = a
            .pressure
            .iter()
            .zip(b.pressure.iter())
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(dp <= 1e-7 * pmax, "max |Δp| {dp:e} of p_max {pmax:e}");
    }
}

// ------------------------------------------------------------------ grid independence

/// A switch pattern g(grid, node).
type SwitchFn = dyn Fn(&Grid, usize) -> f64;

/// Krylov iterations of one frozen solve (1e-10 from the Dirichlet start) on the three grids.
fn iterations_on_grids(dt: Option<f64>, switch: &dyn Fn(&Grid, usize) -> f64) -> [usize; 3] {
    [(60, 15), (120, 31), (240, 61)].map(|(nt, nz)| {
        let (s, st, g) = frozen_system(
            compressor(LinearSolver::MultigridKrylov, nt, nz),
            [0.0, -0.8],
            dt,
            switch,
        );
        solve_mg(&s.grid, &st, &g, 1e-10).1
    })
}

/// The cavity of the ε = (0, −0.8) film as a function of θ: the diverging half, from the
/// minimum film (θ = 270°) round to just before the groove (θ = 90°).
fn diverging_half(grid: &Grid, k: usize) -> f64 {
    let th = grid.theta(k / grid.n_z).to_degrees();
    if (85.0..=270.0).contains(&th) {
        1.0
    } else {
        0.0
    }
}

/// Krylov iterations per solve grow by at most 1.3× from 60 × 15 to 240 × 61 (16× the nodes;
/// the ADI preconditioner grows ~4×) for the same physical problem, ε = 0.8 with the feed
/// groove: the steady full film (the first Newton system of a steady solve), a 1° time step
/// with the full film, and a 1° time step with the film cavitated over the diverging half.
/// Measured 7 / 7 / 7, 7 / 7 / 8 and 7 / 7 / 7 (2026-11-28).
#[test]
fn krylov_iterations_do_not_grow_with_the_grid() {
    let cases: [(&str, Option<f64>, &SwitchFn); 3] = [
        ("steady, full film", None, &|_, _| 1.0),
        ("1° step, full film", Some(STEP), &|_, _| 1.0),
        ("1° step, cavitated", Some(STEP), &diverging_half),
    ];
    for (name, dt, switch) in cases {
        let it = iterations_on_grids(dt, switch);
        let hi = *it.iter().max().unwrap();
        assert!(
            it[0] > 0 && hi as f64 <= 1.3 * it[0] as f64,
            "{name}: iterations {it:?} on 60×15 / 120×31 / 240×61 grow more than 1.3×"
        );
    }
}

/// The frozen system of the steady ε = (0, −0.8) film at its converged cavity (solved by the
/// sparse-LU film first): a reformation front meets the feed groove's upstream edge across a
/// strip of 1, 2, 3 full columns on 60 × 15, 120 × 31, 240 × 61.
fn converged_steady_cavity(nt: usize, nz: usize) -> (ReynoldsSolver, Stencil, Vec<f64>) {
    let mut s = ReynoldsSolver::new(compressor(LinearSolver::SparseLu, nt, nz)).unwrap();
    let sol = s.solve_steady([0.0, -0.8], &running()).unwrap();
    let sw: Vec<f64> = s.grid.fold(&sol.switch.iter().copied().collect::<Vec<_>>());
    let system = frozen_system(
        compressor(LinearSolver::MultigridKrylov, nt, nz),
        [0.0, -0.8],
        None,
        &|_, k| sw[k],
    );
    assert!(system.2.contains(&0.0), "the steady film must cavitate");
    system
}

/// Issue 11 item 5 at the *converged* cavity of the real film: Krylov iterations per solve
/// within 1.3× from 60 × 15 to 240 × 61, for the steady film and a 1° time step. Measured
/// 7 / 7 / 7 and 7 / 7 / 8. Without the reformation-front coupling of the smoother and the
/// coarsening (module docs, "Reformation fronts") they were 7 / 9 / 12 and 7 / 8 / 9: the slow
/// mode sat on the full strip between a reformation front and the groove, whose boundary
/// condition at the front the coarse space saw as Dirichlet.
#[test]
fn krylov_iterations_at_the_converged_cavity_do_not_grow_with_the_grid() {
    let grids = [(60, 15), (120, 31), (240, 61)];
    let mut steady_it = [0usize; 3];
    let mut step_it = [0usize; 3];
    for (slot, (nt, nz)) in grids.into_iter().enumerate() {
        let (s, st, g) = converged_steady_cavity(nt, nz);
        steady_it[slot] = solve_mg(&s.grid, &st, &g, 1e-10).1;

        let mut s = ReynoldsSolver::new(compressor(LinearSolver::SparseLu, nt, nz)).unwrap();
        let state = s.initial_state([0.1, -0.6]);
        let input = StepInput {
            eccentricity_ratio: [0.12, -0.63],
            dt: STEP,
            conditions: running(),
        };
        let (step, _) = s.solve_step(&state, &input).unwrap();
        let sw: Vec<f64> = step.switch.iter().copied().collect();
        let (s, st, g) = frozen_system(
            compressor(LinearSolver::MultigridKrylov, nt, nz),
            [0.12, -0.63],
            Some(STEP),
            &|_, k| sw[k],
        );
        assert!(g.contains(&0.0), "the step must cavitate");
        step_it[slot] = solve_mg(&s.grid, &st, &g, 1e-10).1;
    }
    for (name, it) in [("steady", steady_it), ("1° step", step_it)] {
        assert!(
            it[0] > 0 && *it.iter().max().unwrap() as f64 <= 1.3 * it[0] as f64,
            "{name} at the converged cavity: iterations {it:?} on 60×15 / 120×31 / 240×61 \
             grow more than 1.3×"
        );
    }
}

/// The stationary V-cycle x ← x + M⁻¹(b − A x) at the converged steady cavity contracts the
/// error by ≤ 0.2 per cycle on every grid (the asymptotic rate, from 30 cycles of the error
/// equation from a random start). Measured 0.091 / 0.102 / 0.108 on 60 × 15 / 120 × 31 /
/// 240 × 61 — the full film's ≈ 0.1 (module docs, "Convergence"); without the reformation-front
/// coupling 0.091 / 0.53 / 0.55, with its dominant error on the strip between the front and the
/// groove.
#[test]
fn v_cycle_contraction_at_the_converged_cavity_is_grid_independent() {
    for (nt, nz) in [(60, 15), (120, 31), (240, 61)] {
        let (s, st, g) = converged_steady_cavity(nt, nz);
        let grid = &s.grid;
        let mut mg = Multigrid::default();
        mg.rebuild(grid, &st, Some(&g)).unwrap();
        let mut random = rng(7);
        let n = grid.len();
        let mut e: Vec<f64> = (0..n)
            .map(|k| {
                if grid.kind[k] == NodeKind::Unknown {
                    random() - 0.5
                } else {
                    0.0
                }
            })
            .collect();
        let (mut ae, mut z) = (vec![0.0; n], vec![0.0; n]);
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut rate = 0.0;
        for _ in 0..30 {
            let before = norm(&e);
            st.apply(grid, &e, &mut ae);
            mg.apply(&ae, &mut z).unwrap();
            for (e, z) in e.iter_mut().zip(&z) {
                *e -= z;
            }
            let after = norm(&e);
            rate = after / before;
            // Renormalized: the asymptotic mode stays far above the single-precision floor.
            e.iter_mut().for_each(|x| *x /= after);
        }
        assert!(
            rate <= 0.2,
            "{nt} × {nz}: stationary V-cycle contraction {rate:.3} per cycle at the converged \
             cavity"
        );
    }
}

/// The zebra sweep solves each attached cavitated node m with its full node k's axial line:
/// after the sweep of one half, row k has no defect, and row m none against its other
/// neighbours' values from before the sweep (its upstream neighbour may sit in a line of the
/// same half, solved at the same time: block Jacobi between the lines of a half, as without
/// attachments) — to the single precision of the cycle, from a random start and right-hand
/// side. A sweep that lagged m (the plain line smoother) leaves row m's defect at the size of
/// its β-sized coupling times the line's correction, and row k's at its Couette inflow times
/// m's correction.
#[test]
fn attached_cavitated_nodes_are_solved_with_their_axial_line() {
    let (s, st, g) = converged_steady_cavity(120, 31);
    let grid = &s.grid;
    let mut mg = Multigrid::default();
    mg.rebuild(grid, &st, Some(&g)).unwrap();
    let f = &mut mg.levels[0];
    let (nt, nz) = (f.a.nt, f.a.nz);
    let attached: usize = f.attached.iter().map(Vec::len).sum();
    assert!(
        attached >= nz / 2,
        "the steady film's reformation fronts must attach cavitated nodes ({attached})"
    );
    let mut random = rng(11);
    let unknown = |k: usize| grid.kind[k] == NodeKind::Unknown;
    for parity in 0..2 {
        for k in 0..nt * nz {
            let u = unknown(k);
            f.x[k] = if u { (random() - 0.5) as Work } else { 0.0 };
            f.b[k] = if u { (random() - 0.5) as Work } else { 0.0 };
        }
        let before: Vec<f64> = f.x.iter().map(|v| v.to_f64()).collect();
        f.axial_sweep(0, parity, false).unwrap();
        let after: Vec<f64> = f.x.iter().map(|v| v.to_f64()).collect();
        let b: Vec<f64> = f.b.iter().map(|v| v.to_f64()).collect();
        // Row k's defect in f64 of the f64 operator at x, against the row's size.
        let relative_defect = |k: usize, x: &[f64]| {
            let (i, j) = (k / nz, k % nz);
            let (mut sum, mut size) = (0.0, b[k].abs());
            for (o, di, dj) in [(C, 0, 0), (W, -1, 0), (E, 1, 0), (S, 0, -1), (N, 0, 1)] {
                let jj = j as isize + dj;
                if (0..nz as isize).contains(&jj) {
                    let v = f.a.c[o][k] * x[wrap(i, di, nt) * nz + jj as usize];
                    sum += v;
                    size += v.abs();
                }
            }
            (b[k] - sum).abs() / size
        };
        for at in &f.attached[parity] {
            let mut block = before.clone();
            for (i, v) in block.iter_mut().enumerate() {
                if i / nz == at.k / nz {
                    *v = after[i];
                }
            }
            block[at.m] = after[at.m];
            for (what, k, x) in [("line node", at.k, &after), ("attached node", at.m, &block)] {
                let d = relative_defect(k, x);
                assert!(
                    d <= 1e-4,
                    "half {parity}: {what} {k} keeps a relative defect {d:.2e} after its sweep"
                );
            }
        }
    }
}

/// `mg` is, bit for bit, the hierarchy rebuilt for `st` with switch `g`: every level's operator
/// and mask, their single-precision copies, and the V-cycle's answers to random right-hand
/// sides (which run through the line factors, the attachments and the coarsest LU).
fn assert_is_the_rebuilt_hierarchy(
    mg: &mut Multigrid,
    grid: &Grid,
    st: &Stencil,
    g: &[f64],
    random: &mut impl FnMut() -> f64,
) {
    let (nt, nz) = (grid.n_theta, grid.n_z);
    let mut fresh = Multigrid::default();
    fresh.rebuild(grid, st, Some(g)).unwrap();
    assert_eq!(mg.levels.len(), fresh.levels.len());
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let bits32 = |v: &[Work]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (l, (a, b)) in mg.levels.iter().zip(&fresh.levels).enumerate() {
        for o in 0..9 {
            assert!(
                bits(&a.a.c[o]) == bits(&b.a.c[o]),
                "{nt}: level {l} entry {o}"
            );
            assert!(
                bits32(&a.aw.c[o]) == bits32(&b.aw.c[o]),
                "{nt}: level {l} f32 entry {o}"
            );
        }
        assert!(bits(&a.mask) == bits(&b.mask), "{nt}: level {l} mask");
        assert!(
            bits32(&a.maskw) == bits32(&b.maskw),
            "{nt}: level {l} f32 mask"
        );
    }
    let unknown = |k: usize| grid.kind[k] == NodeKind::Unknown;
    for _ in 0..3 {
        let r: Vec<f64> = (0..grid.len())
            .map(|k| if unknown(k) { random() - 0.5 } else { 0.0 })
            .collect();
        let (mut za, mut zb) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
        mg.apply(&r, &mut za).unwrap();
        fresh.apply(&r, &mut zb).unwrap();
        assert!(
            bits(&za) == bits(&zb),
            "{nt} × {nz}: V-cycle answers differ"
        );
    }
}

/// The update in changed columns next to a reformation front: a change of the cavitated rows of
/// one column only (their diagonal, as a different time term gives), whose nodes are attached
/// to the full nodes of the next column. The attachments and the coarsening operator of that
/// neighbour read them (module docs, "Reformation fronts"), so the update must redo the
/// neighbour's line factors and Galerkin columns too: bit for bit the rebuilt hierarchy.
#[test]
fn a_hierarchy_updated_next_to_a_reformation_front_is_the_rebuilt_one() {
    let (s, st0, g) = converged_steady_cavity(120, 31);
    let grid = &s.grid;
    let nz = grid.n_z;
    let mut mg = Multigrid::default();
    mg.setup(grid, &st0, Some(&g)).unwrap();
    let columns: Vec<usize> = mg.levels[0]
        .attached
        .iter()
        .flatten()
        .map(|at| at.m / nz)
        .collect();
    assert!(
        !columns.is_empty(),
        "the steady film must have attached nodes"
    );
    let mut random = rng(5);
    for &column in columns.iter().take(2) {
        // The cavitated rows' couplings by more than the kept hierarchy's drift, their
        // diagonal by less (so that A[k,m] A[m,k] / A[m,m] changes).
        let mut st = st0.clone();
        for k in column * nz..(column + 1) * nz {
            if g[k] == 0.0 && grid.kind[k] == NodeKind::Unknown {
                st.p[k] *= 1.25;
                for v in [&mut st.w, &mut st.e, &mut st.s, &mut st.n] {
                    v[k] *= 1.5;
                }
            }
        }
        let changed = mg.changed_columns(grid, &st, Some(&g)).expect("an update");
        assert_eq!(
            changed.iter().filter(|&&c| c).count(),
            1,
            "only column {column} changed"
        );
        assert_eq!(mg.setup(grid, &st, Some(&g)).unwrap(), Hierarchy::Built);
        assert_is_the_rebuilt_hierarchy(&mut mg, grid, &st, &g, &mut random);
        // Back to the original system for the next column (an update again).
        assert_eq!(mg.setup(grid, &st0, Some(&g)).unwrap(), Hierarchy::Built);
    }
}

/// A hierarchy updated in the θ-columns where a few switches changed
/// ([`Multigrid::update_columns`], the Newton loop's case) is the hierarchy rebuilt from
/// scratch, bit for bit: every level's operator and mask, their single-precision copies, and
/// the V-cycle's answer for random right-hand sides (which runs through the line factors and
/// the coarsest LU). On an even and an odd ring (the odd one's coarse ring is non-uniform at
/// the seam), with switches flipped at the seam, at the groove's edge and in the middle, in a
/// time step and a steady film; and the update must have been taken, not a rebuild.
#[test]
fn a_hierarchy_updated_in_the_switched_columns_is_the_rebuilt_one() {
    let half = |grid: &Grid, k: usize| diverging_half(grid, k);
    for (nt, nz, dt) in [(120, 31, Some(STEP)), (75, 15, Some(STEP)), (60, 15, None)] {
        let (s, st0, g0) = frozen_system(
            compressor(LinearSolver::MultigridKrylov, nt, nz),
            [0.1, -0.8],
            dt,
            &half,
        );
        let grid = &s.grid;
        let mut mg = Multigrid::default();
        mg.setup(grid, &st0, Some(&g0)).unwrap();
        let unknown = |k: usize| grid.kind[k] == NodeKind::Unknown;
        // Flip sets: the seam (columns nt − 1 and 0), the middle, and three spread nodes (on
        // the solver's grid, the half grid of this symmetric bearing: `gz` rows).
        let gz = grid.n_z;
        let flips: [Vec<usize>; 3] = [
            vec![(nt - 1) * gz + gz / 2, gz / 3],
            vec![(nt / 2) * gz + gz / 2],
            vec![
                (nt / 4) * gz + 2,
                (nt / 4 + 1) * gz + 3,
                (3 * nt / 4) * gz + gz / 2,
            ],
        ];
        let mut g = g0.clone();
        let mut random = rng(nt as u64 * 7919 + nz as u64);
        for set in flips {
            for k in set.into_iter().filter(|&k| unknown(k)) {
                g[k] = 1.0 - g[k];
            }
            // The stencil of the new switch (what the Newton loop's re-assembly gives).
            let (_, st, _) = frozen_system(
                compressor(LinearSolver::MultigridKrylov, nt, nz),
                [0.1, -0.8],
                dt,
                &|_, k| g[k],
            );
            assert!(
                mg.changed_columns(grid, &st, Some(&g)).is_some(),
                "{nt} × {nz}: a few switched nodes must take the update"
            );
            assert_eq!(mg.setup(grid, &st, Some(&g)).unwrap(), Hierarchy::Built);
            assert_is_the_rebuilt_hierarchy(&mut mg, grid, &st, &g, &mut random);
        }
    }
}

/// The coarsest solve (banded LU in z-outer order, `CoarsestLu`) against an independent dense LU
/// of the same nine-point operator, whose columns come from the level's own defect (A e_k =
/// −defect(e_k, 0)), not from the banded assembly: random diagonally dominant stencils on the
/// rings the coarsening can end on (n_θ = 1 … 4, where n_θ ≤ 2 makes offsets meet in one
/// entry, and the default grid's 4 × 31). A wrong index map, band or wrap fails it.
#[test]
fn coarsest_banded_solve_matches_a_dense_lu() {
    let mut next = rng(7);
    for (nt, nz) in [(1, 3), (2, 4), (3, 5), (4, 6), (3, 31), (4, 31)] {
        let n = nt * nz;
        let mut a = Stencil9::default();
        a.reset(nt, nz);
        for (slot, c) in a.c.iter_mut().enumerate() {
            for v in c.iter_mut() {
                *v = if slot == C {
                    9.0 + next()
                } else {
                    2.0 * next() - 1.0
                };
            }
        }
        let mut dense = nalgebra::DMatrix::<f64>::zeros(n, n);
        let (zero, mut unit, mut y) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for k in 0..n {
            unit.fill(0.0);
            unit[k] = 1.0;
            a.defect(&unit, &zero, &mut y);
            for r in 0..n {
                dense[(r, k)] = -y[r];
            }
        }
        let b: Vec<f64> = (0..n).map(|_| 2.0 * next() - 1.0).collect();
        // The level's right-hand side is single precision: the reference solves the rounded one.
        let bw: Vec<Work> = b.iter().map(|&v| Work::from_f64(v)).collect();
        let reference = dense
            .lu()
            .solve(&nalgebra::DVector::from_iterator(
                n,
                bw.iter().map(|v| v.to_f64()),
            ))
            .expect("diagonally dominant");
        let mut mg = Multigrid::default();
        mg.levels.resize_with(1, MgLevel::default);
        mg.levels[0].a = a;
        mg.levels[0].b = bw;
        mg.levels[0].x = vec![0.0; n];
        mg.coarsest.factor(&mg.levels[0].a).unwrap();
        mg.solve_coarsest().unwrap();
        let scale = reference.amax();
        for k in 0..n {
            let got = mg.levels[0].x[k].to_f64();
            // The answer is rounded to single precision on the way out (relative 2⁻²⁴).
            assert!(
                (got - reference[k]).abs() <= 1e-7 * scale,
                "{nt} × {nz}: x[{k}] = {got} against the dense {}",
                reference[k]
            );
        }
    }
}

// ------------------------------------------------------------------ switch checks

/// The semismooth Newton's switch checks inside a Krylov solve (`adi::KrylovStop::
/// switch_check`, `mod.rs` module docs). On the 1° step of the ε = 0.8 film cavitated over
/// the diverging half, with the right-hand side of a chosen answer x*: when x* has the signs of
/// the frozen switch the checks only read the iterates — the checked solve is the unchecked one
/// (same count, same bits) and reaches the LU oracle's answer; when x* contradicts the switch
/// at a few full nodes the checked solve stops early, at an iterate within the first check
/// level whose switch differs from the frozen one, in fewer iterations than the full solve.
#[test]
fn a_switch_check_stops_only_a_solve_whose_switch_is_wrong() {
    let (s, st0, g) = frozen_system(
        compressor(LinearSolver::MultigridKrylov, 60, 15),
        [0.0, -0.8],
        Some(STEP),
        &diverging_half,
    );
    let grid = &s.grid;
    let n = grid.len();
    let unknown = |k: usize| grid.kind[k] == NodeKind::Unknown;
    // x*: the Dirichlet values where they are, elsewhere +1 … +2 on full and −0.2 … −0.7 on
    // cavitated nodes — or, with `contradict`, −0.5 on every 37th full node.
    let with_answer = |contradict: bool| {
        let mut next = rng(7);
        let answer: Vec<f64> = (0..n)
            .map(|k| match (unknown(k), g[k] == 1.0) {
                (false, _) => st0.rhs[k],
                (true, true) if contradict && k % 37 == 0 => -0.5,
                (true, true) => 1.0 + next(),
                (true, false) => -0.2 - 0.5 * next(),
            })
            .collect();
        let mut st = st0.clone();
        let mut rhs = vec![0.0; n];
        st.apply(grid, &answer, &mut rhs);
        st.rhs = rhs;
        (st, answer)
    };
    let solve = |st: &Stencil, check: Option<[f64; 2]>| {
        krylov_from_dirichlet(grid, st, &g, 1e-10, check, &mut Default::default())
    };
    let disagrees = |x: &[f64]| {
        (0..n)
            .filter(|&k| unknown(k) && (x[k] >= 0.0) != (g[k] == 1.0))
            .count()
    };
    let check = Some([1e-3, 1e-5]);

    let (st, answer) = with_answer(false);
    let (plain, plain_info) = solve(&st, None);
    let (checked, checked_info) = solve(&st, check);
    assert_eq!(checked_info.iterations, plain_info.iterations);
    assert!(
        checked
            .iter()
            .zip(&plain)
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
    assert!(checked_info.residual <= 1e-10 * checked_info.scale);
    let mut lu = vec![0.0; n];
    oracle::solve_lu(grid, &st, &mut lu).unwrap();
    let gap = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
    };
    let (oracle_err, solve_err) = (gap(&lu, &answer), gap(&checked, &lu));
    // The LU oracle reproduces x* to round-off (the right-hand side is x*'s). The solve's
    // tolerance bounds the mass residual against the flux scale; the β-sized pressure
    // couplings amplify it into ψ (measured: a residual of 4e-12 of the scale, an error of
    // 3.9e-8): allowed 1e4 × the tolerance.
    assert!(
        oracle_err <= 1e-12,
        "the LU answer misses x* by {oracle_err:e}"
    );
    assert!(
        solve_err <= 1e4 * 1e-10,
        "the checked solve misses the LU answer by {solve_err:e}"
    );
    assert_eq!(disagrees(&checked), 0);

    let (st, answer) = with_answer(true);
    let wrong = disagrees(&answer);
    assert!(wrong > 3, "x* contradicts the switch at {wrong} nodes");
    let (_, plain_info) = solve(&st, None);
    let (stopped, stopped_info) = solve(&st, check);
    assert!(
        stopped_info.iterations < plain_info.iterations,
        "stopped after {} of the full solve's {} iterations",
        stopped_info.iterations,
        plain_info.iterations
    );
    assert!(stopped_info.residual > 1e-10 * stopped_info.scale);
    assert!(stopped_info.residual <= 1e-3 * stopped_info.scale);
    assert!(disagrees(&stopped) > 0);
}

/// The AVX2 copies of the hierarchy set-up and of the Krylov solve (chosen at run time where
/// the CPU has AVX2) give the bits of the copies for any CPU: the same operations in the same
/// order on wider vectors, no fused multiply-add. (Where the CPU has no AVX2 both sides are
/// the generic copy.)
#[test]
fn avx2_copies_give_the_generic_bits() {
    let (s, st, g) = converged_steady_cavity(120, 31);
    let grid = &s.grid;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    // The set-up: both hierarchies applied to one vector by the same V-cycle.
    let mut dispatched = Multigrid::default();
    let mut generic = Multigrid::default();
    dispatched.setup(grid, &st, Some(&g)).unwrap();
    generic.setup_generic(grid, &st, Some(&g)).unwrap();
    let r: Vec<f64> = (0..grid.len())
        .map(|k| ((k * 7919) % 1000) as f64 / 1000.0 - 0.5)
        .collect();
    let (mut za, mut zg) = (vec![0.0; r.len()], vec![0.0; r.len()]);
    dispatched.apply(&r, &mut za).unwrap();
    generic.apply(&r, &mut zg).unwrap();
    assert_eq!(bits(&za), bits(&zg), "set-up copies differ");
    // The Krylov solve, each on a fresh workspace.
    let stop = adi::KrylovStop {
        tolerance: 1e-10,
        flux_scale: None,
        max_iterations: 400,
        switch_check: None,
    };
    let solve = |generic: bool| {
        let mut ws = adi::AdiWorkspace::default();
        let mut x = dirichlet_start(grid, &st);
        let pc = adi::Preconditioner::Multigrid;
        let info = if generic {
            adi::solve_krylov_generic(grid, &st, &mut x, stop, pc, Some(&g), &mut ws)
        } else {
            adi::solve_krylov(grid, &st, &mut x, stop, pc, Some(&g), &mut ws)
        }
        .unwrap();
        (x, info.iterations, info.residual.to_bits())
    };
    let (xa, ia, ra) = solve(false);
    let (xg, ig, rg) = solve(true);
    assert_eq!(
        (ia, ra),
        (ig, rg),
        "Krylov copies differ in count or residual"
    );
    assert_eq!(bits(&xa), bits(&xg), "Krylov copies differ");
}
