//! Cross-validation of a user's fixed-step results (`stickslip compare`),
//! in two halves kept apart: the readers turn files into arrays
//! (`read`: names and units; CSV in `csv_file`, MAT-files in
//! `mat_file`), and the analysis takes arrays ([`compare_data`], for any
//! caller with arrays): the exact solution is evaluated at the user's own
//! times (`exact`), the per-period series is formed from `x_S` when the
//! file has none (`periods`), the rod motion is checked (`rod`),
//! events are located and matched (`events`), errors are measured per
//! file (`analysis`) and, over several files of one scene at different
//! steps, their convergence order is fitted (`convergence`).
//! docs/model.md section 12 states the equations of the period ends, the
//! event times and the split of the `v_inf` error.
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
//!
//! The `v_inf` error of a file ending at period `P` splits into the
//! step-size part `v_p,user(P) - v_p(P)` and the truncation part
//! `v_p(P) - v_inf` ([`VInfSplit`]); the verdict and the order fit of
//! `v_inf` take the step-size part ([`FileReport::judged`]).

mod analysis;
pub(crate) mod convergence;
#[cfg(feature = "files")]
mod csv_file;
pub(crate) mod events;
pub(crate) mod exact;
#[cfg(feature = "files")]
mod mat_file;
mod output;
pub(crate) mod periods;
pub(crate) mod read;
pub(crate) mod reference;
pub(crate) mod rod;

use crate::scene::{EngineKind, Scene};
use crate::signal::description::SignalDescription;
use crate::simulation;
use read::ReadOptions;
pub use read::{Column, UserData};
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
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "cli",
    derive(clap::ValueEnum),
    value(rename_all = "verbatim")
)]
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

    pub(crate) fn index(self) -> usize {
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
    /// How the per-period series was found from the samples (`None`: the
    /// file's own `v_p`, or no series).
    pub period_ends: Option<periods::PeriodEnds>,
    /// The `v_inf` error split into its step-size and truncation parts.
    pub v_inf_split: Option<VInfSplit>,
    /// What the reader of the report must know (truncation dominates...).
    pub warnings: Vec<String>,
    /// Per-period `(p, v_p,user - v_p)`.
    pub period_errors: Vec<(u64, f64)>,
    /// Samples `(t, v_S,user, v_S)` for the figure.
    pub velocity: Vec<(f64, f64, f64)>,
    /// True if the chosen metric is within the tolerance; `None` when the
    /// file has no data for it.
    pub pass: Option<bool>,
}

/// The `v_inf` error of a file whose last period is `P`:
/// `v_inf,user - v_inf = (v_p,user(P) - v_p(P)) + (v_p(P) - v_inf)`, the
/// step-size part (the user's `v_p` against the exact `v_p` of the same
/// period) plus the truncation part (the exact `v_p` of that period
/// against `v_inf`: the start-up not yet over). Signed, m/s.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct VInfSplit {
    /// The file's last period `P`.
    pub period: u64,
    /// Exact `v_p(P)` (m/s).
    pub exact_v_p: f64,
    /// `v_p,user(P) - v_p(P)` (m/s).
    pub step_size: f64,
    /// `v_p(P) - v_inf` (m/s).
    pub truncation: f64,
    /// `step_size / abs(v_inf)`.
    pub step_size_relative: f64,
    /// `truncation / abs(v_inf)`.
    pub truncation_relative: f64,
    /// True when `abs(truncation) > abs(step_size)`.
    pub truncation_dominates: bool,
}

impl FileReport {
    /// The error judged by the verdict and fitted over steps: the metric's,
    /// except for `v_inf`, where it is the step-size part of the split.
    pub fn judged(&self, metric: Metric) -> Option<ErrorValue> {
        match (metric, &self.v_inf_split) {
            (Metric::v_inf, Some(split)) => Some(ErrorValue {
                absolute: split.step_size.abs(),
                relative: split.step_size_relative.abs(),
            }),
            _ => self.errors[metric.index()],
        }
    }
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

/// Compares the user's files with the exact solution of `scene`: each
/// file is read (CSV or MAT, by extension), then the arrays are compared
/// ([`compare_data`]). The readers are the `files` feature's.
#[cfg(feature = "files")]
pub fn compare(
    scene: &Scene,
    files: &[PathBuf],
    options: &CompareOptions,
) -> Result<Report, CompareError> {
    check_options(options)?;
    let data = files
        .iter()
        .map(|path| Ok((path.display().to_string(), read::read(path, &options.read)?)))
        .collect::<Result<Vec<_>, CompareError>>()?;
    compare_data(scene, &data, options)
}

fn check_options(options: &CompareOptions) -> Result<(), CompareError> {
    if !(options.tolerance > 0.0 && options.tolerance.is_finite()) {
        return Err(CompareError::Option {
            option: "--tolerance".into(),
            value: options.tolerance.to_string(),
            reason: "must be a positive number".into(),
        });
    }
    Ok(())
}

/// Compares results given as arrays, each with the name it is reported
/// under, with the exact solution of `scene` (`options.read` is not
/// used: the arrays are in SI units). The data are validated as a file's
/// are ([`UserData::validate`]).
pub fn compare_data(
    scene: &Scene,
    data: &[(String, UserData)],
    options: &CompareOptions,
) -> Result<Report, CompareError> {
    check_options(options)?;
    for (name, d) in data {
        d.validate(name)?;
    }
    let mut exact_scene = scene.clone();
    exact_scene.run.engine = EngineKind::Event;
    let (signal, motor) = simulation::build_prescribed(&exact_scene, "compare")?;
    let run = simulation::steady(&exact_scene)?;
    let v_inf = run.indicators.v_inf;
    let description = SignalDescription::new(&scene.signal, &signal, &motor);
    let exact = analysis::Exact {
        signal: &signal,
        motor: &motor,
        description: &description,
        v_inf,
        startup_periods: run.startup_periods,
        max_periods: scene.run.max_periods,
    };
    let mut reports = Vec::new();
    for (name, d) in data {
        reports.push(analysis::compare_file(name, d, &exact, options)?);
    }
    let metric = options.metric;
    if reports.iter().all(|r| r.pass.is_none()) {
        let found: Vec<String> = data
            .iter()
            .map(|(name, d)| format!("{name} has {}", d.found()))
            .collect();
        return Err(CompareError::Option {
            option: "--metric".into(),
            value: metric.name().into(),
            reason: format!(
                "no file has data for it (v_inf and v_p need p and v_p or the samples x_S over \
                 a whole period, startup_periods a start-up reaching 99 %, x_S and v_S \
                 samples, event times v_S samples with events); {}; name columns with \
                 --var-t, --var-x-s, --var-v-s, --var-x-r, --var-p, --var-v-p",
                found.join("; ")
            ),
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
                    .filter_map(|r| Some((r.step?, r.judged(m)?.relative)))
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
