//! The driven engine's events against a dense scan over many random driven
//! scenes (docs/model.md section 16): every segment of a few periods from
//! rest integrated again by a Taylor series from its start state
//! (`tests/common/driven_taylor.rs`), its event function (`v_rel` in
//! slip, `a_st` in stick) sampled densely with every critical point
//! refined, and every segment end read by the friction law
//! (`tests/common/driven_scan.rs`).
//!
//! Two sets of scenes: random ones (`tests/common/driven_cases.rs`), and
//! pairs placed by bisection on the contact force at a change of the
//! engine's event count, where an event appears (a grazing, a touch of a
//! band edge, an event at a period end): the near-decisions the scan's
//! rounding allowances are for. For each set it prints the scenes, the
//! events by kind (engine and scan), the disagreements (events missed
//! inside segments, or read differently at segment ends), the readings
//! within the scan's rounding of a decision, the near grazings and
//! touches inside segments, the largest difference between the engine's
//! closed form and the scan's integration, and how much of its location
//! allowance an event used, and the kinds of disagreement.
//! `tests/driven_events.rs` asserts the same on 100 random scenes.
//!
//! Both sets agree with the scan (seed 1: 1000 random scenes, and 234
//! placed at 117 changes). At a zero of `v_rel` the scan reads the band
//! where it puts the zero, and a reading within the zero's resolution of a
//! band edge (`|a_st'|` times `(loc_v + err_v) / |v_rel'|`, plus `loc_a +
//! err_a`) is right either way: a stick phase or slip that short is below
//! what either side resolves. The example prints how many readings that
//! was and the largest distance from the edge against its allowance.
//!
//! `cargo run --release --example driven_events [-- SCENES [PAIRS [PERIODS [SEED]]]]`
//! (defaults: 1000 scenes, 200 pairs, 4 periods, seed 1).

#[path = "../tests/common/driven_cases.rs"]
mod driven_cases;
#[path = "../tests/common/driven_scan.rs"]
mod driven_scan;
#[path = "../tests/common/driven_taylor.rs"]
mod driven_taylor;

use driven_cases::{DrivenCase, Rng};
use driven_scan::{Model, Scan};
use rayon::prelude::*;
use std::time::Instant;

/// The scan of one case's run.
fn scan_case(case: &DrivenCase, periods: u64) -> Result<Scan, String> {
    let built = case.build()?;
    let (record, tol_v) = driven_cases::record(&built, periods)?;
    let model = Model::new(case, &built, tol_v);
    Ok(driven_scan::scan(&model, &record))
}

/// Scans `cases` and prints the tally under `title`.
fn report(title: &str, cases: &[DrivenCase], periods: u64) {
    let clock = Instant::now();
    let results: Vec<Result<Scan, String>> =
        cases.par_iter().map(|c| scan_case(c, periods)).collect();
    let mut total = Scan::default();
    let (mut failed, mut sticking, mut disagreeing) = (Vec::new(), 0, Vec::new());
    for (i, r) in results.into_iter().enumerate() {
        match r {
            Ok(scan) => {
                sticking += usize::from(scan.engine.slip_to_stick + scan.engine.stick_to_slip > 0);
                if !scan.disagreements.is_empty() {
                    disagreeing.push((i, scan.disagreements.clone()));
                }
                total.merge(scan);
            }
            Err(e) => failed.push((i, e)),
        }
    }
    let reaction = cases.iter().filter(|c| c.spec.reaction).count();
    let (e, s) = (total.engine, total.scan);
    println!(
        "{title}: {} scenes, {periods} periods each from rest ({reaction} with the reaction, \
         {sticking} with a stick phase, {} not run); {} segments, {} evaluations of the \
         event functions, {:.1} s",
        cases.len(),
        failed.len(),
        total.segments,
        total.samples,
        clock.elapsed().as_secs_f64()
    );
    println!("  events          engine     scan");
    for (name, a, b) in [
        ("stick_to_slip", e.stick_to_slip, s.stick_to_slip),
        ("slip_to_stick", e.slip_to_stick, s.slip_to_stick),
        ("reversal", e.reversal, s.reversal),
        ("grazing", e.grazing, s.grazing),
        ("total", e.total(), s.total() + total.missed),
    ] {
        println!("  {name:<13} {a:>8} {b:>8}");
    }
    println!(
        "  disagreements {} in {} scenes ({} events missed inside segments); \
         readings within rounding of a decision {}; near grazings and edge touches \
         inside segments {}",
        total.disagreements.len(),
        disagreeing.len(),
        total.missed,
        total.ambiguous,
        total.near
    );
    if let Some(worst) = total
        .at_zero
        .iter()
        .max_by(|a, b| (a[0] / a[1]).total_cmp(&(b[0] / b[1])))
    {
        println!(
            "  of those, at zeros of v_rel within the zero's resolution of a band edge: {}, \
             the farthest {:.2e} m/s^2 from the edge against an allowance of {:.2e}",
            total.at_zero.len(),
            worst[0],
            worst[1]
        );
    }
    println!(
        "  rod state at segment ends, engine against scan: largest difference {:.1e} of its \
         scale; events: largest distance from their crossing {:.2} of the allowance",
        total.state, total.offset
    );
    let kinds = [
        (
            "a_st beyond the band in a stick segment (a missed exit)",
            "stick segment",
        ),
        (
            "v_rel of the wrong sign in a slip (a missed zero)",
            "changes sign",
        ),
        (
            "v_rel within tol_v at a critical point (a missed touch)",
            "critical point",
        ),
    ];
    for (what, key) in kinds {
        let n = total
            .disagreements
            .iter()
            .filter(|d| d.contains(key))
            .count();
        if n > 0 {
            println!("    {n}: {what}");
        }
    }
    let other = total
        .disagreements
        .iter()
        .filter(|d| !kinds.iter().any(|(_, key)| d.contains(key)))
        .count();
    if other > 0 {
        println!("    {other}: a segment end read differently");
    }
    for (i, d) in disagreeing.iter().take(3) {
        println!("  scene {i}: {:?}\n    {}", cases[*i], d.join("\n    "));
    }
    for (i, e) in failed.iter().take(5) {
        println!("  scene {i} not run: {e}");
    }
}

fn main() {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    let scenes = args.first().copied().unwrap_or(1000) as usize;
    let pairs = args.get(1).copied().unwrap_or(200) as usize;
    let periods = args.get(2).copied().unwrap_or(4);
    let seed = args.get(3).copied().unwrap_or(1);
    let mut rng = Rng::new(seed);
    let cases: Vec<DrivenCase> = (0..scenes).map(|_| DrivenCase::random(&mut rng)).collect();
    report(&format!("random scenes (seed {seed})"), &cases, periods);
    if pairs == 0 {
        return;
    }
    let clock = Instant::now();
    let seeds: Vec<DrivenCase> = (0..pairs).map(|_| DrivenCase::random(&mut rng)).collect();
    let placed: Vec<DrivenCase> = seeds
        .par_iter()
        .filter_map(|c| c.at_count_change(periods))
        .flat_map(|(a, b)| [a, b])
        .collect();
    println!(
        "\n{} of {pairs} scenes have an event-count change within twice their contact \
         force; placed by bisection in {:.1} s",
        placed.len() / 2,
        clock.elapsed().as_secs_f64()
    );
    report("both sides of a change", &placed, periods);
}
