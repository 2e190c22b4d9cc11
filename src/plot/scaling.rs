//! The influence of the actuator stroke (the paper's section 8).
//!
//! * Figure 9, a schematic: the signal's highest frequency
//!   `f_max = n sqrt(kappa) sqrt(a_0 / (2 x_hat))` (37) falls as
//!   `1/sqrt(x_hat)`, the actuator's allowed frequency as `1/x_hat` (43).
//!   `f_max` is drawn for the default signal (`n = 2`, `sqrt(kappa) = 6`);
//!   `f_allowed` is scaled to cross it at the paper's stroke of 25 um. The
//!   best design has `f_max = f_allowed`.
//! * The stroke scaling law: with the signal shape fixed and
//!   `T ∝ sqrt(x_hat)` (40), `x_inf ∝ x_hat` (38), `v_inf ∝ sqrt(x_hat)`
//!   (39) and the start-up time `∝ sqrt(x_hat)` (42). Runs from 1 nm to
//!   1 mm for three signals, with the least-squares slopes of the log-log
//!   data in the legend.

use super::{
    Anchor, Axis, Cell, Csv, Figure, Look, Marker, Panel, Plot, PlotError, Preset, Series, min_max,
};
use crate::motor::Motor;
use crate::numerics::line_fit::loglog_slope;
use crate::scene::Scene;
use crate::signal::SignalSpec;
use crate::simulation;
use rayon::prelude::*;

/// Figure 9: `f_max` (37) and `f_allowed` (43) against the stroke.
pub fn figure9(motor: &Motor) -> Result<Figure, PlotError> {
    const NAME: &str = "fig9_fmax_fallowed";
    let (n, sqrt_kappa, x_design) = (2.0, 6.0, 25e-6);
    let f_max = |x: f64| n * sqrt_kappa * (motor.a_0() / (2.0 * x)).sqrt();
    let f_design = f_max(x_design);
    let f_allowed = |x: f64| f_design * x_design / x;
    let strokes: Vec<f64> = (0..=60)
        .map(|i| 10f64.powf(-6.0 + i as f64 / 20.0))
        .collect();
    let mut csv = Csv::new(
        &[
            "Figure 9 (schematic): f_max = n sqrt(kappa) sqrt(a_0/(2 x_hat)) (37) for n = 2, sqrt(kappa) = 6, a_0 = 124 m/s^2,",
            "and f_allowed = f_max(25 um) * 25 um / x_hat (43), chosen to cross f_max at x_hat = 25 um. SI units.",
        ],
        &["stroke_m", "f_max_hz", "f_allowed_hz"],
    );
    for &x in &strokes {
        csv.row(&[Cell::F(x), Cell::F(f_max(x)), Cell::F(f_allowed(x))]);
    }
    let mut p = Panel::new(
        None,
        Axis::log("actuator stroke $x̂_R$ (µm)", (1.0, 1e3)).scaled(1e6),
        Axis::log("frequency $f$ (kHz)", (0.3, 1e3)).scaled(1e-3),
    );
    p.series.push(Series::line(
        Some("$f_{max}$ ∝ 1/√$x̂_R$ (37)"),
        // Power laws are straight on log-log axes: the ends draw them exactly.
        [strokes[0], strokes[strokes.len() - 1]]
            .iter()
            .map(|&x| (x, f_max(x)))
            .collect(),
        Look::nth(1).weighted(1.4),
    ));
    p.series.push(Series::line(
        Some("$f_{allowed}$ ∝ 1/$x̂_R$ (43)"),
        [strokes[0], strokes[strokes.len() - 1]]
            .iter()
            .map(|&x| (x, f_allowed(x)))
            .collect(),
        Look::nth(2).weighted(1.4),
    ));
    p.series.push(Series::line(
        Some("best design, $f_{max}$ = $f_{allowed}$"),
        vec![(x_design, 1e2), (x_design, 1e6)],
        Look::reference(),
    ));
    p.series.push(Series::points(
        None,
        vec![(x_design, f_design)],
        Look::nth(0).with_marker(Marker::Circle),
    ));
    p.note((5e-6, 1.2e3), "bandwidth unused", Anchor::Middle);
    p.note((1.8e-4, 3e5), "velocity impaired", Anchor::Middle);
    p.note(
        (x_design * 1.3, f_design * 1.3),
        &format!("{:.1} kHz at 25 µm", f_design / 1e3),
        Anchor::Start,
    );
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(vec![p], 1, 0.75),
        csv: csv.finish(),
        preset: Preset::SingleColumn,
    })
}

/// What the stroke scaling figure needs of a run.
struct Run {
    period: f64,
    v_inf: f64,
    startup_periods: Option<u64>,
}

/// One signal of the stroke scaling figure.
struct Shape {
    label: &'static str,
    kappa: f64,
    n: usize,
    sigma: bool,
}

const SHAPES: [Shape; 3] = [
    Shape {
        label: "$n$ = 2, √$κ$ = 6, with $σ$",
        kappa: 36.0,
        n: 2,
        sigma: true,
    },
    Shape {
        label: "$n$ = 3, $κ$ = 1, no $σ$",
        kappa: 1.0,
        n: 3,
        sigma: false,
    },
    Shape {
        label: "$n$ = 5, $κ$ = 0.36, with $σ$",
        kappa: 0.36,
        n: 5,
        sigma: true,
    },
];

/// The stroke scaling law: `v_inf`, the steady-state step `x_inf` and the
/// start-up time against the stroke (1 nm to 1 mm, 13 strokes) for three
/// signals of the base scene's motor, with least-squares log-log slopes.
pub fn stroke_scaling(base: &Scene) -> Result<Figure, PlotError> {
    const NAME: &str = "stroke_scaling";
    let strokes: Vec<f64> = (0..=12)
        .map(|i| 10f64.powf(-9.0 + i as f64 / 2.0))
        .collect();
    let jobs: Vec<(usize, f64)> = (0..SHAPES.len())
        .flat_map(|s| strokes.iter().map(move |&x| (s, x)))
        .collect();
    let runs: Vec<Result<Run, crate::error::Error>> = jobs
        .par_iter()
        .map(|&(s, stroke)| {
            let shape = &SHAPES[s];
            let mut scene = base.clone();
            scene.signal = SignalSpec::fourier(stroke, shape.kappa, shape.n, shape.sigma);
            scene.actuator = None;
            scene.outputs.indicators = vec![
                crate::indicator::Indicator::VInf,
                crate::indicator::Indicator::StartupTime,
            ];
            scene.outputs.trajectory = false;
            scene.outputs.events = false;
            simulation::steady(&scene).map(|r| Run {
                period: r.period,
                v_inf: r.indicators.v_inf,
                startup_periods: r.startup_periods,
            })
        })
        .collect();
    let mut csv = Csv::new(
        &[
            "Stroke scaling (section 8): steady-state velocity v_inf (39), step x_inf = v_inf T (38) and start-up time T p_0.99 (42)",
            "against the stroke x_hat, signal shape fixed (kappa, n, sigma), so T ∝ sqrt(x_hat) (40). Paper motor. SI units.",
        ],
        &[
            "signal",
            "n",
            "kappa",
            "sigma",
            "stroke_m",
            "period_s",
            "v_inf_m_per_s",
            "x_inf_m",
            "startup_periods",
            "startup_time_s",
        ],
    );
    // Per signal: (stroke, v_inf), (stroke, x_inf), (stroke, startup time).
    let mut data: Vec<[Vec<(f64, f64)>; 3]> =
        vec![Default::default(), Default::default(), Default::default()];
    for (&(s, stroke), run) in jobs.iter().zip(runs) {
        let Run {
            period,
            v_inf,
            startup_periods: p,
        } = run.map_err(PlotError::simulation(NAME))?;
        let shape = &SHAPES[s];
        let startup = p.map(|p| p as f64 * period);
        csv.row(&[
            Cell::S(crate::plot::visible(shape.label).replace(',', ";").as_str()),
            Cell::I(shape.n as i64),
            Cell::F(shape.kappa),
            Cell::S(if shape.sigma { "true" } else { "false" }),
            Cell::F(stroke),
            Cell::F(period),
            Cell::F(v_inf),
            Cell::F(v_inf * period),
            p.map_or(Cell::S(""), |p| Cell::I(p as i64)),
            startup.map_or(Cell::S(""), Cell::F),
        ]);
        data[s][0].push((stroke, v_inf));
        data[s][1].push((stroke, v_inf * period));
        if let Some(t) = startup {
            data[s][2].push((stroke, t));
        }
    }
    let quantities = [
        ("(a) $v_∞$ (39): slope ½", "$v_∞$ (m/s)", 0.5),
        ("(b) $x_∞$ (38): slope 1", "$x_∞$ = $v_∞T$ (m)", 1.0),
        ("(c) $Tp_{0.99}$ (42): slope ½", "$Tp_{0.99}$ (s)", 0.5),
    ];
    const SHAPE_MARKERS: [Marker; 3] = [Marker::Circle, Marker::Square, Marker::Triangle];
    let mut panels = Vec::new();
    let mut slopes = Vec::new();
    for (q, (title, label, _)) in quantities.iter().enumerate() {
        let (lo, hi) = min_max(data.iter().flat_map(|d| d[q].iter().map(|p| p.1)));
        // Whole decades.
        let y_range = (
            10f64.powf(lo.log10().floor()),
            10f64.powf(hi.log10().ceil()),
        );
        let mut p = Panel::new(
            Some(title),
            Axis::log(
                "stroke $x̂_R$ (m)",
                (strokes[0] / 2.0, strokes[strokes.len() - 1] * 2.0),
            ),
            Axis::log(label, y_range),
        );
        let mut line = format!(
            "panel {} fitted log-log slopes ({}):",
            &title[..3],
            SHAPES.map(|s| crate::plot::visible(s.label)).join("; ")
        );
        for (s, shape) in SHAPES.iter().enumerate() {
            let slope = loglog_slope(&data[s][q]);
            line.push_str(&format!(
                " {slope:.9}{}",
                if s + 1 < SHAPES.len() { "," } else { "" }
            ));
            p.series.push(Series::line(
                Some(shape.label),
                data[s][q].clone(),
                Look::nth(s).with_marker(SHAPE_MARKERS[s % SHAPE_MARKERS.len()]),
            ));
        }
        slopes.push(line);
        panels.push(p);
    }
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(panels, 3, 0.9).with_notes(slopes),
        csv: csv.finish(),
        preset: Preset::DoubleColumn,
    })
}
