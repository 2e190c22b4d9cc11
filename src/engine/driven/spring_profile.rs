//! What the spring reads over a steady orbit (docs/model.md section 17):
//! the spring's force `F_spring` and the slider's position over the `k`
//! periods of the orbit.
//!
//! * `spring_force_mean = (1 / kT) int F_spring dt`, and the position's
//!   mean likewise;
//! * `spring_force_max`, `spring_force_min`: at the segment ends and at the
//!   zeros of `F_spring' = k v_S + b a_S` inside the segments (in contact),
//!   found by the certified finder;
//! * `contact_fraction`: the time in contact with the spring over `kT` (1
//!   for a tied spring).
//!
//! On every segment the slider's motion is closed form (`slider.rs`): the
//! rod plus a constant in stick, a damped oscillator or a parabola in
//! slip. The integrals are Gauss-Legendre sums of 12 points on pieces
//! short against the highest harmonic and the slider's own oscillation
//! (exact to rounding for these analytic functions), accumulated with
//! Neumaier's compensated sum.
//!
//! ## What the profile knows of its own error
//! ([`ProfileBounds`]; docs/model.md section 17, "The reading's error")
//!
//! * **Quadrature**: the same sums on pieces halved; `|Q_p - Q_2p| / kT`
//!   bounds the error of `Q_p` (the reported one) where `Q_2p` is the
//!   more accurate, as it is for analytic integrands (the rule's error
//!   falls like `rho^(-24)` with the Bernstein ellipse `rho` of a piece,
//!   which halving the pieces widens).
//! * **Rounding**: each value of `F_spring` is summed from terms
//!   (`F_p`, `k x_S`, `b v_S`, and `x_S` itself from the segment's start
//!   and the closed form's parts, [`SliderMotion::term_magnitudes`]), and
//!   is exact to a few `eps` of their magnitudes; the compensated sum adds
//!   `2 eps` of the result. So the means carry
//!   `16 eps sum w |terms| / kT + 2 eps |mean|`, the largest and least
//!   value `16 eps |terms|` where they lie, and the contact fraction
//!   `4 eps` per segment (each span's ends to `eps T`, their sum).
//! * **Event times**: where the largest or least value lies at a segment
//!   end (an event), its value moves with the event's time error at the
//!   rate `|F_spring'|` there ([`ProfileBounds::extreme_rates`]); at a
//!   zero of `F_spring'` inside a segment it is first-order insensitive to
//!   the location's error. The contact fraction moves with each contact
//!   event's time ([`ProfileBounds::contact_changes`]).

use super::segment::ModeFunctions;
use super::slider::{SliderMotion, SpringLaw};
use super::{DrivenState, SliderState};
use crate::engine::{Direction, Event, EventKind, Kinematics, Mode, Segment};
use crate::numerics::CompensatedSum;
use crate::numerics::exp_trig::{DampedOscillator, ExpTrig, Start};
use crate::numerics::quadrature::GaussLegendre;
use crate::spring::{Spring, SpringEnd};
use std::borrow::Cow;

/// The spring's reading over a steady orbit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringProfile {
    /// The time mean of the spring's force (N).
    pub force_mean: f64,
    /// Its largest value (N).
    pub force_max: f64,
    /// Its least value (N).
    pub force_min: f64,
    /// The time mean of the slider's position from its start (m).
    pub position_mean: f64,
    /// The fraction of the time in contact with the spring.
    pub contact_fraction: f64,
    /// What the profile knows of its own error (module docs).
    pub bounds: ProfileBounds,
}

/// What a [`SpringProfile`] knows of its own error (module docs): the
/// quadrature's, the rounding's, and what the event times' errors act
/// through.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProfileBounds {
    /// `|Q_p - Q_2p| / kT` of the force's mean (N) and of the position's
    /// (m): the Gauss-Legendre sums against the same sums on pieces
    /// halved.
    pub quadrature: [f64; 2],
    /// A rounding bound on each figure, in the order `force_mean`,
    /// `force_max`, `force_min`, `position_mean`, `contact_fraction` (their
    /// units).
    pub rounding: [f64; 5],
    /// `|F_spring'|` (N/s) where the largest and where the least value lie
    /// at a segment end; 0 where they lie at a zero of `F_spring'` inside
    /// a segment.
    pub extreme_rates: [f64; 2],
    /// Contacts made or lost over the orbit (a free end's `contact_start`
    /// and `contact_end` events).
    pub contact_changes: u64,
}

/// Gauss-Legendre points per piece.
const POINTS: usize = 12;

/// The slider at a point of a segment, and the magnitudes of the terms
/// its position and velocity are summed from.
struct Point {
    x: f64,
    v: f64,
    terms: [f64; 2],
}

/// The magnitudes of the terms `F_spring` is summed from, given those of
/// the position and the velocity (`[x, v]`).
fn force_terms(spring: &Spring, [x, v]: [f64; 2]) -> f64 {
    match spring.end {
        SpringEnd::Tied { preload } => preload.abs() + spring.stiffness * x + spring.damping * v,
        SpringEnd::Free { gap } => spring.stiffness * (x + gap),
    }
}

/// A largest or least value so far: the value, its terms' magnitude and
/// the rate there (0 inside a segment).
#[derive(Clone, Copy)]
struct Extreme {
    value: f64,
    terms: f64,
    rate: f64,
}

/// The profile of the orbit whose segments and events (in order, covering
/// `periods` whole periods of length `period`) start from `start`;
/// `slip(dir)` is the slider's slip acceleration, `functions(segment,
/// contact)` the rod's closed forms on a segment with the slider in
/// contact or not.
#[allow(clippy::too_many_arguments)]
pub(super) fn profile<'a>(
    law: &SpringLaw,
    start: &DrivenState,
    (segments, events): (&[Segment], &[Event]),
    (period, periods): (f64, u64),
    slip: impl Fn(Direction) -> f64,
    functions: impl Fn(&Segment, bool) -> Cow<'a, ModeFunctions>,
) -> SpringProfile {
    let spring = law.spring;
    let rule = GaussLegendre::new(POINTS);
    let SliderState {
        x: x_first,
        contact,
    } = start.slider.unwrap_or(SliderState {
        x: 0.0,
        contact: true,
    });
    let mut contact = contact;
    let mut x_start = x_first;
    let mut current_period = segments.first().map_or(1, |s| s.period);
    let mut last_end = 0.0;
    // The means' sums on pieces and on pieces halved, and the magnitudes
    // of their terms.
    let mut force = [CompensatedSum::default(); 2];
    let mut position = [CompensatedSum::default(); 2];
    let (mut force_terms_sum, mut x_terms_sum) = (0.0, 0.0);
    let mut contact_time = 0.0;
    let mut counted = 0u64;
    let mut max = Extreme {
        value: f64::NEG_INFINITY,
        terms: 0.0,
        rate: 0.0,
    };
    let mut min = Extreme {
        value: f64::INFINITY,
        ..max
    };
    let contact_changes = events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::ContactStart | EventKind::ContactEnd))
        .count() as u64;
    let mut events = events.iter().peekable();
    for seg in segments {
        if seg.period != current_period {
            // The next period starts where this one's slider ended.
            x_start += last_end;
            current_period = seg.period;
        }
        // Contact events at or before this segment's start.
        while let Some(e) = events.peek() {
            if (e.period, e.phase) > (seg.period, seg.start) {
                break;
            }
            match e.kind {
                EventKind::ContactStart => contact = true,
                EventKind::ContactEnd => contact = false,
                _ => {}
            }
            events.next();
        }
        counted += 1;
        last_end = seg.slider_end.x;
        let span = seg.end - seg.start;
        if span <= 0.0 {
            continue;
        }
        let x0 = x_start + seg.slider_start.x;
        let f = functions(seg, contact);
        let f = f.as_ref();
        let w = f.particular().omega();
        let (state, rate): (Box<dyn Fn(f64) -> Point + '_>, ExpTrig) = match seg.mode {
            Mode::Stick => {
                let rod0 = seg.rod_start;
                let tau = seg.start;
                let at = move |s: f64| {
                    let r = f.rod_at(tau, rod0, s);
                    Point {
                        x: x0 + (r.x - rod0.x),
                        v: r.v,
                        terms: [x0.abs() + r.x.abs() + rod0.x.abs(), r.v.abs()],
                    }
                };
                (Box::new(at), law.stuck_force_rate(f, tau, rod0))
            }
            Mode::Slip(dir) => {
                let motion = law.slip(contact, x0, seg.slider_start.v, slip(dir));
                let rate = law.slip_force_rate(&motion, w);
                let at = move |s: f64| {
                    let Kinematics { x, v } = motion.at(s);
                    Point {
                        x,
                        v,
                        terms: motion.term_magnitudes(s),
                    }
                };
                (Box::new(at), rate)
            }
        };
        let force_at = |p: &Point| {
            if contact { spring.force(p.x, p.v) } else { 0.0 }
        };
        let terms_at = |p: &Point| {
            if contact {
                force_terms(&spring, p.terms)
            } else {
                0.0
            }
        };
        let n = f.particular().degree().max(1) as f64;
        let slider_rate = spring.oscillator(law.slider_mass()).omega0 / std::f64::consts::PI;
        let pieces = ((span / period) * 4.0 * n + span * slider_rate * 2.0)
            .ceil()
            .clamp(1.0, 1e6) as usize;
        for (i, p) in [pieces, 2 * pieces].into_iter().enumerate() {
            for [s, weight] in rule.points(0.0, span, p) {
                let point = state(s);
                force[i].add(weight * force_at(&point));
                position[i].add(weight * point.x);
                if i == 0 {
                    force_terms_sum += weight * terms_at(&point);
                    x_terms_sum += weight * point.terms[0];
                }
            }
        }
        if contact {
            contact_time += span;
        }
        for (s, inside) in critical_points(&rate, span, contact) {
            let point = state(s);
            let at = Extreme {
                value: force_at(&point),
                terms: terms_at(&point),
                rate: if inside || !contact {
                    0.0
                } else {
                    rate.eval(s)[0].abs()
                },
            };
            if at.value > max.value {
                max = at;
            }
            if at.value < min.value {
                min = at;
            }
        }
    }
    let total = period * periods as f64;
    let eps = f64::EPSILON;
    let [force_p, force_2p] = force.map(|s| s.value());
    let [x_p, x_2p] = position.map(|s| s.value());
    let force_mean = force_p / total;
    let position_mean = x_p / total;
    SpringProfile {
        force_mean,
        force_max: max.value,
        force_min: min.value,
        position_mean,
        contact_fraction: (contact_time / total).clamp(0.0, 1.0),
        bounds: ProfileBounds {
            quadrature: [
                (force_p - force_2p).abs() / total,
                (x_p - x_2p).abs() / total,
            ],
            rounding: [
                16.0 * eps * force_terms_sum / total + 2.0 * eps * force_mean.abs(),
                16.0 * eps * max.terms,
                16.0 * eps * min.terms,
                16.0 * eps * x_terms_sum / total + 2.0 * eps * position_mean.abs(),
                4.0 * eps * (counted as f64 + 1.0),
            ],
            extreme_rates: [max.rate, min.rate],
            contact_changes,
        },
    }
}

/// The segment's ends and, in contact, the zeros of the force's rate
/// (`true`: inside the segment).
fn critical_points(rate: &ExpTrig, span: f64, contact: bool) -> Vec<(f64, bool)> {
    let mut points = vec![(0.0, false), (span, false)];
    if !contact {
        return points;
    }
    let tol = rate.eval_error_bound(span)[0];
    let mut from = 0.0;
    let mut start = Start::Clear;
    while let Some(c) = rate.first_zero(from, span, tol, start) {
        start = Start::AfterEvent;
        let s = c.s();
        if s <= from {
            break;
        }
        points.push((s, true));
        from = s;
    }
    points
}

impl SpringLaw {
    /// `F_spring' = k v_R + b a_R` over a stick from `tau` with the rod at
    /// `rod` (the slider moves with the rod).
    pub(super) fn stuck_force_rate(
        &self,
        functions: &ModeFunctions,
        tau: f64,
        rod: Kinematics,
    ) -> ExpTrig {
        let (k, b) = (self.spring.stiffness, self.spring.damping);
        let [vel_a, vel_b] = functions.velocity_coefficients();
        let [acc_a, acc_b] = functions.acceleration_coefficients();
        let mix = |v: &[f64], a: &[f64]| -> Vec<f64> {
            v.iter().zip(a).map(|(v, a)| k * v + b * a).collect()
        };
        let h = functions.free_at(tau, rod);
        let [_, h1, h2, h3] = h.extend::<4>(&[h.y0, h.y1]);
        ExpTrig {
            poly: [0.0; 3],
            w: functions.particular().omega(),
            phi: tau,
            a: mix(vel_a, acc_a),
            b: mix(vel_b, acc_b),
            osc: [
                Some(DampedOscillator {
                    y0: k * h1 + b * h2,
                    y1: k * h2 + b * h3,
                    ..h
                }),
                None,
            ],
        }
    }

    /// `F_spring' = k v_S + b a_S` of a slip with `motion`.
    pub(super) fn slip_force_rate(&self, motion: &SliderMotion, w: f64) -> ExpTrig {
        let (k, b) = (self.spring.stiffness, self.spring.damping);
        let (poly, osc) = match *motion {
            SliderMotion::Uniform { v0, a, .. } => ([k * v0 + b * a, k * a, 0.0], None),
            SliderMotion::Oscillating { y, .. } => {
                let [_, y1, y2, y3] = y.extend::<4>(&[y.y0, y.y1]);
                (
                    [0.0; 3],
                    Some(DampedOscillator {
                        y0: k * y1 + b * y2,
                        y1: k * y2 + b * y3,
                        ..y
                    }),
                )
            }
        };
        ExpTrig::local(poly, w, osc)
    }
}
