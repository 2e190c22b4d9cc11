//! The exact engine with a spring against the slider (docs/model.md
//! section 17): closed forms with the rod at rest.

use stickslip::engine::{DrivenEngine, Mode, PeriodEngine, PeriodStart};
use stickslip::motor::Motor;
use stickslip::observer::Trajectory;
use stickslip::signal::{FourierSignal, Signal};
use stickslip::spring::{Spring, SpringEnd, coulomb_turning_points};

/// A rod at rest: a Fourier signal of zero stroke, reached through the
/// library (a scene's signal needs a stroke).
fn rod_at_rest(period: f64) -> Signal {
    Signal::Fourier(FourierSignal::from_coefficients(
        period,
        0.0,
        vec![0.0],
        vec![0.0],
    ))
}

/// The slider's absolute position at the end of every slip segment that
/// ends with `v_S = 0` (`v_rel = 0` with the rod at rest), over `periods`.
fn turning_points(engine: &mut DrivenEngine<'_>, periods: u64) -> Vec<f64> {
    let mut points = Vec::new();
    let mut x_start = 0.0;
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    for p in 1..=periods {
        let mut t = Trajectory::default();
        let end = engine.run_period(p, start, &mut t).expect("a period");
        for s in &t.segments {
            if matches!(s.mode, Mode::Slip(_)) && s.slider_end.v.abs() < 1e-12 {
                points.push(x_start + s.slider_end.x);
            }
        }
        x_start = engine
            .boundary_state()
            .and_then(|z| z.slider)
            .expect("a slider against a spring")
            .x;
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    points
}

/// With the rod at rest, a slider released on an undamped tied spring is
/// the Coulomb-damped oscillator: each half swing moves its turning point
/// `2 mu_d F_c / k` towards the spring's rest position (`4 mu_d F_c / k`
/// per cycle), and it stops at the first turning point within
/// `|k u| <= mu_0 F_c` (the closed form `coulomb_turning_points`). The
/// spring's rest position is `-F_p / k`; the slider starts at rest at 0,
/// `u_0 = F_p / k` from it. To 1e-12 of the first amplitude.
#[test]
fn a_slider_released_on_a_tied_spring_is_the_coulomb_damped_oscillator() {
    let motor = Motor::default();
    let f_d = motor.mu_d() * motor.contact_force();
    let f_0 = motor.params().mu_static * motor.contact_force();
    for (k, u0) in [(1e3, 1.3e-3), (1e4, -2.1e-4), (1e6, 7.7e-6)] {
        let spring = Spring {
            stiffness: k,
            damping: 0.0,
            end: SpringEnd::Tied { preload: k * u0 },
        };
        // Half a swing is pi sqrt(m_s / k): 3.7 ms at 1 kN/m.
        let signal = rod_at_rest(1e-3);
        let mut engine = DrivenEngine::prescribed(&signal, &motor, 1e-9, 10_000)
            .expect("a Fourier signal")
            .with_spring(spring, &motor)
            .expect("a rod without a free oscillation");
        let swings = coulomb_turning_points(u0, k, f_d, f_0);
        let found: Vec<f64> = turning_points(&mut engine, 60)
            .into_iter()
            .map(|x| x + u0)
            .collect();
        // The start is the first point of the closed form; the engine's
        // are the later ones.
        assert_eq!(
            found.len(),
            swings.len() - 1,
            "k = {k}: {found:?} against {swings:?}"
        );
        for (a, b) in found.iter().zip(&swings[1..]) {
            assert!(
                (a - b).abs() <= 1e-12 * u0.abs(),
                "k = {k}: turning point {a:e} against {b:e}"
            );
        }
        // At rest in the band at the end.
        let z = engine.boundary_state().expect("state");
        assert_eq!(z.mode, Mode::Stick, "k = {k}");
        let u_end = z.slider.expect("spring").x + u0;
        assert!((k * u_end).abs() <= f_0, "k = {k}");
        assert!((u_end - swings.last().unwrap()).abs() <= 1e-12 * u0.abs());
    }
}
