//! The companion-matrix root finder, kept as an independent oracle for the
//! tests of [`TrigPoly::roots`] (it shares only the final polish and merge).
//!
//! 1. *Substitution.* With `z = e^{iθ}`, `cos kθ = (z^k + z^{-k})/2` and
//!    `sin kθ = (z^k - z^{-k})/(2i)`, so `q(z) = z^n p(θ)` is an ordinary
//!    polynomial of degree `N = 2n` with complex coefficients
//!    `q_{n+k} = (a_k - i b_k)/2`, `q_{n-k} = (a_k + i b_k)/2`, `q_n = c0`.
//!    As `q_{N-j} = conj(q_j)`, its roots come in pairs `z, 1/conj(z)` with the
//!    same argument; the real roots of `p` are the arguments of its roots on
//!    the unit circle.
//! 2. *Eigenvalues.* The roots of `q` are the eigenvalues of its upper
//!    Hessenberg companion matrix, balanced by a diagonal power-of-two
//!    similarity (Parlett–Reinsch, exact) and reduced to complex Schur form by
//!    nalgebra's [`Schur`] on a `DMatrix<Complex<f64>>`: the eigenvalues are
//!    the diagonal of the triangular factor. nalgebra's shifted QR has no
//!    exceptional shifts and stalls on symmetric companions such as that of
//!    `z^N + 1` (`p = cos nθ`), so it runs with an iteration cap and, on
//!    failure, is rerun on a unitary (Householder) similarity of the matrix,
//!    which has the same eigenvalues and condition numbers.
//! 3. *Selection.* An eigenvalue `z` is a candidate when `| |z| - 1 |` is
//!    below a tolerance scaled by its conditioning, evaluated at `θ = arg z`:
//!    a generous multiple of `η/|p'|` (a simple root moves by that much) or of
//!    `sqrt(2η/|p''|)` (a double root, a tangency, splits into a pair displaced
//!    by that much, possibly both off the circle), whichever is larger.
//! 4. *Polish and verification.* Each candidate is polished by Newton on `p`
//!    and accepted if `|p| ≤ η + |p'| ulp(θ)` there; otherwise it may be a
//!    tangency: Newton on `p'`, accepted if `|p| ≤ η` there.
//!
//! A root can only be missed if its eigenvalue is farther from the unit circle
//! than the conditioning-scaled tolerance; the method gives no proof that
//! none is. Cost `O(n^3)` (about 7 ms for `n = 32` and 60 ms for `n = 64`).

use nalgebra::{Complex, DMatrix, DVector, Schur};

use super::{EPS, MAX_ACCEPT, TrigPoly, WithTwoDerivatives};

/// Multiple of the simple-root displacement `η/|p'|` accepted off the circle
/// (measured displacements stay below 100).
const SIMPLE_ACCEPT: f64 = 1.0e4;
/// Multiple of the double-root displacement `sqrt(2η/|p''|)` accepted off the
/// circle (measured displacements stay below 1).
const DOUBLE_ACCEPT: f64 = 1.0e2;
/// Shifted-QR sweeps allowed: `QR_SWEEPS_PER_EIGENVALUE · N + QR_SWEEPS_EXTRA`
/// before the iteration is declared stalled. Measured needs: up to `2.9 N`
/// for random companions (`N ≤ 128`), plus about 20 per multiple root.
const QR_SWEEPS_PER_EIGENVALUE: usize = 5;
/// See [`QR_SWEEPS_PER_EIGENVALUE`].
const QR_SWEEPS_EXTRA: usize = 100;
/// Reruns on unitary similarities after a stall.
const QR_RETRIES: usize = 6;

impl TrigPoly {
    /// Candidate roots of the normalised `p` truncated to degree `n`: polished
    /// and verified arguments of the companion eigenvalues near the circle.
    pub(super) fn eigenvalue_candidates(&self, n: usize, eta: f64) -> Vec<f64> {
        self.candidates(n, eta)
            .into_iter()
            .filter_map(|(theta, off)| self.polish_and_verify(theta, off, eta))
            .collect()
    }

    /// Eigenvalues of the balanced companion matrix of `z^n p(θ)`, `p`
    /// truncated to degree `n`.
    fn companion_eigenvalues(&self, n: usize) -> Vec<Complex<f64>> {
        let big_n = 2 * n;
        // q_j, j = 0..=N
        let mut q = vec![Complex::new(0.0, 0.0); big_n + 1];
        q[n] = Complex::new(self.c0, 0.0);
        for (k, (&ak, &bk)) in (1..=n).zip(self.a.iter().zip(&self.b)) {
            q[n + k] = Complex::new(ak / 2.0, -bk / 2.0);
            q[n - k] = Complex::new(ak / 2.0, bk / 2.0);
        }
        // monic q: z^N + Σ_{j<N} (q_j/q_N) z^j; first row -q_{N-1}/q_N .. -q_0/q_N
        let lead = q[big_n];
        let mut c = DMatrix::<Complex<f64>>::zeros(big_n, big_n);
        for (j, &qj) in q[..big_n].iter().rev().enumerate() {
            c[(0, j)] = -qj / lead;
        }
        for i in 1..big_n {
            c[(i, i - 1)] = Complex::new(1.0, 0.0);
        }
        balance(&mut c);
        eigenvalues(c)
    }

    /// `(arg z, | |z| - 1 |)` for the eigenvalues `z` close enough to the unit
    /// circle relative to their conditioning at `θ = arg z`: a simple root is
    /// displaced by `~η/|p'|`, the pair of a double root by `~sqrt(2η/|p''|)`.
    fn candidates(&self, n: usize, eta: f64) -> Vec<(f64, f64)> {
        self.companion_eigenvalues(n)
            .into_iter()
            .filter(|z| z.re.is_finite() && z.im.is_finite())
            .filter_map(|z| {
                let off = (z.norm() - 1.0).abs();
                if off > MAX_ACCEPT {
                    return None;
                }
                let theta = z.im.atan2(z.re);
                let WithTwoDerivatives {
                    first: dp,
                    second: d2p,
                    ..
                } = self.eval_with_two_derivatives(theta);
                let simple = SIMPLE_ACCEPT * eta / dp.abs();
                let double = DOUBLE_ACCEPT * (2.0 * eta / d2p.abs()).sqrt();
                (off <= simple.max(double)).then_some((theta, off))
            })
            .collect()
    }

    /// Newton on `p` from the eigenvalue's `theta0`; if that does not reach
    /// rounding level, the critical point of `p` nearby (a tangency).
    /// `None`: not a real root.
    fn polish_and_verify(&self, theta0: f64, off: f64, eta: f64) -> Option<f64> {
        let theta = self.newton(theta0);
        if self.is_zero_at(theta, eta) {
            return Some(theta);
        }
        let d2p = self.eval_with_two_derivatives(theta0).second;
        let radius = (10.0 * off)
            .max(10.0 * (2.0 * eta / d2p.abs()).sqrt())
            .min(MAX_ACCEPT);
        let tc = self.critical_point(theta0, radius)?;
        (self.eval(tc).abs() <= eta).then_some(tc)
    }
}

/// Diagonal power-of-two balancing (Parlett–Reinsch with 1-norms, as LAPACK
/// `zgebal` without permutations): `m ← D⁻¹ m D`, exact, same eigenvalues,
/// smaller norm, hence smaller absolute eigenvalue errors.
fn balance(m: &mut DMatrix<Complex<f64>>) {
    const RADIX: f64 = 2.0;
    let n = m.nrows();
    for _sweep in 0..100 {
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
            while c < r / RADIX && f < 1e150 {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            while c >= r * RADIX && f > 1e-150 {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if (c + r) / f < 0.95 * s {
                converged = false;
                m.row_mut(i).scale_mut(1.0 / f);
                m.column_mut(i).scale_mut(f);
            }
        }
        if converged {
            break;
        }
    }
}

/// Eigenvalues of a complex square matrix: the diagonal of the triangular
/// factor of its complex Schur form. nalgebra's QR iteration has no
/// exceptional shifts, so it is capped and, if it stalls, rerun on unitary
/// similarities of the matrix (same eigenvalues, same condition numbers).
fn eigenvalues(m: DMatrix<Complex<f64>>) -> Vec<Complex<f64>> {
    let max_sweeps = QR_SWEEPS_PER_EIGENVALUE * m.nrows() + QR_SWEEPS_EXTRA;
    let schur_diagonal = |m: &DMatrix<Complex<f64>>| {
        Schur::try_new(m.clone(), EPS, max_sweeps)
            .map(|s| s.unpack().1.diagonal().iter().copied().collect::<Vec<_>>())
    };
    if let Some(d) = schur_diagonal(&m) {
        return d;
    }
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut current = m;
    for _ in 0..QR_RETRIES {
        current = householder_similarity(&current, &mut seed);
        if let Some(d) = schur_diagonal(&current) {
            return d;
        }
    }
    // Not observed. Candidates from the diagonal are still verified by the
    // caller, so nothing wrong is returned, but roots may be missing.
    current.diagonal().iter().copied().collect()
}

/// `H m H` with the Householder reflector `H = I - 2 v v*/(v* v)` (unitary and
/// Hermitian) for a deterministic pseudo-random `v`.
fn householder_similarity(m: &DMatrix<Complex<f64>>, seed: &mut u64) -> DMatrix<Complex<f64>> {
    let n = m.nrows();
    let mut next = || {
        // xorshift64*
        *seed ^= *seed >> 12;
        *seed ^= *seed << 25;
        *seed ^= *seed >> 27;
        let x = seed.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let v = DVector::<Complex<f64>>::from_fn(n, |_, _| Complex::new(next(), next()));
    let scale = Complex::new(2.0 / v.norm_squared(), 0.0);
    let h = DMatrix::<Complex<f64>>::identity(n, n) - (&v * v.adjoint()) * scale;
    &h * m * &h
}
