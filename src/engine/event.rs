//! The exact event-driven engine (docs/model.md sections 1 and 8).
//!
//! ## Method
//! Between events the slider's acceleration is constant (slip) or equal to
//! the rod's (stick), so its state is known in closed form; only event times
//! need root finding.
//!
//! Once per signal the period is cut into pieces by the roots of
//! `a_R(tau) = c` for `c` in `{a_0^+, a_0^-, a_d + g_t, -a_d + g_t}`
//! ([`Signal::partition`], all roots of a trigonometric polynomial). These
//! pieces serve every period:
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
//!   forward, below it slips backward (docs/model.md section 1). Detection (when)
//!   and decision (what) are separate steps.
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
//! Time is kept as `(period index, phase in [0, T))` and the slider position
//! relative to its position at the period start, so precision does not decay
//! over long runs.

use super::{
    Direction, Event, EventKind, Kinematics, Mode, PeriodEngine, PeriodStart, Segment, WorkCounters,
};
use super::{Observer, PeriodEnd};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::numerics::bracket;
use crate::signal::{Partition, RodState, Signal};
use std::cmp::Ordering;

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

/// Where `a_R` lies relative to the stick band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Band {
    /// `a_R < a_0^-`.
    Below,
    /// `a_0^- <= a_R <= a_0^+`.
    Inside,
    /// `a_R > a_0^+`.
    Above,
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
    slip_forward: (Partition, f64),
    slip_backward: (Partition, f64),
    band: Vec<BandPiece>,
    jump: Option<f64>,
    tol_v: f64,
    tol_x: f64,
    tol_t: f64,
    tol_f: f64,
    /// The last two roots found on each piece: events recur at nearly the
    /// same phase every period, drifting smoothly while the motion settles,
    /// so their linear extrapolation is the best first iterate.
    hints_forward: Vec<[f64; 2]>,
    hints_backward: Vec<[f64; 2]>,
    max_events: u64,
    /// Rod state at phase 0 (right limit) and at the period end (left limit).
    rod_at_start: RodState,
    rod_at_end: RodState,
    counters: WorkCounters,
    last_uncertainty: f64,
}

/// How a slip phase ended.
enum SlipEnd {
    /// Transversal zero of `v_rel` at this phase, known to within the
    /// second value (s), with `a_R` there if the solver saw it.
    Crossing(f64, f64, Option<f64>),
    /// Tangential touch at this critical point.
    Grazing(f64),
    /// A rod jump at this phase.
    Jump(f64),
    /// The period ended.
    PeriodEnd,
}

impl<'s> EventEngine<'s> {
    /// Prepares the engine: finds the partitions of the period once.
    pub fn new(signal: &'s Signal, motor: &Motor, options: EventOptions) -> Self {
        let period = signal.period();
        let a_fwd = motor.slip_forward_acceleration();
        let a_bwd = motor.slip_backward_acceleration();
        let plus = signal.partition(motor.a_0_plus());
        let minus = if motor.a_0_minus() == motor.a_0_plus() {
            plus.clone()
        } else {
            signal.partition(motor.a_0_minus())
        };
        let reuse = |level: f64| {
            if level == plus.level {
                Some(plus.clone())
            } else if level == minus.level {
                Some(minus.clone())
            } else {
                None
            }
        };
        let fwd = reuse(a_fwd).unwrap_or_else(|| signal.partition(a_fwd));
        let bwd = if a_bwd == a_fwd {
            fwd.clone()
        } else {
            reuse(a_bwd).unwrap_or_else(|| signal.partition(a_bwd))
        };
        let jump = signal.jump_phase();
        let band = band_pieces(&plus, &minus, jump);
        let v_scale = signal.velocity_scale().max(f64::MIN_POSITIVE);
        Self {
            signal,
            period,
            hints_forward: vec![[f64::NAN; 2]; fwd.pieces.len()],
            hints_backward: vec![[f64::NAN; 2]; bwd.pieces.len()],
            slip_forward: (fwd, a_fwd),
            slip_backward: (bwd, a_bwd),
            band,
            jump,
            tol_v: options.velocity_tolerance * v_scale,
            tol_x: options.velocity_tolerance * v_scale * period,
            tol_t: options.time_tolerance * period,
            tol_f: 4.0 * f64::EPSILON * v_scale,
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

    /// The stick band pieces of a period.
    pub fn band(&self) -> &[BandPiece] {
        &self.band
    }

    /// The zero-velocity tolerance `tol_v` in m/s.
    pub fn velocity_tolerance(&self) -> f64 {
        self.tol_v
    }

    fn band_at(&self, tau: f64) -> (usize, Band) {
        let i = self
            .band
            .partition_point(|p| p.start <= tau)
            .saturating_sub(1);
        (i, self.band[i].band)
    }

    /// The mode after `v_rel` takes the value `v_rel` at phase `tau`.
    fn mode_for(&self, v_rel: f64, tau: f64) -> Mode {
        if v_rel.abs() <= self.tol_v {
            match self.band_at(tau).1 {
                Band::Inside => Mode::Stick,
                Band::Above => Mode::Slip(Direction::Forward),
                Band::Below => Mode::Slip(Direction::Backward),
            }
        } else if v_rel > 0.0 {
            Mode::Slip(Direction::Forward)
        } else {
            Mode::Slip(Direction::Backward)
        }
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
            match walk.mode {
                Mode::Stick => self.stick(&mut walk, observer)?,
                Mode::Slip(dir) => self.slip(&mut walk, dir, observer)?,
            }
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
            let jumps = rod0.x.abs() > self.tol_x || rod0.v.abs() > self.tol_v;
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
        walk.departure = v_rel.abs() <= self.tol_v;
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

    fn emit<O: Observer>(
        &mut self,
        walk: &mut Walk,
        kind: EventKind,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        walk.events += 1;
        self.counters.events.add(&kind);
        if walk.events > self.max_events {
            return Err(SimulationError::TooManyEvents {
                limit: self.max_events,
                period: walk.period,
                phase: walk.tau,
            });
        }
        observer.event(&Event {
            period: walk.period,
            phase: walk.tau,
            kind,
        });
        Ok(())
    }

    /// A stuck slider: follow the rod to the end of the band piece.
    fn stick<O: Observer>(
        &mut self,
        walk: &mut Walk,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let (i, band) = self.band_at(walk.tau);
        let end = if band == Band::Inside {
            self.band[i].end
        } else {
            walk.tau
        };
        if end > walk.tau {
            let rod_start = self.signal.state(walk.tau);
            let rod_end = self.signal.state_before(end);
            let dx = rod_end.x - rod_start.x;
            if observer.wants_segments() {
                let segment = Segment {
                    period: walk.period,
                    start: walk.tau,
                    end,
                    mode: Mode::Stick,
                    slider_start: Kinematics {
                        x: walk.x,
                        v: rod_start.v,
                    },
                    slider_end: Kinematics {
                        x: walk.x + dx,
                        v: rod_end.v,
                    },
                    rod_start: Kinematics {
                        x: rod_start.x,
                        v: rod_start.v,
                    },
                    rod_end: Kinematics {
                        x: rod_end.x,
                        v: rod_end.v,
                    },
                    slip_acceleration: 0.0,
                };
                observer.segment(&segment, self.signal);
            }
            walk.x += dx;
            walk.v = rod_end.v;
            walk.tau = end;
        }
        if walk.tau >= self.period {
            return Ok(());
        }
        if self.is_jump(walk.tau) {
            return self.jump(walk, observer);
        }
        let next = if band == Band::Inside {
            self.band.get(i + 1).map_or(Band::Inside, |p| p.band)
        } else {
            band
        };
        let to = match next {
            Band::Above => Direction::Forward,
            Band::Below => Direction::Backward,
            Band::Inside => return Ok(()),
        };
        walk.mode = Mode::Slip(to);
        walk.departure = true;
        self.emit(walk, EventKind::StickToSlip { to }, observer)
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
        walk.departure = v_rel.abs() <= self.tol_v;
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

    /// A sliding slider: find the next zero of `v_rel`, a jump, or the
    /// period end.
    fn slip<O: Observer>(
        &mut self,
        walk: &mut Walk,
        dir: Direction,
        observer: &mut O,
    ) -> Result<(), SimulationError> {
        let signal = self.signal;
        let (part, a_s, hints) = match dir {
            Direction::Forward => (
                &self.slip_forward.0,
                self.slip_forward.1,
                &mut self.hints_forward,
            ),
            Direction::Backward => (
                &self.slip_backward.0,
                self.slip_backward.1,
                &mut self.hints_backward,
            ),
        };
        let d = dir.sign();
        // |v_rel| shrinks where d (a_R - a_s) < 0.
        let approaching = match dir {
            Direction::Forward => Ordering::Less,
            Direction::Backward => Ordering::Greater,
        };
        let (tau0, x0, v0) = (walk.tau, walk.x, walk.v);
        // d * v_rel on the slip phase: at a piece end the rod's left limit,
        // at a piece start its right limit (they differ at a rod jump).
        let f_end_of = |t: f64| d * (signal.velocity_before(t) - (v0 + a_s * (t - tau0)));
        let f_start_of = |t: f64| d * (signal.velocity(t) - (v0 + a_s * (t - tau0)));
        let first = part.locate(tau0);
        let mut evaluations = 0u64;
        let mut iterations = 0u64;
        let mut j = first;
        let outcome = loop {
            let piece = part.pieces[j];
            let end = piece.end;
            let at_period_end = end >= self.period;
            let jump_here = !at_period_end && self.jump == Some(end);
            let departure_piece = walk.departure && j == first;
            if piece.sign == approaching && !departure_piece {
                let f_end = f_end_of(end);
                evaluations += 1;
                let next_sign = if at_period_end {
                    part.pieces[0].sign
                } else {
                    part.pieces[j + 1].sign
                };
                let turns = next_sign != approaching
                    && !jump_here
                    && !(at_period_end && self.jump == Some(0.0));
                if f_end.abs() <= self.tol_v && turns {
                    break SlipEnd::Grazing(end);
                }
                if f_end < 0.0 {
                    let lo = piece.start.max(tau0);
                    let f_lo = f_start_of(lo);
                    evaluations += 1;
                    if f_lo <= 0.0 {
                        break SlipEnd::Crossing(lo, 0.0, None);
                    }
                    let root = bracket::solve(
                        |t| {
                            let (v_r, a_r) = signal.velocity_acceleration(t);
                            (d * (v_r - (v0 + a_s * (t - tau0))), d * (a_r - a_s))
                        },
                        (lo, end),
                        (f_lo, f_end),
                        self.tol_t,
                        self.tol_f,
                        extrapolate(hints[j]),
                    );
                    hints[j] = [hints[j][1], root.t];
                    iterations += u64::from(root.iterations);
                    evaluations += u64::from(root.iterations);
                    // f' = d (a_R - a_s) at the solver's last point.
                    let a_r = root
                        .derivative
                        .is_finite()
                        .then_some(d * root.derivative + a_s);
                    break SlipEnd::Crossing(root.t, root.bracket, a_r);
                }
            }
            if at_period_end {
                break SlipEnd::PeriodEnd;
            }
            if jump_here {
                break SlipEnd::Jump(end);
            }
            j += 1;
        };
        self.counters.evaluations += evaluations;
        self.counters.root_iterations += iterations;
        let end = match outcome {
            SlipEnd::Crossing(t, _, _) | SlipEnd::Grazing(t) | SlipEnd::Jump(t) => t,
            SlipEnd::PeriodEnd => self.period,
        };
        // Closed-form slip segment [tau0, end].
        let dt = end - tau0;
        let x1 = x0 + v0 * dt + 0.5 * a_s * dt * dt;
        let v1 = v0 + a_s * dt;
        if end > tau0 && observer.wants_slip_segments() {
            let rod_start = signal.state(tau0);
            let rod_end = signal.state_before(end);
            let segment = Segment {
                period: walk.period,
                start: tau0,
                end,
                mode: walk.mode,
                slider_start: Kinematics { x: x0, v: v0 },
                slider_end: Kinematics { x: x1, v: v1 },
                rod_start: Kinematics {
                    x: rod_start.x,
                    v: rod_start.v,
                },
                rod_end: Kinematics {
                    x: rod_end.x,
                    v: rod_end.v,
                },
                slip_acceleration: a_s,
            };
            observer.segment(&segment, signal);
        }
        walk.tau = end;
        walk.x = x1;
        walk.v = v1;
        walk.departure = false;
        match outcome {
            SlipEnd::PeriodEnd => Ok(()),
            SlipEnd::Jump(_) => self.jump(walk, observer),
            SlipEnd::Crossing(t, _, _) | SlipEnd::Grazing(t) => {
                let (grazing, time_error, a_r_seen) = match outcome {
                    SlipEnd::Crossing(_, e, a) => (false, e, a),
                    _ => (true, 0.0, None),
                };
                let mode = self.mode_for(0.0, t);
                let old = walk.mode;
                walk.mode = mode;
                let a_r = a_r_seen.unwrap_or_else(|| signal.acceleration(t));
                let a_new = match mode {
                    Mode::Stick => a_r,
                    Mode::Slip(Direction::Forward) => self.slip_forward.1,
                    Mode::Slip(Direction::Backward) => self.slip_backward.1,
                };
                // An event time off by dt leaves the slider with the old
                // acceleration for dt too long or too short: its velocity is
                // off by |a_old - a_new| dt.
                walk.uncertainty += (a_s - a_new).abs() * time_error;
                match mode {
                    Mode::Stick => {
                        let v_rod = signal.velocity(t);
                        walk.uncertainty += (v_rod - walk.v).abs();
                        walk.v = v_rod;
                        walk.map_derivative = 0.0;
                    }
                    Mode::Slip(new_dir) => {
                        walk.departure = true;
                        if new_dir != dir {
                            // Perturbation of the crossing time carries over
                            // as dv_after = dv (a_R - a_new) / (a_R - a_old).
                            walk.map_derivative *= (a_r - a_new) / (a_r - a_s);
                        }
                    }
                }
                if grazing {
                    // Sticking or sliding on is decided within tol_v: the
                    // two outcomes differ by a finite amount, so no bound on
                    // the velocity error holds through a grazing.
                    walk.uncertainty = f64::INFINITY;
                }
                let kind =
                    transition(old, mode, grazing).unwrap_or(EventKind::Grazing { then: mode });
                self.emit(walk, kind, observer)
            }
        }
    }
}

/// The first iterate from the last two roots on a piece: their linear
/// extrapolation, or the last root alone.
fn extrapolate([before, last]: [f64; 2]) -> Option<f64> {
    match (before.is_finite(), last.is_finite()) {
        (true, true) => Some(2.0 * last - before),
        (_, true) => Some(last),
        _ => None,
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

/// The event a change of mode at a zero of `v_rel` is; `None` if the mode
/// does not change and it was no tangency.
fn transition(old: Mode, new: Mode, grazing: bool) -> Option<EventKind> {
    if grazing {
        return Some(EventKind::Grazing { then: new });
    }
    match (old, new) {
        (Mode::Stick, Mode::Stick) => None,
        (Mode::Stick, Mode::Slip(to)) => Some(EventKind::StickToSlip { to }),
        (Mode::Slip(_), Mode::Stick) => Some(EventKind::SlipToStick),
        (Mode::Slip(a), Mode::Slip(b)) if a != b => Some(EventKind::Reversal { to: b }),
        (Mode::Slip(_), Mode::Slip(_)) => None,
    }
}

/// Merges the partitions of `a_R - a_0^+` and `a_R - a_0^-` into band
/// pieces; a jump phase always stays a piece boundary.
fn band_pieces(plus: &Partition, minus: &Partition, jump: Option<f64>) -> Vec<BandPiece> {
    let mut knots: Vec<f64> = plus
        .pieces
        .iter()
        .chain(&minus.pieces)
        .map(|p| p.start)
        .collect();
    let period = plus.pieces.last().map_or(0.0, |p| p.end);
    knots.sort_by(f64::total_cmp);
    knots.dedup();
    knots.push(period);
    let mut pieces: Vec<BandPiece> = Vec::with_capacity(knots.len());
    for w in knots.windows(2) {
        let (start, end) = (w[0], w[1]);
        let mid = 0.5 * (start + end);
        let band = if plus.pieces[plus.locate(mid)].sign == Ordering::Greater {
            Band::Above
        } else if minus.pieces[minus.locate(mid)].sign == Ordering::Less {
            Band::Below
        } else {
            Band::Inside
        };
        match pieces.last_mut() {
            Some(last) if last.band == band && jump != Some(start) => last.end = end,
            _ => pieces.push(BandPiece { start, end, band }),
        }
    }
    pieces
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
        self.tol_v
    }

    fn last_velocity_uncertainty(&self) -> Option<f64> {
        Some(self.last_uncertainty)
    }
}
