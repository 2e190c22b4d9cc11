//! One step of the fixed-step reference for a driven rod (docs/model.md
//! section 16): the actuator equation integrated by the trapezoidal rule,
//! coupled to the slider through a friction force held constant over the
//! step.
//!
//! ## Equations
//! With `F` the friction force on the slider (the rod feels `-F`), the
//! voltage force `f(t) = alpha u(t)` and `r = 1` when the friction acts
//! back on the rod (`reaction`), `r = 0` when it does not:
//!
//! ```text
//! rod:     M v_R' = f(t) - d v_R - c x_R - r F,   x_R' = v_R
//! slider:  m_s v_S' = F + m_s g_t
//! ```
//!
//! Over a step `[t_0, t_0 + h]` with `F` constant on it, the trapezoidal
//! rule (Newmark's average acceleration, second order and unconditionally
//! stable for the linear rod), with `f` evaluated exactly at both nodes,
//!
//! ```text
//! x_1 = x_0 + h (v_0 + v_1) / 2
//! M (v_1 - v_0) = h (f_0 + f_1) / 2 - h d (v_0 + v_1) / 2 - h c (x_0 + x_1) / 2 - r h F
//! ```
//!
//! gives the rod's end velocity in closed form,
//!
//! ```text
//! v_1 = v_free - r h F / D,
//! v_free = (P v_0 - h c x_0 + h (f_0 + f_1) / 2) / D,
//! D = M + h d / 2 + h^2 c / 4,   P = M - h d / 2 - h^2 c / 4,
//! ```
//!
//! `v_free` being where the rod would end without friction; the slider
//! ends at `v_S1 = v_S0 + h (F / m_s + g_t)`. The step's mode gives `F`:
//!
//! * **slip** in direction `s` (+1 forward, -1 backward): `F = s mu_d F_c`,
//!   so `v_1 = v_free - r s h mu_d F_c / D` and `v_S1 = v_S0 + h a_s` with
//!   the slip acceleration `a_s = s a_d + g_t`;
//! * **stick**: the `F` that makes the two end velocities equal,
//!
//!   ```text
//!   V = v_1 = v_S1 = (D v_free + m_s (v_S0 + h g_t)) / (D + m_s)   (r = 1),
//!   V = v_free                                                    (r = 0),
//!   ```
//!
//!   the impulse balance of rod and slider over the step with a common end
//!   velocity (Moreau's implicit contact). A slider stuck at `t_0`
//!   (`v_S0 = v_0`) makes this exactly the trapezoidal step of the stuck
//!   system `(M + m_s) a_R + d v_R + c x_R = f + m_s g_t`.
//!
//! The acceleration a stuck slider needs over the step is
//! `a_req = (V - v_S0) / h = F_stick / m_s + g_t`, so `a_req` lies in the
//! band `[a_0^-, a_0^+]` exactly when the stuck friction `|F_stick| <= mu_0
//! F_c`; for a slider stuck at `t_0` it is the mean over the step of the
//! stuck system's acceleration
//! `a_st = (f + r m_s g_t - d v_R - c x_R) / (M + r m_s)`. Every slip
//! candidate ends with the relative velocity
//!
//! ```text
//! v_1 - v_S1 = h (r / D + 1 / m_s) (F_stick - F),
//! ```
//!
//! so forward slip goes on (`v_rel > 0` at the step end) exactly while
//! `a_req > a_d + g_t`, the same test as the prescribed rod's; and a slip
//! decision taken because `a_req` left the band ends with `v_rel` of the
//! slip's sign (`mu_d <= mu_0`).
//!
//! ## Contract
//! [`RodStep::ends`] returns, for one step, the end velocities of rod and
//! slider in each of the three modes and `a_req`; the caller decides the
//! mode (the prescribed rod's law with this `a_req`) and advances the
//! positions by the trapezoidal rule. [`RodStep::tangent`] carries the
//! derivative of the state with respect to the slider's velocity at the
//! period start through the same step, the mode held. Nothing here divides
//! by a quantity that can vanish: `D >= M > 0`, `h > 0`.

use super::super::{Direction, Kinematics, Mode};
use super::spring::Load;
use crate::actuator::DrivenRod;
use crate::motor::Motor;
use crate::signal::FourierSignal;

/// The driven rod's step on a grid of step `h` (module doc).
#[derive(Debug, Clone)]
pub(super) struct RodStep {
    /// Step length `h` (s).
    h: f64,
    /// The voltage `u(t)` (V), as a series evaluated exactly at the nodes.
    voltage: FourierSignal,
    /// `alpha` (N/V).
    alpha: f64,
    /// `c` (N/m).
    stiffness: f64,
    /// `m_s` (kg).
    slider_mass: f64,
    /// The friction acts back on the rod (`r = 1`).
    reaction: bool,
    /// `g_t` (m/s^2).
    g_t: f64,
    /// The slider's slip accelerations `[a_d + g_t, -a_d + g_t]` (m/s^2).
    slip: [f64; 2],
    /// `D = M + h d / 2 + h^2 c / 4` (kg).
    lead: f64,
    /// `P = M - h d / 2 - h^2 c / 4` (kg).
    lag: f64,
    /// `r h mu_d F_c / D`: the rod's velocity change from the sliding
    /// friction over one step (m/s).
    kick: f64,
}

/// The end velocities of one step in each mode (m/s), and the
/// acceleration a stuck slider needs over it (m/s^2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Ends {
    /// `a_req = (V - v_S0) / h`.
    pub a_req: f64,
    /// `V`: rod and slider in stick.
    pub stick: f64,
    /// `[rod, slider]` in forward slip.
    pub forward: [f64; 2],
    /// `[rod, slider]` in backward slip.
    pub backward: [f64; 2],
}

impl Ends {
    /// `[rod, slider]` at the step end in `mode`.
    #[inline]
    pub(super) fn of(&self, mode: Mode) -> [f64; 2] {
        match mode {
            Mode::Stick => [self.stick, self.stick],
            Mode::Slip(Direction::Forward) => self.forward,
            Mode::Slip(Direction::Backward) => self.backward,
        }
    }

    /// The relative velocities `v_R - v_S` at the step end in
    /// `[forward, backward]` slip.
    #[inline]
    pub(super) fn relative(&self) -> [f64; 2] {
        [
            self.forward[0] - self.forward[1],
            self.backward[0] - self.backward[1],
        ]
    }
}

/// Derivatives of the rod's position and velocity and of the slider's
/// velocity with respect to the slider's velocity at the period start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Tangent {
    /// `d x_R` (s).
    pub x: f64,
    /// `d v_R` (1).
    pub v: f64,
    /// `d v_S` (1).
    pub slider: f64,
    /// `d x_S` (s).
    pub slider_x: f64,
}

impl Tangent {
    /// At the period start: only the slider's velocity is varied.
    pub(super) const START: Tangent = Tangent {
        x: 0.0,
        v: 0.0,
        slider: 1.0,
        slider_x: 0.0,
    };
}

impl RodStep {
    /// The step of length `h` (s) for `rod` under `motor`'s slider.
    pub(super) fn new(rod: &DrivenRod, motor: &Motor, h: f64) -> Self {
        let real = rod.real();
        let voltage = rod.voltage();
        let (cos, sin): (Vec<f64>, Vec<f64>) = voltage.harmonics().unzip();
        let series = FourierSignal::from_coefficients(voltage.period(), voltage.offset(), cos, sin)
            .with_fast_evaluation();
        let (m, d, c) = (real.mass, real.damping, real.stiffness);
        let spring = 0.5 * h * d + 0.25 * h * h * c;
        let lead = m + spring;
        let friction = motor.mu_d() * motor.contact_force();
        Self {
            h,
            voltage: series,
            alpha: real.transfer_factor,
            stiffness: c,
            slider_mass: motor.params().slider_mass,
            reaction: rod.reaction(),
            g_t: motor.g_t(),
            slip: [
                motor.slip_forward_acceleration(),
                motor.slip_backward_acceleration(),
            ],
            lead,
            lag: m - spring,
            kick: if rod.reaction() {
                h * friction / lead
            } else {
                0.0
            },
        }
    }

    /// The voltage force `f = alpha u(tau)` (N) at phase `tau`.
    #[inline]
    pub(super) fn force(&self, tau: f64) -> f64 {
        self.alpha * self.voltage.position(tau)
    }

    /// The step from the rod at `rod` and the slider at velocity `v_s`,
    /// under the forces `f = [f_0, f_1]` (N) at its two nodes.
    #[inline]
    pub(super) fn ends(&self, rod: Kinematics, v_s: f64, f: [f64; 2]) -> Ends {
        let h = self.h;
        let free =
            (self.lag * rod.v - h * self.stiffness * rod.x + 0.5 * h * (f[0] + f[1])) / self.lead;
        let stick = if self.reaction {
            (self.lead * free + self.slider_mass * (v_s + h * self.g_t))
                / (self.lead + self.slider_mass)
        } else {
            free
        };
        Ends {
            a_req: (stick - v_s) / h,
            stick,
            forward: [free - self.kick, v_s + h * self.slip[0]],
            backward: [free + self.kick, v_s + h * self.slip[1]],
        }
    }

    /// `t` carried through one step in `mode` (the derivative of
    /// [`RodStep::ends`] and of the trapezoidal position update; the
    /// voltage and the sliding friction do not depend on the state).
    #[inline]
    pub(super) fn tangent(&self, mode: Mode, t: Tangent) -> Tangent {
        let h = self.h;
        let free = (self.lag * t.v - h * self.stiffness * t.x) / self.lead;
        let [rod, slider] = match mode {
            Mode::Stick if self.reaction => {
                let s = (self.lead * free + self.slider_mass * t.slider)
                    / (self.lead + self.slider_mass);
                [s, s]
            }
            Mode::Stick => [free, free],
            Mode::Slip(_) => [free, t.slider],
        };
        Tangent {
            x: t.x + 0.5 * h * (t.v + rod),
            v: rod,
            slider,
            slider_x: t.slider_x + 0.5 * h * (t.slider + slider),
        }
    }

    /// [`RodStep::ends`] with a spring's `load` on the slider
    /// (`spring.rs`): the slider's inertia over the step is `m_s q`, the
    /// spring's force `m_s a_g` acts on it, and `a_req` is the friction's
    /// acceleration `a_fr = q (V - v_S0) / h + a_g` the band is tested on.
    #[inline]
    pub(super) fn ends_with_spring(
        &self,
        rod: Kinematics,
        v_s: f64,
        f: [f64; 2],
        load: &Load,
    ) -> Ends {
        let h = self.h;
        let free =
            (self.lag * rod.v - h * self.stiffness * rod.x + 0.5 * h * (f[0] + f[1])) / self.lead;
        let inertia = self.slider_mass * load.q;
        let stick = if self.reaction {
            (self.lead * free + inertia * v_s + h * self.slider_mass * (self.g_t - load.accel))
                / (self.lead + inertia)
        } else {
            free
        };
        Ends {
            a_req: load.friction(v_s, stick, h),
            stick,
            forward: [free - self.kick, load.slide(v_s, self.slip[0], h)],
            backward: [free + self.kick, load.slide(v_s, self.slip[1], h)],
        }
    }

    /// [`RodStep::tangent`] with a spring's `load`: `a_g` varies with the
    /// slider's start state, `d a_g = (k d x_S + (b + k h / 2) d v_S) / m_s`.
    #[inline]
    pub(super) fn tangent_with_spring(&self, mode: Mode, t: Tangent, load: &Load) -> Tangent {
        let h = self.h;
        let free = (self.lag * t.v - h * self.stiffness * t.x) / self.lead;
        let d_accel = load.dx * t.slider_x + load.dv * t.slider;
        let [rod, slider] = match mode {
            Mode::Stick if self.reaction => {
                let inertia = self.slider_mass * load.q;
                let s = (self.lead * free + inertia * t.slider - h * self.slider_mass * d_accel)
                    / (self.lead + inertia);
                [s, s]
            }
            Mode::Stick => [free, free],
            Mode::Slip(_) => [free, t.slider - h * d_accel / load.q],
        };
        Tangent {
            x: t.x + 0.5 * h * (t.v + rod),
            v: rod,
            slider,
            slider_x: t.slider_x + 0.5 * h * (t.slider + slider),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::actuator::{DrivenSpec, Load, Voltage};
    use crate::motor::MotorParams;
    use crate::power::ActuatorParams;
    use crate::signal::Signal;

    /// The default signal's rod with reaction, under a slider with a load
    /// (`g_t != 0`, so that every term counts), on a step of `T / 1000`.
    fn step() -> (RodStep, DrivenRod, Motor, f64) {
        let built = crate::Scene::default().build().expect("default scene");
        let Signal::Fourier(series) = &built.signal else {
            panic!("a Fourier signal");
        };
        let motor = Motor::new(MotorParams {
            extra_acceleration: -30.0,
            ..MotorParams::default()
        })
        .expect("valid motor");
        let design = ActuatorParams::default();
        let rod = DrivenRod::new(
            &DrivenSpec::default(),
            &design,
            Voltage::designed(series, &design),
            &motor,
        )
        .expect("valid rod");
        let h = series.period() / 1000.0;
        (RodStep::new(&rod, &motor, h), rod, motor, h)
    }

    /// A slider stuck at the step start (`v_S0 = v_0`) makes the stick
    /// step the trapezoidal step of the stuck system
    /// `(M + m_s) a + d v + c x = alpha u + m_s g_t`, solved here from its
    /// two equations directly, and `a_req` the mean of that system's
    /// acceleration (`DrivenRod::acceleration`) at the two nodes.
    #[test]
    fn stick_step_from_a_stuck_slider_is_the_stuck_systems_trapezoidal_step() {
        let (s, rod, motor, h) = step();
        let real = rod.real();
        let (m, d, c) = (real.mass + s.slider_mass, real.damping, real.stiffness);
        let load = s.slider_mass * motor.g_t();
        for (node, x0, v0) in [(0, 0.0, 0.0), (137, 3e-6, 0.4), (611, -1e-5, -0.9)] {
            let tau = [node as f64 * h, (node + 1) as f64 * h];
            let f = [s.force(tau[0]), s.force(tau[1])];
            let ends = s.ends(Kinematics { x: x0, v: v0 }, v0, f);
            // m (v1 - v0) = h (f0 + f1)/2 + h load - h d (v0 + v1)/2
            //               - h c (2 x0 + h (v0 + v1)/2)/2, linear in v1.
            let rhs = m * v0 + 0.5 * h * (f[0] + f[1]) + h * load
                - 0.5 * h * d * v0
                - h * c * x0
                - 0.25 * h * h * c * v0;
            let v1 = rhs / (m + 0.5 * h * d + 0.25 * h * h * c);
            assert!(
                (ends.stick - v1).abs() <= 1e-14 * v1.abs().max(1.0),
                "{ends:?} {v1}"
            );
            let x1 = x0 + 0.5 * h * (v0 + v1);
            let mean = 0.5
                * (rod.acceleration(Load::Stuck, tau[0], x0, v0)
                    + rod.acceleration(Load::Stuck, tau[1], x1, v1));
            assert!(
                (ends.a_req - mean).abs() <= 1e-9 * mean.abs().max(1.0),
                "{} {mean}",
                ends.a_req
            );
        }
    }

    /// Forward slip ends the step with `v_rel > 0` exactly when `a_req`
    /// exceeds the slip acceleration `a_d + g_t`, backward slip with
    /// `v_rel < 0` exactly when `a_req < -a_d + g_t` (module doc): the
    /// decision of the prescribed rod carries over. Checked across slider
    /// velocities on both sides of the thresholds.
    #[test]
    fn slip_goes_on_exactly_while_a_req_is_beyond_the_slip_acceleration() {
        let (s, _, motor, _) = step();
        let rod = Kinematics { x: 2e-6, v: 0.3 };
        let f = [1.5, 1.1];
        let mut signs = [0, 0];
        for i in -200..=200 {
            let v_s = rod.v + i as f64 * 1e-3;
            let ends = s.ends(rod, v_s, f);
            let [forward, backward] = ends.relative();
            let a_f = motor.slip_forward_acceleration();
            let a_b = motor.slip_backward_acceleration();
            assert_eq!(forward > 0.0, ends.a_req > a_f, "v_s {v_s}: {ends:?}");
            assert_eq!(backward < 0.0, ends.a_req < a_b, "v_s {v_s}: {ends:?}");
            signs[usize::from(forward > 0.0)] += 1;
        }
        // Both outcomes occur: the sweep crosses the threshold.
        assert!(signs[0] > 0 && signs[1] > 0, "{signs:?}");
    }
}
