//! The sampled curve: `v_inf` along the load axis (force `F`, or incline
//! angle `theta` with `F = m_s g sin(theta)`), denser where the curve
//! bends.
//!
//! Contract:
//!
//! 1. 17 equally spaced loads over the range (and `0` when it lies inside)
//!    are evaluated.
//! 2. If the range's ends have no steady state, each end of the curve is
//!    found by bisection between the outermost steady load and its unsteady
//!    neighbour ([`super::domain`]), to the limit tolerance in force (or up
//!    to the first load whose run did not converge); the last steady load
//!    joins the samples.
//! 3. Every interval between two neighbouring steady samples has its
//!    midpoint evaluated (so even a straight stretch is sampled twice as
//!    densely as the grid); where `v_inf` at the midpoint differs from the
//!    chord through the ends by more than `tolerance` times the range of
//!    `v_inf` seen so far, both halves are tested the same way, down to a
//!    width of `1e-6` of the range. Intervals are taken breadth first, so
//!    that when the budget of evaluations runs out the curve is refined
//!    evenly and the result says it is incomplete.
//!
//! A kink (the event structure changes, e.g. stick phases appear) is
//! refined until the chord error is below the tolerance; a jump (with
//! `mu_dynamic = 0`, `v_inf` jumps at zero load) down to the minimum width,
//! where it shows as a steep segment, or until a midpoint has no steady
//! state or did not converge: its halves are not between steady
//! neighbours. Nothing here depends on the slopes, which are computed
//! afterwards at the points found.

use super::domain::{Limit, limit_between};
use super::evaluate::{Evaluation, Evaluator, Purpose};
use super::{CharacteristicError, LoadAxis};
use std::collections::VecDeque;

/// Loads of the first grid.
const GRID: usize = 17;
/// Smallest interval refined, relative to the range.
const MIN_WIDTH: f64 = 1e-6;

/// One sample: the axis value and the evaluation at its load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Sample {
    /// Position on the load axis (N, or degrees on an incline).
    pub x: f64,
    /// The evaluation at `F(x)`.
    pub evaluation: Evaluation,
}

/// The sampled curve.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Sampled {
    /// Samples in increasing `x`.
    pub samples: Vec<Sample>,
    /// The end of the curve at the low side of the range, if the range's
    /// low end has no steady state.
    pub below: Option<Limit>,
    /// The end of the curve at the high side.
    pub above: Option<Limit>,
    /// False if the budget of evaluations ended the refinement.
    pub complete: bool,
}

/// What the sampling needs to know.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SamplingSpec {
    /// Load axis.
    pub axis: LoadAxis,
    /// Range on the axis, low to high.
    pub range: (f64, f64),
    /// Chord tolerance, relative to the range of `v_inf`.
    pub tolerance: f64,
    /// Evaluations the refinement may use (counted under
    /// [`Purpose::Sampling`]).
    pub budget: u64,
    /// Tolerance of the curve's ends in force (N).
    pub limit_tolerance: f64,
}

/// Samples the curve as the module docs say.
pub(super) fn sample(ev: &Evaluator, spec: &SamplingSpec) -> Result<Sampled, CharacteristicError> {
    let (lo, hi) = spec.range;
    let m = ev.slider_mass();
    let at = |x: f64| -> Result<Sample, CharacteristicError> {
        Ok(Sample {
            x,
            evaluation: ev.at(spec.axis.force(x, m), Purpose::Sampling)?,
        })
    };
    let step = (hi - lo) / (GRID - 1) as f64;
    let mut xs: Vec<f64> = (0..GRID)
        .map(|i| {
            if i + 1 == GRID {
                hi
            } else {
                lo + step * i as f64
            }
        })
        .collect();
    if lo < 0.0 && hi > 0.0 && !xs.contains(&0.0) {
        xs.push(0.0);
    }
    let mut samples = xs.into_iter().map(at).collect::<Result<Vec<_>, _>>()?;
    samples.sort_by(|a, b| a.x.total_cmp(&b.x));
    let steady: Vec<usize> = (0..samples.len())
        .filter(|&i| samples[i].evaluation.is_steady())
        .collect();
    let (mut below, mut above) = (None, None);
    if let (Some(&first), Some(&last)) = (steady.first(), steady.last()) {
        if first > 0 {
            below = Some(limit_between(
                ev,
                samples[first].evaluation,
                samples[first - 1].evaluation,
                spec.limit_tolerance,
            )?);
        }
        if last + 1 < samples.len() {
            above = Some(limit_between(
                ev,
                samples[last].evaluation,
                samples[last + 1].evaluation,
                spec.limit_tolerance,
            )?);
        }
    }
    for limit in [below, above].into_iter().flatten() {
        let e = limit.last_steady;
        samples.push(Sample {
            x: spec.axis.parameter(e.load, m).clamp(lo, hi),
            evaluation: e,
        });
    }
    samples.sort_by(|a, b| a.x.total_cmp(&b.x));
    let complete = refine(ev, spec, &mut samples, &at)?;
    samples.sort_by(|a, b| a.x.total_cmp(&b.x));
    samples.dedup_by(|a, b| a.evaluation.load == b.evaluation.load);
    Ok(Sampled {
        samples,
        below,
        above,
        complete,
    })
}

/// Step 3 of the module docs; false if the budget ran out.
fn refine(
    ev: &Evaluator,
    spec: &SamplingSpec,
    samples: &mut Vec<Sample>,
    at: &dyn Fn(f64) -> Result<Sample, CharacteristicError>,
) -> Result<bool, CharacteristicError> {
    let (lo, hi) = spec.range;
    let min_width = MIN_WIDTH * (hi - lo);
    let v = |s: &Sample| s.evaluation.v_inf;
    let (mut v_lo, mut v_hi) = samples
        .iter()
        .filter_map(v)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
    let mut queue: VecDeque<(Sample, Sample)> = samples
        .windows(2)
        .filter(|w| w[0].evaluation.is_steady() && w[1].evaluation.is_steady())
        .map(|w| (w[0], w[1]))
        .collect();
    while let Some((a, b)) = queue.pop_front() {
        if b.x - a.x <= min_width {
            continue;
        }
        if ev.counts().sampling >= spec.budget {
            return Ok(false);
        }
        let mid = at(0.5 * (a.x + b.x))?;
        samples.push(mid);
        let (Some(va), Some(vb), Some(vm)) = (v(&a), v(&b), v(&mid)) else {
            continue;
        };
        v_lo = v_lo.min(vm);
        v_hi = v_hi.max(vm);
        if (vm - 0.5 * (va + vb)).abs() > spec.tolerance * (v_hi - v_lo) {
            queue.push_back((a, mid));
            queue.push_back((mid, b));
        }
    }
    Ok(true)
}
