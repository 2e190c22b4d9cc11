//! Sensitivities of a run's values to the signal's parameters
//! (docs/model.md sections 14 and 15): `d v_inf / d d_k` and
//! `d v_inf / d phi_k` of a `kind = "harmonics"` series, with the stroke
//! scaling and the shift included (both are part of the signal a series
//! stands for), and the same for the other [`Values`]. This is the one
//! place the local search takes derivatives from.
//!
//! # Where each derivative comes from ([`gradient`])
//!
//! | value | derivative |
//! | --- | --- |
//! | `v_inf` | exact: the period map's sensitivities (model 14.3, 14.6), `dv*/dtheta = (dP/dtheta) / (1 - dP/dv)`, from the steady orbit of the point's own run |
//! | `S`, `U` | exact: the closed forms (33)-(35) of the actuator model (model 4) differentiated through the stroke scaling (below) |
//! | smoothness, durability, start-up stand-in | central differences of exact runs, only when the problem asks for them |
//!
//! `velocity_per_power = v_inf / S` has the exact derivative of a
//! quotient ([`super::Objective::derivative`]). Smoothness (16) and
//! durability (18) are integrals over the steady period and the start-up
//! stand-in a property of the start-up from rest; the sensitivity machinery
//! carries none of them, so for these three alone the derivatives are
//! central differences, `(q(p + h) - q(p - h)) / (2h)` with `h` =
//! [`STEP`] times the largest amplitude for an amplitude and [`STEP`] rad
//! for a phase ([`gradient_by_differences`]; rounding part about
//! `1e-12 / STEP = 1e-7` relative, truncation about `STEP^2 = 1e-10`
//! where smooth). A scene whose run uses the fixed-step engine, and a
//! parameter whose exact derivative does not exist (a period map that does
//! not contract, a tangential event on the orbit itself), falls back to
//! central differences for that parameter.
//!
//! **Power.** The run's amplitudes are `a_k = q d_k` with
//! `q = x_hat / (max R - min R)` (model 14.6); by the envelope theorem
//! `dq/q = -(dR(t_max) - dR(t_min)) / (max R - min R)` with `dR = sin(k w_0
//! t + phi_k)` for `d_k` and `d_k cos(k w_0 t + phi_k)` for `phi_k`, so
//! `da_j/dd_k = q (delta_jk + d_j dq/q)` and `da_j/dphi_k = q d_j dq/q`
//! (the shift changes no amplitude), and `dU`, `dS` follow from (33)-(35)
//! (`power::input_power_derivative`).
//!
//! # At a change of the event structure
//!
//! `v_inf` has a kink where the event structure of the steady orbit
//! changes, and the exact sensitivities there are one-sided
//! ([`crate::sensitivity::Derivative::OneSided`]). The gradient the search
//! uses is **the derivative of the branch of the point's own steady
//! orbit** (its event structure as the run found it). At a point at any
//! positive distance from the change, however small, `v_inf` is
//! differentiable and this is its gradient; exactly on the change it is the
//! one-sided derivative towards the side whose structure the orbit has,
//! the limit of the gradients at the points of differentiability on that
//! side. That is what the Lewis-Overton analysis of BFGS on nonsmooth
//! functions assumes (gradients at points of differentiability, which the
//! iterates are with probability one), and it is consistent with the line
//! search: the slope `g.d` it tests at a trial point is the derivative of
//! `v_inf` along `d` there, from the side the run's orbit lies on. The
//! other side's derivative is not computed. A central difference across
//! the kink would instead mix the two sides.
//!
//! [`coordinate_gradient`] turns the derivatives into derivatives with
//! respect to a [`Shape`]'s coordinates by the chain rule (module docs of
//! [`super::params`]).

use super::objective::Values;
use super::params::{HarmonicSeries, Shape, wrap};
use super::problem::{Measured, Problem};
use crate::indicator::Indicator;
use crate::scene::EngineKind;
use crate::sensitivity::{self, Parameter};
use std::f64::consts::PI;

/// A parameter of a harmonic series, `k` from 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    /// The amplitude `d_k`.
    Amplitude(usize),
    /// The phase `phi_k`.
    Phase(usize),
}

impl Param {
    /// The scene field ([`Parameter`] counts from 0).
    fn field(self) -> Parameter {
        match self {
            Param::Amplitude(k) => Parameter::Amplitude(k - 1),
            Param::Phase(k) => Parameter::Phase(k - 1),
        }
    }
}

/// Relative step of the central differences (module docs).
pub(crate) const STEP: f64 = 1e-5;

/// Derivatives and what they cost.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Counted {
    /// One [`Values`] of derivatives per parameter, or why a central
    /// difference could not be taken.
    pub values: Result<Vec<Values>, String>,
    /// Simulator runs made for them (the central differences, up to a
    /// failure included).
    pub runs: u64,
}

/// The series with one parameter moved by `delta`; an amplitude moved
/// below 0 becomes the positive amplitude with the phase plus `pi`
/// (the same signal).
fn moved(series: &HarmonicSeries, param: Param, delta: f64) -> HarmonicSeries {
    let mut s = series.clone();
    match param {
        Param::Amplitude(k) => {
            let d = s.amplitudes[k - 1] + delta;
            if d < 0.0 {
                s.amplitudes[k - 1] = -d;
                s.phases[k - 1] = wrap(s.phases[k - 1] + PI);
            } else {
                s.amplitudes[k - 1] = d;
            }
        }
        Param::Phase(k) => s.phases[k - 1] += delta,
    }
    s
}

/// The central difference of every `Values` quantity along one parameter
/// (module docs).
fn central(problem: &Problem, series: &HarmonicSeries, param: Param) -> Result<Values, String> {
    let largest = series.amplitudes.iter().copied().fold(0.0, f64::max);
    let h = match param {
        Param::Amplitude(_) => STEP * largest,
        Param::Phase(_) => STEP,
    };
    let run = |delta: f64| problem.measure(problem.spec(&moved(series, param, delta)));
    let plus = run(h).map_err(|e| format!("{param:?} + {h:e}: {e}"))?;
    let minus = run(-h).map_err(|e| format!("{param:?} - {h:e}: {e}"))?;
    Ok(Values::difference(&plus.values, &minus.values, 2.0 * h))
}

/// The partial derivatives of every `Values` quantity of the run of
/// `series` (as [`Problem::spec`] builds it) with respect to each of
/// `wrt`, in that order, by central differences of exact runs alone: the
/// oracle the exact [`gradient`] is checked against. `Err` names the
/// parameter whose neighbouring runs have no steady state.
pub fn gradient_by_differences(
    problem: &Problem,
    series: &HarmonicSeries,
    wrt: &[Param],
) -> Result<Vec<Values>, String> {
    wrt.iter()
        .map(|&param| central(problem, series, param))
        .collect()
}

/// The partial derivatives of every `Values` quantity of the run of
/// `series` with respect to each of `wrt`, as the search uses them: exact
/// where the model gives them, central differences for the rest (module
/// docs). Runs the series once for its steady orbit; `Err` when it has no
/// steady state, or a needed difference cannot be taken.
pub fn gradient(
    problem: &Problem,
    series: &HarmonicSeries,
    wrt: &[Param],
) -> Result<Vec<Values>, String> {
    let at = problem.measure(problem.spec(series))?;
    gradient_at(problem, series, &at, wrt).values
}

/// [`gradient`] at a series whose run reported `at`, with the runs it made.
pub(crate) fn gradient_at(
    problem: &Problem,
    series: &HarmonicSeries,
    at: &Measured,
    wrt: &[Param],
) -> Counted {
    let spec = problem.spec(series);
    let fields: Vec<Parameter> = wrt.iter().map(|p| p.field()).collect();
    let v_inf = match problem.base.run.engine {
        EngineKind::Event => {
            sensitivity::own_branch(&spec, &problem.base.motor, at.boundary_velocity, &fields)
                .unwrap_or_else(|_| vec![f64::NAN; wrt.len()])
        }
        _ => vec![f64::NAN; wrt.len()],
    };
    let power = power_derivatives(problem, series, wrt);
    let wanted = problem.indicators();
    let differenced = [
        Indicator::Smoothness,
        Indicator::Durability,
        Indicator::StartupTime,
    ]
    .iter()
    .any(|i| wanted.contains(i));
    let mut runs = 0;
    let mut values = Vec::with_capacity(wrt.len());
    for ((&param, dv), power) in wrt.iter().zip(&v_inf).zip(&power) {
        let mut d = if differenced || !dv.is_finite() {
            runs += 2;
            match central(problem, series, param) {
                Ok(d) => d,
                Err(e) => {
                    return Counted {
                        values: Err(e),
                        runs,
                    };
                }
            }
        } else {
            Values::default()
        };
        if dv.is_finite() {
            d.v_inf = *dv;
        }
        if let Some((du, ds)) = power {
            d.voltage_rms = *du;
            d.apparent_power = *ds;
        }
        values.push(d);
    }
    Counted {
        values: Ok(values),
        runs,
    }
}

/// `(dU, dS)` per parameter (module docs), where the runs compute the
/// power (`None` otherwise: the values are 0 and so are their
/// derivatives).
fn power_derivatives(
    problem: &Problem,
    series: &HarmonicSeries,
    wrt: &[Param],
) -> Vec<Option<(f64, f64)>> {
    let none = vec![None; wrt.len()];
    let Some(actuator) = &problem.base.actuator else {
        return none;
    };
    if !problem.indicators().contains(&Indicator::VelocityPerPower) {
        return none;
    }
    let built = |scale: Option<f64>, shift: bool| {
        crate::signal::harmonics::build(
            problem.f0,
            &series.amplitudes,
            &series.phases,
            scale,
            shift,
        )
    };
    let (Ok(raw), Ok(run)) = (built(None, false), built(Some(problem.stroke), true)) else {
        return none;
    };
    let ext = raw.extrema();
    let spread = ext.max - ext.min;
    let q = problem.stroke / spread;
    let omega = raw.omega();
    wrt.iter()
        .map(|&param| {
            let (k, dr): (usize, Box<dyn Fn(f64) -> f64>) = match param {
                Param::Amplitude(k) => {
                    let phi = series.phases[k - 1];
                    (k, Box::new(move |t| (k as f64 * omega * t + phi).sin()))
                }
                Param::Phase(k) => {
                    let (d, phi) = (series.amplitudes[k - 1], series.phases[k - 1]);
                    (k, Box::new(move |t| d * (k as f64 * omega * t + phi).cos()))
                }
            };
            let rate = -(dr(ext.tau_max) - dr(ext.tau_min)) / spread;
            let da: Vec<f64> = series
                .amplitudes
                .iter()
                .enumerate()
                .map(|(j, d)| {
                    let own = matches!(param, Param::Amplitude(_)) && j + 1 == k;
                    q * (d * rate + if own { 1.0 } else { 0.0 })
                })
                .collect();
            let (du, _, ds) = crate::power::input_power_derivative(&run, actuator, &da);
            Some((du, ds))
        })
        .collect()
}

/// The parameters [`coordinate_gradient`] differentiates by: every
/// amplitude and the phases `phi_2 .. phi_n` (`phi_1` is the time origin).
pub(crate) fn shape_parameters(n: usize) -> Vec<Param> {
    (1..=n)
        .map(Param::Amplitude)
        .chain((2..=n).map(Param::Phase))
        .collect()
}

/// The derivatives of the values with respect to a shape's coordinates
/// (its angles, then its phases) at a shape whose run reported `at`, from
/// [`gradient`] by the chain rule:
/// `d/dt_j = sum_k sign(u_k) (x_hat / 2) (du_k/dt_j) d/dd_k` and
/// `d/dpsi_k = d/dphi_k`; with the runs made.
pub(crate) fn coordinate_gradient(problem: &Problem, shape: &Shape, at: &Measured) -> Counted {
    let n = shape.harmonics();
    let series = shape.series(problem.stroke);
    let raw = gradient_at(problem, &series, at, &shape_parameters(n));
    let values = match raw.values {
        Ok(v) => v,
        Err(e) => {
            return Counted {
                values: Err(e),
                runs: raw.runs,
            };
        }
    };
    let (amplitude, phase) = values.split_at(n);
    let u = shape.unit_amplitudes();
    let jac = shape.unit_jacobian();
    let half = 0.5 * problem.stroke;
    let mut out = Vec::with_capacity(2 * n - 2);
    for j in 0..n - 1 {
        let mut d = Values::default();
        for ((uk, row), dk) in u.iter().zip(&jac).zip(amplitude) {
            let sign = if *uk < 0.0 { -1.0 } else { 1.0 };
            d = d.plus(&dk.scaled(sign * half * row[j]));
        }
        out.push(d);
    }
    out.extend_from_slice(phase);
    Counted {
        values: Ok(out),
        runs: raw.runs,
    }
}
