//! What `stickslip optimize` can optimise (docs/model.md section 15): the
//! objectives, and the quantities of one run they and the limits are made
//! of.
//!
//! | objective | sense | value |
//! | --- | --- | --- |
//! | `v_inf` | maximise | `v_inf` (model 3) |
//! | `velocity_per_power` | maximise | `v_inf / S`, `S` (35) of the actuator model (model 4) |
//! | `durability` | maximise | `delta_inf` (18) |
//! | `smoothness` | maximise | `zeta_inf` (16) |
//! | `startup_time` | minimise | `T p_0.99` (model 3) |
//!
//! The start-up time is a whole number of periods, a step function of the
//! signal whose derivative is zero almost everywhere. The search therefore
//! works on a continuous stand-in, [`Values::startup`]: the period at which
//! the line through `(p - 1, v_(p-1))` and `(p, v_p)` reaches
//! `0.99 v_inf` (`v_0 = 0`, the rest), which lies in `(p_0.99 - 1, p_0.99]`
//! and moves continuously with the signal; reports and limits use
//! `T p_0.99` itself.

use crate::indicator::Indicator;
use std::fmt;

/// An objective (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Objective {
    /// Maximise `v_inf`.
    VInf,
    /// Maximise `v_inf / S`.
    VelocityPerPower,
    /// Maximise the durability (18).
    Durability,
    /// Maximise the smoothness (16).
    Smoothness,
    /// Minimise the start-up time `T p_0.99`.
    StartupTime,
}

impl Objective {
    /// Every objective, in the order of the docs.
    pub const ALL: [Objective; 5] = [
        Objective::VInf,
        Objective::VelocityPerPower,
        Objective::Durability,
        Objective::Smoothness,
        Objective::StartupTime,
    ];

    /// The name on the command line and in the `[optimize]` table.
    pub fn name(self) -> &'static str {
        match self {
            Objective::VInf => "v_inf",
            Objective::VelocityPerPower => "velocity_per_power",
            Objective::Durability => "durability",
            Objective::Smoothness => "smoothness",
            Objective::StartupTime => "startup_time",
        }
    }

    /// The objective called `name`.
    pub fn from_name(name: &str) -> Option<Objective> {
        Self::ALL.into_iter().find(|o| o.name() == name)
    }

    /// Every name, for messages.
    pub fn names() -> String {
        Self::ALL.map(Objective::name).join(", ")
    }

    /// `+1` for an objective to maximise, `-1` for one to minimise.
    pub fn sense(self) -> f64 {
        match self {
            Objective::StartupTime => -1.0,
            _ => 1.0,
        }
    }

    /// The indicator a run must compute for this objective.
    pub fn indicator(self) -> Indicator {
        match self {
            Objective::VInf => Indicator::VInf,
            Objective::VelocityPerPower => Indicator::VelocityPerPower,
            Objective::Durability => Indicator::Durability,
            Objective::Smoothness => Indicator::Smoothness,
            Objective::StartupTime => Indicator::StartupTime,
        }
    }

    /// The objective's value as the search sees it (the start-up time as
    /// its continuous stand-in), from a run's values.
    pub fn searched(self, v: &Values) -> f64 {
        match self {
            Objective::VInf => v.v_inf,
            Objective::VelocityPerPower => v.v_inf / v.apparent_power,
            Objective::Durability => v.durability,
            Objective::Smoothness => v.smoothness,
            Objective::StartupTime => v.startup,
        }
    }

    /// The derivative of [`Objective::searched`] along a direction in which
    /// the values change by `dv`.
    pub fn derivative(self, v: &Values, dv: &Values) -> f64 {
        match self {
            Objective::VInf => dv.v_inf,
            Objective::VelocityPerPower => {
                (dv.v_inf * v.apparent_power - v.v_inf * dv.apparent_power)
                    / (v.apparent_power * v.apparent_power)
            }
            Objective::Durability => dv.durability,
            Objective::Smoothness => dv.smoothness,
            Objective::StartupTime => dv.startup,
        }
    }
}

impl fmt::Display for Objective {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The quantities of one run that objectives and limits are made of; `0`
/// where the run did not compute one. Differences of these are what
/// [`super::gradient::gradient`] returns.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Values {
    /// `v_inf` (m/s).
    pub v_inf: f64,
    /// Apparent power `S` (35) (VA).
    pub apparent_power: f64,
    /// RMS voltage `U` (33) (V).
    pub voltage_rms: f64,
    /// Smoothness (16).
    pub smoothness: f64,
    /// Durability (18) (1/N).
    pub durability: f64,
    /// The continuous stand-in of the start-up time (s) (module docs).
    pub startup: f64,
}

impl Values {
    /// `(a - b) / h`, quantity by quantity.
    pub fn difference(a: &Values, b: &Values, h: f64) -> Values {
        Values {
            v_inf: (a.v_inf - b.v_inf) / h,
            apparent_power: (a.apparent_power - b.apparent_power) / h,
            voltage_rms: (a.voltage_rms - b.voltage_rms) / h,
            smoothness: (a.smoothness - b.smoothness) / h,
            durability: (a.durability - b.durability) / h,
            startup: (a.startup - b.startup) / h,
        }
    }

    /// `self * s`, quantity by quantity.
    pub fn scaled(&self, s: f64) -> Values {
        Values {
            v_inf: self.v_inf * s,
            apparent_power: self.apparent_power * s,
            voltage_rms: self.voltage_rms * s,
            smoothness: self.smoothness * s,
            durability: self.durability * s,
            startup: self.startup * s,
        }
    }

    /// `self + other`, quantity by quantity.
    pub fn plus(&self, other: &Values) -> Values {
        Values {
            v_inf: self.v_inf + other.v_inf,
            apparent_power: self.apparent_power + other.apparent_power,
            voltage_rms: self.voltage_rms + other.voltage_rms,
            smoothness: self.smoothness + other.smoothness,
            durability: self.durability + other.durability,
            startup: self.startup + other.startup,
        }
    }

    /// True if every quantity is a finite number.
    pub fn is_finite(&self) -> bool {
        [
            self.v_inf,
            self.apparent_power,
            self.voltage_rms,
            self.smoothness,
            self.durability,
            self.startup,
        ]
        .iter()
        .all(|x| x.is_finite())
    }
}

/// The continuous stand-in of `p_0.99` (module docs): with `v_0 = 0`, the
/// first `p` with `v_p / v_inf >= 0.99` and the line through the two
/// periods around it. `None` if the start-up does not reach it.
pub(super) fn startup_periods_continuous(mean_velocities: &[f64], v_inf: f64) -> Option<f64> {
    if v_inf == 0.0 || !v_inf.is_finite() {
        return None;
    }
    let target = 0.99 * v_inf;
    let reached = |v: f64| v / v_inf >= 0.99;
    let p = mean_velocities.iter().position(|v| reached(*v))?;
    let before = if p == 0 { 0.0 } else { mean_velocities[p - 1] };
    let at = mean_velocities[p];
    let fraction = if at == before {
        1.0
    } else {
        ((target - before) / (at - before)).clamp(0.0, 1.0)
    };
    Some(p as f64 + fraction)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for o in Objective::ALL {
            assert_eq!(Objective::from_name(o.name()), Some(o));
        }
        assert_eq!(Objective::from_name("speed"), None);
    }

    #[test]
    fn continuous_startup_lies_in_the_last_period() {
        // v_p = 1 - 0.5^p towards 1: p_0.99 = 7 (0.9921875); the line from
        // (6, 0.984375) reaches 0.99 at 6 + 0.005625 / 0.0078125 = 6.72.
        let v: Vec<f64> = (1..=10).map(|p| 1.0 - 0.5f64.powi(p)).collect();
        let p = startup_periods_continuous(&v, 1.0).unwrap();
        assert!((p - 6.72).abs() < 1e-12, "{p}");
        // Reached in the first period: measured from rest, v_0 = 0.
        let p = startup_periods_continuous(&[1.0, 1.0], 1.0).unwrap();
        assert!((p - 0.99).abs() < 1e-15);
        assert_eq!(startup_periods_continuous(&[0.1], 1.0), None);
    }
}
