//! The exact event-driven engine (docs/model.md sections 1 and 8).
//!
//! ## Method
//! Between events the slider's acceleration is constant (slip) or equal to
//! the rod's (stick), so its state is known in closed form; only event times
//! need root finding.
//!
//! Once per signal the period is cut into pieces by the roots of
//! `a_R(tau) = c` for `c` in `{a_d + g_t, -a_d + g_t}` and, when first
//! needed, `{a_0^+, a_0^-}` ([`Signal::partition`], all roots of a
//! trigonometric polynomial). These pieces serve every period:
//!
//! * **Stick -> slip**: the stick band `[a_0^-, a_0^+]` partition says on
//!   which pieces `a_R` is inside the band; a stuck slider stays stuck to the
//!   end of its piece and then slips in the direction `a_R` left the band.
//! * **Slip**: with slider acceleration `a_s`, `v_rel' = a_R - a_s` changes
//!   sign only at the roots of `a_R = a_s`, so `v_rel` is monotone on every
//!   piece of that partition. A piece on which `|v_rel|` grows cannot hold a
//!   zero; on a piece where it shrinks there is a zero iff `v_rel` has
//!   changed sign at the piece's end, and then exactly one, found by
//!   safeguarded Newton ([`crate::numerics::bracket`]) to `4 eps T`. No event can be
//!   missed: this is a proof, not a sampling.
//! * **Grazing**: at the end of a shrinking piece whose next piece grows,
//!   `v_rel` has a local extremum (a critical point of `v_rel`). If
//!   `|v_rel|` there is within the *zero-velocity tolerance*
//!   `tol_v = velocity_tolerance x max |v_R|` (default `1e-13 x max |v_R|`,
//!   about 450 ulps of the largest rod velocity), the engine decides that
//!   `v_rel` touches zero: a grazing event at the critical point, after
//!   which the slider sticks (`a_R = a_s` lies in the band). A trajectory
//!   that misses zero by more than `tol_v` keeps sliding; one that crosses
//!   zero by more than `tol_v` has a transversal zero, found by the solver.
//!   The same tolerance decides, at a period start or after a rod jump,
//!   whether `v_rel` is zero.
//! * **What a zero of `v_rel` leads to** is decided by the band piece right
//!   of the event time: inside the band the slider sticks, above it slips
//!   forward, below it slips backward (docs/model.md section 1; the law is
//!   [`super::contact`], shared with the fixed-step reference). For a
//!   series, `a_R` at the event time stands in for the band pieces where
//!   it lies farther than a rounding margin from both band edges
//!   ([`Signal::partition_margin`]: there the pieces give the same band),
//!   so the partitions of `a_0^+` and `a_0^-` are found only when a
//!   slider sticks or a zero of `v_rel` falls within the margin of an
//!   edge; a slip-slip motion usually never needs them.
//! * **The departure skip**: after an event that leaves `v_rel = 0` and
//!   starts a slip (stick -> slip, reversal, grazing without sticking), the
//!   root search starts at the end of the piece that holds the event. On that
//!   *departure piece* `|v_rel|` grows away from zero by construction (the
//!   new slip direction is the one `a_R` pushes towards), so it holds no
//!   further zero; skipping it is what keeps the event from firing twice
//!   without any nudge in time.
//! * **Rod jumps** (ideal signals): the rod's position and velocity change
//!   in zero time; the slider's do not (friction is bounded). The new mode
//!   follows from the sign of the new `v_rel`.
//!
//! ## One segment in three steps
//! The walk through a period repeats, until the period ends:
//!
//! 1. **When** (detection, `event/detect.rs`): from the slider's state and
//!    mode, find where the current segment ends and what is there, a
//!    `SegmentEnd`: the period end, a rod jump, the end of the stuck
//!    slider's band piece (with the band of the next piece), a transversal
//!    zero of `v_rel` (with its time error and `a_R` there when the solver
//!    saw it) or a grazing. Detection changes no slider state; it only
//!    records the solver's work and its last roots (first iterates for
//!    later periods).
//! 2. **Move**: carry the slider to that phase in closed form and hand the
//!    segment to the observers (if they want it).
//! 3. **What** (decision): at the end found, decide the new mode with the
//!    contact law, update the slider velocity, the period-map derivative and
//!    the uncertainty bound, and hand the typed event to the observers.
//!
//! Time is kept as `(period index, phase in [0, T))` and the slider position
//! relative to its position at the period start, so precision does not decay
//! over long runs.

use super::contact::{Contact, transition};
use super::{
    Direction, Event, EventKind, Kinematics, Mode, PeriodEngine, PeriodStart, WorkCounters,
};
use super::{Observer, PeriodEnd};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::signal::{Partition, RodState, Signal};
use detect::{Found, SlipPieces, band_pieces};
use rayon::prelude::*;
use std::sync::OnceLock;

pub(crate) use super::contact::Band;

mod detect;

/// Tolerances and limits of the event engine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventOptions {
    /// Zero-velocity tolerance relative to `max |v_R|` (see the module doc).
    pub velocity_tolerance: f64,
    /// Absolute tolerance of event times relative to the period `T`.
    pub time_tolerance: f64,
    /// More events than this in one period stop the run with
    /// [`SimulationError::TooManyEvents`] (chattering).
    pub max_events_per_period: u64,
}

impl Default for EventOptions {
    fn default() -> Self {
        Self {
            velocity_tolerance: 1e-13,
            time_tolerance: 4.0 * f64::EPSILON,
            max_events_per_period: 100_000,
        }
    }
}

/// A piece of the period with one [`Band`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandPiece {
    /// Start phase (s).
    pub start: f64,
    /// End phase (s).
    pub end: f64,
    /// Band on the piece.
    pub band: Band,
}

/// The event engine for one signal and motor.
#[derive(Debug, Clone)]
pub struct EventEngine<'s> {
    signal: &'s Signal,
    period: f64,
    slip_forward: SlipPieces,
    slip_backward: SlipPieces,
    /// The stick band pieces, found when first needed ([`EventEngine::band`]).
    band: OnceLock<Vec<BandPiece>>,
    /// For a series: the margin beyond which `a_R` evaluated at a phase
    /// decides the band there without the band pieces
    /// ([`Signal::partition_margin`] of both band edges).
    band_margin: Option<f64>,
    jump: Option<f64>,
    /// The friction law, with the zero-velocity tolerance `tol_v`.
    contact: Contact,
    tol_x: f64,
    tol_t: f64,
    tol_f: f64,
    /// The largest `|v_R|` (`signal.velocity_scale()`, at least the
    /// smallest positive number).
    v_scale: f64,
    /// Bound on the rounding of a computed rod velocity.
    gap_rounding: f64,
    max_events: u64,
    /// Rod state at phase 0 (right limit) and at the period end (left limit).
    rod_at_start: RodState,
    rod_at_end: RodState,
    counters: WorkCounters,
    last_uncertainty: f64,
}

/// Fewest harmonics for which [`partitions`] finds its levels on several
/// threads. Below, a level takes under 0.2 ms and starting the thread
/// pool costs a whole process about as much as it saves (whole-process
/// medians of `stickslip run` at `n = 64`: 2.82 ms sequential, 2.99 ms on
/// the pool; at `n = 256`: 8.6 ms and 8.1 ms).
const PARALLEL_DEGREE: usize = 128;

/// The partitions of the period at `levels` (docs/model.md section 8),
/// each distinct level found once. A series of [`PARALLEL_DEGREE`] or more
/// harmonics finds them on the threads of the `rayon` pool: each partition
/// is a function of its level alone (they share the Taylor models of `a_R`,
/// found once with its roots), so the result is the same to the bit.
fn partitions<const L: usize>(signal: &Signal, levels: [f64; L]) -> [Partition; L] {
    let mut distinct: Vec<f64> = Vec::with_capacity(L);
    for level in levels {
        if !distinct.contains(&level) {
            distinct.push(level);
        }
    }
    let many = match signal {
        Signal::Fourier(s) => s.degree() >= PARALLEL_DEGREE,
        Signal::Ideal(_) => false,
    };
    let found: Vec<Partition> = if many && distinct.len() > 1 {
        distinct.par_iter().map(|&c| signal.partition(c)).collect()
    } else {
        distinct.iter().map(|&c| signal.partition(c)).collect()
    };
    levels.map(|level| {
        let i = distinct.iter().position(|d| *d == level).unwrap_or(0);
        found[i].clone()
    })
}

impl<'s> EventEngine<'s> {
    /// Prepares the engine: finds the partitions of the period once.
    pub fn new(signal: &'s Signal, motor: &Motor, options: EventOptions) -> Self {
        let period = signal.period();
        let a_fwd = motor.slip_forward_acceleration();
        let a_bwd = motor.slip_backward_acceleration();
        let [fwd, bwd] = partitions(signal, [a_fwd, a_bwd]);
        let jump = signal.jump_phase();
        let band_margin = signal
            .partition_margin(motor.a_0_plus())
            .zip(signal.partition_margin(motor.a_0_minus()))
            .map(|(plus, minus)| plus.max(minus));
        let v_scale = signal.velocity_scale().max(f64::MIN_POSITIVE);
        let envelope = signal.acceleration_envelope();
        Self {
            signal,
            period,
            slip_forward: SlipPieces::new(fwd, a_fwd, &envelope),
            slip_backward: SlipPieces::new(bwd, a_bwd, &envelope),
            band: OnceLock::new(),
            band_margin,
            jump,
            contact: Contact::new(motor, options.velocity_tolerance * v_scale),
            tol_x: options.velocity_tolerance * v_scale * period,
            tol_t: options.time_tolerance * period,
            tol_f: 4.0 * f64::EPSILON * v_scale,
            v_scale,
            gap_rounding: signal.velocity_rounding(),
            max_events: options.max_events_per_period,
            rod_at_start: signal.state(0.0),
            rod_at_end: signal.state_before(period),
            counters: WorkCounters::default(),
            last_uncertainty: 0.0,
        }
    }

    /// The signal this engine drives.
    pub fn signal(&self) -> &'s Signal {
        self.signal
    }

    /// The stick band pieces of a period, from the partitions of
    /// `a_R = a_0^+` and `a_R = a_0^-`, found on the first call.
    pub fn band(&self) -> &[BandPiece] {
        self.band.get_or_init(|| {
            let [plus, minus] =
                partitions(self.signal, [self.contact.a_plus, self.contact.a_minus]);
            band_pieces(&plus, &minus, self.jump)
        })
    }

    /// The zero-velocity tolerance `tol_v` in m/s.
    pub fn velocity_tolerance(&self) -> f64 {
        self.contact.tol_v
    }

    /// The band piece holding `tau`, its index and band.
    fn band_at(&self, tau: f64) -> (usize, Band) {
        let band = self.band();
        let i = band.partition_point(|p| p.start <= tau).saturating_sub(1);
        (i, band[i].band)
    }

    /// The band right of `tau`. Before the band pieces are found, `a_R(tau)`
    /// decides where it lies clearly (by more than the margin) above,
    /// below or inside the band: the band pieces would give the same
    /// answer ([`Signal::partition_margin`]). Only a phase within the
    /// margin of an edge, or a stuck slider, needs the band pieces, so a
    /// motion that never comes near sticking never finds them.
    fn band_after(&self, tau: f64) -> Band {
        if let Some(margin) = self.band_margin
            && self.band.get().is_none()
        {
            let a = self.signal.acceleration(tau);
            let (plus, minus) = (self.contact.a_plus, self.contact.a_minus);
            if a > plus + margin {
                return Band::Above;
            }
            if a < minus - margin {
                return Band::Below;
            }
            if a < plus - margin && a > minus + margin {
                return Band::Inside;
            }
        }
        self.band_at(tau).1
    }

    /// The mode after `v_rel` takes the value `v_rel` at phase `tau`.
    fn mode_for(&self, v_rel: f64, tau: f64) -> Mode {
        self.contact.mode(v_rel, || self.band_after(tau))
    }

    fn is_jump(&self, tau: f64) -> bool {
        self.jump == Some(tau)
    }

    fn run_period_impl<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        let mut walk = Walk {
            period,
            tau: 0.0,
            x: 0.0,
            v: start.velocity,
            map_derivative: 1.0,
            uncertainty: 0.0,
            events: 0,
            mode: Mode::Stick,
            departure: false,
        };
        self.start_period(&mut walk, start, observer)?;
        loop {
            if walk.tau >= self.period {
                break;
            }
            // When, move, what (module doc).
            let end = match walk.mode {
                Mode::Stick => {
                    let end = self.find_stick_end(walk.tau);
                    self.follow_rod(&mut walk, end.at, observer);
                    end
                }
                Mode::Slip(dir) => {
                    let end = self.find_slip_end(&walk, dir);
                    self.slide(&mut walk, dir, end.at, observer);
                    end
                }
            };
            self.decide(&mut walk, end.found, observer)?;
        }
        self.counters.periods += 1;
        self.last_uncertainty = walk.uncertainty;
        let end = PeriodEnd {
            period,
            step: walk.x,
            velocity: walk.v,
            mode: walk.mode,
            map_derivative: walk.map_derivative,
        };
        observer.period_end(&end);
        Ok(end)
    }

    fn start_period<O: Observer>(
        &mut self,
        walk: &mut Walk,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let rod0 = self.rod_at_start;
        let (jumps, rod_before) = if walk.period == 1 {
            let jumps = rod0.x.abs() > self.tol_x || rod0.v.abs() > self.contact.tol_v;
            (jumps, Default::default())
        } else {
            (self.is_jump(0.0), self.rod_at_end)
        };
        let v_rel = if start.mode == Some(Mode::Stick) && !jumps {
            0.0
        } else {
            rod0.v - walk.v
        };
        let mode = self.mode_for(v_rel, 0.0);
        walk.mode = mode;
        walk.departure = self.contact.at_rest(v_rel);
        if mode == Mode::Stick {
            walk.uncertainty += (rod0.v - walk.v).abs();
            walk.v = rod0.v;
            walk.map_derivative = 0.0;
        }
        if jumps {
            let kind = EventKind::Jump {
                dx: rod0.x - rod_before.x,
                dv: rod0.v - rod_before.v,
                then: mode,
            };
            self.emit(walk, kind, observer)?;
        } else if let Some(kind) = start.mode.and_then(|prev| transition(prev, mode, false)) {
            self.emit(walk, kind, observer)?;
        }
        Ok(())
    }

    /// Hands an event at the walk's phase to the observer; too many in one
    /// period stop the run.
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

    /// Moves a stuck slider with the rod to `end`, handing the stick
    /// segment to the observer.
    fn follow_rod<O: Observer>(&self, walk: &mut Walk, end: f64, observer: &mut O) {
        if end <= walk.tau {
            return;
        }
        let rod_start = self.signal.state(walk.tau);
        let rod_end = self.signal.state_before(end);
        let dx = rod_end.x - rod_start.x;
        if observer.wants_segments() {
            let slider = [
                Kinematics {
                    x: walk.x,
                    v: rod_start.v,
                },
                Kinematics {
                    x: walk.x + dx,
                    v: rod_end.v,
                },
            ];
            let segment = self.contact.segment(
                walk.period,
                [walk.tau, end],
                Mode::Stick,
                slider,
                [rod_start, rod_end],
            );
            observer.segment(&segment, self.signal);
        }
        walk.x += dx;
        walk.v = rod_end.v;
        walk.tau = end;
    }

    /// Moves a sliding slider in closed form to `end`, handing the slip
    /// segment to the observer.
    fn slide<O: Observer>(&self, walk: &mut Walk, dir: Direction, end: f64, observer: &mut O) {
        let a_s = self.contact.slip_acceleration(dir);
        let (tau0, x0, v0) = (walk.tau, walk.x, walk.v);
        let dt = end - tau0;
        let x1 = x0 + v0 * dt + 0.5 * a_s * dt * dt;
        let v1 = v0 + a_s * dt;
        if end > tau0 && observer.wants_slip_segments() {
            let rod = [self.signal.state(tau0), self.signal.state_before(end)];
            let slider = [Kinematics { x: x0, v: v0 }, Kinematics { x: x1, v: v1 }];
            let segment = self
                .contact
                .segment(walk.period, [tau0, end], walk.mode, slider, rod);
            observer.segment(&segment, self.signal);
        }
        walk.tau = end;
        walk.x = x1;
        walk.v = v1;
        walk.departure = false;
    }

    /// What happens at the end of a segment, at the walk's phase.
    fn decide<O: Observer>(
        &mut self,
        walk: &mut Walk,
        found: Found,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        match found {
            Found::PeriodEnd => Ok(()),
            Found::Jump => self.jump(walk, observer),
            Found::BandEnd(next) => {
                // A stuck slider stays stuck while a_R stays in the band.
                let mode = next.mode_at_rest();
                match transition(walk.mode, mode, false) {
                    Some(kind) => {
                        walk.mode = mode;
                        walk.departure = true;
                        self.emit(walk, kind, observer)
                    }
                    None => Ok(()),
                }
            }
            Found::Crossing { .. } | Found::Grazing => {
                let (grazing, time_error, a_r) = match found {
                    Found::Crossing { time_error, a_r } => (false, time_error, a_r),
                    _ => (true, 0.0, None),
                };
                self.zero_of_v_rel(walk, grazing, time_error, a_r, observer)
            }
        }
    }

    /// A rod jump at the current phase (inside the period).
    fn jump<O: Observer>(
        &mut self,
        walk: &mut Walk,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let before = self.signal.state_before(walk.tau);
        let after = self.signal.state(walk.tau);
        let v_rel = after.v - walk.v;
        let mode = self.mode_for(v_rel, walk.tau);
        walk.mode = mode;
        walk.departure = self.contact.at_rest(v_rel);
        if mode == Mode::Stick {
            walk.v = after.v;
            walk.map_derivative = 0.0;
        }
        let kind = EventKind::Jump {
            dx: after.x - before.x,
            dv: after.v - before.v,
            then: mode,
        };
        self.emit(walk, kind, observer)
    }

    /// A zero of `v_rel` at the walk's phase ends a slip: the band right of
    /// it decides the new mode (a tangency if `grazing`); the phase is
    /// known to within `time_error`, `a_r` is `a_R` there if already known.
    fn zero_of_v_rel<O: Observer>(
        &mut self,
        walk: &mut Walk,
        grazing: bool,
        time_error: f64,
        a_r: Option<f64>,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let t = walk.tau;
        let mode = self.mode_for(0.0, t);
        let old = walk.mode;
        walk.mode = mode;
        let a_r = a_r.unwrap_or_else(|| self.signal.acceleration(t));
        let a_old = self.contact.acceleration(old, a_r);
        let a_new = self.contact.acceleration(mode, a_r);
        // An event time off by dt leaves the slider with the old
        // acceleration for dt too long or too short: its velocity is off by
        // |a_old - a_new| dt.
        walk.uncertainty += (a_old - a_new).abs() * time_error;
        match mode {
            Mode::Stick => {
                let v_rod = self.signal.velocity(t);
                walk.uncertainty += (v_rod - walk.v).abs();
                walk.v = v_rod;
                walk.map_derivative = 0.0;
            }
            Mode::Slip(_) => {
                walk.departure = true;
                if mode != old {
                    // Perturbation of the crossing time carries over as
                    // dv_after = dv (a_R - a_new) / (a_R - a_old).
                    walk.map_derivative *= (a_r - a_new) / (a_r - a_old);
                }
            }
        }
        if grazing {
            // Sticking or sliding on is decided within tol_v: the two
            // outcomes differ by a finite amount, so no bound on the
            // velocity error holds through a grazing.
            walk.uncertainty = f64::INFINITY;
        }
        let kind = transition(old, mode, grazing).unwrap_or(EventKind::Grazing { then: mode });
        self.emit(walk, kind, observer)
    }
}

/// Mutable state of the walk through one period.
struct Walk {
    period: u64,
    tau: f64,
    x: f64,
    v: f64,
    map_derivative: f64,
    /// Bound on the slider velocity error introduced in this period by
    /// event-time tolerances and zero-velocity decisions (m/s).
    uncertainty: f64,
    events: u64,
    mode: Mode,
    /// `v_rel = 0` at `tau` and the mode is a slip leaving zero: the piece
    /// holding `tau` is the departure piece and is not searched.
    departure: bool,
}

impl PeriodEngine for EventEngine<'_> {
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
}
