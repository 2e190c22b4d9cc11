//! What `stickslip optimize` writes (docs/interface.md, `optimize`): the
//! optimum as a runnable scene, that scene run as `stickslip run` runs it,
//! the comparison with the sigma and plain Fourier signals of the same
//! `n` and `f_max`, and the report as text or JSON.
//!
//! The scene is written as TOML text, read back with
//! [`Scene::from_toml_str`] and run: every number reported for the optimum
//! is from that run of the text on disk, so `stickslip run BEST.toml`
//! prints the same. Its signal is the `kind = "harmonics"` series the
//! search evaluated, bit for bit (amplitudes `|u_k| x_hat / 2` before the
//! scaling, which the scene performs), so the run reproduces the search's
//! `v_inf` exactly. Nothing in the text or in the JSON (without timing)
//! depends on the clock or the thread count.

use super::Optimum;
use super::objective::Objective;
use super::params::Shape;
use super::search::HistoryPoint;
use crate::error::Error;
use crate::indicator::Indicator;
use crate::plural::count;
use crate::report::{self, format_with_error};
use crate::scene::Scene;
use crate::signal::SignalSpec;
use crate::signal::description::SignalDescription;
use crate::simulation::{self, Outcome};
use serde_json::{Map, Value, json};
use std::fmt::Write as _;
use std::time::Duration;

/// One row of the comparison.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    /// `"optimum"`, `"sigma"` or `"fourier"`.
    pub name: &'static str,
    /// The run of its scene (the written scene's outputs), or why it
    /// failed.
    pub outcome: Result<Outcome, String>,
}

/// The written optimum and its comparison.
#[derive(Debug, Clone)]
pub(crate) struct Written {
    /// The scene file's text.
    pub text: String,
    /// The scene read back from it.
    pub scene: Scene,
    /// `stickslip run` of that scene.
    pub outcome: Outcome,
    /// Optimum, sigma and plain Fourier signal.
    pub rows: Vec<Row>,
}

/// The scene an optimum is written as: the base scene with the series,
/// and with the indicators the objectives and limits need added to its
/// outputs.
fn written_scene(optimum: &Optimum, spec: SignalSpec) -> Scene {
    let p = &optimum.problem;
    let mut scene = p.base.clone();
    scene.signal = spec;
    let mut wanted: Vec<Indicator> = scene.outputs.indicators.clone();
    wanted.extend(p.indicators());
    scene.outputs.indicators = Indicator::ALL
        .into_iter()
        .filter(|i| wanted.contains(i))
        .collect();
    scene
}

fn objective_label(optimum: &Optimum) -> String {
    optimum
        .settings
        .objectives
        .iter()
        .map(|o| o.name())
        .collect::<Vec<_>>()
        .join(",")
}

/// Writes the optimum as scene text, reads it back, runs it, and runs the
/// sigma and plain Fourier signals with the same outputs.
pub(crate) fn write_up(optimum: &Optimum) -> Result<Written, Error> {
    let p = &optimum.problem;
    let series = optimum.best.shape.series(p.stroke);
    let scene = written_scene(optimum, p.spec(&series));
    let s = &optimum.settings;
    let v = optimum.best.measured.values.v_inf;
    let sigma = optimum
        .references
        .iter()
        .find(|r| r.name == "sigma")
        .and_then(|r| r.measured.as_ref().ok())
        .map(|m| m.values.v_inf);
    let mut text = format!(
        "# The best rod signal found by stickslip {} optimize: objective {}, n = {} harmonics \
         of f_0 = {} Hz\n# (f_max = {} Hz, {} kept), stroke {} m, seed {}.\n# v_inf = {} m/s",
        env!("CARGO_PKG_VERSION"),
        objective_label(optimum),
        p.harmonics,
        p.f0,
        p.f_max,
        s.keep.name(),
        p.stroke,
        s.seed,
        format_with_error(v, optimum.best.measured.v_inf_error),
    );
    if let Some(sv) = sigma {
        let _ = write!(
            text,
            "; the sigma signal of the same n and f_max: {} m/s",
            format_with_error(sv, None)
        );
    }
    text.push_str(".\n\n");
    text.push_str(&scene.to_toml());
    let read = Scene::from_toml_str(&text, "<written scene>")?;
    let outcome = simulation::simulate(&read)?;
    let mut rows = vec![Row {
        name: "optimum",
        outcome: Ok(outcome.clone()),
    }];
    for r in &optimum.references {
        let scene = written_scene(optimum, r.spec.clone());
        rows.push(Row {
            name: r.name,
            outcome: simulation::simulate(&scene).map_err(|e| e.to_string()),
        });
    }
    Ok(Written {
        text,
        scene: read,
        outcome,
        rows,
    })
}

fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

fn option(x: Option<f64>) -> Value {
    x.map_or(Value::Null, number)
}

/// The reported value of an objective in a run.
fn objective_value(outcome: &Outcome, o: Objective) -> Option<f64> {
    outcome.value(o.indicator())
}

/// `optimum / sigma - 1` of the first objective, when both exist.
fn change(rows: &[Row], o: Objective) -> Option<f64> {
    let value = |name: &str| {
        rows.iter()
            .find(|r| r.name == name)
            .and_then(|r| r.outcome.as_ref().ok())
            .and_then(|out| objective_value(out, o))
    };
    let (a, b) = (value("optimum")?, value("sigma")?);
    (b != 0.0).then(|| a / b - 1.0)
}

/// Amplitude ratios `d_k / max d` and relative phases `psi_k` (k >= 2) of
/// a shape, canonical (module docs of [`super::params`]).
fn shape_json(shape: &Shape) -> Value {
    let c = shape.coefficients();
    let d: Vec<f64> = c.iter().map(|(re, im)| re.hypot(*im)).collect();
    let top = d.iter().copied().fold(0.0, f64::max);
    let phases: Vec<f64> = c
        .iter()
        .skip(1)
        .map(|(re, im)| super::params::wrap(im.atan2(*re)))
        .collect();
    json!({
        "amplitude_ratios": d.iter().map(|x| x / top).collect::<Vec<_>>(),
        "relative_phases": phases,
    })
}

fn history_json(h: &HistoryPoint) -> Value {
    json!({
        "stage": h.stage,
        "start": h.start,
        "iteration": h.iteration,
        "evaluations": h.evaluations,
        "merit": number(h.merit),
        "best": option(h.best),
    })
}

/// The JSON report (keys in docs/interface.md); `timing` adds
/// `wall_time_s`, and the run's own timing keys, when given.
pub(crate) fn to_json(optimum: &Optimum, written: &Written, timing: Option<Duration>) -> Value {
    let p = &optimum.problem;
    let s = &optimum.settings;
    let first = s.objectives[0];
    let mut run = report::to_json(&written.outcome, &written.scene);
    if timing.is_none()
        && let Value::Object(m) = &mut run
    {
        for key in ["wall_time_s", "setup_time_s", "simulation_time_s"] {
            m.remove(key);
        }
    }
    let series = optimum.best.shape.series(p.stroke);
    let built = simulation::build(&written.scene).ok();
    let signal = built
        .as_ref()
        .map(|(sig, motor)| SignalDescription::new(&written.scene.signal, sig, motor).to_json());
    let highest = built.as_ref().and_then(|(sig, _)| sig.f_max());
    let l = &s.limits;
    let comparison: Vec<Value> = written
        .rows
        .iter()
        .map(|r| match &r.outcome {
            Ok(out) => json!({
                "signal": r.name,
                "regime": out.regime(),
                "v_inf": option(out.value(Indicator::VInf)),
                "error_v_inf": option(out.report().and_then(|rep| rep.error.v_inf)),
                "objective": option(objective_value(out, first)),
                "failure": Value::Null,
            }),
            Err(e) => json!({
                "signal": r.name,
                "regime": Value::Null,
                "v_inf": Value::Null,
                "error_v_inf": Value::Null,
                "objective": Value::Null,
                "failure": e,
            }),
        })
        .collect();
    let refinements: Vec<Value> = optimum
        .search
        .refinements
        .iter()
        .enumerate()
        .map(|(i, r)| {
            json!({
                "start": i,
                "iterations": r.iterations,
                "evaluations": r.evaluations,
                "gradients": r.gradients,
                "stop": r.stop.name(),
                "merit": number(r.merit),
                "objective": option(r.best.as_ref().and_then(|b| p.reported(first, &b.measured))),
            })
        })
        .collect();
    let pareto = optimum.front.as_ref().map_or(Value::Null, |front| {
        Value::Array(
            front
                .iter()
                .map(|f| {
                    let series = f.found.shape.series(p.stroke);
                    json!({
                        "objectives": [number(f.objectives[0]), number(f.objectives[1])],
                        "v_inf": number(f.found.measured.values.v_inf),
                        "amplitudes": series.amplitudes,
                        "phases": series.phases,
                    })
                })
                .collect(),
        )
    });
    let mut m = Map::new();
    m.insert("stickslip_version".into(), json!(env!("CARGO_PKG_VERSION")));
    m.insert(
        "objectives".into(),
        json!(s.objectives.iter().map(|o| o.name()).collect::<Vec<_>>()),
    );
    m.insert("harmonics".into(), json!(p.harmonics));
    m.insert("keep".into(), json!(s.keep.name()));
    m.insert("f0".into(), number(p.f0));
    m.insert("f_max".into(), number(p.f_max));
    m.insert("stroke".into(), number(p.stroke));
    m.insert("seed".into(), json!(s.seed));
    m.insert(
        "limits".into(),
        json!({
            "max_apparent_power": option(l.max_apparent_power),
            "max_voltage_rms": option(l.max_voltage_rms),
            "min_smoothness": option(l.min_smoothness),
            "min_durability": option(l.min_durability),
            "max_startup_time": option(l.max_startup_time),
            "min_v_inf": option(l.min_v_inf),
        }),
    );
    let mut optimum_json = json!({
        "objective": option(objective_value(&written.outcome, first)),
        "v_inf": option(written.outcome.value(Indicator::VInf)),
        "error_v_inf": option(written.outcome.report().and_then(|r| r.error.v_inf)),
        "v_inf_search": number(optimum.best.measured.values.v_inf),
        "amplitudes": series.amplitudes,
        "phases": series.phases,
        "highest_frequency": option(highest),
        "signal": signal.unwrap_or(Value::Null),
    });
    if let (Value::Object(o), Value::Object(extra)) =
        (&mut optimum_json, shape_json(&optimum.best.shape))
    {
        o.extend(extra);
    }
    m.insert("optimum".into(), optimum_json);
    m.insert("run".into(), run);
    m.insert("comparison".into(), Value::Array(comparison));
    m.insert(
        "change_over_sigma".into(),
        option(change(&written.rows, first)),
    );
    m.insert("samples".into(), json!(optimum.search.samples));
    m.insert("local_optima".into(), json!(optimum.search.local_optima));
    m.insert("refinements".into(), Value::Array(refinements));
    m.insert("evaluations".into(), json!(optimum.search.evaluations));
    m.insert("gradients".into(), json!(optimum.search.gradients));
    m.insert(
        "history".into(),
        Value::Array(optimum.search.history.iter().map(history_json).collect()),
    );
    m.insert("pareto".into(), pareto);
    if let Some(t) = timing {
        m.insert("wall_time_s".into(), number(t.as_secs_f64()));
    }
    Value::Object(m)
}

/// The readable summary.
pub(crate) fn to_text(optimum: &Optimum, written: &Written, timing: Option<Duration>) -> String {
    let p = &optimum.problem;
    let s = &optimum.settings;
    let first = s.objectives[0];
    let mut t = String::new();
    let _ = writeln!(
        t,
        "optimum of {}: n = {} harmonics of f_0 = {:.6} Hz, f_max = {:.6} Hz ({} kept), stroke {} m, seed {}",
        objective_label(optimum),
        p.harmonics,
        p.f0,
        p.f_max,
        s.keep.name(),
        p.stroke,
        s.seed
    );
    let heading = format!("{first} ({})", first.indicator().printed_unit());
    let _ = writeln!(
        t,
        "{:<9} {:<12} {:<34} {heading}",
        "signal", "regime", "v_inf (m/s)"
    );
    for r in &written.rows {
        match &r.outcome {
            Ok(out) => {
                let rep = out.report();
                let v = out.value(Indicator::VInf);
                let ev = rep.and_then(|r| r.error.v_inf);
                let o = objective_value(out, first);
                let eo = rep.and_then(|r| r.error(first.indicator()));
                let _ = writeln!(
                    t,
                    "{:<9} {:<12} {:<34} {}",
                    r.name,
                    out.regime(),
                    v.map_or("none".to_owned(), |v| format_with_error(v, ev)),
                    o.map_or("none".to_owned(), |o| format_with_error(o, eo)),
                );
            }
            Err(e) => {
                let _ = writeln!(t, "{:<9} failed: {e}", r.name);
            }
        }
    }
    if let Some(c) = change(&written.rows, first) {
        let _ = writeln!(t, "optimum against sigma: {:+.2} % in {first}", 100.0 * c);
    }
    let c = optimum.best.shape.coefficients();
    let d: Vec<f64> = c.iter().map(|(re, im)| re.hypot(*im)).collect();
    let top = d.iter().copied().fold(0.0, f64::max);
    let ratios: Vec<String> = d.iter().map(|x| format!("{:.6}", x / top)).collect();
    let phases: Vec<String> = c
        .iter()
        .skip(1)
        .map(|(re, im)| format!("{:.6}", super::params::wrap(im.atan2(*re))))
        .collect();
    let _ = writeln!(
        t,
        "shape: amplitude ratios d_k / max d = [{}], relative phases psi_k (k >= 2) = [{}] rad",
        ratios.join(", "),
        phases.join(", ")
    );
    let search = &optimum.search;
    let _ = write!(
        t,
        "search: {}, {}, {} found, {}, {}",
        count(search.samples, "global point", "global points"),
        count(
            search.refinements.len(),
            "local refinement",
            "local refinements"
        ),
        count(search.local_optima, "local optimum", "local optima"),
        count(search.evaluations, "run", "runs"),
        count(search.gradients, "gradient", "gradients")
    );
    if let Some(time) = timing {
        let _ = write!(t, ", {:.3} s", time.as_secs_f64());
    }
    t.push('\n');
    if let Some(front) = &optimum.front {
        let second = s.objectives[1];
        let _ = writeln!(t, "Pareto front ({first}, {second}):");
        for f in front {
            let _ = writeln!(
                t,
                "  {:<24} {:<24} v_inf {}",
                format_with_error(f.objectives[0], None),
                format_with_error(f.objectives[1], None),
                format_with_error(f.found.measured.values.v_inf, None)
            );
        }
    }
    t.push_str(
        "a local optimum: the best of a seeded global sample and of local refinements from \
         its best points, not a proof that no better signal exists\n",
    );
    t
}
