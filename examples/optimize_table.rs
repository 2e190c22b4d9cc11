//! The README table: the optimised signal against the sigma and the plain
//! Fourier signal, `v_inf` for `n = 2..6` at the paper's section-7 levels
//! `n sqrt(kappa)` in {3, 6, 9, 12, 15} (equal `f_max` per level,
//! 1574.8 Hz per level for the paper's motor, model 2), stroke 25 um,
//! objective `v_inf`, seed 1, default search settings. Prints a Markdown
//! table and, per level, which `n` is best once every `n` is optimised.
//! Takes about half a minute.
//!
//! `cargo run --release --example optimize_table`

use std::time::Instant;
use stickslip::Scene;
use stickslip::SignalSpec;
use stickslip::optimize::{self, OptimizeTable, Overrides, Settings};

fn main() {
    let clock = Instant::now();
    let levels = [3.0, 6.0, 9.0, 12.0, 15.0];
    let orders = [2usize, 3, 4, 5, 6];
    println!(
        "| level `n sqrt(kappa)` | `f_max` (Hz) | `n` | plain Fourier (m/s) | sigma (m/s) | optimised (m/s) | optimised / sigma | local optima found |"
    );
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let mut best_per_level = Vec::new();
    for level in levels {
        let mut best: Option<(usize, f64)> = None;
        let mut two = f64::NAN;
        for n in orders {
            let mut scene = Scene::default();
            let sqrt_kappa = level / n as f64;
            scene.signal = SignalSpec::fourier(25e-6, sqrt_kappa * sqrt_kappa, n, true);
            let overrides = Overrides {
                harmonics: Some(n as i64),
                ..Overrides::default()
            };
            let settings = Settings::resolve(&OptimizeTable::default(), &overrides, &scene)
                .expect("valid settings");
            let found = optimize::optimize(&scene, &settings).expect("optimises");
            let v_of = |name: &str| {
                found
                    .references
                    .iter()
                    .find(|r| r.name == name)
                    .and_then(|r| r.measured.as_ref().ok())
                    .map(|m| m.values.v_inf)
                    .expect("the paper's signals run")
            };
            let (plain, sigma) = (v_of("fourier"), v_of("sigma"));
            let v = found.best.measured.values.v_inf;
            println!(
                "| {level} | {:.1} | {n} | {plain:.4} | {sigma:.4} | {v:.4} | {:.2} | {} |",
                found.problem.f_max,
                v / sigma,
                found.search.local_optima
            );
            if best.is_none_or(|(_, b)| v > b) {
                best = Some((n, v));
            }
            if n == 2 {
                two = v;
            }
        }
        best_per_level.push((level, best.expect("five orders"), two));
    }
    println!();
    for (level, (n, v), two) in best_per_level {
        println!(
            "level {level}: best optimised n = {n}, v_inf = {v:.9} m/s ({:+.1e} relative to n = 2's {two:.9} m/s)",
            v / two - 1.0
        );
    }
    println!("({:.0} s)", clock.elapsed().as_secs_f64());
}
