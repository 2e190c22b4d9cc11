//! Figures (`src/plot/`): the same inputs give the same bytes, every figure
//! is written with its CSV beside it, and the CSV is rectangular.

#[path = "common/grid.rs"]
mod grid;

use grid::grid;
use stickslip::motor::Motor;
use stickslip::plot::performance::{GridPoint, figures6_7};
use stickslip::plot::{Figure, PlotError, Preset, scaling, signals};

/// A figure made from the motor alone.
type MotorFigure = fn(&Motor) -> Result<Figure, PlotError>;

/// Every data row has as many cells as the header; returns the row count.
fn check_csv(figure: &Figure) -> usize {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(figure.csv.as_bytes());
    let columns = reader.headers().expect("a header").len();
    let mut rows = 0;
    for record in reader.records() {
        let record = record.unwrap_or_else(|e| panic!("{}: {e}", figure.name));
        assert_eq!(record.len(), columns, "{}", figure.name);
        rows += 1;
    }
    rows
}

#[test]
fn signal_figures_are_byte_identical_and_complete() {
    let motor = Motor::default();
    let makers: [MotorFigure; 5] = [
        signals::figure2,
        signals::figure3,
        signals::figure4,
        signals::figure5,
        scaling::figure9,
    ];
    for make in makers {
        let a = make(&motor).unwrap();
        let b = make(&motor).unwrap();
        assert_eq!(a, b, "{} differs between two runs", a.name);
        for preset in Preset::ALL {
            let svg = a.svg(&preset.style());
            assert_eq!(svg, b.svg(&preset.style()), "{} in {preset}", a.name);
            assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        }
        assert!(check_csv(&a) > 0, "{} has data", a.name);
    }
}

/// Figures 6 and 7 from a synthetic grid: both figures, one CSV row per
/// point, the same bytes twice.
#[test]
fn grid_figures_from_points() {
    let points = grid();
    let [six, seven] = figures6_7(&points).unwrap();
    assert_eq!(check_csv(&six), 6);
    assert_eq!(check_csv(&seven), 6);
    assert_eq!(figures6_7(&points).unwrap(), [six, seven]);
    let without_sigma: Vec<GridPoint> = points.iter().filter(|p| !p.sigma).copied().collect();
    assert!(
        figures6_7(&without_sigma).is_err(),
        "needs both sigma settings"
    );
}

#[test]
fn figures_are_written_beside_each_other() {
    let dir = std::env::temp_dir().join(format!("stickslip-plot-test-{}", std::process::id()));
    let figure = signals::figure3(&Motor::default()).unwrap();
    let [svg, csv] = figure.write_to(&dir).unwrap();
    assert_eq!(
        std::fs::read_to_string(&svg).unwrap(),
        figure.svg(&figure.preset.style())
    );
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), figure.csv);
    assert_eq!(stickslip::plot::data_path(&svg), csv);
    assert!(csv.to_str().unwrap().ends_with(".svg.csv"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Figure 8 draws the scene it is given. Two scenes that differ
/// only in the signal's harmonics give different figures and data, and the
/// CSV's period is the given scene's.
#[test]
fn figure8_uses_the_scene_it_is_given() {
    use stickslip::SignalSpec;
    let two = stickslip::Scene {
        signal: SignalSpec::fourier(25e-6, 1.0, 2, false),
        ..Default::default()
    };
    let mut three = two.clone();
    three.signal = SignalSpec::fourier(25e-6, 1.0, 3, false);
    let a = stickslip::plot::motion::figure8(&two).unwrap();
    let b = stickslip::plot::motion::figure8(&three).unwrap();
    assert_ne!(a.csv, b.csv);
    let period = |scene: &stickslip::Scene| scene.build().unwrap().signal.period();
    assert!(a.csv.contains(&format!("T = {:e} s", period(&two))));
    assert!(b.csv.contains(&format!("T = {:e} s", period(&three))));
}

/// The driven rod's figure (`plot::driven`) at the paper's default scene
/// draws what the model says: without the reaction and with the actuator
/// as designed the rod is the signal, so that run's `v_inf` is the
/// prescribed rod's (to 1e-12); the sampled deviation of each steady
/// period reaches the maximum the run certifies (within the sampling's
/// 1e-3) and never exceeds it; and the period mean of the 5 % stiffer
/// rod's deviation is the static deflection `x_0 (c/c_real - 1)` under the
/// offset voltage, up to the mean friction force over `c_real`, which is
/// at most `mu_0 F_c / c_real` (the period mean of the rod's equation,
/// `c_real <x_R> = alpha u_0 + <F>`). Its CSV holds every point drawn.
#[test]
fn the_driven_rod_figure_draws_the_model() {
    use stickslip::plot::driven::{self, STIFFER};
    let scene = stickslip::Scene::default();
    let runs = driven::runs(&scene).unwrap();
    let design = runs.sweep.iter().find(|p| p.stiffness_error == 0).unwrap();
    let v = design.without_reaction.unwrap();
    assert!(
        (v - runs.prescribed).abs() <= 1e-12 * runs.prescribed,
        "{v:e} against {:e}",
        runs.prescribed
    );
    assert_eq!(runs.sweep.len(), 21);
    for p in &runs.periods {
        let sampled = p
            .samples
            .iter()
            .map(|s| s.deviation.abs())
            .fold(0.0, f64::max);
        assert!(
            sampled <= p.deviation_max * (1.0 + 1e-9) && sampled >= p.deviation_max * (1.0 - 1e-3),
            "{} %: sampled {sampled:e}, certified {:e}",
            p.stiffness_error,
            p.deviation_max
        );
    }
    let stiffer = &runs.periods[1];
    assert_eq!(stiffer.stiffness_error, STIFFER);
    let c_real = scene.actuator.unwrap().stiffness * f64::from(100 + STIFFER) / 100.0;
    let mean: f64 = stiffer
        .samples
        .windows(2)
        .map(|w| 0.5 * (w[0].deviation + w[1].deviation) * (w[1].t - w[0].t))
        .sum::<f64>()
        / runs.period;
    let static_shift = runs.offset * (100.0 / f64::from(100 + STIFFER) - 1.0);
    let friction = scene.motor.mu_static * scene.motor.contact_force / c_real;
    assert!(
        (mean - static_shift).abs() <= friction,
        "mean {mean:e}, static {static_shift:e}, friction bound {friction:e}"
    );
    let figure = driven::figure(&runs, stickslip::plot::Preset::DoubleColumn).unwrap();
    // One row per sample of both periods, per stiffness error, and the
    // prescribed rod's.
    let samples: usize = runs.periods.iter().map(|p| p.samples.len()).sum();
    assert_eq!(check_csv(&figure), samples + runs.sweep.len() + 1);
}
