//! The ideal excitation signal (11) of the paper:
//!
//! ```text
//! x_R(tau) = (a_R / 2) tau^2   for 0 <= tau < t_1
//!          = 0                 for t_1 <= tau < T
//! ```
//!
//! repeated with period `T`, with `a_R = kappa a_0` and
//! `t_1 = sqrt(2 x_Rmax / a_R)`. At `tau = t_1` (discrete signal, `t_1 < T`)
//! or at the period boundary (continuous signal, `t_1 = T`) the rod position
//! jumps from `x_Rmax` back to 0 and its velocity from `a_R t_1` to 0, in zero
//! time. The rod starts from rest at `t = 0`, so the jump at phase 0 of the
//! continuous signal first happens at `t = T`.

use super::{IdealShape, RodState};
use crate::motor::Motor;

/// The ideal signal (11).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdealSignal {
    /// Signed acceleration in the acceleration phase (negative when mirrored).
    a_r: f64,
    t1: f64,
    period: f64,
}

impl IdealSignal {
    /// The signal for a validated shape and motor.
    pub fn new(shape: IdealShape, motor: &Motor) -> Self {
        let super::IdealTimes { t1, period } = shape.times(motor);
        let t1 = if shape.duty == 1.0 { period } else { t1 };
        Self {
            a_r: shape.a_r(motor),
            t1,
            period,
        }
    }

    /// Period `T` (s).
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Length of the acceleration phase `t_1` (s).
    pub fn t1(&self) -> f64 {
        self.t1
    }

    /// Rod acceleration in the acceleration phase, `a_R` (m/s^2).
    pub fn a_r(&self) -> f64 {
        self.a_r
    }

    /// True for the continuous signal (`t_1 = T`).
    pub fn is_continuous(&self) -> bool {
        self.t1 >= self.period
    }

    /// The acceleration phase's state at `tau`, or rest.
    #[inline]
    fn accelerating(&self, tau: f64, accelerating: bool) -> RodState {
        if accelerating {
            RodState {
                x: 0.5 * self.a_r * tau * tau,
                v: self.a_r * tau,
                a: self.a_r,
            }
        } else {
            RodState::default()
        }
    }

    /// State at phase `tau` in `[0, T)` (right limit at the jump).
    #[inline]
    pub fn state(&self, tau: f64) -> RodState {
        self.accelerating(tau, tau < self.t1)
    }

    /// Left limit of the state at phase `tau` in `(0, T]`; at `tau = 0` the
    /// left limit is the end of the previous period.
    pub fn state_before(&self, tau: f64) -> RodState {
        let tau = if tau <= 0.0 { self.period } else { tau };
        self.accelerating(tau, tau <= self.t1)
    }

    /// Phase of the jump: `t_1` (discrete) or 0 (continuous).
    pub fn jump_phase(&self) -> f64 {
        if self.is_continuous() { 0.0 } else { self.t1 }
    }

    /// Inner phases where the acceleration changes (the jump of a discrete
    /// signal).
    pub fn piece_boundaries(&self) -> Vec<f64> {
        if self.is_continuous() {
            Vec::new()
        } else {
            vec![self.t1]
        }
    }

    /// The signal with reversed direction, `x_R -> -x_R`.
    pub fn mirrored(&self) -> Self {
        Self {
            a_r: -self.a_r,
            ..*self
        }
    }
}
