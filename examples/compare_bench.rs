//! Benchmark: `stickslip compare` of a 10^6-sample file (the paper's
//! scene, samples t, x_S, v_S of the exact solution at a fixed step over
//! 100 periods, plus the per-period series). Prints the wall time; the
//! target is under 2 s on one core.
//!
//! `cargo run --release --example compare_bench`

use std::fmt::Write as _;
use std::time::Instant;
use stickslip::cli::{Streams, main_with};

fn main() {
    let dir = std::env::temp_dir().join(format!("stickslip-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let data = dir.join("samples.csv");
    let times = dir.join("times.csv");
    let scene = stickslip::Scene::default();
    let stickslip::scene::BuiltScene { signal, motor: _ } = scene.build().expect("default scene");
    let samples = 1_000_000u32;
    let h = 100.0 * signal.period() / f64::from(samples);
    let mut text = String::from("t\n");
    for i in 0..samples {
        let _ = writeln!(text, "{:e}", f64::from(i) * h);
    }
    std::fs::write(&times, text).expect("write times");
    // The exact solution at those times, written by `run --trajectory`.
    let run = |args: &[&str]| {
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let code = main_with(
            args.iter().copied(),
            &mut Streams {
                out: &mut out,
                err: &mut err,
            },
        );
        (code, String::from_utf8_lossy(&err).into_owned())
    };
    let (code, err) = run(&[
        "stickslip",
        "run",
        "--trajectory",
        data.to_str().unwrap(),
        "--times",
        times.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let clock = Instant::now();
    let (code, err) = run(&[
        "stickslip",
        "compare",
        "examples/scenes/paper_default.toml",
        data.to_str().unwrap(),
        "--metric",
        "v_S_max",
    ]);
    let wall = clock.elapsed().as_secs_f64();
    assert!(code <= 1, "{err}");
    println!("compare of {samples} samples: {wall:.3} s (target < 2 s)");
    let _ = std::fs::remove_dir_all(&dir);
}
