//! What a spring against the slider reads (docs/model.md section 17):
//! over the orbit the start-up locked into, or, where it locked into none,
//! over the periods after it.

use super::SpringReading;
use crate::analysis::Transient;
use crate::engine::{DrivenState, EventKind, PeriodEngine, PeriodStart, SpringProfile};
use crate::error::Error;
use crate::observer::{EventLog, Trajectory};

/// An orbit of whole periods run by the engine from a boundary state:
/// what the spring reads over it, and what the reading's error needs
/// (`spring_error.rs`).
#[derive(Debug, Clone)]
pub(crate) struct OrbitRun {
    /// The boundary state it starts from.
    pub start: DrivenState,
    /// The one it ends in.
    pub end: DrivenState,
    /// The periods it covers.
    pub periods: u64,
    /// The spring's reading over it.
    pub profile: SpringProfile,
    /// Its events' kinds in order: its event structure.
    pub kinds: Vec<EventKind>,
    /// The engine's largest velocity bound of one of its periods (m/s;
    /// infinite through a grazing).
    pub velocity_uncertainty: f64,
    /// The engine's largest event-time bound of one of its periods (s).
    pub event_time_uncertainty: f64,
    /// The most events one of its periods holds.
    pub events: u64,
}

impl OrbitRun {
    /// The reading of this orbit, `error` its estimate.
    pub(super) fn reading(&self, error: Option<super::SpringReadingError>) -> SpringReading {
        SpringReading {
            orbit_periods: self.periods,
            periods: self.periods,
            profile: self.profile,
            mean_range: None,
            searched: None,
            error,
        }
    }
}

/// The orbit of `periods` periods the engine runs from `start` (numbered
/// from 2 on, so that the profile sees where each period starts); `None`
/// for an engine without a boundary state or a spring.
pub(super) fn run_orbit<E: PeriodEngine>(
    engine: &mut E,
    start: DrivenState,
    periods: u64,
) -> Result<Option<OrbitRun>, Error> {
    if !engine.restart_from(start) {
        return Ok(None);
    }
    let mut segments = Trajectory::default();
    let mut events = EventLog::default();
    let mut from = PeriodStart {
        velocity: start.slider_v,
        mode: Some(start.mode),
    };
    let (mut velocity_uncertainty, mut event_time_uncertainty, mut most) = (0.0, 0.0, 0);
    for p in 0..periods {
        let before = events.events.len() + events.omitted as usize;
        let end = engine.run_period(2 + p, from, &mut (&mut segments, &mut events))?;
        let after = events.events.len() + events.omitted as usize;
        most = most.max((after - before) as u64);
        velocity_uncertainty = engine
            .last_velocity_uncertainty()
            .map_or(f64::INFINITY, |u| u.max(velocity_uncertainty));
        event_time_uncertainty = engine.event_time_uncertainty().max(event_time_uncertainty);
        from = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    let Some(end) = engine.boundary_state() else {
        return Ok(None);
    };
    Ok(engine
        .spring_profile(&start, (&segments.segments, &events.events), periods)
        .map(|profile| OrbitRun {
            start,
            end,
            periods,
            profile,
            kinds: events.events.iter().map(|e| e.kind).collect(),
            velocity_uncertainty,
            event_time_uncertainty,
            events: most,
        }))
}

/// The orbit of `periods` periods from the engine's boundary state (an
/// orbit of that many periods, the engine at its start).
pub(crate) fn orbit_reading<E: PeriodEngine>(
    engine: &mut E,
    periods: u64,
) -> Result<Option<OrbitRun>, Error> {
    match engine.boundary_state() {
        Some(start) => run_orbit(engine, start, periods),
        None => Ok(None),
    }
}

/// Periods over which a spring that did not lock is read.
const UNLOCKED_READING: u64 = 64;

/// The spring's reading over the [`UNLOCKED_READING`] periods after a
/// start-up of `simulated` periods that locked into no orbit of up to 64
/// periods (the start-up's cycle test): their mean, and the least and
/// largest mean of a single period.
pub(super) fn unlocked_reading<E: PeriodEngine>(
    engine: &mut E,
    simulated: u64,
) -> Result<Option<SpringReading>, Error> {
    let Some(start) = engine.boundary_state() else {
        return Ok(None);
    };
    let mut from = PeriodStart {
        velocity: start.slider_v,
        mode: Some(start.mode),
    };
    let (mut segments, mut events) = (Trajectory::default(), EventLog::default());
    let mut means = Vec::new();
    let mut period_start = start;
    for p in 0..UNLOCKED_READING {
        let (mut one, mut one_events) = (Trajectory::default(), EventLog::default());
        let end = engine.run_period(simulated + 1 + p, from, &mut (&mut one, &mut one_events))?;
        if let Some(profile) =
            engine.spring_profile(&period_start, (&one.segments, &one_events.events), 1)
        {
            means.push(profile.force_mean);
        }
        segments.segments.extend(one.segments);
        events.events.extend(one_events.events);
        period_start = engine.boundary_state().unwrap_or(period_start);
        from = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    let range = means
        .iter()
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], m| {
            [lo.min(*m), hi.max(*m)]
        });
    Ok(engine
        .spring_profile(
            &start,
            (&segments.segments, &events.events),
            UNLOCKED_READING,
        )
        .map(|profile| SpringReading {
            orbit_periods: 0,
            periods: UNLOCKED_READING,
            profile,
            mean_range: Some(range),
            searched: Some((64, simulated)),
            error: None,
        }))
}

/// The period of the orbit a start-up locked into, in drive periods: the
/// least `k` dividing its cycle of repeating boundary states for which the
/// boundary velocities `k` periods apart agree within `1e-9` of the
/// velocity scale over the cycle (a cycle of a few doubles, which rounding
/// makes of a period-1 orbit, is period 1).
pub(super) fn orbit_periods(transient: &Transient, scale: f64) -> u64 {
    let b = &transient.boundary_velocities;
    let cycle = (transient.cycle.max(1) as usize).min(b.len() / 2).max(1);
    let n = b.len();
    (1..=cycle)
        .find(|k| {
            cycle.is_multiple_of(*k)
                && (0..cycle)
                    .all(|i| n > i + k && (b[n - 1 - i] - b[n - 1 - i - k]).abs() <= 1e-9 * scale)
        })
        .unwrap_or(cycle) as u64
}

/// The spring's figures: their keys (in `run --json`, and the rows of
/// `check`), values and units, in the order the reports print them.
pub(crate) fn spring_figures(p: &SpringProfile) -> [(&'static str, f64, &'static str); 5] {
    [
        ("spring_force_mean", p.force_mean, "N"),
        ("spring_force_max", p.force_max, "N"),
        ("spring_force_min", p.force_min, "N"),
        ("spring_position_mean", p.position_mean, "m"),
        ("contact_fraction", p.contact_fraction, ""),
    ]
}
