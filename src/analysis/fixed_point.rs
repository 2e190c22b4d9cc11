//! The fixed point of the period map `P: v_S((p-1)T) -> v_S(pT)`
//! (docs/model.md section 3). `P` is non-decreasing (two sliders on the
//! same rod never overtake each other), so the iterates from rest move
//! monotonically towards the nearest fixed point in the direction `P`
//! moves them. A zero of `g(v) = P(v) - v` is found by safeguarded Newton in
//! a bracket `g(lo) > 0 >= g(hi)` grown from the starting guess in that
//! direction, with `P'(v)` carried exactly through the period by the
//! engine. `g` need not be monotone (a slider that sticks can outrun one
//! that slides on), so a map with several fixed points may yield one the
//! start-up does not reach: the caller certifies the fixed point
//! (`super::certificate`), and where the covering finds a nearer one,
//! [`fixed_point_between`] finds it in the bracket the covering gives.

use crate::engine::{PeriodEngine, PeriodStart};
use crate::error::SimulationError;

/// `P(v)` and `P'(v)`.
fn period_map<E: PeriodEngine>(engine: &mut E, v: f64) -> Result<(f64, f64), SimulationError> {
    let end = engine.run_period(
        2,
        PeriodStart {
            velocity: v,
            mode: None,
        },
        &mut (),
    )?;
    Ok((end.velocity, end.map_derivative))
}

/// A fixed point of the period map as the search found it
/// ([`fixed_point`], [`fixed_point_between`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedPoint {
    /// The slider velocity at the period boundary, `P(v) = v` (m/s).
    pub velocity: f64,
    /// The map's derivative there, `P'(v)`.
    pub map_derivative: f64,
    /// Iterations of the search (0: the guess was the fixed point).
    pub iterations: u32,
    /// The search's last step (m/s).
    pub last_correction: f64,
}

impl FixedPoint {
    fn new(velocity: f64, map_derivative: f64, iterations: u32, last_correction: f64) -> Self {
        Self {
            velocity,
            map_derivative,
            iterations,
            last_correction,
        }
    }
}

/// Iteration limit of the fixed-point search.
const MAX_FIXED_POINT_ITERATIONS: u32 = 200;

/// The fixed point of the period map nearest to `guess` in the direction
/// the map moves it (the one a slider starting at `guess` converges to).
pub fn fixed_point<E: PeriodEngine>(
    engine: &mut E,
    guess: f64,
) -> Result<FixedPoint, SimulationError> {
    let crate::signal::VelocityRange {
        min: lo_r,
        max: hi_r,
    } = engine.signal().velocity_range();
    let span = (hi_r - lo_r).max(f64::MIN_POSITIVE);
    let (p0, d0) = period_map(engine, guess)?;
    let g0 = p0 - guess;
    if g0 == 0.0 {
        return Ok(FixedPoint::new(guess, d0, 0, 0.0));
    }
    // Bracket [lo, hi] with g(lo) > 0 >= g(hi) in the direction P moves
    // the guess. The rod's velocity range closes it: a slider faster than
    // the rod ever is slides backwards, and can only climb again by sliding
    // forwards, that is, slower than the rod; so unless the load g_t
    // outweighs sliding friction, P(max v_R) <= max v_R and likewise
    // P(min v_R) >= min v_R. Where that fails there is no periodic orbit
    // reachable in that direction: the slider runs away.
    let (lo, hi, far, direction) = if g0 > 0.0 {
        (guess, guess.max(hi_r), guess.max(hi_r), "growing")
    } else {
        (guess.min(lo_r), guess, guess.min(lo_r), "falling")
    };
    let (p_far, _) = period_map(engine, far)?;
    let closes = if g0 > 0.0 { p_far <= far } else { p_far > far };
    if !closes {
        return Err(SimulationError::NoSteadyState {
            direction,
            velocity: p_far,
            periods: engine.counters().periods,
        });
    }
    bracketed(engine, (lo, hi), (guess, g0, d0), span)
}

/// The fixed point of the period map in `[lo, hi]`, where `P(lo) > lo`
/// and `P(hi) <= hi` (beyond rounding): safeguarded Newton from the end
/// `start` (either one), bisecting whenever Newton leaves the bracket.
pub fn fixed_point_between<E: PeriodEngine>(
    engine: &mut E,
    lo: f64,
    hi: f64,
    start: f64,
) -> Result<FixedPoint, SimulationError> {
    let crate::signal::VelocityRange {
        min: lo_r,
        max: hi_r,
    } = engine.signal().velocity_range();
    let span = (hi_r - lo_r).max(f64::MIN_POSITIVE);
    let (p, d) = period_map(engine, start)?;
    if p == start {
        return Ok(FixedPoint::new(start, d, 0, 0.0));
    }
    bracketed(engine, (lo, hi), (start, p - start, d), span)
}

/// Safeguarded Newton on `g(v) = P(v) - v` in the bracket `[lo, hi]`
/// (`g(lo) > 0 >= g(hi)`) from `v` with `g(v)`, `P'(v)`.
fn bracketed<E: PeriodEngine>(
    engine: &mut E,
    (lo, hi): (f64, f64),
    (guess, g0, d0): (f64, f64, f64),
    span: f64,
) -> Result<FixedPoint, SimulationError> {
    let (mut lo, mut hi) = (lo, hi);
    let tiny = 4.0 * f64::EPSILON * span;
    let (mut v, mut g, mut dp) = (guess, g0, d0);
    let mut correction = f64::INFINITY;
    for iteration in 1..=MAX_FIXED_POINT_ITERATIONS {
        let newton = v - g / (dp - 1.0);
        let next = if newton.is_finite() && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        correction = (next - v).abs();
        v = next;
        let (p, d) = period_map(engine, v)?;
        g = p - v;
        dp = d;
        if g == 0.0 {
            return Ok(FixedPoint::new(v, dp, iteration, correction));
        }
        if g > 0.0 {
            lo = v;
        } else {
            hi = v;
        }
        if correction <= tiny.max(4.0 * f64::EPSILON * v.abs()) || hi - lo <= tiny {
            return Ok(FixedPoint::new(v, dp, iteration, correction));
        }
    }
    Ok(FixedPoint::new(
        v,
        dp,
        MAX_FIXED_POINT_ITERATIONS,
        correction,
    ))
}
