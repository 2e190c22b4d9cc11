//! The fixed-step reference's results as a user exports them: the input
//! of a comparison made in this process (the figure registry's compare
//! figure), without files.
//!
//! Contract: [`export`] runs the reference (`engine::fixed_step`) from rest
//! on a scene and returns what a user's fixed-step program writes
//! (tests/data/compare/generate.py): the samples `t, x_S, v_S` at every
//! step of period 1 (`t = k h`, `k = 0..N`, `h = T / N`) and the
//! per-period series `p, v_p` of periods `1..=periods`, in SI units. A
//! sample is the reference's own segment evaluated at its time (slip:
//! constant acceleration; stick: moving with the rod).

use super::exact::{PeriodRecord, state_in};
use super::{Column, CompareError, UserData};
use crate::engine::fixed_step::{FixedStepEngine, FixedStepOptions};
use crate::engine::{PeriodEngine, PeriodStart};
use crate::observer::Trajectory;
use crate::scene::Scene;
use crate::simulation;

/// The reference at `steps_per_harmonic` steps per period of the highest
/// harmonic on `scene`, over `periods` periods (see the module doc).
pub(crate) fn export(
    scene: &Scene,
    steps_per_harmonic: u32,
    periods: u64,
) -> Result<UserData, CompareError> {
    let (signal, motor) = simulation::build_prescribed(scene, "compare")?;
    let options = FixedStepOptions {
        steps_per_harmonic,
        ..FixedStepOptions::default()
    };
    let mut engine = FixedStepEngine::new(&signal, &motor, options);
    let period = signal.period();
    let steps = engine.steps_per_period();
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let (mut t, mut x_s, mut v_s) = (Vec::new(), Vec::new(), Vec::new());
    let (mut p, mut v_p) = (Vec::new(), Vec::new());
    for index in 1..=periods.max(1) {
        let mut trajectory = Trajectory::default();
        let end = if index == 1 {
            engine.run_period(index, start, &mut trajectory)?
        } else {
            engine.run_period(index, start, &mut ())?
        };
        if index == 1 {
            let record = PeriodRecord {
                period: 1,
                x_start: 0.0,
                step: end.step,
                v_p: end.step / period,
                stick_time: 0.0,
                events: Vec::new(),
                segments: trajectory.segments,
            };
            for k in 0..=steps {
                let tau = if k == steps {
                    period
                } else {
                    k as f64 * period / steps as f64
                };
                let s = state_in(&record, &signal, tau);
                t.push(s.t);
                x_s.push(s.x_s);
                v_s.push(s.v_s);
            }
        }
        p.push(index as f64);
        v_p.push(end.step / period);
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    Ok(UserData {
        t: Some(Column::new("t", t)),
        x_s: Some(Column::new("x_S", x_s)),
        v_s: Some(Column::new("v_S", v_s)),
        x_r: None,
        p: Some(Column::new("p", p)),
        v_p: Some(Column::new("v_p", v_p)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::fixed_step::FixedStepEngine;

    #[test]
    fn the_last_mean_velocity_is_the_references_own_steady_state() {
        // The analysis finds the reference's v_inf from its start-up and a
        // fixed-point search; the export walks the same scheme from rest.
        let scene = Scene::default();
        let (signal, motor) = simulation::build(&scene).unwrap();
        let options = FixedStepOptions {
            steps_per_harmonic: 500,
            ..FixedStepOptions::default()
        };
        let report = simulation::run_with(
            FixedStepEngine::new(&signal, &motor, options),
            &scene,
            &motor,
        )
        .unwrap();
        let data = export(&scene, 500, 1200).unwrap();
        let v_p = &data.v_p.unwrap().values;
        assert_eq!(v_p.len(), 1200);
        approx::assert_relative_eq!(
            v_p[v_p.len() - 1],
            report.indicators.v_inf,
            max_relative = 1e-12
        );
    }

    #[test]
    fn period_one_is_sampled_at_every_node_of_the_grid() {
        // N = n x S steps of h = T / N: N + 1 samples from 0 to T.
        let scene = Scene::default();
        let (signal, _) = simulation::build(&scene).unwrap();
        let data = export(&scene, 50, 3).unwrap();
        let t = &data.t.unwrap().values;
        let n = 2 * 50;
        assert_eq!(t.len(), n + 1);
        assert_eq!(t[n], signal.period());
        let h = signal.period() / n as f64;
        for w in t.windows(2) {
            approx::assert_relative_eq!(w[1] - w[0], h, max_relative = 1e-9);
        }
        // The slider starts from rest.
        assert_eq!(data.v_s.unwrap().values[0], 0.0);
    }
}
