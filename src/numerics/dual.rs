//! Forward-mode derivatives: a value with its gradient in `N` directions,
//! `a + sum_i g_i e_i` with `e_i e_j = 0`. Every operation applies the
//! chain rule exactly (`(a b)' = a' b + a b'`, `exp(a)' = exp(a) a'`, ...),
//! so a closed form evaluated on duals returns its value and its exact
//! first derivatives, to rounding.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its derivatives in `N` directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dual<const N: usize> {
    /// The value.
    pub v: f64,
    /// The derivatives.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant: all derivatives zero.
    pub(crate) fn constant(v: f64) -> Self {
        Self { v, d: [0.0; N] }
    }

    /// The `i`-th variable at `v`: derivative 1 in direction `i`.
    pub(crate) fn variable(v: f64, i: usize) -> Self {
        let mut d = [0.0; N];
        d[i] = 1.0;
        Self { v, d }
    }

    /// `f(self)` with `f(v)` and `f'(v)` given.
    fn chain(self, f: f64, df: f64) -> Self {
        Self {
            v: f,
            d: self.d.map(|g| df * g),
        }
    }

    pub(crate) fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e)
    }

    pub(crate) fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.chain(r, 0.5 / r)
    }

    /// `(sin, cos)`.
    pub(crate) fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.v.sin_cos();
        (self.chain(s, c), self.chain(c, -s))
    }

    /// `(sinh, cosh)`.
    pub(crate) fn sinh_cosh(self) -> (Self, Self) {
        let (s, c) = (self.v.sinh(), self.v.cosh());
        (self.chain(s, c), self.chain(c, s))
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        for (a, b) in d.iter_mut().zip(o.d) {
            *a += b;
        }
        Self { v: self.v + o.v, d }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: self.d.map(|g| -g),
        }
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for (i, di) in d.iter_mut().enumerate() {
            *di = self.d[i] * o.v + self.v * o.d[i];
        }
        Self { v: self.v * o.v, d }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        let mut d = [0.0; N];
        for (i, di) in d.iter_mut().enumerate() {
            *di = (self.d[i] - q * o.d[i]) * inv;
        }
        Self { v: q, d }
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    fn add(self, o: f64) -> Self {
        Self {
            v: self.v + o,
            d: self.d,
        }
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    fn sub(self, o: f64) -> Self {
        self + (-o)
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    fn mul(self, o: f64) -> Self {
        Self {
            v: self.v * o,
            d: self.d.map(|g| g * o),
        }
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    fn div(self, o: f64) -> Self {
        self * (1.0 / o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The derivative of `f(x, y) = exp(x y) sin(x) / sqrt(y) + cosh(x - y)`
    /// against its closed-form partial derivatives.
    #[test]
    fn derivatives_of_a_composite_function_are_the_closed_form() {
        let (x0, y0) = (0.7, 1.9);
        let x = Dual::<2>::variable(x0, 0);
        let y = Dual::<2>::variable(y0, 1);
        let (s, _) = x.sin_cos();
        let (_, ch) = (x - y).sinh_cosh();
        let f = (x * y).exp() * s / y.sqrt() + ch;
        let e = (x0 * y0).exp();
        let dfx = e * y0 * x0.sin() / y0.sqrt() + e * x0.cos() / y0.sqrt() + (x0 - y0).sinh();
        let dfy =
            e * x0 * x0.sin() / y0.sqrt() - 0.5 * e * x0.sin() * y0.powf(-1.5) - (x0 - y0).sinh();
        assert!((f.d[0] - dfx).abs() < 1e-13 * dfx.abs());
        assert!((f.d[1] - dfy).abs() < 1e-13 * dfy.abs().max(1.0));
    }
}
