//! The certified first-zero finder of `src/numerics/exp_trig` on many
//! random functions (a quadratic, up to 15 harmonics, one or two damped oscillators
//! in every regime; `src/numerics/exp_trig/cases.rs`):
//!
//! * a simple root planted at a random `r` (`p0 -= f(r)`, where `f'(r)` is
//!   at least 5 % of its scale): is an event found within `1e-12 T` of
//!   `r`, a transversal zero, and is every event before it genuine;
//! * a double root planted at `r` (`f(r) = f'(r) = 0`, where `f''(r)` is at
//!   least 5 % of its scale): the same, as a tangency;
//! * a triple root (`f''(r) = 0` too): an event within `1e-4 T` (rounding
//!   spreads such a root over `~ε^{1/3}`), of either kind;
//!
//! each with the tolerance `tol` in turn 0 (the rounding level), `1e-13`
//! and `1e-9` of the size of `f`;
//! * the chain of events over two periods against the sign changes of
//!   10^5 samples (where those decide);
//! * the rounding bound `η` against a term-by-term evaluation, and the
//!   cost of a search.
//!
//! The finder is crate-private; this example compiles its source files
//! (and `bracket.rs`) into itself.
//!
//! `cargo run --release --example exp_trig_roots [functions] [dense cases]`
//! (default 100000 and 1000).

use std::time::Instant;

#[path = "../src/numerics/bracket.rs"]
#[allow(dead_code)]
mod bracket;
#[path = "../src/numerics/exp_trig/cases.rs"]
mod cases;
#[path = "../src/numerics/exp_trig/mod.rs"]
#[allow(dead_code)]
mod exp_trig;
#[path = "../src/numerics/power_of_two.rs"]
mod power_of_two;

// `cases.rs` finds the finder's names here (as `super::`).
use exp_trig::{Crossing, DampedOscillator, ExpTrig, Start, Work};

use cases::{Dense, PERIOD, Plant};
use rand::SeedableRng;
use rand::rngs::StdRng;

/// Counts of one kind of planted root.
#[derive(Default)]
struct Tally {
    tried: u64,
    conditioned: u64,
    found: u64,
    other_kind: u64,
    covered: u64,
    missed: u64,
    spurious: u64,
    before: u64,
    worst_error: f64,
}

/// The tolerances, as fractions of the size of `f`, used in turn.
const LEVELS: [f64; 3] = [0.0, 1e-13, 1e-9];

fn plant_all(functions: u64, kind: Plant, seed0: u64) -> Tally {
    let mut t = Tally::default();
    for seed in seed0..seed0 + functions {
        t.tried += 1;
        let Some((f, r)) = cases::planted(seed, 15, kind) else {
            continue;
        };
        t.conditioned += 1;
        let tol = cases::tolerance(&f, r, LEVELS[(seed % 3) as usize]);
        let out = cases::search_planted(&f, r, kind, tol);
        if out.found {
            t.found += 1;
            t.worst_error = t.worst_error.max(out.error);
        } else if out.other_kind {
            t.other_kind += 1;
        } else if out.covered {
            t.covered += 1;
        } else {
            t.missed += 1;
            println!(
                "  missed: seed {seed}, r = {r:e}, closest {:e} T",
                out.error
            );
        }
        t.spurious += out.spurious as u64;
        t.before += out.before as u64;
    }
    t
}

fn print_tally(name: &str, t: &Tally) {
    println!(
        "{name}: {} functions, {} well conditioned: found {} (worst |s - r| = {:.1e} T), \
         reported as the other kind {}, inside the band of an earlier event {}, missed {}; \
         events before r: {} ({} not genuine)",
        t.tried,
        t.conditioned,
        t.found,
        t.worst_error,
        t.other_kind,
        t.covered,
        t.missed,
        t.before,
        t.spurious
    );
}

fn main() {
    let mut args = std::env::args().skip(1);
    let functions: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let dense_cases: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1000);

    let clock = Instant::now();
    let simple = plant_all(functions, Plant::Simple, 1 << 40);
    print_tally("simple roots", &simple);
    let double = plant_all(functions, Plant::Double, 2 << 40);
    print_tally("double roots", &double);
    let triple = plant_all(functions / 10, Plant::Triple, 5 << 40);
    print_tally("triple roots (found: within 1e-4 T)", &triple);
    println!("({:.1} s)", clock.elapsed().as_secs_f64());

    let clock = Instant::now();
    let (mut agree, mut skipped, mut disagree, mut changes) = (0u64, 0u64, 0u64, 0usize);
    for seed in 0..dense_cases {
        let f = cases::random_function(&mut StdRng::seed_from_u64((3 << 40) + seed), 15);
        match cases::dense_scan(&f, 2.0 * PERIOD, 100_000) {
            Dense::Agrees { changes: c } => {
                agree += 1;
                changes += c;
            }
            Dense::Skipped => skipped += 1,
            Dense::Disagrees(why) => {
                disagree += 1;
                println!("  dense scan disagrees, seed {seed}: {why}");
            }
        }
    }
    println!(
        "dense scan (10^5 samples on 2 periods): {dense_cases} functions, agree {agree} \
         ({changes} sign changes), disagree {disagree}, undecided by the samples {skipped} ({:.1} s)",
        clock.elapsed().as_secs_f64()
    );

    let ratio = cases::rounding_ratio(6 << 40..(6 << 40) + 2000, 40, 50);
    println!(
        "rounding bound: largest |eval - term-by-term sum| / eta_j (j = 0, 1, 2) over 2000 \
         functions of up to 40 harmonics, 50 times each: {:.3} {:.3} {:.3}",
        ratio[0], ratio[1], ratio[2]
    );

    // Cost: every event on three periods, one search after the other.
    let mut work = Work::default();
    let (mut calls, mut events) = (0u64, 0u64);
    let count = functions.min(20_000);
    let fs: Vec<ExpTrig> = (0..count)
        .map(|seed| cases::random_function(&mut StdRng::seed_from_u64((4 << 40) + seed), 15))
        .collect();
    let clock = Instant::now();
    for f in &fs {
        let (mut s, mut start) = (0.0, Start::Clear);
        loop {
            calls += 1;
            let Some(e) = f.first_zero_counting(s, 3.0 * PERIOD, 0.0, start, &mut work) else {
                break;
            };
            events += 1;
            (s, start) = (e.s(), Start::AfterEvent);
        }
    }
    let elapsed = clock.elapsed().as_secs_f64();
    println!(
        "cost: {count} functions, {calls} searches, {events} events on 3 periods: \
         {:.2} us per search; per search {:.1} evaluations, {:.1} pieces, {:.2} halvings, \
         {} clusters in all",
        1e6 * elapsed / calls as f64,
        work.evaluations as f64 / calls as f64,
        work.pieces as f64 / calls as f64,
        work.subdivisions as f64 / calls as f64,
        work.clusters
    );
}
