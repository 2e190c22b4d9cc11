//! Throughput of the event engine: the default scene's full run (transient
//! to steady state plus every indicator) and the raw event rate, as medians
//! over repeated runs.
//!
//! `cargo run --release --example throughput`

use std::time::Instant;
use stickslip::engine::PeriodEngine;
use stickslip::engine::PeriodStart;
use stickslip::engine::event::{EventEngine, EventOptions};
use stickslip::signal::SignalSpec;
use stickslip::{Motor, Scene, Signal, simulation};

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Events per second of `periods` steady periods of a signal.
fn event_rate(signal: &Signal, motor: &Motor, periods: u64) -> (f64, u64) {
    let mut engine = EventEngine::new(signal, motor, EventOptions::default());
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let clock = Instant::now();
    for p in 1..=periods {
        let end = engine.run_period(p, start, &mut ()).expect("runs");
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    let seconds = clock.elapsed().as_secs_f64();
    let events = engine.counters().events.total();
    (events as f64 / seconds, events)
}

fn main() {
    let runs = 31;
    let scene = Scene::default();
    let mut walls = Vec::new();
    let mut internal = Vec::new();
    let mut events = 0;
    for _ in 0..runs {
        let clock = Instant::now();
        let r = simulation::run(&scene).expect("default scene runs");
        walls.push(clock.elapsed().as_secs_f64() * 1e6);
        internal.push(r.wall_time.as_secs_f64() * 1e6);
        events = r.work.events.total();
    }
    println!("default scene (n = 2, sqrt(kappa) = 6, sigma), {runs} runs:");
    println!(
        "  full run incl. signal set-up: median {:.0} us; simulation alone: median {:.0} us; {events} events",
        median(walls),
        median(internal)
    );
    let motor = Motor::default();
    println!("event rate over 100000 periods (median of 5 runs):");
    for (n, kappa, sigma) in [
        (2, 36.0, true),
        (2, 1.0, false),
        (5, 0.36, true),
        (12, 1.0, true),
    ] {
        let spec = SignalSpec::fourier(25e-6, kappa, n, sigma);
        let signal = Signal::build(&spec, &motor).expect("valid signal");
        let mut rates = Vec::new();
        let mut count = 0;
        for _ in 0..5 {
            let (rate, c) = event_rate(&signal, &motor, 100_000);
            rates.push(rate);
            count = c;
        }
        println!(
            "  n = {n:2}, kappa = {kappa:5}, sigma = {sigma:5}: {:.2} M events/s ({} events per period)",
            median(rates) / 1e6,
            count as f64 / 100_000.0
        );
    }
}
