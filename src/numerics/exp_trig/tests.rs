//! Tests of the finder: planted roots, a dense scan, closed forms for the
//! start, the band and the interval's ends, bad input, the rounding bound
//! and the cost.

use std::f64::consts::{PI, TAU};

use proptest::prelude::*;
use rand::SeedableRng;
use rand::rngs::StdRng;

use super::cases::{self, Dense, PERIOD, Plant};
use super::{Crossing, DampedOscillator, ExpTrig, Start, Work};

const T: f64 = PERIOD;

fn w() -> f64 {
    TAU / T
}

/// `p0 + Σ (a_k cos kθ + b_k sin kθ)`, `θ = w s`, no oscillator.
fn series(p0: f64, a: &[f64], b: &[f64]) -> ExpTrig {
    ExpTrig {
        poly: [p0, 0.0, 0.0],
        w: w(),
        phi: 0.0,
        a: a.to_vec(),
        b: b.to_vec(),
        osc: [None, None],
    }
}

/// Asserts a transversal zero at `s` (within `1e-12 T`) with the direction.
fn assert_transversal(found: Option<Crossing>, s: f64, rising: bool) {
    match found {
        Some(Crossing::Transversal { s: got, rising: r }) => {
            assert!(
                (got - s).abs() <= 1e-12 * T,
                "zero at {got:e}, expected {s:e}"
            );
            assert_eq!(r, rising, "direction at {got:e}");
        }
        other => panic!("expected a transversal zero at {s:e}, got {other:?}"),
    }
}

/// Asserts a tangency at `s` (within `1e-12 T`).
fn assert_tangency(found: Option<Crossing>, s: f64) {
    match found {
        Some(Crossing::Tangency { s: got }) => {
            assert!(
                (got - s).abs() <= 1e-12 * T,
                "tangency at {got:e}, expected {s:e}"
            );
        }
        other => panic!("expected a tangency at {s:e}, got {other:?}"),
    }
}

/// The tolerances of the planted searches: none (the rounding level),
/// the engine's default `1e-13` and a wide `1e-9` of the size of `f`.
const LEVELS: [f64; 3] = [0.0, 1e-13, 1e-9];

/// Searches for a root of the kind planted by `seed`; `None` where the
/// draw was ill-conditioned.
fn planted_search(seed: u64, n: usize, kind: Plant, level: usize) -> Option<cases::PlantedOutcome> {
    let (f, r) = cases::planted(seed, n, kind)?;
    let tol = cases::tolerance(&f, r, LEVELS[level]);
    Some(cases::search_planted(&f, r, kind, tol))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 3000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x00e7_5157),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// A simple root planted at `r` (`p0 -= f(r)`) is found there, as a
    /// transversal zero, and every event before it is genuine.
    #[test]
    fn a_planted_simple_root_is_found_and_nothing_false_before_it(
        seed in any::<u64>(), n in 0usize..=15, level in 0usize..3,
    ) {
        if let Some(out) = planted_search(seed, n, Plant::Simple, level) {
            prop_assert!(out.found || out.covered, "{:?}", out);
            prop_assert_eq!(out.spurious, 0, "{:?}", out);
        }
    }

    /// A double root planted at `r` (`p0`, `p1` adjusted so that
    /// `f(r) = f'(r) = 0`, where `f''(r)` is clearly nonzero) is reported
    /// as a tangency there, and every event before it is genuine.
    #[test]
    fn a_planted_double_root_is_a_tangency_and_nothing_false_before_it(
        seed in any::<u64>(), n in 0usize..=15, level in 0usize..3,
    ) {
        if let Some(out) = planted_search(seed, n, Plant::Double, level) {
            prop_assert!(out.found || out.covered, "{:?}", out);
            prop_assert_eq!(out.spurious, 0, "{:?}", out);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 500,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x0007_7121),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// A triple root (`f = f' = f'' = 0`: no test decides the pieces around
    /// it, a cluster) is found once, within `1e-4 T`, and nothing false
    /// before it.
    #[test]
    fn a_planted_triple_root_is_found_once(seed in any::<u64>(), n in 0usize..=15) {
        if let Some(out) = planted_search(seed, n, Plant::Triple, 0) {
            prop_assert!(out.found || out.covered, "{:?}", out);
            prop_assert_eq!(out.spurious, 0, "{:?}", out);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 1000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x00ba_4d5e),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// A double root at `r` lifted by `p0 += shift` (the critical point
    /// stays at `r`): within the band (`|shift| = tol/2`) it is a tangency
    /// at `r` on either side of zero; beyond it (`2 tol`) through zero, two
    /// transversal zeros around `r` and no tangency near it; away from
    /// zero, no event near `r`.
    #[test]
    fn the_band_decides_between_a_tangency_and_two_zeros(
        seed in any::<u64>(), n in 0usize..=15, sign in prop::bool::ANY,
    ) {
        let Some((mut f, r)) = cases::planted(seed, n, Plant::Double) else {
            return Ok(());
        };
        let tol = cases::tolerance(&f, r, 1e-9);
        let curvature = f.eval(r)[2].signum();
        let p0 = f.poly[0];
        let near = |e: &Crossing| (e.s() - r).abs() <= 1e-3 * T;
        let s_b = r + 0.25 * T;
        for shift in [0.5 * tol, -0.5 * tol] {
            f.poly[0] = p0 + if sign { shift } else { -shift };
            let found = cases::events(&f, 0.0, s_b, tol, 1000);
            let at_r = found.iter().find(|e| near(e));
            prop_assert!(
                matches!(at_r, Some(Crossing::Tangency { s }) if (s - r).abs() <= 1e-12 * T),
                "shift {shift:e}: {found:?}"
            );
        }
        // through zero: f(r) = -2 tol sign(f'')
        f.poly[0] = p0 - 2.0 * tol * curvature;
        let found = cases::events(&f, 0.0, s_b, tol, 1000);
        let around: Vec<&Crossing> = found.iter().filter(|e| near(e)).collect();
        prop_assert_eq!(around.len(), 2, "{:?}", found);
        prop_assert!(around[0].s() < r && around[1].s() > r, "{:?}", around);
        let transversal = around.iter().all(|e| matches!(e, Crossing::Transversal { .. }));
        prop_assert!(transversal, "{:?}", around);
        // away from zero: nothing near r
        f.poly[0] = p0 + 2.0 * tol * curvature;
        let found = cases::events(&f, 0.0, s_b, tol, 1000);
        prop_assert!(!found.iter().any(near), "{:?}", found);
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x0de7_5e5c),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// The events found one after the other on two periods are exactly
    /// the sign changes of 10^5 samples (where those are separated by four
    /// samples or more and no sample is at the rounding level).
    #[test]
    fn restarted_searches_enumerate_the_sign_changes_of_a_dense_scan(seed in any::<u64>(), n in 0usize..=15) {
        let f = cases::random_function(&mut StdRng::seed_from_u64(seed), n);
        let out = cases::dense_scan(&f, 2.0 * T, 100_000);
        prop_assert!(!matches!(out, Dense::Disagrees(_)), "{out:?} for {f:?}");
    }
}

#[test]
fn the_dense_scan_comparison_decides_most_cases() {
    // The comparison above skips undecidable draws: it must decide most,
    // and see sign changes in them.
    let (mut decided, mut changes) = (0, 0);
    for seed in 0..16 {
        let f = cases::random_function(&mut StdRng::seed_from_u64(seed), 15);
        if let Dense::Agrees { changes: c } = cases::dense_scan(&f, 2.0 * T, 20_000) {
            decided += 1;
            changes += c;
        }
    }
    assert!(
        decided >= 12 && changes >= 20,
        "{decided} decided, {changes} changes"
    );
}

#[test]
fn a_zero_exactly_at_the_start_is_not_an_event() {
    // sin(w s): zeros at multiples of T/2 (closed form), f(0) = 0 exactly.
    let f = series(0.0, &[0.0], &[1.0]);
    for start in [Start::Clear, Start::AfterEvent] {
        assert_transversal(f.first_zero(0.0, T, 0.0, start), T / 2.0, false);
    }
}

#[test]
fn a_restart_at_a_computed_zero_finds_the_next_one_on_either_side_of_it() {
    // Restarting at the computed zero of sin(w s) near T/2, or a few ulps
    // to either side of it (where f has the wrong sign by rounding), gives
    // the next zero at T: the same event is not found twice.
    let f = series(0.0, &[0.0], &[1.0]);
    let Some(first) = f.first_zero(0.0, T, 0.0, Start::Clear) else {
        panic!("the zero at T/2");
    };
    let mut s = first.s();
    for _ in 0..4 {
        s = s.next_down();
    }
    for _ in 0..9 {
        assert_transversal(f.first_zero(s, 2.0 * T, 0.0, Start::AfterEvent), T, true);
        s = s.next_up();
    }
}

#[test]
fn a_restart_at_a_tangency_finds_the_next_one() {
    // 1 + cos(w s) touches zero at T/2 and 3T/2 (closed form).
    let f = series(1.0, &[1.0], &[0.0]);
    let first = f.first_zero(0.0, 2.0 * T, 0.0, Start::Clear);
    assert_tangency(first, T / 2.0);
    let s = first.map_or(0.0, |e| e.s());
    assert_tangency(f.first_zero(s, 2.0 * T, 0.0, Start::AfterEvent), 1.5 * T);
}

#[test]
fn a_minimum_within_the_band_is_a_tangency_on_either_side_of_zero() {
    // 1 - d + cos(w s) has its minimum -d at T/2 (closed form): within
    // tol = 1e-6 on either side of zero it is a tangency there; a dip by
    // 2e-6 gives the two zeros at (π ∓ acos(1 - d)) / w.
    let tol = 1e-6;
    for d in [5e-7, -5e-7] {
        let f = series(1.0 - d, &[1.0], &[0.0]);
        assert_tangency(f.first_zero(0.0, T, tol, Start::Clear), T / 2.0);
    }
    let d = 2e-6;
    let f = series(1.0 - d, &[1.0], &[0.0]);
    let first = (PI - (1.0 - d).acos()) / w();
    let second = (PI + (1.0 - d).acos()) / w();
    let found = f.first_zero(0.0, T, tol, Start::Clear);
    assert_transversal(found, first, false);
    let from = found.map_or(0.0, |e| e.s());
    assert_transversal(f.first_zero(from, T, tol, Start::AfterEvent), second, true);
}

#[test]
fn crossings_inside_the_band_of_a_tangency_belong_to_it_wherever_the_pieces_fall() {
    // 0.95 + cos(w s) dips to -0.05 at T/2: with tol = 0.1 the two zeros
    // 0.045 T either side lie in the band of the minimum, so the event is
    // the tangency at T/2, from any start before the first zero (the
    // pieces fall differently); with tol = 0.01 it is the first zero.
    let f = series(0.95, &[1.0], &[0.0]);
    let first = (PI - 0.95_f64.acos()) / w();
    for i in 0..40 {
        let s_a = 0.01 * i as f64 * T;
        assert_tangency(f.first_zero(s_a, T, 0.1, Start::Clear), T / 2.0);
        assert_transversal(f.first_zero(s_a, T, 0.01, Start::Clear), first, false);
    }
}

#[test]
fn a_departure_lasts_while_f_stays_in_the_band() {
    // f = 0.4 tol sin(w s) never leaves the band: after an event at 0
    // there is none; without one, its first critical point T/4 is a
    // tangency (|f| <= tol there).
    let tol = 1e-3;
    let f = series(0.0, &[0.0], &[0.4 * tol]);
    assert_eq!(f.first_zero(0.0, 2.0 * T, tol, Start::AfterEvent), None);
    assert_tangency(f.first_zero(0.0, 2.0 * T, tol, Start::Clear), T / 4.0);
    // sin(w s) with tol = 0.5 leaves the band at T/12: the next event is
    // the zero at T/2, the maximum (1 > tol) is none.
    let f = series(0.0, &[0.0], &[1.0]);
    assert_transversal(f.first_zero(0.0, T, 0.5, Start::AfterEvent), T / 2.0, false);
}

#[test]
fn the_interval_is_open_at_the_start_and_closed_at_the_end() {
    // sin(w s) on (0, s_b]: a zero at s_b is found, one after it is not.
    let f = series(0.0, &[0.0], &[1.0]);
    let zero = f
        .first_zero(0.0, T, 0.0, Start::Clear)
        .map_or(0.0, |e| e.s());
    assert_transversal(f.first_zero(0.0, zero, 0.0, Start::Clear), T / 2.0, false);
    assert_eq!(f.first_zero(0.0, 0.45 * T, 0.0, Start::Clear), None);
    assert_eq!(f.first_zero(0.55 * T, 0.95 * T, 0.0, Start::Clear), None);
}

#[test]
fn the_oscillator_alone_and_its_zeros() {
    // An undamped oscillator y = cos(ω0 s) has zeros at (k + 1/2) π/ω0; the
    // critically damped y = (1 - s ω0) e^{-ω0 s} (y0 = 1, y1 = -2 ω0) one at
    // 1/ω0 (closed forms).
    let omega0 = 3.0 * w();
    let mut f = ExpTrig {
        poly: [0.0; 3],
        w: w(),
        phi: 0.0,
        a: Vec::new(),
        b: Vec::new(),
        osc: [
            Some(DampedOscillator {
                sigma: 0.0,
                omega0,
                y0: 1.0,
                y1: 0.0,
            }),
            None,
        ],
    };
    let zero = f.first_zero(0.0, T, 0.0, Start::Clear);
    assert_transversal(zero, 0.5 * PI / omega0, false);
    let from = zero.map_or(0.0, |e| e.s());
    assert_transversal(
        f.first_zero(from, T, 0.0, Start::AfterEvent),
        1.5 * PI / omega0,
        true,
    );
    f.osc[0] = Some(DampedOscillator {
        sigma: omega0,
        omega0,
        y0: 1.0,
        y1: -2.0 * omega0,
    });
    assert_transversal(
        f.first_zero(0.0, 10.0 * T, 0.0, Start::Clear),
        1.0 / omega0,
        false,
    );
}

#[test]
fn two_oscillators_beat_and_every_zero_of_the_beat_is_found() {
    // cos(ω1 s) + cos(ω2 s) = 2 cos((ω1 + ω2) s / 2) cos((ω1 - ω2) s / 2)
    // (the sum-to-product identity): its zeros are those of either factor,
    // (k + 1/2) 2π / (ω1 + ω2) and (k + 1/2) 2π / (ω1 - ω2), distinct
    // here. Two undamped oscillators of 7 w and 3 w, over two periods.
    let (w1, w2) = (7.0 * w(), 3.0 * w());
    let undamped = |omega0: f64| DampedOscillator {
        sigma: 0.0,
        omega0,
        y0: 1.0,
        y1: 0.0,
    };
    let f = ExpTrig {
        poly: [0.0; 3],
        w: w(),
        phi: 0.0,
        a: Vec::new(),
        b: Vec::new(),
        osc: [Some(undamped(w1)), Some(undamped(w2))],
    };
    let span = 2.0 * T;
    let mut expected = Vec::new();
    for q in [w1 + w2, w1 - w2] {
        let mut k = 0.0;
        while (k + 0.5) * TAU / q < span {
            expected.push((k + 0.5) * TAU / q);
            k += 1.0;
        }
    }
    expected.sort_by(f64::total_cmp);
    let found = cases::events(&f, 0.0, span, 0.0, 100);
    assert_eq!(found.len(), expected.len(), "{found:?}");
    for (c, &z) in found.iter().zip(&expected) {
        assert!(matches!(c, Crossing::Transversal { .. }), "{c:?}");
        assert!((c.s() - z).abs() <= 1e-12 * T, "{} against {z}", c.s());
    }
}

#[test]
fn bad_input_gives_no_event_and_no_panic() {
    let good = series(0.0, &[0.0], &[1.0]);
    let search =
        |f: &ExpTrig, s_a: f64, s_b: f64, tol: f64| f.first_zero(s_a, s_b, tol, Start::Clear);
    assert!(search(&good, 0.0, T, 0.0).is_some());
    let mut nan = good.clone();
    nan.a[0] = f64::NAN;
    assert_eq!(search(&nan, 0.0, T, 0.0), None);
    let mut no_frequency = good.clone();
    no_frequency.w = 0.0;
    assert_eq!(search(&no_frequency, 0.0, T, 0.0), None);
    for osc in [(-1.0, 1.0), (1.0, 0.0), (f64::INFINITY, 1.0), (1.0, 1e300)] {
        let mut f = good.clone();
        f.osc[1] = Some(DampedOscillator {
            sigma: osc.0,
            omega0: osc.1,
            y0: 1.0,
            y1: 0.0,
        });
        assert_eq!(search(&f, 0.0, T, 0.0), None, "{osc:?}");
    }
    assert_eq!(search(&good, 0.5 * T, 0.5 * T, 0.0), None);
    assert_eq!(search(&good, -T, T, 0.0), None);
    assert_eq!(search(&good, 0.0, f64::INFINITY, 0.0), None);
    assert_eq!(search(&good, 0.0, T, f64::NAN), None);
    // a constant, zero or not, has no event
    assert_eq!(search(&series(0.0, &[], &[]), 0.0, T, 1.0), None);
    assert_eq!(search(&series(1e-3, &[0.0], &[0.0]), 0.0, T, 1.0), None);
    // No frequency is needed without harmonics: p0 + p1 s has its zero at
    // -p0/p1.
    let mut line = series(-1.0, &[], &[]);
    line.w = f64::NAN;
    line.poly[1] = 4.0 / T;
    assert_transversal(search(&line, 0.0, T, 0.0), T / 4.0, true);
}

#[test]
fn the_scale_of_f_and_padding_change_nothing() {
    // 1e300 sin, 1e-300 sin and sin with a longer cosine slice of zeros
    // have the same first zero T/2 (the search scales by a power of two).
    for (amplitude, a) in [
        (1e300, vec![0.0]),
        (1e-300, vec![0.0]),
        (1.0, vec![0.0, 0.0, 0.0]),
    ] {
        let f = series(0.0, &a, &[amplitude]);
        assert_transversal(f.first_zero(0.1 * T, T, 0.0, Start::Clear), T / 2.0, false);
    }
}

#[test]
fn evaluation_agrees_with_term_by_term_sums_within_the_rounding_bound() {
    // The recurrence against cos(kθ), sin(kθ) of each harmonic (an
    // independent evaluation with its own rounding, up to 40 harmonics):
    // the difference stays within the bound eta_j, and is not far below it
    // everywhere (the comparison sees rounding).
    let worst = cases::rounding_ratio(0..200, 40, 20);
    assert!(worst.iter().all(|&r| r <= 1.0), "{worst:?}");
    assert!(worst.iter().all(|&r| r > 1e-3), "{worst:?}");
}

#[test]
fn the_derivatives_are_those_of_the_value() {
    // Central differences of f and f' (step 1e-6 T, error ~1e-12 of the
    // derivatives' scale) against f' and f''.
    for seed in 0..50 {
        let f = cases::random_function(&mut StdRng::seed_from_u64(seed), 15);
        let scale = f.harmonic_bounds();
        let mut osc = [0.0; 3];
        for o in f.osc.iter().flatten() {
            let b = o.derivative_bounds::<3>(&o.extend::<4>(&[o.y0, o.y1]), &[0.0; 4]);
            for (t, b) in osc.iter_mut().zip(b) {
                *t += b;
            }
        }
        let h = 1e-6 * T;
        for i in 1..10 {
            let s = 0.3 * T * i as f64;
            let (lo, mid, hi) = (f.eval(s - h), f.eval(s), f.eval(s + h));
            for j in 0..2 {
                let quotient = (hi[j] - lo[j]) / (2.0 * h);
                let size = scale[j + 1] + osc[j + 1] + f.poly[1].abs() + f.poly[2].abs() * 6.0 * T;
                assert!(
                    (quotient - mid[j + 1]).abs() <= 1e-6 * size,
                    "order {j} at {s:e}"
                );
            }
        }
    }
}

#[test]
fn the_work_is_that_of_the_stretch_walked() {
    // The first zero of sin is at T/2 whatever the end of the interval:
    // the walk stops there, so the work on (0, 1000 T] is about that on
    // (0, T], not a thousand times more.
    let f = series(0.0, &[0.3, 0.0, 0.02], &[1.0, 0.1, 0.0]);
    let mut near = Work::default();
    let mut far = Work::default();
    let a = f.first_zero_counting(0.01 * T, T, 0.0, Start::Clear, &mut near);
    let b = f.first_zero_counting(0.01 * T, 1000.0 * T, 0.0, Start::Clear, &mut far);
    assert_eq!(a.map(|e| e.s()), b.map(|e| e.s()));
    assert!(near.evaluations > 0);
    assert!(
        far.evaluations <= 2 * near.evaluations + 4,
        "{near:?} {far:?}"
    );
}

#[test]
fn most_pieces_are_decided_at_the_first_width() {
    // Random functions of up to 15 harmonics on three periods: bisections
    // are a minority of the pieces, and no cluster occurs.
    let mut work = Work::default();
    for seed in 0..100 {
        let f = cases::random_function(&mut StdRng::seed_from_u64(seed), 15);
        let mut s = 0.0;
        let mut start = Start::Clear;
        while let Some(e) = f.first_zero_counting(s, 3.0 * T, 0.0, start, &mut work) {
            (s, start) = (e.s(), Start::AfterEvent);
        }
    }
    assert!(work.subdivisions * 2 <= work.pieces, "{work:?}");
    assert_eq!(work.clusters, 0, "{work:?}");
}

#[test]
fn zeros_a_thousand_periods_on_are_found_to_the_phase_resolution() {
    // sin(w s) on (1000.2 T, 1001 T]: the zero 1000.5 T (closed form), to
    // the resolution of the phase there (~ε · 1000 T).
    let f = series(0.0, &[0.0], &[1.0]);
    let found = f.first_zero(1000.2 * T, 1001.0 * T, 0.0, Start::Clear);
    match found {
        Some(Crossing::Transversal { s, rising }) => {
            assert!((s - 1000.5 * T).abs() <= 1e-12 * T && !rising, "{s:e}");
        }
        other => panic!("{other:?}"),
    }
}
