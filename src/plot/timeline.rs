//! The event timeline: the slider's modes over the start-up from rest.
//!
//! * (a) A stick-heavy signal (`n = 5`, `kappa = 0.36`, sigma factors),
//!   whose acceleration stays inside the stick band for long phases: rod
//!   and slider velocity over the first periods, the slider's curve
//!   coloured by mode, every event marked.
//! * (b) The paper's default signal (`n = 2`, `sqrt(kappa) = 6`, sigma
//!   factors): a raster of the modes, one row per period from `p = 1`
//!   past `p_0.99`, against the phase in the period. The slider speeds up
//!   over hundreds of periods; as it does, the forward slip (rod faster
//!   than slider) shrinks and the backward slip grows, until the pattern
//!   stops changing. It never sticks (section 7: "almost completely using
//!   sliding friction").
//!
//! Both come from the exact segments and the event log of the event
//! engine run period by period from rest.

use super::style::{GREY, PALETTE};
use super::{
    Axis, Cell, Csv, Dash, Figure, Kind, Look, Marker, Panel, Plot, PlotError, Preset, Series,
    min_max, padded,
};
use crate::engine::Observer;
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{Direction, EventKind, Mode, PeriodEngine, PeriodStart, Segment};
use crate::scene::Scene;
use crate::signal::{Signal, SignalSpec};
use crate::simulation;

/// A sample of the exact motion, for drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sample {
    /// Phase in the period (s).
    pub phase: f64,
    /// Rod velocity (m/s).
    pub v_rod: f64,
    /// Slider velocity (m/s).
    pub v_slider: f64,
    /// The slider's mode on the segment the sample belongs to.
    pub mode: Mode,
}

/// Samples each segment at its ends and about `per_period` points per
/// period inside; the slider velocity is exact (linear in slip, the rod's
/// in stick). Returns one polyline per segment.
pub(crate) fn sample_segments(
    segments: &[Segment],
    signal: &Signal,
    per_period: usize,
) -> Vec<Vec<Sample>> {
    let period = signal.period();
    segments
        .iter()
        .map(|s| {
            let inner = ((s.duration() / period) * per_period as f64).ceil() as usize;
            let count = inner.max(1) + 1;
            (0..count)
                .map(|i| {
                    let phase = if i + 1 == count {
                        s.end
                    } else {
                        s.start + s.duration() * i as f64 / (count - 1) as f64
                    };
                    // Segment ends use the engine's own (left/right limit)
                    // values; inner points the signal.
                    let v_rod = if i == 0 {
                        s.rod_start.v
                    } else if i + 1 == count {
                        s.rod_end.v
                    } else {
                        signal.velocity(phase)
                    };
                    let v_slider = match s.mode {
                        Mode::Stick => v_rod,
                        Mode::Slip(_) if i + 1 == count => s.slider_end.v,
                        Mode::Slip(_) => s.slider_start.v + s.slip_acceleration * (phase - s.start),
                    };
                    Sample {
                        phase,
                        v_rod,
                        v_slider,
                        mode: s.mode,
                    }
                })
                .collect()
        })
        .collect()
}

/// Segments in time order, each with the event that ended it (`None`: the
/// period ended).
#[derive(Debug, Default)]
struct Timeline {
    segments: Vec<Segment>,
    ends: Vec<Option<EventKind>>,
}

impl Observer for Timeline {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        self.segments.push(*segment);
        self.ends.push(None);
    }
    fn event(&mut self, event: &crate::engine::Event) {
        if let Some(last) = self.ends.last_mut() {
            *last = Some(event.kind);
        }
    }
}

fn event_name(kind: &EventKind) -> &'static str {
    match kind {
        EventKind::StickToSlip {
            to: Direction::Forward,
        } => "stick_to_slip_forward",
        EventKind::StickToSlip {
            to: Direction::Backward,
        } => "stick_to_slip_backward",
        EventKind::SlipToStick => "slip_to_stick",
        EventKind::Reversal {
            to: Direction::Forward,
        } => "reversal_to_forward",
        EventKind::Reversal {
            to: Direction::Backward,
        } => "reversal_to_backward",
        EventKind::Grazing { .. } => "grazing",
        EventKind::Jump { .. } => "jump",
        EventKind::ContactStart => "contact_start",
        EventKind::ContactEnd => "contact_end",
    }
}

/// The look of the slider's curve in a mode: distinct dash patterns, and
/// colours of distinct lightness (black, blue, orange) so that the raster
/// of panel (b) reads in greyscale too.
pub(crate) fn mode_look(mode: Mode) -> Look {
    match mode {
        Mode::Stick => Look::line(PALETTE[0], Dash::Solid).weighted(1.6),
        Mode::Slip(Direction::Forward) => Look::line(PALETTE[1], Dash::Dashed).weighted(1.3),
        Mode::Slip(Direction::Backward) => Look::line(PALETTE[5], Dash::Dotted).weighted(1.6),
    }
}

fn mode_label(mode: Mode) -> &'static str {
    match mode {
        Mode::Stick => "stick",
        Mode::Slip(Direction::Forward) => "slip forward",
        Mode::Slip(Direction::Backward) => "slip backward",
    }
}

const MODES: [Mode; 3] = [
    Mode::Stick,
    Mode::Slip(Direction::Forward),
    Mode::Slip(Direction::Backward),
];

/// Runs `periods` periods from rest and returns the timeline and the
/// signal.
fn record(scene: &Scene, periods: u64, figure: &str) -> Result<(Timeline, Signal), PlotError> {
    let (signal, motor) = simulation::build_prescribed(scene, "the timeline figure")
        .map_err(PlotError::simulation(figure))?;
    let mut timeline = Timeline::default();
    {
        let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
        let mut start = PeriodStart {
            velocity: 0.0,
            mode: None,
        };
        for p in 1..=periods {
            let end = engine
                .run_period(p, start, &mut timeline)
                .map_err(|e| PlotError::simulation(figure)(e.into()))?;
            start = PeriodStart {
                velocity: end.velocity,
                mode: Some(end.mode),
            };
        }
    }
    Ok((timeline, signal))
}

/// [`record`], and `p_0.99` of the full run.
fn simulate(
    scene: &Scene,
    periods: u64,
    figure: &str,
) -> Result<(Timeline, Signal, Option<u64>), PlotError> {
    let (timeline, signal) = record(scene, periods, figure)?;
    let report = simulation::steady(scene).map_err(PlotError::simulation(figure))?;
    Ok((timeline, signal, report.startup_periods))
}

fn fourier(kappa: f64, n: usize, sigma: bool) -> SignalSpec {
    SignalSpec::fourier(25e-6, kappa, n, sigma)
}

/// The event timeline figure for the base scene's motor.
pub fn event_timeline(base: &Scene) -> Result<Figure, PlotError> {
    const NAME: &str = "event_timeline";
    let mut scene_a = base.clone();
    scene_a.signal = fourier(0.36, 5, true);
    scene_a.actuator = None;
    scene_a.outputs.indicators = vec![
        crate::indicator::Indicator::VInf,
        crate::indicator::Indicator::StartupTime,
    ];
    let mut scene_b = scene_a.clone();
    scene_b.signal = fourier(36.0, 2, true);
    let periods_a = 5;
    let (tl_a, sig_a, p99_a) = simulate(&scene_a, periods_a, NAME)?;
    let p99_b = simulate(&scene_b, 1, NAME)?.2.unwrap_or(400);
    let periods_b = (p99_b + p99_b / 10).max(20);
    let (tl_b, sig_b, _) = simulate(&scene_b, periods_b, NAME)?;

    let mut csv = Csv::new(
        &[
            "Event timeline: every exact segment of the motion from rest, with its mode and the event that ends it",
            "(period_end: the period ended). Motor of the paper; scene a: n = 5, kappa = 0.36, sigma; scene b: n = 2, sqrt(kappa) = 6, sigma.",
            &format!(
                "Periods: a {periods_a} (T = {:e} s, p_0.99 = {}), b {periods_b} (T = {:e} s, p_0.99 = {}). Phases in s within the period.",
                sig_a.period(),
                p99_a.map_or("none".to_owned(), |p| p.to_string()),
                sig_b.period(),
                p99_b
            ),
        ],
        &[
            "scene",
            "period",
            "start_phase_s",
            "end_phase_s",
            "mode",
            "ends_with",
            "slider_v_start_m_per_s",
            "slider_v_end_m_per_s",
        ],
    );
    for (label, tl) in [("a", &tl_a), ("b", &tl_b)] {
        for (s, end) in tl.segments.iter().zip(&tl.ends) {
            csv.row(&[
                Cell::S(label),
                Cell::I(s.period as i64),
                Cell::F(s.start),
                Cell::F(s.end),
                Cell::S(s.mode.name()),
                Cell::S(end.as_ref().map_or("period_end", event_name)),
                Cell::F(s.slider_start.v),
                Cell::F(s.slider_end.v),
            ]);
        }
    }

    // (a): velocities over absolute time.
    let period_a = sig_a.period();
    let samples = sample_segments(&tl_a.segments, &sig_a, 400);
    let abs_t = |seg: &Segment, phase: f64| (seg.period - 1) as f64 * period_a + phase;
    let t_end = periods_a as f64 * period_a;
    let (lo, hi) = min_max(samples.iter().flatten().flat_map(|s| [s.v_rod, s.v_slider]));
    let mut a = Panel::new(
        Some("(a) $n$ = 5, $κ$ = 0.36, $σ$: velocities from rest"),
        Axis::linear("time $t$ (ms)", (0.0, t_end * 1e3)).scaled(1e3),
        Axis::linear("velocity $v$ (m/s)", padded(lo, hi, 0.06)),
    );
    a.series.push(Series {
        label: Some("rod velocity".to_owned()),
        pieces: vec![
            tl_a.segments
                .iter()
                .zip(&samples)
                .flat_map(|(seg, ss)| ss.iter().map(move |s| (abs_t(seg, s.phase), s.v_rod)))
                .collect(),
        ],
        look: Look::line(GREY, Dash::DashDot).weighted(0.8),
        kind: Kind::Curve,
    });
    for mode in MODES {
        let pieces: Vec<Vec<(f64, f64)>> = tl_a
            .segments
            .iter()
            .zip(&samples)
            .filter(|(seg, _)| seg.mode == mode)
            .map(|(seg, ss)| {
                // A slip segment is a straight line: its ends draw it exactly.
                let keep: Vec<&Sample> = match mode {
                    Mode::Stick => ss.iter().collect(),
                    Mode::Slip(_) => [ss.first(), ss.last()].into_iter().flatten().collect(),
                };
                keep.into_iter()
                    .map(|s| (abs_t(seg, s.phase), s.v_slider))
                    .collect()
            })
            .collect();
        a.series.push(Series {
            label: Some(format!("slider: {}", mode_label(mode))),
            pieces,
            look: mode_look(mode),
            kind: Kind::Curve,
        });
    }
    let events: Vec<Vec<(f64, f64)>> = tl_a
        .segments
        .iter()
        .zip(&tl_a.ends)
        .filter(|(_, e)| e.is_some())
        .map(|(seg, _)| vec![(abs_t(seg, seg.end), seg.slider_end.v)])
        .collect();
    a.series.push(Series {
        label: Some("event".to_owned()),
        pieces: events,
        look: Look::nth_points(0).with_marker(Marker::Circle),
        kind: Kind::Points,
    });
    if let Some(p) = p99_a {
        let t = p as f64 * period_a;
        a.series.push(Series::line(
            Some("end of the start-up, $p_{0.99}$"),
            vec![(t, -1e3), (t, 1e3)],
            Look::reference(),
        ));
    }

    // (b): raster of modes, one row per period.
    let b = raster(
        Some("(b) $n$ = 2, √$κ$ = 6, $σ$: modes, one row per period"),
        &tl_b,
        &sig_b,
        periods_b,
        Some(p99_b),
    );

    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(vec![a, b], 1, 0.45),
        csv: csv.finish(),
        preset: Preset::DoubleColumn,
    })
}

/// A raster of the slider's modes, one row per period from `p = 1`, with
/// `p_0.99` marked. Beside a panel of the slider's curves (`title` given),
/// whose legend names the same modes, the raster's entries say
/// `raster: `; alone, they name the mode only.
fn raster(
    title: Option<&str>,
    tl: &Timeline,
    signal: &Signal,
    periods: u64,
    p99: Option<u64>,
) -> Panel {
    let period = signal.period();
    let (scale, unit) = if period < 1e-3 {
        (1e6, "µs")
    } else {
        (1e3, "ms")
    };
    let mut b = Panel::new(
        title,
        Axis::linear(
            &format!("time in the period $t$ ({unit})"),
            (0.0, period * scale),
        )
        .scaled(scale),
        Axis::linear(&super::sym("p").label(), (0.0, periods as f64)).integers(),
    );
    for mode in MODES {
        let rects: Vec<[(f64, f64); 2]> = tl
            .segments
            .iter()
            .filter(|s| s.mode == mode && s.end > s.start)
            .map(|s| [(s.start, (s.period - 1) as f64), (s.end, s.period as f64)])
            .collect();
        if !rects.is_empty() {
            b.series.push(Series::bands(
                Some(&match title {
                    Some(_) => format!("raster: {}", mode_label(mode)),
                    None => mode_label(mode).to_owned(),
                }),
                rects,
                mode_look(mode),
            ));
        }
    }
    if let Some(p) = p99 {
        b.series.push(Series::hline(
            Some("end of the start-up, $p_{0.99}$"),
            p as f64,
            (0.0, period),
            Look::reference(),
        ));
    }
    b
}

/// Most periods the scene timeline draws (one raster row each).
const MAX_TIMELINE_PERIODS: u64 = 5_000;

/// The event timeline of one scene: the raster of its modes over the
/// start-up from rest (to a tenth past `p_0.99`, at least 20 periods; or
/// the periods simulated when there is no steady state), every segment
/// and the event that ends it in the CSV.
pub fn scene_timeline(scene: &Scene, name: &str) -> Result<Figure, PlotError> {
    let mut quiet = scene.clone();
    quiet.outputs.trajectory = false;
    quiet.outputs.events = false;
    let outcome = simulation::simulate(&quiet).map_err(PlotError::simulation(name))?;
    let p99 = outcome.report().and_then(|r| r.startup_periods);
    let periods = p99
        .map_or(outcome.periods_simulated(), |p| p + p / 10)
        .clamp(20, MAX_TIMELINE_PERIODS);
    let (tl, signal) = record(scene, periods, name)?;
    let mut csv = Csv::new(
        &[
            &format!(
                "Event timeline of the scene: every exact segment of the motion from rest over {periods} periods (T = {:e} s, p_0.99 = {}, outcome {}),",
                signal.period(),
                p99.map_or("none".to_owned(), |p| p.to_string()),
                outcome.regime()
            ),
            "with its mode and the event that ends it (period_end: the period ended). Phases in s within the period.",
        ],
        &[
            "period",
            "start_phase_s",
            "end_phase_s",
            "mode",
            "ends_with",
        ],
    );
    for (s, end) in tl.segments.iter().zip(&tl.ends) {
        csv.row(&[
            Cell::I(s.period as i64),
            Cell::F(s.start),
            Cell::F(s.end),
            Cell::S(s.mode.name()),
            Cell::S(end.as_ref().map_or("period_end", event_name)),
        ]);
    }
    let panel = raster(None, &tl, &signal, periods, p99);
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(vec![panel], 1, 0.7),
        csv: csv.finish(),
        preset: Preset::SingleColumn,
    })
}
