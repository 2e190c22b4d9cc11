//! Publication figures: one run's motion, start-up and events, any sweep
//! output, and the paper's figures 2-9, all drawn by one plotting kit and
//! written as SVG, PDF or PNG with their data as CSV beside them.
//!
//! The kit, one idea per file:
//!
//! * `style`: print presets (`single-column` 85 mm, `double-column`
//!   175 mm, `slide`), font size, and the look of series (Okabe-Ito
//!   colours, dash patterns, markers);
//! * `axes`: ranges, linear and logarithmic ticks, tick labels;
//! * `series`: curves, points, bands, areas, panels, clipping;
//! * `legend`: legend entries and their layout; `colorbar`: the scale of
//!   a map's colours;
//! * `layout`: panels in a grid at the printed size, drawn to SVG;
//! * `export`: SVG to PDF (svg2pdf) and PNG (resvg);
//! * `data`: the CSV behind each figure; `font`: the shipped fonts;
//!   `text`: quantity markup (italic, subscripts) and its measurement;
//! * [`marks`]: what a drawing put where (text boxes, frames, data, the
//!   legend's box); [`review`]: a journal reviewer's checks on them;
//!   [`registry`]: every figure the project draws, for those checks.
//!
//! The figure families, one file each:
//!
//! * [`motion`]: a scene's rod and slider velocity, displacement and
//!   acceleration (with the stick band) over chosen periods, events marked
//!   by kind, and its start-up (`v_p` against `p` with `v_inf` and
//!   `p_0.99`); figure 8 of the paper is its first and steady period;
//! * [`sweep`]: an indicator of a sweep output against an axis, in series
//!   and facets, failed and unsettled cases shown apart;
//! * [`signals`]: figures 2-5 (ideal signals, harmonic amplitudes, rod
//!   signals, signals of equal `f_max`);
//! * [`performance`]: figures 6 and 7 (indicators against `n`);
//! * [`precision`]: error against wall time of the event engine and the
//!   fixed-step reference (the work-precision study);
//! * [`scaling`]: figure 9 and the stroke scaling law;
//! * [`timeline`]: the slider's modes over the start-up;
//! * [`characteristic`]: `v_inf` against the load, with the stall force
//!   and the output power;
//! * [`compare`]: a user's fixed-step results against the exact solution
//!   (`stickslip compare`);
//! * [`optimize`]: an optimal signal against the sigma signal, and the
//!   `n = 2` design plane as a heat map;
//! * [`driven`]: the actuator in the loop: a driven rod's velocity and
//!   deviation from its signal, and `v_inf` against the actuator's
//!   stiffness error.
//!
//! # Output contract
//!
//! A [`Figure`] holds its drawing ([`Plot`]) and its data (CSV text);
//! [`Figure::svg`] draws it at a [`Style`]. Text is at least 7 pt at the
//! printed size (scripts included); quantities are typeset from the table
//! of symbols (`src/symbol.rs`) in the markup of `text` (italic, real
//! subscripts); there is no title unless the style has one and no caption
//! text in the drawing (what a caption says goes to the CSV's `# caption:`
//! lines, [`Figure::data`]); a legend takes at most a quarter of the
//! height; no two
//! labelled series share both dash pattern and marker; nothing is drawn in
//! the background colour. Nothing depends on the clock, the thread count
//! or the machine's fonts, so the same inputs give the same bytes. Every
//! file carries the program version (SVG `<metadata>`, PDF information
//! dictionary, PNG `Software` text). [`Figure::write`] writes the figure and its CSV
//! atomically (temporary file and rename) into an existing directory.

mod axes;
pub mod bench;
mod canvas;
pub mod characteristic;
mod colorbar;
pub mod compare;
mod data;
pub mod driven;
pub(crate) mod export;
mod font;
mod layout;
mod legend;
pub mod marks;
pub mod motion;
pub mod optimize;
pub mod performance;
pub mod precision;
pub mod registry;
pub mod review;
pub mod scaling;
mod series;
pub mod signals;
pub(crate) mod style;
pub mod sweep;
mod text;
pub mod timeline;

pub use axes::{Axis, superscript};
pub use canvas::Anchor;
pub use colorbar::ColorBar;
pub use data::{Cell, Csv};
pub use export::ImageFormat;
pub use font::{FAMILY, text_width};
pub use layout::{Plot, fitted};
pub use legend::LegendEntry;
pub use series::{Kind, Panel, Series};
pub use style::{Dash, Look, Marker, Preset, Rgb, Style};
pub use text::visible;

use std::path::{Path, PathBuf};
use thiserror::Error;

/// The program and version, as written into every figure.
pub const PRODUCER: &str = concat!("stickslip ", env!("CARGO_PKG_VERSION"));

/// A finished figure: its drawing, its data, and the preset it is made
/// for.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// File stem: written as `NAME.svg` (or `.pdf`, `.png`) and `NAME.csv`.
    pub name: String,
    /// The drawing.
    pub plot: Plot,
    /// The data drawn, as CSV.
    pub csv: String,
    /// The journal preset the figure is laid out for.
    pub preset: Preset,
}

impl Figure {
    /// The CSV written beside the figure: the caption's text
    /// ([`Plot::notes`], which figures do not draw) as `# caption: ` lines,
    /// then [`Figure::csv`].
    pub fn data(&self) -> String {
        let mut text: String = self
            .plot
            .notes
            .iter()
            .map(|n| format!("# caption: {}\n", visible(n)))
            .collect();
        text.push_str(&self.csv);
        text
    }

    /// The figure's SVG at `style`.
    pub fn svg(&self, style: &Style) -> String {
        self.plot
            .render(style, &format!("{PRODUCER}; figure {}", self.name))
    }

    /// What [`Figure::svg`] puts where at `style` (text boxes, frames,
    /// data, the legend's box), for [`review::review`].
    pub fn marks(&self, style: &Style) -> marks::Marks {
        self.plot.marks(style)
    }

    /// The figure's bytes in `format` at `style` (`dpi` for PNG).
    pub fn encode(
        &self,
        format: ImageFormat,
        style: &Style,
        dpi: f64,
    ) -> Result<Vec<u8>, PlotError> {
        let svg = self.svg(style);
        match format {
            ImageFormat::Svg => Ok(svg.into_bytes()),
            ImageFormat::Pdf => export::pdf(&svg, PRODUCER, &self.name),
            ImageFormat::Png => export::png(&svg, dpi, PRODUCER),
        }
    }

    /// Writes the figure to `path` (format from the extension) and its CSV
    /// ([`Figure::data`]) beside it ([`data_path`]: `path` with `.csv` appended), each
    /// atomically. The directory must exist. Returns the two paths.
    pub fn write(&self, path: &Path, style: &Style, dpi: f64) -> Result<[PathBuf; 2], PlotError> {
        let format = ImageFormat::of(path)?;
        let bytes = self.encode(format, style, dpi)?;
        let csv = data_path(path);
        write_atomically(path, &bytes)?;
        write_atomically(&csv, self.data().as_bytes())?;
        Ok([path.to_owned(), csv])
    }

    /// Writes `NAME.svg` and `NAME.svg.csv` into `dir` (created if missing)
    /// in the figure's own preset.
    pub fn write_to(&self, dir: &Path) -> Result<[PathBuf; 2], PlotError> {
        std::fs::create_dir_all(dir).map_err(|source| PlotError::Io {
            path: dir.display().to_string(),
            source,
        })?;
        self.write(
            &dir.join(format!("{}.svg", self.name)),
            &self.preset.style(),
            300.0,
        )
    }
}

/// The data file of the figure at `figure`: its name with `.csv` appended
/// (`grid.svg` -> `grid.svg.csv`), so that it is never an input of the
/// figure (`grid.csv` plotted to `grid.svg`) nor another figure's data
/// (`x.png` and `x.pdf`).
pub fn data_path(figure: &Path) -> PathBuf {
    let mut name = figure.as_os_str().to_owned();
    name.push(".csv");
    PathBuf::from(name)
}

fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), PlotError> {
    crate::output::write_atomically(path, bytes).map_err(|source| PlotError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// What can go wrong while making a figure.
#[derive(Debug, Error)]
pub enum PlotError {
    /// A simulation behind the figure failed.
    #[error("simulating for figure {figure}: {source}")]
    Simulation {
        /// The figure's name.
        figure: String,
        /// The simulator's error.
        #[source]
        source: crate::error::Error,
    },
    /// The data handed in cannot make the figure.
    #[error("figure {figure}: {reason}")]
    Data {
        /// The figure's name.
        figure: String,
        /// What is wrong with the data.
        reason: String,
    },
    /// An argument (column, axis, option) is not usable.
    #[error("{0}")]
    Argument(String),
    /// The SVG could not be converted.
    #[error("{0}")]
    Export(String),
    /// A file could not be read or written.
    #[error("writing {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
}

impl PlotError {
    fn simulation(figure: &str) -> impl FnOnce(crate::error::Error) -> PlotError + '_ {
        move |source| PlotError::Simulation {
            figure: figure.to_owned(),
            source,
        }
    }
}

/// The entry `key` of the table of symbols (`src/symbol.rs`); the figures
/// name only quantities the table has.
pub(crate) fn sym(key: &str) -> &'static crate::symbol::Symbol {
    crate::symbol::symbol(key).unwrap_or_else(|| panic!("{key} is in the table of symbols"))
}

/// `n` evenly spaced values from `a` to `b`, both included.
pub(crate) fn linspace(a: f64, b: f64, n: usize) -> impl Iterator<Item = f64> {
    let step = (b - a) / (n - 1) as f64;
    (0..n).map(move |i| if i + 1 == n { b } else { a + step * i as f64 })
}

/// A range padded by `frac` of its width on both ends.
pub(crate) fn padded(lo: f64, hi: f64, frac: f64) -> (f64, f64) {
    let pad = (hi - lo) * frac;
    (lo - pad, hi + pad)
}

/// Smallest and largest of some values.
pub(crate) fn min_max(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}
