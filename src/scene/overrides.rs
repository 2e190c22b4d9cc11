//! Overrides of single scene fields, `PATH=VALUE` (`--set` on the command
//! line): one grammar for every front end.
//!
//! **Path.** Keys joined by dots, each optionally followed by a 0-based
//! index into an array: `motor.slider_mass`, `signal.harmonics`,
//! `signal.amplitudes[1]` (the second entry, `d_2`, as error messages and
//! sensitivities name it). Keys are the scene file's (docs/interface.md
//! section 2): letters, digits, `_` and `-`.
//!
//! **Value.** A TOML value (`5e-3`, `3`, `true`, `"text"`, `[1e-6, 2e-6]`,
//! `nan`); a bare word that is not one (`fourier`) is taken as a string.
//!
//! **Contract.** The overrides are applied in order to the scene's TOML
//! table before it is read, so an overridden field is checked exactly as if
//! the file held it, with the same one-line messages. A table the scene
//! leaves to its default (`[motor]`, `[signal]`, `[run]`, `[outputs]`) is
//! written out with that default first, so `motor.mu_dynamic=0` changes
//! one field of the default motor; other missing tables are created empty
//! (`actuator.mass` on a scene without `[actuator]`); an index must
//! lie within its array; a key cannot descend into a value that is not a
//! table. The drive of a signal is given by exactly one of `kappa`,
//! `sqrt_kappa`, `frequency` and `f_max`: setting one removes the others
//! from the `[signal]` table, so an override replaces whichever the scene
//! gave.

pub use crate::error::OverrideError;
use std::fmt;
use std::str::FromStr;
use toml::{Table, Value};

/// The fields of `[signal]` of which a scene gives exactly one: setting one
/// replaces the others.
const DRIVE: [&str; 4] = ["kappa", "sqrt_kappa", "frequency", "f_max"];

/// One step of a path: a key, and an index into the array it holds.
#[derive(Debug, Clone, PartialEq)]
struct Step {
    key: String,
    index: Option<usize>,
}

/// One override `PATH=VALUE`, parsed.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    path: Vec<Step>,
    value: Value,
    /// As given, for messages.
    text: String,
}

impl OverrideError {
    fn new(given: &str, reason: impl Into<String>) -> Self {
        Self {
            given: given.escape_debug().to_string(),
            reason: reason.into(),
        }
    }
}

impl fmt::Display for Override {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.text)
    }
}

impl Override {
    /// The first key of the path: the scene table it sets a field of.
    pub(super) fn table(&self) -> &str {
        &self.path[0].key
    }

    /// The dotted path, as the scene's messages name fields.
    pub fn path(&self) -> String {
        self.path
            .iter()
            .map(|s| match s.index {
                Some(i) => format!("{}[{i}]", s.key),
                None => s.key.clone(),
            })
            .collect::<Vec<_>>()
            .join(".")
    }
}

fn parse_step(given: &str, step: &str) -> Result<Step, OverrideError> {
    let (key, index) = match step.split_once('[') {
        Some((key, rest)) => {
            let digits = rest.strip_suffix(']').ok_or_else(|| {
                OverrideError::new(given, format!("`{step}`: an index is written `key[0]`"))
            })?;
            let index = digits.parse::<usize>().map_err(|_| {
                OverrideError::new(
                    given,
                    format!("`{step}`: the index must be a whole number from 0, not `{digits}`"),
                )
            })?;
            (key, Some(index))
        }
        None => (step, None),
    };
    let valid = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
    if key.is_empty() || !key.chars().all(valid) {
        return Err(OverrideError::new(
            given,
            format!(
                "`{}` is not a field name (letters, digits, `_`, `-`; fields joined by `.`)",
                key.escape_debug()
            ),
        ));
    }
    Ok(Step {
        key: key.to_owned(),
        index,
    })
}

impl FromStr for Override {
    type Err = OverrideError;

    fn from_str(given: &str) -> Result<Self, Self::Err> {
        let (path, value) = given.split_once('=').ok_or_else(|| {
            OverrideError::new(given, "expected PATH=VALUE, e.g. motor.slider_mass=5e-3")
        })?;
        let path = path.trim();
        if path.is_empty() {
            return Err(OverrideError::new(given, "the path before `=` is empty"));
        }
        let steps = path
            .split('.')
            .map(|s| parse_step(given, s.trim()))
            .collect::<Result<Vec<_>, _>>()?;
        let value = value.trim();
        if value.is_empty() {
            return Err(OverrideError::new(given, "the value after `=` is empty"));
        }
        Ok(Override {
            path: steps,
            value: parse_value(value),
            text: given.escape_debug().to_string(),
        })
    }
}

/// A TOML value, or the text itself as a string.
fn parse_value(text: &str) -> Value {
    format!("v = {text}")
        .parse::<Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| Value::String(text.to_owned()))
}

/// What a value is, for messages.
fn kind(value: &Value) -> &'static str {
    match value {
        Value::String(_) => "a string",
        Value::Integer(_) | Value::Float(_) => "a number",
        Value::Boolean(_) => "a boolean",
        Value::Datetime(_) => "a date",
        Value::Array(_) => "an array",
        Value::Table(_) => "a table",
    }
}

/// Applies `overrides`, in order, to a scene's TOML table (module docs).
pub(super) fn apply(table: &mut Table, overrides: &[Override]) -> Result<(), OverrideError> {
    for o in overrides {
        apply_one(table, o)?;
    }
    Ok(())
}

fn apply_one(table: &mut Table, o: &Override) -> Result<(), OverrideError> {
    let err = |reason: String| OverrideError {
        given: o.text.clone(),
        reason,
    };
    if let [signal, field] = o.path.as_slice()
        && signal.key == "signal"
        && signal.index.is_none()
        && field.index.is_none()
        && DRIVE.contains(&field.key.as_str())
        && let Some(Value::Table(t)) = table.get_mut("signal")
    {
        for other in DRIVE {
            t.remove(other);
        }
    }
    let mut here = table;
    let mut walked = String::new();
    let (last, inner) = o.path.split_last().expect("a path has a step");
    for step in inner {
        let name = join(&walked, &step.key);
        let entry = here
            .entry(step.key.clone())
            .or_insert_with(|| Value::Table(Table::new()));
        let entry = match step.index {
            None => entry,
            Some(i) => element(entry, i, &name).map_err(err)?,
        };
        walked = match step.index {
            Some(i) => format!("{name}[{i}]"),
            None => name,
        };
        here = match entry {
            Value::Table(t) => t,
            other => {
                return Err(err(format!(
                    "{walked} is {}, not a table of fields",
                    kind(other)
                )));
            }
        };
    }
    let name = join(&walked, &last.key);
    match last.index {
        None => {
            here.insert(last.key.clone(), o.value.clone());
        }
        Some(i) => {
            let Some(entry) = here.get_mut(&last.key) else {
                return Err(err(format!(
                    "{name} is not in the scene: no array to index"
                )));
            };
            *element(entry, i, &name).map_err(err)? = o.value.clone();
        }
    }
    Ok(())
}

fn join(walked: &str, key: &str) -> String {
    if walked.is_empty() {
        key.to_owned()
    } else {
        format!("{walked}.{key}")
    }
}

/// Entry `i` of the array `value` (named `name` in messages).
fn element<'a>(value: &'a mut Value, i: usize, name: &str) -> Result<&'a mut Value, String> {
    match value {
        Value::Array(a) => {
            let len = a.len();
            a.get_mut(i).ok_or_else(|| match len {
                0 => format!("{name} is empty: no entry [{i}]"),
                _ => format!(
                    "{name} has {len} entries, indices 0 to {}: no entry [{i}]",
                    len - 1
                ),
            })
        }
        other => Err(format!("{name} is {}, not an array", kind(other))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> Table {
        text.parse().unwrap()
    }

    fn set(text: &str, overrides: &[&str]) -> Result<Table, OverrideError> {
        let mut t = table(text);
        let o: Vec<Override> = overrides.iter().map(|s| s.parse().unwrap()).collect();
        apply(&mut t, &o)?;
        Ok(t)
    }

    #[test]
    fn a_field_an_array_entry_and_a_new_table_are_set() {
        let t = set(
            "[motor]\nslider_mass = 1e-3\n[signal]\namplitudes = [1.0, 2.0]\n",
            &[
                "motor.slider_mass=5e-3",
                "signal.amplitudes[1]=3",
                "actuator.mass=2e-3",
                "signal.kind=harmonics",
            ],
        )
        .unwrap();
        assert_eq!(t["motor"]["slider_mass"].as_float(), Some(5e-3));
        assert_eq!(t["signal"]["amplitudes"][0].as_float(), Some(1.0));
        assert_eq!(t["signal"]["amplitudes"][1].as_integer(), Some(3));
        assert_eq!(t["actuator"]["mass"].as_float(), Some(2e-3));
        assert_eq!(t["signal"]["kind"].as_str(), Some("harmonics"));
    }

    #[test]
    fn setting_one_drive_field_removes_the_others() {
        let t = set(
            "[signal]\nkind = \"fourier\"\nkappa = 36.0\n",
            &["signal.frequency=9000"],
        )
        .unwrap();
        assert!(t["signal"].get("kappa").is_none());
        assert_eq!(t["signal"]["frequency"].as_integer(), Some(9000));
        let t = set(
            "[signal]\nsqrt_kappa = 6.0\n",
            &["signal.kappa=4", "signal.f_max=2e4"],
        )
        .unwrap();
        assert!(t["signal"].get("kappa").is_none() && t["signal"].get("sqrt_kappa").is_none());
        assert_eq!(t["signal"]["f_max"].as_float(), Some(2e4));
    }

    #[test]
    fn malformed_overrides_name_what_is_wrong() {
        for (given, says) in [
            ("motor.slider_mass", "expected PATH=VALUE"),
            ("=3", "path before `=` is empty"),
            ("motor.slider_mass=", "value after `=` is empty"),
            ("motor..x=1", "is not a field name"),
            ("signal.amplitudes[x]=1", "whole number from 0"),
            ("signal.amplitudes[1=1", "an index is written"),
            ("mo tor.x=1", "is not a field name"),
        ] {
            let e = given.parse::<Override>().unwrap_err().to_string();
            assert!(e.starts_with("--set ") && e.contains(says), "{given}: {e}");
            assert!(!e.contains('\n'));
        }
        // A control character inside a key is written escaped.
        let e = "mo\rtor.x=1".parse::<Override>().unwrap_err().to_string();
        assert!(!e.contains('\r') && e.contains("\\r"), "{e}");
    }

    #[test]
    fn overrides_that_do_not_fit_the_scene_name_the_field() {
        let text = "[motor]\nslider_mass = 1e-3\n[signal]\namplitudes = [1.0, 2.0]\n";
        for (given, says) in [
            (
                "signal.amplitudes[2]=1",
                "signal.amplitudes has 2 entries, indices 0 to 1",
            ),
            (
                "motor.slider_mass.x=1",
                "motor.slider_mass is a number, not a table",
            ),
            ("signal.phases[0]=1", "signal.phases is not in the scene"),
            (
                "motor.slider_mass[0]=1",
                "motor.slider_mass is a number, not an array",
            ),
        ] {
            let e = set(text, &[given]).unwrap_err().to_string();
            assert!(e.contains(says), "{given}: {e}");
        }
    }

    #[test]
    fn values_are_toml_or_else_text() {
        assert_eq!(parse_value("5e-3"), Value::Float(5e-3));
        assert_eq!(parse_value("true"), Value::Boolean(true));
        assert_eq!(parse_value("\"a b\""), Value::String("a b".into()));
        assert_eq!(parse_value("fourier"), Value::String("fourier".into()));
        assert!(parse_value("nan").as_float().is_some_and(f64::is_nan));
        assert_eq!(
            parse_value("[1, 2]"),
            Value::Array(vec![Value::Integer(1), Value::Integer(2)])
        );
    }
}
