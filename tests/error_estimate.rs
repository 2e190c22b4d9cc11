//! The error estimate printed beside every run is honest: the true error
//! is below it wherever the truth is known — closed forms, exact scaling
//! laws, and the same run at a looser event-time tolerance.

mod common;

use common::*;
use stickslip::RunReport;
use stickslip::{Scene, motor::Motor};
use stickslip::{engine::EventEngine, engine::EventOptions};

fn run_with_tolerance(scene: &Scene, time_tolerance: f64) -> RunReport {
    let stickslip::scene::BuiltScene { signal, motor } = scene.build().unwrap();
    let options = EventOptions {
        time_tolerance,
        ..EventOptions::default()
    };
    stickslip::Outcome::of_engine(EventEngine::new(&signal, &motor, options), scene, &motor)
        .and_then(stickslip::Outcome::into_report)
        .unwrap()
}

/// Closed forms of docs/model.md section 7 (and the discrete step of
/// `tests/engine.rs`): the estimate bounds the true error.
#[test]
fn estimate_bounds_the_error_against_closed_forms() {
    let motor = Motor::default();
    for kappa in [0.25, 0.5, 1.0, 1.5, 4.0, 36.0] {
        let r = run(&scene_with(ideal(kappa, 1.0)));
        let a_r = kappa * motor.a_0();
        let t = r.period;
        let exact = if kappa <= 1.0 {
            25e-6 / t * (1.0 + a_r / (a_r + motor.a_d()))
        } else {
            t * (2.0 * a_r + motor.a_d()) / 4.0
        };
        let err = (r.indicators.v_inf - exact).abs();
        let est = r.error.v_inf.unwrap();
        assert!(
            err <= est,
            "kappa {kappa}: error {err:e} > estimate {est:e}"
        );
        // And it is a useful bound: within 1e-12 relative.
        assert!(est <= 1e-12 * exact, "kappa {kappa}: estimate {est:e}");
    }
}

/// The scaling laws (38), (39) hold exactly in the model, so the results at
/// two strokes, rescaled, differ only by the two runs' errors: the
/// difference must lie within the sum of the two estimates.
#[test]
fn estimate_bounds_the_scaling_law_residual() {
    for (kappa, n, sigma) in [
        (36.0, 2, true),
        (0.36, 5, true),
        (1.0, 12, true),
        (4.0, 3, false),
    ] {
        let a = run(&scene_with(fourier(25e-6, kappa, n, sigma)));
        for stroke in [1e-9, 1e-6, 1e-3] {
            let b = run(&scene_with(fourier(stroke, kappa, n, sigma)));
            let s = (25e-6 / stroke).sqrt();
            let residual = (b.indicators.v_inf * s - a.indicators.v_inf).abs();
            let bound = b.error.v_inf.unwrap() * s + a.error.v_inf.unwrap();
            assert!(
                residual <= bound,
                "kappa {kappa} n {n} stroke {stroke}: {residual:e} > {bound:e}"
            );
        }
    }
}

/// A run at a loose event-time tolerance is checked against the default
/// (tighter) run: its true error is below its own estimate.
#[test]
fn estimate_bounds_the_error_of_a_looser_run() {
    for spec in [
        fourier(25e-6, 36.0, 2, true),
        fourier(25e-6, 0.36, 5, true),
        fourier(25e-6, 1.0, 12, true),
    ] {
        let scene = scene_with(spec);
        let tight = run(&scene);
        for tol in [1e-2, 1e-4, 1e-6] {
            let loose = run_with_tolerance(&scene, tol);
            let err = (loose.indicators.v_inf - tight.indicators.v_inf).abs();
            let est = loose.error.v_inf.unwrap();
            assert!(
                err <= est,
                "{:?} tol {tol}: {err:e} > {est:e}",
                scene.signal
            );
            for (name, a, b, e) in [
                (
                    "smoothness",
                    loose.indicators.smoothness,
                    tight.indicators.smoothness,
                    loose.error.smoothness,
                ),
                (
                    "durability",
                    loose.indicators.durability,
                    tight.indicators.durability,
                    loose.error.durability,
                ),
            ] {
                assert!((a - b).abs() <= e.unwrap(), "{name} tol {tol}");
            }
        }
    }
}
