//! The force a start-up (transient) measurement would report: `m_s` times
//! the slider's acceleration from rest, by Newton's second law (the third
//! way of measuring an inertia drive's force that the paper's section 5
//! names; docs/model.md section 9).
//!
//! With `u_k` the slider velocity at the end of period `k` of the start-up
//! from rest at zero load (`u_0 = 0`), the mean acceleration of period `k`
//! is exactly `a_k = (u_k - u_(k-1)) / T` (the velocity change over the
//! period divided by its length). Reported: the initial force `m_s a_1`
//! and the largest `m_s a_k` in the drive direction over the start-up
//! (periods `1..=p_0.99`, the start-up of docs/model.md section 3). Both
//! are signed like the stall force, so that the ratio of the two
//! measurements reads directly. Nothing in the model makes the two equal:
//! at the stall force the mean friction force over a steady period
//! balances the load, while the start-up force is the mean friction force
//! on a slider that starts from rest without a load.

use super::CharacteristicError;
use super::evaluate::{Evaluator, Purpose};
use crate::scene::Indicator;

/// What a start-up measurement at zero load would report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientForce {
    /// `m_s u_1 / T` (N).
    pub initial_force: f64,
    /// The largest `m_s (u_k - u_(k-1)) / T` in the drive direction (N).
    pub max_force: f64,
    /// The period `k` where it is reached.
    pub max_period: u64,
    /// Periods of the start-up looked at (`p_0.99`, or every simulated
    /// period when `p_0.99` is undefined).
    pub periods: u64,
}

/// The start-up from rest at zero load and the forces it shows; `None`
/// when the run has no steady state or simulated no start-up.
pub fn transient_force(ev: &Evaluator) -> Result<Option<TransientForce>, CharacteristicError> {
    let mut scene = ev.scene_at(0.0);
    scene.outputs.indicators = vec![Indicator::VInf, Indicator::StartupTime];
    let outcome = ev.simulate(&scene, 0.0, Purpose::Transient)?;
    let Some(report) = outcome.report() else {
        return Ok(None);
    };
    let Some(transient) = &report.transient else {
        return Ok(None);
    };
    let span = (report.startup_span() as usize).min(transient.boundary_velocities.len());
    if span == 0 {
        return Ok(None);
    }
    let s = if report.indicators.v_inf < 0.0 {
        -1.0
    } else {
        1.0
    };
    let m = ev.slider_mass();
    let forces: Vec<f64> = std::iter::once(0.0)
        .chain(transient.boundary_velocities[..span].iter().copied())
        .collect::<Vec<f64>>()
        .windows(2)
        .map(|w| m * (w[1] - w[0]) / report.period)
        .collect();
    let (k, max) = forces
        .iter()
        .enumerate()
        .max_by(|a, b| (s * a.1).total_cmp(&(s * b.1)))
        .map(|(k, f)| (k, *f))
        .unwrap_or((0, forces[0]));
    Ok(Some(TransientForce {
        initial_force: forces[0],
        max_force: max,
        max_period: k as u64 + 1,
        periods: span as u64,
    }))
}
