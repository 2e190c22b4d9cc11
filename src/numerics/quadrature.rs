//! Gauss-Legendre quadrature: `integral_a^b f ≈ (b - a)/2 sum_i w_i f(m + r x_i)`
//! with the `n` roots `x_i` of the Legendre polynomial `P_n` and weights
//! `w_i = 2 / ((1 - x_i^2) P_n'(x_i)^2)`, exact for polynomials of degree
//! `2n - 1`. For a function analytic in a Bernstein ellipse of parameter
//! `rho` around `[a, b]` the error falls like `rho^(-2n)`: on pieces short
//! against the function's shortest oscillation a rule of 12 points is
//! exact to rounding.
//!
//! Nodes come from Newton's method on `P_n` (three-term recurrence) from
//! the Chebyshev-like first guesses `cos(pi (i - 1/4) / (n + 1/2))`,
//! converged to rounding.

use std::f64::consts::PI;

/// A Gauss-Legendre rule on `[-1, 1]`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The rule of `n >= 1` points.
    pub(crate) fn new(n: usize) -> Self {
        let n = n.max(1);
        let mut nodes = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        for i in 1..=n {
            let mut x = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() <= 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre(n, x);
            dp = if d.is_finite() { d } else { dp };
            nodes.push(x);
            weights.push(2.0 / ((1.0 - x * x) * dp * dp));
        }
        Self { nodes, weights }
    }

    /// `integral_a^b f(t) dt` on `pieces` equal pieces.
    pub(crate) fn integrate(&self, f: impl Fn(f64) -> f64, a: f64, b: f64, pieces: usize) -> f64 {
        let pieces = pieces.max(1);
        let h = (b - a) / pieces as f64;
        let r = 0.5 * h;
        let mut sum = 0.0;
        for j in 0..pieces {
            let m = a + (j as f64 + 0.5) * h;
            let piece: f64 = self
                .nodes
                .iter()
                .zip(&self.weights)
                .map(|(x, w)| w * f(m + r * x))
                .sum();
            sum += r * piece;
        }
        sum
    }

    /// The points `t` and weights `w` of the rule on `pieces` equal pieces
    /// of `[a, b]`: `integral_a^b f(t) dt ≈ sum w f(t)` (the sum
    /// [`GaussLegendre::integrate`] forms, for a caller that sums several
    /// functions, or their magnitudes, at the same points).
    pub(crate) fn points(&self, a: f64, b: f64, pieces: usize) -> impl Iterator<Item = [f64; 2]> {
        let pieces = pieces.max(1);
        let h = (b - a) / pieces as f64;
        let r = 0.5 * h;
        (0..pieces).flat_map(move |j| {
            let m = a + (j as f64 + 0.5) * h;
            self.nodes
                .iter()
                .zip(&self.weights)
                .map(move |(x, w)| [m + r * x, r * w])
        })
    }
}

/// `P_n(x)` and `P_n'(x)`.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact for polynomials of degree 2n - 1 (here x^(2n-1) + x^(2n-2)
    /// on [0, 1], integral 1/(2n) + 1/(2n-1)); the weights sum to 2.
    #[test]
    fn exact_for_polynomials_up_to_degree_2n_minus_1() {
        for n in [1, 2, 5, 12] {
            let g = GaussLegendre::new(n);
            let sum: f64 = g.weights.iter().sum();
            assert!((sum - 2.0).abs() < 1e-14, "n = {n}: weights sum to {sum}");
            let d = 2 * n as i32 - 1;
            let f = |x: f64| x.powi(d) + if d >= 1 { x.powi(d - 1) } else { 0.0 };
            let exact = 1.0 / (d + 1) as f64 + if d >= 1 { 1.0 / d as f64 } else { 0.0 };
            let got = g.integrate(f, 0.0, 1.0, 1);
            assert!(
                (got - exact).abs() < 1e-14,
                "n = {n}: {got} against {exact}"
            );
        }
    }

    /// The points and weights sum what `integrate` sums: the weights add
    /// up to the interval's length, and `x^5` on `[0, 2]` on three pieces
    /// is its integral `2^6 / 6` (exact for degree `2n - 1 = 23`).
    #[test]
    fn the_points_and_weights_integrate_as_the_rule_does() {
        let g = GaussLegendre::new(12);
        let length: f64 = g.points(0.0, 2.0, 3).map(|[_, w]| w).sum();
        assert!((length - 2.0).abs() < 1e-15, "{length}");
        let sum: f64 = g.points(0.0, 2.0, 3).map(|[t, w]| w * t.powi(5)).sum();
        assert!((sum - 64.0 / 6.0).abs() < 1e-13, "{sum}");
        assert_eq!(g.points(0.0, 2.0, 3).count(), 36);
    }

    /// An oscillating function to rounding: integral of sin^2(7 t) over
    /// [0, pi] is pi / 2.
    #[test]
    fn an_oscillation_on_short_pieces_to_rounding() {
        let g = GaussLegendre::new(12);
        let got = g.integrate(|t| (7.0 * t).sin().powi(2), 0.0, PI, 14);
        assert!((got - PI / 2.0).abs() < 1e-14, "{got}");
    }
}
