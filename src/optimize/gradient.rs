//! Sensitivities of a run's values to the signal's parameters
//! (docs/model.md sections 9 and 14): `d v_inf / d d_k` and
//! `d v_inf / d phi_k` of a `kind = "harmonics"` series, with the stroke
//! scaling and the shift included (both are part of the signal a series
//! stands for), and the same for the other [`Values`].
//!
//! **For now [`gradient`] computes them by central differences of exact
//! runs**: `(q(p + h) - q(p - h)) / (2h)` for every value `q` and
//! parameter `p`, `h` = [`STEP`] times the largest amplitude for an
//! amplitude and [`STEP`] rad for a phase. Every run is exact to its error
//! estimate (about `1e-12` relative for `v_inf`), so the rounding part of
//! the difference is about `1e-12 / STEP = 1e-7` relative and the
//! truncation part `STEP^2 = 1e-10` relative where the values are smooth.
//! Where the event structure of the steady orbit changes (a stick phase
//! appears, a reversal becomes a stick, a grazing) the values have a kink
//! and the difference quotient across it mixes the two one-sided
//! derivatives. This function is the one place the local search takes
//! derivatives from: the exact sensitivities of the period map (model 9,
//! `dv*/dtheta = (dP/dtheta) / (1 - dP/dv)`) replace its body, with the
//! same signature, when they cover signal parameters.
//!
//! [`coordinate_gradient`] turns them into derivatives with respect to a
//! [`Shape`]'s coordinates by the chain rule (module docs of
//! [`super::params`]).

use super::objective::Values;
use super::params::{Series, Shape, wrap};
use super::problem::Problem;
use std::f64::consts::PI;

/// A parameter of a harmonic series, `k` from 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    /// The amplitude `d_k`.
    Amplitude(usize),
    /// The phase `phi_k`.
    Phase(usize),
}

/// Relative step of the central differences (module docs).
pub(crate) const STEP: f64 = 1e-5;

/// The series with one parameter moved by `delta`; an amplitude moved
/// below 0 becomes the positive amplitude with the phase plus `pi`
/// (the same signal).
fn moved(series: &Series, param: Param, delta: f64) -> Series {
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

/// The partial derivatives of every `Values` quantity of the run of
/// `series` (as [`Problem::spec`] builds it) with respect to each of
/// `wrt`, in that order, by central differences (module docs). `Err` names
/// the parameter whose neighbouring runs have no steady state.
pub fn gradient(problem: &Problem, series: &Series, wrt: &[Param]) -> Result<Vec<Values>, String> {
    let largest = series.amplitudes.iter().copied().fold(0.0, f64::max);
    wrt.iter()
        .map(|&param| {
            let h = match param {
                Param::Amplitude(_) => STEP * largest,
                Param::Phase(_) => STEP,
            };
            let run = |delta: f64| problem.measure(problem.spec(&moved(series, param, delta)));
            let plus = run(h).map_err(|e| format!("{param:?} + {h:e}: {e}"))?;
            let minus = run(-h).map_err(|e| format!("{param:?} - {h:e}: {e}"))?;
            Ok(Values::difference(&plus.values, &minus.values, 2.0 * h))
        })
        .collect()
}

/// Runs one [`gradient`] takes for `wrt`.
pub(crate) fn runs_per_gradient(wrt: usize) -> u64 {
    2 * wrt as u64
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
/// (its angles, then its phases), from [`gradient`] by the chain rule:
/// `d/dt_j = sum_k sign(u_k) (x_hat / 2) (du_k/dt_j) d/dd_k` and
/// `d/dpsi_k = d/dphi_k`.
pub(crate) fn coordinate_gradient(problem: &Problem, shape: &Shape) -> Result<Vec<Values>, String> {
    let n = shape.harmonics();
    let series = shape.series(problem.stroke);
    let raw = gradient(problem, &series, &shape_parameters(n))?;
    let (amplitude, phase) = raw.split_at(n);
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
    Ok(out)
}
