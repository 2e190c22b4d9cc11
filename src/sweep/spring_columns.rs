//! The columns of a spring's reading (docs/model.md section 17), written
//! by a sweep whose base scene has a `[spring]` and by no other: the keys
//! of `run --json`, one column each, the range of a single period's mean
//! force as two, and each figure's error estimate (`error_estimate` of
//! `run --json`) as `error_` and the figure's name, as `error_v_inf` is
//! `v_inf`'s.
//!
//! Contract: a case's reading is its steady orbit's
//! ([`crate::simulation::RunReport::spring`]) or, where no orbit locked,
//! the one over the periods after the start-up
//! ([`crate::simulation::Unsettled::spring`]); every cell is empty where
//! the reading, or the figure, does not exist (no reading, `orbit_periods`
//! where no orbit locked, the range where one did, an error estimate
//! where no orbit locked or no bound holds), never `NaN`.

use super::table::Cell;
use crate::simulation::{Outcome, SpringReading};

/// One figure of the spring's reading.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum SpringColumn {
    /// `spring_force_mean` (N): the time mean of `F_spring`.
    ForceMean,
    /// `spring_force_max` (N).
    ForceMax,
    /// `spring_force_min` (N).
    ForceMin,
    /// `spring_position_mean` (m): the time mean of `x_S`.
    PositionMean,
    /// `contact_fraction`: the time in contact over the time read.
    ContactFraction,
    /// `orbit_periods`: the orbit's period in drive periods; empty where
    /// no orbit locked.
    OrbitPeriods,
    /// `spring_reading_periods`: the periods the reading covers.
    ReadingPeriods,
    /// `spring_force_mean_range_low` (N): where no orbit locked, the least
    /// mean force of a single period.
    MeanRangeLow,
    /// `spring_force_mean_range_high` (N): where no orbit locked, the
    /// largest mean force of a single period.
    MeanRangeHigh,
    /// `error_spring_force_mean` (N): the estimated absolute error of
    /// `spring_force_mean`.
    ErrorForceMean,
    /// `error_spring_force_max` (N).
    ErrorForceMax,
    /// `error_spring_force_min` (N).
    ErrorForceMin,
    /// `error_spring_position_mean` (m).
    ErrorPositionMean,
    /// `error_contact_fraction`.
    ErrorContactFraction,
}

impl SpringColumn {
    /// Every column, in output order.
    pub(super) const ALL: [SpringColumn; 14] = [
        SpringColumn::ForceMean,
        SpringColumn::ForceMax,
        SpringColumn::ForceMin,
        SpringColumn::PositionMean,
        SpringColumn::ContactFraction,
        SpringColumn::OrbitPeriods,
        SpringColumn::ReadingPeriods,
        SpringColumn::MeanRangeLow,
        SpringColumn::MeanRangeHigh,
        SpringColumn::ErrorForceMean,
        SpringColumn::ErrorForceMax,
        SpringColumn::ErrorForceMin,
        SpringColumn::ErrorPositionMean,
        SpringColumn::ErrorContactFraction,
    ];

    /// The column's name.
    pub(super) fn name(self) -> &'static str {
        match self {
            SpringColumn::ForceMean => "spring_force_mean",
            SpringColumn::ForceMax => "spring_force_max",
            SpringColumn::ForceMin => "spring_force_min",
            SpringColumn::PositionMean => "spring_position_mean",
            SpringColumn::ContactFraction => "contact_fraction",
            SpringColumn::OrbitPeriods => "orbit_periods",
            SpringColumn::ReadingPeriods => "spring_reading_periods",
            SpringColumn::MeanRangeLow => "spring_force_mean_range_low",
            SpringColumn::MeanRangeHigh => "spring_force_mean_range_high",
            SpringColumn::ErrorForceMean => "error_spring_force_mean",
            SpringColumn::ErrorForceMax => "error_spring_force_max",
            SpringColumn::ErrorForceMin => "error_spring_force_min",
            SpringColumn::ErrorPositionMean => "error_spring_position_mean",
            SpringColumn::ErrorContactFraction => "error_contact_fraction",
        }
    }

    /// Position in [`SpringColumn::ALL`].
    pub(super) fn position(self) -> usize {
        Self::ALL.iter().position(|c| *c == self).unwrap_or(0)
    }

    /// True for the columns of whole numbers (periods).
    pub(super) fn counts(self) -> bool {
        matches!(
            self,
            SpringColumn::OrbitPeriods | SpringColumn::ReadingPeriods
        )
    }

    /// The cell of this column for an outcome.
    pub(super) fn cell(self, outcome: &Outcome) -> Cell {
        let reading: Option<SpringReading> = outcome
            .report()
            .and_then(|r| r.spring)
            .or_else(|| outcome.unsettled().and_then(|u| u.spring));
        let Some(r) = reading else {
            return Cell::Empty;
        };
        let p = &r.profile;
        let number = |x: f64| Cell::number(Some(x));
        let error = |i: usize| Cell::number(r.error.map(|e| e.figures()[i].total()));
        match self {
            SpringColumn::ForceMean => number(p.force_mean),
            SpringColumn::ForceMax => number(p.force_max),
            SpringColumn::ForceMin => number(p.force_min),
            SpringColumn::PositionMean => number(p.position_mean),
            SpringColumn::ContactFraction => number(p.contact_fraction),
            SpringColumn::OrbitPeriods if r.orbit_periods > 0 => Cell::Unsigned(r.orbit_periods),
            SpringColumn::OrbitPeriods => Cell::Empty,
            SpringColumn::ReadingPeriods => Cell::Unsigned(r.periods),
            SpringColumn::MeanRangeLow => Cell::number(r.mean_range.map(|[lo, _]| lo)),
            SpringColumn::MeanRangeHigh => Cell::number(r.mean_range.map(|[_, hi]| hi)),
            SpringColumn::ErrorForceMean => error(0),
            SpringColumn::ErrorForceMax => error(1),
            SpringColumn::ErrorForceMin => error(2),
            SpringColumn::ErrorPositionMean => error(3),
            SpringColumn::ErrorContactFraction => error(4),
        }
    }
}
