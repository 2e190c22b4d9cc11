//! The slider against a spring (docs/model.md section 17) against an
//! independent reference: `tests/data/spring_reference.py`, scipy's
//! `solve_ivp` (DOP853, rtol 1e-12) with event location, which shares no
//! code with the engine, and its output `tests/data/spring_reference.csv`
//! (provenance in its header and in `tests/data/spring_reference.md`).

mod common;

use stickslip::{Outcome, RunOptions, Scene};

/// One row of the reference.
struct Row {
    scene: String,
    tied: bool,
    k: f64,
    gap: f64,
    mean_force: f64,
    max_force: f64,
    min_force: f64,
    contact_fraction: f64,
    orbit_period: u64,
    rel_err_est: f64,
}

fn rows() -> Vec<Row> {
    let table = common::data_table("spring_reference.csv");
    let col = |name: &str| table.column(name);
    let [scene, spring, k, gap, mean, max, min, contact, orbit, err] = [
        "scene",
        "spring",
        "k",
        "gap",
        "mean_force",
        "max_force",
        "min_force",
        "contact_fraction",
        "orbit_period",
        "rel_err_est",
    ]
    .map(col);
    let rows: Vec<Row> = table
        .records
        .iter()
        .map(|r| {
            let num = |i: usize| r[i].parse::<f64>().expect("a number");
            Row {
                scene: r[scene].to_owned(),
                tied: &r[spring] == "tied",
                k: num(k),
                gap: num(gap),
                mean_force: num(mean),
                max_force: num(max),
                min_force: num(min),
                contact_fraction: num(contact),
                orbit_period: r[orbit].parse().expect("an orbit period"),
                rel_err_est: num(err),
            }
        })
        .collect();
    assert!(
        rows.len() >= 20,
        "{}: {} rows",
        table.path.display(),
        rows.len()
    );
    rows
}

/// The reference's scene (its `[motor]` and signal) with the spring of
/// `row`, asking only for the friction energy.
fn scene(row: &Row) -> Scene {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/spring_reference_scene.toml"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut table: toml::Table = text.parse().expect("the reference's scene parses");
    let signal = table["signal"].as_table_mut().expect("[signal]");
    match row.scene.as_str() {
        "default" => {}
        "n3_sqrtkappa2" => {
            signal.insert("kappa".into(), toml::Value::Float(4.0));
            signal.insert("harmonics".into(), toml::Value::Integer(3));
        }
        other => panic!("unknown reference scene {other}"),
    }
    let mut spring = toml::Table::new();
    spring.insert("stiffness".into(), toml::Value::Float(row.k));
    spring.insert("tied".into(), toml::Value::Boolean(row.tied));
    if !row.tied {
        spring.insert("gap".into(), toml::Value::Float(row.gap));
    }
    table.insert("spring".into(), toml::Value::Table(spring));
    let outputs = table["outputs"].as_table_mut().expect("[outputs]");
    outputs.insert(
        "indicators".into(),
        toml::Value::Array(vec![toml::Value::String("friction_energy".into())]),
    );
    Scene::from_toml_str(&toml::to_string(&table).expect("TOML"), "reference")
        .expect("a valid scene")
}

/// Tied springs of 1 kN/m to 1 MN/m on the paper's default signal and on
/// `n = 3`, `sqrt(kappa) = 2`, and free ends of 10 kN/m to 1 MN/m at gaps
/// 0 and 10 um (at 1 MN/m the slider leaves the free end every period):
/// the mean spring force agrees with the reference to 1e-7 relative (its
/// own error estimate is below 1e-13), its largest and least values and
/// the contact fraction to 1e-7, and both find an orbit of one period.
#[test]
fn the_spring_reads_what_an_independent_integrator_reads() {
    let mut worst: f64 = 0.0;
    for row in rows() {
        let at = format!(
            "{} {} k = {} gap = {}",
            row.scene,
            if row.tied { "tied" } else { "free" },
            row.k,
            row.gap
        );
        assert!(row.rel_err_est < 1e-10, "{at}: the reference's own error");
        let report = stickslip::run(&scene(&row), &RunOptions::default())
            .and_then(Outcome::into_report)
            .unwrap_or_else(|e| panic!("{at}: {e}"));
        let s = report.spring.expect("a spring reading");
        assert_eq!(s.orbit_periods, row.orbit_period, "{at}");
        // Relative to the largest force (the least is 0 where the slider
        // leaves a free end).
        let rel = |a: f64, b: f64| (a - b).abs() / row.max_force.abs();
        let d = rel(s.profile.force_mean, row.mean_force);
        worst = worst.max(d);
        assert!(
            d <= 1e-7,
            "{at}: mean force {} against {}",
            s.profile.force_mean,
            row.mean_force
        );
        assert!(rel(s.profile.force_max, row.max_force) <= 1e-7, "{at}: max");
        assert!(rel(s.profile.force_min, row.min_force) <= 1e-7, "{at}: min");
        assert!(
            (s.profile.contact_fraction - row.contact_fraction).abs() <= 1e-7,
            "{at}: contact fraction {} against {}",
            s.profile.contact_fraction,
            row.contact_fraction
        );
    }
    eprintln!("largest relative difference of the mean spring force: {worst:.1e}");
}
