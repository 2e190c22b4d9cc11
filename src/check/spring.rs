//! The cross-check of a slider against a spring (docs/model.md section
//! 17): the exact engine's run with the spring, and the fixed-step
//! reference with it, bounded, over the periods the exact engine's
//! figures describe (the rule is in the module docs of [`crate::check`],
//! "A spring against the slider").

use super::{CheckReport, EngineRun, Figure, indicator_figures, rows};
use crate::actuator::DrivenRod;
use crate::analysis::{StatsObserver, StatsWanted, SteadyIndicators, SteadyState};
use crate::engine::event::EventOptions;
use crate::engine::{
    DrivenEngine, DrivenState, EventCounts, PeriodEngine, PeriodStart, SpringProfile,
};
use crate::error::{Error, ParamError};
use crate::indicator::Indicator;
use crate::motor::Motor;
use crate::scene::Scene;
use crate::signal::Signal;
use crate::simulation::budget::TimeBudget;
use crate::simulation::{self, SpringReading};
use crate::spring::Spring;
use std::time::{Duration, Instant};

/// Where the event engine's motion from rest reads its orbit: every force
/// figure (`spring_force_mean`, `_max`, `_min`) within this fraction of
/// the orbit's largest `|F_spring|`, the contact fraction within it.
pub const SETTLED: f64 = 1e-9;

/// The periods the fixed-step reference against a spring is run and read
/// over (module docs of [`crate::check`], "A spring against the slider").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpringWindow {
    /// Periods `1..=startup` from rest of the start-up figures (the
    /// start-up's `stiction_fraction` and events): the event engine's
    /// start-up ([`crate::simulation::RunReport::startup_span`]).
    pub startup: u64,
    /// Periods of the event engine's motion from rest before the orbit
    /// is read: the first of `p`, `2p`, `4p`, ... (`p` the periods of its
    /// start-up, at most `run.max_periods`) after which it reads its
    /// orbit's spring figures within [`SETTLED`].
    pub settle: u64,
    /// False if it did not read them within `run.max_periods`; `settle`
    /// is then that limit.
    pub settled: bool,
    /// Periods read from the event engine's state after `settle`: its
    /// orbit's.
    pub read: u64,
}

/// One run of the fixed-step reference against a spring.
#[derive(Debug, Clone)]
pub struct SpringRun {
    /// Steps per period of the highest harmonic.
    pub steps_per_harmonic: u32,
    /// Steps per signal period.
    pub steps_per_period: u64,
    /// Periods simulated: `startup + read`.
    pub periods: u64,
    /// Events over periods `1..=startup`.
    pub startup_events: EventCounts,
    /// Time in stick over periods `1..=startup` over their duration, when
    /// `stiction_fraction` is asked for.
    pub stiction_fraction: Option<f64>,
    /// The indicators of the first period read, as of a steady period.
    pub steady: SteadyIndicators,
    /// The spring's figures over the periods read.
    pub reading: SpringProfile,
    /// Wall time of engine set-up and the whole run.
    pub wall_time: Duration,
}

/// The fixed-step reference against a spring at every resolution.
#[derive(Debug, Clone)]
pub struct SpringCheck {
    /// What every reference run reads over.
    pub window: SpringWindow,
    /// The runs, from coarse to fine.
    pub reference: Vec<SpringRun>,
}

/// [`super::check`] for a scene with `spring`; `steps` are validated.
pub(super) fn check(
    scene: &Scene,
    (signal, motor): (&Signal, &Motor),
    rod: Option<&DrivenRod>,
    spring: Spring,
    steps: &[u32],
) -> Result<CheckReport, Error> {
    let clock = Instant::now();
    let make = || simulation::spring_engine(signal, motor, rod, spring, EventOptions::default());
    let engine = make()?;
    let setup = clock.elapsed();
    let mut report = simulation::run_with_rod(engine, scene, motor, rod)?;
    report.setup_time = setup;
    report.wall_time = clock.elapsed();
    let orbit = report
        .spring
        .ok_or_else(|| no_reading("the exact engine"))?;
    let startup = report.startup_span();
    let from = report.transient.as_ref().map_or(1, |t| t.periods());
    let settled = settle_periods(make()?, scene, &orbit, from)?;
    let window = SpringWindow {
        startup,
        settle: settled.periods,
        settled: settled.reached,
        read: orbit.periods,
    };
    let event = EngineRun {
        steps_per_harmonic: None,
        steps_per_period: None,
        wall_time: report.wall_time,
        report,
    };
    let mut reference = Vec::with_capacity(steps.len());
    for &s in steps {
        reference.push(reference_run(
            scene,
            (signal, motor),
            rod,
            spring,
            s,
            (&window, &settled.state),
        )?);
    }
    let fixed: Vec<(u32, Vec<Figure>)> = reference
        .iter()
        .map(|r| (r.steps_per_harmonic, r.figures(&event.report.requested)))
        .collect();
    let rows = rows(&event_figures(&event), &fixed);
    Ok(CheckReport {
        event,
        reference: Vec::new(),
        rows,
        spring: Some(SpringCheck { window, reference }),
    })
}

/// The error of an engine with a spring that read none (not expected: an
/// engine with a spring reads it over every period it runs).
fn no_reading(engine: &str) -> Error {
    ParamError::Inconsistent {
        field: "spring".to_owned(),
        reason: format!("{engine} gave no reading of the spring"),
    }
    .into()
}

/// The spring's figures in the units of the check's table.
fn reading_figures(p: &SpringProfile) -> Vec<Figure> {
    simulation::spring_figures(p)
        .into_iter()
        .map(|(name, value, unit)| Figure {
            name,
            unit: if unit.is_empty() { "1" } else { unit },
            value,
            error: None,
        })
        .collect()
}

/// The event engine's figures: its indicators, then the spring's.
fn event_figures(event: &EngineRun) -> Vec<Figure> {
    let mut out = indicator_figures(&event.report);
    if let Some(s) = &event.report.spring {
        out.extend(reading_figures(&s.profile));
    }
    out
}

impl SpringRun {
    /// The run's figures by the names of the event engine's: the
    /// indicators asked for that apply with a spring, then the spring's.
    fn figures(&self, requested: &[Indicator]) -> Vec<Figure> {
        let mut out = Vec::new();
        let mut push = |name, unit, value: f64| {
            if value.is_finite() {
                out.push(Figure {
                    name,
                    unit,
                    value,
                    error: None,
                });
            }
        };
        for indicator in requested {
            match indicator {
                Indicator::FrictionEnergy => push(
                    indicator.name(),
                    indicator.printed_unit(),
                    self.steady.friction_energy,
                ),
                Indicator::StictionFraction => {
                    if let Some(f) = self.stiction_fraction {
                        push(indicator.name(), indicator.printed_unit(), f);
                    }
                    push(
                        "stiction_fraction_steady",
                        "1",
                        self.steady.stiction_fraction,
                    );
                }
                // The others assume the slider travels on: refused with
                // a spring (docs/model.md section 17).
                _ => {}
            }
        }
        out.extend(reading_figures(&self.reading));
        out
    }
}

/// Where the exact motion from rest reads its orbit.
struct Settled {
    /// Periods from rest.
    periods: u64,
    /// Whether it reads the orbit there.
    reached: bool,
    /// Its boundary state there.
    state: DrivenState,
}

/// The periods from rest after which `engine` (the exact engine with the
/// spring) reads its `orbit` within [`SETTLED`]: the first of `from`,
/// `2 from`, ... up to `run.max_periods`, whether it did, and its state.
fn settle_periods(
    engine: DrivenEngine<'_>,
    scene: &Scene,
    orbit: &SpringReading,
    from: u64,
) -> Result<Settled, Error> {
    let o = &orbit.profile;
    let scale = o.force_max.abs().max(o.force_min.abs());
    let reads_orbit = |p: &SpringProfile| {
        [
            (p.force_mean, o.force_mean),
            (p.force_max, o.force_max),
            (p.force_min, o.force_min),
        ]
        .iter()
        .all(|(a, b)| (a - b).abs() <= SETTLED * scale)
            && (p.contact_fraction - o.contact_fraction).abs() <= SETTLED
    };
    let cap = scene.run.max_periods.max(1);
    let mut engine = TimeBudget::new(engine, scene.run.time_limit_s);
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let (mut done, mut target) = (0, from.clamp(1, cap));
    loop {
        while done < target {
            done += 1;
            let end = engine.run_period(done, start, &mut ())?;
            start = PeriodStart {
                velocity: end.velocity,
                mode: Some(end.mode),
            };
        }
        let state = engine
            .boundary_state()
            .ok_or_else(|| no_reading("the exact engine"))?;
        let mut trial = engine.engine().clone();
        let reading = simulation::orbit_reading(&mut trial, orbit.periods)?;
        let reached = reading.is_some_and(|orbit| reads_orbit(&orbit.profile));
        if reached || target >= cap {
            return Ok(Settled {
                periods: target,
                reached,
                state,
            });
        }
        target = target.saturating_mul(2).min(cap);
    }
}

/// The fixed-step reference at `steps` per harmonic over `window`: from
/// rest over `window.startup` periods (the start-up figures), then from
/// the exact motion's boundary state `state` after `window.settle`
/// periods, the spring read over `window.read` periods (the indicators of
/// a steady period from the first of them).
fn reference_run(
    scene: &Scene,
    (signal, motor): (&Signal, &Motor),
    rod: Option<&DrivenRod>,
    spring: Spring,
    steps: u32,
    (window, state): (&SpringWindow, &DrivenState),
) -> Result<SpringRun, Error> {
    let clock = Instant::now();
    let engine = simulation::fixed_step_engine(signal, motor, rod, Some(spring), steps);
    let steps_per_period = engine.steps_per_period();
    let period = signal.period();
    let mut engine = TimeBudget::new(engine, scene.run.time_limit_s);
    let wanted = StatsWanted {
        sliding: true,
        stiction: true,
        ..StatsWanted::default()
    };
    let mut stats = StatsObserver::for_engine(&engine, wanted);
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let (mut stick, mut startup_events) = (0.0, EventCounts::default());
    for p in 1..=window.startup {
        let end = engine.run_period(p, start, &mut stats)?;
        stick += stats.last.stick_time;
        startup_events = startup_events.merged(&stats.last.events);
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    engine.engine_mut().continue_from(state);
    start = PeriodStart {
        velocity: state.slider_v,
        mode: Some(state.mode),
    };
    engine.engine_mut().read_spring();
    // The first period read stands for a steady period.
    let end = engine.run_period(window.settle + 1, start, &mut stats)?;
    let first = stats.last;
    start = PeriodStart {
        velocity: end.velocity,
        mode: Some(end.mode),
    };
    for p in 2..=window.read {
        let next = engine.run_period(window.settle + p, start, &mut ())?;
        start = PeriodStart {
            velocity: next.velocity,
            mode: Some(next.mode),
        };
    }
    let reading = engine
        .engine()
        .spring_reading()
        .ok_or_else(|| no_reading("the fixed-step reference"))?;
    let steady = SteadyState {
        boundary_velocity: end.velocity,
        map_derivative: end.map_derivative,
        v_inf: first.step / period,
        stats: first,
        iterations: 0,
        last_correction: 0.0,
        residual: 0.0,
        velocity_uncertainty: None,
        event_time_uncertainty: engine.event_time_uncertainty(),
        boundary_bound: None,
    }
    .indicators(motor, period);
    let asked = scene
        .outputs
        .indicators
        .contains(&Indicator::StictionFraction);
    Ok(SpringRun {
        steps_per_harmonic: steps,
        steps_per_period,
        periods: engine.counters().periods,
        startup_events,
        stiction_fraction: (asked && window.startup > 0)
            .then(|| stick / (window.startup as f64 * period)),
        steady,
        reading,
        wall_time: clock.elapsed(),
    })
}
