//! Figures 6 and 7: the indicators of the paper's section 7 against the
//! number of harmonics `n` at equal maximum frequencies
//! `f_max = n sqrt(kappa) sqrt(a_0 / (2 x_Rmax))` (37), without (figure 6)
//! and with (figure 7) sigma factors (15).
//!
//! Each curve is one level `L = n sqrt(kappa)` (so `sqrt(kappa) = L / n`);
//! the panels show the steady-state velocity `v_inf`, the start-up time
//! `T p_0.99`, the smoothness `zeta_inf` (16), the velocity to input power
//! ratio `v_inf / S` (35) and the durability `delta_inf` (18). Both figures
//! share their y ranges, so that the effect of the sigma factors reads off
//! directly. The grid itself is run by the caller (the example uses
//! `examples/sweeps/section7.toml` and [`crate::sweep`]); this module only
//! draws [`GridPoint`]s.

use super::axes::tick_label;
use super::{Axis, Cell, Csv, Figure, Look, Panel, Plot, PlotError, Preset, Series, min_max};
use crate::indicator::Indicator;
use crate::simulation::RunReport;

/// The ideal stick-slip maximum velocity of the paper's motor, from Part I
/// (m/s), drawn as a reference in the `v_inf` panels.
pub const IDEAL_STICK_SLIP_MAX: f64 = 0.06;

/// One case of the section-7 grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPoint {
    /// Level `L = n sqrt(kappa)`.
    pub level: f64,
    /// Number of harmonics `n`.
    pub n: usize,
    /// Lanczos sigma factors (15).
    pub sigma: bool,
    /// Highest frequency `f_max = n f_0` (Hz).
    pub f_max: f64,
    /// Period `T` (s).
    pub period: f64,
    /// `v_inf` (m/s).
    pub v_inf: f64,
    /// `p_0.99`, if the start-up was reached.
    pub startup_periods: Option<u64>,
    /// Smoothness `zeta_inf` (16).
    pub smoothness: f64,
    /// Durability `delta_inf` (18) (1/N).
    pub durability: f64,
    /// Time in stick / simulated start-up time.
    pub stiction_fraction: f64,
    /// Time in stick / period, in the steady state.
    pub stiction_fraction_steady: f64,
    /// `v_inf / S` (m/(s VA)), if an actuator was given.
    pub velocity_per_power: Option<f64>,
}

impl GridPoint {
    /// The point of a run of the level-`level` case with `n` harmonics.
    /// Values are [`RunReport::value`]'s, the definitions of every output
    /// (NaN where a value does not exist).
    pub fn from_report(level: f64, n: usize, sigma: bool, report: &RunReport) -> Self {
        let value = |i: Indicator| report.value(i).unwrap_or(f64::NAN);
        GridPoint {
            level,
            n,
            sigma,
            f_max: report.f_max.unwrap_or(f64::NAN),
            period: report.period,
            v_inf: value(Indicator::VInf),
            startup_periods: report.startup_periods,
            smoothness: value(Indicator::Smoothness),
            durability: value(Indicator::Durability),
            stiction_fraction: value(Indicator::StictionFraction),
            stiction_fraction_steady: report.indicators.stiction_fraction,
            velocity_per_power: report.value(Indicator::VelocityPerPower),
        }
    }

    /// Start-up time `T p_0.99` (s).
    pub fn startup_time(&self) -> Option<f64> {
        self.startup_periods.map(|p| p as f64 * self.period)
    }
}

/// One indicator panel: title, the indicator's key in the table of
/// symbols and the unit drawn, how to read the value, the drawing scale.
struct PanelSpec {
    title: &'static str,
    symbol: &'static str,
    unit: &'static str,
    value: fn(&GridPoint) -> Option<f64>,
    scale: f64,
    /// Logarithmic y axis (values spanning two decades).
    log: bool,
}

const PANELS: [PanelSpec; 5] = [
    PanelSpec {
        title: "(a) steady-state velocity",
        log: false,
        symbol: "v_inf",
        unit: "m/s",
        value: |p| Some(p.v_inf),
        scale: 1.0,
    },
    PanelSpec {
        title: "(b) start-up time",
        log: true,
        symbol: "startup_time",
        unit: "ms",
        value: GridPoint::startup_time,
        scale: 1e3,
    },
    PanelSpec {
        title: "(c) smoothness",
        log: true,
        symbol: "smoothness",
        unit: "1",
        value: |p| Some(p.smoothness),
        scale: 1.0,
    },
    PanelSpec {
        title: "(d) velocity per input power",
        log: false,
        symbol: "velocity_per_power",
        unit: "mm s⁻¹ VA⁻¹",
        value: |p| p.velocity_per_power,
        scale: 1e3,
    },
    PanelSpec {
        title: "(e) durability",
        log: false,
        symbol: "durability",
        unit: "N⁻¹",
        value: |p| Some(p.durability),
        scale: 1.0,
    },
];

/// Levels in the grid, ascending.
fn levels(points: &[GridPoint]) -> Vec<f64> {
    let mut l: Vec<f64> = points.iter().map(|p| p.level).collect();
    l.sort_by(f64::total_cmp);
    l.dedup();
    l
}

/// The power of ten at or below `min / 1.06`, for a logarithmic axis.
fn nice_bottom(min: f64) -> f64 {
    10f64.powf((min / 1.06).log10().floor())
}

/// A round upper limit for an axis from 0 that holds `max` with a margin.
fn nice_top(max: f64) -> f64 {
    let raw = max * 1.06;
    let mag = 10f64.powf(raw.log10().floor());
    let steps = [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0];
    steps
        .iter()
        .map(|s| s * mag)
        .find(|v| *v >= raw)
        .unwrap_or(10.0 * mag)
}

/// Figures 6 (without sigma) and 7 (with sigma) from the grid points,
/// which must hold both sigma settings.
pub fn figures6_7(points: &[GridPoint]) -> Result<[Figure; 2], PlotError> {
    let levels = levels(points);
    let (n_lo, n_hi) = points
        .iter()
        .fold((usize::MAX, 0), |(lo, hi), p| (lo.min(p.n), hi.max(p.n)));
    if levels.is_empty() || !points.iter().any(|p| p.sigma) || !points.iter().any(|p| !p.sigma) {
        return Err(PlotError::Data {
            figure: "fig6/fig7".to_owned(),
            reason: "the grid needs points with and without sigma factors".to_owned(),
        });
    }
    // Shared y ranges for both figures: linear from 0 to a round value above
    // the largest value, or logarithmic between 1-2-5 values around all.
    let ranges: Vec<(f64, f64)> = PANELS
        .iter()
        .map(|ind| {
            let (lo, hi) = min_max(
                points
                    .iter()
                    .filter_map(|p| (ind.value)(p))
                    .filter(|v| v.is_finite() && *v > 0.0)
                    .map(|v| v * ind.scale),
            );
            if ind.log {
                (nice_bottom(lo), nice_top(hi))
            } else {
                (0.0, nice_top(hi))
            }
        })
        .collect();
    let make = |sigma: bool| -> Result<Figure, PlotError> {
        let name = if sigma {
            "fig7_indicators_with_sigma"
        } else {
            "fig6_indicators_without_sigma"
        };
        let mut csv = Csv::new(
            &[
                &format!(
                    "Figure {}: section-7 indicators at equal f_max (37), {} Lanczos sigma factors (15).",
                    if sigma { 7 } else { 6 },
                    if sigma { "with" } else { "without" }
                ),
                "level = n sqrt(kappa); paper motor and Table 1 actuator, stroke 25 um, continuous signal. SI units;",
                "startup_time = T p_0.99; stiction_fraction over the simulated start-up, stiction_fraction_steady over a steady-state period; empty: not available.",
            ],
            &[
                "level",
                "n",
                "sqrt_kappa",
                "f_max_hz",
                "period_s",
                "v_inf_m_per_s",
                "startup_periods",
                "startup_time_s",
                "smoothness",
                "velocity_per_power_m_per_s_va",
                "durability_per_n",
                "stiction_fraction",
                "stiction_fraction_steady",
            ],
        );
        let mut rows: Vec<&GridPoint> = points.iter().filter(|p| p.sigma == sigma).collect();
        rows.sort_by(|a, b| a.level.total_cmp(&b.level).then(a.n.cmp(&b.n)));
        for p in &rows {
            let opt = |v: Option<f64>| v.map_or(Cell::S(""), Cell::F);
            csv.row(&[
                Cell::F(p.level),
                Cell::I(p.n as i64),
                Cell::F(p.level / p.n as f64),
                Cell::F(p.f_max),
                Cell::F(p.period),
                Cell::F(p.v_inf),
                p.startup_periods.map_or(Cell::S(""), |v| Cell::I(v as i64)),
                opt(p.startup_time()),
                Cell::F(p.smoothness),
                opt(p.velocity_per_power),
                Cell::F(p.durability),
                Cell::F(p.stiction_fraction),
                Cell::F(p.stiction_fraction_steady),
            ]);
        }
        let panels: Vec<Panel> = PANELS
            .iter()
            .zip(&ranges)
            .enumerate()
            .map(|(i, (ind, range))| {
                let q = super::sym(ind.symbol).quantity;
                let label = if ind.unit == "1" {
                    q.to_owned()
                } else {
                    format!("{q} ({})", ind.unit)
                };
                let mut panel = Panel::new(
                    Some(ind.title),
                    Axis::linear(
                        &super::sym("harmonics").label(),
                        (n_lo as f64 - 0.3, n_hi as f64 + 0.3),
                    )
                    .with_ticks((n_hi - n_lo + 1).min(7))
                    .integers(),
                    if ind.log {
                        Axis::log(&label, *range)
                    } else {
                        Axis::linear(&label, *range).with_ticks(4)
                    }
                    .scaled(ind.scale),
                );
                if i == 0 {
                    panel.series.push(Series::hline(
                        Some("ideal stick-slip maximum, 0.06 m/s"),
                        IDEAL_STICK_SLIP_MAX,
                        (n_lo as f64 - 0.3, n_hi as f64 + 0.3),
                        Look::reference(),
                    ));
                }
                for (c, level) in levels.iter().enumerate() {
                    let pts: Vec<(f64, f64)> = rows
                        .iter()
                        .filter(|p| p.level == *level)
                        .filter_map(|p| {
                            (ind.value)(p)
                                .filter(|v| v.is_finite())
                                .map(|v| (p.n as f64, v))
                        })
                        .collect();
                    let f_max = rows
                        .iter()
                        .find(|p| p.level == *level)
                        .map_or(f64::NAN, |p| p.f_max);
                    let label = format!(
                        "$n$√$κ$ = {} ({:.1} kHz)",
                        tick_label(*level, 1.0),
                        f_max / 1e3
                    );
                    panel
                        .series
                        .push(Series::line(Some(&label), pts, level_look(c)));
                }
                panel
            })
            .collect();
        let notes = vec![format!(
            "f_max = n sqrt(kappa) 1574.8 Hz (37); paper motor, Table 1 actuator, stroke 25 µm; n = {n_lo} … {n_hi}; lines guide the eye."
        )];
        Ok(Figure {
            name: name.to_owned(),
            plot: Plot::grid(panels, 3, 0.8).with_notes(notes),
            csv: csv.finish(),
            preset: Preset::DoubleColumn,
        })
    };
    Ok([make(false)?, make(true)?])
}

/// The look of the `c`-th level: its own colour, dash pattern and marker
/// (every point is a case of the grid).
fn level_look(c: usize) -> Look {
    const MARKERS: [super::Marker; 6] = [
        super::Marker::Circle,
        super::Marker::Square,
        super::Marker::Triangle,
        super::Marker::Diamond,
        super::Marker::TriangleDown,
        super::Marker::Plus,
    ];
    Look::nth(c).with_marker(MARKERS[c % MARKERS.len()])
}

#[cfg(test)]
mod tests {
    use super::{nice_bottom, nice_top};

    #[test]
    fn nice_tops_are_round_and_above() {
        for (max, top) in [(0.29, 0.4), (47.0, 50.0), (1.3, 1.5)] {
            assert!((nice_top(max) - top).abs() < 1e-12 * top, "{max}");
        }
        for (min, bottom) in [(0.49, 0.1), (1.5, 1.0), (60.0, 10.0)] {
            assert!((nice_bottom(min) - bottom).abs() < 1e-12 * bottom, "{min}");
        }
    }
}
