//! Every figure the project draws, in one list: the figures in `plots/`
//! (the paper's figures 2-9, the stroke scaling law, the event timeline,
//! the characteristic, the optimiser's two figures and the driven rod),
//! every `stickslip plot --figure` kind of a scene, sweep plots (faceted; two
//! columns on one axis; display units and a named column), the
//! work-precision study (drawn from its committed data,
//! `plots/work_precision.svg.csv`: its wall times are measured, so the
//! data, not a run, is the input) and the `stickslip compare` figure of
//! the default scene's own fixed-step reference at two resolutions.
//!
//! Contract: each [`Entry`] makes its figure from the project's own
//! inputs (the default scene and motor, the section-7 grid, the default
//! optimisation) laid out for the preset it is given
//! ([`Figure::preset`]), so a check that walks [`ALL`] in every
//! [`Preset`] covers a figure added here without being touched. A figure
//! added to the project is added here. Inputs shared by several entries
//! (the section-7 grid, the optimum) are computed once per process.

use super::motion::{self, Row, Span};
use super::performance::{GridPoint, figures6_7};
use super::sweep::{SweepSpec, sweep_figure_from};
use super::{
    Figure, PlotError, Preset, bench, characteristic, compare, driven, optimize, precision,
    scaling, signals, timeline,
};
use crate::motor::Motor;
use crate::optimize::map::{self, MapGrid};
use crate::optimize::{OptimizeTable, Optimum, Overrides, Settings};
use crate::scene::Scene;
use crate::signal::SignalSpec;
use std::sync::OnceLock;

/// One figure of the project.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// The figure's name (its file stem where it is written).
    pub name: &'static str,
    /// Makes the figure laid out for a preset.
    pub make: fn(Preset) -> Result<Figure, PlotError>,
}

/// Every figure the project draws.
pub const ALL: &[Entry] = &[
    entry("fig2_ideal_and_fourier", |_| {
        signals::figure2(&Motor::default())
    }),
    entry("fig3_harmonic_amplitudes", |_| {
        signals::figure3(&Motor::default())
    }),
    entry("fig4_rod_signals", |_| signals::figure4(&Motor::default())),
    entry("fig5_equal_fmax", |_| signals::figure5(&Motor::default())),
    entry("fig6_indicators_without_sigma", |_| {
        Ok(figures6_7(grid()?)?
            .into_iter()
            .next()
            .expect("two figures"))
    }),
    entry("fig7_indicators_with_sigma", |_| {
        Ok(figures6_7(grid()?)?
            .into_iter()
            .nth(1)
            .expect("two figures"))
    }),
    entry("fig8_rod_slider_velocity", |_| {
        motion::figure8(&figure8_scene())
    }),
    entry(
        "fig9_fmax_fallowed",
        |_| scaling::figure9(&Motor::default()),
    ),
    entry("stroke_scaling", |_| {
        scaling::stroke_scaling(&Scene::default())
    }),
    entry("event_timeline", |_| {
        timeline::event_timeline(&Scene::default())
    }),
    entry("characteristic_default", |_| {
        characteristic::scene_characteristic(&Scene::default(), "characteristic_default")
    }),
    entry("bench_default", |_| {
        bench::figure(bench_default()?, &Scene::default(), "bench_default")
    }),
    entry("optimize_signal", |_| {
        optimize::signal_figure(optimum()?, "optimize_signal")
    }),
    entry("optimize_plane", |_| {
        let m = map::map(optimum()?, MapGrid::default());
        optimize::map_figure(&m, "optimize_plane")
    }),
    entry(driven::NAME, |preset| {
        driven::figure(driven_runs()?, preset)
    }),
    entry("plot_motion", |_| {
        // `stickslip plot SCENE -o FILE`: its default periods and rows.
        let spans: Vec<Span> = motion::parse_periods("1,last").map_err(PlotError::Argument)?;
        motion::motion(
            &Scene::default(),
            &spans,
            &[Row::Velocity, Row::Displacement, Row::Acceleration],
            "plot_motion",
        )
    }),
    entry("plot_startup", |_| {
        motion::startup(&Scene::default(), "plot_startup")
    }),
    entry("plot_timeline", |_| {
        timeline::scene_timeline(&Scene::default(), "plot_timeline")
    }),
    entry("compare_reference", |_| {
        // `stickslip compare` of the default scene's fixed-step reference
        // at 500 and at the paper's 5000 steps per harmonic period, over
        // 1200 periods (the start-up is over).
        compare::reference_figure(&Scene::default(), &[500, 5000], 1200, "compare_reference")
    }),
    entry(precision::NAME, |preset| {
        precision::figure(&precision::committed()?, preset)
    }),
    entry("plot_sweep_faceted", |_| {
        let spec = SweepSpec {
            x: "harmonics".into(),
            y: vec!["v_inf".into()],
            series: Some("level".into()),
            facet: Some("sigma".into()),
            ..SweepSpec::default()
        };
        sweep_figure_from(
            sweep_csv()?.as_bytes(),
            "section-7 grid",
            &spec,
            "plot_sweep_faceted",
        )
    }),
    entry("plot_sweep_two_columns", |_| {
        // Two columns of one unit on one log axis in ms, per sigma.
        let spec = SweepSpec {
            x: "harmonics".into(),
            y: vec!["startup_time".into(), "period".into()],
            facet: Some("sigma".into()),
            log_y: true,
            y_unit: Some("ms".into()),
            ..SweepSpec::default()
        };
        sweep_figure_from(
            sweep_csv()?.as_bytes(),
            "section-7 grid",
            &spec,
            "plot_sweep_two_columns",
        )
    }),
    entry("plot_sweep_units", |_| {
        // A log axis in ms with a reference line, and a column named by
        // the user.
        let spec = SweepSpec {
            x: "level".into(),
            y: vec!["startup_time".into()],
            series: Some("harmonics".into()),
            log_y: true,
            y_unit: Some("ms".into()),
            ref_y: vec![10.0],
            labels: vec![("level".into(), "level $L$ = $n$√$κ$".into())],
            ..SweepSpec::default()
        };
        sweep_figure_from(
            sweep_csv()?.as_bytes(),
            "section-7 grid",
            &spec,
            "plot_sweep_units",
        )
    }),
];

/// An entry whose figure is laid out for the preset asked for.
const fn entry(name: &'static str, make: fn(Preset) -> Result<Figure, PlotError>) -> Entry {
    Entry { name, make }
}

impl Entry {
    /// The figure laid out for `preset`.
    pub fn figure(&self, preset: Preset) -> Result<Figure, PlotError> {
        let mut f = (self.make)(preset)?;
        f.preset = preset;
        Ok(f)
    }
}

/// Figure 8's scene (the paper's caption): n = 2, no sigma factors,
/// sqrt(kappa) = 1, stroke 25 µm.
fn figure8_scene() -> Scene {
    Scene {
        signal: SignalSpec::fourier(25e-6, 1.0, 2, false),
        ..Scene::default()
    }
}

/// The section-7 grid (`examples/sweeps/section7.toml`): levels
/// `n sqrt(kappa)` 3 to 15, n = 2..8, with and without sigma factors.
fn grid() -> Result<&'static [GridPoint], PlotError> {
    static GRID: OnceLock<Result<Vec<GridPoint>, String>> = OnceLock::new();
    let grid = GRID.get_or_init(|| {
        let mut points = Vec::new();
        for level in [3.0, 6.0, 9.0, 12.0, 15.0] {
            for n in 2..=8usize {
                for sigma in [false, true] {
                    let sqrt_kappa = level / n as f64;
                    let scene = Scene {
                        signal: SignalSpec::fourier(25e-6, sqrt_kappa * sqrt_kappa, n, sigma),
                        ..Scene::default()
                    };
                    let report = crate::simulation::steady(&scene).map_err(|e| e.to_string())?;
                    points.push(GridPoint::from_report(level, n, sigma, &report));
                }
            }
        }
        Ok(points)
    });
    grid.as_deref().map_err(|e| PlotError::Data {
        figure: "section-7 grid".to_owned(),
        reason: e.clone(),
    })
}

/// The section-7 grid as a sweep output.
fn sweep_csv() -> Result<String, PlotError> {
    let mut csv =
        String::from("case,level,harmonics,sigma,v_inf,startup_time,period,regime,failure\n");
    for (i, p) in grid()?.iter().enumerate() {
        let startup = p.startup_time().map_or(String::new(), |t| t.to_string());
        csv.push_str(&format!(
            "{i},{},{},{},{},{startup},{},,\n",
            p.level, p.n, p.sigma, p.v_inf, p.period
        ));
    }
    Ok(csv)
}

/// The driven rod's runs at the default scene (the paper's signal, the
/// Table 1 actuator), shared by the presets.
fn driven_runs() -> Result<&'static driven::DrivenRuns, PlotError> {
    static RUNS: OnceLock<Result<driven::DrivenRuns, String>> = OnceLock::new();
    RUNS.get_or_init(|| driven::runs(&Scene::default()).map_err(|e| e.to_string()))
        .as_ref()
        .map_err(|e| PlotError::Data {
            figure: driven::NAME.to_owned(),
            reason: e.clone(),
        })
}

/// The optimum of the default scene with the default settings (`stickslip
/// optimize examples/scenes/paper_default.toml`).
fn optimum() -> Result<&'static Optimum, PlotError> {
    static OPTIMUM: OnceLock<Result<Optimum, String>> = OnceLock::new();
    let found = OPTIMUM.get_or_init(|| {
        let scene = Scene::default();
        let settings = Settings::resolve(&OptimizeTable::default(), &Overrides::default(), &scene)
            .map_err(|e| e.to_string())?;
        crate::optimize::optimize(&scene, &settings).map_err(|e| e.to_string())
    });
    found.as_ref().map_err(|e| PlotError::Data {
        figure: "optimize".to_owned(),
        reason: e.clone(),
    })
}

/// The bench of the default scene with the default options, computed once.
fn bench_default() -> Result<&'static crate::bench::Bench, PlotError> {
    static BENCH: OnceLock<Result<crate::bench::Bench, String>> = OnceLock::new();
    let found = BENCH.get_or_init(|| {
        crate::bench::bench(&Scene::default(), &crate::bench::BenchOptions::default())
            .map_err(|e| e.to_string())
    });
    found.as_ref().map_err(|e| PlotError::Data {
        figure: "bench_default".to_owned(),
        reason: e.clone(),
    })
}
