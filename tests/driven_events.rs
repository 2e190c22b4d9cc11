//! The driven engine's events against a dense scan that does not use the
//! engine's root finder (docs/model.md section 16): every segment of a
//! run is integrated again from its start state by a Taylor series
//! (`common/driven_taylor.rs`), its event function sampled densely with
//! every critical point refined, and every segment end read by the
//! friction law (`common/driven_scan.rs`, which documents how values
//! within rounding of a decision are treated). `examples/driven_events.rs`
//! runs the same over 1000 scenes and over scenes placed at changes of the
//! event structure.

#[path = "common/driven_cases.rs"]
mod driven_cases;
#[path = "common/driven_scan.rs"]
mod driven_scan;
#[path = "common/driven_taylor.rs"]
mod driven_taylor;

use driven_cases::{DrivenCase, Item, Record, Rng};
use driven_scan::{Model, Scan};
use driven_taylor::{ModeOde, Solution};
use stickslip::MotorParams;
use stickslip::actuator::{DrivenSpec, RealActuator, Voltage};
use stickslip::engine::Mode;
use stickslip::power::ActuatorParams;
use stickslip::signal::{FourierSignal, SignalSpec};

/// The mode equation of `actuator` carrying `mass` with the force `force`
/// under `voltage`.
fn ode(actuator: &ActuatorParams, mass: f64, force: f64, voltage: &Voltage) -> ModeOde {
    let (cos, sin) = voltage.harmonics().unzip();
    ModeOde {
        mass,
        damping: actuator.damping,
        stiffness: actuator.stiffness,
        alpha: actuator.transfer_factor,
        force,
        offset: voltage.offset(),
        w: voltage.omega(),
        cos,
        sin,
    }
}

/// The Taylor integrator against two closed forms: under the voltage
/// designed for it (the inverse of (23)) the actuator moves along the
/// signal; without a voltage, under a constant force, it oscillates
/// freely about `F / c`:
/// `x = F/c + e^{-sigma t} (y_0 cos nu t + (v_0 + sigma y_0) / nu sin nu t)`,
/// `y_0 = x_0 - F/c`, `nu^2 = c/M - sigma^2`. Both to 1e-13 of their scale
/// over two periods of the signal.
#[test]
fn taylor_series_follows_the_closed_forms_of_the_actuator() {
    let actuator = ActuatorParams::default();
    let signal = FourierSignal::from_coefficients(
        1.0 / 3100.0,
        12.5e-6,
        vec![-10e-6, 1.5e-6, 0.4e-6, -0.2e-6],
        vec![4e-6, -2e-6, 0.3e-6, 0.1e-6],
    );
    let voltage = Voltage::designed(&signal, &actuator);
    let forced = ode(&actuator, actuator.mass, 0.0, &voltage);
    let start = signal.state(0.0);
    let span = 2.0 * signal.period();
    let sol = Solution::new(&forced, 0.0, start.x, start.v, span);
    let v_scale = signal
        .velocity_range()
        .max
        .abs()
        .max(signal.velocity_range().min.abs());
    let a_scale = signal.acceleration_bound();
    for i in 0..=200 {
        let t = span * i as f64 / 200.0;
        let [x, v, a, _] = sol.at(t);
        let exact = signal.state(t);
        assert!(
            (x - exact.x).abs() <= 1e-13 * 25e-6,
            "x at {t}: {x} against {}",
            exact.x
        );
        assert!(
            (v - exact.v).abs() <= 1e-13 * v_scale,
            "v at {t}: {v} against {}",
            exact.v
        );
        assert!(
            (a - exact.a).abs() <= 1e-13 * a_scale,
            "a at {t}: {a} against {}",
            exact.a
        );
    }
    let silent = Voltage::from_amplitudes(3100.0, &[], &[], 0.0);
    let force = 0.3;
    let free = ode(&actuator, actuator.mass, force, &silent);
    let (x0, v0) = (2e-6, -0.05);
    let sol = Solution::new(&free, 0.0, x0, v0, span);
    let sigma = actuator.damping / (2.0 * actuator.mass);
    let nu = (actuator.stiffness / actuator.mass - sigma * sigma).sqrt();
    let rest = force / actuator.stiffness;
    let y0 = x0 - rest;
    for i in 0..=200 {
        let t = span * i as f64 / 200.0;
        let (s, c) = (nu * t).sin_cos();
        let e = (-sigma * t).exp();
        let b = (v0 + sigma * y0) / nu;
        let x = rest + e * (y0 * c + b * s);
        let v = e * ((b * nu - sigma * y0) * c - (y0 * nu + sigma * b) * s);
        let [xt, vt, _, _] = sol.at(t);
        assert!(
            (xt - x).abs() <= 1e-13 * y0.abs(),
            "free x at {t}: {xt} against {x}"
        );
        assert!(
            (vt - v).abs() <= 1e-13 * v0.abs().max(nu * y0.abs()),
            "free v at {t}: {vt} against {v}"
        );
    }
}

/// Runs and scans one case.
fn scan_case(case: &DrivenCase, periods: u64) -> (Scan, Record, Model) {
    let built = case.build().expect("the case builds");
    let (record, tol_v) = driven_cases::record(&built, periods).expect("the case runs");
    let model = Model::new(case, &built, tol_v);
    (driven_scan::scan(&model, &record), record, model)
}

/// Four periods of `case` from rest read as the scan reads them.
fn assert_scan_agrees(case: &DrivenCase) {
    let (scan, _, _) = scan_case(case, 4);
    assert!(
        scan.disagreements.is_empty(),
        "{}",
        scan.disagreements.join("\n")
    );
}

/// Over 100 random driven scenes (random motor friction, `fourier` and
/// `harmonics` signals of up to 8 harmonics, `kappa` from 0.5 to 20, real
/// actuators off their design, the reaction on and off), four periods from
/// rest each: no event missed inside a segment, every event where the scan
/// reads one and of its kind, so the counts by kind are equal; the engine's
/// rod state at every segment end is the Taylor series' to 1e-12 of its
/// scale.
#[test]
fn random_driven_scenes_have_the_events_of_a_dense_scan() {
    let mut rng = Rng::new(1);
    let mut total = Scan::default();
    let (mut sticking, mut reaction) = (0, 0);
    for i in 0..100 {
        let case = DrivenCase::random(&mut rng);
        let (scan, _, _) = scan_case(&case, 4);
        assert!(
            scan.disagreements.is_empty(),
            "scene {i}: {case:?}\n{}",
            scan.disagreements.join("\n")
        );
        assert_eq!(scan.engine, scan.scan, "scene {i}: {case:?}");
        sticking += usize::from(scan.engine.slip_to_stick > 0);
        reaction += usize::from(case.spec.reaction);
        total.merge(scan);
    }
    eprintln!(
        "events {:?}, ambiguous readings {}, segments {}, largest state difference {:e}",
        total.engine, total.ambiguous, total.segments, total.state
    );
    assert_eq!(total.missed, 0);
    // The scenes cover what the scan checks: stick phases, reversals,
    // both reaction settings.
    assert!(sticking >= 10, "{sticking} scenes with a stick phase");
    assert!(total.engine.reversal >= 500, "{:?}", total.engine);
    assert!(
        (40..=90).contains(&reaction),
        "{reaction} scenes with the reaction"
    );
}

/// The scan is not blind: an event taken out of a record, or a record
/// scanned against a stick band 2 % narrower than the one it was run
/// with, is reported.
#[test]
fn the_scan_reports_a_missing_event_and_a_stick_phase_beyond_its_band() {
    let mut rng = Rng::new(1);
    let case = (0..200)
        .map(|_| DrivenCase::random(&mut rng))
        .find(|c| {
            let (scan, _, _) = scan_case(c, 4);
            scan.engine.stick_to_slip >= 2 && scan.disagreements.is_empty()
        })
        .expect("a scene with stick phases");
    let (_, mut record, model) = scan_case(&case, 4);
    let at = record
        .items
        .iter()
        .position(|i| matches!(i, Item::Event(_)))
        .expect("an event");
    record.items.remove(at);
    let scan = driven_scan::scan(&model, &record);
    assert!(
        !scan.disagreements.is_empty(),
        "the missing event went unnoticed"
    );

    let (_, record, _) = scan_case(&case, 4);
    let narrower = DrivenCase {
        motor: MotorParams {
            mu_static: 0.98 * case.motor.mu_static,
            mu_dynamic: case.motor.mu_dynamic.min(0.98 * case.motor.mu_static),
            ..case.motor
        },
        ..case.clone()
    };
    let built = narrower.build().expect("builds");
    let model = Model::new(&narrower, &built, 1e-13 * built.signal.velocity_scale());
    let scan = driven_scan::scan(&model, &record);
    let stuck = record
        .items
        .iter()
        .filter(|i| matches!(i, Item::Segment(s) if s.mode == Mode::Stick))
        .count();
    assert!(stuck > 0);
    assert!(scan.missed > 0, "{:?}", scan.disagreements);
}

/// Two scenes placed (by `examples/driven_events.rs`) where the engine's
/// event count changes with the contact force.
fn scene(motor: MotorParams, signal: SignalSpec, reaction: bool, real: RealActuator) -> DrivenCase {
    DrivenCase {
        motor,
        signal,
        design: ActuatorParams::default(),
        spec: DrivenSpec { reaction, real },
    }
}

/// A slip that ends in stick where `a_st` sits inside the band by less
/// than the root finder's band, falling fast: the slider sticks, and
/// `a_st` leaves the band 7e-19 s later; the engine's stick search starts
/// "after an event" and takes that exit for the departure from the event,
/// so the slider stays stuck with `a_st` far below the band (-360 against
/// -226 m/s^2) for 1.4e-5 s.
#[test]
fn a_stick_phase_that_starts_on_a_band_edge_ends_when_a_st_leaves_it() {
    let case = scene(
        MotorParams {
            slider_mass: 0.0047555515067565675,
            contact_force: 20.347473119582798,
            mu_static: 0.05286357757139838,
            mu_dynamic: 0.03888523343377966,
            extra_acceleration: 0.0,
        },
        SignalSpec::fourier(2.0910055392994927e-5, 9.691603400036561, 7, true),
        false,
        RealActuator {
            damping: Some(8.694249232231872),
            stiffness: Some(29431738.89089481),
            ..RealActuator::default()
        },
    );
    assert_scan_agrees(&case);
}

/// With `mu_d = mu_0`, a stick phase ends where `a_st` touches `a_0^+`
/// almost tangentially: the forward slip's `v_rel` rises to 3e-14 m/s,
/// below `tol_v`, and falls back through zero. The engine's slip search
/// takes the whole excursion for the departure from the exit and never
/// ends the slip: the slider slides forward on a rod slower than itself
/// to the period's end (`v_rel = -0.44 m/s`).
#[test]
fn a_slip_whose_v_rel_turns_back_within_the_tolerance_ends_at_its_zero() {
    let case = scene(
        MotorParams {
            slider_mass: 0.00035535244350416706,
            contact_force: 0.7423604064597872,
            mu_static: 0.43888985936400976,
            mu_dynamic: 0.43888985936400976,
            extra_acceleration: 0.0,
        },
        SignalSpec::fourier(5.777179802180123e-5, 0.5338179630057432, 6, true),
        true,
        RealActuator {
            mass: Some(0.0030203991922304564),
            ..RealActuator::default()
        },
    );
    assert_scan_agrees(&case);
}

/// From rest the stuck system's `a_st` lies inside the band by 2.7e-10
/// m/s^2 and rises at 1.04e6 m/s^3 (a single harmonic, `mu_d` just below
/// `mu_0`); by a 50-digit evaluation of the closed form it crosses
/// `a_0^+` after 2.6e-16 s and is 0.05 m/s^2 above it 4.6e-8 s later. The
/// band decision and the stick search read the distance from the edge from
/// two evaluations that differed in the last bits, right at the search's
/// tolerance: the decision said inside, the search on the edge, and took
/// the exit for the start; the slider stayed stuck for 9.4e-5 s.
#[test]
fn a_stick_phase_from_rest_just_inside_a_band_edge_leaves_it() {
    let case = scene(
        MotorParams {
            slider_mass: 0.00915566061106585,
            contact_force: 44.41049383916847,
            mu_static: 0.10218733353631587,
            mu_dynamic: 0.10202146150001085,
            extra_acceleration: 0.0,
        },
        SignalSpec::Harmonics {
            frequency: 3127.218123029408,
            amplitudes: vec![1.4722998326449234e-5],
            phases: vec![1.6714635608256279],
            scale_to_stroke: Some(9.914318950829246e-6),
            shift_to_minimum: true,
        },
        true,
        RealActuator {
            damping: Some(10.737486815189442),
            stiffness: Some(26381369.25678998),
            ..RealActuator::default()
        },
    );
    assert_scan_agrees(&case);
}
