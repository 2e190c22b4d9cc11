//! Real roots of real trigonometric polynomials (docs/model.md, section 8).
//!
//! A real trigonometric polynomial of degree `n` is
//!
//! ```text
//! p(θ) = c0 + Σ_{k=1}^{n} ( a_k cos kθ + b_k sin kθ ),   θ ∈ [0, 2π).
//! ```
//!
//! [`TrigPoly::roots`] finds all its real roots by certified subdivision in
//! `O(n^2)` operations, with a proof (below) that none is missed.
//!
//! # Method
//!
//! 0. *Scaling.* The coefficients are scaled by a power of two (exact) to a
//!    largest one in `[1, 2)`. Leading pairs with `hypot(a_k, b_k) ≤ ε · max`
//!    are left out of the models below (degree `n` from here on); their sum
//!    and its derivatives are added to the model errors, and every full
//!    evaluation keeps them.
//! 1. *Taylor models.* The circle is covered by `N = ⌈π n / 2⌉` (at least 3)
//!    intervals `[m - r, m + r]`, `m = (i + 1/2) 2π/N`, `r = (π/N)(1 + 10^-9)`
//!    (the overlap covers the rounding of `m`), so `n r ≤ 2`. On each, with
//!    `θ = m + r s`, `s ∈ [-1, 1]` and `W_k = (a_k - i b_k) e^{ikm}`,
//!
//!    ```text
//!    p(m + r s) = Σ_{j<24} g_j s^j + R,   g_j = Σ_k (k r)^j / j! · Re(i^j W_k)  (+ c0 for j = 0),
//!    ```
//!
//!    one `sin_cos` and the rotation recurrence for all `e^{ikm}`, `O(24 n)`.
//!    The Lagrange remainder is `|R| ≤ Σ_k |W_k| (k r)^24 / 24! ≤ 3e-17 Σ|W_k|`,
//!    and similarly for the `s`-derivatives. Rounding (R1-R3): the recurrence
//!    gives `e^{ikm}` to `≤ 5 k ε` (one `sin_cos` to 1 ulp, then `k` complex
//!    products of `2√2 ε` each), so `Re(i^j W_k)` is off by
//!    `≤ (5k + 3) ε (|a_k| + |b_k|)`; the factors `(kr)^j/j!` carry `≤ 3·24 ε`
//!    relative error and the sums over `k` `≤ n ε` of their absolute terms.
//!    Summed with the weights `Σ_j (kr)^j/j!`, `Σ_j j (kr)^j/j!`,
//!    `Σ_j j(j-1) (kr)^j/j!` this gives `δ_0, δ_1, δ_2`: bounds on
//!    `|p - q|`, `|d/ds p - q'|`, `|d²/ds² p - q''|` on `[-1, 1]` for the
//!    computed `q(s) = Σ g_j s^j`, all multiplied by a safety factor 2.
//! 2. *Subdivision.* A piece `s ∈ [c - ρ, c + ρ]` (`ρ` a power of two) is
//!    rewritten as `u ↦ q(c + ρ u) = Σ e_i u^i`, `u ∈ [-1, 1]`, by a Horner
//!    Taylor shift (R4: each `e_i` off by `≤ γ ρ^i Σ_j C(j,i) |c|^{j-i} |g_j|`,
//!    `γ = 2 (2·24 + 4) ε`, whence `Σ_i i^l err_i ≤ γ ρ^l Σ_j j^l |g_j|`). With
//!    `U_0 = δ_0 + Σ err_i`, `U_1 = ρ δ_1 + Σ i err_i`,
//!    `U_2 = ρ² δ_2 + Σ i(i-1) err_i`, each plus the rounding of its own sum:
//!    * (E) `|e_0| - Σ_{i≥1} |e_i| > U_0` ⇒ `|p| > 0` on the piece: **excluded**;
//!    * (M) `|e_1| - Σ_{i≥2} i |e_i| > U_1` ⇒ `p' ≠ 0`: **monotone**;
//!    * (C) `2|e_2| - Σ_{i≥3} i(i-1) |e_i| = U_2 + μ_u`, `μ_u > 0` ⇒
//!      `|p''| ≥ μ_u / (rρ)²`: **convex** (or concave);
//!    * otherwise the piece is bisected, down to a half-width of `6e-8` rad,
//!      below which it is **unresolved**.
//!
//!    Each lower bound is the triangle inequality on the Taylor expansion of
//!    the model at `c`, with the model and rounding errors subtracted, so it
//!    holds for `p` itself.
//! 3. *Resolution* (full `O(n)` evaluations, `η` = [`TrigPoly::eval_error_bound`]
//!    taken as the bound on the error of a computed `p(θ)`). The sign of `p`
//!    at a piece end is that of `q` if `|q| > U_0` there, else that of the
//!    full `p(θ)` if `|p(θ)| > η`, else "zero" (rounding level).
//!    * Monotone piece: opposite signs at the ends ⇒ exactly one root, found
//!      by Newton from the model root, safeguarded by bisection in the bracket
//!      (rtsafe); equal nonzero signs ⇒ no root; an end at rounding level ⇒
//!      Newton from that end, kept if it reaches `|p| ≤ η + |p'| ulp`.
//!    * Convex piece: if `p'` has one certified sign, as monotone. Else the
//!      critical point `θ_c` (model root of `q'`, then Newton on `p'` inside the
//!      piece). `|p(θ_c)| ≤ η` ⇒ a tangency, reported once at `θ_c`. If
//!      `σ p(θ_c) > η + (|p'(θ_c)| + η')²/(2μ)` (`σ` the sign of `p''`, `μ` its
//!      certified lower bound, `η'` the rounding level of `p'`), then by
//!      convexity `σ p ≥ σ p(θ_c) - p'(θ_c)²/(2μ) > 0` on the piece: no root.
//!      Otherwise `p(θ_c)` is clearly nonzero and each side of `θ_c`, on which
//!      `p` is monotone, is resolved as a monotone piece with `θ_c` as one end.
//!    * Unresolved pieces (a root of multiplicity ≥ 3, or `p`, `p'`, `p''` all
//!      within the model error) are joined into clusters, each sampled at 9
//!      points: a bracketed solve per certified sign change, and Newton from
//!      the sample of smallest `|p|`, kept if it reaches rounding level.
//! 4. *Merge.* Adjacent candidates `θ_a < θ_b` (cyclically, across the
//!    `0/2π` seam) are one root when `p` at their midpoint is at rounding
//!    level; a genuine pair of simple roots has `p` clearly nonzero between
//!    them and is kept. A merged group, or a root with `p' ≈ 0`, is reported
//!    once: at the critical point of `p` if that lies within the group and
//!    `|p|` is at rounding level there, else at the member of smallest `|p|`.
//!    The values are wrapped into `[0, 2π)` and sorted. Two shortcuts give
//!    the same values without most of these evaluations: a midpoint where
//!    the top-level model of step 1 proves `|p|` above the rounding level
//!    (model value less its error bound, which adds the Horner pass and the
//!    rounding of the model variable) is not evaluated, and a lone root
//!    whose solve left `|p'| > 4 sqrt(2η Σ k²(|a_k| + |b_k|))` is no
//!    tangency and needs no second-derivative evaluation.
//!
//! # No root is missed
//!
//! Let `θ*` be a root of `p` (exact coefficients). The top-level intervals
//! cover the circle, and every piece is either bisected into two halves that
//! cover it or classified, so `θ*` lies in a classified piece `J`:
//! * `J` excluded: impossible, (E) proves `|p| > 0` on `J` (the bounds
//!   include the remainder, the left-out terms and every rounding, 1-2).
//! * `J` monotone: `θ*` is its only root. Signs at the ends are true signs
//!   (`|q| > U_0` or `|p̂| > η`), so if both are nonzero they are opposite and
//!   the bracketed solve, which keeps a sign-change bracket, converges to
//!   `θ*` (to `~η/|p'|`). If an end is at rounding level, `|p| ≤ 2η` there and
//!   `θ*` is within `2η / min_J |p'|` of it: Newton from that end reaches it.
//! * `J` convex: `p'` is monotone, so `p` has at most two roots, one on each
//!   side of the extremum `t*`. If `|p(θ_c)| ≤ η`, both lie within the band
//!   `|p| ≤ 2η` around `θ_c` and are reported as one tangency (the contract).
//!   The no-root branch is excluded by the convexity bound. Otherwise
//!   `σ p(θ_c) ≤ -η`, or it is within `(|p'(θ_c)| + η')²/(2μ)` of the
//!   rounding level (after Newton on `p'`, `|p'(θ_c)| ~ η'` and this margin
//!   is `~1e-28`: a near-tangency at rounding level, decided by rounding as
//!   the contract says); each side `[end, θ_c]` is then monotone except for
//!   the stretch between `θ_c` and `t*`, where `σ p` stays at most
//!   `σ p(θ_c) < 0`, so the side's root is found as in the monotone case.
//! * `J` unresolved: `θ*` lies in a cluster of width `~1e-7` where `p`, `p'`
//!   and `p''` are all within the model error: a root of multiplicity ≥ 3,
//!   which is reported once (a sign change between samples, or the sample of
//!   smallest `|p|` polished to rounding level), to about `ε^{1/m}`.
//!
//! The merge only joins candidates with `p` at rounding level between them,
//! so it never loses a root that the contract keeps apart. The only
//! assumption beyond the derived bounds is that `η` bounds the error of a
//! computed `p(θ)` (it is 4 times the largest error measured for `n <= 64`
//! and 3 times that measured at `n = 256`, see
//! [`TrigPoly::eval_error_bound`]); a proven a-priori bound of the
//! recurrence, about `Σ (5k + 3) ε (|a_k| + |b_k|)`, would remove it.
//!
//! Cost: `O(24 n)` per top-level interval, `O(n^2)` in all, plus `O(24²)` per
//! piece and a few `O(n)` evaluations per root: about 0.2 ms for `n = 64`
//! and 2 ms for `n = 256` (`cargo run --release --example roots_bench`),
//! against 0.03 s and 2 s for the companion-matrix finder kept as
//! [`TrigPoly::roots_by_eigenvalues`]; a further level of the same
//! polynomial ([`LevelRoots`]) about 0.1 ms and 0.8 ms. [`TrigPoly::eval`] and its derivative
//! variants are `O(n)` with one `sin_cos` and no allocation.

use super::power_of_two::ldexp;
use std::f64::consts::TAU;
use std::sync::{Arc, OnceLock};

use nalgebra::Complex;

mod eigen;
mod isolate;
mod merge;

use isolate::Candidate;

/// Machine epsilon.
const EPS: f64 = f64::EPSILON;
/// Safety factor of the rounding level `η` over the measured evaluation error.
const NOISE_FACTOR: f64 = 16.0;
/// Largest distance of a merged root from its group (a root of multiplicity
/// `m` spreads over `~ε^{1/m}`: this admits `m ≤ 8`).
const MAX_ACCEPT: f64 = 1.0e-2;
/// Newton iterations (linear convergence at double roots needs more than a few).
const NEWTON_ITERS: usize = 30;
/// Largest single Newton step on `p`, radians.
const NEWTON_MAX_STEP: f64 = 1.0e-3;

/// `p(θ)` and its derivative ([`TrigPoly::eval_with_derivative`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WithDerivative {
    /// `p(θ)`.
    pub value: f64,
    /// `p'(θ)`.
    pub derivative: f64,
}

/// `p(θ)` and its first two derivatives
/// ([`TrigPoly::eval_with_two_derivatives`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WithTwoDerivatives {
    /// `p(θ)`.
    pub value: f64,
    /// `p'(θ)`.
    pub first: f64,
    /// `p''(θ)`.
    pub second: f64,
}

/// The roots of a polynomial and an envelope of its magnitude
/// ([`TrigPoly::roots_and_envelope`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RootsAndEnvelope {
    /// The roots in `[0, 2π)`, ascending ([`TrigPoly::roots`]).
    pub roots: Vec<f64>,
    /// Bounds on `|p|` over `N` equal intervals of `[0, 2π)`: entry `i`
    /// bounds `|p(θ)|` for `θ` in `[i 2π/N, (i + 1) 2π/N]`.
    pub envelope: Vec<f64>,
}

/// A real trigonometric polynomial
/// `p(θ) = c0 + Σ_{k=1}^{n} (a[k-1] cos kθ + b[k-1] sin kθ)`.
#[derive(Debug, Clone, PartialEq)]
pub struct TrigPoly {
    /// Constant term.
    pub c0: f64,
    /// Cosine coefficients, `a[k-1]` multiplies `cos kθ`.
    pub a: Vec<f64>,
    /// Sine coefficients, `b[k-1]` multiplies `sin kθ`.
    pub b: Vec<f64>,
}

impl TrigPoly {
    /// Builds `c0 + Σ (a[k-1] cos kθ + b[k-1] sin kθ)`.
    ///
    /// # Panics
    ///
    /// Panics if `a.len() != b.len()` (pad the shorter one with zeros).
    pub fn new(c0: f64, a: Vec<f64>, b: Vec<f64>) -> Self {
        assert_eq!(
            a.len(),
            b.len(),
            "TrigPoly::new: a and b must have the same length"
        );
        Self { c0, a, b }
    }

    /// The constant polynomial `c0`.
    pub fn constant(c0: f64) -> Self {
        Self::new(c0, Vec::new(), Vec::new())
    }

    /// Degree: the largest `k` with `(a_k, b_k) != (0, 0)`; trailing zero pairs
    /// are ignored. A constant has degree 0.
    pub fn degree(&self) -> usize {
        self.a
            .iter()
            .zip(&self.b)
            .rposition(|(&a, &b)| a != 0.0 || b != 0.0)
            .map_or(0, |i| i + 1)
    }

    /// `p(θ)`: one `sin_cos`, then `cos kθ, sin kθ` by the angle-addition
    /// recurrence. No allocation.
    #[inline]
    pub fn eval(&self, theta: f64) -> f64 {
        let (s1, c1) = theta.sin_cos();
        let (mut ck, mut sk) = (1.0, 0.0);
        let mut p = self.c0;
        for (&ak, &bk) in self.a.iter().zip(&self.b) {
            let c = ck * c1 - sk * s1;
            sk = sk * c1 + ck * s1;
            ck = c;
            p += ak * ck + bk * sk;
        }
        p
    }

    /// `p(θ)` and `p'(θ)`, one `sin_cos`, no allocation.
    #[inline]
    pub fn eval_with_derivative(&self, theta: f64) -> WithDerivative {
        let (s1, c1) = theta.sin_cos();
        let (mut ck, mut sk) = (1.0, 0.0);
        let mut p = self.c0;
        let mut dp = 0.0;
        let mut k = 0.0;
        for (&ak, &bk) in self.a.iter().zip(&self.b) {
            let c = ck * c1 - sk * s1;
            sk = sk * c1 + ck * s1;
            ck = c;
            k += 1.0;
            p += ak * ck + bk * sk;
            dp += k * (bk * ck - ak * sk);
        }
        WithDerivative {
            value: p,
            derivative: dp,
        }
    }

    /// `p(θ)`, `p'(θ)` and `p''(θ)`, one `sin_cos`, no allocation.
    #[inline]
    pub fn eval_with_two_derivatives(&self, theta: f64) -> WithTwoDerivatives {
        let (s1, c1) = theta.sin_cos();
        let (mut ck, mut sk) = (1.0, 0.0);
        let mut p = self.c0;
        let mut dp = 0.0;
        let mut d2p = 0.0;
        let mut k = 0.0;
        for (&ak, &bk) in self.a.iter().zip(&self.b) {
            let c = ck * c1 - sk * s1;
            sk = sk * c1 + ck * s1;
            ck = c;
            k += 1.0;
            let even = ak * ck + bk * sk;
            p += even;
            dp += k * (bk * ck - ak * sk);
            d2p -= k * k * even;
        }
        WithTwoDerivatives {
            value: p,
            first: dp,
            second: d2p,
        }
    }

    /// The derivative `d/dθ`: `a'_k = k b_k`, `b'_k = -k a_k`, `c0' = 0`.
    pub fn derivative(&self) -> TrigPoly {
        let (a, b) = self
            .a
            .iter()
            .zip(&self.b)
            .enumerate()
            .map(|(i, (&ak, &bk))| {
                let k = (i + 1) as f64;
                (k * bk, -k * ak)
            })
            .unzip();
        TrigPoly { c0: 0.0, a, b }
    }

    /// The product `self · other` (`a.len()` is the sum of both), computed as
    /// a convolution of the coefficients of `e^{ikθ}`.
    pub fn product(&self, other: &TrigPoly) -> TrigPoly {
        let (n1, n2) = (self.a.len(), other.a.len());
        let d1 = self.laurent();
        let d2 = other.laurent();
        let n = n1 + n2;
        // coefficient of e^{ikθ}, k = -n..=n, index k + n
        let mut d = vec![Complex::new(0.0, 0.0); 2 * n + 1];
        for (i, &x) in d1.iter().enumerate() {
            for (j, &y) in d2.iter().enumerate() {
                d[i + j] += x * y;
            }
        }
        let c0 = d[n].re;
        // real coefficients: a_k = d_k + d_{-k}, b_k = i (d_k - d_{-k})
        let a = (1..=n).map(|k| d[n + k].re + d[n - k].re).collect();
        let b = (1..=n).map(|k| d[n - k].im - d[n + k].im).collect();
        TrigPoly { c0, a, b }
    }

    /// Coefficients of `e^{ikθ}` for `k = -n..=n` (index `k + n`).
    fn laurent(&self) -> Vec<Complex<f64>> {
        let n = self.a.len();
        let mut d = vec![Complex::new(0.0, 0.0); 2 * n + 1];
        d[n] = Complex::new(self.c0, 0.0);
        for k in 1..=n {
            let (ak, bk) = (self.a[k - 1], self.b[k - 1]);
            d[n + k] = Complex::new(ak / 2.0, -bk / 2.0);
            d[n - k] = Complex::new(ak / 2.0, bk / 2.0);
        }
        d
    }

    /// Rounding level `η` of `p` as computed by [`TrigPoly::eval`]:
    /// `η = 16 ε (|c0| + Σ_k √k (|a_k| + |b_k|))`, a safety factor 4 above the
    /// largest evaluation error measured for random coefficients (`n ≤ 64`)
    /// and 3 above that measured at `n = 256` (one top harmonic, against a
    /// high-precision evaluation).
    /// [`TrigPoly::roots`] treats `|p(θ)| ≤ η + |p'(θ)| ulp(θ)` as zero.
    pub fn eval_error_bound(&self) -> f64 {
        let s = self
            .a
            .iter()
            .zip(&self.b)
            .enumerate()
            .fold(self.c0.abs(), |s, (i, (&ak, &bk))| {
                s + ((i + 1) as f64).sqrt() * (ak.abs() + bk.abs())
            });
        NOISE_FACTOR * EPS * s
    }

    /// All real roots of `p(θ) = level` in `[0, 2π)`: [`TrigPoly::roots`] of
    /// `p - level`, same contract.
    pub fn roots_at_level(&self, level: f64) -> Vec<f64> {
        let mut q = self.clone();
        q.c0 -= level;
        q.roots()
    }

    /// All real roots in `[0, 2π)`, sorted ascending, each reported once.
    ///
    /// Method: certified subdivision with Taylor models, one bracketed solve
    /// per isolated root; see the module documentation, which also proves that
    /// no root is missed.
    ///
    /// # Contract
    ///
    /// Let `η` = [`TrigPoly::eval_error_bound`] (a few ulps of the coefficient
    /// sum: the rounding level of `p`).
    ///
    /// * The vector is strictly increasing and every value is in `[0, 2π)`; a
    ///   root at the seam is reported once (as `0.0` or just below `2π`).
    /// * Every returned `θ` satisfies `|p(θ)| ≤ η + |p'(θ)| ulp(θ)`. A simple
    ///   root `θ*` is therefore returned to within `~η/|p'(θ*)|`: a few ulps
    ///   times its condition number `Σ|coefficients| / |p'(θ*)|`.
    /// * A double root (a tangency, `p = p' = 0`) is reported **once**, to about
    ///   `sqrt(ε)` in the worst case (`sqrt(2η/|p''|)`, the width of the band
    ///   where `|p| ≤ η`); it is normally the critical point of `p` (Newton on
    ///   `p'`), which is much more accurate. A near-tangency is decided by
    ///   rounding: one root if `min |p|` is at rounding level (`≤ η`), none if
    ///   `p` stays clearly away from zero, two if `p` clearly changes sign.
    /// * Two roots are reported separately exactly when `p` between them is
    ///   above rounding level (`> η` at the midpoint); a pair of simple roots
    ///   closer than about `sqrt(8η/|p''|)` (`~1e-7` for well-scaled `p`) is
    ///   reported as one root.
    /// * A root of multiplicity `m ≥ 3` is reported once, to about `ε^{1/m}`.
    /// * Degree 0 gives an empty vector, including the identically zero
    ///   polynomial (whose "roots" are every θ). Leading pairs with
    ///   `hypot(a_n, b_n) ≤ ε · max|coefficient|` are ignored. Non-finite
    ///   coefficients give an empty vector.
    /// * No root is missed: every root of `p` is reported (within the bounds
    ///   above), except that roots closer together than the rounding level
    ///   allows are reported once (module documentation, "No root is
    ///   missed"). Nothing is sampled: excluded intervals carry a proof.
    ///
    /// Cost: `O(n^2)`; about 0.2 ms for `n = 64`, 2 ms for `n = 256`.
    pub fn roots(&self) -> Vec<f64> {
        self.roots_and_envelope().roots
    }

    /// [`TrigPoly::roots`], and an envelope of `|p|` from the same Taylor
    /// models at no extra cost: with `N` the length of the envelope,
    /// its entry `i` bounds `|p(θ)|` for `θ` in `[i 2π/N, (i + 1) 2π/N]`
    /// (the model of that interval plus its error bound, `Σ_j |g_j| + δ_0`,
    /// module docs, step 1). Each entry is close to the largest `|p|` on its
    /// interval where `p` varies slowly over it, and at most about `e^2`
    /// times the largest `|p|` within `2/n` of it. A polynomial without
    /// significant harmonics gives one entry, `|c0|` plus the coefficients'
    /// sum; non-finite coefficients give one infinite entry.
    pub fn roots_and_envelope(&self) -> RootsAndEnvelope {
        let Some((p, e)) = self.normalized_with_exponent() else {
            let all_zero = self.c0 == 0.0 && self.degree() == 0;
            return RootsAndEnvelope {
                roots: Vec::new(),
                envelope: vec![if all_zero { 0.0 } else { f64::INFINITY }],
            };
        };
        let Some(n) = p.significant_degree() else {
            return RootsAndEnvelope {
                roots: Vec::new(),
                envelope: vec![self.c0.abs() + self.coefficient_mass()],
            };
        };
        let eta = p.eval_error_bound();
        let (found, bounds, models) = isolate::candidates(&p, n, eta);
        let roots = p.merge(found, eta, Some(&models));
        RootsAndEnvelope {
            roots,
            envelope: bounds.into_iter().map(|b| ldexp(b, -e)).collect(),
        }
    }

    /// A finder of the roots of `self = level` for many levels that shares
    /// the Taylor models' `O(n^2)` sums over the harmonics between them
    /// ([`LevelRoots`]).
    pub fn levels(&self) -> LevelRoots {
        LevelRoots {
            poly: self.clone(),
            shared: OnceLock::new(),
        }
    }

    /// `Σ_k (|a_k| + |b_k|)`.
    fn coefficient_mass(&self) -> f64 {
        self.a
            .iter()
            .zip(&self.b)
            .map(|(a, b)| a.abs() + b.abs())
            .sum()
    }

    /// The previous root finder, kept as an independent test oracle for
    /// [`TrigPoly::roots`]: eigenvalues of the `2n × 2n` companion matrix of
    /// `z^n p(θ)` (nalgebra's complex Schur form), then the same polish and
    /// merge. Same contract except that it proves nothing about missed roots.
    /// Cost `O(n^3)` with a large constant (about 1 s at `n = 256`).
    #[doc(hidden)]
    pub fn roots_by_eigenvalues(&self) -> Vec<f64> {
        let Some(p) = self.normalized() else {
            return Vec::new();
        };
        let Some(n) = p.significant_degree() else {
            return Vec::new();
        };
        let eta = p.eval_error_bound();
        let found = p.eigenvalue_candidates(n, eta);
        let found = found
            .into_iter()
            .map(|theta| Candidate { theta, slope: None });
        p.merge(found.collect(), eta, None)
    }

    /// `p` scaled by the power of two that brings its largest coefficient into
    /// `[1, 2)` (exact: the roots are unchanged and nothing overflows or
    /// underflows); `None` if a coefficient is not finite or all are zero.
    fn normalized(&self) -> Option<TrigPoly> {
        self.normalized_with_exponent().map(|(p, _)| p)
    }

    /// [`TrigPoly::normalized`] and the exponent `e` it scaled by (`2^e`).
    fn normalized_with_exponent(&self) -> Option<(TrigPoly, i32)> {
        let all = std::iter::once(&self.c0).chain(&self.a).chain(&self.b);
        if all.clone().any(|x| !x.is_finite()) {
            return None;
        }
        let scale = all.fold(0.0_f64, |m, x| m.max(x.abs()));
        if scale == 0.0 {
            return None;
        }
        let e = -(scale.log2().floor() as i32);
        let p = TrigPoly {
            c0: ldexp(self.c0, e),
            a: self.a.iter().map(|&x| ldexp(x, e)).collect(),
            b: self.b.iter().map(|&x| ldexp(x, e)).collect(),
        };
        Some((p, e))
    }

    /// The degree without the leading pairs with
    /// `hypot(a_k, b_k) ≤ ε · max|coefficient|`; `None` if that is 0.
    fn significant_degree(&self) -> Option<usize> {
        let largest = self
            .a
            .iter()
            .zip(&self.b)
            .fold(self.c0.abs(), |m, (&a, &b)| m.max(a.hypot(b)));
        let mut n = self.degree();
        while n > 0 && self.a[n - 1].hypot(self.b[n - 1]) <= EPS * largest {
            n -= 1;
        }
        (n > 0).then_some(n)
    }

    /// `|p(θ)|` is at rounding level: `≤ η + |p'(θ)| ulp(θ)`.
    fn is_zero_at(&self, theta: f64, eta: f64) -> bool {
        self.slope_if_zero_at(theta, eta).is_some()
    }

    /// The computed `p'(θ)` if `|p(θ)|` is at rounding level
    /// ([`TrigPoly::is_zero_at`]).
    fn slope_if_zero_at(&self, theta: f64, eta: f64) -> Option<f64> {
        let WithDerivative {
            value: p,
            derivative: dp,
        } = self.eval_with_derivative(theta);
        (p.abs() <= eta + dp.abs() * EPS * theta.abs().max(1.0)).then_some(dp)
    }

    /// Newton on `p` with steps bounded by `NEWTON_MAX_STEP`; returns the
    /// iterate of smallest `|p|`, which is `theta0` if Newton never improves.
    fn newton(&self, theta0: f64) -> f64 {
        let WithDerivative {
            value: mut p,
            derivative: mut dp,
        } = self.eval_with_derivative(theta0);
        let mut theta = theta0;
        let mut best = (theta0, p.abs());
        for _ in 0..NEWTON_ITERS {
            if p == 0.0 || dp == 0.0 || !dp.is_finite() {
                break;
            }
            let step = (p / dp).clamp(-NEWTON_MAX_STEP, NEWTON_MAX_STEP);
            theta -= step;
            WithDerivative {
                value: p,
                derivative: dp,
            } = self.eval_with_derivative(theta);
            if p.abs() < best.1 {
                best = (theta, p.abs());
            }
            if step.abs() <= 2.0 * EPS * theta.abs().max(1.0) {
                break;
            }
        }
        best.0
    }

    /// Newton on `p'` from `theta0`; `None` if it leaves
    /// `[theta0 - radius, theta0 + radius]` or `p''` vanishes.
    fn critical_point(&self, theta0: f64, radius: f64) -> Option<f64> {
        let mut theta = theta0;
        for _ in 0..NEWTON_ITERS {
            let WithTwoDerivatives {
                first: dp,
                second: d2p,
                ..
            } = self.eval_with_two_derivatives(theta);
            if dp == 0.0 {
                break;
            }
            if d2p == 0.0 || !d2p.is_finite() {
                return None;
            }
            let step = dp / d2p;
            theta -= step;
            if (theta - theta0).abs() > radius {
                return None;
            }
            if step.abs() <= 2.0 * EPS * theta.abs().max(1.0) {
                break;
            }
        }
        Some(theta)
    }
}

/// The roots of `p(θ) = level` for many levels of one polynomial `p`
/// ([`TrigPoly::levels`]). A level changes only `c0`, so the models of
/// step 1 (module docs) differ only in `g_0`: their sums over the
/// harmonics, `O(n^2)` in all, are computed for the first level and kept.
/// So is the subdivision of step 2: a piece's shifted model differs
/// between levels only in `e_0 = g_0 + X` (`X` the same for all), and only
/// the exclusion test (E) reads `e_0`, so each piece keeps its shift and
/// its (M)/(C) class, and its halves once made; a later level tests (E)
/// and resolves its own roots. Every later level whose normalised
/// polynomial has the same scale and degree (so the same harmonics to the
/// bit) reuses them, and its roots and envelope are those of
/// [`TrigPoly::roots_and_envelope`] of `p - level`, to the bit; any other
/// level is solved on its own. Levels may be solved on several threads at
/// once.
#[derive(Debug, Clone)]
pub struct LevelRoots {
    poly: TrigPoly,
    /// Scale exponent and degree of the first level solved, and the work
    /// its levels share.
    shared: OnceLock<(i32, usize, Arc<isolate::Shared>)>,
}

impl LevelRoots {
    /// The polynomial whose levels are solved.
    pub fn poly(&self) -> &TrigPoly {
        &self.poly
    }

    /// [`TrigPoly::roots_and_envelope`] of `p - level`.
    pub fn roots_and_envelope(&self, level: f64) -> RootsAndEnvelope {
        let mut q = self.poly.clone();
        q.c0 -= level;
        let Some((p, e)) = q.normalized_with_exponent() else {
            return q.roots_and_envelope();
        };
        let Some(n) = p.significant_degree() else {
            return q.roots_and_envelope();
        };
        let (e0, n0, models) = self
            .shared
            .get_or_init(|| (e, n, Arc::new(isolate::Shared::new(&p, n))));
        if (*e0, *n0) != (e, n) {
            return q.roots_and_envelope();
        }
        let eta = p.eval_error_bound();
        let (found, bounds, kept) = isolate::candidates_with(&p, n, eta, models);
        let roots = p.merge(found, eta, Some(&kept));
        RootsAndEnvelope {
            roots,
            envelope: bounds.into_iter().map(|b| ldexp(b, -e)).collect(),
        }
    }

    /// The roots of `p = level` ([`TrigPoly::roots_at_level`]).
    pub fn roots(&self, level: f64) -> Vec<f64> {
        self.roots_and_envelope(level).roots
    }
}

/// `theta` reduced to `[0, 2π)` (never `2π` itself, never `-0.0`).
fn wrap(theta: f64) -> f64 {
    let t = theta.rem_euclid(TAU);
    if t >= TAU { 0.0 } else { t + 0.0 }
}
