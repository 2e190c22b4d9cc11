//! Typed errors. Each subsystem has its own enum with structured fields;
//! [`enum@Error`] gathers them for callers that do not care which one failed.
//!
//! Parameter errors always carry the offending field's path as it is
//! spelled in a scene file (`motor.slider_mass`, `signal.harmonics`) and the
//! value, so that a message can be acted on without reading the code.

use std::fmt;
use thiserror::Error;

/// A number as messages print it: plain for everyday magnitudes and for
/// integers below `1e16` (`0.2`, `-3`, `1574.8`, `4294967295`), scientific
/// otherwise (`5e-324`, `2.5e-5`, `1.5e9`, `1e300`), so that no message
/// spells out hundreds of zeros. Every `f64` in an error message goes
/// through it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        let integer = x.fract() == 0.0 && magnitude < 1e16;
        if integer || !x.is_finite() || (1e-4..1e9).contains(&magnitude) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// An invalid parameter value, named by its scene path.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ParamError {
    /// NaN or infinite.
    #[error("{field} = {}: must be a finite number", Num(*value))]
    NonFinite {
        /// Scene path of the field.
        field: String,
        /// The value given.
        value: f64,
    },
    /// Zero or negative where a positive value is required.
    #[error("{field} = {}: must be positive", Num(*value))]
    NotPositive {
        /// Scene path of the field.
        field: String,
        /// The value given.
        value: f64,
    },
    /// Outside its allowed range.
    #[error("{field} = {}: {requirement}", Num(*value))]
    OutOfRange {
        /// Scene path of the field.
        field: String,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        requirement: String,
    },
    /// A combination of fields that does not fit together.
    #[error("{field}: {reason}")]
    Inconsistent {
        /// Scene path of the field.
        field: String,
        /// Why it does not fit.
        reason: String,
    },
}

impl ParamError {
    /// Checks that `value` is finite.
    pub fn finite(field: &str, value: f64) -> Result<f64, ParamError> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(ParamError::NonFinite {
                field: field.to_owned(),
                value,
            })
        }
    }

    /// Checks that `value` is finite and strictly positive.
    pub fn positive(field: &str, value: f64) -> Result<f64, ParamError> {
        Self::finite(field, value)?;
        if value > 0.0 {
            Ok(value)
        } else {
            Err(ParamError::NotPositive {
                field: field.to_owned(),
                value,
            })
        }
    }

    /// Checks that `value` is finite and not negative.
    pub fn non_negative(field: &str, value: f64) -> Result<f64, ParamError> {
        Self::finite(field, value)?;
        if value >= 0.0 {
            Ok(value)
        } else {
            Err(ParamError::OutOfRange {
                field: field.to_owned(),
                value,
                requirement: "must not be negative".to_owned(),
            })
        }
    }

    /// An out-of-range error with a free-form requirement.
    pub fn out_of_range(field: &str, value: f64, requirement: impl Into<String>) -> Self {
        ParamError::OutOfRange {
            field: field.to_owned(),
            value,
            requirement: requirement.into(),
        }
    }
}

/// Failures of a simulation run (after the scene was accepted).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SimulationError {
    /// The period map has no fixed point: the slider does not settle into a
    /// periodic motion but keeps accelerating in one direction (a run-away:
    /// the extra acceleration exceeds what sliding friction can hold).
    #[error(
        "no periodic steady state: the slider runs away, its velocity keeps {direction} \
         (slider velocity {velocity:e} m/s after {periods} periods, outside the rod's \
         velocity range, sliding without any event; motor.extra_acceleration exceeds \
         what sliding friction can hold)"
    )]
    NoSteadyState {
        /// "growing" or "falling".
        direction: &'static str,
        /// Last boundary velocity seen.
        velocity: f64,
        /// Periods simulated.
        periods: u64,
    },
    /// The start-up from rest did not establish its limit within
    /// `run.max_periods` (for callers that need a steady state; `stickslip
    /// run` reports it as a result).
    #[error(
        "no steady state established: the start-up from rest did not converge within \
         {periods} periods (run.max_periods); last mean velocity {last_v_p:e} m/s"
    )]
    NotConverged {
        /// Periods simulated.
        periods: u64,
        /// Mean velocity of the last simulated period (m/s).
        last_v_p: f64,
    },
    /// More events in one period than the engine allows: the motion
    /// chatters (Zeno behaviour) at the given place.
    #[error(
        "more than {limit} events in period {period} (last at phase {} s): \
         the motion chatters", Num(*phase)
    )]
    TooManyEvents {
        /// The per-period event limit.
        limit: u64,
        /// Period index (1-based).
        period: u64,
        /// Phase of the last event in that period, s.
        phase: f64,
    },
    /// The wall-clock budget (`run.time_limit_s` or `--time-limit`) ran
    /// out before the run finished.
    #[error(
        "time limit of {} s reached after {period} simulated periods; the run \
         stopped there (raise run.time_limit_s or --time-limit to let it go on)",
        Num(*seconds)
    )]
    TimeLimit {
        /// The budget, s.
        seconds: f64,
        /// Periods simulated when the budget ran out (period-map
        /// evaluations included): how far the run got.
        period: u64,
    },
    /// The signal's event structure could not be computed.
    #[error("signal analysis failed: {0}")]
    Signal(String),
    /// The steady state has no derivatives with respect to the scene's
    /// parameters (docs/model.md section 14): the reason.
    #[error("no sensitivities: {0}")]
    NoSensitivity(String),
}

/// Scene files: reading, parsing and validating.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene file {path}: {source}")]
    Io {
        /// The path given.
        path: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// Not valid TOML, an unknown field, or a value of the wrong type.
    #[error("invalid scene {path}: {message}")]
    Parse {
        /// The path given (or `<string>`).
        path: String,
        /// The parser's message, which names the field and line.
        message: String,
    },
    /// A value that parses but is not allowed.
    #[error("invalid scene {path}: {source}")]
    Param {
        /// The path given (or `<string>`).
        path: String,
        /// The offending field and value.
        source: ParamError,
    },
    /// An override (`--set PATH=VALUE`) that does not fit the scene.
    #[error("scene {path}: {source}")]
    Override {
        /// The path given (or `<string>`).
        path: String,
        /// The override and what is wrong with it.
        source: OverrideError,
    },
}

/// A malformed override `PATH=VALUE` (`--set`, `crate::scene::Override`),
/// or one that does not fit the scene's table.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("--set {given}: {reason}")]
pub struct OverrideError {
    /// The override as given (control characters escaped).
    pub given: String,
    /// What is wrong with it.
    pub reason: String,
}

/// Sweep files, sweep outputs and their merging.
#[derive(Debug, Error)]
pub enum SweepError {
    /// A file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path given.
        path: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// An output file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The output path.
        path: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// Not valid TOML, an unknown field, or a value of the wrong type.
    #[error("invalid sweep {path}: {message}")]
    Parse {
        /// The sweep file (or `<string>`).
        path: String,
        /// The parser's message.
        message: String,
    },
    /// The base scene could not be loaded.
    #[error("invalid sweep {path}: base scene: {source}")]
    Base {
        /// The sweep file.
        path: String,
        /// Why the base scene failed.
        source: Box<SceneError>,
    },
    /// A bad axis value or output setting, named by its sweep field
    /// (`axes.level[2] = -3: must be positive`).
    #[error("invalid sweep {path}: {source}")]
    Param {
        /// The sweep file.
        path: String,
        /// The sweep field and value.
        source: ParamError,
    },
    /// A case whose combination of axis values is not a valid scene.
    #[error("invalid sweep {path}: case {case} ({values}): {source}")]
    Case {
        /// The sweep file.
        path: String,
        /// The case index.
        case: usize,
        /// The case's axis values, `name = value, ...`.
        values: String,
        /// The scene field and value at fault (boxed: keeps [`enum@Error`] small).
        source: Box<ParamError>,
    },
    /// More cases than a sweep may have.
    #[error("invalid sweep {path}: {cases} cases, more than the {max} a sweep may have")]
    TooLarge {
        /// The sweep file.
        path: String,
        /// The number of cases (saturated at `u128::MAX`).
        cases: u128,
        /// The limit.
        max: usize,
    },
    /// A bad `--shard i/N`.
    #[error("bad shard \"{given}\": {reason}")]
    Shard {
        /// What was given.
        given: String,
        /// What is wrong.
        reason: String,
    },
    /// An existing output or a merge input that does not fit.
    #[error("{path}: {reason}")]
    Output {
        /// The file.
        path: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// Any error of the crate.
#[derive(Debug, Error)]
pub enum Error {
    /// Bad parameter value.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A run that could not finish.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// A scene that could not be loaded.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A sweep that could not be loaded, run or written.
    #[error(transparent)]
    Sweep(#[from] SweepError),
}
