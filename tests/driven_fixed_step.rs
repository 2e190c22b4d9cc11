//! The fixed-step reference with a driven rod (`engine::fixed_step`,
//! `driven.rs`, docs/model.md section 16) on the paper's default signal,
//! against closed forms of the rod's linear equation:
//!
//! * without reaction, the actuator driven by the voltage designed for it
//!   follows the signal (the voltage is the inverse of (23));
//! * a slider that never slips rides on the rod as one body of mass
//!   `M + m_s`;
//! * with slip and reaction, between two mode changes the rod obeys (23)
//!   with the mode's constant friction or the slider's mass: the same
//!   equation, solved in closed form through the engine's segments.
//!
//! The closed form is written out here (periodic particular solution plus
//! the damped free response), independently of the crate's own.

#[path = "common/one_body.rs"]
mod one_body;

use one_body::Oscillator;
use stickslip::Scene;
use stickslip::actuator::{DrivenRod, DrivenSpec, RealActuator, Voltage};
use stickslip::engine::{
    FixedStepEngine, FixedStepOptions, Kinematics, Mode, PeriodEnd, PeriodEngine, PeriodStart,
    Segment,
};
use stickslip::motor::{Motor, MotorParams};
use stickslip::observer::Trajectory;
use stickslip::power::ActuatorParams;
use stickslip::signal::Signal;

/// The paper's default signal and motor, the Table 1 actuator.
fn default_scene() -> (Signal, Motor, ActuatorParams) {
    let built = Scene::default().build().expect("the default scene builds");
    (built.signal, built.motor, ActuatorParams::default())
}

/// The rod of the default actuator, driven by the voltage designed for
/// `signal`, under `motor`'s slider.
fn driven_rod(signal: &Signal, motor: &Motor, reaction: bool) -> DrivenRod {
    let Signal::Fourier(series) = signal else {
        panic!("the default signal is a Fourier series");
    };
    let design = ActuatorParams::default();
    let spec = DrivenSpec {
        reaction,
        real: RealActuator::default(),
    };
    DrivenRod::new(&spec, &design, Voltage::designed(series, &design), motor)
        .expect("a valid driven rod")
}

fn engine<'s>(
    signal: &'s Signal,
    motor: &Motor,
    rod: &DrivenRod,
    steps: u32,
) -> FixedStepEngine<'s> {
    let options = FixedStepOptions {
        steps_per_harmonic: steps,
        ..FixedStepOptions::default()
    };
    FixedStepEngine::driven(signal, motor, rod, options)
}

/// `periods` periods from rest: the period ends, every segment, and the
/// rod at each period end.
fn run(
    engine: &mut FixedStepEngine,
    periods: u64,
) -> (Vec<PeriodEnd>, Vec<Segment>, Vec<Kinematics>) {
    let mut trajectory = Trajectory::default();
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let (mut ends, mut rods) = (Vec::new(), Vec::new());
    for p in 1..=periods {
        let end = engine
            .run_period(p, start, &mut trajectory)
            .expect("the period runs");
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
        ends.push(end);
        rods.push(engine.rod_state().expect("a driven rod"));
    }
    (ends, trajectory.segments, rods)
}

/// Convergence orders `log2(e_i / e_{i+1})` of errors at doubling step
/// counts.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// Without reaction and with the actuator as designed, the rod obeys (23)
/// under the voltage that is its inverse for the signal, from rest at the
/// signal's start: it follows the signal exactly, and the scheme's error
/// is the trapezoidal rule's, second order.
#[test]
fn rod_without_reaction_follows_the_signal_at_second_order() {
    let (signal, motor, _) = default_scene();
    // The signal starts at rest at 0 (shifted to its minimum), so the
    // exact rod has no free oscillation.
    let s0 = signal.state(0.0);
    assert!(s0.x.abs() < 1e-20 && s0.v.abs() < 1e-12, "{s0:?}");
    let rod = driven_rod(&signal, &motor, false);
    let stroke = 25e-6;
    let mut errors = Vec::new();
    for steps in [1250, 2500, 5000] {
        let mut e = engine(&signal, &motor, &rod, steps);
        assert!(e.carries_rod_state());
        let (_, segments, rods) = run(&mut e, 5);
        // The rod at every segment end and every period end.
        let mut error: f64 = 0.0;
        for s in &segments {
            error = error.max((s.rod_start.x - signal.position(s.start)).abs());
            let end = signal.state_before(s.end);
            error = error.max((s.rod_end.x - end.x).abs());
        }
        for r in &rods {
            error = error.max((r.x - signal.position(0.0)).abs());
        }
        // The slider stuck and slipped: the rod was seen at many phases.
        assert!(segments.len() > 10, "{} segments", segments.len());
        errors.push(error);
    }
    let orders = orders(&errors);
    assert!(
        orders.iter().all(|o| (1.9..2.1).contains(o)),
        "errors {errors:?}, orders {orders:?}"
    );
    assert!(errors[2] < 1e-4 * stroke, "errors {errors:?}");
}

/// A slider that static friction always holds (`mu_0 = mu_d = 1e6`) rides
/// on the rod as one body: `(M + m_s) x'' + d x' + c x = alpha u`, from
/// rest. The rod at every period end agrees with its closed form at second
/// order, the slider moves with it, and no event happens.
#[test]
fn slider_that_never_slips_moves_with_the_rod_as_one_body() {
    let (signal, _, actuator) = default_scene();
    let motor = Motor::new(MotorParams {
        mu_static: 1e6,
        mu_dynamic: 1e6,
        ..MotorParams::default()
    })
    .expect("a valid motor");
    let rod = driven_rod(&signal, &motor, true);
    let body = Oscillator::new(
        &rod,
        [
            actuator.mass + motor.params().slider_mass,
            actuator.damping,
            actuator.stiffness,
            0.0,
        ],
    );
    let period = signal.period();
    let periods = 6;
    let mut errors = Vec::new();
    for steps in [250, 500, 1000] {
        let mut e = engine(&signal, &motor, &rod, steps);
        let (ends, segments, rods) = run(&mut e, periods);
        assert_eq!(e.counters().events.total(), 0, "no event");
        assert!(segments.iter().all(|s| s.mode == Mode::Stick));
        let mut exact = Kinematics::default();
        let mut error: f64 = 0.0;
        let mut before = Kinematics::default();
        for (p, (end, r)) in ends.iter().zip(&rods).enumerate() {
            exact = body.advance(exact, p as f64 * period, (p + 1) as f64 * period);
            error = error.max((r.x - exact.x).abs());
            // The slider moves with the rod, exactly on the grid.
            assert_eq!(end.velocity, r.v);
            assert!((end.step - (r.x - before.x)).abs() <= 1e-12 * 25e-6);
            before = *r;
        }
        // Period 1 from rest again: the state carried is reset.
        let again = e
            .run_period(
                1,
                PeriodStart {
                    velocity: 0.0,
                    mode: None,
                },
                &mut (),
            )
            .expect("the period runs");
        assert_eq!(again, ends[0]);
        errors.push(error);
    }
    let orders = orders(&errors);
    assert!(
        orders.iter().all(|o| (1.9..2.1).contains(o)),
        "errors {errors:?}, orders {orders:?}"
    );
}

/// With slip and reaction, the rod between two mode changes obeys (23)
/// with the mode's load: `M` and the friction `-+mu_d F_c` in slip, `M + m_s`
/// in stick. Solved in closed form through the engine's own segments from
/// rest, it meets the engine's rod at every segment end to first order in
/// the step (the scheme gives each step holding an event wholly to the
/// new mode).
#[test]
fn rod_with_reaction_obeys_its_equation_through_slip_and_stick() {
    let (signal, _, actuator) = default_scene();
    // Friction strong enough to hold the slider through part of each
    // period against the rod's acceleration at kappa = 36.
    let motor = Motor::new(MotorParams {
        mu_static: 40.0,
        mu_dynamic: 20.0,
        ..MotorParams::default()
    })
    .expect("a valid motor");
    let rod = driven_rod(&signal, &motor, true);
    let friction = motor.mu_d() * motor.contact_force();
    let ms = motor.params().slider_mass;
    let forward = Oscillator::new(
        &rod,
        [
            actuator.mass,
            actuator.damping,
            actuator.stiffness,
            -friction,
        ],
    );
    let backward = Oscillator::new(
        &rod,
        [
            actuator.mass,
            actuator.damping,
            actuator.stiffness,
            friction,
        ],
    );
    let stuck = Oscillator::new(
        &rod,
        [
            actuator.mass + ms,
            actuator.damping,
            actuator.stiffness,
            ms * motor.g_t(),
        ],
    );
    let period = signal.period();
    let mut errors = Vec::new();
    for steps in [500, 1000, 2000, 4000, 8000] {
        let mut e = engine(&signal, &motor, &rod, steps);
        let (_, segments, _) = run(&mut e, 4);
        assert!(segments.iter().any(|s| s.mode == Mode::Stick));
        assert!(segments.iter().any(|s| s.mode != Mode::Stick));
        let mut exact = Kinematics::default();
        let mut error: f64 = 0.0;
        for s in &segments {
            let t0 = (s.period - 1) as f64 * period;
            let law = match s.mode {
                Mode::Stick => &stuck,
                Mode::Slip(stickslip::engine::Direction::Forward) => &forward,
                Mode::Slip(stickslip::engine::Direction::Backward) => &backward,
            };
            exact = law.advance(exact, t0 + s.start, t0 + s.end);
            error = error.max((s.rod_end.x - exact.x).abs());
        }
        errors.push(error);
    }
    // Where the events fall on the grid scatters the error constant from
    // one step to the next: the order is a trend over the whole range
    // (16 times the steps).
    let order = (errors[0] / errors[4]).log2() / 4.0;
    assert!(order > 0.75, "errors {errors:?}, order {order}");
    assert!(errors[4] < 1e-4 * 25e-6, "errors {errors:?}");
}
