//! Tests of `stickslip::numerics::trig_roots`: evaluation, derivatives and the
//! real-root finder of trigonometric polynomials.
//!
//! Sources of the expected values:
//! * planted roots: `p(θ) = C Π_j 2 sin((θ-θ_j)/2)`, multiplied out exactly in
//!   the trigonometric basis with the product-to-sum identity
//!   `2 sin((θ-x)/2) sin((θ-y)/2) = cos((x-y)/2) - cos(θ - (x+y)/2)`, so the
//!   roots are the `θ_j` by construction; tangencies from
//!   `2 sin²((θ-x)/2) = 1 - cos(θ-x)`; positive factors `2 + cos(kθ+φ) ≥ 1` add
//!   degree without roots;
//! * closed forms: `cos kθ = c` ⇔ `θ = ±acos(c)/k + 2πj/k`; `sin θ = 0` ⇔ `θ ∈ πℤ`;
//! * evaluation: the direct sum with one libm `cos`/`sin` per term; derivatives:
//!   `d/dθ (a cos kθ + b sin kθ) = k (b cos kθ - a sin kθ)` and central
//!   differences.
//!
//! Root tolerances follow first-order perturbation theory: the built polynomial
//! (rounded coefficients) has its root at `θ_j - p(θ_j)/p'(θ_j) + O(δ²)`, and
//! the contract of `roots()` puts the returned root within
//! `(η + |p'| ulp)/|p'|` of that, `η = eval_error_bound()`. Hence
//! `|θ̂ - θ_j| ≤ 2 (|p(θ_j)| + 2η)/|p'(θ_j)| + 4 ulp(2π)` (factor 2 for the
//! second-order terms), applied only when that is well below the spacing of the
//! roots. Double roots: the contract gives `~sqrt(2η/|p''|)`; cases where this
//! exceeds `1e-8` are discarded and the test asks for `1e-7`.

use approx::assert_relative_eq;
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};
use stickslip::numerics::TrigPoly;

/// Unoptimised builds (plain `cargo test`) run nalgebra's Schur form about 30
/// times slower: they get fewer cases; `cargo test --release` runs them all.
const OPTIMISED: bool = !cfg!(debug_assertions);

/// Proptest cases: all of them when optimised, 1/16 otherwise.
/// A fixed seed keeps CI reproducible (`PROPTEST_RNG_SEED` explores others).
fn cases(release: u32) -> ProptestConfig {
    ProptestConfig {
        cases: if OPTIMISED { release } else { release / 16 },
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x0057_17c4_5119),
        ..ProptestConfig::default()
    }
}

/// `2 sin((θ-x)/2) sin((θ-y)/2) = cos((x-y)/2) - cos(θ - (x+y)/2)`: roots `x`, `y`.
fn pair_factor(x: f64, y: f64) -> TrigPoly {
    let mu = 0.5 * (x + y);
    TrigPoly::new((0.5 * (x - y)).cos(), vec![-mu.cos()], vec![-mu.sin()])
}

/// `2 sin²((θ-x)/2) = 1 - cos(θ-x)`: a tangency (double root) at `x`.
fn double_factor(x: f64) -> TrigPoly {
    TrigPoly::new(1.0, vec![-x.cos()], vec![-x.sin()])
}

/// `2 + cos(kθ+φ) ≥ 1`: degree `k`, no roots.
fn positive_factor(k: usize, phi: f64) -> TrigPoly {
    let mut a = vec![0.0; k];
    let mut b = vec![0.0; k];
    a[k - 1] = phi.cos();
    b[k - 1] = -phi.sin();
    TrigPoly::new(2.0, a, b)
}

/// Direct sum with one libm call per term.
fn direct_eval(p: &TrigPoly, theta: f64) -> f64 {
    p.a.iter()
        .zip(&p.b)
        .enumerate()
        .fold(p.c0, |s, (i, (&a, &b))| {
            let k = (i + 1) as f64;
            s + a * (k * theta).cos() + b * (k * theta).sin()
        })
}

fn coeff_sum(p: &TrigPoly) -> f64 {
    p.a.iter().chain(&p.b).fold(p.c0.abs(), |s, x| s + x.abs())
}

/// Distance on the circle.
fn cyc(x: f64, y: f64) -> f64 {
    let d = (x - y).rem_euclid(TAU);
    d.min(TAU - d)
}

fn scaled(p: &TrigPoly, c: f64) -> TrigPoly {
    TrigPoly::new(
        c * p.c0,
        p.a.iter().map(|x| c * x).collect(),
        p.b.iter().map(|x| c * x).collect(),
    )
}

/// Sorted, in `[0, 2π)`, finite.
fn assert_well_formed(roots: &[f64]) {
    for &r in roots {
        assert!(
            r.is_finite() && (0.0..TAU).contains(&r),
            "root {r} not in [0, 2π)"
        );
    }
    for w in roots.windows(2) {
        assert!(w[0] < w[1], "roots not strictly increasing: {roots:?}");
    }
}

/// A planted test case.
#[derive(Debug)]
struct Planted {
    p: TrigPoly,
    simple: Vec<f64>,
    double: Vec<f64>,
}

/// Product of `factors`, even- and odd-indexed halves recursively: with the
/// factors sorted by angle every partial product has its roots spread around
/// the circle, which keeps the rounding of its coefficients small (a partial
/// product of clustered roots has large, cancelling coefficients).
fn interleaved_product(factors: &[TrigPoly]) -> TrigPoly {
    match factors.len() {
        0 => TrigPoly::constant(1.0),
        1 => factors[0].clone(),
        _ => {
            let even: Vec<TrigPoly> = factors.iter().step_by(2).cloned().collect();
            let odd: Vec<TrigPoly> = factors.iter().skip(1).step_by(2).cloned().collect();
            interleaved_product(&even).product(&interleaved_product(&odd))
        }
    }
}

/// `C Π (pair factors) Π (double factors) Π (positive factors)`, the pairs
/// matching root `i` with root `i + m/2` of the sorted list (no factor holds two
/// close roots unless `m = 2`), multiplied in interleaved order.
fn build(
    mut simple: Vec<f64>,
    double: Vec<f64>,
    positive: &[(usize, f64)],
    max_degree: usize,
    c: f64,
) -> Planted {
    assert!(simple.len().is_multiple_of(2));
    simple.sort_by(f64::total_cmp);
    let h = simple.len() / 2;
    let mut sites: Vec<(f64, TrigPoly)> = (0..h)
        .map(|i| (simple[i], pair_factor(simple[i], simple[i + h])))
        .chain(double.iter().map(|&x| (x, double_factor(x))))
        .collect();
    sites.sort_by(|x, y| x.0.total_cmp(&y.0));
    let factors: Vec<TrigPoly> = sites.into_iter().map(|(_, f)| f).collect();
    let mut p = scaled(&interleaved_product(&factors), c);
    for &(k, phi) in positive {
        if p.degree() + k <= max_degree {
            p = p.product(&positive_factor(k, phi));
        }
    }
    Planted { p, simple, double }
}

/// `count` points on the circle with gaps `≥ min_gap`, from gap weights.
fn spread(weights: &[f64], offset: f64, min_gap: f64) -> Vec<f64> {
    let total: f64 = weights.iter().sum();
    let free = TAU - weights.len() as f64 * min_gap;
    assert!(free > 0.0);
    let mut t = offset;
    let mut out = Vec::with_capacity(weights.len());
    for w in weights {
        out.push(t.rem_euclid(TAU));
        t += min_gap + w / total * free;
    }
    out
}

/// Checks a planted case against `roots()`; returns `Err` (a discarded case)
/// when the case is beyond the contract's resolution.
fn check_planted(case: &Planted) -> Result<(), TestCaseError> {
    let p = &case.p;
    let eta = p.eval_error_bound();
    let mut expected: Vec<(f64, bool)> = case
        .simple
        .iter()
        .map(|&x| (x, false))
        .chain(case.double.iter().map(|&x| (x, true)))
        .collect();
    expected.sort_by(|x, y| x.0.total_cmp(&y.0));
    let m = expected.len();
    let mut tol = vec![0.0; m];
    for (j, &(x, is_double)) in expected.iter().enumerate() {
        let gap = if m == 1 {
            TAU
        } else {
            cyc(x, expected[(j + 1) % m].0).min(cyc(x, expected[(j + m - 1) % m].0))
        };
        let w = p.eval_with_two_derivatives(x);
        let (px, dpx, d2px) = (w.value, w.first, w.second);
        if is_double {
            // the built polynomial must be tangent at rounding level and the
            // tangency not too flat (width of the band |p| ≤ η below 1e-6)
            prop_assume!((2.0 * eta / d2px.abs()).sqrt() <= 1e-6);
            prop_assume!(px.abs() <= 0.5 * eta);
            tol[j] = 1e-7;
        } else {
            tol[j] = 2.0 * (px.abs() + 2.0 * eta) / dpx.abs() + 4.0 * f64::EPSILON * TAU;
            // first-order theory needs the tolerance well below the spacing
            prop_assume!(tol[j] < 0.05 * gap);
            // the contract resolves a pair only if p between them is above η
            let next = expected[(j + 1) % m].0;
            if m > 1 && cyc(x, next) < 1e-2 {
                prop_assume!(p.eval(x + 0.5 * cyc(x, next)).abs() > 4.0 * eta);
            }
        }
    }
    let found = p.roots();
    assert_well_formed(&found);
    prop_assert_eq!(
        found.len(),
        m,
        "found {:?}, planted {:?}, p = {:?}",
        found,
        expected,
        p
    );
    // nearest found root of each planted root; one-to-one
    let mut used = vec![false; m];
    for (j, &(x, _)) in expected.iter().enumerate() {
        let (i, d) = found
            .iter()
            .enumerate()
            .map(|(i, &r)| (i, cyc(r, x)))
            .min_by(|u, v| u.1.total_cmp(&v.1))
            .expect("m > 0");
        prop_assert!(
            d <= tol[j],
            "planted {} found {} error {:e} > tol {:e}",
            x,
            found[i],
            d,
            tol[j]
        );
        prop_assert!(!used[i], "root {} matched twice", found[i]);
        used[i] = true;
    }
    Ok(())
}

// ---------------------------------------------------------------- evaluation

proptest! {
    #![proptest_config(cases(256))]

    #[test]
    fn eval_matches_direct_sum(
        c0 in -1.0f64..1.0,
        ab in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 0..=64),
        theta in -20.0f64..20.0,
    ) {
        let (a, b): (Vec<f64>, Vec<f64>) = ab.into_iter().unzip();
        let p = TrigPoly::new(c0, a, b);
        let scale = coeff_sum(&p);
        let direct = direct_eval(&p, theta);
        prop_assert!((p.eval(theta) - direct).abs() <= 1e-12 * scale);
        let v = p.eval_with_derivative(theta).value;
        let w = p.eval_with_two_derivatives(theta).value;
        prop_assert!((v - direct).abs() <= 1e-12 * scale);
        prop_assert!((w - direct).abs() <= 1e-12 * scale);
    }

    #[test]
    fn derivatives_match_closed_form(
        c0 in -1.0f64..1.0,
        ab in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 0..=64),
        theta in -20.0f64..20.0,
    ) {
        let (a, b): (Vec<f64>, Vec<f64>) = ab.into_iter().unzip();
        let p = TrigPoly::new(c0, a, b);
        let d = p.derivative();
        let dd = d.derivative();
        // closed form k (b cos kθ - a sin kθ), evaluated directly
        let direct_d = p.a.iter().zip(&p.b).enumerate().fold(0.0, |s, (i, (&a, &b))| {
            let k = (i + 1) as f64;
            s + k * (b * (k * theta).cos() - a * (k * theta).sin())
        });
        let scale1 = coeff_sum(&d).max(f64::MIN_POSITIVE);
        let scale2 = coeff_sum(&dd).max(f64::MIN_POSITIVE);
        let dp = p.eval_with_derivative(theta).derivative;
        let two = p.eval_with_two_derivatives(theta);
        let (dp2, d2p) = (two.first, two.second);
        prop_assert!((d.eval(theta) - direct_d).abs() <= 1e-12 * scale1);
        prop_assert!((dp - direct_d).abs() <= 1e-12 * scale1);
        prop_assert!((dp2 - direct_d).abs() <= 1e-12 * scale1);
        prop_assert!((d2p - direct_eval(&dd, theta)).abs() <= 1e-12 * scale2);
    }

    #[test]
    fn derivative_matches_central_difference(
        c0 in -1.0f64..1.0,
        ab in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 1..=16),
        theta in 0.0f64..TAU,
    ) {
        let (a, b): (Vec<f64>, Vec<f64>) = ab.into_iter().unzip();
        let p = TrigPoly::new(c0, a, b);
        let h = 1e-5;
        let fd = (p.eval(theta + h) - p.eval(theta - h)) / (2.0 * h);
        // truncation h²/6 max|p'''| ≤ h²/6 Σ k³(|a|+|b|); rounding ≤ 2·1e-15 Σ|coef| / (2h)
        let third = p.a.iter().zip(&p.b).enumerate().fold(0.0, |s, (i, (&a, &b))| {
            let k = (i + 1) as f64;
            s + k * k * k * (a.abs() + b.abs())
        });
        let tol = h * h / 6.0 * third + 1e-15 * coeff_sum(&p) / h;
        prop_assert!((p.eval_with_derivative(theta).derivative - fd).abs() <= tol);
    }

    #[test]
    fn product_evaluates_to_product_of_values(
        ab1 in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 0..=8),
        ab2 in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 0..=8),
        c1 in -1.0f64..1.0,
        c2 in -1.0f64..1.0,
        theta in 0.0f64..TAU,
    ) {
        let (a1, b1): (Vec<f64>, Vec<f64>) = ab1.into_iter().unzip();
        let (a2, b2): (Vec<f64>, Vec<f64>) = ab2.into_iter().unzip();
        let p = TrigPoly::new(c1, a1, b1);
        let q = TrigPoly::new(c2, a2, b2);
        let pq = p.product(&q);
        prop_assert_eq!(pq.a.len(), p.a.len() + q.a.len());
        let tol = 1e-13 * coeff_sum(&p) * coeff_sum(&q);
        prop_assert!((pq.eval(theta) - p.eval(theta) * q.eval(theta)).abs() <= tol);
    }
}

#[test]
fn derivative_of_sin_is_cos() {
    // d/dθ (3 + 2 sin θ - cos 2θ) = 2 cos θ + 2 sin 2θ
    let p = TrigPoly::new(3.0, vec![0.0, -1.0], vec![2.0, 0.0]);
    assert_eq!(
        p.derivative(),
        TrigPoly::new(0.0, vec![2.0, 0.0], vec![0.0, 2.0])
    );
    for i in 0..50 {
        let t = 0.13 * i as f64;
        let vd = p.eval_with_derivative(t);
        let (v, d) = (vd.value, vd.derivative);
        assert_relative_eq!(v, 3.0 + 2.0 * t.sin() - (2.0 * t).cos(), epsilon = 1e-14);
        assert_relative_eq!(d, 2.0 * t.cos() + 2.0 * (2.0 * t).sin(), epsilon = 1e-14);
    }
}

#[test]
fn degree_ignores_trailing_zero_pairs() {
    assert_eq!(TrigPoly::constant(1.0).degree(), 0);
    assert_eq!(TrigPoly::new(1.0, vec![0.0; 5], vec![0.0; 5]).degree(), 0);
    assert_eq!(
        TrigPoly::new(0.0, vec![1.0, 0.0, 0.0], vec![0.0, 2.0, 0.0]).degree(),
        2
    );
    assert_eq!(
        TrigPoly::new(0.0, vec![0.0, 0.0, 0.0], vec![0.0, 0.0, -1.0]).degree(),
        3
    );
}

#[test]
#[should_panic]
fn new_panics_on_length_mismatch() {
    let _ = TrigPoly::new(0.0, vec![1.0, 2.0], vec![1.0]);
}

// ---------------------------------------------------------------- closed forms

#[test]
fn cos_k_theta_minus_c() {
    // cos kθ = c  ⇔  θ = ±acos(c)/k + 2πj/k,  j = 0..k
    let ks: Vec<usize> = if OPTIMISED {
        (1..=30).collect()
    } else {
        vec![1, 2, 3, 4, 7, 8, 13, 30]
    };
    let cs: &[f64] = if OPTIMISED {
        &[0.0, -0.5, 0.9, 0.999]
    } else {
        &[0.0, -0.99, 0.999]
    };
    for &k in &ks {
        for &c in cs {
            let mut a = vec![0.0; k];
            a[k - 1] = 1.0;
            let p = TrigPoly::new(-c, a, vec![0.0; k]);
            let mut expected: Vec<f64> = (0..k)
                .flat_map(|j| {
                    let base = TAU * j as f64 / k as f64;
                    let d = f64::acos(c) / k as f64;
                    [(base + d).rem_euclid(TAU), (base - d).rem_euclid(TAU)]
                })
                .collect();
            expected.sort_by(f64::total_cmp);
            let found = p.roots();
            assert_well_formed(&found);
            assert_eq!(found.len(), 2 * k, "k={k} c={c}: {found:?}");
            // |p'| = k sqrt(1-c²) at every root; the expected values carry a few ulps of 2π
            let slope = k as f64 * (1.0 - c * c).sqrt();
            let tol = 4.0 * p.eval_error_bound() / slope + 8.0 * f64::EPSILON * TAU;
            for (f, e) in found.iter().zip(&expected) {
                assert!(
                    cyc(*f, *e) <= tol,
                    "k={k} c={c}: found {f}, expected {e}, tol {tol:e}"
                );
            }
        }
    }
}

#[test]
fn sin_theta_has_roots_zero_and_pi_once() {
    // sin θ = 0 ⇔ θ ∈ {0, π} in [0, 2π): exactly one root at the seam
    for c in [1.0, -1.0, 1e-300, 1e300] {
        let p = TrigPoly::new(0.0, vec![0.0], vec![c]);
        let r = p.roots();
        assert_well_formed(&r);
        assert_eq!(r.len(), 2, "{r:?}");
        assert!(cyc(r[0], 0.0) <= 1e-15, "{r:?}");
        assert!((r[1] - PI).abs() <= 1e-15, "{r:?}");
    }
}

#[test]
fn roots_next_to_the_seam() {
    // sin(θ - δ) = cos δ sin θ - sin δ cos θ: roots δ and π + δ (mod 2π)
    for &delta in &[1e-17, -1e-17, 1e-12, -1e-12, 1e-9, -1e-9, 1e-3, -1e-3] {
        let p = TrigPoly::new(0.0, vec![-f64::sin(delta)], vec![f64::cos(delta)]);
        let r = p.roots();
        assert_well_formed(&r);
        assert_eq!(r.len(), 2, "δ={delta}: {r:?}");
        let near_zero: Vec<f64> = r.iter().copied().filter(|&x| cyc(x, 0.0) < 0.1).collect();
        assert_eq!(near_zero.len(), 1, "δ={delta}: {r:?}");
        assert!(cyc(near_zero[0], delta) <= 1e-15, "δ={delta}: {r:?}");
        assert!(
            r.iter().any(|&x| cyc(x, PI + delta) <= 1e-15),
            "δ={delta}: {r:?}"
        );
    }
}

#[test]
fn tangency_at_the_seam_is_one_root() {
    // 1 - cos θ = 2 sin²(θ/2): a double root at 0, reported once
    let r = TrigPoly::new(1.0, vec![-1.0], vec![0.0]).roots();
    assert_eq!(r.len(), 1, "{r:?}");
    assert!(cyc(r[0], 0.0) <= 1e-7, "{r:?}");
    // 1 + cos θ = 2 cos²(θ/2): a double root at π
    let r = TrigPoly::new(1.0, vec![1.0], vec![0.0]).roots();
    assert_eq!(r.len(), 1, "{r:?}");
    assert!((r[0] - PI).abs() <= 1e-7, "{r:?}");
}

#[test]
fn constants_have_no_roots() {
    assert!(TrigPoly::constant(2.5).roots().is_empty());
    assert!(TrigPoly::constant(-1.0).roots().is_empty());
    // identically zero: documented as empty
    assert!(TrigPoly::constant(0.0).roots().is_empty());
    assert!(
        TrigPoly::new(0.0, vec![0.0; 4], vec![0.0; 4])
            .roots()
            .is_empty()
    );
    // trailing zero pairs do not matter
    assert!(
        TrigPoly::new(3.0, vec![0.0; 4], vec![0.0; 4])
            .roots()
            .is_empty()
    );
    // non-finite coefficients: documented as empty
    assert!(
        TrigPoly::new(f64::NAN, vec![1.0], vec![0.0])
            .roots()
            .is_empty()
    );
}

#[test]
fn no_real_roots_when_bounded_away_from_zero() {
    // 2 + cos(5θ + 1) ≥ 1
    assert!(positive_factor(5, 1.0).roots().is_empty());
    // near-tangency clearly above rounding: 1 - cos(θ-2) + 1e-12 > 0
    let mut p = double_factor(2.0);
    p.c0 += 1e-12;
    assert!(p.roots().is_empty());
    // ... and clearly below: two roots at 2 ± acos(1 - 1e-12)
    let mut p = double_factor(2.0);
    p.c0 -= 1e-12;
    let r = p.roots();
    assert_eq!(r.len(), 2, "{r:?}");
    let d = f64::acos(1.0 - 1e-12);
    // condition: |p'| = sin d ≈ 1.4e-6, so the roots are good to ~η/1.4e-6
    assert!(
        (r[0] - (2.0 - d)).abs() <= 1e-9 && (r[1] - (2.0 + d)).abs() <= 1e-9,
        "{r:?}"
    );
}

#[test]
fn negligible_leading_pair_is_trimmed() {
    // sin θ + 1e-17 cos 2θ: the degree-2 pair is below ε times the largest
    let p = TrigPoly::new(0.0, vec![0.0, 1e-17], vec![1.0, 0.0]);
    let r = p.roots();
    assert_eq!(r.len(), 2, "{r:?}");
    assert!(
        cyc(r[0], 0.0) <= 1e-15 && (r[1] - PI).abs() <= 1e-15,
        "{r:?}"
    );
}

#[test]
fn roots_at_level_shifts_the_constant() {
    // cos θ = 1/2 ⇔ θ = π/3, 5π/3
    let r = TrigPoly::new(0.0, vec![1.0], vec![0.0]).roots_at_level(0.5);
    assert_eq!(r.len(), 2);
    assert_relative_eq!(r[0], PI / 3.0, epsilon = 1e-14);
    assert_relative_eq!(r[1], 5.0 * PI / 3.0, epsilon = 1e-14);
}

#[test]
fn higher_multiplicities_are_reported_once() {
    // 8 sin³((θ-1)/2) sin((θ-2)/2): triple root at 1 (odd: sign change), simple at 2
    let p = pair_factor(1.0, 1.0).product(&pair_factor(1.0, 2.0));
    let r = p.roots();
    assert_eq!(r.len(), 2, "{r:?}");
    // a triple root is good to about ε^{1/3} ≈ 6e-6
    assert!(
        (r[0] - 1.0).abs() <= 1e-4 && (r[1] - 2.0).abs() <= 1e-14,
        "{r:?}"
    );
    // 16 sin⁴((θ-1)/2): quadruple root, ε^{1/4} ≈ 1e-4
    let r = pair_factor(1.0, 1.0)
        .product(&pair_factor(1.0, 1.0))
        .roots();
    assert_eq!(r.len(), 1, "{r:?}");
    assert!((r[0] - 1.0).abs() <= 1e-3, "{r:?}");
}

#[test]
fn scaling_does_not_change_roots() {
    let base = build(vec![0.3, 1.0, 2.5, 4.0], vec![5.5], &[(3, 0.7)], 30, 1.0).p;
    let r0 = base.roots();
    assert_eq!(r0.len(), 5);
    for c in [1e-300, 1e-100, -1.0, 1e100, 1e300] {
        let r = scaled(&base, c).roots();
        assert_eq!(r.len(), r0.len());
        for (x, y) in r.iter().zip(&r0) {
            assert!((x - y).abs() <= 1e-12, "c={c}: {r:?} vs {r0:?}");
        }
    }
}

#[test]
fn degree_64_with_128_planted_roots() {
    // the engine's usual maximum degree, all roots simple and spread
    let weights: Vec<f64> = (0..128)
        .map(|i| 1.0 + 0.1 * ((i * 37 % 11) as f64 / 11.0))
        .collect();
    let roots = spread(&weights, 0.1, 0.01);
    let case = build(roots, vec![], &[], 64, 1.0);
    assert_eq!(case.p.degree(), 64);
    check_planted(&case).expect("well-conditioned case");
}

// ---------------------------------------------------------------- planted roots

/// Gap weights, offset, positive factors, sign and scale.
fn common() -> impl Strategy<Value = (f64, Vec<(usize, f64)>, f64)> {
    (
        0.0..TAU,
        prop::collection::vec((1usize..=10, 0.0..TAU), 0..=4),
        (-3.0f64..3.0, any::<bool>())
            .prop_map(|(e, s)| if s { 10f64.powf(e) } else { -(10f64.powf(e)) }),
    )
}

proptest! {
    #![proptest_config(cases(256))]

    /// m = 2..=60 well separated simple roots, degree m/2..=30.
    #[test]
    fn planted_simple_roots(
        weights in prop::collection::vec(0.05f64..1.0, 1..=30).prop_map(|w| {
            let mut w2 = w.clone();
            w2.extend(w.iter().map(|x| 1.05 - x));
            w2
        }),
        (offset, positive, c) in common(),
    ) {
        let roots = spread(&weights, offset, 0.02);
        let case = build(roots, vec![], &positive, 30, c);
        prop_assert!(case.p.degree() <= 30);
        check_planted(&case)?;
    }

}

proptest! {
    #![proptest_config(cases(128))]

    /// As above, plus one close pair with spacing 1e-6..1e-2.
    #[test]
    fn planted_close_pair(
        weights in prop::collection::vec(0.05f64..1.0, 1..=29),
        (offset, positive, c) in common(),
        log_spacing in -6.0f64..-2.0,
        which in any::<prop::sample::Index>(),
    ) {
        // 2·len - 1 sites, one of which is split into a close pair
        let mut w = weights.clone();
        w.extend(weights.iter().skip(1).map(|x| 1.05 - x));
        let mut roots = spread(&w, offset, 0.05);
        let i = which.index(roots.len());
        roots.push(roots[i] + 10f64.powf(log_spacing));
        let case = build(roots, vec![], &positive, 30, c);
        check_planted(&case)?;
    }

    /// 1..=4 tangencies among simple roots, degree ≤ 30.
    #[test]
    fn planted_double_roots(
        weights in prop::collection::vec(0.05f64..1.0, 0..=12),
        double_weights in prop::collection::vec(0.05f64..1.0, 1..=4),
        (offset, positive, c) in common(),
    ) {
        // simple roots: an even number; all sites spread with gap ≥ 0.05
        let mut w = weights.clone();
        w.extend(weights.iter().map(|x| 1.05 - x));
        let n_simple = w.len();
        w.extend(double_weights.iter());
        let sites = spread(&w, offset, 0.05);
        // interleave roles so tangencies sit between simple roots
        let mut order: Vec<usize> = (0..sites.len()).collect();
        order.sort_by_key(|&i| (i * 7919) % sites.len());
        let simple: Vec<f64> = order[..n_simple].iter().map(|&i| sites[i]).collect();
        let double: Vec<f64> = order[n_simple..].iter().map(|&i| sites[i]).collect();
        let case = build(simple, double, &positive, 30, c);
        check_planted(&case)?;
    }
}

// ---------------------------------------------------------------- high degree

proptest! {
    #![proptest_config(cases(64))]

    /// m = 2..=512 well separated simple roots, degree up to 256.
    #[test]
    fn planted_simple_roots_up_to_degree_256(
        weights in prop::collection::vec(0.05f64..1.0, 1..=256).prop_map(|w| {
            let mut w2 = w.clone();
            w2.extend(w.iter().map(|x| 1.05 - x));
            w2
        }),
        (offset, positive, c) in common(),
    ) {
        let min_gap = 0.2 * TAU / weights.len() as f64;
        let roots = spread(&weights, offset, min_gap);
        let case = build(roots, vec![], &positive, 256, c);
        prop_assert!(case.p.degree() <= 256);
        check_planted(&case)?;
    }

    /// Tangencies and a close pair among simple roots, degree up to 256.
    #[test]
    fn planted_double_roots_and_close_pair_up_to_degree_256(
        weights in prop::collection::vec(0.05f64..1.0, 8..=120),
        double_weights in prop::collection::vec(0.05f64..1.0, 1..=6),
        (offset, positive, c) in common(),
        log_spacing in -6.0f64..-3.0,
    ) {
        let mut w = weights.clone();
        w.extend(weights.iter().map(|x| 1.05 - x));
        let n_simple = w.len();
        w.extend(double_weights.iter());
        let sites = spread(&w, offset, 0.2 * TAU / w.len() as f64);
        let mut order: Vec<usize> = (0..sites.len()).collect();
        order.sort_by_key(|&i| (i * 7919) % sites.len());
        let mut simple: Vec<f64> = order[..n_simple].iter().map(|&i| sites[i]).collect();
        let double: Vec<f64> = order[n_simple..].iter().map(|&i| sites[i]).collect();
        // split one simple root into a close pair (and drop another to keep
        // the count even)
        let x = simple.pop().expect("n_simple ≥ 16");
        simple[0] = x;
        simple.push(x + 10f64.powf(log_spacing));
        let case = build(simple, double, &positive, 256, c);
        check_planted(&case)?;
    }
}

#[test]
fn degree_256_with_512_planted_roots() {
    // the largest degree the engine is asked for, every root simple
    let weights: Vec<f64> = (0..512)
        .map(|i| 1.0 + 0.1 * ((i * 37 % 11) as f64 / 11.0))
        .collect();
    let roots = spread(&weights, 0.1, 0.002);
    let case = build(roots, vec![], &[], 256, 1.0);
    assert_eq!(case.p.degree(), 256);
    check_planted(&case).expect("well-conditioned case");
}

/// Random `c0, a_k, b_k` uniform in `[-1, 1]` (a fixed xorshift stream, so
/// that CI sees the same 10^4 polynomials).
fn random_poly(n: usize, state: &mut u64) -> TrigPoly {
    let mut next = || {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let c0 = next();
    let a = (0..n).map(|_| next()).collect();
    let b = (0..n).map(|_| next()).collect();
    TrigPoly::new(c0, a, b)
}

/// Every returned root is at rounding level (the contract's
/// `|p| ≤ η + |p'| ulp`).
fn assert_at_rounding_level(p: &TrigPoly, roots: &[f64]) {
    let eta = p.eval_error_bound();
    for &t in roots {
        let vd = p.eval_with_derivative(t);
        let (v, d) = (vd.value, vd.derivative);
        assert!(
            v.abs() <= eta + d.abs() * f64::EPSILON * t.max(1.0),
            "p({t}) = {v:e} > η = {eta:e}"
        );
    }
}

/// `Σ_k k^l (|a_k| + |b_k|)`: a bound on `|p^{(l)}|` over the circle.
fn derivative_bound(p: &TrigPoly, l: i32) -> f64 {
    p.a.iter()
        .zip(&p.b)
        .enumerate()
        .map(|(i, (a, b))| ((i + 1) as f64).powi(l) * (a.abs() + b.abs()))
        .sum()
}

/// The number of roots of `p` in `[lo, hi]`, counted by a method of its own
/// (global derivative bounds, not the finder's Taylor models): with `m`
/// the midpoint, `h` the half-width and `M_l` = [`derivative_bound`],
/// * `|p(m)| > |p'(m)| h + M_2 h²/2` (each less its rounding bound) proves
///   no root (Taylor's theorem with the Lagrange remainder);
/// * `|p'(m)| > |p''(m)| h + M_3 h²/2` proves `p` monotone, so the signs of
///   `p` at the ends give the count, 0 or 1;
/// * otherwise the interval is halved.
///
/// `None` if an end value is at rounding level or a piece narrower than
/// `1e-10` is still undecided (a root of multiplicity two or more, or a
/// root at a grid point: random coefficients give neither).
fn certified_count(p: &TrigPoly, lo: f64, hi: f64, bounds: &[f64; 4], depth: u32) -> Option<usize> {
    let [eta, m2, m3, eta1] = *bounds;
    let (m, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    let first = p.eval_with_derivative(m);
    let (v, d1) = (first.value, first.derivative);
    if v.abs() - eta > (d1.abs() + eta1) * h + 0.5 * m2 * h * h {
        return Some(0);
    }
    let d2 = p.eval_with_two_derivatives(m).second;
    if d1.abs() - eta1 > (d2.abs() + eta1 * 64.0) * h + 0.5 * m3 * h * h {
        let (a, b) = (p.eval(lo), p.eval(hi));
        if a.abs() <= eta || b.abs() <= eta {
            return None;
        }
        return Some(usize::from(a.signum() != b.signum()));
    }
    if depth == 0 || h < 1e-10 {
        return None;
    }
    let left = certified_count(p, lo, m, bounds, depth - 1)?;
    let right = certified_count(p, m, hi, bounds, depth - 1)?;
    Some(left + right)
}

#[test]
fn ten_thousand_random_polynomials_lose_no_root() {
    // Independent references: the companion-matrix eigenvalue finder
    // (`roots_by_eigenvalues`) for degrees up to 48, where it is affordable;
    // above, an exact count on each cell of a grid of 8 n cells by
    // `certified_count` (global derivative bounds): in every cell the finder
    // must report exactly as many roots as the count proves, so a missed,
    // spurious or doubled root anywhere fails.
    let total = if OPTIMISED { 10_000 } else { 400 };
    let mut state = 0x2545_F491_4F6C_DD1D_u64;
    let (mut compared, mut counted_cells, mut roots_seen) = (0, 0usize, 0usize);
    for i in 0..total {
        let low = i % 5 == 0;
        let n = if low {
            1 + (i / 5) % 48
        } else {
            49 + (i * 7) % 208
        };
        let p = random_poly(n, &mut state);
        let found = p.roots();
        assert_well_formed(&found);
        assert_at_rounding_level(&p, &found);
        if low {
            let old = p.roots_by_eigenvalues();
            assert_eq!(found.len(), old.len(), "n = {n}: {found:?} vs {old:?}");
            for (x, y) in found.iter().zip(&old) {
                let slope = p.eval_with_derivative(*x).derivative.abs();
                let tol = 8.0 * p.eval_error_bound() / slope + 1e-14;
                assert!(cyc(*x, *y) <= tol, "n = {n}: {x} vs {y}");
            }
            compared += 1;
            continue;
        }
        let eta = p.eval_error_bound();
        // rounding levels of p' and p'' as computed: the same form as η
        // with one and two more powers of k
        let eta1 = 16.0 * f64::EPSILON * derivative_bound(&p, 2);
        let bounds = [eta, derivative_bound(&p, 2), derivative_bound(&p, 3), eta1];
        let cells = 8 * n;
        for j in 0..cells {
            let (lo, hi) = (
                TAU * j as f64 / cells as f64,
                TAU * (j + 1) as f64 / cells as f64,
            );
            let count = certified_count(&p, lo, hi, &bounds, 40)
                .unwrap_or_else(|| panic!("n = {n}: cell [{lo}, {hi}] not decided"));
            let inside = found.iter().filter(|&&t| t >= lo && t < hi).count();
            assert_eq!(
                inside, count,
                "n = {n}: the finder has {inside} roots in [{lo}, {hi}], the count {count}"
            );
            counted_cells += 1;
            roots_seen += inside;
        }
    }
    assert!(compared >= total / 5);
    if OPTIMISED {
        assert!(counted_cells > 1_000_000, "{counted_cells}");
        assert!(roots_seen > 500_000, "{roots_seen}");
    }
}

/// `LevelRoots` shares the models' sums between levels: its roots must be
/// those of `roots_at_level`, to the bit (the sums are the same numbers, and
/// a level whose scale or degree differs is solved on its own), and its
/// envelope must bound `|p - level|` on every slice (checked against the
/// direct sum, with its rounding level, at 500 points per level).
#[test]
fn shared_levels_give_the_same_roots_and_a_true_envelope() {
    use rand::rngs::StdRng;
    use rand::{RngExt, SeedableRng};
    let mut rng = StdRng::seed_from_u64(0x001e_7e15);
    for case in 0..200 {
        let n = [3, 8, 17, 40, 64, 128][case % 6];
        let a: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let b: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let p = TrigPoly::new(rng.random_range(-0.5..0.5), a, b);
        let levels = p.levels();
        let mass = coeff_sum(&p);
        // levels inside the range, near its edges, and far outside (other scale)
        let spread = [0.0, 0.3, -0.7, 0.95, -1.0, 3.0, -40.0, 1e3];
        for s in spread {
            let level = s * mass * rng.random_range(0.5..1.0);
            let shared = levels.roots_and_envelope(level);
            assert_eq!(
                shared.roots,
                p.roots_at_level(level),
                "n = {n}, level {level}"
            );
            let count = shared.envelope.len();
            let eta = 4.0 * p.eval_error_bound() + 4.0 * f64::EPSILON * level.abs();
            for i in 0..500 {
                let theta = TAU * (i as f64 + 0.5) / 500.0;
                let slice = ((theta / TAU * count as f64) as usize).min(count - 1);
                let value = (direct_eval(&p, theta) - level).abs();
                assert!(
                    value <= shared.envelope[slice] + eta,
                    "n = {n}: |p - {level}| = {value} above its envelope {}",
                    shared.envelope[slice]
                );
            }
        }
    }
}
