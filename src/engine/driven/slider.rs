//! The slider's closed forms with a spring against it (docs/model.md
//! section 17, [`crate::spring`]): its motion in slip, the stuck slider's
//! required friction with the spring's force, and where a free end is met
//! or left, as exponential-trigonometric functions of the time `s` since
//! the segment start.
//!
//! * **Slip.** Out of contact (or without a spring) the slider's
//!   acceleration is the constant `a_s = ±a_d + g_t`. In contact it is a
//!   damped oscillator under the constant force `F = m_s a_s`:
//!   `x_S(s) = x_eq + y(s)`, `x_eq` where `F = F_spring` at rest
//!   ([`crate::spring::Spring::slip_equilibrium`]),
//!   `y'' + 2 sigma_s y' + omega_s^2 y = 0`, `sigma_s = b / (2 m_s)`,
//!   `omega_s^2 = k / m_s`, `y(0) = x_S0 - x_eq`, `y'(0) = v_S0`.
//! * **Stick.** `x_S = x_R + delta` (`delta` fixed at the stick's start),
//!   and the friction a stuck slider needs is
//!   `F* = m_s (a_R - g_t) + F_spring`: the band `|F*| <= mu_0 F_c` is
//!   `a_R + F_spring / m_s` in `[a_0^-, a_0^+]`. With `kappa = k / m_s`,
//!   `beta = b / m_s` the function followed is
//!   `a_R + kappa x_R + beta v_R + kappa delta + F_p / m_s` (tied),
//!   `a_R + kappa (x_R + delta - x_gap)` (free end in contact), `a_R`
//!   (out of contact): harmonics (the rod's particular solution's
//!   acceleration, position and velocity combined), a constant, and the
//!   rod's free oscillation combined the same way (a solution of the same
//!   equation).
//! * **Contact** (free end): `x_S - x_gap` crosses zero. In slip out of
//!   contact it is the quadratic `x_S0 - x_gap + v_S0 s + a_s s^2 / 2`, in
//!   contact `x_eq - x_gap + y(s)`, in stick
//!   `x_R(s) - x_R0 + x_S0 - x_gap`. The spring's force is continuous
//!   there (zero), so neither velocity nor friction mode changes.

use super::super::Kinematics;
use super::segment::ModeFunctions;
use crate::numerics::exp_trig::{DampedOscillator, ExpTrig};
use crate::spring::{Spring, SpringEnd};

/// The spring as the engine uses it, for a slider of mass `m_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SpringLaw {
    pub spring: Spring,
    slider_mass: f64,
    /// `k / m_s`.
    kappa: f64,
    /// `b / m_s`.
    beta: f64,
}

/// The slider's motion in one slip segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum SliderMotion {
    /// Constant acceleration `a` from `(x0, v0)`.
    Uniform { x0: f64, v0: f64, a: f64 },
    /// `x_eq + y(s)` on the spring.
    Oscillating { x_eq: f64, y: DampedOscillator },
}

impl SliderMotion {
    /// Position and velocity `s` after the segment start.
    pub(super) fn at(&self, s: f64) -> Kinematics {
        match *self {
            SliderMotion::Uniform { x0, v0, a } => Kinematics {
                x: x0 + v0 * s + 0.5 * a * s * s,
                v: v0 + a * s,
            },
            SliderMotion::Oscillating { x_eq, y } => {
                if s == 0.0 {
                    return Kinematics {
                        x: x_eq + y.y0,
                        v: y.y1,
                    };
                }
                let [p, v, _] = y.eval(s);
                Kinematics { x: x_eq + p, v }
            }
        }
    }

    /// The magnitudes of the terms `x_S(s)` and `v_S(s)` are summed from
    /// (a bound on their rounding is a few `eps` of them): `|x0| + |v0 s| +
    /// |a| s^2 / 2` and `|v0| + |a s|` at constant acceleration; on the
    /// spring `y = u0 c + (u1 + sigma u0) g` with `|c| <= 1`, `|g| <= G`
    /// (the oscillator's gain), so `|x_eq| + |y0| + G |y1 + sigma y0|` and
    /// `|y1| + G (sigma |y1| + omega_0^2 |y0|)`.
    pub(super) fn term_magnitudes(&self, s: f64) -> [f64; 2] {
        match *self {
            SliderMotion::Uniform { x0, v0, a } => [
                x0.abs() + (v0 * s).abs() + 0.5 * (a * s * s).abs(),
                v0.abs() + (a * s).abs(),
            ],
            SliderMotion::Oscillating { x_eq, y } => {
                let g = y.gain();
                let (u0, u1) = (y.y0.abs(), y.y1.abs());
                [
                    x_eq.abs() + u0 + g * (y.y1 + y.sigma * y.y0).abs(),
                    u1 + g * (y.sigma * u1 + y.omega0 * y.omega0 * u0),
                ]
            }
        }
    }

    /// `-v_S(s)` as the polynomial and oscillator parts of an
    /// [`ExpTrig`].
    pub(super) fn negative_velocity(&self) -> ([f64; 3], Option<DampedOscillator>) {
        match *self {
            SliderMotion::Uniform { v0, a, .. } => ([-v0, -a, 0.0], None),
            SliderMotion::Oscillating { y, .. } => {
                let d = y.derivative();
                (
                    [0.0; 3],
                    Some(DampedOscillator {
                        y0: -d.y0,
                        y1: -d.y1,
                        ..d
                    }),
                )
            }
        }
    }
}

impl SpringLaw {
    /// `spring` against a slider of mass `slider_mass` (kg).
    pub(super) fn new(spring: Spring, slider_mass: f64) -> Self {
        Self {
            spring,
            slider_mass,
            kappa: spring.stiffness / slider_mass,
            beta: spring.damping / slider_mass,
        }
    }

    /// The slider in slip from `(x0, v0)` (absolute position, m) with the
    /// friction and extra acceleration `a_s` (m/s^2), in contact or not.
    pub(super) fn slip(&self, contact: bool, x0: f64, v0: f64, a_s: f64) -> SliderMotion {
        if !contact {
            return SliderMotion::Uniform { x0, v0, a: a_s };
        }
        let x_eq = self.spring.slip_equilibrium(self.slider_mass * a_s);
        let o = self.spring.oscillator(self.slider_mass);
        SliderMotion::Oscillating {
            x_eq,
            y: DampedOscillator {
                sigma: o.sigma,
                omega0: o.omega0,
                y0: x0 - x_eq,
                y1: v0,
            },
        }
    }

    /// `m_s` (kg).
    pub(super) fn slider_mass(&self) -> f64 {
        self.slider_mass
    }

    /// The constant part of the stuck slider's spring term over `m_s`,
    /// without the rod's own position (`kappa delta + F_p / m_s` tied,
    /// `kappa (delta - x_gap)` free end in contact), or `None` out of
    /// contact; `delta = x_S - x_R`.
    fn stuck_constant(&self, contact: bool, delta: f64) -> Option<f64> {
        match self.spring.end {
            SpringEnd::Tied { preload } => Some(self.kappa * delta + preload / self.slider_mass),
            SpringEnd::Free { gap } if contact => Some(self.kappa * (delta - gap)),
            SpringEnd::Free { .. } => None,
        }
    }

    /// `a_R + F_spring / m_s - level` for each of `levels` over a stick
    /// that starts at `tau` with the rod at `rod` and the slider `delta`
    /// ahead of it, in contact or not (module docs), from the stick mode's
    /// `functions`.
    pub(super) fn stuck_functions<const N: usize>(
        &self,
        functions: &ModeFunctions,
        tau: f64,
        rod: Kinematics,
        (contact, delta): (bool, f64),
        levels: [f64; N],
    ) -> [ExpTrig; N] {
        let Some(constant) = self.stuck_constant(contact, delta) else {
            return functions.band_functions(tau, rod.x, rod.v, levels);
        };
        let (kappa, beta) = (self.kappa, self.beta);
        let p = functions.particular();
        let c = p.coefficients();
        let [acc_a, acc_b] = functions.acceleration_coefficients();
        let [vel_a, vel_b] = functions.velocity_coefficients();
        let combine = |acc: &[f64], pos: &[f64], vel: &[f64]| -> Vec<f64> {
            acc.iter()
                .zip(pos)
                .zip(vel)
                .map(|((a, x), v)| a + kappa * x + beta * v)
                .collect()
        };
        let a = combine(acc_a, c.cosines, vel_a);
        let b = combine(acc_b, c.sines, vel_b);
        let h = functions.free_at(tau, rod);
        let [h0, h1, h2, h3] = h.extend::<4>(&[h.y0, h.y1]);
        let osc = DampedOscillator {
            y0: h2 + beta * h1 + kappa * h0,
            y1: h3 + beta * h2 + kappa * h1,
            ..h
        };
        let base = kappa * p.offset() + constant;
        levels.map(|level| ExpTrig {
            poly: [base - level, 0.0, 0.0],
            w: p.omega(),
            phi: tau,
            a: a.clone(),
            b: b.clone(),
            osc: [Some(osc), None],
        })
    }

    /// `x_S(s) - x_gap` of a slip segment with `motion` (a free end).
    pub(super) fn slip_contact_function(&self, motion: &SliderMotion, w: f64) -> ExpTrig {
        let gap = self.gap();
        let (poly, osc) = match *motion {
            SliderMotion::Uniform { x0, v0, a } => ([x0 - gap, v0, 0.5 * a], None),
            SliderMotion::Oscillating { x_eq, y } => ([x_eq - gap, 0.0, 0.0], Some(y)),
        };
        ExpTrig::local(poly, w, osc)
    }

    /// `x_S(s) - x_gap = x_R(tau + s) - x_R(tau) + x_S0 - x_gap` of a stick
    /// that starts at `tau` with the rod at `rod` and the slider at `x_s0`.
    pub(super) fn stuck_contact_function(
        &self,
        functions: &ModeFunctions,
        tau: f64,
        rod: Kinematics,
        x_s0: f64,
    ) -> ExpTrig {
        let p = functions.particular();
        let c = p.coefficients();
        ExpTrig {
            poly: [p.offset() - rod.x + x_s0 - self.gap(), 0.0, 0.0],
            w: p.omega(),
            phi: tau,
            a: c.cosines.to_vec(),
            b: c.sines.to_vec(),
            osc: [Some(functions.free_at(tau, rod)), None],
        }
    }

    /// The free end's distance from the slider's start (0 for a tied
    /// spring, which has no contact events).
    pub(super) fn gap(&self) -> f64 {
        match self.spring.end {
            SpringEnd::Free { gap } => gap,
            SpringEnd::Tied { .. } => 0.0,
        }
    }

    /// Whether contact events exist.
    pub(super) fn free_end(&self) -> bool {
        matches!(self.spring.end, SpringEnd::Free { .. })
    }
}
