//! The design plane of `n = 2` (docs/model.md section 15): at a fixed
//! stroke and `f_0` a signal of two harmonics is fixed by two numbers,
//! the amplitude ratio `r = d_2 / d_1` and the relative phase
//! `psi = phi_2 - 2 phi_1`. [`map`] computes `v_inf` on a grid over
//! `r` in `[0, r_max]` and `psi` in `[0, 2 pi)`, each point one exact run
//! of the `kind = "harmonics"` scene the optimiser would write, with the
//! sigma, plain Fourier and optimal signals marked.
//!
//! The plane has a symmetry that checks it: `psi + pi` is the mirrored
//! signal `-x_R` delayed by half a period (`sin(t + pi) = -sin t`, and
//! `-sin(2t + psi) = sin(2t + psi + pi)`), so without a load
//! `v_inf(r, psi + pi) = -v_inf(r, psi)` (model 7).

use super::params::Shape;
use super::problem::Problem;
use super::{Objective, Optimum};
use rayon::prelude::*;
use std::f64::consts::TAU;

/// The grid of a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapGrid {
    /// Points along the amplitude ratio, `0..=r_max` (at least 2).
    pub ratios: usize,
    /// Points along the relative phase, `i 2 pi / phases` (at least 2).
    pub phases: usize,
    /// The largest amplitude ratio.
    pub max_ratio: f64,
}

impl Default for MapGrid {
    /// 81 ratios from 0 to 1 (steps of 0.0125) by 96 phases (3.75
    /// degrees).
    fn default() -> Self {
        MapGrid {
            ratios: 81,
            phases: 96,
            max_ratio: 1.0,
        }
    }
}

/// One grid point.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPoint {
    /// `d_2 / d_1`.
    pub ratio: f64,
    /// `psi` (rad).
    pub phase: f64,
    /// `v_inf` (m/s); `None` without a steady state.
    pub v_inf: Option<f64>,
    /// Its estimated error (m/s).
    pub error: Option<f64>,
    /// The regime, or the reason there is none.
    pub regime: String,
}

/// A marked signal: the sigma, plain Fourier or optimal one.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// `"optimum"`, `"sigma"` or `"fourier"`.
    pub name: &'static str,
    /// `d_2 / d_1`.
    pub ratio: f64,
    /// `psi` (rad).
    pub phase: f64,
    /// Its `v_inf` (m/s), if it has one.
    pub v_inf: Option<f64>,
}

/// The map: grid points (phase varying fastest) and marks.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// The grid.
    pub grid: MapGrid,
    /// `grid.ratios x grid.phases` points, ratio-major.
    pub points: Vec<MapPoint>,
    /// The marked signals.
    pub marks: Vec<Mark>,
    /// Stroke (m) and fundamental frequency (Hz) of every signal.
    pub stroke: f64,
    /// `f_0` (Hz).
    pub f0: f64,
}

/// The map of an `n = 2` optimum (module docs). The grid's `max_ratio` is
/// raised to hold every mark.
pub(crate) fn map(optimum: &Optimum, grid: MapGrid) -> Map {
    let mut problem: Problem = optimum.problem.clone();
    problem.objective = Objective::VInf;
    problem.limits = Default::default();
    problem.bound = None;
    problem.also = None;
    let mut marks = vec![Mark {
        name: "optimum",
        ratio: optimum.best.shape.ratio_and_phase().0,
        phase: optimum.best.shape.ratio_and_phase().1,
        v_inf: Some(optimum.best.measured.values.v_inf),
    }];
    for r in &optimum.references {
        let (ratio, phase) = r.shape.ratio_and_phase();
        marks.push(Mark {
            name: r.name,
            ratio,
            phase,
            v_inf: r.measured.as_ref().ok().map(|m| m.values.v_inf),
        });
    }
    let top = marks.iter().map(|m| m.ratio).fold(0.0, f64::max);
    let grid = MapGrid {
        max_ratio: if top > grid.max_ratio {
            (top * 1.1 * 10.0).ceil() / 10.0
        } else {
            grid.max_ratio
        },
        ..grid
    };
    let cells: Vec<(f64, f64)> = (0..grid.ratios)
        .flat_map(|i| {
            let ratio = grid.max_ratio * i as f64 / (grid.ratios - 1) as f64;
            (0..grid.phases).map(move |j| (ratio, TAU * j as f64 / grid.phases as f64))
        })
        .collect();
    let points = cells
        .par_iter()
        .map(|&(ratio, phase)| {
            let shape = Shape::from_ratio_and_phase(ratio, phase);
            match problem.evaluate(&shape) {
                Ok(m) => MapPoint {
                    ratio,
                    phase,
                    v_inf: Some(m.values.v_inf),
                    error: m.v_inf_error,
                    regime: m.regime.to_owned(),
                },
                Err(reason) => MapPoint {
                    ratio,
                    phase,
                    v_inf: None,
                    error: None,
                    regime: reason,
                },
            }
        })
        .collect();
    Map {
        grid,
        points,
        marks,
        stroke: problem.stroke,
        f0: problem.f0,
    }
}

impl Map {
    /// The map as CSV: comment lines, the header
    /// `amplitude_ratio,relative_phase_rad,v_inf_m_per_s,error_v_inf_m_per_s,regime`,
    /// one row per grid point, then one row per mark with its name as the
    /// regime cell prefixed by `mark:`. Numbers in shortest round-trip
    /// form; a missing value is an empty cell.
    pub fn csv(&self) -> String {
        let mut text = format!(
            "# v_inf over the design plane of n = 2 harmonics (stickslip {}): x_R = d_1 sin(w_0 t) + d_2 sin(2 w_0 t + psi),\n\
             # scaled to the stroke {} m and shifted to its minimum, f_0 = {} Hz; amplitude_ratio = d_2 / d_1, relative_phase = psi.\n\
             # Rows with regime mark:NAME are the marked signals (optimum, sigma, fourier). SI units.\n",
            env!("CARGO_PKG_VERSION"),
            self.stroke,
            self.f0
        );
        let cell = |x: Option<f64>| {
            x.filter(|v| v.is_finite())
                .map_or(String::new(), |v| format!("{v}"))
        };
        let rows = std::iter::once([
            "amplitude_ratio".to_owned(),
            "relative_phase_rad".to_owned(),
            "v_inf_m_per_s".to_owned(),
            "error_v_inf_m_per_s".to_owned(),
            "regime".to_owned(),
        ])
        .chain(self.points.iter().map(|p| {
            [
                format!("{}", p.ratio),
                format!("{}", p.phase),
                cell(p.v_inf),
                cell(p.error),
                p.regime.clone(),
            ]
        }))
        .chain(self.marks.iter().map(|m| {
            [
                format!("{}", m.ratio),
                format!("{}", m.phase),
                cell(m.v_inf),
                String::new(),
                format!("mark:{}", m.name),
            ]
        }));
        for row in rows {
            text.push_str(&crate::csv_text::line(&row));
            text.push('\n');
        }
        text
    }
}
