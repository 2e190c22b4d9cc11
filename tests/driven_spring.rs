//! A driven rod with a spring against the slider (docs/model.md sections
//! 16 and 17): closed forms of the stuck system and of a slip with the
//! voltage at zero, the prescribed rod's readings without the reaction,
//! and the fixed-step reference's convergence.

mod common;

use common::fourier;
use stickslip::actuator::{DrivenRod, DrivenSpec, RealActuator, RodModel, Voltage};
use stickslip::engine::{
    DrivenEngine, EventKind, FixedStepEngine, FixedStepOptions, PeriodEnd, PeriodEngine,
    PeriodStart,
};
use stickslip::motor::Motor;
use stickslip::observer::EventLog;
use stickslip::power::ActuatorParams;
use stickslip::signal::Signal;
use stickslip::spring::{Spring, SpringEnd};
use stickslip::{Indicator, Scene};

/// The paper's motor, its default signal (for the engine's scales) and
/// the Table 1 actuator.
fn paper() -> (Motor, Signal, ActuatorParams) {
    let built = Scene::default().build().expect("the paper's scene");
    (built.motor, built.signal, ActuatorParams::default())
}

/// The Table 1 actuator driven by no voltage at all, with the reaction:
/// the rod moves only as the slider and the spring push it.
fn at_zero_voltage(motor: &Motor, actuator: &ActuatorParams, period: f64) -> DrivenRod {
    let voltage = Voltage::from_amplitudes(1.0 / period, &[0.0], &[0.0], 0.0);
    DrivenRod::new(&DrivenSpec::default(), actuator, voltage, motor).expect("a driven rod")
}

fn tied(stiffness: f64, preload: f64) -> Spring {
    Spring {
        stiffness,
        damping: 0.0,
        end: SpringEnd::Tied { preload },
    }
}

/// `x(t)`, `x'(t)` of `m x'' + d x' + c x = f` from rest at `x = 0`, `f`
/// constant, under-damped (the textbook closed form, written here
/// independently of the engine's).
fn step_response(m: f64, d: f64, c: f64, f: f64, t: f64) -> [f64; 2] {
    let (sigma, w2) = (d / (2.0 * m), c / m);
    let nu = (w2 - sigma * sigma).sqrt();
    let x_eq = f / c;
    let decay = (-sigma * t).exp();
    let (sn, cs) = (nu * t).sin_cos();
    [
        x_eq * (1.0 - decay * (cs + sigma / nu * sn)),
        x_eq * decay * (w2 / nu) * sn,
    ]
}

/// With the voltage at zero, a slider stuck on the rod with a preloaded
/// tied spring is one damped oscillator: `(M + m_s) x'' + d x' + (c + k) x
/// = -F_p` from rest at 0 (the stuck system of `stuck.rs`, where the
/// spring's stiffness adds to the actuator's). The friction it needs stays
/// far inside the band (`F_p = 0.05 N`, `mu_0 F_c = 0.17 N`), so it stays
/// stuck. The rod's and the slider's state at the ends of the first three
/// periods agree with the closed form to 1e-12 of `|x_eq|` and
/// `omega_0 |x_eq|`, and the spring reads `F_p c / (c + k)` at rest.
#[test]
fn a_stuck_slider_on_a_preloaded_spring_moves_the_rod_as_one_damped_oscillator() {
    let (motor, signal, actuator) = paper();
    let rod = at_zero_voltage(&motor, &actuator, signal.period());
    let (k, f_p) = (1e5, 0.05);
    let mut engine = DrivenEngine::new(&signal, &rod, &motor, 1e-9, 10_000)
        .with_spring(tied(k, f_p), &motor)
        .expect("a spring in range");
    let mass = actuator.mass + motor.params().slider_mass;
    let stiffness = actuator.stiffness + k;
    let x_eq = -f_p / stiffness;
    let omega0 = (stiffness / mass).sqrt();
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    for p in 1..=3u64 {
        let mut log = EventLog::default();
        let end: PeriodEnd = engine.run_period(p, start, &mut log).expect("a period");
        assert!(log.events.is_empty(), "stays stuck: {:?}", log.events);
        let t = p as f64 * signal.period();
        let [x, v] = step_response(mass, actuator.damping, stiffness, -f_p, t);
        let z = engine.boundary_state().expect("a state");
        let slider = z.slider.expect("a slider against a spring");
        assert!(
            (z.rod_x - x).abs() <= 1e-12 * x_eq.abs(),
            "x_R {} against {x}",
            z.rod_x
        );
        assert!(
            (z.rod_v - v).abs() <= 1e-12 * omega0 * x_eq.abs(),
            "v_R {} against {v}",
            z.rod_v
        );
        assert!(
            (slider.x - x).abs() <= 1e-12 * x_eq.abs(),
            "x_S {}",
            slider.x
        );
        assert!((end.velocity - v).abs() <= 1e-12 * omega0 * x_eq.abs());
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    let force_at_rest = f_p + k * x_eq;
    assert!((force_at_rest - f_p * actuator.stiffness / stiffness).abs() <= 1e-15);
}

/// The time and state of the first event after `t = 0` of a run from rest.
fn first_event(engine: &mut DrivenEngine<'_>, period: f64) -> (f64, EventKind) {
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    for p in 1..=20u64 {
        let mut log = EventLog::default();
        let end = engine.run_period(p, start, &mut log).expect("a period");
        if let Some(e) = log.events.first() {
            return ((e.period - 1) as f64 * period + e.phase, e.kind);
        }
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    panic!("no event in 20 periods");
}

/// With the voltage at zero and a preload beyond what static friction
/// holds (`F_p = 0.5 N` against `mu_0 F_c = 0.17 N`, so the stuck system
/// would need `F_p M / (M + m_s) = 0.35 N`), the slider slips from rest
/// on the spring while the friction's reaction deflects the rod: two
/// independent damped oscillators, `m_s x_S'' + k x_S = mu_d F_c - F_p`
/// and `M x_R'' + d x_R' + c x_R = -mu_d F_c` (forward slip, `v_rel > 0`),
/// until `v_rel = v_R - v_S` returns to zero. That zero, bracketed on the
/// closed forms and bisected to the last bit, is the engine's first event
/// to 1e-12 of the period: the finder's function with two oscillators.
#[test]
fn a_slip_on_a_spring_beside_the_rods_own_oscillation_ends_where_the_closed_forms_meet() {
    let (motor, signal, actuator) = paper();
    let rod = at_zero_voltage(&motor, &actuator, signal.period());
    let (k, f_p) = (1e6, 0.5);
    let mut engine = DrivenEngine::new(&signal, &rod, &motor, 1e-9, 10_000)
        .with_spring(tied(k, f_p), &motor)
        .expect("a spring in range");
    let (t_event, kind) = first_event(&mut engine, signal.period());
    let ms = motor.params().slider_mass;
    let friction = motor.mu_d() * motor.contact_force();
    let v_rel = |t: f64| {
        let v_rod = step_response(
            actuator.mass,
            actuator.damping,
            actuator.stiffness,
            -friction,
            t,
        )[1];
        let v_slider = step_response(ms, 0.0, k, friction - f_p, t)[1];
        v_rod - v_slider
    };
    // v_rel > 0 from the start until the slider's half swing ends near
    // pi / omega_s; bracket the zero by a scan, then bisect.
    let omega_s = (k / ms).sqrt();
    let (mut lo, mut hi) = (0.5 * std::f64::consts::PI / omega_s, 0.0);
    let dt = 1e-3 / omega_s;
    let mut t = lo;
    assert!(v_rel(lo) > 0.0);
    while t < 2.0 * std::f64::consts::PI / omega_s {
        t += dt;
        if v_rel(t) <= 0.0 {
            hi = t;
            break;
        }
        lo = t;
    }
    assert!(hi > 0.0, "v_rel returns to zero");
    while hi - lo > f64::EPSILON * hi {
        let mid = 0.5 * (lo + hi);
        if v_rel(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    assert!(
        (t_event - lo).abs() <= 1e-12 * signal.period(),
        "first event {kind:?} at {t_event:e} s against {lo:e} s"
    );
}

/// The paper's scene with `signal`, the rod driven as `spec` and `spring`
/// against the slider, asking for the friction energy only.
fn driven_with_spring(signal: stickslip::SignalSpec, spec: DrivenSpec, spring: Spring) -> Scene {
    let mut scene = Scene {
        signal,
        rod: RodModel::Driven(spec),
        spring: Some(spring),
        ..Scene::default()
    };
    scene.outputs.indicators = vec![Indicator::FrictionEnergy];
    scene
}

/// Without the reaction and with the actuator as designed, the voltage
/// moves the rod along the signal whatever the slider does (the inverse of
/// (23)), so a spring reads what it reads against the prescribed rod: the
/// same orbit computed with the rod's free oscillation beside the
/// slider's (two oscillators in `v_rel`) and without. Tied springs of
/// 1 kN/m to 1 MN/m and free ends of 100 kN/m at gaps 0 and 5 um (met and
/// left some 40 times in the start-up) on `n = 3`, `sqrt(kappa) = 2`: the
/// spring's forces to 1e-11 of the largest force, the contact fraction to
/// 1e-11.
#[test]
fn without_the_reaction_a_driven_rod_reads_the_spring_as_the_prescribed_rod() {
    let springs = [
        tied(1e3, 0.0),
        tied(1e5, 0.0),
        tied(1e6, 0.0),
        Spring {
            stiffness: 1e5,
            damping: 0.0,
            end: SpringEnd::Free { gap: 0.0 },
        },
        Spring {
            stiffness: 1e5,
            damping: 0.0,
            end: SpringEnd::Free { gap: 5e-6 },
        },
    ];
    let spec = DrivenSpec {
        reaction: false,
        real: RealActuator::default(),
    };
    let signal = fourier(25e-6, 4.0, 3, true);
    let mut worst: f64 = 0.0;
    for spring in springs {
        let mut prescribed = driven_with_spring(signal.clone(), spec, spring);
        prescribed.rod = RodModel::Prescribed;
        let a = common::run(&prescribed).spring.expect("a reading");
        let b = common::run(&driven_with_spring(signal.clone(), spec, spring))
            .spring
            .expect("a reading");
        assert_eq!(a.orbit_periods, b.orbit_periods, "{spring:?}");
        let scale = a.profile.force_max.abs().max(a.profile.force_min.abs());
        for (x, y) in [
            (a.profile.force_mean, b.profile.force_mean),
            (a.profile.force_max, b.profile.force_max),
            (a.profile.force_min, b.profile.force_min),
        ] {
            worst = worst.max((x - y).abs() / scale);
            assert!(
                (x - y).abs() <= 1e-11 * scale,
                "{spring:?}: {x} against {y}"
            );
        }
        let (ca, cb) = (a.profile.contact_fraction, b.profile.contact_fraction);
        assert!(
            (ca - cb).abs() <= 1e-11,
            "{spring:?}: contact {ca} against {cb}"
        );
    }
    eprintln!("largest difference {worst:.1e} of the force scale");
}

/// The fixed-step reference with a driven rod and a spring (the stick step
/// shares the spring's impulse between rod and slider) converges to the
/// exact engine at first order: the rod's and the slider's state after 20
/// periods from rest, at 1000 to 256000 steps per harmonic (a factor 256:
/// the error constant scatters with where the events fall on the grid),
/// with the reaction on: on `n = 3`, `sqrt(kappa) = 2` (slip-slip) a tied
/// spring of 100 kN/m and a free end of 100 kN/m 5 um ahead (which the
/// slider meets and leaves), on `sqrt(kappa) = 0.5` a preloaded tied
/// spring of 100 kN/m with stick phases (the stick mode on the spring);
/// least-squares order between 0.7 and 1.6 (the reference is first order,
/// docs/model.md section 12).
#[test]
fn the_fixed_step_engine_with_a_driven_rod_and_a_spring_converges_at_first_order() {
    let (motor, _, actuator) = paper();
    let periods = 20;
    let free = Spring {
        stiffness: 1e5,
        damping: 0.0,
        end: SpringEnd::Free { gap: 5e-6 },
    };
    for (kappa, spring) in [(4.0, tied(1e5, 0.0)), (4.0, free), (0.25, tied(1e5, 0.02))] {
        let scene = Scene {
            signal: fourier(25e-6, kappa, 3, true),
            ..Scene::default()
        };
        let signal = scene.build().expect("the scene").signal;
        let voltage = match &signal {
            Signal::Fourier(series) => Voltage::designed(series, &actuator),
            _ => unreachable!("a Fourier signal"),
        };
        let rod =
            DrivenRod::new(&DrivenSpec::default(), &actuator, voltage, &motor).expect("a rod");
        let mut exact = DrivenEngine::new(&signal, &rod, &motor, 1e-9, 10_000)
            .with_spring(spring, &motor)
            .expect("a spring in range");
        let mut log = EventLog::default();
        let e_end = common::from_rest(periods, &mut |p, s| {
            exact.run_period(p, s, &mut log).expect("a period")
        });
        let count = |kind: EventKind| log.events.iter().filter(|e| e.kind == kind).count();
        if matches!(spring.end, SpringEnd::Free { .. }) {
            assert!(
                count(EventKind::ContactStart) >= 2,
                "the free end is met and met again"
            );
        }
        if kappa < 1.0 {
            let stuck = log
                .events
                .iter()
                .filter(|e| e.kind == EventKind::SlipToStick);
            assert!(
                stuck.count() >= 10,
                "the slider sticks and slips: {:?}",
                log.events
            );
        }
        let z = exact.boundary_state().expect("a state");
        let x_exact = z.slider.expect("a spring").x;
        let (mut hs, mut errors) = (Vec::new(), Vec::new());
        for steps in [1000u32, 4000, 16000, 64000, 256000] {
            let options = FixedStepOptions {
                steps_per_harmonic: steps,
                ..FixedStepOptions::default()
            };
            let mut fixed =
                FixedStepEngine::driven(&signal, &motor, &rod, options).with_spring(spring);
            let f_end = common::from_rest(periods, &mut |p, s| {
                fixed.run_period(p, s, &mut ()).expect("a period")
            });
            let dx = (fixed.slider_position() - x_exact).abs() / 1e-6;
            let dv = (f_end.velocity - e_end.velocity).abs() / signal.velocity_scale();
            hs.push(1.0 / f64::from(steps));
            errors.push(dx.max(dv));
        }
        let slope = common::log_slope(&hs, &errors);
        eprintln!("{spring:?}: errors {errors:?}, order {slope:.2}");
        assert!(
            (0.7..1.6).contains(&slope),
            "{spring:?}: order {slope}: errors {errors:?}"
        );
        assert!(errors.last().unwrap() < &1e-3, "{spring:?}: {errors:?}");
    }
}

/// `v_inf` does not apply against a spring, so neither do its
/// sensitivities: the library refuses them, naming the field `spring`,
/// for a prescribed and for a driven rod, and `run --sensitivities`
/// exits non-zero with one line.
#[test]
fn the_sensitivities_of_v_inf_are_refused_against_a_spring() {
    let prescribed = {
        let mut scene = Scene {
            spring: Some(tied(1e4, 0.0)),
            ..Scene::default()
        };
        scene.outputs.indicators = vec![Indicator::FrictionEnergy];
        scene
    };
    let report = common::run(&prescribed);
    let refused = report.sensitivities(&prescribed).expect_err("refused");
    assert!(refused.to_string().contains("spring"), "{refused}");
    let driven = driven_with_spring(
        fourier(25e-6, 4.0, 3, true),
        DrivenSpec::default(),
        tied(1e4, 0.0),
    );
    let report = common::run(&driven);
    let refused = report.actuator_sensitivities(&driven).expect_err("refused");
    assert!(refused.to_string().contains("spring"), "{refused}");
    let dir = common::scratch("driven_spring", "sensitivities");
    let text = driven.to_toml();
    let path = common::write(&dir, "scene.toml", &text);
    let out = common::stickslip(&["run", common::s(&path), "--sensitivities"]);
    let err = common::failure(out);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("spring") && err.contains("--sensitivities"),
        "{err}"
    );
}

/// The fixed-step reference has no steady orbit of its own against a
/// spring (its period map is neutral in slip-slip, docs/model.md section
/// 12), so a scene asks for it in vain: refused in one line naming
/// `run.engine`, while `check` compares it with the exact engine.
#[test]
fn a_spring_with_the_fixed_step_engine_is_refused_naming_the_engine() {
    let mut scene = Scene {
        spring: Some(tied(1e4, 0.0)),
        ..Scene::default()
    };
    scene.outputs.indicators = vec![Indicator::FrictionEnergy];
    assert!(scene.validate().is_ok());
    scene.run.engine = stickslip::scene::EngineKind::Fixed;
    let refused = scene.validate().expect_err("refused").to_string();
    assert!(refused.starts_with("run.engine"), "{refused}");
    assert_eq!(refused.lines().count(), 1, "{refused}");
}
