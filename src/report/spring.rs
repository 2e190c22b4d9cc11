//! The spring's reading in the run report (docs/model.md section 17): the
//! keys of `run --json` and the lines of the text summary. Each figure
//! comes with its error estimate (docs/model.md section 17, "The
//! reading's error"): in the text as `value ± error`, the value rounded to
//! the digits the estimate supports as an indicator's is, `± unknown`
//! without one; in JSON under `error_estimate`, named like the figure,
//! `null` without one.

use crate::simulation::{SpringReading, spring_figures};
use serde_json::{Map, Value, json};
use std::fmt::Write as _;

/// One figure of the reading: its JSON key, value, error estimate and
/// unit.
pub(super) struct Figure {
    pub key: &'static str,
    pub value: f64,
    pub error: Option<f64>,
    pub unit: &'static str,
}

/// The reading's figures ([`spring_figures`]) with their estimates, in
/// the order the text prints them.
pub(super) fn figures(r: &SpringReading) -> [Figure; 5] {
    let errors = r.error.map(|e| e.figures().map(|part| part.total()));
    let mut i = 0;
    spring_figures(&r.profile).map(|(key, value, unit)| {
        let f = Figure {
            key,
            value,
            error: errors.map(|e| e[i]),
            unit,
        };
        i += 1;
        f
    })
}

/// The reading's error estimates in `run --json`'s `error_estimate`
/// object `err`: one key per figure, named like it; `null` where there is
/// none.
pub(super) fn add_spring_errors(err: &mut Map<String, Value>, r: &SpringReading) {
    for f in figures(r) {
        err.insert(f.key.into(), super::option_number(f.error));
    }
}

/// The reading's keys in `run --json`: the figures, `orbit_periods`
/// (`null` where no orbit locked), `spring_reading_periods`, and where no
/// orbit locked `spring_force_mean_range` and `orbit_search`.
pub(super) fn add_spring_json(m: &mut Map<String, Value>, r: &SpringReading) {
    for f in figures(r) {
        m.insert(f.key.into(), super::number(f.value));
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
             rest; read over the next {} (not an orbit: no error estimate, the range of a \
             single period's mean below is what the run knows):",
            crate::plural::count(r.periods, "period", "periods")
        );
    }
    for f in figures(r) {
        let _ = writeln!(
            out,
            "  {:<22} {} {}",
            f.key,
            super::with_estimate(f.value, f.error),
            f.unit
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
