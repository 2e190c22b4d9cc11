//! Where the event structure of the steady period changes with a
//! parameter (docs/model.md section 14.4).
//!
//! Every place where the orbit is close to another event sequence has a
//! *measure* `m`, oriented so that the orbit's own structure holds while
//! `m > 0`, with a derivative `dm/dtheta` carried by the same tangents as
//! the event times. The structure changes at `theta + Delta` with
//! `Delta = -m / (dm/dtheta)`; the orbit's branch lies on the side
//! `sign(dm/dtheta)`. The measures:
//!
//! | change | measure | kind |
//! | --- | --- | --- |
//! | a reversal becomes slip -> stick -> slip (a stick phase appears), or a short stick phase vanishes | `a_R - a_0^+-` at the zero of `v_rel` | `stick_phase` when `a_R` crosses the edge outwards there (continuous), else `band_edge` |
//! | a zero of `v_rel` becomes tangential and disappears (grazing); a slip that misses zero touches it | `v_rel` at its critical point (`a_R = a_s`) | `grazing` |
//! | a stuck slider's `a_R` touches a band edge from inside, or leaves it only briefly | `a_R - a_0^+-` at the critical point of `a_R` | `band_tangency` |
//! | an event meets a rod jump; `v_rel` after a jump is zero | time to the jump; `v_rel` after it | `jump` |
//!
//! A `stick_phase` change is continuous (a kink of `v_inf`): the branch on
//! the other side is the same period with a stick phase of zero length
//! inserted (or removed), and its derivative is computed exactly
//! ([`Candidate::alternative`]). The others change the motion by a finite
//! amount (Coulomb friction with stiction is discontinuous there), so the
//! other side's branch is a different orbit, found by a run on that side.

use super::orbit::{End, Orbit, Piece};
use super::propagate::{Context, Tan};
use super::tangent::{RodPoint, Tangent};
use crate::engine::{Direction, Mode};
use crate::signal::Signal;

/// What kind of change of the event structure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChangeKind {
    /// A stick phase of vanishing length appears at a reversal, or
    /// vanishes: `v_inf` is continuous with a kink.
    StickPhase,
    /// A zero of `v_rel` lies on a band edge where `a_R` moves into the band
    /// (or stays on the edge): stick and slip differ by a finite amount.
    BandEdge,
    /// `v_rel` touches zero tangentially.
    Grazing,
    /// `a_R` touches a band edge tangentially while the slider sticks.
    BandTangency,
    /// An event meets a rod jump, or `v_rel` is zero right after one.
    Jump,
    /// Several changes at once.
    Several,
}

impl ChangeKind {
    /// Name in reports: `stick_phase`, `band_edge`, `grazing`,
    /// `band_tangency`, `jump`, `several`.
    pub fn name(self) -> &'static str {
        match self {
            ChangeKind::StickPhase => "stick_phase",
            ChangeKind::BandEdge => "band_edge",
            ChangeKind::Grazing => "grazing",
            ChangeKind::BandTangency => "band_tangency",
            ChangeKind::Jump => "jump",
            ChangeKind::Several => "several",
        }
    }
}

/// How a measure is evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Measure {
    /// `a_R - edge` at the end of slip piece `piece` (a zero of `v_rel`).
    BandAtEnd { piece: usize, edge: Direction },
    /// `v_rel` of slip piece `piece`, continued, at the fixed critical time
    /// `t_c`.
    SlipExtremum { piece: usize, t_c: f64 },
    /// `a_R - edge` at the fixed critical time `t_c` of `a_R`.
    RodExtremum { t_c: f64, edge: Direction },
    /// End of piece `piece` minus the jump phase `tau_j`.
    JumpTime { piece: usize, tau_j: f64 },
    /// `v_rel` right after the rod jump at node `node` (phase `tau`).
    AfterJump { node: usize, tau: f64 },
}

/// A place where the event structure may change.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Candidate {
    /// What would change.
    pub kind: ChangeKind,
    /// Phase in the steady period (s).
    pub phase: f64,
    measure: Measure,
    /// `+-1`: the orbit's structure holds where `sign * raw > 0`.
    sign: f64,
    /// The oriented measure at the orbit.
    pub m: f64,
    /// For a `stick_phase` change: the pieces of the branch on the other
    /// side.
    pub alternative: Option<Vec<Piece>>,
}

impl Candidate {
    /// `dm/dtheta` (oriented) along `dir`, with the total tangents `nodes`
    /// of the orbit's branch.
    pub(super) fn derivative(
        &self,
        ctx: &Context,
        orbit: &Orbit,
        dir: &Tangent,
        nodes: &[Tan],
    ) -> f64 {
        let signal = ctx.signal;
        let raw = match self.measure {
            Measure::BandAtEnd { piece, edge } => {
                let p = RodPoint::left(signal, orbit.pieces[piece].end);
                dir.rod.at(&p).a + p.j * nodes[piece + 1].t - dir.edge(edge)
            }
            Measure::SlipExtremum { piece, t_c } => {
                let pc = &orbit.pieces[piece];
                let a_s = ctx.sliding(pc.mode);
                let da_s = match pc.mode {
                    Mode::Slip(d) => dir.slip(d),
                    Mode::Stick => 0.0,
                };
                let n = nodes[piece];
                let p = RodPoint::right(signal, t_c);
                dir.rod.at(&p).v - (n.v + da_s * (t_c - pc.start) - a_s * n.t)
            }
            Measure::RodExtremum { t_c, edge } => {
                let p = RodPoint::right(signal, t_c);
                dir.rod.at(&p).a - dir.edge(edge)
            }
            Measure::JumpTime { piece, tau_j } => {
                let moved = if tau_j >= orbit.period {
                    dir.rod.period(orbit.period)
                } else {
                    dir.rod.feature(tau_j)
                };
                nodes[piece + 1].t - moved
            }
            Measure::AfterJump { node, tau } => {
                let p = RodPoint::right(signal, tau);
                dir.rod.at(&p).v + p.a * nodes[node].t - nodes[node].v
            }
        };
        self.sign * raw
    }
}

/// Sign-changing roots of `a_R = level` in `[0, T)` (partition knots).
fn level_roots(signal: &Signal, level: f64) -> Vec<f64> {
    signal
        .partition(level)
        .pieces
        .iter()
        .skip(1)
        .map(|p| p.start)
        .collect()
}

/// Critical points of `a_R` (roots of the jerk) in `[0, T)`; none for the
/// ideal signal, whose acceleration is piecewise constant.
fn jerk_roots(signal: &Signal) -> Vec<f64> {
    match signal {
        Signal::Ideal(_) => Vec::new(),
        Signal::Fourier(s) => {
            let omega = s.omega();
            s.acceleration_poly()
                .derivative()
                .roots()
                .into_iter()
                .map(|theta| theta / omega)
                .collect()
        }
    }
}

/// Every candidate of the orbit with its oriented measure.
pub(super) fn candidates(ctx: &Context, orbit: &Orbit) -> Vec<Candidate> {
    let signal = ctx.signal;
    let period = orbit.period;
    let fourier = matches!(signal, Signal::Fourier(_));
    // v_rel is linear between the ideal signal's jumps: no critical points.
    let levels: [(Direction, Vec<f64>); 2] = [Direction::Forward, Direction::Backward].map(|d| {
        let roots = if fourier {
            level_roots(signal, ctx.sliding(Mode::Slip(d)))
        } else {
            Vec::new()
        };
        (d, roots)
    });
    let roots_for = |d: Direction| &levels[usize::from(d == Direction::Backward)].1;
    let jerk_zeros = jerk_roots(signal);
    let jumps: Vec<f64> = match signal.jump_phase() {
        Some(0.0) => vec![0.0, period],
        Some(t) => vec![t],
        None => Vec::new(),
    };
    let mut out = Vec::new();
    let mut push = |kind, phase, measure, sign: f64, alternative| {
        out.push(Candidate {
            kind,
            phase,
            measure,
            sign,
            m: 0.0,
            alternative,
        })
    };
    let pieces = &orbit.pieces;
    for (i, pc) in pieces.iter().enumerate() {
        let (ta, tb) = (pc.start, pc.end);
        match pc.mode {
            Mode::Slip(d) => {
                // Interior critical points of v_rel: a slip that misses zero.
                for &t_c in roots_for(d).iter().filter(|t| **t > ta && **t < tb) {
                    push(
                        ChangeKind::Grazing,
                        t_c,
                        Measure::SlipExtremum { piece: i, t_c },
                        d.sign(),
                        None,
                    );
                }
                match pc.end_cause {
                    End::Crossing(_) | End::Grazing(_) => {
                        // The critical point the continued slip reaches next:
                        // a crossing close to it is nearly tangential.
                        let t_c = if matches!(pc.end_cause, End::Grazing(_)) {
                            Some(tb)
                        } else {
                            roots_for(d).iter().copied().find(|t| *t >= tb)
                        };
                        if let Some(t_c) = t_c {
                            push(
                                ChangeKind::Grazing,
                                tb,
                                Measure::SlipExtremum { piece: i, t_c },
                                -d.sign(),
                                None,
                            );
                        }
                        if let End::Crossing(next) = pc.end_cause {
                            band_at_crossing(ctx, orbit, i, d, next, &mut push);
                        }
                    }
                    _ => {}
                }
            }
            Mode::Stick => {
                // a_R inside the band throughout: its extrema against the
                // edges (the middle of a piece of constant a_R).
                let inner: Vec<f64> = if fourier {
                    jerk_zeros
                        .iter()
                        .copied()
                        .filter(|t| *t > ta && *t < tb)
                        .collect()
                } else {
                    vec![0.5 * (ta + tb)]
                };
                for t_c in inner {
                    for edge in [Direction::Forward, Direction::Backward] {
                        push(
                            ChangeKind::BandTangency,
                            t_c,
                            Measure::RodExtremum { t_c, edge },
                            -edge.sign(),
                            None,
                        );
                    }
                }
                if let End::BandExit(to) = pc.end_cause
                    && fourier
                {
                    // A short excursion out of the band: its extremum.
                    if let Some(t_c) = jerk_zeros.iter().copied().find(|t| *t > tb) {
                        push(
                            ChangeKind::BandTangency,
                            tb,
                            Measure::RodExtremum { t_c, edge: to },
                            to.sign(),
                            None,
                        );
                    }
                }
            }
        }
        match pc.end_cause {
            End::Jump => {
                let sign = match pieces.get(i + 1).map(|p| p.mode) {
                    Some(Mode::Slip(d)) => d.sign(),
                    _ => 1.0,
                };
                push(
                    ChangeKind::Jump,
                    tb,
                    Measure::AfterJump {
                        node: i + 1,
                        tau: tb,
                    },
                    sign,
                    None,
                );
            }
            End::Period => {}
            _ => {
                if let Some(&tau_j) = jumps
                    .iter()
                    .min_by(|a, b| (*a - tb).abs().total_cmp(&(*b - tb).abs()))
                {
                    push(
                        ChangeKind::Jump,
                        tb,
                        Measure::JumpTime { piece: i, tau_j },
                        if tb < tau_j { -1.0 } else { 1.0 },
                        None,
                    );
                }
            }
        }
    }
    if jumps.first() == Some(&0.0) {
        let sign = match pieces.first().map(|p| p.mode) {
            Some(Mode::Slip(d)) => d.sign(),
            _ => 1.0,
        };
        push(
            ChangeKind::Jump,
            0.0,
            Measure::AfterJump { node: 0, tau: 0.0 },
            sign,
            None,
        );
    }
    for c in &mut out {
        c.m = c.sign * value(ctx, orbit, &c.measure);
    }
    out
}

/// The candidates at a zero of `v_rel` that ends slip piece `i` in
/// direction `d` and is followed by `next`: `a_R` against the band edge a
/// reversal would cross.
fn band_at_crossing(
    ctx: &Context,
    orbit: &Orbit,
    i: usize,
    d: Direction,
    next: Mode,
    push: &mut impl FnMut(ChangeKind, f64, Measure, f64, Option<Vec<Piece>>),
) {
    let pieces = &orbit.pieces;
    let pc = pieces[i];
    let tb = pc.end;
    let to = d.reversed();
    let p = RodPoint::left(ctx.signal, tb);
    // a_R crossing the edge outwards: a short stick ends by a slip in the
    // reversal's direction, so the two branches meet continuously.
    let outwards = to.sign() * p.j > 0.0;
    let measure = Measure::BandAtEnd { piece: i, edge: to };
    match next {
        Mode::Slip(_) => {
            let alternative = outwards.then(|| {
                let mut alt = pieces[..=i].to_vec();
                alt[i].end_cause = End::Crossing(Mode::Stick);
                alt.push(Piece {
                    start: tb,
                    end: tb,
                    mode: Mode::Stick,
                    v_start: p.v,
                    end_cause: End::BandExit(to),
                });
                alt.extend_from_slice(&pieces[i + 1..]);
                alt
            });
            let kind = if alternative.is_some() {
                ChangeKind::StickPhase
            } else {
                ChangeKind::BandEdge
            };
            push(kind, tb, measure, to.sign(), alternative);
        }
        Mode::Stick => {
            let short = matches!(
                (pieces.get(i + 1), pieces.get(i + 2)),
                (Some(s), Some(n))
                    if s.end_cause == End::BandExit(to) && n.mode == Mode::Slip(to)
            );
            let alternative = (outwards && short).then(|| {
                let mut alt = pieces[..=i].to_vec();
                alt[i].end_cause = End::Crossing(Mode::Slip(to));
                let mut n = pieces[i + 2];
                n.start = tb;
                n.v_start = pc.v_start + ctx.sliding(pc.mode) * (tb - pc.start);
                alt.push(n);
                alt.extend_from_slice(&pieces[i + 3..]);
                alt
            });
            let kind = if alternative.is_some() {
                ChangeKind::StickPhase
            } else {
                ChangeKind::BandEdge
            };
            push(kind, tb, measure, -to.sign(), alternative);
        }
    }
}

/// The raw (unoriented) measure at the orbit.
fn value(ctx: &Context, orbit: &Orbit, measure: &Measure) -> f64 {
    let signal = ctx.signal;
    match *measure {
        Measure::BandAtEnd { piece, edge } => {
            RodPoint::left(signal, orbit.pieces[piece].end).a - ctx.band_edge(edge)
        }
        Measure::SlipExtremum { piece, t_c } => {
            let pc = &orbit.pieces[piece];
            let v_s = pc.v_start + ctx.sliding(pc.mode) * (t_c - pc.start);
            signal.velocity(t_c) - v_s
        }
        Measure::RodExtremum { t_c, edge } => signal.acceleration(t_c) - ctx.band_edge(edge),
        Measure::JumpTime { piece, tau_j } => orbit.pieces[piece].end - tau_j,
        Measure::AfterJump { node, tau } => {
            let v_s = if node == 0 {
                orbit.boundary_velocity
            } else {
                let pc = &orbit.pieces[node - 1];
                match pc.mode {
                    Mode::Stick => signal.velocity_before(pc.end),
                    _ => pc.v_start + ctx.sliding(pc.mode) * (pc.end - pc.start),
                }
            };
            signal.velocity(tau) - v_s
        }
    }
}
