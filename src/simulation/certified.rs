//! The certificates of a run (docs/model.md section 3, "The
//! certificate", and section 11): the steady state certified as the limit
//! of the motion from rest by the covering of
//! [`crate::analysis::certificate`]; the covering as a search where the
//! search from rest sees no fixed point (a fixed point in a narrow stick
//! band, or a run-away proven without the start-up); and the bracket of
//! `v_inf` across both outcomes of a grazing in the steady orbit.
//!
//! Contract: every function returns only what the covering proves; where
//! it proves nothing within [`CERTIFICATE_BUDGET`] map evaluations it
//! returns `None` (or [`Search::Nothing`]) and the orbit from rest decides.

use super::{CertificateKind, SteadyStateCertificate};
use crate::analysis::certificate::{CERTIFIED_REACH, Verdict, certify, certify_between};
use crate::analysis::error_estimate::established_bound;
use crate::analysis::{self, StatsWanted, SteadyState};
use crate::engine::{PeriodEngine, PeriodStart};
use crate::error::Error;
use crate::motor::Motor;
use crate::observer::Trajectory;

/// A certified steady state with the covering's bounds `(lo, hi)` on its
/// `v_inf` (m/s).
pub(super) type Certified = (SteadyState, (f64, f64));

/// Largest number of map evaluations a certificate may take before the
/// orbit from rest decides.
pub(super) const CERTIFICATE_BUDGET: u32 = 256;

/// The steady state reached from `from` (rest, or a point of the orbit from
/// rest), certified: the covering of `crate::analysis::certificate` from
/// `from` to the established fixed point `(steady, bound)`; where it finds
/// a nearer fixed point, that one is found in the bracket it gives, and
/// certified in turn. `None` when no certificate is found within
/// [`CERTIFICATE_BUDGET`] map evaluations or a nearer fixed point is not
/// established: then the orbit from rest decides. Records the cost and the
/// other fixed points found in `certificate`; returns the certified steady
/// state with the covering's bounds on its `v_inf`.
pub(super) fn certified_limit<E: PeriodEngine>(
    engine: &mut E,
    motor: &Motor,
    from: f64,
    (steady, bound): (SteadyState, f64),
    wanted: StatsWanted,
    trajectory: &mut Option<Trajectory>,
    certificate: &mut SteadyStateCertificate,
) -> Result<Option<Certified>, Error> {
    let (mut from, mut steady, mut bound) = (from, steady, bound);
    let mut rejected: Vec<f64> = Vec::new();
    let mut spent = 0;
    let earlier = certificate.evaluations;
    loop {
        let covering = certify(
            engine,
            motor,
            from,
            steady.boundary_velocity,
            bound,
            CERTIFICATE_BUDGET.saturating_sub(spent),
        )?;
        spent += covering.evaluations;
        certificate.evaluations = earlier + u64::from(spent);
        match covering.verdict {
            Verdict::Certified => {
                certificate.kind = CertificateKind::Covering;
                let v = steady.boundary_velocity;
                certificate.other_fixed_point = rejected
                    .iter()
                    .map(|w| (w - v).abs())
                    .min_by(f64::total_cmp);
                // At rest with a map that keeps it there, nothing bounds
                // v_inf but the steady state itself.
                let bounds = covering
                    .v_inf_bounds
                    .unwrap_or((steady.v_inf, steady.v_inf));
                return Ok(Some((steady, bounds)));
            }
            Verdict::Undecided | Verdict::Open { .. } => return Ok(None),
            Verdict::Nearer { near, far } => {
                if near == far || spent >= CERTIFICATE_BUDGET {
                    return Ok(None);
                }
                rejected.push(steady.boundary_velocity);
                let (lo, hi) = (near.min(far), near.max(far));
                let before = engine.counters().periods;
                // A fresh observation of the new steady period.
                *trajectory = trajectory.as_ref().map(|_| Trajectory::default());
                let next = steady_between(engine, (lo, hi), near, wanted, trajectory)?;
                spent += (engine.counters().periods - before) as u32;
                let Some(b) = established_bound(engine.signal(), &next) else {
                    return Ok(None);
                };
                (from, steady, bound) = (near, next, b);
            }
        }
    }
}

/// Reaches of [`bracketed_v_inf`], relative to `max |v_R|`.
const BRACKET_REACHES: [f64; 3] = [1e-10, 1e-8, 1e-6];

/// Bounds on the `v_inf` of the limit from rest where the steady orbit
/// `steady` (at `v*`) grazes: a zero of `v_rel` decided within the
/// engine's tolerance, through which the engine bounds no error
/// (docs/model.md section 11) and the map may jump (a stick phase that the
/// touch starts, or not). The covering from rest to `v* - r`
/// (`crate::analysis::certificate`), for the smallest reach `r` of
/// [`BRACKET_REACHES`] whose periods are decided, is closed by a point
/// the map moves back:
///
/// * `v* + r` where the map moves it back;
/// * where the map pushes `v* + r` on (the fixed point sits at the jump,
///   and a motion from rest that rounding carries past it settles on the
///   next fixed point), `v_2 + 2 b_2` beyond the next fixed point `v_2`
///   (with its bound `b_2`).
///
/// The steps of the two ends bound the limit's (a slider that starts
/// faster stays ahead): across the jump, and over both outcomes. `None`
/// if no reach is decided within the certificate's budget, or the covering
/// finds a nearer fixed point.
pub(super) fn bracketed_v_inf<E: PeriodEngine>(
    engine: &mut E,
    motor: &Motor,
    steady: &SteadyState,
    certificate: &mut SteadyStateCertificate,
) -> Result<Option<(f64, f64)>, Error> {
    let scale = engine.signal().velocity_scale();
    let v_star = steady.boundary_velocity;
    let mut spent = 0;
    for reach in BRACKET_REACHES {
        let r = reach * scale;
        let budget = CERTIFICATE_BUDGET.saturating_sub(spent);
        let mut covering = certify_between(engine, motor, 0.0, v_star, (r, r), budget)?;
        spent += covering.evaluations;
        if let Verdict::Open { .. } = covering.verdict {
            let s = v_star.signum();
            let before = engine.counters().periods;
            let next = analysis::fixed_point(engine, v_star + s * r).ok();
            spent += (engine.counters().periods - before) as u32;
            let Some(analysis::FixedPoint {
                velocity: v_2,
                map_derivative: d,
                iterations,
                last_correction: correction,
            }) = next.filter(|n| (n.velocity - v_star) * s > r)
            else {
                break;
            };
            let before = engine.counters().periods;
            let second = analysis::steady_state_at(
                engine,
                PeriodStart {
                    velocity: v_2,
                    mode: None,
                },
                (Some(d), iterations, correction),
                StatsWanted::default(),
                &mut (),
            )?;
            spent += (engine.counters().periods - before) as u32;
            let Some(b_2) = established_bound(engine.signal(), &second) else {
                break;
            };
            let above = (v_2 - v_star).abs() + CERTIFIED_REACH * b_2;
            let budget = CERTIFICATE_BUDGET.saturating_sub(spent);
            covering = certify_between(engine, motor, 0.0, v_star, (r, above), budget)?;
            spent += covering.evaluations;
        }
        match covering.verdict {
            Verdict::Certified => {
                certificate.evaluations += u64::from(spent);
                return Ok(covering.v_inf_bounds);
            }
            Verdict::Nearer { .. } => break,
            Verdict::Undecided | Verdict::Open { .. } => {}
        }
        if spent >= CERTIFICATE_BUDGET {
            break;
        }
    }
    certificate.evaluations += u64::from(spent);
    Ok(None)
}

/// What the covering from rest found where the search from rest did not.
pub(super) enum Search {
    /// The first fixed point beyond rest, the velocity up to which the
    /// covering proved the gap from rest free (the certificate goes on
    /// from there), and the covering's map evaluations.
    Found(SteadyState, f64, u64),
    /// No fixed point at all in the direction the map moves rest: the
    /// slider runs away. `P` at the rod's extreme velocity (m/s), and the
    /// covering's map evaluations.
    RunAway(f64, u64),
    /// Neither within the budget: the orbit from rest decides.
    Nothing,
}

/// Where the search from rest finds the map pushing every velocity it
/// tries onwards to the end of the rod's velocity range (the run-away test
/// of `crate::analysis::fixed_point`), a fixed point may still lie in a
/// band too narrow for it to see: where the slider meets the rod near an
/// extremum of the rod's velocity and sticks, with sliding friction too
/// weak to stop it anywhere else (`mu_dynamic = 0`: `P(v) = v + g_t T`
/// wherever it slips). The covering of `crate::analysis::certificate`
/// from rest to that end (`v_R,max` for a rising map) decides:
///
/// * the first point the map moves back brackets the first fixed point
///   beyond rest, which is searched in that bracket;
/// * a covering that reaches the end, with the end moved on beyond
///   rounding, proves a run-away when the slider also only gains speed
///   beyond the end: a slider faster than the rod throughout slides
///   backwards, `P(v) = v + (g_t - a_d) T > v` for every `v > v_R,max`
///   when `g_t > a_d` (and mirrored for a falling map). With no fixed
///   point from rest on, the monotone orbit from rest passes every
///   velocity (docs/model.md section 3).
pub(super) fn covering_search<E: PeriodEngine>(
    engine: &mut E,
    motor: &Motor,
    growing: bool,
    wanted: StatsWanted,
    trajectory: &mut Option<Trajectory>,
) -> Result<Search, Error> {
    let crate::signal::VelocityRange {
        min: lo_r,
        max: hi_r,
    } = engine.signal().velocity_range();
    let (far, slides_on) = if growing && hi_r > 0.0 {
        (hi_r, motor.g_t() - motor.a_d() > 0.0)
    } else if !growing && lo_r < 0.0 {
        (lo_r, motor.g_t() + motor.a_d() < 0.0)
    } else {
        return Ok(Search::Nothing);
    };
    let covering = certify(engine, motor, 0.0, far, 0.0, CERTIFICATE_BUDGET)?;
    let evaluations = u64::from(covering.evaluations);
    let (near, far) = match covering.verdict {
        Verdict::Nearer { near, far } => (near, far),
        Verdict::Open { beyond } if slides_on => return Ok(Search::RunAway(beyond, evaluations)),
        _ => return Ok(Search::Nothing),
    };
    let (lo, hi) = (near.min(far), near.max(far));
    let steady = steady_between(engine, (lo, hi), near, wanted, trajectory)?;
    Ok(Search::Found(steady, near, evaluations))
}

/// The steady state at the fixed point in the bracket `[lo, hi]` that the
/// covering found, searched from `start`, with its period observed.
fn steady_between<E: PeriodEngine, O: crate::engine::Observer>(
    engine: &mut E,
    (lo, hi): (f64, f64),
    start: f64,
    wanted: StatsWanted,
    observer: &mut O,
) -> Result<SteadyState, Error> {
    let analysis::FixedPoint {
        velocity: v,
        map_derivative: d,
        iterations,
        last_correction: correction,
    } = analysis::fixed_point_between(engine, lo, hi, start)?;
    Ok(analysis::steady_state_at(
        engine,
        PeriodStart {
            velocity: v,
            mode: None,
        },
        (Some(d), iterations, correction),
        wanted,
        observer,
    )?)
}
