//! One spring against the slider: the scene run with it and what the
//! spring reads over the steady orbit, or what happened instead.
//!
//! Only the friction energy indicator is asked, so the run needs no
//! start-up to `p_0.99`: the steady orbit is found by Newton and the
//! start-up from rest followed only as far as its attraction (certificate
//! `attracted`), or the start-up is repeated until it repeats itself
//! exactly (`orbit`); see `crate::simulation`.

use crate::indicator::Indicator;
use crate::scene::Scene;
use crate::simulation::{CertificateKind, SignalCache, SpringReading};
use crate::spring::{Spring, SpringEnd};
use std::time::Duration;

/// What one spring read.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringCase {
    /// The spring.
    pub spring: Spring,
    /// The run's outcome (`crate::simulation::Outcome::regime`):
    /// `stuck`, `stick-slip`, `slip-slip`, `run-away` or `not_converged`.
    pub regime: &'static str,
    /// The reading over the steady orbit; `None` without a steady state.
    pub reading: Option<SpringReading>,
    /// Periods of the start-up from rest simulated.
    pub periods_simulated: u64,
    /// How the steady state was established; `None` without one.
    pub certificate: Option<CertificateKind>,
    /// `run.max_periods` of the run (what a `not_converged` case used up).
    pub max_periods: u64,
    /// The run's wall time.
    pub wall_time: Duration,
}

impl SpringCase {
    /// `tied` or `free`.
    pub fn end_name(&self) -> &'static str {
        match self.spring.end {
            SpringEnd::Tied { .. } => "tied",
            SpringEnd::Free { .. } => "free",
        }
    }

    /// Why there is no orbit's reading, in words; `None` with one.
    pub fn note(&self) -> Option<String> {
        if let Some(r) = &self.reading {
            return (r.orbit_periods == 0).then(|| {
                format!(
                    "no orbit of up to 64 periods locked within {} periods from rest; read over the next {}",
                    self.periods_simulated, r.periods
                )
            });
        }
        Some(match self.regime {
            "not_converged" => format!(
                "no steady orbit established within run.max_periods = {} periods",
                self.max_periods
            ),
            "run-away" => "the slider runs away: no steady orbit".to_owned(),
            other => format!("{other}: no spring reading"),
        })
    }
}

/// `scene` as one case runs it: with `spring`, only the friction energy
/// asked, no trajectory and no event log.
pub(super) fn case_scene(scene: &Scene, spring: Spring, max_periods: u64) -> Scene {
    let mut s = scene.clone();
    s.spring = Some(spring);
    s.run.max_periods = max_periods;
    s.outputs.indicators = vec![Indicator::FrictionEnergy];
    s.outputs.trajectory = false;
    s.outputs.events = false;
    s
}

/// Runs `scene` with `spring` (the signal from `signals`).
pub(super) fn measure(
    scene: &Scene,
    spring: Spring,
    max_periods: u64,
    signals: &SignalCache,
) -> Result<SpringCase, crate::error::Error> {
    let s = case_scene(scene, spring, max_periods);
    let outcome = signals.simulate(&s)?;
    let report = outcome.report();
    Ok(SpringCase {
        spring,
        regime: outcome.regime(),
        // An orbit's reading, or the reading after a start-up that locked
        // into none.
        reading: report
            .and_then(|r| r.spring)
            .or_else(|| outcome.unsettled().and_then(|u| u.spring)),
        periods_simulated: outcome.periods_simulated(),
        certificate: report.map(|r| r.certificate.kind),
        max_periods: s.run.max_periods,
        wall_time: outcome.times().wall,
    })
}
