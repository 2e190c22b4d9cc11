//! An independent integrator of the driven rod's equation in one mode
//! (docs/model.md section 16), for the dense scans of
//! `tests/driven_events.rs` and `examples/driven_events.rs`:
//!
//! ```text
//! M_m x'' + d x' + c x = alpha u(t) + F_m,
//! u(t) = u_0 + sum_k (P_k cos k w t + Q_k sin k w t),
//! ```
//!
//! solved by its Taylor series, not by the closed form the engine uses.
//! With `x(t_0 + theta h) = sum_j D_j theta^j` (`D_j = x^(j)(t_0) h^j / j!`)
//! the equation gives, power by power,
//!
//! ```text
//! D_{j+2} = (h^2 (alpha U_j + F_m [j = 0] - c D_j) - d (j + 1) h D_{j+1}) / (M_m (j + 1) (j + 2)),
//! U_j = u^(j)(t_0) h^j / j!,   u^(j) = sum_k (k w)^j (P_k cos(k w t + j pi/2) + Q_k sin(k w t + j pi/2)),
//! ```
//!
//! from `D_0 = x(t_0)`, `D_1 = h v(t_0)`. A step `h` with `Omega h <= 1/2`,
//! where `Omega` bounds every rate of the solution (the top harmonic's
//! `n w` and the free oscillation's characteristic roots), makes the terms
//! fall at least like `2^-j / j!`: the series to degree 24 is exact to
//! rounding (its remainder is below `1e-30` of the solution). Each step
//! starts from the last one's end, so a segment is a chain of polynomials,
//! which also give the solution's derivatives at any point (dense output).

#![allow(dead_code)] // each includer uses a part

/// Degree of the Taylor polynomials.
pub const DEGREE: usize = 24;

/// One mode's equation.
#[derive(Debug, Clone)]
pub struct ModeOde {
    /// `M_m` (kg).
    pub mass: f64,
    /// `d` (N s/m).
    pub damping: f64,
    /// `c` (N/m).
    pub stiffness: f64,
    /// `alpha` (N/V).
    pub alpha: f64,
    /// `F_m` (N).
    pub force: f64,
    /// `u_0` (V).
    pub offset: f64,
    /// `w` (rad/s).
    pub w: f64,
    /// `P_k`, `Q_k` (V).
    pub cos: Vec<f64>,
    pub sin: Vec<f64>,
}

impl ModeOde {
    /// The fastest rate of the solution (1/s): the top harmonic's and the
    /// free oscillation's characteristic roots `|-sigma +- sqrt(sigma^2 - omega_0^2)|`.
    pub fn rate(&self) -> f64 {
        let sigma = self.damping / (2.0 * self.mass);
        let w0 = (self.stiffness / self.mass).sqrt();
        let root = sigma + (sigma * sigma - w0 * w0).abs().sqrt();
        (self.cos.len() as f64 * self.w).max(root).max(w0)
    }

    /// `u(t)` and `u'(t)`.
    pub fn voltage(&self, t: f64) -> [f64; 2] {
        let (mut u, mut du) = (self.offset, 0.0);
        for (k, (p, q)) in self.cos.iter().zip(&self.sin).enumerate() {
            let kw = (k + 1) as f64 * self.w;
            let (s, c) = (kw * t).sin_cos();
            u += p * c + q * s;
            du += kw * (q * c - p * s);
        }
        [u, du]
    }

    /// `x''` from the equation at `(t, x, v)`.
    pub fn acceleration(&self, t: f64, x: f64, v: f64) -> f64 {
        let u = self.voltage(t)[0];
        (self.alpha * u + self.force - self.damping * v - self.stiffness * x) / self.mass
    }

    /// `x'''` from the differentiated equation at `(t, x, v)`.
    pub fn jerk(&self, t: f64, x: f64, v: f64) -> f64 {
        let a = self.acceleration(t, x, v);
        let du = self.voltage(t)[1];
        (self.alpha * du - self.damping * a - self.stiffness * v) / self.mass
    }

    /// `U_j = u^(j)(t) h^j / j!`, `j = 0..=DEGREE`.
    fn forcing(&self, t: f64, h: f64) -> [f64; DEGREE + 1] {
        let mut out = [0.0; DEGREE + 1];
        out[0] = self.offset;
        for (k, (p, q)) in self.cos.iter().zip(&self.sin).enumerate() {
            let kw = (k + 1) as f64 * self.w;
            let (s, c) = (kw * t).sin_cos();
            let mut r = 1.0;
            for (j, o) in out.iter_mut().enumerate() {
                let term = match j % 4 {
                    0 => p * c + q * s,
                    1 => q * c - p * s,
                    2 => -(p * c + q * s),
                    _ => p * s - q * c,
                };
                *o += r * term;
                r *= kw * h / (j + 1) as f64;
            }
        }
        out
    }

    /// The Taylor polynomial of one step of length `h` from `(x, v)` at `t`.
    fn step(&self, t: f64, x: f64, v: f64, h: f64) -> [f64; DEGREE + 1] {
        let u = self.forcing(t, h);
        let mut d = [0.0; DEGREE + 1];
        d[0] = x;
        d[1] = h * v;
        for j in 0..=DEGREE - 2 {
            let f = if j == 0 { self.force } else { 0.0 };
            let jf = j as f64;
            d[j + 2] = (h * h * (self.alpha * u[j] + f - self.stiffness * d[j])
                - self.damping * (jf + 1.0) * h * d[j + 1])
                / (self.mass * (jf + 1.0) * (jf + 2.0));
        }
        d
    }
}

/// The solution over `[t_0, t_0 + span]` as a chain of Taylor steps.
#[derive(Debug, Clone)]
pub struct Solution {
    /// `x, x', x'', x'''` at the start, from the equation.
    start: [f64; 4],
    h: f64,
    steps: Vec<[f64; DEGREE + 1]>,
}

impl Solution {
    /// Integrates `ode` from `(x, v)` at `t0` over `span >= 0`.
    pub fn new(ode: &ModeOde, t0: f64, x0: f64, v0: f64, span: f64) -> Self {
        let count = ((span * ode.rate() / 0.5).ceil() as usize).max(1);
        let h = span / count as f64;
        let mut steps = Vec::with_capacity(count);
        let (mut x, mut v) = (x0, v0);
        for k in 0..count {
            let d = ode.step(t0 + k as f64 * h, x, v, h);
            let [x1, v1, _, _] = eval(&d, 1.0, h);
            steps.push(d);
            x = x1;
            v = v1;
        }
        let a = ode.acceleration(t0, x0, v0);
        let j = ode.jerk(t0, x0, v0);
        Self {
            start: [x0, v0, a, j],
            h,
            steps,
        }
    }

    /// `x, x', x'', x'''` at `s` in `[0, span]` after the start.
    pub fn at(&self, s: f64) -> [f64; 4] {
        if self.h == 0.0 {
            return self.start;
        }
        let k = ((s / self.h).floor().max(0.0) as usize).min(self.steps.len() - 1);
        let theta = (s - k as f64 * self.h) / self.h;
        eval(&self.steps[k], theta, self.h)
    }
}

/// `x, x', x'', x'''` of `sum_j d_j theta^j` at `theta`, per unit time.
fn eval(d: &[f64; DEGREE + 1], theta: f64, h: f64) -> [f64; 4] {
    let (mut p0, mut p1, mut p2, mut p3) = (0.0, 0.0, 0.0, 0.0);
    for j in (0..=DEGREE).rev() {
        let jf = j as f64;
        p0 = p0 * theta + d[j];
        if j >= 1 {
            p1 = p1 * theta + jf * d[j];
        }
        if j >= 2 {
            p2 = p2 * theta + jf * (jf - 1.0) * d[j];
        }
        if j >= 3 {
            p3 = p3 * theta + jf * (jf - 1.0) * (jf - 2.0) * d[j];
        }
    }
    [p0, p1 / h, p2 / (h * h), p3 / (h * h * h)]
}
