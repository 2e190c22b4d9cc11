//! The actuator's voltage `u(t)` (docs/model.md section 16).
//!
//! A periodic voltage of period `T`,
//!
//! ```text
//! u(t) = u_0 + sum_k ( P_k cos(k w t) + Q_k sin(k w t) ) = u_0 + sum_k Re(U_k e^{i k w t}),
//! U_k = P_k - i Q_k,
//! ```
//!
//! either designed for the actuator (23) `M x'' + d x' + c x = alpha u`
//! to move the rod exactly along a signal
//! `x_R = x_0 + sum_k Re(X_k e^{i k w t})` (the inverse of (23) harmonic
//! by harmonic, the complex form of (25)):
//!
//! ```text
//! U_k = (c - M (k w)^2 + i d k w) X_k / alpha,   u_0 = c x_0 / alpha,
//! ```
//!
//! or given by amplitudes and phases in the paper's convention (5):
//! `u = u_0 + sum_k u_k sin(k w t + phi_k)`.
//!
//! Its peak `max |u(t)|` over a period is found at the exact extrema (the
//! roots of `u'`, [`crate::numerics::TrigPoly`]); its RMS value is (33),
//! `sqrt(sum_k |U_k|^2 / 2)`, without the offset.

use crate::numerics::TrigPoly;
use crate::power::ActuatorParams;
use crate::signal::FourierSignal;
use std::f64::consts::PI;

/// A periodic voltage: offset and harmonics (V).
#[derive(Debug, Clone, PartialEq)]
pub struct Voltage {
    period: f64,
    offset: f64,
    /// `P_k`, multiplying `cos(k w t)` (V).
    cos: Vec<f64>,
    /// `Q_k`, multiplying `sin(k w t)` (V).
    sin: Vec<f64>,
}

impl Voltage {
    /// The voltage that drives `actuator` exactly along `signal` when no
    /// force but its own acts on it.
    pub fn designed(signal: &FourierSignal, actuator: &ActuatorParams) -> Self {
        let w = signal.omega();
        let c = signal.coefficients();
        let alpha = actuator.transfer_factor;
        let (mut cos, mut sin) = (Vec::new(), Vec::new());
        for (k, (a, b)) in c.cosines.iter().zip(c.sines).enumerate() {
            let kw = (k + 1) as f64 * w;
            // X_k = A_k - i B_k; Z_k = (c - M (kw)^2) + i d kw.
            let (zr, zi) = (
                actuator.stiffness - actuator.mass * kw * kw,
                actuator.damping * kw,
            );
            let (ur, ui) = ((zr * a + zi * b) / alpha, (zi * a - zr * b) / alpha);
            cos.push(ur);
            sin.push(-ui);
        }
        Self {
            period: signal.period(),
            offset: actuator.stiffness * signal.offset() / alpha,
            cos,
            sin,
        }
    }

    /// A voltage given by frequency (Hz), amplitudes `u_k` (V), phases
    /// `phi_k` (rad) and offset (V): `u = u_0 + sum_k u_k sin(k w t + phi_k)`.
    /// The caller has validated the values.
    pub fn from_amplitudes(
        frequency: f64,
        amplitudes: &[f64],
        phases: &[f64],
        offset: f64,
    ) -> Self {
        let cos = amplitudes
            .iter()
            .zip(phases)
            .map(|(u, p)| u * p.sin())
            .collect();
        let sin = amplitudes
            .iter()
            .zip(phases)
            .map(|(u, p)| u * p.cos())
            .collect();
        Self {
            period: 1.0 / frequency,
            offset,
            cos,
            sin,
        }
    }

    /// Period `T` (s).
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Angular fundamental frequency `w = 2 pi / T` (rad/s).
    pub fn omega(&self) -> f64 {
        2.0 * PI / self.period
    }

    /// The offset `u_0` (V).
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// `(P_k, Q_k)` for `k = 1..`: `u = u_0 + sum P_k cos + Q_k sin`.
    pub fn harmonics(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.cos.iter().copied().zip(self.sin.iter().copied())
    }

    /// Amplitudes `u_k = |U_k|` (V), `k = 1..`.
    pub fn amplitudes(&self) -> Vec<f64> {
        self.harmonics().map(|(p, q)| p.hypot(q)).collect()
    }

    /// Phases `phi_k = atan2(P_k, Q_k)` (rad) of `u_k sin(k w t + phi_k)`.
    pub fn phases(&self) -> Vec<f64> {
        self.harmonics().map(|(p, q)| p.atan2(q)).collect()
    }

    /// `u(tau)` and `u'(tau)` (V, V/s) at phase `tau`.
    pub fn value(&self, tau: f64) -> [f64; 2] {
        let w = self.omega();
        let (mut u, mut du) = (self.offset, 0.0);
        for (k, (p, q)) in self.harmonics().enumerate() {
            let kw = (k + 1) as f64 * w;
            let (s, c) = (kw * tau).sin_cos();
            u += p * c + q * s;
            du += kw * (q * c - p * s);
        }
        [u, du]
    }

    /// `u(theta)` as a trigonometric polynomial in `theta = w tau`.
    fn poly(&self) -> TrigPoly {
        TrigPoly::new(self.offset, self.cos.clone(), self.sin.clone())
    }

    /// `max |u(t)|` over a period, offset included (V): `u` at every root
    /// of `u'` (all found, certified) and at phase 0.
    pub fn peak(&self) -> f64 {
        let w = self.omega();
        self.poly()
            .derivative()
            .roots()
            .into_iter()
            .map(|theta| self.value(theta / w)[0].abs())
            .fold(self.value(0.0)[0].abs(), f64::max)
    }

    /// RMS value (33) over the harmonics, without the offset (V).
    pub fn rms(&self) -> f64 {
        (0.5 * self.harmonics().map(|(p, q)| p * p + q * q).sum::<f64>()).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The designed voltage drives the friction-free actuator (23) along
    /// the signal: `M x'' + d x' + c x = alpha u` holds at every phase with
    /// `x` the signal (residual at rounding level of the largest term).
    #[test]
    fn designed_voltage_satisfies_the_actuator_equation_along_the_signal() {
        let actuator = ActuatorParams::default();
        let signal = FourierSignal::from_coefficients(
            1.0 / 9448.8,
            12.5e-6,
            vec![-10e-6, 1.5e-6, 0.3e-6],
            vec![4e-6, -2e-6, 0.1e-6],
        );
        let u = Voltage::designed(&signal, &actuator);
        for i in 0..50 {
            let tau = signal.period() * i as f64 / 50.0;
            let st = signal.state(tau);
            let lhs = actuator.mass * st.a + actuator.damping * st.v + actuator.stiffness * st.x;
            let rhs = actuator.transfer_factor * u.value(tau)[0];
            let scale = actuator.stiffness * 30e-6;
            assert!((lhs - rhs).abs() <= 1e-13 * scale, "{lhs} against {rhs}");
        }
    }

    /// Amplitudes and phases in the paper's convention (5) round-trip, and
    /// the peak of a single sine is its amplitude plus the offset.
    #[test]
    fn amplitudes_phases_and_peak_of_a_sine() {
        let u = Voltage::from_amplitudes(1000.0, &[100.0, 0.0], &[0.3, 0.0], 20.0);
        assert!((u.amplitudes()[0] - 100.0).abs() < 1e-12);
        assert!((u.phases()[0] - 0.3).abs() < 1e-15);
        // max |20 + 100 sin| = 120 (closed form).
        assert!((u.peak() - 120.0).abs() < 1e-10);
        // (33): 100 / sqrt(2).
        assert!((u.rms() - 100.0 / 2f64.sqrt()).abs() < 1e-12);
    }
}
