//! A nearer periodic orbit that appears (docs/model.md section 14.4).
//!
//! Where the motion changes by a finite amount (a grazing, a band
//! tangency, a zero of `v_rel` on a band edge with `a_R` moving inwards),
//! the period map `P(v)` jumps at the start velocity `v_c` that meets the
//! degenerate event. Two periodic orbits can then coexist, one on each side
//! of `v_c`, and the motion from rest converges to the one it meets first.
//! The orbit found is regular (its own measures are far from zero), but it
//! stops being the limit from rest when the map, on the far side of the
//! jump (towards rest), reaches the diagonal there: a fixed point appears
//! at `v_c`. The measure is that gap,
//!
//! ```text
//! g = s (P(v_c^-) - v_c),   s = sign(v*)  (the side the motion from rest comes from),
//! dg/dtheta = s (dP/dtheta + (P' - 1) dv_c/dtheta),   dv_c/dtheta = -(dm/dtheta)_v / (dm/dv),
//! ```
//!
//! with `m` the measure of the degenerate event on the orbit as a function
//! of the start velocity, and `dP/dtheta`, `P'` propagated along the period
//! from `v_c^-` (just past the jump). `v_c` is located by bisection on the
//! event sequence of the period from `v`, between the orbit and its first
//! order estimate `v* - m / (dm/dv)`.

use super::orbit::{self, Orbit};
use super::propagate::{Context, Tan};
use super::structure::{Candidate, ChangeKind};
use super::tangent::Tangent;
use crate::engine::{Event, EventKind, Mode};

/// Where a nearer orbit may appear.
#[derive(Debug, Clone)]
pub(super) struct Selection {
    /// The candidate of the orbit whose event degenerates at `v_c`.
    pub candidate: usize,
    /// The jump's kind.
    pub kind: ChangeKind,
    /// Phase of the degenerate event (s).
    pub phase: f64,
    /// The period of the map from just past the jump, towards rest.
    pub map: Orbit,
    /// `dm/dv` on the orbit.
    dm_dv: f64,
    /// `P'` just past the jump.
    map_derivative: f64,
    /// `+-1`: the side the motion from rest comes from.
    side: f64,
    /// The oriented gap `g`.
    pub m: f64,
}

/// The events of a period as a sequence of kinds and the modes they lead
/// to. A grazing that sticks counts as the zero of `v_rel` it is in the
/// limit (the engine decides it within its zero-velocity tolerance): it
/// belongs to the same branch of the map.
fn kinds(events: &[Event]) -> Vec<(&'static str, Mode)> {
    events
        .iter()
        .filter(|e| !e.kind.is_contact())
        .map(|e| match e.kind {
            EventKind::StickToSlip { to } | EventKind::Reversal { to } => {
                (e.kind.name(), Mode::Slip(to))
            }
            EventKind::SlipToStick | EventKind::Grazing { then: Mode::Stick } => {
                ("slip_to_stick", Mode::Stick)
            }
            EventKind::Grazing { then } | EventKind::Jump { then, .. } => (e.kind.name(), then),
            EventKind::ContactStart | EventKind::ContactEnd => (e.kind.name(), Mode::Stick),
        })
        .collect()
}

/// The places of `candidates` (discontinuous kinds) at which the period
/// map jumps between rest and the orbit, within `reach` (m/s) of `v*`.
pub(super) fn selections(
    ctx: &Context,
    orbit: &Orbit,
    candidates: &[Candidate],
    by_v: &[Tan],
    reach: f64,
) -> Vec<Selection> {
    let v_star = orbit.boundary_velocity;
    let side = v_star.signum();
    if orbit.stuck_at_boundary || side == 0.0 {
        return Vec::new();
    }
    let v_scale = ctx.signal.velocity_scale();
    // Past the jump by far more than the engine's zero-velocity tolerance
    // (1e-13 max |v_R|), by far less than a relevant gap.
    let past = 1e-11 * v_scale;
    let own = kinds(&orbit.events);
    let structure = |v: f64| {
        orbit::record_map(ctx.signal, ctx.motor, v)
            .ok()
            .map(|o| (kinds(&o.events) == own, o))
    };
    let none = Tangent::none();
    let mut out = Vec::new();
    for (i, c) in candidates.iter().enumerate() {
        if c.kind == ChangeKind::StickPhase {
            continue;
        }
        let dm_dv = c.derivative(ctx, orbit, &none, by_v);
        if !(dm_dv.is_finite() && dm_dv != 0.0) {
            continue;
        }
        let v_c = v_star - c.m / dm_dv;
        // Between rest and the orbit, within reach.
        let gap = (v_star - v_c) * side;
        if !(gap > past && gap <= reach && v_c * side > 0.0) {
            continue;
        }
        let mut lo = v_star - side * (2.0 * gap).min(v_star.abs());
        let mut hi = v_star;
        let Some((false, _)) = structure(lo) else {
            continue;
        };
        while (hi - lo).abs() > past {
            let mid = 0.5 * (lo + hi);
            match structure(mid) {
                Some((true, _)) => hi = mid,
                Some((false, _)) => lo = mid,
                None => break,
            }
        }
        let Some((false, map)) = structure(lo) else {
            continue;
        };
        let map_ctx_walk = ctx.by_velocity(&map);
        let map_derivative = map_ctx_walk.end().v;
        let m = side * (map.end_velocity - map.boundary_velocity);
        out.push(Selection {
            candidate: i,
            kind: c.kind,
            phase: c.phase,
            map,
            dm_dv,
            map_derivative,
            side,
            m,
        });
    }
    out
}

impl Selection {
    /// `dg/dtheta` along `dir`, with the orbit's tangents at a fixed start
    /// velocity `by_theta`.
    pub(super) fn derivative(
        &self,
        ctx: &Context,
        orbit: &Orbit,
        candidates: &[Candidate],
        dir: &Tangent,
        by_theta: &[Tan],
    ) -> f64 {
        let dm_dtheta = candidates[self.candidate].derivative(ctx, orbit, dir, by_theta);
        let dv_c = -dm_dtheta / self.dm_dv;
        let start = ctx.start(&self.map, dir, 0.0);
        let dp_dtheta = ctx.walk(&self.map, &self.map.pieces, dir, start).end().v;
        self.side * (dp_dtheta + (self.map_derivative - 1.0) * dv_c)
    }
}
