//! Benchmark of `stickslip plot` on a large sweep output: a synthetic
//! 10^5-row CSV (50 000 strokes × sigma on/off, one failed case in 1000 and
//! one run-away in 1000), plotted as `v_inf` against `stroke` on log axes
//! with one series per `sigma`, to SVG, PDF and PNG through
//! `cli::main_with` (the binary's code path); the goal is under 2 s.
//!
//! `cargo run --release --example plot_bench [ROWS]`

use std::fmt::Write as _;
use std::time::Instant;
use stickslip::cli::{Streams, main_with};

fn main() -> std::process::ExitCode {
    let rows: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100_000);
    let dir = std::env::temp_dir().join(format!("stickslip-plot-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let input = dir.join("sweep.csv");
    let mut text = String::from(
        "# stickslip_version = 0.1.0, base_scene_hash = 0\ncase,stroke,sigma,v_inf,regime,failure\n",
    );
    let strokes = rows.div_ceil(2);
    for case in 0..rows {
        let (i, sigma) = (case / 2, case % 2 == 1);
        let stroke = 1e-9 * 1e6f64.powf(i as f64 / strokes as f64);
        let v = 2.0 * stroke.sqrt() * if sigma { 1.3 } else { 1.0 };
        let (v, regime, failure) = match case % 1000 {
            7 => (String::new(), "", "time limit reached"),
            501 => (String::new(), "run-away", ""),
            _ => (format!("{v:e}"), "slip-slip", ""),
        };
        let _ = writeln!(text, "{case},{stroke:e},{sigma},{v},{regime},{failure}");
    }
    std::fs::write(&input, text).expect("the input is written");
    println!(
        "{rows} rows, {} bytes",
        std::fs::metadata(&input).map_or(0, |m| m.len())
    );
    let mut worst: f64 = 0.0;
    for ext in ["svg", "pdf", "png"] {
        let output = dir.join(format!("v_inf.{ext}"));
        let args = [
            "stickslip",
            "plot",
            input.to_str().unwrap(),
            "-o",
            output.to_str().unwrap(),
            "--x",
            "stroke",
            "--y",
            "v_inf",
            "--series",
            "sigma",
            "--log-x",
            "--log-y",
        ];
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let clock = Instant::now();
        let code = main_with(
            args,
            &mut Streams {
                out: &mut out,
                err: &mut err,
            },
        );
        let seconds = clock.elapsed().as_secs_f64();
        worst = worst.max(seconds);
        assert_eq!(code, 0, "{}", String::from_utf8_lossy(&err));
        let bytes = std::fs::metadata(&output).map_or(0, |m| m.len());
        println!("{ext}: {seconds:.3} s, {bytes} bytes");
    }
    let _ = std::fs::remove_dir_all(&dir);
    if worst < 2.0 {
        println!("every format under 2 s (slowest {worst:.3} s)");
        std::process::ExitCode::SUCCESS
    } else {
        println!("slowest {worst:.3} s: over the 2 s budget");
        std::process::ExitCode::FAILURE
    }
}
