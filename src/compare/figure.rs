//! The comparison figure (SVG): above, the user's slider velocity against
//! the exact one over chosen periods (of the first file with `v_S`);
//! below, the per-period mean-velocity error `v_p,user - v_p` of every
//! file with a per-period series.

use super::Report;
use plotters::prelude::*;

/// Draws the figure for periods `from..=to` (1-based); `None`: the first
/// period with samples.
pub(crate) fn draw(report: &Report, periods: Option<(u64, u64)>) -> Result<String, String> {
    let period = report.signal.period;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (top, bottom) = root.split_vertically(380);
        let file = report.files.iter().find(|f| !f.velocity.is_empty());
        if let Some(f) = file {
            let (a, b) = periods.unwrap_or_else(|| {
                let p = (f.velocity[0].0 / period).floor() as u64 + 1;
                (p, p)
            });
            let (t0, t1) = ((a - 1) as f64 * period, b as f64 * period);
            let pts: Vec<&(f64, f64, f64)> = f
                .velocity
                .iter()
                .filter(|s| s.0 >= t0 && s.0 <= t1)
                .collect();
            let (lo, hi) = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| {
                    (l.min(s.1).min(s.2), h.max(s.1).max(s.2))
                });
            let (lo, hi) = if lo < hi { (lo, hi) } else { (-1.0, 1.0) };
            let mut chart = ChartBuilder::on(&top)
                .caption(
                    format!("slider velocity, periods {a}..{b}: {}", f.file),
                    ("sans-serif", 16),
                )
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(60)
                .build_cartesian_2d(t0 * 1e3..t1 * 1e3, lo..hi)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc("t (ms)")
                .y_desc("v_S (m/s)")
                .draw()
                .map_err(|e| e.to_string())?;
            chart
                .draw_series(LineSeries::new(
                    pts.iter().map(|s| (s.0 * 1e3, s.2)),
                    &BLACK,
                ))
                .map_err(|e| e.to_string())?
                .label("exact")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
            chart
                .draw_series(LineSeries::new(pts.iter().map(|s| (s.0 * 1e3, s.1)), &RED))
                .map_err(|e| e.to_string())?
                .label("user")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
            chart
                .configure_series_labels()
                .border_style(BLACK)
                .draw()
                .map_err(|e| e.to_string())?;
        }
        let series: Vec<_> = report
            .files
            .iter()
            .filter(|f| !f.period_errors.is_empty())
            .collect();
        if !series.is_empty() {
            let p_max = series
                .iter()
                .flat_map(|f| f.period_errors.iter().map(|e| e.0))
                .max()
                .unwrap_or(1) as f64;
            let (lo, hi) = series
                .iter()
                .flat_map(|f| f.period_errors.iter().map(|e| e.1))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), e| {
                    (l.min(e), h.max(e))
                });
            let (lo, hi) = if lo < hi {
                (lo, hi)
            } else {
                (lo - 1e-9, hi + 1e-9)
            };
            let mut chart = ChartBuilder::on(&bottom)
                .caption(
                    "per-period mean-velocity error v_p,user - v_p",
                    ("sans-serif", 16),
                )
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(60)
                .build_cartesian_2d(1.0..p_max.max(2.0), lo..hi)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc("period p")
                .y_desc("error (m/s)")
                .draw()
                .map_err(|e| e.to_string())?;
            for (i, f) in series.iter().enumerate() {
                let color = Palette99::pick(i).to_rgba();
                chart
                    .draw_series(LineSeries::new(
                        f.period_errors.iter().map(|e| (e.0 as f64, e.1)),
                        color,
                    ))
                    .map_err(|e| e.to_string())?;
            }
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
