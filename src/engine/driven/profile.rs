//! What a driven rod's steady period asks of the amplifier, and how far
//! the rod strays from its signal (docs/model.md section 16):
//!
//! * the rod's deviation `e(t) = x_R(t) - x_sig(t)` from the signal the
//!   voltage was designed for: `max |e|` and `sqrt(mean e^2)`;
//! * the voltage's peak `max |u|` (offset included) and RMS (33) (without
//!   it);
//! * the current (21) `i = C u' + alpha v_R` with the rod's actual
//!   velocity: `max |i|` and `sqrt(mean i^2)`, which for a periodic `i`
//!   is (34) (Parseval).
//!
//! On every segment of the period the rod is the mode's particular
//! solution plus its free oscillation, so `e` and `i` are
//! exponential-trigonometric functions of the time in the segment: their
//! extrema are the segment ends and the zeros of `e'` and `i'`, all found
//! by the certified finder; the mean squares are Gauss-Legendre sums on
//! pieces short against the highest harmonic (exact to rounding for these
//! analytic functions).

use super::segment::ModeFunctions;
use crate::actuator::DrivenRod;
use crate::engine::Segment;
use crate::numerics::exp_trig::{DampedOscillator, ExpTrig, Start};
use crate::numerics::quadrature::GaussLegendre;
use crate::signal::FourierSignal;
use std::borrow::Cow;

/// The amplifier's and the rod's figures over one steady period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveProfile {
    /// `max |x_R - x_sig|` (m).
    pub rod_deviation_max: f64,
    /// `sqrt(mean (x_R - x_sig)^2)` (m).
    pub rod_deviation_rms: f64,
    /// `max |u|`, offset included (V).
    pub voltage_peak: f64,
    /// (33), without the offset (V).
    pub voltage_rms: f64,
    /// `max |C u' + alpha v_R|` (A).
    pub current_peak: f64,
    /// `sqrt(mean i^2)` over the period (A).
    pub current_rms: f64,
}

/// Gauss-Legendre points per piece.
const POINTS: usize = 12;

/// The profile of the period whose segments are `segments` (in order,
/// covering the period), with `functions(segment)` the closed forms of
/// its mode.
pub(super) fn profile<'a>(
    segments: &[Segment],
    rod: &DrivenRod,
    signal: &FourierSignal,
    functions: impl Fn(&Segment) -> Cow<'a, ModeFunctions>,
) -> DriveProfile {
    let voltage = rod.voltage();
    let period = signal.period();
    let w = signal.omega();
    let n = signal.degree().max(voltage.harmonics().count()).max(1);
    let rule = GaussLegendre::new(POINTS);
    let capacitance = rod.design().capacitance;
    let alpha = rod.real().transfer_factor;
    // u' and u'' as cos/sin coefficients.
    let (mut du, mut ddu) = ([Vec::new(), Vec::new()], [Vec::new(), Vec::new()]);
    for (k, (p, q)) in voltage.harmonics().enumerate() {
        let kw = (k + 1) as f64 * w;
        du[0].push(kw * q);
        du[1].push(-kw * p);
        ddu[0].push(-kw * kw * p);
        ddu[1].push(-kw * kw * q);
    }
    let sig = signal.coefficients();
    let (mut e_max, mut e_sq, mut i_max, mut i_sq): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
    for seg in segments.iter().filter(|s| s.end > s.start) {
        let f = functions(seg);
        let f = f.as_ref();
        let rod0 = seg.rod_start;
        let free = f.free_at(seg.start, rod0);
        let span = seg.end - seg.start;
        let deviation = |s: f64| {
            let [h, _, _] = free.eval(s);
            f.particular().position(seg.start + s) + h - signal.position(seg.start + s)
        };
        let current = |s: f64| {
            let [_, dh, _] = free.eval(s);
            let v = f.particular().velocity(seg.start + s) + dh;
            capacitance * voltage.value(seg.start + s)[1] + alpha * v
        };
        // e' = (v_p - v_sig) + h'; i' = C u'' + alpha (a_p + h'').
        let (vel, acc) = (f.velocity_coefficients(), f.acceleration_coefficients());
        let sig_vel: [Vec<f64>; 2] = {
            let (mut a, mut b) = (Vec::new(), Vec::new());
            for (k, (x, y)) in sig.cosines.iter().zip(sig.sines).enumerate() {
                let kw = (k + 1) as f64 * w;
                a.push(kw * y);
                b.push(-kw * x);
            }
            [a, b]
        };
        let de = ExpTrig {
            poly: [0.0; 3],
            w,
            phi: seg.start,
            a: difference(&vel[0], &sig_vel[0]),
            b: difference(&vel[1], &sig_vel[1]),
            osc: [Some(free.derivative()), None],
        };
        let di = ExpTrig {
            poly: [0.0; 3],
            w,
            phi: seg.start,
            a: combination(capacitance, &ddu[0], alpha, &acc[0]),
            b: combination(capacitance, &ddu[1], alpha, &acc[1]),
            osc: [Some(scaled(free.derivative().derivative(), alpha)), None],
        };
        e_max = e_max.max(extremum(&de, span, &deviation));
        i_max = i_max.max(extremum(&di, span, &current));
        let pieces = ((span / period) * 4.0 * n as f64).ceil().max(1.0) as usize;
        e_sq += rule.integrate(|s| deviation(s).powi(2), 0.0, span, pieces);
        i_sq += rule.integrate(|s| current(s).powi(2), 0.0, span, pieces);
    }
    DriveProfile {
        rod_deviation_max: e_max,
        rod_deviation_rms: (e_sq / period).sqrt(),
        voltage_peak: voltage.peak(),
        voltage_rms: voltage.rms(),
        current_peak: i_max,
        current_rms: (i_sq / period).sqrt(),
    }
}

/// `max |g|` on `[0, span]`: at the ends and at every zero of `dg`.
fn extremum(dg: &ExpTrig, span: f64, g: &impl Fn(f64) -> f64) -> f64 {
    let mut best = g(0.0).abs().max(g(span).abs());
    let tol = dg.eval_error_bound(span)[0];
    let mut from = 0.0;
    let mut start = Start::Clear;
    while let Some(c) = dg.first_zero(from, span, tol, start) {
        start = Start::AfterEvent;
        let s = c.s();
        best = best.max(g(s).abs());
        if s <= from {
            break;
        }
        from = s;
    }
    best
}

fn difference(a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..a.len().max(b.len()))
        .map(|k| a.get(k).copied().unwrap_or(0.0) - b.get(k).copied().unwrap_or(0.0))
        .collect()
}

fn combination(p: f64, a: &[f64], q: f64, b: &[f64]) -> Vec<f64> {
    (0..a.len().max(b.len()))
        .map(|k| p * a.get(k).copied().unwrap_or(0.0) + q * b.get(k).copied().unwrap_or(0.0))
        .collect()
}

fn scaled(osc: DampedOscillator, factor: f64) -> DampedOscillator {
    DampedOscillator {
        y0: osc.y0 * factor,
        y1: osc.y1 * factor,
        ..osc
    }
}
