//! Is the user's rod motion the scene's? The largest deviation of the
//! user's `x_R` from the exact `x_R` at the user's times, relative to the
//! stroke, decides. When it is too large and the signal is a harmonic
//! series, the user's samples are fitted by least squares with the scene's
//! harmonics, `x_R ~ c_0' + sum_k A_k' cos(k w_0 t) + B_k' sin(k w_0 t)`,
//! and the fitted amplitudes `d_k'` and phases `phi_k'` (docs/model.md
//! section 2, (6) and (7)) are compared with the scene's to say what is
//! wrong:
//!
//! * `shape`: amplitudes not proportional to the scene's;
//! * `scaling`: proportional with a factor other than 1 (stroke scaling
//!   missing or different);
//! * `missing_shift`: phases `phi_k' = phi_k - k w_0 t_s` with the scene's
//!   shift `t_s` (the series was not shifted to its minimum);
//! * `time_shift`: phases of another time shift (a different time origin);
//! * `wrong_phase`: phases no time shift explains (negated phases, a
//!   constant phase error such as cos for sin, or others);
//! * `offset`: only the constant term differs;
//! * `not_harmonic`: the samples are not a series of the scene's
//!   harmonics at its period (a different period or signal kind).

use crate::signal::description::SignalDescription;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::f64::consts::PI;

/// Default tolerance on the rod deviation, relative to the stroke.
pub(crate) const DEFAULT_ROD_TOLERANCE: f64 = 1e-6;

/// Outcome of the rod check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RodCheck {
    /// Largest `|x_R,user - x_R|` (m).
    pub max_deviation: f64,
    /// The same relative to the stroke.
    pub relative_deviation: f64,
    /// True when within the tolerance.
    pub matches: bool,
    /// What is wrong, as codes (see the module doc); empty when it matches.
    pub diagnosis: Vec<&'static str>,
    /// The same in words.
    pub message: Option<String>,
}

fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.4e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn wrap(a: f64) -> f64 {
    let r = (a + PI).rem_euclid(2.0 * PI) - PI;
    if r <= -PI { r + 2.0 * PI } else { r }
}

/// Checks the user's rod positions `x_user` at times `t` against the exact
/// ones `x_exact`.
pub(crate) fn check(
    t: &[f64],
    x_user: &[f64],
    x_exact: &[f64],
    signal: &SignalDescription,
    tolerance: f64,
) -> RodCheck {
    let max_deviation = x_user
        .iter()
        .zip(x_exact)
        .fold(0.0_f64, |m, (u, e)| m.max((u - e).abs()));
    let relative_deviation = max_deviation / signal.stroke;
    let matches = relative_deviation <= tolerance;
    let (diagnosis, message) = if matches {
        (Vec::new(), None)
    } else {
        let (codes, text) = diagnose(t, x_user, signal);
        (codes, Some(text))
    };
    RodCheck {
        max_deviation,
        relative_deviation,
        matches,
        diagnosis,
        message,
    }
}

fn diagnose(t: &[f64], x: &[f64], sig: &SignalDescription) -> (Vec<&'static str>, String) {
    let n = sig.harmonics.len();
    let span = t.last().copied().unwrap_or(0.0) - t.first().copied().unwrap_or(0.0);
    if n == 0 || span < 0.999 * sig.period || t.len() < 2 * n + 2 {
        return (
            Vec::new(),
            "the rod positions differ from the scene's; give at least one whole period of a \
             harmonic signal for a diagnosis"
                .to_owned(),
        );
    }
    // Normal equations of the least-squares fit.
    let w0 = 2.0 * PI / sig.period;
    let m = 2 * n + 1;
    let mut ata = DMatrix::<f64>::zeros(m, m);
    let mut atb = DVector::<f64>::zeros(m);
    let mut row = vec![0.0; m];
    for (&ti, &xi) in t.iter().zip(x) {
        row[0] = 1.0;
        for k in 1..=n {
            let (s, c) = (k as f64 * w0 * ti).sin_cos();
            row[2 * k - 1] = c;
            row[2 * k] = s;
        }
        for a in 0..m {
            atb[a] += row[a] * xi;
            for b in 0..m {
                ata[(a, b)] += row[a] * row[b];
            }
        }
    }
    let Some(coef) = ata.lu().solve(&atb) else {
        return (
            vec!["not_harmonic"],
            "the rod positions cannot be fitted".to_owned(),
        );
    };
    let residual = t.iter().zip(x).fold(0.0_f64, |r, (&ti, &xi)| {
        let mut f = coef[0];
        for k in 1..=n {
            let (s, c) = (k as f64 * w0 * ti).sin_cos();
            f += coef[2 * k - 1] * c + coef[2 * k] * s;
        }
        r.max((f - xi).abs())
    });
    if residual > 1e-3 * sig.stroke {
        return (
            vec!["not_harmonic"],
            format!(
                "the rod positions are not a series of the scene's {n} harmonics at its period \
                 T = {:e} s (fit residual {:.2e} of the stroke): a different period or signal",
                sig.period,
                residual / sig.stroke
            ),
        );
    }
    let du: Vec<f64> = (1..=n)
        .map(|k| coef[2 * k - 1].hypot(coef[2 * k]))
        .collect();
    let pu: Vec<f64> = (1..=n)
        .map(|k| coef[2 * k - 1].atan2(coef[2 * k]))
        .collect();
    let d: Vec<f64> = sig.harmonics.iter().map(|h| h.amplitude).collect();
    let p: Vec<f64> = sig.harmonics.iter().map(|h| h.phase).collect();
    let d_max = d.iter().copied().fold(0.0, f64::max);
    let scale =
        du.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>() / d.iter().map(|b| b * b).sum::<f64>();
    let mut codes = Vec::new();
    let mut words = Vec::new();
    let shape = du
        .iter()
        .zip(&d)
        .fold(0.0_f64, |m, (a, b)| m.max((a - scale * b).abs()))
        / d_max;
    if shape > 1e-3 {
        codes.push("shape");
        words.push(format!(
            "the harmonic amplitudes d_k = [{}] m are not proportional to the scene's \
             [{}] m: a different signal shape (harmonics, sigma factors?)",
            list(&du),
            list(&d)
        ));
    } else if (scale - 1.0).abs() > 1e-4 {
        codes.push("scaling");
        words.push(format!(
            "the amplitudes are {scale:.6} times the scene's: the stroke scaling is missing \
             or different (stroke {:.6e} m instead of {:.6e} m)",
            scale * sig.stroke,
            sig.stroke
        ));
    }
    // Phase differences; only harmonics with amplitude carry a phase.
    let keep: Vec<usize> = (0..n).filter(|&i| d[i] > 1e-6 * d_max).collect();
    let delta: Vec<f64> = keep.iter().map(|&i| wrap(pu[i] - p[i])).collect();
    let tol = 1e-3;
    let linear = |values: &[f64]| {
        keep.iter()
            .zip(values)
            .all(|(&i, v)| wrap(v - (i + 1) as f64 * values[0] / (keep[0] + 1) as f64).abs() < tol)
    };
    let mut phase_ok = true;
    if delta.iter().all(|v| v.abs() < tol) {
        // Same phases.
    } else if keep[0] == 0 && linear(&delta) {
        // x_user(t) = x(t + dt) with w0 dt = delta_1.
        let dt = (delta[0] / w0).rem_euclid(sig.period);
        let missing = sig.time_shift.is_some_and(|ts| {
            let r = (dt + ts).rem_euclid(sig.period);
            r.min(sig.period - r) < 1e-3 * sig.period
        });
        phase_ok = false;
        if missing {
            codes.push("missing_shift");
            words.push(format!(
                "the rod signal is the scene's series without the shift: the scene moves the \
                 minimum from t_s = {:e} s to t = 0 and offsets it to x_R = 0 (see `stickslip \
                 signal`)",
                sig.time_shift.unwrap_or(0.0)
            ));
        } else {
            codes.push("time_shift");
            words.push(format!(
                "the rod signal is the scene's shifted in time: x_R,user(t) = x_R(t + {dt:e} s); \
                 a different time origin"
            ));
        }
    } else {
        phase_ok = false;
        codes.push("wrong_phase");
        let sum: Vec<f64> = keep.iter().map(|&i| wrap(pu[i] + p[i])).collect();
        let constant = delta.iter().all(|v| wrap(v - delta[0]).abs() < tol);
        let detail = if keep[0] == 0 && linear(&sum) {
            "the phases have the wrong sign (sin(k w0 t - phi_k) for sin(k w0 t + phi_k), or \
             the signal reversed in time)"
                .to_owned()
        } else if constant {
            format!(
                "every phase is off by {:.6} rad{}",
                delta[0],
                if (delta[0].abs() - PI / 2.0).abs() < tol {
                    " (cos for sin?)"
                } else {
                    ""
                }
            )
        } else {
            format!(
                "the phases differ by [{}] rad, which no time shift explains",
                list(&delta)
            )
        };
        words.push(format!("wrong phase: {detail}"));
    }
    if codes.is_empty() || (phase_ok && codes.iter().all(|c| *c != "shape")) {
        let offset = coef[0] - sig.offset;
        if offset.abs() > 1e-6 * sig.stroke && codes.is_empty() {
            codes.push("offset");
            words.push(format!(
                "the rod positions are offset by {offset:e} m: the minimum is not moved to x_R = 0"
            ));
        }
    }
    if words.is_empty() {
        words.push("the rod positions differ from the scene's".to_owned());
    }
    (codes, words.join("; "))
}
