//! A wall-clock budget for a run (`[run] time_limit_s`, `--time-limit`).
//!
//! [`TimeBudget`] wraps any [`PeriodEngine`] and refuses to start another
//! period once the budget has run out, with
//! [`SimulationError::TimeLimit`] naming the budget and how many periods
//! were simulated. Every analysis (start-up, fixed-point search, steady
//! period) advances the motion only through `run_period`, so one check
//! there bounds the whole run to the budget plus one period; the work of a
//! single period is bounded separately (the event engine's events per
//! period, [`crate::scene::MAX_FIXED_STEPS_PER_PERIOD`]).

use crate::engine::{Observer, PeriodEnd};
use crate::engine::{PeriodEngine, PeriodStart, WorkCounters};
use crate::error::SimulationError;
use crate::signal::Signal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Whether long runs report progress on standard error (set by the command
/// line for an interactive terminal).
static PROGRESS: AtomicBool = AtomicBool::new(false);

/// Seconds between two progress lines of a long run.
const PROGRESS_EVERY: Duration = Duration::from_secs(2);

/// Turns progress lines of long runs on standard error on or off.
pub(crate) fn show_progress(on: bool) {
    PROGRESS.store(on, Ordering::Relaxed);
}

/// An engine that stops with [`SimulationError::TimeLimit`] once the
/// budget, counted from [`TimeBudget::new`], has run out. Without a budget
/// it is the engine itself.
pub(crate) struct TimeBudget<E> {
    engine: E,
    /// Start of the clock and the budget in seconds, when there is one.
    limit: Option<(Instant, Duration, f64)>,
    /// Start of the run and the time of the last progress line, when
    /// progress is shown.
    progress: Option<(Instant, Instant)>,
}

impl<E: PeriodEngine> TimeBudget<E> {
    /// Wraps `engine` with a budget of `seconds` (none: no limit). The
    /// clock starts now. A budget too large for a [`Duration`] is no limit.
    pub(crate) fn new(engine: E, seconds: Option<f64>) -> Self {
        let limit = seconds.and_then(|s| {
            Duration::try_from_secs_f64(s)
                .ok()
                .map(|d| (Instant::now(), d, s))
        });
        let now = Instant::now();
        let progress = PROGRESS.load(Ordering::Relaxed).then_some((now, now));
        Self {
            engine,
            limit,
            progress,
        }
    }

    /// The engine inside.
    pub(crate) fn engine(&self) -> &E {
        &self.engine
    }

    /// The engine inside, to change.
    pub(crate) fn engine_mut(&mut self) -> &mut E {
        &mut self.engine
    }

    /// A progress line every [`PROGRESS_EVERY`] of a long run.
    fn report_progress(&mut self) {
        let Some((start, last)) = self.progress else {
            return;
        };
        if last.elapsed() >= PROGRESS_EVERY {
            let now = Instant::now();
            self.progress = Some((start, now));
            eprintln!(
                "stickslip: running: {} periods simulated in {:.0} s (run.max_periods bounds the start-up; --time-limit the run)",
                self.engine.counters().periods,
                (now - start).as_secs_f64()
            );
        }
    }
}

impl<E: PeriodEngine> PeriodEngine for TimeBudget<E> {
    fn signal(&self) -> &Signal {
        self.engine.signal()
    }

    #[inline]
    fn run_period<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        if let Some((clock, budget, seconds)) = self.limit
            && clock.elapsed() > budget
        {
            return Err(SimulationError::TimeLimit {
                seconds,
                period: self.engine.counters().periods,
            });
        }
        self.report_progress();
        self.engine.run_period(period, start, observer)
    }

    fn counters(&self) -> WorkCounters {
        self.engine.counters()
    }

    fn zero_velocity_tolerance(&self) -> f64 {
        self.engine.zero_velocity_tolerance()
    }

    fn last_velocity_uncertainty(&self) -> Option<f64> {
        self.engine.last_velocity_uncertainty()
    }

    fn event_time_uncertainty(&self) -> f64 {
        self.engine.event_time_uncertainty()
    }

    fn steady_state_from_transient(&self) -> bool {
        self.engine.steady_state_from_transient()
    }

    fn carries_rod_state(&self) -> bool {
        self.engine.carries_rod_state()
    }

    fn drive_profile(
        &self,
        segments: &[crate::engine::Segment],
    ) -> Option<crate::engine::DriveProfile> {
        self.engine.drive_profile(segments)
    }

    fn boundary_state(&self) -> Option<crate::engine::DrivenState> {
        self.engine.boundary_state()
    }

    fn spring_profile(
        &self,
        start: &crate::engine::DrivenState,
        recorded: (&[crate::engine::Segment], &[crate::engine::Event]),
        periods: u64,
    ) -> Option<crate::engine::SpringProfile> {
        self.engine.spring_profile(start, recorded, periods)
    }

    fn restart_from(&mut self, state: crate::engine::DrivenState) -> bool {
        self.engine.restart_from(state)
    }
}
