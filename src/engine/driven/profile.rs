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
//! pieces short against the highest harmonic and the free oscillation's
//! decay (exact to rounding for these analytic functions).
//!
//! **Restarts.** The finder's rounding bound on a function follows the
//! size of its oscillator's coefficients at the search's start. A rod
//! whose free oscillation decays within a small part of a segment (a very
//! light or heavily damped actuator) would have the decayed function
//! searched against the bound of its start, at the finder's smallest
//! pieces. So the free oscillation is restarted from the rod's state
//! `36 / r` into the segment for each of its decay rates `r` (where that
//! lies within its first half), as the engine restarts it at every event:
//! the part with that rate is then below `e^-36` of its start. An
//! over-damped oscillation far from critical keeps a slow part whose
//! higher derivatives the closed form computes with large cancellation,
//! so its rounding bound stays wide; where the searches of a profile
//! spend more than a budget of evaluations the profile is not resolved
//! (`None`), and the run says so instead of its figures.

use super::segment::ModeFunctions;
use crate::actuator::DrivenRod;
use crate::engine::Segment;
use crate::numerics::exp_trig::{DampedOscillator, ExpTrig, Start, Work};
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

/// Evaluations the searches of one profile may spend (a profile of a
/// period takes some thousands): beyond, the profile is not resolved.
const BUDGET: u64 = 2_000_000;

/// The profile of the period whose segments are `segments` (in order,
/// covering the period), with `functions(segment)` the closed forms of
/// its mode; `None` where its searches spend [`BUDGET`] (module docs,
/// "Restarts").
pub(super) fn profile<'a>(
    segments: &[Segment],
    rod: &DrivenRod,
    signal: &FourierSignal,
    functions: impl Fn(&Segment) -> Cow<'a, ModeFunctions>,
) -> Option<DriveProfile> {
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
    let mut work = Work {
        budget: BUDGET,
        ..Work::default()
    };
    for seg in segments.iter().filter(|s| s.end > s.start) {
        let f = functions(seg);
        let f = f.as_ref();
        let span = seg.end - seg.start;
        // The free oscillation restarted where its fast parts have decayed
        // (module docs, "Restarts"), so that its rounding bound follows it.
        let mut from = 0.0;
        for to in restarts(&f.free_at(seg.start, seg.rod_start), span) {
            let tau = seg.start + from;
            let rod0 = f.rod_at(seg.start, seg.rod_start, from);
            let free = f.free_at(tau, rod0);
            let span = to - from;
            from = to;
            let deviation = |s: f64| {
                let [h, _, _] = free.eval(s);
                f.particular().position(tau + s) + h - signal.position(tau + s)
            };
            let current = |s: f64| {
                let [_, dh, _] = free.eval(s);
                let v = f.particular().velocity(tau + s) + dh;
                capacitance * voltage.value(tau + s)[1] + alpha * v
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
                phi: tau,
                a: difference(&vel[0], &sig_vel[0]),
                b: difference(&vel[1], &sig_vel[1]),
                osc: [Some(free.derivative()), None],
            };
            let di = ExpTrig {
                poly: [0.0; 3],
                w,
                phi: tau,
                a: combination(capacitance, &ddu[0], alpha, &acc[0]),
                b: combination(capacitance, &ddu[1], alpha, &acc[1]),
                osc: [Some(scaled(free.derivative().derivative(), alpha)), None],
            };
            e_max = e_max.max(extremum(&de, span, &deviation, &mut work)?);
            i_max = i_max.max(extremum(&di, span, &current, &mut work)?);
            // Pieces short against the highest harmonic and the free
            // oscillation's fastest decay.
            let pieces = ((span / period) * 4.0 * n as f64)
                .max(0.5 * span * fastest_rate(&free))
                .ceil()
                .clamp(1.0, 1e5) as usize;
            e_sq += rule.integrate(|s| deviation(s).powi(2), 0.0, span, pieces);
            i_sq += rule.integrate(|s| current(s).powi(2), 0.0, span, pieces);
        }
    }
    Some(DriveProfile {
        rod_deviation_max: e_max,
        rod_deviation_rms: (e_sq / period).sqrt(),
        voltage_peak: voltage.peak(),
        voltage_rms: voltage.rms(),
        current_peak: i_max,
        current_rms: (i_sq / period).sqrt(),
    })
}

/// The ends of the pieces a segment of length `span` is searched on, the
/// last `span`: the free oscillation `free` is restarted `36 / r` after the
/// segment start for each of its decay rates `r` (the fast and the slow
/// one of an over-damped oscillation, `sigma` otherwise) where that lies
/// well inside the segment, `e^-36 < eps` of its part with that rate left.
fn restarts(free: &DampedOscillator, span: f64) -> Vec<f64> {
    let mut ends: Vec<f64> = decay_rates(free)
        .iter()
        .map(|r| 36.0 / r)
        .filter(|&s| s.is_finite() && s > 0.0 && s < 0.5 * span)
        .collect();
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    ends.push(span);
    ends
}

/// The decay rates of a free oscillation: the fast and the slow one where
/// it is over-damped, `sigma` twice otherwise.
fn decay_rates(free: &DampedOscillator) -> [f64; 2] {
    let (sigma, w0) = (free.sigma, free.omega0);
    if sigma > w0 {
        let beta = ((sigma - w0) * (sigma + w0)).sqrt();
        [sigma + beta, w0 * w0 / (sigma + beta)]
    } else {
        [sigma, sigma]
    }
}

/// The faster decay rate of a free oscillation (1/s).
fn fastest_rate(free: &DampedOscillator) -> f64 {
    decay_rates(free)[0]
}

/// `max |g|` on `[0, span]`: at the ends and at every zero of `dg`;
/// `None` where the searches spend `work`'s budget.
fn extremum(dg: &ExpTrig, span: f64, g: &impl Fn(f64) -> f64, work: &mut Work) -> Option<f64> {
    let mut best = g(0.0).abs().max(g(span).abs());
    let tol = dg.eval_error_bound(span)[0];
    let mut from = 0.0;
    let mut start = Start::Clear;
    while let Some(c) = dg.first_zero_counting(from, span, tol, start, work) {
        start = Start::AfterEvent;
        let s = c.s();
        best = best.max(g(s).abs());
        if s <= from {
            break;
        }
        from = s;
    }
    (!work.exhausted).then_some(best)
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
