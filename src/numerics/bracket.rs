//! One root of a function in a bracket: safeguarded Newton (the `rtsafe`
//! scheme: Newton steps that leave the bracket or shrink too slowly are
//! replaced by bisection).
//!
//! Contract: given `lo < hi` with `f(lo)` and `f(hi)` of opposite sign (or
//! one of them zero), [`solve`] returns a `t` in `[lo, hi]` such that either
//! `|f(t)| <= f_tol` (the caller's noise level of `f`: below it the sign of
//! `f` carries no information, so the root is known as well as `f` allows)
//! or the true root lies within `tol` of `t`, where `tol` is the caller's
//! absolute tolerance in `t`. It always terminates: every step either
//! halves the bracket (bisection) or is a Newton step at most half as long
//! as the step before the last, so the steps shrink geometrically; the
//! iteration stops when a step is below `tol`, and after
//! [`MAX_ITERATIONS`] at the latest (returning the midpoint of the
//! remaining bracket). The bracket itself need not shrink when Newton
//! converges from one side. For a linear function (the relative velocity
//! under the ideal signal) the first secant step is exact.

/// Hard limit on iterations: steps that shrink at least by half every two
/// iterations fall below any tolerance above a double's resolution well
/// within 2 x 64 iterations.
pub(crate) const MAX_ITERATIONS: u32 = 128;

/// A root and what it cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Root {
    /// The root.
    pub t: f64,
    /// Iterations taken.
    pub iterations: u32,
    /// Width of the final bracket (an upper bound of the error unless the
    /// root was hit exactly, when it is 0).
    pub bracket: f64,
    /// `f'` at the last point evaluated (within the bracket width of `t`),
    /// NaN if none was evaluated.
    pub derivative: f64,
}

/// Finds a root of `f` in `[lo, hi]`; `f_and_df(t)` returns `(f(t), f'(t))`.
/// `f_lo`, `f_hi` are the known end values; `tol` is the absolute tolerance
/// in `t`, `f_tol` the noise level of `f`. A `guess` strictly inside the
/// bracket is the first iterate; otherwise the secant point is.
pub(crate) fn solve(
    mut f_and_df: impl FnMut(f64) -> (f64, f64),
    (mut lo, mut hi): (f64, f64),
    (f_lo, f_hi): (f64, f64),
    tol: f64,
    f_tol: f64,
    guess: Option<f64>,
) -> Root {
    if f_lo == 0.0 {
        return Root {
            t: lo,
            iterations: 0,
            bracket: 0.0,
            derivative: f64::NAN,
        };
    }
    if f_hi == 0.0 {
        return Root {
            t: hi,
            iterations: 0,
            bracket: 0.0,
            derivative: f64::NAN,
        };
    }
    let lo_positive = f_lo.is_sign_positive();
    debug_assert!(
        lo_positive != f_hi.is_sign_positive(),
        "bracket without a sign change"
    );
    // Secant start: exact for linear f.
    let mut t = match guess {
        Some(g) if g > lo && g < hi => g,
        _ => (lo - f_lo * (hi - lo) / (f_hi - f_lo)).clamp(lo, hi),
    };
    let mut step_before_last = hi - lo;
    let mut last_step = step_before_last;
    for iteration in 1..=MAX_ITERATIONS {
        let (f, df) = f_and_df(t);
        if f.abs() <= f_tol {
            return Root {
                t,
                iterations: iteration,
                bracket: if df != 0.0 {
                    (2.0 * f_tol / df).abs()
                } else {
                    hi - lo
                },
                derivative: df,
            };
        }
        if f.is_sign_positive() == lo_positive {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - f / df;
        if df != 0.0 && (newton - t).abs() <= tol {
            // Converged: the Newton correction is below the tolerance.
            return Root {
                t: newton.clamp(lo, hi),
                iterations: iteration,
                bracket: 2.0 * (newton - t).abs(),
                derivative: df,
            };
        }
        let newton_ok = df != 0.0
            && newton.is_finite()
            && newton > lo
            && newton < hi
            && (newton - t).abs() < 0.5 * step_before_last.abs();
        let next = if newton_ok { newton } else { 0.5 * (lo + hi) };
        step_before_last = last_step;
        last_step = next - t;
        if hi - lo <= tol {
            return Root {
                t: next.clamp(lo, hi),
                iterations: iteration,
                bracket: hi - lo,
                derivative: df,
            };
        }
        t = next;
    }
    Root {
        t: 0.5 * (lo + hi),
        iterations: MAX_ITERATIONS,
        bracket: hi - lo,
        derivative: f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_function_is_solved_by_the_first_secant_step() {
        // f(t) = 3 t - 1, root 1/3 (closed form).
        let r = solve(
            |t| (3.0 * t - 1.0, 3.0),
            (0.0, 1.0),
            (-1.0, 2.0),
            1e-15,
            0.0,
            None,
        );
        assert!((r.t - 1.0 / 3.0).abs() <= 1e-16);
        assert!(r.iterations <= 2);
    }

    #[test]
    fn cosine_root_to_machine_precision() {
        // cos t = 0 at pi/2 (closed form).
        let r = solve(
            |t| (t.cos(), -t.sin()),
            (0.0, 3.0),
            (1.0, 3f64.cos()),
            1e-15,
            0.0,
            None,
        );
        assert!((r.t - std::f64::consts::FRAC_PI_2).abs() <= 4e-16, "{r:?}");
    }

    #[test]
    fn noise_level_stops_the_iteration() {
        // f(t) = t - 0.25 seen through noise of 1e-9: a point with
        // |f| <= 1e-9 is accepted, within 1e-9 of the root.
        let r = solve(
            |t| (t - 0.25, 1.0),
            (0.0, 1.0),
            (-0.25, 0.75),
            0.0,
            1e-9,
            None,
        );
        assert!((r.t - 0.25).abs() <= 1e-9);
    }

    #[test]
    fn flat_derivative_falls_back_to_bisection() {
        // f(t) = (t - 0.3)^3 has f' = 0 at its root: Newton alone converges
        // linearly; the bracket must still close to the tolerance.
        let r = solve(
            |t| ((t - 0.3f64).powi(3), 3.0 * (t - 0.3f64).powi(2)),
            (0.0, 1.0),
            (-0.027, 0.343),
            1e-12,
            0.0,
            None,
        );
        assert!((r.t - 0.3).abs() <= 1e-11, "{r:?}");
        assert!(r.iterations < MAX_ITERATIONS);
    }
}
