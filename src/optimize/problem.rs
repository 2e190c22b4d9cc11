//! The optimisation problem: which signals are allowed (stroke, frequency,
//! limits), how one is evaluated, and how the search weighs objective and
//! limits (docs/model.md section 15).
//!
//! A candidate is a [`Shape`]; its signal is the `kind = "harmonics"`
//! series [`Shape::series`] at the fundamental frequency `f_0`, scaled to
//! the stroke exactly and shifted to its minimum, with the scene's motor.
//! Every evaluation is one [`simulation::simulate`] of that scene, asking
//! only for the indicators the objective and the limits need, so the value
//! the search sees is the value `stickslip run` prints for the same scene.
//!
//! **Constraints.** The stroke and the highest frequency are exact by
//! construction (stroke scaling; harmonics `1..n` of `f_0` with
//! `n f_0 <= f_max`). The optional [`Limits`] are inequalities on what a
//! run reports. The search maximises the exact penalty function
//!
//! ```text
//! m(x) = sense * objective(x) / scale - mu * sum_i max(0, g_i(x))
//! ```
//!
//! with every limit written as a relative violation `g_i` (`(S - S_max) /
//! S_max`, ...), `scale` the magnitude of the objective for the sigma
//! signal and `mu` a weight raised until the result is feasible. For
//! objectives other than `v_inf` the slider must move forward
//! (`v_inf > 0`). A candidate whose run has no steady state, or fails, has
//! `m = -inf`. Which result is reported is decided by [`Problem::feasible`]
//! on the values the run reports, never by the penalty.

use super::objective::{Objective, Values, startup_periods_continuous};
use super::params::{HarmonicSeries, Shape};
use crate::indicator::Indicator;
use crate::scene::{Outputs, Scene};
use crate::signal::{IdealShape, SignalSpec};
use crate::simulation::{self, Outcome};

/// Optional limits on what a run reports (all `None` by default).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Limits {
    /// Largest apparent power `S` (35) (VA).
    pub max_apparent_power: Option<f64>,
    /// Largest RMS voltage `U` (33) (V).
    pub max_voltage_rms: Option<f64>,
    /// Smallest smoothness (16).
    pub min_smoothness: Option<f64>,
    /// Smallest durability (18) (1/N).
    pub min_durability: Option<f64>,
    /// Largest start-up time `T p_0.99` (s).
    pub max_startup_time: Option<f64>,
    /// Smallest `v_inf` (m/s).
    pub min_v_inf: Option<f64>,
}

impl Limits {
    /// True if no limit is set.
    pub fn is_empty(&self) -> bool {
        *self == Limits::default()
    }

    /// The indicators a run must compute to check these limits.
    pub fn indicators(&self) -> Vec<Indicator> {
        let mut out = Vec::new();
        if self.max_apparent_power.is_some() || self.max_voltage_rms.is_some() {
            out.push(Indicator::VelocityPerPower);
        }
        if self.min_smoothness.is_some() {
            out.push(Indicator::Smoothness);
        }
        if self.min_durability.is_some() {
            out.push(Indicator::Durability);
        }
        if self.max_startup_time.is_some() {
            out.push(Indicator::StartupTime);
        }
        out
    }
}

/// What one evaluated candidate's run reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// The quantities objectives and limits use.
    pub values: Values,
    /// The start-up time `T p_0.99` as reported (s), when computed and
    /// reached.
    pub startup_time: Option<f64>,
    /// The estimated error of `v_inf` (m/s), where a bound holds.
    pub v_inf_error: Option<f64>,
    /// The steady-state regime.
    pub regime: &'static str,
    /// The slider's velocity at the boundary of the steady period (m/s),
    /// where the exact sensitivities start (docs/model.md section 14).
    pub boundary_velocity: f64,
}

/// The problem: the scene's motor, actuator and run settings; the stroke,
/// the fundamental frequency and `n`; objective and limits.
#[derive(Debug, Clone)]
pub struct Problem {
    /// The scene the written optimum is built on: its motor, actuator,
    /// run settings and outputs.
    pub base: Scene,
    /// Stroke `x_hat` (m).
    pub stroke: f64,
    /// Fundamental frequency `f_0` (Hz).
    pub f0: f64,
    /// The highest frequency allowed (Hz); `n f_0 <= f_max`.
    pub f_max: f64,
    /// Number of harmonics `n`.
    pub harmonics: usize,
    /// What is optimised.
    pub objective: Objective,
    /// Limits on the run's values.
    pub limits: Limits,
    /// A further bound `sense * value >= level` on a second objective (the
    /// points of a Pareto front).
    pub bound: Option<(Objective, f64)>,
    /// A second objective whose indicator every run computes as well (the
    /// other end of a Pareto front).
    pub also: Option<Objective>,
    /// The objective's magnitude for the sigma signal: the merit's unit.
    pub scale: f64,
    /// `|v_inf|` of the sigma signal (m/s): the unit of the forward
    /// requirement.
    pub v_ref: f64,
}

impl Problem {
    /// The signal of a series: harmonics `1..n` of `f_0`, scaled to the
    /// stroke and shifted to the minimum.
    pub fn spec(&self, series: &HarmonicSeries) -> SignalSpec {
        SignalSpec::Harmonics {
            frequency: self.f0,
            amplitudes: series.amplitudes.clone(),
            phases: series.phases.clone(),
            scale_to_stroke: Some(self.stroke),
            shift_to_minimum: true,
        }
    }

    /// The paper's Fourier signal with `n` harmonics at the same stroke
    /// and `f_0` (so the same `f_max`), with or without sigma factors:
    /// `kappa = 2 x_hat f_0^2 / a_0` (model 2). `None` without friction
    /// (`a_0 = 0`), where `kappa` is undefined.
    pub fn reference_spec(&self, sigma: bool) -> Option<SignalSpec> {
        let a0 = crate::motor::Motor::new(self.base.motor).ok()?.a_0();
        let kappa = 2.0 * self.stroke * self.f0 * self.f0 / a0;
        (a0 > 0.0 && kappa.is_finite() && kappa > 0.0).then_some(SignalSpec::Fourier {
            shape: IdealShape::with_kappa(self.stroke, kappa, 1.0),
            harmonics: self.harmonics,
            sigma,
        })
    }

    /// The indicators a search run computes: `v_inf` and what the
    /// objectives and limits need.
    pub fn indicators(&self) -> Vec<Indicator> {
        let mut wanted = vec![Indicator::VInf, self.objective.indicator()];
        if let Some((o, _)) = self.bound {
            wanted.push(o.indicator());
        }
        if let Some(o) = self.also {
            wanted.push(o.indicator());
        }
        wanted.extend(self.limits.indicators());
        Indicator::ALL
            .into_iter()
            .filter(|i| wanted.contains(i))
            .collect()
    }

    /// The scene of a search run with signal `spec`: the base scene with
    /// only the indicators the search needs and no cross-check of the
    /// steady state (which changes no value, model 10).
    pub fn search_scene(&self, spec: SignalSpec) -> Scene {
        let mut scene = self.base.clone();
        scene.signal = spec;
        scene.outputs = Outputs {
            indicators: self.indicators(),
            trajectory: false,
            events: false,
        };
        scene.run.verify_steady_state = false;
        scene
    }

    /// The scene written for a series: the base scene (its outputs and run
    /// settings) with the series as its signal.
    pub fn written_scene(&self, series: &HarmonicSeries) -> Scene {
        let mut scene = self.base.clone();
        scene.signal = self.spec(series);
        scene
    }

    /// Runs the search scene of `spec`; `Err` with the reason when there
    /// is no steady state or a needed value does not exist.
    pub fn measure(&self, spec: SignalSpec) -> Result<Measured, String> {
        let scene = self.search_scene(spec);
        let outcome = simulation::simulate(&scene).map_err(|e| e.to_string())?;
        let Outcome::Steady(r) = outcome else {
            return Err(format!("no steady state ({})", outcome.regime()));
        };
        let ind = &r.indicators;
        let wants = |i: Indicator| scene.outputs.indicators.contains(&i);
        let startup_periods = r
            .transient
            .as_ref()
            .and_then(|t| startup_periods_continuous(&t.mean_velocities, ind.v_inf));
        let values = Values {
            v_inf: ind.v_inf,
            apparent_power: r.power.as_ref().map_or(0.0, |p| p.apparent_power),
            voltage_rms: r.power.as_ref().map_or(0.0, |p| p.u_rms),
            smoothness: if wants(Indicator::Smoothness) {
                ind.smoothness
            } else {
                0.0
            },
            durability: if wants(Indicator::Durability) {
                ind.durability
            } else {
                0.0
            },
            startup: if wants(Indicator::StartupTime) {
                startup_periods.map_or(f64::INFINITY, |p| p * r.period)
            } else {
                0.0
            },
        };
        if !values.is_finite() {
            return Err("an indicator the search needs does not exist".to_owned());
        }
        Ok(Measured {
            values,
            startup_time: r.startup_time(),
            v_inf_error: r.error.v_inf,
            regime: r.regime().name(),
            boundary_velocity: r.steady.boundary_velocity,
        })
    }

    /// [`Problem::measure`] of a shape's series.
    pub fn evaluate(&self, shape: &Shape) -> Result<Measured, String> {
        self.measure(self.spec(&shape.series(self.stroke)))
    }

    /// The relative violations `g_i` of the limits (and of the Pareto
    /// bound and the forward requirement) as the search sees them, each
    /// `> 0` where violated, with their derivatives along a direction in
    /// which the values change by `dv`.
    fn violations(&self, v: &Values, dv: &Values) -> Vec<(f64, f64)> {
        let l = &self.limits;
        let unit = |b: f64| b.abs().max(f64::MIN_POSITIVE);
        let mut g = Vec::new();
        if let Some(b) = l.max_apparent_power {
            g.push(((v.apparent_power - b) / b, dv.apparent_power / b));
        }
        if let Some(b) = l.max_voltage_rms {
            g.push(((v.voltage_rms - b) / b, dv.voltage_rms / b));
        }
        if let Some(b) = l.min_smoothness {
            g.push(((b - v.smoothness) / unit(b), -dv.smoothness / unit(b)));
        }
        if let Some(b) = l.min_durability {
            g.push(((b - v.durability) / unit(b), -dv.durability / unit(b)));
        }
        if let Some(b) = l.max_startup_time {
            g.push(((v.startup - b) / b, dv.startup / b));
        }
        if let Some(b) = l.min_v_inf {
            let u = unit(b).max(self.v_ref);
            g.push(((b - v.v_inf) / u, -dv.v_inf / u));
        }
        if self.objective != Objective::VInf {
            g.push((-v.v_inf / self.v_ref, -dv.v_inf / self.v_ref));
        }
        if let Some((o, level)) = self.bound {
            let u = unit(level);
            g.push((
                (level - o.sense() * o.searched(v)) / u,
                -o.sense() * o.derivative(v, dv) / u,
            ));
        }
        g
    }

    /// The merit `m` (module docs) with penalty weight `mu`.
    pub fn merit(&self, m: &Measured, mu: f64) -> f64 {
        let v = &m.values;
        let objective = self.objective.sense() * self.objective.searched(v) / self.scale;
        let penalty: f64 = self
            .violations(v, &Values::default())
            .iter()
            .map(|(g, _)| g.max(0.0))
            .sum();
        let merit = objective - mu * penalty;
        if merit.is_nan() {
            f64::NEG_INFINITY
        } else {
            merit
        }
    }

    /// The derivative of the merit along a direction in which the values
    /// change by `dv` (at a violation of exactly 0 the limit counts as
    /// inactive).
    pub fn merit_derivative(&self, m: &Measured, dv: &Values, mu: f64) -> f64 {
        let v = &m.values;
        let objective = self.objective.sense() * self.objective.derivative(v, dv) / self.scale;
        let slope: f64 = self
            .violations(v, dv)
            .iter()
            .filter(|(g, _)| *g > 0.0)
            .map(|(_, dg)| dg)
            .sum();
        objective - mu * slope
    }

    /// True if the run's reported values satisfy every limit, the Pareto
    /// bound and (for objectives other than `v_inf`) `v_inf > 0`, and the
    /// objective exists.
    pub fn feasible(&self, m: &Measured) -> bool {
        let v = &m.values;
        let l = &self.limits;
        let le = |x: f64, b: Option<f64>| b.is_none_or(|b| x <= b);
        let ge = |x: f64, b: Option<f64>| b.is_none_or(|b| x >= b);
        let startup_ok = match l.max_startup_time {
            Some(b) => m.startup_time.is_some_and(|t| t <= b),
            None => true,
        };
        let bound_ok = self.bound.is_none_or(|(o, level)| {
            let value = match o {
                Objective::StartupTime => m.startup_time.unwrap_or(f64::INFINITY),
                _ => o.searched(v),
            };
            o.sense() * value >= level
        });
        self.objective.searched(v).is_finite()
            && le(v.apparent_power, l.max_apparent_power)
            && le(v.voltage_rms, l.max_voltage_rms)
            && ge(v.smoothness, l.min_smoothness)
            && ge(v.durability, l.min_durability)
            && ge(v.v_inf, l.min_v_inf)
            && startup_ok
            && bound_ok
            && (self.objective == Objective::VInf || v.v_inf > 0.0)
            && (self.objective != Objective::StartupTime || m.startup_time.is_some())
    }

    /// The objective's reported value: the start-up time as `T p_0.99`.
    pub fn reported(&self, objective: Objective, m: &Measured) -> Option<f64> {
        match objective {
            Objective::StartupTime => m.startup_time,
            o => Some(o.searched(&m.values)).filter(|x| x.is_finite()),
        }
    }
}
