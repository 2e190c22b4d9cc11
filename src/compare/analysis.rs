//! The comparison of one user's result, given as arrays ([`UserData`]),
//! with the exact solution at the user's own times (the errors of the
//! table in [`super`]).
//!
//! * The per-period series is the file's `p, v_p` if it has one, else it
//!   is formed from the samples of `x_S` at the period ends
//!   ([`super::periods`], with the bound of its interpolation error).
//! * The `v_inf` error is split ([`VInfSplit`]) into the step-size part
//!   `v_p,user(P) - v_p(P)` and the truncation part `v_p(P) - v_inf` of the
//!   file's last period `P`; the verdict on `v_inf` judges the step-size
//!   part, and a warning says when truncation dominates.
//! * Events are located between samples ([`super::events`]).
//!
//! Contract: the data satisfy [`UserData::validate`]; times beyond
//! `run.max_periods` periods and period indices beyond it are bad input.

use super::exact;
use super::periods::{self, PeriodEnds};
use super::read::UserData;
use super::{CompareError, CompareOptions, ErrorValue, FileReport, Metric, VInfSplit};
use super::{events, rod};
use crate::motor::Motor;
use crate::signal::Signal;
use crate::signal::description::SignalDescription;

/// What the comparison of every file needs of the exact solution.
pub(crate) struct Exact<'a> {
    pub signal: &'a Signal,
    pub motor: &'a Motor,
    pub description: &'a SignalDescription,
    /// Exact `v_inf` (m/s).
    pub v_inf: f64,
    /// Exact `p_0.99`.
    pub startup_periods: Option<u64>,
    /// `run.max_periods` of the scene.
    pub max_periods: u64,
}

fn max_rms(d: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (mut m, mut s, mut n) = (0.0_f64, 0.0, 0usize);
    for x in d {
        m = m.max(x.abs());
        s += x * x;
        n += 1;
    }
    (n > 0).then(|| (m, (s / n as f64).sqrt()))
}

/// The per-period series `(p, v_p)` of `data`, and how its ends were found
/// when it comes from the samples.
fn series(data: &UserData, ex: &Exact<'_>) -> (Vec<u64>, Vec<f64>, Option<PeriodEnds>) {
    match (&data.p, &data.v_p) {
        (Some(p), Some(v)) => (
            p.values.iter().map(|&q| q as u64).collect(),
            v.values.clone(),
            None,
        ),
        (None, Some(v)) => (
            (1..=v.values.len() as u64).collect(),
            v.values.clone(),
            None,
        ),
        _ => {
            let (Some(t), Some(x)) = (&data.t, &data.x_s) else {
                return (Vec::new(), Vec::new(), None);
            };
            match periods::from_samples(&t.values, &x.values, ex.signal.period()) {
                Some(s) => (s.periods, s.v_p, Some(s.ends)),
                None => (Vec::new(), Vec::new(), None),
            }
        }
    }
}

/// Compares one file's data (see the module doc).
pub(crate) fn compare_file(
    file: &str,
    data: &UserData,
    ex: &Exact<'_>,
    options: &CompareOptions,
) -> Result<FileReport, CompareError> {
    let (signal, description, v_inf) = (ex.signal, ex.description, ex.v_inf);
    let max_periods = ex.max_periods;
    let period = signal.period();
    let span_end = max_periods as f64 * period;
    let times: &[f64] = data.t.as_ref().map_or(&[], |c| &c.values);
    if let Some(&last) = times.last()
        && last > span_end
    {
        let name = data.t.as_ref().map_or("t", |c| c.name.as_str());
        return Err(CompareError::data(
            file,
            Some(name),
            Some(format!("row {}", times.len())),
            format!(
                "time {last} s is after the simulated span, which ends after run.max_periods = \
                 {max_periods} periods at {span_end} s"
            ),
        ));
    }
    let (user_periods, user_v_p, period_ends) = series(data, ex);
    if let Some(&p_last) = user_periods.last()
        && p_last > max_periods
    {
        return Err(CompareError::data(
            file,
            Some(data.p.as_ref().map_or("p", |c| c.name.as_str())),
            Some(format!("row {}", user_periods.len())),
            format!("period {p_last} is beyond run.max_periods = {max_periods}"),
        ));
    }
    let min_periods = user_periods.last().copied().unwrap_or(0);
    let exact = exact::evaluate(signal, ex.motor, times, min_periods)?;
    let mut errors = [None; 10];
    let mut set = |m: Metric, absolute: f64, scale: f64| {
        errors[m.index()] = Some(ErrorValue {
            absolute,
            relative: absolute / scale,
        });
    };
    let mut warnings = Vec::new();
    // Per-period series.
    let period_errors: Vec<(u64, f64)> = user_periods
        .iter()
        .zip(&user_v_p)
        .map(|(&p, &vp)| (p, vp - exact.periods[p as usize - 1].v_p))
        .collect();
    let mut user_v_inf = None;
    let mut user_startup = None;
    let mut v_inf_split = None;
    if let (Some(&last), Some(&p_last)) = (user_v_p.last(), user_periods.last()) {
        user_v_inf = Some(last);
        set(Metric::v_inf, (last - v_inf).abs(), v_inf.abs());
        let exact_v_p = exact.periods[p_last as usize - 1].v_p;
        let (step_size, truncation) = (last - exact_v_p, exact_v_p - v_inf);
        let split = VInfSplit {
            period: p_last,
            exact_v_p,
            step_size,
            truncation,
            step_size_relative: step_size / v_inf.abs(),
            truncation_relative: truncation / v_inf.abs(),
            truncation_dominates: truncation.abs() > step_size.abs(),
        };
        if split.truncation_dominates {
            warnings.push(format!(
                "truncation dominates the v_inf error: the file ends at period {p_last}, where \
                 the exact v_p = {exact_v_p} m/s is still {truncation:.3e} m/s from v_inf \
                 (the start-up is not over), against a step-size part of {step_size:.3e} m/s; \
                 the verdict judges the step-size part"
            ));
        }
        v_inf_split = Some(split);
        if let Some((m, r)) = max_rms(period_errors.iter().map(|e| e.1)) {
            set(Metric::v_p_max, m, v_inf.abs());
            set(Metric::v_p_rms, r, v_inf.abs());
        }
        user_startup = (last != 0.0)
            .then(|| {
                user_periods
                    .iter()
                    .zip(&user_v_p)
                    .find(|(_, vp)| **vp / last >= 0.99)
                    .map(|(p, _)| *p)
            })
            .flatten();
        if let (Some(u), Some(e)) = (user_startup, ex.startup_periods) {
            set(Metric::startup_periods, u.abs_diff(e) as f64, e as f64);
        }
    }
    let states = &exact.states;
    if let Some(x) = &data.x_s
        && let Some((m, r)) = max_rms(x.values.iter().zip(states).map(|(u, s)| u - s.x_s))
    {
        set(Metric::x_S_max, m, description.stroke);
        set(Metric::x_S_rms, r, description.stroke);
    }
    let v_scale = signal.velocity_scale();
    let mut event_match = None;
    let mut velocity = Vec::new();
    if let Some(v) = &data.v_s {
        if let Some((m, r)) = max_rms(v.values.iter().zip(states).map(|(u, s)| u - s.v_s)) {
            set(Metric::v_S_max, m, v_scale);
            set(Metric::v_S_rms, r, v_scale);
        }
        let v_r: Vec<f64> = states.iter().map(|s| s.v_r).collect();
        let (t0, t1) = (times[0], times[times.len() - 1]);
        // A change out of the first sample (the start from rest) cannot be
        // placed in time: left out, like exact events at t0.
        let mut user = events::detect(times, &v.values, &v_r, options.stick_tolerance * v_scale);
        user.retain(|e| e.t > t0);
        let mut exact_events = events::exact_events(&exact.periods, period, t0, t1);
        exact_events.retain(|e| e.t > t0);
        let matched = events::match_events(&exact_events, &user, 0.25 * period);
        if let (Some(m), Some(r)) = (matched.max_time_error, matched.rms_time_error) {
            set(Metric::event_time_max, m, period);
            set(Metric::event_time_rms, r, period);
        }
        event_match = Some(matched);
        velocity = times
            .iter()
            .zip(&v.values)
            .zip(states)
            .map(|((t, u), s)| (*t, *u, s.v_s))
            .collect();
    }
    let rod = data.x_r.as_ref().map(|x| {
        let exact_x: Vec<f64> = states.iter().map(|s| s.x_r).collect();
        rod::check(
            times,
            &x.values,
            &exact_x,
            description,
            options.rod_tolerance,
        )
    });
    let mut report = FileReport {
        file: file.to_owned(),
        samples: times.len(),
        step: data.step(),
        span: (!times.is_empty()).then(|| (times[0], times[times.len() - 1])),
        periods: user_periods.len(),
        v_inf: user_v_inf,
        startup_periods: user_startup,
        rod,
        events: event_match,
        errors,
        period_ends,
        v_inf_split,
        warnings,
        period_errors,
        velocity,
        pass: None,
    };
    report.pass = report
        .judged(options.metric)
        .map(|e| e.relative <= options.tolerance);
    Ok(report)
}
