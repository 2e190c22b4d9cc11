//! What to optimise: the scene's `[optimize]` table and the command-line
//! flags that override it, checked into [`Settings`], and the
//! [`Problem`] they make with the scene (docs/interface.md, `optimize`).
//!
//! The motor, the actuator, the run settings and the stroke come from the
//! scene; so does the highest frequency (`keep = "f_max"`: the scene
//! signal's `f_max = n f_0`, or `optimize.f_max`) or the fundamental
//! frequency (`keep = "f0"`). With `keep = "f_max"` and `n` harmonics the
//! fundamental is `f_0 = f_max / n` (rounded down so that `n f_0` never
//! exceeds `f_max`): the paper's comparison at equal `f_max`.
//!
//! Every error names the field (`optimize.harmonics`, or the flag
//! `--harmonics`) and the value.

use super::objective::Objective;
use super::problem::{Limits, Problem};
use crate::error::{Num, ParamError, SceneError};
use crate::scene::Scene;
use crate::signal::{Signal, SignalSpec};
use serde::Deserialize;

/// Most harmonics `optimize` takes: `2n - 2` free numbers, each local
/// step costing `4n - 2` runs.
pub(crate) const MAX_HARMONICS: usize = 16;

/// The `[optimize]` table of a scene, as written (every field optional).
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OptimizeTable {
    /// `n`, 2 to `MAX_HARMONICS`.
    pub harmonics: Option<i64>,
    /// An objective name, or two separated by a comma (a Pareto front).
    pub objective: Option<String>,
    /// `"f_max"` or `"f0"`.
    pub keep: Option<String>,
    /// Seed of the global stage (>= 0).
    pub seed: Option<i64>,
    /// The highest frequency (Hz), with `keep = "f_max"`.
    pub f_max: Option<f64>,
    /// Points of the global stage.
    pub samples: Option<i64>,
    /// Local refinements.
    pub local_starts: Option<i64>,
    /// Iterations of each local refinement.
    pub max_iterations: Option<i64>,
    /// Points of a Pareto front.
    pub pareto_points: Option<i64>,
    /// Largest apparent power `S` (VA).
    pub max_apparent_power: Option<f64>,
    /// Largest RMS voltage `U` (V).
    pub max_voltage_rms: Option<f64>,
    /// Smallest smoothness.
    pub min_smoothness: Option<f64>,
    /// Smallest durability (1/N).
    pub min_durability: Option<f64>,
    /// Largest start-up time (s).
    pub max_startup_time: Option<f64>,
    /// Smallest `v_inf` (m/s).
    pub min_v_inf: Option<f64>,
}

/// A scene file seen by `optimize`: only its `[optimize]` table (the rest
/// is read by [`Scene::from_toml_str`]).
#[derive(Deserialize)]
struct WithTable {
    #[serde(default)]
    optimize: Option<OptimizeTable>,
}

/// The `[optimize]` table of a scene's text (empty when absent); errors
/// name the field, line and column.
pub(crate) fn read_table(text: &str, origin: &str) -> Result<OptimizeTable, SceneError> {
    let file: WithTable = toml::from_str(text).map_err(|e| SceneError::Parse {
        path: origin.to_owned(),
        message: crate::scene::parse_message(text, &e),
    })?;
    Ok(file.optimize.unwrap_or_default())
}

/// Command-line values that replace the table's.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// `--harmonics`.
    pub harmonics: Option<i64>,
    /// `--objective`.
    pub objective: Option<String>,
    /// `--keep`.
    pub keep: Option<String>,
    /// `--seed`.
    pub seed: Option<u64>,
}

/// Which frequency stays fixed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// The highest frequency `f_max = n f_0` (the paper's comparison).
    FMax,
    /// The fundamental frequency `f_0`.
    F0,
}

impl Keep {
    /// The name in the table and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Keep::FMax => "f_max",
            Keep::F0 => "f0",
        }
    }
}

/// Checked settings of one optimisation.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// `n`.
    pub harmonics: usize,
    /// One objective, or two for a Pareto front.
    pub objectives: Vec<Objective>,
    /// Which frequency stays fixed.
    pub keep: Keep,
    /// Seed of the global stage.
    pub seed: u64,
    /// `optimize.f_max`, if given (Hz).
    pub f_max: Option<f64>,
    /// Points of the global stage.
    pub samples: usize,
    /// Local refinements.
    pub local_starts: usize,
    /// Iterations of each local refinement.
    pub max_iterations: usize,
    /// Points of a Pareto front.
    pub pareto_points: usize,
    /// Limits.
    pub limits: Limits,
}

/// An integer field in `lo..=hi`.
fn integer(field: &str, value: i64, lo: i64, hi: i64) -> Result<usize, ParamError> {
    if (lo..=hi).contains(&value) {
        Ok(value as usize)
    } else {
        Err(ParamError::out_of_range(
            field,
            value as f64,
            format!("must be an integer from {lo} to {hi}"),
        ))
    }
}

/// The number of harmonics of a scene's signal (2 for the ideal signal).
fn scene_harmonics(spec: &SignalSpec) -> usize {
    match spec {
        SignalSpec::Fourier { harmonics, .. } => *harmonics,
        SignalSpec::Harmonics { amplitudes, .. } => amplitudes.len(),
        SignalSpec::Response { cosines, .. } => cosines.len(),
        SignalSpec::Ideal(_) => 2,
    }
}

impl Settings {
    /// Checks the table and the overrides against the scene.
    pub fn resolve(
        table: &OptimizeTable,
        overrides: &Overrides,
        scene: &Scene,
    ) -> Result<Settings, ParamError> {
        let (field, n) = match (overrides.harmonics, table.harmonics) {
            (Some(n), _) => ("--harmonics", n),
            (None, Some(n)) => ("optimize.harmonics", n),
            (None, None) => (
                "signal.harmonics",
                scene_harmonics(&scene.signal).clamp(2, MAX_HARMONICS) as i64,
            ),
        };
        let harmonics = integer(field, n, 2, MAX_HARMONICS as i64)?;
        let (objective_field, text) = match (&overrides.objective, &table.objective) {
            (Some(o), _) => ("--objective", o.clone()),
            (None, Some(o)) => ("optimize.objective", o.clone()),
            (None, None) => ("optimize.objective", "v_inf".to_owned()),
        };
        let objectives = text
            .split(',')
            .map(|name| {
                Objective::from_name(name.trim()).ok_or_else(|| ParamError::Inconsistent {
                    field: objective_field.to_owned(),
                    reason: format!(
                        "unknown objective \"{}\"; expected one of {}, or two of them \
                         separated by a comma (a Pareto front)",
                        name.trim(),
                        Objective::names()
                    ),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        if objectives.len() > 2 || (objectives.len() == 2 && objectives[0] == objectives[1]) {
            return Err(ParamError::Inconsistent {
                field: objective_field.to_owned(),
                reason: format!(
                    "\"{text}\": give one objective, or two different ones for a Pareto front"
                ),
            });
        }
        let (field, keep_text) = match (&overrides.keep, &table.keep) {
            (Some(k), _) => ("--keep", k.as_str()),
            (None, Some(k)) => ("optimize.keep", k.as_str()),
            (None, None) => ("optimize.keep", "f_max"),
        };
        let keep = match keep_text {
            "f_max" => Keep::FMax,
            "f0" => Keep::F0,
            other => {
                return Err(ParamError::Inconsistent {
                    field: field.to_owned(),
                    reason: format!("\"{other}\": expected \"f_max\" or \"f0\""),
                });
            }
        };
        let seed = match (overrides.seed, table.seed) {
            (Some(s), _) => s,
            (None, Some(s)) => integer("optimize.seed", s, 0, i64::MAX)? as u64,
            (None, None) => 1,
        };
        if let Some(f) = table.f_max {
            ParamError::positive("optimize.f_max", f)?;
            if keep == Keep::F0 {
                return Err(ParamError::Inconsistent {
                    field: "optimize.f_max".to_owned(),
                    reason: "only used with keep = \"f_max\"".to_owned(),
                });
            }
        }
        let dims = 2 * harmonics as i64 - 2;
        let samples = match table.samples {
            Some(s) => integer("optimize.samples", s, 1, 1_000_000)?,
            None => 32 * dims as usize,
        };
        let local_starts = match table.local_starts {
            Some(s) => integer("optimize.local_starts", s, 1, 1000)?,
            None => 2 + dims as usize,
        };
        let max_iterations = match table.max_iterations {
            Some(s) => integer("optimize.max_iterations", s, 1, 100_000)?,
            None => 100,
        };
        let pareto_points = match table.pareto_points {
            Some(s) => integer("optimize.pareto_points", s, 2, 100)?,
            None => 7,
        };
        let positive = |field: &str, v: Option<f64>| -> Result<Option<f64>, ParamError> {
            v.map(|x| ParamError::positive(field, x)).transpose()
        };
        let finite = |field: &str, v: Option<f64>| -> Result<Option<f64>, ParamError> {
            v.map(|x| ParamError::finite(field, x)).transpose()
        };
        let limits = Limits {
            max_apparent_power: positive("optimize.max_apparent_power", table.max_apparent_power)?,
            max_voltage_rms: positive("optimize.max_voltage_rms", table.max_voltage_rms)?,
            min_smoothness: finite("optimize.min_smoothness", table.min_smoothness)?,
            min_durability: finite("optimize.min_durability", table.min_durability)?,
            max_startup_time: positive("optimize.max_startup_time", table.max_startup_time)?,
            min_v_inf: finite("optimize.min_v_inf", table.min_v_inf)?,
        };
        let needs_power = objectives.contains(&Objective::VelocityPerPower)
            || limits.max_apparent_power.is_some()
            || limits.max_voltage_rms.is_some();
        if needs_power && scene.actuator.is_none() {
            let field = if objectives.contains(&Objective::VelocityPerPower) {
                objective_field
            } else if limits.max_apparent_power.is_some() {
                "optimize.max_apparent_power"
            } else {
                "optimize.max_voltage_rms"
            };
            return Err(ParamError::Inconsistent {
                field: field.to_owned(),
                reason: "needs the apparent power (35) of the actuator model: add an \
                         [actuator] table to the scene"
                    .to_owned(),
            });
        }
        Ok(Settings {
            harmonics,
            objectives,
            keep,
            seed,
            f_max: table.f_max,
            samples,
            local_starts,
            max_iterations,
            pareto_points,
            limits,
        })
    }

    /// The problem of these settings on `scene`, optimising objective
    /// `objective` (one of [`Settings::objectives`]); its `scale` and
    /// `v_ref` are 1 until the driver sets them from the sigma signal.
    pub fn problem(
        &self,
        scene: &Scene,
        objective: Objective,
    ) -> Result<Problem, crate::error::Error> {
        let (signal, _) = crate::simulation::build_prescribed(scene, "optimize")?;
        let stroke = match (&scene.signal, &signal) {
            (SignalSpec::Ideal(shape) | SignalSpec::Fourier { shape, .. }, _) => shape.stroke,
            (
                SignalSpec::Harmonics {
                    scale_to_stroke: Some(s),
                    ..
                },
                _,
            ) => *s,
            (_, Signal::Fourier(s)) => s.stroke(),
            (_, Signal::Ideal(_)) => unreachable!("a harmonic series builds a Fourier signal"),
        };
        let n = self.harmonics;
        let (f0, f_max) = match self.keep {
            Keep::FMax => {
                let f_max = match self.f_max.or(signal.f_max()) {
                    Some(f) => f,
                    None => {
                        return Err(ParamError::Inconsistent {
                            field: "optimize.keep".to_owned(),
                            reason: "the scene's signal (kind = \"ideal\") has no highest \
                                     frequency: give optimize.f_max, or keep = \"f0\""
                                .to_owned(),
                        }
                        .into());
                    }
                };
                let mut f0 = f_max / n as f64;
                while f0 * n as f64 > f_max {
                    f0 = f0.next_down();
                }
                (f0, f_max)
            }
            Keep::F0 => (signal.f0(), n as f64 * signal.f0()),
        };
        if !(f0.is_finite() && f0 > 0.0) {
            return Err(ParamError::Inconsistent {
                field: "optimize.f_max".to_owned(),
                reason: format!(
                    "gives the fundamental frequency f_0 = {} Hz, not a positive number",
                    Num(f0)
                ),
            }
            .into());
        }
        let mut base = scene.clone();
        base.signal = SignalSpec::Harmonics {
            frequency: f0,
            amplitudes: vec![0.5 * stroke; n],
            phases: vec![0.0; n],
            scale_to_stroke: Some(stroke),
            shift_to_minimum: true,
        };
        base.validate()?;
        Ok(Problem {
            base,
            stroke,
            f0,
            f_max,
            harmonics: n,
            objective,
            limits: self.limits,
            bound: None,
            also: None,
            scale: 1.0,
            v_ref: 1.0,
        })
    }
}
