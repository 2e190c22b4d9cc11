//! The grid of a sweep: the sweep file, its axes and values, and the cases,
//! each made from its index on demand ([`Sweep::case`]), so that a sweep
//! holds only its axes whatever the number of cases.

use super::axis::set_level;
pub use super::axis::{AxisKey, AxisValue, SweepAxis};
use crate::error::{ParamError, SweepError};
use crate::indicator::Indicator;
use crate::scene::Override;
use crate::scene::Scene;
use rayon::prelude::*;
use serde::Deserialize;
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// The largest number of cases a sweep may have. The grid is not stored
/// (cases are made from their index), but every case is validated when the
/// sweep is loaded, which takes about a second per million cases.
pub const MAX_CASES: usize = 10_000_000;

/// Output format of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepFormat {
    /// Comma-separated values with a header line.
    #[default]
    Csv,
    /// One JSON object per line, keys in column order.
    Jsonl,
}

impl SweepFormat {
    /// The format a file name asks for: `.csv` or `.jsonl`, else `None`.
    pub fn from_path(path: &Path) -> Option<SweepFormat> {
        match path.extension()?.to_str()? {
            "csv" => Some(SweepFormat::Csv),
            "jsonl" => Some(SweepFormat::Jsonl),
            _ => None,
        }
    }

    /// The usual file extension.
    pub fn extension(self) -> &'static str {
        match self {
            SweepFormat::Csv => "csv",
            SweepFormat::Jsonl => "jsonl",
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
    pub frequency: Option<Vec<f64>>,
    pub f_max: Option<Vec<f64>>,
    pub harmonics: Option<Vec<i64>>,
    pub sigma: Option<Vec<bool>>,
    pub stroke: Option<Vec<f64>>,
    pub duty: Option<Vec<f64>>,
    pub mu_static: Option<Vec<f64>>,
    pub mu_dynamic: Option<Vec<f64>>,
    pub contact_force: Option<Vec<f64>>,
    pub slider_mass: Option<Vec<f64>>,
    pub extra_acceleration: Option<Vec<f64>>,
    /// `spring.stiffness = [...]` and the other fields of the base scene's
    /// `[spring]` (TOML's dotted keys, or an `[axes.spring]` table).
    pub spring: Option<SpringAxesTable>,
}

/// The `[axes.spring]` table: the fields of the base scene's `[spring]`,
/// each a list of values.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SpringAxesTable {
    pub stiffness: Option<Vec<f64>>,
    pub damping: Option<Vec<f64>>,
    pub gap: Option<Vec<f64>>,
    pub preload: Option<Vec<f64>>,
}

impl AxesTable {
    /// The given axes in case order.
    fn axes(&self) -> Vec<(SweepAxis, Vec<AxisValue>)> {
        let numbers = |v: &Option<Vec<f64>>| {
            v.as_ref()
                .map(|v| v.iter().map(|x| AxisValue::Number(*x)).collect::<Vec<_>>())
        };
        let no_spring = SpringAxesTable::default();
        let spring = self.spring.as_ref().unwrap_or(&no_spring);
        SweepAxis::ALL
            .into_iter()
            .filter_map(|axis| {
                let values = match axis {
                    SweepAxis::Level => numbers(&self.level),
                    SweepAxis::SqrtKappa => numbers(&self.sqrt_kappa),
                    SweepAxis::Kappa => numbers(&self.kappa),
                    SweepAxis::Frequency => numbers(&self.frequency),
                    SweepAxis::FMax => numbers(&self.f_max),
                    SweepAxis::Harmonics => self
                        .harmonics
                        .as_ref()
                        .map(|v| v.iter().map(|n| AxisValue::Integer(*n)).collect()),
                    SweepAxis::Sigma => self
                        .sigma
                        .as_ref()
                        .map(|v| v.iter().map(|b| AxisValue::Bool(*b)).collect()),
                    SweepAxis::Stroke => numbers(&self.stroke),
                    SweepAxis::Duty => numbers(&self.duty),
                    SweepAxis::MuStatic => numbers(&self.mu_static),
                    SweepAxis::MuDynamic => numbers(&self.mu_dynamic),
                    SweepAxis::ContactForce => numbers(&self.contact_force),
                    SweepAxis::SliderMass => numbers(&self.slider_mass),
                    SweepAxis::ExtraAcceleration => numbers(&self.extra_acceleration),
                    SweepAxis::SpringStiffness => numbers(&spring.stiffness),
                    SweepAxis::SpringDamping => numbers(&spring.damping),
                    SweepAxis::SpringGap => numbers(&spring.gap),
                    SweepAxis::SpringPreload => numbers(&spring.preload),
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
    pub format: Option<SweepFormat>,
}

/// One case of a sweep: its index, its axis values and the scene it runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Position in the grid, `0..N` (see the module docs).
    pub index: usize,
    /// The value of every axis, in axis order.
    pub values: Vec<(SweepAxis, AxisValue)>,
    /// The validated scene.
    pub scene: Scene,
}

impl Case {
    /// The value of `axis`, if the sweep varies it.
    pub fn value(&self, axis: SweepAxis) -> Option<AxisValue> {
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
    base_path: Option<PathBuf>,
    axes: Vec<(SweepAxis, Vec<AxisValue>)>,
    format: SweepFormat,
    len: usize,
}

/// Reads, parses and validates a sweep file.
pub fn load(path: impl AsRef<Path>) -> Result<Sweep, SweepError> {
    load_with(path, &[])
}

/// [`load`] with `overrides` (`PATH=VALUE`) applied to the base scene
/// before the axes (`Scene::from_toml_str_with`).
pub fn load_with(path: impl AsRef<Path>, overrides: &[Override]) -> Result<Sweep, SweepError> {
    let path = path.as_ref();
    let origin = crate::scene::origin_of(path);
    let text = crate::scene::read_input(path).map_err(|source| SweepError::Io {
        path: origin.clone(),
        source,
    })?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let file: SweepFile = toml::from_str(&text).map_err(|e| SweepError::Parse {
        path: origin.clone(),
        message: crate::scene::parse_message(&text, &e),
    })?;
    Sweep::from_file_with(file, &origin, dir, overrides)
}

impl Sweep {
    /// Parses and validates a sweep from TOML text; `origin` names it in
    /// errors and `dir` is where a relative `base` path starts.
    pub fn from_toml_str(text: &str, origin: &str, dir: &Path) -> Result<Sweep, SweepError> {
        let file: SweepFile = toml::from_str(text).map_err(|e| SweepError::Parse {
            path: origin.to_owned(),
            message: crate::scene::parse_message(text, &e),
        })?;
        Self::from_file(file, origin, dir)
    }

    /// Validates a parsed sweep file.
    pub fn from_file(file: SweepFile, origin: &str, dir: &Path) -> Result<Sweep, SweepError> {
        Self::from_file_with(file, origin, dir, &[])
    }

    /// [`Sweep::from_file`] with `overrides` applied to the base scene.
    pub fn from_file_with(
        file: SweepFile,
        origin: &str,
        dir: &Path,
        overrides: &[Override],
    ) -> Result<Sweep, SweepError> {
        let param = |source: ParamError| SweepError::Param {
            path: origin.to_owned(),
            source,
        };
        let base_error = |source| SweepError::Base {
            path: origin.to_owned(),
            source: Box::new(source),
        };
        let mut base = match &file.base {
            Some(p) => Scene::from_path_with(&dir.join(p), overrides).map_err(base_error)?,
            None if overrides.is_empty() => Scene::default(),
            None => {
                Scene::from_toml_str_with(&Scene::default().to_toml(), "<default scene>", overrides)
                    .map_err(base_error)?
            }
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
            .filter(|a| {
                matches!(
                    a,
                    SweepAxis::Level
                        | SweepAxis::SqrtKappa
                        | SweepAxis::Kappa
                        | SweepAxis::Frequency
                        | SweepAxis::FMax
                )
            })
            .collect();
        if shape_axes.len() > 1 {
            return Err(param(ParamError::Inconsistent {
                field: format!("axes.{}", shape_axes[1]),
                reason: format!(
                    "give at most one of axes.level, axes.sqrt_kappa, axes.kappa, axes.frequency \
                     and axes.f_max: each fixes the drive (also given: axes.{})",
                    shape_axes[0]
                ),
            }));
        }
        let mut count: u128 = 1;
        for (axis, values) in &axes {
            let field = format!("axes.{axis}");
            if values.is_empty() {
                return Err(param(ParamError::Inconsistent {
                    field,
                    reason: "is empty: give at least one value".to_owned(),
                }));
            }
            if let Some(reason) = axis.unfit_for(&base) {
                return Err(param(ParamError::Inconsistent { field, reason }));
            }
            for (i, value) in values.iter().enumerate() {
                let field = format!("{field}[{i}]");
                axis.check(&field, *value).map_err(param)?;
                if let Some(j) = values[..i].iter().position(|v| v.key() == value.key()) {
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
            count = count.saturating_mul(values.len() as u128);
        }
        let len = usize::try_from(count)
            .ok()
            .filter(|c| *c <= MAX_CASES)
            .ok_or_else(|| SweepError::TooLarge {
                path: origin.to_owned(),
                cases: count,
                max: MAX_CASES,
            })?;
        // Every case, in parallel, without keeping them; the first bad one
        // by index is reported, whatever the thread count.
        let bad = (0..len).into_par_iter().find_map_first(|index| {
            let case = make_case(&base, &axes, index);
            case.scene.validate().err().map(|e| (case, e))
        });
        if let Some((case, source)) = bad {
            return Err(SweepError::Case {
                path: origin.to_owned(),
                case: case.index,
                values: case.describe(),
                source: Box::new(source),
            });
        }
        Ok(Sweep {
            origin: origin.to_owned(),
            base,
            base_path: file.base.as_ref().map(|p| dir.join(p)),
            axes,
            format: outputs.format.unwrap_or_default(),
            len,
        })
    }

    /// The base scene's file, if the sweep names one.
    pub fn base_path(&self) -> Option<&Path> {
        self.base_path.as_deref()
    }

    /// Case `index` (`0 <= index < len()`), made from its index; `None`
    /// past the end.
    pub fn case(&self, index: usize) -> Option<Case> {
        (index < self.len).then(|| make_case(&self.base, &self.axes, index))
    }

    /// Every case, in index order. This holds the whole grid: for large
    /// sweeps use [`Sweep::case`].
    pub fn cases(&self) -> Vec<Case> {
        (0..self.len)
            .map(|i| make_case(&self.base, &self.axes, i))
            .collect()
    }

    /// Number of cases.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True for a sweep without cases (never: a sweep without axes has one).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The base scene, with the sweep's indicators.
    pub fn base(&self) -> &Scene {
        &self.base
    }

    /// The axes and their values, in case order.
    pub fn axes(&self) -> &[(SweepAxis, Vec<AxisValue>)] {
        &self.axes
    }

    /// The output format the sweep file asks for.
    pub fn format(&self) -> SweepFormat {
        self.format
    }

    /// Where the sweep came from (its path, or `<string>`).
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// The output columns (see the module docs).
    pub fn columns(&self, timing: bool) -> Vec<String> {
        super::table::column_kinds(self, timing)
            .iter()
            .map(|c| c.name().to_owned())
            .collect()
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

fn make_case(base: &Scene, axes: &[(SweepAxis, Vec<AxisValue>)], index: usize) -> Case {
    let mut rest = index;
    let mut values = vec![(SweepAxis::Level, AxisValue::Bool(false)); axes.len()];
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
        if let (SweepAxis::Level, Some(level)) = (axis, value.as_f64()) {
            set_level(&mut scene, level);
        }
    }
    Case {
        index,
        values,
        scene,
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

    /// The cases of this shard among `0..len`, in order.
    pub fn cases(self, len: usize) -> impl Iterator<Item = usize> {
        (self.index - 1..len).step_by(self.count)
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
