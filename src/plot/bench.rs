//! The spring method against stiffness ([`crate::bench`]) as a figure.
//!
//! Panel (a): how far the spring's mean force departs from the stall
//! force (weight method), `|F_spring / F_stall - 1|`, against the
//! stiffness `k`, both axes logarithmic, tied and free-ended; a free end
//! the slider keeps bouncing off (no orbit locked) as points of its
//! 64-period mean. Panel (b): the spring's largest and least force over
//! the orbit (its swing), with the stall force and the start-up force
//! (Newton method) as reference lines named by their values. A stiffness
//! without a reading breaks the curves and is named in the note. The CSV beside the figure is the bench's table
//! (`table::to_csv`).

use super::axes::tick_label;
use super::style::{Dash, GREY};
use super::{Axis, Figure, Look, Panel, Plot, PlotError, Preset, Series, min_max, padded};
use crate::bench::{self, Bench, BenchOptions, SpringCase, table};
use crate::scene::Scene;

/// Three significant digits.
fn short(x: f64) -> String {
    if x == 0.0 {
        return "0".to_owned();
    }
    let step = 10f64.powf(x.abs().log10().floor() - 2.0);
    tick_label((x / step).round() * step, step)
}

/// The bench of `scene` with the default options (10 N/m to 10 MN/m, 50
/// stiffnesses, tied and free-ended), drawn.
pub fn scene_bench(scene: &Scene, name: &str) -> Result<Figure, PlotError> {
    let b = bench::bench(scene, &BenchOptions::default())
        .map_err(|e| PlotError::Argument(e.to_string()))?;
    figure(&b, scene, name)
}

/// The pieces of `value` over the rows, broken where a case has no
/// reading.
fn pieces(
    b: &Bench,
    tied: bool,
    value: impl Fn(&SpringCase) -> Option<f64>,
) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for r in &b.rows {
        let case = if tied { &r.tied } else { &r.free };
        let Some(c) = case else { continue };
        match value(c) {
            Some(v) => out.last_mut().expect("one piece").push((r.stiffness, v)),
            None => out.push(Vec::new()),
        }
    }
    out.retain(|p| !p.is_empty());
    out
}

/// The look of the tied (0) and the free-ended (1) spring's curves: the
/// free end's with markers, so that a stiffness between two without a
/// steady orbit still shows.
fn look(i: usize) -> Look {
    let look = Look::nth(i);
    if i == 1 {
        Look {
            marker: super::style::Marker::Circle,
            ..look
        }
    } else {
        look
    }
}

fn curve(label: &str, pieces: Vec<Vec<(f64, f64)>>, look: Look) -> Series {
    Series {
        label: Some(label.to_owned()),
        pieces,
        look,
        kind: super::Kind::Curve,
    }
}

/// The figure of a computed bench (module docs); its CSV is the bench's
/// table for `scene`.
pub fn figure(b: &Bench, scene: &Scene, name: &str) -> Result<Figure, PlotError> {
    let stall = b.stall_force();
    let startup = b.startup_force();
    let mean = |c: &SpringCase| c.reading.map(|r| r.profile.force_mean);
    let max = |c: &SpringCase| c.reading.map(|r| r.profile.force_max);
    let min = |c: &SpringCase| c.reading.map(|r| r.profile.force_min);
    let means: Vec<f64> = b.cases().filter_map(mean).collect();
    if means.is_empty() {
        return Err(PlotError::Data {
            figure: name.to_owned(),
            reason: "no spring of the range reached a steady orbit".to_owned(),
        });
    }
    let (k_lo, k_hi) = min_max(b.rows.iter().map(|r| r.stiffness));
    let k_range = if k_lo < k_hi {
        (k_lo, k_hi)
    } else {
        (k_lo / 2.0, k_hi * 2.0)
    };
    let k_label = "spring stiffness $k$ (N/m)";
    let stall_label = format!("stall force {} N", short(stall));
    let startup_label = startup.map(|f| format!("start-up force {} N", short(f)));

    // (a) how far the mean force departs from the stall force, relative:
    // the spring method's error, over decades. Orbits as curves; a free end
    // that locked into no orbit as open points (its 64-period mean).
    let departure = |c: &SpringCase| {
        c.reading
            .filter(|r| r.orbit_periods > 0)
            .map(|r| (r.profile.force_mean / stall - 1.0).abs())
            .filter(|d| *d > 0.0)
    };
    let unlocked = |c: &SpringCase| {
        c.reading
            .filter(|r| r.orbit_periods == 0)
            .map(|r| (r.profile.force_mean / stall - 1.0).abs())
            .filter(|d| *d > 0.0)
    };
    let shown: Vec<f64> = b
        .cases()
        .filter_map(departure)
        .chain(b.cases().filter_map(unlocked))
        .collect();
    let (lo, hi) = min_max(shown.iter().copied());
    let mut a = Panel::new(
        Some("(a) mean spring force against the stall force"),
        Axis::log(k_label, k_range),
        Axis::log(
            "$|F_{spring} / F_{stall} - 1|$",
            (lo.max(1e-16) / 2.0, hi.max(lo * 10.0) * 2.0),
        ),
    );
    let kinds = [
        ("tied", 0usize, pieces(b, true, departure)),
        ("free end", 1, pieces(b, false, departure)),
    ];
    for (label, i, p) in kinds {
        if !p.is_empty() {
            a.series.push(curve(label, p, look(i).weighted(1.2)));
        }
    }
    let bouncing: Vec<(f64, f64)> = b
        .rows
        .iter()
        .filter_map(|r| r.free.as_ref().and_then(unlocked).map(|d| (r.stiffness, d)))
        .collect();
    if !bouncing.is_empty() {
        a.series.push(Series {
            label: Some("free end, no orbit (64-period mean)".to_owned()),
            pieces: vec![bouncing],
            look: Look {
                marker: super::style::Marker::Square,
                ..Look::nth(2)
            },
            kind: super::Kind::Points,
        });
    }

    // (b) the largest and least force.
    let swing: Vec<f64> = b
        .cases()
        .filter_map(max)
        .chain(b.cases().filter_map(min))
        .collect();
    let (lo, hi) = min_max(swing.into_iter().chain([stall, 0.0]).chain(startup));
    let mut panel_b = Panel::new(
        Some("(b) largest and least spring force"),
        Axis::log(k_label, k_range),
        Axis::linear("spring force (N)", padded(lo, hi, 0.06)),
    );
    panel_b.series.push(Series::hline(
        Some(&stall_label),
        stall,
        k_range,
        Look::reference(),
    ));
    if let (Some(f), Some(label)) = (startup, &startup_label) {
        panel_b.series.push(Series::hline(
            Some(label),
            f,
            k_range,
            Look::line(GREY, Dash::Dotted),
        ));
    }
    for (label, i, case) in [("tied", 0usize, true), ("free end", 1, false)] {
        let top = pieces(b, case, max);
        let bottom = pieces(b, case, min);
        if top.is_empty() {
            continue;
        }
        let look = look(i);
        panel_b
            .series
            .push(curve(&format!("{label}, largest"), top, look.weighted(1.2)));
        panel_b.series.push(curve(
            &format!("{label}, least"),
            bottom,
            Look {
                weight: 0.7,
                dash: Dash::Dashed,
                ..look
            },
        ));
    }

    let missing: Vec<String> = b
        .cases()
        .filter(|c| c.reading.is_none_or(|r| r.orbit_periods == 0))
        .map(|c| format!("{} at {} N/m", c.end_name(), short(c.spring.stiffness)))
        .collect();
    let mut note = format!(
        "Spring method: the slider against a spring of stiffness k over its steady orbit. Weight method: stall force {} N. Newton method: start-up force {}.",
        short(stall),
        startup.map_or("none".to_owned(), |f| format!("{} N", short(f))),
    );
    if !missing.is_empty() {
        note.push_str(&format!(
            " No steady orbit within {} periods (read over the next 64): {}.",
            b.options.max_periods,
            missing.join(", ")
        ));
    }
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(vec![a, panel_b], 1, 0.62).with_notes(vec![note]),
        csv: table::to_csv(b, scene),
        preset: Preset::SingleColumn,
    })
}
