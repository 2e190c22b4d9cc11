//! A parameter direction (docs/model.md section 14.1): what a change of one
//! parameter `theta` does to the motor's accelerations and to the rod
//! signal, to first order.
//!
//! * The motor: `d a_0/dtheta`, `d a_d/dtheta`, `d g_t/dtheta`, hence the
//!   band edges `a_0^+- = +-a_0 + g_t` and the sliding accelerations
//!   `+-a_d + g_t`.
//! * The rod, at a fixed phase `tau` ([`RodTangent::at`]):
//!
//!   ```text
//!   dx_R = s x_R - r tau v_R        + c v_R + dX(tau)
//!   dv_R = s v_R - r (v_R + tau a_R) + c a_R + dV(tau)
//!   da_R = s a_R - r (2 a_R + tau j_R) + c j_R + dA(tau)
//!   ```
//!
//!   with the amplitude rate `s = d ln L / dtheta` (all amplitudes scale),
//!   the time-scale rate `r = d ln T / dtheta` (`x_R(tau) = X(tau / T)`:
//!   the shape in normalised time is kept), the shift rate
//!   `c = d delta / dtheta` (`x_R(tau) = X(tau + delta)`) and a series
//!   `dX` of the same period for everything else (amplitudes and phases of
//!   single harmonics). A feature of the signal at a fixed normalised
//!   phase (a rod jump, a step of the ideal signal's acceleration) moves
//!   by `r tau - c`; the period end by `r T`.
//!
//! Each term is the derivative of one of the ways the program builds a
//! signal (docs/model.md section 2): a `kappa`-based signal depends on the
//! motor only through `a_0`, and at fixed stroke and `kappa` it is the
//! same shape in time scaled by `T ∝ a_0^(-1/2)`; stroke scaling is `s`;
//! the shift to the minimum is `c`.

use crate::engine::Direction;
use crate::signal::{FourierSignal, Signal};

/// Rod position, velocity, acceleration and jerk at a phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodPoint {
    /// Phase (s); `T` for the left limit at the period end.
    pub tau: f64,
    /// `x_R` (m).
    pub x: f64,
    /// `v_R` (m/s).
    pub v: f64,
    /// `a_R` (m/s^2).
    pub a: f64,
    /// `j_R = a_R'` (m/s^3); 0 for the ideal signal.
    pub j: f64,
}

impl RodPoint {
    /// The right limit at `tau` in `[0, T)`.
    pub fn right(signal: &Signal, tau: f64) -> Self {
        let s = signal.state(tau);
        Self {
            tau,
            x: s.x,
            v: s.v,
            a: s.a,
            j: signal.jerk(tau),
        }
    }

    /// The left limit at `tau` in `(0, T]`.
    pub fn left(signal: &Signal, tau: f64) -> Self {
        let s = signal.state_before(tau);
        Self {
            tau,
            x: s.x,
            v: s.v,
            a: s.a,
            j: signal.jerk(tau),
        }
    }
}

/// First-order change of the rod signal with a parameter (module docs).
#[derive(Debug, Clone, Default)]
pub struct RodTangent {
    /// `s = d ln L / dtheta`: every amplitude scales (1/unit of theta).
    pub scale: f64,
    /// `r = d ln T / dtheta`: time scales about phase 0.
    pub time_scale: f64,
    /// `c = d delta / dtheta`: the signal moves earlier in phase (s per unit).
    pub shift: f64,
    /// Any further change at a fixed phase, as a series of the same period.
    pub series: Option<FourierSignal>,
}

/// `(dx_R, dv_R, da_R)` at a fixed phase.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RodChange {
    /// `dx_R / dtheta`.
    pub x: f64,
    /// `dv_R / dtheta`.
    pub v: f64,
    /// `da_R / dtheta`.
    pub a: f64,
}

impl RodTangent {
    /// `(dx_R, dv_R, da_R)` at the fixed phase of `p`.
    pub fn at(&self, p: &RodPoint) -> RodChange {
        let (s, r, c) = (self.scale, self.time_scale, self.shift);
        let mut d = RodChange {
            x: s * p.x - r * p.tau * p.v + c * p.v,
            v: s * p.v - r * (p.v + p.tau * p.a) + c * p.a,
            a: s * p.a - r * (2.0 * p.a + p.tau * p.j) + c * p.j,
        };
        if let Some(series) = &self.series {
            let q = series.state(p.tau);
            d.x += q.x;
            d.v += q.v;
            d.a += q.a;
        }
        d
    }

    /// How far a feature at the fixed normalised phase `tau` moves.
    pub fn feature(&self, tau: f64) -> f64 {
        self.time_scale * tau - self.shift
    }

    /// `dT / dtheta`.
    pub fn period(&self, period: f64) -> f64 {
        self.time_scale * period
    }

    /// True if the rod does not change.
    pub fn is_zero(&self) -> bool {
        self.scale == 0.0 && self.time_scale == 0.0 && self.shift == 0.0 && self.series.is_none()
    }
}

/// A parameter direction: the first-order change of the motor's
/// accelerations and of the rod signal per unit of the parameter.
#[derive(Debug, Clone, Default)]
pub struct Tangent {
    /// `d a_0 / dtheta` (m/s^2 per unit).
    pub a_0: f64,
    /// `d a_d / dtheta`.
    pub a_d: f64,
    /// `d g_t / dtheta`.
    pub g_t: f64,
    /// The rod signal's change.
    pub rod: RodTangent,
}

impl Tangent {
    /// No change at all: the direction of the period map's own argument.
    pub fn none() -> Self {
        Self::default()
    }

    /// Change of the band edge `a_0^+` (forward) or `a_0^-` (backward).
    pub fn edge(&self, to: Direction) -> f64 {
        to.sign() * self.a_0 + self.g_t
    }

    /// Change of the sliding acceleration `+-a_d + g_t`.
    pub fn slip(&self, dir: Direction) -> f64 {
        dir.sign() * self.a_d + self.g_t
    }
}
