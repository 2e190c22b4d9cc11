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
//! slip. The integrals are Gauss-Legendre sums on pieces short against the
//! highest harmonic and the slider's own oscillation (exact to rounding for
//! these analytic functions).

use super::segment::ModeFunctions;
use super::slider::{SliderMotion, SpringLaw};
use super::{DrivenState, SliderState};
use crate::engine::{Direction, Event, EventKind, Kinematics, Mode, Segment};
use crate::numerics::exp_trig::{DampedOscillator, ExpTrig, Start};
use crate::numerics::quadrature::GaussLegendre;
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
}

/// Gauss-Legendre points per piece.
const POINTS: usize = 12;

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
    let (mut force_int, mut x_int, mut contact_time) = (0.0, 0.0, 0.0);
    let (mut f_max, mut f_min) = (f64::NEG_INFINITY, f64::INFINITY);
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
        last_end = seg.slider_end.x;
        let span = seg.end - seg.start;
        if span <= 0.0 {
            continue;
        }
        let x0 = x_start + seg.slider_start.x;
        let f = functions(seg, contact);
        let f = f.as_ref();
        let w = f.particular().omega();
        let (state, rate): (Box<dyn Fn(f64) -> Kinematics + '_>, ExpTrig) = match seg.mode {
            Mode::Stick => {
                let rod0 = seg.rod_start;
                let tau = seg.start;
                let at = move |s: f64| {
                    let r = f.rod_at(tau, rod0, s);
                    Kinematics {
                        x: x0 + (r.x - rod0.x),
                        v: r.v,
                    }
                };
                (Box::new(at), law.stuck_force_rate(f, tau, rod0))
            }
            Mode::Slip(dir) => {
                let motion = law.slip(contact, x0, seg.slider_start.v, slip(dir));
                let rate = law.slip_force_rate(&motion, w);
                (Box::new(move |s: f64| motion.at(s)), rate)
            }
        };
        let force = |s: f64| {
            let k = state(s);
            if contact { spring.force(k.x, k.v) } else { 0.0 }
        };
        let n = f.particular().degree().max(1) as f64;
        let slider_rate = spring.oscillator(law.slider_mass()).omega0 / std::f64::consts::PI;
        let pieces = ((span / period) * 4.0 * n + span * slider_rate * 2.0)
            .ceil()
            .clamp(1.0, 1e6) as usize;
        force_int += rule.integrate(force, 0.0, span, pieces);
        x_int += rule.integrate(|s| state(s).x, 0.0, span, pieces);
        if contact {
            contact_time += span;
        }
        for s in critical_points(&rate, span, contact) {
            let v = force(s);
            f_max = f_max.max(v);
            f_min = f_min.min(v);
        }
    }
    let total = period * periods as f64;
    SpringProfile {
        force_mean: force_int / total,
        force_max: f_max,
        force_min: f_min,
        position_mean: x_int / total,
        contact_fraction: (contact_time / total).clamp(0.0, 1.0),
    }
}

/// The segment's ends and, in contact, the zeros of the force's rate.
fn critical_points(rate: &ExpTrig, span: f64, contact: bool) -> Vec<f64> {
    let mut points = vec![0.0, span];
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
        points.push(s);
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
