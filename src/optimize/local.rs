//! Local refinement: BFGS with a weak Wolfe line search, as Lewis and
//! Overton use it for functions that are smooth almost everywhere but not
//! at their optimum (A. S. Lewis, M. L. Overton, *Nonsmooth optimization
//! via quasi-Newton methods*, Math. Program. 141 (2013) 135-163);
//! docs/model.md section 15.
//!
//! `v_inf` as a function of the signal is smooth where the event structure
//! of the steady orbit stays the same and has a kink where it changes (a
//! stick phase appears, a reversal becomes a stick). Optima often lie on
//! such a kink: on one side more slip, on the other a stick phase. A
//! method for smooth functions (Newton, BFGS with a strong Wolfe line
//! search) stalls there; BFGS with the weak Wolfe conditions does not
//! need the function to be smooth at the optimum and in practice
//! converges to it, its inverse Hessian approximation growing
//! ill-conditioned across the kink.
//!
//! Each iteration takes the direction `d = H g` (ascent: this maximises),
//! then a step `t` satisfying the weak Wolfe conditions
//!
//! ```text
//! f(z + t d) >= f(z) + c1 t g.d            (sufficient increase)
//! g(z + t d).d <= c2 g.d                   (the slope has fallen)
//! ```
//!
//! with `c1 = 1e-4`, `c2 = 0.9`, found by doubling and bisection, and
//! updates `H` by the BFGS formula when `s.y < 0` (curvature of a
//! maximisation). When the line search fails along `H g` the iteration is
//! repeated once along the gradient itself, with the last step's length;
//! it stops when that fails too (at a nonsmooth optimum no step
//! satisfies both conditions: the usual end), when a step is below
//! `min_step`, when the merit has not risen by a relative `1e-13` over
//! five iterations, or after `max_iterations`. Nothing here is a proof
//! of optimality: the result is a point the method could not improve.

/// Settings of one local refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalOptions {
    /// Most iterations.
    pub max_iterations: usize,
    /// Length of the first step (coordinates, rad).
    pub first_step: f64,
    /// A step shorter than this ends the search.
    pub min_step: f64,
}

impl Default for LocalOptions {
    fn default() -> Self {
        LocalOptions {
            max_iterations: 100,
            first_step: 0.05,
            min_step: 1e-10,
        }
    }
}

/// Why a refinement stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// No step satisfied the line search (a nonsmooth optimum, or the
    /// resolution of the values reached).
    LineSearch,
    /// The step fell below `min_step`, or the merit stopped rising.
    Converged,
    /// `max_iterations` reached.
    Iterations,
    /// The gradient is zero, or could not be computed.
    Gradient,
}

impl Stop {
    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Stop::LineSearch => "line_search",
            Stop::Converged => "converged",
            Stop::Iterations => "iterations",
            Stop::Gradient => "gradient",
        }
    }
}

/// The end of one refinement.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct LocalResult {
    /// The last accepted point.
    pub z: Vec<f64>,
    /// Its merit.
    pub value: f64,
    /// The merit after each accepted step (the start first).
    pub history: Vec<f64>,
    /// Why it stopped.
    pub stop: Stop,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// `H v` for a dense symmetric `H`.
fn apply(h: &[Vec<f64>], v: &[f64]) -> Vec<f64> {
    h.iter().map(|row| dot(row, v)).collect()
}

fn scaled_identity(n: usize, s: f64) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| (0..n).map(|j| if i == j { s } else { 0.0 }).collect())
        .collect()
}

/// Maximises `value` from `z0` (whose value is `f0`), with `gradient`
/// giving the derivatives (`None` ends the search); `on_step` hears of
/// every accepted step (its number from 1, the new value). Module docs.
pub(super) fn maximise(
    z0: &[f64],
    f0: f64,
    mut value: impl FnMut(&[f64]) -> f64,
    mut gradient: impl FnMut(&[f64]) -> Option<Vec<f64>>,
    mut on_step: impl FnMut(usize, f64),
    options: &LocalOptions,
) -> LocalResult {
    const C1: f64 = 1e-4;
    const C2: f64 = 0.9;
    const TRIALS: usize = 40;
    let n = z0.len();
    let mut z = z0.to_vec();
    let mut f = f0;
    let mut history = vec![f];
    let finish = |z: Vec<f64>, f: f64, history: Vec<f64>, stop: Stop| LocalResult {
        z,
        value: f,
        history,
        stop,
    };
    let Some(mut g) = gradient(&z) else {
        return finish(z, f, history, Stop::Gradient);
    };
    let g_norm = norm(&g);
    if !(g_norm > 0.0 && g_norm.is_finite()) {
        return finish(z, f, history, Stop::Gradient);
    }
    let mut h = scaled_identity(n, options.first_step / g_norm);
    let mut first = true;
    // True while H is a fresh multiple of the identity.
    let mut fresh = true;
    let mut history_step = options.first_step;
    for _ in 0..options.max_iterations {
        let mut d = apply(&h, &g);
        let mut slope = dot(&g, &d);
        if slope.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            // Not an ascent direction (rounding in H): restart from the
            // gradient.
            h = scaled_identity(n, options.first_step / norm(&g).max(f64::MIN_POSITIVE));
            d = apply(&h, &g);
            slope = dot(&g, &d);
            if slope.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return finish(z, f, history, Stop::Gradient);
            }
        }
        // Weak Wolfe line search: doubling, then bisection.
        let (mut lo, mut hi) = (0.0, f64::INFINITY);
        let mut t = 1.0;
        let mut accepted: Option<(Vec<f64>, f64, Vec<f64>)> = None;
        let mut at_lo: Option<(Vec<f64>, f64, Vec<f64>)> = None;
        for _ in 0..TRIALS {
            let zt: Vec<f64> = z.iter().zip(&d).map(|(a, b)| a + t * b).collect();
            let ft = value(&zt);
            let increase = f + C1 * t * slope;
            if ft
                .partial_cmp(&increase)
                .is_none_or(|o| o == std::cmp::Ordering::Less)
            {
                hi = t;
            } else {
                let Some(gt) = gradient(&zt) else {
                    hi = t;
                    t = 0.5 * (lo + hi);
                    continue;
                };
                if dot(&gt, &d) > C2 * slope {
                    lo = t;
                    at_lo = Some((zt, ft, gt));
                } else {
                    accepted = Some((zt, ft, gt));
                    break;
                }
            }
            t = if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * t
            };
        }
        let Some((zt, ft, gt)) = accepted.or(at_lo) else {
            if fresh {
                return finish(z, f, history, Stop::LineSearch);
            }
            // The quasi-Newton direction failed: once more along the
            // gradient, with a step as short as the last one.
            let last = history_step.max(options.min_step);
            h = scaled_identity(n, last / norm(&g).max(f64::MIN_POSITIVE));
            fresh = true;
            continue;
        };
        fresh = false;
        let s: Vec<f64> = zt.iter().zip(&z).map(|(a, b)| a - b).collect();
        // For a maximisation the curvature condition is s.y < 0 with
        // y = g_new - g; BFGS runs on -f, whose y is -(g_new - g).
        let y: Vec<f64> = g.iter().zip(&gt).map(|(a, b)| a - b).collect();
        z = zt;
        f = ft;
        g = gt;
        history.push(f);
        on_step(history.len() - 1, f);
        history_step = norm(&s);
        if history_step < options.min_step {
            return finish(z, f, history, Stop::Converged);
        }
        let k = history.len();
        if k > 5 && history[k - 1] - history[k - 6] <= 1e-13 * history[k - 1].abs() {
            return finish(z, f, history, Stop::Converged);
        }
        let sy = dot(&s, &y);
        if sy > 0.0 {
            if first {
                h = scaled_identity(n, sy / dot(&y, &y));
                first = false;
            }
            // H <- (I - rho s y^T) H (I - rho y s^T) + rho s s^T.
            let rho = 1.0 / sy;
            let hy = apply(&h, &y);
            let yhy = dot(&y, &hy);
            for i in 0..n {
                for j in 0..n {
                    h[i][j] += -rho * (s[i] * hy[j] + hy[i] * s[j])
                        + (rho * rho * yhy + rho) * s[i] * s[j];
                }
            }
        }
    }
    finish(z, f, history, Stop::Iterations)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth concave quadratic: the maximum at (1, -2).
    #[test]
    fn finds_the_maximum_of_a_quadratic() {
        let f = |z: &[f64]| -(z[0] - 1.0).powi(2) - 10.0 * (z[1] + 2.0).powi(2);
        let g = |z: &[f64]| Some(vec![-2.0 * (z[0] - 1.0), -20.0 * (z[1] + 2.0)]);
        let r = maximise(
            &[0.0, 0.0],
            f(&[0.0, 0.0]),
            f,
            g,
            |_, _| {},
            &LocalOptions::default(),
        );
        assert!(
            (r.z[0] - 1.0).abs() < 1e-6 && (r.z[1] + 2.0).abs() < 1e-6,
            "{r:?}"
        );
    }

    /// A kink along a line (the maximum of `min(a, b)` of two planes, in
    /// a concave bowl): the maximum at (0.5, 0.5) lies on the kink
    /// `z0 = z1`, where the gradient jumps. The known answer: the bowl
    /// `-(z0^2 + z1^2)` plus `-|z0 - z1|` plus `z0 + z1` has its maximum
    /// where `z0 = z1` and `1 - 2 z = 0`.
    #[test]
    fn finds_a_maximum_on_a_kink() {
        let f = |z: &[f64]| z[0] + z[1] - z[0] * z[0] - z[1] * z[1] - 3.0 * (z[0] - z[1]).abs();
        let g = |z: &[f64]| {
            let s = (z[0] - z[1]).signum();
            Some(vec![1.0 - 2.0 * z[0] - 3.0 * s, 1.0 - 2.0 * z[1] + 3.0 * s])
        };
        let start = [0.9, -0.3];
        let r = maximise(&start, f(&start), f, g, |_, _| {}, &LocalOptions::default());
        assert!(
            (r.z[0] - 0.5).abs() < 1e-5 && (r.z[1] - 0.5).abs() < 1e-5,
            "{r:?}"
        );
    }
}
