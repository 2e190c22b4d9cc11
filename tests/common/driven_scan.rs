//! The driven engine's events against a dense scan (docs/model.md
//! section 16), for `tests/driven_events.rs` and
//! `examples/driven_events.rs`.
//!
//! A run's record (`driven_cases.rs`: every segment and event of a few
//! periods from rest) is checked segment by segment. Each segment is
//! integrated again from its start state with the Taylor series of
//! `driven_taylor.rs` (not the engine's closed form, nor its root finder),
//! in the mode's own equation, and its event function is sampled at
//! [`SAMPLES`] + 1 points:
//!
//! ```text
//! slip (direction s):  v_rel(t) = x_R'(t) - v_S0 - a_s (t - t_0)   keeps the sign s;
//! stick:               a_st(t)  = x_R''(t), the stuck system's      stays in [a_0^-, a_0^+];
//! ```
//!
//! every critical point between two samples (a sign change of `v_rel'` or
//! `a_st'`) is found by bisection and its value checked too. The rod's
//! state at the segment end is compared with the engine's. At every
//! segment end the scan reads what happens there from its own values, by
//! the law of docs/model.md section 1 with `a_R` replaced by `a_st`, and
//! compares it with the engine's event or its absence:
//!
//! * slip: `v_rel` is zero if `|v_rel| <= tol_v` (the engine's
//!   zero-velocity tolerance). The depth `m` of the coming minimum of
//!   `s v_rel`, from `v_rel`, `v_rel'` and `v_rel''` at the end (the local
//!   parabola; at a tangency `m = s v_rel`), says a crossing
//!   (`m < -tol_v`) or a touch (a grazing); the band of `a_st` the mode
//!   after (stick inside, slip the way it lies outside). At a period end
//!   a slider with `|v_rel| <= tol_v` rests on the rod and the band
//!   decides, without a grazing.
//! * stick: an exit if `a_st` is on a band edge and moves outward; else
//!   the end is a zero of `a_st` (where the engine cuts stick phases) or
//!   the period end.
//!
//! So the scan's counts by kind are those of the engine exactly when no
//! event is missed inside a segment and every reading agrees.
//!
//! **Values within rounding of a decision** ([`Tolerances`]). The scan's
//! own values carry its rounding, `err_v` for `v_rel` and `err_a` for
//! `a_st` (16 eps of the scale of the terms they are sums of). The
//! engine puts an event where its own computed function is within its
//! rounding bound of the threshold (`src/numerics/exp_trig/`), which is
//! wider: at an event the scan allows `loc_v` or `loc_a` (256 eps of the
//! same scales) plus the slope times the rounding of a phase, `dt`. Then
//!
//! * a reading is *ambiguous* when a deciding value lies within these
//!   allowances of its threshold: the depth `m` or `|v_rel|` within
//!   `err_v` of `tol_v`; `a_st` on a band edge at a zero of `v_rel` or
//!   from rest (the zero and the crossing of the edge coincide to
//!   rounding: slipping on, or sticking and leaving at once, are both
//!   right); `a_st` on an edge with `|a_st'| <= err_da`. Either answer
//!   holds to rounding; the engine's is counted, and so is the case. What
//!   follows such a decision is checked by the next segments' scans.
//! * inside a segment, an event the engine missed is: a sample of
//!   `s v_rel` below `-(tol_v + loc_v + |v_rel'| dt)` (a sign change), a
//!   critical point of `s v_rel` at most `tol_v - err_v` (a touch), or
//!   `a_st` beyond an edge by more than `loc_a + |a_st'| dt`, at a sample
//!   or an extremum. A critical point within `err_v` of `tol_v`, or an
//!   extremum of `a_st` within `loc_a` of an edge, is counted as a near
//!   grazing or touch. Critical points within `1e-9 T` of a segment end
//!   belong to the event there.

#![allow(dead_code)] // each includer uses a part

use crate::driven_cases::{Built, DrivenCase, Item, Record};
use crate::driven_taylor::{ModeOde, Solution};
use stickslip::engine::{Direction, Event, EventCounts, EventKind, Mode, Segment};
use stickslip::signal::Signal;

/// Samples per segment.
pub const SAMPLES: usize = 2048;

/// The scan's allowances (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub struct Tolerances {
    /// The engine's zero-velocity tolerance (m/s).
    pub tol_v: f64,
    /// Error of the scan's `v_rel` (m/s).
    pub err_v: f64,
    /// Error of the scan's `a_st` (m/s^2).
    pub err_a: f64,
    /// Error of the scan's `a_st'` (m/s^3).
    pub err_da: f64,
    /// How far from zero `v_rel` may be where the engine puts a zero
    /// (m/s), before `|v_rel'| dt` is added.
    pub loc_v: f64,
    /// How far from its edge `a_st` may be where the engine puts an exit
    /// (m/s^2), before `|a_st'| dt` is added.
    pub loc_a: f64,
    /// The rounding of an event's phase (s).
    pub dt: f64,
    /// Largest state difference at a segment end, relative to the
    /// position and velocity scales, that counts as agreement.
    pub state: f64,
}

/// The scan's own rounding, in `eps` times the scale of the terms its
/// values come from (`v_rel`: `v_scale + omega_0 x_scale + (a_0 + |g_t|) T`;
/// `a_st`: `sum_k (k w)^2 |X_k| + omega_0^2 x_scale`). The scan's rod
/// state agrees with the engine's closed form to 8 eps of the first scale
/// (`examples/driven_events.rs`).
const ROUNDING: f64 = 16.0;
/// Where the engine puts an event, in `eps` times the same scales: it
/// stops its search where its own computed function is within its
/// rounding bound of zero (`src/numerics/exp_trig/`), a generous bound;
/// measured, zeros of `v_rel` within 128 eps of its scale and exits
/// within 67 eps of `a_st`'s (`examples/driven_events.rs`).
const LOCATION: f64 = 256.0;
/// The rounding of an event's phase, in `eps T`.
const PHASE: f64 = 16.0;

/// The scan's own model of a scene: the three modes' equations and the
/// contact law, from the scene's parameters.
pub struct Model {
    /// Forward slip, backward slip, stick.
    modes: [ModeOde; 3],
    a_plus: f64,
    a_minus: f64,
    a_forward: f64,
    a_backward: f64,
    period: f64,
    x_scale: f64,
    v_scale: f64,
    a_scale: f64,
    pub tol: Tolerances,
}

impl Model {
    /// The model of `case` (built as `built`) with the engine's
    /// zero-velocity tolerance `tol_v`.
    pub fn new(case: &DrivenCase, built: &Built, tol_v: f64) -> Self {
        let p = case.motor;
        let design = case.design;
        let real = case.spec.real;
        let mass = real.mass.unwrap_or(design.mass);
        let damping = real.damping.unwrap_or(design.damping);
        let stiffness = real.stiffness.unwrap_or(design.stiffness);
        let alpha = real.transfer_factor.unwrap_or(design.transfer_factor);
        let voltage = built.rod.voltage();
        let (cos, sin): (Vec<f64>, Vec<f64>) = voltage.harmonics().unzip();
        let ode = |m: f64, force: f64| ModeOde {
            mass: m,
            damping,
            stiffness,
            alpha,
            force,
            offset: voltage.offset(),
            w: voltage.omega(),
            cos: cos.clone(),
            sin: sin.clone(),
        };
        let friction = p.mu_dynamic * p.contact_force;
        let modes = if case.spec.reaction {
            [
                ode(mass, -friction),
                ode(mass, friction),
                ode(mass + p.slider_mass, p.slider_mass * p.extra_acceleration),
            ]
        } else {
            [ode(mass, 0.0), ode(mass, 0.0), ode(mass, 0.0)]
        };
        let a0 = p.mu_static * p.contact_force / p.slider_mass;
        let ad = friction / p.slider_mass;
        let g = p.extra_acceleration;
        let signal = &built.signal;
        let period = signal.period();
        let v_scale = signal.velocity_scale();
        let x_scale = v_scale * period / std::f64::consts::PI;
        let Signal::Fourier(series) = signal else {
            unreachable!("a driven rod has a series")
        };
        let a_scale = series.acceleration_bound().max(a0 + g.abs());
        let w0 = (stiffness / mass).sqrt();
        let rate = modes[0].rate().max(modes[2].rate());
        let eps = f64::EPSILON;
        // v_rel sums the rod's velocity, whose terms carry w0 x (the free
        // oscillation), and the slider's; a_st the terms of the equation.
        let scale_v = v_scale + w0 * x_scale + (a0 + g.abs()) * period;
        let scale_a = a_scale + w0 * w0 * x_scale;
        let err_a = ROUNDING * eps * scale_a;
        Self {
            modes,
            a_plus: a0 + g,
            a_minus: -a0 + g,
            a_forward: ad + g,
            a_backward: -ad + g,
            period,
            x_scale,
            v_scale,
            a_scale,
            tol: Tolerances {
                tol_v,
                err_v: ROUNDING * eps * scale_v,
                err_a,
                err_da: err_a * rate,
                loc_v: LOCATION * eps * scale_v,
                loc_a: LOCATION * eps * scale_a,
                dt: PHASE * eps * period,
                state: 1e-12,
            },
        }
    }

    fn ode(&self, mode: Mode) -> &ModeOde {
        match mode {
            Mode::Slip(Direction::Forward) => &self.modes[0],
            Mode::Slip(Direction::Backward) => &self.modes[1],
            Mode::Stick => &self.modes[2],
        }
    }

    fn slip_acceleration(&self, dir: Direction) -> f64 {
        match dir {
            Direction::Forward => self.a_forward,
            Direction::Backward => self.a_backward,
        }
    }
}

/// What the scan reads at a segment end.
#[derive(Debug, Clone, PartialEq)]
pub enum Reading {
    /// No event.
    Nothing,
    /// This event.
    Event(EventKind),
    /// Within the scan's rounding of a decision: either reading holds.
    Ambiguous,
}

/// The outcome of scanning one run.
#[derive(Debug, Default, Clone)]
pub struct Scan {
    /// Segments scanned (of positive length).
    pub segments: usize,
    /// Points the event functions were evaluated at (samples and
    /// bisection steps).
    pub samples: usize,
    /// The engine's events by kind.
    pub engine: EventCounts,
    /// The scan's events by kind at the segment ends.
    pub scan: EventCounts,
    /// Events inside segments, which the engine did not report.
    pub missed: u64,
    /// Segment-end readings within the scan's rounding of a decision.
    pub ambiguous: u64,
    /// Critical points inside segments within the scan's rounding of
    /// `tol_v` or of a band edge (near grazings, touches from inside).
    pub near: u64,
    /// Largest difference of the rod's state at a segment end, the
    /// engine's closed form against the scan's integration, relative to
    /// the position and velocity scales.
    pub state: f64,
    /// Largest `|v_rel|` at a transversal zero and `|a_st - edge|` at an
    /// exit, as a fraction of the allowance `loc + |slope| dt`.
    pub offset: f64,
    /// Ambiguous readings at zeros of `v_rel` inside the period: the
    /// distance of `a_st` from the nearer band edge where the scan puts the
    /// zero, and the allowance it lay within (m/s^2).
    pub at_zero: Vec<[f64; 2]>,
    /// Every disagreement, described.
    pub disagreements: Vec<String>,
}

impl Scan {
    /// Adds another run's scan.
    pub fn merge(&mut self, other: Scan) {
        self.segments += other.segments;
        self.samples += other.samples;
        self.engine = self.engine.merged(&other.engine);
        self.scan = self.scan.merged(&other.scan);
        self.missed += other.missed;
        self.ambiguous += other.ambiguous;
        self.near += other.near;
        self.state = self.state.max(other.state);
        self.offset = self.offset.max(other.offset);
        self.at_zero.extend(other.at_zero);
        self.disagreements.extend(other.disagreements);
    }
}

/// Where the stuck system's acceleration `a` (with derivative `da`)
/// lies: its mode for a slider at rest on the rod, and whether it is on
/// a band edge within `reach + |da| dt` (then the mode is where it goes
/// right after; `None` if `|da|` is within rounding too).
fn band(model: &Model, a: f64, da: f64, reach: f64) -> (Option<Mode>, bool) {
    let t = model.tol;
    let (fwd, bwd) = (
        Mode::Slip(Direction::Forward),
        Mode::Slip(Direction::Backward),
    );
    let on = |edge: f64| (a - edge).abs() <= reach + da.abs() * t.dt;
    let rising = da > t.err_da;
    let falling = da < -t.err_da;
    let direction = |out: bool, into: bool, slip: Mode| {
        if out {
            Some(slip)
        } else if into {
            Some(Mode::Stick)
        } else {
            None
        }
    };
    if on(model.a_plus) {
        (direction(rising, falling, fwd), true)
    } else if on(model.a_minus) {
        (direction(falling, rising, bwd), true)
    } else if a > model.a_plus {
        (Some(fwd), false)
    } else if a < model.a_minus {
        (Some(bwd), false)
    } else {
        (Some(Mode::Stick), false)
    }
}

/// The mode an event leads to.
fn mode_after(kind: &EventKind) -> Mode {
    match *kind {
        EventKind::StickToSlip { to } | EventKind::Reversal { to } => Mode::Slip(to),
        EventKind::SlipToStick => Mode::Stick,
        EventKind::Grazing { then } | EventKind::Jump { then, .. } => then,
        EventKind::ContactStart | EventKind::ContactEnd => {
            panic!("the scanned scenes have no spring, so no contact events")
        }
    }
}

/// A zero of `g` in `[lo, hi]` where `g(lo) < 0 <= g(hi)`, by bisection to
/// the rounding of the phase.
fn bisect(g: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, period: f64, count: &mut usize) -> f64 {
    while hi - lo > 4.0 * f64::EPSILON * period {
        let mid = 0.5 * (lo + hi);
        *count += 1;
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Scans one run's record.
pub fn scan(model: &Model, record: &Record) -> Scan {
    let mut out = Scan::default();
    let mut segments: Vec<(Segment, Vec<Event>)> = Vec::new();
    for item in &record.items {
        match item {
            Item::Segment(s) => segments.push((*s, Vec::new())),
            Item::Event(e) => {
                out.engine.add(&e.kind);
                match segments.last_mut() {
                    Some(last) => last.1.push(*e),
                    None => out
                        .disagreements
                        .push(format!("event {e:?} before any segment")),
                }
            }
        }
    }
    if let Some((first, _)) = segments.first() {
        let stick = model.ode(Mode::Stick);
        // From rest at t = 0. On an edge the engine's decision (its value
        // against its rounding bound) is right either way; the segments
        // that follow are checked.
        let (a, da) = (stick.acceleration(0.0, 0.0, 0.0), stick.jerk(0.0, 0.0, 0.0));
        match band(model, a, da, model.tol.loc_a) {
            (Some(mode), false) if mode != first.mode => out.disagreements.push(format!(
                "from rest the band says {mode:?}, the engine starts in {:?}",
                first.mode
            )),
            (_, true) | (None, _) => out.ambiguous += 1,
            _ => {}
        }
    }
    for (i, (seg, events)) in segments.iter().enumerate() {
        let next = segments.get(i + 1).map(|(s, _)| s);
        let end = scan_segment(model, seg, &mut out);
        if let Some(n) = next
            && n.rod_start != seg.rod_end
        {
            out.disagreements.push(format!(
                "the rod jumps between segments: {:?} then {:?}",
                seg.rod_end, n.rod_start
            ));
        }
        for e in events {
            let here = e.period == seg.period && e.phase == seg.end;
            let next_start = e.period == seg.period + 1 && e.phase == 0.0;
            if !(here || next_start) {
                out.disagreements
                    .push(format!("event {e:?} away from the end of segment {seg:?}"));
            }
        }
        if next.is_none() && events.is_empty() {
            // The run's last segment: what follows it was not run.
            continue;
        }
        let reading = read_end(model, seg, end, &mut out);
        compare(model, seg, events, &reading, end, &mut out);
        if let Some(n) = next {
            let expected = events.last().map_or(seg.mode, |e| mode_after(&e.kind));
            if n.mode != expected {
                out.disagreements.push(format!(
                    "after {seg:?} and {events:?} the next segment is in {:?}",
                    n.mode
                ));
            }
        }
    }
    out
}

/// The engine's events at a segment end against the scan's reading.
fn compare(
    model: &Model,
    seg: &Segment,
    events: &[Event],
    reading: &Reading,
    [x, v]: [f64; 2],
    out: &mut Scan,
) {
    let inside = seg.end < model.period;
    match reading {
        Reading::Nothing => {
            if !events.is_empty() {
                out.disagreements.push(format!(
                    "engine {events:?} after {seg:?}, the scan sees none"
                ));
            } else if inside {
                match seg.mode {
                    Mode::Slip(_) => out.disagreements.push(format!(
                        "a slip ends inside the period without a zero: {seg:?}"
                    )),
                    Mode::Stick => {
                        // The engine cuts stick phases at the zeros of a_st.
                        let a = model.ode(Mode::Stick).acceleration(seg.end, x, v);
                        if a.abs() > 1e-6 * model.a_scale {
                            out.disagreements.push(format!(
                                "a stick segment ends at a_st = {a:e}, not an edge or a zero: {seg:?}"
                            ));
                        }
                    }
                }
            }
        }
        Reading::Event(kind) => {
            out.scan.add(kind);
            if events.len() != 1 || events[0].kind != *kind {
                out.disagreements.push(format!(
                    "the scan reads {kind:?}, the engine {events:?}, after {seg:?}"
                ));
            }
        }
        Reading::Ambiguous => {
            out.ambiguous += 1;
            for e in events {
                out.scan.add(&e.kind);
            }
        }
    }
}

/// What the scan reads at the end of `seg`, where its own integration
/// puts the rod at `(x, v)`.
fn read_end(model: &Model, seg: &Segment, [x, v]: [f64; 2], out: &mut Scan) -> Reading {
    let t = model.tol;
    let tau = seg.end;
    let stick = model.ode(Mode::Stick);
    let (a_st, da_st) = (stick.acceleration(tau, x, v), stick.jerk(tau, x, v));
    let Mode::Slip(dir) = seg.mode else {
        return match band(model, a_st, da_st, t.loc_a).0 {
            None => Reading::Ambiguous,
            Some(Mode::Stick) => Reading::Nothing,
            Some(Mode::Slip(to)) => {
                let edge = match to {
                    Direction::Forward => model.a_plus,
                    Direction::Backward => model.a_minus,
                };
                let allowance = t.loc_a + da_st.abs() * t.dt;
                out.offset = out.offset.max((a_st - edge).abs() / allowance);
                if (a_st - edge).abs() > allowance {
                    out.disagreements.push(format!(
                        "a_st = {a_st:e} beyond the edge {edge:e} at the end of {seg:?}"
                    ));
                }
                Reading::Event(EventKind::StickToSlip { to })
            }
        };
    };
    let ode = model.ode(seg.mode);
    let sign = dir.sign();
    let a_s = model.slip_acceleration(dir);
    let span = seg.end - seg.start;
    let f0 = sign * (v - seg.slider_start.v - a_s * span);
    let f1 = sign * (ode.acceleration(tau, x, v) - a_s);
    let f2 = sign * ode.jerk(tau, x, v);
    // At a period end v_rel is a value at a given phase, known to the
    // scan's error; elsewhere the end is the engine's event, placed to
    // its own allowance.
    let at_period_end = seg.end >= model.period;
    let reach = if at_period_end {
        t.err_v
    } else {
        t.loc_v + f1.abs() * t.dt
    };
    if f0.abs() > t.tol_v + reach {
        return Reading::Nothing;
    }
    // The coming minimum of sign v_rel, from the local parabola.
    let depth = if f1 < 0.0 {
        if f2 > 0.0 {
            f0 - f1 * f1 / (2.0 * f2)
        } else {
            f64::NEG_INFINITY
        }
    } else {
        f0
    };
    let touch = if at_period_end {
        // At a period end the slider rests on the rod if |v_rel| <= tol_v,
        // and the band decides, without a grazing (docs/model.md section 1).
        if f0.abs() > t.tol_v - reach {
            return Reading::Ambiguous;
        }
        false
    } else if depth < -(t.tol_v + t.err_v) {
        false
    } else if depth > -(t.tol_v - t.err_v) && f0.abs() <= t.tol_v - t.err_v {
        true
    } else {
        return Reading::Ambiguous;
    };
    // The band at the zero. At a crossing inside the period, a_st is read
    // where the scan puts the zero, `f0 / f1` before the end, and the zero
    // is known to `e / |v_rel'|` with `e = loc_v + err_v` (where the engine
    // may put it and the scan's own error): a_st moves by `|a_st'|` times
    // that. Near a tangency (`e / |v_rel'| > sqrt(2 e / |v_rel''|)`) the
    // line says nothing and the band is read at the end.
    let e = t.loc_v + t.err_v;
    let near_tangency = e / f1.abs() > (2.0 * e / f2.abs()).sqrt();
    let (a_zero, zero_reach) = if touch || at_period_end || near_tangency {
        (a_st, t.loc_a)
    } else {
        (
            a_st - da_st * f0 / f1,
            t.loc_a + t.err_a + da_st.abs() * e / f1.abs(),
        )
    };
    // On an edge, a zero of v_rel and a crossing of the edge coincide to
    // rounding: a slip on, or a stick that ends at once, are both right
    // (the scans of the segments that follow check what comes next).
    let (Some(then), false) = band(model, a_zero, da_st, zero_reach) else {
        if !touch && !at_period_end {
            let edge = (a_zero - model.a_plus)
                .abs()
                .min((a_zero - model.a_minus).abs());
            out.at_zero.push([edge, zero_reach]);
        }
        return Reading::Ambiguous;
    };
    let transition = |touch: bool| match (touch, then) {
        (true, _) => Some(EventKind::Grazing { then }),
        (false, Mode::Stick) => Some(EventKind::SlipToStick),
        (false, Mode::Slip(to)) if to != dir => Some(EventKind::Reversal { to }),
        (false, _) => None,
    };
    if at_period_end {
        return transition(false).map_or(Reading::Nothing, Reading::Event);
    }
    if !touch {
        out.offset = out.offset.max(f0.abs() / (t.loc_v + f1.abs() * t.dt));
    }
    // A zero that changes no mode is a grazing (the engine's name for it).
    Reading::Event(transition(touch).unwrap_or(EventKind::Grazing { then }))
}

/// Integrates `seg` from its start with the scan's own solver, checks its
/// end state against the engine's and scans its event function; returns
/// the scan's rod state at the end.
fn scan_segment(model: &Model, seg: &Segment, out: &mut Scan) -> [f64; 2] {
    let span = seg.end - seg.start;
    let ode = model.ode(seg.mode);
    let sol = Solution::new(ode, seg.start, seg.rod_start.x, seg.rod_start.v, span);
    let [x, v, _, _] = sol.at(span);
    let dx = (x - seg.rod_end.x).abs() / model.x_scale;
    let dv = (v - seg.rod_end.v).abs() / model.v_scale;
    out.state = out.state.max(dx).max(dv);
    if dx.max(dv) > model.tol.state {
        out.disagreements.push(format!(
            "the rod at the end of {seg:?}: scan ({x:e}, {v:e}), relative differences {dx:e}, {dv:e}"
        ));
    }
    if span > 0.0 {
        out.segments += 1;
        match seg.mode {
            Mode::Slip(dir) => scan_slip(model, &sol, seg, dir, out),
            Mode::Stick => scan_stick(model, &sol, span, out),
        }
    }
    [x, v]
}

/// `v_rel` keeps the sign of the slip inside the segment, and no critical
/// point of it comes within `tol_v` of zero.
fn scan_slip(model: &Model, sol: &Solution, seg: &Segment, dir: Direction, out: &mut Scan) {
    let t = model.tol;
    let sign = dir.sign();
    let a_s = model.slip_acceleration(dir);
    let v0 = seg.slider_start.v;
    let span = seg.end - seg.start;
    let edge = 1e-9 * model.period;
    // sign v_rel and sign v_rel'.
    let f = |s: f64| {
        let [_, v, a, _] = sol.at(s);
        (sign * (v - v0 - a_s * s), sign * (a - a_s))
    };
    let mut count = 0;
    let (mut prev, mut prev_s, mut below) = (f(0.0), 0.0, false);
    for i in 1..=SAMPLES {
        let s = span * i as f64 / SAMPLES as f64;
        let cur = f(s);
        let under = i < SAMPLES && cur.0 < -(t.tol_v + t.loc_v + cur.1.abs() * t.dt);
        if under && !below {
            out.missed += 1;
            out.disagreements
                .push(format!("v_rel changes sign {s:e} s into {seg:?}"));
        }
        if prev.1 < 0.0 && cur.1 >= 0.0 {
            let c = bisect(|s| f(s).1, prev_s, s, model.period, &mut count);
            let m = f(c).0;
            if c > edge && c < span - edge && m >= -(t.tol_v + t.loc_v) {
                if m <= t.tol_v - t.err_v && exit_could_be_at(model, sol, seg, dir, c) {
                    // The slip's start: its exit from a stick phase lies here
                    // within its allowance.
                    out.near += 1;
                } else if m <= t.tol_v - t.err_v {
                    out.missed += 1;
                    out.disagreements.push(format!(
                        "v_rel = {m:e} at a critical point {c:e} s into {seg:?}"
                    ));
                } else if m <= t.tol_v + t.err_v {
                    out.near += 1;
                }
            }
        }
        below = under;
        prev = cur;
        prev_s = s;
    }
    out.samples += SAMPLES + 1 + count;
}

/// Whether the slip `seg` (direction `dir`) starts from rest on the rod
/// (`|v_rel| <= tol_v`) and the stuck system's `a_st` at `c` seconds into
/// it lies within the exit allowance `loc_a + |a_st'| dt` of the edge the
/// slip leaves: a stick exit placed at `c` would be right, so a critical
/// point of `v_rel` there is the slip's own start, not a touch.
fn exit_could_be_at(model: &Model, sol: &Solution, seg: &Segment, dir: Direction, c: f64) -> bool {
    let t = model.tol;
    let v_rel_0 = seg.rod_start.v - seg.slider_start.v;
    let [x, v, _, _] = sol.at(c);
    let stick = model.ode(Mode::Stick);
    let tau = seg.start + c;
    let (a, da) = (stick.acceleration(tau, x, v), stick.jerk(tau, x, v));
    let edge = match dir {
        Direction::Forward => model.a_plus,
        Direction::Backward => model.a_minus,
    };
    v_rel_0.abs() <= t.tol_v && (a - edge).abs() <= t.loc_a + da.abs() * t.dt
}

/// `a_st` stays in the band inside the segment, its extrema included.
fn scan_stick(model: &Model, sol: &Solution, span: f64, out: &mut Scan) {
    let t = model.tol;
    let (hi, lo) = (model.a_plus, model.a_minus);
    let edge = 1e-9 * model.period;
    let f = |s: f64| {
        let [_, _, a, j] = sol.at(s);
        (a, j)
    };
    let reach = |j: f64| t.loc_a + j.abs() * t.dt;
    let outside = |(a, j): (f64, f64)| a > hi + reach(j) || a < lo - reach(j);
    let mut count = 0;
    let (mut prev, mut prev_s, mut was_out) = (f(0.0), 0.0, false);
    for i in 1..=SAMPLES {
        let s = span * i as f64 / SAMPLES as f64;
        let cur = f(s);
        let out_now = i < SAMPLES && outside(cur);
        if out_now && !was_out {
            out.missed += 1;
            out.disagreements.push(format!(
                "a_st = {:e} outside [{lo:e}, {hi:e}] {s:e} s into a stick segment",
                cur.0
            ));
        }
        // A maximum (a_st' from + to -) or a minimum between the samples.
        let turn = if prev.1 > 0.0 && cur.1 <= 0.0 {
            Some(bisect(|s| -f(s).1, prev_s, s, model.period, &mut count))
        } else if prev.1 < 0.0 && cur.1 >= 0.0 {
            Some(bisect(|s| f(s).1, prev_s, s, model.period, &mut count))
        } else {
            None
        };
        if let Some(c) = turn
            && c > edge
            && c < span - edge
        {
            let a = f(c).0;
            if outside((a, 0.0)) && !was_out && !out_now {
                out.missed += 1;
                out.disagreements.push(format!(
                    "a_st = {a:e} outside [{lo:e}, {hi:e}] at an extremum {c:e} s into a stick segment"
                ));
            } else if (a - hi).abs() <= t.loc_a || (a - lo).abs() <= t.loc_a {
                out.near += 1;
            }
        }
        was_out = out_now;
        prev = cur;
        prev_s = s;
    }
    out.samples += SAMPLES + 1 + count;
}
