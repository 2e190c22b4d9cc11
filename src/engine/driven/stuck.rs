//! The stuck system with a spring against the slider, for a driven rod
//! that feels the slider (docs/model.md sections 16 and 17).
//!
//! In stick the slider rides on the rod, `x_S = x_R + delta` with `delta`
//! fixed for the stick phase, so the spring's force acts on the stuck
//! system: with the spring in contact,
//!
//! ```text
//! (M + m_s) x_R'' + (d + b) x_R' + (c + k) x_R = alpha u + m_s g_t - F_0 - k delta,
//! ```
//!
//! `F_0 = F_p` for a tied spring and `-k x_gap` for a free end in contact
//! (the spring's force at `x_S = 0`, `v_S = 0`). It is the actuator
//! equation of the stick mode with `d + b`, `c + k` and a constant force
//! that changes with each stick phase, so its particular solution is that
//! of `delta = 0` with its constant moved by `-k delta / (c + k)`, and its
//! free oscillation has `sigma = (d + b) / (2 (M + m_s))`,
//! `omega_0^2 = (c + k) / (M + m_s)`. Out of contact (a free end) the
//! stick mode is the one without the spring. Without the reaction the rod
//! does not feel the slider, and the spring acts on the slider alone.

use std::borrow::Cow;

use super::segment::ModeFunctions;
use crate::actuator::{DrivenRod, ModeResponse};
use crate::motor::Motor;
use crate::power::ActuatorParams;
use crate::spring::Spring;

/// The stick mode with the spring in contact.
#[derive(Debug, Clone)]
pub(super) struct StuckOnSpring {
    /// Its functions at `delta = 0`.
    base: ModeFunctions,
    /// `-k / (c + k)`: the particular constant's change per metre of
    /// `delta`.
    shift: f64,
}

impl StuckOnSpring {
    /// The stuck system of `rod` under `motor` with `spring` in contact;
    /// `None` without the reaction (the rod does not feel the slider).
    pub(super) fn new(rod: &DrivenRod, spring: &Spring, motor: &Motor) -> Option<Self> {
        if !rod.reaction() {
            return None;
        }
        let real = rod.real();
        let carried = ActuatorParams {
            damping: real.damping + spring.damping,
            stiffness: real.stiffness + spring.stiffness,
            ..*real
        };
        let ms = motor.params().slider_mass;
        let force = ms * motor.g_t() - spring.force_in_contact(0.0, 0.0);
        let response = ModeResponse::new(&carried, real.mass + ms, force, rod.voltage());
        Some(Self {
            base: ModeFunctions::new(&response),
            shift: -spring.stiffness / carried.stiffness,
        })
    }

    /// The stick mode's functions with the slider `delta = x_S - x_R`
    /// (m) ahead of the rod.
    pub(super) fn at(&self, delta: f64) -> Cow<'_, ModeFunctions> {
        if delta == 0.0 {
            Cow::Borrowed(&self.base)
        } else {
            Cow::Owned(self.base.shifted(self.shift * delta))
        }
    }
}
