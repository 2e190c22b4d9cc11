//! The exact solution at arbitrary times: the start-up from rest walked
//! period by period with the event engine (docs/model.md sections 1, 8),
//! and the slider state at any instant taken in closed form from the
//! segment that contains it: in slip the slider's acceleration is constant,
//! in stick it moves with the rod. Nothing is interpolated.
//!
//! Time `t` lies in period `p = floor(t / T) + 1` at phase
//! `tau = t - (p - 1) T`; slider positions are absolute (the sum of the
//! steps of the earlier periods, compensated, plus the position within the
//! period).

use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{Event, EventKind, Mode, PeriodEngine, PeriodStart, Segment};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::numerics::CompensatedSum;
use crate::observer::{EventLog, Trajectory};
use crate::signal::Signal;

/// The exact state of rod and slider at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ExactState {
    /// Time (s).
    pub t: f64,
    /// Rod position `x_R` (m).
    pub x_r: f64,
    /// Rod velocity `v_R` (m/s).
    pub v_r: f64,
    /// Rod acceleration `a_R` (m/s^2).
    pub a_r: f64,
    /// Slider position `x_S` (m), from `x_S(0) = 0`.
    pub x_s: f64,
    /// Slider velocity `v_S` (m/s).
    pub v_s: f64,
    /// The slider's mode at `t`.
    pub mode: Mode,
}

/// One simulated period with what the walk recorded of it.
#[derive(Debug, Clone)]
pub(crate) struct PeriodRecord {
    /// Period index, 1-based.
    pub period: u64,
    /// Slider position at the period start (m).
    pub x_start: f64,
    /// Step `x_p` (m).
    pub step: f64,
    /// Mean velocity `v_p = x_p / T` (m/s).
    pub v_p: f64,
    /// Time stuck in the period (s).
    pub stick_time: f64,
    /// Events of the period, in time order.
    pub events: Vec<Event>,
    /// Segments of the period, when asked for.
    pub segments: Vec<Segment>,
}

/// Walks the start-up from rest period by period.
pub(crate) struct Walker<'s> {
    engine: EventEngine<'s>,
    signal: &'s Signal,
    start: PeriodStart,
    position: CompensatedSum,
    next: u64,
}

impl<'s> Walker<'s> {
    /// A walk from rest at `t = 0` with the event engine's default options.
    pub(crate) fn new(signal: &'s Signal, motor: &Motor) -> Self {
        Self {
            engine: EventEngine::new(signal, motor, EventOptions::default()),
            signal,
            start: PeriodStart {
                velocity: 0.0,
                mode: None,
            },
            position: CompensatedSum::default(),
            next: 1,
        }
    }

    /// Simulates the next period, keeping its segments (a handful per
    /// period) so that states inside it can be evaluated.
    pub(crate) fn next_period(&mut self) -> Result<PeriodRecord, SimulationError> {
        let mut observer = (Trajectory::default(), EventLog::default());
        let p = self.next;
        let end = self.engine.run_period(p, self.start, &mut observer)?;
        let (trajectory, log) = observer;
        let segments = trajectory.segments;
        let stick_time = segments
            .iter()
            .filter(|s| s.mode == Mode::Stick)
            .map(Segment::duration)
            .fold(0.0, |a, b| a + b);
        let x_start = self.position.value();
        self.position.add(end.step);
        self.start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
        self.next += 1;
        Ok(PeriodRecord {
            period: p,
            x_start,
            step: end.step,
            v_p: end.step / self.signal.period(),
            stick_time,
            events: log.events,
            segments,
        })
    }
}

/// The segment of `record` containing phase `tau` (the last one at the
/// period end).
fn segment_at(record: &PeriodRecord, tau: f64) -> &Segment {
    let i = record.segments.partition_point(|s| s.end < tau);
    &record.segments[i.min(record.segments.len() - 1)]
}

/// The exact state at phase `tau` of a period whose segments were kept.
pub(crate) fn state_in(record: &PeriodRecord, signal: &Signal, tau: f64) -> ExactState {
    let period = signal.period();
    let tau = tau.clamp(0.0, period);
    let seg = segment_at(record, tau);
    let rod = if tau >= period {
        signal.state_before(period)
    } else {
        signal.state(tau)
    };
    let (x, v) = match seg.mode {
        Mode::Stick => (seg.slider_start.x + (rod.x - seg.rod_start.x), rod.v),
        Mode::Slip(_) => {
            let dt = tau - seg.start;
            let a = seg.slip_acceleration;
            (
                seg.slider_start.x + seg.slider_start.v * dt + 0.5 * a * dt * dt,
                seg.slider_start.v + a * dt,
            )
        }
    };
    ExactState {
        t: (record.period - 1) as f64 * period + tau,
        x_r: rod.x,
        v_r: rod.v,
        a_r: rod.a,
        x_s: record.x_start + x,
        v_s: v,
        mode: seg.mode,
    }
}

/// Period index (1-based) and phase of time `t >= 0`.
pub(crate) fn locate(t: f64, period: f64) -> (u64, f64) {
    let p = (t / period).floor().max(0.0);
    let tau = t - p * period;
    if tau >= period {
        (p as u64 + 2, tau - period)
    } else {
        (p as u64 + 1, tau.max(0.0))
    }
}

/// What [`evaluate`] returns: the states at the requested times and every
/// period walked up to the last one needed.
#[derive(Debug, Clone)]
pub(crate) struct ExactSeries {
    /// States at the requested times, in their order.
    pub states: Vec<ExactState>,
    /// Periods `1..=last`, segments dropped.
    pub periods: Vec<PeriodRecord>,
}

/// The exact states at the sorted times `times` (s, `>= 0`), walking the
/// start-up from rest through at least `min_periods` periods. The segments
/// of a period are dropped once its samples are evaluated.
pub(crate) fn evaluate(
    signal: &Signal,
    motor: &Motor,
    times: &[f64],
    min_periods: u64,
) -> Result<ExactSeries, SimulationError> {
    let period = signal.period();
    let mut walker = Walker::new(signal, motor);
    let mut states = Vec::with_capacity(times.len());
    let mut periods = Vec::new();
    let last_needed = times
        .last()
        .map_or(0, |&t| locate(t, period).0)
        .max(min_periods);
    let mut i = 0;
    for p in 1..=last_needed {
        let mut record = walker.next_period()?;
        while let Some(&t) = times.get(i) {
            let (q, tau) = locate(t, period);
            if q != p {
                break;
            }
            states.push(state_in(&record, signal, tau));
            i += 1;
        }
        record.segments = Vec::new();
        periods.push(record);
    }
    Ok(ExactSeries { states, periods })
}

/// The short name of an event kind, as in the `event_log` of `run --json`.
pub(crate) fn event_name(kind: &EventKind) -> &'static str {
    kind.name()
}
