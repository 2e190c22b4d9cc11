//! The per-period series of a trajectory export: the mean velocity of
//! period `p`, `v_p = (x_S(pT) - x_S((p-1)T)) / T` (docs/model.md
//! section 3), from the user's slider positions at the period ends.
//!
//! An end `kT` that is a sample time takes that sample. One that the grid
//! misses is interpolated linearly between the samples `t_a < kT < t_b`
//! around it. The error of the linear interpolant of a smooth `x` is
//!
//! ```text
//! e_k = (kT - t_a) (t_b - kT) / 2 * |x''|
//! ```
//!
//! to leading order, with `x''` between `t_a` and `t_b`; it is estimated
//! with the largest of the second divided differences of the samples
//! `(t_(a-1), t_a, t_b)` and `(t_a, t_b, t_(b+1))`. The estimate of `v_p`
//! is `(e_(p-1) + e_p) / T`. It is an estimate, not a bound: an event
//! between `t_a` and `t_b` (a jump of the slider's acceleration) makes
//! `x''` there differ from its neighbours'; samples a step apart see it.
//! An end within `1e-6` of the spacing from a sample counts as on it.
//!
//! Contract: a period is in the series only if the samples cover both its
//! ends (nothing is extrapolated); the times are sorted and increasing
//! (as `read` guarantees).

use serde::Serialize;

/// A per-period series found from samples.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SampledPeriods {
    /// Period indices, increasing, from 1.
    pub periods: Vec<u64>,
    /// Mean velocities (m/s).
    pub v_p: Vec<f64>,
    /// What the interpolation of the period ends says.
    pub ends: PeriodEnds,
}

/// How the period ends were found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PeriodEnds {
    /// Period ends found.
    pub ends: usize,
    /// Of those, ends between samples (interpolated).
    pub interpolated: usize,
    /// Largest estimated interpolation error of an end position (m).
    pub max_position_error: f64,
    /// Largest estimated interpolation error of a `v_p` (m/s).
    pub max_v_p_error: f64,
}

/// The second divided difference of `x` over the samples `i, i+1, i+2`.
fn curvature(t: &[f64], x: &[f64], i: usize) -> f64 {
    if i + 2 >= t.len() {
        return 0.0;
    }
    let d1 = (x[i + 1] - x[i]) / (t[i + 1] - t[i]);
    let d2 = (x[i + 2] - x[i + 1]) / (t[i + 2] - t[i + 1]);
    2.0 * (d2 - d1) / (t[i + 2] - t[i])
}

/// The per-period series of the samples `(t, x)` for period `period`.
/// `None` when the samples cover no whole period.
pub(crate) fn from_samples(t: &[f64], x: &[f64], period: f64) -> Option<SampledPeriods> {
    if t.len() < 2 {
        return None;
    }
    let (t0, t1) = (t[0], t[t.len() - 1]);
    // An end this close to the first or last sample is on it.
    let (near0, near1) = (1e-6 * (t[1] - t0), 1e-6 * (t1 - t[t.len() - 2]));
    let first = ((t0 - near0) / period).ceil().max(0.0) as u64;
    let last = ((t1 + near1) / period).floor() as u64;
    if last <= first {
        return None;
    }
    let mut positions = Vec::with_capacity((last - first + 1) as usize);
    let mut ends = PeriodEnds {
        ends: 0,
        interpolated: 0,
        max_position_error: 0.0,
        max_v_p_error: 0.0,
    };
    for k in first..=last {
        let end = k as f64 * period;
        let j = t.partition_point(|&s| s < end).clamp(1, t.len() - 1);
        let (ta, tb) = (t[j - 1], t[j]);
        let on = 1e-6 * (tb - ta);
        let (x_end, error) = if (end - ta).abs() <= on {
            (x[j - 1], 0.0)
        } else if (tb - end).abs() <= on {
            (x[j], 0.0)
        } else {
            let w = (end - ta) / (tb - ta);
            let a = curvature(t, x, j.saturating_sub(2))
                .abs()
                .max(curvature(t, x, j - 1).abs());
            ends.interpolated += 1;
            (
                x[j - 1] + w * (x[j] - x[j - 1]),
                0.5 * (end - ta) * (tb - end) * a,
            )
        };
        ends.ends += 1;
        ends.max_position_error = ends.max_position_error.max(error);
        positions.push((x_end, error));
    }
    let mut periods = Vec::new();
    let mut v_p = Vec::new();
    for (i, w) in positions.windows(2).enumerate() {
        periods.push(first + i as u64 + 1);
        v_p.push((w[1].0 - w[0].0) / period);
        ends.max_v_p_error = ends.max_v_p_error.max((w[0].1 + w[1].1) / period);
    }
    Some(SampledPeriods { periods, v_p, ends })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_motion_is_exact_and_a_parabola_meets_the_bound() {
        // x = 2 t: linear interpolation is exact, v_p = 2 whatever the grid.
        let t: Vec<f64> = (0..=70).map(|i| i as f64 * 0.3).collect();
        let x: Vec<f64> = t.iter().map(|t| 2.0 * t).collect();
        let s = from_samples(&t, &x, 1.0).unwrap();
        assert_eq!(s.periods, (1..=21).collect::<Vec<u64>>());
        for v in &s.v_p {
            approx::assert_relative_eq!(*v, 2.0, max_relative = 1e-12);
        }
        // x = t^2 / 2 (x'' = 1): the end k = 1 lies between 0.9 and 1.2;
        // the chord there is above the parabola by (0.1)(0.2)/2 = 0.01,
        // which the estimate finds exactly (the second differences of a
        // parabola are its x''), and x(0) is a sample.
        let x: Vec<f64> = t.iter().map(|t| 0.5 * t * t).collect();
        let s = from_samples(&t, &x, 1.0).unwrap();
        approx::assert_relative_eq!(s.v_p[0] - 0.5, 0.01, max_relative = 1e-9);
        approx::assert_relative_eq!(s.ends.max_position_error, 0.01, max_relative = 1e-9);
    }
}
