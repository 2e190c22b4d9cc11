//! Turning a [`RunReport`] into text or JSON.
//!
//! The text summary prints each value with as many significant digits as
//! its error estimate supports (never more than 15), followed by the
//! estimate, so every printed digit is meant. The JSON object uses the keys
//! fixed in `docs/interface.md`; values that do not exist (an infinite
//! smoothness when the slider velocity is constant, a start-up that was not
//! reached) are `null`, never NaN.

use crate::engine::EventCounts;
use crate::scene::Indicator;
use crate::simulation::RunReport;
use serde_json::{Map, Value, json};
use std::fmt::Write as _;

/// `value` rounded to the digits its absolute error `err` supports (15
/// significant digits without an estimate), then `± err`; an error of 0
/// prints as `(exact)`. Moderate magnitudes print in plain decimal notation.
pub fn format_with_error(value: f64, err: Option<f64>) -> String {
    if !value.is_finite() {
        return "none".to_owned();
    }
    let digits = match err {
        Some(e) if e > 0.0 && value != 0.0 => {
            let d = (value.abs() / e).log10().floor() as i32 + 1;
            d.clamp(1, 15)
        }
        _ => 15,
    };
    let magnitude = if value == 0.0 {
        0
    } else {
        value.abs().log10().floor() as i32
    };
    let text = if value == 0.0 {
        "0".to_owned()
    } else if (-4..6).contains(&magnitude) {
        let decimals = (digits - 1 - magnitude).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{:.*e}", (digits - 1) as usize, value)
    };
    match err {
        Some(e) if e > 0.0 => format!("{text} ± {e:.1e}"),
        Some(_) => format!("{text} (exact)"),
        None => text,
    }
}

fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

fn option_number(x: Option<f64>) -> Value {
    x.map_or(Value::Null, number)
}

fn events_json(e: &EventCounts) -> Value {
    json!({
        "stick_to_slip": e.stick_to_slip,
        "slip_to_stick": e.slip_to_stick,
        "reversal": e.reversal,
        "grazing": e.grazing,
        "jump": e.jump,
    })
}

/// The run as one JSON object with the keys of `docs/interface.md`.
pub fn to_json(r: &RunReport) -> Value {
    let mut m = Map::new();
    let ind = &r.indicators;
    let mut err = Map::new();
    for indicator in &r.requested {
        let (value, error) = match indicator {
            Indicator::VInf => (number(ind.v_inf), r.error.v_inf),
            Indicator::StartupTime => {
                m.insert(
                    "startup_periods".into(),
                    r.startup_periods.map_or(Value::Null, |p| json!(p)),
                );
                (option_number(r.startup_time()), r.error.startup_time)
            }
            Indicator::Smoothness => (number(ind.smoothness), r.error.smoothness),
            Indicator::Durability => (number(ind.durability), r.error.durability),
            Indicator::FrictionEnergy => (number(ind.friction_energy), r.error.friction_energy),
            Indicator::StictionFraction => {
                m.insert(
                    "stiction_fraction_steady".into(),
                    number(ind.stiction_fraction),
                );
                (
                    option_number(r.stiction_fraction_transient),
                    r.error.stiction_fraction,
                )
            }
            Indicator::VelocityPerPower => {
                if let Some(p) = &r.power {
                    m.insert("apparent_power".into(), number(p.apparent_power));
                    m.insert("voltage_rms".into(), number(p.u_rms));
                    m.insert("current_rms".into(), number(p.i_rms));
                }
                (
                    option_number(r.velocity_per_power()),
                    r.error.velocity_per_power,
                )
            }
        };
        m.insert(indicator.name().into(), value);
        err.insert(indicator.name().into(), option_number(error));
    }
    m.insert("regime".into(), json!(r.regime().name()));
    if let Some(t) = r.transient.as_ref().filter(|t| t.converged) {
        // The cross-check of run.verify_steady_state: the start-up's own
        // limit beside the period map's.
        m.insert("v_inf_transient".into(), number(t.v_inf()));
    }
    m.insert("period".into(), number(r.period));
    m.insert("f0".into(), number(1.0 / r.period));
    m.insert("f_max".into(), option_number(r.f_max));
    m.insert(
        "periods_simulated".into(),
        json!(r.transient.as_ref().map_or(0, |t| t.periods())),
    );
    m.insert("events".into(), events_json(&r.events()));
    m.insert(
        "events_per_steady_period".into(),
        events_json(&r.steady.stats.events),
    );
    m.insert("wall_time_s".into(), number(r.wall_time.as_secs_f64()));
    m.insert("error_estimate".into(), Value::Object(err));
    m.insert(
        "work".into(),
        json!({
            "periods": r.work.periods,
            "events": r.work.events.total(),
            "evaluations": r.work.evaluations,
            "root_iterations": r.work.root_iterations,
            "fixed_point_iterations": r.steady.iterations,
        }),
    );
    if let Some(log) = &r.event_log {
        let events: Vec<Value> = log
            .iter()
            .map(|e| {
                json!({
                    "period": e.period,
                    "phase": e.phase,
                    "time": (e.period - 1) as f64 * r.period + e.phase,
                    "kind": format!("{:?}", e.kind),
                })
            })
            .collect();
        m.insert("event_log".into(), Value::Array(events));
        m.insert("event_log_omitted".into(), json!(r.event_log_omitted));
    }
    if let Some(segments) = &r.trajectory {
        let rows: Vec<Value> = segments
            .iter()
            .map(|s| {
                json!({
                    "start": s.start, "end": s.end, "mode": s.mode.name(),
                    "slider_x": [s.slider_start.x, s.slider_end.x],
                    "slider_v": [s.slider_start.v, s.slider_end.v],
                    "rod_x": [s.rod_start.x, s.rod_end.x],
                    "rod_v": [s.rod_start.v, s.rod_end.v],
                })
            })
            .collect();
        m.insert("trajectory".into(), Value::Array(rows));
    }
    Value::Object(m)
}

/// An indicator with its estimate; without one (no bound holds, e.g. a
/// grazing steady orbit) it says so instead of implying exact digits.
fn with_estimate(value: f64, err: Option<f64>) -> String {
    match err {
        Some(_) => format_with_error(value, err),
        None if value.is_finite() => format!("{} ± unknown", format_with_error(value, None)),
        None => format_with_error(value, None),
    }
}

/// A readable summary.
pub fn to_text(r: &RunReport) -> String {
    let mut out = String::new();
    let ind = &r.indicators;
    let e = &r.error;
    let line = |out: &mut String, name: &str, value: String, unit: &str| {
        let _ = writeln!(out, "  {name:<22} {value} {unit}");
    };
    let _ = writeln!(
        out,
        "signal: T = {} s, f0 = {} Hz{}",
        format_with_error(r.period, None),
        format_with_error(1.0 / r.period, None),
        r.f_max
            .map(|f| format!(", f_max = {} Hz", format_with_error(f, None)))
            .unwrap_or_default()
    );
    let _ = writeln!(out, "steady state: {}", r.regime().name());
    let _ = writeln!(out, "indicators (± estimated absolute error):");
    for indicator in &r.requested {
        match indicator {
            Indicator::VInf => line(&mut out, "v_inf", with_estimate(ind.v_inf, e.v_inf), "m/s"),
            Indicator::StartupTime => match (r.startup_time(), r.startup_periods) {
                (Some(t), Some(p)) => line(
                    &mut out,
                    "startup_time",
                    format!(
                        "{} s = {p} period{}",
                        with_estimate(t, e.startup_time),
                        if p == 1 { "" } else { "s" }
                    ),
                    "",
                ),
                _ => line(&mut out, "startup_time", "not reached".into(), ""),
            },
            Indicator::Smoothness => line(
                &mut out,
                "smoothness",
                with_estimate(ind.smoothness, e.smoothness),
                "",
            ),
            Indicator::Durability => line(
                &mut out,
                "durability",
                with_estimate(ind.durability, e.durability),
                "1/N",
            ),
            Indicator::FrictionEnergy => line(
                &mut out,
                "friction_energy",
                with_estimate(ind.friction_energy, e.friction_energy),
                "J/period",
            ),
            Indicator::StictionFraction => {
                line(
                    &mut out,
                    "stiction_fraction",
                    with_estimate(
                        r.stiction_fraction_transient.unwrap_or(f64::NAN),
                        e.stiction_fraction,
                    ),
                    "(of the simulated start-up)",
                );
                line(
                    &mut out,
                    "  in steady state",
                    with_estimate(ind.stiction_fraction, e.stiction_fraction),
                    "(of a period)",
                );
            }
            Indicator::VelocityPerPower => {
                if let Some(p) = &r.power {
                    line(
                        &mut out,
                        "apparent_power",
                        format_with_error(p.apparent_power, None),
                        "VA",
                    );
                }
                line(
                    &mut out,
                    "velocity_per_power",
                    with_estimate(
                        r.velocity_per_power().unwrap_or(f64::NAN),
                        e.velocity_per_power,
                    ),
                    "m/(s VA)",
                );
            }
        }
    }
    let ev = r.events();
    let _ = writeln!(
        out,
        "events over {} periods from rest: {} stick->slip, {} slip->stick, {} reversal, {} grazing, {} jump",
        r.transient.as_ref().map_or(0, |t| t.periods()),
        ev.stick_to_slip,
        ev.slip_to_stick,
        ev.reversal,
        ev.grazing,
        ev.jump
    );
    let _ = writeln!(
        out,
        "work: {} periods, {} events, {} root iterations; wall time {:.3} ms",
        r.work.periods,
        r.work.events.total(),
        r.work.root_iterations,
        r.wall_time.as_secs_f64() * 1e3
    );
    out
}
