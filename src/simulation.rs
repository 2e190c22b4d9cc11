//! One run of a scene: build the signal and the motor, run the engine the
//! scene names through the start-up and the steady state with the
//! observers the scene asks for, and gather every requested indicator with
//! its error estimate, the work counters and the wall time.

use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::fixed_step::{FixedStepEngine, FixedStepOptions};
use crate::engine::{Event, EventCounts, PeriodEngine, Segment, WorkCounters};
use crate::error::Error;
use crate::indicators::{
    self, AnalysisOptions, StatsWanted, SteadyIndicators, SteadyState, Transient,
};
use crate::motor::Motor;
use crate::observer::{EventLog, Trajectory};
use crate::power::{self, PowerReport};
use crate::scene::{EngineKind, Indicator, Scene};
use crate::signal::Signal;
use std::time::{Duration, Instant};

/// Estimated absolute error of each reported indicator (same units).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ErrorEstimate {
    /// Of `v_inf` (m/s).
    pub v_inf: Option<f64>,
    /// Of the start-up time (s).
    pub startup_time: Option<f64>,
    /// Of the smoothness.
    pub smoothness: Option<f64>,
    /// Of the durability (1/N).
    pub durability: Option<f64>,
    /// Of the friction energy (J).
    pub friction_energy: Option<f64>,
    /// Of the stiction fraction.
    pub stiction_fraction: Option<f64>,
    /// Of the velocity per power (m/(s VA)).
    pub velocity_per_power: Option<f64>,
}

/// Everything a run produced.
#[derive(Debug, Clone)]
pub struct RunReport {
    /// Period `T` (s).
    pub period: f64,
    /// Highest frequency `f_max = n f_0` (Hz), for harmonic signals.
    pub f_max: Option<f64>,
    /// The indicators asked for.
    pub requested: Vec<Indicator>,
    /// The steady state.
    pub steady: SteadyState,
    /// Indicators of the steady state.
    pub indicators: SteadyIndicators,
    /// The start-up from rest, when an indicator needs it.
    pub transient: Option<Transient>,
    /// `p_0.99`.
    pub startup_periods: Option<u64>,
    /// Time in stick over the simulated transient / its duration.
    pub stiction_fraction_transient: Option<f64>,
    /// Electrical input power, when asked for.
    pub power: Option<PowerReport>,
    /// Error estimates.
    pub error: ErrorEstimate,
    /// Engine work (all periods simulated, period-map evaluations included).
    pub work: WorkCounters,
    /// Wall time of the simulation (not of parsing or output).
    pub wall_time: Duration,
    /// The event log of the transient, if asked: its first
    /// [`crate::observer::MAX_LOGGED_EVENTS`] events.
    pub event_log: Option<Vec<Event>>,
    /// Events of the transient left out of the full event log.
    pub event_log_omitted: u64,
    /// The steady-state period's segments, if asked.
    pub trajectory: Option<Vec<Segment>>,
}

/// The mode of operation in steady state (Part I of the paper): whether the
/// slider sticks at all, and whether it ever slips.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Regime {
    /// The slider never slips: it follows the rod (`a_R` stays in the stick
    /// band).
    Stuck,
    /// Phases of stiction and of sliding in every period.
    StickSlip,
    /// No stiction in steady state: the slider always slides.
    SlipSlip,
}

impl Regime {
    /// Name in reports: `stuck`, `stick-slip`, `slip-slip`.
    pub fn name(self) -> &'static str {
        match self {
            Regime::Stuck => "stuck",
            Regime::StickSlip => "stick-slip",
            Regime::SlipSlip => "slip-slip",
        }
    }
}

impl RunReport {
    /// The steady-state mode of operation, from the steady period's time in
    /// stick and time sliding.
    pub fn regime(&self) -> Regime {
        let stats = &self.steady.stats;
        match (stats.stick_time > 0.0, stats.slip_time > 0.0) {
            (_, false) => Regime::Stuck,
            (true, true) => Regime::StickSlip,
            (false, true) => Regime::SlipSlip,
        }
    }

    /// `v_inf / S` (35), when power was computed.
    pub fn velocity_per_power(&self) -> Option<f64> {
        self.power
            .as_ref()
            .map(|p| self.indicators.v_inf / p.apparent_power)
    }

    /// Start-up time `T p_0.99` (s).
    pub fn startup_time(&self) -> Option<f64> {
        self.startup_periods.map(|p| p as f64 * self.period)
    }

    /// Events of the simulated motion from rest (the transient), or of one
    /// steady-state period when no transient was simulated.
    pub fn events(&self) -> EventCounts {
        self.transient
            .as_ref()
            .map_or(self.steady.stats.events, |t| t.events)
    }

    /// True if this indicator was asked for.
    pub fn wants(&self, indicator: Indicator) -> bool {
        self.requested.contains(&indicator)
    }
}

/// Builds the signal and motor of a scene.
pub fn build(scene: &Scene) -> Result<(Signal, Motor), Error> {
    let motor = Motor::new(scene.motor)?;
    let signal = Signal::build(&scene.signal, &motor)?;
    Ok((signal, motor))
}

/// Runs a scene with the engine it names.
pub fn run(scene: &Scene) -> Result<RunReport, Error> {
    let (signal, motor) = build(scene)?;
    match scene.run.engine {
        EngineKind::Event => {
            let engine = EventEngine::new(&signal, &motor, EventOptions::default());
            run_with(engine, scene, &motor)
        }
        EngineKind::Fixed => {
            let options = FixedStepOptions {
                steps_per_harmonic: scene.run.steps_per_harmonic,
                ..FixedStepOptions::default()
            };
            let engine = FixedStepEngine::new(&signal, &motor, options);
            run_with(engine, scene, &motor)
        }
    }
}

/// Runs the analysis a scene asks for with a prepared engine.
pub fn run_with<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
) -> Result<RunReport, Error> {
    let clock = Instant::now();
    let mut engine = crate::budget::TimeBudget::new(engine, scene.run.time_limit_s);
    let requested = scene.outputs.indicators.clone();
    let wants = |i: Indicator| requested.contains(&i);
    let signal = engine.signal().clone();
    let period = signal.period();
    let wanted = StatsWanted {
        smoothness: wants(Indicator::Smoothness),
        sliding: wants(Indicator::Durability) || wants(Indicator::FrictionEnergy),
        stiction: wants(Indicator::StictionFraction),
        slip_time: false,
    };
    let mut trajectory = scene.outputs.trajectory.then(Trajectory::default);
    let mut event_log = scene.outputs.events.then(EventLog::default);
    let mut options = AnalysisOptions {
        max_periods: scene.run.max_periods,
        ..Default::default()
    };
    // Fast path: the period map's fixed point from rest (the first period
    // from rest moves the slider exactly as the map does from v = 0), then
    // the start-up up to p_0.99 (or to convergence, as a cross-check).
    // The map is monotone but may have several fixed points; the steady
    // state is the one the start-up reaches. When the fast path cannot be
    // trusted (the engine's map has bands of fixed points, the search from
    // rest fails, or the start-up settles elsewhere) the start-up is run to
    // convergence first and seeds the fixed point.
    let fast = if engine.steady_state_from_transient() {
        None
    } else {
        match indicators::steady_state(&mut engine, 0.0, wanted, &mut trajectory) {
            Ok(steady) => {
                options.stop_at_startup = (!scene.run.verify_steady_state).then_some(steady.v_inf);
                let transient =
                    indicators::transient(&mut engine, &options, wanted, &mut event_log)?;
                let settled_elsewhere = transient.converged
                    && (transient.v_inf() - steady.v_inf).abs() > 1e-6 * signal.velocity_scale();
                (!settled_elsewhere).then_some((steady, transient))
            }
            Err(_) => None,
        }
    };
    let (steady, transient) = match fast {
        Some(found) => found,
        None => {
            options.stop_at_startup = None;
            event_log = scene.outputs.events.then(EventLog::default);
            trajectory = scene.outputs.trajectory.then(Trajectory::default);
            let transient = indicators::transient(&mut engine, &options, wanted, &mut event_log)?;
            let steady = indicators::steady_state(
                &mut engine,
                transient.final_velocity,
                wanted,
                &mut trajectory,
            )?;
            (steady, transient)
        }
    };
    let indicators = steady.indicators(motor, period);
    let startup_periods = transient.startup_periods(steady.v_inf);
    let power = match (&scene.actuator, &signal) {
        (Some(actuator), Signal::Fourier(s)) if wants(Indicator::VelocityPerPower) => {
            Some(power::input_power(s, actuator))
        }
        _ => None,
    };
    let wall_time = clock.elapsed();
    let stiction_fraction_transient = wanted
        .stiction
        .then(|| transient.stick_time / (transient.periods() as f64 * period));
    let mut error = estimate_errors(&signal, &steady, &transient, &indicators, startup_periods);
    if let Some(p) = &power {
        // S (35) is a closed form of the signal: only v_inf carries error.
        error.velocity_per_power = error.v_inf.map(|dv| dv / p.apparent_power);
    }
    Ok(RunReport {
        period,
        f_max: signal.f_max(),
        requested,
        indicators,
        startup_periods,
        stiction_fraction_transient,
        power,
        error,
        work: engine.counters(),
        wall_time,
        event_log_omitted: event_log.as_ref().map_or(0, |l| l.omitted),
        event_log: event_log.map(|l| l.events),
        trajectory: trajectory.map(|t| t.segments),
        transient: Some(transient),
        steady,
    })
}

/// Error estimates from measurable quantities:
/// * `v_inf`: the engine's bound `u` on the velocity error one period
///   introduces (event-time brackets times the jump in slider acceleration
///   at each event, plus zero-velocity decisions) and the fixed point's
///   residual `|P(v*) - v*|`, carried to the fixed point as
///   `/ (1 - P')` with the period map's derivative `P'`, plus `u` again for
///   the steady-state period itself, plus a rounding bound of `8 eps` per
///   segment on velocities and positions; a velocity error moves the slider
///   only while it slides. No bound is given through a grazing or where
///   `P' >= 1`. Without an engine bound, the disagreement of transient and
///   fixed point is used;
/// * ratios (smoothness, durability, friction energy) carry the relative
///   error of `v_inf` and the same rounding bound on their own inputs;
/// * `p_0.99` is exact unless a `v_p` lies within the `v_inf` error of the
///   0.99 threshold, in which case it may be off by one period.
fn estimate_errors(
    signal: &Signal,
    steady: &SteadyState,
    transient: &Transient,
    ind: &SteadyIndicators,
    startup_periods: Option<u64>,
) -> ErrorEstimate {
    let period = signal.period();
    let v_scale = signal.velocity_scale();
    let stats = &steady.stats;
    let segments = stats.events.total() as f64 + 2.0;
    // Relative rounding of a sum over the period's segments.
    let rounding_rel = 16.0 * f64::EPSILON * segments;
    let rounding_v = 8.0 * f64::EPSILON * segments * v_scale;
    let rounding_x = 8.0 * f64::EPSILON * segments * (signal.position_scale() + stats.step.abs());
    // A velocity error moves the slider only while it slides: in stick it
    // follows the rod whatever its velocity was before.
    let slip_fraction = (stats.slip_time / period).clamp(0.0, 1.0);
    // Bound on the slider velocity error along the orbit, if one exists.
    let velocity_error = match steady.velocity_uncertainty {
        Some(u) if u.is_finite() => {
            let contraction = 1.0 - steady.map_derivative;
            (contraction > 0.0)
                .then(|| (u + rounding_v + steady.residual) / contraction + u + rounding_v)
        }
        // A grazing in the steady orbit: the motion depends discontinuously
        // on the data there, so no bound holds.
        Some(_) => None,
        None => Some(
            (transient.v_inf() - steady.v_inf)
                .abs()
                .max(steady.last_correction)
                + rounding_v,
        ),
    };
    let Some(dvel) = velocity_error else {
        return ErrorEstimate::default();
    };
    let dv = dvel * slip_fraction + rounding_x / period;
    let spread = stats.v_max - stats.v_min;
    let sliding = stats.sliding_distance;
    let d_sliding = dvel * stats.slip_time + rounding_x;
    let startup = startup_periods.map(|p| {
        let threshold = 0.99 * steady.v_inf;
        let near = transient
            .mean_velocities
            .iter()
            .take(p as usize)
            .any(|v| (v - threshold).abs() <= 0.99 * dv);
        if near { period } else { 0.0 }
    });
    ErrorEstimate {
        v_inf: Some(dv),
        startup_time: startup,
        // zeta = |v_inf| / spread; the spread's ends carry the velocity error.
        smoothness: ind
            .smoothness
            .is_finite()
            .then(|| dv / spread + ind.smoothness * (2.0 * dvel / spread + rounding_rel)),
        // delta = x_p / (F_c s) with x_p = v_inf T.
        durability: ind.durability.is_finite().then(|| {
            ind.durability.abs()
                * (dv * period / stats.step.abs() + d_sliding / sliding + rounding_rel)
        }),
        // W_f = mu_d F_c s.
        friction_energy: Some(if sliding > 0.0 {
            ind.friction_energy * (d_sliding / sliding + rounding_rel)
        } else {
            0.0
        }),
        // Every start or end of a stick phase may be off by the engine's
        // event-time uncertainty.
        stiction_fraction: Some(
            rounding_rel
                + (stats.events.stick_to_slip + stats.events.slip_to_stick + stats.events.jump)
                    as f64
                    * steady.event_time_uncertainty
                    / period,
        ),
        velocity_per_power: None,
    }
}
