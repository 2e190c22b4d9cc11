//! How a sweep plot names its columns and in which units it draws them.
//!
//! Contract: a column is named by its `--label` text if given, else by its
//! entry in the table of symbols (`src/symbol.rs`), else by its name with
//! spaces for underscores; its SI unit comes from the table of symbols,
//! the indicator table or the documented sweep columns ([`si_unit`]). A
//! display unit ([`UNITS`]) is accepted for a column whose SI unit it
//! shares, or for an undocumented column (taken to be in SI), never for a
//! ratio; the factor from SI to drawn values is the unit's `per_si`.
//! Numbers in names have at most four significant digits.

use super::super::{PlotError, superscript};
use crate::indicator::Indicator;
use crate::symbol::symbol;

/// The SI unit of a documented column (`1` for a ratio): from the table
/// of symbols, the indicator table, or the other columns of a sweep
/// output; `None` for a column the project does not document.
pub(super) fn si_unit(column: &str) -> Option<&'static str> {
    if let Some(s) = symbol(column) {
        return Some(s.unit);
    }
    if let Ok(indicator) = column.parse::<Indicator>() {
        return Some(indicator.unit());
    }
    Some(match column {
        "error_v_inf" | "last_v_p" => "m/s",
        "wall_time_s" => "s",
        "apparent_power" => "VA",
        "f0" => "Hz",
        _ => return None,
    })
}

/// A unit a sweep axis can be shown in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// Its name as shown (`ms`).
    pub name: &'static str,
    /// The SI unit of the same dimension (`s`).
    pub si: &'static str,
    /// How many of it make one SI unit (1000 for ms).
    pub per_si: f64,
}

const fn u(name: &'static str, si: &'static str, per_si: f64) -> Unit {
    Unit { name, si, per_si }
}

/// The display units of `--x-unit` and `--y-unit`, SI first in each
/// dimension.
pub const UNITS: &[Unit] = &[
    u("s", "s", 1.0),
    u("ms", "s", 1e3),
    u("µs", "s", 1e6),
    u("ns", "s", 1e9),
    u("m", "m", 1.0),
    u("mm", "m", 1e3),
    u("µm", "m", 1e6),
    u("nm", "m", 1e9),
    u("m/s", "m/s", 1.0),
    u("mm/s", "m/s", 1e3),
    u("µm/s", "m/s", 1e6),
    u("m/s²", "m/s²", 1.0),
    u("mm/s²", "m/s²", 1e3),
    u("km/s²", "m/s²", 1e-3),
    u("N", "N", 1.0),
    u("mN", "N", 1e3),
    u("µN", "N", 1e6),
    u("kN", "N", 1e-3),
    u("W", "W", 1.0),
    u("mW", "W", 1e3),
    u("µW", "W", 1e6),
    u("kW", "W", 1e-3),
    u("VA", "VA", 1.0),
    u("mVA", "VA", 1e3),
    u("J", "J", 1.0),
    u("mJ", "J", 1e3),
    u("µJ", "J", 1e6),
    u("nJ", "J", 1e9),
    u("Hz", "Hz", 1.0),
    u("kHz", "Hz", 1e-3),
    u("MHz", "Hz", 1e-6),
    u("kg", "kg", 1.0),
    u("g", "kg", 1e3),
    u("mg", "kg", 1e6),
];

/// The unit named `text`: `u` (`um`, `us`) and the Greek mu stand for
/// the micro sign, `^2` for `²`.
fn unit_named(text: &str) -> Option<&'static Unit> {
    let mut name = text.trim().replace('μ', "µ").replace("^2", "²");
    if let Some(rest) = name.strip_prefix('u') {
        name = format!("µ{rest}");
    }
    UNITS.iter().find(|u| u.name == name)
}

/// How an axis of `columns` (sharing a unit) is shown with the unit
/// option `flag` `wanted`: the factor from SI to drawn values, and the
/// unit the label shows (none for a ratio or an undocumented column).
pub(super) fn display_unit(
    flag: &str,
    wanted: Option<&str>,
    columns: &[String],
) -> Result<(f64, Option<&'static str>), PlotError> {
    let si = columns.first().and_then(|c| si_unit(c));
    let Some(wanted) = wanted else {
        return Ok((1.0, si.filter(|u| *u != "1")));
    };
    let Some(unit) = unit_named(wanted) else {
        let names: Vec<&str> = UNITS.iter().map(|u| u.name).collect();
        return Err(PlotError::Argument(format!(
            "{flag} {wanted}: not a unit; units are {} (um, us for µm, µs)",
            names.join(", ")
        )));
    };
    let column = columns.join(",");
    match si {
        Some("1") => Err(PlotError::Argument(format!(
            "{flag} {wanted}: {column} is a ratio (no unit)"
        ))),
        Some(si) if si != unit.si => {
            let same: Vec<&str> = UNITS
                .iter()
                .filter(|u| u.si == si)
                .map(|u| u.name)
                .collect();
            Err(PlotError::Argument(if same.is_empty() {
                format!("{flag} {wanted}: {column} is in {si}, which has no other unit here")
            } else {
                format!(
                    "{flag} {wanted}: {column} is in {si}, not {}; use one of {}",
                    unit.si,
                    same.join(", ")
                )
            }))
        }
        // A documented column in this unit's SI unit, or a column the
        // project does not document, taken to be in SI as sweep outputs
        // are.
        _ => Ok((unit.per_si, Some(unit.name))),
    }
}

/// A column's name as words (another tool's column, not in the table of
/// symbols): underscores become spaces.
fn words(column: &str) -> String {
    column.replace('_', " ")
}

/// How columns are named in the figure: by `--label` text, else from the
/// table of symbols, else in words.
pub(super) struct Names<'a> {
    pub(super) labels: &'a [(String, String)],
}

impl Names<'_> {
    fn given(&self, column: &str) -> Option<&str> {
        self.labels
            .iter()
            .rev()
            .find(|(c, _)| c == column)
            .map(|(_, t)| t.as_str())
    }

    /// Description and symbol (`steady-state velocity $v_∞$`).
    pub(super) fn long(&self, column: &str) -> String {
        if let Some(t) = self.given(column) {
            return t.to_owned();
        }
        match symbol(column) {
            Some(s) if s.description.is_empty() => s.quantity.to_owned(),
            Some(s) => format!("{} {}", s.description, s.quantity),
            None => words(column),
        }
    }

    /// The symbol alone (`$v_∞$`).
    pub(super) fn short(&self, column: &str) -> String {
        if let Some(t) = self.given(column) {
            return t.to_owned();
        }
        symbol(column).map_or_else(|| words(column), |s| s.quantity.to_owned())
    }

    /// What a switch column switches (`sigma factors`).
    fn switch(&self, column: &str) -> String {
        if let Some(t) = self.given(column) {
            return t.to_owned();
        }
        match symbol(column) {
            Some(s) if !s.description.is_empty() => s.description.to_owned(),
            _ => self.short(column),
        }
    }

    /// The axis label of `columns` drawn in `unit`: description, symbol
    /// and unit for one column, the symbols for several.
    pub(super) fn axis(&self, columns: &[String], unit: Option<&str>) -> String {
        let text = match columns {
            [one] => self.long(one),
            _ => columns
                .iter()
                .map(|c| self.short(c))
                .collect::<Vec<_>>()
                .join(", "),
        };
        match unit {
            Some(u) => format!("{text} ({u})"),
            None => text,
        }
    }

    /// How a series or facet of `column` = `value` is named: "with" or
    /// "without" for a switch, the symbol, the value (as a number where
    /// it is one) and the column's unit otherwise.
    pub(super) fn value(&self, column: &str, value: &str) -> String {
        match value {
            "true" => format!("with {}", self.switch(column)),
            "false" => format!("without {}", self.switch(column)),
            _ => match value.parse::<f64>() {
                Ok(v) if v.is_finite() => {
                    let unit = si_unit(column)
                        .filter(|u| *u != "1")
                        .map_or(String::new(), |u| format!(" {u}"));
                    format!("{} = {}{unit}", self.short(column), number(v))
                }
                _ => format!("{} = {}", self.short(column), words(value)),
            },
        }
    }
}

/// A number for a legend or title: at most four significant digits,
/// plain from 0.001 to 99 999, with a power of ten otherwise.
pub(super) fn number(v: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    let a = v.abs();
    let sign = if v < 0.0 { "−" } else { "" };
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            s
        }
    };
    let exp = a.log10().floor() as i32;
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - exp).max(0) as usize;
        return format!("{sign}{}", trim(format!("{a:.decimals$}")));
    }
    let mantissa = trim(format!("{:.3}", a / 10f64.powi(exp)));
    if mantissa == "1" {
        format!("{sign}10{}", superscript(exp))
    } else {
        format!("{sign}{mantissa}×10{}", superscript(exp))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_scale_from_si_and_ascii_u_stands_for_micro() {
        assert_eq!(unit_named("ms").map(|u| u.per_si), Some(1e3));
        assert_eq!(unit_named("um").map(|u| u.name), Some("µm"));
        assert_eq!(unit_named("us").map(|u| u.name), Some("µs"));
        assert_eq!(unit_named("μm/s").map(|u| u.name), Some("µm/s"));
        assert_eq!(unit_named("m/s^2").map(|u| u.name), Some("m/s²"));
        assert_eq!(unit_named("furlong"), None);
        // Every unit's SI unit is itself a unit of the table, at factor 1.
        for unit in UNITS {
            assert_eq!(
                unit_named(unit.si).map(|u| u.per_si),
                Some(1.0),
                "{}",
                unit.name
            );
        }
    }

    #[test]
    fn a_unit_must_measure_what_the_column_measures() {
        let y = ["startup_time".to_owned()];
        assert_eq!(
            display_unit("--y-unit", Some("ms"), &y).unwrap(),
            (1e3, Some("ms"))
        );
        assert_eq!(
            display_unit("--y-unit", None, &y).unwrap(),
            (1.0, Some("s"))
        );
        let wrong = display_unit("--y-unit", Some("mm"), &y)
            .unwrap_err()
            .to_string();
        assert!(
            wrong.contains("--y-unit mm") && wrong.contains("ms"),
            "{wrong}"
        );
        let ratio = ["smoothness".to_owned()];
        assert!(display_unit("--y-unit", Some("ms"), &ratio).is_err());
        assert_eq!(display_unit("--y-unit", None, &ratio).unwrap(), (1.0, None));
        // A column the project does not document is taken to be in SI.
        let other = ["their_time".to_owned()];
        assert_eq!(
            display_unit("--y-unit", Some("us"), &other).unwrap(),
            (1e6, Some("µs"))
        );
    }

    #[test]
    fn numbers_in_legends_have_at_most_four_significant_digits() {
        assert_eq!(number(3.0), "3");
        assert_eq!(number(0.428_571_428_571), "0.4286");
        assert_eq!(number(0.1 + 0.2), "0.3");
        assert_eq!(number(-12.5), "−12.5");
        assert_eq!(number(2.5e-5), "2.5×10⁻⁵");
        assert_eq!(number(1e6), "10⁶");
    }

    #[test]
    fn switches_read_with_and_without_and_labels_replace_symbols() {
        let labels = vec![("level".to_owned(), "$L$".to_owned())];
        let names = Names { labels: &labels };
        assert_eq!(names.value("sigma", "false"), "without sigma factors");
        assert_eq!(names.value("level", "6"), "$L$ = 6");
        assert_eq!(names.value("contact_force", "2.50"), "$F_c$ = 2.5 N");
        assert_eq!(
            names.axis(&["v_inf".to_owned()], Some("mm/s")),
            "steady-state velocity $v_∞$ (mm/s)"
        );
        assert_eq!(
            names.axis(
                &["startup_time".to_owned(), "period".to_owned()],
                Some("ms")
            ),
            "$Tp_{0.99}$, $T$ (ms)"
        );
    }
}
