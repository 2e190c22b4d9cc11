//! One-line messages for TOML errors: the field path, the parser's
//! complaint, line and column, and the offending line.

use std::ops::Range;
use toml::de::{DeTable, DeValue};

/// One line from a TOML error: the field path (found from the error's span
/// in the parsed document or, when the text does not parse, from the
/// offending line and the table above it), the parser's message, line and
/// column, and the offending line itself.
pub(crate) fn parse_message(text: &str, error: &toml::de::Error) -> String {
    let message = error
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let Some(span) = error.span() else {
        return message;
    };
    let start = span.start.min(text.len());
    let before = text.get(..start).unwrap_or("");
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    let shown = shown_line(text, line);
    match field_path(text, &span).or_else(|| key_on_line(text, line)) {
        Some(path) => format!("{path}: {message} (line {line}, column {column}: {shown})"),
        None => format!("{message} (line {line}, column {column}: {shown})"),
    }
}

/// Longest excerpt of an offending line shown in a message, in characters.
const SHOWN_LINE_CHARS: usize = 80;

/// Line `line` (1-based) of `text`, trimmed and quoted, cut to
/// [`SHOWN_LINE_CHARS`] characters.
fn shown_line(text: &str, line: usize) -> String {
    let content = text.lines().nth(line - 1).unwrap_or("").trim();
    let mut shown: String = content.chars().take(SHOWN_LINE_CHARS).collect();
    if content.chars().count() > SHOWN_LINE_CHARS {
        shown.push_str("...");
    }
    format!("`{shown}`")
}

/// The key on line `line` of a text that does not parse, as a dotted path
/// under the last `[table]` header above it (`motor.slider_mass`); the
/// header itself for a header line. A plain scan: the parser gives no tree
/// for broken text.
fn key_on_line(text: &str, line: usize) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let content = lines.get(line - 1)?.trim();
    let header = |l: &str| {
        l.strip_prefix('[')
            .and_then(|h| h.split(']').next())
            .map(|h| h.trim().to_owned())
    };
    if content.starts_with('[') {
        return header(content).filter(|h| !h.is_empty());
    }
    let key = content.split(['=', ' ', '\t']).next()?.trim();
    let bare = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '"' | '\'');
    if key.is_empty() || !key.chars().all(bare) {
        return None;
    }
    let table = lines[..line - 1]
        .iter()
        .rev()
        .map(|l| l.trim())
        .find(|l| l.starts_with('['))
        .and_then(header);
    Some(match table {
        Some(t) if !t.is_empty() => format!("{t}.{key}"),
        _ => key.to_owned(),
    })
}

/// The dotted path (`motor.slider_mass`, `signal.amplitudes[1]`) of the key
/// or value at `span`, if the text parses as TOML and one contains it.
fn field_path(text: &str, span: &Range<usize>) -> Option<String> {
    let root = DeTable::parse(text).ok()?;
    let mut path = Vec::new();
    path_in_table(root.get_ref(), span, &mut path);
    (!path.is_empty()).then(|| path.join("."))
}

fn contains(outer: &Range<usize>, inner: &Range<usize>) -> bool {
    outer.start <= inner.start && inner.end <= outer.end
}

fn path_in_table(table: &DeTable<'_>, span: &Range<usize>, path: &mut Vec<String>) {
    for (key, value) in table.iter() {
        if contains(&key.span(), span) {
            path.push(key.get_ref().to_string());
            return;
        }
        if contains(&value.span(), span) {
            path.push(key.get_ref().to_string());
            path_in_value(value.get_ref(), span, path);
            return;
        }
    }
    // A `[table]`'s span is its header; its keys lie elsewhere in the text.
    for (key, value) in table.iter() {
        if let DeValue::Table(inner) = value.get_ref() {
            let mut sub = vec![key.get_ref().to_string()];
            path_in_table(inner, span, &mut sub);
            if sub.len() > 1 {
                path.extend(sub);
                return;
            }
        }
    }
}

fn path_in_value(value: &DeValue<'_>, span: &Range<usize>, path: &mut Vec<String>) {
    match value {
        DeValue::Table(table) => path_in_table(table, span, path),
        DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                if contains(&item.span(), span) {
                    if let Some(last) = path.last_mut() {
                        last.push_str(&format!("[{i}]"));
                    }
                    path_in_value(item.get_ref(), span, path);
                    return;
                }
            }
        }
        _ => {}
    }
}
