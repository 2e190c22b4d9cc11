"""stickslip: an event-driven simulator for piezoelectric inertia drives.

The Python face of the ``stickslip`` command line, computed by the same
Rust library in process: every result is the command line's, value for
value (``run(...).to_dict()`` is ``stickslip run --json``, a sweep's
DataFrame the CSV of ``stickslip sweep``).

Scenes
    A scene is a dict with the structure of the scene TOML
    (``docs/interface.md``), a path to a scene file, or
    ``default_scene()`` (``None`` means the same). Overrides are keyword
    arguments with dotted names, applied before the scene is checked, as
    ``--set PATH=VALUE`` on the command line::

        import stickslip
        r = stickslip.run(stickslip.default_scene(), **{"motor.slider_mass": 5e-3})
        r.v_inf, r.regime, r.error["v_inf"]

Errors
    Bad input (a field out of range, an unknown key, a file that cannot be
    read) raises :class:`SceneError`, a ``ValueError`` whose text is the
    command line's one-line message. A slider that runs away or a start-up
    that does not settle is a result (``Result.regime``), not an error.
    A run that cannot finish (its time limit) raises
    :class:`SimulationError`.

Every long computation releases the GIL; sweeps run on worker threads.
"""

from __future__ import annotations

import os
import warnings as _warnings
from typing import Any, Dict, Iterable, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

from . import _stickslip
from ._stickslip import SceneError, SimulationError

__all__ = [
    "SceneError",
    "SimulationError",
    "Result",
    "default_scene",
    "scene_toml",
    "run",
    "sweep",
    "characteristic",
    "optimize",
    "compare",
    "signal",
    "INDICATORS",
    "__version__",
]

__version__: str = _stickslip.VERSION

Scene = Union[Mapping[str, Any], str, "os.PathLike[str]", None]
"""A scene: a dict shaped like the scene TOML, a path, or None (the default)."""

INDICATORS: Tuple[str, ...] = (
    "v_inf",
    "startup_time",
    "startup_periods",
    "smoothness",
    "durability",
    "friction_energy",
    "stiction_fraction",
    "stiction_fraction_steady",
    "apparent_power",
    "velocity_per_power",
)
"""Indicator keys of ``run --json`` that :class:`Result` has as attributes."""


class StickslipWarning(UserWarning):
    """A valid but implausible scene value (the command line's warnings)."""


def _warn(lines: Iterable[str]) -> None:
    for line in lines:
        _warnings.warn(line, StickslipWarning, stacklevel=3)


def default_scene() -> Dict[str, Any]:
    """The built-in default scene as a dict (``stickslip default-scene``).

    The paper's motor (slider mass 1.4 g, contact force 1 N, mu_0 = 0.1736,
    mu_d = 0.1568) driven by n = 2 harmonics with sqrt(kappa) = 6 and the
    Lanczos sigma factors. Change it like any dict and pass it to
    :func:`run`, :func:`sweep` and the others.
    """
    return _stickslip.default_scene()


def scene_toml(scene: Scene = None, **overrides: Any) -> str:
    """The scene with the overrides applied, checked, as TOML text.

    Raises :class:`SceneError` with the command line's message if the scene
    is not valid.
    """
    text, _ = _stickslip.resolve(scene, overrides or None)
    return text


def _frame(columns: Sequence[Tuple[str, str, Any]]) -> pd.DataFrame:
    data = {}
    for name, kind, values in columns:
        if kind == "f8":
            data[name] = np.frombuffer(values, dtype=np.float64).copy()
        elif kind == "i8":
            data[name] = np.frombuffer(values, dtype=np.int64).copy()
        else:
            data[name] = np.asarray(values, dtype=object)
    return pd.DataFrame(data)


class Result:
    """One run of a scene: what ``stickslip run --json`` reports.

    Attributes
    ----------
    regime : str
        ``stick-slip``, ``slip-slip``, ``stuck``, ``run-away`` or
        ``not_converged``.
    v_inf, startup_time, startup_periods, smoothness, durability,
    friction_energy, stiction_fraction, stiction_fraction_steady,
    apparent_power, velocity_per_power : float or None
        The indicators (SI units, ``docs/interface.md``); None when not
        requested or without a steady state.
    period, f0 : float
        The drive period T (s) and frequency 1/T (Hz).
    error : dict
        The estimated absolute error of each reported indicator
        (``error_estimate`` of the JSON).
    warnings : list of str
        The scene's warnings (valid but implausible values).
    """

    __slots__ = ("_run", "_dict")

    def __init__(self, native: Any) -> None:
        self._run = native
        self._dict: Optional[Dict[str, Any]] = None

    def to_dict(self) -> Dict[str, Any]:
        """The JSON object of ``stickslip run --json`` as a dict (a copy).

        Same keys, same values to the bit (floats are the same ``f64``);
        the timing keys (``wall_time_s``, ``setup_time_s``,
        ``simulation_time_s``) are those of this run.
        """
        return _copy(self._json())

    def _json(self) -> Dict[str, Any]:
        if self._dict is None:
            self._dict = self._run.to_dict()
        return self._dict

    @property
    def regime(self) -> str:
        """The outcome: a steady regime, ``run-away`` or ``not_converged``."""
        return self._run.regime

    @property
    def error(self) -> Dict[str, Optional[float]]:
        """Estimated absolute error of each reported indicator."""
        return dict(self._json().get("error_estimate") or {})

    @property
    def warnings(self) -> list:
        """The scene's warnings, one line each."""
        return self._run.warnings

    @property
    def period(self) -> float:
        """Drive period T (s)."""
        return self._json()["period"]

    @property
    def f0(self) -> Optional[float]:
        """Drive frequency f_0 = 1/T (Hz)."""
        return self._json().get("f0")

    def scene_toml(self) -> str:
        """The scene that was run (overrides applied) as TOML text."""
        return self._run.scene_toml()

    def trajectory(self, times: Union[Sequence[float], np.ndarray]) -> pd.DataFrame:
        """The exact state at each of ``times`` (s, increasing, >= 0).

        Columns ``t, x_R, v_R, a_R, x_S, v_S`` (float64; rod and slider
        position, velocity, acceleration from rest at t = 0) and ``mode``
        (``stick``/``slip``), exactly the table of ``stickslip run
        --trajectory FILE --times TIMES``: nothing is interpolated.
        """
        t = np.ascontiguousarray(np.asarray(times, dtype=np.float64).ravel())
        return _frame(self._run.trajectory(t.tobytes()))

    def periods(self) -> pd.DataFrame:
        """The per-period series of the start-up from rest to p_0.99.

        Columns ``p, v_p, x_p, stick_time, events, event_kinds, x_S_end``,
        the table of ``stickslip run --periods-series FILE``.
        """
        return _frame(self._run.periods())

    def events(self) -> pd.DataFrame:
        """The event log of the start-up: ``period, phase, time, kind``.

        As ``[outputs] events = true`` reports it (``event_log`` of the
        JSON); the scene is run again with the log on if it was off. At
        most the first 100000 events are logged; ``attrs["omitted"]``
        counts the rest. Empty without a steady state.
        """
        log = self._run.events()
        rows = log.get("event_log") or []
        frame = pd.DataFrame(
            {
                "period": np.array([e["period"] for e in rows], dtype=np.int64),
                "phase": np.array([e["phase"] for e in rows], dtype=np.float64),
                "time": np.array([e["time"] for e in rows], dtype=np.float64),
                "kind": np.array([e["kind"] for e in rows], dtype=object),
            }
        )
        frame.attrs["omitted"] = log.get("event_log_omitted") or 0
        return frame

    def __getattr__(self, name: str) -> Any:
        if name in INDICATORS:
            return self._json().get(name)
        raise AttributeError(f"'Result' object has no attribute '{name}'")

    def __dir__(self) -> Iterable[str]:
        return sorted(set(super().__dir__()) | set(INDICATORS))

    def __repr__(self) -> str:
        v = self._json().get("v_inf")
        return f"<stickslip.Result regime={self.regime!r} v_inf={v!r}>"


def _copy(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _copy(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_copy(v) for v in value]
    return value


def run(scene: Scene = None, **overrides: Any) -> Result:
    """Run a scene, as ``stickslip run SCENE --json``.

    Parameters
    ----------
    scene : dict, str, os.PathLike or None
        A dict shaped like the scene TOML, a path to a scene file, or
        ``default_scene()`` / None.
    **overrides
        Dotted scene paths and values, applied in order before the scene is
        checked: ``run(scene, **{"motor.slider_mass": 5e-3})``,
        ``**{"signal.amplitudes[1]": 2e-6}``. Setting one of
        ``signal.kappa``, ``sqrt_kappa``, ``frequency``, ``f_max`` replaces
        whichever the scene gave.

    Returns
    -------
    Result
        The indicators as attributes (``.v_inf``), ``.regime``, ``.error``
        and ``.to_dict()`` (equal to ``run --json``); ``.trajectory(times)``,
        ``.periods()``, ``.events()`` as DataFrames.

    Raises
    ------
    SceneError
        Bad input, with the command line's one-line message.
    SimulationError
        A run that could not finish (its time limit).

    Example
    -------
    >>> r = run(default_scene())
    >>> round(r.v_inf, 4), r.regime
    (0.2971, 'slip-slip')
    """
    native = _stickslip.run(scene, overrides or None)
    if native.warnings:
        _warn(native.warnings)
    return Result(native)


def _sweep_frame(head: str, columns: Sequence[Tuple[str, str, Any]]) -> pd.DataFrame:
    data = {}
    for name, kind, values in columns:
        if kind == "bool":
            data[name] = np.array(values, dtype=bool)
        else:
            data[name] = _frame([(name, kind, values)])[name]
    frame = pd.DataFrame(data)
    for item in head.lstrip("#").split(","):
        if "=" in item:
            key, value = item.split("=", 1)
            frame.attrs[key.strip()] = value.strip()
    return frame


def sweep(
    scene: Scene,
    axes: Mapping[str, Sequence[Any]],
    jobs: Optional[int] = None,
    shard: Optional[Tuple[int, int]] = None,
    *,
    indicators: Optional[Sequence[str]] = None,
    timing: bool = True,
    **overrides: Any,
) -> pd.DataFrame:
    """Run a grid of scenes in parallel, as ``stickslip sweep``.

    Parameters
    ----------
    scene : dict, str, os.PathLike or None
        The base scene (see :func:`run`).
    axes : dict
        Axis name to list of values, the ``[axes]`` table of a sweep file:
        ``level``, ``sqrt_kappa``, ``kappa``, ``frequency``, ``f_max``,
        ``harmonics``, ``sigma``, ``stroke``, ``duty``, ``mu_static``,
        ``mu_dynamic``, ``contact_force``, ``slider_mass``,
        ``extra_acceleration``, and for a scene with a ``spring`` table
        ``spring.stiffness``, ``spring.damping``, ``spring.gap``,
        ``spring.preload`` (dotted names, as TOML's dotted keys; the
        DataFrame then has the spring's reading as columns,
        ``spring_force_mean`` and on). The cases are their cartesian
        product, the last axis (in that order) varying fastest.
    jobs : int, optional
        Worker threads (default and maximum: the available CPUs).
    shard : (i, n), optional
        Only the cases with ``case % n == i - 1`` (``1 <= i <= n``), as
        ``--shard i/n``: Dask, Ray or a Slurm array can run the shards
        apart and ``pandas.concat`` them (sorted by ``case``).
    indicators : list of str, optional
        The ``[outputs] indicators`` of the sweep (default: the scene's).
    timing : bool
        Keep the timing columns (``wall_time_s``, ``setup_time_s``,
        ``simulation_time_s``); False is ``--no-timing``.
    **overrides
        Overrides of the base scene (see :func:`run`).

    Returns
    -------
    pandas.DataFrame
        The columns of the CSV that ``stickslip sweep`` writes, one row per
        case, sorted by case; floats are the same ``f64`` as the CSV's, an
        empty cell is NaN (``""`` in the text columns ``scene_hash``,
        ``regime``, ``failure``). ``attrs`` holds the header line's
        ``stickslip_version`` and ``base_scene_hash``.
    """
    head, columns = _stickslip.sweep(
        scene,
        _axes_table(axes),
        overrides or None,
        list(indicators) if indicators is not None else None,
        jobs,
        tuple(shard) if shard is not None else None,
        timing,
    )
    return _sweep_frame(head, columns)


def _axes_table(axes: Mapping[str, Sequence[Any]]) -> Dict[str, Any]:
    """The ``[axes]`` table of ``axes``: a dotted name (``spring.stiffness``)
    is a key of a nested table, as a TOML dotted key is."""
    table: Dict[str, Any] = {k: v for k, v in axes.items() if "." not in k}
    for name, values in axes.items():
        if "." in name:
            head, rest = name.split(".", 1)
            inner = table.get(head, {})
            if not isinstance(inner, Mapping):
                # Left for the sweep to refuse, naming it.
                table[name] = values
                continue
            table[head] = {**inner, rest: values}
    return table


def _options(**flags: Any) -> list:
    args = []
    for flag, value in flags.items():
        if value is None or value is False:
            continue
        name = "--" + flag.replace("_", "-")
        if value is True:
            args.append(name)
        else:
            args.extend([name, str(value) if not isinstance(value, float) else repr(value)])
    return args


def characteristic(
    scene: Scene = None,
    *,
    load: str = "force",
    range: Optional[Tuple[float, float]] = None,
    tolerance: Optional[float] = None,
    max_evaluations: Optional[int] = None,
    **overrides: Any,
) -> Dict[str, Any]:
    """The force-velocity characteristic, as ``stickslip characteristic --json``.

    ``load`` is ``"force"`` (a force F in N against forward motion) or
    ``"incline"`` (the slider's weight on an incline, degrees); ``range``
    is the (low, high) end of the load (default: the whole range).
    Returns the JSON object as a dict: the points, the stall force, the
    held band, the holding force, the largest output power and the
    datasheet block; ``pandas.DataFrame(result["points"])`` tabulates the
    points.
    """
    low, high = range if range is not None else (None, None)
    args = ["--load", load] + _options(tolerance=tolerance, max_evaluations=max_evaluations)
    if low is not None:
        args += ["--from", repr(float(low))]
    if high is not None:
        args += ["--to", repr(float(high))]
    return _stickslip.characteristic(scene, overrides or None, args)


def optimize(
    scene: Scene = None,
    *,
    harmonics: Optional[int] = None,
    objective: Optional[str] = None,
    keep: Optional[str] = None,
    seed: Optional[int] = None,
    jobs: Optional[int] = None,
    timing: bool = True,
    **overrides: Any,
) -> Dict[str, Any]:
    """The best rod signal of n harmonics, as ``stickslip optimize --json``.

    The scene's ``[optimize]`` table (if any) and the arguments (each
    overriding it, as the command line's flags) set the search. Returns
    the JSON object as a dict, with the best signal as a runnable scene's
    TOML text under ``"scene_toml"``.
    """
    args = _options(harmonics=harmonics, objective=objective, keep=keep, seed=seed, jobs=jobs)
    if not timing:
        args.append("--no-timing")
    result, written = _stickslip.optimize(scene, overrides or None, args)
    result["scene_toml"] = written
    return result


def compare(
    scene: Scene,
    data: Union[pd.DataFrame, Mapping[str, Any]],
    *,
    name: str = "data",
    tolerance: Optional[float] = None,
    **overrides: Any,
) -> Dict[str, Any]:
    """Compare a user's results with the exact solution (``stickslip compare``).

    ``data`` is a DataFrame or a dict of arrays in SI units with any of the
    columns ``t`` (s), ``x_S``, ``v_S``, ``x_R`` (samples at the times t),
    ``p`` and ``v_p`` (mean velocity of period p); other columns are left
    out. No file is needed. Returns the report as a dict (the JSON of
    ``stickslip compare --json``); ``tolerance`` is the verdict's relative
    tolerance (default 1e-3).
    """
    columns = data.items() if isinstance(data, pd.DataFrame) else dict(data).items()
    arrays = [
        (str(key), np.ascontiguousarray(np.asarray(values, dtype=np.float64)).tobytes())
        for key, values in columns
        if str(key) in {"t", "x_S", "x_s", "v_S", "v_s", "x_R", "x_r", "p", "v_p"}
    ]
    return _stickslip.compare(scene, arrays, name, overrides or None, tolerance)


def signal(scene: Scene = None, **overrides: Any) -> Dict[str, Any]:
    """The rod signal exactly as simulated (``stickslip signal --json``).

    Its kind, period, frequency, stroke and the harmonics' amplitudes and
    phases with which x_R(t) is evaluated, as a dict.
    """
    return _stickslip.signal(scene, overrides or None)
