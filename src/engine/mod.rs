//! Engines walk the slider through time (docs/model.md section 1).
//!
//! * `event.rs`: the exact event-driven engine ([`EventEngine`]). It
//!   finds every stick/slip transition and every zero of the relative
//!   velocity by root finding on the analytic signal and moves the slider
//!   in closed form between them.
//! * `fixed_step/`: the fixed-step reference, first-order Moreau-Jean
//!   ([`FixedStepEngine`]), for a prescribed rod and, in `driven.rs` and
//!   `rod.rs`, for a rod driven by a voltage.
//! * `contact.rs`: the friction law both share: the band of `a_R`, the mode
//!   a relative velocity leads to, the event a change of mode is, and the
//!   segment handed to observers. Each engine only finds *when* a change
//!   happens.
//! * `observer.rs`: what an engine hands its observers, and the period end
//!   it reports.
//!
//! The shared vocabulary lives here: the slider's [`Mode`], typed
//! [`Event`]s, the exact [`Segment`]s handed to observers, and the work
//! counters every run returns.

use crate::error::SimulationError;
use crate::signal::Signal;
pub use driven::{
    DriveProfile, DrivenEngine, DrivenState, ProfileBounds, SliderState, SpringProfile,
};
pub use event::{EventEngine, EventOptions};
pub use fixed_step::{FixedStepEngine, FixedStepOptions};
pub use observer::{Observer, PeriodEnd};

pub(crate) mod contact;
pub(crate) mod driven;
pub(crate) mod event;
pub(crate) mod fixed_step;
pub(crate) mod observer;

/// Direction of sliding, seen from the slider: `Forward` while the rod is
/// faster (`v_R > v_S`, friction pushes the slider forward).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// `v_R > v_S`: slider acceleration `+a_d + g_t`.
    Forward,
    /// `v_R < v_S`: slider acceleration `-a_d + g_t`.
    Backward,
}

impl Direction {
    /// +1 for forward, -1 for backward.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Forward => 1.0,
            Direction::Backward => -1.0,
        }
    }

    /// The other direction.
    pub fn reversed(self) -> Self {
        match self {
            Direction::Forward => Direction::Backward,
            Direction::Backward => Direction::Forward,
        }
    }
}

/// The slider's mode (docs/model.md section 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Mode {
    /// `v_S = v_R`, the slider follows the rod.
    Stick,
    /// Sliding with constant acceleration in the given direction.
    Slip(Direction),
}

impl Mode {
    /// Short name for reports: `stick`, `slip_forward`, `slip_backward`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Stick => "stick",
            Mode::Slip(Direction::Forward) => "slip_forward",
            Mode::Slip(Direction::Backward) => "slip_backward",
        }
    }
}

/// What happened at an event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EventKind {
    /// `a_R` left the stick band `[a_0^-, a_0^+]`.
    StickToSlip {
        /// Direction of the new slip.
        to: Direction,
    },
    /// `v_rel` crossed zero with `a_R` inside the stick band.
    SlipToStick,
    /// `v_rel` crossed zero with `a_R` outside the band: slip the other way.
    Reversal {
        /// Direction of the new slip.
        to: Direction,
    },
    /// `v_rel` touched zero without changing sign (a tangency, at a critical
    /// point of `v_rel`).
    Grazing {
        /// The mode after the touch (`Stick` unless `mu_d = mu_0`).
        then: Mode,
    },
    /// The slider met the free end of a spring (`[spring] tied = false`,
    /// docs/model.md section 17): the spring's compression rose from zero.
    ContactStart,
    /// The slider left the free end of the spring: its compression fell
    /// back to zero.
    ContactEnd,
    /// The rod position and velocity jumped (ideal signals).
    Jump {
        /// Rod position change (m).
        dx: f64,
        /// Rod velocity change (m/s).
        dv: f64,
        /// The mode after the jump.
        then: Mode,
    },
}

impl EventKind {
    /// Stable name in reports and logs (docs/interface.md): `stick_to_slip`,
    /// `slip_to_stick`, `reversal`, `grazing`, `jump`, `contact_start`,
    /// `contact_end`; the same names as the keys of the event counts.
    pub fn name(&self) -> &'static str {
        match self {
            EventKind::StickToSlip { .. } => "stick_to_slip",
            EventKind::SlipToStick => "slip_to_stick",
            EventKind::Reversal { .. } => "reversal",
            EventKind::Grazing { .. } => "grazing",
            EventKind::Jump { .. } => "jump",
            EventKind::ContactStart => "contact_start",
            EventKind::ContactEnd => "contact_end",
        }
    }

    /// True for the events of a spring's free end, which change what acts
    /// on the slider but not its friction mode.
    pub fn is_contact(&self) -> bool {
        matches!(self, EventKind::ContactStart | EventKind::ContactEnd)
    }
}

/// An event at time `(period - 1) T + phase`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// Period index, 1-based.
    pub period: u64,
    /// Phase within the period, in `[0, T)` (s).
    pub phase: f64,
    /// What happened.
    pub kind: EventKind,
}

/// Events counted by kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EventCounts {
    /// Stick to slip transitions.
    pub stick_to_slip: u64,
    /// Slip to stick transitions.
    pub slip_to_stick: u64,
    /// Slip reversals.
    pub reversal: u64,
    /// Tangential touches of `v_rel = 0`.
    pub grazing: u64,
    /// Rod jumps.
    pub jump: u64,
    /// The slider met a spring's free end.
    pub contact_start: u64,
    /// The slider left a spring's free end.
    pub contact_end: u64,
}

impl EventCounts {
    /// Counts one event.
    pub fn add(&mut self, kind: &EventKind) {
        match kind {
            EventKind::StickToSlip { .. } => self.stick_to_slip += 1,
            EventKind::SlipToStick => self.slip_to_stick += 1,
            EventKind::Reversal { .. } => self.reversal += 1,
            EventKind::Grazing { .. } => self.grazing += 1,
            EventKind::Jump { .. } => self.jump += 1,
            EventKind::ContactStart => self.contact_start += 1,
            EventKind::ContactEnd => self.contact_end += 1,
        }
    }

    /// All events.
    pub fn total(&self) -> u64 {
        self.stick_to_slip
            + self.slip_to_stick
            + self.reversal
            + self.grazing
            + self.jump
            + self.contact_start
            + self.contact_end
    }

    /// Sum of two counts.
    pub fn merged(&self, other: &EventCounts) -> EventCounts {
        EventCounts {
            stick_to_slip: self.stick_to_slip + other.stick_to_slip,
            slip_to_stick: self.slip_to_stick + other.slip_to_stick,
            reversal: self.reversal + other.reversal,
            grazing: self.grazing + other.grazing,
            jump: self.jump + other.jump,
            contact_start: self.contact_start + other.contact_start,
            contact_end: self.contact_end + other.contact_end,
        }
    }
}

/// Position and velocity of a body (m, m/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Kinematics {
    /// Position (m).
    pub x: f64,
    /// Velocity (m/s).
    pub v: f64,
}

/// A piece of the motion with one mode and no event inside, known exactly:
/// in slip the slider's acceleration is constant, in stick it moves with
/// the rod. Slider positions are relative to the slider's position at the
/// start of the period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Period index, 1-based.
    pub period: u64,
    /// Start phase (s).
    pub start: f64,
    /// End phase (s), `>= start`.
    pub end: f64,
    /// Mode throughout.
    pub mode: Mode,
    /// Slider at the start.
    pub slider_start: Kinematics,
    /// Slider at the end.
    pub slider_end: Kinematics,
    /// Rod at the start (right limit).
    pub rod_start: Kinematics,
    /// Rod at the end (left limit).
    pub rod_end: Kinematics,
    /// Slider acceleration in slip (m/s^2); unused in stick.
    pub slip_acceleration: f64,
    /// The slider's position from its start at the start of the period
    /// (m), where the engine follows it (a spring against the slider); 0
    /// elsewhere.
    pub slider_origin: f64,
}

impl Segment {
    /// Duration (s).
    pub fn duration(&self) -> f64 {
        self.end - self.start
    }

    /// `integral |v_R - v_S| dt` over the segment, exact: `v_rel` keeps its
    /// sign on a segment, so the integral is `|delta(x_R - x_S)|`; zero in
    /// stick.
    pub fn sliding_distance(&self) -> f64 {
        match self.mode {
            Mode::Stick => 0.0,
            Mode::Slip(_) => ((self.rod_end.x - self.slider_end.x)
                - (self.rod_start.x - self.slider_start.x))
                .abs(),
        }
    }
}

/// Work counters of a run: what the result cost.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WorkCounters {
    /// Events by kind.
    pub events: EventCounts,
    /// Periods simulated (transient, period-map evaluations and the
    /// steady-state period together).
    pub periods: u64,
    /// Evaluations of the rod signal in root finding.
    pub evaluations: u64,
    /// Root-finder iterations.
    pub root_iterations: u64,
}

impl WorkCounters {
    /// Sum of two counters.
    pub fn merged(&self, other: &WorkCounters) -> WorkCounters {
        WorkCounters {
            events: self.events.merged(&other.events),
            periods: self.periods + other.periods,
            evaluations: self.evaluations + other.evaluations,
            root_iterations: self.root_iterations + other.root_iterations,
        }
    }
}

/// How a slider starts a period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeriodStart {
    /// Slider velocity at the period start, before a rod jump at phase 0.
    pub velocity: f64,
    /// The mode the previous period ended in; `None` for the first period
    /// or a period-map evaluation, where the mode follows from `velocity`.
    pub mode: Option<Mode>,
}

/// An engine that advances the slider by whole periods: the event engine
/// or the fixed-step reference. The steady-state and start-up analysis
/// ([`crate::analysis`]) works with any of them.
pub trait PeriodEngine {
    /// The rod signal.
    fn signal(&self) -> &Signal;

    /// Simulates one period from `start`, handing segments, events and the
    /// period end to `observer`. `period` is 1-based; period 1 starts from
    /// rest at `x_R = 0`.
    fn run_period<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError>;

    /// Work done so far.
    fn counters(&self) -> WorkCounters;

    /// Below this `|v_rel|` (m/s) counts as zero.
    fn zero_velocity_tolerance(&self) -> f64;

    /// A bound on the slider velocity error the last simulated period
    /// introduced through the engine's tolerances (m/s), when the engine
    /// can state one; infinite when the period held a decision no bound
    /// survives (a grazing).
    fn last_velocity_uncertainty(&self) -> Option<f64> {
        None
    }

    /// A bound on how far the engine may place an event from its true time
    /// (s): the step of a fixed-step engine, a few ulps of the period for
    /// the event engine.
    fn event_time_uncertainty(&self) -> f64 {
        4.0 * f64::EPSILON * self.signal().period()
    }

    /// True if the engine's period map may have whole bands of fixed points
    /// (a fixed-step map in slip-slip changes `v` by whole steps' worth of
    /// acceleration, so its derivative is exactly 1): then the steady state
    /// is the one the start-up from rest reaches, and the analysis runs the
    /// start-up to convergence first and seeds the fixed point with it.
    fn steady_state_from_transient(&self) -> bool {
        false
    }

    /// True if the engine's state at a period boundary holds more than the
    /// slider's velocity: a driven rod (docs/model.md section 16) carries
    /// its own position and velocity from period to period. Such an engine
    /// continues, in `run_period`, from the state its previous period
    /// ended in (period 1 starts from rest), so the period map is not a
    /// function of the slider velocity: the motion from rest decides the
    /// steady state, and no search evaluates the map from a chosen
    /// velocity. It cuts its stick segments at the zeros of the rod's
    /// own acceleration, so that a stuck slider's velocity extrema are
    /// segment ends.
    fn carries_rod_state(&self) -> bool {
        false
    }

    /// For an engine with a driven rod: the rod's deviation from its
    /// signal, and the voltage and current over the period whose
    /// `segments` (in order, covering it) are given; `None` otherwise.
    fn drive_profile(&self, _segments: &[Segment]) -> Option<DriveProfile> {
        None
    }

    /// For an engine whose period map acts on a driven rod's boundary
    /// state and that can start a period from any such state: the state
    /// the last period ended in; `None` otherwise (and before the first
    /// period).
    fn boundary_state(&self) -> Option<DrivenState> {
        None
    }

    /// For an engine with a spring against the slider: what the spring
    /// reads over the `periods` periods whose segments and events (in
    /// order) are given, starting from `start`; `None` otherwise.
    fn spring_profile(
        &self,
        _start: &DrivenState,
        _recorded: (&[Segment], &[Event]),
        _periods: u64,
    ) -> Option<SpringProfile> {
        None
    }

    /// Sets the state the next period (any but period 1 without a mode)
    /// starts from, for an engine with [`PeriodEngine::boundary_state`];
    /// false (and nothing set) for any other.
    fn restart_from(&mut self, _state: DrivenState) -> bool {
        false
    }
}

/// Hands the event `at` to `observer` and counts it, in the run's counters
/// and in its period's `(count, limit)`: more events than the limit in one
/// period stop the run ([`SimulationError::TooManyEvents`], chattering).
pub(crate) fn emit_event<O: Observer>(
    counters: &mut WorkCounters,
    (count, limit): (&mut u64, u64),
    at: Event,
    observer: &mut O,
) -> Result<(), SimulationError> {
    *count += 1;
    counters.events.add(&at.kind);
    if *count > limit {
        return Err(SimulationError::TooManyEvents {
            limit,
            period: at.period,
            phase: at.phase,
        });
    }
    observer.event(&at);
    Ok(())
}
