//! Parameter sweeps: a grid of scenes run in parallel, one output row per
//! case, shardable over a job array and resumable.
//!
//! A sweep file (TOML) names a base scene and the axes to vary; the grid is
//! the cartesian product of the axes. Every case is checked with
//! [`Scene::validate`] when the sweep is loaded, before anything runs or is
//! written. `stickslip sweep FILE` runs the grid (or one shard of it) with
//! rayon and writes one CSV or JSON-lines row per case; `stickslip merge`
//! joins shard outputs.
//!
//! # Format
//!
//! ```toml
//! base = "../scenes/paper_default.toml"   # relative to the sweep file;
//!                                         # omitted: Scene::default()
//! [axes]                      # each a non-empty list without repeats
//! level = [3, 6, 9, 12, 15]   # f_max level L = n sqrt(kappa) (37): sqrt_kappa = L / n
//! harmonics = [2, 3, 4]       # n
//! sigma = [false, true]       # Lanczos sigma factors (15)
//!
//! [outputs]                   # optional
//! indicators = ["v_inf", "startup_time"]   # default: the base scene's
//! format = "csv"              # "csv" | "jsonl"; an output named *.csv or *.jsonl
//!                             # overrides it                   (default "csv")
//! ```
//!
//! The axes, in their fixed order (the first varies slowest):
//!
//! | axis | sets | values |
//! | --- | --- | --- |
//! | `level` | `sqrt(kappa) = level / n` (37), fourier signals | > 0 |
//! | `sqrt_kappa` | `signal.sqrt_kappa` | > 0 |
//! | `kappa` | `signal.kappa` | > 0 |
//! | `harmonics` | `signal.harmonics`, fourier signals | integers 1..=256 |
//! | `sigma` | `signal.sigma`, fourier signals | booleans |
//! | `stroke` | `signal.stroke` (or the `scale_to_stroke` target of kind = "harmonics") | > 0 |
//! | `duty` | `signal.duty` | (0, 1] |
//! | `mu_static` | `motor.mu_static` | >= 0 |
//! | `mu_dynamic` | `motor.mu_dynamic` | >= 0 |
//! | `contact_force` | `motor.contact_force` | > 0 |
//! | `slider_mass` | `motor.slider_mass` | > 0 |
//! | `extra_acceleration` | `motor.extra_acceleration` | finite |
//!
//! At most one of `level`, `sqrt_kappa` and `kappa` may be given; `level`
//! takes `n` from the `harmonics` axis, or from the base scene without one.
//! Axes that do not fit the base signal (`harmonics` with `kind = "ideal"`)
//! are errors. The `base` scene's `[outputs] trajectory` and `events` are
//! ignored: a sweep writes one row per case.
//!
//! # Cases
//!
//! Case `i` (`0 <= i < N`, `N` the product of the axis lengths) takes the
//! values of a mixed-radix number in the axis order above, the last axis
//! varying fastest, like nested loops. The index depends on the sweep file
//! only, so shards, reruns and merges agree on it.
//!
//! # Output
//!
//! One row per case, sorted by case, with the columns
//!
//! * `case`, then one column per axis (in the order above);
//! * each requested indicator under its `docs/interface.md` name, in the order
//!   of [`Indicator::ALL`]; `stiction_fraction` (the start-up from rest, as
//!   in `stickslip run --json`) is followed by `stiction_fraction_steady`
//!   and `velocity_per_power` by `apparent_power` (VA);
//! * `period` (s), `startup_periods`, `periods_simulated`, `events_total`
//!   (events of the simulated start-up), `wall_time_s` (left out with
//!   [`Options::timing`] `= false`, so that the same sweep gives the same
//!   bytes), `error_v_inf` (estimated absolute error of `v_inf`), and
//!   `failure` (empty, or why the case could not be run).
//!
//! Numbers are written with the shortest digits that read back to the same
//! `f64`: Rust's `{}` (`{:e}` below `1e-4` and from `1e16`) in CSV,
//! serde_json's in JSON lines.
//! Values that do not exist (a start-up that was not reached, an infinite
//! smoothness) are empty in CSV and `null` in JSON lines. A JSON-lines row
//! is one object with the keys in column order.
//!
//! # Shards, reruns, merging
//!
//! A [`Shard`] `i/N` (`1 <= i <= N`, 1-based like Slurm's
//! `--array=1-N`) takes the cases with `index % N == i - 1`. If the output
//! file exists, its rows are kept and only the missing cases are run (a row
//! is kept only when its columns and axis values match the sweep; any
//! mismatch is an error and the file is left alone). The output is written
//! to a temporary file in the same directory and renamed over the target,
//! at the end and at checkpoints while running (about every 10 s), so an
//! interrupted run leaves the rows finished so far, and never a
//! half-written file. A case that fails is written with its `failure` and
//! not rerun. [`merge`] joins shard outputs: same columns required, rows
//! sorted by case, duplicates allowed only when identical.
//!
//! ```sh
//! # One Slurm job array, 16 shards; a rerun of the array skips finished cases.
//! #SBATCH --array=1-16
//! stickslip sweep grid.toml --quiet --no-timing \
//!     --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT" \
//!     -j "$SLURM_CPUS_PER_TASK" -o "grid.$SLURM_ARRAY_TASK_ID.csv"
//! # Afterwards:
//! stickslip merge grid.csv grid.*.csv
//! ```
//!
//! # Library use
//!
//! ```
//! use stickslip::Scene;
//! use stickslip::sweep::{self, Axis, Sweep};
//! use std::path::Path;
//!
//! let text = "[axes]\nlevel = [6]\nharmonics = [2, 3]\n[outputs]\nindicators = [\"v_inf\"]\n";
//! let sweep = Sweep::from_toml_str(text, "<string>", Path::new("."))?;
//! let cases = sweep.cases();
//! assert_eq!(cases.len(), 2);
//! assert_eq!(cases[1].value(Axis::Harmonics).and_then(|v| v.as_f64()), Some(3.0));
//! // level 6 at n = 3: sqrt(kappa) = 2
//! assert_eq!(cases[1].scene.signal, Scene::from_toml_str(
//!     "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nsqrt_kappa = 2\nharmonics = 3\nsigma = true",
//!     "<string>",
//! )?.signal);
//! let results = sweep::run_cases(&cases, false);
//! let v_inf: Vec<f64> = results
//!     .iter()
//!     .map(|r| r.as_ref().unwrap().report.indicators.v_inf)
//!     .collect();
//! assert!(v_inf[0] > v_inf[1]); // n = 2 is fastest at equal f_max (section 7)
//! # Ok::<(), stickslip::Error>(())
//! ```
//!
//! [`load`] reads a sweep file, [`Sweep::cases`] lists its cases,
//! [`run_cases`] runs any of them in parallel and returns the results in the
//! order given (deterministic, whatever the thread count), and
//! [`execute`] is what `stickslip sweep` does: shard, skip, run, write.

use crate::Scene;
use crate::error::{Error, ParamError, SweepError};
use crate::scene::Indicator;
use crate::signal::{MAX_HARMONICS, SignalSpec};
use crate::simulation::{self, RunReport};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The largest number of cases a sweep may have.
pub const MAX_CASES: usize = 10_000_000;

/// A sweep axis: a scene parameter that takes a list of values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Axis {
    /// `f_max` level `L = n sqrt(kappa)` (37), so `sqrt(kappa) = L / n`.
    Level,
    /// `sqrt(kappa)`.
    SqrtKappa,
    /// `kappa = a_R / a_0`.
    Kappa,
    /// Number of harmonics `n`.
    Harmonics,
    /// Lanczos sigma factors (15) on or off.
    Sigma,
    /// `x_Rmax` (m).
    Stroke,
    /// `t_1 / T` of the ideal signal.
    Duty,
    /// `mu_0`.
    MuStatic,
    /// `mu_d`.
    MuDynamic,
    /// `F_c` (N).
    ContactForce,
    /// `m_s` (kg).
    SliderMass,
    /// `g_t` (m/s^2).
    ExtraAcceleration,
}

impl Axis {
    /// Every axis, in case order (the first varies slowest).
    pub const ALL: [Axis; 12] = [
        Axis::Level,
        Axis::SqrtKappa,
        Axis::Kappa,
        Axis::Harmonics,
        Axis::Sigma,
        Axis::Stroke,
        Axis::Duty,
        Axis::MuStatic,
        Axis::MuDynamic,
        Axis::ContactForce,
        Axis::SliderMass,
        Axis::ExtraAcceleration,
    ];

    /// The name in sweep files and output columns.
    pub fn name(self) -> &'static str {
        match self {
            Axis::Level => "level",
            Axis::SqrtKappa => "sqrt_kappa",
            Axis::Kappa => "kappa",
            Axis::Harmonics => "harmonics",
            Axis::Sigma => "sigma",
            Axis::Stroke => "stroke",
            Axis::Duty => "duty",
            Axis::MuStatic => "mu_static",
            Axis::MuDynamic => "mu_dynamic",
            Axis::ContactForce => "contact_force",
            Axis::SliderMass => "slider_mass",
            Axis::ExtraAcceleration => "extra_acceleration",
        }
    }

    /// Checks one value on its own (`field` is `axes.<name>[i]`).
    fn check(self, field: &str, value: AxisValue) -> Result<(), ParamError> {
        match (self, value) {
            (Axis::Harmonics, AxisValue::Integer(n)) => {
                if usize::try_from(n).is_ok_and(|n| (1..=MAX_HARMONICS).contains(&n)) {
                    Ok(())
                } else {
                    Err(ParamError::out_of_range(
                        field,
                        n as f64,
                        format!("must be an integer from 1 to {MAX_HARMONICS}"),
                    ))
                }
            }
            (Axis::Sigma, AxisValue::Bool(_)) => Ok(()),
            (Axis::MuStatic | Axis::MuDynamic, AxisValue::Number(x)) => {
                ParamError::non_negative(field, x).map(drop)
            }
            (Axis::ExtraAcceleration, AxisValue::Number(x)) => {
                ParamError::finite(field, x).map(drop)
            }
            (Axis::Duty, AxisValue::Number(x)) => {
                ParamError::positive(field, x)?;
                if x > 1.0 {
                    Err(ParamError::out_of_range(
                        field,
                        x,
                        "must lie in (0, 1] (t_1 / T)",
                    ))
                } else {
                    Ok(())
                }
            }
            (Axis::SqrtKappa, AxisValue::Number(x)) => {
                ParamError::positive(field, x)?;
                if (x * x).is_finite() && x * x > 0.0 {
                    Ok(())
                } else {
                    Err(ParamError::out_of_range(
                        field,
                        x,
                        "its square kappa must be positive and finite",
                    ))
                }
            }
            (_, AxisValue::Number(x)) => ParamError::positive(field, x).map(drop),
            (_, other) => Err(ParamError::Inconsistent {
                field: field.to_owned(),
                reason: format!("{other} has the wrong type"),
            }),
        }
    }

    /// Why this axis cannot vary the base signal, or `None` if it can.
    fn unfit_for(self, signal: &SignalSpec) -> Option<String> {
        let kind = match signal {
            SignalSpec::Fourier { .. } => return None,
            SignalSpec::Ideal(_) => "ideal",
            SignalSpec::Harmonics {
                scale_to_stroke, ..
            } => {
                if self == Axis::Stroke && scale_to_stroke.is_none() {
                    return Some(
                        "the base signal (kind = \"harmonics\") has scale_to_stroke = false"
                            .to_owned(),
                    );
                }
                "harmonics"
            }
        };
        let needs_fourier = matches!(self, Axis::Level | Axis::Harmonics | Axis::Sigma);
        let needs_shape = matches!(self, Axis::SqrtKappa | Axis::Kappa | Axis::Duty);
        (needs_fourier || (needs_shape && kind == "harmonics")).then(|| {
            format!(
                "needs a base signal with kind = \"{}\", the base has kind = \"{kind}\"",
                if needs_fourier {
                    "fourier"
                } else {
                    "fourier\" or \"ideal"
                }
            )
        })
    }

    /// Sets this axis's parameter; `level` is applied by [`set_level`].
    fn apply(self, scene: &mut Scene, value: AxisValue) {
        let motor = &mut scene.motor;
        let number = value.as_f64().unwrap_or(f64::NAN);
        match (self, &mut scene.signal) {
            (Axis::MuStatic, _) => motor.mu_static = number,
            (Axis::MuDynamic, _) => motor.mu_dynamic = number,
            (Axis::ContactForce, _) => motor.contact_force = number,
            (Axis::SliderMass, _) => motor.slider_mass = number,
            (Axis::ExtraAcceleration, _) => motor.extra_acceleration = number,
            (
                Axis::Stroke,
                SignalSpec::Harmonics {
                    scale_to_stroke, ..
                },
            ) => *scale_to_stroke = Some(number),
            (Axis::Harmonics, SignalSpec::Fourier { harmonics, .. }) => {
                if let AxisValue::Integer(n) = value {
                    *harmonics = usize::try_from(n).unwrap_or(0);
                }
            }
            (Axis::Sigma, SignalSpec::Fourier { sigma, .. }) => {
                if let AxisValue::Bool(b) = value {
                    *sigma = b;
                }
            }
            (axis, SignalSpec::Fourier { shape, .. } | SignalSpec::Ideal(shape)) => match axis {
                Axis::SqrtKappa => shape.kappa = number * number,
                Axis::Kappa => shape.kappa = number,
                Axis::Stroke => shape.stroke = number,
                Axis::Duty => shape.duty = number,
                _ => {}
            },
            _ => {}
        }
    }
}

/// `sqrt(kappa) = level / n` (37).
fn set_level(scene: &mut Scene, level: f64) {
    if let SignalSpec::Fourier {
        shape, harmonics, ..
    } = &mut scene.signal
    {
        let sqrt_kappa = level / *harmonics as f64;
        shape.kappa = sqrt_kappa * sqrt_kappa;
    }
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Axis {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| format!("unknown sweep axis \"{s}\""))
    }
}

/// One value of an axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AxisValue {
    /// A real number (SI units).
    Number(f64),
    /// An integer (`harmonics`).
    Integer(i64),
    /// A switch (`sigma`).
    Bool(bool),
}

impl AxisValue {
    /// The value as a number (`Integer` converted), `None` for a switch.
    pub fn as_f64(self) -> Option<f64> {
        match self {
            AxisValue::Number(x) => Some(x),
            AxisValue::Integer(n) => Some(n as f64),
            AxisValue::Bool(_) => None,
        }
    }

    /// The value as a switch, `None` for numbers.
    pub fn as_bool(self) -> Option<bool> {
        match self {
            AxisValue::Bool(b) => Some(b),
            _ => None,
        }
    }

    /// Identical values (bitwise for numbers, so `-0` differs from `0`).
    fn same(self, other: AxisValue) -> bool {
        match (self, other) {
            (AxisValue::Number(a), AxisValue::Number(b)) => a.to_bits() == b.to_bits(),
            _ => self == other,
        }
    }

    fn cell(self) -> Cell {
        match self {
            AxisValue::Number(x) => Cell::Number(x),
            AxisValue::Integer(n) => Cell::Integer(n),
            AxisValue::Bool(b) => Cell::Bool(b),
        }
    }
}

impl fmt::Display for AxisValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AxisValue::Number(x) => write!(f, "{x}"),
            AxisValue::Integer(n) => write!(f, "{n}"),
            AxisValue::Bool(b) => write!(f, "{b}"),
        }
    }
}

/// Output format of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// Comma-separated values with a header line.
    #[default]
    Csv,
    /// One JSON object per line, keys in column order.
    Jsonl,
}

impl Format {
    /// The format a file name asks for: `.csv` or `.jsonl`, else `None`.
    pub fn from_path(path: &Path) -> Option<Format> {
        match path.extension()?.to_str()? {
            "csv" => Some(Format::Csv),
            "jsonl" => Some(Format::Jsonl),
            _ => None,
        }
    }

    /// The usual file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Jsonl => "jsonl",
        }
    }
}

/// The sweep file as written.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// Base scene, relative to the sweep file; `None`: [`Scene::default`].
    #[serde(default)]
    pub base: Option<PathBuf>,
    /// `[axes]`.
    #[serde(default)]
    pub axes: AxesTable,
    /// `[outputs]`.
    #[serde(default)]
    pub outputs: Option<SweepOutputsTable>,
}

/// The `[axes]` table: each field a list of values (see the module docs).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct AxesTable {
    pub level: Option<Vec<f64>>,
    pub sqrt_kappa: Option<Vec<f64>>,
    pub kappa: Option<Vec<f64>>,
    pub harmonics: Option<Vec<i64>>,
    pub sigma: Option<Vec<bool>>,
    pub stroke: Option<Vec<f64>>,
    pub duty: Option<Vec<f64>>,
    pub mu_static: Option<Vec<f64>>,
    pub mu_dynamic: Option<Vec<f64>>,
    pub contact_force: Option<Vec<f64>>,
    pub slider_mass: Option<Vec<f64>>,
    pub extra_acceleration: Option<Vec<f64>>,
}

impl AxesTable {
    /// The given axes in case order.
    fn axes(&self) -> Vec<(Axis, Vec<AxisValue>)> {
        let numbers = |v: &Option<Vec<f64>>| {
            v.as_ref()
                .map(|v| v.iter().map(|x| AxisValue::Number(*x)).collect::<Vec<_>>())
        };
        Axis::ALL
            .into_iter()
            .filter_map(|axis| {
                let values = match axis {
                    Axis::Level => numbers(&self.level),
                    Axis::SqrtKappa => numbers(&self.sqrt_kappa),
                    Axis::Kappa => numbers(&self.kappa),
                    Axis::Harmonics => self
                        .harmonics
                        .as_ref()
                        .map(|v| v.iter().map(|n| AxisValue::Integer(*n)).collect()),
                    Axis::Sigma => self
                        .sigma
                        .as_ref()
                        .map(|v| v.iter().map(|b| AxisValue::Bool(*b)).collect()),
                    Axis::Stroke => numbers(&self.stroke),
                    Axis::Duty => numbers(&self.duty),
                    Axis::MuStatic => numbers(&self.mu_static),
                    Axis::MuDynamic => numbers(&self.mu_dynamic),
                    Axis::ContactForce => numbers(&self.contact_force),
                    Axis::SliderMass => numbers(&self.slider_mass),
                    Axis::ExtraAcceleration => numbers(&self.extra_acceleration),
                };
                values.map(|v| (axis, v))
            })
            .collect()
    }
}

/// The `[outputs]` table of a sweep file.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepOutputsTable {
    /// Indicator names; `None`: the base scene's.
    #[serde(default)]
    pub indicators: Option<Vec<String>>,
    /// `csv` (default) or `jsonl`.
    #[serde(default)]
    pub format: Option<Format>,
}

/// One case of a sweep: its index, its axis values and the scene it runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Position in the grid, `0..N` (see the module docs).
    pub index: usize,
    /// The value of every axis, in axis order.
    pub values: Vec<(Axis, AxisValue)>,
    /// The validated scene.
    pub scene: Scene,
}

impl Case {
    /// The value of `axis`, if the sweep varies it.
    pub fn value(&self, axis: Axis) -> Option<AxisValue> {
        self.values
            .iter()
            .find_map(|(a, v)| (*a == axis).then_some(*v))
    }

    /// `name = value, ...` of every axis.
    pub fn describe(&self) -> String {
        self.values
            .iter()
            .map(|(a, v)| format!("{a} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// A loaded, validated sweep.
#[derive(Debug, Clone)]
pub struct Sweep {
    origin: String,
    base: Scene,
    axes: Vec<(Axis, Vec<AxisValue>)>,
    format: Format,
    cases: Vec<Case>,
}

/// Reads, parses and validates a sweep file.
pub fn load(path: impl AsRef<Path>) -> Result<Sweep, SweepError> {
    let path = path.as_ref();
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| SweepError::Io {
        path: origin.clone(),
        source,
    })?;
    let dir = path.parent().unwrap_or(Path::new("."));
    Sweep::from_toml_str(&text, &origin, dir)
}

impl Sweep {
    /// Parses and validates a sweep from TOML text; `origin` names it in
    /// errors and `dir` is where a relative `base` path starts.
    pub fn from_toml_str(text: &str, origin: &str, dir: &Path) -> Result<Sweep, SweepError> {
        let file: SweepFile = toml::from_str(text).map_err(|e| SweepError::Parse {
            path: origin.to_owned(),
            message: one_line(text, &e),
        })?;
        Self::from_file(file, origin, dir)
    }

    /// Validates a parsed sweep file.
    pub fn from_file(file: SweepFile, origin: &str, dir: &Path) -> Result<Sweep, SweepError> {
        let param = |source: ParamError| SweepError::Param {
            path: origin.to_owned(),
            source,
        };
        let mut base = match &file.base {
            Some(p) => Scene::from_path(&dir.join(p)).map_err(|source| SweepError::Base {
                path: origin.to_owned(),
                source: Box::new(source),
            })?,
            None => Scene::default(),
        };
        base.outputs.trajectory = false;
        base.outputs.events = false;
        let outputs = file.outputs.unwrap_or_default();
        if let Some(names) = outputs.indicators {
            let mut wanted = Vec::new();
            for name in &names {
                let indicator = name
                    .parse::<Indicator>()
                    .map_err(|e| ParamError::Inconsistent {
                        field: "outputs.indicators".to_owned(),
                        reason: e.to_string(),
                    })
                    .map_err(param)?;
                wanted.push(indicator);
            }
            base.outputs.indicators = wanted;
            base.validate().map_err(param)?;
        }
        let axes = file.axes.axes();
        let shape_axes: Vec<_> = axes
            .iter()
            .map(|(a, _)| *a)
            .filter(|a| matches!(a, Axis::Level | Axis::SqrtKappa | Axis::Kappa))
            .collect();
        if shape_axes.len() > 1 {
            return Err(param(ParamError::Inconsistent {
                field: format!("axes.{}", shape_axes[1]),
                reason: format!(
                    "give at most one of axes.level, axes.sqrt_kappa and axes.kappa (also given: axes.{})",
                    shape_axes[0]
                ),
            }));
        }
        let mut count: usize = 1;
        for (axis, values) in &axes {
            let field = format!("axes.{axis}");
            if values.is_empty() {
                return Err(param(ParamError::Inconsistent {
                    field,
                    reason: "is empty: give at least one value".to_owned(),
                }));
            }
            if let Some(reason) = axis.unfit_for(&base.signal) {
                return Err(param(ParamError::Inconsistent { field, reason }));
            }
            for (i, value) in values.iter().enumerate() {
                let field = format!("{field}[{i}]");
                axis.check(&field, *value).map_err(param)?;
                if let Some(j) = values[..i].iter().position(|v| v.same(*value)) {
                    let reason = format!("repeats axes.{axis}[{j}]");
                    return Err(param(match value.as_f64() {
                        Some(x) => ParamError::out_of_range(&field, x, reason),
                        None => ParamError::Inconsistent {
                            field,
                            reason: format!("{value} {reason}"),
                        },
                    }));
                }
            }
            count = count
                .checked_mul(values.len())
                .filter(|c| *c <= MAX_CASES)
                .ok_or_else(|| SweepError::TooLarge {
                    path: origin.to_owned(),
                    max: MAX_CASES,
                })?;
        }
        let mut cases = Vec::with_capacity(count);
        for index in 0..count {
            let case = make_case(&base, &axes, index);
            case.scene.validate().map_err(|source| SweepError::Case {
                path: origin.to_owned(),
                case: index,
                values: case.describe(),
                source: Box::new(source),
            })?;
            cases.push(case);
        }
        Ok(Sweep {
            origin: origin.to_owned(),
            base,
            axes,
            format: outputs.format.unwrap_or_default(),
            cases,
        })
    }

    /// Every case, in index order.
    pub fn cases(&self) -> Vec<Case> {
        self.cases.clone()
    }

    /// Number of cases.
    pub fn len(&self) -> usize {
        self.cases.len()
    }

    /// True for a sweep without cases (never: a sweep without axes has one).
    pub fn is_empty(&self) -> bool {
        self.cases.is_empty()
    }

    /// The base scene, with the sweep's indicators.
    pub fn base(&self) -> &Scene {
        &self.base
    }

    /// The axes and their values, in case order.
    pub fn axes(&self) -> &[(Axis, Vec<AxisValue>)] {
        &self.axes
    }

    /// The output format the sweep file asks for.
    pub fn format(&self) -> Format {
        self.format
    }

    /// Where the sweep came from (its path, or `<string>`).
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// The output columns (see the module docs).
    pub fn columns(&self, timing: bool) -> Vec<String> {
        self.column_kinds(timing)
            .iter()
            .map(|c| c.name().to_owned())
            .collect()
    }

    fn column_kinds(&self, timing: bool) -> Vec<Column> {
        let mut columns = vec![Column::Case];
        columns.extend(self.axes.iter().map(|(a, _)| Column::Axis(*a)));
        for indicator in Indicator::ALL {
            if self.base.outputs.indicators.contains(&indicator) {
                columns.push(Column::Indicator(indicator));
                match indicator {
                    Indicator::StictionFraction => columns.push(Column::StictionSteady),
                    Indicator::VelocityPerPower => columns.push(Column::ApparentPower),
                    _ => {}
                }
            }
        }
        columns.extend([
            Column::Period,
            Column::StartupPeriods,
            Column::PeriodsSimulated,
            Column::EventsTotal,
        ]);
        if timing {
            columns.push(Column::WallTime);
        }
        columns.extend([Column::ErrorVInf, Column::Failure]);
        columns
    }

    /// The default output file: `<sweep file stem>.<ext>`, or
    /// `<stem>.<i>-of-<N>.<ext>` for a shard, in the current directory.
    pub fn default_output(&self, shard: Option<Shard>) -> PathBuf {
        let stem = Path::new(&self.origin)
            .file_stem()
            .map_or("sweep".to_owned(), |s| s.to_string_lossy().into_owned());
        let ext = self.format.extension();
        PathBuf::from(match shard {
            Some(s) => format!("{stem}.{}-of-{}.{ext}", s.index, s.count),
            None => format!("{stem}.{ext}"),
        })
    }
}

fn make_case(base: &Scene, axes: &[(Axis, Vec<AxisValue>)], index: usize) -> Case {
    let mut rest = index;
    let mut values = vec![(Axis::Level, AxisValue::Bool(false)); axes.len()];
    for (slot, (axis, list)) in values.iter_mut().zip(axes).rev() {
        *slot = (*axis, list[rest % list.len()]);
        rest /= list.len();
    }
    let mut scene = base.clone();
    for (axis, value) in &values {
        axis.apply(&mut scene, *value);
    }
    // After `harmonics`, which `level` divides by.
    for (axis, value) in &values {
        if let (Axis::Level, Some(level)) = (axis, value.as_f64()) {
            set_level(&mut scene, level);
        }
    }
    Case {
        index,
        values,
        scene,
    }
}

/// A TOML error on one line: the message, then line, column and the
/// offending line's text.
fn one_line(text: &str, error: &toml::de::Error) -> String {
    let message = error
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let Some(span) = error.span() else {
        return message;
    };
    let before = text.get(..span.start).unwrap_or("");
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    let source = text.lines().nth(line - 1).unwrap_or("").trim();
    format!("{message} (line {line}, column {column}: {source})")
}

/// How the columns `found` differ from `wanted`.
fn column_difference(found: &[String], wanted: &[String]) -> String {
    let extra: Vec<&str> = found
        .iter()
        .filter(|c| !wanted.contains(c))
        .map(String::as_str)
        .collect();
    let missing: Vec<&str> = wanted
        .iter()
        .filter(|c| !found.contains(c))
        .map(String::as_str)
        .collect();
    match (extra.is_empty(), missing.is_empty()) {
        (true, true) => "the same columns in another order".to_owned(),
        (false, true) => format!("the extra columns {}", extra.join(", ")),
        (true, false) => format!("no columns {}", missing.join(", ")),
        (false, false) => format!(
            "the extra columns {} and no columns {}",
            extra.join(", "),
            missing.join(", ")
        ),
    }
}

/// The result of one case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The case's index.
    pub index: usize,
    /// The case's axis values.
    pub values: Vec<(Axis, AxisValue)>,
    /// The run.
    pub report: RunReport,
}

/// Runs `cases` in parallel (rayon's global pool) and returns their
/// results in the order of `cases`, whatever order they finish in. With
/// `progress`, a progress bar is drawn on stderr if it is a terminal.
pub fn run_cases(cases: &[Case], progress: bool) -> Vec<Result<CaseResult, Error>> {
    let mut results: Vec<Option<Result<CaseResult, Error>>> = Vec::new();
    results.resize_with(cases.len(), || None);
    run_streaming(cases, progress, |position, result| {
        results[position] = Some(result);
    });
    results
        .into_iter()
        .map(|r| r.expect("every case reports once"))
        .collect()
}

/// Runs one case.
pub fn run_case(case: &Case) -> Result<CaseResult, Error> {
    simulation::run(&case.scene).map(|report| CaseResult {
        index: case.index,
        values: case.values.clone(),
        report,
    })
}

/// Runs `cases` in parallel and hands every result, with its position in
/// `cases`, to `sink` on the calling thread as soon as it is done.
fn run_streaming(
    cases: &[Case],
    progress: bool,
    mut sink: impl FnMut(usize, Result<CaseResult, Error>),
) {
    let bar = progress_bar(cases.len(), progress);
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::channel();
        scope.spawn(move || {
            cases
                .par_iter()
                .enumerate()
                .for_each_with(sender, |sender, (position, case)| {
                    // The receiver lives until every sender is gone.
                    let _ = sender.send((position, run_case(case)));
                });
        });
        for (position, result) in receiver {
            bar.inc(1);
            sink(position, result);
        }
    });
    bar.finish_and_clear();
}

fn progress_bar(len: usize, progress: bool) -> ProgressBar {
    if !progress || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:40} {pos}/{len} cases, {elapsed} elapsed, about {eta} left",
    ) {
        bar.set_style(style);
    }
    bar
}

/// One cell of an output row.
#[derive(Debug, Clone, PartialEq)]
enum Cell {
    Empty,
    Number(f64),
    Integer(i64),
    Unsigned(u64),
    Bool(bool),
    Text(String),
}

impl Cell {
    fn number(x: Option<f64>) -> Cell {
        match x {
            Some(x) if x.is_finite() => Cell::Number(x),
            _ => Cell::Empty,
        }
    }

    fn csv(&self) -> String {
        match self {
            Cell::Empty => String::new(),
            // Shortest round-tripping digits; exponent form where plain
            // decimals would run long.
            Cell::Number(x) if *x == 0.0 || (1e-4..1e16).contains(&x.abs()) => format!("{x}"),
            Cell::Number(x) => format!("{x:e}"),
            Cell::Integer(n) => n.to_string(),
            Cell::Unsigned(n) => n.to_string(),
            Cell::Bool(b) => b.to_string(),
            Cell::Text(s) => s.clone(),
        }
    }

    fn json(&self) -> serde_json::Value {
        match self {
            Cell::Empty => serde_json::Value::Null,
            Cell::Number(x) => serde_json::json!(x),
            Cell::Integer(n) => serde_json::json!(n),
            Cell::Unsigned(n) => serde_json::json!(n),
            Cell::Bool(b) => serde_json::json!(b),
            Cell::Text(s) => serde_json::json!(s),
        }
    }
}

/// An output column.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Column {
    Case,
    Axis(Axis),
    Indicator(Indicator),
    StictionSteady,
    ApparentPower,
    Period,
    StartupPeriods,
    PeriodsSimulated,
    EventsTotal,
    WallTime,
    ErrorVInf,
    Failure,
}

impl Column {
    fn name(self) -> &'static str {
        match self {
            Column::Case => "case",
            Column::Axis(a) => a.name(),
            Column::Indicator(i) => i.name(),
            Column::StictionSteady => "stiction_fraction_steady",
            Column::ApparentPower => "apparent_power",
            Column::Period => "period",
            Column::StartupPeriods => "startup_periods",
            Column::PeriodsSimulated => "periods_simulated",
            Column::EventsTotal => "events_total",
            Column::WallTime => "wall_time_s",
            Column::ErrorVInf => "error_v_inf",
            Column::Failure => "failure",
        }
    }

    fn cell(self, case: &Case, result: &Result<CaseResult, Error>) -> Cell {
        match self {
            Column::Case => return Cell::Unsigned(case.index as u64),
            Column::Axis(a) => return case.value(a).map_or(Cell::Empty, AxisValue::cell),
            Column::Failure => {
                return match result {
                    Ok(_) => Cell::Empty,
                    Err(e) => Cell::Text(e.to_string().replace(['\n', '\r'], " ")),
                };
            }
            _ => {}
        }
        let Ok(CaseResult { report: r, .. }) = result else {
            return Cell::Empty;
        };
        let ind = &r.indicators;
        match self {
            Column::Indicator(indicator) => Cell::number(match indicator {
                Indicator::VInf => Some(ind.v_inf),
                Indicator::StartupTime => r.startup_time(),
                Indicator::Smoothness => Some(ind.smoothness),
                Indicator::Durability => Some(ind.durability),
                Indicator::FrictionEnergy => Some(ind.friction_energy),
                Indicator::StictionFraction => r.stiction_fraction_transient,
                Indicator::VelocityPerPower => r.velocity_per_power(),
            }),
            Column::StictionSteady => Cell::number(Some(ind.stiction_fraction)),
            Column::ApparentPower => Cell::number(r.power.as_ref().map(|p| p.apparent_power)),
            Column::Period => Cell::number(Some(r.period)),
            Column::StartupPeriods => r.startup_periods.map_or(Cell::Empty, Cell::Unsigned),
            Column::PeriodsSimulated => {
                Cell::Unsigned(r.transient.as_ref().map_or(0, |t| t.periods()))
            }
            Column::EventsTotal => Cell::Unsigned(r.events().total()),
            Column::WallTime => Cell::number(Some(r.wall_time.as_secs_f64())),
            Column::ErrorVInf => Cell::number(r.error.v_inf),
            Column::Case | Column::Axis(_) | Column::Failure => unreachable!("handled above"),
        }
    }
}

/// A shard `i/N` of a sweep: the cases with `index % N == i - 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// `i`, 1-based: `1 <= index <= count`.
    pub index: usize,
    /// `N >= 1`.
    pub count: usize,
}

impl Shard {
    /// True if case `case` belongs to this shard.
    pub fn contains(self, case: usize) -> bool {
        case % self.count == self.index - 1
    }
}

impl FromStr for Shard {
    type Err = SweepError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = |reason: &str| SweepError::Shard {
            given: s.to_owned(),
            reason: reason.to_owned(),
        };
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| bad("expected i/N, e.g. 2/8"))?;
        let parse = |x: &str| x.trim().parse::<usize>().ok();
        match (parse(i), parse(n)) {
            (Some(index), Some(count)) if count >= 1 && (1..=count).contains(&index) => {
                Ok(Shard { index, count })
            }
            (Some(_), Some(_)) => Err(bad("needs 1 <= i <= N (i is 1-based)")),
            _ => Err(bad("expected two whole numbers i/N, e.g. 2/8")),
        }
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// How [`execute`] runs a sweep.
#[derive(Debug, Clone)]
pub struct Options {
    /// Output file; existing rows in it are kept and not rerun.
    pub output: PathBuf,
    /// Run only this shard; `None`: every case.
    pub shard: Option<Shard>,
    /// Output format; `None`: the one the output's extension names
    /// ([`Format::from_path`]), else the sweep file's.
    pub format: Option<Format>,
    /// Write the `wall_time_s` column (the only one that differs between
    /// runs of the same sweep).
    pub timing: bool,
    /// Draw a progress bar on stderr (only if it is a terminal).
    pub progress: bool,
    /// Least time between checkpoint writes of the output while running.
    pub checkpoint: Duration,
}

impl Options {
    /// Timing on, progress on, the format from the file name or the sweep,
    /// a checkpoint at most every 10 s.
    pub fn new(output: impl Into<PathBuf>) -> Self {
        Self {
            output: output.into(),
            shard: None,
            format: None,
            timing: true,
            progress: true,
            checkpoint: Duration::from_secs(10),
        }
    }
}

/// What [`execute`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Summary {
    /// Cases of the shard (all cases without one).
    pub cases: usize,
    /// Of those, found in the existing output and skipped.
    pub skipped: usize,
    /// Of those, run now.
    pub ran: usize,
    /// Of those run now, failed (written with a `failure`).
    pub failed: usize,
    /// Rows in the output file.
    pub rows: usize,
}

/// An output table: the columns and the rendered rows by case.
struct Table {
    format: Format,
    columns: Vec<String>,
    rows: BTreeMap<usize, String>,
}

impl Table {
    fn render_row(&self, cells: &[Cell]) -> String {
        match self.format {
            Format::Csv => csv_line(&cells.iter().map(Cell::csv).collect::<Vec<_>>()),
            Format::Jsonl => {
                let fields: Vec<String> = self
                    .columns
                    .iter()
                    .zip(cells)
                    .map(|(name, cell)| format!("{}:{}", serde_json::json!(name), cell.json()))
                    .collect();
                format!("{{{}}}", fields.join(","))
            }
        }
    }

    fn text(&self) -> String {
        let mut out = String::new();
        if self.format == Format::Csv {
            out.push_str(&csv_line(&self.columns));
            out.push('\n');
        }
        for line in self.rows.values() {
            out.push_str(line);
            out.push('\n');
        }
        out
    }

    /// Writes the table to `path` atomically.
    fn write(&self, path: &Path) -> Result<(), SweepError> {
        write_atomically(path, &self.text())
    }
}

/// One CSV record, without the line end.
fn csv_line<S: AsRef<[u8]>>(fields: &[S]) -> String {
    let mut writer = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    // Writing to memory cannot fail.
    let _ = writer.write_record(fields);
    let bytes = writer.into_inner().unwrap_or_default();
    let mut line = String::from_utf8_lossy(&bytes).into_owned();
    if line.ends_with('\n') {
        line.pop();
    }
    line
}

/// Writes `text` to `path` atomically ([`crate::output::write_atomically`]):
/// readers see the old file or the new one, never a part.
fn write_atomically(path: &Path, text: &str) -> Result<(), SweepError> {
    crate::output::write_atomically(path, text.as_bytes()).map_err(|source| SweepError::Write {
        path: path.display().to_string(),
        source,
    })
}

/// The rows of an output file: the format and columns (`None` for a file
/// without a complete line), and every row with its case and line. The
/// columns of JSON lines are sorted by name: serde_json's objects do not
/// keep the key order.
struct ParsedOutput {
    layout: Option<(Format, Vec<String>)>,
    rows: Vec<(usize, String, ParsedRow)>,
}

/// The cells of one parsed row, as text (CSV) or JSON values.
enum ParsedRow {
    Csv(Vec<String>),
    Json(serde_json::Map<String, serde_json::Value>),
}

fn parse_output(path: &Path, text: &str) -> Result<ParsedOutput, SweepError> {
    let bad = |reason: String| SweepError::Output {
        path: path.display().to_string(),
        reason,
    };
    // Only complete lines: a last line without its end is dropped.
    let complete = &text[..text.rfind('\n').map_or(0, |i| i + 1)];
    if complete.trim().is_empty() {
        return Ok(ParsedOutput {
            layout: None,
            rows: Vec::new(),
        });
    }
    if !complete.trim_start().starts_with('{') {
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(complete.as_bytes());
        let mut records = reader.records();
        let header = records
            .next()
            .unwrap_or_else(|| Ok(csv::StringRecord::new()))
            .map_err(|e| bad(format!("unreadable CSV header: {e}")))?;
        let columns: Vec<String> = header.iter().map(str::to_owned).collect();
        if columns.first().map(String::as_str) != Some("case") {
            return Err(bad(
                "not a sweep output: the first column is not \"case\"".into()
            ));
        }
        let mut rows = Vec::new();
        for record in records {
            let record = record.map_err(|e| bad(format!("unreadable CSV row: {e}")))?;
            let fields: Vec<String> = record.iter().map(str::to_owned).collect();
            let line = record.position().map_or(0, |p| p.line());
            let case = fields[0].parse::<usize>().map_err(|_| {
                bad(format!(
                    "line {line}: case \"{}\" is not an index",
                    fields[0]
                ))
            })?;
            rows.push((case, csv_line(&fields), ParsedRow::Csv(fields)));
        }
        return Ok(ParsedOutput {
            layout: Some((Format::Csv, columns)),
            rows,
        });
    }
    let mut columns: Option<Vec<String>> = None;
    let mut rows = Vec::new();
    for (number, line) in complete.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let value: serde_json::Value = serde_json::from_str(line)
            .map_err(|e| bad(format!("line {}: not JSON: {e}", number + 1)))?;
        let serde_json::Value::Object(map) = value else {
            return Err(bad(format!("line {}: not a JSON object", number + 1)));
        };
        let keys = sorted(&map.keys().cloned().collect::<Vec<_>>());
        match &columns {
            None => columns = Some(keys),
            Some(c) if *c != keys => {
                return Err(bad(format!(
                    "line {}: its keys differ from those of the first row",
                    number + 1
                )));
            }
            Some(_) => {}
        }
        let case = map
            .get("case")
            .and_then(serde_json::Value::as_u64)
            .and_then(|c| usize::try_from(c).ok())
            .ok_or_else(|| bad(format!("line {}: no case index", number + 1)))?;
        rows.push((case, line.trim().to_owned(), ParsedRow::Json(map)));
    }
    Ok(ParsedOutput {
        layout: columns.map(|c| (Format::Jsonl, c)),
        rows,
    })
}

/// The columns sorted by name.
fn sorted(columns: &[String]) -> Vec<String> {
    let set: BTreeSet<&String> = columns.iter().collect();
    set.into_iter().cloned().collect()
}

/// Runs a sweep (or one shard of it) into `options.output`: existing rows
/// of the output are kept and their cases skipped; the missing cases run in
/// parallel; the file is rewritten atomically at checkpoints and at the end
/// with every row sorted by case.
pub fn execute(sweep: &Sweep, options: &Options) -> Result<Summary, SweepError> {
    let kinds = sweep.column_kinds(options.timing);
    let mut table = Table {
        format: options
            .format
            .or_else(|| Format::from_path(&options.output))
            .unwrap_or(sweep.format),
        columns: kinds.iter().map(|c| c.name().to_owned()).collect(),
        rows: BTreeMap::new(),
    };
    let path = &options.output;
    let bad = |reason: String| SweepError::Output {
        path: path.display().to_string(),
        reason,
    };
    match std::fs::read_to_string(path) {
        Ok(text) => {
            let existing = parse_output(path, &text)?;
            if let Some((format, columns)) = &existing.layout {
                if *format != table.format {
                    return Err(bad(format!(
                        "holds {} rows, the sweep writes {}; choose another --output",
                        format.extension(),
                        table.format.extension()
                    )));
                }
                let expected = match table.format {
                    Format::Csv => table.columns.clone(),
                    Format::Jsonl => sorted(&table.columns),
                };
                if *columns != expected {
                    return Err(bad(format!(
                        "has {} compared with what this sweep writes; delete it or choose another --output",
                        column_difference(columns, &expected)
                    )));
                }
            }
            for (case, line, row) in existing.rows {
                check_existing_row(sweep, &kinds, case, &row).map_err(bad)?;
                if let Some(previous) = table.rows.insert(case, line.clone())
                    && previous != line
                {
                    return Err(bad(format!("holds two different rows for case {case}")));
                }
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(source) => {
            return Err(SweepError::Io {
                path: path.display().to_string(),
                source,
            });
        }
    }
    let mine: Vec<&Case> = sweep
        .cases
        .iter()
        .filter(|c| options.shard.is_none_or(|s| s.contains(c.index)))
        .collect();
    let todo: Vec<Case> = mine
        .iter()
        .filter(|c| !table.rows.contains_key(&c.index))
        .map(|c| (*c).clone())
        .collect();
    let mut summary = Summary {
        cases: mine.len(),
        skipped: mine.len() - todo.len(),
        ran: todo.len(),
        ..Summary::default()
    };
    let mut next_checkpoint = Instant::now() + options.checkpoint;
    let mut write_error = None;
    run_streaming(&todo, options.progress, |position, result| {
        let case = &todo[position];
        if result.is_err() {
            summary.failed += 1;
        }
        let cells: Vec<Cell> = kinds.iter().map(|c| c.cell(case, &result)).collect();
        let line = table.render_row(&cells);
        table.rows.insert(case.index, line);
        if write_error.is_none() && Instant::now() >= next_checkpoint {
            let clock = Instant::now();
            write_error = table.write(path).err();
            // Rewriting a large file costs; keep it a small share of the run.
            next_checkpoint = Instant::now() + options.checkpoint.max(clock.elapsed() * 20);
        }
    });
    if let Some(e) = write_error {
        return Err(e);
    }
    table.write(path)?;
    summary.rows = table.rows.len();
    Ok(summary)
}

/// A kept row must belong to this sweep: a valid case whose axis values
/// are the case's.
fn check_existing_row(
    sweep: &Sweep,
    kinds: &[Column],
    case: usize,
    row: &ParsedRow,
) -> Result<(), String> {
    let Some(c) = sweep.cases.get(case) else {
        return Err(format!(
            "has a row for case {case}, but the sweep has {} cases",
            sweep.len()
        ));
    };
    for (position, kind) in kinds.iter().enumerate() {
        let Column::Axis(axis) = kind else { continue };
        let expected = c.value(*axis).map_or(Cell::Empty, AxisValue::cell);
        let same = match row {
            ParsedRow::Csv(fields) => fields.get(position) == Some(&expected.csv()),
            ParsedRow::Json(map) => map.get(axis.name()) == Some(&expected.json()),
        };
        if !same {
            return Err(format!(
                "row of case {case} has another {axis} than the sweep's ({}): \
                 it was written by a different sweep; delete it or choose another --output",
                expected.csv()
            ));
        }
    }
    Ok(())
}

/// What [`merge`] did.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct MergeSummary {
    /// Rows written.
    pub rows: usize,
    /// Case indices below the largest one that no input has.
    pub missing: Vec<usize>,
}

/// Joins sweep outputs (shards) into `output`: all inputs must have the
/// same format and columns; rows are sorted by case; a case in several
/// inputs must have identical rows. Written atomically.
pub fn merge(output: &Path, inputs: &[PathBuf]) -> Result<MergeSummary, SweepError> {
    let mut table: Option<Table> = None;
    let mut first = PathBuf::new();
    let mut sources: BTreeMap<usize, PathBuf> = BTreeMap::new();
    for input in inputs {
        let text = std::fs::read_to_string(input).map_err(|source| SweepError::Io {
            path: input.display().to_string(),
            source,
        })?;
        let parsed = parse_output(input, &text)?;
        let bad = |reason: String| SweepError::Output {
            path: input.display().to_string(),
            reason,
        };
        // An empty file (a shard without cases, as JSON lines) adds nothing.
        let Some((format, columns)) = parsed.layout else {
            continue;
        };
        let table = table.get_or_insert_with(|| {
            first = input.clone();
            Table {
                format,
                columns: columns.clone(),
                rows: BTreeMap::new(),
            }
        });
        if format != table.format {
            return Err(bad(format!(
                "holds {} rows, {} holds {}",
                format.extension(),
                first.display(),
                table.format.extension()
            )));
        }
        if columns != table.columns {
            return Err(bad(format!(
                "has {} compared with {}",
                column_difference(&columns, &table.columns),
                first.display()
            )));
        }
        for (case, line, _) in parsed.rows {
            match table.rows.get(&case) {
                Some(existing) if *existing != line => {
                    return Err(bad(format!(
                        "its row of case {case} differs from the one in {}",
                        sources[&case].display()
                    )));
                }
                Some(_) => {}
                None => {
                    table.rows.insert(case, line);
                    sources.insert(case, input.clone());
                }
            }
        }
    }
    let Some(table) = table else {
        return Err(SweepError::Output {
            path: output.display().to_string(),
            reason: "nothing to merge: no input has a header or a row".into(),
        });
    };
    table.write(output)?;
    let last = table.rows.keys().next_back().copied();
    let missing = last.map_or_else(Vec::new, |last| {
        (0..last).filter(|c| !table.rows.contains_key(c)).collect()
    });
    Ok(MergeSummary {
        rows: table.rows.len(),
        missing,
    })
}
