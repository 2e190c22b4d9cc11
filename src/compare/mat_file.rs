//! The columns of a MATLAB Level 5 MAT-file (as MATLAB's `save`, Simulink
//! and scipy's `savemat` write it, compressed or not), read with `matrw`.
//!
//! Every variable is flattened into named columns:
//!
//! * a real numeric vector `v`: the column `v`;
//! * a real numeric matrix `M` of `N x k` (an array with a time column, a
//!   matrix of several signals): the columns `M(:,1)` .. `M(:,k)`;
//! * a struct `s`: its fields, named `s.f`, flattened alike (`s.f(:,j)`,
//!   `s.f.g`); the elements `i >= 2` of a struct array as `s(i).f`;
//! * a matrix with named columns, a struct with `data` (`N x k`) and
//!   `colheaders` (a cell of `k` names, as MATLAB's `importdata` returns):
//!   also the columns by those names;
//! * Simulink's "Structure with time" and "Structure", a struct `s` with
//!   `time` (empty in "Structure") and `signals` (`values`, `label`): also
//!   the column `s.time`, and every signal by its `label` when it has one
//!   (with the struct's time as `label.time`);
//!   a struct with one signal also by the variable's name `s` (a "To
//!   Workspace" block names the variable), `s(:,j)` for a matrix of
//!   signals.
//!
//! A variable that is not real numeric data (text, a complex array, an
//! array of more than two dimensions) is listed with the reason; that is
//! an error only when the variable is used.

use super::CompareError;
use super::read::RawColumn;
use matrw::{MatVariable, MatlabType};
use std::cell::Cell;
use std::sync::Once;

/// Length of the header of a MAT-file: 116 bytes of descriptive text, 8
/// of subsystem offset, 2 of version and 2 of endian indicator.
const HEADER: usize = 128;

/// The text `matrw` expects at the start of a Level 5 header.
const LEVEL_5_TEXT: &[u8] = b"MATLAB 5.0 MAT-file, ";

/// The flattened columns of the MAT-file `bytes` (read from `file`).
///
/// The header is checked here: a version-5 file (`0x0100`) with the
/// endian indicator `IM` or `MI`. Its descriptive text is only text
/// (MATLAB writes `MATLAB 5.0 MAT-file, Platform: ...`, scipy omits the
/// comma), so it is replaced by the one `matrw` expects before parsing,
/// and compressed variables are inflated here ([`inflated`]).
pub(crate) fn columns(bytes: &[u8], file: &str) -> Result<Vec<RawColumn>, CompareError> {
    let bad = |reason: String| CompareError::data(file, None, None, reason);
    if bytes.len() < HEADER || !bytes.starts_with(b"MATLAB") {
        return Err(bad(
            "not a MATLAB Level 5 MAT-file (no 128-byte header starting with `MATLAB`)".to_owned(),
        ));
    }
    let endian = &bytes[126..128];
    let version = match endian {
        b"IM" => u16::from_le_bytes([bytes[124], bytes[125]]),
        b"MI" => u16::from_be_bytes([bytes[124], bytes[125]]),
        _ => {
            return Err(bad(
                "not a MATLAB Level 5 MAT-file (no endian indicator IM or MI)".to_owned(),
            ));
        }
    };
    if version != 0x0100 {
        return Err(bad(format!(
            "a MAT-file of version {version:#06x} (0x0200 is v7.3, HDF5); save it as a Level 5 \
             file (MATLAB: save -v7)"
        )));
    }
    let bytes = inflated(bytes, endian == b"IM").map_err(bad)?;
    let mat = parse(&bytes).map_err(|e| bad(format!("a damaged MAT-file ({e})")))?;
    let mut out = Vec::new();
    for (name, var) in mat.iter() {
        flatten(name, var, &mut out);
    }
    Ok(out)
}

thread_local! {
    /// True while this thread parses with `matrw`: its panics are reported
    /// as errors, not printed.
    static PARSING: Cell<bool> = const { Cell::new(false) };
}

/// `matrw`'s parse of an inflated file. `matrw` panics on some damaged
/// files (a field name that is not UTF-8, an array whose size disagrees
/// with its dimensions); such a panic is caught and becomes the error,
/// and the panic hook stays silent for it (for this thread, during the
/// parse only; other panics are printed as before).
fn parse(bytes: &[u8]) -> Result<matrw::MatFile, String> {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !PARSING.with(Cell::get) {
                previous(info);
            }
        }));
    });
    PARSING.with(|p| p.set(true));
    let result = std::panic::catch_unwind(|| matrw::load_matfile_from_u8(bytes));
    PARSING.with(|p| p.set(false));
    let first_line = |text: &str| text.lines().next().unwrap_or("").trim().to_owned();
    match result {
        Ok(Ok(mat)) => Ok(mat),
        Ok(Err(e)) => Err(first_line(&e.to_string())),
        Err(payload) => Err(payload
            .downcast_ref::<String>()
            .map(|s| first_line(s))
            .or_else(|| payload.downcast_ref::<&str>().map(|s| first_line(s)))
            .unwrap_or_else(|| "the reader failed".to_owned())),
    }
}

/// Data type of a compressed data element.
const MI_COMPRESSED: u32 = 15;
/// Data type of an array.
const MI_MATRIX: u32 = 14;

/// The file with the descriptive text `matrw` expects and every
/// compressed top-level element (zlib, type 15) replaced by the element it
/// holds, so that a damaged stream is reported here. Each top-level
/// element is a tag (type and size, 4 bytes each) and its data.
fn inflated(bytes: &[u8], little: bool) -> Result<Vec<u8>, String> {
    use std::io::Read as _;
    let word = |at: usize| -> u32 {
        let b = [bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]];
        if little {
            u32::from_le_bytes(b)
        } else {
            u32::from_be_bytes(b)
        }
    };
    let mut out = Vec::with_capacity(bytes.len());
    out.extend_from_slice(&bytes[..HEADER]);
    out[..116].fill(b' ');
    out[..LEVEL_5_TEXT.len()].copy_from_slice(LEVEL_5_TEXT);
    let mut at = HEADER;
    let mut index = 0;
    while at + 8 <= bytes.len() {
        index += 1;
        let (kind, size) = (word(at), word(at + 4) as usize);
        let end = at
            .checked_add(8 + size)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                format!(
                    "a damaged MAT-file: variable {index} claims {size} bytes, {} are left",
                    bytes.len() - at - 8
                )
            })?;
        match kind {
            MI_COMPRESSED => {
                let mut inner = Vec::new();
                flate2::read::ZlibDecoder::new(&bytes[at + 8..end])
                    .read_to_end(&mut inner)
                    .map_err(|e| {
                        format!("a damaged MAT-file: variable {index} does not decompress ({e})")
                    })?;
                out.extend_from_slice(&inner);
            }
            MI_MATRIX => out.extend_from_slice(&bytes[at..end]),
            other => {
                return Err(format!(
                    "a damaged MAT-file: variable {index} has the data type {other}, not an \
                     array (14) or compressed data (15)"
                ));
            }
        }
        at = end;
    }
    Ok(out)
}

/// The values of a real numeric array as doubles, or why not.
fn numbers(var: &MatVariable) -> Result<(Vec<usize>, Vec<f64>), String> {
    let MatVariable::NumericArray(a) = var else {
        return Err("is not a numeric array".to_owned());
    };
    let shape = a
        .dim
        .iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join("x");
    if a.value_cmp.is_some() {
        return Err(format!(
            "is a complex {shape} array, not a real numeric one"
        ));
    }
    let values: Vec<f64> = match &a.value {
        MatlabType::U8(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::I8(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::U16(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::I16(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::U32(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::I32(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::U64(v) => v.iter().map(|&x| x as f64).collect(),
        MatlabType::I64(v) => v.iter().map(|&x| x as f64).collect(),
        MatlabType::F32(v) => v.iter().map(|&x| f64::from(x)).collect(),
        MatlabType::F64(v) => v.clone(),
        MatlabType::UTF8(_) | MatlabType::UTF16(_) => {
            return Err(format!("is a {shape} text, not numbers"));
        }
        MatlabType::BOOL(_) => return Err(format!("is a {shape} logical array, not numbers")),
    };
    Ok((a.dim.clone(), values))
}

/// A text (char array), if `var` is one.
fn text(var: &MatVariable) -> Option<String> {
    match var {
        MatVariable::NumericArray(a) => match &a.value {
            MatlabType::UTF8(c) | MatlabType::UTF16(c) => Some(c.iter().collect()),
            _ => None,
        },
        MatVariable::Compressed(c) => text(&c.value),
        _ => None,
    }
}

/// Adds the columns of a numeric array named `name`.
fn add_numeric(name: &str, var: &MatVariable, out: &mut Vec<RawColumn>) {
    match numbers(var) {
        Err(reason) => out.push((name.to_owned(), Err((None, reason)))),
        Ok((dim, values)) => {
            let big = dim.iter().filter(|&&n| n > 1).count();
            if dim.len() > 2 {
                let shape = dim
                    .iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join("x");
                out.push((
                    name.to_owned(),
                    Err((None, format!("is a {shape} array, not a vector or matrix"))),
                ));
            } else if big <= 1 {
                out.push((name.to_owned(), Ok(values)));
            } else {
                let rows = dim[0];
                for (j, column) in values.chunks(rows).enumerate() {
                    out.push((format!("{name}(:,{})", j + 1), Ok(column.to_vec())));
                }
            }
        }
    }
}

/// The columns `name`, `name(:,j)` again as `alias`, `alias(:,j)`.
fn alias(out: &mut Vec<RawColumn>, name: &str, alias: &str) {
    let renamed: Vec<RawColumn> = out
        .iter()
        .filter_map(|(n, v)| {
            let rest = n.strip_prefix(name)?;
            (rest.is_empty() || rest.starts_with("(:,"))
                .then(|| (format!("{alias}{rest}"), v.clone()))
        })
        .collect();
    out.extend(renamed);
}

fn flatten(name: &str, var: &MatVariable, out: &mut Vec<RawColumn>) {
    match var {
        MatVariable::Compressed(c) => flatten(name, &c.value, out),
        MatVariable::NumericArray(_) => add_numeric(name, var, out),
        MatVariable::Structure(s) => {
            let fields = s.fieldnames();
            for f in &fields {
                if let Some(v) = s.get(f) {
                    flatten(&format!("{name}.{f}"), v, out);
                }
            }
            let has = |f: &str| fields.iter().any(|g| g == f);
            if has("data") && has("colheaders") {
                named_columns(name, s.get("colheaders"), out);
            }
            if has("signals") && has("time") {
                simulink(name, s.get("signals"), out);
            }
        }
        MatVariable::StructureArray(a) => {
            for (i, element) in a.value.iter().enumerate() {
                let n = if i == 0 {
                    name.to_owned()
                } else {
                    format!("{name}({})", i + 1)
                };
                flatten(&n, element, out);
            }
        }
        _ => out.push((
            name.to_owned(),
            Err((
                None,
                "is not numeric data (a cell array, sparse matrix or object)".to_owned(),
            )),
        )),
    }
}

/// `data` with its `colheaders`: the columns of `name.data` (already
/// flattened) again by their headers.
fn named_columns(name: &str, headers: Option<&MatVariable>, out: &mut Vec<RawColumn>) {
    let Some(MatVariable::CellArray(cells)) = headers.map(uncompressed) else {
        return;
    };
    let single = cells.value.len() == 1;
    for (j, header) in cells.value.iter().map(text).enumerate() {
        let Some(header) = header.map(|h| h.trim().to_owned()) else {
            continue;
        };
        let wanted = if single {
            format!("{name}.data")
        } else {
            format!("{name}.data(:,{})", j + 1)
        };
        if let Some((_, v)) = out.iter().find(|(n, _)| *n == wanted) {
            let v = v.clone();
            out.push((header, v));
        }
    }
}

fn uncompressed(var: &MatVariable) -> &MatVariable {
    match var {
        MatVariable::Compressed(c) => uncompressed(&c.value),
        v => v,
    }
}

/// Simulink's `signals` of the struct `name` (already flattened): each
/// again by its label, and the only one by the struct's name.
fn simulink(name: &str, signals: Option<&MatVariable>, out: &mut Vec<RawColumn>) {
    let elements: Vec<&MatVariable> = match signals.map(uncompressed) {
        Some(s @ MatVariable::Structure(_)) => vec![s],
        Some(MatVariable::StructureArray(a)) => a.value.iter().map(uncompressed).collect(),
        _ => return,
    };
    for (i, element) in elements.iter().enumerate() {
        let MatVariable::Structure(s) = element else {
            continue;
        };
        let path = if i == 0 {
            format!("{name}.signals.values")
        } else {
            format!("{name}.signals({}).values", i + 1)
        };
        let label = s.get("label").and_then(text).map(|l| l.trim().to_owned());
        if let Some(label) = label.filter(|l| !l.is_empty()) {
            alias(out, &path, &label);
            // Its time under the label too, so that the signal found by
            // its label finds its struct's time.
            let time = format!("{name}.time");
            if let Some((_, v)) = out.iter().find(|(n, _)| *n == time) {
                let v = v.clone();
                out.push((format!("{label}.time"), v));
            }
        }
        if elements.len() == 1 {
            alias(out, &path, name);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_damaged_file_is_an_error_never_a_panic() {
        // The fixture inflated, then one byte at a time set to each of a
        // few values past the header: every outcome is columns or an error.
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/data/compare/simulink_array.mat"
        );
        let bytes = std::fs::read(path).expect("the fixture is committed");
        let plain = inflated(&bytes, true).expect("the fixture inflates");
        assert!(columns(&plain, "plain.mat").is_ok());
        let (mut errors, mut read) = (0, 0);
        for at in (HEADER..plain.len().min(HEADER + 600)).step_by(7) {
            for value in [0u8, 0x7f, 0xd7, 0xff] {
                let mut damaged = plain.clone();
                damaged[at] = value;
                match columns(&damaged, "damaged.mat") {
                    Ok(_) => read += 1,
                    Err(e) => {
                        assert_eq!(e.to_string().lines().count(), 1, "{e}");
                        errors += 1;
                    }
                }
            }
        }
        // Damage in the tags, dimensions and names is found.
        assert!(errors > 0 && read > 0, "{errors} errors, {read} read");
    }
}
