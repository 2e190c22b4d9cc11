//! The trends of the paper's section 7 (figures 6 and 7), as listed in
//! docs/model.md section 7, asserted from sweep data on the grid the figures use:
//! `examples/sweeps/section7.toml` (f_max levels `n sqrt(kappa)` of the
//! reference grid, `n = 2..=8`, with and without sigma factors, the paper's
//! motor and the Table 1 actuator).
//!
//! Where a statement of the paper does not hold on every case of this grid,
//! the test asserts exactly where it holds and pins the exceptions, so a
//! change in either shows up. `cargo test --release --test trends --
//! --nocapture` prints the table the assertions read.

mod common;

use std::collections::BTreeMap;
use std::sync::OnceLock;
use stickslip::Scene;
use stickslip::sweep::{self, AxisValue, SweepAxis};

const SWEEP: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/sweeps/section7.toml");

/// The indicators of one case.
#[derive(Debug, Clone, Copy)]
struct Point {
    v_inf: f64,
    /// `T p_0.99` (s).
    startup_time: f64,
    smoothness: f64,
    durability: f64,
    velocity_per_power: f64,
}

/// The section 7 grid: levels, `n` values, and every case by
/// `(level index, n, sigma)`.
struct Grid {
    levels: Vec<f64>,
    ns: Vec<usize>,
    points: BTreeMap<(usize, usize, bool), Point>,
}

impl Grid {
    fn at(&self, level: usize, n: usize, sigma: bool) -> Point {
        self.points[&(level, n, sigma)]
    }
}

fn grid() -> &'static Grid {
    static GRID: OnceLock<Grid> = OnceLock::new();
    GRID.get_or_init(|| {
        let sweep = sweep::load(SWEEP).expect("the section 7 sweep loads");
        let cases = sweep.cases();
        let levels: Vec<f64> = axis(&sweep, SweepAxis::Level)
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let ns: Vec<usize> = axis(&sweep, SweepAxis::Harmonics)
            .iter()
            .map(|v| v.as_f64().unwrap() as usize)
            .collect();
        let mut points = BTreeMap::new();
        for (case, result) in cases.iter().zip(sweep::run_cases(&cases, false)) {
            let r = result
                .unwrap_or_else(|e| panic!("case {}: {e}", case.index))
                .report;
            let level = case
                .value(SweepAxis::Level)
                .and_then(AxisValue::as_f64)
                .unwrap();
            let n = case
                .value(SweepAxis::Harmonics)
                .and_then(AxisValue::as_f64)
                .unwrap();
            let sigma = case
                .value(SweepAxis::Sigma)
                .and_then(AxisValue::as_bool)
                .unwrap();
            let point = Point {
                v_inf: r.indicators.v_inf,
                startup_time: r.startup_time().expect("start-up reached"),
                smoothness: r.indicators.smoothness,
                durability: r.indicators.durability,
                velocity_per_power: r.velocity_per_power().expect("power computed"),
            };
            let li = levels.iter().position(|l| *l == level).unwrap();
            points.insert((li, n as usize, sigma), point);
        }
        let grid = Grid { levels, ns, points };
        print_table(&grid);
        grid
    })
}

fn axis(sweep: &sweep::Sweep, axis: SweepAxis) -> Vec<AxisValue> {
    sweep
        .axes()
        .iter()
        .find(|(a, _)| *a == axis)
        .map(|(_, v)| v.clone())
        .unwrap_or_else(|| panic!("the section 7 sweep varies {axis}"))
}

fn print_table(g: &Grid) {
    type Get = fn(&Point) -> f64;
    let columns: [(&str, Get); 5] = [
        ("v_inf m/s", |p| p.v_inf),
        ("T p_0.99 ms", |p| p.startup_time * 1e3),
        ("smoothness", |p| p.smoothness),
        ("durability 1/N", |p| p.durability),
        ("v/S mm/(s VA)", |p| p.velocity_per_power * 1e3),
    ];
    for (name, get) in columns {
        println!("{name}: rows level/sigma, columns n = {:?}", g.ns);
        for (li, level) in g.levels.iter().enumerate() {
            for sigma in [false, true] {
                let row: Vec<String> =
                    g.ns.iter()
                        .map(|n| format!("{:10.5}", get(&g.at(li, *n, sigma))))
                        .collect();
                println!("  {level:>3} {:<5} {}", sigma, row.join(" "));
            }
        }
    }
}

/// The grid is the one the figures use: the levels of the independent
/// reference grid (`tests/data/section7_grid.csv`), `n = 2..=8`,
/// sigma off and on, on the paper's motor and actuator.
#[test]
fn the_sweep_is_the_figures_grid() {
    let text = common::reference_grid_text();
    let mut reference_levels: Vec<f64> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("level"))
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    reference_levels.dedup();
    let sweep = sweep::load(SWEEP).unwrap();
    let levels: Vec<f64> = axis(&sweep, SweepAxis::Level)
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(levels, reference_levels);
    let ns: Vec<f64> = axis(&sweep, SweepAxis::Harmonics)
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(ns, [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
    let sigma: Vec<_> = axis(&sweep, SweepAxis::Sigma)
        .iter()
        .map(|v| v.as_bool())
        .collect();
    assert_eq!(sigma, [Some(false), Some(true)]);
    let default = Scene::default();
    for case in sweep.cases() {
        assert_eq!(case.scene.motor, default.motor);
        assert_eq!(case.scene.actuator, default.actuator);
        assert_eq!(case.scene.outputs.indicators, default.outputs.indicators);
    }
    assert_eq!(grid().points.len(), 70);
}

/// docs/model.md section 7, paper section 7: "For any given maximum frequency
/// the highest steady state velocity is reached with n = 2" — with and
/// without sigma factors. Also paper section 7: "Higher maximum frequencies
/// lead to higher steady state velocities" (at every n).
#[test]
fn v_inf_is_highest_at_n_2_and_rises_with_f_max() {
    let g = grid();
    for li in 0..g.levels.len() {
        for sigma in [false, true] {
            let best = g.at(li, 2, sigma).v_inf;
            for &n in &g.ns[1..] {
                let v = g.at(li, n, sigma).v_inf;
                assert!(
                    v < best,
                    "level {} sigma {sigma}: n = {n} {v} >= n = 2 {best}",
                    g.levels[li]
                );
            }
        }
    }
    for &n in &g.ns {
        for sigma in [false, true] {
            for li in 1..g.levels.len() {
                let (lower, higher) = (g.at(li - 1, n, sigma).v_inf, g.at(li, n, sigma).v_inf);
                assert!(
                    higher > lower,
                    "n = {n} sigma {sigma}: level {}",
                    g.levels[li]
                );
            }
        }
    }
}

/// docs/model.md section 7: sigma factors raise `v_inf` by roughly 30-130 %.
/// (The paper, section 7, says "between 55% and 130% in the shown cases";
/// on this grid the smallest gain is 31 % at level 15, n = 5, the largest
/// 125 % at level 3, n = 2.)
#[test]
fn sigma_factors_raise_v_inf_by_30_to_130_percent() {
    let g = grid();
    let mut gains = Vec::new();
    for li in 0..g.levels.len() {
        for &n in &g.ns {
            let gain = g.at(li, n, true).v_inf / g.at(li, n, false).v_inf - 1.0;
            gains.push((gain, g.levels[li], n));
            assert!(
                (0.30..=1.30).contains(&gain),
                "level {} n {n}: +{:.1} %",
                g.levels[li],
                gain * 100.0
            );
        }
    }
    gains.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (min, max) = (gains[0], gains[gains.len() - 1]);
    println!(
        "sigma v_inf gain: min {:.1} % (level {}, n {}), max {:.1} % (level {}, n {})",
        min.0 * 100.0,
        min.1,
        min.2,
        max.0 * 100.0,
        max.1,
        max.2
    );
    // Below the paper's 55 %: the gain falls with n at high levels.
    assert!(min.0 < 0.55 && (min.1, min.2) == (15.0, 5), "{min:?}");
    assert!(max.0 > 1.2 && (max.1, max.2) == (3.0, 2), "{max:?}");
}

/// docs/model.md section 7, paper section 7: "with sigma, odd n start up faster
/// than their even neighbours" (start-up time `T p_0.99`; at equal `f_max`
/// the period grows with `n`, `T ∝ n`).
///
/// Holds for every odd `n` at levels 6 to 15. At level 3 it fails for
/// every odd `n` against its next even neighbour: there `n >= 4` has
/// `sqrt(kappa) = 3/n < 1` (stick-slip), `p_0.99` is 1 or 2, and the
/// start-up time mostly grows with `T ∝ n` instead (n = 3: 1.905 ms, n = 4:
/// 1.693 ms, n = 5: 2.117 ms, n = 6: 2.540 ms, n = 7: 2.963 ms, n = 8:
/// 1.693 ms). So also the paper's "n = 3 is shorter than n = 2 or 4 in all
/// investigated cases" fails at level 3. The exceptions are pinned.
#[test]
fn with_sigma_odd_n_start_up_faster_than_even_neighbours() {
    let g = grid();
    let mut exceptions = Vec::new();
    for li in 0..g.levels.len() {
        for &n in g.ns.iter().filter(|n| *n % 2 == 1) {
            let t = g.at(li, n, true).startup_time;
            for m in [n - 1, n + 1].into_iter().filter(|m| g.ns.contains(m)) {
                let neighbour = g.at(li, m, true).startup_time;
                if t >= neighbour {
                    println!(
                        "level {}: n = {n} {:.4} ms >= n = {m} {:.4} ms",
                        g.levels[li],
                        t * 1e3,
                        neighbour * 1e3
                    );
                    exceptions.push((g.levels[li], n, m));
                }
            }
        }
    }
    assert_eq!(
        exceptions,
        [(3.0, 3, 4), (3.0, 5, 4), (3.0, 7, 6), (3.0, 7, 8)]
    );
    // Without sigma there is no such alternation: the paper's "increasing n
    // decreases the start-up time" holds at levels 6 to 15. At level 3 it
    // stops at n = 6 (n = 6: 2.540 ms, n = 7: 2.963 ms, n = 8: 3.387 ms).
    for li in 1..g.levels.len() {
        for w in g.ns.windows(2) {
            let (a, b) = (
                g.at(li, w[0], false).startup_time,
                g.at(li, w[1], false).startup_time,
            );
            assert!(b < a, "level {} n {} -> {}", g.levels[li], w[0], w[1]);
        }
    }
}

/// docs/model.md section 7, paper section 7: sigma factors raise the smoothness
/// at n = 2, hardly change it at n = 3, and lower it for n >= 4. Also
/// paper section 7: "increasing n decreases the smoothness" (with and
/// without sigma) at every level.
///
/// On this grid: n = 2 gains 60-65 %; n = 3 changes by -5.4 % to +10.4 %
/// (the +10.4 % at level 3, elsewhere within 6 %); n >= 4 loses 4.8-56 %. At
/// level 3 the n = 3 change (+10.4 %) is as large as the losses at n >= 4
/// there (4.8-9.9 %); at levels 6 to 15 it is smaller than every one.
#[test]
fn sigma_raises_smoothness_at_2_keeps_it_at_3_lowers_it_from_4() {
    let g = grid();
    let ratio = |li: usize, n: usize| g.at(li, n, true).smoothness / g.at(li, n, false).smoothness;
    for li in 0..g.levels.len() {
        let level = g.levels[li];
        let r2 = ratio(li, 2);
        assert!(r2 > 1.5, "level {level}: n = 2 ratio {r2}");
        let change3 = (ratio(li, 3) - 1.0).abs();
        let bound = if li == 0 { 0.11 } else { 0.06 };
        assert!(
            change3 <= bound,
            "level {level}: n = 3 changes by {change3}"
        );
        let mut smallest_loss = f64::INFINITY;
        for &n in g.ns.iter().filter(|n| **n >= 4) {
            let r = ratio(li, n);
            assert!(r < 1.0, "level {level}: n = {n} ratio {r}");
            smallest_loss = smallest_loss.min(1.0 - r);
        }
        println!(
            "level {level}: n = 2 x{r2:.3}, n = 3 |change| {change3:.3}, smallest loss n >= 4 {smallest_loss:.3}"
        );
        if li > 0 {
            assert!(change3 < smallest_loss, "level {level}");
        }
        for sigma in [false, true] {
            for w in g.ns.windows(2) {
                let (a, b) = (
                    g.at(li, w[0], sigma).smoothness,
                    g.at(li, w[1], sigma).smoothness,
                );
                assert!(b < a, "level {level} sigma {sigma}: n {} -> {}", w[0], w[1]);
            }
        }
    }
}

/// docs/model.md section 7, paper section 7: without sigma the durability is
/// lowest at n = 2 (every level); with sigma it is "on average about twice
/// as high". On this grid the sigma/no-sigma ratio is 2.28-2.36 at n = 2
/// and 1.59 (level 15, n = 5) to 2.36 over all cases, mean 1.95.
#[test]
fn durability_lowest_at_n_2_without_sigma_and_about_doubled_with_sigma() {
    let g = grid();
    let mut ratios = Vec::new();
    for li in 0..g.levels.len() {
        let level = g.levels[li];
        let at2 = g.at(li, 2, false).durability;
        for &n in &g.ns[1..] {
            assert!(g.at(li, n, false).durability > at2, "level {level} n {n}");
        }
        for &n in &g.ns {
            let r = g.at(li, n, true).durability / g.at(li, n, false).durability;
            if n == 2 {
                assert!((2.2..=2.4).contains(&r), "level {level}: n = 2 ratio {r}");
            }
            assert!((1.5..=2.5).contains(&r), "level {level} n {n}: ratio {r}");
            ratios.push(r);
        }
    }
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    println!("durability sigma/no-sigma: mean {mean:.3}");
    assert!((1.8..=2.2).contains(&mean), "mean ratio {mean}");
}

/// docs/model.md section 7, paper section 7: the velocity to input power ratio
/// is "maximal for n = 2 for any f_max" with sigma factors — here the
/// highest of all 14 cases (n, sigma) of each level.
#[test]
fn velocity_per_power_is_highest_at_n_2_with_sigma() {
    let g = grid();
    for li in 0..g.levels.len() {
        let best = g.at(li, 2, true).velocity_per_power;
        for &n in &g.ns {
            for sigma in [false, true] {
                if (n, sigma) != (2, true) {
                    let v = g.at(li, n, sigma).velocity_per_power;
                    assert!(
                        v < best,
                        "level {}: n {n} sigma {sigma}: {v} >= {best}",
                        g.levels[li]
                    );
                }
            }
        }
    }
}
