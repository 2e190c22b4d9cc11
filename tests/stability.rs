//! Every case of the stability catalogue (`stickslip::stability`) passes
//! its check: closed forms, exact scaling laws, symmetries, run-away
//! detection, constructed grazing and a 1e7-period run without drift.

#[path = "common/stability.rs"]
mod stability;
use stability::{catalogue, run_case};

#[test]
fn every_stress_case_passes_its_check() {
    let mut failures = Vec::new();
    for case in catalogue() {
        let outcome = run_case(&case);
        if !outcome.passed {
            failures.push(format!(
                "{}: {} ({})",
                outcome.name, outcome.check, outcome.result
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
