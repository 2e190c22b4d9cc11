//! What a user needs to rebuild and check our results elsewhere:
//!
//! * [`SignalDescription`]: the rod signal exactly as simulated
//!   (docs/model.md section 2): period, offset, the time shift and the
//!   stroke scaling factor that were applied, and every harmonic's
//!   amplitude `d_k` and phase `phi_k` after sigma factors, scaling and
//!   shift, so that `x_R(t) = c_0 + sum_k d_k sin(k w_0 t + phi_k)`; as
//!   text, JSON, or a MATLAB or Python snippet that evaluates `x_R(t)`;
//! * the exact trajectory at given times and the per-period series of the
//!   start-up, as CSV or JSON lines ([`trajectory_table`],
//!   [`periods_table`]).

use crate::compare::exact::{ExactState, PeriodRecord, event_name};
use crate::error::Num;
use crate::motor::Motor;
use crate::signal::fourier::FourierSignal;
use crate::signal::{Signal, SignalSpec};
use serde::Serialize;
use serde_json::{Value, json};
use std::fmt::Write as _;

/// Most samples a trajectory export may have (`--times` or
/// `--sample-rate`): the exact states and the table are built in memory,
/// about 500 bytes a sample, before the file is written atomically; longer
/// spans are exported in several runs (`--periods`).
const MAX_SAMPLES: u64 = 2_000_000;

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
    /// `"fourier"`, `"harmonics"` or `"ideal"`.
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
                    SignalSpec::Ideal(_) => (None, Vec::new(), None, false),
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
                    kind: if matches!(spec, SignalSpec::Harmonics { .. }) {
                        "harmonics"
                    } else {
                        "fourier"
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

/// Output format of a table, from the file name: `.jsonl`/`.json` gives
/// JSON lines, anything else CSV.
pub fn is_json_lines(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("jsonl") || e.eq_ignore_ascii_case("json"))
}

fn table(columns: &[&str], rows: Vec<Vec<Value>>, json_lines: bool) -> String {
    let mut s = String::new();
    if json_lines {
        for row in rows {
            let object: serde_json::Map<String, Value> =
                columns.iter().map(|c| (*c).to_owned()).zip(row).collect();
            let _ = writeln!(s, "{}", Value::Object(object));
        }
    } else {
        let _ = writeln!(s, "{}", columns.join(","));
        for row in rows {
            let cells: Vec<String> = row
                .iter()
                .map(|v| match v {
                    Value::String(text) => text.clone(),
                    Value::Null => String::new(),
                    other => other.to_string(),
                })
                .collect();
            let _ = writeln!(s, "{}", cells.join(","));
        }
    }
    s
}

/// Columns of the trajectory table.
pub const TRAJECTORY_COLUMNS: [&str; 7] = ["t", "x_R", "v_R", "a_R", "x_S", "v_S", "mode"];

/// The exact states as a CSV or JSON-lines table.
pub fn trajectory_table(states: &[ExactState], json_lines: bool) -> String {
    let rows = states
        .iter()
        .map(|s| {
            vec![
                json!(s.t),
                json!(s.x_r),
                json!(s.v_r),
                json!(s.a_r),
                json!(s.x_s),
                json!(s.v_s),
                json!(s.mode.name()),
            ]
        })
        .collect();
    table(&TRAJECTORY_COLUMNS, rows, json_lines)
}

/// Columns of the per-period table.
pub const PERIOD_COLUMNS: [&str; 7] = [
    "p",
    "v_p",
    "x_p",
    "stick_time",
    "events",
    "event_kinds",
    "x_S_end",
];

/// The per-period series as a CSV or JSON-lines table: `events` counts the
/// period's events, `event_kinds` lists their kinds separated by `;`.
pub fn periods_table(periods: &[PeriodRecord], json_lines: bool) -> String {
    let rows = periods
        .iter()
        .map(|r| {
            let kinds: Vec<&str> = r.events.iter().map(|e| event_name(&e.kind)).collect();
            vec![
                json!(r.period),
                json!(r.v_p),
                json!(r.step),
                json!(r.stick_time),
                json!(r.events.len()),
                json!(kinds.join(";")),
                json!(r.x_start + r.step),
            ]
        })
        .collect();
    table(&PERIOD_COLUMNS, rows, json_lines)
}

/// What `run --trajectory` / `--periods-series` asks for.
#[derive(Debug, Clone, Default)]
pub struct TrajectoryRequest {
    /// Write the states here.
    pub trajectory: Option<std::path::PathBuf>,
    /// Sample times (s), one a line or a CSV column `t`.
    pub times: Option<std::path::PathBuf>,
    /// Or a sample rate (Hz) over `periods`.
    pub sample_rate: Option<f64>,
    /// Periods `A..=B` for `sample_rate`.
    pub periods: Option<(u64, u64)>,
    /// Write the per-period series of the start-up here.
    pub periods_series: Option<std::path::PathBuf>,
}

impl TrajectoryRequest {
    /// True if anything is asked for.
    pub fn any(&self) -> bool {
        self.trajectory.is_some() || self.periods_series.is_some()
    }
}

/// Writes what `request` asks for, for `scene`; the per-period series
/// covers the start-up to `p_0.99` (or the last sampled period, if later).
pub fn write_requested(scene: &crate::Scene, request: &TrajectoryRequest) -> Result<(), String> {
    use crate::compare::exact;
    let (signal, motor) = crate::simulation::build(scene).map_err(|e| e.to_string())?;
    let period = signal.period();
    let times: Vec<f64> = match (&request.trajectory, &request.times, request.sample_rate) {
        (None, _, _) => Vec::new(),
        (Some(_), Some(path), None) => {
            let options = crate::compare::read::ReadOptions::default();
            crate::compare::read::read_times(path, &options).map_err(|e| e.to_string())?
        }
        (Some(_), None, Some(rate)) => {
            if !(rate > 0.0 && rate.is_finite()) {
                return Err(format!(
                    "--sample-rate = {}: must be a positive number",
                    Num(rate)
                ));
            }
            let (a, b) = request.periods.unwrap_or((1, 1));
            let (t0, t1) = ((a - 1) as f64 * period, b as f64 * period);
            // Compared as a float: a count beyond u64 must not wrap.
            let samples = ((t1 - t0) * rate).floor();
            if samples.is_nan() || samples > MAX_SAMPLES as f64 {
                return Err(format!(
                    "--sample-rate = {}: {} samples over periods {a}..{b} is too many (at most {MAX_SAMPLES})",
                    Num(rate),
                    Num(samples)
                ));
            }
            let n = samples as u64;
            (0..=n)
                .map(|i| t0 + i as f64 / rate)
                .filter(|t| *t <= t1)
                .collect()
        }
        (Some(_), Some(_), Some(_)) => {
            return Err("give either --times or --sample-rate, not both".to_owned());
        }
        (Some(_), None, None) => {
            return Err("--trajectory needs --times FILE or --sample-rate HZ".to_owned());
        }
    };
    if times.len() as u64 > MAX_SAMPLES {
        return Err(format!(
            "--times: {} samples, more than the {MAX_SAMPLES} one export may have; split the file",
            times.len()
        ));
    }
    let max = scene.run.max_periods;
    if let Some(&last) = times.last()
        && last > max as f64 * period
    {
        return Err(format!(
            "time {} s is after the simulated span of run.max_periods = {max} periods",
            Num(last)
        ));
    }
    let startup = if request.periods_series.is_some() {
        let mut exact_scene = scene.clone();
        exact_scene.run.engine = crate::scene::EngineKind::Event;
        // p_0.99 needs the start-up, which a run simulates only when asked.
        let startup = crate::scene::Indicator::StartupTime;
        if !exact_scene.outputs.indicators.contains(&startup) {
            exact_scene.outputs.indicators.push(startup);
        }
        crate::simulation::run(&exact_scene)
            .map_err(|e| e.to_string())?
            .startup_periods
            .unwrap_or(1)
    } else {
        0
    };
    let series = exact::evaluate(&signal, &motor, &times, startup).map_err(|e| e.to_string())?;
    if let Some(path) = &request.trajectory {
        let text = trajectory_table(&series.states, is_json_lines(path));
        crate::output::write_atomically(path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    if let Some(path) = &request.periods_series {
        let text = periods_table(&series.periods, is_json_lines(path));
        crate::output::write_atomically(path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}
