//! Rod excitation signals `x_R(t)` (docs/model.md section 2, the paper's
//! section 4).
//!
//! * `ideal`: the ideal signal (11), constant acceleration `a_R = kappa a_0`
//!   on `[0, t_1]`, rest on `(t_1, T)`; position and velocity jump back to 0
//!   at the end of the acceleration phase.
//! * `fourier`: the first `n` harmonics of the ideal signal, coefficients
//!   (12)-(14), optionally with Lanczos sigma factors (15), scaled to the
//!   stroke and shifted so that the minimum lies at `t = 0` with value 0.
//! * `harmonics`: an explicit list of harmonics `(k, d_k, phi_k)` at a given
//!   fundamental frequency, with the same optional scaling and shift.
//! * `response`: a driven rod's reference motion under a voltage given in
//!   the scene's `[voltage]`, the actuator's response as the scene computes
//!   it (`crate::actuator::GivenVoltage`): a series given by its
//!   coefficients, not scaled, not shifted.
//!
//! A [`Signal`] is periodic with period `T`. It is evaluated at a *phase*
//! `tau` in `[0, T)`; time itself is kept by the engines as
//! `(period index, phase)`. Before `t = 0` the rod rests at `x_R = 0`.
//!
//! Besides evaluation, a signal answers the questions the event engine asks:
//! where in a period `a_R(tau) - c` changes sign ([`Signal::partition`]), and
//! where the rod jumps ([`Signal::jump_phase`]).

pub(crate) mod description;
pub(crate) mod fourier;
pub(crate) mod harmonics;
pub(crate) mod ideal;
pub(crate) mod piecewise;
pub(crate) mod shape;
mod spec;

use crate::error::{Num, ParamError};
use crate::motor::Motor;
use std::cmp::Ordering;

pub use description::SignalDescription;
pub use fourier::FourierSignal;
pub(crate) use ideal::IdealSignal;
pub use shape::{Drive, Held, IdealShape, IdealTimes};
pub use spec::{MAX_HARMONICS, SignalSpec};

/// The coefficients of a series ([`FourierSignal::coefficients`]),
/// harmonic `k` at index `k - 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients<'a> {
    /// `A_k`, multiplying `cos(k w_0 t)` (m).
    pub cosines: &'a [f64],
    /// `B_k`, multiplying `sin(k w_0 t)` (m).
    pub sines: &'a [f64],
}

/// The smallest and largest rod velocity over a period (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityRange {
    /// `min v_R`.
    pub min: f64,
    /// `max v_R`.
    pub max: f64,
}

/// Sign of `a_R(tau) - c` on a piece of the period.
pub(crate) type Sign = Ordering;

/// One piece `[start, end)` of a period on which `a_R - c` has one sign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// Phase where the piece starts (s).
    pub start: f64,
    /// Phase where it ends (s); the last piece ends at `T`.
    pub end: f64,
    /// Sign of `a_R - c` inside the piece.
    pub sign: Sign,
}

/// The period `[0, T)` cut into pieces on which `a_R(tau) - c` keeps its
/// sign. Piece boundaries are the roots of `a_R = c` where the sign changes,
/// the phase of a rod jump (if any) and `0`/`T`. Adjacent pieces of equal
/// sign are merged, so a double root (a tangency) is not a boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct Partition {
    /// The threshold `c` (m/s^2).
    pub level: f64,
    /// Pieces in order, covering `[0, T)` without gaps.
    pub pieces: Vec<Piece>,
}

impl Partition {
    /// Index of the piece containing `tau` (pieces are closed on the left).
    pub fn locate(&self, tau: f64) -> usize {
        // pieces[i].start <= tau < pieces[i].end
        let idx = self.pieces.partition_point(|p| p.start <= tau);
        idx.saturating_sub(1)
    }

    /// Builds a partition from sorted roots in `[0, T)` and a sign oracle
    /// asked for each piece `(start, end)`; `breaks` are extra boundaries
    /// (jumps).
    fn from_roots(
        level: f64,
        period: f64,
        roots: &[f64],
        breaks: &[f64],
        mut sign_of: impl FnMut(f64, f64) -> Sign,
    ) -> Self {
        let mut knots: Vec<f64> = Vec::with_capacity(roots.len() + breaks.len() + 2);
        knots.push(0.0);
        knots.extend(roots.iter().copied().filter(|r| *r > 0.0 && *r < period));
        knots.extend(breaks.iter().copied().filter(|r| *r > 0.0 && *r < period));
        knots.sort_by(f64::total_cmp);
        knots.dedup();
        knots.push(period);
        let mut pieces: Vec<Piece> = Vec::with_capacity(knots.len());
        for w in knots.windows(2) {
            let (start, end) = (w[0], w[1]);
            let sign = sign_of(start, end);
            let is_break = breaks.contains(&start);
            match pieces.last_mut() {
                Some(last) if last.sign == sign && !is_break => last.end = end,
                _ => pieces.push(Piece { start, end, sign }),
            }
        }
        Partition { level, pieces }
    }
}

/// Upper bounds of `|a_R|` on `N` equal slices of the period, for bounding
/// how far the rod velocity can move over a stretch of phase without
/// evaluating it. Each slice holds the largest bound of itself and its two
/// neighbours, so that a phase whose slice index is off by one through
/// rounding is still covered.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Envelope {
    /// Width of a slice (s).
    step: f64,
    bounds: Vec<f64>,
}

impl Envelope {
    /// The envelope of `slices` (entry `i` bounds `|a_R|` on
    /// `[i T/N, (i + 1) T/N]`) over a period `period`.
    pub(crate) fn new(period: f64, slices: Vec<f64>) -> Self {
        let n = slices.len();
        let bounds = (0..n)
            .map(|i| {
                let prev = slices[(i + n - 1) % n];
                let next = slices[(i + 1) % n];
                slices[i].max(prev).max(next)
            })
            .collect();
        Self {
            step: period / n as f64,
            bounds,
        }
    }

    /// An upper bound on `∫ |a_R| dtau` over `[start, end]` within a period
    /// (`start <= end`).
    pub(crate) fn integral(&self, start: f64, end: f64) -> f64 {
        let last = self.bounds.len() - 1;
        let index = |t: f64| ((t / self.step).floor().max(0.0) as usize).min(last);
        let (i0, i1) = (index(start), index(end));
        if i0 == i1 {
            return self.bounds[i0] * (end - start);
        }
        let mut sum = self.bounds[i0] * ((i0 + 1) as f64 * self.step - start);
        for b in &self.bounds[i0 + 1..i1] {
            sum += b * self.step;
        }
        sum + self.bounds[i1] * (end - i1 as f64 * self.step)
    }
}

/// Where the rod is at an instant: position, velocity, acceleration.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RodState {
    /// `x_R` (m).
    pub x: f64,
    /// `v_R` (m/s).
    pub v: f64,
    /// `a_R` (m/s^2).
    pub a: f64,
}

/// A periodic rod signal.
// A signal is built once per scene and passed by reference; the series
// variant carries its cached roots and slices, so boxing it would only add
// an indirection to every evaluation.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Signal {
    /// The ideal signal (11).
    Ideal(IdealSignal),
    /// A finite harmonic series (8) (Fourier approximation or explicit).
    Fourier(FourierSignal),
}

impl Signal {
    /// Builds the signal a spec describes for this motor (`kappa` refers to
    /// the motor's `a_0`). Validates the spec first.
    pub fn build(spec: &SignalSpec, motor: &Motor) -> Result<Self, ParamError> {
        spec.validate()?;
        // A frequency fixes the period whatever the motor; kappa needs a_0.
        if let Some(
            shape @ IdealShape {
                drive: Drive::Kappa(_),
                ..
            },
        ) = spec.shape()
        {
            let a_r = shape.a_r(motor);
            let period = shape.times(motor).period;
            if !(a_r > 0.0 && period.is_finite() && period > 0.0) {
                return Err(ParamError::Inconsistent {
                    field: "signal.kappa".to_owned(),
                    reason: format!(
                        "the rod acceleration a_R = kappa a_0 = {} m/s^2 gives the period \
                         T = {} s; a kappa-based signal needs a_0 = mu_0 F_c / m_s > 0 \
                         (for a motor without friction give signal.frequency instead)",
                        Num(a_r),
                        Num(period)
                    ),
                });
            }
        }
        let signal = match spec {
            SignalSpec::Ideal(shape) => Signal::Ideal(IdealSignal::new(*shape, motor)),
            SignalSpec::Fourier {
                shape,
                harmonics,
                sigma,
            } => Signal::Fourier(FourierSignal::approximate_ideal(
                *shape, *harmonics, *sigma, motor,
            )?),
            SignalSpec::Harmonics {
                frequency,
                amplitudes,
                phases,
                scale_to_stroke,
                shift_to_minimum,
            } => Signal::Fourier(harmonics::build(
                *frequency,
                amplitudes,
                phases,
                *scale_to_stroke,
                *shift_to_minimum,
            )?),
            SignalSpec::Response {
                frequency,
                offset,
                cosines,
                sines,
            } => Signal::Fourier(FourierSignal::from_coefficients(
                1.0 / frequency,
                *offset,
                cosines.clone(),
                sines.clone(),
            )),
        };
        let signal = match signal {
            Signal::Fourier(s) => Signal::Fourier(s.with_fast_evaluation()),
            ideal => ideal,
        };
        // Position, velocity and acceleration must be representable.
        let scale = signal.velocity_scale() * signal.period();
        let (_, a_max) = signal.acceleration_bound();
        if !(scale.is_finite() && a_max.is_finite() && signal.period().is_finite()) {
            return Err(ParamError::Inconsistent {
                field: "signal".to_owned(),
                reason: format!(
                    "the rod acceleration (up to {} m/s^2) or velocity is not \
                     representable in double precision; choose a lower frequency or amplitude",
                    Num(a_max)
                ),
            });
        }
        Ok(signal)
    }

    /// A bound on `|a_R|` over a period: `(0, sum k^2 w^2 d_k)` for a
    /// series, `(0, |a_R|)` for the ideal signal.
    pub(crate) fn acceleration_bound(&self) -> (f64, f64) {
        match self {
            Signal::Ideal(s) => (0.0, s.a_r().abs()),
            Signal::Fourier(s) => (0.0, s.acceleration_bound()),
        }
    }

    /// A position scale for rounding bounds: the stroke of the ideal
    /// signal, `max |v_R| T / pi` for a series (the stroke of one harmonic).
    pub fn position_scale(&self) -> f64 {
        match self {
            Signal::Ideal(s) => 0.5 * s.a_r().abs() * s.t1() * s.t1(),
            Signal::Fourier(_) => self.velocity_scale() * self.period() / std::f64::consts::PI,
        }
    }

    /// Period `T` (s).
    pub fn period(&self) -> f64 {
        match self {
            Signal::Ideal(s) => s.period(),
            Signal::Fourier(s) => s.period(),
        }
    }

    /// Fundamental frequency `f_0 = 1/T` (Hz).
    pub fn f0(&self) -> f64 {
        1.0 / self.period()
    }

    /// Highest frequency in the signal, `f_max = n f_0` (37); `None` for the
    /// ideal signal, whose spectrum is unbounded.
    pub fn f_max(&self) -> Option<f64> {
        match self {
            Signal::Ideal(_) => None,
            Signal::Fourier(s) => Some(s.degree() as f64 * s.f0()),
        }
    }

    /// Position, velocity and acceleration at phase `tau` in `[0, T)`; at a
    /// jump the value right after it.
    #[inline]
    pub fn state(&self, tau: f64) -> RodState {
        match self {
            Signal::Ideal(s) => s.state(tau),
            Signal::Fourier(s) => s.state(tau),
        }
    }

    /// Velocity and acceleration at phase `tau` (the engine's hot path).
    #[inline]
    pub(crate) fn velocity_acceleration(&self, tau: f64) -> (f64, f64) {
        match self {
            Signal::Ideal(s) => {
                let st = s.state(tau);
                (st.v, st.a)
            }
            Signal::Fourier(s) => s.velocity_acceleration(tau),
        }
    }

    /// Rod velocity at phase `tau`.
    #[inline]
    pub fn velocity(&self, tau: f64) -> f64 {
        match self {
            Signal::Ideal(s) => s.state(tau).v,
            Signal::Fourier(s) => s.velocity(tau),
        }
    }

    /// Rod position at phase `tau`.
    #[inline]
    pub fn position(&self, tau: f64) -> f64 {
        match self {
            Signal::Ideal(s) => s.state(tau).x,
            Signal::Fourier(s) => s.position(tau),
        }
    }

    /// Rod acceleration at phase `tau`.
    #[inline]
    pub fn acceleration(&self, tau: f64) -> f64 {
        match self {
            Signal::Ideal(s) => s.state(tau).a,
            Signal::Fourier(s) => s.acceleration(tau),
        }
    }

    /// Rod jerk `da_R/dt` at phase `tau` (0 for the piecewise constant
    /// acceleration of the ideal signal, away from its jumps).
    pub fn jerk(&self, tau: f64) -> f64 {
        match self {
            Signal::Ideal(_) => 0.0,
            Signal::Fourier(s) => s.jerk(tau),
        }
    }

    /// State just before the phase `tau` (the left limit); differs from
    /// [`Signal::state`] only at a jump. `tau = T` gives the end of a period.
    pub fn state_before(&self, tau: f64) -> RodState {
        match self {
            Signal::Ideal(s) => s.state_before(tau),
            Signal::Fourier(s) => s.state(if tau >= s.period() { 0.0 } else { tau }),
        }
    }

    /// Velocity just before phase `tau` (the left limit; `tau = T` gives the
    /// end of a period).
    #[inline]
    pub fn velocity_before(&self, tau: f64) -> f64 {
        match self {
            Signal::Ideal(s) => s.state_before(tau).v,
            Signal::Fourier(s) => s.velocity(if tau >= s.period() { 0.0 } else { tau }),
        }
    }

    /// The phase in `[0, T)` at which position and velocity jump (ideal
    /// signals only): `t_1` for a discrete signal, `0` for a continuous one.
    /// The jump at phase 0 does not happen at `t = 0`, where the rod starts
    /// from rest.
    pub fn jump_phase(&self) -> Option<f64> {
        match self {
            Signal::Ideal(s) => Some(s.jump_phase()),
            Signal::Fourier(_) => None,
        }
    }

    /// Where `a_R(tau) - level` changes sign within a period. Root finding on
    /// the analytic signal, never sampling; the sign of each piece is taken
    /// at its midpoint. For a series, where `a_R - level` there lies within
    /// the rounding margin of `Signal::partition_margin` (the midpoint of
    /// a piece on which `a_R` comes close to the level without crossing
    /// it), it is taken where `abs(a_R - level)` is largest among the seven
    /// points `start + k (end - start) / 8`, if that is beyond the margin.
    pub fn partition(&self, level: f64) -> Partition {
        let period = self.period();
        match self {
            Signal::Ideal(s) => {
                let breaks: Vec<f64> = s.piece_boundaries();
                Partition::from_roots(level, period, &[], &breaks, |start, end| {
                    s.state(0.5 * (start + end)).a.total_cmp(&level)
                })
            }
            Signal::Fourier(s) => {
                let roots = s.acceleration_roots(level);
                let margin = s.partition_margin(level);
                Partition::from_roots(level, period, &roots, &[], |start, end| {
                    let a = s.acceleration(0.5 * (start + end));
                    if (a - level).abs() > margin {
                        return a.total_cmp(&level);
                    }
                    let off = |x: f64| (x - level).abs();
                    let farthest = (1..8)
                        .map(|k| s.acceleration(start + (end - start) * k as f64 / 8.0))
                        .max_by(|x, y| off(*x).total_cmp(&off(*y)))
                        .unwrap_or(a);
                    if off(farthest) > margin {
                        farthest.total_cmp(&level)
                    } else {
                        a.total_cmp(&level)
                    }
                })
            }
        }
    }

    /// A margin beyond which the sign of a computed `a_R(tau) - level`
    /// ([`Signal::acceleration`]) is the sign of the piece of
    /// [`Signal::partition`] of `level` that holds `tau`, so that the
    /// evaluation can stand in for the partition; `None` for the ideal
    /// signal, whose partitions cost nothing.
    pub(crate) fn partition_margin(&self, level: f64) -> Option<f64> {
        match self {
            Signal::Ideal(_) => None,
            Signal::Fourier(s) => Some(s.partition_margin(level)),
        }
    }

    /// Smallest and largest rod velocity over a period, exact (from the
    /// roots of `a_R`; for the ideal signal `0` and `a_R t_1`).
    pub fn velocity_range(&self) -> VelocityRange {
        match self {
            Signal::Ideal(s) => {
                let v = s.a_r() * s.t1();
                VelocityRange {
                    min: v.min(0.0),
                    max: v.max(0.0),
                }
            }
            Signal::Fourier(s) => s.velocity_range(),
        }
    }

    /// Bounds `(lo, hi)` on `a_R` over the phases `[p, q]` (`0 <= p <= q <=
    /// T`), rounding included, given the computed `a_p = a_R(p)` and
    /// `a_q = a_R(q)`: for a series `|a_R'| <= J` (the jerk bound) gives
    /// `a_R <= (a_p + a_q) / 2 + J (q - p) / 2` and the mirror image, each
    /// widened by the evaluation's rounding; the ideal signal's acceleration
    /// is piecewise constant, and the bounds are the values of the pieces
    /// that meet `[p, q]`.
    pub(crate) fn acceleration_range(&self, p: f64, q: f64, a_p: f64, a_q: f64) -> (f64, f64) {
        match self {
            Signal::Ideal(s) => {
                // a_r on [0, t_1), 0 on [t_1, T); t_1 = T for the continuous
                // signal.
                let mut values = [None, None];
                if p < s.t1() {
                    values[0] = Some(s.a_r());
                }
                if q >= s.t1() {
                    values[1] = Some(0.0);
                }
                let lo = values
                    .iter()
                    .flatten()
                    .copied()
                    .fold(f64::INFINITY, f64::min);
                let hi = values
                    .iter()
                    .flatten()
                    .copied()
                    .fold(f64::NEG_INFINITY, f64::max);
                (lo, hi)
            }
            Signal::Fourier(s) => {
                let r = s.acceleration_rounding();
                let half = 0.5 * s.jerk_bound() * (q - p);
                let mid = 0.5 * (a_p + a_q);
                (
                    (mid - half).min(a_p.min(a_q)) - r,
                    (mid + half).max(a_p.max(a_q)) + r,
                )
            }
        }
    }

    /// The [`Envelope`] of `|a_R|`: for the ideal signal `|a_R|` over the
    /// whole period; for a series the bounds of the root finder's Taylor
    /// models on `~pi n / 2` slices (`FourierSignal::acceleration_slices`).
    pub(crate) fn acceleration_envelope(&self) -> Envelope {
        match self {
            Signal::Ideal(s) => Envelope::new(s.period(), vec![s.a_r().abs()]),
            Signal::Fourier(s) => Envelope::new(s.period(), s.acceleration_slices()),
        }
    }

    /// A bound on the rounding error of a computed rod velocity
    /// ([`Signal::velocity`], [`Signal::velocity_before`]) at any phase:
    /// for a series see `FourierSignal::velocity_rounding`; for the ideal
    /// signal `v_R = a_R tau` is one product, bounded by `8 ε |a_R| T`.
    pub(crate) fn velocity_rounding(&self) -> f64 {
        match self {
            Signal::Ideal(s) => 8.0 * f64::EPSILON * s.a_r().abs() * s.period(),
            Signal::Fourier(s) => s.velocity_rounding(),
        }
    }

    /// Largest magnitude of the rod velocity over a period.
    pub fn velocity_scale(&self) -> f64 {
        let VelocityRange { min: lo, max: hi } = self.velocity_range();
        lo.abs().max(hi.abs())
    }

    /// The same signal mirrored: `x_R -> stroke - x_R` is not periodic-start
    /// preserving in general, so the mirror is taken as `x_R -> -x_R`,
    /// which reverses the direction of motion (docs/model.md section 7).
    pub fn mirrored(&self) -> Signal {
        match self {
            Signal::Ideal(s) => Signal::Ideal(s.mirrored()),
            Signal::Fourier(s) => Signal::Fourier(s.mirrored()),
        }
    }
}
