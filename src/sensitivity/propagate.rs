//! Forward propagation of a parameter direction through one period of the
//! orbit, piece by piece in closed form, and the fixed point's response
//! (docs/model.md sections 14.2 and 14.3).
//!
//! The tangent is carried at the moving event times: `dt` (the event
//! time's derivative), `dx`, `dv` (the slider's position and velocity *at*
//! the moving event time). The slider's state is continuous through every
//! event, so the tangent is too; only the rule for the next event time
//! depends on what ends a piece:
//!
//! ```text
//! slip (a_s = +-a_d + g_t), from t_a to t_b, D = t_b - t_a:
//!   dv_b = dv_a + da_s D + a_s (dt_b - dt_a)
//!   dx_b = dx_a + dv_a D + da_s D^2/2 + v_b (dt_b - dt_a)
//!   ends where v_rel = v_R - v_S = 0:
//!     dt_b = (dv_a + da_s D - a_s dt_a - dv_R(t_b)) / (a_R(t_b) - a_s)
//! stick, from t_a to t_b (x_S - x_R constant, v_S = v_R):
//!   dx_b = dx_a + [dx_R + v_R dt]_(t_b) - [dx_R + v_R dt]_(t_a)
//!   dv_b = dv_R(t_b) + a_R(t_b) dt_b
//!   ends where a_R = a_0^+- (a_R - g_t -+ a_0 = 0):
//!     dt_b = (d a_0^+- - da_R(t_b)) / j_R(t_b)
//! a rod jump, a step of the ideal signal's acceleration, the period end:
//!   dt_b = r t_b - c (a feature at a fixed normalised phase)
//! ```
//!
//! with `dx_R`, `dv_R`, `da_R` the rod's change at a fixed phase
//! ([`super::tangent`]). The denominators are `dF/dt` of the event
//! conditions (implicit function theorem); where one vanishes the event
//! structure changes ([`super::structure`]).
//!
//! Carried from `dv(0) = 1` with no parameter change this gives `P'(v*)`
//! and `dx_inf/dv`; from `dv(0) = 0` with the parameter's direction,
//! `dP/dtheta` and `dx_inf/dtheta`. Then
//!
//! ```text
//! dv*/dtheta    = (dP/dtheta) / (1 - P'(v*))
//! dx_inf/dtheta = (dx_inf/dtheta)_v + (dx_inf/dv) dv*/dtheta
//! dv_inf/dtheta = (dx_inf/dtheta) / T - v_inf r
//! ```
//!
//! A slider stuck at the period boundary starts every period with the
//! rod's velocity whatever it had: then `P' = 0` and the start tangent is
//! the rod's, `dv_R(T) + a_R(T) dT`.

use super::orbit::{End, Orbit, Piece};
use super::tangent::{RodPoint, Tangent};
use crate::engine::Mode;
use crate::motor::Motor;
use crate::signal::Signal;

/// The tangent at a moving event time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Tan {
    /// Derivative of the event time (s per unit).
    pub t: f64,
    /// Derivative of the slider's position there (relative to the period
    /// start).
    pub x: f64,
    /// Derivative of the slider's velocity there.
    pub v: f64,
    /// Derivative of the slider's position relative to the rod,
    /// `x_S - x_R`, there. At a zero of `v_rel` it does not depend on how
    /// fast the event time moves (`d(x_S - x_R)/dt = v_rel = 0`), which keeps
    /// a nearly tangential zero (a large `dt`) from cancelling in the stick
    /// that follows.
    pub xi: f64,
}

impl Tan {
    fn plus(self, k: f64, o: Tan) -> Tan {
        Tan {
            t: self.t + k * o.t,
            x: self.x + k * o.x,
            v: self.v + k * o.v,
            xi: self.xi + k * o.xi,
        }
    }
}

/// The tangents at every piece start and at the period end.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Walk {
    /// `nodes[i]` at the start of piece `i`; the last one at the period end.
    pub nodes: Vec<Tan>,
}

impl Walk {
    /// The tangent at the period end.
    pub(super) fn end(&self) -> Tan {
        *self.nodes.last().expect("a walk has its end node")
    }
}

/// What the propagation needs besides the orbit.
#[derive(Debug, Clone, Copy)]
pub(super) struct Context<'a> {
    /// The rod signal.
    pub signal: &'a Signal,
    /// The motor.
    pub motor: &'a Motor,
}

impl Context<'_> {
    fn slip_acceleration(&self, mode: Mode) -> f64 {
        match mode {
            Mode::Slip(d) => d.sign() * self.motor.a_d() + self.motor.g_t(),
            Mode::Stick => 0.0,
        }
    }

    fn edge(&self, to: crate::engine::Direction) -> f64 {
        to.sign() * self.motor.a_0() + self.motor.g_t()
    }

    /// The tangent of the slider's velocity at the period start.
    pub(super) fn start(&self, orbit: &Orbit, dir: &Tangent, dv0: f64) -> Tan {
        let v = if orbit.stuck_at_boundary {
            // v_S(0) = v_R(T^-) of the previous period, at its moving end.
            let p = RodPoint::left(self.signal, orbit.period);
            dir.rod.at(&p).v + p.a * dir.rod.period(orbit.period)
        } else {
            dv0
        };
        let rod = dir.rod.at(&RodPoint::right(self.signal, 0.0));
        Tan {
            t: 0.0,
            x: 0.0,
            v,
            xi: -rod.x,
        }
    }

    /// Carries `dir` through `pieces` from the start tangent `start`.
    pub(super) fn walk(&self, orbit: &Orbit, pieces: &[Piece], dir: &Tangent, start: Tan) -> Walk {
        let mut nodes = Vec::with_capacity(pieces.len() + 1);
        let mut tan = start;
        nodes.push(tan);
        let mut after_zero = false;
        for piece in pieces {
            tan = self.piece(orbit, piece, dir, tan, after_zero);
            after_zero = matches!(piece.end_cause, End::Crossing(_) | End::Grazing(_));
            nodes.push(tan);
        }
        Walk { nodes }
    }

    /// `dt` of a piece end at a feature of the signal (jump, period end,
    /// acceleration step).
    fn feature_time(&self, orbit: &Orbit, dir: &Tangent, t: f64) -> f64 {
        if t >= orbit.period {
            dir.rod.period(orbit.period)
        } else {
            dir.rod.feature(t)
        }
    }

    /// The tangent at the end of `piece` from the one at its start `a`;
    /// `after_zero`: the piece starts at a zero of `v_rel` (its `xi` is
    /// exact there).
    fn piece(&self, orbit: &Orbit, piece: &Piece, dir: &Tangent, a: Tan, after_zero: bool) -> Tan {
        let (ta, tb) = (piece.start, piece.end);
        let end = RodPoint::left(self.signal, tb);
        let d_end = dir.rod.at(&end);
        match piece.mode {
            Mode::Slip(d) => {
                let a_s = self.slip_acceleration(piece.mode);
                let da_s = dir.slip(d);
                let span = tb - ta;
                let at_zero = matches!(piece.end_cause, End::Crossing(_) | End::Grazing(_));
                let dt_b = if at_zero {
                    (a.v + da_s * span - a_s * a.t - d_end.v) / (end.a - a_s)
                } else {
                    self.feature_time(orbit, dir, tb)
                };
                let v_b = piece.v_start + a_s * span;
                let moved = dt_b - a.t;
                let fixed = a.x + a.v * span + 0.5 * da_s * span * span - v_b * a.t;
                // At a zero of v_rel, v_S = v_R: the moving end does not
                // move the slider relative to the rod.
                let relative = if at_zero { 0.0 } else { (v_b - end.v) * dt_b };
                Tan {
                    t: dt_b,
                    x: fixed + v_b * dt_b,
                    v: a.v + da_s * span + a_s * moved,
                    xi: fixed + relative - d_end.x,
                }
            }
            Mode::Stick => {
                let dt_b = match piece.end_cause {
                    End::BandExit(to) if matches!(self.signal, Signal::Fourier(_)) => {
                        (dir.edge(to) - d_end.a) / end.j
                    }
                    _ => self.feature_time(orbit, dir, tb),
                };
                // x_S - x_R is constant in stick, and so is its tangent.
                let xi = if after_zero {
                    a.xi
                } else {
                    let start = RodPoint::right(self.signal, ta);
                    a.x - (dir.rod.at(&start).x + start.v * a.t)
                };
                Tan {
                    t: dt_b,
                    x: xi + d_end.x + end.v * dt_b,
                    v: d_end.v + end.a * dt_b,
                    xi,
                }
            }
        }
    }
}

/// The derivative of the steady state along one branch of the event
/// structure.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Branch {
    /// `P'(v*)` as propagated (equals the engine's).
    pub map_derivative: f64,
    /// `dv*/dtheta`.
    pub boundary_velocity: f64,
    /// `dx_inf/dtheta`.
    pub step: f64,
    /// `dv_inf/dtheta`.
    pub v_inf: f64,
    /// The total tangents (the fixed point's response included) at every
    /// piece start and the period end.
    pub nodes: Vec<Tan>,
    /// The tangents along the parameter at a fixed start velocity.
    pub by_theta: Vec<Tan>,
}

/// Why a derivative does not exist.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoDerivative {
    /// `P'(v*) >= 1`: the period map does not contract, so its fixed point
    /// does not move smoothly with the parameters.
    NotContracting(f64),
}

impl Context<'_> {
    /// The derivative along the branch with these `pieces` (the orbit's
    /// own, or an alternative at a structure change).
    pub(super) fn branch(
        &self,
        orbit: &Orbit,
        pieces: &[Piece],
        dir: &Tangent,
    ) -> Result<Branch, NoDerivative> {
        let none = Tangent::none();
        let by_v = self.walk(orbit, pieces, &none, self.start(orbit, &none, 1.0));
        let by_theta = self.walk(orbit, pieces, dir, self.start(orbit, dir, 0.0));
        let p_v = by_v.end().v;
        let contraction = 1.0 - p_v;
        // NaN fails too.
        if contraction.is_nan() || contraction <= 0.0 {
            return Err(NoDerivative::NotContracting(p_v));
        }
        let dv_star = by_theta.end().v / contraction;
        let nodes: Vec<Tan> = by_theta
            .nodes
            .iter()
            .zip(&by_v.nodes)
            .map(|(t, v)| t.plus(dv_star, *v))
            .collect();
        let step = nodes.last().map_or(0.0, |n| n.x);
        let period = orbit.period;
        Ok(Branch {
            map_derivative: p_v,
            boundary_velocity: dv_star,
            step,
            v_inf: step / period - orbit.v_inf() * dir.rod.time_scale,
            nodes,
            by_theta: by_theta.nodes,
        })
    }

    /// The tangents along the start velocity alone (`dv(0) = 1`, no
    /// parameter change): `P'` at the end.
    pub(super) fn by_velocity(&self, orbit: &Orbit) -> Walk {
        let none = Tangent::none();
        self.walk(orbit, &orbit.pieces, &none, self.start(orbit, &none, 1.0))
    }

    /// The measure's helpers: band edge level for a direction.
    pub(super) fn band_edge(&self, to: crate::engine::Direction) -> f64 {
        self.edge(to)
    }

    /// Sliding acceleration of a mode (0 in stick).
    pub(super) fn sliding(&self, mode: Mode) -> f64 {
        self.slip_acceleration(mode)
    }
}
