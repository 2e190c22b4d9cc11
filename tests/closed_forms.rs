//! The checks with known answers of docs/model.md section 7, to 1e-12 relative.

mod common;

use common::*;
use stickslip::SignalSpec;
use stickslip::signal::Signal;

/// Ideal continuous signal, `kappa <= 1` (stick-slip). Closed form (docs/model.md
/// section 7): `v_1 = x_Rmax / T`, `v_p = (x_Rmax/T)(1 + a_R/(a_R + a_d))`
/// for `p >= 2`, so `p_0.99 = 2`.
#[test]
fn ideal_stick_slip_velocities_match_the_closed_form() {
    let motor = paper_motor();
    for kappa in [0.25, 0.5, 1.0] {
        let scene = scene_with(ideal(kappa, 1.0));
        let r = run(&scene);
        let a_r = kappa * motor.a_0();
        let t = (2.0 * 25e-6 / a_r).sqrt();
        assert_rel(r.period, t, 1e-15, "T = sqrt(2 x_Rmax / a_R)");
        let tr = r.transient.as_ref().unwrap();
        assert_rel(tr.mean_velocities[0], 25e-6 / t, 1e-12, "v_1");
        let v_p = 25e-6 / t * (1.0 + a_r / (a_r + motor.a_d()));
        for (p, v) in tr.mean_velocities.iter().enumerate().skip(1) {
            assert_rel(*v, v_p, 1e-12, &format!("v_{} at kappa {kappa}", p + 1));
        }
        assert_rel(r.indicators.v_inf, v_p, 1e-12, "v_inf");
        assert_eq!(r.startup_periods, Some(2), "p_0.99 at kappa {kappa}");
    }
}

/// Ideal continuous signal, `kappa > 1` (slip-slip): `v_inf = T (2 a_R + a_d)/4`,
/// the rod overtaking the slider exactly at `T/2` (docs/model.md section 7).
#[test]
fn ideal_slip_slip_velocity_matches_the_closed_form() {
    let motor = paper_motor();
    for kappa in [1.5, 4.0, 36.0] {
        let mut scene = scene_with(ideal(kappa, 1.0));
        scene.outputs.events = true;
        scene.run.verify_steady_state = true;
        let r = run(&scene);
        let a_r = kappa * motor.a_0();
        let t = (2.0 * 25e-6 / a_r).sqrt();
        let expected = t * (2.0 * a_r + motor.a_d()) / 4.0;
        assert_rel(
            r.indicators.v_inf,
            expected,
            1e-12,
            &format!("v_inf at kappa {kappa}"),
        );
        // In steady state one reversal (back to forward slip) at T/2 and one
        // jump per period, no stiction.
        let ev = r.steady.stats.events;
        assert_eq!(
            (ev.reversal, ev.jump, ev.slip_to_stick),
            (1, 1, 0),
            "{ev:?}"
        );
        assert_eq!(r.indicators.stiction_fraction, 0.0);
        // The transient converges to the same steady state.
        let tr = r.transient.as_ref().unwrap();
        assert_rel(tr.v_inf(), expected, 1e-10, "transient v_inf");
    }
}

/// Without friction (`mu_0 = mu_d = 0`) the slider never moves. The
/// signals are those of the paper's motor (a kappa-based signal needs
/// `a_0 > 0` to define its period).
#[test]
fn frictionless_slider_never_moves() {
    for spec in [
        ideal(4.0, 1.0),
        fourier(25e-6, 36.0, 2, true),
        fourier(25e-6, 1.0, 5, false),
    ] {
        let signal = Signal::build(&spec, &paper_motor()).unwrap();
        let mut scene = scene_with(spec);
        scene.motor = motor_with(0.0, 0.0);
        let r = run_signal(&scene, &signal);
        assert_eq!(r.indicators.v_inf, 0.0, "{:?}", scene.signal);
        assert!(
            r.transient
                .unwrap()
                .mean_velocities
                .iter()
                .all(|v| *v == 0.0)
        );
        // And a kappa-based scene without friction is refused, naming the field.
        let err = stickslip::run(&scene, &stickslip::RunOptions::default())
            .and_then(stickslip::Outcome::into_report)
            .unwrap_err()
            .to_string();
        assert!(err.contains("signal.kappa"), "{err}");
    }
}

/// A single harmonic is symmetric under `t -> t + T/2, x -> x_Rmax - x`,
/// so the slider cannot prefer a direction: `v_inf = 0` (docs/model.md section 7).
#[test]
fn single_harmonic_gives_no_net_motion() {
    for (kappa, sigma) in [(1.0, false), (36.0, true), (0.3, false), (100.0, false)] {
        let scene = scene_with(fourier(25e-6, kappa, 1, sigma));
        let r = run(&scene);
        let range = Signal::build(&scene.signal, &paper_motor())
            .unwrap()
            .velocity_range();
        let (lo, hi) = (range.min, range.max);
        assert!(
            r.indicators.v_inf.abs() <= 1e-12 * (hi - lo),
            "v_inf = {:e} at kappa {kappa}",
            r.indicators.v_inf
        );
    }
}

/// Mirroring the signal (`x_R -> -x_R`) mirrors the velocity exactly
/// (symmetry of the model with `g_t = 0`).
#[test]
fn mirrored_signal_gives_mirrored_velocity() {
    let motor = paper_motor();
    for spec in [
        fourier(25e-6, 36.0, 2, true),
        fourier(25e-6, 0.36, 5, true),
        fourier(25e-6, 4.0, 3, false),
        ideal(4.0, 1.0),
        ideal(0.5, 0.6),
    ] {
        let scene = scene_with(spec);
        let signal = Signal::build(&scene.signal, &motor).unwrap();
        let forward = run_signal(&scene, &signal);
        let backward = run_signal(&scene, &signal.mirrored());
        assert_rel(
            backward.indicators.v_inf,
            -forward.indicators.v_inf,
            1e-12,
            &format!("mirrored {:?}", scene.signal),
        );
        assert_eq!(backward.startup_periods, forward.startup_periods);
    }
}

/// `f_0 = 1574.8 Hz` at `kappa = 1` (paper, section 6.3.1): for the
/// continuous signal `f_0 = sqrt(a_0 / (2 x_Rmax))` (37).
#[test]
fn fundamental_frequency_of_the_paper() {
    let motor = paper_motor();
    let s = Signal::build(&fourier(25e-6, 1.0, 2, false), &motor).unwrap();
    assert!((s.f0() - 1574.8).abs() < 0.05, "f0 = {}", s.f0());
    assert_rel(s.f0(), (motor.a_0() / 50e-6).sqrt(), 1e-15, "(37)");
}

/// Transient and period-map steady states agree (docs/model.md section 3), with
/// the start-up simulated to convergence (`run.verify_steady_state`).
#[test]
fn transient_and_period_map_agree() {
    for spec in [
        fourier(25e-6, 36.0, 2, true),
        fourier(25e-6, 1.0, 3, false),
        fourier(25e-6, 0.36, 5, true),
        fourier(25e-6, 20.25, 2, false),
        fourier(25e-6, 1.0, 12, true),
    ] {
        let mut scene = scene_with(spec);
        scene.run.verify_steady_state = true;
        let r = run(&scene);
        let tr = r.transient.as_ref().unwrap();
        assert!(tr.converged, "{:?}", scene.signal);
        assert_rel(
            tr.v_inf(),
            r.indicators.v_inf,
            1e-10,
            &format!("{:?}", scene.signal),
        );
    }
}

/// The scene-level check that a mirrored harmonic scene (phases shifted by
/// pi) runs through the public scene path as well.
#[test]
fn mirrored_harmonics_scene() {
    let make = |shift: f64| SignalSpec::Harmonics {
        frequency: 1574.8,
        amplitudes: vec![1.2e-5, 3.0e-6],
        phases: vec![0.3 + shift, -1.1 + shift],
        scale_to_stroke: Some(25e-6),
        shift_to_minimum: true,
    };
    let a = stickslip::run(&scene_with(make(0.0)), &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .unwrap();
    // x -> -x is a phase shift of pi in every harmonic (sin(u + pi) = -sin u).
    let b = stickslip::run(
        &scene_with(make(std::f64::consts::PI)),
        &stickslip::RunOptions::default(),
    )
    .and_then(stickslip::Outcome::into_report)
    .unwrap();
    assert!(a.indicators.v_inf.abs() > 1e-3);
    assert_rel(
        b.indicators.v_inf,
        -a.indicators.v_inf,
        1e-12,
        "mirrored harmonics",
    );
}
