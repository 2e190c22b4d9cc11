//! The state a driven engine carries: at a period boundary
//! ([`DrivenState`]), and through one period (`Walk`), with the search for
//! a spring's free end being met or left.

use super::super::{Kinematics, Mode};
use crate::numerics::exp_trig::{Crossing, ExpTrig, Start};

/// The rod's and the slider's state at a period boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenState {
    /// Rod position (m).
    pub rod_x: f64,
    /// Rod velocity (m/s).
    pub rod_v: f64,
    /// Slider velocity (m/s).
    pub slider_v: f64,
    /// The mode the period ended in.
    pub mode: Mode,
    /// With a spring against the slider: its position from its start (m)
    /// and whether it is in contact with the spring's free end (always
    /// for a tied spring). Without a spring the position does not enter
    /// the motion, and is `None`.
    pub slider: Option<SliderState>,
}

/// A slider's place against a spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderState {
    /// Position from the slider's start (m).
    pub x: f64,
    /// In contact with the spring.
    pub contact: bool,
}

/// Mutable state of the walk through one period.
pub(super) struct Walk {
    pub(super) period: u64,
    pub(super) tau: f64,
    /// The rod's state at `tau`.
    pub(super) rod: Kinematics,
    /// Slider position relative to the period start (m).
    pub(super) x: f64,
    /// Slider velocity (m/s).
    pub(super) v: f64,
    pub(super) uncertainty: f64,
    /// The largest bound on an event time's error in the period (s).
    pub(super) time_error: f64,
    pub(super) events: u64,
    pub(super) mode: Mode,
    /// `v_rel = 0` at `tau` and the slip leaves zero: not an event again.
    pub(super) departure: bool,
    /// The slider's position from its start at the period start (m).
    pub(super) x_start: f64,
    /// In contact with the spring (always with a tied one).
    pub(super) contact: bool,
    /// The slider is at the spring's free end at `tau` (a contact event
    /// there, or a start there): not an event again.
    pub(super) at_end: bool,
}

impl Walk {
    /// In contact, and `x_S - x_R` at `tau`.
    pub(super) fn place(&self) -> (bool, f64) {
        (self.contact, self.x_start + self.x - self.rod.x)
    }
}

/// The first time within `(0, span]` the slider meets (`!contact`, a
/// rising zero of `f = x_S - x_gap`) or leaves (`contact`, a falling one)
/// the free end; touches and crossings the other way are passed over.
/// `at_end`: it is at the end at `s = 0`, which is not an event again.
pub(super) fn contact_change(f: &ExpTrig, span: f64, contact: bool, at_end: bool) -> Option<f64> {
    let mut from = 0.0;
    let mut start = if at_end {
        Start::AfterEvent
    } else {
        Start::Clear
    };
    loop {
        match f.first_zero(from, span, 0.0, start)? {
            Crossing::Transversal { s, rising } if rising != contact => return Some(s),
            c => {
                let s = c.s();
                if s <= from || s >= span {
                    return None;
                }
                from = s;
                start = Start::AfterEvent;
            }
        }
    }
}
