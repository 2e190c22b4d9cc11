//! The largest mechanical output power `P = F v_inf` of the drive, and the
//! load where it is delivered.
//!
//! The drive does work on the load while both push the same way: loads
//! between 0 and the stall force `F_s` (for a drive that moves forward,
//! `0 < F < F_s` and `v_inf > 0`; `P = 0` at both ends). Contract: `P` is
//! evaluated at 16 equally spaced loads inside `(0, F_s)` and compared with
//! every load already evaluated there; around the largest, Brent's
//! minimisation ([`argmin::solver::brent::BrentOpt`]: golden section and
//! parabolic steps within a bracket) of `-P` between its two neighbours
//! finds a maximum, to `1e-7` relative in the load. That is the largest
//! `P` if `P` has one hump between the neighbours of the best sample,
//! which the samples cannot prove but make likely. `P` is flat at its
//! maximum, so the power itself is found to far more digits than the load:
//! its error is that of `F v_inf`, `|F|` times the error estimate of
//! `v_inf`.

use super::CharacteristicError;
use super::evaluate::{Evaluation, Evaluator, Purpose, keep};
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::brent::BrentOpt;
use std::cell::RefCell;

/// Loads of the first look at `P`.
const GRID: usize = 16;

/// The largest output power.
#[derive(Debug, Clone, PartialEq)]
pub struct MaxPower {
    /// `P = F v_inf` there (W).
    pub power: f64,
    /// Its estimated absolute error (W): `|F|` times that of `v_inf`.
    pub error: Option<f64>,
    /// The evaluation at the load of the maximum.
    pub at: Evaluation,
    /// The loads evaluated on the grid (to be shown with the curve).
    pub grid: Vec<Evaluation>,
}

/// Relative tolerance of Brent's search for the load of the largest
/// power.
const LOAD_TOLERANCE: f64 = 1e-7;

impl MaxPower {
    /// Relative resolution of the load of the maximum, [`MaxPower::at`]:
    /// Brent's tolerance, or, where larger, the square root of the
    /// power's relative error, since near a maximum `P(F)` changes by
    /// `P'' dF^2 / 2` and values that close cannot be told apart (with the
    /// curvature scale `F^2 |P''| / P` of order one, as for the
    /// characteristic's near-parabolic `F v_inf(F)`).
    pub fn load_resolution(&self) -> f64 {
        let relative = self
            .error
            .filter(|_| self.power != 0.0)
            .map_or(0.0, |e| (e / self.power).abs());
        LOAD_TOLERANCE.max(relative.sqrt())
    }
}

/// `-F v_inf(F)`.
struct NegativePower<'a> {
    ev: &'a Evaluator,
    failure: &'a RefCell<Option<CharacteristicError>>,
}

impl CostFunction for NegativePower<'_> {
    type Param = f64;
    type Output = f64;

    fn cost(&self, load: &f64) -> Result<f64, argmin::core::Error> {
        let e = self
            .ev
            .at_in_solver(*load, Purpose::MaxPower, self.failure)?;
        match e.output_power() {
            Some(p) => Ok(-p),
            None => Err(keep(
                self.failure,
                CharacteristicError::NoSteadyState {
                    load: *load,
                    regime: e.regime,
                },
            )),
        }
    }
}

/// The largest `F v_inf` for loads between 0 and `stall_force` (module
/// docs); `None` if the drive has no stall force away from 0.
pub(super) fn find(
    ev: &Evaluator,
    stall_force: f64,
) -> Result<Option<MaxPower>, CharacteristicError> {
    if stall_force == 0.0 || !stall_force.is_finite() {
        return Ok(None);
    }
    let grid = (1..=GRID)
        .map(|j| {
            ev.at(
                stall_force * j as f64 / (GRID + 1) as f64,
                Purpose::MaxPower,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let s = stall_force.signum();
    let mut candidates: Vec<(f64, f64)> = ev
        .evaluations()
        .iter()
        .filter(|e| s * e.load > 0.0 && s * e.load < s * stall_force)
        .filter_map(|e| e.output_power().map(|p| (e.load, p)))
        .collect();
    candidates.push((0.0, 0.0));
    candidates.push((stall_force, 0.0));
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
    let best = (1..candidates.len() - 1)
        .max_by(|&i, &j| candidates[i].1.total_cmp(&candidates[j].1))
        .unwrap_or(0);
    let (a, b) = (
        candidates[best.saturating_sub(1)].0,
        candidates[(best + 1).min(candidates.len() - 1)].0,
    );
    let failure = RefCell::new(None);
    let cost = NegativePower {
        ev,
        failure: &failure,
    };
    let solver = BrentOpt::new(a, b).set_tolerance(LOAD_TOLERANCE, 0.0);
    let result = Executor::new(cost, solver)
        .configure(|state| state.max_iters(200))
        .run();
    if let Some(e) = failure.borrow_mut().take() {
        return Err(e);
    }
    let result = result.map_err(|e| CharacteristicError::Unexpected(e.to_string()))?;
    let mut load = result
        .state()
        .get_best_param()
        .copied()
        .unwrap_or(candidates[best].0);
    // The best evaluation seen, Brent's or a sample's.
    if candidates[best].1 > -result.state().get_best_cost() {
        load = candidates[best].0;
    }
    let at = ev.at(load, Purpose::MaxPower)?;
    Ok(Some(MaxPower {
        power: at.output_power().unwrap_or(0.0),
        error: at.error.map(|e| e * load.abs()),
        at,
        grid,
    }))
}
