//! What a bench measures: the stiffness range, its points and the kinds
//! of spring; the stiffnesses are log spaced,
//! `k_i = k_from 10^(log10(k_to / k_from) i / (N - 1))`, `i = 0..N`, the ends
//! exactly as given.

use super::BenchError;
use crate::error::Num;

/// Lowest stiffness by default (N/m).
pub const DEFAULT_FROM: f64 = 10.0;
/// Highest stiffness by default (N/m).
pub const DEFAULT_TO: f64 = 1e7;
/// Stiffnesses by default.
pub const DEFAULT_POINTS: usize = 50;
/// Most stiffnesses a bench takes.
pub const MAX_POINTS: usize = 10_000;
/// Periods from rest within which an orbit must lock, by default: the
/// slowest orbits of the paper's motor settle in about 5000 periods
/// (`tests/data/spring_reference.md`); a stiff free end that the slider
/// keeps bouncing off is read over the periods after these.
pub const DEFAULT_MAX_PERIODS: u64 = 20_000;

/// Which springs a bench puts against the slider.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpringKinds {
    /// Only the spring tied to the slider.
    Tied,
    /// Only the free-ended spring.
    Free,
    /// Both, at every stiffness.
    Both,
}

impl SpringKinds {
    /// True if the tied spring is measured.
    pub fn tied(self) -> bool {
        self != SpringKinds::Free
    }

    /// True if the free-ended spring is measured.
    pub fn free(self) -> bool {
        self != SpringKinds::Tied
    }

    /// The name in outputs: `tied`, `free` or `both`.
    pub fn name(self) -> &'static str {
        match self {
            SpringKinds::Tied => "tied",
            SpringKinds::Free => "free",
            SpringKinds::Both => "both",
        }
    }
}

/// How to run a bench.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchOptions {
    /// Lowest stiffness (N/m).
    pub from: f64,
    /// Highest stiffness (N/m).
    pub to: f64,
    /// Number of stiffnesses, log spaced from `from` to `to`.
    pub points: usize,
    /// Which springs.
    pub kinds: SpringKinds,
    /// Periods from rest within which an orbit must lock (each case's
    /// `run.max_periods`).
    pub max_periods: u64,
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions {
            from: DEFAULT_FROM,
            to: DEFAULT_TO,
            points: DEFAULT_POINTS,
            kinds: SpringKinds::Both,
            max_periods: DEFAULT_MAX_PERIODS,
        }
    }
}

impl BenchOptions {
    /// Checks the options; an error names the command-line flag and the
    /// value.
    pub fn validate(&self) -> Result<(), BenchError> {
        let bad = |flag, value: String, requirement: &str| BenchError::Option {
            flag,
            value,
            requirement: requirement.to_owned(),
        };
        for (flag, k) in [("--from", self.from), ("--to", self.to)] {
            if !(k.is_finite() && k > 0.0) {
                return Err(bad(
                    flag,
                    Num(k).to_string(),
                    "must be a positive, finite stiffness in N/m",
                ));
            }
        }
        if !(1..=MAX_POINTS).contains(&self.points) {
            return Err(bad(
                "--points",
                self.points.to_string(),
                &format!("must be from 1 to {MAX_POINTS}"),
            ));
        }
        if self.points > 1 && self.to <= self.from {
            return Err(bad(
                "--to",
                Num(self.to).to_string(),
                &format!(
                    "must be above --from {} when --points is above 1",
                    Num(self.from)
                ),
            ));
        }
        if self.max_periods == 0 {
            return Err(bad("--max-periods", "0".to_owned(), "must be at least 1"));
        }
        Ok(())
    }

    /// The stiffnesses (N/m), log spaced (module docs), in increasing
    /// order; one point is `from`.
    pub fn stiffnesses(&self) -> Vec<f64> {
        let n = self.points;
        if n <= 1 {
            return vec![self.from];
        }
        let decades = (self.to / self.from).log10();
        (0..n)
            .map(|i| match i {
                0 => self.from,
                i if i == n - 1 => self.to,
                i => self.from * 10f64.powf(decades * i as f64 / (n - 1) as f64),
            })
            .collect()
    }
}
