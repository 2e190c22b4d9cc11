//! Cost of the real-root finder of trigonometric polynomials: medians of
//! `TrigPoly::roots_at_level` (certified subdivision) against the previous
//! companion-matrix finder `TrigPoly::roots_by_eigenvalues`, for degrees
//! 2..=256 and two kinds of coefficients:
//! * `random`: `c0, a_k, b_k` uniform in `[-1, 1]`, level 0 (about `0.8 n`
//!   roots, some close together);
//! * `fourier`: the acceleration `a_R` of the paper's sigma-smoothed Fourier
//!   approximation of the ideal signal (docs/model.md section 4) for the
//!   default motor, at the levels 0 and half its maximum.
//!
//! The `roots` columns count the roots each finder reports (they agree on
//! every case here). `cargo run --release --example roots_bench`

use std::time::Instant;

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use stickslip::motor::Motor;
use stickslip::numerics::TrigPoly;
use stickslip::signal::FourierSignal;
use stickslip::{signal::Drive, signal::IdealShape};

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Median wall time (µs) of `f` over `reps` calls, and its last result.
fn time<F: Fn() -> Vec<f64>>(reps: usize, f: F) -> (f64, Vec<f64>) {
    let mut out = Vec::new();
    let times = (0..reps)
        .map(|_| {
            let clock = Instant::now();
            out = f();
            clock.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    (median(times), out)
}

fn random_poly(n: usize, rng: &mut StdRng) -> TrigPoly {
    let mut coef = || rng.random_range(-1.0..1.0);
    let c0 = coef();
    let a = (0..n).map(|_| coef()).collect();
    let b = (0..n).map(|_| coef()).collect();
    TrigPoly::new(c0, a, b)
}

/// `a_R` of the sigma-smoothed `n`-harmonic signal with `sqrt(kappa) = 6`.
fn fourier_poly(n: usize) -> TrigPoly {
    let motor = Motor::default();
    let shape = IdealShape {
        stroke: 25e-6,
        drive: Drive::Kappa(36.0),
        duty: 1.0,
    };
    FourierSignal::approximate_ideal(shape, n, true, &motor)
        .expect("valid signal")
        .acceleration_poly()
}

fn main() {
    let degrees = [2, 8, 16, 32, 64, 128, 256];
    let mut rng = StdRng::seed_from_u64(12);
    println!(
        "{:>4} {:>12} {:>6} {:>6} {:>12} {:>12} {:>8}",
        "n", "kind", "roots", "old", "new (us)", "old (us)", "speedup"
    );
    for &n in &degrees {
        let max = fourier_poly(n);
        let peak = (0..4096)
            .map(|i| max.eval(i as f64 / 4096.0 * std::f64::consts::TAU).abs())
            .fold(0.0, f64::max);
        let cases = [
            ("random", random_poly(n, &mut rng), 0.0),
            ("fourier", fourier_poly(n), 0.0),
            ("fourier/2", fourier_poly(n), 0.5 * peak),
        ];
        for (kind, p, level) in cases {
            let reps_new = 101;
            let reps_old = if n >= 128 { 3 } else { 15 };
            let (t_new, r_new) = time(reps_new, || p.roots_at_level(level));
            let mut q = p.clone();
            q.c0 -= level;
            let (t_old, r_old) = time(reps_old, || q.roots_by_eigenvalues());
            println!(
                "{:>4} {:>12} {:>6} {:>6} {:>12.1} {:>12.1} {:>8.0}",
                n,
                kind,
                r_new.len(),
                r_old.len(),
                t_new,
                t_old,
                t_old / t_new
            );
        }
    }
}
