//! The stall force and the band of loads that hold the slider still
//! (docs/model.md section 9).
//!
//! `v_inf(F)` does not increase with the load: a slider pushed harder is
//! never ahead of one pushed less on the same rod (the comparison argument
//! of docs/model.md section 3, applied to `g_t`), so it changes sign once,
//! and the loads with `v_inf = 0` form one interval. Let `s` be the sign of
//! the no-load speed (the drive direction). The **stall force** is the
//! smallest load (in the drive direction, `s F`) at which `v_inf` is no
//! longer of sign `s` beyond its error estimate. It is one of:
//!
//! * `crossing`: `v_inf` passes through 0. Brent's method
//!   ([`argmin::solver::brent::BrentRoot`]: bisection, secant and inverse
//!   quadratic interpolation; it keeps a sign-changing bracket and never
//!   leaves it) runs on `s v_inf(F)` set to 0 where `|v_inf|` is within its
//!   error estimate, between the last load of the drive sign and the first
//!   that is not, on a grid of eighths of the holding force. It stops at a
//!   load where `v_inf` cannot be told from 0 (or when its bracket is a few
//!   units in the last place wide, which on a zone of noise wider than
//!   that cannot happen first). One more load `1e-10` relative towards the
//!   drive side shows `v_inf` of the drive sign there; then the stall
//!   force is the load Brent's method ended on, the bracket is those two
//!   loads, and `v_inf` at the stall force is within its error estimate.
//!   If that load is not of the drive sign (the zone is wider), the zone's
//!   edge is found by bisection to `1e-10` relative instead. A last load
//!   `1e-10` beyond shows the sign change;
//! * `held`: Brent's method ended on a load where the slider is held
//!   still (regime `stuck`: it follows the rod throughout, docs/model.md
//!   section 1, so `v_inf = 0` exactly), which happens over a band of
//!   loads. The stall force is the band's drive-side edge, the first load
//!   held; both edges are found by stepping out in eighths of the holding
//!   force and bisection ([`super::domain::boundary`]) to `1e-10`
//!   relative. (Just outside the band the slider slips for a moment per
//!   period and `v_inf` can be positive yet below its error estimate; the
//!   regime, decided by the event structure, marks the edge sharply.)
//! * `run-away`: `v_inf` keeps the drive sign up to the load at which the
//!   slider starts to run away backwards; that load (the last with a
//!   steady state) is the stall force;
//! * `no-drive`: `v_inf(0)` itself cannot be told from 0; the stall force
//!   is 0 (and the held band, if any, contains 0).

use super::CharacteristicError;
use super::domain::{Limit, boundary, limit_between};
use super::evaluate::{Evaluation, Evaluator, Purpose, keep};
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::brent::BrentRoot;
use std::cell::RefCell;

/// Relative precision of the stall force and of the held band's edges.
pub(super) const RELATIVE_TOLERANCE: f64 = 1e-10;

/// How the drive stalls (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StallKind {
    /// `v_inf` passes through 0.
    Crossing,
    /// The slider is held still from the stall force on.
    Held,
    /// The slider runs away before `v_inf` reaches 0.
    RunAway,
    /// No drive at zero load.
    NoDrive,
}

impl StallKind {
    /// The name in outputs: `crossing`, `held`, `run-away`, `no-drive`.
    pub fn name(self) -> &'static str {
        match self {
            StallKind::Crossing => "crossing",
            StallKind::Held => "held",
            StallKind::RunAway => "run-away",
            StallKind::NoDrive => "no-drive",
        }
    }
}

/// The stall force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stall {
    /// The stall force (N), signed like the load (positive for a drive
    /// that moves forward).
    pub force: f64,
    /// How the drive stalls.
    pub kind: StallKind,
    /// Loads enclosing it (N): the last evaluated with `v_inf` of the
    /// drive sign, and the first without (opposite sign, held, or no
    /// steady state).
    pub bracket: (f64, f64),
    /// The evaluation at [`Stall::force`].
    pub at: Evaluation,
}

impl Stall {
    /// Width of the bracket relative to the stall force.
    pub fn relative_width(&self) -> f64 {
        let w = (self.bracket.1 - self.bracket.0).abs();
        if self.force == 0.0 {
            w
        } else {
            w / self.force.abs()
        }
    }
}

/// The band of loads that hold the slider still (regime `stuck`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeldBand {
    /// Smallest load found held (N).
    pub lower: f64,
    /// Largest load found held (N).
    pub upper: f64,
    /// The largest load found not held below the band (N).
    pub below: f64,
    /// The smallest load found not held above the band (N).
    pub above: f64,
}

impl HeldBand {
    /// The edge on the side `side` (`-1` low loads, `1` high loads) as the
    /// pair (load not held, load held).
    pub(crate) fn edge(&self, side: f64) -> (f64, f64) {
        if side < 0.0 {
            (self.below, self.lower)
        } else {
            (self.above, self.upper)
        }
    }
}

/// Stall force, held band, and the end of the curve on the drive side if
/// it was needed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct StallResult {
    /// The stall force.
    pub stall: Stall,
    /// The held band, if any.
    pub band: Option<HeldBand>,
    /// The end of the curve on the drive side, when the search met it.
    pub limit: Option<Limit>,
}

/// Finds the stall force of a drive whose no-load evaluation is
/// `no_load` (module docs); `holding_force` is `mu_0 F_c`, `limit_tol` the
/// tolerance of a run-away limit (N).
pub(super) fn find(
    ev: &Evaluator,
    no_load: Evaluation,
    holding_force: f64,
    limit_tol: f64,
) -> Result<StallResult, CharacteristicError> {
    let grid = |k: usize, s: f64| s * holding_force * k as f64 / 8.0;
    let s = match no_load.sign() {
        Some(0) | None => return no_drive(ev, no_load, holding_force),
        Some(s) => f64::from(s),
    };
    let drives = |e: &Evaluation| e.sign() == Some(s as i8);
    let mut prev = no_load;
    for k in 1..=8 {
        let mut e = ev.at(grid(k, s), Purpose::Stall)?;
        let mut limit = None;
        if !e.is_steady() {
            let l = limit_between(ev, prev, e, limit_tol)?;
            if drives(&l.last_steady) {
                return Ok(StallResult {
                    stall: Stall {
                        force: l.last_steady.load,
                        kind: StallKind::RunAway,
                        bracket: (l.last_steady.load, l.first_unsteady.load),
                        at: l.last_steady,
                    },
                    band: None,
                    limit: Some(l),
                });
            }
            e = l.last_steady;
            limit = Some(l);
        }
        if drives(&e) {
            prev = e;
            continue;
        }
        let mut result = resolve(ev, s, prev, e, holding_force)?;
        result.limit = limit;
        return Ok(result);
    }
    Err(CharacteristicError::Unexpected(format!(
        "v_inf keeps its sign up to the holding force {holding_force} N, beyond which no steady state exists"
    )))
}

/// The stall between `prev` (drive sign) and `e` (not), by Brent's method
/// and, on a held band, by bisection.
fn resolve(
    ev: &Evaluator,
    s: f64,
    prev: Evaluation,
    e: Evaluation,
    holding_force: f64,
) -> Result<StallResult, CharacteristicError> {
    let star = brent(ev, s, prev.load, e.load)?;
    let star = ev.at(star, Purpose::Stall)?;
    let tol = RELATIVE_TOLERANCE * star.load.abs();
    if star.is_held() {
        // The drive-side edge of the band: the first load held.
        let band = band_around(ev, star, holding_force, tol)?;
        let (outside, inside) = band.edge(-s);
        return Ok(StallResult {
            stall: Stall {
                force: inside,
                kind: StallKind::Held,
                bracket: (outside, inside),
                at: ev.at(inside, Purpose::HeldBand)?,
            },
            band: Some(band),
            limit: None,
        });
    }
    // The drive-side end: a load of the drive sign within `tol` below the
    // load Brent's method ended on (normally inside the zone where `v_inf`
    // cannot be told from 0), or else the zone's edge by bisection.
    let drives =
        |f: f64| Ok::<_, CharacteristicError>(ev.at(f, Purpose::Stall)?.sign() == Some(s as i8));
    let (inside, outside) = if star.sign() == Some(s as i8) {
        boundary(star.load, e.load, tol, drives)?
    } else if drives(star.load - s * tol)? {
        (star.load - s * tol, star.load)
    } else {
        boundary(prev.load, star.load, tol, drives)?
    };
    // One load beyond, to show the sign change.
    ev.at(outside + s * tol, Purpose::Stall)?;
    Ok(StallResult {
        stall: Stall {
            force: outside,
            kind: StallKind::Crossing,
            bracket: (inside, outside),
            at: ev.at(outside, Purpose::Stall)?,
        },
        band: None,
        limit: None,
    })
}

/// `s v_inf(F)`, 0 where `v_inf` is within its error estimate.
struct SignedVelocity<'a> {
    ev: &'a Evaluator,
    s: f64,
    failure: &'a RefCell<Option<CharacteristicError>>,
}

impl CostFunction for SignedVelocity<'_> {
    type Param = f64;
    type Output = f64;

    fn cost(&self, load: &f64) -> Result<f64, argmin::core::Error> {
        let e = self.ev.at_in_solver(*load, Purpose::Stall, self.failure)?;
        match (e.sign(), e.v_inf) {
            (Some(0), _) => Ok(0.0),
            (_, Some(v)) => Ok(self.s * v),
            _ => Err(keep(
                self.failure,
                CharacteristicError::NoSteadyState {
                    load: *load,
                    regime: e.regime,
                },
            )),
        }
    }
}

/// Brent's method on [`SignedVelocity`] between `a` (positive) and `b`.
fn brent(ev: &Evaluator, s: f64, a: f64, b: f64) -> Result<f64, CharacteristicError> {
    let failure = RefCell::new(None);
    let cost = SignedVelocity {
        ev,
        s,
        failure: &failure,
    };
    let result = Executor::new(cost, BrentRoot::new(a, b, 0.0))
        .configure(|state| state.max_iters(200))
        .run();
    if let Some(e) = failure.borrow_mut().take() {
        return Err(e);
    }
    let result = result.map_err(|e| CharacteristicError::Unexpected(e.to_string()))?;
    result
        .state()
        .get_best_param()
        .copied()
        .ok_or_else(|| CharacteristicError::Unexpected("Brent's method returned no load".into()))
}

/// No drive at zero load: stall force 0, and the held band around 0 if
/// the slider is held there.
fn no_drive(
    ev: &Evaluator,
    no_load: Evaluation,
    holding_force: f64,
) -> Result<StallResult, CharacteristicError> {
    let band = if no_load.is_held() {
        Some(band_around(
            ev,
            no_load,
            holding_force,
            RELATIVE_TOLERANCE * holding_force,
        )?)
    } else {
        None
    };
    Ok(StallResult {
        stall: Stall {
            force: 0.0,
            kind: StallKind::NoDrive,
            bracket: (0.0, 0.0),
            at: no_load,
        },
        band,
        limit: None,
    })
}

/// Both edges of the held band containing the held load `held`: each found
/// by stepping out in eighths of the holding force to the first load not
/// held, then by bisection to `tol`.
fn band_around(
    ev: &Evaluator,
    held: Evaluation,
    holding_force: f64,
    tol: f64,
) -> Result<HeldBand, CharacteristicError> {
    let is_held = |f: f64| Ok::<_, CharacteristicError>(ev.at(f, Purpose::HeldBand)?.is_held());
    let mut edges = [(held.load, held.load); 2];
    for (edge, side) in edges.iter_mut().zip([-1.0, 1.0]) {
        let mut inside = held.load;
        for k in 1..=16 {
            let f = held.load + side * holding_force * k as f64 / 8.0;
            if is_held(f)? {
                inside = f;
                continue;
            }
            *edge = boundary(inside, f, tol, is_held)?;
            break;
        }
    }
    Ok(HeldBand {
        lower: edges[0].0,
        below: edges[0].1,
        upper: edges[1].0,
        above: edges[1].1,
    })
}
