//! Least-squares straight line `y = c + q x` through points, with the
//! residuals and the standard error of the slope,
//! `sqrt(s^2 / sum (x - mean x)^2)` with `s^2 = sum r^2 / (m - 2)` for `m`
//! points. Log-log fits (power laws, convergence orders) pass `ln x` and
//! `ln y`.

/// A fitted line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LineFit {
    /// Slope `q`.
    pub slope: f64,
    /// Intercept `c`.
    pub intercept: f64,
    /// Residuals `y - (c + q x)`, in the order of the points.
    pub residuals: Vec<f64>,
    /// Standard error of the slope (NaN for fewer than three points).
    pub standard_error: f64,
}

/// Fits the line through `(x[i], y[i])`; the slices have equal lengths.
pub(crate) fn fit_line(x: &[f64], y: &[f64]) -> LineFit {
    let m = x.len();
    let mx = x.iter().sum::<f64>() / m as f64;
    let my = y.iter().sum::<f64>() / m as f64;
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let residuals: Vec<f64> = x
        .iter()
        .zip(y)
        .map(|(a, b)| b - (intercept + slope * a))
        .collect();
    let s2 = residuals.iter().map(|r| r * r).sum::<f64>() / (m as f64 - 2.0);
    LineFit {
        slope,
        intercept,
        residuals,
        standard_error: (s2 / sxx).sqrt(),
    }
}

/// Exponent `s` of a power law `y ∝ x^s` through positive points: the
/// slope of `ln y` over `ln x`.
pub(crate) fn loglog_slope(points: &[(f64, f64)]) -> f64 {
    let x: Vec<f64> = points.iter().map(|p| p.0.ln()).collect();
    let y: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    fit_line(&x, &y).slope
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_planted_line_with_zero_residuals() {
        // y = 2 - 3 x exactly (dyadic values): slope -3, intercept 2.
        let x = [0.0, 0.5, 1.0, 2.0];
        let y: Vec<f64> = x.iter().map(|v| 2.0 - 3.0 * v).collect();
        let fit = fit_line(&x, &y);
        assert_eq!(fit.slope, -3.0);
        assert_eq!(fit.intercept, 2.0);
        assert!(fit.residuals.iter().all(|r| *r == 0.0));
        assert_eq!(fit.standard_error, 0.0);
    }

    #[test]
    fn slope_of_a_power_law() {
        // y = 3 x^0.5: exponent 0.5.
        let pts: Vec<(f64, f64)> = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|x: &f64| (*x, 3.0 * x.sqrt()))
            .collect();
        assert!((loglog_slope(&pts) - 0.5).abs() < 1e-12);
    }
}
