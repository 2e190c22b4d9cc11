//! Figure 8: rod and slider velocity over the first period (`p = 1`, from
//! rest) and over a steady-state period (`p -> inf`), for `n = 2` without
//! sigma factors (the paper's caption) at `sqrt(kappa) = 1`.
//!
//! The slider velocity is drawn exactly from the engine's segments: linear
//! with slope `±a_d` in slip, equal to the rod velocity in stick (the rod
//! velocity is sampled densely, for drawing only). The first period comes
//! from [`PeriodEngine::run_period`] with a [`Trajectory`] observer, the
//! steady-state period from a run with `outputs.trajectory = true`.

use super::{
    Axis, Cell, Csv, Figure, Mark, PALETTE, Panel, PlotError, REFERENCE, Series, min_max, padded,
    side_by_side,
};
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{Mode, PeriodEngine, PeriodStart, Segment};
use crate::observer::Trajectory;
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

/// Figure 8 for the scene's motor with `n = 2`, no sigma, `sqrt(kappa) = 1`,
/// stroke 25 um.
pub fn figure8(base: &Scene) -> Result<Figure, PlotError> {
    const NAME: &str = "fig8_rod_slider_velocity";
    let sqrt_kappa = 1.0;
    let mut scene = base.clone();
    scene.signal = SignalSpec::fourier(25e-6, sqrt_kappa * sqrt_kappa, 2, false);
    scene.outputs.trajectory = true;
    let sim = PlotError::simulation(NAME);
    let (signal, motor) = simulation::build(&scene).map_err(sim)?;
    let mut first = Trajectory::default();
    let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
    engine
        .run_period(
            1,
            PeriodStart {
                velocity: 0.0,
                mode: None,
            },
            &mut first,
        )
        .map_err(|e| PlotError::simulation(NAME)(e.into()))?;
    let report = simulation::run(&scene).map_err(PlotError::simulation(NAME))?;
    let steady = report.trajectory.clone().ok_or_else(|| PlotError::Data {
        figure: NAME.to_owned(),
        reason: "the run recorded no trajectory".to_owned(),
    })?;
    let period = signal.period();
    let parts = [
        (
            "(a) first period, p = 1 (from rest)",
            "1",
            sample_segments(&first.segments, &signal, 600),
        ),
        (
            "(b) steady-state period, p → ∞",
            "inf",
            sample_segments(&steady, &signal, 600),
        ),
    ];
    let mut csv = Csv::new(
        &[
            "Figure 8: rod and slider velocity, n = 2, no sigma factors, sqrt(kappa) = 1, stroke 25 um, paper motor.",
            &format!(
                "period: 1 (from rest) or inf (steady state); phase in s within the period (T = {period:e} s); v_inf = {:e} m/s.",
                report.indicators.v_inf
            ),
            "Samples of the exact segments: each segment's ends and inner points; slider velocity exact (linear in slip, the rod's in stick).",
        ],
        &[
            "period",
            "segment",
            "mode",
            "phase_s",
            "v_rod_m_per_s",
            "v_slider_m_per_s",
        ],
    );
    for (_, label, segs) in &parts {
        for (i, seg) in segs.iter().enumerate() {
            for s in seg {
                csv.row(&[
                    Cell::S(label),
                    Cell::I(i as i64),
                    Cell::S(s.mode.name()),
                    Cell::F(s.phase),
                    Cell::F(s.v_rod),
                    Cell::F(s.v_slider),
                ]);
            }
        }
    }
    let (lo, hi) = min_max(
        parts
            .iter()
            .flat_map(|p| p.2.iter().flatten())
            .flat_map(|s| [s.v_rod, s.v_slider]),
    );
    let y_range = padded(lo, hi, 0.05);
    let panels: Vec<Panel> = parts
        .iter()
        .enumerate()
        .map(|(i, (title, _, segs))| {
            let mut p = Panel::new(
                Some(title),
                Axis::linear("time in the period, t − (p−1)T (µs)", (0.0, period * 1e6))
                    .scaled(1e6),
                Axis::linear("velocity (m/s)", y_range),
            );
            p.series.push(Series::hline(
                None,
                0.0,
                (0.0, period),
                REFERENCE,
                Mark::Line(1),
            ));
            if i == 1 {
                p.series.push(Series::hline(
                    Some("mean slider velocity v∞ (steady state)"),
                    report.indicators.v_inf,
                    (0.0, period),
                    REFERENCE,
                    Mark::Dashed(2, 8, 5),
                ));
            }
            let rod: Vec<(f64, f64)> = segs.iter().flatten().map(|s| (s.phase, s.v_rod)).collect();
            p.series.push(Series::line(
                Some("rod velocity"),
                rod,
                PALETTE[0],
                Mark::Line(2),
            ));
            p.series.push(slider_series(segs));
            let events: Vec<(f64, f64)> = segs
                .iter()
                .skip(1)
                .filter_map(|seg| seg.first().map(|s| (s.phase, s.v_slider)))
                .collect();
            p.series.push(Series {
                label: Some("events (reversal of slip, stick ↔ slip)".to_owned()),
                pieces: events.into_iter().map(|e| vec![e]).collect(),
                color: PALETTE[7],
                mark: Mark::Points(4),
            });
            p
        })
        .collect();
    side_by_side(
        NAME,
        (1400, 620),
        &format!(
            "Figure 8: velocities of rod and slider, n = 2, no σ factors, √κ = 1 (T = {:.0} µs)",
            period * 1e6
        ),
        &panels,
        csv,
    )
}

/// The slider velocity as one polyline: slip segments by their two ends
/// (exact straight lines), stick segments by their samples.
pub(crate) fn slider_series(segs: &[Vec<Sample>]) -> Series {
    let pts: Vec<(f64, f64)> = segs
        .iter()
        .flat_map(|seg| {
            let keep: Vec<&Sample> = match seg.first().map(|s| s.mode) {
                Some(Mode::Slip(_)) => [seg.first(), seg.last()].into_iter().flatten().collect(),
                _ => seg.iter().collect(),
            };
            keep.into_iter().map(|s| (s.phase, s.v_slider))
        })
        .collect();
    Series::line(
        Some("slider velocity (slip: slope ±a_d; stick: equals the rod's)"),
        pts,
        PALETTE[1],
        Mark::Line(3),
    )
}
