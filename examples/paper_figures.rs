//! Regenerates every figure in `plots/`: the paper's figures 2-9, the
//! stroke scaling law and the event timeline, each as SVG with its data as
//! CSV beside it (see `src/plot/`). Figures 6 and 7 are drawn from the grid
//! of `examples/sweeps/section7.toml`, run in parallel with
//! [`stickslip::sweep`]. The same inputs give the same bytes.
//!
//! `cargo run --release --example paper_figures [OUTPUT_DIR]`
//! (default `plots/` in the crate).

use std::path::{Path, PathBuf};
use std::time::Instant;
use stickslip::plot::performance::GridPoint;
use stickslip::plot::{self, Figure};
use stickslip::sweep::{self, Axis};
use stickslip::{Motor, Scene};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let clock = Instant::now();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = std::env::args_os()
        .nth(1)
        .map_or_else(|| root.join("plots"), PathBuf::from);
    let motor = Motor::default();
    let scene = Scene::default();

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
        plot::velocity::figure8(&scene)?,
        plot::scaling::figure9(&motor)?,
        plot::scaling::stroke_scaling(&scene)?,
        plot::timeline::event_timeline(&scene)?,
    ];
    println!("\n{:<34} {:>10} {:>10}", "figure", "svg bytes", "csv rows");
    for f in &figures {
        f.write_to(&out)?;
        let rows = f.csv.lines().filter(|l| !l.starts_with('#')).count() - 1;
        println!("{:<34} {:>10} {:>10}", f.name, f.svg.len(), rows);
    }
    println!(
        "\nwrote {} figures (SVG + CSV) to {} in {:.2} s",
        figures.len(),
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
