//! Work-precision study: error against wall time for the exact event engine
//! and the fixed-step reference (`engine::fixed_step`, first-order
//! Moreau-Jean), on three scenes with the paper's motor:
//!
//! * the default scene (n = 2, sqrt(kappa) = 6, sigma factors; slip-slip),
//! * a stick-heavy scene (n = 5, kappa = 0.36, sigma factors),
//! * many harmonics (n = 12, kappa = 1, sigma factors).
//!
//! The reference runs at 10 to 10^5 steps per period of the highest
//! harmonic, the event engine at its default tolerances and at looser event
//! time tolerances (`EventOptions::time_tolerance` 1e-10, 1e-7, 1e-4 of `T`).
//!
//! `cargo run --release --example work_precision`
//!
//! prints a table and writes `plots/work_precision.svg` (drawn with the
//! library's plotting kit, `stickslip::plot`, double-column preset; log-log relative
//! error of `v_inf` and of the start-up time `T p_0.99` against wall time)
//! and `plots/work_precision.svg.csv` (every point drawn).
//!
//! **Errors.** The event engine at default tolerances is the reference
//! value. For the fixed-step runs the error is the difference to it; for
//! the event engine it is bounded by its own error estimate (default run)
//! or by the difference to the default run plus that estimate (looser
//! runs), and the plot shows that bound. A start-up error of exactly zero
//! (the same `p_0.99`, which is an integer) cannot be drawn on log axes and
//! is left out of the figure (it is in the CSV).
//!
//! **Timing.** A wall time is the median over repeated runs of the engine's
//! set-up plus the whole analysis (transient, steady state, indicators), in
//! this process, one run at a time. The headline ratio (reference at 5000
//! steps against the event engine on the default scene) interleaves the two
//! engines' runs. Wall times depend on the machine and its load, so the
//! time columns of the CSV and the figure differ from run to run; every
//! other column is the same on every run.

use std::fmt::Write as _;
use std::time::Instant;
use stickslip::PeriodEngine;
use stickslip::RunReport;
use stickslip::SignalSpec;
use stickslip::plot::{Anchor, Axis, Figure, Kind, Look, Marker, Panel, Plot, Preset, Series};
use stickslip::{EventEngine, EventOptions};
use stickslip::{FixedStepEngine, FixedStepOptions};
use stickslip::{Motor, Scene, Signal};

/// Steps per period of the highest harmonic for the reference.
const STEPS: [u32; 13] = [
    10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10_000, 20_000, 50_000, 100_000,
];
/// Event-time tolerances (relative to `T`) beyond the default `4 eps`.
const TIME_TOLERANCES: [f64; 3] = [1e-10, 1e-7, 1e-4];
/// The paper's resolution, compared with the event engine in the summary.
const PAPER_STEPS: u32 = 5000;

struct Case {
    /// Short name for the table and CSV.
    key: &'static str,
    /// Legend text.
    label: &'static str,
    scene: Scene,
}

fn cases() -> Vec<Case> {
    let fourier = |kappa: f64, n: usize| SignalSpec::fourier(25e-6, kappa, n, true);
    let with = |spec| Scene {
        signal: spec,
        ..Scene::default()
    };
    vec![
        Case {
            key: "default",
            label: "default scene: n = 2, sqrt(kappa) = 6",
            scene: Scene::default(),
        },
        Case {
            key: "stick_heavy",
            label: "stick-heavy: n = 5, kappa = 0.36",
            scene: with(fourier(0.36, 5)),
        },
        Case {
            key: "many_harmonics",
            label: "many harmonics: n = 12, kappa = 1",
            scene: with(fourier(1.0, 12)),
        },
    ]
}

#[derive(Clone, Copy, PartialEq)]
enum Engine {
    /// The event engine with this event-time tolerance (`None`: default).
    Event(Option<f64>),
    /// The reference at this many steps per harmonic period.
    Fixed(u32),
}

impl Engine {
    fn setting(self) -> String {
        match self {
            Engine::Event(None) => "default".to_owned(),
            Engine::Event(Some(t)) => format!("time_tol {t:.0e}"),
            Engine::Fixed(s) => format!("{s} steps"),
        }
    }
}

/// One point of the study.
struct Point {
    case: usize,
    engine: Engine,
    wall: f64,
    runs: usize,
    v_inf: f64,
    /// Relative error of `v_inf` (fixed: measured; event: bound).
    v_error: f64,
    startup_periods: Option<u64>,
    /// Relative error of the start-up time.
    startup_error: Option<f64>,
    periods: u64,
    events: u64,
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// One run: engine set-up plus analysis, timed.
fn run_once(
    signal: &Signal,
    motor: &Motor,
    scene: &Scene,
    engine: Engine,
) -> Result<(RunReport, f64), stickslip::Error> {
    fn go<E: PeriodEngine>(
        e: E,
        scene: &Scene,
        motor: &Motor,
    ) -> Result<RunReport, stickslip::Error> {
        stickslip::run_with(e, scene, motor)
    }
    let clock = Instant::now();
    let report = match engine {
        Engine::Event(tol) => {
            let options = EventOptions {
                time_tolerance: tol.unwrap_or(EventOptions::default().time_tolerance),
                ..EventOptions::default()
            };
            go(EventEngine::new(signal, motor, options), scene, motor)?
        }
        Engine::Fixed(steps) => {
            let options = FixedStepOptions {
                steps_per_harmonic: steps,
                ..FixedStepOptions::default()
            };
            go(FixedStepEngine::new(signal, motor, options), scene, motor)?
        }
    };
    Ok((report, clock.elapsed().as_secs_f64()))
}

/// Median wall time over enough runs to fill about a second (3 to 9 runs;
/// a single run when one takes longer than a second). A run without a
/// steady state (a coarse reference may not settle) is an error.
fn measure(
    signal: &Signal,
    motor: &Motor,
    scene: &Scene,
    engine: Engine,
) -> Result<(RunReport, f64, usize), stickslip::Error> {
    let (report, first) = run_once(signal, motor, scene, engine)?;
    let runs = if first > 1.0 {
        1
    } else {
        ((1.0 / first).ceil() as usize).clamp(3, 9)
    };
    let mut times = vec![first];
    for _ in 1..runs {
        times.push(run_once(signal, motor, scene, engine)?.1);
    }
    Ok((report, median(times), runs))
}

fn relative(value: f64, exact: f64) -> f64 {
    ((value - exact) / exact).abs()
}

fn main() {
    let cases = cases();
    let mut points = Vec::new();
    let mut summary = String::new();
    for (ci, case) in cases.iter().enumerate() {
        let (signal, motor) = stickslip::build(&case.scene).expect("valid scene");
        let (exact, wall, runs) = measure(&signal, &motor, &case.scene, Engine::Event(None))
            .expect("the event engine runs");
        let v_exact = exact.indicators.v_inf;
        let bound = exact.error.v_inf.unwrap_or(0.0);
        let p_exact = exact.startup_periods;
        let startup_error = |p: Option<u64>| match (p, p_exact) {
            (Some(p), Some(q)) => Some((p as f64 - q as f64).abs() / q as f64),
            _ => None,
        };
        let point = |engine, report: &RunReport, wall, runs, v_error| Point {
            case: ci,
            engine,
            wall,
            runs,
            v_inf: report.indicators.v_inf,
            v_error,
            startup_periods: report.startup_periods,
            startup_error: startup_error(report.startup_periods),
            periods: report.work.periods,
            events: report.work.events.total(),
        };
        points.push(point(
            Engine::Event(None),
            &exact,
            wall,
            runs,
            bound / v_exact.abs(),
        ));
        for tol in TIME_TOLERANCES {
            let engine = Engine::Event(Some(tol));
            let (r, wall, runs) =
                measure(&signal, &motor, &case.scene, engine).expect("the event engine runs");
            let v_error = ((r.indicators.v_inf - v_exact).abs() + bound) / v_exact.abs();
            points.push(point(engine, &r, wall, runs, v_error));
        }
        for steps in STEPS {
            let engine = Engine::Fixed(steps);
            let (r, wall, runs) = match measure(&signal, &motor, &case.scene, engine) {
                Ok(m) => m,
                Err(e) => {
                    println!("{} {}: {e}: left out", case.key, engine.setting());
                    continue;
                }
            };
            let v_error = relative(r.indicators.v_inf, v_exact);
            points.push(point(engine, &r, wall, runs, v_error));
        }
        if ci == 0 {
            summary = headline(&signal, &motor, &case.scene, v_exact, bound);
        }
    }
    print!("{}", table(&cases, &points));
    println!();
    print!("{summary}");
    let figure = figure(&cases, &points, csv(&cases, &points));
    // Its data are timings, so it is not in the figure registry: the
    // reviewer's checks (`stickslip::plot::review`) run here. In its own
    // preset it must pass them; what they find in the others is printed.
    for preset in Preset::ALL {
        let findings = stickslip::plot::review::review(&figure.marks(&preset.style()));
        let text = findings
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join("\n  ");
        assert!(
            preset != figure.preset || findings.is_empty(),
            "work_precision ({preset}):\n  {text}"
        );
        if !findings.is_empty() {
            println!("reviewer, work_precision at {preset}:\n  {text}");
        }
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("plots");
    figure.write_to(&dir).expect("plots/ is writable");
    println!("wrote plots/work_precision.svg and plots/work_precision.svg.csv");
}

/// The reference at the paper's resolution against the event engine on the
/// default scene, interleaved in this process.
fn headline(signal: &Signal, motor: &Motor, scene: &Scene, v_exact: f64, bound: f64) -> String {
    let pairs = 7;
    let (mut event_times, mut fixed_times) = (Vec::new(), Vec::new());
    let mut fixed_v = 0.0;
    for _ in 0..pairs {
        event_times.push(
            run_once(signal, motor, scene, Engine::Event(None))
                .expect("the event engine runs")
                .1,
        );
        let (r, t) = run_once(signal, motor, scene, Engine::Fixed(PAPER_STEPS))
            .expect("the reference at the paper's resolution runs");
        fixed_v = r.indicators.v_inf;
        fixed_times.push(t);
    }
    let (te, tf) = (median(event_times), median(fixed_times));
    let error_fixed = (fixed_v - v_exact).abs();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "default scene, {pairs} interleaved runs each (medians), in this process:"
    );
    let _ = writeln!(
        s,
        "  event engine:               {:9.3} ms, |error of v_inf| <= {bound:.1e} m/s (its estimate)",
        te * 1e3
    );
    let _ = writeln!(
        s,
        "  reference at {PAPER_STEPS} steps:    {:9.3} ms, |error of v_inf| =  {error_fixed:.1e} m/s (against the event engine)",
        tf * 1e3
    );
    let _ = writeln!(
        s,
        "  time ratio reference / event: {:.0}x (target >= 500x)",
        tf / te
    );
    let _ = writeln!(
        s,
        "  accuracy ratio: the event engine is at least {:.1e}x more accurate (target >= 1000x)",
        error_fixed / bound
    );
    s
}

fn table(cases: &[Case], points: &[Point]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<15} {:<6} {:<16} {:>11} {:>5} {:>22} {:>10} {:>7} {:>10} {:>8} {:>9}",
        "scene",
        "engine",
        "setting",
        "wall (s)",
        "runs",
        "v_inf (m/s)",
        "rel.err",
        "p_0.99",
        "rel.err",
        "periods",
        "events"
    );
    for p in points {
        let engine = match p.engine {
            Engine::Event(_) => "event",
            Engine::Fixed(_) => "fixed",
        };
        let _ = writeln!(
            s,
            "{:<15} {:<6} {:<16} {:>11.3e} {:>5} {:>22.15e} {:>10.2e} {:>7} {:>10} {:>8} {:>9}",
            cases[p.case].key,
            engine,
            p.engine.setting(),
            p.wall,
            p.runs,
            p.v_inf,
            p.v_error,
            p.startup_periods.map_or("-".to_owned(), |v| v.to_string()),
            p.startup_error
                .map_or("-".to_owned(), |e| format!("{e:.2e}")),
            p.periods,
            p.events
        );
    }
    s
}

fn csv(cases: &[Case], points: &[Point]) -> String {
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
    s.push_str(
        "scene,engine,steps_per_harmonic,time_tolerance,wall_time_s,runs,v_inf,\
         v_inf_error_rel,startup_periods,startup_error_rel,periods,events\n",
    );
    for p in points {
        let (engine, steps, tol) = match p.engine {
            Engine::Event(t) => (
                "event",
                String::new(),
                format!("{:e}", t.unwrap_or(EventOptions::default().time_tolerance)),
            ),
            Engine::Fixed(n) => ("fixed", n.to_string(), String::new()),
        };
        let _ = writeln!(
            s,
            "{},{engine},{steps},{tol},{:e},{},{:e},{:e},{},{},{},{}",
            cases[p.case].key,
            p.wall,
            p.runs,
            p.v_inf,
            p.v_error,
            p.startup_periods.map_or(String::new(), |v| v.to_string()),
            p.startup_error.map_or(String::new(), |e| format!("{e:e}")),
            p.periods,
            p.events
        );
    }
    s
}

// ------------------------------------------------------------- figure ----

/// The figure, drawn with the library's plotting kit (`stickslip::plot`):
/// per scene, the reference as a line with dots and the event engine as
/// markers, both panels on log-log axes.
fn figure(cases: &[Case], points: &[Point], csv: String) -> Figure {
    let wall = Axis::log("wall time $t_{wall}$ (s)", (1e-5, 1e1));
    let mut v = Panel::new(
        Some("(a) steady-state velocity $v_∞$"),
        wall.clone(),
        Axis::log("relative error of $v_∞$", (1e-16, 1.0)),
    );
    // First order: error ∝ steps^-1 ∝ wall time^-1.
    v.series.push(Series::line(
        Some("slope −1 (first order)"),
        vec![(3e-5, 1e-6), (3e-3, 1e-8)],
        Look::reference(),
    ));
    let mut startup = Panel::new(
        Some("(b) start-up time $Tp_{0.99}$"),
        wall,
        Axis::log("relative error of $Tp_{0.99}$", (1e-4, 1.0)),
    );
    let values: [fn(&Point) -> Option<f64>; 2] = [|p| Some(p.v_error), |p| p.startup_error];
    for (panel, value) in [&mut v, &mut startup].into_iter().zip(values) {
        let drawable = |p: &Point| {
            value(p)
                .filter(|v| *v > 0.0 && v.is_finite())
                .map(|v| (p.wall, v))
        };
        for (ci, case) in cases.iter().enumerate() {
            let name = case.label.split(':').next().unwrap_or(case.key);
            // The reference's curve, broken where a point is not drawable.
            let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for p in points
                .iter()
                .filter(|p| p.case == ci && matches!(p.engine, Engine::Fixed(_)))
            {
                match drawable(p) {
                    Some(xy) => pieces.last_mut().expect("a piece").push(xy),
                    None => pieces.push(Vec::new()),
                }
            }
            panel.series.push(Series {
                label: Some(format!("{name}: reference")),
                pieces,
                look: Look::nth(ci).with_marker(Marker::Circle),
                kind: Kind::Curve,
            });
            let event: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.case == ci && matches!(p.engine, Engine::Event(_)))
                .filter_map(drawable)
                .collect();
            panel.series.push(Series::points(
                Some(&format!("{name}: event engine")),
                event,
                Look::nth_points(ci).with_marker(EVENT_MARKERS[ci]),
            ));
        }
    }
    // Step counts beside the default scene's reference points.
    for p in points.iter().filter(|p| p.case == 0) {
        if let Engine::Fixed(s) = p.engine
            && [10, 100, 1000, PAPER_STEPS, 100_000].contains(&s)
            && p.v_error > 0.0
        {
            let text = if s == PAPER_STEPS {
                format!("{s} (paper)")
            } else {
                s.to_string()
            };
            // Above and right of the point (the curve falls to the right),
            // never so high that the text meets the panel's top.
            v.note(
                (p.wall * 1.4, (p.v_error * 2.0).min(0.1)),
                &text,
                Anchor::Start,
            );
        }
    }
    let mut notes = vec![
        "Reference: 10 to 10⁵ steps per period of the highest harmonic (labels: steps, default scene).".to_owned(),
        "Event errors are bounds; wall times are medians and machine dependent.".to_owned(),
    ];
    notes.extend(zero_startup_notes(cases, points));
    Figure {
        name: "work_precision".to_owned(),
        plot: Plot::grid(vec![v, startup], 2, 0.8).with_notes(notes),
        csv,
        preset: Preset::DoubleColumn,
    }
}

/// Markers of the event engine's points, one per scene.
const EVENT_MARKERS: [Marker; 3] = [Marker::Triangle, Marker::Diamond, Marker::TriangleDown];

/// Which start-up errors are exactly zero (and so not drawn).
fn zero_startup_notes(cases: &[Case], points: &[Point]) -> Vec<String> {
    let mut notes = vec!["Start-up error 0 (same p₀.₉₉), not drawn:".to_owned()];
    let zero = |p: &Point| p.startup_error == Some(0.0);
    let events: Vec<&Point> = points
        .iter()
        .filter(|p| matches!(p.engine, Engine::Event(_)))
        .collect();
    if events.iter().all(|p| zero(p)) {
        notes.push("event engine: every scene and tolerance".to_owned());
    }
    for (ci, case) in cases.iter().enumerate() {
        let fixed: Vec<&Point> = points
            .iter()
            .filter(|p| p.case == ci && matches!(p.engine, Engine::Fixed(_)))
            .collect();
        let zeros: Vec<String> = fixed
            .iter()
            .filter(|p| zero(p))
            .filter_map(|p| match p.engine {
                Engine::Fixed(s) => Some(s.to_string()),
                Engine::Event(_) => None,
            })
            .collect();
        let name = case.label.split(':').next().unwrap_or(case.key);
        if zeros.len() == fixed.len() {
            notes.push(format!("{name}, reference: every resolution"));
        } else if !zeros.is_empty() {
            notes.push(format!("{name}, reference: {} steps", zeros.join(", ")));
        }
    }
    vec![notes.join("; ").replacen(":;", ":", 1)]
}
