//! The direction of one amplitude `d_k` or phase `phi_k` of a
//! `harmonics` signal (docs/model.md section 14.6), through the stroke
//! scaling and the shift to the minimum of section 2.
//!
//! With the series as given, `R(t) = sum_k d_k sin(k w_0 t + phi_k)`, the
//! program drives
//!
//! ```text
//! x_R(tau) = q R(tau + t_min) - q R(t_min),   q = x_hat / (max R - min R),
//! ```
//!
//! `t_min` the phase of the minimum of `R` (0 without the shift, `q = 1`
//! without the scaling). At a fixed phase, with `dR = dR/dtheta`:
//!
//! ```text
//! dx_R(tau) = (dq/q) x_R(tau) + q dR(tau + t_min) + v_R(tau) dt_min + const
//! dq/q      = -(dR(t_max) - dR(t_min)) / (max R - min R)   (the extrema move,
//!                                                           their values change by dR: envelope theorem)
//! dt_min    = -(d/dt dR)(t_min) / R''(t_min)                (R'(t_min) = 0 stays)
//! ```
//!
//! that is the amplitude rate `s = dq/q`, the shift rate `c = dt_min` and
//! the series `q dR(tau + t_min)` of [`super::tangent::RodTangent`]. For
//! `theta = d_k`, `dR = sin(k w_0 t + phi_k)`; for `theta = phi_k`,
//! `dR = d_k cos(k w_0 t + phi_k)`. A minimum or maximum that is attained
//! twice (a tie between two extrema) makes the stroke scaling or the shift
//! jump with the parameter; that is not treated here.

use super::parameter::Parameter;
use super::tangent::RodTangent;
use crate::error::ParamError;
use crate::signal::{FourierSignal, Signal, SignalSpec};

/// `dR/dtheta` and its time derivative at `t` for harmonic `m = k + 1`.
fn d_series(theta: Parameter, d_k: f64, phi_k: f64, m: f64, omega: f64, t: f64) -> (f64, f64) {
    let (s, c) = (m * omega * t + phi_k).sin_cos();
    match theta {
        Parameter::Amplitude(_) => (s, m * omega * c),
        _ => (d_k * c, -m * omega * d_k * s),
    }
}

/// The rod's direction for `theta` = `Amplitude(k)` or `Phase(k)` of a
/// `harmonics` spec whose built signal is `signal`.
pub(super) fn tangent(
    spec: &SignalSpec,
    signal: &Signal,
    theta: Parameter,
) -> Result<RodTangent, ParamError> {
    let (
        SignalSpec::Harmonics {
            frequency,
            amplitudes,
            phases,
            scale_to_stroke,
            shift_to_minimum,
        },
        Parameter::Amplitude(k) | Parameter::Phase(k),
    ) = (spec, theta)
    else {
        return Err(ParamError::Inconsistent {
            field: theta.to_string(),
            reason: "only a kind = \"harmonics\" signal has amplitudes and phases".to_owned(),
        });
    };
    if k >= amplitudes.len() {
        return Err(ParamError::out_of_range(
            &theta.to_string(),
            k as f64,
            format!("the signal has {} harmonics", amplitudes.len()),
        ));
    }
    let raw = crate::signal::harmonics::build(*frequency, amplitudes, phases, None, false)?;
    let omega = raw.omega();
    let ext = raw.extrema();
    let (d_k, phi_k, m) = (amplitudes[k], phases[k], (k + 1) as f64);
    let d = |t: f64| d_series(theta, d_k, phi_k, m, omega, t);
    let (q, scale) = match scale_to_stroke {
        Some(stroke) => {
            let spread = ext.max - ext.min;
            (
                stroke / spread,
                -(d(ext.tau_max).0 - d(ext.tau_min).0) / spread,
            )
        }
        None => (1.0, 0.0),
    };
    let (t0, shift) = if *shift_to_minimum {
        (
            ext.tau_min,
            -d(ext.tau_min).1 / raw.acceleration(ext.tau_min),
        )
    } else {
        (0.0, 0.0)
    };
    // q dR(tau + t0) as a series in tau: harmonic m with phase psi.
    let psi = phi_k + m * omega * t0;
    let (s, cs) = psi.sin_cos();
    let (a_m, b_m) = match theta {
        Parameter::Amplitude(_) => (q * s, q * cs),
        _ => (q * d_k * cs, -q * d_k * s),
    };
    let mut cos = vec![0.0; k + 1];
    let mut sin = vec![0.0; k + 1];
    cos[k] = a_m;
    sin[k] = b_m;
    Ok(RodTangent {
        scale,
        time_scale: 0.0,
        shift,
        series: Some(FourierSignal::from_coefficients(
            signal.period(),
            0.0,
            cos,
            sin,
        )),
    })
}
