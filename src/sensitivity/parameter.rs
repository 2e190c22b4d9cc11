//! The parameters whose sensitivities are computed: scene fields, each
//! with its direction ([`super::tangent::Tangent`]) and its unit.
//!
//! Derivatives are partial derivatives with respect to the scene field,
//! every other scene field held, the drive as the scene gives it
//! (`crate::signal::Drive`): an `ideal` or `fourier` signal driven by
//! `kappa` is built from `a_0 = mu_0 F_c / m_s`, so the friction
//! coefficient, the contact force and the mass change its period too
//! (`T ∝ a_0^(-1/2)` at fixed stroke and `kappa`); one driven by
//! `frequency` or `f_max`, like a `harmonics` signal, does not depend on
//! the motor, and its stroke scales it at a fixed period. To hold the
//! other quantity, differentiate the same signal with its drive given the
//! other way (`SignalSpec::holding`). `motor.extra_acceleration` is
//! `g_t` itself (a load `F` is `g_t = -F / m_s`, so `dv_inf/dF =
//! -(dv_inf/dg_t) / m_s`).

use super::harmonics;
use super::tangent::{RodTangent, Tangent};
use crate::error::ParamError;
use crate::motor::{Motor, MotorParams};
use crate::signal::{Drive, Signal, SignalSpec};
use std::fmt;

/// A scene's signal and motor with one [`Parameter`] set
/// ([`Parameter::apply`]).
#[derive(Debug, Clone, PartialEq)]
pub struct VariedScene {
    /// The signal as the scene gives it.
    pub signal: SignalSpec,
    /// The motor parameters.
    pub motor: MotorParams,
}

/// A scene field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Parameter {
    /// `motor.extra_acceleration`, `g_t` (m/s^2).
    ExtraAcceleration,
    /// `motor.mu_static`, `mu_0`.
    MuStatic,
    /// `motor.mu_dynamic`, `mu_d`.
    MuDynamic,
    /// `motor.contact_force`, `F_c` (N).
    ContactForce,
    /// `motor.slider_mass`, `m_s` (kg).
    SliderMass,
    /// `signal.stroke` (m): `x_Rmax`, or the stroke a `harmonics` signal is
    /// scaled to.
    Stroke,
    /// `signal.kappa` (signals driven by `kappa`).
    Kappa,
    /// `signal.frequency`, `f_0` (Hz; `harmonics` signals and signals
    /// driven by `frequency`).
    Frequency,
    /// `signal.f_max`, `n f_0` (Hz; signals driven by `f_max`).
    FMax,
    /// `signal.amplitudes[k]`, `d_(k+1)` (m; `harmonics` signals).
    Amplitude(usize),
    /// `signal.phases[k]`, `phi_(k+1)` (rad; `harmonics` signals).
    Phase(usize),
}

impl fmt::Display for Parameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Parameter::ExtraAcceleration => write!(f, "motor.extra_acceleration"),
            Parameter::MuStatic => write!(f, "motor.mu_static"),
            Parameter::MuDynamic => write!(f, "motor.mu_dynamic"),
            Parameter::ContactForce => write!(f, "motor.contact_force"),
            Parameter::SliderMass => write!(f, "motor.slider_mass"),
            Parameter::Stroke => write!(f, "signal.stroke"),
            Parameter::Kappa => write!(f, "signal.kappa"),
            Parameter::Frequency => write!(f, "signal.frequency"),
            Parameter::FMax => write!(f, "signal.f_max"),
            Parameter::Amplitude(k) => write!(f, "signal.amplitudes[{k}]"),
            Parameter::Phase(k) => write!(f, "signal.phases[{k}]"),
        }
    }
}

/// The five motor fields.
pub(super) const MOTOR: [Parameter; 5] = [
    Parameter::ExtraAcceleration,
    Parameter::MuStatic,
    Parameter::MuDynamic,
    Parameter::ContactForce,
    Parameter::SliderMass,
];

impl Parameter {
    /// Every parameter of a scene with this signal: the motor's five, then
    /// the signal's (`stroke` and the drive, `kappa`, `frequency` or
    /// `f_max`, of an `ideal` or `fourier` signal;
    /// `frequency`, `stroke` if scaled, every amplitude and phase of a
    /// `harmonics` signal).
    pub fn all_for(spec: &SignalSpec) -> Vec<Parameter> {
        let mut all = MOTOR.to_vec();
        match spec {
            SignalSpec::Ideal(shape) | SignalSpec::Fourier { shape, .. } => {
                all.extend([Parameter::Stroke, Parameter::of_drive(shape.drive)]);
            }
            SignalSpec::Harmonics {
                amplitudes,
                scale_to_stroke,
                ..
            } => {
                all.push(Parameter::Frequency);
                if scale_to_stroke.is_some() {
                    all.push(Parameter::Stroke);
                }
                all.extend((0..amplitudes.len()).map(Parameter::Amplitude));
                all.extend((0..amplitudes.len()).map(Parameter::Phase));
            }
            // A driven rod's: the actuator's (RunReport::actuator_sensitivities).
            SignalSpec::Response { .. } => {}
        }
        all
    }

    /// The parameter of a drive.
    pub fn of_drive(drive: Drive) -> Parameter {
        match drive {
            Drive::Kappa(_) => Parameter::Kappa,
            Drive::Frequency(_) => Parameter::Frequency,
            Drive::FMax(_) => Parameter::FMax,
        }
    }

    /// The unit of `dv_inf / dtheta`.
    pub fn unit(self) -> &'static str {
        match self {
            Parameter::ExtraAcceleration => "s",
            Parameter::MuStatic | Parameter::MuDynamic | Parameter::Kappa => "m/s",
            Parameter::ContactForce => "m/(s N)",
            Parameter::SliderMass => "m/(s kg)",
            Parameter::Stroke | Parameter::Amplitude(_) => "1/s",
            Parameter::Frequency | Parameter::FMax => "m",
            Parameter::Phase(_) => "m/(s rad)",
        }
    }

    /// The parameter's value in the scene, if the scene has it.
    pub fn value(self, spec: &SignalSpec, motor: &MotorParams) -> Option<f64> {
        match (self, spec) {
            (Parameter::ExtraAcceleration, _) => Some(motor.extra_acceleration),
            (Parameter::MuStatic, _) => Some(motor.mu_static),
            (Parameter::MuDynamic, _) => Some(motor.mu_dynamic),
            (Parameter::ContactForce, _) => Some(motor.contact_force),
            (Parameter::SliderMass, _) => Some(motor.slider_mass),
            (Parameter::Stroke, SignalSpec::Ideal(s) | SignalSpec::Fourier { shape: s, .. }) => {
                Some(s.stroke)
            }
            (
                Parameter::Kappa | Parameter::Frequency | Parameter::FMax,
                SignalSpec::Ideal(s) | SignalSpec::Fourier { shape: s, .. },
            ) => (Parameter::of_drive(s.drive) == self).then_some(s.drive.value()),
            (
                Parameter::Stroke,
                SignalSpec::Harmonics {
                    scale_to_stroke, ..
                },
            ) => *scale_to_stroke,
            (Parameter::Frequency, SignalSpec::Harmonics { frequency, .. }) => Some(*frequency),
            (Parameter::Amplitude(k), SignalSpec::Harmonics { amplitudes, .. }) => {
                amplitudes.get(k).copied()
            }
            (Parameter::Phase(k), SignalSpec::Harmonics { phases, .. }) => phases.get(k).copied(),
            _ => None,
        }
    }

    /// The scene with this parameter set to `value` (validated when the
    /// motor and signal are built).
    pub fn apply(self, spec: &SignalSpec, motor: &MotorParams, value: f64) -> VariedScene {
        let (mut spec, mut motor) = (spec.clone(), *motor);
        match (self, &mut spec) {
            (Parameter::ExtraAcceleration, _) => motor.extra_acceleration = value,
            (Parameter::MuStatic, _) => motor.mu_static = value,
            (Parameter::MuDynamic, _) => motor.mu_dynamic = value,
            (Parameter::ContactForce, _) => motor.contact_force = value,
            (Parameter::SliderMass, _) => motor.slider_mass = value,
            (Parameter::Stroke, SignalSpec::Ideal(s) | SignalSpec::Fourier { shape: s, .. }) => {
                s.stroke = value
            }
            (
                Parameter::Kappa | Parameter::Frequency | Parameter::FMax,
                SignalSpec::Ideal(s) | SignalSpec::Fourier { shape: s, .. },
            ) => {
                s.drive = match self {
                    Parameter::Kappa => Drive::Kappa(value),
                    Parameter::Frequency => Drive::Frequency(value),
                    _ => Drive::FMax(value),
                }
            }
            (
                Parameter::Stroke,
                SignalSpec::Harmonics {
                    scale_to_stroke, ..
                },
            ) => *scale_to_stroke = Some(value),
            (Parameter::Frequency, SignalSpec::Harmonics { frequency, .. }) => *frequency = value,
            (Parameter::Amplitude(k), SignalSpec::Harmonics { amplitudes, .. }) => {
                if let Some(d) = amplitudes.get_mut(k) {
                    *d = value;
                }
            }
            (Parameter::Phase(k), SignalSpec::Harmonics { phases, .. }) => {
                if let Some(p) = phases.get_mut(k) {
                    *p = value;
                }
            }
            _ => {}
        }
        VariedScene {
            signal: spec,
            motor,
        }
    }

    /// A scale for the parameter (its own units): the distance to a change
    /// of the event structure is judged against it. The magnitude of the
    /// value, or a natural scale where the value may be 0 (`g_t` against
    /// `a_d`, the largest load sliding friction holds; an amplitude against
    /// the largest; a phase against 1 rad).
    pub fn scale(self, spec: &SignalSpec, motor: &Motor) -> f64 {
        let value = self.value(spec, motor.params()).unwrap_or(0.0).abs();
        let natural = match (self, spec) {
            // Sliding friction holds loads up to a_d (docs/model.md section 9).
            (Parameter::ExtraAcceleration, _) if motor.a_d() > 0.0 => motor.a_d(),
            (Parameter::ExtraAcceleration, _) => motor.a_0(),
            (Parameter::Amplitude(_), SignalSpec::Harmonics { amplitudes, .. }) => {
                amplitudes.iter().fold(0.0, |m: f64, d| m.max(d.abs()))
            }
            (Parameter::Phase(_), _) => 1.0,
            _ => 0.0,
        };
        let s = value.max(natural);
        if s > 0.0 { s } else { 1.0 }
    }

    /// The direction of this parameter for a scene with this signal spec,
    /// motor and (built) signal.
    pub fn tangent(
        self,
        spec: &SignalSpec,
        motor: &Motor,
        signal: &Signal,
    ) -> Result<Tangent, ParamError> {
        let p = motor.params();
        // The period follows a_0 only for a drive given by kappa.
        let kappa_based = matches!(spec.drive(), Some(Drive::Kappa(_)));
        // d ln T / d ln a_0 = -1/2 for a signal driven by kappa.
        let time_scale_of = |d_ln_a0: f64| {
            if kappa_based { -0.5 * d_ln_a0 } else { 0.0 }
        };
        let motor_tangent = |a_0: f64, a_d: f64, g_t: f64| {
            let d_ln_a0 = if motor.a_0() > 0.0 {
                a_0 / motor.a_0()
            } else {
                0.0
            };
            Tangent {
                a_0,
                a_d,
                g_t,
                rod: RodTangent {
                    time_scale: time_scale_of(d_ln_a0),
                    ..RodTangent::default()
                },
            }
        };
        let (f, m) = (p.contact_force, p.slider_mass);
        Ok(match self {
            Parameter::ExtraAcceleration => motor_tangent(0.0, 0.0, 1.0),
            Parameter::MuStatic => motor_tangent(f / m, 0.0, 0.0),
            Parameter::MuDynamic => motor_tangent(0.0, f / m, 0.0),
            Parameter::ContactForce => motor_tangent(p.mu_static / m, p.mu_dynamic / m, 0.0),
            Parameter::SliderMass => motor_tangent(-motor.a_0() / m, -motor.a_d() / m, 0.0),
            Parameter::Stroke => {
                let stroke = self.value(spec, p).unwrap_or(f64::NAN);
                Tangent {
                    rod: RodTangent {
                        scale: 1.0 / stroke,
                        // T = t_1 / duty with t_1 = sqrt(2 x_Rmax / a_R).
                        time_scale: if kappa_based { 0.5 / stroke } else { 0.0 },
                        ..RodTangent::default()
                    },
                    ..Tangent::none()
                }
            }
            Parameter::Kappa => {
                let kappa = self.value(spec, p).unwrap_or(f64::NAN);
                Tangent {
                    rod: RodTangent {
                        time_scale: -0.5 / kappa,
                        ..RodTangent::default()
                    },
                    ..Tangent::none()
                }
            }
            // d ln T / d f_0 = -1 / f_0 = -T.
            Parameter::Frequency => Tangent {
                rod: RodTangent {
                    time_scale: -signal.period(),
                    ..RodTangent::default()
                },
                ..Tangent::none()
            },
            // T = n / f_max: d ln T / d f_max = -1 / f_max.
            Parameter::FMax => {
                let f_max = self.value(spec, p).unwrap_or(f64::NAN);
                Tangent {
                    rod: RodTangent {
                        time_scale: -1.0 / f_max,
                        ..RodTangent::default()
                    },
                    ..Tangent::none()
                }
            }
            Parameter::Amplitude(_) | Parameter::Phase(_) => Tangent {
                rod: harmonics::tangent(spec, signal, self)?,
                ..Tangent::none()
            },
        })
    }
}
