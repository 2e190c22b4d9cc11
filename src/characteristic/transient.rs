//! The force a start-up (transient) measurement would report: `m_s` times
//! the slider's acceleration from rest, by Newton's second law (the third
//! way of measuring an inertia drive's force that the paper's section 5
//! names; docs/model.md section 9).
//!
//! A measurement sees the slider's motion averaged over each period: the
//! mean velocity `v_p` of period `p` (docs/model.md section 3), which
//! belongs to the period's middle, `t_p = (p - 1/2) T`, while the slider
//! is at rest (`v = 0`) at `t = 0`. The accelerations it reports are the
//! slopes between these samples,
//!
//! ```text
//! a_1 = v_1 / (T / 2),      a_p = (v_p - v_(p-1)) / T   (p >= 2),
//! ```
//!
//! over the start-up from rest at zero load, periods `1..=p_0.99` (the
//! start-up of docs/model.md section 3). Reported: the initial force
//! `m_s a_1` and the largest `m_s a_p` in the drive direction, signed like
//! the stall force, so that their ratios to it read directly. (The
//! velocity at the period boundaries would not do: a slider that sticks
//! there has the rod's velocity, whatever it does in between.) For the
//! ideal signals (docs/model.md section 7) `a_1` is the slider's true
//! initial acceleration: `kappa a_0` when it sticks through the first
//! period, `a_d` when it slips forward through it. Nothing in the model
//! makes the start-up force equal the stall force: at the stall force the
//! mean friction force over a steady period balances the load, while the
//! start-up force is the mean friction force on a slider that starts from
//! rest without a load.

use super::CharacteristicError;
use super::evaluate::{Evaluator, Purpose};
use crate::indicator::Indicator;

/// What a start-up measurement at zero load would report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientForce {
    /// `m_s a_1 = m_s v_1 / (T / 2)` (N).
    pub initial_force: f64,
    /// The largest `m_s a_p` in the drive direction (N).
    pub max_force: f64,
    /// The period `p` where it is reached.
    pub max_period: u64,
    /// Periods of the start-up looked at (`p_0.99`, or every simulated
    /// period when `p_0.99` is undefined).
    pub periods: u64,
}

/// The start-up from rest at zero load and the forces it shows; `None`
/// when the run has no steady state or simulated no start-up.
pub(super) fn transient_force(
    ev: &Evaluator,
) -> Result<Option<TransientForce>, CharacteristicError> {
    let mut scene = ev.scene_at(0.0);
    scene.outputs.indicators = vec![Indicator::VInf, Indicator::StartupTime];
    let outcome = ev.simulate(&scene, 0.0, Purpose::Transient)?;
    let Some(report) = outcome.report() else {
        return Ok(None);
    };
    let Some(transient) = &report.transient else {
        return Ok(None);
    };
    let span = (report.startup_span() as usize).min(transient.mean_velocities.len());
    if span == 0 {
        return Ok(None);
    }
    let s = if report.indicators.v_inf < 0.0 {
        -1.0
    } else {
        1.0
    };
    let (m, t) = (ev.slider_mass(), report.period);
    let v = &transient.mean_velocities[..span];
    let forces: Vec<f64> = std::iter::once(m * v[0] / (t / 2.0))
        .chain(v.windows(2).map(|w| m * (w[1] - w[0]) / t))
        .collect();
    let (k, max) = forces
        .iter()
        .enumerate()
        .max_by(|a, b| (s * a.1).total_cmp(&(s * b.1)))
        .map_or((0, forces[0]), |(k, f)| (k, *f));
    Ok(Some(TransientForce {
        initial_force: forces[0],
        max_force: max,
        max_period: k as u64 + 1,
        periods: span as u64,
    }))
}
