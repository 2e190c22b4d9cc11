//! Where the characteristic exists: the loads with a periodic steady
//! state, ended on each side by a run-away (docs/model.md section 9).
//!
//! **No steady state beyond the holding force.** For `F > mu_0 F_c`,
//! `g_t < -a_0`, and in every mode the slider's acceleration is below
//! `a_0 + g_t < 0`: forward slip `a_d + g_t <= a_0 + g_t`, backward slip
//! `-a_d + g_t`, stick `a_R <= a_0^+ = a_0 + g_t`. Its velocity falls by at
//! least `|a_0 + g_t| T` every period, so it runs away backwards; the same
//! holds forwards for `F < -mu_0 F_c`. The curve therefore lies within
//! `[-mu_0 F_c, mu_0 F_c]`; where exactly it ends (in practice near
//! `+-mu_d F_c`, where sliding friction can no longer hold the load) is
//! found by bisection ([`limit_between`]).
//!
//! **A run that does not converge ends the bisection.** A load whose run
//! did not establish the limit of the motion from rest within
//! `run.max_periods` (regime `not_converged`) may or may not have a steady
//! state, and every such run costs `run.max_periods` periods. Near a load
//! where the slider barely drifts (with `mu_dynamic = 0` the slider slips
//! without friction, and a load `F` changes its velocity by only `F T / m_s`
//! per period, so the loads nearest to 0 need ever more periods), halving
//! towards the steady load would meet one such run after another. So the
//! bisection stops at the first: the end is then the last steady load and
//! that load (regime `not_converged`), farther apart than the tolerance.
//!
//! [`boundary`]: bisection of a predicate that changes once along a
//! segment. Contract: given `inside` where the predicate holds and
//! `outside` where it does not, it returns the pair `(inside, outside)`
//! after halving their distance until it is at most `tol` (or the two are
//! adjacent doubles), keeping the predicate true at the first and false at
//! the second. If the predicate changes more than once on the segment it
//! finds one of the changes.

use super::CharacteristicError;
use super::evaluate::{Evaluation, Evaluator, Purpose};

/// One end of the curve: the last load with a steady state and the first
/// without, at most the tolerance apart; or, when the bisection met a run
/// that did not converge, the last steady load and that load, which may be
/// farther apart (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// The last load with a steady state (N): the end of the curve.
    pub last_steady: Evaluation,
    /// The first load without one (N).
    pub first_unsteady: Evaluation,
}

impl Limit {
    /// The load where the steady state ends (N): the end of the curve.
    pub fn load(&self) -> f64 {
        self.last_steady.load
    }

    /// Distance between the last steady and the first unsteady load (N).
    pub fn width(&self) -> f64 {
        (self.first_unsteady.load - self.last_steady.load).abs()
    }
}

/// Bisection of `holds` between `inside` (true) and `outside` (false) down
/// to `tol` (module docs).
pub(super) fn boundary<E>(
    mut inside: f64,
    mut outside: f64,
    tol: f64,
    mut holds: impl FnMut(f64) -> Result<bool, E>,
) -> Result<(f64, f64), E> {
    while (outside - inside).abs() > tol {
        let mid = 0.5 * (inside + outside);
        if mid == inside || mid == outside {
            break;
        }
        if holds(mid)? {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    Ok((inside, outside))
}

/// The end of the curve between a steady evaluation and an unsteady one:
/// bisection as [`boundary`] to within `tol` (N), except that it stops at
/// the first load whose run did not converge (module docs).
pub(super) fn limit_between(
    evaluator: &Evaluator,
    steady: Evaluation,
    unsteady: Evaluation,
    tol: f64,
) -> Result<Limit, CharacteristicError> {
    let (mut inside, mut outside) = (steady, unsteady);
    while (outside.load - inside.load).abs() > tol && !outside.is_unsettled() {
        let mid = 0.5 * (inside.load + outside.load);
        if mid == inside.load || mid == outside.load {
            break;
        }
        let e = evaluator.at(mid, Purpose::RunAway)?;
        if e.is_steady() {
            inside = e;
        } else {
            outside = e;
        }
    }
    Ok(Limit {
        last_steady: inside,
        first_unsteady: outside,
    })
}
