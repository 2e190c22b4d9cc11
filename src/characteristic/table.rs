//! A characteristic as text, JSON or CSV (keys and columns in
//! `docs/interface.md`, "stickslip characteristic").
//!
//! Contract: every value is in SI units (angles in degrees); a value that
//! does not exist is `null` in JSON and an empty cell in CSV, never NaN.
//! The text prints each value with the digits its error estimate supports
//! ([`crate::report::format_with_error`]). The JSON carries the program
//! version and the resolved scene with its fingerprint, like `run --json`;
//! the CSV's first line says the same as a comment.

use super::datasheet::Datasheet;
use super::domain::Limit;
use super::{Characteristic, LoadAxis};
use crate::provenance;
use crate::report::{format_with_error, rounded};
use crate::scene::Scene;
use crate::scene::SceneFile;
use serde_json::{Value, json};
use std::fmt::Write as _;

/// The sign convention, as every output states it.
pub(crate) const SIGN_CONVENTION: &str =
    "the load force F opposes forward motion: g_t = -F / m_s (F > 0 pushes back, F < 0 assists)";

/// `x` in JSON: `null` where it is not finite.
pub(crate) fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// [`number`] of a value that may be absent.
pub(crate) fn option(x: Option<f64>) -> Value {
    x.map_or(Value::Null, number)
}

/// `a / b`, if finite.
pub(crate) fn ratio(a: f64, b: f64) -> Option<f64> {
    (b != 0.0).then(|| a / b).filter(|r| r.is_finite())
}

fn limit_json(limit: Option<&Limit>) -> Value {
    limit.map_or(Value::Null, |l| {
        json!({
            "load": number(l.load()),
            "first_unsteady_load": number(l.first_unsteady.load),
            "regime": l.first_unsteady.regime,
        })
    })
}

/// The datasheet block: each entry `{value, unit}`.
pub(crate) fn datasheet_json(d: &Datasheet) -> Value {
    let mut m = serde_json::Map::new();
    for e in d.entries() {
        m.insert(
            e.key.into(),
            json!({"value": option(e.value), "unit": e.unit}),
        );
    }
    Value::Object(m)
}

/// The characteristic of `scene` as one JSON object.
pub(crate) fn to_json(c: &Characteristic, scene: &Scene) -> Value {
    let s = &c.stall;
    let points: Vec<Value> = c
        .points
        .iter()
        .map(|p| {
            let e = &p.evaluation;
            json!({
                "load": number(e.load),
                "angle": if c.axis == LoadAxis::Incline { number(p.x) } else { Value::Null },
                "extra_acceleration": number(e.extra_acceleration),
                "regime": e.regime,
                "v_inf": option(e.v_inf),
                "v_inf_error": option(e.error),
                "output_power": option(e.output_power()),
                "slope": option(p.slope.value),
                "slope_left": option(p.slope.left),
                "slope_right": option(p.slope.right),
                "slope_method": p.slope.method.name(),
                "marks": p.marks.iter().map(|m| m.name()).collect::<Vec<_>>(),
            })
        })
        .collect();
    let stall_force = s.force;
    json!({
        "stickslip_version": provenance::VERSION,
        "scene_hash": provenance::scene_hash(scene),
        "scene": serde_json::to_value(SceneFile::from(scene)).unwrap_or(Value::Null),
        "load_axis": c.axis.name(),
        "sign_convention": SIGN_CONVENTION,
        "range": [number(c.range.0), number(c.range.1)],
        "range_unit": c.axis.unit(),
        "slider_mass": number(c.slider_mass),
        "replaced_extra_acceleration": number(c.replaced_extra_acceleration),
        "drive_direction": c.drive_direction(),
        "no_load_speed": option(c.no_load.v_inf),
        "no_load_speed_error": option(c.no_load.error),
        "stall": {
            "force": number(stall_force),
            "kind": s.kind.name(),
            "bracket": [number(s.bracket.0), number(s.bracket.1)],
            "relative_width": number(s.relative_width()),
            "v_inf": option(s.at.v_inf),
            "v_inf_error": option(s.at.error),
            "regime": s.at.regime,
        },
        "held_band": c.held_band.map_or(Value::Null, |b| json!({
            "lower": number(b.lower),
            "upper": number(b.upper),
            "below": number(b.below),
            "above": number(b.above),
        })),
        "holding_force": number(c.holding_force),
        "max_output_power": c.max_power.as_ref().map_or(Value::Null, |p| json!({
            "power": number(p.power),
            "power_error": option(p.error),
            "load": number(p.at.load),
            "v_inf": option(p.at.v_inf),
        })),
        "run_away": {
            "below": limit_json(c.run_away_below.as_ref()),
            "above": limit_json(c.run_away_above.as_ref()),
        },
        "incline": c.incline.map_or(Value::Null, |i| json!({
            "stall_angle": option(i.stall_angle),
            "holding_angle": number(i.holding_angle),
        })),
        "transient_force": c.transient.map_or(Value::Null, |t| json!({
            "initial_force": number(t.initial_force),
            "max_force": number(t.max_force),
            "max_period": t.max_period,
            "periods": t.periods,
            "initial_over_stall": option(ratio(t.initial_force, stall_force)),
            "max_over_stall": option(ratio(t.max_force, stall_force)),
        })),
        "datasheet": datasheet_json(&c.datasheet),
        "sampling_complete": c.sampling_complete,
        "evaluations": {
            "total": c.counts.total(),
            "v_inf": c.counts.v_inf(),
            "sampling": c.counts.sampling,
            "run_away": c.counts.run_away,
            "stall": c.counts.stall,
            "held_band": c.counts.held_band,
            "max_power": c.counts.max_power,
            "transient": c.counts.transient,
            "not_converged": c.counts.not_converged,
        },
        "points": points,
        "wall_time_s": number(c.wall_time.as_secs_f64()),
    })
}

/// A CSV number: shortest digits that read back to the same double.
fn cell(x: Option<f64>) -> String {
    match x {
        Some(x) if x.is_finite() && (x == 0.0 || (1e-4..1e16).contains(&x.abs())) => {
            format!("{x}")
        }
        Some(x) if x.is_finite() => format!("{x:e}"),
        _ => String::new(),
    }
}

/// The points as CSV, after comment lines naming the program, the scene
/// and the sign convention.
pub(crate) fn to_csv(c: &Characteristic, scene: &Scene) -> String {
    let mut out = format!(
        "# stickslip_version = {}, scene_hash = {}, load_axis = {}\n# {}; slope = d v_inf / d F by {}\n",
        provenance::VERSION,
        provenance::scene_hash(scene),
        c.axis.name(),
        SIGN_CONVENTION,
        super::slope::DESCRIPTION,
    );
    let incline = c.axis == LoadAxis::Incline;
    let mut header = vec!["load"];
    if incline {
        header.push("angle");
    }
    header.extend([
        "extra_acceleration",
        "regime",
        "v_inf",
        "error_v_inf",
        "output_power",
        "slope",
        "slope_left",
        "slope_right",
        "slope_method",
        "marks",
    ]);
    out.push_str(&header.join(","));
    out.push('\n');
    for p in &c.points {
        let e = &p.evaluation;
        let mut row = vec![cell(Some(e.load))];
        if incline {
            row.push(cell(Some(p.x)));
        }
        let marks: Vec<&str> = p.marks.iter().map(|m| m.name()).collect();
        row.extend([
            cell(Some(e.extra_acceleration)),
            e.regime.to_owned(),
            cell(e.v_inf),
            cell(e.error),
            cell(e.output_power()),
            cell(p.slope.value),
            cell(p.slope.left),
            cell(p.slope.right),
            p.slope.method.name().to_owned(),
            marks.join(";"),
        ]);
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

fn value_or_none(x: Option<f64>, unit: &str) -> String {
    x.filter(|v| v.is_finite())
        .map_or("none".to_owned(), |v| format!("{} {unit}", fmt(v)))
}

/// The width of the stall force's bracket (N): the force lies inside it.
fn stall_width(s: &super::Stall) -> f64 {
    (s.bracket.1 - s.bracket.0).abs()
}

/// A value without an error estimate: the shortest digits that read back
/// to the same double.
fn fmt(x: f64) -> String {
    if x == 0.0 || (1e-4..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The readable summary: the special loads, the datasheet block and the
/// table of points.
pub(crate) fn to_text(c: &Characteristic) -> String {
    let mut t = String::new();
    let s = &c.stall;
    let w = |t: &mut String, label: &str, text: String| {
        let _ = writeln!(t, "{label:<22}{text}");
    };
    let _ = writeln!(
        t,
        "characteristic: v_inf against the load ({}; {SIGN_CONVENTION})",
        match c.axis {
            LoadAxis::Force => "force F".to_owned(),
            LoadAxis::Incline => "incline angle theta, F = m_s g sin(theta)".to_owned(),
        }
    );
    if c.replaced_extra_acceleration != 0.0 {
        let _ = writeln!(
            t,
            "(the scene's motor.extra_acceleration = {} m/s^2 is replaced by the load)",
            fmt(c.replaced_extra_acceleration)
        );
    }
    w(
        &mut t,
        "no-load speed",
        format!(
            "{} m/s ({})",
            format_with_error(c.no_load.v_inf.unwrap_or(0.0), c.no_load.error),
            c.drive_direction()
        ),
    );
    w(
        &mut t,
        "stall force",
        format!(
            "{} N ({}; bracketed to a relative width of {:.1e}; v_inf there {} m/s)",
            format_with_error(s.force, Some(stall_width(s))),
            s.kind.name(),
            s.relative_width(),
            format_with_error(s.at.v_inf.unwrap_or(0.0), s.at.error)
        ),
    );
    w(
        &mut t,
        "held still",
        match &c.held_band {
            Some(b) => format!("for loads from {} to {} N", fmt(b.lower), fmt(b.upper)),
            None => "by no load while running".to_owned(),
        },
    );
    w(
        &mut t,
        "holding force",
        format!(
            "{} N (mu_0 F_c, slider and rod at rest)",
            fmt(c.holding_force)
        ),
    );
    w(
        &mut t,
        "max output power",
        match &c.max_power {
            Some(p) => format!(
                "{} W at F = {} N (located to {:.0e} relative), v_inf = {} m/s",
                format_with_error(p.power, p.error),
                rounded(p.at.load, Some(p.at.load.abs() * p.load_resolution())),
                p.load_resolution(),
                format_with_error(p.at.v_inf.unwrap_or(0.0), p.at.error)
            ),
            None => "none (no drive)".to_owned(),
        },
    );
    let limit = |l: Option<&Limit>| {
        l.map_or("none in range".to_owned(), |l| {
            if l.first_unsteady.is_unsettled() {
                format!(
                    "{} N (at {} N not converged within run.max_periods)",
                    format_with_error(l.load(), Some(l.width())),
                    rounded(l.first_unsteady.load, Some(l.width()))
                )
            } else {
                format!("{} N", format_with_error(l.load(), Some(l.width())))
            }
        })
    };
    w(
        &mut t,
        "curve ends (run-away)",
        format!(
            "below {} / above {}",
            limit(c.run_away_below.as_ref()),
            limit(c.run_away_above.as_ref())
        ),
    );
    if let Some(i) = &c.incline {
        w(
            &mut t,
            "incline",
            format!(
                "stalls at {}, holds at rest up to {} deg",
                i.stall_angle
                    .map_or("no angle".to_owned(), |a| format!("{} deg", fmt(a))),
                fmt(i.holding_angle)
            ),
        );
    }
    if let Some(tr) = &c.transient {
        w(
            &mut t,
            "start-up force",
            format!(
                "initial {} N ({}), largest {} N in period {} ({}) of {}",
                rounded(tr.initial_force, None),
                ratio(tr.initial_force, s.force)
                    .map_or("-".to_owned(), |r| format!("{r:.3} x stall")),
                rounded(tr.max_force, None),
                tr.max_period,
                ratio(tr.max_force, s.force).map_or("-".to_owned(), |r| format!("{r:.3} x stall")),
                crate::plural::count(tr.periods, "period", "periods")
            ),
        );
    }
    let _ = writeln!(t, "\ndatasheet");
    for e in c.datasheet.entries() {
        // Each entry to the digits its source resolves: the no-load run's
        // estimate, the stall bracket, the power's estimate; the holding
        // force is the product of two inputs.
        let error = match e.key {
            "max_speed" => c.no_load.error,
            "stall_force" => Some(stall_width(&c.stall)),
            "recommended_load" => Some(stall_width(&c.stall) / 2.0),
            "max_output_power" => c.max_power.as_ref().and_then(|p| p.error),
            _ => None,
        };
        let shown = match (e.value.filter(|v| v.is_finite()), error) {
            (Some(v), Some(err)) => format!("{} {}", format_with_error(v, Some(err)), e.unit),
            _ => value_or_none(e.value, e.unit),
        };
        let _ = writeln!(t, "  {:<20}{shown}", e.key);
    }
    let _ = writeln!(t);
    let incline = c.axis == LoadAxis::Incline;
    let _ = writeln!(
        t,
        "{}{:>14} {:>12} {:>24} {:>11} {:>14} {:>16}  marks",
        if incline {
            format!("{:>10} ", "theta (deg)")
        } else {
            String::new()
        },
        "F (N)",
        "g_t (m/s^2)",
        "v_inf (m/s)",
        "regime",
        "F v_inf (W)",
        "dv/dF (m/(s N))"
    );
    for p in &c.points {
        let e = &p.evaluation;
        let marks: Vec<&str> = p.marks.iter().map(|m| m.name()).collect();
        let _ = writeln!(
            t,
            "{}{:>14.7e} {:>12.5e} {:>24} {:>11} {:>14} {:>16}  {}",
            if incline {
                format!("{:>10.4} ", p.x)
            } else {
                String::new()
            },
            e.load,
            e.extra_acceleration,
            e.v_inf
                .map_or("-".to_owned(), |v| format_with_error(v, e.error)),
            e.regime,
            e.output_power()
                .map_or("-".to_owned(), |p| format!("{p:.5e}")),
            p.slope.value.map_or("-".to_owned(), |v| format!("{v:.6e}")),
            marks.join(",")
        );
    }
    let n = &c.counts;
    let _ = writeln!(
        t,
        "\n{} simulations ({} of v_inf: sampling {}, run-away {}, stall {}, held band {}, max power {}; start-up {}){}{}; {:.1} ms\nslopes: {}",
        n.total(),
        n.v_inf(),
        n.sampling,
        n.run_away,
        n.stall,
        n.held_band,
        n.max_power,
        n.transient,
        if n.not_converged > 0 {
            format!("; {} not converged within run.max_periods", n.not_converged)
        } else {
            String::new()
        },
        if c.sampling_complete {
            ""
        } else {
            "; sampling stopped at --max-evaluations"
        },
        c.wall_time.as_secs_f64() * 1e3,
        super::slope::DESCRIPTION,
    );
    t
}
