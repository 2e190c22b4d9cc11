//! The force-velocity characteristic of a drive (docs/model.md section 9):
//! the steady-state velocity `v_inf` against a constant load force, with
//! the numbers motor datasheets state.
//!
//! # Sign convention
//!
//! The load force `F` **opposes forward motion**: it enters the model as
//! the extra acceleration `g_t = -F / m_s` (`motor.extra_acceleration`,
//! which the characteristic replaces). `F > 0` is a load the drive pushes
//! against (a lifted weight), `F < 0` a load that assists forward motion.
//! On an incline of angle `theta` (positive: forward points uphill) the
//! load is the slider's weight, `F = m_s g sin(theta)` with the standard
//! gravity `g = 9.80665 m/s^2` ([`G`]).
//!
//! # What is computed
//!
//! Every number comes from the exact `v_inf` of `crate::simulation`
//! with its error estimate (docs/model.md sections 10, 11), evaluated at
//! chosen loads with one shared signal (`evaluate`):
//!
//! * the curve, sampled where it bends (`sampling`), from an assisting
//!   load through zero to the stall force and beyond (backward motion),
//!   ended on each side where the slider runs away (`domain`: no steady
//!   state exists beyond the holding force);
//! * the no-load speed `v_inf(0)`;
//! * the stall force, where `v_inf` becomes 0, to `1e-10` relative, and
//!   the band of loads that hold the slider still, if any (`stall`);
//! * the holding force at rest `mu_0 F_c` (closed form: a slider at rest
//!   on a rod at rest stays while `|g_t| <= a_0`);
//! * the largest mechanical output power `F v_inf` and its load
//!   (`output_power`);
//! * the force a start-up measurement would report (`transient`);
//! * the datasheet block (`datasheet`);
//! * the slope `d v_inf / d F` at every point (`slope`: exact, one-sided
//!   where the event structure changes, absent where the period map does
//!   not contract), computed after the points are chosen, so that a slope
//!   that is not available changes no other number;
//! * text, JSON and CSV (`table`).
//!
//! Monotonicity: `v_inf` does not increase with `F` (a slider pushed harder
//! never overtakes one pushed less on the same rod, the comparison argument
//! of docs/model.md section 3), so the curve changes sign once and the
//! held loads form one interval.
//!
//! # Cost
//!
//! [`Characteristic::counts`] gives the simulations run by purpose, and how
//! many of them did not converge within `run.max_periods` (each of those
//! simulated that many periods); every distinct load is simulated once.
//! The number of simulations is bounded by construction: at most
//! `--max-evaluations` for the sampled curve (or its 17 + 1 grid loads), a
//! bisection per end of the curve (about 27 halvings from a grid step of
//! `mu_0 F_c / 8` down to `1e-9 mu_0 F_c`), the stall search (eight grid
//! loads, Brent's method and bisections, each at most 200 steps), the held
//! band's edges, the 16 loads and Brent's search of the largest power, and
//! one start-up run.

mod datasheet;
mod domain;
mod evaluate;
mod output_power;
mod sampling;
mod slope;
mod stall;
pub(crate) mod table;
mod transient;

use crate::error::{Num, ParamError};
use crate::scene::Scene;
pub use datasheet::{Datasheet, DatasheetEntry};
pub use domain::Limit;
pub use evaluate::{Counts, Evaluation};
use evaluate::{Evaluator, Purpose};
pub use output_power::MaxPower;
use slope::slope_at;
pub use slope::{Slope, SlopeMethod};
pub use stall::{HeldBand, Stall, StallKind};
use std::time::{Duration, Instant};
use thiserror::Error;
pub use transient::TransientForce;

/// Standard gravity (m/s^2), for loads on an incline.
pub const G: f64 = 9.80665;

/// Tolerance of the curve's ends (run-away limits), relative to the
/// holding force.
pub const LIMIT_TOLERANCE: f64 = 1e-9;

/// What goes wrong while computing a characteristic.
#[derive(Debug, Error)]
pub enum CharacteristicError {
    /// An option out of its range.
    #[error("{flag} {value}: {requirement}")]
    Option {
        /// The option's flag.
        flag: &'static str,
        /// The value given.
        value: String,
        /// What it must satisfy.
        requirement: String,
    },
    /// A scene that has no characteristic.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A simulation failed (a time limit, an internal limit).
    #[error("at load F = {} N: {source}", Num(*load))]
    Simulation {
        /// The load (N).
        load: f64,
        /// The simulator's error.
        #[source]
        source: crate::error::Error,
    },
    /// A load where a steady state is needed has none.
    #[error("at load F = {} N the slider has no steady state ({regime})", Num(*load))]
    NoSteadyState {
        /// The load (N).
        load: f64,
        /// The outcome's regime.
        regime: &'static str,
    },
    /// A solver failed in a way the contract does not foresee.
    #[error("characteristic: {0}")]
    Unexpected(String),
}

/// What the load is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadAxis {
    /// A force `F` (N).
    Force,
    /// The slider's weight on an incline of angle `theta` (degrees):
    /// `F = m_s g sin(theta)`.
    Incline,
}

impl LoadAxis {
    /// The name in outputs: `force` or `incline`.
    pub fn name(self) -> &'static str {
        match self {
            LoadAxis::Force => "force",
            LoadAxis::Incline => "incline",
        }
    }

    /// The unit of the axis: `N` or `deg`.
    pub fn unit(self) -> &'static str {
        match self {
            LoadAxis::Force => "N",
            LoadAxis::Incline => "deg",
        }
    }

    /// The load force (N) at axis value `x`, for slider mass `m_s`.
    pub fn force(self, x: f64, slider_mass: f64) -> f64 {
        match self {
            LoadAxis::Force => x,
            LoadAxis::Incline => slider_mass * G * x.to_radians().sin(),
        }
    }

    /// The axis value of load `force` (NaN on an incline that cannot
    /// carry it, `|F| > m_s g`).
    pub fn parameter(self, force: f64, slider_mass: f64) -> f64 {
        match self {
            LoadAxis::Force => force,
            LoadAxis::Incline => {
                let s = force / (slider_mass * G);
                if s.abs() <= 1.0 {
                    s.asin().to_degrees()
                } else {
                    f64::NAN
                }
            }
        }
    }

    /// The whole range: `[-mu_0 F_c, mu_0 F_c]` for a force (no steady state
    /// exists beyond, `domain`), `[-90, 90]` degrees on an incline.
    pub(crate) fn default_range(self, holding_force: f64) -> (f64, f64) {
        match self {
            LoadAxis::Force => (-holding_force, holding_force),
            LoadAxis::Incline => (-90.0, 90.0),
        }
    }
}

/// How to compute a characteristic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacteristicOptions {
    /// The load axis.
    pub axis: LoadAxis,
    /// The range sampled, in the axis unit; `None`: the whole range.
    pub range: Option<(f64, f64)>,
    /// Chord tolerance of the sampling, relative to the range of `v_inf`.
    pub tolerance: f64,
    /// Evaluations the sampled curve may use (grid and refinement).
    pub max_evaluations: u64,
}

impl Default for CharacteristicOptions {
    fn default() -> Self {
        CharacteristicOptions {
            axis: LoadAxis::Force,
            range: None,
            tolerance: 1e-3,
            max_evaluations: 400,
        }
    }
}

impl CharacteristicOptions {
    /// Checks the options; errors name the command-line flag.
    pub fn validate(&self) -> Result<(), CharacteristicError> {
        let bad = |flag, value: f64, requirement: &str| CharacteristicError::Option {
            flag,
            value: Num(value).to_string(),
            requirement: requirement.to_owned(),
        };
        if !(1e-6..=0.5).contains(&self.tolerance) {
            return Err(bad(
                "--tolerance",
                self.tolerance,
                "must be from 1e-6 to 0.5 (relative to the range of v_inf)",
            ));
        }
        if self.max_evaluations < 20 {
            return Err(bad(
                "--max-evaluations",
                self.max_evaluations as f64,
                "must be at least 20",
            ));
        }
        if let Some((lo, hi)) = self.range {
            for (flag, v) in [("--from", lo), ("--to", hi)] {
                if !v.is_finite() {
                    return Err(bad(flag, v, "must be a finite number"));
                }
                if self.axis == LoadAxis::Incline && !(-90.0..=90.0).contains(&v) {
                    return Err(bad(flag, v, "must be an angle from -90 to 90 degrees"));
                }
            }
            if lo >= hi {
                return Err(bad(
                    "--to",
                    hi,
                    &format!("must be above --from {}", Num(lo)),
                ));
            }
        }
        Ok(())
    }
}

/// Which special load a point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadMark {
    /// Zero load.
    NoLoad,
    /// The stall force.
    Stall,
    /// An edge of the held band.
    HeldEdge,
    /// The load of the largest output power.
    MaxPower,
    /// The last load with a steady state before a run-away.
    RunAwayLimit,
    /// The last load with a steady state before a load whose run did not
    /// converge within `run.max_periods` (the end of the curve as far as
    /// it is known, `domain`).
    UnsettledLimit,
}

impl LoadMark {
    /// The name in outputs.
    pub fn name(self) -> &'static str {
        match self {
            LoadMark::NoLoad => "no_load",
            LoadMark::Stall => "stall",
            LoadMark::HeldEdge => "held_edge",
            LoadMark::MaxPower => "max_power",
            LoadMark::RunAwayLimit => "run_away_limit",
            LoadMark::UnsettledLimit => "not_converged_limit",
        }
    }
}

/// One point of the characteristic.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Position on the load axis (N, or degrees on an incline).
    pub x: f64,
    /// The steady state at its load.
    pub evaluation: Evaluation,
    /// `d v_inf / d F` there.
    pub slope: Slope,
    /// The special loads it is (empty for a plain sample).
    pub marks: Vec<LoadMark>,
}

/// The incline's own numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclineSummary {
    /// The angle at which the drive stalls (degrees), if an incline is
    /// steep enough.
    pub stall_angle: Option<f64>,
    /// The steepest incline on which the slider at rest stays put
    /// (degrees): `asin(min(1, mu_0 F_c / (m_s g)))`.
    pub holding_angle: f64,
}

/// A drive's characteristic.
#[derive(Debug, Clone, PartialEq)]
pub struct Characteristic {
    /// The load axis.
    pub axis: LoadAxis,
    /// The range sampled, in the axis unit.
    pub range: (f64, f64),
    /// Slider mass `m_s` (kg).
    pub slider_mass: f64,
    /// The scene's own `motor.extra_acceleration`, replaced by the load.
    pub replaced_extra_acceleration: f64,
    /// The points, in increasing `x`.
    pub points: Vec<Point>,
    /// The evaluation at zero load.
    pub no_load: Evaluation,
    /// The drive direction: `1` forward, `-1` backward, `0` none (the
    /// sign of the no-load speed beyond its error).
    pub drive: i8,
    /// The stall force.
    pub stall: Stall,
    /// The band of loads that hold the slider still.
    pub held_band: Option<HeldBand>,
    /// The holding force at rest, `mu_0 F_c` (N).
    pub holding_force: f64,
    /// The largest output power.
    pub max_power: Option<MaxPower>,
    /// The end of the curve at low loads (the slider runs away forwards).
    pub run_away_below: Option<Limit>,
    /// The end of the curve at high loads (it runs away backwards).
    pub run_away_above: Option<Limit>,
    /// On an incline: stall and holding angles.
    pub incline: Option<InclineSummary>,
    /// What a start-up measurement would report.
    pub transient: Option<TransientForce>,
    /// The datasheet block.
    pub datasheet: Datasheet,
    /// False if the sampling budget ended the refinement.
    pub sampling_complete: bool,
    /// Simulations run, by purpose.
    pub counts: Counts,
    /// Wall time of the whole computation.
    pub wall_time: Duration,
}

impl Characteristic {
    /// The name of the drive direction: `forward`, `backward` or `none`.
    pub fn drive_direction(&self) -> &'static str {
        match self.drive {
            1 => "forward",
            -1 => "backward",
            _ => "none",
        }
    }
}

/// The two forces a characteristic gives for comparing a drive with a
/// force measurement (the paper's section 5): the stall force (the weight
/// method) and what a start-up measurement reports (the Newton method).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceForces {
    /// The stall force (module docs, `stall`).
    pub stall: Stall,
    /// The start-up force (`transient`); `None` when the run from rest
    /// shows no start-up.
    pub transient: Option<TransientForce>,
    /// The holding force at rest, `mu_0 F_c` (N).
    pub holding_force: f64,
}

/// The holding force `mu_0 F_c` of `scene`'s motor, for `what` (a
/// characteristic, a stall force): a prescribed rod and static friction
/// are needed.
fn holding_force(scene: &Scene, what: &str) -> Result<f64, CharacteristicError> {
    crate::simulation::prescribed_only(scene, "characteristic")?;
    let motor = scene.motor;
    if motor.mu_static <= 0.0 {
        return Err(ParamError::out_of_range(
            "motor.mu_static",
            motor.mu_static,
            format!("must be positive for {what}: without static friction no load is held"),
        )
        .into());
    }
    Ok(motor.mu_static * motor.contact_force)
}

/// The run at zero load, which must reach a steady state.
fn steady_without_load(ev: &Evaluator) -> Result<Evaluation, CharacteristicError> {
    let no_load = ev.at(0.0, Purpose::Sampling)?;
    if !no_load.is_steady() {
        return Err(CharacteristicError::NoSteadyState {
            load: 0.0,
            regime: no_load.regime,
        });
    }
    Ok(no_load)
}

/// The stall force and the start-up force of `scene`, exactly as
/// [`characteristic`] finds them, without sampling the curve: the zero
/// load, the stall search and one start-up run.
pub fn reference_forces(scene: &Scene) -> Result<ReferenceForces, CharacteristicError> {
    let holding_force = holding_force(scene, "a stall force")?;
    let ev = Evaluator::new(scene);
    let no_load = steady_without_load(&ev)?;
    let found = stall::find(&ev, no_load, holding_force, LIMIT_TOLERANCE * holding_force)?;
    Ok(ReferenceForces {
        stall: found.stall,
        transient: transient::transient_force(&ev)?,
        holding_force,
    })
}

/// The characteristic of `scene` (module docs).
pub fn characteristic(
    scene: &Scene,
    options: &CharacteristicOptions,
) -> Result<Characteristic, CharacteristicError> {
    let clock = Instant::now();
    options.validate()?;
    let holding_force = holding_force(scene, "a characteristic")?;
    let m = scene.motor.slider_mass;
    let axis = options.axis;
    let range = options
        .range
        .unwrap_or_else(|| axis.default_range(holding_force));
    let ev = Evaluator::new(scene);
    let no_load = steady_without_load(&ev)?;
    let limit_tolerance = LIMIT_TOLERANCE * holding_force;
    let sampled = sampling::sample(
        &ev,
        &sampling::SamplingSpec {
            axis,
            range,
            tolerance: options.tolerance,
            budget: options.max_evaluations,
            limit_tolerance,
        },
    )?;
    let found = stall::find(&ev, no_load, holding_force, limit_tolerance)?;
    let max_power = output_power::find(&ev, found.stall.force)?;
    let transient = transient::transient_force(&ev)?;
    let (mut below, mut above) = (sampled.below, sampled.above);
    if let Some(limit) = found.limit {
        let side = if limit.last_steady.load > 0.0 {
            &mut above
        } else {
            &mut below
        };
        side.get_or_insert(limit);
    }

    // The points: samples, then the special loads inside the range.
    let (f_lo, f_hi) = (axis.force(range.0, m), axis.force(range.1, m));
    let mut points: Vec<Point> = Vec::new();
    let mut add = |e: Evaluation, mark: Option<LoadMark>| {
        if let Some(p) = points.iter_mut().find(|p| p.evaluation.load == e.load) {
            p.marks.extend(mark);
            return;
        }
        let x = axis.parameter(e.load, m);
        if e.load >= f_lo && e.load <= f_hi && x.is_finite() {
            points.push(Point {
                x,
                evaluation: e,
                slope: Slope::NONE,
                marks: mark.into_iter().collect(),
            });
        }
    };
    for s in &sampled.samples {
        add(s.evaluation, None);
    }
    add(no_load, Some(LoadMark::NoLoad));
    add(found.stall.at, Some(LoadMark::Stall));
    if let Some(band) = &found.band {
        for edge in [band.lower, band.upper] {
            add(ev.at(edge, Purpose::HeldBand)?, Some(LoadMark::HeldEdge));
        }
    }
    if let Some(p) = &max_power {
        for e in &p.grid {
            add(*e, None);
        }
        add(p.at, Some(LoadMark::MaxPower));
    }
    for limit in [below, above].into_iter().flatten() {
        let mark = if limit.first_unsteady.is_unsettled() {
            LoadMark::UnsettledLimit
        } else {
            LoadMark::RunAwayLimit
        };
        add(limit.last_steady, Some(mark));
    }
    points.sort_by(|a, b| a.x.total_cmp(&b.x));
    for p in &mut points {
        p.slope = slope_at(&ev, p.evaluation.load)?;
    }

    let incline = (axis == LoadAxis::Incline).then(|| {
        let angle = axis.parameter(found.stall.force, m);
        InclineSummary {
            stall_angle: (angle.is_finite() && found.stall.force != 0.0).then_some(angle),
            holding_angle: (holding_force / (m * G)).min(1.0).asin().to_degrees(),
        }
    });
    let datasheet = Datasheet::new(
        no_load.v_inf.unwrap_or(0.0),
        Some(found.stall.force),
        holding_force,
        Some(max_power.as_ref().map_or(0.0, |p| p.power)),
    );
    Ok(Characteristic {
        axis,
        range,
        slider_mass: m,
        replaced_extra_acceleration: scene.motor.extra_acceleration,
        points,
        no_load,
        drive: no_load.sign().unwrap_or(0),
        stall: found.stall,
        held_band: found.band,
        holding_force,
        max_power,
        run_away_below: below,
        run_away_above: above,
        incline,
        transient,
        datasheet,
        sampling_complete: sampled.complete,
        counts: ev.counts(),
        wall_time: clock.elapsed(),
    })
}
