//! The walk of the fixed-step reference through one period of a
//! prescribed rod (module [`super`]: the grid, the step law, what it
//! reports): the rod from the signal, its jumps as events, and with a
//! spring (`spring.rs`) the slider's absolute position carried from period
//! to period.

use super::spring;
use super::{FixedStepEngine, Walk};
use crate::engine::contact::transition;
use crate::engine::{EventKind, Mode, Observer, PeriodEnd, PeriodStart};
use crate::error::SimulationError;
use crate::signal::RodState;

impl FixedStepEngine<'_> {
    /// The mode of a slider with relative velocity `v_rel` at phase `tau`
    /// (right limit): slip in the direction of `v_rel`, or, within the
    /// zero-velocity tolerance, the mode the band of `a_R(tau+)` gives.
    fn mode_for(&self, v_rel: f64, tau: f64) -> Mode {
        self.contact
            .mode(v_rel, || self.contact.band(self.signal.state(tau).a))
    }

    /// [`Self::mode_for`] for the slider of `walk`: with a spring, the
    /// band at rest is shifted by `F_spring / m_s` (`spring.rs`).
    fn mode_of(&self, walk: &Walk, v_rel: f64) -> Mode {
        match self.spring {
            None => self.mode_for(v_rel, walk.tau),
            Some(spring) => self.contact.mode(v_rel, || {
                let shift = spring.accel(walk.origin + walk.x, walk.v);
                self.contact.band(self.signal.state(walk.tau).a + shift)
            }),
        }
    }
    /// A rod jump at the current phase: the slider keeps its velocity, the
    /// mode follows from the new `v_rel`.
    fn jump<O: Observer>(&mut self, walk: &mut Walk, before: RodState, observer: &mut O) {
        self.close_segment(walk, observer);
        let after = self.signal.state(walk.tau);
        let mode = self.mode_of(walk, after.v - walk.v);
        if mode == Mode::Stick {
            walk.stick_to(after.v);
        }
        walk.mode = mode;
        let kind = EventKind::Jump {
            dx: after.x - before.x,
            dv: after.v - before.v,
            then: mode,
        };
        self.emit(walk, kind, observer);
    }

    /// The slider's absolute position at the start of `period` from
    /// `start`: 0 for period 1 without a mode (from rest), else where the
    /// last period ended.
    pub(super) fn origin(&mut self, period: u64, start: &PeriodStart) -> f64 {
        if period == 1 && start.mode.is_none() {
            self.slider_x = 0.0;
        }
        self.slider_x
    }

    pub(super) fn run_period_impl<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        let rod0 = self.rod_at_start;
        let jumps = if period == 1 {
            // From rest: the rod starts at x_R = 0, v_R = 0.
            rod0.x.abs() > self.contact.tol_v * self.period || rod0.v.abs() > self.contact.tol_v
        } else {
            self.jump_at_start
        };
        let origin = self.origin(period, &start);
        let mut walk = Walk::new(period, origin, start.velocity, self.spring.as_ref());
        // The mode at 0+: the previous period's if it simply continues,
        // else from v_rel (rest within tol_v: from the band of a_R(0+)).
        let mode = match start.mode {
            Some(m) if !jumps => m,
            _ => self.mode_of(&walk, rod0.v - walk.v),
        };
        if mode == Mode::Stick {
            walk.stick_to(rod0.v);
        }
        walk.mode = mode;
        if jumps {
            let before = if period == 1 {
                RodState::default()
            } else {
                self.rod_at_end
            };
            let kind = EventKind::Jump {
                dx: rod0.x - before.x,
                dv: rod0.v - before.v,
                then: mode,
            };
            self.emit(&walk, kind, observer);
        }

        let snap = 1e-6 * self.h;
        let mut k = 0u64;
        let mut steps = 0u64;
        let mut v_rod = rod0.v;
        while k < self.steps {
            let mut next = self.node(k + 1);
            let mut advance = true;
            let mut at_jump = false;
            if let Some(tj) = self.inner_jump
                && walk.tau < tj
                && tj < next + snap
            {
                at_jump = true;
                if next - tj > snap {
                    // Split the step at the jump; the rest follows.
                    advance = false;
                }
                next = tj;
            }
            let h = next - walk.tau;
            let v_rod_end = self.signal.velocity_before(next);
            let load = self
                .spring
                .as_ref()
                .and_then(|s| s.load(walk.origin + walk.x, walk.v, h));
            let (new_mode, v1, a_req) = match &load {
                None => {
                    let (m, v1) = self.step_law(walk.mode, walk.v, v_rod_end, h);
                    (m, v1, (v_rod_end - walk.v) / h)
                }
                Some(load) => self.spring_step_law(walk.mode, walk.v, v_rod_end, h, load),
            };
            steps += 1;
            if new_mode != walk.mode {
                walk.uncertainty += h * self.acceleration_jump(walk.mode, new_mode, a_req);
                if new_mode == Mode::Stick {
                    walk.derivative = 0.0;
                }
                self.close_segment(&mut walk, observer);
                // A grid cannot tell a tangency from a crossing: every
                // change of mode is a transition (never `None` here).
                let kind = transition(walk.mode, new_mode, false);
                walk.mode = new_mode;
                if let Some(kind) = kind {
                    self.emit(&walk, kind, observer);
                }
            }
            if self.spring.is_some() {
                self.spring_cuts(
                    &mut walk,
                    load.is_some(),
                    v_rod_end - v_rod,
                    observer,
                    |w| self.rod_ends(w),
                );
                walk.tangent = match &load {
                    None => spring::free_tangent(new_mode, walk.tangent, 0.0, h),
                    Some(load) => load.tangent(new_mode, walk.tangent, 0.0, h),
                };
            }
            let (x0, v0) = (walk.origin + walk.x, walk.v);
            walk.x += 0.5 * h * (walk.v + v1);
            walk.v = v1;
            walk.tau = next;
            v_rod = v_rod_end;
            if self.spring.is_some() {
                self.tally_step(h, [x0, v0], [walk.origin + walk.x, v1], load.is_some());
                if load.is_some() && matches!(new_mode, Mode::Slip(_)) {
                    walk.step_accel = Some((v1 - v0) / h);
                }
                if let Some(kind) = self.contact_change(&mut walk, observer, |w| self.rod_ends(w)) {
                    self.emit(&walk, kind, observer);
                }
                if walk.step_accel.is_some() {
                    self.close_segment(&mut walk, observer);
                }
            }
            if at_jump {
                let before = self.signal.state_before(next);
                self.jump(&mut walk, before, observer);
                v_rod = self.signal.state(next).v;
            }
            if advance {
                k += 1;
            }
        }
        walk.tau = self.period;
        self.close_segment(&mut walk, observer);
        self.counters.evaluations += steps;
        self.counters.periods += 1;
        self.last_uncertainty = walk.uncertainty;
        self.slider_x = walk.origin + walk.x;
        let end = PeriodEnd {
            period,
            step: walk.x,
            velocity: walk.v,
            mode: walk.mode,
            map_derivative: if self.spring.is_some() {
                walk.tangent[1]
            } else {
                walk.derivative
            },
        };
        observer.period_end(&end);
        Ok(end)
    }

    /// The signal at the open segment's ends.
    pub(super) fn rod_ends(&self, w: &Walk) -> [RodState; 2] {
        [
            self.signal.state(w.segment_start),
            self.signal.state_before(w.tau),
        ]
    }
}
