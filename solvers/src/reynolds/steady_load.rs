//! Steady load → eccentricity: Newton on (ε_x, ε_y) for a constant load.
//!
//! ```text
//!   r(ε) = F_film(ε) + W = 0          (docs/conventions.md §1: the film balances the machine's load)
//!   J Δε = −r,   J_ab = ∂r_a/∂ε_b by forward differences (δ = 1e-6)
//! ```
//!
//! Start: |ε| = 0.5, 45° ahead of the load in the direction of U (between the short-bearing
//! attitude at high and low load). Steps are limited to |Δε| ≤ 0.25 and kept inside
//! |ε| ≤ 0.995, and halved (up to 8 times) while |r| does not decrease. Converged when
//! |r| ≤ 1e-8 |W|.

use super::{FilmSolution, OperatingConditions, ReynoldsError, ReynoldsSolver};

/// How the steady load solve went.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyLoadInfo {
    /// Journal position that carries the load.
    pub eccentricity_ratio: [f64; 2],
    /// Newton iterations.
    pub iterations: usize,
    /// |F_film + W| at the answer, N.
    pub force_residual: f64,
    /// Film solves used (including the finite-difference Jacobians).
    pub film_solves: usize,
}

const MAX_NEWTON: usize = 40;

pub(crate) fn solve(
    solver: &mut ReynoldsSolver,
    load: [f64; 2],
    conditions: &OperatingConditions,
) -> Result<(FilmSolution, SteadyLoadInfo), ReynoldsError> {
    solve_from(solver, load, conditions, None)
}

/// The Newton solve from `start` (None: the default start of the module docs). With a film
/// deformation set the |ε| ≤ 0.995 limit is lifted (the deformed film may carry the journal
/// beyond the clearance circle); a trial step that closes the film fails its solve and is
/// halved like any other.
pub(crate) fn solve_from(
    solver: &mut ReynoldsSolver,
    load: [f64; 2],
    conditions: &OperatingConditions,
    start: Option<[f64; 2]>,
) -> Result<(FilmSolution, SteadyLoadInfo), ReynoldsError> {
    let wmag = load[0].hypot(load[1]);
    if !(wmag > 0.0 && wmag.is_finite()) {
        return Err(ReynoldsError::InvalidParameter {
            name: "load",
            value: wmag,
            reason: "a steady load solve needs a non-zero finite load",
        });
    }
    let speed = conditions.journal_speed - conditions.bearing_speed;
    let dir = load[1].atan2(load[0]) + speed.signum() * std::f64::consts::FRAC_PI_4;
    let mut eps = start.unwrap_or([0.5 * dir.cos(), 0.5 * dir.sin()]);
    let rigid = solver.deformation().is_none();
    let mut solves = 0;
    let mut eval = |solver: &mut ReynoldsSolver, e: [f64; 2]| {
        solves += 1;
        solver.solve_steady(e, conditions).map(|s| {
            let r = [s.film_force[0] + load[0], s.film_force[1] + load[1]];
            (s, r)
        })
    };
    let (mut sol, mut r) = eval(solver, eps)?;
    let tol = 1e-8 * wmag;
    for it in 0..MAX_NEWTON {
        let rn = r[0].hypot(r[1]);
        if rn <= tol {
            let info = SteadyLoadInfo {
                eccentricity_ratio: eps,
                iterations: it,
                force_residual: rn,
                film_solves: solves,
            };
            return Ok((sol, info));
        }
        let not_converged = ReynoldsError::SteadyLoadNotConverged {
            iterations: it,
            force_residual: rn,
            eccentricity_ratio: eps,
        };
        let jac = jacobian(solver, &mut eval, eps, r)?;
        let Some(de) = newton_step(jac, r) else {
            return Err(not_converged);
        };
        match line_search(solver, &mut eval, eps, de, rn, rigid)? {
            Some((trial, s, rt)) => {
                eps = trial;
                sol = s;
                r = rt;
            }
            None => return Err(not_converged),
        }
    }
    Err(ReynoldsError::SteadyLoadNotConverged {
        iterations: MAX_NEWTON,
        force_residual: r[0].hypot(r[1]),
        eccentricity_ratio: eps,
    })
}

/// The residual r(ε) = F_film(ε) + W of one steady film solve, with the film.
type Residual = Result<(FilmSolution, [f64; 2]), ReynoldsError>;

/// J_ab = ∂r_a/∂ε_b at `eps` by forward differences (δ = 1e-6, backwards beyond |ε| = 0.99),
/// the module docs' second line.
fn jacobian(
    solver: &mut ReynoldsSolver,
    eval: &mut impl FnMut(&mut ReynoldsSolver, [f64; 2]) -> Residual,
    eps: [f64; 2],
    r: [f64; 2],
) -> Result<[[f64; 2]; 2], ReynoldsError> {
    let d = 1e-6;
    let mut jac = [[0.0; 2]; 2];
    for b in 0..2 {
        let mut e = eps;
        e[b] += if eps[0].hypot(eps[1]) > 0.99 { -d } else { d };
        let step = e[b] - eps[b];
        let (_, rb) = eval(solver, e)?;
        jac[0][b] = (rb[0] - r[0]) / step;
        jac[1][b] = (rb[1] - r[1]) / step;
    }
    Ok(jac)
}

/// The Newton step J Δε = −r, limited to |Δε| ≤ 0.25; None when J is singular.
fn newton_step(jac: [[f64; 2]; 2], r: [f64; 2]) -> Option<[f64; 2]> {
    let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
    if !(det.is_finite() && det != 0.0) {
        return None;
    }
    let mut de = [
        -(jac[1][1] * r[0] - jac[0][1] * r[1]) / det,
        -(-jac[1][0] * r[0] + jac[0][0] * r[1]) / det,
    ];
    let len = de[0].hypot(de[1]);
    if len > 0.25 {
        de = [de[0] * 0.25 / len, de[1] * 0.25 / len];
    }
    Some(de)
}

/// An accepted trial: ε, its film and its residual r(ε).
type Accepted = ([f64; 2], FilmSolution, [f64; 2]);

/// The step ε + λ Δε with λ halved (up to 8 times) until |r| falls below `rn`, kept inside
/// |ε| ≤ 0.995 when `rigid`: the accepted position, its film and residual, or None. A film
/// solve that fails is a rejected trial, unless λ is below 0.01 (its error is returned).
fn line_search(
    solver: &mut ReynoldsSolver,
    eval: &mut impl FnMut(&mut ReynoldsSolver, [f64; 2]) -> Residual,
    eps: [f64; 2],
    de: [f64; 2],
    rn: f64,
    rigid: bool,
) -> Result<Option<Accepted>, ReynoldsError> {
    let mut lambda = 1.0;
    for _ in 0..9 {
        let mut trial = [eps[0] + lambda * de[0], eps[1] + lambda * de[1]];
        let m = trial[0].hypot(trial[1]);
        if rigid && m > 0.995 {
            trial = [trial[0] * 0.995 / m, trial[1] * 0.995 / m];
        }
        match eval(solver, trial) {
            Ok((s, rt)) if rt[0].hypot(rt[1]) < rn => return Ok(Some((trial, s, rt))),
            Ok(_) => {}
            Err(e) if lambda < 0.01 => return Err(e),
            Err(_) => {}
        }
        lambda *= 0.5;
    }
    Ok(None)
}
