//! Scene files: what to simulate and what to report, in TOML.
//!
//! A scene is read in two steps, so that nothing unchecked reaches the
//! simulation: serde reads the text into a [`SceneFile`], which mirrors the
//! format and rejects unknown fields, and [`Scene::try_from`] checks every
//! value and builds the typed [`Scene`]. The field names are the user-facing
//! contract of `docs/interface.md` and do not change.
//!
//! # Format
//!
//! All values in SI units. Every table may be omitted: without `[motor]`
//! the paper's motor ([`MotorParams::default`]), without `[signal]` the
//! paper's signal ([`SignalSpec::paper_default`]), without `[actuator]` no
//! power outputs. An empty file is therefore [`Scene::default`] without its
//! actuator; `examples/scenes/paper_default.toml` is `Scene::default()`
//! written out.
//!
//! ```toml
//! [motor]                     # omitted: the paper's motor (MotorParams::default)
//! slider_mass = 1.4e-3        # m_s, kg, > 0                       (required)
//! contact_force = 1.0         # F_c, N, > 0                         (required)
//! mu_static = 0.1736          # mu_0, >= 0                          (required)
//! mu_dynamic = 0.1568         # mu_d, 0 <= mu_d <= mu_0             (required)
//! extra_acceleration = 0.0    # g_t, m/s^2, finite                  (default 0)
//!
//! [signal]                    # omitted: the paper's signal (SignalSpec::paper_default)
//! kind = "fourier"            # "fourier" | "ideal" | "harmonics"   (required)
//! # kind = "fourier" and kind = "ideal":
//! stroke = 25e-6              # x_Rmax, m, > 0                      (required)
//! sqrt_kappa = 6.0            # or kappa = 36.0: exactly one of the two, > 0
//! duty = 1.0                  # t_1 / T in (0, 1]; 1 = continuous   (default 1)
//! # kind = "fourier" only:
//! harmonics = 2               # n, 1..=256                          (required)
//! sigma = true                # Lanczos sigma factors (15)          (default false)
//! # kind = "harmonics" only (x_R = sum_k d_k sin(k w_0 t + phi_k)):
//! # frequency = 1574.8        # f_0, Hz, > 0                        (required)
//! # amplitudes = [..]         # d_k, m, >= 0, not all 0             (required)
//! # phases = [..]             # phi_k, rad, as many as amplitudes   (required)
//! # scale_to_stroke = false   # scale so that max - min = stroke    (default false)
//! # stroke = 25e-6            # m: required with scale_to_stroke = true, refused otherwise
//! # shift_to_minimum = true   # minimum at t = 0 with x_R = 0       (default true)
//!
//! [actuator]                  # optional; all five fields required when given
//! mass = 3.2e-3               # M, kg, > 0
//! damping = 9.50              # d, N s/m, > 0
//! stiffness = 24.6e6          # c, N/m, > 0
//! transfer_factor = 1.985     # alpha, N/V, > 0
//! capacitance = 800e-9        # C, F, > 0
//!
//! [run]                       # optional
//! engine = "event"            # "event" | "fixed"                   (default "event")
//! steps_per_harmonic = 5000   # fixed-step engine: steps per period of the
//!                             # highest harmonic, >= 1               (default 5000)
//! max_periods = 1000000       # transient limit, >= 1               (default 1000000)
//! verify_steady_state = false # run the start-up to convergence and cross-check
//!                             # it against the period map's steady state (default false)
//! time_limit_s = 60.0         # wall-clock budget of each simulation, s, > 0
//!                             # (default: none); `--time-limit` overrides it
//!
//! [outputs]                   # optional
//! indicators = ["v_inf", "startup_time", "smoothness", "durability",
//!               "friction_energy", "stiction_fraction", "velocity_per_power"]
//! trajectory = false          # record the steady-state period's trajectory
//! events = false              # record the event log
//!
//! [optimize]                  # optional: read by `stickslip optimize` only
//! ```
//!
//! # Rules
//!
//! * Unknown fields, in any table or at the top level, are errors; so are
//!   fields that do not belong to the chosen signal `kind` (`harmonics`
//!   with `kind = "ideal"`, `duty` with `kind = "harmonics"`, ...).
//! * Integers are accepted where numbers are expected (`contact_force = 1`).
//!   `nan` and `inf` are valid TOML floats; they are refused with the field's
//!   name.
//! * Without an `indicators` list, every indicator the scene allows is
//!   computed: all of [`Indicator::ALL`], except `velocity_per_power` unless
//!   an `[actuator]` is given and the signal is not `kind = "ideal"` (the
//!   ideal signal has infinitely many harmonics, so its input power (35) is
//!   undefined). Asking for `velocity_per_power` explicitly without an
//!   actuator or with the ideal signal is an error. An empty list asks for
//!   no indicators; a name may appear once.
//! * `sigma` defaults to `false`, the plain partial sums (8), which are what
//!   the signal *is* without the paper's modification (15); the paper's
//!   default scene sets it explicitly.
//!
//! # Limits and warnings
//!
//! * A scene file larger than [`MAX_INPUT_BYTES`] (1 MiB) is refused with
//!   its size, before it is parsed; files are read through
//!   [`read_input`], which stops reading at the limit, so that endless
//!   inputs (`/dev/zero`) are refused too.
//! * With `engine = "fixed"`, `n x steps_per_harmonic` steps per period
//!   above [`MAX_FIXED_STEPS_PER_PERIOD`] are refused: one period alone
//!   would take seconds, and a run simulates many.
//! * [`Scene::warnings`] lists values that are valid but implausible for a
//!   piezo inertia drive (usually a unit slip, `stroke = 25` for 25 um);
//!   the command line prints them on stderr and runs on. The bounds are
//!   the `PLAUSIBLE_*` constants.
//!
//! # Errors
//!
//! Malformed TOML, unknown fields and values of the wrong type give
//! [`SceneError::Parse`], whose one-line message names the field path, the
//! parser's complaint and the line and column. Values that parse but are not
//! allowed give [`SceneError::Param`], naming the field path and value
//! (`motor.slider_mass = -1: must be positive`). An unreadable file gives
//! [`SceneError::Io`].

use crate::error::{Num, ParamError, SceneError};
use crate::motor::{Motor, MotorParams};
use crate::power::ActuatorParams;
use crate::signal::{IdealShape, MAX_HARMONICS, SignalSpec};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::io::Read;
use std::ops::Range;
use std::path::Path;
use std::str::FromStr;
use thiserror::Error;
use toml::de::{DeTable, DeValue};

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
    /// `[actuator]`; `None`: no power outputs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub actuator: Option<ActuatorParams>,
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

/// Which engine runs the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EngineKind {
    /// The exact event-driven engine.
    #[default]
    Event,
    /// The fixed-step reference (the paper's method, section 7).
    Fixed,
}

impl EngineKind {
    /// The spelling in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            EngineKind::Event => "event",
            EngineKind::Fixed => "fixed",
        }
    }
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

/// A performance indicator a scene can ask for (docs/model.md sections 3, 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Indicator {
    /// Steady-state mean slider velocity `v_inf` (m/s).
    VInf,
    /// Start-up time `T p_0.99` (s).
    StartupTime,
    /// Steady-state smoothness `zeta` (16).
    Smoothness,
    /// Steady-state durability `delta` (18) (1/N).
    Durability,
    /// Steady-state friction energy per period `W_f` (19) (J).
    FrictionEnergy,
    /// Time stuck / simulated time.
    StictionFraction,
    /// `v_inf / S` with the apparent power `S` (35) (m/(s VA)).
    VelocityPerPower,
}

/// A name that is not an [`Indicator`].
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown indicator \"{name}\"; valid names: {valid}", valid = Indicator::valid_names())]
pub struct UnknownIndicator {
    /// The name given.
    pub name: String,
}

impl Indicator {
    /// Every indicator, in the order of `docs/interface.md`.
    pub const ALL: [Indicator; 7] = [
        Indicator::VInf,
        Indicator::StartupTime,
        Indicator::Smoothness,
        Indicator::Durability,
        Indicator::FrictionEnergy,
        Indicator::StictionFraction,
        Indicator::VelocityPerPower,
    ];

    /// The name in scene files and JSON output.
    pub fn name(self) -> &'static str {
        match self {
            Indicator::VInf => "v_inf",
            Indicator::StartupTime => "startup_time",
            Indicator::Smoothness => "smoothness",
            Indicator::Durability => "durability",
            Indicator::FrictionEnergy => "friction_energy",
            Indicator::StictionFraction => "stiction_fraction",
            Indicator::VelocityPerPower => "velocity_per_power",
        }
    }

    /// All names, comma separated.
    pub fn valid_names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// Why this indicator cannot be computed for the given signal and
    /// actuator, or `None` if it can.
    pub fn unavailable_because(
        self,
        signal: &SignalSpec,
        actuator: Option<&ActuatorParams>,
    ) -> Option<&'static str> {
        if self != Indicator::VelocityPerPower {
            return None;
        }
        if actuator.is_none() {
            Some("velocity_per_power needs an [actuator] table")
        } else if matches!(signal, SignalSpec::Ideal(_)) {
            Some(
                "velocity_per_power is undefined for kind = \"ideal\": the ideal \
                 signal has infinitely many harmonics, so its input power (35) is not finite",
            )
        } else {
            None
        }
    }

    /// The indicators a scene with this signal and actuator can compute,
    /// in the order of [`Indicator::ALL`].
    pub fn available(signal: &SignalSpec, actuator: Option<&ActuatorParams>) -> Vec<Indicator> {
        Self::ALL
            .into_iter()
            .filter(|i| i.unavailable_because(signal, actuator).is_none())
            .collect()
    }
}

impl fmt::Display for Indicator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Indicator {
    type Err = UnknownIndicator;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|i| i.name() == s)
            .ok_or_else(|| UnknownIndicator { name: s.to_owned() })
    }
}

/// How to run a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSettings {
    /// Which engine.
    pub engine: EngineKind,
    /// Fixed-step engine: steps per period of the highest harmonic (>= 1).
    /// The paper used 5000 (section 7).
    pub steps_per_harmonic: u32,
    /// Largest number of transient periods simulated (>= 1).
    pub max_periods: u64,
    /// Simulate the start-up from rest until it has converged and report
    /// its steady state beside the period map's, as a cross-check. Without
    /// it the start-up stops at `p_0.99`, which is all the indicators need.
    pub verify_steady_state: bool,
    /// Wall-clock budget of each simulation of the scene, in seconds,
    /// finite and positive: a run still going when it runs out stops with
    /// [`crate::error::SimulationError::TimeLimit`], naming how far it got.
    /// `None`: no budget.
    pub time_limit_s: Option<f64>,
}

impl Default for RunSettings {
    /// The event engine; 5000 steps per harmonic; 1 000 000 periods; no
    /// cross-check of the steady state; no time limit.
    fn default() -> Self {
        Self {
            engine: EngineKind::Event,
            steps_per_harmonic: 5000,
            max_periods: 1_000_000,
            verify_steady_state: false,
            time_limit_s: None,
        }
    }
}

/// Largest scene or sweep file read, in bytes (1 MiB): far above any real
/// scene (a few hundred bytes; a 256-harmonic series about 10 kB) and small
/// enough that reading and parsing it takes milliseconds.
pub const MAX_INPUT_BYTES: u64 = 1 << 20;

/// Largest number of fixed-step steps per period, `n x steps_per_harmonic`
/// (10^8, about a second of work per period): the paper's 5000 steps per
/// harmonic at `n = 256` are 1.28e6, `stickslip check`'s finest default
/// resolution 1.28e7. A run simulates at least a few periods, usually
/// hundreds, so more steps than this are refused up front.
pub const MAX_FIXED_STEPS_PER_PERIOD: u64 = 100_000_000;

/// Reads a text input file (scene or sweep) of at most [`MAX_INPUT_BYTES`],
/// reading no more than one byte past the limit whatever the file is, so
/// that `/dev/zero` or a huge file is refused quickly and without memory.
/// A file over the limit is an [`std::io::ErrorKind::InvalidData`] error
/// whose message gives its size (or "more than", for a stream) and the
/// limit; so is text that is not UTF-8.
pub fn read_input(path: &Path) -> std::io::Result<String> {
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        let size = std::fs::metadata(path)
            .ok()
            .filter(|m| m.is_file())
            .map_or_else(
                || format!("more than {MAX_INPUT_BYTES} bytes"),
                |m| format!("{} bytes", m.len()),
            );
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "the file holds {size}; input files are limited to {MAX_INPUT_BYTES} bytes (1 MiB)"
            ),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Steps per period the fixed-step engine takes for `signal`:
/// `n x steps_per_harmonic`, with `n` the number of harmonics (1 for the
/// ideal signal), as [`crate::engine::fixed_step::FixedStepEngine::steps_for`]
/// counts them on the built signal.
pub fn fixed_steps_per_period(signal: &SignalSpec, steps_per_harmonic: u32) -> u64 {
    let harmonics = match signal {
        SignalSpec::Ideal(_) => 1,
        SignalSpec::Fourier { harmonics, .. } => *harmonics,
        SignalSpec::Harmonics { amplitudes, .. } => amplitudes.len().max(1),
    };
    harmonics as u64 * u64::from(steps_per_harmonic)
}

/// Refuses fixed-step resolutions whose work per period exceeds
/// [`MAX_FIXED_STEPS_PER_PERIOD`]; `field` names where the resolution came
/// from (`run.steps_per_harmonic`, `--steps`).
pub fn check_fixed_steps(
    signal: &SignalSpec,
    steps_per_harmonic: u32,
    field: &str,
) -> Result<(), ParamError> {
    let per_period = fixed_steps_per_period(signal, steps_per_harmonic);
    if per_period > MAX_FIXED_STEPS_PER_PERIOD {
        return Err(ParamError::out_of_range(
            field,
            f64::from(steps_per_harmonic),
            format!(
                "gives {} fixed steps per period (n x steps_per_harmonic), above the limit of \
                 {} (about a second per period, and a run simulates many periods)",
                Num(per_period as f64),
                Num(MAX_FIXED_STEPS_PER_PERIOD as f64)
            ),
        ));
    }
    Ok(())
}

/// What a run records and reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Outputs {
    /// Indicators to compute, each at most once.
    pub indicators: Vec<Indicator>,
    /// Record the steady-state period's trajectory.
    pub trajectory: bool,
    /// Record the event log.
    pub events: bool,
}

/// A validated scene: motor, signal, optional actuator, run settings and
/// outputs.
///
/// The fields are public for programmatic scenes (sweeps); after changing
/// them, [`Scene::validate`] checks the same rules as a scene file.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The motor (`[motor]`).
    pub motor: MotorParams,
    /// The rod signal (`[signal]`).
    pub signal: SignalSpec,
    /// The actuator model, needed for power outputs (`[actuator]`).
    pub actuator: Option<ActuatorParams>,
    /// How to run (`[run]`).
    pub run: RunSettings,
    /// What to report (`[outputs]`).
    pub outputs: Outputs,
}

impl Default for Scene {
    /// The paper's example (docs/model.md section 6): its motor, `n = 2`,
    /// `sqrt(kappa) = 6`, sigma factors, stroke 25 um, the Table 1 actuator,
    /// the event engine and every indicator.
    fn default() -> Self {
        Self {
            motor: MotorParams::default(),
            signal: SignalSpec::paper_default(),
            actuator: Some(ActuatorParams::default()),
            run: RunSettings::default(),
            outputs: Outputs {
                indicators: Indicator::ALL.to_vec(),
                trajectory: false,
                events: false,
            },
        }
    }
}

impl Scene {
    /// Parses and validates a scene from TOML text; `origin` names the
    /// source in error messages (a path, or `<string>`).
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let file: SceneFile = toml::from_str(text).map_err(|e| SceneError::Parse {
            path: origin.to_owned(),
            message: parse_message(text, &e),
        })?;
        Scene::try_from(file).map_err(|source| SceneError::Param {
            path: origin.to_owned(),
            source,
        })
    }

    /// Reads, parses and validates a scene file.
    pub fn from_path(path: &Path) -> Result<Scene, SceneError> {
        let origin = path.display().to_string();
        let text = read_input(path).map_err(|source| SceneError::Io {
            path: origin.clone(),
            source,
        })?;
        Scene::from_toml_str(&text, &origin)
    }

    /// The scene as TOML, every field written out (`kappa`, not
    /// `sqrt_kappa`). [`Scene::from_toml_str`] reads it back to an equal
    /// scene.
    pub fn to_toml(&self) -> String {
        toml::to_string(&SceneFile::from(self))
            .expect("a SceneFile has only tables, numbers, strings, booleans and arrays")
    }

    /// Checks every rule a scene file is checked against; errors name the
    /// scene field.
    pub fn validate(&self) -> Result<(), ParamError> {
        Motor::new(self.motor)?;
        self.signal.validate()?;
        if let Some(actuator) = &self.actuator {
            actuator.validate()?;
        }
        if self.run.steps_per_harmonic == 0 {
            return Err(ParamError::out_of_range(
                "run.steps_per_harmonic",
                0.0,
                "must be at least 1",
            ));
        }
        if self.run.engine == EngineKind::Fixed {
            check_fixed_steps(
                &self.signal,
                self.run.steps_per_harmonic,
                "run.steps_per_harmonic",
            )?;
        }
        if let Some(limit) = self.run.time_limit_s {
            ParamError::positive("run.time_limit_s", limit)?;
        }
        if self.run.max_periods == 0 {
            return Err(ParamError::out_of_range(
                "run.max_periods",
                0.0,
                "must be at least 1",
            ));
        }
        for (i, indicator) in self.outputs.indicators.iter().enumerate() {
            if self.outputs.indicators[..i].contains(indicator) {
                return Err(ParamError::Inconsistent {
                    field: "outputs.indicators".to_owned(),
                    reason: format!("lists \"{indicator}\" more than once"),
                });
            }
            if let Some(reason) =
                indicator.unavailable_because(&self.signal, self.actuator.as_ref())
            {
                return Err(ParamError::Inconsistent {
                    field: "outputs.indicators".to_owned(),
                    reason: reason.to_owned(),
                });
            }
        }
        Ok(())
    }
}

/// Plausible strokes (and harmonic amplitudes) of a piezo inertia drive, m:
/// 1 nm to 1 mm (the paper's is 25 um).
pub const PLAUSIBLE_STROKE: (f64, f64) = (1e-9, 1e-3);
/// Highest plausible fundamental frequency, Hz (10 MHz; the paper's drive
/// runs at 1.6 kHz, piezo stacks resonate below 1 MHz).
pub const PLAUSIBLE_MAX_FREQUENCY: f64 = 10e6;
/// Plausible slider masses, kg: 1 mg to 10 kg (the paper's is 1.4 g).
pub const PLAUSIBLE_SLIDER_MASS: (f64, f64) = (1e-6, 10.0);
/// Highest plausible contact force, N (1 kN; the paper's is 1 N).
pub const PLAUSIBLE_MAX_CONTACT_FORCE: f64 = 1e3;
/// Highest plausible friction coefficient (dry friction of solids lies
/// below about 1.5; the paper's mu_0 is 0.17).
pub const PLAUSIBLE_MAX_FRICTION: f64 = 2.0;
/// Highest plausible `kappa = a_R / a_0` (the paper's figures use 1 to
/// about 400): a slider gains at most `a_0 T`, a `1 / (kappa duty)` part of
/// the rod's peak velocity, per period, so beyond this the start-up from
/// rest takes very many periods.
pub const PLAUSIBLE_MAX_KAPPA: f64 = 1e4;

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
            Some(format!(
                "is {bound}; {noun} are in metres ({} um = {}e-6)",
                Num(value),
                Num(value)
            ))
        };
        match &self.signal {
            SignalSpec::Ideal(shape) | SignalSpec::Fourier { shape, .. } => {
                if let Some(reason) = stroke_warning(shape.stroke, "strokes") {
                    warn("signal.stroke", shape.stroke, "m", reason);
                }
                if shape.kappa > PLAUSIBLE_MAX_KAPPA {
                    warn(
                        "signal.kappa",
                        shape.kappa,
                        "",
                        format!(
                            "is above {}: a slider gains at most 1/(kappa duty) of the rod's \
                             peak velocity per period, so the start-up may take of the order \
                             of {} periods (run.max_periods = {}; run.time_limit_s bounds the run)",
                            Num(PLAUSIBLE_MAX_KAPPA),
                            Num((shape.kappa * shape.duty).round()),
                            self.run.max_periods
                        ),
                    );
                }
                if let Ok(motor) = Motor::new(self.motor) {
                    let (_, period) = shape.times(&motor);
                    let f0 = 1.0 / period;
                    if f0 > PLAUSIBLE_MAX_FREQUENCY {
                        warn(
                            "signal.stroke",
                            shape.stroke,
                            "m",
                            format!(
                                "with signal.kappa = {} and a_0 = {} m/s^2 gives the \
                                 frequency f_0 = {} Hz, above 10 MHz; check the units of \
                                 the stroke (m), the motor and kappa",
                                Num(shape.kappa),
                                Num(motor.a_0()),
                                Num(f0)
                            ),
                        );
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
        }
        out
    }
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
        let signal = match file.signal {
            Some(table) => signal_spec(table)?,
            None => SignalSpec::paper_default(),
        };
        let run = run_settings(file.run)?;
        let outputs = outputs(file.outputs, &signal, file.actuator.as_ref())?;
        let scene = Scene {
            motor,
            signal,
            actuator: file.actuator,
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
            SignalSpec::Ideal(shape) => SignalTable {
                duty: Some(shape.duty),
                ..shape_table(SignalKind::Ideal, shape)
            },
            SignalSpec::Fourier {
                shape,
                harmonics,
                sigma,
            } => SignalTable {
                harmonics: Some(i64::try_from(*harmonics).unwrap_or(i64::MAX)),
                sigma: Some(*sigma),
                duty: Some(shape.duty),
                ..shape_table(SignalKind::Fourier, shape)
            },
            SignalSpec::Harmonics {
                frequency,
                amplitudes,
                phases,
                scale_to_stroke,
                shift_to_minimum,
            } => SignalTable {
                frequency: Some(*frequency),
                amplitudes: Some(amplitudes.clone()),
                phases: Some(phases.clone()),
                scale_to_stroke: Some(scale_to_stroke.is_some()),
                stroke: *scale_to_stroke,
                shift_to_minimum: Some(*shift_to_minimum),
                ..empty_signal_table(SignalKind::Harmonics)
            },
        };
        SceneFile {
            motor: Some(MotorTable {
                slider_mass: m.slider_mass,
                contact_force: m.contact_force,
                mu_static: m.mu_static,
                mu_dynamic: m.mu_dynamic,
                extra_acceleration: m.extra_acceleration,
            }),
            signal: Some(signal),
            actuator: scene.actuator,
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
        amplitudes: None,
        phases: None,
        scale_to_stroke: None,
        shift_to_minimum: None,
    }
}

fn shape_table(kind: SignalKind, shape: &IdealShape) -> SignalTable {
    SignalTable {
        stroke: Some(shape.stroke),
        kappa: Some(shape.kappa),
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

/// `kappa` from exactly one of `kappa` and `sqrt_kappa`.
fn kappa(kappa: Option<f64>, sqrt_kappa: Option<f64>) -> Result<f64, ParamError> {
    match (kappa, sqrt_kappa) {
        (Some(k), None) => Ok(k),
        (None, Some(s)) => {
            ParamError::positive("signal.sqrt_kappa", s)?;
            let k = s * s;
            if k.is_finite() && k > 0.0 {
                Ok(k)
            } else {
                Err(ParamError::out_of_range(
                    "signal.sqrt_kappa",
                    s,
                    format!("its square kappa = {} must be positive and finite", Num(k)),
                ))
            }
        }
        (Some(_), Some(_)) => Err(ParamError::Inconsistent {
            field: "signal.kappa".to_owned(),
            reason: "give exactly one of signal.kappa and signal.sqrt_kappa, not both".to_owned(),
        }),
        (None, None) => Err(ParamError::Inconsistent {
            field: "signal.kappa".to_owned(),
            reason: "missing: give exactly one of signal.kappa and signal.sqrt_kappa".to_owned(),
        }),
    }
}

fn signal_spec(t: SignalTable) -> Result<SignalSpec, ParamError> {
    let kind = t.kind;
    match kind {
        SignalKind::Fourier | SignalKind::Ideal => {
            refuse_fields(
                kind,
                &[
                    ("frequency", t.frequency.is_some()),
                    ("amplitudes", t.amplitudes.is_some()),
                    ("phases", t.phases.is_some()),
                    ("scale_to_stroke", t.scale_to_stroke.is_some()),
                    ("shift_to_minimum", t.shift_to_minimum.is_some()),
                ],
            )?;
            let shape = IdealShape {
                stroke: required(t.stroke, "stroke", kind)?,
                kappa: kappa(t.kappa, t.sqrt_kappa)?,
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
) -> Result<Outputs, ParamError> {
    let t = table.unwrap_or(OutputsTable {
        indicators: None,
        trajectory: None,
        events: None,
    });
    let indicators = match t.indicators {
        None => Indicator::available(signal, actuator),
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

/// One line from a TOML error: the field path (found from the error's span
/// in the parsed document or, when the text does not parse, from the
/// offending line and the table above it), the parser's message, line and
/// column, and the offending line itself.
pub(crate) fn parse_message(text: &str, error: &toml::de::Error) -> String {
    let message = error
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let Some(span) = error.span() else {
        return message;
    };
    let start = span.start.min(text.len());
    let before = text.get(..start).unwrap_or("");
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    let shown = shown_line(text, line);
    match field_path(text, &span).or_else(|| key_on_line(text, line)) {
        Some(path) => format!("{path}: {message} (line {line}, column {column}: {shown})"),
        None => format!("{message} (line {line}, column {column}: {shown})"),
    }
}

/// Longest excerpt of an offending line shown in a message, in characters.
const SHOWN_LINE_CHARS: usize = 80;

/// Line `line` (1-based) of `text`, trimmed and quoted, cut to
/// [`SHOWN_LINE_CHARS`] characters.
fn shown_line(text: &str, line: usize) -> String {
    let content = text.lines().nth(line - 1).unwrap_or("").trim();
    let mut shown: String = content.chars().take(SHOWN_LINE_CHARS).collect();
    if content.chars().count() > SHOWN_LINE_CHARS {
        shown.push_str("...");
    }
    format!("`{shown}`")
}

/// The key on line `line` of a text that does not parse, as a dotted path
/// under the last `[table]` header above it (`motor.slider_mass`); the
/// header itself for a header line. A plain scan: the parser gives no tree
/// for broken text.
fn key_on_line(text: &str, line: usize) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let content = lines.get(line - 1)?.trim();
    let header = |l: &str| {
        l.strip_prefix('[')
            .and_then(|h| h.split(']').next())
            .map(|h| h.trim().to_owned())
    };
    if content.starts_with('[') {
        return header(content).filter(|h| !h.is_empty());
    }
    let key = content.split(['=', ' ', '\t']).next()?.trim();
    let bare = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '"' | '\'');
    if key.is_empty() || !key.chars().all(bare) {
        return None;
    }
    let table = lines[..line - 1]
        .iter()
        .rev()
        .map(|l| l.trim())
        .find(|l| l.starts_with('['))
        .and_then(header);
    Some(match table {
        Some(t) if !t.is_empty() => format!("{t}.{key}"),
        _ => key.to_owned(),
    })
}

/// The dotted path (`motor.slider_mass`, `signal.amplitudes[1]`) of the key
/// or value at `span`, if the text parses as TOML and one contains it.
fn field_path(text: &str, span: &Range<usize>) -> Option<String> {
    let root = DeTable::parse(text).ok()?;
    let mut path = Vec::new();
    path_in_table(root.get_ref(), span, &mut path);
    (!path.is_empty()).then(|| path.join("."))
}

fn contains(outer: &Range<usize>, inner: &Range<usize>) -> bool {
    outer.start <= inner.start && inner.end <= outer.end
}

fn path_in_table(table: &DeTable<'_>, span: &Range<usize>, path: &mut Vec<String>) {
    for (key, value) in table.iter() {
        if contains(&key.span(), span) {
            path.push(key.get_ref().to_string());
            return;
        }
        if contains(&value.span(), span) {
            path.push(key.get_ref().to_string());
            path_in_value(value.get_ref(), span, path);
            return;
        }
    }
    // A `[table]`'s span is its header; its keys lie elsewhere in the text.
    for (key, value) in table.iter() {
        if let DeValue::Table(inner) = value.get_ref() {
            let mut sub = vec![key.get_ref().to_string()];
            path_in_table(inner, span, &mut sub);
            if sub.len() > 1 {
                path.extend(sub);
                return;
            }
        }
    }
}

fn path_in_value(value: &DeValue<'_>, span: &Range<usize>, path: &mut Vec<String>) {
    match value {
        DeValue::Table(table) => path_in_table(table, span, path),
        DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                if contains(&item.span(), span) {
                    if let Some(last) = path.last_mut() {
                        last.push_str(&format!("[{i}]"));
                    }
                    path_in_value(item.get_ref(), span, path);
                    return;
                }
            }
        }
        _ => {}
    }
}
