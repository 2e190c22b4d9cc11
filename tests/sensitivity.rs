//! Exact sensitivities of the steady state (docs/model.md section 14)
//! against their sources:
//! * central differences of the library's own `v_inf` on 250 seeded random
//!   scenes, every parameter, where the event structure is the same at
//!   `theta - h`, `theta` and `theta + h`;
//! * one-sided differences at changes of the event structure found by
//!   bisection;
//! * the closed forms of the continuous ideal signal under a load
//!   (`tests/common/ideal_load.rs`);
//! * the engine's own `P'(v*)` and `v_inf`, bit for bit.

mod common;
use common::event_token as token;

use common::ideal_load::{IdealRegime, ideal_load, stall_extra_acceleration};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use stickslip::Indicator;
use stickslip::Outcome;
use stickslip::sensitivity::{self, ChangeKind, Derivative, Parameter};
use stickslip::{MotorParams, Scene, motor::Motor};
use stickslip::{SignalSpec, signal::Drive, signal::IdealShape};

/// The scene with `parameter` set to `value`.
fn with(scene: &Scene, parameter: Parameter, value: f64) -> Scene {
    let varied = parameter.apply(&scene.signal, &scene.motor, value);
    let (signal, motor) = (varied.signal, varied.motor);
    Scene {
        signal,
        motor,
        ..scene.clone()
    }
}

/// `v_inf` of a scene, its error estimate (0 if none) and the event
/// structure of its steady period (as a cyclic sequence: an event that
/// moves across phase 0 changes nothing), if it has a steady state.
fn steady(scene: &Scene) -> Option<(f64, f64, Vec<String>)> {
    let Ok(Outcome::Steady(r)) = stickslip::run(scene, &stickslip::RunOptions::default()) else {
        return None;
    };
    let s =
        sensitivity::of_steady_state(&scene.signal, &scene.motor, r.steady.boundary_velocity, &[])
            .ok()?;
    // The same orbit; event times agree to the engine's tolerance.
    assert!((s.v_inf - r.indicators.v_inf).abs() <= 1e-12 * r.indicators.v_inf.abs().max(1e-300));
    let tokens: Vec<String> = s.events.iter().map(|e| token(&e.kind)).collect();
    let cycle = cycle(tokens);
    Some((
        r.indicators.v_inf,
        r.error.v_inf.unwrap_or(f64::INFINITY),
        cycle,
    ))
}

fn signal_spec() -> impl Strategy<Value = SignalSpec> {
    let shape = (-7.0f64..-4.0, -1.0f64..1.5, 0.2f64..0.95, any::<bool>()).prop_map(
        |(stroke, kappa, duty, continuous)| IdealShape {
            stroke: 10f64.powf(stroke),
            drive: Drive::Kappa(10f64.powf(kappa)),
            duty: if continuous { 1.0 } else { duty },
        },
    );
    prop_oneof![
        3 => (shape.clone(), 1usize..=8, any::<bool>()).prop_map(|(mut shape, n, sigma)| {
            shape.duty = 1.0;
            SignalSpec::Fourier { shape, harmonics: n, sigma }
        }),
        1 => shape.prop_map(SignalSpec::Ideal),
        2 => (
            prop::collection::vec((0.05f64..1.0, -3.1f64..3.1), 1..=4),
            2.0f64..4.0,
        )
            .prop_map(|(h, f)| SignalSpec::Harmonics {
                frequency: 10f64.powf(f),
                amplitudes: h.iter().map(|(d, _)| d * 1e-5).collect(),
                phases: h.iter().map(|(_, p)| *p).collect(),
                scale_to_stroke: Some(25e-6),
                shift_to_minimum: true,
            }),
    ]
}

/// Random valid scenes in the style of `tests/properties.rs`, with
/// `mu_d <= 0.95 mu_0` (a central difference of `mu_dynamic` needs room
/// below `mu_static`) and loads within what sliding friction holds.
fn scene() -> impl Strategy<Value = Scene> {
    (
        signal_spec(),
        -4.0f64..0.0,
        -2.0f64..2.0,
        0.02f64..1.0,
        0.0f64..0.95,
        -0.9f64..0.9,
    )
        .prop_map(|(signal, mass, force, mu_0, mu_ratio, g)| {
            let slider_mass = 10f64.powf(mass);
            let contact_force = 10f64.powf(force);
            let mu_dynamic = mu_0 * mu_ratio;
            let a_d = mu_dynamic * contact_force / slider_mass;
            let mut scene = Scene {
                motor: MotorParams {
                    slider_mass,
                    contact_force,
                    mu_static: mu_0,
                    mu_dynamic,
                    extra_acceleration: g * a_d,
                },
                signal,
                actuator: None,
                ..Scene::default()
            };
            scene.run.max_periods = 20_000;
            scene.outputs.indicators = vec![Indicator::VInf];
            scene
        })
}

/// Relative step of the central differences: truncation `~h^2`, rounding
/// `~1e-15 / h`, both far below the 1e-6 asked of the derivatives.
const H: f64 = 1e-5;

#[test]
fn random_scenes_match_central_differences() {
    let mut runner = TestRunner::new_with_rng(
        Config {
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &[0x5e; 32]),
    );
    let strategy = scene();
    let (mut scenes, mut checked, mut skipped) = (0, 0, 0);
    let mut regimes = std::collections::BTreeMap::new();
    while scenes < 250 {
        let scene = strategy.new_tree(&mut runner).unwrap().current();
        let Ok(Outcome::Steady(report)) = stickslip::run(&scene, &stickslip::RunOptions::default())
        else {
            continue;
        };
        let Ok(sens) = report.sensitivities(&scene) else {
            continue;
        };
        scenes += 1;
        *regimes.entry(report.regime().name()).or_insert(0) += 1;
        // The propagated P' is the engine's.
        assert!(
            (sens.map_derivative - report.steady.map_derivative).abs() <= 1e-9,
            "{scene:?}"
        );
        let (_, _, structure) = steady(&scene).unwrap();
        let motor = Motor::new(scene.motor).unwrap();
        for entry in &sens.entries {
            let theta = entry.value;
            let scale = entry.parameter.scale(&scene.signal, &motor);
            let h = H * scale;
            let (Some((up, e_up, s_up)), Some((down, e_down, s_down))) = (
                steady(&with(&scene, entry.parameter, theta + h)),
                steady(&with(&scene, entry.parameter, theta - h)),
            ) else {
                skipped += 1;
                continue;
            };
            if s_up != structure || s_down != structure {
                skipped += 1;
                continue;
            }
            let fd = (up - down) / (2.0 * h);
            let Derivative::Smooth(d) = entry.derivative else {
                panic!(
                    "{}: one-sided {:?} although the event structure is the same within \
                     {h:e}: {scene:?}",
                    entry.parameter, entry.derivative
                );
            };
            // 1e-6 relative, beyond the difference quotient's own error
            // from the runs' error estimates of v_inf.
            let tol = 1e-6 * fd.abs() + (e_up + e_down) / (2.0 * h);
            assert!(
                (d - fd).abs() <= tol,
                "{}: {d:e} vs central difference {fd:e} (tolerance {tol:e}): {scene:?}",
                entry.parameter
            );
            checked += 1;
        }
    }
    println!("{scenes} scenes {regimes:?}, {checked} derivatives checked, {skipped} skipped");
    assert!(checked >= 1000, "only {checked} derivatives checked");
    for regime in ["stick-slip", "slip-slip"] {
        assert!(
            regimes.get(regime).copied().unwrap_or(0) >= 25,
            "{regimes:?}"
        );
    }
}

/// The paper's motor with the continuous ideal signal at `kappa` and the
/// load `g_t`.
fn ideal_scene(kappa: f64, g_t: f64) -> Scene {
    let mut scene = Scene {
        signal: SignalSpec::ideal(25e-6, kappa, 1.0),
        actuator: None,
        ..Scene::default()
    };
    scene.motor.extra_acceleration = g_t;
    scene.outputs.indicators = vec![Indicator::VInf];
    scene
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn ideal_continuous_signal_under_load_matches_the_closed_forms() {
    let motor = Motor::default();
    let (a_0, a_d) = (motor.a_0(), motor.a_d());
    let (f_over_m, stroke) = (1.0 / 1.4e-3, 25e-6);
    let mut seen = std::collections::BTreeSet::new();
    for kappa in [0.3, 0.8, 1.0, 1.2, 2.0, 5.0] {
        let a_r = kappa * a_0;
        let period = (2.0 * stroke / a_r).sqrt();
        for i in 1..40 {
            let g_t = -a_d + 2.0 * a_d * f64::from(i) / 40.0;
            // kappa = 1, g_t = 0: a_R on the band edge for the whole
            // acceleration phase, the discontinuity between the regimes.
            if (a_r - a_0 - g_t).abs() < 1e-9 * a_0 {
                continue;
            }
            let expected = ideal_load(a_r, period, a_0, a_d, g_t).expect("a regime");
            seen.insert(format!("{:?}", expected.regime));
            let scene = ideal_scene(kappa, g_t);
            let report = stickslip::run(&scene, &stickslip::RunOptions::default())
                .and_then(stickslip::Outcome::into_report)
                .unwrap();
            let what = format!("kappa {kappa}, g_t {g_t}: {:?}", expected.regime);
            assert!(
                rel(report.indicators.v_inf, expected.v_inf) <= 1e-12,
                "{what}"
            );
            let sens = report.sensitivities(&scene).unwrap();
            let d = |p: Parameter| sens.get(p).unwrap().derivative.value().unwrap();
            assert!(
                rel(d(Parameter::ExtraAcceleration), expected.d_g_t) <= 1e-12,
                "{what}"
            );
            // mu_d enters through a_d = mu_d F_c / m_s only.
            assert!(
                rel(d(Parameter::MuDynamic), expected.d_a_d * f_over_m) <= 1e-12,
                "{what}"
            );
            // mu_0 through a_0: the band and the signal (a_R, T).
            assert!(
                rel(d(Parameter::MuStatic), expected.d_a_0 * f_over_m) <= 1e-12,
                "{what}: {} vs {}",
                d(Parameter::MuStatic),
                expected.d_a_0 * f_over_m
            );
        }
    }
    assert_eq!(seen.len(), 2, "both regimes: {seen:?}");
}

#[test]
fn ideal_continuous_signal_stalls_at_the_sliding_friction() {
    let motor = Motor::default();
    let (a_0, a_d) = (motor.a_0(), motor.a_d());
    for kappa in [0.5, 1.5, 4.0] {
        let a_r = kappa * a_0;
        let period = (2.0 * 25e-6 / a_r).sqrt();
        let stall = stall_extra_acceleration(a_r, a_0, a_d).unwrap();
        // Just above the stall load (g_t just above -a_d) v_inf is small
        // and positive and follows its slope there; just below, the slider
        // runs away backwards.
        for eps in [1e-2, 1e-4, 1e-6] {
            let g_t = stall + eps * a_d;
            let expected = ideal_load(a_r, period, a_0, a_d, g_t).unwrap();
            assert_eq!(expected.regime, IdealRegime::SlipSlip);
            let scene = ideal_scene(kappa, g_t);
            let report = stickslip::run(&scene, &stickslip::RunOptions::default())
                .and_then(stickslip::Outcome::into_report)
                .unwrap();
            assert!(report.indicators.v_inf > 0.0);
            // v_inf -> 0 here: against the rod's velocity scale a_R T.
            let v = report.indicators.v_inf;
            assert!(
                (v - expected.v_inf).abs() <= 1e-12 * a_r * period,
                "kappa {kappa}, eps {eps}: {v:e} vs {:e}",
                expected.v_inf
            );
            let sens = report.sensitivities(&scene).unwrap();
            let slope = sens
                .get(Parameter::ExtraAcceleration)
                .unwrap()
                .derivative
                .value()
                .unwrap();
            assert!(
                rel(slope, expected.d_g_t) <= 1e-12,
                "kappa {kappa}, eps {eps}: {slope:e} vs {:e}",
                expected.d_g_t
            );
            // The closed-form slope at the stall, T (a_R + a_d) / (2 a_d).
            let at_stall = period * (a_r + a_d) / (2.0 * a_d);
            assert!(rel(slope, at_stall) <= 2.0 * eps);
        }
        let beyond = ideal_scene(kappa, stall - 1e-3 * a_d);
        assert!(matches!(
            stickslip::run(&beyond, &stickslip::RunOptions::default()).unwrap(),
            Outcome::RunAway { .. }
        ));
    }
}

/// `v_inf` of the orbit the motion from rest converges to (simulated to
/// convergence: the definition of `v_inf`, docs/model.md section 3), the
/// sensitivities there for `parameters` and the orbit's event structure.
fn limit_from_rest(
    scene: &Scene,
    parameters: &[Parameter],
) -> Option<(f64, Vec<Derivative>, Vec<String>)> {
    let motor = Motor::new(scene.motor).ok()?;
    let signal = stickslip::signal::Signal::build(&scene.signal, &motor).ok()?;
    let boundary = sensitivity::from_rest(&signal, &motor)?;
    let s = sensitivity::of_steady_state(&scene.signal, &scene.motor, boundary, parameters).ok()?;
    let tokens: Vec<String> = s.events.iter().map(|e| token(&e.kind)).collect();
    let derivatives = s.entries.iter().map(|e| e.derivative).collect();
    Some((s.v_inf, derivatives, cycle(tokens)))
}

/// A cyclic sequence named by its smallest rotation.
fn cycle(tokens: Vec<String>) -> Vec<String> {
    (0..tokens.len().max(1))
        .map(|k| {
            let mut t = tokens.clone();
            t.rotate_left(k);
            t
        })
        .min()
        .unwrap_or_default()
}

#[test]
fn changes_of_the_event_structure_give_one_sided_derivatives() {
    let p = Parameter::ExtraAcceleration;
    let mut kinds = std::collections::BTreeMap::new();
    for signal in [
        SignalSpec::fourier(25e-6, 4.0, 2, true),
        SignalSpec::fourier(25e-6, 1.5, 3, false),
        SignalSpec::fourier(25e-6, 9.0, 4, true),
        SignalSpec::fourier(25e-6, 0.6, 2, true),
    ] {
        let scene = Scene {
            signal,
            actuator: None,
            ..Scene::default()
        };
        let motor = Motor::new(scene.motor).unwrap();
        let scale = p.scale(&scene.signal, &motor);
        let grid: Vec<f64> = (0..=30)
            .map(|i| motor.a_d() * (-0.95 + 1.9 * f64::from(i) / 30.0))
            .collect();
        let at = |g: f64| limit_from_rest(&with(&scene, p, g), &[]);
        let derivative = |g: f64| limit_from_rest(&with(&scene, p, g), &[p]).map(|x| x.1[0]);
        for w in grid.windows(2) {
            let (Some((_, _, left)), Some((_, _, right))) = (at(w[0]), at(w[1])) else {
                continue;
            };
            if left == right {
                continue;
            }
            // Bisection on the event structure to 1e-12 of g_t's scale,
            // well within NEAR of the change.
            let (mut lo, mut hi) = (w[0], w[1]);
            while hi - lo > 1e-12 * scale {
                let mid = 0.5 * (lo + hi);
                match at(mid) {
                    Some((_, _, s)) if s == left => lo = mid,
                    _ => hi = mid,
                }
            }
            let (Some((_, _, s_lo)), Some((_, _, s_hi)), Some(d_lo), Some(d_hi)) =
                (at(lo), at(hi), derivative(lo), derivative(hi))
            else {
                continue;
            };
            // One-sided differences on each branch: the derivative at the
            // change of the fit through points on the branch at k h. The
            // fit is a + b x + c x^2 (three points); where a zero of v_rel
            // is nearly tangential its time moves like sqrt(x), which adds
            // a term x^(3/2) to v_inf: then a + b x + c x^(3/2) + d x^2
            // (four points).
            let h = 1e-6 * scale;
            let side = |from: f64, step: f64, structure: &[String]| -> Option<(f64, f64)> {
                let f: Vec<f64> = (1..=4)
                    .map(|k| {
                        at(from + f64::from(k) * step)
                            .filter(|(_, _, s)| s == structure)
                            .map(|(v, _, _)| v)
                    })
                    .collect::<Option<_>>()?;
                let three = (2.5 * f[0] - 4.0 * f[1] + 1.5 * f[2]) / -step;
                Some((three, fit_with_root_term(&f) / step))
            };
            let (Some(fd_left), Some(fd_right)) = (side(lo, -h, &s_lo), side(hi, h, &s_hi)) else {
                continue;
            };
            for (d, there) in [(d_lo, lo), (d_hi, hi)] {
                let Derivative::OneSided {
                    left,
                    right,
                    change,
                } = d
                else {
                    panic!(
                        "{:?}, g_t = {there}: {s_lo:?} -> {s_hi:?} not detected: {d:?}",
                        scene.signal
                    );
                };
                let grazing = change.kind == ChangeKind::Grazing;
                let pick = |(three, four): (f64, f64)| if grazing { four } else { three };
                let (fd_left, fd_right) = (pick(fd_left), pick(fd_right));
                let rl = left.map_or(f64::NAN, |l| rel(l, fd_left));
                let rr = right.map_or(f64::NAN, |r| rel(r, fd_right));
                println!(
                    "g_t = {there}: {:?} {s_lo:?} -> {s_hi:?}: left {left:?} vs {fd_left:e} ({rl:.1e}), \
                     right {right:?} vs {fd_right:e} ({rr:.1e})",
                    change.kind
                );
                *kinds.entry(change.kind.name()).or_insert(0) += 1;
                // At a grazing the branch that sticks moves its zero of
                // v_rel like sqrt(theta - theta_c): its derivative has a
                // sqrt term, the differences converge like sqrt(h).
                let tol = if grazing { 1e-5 } else { 1e-6 };
                assert!(rl <= tol && rr <= tol, "g_t = {there}: {d:?}");
            }
        }
    }
    println!("{kinds:?}");
    for (kind, least) in [("stick_phase", 4), ("grazing", 4), ("band_edge", 2)] {
        assert!(kinds.get(kind).copied().unwrap_or(0) >= least, "{kinds:?}");
    }
}

/// The slope `b` at 0 of `a + b x + c x^(3/2) + d x^2` through `f[k-1]`
/// at `x = k`, `k = 1..4` (per step).
fn fit_with_root_term(f: &[f64]) -> f64 {
    let basis = nalgebra::Matrix4::from_fn(|i, j| {
        let x = (i + 1) as f64;
        [1.0, x, x.powf(1.5), x * x][j]
    });
    let rhs = nalgebra::Vector4::new(f[0], f[1], f[2], f[3]);
    basis.lu().solve(&rhs).expect("the four points fit")[1]
}
