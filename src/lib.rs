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
//! use stickslip::{Indicator, RunOptions, Scene};
//!
//! // The paper's motor and signal: n = 2 harmonics, sqrt(kappa) = 6,
//! // Lanczos sigma factors (docs/model.md section 7).
//! let mut scene = Scene::default();
//! scene.outputs.indicators = vec![Indicator::VInf, Indicator::Smoothness];
//! let outcome = stickslip::run(&scene, &RunOptions::default())?;
//! let report = outcome.report().expect("this motor reaches a steady state");
//! let v_inf = report.value(Indicator::VInf).unwrap();
//! let error = report.error(Indicator::VInf).unwrap();
//! assert!((v_inf - 0.2971).abs() < 1e-4 && error < 1e-9);
//! # Ok::<(), stickslip::Error>(())
//! ```
//!
//! A scene can also be read from TOML ([`Scene::from_toml_str`],
//! [`Scene::from_path`]); [`run`] returns an [`Outcome`]: a periodic
//! steady state with its indicators ([`RunReport`]), a slider that runs
//! away, or a start-up that did not settle. Each is a result, not an error.
//! [`RunOptions`] hands [`run`] a signal built once ([`Scene::build`],
//! [`simulation::SignalCache`]) or the event engine's tolerances;
//! [`Outcome::of_engine`] runs the same analysis on an engine set up by
//! the caller, and [`RunReport::sensitivities`] gives the exact
//! derivatives of `v_inf` at the steady state.
//!
//! ## The front door
//!
//! The crate root names what a script runs against: [`Scene`] (with its
//! [`SignalSpec`] and [`MotorParams`]), [`run`] and its [`RunOptions`],
//! the [`Outcome`] and its [`RunReport`], the [`Indicator`]s, and
//! [`Error`]. Everything else lives in a namespace, one per step of the
//! data path below; every public type name is used once across them
//! (`tests/architecture.rs` checks it).
//!
//! ## The data path
//!
//! Dependencies point one way, from the bottom of this list to the top
//! (`tests/architecture.rs` checks it):
//!
//! 1. [`error`] (every error type), [`numerics`]: trigonometric
//!    polynomials and their certified roots, brackets, compensated sums,
//!    line fits, contours of gridded values; no physics; [`symbol`]: the
//!    one table of quantity symbols and units that the indicators and
//!    every figure's labels share;
//! 2. [`signal`] (the rod signal, docs/model.md section 2), [`motor`] (the
//!    slider and its friction), [`power`] (the actuator's input power,
//!    section 6.3 of the paper); [`actuator`]: the rod driven by a voltage
//!    through the actuator's equation, with the friction acting back on it;
//!    [`spring`]: a spring against the slider (the spring method of
//!    measuring force, section 5 of the paper);
//! 3. [`engine`]: walks the slider through time and hands every exact
//!    segment, event and period end to an [`engine::Observer`];
//!    `engine/<method>.rs` is one engine ([`engine::EventEngine`], the
//!    exact one; [`engine::FixedStepEngine`], the fixed-step reference),
//!    `engine/contact.rs` the stick/slip decision they share;
//! 4. [`observer`]: what a run records ([`observer::EventLog`],
//!    [`observer::Trajectory`]);
//! 5. [`analysis`]: per-period statistics, the start-up, the fixed point of
//!    the period map, the steady state and the error estimates;
//!    [`sensitivity`]: exact derivatives of the steady state with respect
//!    to the motor's and the signal's parameters;
//! 6. [`indicator`]: the one table of indicators ([`Indicator`]);
//! 7. [`scene`]: the validated description of a run ([`Scene`]);
//!    [`provenance`]: the version and the scene's hash;
//! 8. [`simulation`]: runs a scene ([`run`]) with a time budget;
//! 9. [`report`] (text and JSON), [`check`] (the fixed-step cross-check),
//!    [`export`], [`compare`] (a user's own results against the exact
//!    ones), [`sweep`], [`characteristic`] (velocity against load, stall
//!    force), [`optimize`] (the best drive signal), [`plot`]
//!    (`plot/<figure family>.rs`);
//! 10. [`bench`](mod@bench): the spring method's reading against stiffness, beside
//!     the stall force and the start-up force (the characteristic's);
//! 11. [`cli`], the `stickslip` command.
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

pub mod actuator;
pub mod analysis;
pub mod bench;
pub mod characteristic;
pub mod check;
#[cfg(feature = "cli")]
pub mod cli;
pub mod compare;
mod csv_text;
pub mod engine;
pub mod error;
pub mod export;
pub mod indicator;
mod interrupt;
pub mod motor;
pub mod numerics;
pub mod observer;
pub mod optimize;
mod output;
#[cfg(feature = "plot")]
pub mod plot;
mod plural;
pub mod power;
pub mod provenance;
pub mod report;
pub mod scene;
pub mod sensitivity;
pub mod signal;
pub mod simulation;
pub mod spring;
pub mod sweep;
pub mod symbol;

pub use error::Error;
pub use indicator::Indicator;
pub use motor::MotorParams;
pub use scene::Scene;
pub use signal::SignalSpec;
pub use simulation::{Outcome, RunOptions, RunReport, run};
