//! Plausibility warnings: values that are allowed but far from any real
//! piezo inertia drive (a stroke of a metre, a kilogram slider); printed,
//! never fatal.

use super::Scene;
use crate::error::Num;
use crate::motor::Motor;
use crate::signal::{Drive, FourierSignal, SignalSpec};
use std::fmt;

/// Plausible strokes (and harmonic amplitudes) of a piezo inertia drive, m:
/// 1 nm to 1 mm (the paper's is 25 um).
pub(crate) const PLAUSIBLE_STROKE: (f64, f64) = (1e-9, 1e-3);
/// Highest plausible fundamental frequency, Hz (10 MHz; the paper's drive
/// runs at 1.6 kHz, piezo stacks resonate below 1 MHz).
pub(crate) const PLAUSIBLE_MAX_FREQUENCY: f64 = 10e6;
/// Plausible slider masses, kg: 1 mg to 10 kg (the paper's is 1.4 g).
pub(crate) const PLAUSIBLE_SLIDER_MASS: (f64, f64) = (1e-6, 10.0);
/// Highest plausible contact force, N (1 kN; the paper's is 1 N).
pub(crate) const PLAUSIBLE_MAX_CONTACT_FORCE: f64 = 1e3;
/// Highest plausible friction coefficient (dry friction of solids lies
/// below about 1.5; the paper's mu_0 is 0.17).
pub(crate) const PLAUSIBLE_MAX_FRICTION: f64 = 2.0;
/// Highest plausible `kappa = a_R / a_0` (the paper's figures use 1 to
/// about 400): a slider gains at most `a_0 T`, a `1 / (kappa duty)` part of
/// the rod's peak velocity, per period, so beyond this the start-up from
/// rest takes very many periods.
pub(crate) const PLAUSIBLE_MAX_KAPPA: f64 = 1e4;

/// A value that is valid but implausible for a piezo inertia drive,
/// usually a unit slip. Displayed as one line:
/// `signal.stroke = 25 m is above 1 mm; strokes are in metres (25 um = 25e-6)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// Scene path of the field.
    pub field: String,
    /// The value given.
    pub value: f64,
    /// Its unit, as printed after the value (empty for a ratio).
    pub unit: &'static str,
    /// What is implausible and what was probably meant.
    pub reason: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {}", self.field, Num(self.value))?;
        if !self.unit.is_empty() {
            write!(f, " {}", self.unit)?;
        }
        write!(f, " {}", self.reason)
    }
}

impl Scene {
    /// Values that are valid but implausible for a piezo inertia drive
    /// (bounds: the `PLAUSIBLE_*` constants), in field order. A run goes on
    /// regardless; the command line prints these on stderr unless
    /// `--quiet`.
    pub fn warnings(&self) -> Vec<Warning> {
        let mut out = Vec::new();
        let mut warn = |field: &str, value: f64, unit: &'static str, reason: String| {
            out.push(Warning {
                field: field.to_owned(),
                value,
                unit,
                reason,
            });
        };
        let m = &self.motor;
        let (mass_lo, mass_hi) = PLAUSIBLE_SLIDER_MASS;
        if m.slider_mass > mass_hi {
            warn(
                "motor.slider_mass",
                m.slider_mass,
                "kg",
                "is above 10 kg; masses are in kg (1.4 g = 1.4e-3)".to_owned(),
            );
        } else if m.slider_mass < mass_lo {
            warn(
                "motor.slider_mass",
                m.slider_mass,
                "kg",
                "is below 1 mg; masses are in kg (1.4 g = 1.4e-3)".to_owned(),
            );
        }
        if m.contact_force > PLAUSIBLE_MAX_CONTACT_FORCE {
            warn(
                "motor.contact_force",
                m.contact_force,
                "N",
                "is above 1 kN; forces are in N (a piezo inertia drive presses with a few N)"
                    .to_owned(),
            );
        }
        for (field, mu) in [
            ("motor.mu_static", m.mu_static),
            ("motor.mu_dynamic", m.mu_dynamic),
        ] {
            if mu > PLAUSIBLE_MAX_FRICTION {
                warn(
                    field,
                    mu,
                    "",
                    "is above 2; friction coefficients of dry contacts lie between about 0.05 and 1"
                        .to_owned(),
                );
            }
        }
        let stroke_warning = |value: f64, noun: &str| {
            let (lo, hi) = PLAUSIBLE_STROKE;
            let bound = if value > hi {
                "above 1 mm"
            } else if value < lo {
                "below 1 nm"
            } else {
                return None;
            };
            Some(if value > hi {
                // The value given, read in micrometres: its decimal
                // exponent lowered by 6 in the text, not by a rounded
                // product.
                let scientific = format!("{value:e}");
                let (mantissa, exponent) = scientific
                    .split_once('e')
                    .expect("`{:e}` writes an exponent");
                let exponent: i32 = exponent.parse().expect("an integer exponent");
                format!(
                    "is {bound}; {noun} are in metres ({} um = {mantissa}e{} m)",
                    Num(value),
                    exponent - 6
                )
            } else {
                format!("is {bound}; {noun} are in metres (25 um = 2.5e-5 m)")
            })
        };
        match &self.signal {
            SignalSpec::Ideal(shape) | SignalSpec::Fourier { shape, .. } => {
                if let Some(reason) = stroke_warning(shape.stroke, "strokes") {
                    warn("signal.stroke", shape.stroke, "m", reason);
                }
                let drive = shape.drive;
                if let Drive::Kappa(kappa) = drive
                    && kappa > PLAUSIBLE_MAX_KAPPA
                {
                    warn(
                        "signal.kappa",
                        kappa,
                        "",
                        format!(
                            "is above {}: a slider gains at most 1/(kappa duty) of the rod's \
                             peak velocity per period, so the start-up may take of the order \
                             of {} periods (run.max_periods = {}; run.time_limit_s bounds the run)",
                            Num(PLAUSIBLE_MAX_KAPPA),
                            Num((kappa * shape.duty).round()),
                            self.run.max_periods
                        ),
                    );
                }
                let resolved = self.signal.shape();
                if let (Ok(motor), Some(resolved)) = (Motor::new(self.motor), resolved) {
                    let f0 = resolved.f0(&motor);
                    let kappa = resolved.kappa(&motor);
                    let field = format!("signal.{}", drive.field());
                    if !matches!(drive, Drive::Kappa(_))
                        && kappa.is_finite()
                        && kappa > PLAUSIBLE_MAX_KAPPA
                    {
                        warn(
                            &field,
                            drive.value(),
                            "Hz",
                            format!(
                                "gives kappa = a_R / a_0 = {} (a_0 = {} m/s^2), above {}: a \
                                 slider gains at most 1/(kappa duty) of the rod's peak velocity \
                                 per period, so the start-up may take of the order of {} periods",
                                Num(kappa),
                                Num(motor.a_0()),
                                Num(PLAUSIBLE_MAX_KAPPA),
                                Num((kappa * shape.duty).round()),
                            ),
                        );
                    }
                    if f0 > PLAUSIBLE_MAX_FREQUENCY {
                        match drive {
                            Drive::Kappa(kappa) => warn(
                                "signal.stroke",
                                shape.stroke,
                                "m",
                                format!(
                                    "with signal.kappa = {} and a_0 = {} m/s^2 gives the \
                                     frequency f_0 = {} Hz, above 10 MHz; check the units of \
                                     the stroke (m), the motor and kappa",
                                    Num(kappa),
                                    Num(motor.a_0()),
                                    Num(f0)
                                ),
                            ),
                            _ => warn(
                                &field,
                                drive.value(),
                                "Hz",
                                format!(
                                    "gives f_0 = {} Hz, above 10 MHz; frequencies are in Hz \
                                     (1.6 kHz = 1600)",
                                    Num(f0)
                                ),
                            ),
                        }
                    }
                }
            }
            SignalSpec::Harmonics {
                frequency,
                amplitudes,
                scale_to_stroke,
                ..
            } => {
                if *frequency > PLAUSIBLE_MAX_FREQUENCY {
                    warn(
                        "signal.frequency",
                        *frequency,
                        "Hz",
                        "is above 10 MHz; frequencies are in Hz (1.6 kHz = 1600)".to_owned(),
                    );
                }
                match scale_to_stroke {
                    Some(stroke) => {
                        if let Some(reason) = stroke_warning(*stroke, "strokes") {
                            warn("signal.stroke", *stroke, "m", reason);
                        }
                    }
                    None => {
                        for (k, d) in amplitudes.iter().enumerate() {
                            if *d > PLAUSIBLE_STROKE.1 {
                                warn(
                                    &format!("signal.amplitudes[{k}]"),
                                    *d,
                                    "m",
                                    stroke_warning(*d, "amplitudes").unwrap_or_default(),
                                );
                            }
                        }
                    }
                }
            }
            SignalSpec::Response {
                frequency,
                offset,
                cosines,
                sines,
            } => {
                if *frequency > PLAUSIBLE_MAX_FREQUENCY {
                    warn(
                        "voltage.frequency",
                        *frequency,
                        "Hz",
                        "is above 10 MHz; frequencies are in Hz (1.6 kHz = 1600)".to_owned(),
                    );
                }
                let stroke = FourierSignal::from_coefficients(
                    1.0 / frequency,
                    *offset,
                    cosines.clone(),
                    sines.clone(),
                )
                .stroke();
                let (lo, hi) = PLAUSIBLE_STROKE;
                let largest = self.voltage.as_ref().map_or(f64::NAN, |v| {
                    v.amplitudes.iter().copied().fold(0.0, f64::max)
                });
                if stroke.is_finite() && !(lo..=hi).contains(&stroke) {
                    warn(
                        "voltage.amplitudes",
                        largest,
                        "V",
                        format!(
                            "(the largest) move the [actuator]'s rod by a stroke of {} m, {} \
                             1 {}; voltages are in V",
                            Num(stroke),
                            if stroke > hi { "above" } else { "below" },
                            if stroke > hi { "mm" } else { "nm" }
                        ),
                    );
                }
            }
        }
        out
    }
}
