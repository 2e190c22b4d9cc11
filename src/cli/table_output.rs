//! The outputs of the commands that print a table and draw a figure
//! (`characteristic`, `bench`): the table as text, JSON or CSV, to
//! standard output or a file, and the figure with its data beside it.
//!
//! The format is `--json` or `--csv`, else the output file's extension
//! (`.json`, `.csv`), else text. Every output is checked before anything
//! runs: none is the scene or another output, and the figure's format and
//! directory are usable. The table file is written atomically, only after
//! success.

use super::{Failure, Streams, write_out};
use clap::Args;
use std::path::{Path, PathBuf};

/// The table's and the figure's outputs.
#[derive(Args)]
pub(crate) struct TableOutput {
    /// Print one JSON object instead of the text table.
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// Print CSV rows instead of the text table.
    #[arg(long)]
    csv: bool,
    /// Write the output to this file (atomically, only after success);
    /// a name ending in .json or .csv chooses that format.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Also draw the figure: .svg, .pdf or .png, with its data as .csv
    /// beside it.
    #[arg(long, value_name = "FILE")]
    figure: Option<PathBuf>,
    /// Print preset of the figure (default: single-column).
    #[arg(long, value_parser = ["single-column", "double-column", "slide"])]
    style: Option<String>,
}

/// The table's format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TableFormat {
    Text,
    Json,
    Csv,
}

impl TableOutput {
    /// Refuses outputs over the input `scene` or over each other, and a
    /// figure that cannot be written (module docs).
    pub(crate) fn check(&self, scene: Option<&Path>) -> Result<(), Failure> {
        super::check_table_outputs(scene, self.output.as_deref(), self.figure.as_deref())
    }

    /// The format asked for (module docs).
    pub(crate) fn format(&self) -> TableFormat {
        let named = |ext| {
            self.output
                .as_deref()
                .is_some_and(|o| super::extension_is(o, ext))
        };
        if self.json || (!self.csv && named("json")) {
            TableFormat::Json
        } else if self.csv || named("csv") {
            TableFormat::Csv
        } else {
            TableFormat::Text
        }
    }

    /// Draws the figure, if asked, from `draw(name)`, `name` the file's
    /// stem (`fallback` without one).
    pub(crate) fn figure(
        &self,
        fallback: &str,
        draw: impl FnOnce(&str) -> Result<crate::plot::Figure, Failure>,
    ) -> Result<(), Failure> {
        let Some(path) = &self.figure else {
            return Ok(());
        };
        let name = path
            .file_stem()
            .map_or(fallback.to_owned(), |s| s.to_string_lossy().into_owned());
        super::write_figure(&draw(&name)?, self.style.as_deref(), path)
    }

    /// Writes the table's `text` to the output file, or to standard
    /// output.
    pub(crate) fn write(&self, streams: &mut Streams<'_>, text: &str) -> Result<(), Failure> {
        match &self.output {
            Some(path) => crate::output::write_atomically(path, text.as_bytes())
                .map_err(|e| format!("cannot write {}: {e}", path.display())),
            None => write_out(streams, text),
        }
    }
}
