//! The fixed-step reference integrator (docs/model.md section 1, true stick, no
//! smoothing): the method of the paper's section 7, which used 5000 fixed
//! steps per period of the highest harmonic, made available in the same
//! program so that its results can be compared indicator by indicator with
//! the exact [event engine](super::event).
//!
//! ## Grid
//! A period `T` of a signal with `n` harmonics is cut into
//! `N = n x steps_per_harmonic` steps of equal length `h = T / N`; node
//! `k` lies at phase `tau_k = k h` (`tau_N = T` exactly), so time is kept as
//! `(period index, step index)` and phases never drift. The ideal signal
//! (11) has no highest harmonic; it counts as `n = 1`, so `N` steps span its
//! whole period. A rod jump inside the period (discrete ideal signal, at
//! `t_1`) becomes an extra node: the step holding it is split in two, and a
//! node closer than `1e-6 h` to `t_1` is moved onto it so that no step is
//! vanishingly short.
//!
//! ## Scheme (velocity level, Moreau-Jean type)
//! Over a step `[tau_k, tau_k + h]` the slider's acceleration `a_k` is taken
//! constant and chosen by the Coulomb law at the step *end* (implicit in the
//! contact, like Moreau's sweeping process). With the rod velocity at the
//! step end `v_R1 = v_R(tau_k + h)` (left limit) and the slider velocity
//! `v_k`, the acceleration a stuck slider would need is
//!
//! ```text
//! a_req = (v_R1 - v_k) / h
//! ```
//!
//! and with the slip accelerations `a_f = a_d + g_t`, `a_b = -a_d + g_t` and
//! the band `[a_0^-, a_0^+]`:
//!
//! * **stuck at `tau_k`** (`v_k = v_R(tau_k)`, so `a_req` is the mean of
//!   `a_R` over the step): stick if `a_0^- <= a_req <= a_0^+`, else slip
//!   forward (`a_req > a_0^+`) or backward (`a_req < a_0^-`);
//! * **slipping forward**: keep slipping if the predicted relative
//!   velocity `v_R1 - (v_k + h a_f) = h (a_req - a_f)` is still positive;
//!   if it is not, `v_rel` reached zero inside the step, and the slider
//!   sticks if `a_req >= a_0^-` (the static friction can hold it) or
//!   reverses to backward slip if `a_req < a_0^-`; mirrored for backward.
//!
//! Then `v_{k+1} = v_R1` in stick and `v_{k+1} = v_k + h a_k` in slip, and
//! the position follows the constant acceleration exactly,
//! `x_{k+1} = x_k + h (v_k + v_{k+1}) / 2`. Every outcome is consistent
//! with the Coulomb law at the step end: after a slip decision the new
//! relative velocity has the sign of the slip direction (`a_0^- <= a_b` and
//! `a_f <= a_0^+` because `a_d <= a_0`). Static friction holds only a slider
//! that is stuck or comes to rest within the step, which resolves the
//! ambiguity `mu_d < mu_0` leaves (a slider slipping with
//! `a_f < a_req <= a_0^+` keeps slipping).
//!
//! A difference quotient within `tol_v / h` of the band counts as inside it
//! (`tol_v` below), so that a rod acceleration exactly at a threshold (the
//! ideal signal at `kappa = 1`) does not slip on rounding.
//!
//! **Why first order.** Between events both the slip phases (constant
//! acceleration) and the stick phases (`v_S = v_R` at every node) are exact
//! at the nodes; the error comes from the steps that hold an event, which
//! the scheme gives wholly to the new mode. After a stick -> slip or a
//! reversal the slider velocity is off by up to `h |Delta a|` (`Delta a`
//! the jump of the slider's acceleration, `|a_s - a_R|` or `2 a_d`); a step
//! that ends in stick ends exactly on the rod velocity. With a bounded
//! number of events per period the error is `O(h)`. Its constant depends on
//! where the events fall on the grid (the fraction of the step before the
//! event), which moves erratically with `h`: the error is `C(h) h` with a
//! scattering `C(h)`, and a convergence order is only meaningful as a trend
//! over several resolutions (see `tests/fixed_step.rs`).
//!
//! Two consequences are worth knowing when reading fixed-step results:
//!
//! * **A continuum of periodic orbits in slip-slip.** Without stick, the
//!   scheme's period map is `P_h(v) = v + h (n_f a_f + n_b a_b)` with the
//!   integer numbers `n_f`, `n_b` of forward and backward slip steps, which
//!   change only when an event moves to another step: its derivative is
//!   exactly 1, and every start velocity in an interval of width about
//!   `h |a_R - a_s|` (at the events) is a periodic orbit. The exact map
//!   contracts through the event times, which a grid cannot move
//!   continuously. The steady state found then depends on where the search
//!   enters that interval, and `v_inf` is determined only to its width: at
//!   the paper's 5000 steps per harmonic on the default scene, about
//!   `1e-4 v_inf`.
//! * **Reversals as one-step sticks.** A slip reversal whose zero of
//!   `v_rel` lies late in its step can pass the stick test (`a_req` mixes
//!   the old slip with the rod's acceleration) and is rendered as a stick
//!   of one step followed by slip the other way: `SlipToStick` and
//!   `StickToSlip` one node apart, and a stick time of `h` per such event.
//!
//! ## What it reports
//! The same [`Segment`](super::Segment)s, [`Event`]s and period ends as the event engine, so
//! every observer and indicator works unchanged:
//!
//! * consecutive steps of equal mode are merged into one segment (with a
//!   spring, see below); a slip
//!   segment is a true constant-acceleration piece, a stick segment follows
//!   the rod at the nodes (its first step may start off the rod velocity:
//!   the step in which the slider came to rest);
//! * a mode change is an event at the node where the first step in the new
//!   mode starts. For an exact slider state the true event lies within one
//!   step of it; the first-order velocity error moves a slip -> stick
//!   crossing by `dv / |v_rel'|`, which at a shallow crossing is more than a
//!   step. A tangency of `v_rel` cannot be told from a crossing on a grid
//!   and is reported as `SlipToStick`;
//! * rod jumps are `Jump` events at their exact phase; the slider velocity
//!   does not change, and the mode after the jump follows from the sign of
//!   the new `v_rel` (within the zero-velocity tolerance, from the band
//!   `a_R` lies in right after the jump);
//! * [`PeriodEnd::map_derivative`] is the derivative of the scheme's own
//!   period map, exact almost everywhere: 0 if the slider stuck in the
//!   period (its velocity was reset to the rod's at a node), else 1. The
//!   fixed-point search ([`crate::analysis::fixed_point`]) then takes one
//!   functional-iteration step where the map is locally constant and
//!   bisects where it is not (a Newton step `g / (1 - 1)` is rejected);
//! * [`PeriodEngine::last_velocity_uncertainty`] is `h sum |Delta a|` over
//!   the period's stick -> slip transitions and reversals: the velocity
//!   error the grid may have introduced (a bound to first order).
//!
//! A slider whose `|v_rel|` at a period start (or after a rod jump) is at
//! most `tol_v = velocity_tolerance x max |v_R|` counts as resting on the
//! rod, as in the event engine: that decision, the event kind of a mode
//! change and the segments come from the shared [contact law](super::contact);
//! the step law above is the scheme's own.
//!
//! ## A driven rod
//! [`FixedStepEngine::driven`] replaces the signal by a rod driven by a
//! voltage (docs/model.md section 16), on the same grid: `rod.rs` is one
//! step of the rod's equation (trapezoidal rule, friction of the step's
//! mode held constant over it) coupled to the slider, `driven.rs` the walk
//! through a period, with the rod's state carried from period to period.
//! The step law above decides the mode with `a_req` taken from the coupled
//! step; for a prescribed rod nothing changes.
//!
//! ## A spring against the slider
//! [`FixedStepEngine::with_spring`] puts a spring against the slider
//! (docs/model.md section 17), for a prescribed or a driven rod
//! (`spring.rs`): `m_s a_S = F_f + m_s g_t - F_spring`, the spring taken
//! by the trapezoidal rule over each step (semi-implicit), which adds
//! `h (k h / 4 + b / 2)` to the slider's inertia over the step (`q`) and
//! a force `G` known at the step start:
//!
//! ```text
//! slip:  v_1 = v_0 + h (±a_d + g_t - a_g) / q,   a_g = G / m_s,
//!        G = F_spring(x_0, v_0) + k h v_0 / 2,   q = 1 + h (k h / 4 + b / 2) / m_s
//! stick: v_1 = v_R1, the band test on a_fr = q a_req + a_g
//! ```
//!
//! (with `g_t` the stuck slider's friction is `m_s (a_fr - g_t)`). In slip
//! in contact the step is second order (the trapezoidal rule on the
//! slider's oscillator); the steps holding events keep the scheme first
//! order. The engine then carries the slider's absolute position from
//! period to period ([`FixedStepEngine::slider_position`],
//! [`PeriodEngine::carries_rod_state`]); each slip step in contact is a
//! segment of its own (its acceleration is the step's, not the mode's),
//! stick segments are cut at the slider's velocity extrema, and a free end
//! met or left at a node is a `ContactStart` or `ContactEnd` event there.
//! A step out of contact is the spring-free step, bit for bit.

mod driven;
mod prescribed;
mod rod;
mod spring;
mod spring_reading;

use super::contact::Contact;
use super::{
    Direction, Event, EventKind, Kinematics, Mode, PeriodEngine, PeriodStart, WorkCounters,
};
use super::{Observer, PeriodEnd};
use crate::actuator::DrivenRod;
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::signal::{RodState, Signal};
use crate::spring::Spring;
use driven::Driven;
use spring::SpringStep;

/// Settings of the fixed-step reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedStepOptions {
    /// Steps per period of the highest harmonic (`>= 1`); the paper used
    /// 5000 (section 7). The default.
    pub steps_per_harmonic: u32,
    /// Zero-velocity tolerance relative to `max |v_R|`, for the slider's
    /// mode at a period start or after a rod jump (as in the event engine).
    pub velocity_tolerance: f64,
}

impl Default for FixedStepOptions {
    /// 5000 steps per harmonic period, velocity tolerance `1e-13`.
    fn default() -> Self {
        Self {
            steps_per_harmonic: 5000,
            velocity_tolerance: 1e-13,
        }
    }
}

/// The fixed-step reference engine for one signal and motor.
#[derive(Debug, Clone)]
pub struct FixedStepEngine<'s> {
    signal: &'s Signal,
    period: f64,
    /// Steps per period `N`.
    steps: u64,
    /// Step length `h = T / N` (s).
    h: f64,
    /// Jump phase inside `(0, T)` (discrete ideal signal).
    inner_jump: Option<f64>,
    /// The rod jumps at phase 0 from period 2 on (continuous ideal signal).
    jump_at_start: bool,
    /// The friction law, with the zero-velocity tolerance `tol_v`.
    contact: Contact,
    rod_at_start: RodState,
    rod_at_end: RodState,
    last_uncertainty: f64,
    counters: WorkCounters,
    /// The driven rod and the state it carries from period to period
    /// (`driven.rs`); `None` for a prescribed rod.
    driven: Option<Box<Driven>>,
    /// The spring against the slider (`spring.rs`), if any.
    spring: Option<SpringStep>,
    /// The slider's absolute position at the end of the last period (m).
    slider_x: f64,
    /// `m_s` (kg), for a spring's force.
    slider_mass: f64,
    /// A reading of the spring in progress (`spring_reading.rs`).
    tally: Option<spring_reading::SpringTally>,
}

/// Mutable state of the walk through one period.
struct Walk {
    period: u64,
    /// Phase of the current node (s).
    tau: f64,
    /// Slider position relative to the period start (m).
    x: f64,
    /// The slider's absolute position at the period start (m).
    origin: f64,
    /// A spring's free end is in contact at the current node.
    contact: bool,
    /// `[d x_S, d v_S]` with respect to the slider's velocity at the
    /// period start, for an engine with a spring (`spring.rs`).
    tangent: [f64; 2],
    /// The rod's (stuck slider's) velocity increment over the last step,
    /// for the stick segments' cuts at its extrema.
    last_dv: f64,
    /// The acceleration of the open segment when it is one slip step under
    /// a spring's load (its own, not the mode's).
    step_accel: Option<f64>,
    /// Slider velocity (m/s).
    v: f64,
    mode: Mode,
    /// Derivative of the scheme's own period map: 0 once the slider stuck.
    derivative: f64,
    /// Velocity error the grid introduced in this period (m/s).
    uncertainty: f64,
    /// The open segment: its start phase and the slider there.
    segment_start: f64,
    segment_slider: Kinematics,
}

impl Walk {
    /// The slider sticks to the rod moving at `v_rod`: it takes the rod's
    /// velocity, which no longer depends on its own start velocity.
    fn stick_to(&mut self, v_rod: f64) {
        self.v = v_rod;
        self.segment_slider.v = v_rod;
        self.derivative = 0.0;
        self.tangent[1] = 0.0;
    }

    /// A walk through `period` from the slider at absolute position
    /// `origin` with velocity `v`, in stick until the caller decides.
    fn new(period: u64, origin: f64, v: f64, spring: Option<&SpringStep>) -> Self {
        Walk {
            period,
            tau: 0.0,
            x: 0.0,
            origin,
            contact: spring.is_some_and(|s| s.in_contact(origin)),
            tangent: [0.0, 1.0],
            last_dv: 0.0,
            step_accel: None,
            v,
            mode: Mode::Stick,
            derivative: 1.0,
            uncertainty: 0.0,
            segment_start: 0.0,
            segment_slider: Kinematics { x: 0.0, v },
        }
    }
}

impl<'s> FixedStepEngine<'s> {
    /// Prepares the engine.
    ///
    /// # Panics
    /// If `options.steps_per_harmonic` is 0 (a scene rejects that value
    /// before it gets here).
    pub fn new(signal: &'s Signal, motor: &Motor, options: FixedStepOptions) -> Self {
        assert!(
            options.steps_per_harmonic >= 1,
            "steps_per_harmonic must be at least 1"
        );
        let period = signal.period();
        let steps = Self::steps_for(signal, options.steps_per_harmonic);
        let v_scale = signal.velocity_scale().max(f64::MIN_POSITIVE);
        let jump = signal.jump_phase();
        Self {
            signal,
            period,
            steps,
            h: period / steps as f64,
            inner_jump: jump.filter(|t| *t > 0.0 && *t < period),
            jump_at_start: jump == Some(0.0),
            contact: Contact::new(motor, options.velocity_tolerance * v_scale),
            rod_at_start: signal.state(0.0),
            rod_at_end: signal.state_before(period),
            last_uncertainty: 0.0,
            counters: WorkCounters::default(),
            driven: None,
            spring: None,
            slider_x: 0.0,
            slider_mass: motor.params().slider_mass,
            tally: None,
        }
    }

    /// Puts `spring` against the slider (`spring.rs`, docs/model.md
    /// section 17), for a prescribed or a driven rod. The engine then
    /// carries the slider's absolute position from period to period
    /// ([`PeriodEngine::carries_rod_state`]); period 1 without a mode
    /// starts it at `x_S = 0`. `spring` is expected to be valid
    /// ([`Spring::validate`]).
    pub fn with_spring(mut self, spring: Spring) -> Self {
        self.spring = Some(SpringStep::new(spring, self.slider_mass));
        self
    }

    /// The slider's absolute position at the end of the last period run
    /// (m), counted from the start of the last run from rest (period 1
    /// without a mode); 0 before the first.
    pub fn slider_position(&self) -> f64 {
        self.slider_x
    }

    /// Prepares the engine for a rod driven by a voltage (`driven.rs`,
    /// docs/model.md section 16): `signal` is the scene's signal the
    /// voltage was designed for. It gives the grid, the scales (the
    /// zero-velocity tolerance) and [`PeriodEngine::signal`]; the rod
    /// itself moves by its own equation, starts at rest at `x_R = 0` in
    /// period 1 and carries its state from period to period
    /// ([`PeriodEngine::carries_rod_state`]). The rod never jumps, even
    /// where the signal would.
    ///
    /// # Panics
    /// If `options.steps_per_harmonic` is 0 (as [`FixedStepEngine::new`]).
    pub fn driven(
        signal: &'s Signal,
        motor: &Motor,
        rod: &DrivenRod,
        options: FixedStepOptions,
    ) -> Self {
        let mut engine = Self::new(signal, motor, options);
        engine.inner_jump = None;
        engine.jump_at_start = false;
        engine.driven = Some(Box::new(Driven::new(rod, motor, engine.h)));
        engine
    }

    /// The driven rod's position and velocity at the end of the last
    /// simulated period (at rest at `x_R = 0` before the first); `None` for
    /// a prescribed rod.
    pub fn rod_state(&self) -> Option<Kinematics> {
        self.driven.as_ref().map(|d| d.rod_state())
    }

    /// Steps per period `N = n x steps_per_harmonic` for a signal with `n`
    /// harmonics (`n = 1` for the ideal signal).
    pub fn steps_for(signal: &Signal, steps_per_harmonic: u32) -> u64 {
        let harmonics = match signal {
            Signal::Fourier(s) => s.degree().max(1) as u64,
            Signal::Ideal(_) => 1,
        };
        harmonics * u64::from(steps_per_harmonic)
    }

    /// Steps per period `N = n x steps_per_harmonic`.
    pub fn steps_per_period(&self) -> u64 {
        self.steps
    }

    /// Step length `h = T / N` (s).
    pub fn step(&self) -> f64 {
        self.h
    }

    /// Phase of node `k` (`k <= N`): exact multiples of `h`, and `T` itself
    /// at the end.
    fn node(&self, k: u64) -> f64 {
        if k >= self.steps {
            self.period
        } else {
            k as f64 * self.h
        }
    }

    /// One step of the scheme (module doc): the mode on the step and the
    /// slider velocity at its end, from the mode and velocity at its start,
    /// the rod velocity at its end and its length.
    #[inline]
    fn step_law(&self, mode: Mode, v: f64, v_rod_end: f64, h: f64) -> (Mode, f64) {
        let a_req = (v_rod_end - v) / h;
        let c = &self.contact;
        let forward = v + h * c.a_forward;
        let backward = v + h * c.a_backward;
        let relative = [v_rod_end - forward, v_rod_end - backward];
        match self.choose(mode, a_req, relative, h) {
            Mode::Stick => (Mode::Stick, v_rod_end),
            m @ Mode::Slip(Direction::Forward) => (m, forward),
            m @ Mode::Slip(Direction::Backward) => (m, backward),
        }
    }

    /// The decision of the step law (module doc) from the mode at the step
    /// start, the acceleration `a_req` a stuck slider would need over the
    /// step and the relative velocities `[forward, backward]` the step
    /// would end with in forward and in backward slip.
    #[inline]
    fn choose(&self, mode: Mode, a_req: f64, relative: [f64; 2], h: f64) -> Mode {
        // a_req is a difference quotient of velocities: within tol_v / h of
        // the band it counts as inside (a_R = a_0 exactly, as in the ideal
        // signal at kappa = 1, must not slip on rounding).
        let c = &self.contact;
        let tol_a = c.tol_v / h;
        let (a_plus, a_minus) = (c.a_plus + tol_a, c.a_minus - tol_a);
        let (forward, backward) = (
            Mode::Slip(Direction::Forward),
            Mode::Slip(Direction::Backward),
        );
        match mode {
            Mode::Stick => {
                if a_req > a_plus {
                    forward
                } else if a_req < a_minus {
                    backward
                } else {
                    Mode::Stick
                }
            }
            Mode::Slip(Direction::Forward) => {
                if relative[0] > 0.0 {
                    forward
                } else if a_req < a_minus {
                    backward
                } else {
                    Mode::Stick
                }
            }
            Mode::Slip(Direction::Backward) => {
                if relative[1] < 0.0 {
                    backward
                } else if a_req > a_plus {
                    forward
                } else {
                    Mode::Stick
                }
            }
        }
    }

    /// `|Delta a|` of a mode change on a step: how far the slider's true
    /// acceleration over the step may differ from the one the scheme gave
    /// the whole step. A stuck slider follows `a_R`, whose mean over the step
    /// is `a_req`; a step that ends in stick ends exactly on the rod
    /// velocity, so it adds no velocity error.
    fn acceleration_jump(&self, old: Mode, new: Mode, a_req: f64) -> f64 {
        let slip = |d: Direction| self.contact.slip_acceleration(d);
        match (old, new) {
            (_, Mode::Stick) => 0.0,
            (Mode::Stick, Mode::Slip(d)) => (slip(d) - a_req).abs(),
            (Mode::Slip(a), Mode::Slip(b)) => (slip(b) - slip(a)).abs(),
        }
    }

    fn emit<O: Observer>(&mut self, walk: &Walk, kind: EventKind, observer: &mut O) {
        self.counters.events.add(&kind);
        observer.event(&Event {
            period: walk.period,
            phase: walk.tau,
            kind,
        });
    }

    /// Hands the open segment `[segment_start, tau]` to the observer and
    /// opens the next one at `tau`.
    fn close_segment<O: Observer>(&self, walk: &mut Walk, observer: &mut O) {
        self.close_segment_with(walk, observer, |w| self.rod_ends(w));
    }

    /// [`Self::close_segment`] with the rod at the segment's start and end
    /// from `rod` (asked only if the observer wants the segment).
    fn close_segment_with<O: Observer>(
        &self,
        walk: &mut Walk,
        observer: &mut O,
        rod: impl FnOnce(&Walk) -> [RodState; 2],
    ) {
        if walk.tau > walk.segment_start && observer.wants_segments() {
            let [rod_start, rod_end] = rod(walk);
            let slider_end = Kinematics {
                x: walk.x,
                v: walk.v,
            };
            let mut segment = self.contact.segment(
                walk.period,
                [walk.segment_start, walk.tau],
                walk.mode,
                [walk.segment_slider, slider_end],
                [rod_start, rod_end],
            );
            if let Some(a) = walk.step_accel {
                segment.slip_acceleration = a;
            }
            observer.segment(&segment, self.signal);
        }
        walk.step_accel = None;
        walk.segment_start = walk.tau;
        walk.segment_slider = Kinematics {
            x: walk.x,
            v: walk.v,
        };
    }
}

impl PeriodEngine for FixedStepEngine<'_> {
    fn signal(&self) -> &Signal {
        self.signal
    }

    fn run_period<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        if let Some(mut driven) = self.driven.take() {
            let end = self.run_driven_period(&mut driven, period, start, observer);
            self.driven = Some(driven);
            return Ok(end);
        }
        self.run_period_impl(period, start, observer)
    }

    fn counters(&self) -> WorkCounters {
        self.counters
    }

    fn zero_velocity_tolerance(&self) -> f64 {
        self.contact.tol_v
    }

    /// The scheme's period map has whole bands of fixed points in
    /// slip-slip (its derivative is exactly 1 there): the start-up from
    /// rest decides which one is the steady state.
    fn steady_state_from_transient(&self) -> bool {
        true
    }

    /// True for a driven rod ([`FixedStepEngine::driven`]) and with a
    /// spring ([`FixedStepEngine::with_spring`]: the slider's position).
    fn carries_rod_state(&self) -> bool {
        self.driven.is_some() || self.spring.is_some()
    }

    /// A driven rod's figures over the last period run with an observer of
    /// segments, from its nodes (`driven.rs`).
    fn drive_profile(&self, _segments: &[super::Segment]) -> Option<super::DriveProfile> {
        self.driven.as_ref()?.profile(self.signal)
    }

    /// The velocity error the grid introduced in the last period, `sum h
    /// |Delta a|` over its mode changes (see [`FixedStepEngine`]).
    fn last_velocity_uncertainty(&self) -> Option<f64> {
        Some(self.last_uncertainty)
    }

    /// An event is detected at the end of the step that holds it.
    fn event_time_uncertainty(&self) -> f64 {
        self.signal().period() / self.steps_per_period() as f64
    }
}
