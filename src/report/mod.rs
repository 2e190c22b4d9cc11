//! Turning an [`Outcome`] into text or JSON.
//!
//! The text summary prints each value with as many significant digits as
//! its error estimate supports (never more than 15), followed by the
//! estimate, so every printed digit is meant. The JSON object uses the keys
//! fixed in `docs/interface.md`; values that do not exist (an infinite
//! smoothness when the slider velocity is constant, a start-up that was not
//! reached, every indicator of a slider that runs away) are `null`, never
//! NaN. Every output carries `regime`, the program version and the resolved
//! scene with its fingerprint ([`crate::provenance`]).
//!
//! Every indicator has one definition and one unit ([`RunReport::value`],
//! [`Indicator`]), the same in `run`, `check`, sweeps and figures.

use crate::engine::{Direction, EventCounts};
use crate::indicator::Indicator;
use crate::provenance;
use crate::scene::Scene;
use crate::scene::SceneFile;
use crate::sensitivity::{Derivative, Sensitivities};

mod driven;
mod spring;
mod unsettled;

use crate::signal::Held;
use crate::simulation::{CertificateKind, Outcome, RunReport, RunTimes};
use driven::drive_figures;
pub(crate) use driven::{actuator_sensitivities_text, add_actuator_sensitivities_json};
use serde_json::{Map, Value, json};
use spring::{add_spring_errors, add_spring_json, spring_text};
use std::fmt::Write as _;
use unsettled::{unsettled_json, unsettled_text};

/// `value` rounded to the digits its absolute error `err` supports (15
/// significant digits without an estimate), then `± err`; an error of 0
/// prints as `(exact)`. Moderate magnitudes print in plain decimal notation.
pub fn format_with_error(value: f64, err: Option<f64>) -> String {
    if !value.is_finite() {
        return "none".to_owned();
    }
    let text = rounded(value, err);
    match err {
        Some(e) if e > 0.0 => format!("{text} ± {e:.1e}"),
        Some(_) => format!("{text} (exact)"),
        None => text,
    }
}

/// `value` rounded to the digits its absolute error `err` supports (15
/// significant digits without an estimate or with an error of 0), without
/// the error: for a number whose resolution is stated beside it.
pub(crate) fn rounded(value: f64, err: Option<f64>) -> String {
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
    if value == 0.0 {
        "0".to_owned()
    } else if (-4..6).contains(&magnitude) {
        let decimals = (digits - 1 - magnitude).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{:.*e}", (digits - 1) as usize, value)
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
        "contact_start": e.contact_start,
        "contact_end": e.contact_end,
    })
}

/// The keys every outcome carries first: `regime`, the provenance and the
/// resolved scene.
fn header(outcome: &Outcome, scene: &Scene) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("regime".into(), json!(outcome.regime()));
    m.insert("stickslip_version".into(), json!(provenance::VERSION));
    m.insert("scene_hash".into(), json!(provenance::scene_hash(scene)));
    m.insert(
        "scene".into(),
        serde_json::to_value(SceneFile::from(scene)).unwrap_or(Value::Null),
    );
    m
}

fn times_json(
    m: &mut Map<String, Value>,
    RunTimes {
        setup,
        simulation,
        wall,
    }: RunTimes,
) {
    m.insert("wall_time_s".into(), number(wall.as_secs_f64()));
    m.insert("setup_time_s".into(), number(setup.as_secs_f64()));
    m.insert("simulation_time_s".into(), number(simulation.as_secs_f64()));
}

/// The outcome of a run of `scene` as one JSON object with the keys of
/// `docs/interface.md`.
pub fn to_json(outcome: &Outcome, scene: &Scene) -> Value {
    let mut m = header(outcome, scene);
    match outcome {
        Outcome::Steady(r) => steady_json(&mut m, r),
        Outcome::RunAway { direction, state } => {
            unsettled_json(&mut m, state, scene.run.verify_steady_state);
            m.insert("direction".into(), json!(direction_name(*direction)));
        }
        Outcome::NotConverged(state) => {
            unsettled_json(&mut m, state, scene.run.verify_steady_state)
        }
    }
    // The drive frequency with the digits the scene gives (a frequency
    // drive's f_0 itself, not 1 / (1 / f_0)); 1 / T for kappa.
    if let Ok(motor) = crate::motor::Motor::new(scene.motor) {
        let f0 = scene.signal.f0(&motor);
        if f0.is_finite() {
            m.insert("f0".into(), number(f0));
        }
    }
    times_json(&mut m, outcome.times());
    Value::Object(m)
}

fn direction_name(d: Direction) -> &'static str {
    match d {
        Direction::Forward => "forward",
        Direction::Backward => "backward",
    }
}

fn steady_json(m: &mut Map<String, Value>, r: &RunReport) {
    let ind = &r.indicators;
    let mut err = Map::new();
    for indicator in &r.requested {
        match indicator {
            Indicator::StartupTime => {
                m.insert(
                    "startup_periods".into(),
                    r.startup_periods.map_or(Value::Null, |p| json!(p)),
                );
            }
            Indicator::StictionFraction => {
                m.insert(
                    "stiction_fraction_steady".into(),
                    number(ind.stiction_fraction),
                );
            }
            Indicator::VelocityPerPower => {
                if let Some(p) = &r.power {
                    m.insert("apparent_power".into(), number(p.apparent_power));
                    m.insert("voltage_rms".into(), number(p.u_rms));
                    m.insert("current_rms".into(), number(p.i_rms));
                }
            }
            _ => {}
        }
        m.insert(indicator.name().into(), option_number(r.value(*indicator)));
        err.insert(indicator.name().into(), option_number(r.error(*indicator)));
    }
    if let Some(d) = &r.drive {
        for (key, value) in drive_figures(d) {
            m.insert(key.into(), number(value));
        }
    }
    if let Some(s) = &r.spring {
        add_spring_json(m, s);
        add_spring_errors(&mut err, s);
    }
    if let Some(check) = &r.steady_state_check {
        // The cross-check of run.verify_steady_state: the start-up's own
        // limit beside the steady state's.
        m.insert(
            "v_inf_transient".into(),
            option_number(check.v_inf_transient),
        );
        m.insert(
            "steady_state_check".into(),
            json!({
                "agrees": check.agrees(),
                "difference": option_number(check.difference),
                "tolerance": option_number(check.tolerance),
                "periods": check.periods,
            }),
        );
    }
    m.insert(
        "steady_state_certificate".into(),
        json!(r.certificate.kind.name()),
    );
    m.insert(
        "other_fixed_point_distance".into(),
        option_number(r.certificate.other_fixed_point),
    );
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
    m.insert("error_estimate".into(), Value::Object(err));
    m.insert(
        "work".into(),
        json!({
            "periods": r.work.periods,
            "events": r.work.events.total(),
            "evaluations": r.work.evaluations,
            "root_iterations": r.work.root_iterations,
            "fixed_point_iterations": r.steady.iterations,
            "map_evaluations": r.map_evaluations,
            "certificate_evaluations": r.certificate.evaluations,
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
                    "kind": e.kind.name(),
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
}

/// An indicator with its estimate; without one (no bound holds, e.g. a
/// grazing steady orbit) it says so instead of implying exact digits.
fn with_estimate(value: f64, err: Option<f64>) -> String {
    // An estimate that is not a number is no estimate (JSON: null).
    let err = err.filter(|e| e.is_finite());
    match err {
        Some(_) => format_with_error(value, err),
        None if value.is_finite() => format!("{} ± unknown", format_with_error(value, None)),
        None => format_with_error(value, None),
    }
}

fn signal_line(out: &mut String, period: f64, f_max: Option<f64>) {
    let _ = writeln!(
        out,
        "signal: T = {} s, f0 = {} Hz{}",
        format_with_error(period, None),
        format_with_error(1.0 / period, None),
        f_max
            .map(|f| format!(", f_max = {} Hz", format_with_error(f, None)))
            .unwrap_or_default()
    );
}

fn cost_line(out: &mut String, periods: u64, events: u64, roots: u64, times: RunTimes) {
    let RunTimes {
        setup,
        simulation,
        wall,
    } = times;
    let _ = writeln!(
        out,
        "work: {periods} periods, {events} events, {roots} root iterations; wall time {:.3} ms \
         (set-up {:.3} ms, simulation {:.3} ms)",
        wall.as_secs_f64() * 1e3,
        setup.as_secs_f64() * 1e3,
        simulation.as_secs_f64() * 1e3,
    );
}

/// A readable summary of the outcome.
pub fn to_text(outcome: &Outcome) -> String {
    match outcome {
        Outcome::Steady(r) => steady_text(r),
        Outcome::RunAway { direction, state } => {
            let mut out = String::new();
            signal_line(&mut out, state.period, state.f_max);
            match state.certificate_evaluations {
                None => {
                    let _ = writeln!(
                        out,
                        "outcome: run-away ({}): no periodic steady state; after {} period{} \
                         the slider slides at {} m/s outside the rod's velocity range, without \
                         any event, and keeps accelerating (motor.extra_acceleration exceeds \
                         what sliding friction can hold)",
                        direction_name(*direction),
                        state.periods_simulated,
                        if state.periods_simulated == 1 {
                            ""
                        } else {
                            "s"
                        },
                        format_with_error(state.final_velocity, None),
                    );
                }
                Some(evaluations) => {
                    let _ = writeln!(
                        out,
                        "outcome: run-away ({}): no periodic steady state; proven by a covering \
                         of {} map evaluations: no fixed point between rest and the rod's \
                         extreme velocity, beyond which the slider slides without any event and \
                         only gains speed (motor.extra_acceleration exceeds what sliding \
                         friction can hold); a slider starting a period there ends it at {} m/s",
                        direction_name(*direction),
                        evaluations,
                        format_with_error(state.final_velocity, None),
                    );
                }
            }
            unsettled_text(&mut out, state, outcome.times());
            out
        }
        Outcome::NotConverged(state) => {
            let mut out = String::new();
            signal_line(&mut out, state.period, state.f_max);
            let _ = writeln!(
                out,
                "outcome: not converged: the start-up from rest did not establish its limit \
                 within {} (run.max_periods){}",
                crate::plural::count(state.periods_simulated, "period", "periods"),
                if state.spring.is_some() {
                    ""
                } else {
                    "; v_inf is not reported"
                },
            );
            // Against a spring there is no travel to bound.
            if state.spring.is_none() {
                let bound =
                    |b: Option<f64>| b.map_or("unknown".to_owned(), |v| format_with_error(v, None));
                let _ = writeln!(
                    out,
                    "  v_inf lies between {} and {} m/s",
                    bound(state.v_inf_bounds.0),
                    bound(state.v_inf_bounds.1)
                );
            }
            unsettled_text(&mut out, state, outcome.times());
            out
        }
    }
}

fn steady_text(r: &RunReport) -> String {
    let mut out = String::new();
    let ind = &r.indicators;
    let line = |out: &mut String, name: &str, value: String, unit: &str| {
        let _ = writeln!(out, "  {name:<22} {value} {unit}");
    };
    signal_line(&mut out, r.period, r.f_max);
    let _ = writeln!(out, "steady state: {}", r.regime().name());
    let _ = writeln!(out, "indicators (± estimated absolute error):");
    let shown = |i: Indicator| with_estimate(r.value(i).unwrap_or(f64::NAN), r.error(i));
    for indicator in &r.requested {
        let name = indicator.name();
        match indicator {
            Indicator::StartupTime => match (r.startup_time(), r.startup_periods) {
                (Some(_), Some(p)) => line(
                    &mut out,
                    name,
                    format!(
                        "{} s = {p} period{}",
                        shown(*indicator),
                        if p == 1 { "" } else { "s" }
                    ),
                    "",
                ),
                _ => line(&mut out, name, "not reached".into(), ""),
            },
            Indicator::StictionFraction => {
                line(
                    &mut out,
                    name,
                    shown(*indicator),
                    &format!("(of the start-up, periods 1..{})", r.startup_span()),
                );
                line(
                    &mut out,
                    "  in steady state",
                    format_with_error(ind.stiction_fraction, None),
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
                line(&mut out, name, shown(*indicator), indicator.printed_unit());
            }
            Indicator::Smoothness => line(&mut out, name, shown(*indicator), ""),
            _ => line(&mut out, name, shown(*indicator), indicator.printed_unit()),
        }
    }
    if let Some(d) = &r.drive {
        let _ = writeln!(out, "driven rod (steady period):");
        for (key, value) in drive_figures(d) {
            let unit = match key {
                "rod_deviation_max" | "rod_deviation_rms" => "m",
                "voltage_peak" | "voltage_rms" => "V",
                _ => "A",
            };
            line(&mut out, key, format_with_error(value, None), unit);
        }
    }
    if r.drive.is_none() && r.driven_period.is_some() {
        let _ = writeln!(
            out,
            "driven rod (steady period): not resolved (the rod's free oscillation, heavily \
             over-damped, is beyond the root finder's budget: model section 16)"
        );
    }
    if let Some(s) = &r.spring {
        spring_text(&mut out, s);
    }
    if let Some(check) = &r.steady_state_check {
        let tr = check
            .v_inf_transient
            .map_or("not established".to_owned(), |v| format_with_error(v, None));
        let _ = writeln!(
            out,
            "cross-check: the start-up from rest ({}) gives v_inf = {tr} m/s",
            crate::plural::count(check.periods, "period", "periods")
        );
        match (check.agrees(), check.difference, check.tolerance) {
            (Some(true), Some(d), Some(t)) => {
                let _ = writeln!(
                    out,
                    "  agrees with the steady state: difference {d:.1e} m/s within the estimates {t:.1e} m/s"
                );
            }
            (Some(false), Some(d), Some(t)) => {
                let _ = writeln!(
                    out,
                    "  WARNING: differs from the steady state by {d:.1e} m/s, beyond the error \
                     estimates {t:.1e} m/s"
                );
            }
            _ => {
                let _ = writeln!(
                    out,
                    "  WARNING: agreement cannot be judged (no limit of the start-up or no error estimate)"
                );
            }
        }
    }
    let c = &r.certificate;
    let plural = if c.evaluations == 1 { "" } else { "s" };
    let _ = match c.kind {
        CertificateKind::Covering => writeln!(
            out,
            "limit from rest: certified by covering the gap with pieces free of other fixed \
             points ({} map evaluation{plural})",
            c.evaluations
        ),
        CertificateKind::Orbit if c.evaluations > 0 => writeln!(
            out,
            "limit from rest: the start-up simulated to its own limit (the covering did not \
             close in {} map evaluation{plural})",
            c.evaluations
        ),
        CertificateKind::Orbit => writeln!(
            out,
            "limit from rest: the start-up simulated to its own limit"
        ),
        CertificateKind::Attracted => writeln!(
            out,
            "limit from rest: the fixed point of the period map on {} by Newton, the start-up \
             followed into its attraction ({} periods)",
            match (r.spring.is_some(), r.drive.is_some()) {
                (true, true) => "(x_R, v_R, x_S, v_S)",
                (true, false) => "(x_S, v_S)",
                (false, _) => "(x_R, v_R, v_S)",
            },
            r.transient.as_ref().map_or(0, |t| t.periods())
        ),
    };
    if let Some(d) = c.other_fixed_point {
        let _ = writeln!(
            out,
            "  another fixed point of the period map lies {d:.1e} m/s away (in the boundary \
             velocity): a small change can switch the steady state"
        );
    }
    let ev = r.events();
    let contacts = if ev.contact_start + ev.contact_end > 0 {
        format!(
            ", {} contact start, {} contact end",
            ev.contact_start, ev.contact_end
        )
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "events over {} from rest: {} stick->slip, {} slip->stick, {} reversal, {} grazing, {} jump{contacts}",
        crate::plural::count(r.startup_span(), "period", "periods"),
        ev.stick_to_slip,
        ev.slip_to_stick,
        ev.reversal,
        ev.grazing,
        ev.jump
    );
    cost_line(
        &mut out,
        r.work.periods,
        r.work.events.total(),
        r.work.root_iterations,
        RunTimes {
            setup: r.setup_time,
            simulation: r.simulation_time,
            wall: r.wall_time,
        },
    );
    out
}

/// The `sensitivities` key of `run --json --sensitivities`
/// (docs/interface.md section 3): one object per parameter with `value`
/// and `unit`, and `left`, `right`, `change`, `change_at` where the event
/// structure changes; `null` (and `sensitivities_unavailable` with the
/// reason) when there are none; and `held_fixed`, what the derivatives
/// hold of the drive (`"kappa"` or `"frequency"`; `f0` is beside it).
pub(crate) fn add_sensitivities_json(
    object: &mut Value,
    sensitivities: &Result<Sensitivities, String>,
    held_fixed: Held,
) {
    let Value::Object(m) = object else {
        return;
    };
    m.insert("held_fixed".into(), json!(held_fixed.name()));
    match sensitivities {
        Ok(s) => {
            let mut entries = Map::new();
            for e in &s.entries {
                let mut entry = Map::new();
                entry.insert("value".into(), option_number(e.derivative.value()));
                entry.insert("unit".into(), json!(e.parameter.unit()));
                if let Derivative::OneSided {
                    left,
                    right,
                    change,
                } = e.derivative
                {
                    entry.insert("left".into(), option_number(left));
                    entry.insert("right".into(), option_number(right));
                    entry.insert("change".into(), json!(change.kind.name()));
                    entry.insert("change_at".into(), number(change.at));
                }
                entries.insert(e.parameter.to_string(), Value::Object(entry));
            }
            m.insert("sensitivities".into(), Value::Object(entries));
        }
        Err(reason) => {
            m.insert("sensitivities".into(), Value::Null);
            m.insert("sensitivities_unavailable".into(), json!(reason));
        }
    }
}

/// The sensitivities as lines of the text summary, after the line saying
/// what they hold of the drive at the drive frequency `f0` (Hz).
pub(crate) fn sensitivities_text(
    sensitivities: &Result<Sensitivities, String>,
    held_fixed: Held,
    f0: f64,
) -> String {
    let mut out = String::new();
    let f0 = format_with_error(f0, None);
    let _ = match held_fixed {
        Held::Frequency => writeln!(
            out,
            "sensitivities held fixed: the drive frequency f0 = {f0} Hz (a change of the motor \
             keeps it; for kind = \"fourier\" or \"ideal\" --sensitivities-at kappa holds kappa)"
        ),
        Held::Kappa => writeln!(
            out,
            "sensitivities held fixed: kappa = a_R / a_0, at f0 = {f0} Hz (a change of a_0 \
             retunes the drive, f0 ∝ sqrt(a_0); --sensitivities-at frequency holds f0 instead)"
        ),
    };
    match sensitivities {
        Ok(s) => {
            let _ = writeln!(out, "sensitivities of v_inf:");
            for e in &s.entries {
                let name = e.parameter.to_string();
                let unit = e.parameter.unit();
                let shown = |d: Option<f64>| d.map_or("none".to_owned(), |d| format!("{d:.6e}"));
                match e.derivative {
                    Derivative::Smooth(d) => {
                        let _ = writeln!(out, "  d/d {name:<26} {d:.6e} {unit}");
                    }
                    Derivative::OneSided {
                        left,
                        right,
                        change,
                    } => {
                        let _ = writeln!(
                            out,
                            "  d/d {name:<26} left {} / right {} {unit} ({} at {})",
                            shown(left),
                            shown(right),
                            change.kind.name(),
                            format_with_error(change.at, None)
                        );
                    }
                }
            }
        }
        Err(reason) => {
            let _ = writeln!(out, "sensitivities: none ({reason})");
        }
    }
    out
}
