//! Regenerates every figure in `plots/`: the paper's figures 2-9, the
//! stroke scaling law and the event timeline, each in its journal preset
//! (`single-column` or `double-column`, see `src/plot/style.rs`) as SVG
//! with its data as CSV beside it, drawn by the library's plotting kit
//! (`src/plot/`), the same path as `stickslip plot`. Figures 6 and 7 are
//! drawn from the grid of `examples/sweeps/section7.toml`, run in parallel
//! with [`stickslip::sweep`]. The same inputs give the same bytes.
//!
//! `cargo run --release --example paper_figures -- [OUTPUT_DIR] [--format svg|pdf|png] [--style PRESET]`
//! (default `plots/` in the crate, SVG).

use clap::Parser;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stickslip::SignalSpec;
use stickslip::plot::performance::GridPoint;
use stickslip::plot::{self, Figure, Preset};
use stickslip::sweep::{self, Axis};
use stickslip::{Motor, Scene};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Regenerate the paper's figures and the project's own.
#[derive(Parser)]
struct Args {
    /// Directory to write into (created if missing).
    output_dir: Option<PathBuf>,
    /// File format of the figures (the CSV is always written beside).
    #[arg(long, default_value = "svg", value_parser = ["svg", "pdf", "png"])]
    format: String,
    /// Print preset for every figure (default: each figure's own journal
    /// preset).
    #[arg(long, value_parser = ["single-column", "double-column", "slide"])]
    style: Option<String>,
    /// Resolution of PNG output (pixels per inch).
    #[arg(long, default_value_t = 300.0)]
    dpi: f64,
}

fn main() -> Result<()> {
    let args = Args::parse();
    let clock = Instant::now();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = args.output_dir.unwrap_or_else(|| root.join("plots"));
    let motor = Motor::default();
    let scene = Scene::default();
    // Figure 8's scene (the paper's caption): n = 2, no sigma factors,
    // sqrt(kappa) = 1, stroke 25 um.
    let mut fig8_scene = scene.clone();
    fig8_scene.signal = SignalSpec::fourier(25e-6, 1.0, 2, false);

    let grid = section7_grid(&root.join("examples/sweeps/section7.toml"))?;
    print_grid(&grid);
    let [fig6, fig7] = plot::performance::figures6_7(&grid)?;
    let figures: Vec<Figure> = vec![
        plot::signals::figure2(&motor)?,
        plot::signals::figure3(&motor)?,
        plot::signals::figure4(&motor)?,
        plot::signals::figure5(&motor)?,
        fig6,
        fig7,
        plot::motion::figure8(&fig8_scene)?,
        plot::scaling::figure9(&motor)?,
        plot::scaling::stroke_scaling(&scene)?,
        plot::timeline::event_timeline(&scene)?,
    ];
    std::fs::create_dir_all(&out)?;
    println!(
        "\n{:<34} {:>14} {:>10} {:>10}",
        "figure", "preset", "bytes", "csv rows"
    );
    for f in &figures {
        let path = out.join(format!("{}.{}", f.name, args.format));
        let preset = args
            .style
            .as_deref()
            .and_then(Preset::from_name)
            .unwrap_or(f.preset);
        let [written, _] = f.write(&path, &preset.style(), args.dpi)?;
        let bytes = std::fs::metadata(&written)?.len();
        let rows = f.csv.lines().filter(|l| !l.starts_with('#')).count() - 1;
        println!(
            "{:<34} {:>14} {:>10} {:>10}",
            f.name,
            f.preset.name(),
            bytes,
            rows
        );
    }
    println!(
        "\nwrote {} figures ({} + CSV) to {} in {:.2} s",
        figures.len(),
        args.format,
        out.display(),
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The section-7 grid of the sweep file, run in parallel, in case order.
fn section7_grid(path: &Path) -> Result<Vec<GridPoint>> {
    let sweep = sweep::load(path)?;
    let cases = sweep.cases();
    let mut points = Vec::with_capacity(cases.len());
    for (case, result) in cases.iter().zip(sweep::run_cases(&cases, false)) {
        let report = result?.report;
        let level = case.value(Axis::Level).and_then(|v| v.as_f64());
        let n = case.value(Axis::Harmonics).and_then(|v| v.as_f64());
        let sigma = case.value(Axis::Sigma).and_then(|v| v.as_bool());
        let (Some(level), Some(n), Some(sigma)) = (level, n, sigma) else {
            return Err(format!(
                "{}: needs the axes level, harmonics and sigma",
                path.display()
            )
            .into());
        };
        points.push(GridPoint::from_report(level, n as usize, sigma, &report));
    }
    Ok(points)
}

fn print_grid(grid: &[GridPoint]) {
    println!(
        "section-7 grid ({} cases): level = n sqrt(kappa)",
        grid.len()
    );
    println!(
        "{:>5} {:>2} {:>5} {:>10} {:>8} {:>9} {:>10} {:>12}",
        "level", "n", "sigma", "v_inf m/s", "p_0.99", "zeta", "delta 1/N", "v/S m/(sVA)"
    );
    for p in grid {
        println!(
            "{:>5} {:>2} {:>5} {:>10.5} {:>8} {:>9.4} {:>10.4} {:>12.4e}",
            p.level,
            p.n,
            p.sigma,
            p.v_inf,
            p.startup_periods.map_or("-".to_owned(), |p| p.to_string()),
            p.smoothness,
            p.durability,
            p.velocity_per_power.unwrap_or(f64::NAN)
        );
    }
}
