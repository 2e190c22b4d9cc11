//! Real roots of real trigonometric polynomials (docs/model.md, section 8).
//!
//! A real trigonometric polynomial of degree `n` is
//!
//! ```text
//! p(θ) = c0 + Σ_{k=1}^{n} ( a_k cos kθ + b_k sin kθ ),   θ ∈ [0, 2π).
//! ```
//!
//! [`TrigPoly::roots`] finds all its real roots without sampling:
//!
//! 1. *Substitution.* With `z = e^{iθ}`, `cos kθ = (z^k + z^{-k})/2` and
//!    `sin kθ = (z^k - z^{-k})/(2i)`, so `q(z) = z^n p(θ)` is an ordinary
//!    polynomial of degree `N = 2n` with complex coefficients
//!    `q_{n+k} = (a_k - i b_k)/2`, `q_{n-k} = (a_k + i b_k)/2`, `q_n = c0`.
//!    As `q_{N-j} = conj(q_j)`, its roots come in pairs `z, 1/conj(z)` with the
//!    same argument; the real roots of `p` are the arguments of its roots on
//!    the unit circle.
//! 2. *Eigenvalues.* The coefficients are scaled by a power of two (exact), and
//!    leading pairs with `hypot(a_n, b_n) ≤ ε · max` are dropped (a change of
//!    `p` at rounding level). The roots of `q` are the eigenvalues of its upper
//!    Hessenberg companion matrix, balanced by a diagonal power-of-two
//!    similarity (Parlett–Reinsch, exact) and reduced to complex Schur form by
//!    nalgebra's [`Schur`] on a `DMatrix<Complex<f64>>`: the eigenvalues are
//!    the diagonal of the triangular factor. nalgebra's shifted QR has no
//!    exceptional shifts and stalls on symmetric companions such as that of
//!    `z^N + 1` (`p = cos nθ`), so it runs with an iteration cap and, on
//!    failure, is rerun on a unitary (Householder) similarity of the matrix,
//!    which has the same eigenvalues and condition numbers.
//! 3. *Selection.* With `η` = [`TrigPoly::eval_error_bound`], the rounding
//!    level of `p`, an eigenvalue `z` is a candidate when `| |z| - 1 |` is
//!    below a tolerance scaled by its conditioning, evaluated at `θ = arg z`:
//!    a generous multiple of `η/|p'|` (a simple root moves by that much) or of
//!    `sqrt(2η/|p''|)` (a double root, a tangency, splits into a pair displaced
//!    by that much, possibly both off the circle), whichever is larger.
//! 4. *Polish and verification.* Each candidate is polished by Newton on `p`
//!    (bounded steps; the iterate of smallest `|p|` is kept, which is the
//!    unpolished value if Newton diverges) and accepted if `|p| ≤ η + |p'| ulp(θ)`
//!    there. Otherwise it may be a tangency: Newton on `p'` (the nearby
//!    critical point of `p`), accepted if `|p| ≤ η` there. Eigenvalues near
//!    the circle that are not real roots (a minimum of `|p|` above rounding
//!    level) are rejected here.
//! 5. *Double roots and duplicates.* Adjacent accepted values `θ_a < θ_b`
//!    (cyclically, across the `0/2π` seam) are one root when `p` at their
//!    midpoint is at rounding level; a genuine pair of simple roots has `p`
//!    clearly nonzero between them and is kept. A merged group, or a root with
//!    `p' ≈ 0`, is reported once: at the critical point of `p` if that lies
//!    within the group and `|p|` is at rounding level there, else at the member
//!    of smallest `|p|`. The values are wrapped into `[0, 2π)` and sorted.
//!
//! Cost: `O(n^3)` for [`TrigPoly::roots`] (about 7 ms for `n = 32` and 60 ms
//! for `n = 64`, optimised build); [`TrigPoly::eval`] and its derivative
//! variants are `O(n)` with one `sin_cos` and no allocation.

use std::f64::consts::TAU;

use nalgebra::Complex;

mod eigen;
mod isolate;

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

    /// `(p(θ), p'(θ))`, one `sin_cos`, no allocation.
    #[inline]
    pub fn eval_with_derivative(&self, theta: f64) -> (f64, f64) {
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
        (p, dp)
    }

    /// `(p(θ), p'(θ), p''(θ))`, one `sin_cos`, no allocation.
    #[inline]
    pub fn eval_with_two_derivatives(&self, theta: f64) -> (f64, f64, f64) {
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
        (p, dp, d2p)
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
    /// largest evaluation error measured for random coefficients (`n ≤ 64`).
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
    /// Method: eigenvalues of the companion matrix of `z^n p`, Newton polish;
    /// see the module documentation.
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
    /// * Every root comes from an eigenvalue: none is found by sampling. A root
    ///   can only be missed if its eigenvalue is farther from the unit circle
    ///   than the conditioning-scaled tolerance (`10^4 η/|p'|` or
    ///   `100 sqrt(2η/|p''|)`, whichever is larger); this has not been observed
    ///   up to degree 256 (random coefficients, roots counted independently).
    ///
    /// Cost: `O(n^3)`, the complex Schur form of a `2n × 2n` matrix.
    pub fn roots(&self) -> Vec<f64> {
        let Some(p) = self.normalized() else {
            return Vec::new();
        };
        let Some(n) = p.significant_degree() else {
            return Vec::new();
        };
        let eta = p.eval_error_bound();
        let found = isolate::candidates(&p, n, eta);
        p.merge(found.into_iter().map(wrap).collect(), eta)
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
        p.merge(found.into_iter().map(wrap).collect(), eta)
    }

    /// `p` scaled by the power of two that brings its largest coefficient into
    /// `[1, 2)` (exact: the roots are unchanged and nothing overflows or
    /// underflows); `None` if a coefficient is not finite or all are zero.
    fn normalized(&self) -> Option<TrigPoly> {
        let all = std::iter::once(&self.c0).chain(&self.a).chain(&self.b);
        if all.clone().any(|x| !x.is_finite()) {
            return None;
        }
        let scale = all.fold(0.0_f64, |m, x| m.max(x.abs()));
        if scale == 0.0 {
            return None;
        }
        let e = -(scale.log2().floor() as i32);
        Some(TrigPoly {
            c0: ldexp(self.c0, e),
            a: self.a.iter().map(|&x| ldexp(x, e)).collect(),
            b: self.b.iter().map(|&x| ldexp(x, e)).collect(),
        })
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
        let (p, dp) = self.eval_with_derivative(theta);
        p.abs() <= eta + dp.abs() * EPS * theta.abs().max(1.0)
    }

    /// Newton on `p` with steps bounded by `NEWTON_MAX_STEP`; returns the
    /// iterate of smallest `|p|`, which is `theta0` if Newton never improves.
    fn newton(&self, theta0: f64) -> f64 {
        let (mut p, mut dp) = self.eval_with_derivative(theta0);
        let mut theta = theta0;
        let mut best = (theta0, p.abs());
        for _ in 0..NEWTON_ITERS {
            if p == 0.0 || dp == 0.0 || !dp.is_finite() {
                break;
            }
            let step = (p / dp).clamp(-NEWTON_MAX_STEP, NEWTON_MAX_STEP);
            theta -= step;
            (p, dp) = self.eval_with_derivative(theta);
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
            let (_, dp, d2p) = self.eval_with_two_derivatives(theta);
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

    /// Groups the accepted values (in `[0, 2π)`) that are one root — `p` at
    /// rounding level between neighbours, cyclically — and returns one value
    /// per group, sorted, in `[0, 2π)`.
    fn merge(&self, mut roots: Vec<f64>, eta: f64) -> Vec<f64> {
        if roots.is_empty() {
            return roots;
        }
        roots.sort_by(f64::total_cmp);
        let same = |x: f64, y: f64| {
            y - x <= 4.0 * EPS * y.abs().max(1.0) || self.is_zero_at(0.5 * (x + y), eta)
        };
        let mut groups: Vec<Vec<f64>> = vec![vec![roots[0]]];
        for w in roots.windows(2) {
            match groups.last_mut() {
                Some(g) if same(w[0], w[1]) => g.push(w[1]),
                _ => groups.push(vec![w[1]]),
            }
        }
        // across the seam: the last group continues the first one
        if groups.len() > 1
            && same(roots[roots.len() - 1] - TAU, roots[0])
            && let Some(last) = groups.pop()
        {
            let mut joined: Vec<f64> = last.into_iter().map(|t| t - TAU).collect();
            joined.append(&mut groups[0]);
            groups[0] = joined;
        }
        let mut out: Vec<f64> = groups
            .iter()
            .map(|g| wrap(self.representative(g, eta)))
            .collect();
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }

    /// One value for a group (sorted, nonempty) of accepted values that are
    /// one root: the member of smallest `|p|`, replaced by the critical point of
    /// `p` when the group looks like a tangency (several members, or
    /// `p' ≈ 0`) and that point is within the group and at rounding level.
    fn representative(&self, group: &[f64], eta: f64) -> f64 {
        let abs_p = |x: f64| self.eval(x).abs();
        let best = group
            .iter()
            .copied()
            .min_by(|&x, &y| abs_p(x).total_cmp(&abs_p(y)))
            .unwrap_or(0.0);
        let (p, dp, d2p) = self.eval_with_two_derivatives(best);
        let tangent = group.len() > 1 || dp.abs() <= 4.0 * (eta * d2p.abs()).sqrt();
        if !tangent {
            return best;
        }
        let width = (2.0 * eta / d2p.abs()).sqrt();
        let span = group[group.len() - 1] - group[0];
        let radius = (span + 4.0 * width).min(MAX_ACCEPT);
        match self.critical_point(best, radius) {
            Some(tc) if abs_p(tc) <= eta.max(p.abs()) => tc,
            _ => best,
        }
    }
}

/// `x · 2^e`, exact unless the result is subnormal.
fn ldexp(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e)
}

/// `theta` reduced to `[0, 2π)` (never `2π` itself, never `-0.0`).
fn wrap(theta: f64) -> f64 {
    let t = theta.rem_euclid(TAU);
    if t >= TAU { 0.0 } else { t + 0.0 }
}
