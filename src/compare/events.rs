//! Events in a user's fixed-step data and their matching to the exact
//! events (docs/model.md section 1).
//!
//! Detection works on the relative velocity `v_rel = v_R - v_S` formed
//! from the user's `v_S` and the exact `v_R` at the user's times. A sample
//! is stuck when `|v_rel| <= tol` (the user's integrator sets `v_S = v_R`
//! in stick), else slipping forward (`v_rel > 0`) or backward. A change
//! between the samples `t_(i-1)` and `t_i` is an event inside
//! `[t_(i-1), t_i]`:
//! * slip to the other slip direction: a reversal;
//! * slip to stick: slip to stick;
//! * stick to slip: stick to slip.
//!
//! Its time is the zero of `v_rel` in that interval, on the polynomial
//! through the (up to) three nearest samples of the slip that the event
//! ends or begins: before the interval for a reversal and slip to stick,
//! after it for stick to slip. In slip `v_rel` is smooth (the rod's
//! velocity less a linear one), so on a trajectory sampled at step `h` the
//! zero is found to `O(h^3)` (three samples), while the kink at the event
//! itself (the slider's acceleration jumps there) is never interpolated
//! across. Without a zero in the interval (too few slip samples, or a
//! polynomial that stays on one side) the event is placed at the sample
//! where it shows, `t_i` (stick to slip: `t_(i-1)`, the last stuck one).
//! Slip out of the first sample is placed at it: when it began (a start
//! from rest at `t_0`) is not in the data, and the caller leaves it out.
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
    let rel: Vec<f64> = v_r.iter().zip(v_s).map(|(r, s)| r - s).collect();
    let state = |i: usize| {
        if rel[i].abs() <= tol {
            State::Stick
        } else if rel[i] > 0.0 {
            State::Slip(Direction::Forward)
        } else {
            State::Slip(Direction::Backward)
        }
    };
    let states: Vec<State> = (0..t.len()).map(state).collect();
    // Up to three samples of the slip `s` ending at `i` (backwards) or
    // starting at `i` (forwards).
    let side = |i: usize, forward: bool| -> Vec<usize> {
        let s = states[i];
        let mut out = vec![i];
        let mut j = i;
        while out.len() < 3 {
            j = match (forward, j) {
                (true, j) if j + 1 < t.len() => j + 1,
                (false, j) if j > 0 => j - 1,
                _ => break,
            };
            if states[j] != s {
                break;
            }
            out.push(j);
        }
        out
    };
    let mut out = Vec::new();
    for i in 1..t.len() {
        let (a, b) = (states[i - 1], states[i]);
        let (class, samples, fallback) = match (a, b) {
            (State::Slip(d), State::Slip(e)) if d != e => {
                (EventClass::Reversal(e), side(i - 1, false), t[i])
            }
            (State::Slip(_), State::Stick) => (EventClass::SlipToStick, side(i - 1, false), t[i]),
            (State::Stick, State::Slip(d)) => (EventClass::StickToSlip(d), side(i, true), t[i - 1]),
            _ => continue,
        };
        if i == 1 && a == State::Stick {
            // Slipping out of the first sample (a start from rest): when
            // it began is not in the data.
            out.push(TimedEvent { t: t[0], class });
            continue;
        }
        let points: Vec<(f64, f64)> = samples.iter().map(|&j| (t[j], rel[j])).collect();
        let time = zero_between(&points, t[i - 1], t[i]).unwrap_or(fallback);
        out.push(TimedEvent { t: time, class });
    }
    out
}

/// The zero in `[a, b]` of the polynomial through `points` (one to three
/// `(t, v)`), by bisection; `None` without a sign change there.
fn zero_between(points: &[(f64, f64)], a: f64, b: f64) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let t0 = points[0].0;
    // Newton's form in s = t - t0.
    let s: Vec<f64> = points.iter().map(|p| p.0 - t0).collect();
    let v: Vec<f64> = points.iter().map(|p| p.1).collect();
    let c1 = (v[1] - v[0]) / (s[1] - s[0]);
    let c2 = if points.len() == 3 {
        ((v[2] - v[1]) / (s[2] - s[1]) - c1) / (s[2] - s[0])
    } else {
        0.0
    };
    let p = |t: f64| {
        let x = t - t0;
        v[0] + c1 * (x - s[0]) + c2 * (x - s[0]) * (x - s[1])
    };
    let (mut lo, mut hi) = (a, b);
    let (mut p_lo, p_hi) = (p(lo), p(hi));
    if !(p_lo.is_finite() && p_hi.is_finite()) || p_lo * p_hi > 0.0 {
        return None;
    }
    if p_lo == 0.0 {
        return Some(lo);
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let p_mid = p(mid);
        if p_mid == 0.0 {
            return Some(mid);
        }
        if (p_mid > 0.0) == (p_lo > 0.0) {
            lo = mid;
            p_lo = p_mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
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
                EventKind::Grazing { .. }
                | EventKind::Jump { .. }
                | EventKind::ContactStart
                | EventKind::ContactEnd => return None,
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
    fn an_event_is_placed_at_the_zero_of_the_relative_velocity() {
        // v_rel = 1 - t^2 / 4 on the slip side (samples at t = 0, 1, 1.5),
        // then stuck at t = 2.5: its zero t = 2 lies in [1.5, 2.5].
        let t = [0.0, 1.0, 1.5, 2.5];
        let v_r = [1.0, 1.0, 1.0, 1.0];
        let v_s: Vec<f64> = t
            .iter()
            .map(|&x: &f64| if x < 2.0 { x * x / 4.0 } else { 1.0 })
            .collect();
        let ev = detect(&t, &v_s, &v_r, 1e-9);
        assert_eq!(ev.len(), 1);
        assert_eq!(ev[0].class, EventClass::SlipToStick);
        approx::assert_relative_eq!(ev[0].t, 2.0, max_relative = 1e-12);
    }

    #[test]
    fn a_reversal_with_one_sample_before_it_is_placed_where_it_shows() {
        // v_rel = 1, -1 at t = 0, 1: no slip samples to extrapolate.
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
