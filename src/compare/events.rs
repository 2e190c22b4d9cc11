//! Events in a user's fixed-step data and their matching to the exact
//! events (docs/model.md section 1).
//!
//! Detection works on the relative velocity `v_rel = v_R - v_S` formed
//! from the user's `v_S` and the exact `v_R` at the user's times. A sample
//! is stuck when `|v_rel| <= tol` (the user's integrator sets `v_S = v_R`
//! in stick), else slipping forward (`v_rel > 0`) or backward. Between two
//! consecutive samples:
//! * slip to the other slip direction: a reversal, at the first sample of
//!   the new direction (a fixed-step result knows an event only to its
//!   step, and shows it at the step after it);
//! * slip to stick: slip to stick at the first stuck sample;
//! * stick to slip: stick to slip at the last stuck sample.
//!
//! The exact events of the same span are classified alike: a grazing that
//! ends in stick counts as a slip to stick; rod jumps and grazings that
//! slide on are not detectable from `v_S` and are left out. An exact event
//! is matched to the nearest unmatched user event of the same class (and,
//! for reversals and stick to slip, direction) within a quarter period;
//! the unmatched exact events are missed, the unmatched user events
//! spurious.

use super::exact::PeriodRecord;
use crate::engine::{Direction, EventKind, Mode};
use serde::Serialize;

/// What a detectable event is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum EventClass {
    /// The slider starts to slip in this direction.
    StickToSlip(Direction),
    /// The slider sticks.
    SlipToStick,
    /// The slip changes to this direction.
    Reversal(Direction),
}

/// An event at a time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TimedEvent {
    /// Time (s).
    pub t: f64,
    /// Its class.
    pub class: EventClass,
}

#[derive(Clone, Copy, PartialEq)]
enum State {
    Stick,
    Slip(Direction),
}

/// Events in the user's samples (`t`, `v_s`) with the exact rod velocity
/// `v_r` at the same times; `tol` is the stick tolerance (m/s).
pub(crate) fn detect(t: &[f64], v_s: &[f64], v_r: &[f64], tol: f64) -> Vec<TimedEvent> {
    let state = |i: usize| {
        let rel = v_r[i] - v_s[i];
        if rel.abs() <= tol {
            State::Stick
        } else if rel > 0.0 {
            State::Slip(Direction::Forward)
        } else {
            State::Slip(Direction::Backward)
        }
    };
    let mut out = Vec::new();
    for i in 1..t.len() {
        let (a, b) = (state(i - 1), state(i));
        let event = match (a, b) {
            (State::Slip(d), State::Slip(e)) if d != e => Some(TimedEvent {
                t: t[i],
                class: EventClass::Reversal(e),
            }),
            (State::Slip(_), State::Stick) => Some(TimedEvent {
                t: t[i],
                class: EventClass::SlipToStick,
            }),
            (State::Stick, State::Slip(d)) => Some(TimedEvent {
                t: t[i - 1],
                class: EventClass::StickToSlip(d),
            }),
            _ => None,
        };
        out.extend(event);
    }
    out
}

/// The exact events between `from` and `to` (s) of the walked periods, in
/// the classes of [`detect`].
pub(crate) fn exact_events(
    periods: &[PeriodRecord],
    period: f64,
    from: f64,
    to: f64,
) -> Vec<TimedEvent> {
    periods
        .iter()
        .flat_map(|r| r.events.iter())
        .filter_map(|e| {
            let t = (e.period - 1) as f64 * period + e.phase;
            let class = match e.kind {
                EventKind::StickToSlip { to } => EventClass::StickToSlip(to),
                EventKind::SlipToStick => EventClass::SlipToStick,
                EventKind::Reversal { to } => EventClass::Reversal(to),
                EventKind::Grazing { then: Mode::Stick } => EventClass::SlipToStick,
                EventKind::Grazing { .. } | EventKind::Jump { .. } => return None,
            };
            (t >= from && t <= to).then_some(TimedEvent { t, class })
        })
        .collect()
}

/// The outcome of matching.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventMatch {
    /// Exact events in the user's time span.
    pub exact: usize,
    /// Events found in the user's data.
    pub found: usize,
    /// Pairs matched.
    pub matched: usize,
    /// Exact events without a partner.
    pub missed: usize,
    /// User events without a partner.
    pub spurious: usize,
    /// Largest `|t_user - t_exact|` over the pairs (s).
    pub max_time_error: Option<f64>,
    /// RMS of `t_user - t_exact` (s).
    pub rms_time_error: Option<f64>,
    /// Mean of `t_user - t_exact` (s): a systematic lag is positive.
    pub mean_time_error: Option<f64>,
}

/// Matches `user` events to `exact` ones (both sorted by time) within
/// `window` (s).
pub(crate) fn match_events(exact: &[TimedEvent], user: &[TimedEvent], window: f64) -> EventMatch {
    let mut used = vec![false; user.len()];
    let mut errors = Vec::new();
    for e in exact {
        let start = user.partition_point(|u| u.t < e.t - window);
        let best = user[start..]
            .iter()
            .enumerate()
            .take_while(|(_, u)| u.t <= e.t + window)
            .filter(|(j, u)| !used[start + j] && u.class == e.class)
            .min_by(|(_, a), (_, b)| (a.t - e.t).abs().total_cmp(&(b.t - e.t).abs()));
        if let Some((j, u)) = best {
            used[start + j] = true;
            errors.push(u.t - e.t);
        }
    }
    let n = errors.len();
    let stats = (n > 0).then(|| {
        (
            errors.iter().fold(0.0_f64, |m, d| m.max(d.abs())),
            (errors.iter().map(|d| d * d).sum::<f64>() / n as f64).sqrt(),
            errors.iter().sum::<f64>() / n as f64,
        )
    });
    EventMatch {
        exact: exact.len(),
        found: user.len(),
        matched: n,
        missed: exact.len() - n,
        spurious: user.len() - n,
        max_time_error: stats.map(|s| s.0),
        rms_time_error: stats.map(|s| s.1),
        mean_time_error: stats.map(|s| s.2),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reversal_is_placed_at_the_first_sample_after_it() {
        // v_rel = 1, -1 at t = 0, 1: the change shows at t = 1.
        let ev = detect(&[0.0, 1.0], &[0.0, 2.0], &[1.0, 1.0], 1e-9);
        assert_eq!(ev.len(), 1);
        assert_eq!(ev[0].class, EventClass::Reversal(Direction::Backward));
        approx::assert_relative_eq!(ev[0].t, 1.0);
    }

    #[test]
    fn matching_counts_missed_and_spurious() {
        let r = |t| TimedEvent {
            t,
            class: EventClass::SlipToStick,
        };
        let m = match_events(&[r(1.0), r(5.0)], &[r(1.1), r(9.0)], 1.0);
        assert_eq!((m.matched, m.missed, m.spurious), (1, 1, 1));
        approx::assert_relative_eq!(m.max_time_error.unwrap(), 0.1, max_relative = 1e-12);
    }
}
