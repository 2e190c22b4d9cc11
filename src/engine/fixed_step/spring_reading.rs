//! What the spring reads in the fixed-step reference (docs/model.md
//! section 17, "Fixed-step reference"): the figures of the exact engine's
//! reading ([`SpringProfile`]) from the scheme's own nodes and steps, over
//! the periods run since [`FixedStepEngine::read_spring`].
//!
//! With node `j` at `(x_j, v_j)` (the slider's absolute position and its
//! velocity) and a step `[t_j, t_j + h]` counted in contact when the
//! spring acts at its start (`spring.rs`):
//!
//! ```text
//! spring_force_mean    = (1 / t) sum h F_bar,  F_bar = F(x_j, v_j) + k (x_(j+1) - x_j) / 2 + b (v_(j+1) - v_j) / 2
//! spring_position_mean = (1 / t) sum h (x_j + x_(j+1)) / 2
//! spring_force_max/min = the largest and least F(x_j, v_j) over the nodes
//! contact_fraction     = (1 / t) sum h over the steps in contact
//! ```
//!
//! with `t` the time read. `F_bar` (0 on a step out of contact) is the
//! spring's force the step applies (the trapezoidal rule of `spring.rs`),
//! so `h F_bar` is the step's spring impulse and the mean is the scheme's
//! own; positions follow the trapezoidal rule as the scheme moves them. A
//! free end's force at a node is `k (x_j - x_gap)` at or past the end, else
//! 0. The scheme is first order (section 12), and so is the reading; the
//! extrema over the nodes are off by `O(h)` more where the force turns
//! within a step.
//!
//! [`FixedStepEngine::continue_from`] sets the state a period starts from
//! (the slider's position, a driven rod's state) to another engine's, so
//! that the reference reads the periods that follow a state the exact
//! engine reached (`stickslip check`).

use super::FixedStepEngine;
use super::spring::SpringStep;
use crate::engine::{DrivenState, Kinematics, ProfileBounds, SpringProfile};

/// The sums of a reading in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SpringTally {
    /// Time read (s).
    time: f64,
    /// `sum h F_bar` (N s).
    impulse: f64,
    /// `sum h (x_j + x_(j+1)) / 2` (m s).
    position: f64,
    /// Time in contact (s).
    contact: f64,
    /// Largest and least force at a node (N).
    max: f64,
    min: f64,
}

impl SpringTally {
    fn new() -> Self {
        Self {
            time: 0.0,
            impulse: 0.0,
            position: 0.0,
            contact: 0.0,
            max: f64::NEG_INFINITY,
            min: f64::INFINITY,
        }
    }

    /// One step of length `h` (s) from `[x_0, v_0]` to `[x_1, v_1]`
    /// (absolute position, m; velocity, m/s), in contact (`loaded`) or not.
    #[inline]
    fn step(&mut self, spring: &SpringStep, h: f64, from: [f64; 2], to: [f64; 2], loaded: bool) {
        let [x0, v0] = from;
        let [x1, v1] = to;
        let (f0, f1) = (spring.force(x0, v0), spring.force(x1, v1));
        self.max = self.max.max(f0).max(f1);
        self.min = self.min.min(f0).min(f1);
        self.time += h;
        self.position += 0.5 * h * (x0 + x1);
        if loaded {
            self.contact += h;
            self.impulse += h * spring.step_force(from, to);
        }
    }

    fn profile(&self) -> Option<SpringProfile> {
        (self.time > 0.0).then(|| SpringProfile {
            force_mean: self.impulse / self.time,
            force_max: self.max,
            force_min: self.min,
            position_mean: self.position / self.time,
            contact_fraction: (self.contact / self.time).clamp(0.0, 1.0),
            // The reference knows no bounds on its own reading: `check`
            // measures it against the exact engine's.
            bounds: ProfileBounds::default(),
        })
    }
}

impl FixedStepEngine<'_> {
    /// Starts a reading of the spring over the periods run from now on
    /// (module doc); nothing without a spring.
    pub(crate) fn read_spring(&mut self) {
        self.tally = self.spring.is_some().then(SpringTally::new);
    }

    /// The spring's figures over the periods run since
    /// [`Self::read_spring`]; `None` without a spring or before a step.
    pub(crate) fn spring_reading(&self) -> Option<SpringProfile> {
        self.tally.as_ref().and_then(SpringTally::profile)
    }

    /// Sets the state the next period starts from (not a period 1 from
    /// rest): the slider's absolute position from `state.slider` and, for
    /// a driven rod, the rod's state and the slider's velocity and mode
    /// (a prescribed rod's are the next period's `start`). The engine then
    /// continues another engine's motion, as from a period it ran itself.
    pub(crate) fn continue_from(&mut self, state: &DrivenState) {
        if let Some(slider) = state.slider {
            self.slider_x = slider.x;
        }
        if let Some(driven) = self.driven.as_mut() {
            let rod = Kinematics {
                x: state.rod_x,
                v: state.rod_v,
            };
            driven.continue_from(rod, state.slider_v, state.mode);
        }
    }

    /// Adds a step of length `h` (s) from `[x_0, v_0]` to `[x_1, v_1]`
    /// (absolute position, velocity), in contact or not, to a reading in
    /// progress.
    #[inline]
    pub(super) fn tally_step(&mut self, h: f64, from: [f64; 2], to: [f64; 2], loaded: bool) {
        if let (Some(tally), Some(spring)) = (self.tally.as_mut(), self.spring.as_ref()) {
            tally.step(spring, h, from, to, loaded);
        }
    }
}
