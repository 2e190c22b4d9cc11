//! Benchmark of the steady-state certificate: is every reported `v_inf` the
//! limit of the motion from rest (docs/model.md section 3)? The expected
//! value of every case is that limit, from the motion from rest simulated
//! period by period with the event engine until its state repeats; the
//! run's own cross-check (`run.verify_steady_state = true`) must agree
//! with it too.
//!
//! * The 36 optima `stickslip optimize` writes for the default scene at
//!   `sqrt(kappa)` in {1.5, 3, 4.5, 6} with the Table 1 actuator,
//!   `n = 2, 3, 4`, objectives `v_inf`, `velocity_per_power`, `durability`,
//!   seed 1: cases, agreeing, disagreeing (and those whose cross-check is
//!   wrong), largest difference, median wall time.
//! * 1000 random scenes placed by bisection on a change of the steady
//!   orbit's event structure (a stick phase appearing, or the events per
//!   period changing), checked there and on both sides: points, the share
//!   established (a steady state with an error estimate), agreeing,
//!   disagreeing, and the first failing scenes as TOML.
//!
//! `tests/steady_state_certificate.rs` asserts the same on a subset.
//!
//! `cargo run --release --example steady_state_certificate [-- SCENES]`
//! (SCENES: how many random scenes, 1000 by default; 0 runs the optima
//! alone). Most of its time goes to the optimisations, whose every run is
//! certified.

#[path = "../tests/common/steady_state_certificate.rs"]
mod cases;

use cases::{Tally, Verdict};
use rayon::prelude::*;
use std::time::{Duration, Instant};

fn median(mut xs: Vec<Duration>) -> Duration {
    xs.sort();
    xs.get(xs.len() / 2).copied().unwrap_or_default()
}

fn optima() {
    let clock = Instant::now();
    // One case after the other: each optimisation uses every CPU itself,
    // so the wall times are those of `stickslip optimize`.
    let results: Vec<_> = cases::optimum_cases()
        .into_iter()
        .map(|case| {
            let r = cases::run_optimum_case(case);
            let c = &r.comparison;
            println!(
                "{:<48} v_inf {:.14} ± {:8.1e}  from rest {:.14} ({:>6} periods)  diff {:8.1e}  \
                 check's start-up {:.14}  {:<18} ({:.2} s + {:.3} s)",
                case.to_string(),
                c.v_inf.unwrap_or(f64::NAN),
                c.estimate.unwrap_or(f64::NAN),
                c.rest.map_or(f64::NAN, |r| r.v_inf),
                c.rest.map_or(0, |r| r.periods),
                c.difference().unwrap_or(f64::NAN),
                c.v_inf_transient.unwrap_or(f64::NAN),
                c.strict_verdict().name(),
                r.optimise_time.as_secs_f64(),
                r.check_time.as_secs_f64(),
            );
            r
        })
        .collect();
    let count = |v: Verdict| {
        results
            .iter()
            .filter(|r| r.comparison.strict_verdict() == v)
            .count()
    };
    let largest = results
        .iter()
        .filter_map(|r| r.comparison.difference())
        .fold(0.0, f64::max);
    let without_estimate = results
        .iter()
        .filter(|r| r.comparison.estimate.is_none())
        .count();
    println!(
        "optima: {} cases; {} report the limit of the motion from rest, {} do not, {} do but \
         their cross-check is wrong, {} without a limit from rest, {} without a steady state \
         ({} without an error estimate); largest difference {largest:.3e} m/s",
        results.len(),
        count(Verdict::Agrees),
        count(Verdict::Disagrees),
        count(Verdict::CheckWrong),
        count(Verdict::NoExpectedValue),
        count(Verdict::NotEstablished),
        without_estimate,
    );
    println!(
        "optima: median wall time per case {:.3} s (optimisation {:.3} s, the comparison {:.4} s); \
         all {:.1} s",
        median(
            results
                .iter()
                .map(|r| r.optimise_time + r.check_time)
                .collect()
        )
        .as_secs_f64(),
        median(results.iter().map(|r| r.optimise_time).collect()).as_secs_f64(),
        median(results.iter().map(|r| r.check_time).collect()).as_secs_f64(),
        clock.elapsed().as_secs_f64()
    );
}

fn random_scenes(scenes: u64) {
    let clock = Instant::now();
    let checked: Vec<_> = (0..scenes)
        .into_par_iter()
        .map(|i| {
            let start = Instant::now();
            let (change, comparisons) = cases::check_random_scene(i);
            (i, change, comparisons, start.elapsed())
        })
        .collect();
    let mut t = Tally::default();
    for (i, change, comparisons, _) in &checked {
        cases::tally(&mut t, *i, change.as_ref(), comparisons);
    }
    println!("random scenes: {}", t.summary());
    println!(
        "random scenes: median {:.1} ms per scene, all {:.1} s",
        1e3 * median(checked.iter().map(|c| c.3).collect()).as_secs_f64(),
        clock.elapsed().as_secs_f64()
    );
    let failing = t.failing_scenes();
    println!(
        "random scenes: {} scenes with a failing point: {failing:?}",
        failing.len()
    );
    for shown in t.first_failures(5) {
        println!("\n{shown}");
    }
}

fn main() {
    let scenes: u64 = std::env::args()
        .nth(1)
        .map(|a| a.parse().expect("SCENES: a whole number"))
        .unwrap_or(1000);
    regressions();
    optima();
    if scenes > 0 {
        random_scenes(scenes);
    }
}

/// Median wall time (s) of `f` over `runs` runs.
fn median_time(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let clock = std::time::Instant::now();
            f();
            clock.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[runs / 2]
}

/// The wall times of the three known cases the tests bound by work: a
/// stuck orbit that alternates between neighbouring doubles
/// (`tests/transient_limit.rs`), a pair of orbits next to a jump of the
/// period map (`tests/steady_state_certificate.rs`), and the
/// characteristic of the default motor without sliding friction
/// (`tests/characteristic.rs`).
fn regressions() {
    let stalled = stickslip::Scene::from_toml_str(
        "[motor]\nslider_mass = 0.0014\ncontact_force = 1.0\nmu_static = 0.1736\n\
         mu_dynamic = 0.1568\nextra_acceleration = -30.857826952979305\n\
         [signal]\nkind = \"fourier\"\nstroke = 25e-6\nkappa = 0.2\nharmonics = 2\n\
         sigma = false\n[run]\nverify_steady_state = true\n\
         [outputs]\nindicators = [\"v_inf\", \"startup_time\"]\n",
        "the stalled scene",
    )
    .expect("a valid scene");
    let t = median_time(9, || {
        stickslip::run(&stalled, &stickslip::RunOptions::default()).expect("runs");
    });
    println!(
        "stuck orbit alternating between doubles, verified: {:.3} ms (median of 9)",
        t * 1e3
    );
    let mut pair = stickslip::Scene {
        signal: stickslip::SignalSpec::fourier(25e-6, 9.0, 4, true),
        ..stickslip::Scene::default()
    };
    pair.motor.extra_acceleration = -46.573362;
    let t = median_time(9, || {
        stickslip::run(&pair, &stickslip::RunOptions::default()).expect("runs");
    });
    println!(
        "pair of orbits next to a jump of the map: {:.3} ms (median of 9)",
        t * 1e3
    );
    let mut no_sliding = stickslip::Scene::default();
    no_sliding.motor.mu_dynamic = 0.0;
    let options = stickslip::characteristic::CharacteristicOptions::default();
    let mut evaluations = 0;
    let t = median_time(3, || {
        let c = stickslip::characteristic::characteristic(&no_sliding, &options).expect("runs");
        evaluations = c.counts.total() - c.counts.transient;
    });
    println!(
        "characteristic with mu_dynamic = 0: {t:.2} s (median of 3), {evaluations} v_inf evaluations (all but the start-up run)"
    );
}
