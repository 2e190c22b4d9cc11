//! The actuator's voltage for a signal generator (docs/model.md section 4):
//! the voltage `u(t)` that moves the rod of the scene's `[actuator]`
//! exactly along the scene's signal, as `stickslip signal --voltage`
//! prints it (text, JSON, or a MATLAB or Python snippet that evaluates
//! `u(t)`).
//!
//! The signal `x_R = x_0 + sum_k Re(X_k e^{i k w_0 t})` is the one
//! simulated (after sigma factors, stroke scaling and shift, as
//! `stickslip signal` prints it). The voltage is the inverse of the
//! actuator equation (23) `M x_R'' + d x_R' + c x_R = alpha u` harmonic
//! by harmonic ([`Voltage::designed`]):
//!
//! ```text
//! U_k = (c - M (k w_0)^2 + i d k w_0) X_k / alpha,    u_0 = c x_0 / alpha,
//! u(t) = u_0 + sum_k u_k sin(k w_0 t + phi_k),        u_k = |U_k|,
//! ```
//!
//! with its peak `max |u(t)|` over a period (offset included, at the
//! exact extrema) and its RMS value (33) `sqrt(sum_k u_k^2 / 2)` (without
//! the offset).
//!
//! Contract: the voltage exists for every `fourier` or `harmonics`
//! signal; it is the periodic voltage under which (23) holds with `x_R`
//! the signal at every instant. A signal shifted to its minimum has
//! `x_R(0) = 0` and `v_R(0) = 0`, the actuator's rest under `u = 0`, so
//! that `u(t)` switched on at `t = 0` moves the resting actuator along
//! the signal from the first instant (`starts_at_rest`); any other signal
//! is followed once the actuator's free oscillation, which decays as
//! `e^{-d t / (2 M)}`, has died out. Errors name the scene field: no
//! `[actuator]` (`actuator`); the ideal signal (`signal.kind`: it jumps,
//! so no voltage moves an actuator along it); a voltage beyond floating
//! point (`actuator`).
//!
//! A voltage given in the scene's `[voltage]` table
//! ([`VoltageDescription::given`]) is printed as given: its frequency,
//! amplitudes, phases and offset, bit for bit, so that the `[voltage]`
//! table the text ends with, or one written from the JSON, reproduces the
//! run. The signal is then the `[actuator]`'s response to it; it starts at
//! rest when its position and velocity at `t = 0` are below `1e-12` of
//! their amplitude sums.

use super::{GivenVoltage, Voltage};
use crate::error::{Num, ParamError};
use crate::power::ActuatorParams;
use crate::signal::{Signal, SignalSpec};
use serde::Serialize;
use serde_json::{Value, json};
use std::fmt::Write as _;

/// One harmonic of the voltage, in the paper's convention (5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct VoltageHarmonic {
    /// Order `k`.
    pub k: usize,
    /// Amplitude `u_k` (V).
    pub amplitude: f64,
    /// Phase `phi_k` (rad, in `(-pi, pi]`) of `u_k sin(k w_0 t + phi_k)`;
    /// 0 where `u_k = 0`.
    pub phase: f64,
}

/// The voltage that moves the rod of `[actuator]` along the signal.
#[derive(Debug, Clone, PartialEq)]
pub struct VoltageDescription {
    /// Period `T` (s), the signal's.
    pub period: f64,
    /// Fundamental frequency `f_0 = 1 / T` (Hz).
    pub f0: f64,
    /// Offset `u_0 = c x_0 / alpha` (V).
    pub offset: f64,
    /// The harmonics `k = 1..=n`, zero amplitudes included.
    pub harmonics: Vec<VoltageHarmonic>,
    /// `max |u(t)|` over a period, offset included (V).
    pub peak: f64,
    /// RMS value (33) of the harmonics, without the offset (V).
    pub rms: f64,
    /// The signal is shifted to its minimum: `x_R(0) = 0`, `v_R(0) = 0`.
    pub starts_at_rest: bool,
    /// The voltage is the scene's `[voltage]`, not designed.
    pub given: bool,
    /// The `[actuator]` parameters the voltage is designed for (given:
    /// whose response is the signal).
    pub actuator: ActuatorParams,
}

/// Relative size of a response's position and velocity at `t = 0` below
/// which it starts at rest (rounding of the response, far above it).
const REST: f64 = 1e-12;

impl VoltageDescription {
    /// The voltage for the signal a scene's `spec` builds (`signal`) and
    /// its `[actuator]` (`None`: the scene has none). Errors name the
    /// field: `actuator`, `signal.kind`.
    pub fn new(
        spec: &SignalSpec,
        signal: &Signal,
        actuator: Option<&ActuatorParams>,
    ) -> Result<Self, ParamError> {
        let Some(actuator) = actuator else {
            return Err(ParamError::Inconsistent {
                field: "actuator".to_owned(),
                reason: "the voltage is designed for the [actuator] parameters, which the \
                         scene does not give"
                    .to_owned(),
            });
        };
        let fourier = match signal {
            Signal::Fourier(f) => f,
            Signal::Ideal(_) => {
                return Err(ParamError::Inconsistent {
                    field: "signal.kind".to_owned(),
                    reason: "\"ideal\" jumps, which no voltage moves an actuator along: \
                             the voltage needs \"fourier\" or \"harmonics\""
                        .to_owned(),
                });
            }
        };
        let voltage = Voltage::designed(fourier, actuator);
        let starts_at_rest = match spec {
            SignalSpec::Fourier { .. } => true,
            SignalSpec::Harmonics {
                shift_to_minimum, ..
            } => *shift_to_minimum,
            SignalSpec::Ideal(_) | SignalSpec::Response { .. } => false,
        };
        let harmonics: Vec<VoltageHarmonic> = voltage
            .amplitudes()
            .into_iter()
            .zip(voltage.phases())
            .enumerate()
            .map(|(i, (amplitude, phase))| VoltageHarmonic {
                k: i + 1,
                amplitude,
                // A zero harmonic has no phase; atan2(+-0, +-0) may be pi.
                phase: if amplitude == 0.0 { 0.0 } else { phase },
            })
            .collect();
        let (peak, rms) = (voltage.peak(), voltage.rms());
        let finite = [voltage.offset(), peak, rms]
            .into_iter()
            .chain(harmonics.iter().flat_map(|h| [h.amplitude, h.phase]))
            .all(f64::is_finite);
        if !finite {
            return Err(ParamError::Inconsistent {
                field: "actuator".to_owned(),
                reason: "the voltage for this signal is beyond floating point \
                         (c x_R / alpha or M a_R / alpha overflows)"
                    .to_owned(),
            });
        }
        Ok(Self {
            period: voltage.period(),
            f0: 1.0 / voltage.period(),
            offset: voltage.offset(),
            harmonics,
            peak,
            rms,
            starts_at_rest,
            given: false,
            actuator: *actuator,
        })
    }

    /// The voltage given in a scene's `[voltage]` (validated), whose
    /// response by `actuator` is `signal`, the scene's built signal.
    pub fn given(voltage: &GivenVoltage, signal: &Signal, actuator: &ActuatorParams) -> Self {
        let u = voltage.voltage();
        let harmonics = voltage
            .amplitudes
            .iter()
            .zip(&voltage.phases)
            .enumerate()
            .map(|(i, (&amplitude, &phase))| VoltageHarmonic {
                k: i + 1,
                amplitude,
                phase,
            })
            .collect();
        let starts_at_rest = match signal {
            Signal::Fourier(f) => {
                let at_zero = f.state(0.0);
                let d = f.amplitudes();
                let x = f.offset().abs() + d.iter().sum::<f64>();
                let v: f64 = d
                    .iter()
                    .enumerate()
                    .map(|(i, a)| (i + 1) as f64 * f.omega() * a)
                    .sum();
                at_zero.x.abs() <= REST * x && at_zero.v.abs() <= REST * v
            }
            Signal::Ideal(_) => false,
        };
        Self {
            period: u.period(),
            f0: voltage.frequency,
            offset: voltage.offset,
            harmonics,
            peak: u.peak(),
            rms: u.rms(),
            starts_at_rest,
            given: true,
            actuator: *actuator,
        }
    }

    /// Readable text.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}",
            if self.given {
                "voltage: given in [voltage]; the signal is the [actuator]'s response to it"
            } else {
                "voltage: moves the [actuator] rod along the signal (inverse of (23))"
            }
        );
        let _ = writeln!(s, "  period T          {:e} s", self.period);
        let _ = writeln!(s, "  f0                {} Hz", self.f0);
        let _ = writeln!(
            s,
            "  u(t) = u0 + sum_k u_k sin(k w0 t + phi_k), w0 = 2 pi / T"
        );
        let _ = writeln!(s, "  u0 (offset)       {} V", Num(self.offset));
        let _ = writeln!(s, "  k  u_k (V)                  phi_k (rad)");
        for h in &self.harmonics {
            let _ = writeln!(
                s,
                "  {:<2} {:<24} {}",
                h.k,
                Num(h.amplitude).to_string(),
                h.phase
            );
        }
        let _ = writeln!(
            s,
            "  peak              {} V (max |u(t)|, offset included)",
            Num(self.peak)
        );
        let _ = writeln!(
            s,
            "  RMS (33)          {} V (harmonics, without the offset)",
            Num(self.rms)
        );
        let _ = writeln!(
            s,
            "  from t = 0        {}",
            if self.starts_at_rest {
                "at rest: x_R(0) = 0, v_R(0) = 0; the rod follows the signal from the first instant"
            } else {
                "not at rest: the rod follows the signal once the free oscillation, \
                 decaying as exp(-d t / (2 M)), has died out"
            }
        );
        let a = &self.actuator;
        let _ = writeln!(
            s,
            "{} [actuator]: M x_R'' + d x_R' + c x_R = alpha u",
            if self.given {
                "the response of"
            } else {
                "designed for"
            }
        );
        let _ = writeln!(s, "  M (mass)          {} kg", Num(a.mass));
        let _ = writeln!(s, "  d (damping)       {} N s/m", Num(a.damping));
        let _ = writeln!(s, "  c (stiffness)     {} N/m", Num(a.stiffness));
        let _ = writeln!(s, "  alpha             {} N/V", Num(a.transfer_factor));
        let _ = writeln!(
            s,
            "as a scene table (in place of [signal], with this [actuator]):"
        );
        s.push_str(&self.to_toml());
        s
    }

    /// The voltage as a scene's `[voltage]` table, every number as printed
    /// in JSON (shortest round trip).
    pub fn to_toml(&self) -> String {
        let list = |values: &mut dyn Iterator<Item = f64>| {
            values
                .map(|v| format!("{v:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        format!(
            "[voltage]\nfrequency = {:?}\namplitudes = [{}]\nphases = [{}]\noffset = {:?}\n",
            self.f0,
            list(&mut self.harmonics.iter().map(|h| h.amplitude)),
            list(&mut self.harmonics.iter().map(|h| h.phase)),
            self.offset
        )
    }

    /// The JSON object (keys in docs/interface.md).
    pub fn to_json(&self) -> Value {
        let a = &self.actuator;
        json!({
            "period": self.period,
            "f0": self.f0,
            "offset": self.offset,
            "harmonics": self.harmonics,
            "peak": self.peak,
            "rms": self.rms,
            "starts_at_rest": self.starts_at_rest,
            "given": self.given,
            "actuator": {
                "mass": a.mass,
                "damping": a.damping,
                "stiffness": a.stiffness,
                "transfer_factor": a.transfer_factor,
            },
        })
    }

    fn list(values: impl Iterator<Item = f64>) -> String {
        values
            .map(|v| format!("{v:e}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    fn amplitudes(&self) -> String {
        Self::list(self.harmonics.iter().map(|h| h.amplitude))
    }

    fn phases(&self) -> String {
        Self::list(self.harmonics.iter().map(|h| h.phase))
    }

    /// The comment lines both snippets start with (`mark`: `%` or `#`).
    fn header(&self, mark: &str) -> String {
        let a = &self.actuator;
        let what = if self.given {
            format!(
                "{mark} actuator voltage u(t) (V, t in s) given in [voltage]; the signal of\n\
                 {mark} `stickslip signal` is its response by [actuator] M = {} kg,\n",
                Num(a.mass)
            )
        } else {
            format!(
                "{mark} actuator voltage u(t) (V, t in s) that moves the rod along the signal\n\
                 {mark} of `stickslip signal`, designed for [actuator] M = {} kg,\n",
                Num(a.mass)
            )
        };
        format!(
            "{what}{mark} d = {} N s/m, c = {} N/m, alpha = {} N/V\n",
            Num(a.damping),
            Num(a.stiffness),
            Num(a.transfer_factor)
        )
    }

    /// A MATLAB snippet defining `u = @(t) ...` and the peak and RMS.
    pub fn to_matlab(&self) -> String {
        let mut s = self.header("%");
        let _ = writeln!(s, "T = {:e};", self.period);
        let _ = writeln!(s, "u0 = {:e};", self.offset);
        let _ = writeln!(s, "u_k = [{}];", self.amplitudes());
        let _ = writeln!(s, "phi_u = [{}];", self.phases());
        let _ = writeln!(s, "u_peak = {:e};  % max |u(t)|", self.peak);
        let _ = writeln!(s, "u_rms = {:e};   % (33), without u0", self.rms);
        let _ = writeln!(s, "k = (1:numel(u_k)).';");
        let _ = writeln!(
            s,
            "u = @(t) u0 + sum(u_k(:) .* sin(k * (2*pi/T) * t(:).' + phi_u(:)), 1).';"
        );
        s
    }

    /// A Python (numpy) snippet defining `u(t)` and the peak and RMS.
    pub fn to_python(&self) -> String {
        let mut s = self.header("#");
        let _ = writeln!(s, "import numpy as np");
        let _ = writeln!(s, "T = {:e}", self.period);
        let _ = writeln!(s, "u0 = {:e}", self.offset);
        let _ = writeln!(s, "u_k = np.array([{}])", self.amplitudes());
        let _ = writeln!(s, "phi_u = np.array([{}])", self.phases());
        let _ = writeln!(s, "u_peak = {:e}  # max |u(t)|", self.peak);
        let _ = writeln!(s, "u_rms = {:e}  # (33), without u0", self.rms);
        let _ = writeln!(s, "k = np.arange(1, len(u_k) + 1)");
        let _ = writeln!(s, "def u(t):");
        let _ = writeln!(s, "    t = np.asarray(t, dtype=float)[..., None]");
        let _ = writeln!(
            s,
            "    return u0 + np.sum(u_k * np.sin(k * (2 * np.pi / T) * t + phi_u), axis=-1)"
        );
        s
    }
}
