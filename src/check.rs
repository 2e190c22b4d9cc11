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
//!
//! # A spring against the slider
//!
//! With `[spring]` (docs/model.md section 17) both engines carry the
//! spring: the event engine's run is the one `stickslip run` makes (the
//! exact engine with the spring, its start-up of `N` periods from rest
//! and its steady orbit of `k` periods), the reference is the fixed-step
//! engine with the spring; for a driven rod both are the driven rod's
//! engines with the spring, and where the exact engine takes no spring
//! with the rod, a one-line error names `spring`. The table gains the spring's figures (`spring_force_mean`,
//! `spring_force_max`, `spring_force_min`, `spring_position_mean`,
//! `contact_fraction`) as rows after the indicators.
//!
//! The reference's own motion from rest is not compared with the orbit:
//! in slip-slip its period map is neutral (docs/model.md section 12), so
//! its start-up locks into no orbit, and the slider's own oscillation on
//! the spring, which the exact map damps through the event times, goes on
//! within a band of width `O(h)` for ever (`run` with `engine = "fixed"`
//! runs it to `run.max_periods`). Each reference run is instead bounded
//! and read over the periods the event engine's figures describe:
//!
//! 1. **Start-up**: from rest over the event engine's start-up, periods
//!    `1..=N'` (`N'` = [`RunReport::startup_span`]): the start-up's
//!    `stiction_fraction` and its events.
//! 2. **Orbit**: the event engine's motion from rest is run on to the
//!    first of `N`, `2N`, `4N`, ... periods (at most `run.max_periods`)
//!    after which it reads its orbit's spring figures within [`SETTLED`]
//!    of the orbit's largest `|F_spring|` (its contact fraction within
//!    [`SETTLED`]): evidence that the orbit is the limit of the motion
//!    from rest, stated in the output, also where it is missing. From the
//!    event engine's boundary state there (slider position and velocity,
//!    mode, a driven rod's state), the reference runs the orbit's `k`
//!    periods and reads the spring over them
//!    (`src/engine/fixed_step/spring_reading.rs`: the scheme's own spring
//!    impulse and nodes); the first of
//!    them stands for a steady period (`friction_energy`,
//!    `stiction_fraction_steady`).
//!
//! Both engines thus describe the same `k` periods from the same state,
//! and the differences are the reference's errors over them: first order,
//! scattering with where the events fall on the grid as every figure of
//! the reference does. A reference run costs `N' + k` periods.
//! ([`SpringWindow`] holds the periods, [`SpringCheck`] the runs.)

mod spring;

pub use spring::{SETTLED, SpringCheck, SpringRun, SpringWindow};

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
    /// [`CheckReport::reference`] (with a spring, of
    /// [`SpringCheck::reference`]).
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
    /// The reference's runs, from coarse to fine; empty with a spring
    /// (they are in [`CheckReport::spring`]).
    pub reference: Vec<EngineRun>,
    /// Indicators the scene asked for, where both engines give a finite
    /// value; with a spring, then the spring's figures.
    pub rows: Vec<IndicatorRow>,
    /// With a spring against the slider: the reference's runs and the
    /// periods they read over (module docs).
    pub spring: Option<SpringCheck>,
}

/// One figure of a run, as a row of the table shows it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Figure {
    /// Name as in the JSON output.
    name: &'static str,
    /// SI unit (`1` for a fraction).
    unit: &'static str,
    value: f64,
    /// The error estimate, where the engine states one.
    error: Option<f64>,
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
    if let Some(spring) = scene.spring {
        return spring::check(scene, (&signal, &motor), rod.as_ref(), spring, &steps);
    }
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
    let fixed: Vec<(u32, Vec<Figure>)> = reference
        .iter()
        .map(|r| {
            let s = r.steps_per_harmonic.unwrap_or(0);
            (s, indicator_figures(&r.report))
        })
        .collect();
    let rows = rows(&indicator_figures(&event.report), &fixed);
    Ok(CheckReport {
        event,
        reference,
        rows,
        spring: None,
    })
}

/// Every requested indicator, with the definitions and units of
/// `stickslip run` ([`RunReport::value`], [`Indicator::printed_unit`]);
/// `stiction_fraction` is followed by `stiction_fraction_steady`, the
/// steady period's.
fn indicator_figures(r: &RunReport) -> Vec<Figure> {
    let mut out = Vec::new();
    for indicator in &r.requested {
        if let Some(value) = r.value(*indicator) {
            out.push(Figure {
                name: indicator.name(),
                unit: indicator.printed_unit(),
                value,
                error: r.error(*indicator),
            });
        }
        if *indicator == Indicator::StictionFraction {
            out.push(Figure {
                name: "stiction_fraction_steady",
                unit: "1",
                value: r.indicators.stiction_fraction,
                error: None,
            });
        }
    }
    out
}

/// A row for every finite figure of the event engine that every
/// reference run, given as `(steps per harmonic, figures)` from coarse to
/// fine, has with a finite value.
fn rows(event: &[Figure], reference: &[(u32, Vec<Figure>)]) -> Vec<IndicatorRow> {
    let mut rows = Vec::new();
    for figure in event {
        let (name, value) = (figure.name, figure.value);
        if !value.is_finite() {
            continue;
        }
        let mut values = Vec::with_capacity(reference.len());
        let mut previous: Option<(f64, f64)> = None;
        for (steps, list) in reference {
            let Some(v) = list.iter().find(|f| f.name == name).map(|f| f.value) else {
                break;
            };
            let s = f64::from(*steps);
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
                .map(|((s, _), v)| (f64::from(*s), v.difference))
                .collect();
            rows.push(IndicatorRow {
                name,
                unit: figure.unit,
                event: value,
                event_error: figure.error,
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

/// A run's line in the text: label, steps per period, periods, wall time
/// and the events of the start-up.
struct RunLine {
    label: String,
    steps_per_period: Option<u64>,
    periods: u64,
    wall_time: Duration,
    events: EventCounts,
}

impl CheckReport {
    /// Every run's line, the event engine's first.
    fn run_lines(&self) -> Vec<RunLine> {
        let label = |s: Option<u32>| s.map_or("event".to_owned(), |s| format!("fixed {s}"));
        let line = |r: &EngineRun| RunLine {
            label: label(r.steps_per_harmonic),
            steps_per_period: r.steps_per_period,
            periods: r.report.work.periods,
            wall_time: r.wall_time,
            events: r.report.events(),
        };
        let mut lines: Vec<RunLine> = std::iter::once(&self.event)
            .chain(&self.reference)
            .map(line)
            .collect();
        if let Some(spring) = &self.spring {
            lines.extend(spring.reference.iter().map(|r| RunLine {
                label: label(Some(r.steps_per_harmonic)),
                steps_per_period: Some(r.steps_per_period),
                periods: r.periods,
                wall_time: r.wall_time,
                events: r.startup_events,
            }));
        }
        lines
    }

    /// The table as text: the runs (resolution, work, wall time), with a
    /// spring what the reference read over, then one block per indicator
    /// and, with a spring, per figure of the spring.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
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
        let lines = self.run_lines();
        let base = self.event.wall_time.as_secs_f64();
        for run in &lines {
            let per_period = run
                .steps_per_period
                .map_or("-".to_owned(), |n| n.to_string());
            let ratio = run.wall_time.as_secs_f64() / base;
            let _ = writeln!(
                out,
                "{:<12} {:>14} {:>9} {:>12} {:>9.1}  {}",
                run.label,
                per_period,
                run.periods,
                seconds(run.wall_time),
                ratio,
                events_text(&run.events),
            );
        }
        if let Some(spring) = &self.spring {
            window_text(&mut out, &spring.window);
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
            for (run, v) in lines[1..].iter().zip(&row.reference) {
                let relative = if row.event != 0.0 {
                    format!("{:>12.2e}", v.difference / row.event.abs())
                } else {
                    format!("{:>12}", "-")
                };
                let order = v.order.map_or("-".to_owned(), |o| format!("{o:.2}"));
                let _ = writeln!(
                    out,
                    "  {:<12} {:>22.15e} {:>12.2e} {relative} {order:>7}",
                    run.label, v.value, v.difference,
                );
            }
        }
        out
    }
}

/// What the reference against a spring read over, in words.
fn window_text(out: &mut String, w: &SpringWindow) {
    let (reads, within) = if w.settled {
        ("reads", format!("after {} periods", w.settle))
    } else {
        (
            "does not read",
            format!("within the {} periods of run.max_periods", w.settle),
        )
    };
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "spring: start-up figures over periods 1..{} from rest (the event engine's start-up); the\n\
         event engine's motion from rest {reads} its orbit's spring figures to {SETTLED:.0e} of the largest\n\
         force {within}; each reference reads the spring over the orbit's {}\n\
         from the event engine's state there, and a steady period's indicators over the first",
        w.startup,
        crate::plural::count(w.read, "period", "periods"),
    );
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

    #[test]
    fn a_spring_on_an_ideal_signal_is_refused_in_one_line_naming_the_spring() {
        // The exact engine takes a spring on a continuous signal only
        // (docs/model.md section 17): an ideal signal's jumps would strike it.
        let motor = Motor::new(crate::motor::MotorParams::default()).expect("the paper's motor");
        let spec = crate::signal::SignalSpec::ideal(25e-6, 36.0, 1.0);
        let signal = crate::signal::Signal::build(&spec, &motor).expect("an ideal signal");
        let spring = crate::spring::Spring {
            stiffness: 1e4,
            damping: 0.0,
            end: crate::spring::SpringEnd::Tied { preload: 0.0 },
        };
        let e = simulation::spring_engine(&signal, &motor, None, spring, EventOptions::default())
            .expect_err("refused")
            .to_string();
        assert!(e.starts_with("spring"), "{e}");
        assert!(!e.contains('\n'), "{e}");
    }
}
