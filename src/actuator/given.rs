//! A voltage given directly, the scene's `[voltage]` table
//! (docs/model.md section 16), and the rod's reference motion under it.
//!
//! The voltage is given in the paper's convention (5), the one
//! `stickslip signal --voltage` prints, so that its output pasted into a
//! scene drives the same rod:
//!
//! ```text
//! u(t) = u_0 + sum_k u_k sin(k w t + phi_k),   w = 2 pi f,
//! ```
//!
//! with `f = frequency` (Hz), `u_k = amplitudes` (V, `>= 0`), `phi_k =
//! phases` (rad) and `u_0 = offset` (V). The rod's reference motion is the
//! steady response of the friction-free `[actuator]` (23)
//! `M x'' + d x' + c x = alpha u`, harmonic by harmonic (`U_k = P_k - i Q_k`
//! as in `voltage.rs`):
//!
//! ```text
//! X_k = alpha U_k / (c - M (k w)^2 + i d k w),   x_0 = alpha u_0 / c,
//! ```
//!
//! which is what the designed voltage inverts: the response to the
//! voltage designed for a signal is that signal. `x_R = 0` is the
//! actuator's rest without voltage, where the rod starts at `t = 0`; the
//! response oscillates about `x_0`, and unlike a designed signal it need
//! not start at rest, so the rod's free oscillation, started at `t = 0`
//! with minus the response's position and velocity, decays as
//! `exp(-d t / (2 M))` before the rod settles onto the response.
//!
//! Contract: [`GivenVoltage::validate`] accepts a positive finite
//! frequency, from 1 to [`MAX_HARMONICS`] amplitudes, non-negative,
//! finite and not all zero, as many finite phases and a finite offset;
//! every error is one line naming the field (`voltage.phases[1]`).

use super::Voltage;
use super::response::ModeResponse;
use crate::error::ParamError;
use crate::power::ActuatorParams;
use crate::signal::{MAX_HARMONICS, SignalSpec};

/// A voltage given by its harmonics in the paper's convention (5).
#[derive(Debug, Clone, PartialEq)]
pub struct GivenVoltage {
    /// The fundamental frequency `f = w / (2 pi)` (Hz).
    pub frequency: f64,
    /// `u_k` for `k = 1..` (V).
    pub amplitudes: Vec<f64>,
    /// `phi_k` for `k = 1..` (rad), of `u_k sin(k w t + phi_k)`.
    pub phases: Vec<f64>,
    /// `u_0` (V).
    pub offset: f64,
}

impl GivenVoltage {
    /// Checks every value; errors name the `[voltage]` field.
    pub fn validate(&self) -> Result<(), ParamError> {
        ParamError::positive("voltage.frequency", self.frequency)?;
        let n = self.amplitudes.len();
        if n == 0 || n > MAX_HARMONICS {
            return Err(ParamError::out_of_range(
                "voltage.amplitudes",
                n as f64,
                format!("must list from 1 to {MAX_HARMONICS} amplitudes (harmonic k = 1, 2, ...)"),
            ));
        }
        if self.phases.len() != n {
            return Err(ParamError::Inconsistent {
                field: "voltage.phases".to_owned(),
                reason: format!(
                    "has {} entries but voltage.amplitudes has {n}",
                    self.phases.len()
                ),
            });
        }
        for (k, u) in self.amplitudes.iter().enumerate() {
            ParamError::non_negative(&format!("voltage.amplitudes[{k}]"), *u)?;
        }
        for (k, phi) in self.phases.iter().enumerate() {
            ParamError::finite(&format!("voltage.phases[{k}]"), *phi)?;
        }
        ParamError::finite("voltage.offset", self.offset)?;
        if self.amplitudes.iter().all(|u| *u == 0.0) {
            return Err(ParamError::Inconsistent {
                field: "voltage.amplitudes".to_owned(),
                reason: "all amplitudes are zero: the rod does not move".to_owned(),
            });
        }
        Ok(())
    }

    /// The voltage (the caller has validated the values).
    pub fn voltage(&self) -> Voltage {
        Voltage::from_amplitudes(self.frequency, &self.amplitudes, &self.phases, self.offset)
    }

    /// The rod's reference motion: the steady response of the
    /// friction-free `actuator` to the voltage, as the scene's signal.
    pub fn response(&self, actuator: &ActuatorParams) -> SignalSpec {
        let r = ModeResponse::new(actuator, actuator.mass, 0.0, &self.voltage());
        let c = r.particular.coefficients();
        SignalSpec::Response {
            frequency: self.frequency,
            offset: r.particular.offset(),
            cosines: c.cosines.to_vec(),
            sines: c.sines.to_vec(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule names its field.
    #[test]
    fn validation_names_the_field() {
        let good = GivenVoltage {
            frequency: 9000.0,
            amplitudes: vec![100.0, 20.0],
            phases: vec![0.0, 1.0],
            offset: 0.0,
        };
        good.validate().expect("valid");
        let cases: [(&str, GivenVoltage); 7] = [
            (
                "voltage.frequency",
                GivenVoltage {
                    frequency: 0.0,
                    ..good.clone()
                },
            ),
            (
                "voltage.amplitudes",
                GivenVoltage {
                    amplitudes: vec![],
                    phases: vec![],
                    ..good.clone()
                },
            ),
            (
                "voltage.phases",
                GivenVoltage {
                    phases: vec![0.0],
                    ..good.clone()
                },
            ),
            (
                "voltage.amplitudes[1]",
                GivenVoltage {
                    amplitudes: vec![1.0, -2.0],
                    ..good.clone()
                },
            ),
            (
                "voltage.phases[0]",
                GivenVoltage {
                    phases: vec![f64::NAN, 0.0],
                    ..good.clone()
                },
            ),
            (
                "voltage.offset",
                GivenVoltage {
                    offset: f64::INFINITY,
                    ..good.clone()
                },
            ),
            (
                "voltage.amplitudes",
                GivenVoltage {
                    amplitudes: vec![0.0, 0.0],
                    ..good.clone()
                },
            ),
        ];
        for (field, v) in cases {
            let message = v.validate().expect_err(field).to_string();
            assert!(message.starts_with(field), "{message}");
            assert!(!message.contains('\n'), "{message}");
        }
    }
}
