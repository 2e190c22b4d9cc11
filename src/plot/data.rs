//! The data behind a figure, as CSV: `#` comment lines that say what the
//! columns are, one header line, then rows. Numbers are written with `{:e}`
//! (Rust's shortest representation that reads back to the same `f64`), so
//! the text is exact and the same on every run; units are SI.

use std::fmt::Write as _;

/// A CSV table built row by row: `#` comment lines, a header, then rows of
#[derive(Debug, Clone, Default)]
pub struct Csv {
    text: String,
    columns: usize,
}

/// One CSV cell.
#[derive(Debug, Clone, Copy)]
pub enum Cell<'a> {
    /// A number, written with `{:e}`.
    F(f64),
    /// An integer.
    I(i64),
    /// A text (quoted when it holds a comma, quote or line break).
    S(&'a str),
}

impl Csv {
    /// A table with comment lines (each written after `# `) and a header.
    pub fn new(comments: &[&str], header: &[&str]) -> Self {
        let mut text = String::new();
        for c in comments {
            text.push_str("# ");
            text.push_str(c);
            text.push('\n');
        }
        text.push_str(&header.join(","));
        text.push('\n');
        Csv {
            text,
            columns: header.len(),
        }
    }

    /// Appends a row; it must have one cell per column.
    pub fn row(&mut self, cells: &[Cell<'_>]) {
        debug_assert_eq!(cells.len(), self.columns, "one cell per column");
        for (i, cell) in cells.iter().enumerate() {
            if i > 0 {
                self.text.push(',');
            }
            match cell {
                Cell::F(x) => write!(self.text, "{x:e}"),
                Cell::I(i) => write!(self.text, "{i}"),
                Cell::S(s) if s.contains([',', '"', '\n', '\r']) => {
                    write!(self.text, "\"{}\"", s.replace('"', "\"\""))
                }
                Cell::S(s) => write!(self.text, "{s}"),
            }
            .expect("writing to a String cannot fail");
        }
        self.text.push('\n');
    }

    /// The CSV text.
    pub fn finish(self) -> String {
        self.text
    }
}
