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
//! The fast path searches `P(v) = v` from rest ([`indicators::fixed_point`])
//! and uses the fixed point only when it is *established*: the map
//! contracts there (`1 - P' > 0`) and the engine's bound on the fixed
//! point, which contains the range where `P(v) - v` is indistinguishable
//! from 0 within rounding, is at most `1e-3 max |v_R|` (see
//! [`established_bound`]). A map that is neutral
//! within rounding (`P(v) - v` indistinguishable from 0 over a range, as
//! with `mu_dynamic = 0`, where every velocity of the slip range passes for
//! a fixed point) or nearly neutral (`P'` within rounding of 1) is not
//! established. The start-up from rest is then simulated up to `p_0.99`;
//! if its orbit passes the fixed point (contradicting 2.) or settles
//! elsewhere before `p_0.99`, the fixed point is rejected. When the fast
//! path is rejected, the orbit from rest decides: the start-up is simulated
//! until its limit is established ([`indicators::transient`]: an exact
//! repetition or a remaining distance bounded by the measured contraction),
//! and the steady state is taken there (a fixed point searched from the
//! orbit's end is used only if it lies within that bound). Without an
//! established limit within `run.max_periods` the result is
//! [`Outcome::NotConverged`], with the bounds of 2.
//!
//! # Only what the scene asks for
//!
//! The start-up from rest is simulated only when something needs it: the
//! start-up time, the start-up's stiction fraction, the event log,
//! `run.verify_steady_state`. Otherwise (a `v_inf`-only scene, or one that
//! asks only for steady-state indicators) an established fixed point `v*`
//! of the search from rest is checked, instead of by the start-up, by a
//! march of map evaluations from rest towards `v*`
//! ([`indicators::fixed_point_is_nearest`]): at `x_i = i v* / 16`
//! (`i = 1..15`), then at `v* (1 - 2^-j)` for `j = 5, 6, ...` while
//! farther than the fixed point's bound from `v*`. When the start-up is
//! simulated up to `p_0.99`, the same march runs from the orbit's last
//! point on, since the orbit covers what lies behind it:
//!
//! 4. a point `x` between rest and `v*` that the map does not move towards
//!    `v*` (`P(x) <= x` for `v* > 0`) proves a fixed point in `[0, x]`:
//!    `P` maps `[0, x]` into itself (`P(0) > 0`, `P(x) <= x`, monotone), so
//!    it has a fixed point there (Tarski), nearer than `v*`; the run then
//!    takes the orbit from rest (the slow path below);
//! 5. every `x_i` with `g(x_i) = P(x_i) - x_i > 0` proves that no fixed
//!    point lies in `[x_i, x_i + g(x_i)]`: for `v` there,
//!    `P(v) >= P(x_i) = x_i + g(x_i) >= v`, equality only at the right
//!    end, which is `P(x_i)`, and `P(P(x_i)) >= P(x_i)`, so the orbit from
//!    `x_i` goes on; with `x_0 = 0` this covers `[0, P(0)]`, and the
//!    orbit's own points cover `[0, u_k]`;
//! 6. what 4. and 5. leave open is a further pair of fixed points (an
//!    interval where `g` has the sign opposite to `P(0) - 0`) that falls
//!    between two march points: narrower than `v* / 16` far from `v*`,
//!    and narrower than about half its distance to `v*` near it (the
//!    geometric points). Covering every gap by 5. would take about as many
//!    map evaluations as the start-up itself, so this is not a proof for
//!    such pairs: `run.verify_steady_state` settles the doubt by
//!    simulating the start-up to its own limit and comparing.
//!
//! The reported `v_inf`, its error estimate (from the engine's bound at the
//! fixed point, which needs no start-up) and the steady-state indicators
//! are bit for bit those of a run that simulates the start-up: both take
//! the same fixed point from the same search. `periods_simulated` is then
//! 0, the start-up's event counts are all 0 (counted over what was
//! simulated), and `work.map_evaluations` ([`RunReport::map_evaluations`])
//! counts the search, the march and the steady-state periods.
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

use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::fixed_step::{FixedStepEngine, FixedStepOptions};
use crate::engine::{Direction, Event, EventCounts, PeriodEngine, Segment, WorkCounters};
use crate::error::{Error, SimulationError};
use crate::indicators::{
    self, AnalysisOptions, StatsWanted, SteadyIndicators, SteadyState, Transient,
};
use crate::motor::Motor;
use crate::observer::{EventLog, Trajectory};
use crate::power::{self, PowerReport};
use crate::scene::{EngineKind, Indicator, Scene};
use crate::signal::{Signal, SignalSpec};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
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
    /// Of the friction energy (J per period).
    pub friction_energy: Option<f64>,
    /// Of the stiction fraction.
    pub stiction_fraction: Option<f64>,
    /// Of the velocity per power (m/(s VA)).
    pub velocity_per_power: Option<f64>,
}

/// The cross-check of `run.verify_steady_state`: the start-up from rest run
/// on to its own limit, against the steady state reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyStateCheck {
    /// The start-up's limit of `v_p` (m/s); `None` if it was not
    /// established within `run.max_periods`.
    pub v_inf_transient: Option<f64>,
    /// `v_inf_transient - v_inf` (m/s).
    pub difference: Option<f64>,
    /// The sum of both error estimates (m/s), when both exist.
    pub tolerance: Option<f64>,
    /// Periods of the start-up simulated.
    pub periods: u64,
}

impl SteadyStateCheck {
    /// `Some(true)` if the two agree within their error estimates,
    /// `Some(false)` if they do not, `None` if that cannot be said (no
    /// limit of the start-up, or no error estimate).
    pub fn agrees(&self) -> Option<bool> {
        match (self.difference, self.tolerance) {
            (Some(d), Some(t)) => Some(d.abs() <= t),
            _ => None,
        }
    }
}

/// Everything a run that reached a periodic steady state produced.
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
    /// The start-up from rest as simulated (up to `p_0.99`, or further to
    /// convergence with `run.verify_steady_state` or where the start-up
    /// decided the steady state).
    pub transient: Option<Transient>,
    /// `p_0.99`: the first period with `v_p / v_inf >= 0.99`; `None` when
    /// not reached or when `|v_inf|` is not larger than its error estimate.
    pub startup_periods: Option<u64>,
    /// Time in stick over the start-up (periods `1..=p_0.99`, or every
    /// simulated period without a start-up time) / its duration.
    pub stiction_fraction_transient: Option<f64>,
    /// Electrical input power, when asked for.
    pub power: Option<PowerReport>,
    /// Error estimates.
    pub error: ErrorEstimate,
    /// Engine work (all periods simulated, period-map evaluations included).
    pub work: WorkCounters,
    /// Periods run from chosen start velocities rather than along the
    /// start-up from rest: the fixed-point searches, the check that the
    /// fixed point is the nearest one, the steady-state periods.
    pub map_evaluations: u64,
    /// Set-up of signal and engine (s): 0 when the engine was handed in.
    pub setup_time: Duration,
    /// The analysis: start-up, fixed point, indicators, power.
    pub simulation_time: Duration,
    /// Everything the run computed (set-up and analysis; not parsing or
    /// output).
    pub wall_time: Duration,
    /// The cross-check of `run.verify_steady_state`, when asked.
    pub steady_state_check: Option<SteadyStateCheck>,
    /// The event log of the start-up (periods `1..=p_0.99`), if asked: its
    /// first [`crate::observer::MAX_LOGGED_EVENTS`] events.
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

    /// The periods the start-up quantities cover: `1..=p_0.99`, or every
    /// simulated period of the start-up when there is no start-up time.
    pub fn startup_span(&self) -> u64 {
        self.startup_periods
            .or_else(|| self.transient.as_ref().map(Transient::periods))
            .unwrap_or(0)
    }

    /// Events of the start-up from rest (periods `1..=p_0.99`, see
    /// [`RunReport::startup_span`]): counted over what was simulated, so all
    /// zero when no start-up was simulated (a run that needs none, module
    /// docs).
    pub fn events(&self) -> EventCounts {
        self.transient
            .as_ref()
            .map_or(EventCounts::default(), |t| t.events(self.startup_span()))
    }

    /// True if this indicator was asked for.
    pub fn wants(&self, indicator: Indicator) -> bool {
        self.requested.contains(&indicator)
    }

    /// The value of an indicator, with one definition for every output
    /// (run text and JSON, check, sweeps, figures): `stiction_fraction` is
    /// the start-up's, `friction_energy` is J per steady-state period.
    /// `None` where it does not exist (not reached, not computed, infinite
    /// or undefined).
    pub fn indicator(&self, indicator: Indicator) -> Option<f64> {
        let ind = &self.indicators;
        let value = match indicator {
            Indicator::VInf => Some(ind.v_inf),
            Indicator::StartupTime => self.startup_time(),
            Indicator::Smoothness => Some(ind.smoothness),
            Indicator::Durability => Some(ind.durability),
            Indicator::FrictionEnergy => Some(ind.friction_energy),
            Indicator::StictionFraction => self.stiction_fraction_transient,
            Indicator::VelocityPerPower => self.velocity_per_power(),
        };
        value.filter(|v| v.is_finite())
    }

    /// The error estimate of an indicator (same unit), when one holds.
    pub fn indicator_error(&self, indicator: Indicator) -> Option<f64> {
        let e = &self.error;
        match indicator {
            Indicator::VInf => e.v_inf,
            Indicator::StartupTime => e.startup_time,
            Indicator::Smoothness => e.smoothness,
            Indicator::Durability => e.durability,
            Indicator::FrictionEnergy => e.friction_energy,
            Indicator::StictionFraction => e.stiction_fraction,
            Indicator::VelocityPerPower => e.velocity_per_power,
        }
    }
}

/// What is known about a run without a periodic steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct Unsettled {
    /// Period `T` (s).
    pub period: f64,
    /// Highest frequency `f_max = n f_0` (Hz), for harmonic signals.
    pub f_max: Option<f64>,
    /// The indicators asked for (none of them exists).
    pub requested: Vec<Indicator>,
    /// Periods of the start-up from rest simulated.
    pub periods_simulated: u64,
    /// Mean velocity `v_p` of the last simulated period (m/s).
    pub last_v_p: Option<f64>,
    /// Slider velocity at the end of the last simulated period (m/s).
    pub final_velocity: f64,
    /// Bounds on the limit `v_inf` of the motion from rest (m/s), lower and
    /// upper, where known: the orbit's last `v_p` on the side it came from,
    /// an established fixed point on the other (see the module docs).
    pub v_inf_bounds: (Option<f64>, Option<f64>),
    /// Engine work.
    pub work: WorkCounters,
    /// Set-up of signal and engine.
    pub setup_time: Duration,
    /// The analysis.
    pub simulation_time: Duration,
    /// Everything the run computed.
    pub wall_time: Duration,
}

/// The result of a run: every physical outcome.
#[derive(Debug, Clone)]
pub enum Outcome {
    /// A periodic steady state (`stuck`, `stick-slip` or `slip-slip`).
    Steady(Box<RunReport>),
    /// The slider runs away: it slid a whole period outside the rod's
    /// velocity range without any event, moving further away (the extra
    /// acceleration exceeds what sliding friction can hold).
    RunAway {
        /// The direction it runs in.
        direction: Direction,
        /// Where it was when that was established.
        state: Unsettled,
    },
    /// The start-up's limit was not established within `run.max_periods`.
    NotConverged(Unsettled),
}

impl Outcome {
    /// Every name [`Outcome::regime`] gives.
    pub const REGIMES: [&'static str; 5] = [
        "stuck",
        "stick-slip",
        "slip-slip",
        "run-away",
        "not_converged",
    ];

    /// `regime` in reports and sweep rows: `stuck`, `stick-slip`,
    /// `slip-slip`, `run-away` or `not_converged`.
    pub fn regime(&self) -> &'static str {
        match self {
            Outcome::Steady(r) => r.regime().name(),
            Outcome::RunAway { .. } => "run-away",
            Outcome::NotConverged(_) => "not_converged",
        }
    }

    /// The steady-state report, if there is a steady state.
    pub fn report(&self) -> Option<&RunReport> {
        match self {
            Outcome::Steady(r) => Some(r),
            _ => None,
        }
    }

    /// What is known without a steady state.
    pub fn unsettled(&self) -> Option<&Unsettled> {
        match self {
            Outcome::Steady(_) => None,
            Outcome::RunAway { state, .. } | Outcome::NotConverged(state) => Some(state),
        }
    }

    /// An indicator's value ([`RunReport::indicator`]); `None` (null in
    /// JSON, empty in CSV) without a steady state.
    pub fn indicator(&self, indicator: Indicator) -> Option<f64> {
        self.report().and_then(|r| r.indicator(indicator))
    }

    /// Periods of the start-up from rest simulated.
    pub fn periods_simulated(&self) -> u64 {
        match self {
            Outcome::Steady(r) => r.transient.as_ref().map_or(0, Transient::periods),
            _ => self.unsettled().map_or(0, |u| u.periods_simulated),
        }
    }

    /// `(setup, simulation, wall)` times.
    pub fn times(&self) -> (Duration, Duration, Duration) {
        match self {
            Outcome::Steady(r) => (r.setup_time, r.simulation_time, r.wall_time),
            _ => {
                let u = self.unsettled().expect("not steady");
                (u.setup_time, u.simulation_time, u.wall_time)
            }
        }
    }

    /// The steady-state report, or the outcome as an error for callers
    /// that need a steady state (figures, stability checks).
    pub fn into_report(self) -> Result<RunReport, SimulationError> {
        match self {
            Outcome::Steady(r) => Ok(*r),
            Outcome::RunAway { direction, state } => Err(SimulationError::NoSteadyState {
                direction: match direction {
                    Direction::Forward => "growing",
                    Direction::Backward => "falling",
                },
                velocity: state.final_velocity,
                periods: state.periods_simulated,
            }),
            Outcome::NotConverged(state) => Err(SimulationError::NotConverged {
                periods: state.periods_simulated,
                last_v_p: state.last_v_p.unwrap_or(0.0),
            }),
        }
    }
}

/// Builds the signal and motor of a scene.
pub fn build(scene: &Scene) -> Result<(Signal, Motor), Error> {
    let motor = Motor::new(scene.motor)?;
    let signal = Signal::build(&scene.signal, &motor)?;
    Ok((signal, motor))
}

/// Runs a scene with the engine it names; every physical outcome is a
/// result.
pub fn simulate(scene: &Scene) -> Result<Outcome, Error> {
    let clock = Instant::now();
    let (signal, motor) = build(scene)?;
    simulate_built(scene, &signal, &motor, clock)
}

/// [`simulate`] with the scene's signal already built (by
/// [`Signal::build`] from `scene.signal` and the scene's motor, e.g. from
/// a [`SignalCache`]): the set-up time is then the motor's and the
/// engine's alone.
pub fn simulate_with_signal(scene: &Scene, signal: &Signal) -> Result<Outcome, Error> {
    let clock = Instant::now();
    let motor = Motor::new(scene.motor)?;
    simulate_built(scene, signal, &motor, clock)
}

fn simulate_built(
    scene: &Scene,
    signal: &Signal,
    motor: &Motor,
    clock: Instant,
) -> Result<Outcome, Error> {
    let mut outcome = match scene.run.engine {
        EngineKind::Event => {
            let engine = EventEngine::new(signal, motor, EventOptions::default());
            simulate_timed(engine, scene, motor, clock)?
        }
        EngineKind::Fixed => {
            let options = FixedStepOptions {
                steps_per_harmonic: scene.run.steps_per_harmonic,
                ..FixedStepOptions::default()
            };
            let engine = FixedStepEngine::new(signal, motor, options);
            simulate_timed(engine, scene, motor, clock)?
        }
    };
    let wall = clock.elapsed();
    match &mut outcome {
        Outcome::Steady(r) => r.wall_time = wall,
        Outcome::RunAway { state, .. } | Outcome::NotConverged(state) => state.wall_time = wall,
    }
    Ok(outcome)
}

/// Signals built once and shared, for many scenes that differ elsewhere
/// (a sweep over the motor): keyed by the signal spec and, for the
/// `kappa`-based kinds, by the motor's `a_0` (the only motor quantity a
/// signal depends on, docs/model.md section 2). Safe to share between
/// threads; holds at most [`SignalCache::CAPACITY`] signals (then it is
/// emptied and starts again), so that a sweep over the signal itself does
/// not keep every signal it ran.
#[derive(Debug, Default)]
pub struct SignalCache {
    signals: Mutex<HashMap<String, Arc<Signal>>>,
}

impl SignalCache {
    /// Signals kept at most.
    pub const CAPACITY: usize = 64;

    /// The signal of `scene`, built on first use.
    pub fn get(&self, scene: &Scene) -> Result<Arc<Signal>, Error> {
        let motor = Motor::new(scene.motor)?;
        let key = match &scene.signal {
            SignalSpec::Harmonics { .. } => format!("{:?}", scene.signal),
            _ => format!("{:?} a_0 = {:?}", scene.signal, motor.a_0()),
        };
        let lock = |m: &Mutex<HashMap<String, Arc<Signal>>>| {
            // A panic elsewhere leaves the map intact: keep using it.
            m.lock()
                .unwrap_or_else(|e| e.into_inner())
                .get(&key)
                .cloned()
        };
        if let Some(signal) = lock(&self.signals) {
            return Ok(signal);
        }
        // Built outside the lock: other threads go on meanwhile.
        let signal = Arc::new(Signal::build(&scene.signal, &motor)?);
        let mut map = self.signals.lock().unwrap_or_else(|e| e.into_inner());
        if map.len() >= Self::CAPACITY {
            map.clear();
        }
        Ok(map.entry(key).or_insert(signal).clone())
    }

    /// [`simulate`] with the signal from this cache.
    pub fn simulate(&self, scene: &Scene) -> Result<Outcome, Error> {
        let clock = Instant::now();
        let signal = self.get(scene)?;
        let motor = Motor::new(scene.motor)?;
        simulate_built(scene, &signal, &motor, clock)
    }

    /// [`run`] with the signal from this cache.
    pub fn run(&self, scene: &Scene) -> Result<RunReport, Error> {
        Ok(self.simulate(scene)?.into_report()?)
    }
}

/// Runs a scene with the engine it names, for callers that need a steady
/// state: a run-away or an unestablished limit is an error here.
pub fn run(scene: &Scene) -> Result<RunReport, Error> {
    Ok(simulate(scene)?.into_report()?)
}

/// [`run`] with a prepared engine.
pub fn run_with<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
) -> Result<RunReport, Error> {
    Ok(simulate_with(engine, scene, motor)?.into_report()?)
}

/// The analysis a scene asks for with a prepared engine (set-up time 0).
pub fn simulate_with<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
) -> Result<Outcome, Error> {
    simulate_timed(engine, scene, motor, Instant::now())
}

/// The rounding bound on velocities over one period's segments (m/s).
fn rounding_velocity(signal: &Signal, steady: &SteadyState) -> f64 {
    let segments = steady.stats.events.total() as f64 + 2.0;
    8.0 * f64::EPSILON * segments * signal.velocity_scale()
}

/// The engine's bound on the boundary velocity of the periodic orbit
/// through `steady` (m/s): the velocity error `u` one period introduces
/// plus the rounding bound and the residual, carried to the fixed point as
/// `/ (1 - P')`, plus `u` again for the steady period itself. `None` where
/// no bound holds: no engine bound, a grazing in the orbit (`u` infinite),
/// or `P' >= 1` (a neutral map).
fn engine_bound(signal: &Signal, steady: &SteadyState) -> Option<f64> {
    let u = steady.velocity_uncertainty.filter(|u| u.is_finite())?;
    let rounding_v = rounding_velocity(signal, steady);
    let contraction = 1.0 - steady.map_derivative;
    (contraction > 0.0).then(|| (u + rounding_v + steady.residual) / contraction + u + rounding_v)
}

/// Largest [`engine_bound`], relative to `max |v_R|`, for which a fixed
/// point counts as established. The bound contains the range over which
/// the map is neutral within rounding, `rounding / (1 - P')`: where `P(v) - v`
/// cannot be told from 0 over a wider range, the map's zero does not say
/// where the motion from rest goes.
const ESTABLISHED: f64 = 1e-3;

/// The engine's bound on a fixed point from the search, if the fixed point
/// is established: the map contracts there (`P' < 1`), the orbit has no
/// grazing, and the bound (neutral range included) is at most
/// `1e-3 max |v_R|`.
pub fn established_bound(signal: &Signal, steady: &SteadyState) -> Option<f64> {
    engine_bound(signal, steady).filter(|b| *b <= ESTABLISHED * signal.velocity_scale())
}

/// True if the orbit from rest, up to period `periods`, went past the fixed
/// point `v_star` (beyond its bound) in the direction it moves: then the
/// fixed point is not the limit (see the module docs, 2.).
fn orbit_passes(transient: &Transient, periods: u64, v_star: f64, bound: f64) -> bool {
    let seen = &transient.boundary_velocities
        [..(periods as usize).min(transient.boundary_velocities.len())];
    if v_star >= 0.0 {
        seen.iter().any(|u| *u > v_star + bound)
    } else {
        seen.iter().any(|u| *u < v_star - bound)
    }
}

fn simulate_timed<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
    setup_clock: Instant,
) -> Result<Outcome, Error> {
    let setup_time = setup_clock.elapsed();
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
    let verify = scene.run.verify_steady_state;
    // The start-up from rest is simulated only for what needs it: the
    // start-up time, the start-up's stiction fraction, its event log and
    // the cross-check of verify_steady_state (module docs, "Only what the
    // scene asks for").
    let needs_startup = verify
        || wants(Indicator::StartupTime)
        || wants(Indicator::StictionFraction)
        || scene.outputs.events;
    // Periods run from chosen velocities: the fixed-point searches, the
    // march of the nearest-fixed-point check and the steady-state periods.
    let mut map_evaluations = 0;
    // Fast path: the period map's fixed point from rest (the first period
    // from rest moves the slider exactly as the map does from v = 0), used
    // only when established; then either the check that it is the nearest
    // fixed point, or the start-up up to p_0.99 (on to convergence with
    // verify_steady_state). See the module docs.
    let mut rest_fixed_point = None;
    let fast = if engine.steady_state_from_transient() {
        None
    } else {
        let before = engine.counters().periods;
        let found = indicators::steady_state(&mut engine, 0.0, wanted, &mut trajectory);
        map_evaluations += engine.counters().periods - before;
        let established = found
            .ok()
            .and_then(|steady| established_bound(&signal, &steady).map(|b| (steady, b)));
        match established {
            Some((steady, bound)) if !needs_startup => {
                rest_fixed_point = Some((steady.boundary_velocity, steady.v_inf));
                let (nearest, marched) = indicators::fixed_point_is_nearest(
                    &mut engine,
                    steady.boundary_velocity,
                    bound,
                    0.0,
                )?;
                map_evaluations += u64::from(marched);
                nearest.then_some((steady, None))
            }
            Some((steady, bound)) => {
                rest_fixed_point = Some((steady.boundary_velocity, steady.v_inf));
                // p_0.99 exists only where |v_inf| exceeds its error.
                let v_error = v_inf_error(&signal, &steady, bound);
                options.stop_at_startup =
                    (!verify && steady.v_inf.abs() > v_error).then_some(steady.v_inf);
                let transient =
                    indicators::transient(&mut engine, &options, wanted, &mut event_log)?;
                // Judge on what a run without verification sees: the
                // periods up to p_0.99.
                let seen = transient
                    .startup_periods(steady.v_inf)
                    .unwrap_or(transient.periods());
                let settled_elsewhere = transient.converged
                    && transient.periods() <= seen
                    && (transient.v_inf() - steady.v_inf).abs()
                        > bound + transient.v_inf_error.unwrap_or(0.0);
                let passes = orbit_passes(&transient, seen, steady.boundary_velocity, bound);
                // Between the orbit's last point and the fixed point, the
                // march of the v_inf-only check looks for a nearer one.
                let last = transient
                    .boundary_velocities
                    .get((seen as usize).saturating_sub(1))
                    .or(transient.boundary_velocities.last())
                    .copied()
                    .unwrap_or(0.0);
                let nearest = if transient.run_away.is_some() || settled_elsewhere || passes {
                    false
                } else {
                    let (nearest, marched) = indicators::fixed_point_is_nearest(
                        &mut engine,
                        steady.boundary_velocity,
                        bound,
                        last,
                    )?;
                    map_evaluations += u64::from(marched);
                    nearest
                };
                if transient.run_away.is_some() || nearest {
                    Some((steady, Some(transient)))
                } else {
                    None
                }
            }
            None => None,
        }
    };
    let from_orbit = fast.is_none();
    let (steady, transient) = match fast {
        Some(found) => found,
        None => {
            // The orbit from rest decides.
            options.stop_at_startup = None;
            event_log = scene.outputs.events.then(EventLog::default);
            trajectory = scene.outputs.trajectory.then(Trajectory::default);
            let transient = indicators::transient(&mut engine, &options, wanted, &mut event_log)?;
            if transient.run_away.is_some() || !transient.converged {
                return Ok(unsettled(
                    &engine,
                    &signal,
                    &requested,
                    &transient,
                    rest_fixed_point,
                    (setup_time, clock.elapsed()),
                ));
            }
            let before = engine.counters().periods;
            let seed = transient.final_velocity;
            let reach = transient.remaining.unwrap_or(0.0) + transient.v_inf_error.unwrap_or(0.0);
            let steady = match indicators::fixed_point(&mut engine, seed) {
                Ok((v, d, iterations, correction)) if (v - seed).abs() <= reach => {
                    indicators::steady_state_at(
                        &mut engine,
                        v,
                        (Some(d), iterations, correction),
                        wanted,
                        &mut trajectory,
                    )?
                }
                _ => indicators::steady_state_at(
                    &mut engine,
                    seed,
                    (None, 0, transient.remaining.unwrap_or(0.0)),
                    wanted,
                    &mut trajectory,
                )?,
            };
            map_evaluations += engine.counters().periods - before;
            (steady, Some(transient))
        }
    };
    if let Some(t) = transient.as_ref().filter(|t| t.run_away.is_some()) {
        return Ok(unsettled(
            &engine,
            &signal,
            &requested,
            t,
            rest_fixed_point,
            (setup_time, clock.elapsed()),
        ));
    }
    let indicators = steady.indicators(motor, period);
    let mut error = estimate_errors(
        &signal,
        &steady,
        transient.as_ref(),
        &indicators,
        from_orbit,
    );
    let startup_periods = transient
        .as_ref()
        .filter(|_| error.v_inf.is_none_or(|e| indicators.v_inf.abs() > e))
        .and_then(|t| t.startup_periods(steady.v_inf));
    error.startup_time = transient
        .as_ref()
        .and_then(|t| startup_error(period, &steady, t, startup_periods, error.v_inf));
    let power = match (&scene.actuator, &signal) {
        (Some(actuator), Signal::Fourier(s)) if wants(Indicator::VelocityPerPower) => {
            Some(power::input_power(s, actuator))
        }
        _ => None,
    };
    if let Some(p) = &power {
        // S (35) is a closed form of the signal: only v_inf carries error.
        error.velocity_per_power = error.v_inf.map(|dv| dv / p.apparent_power);
    }
    let span = startup_periods.unwrap_or(transient.as_ref().map_or(0, Transient::periods));
    let mut stiction_fraction_transient = None;
    let mut event_log_omitted = 0;
    let mut steady_state_check = None;
    if let Some(transient) = &transient {
        stiction_fraction_transient = (wanted.stiction && span > 0)
            .then(|| transient.stick_time(span) / (span as f64 * period));
        if error.stiction_fraction.is_some() {
            // Every start or end of a stick phase in the start-up may be off
            // by the engine's event-time uncertainty; the sum is rounded per
            // period.
            let e = transient.events(span);
            let transitions = (e.stick_to_slip + e.slip_to_stick + e.jump) as f64;
            error.stiction_fraction = Some(
                16.0 * f64::EPSILON * (e.total() as f64 + 2.0)
                    + transitions * steady.event_time_uncertainty / (span.max(1) as f64 * period),
            );
        }
        steady_state_check = verify.then(|| SteadyStateCheck {
            v_inf_transient: transient.converged.then(|| transient.v_inf()),
            difference: transient
                .converged
                .then(|| transient.v_inf() - indicators.v_inf),
            tolerance: error.v_inf.zip(transient.v_inf_error).map(|(a, b)| a + b),
            periods: transient.periods(),
        });
        // Events of the start-up beyond the log's capacity: counted, not
        // kept.
        if let Some(log) = &event_log {
            let logged = log.events.iter().filter(|e| e.period <= span).count();
            event_log_omitted = transient.events(span).total().saturating_sub(logged as u64);
        }
    }
    let event_log: Option<Vec<Event>> =
        event_log.map(|l| l.events.into_iter().filter(|e| e.period <= span).collect());
    let simulation_time = clock.elapsed();
    Ok(Outcome::Steady(Box::new(RunReport {
        period,
        f_max: signal.f_max(),
        requested,
        indicators,
        startup_periods,
        stiction_fraction_transient,
        power,
        error,
        work: engine.counters(),
        map_evaluations,
        setup_time,
        simulation_time,
        wall_time: setup_time + simulation_time,
        steady_state_check,
        event_log_omitted,
        event_log,
        trajectory: trajectory.map(|t| t.segments),
        transient,
        steady,
    })))
}

/// What is known about a start-up without an established limit: its last
/// `v_p` bounds `v_inf` on the side it came from (the orbit and its `v_p`
/// are monotone), an established fixed point beyond it on the other side.
fn unsettled<E: PeriodEngine>(
    engine: &E,
    signal: &Signal,
    requested: &[Indicator],
    transient: &Transient,
    rest_fixed_point: Option<(f64, f64)>,
    (setup_time, simulation_time): (Duration, Duration),
) -> Outcome {
    let last_v_p = transient.mean_velocities.last().copied();
    let u = transient.final_velocity;
    let beyond = |w: f64| {
        rest_fixed_point
            .filter(|(v, _)| (v - u) * w >= 0.0)
            .map(|(_, m)| m)
    };
    let v_inf_bounds = if u > 0.0 {
        (last_v_p, beyond(1.0))
    } else if u < 0.0 {
        (beyond(-1.0), last_v_p)
    } else {
        (None, None)
    };
    let state = Unsettled {
        period: signal.period(),
        f_max: signal.f_max(),
        requested: requested.to_vec(),
        periods_simulated: transient.periods(),
        last_v_p,
        final_velocity: u,
        v_inf_bounds,
        work: engine.counters(),
        setup_time,
        simulation_time,
        wall_time: setup_time + simulation_time,
    };
    match transient.run_away {
        Some(direction) => Outcome::RunAway { direction, state },
        None => Outcome::NotConverged(state),
    }
}

/// The estimated error of `v_inf` (m/s) from a bound on the orbit's
/// boundary velocity: a velocity error moves the slider only while it
/// slides (in stick it follows the rod whatever its velocity was), plus a
/// rounding bound on positions.
fn v_inf_error(signal: &Signal, steady: &SteadyState, velocity_bound: f64) -> f64 {
    let period = signal.period();
    let stats = &steady.stats;
    let segments = stats.events.total() as f64 + 2.0;
    let rounding_x = 8.0 * f64::EPSILON * segments * (signal.position_scale() + stats.step.abs());
    let slip_fraction = (stats.slip_time / period).clamp(0.0, 1.0);
    velocity_bound * slip_fraction + rounding_x / period
}

/// `p_0.99` is exact unless a `v_p` lies within the `v_inf` error of the
/// 0.99 threshold, in which case it may be off by one period.
fn startup_error(
    period: f64,
    steady: &SteadyState,
    transient: &Transient,
    startup_periods: Option<u64>,
    v_error: Option<f64>,
) -> Option<f64> {
    let (p, dv) = (startup_periods?, v_error?);
    let threshold = 0.99 * steady.v_inf;
    let near = transient
        .mean_velocities
        .iter()
        .take(p as usize)
        .any(|v| (v - threshold).abs() <= 0.99 * dv);
    Some(if near { period } else { 0.0 })
}

/// Error estimates from measurable quantities:
/// * `v_inf`: the engine's bound on the orbit's boundary velocity
///   ([`engine_bound`]: event-time brackets times the jump in slider
///   acceleration at each event, zero-velocity decisions, the fixed
///   point's residual, all carried through `/ (1 - P')`), turned into a
///   bound on the mean velocity by [`v_inf_error`]. Where the start-up
///   decided the steady state (or the engine states no bound), its own
///   estimate is used instead: the distance of its limit to the steady
///   state (or the last fixed-point correction) plus its remaining-distance
///   bound. No bound is given through a grazing;
/// * ratios (smoothness, durability, friction energy) carry the relative
///   error of `v_inf` and the same rounding bound on their own inputs;
/// * the start-up time is set by the caller ([`startup_error`]).
fn estimate_errors(
    signal: &Signal,
    steady: &SteadyState,
    transient: Option<&Transient>,
    ind: &SteadyIndicators,
    from_orbit: bool,
) -> ErrorEstimate {
    let period = signal.period();
    let stats = &steady.stats;
    let segments = stats.events.total() as f64 + 2.0;
    // Relative rounding of a sum over the period's segments.
    let rounding_rel = 16.0 * f64::EPSILON * segments;
    let rounding_v = rounding_velocity(signal, steady);
    let rounding_x = 8.0 * f64::EPSILON * segments * (signal.position_scale() + stats.step.abs());
    // Without a simulated start-up (a v_inf-only run) there is none: the
    // fast path needs the engine's bound.
    let from_transient = |t: &Transient| {
        (t.v_inf() - steady.v_inf).abs().max(steady.last_correction)
            + t.v_inf_error.unwrap_or(0.0)
            + rounding_v
    };
    let velocity_error = match steady.velocity_uncertainty {
        // A grazing in the steady orbit: the motion depends discontinuously
        // on the data there, so no bound holds.
        Some(u) if !u.is_finite() => None,
        Some(_) => match engine_bound(signal, steady) {
            Some(b) => Some(b),
            None if from_orbit => transient.filter(|t| t.converged).map(from_transient),
            None => None,
        },
        None => transient.map(from_transient),
    };
    let Some(dvel) = velocity_error else {
        return ErrorEstimate::default();
    };
    let dv = v_inf_error(signal, steady, dvel);
    let spread = stats.v_max - stats.v_min;
    let sliding = stats.sliding_distance;
    let d_sliding = dvel * stats.slip_time + rounding_x;
    ErrorEstimate {
        v_inf: Some(dv),
        startup_time: None,
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
        // Set by the caller over the start-up's periods.
        stiction_fraction: Some(rounding_rel),
        velocity_per_power: None,
    }
}

/// The exact sensitivities of `v_inf` to every parameter of `scene`
/// ([`crate::sensitivity::Parameter::all_for`]) at the steady state of its
/// run `report` (docs/model.md section 14). Only the event engine's steady
/// state has them.
pub fn sensitivities(
    scene: &Scene,
    report: &RunReport,
) -> Result<crate::sensitivity::Sensitivities, Error> {
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
        report.steady.boundary_velocity,
        &parameters,
    )
}
