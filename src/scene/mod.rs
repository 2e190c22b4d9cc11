//! Scene files: what to simulate and what to report, in TOML.
//!
//! A scene is read in two steps, so that nothing unchecked reaches the
//! simulation: serde reads the text into a `SceneFile`, which mirrors the
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
//! sqrt_kappa = 6.0            # the drive, exactly one of: kappa = 36.0, sqrt_kappa,
//!                             # frequency (f_0, Hz), f_max (n f_0, Hz; fourier only); > 0;
//!                             # the one given is held when the motor changes
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

mod actuator_table;
mod file;
mod overrides;
mod spring_table;
mod toml_error;
mod warnings;

pub(crate) use file::SceneFile;
pub use overrides::{Override, OverrideError};
pub(crate) use toml_error::parse_message;
pub use warnings::Warning;

use crate::actuator::{DrivenSpec, GivenVoltage, RodModel};
use crate::error::{Error, Num, ParamError, SceneError};
use crate::indicator::Indicator;
use crate::motor::{Motor, MotorParams};
use crate::power::ActuatorParams;
use crate::signal::{Signal, SignalSpec};
use crate::spring::Spring;
use serde::{Deserialize, Serialize};
use std::io::Read;
use std::path::Path;

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

/// The input path that stands for standard input.
pub(crate) const STDIN: &str = "-";

/// How messages name an input: its path, or `<stdin>`.
pub(crate) fn origin_of(path: &Path) -> String {
    if path == Path::new(STDIN) {
        "<stdin>".to_owned()
    } else {
        path.display().to_string()
    }
}

/// Reads a text input file (scene or sweep) of at most [`MAX_INPUT_BYTES`]
/// (`-`: standard input),
/// reading no more than one byte past the limit whatever the file is, so
/// that `/dev/zero` or a huge file is refused quickly and without memory.
/// A file over the limit is an [`std::io::ErrorKind::InvalidData`] error
/// whose message gives its size (or "more than", for a stream) and the
/// limit; so is text that is not UTF-8.
pub fn read_input(path: &Path) -> std::io::Result<String> {
    let mut bytes = Vec::new();
    if path == Path::new(STDIN) {
        std::io::stdin()
            .lock()
            .take(MAX_INPUT_BYTES + 1)
            .read_to_end(&mut bytes)?;
    } else {
        let file = std::fs::File::open(path)?;
        file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes)?;
    }
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
pub(crate) fn fixed_steps_per_period(signal: &SignalSpec, steps_per_harmonic: u32) -> u64 {
    let harmonics = match signal {
        SignalSpec::Ideal(_) => 1,
        SignalSpec::Fourier { harmonics, .. } => *harmonics,
        SignalSpec::Harmonics { amplitudes, .. } => amplitudes.len().max(1),
        SignalSpec::Response { cosines, .. } => cosines.len().max(1),
    };
    harmonics as u64 * u64::from(steps_per_harmonic)
}

/// Refuses fixed-step resolutions whose work per period exceeds
/// [`MAX_FIXED_STEPS_PER_PERIOD`]; `field` names where the resolution came
/// from (`run.steps_per_harmonic`, `--steps`).
pub(crate) fn check_fixed_steps(
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
    /// How the rod moves (`[actuator] rod`): prescribed, or driven by the
    /// voltage through the actuator (docs/model.md section 16).
    pub rod: RodModel,
    /// The voltage of a driven rod given directly (`[voltage]`); then
    /// `signal` is the `[actuator]`'s response to it
    /// ([`GivenVoltage::response`], set by [`Scene::set_voltage`]).
    /// `None`: a driven rod's voltage is designed from `signal`.
    pub voltage: Option<GivenVoltage>,
    /// A spring against the slider (`[spring]`, docs/model.md section
    /// 17): the spring method of measuring the motor's force.
    pub spring: Option<Spring>,
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
            rod: RodModel::Prescribed,
            voltage: None,
            spring: None,
            run: RunSettings::default(),
            outputs: Outputs {
                indicators: Indicator::ALL.to_vec(),
                trajectory: false,
                events: false,
            },
        }
    }
}

/// The motor and the rod signal of a scene, built ([`Scene::build`]).
#[derive(Debug, Clone)]
pub struct BuiltScene {
    /// The rod signal, with its event structure (docs/model.md section 2).
    pub signal: Signal,
    /// The slider and its friction.
    pub motor: Motor,
}

impl Scene {
    /// Builds the scene's motor and its rod signal (the signal's
    /// `kappa`-based kinds depend on the motor's `a_0`).
    pub fn build(&self) -> Result<BuiltScene, Error> {
        let motor = Motor::new(self.motor)?;
        let signal = Signal::build(&self.signal, &motor)?;
        Ok(BuiltScene { signal, motor })
    }

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

    /// Reads, parses and validates a scene file (`-`: standard input).
    pub fn from_path(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_path_with(path, &[])
    }

    /// [`Scene::from_path`] with `overrides` applied to the file's table
    /// before it is read ([`Scene::from_toml_str_with`]).
    pub fn from_path_with(path: &Path, overrides: &[Override]) -> Result<Scene, SceneError> {
        let origin = origin_of(path);
        let text = read_input(path).map_err(|source| SceneError::Io {
            path: origin.clone(),
            source,
        })?;
        Scene::from_toml_str_with(&text, &origin, overrides)
    }

    /// [`Scene::from_toml_str`] with `overrides` (`PATH=VALUE`, the grammar
    /// of `crate::scene::Override`) applied, in order, to the text's TOML
    /// table before it is read: an overridden field is checked as if the
    /// text held it.
    pub fn from_toml_str_with(
        text: &str,
        origin: &str,
        overrides: &[Override],
    ) -> Result<Scene, SceneError> {
        if overrides.is_empty() {
            return Scene::from_toml_str(text, origin);
        }
        let mut table: toml::Table =
            text.parse()
                .map_err(|e: toml::de::Error| SceneError::Parse {
                    path: origin.to_owned(),
                    message: parse_message(text, &e),
                })?;
        // A table left to its default gets it written out, so that an
        // override changes one field of it.
        let defaults: toml::Table = Scene {
            actuator: None,
            ..Scene::default()
        }
        .to_toml()
        .parse()
        .expect("the default scene writes as TOML");
        for o in overrides {
            if !table.contains_key(o.table())
                && let Some(default) = defaults.get(o.table())
            {
                table.insert(o.table().to_owned(), default.clone());
            }
        }
        overrides::apply(&mut table, overrides).map_err(|source| SceneError::Override {
            path: origin.to_owned(),
            source,
        })?;
        let changed = toml::to_string(&table).expect("a TOML table writes as TOML");
        let given: Vec<String> = overrides.iter().map(Override::to_string).collect();
        let origin = format!("{origin} with --set {}", given.join(" --set "));
        Scene::from_toml_str(&changed, &origin).map_err(|e| match e {
            // The text parsed before the overrides: the place the parser
            // names is in the rewritten table, not in the user's text.
            SceneError::Parse { path, message } => SceneError::Parse {
                path,
                message: match message.rfind(" (line ") {
                    Some(at) if message.ends_with(')') => message[..at].to_owned(),
                    _ => message,
                },
            },
            other => other,
        })
    }

    /// The scene as TOML, every field written out, the drive as given
    /// (`kappa`, `frequency` or `f_max`; `sqrt_kappa` as `kappa`). [`Scene::from_toml_str`] reads it back to an equal
    /// scene.
    pub fn to_toml(&self) -> String {
        toml::to_string(&SceneFile::from(self))
            .expect("a SceneFile has only tables, numbers, strings, booleans and arrays")
    }

    /// Drives the rod by `voltage` given directly (`[voltage]`): the
    /// signal becomes the `[actuator]`'s response to it and a prescribed
    /// rod a driven one (with the reaction). Needs the actuator (the error
    /// names `voltage`); the values are checked by [`Scene::validate`].
    pub fn set_voltage(&mut self, voltage: GivenVoltage) -> Result<(), ParamError> {
        let Some(actuator) = &self.actuator else {
            return Err(ParamError::Inconsistent {
                field: "voltage".to_owned(),
                reason: "drives an actuator: the scene needs [actuator]".to_owned(),
            });
        };
        self.signal = voltage.response(actuator);
        if self.rod == RodModel::Prescribed {
            self.rod = RodModel::Driven(DrivenSpec::default());
        }
        self.voltage = Some(voltage);
        Ok(())
    }

    /// Checks every rule a scene file is checked against; errors name the
    /// scene field.
    pub fn validate(&self) -> Result<(), ParamError> {
        Motor::new(self.motor)?;
        if let Some(actuator) = &self.actuator {
            actuator.validate()?;
        }
        self.check_voltage()?;
        self.signal.validate()?;
        if let Some(voltage) = &self.voltage
            && let Some(actuator) = &self.actuator
            && self.signal != voltage.response(actuator)
        {
            return Err(ParamError::Inconsistent {
                field: "signal".to_owned(),
                reason: "differs from the [actuator]'s response to [voltage] \
                         (set both with Scene::set_voltage)"
                    .to_owned(),
            });
        }
        self.check_spring()?;
        if let RodModel::Driven(spec) = &self.rod {
            check_driven(&self.signal, self.actuator.as_ref(), spec)?;
            check_driven_rates(&self.signal, self.actuator.as_ref(), spec, &self.motor)?;
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
            if let Some(reason) = indicator.unavailable_because(
                &self.signal,
                self.actuator.as_ref(),
                self.spring.is_some(),
            ) {
                return Err(ParamError::Inconsistent {
                    field: "outputs.indicators".to_owned(),
                    reason: reason.to_owned(),
                });
            }
        }
        Ok(())
    }
}

impl Scene {
    /// A `[voltage]` needs a driven rod and the `[actuator]` it drives; a
    /// voltage's response as the signal needs its `[voltage]`.
    fn check_voltage(&self) -> Result<(), ParamError> {
        let Some(voltage) = &self.voltage else {
            if matches!(self.signal, SignalSpec::Response { .. }) {
                return Err(ParamError::Inconsistent {
                    field: "signal".to_owned(),
                    reason: "is a voltage's response without the [voltage] \
                             (set both with Scene::set_voltage)"
                        .to_owned(),
                });
            }
            return Ok(());
        };
        voltage.validate()?;
        if self.actuator.is_none() {
            return Err(ParamError::Inconsistent {
                field: "voltage".to_owned(),
                reason: "drives an actuator: give the [actuator] table (mass, damping, \
                         stiffness, transfer_factor, capacitance)"
                    .to_owned(),
            });
        }
        if self.rod == RodModel::Prescribed {
            return Err(ParamError::Inconsistent {
                field: "actuator.rod".to_owned(),
                reason: "\"prescribed\" with a [voltage] table: a given voltage drives the rod \
                         (actuator.rod = \"driven\", the default with [voltage])"
                    .to_owned(),
            });
        }
        Ok(())
    }
}

/// A driven rod needs an actuator and a continuous signal that starts at
/// rest (docs/model.md section 16): `fourier`, or `harmonics` shifted to
/// its minimum, both followed by the designed voltage from rest; or the
/// response to a given `[voltage]`, which need not start at rest (the
/// rod's free oscillation, excited at `t = 0`, decays).
fn check_driven(
    signal: &SignalSpec,
    actuator: Option<&ActuatorParams>,
    spec: &DrivenSpec,
) -> Result<(), ParamError> {
    let Some(actuator) = actuator else {
        return Err(ParamError::Inconsistent {
            field: "actuator.rod".to_owned(),
            reason: "a driven rod needs the [actuator] parameters".to_owned(),
        });
    };
    spec.real.apply(actuator)?;
    match signal {
        SignalSpec::Fourier { .. } | SignalSpec::Response { .. } => Ok(()),
        SignalSpec::Harmonics {
            shift_to_minimum: true,
            ..
        } => Ok(()),
        SignalSpec::Harmonics { .. } => Err(ParamError::Inconsistent {
            field: "signal.shift_to_minimum".to_owned(),
            reason: "must be true for a driven rod, which starts at rest at x_R = 0".to_owned(),
        }),
        SignalSpec::Ideal(_) => Err(ParamError::Inconsistent {
            field: "signal.kind".to_owned(),
            reason: "\"ideal\" jumps, which no actuator follows: a driven rod needs \"fourier\" or \"harmonics\"".to_owned(),
        }),
    }
}

/// Most time constants of the actuator's free motion in one drive period
/// a driven rod accepts: the event search walks a period in pieces of the
/// fastest one, so a million is about a tenth of a second per search.
const MAX_RATE_PERIOD: f64 = 1e6;

/// A driven rod whose actuator moves freely on a time scale far below the
/// drive period (a vanishing mass, a huge stiffness) is refused: its
/// fastest rate `sigma + sqrt(sigma^2 - omega_0^2) + omega_0` (with
/// `sigma = d / 2M`, `omega_0^2 = c / M`, the real actuator in slip) times
/// the period must not exceed [`MAX_RATE_PERIOD`]. The error names the
/// field that set the mass.
fn check_driven_rates(
    signal: &SignalSpec,
    actuator: Option<&ActuatorParams>,
    spec: &DrivenSpec,
    motor: &MotorParams,
) -> Result<(), ParamError> {
    let (Some(design), Ok(motor)) = (actuator, Motor::new(*motor)) else {
        return Ok(());
    };
    let real = spec.real.apply(design)?;
    let sigma = real.damping / (2.0 * real.mass);
    let omega0 = (real.stiffness / real.mass).sqrt();
    let rate = sigma + (sigma * sigma - omega0 * omega0).max(0.0).sqrt() + omega0;
    let period = 1.0 / signal.f0(&motor);
    if rate * period <= MAX_RATE_PERIOD {
        return Ok(());
    }
    let field = if spec.real.mass.is_some() {
        "actuator.real.mass"
    } else {
        "actuator.mass"
    };
    Err(ParamError::out_of_range(
        field,
        real.mass,
        format!(
            "the actuator's free motion (rate {rate:.3e} 1/s) is too fast for the drive period \
             ({period:.3e} s): a driven rod needs rate x period <= {MAX_RATE_PERIOD:.0e}"
        ),
    ))
}
