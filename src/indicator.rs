//! The performance indicators (docs/model.md sections 3 and 4): one table
//! that every output reads. [`Indicator::ALL`] fixes the order; the name and
//! meaning are here, the symbol and unit in the table of symbols
//! (`src/symbol.rs`); the value and its error estimate come from
//! `RunReport::value` and `RunReport::error` (`src/simulation/outcome.rs`). The
//! text summary, `run --json`, `check`, sweep columns and sweep figures are
//! loops over [`Indicator::ALL`], so they cannot disagree.
//!
//! ## Adding an indicator
//! 1. Add the variant here, in [`Indicator::ALL`], its arms in
//!    [`Indicator::name`] and [`Indicator::meaning`], and its symbol, unit
//!    and description in the table of symbols (`src/symbol.rs`)
//!    (and [`Indicator::unavailable_because`] if some scenes cannot have
//!    it).
//! 2. Compute it: a field of the steady-state indicators or of the
//!    start-up (`src/analysis/`), with its error estimate
//!    (`ErrorEstimate`), and its arms in `RunReport::value` and
//!    `RunReport::error`.
//!
//! Every output then shows it: the JSON key, its `error_estimate` entry,
//! the text line, the `check` row, the sweep column and the axis label.
//! `tests/indicator_table.rs` walks [`Indicator::ALL`] through each of them.

use crate::power::ActuatorParams;
use crate::signal::SignalSpec;
use crate::symbol::{Symbol, symbol};
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// A performance indicator a scene can ask for (docs/model.md sections 3, 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Indicator {
    /// Steady-state mean slider velocity `v_inf` (m/s).
    VInf,
    /// Start-up time `T p_0.99` (s).
    StartupTime,
    /// Steady-state smoothness `zeta` (16).
    Smoothness,
    /// Steady-state durability `delta` (18) (1/N).
    Durability,
    /// Steady-state friction energy per period `W_f` (19) (J).
    FrictionEnergy,
    /// Time stuck / simulated time.
    StictionFraction,
    /// `v_inf / S` with the apparent power `S` (35) (m/(s VA)).
    VelocityPerPower,
}

/// A name that is not an [`Indicator`].
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown indicator \"{name}\"; valid names: {valid}", valid = Indicator::valid_names())]
pub struct UnknownIndicator {
    /// The name given.
    pub name: String,
}

impl Indicator {
    /// Every indicator, in the order of `docs/interface.md`.
    pub const ALL: [Indicator; 7] = [
        Indicator::VInf,
        Indicator::StartupTime,
        Indicator::Smoothness,
        Indicator::Durability,
        Indicator::FrictionEnergy,
        Indicator::StictionFraction,
        Indicator::VelocityPerPower,
    ];

    /// The name in scene files, JSON keys, sweep columns and figure labels.
    pub fn name(self) -> &'static str {
        match self {
            Indicator::VInf => "v_inf",
            Indicator::StartupTime => "startup_time",
            Indicator::Smoothness => "smoothness",
            Indicator::Durability => "durability",
            Indicator::FrictionEnergy => "friction_energy",
            Indicator::StictionFraction => "stiction_fraction",
            Indicator::VelocityPerPower => "velocity_per_power",
        }
    }

    /// The indicator's entry in the table of symbols (`src/symbol.rs`):
    /// its symbol in figures, its unit and description.
    pub fn symbol(self) -> &'static Symbol {
        symbol(self.name()).expect("every indicator is in the table of symbols")
    }

    /// The SI unit (`1` for a ratio): sweep columns and axis labels, from
    /// the table of symbols.
    pub fn unit(self) -> &'static str {
        self.symbol().unit
    }

    /// The unit as the text summary and `check` print it: `friction_energy`
    /// is energy per steady-state period.
    pub fn printed_unit(self) -> &'static str {
        match self {
            Indicator::FrictionEnergy => "J (per period)",
            other => other.unit(),
        }
    }

    /// What the indicator means, with the equation it comes from.
    pub fn meaning(self) -> &'static str {
        match self {
            Indicator::VInf => "steady-state mean slider velocity",
            Indicator::StartupTime => {
                "start-up time T p_0.99: the first period whose mean velocity reaches 99 % of v_inf"
            }
            Indicator::Smoothness => {
                "steady-state smoothness zeta (16): mean velocity over the slider velocity's range in the period, |v_p| / (max v_S - min v_S)"
            }
            Indicator::Durability => {
                "steady-state durability delta (18): distance moved per friction work"
            }
            Indicator::FrictionEnergy => {
                "friction energy W_f (19) dissipated in one steady-state period"
            }
            Indicator::StictionFraction => "time stuck over the simulated start-up time",
            Indicator::VelocityPerPower => "v_inf over the apparent power S (35)",
        }
    }

    /// All names, comma separated.
    pub fn valid_names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// Why this indicator cannot be computed for the given signal and
    /// actuator, with or without a spring against the slider, or `None` if
    /// it can.
    pub fn unavailable_because(
        self,
        signal: &SignalSpec,
        actuator: Option<&ActuatorParams>,
        spring: bool,
    ) -> Option<&'static str> {
        if spring && self.assumes_travel() {
            return Some(
                "assumes net travel: against a spring ([spring]) the slider oscillates about \
                 its equilibrium; the run reports the spring's force instead",
            );
        }
        if self != Indicator::VelocityPerPower {
            return None;
        }
        if actuator.is_none() {
            Some("velocity_per_power needs an [actuator] table")
        } else if matches!(signal, SignalSpec::Ideal(_)) {
            Some(
                "velocity_per_power is undefined for kind = \"ideal\": the ideal \
                 signal has infinitely many harmonics, so its input power (35) is not finite",
            )
        } else {
            None
        }
    }

    /// The indicators a scene with this signal and actuator, with or
    /// without a spring, can compute, in the order of [`Indicator::ALL`].
    pub fn available(
        signal: &SignalSpec,
        actuator: Option<&ActuatorParams>,
        spring: bool,
    ) -> Vec<Indicator> {
        Self::ALL
            .into_iter()
            .filter(|i| i.unavailable_because(signal, actuator, spring).is_none())
            .collect()
    }

    /// The indicators that assume the slider travels on (a mean velocity):
    /// `v_inf`, the start-up time, the smoothness, the durability and the
    /// velocity per power. Against a spring they have no meaning.
    pub fn assumes_travel(self) -> bool {
        matches!(
            self,
            Indicator::VInf
                | Indicator::StartupTime
                | Indicator::Smoothness
                | Indicator::Durability
                | Indicator::VelocityPerPower
        )
    }
}

impl fmt::Display for Indicator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Indicator {
    type Err = UnknownIndicator;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|i| i.name() == s)
            .ok_or_else(|| UnknownIndicator { name: s.to_owned() })
    }
}
