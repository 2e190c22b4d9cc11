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
