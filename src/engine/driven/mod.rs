//! The exact engine for a driven rod (docs/model.md section 16): every
//! mode is a linear system with harmonic forcing, solved in closed form
//! between events, and every event is a certified zero of an
//! exponential-trigonometric function.
//!
//! ## Modes
//! In a mode the rod obeys `M_m x'' + d x' + c x = alpha u(t) + F_m`
//! ([`crate::actuator`]): its motion is the mode's periodic particular
//! solution `x_p(tau)` plus the free damped oscillation `h(s)` of the
//! mode, `h'' + 2 sigma h' + omega_0^2 h = 0`, started at the segment
//! start `s = 0` with the rod's state minus the particular solution's. The
//! slider moves with constant acceleration in slip and with the rod in
//! stick. So between events
//!
//! ```text
//! slip:  v_rel(s)    = x_p'(tau_0 + s) + h'(s) - v_S0 - a_s s
//! stick: a_st(s)     = x_p''(tau_0 + s) + h''(s)      (the stuck system's a_R)
//! ```
//!
//! are exponential-trigonometric functions of `s`
//! ([`crate::numerics::ExpTrig`]), whose derivatives are bounded, so the
//! certified subdivision finds their first zero with none missed.
//!
//! ## Events
//! * **Stick -> slip**: the first time `a_st` leaves the band
//!   `[a_0^-, a_0^+]` (a zero of `a_st - a_0^+` where it rises or of
//!   `a_st - a_0^-` where it falls); a tangency from inside keeps the
//!   slider stuck (the band is closed).
//! * **Slip -> stick, reversal**: the first zero of `v_rel`; the stuck
//!   system's `a_st` there decides (docs/model.md section 1 with `a_R`
//!   replaced by `a_st`, see [`crate::actuator`]). At a band edge within
//!   rounding, the sign of `a_st'` (then `a_st''`) says on which side it
//!   goes on.
//! * **Grazing**: a local extremum of `v_rel` within the zero-velocity
//!   tolerance `tol_v` of zero, as in the prescribed engine.
//!
//! ## State across periods
//! The rod carries its position and velocity from period to period
//! ([`PeriodEngine::carries_rod_state`]): `run_period(1, ..)` without a
//! mode starts everything from rest at `x_R = 0`, every other call goes on
//! from where the last period ended. Time is `(period, phase)`; the
//! particular solutions are periodic, and the free oscillation is
//! restarted at every event and period start from the rod's state, so
//! precision does not decay over long runs.
//!
//! Without the reaction and with the real actuator as designed, the
//! particular solution is the scene's signal and the free oscillation
//! vanishes: the rod follows the signal and the run equals the prescribed
//! rod's (`tests/driven_rod.rs`).

mod profile;
mod segment;

pub use profile::DriveProfile;

use super::contact::{Band, Contact, transition};
use super::{
    Direction, Event, EventKind, Kinematics, Mode, Observer, PeriodEnd, PeriodEngine, PeriodStart,
    Segment, WorkCounters,
};
use crate::actuator::{DrivenRod, Load};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::signal::{RodState, Signal};
use segment::{ModeFunctions, StickExit};

/// The rod's and the slider's state at a period boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenState {
    /// Rod position (m).
    pub rod_x: f64,
    /// Rod velocity (m/s).
    pub rod_v: f64,
    /// Slider velocity (m/s).
    pub slider_v: f64,
    /// The mode the period ended in.
    pub mode: Mode,
}

/// The exact engine for a rod driven through the actuator.
#[derive(Debug, Clone)]
pub struct DrivenEngine<'s> {
    signal: &'s Signal,
    rod: &'s DrivenRod,
    period: f64,
    contact: Contact,
    /// The three modes' functions: forward slip, backward slip, stick.
    modes: [ModeFunctions; 3],
    /// Where the last period ended; `None` before the first.
    state: Option<DrivenState>,
    max_events: u64,
    counters: WorkCounters,
    last_uncertainty: f64,
    /// The largest bound on an event time's error in the last period (s).
    last_time_error: f64,
}

/// The closed forms of `mode` among the three modes'.
fn functions_of(modes: &[ModeFunctions; 3], mode: Mode) -> &ModeFunctions {
    match load_of(mode) {
        Load::SlipForward => &modes[0],
        Load::SlipBackward => &modes[1],
        Load::Stuck => &modes[2],
    }
}

/// The load a mode puts on the rod.
fn load_of(mode: Mode) -> Load {
    match mode {
        Mode::Stick => Load::Stuck,
        Mode::Slip(Direction::Forward) => Load::SlipForward,
        Mode::Slip(Direction::Backward) => Load::SlipBackward,
    }
}

impl<'s> DrivenEngine<'s> {
    /// The engine for `rod` under `motor`; `signal` is the signal the
    /// voltage was designed for (its scales set the tolerances, and it is
    /// what observers see as the rod's signal).
    pub fn new(
        signal: &'s Signal,
        rod: &'s DrivenRod,
        motor: &Motor,
        velocity_tolerance: f64,
        max_events_per_period: u64,
    ) -> Self {
        let v_scale = signal.velocity_scale().max(f64::MIN_POSITIVE);
        let period = signal.period();
        let modes = [Load::SlipForward, Load::SlipBackward, Load::Stuck]
            .map(|load| ModeFunctions::new(rod.response(load)));
        Self {
            signal,
            rod,
            period,
            contact: Contact::new(motor, velocity_tolerance * v_scale),
            modes,
            state: None,
            max_events: max_events_per_period,
            counters: WorkCounters::default(),
            last_uncertainty: 0.0,
            last_time_error: 4.0 * f64::EPSILON * period,
        }
    }

    /// The state the last period ended in (`None` before the first).
    pub fn state(&self) -> Option<DrivenState> {
        self.state
    }

    /// The rod at phase `tau` (s) inside `segment`, a segment of this
    /// rod's motion as observers get it: the closed form of the segment's
    /// mode (the particular solution plus the free oscillation started
    /// from `segment.rod_start` at `segment.start`). Not the signal: the
    /// rod strays from it. `tau` is held to the segment (a NaN to its
    /// start), so the result is always a state of the segment.
    pub fn rod_in_segment(&self, segment: &Segment, tau: f64) -> Kinematics {
        let span = segment.duration().max(0.0);
        let s = (tau - segment.start).clamp(0.0, span);
        let s = if s.is_nan() { 0.0 } else { s };
        self.functions(segment.mode)
            .rod_at(segment.start, segment.rod_start, s)
    }

    fn functions(&self, mode: Mode) -> &ModeFunctions {
        functions_of(&self.modes, mode)
    }

    /// The band the stuck system's acceleration lies in at phase `tau` for
    /// the rod state `(x, v)`, and where it goes on right after `tau` when
    /// it sits on an edge within rounding.
    fn band_after(&self, tau: f64, x: f64, v: f64) -> Band {
        let stick = self.functions(Mode::Stick);
        let (plus, minus) = (self.contact.a_plus, self.contact.a_minus);
        let [f, upper, lower] = stick.band_functions(tau, x, v, [0.0, plus, minus]);
        let [a, da, dda] = f.eval(0.0);
        let [_, eta1, _] = f.eval_error_bound(0.0);
        // On an edge within the stick search's own tolerance, the direction
        // decides (segment::band_tolerance).
        let span = self.period - tau;
        let eta = segment::band_tolerance(&upper, &lower, span);
        // Which way a value at an edge moves: the first derivative that is
        // clearly nonzero.
        let rising = || da > eta1 || (da.abs() <= eta1 && dda > 0.0);
        let falling = || da < -eta1 || (da.abs() <= eta1 && dda < 0.0);
        if (a - plus).abs() <= eta {
            if rising() { Band::Above } else { Band::Inside }
        } else if (a - minus).abs() <= eta {
            if falling() { Band::Below } else { Band::Inside }
        } else {
            self.contact.band(a)
        }
    }

    fn mode_for(&self, v_rel: f64, tau: f64, x: f64, v: f64) -> Mode {
        self.contact.mode(v_rel, || self.band_after(tau, x, v))
    }

    fn run_period_impl<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        let from_rest = period == 1 && start.mode.is_none() || self.state.is_none();
        let boundary = if from_rest {
            DrivenState {
                rod_x: 0.0,
                rod_v: 0.0,
                slider_v: 0.0,
                mode: Mode::Stick,
            }
        } else {
            self.state.expect("a period before")
        };
        let mut walk = Walk {
            period,
            tau: 0.0,
            rod: Kinematics {
                x: boundary.rod_x,
                v: boundary.rod_v,
            },
            x: 0.0,
            v: boundary.slider_v,
            uncertainty: 0.0,
            time_error: 4.0 * f64::EPSILON * self.period,
            events: 0,
            mode: Mode::Stick,
            departure: false,
        };
        let v_rel = if !from_rest && boundary.mode == Mode::Stick {
            0.0
        } else {
            walk.rod.v - walk.v
        };
        walk.mode = self.mode_for(v_rel, 0.0, walk.rod.x, walk.rod.v);
        walk.departure = self.contact.at_rest(v_rel);
        if walk.mode == Mode::Stick {
            walk.v = walk.rod.v;
        }
        if !from_rest && let Some(kind) = transition(boundary.mode, walk.mode, false) {
            self.emit(&mut walk, kind, observer)?;
        }
        while walk.tau < self.period {
            match walk.mode {
                Mode::Stick => self.stick(&mut walk, observer)?,
                Mode::Slip(dir) => self.slip(&mut walk, dir, observer)?,
            }
        }
        self.counters.periods += 1;
        self.last_uncertainty = walk.uncertainty;
        self.last_time_error = walk.time_error;
        self.state = Some(DrivenState {
            rod_x: walk.rod.x,
            rod_v: walk.rod.v,
            slider_v: walk.v,
            mode: walk.mode,
        });
        let end = PeriodEnd {
            period,
            step: walk.x,
            velocity: walk.v,
            mode: walk.mode,
            // The slider's velocity alone does not fix the next period (the
            // rod's state does too): no derivative of a one-dimensional map.
            map_derivative: 1.0,
        };
        observer.period_end(&end);
        Ok(end)
    }

    /// A stuck slider moves with the rod until the stuck system's
    /// acceleration leaves the band or the period ends.
    fn stick<O: Observer>(
        &mut self,
        walk: &mut Walk,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let functions = functions_of(&self.modes, Mode::Stick);
        let span = self.period - walk.tau;
        let exit = functions.stick_exit(
            walk.tau,
            walk.rod,
            span,
            [self.contact.a_minus, self.contact.a_plus],
            &mut self.counters,
        );
        let s_end = match exit {
            StickExit::PeriodEnd => span,
            StickExit::Leaves { s, .. } => s,
        };
        let end_tau = if s_end >= span {
            self.period
        } else {
            walk.tau + s_end
        };
        // Observers get the stick phase cut at the zeros of the rod's
        // acceleration, so that the slider's velocity extrema are segment
        // ends (the contract of `carries_rod_state`).
        let cuts = if observer.wants_segments() {
            functions.acceleration_zeros(walk.tau, walk.rod, s_end)
        } else {
            Vec::new()
        };
        let (tau0, rod0) = (walk.tau, walk.rod);
        for s in cuts.into_iter().chain([s_end]) {
            let rod_end = functions.rod_at(tau0, rod0, s);
            let end = if s == s_end { end_tau } else { tau0 + s };
            if observer.wants_segments() && end > walk.tau {
                let slider = [
                    Kinematics {
                        x: walk.x,
                        v: walk.rod.v,
                    },
                    Kinematics {
                        x: walk.x + (rod_end.x - walk.rod.x),
                        v: rod_end.v,
                    },
                ];
                let segment = self.segment(walk, end, Mode::Stick, slider, rod_end);
                observer.segment(&segment, self.signal);
            }
            walk.x += rod_end.x - walk.rod.x;
            walk.v = rod_end.v;
            walk.rod = rod_end;
            walk.tau = end;
        }
        if let StickExit::Leaves { to, .. } = exit {
            walk.mode = Mode::Slip(to);
            walk.departure = true;
            self.emit(walk, EventKind::StickToSlip { to }, observer)?;
        }
        Ok(())
    }

    /// A sliding slider moves with constant acceleration until `v_rel`
    /// reaches zero or the period ends.
    fn slip<O: Observer>(
        &mut self,
        walk: &mut Walk,
        dir: Direction,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let a_s = self.contact.slip_acceleration(dir);
        let functions = functions_of(&self.modes, Mode::Slip(dir));
        let span = self.period - walk.tau;
        let zero = functions.slip_zero(
            walk.tau,
            walk.rod,
            (walk.v, a_s),
            span,
            self.contact.tol_v,
            (dir, walk.departure),
            &mut self.counters,
        );
        let (s_end, grazing) = match zero {
            Some(z) => (z.s, z.tangency),
            None => (span, false),
        };
        let rod_end = functions.rod_at(walk.tau, walk.rod, s_end);
        let end_tau = if zero.is_none() {
            self.period
        } else {
            walk.tau + s_end
        };
        let x1 = walk.x + walk.v * s_end + 0.5 * a_s * s_end * s_end;
        let v1 = walk.v + a_s * s_end;
        if end_tau > walk.tau && observer.wants_slip_segments() {
            let slider = [
                Kinematics {
                    x: walk.x,
                    v: walk.v,
                },
                Kinematics { x: x1, v: v1 },
            ];
            let segment = self.segment(walk, end_tau, walk.mode, slider, rod_end);
            observer.segment(&segment, self.signal);
        }
        walk.x = x1;
        walk.v = v1;
        walk.rod = rod_end;
        walk.tau = end_tau;
        walk.departure = false;
        if let Some(z) = zero {
            self.zero_of_v_rel(walk, grazing, z.time_error, observer)?;
        }
        Ok(())
    }

    /// A zero of `v_rel` ends a slip: the stuck system's acceleration
    /// decides what follows.
    fn zero_of_v_rel<O: Observer>(
        &mut self,
        walk: &mut Walk,
        grazing: bool,
        time_error: f64,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let old = walk.mode;
        let mode = self.mode_for(0.0, walk.tau, walk.rod.x, walk.rod.v);
        walk.mode = mode;
        let a_st = self
            .rod
            .acceleration(Load::Stuck, walk.tau, walk.rod.x, walk.rod.v);
        let a_old = self.contact.acceleration(old, a_st);
        let a_new = self.contact.acceleration(mode, a_st);
        walk.uncertainty += (a_old - a_new).abs() * time_error;
        walk.time_error = walk.time_error.max(time_error);
        match mode {
            Mode::Stick => {
                walk.uncertainty += (walk.rod.v - walk.v).abs();
                walk.v = walk.rod.v;
            }
            Mode::Slip(_) => walk.departure = true,
        }
        if grazing {
            walk.uncertainty = f64::INFINITY;
        }
        let kind = transition(old, mode, grazing).unwrap_or(EventKind::Grazing { then: mode });
        self.emit(walk, kind, observer)
    }

    fn segment(
        &self,
        walk: &Walk,
        end: f64,
        mode: Mode,
        slider: [Kinematics; 2],
        rod_end: Kinematics,
    ) -> Segment {
        let state = |k: Kinematics| RodState {
            x: k.x,
            v: k.v,
            a: 0.0,
        };
        self.contact.segment(
            walk.period,
            [walk.tau, end],
            mode,
            slider,
            [state(walk.rod), state(rod_end)],
        )
    }

    fn emit<O: Observer>(
        &mut self,
        walk: &mut Walk,
        kind: EventKind,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let at = Event {
            period: walk.period,
            phase: walk.tau,
            kind,
        };
        super::emit_event(
            &mut self.counters,
            (&mut walk.events, self.max_events),
            at,
            observer,
        )
    }
}

/// Mutable state of the walk through one period.
struct Walk {
    period: u64,
    tau: f64,
    /// The rod's state at `tau`.
    rod: Kinematics,
    /// Slider position relative to the period start (m).
    x: f64,
    /// Slider velocity (m/s).
    v: f64,
    uncertainty: f64,
    /// The largest bound on an event time's error in the period (s).
    time_error: f64,
    events: u64,
    mode: Mode,
    /// `v_rel = 0` at `tau` and the slip leaves zero: not an event again.
    departure: bool,
}

impl PeriodEngine for DrivenEngine<'_> {
    fn signal(&self) -> &Signal {
        self.signal
    }

    fn run_period<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        self.run_period_impl(period, start, observer)
    }

    fn counters(&self) -> WorkCounters {
        self.counters
    }

    fn zero_velocity_tolerance(&self) -> f64 {
        self.contact.tol_v
    }

    fn last_velocity_uncertainty(&self) -> Option<f64> {
        Some(self.last_uncertainty)
    }

    /// The largest event-time bound of the last period: the solver's
    /// tolerance plus `eta / |v_rel'|` at each zero of `v_rel`.
    fn event_time_uncertainty(&self) -> f64 {
        self.last_time_error
    }

    fn carries_rod_state(&self) -> bool {
        true
    }

    fn drive_profile(&self, segments: &[Segment]) -> Option<DriveProfile> {
        let Signal::Fourier(signal) = self.signal else {
            return None;
        };
        Some(profile::profile(segments, self.rod, signal, |mode| {
            self.functions(mode)
        }))
    }
}
