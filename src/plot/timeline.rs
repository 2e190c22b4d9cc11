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

use super::velocity::sample_segments;
use super::{
    Axis, Cell, Csv, Figure, Mark, PALETTE, Panel, PlotError, REFERENCE, Series, draw_panel,
    legend_of, min_max, padded, render, titled, with_legend_on_top,
};
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{Direction, EventKind, Mode, PeriodEngine, PeriodStart, Segment};
use crate::observer::Observer;
use crate::scene::Scene;
use crate::signal::{Signal, SignalSpec};
use crate::simulation;
use plotters::prelude::RGBColor;

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
    }
}

fn mode_color(mode: Mode) -> RGBColor {
    match mode {
        Mode::Stick => PALETTE[2],
        Mode::Slip(Direction::Forward) => PALETTE[0],
        Mode::Slip(Direction::Backward) => PALETTE[1],
    }
}

fn mode_label(mode: Mode) -> &'static str {
    match mode {
        Mode::Stick => "stick",
        Mode::Slip(Direction::Forward) => "slip forward (rod faster than slider)",
        Mode::Slip(Direction::Backward) => "slip backward (slider faster than rod)",
    }
}

const MODES: [Mode; 3] = [
    Mode::Stick,
    Mode::Slip(Direction::Forward),
    Mode::Slip(Direction::Backward),
];

/// Runs `periods` periods from rest and returns the timeline, the signal's
/// period and `p_0.99` of the full run.
fn simulate(
    scene: &Scene,
    periods: u64,
    figure: &str,
) -> Result<(Timeline, Signal, Option<u64>), PlotError> {
    let (signal, motor) = simulation::build(scene).map_err(PlotError::simulation(figure))?;
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
    let report = simulation::run(scene).map_err(PlotError::simulation(figure))?;
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
        crate::scene::Indicator::VInf,
        crate::scene::Indicator::StartupTime,
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
        Some(
            "(a) n = 5, κ = 0.36, σ factors: velocities over the first periods from rest, slider coloured by mode",
        ),
        Axis::linear("t (ms)", (0.0, t_end * 1e3)).scaled(1e3),
        Axis::linear("velocity (m/s)", padded(lo, hi, 0.06)),
    );
    a.series.push(Series::hline(
        None,
        0.0,
        (0.0, t_end),
        REFERENCE,
        Mark::Line(1),
    ));
    a.series.push(Series {
        label: Some("rod velocity".to_owned()),
        pieces: vec![
            tl_a.segments
                .iter()
                .zip(&samples)
                .flat_map(|(seg, ss)| ss.iter().map(move |s| (abs_t(seg, s.phase), s.v_rod)))
                .collect(),
        ],
        color: RGBColor(150, 150, 150),
        mark: Mark::Line(2),
    });
    for mode in MODES {
        let pieces: Vec<Vec<(f64, f64)>> = tl_a
            .segments
            .iter()
            .zip(&samples)
            .filter(|(seg, _)| seg.mode == mode)
            .map(|(seg, ss)| {
                // A slip segment is a straight line: its ends draw it exactly.
                let keep: Vec<&super::velocity::Sample> = match mode {
                    Mode::Stick => ss.iter().collect(),
                    Mode::Slip(_) => [ss.first(), ss.last()].into_iter().flatten().collect(),
                };
                keep.into_iter()
                    .map(|s| (abs_t(seg, s.phase), s.v_slider))
                    .collect()
            })
            .collect();
        a.series.push(Series {
            label: Some(mode_label(mode).to_owned()),
            pieces,
            color: mode_color(mode),
            mark: Mark::Line(4),
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
        color: PALETTE[7],
        mark: Mark::Points(4),
    });
    if let Some(p) = p99_a {
        let t = p as f64 * period_a;
        a.series.push(Series::line(
            Some("end of the start-up, t = T·p₀.₉₉"),
            vec![(t, -1e3), (t, 1e3)],
            PALETTE[7],
            Mark::Dashed(2, 8, 5),
        ));
    }

    // (b): raster of modes, one row per period.
    let period_b = sig_b.period();
    let mut b = Panel::new(
        Some(
            "(b) n = 2, √κ = 6, σ factors (the paper's default): mode raster over the start-up, one row per period",
        ),
        Axis::linear("time in the period, t − (p−1)T (µs)", (0.0, period_b * 1e6)).scaled(1e6),
        Axis::linear("period p (–)", (0.0, periods_b as f64)).ticks(8),
    );
    for mode in MODES {
        let rects: Vec<(f64, f64)> = tl_b
            .segments
            .iter()
            .filter(|s| s.mode == mode && s.end > s.start)
            .flat_map(|s| [(s.start, (s.period - 1) as f64), (s.end, s.period as f64)])
            .collect();
        if !rects.is_empty() {
            b.series.push(Series {
                label: Some(mode_label(mode).to_owned()),
                pieces: vec![rects],
                color: mode_color(mode),
                mark: Mark::Rects,
            });
        }
    }
    b.series.push(Series::hline(
        Some("end of the start-up, t = T·p₀.₉₉"),
        p99_b as f64,
        (0.0, period_b),
        PALETTE[7],
        Mark::Dashed(2, 8, 5),
    ));

    let legend = legend_of(&[&a, &b]);
    let svg = render(NAME, (1500, 1200), |root| {
        let body = titled(
            root,
            "Event timeline: the slider's modes over the start-up from rest",
        )?;
        let body = with_legend_on_top(&body, &legend)?;
        let rows = super::signals::split_rows(&body, &[1.0, 1.35]);
        draw_panel(&rows[0], &a)?;
        draw_panel(&rows[1], &b)
    })?;
    Ok(Figure {
        name: NAME.to_owned(),
        svg,
        csv: csv.finish(),
    })
}
