//! A synthetic section-7 grid for the figure tests (`tests/plot.rs`,
//! `tests/plot_svg.rs`).

use stickslip::plot::performance::GridPoint;

/// A synthetic section-7 grid: both sigma settings, two levels, n = 2..4.
pub fn grid() -> Vec<GridPoint> {
    let mut points = Vec::new();
    for level in [3.0, 6.0] {
        for n in 2..=4 {
            for sigma in [false, true] {
                let x = level / n as f64 + if sigma { 1.0 } else { 0.0 };
                points.push(GridPoint {
                    level,
                    n,
                    sigma,
                    f_max: level * 1574.8,
                    period: 1e-4 * n as f64 / level,
                    v_inf: 0.01 * x,
                    startup_periods: Some(n as u64 + 1),
                    smoothness: x,
                    durability: 0.3 + 0.01 * x,
                    stiction_fraction: 0.0,
                    stiction_fraction_steady: 0.0,
                    velocity_per_power: Some(1e-4 * x),
                });
            }
        }
    }
    points
}
