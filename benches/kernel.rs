//! Line-kernel benches (`kernel/…`): time per unknown of one periodic (circumferential) line.
//!
//! All benches solve the same matrix: a non-symmetric, diagonally dominant periodic tridiagonal
//! line of m unknowns (`bench_line`); the Dirichlet benches use the same rows without the two
//! corner entries. Every function id carries m as parameter and declares its number of unknowns
//! as criterion throughput, so `cargo bench-table` (validation/src/bin/bench_table.rs) turns the
//! medians into ns per unknown.
//!
//! - `kernel/modified_thomas/m`: Yu & Sawicki's modified Thomas, `cyclic_thomas_solve`.
//! - `kernel/plain_thomas/m`: Thomas on the Dirichlet line, `thomas_solve` (the floor).
//! - `kernel/sherman_morrison/m`: the textbook cyclic solve (Press et al., Numerical Recipes
//!   §2.7, `cyclic`): the corners go into a rank-one update, two Thomas solves (right-hand side
//!   and update vector) with the modified diagonal, then the Sherman–Morrison combination.
//! - `kernel/faer_sparse_lu/m`: faer sparse LU of the periodic matrix, symbolic analysis +
//!   numeric factorization + solve (assembly of the CSC matrix excluded).
//! - `kernel/faer_sparse_lu_reused_symbolic/m`: the same with the symbolic analysis done once
//!   outside the timed loop (numeric factorization + solve), as a time stepper would do.
//! - `kernel/nalgebra_dense_lu/m` (m ≤ 256): nalgebra dense LU with partial pivoting, factor +
//!   solve (the copy of the prebuilt dense matrix that the factorization consumes is included).
//! - `kernel/batched_32_lines/m`: 32 periodic lines stored interleaved, solved in one call by
//!   `cyclic_thomas_solve_interleaved` (vectorized across lines).
//! - `kernel/loop_32_lines/m`: the same 32 lines, each contiguous, solved one at a time by
//!   `cyclic_thomas_solve` in a loop (the baseline of the batched kernel).
//!
//! No bench allocates inside the timed loop except faer's and nalgebra's factorizations (their
//! APIs allocate the factors; that is part of their cost).
//!
//! ## Clock
//!
//! The group is timed in the CPU time of the benchmarking thread ([`ThreadCpuTime`],
//! `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`), not wall time: the project's machines are shared
//! (2 cores, several builds at once), and a descheduled thread inflates a wall-clock sample by
//! the time slices of other processes, which makes ratios between benches run minutes apart
//! meaningless. CPU time still includes the cache misses that other processes cause. Criterion's
//! warm-up and measurement times then count CPU seconds, so a run takes longer in wall time on a
//! loaded machine. Values are nanoseconds, as with wall time, so reports and `cargo bench-table`
//! read them the same way.
use criterion::measurement::{Measurement, ValueFormatter, WallTime};
use criterion::{BenchmarkId, Criterion, Throughput};
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Mat};
use jbearing_solvers::tridiagonal::{
    BatchWorkspace, InterleavedFactors, LineWorkspace, cyclic_thomas_solve,
    cyclic_thomas_solve_interleaved, thomas_solve,
};
use nalgebra::{DMatrix, DVector};
use std::hint::black_box;

/// Criterion measurement: CPU time of the calling thread, in nanoseconds (see the module docs).
pub struct ThreadCpuTime;

impl ThreadCpuTime {
    fn now_ns() -> u64 {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid, writable timespec; CLOCK_THREAD_CPUTIME_ID is supported by
        // every Linux kernel since 2.6.12.
        let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
        t.tv_sec as u64 * 1_000_000_000 + t.tv_nsec as u64
    }
}

impl Measurement for ThreadCpuTime {
    type Intermediate = u64;
    type Value = u64;

    fn start(&self) -> u64 {
        Self::now_ns()
    }
    fn end(&self, start: u64) -> u64 {
        Self::now_ns().saturating_sub(start)
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        // Nanoseconds, formatted like durations.
        WallTime.formatter()
    }
}

/// Line lengths of the issue (unknowns per line).
const SIZES: [usize; 5] = [16, 64, 256, 1024, 4096];
/// Lines of the batched benches.
const BATCH: usize = 32;

/// One line: sub-diagonal, diagonal, super-diagonal, right-hand side (storage convention of
/// `jbearing_solvers::tridiagonal`; `sub[0]`, `sup[m-1]` are the periodic corners).
struct Line {
    sub: Vec<f64>,
    diag: Vec<f64>,
    sup: Vec<f64>,
    rhs: Vec<f64>,
}

/// A non-symmetric, diagonally dominant periodic line; `seed` varies the coefficients between
/// the lines of a batch.
fn bench_line(m: usize, seed: usize) -> Line {
    let s = seed as f64;
    let sub: Vec<f64> = (0..m)
        .map(|i| -1.0 - 0.3 * (0.37 * i as f64 + s).sin())
        .collect();
    let sup: Vec<f64> = (0..m)
        .map(|i| -0.5 + 0.2 * (1.7 * i as f64 + 0.5 * s).cos())
        .collect();
    let diag = (0..m)
        .map(|i| 1.2 * (sub[i].abs() + sup[i].abs()) + 0.1 * (1.0 + (0.11 * i as f64).sin()))
        .collect();
    let rhs = (0..m).map(|i| (0.05 * i as f64 + s).cos() + 0.5).collect();
    Line {
        sub,
        diag,
        sup,
        rhs,
    }
}

/// (row, column, value) entries of the periodic matrix of `line` (m ≥ 3).
fn periodic_triplets(line: &Line) -> Vec<Triplet<usize, usize, f64>> {
    let m = line.diag.len();
    let mut t = Vec::with_capacity(3 * m);
    for i in 0..m {
        t.push(Triplet::new(i, i, line.diag[i]));
        t.push(Triplet::new(i, (i + m - 1) % m, line.sub[i]));
        t.push(Triplet::new(i, (i + 1) % m, line.sup[i]));
    }
    t
}

/// Scratch of the Sherman–Morrison solve, allocated once.
struct ShermanMorrison {
    diag: Vec<f64>,
    update: Vec<f64>,
    z: Vec<f64>,
    work: LineWorkspace,
}

impl ShermanMorrison {
    fn new(m: usize) -> Self {
        Self {
            diag: vec![0.0; m],
            update: vec![0.0; m],
            z: vec![0.0; m],
            work: LineWorkspace::with_len(m),
        }
    }

    /// Numerical Recipes `cyclic`: A = A' + u vᵀ with u = (γ, 0, …, 0, α)ᵀ,
    /// v = (1, 0, …, 0, β/γ)ᵀ, β = corner of row 0, α = corner of row m-1, γ = −d_0.
    fn solve(&mut self, line: &Line, x: &mut [f64]) {
        let m = line.diag.len();
        let (beta, alpha) = (line.sub[0], line.sup[m - 1]);
        let gamma = -line.diag[0];
        self.diag.copy_from_slice(&line.diag);
        self.diag[0] -= gamma;
        self.diag[m - 1] -= alpha * beta / gamma;
        thomas_solve(
            &line.sub,
            &self.diag,
            &line.sup,
            &line.rhs,
            x,
            &mut self.work,
        )
        .unwrap();
        self.update.fill(0.0);
        self.update[0] = gamma;
        self.update[m - 1] = alpha;
        thomas_solve(
            &line.sub,
            &self.diag,
            &line.sup,
            &self.update,
            &mut self.z,
            &mut self.work,
        )
        .unwrap();
        let fact =
            (x[0] + beta * x[m - 1] / gamma) / (1.0 + self.z[0] + beta * self.z[m - 1] / gamma);
        for (xi, zi) in x.iter_mut().zip(&self.z) {
            *xi -= fact * zi;
        }
    }
}

pub fn bench(c: &mut Criterion<ThreadCpuTime>) {
    // The kernels are sequential; compare faer sequential too.
    faer::set_global_parallelism(faer::Par::Seq);
    let mut group = c.benchmark_group("kernel");
    for m in SIZES {
        let line = bench_line(m, 0);
        let mut x = vec![0.0; m];
        let mut work = LineWorkspace::with_len(m);
        group.throughput(Throughput::Elements(m as u64));

        group.bench_with_input(BenchmarkId::new("modified_thomas", m), &m, |b, _| {
            b.iter(|| {
                cyclic_thomas_solve(
                    black_box(&line.sub),
                    black_box(&line.diag),
                    black_box(&line.sup),
                    black_box(&line.rhs),
                    &mut x,
                    &mut work,
                )
                .unwrap();
                black_box(&x);
            })
        });

        group.bench_with_input(BenchmarkId::new("plain_thomas", m), &m, |b, _| {
            b.iter(|| {
                thomas_solve(
                    black_box(&line.sub),
                    black_box(&line.diag),
                    black_box(&line.sup),
                    black_box(&line.rhs),
                    &mut x,
                    &mut work,
                )
                .unwrap();
                black_box(&x);
            })
        });

        let mut sm = ShermanMorrison::new(m);
        group.bench_with_input(BenchmarkId::new("sherman_morrison", m), &m, |b, _| {
            b.iter(|| {
                sm.solve(black_box(&line), &mut x);
                black_box(&x);
            })
        });

        let a = SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &periodic_triplets(&line))
            .unwrap();
        let mut rhs = Mat::<f64>::from_fn(m, 1, |i, _| line.rhs[i]);
        group.bench_with_input(BenchmarkId::new("faer_sparse_lu", m), &m, |b, _| {
            b.iter(|| {
                let lu = black_box(&a).sp_lu().unwrap();
                rhs.col_mut(0)
                    .iter_mut()
                    .zip(&line.rhs)
                    .for_each(|(r, c)| *r = *c);
                lu.solve_in_place_with_conj(Conj::No, rhs.as_mut());
                black_box(&rhs);
            })
        });

        let symbolic = SymbolicLu::try_new(a.symbolic()).unwrap();
        group.bench_with_input(
            BenchmarkId::new("faer_sparse_lu_reused_symbolic", m),
            &m,
            |b, _| {
                b.iter(|| {
                    let lu = Lu::try_new_with_symbolic(symbolic.clone(), black_box(&a).as_ref())
                        .unwrap();
                    rhs.col_mut(0)
                        .iter_mut()
                        .zip(&line.rhs)
                        .for_each(|(r, c)| *r = *c);
                    lu.solve_in_place_with_conj(Conj::No, rhs.as_mut());
                    black_box(&rhs);
                })
            },
        );

        if m <= 256 {
            let dense = DMatrix::<f64>::from_fn(m, m, |i, j| {
                let mut v = 0.0;
                if i == j {
                    v += line.diag[i];
                }
                if j == (i + m - 1) % m {
                    v += line.sub[i];
                }
                if j == (i + 1) % m {
                    v += line.sup[i];
                }
                v
            });
            let c = DVector::from_column_slice(&line.rhs);
            group.bench_with_input(BenchmarkId::new("nalgebra_dense_lu", m), &m, |b, _| {
                b.iter(|| {
                    let lu = black_box(&dense).clone().lu();
                    black_box(lu.solve(&c).unwrap());
                })
            });
        }

        // 32 lines: contiguous (line l at l·m) for the loop, interleaved (unknown i of line l at
        // i·32 + l) for the batched kernel.
        let lines: Vec<Line> = (0..BATCH).map(|l| bench_line(m, l + 1)).collect();
        let contiguous = |pick: fn(&Line) -> &Vec<f64>| -> Vec<f64> {
            lines.iter().flat_map(|l| pick(l).iter().copied()).collect()
        };
        let interleaved = |pick: fn(&Line) -> &Vec<f64>| -> Vec<f64> {
            (0..m * BATCH)
                .map(|k| pick(&lines[k % BATCH])[k / BATCH])
                .collect()
        };
        let picks: [fn(&Line) -> &Vec<f64>; 4] = [|l| &l.sub, |l| &l.diag, |l| &l.sup, |l| &l.rhs];
        let [cs, cd, ca, cc] = picks.map(contiguous);
        let [is, id, ia, ic] = picks.map(interleaved);
        let mut xs = vec![0.0; m * BATCH];
        let mut batch_work = BatchWorkspace::new(m, BATCH);
        group.throughput(Throughput::Elements((m * BATCH) as u64));

        group.bench_with_input(BenchmarkId::new("batched_32_lines", m), &m, |b, _| {
            b.iter(|| {
                cyclic_thomas_solve_interleaved(
                    m,
                    BATCH,
                    black_box(&is),
                    black_box(&id),
                    black_box(&ia),
                    black_box(&ic),
                    &mut xs,
                    &mut batch_work,
                )
                .unwrap();
                black_box(&xs);
            })
        });

        // The same 32 lines factored once outside the timed loop (InterleavedFactors): the
        // substitution phase alone, what each ADI sweep of a frozen system costs.
        let mut factors = InterleavedFactors::default();
        factors.factor_periodic(m, BATCH, &is, &id, &ia).unwrap();
        group.bench_with_input(BenchmarkId::new("factored_32_lines", m), &m, |b, _| {
            b.iter(|| {
                factors.solve(black_box(&ic), &mut xs).unwrap();
                black_box(&xs);
            })
        });

        group.bench_with_input(BenchmarkId::new("loop_32_lines", m), &m, |b, _| {
            b.iter(|| {
                for l in 0..BATCH {
                    let r = l * m..(l + 1) * m;
                    cyclic_thomas_solve(
                        black_box(&cs[r.clone()]),
                        black_box(&cd[r.clone()]),
                        black_box(&ca[r.clone()]),
                        black_box(&cc[r.clone()]),
                        &mut xs[r],
                        &mut work,
                    )
                    .unwrap();
                }
                black_box(&xs);
            })
        });
    }
    group.finish();
}
