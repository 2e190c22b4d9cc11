//! One run of a scene: build the signal and the motor, run the engine the
//! scene names through the start-up and the steady state with the
//! observers the scene asks for, and gather every requested indicator with
//! its error estimate, the work counters and the time spent.
//!
//! # Outcomes
//!
//! Every physical outcome is a result ([`Outcome`]): a periodic steady state
//! (`stuck`, `stick-slip`, `slip-slip`) with its indicators, a slider that
//! runs away, or a start-up whose limit was not established within
//! `run.max_periods` (with the last `v_p` and the bounds on `v_inf` that
//! are known). Only bad input and internal failures are errors.
//!
//! # Which steady state: the motion from rest
//!
//! `v_inf` is the limit of the motion from rest (docs/model.md section 3,
//! the paper's 6.1). With `u_k` the slider velocity at the end of period
//! `k` (`u_0 = 0`, at rest), `u_(k+1) = P(u_k)` with the period map `P`,
//! which is non-decreasing (two sliders on the same rod never overtake each
//! other). Hence:
//!
//! 1. the orbit `u_k` is monotone: if `u_1 >= u_0` then, inductively,
//!    `u_(k+1) = P(u_k) >= P(u_(k-1)) = u_k`; so it converges (or leaves
//!    every bound: a run-away), and its limit `u*` is the fixed point
//!    nearest to `u_0` in the direction of `P(u_0) - u_0`;
//! 2. every fixed point `w` beyond an iterate (`w >= u_k` for a rising
//!    orbit) bounds the limit: `u_k <= u* <= w`, because `u_k <= w` gives
//!    `u_(k+1) = P(u_k) <= P(w) = w`; the same holds for the mean
//!    velocities, `v_p` and the periodic orbit's `v_inf`, since a slider
//!    starting faster stays ahead;
//! 3. so a fixed point found by a search from rest is the limit when no
//!    other fixed point lies between the orbit and it.
//!
//! The fast path searches `P(v) = v` from rest ([`crate::analysis::fixed_point`])
//! and uses the fixed point only when it is *established* (the map
//! contracts there, `1 - P' > 0`, and the engine's bound on the fixed
//! point, which contains the range where `P(v) - v` is indistinguishable
//! from 0 within rounding, is at most `1e-3 max |v_R|`; see
//! `established_bound`) and *certified*: the covering of
//! `crate::analysis::certificate` proves, by the monotone step and the
//! growth bound of the friction law, that no fixed point lies between the
//! start of the covering and `v* - 2 bound`, so that by 3. `v*` is the limit
//! within twice its bound. Where the covering meets a point the map does
//! not move towards `v*`, a nearer fixed point lies in the bracket it gives
//! (`P` maps it into itself); that one is found
//! ([`crate::analysis::fixed_point_between`]), established and certified in turn,
//! and the first is reported as the other fixed point
//! ([`SteadyStateCertificate`]). When the covering does not close within
//! its budget of map evaluations (or a nearer fixed point is not
//! established), the orbit from rest decides: the start-up is simulated
//! until its limit is established ([`crate::analysis::transient`]: an exact
//! repetition, a repetition within rounding in periods with a stick phase, or a
//! remaining distance bounded by the measured contraction), and the
//! steady state is taken there (a fixed point searched from the orbit's
//! end is used only if it lies within that bound). Without an established limit within `run.max_periods` the result
//! is [`Outcome::NotConverged`], with the bounds of 2.
//!
//! # Only what the scene asks for
//!
//! The start-up from rest is simulated only when something needs it: the
//! start-up time, the start-up's stiction fraction, the event log,
//! `run.verify_steady_state`. Otherwise (a `v_inf`-only scene, or one that
//! asks only for steady-state indicators) the covering starts at rest;
//! when the start-up is simulated up to `p_0.99`, it starts at the orbit's
//! last point, since the orbit covers what lies behind it (each step
//! `[u_k, u_(k+1)]` is a monotone step). If the orbit passes the fixed point
//! (contradicting 2.) or settles elsewhere before `p_0.99`, the orbit
//! decides.
//!
//! Where the search's fixed point is certified, the reported `v_inf`, its
//! error estimate and the steady-state indicators are bit for bit those of
//! a run that simulates the start-up: both take the same fixed point from
//! the same search. `periods_simulated` is then 0, the start-up's event
//! counts are all 0 (counted over what was simulated), and
//! `work.map_evaluations` ([`RunReport::map_evaluations`]) counts the
//! search, the covering and the steady-state periods.
//!
//! With `run.verify_steady_state` the start-up is run on to its own limit
//! and compared with the fixed point: a difference beyond the two error
//! estimates is reported ([`SteadyStateCheck`]), and nothing else that is
//! reported changes (the start-up quantities cover periods `1..=p_0.99`
//! whatever the settings).
//!
//! # Cost
//!
//! [`RunReport::setup_time`] is the signal's and engine's set-up (root
//! finding of the signal's event structure included),
//! [`RunReport::simulation_time`] the analysis (start-up, fixed point,
//! indicators, power), [`RunReport::wall_time`] all of it.

pub(crate) mod budget;
mod cache;
mod certified;
mod drive;
mod driven;
mod outcome;
mod spring_error;
mod spring_reading;

pub use crate::analysis::ErrorEstimate;
pub use cache::SignalCache;
pub use outcome::{
    CertificateKind, Outcome, Regime, RunReport, RunTimes, SpringReading, SteadyStateCertificate,
    SteadyStateCheck, Unsettled,
};
pub use spring_error::{ReadingErrorParts, SpringReadingError};
pub(crate) use spring_reading::{orbit_reading, spring_figures};

use crate::actuator::{DrivenRod, DrivenSpec, RodModel, Voltage};
use crate::engine::DrivenEngine;
use crate::engine::PeriodEngine;
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::fixed_step::{FixedStepEngine, FixedStepOptions};
use crate::error::{Error, ParamError, SimulationError};
use crate::motor::Motor;
use crate::scene::{EngineKind, Scene};
use crate::signal::Signal;
use crate::spring::Spring;
use drive::simulate_timed;
use std::time::Instant;

/// How [`run`] runs a scene, beyond what the scene itself says
/// (`RunOptions::default()`: build the scene's signal, the event engine's
/// default tolerances).
#[derive(Debug, Clone, Copy, Default)]
pub struct RunOptions<'a> {
    /// The rod signal, already built: by [`Scene::build`], or shared from a
    /// [`SignalCache`] between scenes that differ in the motor only. The
    /// set-up time is then the motor's and the engine's alone. `None`:
    /// the run builds `scene.signal`.
    pub signal: Option<&'a Signal>,
    /// The event engine's tolerances and limits (`run.engine = "event"`).
    pub event: EventOptions,
}

/// Runs a scene with the engine it names: the start-up, the steady state
/// and every indicator the scene asks for. Every physical outcome (a
/// steady state, a run-away, a start-up that did not settle) is an
/// [`Outcome`]; only bad input and internal failures are errors.
pub fn run(scene: &Scene, options: &RunOptions) -> Result<Outcome, Error> {
    let clock = Instant::now();
    let motor = Motor::new(scene.motor)?;
    match options.signal {
        Some(signal) => simulate_built(scene, signal, &motor, options.event, clock),
        None => {
            let signal = Signal::build(&scene.signal, &motor)?;
            simulate_built(scene, &signal, &motor, options.event, clock)
        }
    }
}

/// The signal and motor of a scene, for the crate's own front ends.
pub(crate) fn build(scene: &Scene) -> Result<(Signal, Motor), Error> {
    let built = scene.build()?;
    Ok((built.signal, built.motor))
}

/// [`build`] for what computes with the prescribed rod only: a driven rod
/// (docs/model.md section 16) is refused with a one-line error naming
/// `what`.
pub(crate) fn build_prescribed(scene: &Scene, what: &str) -> Result<(Signal, Motor), Error> {
    prescribed_only(scene, what)?;
    build(scene)
}

/// Refuses a driven rod for `what`, which computes with the prescribed
/// rod only.
pub(crate) fn prescribed_only(scene: &Scene, what: &str) -> Result<(), ParamError> {
    match scene.rod {
        RodModel::Prescribed => Ok(()),
        RodModel::Driven(_) => Err(ParamError::Inconsistent {
            field: "actuator.rod".to_owned(),
            reason: format!(
                "not available for a driven rod ({what} assumes the rod follows its signal); a driven rod runs with `run`, `check`, `sweep` and `signal --voltage`"
            ),
        }),
    }
}

/// `v_inf`'s sensitivities need net travel: refused with a spring
/// against the slider (docs/model.md section 17).
fn travel_only(scene: &Scene, what: &str) -> Result<(), ParamError> {
    match scene.spring {
        None => Ok(()),
        Some(_) => Err(ParamError::Inconsistent {
            field: "spring".to_owned(),
            reason: format!(
                "{what} are those of v_inf, which does not apply against a spring (the slider \
                 oscillates about its equilibrium)"
            ),
        }),
    }
}

/// [`run`] with the default options.
pub(crate) fn simulate(scene: &Scene) -> Result<Outcome, Error> {
    run(scene, &RunOptions::default())
}

pub(super) fn simulate_built(
    scene: &Scene,
    signal: &Signal,
    motor: &Motor,
    event: EventOptions,
    clock: Instant,
) -> Result<Outcome, Error> {
    let mut outcome = match (&scene.rod, scene.run.engine) {
        // A spring against the slider: the exact engine's closed forms of a
        // rod that follows its signal (Scene::validate refuses a
        // discontinuous signal with a spring).
        (RodModel::Prescribed, EngineKind::Event) if scene.spring.is_some() => {
            let spring = scene.spring.expect("a spring");
            let engine = spring_engine(signal, motor, None, spring, event)?;
            simulate_timed(engine, scene, motor, None, clock)?
        }
        (RodModel::Driven(spec), engine) => {
            let rod = driven_rod(scene, spec, signal, motor)?;
            match engine {
                EngineKind::Event => {
                    let engine = match scene.spring {
                        Some(spring) => spring_engine(signal, motor, Some(&rod), spring, event)?,
                        None => DrivenEngine::new(
                            signal,
                            &rod,
                            motor,
                            event.velocity_tolerance,
                            event.max_events_per_period,
                        ),
                    };
                    simulate_timed(engine, scene, motor, Some(&rod), clock)?
                }
                EngineKind::Fixed => {
                    let steps = scene.run.steps_per_harmonic;
                    let engine = fixed_step_engine(signal, motor, Some(&rod), scene.spring, steps);
                    simulate_timed(engine, scene, motor, None, clock)?
                }
            }
        }
        (RodModel::Prescribed, EngineKind::Event) => {
            let engine = EventEngine::new(signal, motor, event);
            simulate_timed(engine, scene, motor, None, clock)?
        }
        (RodModel::Prescribed, EngineKind::Fixed) => {
            let steps = scene.run.steps_per_harmonic;
            let engine = fixed_step_engine(signal, motor, None, scene.spring, steps);
            simulate_timed(engine, scene, motor, None, clock)?
        }
    };
    let wall = clock.elapsed();
    match &mut outcome {
        Outcome::Steady(r) => r.wall_time = wall,
        Outcome::RunAway { state, .. } | Outcome::NotConverged(state) => state.wall_time = wall,
    }
    Ok(outcome)
}

/// The exact engine of a slider against `spring` (docs/model.md section
/// 17): a rod that follows `signal` (`rod` is `None`,
/// [`DrivenEngine::prescribed`]) or the driven `rod`
/// ([`DrivenEngine::new`]), with the spring
/// ([`DrivenEngine::with_spring`]). A rod or signal the engine takes no
/// spring with is a one-line error naming `spring`.
pub(crate) fn spring_engine<'a>(
    signal: &'a Signal,
    motor: &Motor,
    rod: Option<&'a DrivenRod>,
    spring: Spring,
    event: EventOptions,
) -> Result<DrivenEngine<'a>, Error> {
    let (tolerance, events) = (event.velocity_tolerance, event.max_events_per_period);
    let (engine, reason) = match rod {
        None => (
            DrivenEngine::prescribed(signal, motor, tolerance, events),
            "needs a continuous signal (fourier or harmonics) and a prescribed rod",
        ),
        Some(rod) => (
            Some(DrivenEngine::new(signal, rod, motor, tolerance, events)),
            "is outside its ranges",
        ),
    };
    engine
        .and_then(|e| e.with_spring(spring, motor))
        .ok_or_else(|| {
            ParamError::Inconsistent {
                field: "spring".to_owned(),
                reason: reason.to_owned(),
            }
            .into()
        })
}

/// The fixed-step reference (docs/model.md section 12) at
/// `steps_per_harmonic`: for a rod that follows `signal` (`rod` is `None`)
/// or the driven `rod`, with `spring` against the slider if there is one
/// (section 17).
pub(crate) fn fixed_step_engine<'a>(
    signal: &'a Signal,
    motor: &Motor,
    rod: Option<&DrivenRod>,
    spring: Option<Spring>,
    steps_per_harmonic: u32,
) -> FixedStepEngine<'a> {
    let options = FixedStepOptions {
        steps_per_harmonic,
        ..FixedStepOptions::default()
    };
    let engine = match rod {
        None => FixedStepEngine::new(signal, motor, options),
        Some(rod) => FixedStepEngine::driven(signal, motor, rod, options),
    };
    match spring {
        Some(spring) => engine.with_spring(spring),
        None => engine,
    }
}

/// The driven rod of a scene (`[actuator] rod = "driven"`): the voltage
/// given in `[voltage]`, or designed for the scene's actuator and signal,
/// driving the real actuator.
pub(crate) fn driven_rod(
    scene: &Scene,
    spec: &DrivenSpec,
    signal: &Signal,
    motor: &Motor,
) -> Result<DrivenRod, Error> {
    let (Some(design), Signal::Fourier(series)) = (&scene.actuator, signal) else {
        // Scene::validate refuses a driven rod without an actuator or with
        // an ideal signal.
        return Err(ParamError::Inconsistent {
            field: "actuator.rod".to_owned(),
            reason: "a driven rod needs [actuator] and a continuous signal".to_owned(),
        }
        .into());
    };
    let voltage = match &scene.voltage {
        Some(given) => given.voltage(),
        None => Voltage::designed(series, design),
    };
    Ok(DrivenRod::new(spec, design, voltage, motor)?)
}

/// [`run_with`] for an engine with a driven rod's state or a spring's
/// (`rod`: the driven rod, whose fixed point is then found by Newton with
/// its exact Jacobian, as [`run`] does; `None` for a rod that follows its
/// signal).
pub(crate) fn run_with_rod<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
    rod: Option<&DrivenRod>,
) -> Result<RunReport, Error> {
    simulate_timed(engine, scene, motor, rod, Instant::now())?.into_report()
}

/// [`run`] for callers that need a steady state: a run-away or an
/// unestablished limit is an error here.
pub(crate) fn steady(scene: &Scene) -> Result<RunReport, Error> {
    simulate(scene)?.into_report()
}

/// [`Outcome::of_engine`] for callers that need a steady state.
pub(crate) fn run_with<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
) -> Result<RunReport, Error> {
    Outcome::of_engine(engine, scene, motor)?.into_report()
}

impl Outcome {
    /// The analysis a scene asks for, on an engine already set up (its
    /// own signal and options, or an engine of the caller's own): the
    /// scene's `run.engine` is not read, the set-up time is 0.
    pub fn of_engine<E: PeriodEngine>(
        engine: E,
        scene: &Scene,
        motor: &Motor,
    ) -> Result<Outcome, Error> {
        simulate_timed(engine, scene, motor, None, Instant::now())
    }
}

impl RunReport {
    /// A driven rod's sensitivities of `v_inf` to the real actuator's
    /// mass, damping, stiffness and transfer factor, the voltage held fixed
    /// (docs/model.md section 16), at this steady state of `scene`.
    pub fn actuator_sensitivities(
        &self,
        scene: &Scene,
    ) -> Result<crate::sensitivity::ActuatorSensitivities, Error> {
        let (RodModel::Driven(spec), Some(segments)) = (&scene.rod, &self.driven_period) else {
            return Err(ParamError::Inconsistent {
                field: "actuator.rod".to_owned(),
                reason:
                    "the actuator's sensitivities need a driven rod (actuator.rod = \"driven\")"
                        .to_owned(),
            }
            .into());
        };
        travel_only(scene, "the actuator's sensitivities")?;
        let (signal, motor) = build(scene)?;
        let rod = driven_rod(scene, spec, &signal, &motor)?;
        crate::sensitivity::of_driven_period(&rod, &motor, self.period, segments).map_err(
            |reason| {
                ParamError::Inconsistent {
                    field: "actuator.rod".to_owned(),
                    reason: format!("no sensitivities: {reason}"),
                }
                .into()
            },
        )
    }

    /// The exact sensitivities of `v_inf` to every parameter of `scene`
    /// ([`crate::sensitivity::Parameter::all_for`]) at this steady state,
    /// the report of a run of `scene` (docs/model.md section 14). Only the
    /// event engine's steady state of a prescribed rod has them (a driven
    /// rod's: [`RunReport::actuator_sensitivities`]).
    pub fn sensitivities(&self, scene: &Scene) -> Result<crate::sensitivity::Sensitivities, Error> {
        prescribed_only(scene, "the sensitivities")?;
        travel_only(scene, "the sensitivities")?;
        if scene.run.engine != EngineKind::Event {
            return Err(SimulationError::NoSensitivity(
                "they are exact for the event engine only (run.engine = \"event\")".to_owned(),
            )
            .into());
        }
        let parameters = crate::sensitivity::Parameter::all_for(&scene.signal);
        crate::sensitivity::of_steady_state(
            &scene.signal,
            &scene.motor,
            self.steady.boundary_velocity,
            &parameters,
        )
    }
}
