//! The steady period as the sensitivities see it: the pieces of constant
//! mode between events, each with what ended it (docs/model.md section
//! 14.2). Recorded by an [`Observer`] on one period of the periodic orbit,
//! the same period [`crate::analysis::steady_state_at`] observes (its
//! event times agree with the run's to the engine's tolerance).

use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{
    Direction, Event, EventKind, Mode, Observer, PeriodEngine, PeriodStart, Segment,
};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::signal::Signal;

/// What ended a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum End {
    /// The period ended (phase `T`).
    Period,
    /// A rod jump (ideal signals).
    Jump,
    /// A transversal zero of `v_rel` in slip, followed by this mode (stick,
    /// or slip the other way: a reversal).
    Crossing(Mode),
    /// A tangential zero of `v_rel` in slip, followed by this mode.
    Grazing(Mode),
    /// A stuck slider's `a_R` left the band in this direction.
    BandExit(Direction),
}

/// A piece of constant mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Piece {
    /// Start phase (s).
    pub start: f64,
    /// End phase (s).
    pub end: f64,
    /// Mode throughout.
    pub mode: Mode,
    /// Slider velocity at the start (m/s).
    pub v_start: f64,
    /// What ended it.
    pub end_cause: End,
}

/// One period of the periodic orbit.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Orbit {
    /// Period `T` (s).
    pub period: f64,
    /// Slider velocity at the period boundary `v*` (m/s).
    pub boundary_velocity: f64,
    /// The slider is stuck at the period boundary (the previous period
    /// ended in stick): it starts the period with the rod's velocity.
    pub stuck_at_boundary: bool,
    /// Pieces in time order, covering `[0, T]`; zero-length pieces (a stick
    /// that ends at phase 0) are left out.
    pub pieces: Vec<Piece>,
    /// Events in time order, phase 0 included.
    pub events: Vec<Event>,
    /// Step of the period `x_inf` (m).
    pub step: f64,
    /// The engine's `P'(v*)`.
    pub map_derivative: f64,
    /// Slider velocity at the period end, `P(v*)` (m/s).
    pub end_velocity: f64,
}

impl Orbit {
    /// `v_inf = x_inf / T`.
    pub(super) fn v_inf(&self) -> f64 {
        self.step / self.period
    }
}

/// Segments and events in the order the engine hands them over.
#[derive(Debug, Default)]
struct Recorder {
    items: Vec<Item>,
}

#[derive(Debug)]
enum Item {
    Segment(Segment),
    Event(Event),
}

impl Observer for Recorder {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        self.items.push(Item::Segment(*segment));
    }
    fn event(&mut self, event: &Event) {
        self.items.push(Item::Event(*event));
    }
}

/// Records one period of the orbit through the boundary velocity
/// `boundary_velocity` ([`crate::analysis::SteadyState::boundary_velocity`]):
/// one unobserved period gives the mode at the boundary, then the observed
/// period starts from the same velocity in that mode.
pub(super) fn record(
    signal: &Signal,
    motor: &Motor,
    boundary_velocity: f64,
) -> Result<Orbit, SimulationError> {
    let mut engine = EventEngine::new(signal, motor, EventOptions::default());
    let before = engine.run_period(
        2,
        PeriodStart {
            velocity: boundary_velocity,
            mode: None,
        },
        &mut (),
    )?;
    record_period(&mut engine, boundary_velocity, Some(before.mode))
}

/// Records one period of the period map from the slider velocity
/// `velocity` at phase 0 (not a periodic orbit in general: the step and
/// [`Orbit::end_velocity`] are `P`'s), the mode at the start following
/// from it.
pub(super) fn record_map(
    signal: &Signal,
    motor: &Motor,
    velocity: f64,
) -> Result<Orbit, SimulationError> {
    let mut engine = EventEngine::new(signal, motor, EventOptions::default());
    record_period(&mut engine, velocity, None)
}

fn record_period(
    engine: &mut EventEngine,
    velocity: f64,
    mode: Option<Mode>,
) -> Result<Orbit, SimulationError> {
    let signal = engine.signal();
    let mut recorder = Recorder::default();
    let end = engine.run_period(2, PeriodStart { velocity, mode }, &mut recorder)?;
    let boundary_velocity = velocity;
    let period = signal.period();
    let items = recorder.items;
    let mut pieces = Vec::new();
    let mut events = Vec::new();
    for (i, item) in items.iter().enumerate() {
        match item {
            Item::Event(e) => events.push(*e),
            Item::Segment(s) => {
                let next = match items.get(i + 1) {
                    Some(Item::Event(e)) if e.phase == s.end => Some(e.kind),
                    _ => None,
                };
                let end_cause = match next {
                    Some(EventKind::SlipToStick) => End::Crossing(Mode::Stick),
                    Some(EventKind::Reversal { to }) => End::Crossing(Mode::Slip(to)),
                    Some(EventKind::Grazing { then }) => End::Grazing(then),
                    Some(EventKind::StickToSlip { to }) => End::BandExit(to),
                    Some(EventKind::Jump { .. }) => End::Jump,
                    // A spring's free end: not a scene these derivatives
                    // take (a prescribed rod without a spring).
                    Some(EventKind::ContactStart | EventKind::ContactEnd) | None => End::Period,
                };
                pieces.push(Piece {
                    start: s.start,
                    end: s.end,
                    mode: s.mode,
                    v_start: s.slider_start.v,
                    end_cause,
                });
            }
        }
    }
    // Without a mode at the boundary, a start with v_rel = 0 sticks.
    let stuck = mode.map_or_else(
        || {
            pieces
                .first()
                .is_some_and(|p| p.start == 0.0 && p.mode == Mode::Stick)
        },
        |m| m == Mode::Stick,
    );
    Ok(Orbit {
        period,
        boundary_velocity,
        stuck_at_boundary: stuck,
        pieces,
        events,
        step: end.step,
        map_derivative: end.map_derivative,
        end_velocity: end.velocity,
    })
}
