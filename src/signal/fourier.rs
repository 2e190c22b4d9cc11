//! Frequency-limited signals: finite harmonic series (8)-(10),
//!
//! ```text
//! x_R(t) = c_0 + sum_{k=1}^{n} ( A_k cos(k w_0 t) + B_k sin(k w_0 t) ),
//! ```
//!
//! which is the paper's harmonic form (5) with `d_k = sqrt(A_k^2 + B_k^2)`
//! and `phi_k = atan2(A_k, B_k)` (7). Velocity, acceleration and jerk are the
//! term-wise derivatives, all evaluated with one `sin_cos` call and the
//! angle-addition recurrence.
//!
//! [`FourierSignal::approximate_ideal`] builds the paper's signals: the
//! coefficients (12)-(14) of the ideal signal (11), optionally multiplied by
//! the modified Lanczos sigma factors (15), `sigma_k(n) = sinc(k pi/(n+1))`,
//! then scaled so that `max x_R - min x_R` equals the stroke and shifted so
//! that the minimum lies at `t = 0` with value 0 (section 4). Extrema come
//! from the roots of `v_R` (a trigonometric polynomial), never from sampling.

use super::IdealShape;
use super::RodState;
use super::piecewise::{MIN_HARMONICS, Piecewise};
use super::{Coefficients, IdealTimes, VelocityRange};
use crate::error::{Num, ParamError};
use crate::motor::Motor;
use crate::numerics::bracket;
use crate::numerics::trig_roots::{LevelRoots, TrigPoly};
use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};

/// A finite harmonic series with period `T`.
#[derive(Debug, Clone)]
pub struct FourierSignal {
    period: f64,
    omega: f64,
    c0: f64,
    /// Cosine coefficients `A_k`, k = 1..=n (m).
    cos: Vec<f64>,
    /// Sine coefficients `B_k`, k = 1..=n (m).
    sin: Vec<f64>,
    /// Precomputed `k w A_k`, `k w B_k` (velocity) and `k^2 w^2 A_k`,
    /// `k^2 w^2 B_k` (acceleration) for the hot path.
    vel: Vec<(f64, f64)>,
    acc: Vec<(f64, f64)>,
    /// Phases of the roots of `a_R` (the extrema of `v_R`) and bounds on
    /// `|a_R|` on slices of the period, found once on demand.
    acceleration_zeros: OnceLock<(Vec<f64>, Vec<f64>)>,
    /// The root finder of `a_R = c` shared by every threshold `c`.
    acceleration_levels: OnceLock<Box<LevelRoots>>,
    /// `min v_R` and `max v_R`, from the roots of `a_R`, found once: every
    /// rounding bound and the engine's tolerances scale with them.
    velocity_range: OnceLock<VelocityRange>,
    /// The extrema of `x_R` (from the roots of `v_R`), found once.
    extrema: OnceLock<Extrema>,
    /// Taylor polynomials on slices of the period, used for every
    /// evaluation when present ([`FourierSignal::with_fast_evaluation`]).
    fast: Option<Arc<Piecewise>>,
}

impl PartialEq for FourierSignal {
    /// Equal series: same period and coefficients.
    fn eq(&self, other: &Self) -> bool {
        self.period == other.period
            && self.c0 == other.c0
            && self.cos == other.cos
            && self.sin == other.sin
    }
}

/// Extrema of `x_R` over a period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extrema {
    /// Phase of the minimum (s).
    pub tau_min: f64,
    /// Minimum value (m).
    pub min: f64,
    /// Phase of the maximum (s).
    pub tau_max: f64,
    /// Maximum value (m).
    pub max: f64,
}

/// The modified Lanczos sigma factor (15): `sigma_k(n) = sinc(k pi / (n+1))`.
pub(crate) fn sigma_factor(k: usize, n: usize) -> f64 {
    let x = k as f64 * PI / (n as f64 + 1.0);
    x.sin() / x
}

/// Fourier coefficients (12)-(14) of the ideal signal (11) with
/// acceleration `a_r`, acceleration time `t1` and period `period`:
/// returns `(a_0 / 2, [a_k], [b_k])` for `k = 1..=n`, where `a_k` multiplies
/// `cos(k w_0 t)` and `b_k` multiplies `sin(k w_0 t)`.
pub(crate) fn ideal_coefficients(
    a_r: f64,
    t1: f64,
    period: f64,
    n: usize,
) -> (f64, Vec<f64>, Vec<f64>) {
    // a_R t_1^3 / (6 T), ordered so that no intermediate overflows.
    let offset = a_r * t1 * t1 * (t1 / period) / 6.0;
    let mut a = Vec::with_capacity(n);
    let mut b = Vec::with_capacity(n);
    for k in 1..=n {
        let kf = k as f64;
        let (s, c) = (2.0 * PI * kf * t1 / period).sin_cos();
        let p = period * t1 / (PI * kf * kf);
        let q = t1 * t1 / kf - period * period / (2.0 * PI * PI * kf.powi(3));
        let r = period * period / (2.0 * PI * PI * kf.powi(3));
        a.push(a_r / (2.0 * PI) * (p * c + q * s));
        b.push(a_r / (2.0 * PI) * (p * s - q * c - r));
    }
    (offset, a, b)
}

impl FourierSignal {
    /// A series from its coefficients: `x_R = c0 + sum A_k cos + B_k sin`.
    /// Trailing zero harmonics are dropped. The caller guarantees a positive
    /// finite period and finite coefficients.
    pub fn from_coefficients(period: f64, c0: f64, mut cos: Vec<f64>, mut sin: Vec<f64>) -> Self {
        assert_eq!(cos.len(), sin.len(), "one sine per cosine coefficient");
        while cos.len() > 1 && cos.last() == Some(&0.0) && sin.last() == Some(&0.0) {
            cos.pop();
            sin.pop();
        }
        let omega = 2.0 * PI / period;
        let vel = (1..=cos.len())
            .map(|k| {
                let w = k as f64 * omega;
                (w * cos[k - 1], w * sin[k - 1])
            })
            .collect();
        let acc = (1..=cos.len())
            .map(|k| {
                let w2 = (k as f64 * omega).powi(2);
                (w2 * cos[k - 1], w2 * sin[k - 1])
            })
            .collect();
        Self {
            period,
            omega,
            c0,
            cos,
            sin,
            vel,
            acc,
            acceleration_zeros: OnceLock::new(),
            acceleration_levels: OnceLock::new(),
            velocity_range: OnceLock::new(),
            extrema: OnceLock::new(),
            fast: None,
        }
    }

    /// The same series, evaluated from here on through Taylor polynomials
    /// on slices of the period (module `piecewise`, docs/model.md section
    /// 8) if it has at least `piecewise::MIN_HARMONICS` harmonics: the
    /// values differ from the recurrence's by rounding only, and cost
    /// `O(1)` instead of `O(n)`. Call it on a finished signal, before any
    /// of its kept quantities (roots of `a_R`, velocity range, extrema) is
    /// found, so that they come from the same evaluation.
    pub(crate) fn with_fast_evaluation(mut self) -> Self {
        if self.cos.len() >= MIN_HARMONICS {
            self.fast = Some(Arc::new(Piecewise::new(
                self.omega, self.c0, &self.cos, &self.sin,
            )));
            self.acceleration_zeros = OnceLock::new();
            self.velocity_range = OnceLock::new();
            self.extrema = OnceLock::new();
        }
        self
    }

    /// Phases in `[0, T)` where `a_R = level`, sorted: the roots of a
    /// trigonometric polynomial. Every level shares the Taylor models of
    /// `a_R` (`numerics::LevelRoots`); the roots of `a_R = 0` are kept once
    /// found.
    pub fn acceleration_roots(&self, level: f64) -> Vec<f64> {
        if level == 0.0 {
            return self.acceleration_zeros().0.clone();
        }
        self.acceleration_levels()
            .roots(level)
            .into_iter()
            .map(|theta| theta / self.omega)
            .collect()
    }

    /// The root finder of `a_R = level` for every level, built once.
    fn acceleration_levels(&self) -> &LevelRoots {
        self.acceleration_levels
            .get_or_init(|| Box::new(self.acceleration_poly().levels()))
    }

    /// The roots of `a_R` (phases) and the envelope of `|a_R|` on `N` equal
    /// slices of the period from the same Taylor models
    /// (`TrigPoly::roots_and_envelope`), found once.
    fn acceleration_zeros(&self) -> &(Vec<f64>, Vec<f64>) {
        self.acceleration_zeros.get_or_init(|| {
            let found = self.acceleration_levels().roots_and_envelope(0.0);
            let (roots, bounds) = (found.roots, found.envelope);
            let phases = roots.into_iter().map(|theta| theta / self.omega).collect();
            (phases, bounds)
        })
    }

    /// Bounds on `|a_R|` on `N` equal slices of the period (entry `i` for
    /// phases in `[i T/N, (i + 1) T/N]`), each at most
    /// [`FourierSignal::acceleration_bound`]. Found with the roots of `a_R`.
    pub(crate) fn acceleration_slices(&self) -> Vec<f64> {
        let cap = self.acceleration_bound();
        self.acceleration_zeros()
            .1
            .iter()
            .map(|b| b.min(cap))
            .collect()
    }

    /// Smallest and largest rod velocity over a period, exact: the values at
    /// the roots of `a_R`. Found once (`O(n^2)`), then kept.
    pub fn velocity_range(&self) -> VelocityRange {
        *self.velocity_range.get_or_init(|| {
            let mut lo = self.velocity(0.0);
            let mut hi = lo;
            for tau in self.acceleration_roots(0.0) {
                let v = self.velocity(tau);
                lo = lo.min(v);
                hi = hi.max(v);
            }
            VelocityRange { min: lo, max: hi }
        })
    }

    /// The first `n` harmonics of the ideal signal of `shape`, with sigma
    /// factors if asked, scaled to the stroke and shifted to the minimum.
    pub fn approximate_ideal(
        shape: IdealShape,
        n: usize,
        sigma: bool,
        motor: &Motor,
    ) -> Result<Self, ParamError> {
        let raw = Self::partial_sum(shape, n, sigma, motor);
        let stroke = raw.stroke();
        if !(stroke.is_finite() && stroke > 0.0) && shape.duty < 1.0 {
            // The coefficients (12)-(14) of so short a rise leave floating
            // point (they overflow, or the harmonics cancel to nothing).
            return Err(ParamError::out_of_range(
                "signal.duty",
                shape.duty,
                "a rise this short leaves the harmonics without a stroke in floating point; \
                 give a longer rise",
            ));
        }
        raw.scaled_to_stroke(shape.stroke)?.shifted_to_minimum()
    }

    /// The unscaled, unshifted partial sum (8) of the ideal signal with the
    /// coefficients (12)-(14), times sigma factors (15) if asked. This is
    /// the signal whose Gibbs overshoot section 4 discusses.
    pub fn partial_sum(shape: IdealShape, n: usize, sigma: bool, motor: &Motor) -> Self {
        let shape = shape.resolved(n);
        let IdealTimes { t1, period } = shape.times(motor);
        let t1 = if shape.duty == 1.0 { period } else { t1 };
        let (offset, mut a, mut b) = ideal_coefficients(shape.a_r(motor), t1, period, n);
        if sigma {
            for k in 1..=n {
                let s = sigma_factor(k, n);
                a[k - 1] *= s;
                b[k - 1] *= s;
            }
        }
        Self::from_coefficients(period, offset, a, b)
    }

    /// Period `T` (s).
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Fundamental frequency (Hz).
    pub fn f0(&self) -> f64 {
        1.0 / self.period
    }

    /// Angular fundamental frequency `w_0 = 2 pi / T` (rad/s).
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Number of harmonics `n` (highest `k` present).
    pub fn degree(&self) -> usize {
        self.cos.len()
    }

    /// Constant term `c_0` (m).
    pub fn offset(&self) -> f64 {
        self.c0
    }

    /// Amplitudes `d_k = sqrt(A_k^2 + B_k^2)` (6), k = 1..=n (m).
    pub fn amplitudes(&self) -> Vec<f64> {
        self.cos
            .iter()
            .zip(&self.sin)
            .map(|(a, b)| a.hypot(*b))
            .collect()
    }

    /// Phases `phi_k = atan2(A_k, B_k)` (7), k = 1..=n (rad).
    pub fn phases(&self) -> Vec<f64> {
        self.cos
            .iter()
            .zip(&self.sin)
            .map(|(a, b)| a.atan2(*b))
            .collect()
    }

    /// The cosine and sine coefficients `A_k`, `B_k`.
    pub fn coefficients(&self) -> Coefficients<'_> {
        Coefficients {
            cosines: &self.cos,
            sines: &self.sin,
        }
    }

    /// `sum_k (k w_0)^2 d_k`, a bound on `|a_R|` (m/s^2).
    pub fn acceleration_bound(&self) -> f64 {
        self.acc.iter().map(|(a, b)| a.hypot(*b)).sum()
    }

    /// `sum_k k w_0 |(k w_0)^2 (A_k, B_k)|`, a bound on the jerk `|da_R/dt|`
    /// (m/s^3).
    pub(crate) fn jerk_bound(&self) -> f64 {
        self.acc
            .iter()
            .enumerate()
            .map(|(i, (a, b))| (i + 1) as f64 * self.omega * a.hypot(*b))
            .sum()
    }

    /// A bound on the rounding error of [`FourierSignal::velocity`] at any
    /// phase: `64 ε Σ_k √k |k w (A_k, B_k)|`, four times the rounding level
    /// of a trigonometric polynomial (`TrigPoly::eval_error_bound`, docs/model.md
    /// section 8), plus the error of the phase `w tau` itself,
    /// `2 ε T Σ |k^2 w^2 (A_k, B_k)|` (the slope of `v_R` times its rounding).
    pub(crate) fn velocity_rounding(&self) -> f64 {
        let sum: f64 = self
            .vel
            .iter()
            .enumerate()
            .map(|(i, (a, b))| ((i + 1) as f64).sqrt() * a.hypot(*b))
            .sum();
        let direct = 64.0 * f64::EPSILON * sum
            + 2.0 * f64::EPSILON * self.period * self.acceleration_bound();
        direct + self.fast.as_ref().map_or(0.0, |f| f.velocity_rounding())
    }

    /// A bound on the rounding error of [`FourierSignal::acceleration`] at
    /// any phase, built as [`FourierSignal::velocity_rounding`]:
    /// `64 ε Σ_k √k |(k w)^2 (A_k, B_k)|`, plus the error of the phase,
    /// `2 ε T Σ_k k w |(k w)^2 (A_k, B_k)|` (the largest jerk times it),
    /// plus the Horner rounding of the slices if they evaluate.
    pub(crate) fn acceleration_rounding(&self) -> f64 {
        let (mut sum, mut jerk) = (0.0, 0.0);
        for (i, (a, b)) in self.acc.iter().enumerate() {
            let k = (i + 1) as f64;
            sum += k.sqrt() * a.hypot(*b);
            jerk += k * self.omega * a.hypot(*b);
        }
        let direct = 64.0 * f64::EPSILON * sum + 2.0 * f64::EPSILON * self.period * jerk;
        direct
            + self
                .fast
                .as_ref()
                .map_or(0.0, |f| f.acceleration_rounding())
    }

    /// A margin beyond which a computed `a_R(tau) - level` has the sign of
    /// the piece of [`Signal::partition`](super::Signal::partition) of
    /// `level` that holds `tau`. A piece's sign is that of `a_R - level` on
    /// it; a sign change between the partition's boundary (a computed root
    /// `θ_r`) and the true root makes `|a_R - level|` at most the root
    /// finder's residual, `η + |p'(θ_r)| ulp(θ_r)` with
    /// `η = 16 ε (|level| + Σ √k |a_k|)` (`TrigPoly::roots`), and merged
    /// close roots and tangencies have `|a_R - level|` at that level
    /// between them. Four times that residual plus the evaluation's own
    /// rounding ([`FourierSignal::acceleration_rounding`]) is the margin.
    /// The piece's sign itself is taken where `a_R - level` lies beyond the
    /// margin (the midpoint, or the farthest of seven sample points), so
    /// it is the true sign on the piece; only a piece on which `a_R` stays
    /// within the margin of the level at all eight points keeps a sign
    /// decided by rounding, and there an evaluation beyond the margin
    /// elsewhere on it could disagree. The argument rests, as the root
    /// finder's proof does, on `η` bounding the error of a computed `p`.
    pub(crate) fn partition_margin(&self, level: f64) -> f64 {
        let (mut sum, mut slope) = (level.abs(), 0.0);
        for (i, (a, b)) in self.acc.iter().enumerate() {
            let k = (i + 1) as f64;
            sum += k.sqrt() * (a.abs() + b.abs());
            slope += k * (a.abs() + b.abs());
        }
        let residual = 16.0 * f64::EPSILON * sum + 2.0 * PI * f64::EPSILON * slope;
        4.0 * (residual + self.acceleration_rounding())
    }

    /// Position at phase `tau` (m).
    pub fn position(&self, tau: f64) -> f64 {
        if let Some(f) = &self.fast {
            return f.position(tau);
        }
        let mut x = self.c0;
        for_each_harmonic(self.omega * tau, self.cos.len(), |k, c, s| {
            x += self.cos[k] * c + self.sin[k] * s;
        });
        x
    }

    /// Velocity at phase `tau` (m/s).
    #[inline]
    pub fn velocity(&self, tau: f64) -> f64 {
        if let Some(f) = &self.fast {
            return f.velocity(tau);
        }
        let mut v = 0.0;
        for_each_harmonic(self.omega * tau, self.vel.len(), |k, c, s| {
            let (wa, wb) = self.vel[k];
            v += wb * c - wa * s;
        });
        v
    }

    /// Acceleration at phase `tau` (m/s^2).
    #[inline]
    pub fn acceleration(&self, tau: f64) -> f64 {
        if let Some(f) = &self.fast {
            return f.acceleration(tau);
        }
        let mut a = 0.0;
        for_each_harmonic(self.omega * tau, self.acc.len(), |k, c, s| {
            let (wa, wb) = self.acc[k];
            a -= wa * c + wb * s;
        });
        a
    }

    /// Velocity and acceleration at phase `tau` in one pass.
    #[inline]
    pub(crate) fn velocity_acceleration(&self, tau: f64) -> (f64, f64) {
        if let Some(f) = &self.fast {
            return f.velocity_acceleration(tau);
        }
        let mut v = 0.0;
        let mut a = 0.0;
        for_each_harmonic(self.omega * tau, self.vel.len(), |k, c, s| {
            let (va, vb) = self.vel[k];
            let (aa, ab) = self.acc[k];
            v += vb * c - va * s;
            a -= aa * c + ab * s;
        });
        (v, a)
    }

    /// Jerk at phase `tau` (m/s^3).
    pub fn jerk(&self, tau: f64) -> f64 {
        if let Some(f) = &self.fast {
            return f.jerk(tau);
        }
        let mut j = 0.0;
        for_each_harmonic(self.omega * tau, self.acc.len(), |k, c, s| {
            let (aa, ab) = self.acc[k];
            let w = (k + 1) as f64 * self.omega;
            j += w * (aa * s - ab * c);
        });
        j
    }

    /// Position, velocity and acceleration at phase `tau`, in one pass.
    #[inline]
    pub fn state(&self, tau: f64) -> RodState {
        if let Some(f) = &self.fast {
            let (x, v, a) = f.state(tau);
            return RodState { x, v, a };
        }
        let mut st = RodState {
            x: self.c0,
            v: 0.0,
            a: 0.0,
        };
        for_each_harmonic(self.omega * tau, self.cos.len(), |k, c, s| {
            let (va, vb) = self.vel[k];
            let (aa, ab) = self.acc[k];
            st.x += self.cos[k] * c + self.sin[k] * s;
            st.v += vb * c - va * s;
            st.a -= aa * c + ab * s;
        });
        st
    }

    /// `a_R(theta)` as a trigonometric polynomial in `theta = w_0 tau`.
    pub fn acceleration_poly(&self) -> TrigPoly {
        TrigPoly::new(
            0.0,
            self.acc.iter().map(|(a, _)| -a).collect(),
            self.acc.iter().map(|(_, b)| -b).collect(),
        )
    }

    /// The median of `v_R` over a period: the velocity `m` that the rod
    /// exceeds for exactly half of the period (docs/model.md section 7: the
    /// limit of `v_inf` for very high `kappa`). Bisection on `m`; the time
    /// above `m` is measured exactly on the monotone pieces of `v_R`
    /// between the roots of `a_R`, one bracketed root per piece.
    pub fn velocity_median(&self) -> f64 {
        let mut knots = vec![0.0];
        knots.extend(self.acceleration_roots(0.0));
        knots.push(self.period);
        let tol = 4.0 * f64::EPSILON * self.period;
        let time_above = |m: f64| -> f64 {
            knots
                .windows(2)
                .map(|w| {
                    let (s, e) = (w[0], w[1]);
                    let (vs, ve) = (self.velocity(s) - m, self.velocity(e) - m);
                    if vs > 0.0 && ve > 0.0 {
                        e - s
                    } else if vs <= 0.0 && ve <= 0.0 {
                        0.0
                    } else {
                        let root = bracket::solve(
                            |t| (self.velocity(t) - m, self.acceleration(t)),
                            (s, e),
                            (vs, ve),
                            tol,
                            0.0,
                            None,
                        );
                        if vs > 0.0 { root.t - s } else { e - root.t }
                    }
                })
                .sum()
        };
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &k in &knots {
            let v = self.velocity(k);
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if lo >= hi {
            return lo;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if time_above(mid) > 0.5 * self.period {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// `v_R(theta) / w_0` as a trigonometric polynomial in `theta`.
    fn velocity_poly(&self) -> TrigPoly {
        let n = self.cos.len();
        TrigPoly::new(
            0.0,
            (1..=n).map(|k| k as f64 * self.sin[k - 1]).collect(),
            (1..=n).map(|k| -(k as f64) * self.cos[k - 1]).collect(),
        )
    }

    /// Exact extrema of `x_R` over a period, at the roots of `v_R`. Found
    /// once, then kept.
    pub fn extrema(&self) -> Extrema {
        *self.extrema.get_or_init(|| self.find_extrema())
    }

    fn find_extrema(&self) -> Extrema {
        let mut ext = Extrema {
            tau_min: 0.0,
            min: self.position(0.0),
            tau_max: 0.0,
            max: self.position(0.0),
        };
        for theta in self.velocity_poly().roots() {
            let tau = theta / self.omega;
            let x = self.position(tau);
            if x < ext.min {
                ext.min = x;
                ext.tau_min = tau;
            }
            if x > ext.max {
                ext.max = x;
                ext.tau_max = tau;
            }
        }
        ext
    }

    /// Peak-to-peak stroke `max x_R - min x_R` (m).
    pub fn stroke(&self) -> f64 {
        let e = self.extrema();
        e.max - e.min
    }

    /// All amplitudes scaled so that the stroke equals `stroke` (m).
    pub fn scaled_to_stroke(&self, stroke: f64) -> Result<Self, ParamError> {
        let actual = self.stroke();
        if !actual.is_finite() || actual <= 0.0 {
            return Err(ParamError::Inconsistent {
                field: "signal".to_owned(),
                reason: if actual.is_finite() {
                    format!(
                        "the signal has no stroke to scale (max - min = {} m)",
                        Num(actual)
                    )
                } else {
                    "the signal's amplitudes are beyond floating point: no stroke to scale"
                        .to_owned()
                },
            });
        }
        let f = stroke / actual;
        let scaled = Self::from_coefficients(
            self.period,
            self.c0 * f,
            self.cos.iter().map(|a| a * f).collect(),
            self.sin.iter().map(|b| b * f).collect(),
        );
        // Scaling moves no root of v_R: the extrema are where they were,
        // their values scaled (one representation for both signals).
        let e = self.extrema();
        let _ = scaled.extrema.set(Extrema {
            tau_min: e.tau_min,
            min: e.min * f,
            tau_max: e.tau_max,
            max: e.max * f,
        });
        Ok(scaled)
    }

    /// The signal shifted in time and offset so that its minimum lies at
    /// `t = 0` with value 0.
    pub fn shifted_to_minimum(&self) -> Result<Self, ParamError> {
        let shifted = self.delayed(-self.extrema().tau_min);
        // c0 from the shifted series itself, so that x_R(0) = 0 to rounding.
        let c0 = shifted.c0 - shifted.position(0.0);
        Ok(Self::from_coefficients(
            self.period,
            c0,
            shifted.cos,
            shifted.sin,
        ))
    }

    /// The mirrored signal `x_R -> -x_R`.
    pub fn mirrored(&self) -> Self {
        let mirror = Self::from_coefficients(
            self.period,
            -self.c0,
            self.cos.iter().map(|a| -a).collect(),
            self.sin.iter().map(|b| -b).collect(),
        );
        if self.fast.is_some() {
            mirror.with_fast_evaluation()
        } else {
            mirror
        }
    }

    /// The same signal delayed by `delay` seconds: `x_R(t - delay)`.
    pub fn delayed(&self, delay: f64) -> Self {
        let theta = -self.omega * delay;
        let mut cos = Vec::with_capacity(self.cos.len());
        let mut sin = Vec::with_capacity(self.sin.len());
        for (k, (a, b)) in self.cos.iter().zip(&self.sin).enumerate() {
            let (s, c) = ((k + 1) as f64 * theta).sin_cos();
            cos.push(a * c + b * s);
            sin.push(b * c - a * s);
        }
        Self::from_coefficients(self.period, self.c0, cos, sin)
    }
}

/// Calls `f(k - 1, cos k theta, sin k theta)` for `k = 1..=n`, with one
/// `sin_cos` call and the angle-addition recurrence.
#[inline(always)]
fn for_each_harmonic(theta: f64, n: usize, mut f: impl FnMut(usize, f64, f64)) {
    let (s1, c1) = theta.sin_cos();
    let (mut c, mut s) = (c1, s1);
    for k in 0..n {
        f(k, c, s);
        let cn = c * c1 - s * s1;
        s = s * c1 + c * s1;
        c = cn;
    }
}
