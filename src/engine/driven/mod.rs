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

mod period_engine;
mod profile;
mod segment;
mod slider;
mod spring_profile;
mod state;
mod stuck;

pub use profile::DriveProfile;
pub use spring_profile::{ProfileBounds, SpringProfile};
pub use state::{DrivenState, SliderState};
use state::{Walk, contact_change};

use super::contact::{Band, Contact, transition};
use super::{
    Direction, Event, EventKind, Kinematics, Mode, Observer, PeriodEnd, PeriodStart, Segment,
    WorkCounters,
};
use crate::actuator::{DrivenRod, Load};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::numerics::exp_trig::ExpTrig;
use crate::signal::{RodState, Signal};
use crate::spring::Spring;
use segment::{ModeFunctions, StickExit};
use slider::{SliderMotion, SpringLaw};
use stuck::{StuckOnSpring, stick_functions_of};

/// The exact engine for a rod driven through the actuator.
#[derive(Debug, Clone)]
pub struct DrivenEngine<'s> {
    signal: &'s Signal,
    /// The driven rod; `None`: the rod follows the signal (a prescribed
    /// rod with a spring against the slider).
    rod: Option<&'s DrivenRod>,
    /// The spring against the slider, if any.
    spring: Option<SpringLaw>,
    /// The stick mode with the spring in contact, where the rod feels the
    /// slider (a driven rod with the reaction).
    stuck_on_spring: Option<StuckOnSpring>,
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
        let modes = [Load::SlipForward, Load::SlipBackward, Load::Stuck]
            .map(|load| ModeFunctions::new(rod.response(load)));
        Self::with_modes(
            signal,
            Some(rod),
            modes,
            motor,
            (velocity_tolerance, max_events_per_period),
        )
    }

    /// The engine for a rod that follows `signal` whatever acts on it (the
    /// paper's prescribed rod) in the engine's closed forms, for a slider
    /// against a spring ([`DrivenEngine::with_spring`]). `None` for a
    /// signal that is not a continuous Fourier series.
    pub fn prescribed(
        signal: &'s Signal,
        motor: &Motor,
        velocity_tolerance: f64,
        max_events_per_period: u64,
    ) -> Option<Self> {
        let Signal::Fourier(fourier) = signal else {
            return None;
        };
        let response = crate::actuator::ModeResponse::prescribed(fourier);
        let modes = [0, 1, 2].map(|_| ModeFunctions::new(&response));
        Some(Self::with_modes(
            signal,
            None,
            modes,
            motor,
            (velocity_tolerance, max_events_per_period),
        ))
    }

    /// The engine with `spring` against the slider (docs/model.md section
    /// 17): in slip the slider oscillates on it, beside a driven rod's own
    /// free oscillation (two oscillators in `v_rel`); in stick its force
    /// acts on the stuck system (`stuck.rs`). `None` where the spring's
    /// fields are outside their ranges.
    pub fn with_spring(mut self, spring: Spring, motor: &Motor) -> Option<Self> {
        spring.validate().ok()?;
        self.stuck_on_spring = self
            .rod
            .and_then(|rod| StuckOnSpring::new(rod, &spring, motor));
        self.spring = Some(SpringLaw::new(spring, motor.params().slider_mass));
        Some(self)
    }

    fn with_modes(
        signal: &'s Signal,
        rod: Option<&'s DrivenRod>,
        modes: [ModeFunctions; 3],
        motor: &Motor,
        (velocity_tolerance, max_events_per_period): (f64, u64),
    ) -> Self {
        let v_scale = signal.velocity_scale().max(f64::MIN_POSITIVE);
        let period = signal.period();
        Self {
            signal,
            rod,
            spring: None,
            stuck_on_spring: None,
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
        self.segment_functions(segment, None)
            .rod_at(segment.start, segment.rod_start, s)
    }

    fn functions(&self, mode: Mode) -> &ModeFunctions {
        functions_of(&self.modes, mode)
    }

    /// The band the stuck system's acceleration lies in at phase `tau` for
    /// the rod state `(x, v)`, and where it goes on right after `tau` when
    /// it sits on an edge within its uncertainty.
    ///
    /// The distances from the edges are the values the stick search starts
    /// from ([`ModeFunctions::edge_functions`]), so the two never differ on
    /// which side of an edge a stick phase starts. On an edge the direction
    /// decides (the first derivative that is clearly nonzero); off it the
    /// value does. At a transversal zero of `v_rel` whose time is known to
    /// `time_error`, a value is on an edge within its rounding bound at
    /// `tau` plus `|a_st'| time_error`: beyond that it lies on its side at
    /// the zero, however close (a stick phase that starts inside the band
    /// moving outwards ends where `a_st` reaches the edge:
    /// [`ModeFunctions::stick_exit`]). Elsewhere (`None`: a period start, or
    /// a grazing, whose time is an extremum of `v_rel`, where `a_st` crosses
    /// the edge itself when `a_d = a_0`) it is on an edge within the stick
    /// search's own tolerance ([`segment::band_tolerance`]).
    fn band_after(
        &self,
        tau: f64,
        rod: Kinematics,
        place: (bool, f64),
        time_error: Option<f64>,
    ) -> Band {
        let [upper, lower] = self.edges(tau, rod, place);
        let [du, da, dda] = upper.eval(0.0);
        let dl = lower.eval(0.0)[0];
        let eta1 = upper.eval_error_bound(0.0)[1];
        let [on_upper, on_lower] = match time_error {
            Some(dt) => [&upper, &lower].map(|f| f.eval_error_bound(0.0)[0] + da.abs() * dt),
            None => [segment::band_tolerance(&upper, &lower, self.period - tau); 2],
        };
        let rising = da > eta1 || (da.abs() <= eta1 && dda > 0.0);
        let falling = da < -eta1 || (da.abs() <= eta1 && dda < 0.0);
        if du.abs() <= on_upper {
            if rising { Band::Above } else { Band::Inside }
        } else if dl.abs() <= on_lower {
            if falling { Band::Below } else { Band::Inside }
        } else if du > 0.0 {
            Band::Above
        } else if dl < 0.0 {
            Band::Below
        } else {
            Band::Inside
        }
    }

    /// `[a_st - a_0^+, a_st - a_0^-]` over a stick from `tau` with the rod
    /// at `rod` and the slider at `place` = (in contact, `x_S - x_R`): the
    /// stuck system's acceleration, with a spring's force over `m_s` added
    /// (`slider.rs`).
    fn edges(&self, tau: f64, rod: Kinematics, place: (bool, f64)) -> [ExpTrig; 2] {
        self.edges_of(&self.stick_functions(place), tau, rod, place)
    }

    /// [`Self::edges`] from the stick mode's functions at `place`, built
    /// by the caller.
    fn edges_of(
        &self,
        stick: &ModeFunctions,
        tau: f64,
        rod: Kinematics,
        place: (bool, f64),
    ) -> [ExpTrig; 2] {
        let band = [self.contact.a_plus, self.contact.a_minus];
        match &self.spring {
            Some(law) => law.stuck_functions(stick, tau, rod, place, band),
            None => stick.edge_functions(tau, rod.x, rod.v, [band[1], band[0]]),
        }
    }

    /// The stuck system's acceleration at the walk's time, with a spring's
    /// force over `m_s` added: from the driven rod's equation of motion
    /// where there is no spring (one evaluation), else from the spring's
    /// band function.
    fn stuck_acceleration(&self, walk: &Walk) -> f64 {
        match (&self.spring, self.rod) {
            (None, Some(rod)) => rod.acceleration(Load::Stuck, walk.tau, walk.rod.x, walk.rod.v),
            _ => self.edges(walk.tau, walk.rod, walk.place())[0].eval(0.0)[0] + self.contact.a_plus,
        }
    }

    /// The mode of a slider with relative velocity `v_rel` at `tau` with
    /// the rod at `rod` and the slider at `place` ([`Self::edges`]);
    /// `time_error`: see [`Self::band_after`].
    fn mode_for(
        &self,
        v_rel: f64,
        tau: f64,
        rod: Kinematics,
        place: (bool, f64),
        time_error: Option<f64>,
    ) -> Mode {
        self.contact
            .mode(v_rel, || self.band_after(tau, rod, place, time_error))
    }

    fn run_period_impl<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        let from_rest = period == 1 && start.mode.is_none() || self.state.is_none();
        let boundary = if from_rest {
            // A rod that follows its signal starts where the signal does.
            let stick = self.functions(Mode::Stick);
            let rod = if stick.has_free() {
                Kinematics { x: 0.0, v: 0.0 }
            } else {
                let p = stick.particular().state(0.0);
                Kinematics { x: p.x, v: p.v }
            };
            DrivenState {
                rod_x: rod.x,
                rod_v: rod.v,
                slider_v: rod.v,
                mode: Mode::Stick,
                slider: self.spring.map(|law| SliderState {
                    x: 0.0,
                    contact: law.spring.in_contact(0.0),
                }),
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
            x_start: boundary.slider.map_or(0.0, |p| p.x),
            contact: boundary.slider.is_some_and(|p| p.contact),
            // A free end met exactly at the start (a gap of 0 from rest)
            // is left or pressed from there on.
            at_end: self
                .spring
                .zip(boundary.slider)
                .is_some_and(|(law, p)| law.free_end() && law.gap() == p.x),
        };
        let v_rel = if !from_rest && boundary.mode == Mode::Stick {
            0.0
        } else {
            walk.rod.v - walk.v
        };
        walk.mode = self.mode_for(v_rel, 0.0, walk.rod, walk.place(), None);
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
            slider: self.spring.map(|_| SliderState {
                x: walk.x_start + walk.x,
                contact: walk.contact,
            }),
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
        let functions =
            stick_functions_of(&self.modes, self.stuck_on_spring.as_ref(), walk.place());
        let functions = functions.as_ref();
        let span = self.period - walk.tau;
        let exit = ModeFunctions::stick_exit(
            self.edges_of(functions, walk.tau, walk.rod, walk.place()),
            walk.tau,
            span,
            &mut self.counters,
        );
        let s_exit = match exit {
            StickExit::PeriodEnd => span,
            StickExit::Leaves { s, .. } => s,
        };
        // A free end met or left before: the stick goes on from there with
        // the spring's force changed (continuously: it is zero there).
        let touch = self.spring.filter(|law| law.free_end()).and_then(|law| {
            let f =
                law.stuck_contact_function(functions, walk.tau, walk.rod, walk.x_start + walk.x);
            contact_change(&f, s_exit, walk.contact, walk.at_end)
        });
        let (s_end, exit) = match touch {
            Some(s) if s < s_exit => (s, StickExit::PeriodEnd),
            _ => (s_exit, exit),
        };
        let touched = touch.is_some_and(|s| s == s_end);
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
        walk.at_end = false;
        if touched {
            self.contact_event(walk, observer)?;
        }
        if let StickExit::Leaves { to, .. } = exit {
            walk.mode = Mode::Slip(to);
            walk.departure = true;
            self.emit(walk, EventKind::StickToSlip { to }, observer)?;
        }
        Ok(())
    }

    /// The free end is met or left at `walk.tau`.
    fn contact_event<O: Observer>(
        &mut self,
        walk: &mut Walk,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        walk.contact = !walk.contact;
        walk.at_end = true;
        let kind = if walk.contact {
            EventKind::ContactStart
        } else {
            EventKind::ContactEnd
        };
        self.emit(walk, kind, observer)
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
        let x_abs = walk.x_start + walk.x;
        let motion = match &self.spring {
            Some(law) => law.slip(walk.contact, x_abs, walk.v, a_s),
            None => SliderMotion::Uniform {
                x0: x_abs,
                v0: walk.v,
                a: a_s,
            },
        };
        let zero = functions.slip_zero(
            walk.tau,
            walk.rod,
            &motion,
            span,
            self.contact.tol_v,
            (dir, walk.departure),
            &mut self.counters,
        );
        let s_zero = zero.map_or(span, |z| z.s);
        // A free end met or left before the zero of v_rel: the slip goes on
        // from there on the other law.
        let touch = self.spring.filter(|law| law.free_end()).and_then(|law| {
            let f = law.slip_contact_function(&motion, functions.particular().omega());
            contact_change(&f, s_zero, walk.contact, walk.at_end)
        });
        let (zero, touched) = match touch {
            Some(s) if s < s_zero || zero.is_none() => (None, Some(s)),
            _ => (zero, None),
        };
        let (s_end, grazing) = match (zero, touched) {
            (Some(z), _) => (z.s, z.tangency),
            (None, Some(s)) => (s, false),
            (None, None) => (span, false),
        };
        let rod_end = functions.rod_at(walk.tau, walk.rod, s_end);
        let end_tau = if zero.is_none() && touched.is_none() {
            self.period
        } else {
            walk.tau + s_end
        };
        let slider_end = motion.at(s_end);
        let x1 = slider_end.x - walk.x_start;
        let v1 = slider_end.v;
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
        walk.at_end = false;
        if touched.is_some() {
            return self.contact_event(walk, observer);
        }
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
        let at_zero = (!grazing).then_some(time_error);
        let mode = self.mode_for(0.0, walk.tau, walk.rod, walk.place(), at_zero);
        walk.mode = mode;
        // The slider's acceleration jumps from the old mode's to the new
        // one's by the difference of the contact law's values at the
        // stuck system's acceleration.
        let a_st = self.stuck_acceleration(walk);
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
        Segment {
            slider_origin: walk.x_start,
            ..self.contact.segment(
                walk.period,
                [walk.tau, end],
                mode,
                slider,
                [state(walk.rod), state(rod_end)],
            )
        }
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
