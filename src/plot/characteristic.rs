//! The force-velocity characteristic of a drive
//! ([`crate::characteristic`]) as a figure.
//!
//! Panel (a): `v_inf` against the load (force `F`, or incline angle), the
//! curve through every point of the characteristic, with the no-load
//! speed, the stall force, the load of the largest output power and the
//! ends of the curve (the slider runs away beyond, or the run beyond did
//! not converge within `run.max_periods`) marked, the band of
//! loads that hold the slider still shaded, and the holding force at rest
//! `+-mu_0 F_c` as reference lines. Panel (b): the output power `F v_inf`
//! over the loads the drive works against (0 to the stall force), with its
//! maximum and the recommended load (half the stall force). The note
//! states the sign convention and the datasheet numbers. The CSV beside
//! the figure is the characteristic's table (`table::to_csv`).

use super::axes::tick_label;
use super::style::{Dash, GREY, Marker, PALETTE};
use super::{Axis, Figure, Look, Panel, Plot, PlotError, Preset, Series, min_max, padded};
use crate::characteristic::{
    self, Characteristic, CharacteristicOptions, LoadAxis, LoadMark, table,
};
use crate::scene::Scene;

/// The look of a marked load: its own marker and colour, no line.
fn marked(marker: Marker, colour: usize) -> Look {
    Look {
        color: PALETTE[colour],
        dash: Dash::NoLine,
        marker,
        weight: 1.0,
    }
}

/// The characteristic of `scene` with the default options (the force
/// axis over the whole range), drawn.
pub fn scene_characteristic(scene: &Scene, name: &str) -> Result<Figure, PlotError> {
    let c = characteristic::characteristic(scene, &CharacteristicOptions::default())
        .map_err(|e| PlotError::Argument(e.to_string()))?;
    figure(&c, scene, name)
}

/// Three significant digits.
fn short(x: f64) -> String {
    if x == 0.0 {
        return "0".to_owned();
    }
    let step = 10f64.powf(x.abs().log10().floor() - 2.0);
    tick_label((x / step).round() * step, step)
}

/// The figure of a computed characteristic (module docs).
pub fn figure(c: &Characteristic, scene: &Scene, name: &str) -> Result<Figure, PlotError> {
    let steady: Vec<_> = c
        .points
        .iter()
        .filter(|p| p.evaluation.is_steady())
        .collect();
    if steady.is_empty() {
        return Err(PlotError::Data {
            figure: name.to_owned(),
            reason: "no load of the range has a steady state".to_owned(),
        });
    }
    let m = c.slider_mass;
    let x_label = match c.axis {
        LoadAxis::Force => "load force $F$ (N)",
        LoadAxis::Incline => "incline angle $θ$ (°)",
    };
    let x_of = |load: f64| c.axis.parameter(load, m);
    let v_of = |p: &&characteristic::Point| p.evaluation.v_inf.unwrap_or(0.0);
    let x_range = padded(c.range.0, c.range.1, 0.02);
    let (v_lo, v_hi) = min_max(steady.iter().map(v_of).chain([0.0]));
    let y_range = padded(v_lo, v_hi, 0.06);

    // (a) v_inf against the load.
    let mut a = Panel::new(
        Some("(a) steady-state velocity"),
        Axis::linear(x_label, x_range),
        Axis::linear(&super::sym("v_inf").short_label(), y_range),
    );
    if let Some(band) = &c.held_band {
        a.series.push(Series::bands(
            Some("held still ($v_∞$ = 0)"),
            vec![[(x_of(band.lower), y_range.0), (x_of(band.upper), y_range.1)]],
            Look::line(super::style::BAND, Dash::Solid),
        ));
    }
    a.series.push(Series::hline(
        None,
        0.0,
        x_range,
        Look::line(GREY, Dash::Solid).weighted(0.5),
    ));
    if c.axis == LoadAxis::Force {
        let lines: Vec<Vec<(f64, f64)>> = [-c.holding_force, c.holding_force]
            .into_iter()
            .filter(|f| (x_range.0..=x_range.1).contains(f))
            .map(|f| vec![(f, y_range.0), (f, y_range.1)])
            .collect();
        if !lines.is_empty() {
            a.series.push(Series {
                label: Some("holding force at rest ±$µ_0F_c$".to_owned()),
                pieces: lines,
                look: Look::reference(),
                kind: super::Kind::Curve,
            });
        }
    }
    // The curve, broken where a point has no steady state.
    let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for p in &c.points {
        match p.evaluation.v_inf {
            Some(v) => pieces.last_mut().expect("one piece").push((p.x, v)),
            None => pieces.push(Vec::new()),
        }
    }
    pieces.retain(|piece| !piece.is_empty());
    a.series.push(Series {
        label: Some(super::sym("v_inf").quantity.to_owned()),
        pieces,
        look: Look::nth(0).weighted(1.2),
        kind: super::Kind::Curve,
    });
    let at = |mark: LoadMark| -> Vec<(f64, f64)> {
        c.points
            .iter()
            .filter(|p| p.marks.contains(&mark))
            .filter_map(|p| p.evaluation.v_inf.map(|v| (p.x, v)))
            .collect()
    };
    let marks = [
        (LoadMark::NoLoad, "no-load speed", marked(Marker::Circle, 1)),
        (LoadMark::Stall, "stall force", marked(Marker::Square, 2)),
        (
            LoadMark::MaxPower,
            "largest output power",
            marked(Marker::Diamond, 3),
        ),
        (
            LoadMark::RunAwayLimit,
            "runs away beyond",
            marked(Marker::Cross, 4),
        ),
        (
            LoadMark::UnsettledLimit,
            "not converged beyond",
            marked(Marker::Cross, 5),
        ),
    ];
    for (mark, label, look) in marks {
        let pts = at(mark);
        if !pts.is_empty() {
            a.series.push(Series::points(Some(label), pts, look));
        }
    }
    let mut panels = vec![a];

    // (b) output power over the loads the drive works against.
    if let Some(best) = &c.max_power {
        let stall_x = x_of(c.stall.force);
        let end = if stall_x.is_finite() {
            stall_x
        } else if c.drive > 0 {
            c.range.1
        } else {
            c.range.0
        };
        let (x0, x1) = (end.min(0.0), end.max(0.0));
        let pts: Vec<(f64, f64)> = c
            .points
            .iter()
            .filter(|p| p.x >= x0 && p.x <= x1)
            .filter_map(|p| p.evaluation.output_power().map(|w| (p.x, w)))
            .collect();
        let top = best.power.max(min_max(pts.iter().map(|p| p.1)).1);
        let x_axis = Axis::linear(x_label, padded(x0, x1, 0.03));
        let mut b = Panel::new(
            Some("(b) output power $Fv_∞$"),
            x_axis.clone(),
            Axis::linear("$Fv_∞$ (mW)", (0.0, top * 1.12e3)).scaled(1e3),
        );
        let recommended = x_of(c.stall.force / 2.0);
        if recommended.is_finite() {
            b.series.push(Series::line(
                Some("recommended load $F_{stall}$/2"),
                vec![(recommended, 0.0), (recommended, top * 1.12)],
                Look::line(GREY, Dash::Dotted),
            ));
        }
        b.series.push(Series::line(
            Some("$Fv_∞$"),
            pts,
            Look::nth(1).weighted(1.2),
        ));
        b.series.push(Series::points(
            Some("largest output power"),
            vec![(x_of(best.at.load), best.power)],
            marked(Marker::Diamond, 3),
        ));
        if stall_x.is_finite() {
            b.series.push(Series::points(
                Some("stall force"),
                vec![(stall_x, 0.0)],
                marked(Marker::Square, 2),
            ));
        }
        panels.push(b);
    }

    let d = &c.datasheet;
    let value = |x: Option<f64>| x.map_or("–".to_owned(), short);
    let note = match &c.max_power {
        Some(p) => format!(
            "F opposes forward motion (g_t = -F/m_s). No-load speed {} m/s, stall force {} N, holding force mu_0 F_c = {} N, largest output power {} mW at F = {} N, recommended load {} N.",
            short(d.max_speed),
            value(d.stall_force),
            short(d.holding_force),
            short(p.power * 1e3),
            short(p.at.load),
            value(d.recommended_load),
        ),
        None => format!(
            "F opposes forward motion (g_t = -F/m_s). No drive at zero load (v_inf = {} m/s); holding force mu_0 F_c = {} N.",
            short(d.max_speed),
            short(d.holding_force),
        ),
    };
    let notes = vec![note];
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(panels, 1, 0.62).with_notes(notes),
        csv: table::to_csv(c, scene),
        preset: Preset::SingleColumn,
    })
}
