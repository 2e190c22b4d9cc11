//! # stickslip
//!
//! An event-driven simulator for piezoelectric inertia drives ("stick-slip
//! drives"), after Hunstig, Hemsel and Sextro, *Stick-slip and slip-slip
//! operation of piezoelectric inertia drives, Part II: frequency-limited
//! excitation*. The model and its numbers are in `docs/model.md`, the scene
//! fields, commands and output keys in `docs/interface.md`.
//!
//! ## Quick start
//!
//! ```
//! use stickslip::{Indicator, Scene, simulate};
//!
//! // The paper's motor and signal: n = 2 harmonics, sqrt(kappa) = 6,
//! // Lanczos sigma factors (docs/model.md section 7).
//! let mut scene = Scene::default();
//! scene.outputs.indicators = vec![Indicator::VInf, Indicator::Smoothness];
//! let outcome = simulate(&scene)?;
//! let report = outcome.report().expect("this motor reaches a steady state");
//! let v_inf = report.value(Indicator::VInf).unwrap();
//! let error = report.error(Indicator::VInf).unwrap();
//! assert!((v_inf - 0.2971).abs() < 1e-4 && error < 1e-9);
//! # Ok::<(), stickslip::Error>(())
//! ```
//!
//! A scene can also be read from TOML ([`Scene::from_toml_str`],
//! [`Scene::from_path`]); [`simulate`] returns an [`Outcome`]: a periodic
//! steady state with its indicators ([`RunReport`]), a slider that runs
//! away, or a start-up that did not settle. Each is a result, not an error.
//!
//! ## The data path
//!
//! Dependencies point one way, from the bottom of this list to the top
//! (`tests/architecture.rs` checks it):
//!
//! 1. `numerics`: trigonometric polynomials and their certified roots,
//!    brackets, compensated sums, line fits, contours of gridded values;
//!    no physics; [`symbol`]: the one table of quantity symbols and
//!    units that the indicators and every figure's labels share;
//! 2. `signal` (the rod signal, docs/model.md section 2), `motor` (the
//!    slider and its friction), `power` (the actuator's input power,
//!    section 6.3 of the paper);
//! 3. `engine`: walks the slider through time and hands every exact segment,
//!    event and period end to an [`Observer`]; `engine/<method>.rs` is one
//!    engine ([`EventEngine`], the exact one; [`FixedStepEngine`], the
//!    fixed-step reference), `engine/contact.rs` the stick/slip decision they
//!    share;
//! 4. `observer`: what a run records ([`EventLog`], [`Trajectory`]);
//! 5. `analysis`: per-period statistics, the start-up, the fixed point of the
//!    period map, the steady state and the error estimates;
//!    [`sensitivity`]: exact derivatives of the steady state with respect to
//!    the motor's and the signal's parameters;
//! 6. `indicator`: the one table of indicators ([`Indicator`]);
//! 7. `scene`: the validated description of a run ([`Scene`]);
//! 8. `simulation`: runs a scene ([`simulate`]) with a time budget;
//! 9. `report` (text and JSON), `check` (the fixed-step cross-check),
//!    `export`, `compare` (a user's own results against the exact ones:
//!    [`compare`] reads files, [`compare_data`] takes arrays),
//!    [`sweep`], [`characteristic`] (velocity against load, stall force),
//!    [`optimize`] (the best drive signal),
//!    [`plot`] (`plot/<figure family>.rs`);
//! 10. [`cli`], the `stickslip` command.
//!
//! Only the names below are public; the rest of the tree is crate-private.

#![warn(missing_docs)]
#![warn(unreachable_pub)]
// The full build (default features) is the one that shows every item is
// used. The core alone (`--no-default-features`) still carries the text,
// JSON and CSV renderings the front ends call (run, characteristic,
// optimize, sweep and trajectory outputs), which nothing inside the core
// calls.
#![cfg_attr(
    not(feature = "cli"),
    allow(dead_code, unused_imports, unreachable_pub)
)]

pub mod analysis;
pub mod characteristic;
mod check;
#[cfg(feature = "cli")]
pub mod cli;
mod compare;
mod csv_text;
mod engine;
mod error;
mod export;
mod indicator;
mod interrupt;
mod motor;
pub mod numerics;
mod observer;
pub mod optimize;
mod output;
#[cfg(feature = "plot")]
pub mod plot;
mod plural;
mod power;
mod provenance;
mod report;
mod scene;
pub mod sensitivity;
mod signal;
mod simulation;
pub mod sweep;
pub mod symbol;

pub use check::{CheckReport, check};
#[cfg(feature = "files")]
pub use compare::compare;
pub use compare::{
    Column as CompareColumn, CompareError, CompareOptions, Report as CompareReport,
    UserData as CompareData, compare_data,
};
pub use engine::event::{EventEngine, EventOptions};
pub use engine::fixed_step::{FixedStepEngine, FixedStepOptions};
pub use engine::{
    Direction, Event, EventCounts, EventKind, Kinematics, Mode, Observer, PeriodEnd, PeriodEngine,
    PeriodStart, Segment, WorkCounters,
};
pub use error::{Error, Num, ParamError, SceneError, SimulationError, SweepError};
pub use export::exact_tables;
pub use indicator::{Indicator, UnknownIndicator};
pub use motor::{Motor, MotorParams};
pub use observer::{EventLog, MAX_LOGGED_EVENTS, Trajectory};
pub use power::{ActuatorParams, PowerReport, input_power};
pub use provenance::{VERSION, scene_hash};
pub use report::{format_with_error, to_json, to_text};
pub use scene::{
    EngineKind, MAX_FIXED_STEPS_PER_PERIOD, MAX_INPUT_BYTES, Outputs, Override, OverrideError,
    RunSettings, Scene, Warning, read_input,
};
pub use signal::description::SignalDescription;
pub use signal::{
    Drive, FourierSignal, Held, IdealShape, MAX_HARMONICS, RodState, Signal, SignalSpec,
};
pub use simulation::{
    CertificateKind, ErrorEstimate, Outcome, Regime, RunReport, SignalCache,
    SteadyStateCertificate, SteadyStateCheck, Unsettled, build, run, run_with, sensitivities,
    simulate, simulate_with, simulate_with_signal,
};
