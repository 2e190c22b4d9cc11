//! Electrical input power of the piezoelectric actuator (docs/model.md section 4,
//! the paper's section 6.3, equations (20)-(36), Table 1).
//!
//! # Model
//!
//! The actuator and the rod form one degree of freedom (23),
//! `M x_R'' + d x_R' + c x_R = alpha u`, with the charge (21)
//! `q = alpha x_R + C u` and the current `i = q'`. Friction on the rod is
//! neglected against its inertia, and every harmonic of the signal is
//! assumed to lie below or around the actuator's first resonance (the
//! paper's section 6.3.1), so that this model holds for all of them.
//!
//! A harmonic `k` of the rod signal has angular frequency `k w_0` and
//! displacement amplitude `d_k`, so velocity amplitude `v_k = k w_0 d_k`.
//! With `A_k = d^2 + (k w_0 M - c/(k w_0))^2` the voltage and current
//! amplitudes it needs are
//!
//! ```text
//! u_k = (w_0 d_k k / alpha) sqrt(A_k)                                            (31)
//! i_k = (w_0 d_k k / alpha) sqrt(alpha^4 + 2 C alpha^2 (c - M k^2 w_0^2)
//!                                 + C^2 k^2 w_0^2 A_k)                           (32)
//! ```
//!
//! and the RMS values and the apparent power are
//!
//! ```text
//! U = sqrt(sum_k u_k^2 / 2)     (33)      I = sqrt(sum_k i_k^2 / 2)     (34)
//! S = U I                                                               (35)
//! ```
//!
//! (32) is the paper's (30) at `w = k w_0`. It is evaluated here in the
//! equivalent sum-of-squares form `(alpha^2 - w C X)^2 + (w C d)^2` with
//! `X = w M - c/w`, i.e. `|alpha^2 + j w C (d + j X)|^2`, which follows from
//! `i = j w (alpha x + C u)` and cannot round to a negative number near the
//! anti-resonance `w^2 = (c + alpha^2/C)/M`, where the expanded form cancels.
//!
//! The amplitudes `d_k` are the signal's actual ones: after sigma factors
//! and stroke scaling ([`FourierSignal::amplitudes`]). The ideal signal has
//! infinitely many harmonics and no finite `S` in this model.
//!
//! # Units
//!
//! SI throughout: `M` kg, `d` N s/m, `c` N/m, `alpha` N/V, `C` F; `u` V,
//! `i` A, `S` VA.
//!
//! # On the paper's (36)
//!
//! The paper inserts (31)-(34) into (35) with `d_k = d*_k x_Rmax` and writes
//! the prefactor as `w_0^2 x_Rmax / (2 alpha^2)`. Each of `U` and `I` is
//! proportional to `x_Rmax`, so the prefactor is `w_0^2 x_Rmax^2 / (2 alpha^2)`:
//! with a single `x_Rmax` the right-hand side of (36) has units of W/m, not
//! VA. Consequences, which this module follows and `tests/power.rs` checks:
//!
//! * at a fixed signal shape (`d*`, `phi`) and fixed `w_0`, `S ∝ x_Rmax^2`
//!   exactly, not `∝ x_Rmax` as the text after (36) says;
//! * under the paper's scaling `T ∝ sqrt(x_Rmax)` (40) the prefactor
//!   `w_0^2 x_Rmax^2` is `∝ x_Rmax`, but the two square roots depend on
//!   `w_0` as well, so `S` follows no single power law: `S ∝ x_Rmax^(3/2)`
//!   when all harmonics lie far below the resonance (stiffness-dominated:
//!   `u` is quasi-static, `i ∝ w_0 x_Rmax`), `S ∝ x_Rmax^(-1/2)` far above
//!   it (mass-dominated). In between, the resonance `sqrt(c/M)/(2 pi)` and
//!   the anti-resonance `sqrt((c + alpha^2/C)/M)/(2 pi)` (13.95 and
//!   15.29 kHz for Table 1) bend the local exponent beyond both limits: for
//!   the paper's default signal (`n = 2`, `sqrt(kappa) = 6`, sigma, 25 um)
//!   it is about 2.07 towards 100 um and -0.25 towards 6.25 um.

use crate::error::ParamError;
use crate::signal::FourierSignal;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Parameters of the actuator's single-degree-of-freedom model (23), (21),
/// as the `[actuator]` table of a scene spells them (every field required
/// there).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActuatorParams {
    /// Equivalent mass of actuator and rod, `M` (kg, > 0).
    pub mass: f64,
    /// Equivalent damping `d` (N s/m, > 0).
    pub damping: f64,
    /// Equivalent stiffness `c` (N/m, > 0).
    pub stiffness: f64,
    /// Electromechanical transfer factor `alpha` (N/V, > 0).
    pub transfer_factor: f64,
    /// Capacitance `C` (F, > 0).
    pub capacitance: f64,
}

impl Default for ActuatorParams {
    /// The paper's Table 1: `M = 3.2 g`, `d = 9.50 N s/m`, `c = 24.6 N/um`,
    /// `alpha = 1.985 N/V`, `C = 800 nF`.
    fn default() -> Self {
        Self {
            mass: 3.2e-3,
            damping: 9.50,
            stiffness: 24.6e6,
            transfer_factor: 1.985,
            capacitance: 800e-9,
        }
    }
}

impl ActuatorParams {
    /// Checks that every parameter is finite and positive; errors name the
    /// scene field (`actuator.mass`, ...).
    pub fn validate(&self) -> Result<(), ParamError> {
        ParamError::positive("actuator.mass", self.mass)?;
        ParamError::positive("actuator.damping", self.damping)?;
        ParamError::positive("actuator.stiffness", self.stiffness)?;
        ParamError::positive("actuator.transfer_factor", self.transfer_factor)?;
        ParamError::positive("actuator.capacitance", self.capacitance)?;
        Ok(())
    }

    /// Undamped mechanical resonance `sqrt(c/M) / (2 pi)` (Hz); 13.95 kHz for
    /// Table 1.
    pub fn resonance_frequency(&self) -> f64 {
        (self.stiffness / self.mass).sqrt() / (2.0 * PI)
    }

    /// Voltage and current amplitudes `(u, i)` (V, A) that drive a
    /// sinusoidal rod motion of velocity amplitude `v_hat` (m/s) at angular
    /// frequency `omega` (rad/s): (29), (30).
    fn drive_amplitudes(&self, omega: f64, v_hat: f64) -> (f64, f64) {
        let reactance = omega * self.mass - self.stiffness / omega;
        let a = self.damping.hypot(reactance);
        let alpha = self.transfer_factor;
        let w_c = omega * self.capacitance;
        let current_factor = (alpha * alpha - w_c * reactance).hypot(w_c * self.damping);
        (v_hat * a / alpha, v_hat * current_factor / alpha)
    }
}

/// Voltage and current needed for one harmonic of the rod signal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HarmonicPower {
    /// Harmonic number `k` (1-based); angular frequency `k w_0`.
    pub k: usize,
    /// Displacement amplitude `d_k` (m).
    pub amplitude: f64,
    /// Voltage amplitude `u_k` (31) (V).
    pub u_hat: f64,
    /// Current amplitude `i_k` (32) (A).
    pub i_hat: f64,
}

/// The electrical input a signal needs: per-harmonic amplitudes, RMS values
/// and apparent power.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerReport {
    /// One entry per harmonic `k = 1..=n` (zero amplitudes included).
    pub harmonics: Vec<HarmonicPower>,
    /// RMS voltage `U` (33) (V).
    pub u_rms: f64,
    /// RMS current `I` (34) (A).
    pub i_rms: f64,
    /// Apparent power `S = U I` (35) (VA).
    pub apparent_power: f64,
}

/// Voltage, current and apparent power (31)-(35) that `actuator` needs to
/// move the rod along `signal`.
pub fn input_power(signal: &FourierSignal, actuator: &ActuatorParams) -> PowerReport {
    let w0 = signal.omega();
    let harmonics: Vec<HarmonicPower> = signal
        .amplitudes()
        .into_iter()
        .enumerate()
        .map(|(i, amplitude)| {
            let k = i + 1;
            let omega = k as f64 * w0;
            let (u_hat, i_hat) = actuator.drive_amplitudes(omega, omega * amplitude);
            HarmonicPower {
                k,
                amplitude,
                u_hat,
                i_hat,
            }
        })
        .collect();
    let rms = |f: fn(&HarmonicPower) -> f64| {
        (0.5 * harmonics.iter().map(|h| f(h).powi(2)).sum::<f64>()).sqrt()
    };
    let u_rms = rms(|h| h.u_hat);
    let i_rms = rms(|h| h.i_hat);
    PowerReport {
        harmonics,
        u_rms,
        i_rms,
        apparent_power: u_rms * i_rms,
    }
}

/// The derivatives `(dU, dI, dS)` of (33)-(35) for `signal` when its
/// amplitudes change by `d_amplitudes` (m per unit of a parameter), at a
/// fixed frequency: with `u_k = u'_k d_k` and `i_k = i'_k d_k` linear in
/// the amplitude (31), (32), `dU = sum_k u'_k^2 d_k dd_k / (2 U)`, the same
/// for `I`, and `dS = dU I + U dI`. Zero where `U` or `I` is zero.
pub(crate) fn input_power_derivative(
    signal: &FourierSignal,
    actuator: &ActuatorParams,
    d_amplitudes: &[f64],
) -> (f64, f64, f64) {
    let w0 = signal.omega();
    let report = input_power(signal, actuator);
    let (mut du, mut di) = (0.0, 0.0);
    for (h, dd) in report.harmonics.iter().zip(d_amplitudes) {
        let omega = h.k as f64 * w0;
        // Amplitudes per metre of displacement: v_hat = omega * 1 m.
        let (u1, i1) = actuator.drive_amplitudes(omega, omega);
        du += 0.5 * u1 * u1 * h.amplitude * dd;
        di += 0.5 * i1 * i1 * h.amplitude * dd;
    }
    let (u, i) = (report.u_rms, report.i_rms);
    let du = if u > 0.0 { du / u } else { 0.0 };
    let di = if i > 0.0 { di / i } else { 0.0 };
    (du, di, du * i + u * di)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`input_power_derivative`] against central differences of
    /// [`input_power`] with one amplitude moved (truncation `~h^2`,
    /// rounding `~1e-16 / h` relative).
    #[test]
    fn power_derivative_matches_central_differences() {
        let actuator = ActuatorParams::default();
        let period = 1.0 / 9448.8;
        let build = |d: &[f64]| {
            let phases: [f64; 3] = [0.0, 3.1, 1.0];
            let cos = d.iter().zip(phases).map(|(d, p)| d * p.sin()).collect();
            let sin = d.iter().zip(phases).map(|(d, p)| d * p.cos()).collect();
            FourierSignal::from_coefficients(period, 0.0, cos, sin)
        };
        let d = [10e-6, 2.5e-6, 1e-6];
        let signal = build(&d);
        for j in 0..3 {
            let mut dd = [0.0; 3];
            dd[j] = 1.0;
            let (du, di, ds) = input_power_derivative(&signal, &actuator, &dd);
            let h = 1e-5 * d[j];
            let at = |delta: f64| {
                let mut x = d;
                x[j] += delta;
                input_power(&build(&x), &actuator)
            };
            let (p, m) = (at(h), at(-h));
            for (exact, fd) in [
                (du, (p.u_rms - m.u_rms) / (2.0 * h)),
                (di, (p.i_rms - m.i_rms) / (2.0 * h)),
                (ds, (p.apparent_power - m.apparent_power) / (2.0 * h)),
            ] {
                assert!(
                    (exact - fd).abs() <= 1e-8 * fd.abs(),
                    "harmonic {j}: {exact:e} against {fd:e}"
                );
            }
        }
    }
}
