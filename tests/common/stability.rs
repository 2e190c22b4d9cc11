//! The stability catalogue (test support, shared by `tests/stability.rs` and
//! `examples/stability_report.rs`): stiff and extreme scenes, each with a check
//! against something known — a closed form, an exact scaling law, a
//! symmetry, or the physics of a run-away. `cargo run --release --example
//! stability_report` prints the table; `tests/stability.rs` asserts that
//! every row passes.
//!
//! Why no scene can hang: the event engine finds at most one event per
//! monotone piece of each partition of the period (a slip search skips the
//! piece it departs from, and `v_rel` is monotone on every piece), so a
//! period of a signal with `n` harmonics holds at most about `3 (2n + 2) + 1`
//! events — Zeno behaviour (infinitely many events in finite time) cannot
//! occur with these signals, and the cost per period is bounded. A slider
//! that cannot settle (the extra acceleration exceeds what sliding friction
//! can hold) is recognised as a run-away and reported with the period and
//! velocity where it left the rod's velocity range; a scene whose start-up
//! exceeds `run.max_periods` still reports its steady state from the period
//! map and says that the start-up was not reached.

// Each user (the test, the report example) reads a different part.
#![allow(dead_code)]

use std::time::Instant;
use stickslip::Error;
use stickslip::Indicator;
use stickslip::RunReport;
use stickslip::Scene;
use stickslip::numerics::CompensatedSum;
use stickslip::observer::EventLog;
use stickslip::{MotorParams, motor::Motor};
use stickslip::{SignalSpec, signal::FourierSignal, signal::Signal};
use stickslip::{engine::EventEngine, engine::EventOptions};
use stickslip::{engine::EventKind, engine::Mode, engine::PeriodEngine, engine::PeriodStart};

/// What a stress case is checked against.
#[derive(Debug, Clone)]
pub enum Check {
    /// `v_inf` equals a closed form to a relative tolerance.
    ClosedForm {
        /// The closed-form value (m/s).
        expected: f64,
        /// Relative tolerance.
        rel: f64,
        /// Where the closed form comes from.
        source: &'static str,
    },
    /// `v_inf` is exactly zero.
    Zero(&'static str),
    /// The mirrored signal gives the mirrored velocity (to 1e-12).
    Mirror,
    /// `v_inf` scales as `sqrt(factor)` against the same scene with
    /// `scene_at_factor_one` (an exact scaling law).
    Scaling {
        /// The reference scene.
        reference: Box<Scene>,
        /// The expected ratio of `v_inf`.
        ratio: f64,
        /// Which law.
        law: &'static str,
    },
    /// `v_inf` is within `rel` of the median rod velocity (very high kappa).
    Median {
        /// Relative tolerance.
        rel: f64,
    },
    /// The run ends with a run-away error.
    RunAway,
    /// A grazing event at this phase fraction of the period (closed form).
    Grazing {
        /// Expected phase / T.
        phase_fraction: f64,
    },
    /// A long run from the periodic orbit: the position after `periods`
    /// equals `periods` times the orbit's step.
    LongRun {
        /// Periods simulated.
        periods: u64,
        /// Allowed relative drift.
        rel: f64,
    },
}

/// One stress case.
#[derive(Debug, Clone)]
pub struct StressCase {
    /// Short description.
    pub name: String,
    /// The scene.
    pub scene: Scene,
    /// A signal that replaces the scene's (for motors a kappa-based signal
    /// cannot describe, such as `mu_0 = 0`).
    pub signal: Option<Signal>,
    /// What it is checked against.
    pub check: Check,
}

/// The outcome of one case.
#[derive(Debug, Clone)]
pub struct StressOutcome {
    /// The case name.
    pub name: String,
    /// Events in the simulated motion (start-up from rest).
    pub events: u64,
    /// Periods simulated in all.
    pub periods: u64,
    /// The result in words (`v_inf = ...` or the error).
    pub result: String,
    /// What it was checked against, and how close it came.
    pub check: String,
    /// Did the check pass?
    pub passed: bool,
    /// Wall time of the case (s).
    pub wall_time: f64,
    /// Engine time per simulated period in steady state (s), measured over
    /// [`COST_PERIODS`] periods with nothing observed; set-up excluded.
    pub period_cost: Option<f64>,
    /// Events per steady-state period.
    pub events_per_period: u64,
    /// Harmonics of the signal (1 for the ideal signal).
    pub harmonics: usize,
}

/// Periods timed for [`StressOutcome::period_cost`].
pub const COST_PERIODS: u64 = 2000;

/// Engine time per steady-state period of a scene (s), set-up excluded:
/// the median of five timings of [`COST_PERIODS`] periods.
pub fn period_cost(signal: &Signal, motor: &Motor, boundary_velocity: f64) -> Option<f64> {
    let mut engine = EventEngine::new(signal, motor, EventOptions::default());
    let mut timings = Vec::with_capacity(5);
    for _ in 0..5 {
        let mut start = PeriodStart {
            velocity: boundary_velocity,
            mode: None,
        };
        let clock = Instant::now();
        for p in 2..COST_PERIODS + 2 {
            let end = engine.run_period(p, start, &mut ()).ok()?;
            start = PeriodStart {
                velocity: end.velocity,
                mode: Some(end.mode),
            };
        }
        timings.push(clock.elapsed().as_secs_f64() / COST_PERIODS as f64);
    }
    timings.sort_by(f64::total_cmp);
    Some(timings[2])
}

fn fourier(stroke: f64, kappa: f64, n: usize, sigma: bool) -> SignalSpec {
    SignalSpec::fourier(stroke, kappa, n, sigma)
}

fn ideal(kappa: f64, duty: f64) -> SignalSpec {
    SignalSpec::ideal(25e-6, kappa, duty)
}

fn scene(signal: SignalSpec) -> Scene {
    let mut s = Scene {
        signal,
        actuator: None,
        ..Scene::default()
    };
    s.outputs.indicators = vec![Indicator::VInf, Indicator::StartupTime];
    s
}

fn with_motor(mut s: Scene, f: impl FnOnce(&mut MotorParams)) -> Scene {
    f(&mut s.motor);
    s
}

/// The catalogue of docs/model.md section 7 and issue 5's extreme cases.
pub fn catalogue() -> Vec<StressCase> {
    let motor = Motor::default();
    let (a_0, a_d) = (motor.a_0(), motor.a_d());
    let mut cases = Vec::new();
    let mut add = |name: String, scene: Scene, check: Check| {
        cases.push(StressCase {
            name,
            scene,
            signal: None,
            check,
        })
    };
    // kappa over ten decades.
    for kappa in [1e-4, 1e-2] {
        add(
            format!("kappa {kappa:e}, n 5, sigma"),
            scene(fourier(25e-6, kappa, 5, true)),
            Check::Zero("a_R stays inside the stick band: the slider follows the rod"),
        );
    }
    for kappa in [1.0, 1e2, 1e4] {
        add(
            format!("kappa {kappa:e}, n 2, sigma"),
            scene(fourier(25e-6, kappa, 2, true)),
            Check::Mirror,
        );
    }
    add(
        "kappa 1e6, n 2, sigma".into(),
        scene(fourier(25e-6, 1e6, 2, true)),
        Check::Median { rel: 1e-5 },
    );
    add(
        "kappa 1e6, n 5".into(),
        scene(fourier(25e-6, 1e6, 5, false)),
        Check::Median { rel: 1e-5 },
    );
    // Many harmonics.
    for n in [16, 32, 64] {
        for sigma in [false, true] {
            add(
                format!("n {n}, kappa 1, sigma {sigma}"),
                scene(fourier(25e-6, 1.0, n, sigma)),
                Check::Mirror,
            );
        }
    }
    // Strokes over six decades against 25 um: (39) v_inf ∝ sqrt(stroke).
    for stroke in [1e-9, 1e-6, 1e-3] {
        add(
            format!("stroke {stroke:e} m, default signal"),
            scene(fourier(stroke, 36.0, 2, true)),
            Check::Scaling {
                reference: Box::new(scene(fourier(25e-6, 36.0, 2, true))),
                ratio: (stroke / 25e-6).sqrt(),
                law: "(39) v_inf ∝ sqrt(stroke)",
            },
        );
    }
    // Masses and forces over six decades: only F_c / m_s matters, and at
    // fixed kappa the motion scales with a_0 as v ∝ sqrt(a_0).
    for (m, f) in [
        (1.4e-6f64, 1e-3f64),
        (1.4, 1e3),
        (1.4e-6, 1.0),
        (1.4, 1.0),
        (1.4e-3, 1e3),
    ] {
        let ratio = (f * 1.4e-3 / m).sqrt();
        add(
            format!("m_s {m:e} kg, F_c {f:e} N"),
            with_motor(scene(fourier(25e-6, 36.0, 2, true)), |p| {
                p.slider_mass = m;
                p.contact_force = f;
            }),
            Check::Scaling {
                reference: Box::new(scene(fourier(25e-6, 36.0, 2, true))),
                ratio,
                law: "v_inf ∝ sqrt(F_c / m_s) at fixed kappa",
            },
        );
    }
    // Friction corner cases.
    add(
        "mu_d = mu_0, stick-heavy".into(),
        with_motor(scene(fourier(25e-6, 0.36, 5, true)), |p| {
            p.mu_dynamic = p.mu_static
        }),
        Check::Mirror,
    );
    add(
        "mu_d = mu_0, default signal".into(),
        with_motor(scene(fourier(25e-6, 36.0, 2, true)), |p| {
            p.mu_dynamic = p.mu_static
        }),
        Check::Mirror,
    );
    add(
        "mu_d = 0 < mu_0, default signal".into(),
        with_motor(scene(fourier(25e-6, 36.0, 2, true)), |p| p.mu_dynamic = 0.0),
        Check::Mirror,
    );
    // g_t: a moderate load drives the slider backwards; a strong one makes
    // it run away.
    add(
        "g_t = -100 m/s^2 (slides backwards)".into(),
        with_motor(scene(fourier(25e-6, 36.0, 2, true)), |p| {
            p.extra_acceleration = -100.0
        }),
        Check::ClosedForm {
            expected: f64::NAN,
            rel: 0.0,
            source: "",
        },
    );
    for g in [-130.0, 200.0] {
        add(
            format!("g_t = {g} m/s^2 (beyond a_d = 112 m/s^2)"),
            with_motor(scene(fourier(25e-6, 36.0, 2, true)), |p| {
                p.extra_acceleration = g
            }),
            Check::RunAway,
        );
    }
    // Ideal signals with jumps: stick-slip and slip-slip closed forms.
    for kappa in [0.5, 1.0, 4.0, 36.0] {
        let a_r = kappa * a_0;
        let t = (2.0 * 25e-6 / a_r).sqrt();
        let (expected, source) = if kappa <= 1.0 {
            (
                25e-6 / t * (1.0 + a_r / (a_r + a_d)),
                "docs/model.md 7: (x/T)(1 + a_R/(a_R + a_d))",
            )
        } else {
            (
                t * (2.0 * a_r + a_d) / 4.0,
                "docs/model.md 7: T (2 a_R + a_d) / 4",
            )
        };
        add(
            format!("ideal continuous, kappa {kappa}"),
            scene(ideal(kappa, 1.0)),
            Check::ClosedForm {
                expected,
                rel: 1e-12,
                source,
            },
        );
    }
    {
        let t1 = (2.0 * 25e-6 / a_0).sqrt();
        let t = t1 / 0.4;
        let v1 = a_0 * t1;
        add(
            "ideal discrete, kappa 1, duty 0.4".into(),
            scene(ideal(1.0, 0.4)),
            Check::ClosedForm {
                expected: (25e-6 + v1 * v1 / (2.0 * a_d)) / t,
                rel: 1e-12,
                source: "stick, jump, coast to rest: x + (a_R t_1)^2/(2 a_d)",
            },
        );
    }
    // Simultaneous events: a_R = a_0^+ exactly (kappa = 1) when v_rel
    // reaches zero after the jump.
    {
        let t = (2.0 * 25e-6 / a_0).sqrt();
        add(
            "simultaneous: a_R = a_0 at v_rel = 0".into(),
            scene(ideal(1.0, 1.0)),
            Check::ClosedForm {
                expected: 25e-6 / t * (1.0 + a_0 / (a_0 + a_d)),
                rel: 1e-12,
                source: "docs/model.md 7 at kappa = 1 (band edge)",
            },
        );
    }
    // Long run.
    add(
        "1e7 periods from the periodic orbit".into(),
        scene(fourier(25e-6, 36.0, 2, true)),
        Check::LongRun {
            periods: 10_000_000,
            rel: 1e-12,
        },
    );
    // Constructed grazing and a frictionless motor need their own signals.
    let single = FourierSignal::from_coefficients(1e-3, 12.5e-6, vec![-12.5e-6], vec![0.0]);
    cases.push(StressCase {
        name: "constructed grazing (v_rel touches 0 at 3T/4)".into(),
        scene: with_motor(scene(fourier(25e-6, 1.0, 1, false)), |p| p.mu_dynamic = 0.0),
        signal: Some(Signal::Fourier(single)),
        check: Check::Grazing {
            phase_fraction: 0.75,
        },
    });
    cases.push(StressCase {
        name: "mu_0 = mu_d = 0 (no friction)".into(),
        scene: with_motor(scene(fourier(25e-6, 36.0, 2, true)), |p| {
            p.mu_static = 0.0;
            p.mu_dynamic = 0.0;
        }),
        signal: Some(
            Signal::build(&fourier(25e-6, 36.0, 2, true), &Motor::default())
                .expect("the paper's signal is valid"),
        ),
        check: Check::Zero("no friction: the slider never moves (docs/model.md 7)"),
    });
    cases
}

fn run_scene(case: &StressCase, scene: &Scene) -> Result<RunReport, Error> {
    match &case.signal {
        None => stickslip::run(scene, &stickslip::RunOptions::default())
            .and_then(stickslip::Outcome::into_report),
        Some(signal) => {
            let motor = Motor::new(scene.motor)?;
            let engine = EventEngine::new(signal, &motor, EventOptions::default());
            stickslip::Outcome::of_engine(engine, scene, &motor)
                .and_then(stickslip::Outcome::into_report)
        }
    }
}

fn relative(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        a.abs()
    } else {
        ((a - b) / b).abs()
    }
}

/// Runs one case and its check.
pub fn run_case(case: &StressCase) -> StressOutcome {
    let clock = Instant::now();
    let report = run_scene(case, &case.scene);
    let mut extra_periods = 0;
    let (passed, check) = match (&case.check, &report) {
        (Check::RunAway, Err(Error::Simulation(e))) => (
            e.to_string().contains("runs away"),
            "run-away reported: friction cannot hold the load".to_owned(),
        ),
        (Check::RunAway, _) => (false, "expected a run-away".into()),
        (_, Err(e)) => (false, format!("error: {e}")),
        (
            Check::ClosedForm {
                expected,
                rel,
                source,
            },
            Ok(r),
        ) if expected.is_finite() => {
            let d = relative(r.indicators.v_inf, *expected);
            (d <= *rel, format!("{source}: rel. diff {d:.1e}"))
        }
        (Check::ClosedForm { .. }, Ok(r)) => {
            // No closed form: the mirrored slider with mirrored load.
            let mut mirrored = case.scene.clone();
            mirrored.motor.extra_acceleration = -mirrored.motor.extra_acceleration;
            let m = mirrored_run(case, &mirrored);
            extra_periods += m.as_ref().map_or(0, |m| m.work.periods);
            match m {
                Ok(m) => {
                    let d = relative(m.indicators.v_inf, -r.indicators.v_inf);
                    (
                        d <= 1e-12 && r.indicators.v_inf < 0.0,
                        format!("backwards, and mirror symmetry with -g_t: rel. diff {d:.1e}"),
                    )
                }
                Err(e) => (false, format!("mirror run failed: {e}")),
            }
        }
        (Check::Zero(why), Ok(r)) => (r.indicators.v_inf == 0.0, (*why).to_owned()),
        (Check::Mirror, Ok(r)) => match mirrored_run(case, &case.scene) {
            Ok(m) => {
                extra_periods += m.work.periods;
                let d = (m.indicators.v_inf + r.indicators.v_inf).abs();
                let scale = r.indicators.v_inf.abs().max(1e-300);
                (
                    d <= 1e-12 * scale || d <= r.error.v_inf.unwrap_or(0.0) * 2.0,
                    format!("mirror symmetry: rel. diff {:.1e}", d / scale),
                )
            }
            Err(e) => (false, format!("mirror run failed: {e}")),
        },
        (
            Check::Scaling {
                reference,
                ratio,
                law,
            },
            Ok(r),
        ) => match stickslip::run(reference, &stickslip::RunOptions::default())
            .and_then(stickslip::Outcome::into_report)
        {
            Ok(base) => {
                extra_periods += base.work.periods;
                let d = relative(r.indicators.v_inf, base.indicators.v_inf * ratio);
                (d <= 1e-12, format!("{law}: rel. diff {d:.1e}"))
            }
            Err(e) => (false, format!("reference failed: {e}")),
        },
        (Check::Median { rel }, Ok(r)) => {
            let median = match case.scene.build() {
                Ok(stickslip::scene::BuiltScene {
                    signal: Signal::Fourier(f),
                    ..
                }) => f.velocity_median(),
                _ => f64::NAN,
            };
            let d = relative(r.indicators.v_inf, median);
            (
                d <= *rel,
                format!("docs/model.md 7: median rod velocity {median:.6}: rel. diff {d:.1e}"),
            )
        }
        (Check::Grazing { phase_fraction }, Ok(_)) => grazing_check(case, *phase_fraction),
        (Check::LongRun { periods, rel }, Ok(r)) => {
            extra_periods += periods;
            long_run_check(case, r, *periods, *rel)
        }
    };
    let wall_time = clock.elapsed().as_secs_f64();
    let (events, periods, result) = match &report {
        Ok(r) => (
            r.events().total(),
            r.work.periods + extra_periods,
            format!(
                "v_inf = {:.6e} m/s{}",
                r.indicators.v_inf,
                match (r.startup_periods, r.indicators.v_inf == 0.0) {
                    (_, true) => ", no net motion",
                    (None, false) => ", start-up longer than run.max_periods",
                    _ => "",
                }
            ),
        ),
        Err(e) => (0, 0, short(&e.to_string())),
    };
    let period_cost = report.as_ref().ok().and_then(|r| {
        let motor = Motor::new(case.scene.motor).ok()?;
        let signal = match &case.signal {
            Some(s) => s.clone(),
            None => Signal::build(&case.scene.signal, &motor).ok()?,
        };
        period_cost(&signal, &motor, r.steady.boundary_velocity)
    });
    let events_per_period = report.as_ref().map_or(0, |r| r.steady.stats.events.total());
    let harmonics = report.as_ref().map_or(1, |r| {
        r.f_max.map_or(1, |f| (f * r.period).round() as usize)
    });
    StressOutcome {
        name: case.name.clone(),
        events,
        periods,
        result,
        check,
        passed,
        wall_time,
        period_cost,
        events_per_period,
        harmonics,
    }
}

fn short(message: &str) -> String {
    message.split(" (").next().unwrap_or(message).to_owned()
}

fn mirrored_run(case: &StressCase, scene: &Scene) -> Result<RunReport, Error> {
    let motor = Motor::new(scene.motor)?;
    let signal = match &case.signal {
        Some(s) => s.clone(),
        None => Signal::build(&scene.signal, &motor)?,
    }
    .mirrored();
    stickslip::Outcome::of_engine(
        EventEngine::new(&signal, &motor, EventOptions::default()),
        scene,
        &motor,
    )
    .and_then(stickslip::Outcome::into_report)
}

fn grazing_check(case: &StressCase, phase_fraction: f64) -> (bool, String) {
    let Some(signal) = &case.signal else {
        return (false, "no signal".into());
    };
    let Ok(motor) = Motor::new(case.scene.motor) else {
        return (false, "invalid motor".into());
    };
    let v_min = signal.velocity_range().min;
    let mut engine = EventEngine::new(signal, &motor, EventOptions::default());
    let mut log = EventLog::default();
    let start = PeriodStart {
        velocity: v_min,
        mode: None,
    };
    if engine.run_period(2, start, &mut log).is_err() {
        return (false, "run failed".into());
    }
    let grazing: Vec<_> = log
        .events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Grazing { then: Mode::Stick }))
        .collect();
    let expected = phase_fraction * signal.period();
    let ok = grazing.len() == 1 && (grazing[0].phase - expected).abs() <= 1e-9 * signal.period();
    (
        ok,
        format!(
            "closed form: one grazing at {phase_fraction} T; found {}",
            grazing.len()
        ),
    )
}

fn long_run_check(case: &StressCase, r: &RunReport, periods: u64, rel: f64) -> (bool, String) {
    let Ok(stickslip::scene::BuiltScene { signal, motor }) = case.scene.build() else {
        return (false, "invalid scene".into());
    };
    let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
    let mut start = PeriodStart {
        velocity: r.steady.boundary_velocity,
        mode: None,
    };
    let mut total = CompensatedSum::default();
    for p in 1..=periods {
        match engine.run_period(p + 1, start, &mut ()) {
            Ok(end) => {
                total.add(end.step);
                start = PeriodStart {
                    velocity: end.velocity,
                    mode: Some(end.mode),
                };
            }
            Err(e) => return (false, format!("failed in period {p}: {e}")),
        }
    }
    let expected = periods as f64 * r.steady.stats.step;
    let d = relative(total.value(), expected);
    (
        d <= rel,
        format!("x after {periods} periods = N x_inf: rel. drift {d:.1e}"),
    )
}
