//! The start-up from rest (docs/model.md section 3): periods are simulated
//! until the boundary velocity has converged, the slider runs away, `p_0.99`
//! is reached or the period limit. `p_0.99` is the first period with
//! `v_p >= 0.99 v_inf` (for a slider that moves backwards,
//! `v_p <= 0.99 v_inf`).
//!
//! Converged means the limit of the orbit is established (see
//! [`transient`]): the boundary state repeated exactly, or it repeated
//! within the rounding of a velocity in periods with a stick phase (the
//! period map is locally constant there), or the measured contraction
//! bounds the remaining distance.

use super::error_estimate::rounding_velocity_of;
use super::stats::{StatsObserver, StatsWanted};
use crate::engine::{Direction, EventCounts, Mode, PeriodEngine, PeriodStart};
use crate::engine::{Observer, PeriodEnd};
use crate::error::SimulationError;
use crate::numerics::CompensatedSum;

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
    /// repeated exactly, or it repeated within rounding in periods with a
    /// stick phase, or the measured contraction bounds the remaining
    /// distance below the tolerance.
    pub converged: bool,
    /// Bound on the distance from the last boundary velocity to its limit
    /// (m/s), when converged: `|c| rho / (1 - rho)` with the last change `c`
    /// and the largest of the last measured contraction ratios `rho`;
    /// the rounding bound `r` for a repetition within it in periods with a
    /// stick phase; 0 when the boundary state repeated exactly.
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
    /// How the limit was established, when it was.
    pub converged_by: Option<Convergence>,
    /// Periods in the repeating cycle of boundary states where the limit
    /// was established by a repetition ([`Convergence::Exact`]): 1 for a
    /// state that repeated after one period, `k` for a cycle of `k`
    /// (a subharmonic orbit against a spring, or a cycle of a few doubles).
    pub cycle: u64,
}

/// The test that established the limit of the start-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Convergence {
    /// The boundary state repeated exactly (after one period, or in a
    /// cycle of up to 64).
    Exact,
    /// It repeated within rounding in periods with a stick phase.
    Rounding,
    /// The measured contraction ratios bound the remaining distance: an
    /// extrapolation, which a motion that slows down only for a while (past
    /// a near-tangency of the period map) can fool.
    Ratio,
    /// It entered the linear attraction of a fixed point found by Newton on
    /// the period map of a driven rod's boundary state (docs/model.md
    /// section 16, "The steady state"): over the last periods it moved
    /// towards the fixed point as the map's Jacobian there says.
    Attracted,
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
    /// Whether the contraction ratios may establish the limit
    /// ([`Convergence::Ratio`]); without, only a repetition does.
    pub ratio_rule: bool,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        Self {
            max_periods: 1_000_000,
            transient_tolerance: 1e-13,
            stop_at_startup: None,
            ratio_rule: true,
        }
    }
}

/// Longest cycle of boundary states the start-up recognises as periodic.
const CYCLE: usize = 64;

/// Contraction ratios kept for the convergence test: the remaining
/// distance is bounded with the largest of them.
const RATIOS: usize = 3;

/// Simulates the start-up from rest with `observer` attached, until the
/// boundary velocity has converged, the slider runs away, `p_0.99` is
/// reached (with [`AnalysisOptions::stop_at_startup`]) or `max_periods`.
///
/// Convergence is claimed only on evidence about the limit, never on the
/// size of a change alone (a motion that has barely begun changes little):
/// * the boundary state (velocity and mode) repeated exactly, after one
///   period or as a state seen again within the last 64 periods (a cycle
///   of a few doubles), so the orbit is periodic from there on, its limit
///   within the cycle's spread; or
/// * it repeated within rounding in periods with a stick phase: in each
///   of the last two periods the mode repeated, the change `c` of the
///   boundary velocity is at most the rounding bound `r` of the period's
///   end velocity (`8 eps` per segment of `max |v_R|`, docs/model.md
///   section 11), and the exact map derivative `P'` the engine carried
///   through both periods is 0 (the map is locally constant: a stuck
///   slider forgets its velocity). The limit is then within the rounding
///   width `r` of the period's end. This is the orbit that lands on two or
///   a few floating point values within rounding of each other and would
///   never repeat exactly. With `0 < P' < 1` such a repetition is not
///   taken: an orbit that creeps by rounding-sized steps past a
///   near-tangency of the map can still be on its way to a change of the
///   event structure, where the map jumps; or
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
    transient_until(engine, options, wanted, observer, |_, _, _| Ok(None))
}

/// Where a start-up was followed into the attraction of a fixed point
/// found by other means ([`Convergence::Attracted`]): the distance of the
/// last boundary velocity to the fixed point's (m/s), and the distance of
/// the last period's `v_p` to the fixed point's `v_inf` (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Attracted {
    pub remaining: f64,
    pub v_inf_error: f64,
}

/// [`transient`], with `settled` asked after every period (with the
/// engine, the period's end and its events) whether the motion has
/// entered the attraction of a known fixed point; it may run periods of
/// its own on the engine, and leaves it as it found it.
pub(crate) fn transient_until<E, O, F>(
    engine: &mut E,
    options: &AnalysisOptions,
    wanted: StatsWanted,
    observer: &mut O,
    mut settled: F,
) -> Result<Transient, SimulationError>
where
    E: PeriodEngine,
    O: Observer,
    F: FnMut(&mut E, &PeriodEnd, &EventCounts) -> Result<Option<Attracted>, SimulationError>,
{
    let v_scale = engine.signal().velocity_scale();
    let crate::signal::VelocityRange {
        min: lo_r,
        max: hi_r,
    } = engine.signal().velocity_range();
    let period = engine.signal().period();
    let tol = options.transient_tolerance * v_scale;
    let mut stats = StatsObserver::for_engine(
        &*engine,
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
    let mut converged_by = None;
    // The boundary state by its bits: the slider's velocity and mode, and
    // where the engine carries more (a driven rod, a spring against the
    // slider) its rod state and the slider's place against the spring.
    let key = |engine: &E, end: &PeriodEnd| -> [u64; 5] {
        let z = engine.boundary_state();
        [
            end.velocity.to_bits(),
            z.map_or(0, |z| z.rod_x.to_bits()),
            z.map_or(0, |z| z.rod_v.to_bits()),
            z.and_then(|z| z.slider).map_or(0, |p| p.x.to_bits()),
            z.and_then(|z| z.slider)
                .map_or(0, |p| if p.contact { 1 } else { 2 }),
        ]
    };
    let mut recent: std::collections::VecDeque<([u64; 5], Mode)> =
        std::collections::VecDeque::with_capacity(CYCLE);
    let mut last_key: Option<[u64; 5]> = None;
    let mut cycle = 0u64;
    // The map derivative of the previous period, if its boundary state
    // repeated within rounding.
    let mut rounded_before: Option<f64> = None;
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
        let same_mode = start.mode == Some(end.mode);
        let state_key = key(engine, &end);
        let repeated = change == 0.0 && same_mode && last_key == Some(state_key);
        last_key = Some(state_key);
        let rounding = rounding_velocity_of(engine.signal(), stats.last.events.total());
        let rounded = same_mode && change.abs() <= rounding;
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
            converged_by = Some(Convergence::Exact);
            cycle = 1;
            break;
        }
        let ev = &stats.last.events;
        run_away = runaway(&end, ev.total() - ev.jump, change, (lo_r, hi_r));
        if run_away.is_some() {
            break;
        }
        if let Some(a) = settled(engine, &end, &stats.last.events)? {
            remaining = Some(a.remaining);
            v_inf_error = Some(a.v_inf_error + tol);
            converged_by = Some(Convergence::Attracted);
            break;
        }
        if rounded {
            let derivative = rounded_before.map(|d: f64| d.max(end.map_derivative));
            // Only a stick phase in both periods (P' = 0: the map is
            // locally constant) makes a repetition within rounding a limit;
            // with 0 < P' < 1 an orbit that creeps by rounding-sized steps
            // can still be on its way past a change of the event
            // structure, where the map jumps.
            if let Some(d) = derivative.filter(|d| *d == 0.0) {
                let tail = rounding + d * (change.abs() + rounding) / (1.0 - d);
                if tail <= tol {
                    remaining = Some(tail);
                    v_inf_error = Some(tail + change.abs() + tol);
                    converged_by = Some(Convergence::Rounding);
                    break;
                }
            }
            rounded_before = Some(end.map_derivative);
        } else {
            rounded_before = None;
        }
        // A state seen again within the last CYCLE periods: the computed
        // orbit is periodic from there on (a cycle of a few doubles).
        let state = (state_key, end.mode);
        if let Some(back) = recent.iter().rev().position(|s| *s == state) {
            cycle = back as u64 + 1;
            let cycle = back + 1;
            let spread = |xs: &[f64]| {
                let tail = &xs[xs.len() - cycle..];
                let lo = tail.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = tail.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                hi - lo
            };
            let reach = spread(&boundary_velocities);
            remaining = Some(reach);
            v_inf_error = Some(spread(&mean_velocities) + reach + tol);
            converged_by = Some(Convergence::Exact);
            break;
        }
        if recent.len() == CYCLE {
            recent.pop_front();
        }
        recent.push_back(state);
        if let Some(before) = last_change {
            if ratios.len() == RATIOS {
                ratios.remove(0);
            }
            ratios.push((change / before).abs());
        }
        last_change = Some(change);
        if ratios.len() < RATIOS || !options.ratio_rule {
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
            converged_by = Some(Convergence::Ratio);
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
        converged_by,
        cycle,
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
