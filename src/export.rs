//! What a user needs to check our results elsewhere (the rod signal itself
//! is described by `crate::signal::description`):
//!
//! * the exact trajectory at given times and the per-period series of the
//!   start-up, as CSV or JSON lines (`trajectory_table`,
//!   `periods_table`); [`exact_tables`] gives both as CSV text to
//!   callers of the library (the Python package).

use crate::compare::exact::{ExactState, PeriodRecord, event_name};
use crate::error::Num;
use serde_json::{Value, json};
use std::fmt::Write as _;

/// Most samples a trajectory export may have (`--times` or
/// `--sample-rate`): the exact states and the table are built in memory,
/// about 500 bytes a sample, before the file is written atomically; longer
/// spans are exported in several runs (`--periods`).
const MAX_SAMPLES: u64 = 2_000_000;

/// Output format of a table, from the file name: `.jsonl`/`.json` gives
/// JSON lines, anything else CSV.
pub(crate) fn is_json_lines(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("jsonl") || e.eq_ignore_ascii_case("json"))
}

fn table(columns: &[&str], rows: Vec<Vec<Value>>, json_lines: bool) -> String {
    let mut s = String::new();
    if json_lines {
        for row in rows {
            let object: serde_json::Map<String, Value> =
                columns.iter().map(|c| (*c).to_owned()).zip(row).collect();
            let _ = writeln!(s, "{}", Value::Object(object));
        }
    } else {
        let _ = writeln!(s, "{}", columns.join(","));
        for row in rows {
            let cells: Vec<String> = row
                .iter()
                .map(|v| match v {
                    Value::String(text) => text.clone(),
                    Value::Null => String::new(),
                    other => other.to_string(),
                })
                .collect();
            let _ = writeln!(s, "{}", cells.join(","));
        }
    }
    s
}

/// Columns of the trajectory table.
pub(crate) const TRAJECTORY_COLUMNS: [&str; 7] = ["t", "x_R", "v_R", "a_R", "x_S", "v_S", "mode"];

/// The exact states as a CSV or JSON-lines table.
pub(crate) fn trajectory_table(states: &[ExactState], json_lines: bool) -> String {
    let rows = states
        .iter()
        .map(|s| {
            vec![
                json!(s.t),
                json!(s.x_r),
                json!(s.v_r),
                json!(s.a_r),
                json!(s.x_s),
                json!(s.v_s),
                json!(s.mode.name()),
            ]
        })
        .collect();
    table(&TRAJECTORY_COLUMNS, rows, json_lines)
}

/// Columns of the per-period table.
pub(crate) const PERIOD_COLUMNS: [&str; 7] = [
    "p",
    "v_p",
    "x_p",
    "stick_time",
    "events",
    "event_kinds",
    "x_S_end",
];

/// The per-period series as a CSV or JSON-lines table: `events` counts the
/// period's events, `event_kinds` lists their kinds separated by `;`.
pub(crate) fn periods_table(periods: &[PeriodRecord], json_lines: bool) -> String {
    let rows = periods
        .iter()
        .map(|r| {
            let kinds: Vec<&str> = r.events.iter().map(|e| event_name(&e.kind)).collect();
            vec![
                json!(r.period),
                json!(r.v_p),
                json!(r.step),
                json!(r.stick_time),
                json!(r.events.len()),
                json!(kinds.join(";")),
                json!(r.x_start + r.step),
            ]
        })
        .collect();
    table(&PERIOD_COLUMNS, rows, json_lines)
}

/// What `run --trajectory` / `--periods-series` asks for.
#[cfg(feature = "cli")]
#[derive(Debug, Clone, Default)]
pub(crate) struct TrajectoryRequest {
    /// Write the states here.
    pub trajectory: Option<std::path::PathBuf>,
    /// Sample times (s), one a line or a CSV column `t`.
    pub times: Option<std::path::PathBuf>,
    /// Or a sample rate (Hz) over `periods`.
    pub sample_rate: Option<f64>,
    /// Periods `A..=B` for `sample_rate`.
    pub periods: Option<(u64, u64)>,
    /// Write the per-period series of the start-up here.
    pub periods_series: Option<std::path::PathBuf>,
}

#[cfg(feature = "cli")]
impl TrajectoryRequest {
    /// True if anything is asked for.
    pub(crate) fn any(&self) -> bool {
        self.trajectory.is_some() || self.periods_series.is_some()
    }
}

/// Writes what `request` asks for, for `scene`; the per-period series
/// covers the start-up to `p_0.99` (or the last sampled period, if later).
#[cfg(feature = "cli")]
pub(crate) fn write_requested(
    scene: &crate::scene::Scene,
    request: &TrajectoryRequest,
) -> Result<(), String> {
    let period = crate::simulation::build(scene)
        .map_err(|e| e.to_string())?
        .0
        .period();
    let times: Vec<f64> = match (&request.trajectory, &request.times, request.sample_rate) {
        (None, _, _) => Vec::new(),
        (Some(_), Some(path), None) => {
            let options = crate::compare::read::ReadOptions::default();
            crate::compare::read::read_times(path, &options).map_err(|e| e.to_string())?
        }
        (Some(_), None, Some(rate)) => {
            if !(rate > 0.0 && rate.is_finite()) {
                return Err(format!(
                    "--sample-rate = {}: must be a positive number",
                    Num(rate)
                ));
            }
            let (a, b) = request.periods.unwrap_or((1, 1));
            let (t0, t1) = ((a - 1) as f64 * period, b as f64 * period);
            // Compared as a float: a count beyond u64 must not wrap.
            let samples = ((t1 - t0) * rate).floor();
            if samples.is_nan() || samples > MAX_SAMPLES as f64 {
                return Err(format!(
                    "--sample-rate = {}: {} samples over periods {a}..{b} is too many (at most {MAX_SAMPLES})",
                    Num(rate),
                    Num(samples)
                ));
            }
            let n = samples as u64;
            (0..=n)
                .map(|i| t0 + i as f64 / rate)
                .filter(|t| *t <= t1)
                .collect()
        }
        (Some(_), Some(_), Some(_)) => {
            return Err("give either --times or --sample-rate, not both".to_owned());
        }
        (Some(_), None, None) => {
            return Err("--trajectory needs --times FILE or --sample-rate HZ".to_owned());
        }
    };
    let (trajectory, periods) = exact_series(scene, &times, request.periods_series.is_some())?;
    if let Some(path) = &request.trajectory {
        let text = trajectory_table(&trajectory.states, is_json_lines(path));
        crate::output::write_atomically(path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    if let Some(path) = &request.periods_series {
        let text = periods_table(&periods, is_json_lines(path));
        crate::output::write_atomically(path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}

/// The exact trajectory of `scene` at `times` (s, increasing) and, with
/// `periods_series`, the per-period series of the start-up to `p_0.99`
/// (or the last sampled period, if later), as the CSV tables that
/// `stickslip run --trajectory` and `--periods-series` write (columns
/// `t, x_R, v_R, a_R, x_S, v_S, mode` and `p, v_p, x_p, stick_time,
/// events, event_kinds, x_S_end`), numbers with the
/// shortest digits that read back to the same `f64`. Errors are the
/// command line's one-line messages (too many samples, a time after the
/// simulated span, a scene that cannot be built).
pub fn exact_tables(
    scene: &crate::scene::Scene,
    times: &[f64],
    periods_series: bool,
) -> Result<ExactTables, String> {
    let (trajectory, periods) = exact_series(scene, times, periods_series)?;
    Ok(ExactTables {
        trajectory: trajectory_table(&trajectory.states, false),
        periods: periods_series.then(|| periods_table(&periods, false)),
    })
}

/// The CSV tables of [`exact_tables`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExactTables {
    /// The trajectory at the times asked for (`run --trajectory`).
    pub trajectory: String,
    /// The per-period series, when asked for (`run --periods-series`).
    pub periods: Option<String>,
}

/// The exact states at `times` and the per-period records asked for
/// ([`exact_tables`]).
fn exact_series(
    scene: &crate::scene::Scene,
    times: &[f64],
    periods_series: bool,
) -> Result<(crate::compare::exact::ExactSeries, Vec<PeriodRecord>), String> {
    use crate::compare::exact;
    let (signal, motor) = crate::simulation::build_prescribed(scene, "the trajectory export")
        .map_err(|e| e.to_string())?;
    let period = signal.period();
    if times.len() as u64 > MAX_SAMPLES {
        return Err(format!(
            "--times: {} samples, more than the {MAX_SAMPLES} one export may have; split the file",
            times.len()
        ));
    }
    let max = scene.run.max_periods;
    if let Some(&last) = times.last()
        && last > max as f64 * period
    {
        return Err(format!(
            "time {} s is after the simulated span of run.max_periods = {max} periods",
            Num(last)
        ));
    }
    let startup = if periods_series {
        let mut exact_scene = scene.clone();
        exact_scene.run.engine = crate::scene::EngineKind::Event;
        // p_0.99 needs the start-up, which a run simulates only when asked.
        let startup = crate::indicator::Indicator::StartupTime;
        if !exact_scene.outputs.indicators.contains(&startup) {
            exact_scene.outputs.indicators.push(startup);
        }
        crate::simulation::steady(&exact_scene)
            .map_err(|e| e.to_string())?
            .startup_periods
            .unwrap_or(1)
    } else {
        0
    };
    let mut series = exact::evaluate(&signal, &motor, times, startup).map_err(|e| e.to_string())?;
    let periods = std::mem::take(&mut series.periods);
    Ok((series, periods))
}
