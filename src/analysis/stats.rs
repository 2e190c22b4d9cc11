//! Per-period statistics (docs/model.md section 3): an observer that
//! turns the exact segments of a period into its step `x_p`, mean velocity
//! `v_p`, exact velocity extrema (segment ends, and in stick the zeros of
//! `a_R`), sliding distance `integral |v_R - v_S| dt` (plus `|delta x_R|` at
//! rod jumps) and time in stick.

use crate::engine::{EventCounts, Mode, PeriodEngine, Segment};
use crate::engine::{Observer, PeriodEnd};
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

    /// An observer for `engine`'s periods: an engine that carries a rod
    /// state cuts its stick segments at the zeros of the rod's own
    /// acceleration ([`PeriodEngine::carries_rod_state`]), so the
    /// segment ends hold every velocity extremum and the signal's are not
    /// used.
    pub fn for_engine<E: PeriodEngine>(engine: &E, wanted: StatsWanted) -> Self {
        let mut stats = Self::new(
            engine.signal(),
            StatsWanted {
                smoothness: false,
                ..wanted
            },
        );
        stats.wanted = wanted;
        if wanted.smoothness && !engine.carries_rod_state() {
            stats.accel_zeros = Some(engine.signal().partition(0.0));
        }
        stats
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
