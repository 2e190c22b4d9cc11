//! The axes of a sweep: the scene parameters a sweep can vary, their
//! values, and how a value is set on a scene.

use crate::error::ParamError;
use crate::scene::Scene;
use crate::signal::{Drive, MAX_HARMONICS, SignalSpec};
use crate::spring::SpringEnd;
use ordered_float::OrderedFloat;
use std::fmt;
use std::str::FromStr;

/// A sweep axis: a scene parameter that takes a list of values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SweepAxis {
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
    /// `k` (N/m) of the base scene's `[spring]`.
    SpringStiffness,
    /// `b` (N s/m) of the base scene's `[spring]`, a tied one (a free end
    /// takes only 0).
    SpringDamping,
    /// `x_gap` (m) of the base scene's free-ended `[spring]`.
    SpringGap,
    /// `F_p` (N) of the base scene's tied `[spring]`.
    SpringPreload,
}

impl SweepAxis {
    /// Every axis, in case order (the first varies slowest).
    pub const ALL: [SweepAxis; 18] = [
        SweepAxis::Level,
        SweepAxis::SqrtKappa,
        SweepAxis::Kappa,
        SweepAxis::Frequency,
        SweepAxis::FMax,
        SweepAxis::Harmonics,
        SweepAxis::Sigma,
        SweepAxis::Stroke,
        SweepAxis::Duty,
        SweepAxis::MuStatic,
        SweepAxis::MuDynamic,
        SweepAxis::ContactForce,
        SweepAxis::SliderMass,
        SweepAxis::ExtraAcceleration,
        SweepAxis::SpringStiffness,
        SweepAxis::SpringDamping,
        SweepAxis::SpringGap,
        SweepAxis::SpringPreload,
    ];

    /// The name in sweep files and output columns.
    pub fn name(self) -> &'static str {
        match self {
            SweepAxis::Level => "level",
            SweepAxis::SqrtKappa => "sqrt_kappa",
            SweepAxis::Kappa => "kappa",
            SweepAxis::Frequency => "frequency",
            SweepAxis::FMax => "f_max",
            SweepAxis::Harmonics => "harmonics",
            SweepAxis::Sigma => "sigma",
            SweepAxis::Stroke => "stroke",
            SweepAxis::Duty => "duty",
            SweepAxis::MuStatic => "mu_static",
            SweepAxis::MuDynamic => "mu_dynamic",
            SweepAxis::ContactForce => "contact_force",
            SweepAxis::SliderMass => "slider_mass",
            SweepAxis::ExtraAcceleration => "extra_acceleration",
            SweepAxis::SpringStiffness => "spring.stiffness",
            SweepAxis::SpringDamping => "spring.damping",
            SweepAxis::SpringGap => "spring.gap",
            SweepAxis::SpringPreload => "spring.preload",
        }
    }

    /// Checks one value on its own (`field` is `axes.<name>[i]`).
    pub(super) fn check(self, field: &str, value: AxisValue) -> Result<(), ParamError> {
        match (self, value) {
            (SweepAxis::Harmonics, AxisValue::Integer(n)) => {
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
            (SweepAxis::Sigma, AxisValue::Bool(_)) => Ok(()),
            (
                SweepAxis::MuStatic
                | SweepAxis::MuDynamic
                | SweepAxis::SpringDamping
                | SweepAxis::SpringGap,
                AxisValue::Number(x),
            ) => ParamError::non_negative(field, x).map(drop),
            (SweepAxis::ExtraAcceleration | SweepAxis::SpringPreload, AxisValue::Number(x)) => {
                ParamError::finite(field, x).map(drop)
            }
            (SweepAxis::Duty, AxisValue::Number(x)) => {
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
            (SweepAxis::SqrtKappa, AxisValue::Number(x)) => {
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

    /// True for the axes of the `[spring]` table.
    fn is_spring(self) -> bool {
        matches!(
            self,
            SweepAxis::SpringStiffness
                | SweepAxis::SpringDamping
                | SweepAxis::SpringGap
                | SweepAxis::SpringPreload
        )
    }

    /// Why this axis cannot vary the base scene, or `None` if it can: a
    /// spring axis needs the base scene's `[spring]`, of the kind that
    /// takes the field (as the `[spring]` table refuses `gap` on a tied
    /// spring and `preload` on a free end); a motor axis always fits; a
    /// signal axis must fit the base signal (`unfit_for_signal`).
    pub(super) fn unfit_for(self, base: &Scene) -> Option<String> {
        if !self.is_spring() {
            return self.unfit_for_signal(&base.signal);
        }
        let Some(spring) = &base.spring else {
            return Some(format!(
                "the base scene has no [spring]: give it one to vary {}",
                self.name()
            ));
        };
        match (self, spring.end) {
            (SweepAxis::SpringGap, SpringEnd::Tied { .. }) => Some(
                "applies to a free end (spring.tied = false); the base scene's spring is tied, \
                 which takes spring.preload"
                    .to_owned(),
            ),
            (SweepAxis::SpringPreload, SpringEnd::Free { .. }) => Some(
                "applies to a tied spring (spring.tied = true); the base scene's spring has a \
                 free end, which takes spring.gap"
                    .to_owned(),
            ),
            _ => None,
        }
    }

    /// Why this axis cannot vary the base signal, or `None` if it can (a
    /// motor axis always can; a signal axis cannot vary a voltage's
    /// response).
    fn unfit_for_signal(self, signal: &SignalSpec) -> Option<String> {
        let kind = match signal {
            SignalSpec::Fourier { .. } => return None,
            SignalSpec::Ideal(_) => "ideal",
            SignalSpec::Response { .. } => {
                let motor = matches!(
                    self,
                    SweepAxis::MuStatic
                        | SweepAxis::MuDynamic
                        | SweepAxis::ContactForce
                        | SweepAxis::SliderMass
                        | SweepAxis::ExtraAcceleration
                );
                return (!motor).then(|| {
                    "the base scene gives the voltage ([voltage]), not the rod signal: \
                     the rod's motion follows from it"
                        .to_owned()
                });
            }
            SignalSpec::Harmonics {
                scale_to_stroke, ..
            } => {
                if self == SweepAxis::Stroke && scale_to_stroke.is_none() {
                    return Some(
                        "the base signal (kind = \"harmonics\") has scale_to_stroke = false"
                            .to_owned(),
                    );
                }
                "harmonics"
            }
        };
        // A harmonics signal has a frequency of its own.
        if self == SweepAxis::Frequency {
            return None;
        }
        let needs_fourier = matches!(
            self,
            SweepAxis::Level | SweepAxis::FMax | SweepAxis::Harmonics | SweepAxis::Sigma
        );
        let needs_shape = matches!(
            self,
            SweepAxis::SqrtKappa | SweepAxis::Kappa | SweepAxis::Duty
        );
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
        if let Some(spring) = scene.spring.as_mut() {
            match (self, &mut spring.end) {
                (SweepAxis::SpringStiffness, _) => spring.stiffness = number,
                (SweepAxis::SpringDamping, _) => spring.damping = number,
                (SweepAxis::SpringGap, SpringEnd::Free { gap }) => *gap = number,
                (SweepAxis::SpringPreload, SpringEnd::Tied { preload }) => *preload = number,
                _ => {}
            }
        }
        match (self, &mut scene.signal) {
            (SweepAxis::MuStatic, _) => motor.mu_static = number,
            (SweepAxis::MuDynamic, _) => motor.mu_dynamic = number,
            (SweepAxis::ContactForce, _) => motor.contact_force = number,
            (SweepAxis::SliderMass, _) => motor.slider_mass = number,
            (SweepAxis::ExtraAcceleration, _) => motor.extra_acceleration = number,
            (
                SweepAxis::Stroke,
                SignalSpec::Harmonics {
                    scale_to_stroke, ..
                },
            ) => *scale_to_stroke = Some(number),
            (SweepAxis::Frequency, SignalSpec::Harmonics { frequency, .. }) => *frequency = number,
            (SweepAxis::Harmonics, SignalSpec::Fourier { harmonics, .. }) => {
                if let AxisValue::Integer(n) = value {
                    *harmonics = usize::try_from(n).unwrap_or(0);
                }
            }
            (SweepAxis::Sigma, SignalSpec::Fourier { sigma, .. }) => {
                if let AxisValue::Bool(b) = value {
                    *sigma = b;
                }
            }
            (axis, SignalSpec::Fourier { shape, .. } | SignalSpec::Ideal(shape)) => match axis {
                SweepAxis::SqrtKappa => shape.drive = Drive::Kappa(number * number),
                SweepAxis::Kappa => shape.drive = Drive::Kappa(number),
                SweepAxis::Frequency => shape.drive = Drive::Frequency(number),
                SweepAxis::FMax => shape.drive = Drive::FMax(number),
                SweepAxis::Stroke => shape.stroke = number,
                SweepAxis::Duty => shape.duty = number,
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

impl fmt::Display for SweepAxis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SweepAxis {
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
