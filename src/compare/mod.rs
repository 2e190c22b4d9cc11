//! Cross-validation of a user's fixed-step results (`stickslip compare`):
//! the user's files are read ([`read`]), the exact solution is evaluated at
//! the user's own times ([`exact`]), the rod motion is checked ([`rod`]),
//! events are detected and matched ([`events`]), errors are measured per
//! file and, over several files of one scene at different steps, their
//! convergence order is fitted ([`convergence`]).
//!
//! The errors, one table ([`Metric`]) that text, JSON, the verdict and the
//! fits loop over. Each has an absolute value and a value relative to a
//! scale of the scene; the tolerance applies to the relative value:
//!
//! | metric | absolute | relative to |
//! | --- | --- | --- |
//! | `v_inf` | `abs(v_inf,user - v_inf)`, `v_inf,user` = the user's last `v_p` | `abs(v_inf)` |
//! | `v_p_max`, `v_p_rms` | max and RMS of `v_p,user - v_p` over the user's periods | `abs(v_inf)` |
//! | `startup_periods` | `abs(p_0.99,user - p_0.99)` (docs/model.md section 3) | `p_0.99` |
//! | `x_S_max`, `x_S_rms` | max and RMS of `x_S,user - x_S` at the user's times | the stroke |
//! | `v_S_max`, `v_S_rms` | max and RMS of `v_S,user - v_S` | `max abs(v_R)` |
//! | `event_time_max`, `event_time_rms` | max and RMS time error of the matched events | `T` |

pub(crate) mod convergence;
pub(crate) mod events;
pub(crate) mod exact;
pub(crate) mod figure;
pub(crate) mod read;
pub(crate) mod rod;

use crate::scene::{EngineKind, Scene};
use crate::signal::Signal;
use crate::signal::description::SignalDescription;
use crate::simulation;
use read::{ReadOptions, UserData};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::PathBuf;
use thiserror::Error;

/// What can go wrong in a comparison (all of it is bad input or a failed
/// simulation; a failed verdict is a result).
#[derive(Debug, Error)]
pub enum CompareError {
    /// A user's file holds something it must not.
    #[error("{file}: {}{reason}", location(.column, .row))]
    Data {
        /// The file.
        file: String,
        /// The column or variable, if one is at fault.
        column: Option<String>,
        /// The row or element, if one is at fault.
        row: Option<String>,
        /// What is wrong.
        reason: String,
    },
    /// A file cannot be read.
    #[error("cannot read {file}: {reason}")]
    Io {
        /// The file.
        file: String,
        /// The reader's complaint.
        reason: String,
    },
    /// An option has a value that cannot be used.
    #[error("{option} = {value}: {reason}")]
    Option {
        /// The option.
        option: String,
        /// Its value.
        value: String,
        /// Why not.
        reason: String,
    },
    /// The scene cannot be simulated.
    #[error(transparent)]
    Simulation(#[from] crate::error::Error),
}

fn location(column: &Option<String>, row: &Option<String>) -> String {
    match (column, row) {
        (Some(c), Some(r)) => format!("column {c}, {r}: "),
        (Some(c), None) => format!("column {c}: "),
        (None, Some(r)) => format!("{r}: "),
        (None, None) => String::new(),
    }
}

impl CompareError {
    pub(crate) fn data(
        file: &str,
        column: Option<&str>,
        row: Option<String>,
        reason: String,
    ) -> Self {
        CompareError::Data {
            file: file.to_owned(),
            column: column.map(str::to_owned),
            row,
            reason,
        }
    }

    pub(crate) fn io(file: &str, reason: String) -> Self {
        CompareError::Io {
            file: file.to_owned(),
            reason,
        }
    }
}

impl From<crate::error::SimulationError> for CompareError {
    fn from(e: crate::error::SimulationError) -> Self {
        CompareError::Simulation(e.into())
    }
}

/// The error metrics (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
#[value(rename_all = "verbatim")]
#[allow(non_camel_case_types)]
pub enum Metric {
    /// Steady-state velocity.
    v_inf,
    /// Largest per-period mean-velocity error.
    v_p_max,
    /// RMS per-period mean-velocity error.
    v_p_rms,
    /// Start-up period difference.
    startup_periods,
    /// Largest slider position error.
    x_S_max,
    /// RMS slider position error.
    x_S_rms,
    /// Largest slider velocity error.
    v_S_max,
    /// RMS slider velocity error.
    v_S_rms,
    /// Largest event-time error.
    event_time_max,
    /// RMS event-time error.
    event_time_rms,
}

impl Metric {
    /// Every metric, in report order.
    pub const ALL: [Metric; 10] = [
        Metric::v_inf,
        Metric::v_p_max,
        Metric::v_p_rms,
        Metric::startup_periods,
        Metric::x_S_max,
        Metric::x_S_rms,
        Metric::v_S_max,
        Metric::v_S_rms,
        Metric::event_time_max,
        Metric::event_time_rms,
    ];

    /// Its name in reports and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Metric::v_inf => "v_inf",
            Metric::v_p_max => "v_p_max",
            Metric::v_p_rms => "v_p_rms",
            Metric::startup_periods => "startup_periods",
            Metric::x_S_max => "x_S_max",
            Metric::x_S_rms => "x_S_rms",
            Metric::v_S_max => "v_S_max",
            Metric::v_S_rms => "v_S_rms",
            Metric::event_time_max => "event_time_max",
            Metric::event_time_rms => "event_time_rms",
        }
    }

    /// Unit of the absolute error.
    pub fn unit(self) -> &'static str {
        match self {
            Metric::v_inf | Metric::v_p_max | Metric::v_p_rms => "m/s",
            Metric::v_S_max | Metric::v_S_rms => "m/s",
            Metric::startup_periods => "periods",
            Metric::x_S_max | Metric::x_S_rms => "m",
            Metric::event_time_max | Metric::event_time_rms => "s",
        }
    }

    fn index(self) -> usize {
        Metric::ALL.iter().position(|m| *m == self).unwrap_or(0)
    }
}

/// Settings of a comparison.
#[derive(Debug, Clone)]
pub struct CompareOptions {
    /// How to read the files.
    pub read: ReadOptions,
    /// Tolerance on the relative error of `metric`.
    pub tolerance: f64,
    /// The metric of the verdict.
    pub metric: Metric,
    /// Tolerance of the rod check, relative to the stroke.
    pub rod_tolerance: f64,
    /// `|v_R - v_S|` below this, relative to `max |v_R|`, counts as stick.
    pub stick_tolerance: f64,
}

/// Default tolerance of the verdict (relative).
pub(crate) const DEFAULT_TOLERANCE: f64 = 1e-3;
/// Default stick tolerance (relative to `max |v_R|`).
pub(crate) const DEFAULT_STICK_TOLERANCE: f64 = 1e-9;

impl Default for CompareOptions {
    fn default() -> Self {
        Self {
            read: ReadOptions::default(),
            tolerance: DEFAULT_TOLERANCE,
            metric: Metric::v_inf,
            rod_tolerance: rod::DEFAULT_ROD_TOLERANCE,
            stick_tolerance: DEFAULT_STICK_TOLERANCE,
        }
    }
}

/// One error: absolute and relative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorValue {
    /// In the metric's unit.
    pub absolute: f64,
    /// Relative to the metric's scale.
    pub relative: f64,
}

/// The comparison of one file.
#[derive(Debug, Clone)]
pub struct FileReport {
    /// The file.
    pub file: String,
    /// Samples (rows of the time column).
    pub samples: usize,
    /// Fixed step from the time column (s).
    pub step: Option<f64>,
    /// First and last sample time (s).
    pub span: Option<(f64, f64)>,
    /// Periods of the per-period series.
    pub periods: usize,
    /// The user's `v_inf` (last `v_p`).
    pub v_inf: Option<f64>,
    /// The user's `p_0.99`.
    pub startup_periods: Option<u64>,
    /// Rod check, when the file has `x_R`.
    pub rod: Option<rod::RodCheck>,
    /// Event matching, when the file has `v_S`.
    pub events: Option<events::EventMatch>,
    /// Errors by [`Metric::ALL`] index.
    pub errors: [Option<ErrorValue>; 10],
    /// Per-period `(p, v_p,user - v_p)`.
    pub period_errors: Vec<(u64, f64)>,
    /// Samples `(t, v_S,user, v_S)` for the figure.
    pub velocity: Vec<(f64, f64, f64)>,
    /// True if the chosen metric is within the tolerance; `None` when the
    /// file has no data for it.
    pub pass: Option<bool>,
}

/// A whole comparison.
#[derive(Debug, Clone)]
pub struct Report {
    /// The scene's signal.
    pub signal: SignalDescription,
    /// Exact `v_inf` (m/s).
    pub v_inf: f64,
    /// Exact `p_0.99`.
    pub startup_periods: Option<u64>,
    /// Tolerance and metric of the verdict.
    pub tolerance: f64,
    /// The verdict's metric.
    pub metric: Metric,
    /// Per file.
    pub files: Vec<FileReport>,
    /// Order fits by metric, over the files with a step.
    pub convergence: Vec<(Metric, convergence::OrderFit)>,
    /// True if every file with data for the metric passes.
    pub pass: bool,
}

fn max_rms(d: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (mut m, mut s, mut n) = (0.0_f64, 0.0, 0usize);
    for x in d {
        m = m.max(x.abs());
        s += x * x;
        n += 1;
    }
    (n > 0).then(|| (m, (s / n as f64).sqrt()))
}

/// Compares the user's files with the exact solution of `scene`.
pub fn compare(
    scene: &Scene,
    files: &[PathBuf],
    options: &CompareOptions,
) -> Result<Report, CompareError> {
    if !(options.tolerance > 0.0 && options.tolerance.is_finite()) {
        return Err(CompareError::Option {
            option: "--tolerance".into(),
            value: options.tolerance.to_string(),
            reason: "must be a positive number".into(),
        });
    }
    let mut exact_scene = scene.clone();
    exact_scene.run.engine = EngineKind::Event;
    let (signal, motor) = simulation::build(&exact_scene)?;
    let run = simulation::run(&exact_scene)?;
    let v_inf = run.indicators.v_inf;
    let description = SignalDescription::new(&scene.signal, &signal, &motor);
    let max_periods = scene.run.max_periods;
    let mut reports = Vec::new();
    for path in files {
        let data = read::read(path, &options.read)?;
        reports.push(compare_file(
            path,
            &data,
            &signal,
            &motor,
            &description,
            v_inf,
            run.startup_periods,
            max_periods,
            options,
        )?);
    }
    let metric = options.metric;
    if reports.iter().all(|r| r.pass.is_none()) {
        return Err(CompareError::Option {
            option: "--metric".into(),
            value: metric.name().into(),
            reason: "no file has data for it (v_inf and v_p need p and v_p, startup_periods \
                     a start-up reaching 99 %, x_S and v_S samples, event times v_S samples \
                     with events)"
                .into(),
        });
    }
    let with_step: Vec<&FileReport> = reports.iter().filter(|r| r.step.is_some()).collect();
    let convergence = if with_step.len() >= 2 {
        Metric::ALL
            .iter()
            .filter(|m| **m != Metric::startup_periods)
            .filter_map(|&m| {
                let pairs: Vec<(f64, f64)> = with_step
                    .iter()
                    .filter_map(|r| Some((r.step?, r.errors[m.index()]?.relative)))
                    .collect();
                (pairs.len() == with_step.len()).then(|| {
                    let (h, e): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
                    (m, convergence::fit(&h, &e, options.tolerance))
                })
            })
            .collect()
    } else {
        Vec::new()
    };
    Ok(Report {
        signal: description,
        v_inf,
        startup_periods: run.startup_periods,
        tolerance: options.tolerance,
        metric,
        pass: reports.iter().all(|r| r.pass != Some(false)),
        files: reports,
        convergence,
    })
}

#[allow(clippy::too_many_arguments)]
fn compare_file(
    path: &std::path::Path,
    data: &UserData,
    signal: &Signal,
    motor: &crate::motor::Motor,
    description: &SignalDescription,
    v_inf: f64,
    startup_exact: Option<u64>,
    max_periods: u64,
    options: &CompareOptions,
) -> Result<FileReport, CompareError> {
    let file = path.display().to_string();
    let period = signal.period();
    let span_end = max_periods as f64 * period;
    let times: &[f64] = data.t.as_ref().map_or(&[], |c| &c.values);
    if let Some(&last) = times.last()
        && last > span_end
    {
        let name = data.t.as_ref().map_or("t", |c| c.name.as_str());
        return Err(CompareError::data(
            &file,
            Some(name),
            Some(format!("row {}", times.len())),
            format!(
                "time {last} s is after the simulated span, which ends after run.max_periods = \
                 {max_periods} periods at {span_end} s"
            ),
        ));
    }
    let user_periods: Vec<u64> = match (&data.p, &data.v_p) {
        (Some(p), Some(_)) => p.values.iter().map(|&q| q as u64).collect(),
        (None, Some(v)) => (1..=v.values.len() as u64).collect(),
        _ => Vec::new(),
    };
    if let Some(&p_last) = user_periods.last()
        && p_last > max_periods
    {
        return Err(CompareError::data(
            &file,
            Some(data.p.as_ref().map_or("p", |c| c.name.as_str())),
            Some(format!("row {}", user_periods.len())),
            format!("period {p_last} is beyond run.max_periods = {max_periods}"),
        ));
    }
    let min_periods = user_periods.last().copied().unwrap_or(0);
    let exact = exact::evaluate(signal, motor, times, min_periods)?;
    let mut errors = [None; 10];
    let mut set = |m: Metric, absolute: f64, scale: f64| {
        errors[m.index()] = Some(ErrorValue {
            absolute,
            relative: absolute / scale,
        });
    };
    // Per-period series.
    let mut period_errors = Vec::new();
    let mut user_v_inf = None;
    let mut user_startup = None;
    if let Some(v) = &data.v_p {
        period_errors = user_periods
            .iter()
            .zip(&v.values)
            .map(|(&p, &vp)| (p, vp - exact.periods[p as usize - 1].v_p))
            .collect();
        let last = *v.values.last().unwrap_or(&0.0);
        user_v_inf = Some(last);
        set(Metric::v_inf, (last - v_inf).abs(), v_inf.abs());
        if let Some((m, r)) = max_rms(period_errors.iter().map(|e| e.1)) {
            set(Metric::v_p_max, m, v_inf.abs());
            set(Metric::v_p_rms, r, v_inf.abs());
        }
        user_startup = (last != 0.0)
            .then(|| {
                user_periods
                    .iter()
                    .zip(&v.values)
                    .find(|(_, vp)| **vp / last >= 0.99)
                    .map(|(p, _)| *p)
            })
            .flatten();
        if let (Some(u), Some(e)) = (user_startup, startup_exact) {
            set(Metric::startup_periods, u.abs_diff(e) as f64, e as f64);
        }
    }
    let states = &exact.states;
    if let Some(x) = &data.x_s
        && let Some((m, r)) = max_rms(x.values.iter().zip(states).map(|(u, s)| u - s.x_s))
    {
        set(Metric::x_S_max, m, description.stroke);
        set(Metric::x_S_rms, r, description.stroke);
    }
    let v_scale = signal.velocity_scale();
    let mut event_match = None;
    let mut velocity = Vec::new();
    if let Some(v) = &data.v_s {
        if let Some((m, r)) = max_rms(v.values.iter().zip(states).map(|(u, s)| u - s.v_s)) {
            set(Metric::v_S_max, m, v_scale);
            set(Metric::v_S_rms, r, v_scale);
        }
        let v_r: Vec<f64> = states.iter().map(|s| s.v_r).collect();
        let (t0, t1) = (times[0], times[times.len() - 1]);
        // A change out of the first sample (the start from rest) cannot be
        // placed in time: left out, like exact events at t0.
        let mut user = events::detect(times, &v.values, &v_r, options.stick_tolerance * v_scale);
        user.retain(|e| e.t > t0);
        let mut exact_events = events::exact_events(&exact.periods, period, t0, t1);
        exact_events.retain(|e| e.t > t0);
        let matched = events::match_events(&exact_events, &user, 0.25 * period);
        if let (Some(m), Some(r)) = (matched.max_time_error, matched.rms_time_error) {
            set(Metric::event_time_max, m, period);
            set(Metric::event_time_rms, r, period);
        }
        event_match = Some(matched);
        velocity = times
            .iter()
            .zip(&v.values)
            .zip(states)
            .map(|((t, u), s)| (*t, *u, s.v_s))
            .collect();
    }
    let rod = data.x_r.as_ref().map(|x| {
        let exact_x: Vec<f64> = states.iter().map(|s| s.x_r).collect();
        rod::check(
            times,
            &x.values,
            &exact_x,
            description,
            options.rod_tolerance,
        )
    });
    let pass = errors[options.metric.index()].map(|e| e.relative <= options.tolerance);
    Ok(FileReport {
        file,
        samples: times.len(),
        step: data.step(),
        span: (!times.is_empty()).then(|| (times[0], times[times.len() - 1])),
        periods: user_periods.len(),
        v_inf: user_v_inf,
        startup_periods: user_startup,
        rod,
        events: event_match,
        errors,
        period_errors,
        velocity,
        pass,
    })
}

impl Report {
    /// The JSON object (keys in docs/interface.md).
    pub fn to_json(&self) -> Value {
        let files: Vec<Value> = self
            .files
            .iter()
            .map(|f| {
                let errors: serde_json::Map<String, Value> = Metric::ALL
                    .iter()
                    .map(|m| {
                        let v = f.errors[m.index()]
                            .map(|e| json!({"absolute": e.absolute, "relative": e.relative}));
                        (m.name().to_owned(), json!(v))
                    })
                    .collect();
                json!({
                    "file": f.file,
                    "samples": f.samples,
                    "step": f.step,
                    "t_first": f.span.map(|s| s.0),
                    "t_last": f.span.map(|s| s.1),
                    "periods": f.periods,
                    "v_inf": f.v_inf,
                    "startup_periods": f.startup_periods,
                    "rod": f.rod,
                    "events": f.events,
                    "errors": errors,
                    "pass": f.pass,
                })
            })
            .collect();
        let convergence: serde_json::Map<String, Value> = self
            .convergence
            .iter()
            .map(|(m, fit)| (m.name().to_owned(), json!(fit)))
            .collect();
        json!({
            "stickslip_version": env!("CARGO_PKG_VERSION"),
            "period": self.signal.period,
            "v_inf": self.v_inf,
            "startup_periods": self.startup_periods,
            "metric": self.metric.name(),
            "tolerance": self.tolerance,
            "pass": self.pass,
            "files": files,
            "convergence": convergence,
        })
    }

    /// Readable text.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "exact: T = {:e} s, v_inf = {} m/s, p_0.99 = {}",
            self.signal.period,
            self.v_inf,
            self.startup_periods
                .map_or("undefined".to_owned(), |p| p.to_string())
        );
        for f in &self.files {
            let _ = writeln!(s, "\n{}", f.file);
            if let (Some(h), Some((a, b))) = (f.step, f.span) {
                let _ = writeln!(
                    s,
                    "  {} samples, step {h:e} s ({:.1} steps per period), t = {a:e} .. {b:e} s",
                    f.samples,
                    self.signal.period / h
                );
            }
            if f.periods > 0 {
                let _ = writeln!(
                    s,
                    "  {} periods, v_inf = {} m/s, p_0.99 = {}",
                    f.periods,
                    f.v_inf.unwrap_or(f64::NAN),
                    f.startup_periods
                        .map_or("not reached".to_owned(), |p| p.to_string())
                );
            }
            if let Some(r) = &f.rod {
                if r.matches {
                    let _ = writeln!(
                        s,
                        "  rod: matches the scene (max deviation {:.3e} m, {:.2e} of the stroke)",
                        r.max_deviation, r.relative_deviation
                    );
                } else {
                    let _ = writeln!(
                        s,
                        "  rod: DIFFERS from the scene (max deviation {:.3e} m, {:.2e} of the \
                         stroke): {}",
                        r.max_deviation,
                        r.relative_deviation,
                        r.message.as_deref().unwrap_or("")
                    );
                }
            }
            if let Some(e) = &f.events {
                let _ = writeln!(
                    s,
                    "  events: {} exact, {} found, {} matched, {} missed, {} spurious",
                    e.exact, e.found, e.matched, e.missed, e.spurious
                );
            }
            for m in Metric::ALL {
                if let Some(e) = f.errors[m.index()] {
                    let _ = writeln!(
                        s,
                        "  {:<16} {:>12.4e} {:<8} relative {:.4e}{}",
                        m.name(),
                        e.absolute,
                        m.unit(),
                        e.relative,
                        if (m == Metric::event_time_max || m == Metric::event_time_rms)
                            && f.step.is_some()
                        {
                            format!(" ({:.2} steps)", e.absolute / f.step.unwrap_or(1.0))
                        } else {
                            String::new()
                        }
                    );
                }
            }
            if let (Some(pass), Some(e)) = (f.pass, f.errors[self.metric.index()]) {
                let _ = writeln!(
                    s,
                    "  verdict: {} ({} relative {:.3e} vs tolerance {:e})",
                    if pass { "pass" } else { "FAIL" },
                    self.metric.name(),
                    e.relative,
                    self.tolerance
                );
            }
        }
        if !self.convergence.is_empty() {
            let _ = writeln!(
                s,
                "\nconvergence over {} files (relative errors):",
                self.files.len()
            );
            for (m, fit) in &self.convergence {
                match (fit.supported, fit.order, fit.standard_error) {
                    (true, Some(q), Some(se)) => {
                        let _ = writeln!(
                            s,
                            "  {:<16} order {q:.2} ± {se:.2}{}",
                            m.name(),
                            fit.step_for_tolerance.map_or(String::new(), |h| format!(
                                ", step for {:e}: {h:.3e} s",
                                self.tolerance
                            ))
                        );
                    }
                    _ => {
                        let _ = writeln!(
                            s,
                            "  {:<16} no order: {}",
                            m.name(),
                            fit.reason.as_deref().unwrap_or("")
                        );
                    }
                }
            }
        }
        let _ = writeln!(s, "\nverdict: {}", if self.pass { "pass" } else { "FAIL" });
        s
    }
}
