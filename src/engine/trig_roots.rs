//! Real roots of real trigonometric polynomials.
//!
//! A real trigonometric polynomial of degree `n` is
//!
//! ```text
//! p(θ) = c0 + Σ_{k=1}^{n} ( a_k cos kθ + b_k sin kθ ),   θ ∈ [0, 2π).
//! ```
//!
//! # Method (MODEL.md, section 8)
//!
//! *Substitution.* With `z = e^{iθ}`, `cos kθ = (z^k + z^{-k})/2` and
//! `sin kθ = (z^k - z^{-k})/(2i)`, so `q(z) = z^n p(θ)` is an ordinary
//! polynomial of degree `N = 2n` with complex coefficients
//! `q_{n+k} = (a_k - i b_k)/2`, `q_{n-k} = (a_k + i b_k)/2`, `q_n = c0`.
//! Its coefficients satisfy `q_{N-j} = conj(q_j)`, so its roots come in pairs
//! `z, 1/conj(z)` with the same argument; the real roots of `p` are the
//! arguments of the roots of `q` on the unit circle.
//!
//! *Eigenvalues.* Leading pairs `(a_n, b_n)` that are negligible relative to
//! the largest coefficient (`≤ ε·max`) are trimmed (this changes `p` by at most
//! that amount on the whole circle). The `N` roots of `q` are the eigenvalues
//! of its (upper Hessenberg) companion matrix, balanced by a diagonal
//! power-of-two similarity (Parlett–Reinsch) and reduced to complex Schur form
//! by nalgebra's [`Schur`]; the eigenvalues are the diagonal of the
//! triangular factor. nalgebra's QR iteration has no exceptional shifts, so it
//! runs with an iteration cap; on failure it is retried on a unitary
//! (Householder) similarity of the balanced matrix, which breaks the
//! symmetric configurations (e.g. `z^N + 1`) on which shifted QR stalls.
//!
//! *Selection.* Let `η = K·ε·Σ_k (k+1)(|a_k|+|b_k|)` (with `k = 0` for `c0`)
//! be an upper bound of the rounding error of [`TrigPoly::eval`]. An
//! eigenvalue `z` is a candidate when `| |z| - 1 |` is below a tolerance that
//! follows its conditioning: a simple root moves by `~η/|p'|`, a double root
//! (tangency) splits into a pair displaced by `~sqrt(2η/|p''|)`, possibly both
//! off the circle; the tolerance is a generous multiple of the larger of the
//! two, evaluated at `θ = arg z`.
//!
//! *Polish and verification.* Each candidate `θ` is polished by Newton's method
//! on `p` (bounded steps, keeping the iterate of smallest `|p|`, which is the
//! unpolished value if Newton diverges). It is accepted when `|p(θ)| ≤ η`;
//! otherwise a tangency is tried: Newton on `p'` (the critical point of `p`
//! next to the candidate), accepted when `|p| ≤ η` there. Candidates off the
//! circle that are not roots (a minimum of `|p|` above rounding level) are
//! rejected here.
//!
//! *Double roots.* Sorted accepted candidates `θ_a < θ_b` (cyclically, across
//! the `0/2π` seam) are the same root when `|p((θ_a+θ_b)/2)| ≤ η`: a genuine
//! pair of simple roots has `p` clearly nonzero, of the opposite sign, between
//! them. A merged group (or a single root with `p' ≈ 0`) is reported once, at
//! the critical point of `p` when that point is within the group and at
//! rounding level, else at the member of smallest `|p|`.
//!
//! No sampling is involved: every root comes from an eigenvalue.

use std::f64::consts::TAU;

use nalgebra::{Complex, DMatrix, Schur};

/// Machine epsilon.
const EPS: f64 = f64::EPSILON;
/// Safety factor of the evaluation rounding bound `η`.
const NOISE_FACTOR: f64 = 16.0;
/// Multiple of the simple-root perturbation `η/|p'|` accepted off the circle.
const SIMPLE_ACCEPT: f64 = 1.0e6;
/// Multiple of the double-root perturbation `sqrt(2η/|p''|)` accepted off the circle.
const DOUBLE_ACCEPT: f64 = 1.0e2;
/// Candidates off the circle by more than this are never roots.
const MAX_ACCEPT: f64 = 1.0e-2;
/// Newton iterations on `p` (linear convergence at double roots needs more than a few).
const NEWTON_ITERS: usize = 30;
/// Largest single Newton step (radians).
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

    /// The product `self · other` (degree `deg self + deg other`), computed as
    /// a convolution of the coefficients of `e^{ikθ}`.
    pub fn mul(&self, other: &TrigPoly) -> TrigPoly {
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

    /// Rounding level `η` of [`TrigPoly::eval`]: `K ε (|c0| + Σ_k √k (|a_k| + |b_k|))`
    /// with a safety factor `K`. Values `|p(θ)| ≤ η` are treated as zero by
    /// [`TrigPoly::roots`] (plus `|p'(θ)| ulp(θ)` for the rounding of `θ`).
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

    #[doc(hidden)]
    pub fn debug_candidates(&self) -> Vec<(f64, f64, f64, f64)> {
        let eta = self.eval_error_bound();
        let n = self.degree();
        self.eigen_near_circle(n, eta, f64::INFINITY)
    }

    /// All real roots of `p(θ) = level` in `[0, 2π)`; see [`TrigPoly::roots`].
    pub fn roots_at_level(&self, level: f64) -> Vec<f64> {
        let mut q = self.clone();
        q.c0 -= level;
        q.roots()
    }

    /// All real roots in `[0, 2π)`, sorted ascending, each reported once.
    ///
    /// # Contract
    ///
    /// * Every value is in `[0, 2π)` (a root at the seam is reported once, as
    ///   `0` or just below `2π`, never both) and the vector is sorted.
    /// * With `η = ` [`TrigPoly::eval_error_bound`] (a few ulps times the
    ///   coefficient sum weighted by `k+1`), every returned `θ` satisfies
    ///   `|p(θ)| ≤ η`: a simple root is within `~η/|p'(θ*)|` of the true
    ///   root `θ*` (a few ulps times its condition number).
    /// * A double root (tangency, `p(θ*) = p'(θ*) = 0`) is reported **once**,
    ///   within about `sqrt(ε)` (`~sqrt(2η/|p''|)`) of the true root; usually it
    ///   is the critical point of `p`, then much more accurate. Whether a
    ///   near-tangency with `|min p| ≲ η` is reported is decided by rounding:
    ///   one root is reported if the minimum of `|p|` is at rounding level, none
    ///   otherwise, never two. Likewise two simple roots closer than
    ///   `~sqrt(8η/|p''|)` (so that `p` between them is at rounding level) are
    ///   reported as one; farther pairs are resolved.
    /// * Roots of odd multiplicity ≥ 3 are reported once, to about `ε^{1/m}`.
    /// * A constant polynomial (degree 0, including the identically zero one)
    ///   has no roots: the result is empty. Leading coefficient pairs below
    ///   `ε` times the largest coefficient are ignored. Non-finite coefficients
    ///   give an empty result.
    ///
    /// Cost: `O(n^3)` (complex Schur form of a `2n × 2n` matrix).
    pub fn roots(&self) -> Vec<f64> {
        let all = std::iter::once(&self.c0).chain(&self.a).chain(&self.b);
        if all.clone().any(|x| !x.is_finite()) {
            return Vec::new();
        }
        let scale = self
            .a
            .iter()
            .zip(&self.b)
            .fold(self.c0.abs(), |m, (&a, &b)| m.max(a.hypot(b)));
        let mut n = self.degree();
        while n > 0 && self.a[n - 1].hypot(self.b[n - 1]) <= EPS * scale {
            n -= 1;
        }
        if n == 0 {
            return Vec::new();
        }
        let eta = self.eval_error_bound();
        let candidates = self.candidates(n, eta);
        let accepted: Vec<f64> = candidates
            .into_iter()
            .filter_map(|(theta, off)| self.polish_and_verify(theta, off, eta))
            .map(wrap)
            .collect();
        self.merge(accepted, eta)
    }

    /// Eigenvalues of the balanced companion matrix of `z^n p(θ)` (trimmed to degree `n`).
    fn companion_eigenvalues(&self, n: usize) -> Vec<Complex<f64>> {
        let big_n = 2 * n;
        // q_j, j = 0..=N
        let mut q = vec![Complex::new(0.0, 0.0); big_n + 1];
        q[n] = Complex::new(self.c0, 0.0);
        for k in 1..=n {
            let (ak, bk) = (self.a[k - 1], self.b[k - 1]);
            q[n + k] = Complex::new(ak / 2.0, -bk / 2.0);
            q[n - k] = Complex::new(ak / 2.0, bk / 2.0);
        }
        let lead = q[big_n];
        let mut c = DMatrix::<Complex<f64>>::zeros(big_n, big_n);
        for j in 0..big_n {
            c[(0, j)] = -q[big_n - 1 - j] / lead;
        }
        for i in 1..big_n {
            c[(i, i - 1)] = Complex::new(1.0, 0.0);
        }
        balance(&mut c);
        eigenvalues(c)
    }

    /// For each finite nonzero eigenvalue `z`: `(arg z, | |z|-1 |, η/|p'|, sqrt(2η/|p''|))`,
    /// the last two evaluated at `θ = arg z`.
    fn eigen_near_circle(&self, n: usize, eta: f64, cap: f64) -> Vec<(f64, f64, f64, f64)> {
        self.companion_eigenvalues(n)
            .into_iter()
            .filter(|z| z.re.is_finite() && z.im.is_finite())
            .filter_map(|z| {
                let r = z.norm();
                let off = (r - 1.0).abs();
                if r == 0.0 || off > cap {
                    return None;
                }
                let theta = z.im.atan2(z.re);
                let (_, dp, d2p) = self.eval_with_two_derivatives(theta);
                Some((theta, off, eta / dp.abs(), (2.0 * eta / d2p.abs()).sqrt()))
            })
            .collect()
    }

    /// Arguments of the eigenvalues close enough to the unit circle (relative
    /// to their conditioning), with their distance to it.
    fn candidates(&self, n: usize, eta: f64) -> Vec<(f64, f64)> {
        self.eigen_near_circle(n, eta, MAX_ACCEPT)
            .into_iter()
            .filter(|&(_, off, simple, double)| {
                off <= (SIMPLE_ACCEPT * simple).max(DOUBLE_ACCEPT * double)
            })
            .map(|(theta, off, _, _)| (theta, off))
            .collect()
    }

    /// `|p(θ)|` is at rounding level: `≤ η + |p'(θ)| ulp(θ)`.
    fn is_zero_at(&self, theta: f64, eta: f64) -> bool {
        let (p, dp) = self.eval_with_derivative(theta);
        p.abs() <= eta + dp.abs() * EPS * theta.abs().max(1.0)
    }

    /// Newton on `p` from `theta0`; if the result is not at rounding level, try
    /// the critical point of `p` (a tangency). `None`: not a root.
    fn polish_and_verify(&self, theta0: f64, off: f64, eta: f64) -> Option<f64> {
        let theta = self.newton(theta0);
        if self.is_zero_at(theta, eta) {
            return Some(theta);
        }
        let (_, _, d2p) = self.eval_with_two_derivatives(theta0);
        let radius = (10.0 * off)
            .max(10.0 * (2.0 * eta / d2p.abs()).sqrt())
            .min(MAX_ACCEPT);
        let tc = self.critical_point(theta0, radius)?;
        (self.eval(tc).abs() <= eta).then_some(tc)
    }

    /// Bounded Newton on `p`; returns the iterate of smallest `|p|` (the start
    /// if Newton never improves).
    fn newton(&self, theta0: f64) -> f64 {
        let (mut p, mut dp) = self.eval_with_derivative(theta0);
        let mut theta = theta0;
        let mut best = (theta0, p);
        for _ in 0..NEWTON_ITERS {
            if p == 0.0 || dp == 0.0 || !dp.is_finite() {
                break;
            }
            let step = (p / dp).clamp(-NEWTON_MAX_STEP, NEWTON_MAX_STEP);
            theta -= step;
            (p, dp) = self.eval_with_derivative(theta);
            if p.abs() < best.1.abs() {
                best = (theta, p);
            }
            if step.abs() <= 2.0 * EPS * theta.abs().max(1.0) {
                break;
            }
        }
        best.0
    }

    /// Newton on `p'` from `theta0`, never leaving `[theta0 - radius, theta0 + radius]`.
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

    /// Groups accepted roots (sorted cyclically) that are one root, and returns
    /// one representative per group, sorted, in `[0, 2π)`.
    fn merge(&self, mut roots: Vec<f64>, eta: f64) -> Vec<f64> {
        if roots.is_empty() {
            return roots;
        }
        roots.sort_by(f64::total_cmp);
        let same = |x: f64, y: f64| self.eval(0.5 * (x + y)).abs() <= eta;
        let mut groups: Vec<Vec<f64>> = vec![vec![roots[0]]];
        for w in roots.windows(2) {
            if same(w[0], w[1]) {
                groups.last_mut().expect("nonempty").push(w[1]);
            } else {
                groups.push(vec![w[1]]);
            }
        }
        if groups.len() > 1 && same(roots[roots.len() - 1] - TAU, roots[0]) {
            let last = groups.pop().expect("len > 1");
            let first = &mut groups[0];
            let mut joined: Vec<f64> = last.into_iter().map(|t| t - TAU).collect();
            joined.append(first);
            *first = joined;
        }
        let mut out: Vec<f64> = groups
            .iter()
            .map(|g| wrap(self.representative(g, eta)))
            .collect();
        out.sort_by(f64::total_cmp);
        out
    }

    /// One value for a group of accepted candidates that are one root.
    fn representative(&self, group: &[f64], eta: f64) -> f64 {
        let best = group
            .iter()
            .copied()
            .min_by(|&x, &y| self.eval(x).abs().total_cmp(&self.eval(y).abs()))
            .expect("nonempty group");
        let (p, dp, d2p) = self.eval_with_two_derivatives(best);
        let width = (2.0 * eta / d2p.abs()).sqrt();
        let tangent = group.len() > 1 || dp.abs() <= 4.0 * (eta * d2p.abs()).sqrt();
        if !tangent {
            return best;
        }
        let span = group[group.len() - 1] - group[0];
        let radius = (span + 4.0 * width).min(MAX_ACCEPT);
        match self.critical_point(best, radius) {
            Some(tc) if self.eval(tc).abs() <= eta.max(p.abs()) => tc,
            _ => best,
        }
    }
}

/// `theta` reduced to `[0, 2π)`.
fn wrap(theta: f64) -> f64 {
    let t = theta.rem_euclid(TAU);
    if t >= TAU { 0.0 } else { t + 0.0 }
}

/// Diagonal power-of-two balancing (Parlett–Reinsch, 1-norms, as in LAPACK
/// `zgebal` without permutations). Exact: it does not change the eigenvalues.
fn balance(m: &mut DMatrix<Complex<f64>>) {
    const RADIX: f64 = 2.0;
    let n = m.nrows();
    for _sweep in 0..64 {
        let mut converged = true;
        for i in 0..n {
            let mut c = 0.0;
            let mut r = 0.0;
            for j in 0..n {
                if j != i {
                    c += m[(j, i)].l1_norm();
                    r += m[(i, j)].l1_norm();
                }
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            let g = r / RADIX;
            while c < g && f < 1e150 {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            let g = r * RADIX;
            while c >= g && f > 1e-150 {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if (c + r) / f < 0.95 * s {
                converged = false;
                let inv = 1.0 / f;
                m.row_mut(i).scale_mut(inv);
                m.column_mut(i).scale_mut(f);
            }
        }
        if converged {
            break;
        }
    }
}

/// Eigenvalues of a complex square matrix (diagonal of its complex Schur
/// form). Retries on unitary similarities if the QR iteration stalls.
fn eigenvalues(m: DMatrix<Complex<f64>>) -> Vec<Complex<f64>> {
    let n = m.nrows();
    let max_iter = 40 * n.max(4);
    if let Some(s) = Schur::try_new(m.clone(), EPS, max_iter) {
        return s.unpack().1.diagonal().iter().copied().collect();
    }
    eprintln!("FALLBACK n={n}");
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut current = m;
    for _attempt in 0..6 {
        current = householder_similarity(&current, &mut seed);
        if let Some(s) = Schur::try_new(current.clone(), EPS, max_iter) {
            return s.unpack().1.diagonal().iter().copied().collect();
        }
    }
    // Unreachable in practice; return the last matrix's diagonal so that the
    // caller still verifies whatever candidates it gets.
    current.diagonal().iter().copied().collect()
}

/// `H m H` with `H = I - 2 v v*/(v* v)` for a pseudo-random `v`.
fn householder_similarity(m: &DMatrix<Complex<f64>>, seed: &mut u64) -> DMatrix<Complex<f64>> {
    let n = m.nrows();
    let mut next = || {
        // xorshift64*: deterministic, good enough to break symmetry
        *seed ^= *seed >> 12;
        *seed ^= *seed << 25;
        *seed ^= *seed >> 27;
        let x = seed.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let v = nalgebra::DVector::<Complex<f64>>::from_fn(n, |_, _| Complex::new(next(), next()));
    let vv = v.norm_squared();
    let h =
        DMatrix::<Complex<f64>>::identity(n, n) - (&v * v.adjoint()) * Complex::new(2.0 / vv, 0.0);
    &h * m * &h
}
