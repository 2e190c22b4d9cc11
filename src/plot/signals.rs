//! The rod signals of the paper's section 4 and 7: figures 2, 3, 4 and 5.
//!
//! * Figure 2: the ideal signal (11) and its partial sums (8) with the
//!   coefficients (12)-(14), `n = 2` and 15, for a discrete (`t_1/T = 0.5`)
//!   and the continuous (`t_1 = T`) signal at `kappa = 1`. The partial sums
//!   are shown as they come out of (12)-(14), before stroke scaling and
//!   shift, so that they lie over the ideal signal and show its Gibbs
//!   over- and undershoot. The paper draws the acceleration on split
//!   scales; here it gets two rows, the full range and a zoom to
//!   `±400 m/s^2` that shows the stick band `±a_0`.
//! * Figure 3: the normalised amplitudes `d*_k = d_k / x_hat` of the
//!   stroke-scaled signals (section 4), without and with sigma factors (15).
//! * Figure 4: the signals the simulator uses (scaled to the stroke and
//!   shifted to the minimum) for `n = 2` and 5, `kappa = 1`, without and with
//!   sigma factors.
//! * Figure 5: signals of equal `f_max = n sqrt(kappa) f_0(kappa = 1)` (37):
//!   more harmonics mean a lower fundamental frequency.

use super::style::BAND;
use super::{
    Axis, Cell, Csv, Dash, Figure, Look, Marker, Panel, Plot, PlotError, Preset, Series, linspace,
    min_max, padded,
};
use crate::motor::Motor;
use crate::signal::fourier::sigma_factor;
use crate::signal::{FourierSignal, IdealShape, IdealSignal, RodState, Signal, SignalSpec};

/// Samples per curve (several per printed point of a panel).
const SAMPLES: usize = 1201;

/// Stroke of the paper's motor (m).
const STROKE: f64 = 25e-6;

fn shape(kappa: f64, duty: f64) -> IdealShape {
    IdealShape::with_kappa(STROKE, kappa, duty)
}

/// The stroke-scaled, shifted signal the simulator uses.
fn built(
    kappa: f64,
    n: usize,
    sigma: bool,
    motor: &Motor,
    figure: &str,
) -> Result<FourierSignal, PlotError> {
    let spec = SignalSpec::Fourier {
        shape: shape(kappa, 1.0),
        harmonics: n,
        sigma,
    };
    match Signal::build(&spec, motor).map_err(|e| PlotError::simulation(figure)(e.into()))? {
        Signal::Fourier(s) => Ok(s),
        Signal::Ideal(_) => unreachable!("a Fourier spec builds a Fourier signal"),
    }
}

// ------------------------------------------------------------ figure 2 ----

/// Which quantity of the rod a row shows.
#[derive(Clone, Copy)]
enum Quantity {
    Position,
    Velocity,
    Acceleration,
}

impl Quantity {
    fn of(self, st: RodState) -> f64 {
        match self {
            Quantity::Position => st.x,
            Quantity::Velocity => st.v,
            Quantity::Acceleration => st.a,
        }
    }

    fn axis(self) -> (&'static str, f64) {
        match self {
            Quantity::Position => ("rod position $x_R$ (µm)", 1e6),
            Quantity::Velocity => ("rod velocity $v_R$ (m/s)", 1.0),
            Quantity::Acceleration => ("rod acceleration $a_R$ (m/s²)", 1.0),
        }
    }
}

/// The ideal signal over one period `[0, T]`, drawn with its jump at `t_1`
/// as a vertical line; velocity and acceleration are infinite there (the
/// jump's impulse), drawn as a vertical line to far below the axis.
fn ideal_curve(ideal: &IdealSignal, q: Quantity) -> Vec<(f64, f64)> {
    let (t1, period) = (ideal.t1(), ideal.period());
    // The left limit at t_1 ends the acceleration phase; `state_before(0)`
    // would be the end of the previous period, so t = 0 uses `state`.
    let mut pts: Vec<(f64, f64)> = linspace(0.0, t1, SAMPLES)
        .map(|t| {
            (
                t,
                q.of(if t > 0.0 {
                    ideal.state_before(t)
                } else {
                    ideal.state(t)
                }),
            )
        })
        .collect();
    let far_below = -1e30;
    match q {
        Quantity::Position => pts.push((t1, 0.0)),
        Quantity::Velocity | Quantity::Acceleration => {
            pts.push((t1, far_below));
            pts.push((t1, q.of(ideal.state(t1.min(period * (1.0 - 1e-12))))));
        }
    }
    if t1 < period {
        pts.push((period, q.of(ideal.state(t1))));
    }
    pts
}

/// Figure 2: ideal signals and their partial sums for `n = 2` and 15,
/// discrete (`t_1/T = 0.5`) and continuous, `kappa = 1`.
pub fn figure2(motor: &Motor) -> Result<Figure, PlotError> {
    const NAME: &str = "fig2_ideal_and_fourier";
    let a0 = motor.a_0();
    let columns = [
        ("(a) discrete, $t_1$/$T$ = 0.5", 0.5),
        ("(b) continuous, $t_1$ = $T$", 1.0),
    ];
    let orders = [2usize, 15];
    let mut csv = Csv::new(
        &[
            "Figure 2: ideal rod signal (11) and its Fourier partial sums (8) with coefficients (12)-(14), before stroke scaling and shift.",
            "kappa = 1, a_0 = 124 m/s^2, stroke 25 um. mode: discrete (t_1/T = 0.5) or continuous (t_1 = T). SI units.",
            "The ideal signal jumps at t_1 (position, velocity; infinite velocity/acceleration there): its row at t_1 holds the left limit.",
        ],
        &[
            "mode",
            "t_s",
            "x_ideal_m",
            "v_ideal_m_per_s",
            "a_ideal_m_per_s2",
            "x_n2_m",
            "v_n2_m_per_s",
            "a_n2_m_per_s2",
            "x_n15_m",
            "v_n15_m_per_s",
            "a_n15_m_per_s2",
        ],
    );
    let mut panels: Vec<Vec<Panel>> = Vec::new();
    for (title, duty) in columns {
        let shape = shape(1.0, duty);
        let ideal = IdealSignal::new(shape, motor);
        let sums: Vec<FourierSignal> = orders
            .iter()
            .map(|&n| FourierSignal::partial_sum(shape, n, false, motor))
            .collect();
        let period = ideal.period();
        let times: Vec<f64> = linspace(0.0, period, SAMPLES).collect();
        let mode = if duty < 1.0 { "discrete" } else { "continuous" };
        for &t in &times {
            let tau = if t >= period { 0.0 } else { t };
            let id = if t > 0.0 && t <= ideal.t1() {
                ideal.state_before(t)
            } else {
                ideal.state(tau)
            };
            let mut cells = vec![
                Cell::S(mode),
                Cell::F(t),
                Cell::F(id.x),
                Cell::F(id.v),
                Cell::F(id.a),
            ];
            for s in &sums {
                let st = s.state(tau);
                cells.extend([Cell::F(st.x), Cell::F(st.v), Cell::F(st.a)]);
            }
            csv.row(&cells);
        }
        let t_axis = || Axis::linear("time $t$ (ms)", (0.0, period * 1e3)).scaled(1e3);
        let quantities = [
            Quantity::Position,
            Quantity::Velocity,
            Quantity::Acceleration,
            Quantity::Acceleration,
        ];
        let column: Vec<Panel> = quantities
            .iter()
            .enumerate()
            .map(|(row, &q)| {
                let (label, scale) = q.axis();
                let curves: Vec<Vec<(f64, f64)>> = sums
                    .iter()
                    .map(|s| {
                        times
                            .iter()
                            .map(|&t| (t, q.of(s.state(if t >= period { 0.0 } else { t }))))
                            .collect()
                    })
                    .collect();
                let ideal_pts = ideal_curve(&ideal, q);
                let (lo, hi) = min_max(
                    curves
                        .iter()
                        .flatten()
                        .chain(ideal_pts.iter().filter(|p| p.1 > -1e29))
                        .map(|p| p.1 * scale),
                );
                let zoom = row == 3;
                let range = if zoom {
                    (-400.0, 400.0)
                } else {
                    padded(lo, hi, 0.06)
                };
                let y_label = if zoom {
                    "rod acceleration, zoom (m/s²)"
                } else {
                    label
                };
                let mut p = Panel::new(
                    (row == 0).then_some(title),
                    t_axis(),
                    Axis::linear(y_label, range).scaled(scale).with_ticks(4),
                );
                if matches!(q, Quantity::Acceleration) {
                    push_stick_band(&mut p, a0, period);
                }
                p.series.push(Series::line(
                    Some("ideal signal (11)"),
                    ideal_pts,
                    Look::nth(0).weighted(1.3),
                ));
                for (i, (n, pts)) in orders.iter().zip(curves).enumerate() {
                    // In the zoom n = 15 crosses the panel many times: thin.
                    let weight = if zoom && *n > 2 { 0.7 } else { 1.0 };
                    p.series.push(Series::line(
                        Some(&format!("partial sum (8), $n$ = {n}")),
                        pts,
                        Look::nth(i + 1).weighted(weight),
                    ));
                }
                p
            })
            .collect();
        panels.push(column);
    }
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(by_rows(panels), 2, 0.5),
        csv: csv.finish(),
        preset: Preset::DoubleColumn,
    })
}

/// Panels given column by column, in row order.
fn by_rows(columns: Vec<Vec<Panel>>) -> Vec<Panel> {
    let rows = columns.iter().map(Vec::len).max().unwrap_or(0);
    (0..rows)
        .flat_map(|r| columns.iter().filter_map(move |c| c.get(r).cloned()))
        .collect()
}

// ------------------------------------------------------------ figure 3 ----

/// Figure 3: normalised amplitudes `d_k / x_hat` of the stroke-scaled
/// continuous signal, without and with sigma factors, `n` = 2, 5, 10, 15.
pub fn figure3(motor: &Motor) -> Result<Figure, PlotError> {
    // Every amplitude is a marked point (the lines only guide the eye).
    const MARKERS: [Marker; 4] = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
    ];
    const NAME: &str = "fig3_harmonic_amplitudes";
    let orders = [2usize, 5, 10, 15];
    let mut csv = Csv::new(
        &[
            "Figure 3: normalised amplitudes d*_k = d_k / x_hat (section 4) of the continuous signal (kappa = 1) scaled to the stroke x_hat,",
            "without and with Lanczos sigma factors (15). With sigma, harmonic n+1 has amplitude 0 (sigma_{n+1}(n) = 0); it is listed for the figure.",
        ],
        &["sigma", "n", "k", "d_k_over_stroke", "sigma_k"],
    );
    let mut panels = Vec::new();
    for sigma in [false, true] {
        let title = if sigma {
            "(b) with $σ$ factors (15)"
        } else {
            "(a) without $σ$ factors"
        };
        let mut p = Panel::new(
            Some(title),
            Axis::linear("harmonic number $k$", (0.5, 16.5))
                .with_ticks(8)
                .integers(),
            Axis::linear("amplitude $d_k$/$x̂_R$", (0.0, 0.5)),
        );
        for (i, &n) in orders.iter().enumerate() {
            let s = built(1.0, n, sigma, motor, NAME)?;
            let mut pts: Vec<(f64, f64)> = s
                .amplitudes()
                .iter()
                .enumerate()
                .map(|(k, d)| ((k + 1) as f64, d / STROKE))
                .collect();
            if sigma {
                pts.push(((n + 1) as f64, 0.0));
            }
            for &(k, d) in &pts {
                let sk = if sigma {
                    sigma_factor(k as usize, n)
                } else {
                    1.0
                };
                csv.row(&[
                    Cell::S(if sigma { "true" } else { "false" }),
                    Cell::I(n as i64),
                    Cell::I(k as i64),
                    Cell::F(d),
                    Cell::F(if sigma && k as usize == n + 1 {
                        0.0
                    } else {
                        sk
                    }),
                ]);
            }
            p.series.push(Series::line(
                Some(&format!("$n$ = {n}")),
                pts,
                Look::nth(i).with_marker(MARKERS[i]),
            ));
        }
        panels.push(p);
    }
    // Both panels on one y scale, up to a multiple of 0.05 above the largest.
    let top = panels
        .iter()
        .flat_map(|p| {
            p.series
                .iter()
                .flat_map(|s| s.pieces.iter().flatten().map(|q| q.1))
        })
        .fold(0.0, f64::max);
    for p in &mut panels {
        p.y.range = (0.0, (top * 1.08 / 0.05).ceil() * 0.05);
    }
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(panels, 2, 0.75),
        csv: csv.finish(),
        preset: Preset::DoubleColumn,
    })
}

// ------------------------------------------------------------ figure 4 ----

/// Figure 4: the rod signals the simulator uses (stroke-scaled, minimum at
/// `t = 0`) for `n = 2` and 5, `kappa = 1`, without and with sigma factors.
pub fn figure4(motor: &Motor) -> Result<Figure, PlotError> {
    const NAME: &str = "fig4_rod_signals";
    let a0 = motor.a_0();
    let mut csv = Csv::new(
        &[
            "Figure 4: rod displacement, velocity and acceleration of the continuous signal, kappa = 1, n = 2 and 5,",
            "without and with sigma factors (15), scaled to the stroke 25 um and shifted so that x_R(0) = 0 is the minimum. SI units.",
        ],
        &[
            "n",
            "t_s",
            "x_m",
            "v_m_per_s",
            "a_m_per_s2",
            "x_sigma_m",
            "v_sigma_m_per_s",
            "a_sigma_m_per_s2",
        ],
    );
    let mut columns: Vec<Vec<Panel>> = Vec::new();
    for (col, n) in [2usize, 5].into_iter().enumerate() {
        let plain = built(1.0, n, false, motor, NAME)?;
        let with = built(1.0, n, true, motor, NAME)?;
        let period = plain.period();
        let times: Vec<f64> = linspace(0.0, period, SAMPLES).collect();
        for &t in &times {
            let tau = if t >= period { 0.0 } else { t };
            let (a, b) = (plain.state(tau), with.state(tau));
            csv.row(&[
                Cell::I(n as i64),
                Cell::F(t),
                Cell::F(a.x),
                Cell::F(a.v),
                Cell::F(a.a),
                Cell::F(b.x),
                Cell::F(b.v),
                Cell::F(b.a),
            ]);
        }
        let column: Vec<Panel> = [
            Quantity::Position,
            Quantity::Velocity,
            Quantity::Acceleration,
        ]
        .iter()
        .enumerate()
        .map(|(row, &q)| {
            let (label, scale) = q.axis();
            let curve = |s: &FourierSignal| -> Vec<(f64, f64)> {
                times
                    .iter()
                    .map(|&t| (t, q.of(s.state(if t >= period { 0.0 } else { t }))))
                    .collect()
            };
            let (c1, c2) = (curve(&plain), curve(&with));
            let (mut lo, mut hi) = min_max(c1.iter().chain(&c2).map(|p| p.1 * scale));
            if matches!(q, Quantity::Acceleration) {
                lo = lo.min(-a0);
                hi = hi.max(a0);
            }
            let title = format!("{} $n$ = {n}", if col == 0 { "(a)" } else { "(b)" });
            let mut p = Panel::new(
                (row == 0).then_some(title.as_str()),
                Axis::linear("time $t$ (ms)", (0.0, period * 1e3)).scaled(1e3),
                Axis::linear(label, padded(lo, hi, 0.06)).scaled(scale),
            );
            if matches!(q, Quantity::Acceleration) {
                push_stick_band(&mut p, a0, period);
            }
            p.series
                .push(Series::line(Some("without $σ$ factors"), c1, Look::nth(0)));
            p.series.push(Series::line(
                Some("with $σ$ factors (15)"),
                c2,
                Look::nth(1),
            ));
            p
        })
        .collect();
        columns.push(column);
    }
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(by_rows(columns), 2, 0.5),
        csv: csv.finish(),
        preset: Preset::DoubleColumn,
    })
}

// ------------------------------------------------------------ figure 5 ----

/// Figure 5: displacement signals of equal `f_max` (`n sqrt(kappa) = 6`,
/// `f_max = 9449 Hz`), without and with sigma factors.
pub fn figure5(motor: &Motor) -> Result<Figure, PlotError> {
    const NAME: &str = "fig5_equal_fmax";
    let level = 6.0;
    let orders = [2usize, 3, 4, 6];
    let mut csv = Csv::new(
        &[
            "Figure 5: rod displacement x_R(t) of signals with equal f_max = n sqrt(kappa) f_0(kappa = 1) (37), n sqrt(kappa) = 6,",
            "continuous, stroke 25 um, scaled and shifted; without and with sigma factors (15). SI units.",
        ],
        &[
            "sigma",
            "n",
            "sqrt_kappa",
            "f_0_hz",
            "f_max_hz",
            "t_s",
            "x_m",
        ],
    );
    let mut signals = Vec::new();
    for sigma in [false, true] {
        for &n in &orders {
            let sk = level / n as f64;
            signals.push((sigma, n, sk, built(sk * sk, n, sigma, motor, NAME)?));
        }
    }
    let t_end = signals.iter().map(|s| s.3.period()).fold(0.0, f64::max);
    let mut panels = Vec::new();
    for sigma in [false, true] {
        let title = if sigma {
            "(b) with $σ$ factors (15)"
        } else {
            "(a) without $σ$ factors"
        };
        let mut p = Panel::new(
            Some(title),
            Axis::linear("time $t$ (ms)", (0.0, t_end * 1e3)).scaled(1e3),
            Axis::linear("rod position $x_R$ (µm)", (-1.5, 26.5)).scaled(1e6),
        );
        for (i, (_, n, sk, s)) in signals.iter().filter(|s| s.0 == sigma).enumerate() {
            let period = s.period();
            let pts: Vec<(f64, f64)> = linspace(0.0, t_end, SAMPLES)
                .map(|t| (t, s.position(t.rem_euclid(period))))
                .collect();
            for &(t, x) in &pts {
                csv.row(&[
                    Cell::S(if sigma { "true" } else { "false" }),
                    Cell::I(*n as i64),
                    Cell::F(*sk),
                    Cell::F(s.f0()),
                    Cell::F(*n as f64 * s.f0()),
                    Cell::F(t),
                    Cell::F(x),
                ]);
            }
            let label = format!("$n$ = {n}, √$κ$ = {}", short(*sk));
            p.series.push(Series::line(Some(&label), pts, Look::nth(i)));
        }
        panels.push(p);
    }
    Ok(Figure {
        name: NAME.to_owned(),
        plot: Plot::grid(panels, 2, 0.7),
        csv: csv.finish(),
        preset: Preset::DoubleColumn,
    })
}

/// A number with at most three significant decimals, for labels.
fn short(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// The stick band `±a_0`, shaded under the curves.
pub(crate) fn push_stick_band(p: &mut Panel, a0: f64, period: f64) {
    p.series.push(Series::bands(
        Some("stick band ±$a_0$"),
        vec![[(0.0, -a0), (period, a0)]],
        band_look(),
    ));
}

/// The look of the stick band: a light grey fill.
pub(crate) fn band_look() -> Look {
    Look {
        color: BAND,
        dash: Dash::NoLine,
        marker: Marker::None,
        weight: 1.0,
    }
}
