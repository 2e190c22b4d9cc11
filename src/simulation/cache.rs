//! Signals built once and shared between scenes (sweeps over the motor).

use super::{Outcome, RunReport, simulate_built};
use crate::engine::event::EventOptions;
use crate::error::Error;
use crate::motor::Motor;
use crate::scene::Scene;
use crate::signal::{Signal, SignalSpec};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Signals built once and shared, for many scenes that differ elsewhere
/// (a sweep over the motor): keyed by the signal spec and, for the
/// `kappa`-based kinds, by the motor's `a_0` (the only motor quantity a
/// signal depends on, docs/model.md section 2). Safe to share between
/// threads; holds at most [`SignalCache::CAPACITY`] signals (then it is
/// emptied and starts again), so that a sweep over the signal itself does
/// not keep every signal it ran.
#[derive(Debug, Default)]
pub struct SignalCache {
    signals: Mutex<HashMap<String, Arc<Signal>>>,
}

impl SignalCache {
    /// Signals kept at most.
    pub const CAPACITY: usize = 64;

    /// The signal of `scene`, built on first use.
    pub fn get(&self, scene: &Scene) -> Result<Arc<Signal>, Error> {
        let motor = Motor::new(scene.motor)?;
        let key = match &scene.signal {
            SignalSpec::Harmonics { .. } => format!("{:?}", scene.signal),
            _ => format!("{:?} a_0 = {:?}", scene.signal, motor.a_0()),
        };
        let lock = |m: &Mutex<HashMap<String, Arc<Signal>>>| {
            // A panic elsewhere leaves the map intact: keep using it.
            m.lock()
                .unwrap_or_else(|e| e.into_inner())
                .get(&key)
                .cloned()
        };
        if let Some(signal) = lock(&self.signals) {
            return Ok(signal);
        }
        // Built outside the lock: other threads go on meanwhile.
        let signal = Arc::new(Signal::build(&scene.signal, &motor)?);
        let mut map = self.signals.lock().unwrap_or_else(|e| e.into_inner());
        if map.len() >= Self::CAPACITY {
            map.clear();
        }
        Ok(map.entry(key).or_insert(signal).clone())
    }

    /// [`run`](super::run) with the signal from this cache.
    pub(crate) fn simulate(&self, scene: &Scene) -> Result<Outcome, Error> {
        let clock = Instant::now();
        let signal = self.get(scene)?;
        let motor = Motor::new(scene.motor)?;
        simulate_built(scene, &signal, &motor, EventOptions::default(), clock)
    }

    /// [`SignalCache::simulate`] for callers that need a steady state.
    pub(crate) fn run(&self, scene: &Scene) -> Result<RunReport, Error> {
        self.simulate(scene)?.into_report()
    }
}
