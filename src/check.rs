//! Cross-check: one scene through the exact event engine and through the
//! fixed-step reference (`crate::engine::fixed_step`) at several
//! resolutions, indicator by indicator (`stickslip check SCENE --steps
//! 50,500,5000,50000`).
//!
//! For every indicator the scene asks for, the table holds the event
//! engine's value (with its error estimate) and, per resolution, the
//! reference's value, its difference to the event engine and the observed
//! convergence order between neighbouring resolutions,
//!
//! ```text
//! order_k = log(|d_k| / |d_{k+1}|) / log(s_{k+1} / s_k),
//! ```
//!
//! with `d_k` the difference to the event engine at `s_k` steps per period
//! of the highest harmonic. The reference is first order, but its error
//! constant depends on where the events fall on the grid, so single orders
//! scatter around 1 (see the module documentation of the reference); the
//! trend is the least-squares slope of `-log |d|` against `log s` over all
//! resolutions with a non-zero difference (at least three). A difference
//! of exactly zero (a start-up period count that agrees) has no order. Every run's wall time covers the engine's set-up and the whole
//! analysis, measured in this process.

use crate::actuator::RodModel;
use crate::engine::DrivenEngine;
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::fixed_step::{FixedStepEngine, FixedStepOptions};
use crate::engine::{EventCounts, PeriodEngine};
use crate::error::{Error, ParamError};
use crate::indicator::Indicator;
use crate::motor::Motor;
use crate::scene::Scene;
use crate::simulation::{self, RunReport};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

/// The resolutions `stickslip check` uses when none are given (steps per
/// period of the highest harmonic; the paper used 5000).
pub(crate) const DEFAULT_STEPS: [u32; 4] = [50, 500, 5000, 50000];

/// One run of the scene.
#[derive(Debug, Clone)]
pub struct EngineRun {
    /// `None` for the event engine, else steps per period of the highest
    /// harmonic of the fixed-step reference.
    pub steps_per_harmonic: Option<u32>,
    /// Steps per signal period (fixed-step reference only).
    pub steps_per_period: Option<u64>,
    /// Everything the run produced.
    pub report: RunReport,
    /// Wall time of engine set-up and analysis.
    pub wall_time: Duration,
}

/// One indicator of the reference at one resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceValue {
    /// The reference's value.
    pub value: f64,
    /// `value - event value`.
    pub difference: f64,
    /// Observed order from the previous (coarser) resolution to this one;
    /// `None` for the first resolution or when a difference is zero or not
    /// finite.
    pub order: Option<f64>,
}

/// One indicator across all runs.
#[derive(Debug, Clone, PartialEq)]
pub struct IndicatorRow {
    /// Name as in the JSON output (`v_inf`, `startup_time`, ...).
    pub name: &'static str,
    /// SI unit.
    pub unit: &'static str,
    /// The event engine's value.
    pub event: f64,
    /// The event engine's error estimate.
    pub event_error: Option<f64>,
    /// The reference at each resolution, in the order of
    /// [`CheckReport::reference`].
    pub reference: Vec<ReferenceValue>,
    /// Least-squares order over all resolutions with a non-zero difference,
    /// when there are at least three.
    pub fitted_order: Option<f64>,
}

/// The whole cross-check.
#[derive(Debug, Clone)]
pub struct CheckReport {
    /// The event engine's run.
    pub event: EngineRun,
    /// The reference's runs, from coarse to fine.
    pub reference: Vec<EngineRun>,
    /// Indicators the scene asked for, where both engines give a finite value.
    pub rows: Vec<IndicatorRow>,
}

/// The observed order between two differences at step counts `s_coarse`
/// and `s_fine`; `None` if a difference is zero or not finite.
pub(crate) fn observed_order(
    d_coarse: f64,
    d_fine: f64,
    s_coarse: f64,
    s_fine: f64,
) -> Option<f64> {
    let (a, b) = (d_coarse.abs(), d_fine.abs());
    let usable = |x: f64| x.is_finite() && x > 0.0;
    (usable(a) && usable(b) && s_fine != s_coarse).then(|| (a / b).ln() / (s_fine / s_coarse).ln())
}

/// The least-squares slope of `-log |d|` against `log s` over the pairs
/// `(s, d)` with a finite non-zero `d`; `None` with fewer than three.
pub(crate) fn fitted_order(points: &[(f64, f64)]) -> Option<f64> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|(s, d)| d.is_finite() && *d != 0.0 && *s > 0.0)
        .map(|(s, d)| (s.ln(), -d.abs().ln()))
        .collect();
    if xy.len() < 3 {
        return None;
    }
    let n = xy.len() as f64;
    let mx = xy.iter().map(|p| p.0).sum::<f64>() / n;
    let my = xy.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Checks a list of resolutions: not empty, every value at least 1.
/// Returns them sorted from coarse to fine, without repeats.
pub(crate) fn validate_steps(steps: &[u32]) -> Result<Vec<u32>, ParamError> {
    if steps.is_empty() {
        return Err(ParamError::Inconsistent {
            field: "steps".to_owned(),
            reason: "give at least one resolution (steps per period of the highest harmonic)"
                .to_owned(),
        });
    }
    if let Some(zero) = steps.iter().find(|s| **s == 0) {
        return Err(ParamError::out_of_range(
            "steps",
            f64::from(*zero),
            "every resolution must be at least 1 step per period of the highest harmonic",
        ));
    }
    let mut sorted = steps.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    Ok(sorted)
}

fn timed<E: PeriodEngine>(
    make: impl FnOnce() -> E,
    scene: &Scene,
    motor: &Motor,
) -> Result<(RunReport, Duration), Error> {
    let clock = Instant::now();
    let engine = make();
    let setup = clock.elapsed();
    let mut report = simulation::run_with(engine, scene, motor)?;
    report.setup_time = setup;
    report.wall_time = clock.elapsed();
    let wall_time = report.wall_time;
    Ok((report, wall_time))
}

/// Runs `scene` with the event engine and with the fixed-step reference at
/// each of `steps` (steps per period of the highest harmonic), whatever
/// engine the scene names.
pub fn check(scene: &Scene, steps: &[u32]) -> Result<CheckReport, Error> {
    let steps = validate_steps(steps)?;
    let (signal, motor) = simulation::build(scene)?;
    let rod = match &scene.rod {
        RodModel::Driven(spec) => Some(simulation::driven_rod(scene, spec, &signal, &motor)?),
        RodModel::Prescribed => None,
    };
    let (report, wall_time) = match &rod {
        Some(rod) => {
            let options = EventOptions::default();
            timed(
                || {
                    DrivenEngine::new(
                        &signal,
                        rod,
                        &motor,
                        options.velocity_tolerance,
                        options.max_events_per_period,
                    )
                },
                scene,
                &motor,
            )?
        }
        None => timed(
            || EventEngine::new(&signal, &motor, EventOptions::default()),
            scene,
            &motor,
        )?,
    };
    let event = EngineRun {
        steps_per_harmonic: None,
        steps_per_period: None,
        report,
        wall_time,
    };
    let mut reference = Vec::with_capacity(steps.len());
    for s in steps {
        let options = FixedStepOptions {
            steps_per_harmonic: s,
            ..FixedStepOptions::default()
        };
        let per_period = FixedStepEngine::steps_for(&signal, s);
        let (report, wall_time) = match &rod {
            Some(rod) => timed(
                || FixedStepEngine::driven(&signal, &motor, rod, options),
                scene,
                &motor,
            )?,
            None => timed(
                || FixedStepEngine::new(&signal, &motor, options),
                scene,
                &motor,
            )?,
        };
        reference.push(EngineRun {
            steps_per_harmonic: Some(s),
            steps_per_period: Some(per_period),
            report,
            wall_time,
        });
    }
    let rows = rows(&event, &reference);
    Ok(CheckReport {
        event,
        reference,
        rows,
    })
}

/// `(name, unit, value, error estimate)` of every requested indicator,
/// with the definitions and units of `stickslip run`
/// ([`RunReport::value`], [`Indicator::printed_unit`]); `stiction_fraction` is
/// followed by `stiction_fraction_steady`, the steady period's.
fn indicator_values(r: &RunReport) -> Vec<(&'static str, &'static str, f64, Option<f64>)> {
    let mut out = Vec::new();
    for indicator in &r.requested {
        if let Some(value) = r.value(*indicator) {
            out.push((
                indicator.name(),
                indicator.printed_unit(),
                value,
                r.error(*indicator),
            ));
        }
        if *indicator == Indicator::StictionFraction {
            out.push((
                "stiction_fraction_steady",
                "1",
                r.indicators.stiction_fraction,
                None,
            ));
        }
    }
    out
}

fn rows(event: &EngineRun, reference: &[EngineRun]) -> Vec<IndicatorRow> {
    let fixed: Vec<_> = reference
        .iter()
        .map(|r| indicator_values(&r.report))
        .collect();
    let mut rows = Vec::new();
    for (name, unit, value, error) in indicator_values(&event.report) {
        if !value.is_finite() {
            continue;
        }
        let mut values = Vec::with_capacity(reference.len());
        let mut previous: Option<(f64, f64)> = None;
        for (run, list) in reference.iter().zip(&fixed) {
            let Some(&(_, _, v, _)) = list.iter().find(|(n, ..)| *n == name) else {
                break;
            };
            let s = f64::from(run.steps_per_harmonic.unwrap_or(0));
            let difference = v - value;
            let order = previous.and_then(|(d, s0)| observed_order(d, difference, s0, s));
            previous = Some((difference, s));
            values.push(ReferenceValue {
                value: v,
                difference,
                order,
            });
        }
        if values.len() == reference.len() && values.iter().all(|v| v.value.is_finite()) {
            let pairs: Vec<(f64, f64)> = reference
                .iter()
                .zip(&values)
                .map(|(r, v)| (f64::from(r.steps_per_harmonic.unwrap_or(0)), v.difference))
                .collect();
            rows.push(IndicatorRow {
                name,
                unit,
                event: value,
                event_error: error,
                fitted_order: fitted_order(&pairs),
                reference: values,
            });
        }
    }
    rows
}

fn events_text(e: &EventCounts) -> String {
    format!(
        "{} stick->slip, {} slip->stick, {} reversal, {} grazing, {} jump",
        e.stick_to_slip, e.slip_to_stick, e.reversal, e.grazing, e.jump
    )
}

fn seconds(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s < 1e-3 {
        format!("{:.1} us", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{s:.3} s")
    }
}

impl CheckReport {
    /// The table as text: the runs (resolution, work, wall time), then one
    /// block per indicator.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let label = |r: &EngineRun| match r.steps_per_harmonic {
            None => "event".to_owned(),
            Some(s) => format!("fixed {s}"),
        };
        let _ = writeln!(
            out,
            "cross-check: event engine against the fixed-step reference (Moreau-Jean, first order)"
        );
        let _ = writeln!(
            out,
            "fixed N = N steps per period of the highest harmonic; the paper used 5000"
        );
        let _ = writeln!(
            out,
            "orders between neighbouring resolutions scatter around 1 (the error constant depends\n\
             on where events fall on the grid); the trend is a least-squares fit over all of them"
        );
        let _ = writeln!(out);
        let _ = writeln!(
            out,
            "{:<12} {:>14} {:>9} {:>12} {:>9}  events of the start-up",
            "run", "steps/period", "periods", "wall time", "/ event"
        );
        let base = self.event.wall_time.as_secs_f64();
        for run in std::iter::once(&self.event).chain(&self.reference) {
            let per_period = run
                .steps_per_period
                .map_or("-".to_owned(), |n| n.to_string());
            let ratio = run.wall_time.as_secs_f64() / base;
            let _ = writeln!(
                out,
                "{:<12} {:>14} {:>9} {:>12} {:>9.1}  {}",
                label(run),
                per_period,
                run.report.work.periods,
                seconds(run.wall_time),
                ratio,
                events_text(&run.report.events()),
            );
        }
        for row in &self.rows {
            let _ = writeln!(out);
            let trend = row.fitted_order.map_or(String::new(), |o| {
                format!(", order over all resolutions {o:.2}")
            });
            let _ = writeln!(out, "{} ({}){trend}", row.name, row.unit);
            let _ = writeln!(
                out,
                "  {:<12} {:>22} {:>12} {:>12} {:>7}",
                "run", "value", "value-event", "relative", "order"
            );
            let error = row
                .event_error
                .map_or(String::new(), |e| format!(" ± {e:.1e}"));
            let _ = writeln!(out, "  {:<12} {:>22.15e}{error}", "event", row.event);
            for (run, v) in self.reference.iter().zip(&row.reference) {
                let relative = if row.event != 0.0 {
                    format!("{:>12.2e}", v.difference / row.event.abs())
                } else {
                    format!("{:>12}", "-")
                };
                let order = v.order.map_or("-".to_owned(), |o| format!("{o:.2}"));
                let _ = writeln!(
                    out,
                    "  {:<12} {:>22.15e} {:>12.2e} {relative} {order:>7}",
                    label(run),
                    v.value,
                    v.difference,
                );
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_trend_of_an_exact_first_order_sequence_is_one() {
        // Differences 1e-2, -5e-3, 2.5e-3 to a limit: halving each time the
        // step doubles (first order); a zero difference carries no order.
        let order = fitted_order(&[(10.0, 1e-2), (20.0, -5e-3), (40.0, 2.5e-3), (80.0, 0.0)]);
        assert!((order.expect("three usable points") - 1.0).abs() < 1e-12);
        assert!(fitted_order(&[(10.0, 1e-2), (20.0, 0.0), (40.0, 2.5e-3)]).is_none());
        assert!(validate_steps(&[]).is_err());
        assert!(validate_steps(&[50, 0]).is_err());
    }
}
