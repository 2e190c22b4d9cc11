//! Sensitivities of a driven rod's `v_inf` to the real actuator's mass,
//! damping, stiffness and transfer factor, the voltage held fixed
//! (docs/model.md section 16).
//!
//! The steady period is a fixed point `z* = P(z*; theta)` of the period
//! map on the boundary state `z = (x_R, v_R, v_S)`; its step is
//! `X(z*; theta)`. With the event structure of the steady period held
//!
//! ```text
//! dz*/dtheta    = (I - dP/dz)^(-1) dP/dtheta
//! dv_inf/dtheta = (dX/dtheta + dX/dz dz*/dtheta) / T
//! ```
//!
//! (`T` is the voltage's period, held). `dP/dz`, `dP/dtheta`, `dX/dz`,
//! `dX/dtheta` come from one pass over the steady period's pieces on dual
//! numbers ([`crate::numerics::dual`]) in seven directions (the three
//! boundary values and the four parameters): each piece is the mode's
//! closed form (its particular solution, harmonic by harmonic
//! `X_k = alpha U_k / (c - M_m (k w)^2 + i d k w)`, plus the free damped
//! oscillation), written out here independently of the engine's, and every
//! event time moves by the implicit function theorem on its condition
//! (`v_rel = 0` ends a slip, `a_st` at a band edge ends a stick): one
//! Newton step on duals from the engine's root, `s - g(s)/g'(s)`, carries
//! the derivatives `ds = -dg / g'`.
//!
//! Where the steady period holds a grazing, or the actuator is within
//! `1e-6` of critical damping in a mode, no derivative is given (the
//! reason says which).

use crate::actuator::DrivenRod;
use crate::engine::{Direction, Mode, Segment};
use crate::motor::Motor;
use crate::numerics::dual::Dual;
use nalgebra::{Matrix3, Matrix3x4, RowVector3, RowVector4};

/// Derivative directions: `x_R`, `v_R`, `v_S` at the period start, then
/// `M`, `d`, `c`, `alpha`.
const N: usize = 7;
type D = Dual<N>;

/// `dv_inf / dtheta` of a driven rod for one real-actuator parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActuatorSensitivity {
    /// The scene field: `actuator.real.mass`, `.damping`, `.stiffness`,
    /// `.transfer_factor`.
    pub field: &'static str,
    /// The unit of the derivative.
    pub unit: &'static str,
    /// `dv_inf / dtheta`.
    pub value: f64,
    /// The parameter's value, for relative sensitivities
    /// `theta / v_inf dv_inf/dtheta`.
    pub at: f64,
}

/// The sensitivities of a driven rod's steady state, the voltage held
/// fixed.
#[derive(Debug, Clone, PartialEq)]
pub struct ActuatorSensitivities {
    /// `v_inf` of the steady period, from the same pass (m/s).
    pub v_inf: f64,
    /// Mass, damping, stiffness, transfer factor.
    pub entries: Vec<ActuatorSensitivity>,
}

/// The parameters' fields and units of `dv_inf/dtheta`.
const FIELDS: [(&str, &str); 4] = [
    ("actuator.real.mass", "m/(s kg)"),
    ("actuator.real.damping", "m/(s N s/m)"),
    ("actuator.real.stiffness", "m/(s N/m)"),
    ("actuator.real.transfer_factor", "m/(s N/V)"),
];

/// The sensitivities at the steady period whose pieces are `segments`
/// (in order, covering `[0, period]`), of `rod` under `motor`.
pub(crate) fn of_driven_period(
    rod: &DrivenRod,
    motor: &Motor,
    period: f64,
    segments: &[Segment],
) -> Result<ActuatorSensitivities, String> {
    let (end, step) = period_pass(rod, motor, period, segments)?;
    let real = rod.real();
    let jacobian = Matrix3::from_fn(|r, c| end[r].d[c]);
    let by_parameter = Matrix3x4::from_fn(|r, c| end[r].d[3 + c]);
    let step_by_state = RowVector3::from_fn(|_, c| step.d[c]);
    let step_by_parameter = RowVector4::from_fn(|_, c| step.d[3 + c]);
    let inverse = (Matrix3::identity() - jacobian)
        .try_inverse()
        .ok_or("the period map has a neutral direction at the steady state")?;
    let dz = inverse * by_parameter;
    let d_step = step_by_parameter + step_by_state * dz;
    let values = [
        real.mass,
        real.damping,
        real.stiffness,
        real.transfer_factor,
    ];
    Ok(ActuatorSensitivities {
        v_inf: step.v / period,
        entries: FIELDS
            .iter()
            .zip(values)
            .enumerate()
            .map(|(k, ((field, unit), at))| ActuatorSensitivity {
                field,
                unit,
                value: d_step[k] / period,
                at,
            })
            .collect(),
    })
}

/// The Jacobian `dP/dz` of the period map on the boundary state
/// `z = (x_R, v_R, v_S)` over the period whose pieces are `segments`, the
/// event structure held (the same pass as [`of_driven_period`]).
pub(crate) fn period_map_jacobian(
    rod: &DrivenRod,
    motor: &Motor,
    period: f64,
    segments: &[Segment],
) -> Result<Matrix3<f64>, String> {
    let (end, _) = period_pass(rod, motor, period, segments)?;
    Ok(Matrix3::from_fn(|r, c| end[r].d[c]))
}

/// One pass over the period on duals: the boundary state at its end and
/// the slider's step, as functions of the state at its start and of the
/// real actuator's parameters.
fn period_pass(
    rod: &DrivenRod,
    motor: &Motor,
    period: f64,
    segments: &[Segment],
) -> Result<([D; 3], D), String> {
    let pieces = merged(segments);
    let first = pieces.first().ok_or("no steady period recorded")?;
    let real = rod.real();
    let model = Model {
        rod,
        m: D::variable(real.mass, 3),
        d: D::variable(real.damping, 4),
        c: D::variable(real.stiffness, 5),
        alpha: D::variable(real.transfer_factor, 6),
        slider_mass: motor.params().slider_mass,
        friction: motor.mu_d() * motor.contact_force(),
        g_t: motor.g_t(),
        bands: [motor.a_0_minus(), motor.a_0_plus()],
        slip: [
            motor.slip_forward_acceleration(),
            motor.slip_backward_acceleration(),
        ],
    };
    let mut x = D::variable(first.rod_start.x, 0);
    let mut v = D::variable(first.rod_start.v, 1);
    let mut w = D::variable(first.slider_start.v, 2);
    let mut step = D::constant(0.0);
    let mut tau = D::constant(0.0);
    for (i, piece) in pieces.iter().enumerate() {
        let mode = model.mode(piece.mode)?;
        let free = mode.free(&model, tau, x, v);
        let s = match pieces.get(i + 1) {
            None => D::constant(period) - tau,
            Some(next) => {
                let s0 = piece.end - piece.start;
                // The event condition g and its rate g' there; a rate
                // within 1e-9 of its terms is a tangency (a grazing), where
                // the event time has no derivative.
                let (g, dg, scale) = match piece.mode {
                    Mode::Slip(dir) => {
                        let a_s = model.slip_acceleration(dir);
                        let [_, v_r, a_r] = mode.rod(&model, tau, &free, D::constant(s0));
                        (v_r - (w + a_s * s0), a_r.v - a_s, a_r.v.abs() + a_s.abs())
                    }
                    Mode::Stick => {
                        let edge = match next.mode {
                            Mode::Slip(Direction::Forward) => model.bands[1],
                            Mode::Slip(Direction::Backward) => model.bands[0],
                            Mode::Stick => return Err("two stick pieces in a row".into()),
                        };
                        let [_, _, a_r] = mode.rod(&model, tau, &free, D::constant(s0));
                        let jerk = mode.jerk(&model, tau, &free, s0);
                        let rate = model.rod.voltage().omega()
                            * model.rod.voltage().harmonics().count().max(1) as f64;
                        (a_r - edge, jerk, rate * a_r.v.abs())
                    }
                };
                if dg.is_nan() || dg.abs() <= 1e-9 * scale {
                    return Err(
                        "the steady period holds a grazing, where an event time has no derivative"
                            .into(),
                    );
                }
                D::constant(s0) - g / dg
            }
        };
        let [x1, v1, _] = mode.rod(&model, tau, &free, s);
        match piece.mode {
            Mode::Slip(dir) => {
                let a_s = model.slip_acceleration(dir);
                step = step + w * s + s * s * (0.5 * a_s);
                w = w + s * a_s;
            }
            Mode::Stick => {
                step = step + (x1 - x);
                w = v1;
            }
        }
        x = x1;
        v = v1;
        tau = tau + s;
        if let Some(next) = pieces.get(i + 1)
            && next.mode == Mode::Stick
        {
            // Slip to stick: the slider takes the rod's velocity.
            w = v;
        }
    }
    Ok(([x, v, w], step))
}

/// Consecutive pieces of the same mode as one (the engine cuts stick
/// phases at the rod's velocity extrema for its observers).
fn merged(segments: &[Segment]) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::new();
    for s in segments {
        match out.last_mut() {
            Some(last) if last.mode == s.mode && last.end == s.start => {
                last.end = s.end;
                last.rod_end = s.rod_end;
                last.slider_end = s.slider_end;
            }
            _ => out.push(*s),
        }
    }
    out
}

/// The model on duals.
struct Model<'a> {
    rod: &'a DrivenRod,
    m: D,
    d: D,
    c: D,
    alpha: D,
    slider_mass: f64,
    friction: f64,
    g_t: f64,
    /// `[a_0^-, a_0^+]`.
    bands: [f64; 2],
    /// Forward, backward slip accelerations.
    slip: [f64; 2],
}

impl Model<'_> {
    fn slip_acceleration(&self, dir: Direction) -> f64 {
        match dir {
            Direction::Forward => self.slip[0],
            Direction::Backward => self.slip[1],
        }
    }

    /// The mass and force of `mode` (docs/model.md section 16).
    fn mode(&self, mode: Mode) -> Result<ModeForm, String> {
        let (mass, force) = match (self.rod.reaction(), mode) {
            (false, _) => (self.m, 0.0),
            (true, Mode::Stick) => (self.m + self.slider_mass, self.slider_mass * self.g_t),
            (true, Mode::Slip(Direction::Forward)) => (self.m, -self.friction),
            (true, Mode::Slip(Direction::Backward)) => (self.m, self.friction),
        };
        let sigma = self.d / (mass * 2.0);
        let omega2 = self.c / mass;
        let nu2 = omega2 - sigma * sigma;
        if nu2.v.abs() <= 1e-6 * omega2.v {
            return Err("the actuator is critically damped in a mode".into());
        }
        Ok(ModeForm {
            mass,
            force,
            sigma,
            omega2,
            under: nu2.v > 0.0,
            nu: if nu2.v > 0.0 {
                nu2.sqrt()
            } else {
                (-nu2).sqrt()
            },
        })
    }
}

/// One mode's closed form on duals.
struct ModeForm {
    mass: D,
    force: f64,
    sigma: D,
    omega2: D,
    /// Under-damped (`nu` the damped frequency) or over-damped (`nu` the
    /// real rate `beta`).
    under: bool,
    nu: D,
}

/// A free oscillation's values at the segment start.
struct Free {
    h0: D,
    h1: D,
}

impl ModeForm {
    /// The particular solution's `x, v, a` at phase `tau`.
    fn particular(&self, model: &Model<'_>, tau: D) -> [D; 3] {
        let voltage = model.rod.voltage();
        let w = voltage.omega();
        let mut x = (model.alpha * voltage.offset() + self.force) / model.c;
        let (mut v, mut a) = (D::constant(0.0), D::constant(0.0));
        for (k, (p, q)) in voltage.harmonics().enumerate() {
            let kw = (k + 1) as f64 * w;
            let zr = model.c - self.mass * (kw * kw);
            let zi = model.d * kw;
            let norm = zr * zr + zi * zi;
            let xr = model.alpha * (zr * p - zi * q) / norm;
            let xi = model.alpha * (-(zr * q) - zi * p) / norm;
            let (s, c) = (tau * kw).sin_cos();
            let xk = xr * c - xi * s;
            x = x + xk;
            v = v - (xr * s + xi * c) * kw;
            a = a - xk * (kw * kw);
        }
        [x, v, a]
    }

    fn free(&self, model: &Model<'_>, tau: D, x: D, v: D) -> Free {
        let [px, pv, _] = self.particular(model, tau);
        Free {
            h0: x - px,
            h1: v - pv,
        }
    }

    /// `C(s)`, `S(s)` of the free oscillation and `e^{-sigma s}`.
    fn basis(&self, s: D) -> [D; 3] {
        let decay = (-(self.sigma * s)).exp();
        let (sn, cs) = if self.under {
            (self.nu * s).sin_cos()
        } else {
            (self.nu * s).sinh_cosh()
        };
        [cs, sn / self.nu, decay]
    }

    /// The rod's `x, v, a` after `s` from phase `tau`.
    fn rod(&self, model: &Model<'_>, tau: D, free: &Free, s: D) -> [D; 3] {
        let [px, pv, pa] = self.particular(model, tau + s);
        let [c, sn, e] = self.basis(s);
        let h = e * (free.h0 * c + (free.h1 + self.sigma * free.h0) * sn);
        let dh = e * (free.h1 * c - (self.omega2 * free.h0 + self.sigma * free.h1) * sn);
        let ddh = -(self.sigma * dh * 2.0) - self.omega2 * h;
        [px + h, pv + dh, pa + ddh]
    }

    /// The rod's jerk after `s` from `tau` (a value only): the derivative
    /// of the mode's equation, `M_m j = alpha u' - d a - c v`.
    fn jerk(&self, model: &Model<'_>, tau: D, free: &Free, s: f64) -> f64 {
        let [_, v, a] = self.rod(model, tau, free, D::constant(s));
        let du = model.rod.voltage().value(tau.v + s)[1];
        (model.alpha.v * du - model.d.v * a.v - model.c.v * v.v) / self.mass.v
    }
}
