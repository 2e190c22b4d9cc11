//! Fast evaluation of a harmonic series of many harmonics: Taylor
//! polynomials on slices of the period (docs/model.md section 8,
//! "Evaluating a series of many harmonics").
//!
//! A series `x_R(t) = c_0 + Σ_{k=1}^{n} (A_k cos kθ + B_k sin kθ)`,
//! `θ = w_0 t`, costs `O(n)` per evaluation (one `sin_cos`, then `n` steps
//! of the angle-addition recurrence, a chain of dependent products). The
//! engine evaluates `v_R` and `a_R` a few times per event and at the end of
//! pieces of the period, so for `n` in the hundreds these evaluations are
//! almost all of a run. Here the period is cut into `N = ⌈π n / 2⌉` equal
//! slices of half-width `r = π / N` in `θ` (so `n r ≤ 2`), and on slice `i`,
//! centred at `m_i = (i + 1/2) 2π / N`, with `θ = m_i + r s`, `s ∈ [-1, 1]`,
//!
//! ```text
//! x_R = c_0 + Σ_{j<J} g_j s^j + R,   g_j = Σ_k (k r)^j / j! · Re(i^j W_k),   W_k = (A_k - i B_k) e^{i k m_i},
//! ```
//!
//! with `J = 28` terms: the Taylor expansion of every harmonic, exactly the
//! models of the root finder (section 8, step 1). Velocity, acceleration
//! and jerk are the term-wise derivatives, `d/dt = (w_0 / r) d/ds`, with
//! `J - 1`, `J - 2` and `J - 3` terms. The remainders are those of the
//! Lagrange form: at most `Σ_k |W_k| (w_0 k)^q (k r)^(J-q) / (J-q)!` for the
//! `q`-th derivative, below `2^25 / 25! = 2.2e-18` of `Σ_k |(A_k, B_k)| (k w_0)^q`
//! for every `q ≤ 3`: far below the rounding of either evaluation.
//!
//! An evaluation is one slice lookup and one Horner pass per quantity,
//! about 30 multiply-adds instead of `n` steps of the recurrence. Building the slices costs
//! `O(J n N) = O(n^2)` once per signal, as the root finder's models do.
//!
//! **Contract.** For `n ≥` [`MIN_HARMONICS`] a signal built by
//! `Signal::build` evaluates through the slices; below, the recurrence is
//! cheaper and is kept. The two differ by rounding only: both are computed
//! from the same coefficients, the slices add the truncation above and the
//! rounding of the Horner pass (`≤ 2 J ε Σ_j |coefficient_j|`, which
//! [`Piecewise::velocity_rounding`] and [`Piecewise::acceleration_rounding`]
//! add to the signal's rounding bounds).
//! `tests/piecewise.rs` compares the two on random series up to `n = 256`.

use crate::numerics::taylor;
use std::f64::consts::{PI, TAU};

/// Fewest harmonics for which a signal evaluates through slices.
pub(crate) const MIN_HARMONICS: usize = 16;
/// Terms of the position polynomial of a slice.
const ORDER: usize = 28;
/// Bound on `n r`.
const NR: f64 = 2.0;

/// The Taylor polynomials of `x_R`, `v_R`, `a_R` and `da_R/dt` on one slice,
/// in the slice variable `s` (coefficients of `s^j`, time derivatives
/// included).
#[derive(Debug, Clone)]
struct Slice {
    x: [f64; ORDER],
    v: [f64; ORDER - 1],
    a: [f64; ORDER - 2],
    jerk: [f64; ORDER - 3],
}

/// A harmonic series as Taylor polynomials on `N` slices of its period
/// (module docs).
#[derive(Debug, Clone)]
pub(crate) struct Piecewise {
    omega: f64,
    /// `N / 2π`: slices per radian.
    per_radian: f64,
    /// Half-width of a slice in `θ`.
    r: f64,
    slices: Vec<Slice>,
    /// Bound on the Horner rounding of a computed `v_R` (m/s).
    v_rounding: f64,
    /// Bound on the rounding of a computed `a_R`: Horner pass and slice
    /// coefficients (m/s^2).
    a_rounding: f64,
}

impl Piecewise {
    /// The slices of `c0 + Σ (cos[k-1] cos kθ + sin[k-1] sin kθ)`,
    /// `θ = omega t`.
    pub(crate) fn new(omega: f64, c0: f64, cos: &[f64], sin: &[f64]) -> Self {
        let n = cos.len();
        let count = ((PI * n as f64 / NR).ceil() as usize).max(3);
        let r = PI / count as f64;
        let powers = taylor::powers::<ORDER>(n, r);
        let d = omega / r;
        let h = TAU / count as f64;
        let mut v_rounding: f64 = 0.0;
        let mut a_rounding: f64 = 0.0;
        let slices: Vec<Slice> = (0..count)
            .map(|i| {
                let m = (i as f64 + 0.5) * h;
                let g = taylor::harmonic_sums(cos, sin, &powers, m);
                let mut slice = Slice {
                    x: g,
                    v: [0.0; ORDER - 1],
                    a: [0.0; ORDER - 2],
                    jerk: [0.0; ORDER - 3],
                };
                slice.x[0] += c0;
                for (j, &gj) in g.iter().enumerate().skip(1) {
                    let fj = j as f64;
                    slice.v[j - 1] = fj * d * gj;
                    if j >= 2 {
                        slice.a[j - 2] = fj * (fj - 1.0) * d * d * gj;
                    }
                    if j >= 3 {
                        slice.jerk[j - 3] = fj * (fj - 1.0) * (fj - 2.0) * d * d * d * gj;
                    }
                }
                let mass: f64 = slice.v.iter().map(|c| c.abs()).sum();
                v_rounding = v_rounding.max(mass);
                a_rounding = a_rounding.max(slice.a.iter().map(|c| c.abs()).sum());
                slice
            })
            .collect();
        Self {
            omega,
            per_radian: count as f64 / TAU,
            r,
            slices,
            v_rounding: 4.0 * ORDER as f64 * f64::EPSILON * v_rounding,
            a_rounding: 4.0 * ORDER as f64 * f64::EPSILON * a_rounding
                + coefficient_rounding(omega, r, cos, sin),
        }
    }

    /// A bound on the rounding of the Horner pass of a computed `v_R`,
    /// `4 J ε max_i Σ_j |v_ij|` (twice the usual `2 J ε` bound of Horner's
    /// rule on `|s| ≤ 1`).
    pub(crate) fn velocity_rounding(&self) -> f64 {
        self.v_rounding
    }

    /// A bound on the rounding of a computed `a_R`: the Horner pass,
    /// `4 J ε max_i Σ_j |a_ij|`, and the rounding of the slices'
    /// coefficients themselves (`coefficient_rounding`).
    pub(crate) fn acceleration_rounding(&self) -> f64 {
        self.a_rounding
    }

    /// The slice of phase `tau` and the slice variable `s`.
    #[inline]
    fn locate(&self, tau: f64) -> (&Slice, f64) {
        let mut theta = self.omega * tau;
        if !(0.0..TAU).contains(&theta) {
            theta = theta.rem_euclid(TAU);
        }
        let last = self.slices.len() - 1;
        let i = ((theta * self.per_radian) as usize).min(last);
        let m = (i as f64 + 0.5) / self.per_radian;
        (&self.slices[i], (theta - m) / self.r)
    }

    /// `x_R(tau)`.
    #[inline]
    pub(crate) fn position(&self, tau: f64) -> f64 {
        let (slice, s) = self.locate(tau);
        horner(&slice.x, s)
    }

    /// `v_R(tau)`.
    #[inline]
    pub(crate) fn velocity(&self, tau: f64) -> f64 {
        let (slice, s) = self.locate(tau);
        horner(&slice.v, s)
    }

    /// `a_R(tau)`.
    #[inline]
    pub(crate) fn acceleration(&self, tau: f64) -> f64 {
        let (slice, s) = self.locate(tau);
        horner(&slice.a, s)
    }

    /// `(v_R, a_R)` at `tau`.
    #[inline]
    pub(crate) fn velocity_acceleration(&self, tau: f64) -> (f64, f64) {
        let (slice, s) = self.locate(tau);
        (horner(&slice.v, s), horner(&slice.a, s))
    }

    /// `(x_R, v_R, a_R)` at `tau`.
    #[inline]
    pub(crate) fn state(&self, tau: f64) -> (f64, f64, f64) {
        let (slice, s) = self.locate(tau);
        (
            horner(&slice.x, s),
            horner(&slice.v, s),
            horner(&slice.a, s),
        )
    }

    /// `da_R/dt` at `tau`.
    pub(crate) fn jerk(&self, tau: f64) -> f64 {
        let (slice, s) = self.locate(tau);
        horner(&slice.jerk, s)
    }
}

/// A bound on the error of `a_R` on a slice from the rounding of the
/// slice's coefficients: the bound (R1)-(R3) of the root finder's models
/// (`numerics::trig_roots`, step 1), `ε (5k + n + 3J + 6) (|A_k| + |B_k|)
/// (k r)^j / j!` on the `k`-th term of `g_j`, carried through
/// `a_j = j (j - 1) (w_0 / r)^2 g_j` and summed over `j` at `|s| <= 1`:
/// `ε Σ_k (5k + n + 3J + 6) (k w_0)^2 (|A_k| + |B_k|) e^{k r}`.
fn coefficient_rounding(omega: f64, r: f64, cos: &[f64], sin: &[f64]) -> f64 {
    let n = cos.len() as f64;
    let sum: f64 = cos
        .iter()
        .zip(sin)
        .enumerate()
        .map(|(i, (a, b))| {
            let k = (i + 1) as f64;
            (5.0 * k + n + 3.0 * ORDER as f64 + 6.0)
                * (k * omega).powi(2)
                * (a.abs() + b.abs())
                * (k * r).exp()
        })
        .sum();
    f64::EPSILON * sum
}

/// `Σ c_j s^j` by Horner's rule.
#[inline]
fn horner(c: &[f64], s: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &cj| acc * s + cj)
}
