//! Throughput of the event engine, as medians over repeated runs: set-up
//! (signal and engine) and simulation time of a run with every indicator
//! for n = 2 to 256 harmonics, with and without sigma factors; the
//! `v_inf`-only default scene, which skips the start-up; and the raw event
//! rate.
//!
//! The last table times whole processes, `stickslip run SCENE` with every
//! indicator from start to exit, and needs the binary: build it first.
//!
//! `cargo build --release && cargo run --release --example throughput`

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Instant;
use stickslip::Indicator;
use stickslip::SignalSpec;
use stickslip::engine::PeriodEngine;
use stickslip::engine::PeriodStart;
use stickslip::{Scene, motor::Motor, signal::Signal};
use stickslip::{engine::EventEngine, engine::EventOptions};

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

/// Medians of set-up, simulation and whole-run time (us) of `scene`, with
/// the report of the last run.
fn timed(scene: &Scene, runs: usize) -> (f64, f64, f64, stickslip::RunReport) {
    let (mut setup, mut sim, mut wall) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..runs {
        let r = stickslip::run(scene, &stickslip::RunOptions::default())
            .and_then(stickslip::Outcome::into_report)
            .expect("scene runs");
        setup.push(r.setup_time.as_secs_f64() * 1e6);
        sim.push(r.simulation_time.as_secs_f64() * 1e6);
        wall.push(r.wall_time.as_secs_f64() * 1e6);
        last = Some(r);
    }
    (
        median(setup),
        median(sim),
        median(wall),
        last.expect("runs > 0"),
    )
}

fn main() {
    println!("run with every indicator, medians (set-up = signal and engine):");
    println!(
        "  {:>4} {:>6} {:>11} {:>11} {:>11} {:>8} {:>7} {:>9}",
        "n", "sigma", "set-up us", "sim. us", "run us", "periods", "events", "M ev/s"
    );
    for n in [2, 8, 16, 32, 64, 128, 256] {
        for sigma in [true, false] {
            let scene = Scene {
                signal: SignalSpec::fourier(25e-6, 36.0, n, sigma),
                ..Scene::default()
            };
            let runs = if n >= 128 { 7 } else { 15 };
            let (setup, sim, wall, r) = timed(&scene, runs);
            let events = r.work.events.total();
            println!(
                "  {n:>4} {sigma:>6} {setup:>11.0} {sim:>11.0} {wall:>11.0} {:>8} {events:>7} {:>9.2}",
                r.work.periods,
                events as f64 / sim
            );
        }
    }
    let mut only = Scene::default();
    only.outputs.indicators = vec![Indicator::VInf];
    let (setup, sim, wall, r) = timed(&only, 101);
    println!(
        "v_inf-only default scene: set-up {setup:.1} us, simulation {sim:.1} us, run {wall:.1} us; \
         {} start-up periods, {} map evaluations, v_inf = {:?} m/s",
        r.transient.as_ref().map_or(0, |t| t.periods()),
        r.map_evaluations,
        r.indicators.v_inf
    );
    let runs = 31;
    let scene = Scene::default();
    let mut walls = Vec::new();
    let mut internal = Vec::new();
    let mut events = 0;
    for _ in 0..runs {
        let clock = Instant::now();
        let r = stickslip::run(&scene, &stickslip::RunOptions::default())
            .and_then(stickslip::Outcome::into_report)
            .expect("default scene runs");
        walls.push(clock.elapsed().as_secs_f64() * 1e6);
        internal.push(r.wall_time.as_secs_f64() * 1e6);
        events = r.work.events.total();
    }
    println!("default scene (n = 2, sqrt(kappa) = 6, sigma), {runs} runs:");
    println!(
        "  run() timed outside: median {:.0} us; its own wall_time (set-up and simulation): median {:.0} us; {events} events",
        median(walls),
        median(internal)
    );
    whole_processes();
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

/// Medians of 21 whole processes `stickslip run SCENE` (every indicator,
/// output to a null device) for the paper's scene with `n` harmonics.
fn whole_processes() {
    let Some(bin) = std::env::current_exe()
        .ok()
        .and_then(|e| Some(e.parent()?.parent()?.join("stickslip")))
        .filter(|b| b.exists())
    else {
        println!(
            "whole processes: no stickslip binary beside the examples (cargo build --release)"
        );
        return;
    };
    let dir: PathBuf =
        std::env::temp_dir().join(format!("stickslip_throughput_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    let base = include_str!("scenes/paper_default.toml");
    println!("whole process `stickslip run SCENE`, every indicator, medians of 21:");
    for (n, sigma) in [
        (2, true),
        (64, true),
        (64, false),
        (256, true),
        (256, false),
    ] {
        let text = base
            .replace("harmonics = 2 ", &format!("harmonics = {n} "))
            .replace("sigma = true ", &format!("sigma = {sigma} "));
        let file = dir.join(format!("n{n}_{sigma}.toml"));
        std::fs::write(&file, text).expect("scene written");
        let mut times = Vec::new();
        for _ in 0..21 {
            let clock = Instant::now();
            let status = Command::new(&bin)
                .arg("run")
                .arg(&file)
                .stdout(Stdio::null())
                .status()
                .expect("binary runs");
            times.push(clock.elapsed().as_secs_f64() * 1e3);
            assert!(status.success(), "{} failed", file.display());
        }
        println!("  n = {n:3}, sigma = {sigma:5}: {:7.2} ms", median(times));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
