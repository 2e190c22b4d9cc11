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
//!
//! The engine picks a stick phase's functions here, from the slider's
//! place (in contact, `delta`), and a recorded segment's from the slider's
//! position in it.

use std::borrow::Cow;

use super::segment::ModeFunctions;
use super::{DrivenEngine, functions_of};
use crate::actuator::{DrivenRod, ModeResponse};
use crate::engine::{Mode, Segment};
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

/// [`DrivenEngine::stick_functions`] from the engine's modes and its stick
/// mode on the spring.
pub(super) fn stick_functions_of<'m>(
    modes: &'m [ModeFunctions; 3],
    on_spring: Option<&'m StuckOnSpring>,
    (contact, delta): (bool, f64),
) -> Cow<'m, ModeFunctions> {
    match on_spring {
        Some(stuck) if contact => stuck.at(delta),
        _ => Cow::Borrowed(functions_of(modes, Mode::Stick)),
    }
}

impl DrivenEngine<'_> {
    /// The stick mode's functions with the slider at `place` = (in
    /// contact, `x_S - x_R`): with a spring in contact against a rod that
    /// feels the slider, the stuck system's with the spring (`stuck.rs`).
    pub(super) fn stick_functions(&self, place: (bool, f64)) -> Cow<'_, ModeFunctions> {
        stick_functions_of(&self.modes, self.stuck_on_spring.as_ref(), place)
    }

    /// The closed forms of `segment`'s mode, in contact with the spring
    /// where `contact` says so. Where it does not say, a stick segment's
    /// slider is in contact with a free end where it is beyond the end
    /// somewhere on the segment (its ends are events, so it is on one side
    /// throughout).
    pub(super) fn segment_functions(
        &self,
        segment: &Segment,
        contact: Option<bool>,
    ) -> Cow<'_, ModeFunctions> {
        match (segment.mode, &self.spring) {
            (Mode::Stick, Some(law)) => {
                let x = segment.slider_origin + segment.slider_start.x;
                let x_end = segment.slider_origin + segment.slider_end.x;
                let contact = contact.unwrap_or_else(|| law.spring.in_contact(x.max(x_end)));
                self.stick_functions((contact, x - segment.rod_start.x))
            }
            (mode, _) => Cow::Borrowed(self.functions(mode)),
        }
    }
}
