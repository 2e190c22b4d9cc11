//! The work-precision figure: the error of the exact event engine and of
//! the fixed-step reference (`engine::fixed_step`) against their wall
//! time, on the study's three scenes ([`SCENES`]).
//!
//! Contract: a study is a list of [`Run`]s, one per engine setting and
//! scene. [`csv()`] writes them as the figure's data and [`parse`] reads
//! that text back into the same runs, bit for bit (every number is written
//! in Rust's shortest round-trip form); lines starting with `#` are
//! comments, a missing or renamed column, a cell that is not a number or
//! an unknown scene is an error naming the line, the column and the
//! value. [`figure`] draws the runs: (a) the relative error of `v_inf`,
//! (b) that of the start-up time `T p_0.99`, both against the wall time on
//! log-log axes; per scene the reference is a line through its
//! resolutions and the event engine a set of markers. An error of exactly
//! zero cannot be drawn on log axes and is named in the caption instead.
//!
//! The study is measured by `examples/work_precision.rs`, which writes
//! `plots/work_precision.svg` and its data `plots/work_precision.svg.csv`.
//! The figure registry draws that committed data ([`committed`]), so the
//! registered figure is the same on every machine, while its wall times
//! are those of the machine and the day of the last measurement.

use super::{
    Axis, Figure, Kind, LegendEntry, Look, Marker, Panel, Plot, PlotError, Preset, Series,
};
use crate::engine::event::EventOptions;
use crate::scene::Scene;
use crate::signal::SignalSpec;
use std::fmt::Write as _;

/// The figure's name (and file stem in `plots/`).
pub const NAME: &str = "work_precision";

/// Steps per period of the highest harmonic of the paper's section 7.
pub const PAPER_STEPS: u32 = 5000;

/// One scene of the study: the paper's motor with a Fourier signal of
/// `harmonics` harmonics, `kappa`, sigma factors and a 25 µm stroke.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StudyScene {
    /// Its key in the data (`scene` column).
    pub key: &'static str,
    /// Its name in the figure's legend.
    pub name: &'static str,
    /// Number of harmonics `n`.
    pub harmonics: usize,
    /// `kappa`.
    pub kappa: f64,
}

impl StudyScene {
    /// The scene simulated.
    pub fn scene(&self) -> Scene {
        Scene {
            signal: SignalSpec::fourier(25e-6, self.kappa, self.harmonics, true),
            ..Scene::default()
        }
    }
}

/// The study's scenes: the default scene (slip-slip), a stick-heavy one
/// and one of many harmonics.
pub const SCENES: [StudyScene; 3] = [
    StudyScene {
        key: "default",
        name: "default scene",
        harmonics: 2,
        kappa: 36.0,
    },
    StudyScene {
        key: "stick_heavy",
        name: "stick-heavy",
        harmonics: 5,
        kappa: 0.36,
    },
    StudyScene {
        key: "many_harmonics",
        name: "many harmonics",
        harmonics: 12,
        kappa: 1.0,
    },
];

/// The engine and setting of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// The event engine with this event-time tolerance relative to `T`
    /// (`None`: its default, [`EventOptions::default`]).
    Event(Option<f64>),
    /// The fixed-step reference at this many steps per period of the
    /// highest harmonic.
    Fixed(u32),
}

impl Method {
    /// The setting in words, for a table.
    pub fn setting(self) -> String {
        match self {
            Method::Event(None) => "default".to_owned(),
            Method::Event(Some(t)) => format!("time tolerance {t:.0e}"),
            Method::Fixed(s) => format!("{s} steps"),
        }
    }
}

/// One run of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The scene's key ([`StudyScene::key`]).
    pub scene: String,
    /// Engine and setting.
    pub method: Method,
    /// Median wall time (s) of the set-up and the whole analysis.
    pub wall_time: f64,
    /// Runs the median is taken over.
    pub runs: usize,
    /// `v_inf` found (m/s).
    pub v_inf: f64,
    /// Relative error of `v_inf`: for the reference its difference to the
    /// event engine at default tolerances; for the event engine a bound.
    pub v_inf_error: f64,
    /// `p_0.99` found, if the start-up reached 99 %.
    pub startup_periods: Option<u64>,
    /// Relative error of `p_0.99` against the event engine's.
    pub startup_error: Option<f64>,
    /// Periods simulated.
    pub periods: u64,
    /// Events found.
    pub events: u64,
}

/// The columns of the data, in order.
const COLUMNS: [&str; 12] = [
    "scene",
    "engine",
    "steps_per_harmonic",
    "time_tolerance",
    "wall_time_s",
    "runs",
    "v_inf",
    "v_inf_error_rel",
    "startup_periods",
    "startup_error_rel",
    "periods",
    "events",
];

/// The runs as the figure's data: comment lines, a header and one row
/// per run.
pub fn csv(runs: &[Run]) -> String {
    let mut s = String::new();
    s.push_str("# Work-precision study (examples/work_precision.rs): one row per run.\n");
    s.push_str(
        "# v_inf_error_rel: fixed = |v_inf - v_inf(event, default)| / v_inf(event, default); \
         event = that difference plus the default run's error estimate (a bound).\n",
    );
    s.push_str(
        "# startup_error_rel: |p_0.99 - p_0.99(event, default)| / p_0.99(event, default). \
         wall_time_s: median over `runs` runs (machine dependent). SI units.\n",
    );
    s.push_str(&COLUMNS.join(","));
    s.push('\n');
    for r in runs {
        let (engine, steps, tol) = match r.method {
            Method::Event(t) => (
                "event",
                String::new(),
                format!("{:e}", t.unwrap_or(EventOptions::default().time_tolerance)),
            ),
            Method::Fixed(n) => ("fixed", n.to_string(), String::new()),
        };
        let _ = writeln!(
            s,
            "{},{engine},{steps},{tol},{:e},{},{:e},{:e},{},{},{},{}",
            r.scene,
            r.wall_time,
            r.runs,
            r.v_inf,
            r.v_inf_error,
            r.startup_periods.map_or(String::new(), |v| v.to_string()),
            r.startup_error.map_or(String::new(), |e| format!("{e:e}")),
            r.periods,
            r.events
        );
    }
    s
}

/// The runs of the data `text` (as [`csv()`] writes it; a figure's
/// `# caption:` lines are comments too).
pub fn parse(text: &str) -> Result<Vec<Run>, PlotError> {
    let bad = |reason: String| PlotError::Data {
        figure: NAME.to_owned(),
        reason,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with('#') && !l.trim().is_empty());
    let (_, header) = lines
        .next()
        .ok_or_else(|| bad("no header row".to_owned()))?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    if names != COLUMNS {
        return Err(bad(format!(
            "header `{header}`: expected the columns {}",
            COLUMNS.join(",")
        )));
    }
    let mut runs = Vec::new();
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let line_no = i + 1;
        if cells.len() != COLUMNS.len() {
            return Err(bad(format!(
                "line {line_no}: {} cells, expected {}",
                cells.len(),
                COLUMNS.len()
            )));
        }
        let cell = |c: usize| cells[c];
        let wrong = |c: usize, what: &str| {
            bad(format!(
                "line {line_no}, column {}: `{}` is not {what}",
                COLUMNS[c], cells[c]
            ))
        };
        let number = |c: usize| -> Result<f64, PlotError> {
            cell(c)
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v >= 0.0)
                .ok_or_else(|| wrong(c, "a finite number >= 0"))
        };
        let count = |c: usize| -> Result<u64, PlotError> {
            cell(c).parse::<u64>().map_err(|_| wrong(c, "a count"))
        };
        let optional = |c: usize| !cell(c).is_empty();
        let scene = cell(0);
        if !SCENES.iter().any(|s| s.key == scene) {
            return Err(wrong(0, "a scene of the study"));
        }
        let method = match cell(1) {
            "event" => {
                let t = number(3)?;
                let default = EventOptions::default().time_tolerance;
                Method::Event((t != default).then_some(t))
            }
            "fixed" => Method::Fixed(
                cell(2)
                    .parse::<u32>()
                    .ok()
                    .filter(|s| *s > 0)
                    .ok_or_else(|| wrong(2, "a positive count of steps"))?,
            ),
            _ => return Err(wrong(1, "`event` or `fixed`")),
        };
        let v_inf = cell(6)
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| wrong(6, "a finite number"))?;
        runs.push(Run {
            scene: scene.to_owned(),
            method,
            wall_time: number(4)?,
            runs: count(5)? as usize,
            v_inf,
            v_inf_error: number(7)?,
            startup_periods: if optional(8) { Some(count(8)?) } else { None },
            startup_error: if optional(9) { Some(number(9)?) } else { None },
            periods: count(10)?,
            events: count(11)?,
        });
    }
    if runs.is_empty() {
        return Err(bad("no runs below the header".to_owned()));
    }
    Ok(runs)
}

/// The study as last measured: `plots/work_precision.svg.csv`.
pub fn committed() -> Result<Vec<Run>, PlotError> {
    parse(include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/plots/work_precision.svg.csv"
    )))
}

/// Markers of the event engine's points, one per scene.
const EVENT_MARKERS: [Marker; 3] = [Marker::Triangle, Marker::Diamond, Marker::TriangleDown];

/// Decades around the positive values (at least one decade).
fn decades(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = super::min_max(values.into_iter().filter(|v| *v > 0.0 && v.is_finite()));
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.1, 1.0);
    }
    let (a, b) = (lo.log10().floor(), hi.log10().ceil());
    (10f64.powf(a), 10f64.powf(b.max(a + 1.0)))
}

/// The work-precision figure of `runs` (see the module doc) laid out for
/// `preset`: its two panels side by side, or stacked in a single column,
/// where side by side they would leave the seven legend entries a third
/// of the height.
pub fn figure(runs: &[Run], preset: Preset) -> Result<Figure, PlotError> {
    let index = |r: &Run| SCENES.iter().position(|s| s.key == r.scene);
    if let Some(r) = runs.iter().find(|r| index(r).is_none()) {
        return Err(PlotError::Data {
            figure: NAME.to_owned(),
            reason: format!("scene `{}` is not a scene of the study", r.scene),
        });
    }
    let drawable = |v: Option<f64>| v.filter(|v| *v > 0.0 && v.is_finite());
    let wall = Axis::log(
        "wall time $t_{wall}$ (s)",
        decades(runs.iter().map(|r| r.wall_time)),
    );
    let mut v = Panel::new(
        Some("(a) steady-state velocity $v_∞$"),
        wall.clone(),
        Axis::log(
            "relative error of $v_∞$",
            decades(runs.iter().map(|r| r.v_inf_error).chain([1.0])),
        ),
    );
    let mut startup = Panel::new(
        Some("(b) start-up time $Tp_{0.99}$"),
        wall,
        Axis::log(
            "relative error of $Tp_{0.99}$",
            decades(runs.iter().filter_map(|r| r.startup_error).chain([1.0])),
        ),
    );
    let values: [fn(&Run) -> Option<f64>; 2] = [|r| Some(r.v_inf_error), |r| r.startup_error];
    for (panel, value) in [&mut v, &mut startup].into_iter().zip(values) {
        for (ci, scene) in SCENES.iter().enumerate() {
            let of_scene = || runs.iter().filter(|r| r.scene == scene.key);
            // The reference's curve, broken where a point is not drawable.
            let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for r in of_scene().filter(|r| matches!(r.method, Method::Fixed(_))) {
                match drawable(value(r)) {
                    Some(e) => pieces.last_mut().expect("a piece").push((r.wall_time, e)),
                    None => pieces.push(Vec::new()),
                }
            }
            pieces.retain(|p| !p.is_empty());
            panel.series.push(Series {
                label: Some(format!("{}: reference", scene.name)),
                pieces,
                look: Look::nth(ci).with_marker(Marker::Circle),
                kind: Kind::Curve,
            });
            let event: Vec<(f64, f64)> = of_scene()
                .filter(|r| matches!(r.method, Method::Event(_)))
                .filter_map(|r| Some((r.wall_time, drawable(value(r))?)))
                .collect();
            panel.series.push(Series::points(
                Some(&format!("{}: event engine", scene.name)),
                event,
                Look::nth_points(ci).with_marker(EVENT_MARKERS[ci]),
            ));
        }
    }
    // The paper's resolution: a square in place of the reference's dot,
    // in every scene (no text in the panel, where the curves leave no
    // room for it in every preset).
    for (ci, scene) in SCENES.iter().enumerate() {
        let at: Vec<(f64, f64)> = runs
            .iter()
            .filter(|r| r.scene == scene.key && r.method == Method::Fixed(PAPER_STEPS))
            .filter_map(|r| Some((r.wall_time, drawable(Some(r.v_inf_error))?)))
            .collect();
        v.series.push(Series::points(
            None,
            at,
            Look::nth_points(ci).with_marker(Marker::Square),
        ));
    }
    let mut notes = vec![
        format!(
            "Reference: {} steps per period of the highest harmonic, left to right; squares: \
             the paper's {PAPER_STEPS}.",
            resolutions(runs)
        ),
        "Event errors are bounds; wall times are medians and machine dependent.".to_owned(),
    ];
    notes.extend(zero_startup_note(runs));
    let columns = if preset == Preset::SingleColumn { 1 } else { 2 };
    let mut plot = Plot::grid(vec![v, startup], columns, 0.8).with_notes(notes);
    plot.legend.push(LegendEntry {
        label: format!("reference at {PAPER_STEPS} steps (paper)"),
        look: Look {
            color: super::style::GREY,
            ..Look::nth_points(0).with_marker(Marker::Square)
        },
        kind: Kind::Points,
    });
    Ok(Figure {
        name: NAME.to_owned(),
        plot,
        csv: csv(runs),
        preset,
    })
}

/// The reference's resolutions in the runs, as a list.
fn resolutions(runs: &[Run]) -> String {
    let mut steps: Vec<u32> = runs
        .iter()
        .filter_map(|r| match r.method {
            Method::Fixed(s) => Some(s),
            Method::Event(_) => None,
        })
        .collect();
    steps.sort_unstable();
    steps.dedup();
    steps
        .iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Which start-up errors are exactly zero (and so not drawn).
fn zero_startup_note(runs: &[Run]) -> Option<String> {
    let zero = |r: &Run| r.startup_error == Some(0.0);
    let mut parts = Vec::new();
    let events: Vec<&Run> = runs
        .iter()
        .filter(|r| matches!(r.method, Method::Event(_)))
        .collect();
    if !events.is_empty() && events.iter().all(|r| zero(r)) {
        parts.push("event engine: every scene and tolerance".to_owned());
    }
    for scene in &SCENES {
        let fixed: Vec<&Run> = runs
            .iter()
            .filter(|r| r.scene == scene.key && matches!(r.method, Method::Fixed(_)))
            .collect();
        let zeros: Vec<String> = fixed
            .iter()
            .filter(|r| zero(r))
            .filter_map(|r| match r.method {
                Method::Fixed(s) => Some(s.to_string()),
                Method::Event(_) => None,
            })
            .collect();
        if !fixed.is_empty() && zeros.len() == fixed.len() {
            parts.push(format!("{}, reference: every resolution", scene.name));
        } else if !zeros.is_empty() {
            parts.push(format!(
                "{}, reference: {} steps",
                scene.name,
                zeros.join(", ")
            ));
        }
    }
    (!parts.is_empty()).then(|| {
        format!(
            "Start-up error 0 (same p₀.₉₉), not drawn: {}",
            parts.join("; ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_study_reads_back_to_the_same_text() {
        // csv and parse are inverse: every number round-trips exactly.
        let runs = committed().unwrap();
        let text = csv(&runs);
        assert_eq!(parse(&text).unwrap(), runs);
        assert_eq!(csv(&parse(&text).unwrap()), text);
        // Every scene of the study, its event engine at the default and
        // three looser tolerances.
        for scene in &SCENES {
            let events = runs
                .iter()
                .filter(|r| r.scene == scene.key && matches!(r.method, Method::Event(_)))
                .count();
            assert_eq!(events, 4, "{}", scene.key);
        }
    }

    #[test]
    fn the_default_study_scene_is_the_default_scene() {
        assert_eq!(SCENES[0].scene(), Scene::default());
    }

    #[test]
    fn a_bad_cell_is_named_by_line_column_and_value() {
        let good = csv(&committed().unwrap());
        let bad = good.replacen(",fixed,10,", ",fixed,ten,", 1);
        let e = parse(&bad).unwrap_err().to_string();
        assert!(
            e.contains("column steps_per_harmonic") && e.contains("`ten`") && e.contains("line "),
            "{e}"
        );
        let e = parse(&good.replace("wall_time_s", "wall")).unwrap_err();
        assert!(e.to_string().contains("header"), "{e}");
        let e = parse(&good.replacen("stick_heavy,", "unknown,", 1)).unwrap_err();
        assert!(e.to_string().contains("`unknown`"), "{e}");
    }
}
