//! The stability report: every stress case of `stickslip::stability`, its
//! events, result, check and wall time, and its cost per simulated period
//! relative to the default scene.
//!
//! `cargo run --release --example stability_report`

use std::time::Instant;
use stickslip::Scene;
#[path = "../tests/common/stability.rs"]
mod stability;
use stability::{catalogue, period_cost, run_case};

fn main() {
    // Engine cost per steady-state period of the default scene, median of
    // 21 measurements of 2000 periods each.
    let r = stickslip::run(&Scene::default(), &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .expect("default scene runs");
    let stickslip::scene::BuiltScene { signal, motor } = Scene::default().build().expect("valid");
    let mut costs: Vec<f64> = (0..21)
        .filter_map(|_| period_cost(&signal, &motor, r.steady.boundary_velocity))
        .collect();
    costs.sort_by(f64::total_cmp);
    let reference = costs[costs.len() / 2];
    println!(
        "default scene: {:.3} us per steady-state period ({} events; median of 21 x 2000 periods)\n",
        reference * 1e6,
        r.steady.stats.events.total()
    );
    println!(
        "| case | events | periods | result | check | pass | wall time | events/period | cost/period vs default | why above 10x |"
    );
    println!("| --- | ---: | ---: | --- | --- | :---: | ---: | ---: | ---: | --- |");
    let clock = Instant::now();
    let mut failed = 0;
    for case in catalogue() {
        let o = run_case(&case);
        let ratio = o.period_cost.map(|c| c / reference);
        let why = match ratio {
            Some(x) if x > 10.0 => format!(
                "{} events/period with n = {} (default: {} with n = 2)",
                o.events_per_period,
                o.harmonics,
                r.steady.stats.events.total()
            ),
            _ => String::new(),
        };
        let ratio = ratio.map_or("-".to_owned(), |x| format!("{x:.1}x"));
        if !o.passed {
            failed += 1;
        }
        println!(
            "| {} | {} | {} | {} | {} | {} | {:.3} s | {} | {} | {} |",
            o.name,
            o.events,
            o.periods,
            o.result,
            o.check,
            if o.passed { "yes" } else { "NO" },
            o.wall_time,
            o.events_per_period,
            ratio,
            why
        );
    }
    println!(
        "\n{failed} of the cases failed; report time {:.1} s",
        clock.elapsed().as_secs_f64()
    );
    println!(
        "The cost of a period is its events (at most about 6n + 7 for n harmonics) \
         times the cost of one signal evaluation (one sin_cos plus n recurrence steps): \
         bounded per period, and above 10x the default scene only where the events per \
         period times n are."
    );
    if failed > 0 {
        std::process::exit(1);
    }
}
