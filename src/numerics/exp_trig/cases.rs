//! Random functions of the class, planted roots, chains of events and the
//! dense scan: the cases of the tests (`tests.rs`) and of
//! `examples/exp_trig_roots.rs`, which includes this file.

use std::f64::consts::TAU;

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

use super::{Crossing, DampedOscillator, ExpTrig, Start};

/// The period of the random functions (s): `w = 2π / PERIOD ~ 6.3e4`.
pub(super) const PERIOD: f64 = 1e-4;

/// A random function: `n <= n_max` harmonics with coefficients in
/// `[-1, 1] / k^d` (`d` in {0, 1, 2}), a quadratic of comparable size over
/// a few periods, and (four times in five) an oscillator in one of seven
/// regimes: undamped, under-damped, `σ/ω0 = 1 - 1e-9, 1, 1 + 1e-9`,
/// over-damped, `σ = 5 ω0`, with `ω0` from `0.3 w` to `30 w`; one time in
/// three that it has one, a second oscillator drawn the same way (a rod's
/// free oscillation and a slider's on a spring).
pub(super) fn random_function(rng: &mut StdRng, n_max: usize) -> ExpTrig {
    let w = TAU / PERIOD;
    let n = rng.random_range(0..=n_max);
    let decay = [0.0, 1.0, 2.0][rng.random_range(0..3usize)];
    let mut coefficient = |k: usize| rng.random_range(-1.0..1.0) / (k as f64).powf(decay);
    let a: Vec<f64> = (1..=n).map(&mut coefficient).collect();
    let b: Vec<f64> = (1..=n).map(&mut coefficient).collect();
    let poly = [
        rng.random_range(-0.5..0.5),
        rng.random_range(-1.0..1.0) * 0.3 * w,
        rng.random_range(-1.0..1.0) * 0.003 * w * w,
    ];
    let osc = (rng.random_range(0.0..1.0) < 0.8).then(|| random_oscillator(rng, w));
    let second = (osc.is_some() && rng.random_range(0.0..1.0) < 1.0 / 3.0)
        .then(|| random_oscillator(rng, w));
    ExpTrig {
        poly,
        w,
        phi: rng.random_range(0.0..PERIOD),
        a,
        b,
        osc: [osc, second],
    }
}

/// An oscillator in one of the seven regimes of [`random_function`].
fn random_oscillator(rng: &mut StdRng, w: f64) -> DampedOscillator {
    let omega0 = w * 10f64.powf(rng.random_range(-0.5..1.5));
    let ratio = match rng.random_range(0..7u32) {
        0 => 0.0,
        1 => rng.random_range(0.0..1.0),
        2 => 1.0 - 1e-9,
        3 => 1.0,
        4 => 1.0 + 1e-9,
        5 => rng.random_range(1.0..5.0),
        _ => 5.0,
    };
    DampedOscillator {
        sigma: ratio * omega0,
        omega0,
        y0: rng.random_range(-1.0..1.0),
        y1: rng.random_range(-1.0..1.0) * omega0,
    }
}

/// The events of `f` on `(s_a, s_b]` one after the other: the first from
/// `s_a` ([`Start::Clear`]), each next from the last
/// ([`Start::AfterEvent`]), at most `limit`.
pub(super) fn events(f: &ExpTrig, s_a: f64, s_b: f64, tol: f64, limit: usize) -> Vec<Crossing> {
    let mut out = Vec::new();
    let (mut from, mut start) = (s_a, Start::Clear);
    while out.len() < limit {
        let Some(event) = f.first_zero(from, s_b, tol, start) else {
            break;
        };
        out.push(event);
        (from, start) = (event.s(), Start::AfterEvent);
        if from >= s_b {
            break;
        }
    }
    out
}

/// Sizes of `f^(j)`, `j <= 3`, over `[0, s]`: sums of the bounds of the
/// parts (the scale against which a planted root is well conditioned).
fn sizes(f: &ExpTrig, s: f64) -> [f64; 4] {
    let m = f.harmonic_bounds();
    let [p0, p1, p2] = f.poly.map(f64::abs);
    let mut osc = [0.0; 4];
    for o in f.osc.iter().flatten() {
        let b = o.derivative_bounds::<4>(&o.extend::<5>(&[o.y0, o.y1]), &[0.0; 5]);
        for (t, b) in osc.iter_mut().zip(b) {
            *t += b;
        }
    }
    [
        p0 + s * (p1 + s * p2) + m[0] + osc[0],
        p1 + 2.0 * p2 * s + m[1] + osc[1],
        2.0 * p2 + m[2] + osc[2],
        m[3] + osc[3],
    ]
}

/// What is planted at `r`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Plant {
    /// `p0 -= f(r)`: a simple root (where `|f'(r)|` is at least 5 % of its
    /// scale).
    Simple,
    /// Also `p1 -= f'(r)`, `p0 += f'(r) r`: a double root (where `|f''(r)|`
    /// is at least 5 % of its scale).
    Double,
    /// Also `p2 -= f''(r)/2` (and `p1`, `p0` to match): a triple root, a
    /// sign change (where `|f'''(r)|` is at least 5 % of its scale).
    Triple,
}

/// A random function with a root of the kind planted at `r` in
/// `[0.05, 3] PERIOD`, or `None` where the draw is ill-conditioned.
pub(super) fn planted(seed: u64, n_max: usize, kind: Plant) -> Option<(ExpTrig, f64)> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut f = random_function(&mut rng, n_max);
    let r = rng.random_range(0.05..3.0) * PERIOD;
    let [_, dv, d2v, d3v] = f.eval4(r);
    let size = sizes(&f, r);
    let conditioned = match kind {
        Plant::Simple => dv.abs() > 0.05 * size[1],
        Plant::Double => d2v.abs() > 0.05 * size[2],
        Plant::Triple => d3v.abs() > 0.05 * size[3],
    };
    // Twice: the second pass removes the rounding of the first (which is
    // that of the original, larger coefficients).
    for _ in 0..2 {
        let [v, dv, d2v] = f.eval(r);
        // subtract v + dv (s - r) + d2v/2 (s - r)^2, as far as planted
        let (v, dv, d2v) = match kind {
            Plant::Simple => (v, 0.0, 0.0),
            Plant::Double => (v, dv, 0.0),
            Plant::Triple => (v, dv, d2v),
        };
        f.poly[0] -= v - dv * r + 0.5 * d2v * r * r;
        f.poly[1] -= dv - d2v * r;
        f.poly[2] -= 0.5 * d2v;
    }
    conditioned.then_some((f, r))
}

/// A tolerance `level` times the size of `f` over `[0, s]` (the
/// engine's `tol_v` is `1e-13` of the largest rod velocity).
pub(super) fn tolerance(f: &ExpTrig, s: f64, level: f64) -> f64 {
    level * sizes(f, s)[0]
}

/// The outcome of a search for a planted root.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PlantedOutcome {
    /// An event of the planted kind within `1e-12 PERIOD` of `r`.
    pub found: bool,
    /// An event within that distance, but of the other kind.
    pub other_kind: bool,
    /// No event near `r`, but `r` lies in the band stretch of the last
    /// event before it: `|f| <= tol` at 1000 samples from that event to
    /// `r`, so the planted root belongs to that event (the contract).
    pub covered: bool,
    /// Events before `r` that are not genuine ([`genuine`]).
    pub spurious: usize,
    /// Events before `r` in all.
    pub before: usize,
    /// `|s - r| / PERIOD` of the closest event.
    pub error: f64,
}

/// Walks the events of `f` on `(0, r + PERIOD/4]` with the tolerance
/// `tol` and compares them with the root planted at `r`: the planted event
/// is looked for within `1e-12 PERIOD` of `r` (simple and double roots),
/// or `1e-4 PERIOD` (a triple root, which rounding spreads over
/// `~ε^{1/3}`, and which is either kind).
pub(super) fn search_planted(f: &ExpTrig, r: f64, kind: Plant, tol: f64) -> PlantedOutcome {
    let s_b = r + 0.25 * PERIOD;
    let found = events(f, 0.0, s_b, tol, 1000);
    let near_r = if kind == Plant::Triple { 1e-4 } else { 1e-12 } * PERIOD;
    let closest = found
        .iter()
        .min_by(|x, y| (x.s() - r).abs().total_cmp(&(y.s() - r).abs()));
    let error = closest.map_or(f64::INFINITY, |e| (e.s() - r).abs() / PERIOD);
    let near = closest.filter(|e| (e.s() - r).abs() <= near_r);
    let right_kind = |e: &Crossing| match kind {
        Plant::Simple => matches!(e, Crossing::Transversal { .. }),
        Plant::Double => matches!(e, Crossing::Tangency { .. }),
        Plant::Triple => true,
    };
    let earlier: Vec<&Crossing> = found.iter().filter(|e| e.s() < r - near_r).collect();
    let band = tol.max(4.0 * f.eval_error_bound(s_b)[0]);
    let covered = near.is_none()
        && earlier.last().is_some_and(|e| {
            (0..=1000).all(|i| {
                let s = e.s() + (r - e.s()) * (i as f64 / 1000.0);
                f.eval(s)[0].abs() <= band
            })
        });
    PlantedOutcome {
        found: near.is_some_and(right_kind),
        other_kind: near.is_some_and(|e| !right_kind(e)),
        covered,
        spurious: earlier.iter().filter(|e| !genuine(f, e, s_b, tol)).count(),
        before: earlier.len(),
        error,
    }
}

/// Whether an event found with the tolerance `tol` is one: `|f|` at the
/// rounding level there (transversal) or within the band (tangency), and
/// `f'` of the reported sign (transversal) or at its own rounding level
/// (tangency), allowing for the time resolution.
pub(super) fn genuine(f: &ExpTrig, e: &Crossing, s_max: f64, tol: f64) -> bool {
    let [eta0, eta1, _] = f.eval_error_bound(s_max);
    let [v, dv, d2v] = f.eval(e.s());
    let resolution = 8.0 * f64::EPSILON * (f.phi.abs() + e.s());
    match *e {
        Crossing::Transversal { rising, .. } => {
            v.abs() <= 8.0 * eta0 + dv.abs() * resolution
                && (dv.abs() <= eta1 || (dv > 0.0) == rising)
        }
        Crossing::Tangency { .. } => {
            v.abs() <= tol.max(4.0 * eta0) + eta0 && dv.abs() <= 4.0 * eta1 + d2v.abs() * resolution
        }
    }
}

/// The outcome of [`dense_scan`].
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Dense {
    /// The samples cannot decide: a sample at the rounding level, or sign
    /// changes closer than four samples.
    Skipped,
    /// The transversal zeros found are the dense scan's sign changes.
    Agrees {
        /// Sign changes.
        changes: usize,
    },
    /// They are not.
    Disagrees(String),
}

/// Compares the chain of events of `f` on `(0, length]` (`tol = 0`) with
/// the sign changes of `samples + 1` equally spaced values: every sample
/// interval must hold an odd number of transversal zeros where the
/// samples change sign and an even number (normally none) elsewhere; a
/// pair in one interval must have `f` of the other sign between them; and
/// any tangency must be genuine.
pub(super) fn dense_scan(f: &ExpTrig, length: f64, samples: usize) -> Dense {
    let eta0 = f.eval_error_bound(length)[0];
    let step = length / samples as f64;
    let values: Vec<f64> = (0..=samples).map(|i| f.eval(i as f64 * step)[0]).collect();
    if values.iter().any(|v| v.abs() <= 1e3 * eta0) {
        return Dense::Skipped;
    }
    let changes: Vec<usize> = (0..samples)
        .filter(|&i| (values[i] > 0.0) != (values[i + 1] > 0.0))
        .collect();
    if changes.windows(2).any(|w| w[1] - w[0] < 4) {
        return Dense::Skipped;
    }
    let found = events(f, 0.0, length, 0.0, 10 * samples);
    let mut per_interval = vec![Vec::new(); samples];
    for e in &found {
        match *e {
            Crossing::Transversal { s, .. } => {
                let i = ((s / step).floor() as usize).min(samples - 1);
                per_interval[i].push(s);
            }
            Crossing::Tangency { .. } => {
                if !genuine(f, e, length, 0.0) {
                    return Dense::Disagrees(format!("a tangency that is none: {e:?}"));
                }
            }
        }
    }
    for (i, zeros) in per_interval.iter().enumerate() {
        let change = changes.binary_search(&i).is_ok();
        if (zeros.len() % 2 == 1) != change {
            return Dense::Disagrees(format!(
                "interval {i} of {samples}: {} zeros found, sign change: {change}",
                zeros.len()
            ));
        }
        for pair in zeros.windows(2) {
            let between = f.eval(0.5 * (pair[0] + pair[1]))[0];
            if (between > 0.0) == (values[i] > 0.0) && between.abs() > eta0 {
                return Dense::Disagrees(format!("two zeros {pair:?} without a sign between"));
            }
        }
    }
    Dense::Agrees {
        changes: changes.len(),
    }
}

/// `f`, `f'`, `f''` summed term by term, each harmonic from its own
/// `sin_cos(kθ)` (an evaluation independent of the recurrence).
pub(super) fn term_by_term(f: &ExpTrig, s: f64) -> [f64; 3] {
    let theta = f.w * (f.phi + s);
    let [p0, p1, p2] = f.poly;
    let mut sum = [p0 + p1 * s + p2 * s * s, p1 + 2.0 * p2 * s, 2.0 * p2];
    for (k, (&a, &b)) in f.a.iter().zip(&f.b).enumerate() {
        let q = (k + 1) as f64 * f.w;
        let (sn, cs) = ((k + 1) as f64 * theta).sin_cos();
        sum[0] += a * cs + b * sn;
        sum[1] += q * (b * cs - a * sn);
        sum[2] -= q * q * (a * cs + b * sn);
    }
    for o in f.osc.iter().flatten() {
        for (t, y) in sum.iter_mut().zip(o.eval(s)) {
            *t += y;
        }
    }
    sum
}

/// The largest `|computed - term by term| / η_j`, `j <= 2`, over random
/// functions of up to `n_max` harmonics (one per seed), at `points` times
/// in `[0, 3 PERIOD]` each.
pub(super) fn rounding_ratio(seeds: std::ops::Range<u64>, n_max: usize, points: usize) -> [f64; 3] {
    let mut worst = [0.0_f64; 3];
    for seed in seeds {
        let f = random_function(&mut StdRng::seed_from_u64(seed), n_max);
        let s_max = 3.0 * PERIOD;
        let eta = f.eval_error_bound(s_max);
        for i in 0..points {
            let s = s_max * (i as f64 + 0.37) / points as f64;
            let (computed, reference) = (f.eval(s), term_by_term(&f, s));
            for j in 0..3 {
                worst[j] = worst[j].max((computed[j] - reference[j]).abs() / eta[j]);
            }
        }
    }
    worst
}
