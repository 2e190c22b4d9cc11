//! Helpers shared by the integration tests, the one folder of test
//! helpers. `mod common;` brings in this file and its modules; the case
//! catalogues beside it (`grid.rs`: the section-7 reference grid,
//! `stability.rs`: the stress cases, `steady_state_certificate.rs`: the
//! certificate's cases) are included by path where used, by tests and by
//! the examples that report on the same cases.
#![allow(dead_code)]

pub mod ideal_load;
pub mod mock;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use stickslip::Indicator;
use stickslip::RunReport;
use stickslip::SignalSpec;
use stickslip::{MotorParams, Scene, motor::Motor, signal::Signal};
use stickslip::{engine::EventEngine, engine::EventOptions};

/// The name of an event in an event structure (`tests/sensitivity.rs`,
/// `tests/optimize_gradient.rs`). A grazing that sticks is the zero of
/// `v_rel` it is in the limit (decided within the engine's zero-velocity
/// tolerance): the same branch.
pub fn event_token(kind: &stickslip::engine::EventKind) -> String {
    use stickslip::engine::EventKind;
    match *kind {
        EventKind::StickToSlip { to } => format!("exit {to:?}"),
        EventKind::SlipToStick
        | EventKind::Grazing {
            then: stickslip::engine::Mode::Stick,
        } => "stick".to_owned(),
        EventKind::Reversal { to } => format!("reversal {to:?}"),
        EventKind::Grazing { then } => format!("grazing {then:?}"),
        EventKind::Jump { then, .. } => format!("jump {then:?}"),
        EventKind::ContactStart | EventKind::ContactEnd => kind.name().to_owned(),
    }
}

/// The paper's motor (docs/model.md section 6).
pub fn paper_motor() -> Motor {
    Motor::default()
}

/// A scene with the paper's motor, the given signal and every indicator
/// that needs no actuator.
pub fn scene_with(signal: SignalSpec) -> Scene {
    let mut scene = Scene {
        signal,
        actuator: None,
        ..Scene::default()
    };
    scene
        .outputs
        .indicators
        .retain(|i| *i != Indicator::VelocityPerPower);
    scene
}

/// The ideal signal (11) with the paper's stroke.
pub fn ideal(kappa: f64, duty: f64) -> SignalSpec {
    SignalSpec::ideal(25e-6, kappa, duty)
}

/// A Fourier signal of the paper's kind.
pub fn fourier(stroke: f64, kappa: f64, n: usize, sigma: bool) -> SignalSpec {
    SignalSpec::fourier(stroke, kappa, n, sigma)
}

/// Runs a scene with the event engine.
pub fn run(scene: &Scene) -> RunReport {
    stickslip::run(scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .expect("scene runs")
}

/// The end of period `periods` of a motion from rest, each period started
/// where the last ended: `period(p, start)` runs period `p` of an engine.
pub fn from_rest(
    periods: u64,
    period: &mut dyn FnMut(u64, stickslip::engine::PeriodStart) -> stickslip::engine::PeriodEnd,
) -> stickslip::engine::PeriodEnd {
    let mut start = stickslip::engine::PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    let mut end = None;
    for p in 1..=periods {
        let e = period(p, start);
        start = stickslip::engine::PeriodStart {
            velocity: e.velocity,
            mode: Some(e.mode),
        };
        end = Some(e);
    }
    end.expect("at least one period")
}

/// A CSV table of `tests/data` whose `#` lines (its provenance) are
/// skipped: its records, and where each named column stands.
pub struct DataTable {
    pub path: PathBuf,
    headers: csv::StringRecord,
    pub records: Vec<csv::StringRecord>,
}

impl DataTable {
    /// The position of the column `name`; a missing one fails the test.
    pub fn column(&self, name: &str) -> usize {
        self.headers
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{}: no column {name}", self.path.display()))
    }
}

/// The table `tests/data/NAME`; a missing or unreadable file fails the
/// test.
pub fn data_table(name: &str) -> DataTable {
    let path = data_path(name);
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let headers = reader.headers().expect("a header").clone();
    let records = reader
        .records()
        .map(|r| r.unwrap_or_else(|e| panic!("{}: {e}", path.display())))
        .collect();
    DataTable {
        path,
        headers,
        records,
    }
}

/// The least-squares slope of `log e` against `log h`: the observed order
/// of convergence of errors `e` at steps `h`.
pub fn log_slope(h: &[f64], e: &[f64]) -> f64 {
    let (lx, ly): (Vec<f64>, Vec<f64>) = h.iter().zip(e).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    lx.iter()
        .zip(&ly)
        .map(|(x, y)| (x - mx) * (y - my))
        .sum::<f64>()
        / lx.iter().map(|x| (x - mx).powi(2)).sum::<f64>()
}

/// Runs a scene's motor and outputs with an arbitrary signal.
pub fn run_signal(scene: &Scene, signal: &Signal) -> RunReport {
    let motor = Motor::new(scene.motor).expect("valid motor");
    let engine = EventEngine::new(signal, &motor, EventOptions::default());
    stickslip::Outcome::of_engine(engine, scene, &motor)
        .and_then(stickslip::Outcome::into_report)
        .expect("signal runs")
}

/// Motor parameters with other friction coefficients.
pub fn motor_with(mu_static: f64, mu_dynamic: f64) -> MotorParams {
    MotorParams {
        mu_static,
        mu_dynamic,
        ..MotorParams::default()
    }
}

/// `|a - b| <= rel * |b|`.
pub fn assert_rel(a: f64, b: f64, rel: f64, what: &str) {
    assert!(
        (a - b).abs() <= rel * b.abs(),
        "{what}: {a:e} vs {b:e} (relative difference {:e} > {rel:e})",
        ((a - b) / b).abs()
    );
}

/// Path of a file in `tests/data/`.
pub fn data_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name)
}

/// The text of a file in `tests/data/`; a missing file fails the test
/// with its path (no test passes without its data).
pub fn data_text(name: &str) -> String {
    let path = data_path(name);
    std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("test data {} cannot be read: {e}", path.display()))
}

/// The independent section-7 reference grid (`tests/data/section7_grid.csv`,
/// provenance in its header).
pub fn reference_grid_text() -> String {
    data_text("section7_grid.csv")
}

/// A fresh, empty scratch directory `<target tmp>/<group>/<name>`.
pub fn scratch(group: &str, name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(group)
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs the binary in the repository's top folder.
pub fn stickslip(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// Runs the command line `stickslip ARGS...` in this process (the code
/// path of the binary, `stickslip::cli::main_with`): the exit status, the
/// output and the error stream.
pub fn in_process(args: &[&str]) -> (u8, String, String) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let mut streams = stickslip::cli::Streams {
        out: &mut out,
        err: &mut err,
    };
    let mut all = vec!["stickslip"];
    all.extend_from_slice(args);
    let code = stickslip::cli::main_with(all, &mut streams);
    (
        code,
        String::from_utf8(out).unwrap(),
        String::from_utf8(err).unwrap(),
    )
}

/// The error stream of a run that must succeed.
pub fn ok(o: Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{err}");
    err
}

/// The error stream of a run that must fail.
pub fn failure(o: Output) -> String {
    assert!(!o.status.success(), "expected a failure");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A path as a command-line argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The texts of an SVG's `<text>` elements, in document order, each its
/// runs joined (the no-break spaces at a rich text's run edges read as
/// spaces).
pub fn svg_texts(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).expect("the SVG parses");
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            n.descendants()
                .filter(|d| d.is_text())
                .filter_map(|d| d.text())
                .collect::<String>()
                .replace('\u{a0}', " ")
        })
        .collect()
}
