//! The fixed-step reference with a driven rod (docs/model.md section 16):
//! the rod obeys the actuator's equation under the voltage, with the
//! friction acting back on it (or not, `reaction = false`), and carries its
//! state from period to period.
//!
//! ```text
//! rod:    M a_R + d v_R + c x_R = alpha u(t) - r F_f
//! slider: m_s a_S = F_f + m_s g_t
//! slip:   F_f = mu_d F_c sign(v_R - v_S)
//! stick:  v_S = v_R, held while |F_f| <= mu_0 F_c
//! ```
//!
//! ## Scheme
//! The grid is the prescribed rod's (module [`super`]): `N` steps of
//! `h = T / N` per period of the scene's signal, node `k` at `tau_k = k h`.
//! Each step (`rod.rs`) integrates the rod by the trapezoidal rule with
//! the voltage evaluated exactly at the two nodes and the friction force of
//! the step's mode held constant over it, and moves the slider with that
//! force. The mode of a step is decided by the prescribed rod's step law
//! (Moreau type, at the step end) with
//!
//! ```text
//! a_req = (V - v_S0) / h,
//! ```
//!
//! `V` the common end velocity of rod and slider in stick (the impulse
//! balance of the two bodies over the step): the mean over the step of the
//! stuck system's acceleration
//! `a_st = (alpha u + m_s g_t - d v_R - c x_R) / (M + m_s)` for a slider
//! stuck at the step start, and, for a slider whose `v_rel` reaches zero in
//! the step, the same mixture of the old slip and `a_st` as the prescribed
//! rod's `a_req`. Without reaction the rod obeys
//! `M a_R + d v_R + c x_R = alpha u` in every mode and `V` is its own end
//! velocity, which is the prescribed rod's scheme with the integrated rod in
//! place of the signal.
//!
//! **Order.** Within a mode the rod's step is second order and the slider's
//! exact (constant acceleration in slip, the rod's velocity at the nodes in
//! stick). A step holding an event is given wholly to the new mode, as for
//! the prescribed rod: the slider's velocity is off by `O(h)` after it, and
//! with reaction the rod's too (a slider coming to rest within the step
//! shares its remaining relative momentum `m_s v_rel = O(h)` with the rod).
//! With a bounded number of events per period the scheme is first order,
//! and second order for a motion without events (a slider that never
//! slips, or the rod without reaction).
//!
//! ## Periods
//! Period 1 called with `mode: None` starts from rest: rod at `x_R = 0`,
//! `v_R = 0`, slider at rest on it, its mode from the band of `a_st(0)`.
//! Every other call continues from the state the previous call ended in:
//! rod position and velocity, the slider's velocity and mode. The slider's
//! velocity is the engine's own; `start.velocity` (and `start.mode`, when
//! given) are expected to be the previous period's end, which a debug
//! build asserts. The rod never jumps, whatever the signal does.
//!
//! ## What it reports
//! Segments, events and period ends as for the prescribed rod, with the
//! rod kinematics at the segment ends the integrated rod's.
//! [`PeriodEnd::map_derivative`] is the derivative of the scheme's own
//! period map with respect to the slider's velocity at the period start,
//! the rod's start state held: carried through every step with the step's
//! mode held (`RodStep::tangent`), exact almost everywhere. Without
//! reaction it is 0 if the slider stuck in the period, else 1, as for the
//! prescribed rod; with reaction a stick step keeps the share
//! `m_s / (D + m_s)` of it in the common velocity, and the rod passes it on.
//! The analysis does not take it for the slider's period map (the rod's
//! state is part of the boundary state); it is information.
//! [`PeriodEngine::last_velocity_uncertainty`](super::PeriodEngine::last_velocity_uncertainty)
//! is `h sum |Delta a|` over the period's stick -> slip transitions and
//! reversals, with `a_req` for the stuck slider's acceleration: the
//! slider's share of the grid's error, to first order.

use super::rod::{RodStep, Tangent};
use super::spring::SpringStep;
use super::{FixedStepEngine, Walk};
use crate::actuator::{DrivenRod, Load, Voltage};
use crate::engine::DriveProfile;
use crate::engine::contact::transition;
use crate::engine::{Kinematics, Mode, Observer, PeriodEnd, PeriodStart};
use crate::motor::Motor;
use crate::signal::RodState;
use crate::signal::Signal;

/// A driven rod on the engine's grid, and the state it carries.
#[derive(Debug, Clone)]
pub(super) struct Driven {
    step: RodStep,
    /// The stuck system's acceleration `a_st` at rest at phase 0 (m/s^2):
    /// the mode a period 1 starts in.
    at_rest: f64,
    /// The share of a force on a stuck slider that the stuck system's
    /// acceleration feels, per slider mass: `m_s / (M + m_s)` with
    /// reaction, 0 without (the rod moves by its own equation).
    stuck_share: f64,
    /// The state the last period ended in; `None` before the first.
    carry: Option<Carry>,
    /// The voltage, the real actuator's `alpha` and the capacitance `C`,
    /// for the current (21).
    voltage: Voltage,
    alpha: f64,
    capacitance: f64,
    /// `(tau, x_R, v_R)` at every node of the last period run with an
    /// observer of segments ([`FixedStepEngine::drive_profile_of`]).
    nodes: Vec<[f64; 3]>,
}

/// The boundary state of a driven rod's period.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Carry {
    rod: Kinematics,
    slider: f64,
    mode: Mode,
}

impl Driven {
    /// `rod` under `motor`'s slider on a grid of step `h` (s).
    pub(super) fn new(rod: &DrivenRod, motor: &Motor, h: f64) -> Self {
        Self {
            step: RodStep::new(rod, motor, h),
            at_rest: rod.acceleration(Load::Stuck, 0.0, 0.0, 0.0),
            stuck_share: if rod.reaction() {
                let m_s = motor.params().slider_mass;
                m_s / (rod.real().mass + m_s)
            } else {
                0.0
            },
            carry: None,
            voltage: rod.voltage().clone(),
            alpha: rod.real().transfer_factor,
            capacitance: rod.design().capacitance,
            nodes: Vec::new(),
        }
    }

    /// The rod's deviation from `signal`, the voltage and the current
    /// over the last period recorded, from the nodes: extrema over the
    /// nodes, mean squares by the trapezoidal rule (periodic).
    pub(super) fn profile(&self, signal: &Signal) -> Option<DriveProfile> {
        if self.nodes.len() < 2 {
            return None;
        }
        let (mut e_max, mut i_max, mut e_sq, mut i_sq): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
        let values: Vec<[f64; 3]> = self
            .nodes
            .iter()
            .map(|[tau, x, v]| {
                let e = x - signal.position(*tau);
                let i = self.capacitance * self.voltage.value(*tau)[1] + self.alpha * v;
                [*tau, e, i]
            })
            .collect();
        for w in values.windows(2) {
            let dt = w[1][0] - w[0][0];
            e_sq += 0.5 * dt * (w[0][1].powi(2) + w[1][1].powi(2));
            i_sq += 0.5 * dt * (w[0][2].powi(2) + w[1][2].powi(2));
        }
        for [_, e, i] in &values {
            e_max = e_max.max(e.abs());
            i_max = i_max.max(i.abs());
        }
        let period = signal.period();
        Some(DriveProfile {
            rod_deviation_max: e_max,
            rod_deviation_rms: (e_sq / period).sqrt(),
            voltage_peak: self.voltage.peak(),
            voltage_rms: self.voltage.rms(),
            current_peak: i_max,
            current_rms: (i_sq / period).sqrt(),
        })
    }

    /// The friction's acceleration `a_fr` for the slider at rest at
    /// phase 0 (x_S = 0) against `spring`: `a_st` of the stuck system
    /// under the spring's force `F` plus `F / m_s` (`spring.rs`).
    fn at_rest_with(&self, spring: Option<&SpringStep>) -> f64 {
        match spring {
            None => self.at_rest,
            Some(spring) => {
                let per_slider = spring.accel(0.0, 0.0);
                self.at_rest + per_slider * (1.0 - self.stuck_share)
            }
        }
    }

    /// Sets the state the next period (not a period 1 from rest) starts
    /// from: the rod's, and the slider's velocity and mode.
    pub(super) fn continue_from(&mut self, rod: Kinematics, slider: f64, mode: Mode) {
        self.carry = Some(Carry { rod, slider, mode });
    }

    /// The rod at the end of the last period (at rest before the first).
    pub(super) fn rod_state(&self) -> Kinematics {
        self.carry.map_or(Kinematics::default(), |c| c.rod)
    }
}

/// A rod state for a segment end (a segment carries no acceleration).
fn rod_state(rod: Kinematics) -> RodState {
    RodState {
        x: rod.x,
        v: rod.v,
        a: 0.0,
    }
}

impl FixedStepEngine<'_> {
    /// One period of `driven` (module doc).
    pub(super) fn run_driven_period<O: Observer>(
        &mut self,
        driven: &mut Driven,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> PeriodEnd {
        let step = &driven.step;
        let origin = self.origin(period, &start);
        let carry = match driven.carry {
            Some(carry) if period != 1 || start.mode.is_some() => {
                debug_assert_eq!(start.velocity, carry.slider, "not the last period's end");
                debug_assert!(start.mode.is_none_or(|m| m == carry.mode));
                carry
            }
            _ => Carry {
                rod: Kinematics::default(),
                slider: 0.0,
                mode: self
                    .contact
                    .band(driven.at_rest_with(self.spring.as_ref()))
                    .mode_at_rest(),
            },
        };
        let mut walk = Walk::new(period, origin, carry.slider, self.spring.as_ref());
        walk.mode = carry.mode;
        let h = self.h;
        let mut rod = carry.rod;
        let mut segment_rod = rod;
        let mut tangent = Tangent::START;
        let record = observer.wants_segments();
        if record {
            driven.nodes.clear();
            driven.nodes.push([0.0, rod.x, rod.v]);
        }
        let mut f0 = step.force(0.0);
        let mut last_dv = 0.0;
        for k in 0..self.steps {
            let next = self.node(k + 1);
            let f1 = step.force(if next >= self.period { 0.0 } else { next });
            let load = self
                .spring
                .as_ref()
                .and_then(|s| s.load(walk.origin + walk.x, walk.v, h));
            let ends = match &load {
                None => step.ends(rod, walk.v, [f0, f1]),
                Some(load) => step.ends_with_spring(rod, walk.v, [f0, f1], load),
            };
            let new_mode = self.choose(walk.mode, ends.a_req, ends.relative(), h);
            if new_mode != walk.mode {
                walk.uncertainty += h * self.acceleration_jump(walk.mode, new_mode, ends.a_req);
                let seg = [rod_state(segment_rod), rod_state(rod)];
                self.close_segment_with(&mut walk, observer, |_| seg);
                segment_rod = rod;
                let kind = transition(walk.mode, new_mode, false);
                walk.mode = new_mode;
                if let Some(kind) = kind {
                    self.emit(&walk, kind, observer);
                }
            }
            let [v_rod, v_slider] = ends.of(new_mode);
            // A stuck slider's velocity extremum at this node ends the
            // segment (the contract of `carries_rod_state`), and so does
            // a slip step under a spring's load (`spring.rs`).
            let dv = v_rod - rod.v;
            let cut = match new_mode {
                Mode::Stick => last_dv * dv < 0.0,
                Mode::Slip(_) => load.is_some(),
            };
            if cut && observer.wants_segments() {
                let seg = [rod_state(segment_rod), rod_state(rod)];
                self.close_segment_with(&mut walk, observer, |_| seg);
                segment_rod = rod;
            }
            last_dv = dv;
            tangent = match &load {
                None => step.tangent(new_mode, tangent),
                Some(load) => step.tangent_with_spring(new_mode, tangent, load),
            };
            rod.x += 0.5 * h * (rod.v + v_rod);
            rod.v = v_rod;
            let (x0, v0) = (walk.origin + walk.x, walk.v);
            walk.x += 0.5 * h * (walk.v + v_slider);
            walk.v = v_slider;
            walk.tau = next;
            self.tally_step(
                h,
                [x0, v0],
                [walk.origin + walk.x, v_slider],
                load.is_some(),
            );
            if load.is_some() && matches!(new_mode, Mode::Slip(_)) {
                walk.step_accel = Some((v_slider - v0) / h);
            }
            let seg = [rod_state(segment_rod), rod_state(rod)];
            if let Some(kind) = self.contact_change(&mut walk, observer, |_| seg) {
                segment_rod = rod;
                self.emit(&walk, kind, observer);
            }
            if walk.step_accel.is_some() {
                self.close_segment_with(&mut walk, observer, |_| seg);
                segment_rod = rod;
            }
            f0 = f1;
            if record {
                driven.nodes.push([next, rod.x, rod.v]);
            }
        }
        walk.tau = self.period;
        let seg = [rod_state(segment_rod), rod_state(rod)];
        self.close_segment_with(&mut walk, observer, |_| seg);
        self.counters.evaluations += self.steps;
        self.counters.periods += 1;
        self.last_uncertainty = walk.uncertainty;
        self.slider_x = walk.origin + walk.x;
        driven.carry = Some(Carry {
            rod,
            slider: walk.v,
            mode: walk.mode,
        });
        let end = PeriodEnd {
            period,
            step: walk.x,
            velocity: walk.v,
            mode: walk.mode,
            map_derivative: tangent.slider,
        };
        observer.period_end(&end);
        end
    }
}
