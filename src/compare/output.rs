//! The report of a comparison as JSON (keys in docs/interface.md) and as
//! readable text.

use super::{Metric, Report};
use serde_json::{Value, json};
use std::fmt::Write as _;

impl Report {
    /// The JSON object (keys in docs/interface.md).
    pub fn to_json(&self) -> Value {
        let files: Vec<Value> = self
            .files
            .iter()
            .map(|f| {
                let errors: serde_json::Map<String, Value> = Metric::ALL
                    .iter()
                    .map(|m| {
                        let v = f.errors[m.index()]
                            .map(|e| json!({"absolute": e.absolute, "relative": e.relative}));
                        (m.name().to_owned(), json!(v))
                    })
                    .collect();
                json!({
                    "file": f.file,
                    "samples": f.samples,
                    "step": f.step,
                    "t_first": f.span.map(|s| s.0),
                    "t_last": f.span.map(|s| s.1),
                    "periods": f.periods,
                    "v_inf": f.v_inf,
                    "startup_periods": f.startup_periods,
                    "rod": f.rod,
                    "events": f.events,
                    "errors": errors,
                    "v_inf_split": f.v_inf_split,
                    "period_ends": f.period_ends,
                    "warnings": f.warnings,
                    "pass": f.pass,
                })
            })
            .collect();
        let convergence: serde_json::Map<String, Value> = self
            .convergence
            .iter()
            .map(|(m, fit)| (m.name().to_owned(), json!(fit)))
            .collect();
        json!({
            "stickslip_version": env!("CARGO_PKG_VERSION"),
            "period": self.signal.period,
            "v_inf": self.v_inf,
            "startup_periods": self.startup_periods,
            "metric": self.metric.name(),
            "tolerance": self.tolerance,
            "pass": self.pass,
            "files": files,
            "convergence": convergence,
        })
    }

    /// Readable text.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "exact: T = {:e} s, v_inf = {} m/s, p_0.99 = {}",
            self.signal.period,
            self.v_inf,
            self.startup_periods
                .map_or("undefined".to_owned(), |p| p.to_string())
        );
        for f in &self.files {
            let _ = writeln!(s, "\n{}", f.file);
            if let (Some(h), Some((a, b))) = (f.step, f.span) {
                let _ = writeln!(
                    s,
                    "  {} samples, step {h:e} s ({:.1} steps per period), t = {a:e} .. {b:e} s",
                    f.samples,
                    self.signal.period / h
                );
            }
            if let (true, Some(v)) = (f.periods > 0, f.v_inf) {
                let _ = writeln!(
                    s,
                    "  {} period{}, v_inf = {v} m/s, p_0.99 = {}",
                    f.periods,
                    if f.periods == 1 { "" } else { "s" },
                    f.startup_periods
                        .map_or("not reached".to_owned(), |p| p.to_string())
                );
            }
            if let Some(e) = &f.period_ends {
                let _ = writeln!(
                    s,
                    "  v_p from x_S at {} period ends, {} interpolated between samples \
                     (estimated v_p interpolation error {:.1e} m/s)",
                    e.ends, e.interpolated, e.max_v_p_error
                );
            }
            if let Some(split) = &f.v_inf_split {
                let _ = writeln!(
                    s,
                    "  v_inf error split at period {}: step size {:+.4e} m/s (relative {:+.4e}), \
                     truncation {:+.4e} m/s (relative {:+.4e})",
                    split.period,
                    split.step_size,
                    split.step_size_relative,
                    split.truncation,
                    split.truncation_relative
                );
            }
            for w in &f.warnings {
                let _ = writeln!(s, "  warning: {w}");
            }
            if let Some(r) = &f.rod {
                if r.matches {
                    let _ = writeln!(
                        s,
                        "  rod: matches the scene (max deviation {:.3e} m, {:.2e} of the stroke)",
                        r.max_deviation, r.relative_deviation
                    );
                } else {
                    let _ = writeln!(
                        s,
                        "  rod: DIFFERS from the scene (max deviation {:.3e} m, {:.2e} of the \
                         stroke): {}",
                        r.max_deviation,
                        r.relative_deviation,
                        r.message.as_deref().unwrap_or("")
                    );
                }
            }
            if let Some(e) = &f.events {
                let _ = writeln!(
                    s,
                    "  events: {} exact, {} found, {} matched, {} missed, {} spurious",
                    e.exact, e.found, e.matched, e.missed, e.spurious
                );
            }
            for m in Metric::ALL {
                if let Some(e) = f.errors[m.index()] {
                    let _ = writeln!(
                        s,
                        "  {:<16} {:>12.4e} {:<8} relative {:.4e}{}",
                        m.name(),
                        e.absolute,
                        m.unit(),
                        e.relative,
                        if (m == Metric::event_time_max || m == Metric::event_time_rms)
                            && f.step.is_some()
                        {
                            format!(" ({:.2} steps)", e.absolute / f.step.unwrap_or(1.0))
                        } else {
                            String::new()
                        }
                    );
                }
            }
            if let (Some(pass), Some(e)) = (f.pass, f.judged(self.metric)) {
                let _ = writeln!(
                    s,
                    "  verdict: {} ({}{} relative {:.3e} vs tolerance {:e})",
                    if pass { "pass" } else { "FAIL" },
                    self.metric.name(),
                    if self.metric == Metric::v_inf && f.v_inf_split.is_some() {
                        ", step-size part,"
                    } else {
                        ""
                    },
                    e.relative,
                    self.tolerance
                );
            }
        }
        if !self.convergence.is_empty() {
            let _ = writeln!(
                s,
                "\nconvergence over {} files (relative errors):",
                self.files.len()
            );
            for (m, fit) in &self.convergence {
                match (fit.supported, fit.order, fit.standard_error) {
                    (true, Some(q), Some(se)) => {
                        let _ = writeln!(
                            s,
                            "  {:<16} order {q:.2} ± {se:.2}{}",
                            m.name(),
                            fit.step_for_tolerance.map_or(String::new(), |h| format!(
                                ", step for {:e}: {h:.3e} s",
                                self.tolerance
                            ))
                        );
                    }
                    _ => {
                        let _ = writeln!(
                            s,
                            "  {:<16} no order: {}",
                            m.name(),
                            fit.reason.as_deref().unwrap_or("")
                        );
                    }
                }
            }
        }
        let _ = writeln!(s, "\nverdict: {}", if self.pass { "pass" } else { "FAIL" });
        s
    }
}
