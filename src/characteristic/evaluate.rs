//! One exact `v_inf` at a load force: the scene with
//! `motor.extra_acceleration = g_t = -F / m_s` (docs/model.md section 9),
//! run by [`crate::simulation`] with a signal shared through a
//! [`SignalCache`] (only the motor changes from load to load).
//!
//! Contract: an [`Evaluator`] runs every distinct load once (results are
//! kept by the load's bits), counts the simulations it ran by
//! [`Purpose`], and turns every physical outcome into an [`Evaluation`]:
//! a steady state with `v_inf` and its error estimate, or a run-away or an
//! unestablished limit without one. Only a failed simulation (a time limit,
//! an internal limit) is an error, naming the load.

use super::CharacteristicError;
use crate::indicator::Indicator;
use crate::scene::Scene;
use crate::simulation::{Outcome, SignalCache};
use std::cell::RefCell;
use std::collections::HashMap;

/// Why a `v_inf` was evaluated; the counts are reported by purpose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Purpose {
    /// The sampled curve (and the no-load speed).
    Sampling,
    /// The run-away limits that end the curve.
    RunAway,
    /// The stall force.
    Stall,
    /// The edges of the band of loads that hold the slider still.
    HeldBand,
    /// The maximum output power.
    MaxPower,
    /// The start-up from rest (one run that simulates the start-up).
    Transient,
}

/// Simulations run, by purpose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// For the sampled curve and the no-load speed.
    pub sampling: u64,
    /// For the run-away limits.
    pub run_away: u64,
    /// For the stall force.
    pub stall: u64,
    /// For the edges of the held band.
    pub held_band: u64,
    /// For the maximum output power.
    pub max_power: u64,
    /// The start-up run.
    pub transient: u64,
    /// Of all these, the runs that did not establish the limit of the
    /// motion from rest within `run.max_periods` (regime `not_converged`):
    /// each simulated that many periods, so they set the cost where they
    /// occur.
    pub not_converged: u64,
}

impl Counts {
    /// Every simulation run.
    pub fn total(&self) -> u64 {
        self.sampling
            + self.run_away
            + self.stall
            + self.held_band
            + self.max_power
            + self.transient
    }

    /// The `v_inf` evaluations: every simulation but the start-up run.
    pub fn v_inf(&self) -> u64 {
        self.total() - self.transient
    }

    fn add(&mut self, purpose: Purpose) {
        let slot = match purpose {
            Purpose::Sampling => &mut self.sampling,
            Purpose::RunAway => &mut self.run_away,
            Purpose::Stall => &mut self.stall,
            Purpose::HeldBand => &mut self.held_band,
            Purpose::MaxPower => &mut self.max_power,
            Purpose::Transient => &mut self.transient,
        };
        *slot += 1;
    }
}

/// The steady state at one load, or what stands in for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// Load force `F` (N), positive against forward motion.
    pub load: f64,
    /// `g_t = -F / m_s` (m/s^2).
    pub extra_acceleration: f64,
    /// The outcome's `regime` (`stuck`, `stick-slip`, `slip-slip`,
    /// `run-away`, `not_converged`).
    pub regime: &'static str,
    /// `v_inf` (m/s), `None` without a steady state.
    pub v_inf: Option<f64>,
    /// Its estimated absolute error (m/s), when one holds.
    pub error: Option<f64>,
    /// Slider velocity at the period boundary on the periodic orbit (m/s),
    /// `None` without a steady state.
    pub boundary_velocity: Option<f64>,
}

impl Evaluation {
    /// True if the motion from rest reaches a periodic steady state.
    pub fn is_steady(&self) -> bool {
        self.v_inf.is_some()
    }

    /// True if the run did not establish the limit of the motion from rest
    /// within `run.max_periods` (regime `not_converged`): whether the load
    /// has a steady state is not known.
    pub fn is_unsettled(&self) -> bool {
        self.regime == "not_converged"
    }

    /// True if the slider is held still: it follows the rod throughout
    /// (regime `stuck`), so `v_inf = 0`.
    pub fn is_held(&self) -> bool {
        self.regime == "stuck"
    }

    /// The sign of `v_inf` where it lies beyond its error estimate (an
    /// estimate that does not exist counts as 0): `1` forward, `-1`
    /// backward, `0` when `v_inf` cannot be told from 0; `None` without a
    /// steady state.
    pub fn sign(&self) -> Option<i8> {
        let v = self.v_inf?;
        let e = self.error.unwrap_or(0.0);
        Some(if v > e {
            1
        } else if v < -e {
            -1
        } else {
            0
        })
    }

    /// Mechanical output power `F v_inf` (W; never `-0`).
    pub fn output_power(&self) -> Option<f64> {
        self.v_inf
            .map(|v| self.load * v)
            .map(|p| if p == 0.0 { 0.0 } else { p })
    }
}

/// Runs the scene at chosen loads (see the module docs).
#[derive(Debug)]
pub(super) struct Evaluator {
    template: Scene,
    slider_mass: f64,
    cache: SignalCache,
    memo: RefCell<HashMap<u64, Evaluation>>,
    counts: RefCell<Counts>,
}

impl Evaluator {
    /// An evaluator for `scene`: its motor, signal and run settings, asking
    /// for `v_inf` alone (no trajectory, no event log); its own
    /// `extra_acceleration` is replaced by the load's.
    pub(super) fn new(scene: &Scene) -> Self {
        let mut template = scene.clone();
        template.outputs.indicators = vec![Indicator::VInf];
        template.outputs.trajectory = false;
        template.outputs.events = false;
        template.actuator = None;
        template.motor.extra_acceleration = 0.0;
        Evaluator {
            slider_mass: template.motor.slider_mass,
            template,
            cache: SignalCache::default(),
            memo: RefCell::new(HashMap::new()),
            counts: RefCell::new(Counts::default()),
        }
    }

    /// Slider mass `m_s` (kg).
    pub(super) fn slider_mass(&self) -> f64 {
        self.slider_mass
    }

    /// `g_t = -F / m_s` for the load `F` (never `-0`).
    pub(super) fn extra_acceleration(&self, load: f64) -> f64 {
        let g = -load / self.slider_mass;
        if g == 0.0 { 0.0 } else { g }
    }

    /// The scene run at load `load` (N).
    pub(super) fn scene_at(&self, load: f64) -> Scene {
        let mut scene = self.template.clone();
        scene.motor.extra_acceleration = self.extra_acceleration(load);
        scene
    }

    /// `v_inf` at `load` (N), run once per distinct load.
    pub(super) fn at(
        &self,
        load: f64,
        purpose: Purpose,
    ) -> Result<Evaluation, CharacteristicError> {
        let load = if load == 0.0 { 0.0 } else { load };
        if let Some(e) = self.memo.borrow().get(&load.to_bits()) {
            return Ok(*e);
        }
        let outcome = self.simulate(&self.scene_at(load), load, purpose)?;
        let report = outcome.report();
        let evaluation = Evaluation {
            load,
            extra_acceleration: self.extra_acceleration(load),
            regime: outcome.regime(),
            v_inf: report.map(|r| r.indicators.v_inf),
            error: report.and_then(|r| r.error.v_inf),
            boundary_velocity: report.map(|r| r.steady.boundary_velocity),
        };
        self.memo.borrow_mut().insert(load.to_bits(), evaluation);
        Ok(evaluation)
    }

    /// Runs `scene` (the template at `load`, perhaps asking for more) with
    /// the shared signal, counted under `purpose`.
    pub(super) fn simulate(
        &self,
        scene: &Scene,
        load: f64,
        purpose: Purpose,
    ) -> Result<Outcome, CharacteristicError> {
        self.counts.borrow_mut().add(purpose);
        let outcome = self
            .cache
            .simulate(scene)
            .map_err(|source| CharacteristicError::Simulation { load, source })?;
        if matches!(outcome, Outcome::NotConverged(_)) {
            self.counts.borrow_mut().not_converged += 1;
        }
        Ok(outcome)
    }

    /// The steady orbit's boundary velocity at a load evaluated before.
    pub(super) fn boundary_velocity(&self, load: f64) -> Option<f64> {
        let load = if load == 0.0 { 0.0 } else { load };
        self.memo.borrow().get(&load.to_bits())?.boundary_velocity
    }

    /// [`Evaluator::at`] for an `argmin` cost function: a failure is kept in
    /// `failure` (argmin's own error carries only its text) and returned as
    /// argmin's error, which stops the solver.
    pub(super) fn at_in_solver(
        &self,
        load: f64,
        purpose: Purpose,
        failure: &RefCell<Option<CharacteristicError>>,
    ) -> Result<Evaluation, argmin::core::Error> {
        self.at(load, purpose).map_err(|e| keep(failure, e))
    }

    /// Every evaluation so far (any order).
    pub(super) fn evaluations(&self) -> Vec<Evaluation> {
        self.memo.borrow().values().copied().collect()
    }

    /// Simulations run so far.
    pub(super) fn counts(&self) -> Counts {
        *self.counts.borrow()
    }
}

/// Keeps `error` in `failure` and returns it as argmin's error, which
/// carries only its text and stops the solver.
pub(super) fn keep(
    failure: &RefCell<Option<CharacteristicError>>,
    error: CharacteristicError,
) -> argmin::core::Error {
    let text = error.to_string();
    *failure.borrow_mut() = Some(error);
    argmin::core::Error::msg(text)
}
