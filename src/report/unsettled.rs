//! The keys and lines of an outcome without a steady state (a run-away,
//! or a start-up that did not establish its limit).

use super::spring::{add_spring_errors, add_spring_json, spring_text};
use super::{cost_line, format_with_error, number, option_number};
use crate::simulation::{RunTimes, Unsettled};
use serde_json::{Map, Value, json};
use std::fmt::Write as _;

/// Without a steady state the keys of one keep their place with `null`
/// (the event counts of a start-up and of a steady period, the fixed-point
/// work, the verification), so that every outcome has the same keys.
pub(super) fn unsettled_json(m: &mut Map<String, Value>, u: &Unsettled, verify: bool) {
    let mut err = Map::new();
    for indicator in &u.requested {
        m.insert(indicator.name().into(), Value::Null);
        err.insert(indicator.name().into(), Value::Null);
    }
    m.insert("last_v_p".into(), option_number(u.last_v_p));
    m.insert("final_velocity".into(), number(u.final_velocity));
    m.insert(
        "v_inf_bounds".into(),
        json!([
            option_number(u.v_inf_bounds.0),
            option_number(u.v_inf_bounds.1)
        ]),
    );
    m.insert("period".into(), number(u.period));
    m.insert("f0".into(), number(1.0 / u.period));
    m.insert("f_max".into(), option_number(u.f_max));
    m.insert("periods_simulated".into(), json!(u.periods_simulated));
    if let Some(s) = &u.spring {
        add_spring_json(m, s);
        add_spring_errors(&mut err, s);
    }
    m.insert(
        "steady_state_certificate".into(),
        match u.certificate_evaluations {
            Some(_) => json!("covering"),
            None => Value::Null,
        },
    );
    m.insert("other_fixed_point_distance".into(), Value::Null);
    m.insert("events".into(), Value::Null);
    m.insert("events_per_steady_period".into(), Value::Null);
    if verify {
        m.insert("v_inf_transient".into(), Value::Null);
        m.insert("steady_state_check".into(), Value::Null);
    }
    m.insert("error_estimate".into(), Value::Object(err));
    m.insert(
        "work".into(),
        json!({
            "periods": u.work.periods,
            "events": u.work.events.total(),
            "evaluations": u.work.evaluations,
            "root_iterations": u.work.root_iterations,
            "fixed_point_iterations": Value::Null,
            "map_evaluations": Value::Null,
            "certificate_evaluations": u.certificate_evaluations,
        }),
    );
}

pub(super) fn unsettled_text(out: &mut String, state: &Unsettled, times: RunTimes) {
    if let Some(v) = state.last_v_p.filter(|_| state.spring.is_none()) {
        let _ = writeln!(
            out,
            "  last mean velocity v_p = {} m/s (period {})",
            format_with_error(v, None),
            state.periods_simulated
        );
    }
    let _ = writeln!(out, "indicators: none (no steady state)");
    if let Some(s) = &state.spring {
        spring_text(out, s);
    }
    cost_line(
        out,
        state.work.periods,
        state.work.events.total(),
        state.work.root_iterations,
        times,
    );
}
