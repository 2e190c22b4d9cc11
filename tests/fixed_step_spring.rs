//! The fixed-step reference with a spring against the slider
//! (`engine::fixed_step`, `spring.rs`; docs/model.md section 17), against
//! closed forms and against itself:
//!
//! * with the rod at rest and an undamped tied spring, the slider is the
//!   Coulomb-damped oscillator: its turning points are
//!   [`coulomb_turning_points`] (each half swing loses `2 mu_d F_c / k`);
//! * a free end the slider never reaches changes nothing, bit for bit;
//! * a tied spring of tiny stiffness perturbs the slider's velocity by
//!   `-(k / m_s) integral x_S dt` over its slip since the last stick;
//! * a free end the slider never leaves is the tied spring of the same
//!   force;
//! * a slider that never slips on a driven rod with reaction rides with it
//!   as one body of mass `M + m_s` on stiffness `c + k`.

#[path = "common/one_body.rs"]
mod one_body;

use one_body::Oscillator;
use stickslip::Scene;
use stickslip::actuator::{DrivenRod, DrivenSpec, RealActuator, Voltage};
use stickslip::engine::{
    Event, EventKind, FixedStepEngine, FixedStepOptions, Kinematics, Mode, Observer, PeriodEnd,
    PeriodEngine, PeriodStart, Segment,
};
use stickslip::motor::{Motor, MotorParams};
use stickslip::power::ActuatorParams;
use stickslip::signal::{FourierSignal, Signal};
use stickslip::spring::{Spring, SpringEnd, coulomb_turning_points};

/// Every segment and event of a run.
#[derive(Default)]
struct Recorder {
    segments: Vec<Segment>,
    events: Vec<Event>,
}

impl Observer for Recorder {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        self.segments.push(*segment);
    }
    fn event(&mut self, event: &Event) {
        self.events.push(*event);
    }
}

/// A run of `periods` periods from rest: the period ends, the slider's
/// absolute position at each period start, and what was recorded.
struct Run {
    ends: Vec<PeriodEnd>,
    origins: Vec<f64>,
    recorded: Recorder,
}

fn run(engine: &mut FixedStepEngine, periods: u64) -> Run {
    let mut recorded = Recorder::default();
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let (mut ends, mut origins) = (Vec::new(), Vec::new());
    for p in 1..=periods {
        origins.push(if p == 1 {
            0.0
        } else {
            engine.slider_position()
        });
        let end = engine
            .run_period(p, start, &mut recorded)
            .expect("the period runs");
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
        ends.push(end);
    }
    Run {
        ends,
        origins,
        recorded,
    }
}

fn options(steps: u32) -> FixedStepOptions {
    FixedStepOptions {
        steps_per_harmonic: steps,
        ..FixedStepOptions::default()
    }
}

fn tied(stiffness: f64, damping: f64, preload: f64) -> Spring {
    let spring = Spring {
        stiffness,
        damping,
        end: SpringEnd::Tied { preload },
    };
    spring.validate().expect("a valid spring");
    spring
}

fn free(stiffness: f64, gap: f64) -> Spring {
    let spring = Spring {
        stiffness,
        damping: 0.0,
        end: SpringEnd::Free { gap },
    };
    spring.validate().expect("a valid spring");
    spring
}

/// The paper's default signal and motor.
fn default_scene() -> (Signal, Motor) {
    let built = Scene::default().build().expect("the default scene builds");
    (built.signal, built.motor)
}

/// Least-squares slope of `log2 e` against `-log2 h` over step counts
/// doubling from one error to the next: the convergence order.
fn order(errors: &[f64]) -> f64 {
    let n = errors.len() as f64;
    let xs: Vec<f64> = (0..errors.len()).map(|i| i as f64).collect();
    let ys: Vec<f64> = errors.iter().map(|e| -e.log2()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// The slider's turning points (absolute positions) from a run's
/// segments: where a slip segment's velocity changes sign, the extremum of
/// its constant-acceleration motion `x_0 - v_0^2 / (2 a)`, and every
/// stick phase's position (the slider at rest on the resting rod: the end
/// of its first segment); the release point first.
fn turning_points(run: &Run) -> Vec<f64> {
    let mut points = vec![0.0];
    let mut stuck = false;
    for s in &run.recorded.segments {
        let origin = run.origins[(s.period - 1) as usize];
        match s.mode {
            Mode::Stick => {
                // The first step of a stick segment may be the one in which
                // the slider came to rest: its end is the rest position.
                if !stuck {
                    points.push(origin + s.slider_end.x);
                }
                stuck = true;
            }
            Mode::Slip(_) => {
                stuck = false;
                let (v0, v1) = (s.slider_start.v, s.slider_end.v);
                if v0 * v1 < 0.0 {
                    points.push(origin + s.slider_start.x - v0 * v0 / (2.0 * s.slip_acceleration));
                }
            }
        }
    }
    points
}

/// With the rod at rest (a series of zero coefficients) and an undamped
/// tied spring whose rest position is `x0` from the slider's start
/// (`F_p = -k x0`), the slider swings as the Coulomb-damped oscillator:
/// its turning points relative to the spring's rest are those of
/// `coulomb_turning_points(-x0, ..)` (the closed form of spring.rs: each
/// half swing loses `2 mu_d F_c / k`), it comes to rest inside
/// `|k x| <= mu_0 F_c` and stays there. The scheme's error in the turning
/// points falls at second order: in slip the step is the trapezoidal rule
/// for the linear oscillator (energy kept exactly without damping), and
/// the first-order velocity error after a step holding an event sits
/// where the slider is slow, costing the swing `O(h^2)` of its energy.
#[test]
fn coulomb_turning_points_with_the_rod_at_rest_at_second_order() {
    let motor = Motor::new(MotorParams::default()).expect("the default motor");
    let (m, f_c) = (motor.params().slider_mass, motor.contact_force());
    let (f_d, f_0) = (motor.mu_d() * f_c, motor.params().mu_static * f_c);
    // k = 1 kN/m: natural period 2 pi sqrt(m_s / k) = 7.4 ms; the rest
    // 1.01 mm away, about 3.2 friction lengths 2 f_d / k = 0.31 mm: three
    // half swings, the slider stopping 0.07 mm from the spring's rest.
    let (k, x0) = (1e3, 1.01e-3);
    let expected: Vec<f64> = coulomb_turning_points(-x0, k, f_d, f_0)
        .iter()
        .map(|y| y + x0)
        .collect();
    let last = expected.last().unwrap() - x0;
    // The slider stops clear of the band's edge and of the swing
    // threshold, so that a grid error cannot change the count.
    assert!((k * last).abs() < 0.8 * f_0, "{expected:?}");
    assert!(expected.len() >= 4, "{expected:?}");
    let signal = Signal::Fourier(FourierSignal::from_coefficients(
        1e-3,
        0.0,
        vec![0.0],
        vec![0.0],
    ));
    let spring = tied(k, 0.0, -k * x0);
    let periods = 40;
    let half_swing = std::f64::consts::PI * (m / k).sqrt();
    let mut errors = Vec::new();
    for steps in [100, 200, 400, 800, 1600] {
        let mut engine = FixedStepEngine::new(&signal, &motor, options(steps)).with_spring(spring);
        assert!(engine.carries_rod_state());
        let r = run(&mut engine, periods);
        let points = turning_points(&r);
        assert_eq!(points.len(), expected.len(), "{points:?} {expected:?}");
        let error = points
            .iter()
            .zip(&expected)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        // O(h): within the distance the fastest swing covers in a step.
        let h = engine.step();
        let v_max = (k / m).sqrt() * x0;
        assert!(
            error < v_max * h,
            "{steps}: error {error:e}, v h {:e}",
            v_max * h
        );
        // At rest on the last turning point to the end (the run spans
        // many more half swings than it has).
        assert!(r.ends.len() as f64 * 1e-3 > 2.0 * half_swing * expected.len() as f64);
        let rest = engine.slider_position();
        assert_eq!(r.ends.last().unwrap().mode, Mode::Stick);
        assert!(
            (rest - points.last().unwrap()).abs() <= 1e-15,
            "{rest} {points:?}"
        );
        errors.push(error);
    }
    let p = order(&errors);
    assert!((1.8..2.3).contains(&p), "errors {errors:?}, order {p}");
}

/// Consecutive stick segments merged into one: an engine with a spring
/// cuts its stick segments at the slider's velocity extrema, the
/// spring-free engine does not.
fn merge_sticks(segments: &[Segment]) -> Vec<Segment> {
    let mut merged: Vec<Segment> = Vec::new();
    for s in segments {
        match merged.last_mut() {
            Some(last)
                if last.mode == Mode::Stick
                    && s.mode == Mode::Stick
                    && last.period == s.period
                    && last.end == s.start =>
            {
                last.end = s.end;
                last.slider_end = s.slider_end;
                last.rod_end = s.rod_end;
            }
            _ => merged.push(*s),
        }
    }
    merged
}

/// A free end farther than the slider travels (1 m, against some 20
/// micrometres in the run) never acts: the run is the spring-free
/// engine's bit for bit, period ends, events and segments (the stick
/// segments merged where the spring's engine cuts them at velocity
/// extrema), and no contact event happens. The slider's absolute position
/// is the sum of the steps.
#[test]
fn a_free_end_out_of_reach_changes_nothing() {
    let (signal, motor) = default_scene();
    let periods = 12;
    let mut plain = FixedStepEngine::new(&signal, &motor, options(500));
    let mut sprung =
        FixedStepEngine::new(&signal, &motor, options(500)).with_spring(free(1e4, 1.0));
    assert!(!plain.carries_rod_state() && sprung.carries_rod_state());
    let a = run(&mut plain, periods);
    let b = run(&mut sprung, periods);
    assert_eq!(a.ends, b.ends);
    assert_eq!(a.recorded.events, b.recorded.events);
    assert!(b.recorded.events.iter().all(|e| !e.kind.is_contact()));
    // The run had stick and slip and moved the slider.
    assert!(
        a.recorded.events.len() > 10,
        "{} events",
        a.recorded.events.len()
    );
    assert_eq!(
        merge_sticks(&a.recorded.segments),
        merge_sticks(&b.recorded.segments)
    );
    assert!(b.recorded.segments.len() >= a.recorded.segments.len());
    let travelled: f64 = b.ends.iter().map(|e| e.step).sum();
    assert!(travelled > 1e-5 && travelled < 1e-3, "{travelled}");
    assert!((sprung.slider_position() - travelled).abs() <= 1e-15 * periods as f64);
    assert_eq!(plain.slider_position(), sprung.slider_position());
}

/// A tied spring of zero preload and tiny stiffness (`k = 1e-6 N/m`)
/// perturbs the slider by `k x_S / m_s`: with the same events (the
/// perturbation moves none across a node), a stuck slider is on the rod
/// (no change) and a slipping one has lost `(k / m_s) integral x_S dt`
/// since it last stuck, the integral taken over the spring-free run's own
/// constant-acceleration segments (`dt (x_0 + x_1) / 2 - a dt^3 / 12`
/// each). The change is first order in `k` (the second-order terms are
/// some `1e-10` of it); the velocities' rounding (`eps |v|` a step, over
/// thousands of steps) leaves agreement to `2e-3` of a change that is
/// itself `1e4 eps |v|` or more.
#[test]
fn a_tiny_tied_spring_perturbs_the_velocity_by_its_impulse() {
    let (signal, motor) = default_scene();
    let m = motor.params().slider_mass;
    let k = 1e-6;
    let periods = 12;
    let mut plain = FixedStepEngine::new(&signal, &motor, options(500));
    let mut sprung =
        FixedStepEngine::new(&signal, &motor, options(500)).with_spring(tied(k, 0.0, 0.0));
    let a = run(&mut plain, periods);
    let b = run(&mut sprung, periods);
    assert_eq!(a.recorded.events, b.recorded.events);
    // integral x_S dt since the slider last stuck, at every period end.
    let mut integral = 0.0;
    let mut expected = vec![0.0; periods as usize];
    for s in &a.recorded.segments {
        let origin = a.origins[(s.period - 1) as usize];
        let dt = s.duration();
        match s.mode {
            Mode::Stick => integral = 0.0,
            Mode::Slip(_) => {
                let mean = origin + 0.5 * (s.slider_start.x + s.slider_end.x);
                integral += dt * mean - s.slip_acceleration * dt.powi(3) / 12.0;
            }
        }
        if s.end == signal.period() {
            expected[(s.period - 1) as usize] = -k / m * integral;
        }
    }
    let mut slipping = 0;
    for ((pa, pb), dv) in a.ends.iter().zip(&b.ends).zip(&expected) {
        let change = pb.velocity - pa.velocity;
        if pa.mode == Mode::Stick {
            assert_eq!(change, 0.0, "period {}", pa.period);
            continue;
        }
        slipping += 1;
        // The change is far above a single rounding of the velocity.
        assert!(dv.abs() > 1e4 * f64::EPSILON * pa.velocity.abs(), "{dv:e}");
        assert!(
            (change - dv).abs() <= 2e-3 * dv.abs(),
            "period {}: change {change:e}, expected {dv:e}",
            pa.period
        );
    }
    assert!(slipping > periods / 2, "{slipping} periods end in slip");
}

/// A free end and a tied spring give the same force `k (x_S - x_gap)`
/// while `x_S >= x_gap` (the tied spring's preload `-k x_gap`); from the
/// start the only such pair is `x_gap = 0` against preload 0, the slider
/// starting at the end. Driven forward into it (1 kN/m, the default
/// scene), the slider never leaves it: no contact event, and the run is
/// the tied spring's bit for bit. The spring did act: the slider ends
/// short of where it gets without it, by more than a stroke.
#[test]
fn a_free_end_in_permanent_contact_reads_what_the_tied_spring_reads() {
    let (signal, motor) = default_scene();
    let periods = 40;
    let k = 1e3;
    let engine = |spring| FixedStepEngine::new(&signal, &motor, options(500)).with_spring(spring);
    let mut at_end = engine(free(k, 0.0));
    let mut tied_on = engine(tied(k, 0.0, 0.0));
    let a = run(&mut at_end, periods);
    let b = run(&mut tied_on, periods);
    assert!(a.recorded.events.iter().all(|e| !e.kind.is_contact()));
    // In contact at every segment end (x_S >= 0).
    for s in &a.recorded.segments {
        let origin = a.origins[(s.period - 1) as usize];
        assert!(origin + s.slider_end.x >= 0.0, "{s:?}");
    }
    assert_eq!(a.ends, b.ends);
    assert_eq!(a.recorded.events, b.recorded.events);
    assert_eq!(a.recorded.segments, b.recorded.segments);
    assert_eq!(at_end.slider_position(), tied_on.slider_position());
    let mut plain = FixedStepEngine::new(&signal, &motor, options(500));
    run(&mut plain, periods);
    let stroke = 25e-6;
    let (x_free, x_spring) = (plain.slider_position(), at_end.slider_position());
    assert!(x_free - x_spring > stroke, "{x_free:e} {x_spring:e}");
}

/// The rod of the default actuator with reaction, driven by the voltage
/// designed for `signal`, under `motor`'s slider.
fn driven_rod(signal: &Signal, motor: &Motor) -> DrivenRod {
    let Signal::Fourier(series) = signal else {
        panic!("the default signal is a Fourier series");
    };
    let design = ActuatorParams::default();
    let spec = DrivenSpec {
        reaction: true,
        real: RealActuator::default(),
    };
    DrivenRod::new(&spec, &design, Voltage::designed(series, &design), motor)
        .expect("a valid driven rod")
}

/// A slider that static friction always holds (`mu_0 = mu_d = 1e6`) on a
/// driven rod with reaction, against a stiff tied spring (`k = c / 2`,
/// `b = 2 N s/m`, preload 100 N), rides with the rod as one body:
/// `(M + m_s) x'' + (d + b) x' + (c + k) x = alpha u - F_p` from rest
/// (the stuck system's equation with the spring). The rod agrees with
/// that closed form at every period end at second order (no event: the
/// stick step is the trapezoidal step of the one body), and the slider's
/// position is the rod's.
#[test]
fn a_stuck_slider_on_a_stiff_spring_rides_with_the_rod_as_one_body() {
    let (signal, _) = default_scene();
    let motor = Motor::new(MotorParams {
        mu_static: 1e6,
        mu_dynamic: 1e6,
        ..MotorParams::default()
    })
    .expect("a valid motor");
    let rod = driven_rod(&signal, &motor);
    let real = *rod.real();
    let (k, b, preload) = (0.5 * real.stiffness, 2.0, 100.0);
    let body = Oscillator::new(
        &rod,
        [
            real.mass + motor.params().slider_mass,
            real.damping + b,
            real.stiffness + k,
            -preload,
        ],
    );
    // Without the spring the body's position differs by more than the
    // errors checked below (the spring matters).
    let bare = Oscillator::new(
        &rod,
        [
            real.mass + motor.params().slider_mass,
            real.damping,
            real.stiffness,
            0.0,
        ],
    );
    let period = signal.period();
    let periods = 6;
    let mut errors = Vec::new();
    let mut difference: f64 = 0.0;
    for steps in [250, 500, 1000] {
        let mut e = FixedStepEngine::driven(&signal, &motor, &rod, options(steps))
            .with_spring(tied(k, b, preload));
        let mut start = PeriodStart {
            velocity: 0.0,
            mode: None,
        };
        let mut recorded = Recorder::default();
        let (mut exact, mut without) = (Kinematics::default(), Kinematics::default());
        let mut error: f64 = 0.0;
        for p in 1..=periods {
            let end = e
                .run_period(p, start, &mut recorded)
                .expect("the period runs");
            start = PeriodStart {
                velocity: end.velocity,
                mode: Some(end.mode),
            };
            let (t0, t1) = ((p - 1) as f64 * period, p as f64 * period);
            exact = body.advance(exact, t0, t1);
            without = bare.advance(without, t0, t1);
            let r = e.rod_state().expect("a driven rod");
            error = error.max((r.x - exact.x).abs());
            difference = difference.max((exact.x - without.x).abs());
            assert_eq!(end.velocity, r.v);
            assert!((e.slider_position() - r.x).abs() <= 1e-12 * 25e-6);
        }
        assert_eq!(e.counters().events.total(), 0, "no event");
        assert!(recorded.segments.iter().all(|s| s.mode == Mode::Stick));
        errors.push(error);
    }
    let p = order(&errors);
    assert!((1.9..2.1).contains(&p), "errors {errors:?}, order {p}");
    assert!(errors[0] < 1e-3 * difference, "{errors:?} {difference:e}");
}

/// A free end 10 um ahead, stiff enough (20 kN/m, 0.2 N at 10 um past
/// it, above the sliding friction) to push the slider back: the slider
/// meets and leaves it, `ContactStart` and `ContactEnd` alternating, each
/// at the first node past the end (before it the slider was on the other
/// side, within the step's travel `|v| h`), and each closing a segment.
#[test]
fn contact_events_mark_the_nodes_where_the_free_end_is_met_and_left() {
    let (signal, motor) = default_scene();
    let gap = 10e-6;
    let mut e = FixedStepEngine::new(&signal, &motor, options(500)).with_spring(free(2e4, gap));
    let r = run(&mut e, 30);
    let h = e.step();
    let contacts: Vec<&Event> = r
        .recorded
        .events
        .iter()
        .filter(|e| e.kind.is_contact())
        .collect();
    // Met (period 8) and left (period 17) at least once.
    assert!(contacts.len() >= 2, "{} contact events", contacts.len());
    for (i, ev) in contacts.iter().enumerate() {
        let expected = if i % 2 == 0 {
            EventKind::ContactStart
        } else {
            EventKind::ContactEnd
        };
        assert_eq!(ev.kind, expected, "{contacts:?}");
        // The segment that ends at the event, and the slider there.
        let s = r
            .recorded
            .segments
            .iter()
            .find(|s| s.period == ev.period && s.end == ev.phase)
            .expect("a segment ends at every contact event");
        let x = r.origins[(s.period - 1) as usize] + s.slider_end.x;
        let before = x - h * s.slider_end.v.abs().max(s.slider_start.v.abs());
        if expected == EventKind::ContactStart {
            assert!(x >= gap, "{ev:?} at {x:e}");
        } else {
            assert!(x < gap, "{ev:?} at {x:e}");
        }
        assert!((x - gap).abs() <= (x - before).abs(), "{ev:?}: {x:e}");
    }
    assert_eq!(
        e.counters().events.contact_start as usize,
        contacts.len().div_ceil(2)
    );
}
