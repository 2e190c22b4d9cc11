//! What an engine hands the observers of a run: every exact [`Segment`],
//! every [`Event`] and every [`PeriodEnd`], in time order. What the scene
//! did not ask for is not attached, so it is neither computed nor stored.
//!
//! Observers compose as tuples `(A, B)`; `()` observes nothing; an
//! `Option<O>` observes when it is `Some`.

use super::{Event, Mode, Segment};
use crate::signal::Signal;

/// What a period ended with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeriodEnd {
    /// Period index, 1-based.
    pub period: u64,
    /// Step `x_p = x_S(pT) - x_S((p-1)T)` (m).
    pub step: f64,
    /// Slider velocity at the period end (before any rod jump at phase 0).
    pub velocity: f64,
    /// Mode at the period end.
    pub mode: Mode,
    /// Derivative of the period map `dv_S(pT) / dv_S((p-1)T)`.
    pub map_derivative: f64,
}

/// Receives the exact motion of a run.
pub trait Observer {
    /// Whether [`Observer::segment`] does anything; when no attached
    /// observer wants segments the engine does not build them.
    fn wants_segments(&self) -> bool {
        true
    }

    /// Whether slip segments are wanted (an observer of stick time needs
    /// only stick segments); implies [`Observer::wants_segments`].
    fn wants_slip_segments(&self) -> bool {
        self.wants_segments()
    }
    /// A segment of constant mode, in time order.
    fn segment(&mut self, _segment: &Segment, _signal: &Signal) {}
    /// An event, in time order, after the segment that ends at it.
    fn event(&mut self, _event: &Event) {}
    /// The end of a period, after its last segment.
    fn period_end(&mut self, _end: &PeriodEnd) {}
}

impl Observer for () {
    fn wants_segments(&self) -> bool {
        false
    }
}

impl<A: Observer, B: Observer> Observer for (A, B) {
    #[inline]
    fn wants_segments(&self) -> bool {
        self.0.wants_segments() || self.1.wants_segments()
    }
    #[inline]
    fn wants_slip_segments(&self) -> bool {
        self.0.wants_slip_segments() || self.1.wants_slip_segments()
    }
    #[inline]
    fn segment(&mut self, segment: &Segment, signal: &Signal) {
        self.0.segment(segment, signal);
        self.1.segment(segment, signal);
    }
    #[inline]
    fn event(&mut self, event: &Event) {
        self.0.event(event);
        self.1.event(event);
    }
    #[inline]
    fn period_end(&mut self, end: &PeriodEnd) {
        self.0.period_end(end);
        self.1.period_end(end);
    }
}

impl<O: Observer> Observer for Option<O> {
    #[inline]
    fn wants_segments(&self) -> bool {
        self.as_ref().is_some_and(O::wants_segments)
    }
    #[inline]
    fn wants_slip_segments(&self) -> bool {
        self.as_ref().is_some_and(O::wants_slip_segments)
    }
    #[inline]
    fn segment(&mut self, segment: &Segment, signal: &Signal) {
        if let Some(o) = self {
            o.segment(segment, signal);
        }
    }
    #[inline]
    fn event(&mut self, event: &Event) {
        if let Some(o) = self {
            o.event(event);
        }
    }
    #[inline]
    fn period_end(&mut self, end: &PeriodEnd) {
        if let Some(o) = self {
            o.period_end(end);
        }
    }
}

impl<O: Observer + ?Sized> Observer for &mut O {
    #[inline]
    fn wants_segments(&self) -> bool {
        (**self).wants_segments()
    }
    #[inline]
    fn wants_slip_segments(&self) -> bool {
        (**self).wants_slip_segments()
    }
    #[inline]
    fn segment(&mut self, segment: &Segment, signal: &Signal) {
        (**self).segment(segment, signal);
    }
    #[inline]
    fn event(&mut self, event: &Event) {
        (**self).event(event);
    }
    #[inline]
    fn period_end(&mut self, end: &PeriodEnd) {
        (**self).period_end(end);
    }
}
