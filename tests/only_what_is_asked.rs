//! A run computes only what its scene asks for.
//! A `v_inf`-only scene takes the fixed point of the period map from rest
//! without simulating the start-up (module docs of `simulation`), and
//! reports the same `v_inf`, bit for bit, as the run that simulates it; a
//! map whose search from rest lands on a far fixed point still gets the
//! one the motion from rest reaches. Signals are shared between scenes
//! that differ only in the motor.

mod common;

use common::mock::ThreeFixedPoints;

use std::sync::Arc;
use stickslip::Indicator;
use stickslip::SignalSpec;
use stickslip::{Outcome, RunReport, simulation::CertificateKind, simulation::SignalCache};
use stickslip::{Scene, motor::Motor, signal::Signal};

fn only_v_inf(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.outputs.indicators = vec![Indicator::VInf];
    s
}

fn steady(scene: &Scene) -> RunReport {
    stickslip::run(scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .expect("a steady state")
}

/// The default scene (the paper's section 7) and scenes of other signals
/// and motors: the `v_inf`-only run simulates no start-up, needs fewer
/// periods than the full run (for the default scene fewer than the 388 of
/// the start-up to `p_0.99` alone), and gives the full run's
/// `v_inf` and error estimate to the last bit.
#[test]
fn v_inf_only_runs_skip_the_start_up_and_give_the_same_bits() {
    let mut scenes = vec![Scene::default()];
    for (n, sigma, kappa) in [(8, true, 36.0), (16, false, 4.0), (3, true, 400.0)] {
        scenes.push(Scene {
            signal: SignalSpec::fourier(25e-6, kappa, n, sigma),
            ..Scene::default()
        });
    }
    let mut loaded = Scene::default();
    loaded.motor.extra_acceleration = -30.0;
    scenes.push(loaded);
    for scene in &scenes {
        let full = steady(scene);
        let fast = steady(&only_v_inf(scene));
        let label = format!(
            "{:?} g_t = {}",
            scene.signal, scene.motor.extra_acceleration
        );
        let startup = full.startup_periods.expect("the full run has a start-up");
        assert!(
            fast.transient.is_none(),
            "{label}: a start-up was simulated"
        );
        assert_eq!(fast.startup_span(), 0, "{label}");
        assert!(startup > 0, "{label}");
        assert!(
            fast.work.periods < full.work.periods,
            "{label}: {} periods against {}",
            fast.work.periods,
            full.work.periods
        );
        assert_eq!(fast.work.periods, fast.map_evaluations, "{label}");
        assert_eq!(
            fast.indicators.v_inf.to_bits(),
            full.indicators.v_inf.to_bits(),
            "{label}"
        );
        assert_eq!(fast.error.v_inf, full.error.v_inf, "{label}");
        // Nothing of the start-up was simulated, so none of its events is
        // counted.
        assert_eq!(fast.events().total(), 0, "{label}");
    }
    // The paper's headline number (section 7: 0.297 m/s, three digits), to
    // the bit as the full run gives it.
    let fast = steady(&only_v_inf(&Scene::default()));
    assert!((fast.indicators.v_inf - 0.297).abs() < 5e-4);
    let full = steady(&Scene::default());
    assert_eq!(
        fast.indicators.v_inf.to_bits(),
        full.indicators.v_inf.to_bits()
    );
    let startup = full.startup_periods.unwrap();
    assert!(fast.work.periods < startup / 4, "{}", fast.work.periods);
}

/// `verify_steady_state` still simulates the start-up to its own limit for
/// a `v_inf`-only scene, and it agrees with the fixed point.
#[test]
fn verify_steady_state_still_simulates_the_start_up() {
    let mut scene = only_v_inf(&Scene::default());
    scene.run.verify_steady_state = true;
    let r = steady(&scene);
    let check = r.steady_state_check.expect("asked for");
    assert_eq!(check.agrees(), Some(true));
    let startup = steady(&Scene::default()).startup_periods.unwrap();
    assert!(check.periods > startup, "{} periods", check.periods);
}

/// The covering between rest and the searched fixed point (2.5) meets a
/// point of `(1, 2)` that the map moves back: a nearer fixed point exists
/// in the bracket it gives, and the `v_inf`-only run finds and certifies
/// it there (1, the limit of the orbit from rest), without the start-up.
#[test]
fn v_inf_only_run_of_a_three_fixed_point_map_takes_the_nearest() {
    let scene = Scene {
        actuator: None,
        ..only_v_inf(&Scene::default())
    };
    let motor = Motor::new(scene.motor).unwrap();
    let signal = Signal::build(&scene.signal, &motor).unwrap();
    let a = signal.velocity_range().max / 5.0;
    let engine = ThreeFixedPoints {
        signal: signal.clone(),
        a,
        periods: 0,
        close: false,
    };
    let r = stickslip::Outcome::of_engine(engine, &scene, &motor)
        .and_then(stickslip::Outcome::into_report)
        .unwrap();
    assert!(
        (r.indicators.v_inf / a - 1.0).abs() < 1e-9,
        "{}",
        r.indicators.v_inf / a
    );
    // The covering proved the gap below 1 free and found 1 without the
    // start-up; the search had reached 2.5, 1.5 away (the mock's closed
    // form).
    assert!(r.transient.is_none());
    assert_eq!(r.certificate.kind, CertificateKind::Covering);
    let other = r
        .certificate
        .other_fixed_point
        .expect("2.5 was found first");
    assert!((other / a - 1.5).abs() < 1e-9, "{}", other / a);
}

/// A further pair of fixed points close to the one the search from rest
/// finds (1.004 and 1.005, the limit of the motion from rest being 1):
/// the covering sees the pair, with and without the start-up, and reports
/// the limit with the fixed point the search reached as the other one.
#[test]
fn a_pair_of_fixed_points_close_to_the_found_one_is_seen() {
    for indicators in [vec![Indicator::VInf], Indicator::ALL[..6].to_vec()] {
        let mut scene = Scene {
            actuator: None,
            ..Scene::default()
        };
        scene.outputs.indicators = indicators.clone();
        let motor = Motor::new(scene.motor).unwrap();
        let signal = Signal::build(&scene.signal, &motor).unwrap();
        let a = signal.velocity_range().max / 5.0;
        let engine = ThreeFixedPoints {
            signal: signal.clone(),
            a,
            periods: 0,
            close: true,
        };
        let r = stickslip::Outcome::of_engine(engine, &scene, &motor)
            .and_then(stickslip::Outcome::into_report)
            .unwrap();
        assert!(
            (r.indicators.v_inf / a - 1.0).abs() < 1e-9,
            "{indicators:?}: {}",
            r.indicators.v_inf / a
        );
        // The search reached 1.005, 0.005 from the limit (the mock's closed
        // form), and the covering found the pair between.
        assert_eq!(r.certificate.kind, CertificateKind::Covering);
        let other = r
            .certificate
            .other_fixed_point
            .expect("1.005 was found first");
        assert!((other / a - 0.005).abs() < 1e-9, "{}", other / a);
    }
}

/// Scenes that differ only in the motor's sliding friction share one
/// signal (it depends on the motor only through `a_0`), and a run with the
/// shared signal gives the same result as one that builds its own; a
/// different `a_0` builds another signal.
#[test]
fn signal_cache_shares_the_signal_between_motors() {
    let cache = SignalCache::default();
    let base = Scene::default();
    let mut other_mu_d = base.clone();
    other_mu_d.motor.mu_dynamic = 0.12;
    let mut other_a0 = base.clone();
    other_a0.motor.mu_static = 0.2;
    let first = cache.get(&base).unwrap();
    assert!(Arc::ptr_eq(&first, &cache.get(&other_mu_d).unwrap()));
    assert!(!Arc::ptr_eq(&first, &cache.get(&other_a0).unwrap()));
    for scene in [&base, &other_mu_d, &other_a0] {
        let own = steady(scene);
        let signal = cache.get(scene).unwrap();
        let with = stickslip::run(
            scene,
            &stickslip::RunOptions {
                signal: Some(&signal),
                ..Default::default()
            },
        )
        .unwrap();
        let Outcome::Steady(with) = with else {
            panic!("a steady state")
        };
        assert_eq!(
            with.indicators.v_inf.to_bits(),
            own.indicators.v_inf.to_bits()
        );
    }
}
