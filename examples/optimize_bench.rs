//! Speed of `stickslip optimize` on one core, as medians over repeated
//! runs: the paper's default (`n = 2`, the `f_max` of `sqrt(kappa) = 6`,
//! stroke 25 um, objective `v_inf`), with the optimum's `v_inf` and its
//! gain over the sigma signal (0.2971 m/s); then one run each of `n = 3`
//! and `n = 4` at the same `f_max`.
//!
//! `cargo run --release --example optimize_bench`

use std::time::Instant;
use stickslip::Scene;
use stickslip::optimize::{self, OptimizeTable, Overrides, Settings};

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

fn main() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("one worker thread");
    let scene = Scene::default();
    let settings = |n: i64| {
        let overrides = Overrides {
            harmonics: Some(n),
            ..Overrides::default()
        };
        Settings::resolve(&OptimizeTable::default(), &overrides, &scene).expect("valid settings")
    };
    let runs = 9;
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let clock = Instant::now();
        let found = pool
            .install(|| optimize::optimize(&scene, &settings(2)))
            .expect("the default optimises");
        times.push(clock.elapsed().as_secs_f64());
        last = Some(found);
    }
    let found = last.expect("runs > 0");
    let sigma = found
        .references
        .iter()
        .find(|r| r.name == "sigma")
        .and_then(|r| r.measured.as_ref().ok())
        .map(|m| m.values.v_inf)
        .expect("the sigma signal runs");
    let v = found.best.measured.values.v_inf;
    println!(
        "stickslip optimize, one core, objective v_inf, the paper's default f_max = 18897.6 Hz"
    );
    println!(
        "n = 2: median {:.3} s over {runs} runs (min {:.3} s, max {:.3} s), {} runs of the simulator and {} gradients each",
        median(times.clone()),
        times.iter().copied().fold(f64::INFINITY, f64::min),
        times.iter().copied().fold(0.0, f64::max),
        found.search.evaluations,
        found.search.gradients
    );
    println!(
        "       v_inf = {v:.9} m/s ± {:.1e}, sigma signal {sigma:.9} m/s, gain {:+.2} %",
        found.best.measured.v_inf_error.unwrap_or(f64::NAN),
        100.0 * (v / sigma - 1.0)
    );
    for n in [3, 4] {
        let clock = Instant::now();
        let found = pool
            .install(|| optimize::optimize(&scene, &settings(n)))
            .expect("optimises");
        println!(
            "n = {n}: {:.3} s, {} runs, {} gradients, v_inf = {:.9} m/s",
            clock.elapsed().as_secs_f64(),
            found.search.evaluations,
            found.search.gradients,
            found.best.measured.values.v_inf
        );
    }
}
