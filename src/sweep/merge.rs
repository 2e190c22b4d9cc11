//! Joining sweep outputs (shards) into one file that holds only what a
//! sweep could have written: same header and columns in every input,
//! every row complete and valid, every case once. The inputs are only
//! read; the output, which may not be one of them, is written atomically
//! and only if the merge succeeds.

use super::execute::write_atomically;
use super::layout::{self, Layout};
use super::table;
use crate::error::SweepError;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// How many missing cases [`MergeSummary::first_missing`] lists.
pub const MISSING_LISTED: usize = 10;

/// What [`merge`] did.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct MergeSummary {
    /// Rows written.
    pub rows: usize,
    /// How many case indices below the largest one no input has.
    pub missing: u64,
    /// The first of those (at most [`MISSING_LISTED`]).
    pub first_missing: Vec<u64>,
}

/// The identity of an existing file: its device and inode where there
/// are such (so that links are recognised), else its canonical path.
fn file_id(path: &Path) -> Option<String> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        std::fs::metadata(path)
            .ok()
            .map(|m| format!("{}:{}", m.dev(), m.ino()))
    }
    #[cfg(not(unix))]
    {
        path.canonicalize().ok().map(|p| p.display().to_string())
    }
}

/// Joins sweep outputs into `output` (see the module docs). Errors name
/// the input and the line; on error nothing is written. Cases of the sweep
/// that no input holds (its number of cases is in the inputs' first line;
/// for files of earlier versions, the cases below the highest one) are an
/// error, naming them, unless `allow_partial`: then the merge is written
/// and [`MergeSummary`] lists them.
pub fn merge(
    output: &Path,
    inputs: &[PathBuf],
    allow_partial: bool,
) -> Result<MergeSummary, SweepError> {
    let refuse = |path: &Path, reason: String| SweepError::Output {
        path: path.display().to_string(),
        reason,
    };
    let mut ids: Vec<(String, &PathBuf)> = Vec::new();
    for input in inputs {
        if let Some(id) = file_id(input) {
            if let Some((_, first)) = ids.iter().find(|(other, _)| *other == id) {
                return Err(refuse(
                    input,
                    format!("is given twice (also as {})", first.display()),
                ));
            }
            ids.push((id, input));
        }
    }
    if let Some(id) = file_id(output)
        && let Some((_, input)) = ids.iter().find(|(other, _)| *other == id)
    {
        return Err(refuse(
            output,
            format!(
                "the output is also an input ({}); merge into a new file",
                input.display()
            ),
        ));
    }

    let mut layout: Option<(Layout, &PathBuf)> = None;
    let mut meta_of_first: Option<(table::Meta, &PathBuf)> = None;
    let mut rows: BTreeMap<u64, (String, &PathBuf, usize)> = BTreeMap::new();
    for input in inputs {
        let text = std::fs::read_to_string(input).map_err(|source| SweepError::Io {
            path: input.display().to_string(),
            source,
        })?;
        let parsed = layout::parse(input, &text)?;
        if let Some(line) = parsed.truncated {
            return Err(refuse(
                input,
                format!("line {line}: the row is truncated (no line end); rerun its sweep"),
            ));
        }
        let Some(format) = parsed.format else {
            return Err(refuse(input, "is empty: not a sweep output".into()));
        };
        let Some(meta) = parsed.meta else {
            return Err(refuse(
                input,
                "line 1: no stickslip_version header line (written by an older stickslip); rerun its sweep"
                    .into(),
            ));
        };
        match &meta_of_first {
            None => meta_of_first = Some((meta.clone(), input)),
            Some((first, first_path)) if *first != meta => {
                return Err(refuse(
                    input,
                    format!(
                        "line 1: written by stickslip {} from base scene {}, {} by stickslip {} from base scene {}",
                        meta.version,
                        meta.base_scene_hash,
                        first_path.display(),
                        first.version,
                        first.base_scene_hash
                    ),
                ));
            }
            Some(_) => {}
        }
        // A JSON-lines shard without rows has no columns to compare.
        let Some(columns) = parsed.columns else {
            continue;
        };
        let here = Layout {
            format,
            meta,
            columns,
        };
        match &layout {
            None => layout = Some((here.clone(), input)),
            Some((first, first_path)) => {
                if here.format != first.format {
                    return Err(refuse(
                        input,
                        format!(
                            "holds {} rows, {} holds {}",
                            here.format.extension(),
                            first_path.display(),
                            first.format.extension()
                        ),
                    ));
                }
                if here.columns != first.columns {
                    return Err(refuse(
                        input,
                        format!(
                            "has {} compared with {}",
                            table::column_difference(&here.columns, &first.columns),
                            first_path.display()
                        ),
                    ));
                }
            }
        }
        for row in parsed.rows {
            if let Some((_, other, line)) = rows.get(&row.case) {
                return Err(refuse(
                    input,
                    format!(
                        "line {}: case {} is also in {} line {line}",
                        row.line,
                        row.case,
                        other.display()
                    ),
                ));
            }
            rows.insert(row.case, (here.render(&row.cells), input, row.line));
        }
    }
    let Some((layout, _)) = layout else {
        return Err(refuse(
            output,
            "nothing to merge: no input has a column header or a row".into(),
        ));
    };
    // Gaps from the keys, not by counting up to the largest case; up to
    // the sweep's number of cases where the inputs give it.
    let last = rows.keys().next_back().copied().unwrap_or(0);
    let end = match layout.meta.cases {
        Some(n) => n.max(last + u64::from(!rows.is_empty())),
        None => last + u64::from(!rows.is_empty()),
    };
    let missing = end - rows.len() as u64;
    let mut first_missing = Vec::new();
    let mut expected = 0;
    for case in rows.keys().copied().chain([end]) {
        first_missing.extend((expected..case).take(MISSING_LISTED - first_missing.len()));
        if first_missing.len() == MISSING_LISTED {
            break;
        }
        expected = case + 1;
    }
    if missing > 0 && !allow_partial {
        let more = if missing > first_missing.len() as u64 {
            ", ..."
        } else {
            ""
        };
        let listed: Vec<String> = first_missing.iter().map(u64::to_string).collect();
        return Err(refuse(
            output,
            format!(
                "not written: {missing} of the sweep's {end} cases are in no input ([{}{more}]); \
                 a shard is missing or unfinished; give it, or pass --allow-partial",
                listed.join(", ")
            ),
        ));
    }
    let mut text = layout.head();
    for (line, _, _) in rows.values() {
        text.push_str(line);
        text.push('\n');
    }
    write_atomically(output, &text)?;
    Ok(MergeSummary {
        rows: rows.len(),
        missing,
        first_missing,
    })
}
