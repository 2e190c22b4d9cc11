//! What a simulation returns: a periodic steady state with its indicators
//! ([`RunReport`]), a slider that runs away, or a start-up that did not
//! settle ([`Outcome`]); each is a result, not an error.

use crate::analysis::error_estimate::ErrorEstimate;
use crate::analysis::{SteadyIndicators, SteadyState, Transient};
use crate::engine::{Direction, DriveProfile, Event, EventCounts, Segment, WorkCounters};
use crate::error::{Error, SimulationError};
use crate::indicator::Indicator;
use crate::power::PowerReport;
use std::time::Duration;

/// The time a run took ([`Outcome::times`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunTimes {
    /// The signal's and the engine's set-up.
    pub setup: Duration,
    /// The analysis: start-up, fixed point, indicators, power.
    pub simulation: Duration,
    /// All of it.
    pub wall: Duration,
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

/// What a spring against the slider reads over the steady orbit
/// (docs/model.md section 17), or, where no orbit locked, over the last
/// periods simulated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringReading {
    /// The orbit's period in drive periods (1, or `k` for a subharmonic);
    /// 0 where no orbit of period up to [`SpringReading::searched`]'s `K`
    /// locked within its `N` periods from rest.
    pub orbit_periods: u64,
    /// The periods the reading covers (the orbit's, or the last ones
    /// simulated).
    pub periods: u64,
    /// The spring's force and the slider's position over them.
    pub profile: crate::engine::SpringProfile,
    /// Where no orbit locked: the least and largest mean force of a single
    /// period among them (N).
    pub mean_range: Option<[f64; 2]>,
    /// Where no orbit locked: `(K, N)`, the longest orbit looked for and
    /// the periods simulated from rest.
    pub searched: Option<(u64, u64)>,
    /// The reading's error estimate over an orbit (docs/model.md section
    /// 17, "The reading's error"); `None` where no orbit locked (none is
    /// invented: [`SpringReading::mean_range`] is what the run knows) or
    /// no bound holds (a grazing in the orbit).
    pub error: Option<super::SpringReadingError>,
}

/// How a steady state was established as the limit of the motion from
/// rest (docs/model.md section 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CertificateKind {
    /// The gap between rest (or the simulated orbit from rest) and the
    /// fixed point was covered by pieces proven free of fixed points.
    Covering,
    /// The orbit from rest was simulated until its own limit was
    /// established (an exact repetition, a repetition within rounding in
    /// periods with a stick phase, or a remaining distance bounded by the measured
    /// contraction).
    Orbit,
    /// A driven rod: the fixed point of the period map on the rod's and
    /// the slider's boundary state was found by Newton, and the start-up
    /// from rest was followed into its attraction (docs/model.md section
    /// 16, "The steady state").
    Attracted,
}

impl CertificateKind {
    /// Name in reports: `covering`, `orbit`, `attracted`.
    pub fn name(self) -> &'static str {
        match self {
            CertificateKind::Covering => "covering",
            CertificateKind::Orbit => "orbit",
            CertificateKind::Attracted => "attracted",
        }
    }
}

/// How the reported steady state was established and what that cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyStateCertificate {
    /// The argument that makes the steady state the motion from rest.
    pub kind: CertificateKind,
    /// Map evaluations the covering took (also when it did not succeed and
    /// the orbit decided).
    pub evaluations: u64,
    /// Distance (m/s, in the boundary velocity) from the reported fixed
    /// point to the nearest other fixed point found on the way: one the
    /// search reached first and the covering showed not to be the limit.
    /// `None` if none was found; its absence proves nothing.
    pub other_fixed_point: Option<f64>,
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
    /// How the steady state was established as the limit from rest.
    pub certificate: SteadyStateCertificate,
    /// The event log of the start-up (periods `1..=p_0.99`), if asked: its
    /// first [`crate::observer::MAX_LOGGED_EVENTS`] events.
    pub event_log: Option<Vec<Event>>,
    /// Events of the transient left out of the full event log.
    pub event_log_omitted: u64,
    /// The steady-state period's segments, if asked.
    pub trajectory: Option<Vec<Segment>>,
    /// A driven rod's deviation from its signal, voltage and current over
    /// the steady period (docs/model.md section 16); `None` for a
    /// prescribed rod, and for a driven rod whose profile is not resolved
    /// (its searches spent their budget; [`RunReport::driven_period`] is
    /// then given).
    pub drive: Option<DriveProfile>,
    /// A driven rod's steady period, segment by segment (the one
    /// [`RunReport::drive`] describes); `None` for a prescribed rod.
    pub driven_period: Option<Vec<Segment>>,
    /// What a spring against the slider reads over the steady orbit
    /// (docs/model.md section 17); `None` without a spring.
    pub spring: Option<SpringReading>,
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
    pub fn value(&self, indicator: Indicator) -> Option<f64> {
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
    pub fn error(&self, indicator: Indicator) -> Option<f64> {
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
    /// For a run-away proven without simulating the start-up: the map
    /// evaluations of the covering that proved it (no fixed point between
    /// rest and the rod's extreme velocity, beyond which the slider only
    /// gains speed; docs/model.md section 3, "The certificate"). `None`
    /// when the start-up from rest decided.
    pub certificate_evaluations: Option<u64>,
    /// Set-up of signal and engine.
    pub setup_time: Duration,
    /// The analysis.
    pub simulation_time: Duration,
    /// Everything the run computed.
    pub wall_time: Duration,
    /// A slider against a spring whose motion did not lock into an orbit:
    /// the spring's reading over the last periods simulated.
    pub spring: Option<SpringReading>,
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

    /// An indicator's value ([`RunReport::value`]); `None` (null in
    /// JSON, empty in CSV) without a steady state.
    pub fn value(&self, indicator: Indicator) -> Option<f64> {
        self.report().and_then(|r| r.value(indicator))
    }

    /// Periods of the start-up from rest simulated.
    pub fn periods_simulated(&self) -> u64 {
        match self {
            Outcome::Steady(r) => r.transient.as_ref().map_or(0, Transient::periods),
            _ => self.unsettled().map_or(0, |u| u.periods_simulated),
        }
    }

    /// The time the run took.
    pub fn times(&self) -> RunTimes {
        let (setup, simulation, wall) = match self {
            Outcome::Steady(r) => (r.setup_time, r.simulation_time, r.wall_time),
            Outcome::RunAway { state, .. } | Outcome::NotConverged(state) => {
                (state.setup_time, state.simulation_time, state.wall_time)
            }
        };
        RunTimes {
            setup,
            simulation,
            wall,
        }
    }

    /// The steady-state report, or the outcome as an error for callers
    /// that need a steady state (figures, stability checks).
    pub fn into_report(self) -> Result<RunReport, Error> {
        let error = match self {
            Outcome::Steady(r) => return Ok(*r),
            Outcome::RunAway { direction, state } => SimulationError::NoSteadyState {
                direction: match direction {
                    Direction::Forward => "growing",
                    Direction::Backward => "falling",
                },
                velocity: state.final_velocity,
                periods: state.periods_simulated,
            },
            Outcome::NotConverged(state) => SimulationError::NotConverged {
                periods: state.periods_simulated,
                last_v_p: state.last_v_p.unwrap_or(0.0),
            },
        };
        Err(error.into())
    }
}
