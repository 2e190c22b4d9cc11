//! Error estimates of the indicators from measurable quantities
//! (docs/model.md section 9): the engine's bound on the periodic orbit's
//! boundary velocity carried to `v_inf`, and its propagation into the
//! ratios (smoothness, durability, friction energy) and the start-up time.

use crate::analysis::{SteadyIndicators, SteadyState, Transient};
use crate::signal::Signal;

/// Estimated absolute error of each reported indicator (same units).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ErrorEstimate {
    /// Of `v_inf` (m/s).
    pub v_inf: Option<f64>,
    /// Of the start-up time (s).
    pub startup_time: Option<f64>,
    /// Of the smoothness.
    pub smoothness: Option<f64>,
    /// Of the durability (1/N).
    pub durability: Option<f64>,
    /// Of the friction energy (J per period).
    pub friction_energy: Option<f64>,
    /// Of the stiction fraction.
    pub stiction_fraction: Option<f64>,
    /// Of the velocity per power (m/(s VA)).
    pub velocity_per_power: Option<f64>,
}

/// The rounding bound on velocities over one period's segments (m/s).
pub(crate) fn rounding_velocity(signal: &Signal, steady: &SteadyState) -> f64 {
    rounding_velocity_of(signal, steady.stats.events.total())
}

/// The rounding bound on the slider velocity at the end of a period with
/// `events` events (m/s): `8 eps` per segment (`events + 2` of them), of
/// `max |v_R|`.
pub(crate) fn rounding_velocity_of(signal: &Signal, events: u64) -> f64 {
    8.0 * f64::EPSILON * (events as f64 + 2.0) * signal.velocity_scale()
}

/// The engine's bound on the boundary velocity of the periodic orbit
/// through `steady` (m/s): the velocity error `u` one period introduces
/// plus the rounding bound and the residual, carried to the fixed point as
/// `/ (1 - P')` (or the multi-dimensional
/// [`SteadyState::boundary_bound`]), plus `u` again for the steady period
/// itself. `None` where
/// no bound holds: no engine bound, a grazing in the orbit (`u` infinite),
/// or `P' >= 1` (a neutral map).
fn engine_bound(signal: &Signal, steady: &SteadyState) -> Option<f64> {
    let u = steady.velocity_uncertainty.filter(|u| u.is_finite())?;
    let rounding_v = rounding_velocity(signal, steady);
    if let Some(b) = steady.boundary_bound {
        return b.is_finite().then_some(b + u + rounding_v);
    }
    let contraction = 1.0 - steady.map_derivative;
    (contraction > 0.0).then(|| (u + rounding_v + steady.residual) / contraction + u + rounding_v)
}

/// Largest [`engine_bound`], relative to `max |v_R|`, for which a fixed
/// point counts as established. The bound contains the range over which
/// the map is neutral within rounding, `rounding / (1 - P')`: where `P(v) - v`
/// cannot be told from 0 over a wider range, the map's zero does not say
/// where the motion from rest goes.
const ESTABLISHED: f64 = 1e-3;

/// The engine's bound on a fixed point from the search, if the fixed point
/// is established: the map contracts there (`P' < 1`), the orbit has no
/// grazing, and the bound (neutral range included) is at most
/// `1e-3 max |v_R|`.
pub(crate) fn established_bound(signal: &Signal, steady: &SteadyState) -> Option<f64> {
    engine_bound(signal, steady).filter(|b| *b <= ESTABLISHED * signal.velocity_scale())
}

/// The estimated error of `v_inf` (m/s) from a bound on the orbit's
/// boundary velocity: a velocity error moves the slider only while it
/// slides (in stick it follows the rod whatever its velocity was), plus a
/// rounding bound on positions.
pub(crate) fn v_inf_error(signal: &Signal, steady: &SteadyState, velocity_bound: f64) -> f64 {
    let period = signal.period();
    let stats = &steady.stats;
    let segments = stats.events.total() as f64 + 2.0;
    let rounding_x = 8.0 * f64::EPSILON * segments * (signal.position_scale() + stats.step.abs());
    let slip_fraction = (stats.slip_time / period).clamp(0.0, 1.0);
    velocity_bound * slip_fraction + rounding_x / period
}

/// `p_0.99` is exact unless a `v_p` lies within the `v_inf` error of the
/// 0.99 threshold, in which case it may be off by one period.
pub(crate) fn startup_error(
    period: f64,
    steady: &SteadyState,
    transient: &Transient,
    startup_periods: Option<u64>,
    v_error: Option<f64>,
) -> Option<f64> {
    let (p, dv) = (startup_periods?, v_error?);
    let threshold = 0.99 * steady.v_inf;
    let near = transient
        .mean_velocities
        .iter()
        .take(p as usize)
        .any(|v| (v - threshold).abs() <= 0.99 * dv);
    Some(if near { period } else { 0.0 })
}

/// Error estimates from measurable quantities:
/// * `v_inf`: the engine's bound on the orbit's boundary velocity
///   ([`engine_bound`]: event-time brackets times the jump in slider
///   acceleration at each event, zero-velocity decisions, the fixed
///   point's residual, all carried through `/ (1 - P')`), turned into a
///   bound on the mean velocity by [`v_inf_error`]; doubled where the
///   covering certified the fixed point (`covered`: the limit from rest is
///   proven within twice the bound, `super::certificate::CERTIFIED_REACH`).
///   Where the start-up decided the steady state (`from_orbit`), the
///   estimate also covers the distance of its limit's `v_inf` to the
///   steady period's. Where the engine states no bound, the start-up's own
///   estimate is used instead: the distance of its limit to the steady
///   state (or the last fixed-point correction) plus its remaining-distance
///   bound. No bound is given through a grazing;
/// * ratios (smoothness, durability, friction energy) carry the relative
///   error of `v_inf` and the same rounding bound on their own inputs;
/// * the start-up time is set by the caller ([`startup_error`]).
pub(crate) fn estimate_errors(
    signal: &Signal,
    steady: &SteadyState,
    transient: Option<&Transient>,
    ind: &SteadyIndicators,
    contact_force: f64,
    (from_orbit, covered): (bool, bool),
) -> ErrorEstimate {
    let period = signal.period();
    let stats = &steady.stats;
    let segments = stats.events.total() as f64 + 2.0;
    // Relative rounding of a sum over the period's segments.
    let rounding_rel = 16.0 * f64::EPSILON * segments;
    let rounding_v = rounding_velocity(signal, steady);
    let rounding_x = 8.0 * f64::EPSILON * segments * (signal.position_scale() + stats.step.abs());
    // Without a simulated start-up (a v_inf-only run) there is none: the
    // fast path needs the engine's bound.
    let from_transient = |t: &Transient| {
        (t.v_inf() - steady.v_inf).abs().max(steady.last_correction)
            + t.v_inf_error.unwrap_or(0.0)
            + rounding_v
    };
    let velocity_error = match steady.velocity_uncertainty {
        // A grazing in the steady orbit: the motion depends discontinuously
        // on the data there, so no bound holds.
        Some(u) if !u.is_finite() => None,
        Some(_) => match engine_bound(signal, steady) {
            // A fixed point certified by the covering: the limit from rest
            // lies within the covering's reach of it.
            Some(b) if covered => Some(super::certificate::CERTIFIED_REACH * b),
            Some(b) => Some(b),
            None if from_orbit => transient.filter(|t| t.converged).map(from_transient),
            None => None,
        },
        None => transient.map(from_transient),
    };
    let Some(dvel) = velocity_error else {
        return ErrorEstimate::default();
    };
    let mut dv = v_inf_error(signal, steady, dvel);
    if from_orbit && let Some(t) = transient.filter(|t| t.converged) {
        // Where the start-up decided, its own limit is the motion from
        // rest: the steady period simulated again must lie within the
        // estimate of it, in v_inf itself (not a velocity weighted by the
        // slip fraction), also where a decision within rounding sends the
        // period simulated again to the other side of a change of the
        // event structure.
        dv = dv.max(
            (t.v_inf() - steady.v_inf).abs() + t.v_inf_error.unwrap_or(0.0) + rounding_x / period,
        );
    }
    let spread = stats.v_max - stats.v_min;
    let sliding = stats.sliding_distance;
    let d_sliding = dvel * stats.slip_time + rounding_x;
    ErrorEstimate {
        v_inf: Some(dv),
        startup_time: None,
        // zeta = |v_inf| / spread; the spread's ends carry the velocity error.
        smoothness: ind
            .smoothness
            .is_finite()
            .then(|| dv / spread + ind.smoothness * (2.0 * dvel / spread + rounding_rel)),
        // delta = x_p / (F_c s) with x_p = v_inf T: the step's error over
        // F_c s (also where the step, and delta, are 0), and delta's
        // relative error from the sliding distance.
        durability: ind.durability.is_finite().then(|| {
            dv * period / (contact_force * sliding)
                + ind.durability.abs() * (d_sliding / sliding + rounding_rel)
        }),
        // W_f = mu_d F_c s.
        friction_energy: Some(if sliding > 0.0 {
            ind.friction_energy * (d_sliding / sliding + rounding_rel)
        } else {
            0.0
        }),
        // Set by the caller over the start-up's periods.
        stiction_fraction: Some(rounding_rel),
        velocity_per_power: None,
    }
}
