//! The layout of an output file (format, header line, columns): rendering
//! a row, and reading a file back strictly, every cell one a sweep could
//! have written, for resuming and merging.

use super::grid::SweepFormat;
use super::table::{Cell, Column, Meta, column_difference};
use crate::csv_text::line as csv_line;
use crate::error::SweepError;
use std::path::Path;

/// The layout of an output file: format, header and columns.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    pub format: SweepFormat,
    pub meta: Meta,
    pub columns: Vec<Column>,
}

impl Layout {
    /// A row as one line, without the line end.
    pub(super) fn render(&self, cells: &[Cell]) -> String {
        match self.format {
            SweepFormat::Csv => csv_line(&cells.iter().map(Cell::csv).collect::<Vec<_>>()),
            SweepFormat::Jsonl => {
                let fields: Vec<String> = self
                    .columns
                    .iter()
                    .zip(cells)
                    .map(|(c, cell)| format!("{}:{}", serde_json::json!(c.name()), cell.json()))
                    .collect();
                format!("{{{}}}", fields.join(","))
            }
        }
    }

    /// The lines before the rows, each with its line end.
    pub(super) fn head(&self) -> String {
        let mut out = self.meta.line(self.format);
        out.push('\n');
        if self.format == SweepFormat::Csv {
            let names: Vec<&str> = self.columns.iter().map(|c| c.name()).collect();
            out.push_str(&csv_line(&names));
            out.push('\n');
        }
        out
    }

    /// Position of a column.
    pub(super) fn position(&self, column: Column) -> Option<usize> {
        self.columns.iter().position(|c| *c == column)
    }
}

/// A row read back.
#[derive(Debug, Clone)]
pub(super) struct Row {
    /// Its case index.
    pub case: u64,
    /// Its line number in the file (1-based).
    pub line: usize,
    /// Its cells, in column order.
    pub cells: Vec<Cell>,
}

/// An output file read back.
#[derive(Debug)]
pub(super) struct Parsed {
    /// The format; `None` for an empty file.
    pub format: Option<SweepFormat>,
    /// The header line, if the file has one.
    pub meta: Option<Meta>,
    /// The columns; `None` for a file without a column header or a row.
    pub columns: Option<Vec<Column>>,
    /// The complete rows, in file order.
    pub rows: Vec<Row>,
    /// The number of an incomplete last line (no line end), if any.
    pub truncated: Option<usize>,
}

/// Reads an output file. Every complete line must be a header line, the
/// column header or a valid row; errors name the file, the line and the
/// column.
pub(super) fn parse(path: &Path, text: &str) -> Result<Parsed, SweepError> {
    let bad = |line: usize, reason: String| SweepError::Output {
        path: path.display().to_string(),
        reason: format!("line {line}: {reason}"),
    };
    let complete = &text[..text.rfind('\n').map_or(0, |i| i + 1)];
    let truncated = (complete.len() < text.len()).then(|| complete.lines().count() + 1);
    let mut lines = complete
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .peekable();
    let mut parsed = Parsed {
        format: None,
        meta: None,
        columns: None,
        rows: Vec::new(),
        truncated,
    };
    let Some(&(_, first)) = lines.peek() else {
        return Ok(parsed);
    };
    if first.starts_with('{') {
        parsed.format = Some(SweepFormat::Jsonl);
        for (number, line) in lines {
            let value: serde_json::Value =
                serde_json::from_str(line).map_err(|e| bad(number, format!("not JSON: {e}")))?;
            let serde_json::Value::Object(map) = value else {
                return Err(bad(number, "not a JSON object".into()));
            };
            if number == 1
                && let Some(meta) = Meta::parse_json(&map)
            {
                parsed.meta = Some(meta);
                continue;
            }
            let mut columns = Vec::new();
            for key in map.keys() {
                columns.push(
                    Column::from_name(key)
                        .ok_or_else(|| bad(number, format!("unknown column \"{key}\"")))?,
                );
            }
            columns.sort_by_key(|c| c.rank());
            match &parsed.columns {
                None => parsed.columns = Some(columns.clone()),
                Some(c) if *c != columns => {
                    return Err(bad(
                        number,
                        format!(
                            "has {} compared with the rows above",
                            column_difference(&columns, c)
                        ),
                    ));
                }
                Some(_) => {}
            }
            let mut cells = Vec::with_capacity(columns.len());
            for column in &columns {
                let cell = column.parse_json(&map[column.name()]).map_err(|reason| {
                    bad(
                        number,
                        format!("{} = {}: {reason}", column.name(), map[column.name()]),
                    )
                })?;
                cells.push(cell);
            }
            consistent(&columns, &cells).map_err(|reason| bad(number, reason))?;
            let row = row(number, cells).ok_or_else(|| bad(number, "no case index".into()))?;
            parsed.rows.push(row);
        }
        return Ok(parsed);
    }
    parsed.format = Some(SweepFormat::Csv);
    let mut offset = 0;
    if let Some(meta) = Meta::parse_csv(first) {
        parsed.meta = Some(meta);
        lines.next();
        offset = 1;
    }
    let rest: String = lines.map(|(_, l)| format!("{l}\n")).collect();
    let records = crate::csv_text::records(&rest)
        .map_err(|(line, reason)| bad(offset + line, format!("unreadable CSV: {reason}")))?;
    let mut records = records.into_iter();
    let Some(header) = records.next() else {
        return Ok(parsed);
    };
    let header = header.fields;
    if header.first().map(String::as_str) != Some("case") {
        return Err(bad(
            offset + 1,
            "not a sweep output: the first column is not \"case\"".into(),
        ));
    }
    let mut columns = Vec::new();
    for name in &header {
        columns.push(
            Column::from_name(name)
                .ok_or_else(|| bad(offset + 1, format!("unknown column \"{name}\"")))?,
        );
    }
    for record in records {
        let number = offset + record.line;
        let mut cells = Vec::with_capacity(columns.len());
        for (column, field) in columns.iter().zip(&record.fields) {
            let cell = column.parse_csv(field).map_err(|reason| {
                bad(number, format!("{} = \"{field}\": {reason}", column.name()))
            })?;
            cells.push(cell);
        }
        consistent(&columns, &cells).map_err(|reason| bad(number, reason))?;
        let row = row(number, cells).ok_or_else(|| bad(number, "no case index".into()))?;
        parsed.rows.push(row);
    }
    parsed.columns = Some(columns);
    Ok(parsed)
}

/// A row holds what a sweep writes: an outcome (a `regime`, no `failure`)
/// or an error (a `failure` text and nothing but the case's own columns).
fn consistent(columns: &[Column], cells: &[Cell]) -> Result<(), String> {
    let at = |c: Column| columns.iter().position(|x| *x == c).map(|i| &cells[i]);
    if let Some(Cell::Text(_)) = at(Column::Failure) {
        let own = |c: &Column| {
            matches!(
                c,
                Column::Case | Column::Axis(_) | Column::SceneHash | Column::F0 | Column::Failure
            )
        };
        if let Some((c, _)) = columns
            .iter()
            .zip(cells)
            .find(|(c, cell)| !own(c) && **cell != Cell::Empty)
        {
            return Err(format!(
                "has a failure and a value of {}: a sweep writes one or the other",
                c.name()
            ));
        }
    } else if let Some(Cell::Empty) = at(Column::Regime) {
        return Err("has neither a regime nor a failure".to_owned());
    }
    Ok(())
}

/// A row from its cells; `None` without a `case` cell first.
fn row(line: usize, cells: Vec<Cell>) -> Option<Row> {
    match cells.first() {
        Some(Cell::Unsigned(case)) => Some(Row {
            case: *case,
            line,
            cells,
        }),
        _ => None,
    }
}
