//! The rod signal exactly as simulated (docs/model.md section 2), for a
//! user who rebuilds it elsewhere: period, offset, the time shift and the
//! stroke scaling factor that were applied, and every harmonic's amplitude
//! `d_k` and phase `phi_k` after sigma factors, scaling and shift, so that
//! `x_R(t) = c_0 + sum_k d_k sin(k w_0 t + phi_k)`; as text, JSON, or a
//! MATLAB or Python snippet that evaluates `x_R(t)`.

use super::fourier::FourierSignal;
use super::{Signal, SignalSpec};
use crate::motor::Motor;
use serde::Serialize;
use serde_json::{Value, json};
use std::fmt::Write as _;

/// One harmonic of the simulated series.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Harmonic {
    /// Order `k`.
    pub k: usize,
    /// Amplitude `d_k` (m) after sigma factor, scaling and shift.
    pub amplitude: f64,
    /// Phase `phi_k` (rad) after the shift.
    pub phase: f64,
    /// The sigma factor (15) applied, 1 without.
    pub sigma: f64,
}

/// The rod signal as simulated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignalDescription {
    /// `"fourier"`, `"harmonics"`, `"ideal"`, or `"response"` (the
    /// actuator's response to a scene's `[voltage]`).
    pub kind: &'static str,
    /// Period `T` (s).
    pub period: f64,
    /// Fundamental frequency `f_0` (Hz).
    pub f0: f64,
    /// Constant term `c_0` (m).
    pub offset: f64,
    /// The time shift `t_s` applied: the simulated signal is the scaled
    /// series evaluated at `t + t_s` (its minimum was at `t_s`), plus the
    /// offset. `None` when no shift was applied.
    pub time_shift: Option<f64>,
    /// The factor the amplitudes were multiplied with to reach the stroke;
    /// `None` when not scaled.
    pub stroke_scale: Option<f64>,
    /// Peak-to-peak stroke `max x_R - min x_R` (m).
    pub stroke: f64,
    /// The harmonics (empty for the ideal signal).
    pub harmonics: Vec<Harmonic>,
    /// Ideal signal: acceleration `a_R` (m/s^2) and acceleration time
    /// `t_1` (s).
    pub ideal: Option<(f64, f64)>,
}

impl SignalDescription {
    /// Describes the signal a scene's spec builds for `motor`; `signal` is
    /// the built signal.
    pub fn new(spec: &SignalSpec, signal: &Signal, motor: &Motor) -> Self {
        let period = signal.period();
        match signal {
            Signal::Ideal(s) => Self {
                kind: "ideal",
                period,
                f0: 1.0 / period,
                offset: 0.0,
                time_shift: None,
                stroke_scale: None,
                stroke: 0.5 * s.a_r() * s.t1() * s.t1(),
                harmonics: Vec::new(),
                ideal: Some((s.a_r(), s.t1())),
            },
            Signal::Fourier(f) => {
                // Rebuild the series before scaling and shift to state
                // both (docs/model.md section 2, steps 1-3).
                let (raw, sigma, scale_to, shift) = match spec {
                    SignalSpec::Fourier {
                        shape,
                        harmonics,
                        sigma,
                    } => (
                        Some(FourierSignal::partial_sum(
                            *shape, *harmonics, *sigma, motor,
                        )),
                        (1..=*harmonics)
                            .map(|k| {
                                if *sigma {
                                    crate::signal::fourier::sigma_factor(k, *harmonics)
                                } else {
                                    1.0
                                }
                            })
                            .collect::<Vec<_>>(),
                        Some(shape.stroke),
                        true,
                    ),
                    SignalSpec::Harmonics {
                        frequency,
                        amplitudes,
                        phases,
                        scale_to_stroke,
                        shift_to_minimum,
                    } => (
                        crate::signal::harmonics::build(
                            *frequency, amplitudes, phases, None, false,
                        )
                        .ok(),
                        vec![1.0; amplitudes.len()],
                        *scale_to_stroke,
                        *shift_to_minimum,
                    ),
                    SignalSpec::Ideal(_) | SignalSpec::Response { .. } => {
                        (None, Vec::new(), None, false)
                    }
                };
                let stroke_scale = match (&raw, scale_to) {
                    (Some(r), Some(target)) => Some(target / r.stroke()),
                    _ => None,
                };
                let time_shift = match (&raw, shift) {
                    (Some(r), true) => {
                        let scaled = match stroke_scale {
                            Some(s) => r.scaled_to_stroke(s * r.stroke()).ok(),
                            None => Some(r.clone()),
                        };
                        scaled.map(|s| s.extrema().tau_min)
                    }
                    _ => None,
                };
                let harmonics = f
                    .amplitudes()
                    .iter()
                    .zip(f.phases())
                    .enumerate()
                    .map(|(i, (&amplitude, phase))| Harmonic {
                        k: i + 1,
                        amplitude,
                        phase,
                        sigma: sigma.get(i).copied().unwrap_or(1.0),
                    })
                    .collect();
                Self {
                    kind: match spec {
                        SignalSpec::Harmonics { .. } => "harmonics",
                        SignalSpec::Response { .. } => "response",
                        _ => "fourier",
                    },
                    period,
                    f0: 1.0 / period,
                    offset: f.offset(),
                    time_shift,
                    stroke_scale,
                    stroke: f.stroke(),
                    harmonics,
                    ideal: None,
                }
            }
        }
    }

    /// Readable text.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "signal: {}", self.kind);
        let _ = writeln!(s, "  period T          {:e} s", self.period);
        let _ = writeln!(s, "  f0                {} Hz", self.f0);
        let _ = writeln!(
            s,
            "  stroke            {:e} m (max x_R - min x_R)",
            self.stroke
        );
        if let Some((a_r, t1)) = self.ideal {
            let _ = writeln!(
                s,
                "  x_R(tau) = a_R tau^2 / 2 for tau < t_1, 0 after (tau = t mod T)"
            );
            let _ = writeln!(s, "  a_R               {a_r} m/s^2");
            let _ = writeln!(s, "  t_1               {t1:e} s");
            return s;
        }
        let _ = writeln!(
            s,
            "  x_R(t) = c0 + sum_k d_k sin(k w0 t + phi_k), w0 = 2 pi / T"
        );
        let _ = writeln!(s, "  c0 (offset)       {:e} m", self.offset);
        match self.time_shift {
            Some(ts) => {
                let _ = writeln!(
                    s,
                    "  time shift t_s    {ts:e} s (minimum moved from t_s to 0)"
                );
            }
            None => {
                let _ = writeln!(s, "  time shift        none");
            }
        }
        match self.stroke_scale {
            Some(f) => {
                let _ = writeln!(s, "  stroke scaling    x {f}");
            }
            None => {
                let _ = writeln!(s, "  stroke scaling    none");
            }
        }
        let _ = writeln!(
            s,
            "  k  d_k (m)                  phi_k (rad)              sigma_k"
        );
        for h in &self.harmonics {
            let _ = writeln!(
                s,
                "  {:<2} {:<24e} {:<24} {}",
                h.k, h.amplitude, h.phase, h.sigma
            );
        }
        s
    }

    /// The JSON object (keys in docs/interface.md).
    pub fn to_json(&self) -> Value {
        json!({
            "kind": self.kind,
            "period": self.period,
            "f0": self.f0,
            "stroke": self.stroke,
            "offset": self.offset,
            "time_shift": self.time_shift,
            "stroke_scale": self.stroke_scale,
            "harmonics": self.harmonics,
            "a_R": self.ideal.map(|i| i.0),
            "t_1": self.ideal.map(|i| i.1),
        })
    }

    fn list(values: impl Iterator<Item = f64>) -> String {
        values
            .map(|v| format!("{v:e}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// A MATLAB snippet defining `x_R = @(t) ...` (t in s, x_R in m).
    pub fn to_matlab(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "% rod signal x_R(t) as simulated by stickslip (SI units)"
        );
        let _ = writeln!(s, "T = {:e};", self.period);
        if let Some((a_r, t1)) = self.ideal {
            let _ = writeln!(s, "a_R = {a_r:e}; t_1 = {t1:e};");
            let _ = writeln!(
                s,
                "x_R = @(t) (mod(t, T) < t_1) .* (a_R / 2) .* mod(t, T).^2;"
            );
            return s;
        }
        let _ = writeln!(s, "c0 = {:e};", self.offset);
        let _ = writeln!(
            s,
            "d = [{}];",
            Self::list(self.harmonics.iter().map(|h| h.amplitude))
        );
        let _ = writeln!(
            s,
            "phi = [{}];",
            Self::list(self.harmonics.iter().map(|h| h.phase))
        );
        let _ = writeln!(s, "k = (1:numel(d)).';");
        let _ = writeln!(
            s,
            "x_R = @(t) c0 + sum(d(:) .* sin(k * (2*pi/T) * t(:).' + phi(:)), 1).';"
        );
        let _ = writeln!(
            s,
            "v_R = @(t) sum(d(:) .* k * (2*pi/T) .* cos(k * (2*pi/T) * t(:).' + phi(:)), 1).';"
        );
        s
    }

    /// A Python (numpy) snippet defining `x_R(t)` and `v_R(t)`.
    pub fn to_python(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# rod signal x_R(t) as simulated by stickslip (SI units)"
        );
        let _ = writeln!(s, "import numpy as np");
        let _ = writeln!(s, "T = {:e}", self.period);
        if let Some((a_r, t1)) = self.ideal {
            let _ = writeln!(s, "a_R, t_1 = {a_r:e}, {t1:e}");
            let _ = writeln!(s, "def x_R(t):");
            let _ = writeln!(s, "    tau = np.mod(t, T)");
            let _ = writeln!(s, "    return np.where(tau < t_1, 0.5 * a_R * tau**2, 0.0)");
            return s;
        }
        let _ = writeln!(s, "c0 = {:e}", self.offset);
        let _ = writeln!(
            s,
            "d = np.array([{}])",
            Self::list(self.harmonics.iter().map(|h| h.amplitude))
        );
        let _ = writeln!(
            s,
            "phi = np.array([{}])",
            Self::list(self.harmonics.iter().map(|h| h.phase))
        );
        let _ = writeln!(s, "k = np.arange(1, len(d) + 1)");
        let _ = writeln!(s, "def x_R(t):");
        let _ = writeln!(s, "    t = np.asarray(t, dtype=float)[..., None]");
        let _ = writeln!(
            s,
            "    return c0 + np.sum(d * np.sin(k * (2 * np.pi / T) * t + phi), axis=-1)"
        );
        let _ = writeln!(s, "def v_R(t):");
        let _ = writeln!(s, "    t = np.asarray(t, dtype=float)[..., None]");
        let _ = writeln!(
            s,
            "    return np.sum(d * k * (2 * np.pi / T) * np.cos(k * (2 * np.pi / T) * t + phi), axis=-1)"
        );
        s
    }
}
