//! User-given harmonic series: the paper's harmonic form (8),
//! `x_R(t) = sum_{k=1}^{n} d_k sin(k w_0 t + phi_k)`, at fundamental
//! frequency `f_0 = w_0 / (2 pi)`, so that measured or designed signals can
//! drive the motor. In cosine/sine form `A_k = d_k sin(phi_k)` and
//! `B_k = d_k cos(phi_k)` (the inverse of (6), (7)).
//!
//! Optionally scaled to a stroke and shifted to the minimum, as the paper's
//! own signals are (section 4). Without the shift the rod starts with
//! `x_R(0)` and `v_R(0)` from rest at `x_R = 0`: a jump at `t = 0`.

use super::FourierSignal;
use crate::error::ParamError;

/// Builds the series from validated amplitudes `d_k` (m) and phases `phi_k`
/// (rad), k = 1..=n.
pub(crate) fn build(
    frequency: f64,
    amplitudes: &[f64],
    phases: &[f64],
    scale_to_stroke: Option<f64>,
    shift_to_minimum: bool,
) -> Result<FourierSignal, ParamError> {
    let cos = amplitudes
        .iter()
        .zip(phases)
        .map(|(d, phi)| d * phi.sin())
        .collect();
    let sin = amplitudes
        .iter()
        .zip(phases)
        .map(|(d, phi)| d * phi.cos())
        .collect();
    let mut signal = FourierSignal::from_coefficients(1.0 / frequency, 0.0, cos, sin);
    if let Some(stroke) = scale_to_stroke {
        signal = signal.scaled_to_stroke(stroke)?;
    }
    if shift_to_minimum {
        signal = signal.shifted_to_minimum()?;
    }
    Ok(signal)
}
