//! Reading a user's result into arrays ([`UserData`]): CSV files (columns
//! by name in a header row, `csv_file`) and MATLAB Level 5 MAT-files
//! (variables, struct fields and Simulink's layouts flattened into named
//! columns, `mat_file`).
//!
//! The quantities and the names they are found under (case-insensitive,
//! the first name present wins; `--var-*` options replace the list):
//!
//! | quantity | names | unit |
//! | --- | --- | --- |
//! | time | `t`, `time`, `tout`, else the `time` of the Simulink struct of a found signal | s (or `--time-unit`) |
//! | slider position | `x_S`, `x` | m (or `--length-unit`) |
//! | slider velocity | `v_S`, `v` | length unit / time unit |
//! | rod position | `x_R` | length unit |
//! | period index | `p` | 1 |
//! | mean velocity per period | `v_p` | length unit / time unit |
//!
//! A CSV column may end early (empty cells below its last value), so that
//! one file holds the samples and the shorter (or longer) per-period
//! series, as two variables of different lengths do in a MAT-file. Lines
//! starting with `#` are comments.
//!
//! Contract: every value returned is finite and in SI units; times are
//! `>= 0` and strictly increasing; sample columns have as many values as
//! the time column; period indices are increasing integers `>= 1`.
//! Anything else is a [`CompareError::Data`] naming the file, the column
//! and the row (CSV: the data row from 1, and the line in the file; MAT:
//! the element from 1).

use super::CompareError;
use std::path::Path;

/// A column as read: its name and its values, or why it cannot be used.
pub(crate) type RawColumn = (String, Result<Vec<f64>, (Option<String>, String)>);

/// Unit of the time values in a user's file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum TimeUnit {
    /// Seconds.
    #[default]
    S,
    /// Milliseconds.
    Ms,
    /// Microseconds.
    Us,
}

impl TimeUnit {
    /// Seconds per unit.
    pub fn factor(self) -> f64 {
        match self {
            TimeUnit::S => 1.0,
            TimeUnit::Ms => 1e-3,
            TimeUnit::Us => 1e-6,
        }
    }
}

/// Unit of the lengths in a user's file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum LengthUnit {
    /// Metres.
    #[default]
    M,
    /// Millimetres.
    Mm,
    /// Micrometres.
    Um,
}

impl LengthUnit {
    /// Metres per unit.
    pub fn factor(self) -> f64 {
        match self {
            LengthUnit::M => 1.0,
            LengthUnit::Mm => 1e-3,
            LengthUnit::Um => 1e-6,
        }
    }
}

/// The quantities a user's file may hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Quantity {
    /// Time `t`.
    Time,
    /// Slider position `x_S`.
    SliderPosition,
    /// Slider velocity `v_S`.
    SliderVelocity,
    /// Rod position `x_R`.
    RodPosition,
    /// Period index `p`.
    Period,
    /// Mean velocity `v_p` of period `p`.
    MeanVelocity,
}

impl Quantity {
    /// All quantities, in reading order.
    pub(crate) const ALL: [Quantity; 6] = [
        Quantity::Time,
        Quantity::SliderPosition,
        Quantity::SliderVelocity,
        Quantity::RodPosition,
        Quantity::Period,
        Quantity::MeanVelocity,
    ];

    /// The names the quantity is looked up under by default.
    pub(crate) fn default_names(self) -> &'static [&'static str] {
        match self {
            Quantity::Time => &["t", "time", "tout"],
            Quantity::SliderPosition => &["x_S", "x"],
            Quantity::SliderVelocity => &["v_S", "v"],
            Quantity::RodPosition => &["x_R"],
            Quantity::Period => &["p"],
            Quantity::MeanVelocity => &["v_p"],
        }
    }

    /// SI value of one unit of the file's value.
    fn factor(self, time: TimeUnit, length: LengthUnit) -> f64 {
        match self {
            Quantity::Time => time.factor(),
            Quantity::SliderPosition | Quantity::RodPosition => length.factor(),
            Quantity::SliderVelocity | Quantity::MeanVelocity => length.factor() / time.factor(),
            Quantity::Period => 1.0,
        }
    }
}

/// How to read a file: units and, per quantity, a name that replaces the
/// default list.
#[derive(Debug, Clone, Default)]
pub struct ReadOptions {
    /// Unit of times.
    pub time_unit: TimeUnit,
    /// Unit of lengths.
    pub length_unit: LengthUnit,
    /// Name overrides in the order of [`Quantity::ALL`].
    pub names: [Option<String>; 6],
}

impl ReadOptions {
    fn names(&self, q: Quantity) -> Vec<String> {
        let i = Quantity::ALL.iter().position(|x| *x == q).unwrap_or(0);
        match &self.names[i] {
            Some(name) => vec![name.clone()],
            None => q.default_names().iter().map(|s| (*s).to_owned()).collect(),
        }
    }
}

/// One column of a user's data, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The name in the file.
    pub name: String,
    /// The values.
    pub values: Vec<f64>,
}

/// A user's result as arrays in SI units: what the readers of CSV and
/// MAT-files return, and what the analysis ([`super::compare_data`])
/// takes, whatever the data came from. [`UserData::validate`] states the
/// contract.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UserData {
    /// Sample times (s).
    pub t: Option<Column>,
    /// Slider positions at the sample times (m).
    pub x_s: Option<Column>,
    /// Slider velocities (m/s).
    pub v_s: Option<Column>,
    /// Rod positions (m).
    pub x_r: Option<Column>,
    /// Period indices of `v_p`.
    pub p: Option<Column>,
    /// Mean velocities per period (m/s).
    pub v_p: Option<Column>,
}

impl Column {
    /// A column named `name` (for messages) holding `values`.
    pub fn new(name: &str, values: Vec<f64>) -> Self {
        Column {
            name: name.to_owned(),
            values,
        }
    }
}

impl UserData {
    /// Checks the contract of the module doc (finite values, times `>= 0`
    /// and increasing, sample columns as long as the time column, period
    /// indices increasing integers `>= 1`, something to compare); errors
    /// name `file`, the column and the element.
    pub fn validate(&self, file: &str) -> Result<(), CompareError> {
        let all = [&self.t, &self.x_s, &self.v_s, &self.x_r, &self.p, &self.v_p];
        for c in all.into_iter().flatten() {
            if let Some(i) = c.values.iter().position(|v| !v.is_finite()) {
                return Err(CompareError::data(
                    file,
                    Some(&c.name),
                    Some(Origin::Mat.row(i, &[])),
                    format!("{} is not a finite number", c.values[i]),
                ));
            }
        }
        validate(self, file, &Origin::Mat, &[], &[])
    }

    /// What the data hold, for messages: `t (N values), x_S (N values)...`
    /// under the names they were found by.
    pub(crate) fn found(&self) -> String {
        let all = [
            ("t", &self.t),
            ("x_S", &self.x_s),
            ("v_S", &self.v_s),
            ("x_R", &self.x_r),
            ("p", &self.p),
            ("v_p", &self.v_p),
        ];
        let held: Vec<String> = all
            .iter()
            .filter_map(|(q, c)| {
                let c = c.as_ref()?;
                Some(if c.name == *q {
                    format!("{q} ({} values)", c.values.len())
                } else {
                    format!("{q} = {} ({} values)", c.name, c.values.len())
                })
            })
            .collect();
        if held.is_empty() {
            "nothing".to_owned()
        } else {
            held.join(", ")
        }
    }

    /// The fixed step of the time column: the median sample spacing (s).
    pub(crate) fn step(&self) -> Option<f64> {
        let t = &self.t.as_ref()?.values;
        if t.len() < 2 {
            return None;
        }
        let mut d: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
        let mid = d.len() / 2;
        d.select_nth_unstable_by(mid, f64::total_cmp);
        Some(d[mid])
    }
}

/// Where a value sits, for messages.
enum Origin {
    Csv,
    Mat,
}

impl Origin {
    fn row(&self, i: usize, header_lines: &[usize]) -> String {
        match self {
            Origin::Csv => format!(
                "row {} (line {})",
                i + 1,
                header_lines.get(i).copied().unwrap_or(0)
            ),
            Origin::Mat => format!("element {}", i + 1),
        }
    }
}

#[cfg(feature = "files")]
/// Reads a CSV or MAT-file (by extension: `.mat` is a MAT-file, anything
/// else CSV).
pub(crate) fn read(path: &Path, options: &ReadOptions) -> Result<UserData, CompareError> {
    let is_mat = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mat"));
    let file = path.display().to_string();
    let (columns, lines, origin) = if is_mat {
        (read_mat(path, &file)?, Vec::new(), Origin::Mat)
    } else {
        let wanted: Vec<String> = Quantity::ALL
            .iter()
            .flat_map(|q| options.names(*q))
            .collect();
        let (c, l) = super::csv_file::columns(path, &file, &wanted)?;
        (c, l, Origin::Csv)
    };
    let mut data = UserData::default();
    for q in Quantity::ALL {
        let names = options.names(q);
        let hit = names.iter().find_map(|n| {
            columns
                .iter()
                .find(|(name, _)| name.eq_ignore_ascii_case(n))
        });
        let Some((name, raw)) = hit else {
            if matches!(q, Quantity::Time) || options.names[index(q)].is_none() {
                continue;
            }
            return Err(CompareError::data(
                &file,
                names.first().map(String::as_str),
                None,
                format!(
                    "no such {}; found {}",
                    if is_mat { "variable" } else { "column" },
                    found(&columns)
                ),
            ));
        };
        let raw = raw.as_ref().map_err(|(row, reason)| {
            CompareError::data(&file, Some(name), row.clone(), reason.clone())
        })?;
        let factor = q.factor(options.time_unit, options.length_unit);
        let mut values = Vec::with_capacity(raw.len());
        for (i, v) in raw.iter().enumerate() {
            if !v.is_finite() {
                return Err(CompareError::data(
                    &file,
                    Some(name),
                    Some(origin.row(i, &lines)),
                    format!("{v} is not a finite number"),
                ));
            }
            values.push(v * factor);
        }
        let column = Some(Column {
            name: name.clone(),
            values,
        });
        match q {
            Quantity::Time => data.t = column,
            Quantity::SliderPosition => data.x_s = column,
            Quantity::SliderVelocity => data.v_s = column,
            Quantity::RodPosition => data.x_r = column,
            Quantity::Period => data.p = column,
            Quantity::MeanVelocity => data.v_p = column,
        }
    }
    if options.names[0].is_some() && data.t.is_none() {
        return Err(CompareError::data(
            &file,
            options.names[0].as_deref(),
            None,
            format!("no such column or variable; found {}", found(&columns)),
        ));
    }
    if data.t.is_none() {
        data.t = own_time(&data, &columns, options.time_unit.factor(), &file)?;
    }
    validate(&data, &file, &origin, &lines, &columns)?;
    Ok(data)
}

#[cfg(feature = "files")]
/// The time of a Simulink struct whose signals were found: `s.time` for
/// the columns `s`, `s(:,j)`, `s.signals...` (the first such struct with a
/// non-empty time).
fn own_time(
    data: &UserData,
    columns: &[RawColumn],
    factor: f64,
    file: &str,
) -> Result<Option<Column>, CompareError> {
    let used = [&data.x_s, &data.v_s, &data.x_r];
    for c in used.into_iter().flatten() {
        let prefix = c.name.split(['.', '(']).next().unwrap_or("");
        let name = format!("{prefix}.time");
        let Some((name, raw)) = columns.iter().find(|(n, v)| {
            n.eq_ignore_ascii_case(&name) && v.as_ref().is_ok_and(|v| !v.is_empty())
        }) else {
            continue;
        };
        let raw = raw
            .as_ref()
            .map_err(|(row, r)| CompareError::data(file, Some(name), row.clone(), r.clone()))?;
        let mut values = Vec::with_capacity(raw.len());
        for (i, v) in raw.iter().enumerate() {
            if !v.is_finite() {
                return Err(CompareError::data(
                    file,
                    Some(name),
                    Some(format!("element {}", i + 1)),
                    format!("{v} is not a finite number"),
                ));
            }
            values.push(v * factor);
        }
        return Ok(Some(Column {
            name: name.clone(),
            values,
        }));
    }
    Ok(None)
}

#[cfg(feature = "files")]
/// Reads only sample times (s): a CSV or MAT-file with a time column or
/// variable (`t`, `time`, `tout`), or a text file with one time per line.
pub(crate) fn read_times(path: &Path, options: &ReadOptions) -> Result<Vec<f64>, CompareError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path);
    let headerless = text.as_ref().is_ok_and(|t| {
        t.lines()
            .find(|l| !l.trim().is_empty() && !l.starts_with('#'))
            .is_some_and(|l| l.trim().parse::<f64>().is_ok())
    });
    let mut values = Vec::new();
    let mut numbers = Vec::new();
    if headerless {
        for (i, line) in text.unwrap_or_default().lines().enumerate() {
            let cell = line.trim();
            if cell.is_empty() || cell.starts_with('#') {
                continue;
            }
            let v: f64 = cell
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| {
                    CompareError::data(
                        &file,
                        Some("t"),
                        Some(format!("line {}", i + 1)),
                        format!("`{cell}` is not a finite number"),
                    )
                })?;
            values.push(v * options.time_unit.factor());
            numbers.push(i + 1);
        }
        let data = UserData {
            t: Some(Column {
                name: "t".into(),
                values,
            }),
            v_p: Some(Column {
                name: "t".into(),
                values: Vec::new(),
            }),
            ..Default::default()
        };
        validate(&data, &file, &Origin::Csv, &numbers, &[])?;
        return Ok(data.t.map(|c| c.values).unwrap_or_default());
    }
    let (columns, lines, origin) = if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mat"))
    {
        (read_mat(path, &file)?, Vec::new(), Origin::Mat)
    } else {
        let wanted: Vec<String> = Quantity::Time
            .default_names()
            .iter()
            .map(|n| (*n).to_owned())
            .collect();
        let (c, l) = super::csv_file::columns(path, &file, &wanted)?;
        (c, l, Origin::Csv)
    };
    let Some((name, raw)) = Quantity::Time
        .default_names()
        .iter()
        .find_map(|n| columns.iter().find(|(c, _)| c.eq_ignore_ascii_case(n)))
    else {
        return Err(CompareError::data(
            &file,
            Some("t"),
            None,
            format!("no such column or variable; found {}", found(&columns)),
        ));
    };
    let raw = raw
        .as_ref()
        .map_err(|(row, r)| CompareError::data(&file, Some(name), row.clone(), r.clone()))?;
    for (i, v) in raw.iter().enumerate() {
        if !v.is_finite() {
            return Err(CompareError::data(
                &file,
                Some(name),
                Some(origin.row(i, &lines)),
                format!("{v} is not a finite number"),
            ));
        }
        values.push(v * options.time_unit.factor());
    }
    let data = UserData {
        t: Some(Column {
            name: name.clone(),
            values,
        }),
        v_p: Some(Column {
            name: name.clone(),
            values: Vec::new(),
        }),
        ..Default::default()
    };
    validate(&data, &file, &origin, &lines, &columns)?;
    Ok(data.t.map(|c| c.values).unwrap_or_default())
}

fn index(q: Quantity) -> usize {
    Quantity::ALL.iter().position(|x| *x == q).unwrap_or(0)
}

/// `column` has as many values as the `what` column `reference`.
fn same_length(
    file: &str,
    column: &Column,
    reference: &Column,
    what: &str,
) -> Result<(), CompareError> {
    if column.values.len() == reference.values.len() {
        return Ok(());
    }
    Err(CompareError::data(
        file,
        Some(&column.name),
        None,
        format!(
            "{} values, but the {what} column {} has {}",
            column.values.len(),
            reference.name,
            reference.values.len()
        ),
    ))
}

fn validate(
    data: &UserData,
    file: &str,
    origin: &Origin,
    lines: &[usize],
    columns: &[RawColumn],
) -> Result<(), CompareError> {
    let samples = [&data.x_s, &data.v_s, &data.x_r];
    let has_samples = samples.iter().any(|c| c.is_some());
    if data.v_p.is_none() && !has_samples {
        return Err(CompareError::data(
            file,
            None,
            None,
            format!(
                "nothing to compare: expected t with x_S (or x), v_S (or v) or x_R, or the \
                 per-period v_p; found {}; name them with --var-t, --var-x-s, --var-v-s, \
                 --var-x-r, --var-p, --var-v-p",
                found(columns)
            ),
        ));
    }
    if let Some(t) = &data.t {
        for (i, w) in t.values.windows(2).enumerate() {
            if w[1] <= w[0] {
                let what = if w[1] == w[0] {
                    format!("time {} s repeats the previous one", w[1])
                } else {
                    format!("time {} s is before the previous {} s", w[1], w[0])
                };
                return Err(CompareError::data(
                    file,
                    Some(&t.name),
                    Some(origin.row(i + 1, lines)),
                    format!("{what}: times must increase"),
                ));
            }
        }
        if let Some(&t0) = t.values.first()
            && t0 < 0.0
        {
            return Err(CompareError::data(
                file,
                Some(&t.name),
                Some(origin.row(0, lines)),
                format!("time {t0} s is before the simulated span, which starts at t = 0"),
            ));
        }
        for c in samples.into_iter().flatten() {
            same_length(file, c, t, "time")?;
        }
    } else if let Some(c) = samples.into_iter().flatten().next() {
        return Err(CompareError::data(
            file,
            Some(&c.name),
            None,
            format!(
                "samples need a time column (t, time, tout or a Simulink struct's time); found \
                 {}; name it with --var-t",
                found(columns)
            ),
        ));
    }
    if let (Some(p), Some(v)) = (&data.p, &data.v_p) {
        same_length(file, v, p, "period")?;
        let mut last = 0.0;
        for (i, &q) in p.values.iter().enumerate() {
            if q.fract() != 0.0 || q < 1.0 || q <= last {
                return Err(CompareError::data(
                    file,
                    Some(&p.name),
                    Some(origin.row(i, lines)),
                    format!("period index {q} is not an integer >= 1 above the previous one"),
                ));
            }
            last = q;
        }
    }
    Ok(())
}

#[cfg(feature = "files")]
/// The flattened variables of a MAT-file ([`super::mat_file`]).
fn read_mat(path: &Path, file: &str) -> Result<Vec<RawColumn>, CompareError> {
    let bytes = std::fs::read(path).map_err(|e| CompareError::io(file, e.to_string()))?;
    super::mat_file::columns(&bytes, file)
}

/// The names found in a file, for messages.
pub(crate) fn found(columns: &[RawColumn]) -> String {
    if columns.is_empty() {
        return "nothing".to_owned();
    }
    let names: Vec<&str> = columns.iter().map(|(n, _)| n.as_str()).collect();
    let shown = names.len().min(24);
    let mut text = names[..shown].join(", ");
    if names.len() > shown {
        text.push_str(&format!(" and {} more", names.len() - shown));
    }
    text
}
