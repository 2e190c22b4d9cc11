//! The axes of a sweep: the scene parameters a sweep can vary, their
//! values, and how a value is set on a scene.

use crate::error::ParamError;
use crate::scene::Scene;
use crate::signal::{Drive, MAX_HARMONICS, SignalSpec};
use ordered_float::OrderedFloat;
use std::fmt;
use std::str::FromStr;

/// A sweep axis: a scene parameter that takes a list of values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Axis {
    /// `f_max` level `L = n sqrt(kappa)` (37), so `sqrt(kappa) = L / n`.
    Level,
    /// `sqrt(kappa)`.
    SqrtKappa,
    /// `kappa = a_R / a_0`.
    Kappa,
    /// `f_0` (Hz): `signal.frequency`.
    Frequency,
    /// `f_max = n f_0` (Hz), fourier signals.
    FMax,
    /// Number of harmonics `n`.
    Harmonics,
    /// Lanczos sigma factors (15) on or off.
    Sigma,
    /// `x_Rmax` (m).
    Stroke,
    /// `t_1 / T` of the ideal signal.
    Duty,
    /// `mu_0`.
    MuStatic,
    /// `mu_d`.
    MuDynamic,
    /// `F_c` (N).
    ContactForce,
    /// `m_s` (kg).
    SliderMass,
    /// `g_t` (m/s^2).
    ExtraAcceleration,
}

impl Axis {
    /// Every axis, in case order (the first varies slowest).
    pub const ALL: [Axis; 14] = [
        Axis::Level,
        Axis::SqrtKappa,
        Axis::Kappa,
        Axis::Frequency,
        Axis::FMax,
        Axis::Harmonics,
        Axis::Sigma,
        Axis::Stroke,
        Axis::Duty,
        Axis::MuStatic,
        Axis::MuDynamic,
        Axis::ContactForce,
        Axis::SliderMass,
        Axis::ExtraAcceleration,
    ];

    /// The name in sweep files and output columns.
    pub fn name(self) -> &'static str {
        match self {
            Axis::Level => "level",
            Axis::SqrtKappa => "sqrt_kappa",
            Axis::Kappa => "kappa",
            Axis::Frequency => "frequency",
            Axis::FMax => "f_max",
            Axis::Harmonics => "harmonics",
            Axis::Sigma => "sigma",
            Axis::Stroke => "stroke",
            Axis::Duty => "duty",
            Axis::MuStatic => "mu_static",
            Axis::MuDynamic => "mu_dynamic",
            Axis::ContactForce => "contact_force",
            Axis::SliderMass => "slider_mass",
            Axis::ExtraAcceleration => "extra_acceleration",
        }
    }

    /// Checks one value on its own (`field` is `axes.<name>[i]`).
    pub(super) fn check(self, field: &str, value: AxisValue) -> Result<(), ParamError> {
        match (self, value) {
            (Axis::Harmonics, AxisValue::Integer(n)) => {
                if usize::try_from(n).is_ok_and(|n| (1..=MAX_HARMONICS).contains(&n)) {
                    Ok(())
                } else {
                    Err(ParamError::out_of_range(
                        field,
                        n as f64,
                        format!("must be an integer from 1 to {MAX_HARMONICS}"),
                    ))
                }
            }
            (Axis::Sigma, AxisValue::Bool(_)) => Ok(()),
            (Axis::MuStatic | Axis::MuDynamic, AxisValue::Number(x)) => {
                ParamError::non_negative(field, x).map(drop)
            }
            (Axis::ExtraAcceleration, AxisValue::Number(x)) => {
                ParamError::finite(field, x).map(drop)
            }
            (Axis::Duty, AxisValue::Number(x)) => {
                ParamError::positive(field, x)?;
                if x > 1.0 {
                    Err(ParamError::out_of_range(
                        field,
                        x,
                        "must lie in (0, 1] (t_1 / T)",
                    ))
                } else {
                    Ok(())
                }
            }
            (Axis::SqrtKappa, AxisValue::Number(x)) => {
                ParamError::positive(field, x)?;
                if (x * x).is_finite() && x * x > 0.0 {
                    Ok(())
                } else {
                    Err(ParamError::out_of_range(
                        field,
                        x,
                        "its square kappa must be positive and finite",
                    ))
                }
            }
            (_, AxisValue::Number(x)) => ParamError::positive(field, x).map(drop),
            (_, other) => Err(ParamError::Inconsistent {
                field: field.to_owned(),
                reason: format!("{other} has the wrong type"),
            }),
        }
    }

    /// True if a sweep file may give `value` for this axis.
    pub(super) fn accepts(self, value: AxisValue) -> bool {
        self.check(self.name(), value).is_ok()
    }

    /// Why this axis cannot vary the base signal, or `None` if it can.
    pub(super) fn unfit_for(self, signal: &SignalSpec) -> Option<String> {
        let kind = match signal {
            SignalSpec::Fourier { .. } => return None,
            SignalSpec::Ideal(_) => "ideal",
            SignalSpec::Harmonics {
                scale_to_stroke, ..
            } => {
                if self == Axis::Stroke && scale_to_stroke.is_none() {
                    return Some(
                        "the base signal (kind = \"harmonics\") has scale_to_stroke = false"
                            .to_owned(),
                    );
                }
                "harmonics"
            }
        };
        // A harmonics signal has a frequency of its own.
        if self == Axis::Frequency {
            return None;
        }
        let needs_fourier = matches!(
            self,
            Axis::Level | Axis::FMax | Axis::Harmonics | Axis::Sigma
        );
        let needs_shape = matches!(self, Axis::SqrtKappa | Axis::Kappa | Axis::Duty);
        (needs_fourier || (needs_shape && kind == "harmonics")).then(|| {
            format!(
                "needs a base signal with kind = \"{}\", the base has kind = \"{kind}\"",
                if needs_fourier {
                    "fourier"
                } else {
                    "fourier\" or \"ideal"
                }
            )
        })
    }

    /// Sets this axis's parameter; `level` is applied by [`set_level`].
    /// `sqrt_kappa`, `kappa`, `frequency` and `f_max` replace the drive
    /// the base scene gave, whichever it was.
    pub(super) fn apply(self, scene: &mut Scene, value: AxisValue) {
        let motor = &mut scene.motor;
        let number = value.as_f64().unwrap_or(f64::NAN);
        match (self, &mut scene.signal) {
            (Axis::MuStatic, _) => motor.mu_static = number,
            (Axis::MuDynamic, _) => motor.mu_dynamic = number,
            (Axis::ContactForce, _) => motor.contact_force = number,
            (Axis::SliderMass, _) => motor.slider_mass = number,
            (Axis::ExtraAcceleration, _) => motor.extra_acceleration = number,
            (
                Axis::Stroke,
                SignalSpec::Harmonics {
                    scale_to_stroke, ..
                },
            ) => *scale_to_stroke = Some(number),
            (Axis::Frequency, SignalSpec::Harmonics { frequency, .. }) => *frequency = number,
            (Axis::Harmonics, SignalSpec::Fourier { harmonics, .. }) => {
                if let AxisValue::Integer(n) = value {
                    *harmonics = usize::try_from(n).unwrap_or(0);
                }
            }
            (Axis::Sigma, SignalSpec::Fourier { sigma, .. }) => {
                if let AxisValue::Bool(b) = value {
                    *sigma = b;
                }
            }
            (axis, SignalSpec::Fourier { shape, .. } | SignalSpec::Ideal(shape)) => match axis {
                Axis::SqrtKappa => shape.drive = Drive::Kappa(number * number),
                Axis::Kappa => shape.drive = Drive::Kappa(number),
                Axis::Frequency => shape.drive = Drive::Frequency(number),
                Axis::FMax => shape.drive = Drive::FMax(number),
                Axis::Stroke => shape.stroke = number,
                Axis::Duty => shape.duty = number,
                _ => {}
            },
            _ => {}
        }
    }
}

/// `sqrt(kappa) = level / n` (37).
pub(super) fn set_level(scene: &mut Scene, level: f64) {
    if let SignalSpec::Fourier {
        shape, harmonics, ..
    } = &mut scene.signal
    {
        let sqrt_kappa = level / *harmonics as f64;
        shape.drive = Drive::Kappa(sqrt_kappa * sqrt_kappa);
    }
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Axis {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| format!("unknown sweep axis \"{s}\""))
    }
}

/// One value of an axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AxisValue {
    /// A real number (SI units).
    Number(f64),
    /// An integer (`harmonics`).
    Integer(i64),
    /// A switch (`sigma`).
    Bool(bool),
}

impl AxisValue {
    /// The value as a number (`Integer` converted), `None` for a switch.
    pub fn as_f64(self) -> Option<f64> {
        match self {
            AxisValue::Number(x) => Some(x),
            AxisValue::Integer(n) => Some(n as f64),
            AxisValue::Bool(_) => None,
        }
    }

    /// The value as a switch, `None` for numbers.
    pub fn as_bool(self) -> Option<bool> {
        match self {
            AxisValue::Bool(b) => Some(b),
            _ => None,
        }
    }

    /// The value as an exact key: numbers compare, order and hash by their
    /// value with [`OrderedFloat`] (no rounding, no tolerance).
    pub fn key(self) -> AxisKey {
        match self {
            AxisValue::Number(x) => AxisKey::Number(OrderedFloat(x)),
            AxisValue::Integer(n) => AxisKey::Integer(n),
            AxisValue::Bool(b) => AxisKey::Bool(b),
        }
    }
}

/// An [`AxisValue`] as an exact, hashable key (see [`AxisValue::key`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum AxisKey {
    /// A real number.
    Number(OrderedFloat<f64>),
    /// An integer.
    Integer(i64),
    /// A switch.
    Bool(bool),
}

impl fmt::Display for AxisValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AxisValue::Number(x) => write!(f, "{x}"),
            AxisValue::Integer(n) => write!(f, "{n}"),
            AxisValue::Bool(b) => write!(f, "{b}"),
        }
    }
}
