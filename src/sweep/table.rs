//! Output files: the header line, the columns, rendering a case's row, and
//! reading a file back strictly (every cell must be one a sweep could have
//! written), for resuming and merging.

use super::grid::{AxisKey, AxisValue, Case, MAX_CASES, Sweep, SweepAxis, SweepFormat};
use super::spring_columns::SpringColumn;
use crate::error::Error;
use crate::indicator::Indicator;
use crate::motor::Motor;
use crate::provenance::{VERSION, scene_hash};
use crate::simulation::Outcome;

/// The first line of an output file: the program that wrote it, the
/// fingerprint of the sweep's base scene and the number of cases of the
/// whole sweep (absent in files of earlier versions).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Meta {
    pub version: String,
    pub base_scene_hash: String,
    pub cases: Option<u64>,
}

impl Meta {
    /// The header this program writes for `sweep`.
    pub(super) fn of(sweep: &Sweep) -> Meta {
        Meta {
            version: VERSION.to_owned(),
            base_scene_hash: scene_hash(sweep.base()),
            cases: Some(sweep.len() as u64),
        }
    }

    pub(super) fn line(&self, format: SweepFormat) -> String {
        match format {
            SweepFormat::Csv => {
                let mut line = format!(
                    "# stickslip_version = {}, base_scene_hash = {}",
                    self.version, self.base_scene_hash
                );
                if let Some(n) = self.cases {
                    line.push_str(&format!(", cases = {n}"));
                }
                line
            }
            SweepFormat::Jsonl => {
                let mut map = serde_json::Map::new();
                map.insert("stickslip_version".into(), self.version.clone().into());
                map.insert(
                    "base_scene_hash".into(),
                    self.base_scene_hash.clone().into(),
                );
                if let Some(n) = self.cases {
                    map.insert("cases".into(), n.into());
                }
                serde_json::Value::Object(map).to_string()
            }
        }
    }

    pub(super) fn parse_csv(line: &str) -> Option<Meta> {
        let rest = line.strip_prefix("# ")?;
        let mut version = None;
        let mut base = None;
        let mut cases = None;
        for item in rest.split(", ") {
            match item.split_once(" = ")? {
                ("stickslip_version", v) => version = Some(v.to_owned()),
                ("base_scene_hash", h) => base = Some(h.to_owned()),
                ("cases", n) => cases = Some(n.parse().ok()?),
                _ => return None,
            }
        }
        Some(Meta {
            version: version?,
            base_scene_hash: base?,
            cases,
        })
    }

    pub(super) fn parse_json(map: &serde_json::Map<String, serde_json::Value>) -> Option<Meta> {
        let cases = match map.get("cases") {
            Some(n) => Some(n.as_u64()?),
            None => None,
        };
        if map.len() != 2 + usize::from(cases.is_some()) {
            return None;
        }
        Some(Meta {
            version: map.get("stickslip_version")?.as_str()?.to_owned(),
            base_scene_hash: map.get("base_scene_hash")?.as_str()?.to_owned(),
            cases,
        })
    }
}

/// The columns `sweep` writes, in order (see the module docs of
/// [`crate::sweep`]).
pub(super) fn column_kinds(sweep: &Sweep, timing: bool) -> Vec<Column> {
    let mut columns = vec![Column::Case];
    columns.extend(sweep.axes().iter().map(|(a, _)| Column::Axis(*a)));
    columns.extend([Column::SceneHash, Column::Regime]);
    for indicator in Indicator::ALL {
        if sweep.base().outputs.indicators.contains(&indicator) {
            columns.push(Column::Indicator(indicator));
            match indicator {
                Indicator::StictionFraction => columns.push(Column::StictionSteady),
                Indicator::VelocityPerPower => columns.push(Column::ApparentPower),
                _ => {}
            }
        }
    }
    if sweep.base().spring.is_some() {
        columns.extend(SpringColumn::ALL.map(Column::Spring));
    }
    columns.extend([
        Column::F0,
        Column::Period,
        Column::StartupPeriods,
        Column::PeriodsSimulated,
        Column::EventsTotal,
        Column::LastVp,
    ]);
    if timing {
        columns.extend([Column::WallTime, Column::SetupTime, Column::SimulationTime]);
    }
    columns.extend([Column::ErrorVInf, Column::Failure]);
    columns
}

/// One cell of an output row.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Cell {
    Empty,
    Number(f64),
    Integer(i64),
    Unsigned(u64),
    Bool(bool),
    Text(String),
}

impl Cell {
    pub(super) fn number(x: Option<f64>) -> Cell {
        match x {
            Some(x) if x.is_finite() => Cell::Number(x),
            _ => Cell::Empty,
        }
    }

    fn axis(value: AxisValue) -> Cell {
        match value {
            AxisValue::Number(x) => Cell::Number(x),
            AxisValue::Integer(n) => Cell::Integer(n),
            AxisValue::Bool(b) => Cell::Bool(b),
        }
    }

    /// The exact key of an axis cell, `None` for other cells.
    pub(super) fn axis_key(&self) -> Option<AxisKey> {
        match self {
            Cell::Number(x) => Some(AxisValue::Number(*x).key()),
            Cell::Integer(n) => Some(AxisValue::Integer(*n).key()),
            Cell::Bool(b) => Some(AxisValue::Bool(*b).key()),
            _ => None,
        }
    }

    pub(super) fn csv(&self) -> String {
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

    pub(super) fn json(&self) -> serde_json::Value {
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
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Column {
    Case,
    Axis(SweepAxis),
    SceneHash,
    Indicator(Indicator),
    StictionSteady,
    ApparentPower,
    Spring(SpringColumn),
    F0,
    Period,
    StartupPeriods,
    PeriodsSimulated,
    EventsTotal,
    WallTime,
    ErrorVInf,
    Failure,
    Regime,
    LastVp,
    SetupTime,
    SimulationTime,
}

impl Column {
    pub(super) fn name(self) -> &'static str {
        match self {
            Column::Case => "case",
            Column::Axis(a) => a.name(),
            Column::SceneHash => "scene_hash",
            Column::Indicator(i) => i.name(),
            Column::StictionSteady => "stiction_fraction_steady",
            Column::ApparentPower => "apparent_power",
            Column::Spring(s) => s.name(),
            Column::F0 => "f0",
            Column::Period => "period",
            Column::StartupPeriods => "startup_periods",
            Column::PeriodsSimulated => "periods_simulated",
            Column::EventsTotal => "events_total",
            Column::WallTime => "wall_time_s",
            Column::ErrorVInf => "error_v_inf",
            Column::Failure => "failure",
            Column::Regime => "regime",
            Column::LastVp => "last_v_p",
            Column::SetupTime => "setup_time_s",
            Column::SimulationTime => "simulation_time_s",
        }
    }

    pub(super) fn from_name(name: &str) -> Option<Column> {
        const FIXED: [Column; 15] = [
            Column::F0,
            Column::Case,
            Column::Regime,
            Column::LastVp,
            Column::SetupTime,
            Column::SimulationTime,
            Column::SceneHash,
            Column::StictionSteady,
            Column::ApparentPower,
            Column::Period,
            Column::StartupPeriods,
            Column::PeriodsSimulated,
            Column::EventsTotal,
            Column::WallTime,
            Column::ErrorVInf,
        ];
        FIXED
            .into_iter()
            .chain([Column::Failure])
            .chain(SweepAxis::ALL.map(Column::Axis))
            .chain(Indicator::ALL.map(Column::Indicator))
            .chain(SpringColumn::ALL.map(Column::Spring))
            .find(|c| c.name() == name)
    }

    /// The position in the column order of [`column_kinds`]: JSON objects
    /// do not keep the order of their keys, so it is restored from this.
    pub(super) fn rank(self) -> usize {
        let indicator = |i: Indicator| Indicator::ALL.iter().position(|x| *x == i).unwrap_or(0);
        match self {
            Column::Case => 0,
            Column::Axis(a) => 1 + SweepAxis::ALL.iter().position(|x| *x == a).unwrap_or(0),
            Column::SceneHash => 20,
            Column::Regime => 21,
            Column::Indicator(i) => 30 + 2 * indicator(i),
            Column::StictionSteady => 31 + 2 * indicator(Indicator::StictionFraction),
            Column::ApparentPower => 31 + 2 * indicator(Indicator::VelocityPerPower),
            Column::Spring(s) => 50 + s.position(),
            Column::F0 => 70,
            Column::Period => 71,
            Column::StartupPeriods => 72,
            Column::PeriodsSimulated => 73,
            Column::EventsTotal => 74,
            Column::LastVp => 75,
            Column::WallTime => 76,
            Column::SetupTime => 77,
            Column::SimulationTime => 78,
            Column::ErrorVInf => 79,
            Column::Failure => 80,
        }
    }

    /// The cell of this column for `case` and its outcome. Every physical
    /// outcome is a row with its `regime`; indicators that do not exist
    /// (no steady state) are empty. Only an error fills `failure`, and its
    /// row has nothing else but the case's own columns.
    pub(super) fn cell(self, case: &Case, result: &Result<Outcome, Error>) -> Cell {
        match self {
            Column::Case => return Cell::Unsigned(case.index as u64),
            Column::Axis(a) => return case.value(a).map_or(Cell::Empty, Cell::axis),
            Column::SceneHash => return Cell::Text(scene_hash(&case.scene)),
            // The drive frequency is the case's own, run or not.
            Column::F0 => {
                let f0 = Motor::new(case.scene.motor).map(|m| case.scene.signal.f0(&m));
                return Cell::number(f0.ok());
            }
            Column::Failure => {
                return match result {
                    Ok(_) => Cell::Empty,
                    Err(e) => Cell::Text(e.to_string().replace(['\n', '\r'], " ")),
                };
            }
            _ => {}
        }
        let Ok(outcome) = result else {
            return Cell::Empty;
        };
        let report = outcome.report();
        let unsettled = outcome.unsettled();
        let times = outcome.times();
        match self {
            Column::Regime => Cell::Text(outcome.regime().to_owned()),
            Column::Indicator(indicator) => Cell::number(outcome.value(indicator)),
            Column::StictionSteady => Cell::number(report.map(|r| r.indicators.stiction_fraction)),
            Column::ApparentPower => {
                Cell::number(report.and_then(|r| r.power.as_ref().map(|p| p.apparent_power)))
            }
            Column::Spring(s) => s.cell(outcome),
            Column::Period => Cell::number(
                report
                    .map(|r| r.period)
                    .or_else(|| unsettled.map(|u| u.period)),
            ),
            Column::StartupPeriods => report
                .and_then(|r| r.startup_periods)
                .map_or(Cell::Empty, Cell::Unsigned),
            Column::PeriodsSimulated => Cell::Unsigned(outcome.periods_simulated()),
            Column::EventsTotal => {
                report.map_or(Cell::Empty, |r| Cell::Unsigned(r.events().total()))
            }
            Column::LastVp => Cell::number(unsettled.and_then(|u| u.last_v_p)),
            Column::WallTime => Cell::number(Some(times.wall.as_secs_f64())),
            Column::SetupTime => Cell::number(Some(times.setup.as_secs_f64())),
            Column::SimulationTime => Cell::number(Some(times.simulation.as_secs_f64())),
            // v_inf does not apply against a spring, nor its error.
            Column::ErrorVInf => Cell::number(
                report
                    .filter(|_| case.scene.spring.is_none())
                    .and_then(|r| r.error.v_inf),
            ),
            Column::Case | Column::Axis(_) | Column::SceneHash | Column::F0 | Column::Failure => {
                unreachable!("handled above")
            }
        }
    }

    /// What a cell of this column may hold, for error messages.
    fn expects(self) -> String {
        match self {
            Column::Case => {
                return format!("a case index below {MAX_CASES} (the most cases a sweep has)");
            }
            Column::StartupPeriods | Column::PeriodsSimulated | Column::EventsTotal => {
                "a whole number or nothing"
            }
            Column::Spring(s) if s.counts() => "a whole number or nothing",
            Column::SceneHash => "16 hexadecimal digits",
            Column::Failure => "text or nothing",
            Column::Regime => {
                return format!("one of {} or nothing", Outcome::REGIMES.join(", "));
            }
            Column::Axis(SweepAxis::Harmonics) => "an integer",
            Column::Axis(SweepAxis::Sigma) => "true or false",
            Column::Axis(_) => "a number",
            _ => "a finite number or nothing",
        }
        .to_owned()
    }

    /// A cell read back: it must be one this column can hold (a finite
    /// number, an axis value its axis accepts, ...).
    fn check(self, cell: Cell) -> Result<Cell, String> {
        let ok = match (self, &cell) {
            (Column::Case, Cell::Unsigned(case)) => *case < MAX_CASES as u64,
            // Empty in the row of a case that failed.
            (
                Column::StartupPeriods | Column::PeriodsSimulated | Column::EventsTotal,
                Cell::Unsigned(_) | Cell::Empty,
            ) => true,
            (Column::Spring(s), Cell::Unsigned(_) | Cell::Empty) if s.counts() => true,
            (Column::Spring(s), _) if s.counts() => false,
            (Column::SceneHash, Cell::Text(s)) => {
                s.len() == 16 && s.bytes().all(|b| b.is_ascii_hexdigit())
            }
            (Column::Failure, Cell::Text(_) | Cell::Empty) => true,
            (Column::Regime, Cell::Text(name)) => Outcome::REGIMES.contains(&name.as_str()),
            (Column::Regime, Cell::Empty) => true,
            (Column::Axis(axis), cell) => match (axis, cell) {
                (SweepAxis::Harmonics, Cell::Integer(n)) => axis.accepts(AxisValue::Integer(*n)),
                (SweepAxis::Sigma, Cell::Bool(_)) => true,
                (SweepAxis::Harmonics | SweepAxis::Sigma, _) => false,
                (_, Cell::Number(x)) => axis.accepts(AxisValue::Number(*x)),
                _ => false,
            },
            (
                Column::Indicator(_)
                | Column::StictionSteady
                | Column::ApparentPower
                | Column::F0
                | Column::Period
                | Column::LastVp
                | Column::WallTime
                | Column::SetupTime
                | Column::SimulationTime
                | Column::ErrorVInf
                | Column::Spring(_),
                Cell::Number(x),
            ) => x.is_finite(),
            (
                Column::Indicator(_)
                | Column::StictionSteady
                | Column::ApparentPower
                | Column::F0
                | Column::Period
                | Column::LastVp
                | Column::WallTime
                | Column::SetupTime
                | Column::SimulationTime
                | Column::ErrorVInf
                | Column::Spring(_),
                Cell::Empty,
            ) => true,
            _ => false,
        };
        if ok {
            Ok(cell)
        } else {
            Err(format!("must be {}", self.expects()))
        }
    }

    /// Reads a CSV field of this column.
    pub(super) fn parse_csv(self, text: &str) -> Result<Cell, String> {
        let cell = if text.is_empty() {
            Cell::Empty
        } else {
            match self {
                Column::Case
                | Column::StartupPeriods
                | Column::PeriodsSimulated
                | Column::EventsTotal => {
                    text.parse().map_or(Cell::Text(text.into()), Cell::Unsigned)
                }
                Column::Spring(s) if s.counts() => {
                    text.parse().map_or(Cell::Text(text.into()), Cell::Unsigned)
                }
                Column::Axis(SweepAxis::Harmonics) => {
                    text.parse().map_or(Cell::Text(text.into()), Cell::Integer)
                }
                Column::Axis(SweepAxis::Sigma) => {
                    text.parse().map_or(Cell::Text(text.into()), Cell::Bool)
                }
                Column::SceneHash | Column::Failure | Column::Regime => Cell::Text(text.into()),
                _ => text.parse().map_or(Cell::Text(text.into()), Cell::Number),
            }
        };
        self.check(cell)
    }

    /// Reads a JSON value of this column.
    pub(super) fn parse_json(self, value: &serde_json::Value) -> Result<Cell, String> {
        use serde_json::Value;
        let cell = match (self, value) {
            (_, Value::Null) => Cell::Empty,
            (_, Value::Bool(b)) => Cell::Bool(*b),
            (_, Value::String(s)) => Cell::Text(s.clone()),
            (
                Column::Case
                | Column::StartupPeriods
                | Column::PeriodsSimulated
                | Column::EventsTotal,
                Value::Number(n),
            ) => n.as_u64().map_or(Cell::Empty, Cell::Unsigned),
            (Column::Spring(s), Value::Number(n)) if s.counts() => {
                n.as_u64().map_or(Cell::Empty, Cell::Unsigned)
            }
            (Column::Axis(SweepAxis::Harmonics), Value::Number(n)) => {
                n.as_i64().map_or(Cell::Empty, Cell::Integer)
            }
            (_, Value::Number(n)) => n.as_f64().map_or(Cell::Empty, Cell::Number),
            _ => Cell::Text(value.to_string()),
        };
        // A number that did not fit its column's type reads as nothing,
        // which the check refuses where a value is required.
        if matches!(value, Value::Number(_)) && cell == Cell::Empty {
            return Err(format!("must be {}", self.expects()));
        }
        self.check(cell)
    }
}

/// How the columns `found` differ from `wanted`.
pub(super) fn column_difference(found: &[Column], wanted: &[Column]) -> String {
    let names = |a: &[Column], b: &[Column]| {
        a.iter()
            .filter(|c| !b.contains(c))
            .map(|c| c.name())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let (extra, missing) = (names(found, wanted), names(wanted, found));
    match (extra.is_empty(), missing.is_empty()) {
        (true, true) => "the same columns in another order".to_owned(),
        (false, true) => format!("the extra columns {extra}"),
        (true, false) => format!("no columns {missing}"),
        (false, false) => format!("the extra columns {extra} and no columns {missing}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    /// JSON lines restore the column order from the ranks: every column,
    /// the spring's and their errors among them, has its own, and the
    /// order of a sweep's columns is the ranks' order.
    #[test]
    fn every_column_has_its_own_rank() {
        let columns: Vec<Column> = [
            Column::Case,
            Column::SceneHash,
            Column::Regime,
            Column::StictionSteady,
            Column::ApparentPower,
            Column::F0,
            Column::Period,
            Column::StartupPeriods,
            Column::PeriodsSimulated,
            Column::EventsTotal,
            Column::LastVp,
            Column::WallTime,
            Column::SetupTime,
            Column::SimulationTime,
            Column::ErrorVInf,
            Column::Failure,
        ]
        .into_iter()
        .chain(SweepAxis::ALL.map(Column::Axis))
        .chain(Indicator::ALL.map(Column::Indicator))
        .chain(SpringColumn::ALL.map(Column::Spring))
        .collect();
        let ranks: BTreeSet<usize> = columns.iter().map(|c| c.rank()).collect();
        assert_eq!(ranks.len(), columns.len());
        let spring: Vec<usize> = SpringColumn::ALL.map(|s| Column::Spring(s).rank()).to_vec();
        assert!(spring.windows(2).all(|w| w[0] < w[1]), "{spring:?}");
        assert!(spring[spring.len() - 1] < Column::F0.rank());
    }
}
