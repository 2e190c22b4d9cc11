//! The columns of a CSV file: names in a header row, lines starting with
//! `#` are comments, cells trimmed; a column may end early (empty cells
//! below its last value) but have no gaps. Read with the `csv` crate.

use super::CompareError;
use super::read::RawColumn;
use std::path::Path;

/// The columns of a CSV file (name, raw values) and the file line of every
/// data row.
/// Only columns named in `wanted` (case-insensitive) are parsed; the others
/// are returned empty.
pub(crate) fn columns(
    path: &Path,
    file: &str,
    wanted: &[String],
) -> Result<(Vec<RawColumn>, Vec<usize>), CompareError> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .flexible(false)
        .from_path(path)
        .map_err(|e| CompareError::io(file, e.to_string()))?;
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| CompareError::io(file, e.to_string()))?
        .iter()
        .map(str::to_owned)
        .collect();
    if header.iter().all(String::is_empty) {
        return Err(CompareError::data(
            file,
            None,
            None,
            "no header row with column names".to_owned(),
        ));
    }
    let mut columns: Vec<RawColumn> = header.iter().map(|n| (n.clone(), Ok(Vec::new()))).collect();
    let parse: Vec<bool> = header
        .iter()
        .map(|n| wanted.iter().any(|w| w.eq_ignore_ascii_case(n)))
        .collect();
    // Row index at which each column ended (its first empty cell).
    let mut ended: Vec<Option<usize>> = vec![None; header.len()];
    let mut lines = Vec::new();
    let mut record = csv::StringRecord::new();
    let mut row = 0;
    loop {
        match reader.read_record(&mut record) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => return Err(CompareError::io(file, e.to_string())),
        }
        let line = record.position().map_or(0, |p| p.line() as usize);
        lines.push(line);
        for (j, cell) in record.iter().enumerate() {
            if !parse[j] {
                continue;
            }
            // A column that cannot be read is an error only if it is used.
            let Ok(values) = &mut columns[j].1 else {
                continue;
            };
            let at = Some(format!("row {} (line {line})", row + 1));
            if cell.is_empty() {
                ended[j].get_or_insert(row);
                continue;
            }
            if let Some(end) = ended[j] {
                columns[j].1 = Err((
                    at,
                    format!(
                        "a value after the empty cell of row {}: a column may only end \
                         early, not have gaps",
                        end + 1
                    ),
                ));
                continue;
            }
            match cell.parse::<f64>() {
                Ok(v) => values.push(v),
                Err(_) => columns[j].1 = Err((at, format!("`{cell}` is not a number"))),
            }
        }
        row += 1;
    }
    Ok((columns, lines))
}
