//! The contact law both engines share: the Coulomb friction between rod and
//! slider decides the slider's mode (docs/model.md section 1).
//!
//! * **Band**: the rod acceleration `a_R` lies below, inside or above the
//!   stick band `[a_0^-, a_0^+]`. A slider at rest on the rod (`v_rel = 0`)
//!   sticks inside the band and slips in the direction `a_R` leaves it
//!   otherwise: forward above (`a_R > a_0^+`), backward below.
//! * **Mode**: with `|v_rel| <= tol_v` (the zero-velocity tolerance) the
//!   slider rests on the rod and the band decides; otherwise it slips in
//!   the direction of `v_rel = v_R - v_S`.
//! * **Accelerations**: in slip the slider accelerates with
//!   `a_f = a_d + g_t` forward or `a_b = -a_d + g_t` backward; in stick it
//!   follows the rod.
//! * **Events**: a change of mode is a typed [`EventKind`]
//!   ([`transition`]); a [`Segment`] is built from its span, mode and the
//!   slider and rod at both ends ([`Contact::segment`]).
//!
//! How an engine finds the *time* of a change (root finding on the exact
//! signal, or a fixed grid) is its own; what the change *is* is decided
//! here.

use super::{Direction, EventKind, Kinematics, Mode, Segment};
use crate::motor::Motor;
use crate::signal::RodState;

/// Where `a_R` lies relative to the stick band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Band {
    /// `a_R < a_0^-`.
    Below,
    /// `a_0^- <= a_R <= a_0^+`.
    Inside,
    /// `a_R > a_0^+`.
    Above,
}

impl Band {
    /// The mode of a slider at rest on the rod while `a_R` lies in this
    /// band: stick inside, slip forward above, slip backward below.
    #[inline]
    pub fn mode_at_rest(self) -> Mode {
        match self {
            Band::Inside => Mode::Stick,
            Band::Above => Mode::Slip(Direction::Forward),
            Band::Below => Mode::Slip(Direction::Backward),
        }
    }
}

/// The friction law of one motor with a zero-velocity tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Contact {
    /// Upper end of the stick band `a_0^+` (m/s^2).
    pub a_plus: f64,
    /// Lower end of the stick band `a_0^-` (m/s^2).
    pub a_minus: f64,
    /// Slider acceleration in forward slip `a_d + g_t` (m/s^2).
    pub a_forward: f64,
    /// Slider acceleration in backward slip `-a_d + g_t` (m/s^2).
    pub a_backward: f64,
    /// Below this `|v_rel|` (m/s) the slider rests on the rod.
    pub tol_v: f64,
}

impl Contact {
    /// The law of `motor`, with zero-velocity tolerance `tol_v` (m/s).
    pub(crate) fn new(motor: &Motor, tol_v: f64) -> Self {
        Self {
            a_plus: motor.a_0_plus(),
            a_minus: motor.a_0_minus(),
            a_forward: motor.slip_forward_acceleration(),
            a_backward: motor.slip_backward_acceleration(),
            tol_v,
        }
    }

    /// The band `a_r` lies in.
    #[inline]
    pub(crate) fn band(&self, a_r: f64) -> Band {
        if a_r > self.a_plus {
            Band::Above
        } else if a_r < self.a_minus {
            Band::Below
        } else {
            Band::Inside
        }
    }

    /// Whether `|v_rel| <= tol_v`: the slider rests on the rod.
    #[inline]
    pub(crate) fn at_rest(&self, v_rel: f64) -> bool {
        v_rel.abs() <= self.tol_v
    }

    /// The mode of a slider with relative velocity `v_rel`: slip in the
    /// direction of `v_rel`, or, at rest, the mode the band of `a_R` right
    /// after the point gives (`band` is asked only then).
    #[inline]
    pub(crate) fn mode(&self, v_rel: f64, band: impl FnOnce() -> Band) -> Mode {
        if self.at_rest(v_rel) {
            band().mode_at_rest()
        } else if v_rel > 0.0 {
            Mode::Slip(Direction::Forward)
        } else {
            Mode::Slip(Direction::Backward)
        }
    }

    /// The slider's acceleration in slip in direction `dir` (m/s^2).
    #[inline]
    pub(crate) fn slip_acceleration(&self, dir: Direction) -> f64 {
        match dir {
            Direction::Forward => self.a_forward,
            Direction::Backward => self.a_backward,
        }
    }

    /// The slider's acceleration in `mode` where the rod accelerates with
    /// `a_r` (m/s^2).
    #[inline]
    pub(crate) fn acceleration(&self, mode: Mode, a_r: f64) -> f64 {
        match mode {
            Mode::Stick => a_r,
            Mode::Slip(dir) => self.slip_acceleration(dir),
        }
    }

    /// The segment of `period` over the phases `span = [start, end]` in
    /// `mode`, with the slider and the rod at both ends (the rod's right
    /// limit at the start and left limit at the end). Its slip acceleration
    /// follows from the mode (0 in stick).
    pub(crate) fn segment(
        &self,
        period: u64,
        span: [f64; 2],
        mode: Mode,
        slider: [Kinematics; 2],
        rod: [RodState; 2],
    ) -> Segment {
        Segment {
            period,
            start: span[0],
            end: span[1],
            mode,
            slider_start: slider[0],
            slider_end: slider[1],
            rod_start: kinematics(rod[0]),
            rod_end: kinematics(rod[1]),
            slip_acceleration: match mode {
                Mode::Stick => 0.0,
                Mode::Slip(dir) => self.slip_acceleration(dir),
            },
            slider_origin: 0.0,
        }
    }
}

/// Position and velocity of a rod state.
#[inline]
fn kinematics(rod: RodState) -> Kinematics {
    Kinematics { x: rod.x, v: rod.v }
}

/// The event a change of mode is: `StickToSlip`, `SlipToStick` or
/// `Reversal`, or `Grazing` when `v_rel` only touched zero; `None` if the
/// mode does not change and it was no tangency.
#[inline]
pub(crate) fn transition(old: Mode, new: Mode, grazing: bool) -> Option<EventKind> {
    if grazing {
        return Some(EventKind::Grazing { then: new });
    }
    match (old, new) {
        (Mode::Stick, Mode::Stick) => None,
        (Mode::Stick, Mode::Slip(to)) => Some(EventKind::StickToSlip { to }),
        (Mode::Slip(_), Mode::Stick) => Some(EventKind::SlipToStick),
        (Mode::Slip(a), Mode::Slip(b)) if a != b => Some(EventKind::Reversal { to: b }),
        (Mode::Slip(_), Mode::Slip(_)) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> Contact {
        // a_0^- = -2, a_0^+ = 3, slip accelerations inside the band
        // (a_d <= a_0), tolerance 1e-3: numbers chosen for the test.
        Contact {
            a_plus: 3.0,
            a_minus: -2.0,
            a_forward: 2.5,
            a_backward: -1.5,
            tol_v: 1e-3,
        }
    }

    #[test]
    fn band_edges_belong_to_the_band() {
        // docs/model.md section 1: the band is the closed interval.
        let c = law();
        assert_eq!(c.band(3.0), Band::Inside);
        assert_eq!(c.band(-2.0), Band::Inside);
        assert_eq!(c.band(3.0 + 1e-12), Band::Above);
        assert_eq!(c.band(-2.0 - 1e-12), Band::Below);
    }

    #[test]
    fn mode_follows_v_rel_and_at_rest_the_band() {
        // docs/model.md section 1: slip in the direction of v_rel; at rest
        // stick inside the band, slip the way a_R leaves it.
        let c = law();
        let never = || -> Band { panic!("band asked although v_rel is not zero") };
        assert_eq!(c.mode(2e-3, never), Mode::Slip(Direction::Forward));
        assert_eq!(c.mode(-2e-3, never), Mode::Slip(Direction::Backward));
        assert_eq!(c.mode(1e-3, || Band::Inside), Mode::Stick);
        assert_eq!(
            c.mode(-1e-3, || Band::Above),
            Mode::Slip(Direction::Forward)
        );
        assert_eq!(c.mode(0.0, || Band::Below), Mode::Slip(Direction::Backward));
        assert_eq!(c.acceleration(Mode::Stick, 7.0), 7.0);
        assert_eq!(c.acceleration(Mode::Slip(Direction::Backward), 7.0), -1.5);
    }

    #[test]
    fn transitions_name_the_change() {
        // The event kinds of docs/interface.md for every pair of modes.
        let (s, f, b) = (
            Mode::Stick,
            Mode::Slip(Direction::Forward),
            Mode::Slip(Direction::Backward),
        );
        assert_eq!(transition(s, s, false), None);
        assert_eq!(transition(f, f, false), None);
        assert_eq!(
            transition(s, b, false),
            Some(EventKind::StickToSlip {
                to: Direction::Backward
            })
        );
        assert_eq!(transition(f, s, false), Some(EventKind::SlipToStick));
        assert_eq!(
            transition(f, b, false),
            Some(EventKind::Reversal {
                to: Direction::Backward
            })
        );
        assert_eq!(transition(f, f, true), Some(EventKind::Grazing { then: f }));
    }
}
