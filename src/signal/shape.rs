//! The ideal signal's shape (docs/model.md section 2): its stroke, its
//! duty `t_1 / T` and its *drive*, the one quantity that fixes its
//! period, given as a scene gives it.
//!
//! The rod accelerates with `a_R` for `t_1`, reaching the stroke
//! `x_Rmax = a_R t_1^2 / 2`, and `T = t_1 / duty`. A drive is one of
//!
//! ```text
//! kappa = a_R / a_0:   a_R = kappa a_0,  t_1 = sqrt(2 x_Rmax / a_R),  T = t_1 / duty
//! f_0 (frequency):     T = 1 / f_0,      t_1 = duty T,               a_R = 2 x_Rmax / t_1^2
//! f_max = n f_0:       f_0 = f_max / n (fourier signals with n harmonics)
//! ```
//!
//! so `kappa = 2 x_Rmax f_0^2 / (duty^2 a_0)`: the two are the same
//! relation solved for the other side. Which one the scene gives is what
//! stays fixed when anything else changes: a drive given by `kappa`
//! retunes its period with the motor (`T ∝ a_0^(-1/2)`), a drive given by
//! a frequency keeps it. A `kappa` drive is computed exactly as written
//! above (`a_R`, then `t_1`, then `T`), so its signal does not depend on
//! the other forms existing.

use super::SignalSpec;
use crate::error::ParamError;
use crate::motor::Motor;

/// The quantity that fixes the period of an ideal shape, as given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// `kappa = a_R / a_0` (> 0; `signal.kappa` or `signal.sqrt_kappa`).
    Kappa(f64),
    /// The fundamental frequency `f_0` (Hz, > 0; `signal.frequency`).
    Frequency(f64),
    /// The highest frequency `f_max = n f_0` (Hz, > 0; `signal.f_max`),
    /// for a Fourier signal with `n` harmonics only.
    FMax(f64),
}

/// What a drive holds fixed: `kappa`, or the frequency (`f_0`, or
/// `f_max`, which at a fixed number of harmonics is the same).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Held {
    /// `kappa`: the period follows `a_0`.
    Kappa,
    /// The frequency: the period is fixed.
    Frequency,
}

impl Held {
    /// `"kappa"` or `"frequency"`.
    pub fn name(self) -> &'static str {
        match self {
            Held::Kappa => "kappa",
            Held::Frequency => "frequency",
        }
    }
}

impl Drive {
    /// The scene field that gives it: `kappa`, `frequency` or `f_max`.
    pub fn field(self) -> &'static str {
        match self {
            Drive::Kappa(_) => "kappa",
            Drive::Frequency(_) => "frequency",
            Drive::FMax(_) => "f_max",
        }
    }

    /// The value given.
    pub fn value(self) -> f64 {
        match self {
            Drive::Kappa(x) | Drive::Frequency(x) | Drive::FMax(x) => x,
        }
    }

    /// What it holds fixed.
    pub fn held(self) -> Held {
        match self {
            Drive::Kappa(_) => Held::Kappa,
            Drive::Frequency(_) | Drive::FMax(_) => Held::Frequency,
        }
    }

    /// Checks the value: finite and positive, named by its field.
    pub fn validate(self) -> Result<(), ParamError> {
        ParamError::positive(&format!("signal.{}", self.field()), self.value()).map(drop)
    }
}

/// The acceleration time and period of an ideal shape
/// ([`IdealShape::times`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdealTimes {
    /// The acceleration time `t_1` (s).
    pub t1: f64,
    /// The period `T` (s).
    pub period: f64,
}

/// The ideal signal (11) as a scene gives it: stroke, drive and duty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdealShape {
    /// Stroke `x_Rmax` in m (> 0).
    pub stroke: f64,
    /// What fixes the period: `kappa`, `f_0` or `f_max`.
    pub drive: Drive,
    /// `t_1 / T` in (0, 1]; 1 is the continuous signal.
    pub duty: f64,
}

impl IdealShape {
    /// The shape with `drive = kappa`.
    pub fn with_kappa(stroke: f64, kappa: f64, duty: f64) -> Self {
        Self {
            stroke,
            drive: Drive::Kappa(kappa),
            duty,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        ParamError::positive("signal.stroke", self.stroke)?;
        self.drive.validate()?;
        ParamError::positive("signal.duty", self.duty)?;
        if self.duty > 1.0 {
            return Err(ParamError::out_of_range(
                "signal.duty",
                self.duty,
                "must lie in (0, 1] (t_1 / T)",
            ));
        }
        Ok(())
    }

    /// The same shape with an `f_max` drive given as `f_0 = f_max / n`
    /// (`n` harmonics); other drives unchanged.
    pub fn resolved(self, harmonics: usize) -> Self {
        match self.drive {
            Drive::FMax(f) => Self {
                drive: Drive::Frequency(f / harmonics as f64),
                ..self
            },
            _ => self,
        }
    }

    /// Rod acceleration `a_R` in the acceleration phase: `kappa a_0`, or
    /// `2 x_Rmax / t_1^2` for a drive given by frequency. An `f_max`
    /// drive must be [`resolved`](Self::resolved) first (NaN otherwise).
    pub fn a_r(&self, motor: &Motor) -> f64 {
        match self.drive {
            Drive::Kappa(kappa) => kappa * motor.a_0(),
            Drive::Frequency(_) => {
                let t1 = self.times(motor).t1;
                2.0 * self.stroke / (t1 * t1)
            }
            Drive::FMax(_) => f64::NAN,
        }
    }

    /// Acceleration time `t_1` and period `T = t_1 / duty`: from
    /// `t_1 = sqrt(2 x_Rmax / a_R)` for a `kappa` drive, from `T = 1 / f_0`
    /// for a frequency (`t_1 = T` for the continuous signal). An `f_max`
    /// drive must be [`resolved`](Self::resolved) first (NaN otherwise).
    pub fn times(&self, motor: &Motor) -> IdealTimes {
        match self.drive {
            Drive::Kappa(_) => {
                let t1 = (2.0 * self.stroke / self.a_r(motor)).sqrt();
                IdealTimes {
                    t1,
                    period: t1 / self.duty,
                }
            }
            Drive::Frequency(f0) => {
                let period = 1.0 / f0;
                let t1 = if self.duty == 1.0 {
                    period
                } else {
                    self.duty * period
                };
                IdealTimes { t1, period }
            }
            Drive::FMax(_) => IdealTimes {
                t1: f64::NAN,
                period: f64::NAN,
            },
        }
    }

    /// `kappa = a_R / a_0` of this shape on `motor` (the value given for
    /// a `kappa` drive).
    pub fn kappa(&self, motor: &Motor) -> f64 {
        match self.drive {
            Drive::Kappa(kappa) => kappa,
            _ => self.a_r(motor) / motor.a_0(),
        }
    }

    /// The fundamental frequency `f_0` on `motor`: the value given for a
    /// frequency drive, `1 / T` for `kappa` (the signal's own `1 / T`).
    pub fn f0(&self, motor: &Motor) -> f64 {
        match self.drive {
            Drive::Frequency(f0) => f0,
            _ => 1.0 / self.times(motor).period,
        }
    }

    /// The same signal on `motor` with its drive given so that it holds
    /// `held`: `kappa = a_R / a_0` or `f_0 = 1 / T` (unchanged if it
    /// already holds it).
    pub fn holding(self, held: Held, motor: &Motor) -> Self {
        if self.drive.held() == held {
            return self;
        }
        let drive = match held {
            Held::Kappa => Drive::Kappa(self.kappa(motor)),
            Held::Frequency => Drive::Frequency(self.f0(motor)),
        };
        Self { drive, ..self }
    }
}

impl SignalSpec {
    /// The ideal shape of a `kappa`-based kind (`ideal`, `fourier`), with
    /// an `f_max` drive resolved to `f_0 = f_max / n`; `None` for
    /// `harmonics` and a voltage's response.
    pub fn shape(&self) -> Option<IdealShape> {
        match self {
            SignalSpec::Ideal(shape) => Some(*shape),
            SignalSpec::Fourier {
                shape, harmonics, ..
            } => Some(shape.resolved(*harmonics)),
            SignalSpec::Harmonics { .. } | SignalSpec::Response { .. } => None,
        }
    }

    /// The drive as the scene gives it; `None` for `harmonics` and a
    /// voltage's response, which give `frequency` directly.
    pub fn drive(&self) -> Option<Drive> {
        match self {
            SignalSpec::Ideal(shape) | SignalSpec::Fourier { shape, .. } => Some(shape.drive),
            SignalSpec::Harmonics { .. } | SignalSpec::Response { .. } => None,
        }
    }

    /// What the signal holds fixed when the motor changes: a `harmonics`
    /// signal or a voltage's response its frequency.
    pub fn held(&self) -> Held {
        self.drive().map_or(Held::Frequency, Drive::held)
    }

    /// The fundamental frequency `f_0` (Hz) on `motor`: the value given
    /// (`frequency`, `f_max / n`), or `1 / T` of a `kappa` drive, equal to
    /// the built signal's `1 / T`.
    pub fn f0(&self, motor: &Motor) -> f64 {
        match self {
            SignalSpec::Harmonics { frequency, .. } | SignalSpec::Response { frequency, .. } => {
                *frequency
            }
            _ => self.shape().map_or(f64::NAN, |s| s.f0(motor)),
        }
    }

    /// The same signal on `motor` with its drive given so that it holds
    /// `held` (`kappa = a_R / a_0`, or `f_0`); a `harmonics` signal, or
    /// one that already holds it, unchanged.
    pub fn holding(&self, held: Held, motor: &Motor) -> SignalSpec {
        let mut spec = self.clone();
        let resolved = self.shape();
        if let (SignalSpec::Ideal(shape) | SignalSpec::Fourier { shape, .. }, Some(resolved)) =
            (&mut spec, resolved)
            && shape.drive.held() != held
        {
            *shape = resolved.holding(held, motor);
        }
        spec
    }
}
