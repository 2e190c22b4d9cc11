//! Observers that record a run: the event log and the exact trajectory.
//! The engine hands every exact [`Segment`], every [`Event`] and every
//! period end to the [`Observer`] attached to the run (the trait lives with
//! the engines, `engine/observer.rs`); what the scene did not ask for is not
//! attached, so it is neither computed nor stored.

use crate::engine::{Event, Observer, Segment};
use crate::signal::Signal;

/// Most events an [`EventLog`] keeps (10^5, a few MB; about 10 MB of
/// JSON): a long start-up (millions of periods) would otherwise fill the
/// memory. The events after these are counted, not kept.
pub const MAX_LOGGED_EVENTS: usize = 100_000;

/// Records the first [`MAX_LOGGED_EVENTS`] events (the event log) and counts
/// the rest.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EventLog {
    /// Events in time order.
    pub events: Vec<Event>,
    /// Events seen after the log was full.
    pub omitted: u64,
}

impl Observer for EventLog {
    fn wants_segments(&self) -> bool {
        false
    }
    fn event(&mut self, event: &Event) {
        if self.events.len() < MAX_LOGGED_EVENTS {
            self.events.push(*event);
        } else {
            self.omitted += 1;
        }
    }
}

/// Records every segment (the exact trajectory).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trajectory {
    /// Segments in time order.
    pub segments: Vec<Segment>,
}

impl Observer for Trajectory {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        self.segments.push(*segment);
    }
}
