//! Observed convergence order over several results of one scene at
//! different step sizes `h`: the least-squares line
//! `ln e = ln C + q ln h` through all `(h, e)` pairs, with the standard
//! error of the slope `q`, `sqrt(s^2 / sum (ln h - mean ln h)^2)` with
//! `s^2 = sum r^2 / (m - 2)` from the residuals `r` of `m` points.
//!
//! A fixed-step error scatters with where the events fall on the time
//! grid, so a pair of files says little; the fit states when the data
//! cannot support an order: fewer than three distinct steps, steps
//! spanning less than a factor of 2, a zero error, a standard error of
//! [`MAX_STANDARD_ERROR`] or more, or an order that is not positive.
//!
//! The step needed for a tolerance `tol` comes from the fitted line moved
//! up by its largest residual, so that every observed error lies on or
//! below it: `h = exp((ln tol - ln C - r_max) / q)`.

use crate::numerics::line_fit::fit_line;
use serde::Serialize;

/// Above this standard error the slope is not reported as an order.
pub(crate) const MAX_STANDARD_ERROR: f64 = 0.5;

/// A fitted order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OrderFit {
    /// Points fitted.
    pub points: usize,
    /// Fitted slope `q` of `ln e` over `ln h`, when it could be fitted.
    pub order: Option<f64>,
    /// Standard error of `q`.
    pub standard_error: Option<f64>,
    /// True when the data support an order (see the module doc).
    pub supported: bool,
    /// Why not, when they do not.
    pub reason: Option<String>,
    /// Step (s) at which the error would reach the tolerance, when the
    /// order is supported.
    pub step_for_tolerance: Option<f64>,
}

/// Fits the order of `errors` (same unit as `tolerance`) over `steps` (s).
pub(crate) fn fit(steps: &[f64], errors: &[f64], tolerance: f64) -> OrderFit {
    let m = steps.len();
    let mut fit = OrderFit {
        points: m,
        order: None,
        standard_error: None,
        supported: false,
        reason: None,
        step_for_tolerance: None,
    };
    let mut distinct: Vec<f64> = steps.to_vec();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
    if distinct.len() < 3 {
        fit.reason = Some(format!(
            "{} distinct step size(s): an order needs at least 3",
            distinct.len()
        ));
        return fit;
    }
    if errors.iter().any(|e| *e <= 0.0) {
        fit.reason = Some("an error is zero: no logarithm to fit".to_owned());
        return fit;
    }
    if errors.iter().any(|e| !e.is_finite()) {
        fit.reason = Some(
            "an error is not finite (a relative error of an exact value 0): no order to fit"
                .to_owned(),
        );
        return fit;
    }
    let x: Vec<f64> = steps.iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let line = fit_line(&x, &y);
    let (q, c, se) = (line.slope, line.intercept, line.standard_error);
    let residuals = line.residuals;
    fit.order = Some(q);
    fit.standard_error = Some(se);
    let span = distinct[distinct.len() - 1] / distinct[0];
    fit.reason = if !(q.is_finite() && se.is_finite()) {
        Some("the fit is not finite: the errors cannot support an order".to_owned())
    } else if span < 2.0 {
        Some(format!(
            "the steps span only a factor of {span:.3}; spread them over at least 2"
        ))
    } else if se >= MAX_STANDARD_ERROR {
        Some(format!(
            "the errors scatter too much for an order (standard error {se:.2}); add step sizes"
        ))
    } else if q <= 0.0 {
        Some(format!(
            "the error does not decrease with the step (slope {q:.2})"
        ))
    } else {
        None
    };
    fit.supported = fit.reason.is_none();
    if fit.supported && tolerance > 0.0 {
        let r_max = residuals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let h = ((tolerance.ln() - c - r_max) / q).exp();
        fit.step_for_tolerance = h.is_finite().then_some(h);
    }
    fit
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_planted_order_with_zero_standard_error() {
        // e = 3 h^2 exactly: slope 2 (the planted power), no scatter.
        let h = [1e-3, 2e-3, 4e-3, 8e-3];
        let e: Vec<f64> = h.iter().map(|h| 3.0 * h * h).collect();
        let f = fit(&h, &e, 3e-8);
        assert!(f.supported);
        approx::assert_relative_eq!(f.order.unwrap(), 2.0, max_relative = 1e-12);
        assert!(f.standard_error.unwrap() < 1e-10);
        // 3 h^2 = 3e-8 at h = 1e-4.
        approx::assert_relative_eq!(f.step_for_tolerance.unwrap(), 1e-4, max_relative = 1e-9);
    }

    #[test]
    fn two_steps_support_no_order() {
        let f = fit(&[1e-3, 2e-3], &[1.0, 2.0], 0.1);
        assert!(!f.supported && f.order.is_none());
    }
}
