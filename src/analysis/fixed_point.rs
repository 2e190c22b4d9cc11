//! The fixed point of the period map `P: v_S((p-1)T) -> v_S(pT)`
//! (docs/model.md section 3). `P` is non-decreasing (two sliders on the
//! same rod never overtake each other), so the iterates from rest move
//! monotonically towards the nearest fixed point in the direction `P`
//! moves them. A zero of `g(v) = P(v) - v` is found by safeguarded Newton in
//! a bracket `g(lo) > 0 >= g(hi)` grown from the starting guess in that
//! direction, with `P'(v)` carried exactly through the period by the
//! engine. `g` need not be monotone (a stuck slider can be outrun by one
//! that slides), so a map with several fixed points may yield one the
//! start-up does not reach: the caller checks the fixed point against the
//! start-up, or without it by [`fixed_point_is_nearest`].

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

/// True if the period map moves `v` towards `target` (or `v` is it): a
/// necessary condition for iterates through `v` to converge to `target`
/// (`P` is monotone, so a fixed point between `v` and `target` would stop
/// them, and `P(v)` on the far side of `v` reveals one).
pub fn moves_towards<E: PeriodEngine>(
    engine: &mut E,
    v: f64,
    target: f64,
) -> Result<bool, SimulationError> {
    if v == target {
        return Ok(true);
    }
    let (p, _) = period_map(engine, v)?;
    Ok(if v < target { p > v } else { p < v })
}

/// Points of the march of [`fixed_point_is_nearest`] between rest and the
/// fixed point.
pub const NEAREST_MARCH_POINTS: u32 = 16;

/// The check of a fixed point `v_star` found by the search from rest that
/// replaces the start-up, or extends it past the orbit's last point `from`
/// (docs/model.md section 10; the argument is in the module docs of
/// `crate::simulation`): the map is evaluated, in order from `from`
/// towards `v_star`, at the points `i v_star / 16` (`i = 1..15`) beyond
/// `from`, then at `v_star (1 - 2^-j)` for `j = 5, 6, ...`, each only
/// while it is farther than `bound` from `v_star`. The geometric points
/// see a further pair of fixed points near `v_star` unless the pair is
/// narrower than about half its distance to `v_star`. `Ok(false)` as soon
/// as one point is not moved towards `v_star` (`P(x) - x` zero or of the
/// other sign): then a fixed point lies between rest and that point,
/// nearer than `v_star`. `Ok(true)` when every point is moved towards
/// `v_star`, with the number of map evaluations.
pub fn fixed_point_is_nearest<E: PeriodEngine>(
    engine: &mut E,
    v_star: f64,
    bound: f64,
    from: f64,
) -> Result<(bool, u32), SimulationError> {
    let uniform = (1..NEAREST_MARCH_POINTS)
        .map(|i| v_star * (f64::from(i) / f64::from(NEAREST_MARCH_POINTS)));
    // 1 - 2^-j for j >= 5 continues the uniform points past 15/16.
    let geometric = (5..60).map(|j| v_star * (1.0 - (0.5f64).powi(j)));
    let mut evaluations = 0;
    for x in uniform.chain(geometric) {
        if (v_star - x).abs() <= bound {
            break;
        }
        // Points the orbit from rest has passed are covered by it.
        if (x - from) * v_star.signum() <= 0.0 {
            continue;
        }
        let (p, _) = period_map(engine, x)?;
        evaluations += 1;
        if (p - x) * v_star.signum() <= 0.0 {
            return Ok((false, evaluations));
        }
    }
    Ok((true, evaluations))
}

/// Iteration limit of the fixed-point search.
const MAX_FIXED_POINT_ITERATIONS: u32 = 200;

/// The fixed point of the period map nearest to `guess` in the direction
/// the map moves it (the one a slider starting at `guess` converges to).
pub fn fixed_point<E: PeriodEngine>(
    engine: &mut E,
    guess: f64,
) -> Result<(f64, f64, u32, f64), SimulationError> {
    let (lo_r, hi_r) = engine.signal().velocity_range();
    let span = (hi_r - lo_r).max(f64::MIN_POSITIVE);
    let (p0, d0) = period_map(engine, guess)?;
    let g0 = p0 - guess;
    if g0 == 0.0 {
        return Ok((guess, d0, 0, 0.0));
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
            return Ok((v, dp, iteration, correction));
        }
        if g > 0.0 {
            lo = v;
        } else {
            hi = v;
        }
        if correction <= tiny.max(4.0 * f64::EPSILON * v.abs()) || hi - lo <= tiny {
            return Ok((v, dp, iteration, correction));
        }
    }
    Ok((v, dp, MAX_FIXED_POINT_ITERATIONS, correction))
}
