//! The figures of `stickslip optimize` (docs/model.md section 15):
//!
//! * [`signal_figure`]: the optimal rod signal against the sigma signal of
//!   the same `n`, stroke and `f_max`, over one period: position, velocity
//!   and acceleration (the stick band `±a_0`, some hundred times narrower
//!   than the acceleration's range, is left out);
//! * [`map_figure`]: the `n = 2` design plane as a heat map of `v_inf`
//!   over the relative phase and the amplitude ratio, with the optimal,
//!   sigma and plain Fourier signals marked.
//!
//! The heat map's colours are eight levels of the viridis scale, whose
//! lightness grows monotonically, so the levels read in greyscale too; a
//! colour bar above the panel gives their values of `v_inf`; the phase
//! axis is ticked at multiples of π/2; grid points without a steady state
//! are light grey. Each cell is
//! centred on its grid point; neighbouring cells of one level in a row
//! are drawn as one rectangle.

use super::{
    Axis, Cell, ColorBar, Csv, Dash, Figure, Look, Marker, Panel, Plot, PlotError, Preset, Rgb,
    Series, linspace, min_max, padded,
};
use crate::motor::Motor;
use crate::optimize::Optimum;
use crate::optimize::map::Map;
use crate::signal::{FourierSignal, Signal};
use std::f64::consts::TAU;

/// One quantity of the rod's state.
type Quantity = fn(&crate::signal::RodState) -> f64;

/// Samples per curve.
const SAMPLES: usize = 801;

/// Eight levels of the viridis colour scale, dark to light.
const VIRIDIS: [Rgb; 8] = [
    Rgb(68, 1, 84),
    Rgb(70, 50, 126),
    Rgb(54, 92, 141),
    Rgb(39, 127, 142),
    Rgb(31, 161, 135),
    Rgb(74, 193, 109),
    Rgb(160, 218, 57),
    Rgb(253, 231, 37),
];

/// Cells without a steady state.
const MISSING: Rgb = Rgb(200, 200, 200);

fn built(
    spec: &crate::signal::SignalSpec,
    motor: &Motor,
    figure: &str,
) -> Result<FourierSignal, PlotError> {
    match Signal::build(spec, motor) {
        Ok(Signal::Fourier(s)) => Ok(s),
        Ok(Signal::Ideal(_)) => Err(PlotError::Data {
            figure: figure.to_owned(),
            reason: "the signal is not a harmonic series".to_owned(),
        }),
        Err(e) => Err(PlotError::Simulation {
            figure: figure.to_owned(),
            source: e.into(),
        }),
    }
}

/// The optimal rod signal against the sigma signal (module docs).
pub fn signal_figure(optimum: &Optimum, name: &str) -> Result<Figure, PlotError> {
    let p = &optimum.problem;
    let motor = Motor::new(p.base.motor).map_err(|e| PlotError::Simulation {
        figure: name.to_owned(),
        source: e.into(),
    })?;
    let best = built(&p.spec(&optimum.best.shape.series(p.stroke)), &motor, name)?;
    let v_best = optimum.best.measured.values.v_inf;
    let mut curves: Vec<(String, FourierSignal)> =
        vec![(format!("optimum, $v_∞$ = {v_best:.4} m/s"), best)];
    if let Some(r) = optimum.references.iter().find(|r| r.name == "sigma") {
        let label = match &r.measured {
            Ok(m) => format!("$σ$ factors (15), $v_∞$ = {:.4} m/s", m.values.v_inf),
            Err(_) => "σ factors (15)".to_owned(),
        };
        curves.push((label, built(&r.spec, &motor, name)?));
    }
    let period = 1.0 / p.f0;
    let times: Vec<f64> = linspace(0.0, period, SAMPLES).collect();
    let mut header = vec!["t_s"];
    let names = ["optimum", "sigma"];
    let mut columns: Vec<String> = Vec::new();
    for n in names.iter().take(curves.len()) {
        for q in ["x_m", "v_m_per_s", "a_m_per_s2"] {
            columns.push(format!("{q}_{n}"));
        }
    }
    header.extend(columns.iter().map(String::as_str));
    let mut csv = Csv::new(
        &[
            &format!(
                "The optimal rod signal (stickslip optimize, objective {}) against the sigma signal (15) of the same n = {}, stroke {} m and f_max = {} Hz,",
                optimum.settings.objectives[0], p.harmonics, p.stroke, p.f_max
            ),
            &format!(
                "both scaled to the stroke and shifted to their minimum, f_0 = {} Hz. SI units.",
                p.f0
            ),
        ],
        &header,
    );
    for &t in &times {
        let tau = if t >= period { 0.0 } else { t };
        let mut cells = vec![Cell::F(t)];
        for (_, s) in &curves {
            let st = s.state(tau);
            cells.extend([Cell::F(st.x), Cell::F(st.v), Cell::F(st.a)]);
        }
        csv.row(&cells);
    }
    let rows: [(&str, f64, Quantity); 3] = [
        ("rod position $x_R$ (µm)", 1e6, |s| s.x),
        ("rod velocity $v_R$ (m/s)", 1.0, |s| s.v),
        ("rod acceleration $a_R$ (m/s²)", 1.0, |s| s.a),
    ];
    let mut panels = Vec::new();
    for (label, scale, of) in rows.iter() {
        let pts: Vec<Vec<(f64, f64)>> = curves
            .iter()
            .map(|(_, s)| {
                times
                    .iter()
                    .map(|&t| (t, of(&s.state(if t >= period { 0.0 } else { t }))))
                    .collect()
            })
            .collect();
        let (lo, hi) = min_max(pts.iter().flatten().map(|q| q.1 * scale));
        let mut panel = Panel::new(
            None,
            Axis::linear("time $t$ (µs)", (0.0, period * 1e6)).scaled(1e6),
            Axis::linear(label, padded(lo, hi, 0.06)).scaled(*scale),
        );
        if *label == "rod velocity $v_R$ (m/s)" {
            panel.series.push(Series::hline(
                Some("$v_∞$ of the optimum"),
                v_best,
                (0.0, period),
                Look::reference(),
            ));
        }
        for (i, ((name, _), pts)) in curves.iter().zip(pts).enumerate() {
            panel
                .series
                .push(Series::line(Some(name), pts, Look::nth(i)));
        }
        panels.push(panel);
    }
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(panels, 1, 0.42),
        csv: csv.finish(),
        preset: Preset::SingleColumn,
    })
}

/// The `n = 2` map as a heat map (module docs).
pub fn map_figure(map: &Map, name: &str) -> Result<Figure, PlotError> {
    let grid = map.grid;
    let (lo, hi) = min_max(map.points.iter().filter_map(|p| p.v_inf));
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(PlotError::Data {
            figure: name.to_owned(),
            reason: "no grid point has a steady state".to_owned(),
        });
    }
    let levels = VIRIDIS.len();
    let width = if hi > lo {
        (hi - lo) / levels as f64
    } else {
        1.0
    };
    let level_of = |v: Option<f64>| -> Option<usize> {
        v.map(|v| (((v - lo) / width).floor().max(0.0) as usize).min(levels - 1))
    };
    let d_phase = TAU / grid.phases as f64;
    let d_ratio = grid.max_ratio / (grid.ratios - 1) as f64;
    // Rectangles per level (index `levels` for cells without a steady
    // state), merged along each row.
    let mut spans: Vec<Vec<[(f64, f64); 2]>> = vec![Vec::new(); levels + 1];
    for i in 0..grid.ratios {
        let row = &map.points[i * grid.phases..(i + 1) * grid.phases];
        let ratio = row[0].ratio;
        // Cells overlap by 2 % so that no seam shows between them.
        let y0 = (ratio - 0.51 * d_ratio).max(0.0);
        let y1 = (ratio + 0.51 * d_ratio).min(grid.max_ratio);
        let mut j = 0;
        while j < row.len() {
            let level = level_of(row[j].v_inf).unwrap_or(levels);
            let mut k = j + 1;
            while k < row.len() && level_of(row[k].v_inf).unwrap_or(levels) == level {
                k += 1;
            }
            let x0 = (row[j].phase - 0.51 * d_phase).max(0.0);
            let x1 = row[k - 1].phase + 0.51 * d_phase;
            spans[level].push([(x0, y0), (x1, y1)]);
            // A cell at phase 0 also covers the end of the period (2 pi
            // is phase 0).
            if j == 0 {
                spans[level].push([(TAU - 0.51 * d_phase, y0), (TAU, y1)]);
            }
            j = k;
        }
    }
    let mut panel = Panel::new(
        None,
        Axis::linear("relative phase $ψ$ = $φ_2$ − 2$φ_1$ (rad)", (0.0, TAU)).in_pi(),
        Axis::linear("amplitude ratio $d_2$/$d_1$", (0.0, grid.max_ratio)),
    );
    for (level, rects) in spans.into_iter().enumerate() {
        if rects.is_empty() {
            continue;
        }
        // The levels read off the colour bar; only cells without a steady
        // state have a legend entry.
        let (color, label) = if level == levels {
            (MISSING, Some("no steady state"))
        } else {
            (VIRIDIS[level], None)
        };
        panel.series.push(Series::bands(
            label,
            rects,
            Look {
                color,
                dash: Dash::NoLine,
                marker: Marker::None,
                weight: 1.0,
            },
        ));
    }
    let markers = [
        ("optimum", Marker::Diamond, Rgb(213, 94, 0)),
        ("sigma", Marker::Circle, Rgb(0, 0, 0)),
        ("fourier", Marker::Square, Rgb(0, 0, 0)),
    ];
    for (mark_name, marker, color) in markers {
        if let Some(m) = map.marks.iter().find(|m| m.name == mark_name) {
            let text = match mark_name {
                "optimum" => "optimum",
                "sigma" => "$σ$ factors (15)",
                _ => "plain Fourier series",
            };
            let label = match m.v_inf {
                Some(v) => format!("{text}, $v_∞$ = {v:.4} m/s"),
                None => text.to_owned(),
            };
            panel.series.push(Series::points(
                Some(&label),
                vec![(m.phase, m.ratio)],
                Look {
                    color,
                    dash: Dash::NoLine,
                    marker,
                    weight: 1.0,
                },
            ));
        }
    }
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(vec![panel], 1, 0.62).with_colorbar(ColorBar {
            label: super::sym("v_inf").label(),
            range: (lo, lo + width * levels as f64),
            colors: VIRIDIS.to_vec(),
        }),
        csv: map.csv(),
        preset: Preset::SingleColumn,
    })
}
