//! The spring's reading in the run report (docs/model.md section 17): the
//! keys of `run --json` and the lines of the text summary.

use crate::simulation::{SpringReading, spring_figures};
use serde_json::{Map, Value, json};
use std::fmt::Write as _;

/// The reading's keys in `run --json`: the figures, `orbit_periods`
/// (`null` where no orbit locked), `spring_reading_periods`, and where no
/// orbit locked `spring_force_mean_range` and `orbit_search`.
pub(super) fn add_spring_json(m: &mut Map<String, Value>, r: &SpringReading) {
    for (key, value, _) in spring_figures(&r.profile) {
        m.insert(key.into(), super::number(value));
    }
    m.insert(
        "orbit_periods".into(),
        if r.orbit_periods > 0 {
            json!(r.orbit_periods)
        } else {
            Value::Null
        },
    );
    m.insert("spring_reading_periods".into(), json!(r.periods));
    if let Some([lo, hi]) = r.mean_range {
        m.insert(
            "spring_force_mean_range".into(),
            json!([super::number(lo), super::number(hi)]),
        );
    }
    if let Some((longest, periods)) = r.searched {
        m.insert(
            "orbit_search".into(),
            json!({ "longest": longest, "periods": periods }),
        );
    }
}

/// The reading's lines in the text summary.
pub(super) fn spring_text(out: &mut String, r: &SpringReading) {
    if r.orbit_periods > 0 {
        let _ = writeln!(
            out,
            "spring (steady orbit of {}; v_inf and what assumes travel do not apply):",
            crate::plural::count(r.orbit_periods, "period", "periods")
        );
    } else {
        let (longest, periods) = r.searched.unwrap_or((0, 0));
        let _ = writeln!(
            out,
            "spring: no orbit of up to {longest} periods locked within {periods} periods from \
             rest; read over the next {}:",
            crate::plural::count(r.periods, "period", "periods")
        );
    }
    for (key, value, unit) in spring_figures(&r.profile) {
        let _ = writeln!(
            out,
            "  {key:<22} {} {unit}",
            super::format_with_error(value, None)
        );
    }
    if let Some([lo, hi]) = r.mean_range {
        let _ = writeln!(
            out,
            "  the mean force of a single period ranges over {} .. {} N",
            super::format_with_error(lo, None),
            super::format_with_error(hi, None)
        );
    }
}
