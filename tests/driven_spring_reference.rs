//! A driven rod with the slider against a spring (docs/model.md sections 16
//! and 17) against an independent reference:
//! `tests/data/driven_spring_reference.py`, scipy's `solve_ivp` (DOP853,
//! rtol 3e-14) integrating the rod's and the slider's equations of motion
//! numerically, with event location and Newton's method on the period map
//! of `(x_R, v_R, x_S, v_S)`; it shares no code or closed form with the
//! engine. Its output is `tests/data/driven_spring_reference.csv`
//! (provenance in its header and in `tests/data/driven_spring_reference.md`).
//!
//! Every quantity is compared within the reference's own error estimate
//! (the spread of its runs at 1, 10 and 100 times its tolerance, a column of
//! the csv), but never tighter than `1e-11`: the level at which the
//! reference, whose stick decisions cancel forces a thousand times larger
//! than the friction, stops resolving.

mod common;

use stickslip::actuator::{DrivenRod, RodModel, Voltage};
use stickslip::engine::{
    DrivenEngine, DrivenState, Event, EventCounts, EventOptions, Mode, Observer, PeriodEngine,
    PeriodStart, Segment, SliderState,
};
use stickslip::motor::Motor;
use stickslip::signal::Signal;
use stickslip::spring::SpringEnd;
use stickslip::{Outcome, RunOptions, Scene};

/// The least tolerance of any comparison (see the module docs).
const FLOOR: f64 = 1e-11;

/// One row of the reference.
struct Row {
    case: String,
    sqrt_kappa: f64,
    reaction: bool,
    spring: String,
    k: f64,
    b: f64,
    preload: f64,
    gap: f64,
    /// `orbit` or `from_rest`.
    reading: String,
    reading_periods: u64,
    mean_force: f64,
    max_force: f64,
    min_force: f64,
    contact_fraction: f64,
    stick_fraction: f64,
    mean_velocity: f64,
    orbit_period: Option<u64>,
    /// Periods to steady state, or, without an orbit, the periods from
    /// rest searched for one.
    periods_to_steady: u64,
    events: EventCounts,
    rel_err_est: f64,
    extrema_err_est: f64,
    fraction_err_est: f64,
}

fn rows() -> Vec<Row> {
    let table = common::data_table("driven_spring_reference.csv");
    let col = |name: &str| table.column(name);
    let rows: Vec<Row> = table
        .records
        .iter()
        .map(|r| {
            let text = |name: &str| r[col(name)].to_owned();
            // An empty cell: a quantity the row does not have.
            let num = |name: &str| {
                let cell = &r[col(name)];
                if cell.is_empty() {
                    f64::NAN
                } else {
                    cell.parse::<f64>()
                        .unwrap_or_else(|e| panic!("{name} = {cell}: {e}"))
                }
            };
            let count = |name: &str| r[col(name)].parse::<u64>().expect("a count");
            Row {
                case: text("case"),
                sqrt_kappa: num("sqrt_kappa"),
                reaction: &r[col("reaction")] == "true",
                spring: text("spring"),
                k: num("k"),
                b: num("b"),
                preload: num("preload"),
                gap: num("gap"),
                reading: text("reading"),
                reading_periods: count("reading_periods"),
                mean_force: num("mean_force"),
                max_force: num("max_force"),
                min_force: num("min_force"),
                contact_fraction: num("contact_fraction"),
                stick_fraction: num("stick_fraction"),
                mean_velocity: num("mean_velocity"),
                orbit_period: r[col("orbit_period")].parse().ok(),
                periods_to_steady: count("periods_to_steady"),
                events: EventCounts {
                    stick_to_slip: count("stick_slip"),
                    slip_to_stick: count("slip_stick"),
                    reversal: count("reversal"),
                    contact_start: count("contact_start"),
                    contact_end: count("contact_end"),
                    ..EventCounts::default()
                },
                rel_err_est: num("rel_err_est"),
                extrema_err_est: num("extrema_err_est"),
                fraction_err_est: num("fraction_err_est"),
            }
        })
        .collect();
    assert!(
        rows.len() >= 14,
        "{}: {} rows",
        table.path.display(),
        rows.len()
    );
    rows
}

/// The reference's scene with what `row` changes: the signal's
/// `sqrt(kappa)`, the reaction, the spring; the indicators that apply.
fn scene(row: &Row) -> Scene {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/driven_spring_reference_scene.toml"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut table: toml::Table = text.parse().expect("the reference's scene parses");
    let signal = table["signal"].as_table_mut().expect("[signal]");
    signal.insert("sqrt_kappa".into(), toml::Value::Float(row.sqrt_kappa));
    let actuator = table["actuator"].as_table_mut().expect("[actuator]");
    actuator.insert("reaction".into(), toml::Value::Boolean(row.reaction));
    let indicators = match row.spring.as_str() {
        "none" => vec!["v_inf", "stiction_fraction"],
        "tied" | "free" => {
            let mut spring = toml::Table::new();
            spring.insert("stiffness".into(), toml::Value::Float(row.k));
            let tied = row.spring == "tied";
            spring.insert("tied".into(), toml::Value::Boolean(tied));
            if tied {
                spring.insert("preload".into(), toml::Value::Float(row.preload));
                spring.insert("damping".into(), toml::Value::Float(row.b));
            } else {
                spring.insert("gap".into(), toml::Value::Float(row.gap));
            }
            table.insert("spring".into(), toml::Value::Table(spring));
            vec!["friction_energy", "stiction_fraction"]
        }
        other => panic!("unknown spring {other}"),
    };
    let mut outputs = toml::Table::new();
    outputs.insert(
        "indicators".into(),
        toml::Value::Array(
            indicators
                .into_iter()
                .map(|s| toml::Value::String(s.into()))
                .collect(),
        ),
    );
    table.insert("outputs".into(), toml::Value::Table(outputs));
    Scene::from_toml_str(&toml::to_string(&table).expect("TOML"), "reference")
        .expect("a valid scene")
}

/// `|a - b| <= max(estimate, FLOOR) scale`, with a message.
fn assert_within(at: &str, what: &str, (a, b): (f64, f64), scale: f64, estimate: f64) {
    let tol = estimate.max(FLOOR);
    assert!(
        (a - b).abs() <= tol * scale,
        "{at}: {what} {a:e} against the reference's {b:e}: difference {:.1e} of {scale:e}, \
         allowed {tol:.1e}",
        (a - b).abs() / scale
    );
}

/// Events per steady period as the reference counts them (a grazing or a
/// rod jump, which it does not count, would not match).
fn counts(e: &EventCounts) -> EventCounts {
    EventCounts {
        grazing: 0,
        jump: 0,
        ..*e
    }
}

/// The steady orbit over tied springs of 1 kN/m to 1 MN/m, a tied spring
/// with preload and damping, free ends of 100 kN/m at gaps 0 and 5 um, all
/// slip-slip at `n = 3`, `sqrt(kappa) = 2` with the reaction (and one with
/// it off); and three that stick once or twice a period at
/// `sqrt(kappa) = 0.5` (one a free end that the slider leaves and meets
/// again every period): the orbit's period and events per period are the
/// reference's, the mean spring force, its largest and least values
/// (relative to the largest |force|), the contact and stick fractions
/// agree within the reference's error estimates (at most `2.7e-9`).
#[test]
fn a_driven_rod_against_a_spring_reads_what_an_independent_integrator_reads() {
    let mut worst: f64 = 0.0;
    let mut sticking = 0;
    for row in rows()
        .iter()
        .filter(|r| r.reading == "orbit" && r.spring != "none")
    {
        let at = &row.case;
        assert!(row.rel_err_est <= 1e-8, "{at}: the reference's own error");
        let report = stickslip::run(&scene(row), &RunOptions::default())
            .and_then(Outcome::into_report)
            .unwrap_or_else(|e| panic!("{at}: {e}"));
        let s = report.spring.expect("a spring reading");
        assert_eq!(Some(s.orbit_periods), row.orbit_period, "{at}: orbit");
        assert_eq!(row.orbit_period, Some(1), "{at}: a period-1 orbit");
        assert_eq!(
            counts(&report.steady.stats.events),
            row.events,
            "{at}: events per period"
        );
        let p = &s.profile;
        let d = (p.force_mean - row.mean_force).abs() / row.mean_force.abs();
        worst = worst.max(d);
        assert_within(
            at,
            "mean force",
            (p.force_mean, row.mean_force),
            row.mean_force.abs(),
            row.rel_err_est,
        );
        let scale = row.max_force.abs().max(row.min_force.abs());
        for (what, a, b) in [
            ("largest force", p.force_max, row.max_force),
            ("least force", p.force_min, row.min_force),
        ] {
            assert_within(at, what, (a, b), scale, row.extrema_err_est);
        }
        for (what, a, b) in [
            ("contact fraction", p.contact_fraction, row.contact_fraction),
            (
                "stick fraction",
                report.indicators.stiction_fraction,
                row.stick_fraction,
            ),
        ] {
            assert_within(at, what, (a, b), 1.0, row.fraction_err_est);
        }
        if row.stick_fraction > 0.0 {
            sticking += 1;
        }
    }
    assert!(sticking >= 2, "{sticking} cases with stick phases");
    eprintln!("largest relative difference of the mean spring force: {worst:.1e}");
}

/// Without a spring the driven slider travels on: its steady velocity is
/// the reference's mean slider velocity over its orbit (slip-slip with
/// four reversals a period at `sqrt(kappa) = 2`; three stick phases a
/// period at `sqrt(kappa) = 0.5`), within the reference's estimate, and so
/// are the stick fraction and the events per period.
#[test]
fn without_a_spring_the_driven_slider_travels_at_the_reference_velocity() {
    let rows = rows();
    let free: Vec<&Row> = rows.iter().filter(|r| r.spring == "none").collect();
    assert_eq!(free.len(), 2, "the free sliders");
    for row in free {
        let at = &row.case;
        let report = stickslip::run(&scene(row), &RunOptions::default())
            .and_then(Outcome::into_report)
            .unwrap_or_else(|e| panic!("{at}: {e}"));
        let v = report.indicators.v_inf;
        assert_within(
            at,
            "v_inf",
            (v, row.mean_velocity),
            row.mean_velocity.abs(),
            row.rel_err_est,
        );
        assert_within(
            at,
            "stick fraction",
            (report.indicators.stiction_fraction, row.stick_fraction),
            1.0,
            row.fraction_err_est,
        );
        assert_eq!(
            counts(&report.steady.stats.events),
            row.events,
            "{at}: events per period"
        );
    }
}

/// Segments and events as the engine hands them over.
#[derive(Default)]
struct Record {
    segments: Vec<Segment>,
    events: Vec<Event>,
}

impl Observer for Record {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        self.segments.push(*segment);
    }

    fn event(&mut self, event: &Event) {
        self.events.push(*event);
    }
}

/// A free end of 1 MN/m at gaps 0 and 5 um: the slider leaves it and
/// strikes it again irregularly. Neither the reference (no orbit of up to
/// 4 periods within 4000 periods from rest) nor the engine (none of up to
/// 64 within as many) finds an orbit; over the first 10 periods from rest,
/// before the motion's sensitivity (the reference's runs part by a factor
/// of about 1.4 a period) has grown, the engine's spring reads the
/// reference's, and has its events.
#[test]
fn a_stiff_free_end_locks_into_no_orbit_and_the_first_periods_agree() {
    let rows = rows();
    let chaotic: Vec<&Row> = rows.iter().filter(|r| r.reading == "from_rest").collect();
    assert_eq!(chaotic.len(), 2, "the rows without an orbit");
    for row in chaotic {
        let at = &row.case;
        let mut scene = scene(row);
        scene.run.max_periods = row.periods_to_steady;
        let outcome =
            stickslip::run(&scene, &RunOptions::default()).unwrap_or_else(|e| panic!("{at}: {e}"));
        let Outcome::NotConverged(unsettled) = &outcome else {
            panic!(
                "{at}: {} within {} periods",
                outcome.regime(),
                row.periods_to_steady
            );
        };
        let reading = unsettled.spring.expect("a reading");
        assert_eq!(reading.orbit_periods, 0, "{at}: no orbit locked");

        // The first periods from rest, through the engine.
        let motor = Motor::new(scene.motor).expect("the motor");
        let signal = Signal::build(&scene.signal, &motor).expect("the signal");
        let Signal::Fourier(series) = &signal else {
            panic!("{at}: a Fourier signal");
        };
        let design = scene.actuator.expect("[actuator]");
        let RodModel::Driven(spec) = &scene.rod else {
            panic!("{at}: a driven rod");
        };
        let rod = DrivenRod::new(spec, &design, Voltage::designed(series, &design), &motor)
            .expect("the rod");
        let spring = scene.spring.expect("a spring");
        let options = EventOptions::default();
        let mut engine = DrivenEngine::new(
            &signal,
            &rod,
            &motor,
            options.velocity_tolerance,
            options.max_events_per_period,
        )
        .with_spring(spring, &motor)
        .expect("the spring");
        let mut record = Record::default();
        let mut start = PeriodStart {
            velocity: 0.0,
            mode: None,
        };
        for p in 1..=row.reading_periods {
            let end = engine
                .run_period(p, start, &mut record)
                .unwrap_or_else(|e| panic!("{at}: period {p}: {e}"));
            start = PeriodStart {
                velocity: end.velocity,
                mode: Some(end.mode),
            };
        }
        assert!(
            matches!(spring.end, SpringEnd::Free { .. }),
            "{at}: a free end"
        );
        // Rest, as the engine starts from it: a free end at gap 0 touches.
        let rest = DrivenState {
            rod_x: 0.0,
            rod_v: 0.0,
            slider_v: 0.0,
            mode: Mode::Stick,
            slider: Some(SliderState {
                x: 0.0,
                contact: spring.in_contact(0.0),
            }),
        };
        let p = engine
            .spring_profile(
                &rest,
                (&record.segments, &record.events),
                row.reading_periods,
            )
            .expect("a spring profile");
        let mut events = EventCounts::default();
        for e in &record.events {
            events.add(&e.kind);
        }
        eprintln!(
            "{at}: first {} periods: mean force {:.1e}, largest {:.1e} (relative), \
             contact fraction {:.1e} (absolute) from the reference's",
            row.reading_periods,
            (p.force_mean / row.mean_force - 1.0).abs(),
            (p.force_max / row.max_force - 1.0).abs(),
            (p.contact_fraction - row.contact_fraction).abs()
        );
        assert_eq!(counts(&events), row.events, "{at}: events");
        assert_within(
            at,
            "mean force",
            (p.force_mean, row.mean_force),
            row.mean_force.abs(),
            row.rel_err_est,
        );
        let scale = row.max_force.abs();
        assert_within(
            at,
            "largest force",
            (p.force_max, row.max_force),
            scale,
            row.extrema_err_est,
        );
        assert_within(
            at,
            "least force",
            (p.force_min, row.min_force),
            scale,
            row.extrema_err_est,
        );
        assert_within(
            at,
            "contact fraction",
            (p.contact_fraction, row.contact_fraction),
            1.0,
            row.fraction_err_est,
        );
    }
}
