//! The effective oil temperature of a bearing from a global heat balance (Raimondi & Boyd
//! 1958, DIN 31652-2 / ISO 7902-2 "heat dissipation by the lubricant"), iterated with any
//! solver that gives the power loss and the flows at a trial viscosity.
//!
//! # The balance
//!
//! ```text
//!            supply Q_s at T_in ──►┐                       ┌──► side leakage Q_s at T_out
//!                                  ▼                       │
//!   recirculated Q_r at T_out ──► groove ──► film (heated by (1 − χ) P̄) ──►┘
//!            ▲                                             │
//!            └─────────── oil carried past the groove ◄────┘
//! ```
//!
//! Over a load cycle (or in steady running) the film's content does not change, so the supply
//! equals the side leakage Q_s (cycle mean) and the oil leaving through the ends carries the
//! part (1 − χ) of the mean power loss P̄ that is not conducted away through the housing and
//! the shaft (χ, the heat-transfer share, a case parameter; DIN 31652-2 takes χ = 0 for
//! pressure-fed bearings):
//!
//! ```text
//!   (1 − χ) P̄ = ρ c_p Q_s (T_out − T_in)                                           (1)
//! ```
//!
//! The oil that crosses the leading edge of the feed groove from the film (Q_r, the
//! circumferential flow arriving at the groove, cycle mean) returns at T_out and mixes with
//! the supply, so the film is fed at the flow-weighted mean
//!
//! ```text
//!   T_1 = (Q_s T_in + Q_r T_out) / (Q_s + Q_r)                                       (2)
//! ```
//!
//! and the effective temperature is the mean of the film's inlet and outlet temperatures (DIN
//! 31652-2's T_eff = (T_en + T_ex)/2 with T_en = T_1; Q_r = 0 gives DIN's own convention):
//!
//! ```text
//!   T_eff = (T_1 + T_out) / 2 = T_in + (1 − χ) P̄ / (ρ c_p Q_s) · (1 + m) / 2,
//!   m = Q_r / (Q_s + Q_r)                                                            (3)
//! ```
//!
//! # The iteration
//!
//! The solver runs at μ = μ(T) and returns P̄, Q_s and Q_r; (3) gives T_bal(T). The effective
//! temperature is the root of r(T) = T_bal(T) − T. Because viscosity falls with temperature,
//! P̄/Q_s falls too, r is decreasing, and r(T_in) > 0 whenever the film dissipates: the root
//! is unique and bracketed from below by T_in. [`solve_heat_balance`] takes secant steps on
//! the logarithms, f(x) = ln(T_bal − T_in) − x with x = ln(T − T_in) (the rise is nearly
//! proportional to μ, so f is nearly linear in x where r is strongly convex in T), from the
//! caller's first guess and an optional slope, kept inside the bracket known so far by
//! bisection (safeguarded secant), until |r| ≤ the tolerance: a converged T_eff agrees with
//! its own balance to `tolerance` kelvin.

use thiserror::Error;

/// Parameters of the heat balance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatBalanceParams {
    /// T_in, the oil supply temperature (°C).
    pub supply_temperature: f64,
    /// ρ c_p of the oil (J/(m³ K)); DIN 31652-2 takes 1.8e6 for mineral oils.
    pub volumetric_heat_capacity: f64,
    /// χ, the share of the power loss conducted away through housing and shaft (0 … 1).
    pub heat_to_structure: f64,
    /// Tolerance on |T_bal(T) − T| (K).
    pub tolerance: f64,
    /// Solves allowed.
    pub max_iterations: usize,
}

impl Default for HeatBalanceParams {
    fn default() -> Self {
        Self {
            supply_temperature: 40.0,
            volumetric_heat_capacity: DIN_31652_VOLUMETRIC_HEAT_CAPACITY,
            heat_to_structure: 0.0,
            tolerance: 0.2,
            max_iterations: 12,
        }
    }
}

/// ρ c_p of mineral oils in DIN 31652-2 (J/(m³ K)).
pub const DIN_31652_VOLUMETRIC_HEAT_CAPACITY: f64 = 1.8e6;

/// What a solve at a trial temperature returns for the balance (cycle means).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatFlows {
    /// P̄, mean power loss of the film (W).
    pub power_loss: f64,
    /// Q_s, mean side leakage out of both ends (m³/s).
    pub side_leakage: f64,
    /// Q_r, mean flow of film oil arriving at the feed groove (m³/s); 0 when unknown.
    pub recirculated_flow: f64,
}

/// One solve of the iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatBalanceIterate {
    /// The trial effective temperature T (°C).
    pub temperature: f64,
    /// What the solve at μ(T) returned.
    pub flows: HeatFlows,
    /// The temperatures of the balance (3) for those flows.
    pub balance: BalanceTemperatures,
}

/// The temperatures of the balance for given flows: eqs. (1)–(3) of the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BalanceTemperatures {
    /// T_out, the temperature of the side leakage and of the recirculated oil (°C).
    pub outlet: f64,
    /// T_1, the film's inlet temperature after mixing (°C).
    pub film_inlet: f64,
    /// T_eff = (T_1 + T_out)/2 (°C).
    pub effective: f64,
}

/// The converged heat balance.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatBalanceInfo {
    /// T_eff (°C): the last trial temperature, within the tolerance of its own balance.
    pub effective_temperature: f64,
    /// The balance at T_eff (outlet and film-inlet temperatures).
    pub balance: BalanceTemperatures,
    /// The flows at T_eff.
    pub flows: HeatFlows,
    /// |T_bal − T| at T_eff (K).
    pub residual: f64,
    /// Every solve, in order (the last one is T_eff's).
    pub iterates: Vec<HeatBalanceIterate>,
}

/// Why the heat balance failed.
#[derive(Debug, Error)]
pub enum HeatBalanceError<E: std::error::Error + 'static> {
    /// A parameter is out of range.
    #[error("heat balance: {name} = {value} is out of range ({reason})")]
    InvalidParameter {
        /// Which.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The range.
        reason: &'static str,
    },
    /// The solve at a trial temperature failed.
    #[error("heat balance: the solve at T = {temperature:.2} °C (iteration {iteration}) failed")]
    Solve {
        /// Iteration (1-based).
        iteration: usize,
        /// Trial temperature (°C).
        temperature: f64,
        /// The solver's error.
        #[source]
        source: E,
    },
    /// The flows of a solve are unusable (no side leakage, negative or non-finite power).
    #[error(
        "heat balance: at T = {temperature:.2} °C the film gives power loss {power_loss:.4e} W \
         and side leakage {side_leakage:.4e} m³/s: no oil flow carries the heat away"
    )]
    NoOilFlow {
        /// Trial temperature (°C).
        temperature: f64,
        /// P̄ (W).
        power_loss: f64,
        /// Q_s (m³/s).
        side_leakage: f64,
    },
    /// The iteration limit was reached.
    #[error(
        "heat balance not converged after {iterations} solves: T = {temperature:.3} °C, \
         |T_bal − T| = {residual:.3e} K > {tolerance:.1e} K"
    )]
    NotConverged {
        /// Solves made.
        iterations: usize,
        /// Last trial temperature (°C).
        temperature: f64,
        /// Its |T_bal − T| (K).
        residual: f64,
        /// The tolerance (K).
        tolerance: f64,
    },
}

impl HeatBalanceParams {
    /// Eqs. (1)–(3) for the flows `flows`; `None` when the flows cannot carry heat (Q_s ≤ 0,
    /// P̄ < 0 or a non-finite value).
    pub fn balance(&self, flows: &HeatFlows) -> Option<BalanceTemperatures> {
        let HeatFlows {
            power_loss,
            side_leakage,
            recirculated_flow,
        } = *flows;
        let usable = side_leakage > 0.0
            && side_leakage.is_finite()
            && power_loss >= 0.0
            && power_loss.is_finite()
            && recirculated_flow.is_finite();
        if !usable {
            return None;
        }
        let rise = (1.0 - self.heat_to_structure) * power_loss
            / (self.volumetric_heat_capacity * side_leakage);
        let q_r = recirculated_flow.max(0.0);
        let outlet = self.supply_temperature + rise;
        let film_inlet =
            (side_leakage * self.supply_temperature + q_r * outlet) / (side_leakage + q_r);
        Some(BalanceTemperatures {
            outlet,
            film_inlet,
            effective: 0.5 * (film_inlet + outlet),
        })
    }

    fn validate<E: std::error::Error>(&self) -> Result<(), HeatBalanceError<E>> {
        let bad = |name, value, reason| {
            Err(HeatBalanceError::InvalidParameter {
                name,
                value,
                reason,
            })
        };
        if !self.supply_temperature.is_finite() {
            return bad("supply_temperature", self.supply_temperature, "finite");
        }
        if !(self.volumetric_heat_capacity > 0.0 && self.volumetric_heat_capacity.is_finite()) {
            return bad(
                "volumetric_heat_capacity",
                self.volumetric_heat_capacity,
                "positive",
            );
        }
        if !(0.0..1.0).contains(&self.heat_to_structure) {
            return bad("heat_to_structure", self.heat_to_structure, "0 ≤ χ < 1");
        }
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return bad("tolerance", self.tolerance, "positive");
        }
        if self.max_iterations < 2 {
            return bad("max_iterations", self.max_iterations as f64, "at least 2");
        }
        Ok(())
    }
}

/// Iterate `solve` (which runs the film at the effective temperature T, °C, and returns its
/// result and cycle-mean flows) to the heat balance; see the module docs. `first_guess` is
/// the first trial temperature (raised to T_in if below it) and `slope`, if known, an estimate
/// of dr/dT (for instance from a cheaper model's iteration) for the first secant step.
///
/// Returns the result of the last solve (at T_eff) and the iteration record.
///
/// ```
/// use jbearing_solvers::heat_balance::{HeatBalanceParams, HeatFlows, solve_heat_balance};
///
/// // A film whose power loss falls as it warms (μ halves every 20 K); fixed side leakage.
/// let params = HeatBalanceParams { supply_temperature: 40.0, ..Default::default() };
/// let film = |t: f64| -> Result<(f64, HeatFlows), std::convert::Infallible> {
///     let power = 400.0 * 0.5f64.powf((t - 40.0) / 20.0);
///     Ok((power, HeatFlows { power_loss: power, side_leakage: 2e-5, recirculated_flow: 0.0 }))
/// };
/// let (power, info) = solve_heat_balance(&params, 50.0, None, film)?;
/// // At the answer the oil carries the heat: P = ρc_p Q (T_out − T_in), T_eff = (T_in + T_out)/2.
/// let t_out = 40.0 + power / (params.volumetric_heat_capacity * 2e-5);
/// assert!((info.effective_temperature - 0.5 * (40.0 + t_out)).abs() <= params.tolerance);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_heat_balance<R, E, S>(
    params: &HeatBalanceParams,
    first_guess: f64,
    slope: Option<f64>,
    mut solve: S,
) -> Result<(R, HeatBalanceInfo), HeatBalanceError<E>>
where
    E: std::error::Error + 'static,
    S: FnMut(f64) -> Result<(R, HeatFlows), E>,
{
    params.validate()?;
    let t_in = params.supply_temperature;
    let mut iterates: Vec<HeatBalanceIterate> = Vec::new();
    // The secant works on x = ln(T − T_in) and f(x) = ln(T_bal − T_in) − x: the rise
    // T_bal − T_in is nearly proportional to μ(T), whose logarithm is smooth and mildly curved
    // in ln(T − T_in), so f is close to linear where r(T) is strongly convex (a cold start
    // can put T_bal hundreds of kelvin away). f decreases; its root is T_eff.
    let floor = 1e-3 * params.tolerance;
    let x_of = |t: f64| (t - t_in).max(floor).ln();
    // Bracket in x: f(lo) > 0, f(hi) < 0 once found.
    let mut lo = f64::NEG_INFINITY;
    let mut hi = f64::INFINITY;
    let mut t = if first_guess.is_finite() {
        first_guess.max(t_in + params.tolerance)
    } else {
        t_in + 10.0
    };
    let mut last_point: Option<(f64, f64)> = None;
    for iteration in 1..=params.max_iterations {
        let (result, flows, balance) = balance_at(params, &mut solve, iteration, t)?;
        let r = balance.effective - t;
        iterates.push(HeatBalanceIterate {
            temperature: t,
            flows,
            balance,
        });
        if r.abs() <= params.tolerance {
            return Ok((
                result,
                HeatBalanceInfo {
                    effective_temperature: t,
                    balance,
                    flows,
                    residual: r.abs(),
                    iterates,
                },
            ));
        }
        let x = x_of(t);
        let f = x_of(balance.effective) - x;
        if f > 0.0 {
            lo = lo.max(x);
        } else {
            hi = hi.min(x);
        }
        // The caller's dr/dT as df/dx = (T − T_in)(r' + 1)/(T_bal − T_in) − 1 (no secant yet).
        let first_slope = slope
            .filter(|s| s.is_finite())
            .map(|s| (t - t_in) * (s + 1.0) / (balance.effective - t_in).max(floor) - 1.0);
        let next = secant_step((x, f), last_point, first_slope, (lo, hi));
        last_point = Some((x, f));
        t = t_in + next.exp();
    }
    let last = iterates.last().expect("at least two iterations");
    Err(HeatBalanceError::NotConverged {
        iterations: iterates.len(),
        temperature: last.temperature,
        residual: (last.balance.effective - last.temperature).abs(),
        tolerance: params.tolerance,
    })
}

/// One trial of [`solve_heat_balance`]: the film at T (its result and flows) and the balance
/// temperatures (1)–(3) of its flows.
fn balance_at<R, E, S>(
    params: &HeatBalanceParams,
    solve: &mut S,
    iteration: usize,
    t: f64,
) -> Result<(R, HeatFlows, BalanceTemperatures), HeatBalanceError<E>>
where
    E: std::error::Error + 'static,
    S: FnMut(f64) -> Result<(R, HeatFlows), E>,
{
    let (result, flows) = solve(t).map_err(|source| HeatBalanceError::Solve {
        iteration,
        temperature: t,
        source,
    })?;
    let balance = params.balance(&flows).ok_or(HeatBalanceError::NoOilFlow {
        temperature: t,
        power_loss: flows.power_loss,
        side_leakage: flows.side_leakage,
    })?;
    Ok((result, flows, balance))
}

/// The safeguarded secant step of [`solve_heat_balance`] (module docs, "The iteration"): the
/// next x = ln(T − T_in) from the iterate (x, f), with the slope df/dx of the secant through
/// the previous iterate, else the caller's `first_slope`, else −2 (a rise inversely
/// proportional to T − T_in); kept inside the bracket (lo, hi) in x by bisecting when both
/// ends are known, else moving at most a factor e² in T − T_in past the known end.
fn secant_step(
    (x, f): (f64, f64),
    last_point: Option<(f64, f64)>,
    first_slope: Option<f64>,
    (lo, hi): (f64, f64),
) -> f64 {
    let secant = match last_point {
        Some((xa, fa)) if x != xa => (f - fa) / (x - xa),
        _ => first_slope.unwrap_or(-2.0),
    };
    let secant = if secant < 0.0 && secant.is_finite() {
        secant
    } else {
        -2.0
    };
    let next = x - f / secant;
    if next > lo && next < hi {
        return next;
    }
    match (lo.is_finite(), hi.is_finite()) {
        (true, true) => 0.5 * (lo + hi),
        (true, false) => lo + 2.0,
        (false, true) => hi - 2.0,
        (false, false) => x,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viscosity::IsoViscosityGrade;

    #[derive(Debug, Error)]
    #[error("never")]
    struct Never;

    /// A film whose power loss is Petroff's, P = μ (ωR)² (2π R L)/c, and whose side leakage
    /// does not depend on μ (a pressure-fed bearing): the balance is a scalar equation in T
    /// whose root bisection finds independently.
    fn petroff(t: f64) -> HeatFlows {
        let mu = IsoViscosityGrade::Vg68.vogel().viscosity(t);
        let (r, l, c, omega): (f64, f64, f64, f64) = (0.05, 0.04, 50e-6, 300.0);
        HeatFlows {
            power_loss: mu * (omega * r).powi(2) * std::f64::consts::TAU * r * l / c,
            side_leakage: 2e-6,
            recirculated_flow: 1e-6,
        }
    }

    #[test]
    fn converges_to_the_root_of_the_scalar_balance() {
        let params = HeatBalanceParams {
            supply_temperature: 45.0,
            tolerance: 1e-3,
            ..Default::default()
        };
        // From the application's default start, T_in + 10 K.
        let (_, info) =
            solve_heat_balance::<(), Never, _>(&params, 55.0, None, |t| Ok(((), petroff(t))))
                .unwrap();
        // Independent: bisection on r(T) = T_bal(T) − T over [T_in, 300 °C].
        let r = |t: f64| params.balance(&petroff(t)).unwrap().effective - t;
        let (mut a, mut b) = (45.0, 300.0);
        for _ in 0..100 {
            let m = 0.5 * (a + b);
            if r(m) > 0.0 { a = m } else { b = m }
        }
        assert!(
            (info.effective_temperature - a).abs() < 2e-3,
            "{} vs {a}",
            info.effective_temperature
        );
        let trace: Vec<_> = info
            .iterates
            .iter()
            .map(|i| (i.temperature, i.balance.effective))
            .collect();
        assert!(
            info.iterates.len() <= 6,
            "{} solves: {trace:?}",
            info.iterates.len()
        );
        // From T_in itself (the rise is 480 K there): slower, still converged.
        let (_, cold) =
            solve_heat_balance::<(), Never, _>(&params, 45.0, None, |t| Ok(((), petroff(t))))
                .unwrap();
        assert!((cold.effective_temperature - a).abs() < 2e-3);
        // Energy: the leakage carries the power at T_out; T_eff between T_1 and T_out.
        let b = info.balance;
        let p = info.flows.power_loss;
        assert!(
            (params.volumetric_heat_capacity * 2e-6 * (b.outlet - 45.0) / p - 1.0).abs() < 1e-12
        );
        // m = 1/3: T_1 = T_in + ΔT/3.
        assert!(((b.film_inlet - 45.0) / (b.outlet - 45.0) - 1.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn heat_to_the_structure_cools_the_film() {
        let run = |chi: f64| {
            let params = HeatBalanceParams {
                supply_temperature: 45.0,
                heat_to_structure: chi,
                ..Default::default()
            };
            solve_heat_balance::<(), Never, _>(&params, 60.0, None, |t| Ok(((), petroff(t))))
                .unwrap()
                .1
                .effective_temperature
        };
        assert!(run(0.5) < run(0.0) - 1.0);
    }

    #[test]
    fn no_leakage_is_an_error_not_a_nan() {
        let err =
            solve_heat_balance::<(), Never, _>(&HeatBalanceParams::default(), 50.0, None, |_| {
                Ok((
                    (),
                    HeatFlows {
                        power_loss: 10.0,
                        side_leakage: 0.0,
                        recirculated_flow: 0.0,
                    },
                ))
            })
            .unwrap_err();
        assert!(matches!(err, HeatBalanceError::NoOilFlow { .. }), "{err}");
    }
}
