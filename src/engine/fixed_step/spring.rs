//! The slider against a spring in the fixed-step reference (docs/model.md
//! section 17, [`crate::spring`]):
//!
//! ```text
//! slider: m_s a_S = F_f + m_s g_t - F_spring
//! tied spring:       F_spring = F_p + k x_S + b v_S
//! free-ended spring: F_spring = k (x_S - x_gap)  while x_S >= x_gap, else 0
//! stick (v_S = v_R): held while |F_f| = |m_s (a_S - g_t) + F_spring| <= mu_0 F_c
//! ```
//!
//! with `x_S` the slider's absolute position (0 at the start of a run from
//! rest), which the engine carries from period to period.
//!
//! ## Scheme (semi-implicit: the spring by the trapezoidal rule)
//! Over a step `[t_0, t_0 + h]` the spring's force is taken at its mean
//! over the step, the mean of the two nodes' forces (the trapezoidal rule,
//! implicit in the spring):
//!
//! ```text
//! F_bar = F_p + k (x_0 + x_1) / 2 + b (v_0 + v_1) / 2,   x_1 = x_0 + h (v_0 + v_1) / 2
//!       = G + K (v_1 - v_0),
//! G = F_spring(x_0, v_0) + k h v_0 / 2,   K = k h / 4 + b / 2,
//! ```
//!
//! `G` the force predicted at the step's middle from its start. The
//! slider's step `m_s (v_1 - v_0) = h (F_f + m_s g_t - F_bar)` is then
//! linear in `v_1`: the spring adds `h K` to the slider's inertia over the
//! step,
//!
//! ```text
//! q (v_1 - v_0) = h (F_f / m_s + g_t - a_g),   q = 1 + h K / m_s,   a_g = G / m_s,
//! ```
//!
//! the same structure as the rod's trapezoidal step (`rod.rs`, `D`). In
//! slip `F_f / m_s + g_t` is the slip acceleration `a_s = ±a_d + g_t`, so
//! `v_1 = v_0 + h (a_s - a_g) / q`. A stuck slider ends on the rod,
//! `v_1 = v_R1`, with the friction
//!
//! ```text
//! F_f / m_s + g_t = a_fr = q a_req + a_g,   a_req = (v_R1 - v_0) / h,
//! ```
//!
//! so the stick band test of the step law (module [`super`]) is taken on
//! `a_fr` instead of `a_req`: the band shifts by the spring's force per
//! slider mass. Every slip candidate ends with the relative velocity
//! `v_R1 - v_1 = (h / q) (a_fr - a_s)`, so forward slip goes on exactly
//! while `a_fr > a_d + g_t`, and a slip decision taken because `a_fr` left
//! the band ends with `v_rel` of the slip's sign: the step law and its
//! consistency carry over with `a_fr` for `a_req`. With a driven rod
//! (`rod.rs`) the stick step shares the spring's impulse between rod and
//! slider (with reaction):
//! `(D + m_s q) V = D v_free + m_s q v_S0 + h m_s (g_t - a_g)`, the
//! trapezoidal step of `(M + m_s) a_R + d v_R + c x_R = alpha u + m_s g_t -
//! F_spring` for a slider stuck at the step start.
//!
//! A free end is in contact on a step if `x_0 >= x_gap` at its start; a
//! step out of contact is the spring-free step, bit for bit. The slider
//! meets or leaves the end at the node where `x_S - x_gap` changes sign:
//! a `ContactStart` or `ContactEnd` event there, which closes the open
//! segment. A slider at the end at the start of a run (`x_gap = 0`) is in
//! contact without an event.
//!
//! **Order.** In slip the step is the trapezoidal rule (the implicit
//! midpoint rule) for the slider's linear oscillator
//! `m_s x'' + b x' + k x = F_mode`: second order, and without damping it
//! keeps the oscillator's energy exactly, so a Coulomb-damped swing loses
//! only what friction takes. In stick the slider is on the rod at the
//! nodes. The steps holding a friction event are given wholly to the new
//! mode as without a spring (velocity error `O(h)` after the event), and
//! the step where the free end is met or left applies the contact state of
//! its start to the whole step (an impulse error `O(k |v| h^2)`): first
//! order overall. A slider position at a turning point (`v_S = 0`) is
//! second order: the `O(h)` velocity error after an event sits where the
//! slider is slow, and changes the swing's energy by `O(h^2)`.
//!
//! ## What it reports
//! A slip step in contact has its own acceleration `(v_1 - v_0) / h`: it is
//! a segment of its own, so that a slip segment stays a constant
//! acceleration piece of the scheme's motion. An engine with a spring
//! carries the slider's position from period to period
//! ([`PeriodEngine::carries_rod_state`](super::super::PeriodEngine::carries_rod_state)),
//! so it cuts its stick segments where the slider's velocity increment
//! changes sign (its extrema on the grid), as the driven rod's do. The
//! period map's derivative is `dv_S / dv_S0` with the start position
//! held, carried through every step with its mode and load held.

use super::{FixedStepEngine, Walk};
use crate::engine::{EventKind, Mode, Observer};
use crate::spring::Spring;

/// The spring against `m_s`, for steps of any length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SpringStep {
    spring: Spring,
    /// `m_s` (kg).
    mass: f64,
}

/// The spring's share of one step in contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Load {
    /// `a_g = G / m_s` (m/s^2).
    pub accel: f64,
    /// `q = 1 + h K / m_s` (1).
    pub q: f64,
    /// `k / m_s` (1/s^2): `d a_g / d x_0`.
    pub dx: f64,
    /// `(b + k h / 2) / m_s` (1/s): `d a_g / d v_0`.
    pub dv: f64,
}

impl SpringStep {
    /// `spring` against a slider of mass `mass` (kg).
    pub(super) fn new(spring: Spring, mass: f64) -> Self {
        Self { spring, mass }
    }

    /// Whether the spring acts on the slider at position `x` (m).
    #[inline]
    pub(super) fn in_contact(&self, x: f64) -> bool {
        self.spring.in_contact(x)
    }

    /// Whether the spring has a free end (contact events).
    #[inline]
    pub(super) fn free_end(&self) -> bool {
        !matches!(self.spring.end, crate::spring::SpringEnd::Tied { .. })
    }

    /// `F_spring / m_s` (m/s^2) at `(x, v)`: the shift of the band for a
    /// slider at rest there.
    #[inline]
    pub(super) fn accel(&self, x: f64, v: f64) -> f64 {
        self.spring.force(x, v) / self.mass
    }

    /// `F_spring` (N) at the slider's absolute position `x` (m) and
    /// velocity `v` (m/s): 0 away from a free end.
    #[inline]
    pub(super) fn force(&self, x: f64, v: f64) -> f64 {
        self.spring.force(x, v)
    }

    /// `F_bar` (N), the force over a step in contact from `[x_0, v_0]` to
    /// `[x_1, v_1]`: the mean of the two nodes' forces of the law in
    /// contact, `F(x_0, v_0) + k (x_1 - x_0) / 2 + b (v_1 - v_0) / 2`
    /// (module doc).
    #[inline]
    pub(super) fn step_force(&self, [x0, v0]: [f64; 2], [x1, v1]: [f64; 2]) -> f64 {
        let (k, b) = (self.spring.stiffness, self.spring.damping);
        self.spring.force(x0, v0) + 0.5 * k * (x1 - x0) + 0.5 * b * (v1 - v0)
    }

    /// The load over a step of length `h` (s) from the slider at `x` (m,
    /// absolute) with velocity `v` (m/s); `None` out of contact.
    #[inline]
    pub(super) fn load(&self, x: f64, v: f64, h: f64) -> Option<Load> {
        if !self.in_contact(x) {
            return None;
        }
        let (k, b, m) = (self.spring.stiffness, self.spring.damping, self.mass);
        let g = self.spring.force(x, v) + 0.5 * k * h * v;
        Some(Load {
            accel: g / m,
            q: 1.0 + h * (0.25 * k * h + 0.5 * b) / m,
            dx: k / m,
            dv: (b + 0.5 * k * h) / m,
        })
    }
}

impl Load {
    /// The slider's velocity at the end of a slip step with slip
    /// acceleration `a_s` (m/s^2): `v_0 + h (a_s - a_g) / q`.
    #[inline]
    pub(super) fn slide(&self, v: f64, a_s: f64, h: f64) -> f64 {
        v + h * (a_s - self.accel) / self.q
    }

    /// `a_fr = q a_req + a_g` for a stuck slider going from `v_0` to `v_1`
    /// over `h`: the acceleration friction (with `g_t`) must give.
    #[inline]
    pub(super) fn friction(&self, v0: f64, v1: f64, h: f64) -> f64 {
        self.q * (v1 - v0) / h + self.accel
    }

    /// The derivative `[d x_S, d v_S]` carried through a step in `mode`
    /// ending at `d v_stick` in stick (module doc).
    #[inline]
    pub(super) fn tangent(&self, mode: Mode, t: [f64; 2], stick: f64, h: f64) -> [f64; 2] {
        let v1 = match mode {
            Mode::Stick => stick,
            Mode::Slip(_) => t[1] - h * (self.dx * t[0] + self.dv * t[1]) / self.q,
        };
        [t[0] + 0.5 * h * (t[1] + v1), v1]
    }
}

/// The derivative `[d x_S, d v_S]` through a step without load.
#[inline]
pub(super) fn free_tangent(mode: Mode, t: [f64; 2], stick: f64, h: f64) -> [f64; 2] {
    let v1 = match mode {
        Mode::Stick => stick,
        Mode::Slip(_) => t[1],
    };
    [t[0] + 0.5 * h * (t[1] + v1), v1]
}

impl FixedStepEngine<'_> {
    /// One step of the prescribed rod's law with the spring's `load`
    /// (module doc): the mode, the slider's end velocity and `a_fr`.
    #[inline]
    pub(super) fn spring_step_law(
        &self,
        mode: Mode,
        v: f64,
        v_rod_end: f64,
        h: f64,
        load: &Load,
    ) -> (Mode, f64, f64) {
        let c = &self.contact;
        let a_fr = load.friction(v, v_rod_end, h);
        let forward = load.slide(v, c.a_forward, h);
        let backward = load.slide(v, c.a_backward, h);
        let relative = [v_rod_end - forward, v_rod_end - backward];
        let new = self.choose(mode, a_fr, relative, h);
        let v1 = match new {
            Mode::Stick => v_rod_end,
            Mode::Slip(crate::engine::Direction::Forward) => forward,
            Mode::Slip(crate::engine::Direction::Backward) => backward,
        };
        (new, v1, a_fr)
    }

    /// Before a step in `walk.mode` whose rod velocity changes by `dv`
    /// (m/s): the open segment ends here if the step is a slip step under
    /// a load (a segment of its own) or a stuck slider's velocity
    /// increment changes sign (an extremum, the contract of
    /// `carries_rod_state`). The rod at the segment's ends from `rod`.
    #[inline]
    pub(super) fn spring_cuts<O: Observer>(
        &self,
        walk: &mut Walk,
        loaded: bool,
        dv: f64,
        observer: &mut O,
        rod: impl FnOnce(&Walk) -> [crate::signal::RodState; 2],
    ) {
        let cut = match walk.mode {
            Mode::Slip(_) => loaded,
            Mode::Stick => walk.last_dv * dv < 0.0,
        };
        walk.last_dv = dv;
        if cut && observer.wants_segments() {
            self.close_segment_with(walk, observer, rod);
        }
    }

    /// At a node after a step: a free end met or left there closes the
    /// open segment (the rod at its ends from `rod`, asked only if the
    /// segment is handed over) and is the event returned, for the caller
    /// to emit.
    pub(super) fn contact_change<O: Observer>(
        &self,
        walk: &mut Walk,
        observer: &mut O,
        rod: impl FnOnce(&Walk) -> [crate::signal::RodState; 2],
    ) -> Option<EventKind> {
        let spring = self.spring.as_ref().filter(|s| s.free_end())?;
        let now = spring.in_contact(walk.origin + walk.x);
        if now == walk.contact {
            return None;
        }
        self.close_segment_with(walk, observer, rod);
        walk.contact = now;
        Some(if now {
            EventKind::ContactStart
        } else {
            EventKind::ContactEnd
        })
    }
}
