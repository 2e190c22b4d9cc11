//! # stickslip
//!
//! An event-driven simulator for piezoelectric inertia drives ("stick-slip
//! drives"), after Hunstig, Hemsel and Sextro, *Stick-slip and slip-slip
//! operation of piezoelectric inertia drives, Part II: frequency-limited
//! excitation*.
//!
//! Data flows one way:
//!
//! 1. [`scene`]: a TOML scene is parsed and validated into a typed [`Scene`];
//! 2. the scene builds the rod [`Signal`] ([`signal`]) and the [`Motor`]
//!    ([`motor`]);
//! 3. an engine ([`engine`]) walks the slider through time, event by event,
//!    and hands every exact segment to the observers the scene asked for
//!    ([`observer`]);
//! 4. [`indicators`] drives the transient and the periodic steady state and
//!    turns observer results into the paper's performance indicators;
//!    [`power`] adds the electrical input power (section 6.3);
//!    [`sensitivity`] differentiates the steady state with respect to the
//!    scene's parameters;
//! 5. [`report`] prints text or JSON.

pub mod budget;
pub mod check;
pub mod cli;
pub mod compare;
pub mod engine;
pub mod error;
pub mod export;
pub mod indicators;
pub mod interrupt;
pub mod motor;
pub mod numerics;
pub mod observer;
pub mod output;
pub mod plot;
pub mod power;
pub mod provenance;
pub mod report;
pub mod scene;
pub mod sensitivity;
pub mod signal;
pub mod simulation;
pub mod stability;
pub mod sweep;

pub use error::{Error, ParamError, SceneError, SimulationError};
pub use motor::{Motor, MotorParams};
pub use scene::Scene;
pub use signal::{Signal, SignalSpec};
