//! Cost of `stickslip bench` on the default scene (the paper's motor): 50
//! spring stiffnesses log spaced from 10 N/m to 10 MN/m, tied and
//! free-ended, with the stall force and the start-up force beside them.
//! Prints the median wall time over repeated runs, the time the reference
//! forces take alone, and per case (from the last run) the outcome, the
//! periods simulated from rest, how the steady state was established
//! (`attracted`: Newton's fixed point with the start-up followed into its
//! attraction; `orbit`: the start-up repeated itself) and the run's own
//! wall time, then the totals by outcome, so that where the time goes can
//! be read off. On a shared machine the wall time also counts the time
//! the threads waited for a core.
//!
//! `cargo run --release --example bench_benchmark [REPEATS]` (default 5)

use std::time::{Duration, Instant};
use stickslip::Scene;
use stickslip::bench::{self, BenchOptions};
use stickslip::characteristic;

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5);
    let scene = Scene::default();
    let options = BenchOptions::default();
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..repeats {
        let clock = Instant::now();
        let b = bench::bench(&scene, &options).expect("a bench of the default scene");
        walls.push(clock.elapsed().as_secs_f64());
        last = Some(b);
    }
    let mut reference_walls = Vec::new();
    for _ in 0..repeats {
        let clock = Instant::now();
        characteristic::reference_forces(&scene).expect("the reference forces");
        reference_walls.push(clock.elapsed().as_secs_f64());
    }
    let b = last.expect("at least one run");
    println!(
        "{:>12} {:>5} {:>14} {:>10} {:>12} {:>10}",
        "k (N/m)", "end", "regime", "periods", "certificate", "wall (ms)"
    );
    let mut by_regime: std::collections::BTreeMap<&str, (usize, u64, Duration)> =
        Default::default();
    for c in b.cases() {
        println!(
            "{:>12.4e} {:>5} {:>14} {:>10} {:>12} {:>10.3}",
            c.spring.stiffness,
            c.end_name(),
            c.regime,
            c.periods_simulated,
            c.certificate.map_or("-", |k| k.name()),
            c.wall_time.as_secs_f64() * 1e3
        );
        let e = by_regime.entry(c.regime).or_default();
        e.0 += 1;
        e.1 += c.periods_simulated;
        e.2 += c.wall_time;
    }
    println!("by outcome (cases, periods simulated, summed run time):");
    for (regime, (n, periods, time)) in &by_regime {
        println!(
            "  {regime:<14} {n:>4} cases {periods:>10} periods {:>9.3} s",
            time.as_secs_f64()
        );
    }
    println!(
        "stall force {:.6} N, start-up force {} N",
        b.stall_force(),
        b.startup_force()
            .map_or("none".to_owned(), |f| format!("{f:.6}"))
    );
    println!(
        "reference forces alone: median {:.3} ms over {repeats} runs",
        median(reference_walls) * 1e3
    );
    println!(
        "bench (default scene, {} stiffnesses, tied and free, {} threads): median wall time {:.3} s over {repeats} runs",
        options.points,
        rayon::current_num_threads(),
        median(walls)
    );
}
