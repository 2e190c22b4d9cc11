//! `stickslip check` with a spring against the slider (docs/model.md
//! section 17; the rule in the module docs of `stickslip::check`, "A
//! spring against the slider"): both engines carry the spring, and the
//! fixed-step reference's spring figures converge to the exact engine's
//! at first order, the reference's order (model section 12).

use stickslip::check::{CheckReport, IndicatorRow, check};
use stickslip::spring::{Spring, SpringEnd};
use stickslip::{Indicator, Scene};

/// The paper's default scene with `spring`, asking for the indicators
/// that apply with a spring.
fn with_spring(spring: Spring) -> Scene {
    let mut scene = Scene {
        spring: Some(spring),
        ..Scene::default()
    };
    scene.outputs.indicators = vec![Indicator::FrictionEnergy, Indicator::StictionFraction];
    scene
}

fn tied(stiffness: f64) -> Spring {
    Spring {
        stiffness,
        damping: 0.0,
        end: SpringEnd::Tied { preload: 0.0 },
    }
}

fn free(stiffness: f64, gap: f64) -> Spring {
    Spring {
        stiffness,
        damping: 0.0,
        end: SpringEnd::Free { gap },
    }
}

fn row<'a>(report: &'a CheckReport, name: &str) -> &'a IndicatorRow {
    report
        .rows
        .iter()
        .find(|r| r.name == name)
        .unwrap_or_else(|| panic!("no {name} row: {}", report.to_text()))
}

/// Four levels of resolution, each eight neighbouring step counts: where
/// the events fall on the grid moves erratically with the step count, so
/// the error of a single resolution scatters about `C h` (as in
/// `tests/fixed_step.rs`); the mean over neighbours follows `h`.
const BASES: [u32; 4] = [50, 100, 200, 400];
const NEIGHBOURS: u32 = 8;

fn steps() -> Vec<u32> {
    BASES
        .iter()
        .flat_map(|b| (0..NEIGHBOURS).map(move |j| b + j))
        .collect()
}

/// The least-squares slope of `-log e` against `log s`.
fn slope(points: &[(f64, f64)]) -> f64 {
    let xy: Vec<(f64, f64)> = points.iter().map(|(s, e)| (s.ln(), -e.ln())).collect();
    let n = xy.len() as f64;
    let mx = xy.iter().map(|p| p.0).sum::<f64>() / n;
    let my = xy.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

/// Asserts that the reference's `spring_force_mean` converges to the
/// exact engine's at first order: the order of the mean error of the
/// neighbours over the four levels in `[0.7, 1.5]` (the reference is first
/// order, model section 12), the check's own least-squares order over
/// every single resolution in `[0.7, 1.6]` (it inherits their scatter),
/// and the error falls by more than 4 over the three doublings. The event column is `run`'s reading of the orbit.
fn assert_first_order(scene: &Scene, what: &str) -> CheckReport {
    let report = check(scene, &steps()).expect("check runs");
    let reading = stickslip::run(scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .expect("a steady orbit")
        .spring
        .expect("a spring reading");
    let mean = row(&report, "spring_force_mean");
    assert_eq!(
        mean.event, reading.profile.force_mean,
        "{what}: run's value"
    );
    assert_eq!(mean.unit, "N");
    let fitted = mean.fitted_order.expect("an order over the resolutions");
    let levels: Vec<(f64, f64)> = BASES
        .iter()
        .enumerate()
        .map(|(l, b)| {
            let n = NEIGHBOURS as usize;
            let errors = &mean.reference[l * n..(l + 1) * n];
            let e = errors.iter().map(|v| v.difference.abs()).sum::<f64>() / n as f64;
            (f64::from(*b), e)
        })
        .collect();
    let level_order = slope(&levels);
    let table = format!("fitted {fitted:.3}, over the levels {level_order:.3}: {levels:?}");
    eprintln!("{what}: {table}");
    assert!((0.7..=1.6).contains(&fitted), "{what}: {table}");
    assert!((0.7..=1.5).contains(&level_order), "{what}: {table}");
    assert!(levels[3].1 < levels[0].1 / 4.0, "{what}: {table}");
    // What the reference read over: the event engine's start-up, then
    // its orbit's periods from where its motion from rest reads the orbit.
    let spring = report.spring.as_ref().expect("the spring's runs");
    let w = spring.window;
    assert!(w.settled, "{what}: {w:?}");
    assert!(w.settle >= w.startup, "{what}: {w:?}");
    assert_eq!(w.read, reading.orbit_periods, "{what}");
    assert_eq!(spring.reference.len(), steps().len());
    for run in &spring.reference {
        assert_eq!(run.periods, w.startup + w.read, "{what}");
    }
    assert!(report.reference.is_empty());
    report
}

/// A tied spring of 10 kN/m on the paper's default scene: slip-slip, the
/// slider in contact throughout.
#[test]
fn the_reference_reads_a_tied_spring_at_first_order() {
    let report = assert_first_order(&with_spring(tied(1e4)), "tied 10 kN/m");
    let contact = row(&report, "contact_fraction");
    assert_eq!(contact.event, 1.0);
    assert!(contact.reference.iter().all(|v| v.value == 1.0));
}

/// A free end of 1 MN/m at gap 0: the slider leaves the spring and meets
/// it again in every period (contact about 77 % of the time).
#[test]
fn the_reference_reads_a_free_end_it_leaves_every_period_at_first_order() {
    let report = assert_first_order(&with_spring(free(1e6, 0.0)), "free end 1 MN/m");
    let contact = row(&report, "contact_fraction");
    assert!(
        contact.event > 0.5 && contact.event < 1.0,
        "{}",
        contact.event
    );
    // Out of contact the free end pushes with 0 N.
    assert_eq!(row(&report, "spring_force_min").event, 0.0);
}

/// The rows of a spring scene: the indicators that apply with a spring,
/// then the five figures of the spring, each with a reference value per
/// resolution; the event column of an indicator is `run`'s.
#[test]
fn a_spring_check_has_the_indicators_and_the_spring_figures_as_rows() {
    let scene = with_spring(tied(1e5));
    let report = check(&scene, &[40, 80]).expect("check runs");
    let names: Vec<&str> = report.rows.iter().map(|r| r.name).collect();
    assert_eq!(
        names,
        [
            "friction_energy",
            "stiction_fraction",
            "stiction_fraction_steady",
            "spring_force_mean",
            "spring_force_max",
            "spring_force_min",
            "spring_position_mean",
            "contact_fraction",
        ]
    );
    let run = stickslip::run(&scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .expect("a steady orbit");
    assert_eq!(
        Some(row(&report, "friction_energy").event),
        run.value(Indicator::FrictionEnergy)
    );
    for r in &report.rows {
        assert_eq!(r.reference.len(), 2, "{}", r.name);
        for v in &r.reference {
            assert_eq!(v.difference, v.value - r.event, "{}", r.name);
        }
    }
    let text = report.to_text();
    assert!(
        text.contains("spring: start-up figures over periods 1.."),
        "{text}"
    );
    assert!(text.contains("fixed 80"), "{text}");
}

/// Without a spring nothing of the spring's appears: no spring runs, no
/// spring rows, no spring line, and the reference's runs carry the rows'
/// values (the existing check tests in `tests/fixed_step.rs`,
/// `tests/indicator_table.rs` and `tests/outcomes.rs` hold the rest).
#[test]
fn a_check_without_a_spring_has_no_spring_rows() {
    let scene = Scene::default();
    let report = check(&scene, &[20, 40]).expect("check runs");
    assert!(report.spring.is_none());
    assert_eq!(report.reference.len(), 2);
    for r in &report.rows {
        assert!(!r.name.starts_with("spring") && r.name != "contact_fraction");
    }
    let v = row(&report, "v_inf");
    for (run, value) in report.reference.iter().zip(&v.reference) {
        assert_eq!(Some(value.value), run.report.value(Indicator::VInf));
    }
    assert!(!report.to_text().contains("spring"));
}

/// `stickslip check` on a scene with `[spring]` prints the spring's rows
/// and what the reference read over.
#[test]
fn the_check_command_prints_the_spring_rows() {
    let dir = std::env::temp_dir().join(format!("stickslip-check-spring-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    let scene = dir.join("spring.toml");
    std::fs::write(
        &scene,
        "[outputs]\nindicators = [\"friction_energy\", \"stiction_fraction\"]\n\
         [spring]\nstiffness = 1e4\n",
    )
    .expect("the scene is written");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "check",
            scene.to_str().expect("a UTF-8 path"),
            "--steps",
            "50,100",
        ])
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("spring_force_mean (N)"), "{text}");
    assert!(text.contains("contact_fraction (1)"), "{text}");
    assert!(text.contains("reads its orbit's spring figures"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The rod driven through the actuator with the reaction on
/// (`examples/scenes/driven_spring.toml`: a tied spring of 100 kN/m, the
/// actuator 5 % stiffer than designed): both engines carry the rod's
/// state, and the reference continues from the exact engine's rod and
/// slider.
#[test]
fn the_reference_reads_a_driven_rods_spring_at_first_order() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/driven_spring.toml"
    );
    let text = std::fs::read_to_string(path).expect("the example scene");
    let scene = Scene::from_toml_str(&text, path).expect("a valid scene");
    assert!(matches!(
        scene.rod,
        stickslip::actuator::RodModel::Driven(_)
    ));
    assert_first_order(&scene, "driven rod, tied 100 kN/m");
}
