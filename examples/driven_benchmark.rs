//! Cost of a driven rod (docs/model.md section 16) against the prescribed
//! one, as medians over repeated runs in one process: `stickslip::run` of
//! the paper's default scene (every indicator, a full run from rest to
//! an established steady state) with the rod prescribed, driven with the
//! reaction and driven without it; then the same for the other signals of
//! the table in docs/model.md section 16. Prints, per run, the median
//! time of `run()` timed outside, its own set-up and simulation times,
//! the periods simulated and events found, the simulation time per
//! period, `v_inf`, and the ratio of the time to the prescribed rod's.
//!
//! The same model solved by a stiff general-purpose solver with event
//! location (scipy's `solve_ivp`, Radau) is
//! `examples/python/driven_scipy.py`.
//!
//! `cargo run --release --example driven_benchmark [-- RUNS]` (21 by
//! default).

use std::time::Instant;
use stickslip::SignalSpec;
use stickslip::actuator::{DrivenSpec, RealActuator, RodModel};
use stickslip::{RunReport, Scene};

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Medians (us) of `run()` timed outside, of its set-up and of its
/// simulation, with the last report.
fn timed(scene: &Scene, runs: usize) -> ([f64; 3], RunReport) {
    let (mut wall, mut setup, mut sim) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..runs {
        let clock = Instant::now();
        let r = stickslip::run(scene, &stickslip::RunOptions::default())
            .and_then(stickslip::Outcome::into_report)
            .expect("scene runs");
        wall.push(clock.elapsed().as_secs_f64() * 1e6);
        setup.push(r.setup_time.as_secs_f64() * 1e6);
        sim.push(r.simulation_time.as_secs_f64() * 1e6);
        last = Some(r);
    }
    (
        [median(wall), median(setup), median(sim)],
        last.expect("runs > 0"),
    )
}

fn main() {
    let runs: usize = std::env::args()
        .nth(1)
        .map_or(21, |a| a.parse().expect("a number of runs"));
    println!(
        "stickslip::run, every indicator, from rest to the steady state; medians of {runs} runs"
    );
    println!(
        "  {:<40} {:<20} {:>8} {:>7} {:>8} {:>8} {:>7} {:>10} {:>17} {:>6}",
        "signal",
        "rod",
        "run us",
        "set-up",
        "sim.",
        "periods",
        "events",
        "us/period",
        "v_inf m/s",
        "ratio"
    );
    let signals = [
        ("default (n = 2, sqrt(kappa) = 6, sigma)", 36.0, 2, true),
        ("n = 3, sqrt(kappa) = 2, sigma", 4.0, 3, true),
        ("n = 4, sqrt(kappa) = 1, no sigma", 1.0, 4, false),
    ];
    let rods = [
        ("prescribed", RodModel::Prescribed),
        (
            "driven, reaction",
            RodModel::Driven(DrivenSpec {
                reaction: true,
                real: RealActuator::default(),
            }),
        ),
        (
            "driven, no reaction",
            RodModel::Driven(DrivenSpec {
                reaction: false,
                real: RealActuator::default(),
            }),
        ),
    ];
    for (name, kappa, n, sigma) in signals {
        let mut prescribed = None;
        for (rod_name, rod) in rods {
            let scene = Scene {
                signal: SignalSpec::fourier(25e-6, kappa, n, sigma),
                rod,
                ..Scene::default()
            };
            let ([wall, setup, sim], r) = timed(&scene, runs);
            let base = *prescribed.get_or_insert(wall);
            println!(
                "  {name:<40} {rod_name:<20} {wall:>8.0} {setup:>7.0} {sim:>8.0} {:>8} {:>7} {:>10.2} {:>17.10e} {:>6.1}",
                r.work.periods,
                r.work.events.total(),
                sim / r.work.periods as f64,
                r.indicators.v_inf,
                wall / base
            );
        }
    }
}
