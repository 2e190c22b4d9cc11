//! One scene's motion: rod and slider velocity, displacement and
//! acceleration (with the stick band) over chosen periods, events marked by
//! kind; the start-up (`v_p` against `p` with `v_inf` and `p_0.99`); and
//! figure 8 of the paper (velocities in the first and a steady period).
//!
//! Contract: everything is drawn from the exact segments of the event
//! engine (docs/model.md): the slider's velocity is linear in slip (slope
//! `±a_d + g_t`) and equals the rod's in stick; its displacement is
//! quadratic in slip. Periods are counted from rest (`p = 1`); the steady
//! period (`last`) starts from the steady state's boundary velocity. A
//! scene without a steady state has no `last` period: asking for it is an
//! error naming the outcome, the numbered periods still plot.
//!
//! The acceleration row is drawn on the stick band's scale: centred on
//! `g_t`, it spans the rod's acceleration but at most [`BAND_SPAN`]
//! half-widths `a_0` of the band `a_0^- … a_0^+` on either side (the
//! rod's larger accelerations leave the panel; their range is in the
//! caption). The slider's acceleration always lies in the band (the rod's
//! in stick, `±a_d + g_t` in slip, `a_d <= a_0`), so it is drawn whole.
//! `v_inf` is drawn over the curves of the steady column. Columns carry
//! panel letters only when there are several; the start-up runs past
//! `p_0.99` ([`startup_end`]) so that its mark lies inside the frame.

use super::series::Kind;
use super::signals::band_look;
use super::style::{PALETTE, Rgb};
use super::{
    Axis, Cell, Csv, Dash, Figure, Look, Marker, Panel, Plot, PlotError, Preset, Series, min_max,
    padded,
};
use crate::engine::Observer;
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{Event, EventKind, Mode, PeriodEngine, PeriodStart, Segment};
use crate::scene::Scene;
use crate::signal::Signal;
use crate::simulation::{self, Outcome};

mod startup;
pub use startup::{startup, startup_end};

/// Which periods a column of the figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Span {
    /// Periods `first..=last`, counted from rest.
    Periods(u64, u64),
    /// One period of the periodic steady state.
    Steady,
}

/// The acceleration row spans at most this many half-widths `a_0` of the
/// stick band on either side of its centre `g_t`.
pub const BAND_SPAN: f64 = 3.0;

/// The acceleration row's range for `motor` and the rod's accelerations
/// `rod` (m/s²): centred on `g_t`, wide enough for the rod's
/// accelerations (6 % padded) and at least 1.25 band half-widths, at
/// most [`BAND_SPAN`] of them. Without a band (`a_0 = 0`) it spans the
/// rod's accelerations.
pub(crate) fn band_range(
    motor: &crate::motor::Motor,
    rod: impl IntoIterator<Item = f64>,
) -> (f64, f64) {
    let g = motor.g_t();
    let reach = rod
        .into_iter()
        .filter(|a| a.is_finite())
        .map(|a| (a - g).abs())
        .fold(0.0, f64::max)
        * 1.06;
    let a_0 = motor.a_0();
    let half = if a_0 > 0.0 {
        reach.clamp(1.25 * a_0, BAND_SPAN * a_0)
    } else if reach > 0.0 {
        reach
    } else {
        1.0
    };
    (g - half, g + half)
}

/// The most periods a numbered span may reach (the start-up is simulated
/// period by period to get there).
pub const MAX_PERIOD: u64 = 100_000;

/// Parses `--periods`: a comma-separated list of columns, each a period
/// (`3`), a range (`1-5`) or `last` (also `steady`): `1,2,last`.
pub fn parse_periods(text: &str) -> Result<Vec<Span>, String> {
    let bad = |why: &str| format!("--periods {text}: {why}");
    let mut spans = Vec::new();
    for part in text.split(',').map(str::trim) {
        let number = |s: &str| -> Result<u64, String> {
            match s.trim().parse::<u64>() {
                Ok(p) if (1..=MAX_PERIOD).contains(&p) => Ok(p),
                _ => Err(bad(&format!(
                    "\"{s}\" is not a period from 1 to {MAX_PERIOD}, a range a-b, or last"
                ))),
            }
        };
        let span = match part {
            "last" | "steady" => Span::Steady,
            _ => match part.split_once('-') {
                Some((a, b)) => {
                    let (a, b) = (number(a)?, number(b)?);
                    if a > b {
                        return Err(bad(&format!("the range {part} runs backwards")));
                    }
                    Span::Periods(a, b)
                }
                None => {
                    let p = number(part)?;
                    Span::Periods(p, p)
                }
            },
        };
        spans.push(span);
    }
    if spans.is_empty() || spans.len() > 4 {
        return Err(bad("give 1 to 4 columns"));
    }
    Ok(spans)
}

/// A row of the motion figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Row {
    /// Rod and slider velocity, events marked.
    Velocity,
    /// Rod and slider displacement from the start of the span.
    Displacement,
    /// Rod and slider acceleration with the stick band.
    Acceleration,
}

/// Segments and events of the periods simulated.
#[derive(Debug, Default)]
struct Record {
    segments: Vec<Segment>,
    events: Vec<Event>,
    /// Record only periods in this range.
    keep: (u64, u64),
}

impl Observer for Record {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        if (self.keep.0..=self.keep.1).contains(&segment.period) {
            self.segments.push(*segment);
        }
    }
    fn event(&mut self, event: &Event) {
        if (self.keep.0..=self.keep.1).contains(&event.period) {
            self.events.push(*event);
        }
    }
}

/// A span's exact motion: segments in time order, events, and the time
/// (s) at which the span starts.
struct Motion {
    label: String,
    /// The steady-state period.
    steady: bool,
    segments: Vec<Segment>,
    events: Vec<Event>,
    first: u64,
}

fn record(
    signal: &Signal,
    motor: &crate::motor::Motor,
    span: Span,
    steady: Option<f64>,
    figure: &str,
) -> Result<Motion, PlotError> {
    let sim = |e: crate::error::SimulationError| PlotError::simulation(figure)(e.into());
    let mut engine = EventEngine::new(signal, motor, EventOptions::default());
    match span {
        Span::Periods(a, b) => {
            let mut rec = Record {
                keep: (a, b),
                ..Record::default()
            };
            let mut start = PeriodStart {
                velocity: 0.0,
                mode: None,
            };
            for p in 1..=b {
                let end = engine.run_period(p, start, &mut rec).map_err(sim)?;
                start = PeriodStart {
                    velocity: end.velocity,
                    mode: Some(end.mode),
                };
            }
            let label = if a == b {
                format!("$p$ = {a}")
            } else {
                format!("$p$ = {a} … {b}")
            };
            Ok(Motion {
                label,
                steady: false,
                segments: rec.segments,
                events: rec.events,
                first: a,
            })
        }
        Span::Steady => {
            let velocity = steady.ok_or_else(|| PlotError::Data {
                figure: figure.to_owned(),
                reason: "no steady state".to_owned(),
            })?;
            // Any period index after the first: the steady period does not
            // start from rest.
            let mut rec = Record {
                keep: (2, 2),
                ..Record::default()
            };
            let start = PeriodStart {
                velocity,
                mode: None,
            };
            engine.run_period(2, start, &mut rec).map_err(sim)?;
            Ok(Motion {
                label: "$p$\u{a0}→\u{a0}∞".to_owned(),
                steady: true,
                segments: rec.segments,
                events: rec.events,
                first: 2,
            })
        }
    }
}

/// The steady state's boundary velocity and `v_inf`, or the outcome's name
/// when there is none.
fn steady_state(
    scene: &Scene,
    figure: &str,
) -> Result<Result<(f64, f64), &'static str>, PlotError> {
    let mut quiet = scene.clone();
    quiet.outputs.trajectory = false;
    quiet.outputs.events = false;
    let outcome = simulation::simulate(&quiet).map_err(PlotError::simulation(figure))?;
    Ok(match &outcome {
        Outcome::Steady(r) => Ok((r.steady.boundary_velocity, r.indicators.v_inf)),
        other => Err(other.regime()),
    })
}

/// The figure of `rows` over `spans` (one column each) for the scene.
pub fn motion(
    scene: &Scene,
    spans: &[Span],
    rows: &[Row],
    name: &str,
) -> Result<Figure, PlotError> {
    let (signal, motor) = simulation::build_prescribed(scene, "the motion figure")
        .map_err(PlotError::simulation(name))?;
    let steady = if spans.contains(&Span::Steady) {
        match steady_state(scene, name)? {
            Ok(s) => Some(s),
            Err(regime) => {
                return Err(PlotError::Argument(format!(
                    "--periods last: the scene has no steady state (outcome {regime}); plot numbered periods instead"
                )));
            }
        }
    } else {
        None
    };
    let period = signal.period();
    let (t_scale, t_unit) = if period < 1e-3 {
        (1e6, "µs")
    } else {
        (1e3, "ms")
    };
    let motions: Vec<Motion> = spans
        .iter()
        .map(|&s| record(&signal, &motor, s, steady.map(|s| s.0), name))
        .collect::<Result<_, _>>()?;
    let mut csv = Csv::new(
        &[
            &format!(
                "Rod and slider motion of the scene, exact segments (docs/model.md); period T = {period:e} s; a_0+ = {:e}, a_0- = {:e} m/s^2.",
                motor.a_0_plus(),
                motor.a_0_minus()
            ),
            "span: the periods shown; t_s: time from the start of the span; x: displacement from the start of the span. SI units.",
            "Rows of kind 'event' mark an event (its name in 'mode') at t_s on the slider.",
        ],
        &[
            "span",
            "kind",
            "period",
            "mode",
            "t_s",
            "x_rod_m",
            "x_slider_m",
            "v_rod_m_per_s",
            "v_slider_m_per_s",
            "a_rod_m_per_s2",
            "a_slider_m_per_s2",
        ],
    );
    let mut columns: Vec<Vec<Panel>> = Vec::new();
    let mut rod_accelerations = (f64::INFINITY, f64::NEG_INFINITY);
    for m in &motions {
        let samples = sample(m, &signal, period);
        let (lo, hi) = min_max(samples.iter().map(|s| s.a_rod));
        rod_accelerations = (rod_accelerations.0.min(lo), rod_accelerations.1.max(hi));
        for s in &samples {
            csv.row(&[
                Cell::S(&crate::plot::visible(&m.label)),
                Cell::S("sample"),
                Cell::I(s.period as i64),
                Cell::S(s.mode.name()),
                Cell::F(s.t),
                Cell::F(s.x_rod),
                Cell::F(s.x_slider),
                Cell::F(s.v_rod),
                Cell::F(s.v_slider),
                Cell::F(s.a_rod),
                Cell::F(s.a_slider),
            ]);
        }
        let events: Vec<(f64, EventKind, f64)> = m
            .events
            .iter()
            .map(|e| {
                let t = (e.period - m.first) as f64 * period + e.phase;
                let v = slider_velocity_at(&samples, t);
                (t, e.kind, v)
            })
            .collect();
        for (t, kind, v) in &events {
            csv.row(&[
                Cell::S(&crate::plot::visible(&m.label)),
                Cell::S("event"),
                Cell::I(0),
                Cell::S(kind.name()),
                Cell::F(*t),
                Cell::S(""),
                Cell::S(""),
                Cell::S(""),
                Cell::F(*v),
                Cell::S(""),
                Cell::S(""),
            ]);
        }
        let t_end = samples.last().map_or(period, |s| s.t);
        let t_axis = || {
            Axis::linear(&format!("time $t$ ({t_unit})"), (0.0, t_end * t_scale)).scaled(t_scale)
        };
        let mut column = Vec::new();
        for (r, row) in rows.iter().enumerate() {
            // A letter names a column only where there are several.
            let title = (r == 0).then(|| {
                if motions.len() > 1 {
                    format!("({}) {}", (b'a' + columns.len() as u8) as char, m.label)
                } else {
                    m.label.clone()
                }
            });
            let panel = match row {
                Row::Velocity => {
                    let (lo, hi) = min_max(samples.iter().flat_map(|s| [s.v_rod, s.v_slider]));
                    let mut p = Panel::new(
                        title.as_deref(),
                        t_axis(),
                        Axis::linear("velocity $v$ (m/s)", padded(lo, hi, 0.06)),
                    );
                    p.series
                        .push(curve("rod", &samples, |s| s.v_rod, rod_look()));
                    p.series
                        .push(curve("slider", &samples, |s| s.v_slider, slider_look()));
                    for (kind, look) in event_looks() {
                        let pts: Vec<(f64, f64)> = events
                            .iter()
                            .filter(|e| e.1.name() == kind)
                            .map(|e| (e.0, e.2))
                            .collect();
                        if !pts.is_empty() {
                            p.series
                                .push(Series::points(Some(&kind.replace('_', " ")), pts, look));
                        }
                    }
                    // Drawn last, over the curves and in a colour of its
                    // own, so that it shows along the slider's velocity.
                    if m.steady
                        && let Some((_, v_inf)) = steady
                    {
                        p.series.push(Series::hline(
                            Some(super::sym("v_inf").quantity),
                            v_inf,
                            (0.0, t_end),
                            v_inf_look(),
                        ));
                    }
                    p
                }
                Row::Displacement => {
                    let (lo, hi) = min_max(samples.iter().flat_map(|s| [s.x_rod, s.x_slider]));
                    let mut p = Panel::new(
                        title.as_deref(),
                        t_axis(),
                        Axis::linear("displacement $x$ (µm)", padded(lo * 1e6, hi * 1e6, 0.06))
                            .scaled(1e6),
                    );
                    p.series
                        .push(curve("rod", &samples, |s| s.x_rod, rod_look()));
                    p.series
                        .push(curve("slider", &samples, |s| s.x_slider, slider_look()));
                    p
                }
                Row::Acceleration => {
                    let (a_minus, a_plus) = (motor.a_0_minus(), motor.a_0_plus());
                    let range = band_range(&motor, samples.iter().map(|s| s.a_rod));
                    let mut p = Panel::new(
                        title.as_deref(),
                        t_axis(),
                        Axis::linear("acceleration $a$ (m/s²)", range),
                    );
                    p.series.push(Series::bands(
                        Some("stick band $a_0^-$ … $a_0^+$"),
                        vec![[(0.0, a_minus), (t_end, a_plus)]],
                        band_look(),
                    ));
                    p.series
                        .push(curve("rod", &samples, |s| s.a_rod, rod_look()));
                    p.series
                        .push(curve("slider", &samples, |s| s.a_slider, slider_look()));
                    p
                }
            };
            column.push(panel);
        }
        columns.push(column);
    }
    let ncols = columns.len();
    let panels: Vec<Panel> = (0..rows.len())
        .flat_map(|r| columns.iter().map(move |c| c[r].clone()))
        .collect();
    let mut notes = vec![format!(
        "Rod (dashed) and slider (solid), periods counted from rest; period T = {} {t_unit}.",
        short(period * t_scale)
    )];
    if rows.contains(&Row::Acceleration) {
        let (lo, hi) = rod_accelerations;
        notes.push(format!(
            "Accelerations on the stick band's scale: the slider can stick only while the rod's acceleration lies in the band a_0^- … a_0^+ = {} … {} m/s²; the rod's acceleration runs from {} to {} m/s².",
            short(motor.a_0_minus()),
            short(motor.a_0_plus()),
            short(lo),
            short(hi)
        ));
    }
    if let Some((_, v_inf)) = steady {
        notes.push(format!(
            "Steady state (p → ∞): mean velocity v_inf = {} m/s.",
            short(v_inf)
        ));
    }
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(panels, ncols, panel_aspect(rows.len(), ncols)).with_notes(notes),
        csv: csv.finish(),
        preset: if ncols > 1 {
            Preset::DoubleColumn
        } else {
            Preset::SingleColumn
        },
    })
}

/// Height over width of a panel of a grid of `rows` by `columns`: flatter
/// as rows are added, so that the default figure (three rows, two
/// columns) is about two thirds as tall as it is wide.
fn panel_aspect(rows: usize, columns: usize) -> f64 {
    let rows = rows.max(1) as f64;
    if columns > 1 {
        (1.25 / rows).clamp(0.4, 0.75)
    } else {
        (1.0 / rows).clamp(0.3, 0.5)
    }
}

/// Three significant digits.
fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

/// `v_inf` over the slider's velocity: long dashes in orange, which no
/// curve of the figure has.
fn v_inf_look() -> Look {
    Look {
        weight: 1.0,
        ..Look::line(PALETTE[5], Dash::LongDash)
    }
}

fn rod_look() -> Look {
    Look::nth(1)
}

fn slider_look() -> Look {
    Look::nth(0).weighted(1.2)
}

/// Markers of the event kinds (reference names of docs/interface.md).
fn event_looks() -> [(&'static str, Look); 5] {
    let point = |c: Rgb, m: Marker| Look {
        color: c,
        dash: Dash::NoLine,
        marker: m,
        weight: 1.0,
    };
    [
        ("stick_to_slip", point(PALETTE[2], Marker::Triangle)),
        ("slip_to_stick", point(PALETTE[3], Marker::Square)),
        ("reversal", point(PALETTE[4], Marker::Diamond)),
        ("grazing", point(PALETTE[5], Marker::Plus)),
        ("jump", point(PALETTE[6], Marker::Cross)),
    ]
}

/// A curve through the samples, broken where a segment of the samples
/// ends with a jump (a rod jump at a period boundary).
fn curve(label: &str, samples: &[Sampled], f: impl Fn(&Sampled) -> f64, look: Look) -> Series {
    Series {
        label: Some(label.to_owned()),
        pieces: vec![samples.iter().map(|s| (s.t, f(s))).collect()],
        look,
        kind: Kind::Curve,
    }
}

/// One sample of the exact motion.
#[derive(Debug, Clone, Copy)]
struct Sampled {
    period: u64,
    mode: Mode,
    t: f64,
    x_rod: f64,
    x_slider: f64,
    v_rod: f64,
    v_slider: f64,
    a_rod: f64,
    a_slider: f64,
}

/// Samples per period, enough for smooth curves at slide size.
const PER_PERIOD: usize = 400;

/// Samples every segment at its ends and inside, exactly (module docs).
fn sample(m: &Motion, signal: &Signal, period: f64) -> Vec<Sampled> {
    let Some(first) = m.segments.first() else {
        return Vec::new();
    };
    let (x_rod0, x_slider0) = (first.rod_start.x, first.slider_start.x);
    let mut out = Vec::new();
    // The engine counts the slider's position from each period's start;
    // the slider moves continuously, so a span of several periods carries
    // the position across each boundary.
    let mut carried = 0.0;
    let mut previous: Option<&Segment> = None;
    for s in &m.segments {
        if let Some(p) = previous
            && p.period != s.period
        {
            carried += p.slider_end.x - s.slider_start.x;
        }
        previous = Some(s);
        let offset = (s.period - m.first) as f64 * period;
        let inner = ((s.duration() / period) * PER_PERIOD as f64).ceil() as usize;
        let count = inner.max(1) + 1;
        for i in 0..count {
            let dt = s.duration() * i as f64 / (count - 1) as f64;
            let phase = s.start + dt;
            let (x_rod, v_rod) = if i == 0 {
                (s.rod_start.x, s.rod_start.v)
            } else if i + 1 == count {
                (s.rod_end.x, s.rod_end.v)
            } else {
                (
                    s.rod_start.x + signal.position(phase) - signal.position(s.start),
                    signal.velocity(phase),
                )
            };
            let a_rod = signal.acceleration(phase);
            let (x_slider, v_slider, a_slider) = match s.mode {
                Mode::Stick => (x_rod - s.rod_start.x + s.slider_start.x, v_rod, a_rod),
                Mode::Slip(_) => {
                    let a = s.slip_acceleration;
                    (
                        s.slider_start.x + s.slider_start.v * dt + 0.5 * a * dt * dt,
                        s.slider_start.v + a * dt,
                        a,
                    )
                }
            };
            out.push(Sampled {
                period: s.period,
                mode: s.mode,
                t: offset + phase,
                x_rod: x_rod - x_rod0,
                x_slider: x_slider - x_slider0 + carried,
                v_rod,
                v_slider,
                a_rod,
                a_slider,
            });
        }
    }
    out
}

/// The slider's velocity at time `t` of the span: the first sample at or
/// after it (events lie on segment ends, which are sampled).
fn slider_velocity_at(samples: &[Sampled], t: f64) -> f64 {
    let i = samples.partition_point(|s| s.t < t);
    samples
        .get(i)
        .or(samples.last())
        .map_or(0.0, |s| s.v_slider)
}

/// Figure 8 of the paper for `scene` (the paper's caption: `n = 2`
/// without sigma factors, `sqrt(kappa) = 1`): rod and slider velocity over
/// the first period from rest and over a steady-state period.
pub fn figure8(scene: &Scene) -> Result<Figure, PlotError> {
    let mut f = motion(
        scene,
        &[Span::Periods(1, 1), Span::Steady],
        &[Row::Velocity],
        "fig8_rod_slider_velocity",
    )?;
    f.plot.aspect = 0.7;
    Ok(f)
}
