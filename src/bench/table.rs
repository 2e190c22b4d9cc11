//! A bench as text, JSON or CSV (keys and columns in `docs/interface.md`,
//! "stickslip bench").
//!
//! Contract: every value is in SI units; a value that does not exist (no
//! steady orbit, a spring kind not asked) is `null` in JSON and an empty
//! cell in CSV, never NaN. The JSON carries the program version and the
//! resolved scene with its fingerprint, like `run --json`; the CSV's first
//! lines say the same, and the two reference forces, as comments.

use super::{Bench, SpringCase};
use crate::csv_text;
use crate::provenance;
use crate::scene::{Scene, SceneFile};
use serde_json::{Value, json};
use std::fmt::Write as _;

use crate::characteristic::table::{number, option, ratio};

/// The CSV columns, one row per stiffness and spring.
pub(crate) const CSV_COLUMNS: [&str; 14] = [
    "stiffness",
    "spring",
    "regime",
    "force_mean",
    "force_max",
    "force_min",
    "force_mean_over_stall",
    "force_max_over_stall",
    "position_mean",
    "contact_fraction",
    "orbit_periods",
    "periods_simulated",
    "certificate",
    "note",
];

fn case_json(c: &SpringCase, stall: f64) -> Value {
    let p = c.reading.map(|r| r.profile);
    json!({
        "regime": c.regime,
        "force_mean": option(p.map(|p| p.force_mean)),
        "force_max": option(p.map(|p| p.force_max)),
        "force_min": option(p.map(|p| p.force_min)),
        "force_mean_over_stall": option(p.and_then(|p| ratio(p.force_mean, stall))),
        "force_max_over_stall": option(p.and_then(|p| ratio(p.force_max, stall))),
        "position_mean": option(p.map(|p| p.position_mean)),
        "contact_fraction": option(p.map(|p| p.contact_fraction)),
        "orbit_periods": c.reading.map(|r| r.orbit_periods),
        "periods_simulated": c.periods_simulated,
        "certificate": c.certificate.map(|k| k.name()),
        "note": c.note(),
        "wall_time_s": c.wall_time.as_secs_f64(),
    })
}

/// The bench of `scene` as one JSON object.
pub(crate) fn to_json(b: &Bench, scene: &Scene) -> Value {
    let stall = b.stall_force();
    let t = b.reference.transient;
    let rows: Vec<Value> = b
        .rows
        .iter()
        .map(|r| {
            json!({
                "stiffness": number(r.stiffness),
                "tied": r.tied.as_ref().map_or(Value::Null, |c| case_json(c, stall)),
                "free": r.free.as_ref().map_or(Value::Null, |c| case_json(c, stall)),
            })
        })
        .collect();
    json!({
        "stickslip_version": provenance::VERSION,
        "scene_hash": provenance::scene_hash(scene),
        "scene": serde_json::to_value(SceneFile::from(scene)).unwrap_or(Value::Null),
        "stiffness_range": [number(b.options.from), number(b.options.to)],
        "points": b.options.points,
        "springs": b.options.kinds.name(),
        "tied_damping": number(b.tied_spring.0),
        "tied_preload": number(b.tied_spring.1),
        "free_gap": number(b.free_gap),
        "stall_force": number(stall),
        "stall_kind": b.reference.stall.kind.name(),
        "startup_force": option(t.map(|t| t.max_force)),
        "startup_force_period": t.map(|t| t.max_period),
        "startup_initial_force": option(t.map(|t| t.initial_force)),
        "startup_force_over_stall": option(t.and_then(|t| ratio(t.max_force, stall))),
        "holding_force": number(b.reference.holding_force),
        "rows": rows,
        "wall_time_s": b.wall_time.as_secs_f64(),
    })
}

fn cell(x: Option<f64>) -> String {
    match x {
        Some(v) if v.is_finite() => {
            if v != 0.0 && (v.abs() < 1e-4 || v.abs() >= 1e16) {
                format!("{v:e}")
            } else {
                format!("{v}")
            }
        }
        _ => String::new(),
    }
}

/// The bench as CSV: comment lines, the header, one row per stiffness and
/// spring (tied before free).
pub(crate) fn to_csv(b: &Bench, scene: &Scene) -> String {
    let stall = b.stall_force();
    let mut out = format!(
        "# stickslip_version = {}, scene_hash = {}\n# stall_force = {} N, startup_force = {} N\n",
        provenance::VERSION,
        provenance::scene_hash(scene),
        cell(Some(stall)),
        cell(b.startup_force()),
    );
    out.push_str(&CSV_COLUMNS.join(","));
    out.push('\n');
    for r in &b.rows {
        for c in r.tied.iter().chain(r.free.iter()) {
            let p = c.reading.map(|r| r.profile);
            let row = [
                cell(Some(r.stiffness)),
                c.end_name().to_owned(),
                c.regime.to_owned(),
                cell(p.map(|p| p.force_mean)),
                cell(p.map(|p| p.force_max)),
                cell(p.map(|p| p.force_min)),
                cell(p.and_then(|p| ratio(p.force_mean, stall))),
                cell(p.and_then(|p| ratio(p.force_max, stall))),
                cell(p.map(|p| p.position_mean)),
                cell(p.map(|p| p.contact_fraction)),
                c.reading
                    .map_or(String::new(), |r| r.orbit_periods.to_string()),
                c.periods_simulated.to_string(),
                c.certificate.map_or("", |k| k.name()).to_owned(),
                c.note().unwrap_or_default(),
            ];
            out.push_str(&csv_text::line(&row));
            out.push('\n');
        }
    }
    out
}

/// `x` with six significant digits.
fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (5 - x.abs().log10().floor() as i32).clamp(0, 15) as usize;
    format!("{x:.decimals$}")
}

/// A force and its ratio to the stall force, or the outcome.
fn force_cell(c: Option<&SpringCase>, stall: f64, max: bool) -> String {
    let Some(c) = c else {
        return String::new();
    };
    match c.reading {
        Some(r) => {
            let f = if max {
                r.profile.force_max
            } else {
                r.profile.force_mean
            };
            match ratio(f, stall) {
                Some(q) => format!("{} ({q:.5})", sig(f)),
                None => sig(f),
            }
        }
        None => c.regime.to_owned(),
    }
}

/// The bench as a text table (module docs of [`super`]).
pub(crate) fn to_text(b: &Bench) -> String {
    let stall = b.stall_force();
    let o = &b.options;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "spring method: {} stiffnesses from {} to {} N/m (log spaced), {} springs",
        o.points,
        crate::error::Num(o.from),
        crate::error::Num(o.to),
        o.kinds.name()
    );
    let _ = writeln!(
        out,
        "  tied: damping {} N s/m, preload {} N; free end: gap {} m",
        crate::error::Num(b.tied_spring.0),
        crate::error::Num(b.tied_spring.1),
        crate::error::Num(b.free_gap)
    );
    let _ = writeln!(
        out,
        "weight method: stall force {} N ({})",
        sig(stall),
        b.reference.stall.kind.name()
    );
    match b.reference.transient {
        Some(t) => {
            let _ = writeln!(
                out,
                "Newton method: start-up force {} N (largest m_s a_p, period {} of the start-up; {:.4} x stall), initial {} N",
                sig(t.max_force),
                t.max_period,
                ratio(t.max_force, stall).unwrap_or(f64::NAN),
                sig(t.initial_force)
            );
        }
        None => {
            let _ = writeln!(out, "Newton method: no start-up to read");
        }
    }
    let _ = writeln!(
        out,
        "spring force in N (ratio to the stall force); contact: time fraction the free end pushes"
    );
    let header = [
        "k (N/m)",
        "tied mean",
        "tied max",
        "free mean",
        "free max",
        "contact",
    ];
    let mut lines: Vec<[String; 6]> = vec![header.map(str::to_owned)];
    for r in &b.rows {
        lines.push([
            format!("{:.4e}", r.stiffness),
            force_cell(r.tied.as_ref(), stall, false),
            force_cell(r.tied.as_ref(), stall, true),
            force_cell(r.free.as_ref(), stall, false),
            force_cell(r.free.as_ref(), stall, true),
            r.free
                .as_ref()
                .and_then(|c| c.reading)
                .map_or(String::new(), |r| {
                    format!("{:.4}", r.profile.contact_fraction)
                }),
        ]);
    }
    let mut widths = [0usize; 6];
    for l in &lines {
        for (w, c) in widths.iter_mut().zip(l) {
            *w = (*w).max(c.chars().count());
        }
    }
    for l in &lines {
        let mut text = String::new();
        for (i, (c, w)) in l.iter().zip(widths).enumerate() {
            if i > 0 {
                text.push_str("  ");
            }
            let _ = write!(text, "{c:>w$}");
        }
        out.push_str(text.trim_end());
        out.push('\n');
    }
    let notes: Vec<String> = b
        .cases()
        .filter_map(|c| {
            c.note().map(|n| {
                format!(
                    "  {} spring, k = {:.4e} N/m: {n}",
                    c.end_name(),
                    c.spring.stiffness
                )
            })
        })
        .collect();
    if !notes.is_empty() {
        let _ = writeln!(out, "without a steady orbit:");
        for n in notes {
            out.push_str(&n);
            out.push('\n');
        }
    }
    let periods: u64 = b.cases().map(|c| c.periods_simulated).sum();
    let _ = writeln!(
        out,
        "{} runs, {} periods simulated from rest; wall time {:.3} s",
        b.cases().count(),
        periods,
        b.wall_time.as_secs_f64()
    );
    out
}
