//! Regenerates every figure in `plots/`: every figure of the registry
//! ([`stickslip::plot::registry::ALL`]: the paper's figures 2-9, the
//! stroke scaling law, the event timeline, the characteristic, the
//! optimiser's figures, each `stickslip plot` kind of the default scene, a
//! sweep plot and the compare figure), each in its journal preset
//! (`single-column` or `double-column`, see `src/plot/style.rs`) as SVG
//! with its data as CSV beside it, drawn by the library's plotting kit
//! (`src/plot/`), the same path as `stickslip plot`. The work-precision
//! figure is redrawn from its committed data (`plots/work_precision.svg.csv`,
//! measured by `examples/work_precision.rs`), which it writes back
//! unchanged. The same inputs give the same bytes.
//!
//! `cargo run --release --example paper_figures -- [OUTPUT_DIR] [--format svg|pdf|png] [--style PRESET]`
//! (default `plots/` in the crate, SVG).

use clap::Parser;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stickslip::plot::registry::ALL;
use stickslip::plot::{Figure, Preset};

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
    std::fs::create_dir_all(&out)?;
    println!(
        "{:<34} {:>14} {:>10} {:>10}",
        "figure", "preset", "bytes", "csv rows"
    );
    let mut written = 0;
    for entry in ALL {
        // The figure in its own preset, unless one is asked for; a figure
        // laid out for whichever preset it is given is written at double
        // column.
        let own: Figure = (entry.make)(Preset::DoubleColumn)?;
        let preset = args
            .style
            .as_deref()
            .and_then(Preset::from_name)
            .unwrap_or(own.preset);
        let figure = entry.figure(preset)?;
        let path = out.join(format!("{}.{}", entry.name, args.format));
        let [file, _] = figure.write(&path, &preset.style(), args.dpi)?;
        let bytes = std::fs::metadata(&file)?.len();
        let rows = figure
            .csv
            .lines()
            .filter(|l| !l.starts_with('#'))
            .count()
            .saturating_sub(1);
        println!(
            "{:<34} {:>14} {:>10} {:>10}",
            entry.name,
            preset.name(),
            bytes,
            rows
        );
        written += 1;
    }
    println!(
        "\nwrote {written} figures ({} + CSV) to {} in {:.2} s",
        args.format,
        out.display(),
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}
