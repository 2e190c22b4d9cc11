//! The event engine's decisions: grazing, asymmetric thresholds, rod
//! jumps, the departure skip, and long runs without drift.

mod common;

use common::*;
use stickslip::observer::EventLog;
use stickslip::{MotorParams, motor::Motor, signal::Signal};
use stickslip::{SignalSpec, signal::FourierSignal};
use stickslip::{
    engine::Direction, engine::EventKind, engine::Mode, engine::PeriodEngine, engine::PeriodStart,
};
use stickslip::{engine::EventEngine, engine::EventOptions};

/// A single harmonic `x_R = (s/2)(1 - cos w t)`: `v_R = V sin w t` with
/// `V = s w / 2`, smallest at `t = 3T/4` where `a_R = 0`.
fn single_harmonic() -> (Signal, f64) {
    let period = 1e-3;
    let s = 25e-6;
    let signal = FourierSignal::from_coefficients(period, s / 2.0, vec![-s / 2.0], vec![0.0]);
    let v_amp = s / 2.0 * 2.0 * std::f64::consts::PI / period;
    (Signal::Fourier(signal), v_amp)
}

/// With `mu_d = 0` a sliding slider keeps its velocity. Started at the rod's
/// smallest velocity `-V`, `v_rel = v_R + V >= 0` touches zero exactly once,
/// at `3T/4` (closed form): one grazing event there, after which the slider
/// sticks (`a_R = 0` lies in the band). Slightly faster, `v_rel` crosses
/// zero transversally (slip -> stick, no grazing); slightly slower, it never
/// reaches zero (no event at all).
#[test]
fn grazing_is_detected_once_and_only_at_a_tangency() {
    let (signal, v_amp) = single_harmonic();
    let motor = Motor::new(MotorParams {
        mu_dynamic: 0.0,
        ..MotorParams::default()
    })
    .unwrap();
    let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
    let period = signal.period();
    let mut first_event = |velocity: f64| {
        let mut log = EventLog::default();
        engine
            .run_period(
                2,
                PeriodStart {
                    velocity,
                    mode: None,
                },
                &mut log,
            )
            .unwrap();
        log.events.first().copied()
    };
    let touch = first_event(-v_amp).expect("an event");
    assert_eq!(touch.kind, EventKind::Grazing { then: Mode::Stick });
    assert!(
        (touch.phase - 0.75 * period).abs() < 1e-9 * period,
        "{touch:?}"
    );

    let cross = first_event(-v_amp * (1.0 - 1e-6)).expect("an event");
    assert_eq!(cross.kind, EventKind::SlipToStick);
    assert!(cross.phase < 0.75 * period);

    assert_eq!(first_event(-v_amp * (1.0 + 1e-6)), None);
}

/// The departure skip: after every event that starts a slip at `v_rel = 0`
/// the next event lies strictly later (no event fires twice), across many
/// periods of scenes rich in events.
#[test]
fn no_event_fires_twice() {
    for spec in [
        fourier(25e-6, 0.36, 5, true),
        fourier(25e-6, 0.5625, 4, true),
        fourier(25e-6, 1.0, 12, false),
        ideal(0.8, 0.5),
    ] {
        let motor = paper_motor();
        let signal = Signal::build(&spec, &motor).unwrap();
        let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
        let mut log = EventLog::default();
        let mut start = PeriodStart {
            velocity: 0.0,
            mode: None,
        };
        for p in 1..=50 {
            let end = engine.run_period(p, start, &mut log).unwrap();
            start = PeriodStart {
                velocity: end.velocity,
                mode: Some(end.mode),
            };
        }
        assert!(log.events.len() > 50, "{spec:?}");
        for w in log.events.windows(2) {
            let (a, b) = (w[0], w[1]);
            let later = (b.period, b.phase) > (a.period, a.phase);
            // A jump may coincide with the mode decision it forces.
            let same_instant_allowed = matches!(a.kind, EventKind::Jump { .. });
            assert!(later || same_instant_allowed, "{spec:?}: {a:?} then {b:?}");
        }
    }
}

/// Asymmetric thresholds (docs/model.md section 1) on the ideal continuous
/// signal. Stick-slip (`a_R <= a_0^+`): after the jump the slider slips
/// back with `-a_d + g_t` until `tau* = a_R T / (a_R + a_d - g_t)`, then
/// sticks, so `x_p = x_Rmax (1 + tau*/T)` for `p >= 2` (the closed form of
/// section 7 with `a_d -> a_d - g_t`).
#[test]
fn extra_acceleration_shifts_the_stick_slip_closed_form() {
    // g_t >= -0.1 a_0 keeps a_R = 0.9 a_0 inside the band.
    for g_t in [-12.0, -5.0, 12.0, 40.0] {
        let mut scene = scene_with(ideal(0.9, 1.0));
        scene.motor.extra_acceleration = g_t;
        let motor = Motor::new(scene.motor).unwrap();
        let r = run(&scene);
        let a_r = 0.9 * motor.a_0();
        let t = r.period;
        let tau = a_r * t / (a_r + motor.a_d() - g_t);
        let expected = 25e-6 * (1.0 + tau / t) / t;
        assert_rel(r.indicators.v_inf, expected, 1e-12, &format!("g_t = {g_t}"));
        assert_eq!(r.startup_periods, Some(2));
    }
}

/// Slip-slip with `g_t` (`a_R > a_0^+`): back-slip with `-a_d + g_t` from
/// `v0` until the rod overtakes at `t*`, then forward slip with `a_d + g_t`.
/// Periodicity gives `t* = (a_d + g_t) T / (2 a_d)`,
/// `v0 = t* (a_R + a_d - g_t)`, and the step is the integral of `v_S`.
#[test]
fn extra_acceleration_shifts_the_slip_slip_closed_form() {
    for g_t in [-40.0, -10.0, 25.0, 60.0] {
        let mut scene = scene_with(ideal(4.0, 1.0));
        scene.motor.extra_acceleration = g_t;
        let motor = Motor::new(scene.motor).unwrap();
        let r = run(&scene);
        let (a_r, a_d, t) = (4.0 * motor.a_0(), motor.a_d(), r.period);
        let ts = (a_d + g_t) * t / (2.0 * a_d);
        let v0 = ts * (a_r + a_d - g_t);
        let step = v0 * ts - (a_d - g_t) * ts * ts / 2.0
            + a_r * ts * (t - ts)
            + (a_d + g_t) * (t - ts).powi(2) / 2.0;
        assert_rel(r.indicators.v_inf, step / t, 1e-12, &format!("g_t = {g_t}"));
    }
}

/// The discrete ideal signal (`t_1 < T`): in each period the rod jumps once
/// at `t_1`, and with `kappa <= 1` the slider sticks in the acceleration
/// phase, slips back after the jump and, if the rest phase is long enough
/// (`T - t_1 >= a_R t_1 / a_d`, i.e. duty `<= 1/(1 + a_R/a_d) = 0.4746`),
/// comes to rest and sticks again: exactly one jump, one slip -> stick per
/// period, no reversal (the discrete stick-slip mode of Part I).
#[test]
fn discrete_ideal_signal_events_per_period() {
    let mut scene = scene_with(ideal(1.0, 0.4));
    scene.outputs.events = true;
    let r = run(&scene);
    let ev = r.steady.stats.events;
    assert_eq!(
        (ev.jump, ev.slip_to_stick, ev.reversal, ev.stick_to_slip),
        (1, 1, 0, 0),
        "{ev:?}"
    );
    // The slider is at rest at the period end, and its step is the stroke
    // plus the distance it coasts after the jump while friction brakes it,
    // (a_R t_1)^2 / (2 a_d) (closed form).
    assert_eq!(r.steady.boundary_velocity, 0.0);
    let motor = paper_motor();
    let t1 = (2.0 * 25e-6 / motor.a_0()).sqrt();
    let v1 = motor.a_0() * t1;
    let step = 25e-6 + v1 * v1 / (2.0 * motor.a_d());
    assert_rel(r.indicators.v_inf * r.period, step, 1e-12, "discrete step");
    let log = r.event_log.unwrap();
    let jump = log
        .iter()
        .find(|e| matches!(e.kind, EventKind::Jump { .. }))
        .unwrap();
    assert!(matches!(
        jump.kind,
        EventKind::Jump {
            then: Mode::Slip(Direction::Backward),
            ..
        }
    ));
    assert_rel(jump.phase, 0.4 * r.period, 1e-15, "jump at t_1");
}

/// Long runs lose no precision: time is `(period, phase)` and steps are
/// summed with compensation. The ideal stick-slip motion is exactly
/// periodic from period 2 on (closed form), so after `N` periods the slider
/// is at `x_1 + (N - 1) x_p`.
#[test]
fn a_million_periods_do_not_drift() {
    let motor = paper_motor();
    let mut scene = scene_with(ideal(0.5, 1.0));
    scene.outputs.indicators = vec![stickslip::Indicator::VInf];
    let signal = Signal::build(&scene.signal, &motor).unwrap();
    let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
    let n = 1_000_000u64;
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let mut total = stickslip::numerics::CompensatedSum::default();
    for p in 1..=n {
        let end = engine.run_period(p, start, &mut ()).unwrap();
        total.add(end.step);
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    let a_r = 0.5 * motor.a_0();
    let x_p = 25e-6 * (1.0 + a_r / (a_r + motor.a_d()));
    let expected = 25e-6 + (n - 1) as f64 * x_p;
    assert_rel(total.value(), expected, 1e-13, "x_S after 1e6 periods");
}

/// The frequency-limited signal spec round trip: kind "harmonics" with the
/// amplitudes and phases of a built Fourier signal reproduces its motion.
#[test]
fn harmonics_spec_reproduces_a_fourier_signal() {
    let motor = paper_motor();
    let Signal::Fourier(f) = Signal::build(&fourier(25e-6, 36.0, 2, true), &motor).unwrap() else {
        unreachable!()
    };
    let spec = SignalSpec::Harmonics {
        frequency: f.f0(),
        amplitudes: f.amplitudes(),
        phases: f.phases(),
        scale_to_stroke: None,
        shift_to_minimum: true,
    };
    let a = run(&scene_with(fourier(25e-6, 36.0, 2, true)));
    let b = run(&scene_with(spec));
    assert_rel(b.indicators.v_inf, a.indicators.v_inf, 1e-12, "v_inf");
    assert_eq!(a.startup_periods, b.startup_periods);
}

/// Modes of operation (Part I; section 7 of the paper): a rod acceleration
/// inside the stick band keeps the slider stuck; the paper's default signal
/// runs slip-slip ("no significant phases of stiction"); the stick-heavy
/// scene (n = 5, kappa = 0.36, sigma) sticks in every period (its reference
/// stiction fraction is 0.25, section7_grid.csv).
#[test]
fn steady_state_regimes() {
    use stickslip::simulation::Regime;
    let cases = [
        (fourier(25e-6, 1e-4, 5, true), Regime::Stuck),
        (fourier(25e-6, 36.0, 2, true), Regime::SlipSlip),
        (fourier(25e-6, 0.36, 5, true), Regime::StickSlip),
        (ideal(0.5, 1.0), Regime::StickSlip),
        (ideal(4.0, 1.0), Regime::SlipSlip),
    ];
    for (spec, regime) in cases {
        let r = run(&scene_with(spec.clone()));
        assert_eq!(r.regime(), regime, "{spec:?}");
    }
}
