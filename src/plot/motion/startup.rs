//! The start-up figure: `v_p` against `p` from rest, with `v_inf` and
//! `p_0.99`, run past `p_0.99` ([`startup_end`]) from where the run
//! stopped, so that the approach shows and the mark lies inside the frame.

use super::short;
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{PeriodEngine, PeriodStart};
use crate::plot::{
    Axis, Cell, Csv, Dash, Figure, Look, Marker, Panel, Plot, PlotError, Preset, Series, min_max,
    padded,
};
use crate::scene::Scene;
use crate::simulation;

/// The last period the start-up figure shows for `p_0.99`: a quarter
/// more periods, at least three more, so that the approach to `v_inf`
/// after `p_0.99` shows and its mark lies inside the frame.
pub fn startup_end(p99: u64) -> u64 {
    (p99 + p99.div_ceil(4)).max(p99 + 3)
}

/// The start-up from rest: `v_p` against `p`, with `v_inf` and `p_0.99`.
pub fn startup(scene: &Scene, name: &str) -> Result<Figure, PlotError> {
    let mut quiet = scene.clone();
    quiet.outputs.trajectory = false;
    quiet.outputs.events = false;
    let outcome = simulation::simulate(&quiet).map_err(PlotError::simulation(name))?;
    let report = outcome.report().ok_or_else(|| {
        PlotError::Argument(format!(
            "the start-up figure needs a steady state; the scene's outcome is {}",
            outcome.regime()
        ))
    })?;
    let transient = report.transient.as_ref().ok_or_else(|| PlotError::Data {
        figure: name.to_owned(),
        reason: "the run simulated no start-up".to_owned(),
    })?;
    let v_inf = report.indicators.v_inf;
    let period = report.period;
    // The start-up runs on past p_0.99 (from where the run stopped), so
    // that the approach to v_inf shows and p_0.99 lies inside the frame.
    let mut v_p = transient.mean_velocities.clone();
    if let Some(p99) = report.startup_periods {
        let end = startup_end(p99) as usize;
        v_p.truncate(end);
        if v_p.len() < end {
            let (signal, motor) = simulation::build_prescribed(scene, "the start-up figure")
                .map_err(PlotError::simulation(name))?;
            let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
            let mut start = PeriodStart {
                velocity: transient.final_velocity,
                mode: Some(transient.final_mode),
            };
            for p in v_p.len() + 1..=end {
                let sim = |e: crate::error::SimulationError| PlotError::simulation(name)(e.into());
                let step = engine.run_period(p as u64, start, &mut ()).map_err(sim)?;
                v_p.push(step.step / period);
                start = PeriodStart {
                    velocity: step.velocity,
                    mode: Some(step.mode),
                };
            }
        }
    }
    let mut csv = Csv::new(
        &[&format!(
            "Start-up from rest: mean velocity v_p of period p (m/s); v_inf = {v_inf:e} m/s; p_0.99 = {}; T = {:e} s.",
            report
                .startup_periods
                .map_or("none".to_owned(), |p| p.to_string()),
            report.period
        )],
        &["p", "v_p_m_per_s", "v_p_over_v_inf"],
    );
    let pts: Vec<(f64, f64)> = v_p
        .iter()
        .enumerate()
        .map(|(i, v)| ((i + 1) as f64, *v))
        .collect();
    for (p, v) in &pts {
        csv.row(&[Cell::I(*p as i64), Cell::F(*v), Cell::F(v / v_inf)]);
    }
    let p_end = pts.len().max(2) as f64;
    let (lo, hi) = min_max(pts.iter().map(|p| p.1).chain([0.0, v_inf]));
    let mut panel = Panel::new(
        None,
        Axis::linear(&crate::plot::sym("p").label(), (0.0, p_end + 0.5)).integers(),
        Axis::linear(&crate::plot::sym("v_p").label(), padded(lo, hi, 0.06)),
    );
    if let Some(p99) = report.startup_periods {
        panel.series.push(Series::line(
            Some(crate::plot::sym("startup_periods").quantity),
            vec![(p99 as f64, lo - (hi - lo)), (p99 as f64, hi + (hi - lo))],
            Look::line(crate::plot::style::GREY, Dash::Dotted),
        ));
    }
    let look = if pts.len() <= 60 {
        Look::nth(0).with_marker(Marker::Circle)
    } else {
        Look::nth(0)
    };
    panel.series.push(Series::line(
        Some(crate::plot::sym("v_p").quantity),
        pts,
        look,
    ));
    // Drawn over v_p, which approaches it.
    panel.series.push(Series::hline(
        Some(crate::plot::sym("v_inf").quantity),
        v_inf,
        (0.0, p_end + 0.5),
        Look::reference(),
    ));
    let notes = vec![format!(
        "Start-up from rest: mean velocity v_p of period p against v_inf = {} m/s; p_0.99 = {}, the first period with v_p/v_inf ≥ 0.99.",
        short(v_inf),
        report
            .startup_periods
            .map_or("not reached".to_owned(), |p| p.to_string()),
    )];
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(vec![panel], 1, 0.62).with_notes(notes),
        csv: csv.finish(),
        preset: Preset::SingleColumn,
    })
}
