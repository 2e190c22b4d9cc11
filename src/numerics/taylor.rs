//! Taylor coefficients of a harmonic series about a point, all harmonics
//! at once (docs/model.md section 8: the models of the root finder and the
//! slices of a series of many harmonics).
//!
//! For `p(θ) = Σ_{k=1}^{n} (a_k cos kθ + b_k sin kθ)` and `θ = m + r s`,
//!
//! ```text
//! p(m + r s) = Σ_j g_j s^j,   g_j = Σ_k (k r)^j / j! · Re(i^j W_k),   W_k = (a_k - i b_k) e^{i k m},
//! ```
//!
//! [`powers`] gives the factors `(k r)^j / j!`, [`harmonic_sums`] the
//! first `J` coefficients `g_j` from one `sin_cos` of `m` and the rotation
//! recurrence for `e^{i k m}`: `O(J n)`. The constant term of the series is
//! not included. The rounding of the result is bounded in the module
//! documentation of the root finder ((R1)-(R3)).

/// `(k r)^j / j!` for `k = 1..=n` (row `k - 1`) and `j < J`.
pub(crate) fn powers<const J: usize>(n: usize, r: f64) -> Vec<[f64; J]> {
    (1..=n)
        .map(|k| {
            let x = k as f64 * r;
            let mut t = [0.0; J];
            t[0] = 1.0;
            for j in 1..J {
                t[j] = t[j - 1] * x / j as f64;
            }
            t
        })
        .collect()
}

/// `g_j`, `j < J`, of the harmonics `a`, `b` about `m` (module docs), with
/// `powers` from [`powers`] for the same `r` (at least as many rows as
/// harmonics are used: the shortest of the three slices decides).
pub(crate) fn harmonic_sums<const J: usize>(
    a: &[f64],
    b: &[f64],
    powers: &[[f64; J]],
    m: f64,
) -> [f64; J] {
    let (s1, c1) = m.sin_cos();
    let (mut ck, mut sk) = (1.0, 0.0);
    let mut g = [0.0; J];
    for ((&ak, &bk), t) in a.iter().zip(b).zip(powers) {
        let c = ck * c1 - sk * s1;
        sk = sk * c1 + ck * s1;
        ck = c;
        // W_k = (a_k - i b_k) e^{ikm} = u + i v; Re(i^j W) = u, -v, -u, v
        let u = ak * ck + bk * sk;
        let v = ak * sk - bk * ck;
        let cycle = [u, -v, -u, v];
        for j in 0..J {
            g[j] += t[j] * cycle[j % 4];
        }
    }
    g
}
