//! The actuator in the loop (docs/model.md section 16) as a figure: what
//! the paper's assumption of a rod that follows its signal leaves out, at
//! the scene's signal (the registry draws the paper's default).
//!
//! * Panel (a): rod and slider velocity over one steady period with the
//!   real actuator as designed and 5 % stiffer (`c_real = 1.05 c`), the
//!   friction acting back on the rod in both;
//! * panel (b): the rod's deviation `x_R - x_sig` from the signal the
//!   voltage was designed for, over the same period, on one scale for
//!   both, so that the two causes compare;
//! * panel (c): `v_inf` against the stiffness error `Δc/c = c_real/c - 1`
//!   from -10 % to +10 % in steps of 1 %, with and without the reaction,
//!   and the prescribed rod's `v_inf` as a reference line.
//!
//! Contract: every number is from runs of the exact driven engine
//! ([`crate::engine::DrivenEngine`]). Inside a segment of the steady
//! period the rod is its mode's closed form from the segment's start
//! state ([`crate::engine::DrivenEngine::rod_in_segment`]), not the
//! signal; the slider moves with the rod in stick and with constant
//! acceleration in slip. A stiffness error of `k` % is the real stiffness
//! `c (100 + k) / 100`, so `+5 %` of Table 1 is `25.83e6 N/m` exactly as a
//! scene writes it. A case without a steady state leaves a gap in its
//! curve and an empty cell in the CSV. The runs are independent and run
//! in parallel; their order, and so the figure's bytes, do not depend on
//! the thread count.

use super::style::PALETTE;
use super::{
    Axis, Cell, Csv, Dash, Figure, Look, Marker, Panel, Plot, PlotError, Preset, Series, min_max,
    padded, sym,
};
use crate::actuator::{DrivenSpec, RealActuator, RodModel};
use crate::engine::event::EventOptions;
use crate::engine::{DrivenEngine, Mode, Segment};
use crate::indicator::Indicator;
use crate::scene::Scene;
use crate::simulation::{self, Outcome};
use rayon::prelude::*;

/// The figure's name.
pub const NAME: &str = "driven_rod";

/// Stiffness errors of panel (c), in percent: -10 to +10.
pub const STIFFNESS_ERRORS: std::ops::RangeInclusive<i32> = -10..=10;

/// The stiffness error of panels (a) and (b), in percent.
pub const STIFFER: i32 = 5;

/// Samples of the steady period, spread over its segments by duration.
const PER_PERIOD: usize = 400;

/// One sample of a steady period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeriodSample {
    /// Phase in the period (s).
    pub t: f64,
    /// Rod velocity (m/s).
    pub v_rod: f64,
    /// Slider velocity (m/s).
    pub v_slider: f64,
    /// `x_R - x_sig` (m).
    pub deviation: f64,
}

/// A driven rod's steady period, sampled.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyPeriod {
    /// The real actuator's stiffness error (%).
    pub stiffness_error: i32,
    /// Its `v_inf` (m/s).
    pub v_inf: f64,
    /// `max |x_R - x_sig|` over the period (m), as the run reports it.
    pub deviation_max: f64,
    /// The samples, in time order.
    pub samples: Vec<PeriodSample>,
}

/// `v_inf` at one stiffness error (`None` where the run has no steady
/// state).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessPoint {
    /// The real actuator's stiffness error (%).
    pub stiffness_error: i32,
    /// With the friction acting back on the rod (m/s).
    pub with_reaction: Option<f64>,
    /// Without it (m/s).
    pub without_reaction: Option<f64>,
}

/// Everything the figure draws, computed once for a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivenRuns {
    /// The scene's signal in words, for the caption.
    pub signal: String,
    /// The scene's signal is the paper's default (`n = 2`,
    /// `sqrt(kappa) = 6`, sigma factors, 25 um).
    pub paper_default: bool,
    /// The period `T` (s).
    pub period: f64,
    /// The signal's highest frequency `f_max` (Hz).
    pub f_max: Option<f64>,
    /// The designed actuator's undamped resonance `sqrt(c/M) / (2 pi)`
    /// (Hz).
    pub resonance: f64,
    /// The signal's mean position `x_0` (m).
    pub offset: f64,
    /// The prescribed rod's `v_inf` (m/s).
    pub prescribed: f64,
    /// The steady periods of panels (a) and (b): as designed and
    /// [`STIFFER`], both with the reaction.
    pub periods: [SteadyPeriod; 2],
    /// Panel (c), in order of the stiffness error.
    pub sweep: Vec<StiffnessPoint>,
}

/// `scene` with a driven rod whose real actuator is `percent` % stiffer
/// than its `[actuator]`; only `v_inf` is asked for, and the steady
/// period's segments where `trajectory`.
fn driven(scene: &Scene, percent: i32, reaction: bool, trajectory: bool) -> Scene {
    let mut s = scene.clone();
    let stiffness = s
        .actuator
        .map(|a| a.stiffness * f64::from(100 + percent) / 100.0);
    s.rod = RodModel::Driven(DrivenSpec {
        reaction,
        real: RealActuator {
            stiffness: if percent == 0 { None } else { stiffness },
            ..RealActuator::default()
        },
    });
    s.outputs.indicators = vec![Indicator::VInf];
    s.outputs.trajectory = trajectory;
    s.outputs.events = false;
    s
}

/// The runs behind the figure for `scene`, which must name an
/// `[actuator]` and a signal a driven rod accepts (docs/interface.md).
pub fn runs(scene: &Scene) -> Result<DrivenRuns, PlotError> {
    if scene.actuator.is_none() {
        return Err(PlotError::Data {
            figure: NAME.to_owned(),
            reason: "the scene has no [actuator] to drive".to_owned(),
        });
    }
    let jobs: Vec<(i32, bool)> = STIFFNESS_ERRORS
        .flat_map(|k| [(k, true), (k, false)])
        .collect();
    let wants_period = |k: i32, reaction: bool| reaction && (k == 0 || k == STIFFER);
    let mut prescribed = scene.clone();
    prescribed.outputs.indicators = vec![Indicator::VInf];
    prescribed.outputs.trajectory = false;
    prescribed.outputs.events = false;
    let outcomes: Vec<Result<Outcome, crate::error::Error>> = jobs
        .par_iter()
        .map(|&(k, reaction)| {
            simulation::simulate(&driven(scene, k, reaction, wants_period(k, reaction)))
        })
        .chain(rayon::iter::once(simulation::simulate(&prescribed)))
        .collect();
    let mut outcomes: Vec<Outcome> = outcomes
        .into_iter()
        .collect::<Result<_, _>>()
        .map_err(PlotError::simulation(NAME))?;
    let prescribed = outcomes
        .pop()
        .and_then(|o| o.report().map(|r| r.indicators.v_inf))
        .ok_or_else(|| no_steady_state("the prescribed rod"))?;
    let v_inf = |o: &Outcome| o.report().map(|r| r.indicators.v_inf);
    let sweep = jobs
        .chunks(2)
        .zip(outcomes.chunks(2))
        .map(|(pair, o)| StiffnessPoint {
            stiffness_error: pair[0].0,
            with_reaction: v_inf(&o[0]),
            without_reaction: v_inf(&o[1]),
        })
        .collect();
    let period_of = |k: i32| -> Result<SteadyPeriod, PlotError> {
        let i = jobs
            .iter()
            .position(|&(j, reaction)| j == k && reaction)
            .expect("a job of every stiffness error");
        let report = outcomes[i]
            .report()
            .ok_or_else(|| no_steady_state(&format!("the rod {k} % stiffer")))?;
        let segments = report.trajectory.as_deref().unwrap_or_default();
        Ok(SteadyPeriod {
            stiffness_error: k,
            v_inf: report.indicators.v_inf,
            deviation_max: report.drive.map_or(0.0, |d| d.rod_deviation_max),
            samples: sample(&driven(scene, k, true, false), segments)?,
        })
    };
    let (signal, _) = simulation::build(scene).map_err(PlotError::simulation(NAME))?;
    let actuator = scene.actuator.unwrap_or_default();
    Ok(DrivenRuns {
        signal: describe(scene),
        paper_default: scene.signal == crate::signal::SignalSpec::paper_default(),
        period: signal.period(),
        f_max: signal.f_max(),
        resonance: (actuator.stiffness / actuator.mass).sqrt() / std::f64::consts::TAU,
        offset: match &signal {
            crate::signal::Signal::Fourier(f) => f.offset(),
            _ => 0.0,
        },
        prescribed,
        periods: [period_of(0)?, period_of(STIFFER)?],
        sweep,
    })
}

fn no_steady_state(what: &str) -> PlotError {
    PlotError::Data {
        figure: NAME.to_owned(),
        reason: format!("{what} has no steady state"),
    }
}

/// The scene's signal in the caption's words.
fn describe(scene: &Scene) -> String {
    use crate::signal::{Drive, SignalSpec};
    match &scene.signal {
        SignalSpec::Fourier {
            shape,
            harmonics,
            sigma,
        } => {
            let drive = match shape.drive {
                Drive::Kappa(k) => format!("sqrt(kappa) = {}", plain(k.sqrt())),
                Drive::Frequency(f) => format!("f_0 = {} Hz", plain(f)),
                Drive::FMax(f) => format!("f_max = {} Hz", plain(f)),
            };
            let sigma = if *sigma { "with" } else { "without" };
            format!(
                "n = {harmonics}, {drive}, {sigma} sigma factors, stroke {} µm",
                plain(shape.stroke * 1e6)
            )
        }
        _ => "the scene's signal".to_owned(),
    }
}

/// The steady period of `scene` (a driven rod) from its `segments`,
/// sampled exactly (module docs).
fn sample(scene: &Scene, segments: &[Segment]) -> Result<Vec<PeriodSample>, PlotError> {
    let (signal, motor) = simulation::build(scene).map_err(PlotError::simulation(NAME))?;
    let RodModel::Driven(spec) = &scene.rod else {
        return Err(no_steady_state("a prescribed rod"));
    };
    let rod = simulation::driven_rod(scene, spec, &signal, &motor)
        .map_err(PlotError::simulation(NAME))?;
    let options = EventOptions::default();
    let engine = DrivenEngine::new(
        &signal,
        &rod,
        &motor,
        options.velocity_tolerance,
        options.max_events_per_period,
    );
    let period = signal.period();
    let mut out = Vec::new();
    for s in segments.iter().filter(|s| s.end > s.start) {
        let inner = ((s.duration() / period) * PER_PERIOD as f64).ceil() as usize;
        let count = inner.max(1) + 1;
        for i in 0..count {
            let dt = s.duration() * i as f64 / (count - 1) as f64;
            let t = s.start + dt;
            let rod = if i == 0 {
                s.rod_start
            } else if i + 1 == count {
                s.rod_end
            } else {
                engine.rod_in_segment(s, t)
            };
            let v_slider = match s.mode {
                Mode::Stick => rod.v,
                Mode::Slip(_) => s.slider_start.v + s.slip_acceleration * dt,
            };
            out.push(PeriodSample {
                t,
                v_rod: rod.v,
                v_slider,
                deviation: rod.x - signal.position(t),
            });
        }
    }
    Ok(out)
}

/// The look of the rod and the slider in a case: the case's colour, the
/// rod dashed (or dotted), the slider solid (or dash-dotted).
fn looks(stiffer: bool) -> (Look, Look) {
    if stiffer {
        (
            Look::line(PALETTE[2], Dash::Dotted).weighted(1.2),
            Look::line(PALETTE[2], Dash::DashDot).weighted(1.2),
        )
    } else {
        (
            Look::line(PALETTE[1], Dash::Dashed),
            Look::line(PALETTE[1], Dash::Solid).weighted(1.2),
        )
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

/// Three significant digits without trailing zeros (`6`, `1.5`).
fn plain(x: f64) -> String {
    let s = short(x);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// `a / b - 1` in percent, signed, three significant digits.
fn change(a: f64, b: f64) -> String {
    let percent = (a / b - 1.0) * 100.0;
    let sign = if percent > 0.0 { "+" } else { "" };
    format!("{sign}{} %", short(percent))
}

/// The figure of `runs`, laid out for `preset`: the three panels in a row,
/// one above the other in a single column.
pub fn figure(runs: &DrivenRuns, preset: Preset) -> Result<Figure, PlotError> {
    // Axis descriptions where the panels have room for them: a single
    // column's panels are short, a slide's narrow against its text.
    let described = preset == Preset::DoubleColumn;
    let axis_label = |description: &str, quantity: &str, unit: &str| {
        if described {
            format!("{description} {quantity} ({unit})")
        } else {
            format!("{quantity} ({unit})")
        }
    };
    let t_end = runs.period;
    let t_axis = || Axis::linear("time $t$ (µs)", (0.0, t_end * 1e6)).scaled(1e6);
    let label = |stiffer: bool, body: &str| {
        if stiffer {
            format!("{body}, {STIFFER} % stiffer")
        } else {
            format!("{body}, as designed")
        }
    };
    // (a) velocities.
    let (v_lo, v_hi) = min_max(
        runs.periods
            .iter()
            .flat_map(|p| p.samples.iter().flat_map(|s| [s.v_rod, s.v_slider])),
    );
    let mut a = Panel::new(
        Some("(a) velocity"),
        t_axis(),
        Axis::linear(
            &axis_label("velocity", "$v$", "m/s"),
            padded(v_lo, v_hi, 0.06),
        ),
    );
    // (b) deviations, one scale for both.
    let (d_lo, d_hi) = min_max(
        runs.periods
            .iter()
            .flat_map(|p| p.samples.iter().map(|s| s.deviation)),
    );
    let deviation = sym("rod_deviation");
    let mut b = Panel::new(
        Some("(b) rod deviation"),
        t_axis(),
        Axis::linear(
            &axis_label(deviation.description, deviation.quantity, "µm"),
            padded(d_lo * 1e6, d_hi * 1e6, 0.08),
        )
        .scaled(1e6),
    );
    for p in &runs.periods {
        let stiffer = p.stiffness_error != 0;
        let (rod, slider) = looks(stiffer);
        let points = |f: fn(&PeriodSample) -> f64| p.samples.iter().map(|s| (s.t, f(s))).collect();
        a.series.push(Series::line(
            Some(&label(stiffer, "rod")),
            points(|s| s.v_rod),
            rod,
        ));
        a.series.push(Series::line(
            Some(&label(stiffer, "slider")),
            points(|s| s.v_slider),
            slider,
        ));
        b.series.push(Series::line(
            Some(&label(stiffer, "rod")),
            points(|s| s.deviation),
            rod,
        ));
    }
    // (c) v_inf against the stiffness error: a marker at every run, lines
    // to guide the eye.
    let pieces = |f: fn(&StiffnessPoint) -> Option<f64>| -> Vec<Vec<(f64, f64)>> {
        let mut pieces = vec![Vec::new()];
        for p in &runs.sweep {
            match f(p) {
                Some(v) => pieces
                    .last_mut()
                    .expect("one piece")
                    .push((f64::from(p.stiffness_error), v)),
                None => pieces.push(Vec::new()),
            }
        }
        pieces.retain(|piece| !piece.is_empty());
        pieces
    };
    let with = pieces(|p| p.with_reaction);
    let without = pieces(|p| p.without_reaction);
    let (lo, hi) = min_max(
        with.iter()
            .chain(&without)
            .flatten()
            .map(|p| p.1)
            .chain([runs.prescribed]),
    );
    let k_range = padded(
        f64::from(*STIFFNESS_ERRORS.start()),
        f64::from(*STIFFNESS_ERRORS.end()),
        0.04,
    );
    let (error, v_inf) = (sym("stiffness_error"), sym("v_inf"));
    let mut c = Panel::new(
        Some("(c) stiffness error"),
        Axis::linear(&axis_label(error.description, error.quantity, "%"), k_range),
        Axis::linear(
            &axis_label(v_inf.description, v_inf.quantity, v_inf.unit),
            padded(lo, hi, 0.08),
        ),
    );
    c.series.push(Series::hline(
        Some("$v_∞$, prescribed rod"),
        runs.prescribed,
        k_range,
        Look::reference(),
    ));
    let cases = [
        (
            with,
            "$v_∞$, with reaction",
            PALETTE[0],
            Dash::Solid,
            Marker::Circle,
        ),
        (
            without,
            "$v_∞$, without reaction",
            PALETTE[3],
            Dash::Dashed,
            Marker::Plus,
        ),
    ];
    for (pieces, name, color, dash, marker) in cases {
        let markers: Vec<(f64, f64)> = pieces.iter().flatten().copied().collect();
        c.series.push(Series {
            label: None,
            pieces,
            look: Look::line(color, dash),
            kind: super::Kind::Curve,
        });
        c.series.push(Series::points(
            Some(name),
            markers,
            Look {
                color,
                dash: Dash::NoLine,
                marker,
                weight: 1.0,
            },
        ));
    }
    // The cases of (a) and (b), in their colours.
    for p in &runs.periods {
        c.series.push(Series::points(
            None,
            vec![(f64::from(p.stiffness_error), p.v_inf)],
            Look {
                color: looks(p.stiffness_error != 0).0.color,
                dash: Dash::NoLine,
                marker: Marker::Square,
                weight: 1.0,
            },
        ));
    }
    let (columns, aspect) = if preset == Preset::SingleColumn {
        (1, 0.45)
    } else {
        (3, 0.85)
    };
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(vec![a, b, c], columns, aspect).with_notes(notes(runs)),
        csv: csv(runs),
        preset: Preset::DoubleColumn,
    })
}

/// The mean of `f` over the period by the trapezoidal rule on the samples.
fn mean(samples: &[PeriodSample], f: fn(&PeriodSample) -> f64, period: f64) -> f64 {
    let integral: f64 = samples
        .windows(2)
        .map(|w| 0.5 * (f(&w[0]) + f(&w[1])) * (w[1].t - w[0].t))
        .sum();
    integral / period
}

/// The caption's text: the signal and why, and the numbers of the panels.
fn notes(runs: &DrivenRuns) -> Vec<String> {
    let [designed, stiffer] = &runs.periods;
    let with = |k: i32| {
        runs.sweep
            .iter()
            .find(|p| p.stiffness_error == k)
            .and_then(|p| p.with_reaction)
    };
    let best = runs
        .sweep
        .iter()
        .filter_map(|p| p.with_reaction.map(|v| (p.stiffness_error, v)))
        .fold(None, |b: Option<(i32, f64)>, (k, v)| match b {
            Some((_, w)) if w >= v => b,
            _ => Some((k, v)),
        });
    let spread = runs
        .sweep
        .iter()
        .filter_map(|p| Some((p.with_reaction? / p.without_reaction? - 1.0).abs()))
        .fold(0.0, f64::max);
    let khz = |f: f64| format!("{:.2} kHz", f / 1e3);
    let f_0 = 1.0 / runs.period;
    let f_max = runs.f_max.unwrap_or(f_0);
    let resonance = khz(runs.resonance);
    // Below the resonance a stiffer actuator moves less, above it more.
    let sides = if f_max < runs.resonance {
        format!("all its harmonics lie below the actuator's resonance, {resonance}")
    } else if f_0 > runs.resonance {
        format!("all its harmonics lie above the actuator's resonance, {resonance}")
    } else {
        format!(
            "its harmonics lie on both sides of the actuator's resonance ({} and {} about {resonance}), so a stiffness error weakens the ones and strengthens the others and the rod's velocity changes shape",
            khz(f_0),
            khz(f_max)
        )
    };
    let why = if runs.paper_default {
        format!("the paper's default signal, its best and the one its numbers are for; {sides}")
    } else {
        sides
    };
    let mut notes = vec![format!(
        "Driven rod (docs/model.md section 16) with the scene's actuator (the voltage designed for it) at {}, T = {} µs: {why}.",
        runs.signal,
        short(runs.period * 1e6)
    )];
    notes.push(format!(
        "(a) Rod (dashed, dotted) and slider (solid, dash-dotted) velocity over one steady period with the real actuator as designed (blue) and {STIFFER} % stiffer (vermillion), the friction acting back on the rod in both.",
    ));
    let static_shift = runs.offset * (100.0 / f64::from(100 + STIFFER) - 1.0);
    notes.push(format!(
        "(b) The rod's deviation x_R - x_sig from its signal, one scale for both: the reaction alone moves the rod by at most {} nm, the {STIFFER} % stiffer actuator by {} µm; the latter's mean, {} µm, is the smaller static deflection under the offset voltage, x_0 (c/c_real - 1) = {} µm.",
        short(designed.deviation_max * 1e9),
        short(stiffer.deviation_max * 1e6),
        short(mean(&stiffer.samples, |s| s.deviation, runs.period) * 1e6),
        short(static_shift * 1e6),
    ));
    notes.push(format!(
        "(c) v_inf against the stiffness error c_real/c - 1 with and without the reaction (within {} % of each other), and the prescribed rod's v_inf = {} m/s; squares mark the cases of (a) and (b).",
        short(spread * 100.0),
        short(runs.prescribed)
    ));
    notes.push(format!(
        "Against the prescribed rod: the reaction changes v_inf by {}; an actuator {STIFFER} % stiffer by {}, {STIFFER} % softer by {}.",
        change(designed.v_inf, runs.prescribed),
        change(stiffer.v_inf, runs.prescribed),
        with(-STIFFER).map_or("-".to_owned(), |v| change(v, runs.prescribed)),
    ));
    if let Some((k, v)) = best {
        notes.push(format!(
            "The largest v_inf of the grid with the reaction, {} m/s, is at {k:+} %.",
            short(v)
        ));
    }
    notes
}

/// The data drawn: the two steady periods, sample by sample, then `v_inf`
/// at every stiffness error.
fn csv(runs: &DrivenRuns) -> String {
    let mut csv = Csv::new(
        &[
            "Driven rod (docs/model.md section 16), the exact driven engine; SI units.",
            "kind 'sample': the steady period of the rod with the reaction, actuator stiffness_error_percent stiffer than designed;",
            "t_s phase, deviation_m = x_R - x_sig. kind 'v_inf': v_inf with and without the reaction at stiffness_error_percent;",
            "empty where the run has no steady state. kind 'prescribed': the prescribed rod's v_inf.",
        ],
        &[
            "kind",
            "stiffness_error_percent",
            "t_s",
            "v_rod_m_per_s",
            "v_slider_m_per_s",
            "deviation_m",
            "v_inf_with_reaction_m_per_s",
            "v_inf_without_reaction_m_per_s",
        ],
    );
    let empty = Cell::S("");
    for p in &runs.periods {
        for s in &p.samples {
            csv.row(&[
                Cell::S("sample"),
                Cell::I(i64::from(p.stiffness_error)),
                Cell::F(s.t),
                Cell::F(s.v_rod),
                Cell::F(s.v_slider),
                Cell::F(s.deviation),
                empty,
                empty,
            ]);
        }
    }
    let value = |v: Option<f64>| v.map_or(Cell::S(""), Cell::F);
    for p in &runs.sweep {
        csv.row(&[
            Cell::S("v_inf"),
            Cell::I(i64::from(p.stiffness_error)),
            empty,
            empty,
            empty,
            empty,
            value(p.with_reaction),
            value(p.without_reaction),
        ]);
    }
    csv.row(&[
        Cell::S("prescribed"),
        Cell::I(0),
        empty,
        empty,
        empty,
        empty,
        empty,
        Cell::F(runs.prescribed),
    ]);
    csv.finish()
}
