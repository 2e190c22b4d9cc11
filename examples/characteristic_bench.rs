//! Cost of the force-velocity characteristic of the default scene (the
//! paper's motor, `stickslip characteristic` with its default options):
//! medians over repeated runs of the wall time and of the thread's time on
//! the CPU (Linux `schedstat`; on a loaded machine the wall time also
//! counts the time the thread waited for a core), and the number of `v_inf`
//! evaluations by purpose. Also prints the stall force with `v_inf` there
//! and its error estimate, so the convergence can be read off.
//!
//! `cargo run --release --example characteristic_bench [REPEATS]`

use std::time::Instant;
use stickslip::Scene;
use stickslip::characteristic::{self, CharacteristicOptions};

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Time this thread has run on a CPU (s), where the system says.
fn cpu_time() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(21);
    let scene = Scene::default();
    let options = CharacteristicOptions::default();
    let mut walls = Vec::new();
    let mut cpus = Vec::new();
    let mut last = None;
    for _ in 0..repeats {
        let cpu0 = cpu_time();
        let clock = Instant::now();
        let c = characteristic::characteristic(&scene, &options).expect("a characteristic");
        walls.push(clock.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (cpu0, cpu_time()) {
            cpus.push(b - a);
        }
        last = Some(c);
    }
    let c = last.expect("at least one run");
    let n = &c.counts;
    println!("characteristic of the default scene, {repeats} runs");
    println!(
        "  median wall time {:.2} ms{}",
        median(walls) * 1e3,
        if cpus.is_empty() {
            String::new()
        } else {
            format!(", median CPU time {:.2} ms", median(cpus) * 1e3)
        }
    );
    println!(
        "  v_inf evaluations {} (sampling {}, run-away limits {}, stall {}, held band {}, max power {}) + 1 start-up run; exact slopes at every point",
        n.v_inf(),
        n.sampling,
        n.run_away,
        n.stall,
        n.held_band,
        n.max_power,
    );
    println!("  points {}", c.points.len());
    let s = &c.stall;
    println!(
        "  stall force {:.15e} N ({}), bracket relative width {:.1e}, v_inf there {:e} m/s, error estimate {:e} m/s",
        s.force,
        s.kind.name(),
        s.relative_width(),
        s.at.v_inf.unwrap_or(f64::NAN),
        s.at.error.unwrap_or(f64::NAN)
    );
    for e in c.datasheet.entries() {
        println!(
            "  {:<18}{} {}",
            e.key,
            e.value.map_or("none".to_owned(), |v| format!("{v:.6e}")),
            e.unit
        );
    }
}
