//! `stickslip._stickslip`: the native half of the Python package
//! `stickslip` (the public API, its docstrings and the pandas tables are in
//! `python/stickslip/__init__.py`).
//!
//! Contract: this file is the only glue between Python and the Rust
//! library, so that a change of the library's API touches only it.
//!
//! * A scene is `None` (the built-in default scene), a path (`str` or
//!   `os.PathLike`), or a dict with the TOML's structure; overrides are
//!   `{dotted path: value}` and go through the library's `PATH=VALUE`
//!   grammar (`--set` on the command line), applied before the scene is
//!   checked. A path is read exactly as `stickslip run PATH` reads it.
//! * Every output is the command line's by construction: `run` returns
//!   [`stickslip::report::to_json`] of the same outcome `stickslip run --json`
//!   prints; trajectories and per-period series are the tables of
//!   `run --trajectory` / `--periods-series`
//!   ([`stickslip::export::exact_tables`]); a sweep runs
//!   [`stickslip::sweep::execute`] into a private temporary directory and
//!   hands back the CSV it wrote; `characteristic` and `optimize` run the
//!   command line in process ([`stickslip::cli::main_with`]) and return
//!   its JSON.
//! * Bad input raises `SceneError` (a `ValueError`) whose text is the
//!   command line's one-line message without the `stickslip: ` prefix;
//!   a run that fails for another reason (a time limit) raises
//!   `SimulationError` (a `RuntimeError`). Physical outcomes (a slider
//!   that runs away, a start-up that does not settle) are results.
//! * Long work (runs, sweeps, characteristics, optimizations) releases the
//!   GIL.

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::Value;
use std::path::{Path, PathBuf};
use stickslip::{Error, Outcome, Scene, scene::Override};

create_exception!(
    _stickslip,
    SceneError,
    PyValueError,
    "Bad input: a scene, an override or an option that the command line refuses. The message is the command line's one line."
);
create_exception!(
    _stickslip,
    SimulationError,
    PyRuntimeError,
    "A run that could not finish (for example: it reached its time limit)."
);

fn scene_error(message: impl std::fmt::Display) -> PyErr {
    SceneError::new_err(stickslip::cli::one_line(&message.to_string()))
}

/// A library error: input errors are `SceneError`, a run that could not
/// finish `SimulationError`.
fn library_error(e: Error) -> PyErr {
    match e {
        Error::Simulation(_) => SimulationError::new_err(stickslip::cli::one_line(&e.to_string())),
        _ => scene_error(e),
    }
}

// ---------------------------------------------------------------------------
// Python values <-> TOML and JSON

/// A Python value as a TOML value; `field` names it in errors.
fn to_toml(obj: &Bound<'_, PyAny>, field: &str) -> PyResult<toml::Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        return match obj.extract::<i64>() {
            Ok(i) => Ok(toml::Value::Integer(i)),
            Err(_) => Err(scene_error(format!(
                "{field} = {obj}: an integer beyond 64 bits"
            ))),
        };
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if let Ok(s) = obj.downcast::<PyString>() {
        return Ok(toml::Value::String(s.extract::<String>()?));
    }
    if let Ok(d) = obj.downcast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let key: String = k
                .extract()
                .map_err(|_| scene_error(format!("{field}: the key {k} is not a string")))?;
            let name = if field.is_empty() {
                key.clone()
            } else {
                format!("{field}.{key}")
            };
            if v.is_none() {
                // A field set to None is left to its default.
                continue;
            }
            table.insert(key, to_toml(&v, &name)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            items.push(to_toml(&v?, &format!("{field}[{i}]"))?);
        }
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and arrays: their Python equivalents.
    if obj.hasattr("tolist")? {
        let plain = obj.call_method0("tolist")?;
        if !plain.is(obj) {
            return to_toml(&plain, field);
        }
    }
    if obj.hasattr("__index__")? {
        return to_toml(&obj.call_method0("__index__")?, field);
    }
    if obj.hasattr("__float__")? {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    let type_name = obj.get_type().name()?.to_string();
    Err(scene_error(format!(
        "{field}: a value of type {type_name} is not a scene value (give a number, bool, string, list or dict)"
    )))
}

/// A TOML value as Python: tables become dicts, arrays lists.
fn toml_to_py(py: Python<'_>, value: &toml::Value) -> PyResult<PyObject> {
    Ok(match value {
        toml::Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any().unbind(),
        toml::Value::Float(f) => f.into_pyobject(py)?.into_any().unbind(),
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any().unbind(),
        toml::Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any().unbind(),
        toml::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(toml_to_py(py, item)?)?;
            }
            list.into_any().unbind()
        }
        toml::Value::Table(table) => {
            let dict = PyDict::new(py);
            for (k, v) in table {
                dict.set_item(k, toml_to_py(py, v)?)?;
            }
            dict.into_any().unbind()
        }
    })
}

/// A JSON value as Python; numbers keep their exact `f64` or integer.
fn json_to_py(py: Python<'_>, value: &Value) -> PyResult<PyObject> {
    Ok(match value {
        Value::Null => py.None(),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any().unbind(),
        Value::Number(n) => {
            if let Some(u) = n.as_u64() {
                u.into_pyobject(py)?.into_any().unbind()
            } else if let Some(i) = n.as_i64() {
                i.into_pyobject(py)?.into_any().unbind()
            } else {
                n.as_f64()
                    .unwrap_or(f64::NAN)
                    .into_pyobject(py)?
                    .into_any()
                    .unbind()
            }
        }
        Value::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_py(py, item)?)?;
            }
            list.into_any().unbind()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, v) in map {
                dict.set_item(k, json_to_py(py, v)?)?;
            }
            dict.into_any().unbind()
        }
    })
}

// ---------------------------------------------------------------------------
// Scenes

/// Where a scene came from: what the command line is given for it.
enum Source {
    /// The built-in default scene.
    Default,
    /// A scene file.
    Path(PathBuf),
    /// A dict, as TOML text.
    Text(String),
}

/// A scene as given from Python, resolved and checked.
struct Loaded {
    scene: Scene,
    source: Source,
    /// The overrides as `PATH=VALUE`, for the command line.
    set: Vec<String>,
}

/// Origin of a dict scene in messages.
const DICT_ORIGIN: &str = "<scene dict>";

fn path_of(obj: &Bound<'_, PyAny>) -> PyResult<Option<PathBuf>> {
    if obj.is_instance_of::<PyString>() {
        return Ok(Some(PathBuf::from(obj.extract::<String>()?)));
    }
    if obj.hasattr("__fspath__")? {
        return Ok(Some(obj.extract::<PathBuf>()?));
    }
    Ok(None)
}

fn overrides_of(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<(Vec<Override>, Vec<String>)> {
    let mut parsed = Vec::new();
    let mut set = Vec::new();
    if let Some(d) = overrides {
        for (k, v) in d.iter() {
            let path: String = k.extract()?;
            let value = to_toml(&v, &path)?;
            let text = format!("{path}={value}");
            parsed.push(
                text.parse::<Override>()
                    .map_err(|e: stickslip::scene::OverrideError| scene_error(e))?,
            );
            set.push(text);
        }
    }
    Ok((parsed, set))
}

fn load(scene: &Bound<'_, PyAny>, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Loaded> {
    let (parsed, set) = overrides_of(overrides)?;
    let (result, source) = if scene.is_none() {
        let result = if parsed.is_empty() {
            Ok(Scene::default())
        } else {
            Scene::from_toml_str_with(&Scene::default().to_toml(), "<default scene>", &parsed)
        };
        (result, Source::Default)
    } else if let Some(path) = path_of(scene)? {
        (Scene::from_path_with(&path, &parsed), Source::Path(path))
    } else if scene.is_instance_of::<PyDict>() {
        let text = match to_toml(scene, "")? {
            toml::Value::Table(t) => toml::to_string(&t).map_err(scene_error)?,
            _ => unreachable!("a dict is a table"),
        };
        (
            Scene::from_toml_str_with(&text, DICT_ORIGIN, &parsed),
            Source::Text(text),
        )
    } else {
        let type_name = scene.get_type().name()?.to_string();
        return Err(scene_error(format!(
            "scene: a value of type {type_name}; give a dict, a path or None (the default scene)"
        )));
    };
    Ok(Loaded {
        scene: result.map_err(scene_error)?,
        source,
        set,
    })
}

/// The built-in default scene as a dict.
#[pyfunction]
fn default_scene(py: Python<'_>) -> PyResult<PyObject> {
    let text = Scene::default().to_toml();
    let table: toml::Table = text.parse().map_err(scene_error)?;
    toml_to_py(py, &toml::Value::Table(table))
}

/// The resolved scene (overrides applied, checked) as TOML text, and its
/// warnings (one line each, as the command line prints them).
#[pyfunction]
#[pyo3(signature = (scene, overrides=None))]
fn resolve(
    scene: &Bound<'_, PyAny>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<(String, Vec<String>)> {
    let loaded = load(scene, overrides)?;
    let warnings = loaded
        .scene
        .warnings()
        .iter()
        .map(ToString::to_string)
        .collect();
    Ok((loaded.scene.to_toml(), warnings))
}

// ---------------------------------------------------------------------------
// Runs

/// One run: the scene and its outcome.
#[pyclass(frozen, module = "stickslip._stickslip")]
struct Run {
    scene: Scene,
    outcome: Outcome,
    warnings: Vec<String>,
}

/// Runs a scene as `stickslip run` does.
#[pyfunction]
#[pyo3(signature = (scene, overrides=None))]
fn run(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<Run> {
    let loaded = load(scene, overrides)?;
    let scene = loaded.scene;
    let outcome = py
        .allow_threads(|| stickslip::run(&scene, &stickslip::RunOptions::default()))
        .map_err(library_error)?;
    let warnings = scene.warnings().iter().map(ToString::to_string).collect();
    Ok(Run {
        scene,
        outcome,
        warnings,
    })
}

/// Strictly increasing, finite times `>= 0`, as the command line requires
/// of `--times`.
fn check_times(times: &[f64]) -> PyResult<()> {
    for (i, t) in times.iter().enumerate() {
        if !(t.is_finite() && *t >= 0.0) {
            return Err(scene_error(format!(
                "times[{i}] = {t}: must be a finite time >= 0 (s)"
            )));
        }
        if i > 0 && *t <= times[i - 1] {
            return Err(scene_error(format!(
                "times[{i}] = {t}: the times must increase (times[{}] = {})",
                i - 1,
                times[i - 1]
            )));
        }
    }
    Ok(())
}

/// Columns of a table for Python: `(name, kind, data)` ([`columns_of`]).
type Columns = Vec<(String, &'static str, PyObject)>;

/// The columns of a CSV table, each `(name, kind, data)`: kind `"f8"`
/// (numbers) or `"i8"` (integers, every cell written without a point or
/// an exponent) with native-endian bytes for `numpy.frombuffer`, or
/// `"str"` with a list of strings.
fn columns_of(py: Python<'_>, csv: &str) -> PyResult<Columns> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let mut out = Vec::with_capacity(header.len());
    for (j, name) in header.iter().enumerate() {
        let cells: Vec<&str> = rows
            .iter()
            .map(|r| r.get(j).copied().unwrap_or(""))
            .collect();
        let integers: Option<Vec<i64>> = cells.iter().map(|c| c.parse::<i64>().ok()).collect();
        let numbers: Option<Vec<f64>> = cells.iter().map(|c| c.parse::<f64>().ok()).collect();
        let text = matches!(*name, "mode" | "event_kinds");
        let (kind, column) = match (integers, numbers) {
            (Some(values), _) if !text => {
                let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
                ("i8", PyBytes::new(py, &bytes).into_any().unbind())
            }
            (_, Some(values)) if !text => {
                let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
                ("f8", PyBytes::new(py, &bytes).into_any().unbind())
            }
            _ => ("str", PyList::new(py, cells)?.into_any().unbind()),
        };
        out.push(((*name).to_owned(), kind, column));
    }
    Ok(out)
}

#[pymethods]
impl Run {
    /// The JSON object of `stickslip run --json`, as a dict.
    fn to_dict(&self, py: Python<'_>) -> PyResult<PyObject> {
        json_to_py(py, &stickslip::report::to_json(&self.outcome, &self.scene))
    }

    /// `steady` regime name, `run-away` or `not_converged`.
    #[getter]
    fn regime(&self) -> &'static str {
        self.outcome.regime()
    }

    /// The scene's warnings, one line each.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The resolved scene as TOML text.
    fn scene_toml(&self) -> String {
        self.scene.to_toml()
    }

    /// The exact states at `times` (native-endian `f64` bytes), as
    /// `run --trajectory` writes them: `[(column, kind, values)]` ([`columns_of`]).
    fn trajectory(&self, py: Python<'_>, times: &[u8]) -> PyResult<Columns> {
        let times: Vec<f64> = times
            .chunks_exact(8)
            .map(|b| f64::from_ne_bytes(b.try_into().unwrap_or([0; 8])))
            .collect();
        check_times(&times)?;
        let scene = &self.scene;
        let tables = py
            .allow_threads(|| stickslip::export::exact_tables(scene, &times, false))
            .map_err(scene_error)?;
        columns_of(py, &tables.trajectory)
    }

    /// The per-period series of the start-up, as `run --periods-series`
    /// writes it: `[(column, kind, values)]` ([`columns_of`]).
    fn periods(&self, py: Python<'_>) -> PyResult<Columns> {
        let scene = &self.scene;
        let tables = py
            .allow_threads(|| stickslip::export::exact_tables(scene, &[], true))
            .map_err(scene_error)?;
        columns_of(py, &tables.periods.unwrap_or_default())
    }

    /// The event log of the run (`[outputs] events = true`), as the JSON's
    /// `event_log` list and `event_log_omitted`; run again with the log on
    /// if the scene did not ask for it. `None`: no steady state (the log is
    /// reported with one).
    fn events(&self, py: Python<'_>) -> PyResult<PyObject> {
        let json = if self.scene.outputs.events {
            stickslip::report::to_json(&self.outcome, &self.scene)
        } else {
            let mut scene = self.scene.clone();
            scene.outputs.events = true;
            let outcome = py
                .allow_threads(|| stickslip::run(&scene, &stickslip::RunOptions::default()))
                .map_err(library_error)?;
            stickslip::report::to_json(&outcome, &scene)
        };
        let log = serde_json::json!({
            "event_log": json.get("event_log").cloned().unwrap_or(Value::Null),
            "event_log_omitted": json.get("event_log_omitted").cloned().unwrap_or(Value::Null),
        });
        json_to_py(py, &log)
    }

    fn __repr__(&self) -> String {
        format!("<stickslip run: {}>", self.outcome.regime())
    }
}

// ---------------------------------------------------------------------------
// Temporary files and the command line in process

/// A private directory under the system's temporary directory, removed
/// when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new() -> PyResult<TempDir> {
        use std::sync::atomic::{AtomicU64, Ordering};
        static NEXT: AtomicU64 = AtomicU64::new(0);
        let base = std::env::temp_dir();
        for _ in 0..100 {
            let nanos = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.subsec_nanos());
            let path = base.join(format!(
                "stickslip-py-{}-{}-{nanos}",
                std::process::id(),
                NEXT.fetch_add(1, Ordering::Relaxed)
            ));
            match std::fs::create_dir(&path) {
                Ok(()) => return Ok(TempDir(path)),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => {
                    return Err(SimulationError::new_err(format!(
                        "cannot create a temporary directory in {}: {e}",
                        base.display()
                    )));
                }
            }
        }
        Err(SimulationError::new_err(
            "cannot create a temporary directory",
        ))
    }

    fn write(&self, name: &str, text: &str) -> PyResult<PathBuf> {
        let path = self.0.join(name);
        std::fs::write(&path, text).map_err(|e| {
            SimulationError::new_err(format!("cannot write {}: {e}", path.display()))
        })?;
        Ok(path)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The scene argument of a command line for `loaded` (a dict is written to
/// `dir` as it was given, so that tables the scene reader passes over, such
/// as `[optimize]`, reach the command), then its `--set` overrides.
fn scene_args(loaded: &Loaded, dir: &TempDir) -> PyResult<Vec<String>> {
    let mut args = Vec::new();
    match &loaded.source {
        Source::Default => {}
        Source::Path(p) => args.push(p.display().to_string()),
        Source::Text(text) => args.push(dir.write("scene.toml", text)?.display().to_string()),
    }
    for s in &loaded.set {
        args.push("--set".to_owned());
        args.push(s.clone());
    }
    Ok(args)
}

/// Runs the command line with `args` (after the program name), the GIL
/// released; returns its standard output, or raises its one-line error.
fn command_line(py: Python<'_>, args: Vec<String>) -> PyResult<String> {
    let (code, out, err) = py.allow_threads(|| {
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let mut streams = stickslip::cli::Streams {
            out: &mut out,
            err: &mut err,
        };
        let code = stickslip::cli::main_with(
            std::iter::once("stickslip".to_owned()).chain(args),
            &mut streams,
        );
        (code, out, err)
    });
    let out = String::from_utf8_lossy(&out).into_owned();
    if code == 0 {
        return Ok(out);
    }
    let err = String::from_utf8_lossy(&err);
    let message = err
        .lines()
        .filter(|l| !l.starts_with("stickslip: warning:"))
        .find(|l| !l.trim().is_empty())
        .unwrap_or("the command failed");
    Err(scene_error(
        message.strip_prefix("stickslip: ").unwrap_or(message),
    ))
}

fn parse_json(py: Python<'_>, text: &str) -> PyResult<PyObject> {
    let value: Value = serde_json::from_str(text)
        .map_err(|e| SimulationError::new_err(format!("unreadable JSON output: {e}")))?;
    json_to_py(py, &value)
}

/// `stickslip characteristic SCENE --json` with `options` (command-line
/// flags after the scene), as a dict.
#[pyfunction]
#[pyo3(signature = (scene, overrides=None, options=Vec::new()))]
fn characteristic(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    overrides: Option<&Bound<'_, PyDict>>,
    options: Vec<String>,
) -> PyResult<PyObject> {
    let loaded = load(scene, overrides)?;
    let dir = TempDir::new()?;
    let mut args = vec!["characteristic".to_owned()];
    args.extend(scene_args(&loaded, &dir)?);
    args.extend(["--json".to_owned(), "--quiet".to_owned()]);
    args.extend(options);
    let text = command_line(py, args)?;
    parse_json(py, &text)
}

/// `stickslip optimize SCENE -o BEST.toml --json` with `options`: the
/// JSON as a dict, and the best scene's TOML text.
#[pyfunction]
#[pyo3(signature = (scene, overrides=None, options=Vec::new()))]
fn optimize(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    overrides: Option<&Bound<'_, PyDict>>,
    options: Vec<String>,
) -> PyResult<(PyObject, String)> {
    let loaded = load(scene, overrides)?;
    let dir = TempDir::new()?;
    let best = dir.0.join("best.toml");
    let mut args = vec!["optimize".to_owned()];
    args.extend(scene_args(&loaded, &dir)?);
    args.extend([
        "-o".to_owned(),
        best.display().to_string(),
        "--json".to_owned(),
        "--quiet".to_owned(),
    ]);
    args.extend(options);
    let text = command_line(py, args)?;
    let written = std::fs::read_to_string(&best)
        .map_err(|e| SimulationError::new_err(format!("cannot read {}: {e}", best.display())))?;
    Ok((parse_json(py, &text)?, written))
}

/// The rod signal exactly as simulated (`stickslip signal --json`).
#[pyfunction]
#[pyo3(signature = (scene, overrides=None))]
fn signal(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyObject> {
    let loaded = load(scene, overrides)?;
    let stickslip::scene::BuiltScene { signal, motor } =
        loaded.scene.build().map_err(library_error)?;
    let d = stickslip::signal::SignalDescription::new(&loaded.scene.signal, &signal, &motor);
    json_to_py(py, &d.to_json())
}

/// Compares a user's arrays (`{column: f64 bytes}`, columns `t`, `x_S`,
/// `v_S`, `x_R`, `p`, `v_p`) with the exact solution; the report as the
/// JSON of `stickslip compare --json`.
#[pyfunction]
#[pyo3(signature = (scene, data, name, overrides=None, tolerance=None))]
fn compare(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    data: Vec<(String, Vec<u8>)>,
    name: String,
    overrides: Option<&Bound<'_, PyDict>>,
    tolerance: Option<f64>,
) -> PyResult<PyObject> {
    let loaded = load(scene, overrides)?;
    let mut user = stickslip::compare::UserData::default();
    for (column, bytes) in data {
        let values: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|b| f64::from_ne_bytes(b.try_into().unwrap_or([0; 8])))
            .collect();
        let slot = match column.as_str() {
            "t" => &mut user.t,
            "x_S" | "x_s" => &mut user.x_s,
            "v_S" | "v_s" => &mut user.v_s,
            "x_R" | "x_r" => &mut user.x_r,
            "p" => &mut user.p,
            "v_p" => &mut user.v_p,
            _ => continue,
        };
        *slot = Some(stickslip::compare::Column::new(&column, values));
    }
    let mut options = stickslip::compare::CompareOptions::default();
    if let Some(t) = tolerance {
        options.tolerance = t;
    }
    let scene = &loaded.scene;
    let report = py
        .allow_threads(|| stickslip::compare::compare_data(scene, &[(name, user)], &options))
        .map_err(scene_error)?;
    json_to_py(py, &report.to_json())
}

// ---------------------------------------------------------------------------
// Sweeps

/// Runs a sweep of `scene` over `axes` (`{axis: [values]}`), as
/// `stickslip sweep` does: the CSV it writes, as its header line and its
/// columns ([`sweep_columns`]).
#[pyfunction]
#[pyo3(signature = (scene, axes, overrides=None, indicators=None, jobs=None, shard=None, timing=true))]
#[allow(clippy::too_many_arguments)]
fn sweep(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    axes: &Bound<'_, PyDict>,
    overrides: Option<&Bound<'_, PyDict>>,
    indicators: Option<Vec<String>>,
    jobs: Option<usize>,
    shard: Option<(usize, usize)>,
    timing: bool,
) -> PyResult<(String, Columns)> {
    let (parsed, _) = overrides_of(overrides)?;
    let dir = TempDir::new()?;
    let mut file = toml::Table::new();
    if !scene.is_none() {
        let base = match path_of(scene)? {
            Some(p) => std::path::absolute(&p).unwrap_or(p),
            None if scene.is_instance_of::<PyDict>() => {
                let text = match to_toml(scene, "")? {
                    toml::Value::Table(t) => toml::to_string(&t).map_err(scene_error)?,
                    _ => unreachable!("a dict is a table"),
                };
                // Checked here so that its errors name the dict, not a file.
                Scene::from_toml_str_with(&text, DICT_ORIGIN, &parsed).map_err(scene_error)?;
                dir.write("scene.toml", &text)?
            }
            None => {
                let type_name = scene.get_type().name()?.to_string();
                return Err(scene_error(format!(
                    "scene: a value of type {type_name}; give a dict, a path or None (the default scene)"
                )));
            }
        };
        file.insert(
            "base".to_owned(),
            toml::Value::String(base.display().to_string()),
        );
    }
    file.insert("axes".to_owned(), to_toml(axes, "axes")?);
    if let Some(names) = indicators {
        let mut outputs = toml::Table::new();
        outputs.insert(
            "indicators".to_owned(),
            toml::Value::Array(names.into_iter().map(toml::Value::String).collect()),
        );
        file.insert("outputs".to_owned(), toml::Value::Table(outputs));
    }
    let file: stickslip::sweep::SweepFile = toml::Value::Table(file)
        .try_into()
        .map_err(|e: toml::de::Error| scene_error(format!("sweep: {}", e.message())))?;
    let sweep = stickslip::sweep::Sweep::from_file_with(file, "<sweep>", Path::new("."), &parsed)
        .map_err(scene_error)?;
    let shard = match shard {
        None => None,
        Some((index, count)) => {
            let text = format!("{index}/{count}");
            Some(
                text.parse::<stickslip::sweep::Shard>()
                    .map_err(|e| scene_error(format!("shard = ({index}, {count}): {e}")))?,
            )
        }
    };
    if jobs == Some(0) {
        return Err(scene_error("jobs = 0: give at least 1 worker thread"));
    }
    let output = dir.0.join("sweep.csv");
    let options = stickslip::sweep::SweepOptions {
        shard,
        timing,
        progress: false,
        jobs,
        format: Some(stickslip::sweep::SweepFormat::Csv),
        ..stickslip::sweep::SweepOptions::new(&output)
    };
    py.allow_threads(|| stickslip::sweep::execute(&sweep, &options))
        .map_err(scene_error)?;
    let text = std::fs::read_to_string(&output)
        .map_err(|e| SimulationError::new_err(format!("cannot read {}: {e}", output.display())))?;
    let (head, table) = text.split_once('\n').unwrap_or((&text, ""));
    Ok((head.to_owned(), sweep_columns(py, table)?))
}

/// The columns of a sweep's CSV (after its header line), each
/// `(name, kind, data)` as [`columns_of`] gives them: `case` integers,
/// `harmonics` integers, `sigma` a list of bools, `scene_hash`, `regime` and `failure` lists of
/// strings, every other column numbers, an empty cell NaN.
fn sweep_columns(py: Python<'_>, csv: &str) -> PyResult<Columns> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let mut out = Vec::with_capacity(header.len());
    for (j, name) in header.iter().enumerate() {
        let cells = rows.iter().map(|r| r.get(j).copied().unwrap_or(""));
        let unreadable = |cell: &str| {
            SimulationError::new_err(format!(
                "sweep output: column {name}: unreadable cell `{cell}`"
            ))
        };
        let (kind, column) = match *name {
            "scene_hash" | "regime" | "failure" => {
                ("str", PyList::new(py, cells)?.into_any().unbind())
            }
            "sigma" => {
                let values: Vec<bool> = cells.map(|c| c == "true").collect();
                ("bool", PyList::new(py, values)?.into_any().unbind())
            }
            "case" | "harmonics" => {
                let mut bytes = Vec::with_capacity(rows.len() * 8);
                for cell in cells {
                    let v: i64 = cell.parse().map_err(|_| unreadable(cell))?;
                    bytes.extend(v.to_ne_bytes());
                }
                ("i8", PyBytes::new(py, &bytes).into_any().unbind())
            }
            _ => {
                let mut bytes = Vec::with_capacity(rows.len() * 8);
                for cell in cells {
                    let v: f64 = if cell.is_empty() {
                        f64::NAN
                    } else {
                        cell.parse().map_err(|_| unreadable(cell))?
                    };
                    bytes.extend(v.to_ne_bytes());
                }
                ("f8", PyBytes::new(py, &bytes).into_any().unbind())
            }
        };
        out.push(((*name).to_owned(), kind, column));
    }
    Ok(out)
}

/// Median wall time (s) of `repeats` runs of the default scene in Rust,
/// `stickslip::run(&Scene::default(), &stickslip::RunOptions::default())`, for the benchmark that
/// compares it with `stickslip.run` (examples/python/bench.py).
#[pyfunction]
fn time_default_run(py: Python<'_>, repeats: usize) -> PyResult<f64> {
    let scene = Scene::default();
    let mut times: Vec<f64> = py.allow_threads(|| {
        (0..repeats.max(1))
            .map(|_| {
                let start = std::time::Instant::now();
                let outcome = stickslip::run(&scene, &stickslip::RunOptions::default());
                std::hint::black_box(&outcome);
                start.elapsed().as_secs_f64()
            })
            .collect()
    });
    times.sort_by(f64::total_cmp);
    Ok(times[times.len() / 2])
}

/// The native module.
#[pymodule]
fn _stickslip(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("SimulationError", m.py().get_type::<SimulationError>())?;
    m.add("VERSION", stickslip::provenance::VERSION)?;
    m.add_class::<Run>()?;
    m.add_function(wrap_pyfunction!(default_scene, m)?)?;
    m.add_function(wrap_pyfunction!(resolve, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(characteristic, m)?)?;
    m.add_function(wrap_pyfunction!(optimize, m)?)?;
    m.add_function(wrap_pyfunction!(signal, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(time_default_run, m)?)?;
    Ok(())
}
