//! The error estimate of a spring's reading (docs/model.md section 17,
//! "The reading's error") against an independent reference: scipy's
//! `solve_ivp` (DOP853, rtol 1e-12, event location; `tests/data/
//! spring_reference.py`, sharing no code with the engine) in
//! `tests/data/spring_reference.csv`, read as `tests/spring_reference.rs`
//! reads it.

mod common;

use stickslip::simulation::{SpringReading, SpringReadingError};
use stickslip::{Outcome, RunOptions, Scene};

/// One tied spring's row of the reference on the paper's default signal.
struct Row {
    k: f64,
    mean_force: f64,
    max_force: f64,
    min_force: f64,
    mean_position: f64,
    rel_err_est: f64,
}

/// The reference's rows of the scene `scene` with a tied spring.
fn tied_rows(scene: &str) -> Vec<Row> {
    let table = common::data_table("spring_reference.csv");
    let col = |name: &str| table.column(name);
    let [s, spring, k, mean, max, min, position, err] = [
        "scene",
        "spring",
        "k",
        "mean_force",
        "max_force",
        "min_force",
        "mean_position",
        "rel_err_est",
    ]
    .map(col);
    table
        .records
        .iter()
        .filter(|r| &r[s] == scene && &r[spring] == "tied")
        .map(|r| {
            let num = |i: usize| r[i].parse::<f64>().expect("a number");
            Row {
                k: num(k),
                mean_force: num(mean),
                max_force: num(max),
                min_force: num(min),
                mean_position: num(position),
                rel_err_est: num(err),
            }
        })
        .collect()
}

/// The reference's own error, relative: the largest of its estimates
/// `|F(rtol) - F(100 rtol)| / F` over all its rows (`5.5e-14`); a single
/// row's estimate can be 0 where the two tolerances happen to agree.
fn reference_error() -> f64 {
    let table = common::data_table("spring_reference.csv");
    let col = table.column("rel_err_est");
    table
        .records
        .iter()
        .map(|r| r[col].parse::<f64>().expect("a number"))
        .fold(0.0, f64::max)
}

/// The reference's scene (its `[motor]` and the paper's default signal)
/// with a tied spring of stiffness `k`.
fn reference_scene(k: f64) -> Scene {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/spring_reference_scene.toml"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut table: toml::Table = text.parse().expect("the reference's scene parses");
    let mut spring = toml::Table::new();
    spring.insert("stiffness".into(), toml::Value::Float(k));
    spring.insert("tied".into(), toml::Value::Boolean(true));
    table.insert("spring".into(), toml::Value::Table(spring));
    let outputs = table["outputs"].as_table_mut().expect("[outputs]");
    outputs.insert(
        "indicators".into(),
        toml::Value::Array(vec![toml::Value::String("friction_energy".into())]),
    );
    Scene::from_toml_str(&toml::to_string(&table).expect("TOML"), "reference")
        .expect("a valid scene")
}

fn reading(scene: &Scene, at: &str) -> (SpringReading, SpringReadingError) {
    let report = stickslip::run(scene, &RunOptions::default())
        .and_then(Outcome::into_report)
        .unwrap_or_else(|e| panic!("{at}: {e}"));
    let r = report.spring.unwrap_or_else(|| panic!("{at}: a reading"));
    let e = r.error.unwrap_or_else(|| panic!("{at}: an error estimate"));
    (r, e)
}

/// Tied springs of 1 kN/m, 100 kN/m and 1 MN/m on the paper's default
/// signal: the reading differs from the independent reference by less
/// than its estimate plus the reference's own error, for the mean force,
/// the largest and least force and the mean position; and the estimate
/// says something: below `1e-10` of the largest force.
#[test]
fn the_estimate_covers_the_distance_to_an_independent_reference() {
    let reference = reference_error();
    assert!(reference < 1e-13, "the reference's own error {reference:e}");
    let rows = tied_rows("default");
    for k in [1e3, 1e5, 1e6] {
        let row = rows
            .iter()
            .find(|r| r.k == k)
            .unwrap_or_else(|| panic!("no reference row at k = {k}"));
        let at = format!("tied k = {k}");
        let (r, e) = reading(&reference_scene(k), &at);
        let p = &r.profile;
        let scale = row.max_force.abs();
        for (name, value, expected, part) in [
            ("mean force", p.force_mean, row.mean_force, e.force_mean),
            ("largest force", p.force_max, row.max_force, e.force_max),
            ("least force", p.force_min, row.min_force, e.force_min),
            (
                "mean position",
                p.position_mean,
                row.mean_position,
                e.position_mean,
            ),
        ] {
            let estimate = part.total();
            let difference = (value - expected).abs();
            eprintln!(
                "{at} {name}: difference {:.1e}, estimate {:.1e} (boundary {:.1e}, quadrature \
                 {:.1e}, rounding {:.1e}, events {:.1e}), relative {:.1e}",
                difference,
                estimate,
                part.boundary_state,
                part.quadrature,
                part.rounding,
                part.event_times,
                estimate / expected.abs()
            );
            assert!(
                difference <= estimate + reference.max(row.rel_err_est) * expected.abs(),
                "{at} {name}: {value} against {expected}, estimate {estimate:e}"
            );
            let relative = if name == "mean position" {
                estimate / expected.abs()
            } else {
                estimate / scale
            };
            assert!(relative < 1e-10, "{at} {name}: estimate {estimate:e}");
        }
    }
}

/// A free end at 1 MN/m, which the slider leaves for 23 % of each period
/// (two contact events per period): the contact fraction differs from the
/// reference's by less than its estimate plus the reference's own error,
/// which is as large as its two gaps disagree (0 and 10 um: the orbit
/// does not depend on the gap, the reference's event location does, by
/// `1.4e-11`), and its estimate holds the contact events' part.
#[test]
fn the_contact_fraction_estimate_covers_the_reference_of_a_free_end_it_leaves() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/spring_reference.csv"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    // default,free,1e6,b,gap,...: the contact fraction is the 11th column.
    let fractions: Vec<f64> = text
        .lines()
        .filter(|l| l.starts_with("default,free,1000000.0,"))
        .map(|l| {
            l.split(',')
                .nth(10)
                .expect("contact_fraction")
                .parse()
                .unwrap()
        })
        .collect();
    assert_eq!(fractions.len(), 2, "gaps 0 and 10 um");
    let reference_error = (fractions[0] - fractions[1]).abs();
    assert!(reference_error < 1e-10, "{fractions:?}");
    let mut scene = reference_scene(1e6);
    let spring = scene.spring.as_mut().expect("a spring");
    spring.end = stickslip::spring::SpringEnd::Free { gap: 0.0 };
    let (r, e) = reading(&scene, "free k = 1e6");
    let c = e.contact_fraction;
    let difference = (r.profile.contact_fraction - fractions[0]).abs();
    eprintln!(
        "contact fraction: difference {difference:.1e}, estimate {:.1e} (boundary {:.1e}, \
         events {:.1e}), reference's own {reference_error:.1e}",
        c.total(),
        c.boundary_state,
        c.event_times
    );
    assert!(difference <= c.total() + reference_error);
    assert!(c.event_times > 0.0 && c.total() < 1e-9, "{c:?}");
}

/// What `run --json` and the text summary print as a figure's error is
/// the sum of the estimate's four parts, added up here: the JSON number
/// to the bit, the text as `value ± error` with the value rounded to the
/// digits the error supports (as an indicator is printed).
#[test]
fn the_printed_estimate_is_the_sum_of_its_parts() {
    let scene = reference_scene(1e5);
    let outcome = stickslip::run(&scene, &RunOptions::default()).expect("a run");
    let json = stickslip::report::to_json(&outcome, &scene);
    let text = stickslip::report::to_text(&outcome);
    let report = outcome.report().expect("a steady state");
    let r = report.spring.expect("a reading");
    let e = r.error.expect("an estimate");
    let p = &r.profile;
    for (key, value, parts) in [
        ("spring_force_mean", p.force_mean, e.force_mean),
        ("spring_force_max", p.force_max, e.force_max),
        ("spring_force_min", p.force_min, e.force_min),
        ("spring_position_mean", p.position_mean, e.position_mean),
        ("contact_fraction", p.contact_fraction, e.contact_fraction),
    ] {
        let sum = parts.boundary_state + parts.quadrature + parts.rounding + parts.event_times;
        assert!(sum > 0.0, "{key}: {parts:?}");
        let printed = json["error_estimate"][key].as_f64().expect("a number");
        assert_eq!(
            printed.to_bits(),
            sum.to_bits(),
            "{key}: {printed} against {sum}"
        );
        let line = text
            .lines()
            .find(|l| l.split_whitespace().next() == Some(key))
            .unwrap_or_else(|| panic!("no line {key}"));
        let shown = stickslip::report::format_with_error(value, Some(sum));
        assert!(line.contains(&shown), "{key}: {line} against {shown}");
        assert!(shown.contains(&format!("± {sum:.1e}")), "{shown}");
    }
    // A tied spring is in contact throughout: its contact fraction moves
    // by rounding alone.
    assert_eq!(e.contact_fraction.boundary_state, 0.0);
    assert!(e.force_mean.boundary_state > 0.0);
}

/// The rod driven through the actuator (`examples/scenes/driven_spring.toml`,
/// the boundary state `(x_R, v_R, x_S, v_S)`): every figure has a finite
/// estimate, below `1e-9` of the force's scale (the position's: of its
/// mean).
#[test]
fn a_driven_rod_against_a_spring_gets_a_finite_estimate() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/driven_spring.toml"
    );
    let scene = Scene::from_path(std::path::Path::new(path)).expect("the example scene");
    let (r, e) = reading(&scene, "driven_spring.toml");
    let p = &r.profile;
    for (name, parts, scale) in [
        ("mean force", e.force_mean, p.force_max),
        ("largest force", e.force_max, p.force_max),
        ("least force", e.force_min, p.force_max),
        ("mean position", e.position_mean, p.position_mean),
        ("contact fraction", e.contact_fraction, 1.0),
    ] {
        let total = parts.total();
        eprintln!("{name}: {total:.1e} ({parts:?})");
        assert!(total.is_finite() && total > 0.0, "{name}: {parts:?}");
        assert!(total < 1e-9 * scale.abs(), "{name}: {total:e} of {scale}");
    }
}

/// A free end at `k = 10^(1 + 6 * 39 / 49)` N/m (a stiffness of the
/// bench) locks, after 8573 periods from rest, into an orbit of 4 periods
/// that repeats exactly (no Newton): its reading, with an estimate from
/// the 4-period map's Jacobian, is what the 64 periods after a start-up
/// stopped at 8000 periods read (each period numbered, the same motion 16
/// times over), to within that estimate; and that reading, of no orbit,
/// has no estimate (none is invented: `null` in JSON, `± unknown` in the
/// text).
#[test]
fn a_subharmonic_orbit_reads_what_the_periods_after_an_unlocked_start_up_read() {
    let mut scene = reference_scene(1e6);
    let spring = scene.spring.as_mut().expect("a spring");
    spring.stiffness = 10f64.powf(1.0 + 6.0 * 39.0 / 49.0);
    spring.end = stickslip::spring::SpringEnd::Free { gap: 0.0 };
    scene.run.max_periods = 20_000;
    let (orbit, e) = reading(&scene, "4-period orbit");
    assert_eq!(orbit.orbit_periods, 4);
    scene.run.max_periods = 8_000;
    let outcome = stickslip::run(&scene, &RunOptions::default()).expect("a run");
    let unlocked = outcome
        .unsettled()
        .and_then(|u| u.spring)
        .expect("a reading without an orbit");
    assert_eq!((unlocked.orbit_periods, unlocked.periods), (0, 64));
    assert!(unlocked.error.is_none());
    let (a, b) = (&orbit.profile, &unlocked.profile);
    for (name, x, y, parts) in [
        ("mean force", a.force_mean, b.force_mean, e.force_mean),
        ("largest force", a.force_max, b.force_max, e.force_max),
        ("least force", a.force_min, b.force_min, e.force_min),
        (
            "mean position",
            a.position_mean,
            b.position_mean,
            e.position_mean,
        ),
        (
            "contact fraction",
            a.contact_fraction,
            b.contact_fraction,
            e.contact_fraction,
        ),
    ] {
        eprintln!("{name}: {x} against {y}, estimate {:.1e}", parts.total());
        assert!((x - y).abs() <= parts.total(), "{name}: {x} against {y}");
    }
    let json = stickslip::report::to_json(&outcome, &scene);
    assert!(json["error_estimate"]["spring_force_mean"].is_null());
    let text = stickslip::report::to_text(&outcome);
    let line = text
        .lines()
        .find(|l| l.split_whitespace().next() == Some("spring_force_mean"))
        .expect("a line");
    assert!(line.contains("± unknown"), "{line}");
}
