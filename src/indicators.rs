//! Performance indicators (docs/model.md section 3; the paper's sections 6.1,
//! 6.2): start-up from rest and the periodic steady state.
//!
//! Per period `p` (`t` in `[(p-1)T, pT]`):
//! * step `x_p = x_S(pT) - x_S((p-1)T)`, mean velocity `v_p = x_p / T`;
//! * smoothness (16) `zeta_p = |v_p| / (max_p v_S - min_p v_S)`, with exact
//!   extrema: segment ends, and in stick the zeros of `a_R`;
//! * sliding distance `integral |v_R - v_S| dt`, exact per segment
//!   (`|delta(x_R - x_S)|`) plus `|delta x_R|` at rod jumps, giving the wear
//!   volume (17) `V_p / w = F_c x` this, the durability (18)
//!   `delta_p = x_p / (F_c integral |v_rel|)` and the friction energy (19)
//!   `W_f,p = mu_d F_c integral |v_rel|`;
//! * time in stick.
//!
//! **Steady state** is the periodic orbit of the period map
//! `P: v_S((p-1)T) -> v_S(pT)`. `P` is non-decreasing (two sliders on the
//! same rod never overtake each other), so the iterates from rest move
//! monotonically towards the nearest fixed point in the direction `P`
//! moves them. A zero of `g(v) = P(v) - v` is found by safeguarded Newton in
//! a bracket `g(lo) > 0 >= g(hi)` grown from the starting guess in that
//! direction, with `P'(v)` carried exactly through the period by the
//! engine. `g` need not be monotone (a stuck slider can be outrun by one
//! that slides), so a map with several fixed points may yield one the
//! start-up does not reach: the caller checks the fixed point against the
//! start-up, or without it by [`fixed_point_is_nearest`]
//! ([`crate::simulation::run_with`]). The transient from rest can
//! be simulated until its own period-to-period changes have died out (with
//! Aitken's extrapolation); the two steady states must agree.
//!
//! **Start-up** `p_0.99` is the first period with `v_p >= 0.99 v_inf`
//! (for a slider that moves backwards, `v_p <= 0.99 v_inf`).

use crate::engine::{Direction, EventCounts, Mode, PeriodEngine, PeriodStart, Segment};
use crate::engine::{Observer, PeriodEnd};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::numerics::CompensatedSum;
use crate::signal::{Partition, Signal};

/// What the per-period statistics should include beyond the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StatsWanted {
    /// Velocity extrema for smoothness (16).
    pub smoothness: bool,
    /// Sliding distance for wear (17), durability (18), friction energy (19).
    pub sliding: bool,
    /// Time in stick.
    pub stiction: bool,
    /// Time sliding (needs slip segments).
    pub slip_time: bool,
}

impl StatsWanted {
    /// Everything.
    pub const ALL: StatsWanted = StatsWanted {
        smoothness: true,
        sliding: true,
        stiction: true,
        slip_time: true,
    };
}

/// Statistics of one period.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PeriodStats {
    /// Step `x_p` (m).
    pub step: f64,
    /// Smallest slider velocity in the period (m/s), if asked.
    pub v_min: f64,
    /// Largest slider velocity in the period (m/s), if asked.
    pub v_max: f64,
    /// `integral |v_R - v_S| dt` over the period (m), if asked.
    pub sliding_distance: f64,
    /// Time in stick (s), if asked.
    pub stick_time: f64,
    /// Time sliding (s), if stick time was asked.
    pub slip_time: f64,
    /// Events in the period.
    pub events: EventCounts,
}

/// Observer that accumulates [`PeriodStats`] for the current period.
#[derive(Debug, Clone)]
pub struct StatsObserver {
    wanted: StatsWanted,
    /// Zeros of `a_R` (velocity extrema of a stuck slider), when smoothness
    /// is wanted.
    accel_zeros: Option<Partition>,
    current: PeriodStats,
    /// The statistics of the last finished period.
    pub last: PeriodStats,
}

impl StatsObserver {
    /// An observer for `signal` collecting what is wanted.
    pub fn new(signal: &Signal, wanted: StatsWanted) -> Self {
        Self {
            wanted,
            accel_zeros: wanted.smoothness.then(|| signal.partition(0.0)),
            current: Self::fresh(),
            last: Self::fresh(),
        }
    }

    fn fresh() -> PeriodStats {
        PeriodStats {
            v_min: f64::INFINITY,
            v_max: f64::NEG_INFINITY,
            ..Default::default()
        }
    }
}

impl Observer for StatsObserver {
    fn wants_segments(&self) -> bool {
        self.wanted.smoothness
            || self.wanted.sliding
            || self.wanted.stiction
            || self.wanted.slip_time
    }

    fn wants_slip_segments(&self) -> bool {
        self.wanted.smoothness || self.wanted.sliding || self.wanted.slip_time
    }

    #[inline]
    fn segment(&mut self, segment: &Segment, signal: &Signal) {
        let c = &mut self.current;
        if self.wanted.sliding {
            c.sliding_distance += segment.sliding_distance();
        }
        if self.wanted.stiction {
            if segment.mode == Mode::Stick {
                c.stick_time += segment.duration();
            } else {
                c.slip_time += segment.duration();
            }
        }
        if self.wanted.smoothness {
            for v in [segment.slider_start.v, segment.slider_end.v] {
                c.v_min = c.v_min.min(v);
                c.v_max = c.v_max.max(v);
            }
            if segment.mode == Mode::Stick
                && let Some(zeros) = &self.accel_zeros
            {
                // v_S = v_R: interior extrema where a_R changes sign.
                let first = zeros.locate(segment.start);
                for piece in &zeros.pieces[first + 1..] {
                    if piece.start >= segment.end {
                        break;
                    }
                    let v = signal.velocity(piece.start);
                    c.v_min = c.v_min.min(v);
                    c.v_max = c.v_max.max(v);
                }
            }
        }
    }

    #[inline]
    fn event(&mut self, event: &crate::engine::Event) {
        self.current.events.add(&event.kind);
        if let crate::engine::EventKind::Jump { dx, .. } = event.kind
            && self.wanted.sliding
        {
            // The rod slides |dx| past the slider in zero time.
            self.current.sliding_distance += dx.abs();
        }
    }

    #[inline]
    fn period_end(&mut self, end: &PeriodEnd) {
        self.current.step = end.step;
        self.last = self.current;
        self.current = Self::fresh();
    }
}

/// The periodic steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyState {
    /// Slider velocity at the period boundary on the periodic orbit (m/s).
    pub boundary_velocity: f64,
    /// `P'` at the fixed point (0 if the orbit sticks).
    pub map_derivative: f64,
    /// Steady-state velocity `v_inf = x_inf / T` (m/s).
    pub v_inf: f64,
    /// Statistics of one steady-state period.
    pub stats: PeriodStats,
    /// Newton/bisection iterations of the fixed-point search.
    pub iterations: u32,
    /// Size of the last fixed-point correction (m/s).
    pub last_correction: f64,
    /// `|P(v*) - v*|` at the fixed point found (m/s): zero to rounding
    /// unless event-time tolerances make `P` ragged.
    pub residual: f64,
    /// Bound on the velocity error one steady-state period introduces
    /// through the engine's tolerances (m/s), if the engine states one.
    pub velocity_uncertainty: Option<f64>,
    /// Bound on the error of each event time (s).
    pub event_time_uncertainty: f64,
}

/// The start-up from rest.
#[derive(Debug, Clone, PartialEq)]
pub struct Transient {
    /// Mean velocity `v_p` of every simulated period, `p = 1..`.
    pub mean_velocities: Vec<f64>,
    /// Slider velocity at the end of the last simulated period.
    pub final_velocity: f64,
    /// Mode at the end of the last simulated period.
    pub final_mode: Mode,
    /// True if the motion's limit was established: the boundary velocity
    /// repeated exactly, or the measured contraction bounds the remaining
    /// distance below the tolerance.
    pub converged: bool,
    /// Bound on the distance from the last boundary velocity to its limit
    /// (m/s), when converged: `|c| rho / (1 - rho)` with the last change `c`
    /// and the largest of the last measured contraction ratios `rho`; 0
    /// when the boundary state repeated exactly.
    pub remaining: Option<f64>,
    /// Estimated error of [`Transient::v_inf`] (m/s), when converged: the
    /// distance of the last period's start velocity to the limit (the
    /// remaining distance plus the last change) and the tolerance of the
    /// test; a mean velocity moves no more than the boundary velocity it
    /// starts from (two sliders never overtake each other).
    pub v_inf_error: Option<f64>,
    /// Time in stick in every period (s), if asked.
    pub stick_times: Vec<f64>,
    /// Events in every period.
    pub period_events: Vec<EventCounts>,
    /// Slider position at the end of the transient, `sum x_p`, summed with
    /// compensation so that it does not drift over long runs (m).
    pub displacement: f64,
    /// Slider velocity at the end of every simulated period (m/s).
    pub boundary_velocities: Vec<f64>,
    /// Set when the slider ran away: it slid a whole period without any
    /// event outside the rod's velocity range, moving further away.
    pub run_away: Option<Direction>,
}

impl Transient {
    /// Periods simulated.
    pub fn periods(&self) -> u64 {
        self.mean_velocities.len() as u64
    }

    /// The transient's estimate of `v_inf`: `v_p` of the last simulated
    /// period.
    pub fn v_inf(&self) -> f64 {
        self.mean_velocities.last().copied().unwrap_or(0.0)
    }

    /// `p_0.99` for a given `v_inf`: the first period with
    /// `v_p / v_inf >= 0.99` (the same sign as `v_inf`); `None` if
    /// `v_inf = 0` or it was not reached.
    pub fn startup_periods(&self, v_inf: f64) -> Option<u64> {
        if v_inf == 0.0 {
            return None;
        }
        self.mean_velocities
            .iter()
            .position(|v| reached_startup(*v, v_inf))
            .map(|i| i as u64 + 1)
    }

    /// Time in stick over periods `1..=periods` (s), if stick times were
    /// asked for.
    pub fn stick_time(&self, periods: u64) -> f64 {
        self.stick_times.iter().take(periods as usize).sum()
    }

    /// Events over periods `1..=periods`.
    pub fn events(&self, periods: u64) -> EventCounts {
        self.period_events
            .iter()
            .take(periods as usize)
            .fold(EventCounts::default(), |a, e| a.merged(e))
    }
}

/// Settings of the analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisOptions {
    /// Longest transient simulated (periods).
    pub max_periods: u64,
    /// The transient stops once its estimated distance to the steady state,
    /// relative to `max |v_R|`, is below this.
    pub transient_tolerance: f64,
    /// When set to the steady-state `v_inf`, the transient stops at the
    /// first period with `v_p / v_inf >= 0.99` (`p_0.99`) instead of running
    /// to convergence.
    pub stop_at_startup: Option<f64>,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        Self {
            max_periods: 1_000_000,
            transient_tolerance: 1e-13,
            stop_at_startup: None,
        }
    }
}

/// Contraction ratios kept for the convergence test: the remaining
/// distance is bounded with the largest of them.
const RATIOS: usize = 3;

/// Simulates the start-up from rest with `observer` attached, until the
/// boundary velocity has converged, the slider runs away, `p_0.99` is
/// reached (with [`AnalysisOptions::stop_at_startup`]) or `max_periods`.
///
/// Convergence is claimed only on evidence about the limit, never on the
/// size of a change alone (a motion that has barely begun changes little):
/// * the boundary state (velocity and mode) repeated exactly, so the orbit
///   is periodic from there on; or
/// * the last three contraction ratios `rho_k = |c_k / c_(k-1)|` of
///   the changes `c_k` of the boundary velocity are below 1 and bound the
///   remaining distance, `|c| rho / (1 - rho) <= tol` with `rho` the
///   largest of them.
///
/// (Aitken's extrapolation of the mean velocities is not used: they carry
/// a second component decaying like `rho^2`, which leaves the extrapolated
/// limit off by far more than the successive limits' agreement shows.)
pub fn transient<E: PeriodEngine, O: Observer>(
    engine: &mut E,
    options: &AnalysisOptions,
    wanted: StatsWanted,
    observer: &mut O,
) -> Result<Transient, SimulationError> {
    let v_scale = engine.signal().velocity_scale();
    let (lo_r, hi_r) = engine.signal().velocity_range();
    let period = engine.signal().period();
    let tol = options.transient_tolerance * v_scale;
    let mut stats = StatsObserver::new(
        engine.signal(),
        StatsWanted {
            stiction: wanted.stiction,
            ..Default::default()
        },
    );
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let mut mean_velocities: Vec<f64> = Vec::new();
    let mut last_change: Option<f64> = None;
    let mut ratios: Vec<f64> = Vec::with_capacity(RATIOS);
    let mut remaining = None;
    let mut v_inf_error = None;
    let mut stick_times = Vec::new();
    let mut period_events = Vec::new();
    let mut displacement = CompensatedSum::default();
    let mut boundary_velocities = Vec::new();
    let mut run_away = None;
    let mut p = 0u64;
    while p < options.max_periods {
        p += 1;
        let end = engine.run_period(p, start, &mut (&mut stats, &mut *observer))?;
        let v_p = end.step / period;
        mean_velocities.push(v_p);
        displacement.add(end.step);
        if wanted.stiction {
            stick_times.push(stats.last.stick_time);
        }
        period_events.push(stats.last.events);
        boundary_velocities.push(end.velocity);
        let change = end.velocity - start.velocity;
        let repeated = change == 0.0 && start.mode == Some(end.mode);
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
        if let Some(v_inf) = options.stop_at_startup
            && v_inf != 0.0
            && reached_startup(v_p, v_inf)
        {
            break;
        }
        if repeated {
            remaining = Some(0.0);
            v_inf_error = Some(tol);
            break;
        }
        let ev = &stats.last.events;
        run_away = runaway(&end, ev.total() - ev.jump, change, (lo_r, hi_r));
        if run_away.is_some() {
            break;
        }
        if let Some(before) = last_change {
            if ratios.len() == RATIOS {
                ratios.remove(0);
            }
            ratios.push((change / before).abs());
        }
        last_change = Some(change);
        if ratios.len() < RATIOS {
            continue;
        }
        let rho = ratios.iter().copied().fold(0.0, f64::max);
        if rho.is_nan() || rho >= 1.0 {
            continue;
        }
        let tail = change.abs() * rho / (1.0 - rho);
        if tail <= tol {
            remaining = Some(tail);
            // v_p of this period started one change before the end.
            v_inf_error = Some(tail + change.abs() + tol);
            break;
        }
    }
    Ok(Transient {
        mean_velocities,
        final_velocity: start.velocity,
        final_mode: start.mode.unwrap_or(Mode::Stick),
        converged: remaining.is_some(),
        remaining,
        v_inf_error,
        stick_times,
        period_events,
        displacement: displacement.value(),
        boundary_velocities,
        run_away,
    })
}

/// `v_p / v_inf >= 0.99`: `v_p >= 0.99 v_inf` for a slider moving
/// forwards, `v_p <= 0.99 v_inf` for one moving backwards.
fn reached_startup(v_p: f64, v_inf: f64) -> bool {
    let target = 0.99 * v_inf;
    if v_inf > 0.0 {
        v_p >= target
    } else {
        v_p <= target
    }
}

/// A slider that slid a whole period in one direction without any event
/// (rod jumps aside: the slider's velocity is outside the rod's range on
/// both sides of one), ends outside the rod's velocity range and moved
/// further away cannot come back: `v_rel` never reaches zero again and its
/// acceleration is constant. This is a run-away (the extra acceleration
/// `g_t` exceeds what sliding friction `a_d` can hold), returned as the
/// direction it runs in.
fn runaway(
    end: &PeriodEnd,
    events: u64,
    change: f64,
    (lo_r, hi_r): (f64, f64),
) -> Option<Direction> {
    if events != 0 {
        return None;
    }
    match end.mode {
        Mode::Slip(Direction::Backward) if end.velocity > hi_r && change > 0.0 => {
            Some(Direction::Forward)
        }
        Mode::Slip(Direction::Forward) if end.velocity < lo_r && change < 0.0 => {
            Some(Direction::Backward)
        }
        _ => None,
    }
}

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
/// [`crate::simulation`]): the map is evaluated, in order from `from`
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

/// The steady state reached from `guess`, with one period observed by
/// `observer`.
pub fn steady_state<E: PeriodEngine, O: Observer>(
    engine: &mut E,
    guess: f64,
    wanted: StatsWanted,
    observer: &mut O,
) -> Result<SteadyState, SimulationError> {
    let (v_star, map_derivative, iterations, last_correction) = fixed_point(engine, guess)?;
    steady_state_at(
        engine,
        v_star,
        (Some(map_derivative), iterations, last_correction),
        wanted,
        observer,
    )
}

/// The periodic orbit through the boundary velocity `v_star`, with one
/// period observed by `observer`; `(P'(v_star), iterations, last
/// correction)` come from the search that found it (or from the start-up
/// that reached it).
pub fn steady_state_at<E: PeriodEngine, O: Observer>(
    engine: &mut E,
    v_star: f64,
    (map_derivative, iterations, last_correction): (Option<f64>, u32, f64),
    wanted: StatsWanted,
    observer: &mut O,
) -> Result<SteadyState, SimulationError> {
    // One unobserved period gives the mode the orbit has at its period
    // boundary, so that the observed period reports the transition at
    // phase 0 like every other.
    let before = engine.run_period(
        2,
        PeriodStart {
            velocity: v_star,
            mode: None,
        },
        &mut (),
    )?;
    // The regime and the error estimate need the stick and slip times and
    // the sliding distance of this one period, whatever else is wanted.
    let mut stats = StatsObserver::new(
        engine.signal(),
        StatsWanted {
            stiction: true,
            slip_time: true,
            sliding: true,
            ..wanted
        },
    );
    let end = engine.run_period(
        2,
        PeriodStart {
            velocity: before.velocity,
            mode: Some(before.mode),
        },
        &mut (&mut stats, observer),
    )?;
    let period = engine.signal().period();
    Ok(SteadyState {
        boundary_velocity: before.velocity,
        residual: (before.velocity - v_star).abs(),
        map_derivative: map_derivative.unwrap_or(before.map_derivative),
        v_inf: end.step / period,
        stats: stats.last,
        iterations,
        last_correction,
        velocity_uncertainty: engine.last_velocity_uncertainty(),
        event_time_uncertainty: engine.event_time_uncertainty(),
    })
}

/// Indicators derived from a steady-state period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyIndicators {
    /// `v_inf` (m/s).
    pub v_inf: f64,
    /// Smoothness `zeta_inf` (16).
    pub smoothness: f64,
    /// Durability `delta_inf` (18), 1/N.
    pub durability: f64,
    /// Friction energy per period `W_f` (19), J.
    pub friction_energy: f64,
    /// Time in stick / period in steady state.
    pub stiction_fraction: f64,
}

impl SteadyState {
    /// The paper's indicators for this steady state and motor.
    pub fn indicators(&self, motor: &Motor, period: f64) -> SteadyIndicators {
        let s = &self.stats;
        let spread = s.v_max - s.v_min;
        let wear_force = motor.contact_force() * s.sliding_distance;
        SteadyIndicators {
            v_inf: self.v_inf,
            // 0/0 (no motion at all) is undefined, reported as none.
            smoothness: if spread > 0.0 {
                self.v_inf.abs() / spread
            } else if self.v_inf != 0.0 {
                f64::INFINITY
            } else {
                f64::NAN
            },
            durability: if wear_force > 0.0 {
                s.step / wear_force
            } else {
                f64::INFINITY
            },
            friction_energy: motor.mu_d() * wear_force,
            stiction_fraction: s.stick_time / period,
        }
    }
}
