//! The scene file as written (every table and field optional, nothing
//! checked) and its conversion to and from a validated [`Scene`].

use super::actuator_table::{ActuatorTable, VoltageTable, actuator_of, actuator_table};
use super::spring_table::{SpringTable, spring_of, spring_table};
use super::{EngineKind, Outputs, RunSettings, Scene};
use crate::actuator::GivenVoltage;
use crate::error::{Num, ParamError};
use crate::indicator::Indicator;
use crate::motor::MotorParams;
use crate::power::ActuatorParams;
use crate::signal::{Drive, IdealShape, MAX_HARMONICS, SignalSpec};
use serde::{Deserialize, Serialize};

/// The scene file as written: every table and optional field as an
/// `Option`, no value checked yet. Convert with [`Scene::try_from`].
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[motor]`; `None`: the paper's motor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motor: Option<MotorTable>,
    /// `[signal]`; `None`: the paper's signal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub signal: Option<SignalTable>,
    /// `[actuator]`; `None`: no power outputs, a prescribed rod.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub actuator: Option<ActuatorTable>,
    /// `[voltage]`; `None`: a driven rod's voltage is designed from the
    /// signal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voltage: Option<VoltageTable>,
    /// `[spring]`; `None`: no spring against the slider.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring: Option<SpringTable>,
    /// `[run]`; `None`: default run settings.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub run: Option<RunTable>,
    /// `[outputs]`; `None`: everything the scene allows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outputs: Option<OutputsTable>,
    /// `[optimize]`: read and checked by `stickslip optimize` only
    /// (`crate::optimize::spec`); every other command ignores it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub optimize: Option<toml::Table>,
}

/// The `[motor]` table (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotorTable {
    /// `m_s`, kg.
    pub slider_mass: f64,
    /// `F_c`, N.
    pub contact_force: f64,
    /// `mu_0`.
    pub mu_static: f64,
    /// `mu_d`.
    pub mu_dynamic: f64,
    /// `g_t`, m/s^2 (default 0).
    #[serde(default)]
    pub extra_acceleration: f64,
}

/// The signal `kind` of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SignalKind {
    /// The frequency-limited approximation (8) of the ideal signal.
    Fourier,
    /// The ideal signal (11).
    Ideal,
    /// An explicit harmonic series.
    Harmonics,
}

impl SignalKind {
    /// The spelling in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            SignalKind::Fourier => "fourier",
            SignalKind::Ideal => "ideal",
            SignalKind::Harmonics => "harmonics",
        }
    }
}

/// The `[signal]` table: the union of the fields of all kinds; which ones
/// are allowed depends on `kind` (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SignalTable {
    /// Which signal.
    pub kind: SignalKind,
    /// `x_Rmax`, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stroke: Option<f64>,
    /// `sqrt(kappa)`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sqrt_kappa: Option<f64>,
    /// `kappa = a_R / a_0`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kappa: Option<f64>,
    /// `n` (read as a signed integer so that `-1` is a value error, not a
    /// type error).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub harmonics: Option<i64>,
    /// Lanczos sigma factors (15).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma: Option<bool>,
    /// `t_1 / T`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duty: Option<f64>,
    /// `f_0`, Hz.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency: Option<f64>,
    /// `f_max = n f_0`, Hz (`fourier` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f_max: Option<f64>,
    /// `d_k`, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amplitudes: Option<Vec<f64>>,
    /// `phi_k`, rad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phases: Option<Vec<f64>>,
    /// Scale the amplitudes to `stroke`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale_to_stroke: Option<bool>,
    /// Shift the minimum to `t = 0`, `x_R = 0`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shift_to_minimum: Option<bool>,
}

/// The `[run]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunTable {
    /// Engine (default `event`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub engine: Option<EngineKind>,
    /// Fixed-step engine: steps per period of the highest harmonic.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps_per_harmonic: Option<i64>,
    /// Largest number of periods of the transient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_periods: Option<i64>,
    /// Simulate the start-up until it has converged to the steady state
    /// and cross-check the two (default false: stop at `p_0.99`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub verify_steady_state: Option<bool>,
    /// Wall-clock budget of each simulation, s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_limit_s: Option<f64>,
}

/// The `[outputs]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputsTable {
    /// Indicator names; `None`: all the scene allows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub indicators: Option<Vec<String>>,
    /// Record the steady-state period's trajectory (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trajectory: Option<bool>,
    /// Record the event log (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub events: Option<bool>,
}

impl TryFrom<SceneFile> for Scene {
    type Error = ParamError;

    fn try_from(file: SceneFile) -> Result<Self, Self::Error> {
        let motor = file
            .motor
            .map_or_else(MotorParams::default, |m| MotorParams {
                slider_mass: m.slider_mass,
                contact_force: m.contact_force,
                mu_static: m.mu_static,
                mu_dynamic: m.mu_dynamic,
                extra_acceleration: m.extra_acceleration,
            });
        let voltage = file.voltage.map(|t| GivenVoltage {
            frequency: t.frequency,
            amplitudes: t.amplitudes,
            phases: t.phases,
            offset: t.offset,
        });
        let (actuator, rod) = actuator_of(file.actuator, voltage.is_some())?;
        let signal = match (file.signal, &voltage, &actuator) {
            (Some(_), Some(_), _) => {
                return Err(ParamError::Inconsistent {
                    field: "voltage".to_owned(),
                    reason: "given together with [signal]: the rod's motion follows from the \
                             voltage; give one of the two"
                        .to_owned(),
                });
            }
            (Some(table), None, _) => signal_spec(table)?,
            // Checked with the scene (Scene::validate).
            (None, Some(v), Some(a)) => v.response(a),
            _ => SignalSpec::paper_default(),
        };
        let run = run_settings(file.run)?;
        let spring = spring_of(file.spring)?;
        let outputs = outputs(file.outputs, &signal, actuator.as_ref(), spring.is_some())?;
        let scene = Scene {
            motor,
            signal,
            actuator,
            rod,
            voltage,
            spring,
            run,
            outputs,
        };
        scene.validate()?;
        Ok(scene)
    }
}

impl From<&Scene> for SceneFile {
    fn from(scene: &Scene) -> Self {
        let m = &scene.motor;
        let signal = match &scene.signal {
            // A voltage's response is written as the voltage.
            _ if scene.voltage.is_some() => None,
            SignalSpec::Response { .. } => None,
            SignalSpec::Ideal(shape) => Some(SignalTable {
                duty: Some(shape.duty),
                ..shape_table(SignalKind::Ideal, shape)
            }),
            SignalSpec::Fourier {
                shape,
                harmonics,
                sigma,
            } => Some(SignalTable {
                harmonics: Some(i64::try_from(*harmonics).unwrap_or(i64::MAX)),
                sigma: Some(*sigma),
                duty: Some(shape.duty),
                ..shape_table(SignalKind::Fourier, shape)
            }),
            SignalSpec::Harmonics {
                frequency,
                amplitudes,
                phases,
                scale_to_stroke,
                shift_to_minimum,
            } => Some(SignalTable {
                frequency: Some(*frequency),
                amplitudes: Some(amplitudes.clone()),
                phases: Some(phases.clone()),
                scale_to_stroke: Some(scale_to_stroke.is_some()),
                stroke: *scale_to_stroke,
                shift_to_minimum: Some(*shift_to_minimum),
                ..empty_signal_table(SignalKind::Harmonics)
            }),
        };
        SceneFile {
            motor: Some(MotorTable {
                slider_mass: m.slider_mass,
                contact_force: m.contact_force,
                mu_static: m.mu_static,
                mu_dynamic: m.mu_dynamic,
                extra_acceleration: m.extra_acceleration,
            }),
            signal,
            actuator: actuator_table(scene.actuator, &scene.rod),
            voltage: scene.voltage.as_ref().map(|v| VoltageTable {
                frequency: v.frequency,
                amplitudes: v.amplitudes.clone(),
                phases: v.phases.clone(),
                offset: v.offset,
            }),
            spring: spring_table(scene.spring.as_ref()),
            run: Some(RunTable {
                engine: Some(scene.run.engine),
                steps_per_harmonic: Some(i64::from(scene.run.steps_per_harmonic)),
                max_periods: Some(i64::try_from(scene.run.max_periods).unwrap_or(i64::MAX)),
                verify_steady_state: Some(scene.run.verify_steady_state),
                time_limit_s: scene.run.time_limit_s,
            }),
            outputs: Some(OutputsTable {
                indicators: Some(
                    scene
                        .outputs
                        .indicators
                        .iter()
                        .map(|i| i.name().to_owned())
                        .collect(),
                ),
                trajectory: Some(scene.outputs.trajectory),
                events: Some(scene.outputs.events),
            }),
            optimize: None,
        }
    }
}

fn empty_signal_table(kind: SignalKind) -> SignalTable {
    SignalTable {
        kind,
        stroke: None,
        sqrt_kappa: None,
        kappa: None,
        harmonics: None,
        sigma: None,
        duty: None,
        frequency: None,
        f_max: None,
        amplitudes: None,
        phases: None,
        scale_to_stroke: None,
        shift_to_minimum: None,
    }
}

/// The shape with its drive written as the scene gave it (`sqrt_kappa` as
/// `kappa`).
fn shape_table(kind: SignalKind, shape: &IdealShape) -> SignalTable {
    let (kappa, frequency, f_max) = match shape.drive {
        Drive::Kappa(k) => (Some(k), None, None),
        Drive::Frequency(f) => (None, Some(f), None),
        Drive::FMax(f) => (None, None, Some(f)),
    };
    SignalTable {
        stroke: Some(shape.stroke),
        kappa,
        frequency,
        f_max,
        ..empty_signal_table(kind)
    }
}

/// An error for a field given with a `kind` that does not use it.
fn refuse_fields(kind: SignalKind, fields: &[(&str, bool)]) -> Result<(), ParamError> {
    match fields.iter().find(|(_, given)| *given) {
        Some((name, _)) => Err(ParamError::Inconsistent {
            field: format!("signal.{name}"),
            reason: format!("not used with kind = \"{}\"", kind.name()),
        }),
        None => Ok(()),
    }
}

fn required<T>(value: Option<T>, name: &str, kind: SignalKind) -> Result<T, ParamError> {
    value.ok_or_else(|| ParamError::Inconsistent {
        field: format!("signal.{name}"),
        reason: format!("missing: required with kind = \"{}\"", kind.name()),
    })
}

/// The drive from exactly one of `kappa`, `sqrt_kappa` (as
/// `kappa = sqrt_kappa^2`), `frequency` and `f_max`.
fn drive(t: &SignalTable) -> Result<Drive, ParamError> {
    const ONE_OF: &str = "give exactly one of signal.kappa, signal.sqrt_kappa, signal.frequency \
                          (f_0, Hz) and signal.f_max (Hz)";
    let given: Vec<(&str, f64)> = [
        ("kappa", t.kappa),
        ("sqrt_kappa", t.sqrt_kappa),
        ("frequency", t.frequency),
        ("f_max", t.f_max),
    ]
    .into_iter()
    .filter_map(|(name, value)| value.map(|v| (name, v)))
    .collect();
    let (name, value) = match given.as_slice() {
        [] => {
            return Err(ParamError::Inconsistent {
                field: "signal.kappa".to_owned(),
                reason: format!("missing: {ONE_OF}"),
            });
        }
        [one] => *one,
        [(name, value), rest @ ..] => {
            let others: Vec<String> = rest
                .iter()
                .map(|(n, v)| format!("signal.{n} = {}", Num(*v)))
                .collect();
            return Err(ParamError::out_of_range(
                &format!("signal.{name}"),
                *value,
                format!("{ONE_OF} (also given: {})", others.join(", ")),
            ));
        }
    };
    ParamError::positive(&format!("signal.{name}"), value)?;
    Ok(match name {
        "kappa" => Drive::Kappa(value),
        "sqrt_kappa" => {
            let k = value * value;
            if !(k.is_finite() && k > 0.0) {
                return Err(ParamError::out_of_range(
                    "signal.sqrt_kappa",
                    value,
                    format!("its square kappa = {} must be positive and finite", Num(k)),
                ));
            }
            Drive::Kappa(k)
        }
        "frequency" => Drive::Frequency(value),
        _ => Drive::FMax(value),
    })
}

fn signal_spec(t: SignalTable) -> Result<SignalSpec, ParamError> {
    let kind = t.kind;
    match kind {
        SignalKind::Fourier | SignalKind::Ideal => {
            refuse_fields(
                kind,
                &[
                    ("amplitudes", t.amplitudes.is_some()),
                    ("phases", t.phases.is_some()),
                    ("scale_to_stroke", t.scale_to_stroke.is_some()),
                    ("shift_to_minimum", t.shift_to_minimum.is_some()),
                ],
            )?;
            if let (SignalKind::Ideal, Some(f)) = (kind, t.f_max) {
                return Err(ParamError::out_of_range(
                    "signal.f_max",
                    f,
                    "not used with kind = \"ideal\" (its spectrum has no highest frequency); \
                     give signal.frequency",
                ));
            }
            let shape = IdealShape {
                stroke: required(t.stroke, "stroke", kind)?,
                drive: drive(&t)?,
                duty: t.duty.unwrap_or(1.0),
            };
            if kind == SignalKind::Ideal {
                refuse_fields(
                    kind,
                    &[
                        ("harmonics", t.harmonics.is_some()),
                        ("sigma", t.sigma.is_some()),
                    ],
                )?;
                return Ok(SignalSpec::Ideal(shape));
            }
            let n = required(t.harmonics, "harmonics", kind)?;
            let harmonics = usize::try_from(n)
                .ok()
                .filter(|n| (1..=MAX_HARMONICS).contains(n))
                .ok_or_else(|| {
                    ParamError::out_of_range(
                        "signal.harmonics",
                        n as f64,
                        format!("must be an integer from 1 to {MAX_HARMONICS}"),
                    )
                })?;
            Ok(SignalSpec::Fourier {
                shape,
                harmonics,
                sigma: t.sigma.unwrap_or(false),
            })
        }
        SignalKind::Harmonics => {
            refuse_fields(
                kind,
                &[
                    ("kappa", t.kappa.is_some()),
                    ("sqrt_kappa", t.sqrt_kappa.is_some()),
                    ("f_max", t.f_max.is_some()),
                    ("harmonics", t.harmonics.is_some()),
                    ("sigma", t.sigma.is_some()),
                    ("duty", t.duty.is_some()),
                ],
            )?;
            let scale_to_stroke = if t.scale_to_stroke.unwrap_or(false) {
                Some(t.stroke.ok_or_else(|| ParamError::Inconsistent {
                    field: "signal.stroke".to_owned(),
                    reason: "missing: required with scale_to_stroke = true".to_owned(),
                })?)
            } else if t.stroke.is_some() {
                return Err(ParamError::Inconsistent {
                    field: "signal.stroke".to_owned(),
                    reason: "only used with scale_to_stroke = true for kind = \"harmonics\""
                        .to_owned(),
                });
            } else {
                None
            };
            Ok(SignalSpec::Harmonics {
                frequency: required(t.frequency, "frequency", kind)?,
                amplitudes: required(t.amplitudes, "amplitudes", kind)?,
                phases: required(t.phases, "phases", kind)?,
                scale_to_stroke,
                shift_to_minimum: t.shift_to_minimum.unwrap_or(true),
            })
        }
    }
}

fn run_settings(table: Option<RunTable>) -> Result<RunSettings, ParamError> {
    let defaults = RunSettings::default();
    let Some(t) = table else {
        return Ok(defaults);
    };
    let steps_per_harmonic = match t.steps_per_harmonic {
        None => defaults.steps_per_harmonic,
        Some(s) => u32::try_from(s).ok().filter(|s| *s >= 1).ok_or_else(|| {
            ParamError::out_of_range(
                "run.steps_per_harmonic",
                s as f64,
                format!("must be an integer from 1 to {}", u32::MAX),
            )
        })?,
    };
    let max_periods = match t.max_periods {
        None => defaults.max_periods,
        Some(p) => u64::try_from(p).ok().filter(|p| *p >= 1).ok_or_else(|| {
            ParamError::out_of_range("run.max_periods", p as f64, "must be at least 1")
        })?,
    };
    Ok(RunSettings {
        engine: t.engine.unwrap_or(defaults.engine),
        steps_per_harmonic,
        max_periods,
        verify_steady_state: t
            .verify_steady_state
            .unwrap_or(defaults.verify_steady_state),
        time_limit_s: t.time_limit_s,
    })
}

fn outputs(
    table: Option<OutputsTable>,
    signal: &SignalSpec,
    actuator: Option<&ActuatorParams>,
    spring: bool,
) -> Result<Outputs, ParamError> {
    let t = table.unwrap_or(OutputsTable {
        indicators: None,
        trajectory: None,
        events: None,
    });
    let indicators = match t.indicators {
        None => Indicator::available(signal, actuator, spring),
        Some(names) => names
            .iter()
            .map(|name| {
                name.parse::<Indicator>()
                    .map_err(|e| ParamError::Inconsistent {
                        field: "outputs.indicators".to_owned(),
                        reason: e.to_string(),
                    })
            })
            .collect::<Result<Vec<_>, _>>()?,
    };
    Ok(Outputs {
        indicators,
        trajectory: t.trajectory.unwrap_or(false),
        events: t.events.unwrap_or(false),
    })
}
