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
//! axis is ticked at multiples of π/2. The levels are filled between the
//! contours of `v_inf` at their seven boundaries, found by marching
//! squares on the grid (`crate::numerics::contour`: linear interpolation
//! along the cells' edges, so a contour is within `O(h^2)` of the true
//! one, not on the cells' edges), with a thin dark line along each; the
//! grid's nodes are the cells' corners, and phase 2π repeats phase 0. A
//! cell with a corner without a steady state has no contour: each quarter
//! of it takes the colour of its nearest node, light grey where there is
//! none. Each level is one filled shape, so no seam shows inside it.

use super::{
    Axis, Cell, ColorBar, Csv, Dash, Figure, Kind, Look, Marker, Panel, Plot, PlotError, Preset,
    Rgb, Series, linspace, min_max, padded,
};
use crate::motor::Motor;
use crate::numerics::contour::{self, Grid};
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

/// The lines between the levels.
const CONTOUR: Rgb = Rgb(40, 40, 40);

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
    let level_of = |v: f64| (((v - lo) / width).floor().max(0.0) as usize).min(levels - 1);
    // The nodes: every phase, and 2 pi again at the end (it is phase 0),
    // by every ratio; NaN where there is no steady state.
    let xs: Vec<f64> = (0..=grid.phases)
        .map(|j| TAU * j as f64 / grid.phases as f64)
        .collect();
    let ys: Vec<f64> = (0..grid.ratios)
        .map(|i| map.points[i * grid.phases].ratio)
        .collect();
    let values: Vec<f64> = (0..grid.ratios)
        .flat_map(|i| (0..=grid.phases).map(move |j| (i, j % grid.phases)))
        .map(|(i, j)| {
            map.points[i * grid.phases + j]
                .v_inf
                .filter(|v| v.is_finite())
                .unwrap_or(f64::NAN)
        })
        .collect();
    let nodes = Grid {
        xs: &xs,
        ys: &ys,
        values: &values,
    };
    let mut panel = Panel::new(
        None,
        Axis::linear("relative phase $ψ$ = $φ_2$ − 2$φ_1$ (rad)", (0.0, TAU)).in_pi(),
        Axis::linear("amplitude ratio $d_2$/$d_1$", (0.0, grid.max_ratio)),
    );
    let fill = |color: Rgb| Look {
        color,
        dash: Dash::NoLine,
        marker: Marker::None,
        weight: 1.0,
    };
    // Each level is filled over the one below: level k covers v_inf >=
    // lo + k width (level 0 every cell whose corners all have a value).
    // The levels read off the colour bar, so they have no legend entry.
    for (k, color) in VIRIDIS.iter().enumerate() {
        let at_least = if k == 0 {
            f64::NEG_INFINITY
        } else {
            lo + k as f64 * width
        };
        let polygons = contour::region_at_least(&nodes, at_least);
        if !polygons.is_empty() {
            panel
                .series
                .push(Series::areas(None, polygons, fill(*color)));
        }
    }
    // A cell with a corner without a steady state has no contour: each
    // quarter of it takes the colour of its nearest node, light grey for
    // the missing ones.
    let mut quarters: Vec<Vec<[(f64, f64); 2]>> = vec![Vec::new(); levels + 1];
    for i in 0..grid.ratios - 1 {
        for j in 0..grid.phases {
            let corners = [(i, j), (i, j + 1), (i + 1, j), (i + 1, j + 1)];
            let value = |(i, j): (usize, usize)| values[i * (grid.phases + 1) + j];
            if corners.iter().all(|&c| !value(c).is_nan()) {
                continue;
            }
            let centre = ((xs[j] + xs[j + 1]) / 2.0, (ys[i] + ys[i + 1]) / 2.0);
            for c in corners {
                let v = value(c);
                let level = if v.is_nan() { levels } else { level_of(v) };
                quarters[level].push([(xs[c.1], ys[c.0]), centre]);
            }
        }
    }
    for (level, rects) in quarters.into_iter().enumerate() {
        if rects.is_empty() {
            continue;
        }
        let (color, label) = if level == levels {
            (MISSING, Some("no steady state"))
        } else {
            (VIRIDIS[level], None)
        };
        panel.series.push(Series::bands(label, rects, fill(color)));
    }
    // A thin line along each boundary between levels.
    let boundaries: Vec<Vec<(f64, f64)>> = (1..levels)
        .flat_map(|k| contour::lines(&nodes, lo + k as f64 * width))
        .collect();
    panel.series.push(Series {
        label: None,
        pieces: boundaries,
        look: Look::line(CONTOUR, Dash::Solid).weighted(0.4),
        kind: Kind::Curve,
    });
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::contour::area;
    use crate::optimize::map::{MapGrid, MapPoint};

    /// `v_inf = 0.3 r cos(psi)` (m/s) on a grid of 21 ratios by 24
    /// phases, with the nodes listed in `missing` left without a value:
    /// antisymmetric under `psi + pi` like the measured plane.
    fn field_map(missing: &[(usize, usize)]) -> Map {
        let grid = MapGrid {
            ratios: 21,
            phases: 24,
            max_ratio: 1.0,
        };
        let mut points = Vec::new();
        for i in 0..grid.ratios {
            for j in 0..grid.phases {
                let (ratio, phase) = (i as f64 / 20.0, TAU * j as f64 / 24.0);
                let v = (!missing.contains(&(i, j))).then(|| field(ratio, phase));
                points.push(MapPoint {
                    ratio,
                    phase,
                    v_inf: v,
                    error: None,
                    regime: if v.is_some() { "slip-slip" } else { "run-away" }.to_owned(),
                });
            }
        }
        Map {
            grid,
            points,
            marks: Vec::new(),
            stroke: 25e-6,
            f0: 1e4,
        }
    }

    fn field(ratio: f64, phase: f64) -> f64 {
        0.3 * ratio * phase.cos()
    }

    fn panel(figure: &Figure) -> &Panel {
        &figure.plot.panels[0]
    }

    #[test]
    fn contours_lie_on_the_level_sets_not_on_the_cell_edges() {
        // Along the ratio v is linear (interpolation exact); along the
        // phase, over a step h = 2 pi / 24, linear interpolation is off by
        // at most h^2 max|v''| / 8 = h^2 0.3 / 8. A boundary along the
        // cells' edges would be off by up to |grad v| h / 2, ten times
        // more here, so the test tells the two apart.
        let f = map_figure(&field_map(&[]), "plane").unwrap();
        let (lo, hi) = (-0.3, 0.3);
        let width = (hi - lo) / 8.0;
        let h = TAU / 24.0;
        let bound = h * h * 0.3 / 8.0 * (1.0 + 1e-9);
        let lines: Vec<&Series> = panel(&f)
            .series
            .iter()
            .filter(|s| s.kind == Kind::Curve && s.look.color == CONTOUR)
            .collect();
        assert_eq!(lines.len(), 1);
        let vertices: Vec<(f64, f64)> = lines[0].pieces.iter().flatten().copied().collect();
        assert!(vertices.len() > 100);
        for &(phase, ratio) in &vertices {
            let off = (1..8)
                .map(|k| (field(ratio, phase) - (lo + k as f64 * width)).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(off <= bound, "({phase}, {ratio}) is {off} off a level");
        }
    }

    #[test]
    fn levels_cover_the_plane_and_nest() {
        // Level 0 covers the whole plane (2 pi x 1); each level above
        // covers less, down to v >= lo + 7 width = 0.225, which within
        // r <= 1 is the cap around psi = 0 (and 2 pi) where r cos psi >=
        // a = 0.75, of area int_a^1 2 acos(a / r) dr = 2 (acos a -
        // a ln((1 + sqrt(1 - a^2)) / a)) = 0.2524. Its boundary is off by
        // at most h^2 0.3 / 8 in v (test above), so by d = that / 0.225
        // in r (dv/dr = 0.3 cos psi >= 0.225 there), and the area by at
        // most its width 2 acos a times d on either side.
        let f = map_figure(&field_map(&[]), "plane").unwrap();
        let areas: Vec<f64> = panel(&f)
            .series
            .iter()
            .filter(|s| s.kind == Kind::Areas)
            .map(|s| s.pieces.iter().map(|p| area(p)).sum())
            .collect();
        assert_eq!(areas.len(), 8);
        assert!((areas[0] - TAU).abs() < 1e-12, "{}", areas[0]);
        assert!(areas.windows(2).all(|w| w[1] < w[0]), "{areas:?}");
        let a: f64 = 0.75;
        let cap = 2.0 * (a.acos() - a * ((1.0 + (1.0 - a * a).sqrt()) / a).ln());
        let h = TAU / 24.0;
        let d = h * h * 0.3 / 8.0 / 0.225;
        let bound = 2.0 * 2.0 * a.acos() * d;
        assert!(
            (areas[7] - cap).abs() <= bound,
            "{} vs {cap} (bound {bound})",
            areas[7]
        );
    }

    #[test]
    fn a_point_without_a_steady_state_is_grey_and_has_no_contour_nearby() {
        // The node (r, psi) = (0.5, pi/2) has no value: its four cells get
        // a grey quarter each, one cell's area (h_psi h_r) in all, and no
        // contour enters them.
        let (i, j) = (10, 6);
        let f = map_figure(&field_map(&[(i, j)]), "plane").unwrap();
        let (h_psi, h_r) = (TAU / 24.0, 1.0 / 20.0);
        let grey: Vec<&Series> = panel(&f)
            .series
            .iter()
            .filter(|s| s.label.as_deref() == Some("no steady state"))
            .collect();
        assert_eq!(grey.len(), 1);
        let covered: f64 = grey[0]
            .pieces
            .iter()
            .map(|p| ((p[1].0 - p[0].0) * (p[1].1 - p[0].1)).abs())
            .sum();
        assert!((covered - h_psi * h_r).abs() < 1e-12, "{covered}");
        let (phase, ratio) = (TAU / 4.0, 0.5);
        let inside = |&(x, y): &(f64, f64)| {
            (x - phase).abs() < h_psi * (1.0 - 1e-9) && (y - ratio).abs() < h_r * (1.0 - 1e-9)
        };
        for s in panel(&f).series.iter().filter(|s| s.kind != Kind::Bands) {
            assert!(!s.pieces.iter().flatten().any(inside), "{:?}", s.label);
        }
    }
}
