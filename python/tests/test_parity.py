"""The Python package gives the command line's results, value for value.

Every expected value here is the output of the ``stickslip`` binary
(an independent path: its own argument parsing, file reading and
printing), parsed with Python's ``json`` and ``float`` (correctly
rounded), and compared bit for bit. The binary is found as
``cli_binary`` says (build it with ``cargo build --release``). Without it
these tests fail: they never skip.
"""

from __future__ import annotations

import csv
import json
import math
import struct
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import stickslip
from cli_binary import ROOT, cli

SCENES = sorted((ROOT / "examples" / "scenes").glob("*.toml"))
TIMING = {"wall_time_s", "setup_time_s", "simulation_time_s"}


def cli_error(*args: object) -> str:
    """The command line's one-line message, without `stickslip: `."""
    p = cli(*args, ok=False)
    assert p.returncode == 1, (p.returncode, p.stderr)
    lines = [l for l in p.stderr.splitlines() if not l.startswith("stickslip: warning:")]
    assert len(lines) == 1 and lines[0].startswith("stickslip: "), p.stderr
    return lines[0][len("stickslip: ") :]


def same(a, b, where="") -> None:
    """Equal keys and values; floats equal to the bit."""
    if isinstance(a, float) or isinstance(b, float):
        assert isinstance(a, (int, float)) and isinstance(b, (int, float)), (where, a, b)
        assert struct.pack("<d", float(a)) == struct.pack("<d", float(b)), (where, a, b)
    elif isinstance(a, dict):
        assert isinstance(b, dict) and list(sorted(a)) == list(sorted(b)), (where, a, b)
        for k in a:
            same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), (where, a, b)
        for i, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{where}[{i}]")
    else:
        assert type(a) is type(b) and a == b, (where, a, b)


def without_timing(d: dict) -> dict:
    return {k: v for k, v in d.items() if k not in TIMING}


def test_example_scenes_exist():
    assert len(SCENES) >= 5, SCENES


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.stem)
def test_run_to_dict_equals_cli_json_for_every_example_scene(scene):
    expected = json.loads(cli("run", scene, "--json", "--quiet").stdout)
    got = stickslip.run(scene).to_dict()
    assert TIMING <= set(got), "the timing keys are reported"
    same(without_timing(got), without_timing(expected))


def test_run_of_a_dict_equals_the_run_of_its_file():
    # The tables of examples/scenes/stick_heavy.toml, written as a dict
    # (no TOML reader needed, so this runs on every supported Python).
    path = ROOT / "examples" / "scenes" / "stick_heavy.toml"
    as_dict = {
        "signal": {
            "kind": "fourier",
            "stroke": 25e-6,
            "kappa": 0.36,
            "harmonics": 5,
            "sigma": True,
            "duty": 1.0,
        },
        "outputs": {
            "indicators": [
                "v_inf",
                "startup_time",
                "smoothness",
                "durability",
                "friction_energy",
                "stiction_fraction",
            ],
            "trajectory": True,
            "events": True,
        },
    }
    same(
        without_timing(stickslip.run(as_dict).to_dict()),
        without_timing(stickslip.run(path).to_dict()),
    )


def test_default_scene_runs_as_the_cli_without_arguments():
    expected = json.loads(cli("run", "--json").stdout)
    same(without_timing(stickslip.run(stickslip.default_scene()).to_dict()), without_timing(expected))
    same(without_timing(stickslip.run().to_dict()), without_timing(expected))


def test_dotted_overrides_equal_cli_set():
    scene = ROOT / "examples" / "scenes" / "paper_default.toml"
    expected = json.loads(
        cli(
            "run", scene, "--json", "--set", "motor.slider_mass=5e-3",
            "--set", "signal.sqrt_kappa=4",
        ).stdout
    )
    r = stickslip.run(scene, **{"motor.slider_mass": 5e-3, "signal.sqrt_kappa": 4})
    same(without_timing(r.to_dict()), without_timing(expected))
    # The override changed the run: the heavier slider is slower (same scene
    # without it from the CLI).
    plain = json.loads(cli("run", scene, "--json").stdout)
    assert r.v_inf != plain["v_inf"]


def test_result_attributes_are_the_json_values():
    r = stickslip.run(None)
    d = r.to_dict()
    for name in stickslip.INDICATORS:
        assert getattr(r, name) == d.get(name), name
    assert r.regime == d["regime"]
    assert r.error == d["error_estimate"]
    assert r.period == d["period"] and r.f0 == d["f0"]


def test_run_away_is_a_result_with_the_cli_regime():
    # A load beyond the holding force mu_0 F_c / m = 124 m/s^2 pulls the
    # slider away: a physical outcome, reported, not raised.
    expected = json.loads(cli("run", "--json", "--set", "motor.extra_acceleration=-500").stdout)
    r = stickslip.run(None, **{"motor.extra_acceleration": -500.0})
    assert r.regime == expected["regime"] == "run-away"
    same(without_timing(r.to_dict()), without_timing(expected))


def sweep_file(tmp_path: Path, axes: dict) -> Path:
    base = ROOT / "examples" / "scenes" / "paper_default.toml"
    lines = [f'base = "{base.as_posix()}"', "[axes]"]
    for k, v in axes.items():
        lines.append(f"{k} = {json.dumps(v)}")
    path = tmp_path / "grid.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def same_as_csv(frame: pd.DataFrame, path: Path) -> None:
    """Each cell of the CLI's CSV (parsed with `csv` and `float`) equals the
    DataFrame's, to the bit; an empty cell is NaN (or "" in text columns)."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header, body = rows[0], rows[1:]
    assert list(frame.columns) == header
    assert len(frame) == len(body) > 0
    for i, row in enumerate(body):
        for name, cell in zip(header, row):
            value = frame[name].iloc[i]
            if name in ("scene_hash", "regime", "failure"):
                assert value == cell, (i, name)
            elif name == "sigma":
                assert bool(value) == (cell == "true"), (i, name)
            elif cell == "":
                assert math.isnan(value), (i, name, value)
            else:
                assert struct.pack("<d", float(value)) == struct.pack("<d", float(cell)), (
                    i, name, value, cell,
                )


SECTION7 = {"level": [3, 6, 9], "harmonics": [2, 3, 5], "sigma": [False, True]}


def test_sweep_dataframe_equals_cli_csv(tmp_path):
    out = tmp_path / "grid.csv"
    cli("sweep", sweep_file(tmp_path, SECTION7), "--no-timing", "--quiet", "-o", out)
    base = ROOT / "examples" / "scenes" / "paper_default.toml"
    frame = stickslip.sweep(base, SECTION7, timing=False)
    same_as_csv(frame, out)
    assert frame["case"].tolist() == list(range(18))
    assert frame.attrs["stickslip_version"] == stickslip.__version__


def test_sweep_with_timing_has_the_cli_columns(tmp_path):
    out = tmp_path / "grid.csv"
    cli("sweep", sweep_file(tmp_path, {"level": [6]}), "--quiet", "-o", out)
    frame = stickslip.sweep(ROOT / "examples" / "scenes" / "paper_default.toml", {"level": [6]})
    with open(out) as f:
        header = [l for l in f if not l.startswith("#")][0].strip().split(",")
    assert list(frame.columns) == header
    assert {"wall_time_s", "setup_time_s", "simulation_time_s"} <= set(header)


def test_sweep_shard_equals_cli_shard_and_shards_make_the_whole(tmp_path):
    base = ROOT / "examples" / "scenes" / "paper_default.toml"
    out = tmp_path / "grid.2-of-3.csv"
    cli("sweep", sweep_file(tmp_path, SECTION7), "--no-timing", "--quiet", "--shard", "2/3", "-o", out)
    shard = stickslip.sweep(base, SECTION7, shard=(2, 3), timing=False)
    same_as_csv(shard, out)
    assert shard["case"].tolist() == [1, 4, 7, 10, 13, 16]
    whole = stickslip.sweep(base, SECTION7, jobs=1, timing=False)
    parts = pd.concat(
        [stickslip.sweep(base, SECTION7, shard=(i, 3), timing=False) for i in (1, 2, 3)]
    ).sort_values("case", ignore_index=True)
    pd.testing.assert_frame_equal(parts, whole, check_exact=True)


def test_spring_sweep_dataframe_equals_cli_csv(tmp_path):
    scene = tmp_path / "spring.toml"
    scene.write_text(
        '[signal]\nkind = "fourier"\nstroke = 25e-6\nsqrt_kappa = 6.0\nharmonics = 2\n'
        'sigma = true\n[spring]\nstiffness = 1e3\n[outputs]\nindicators = ["friction_energy"]\n'
    )
    axes = {"spring.stiffness": [10.0, 1e3], "spring.preload": [0.0, 0.01]}
    grid = tmp_path / "springs.toml"
    grid.write_text(
        f'base = "{scene.as_posix()}"\n[axes]\n'
        + "".join(f"{k} = {json.dumps(v)}\n" for k, v in axes.items())
    )
    out = tmp_path / "springs.csv"
    cli("sweep", grid, "--no-timing", "--quiet", "-o", out)
    frame = stickslip.sweep(scene, axes, timing=False)
    same_as_csv(frame, out)
    assert frame["spring.stiffness"].tolist() == [10.0, 10.0, 1e3, 1e3]
    assert frame["spring_force_mean"].notna().all()


def test_trajectory_equals_cli_trajectory(tmp_path):
    scene = ROOT / "examples" / "scenes" / "stick_heavy.toml"
    r = stickslip.run(scene)
    times = np.linspace(0.0, 5 * r.period, 401)
    (tmp_path / "times.txt").write_text("\n".join(repr(float(t)) for t in times) + "\n")
    cli("run", scene, "--trajectory", tmp_path / "traj.csv", "--times", tmp_path / "times.txt")
    frame = r.trajectory(times)
    with open(tmp_path / "traj.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert list(frame.columns) == rows[0] == ["t", "x_R", "v_R", "a_R", "x_S", "v_S", "mode"]
    assert len(rows) - 1 == len(frame) == len(times)
    for i, row in enumerate(rows[1:]):
        for name, cell in zip(rows[0], row):
            value = frame[name].iloc[i]
            if name == "mode":
                assert value == cell
            else:
                assert struct.pack("<d", value) == struct.pack("<d", float(cell)), (i, name)
    assert frame["x_S"].dtype == np.float64
    # The times are the ones given, not resampled.
    assert np.array_equal(frame["t"].to_numpy(), times)


def test_periods_equal_cli_periods_series(tmp_path):
    scene = ROOT / "examples" / "scenes" / "paper_default.toml"
    cli("run", scene, "--periods-series", tmp_path / "p.csv")
    frame = stickslip.run(scene).periods()
    with open(tmp_path / "p.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert list(frame.columns) == rows[0]
    assert len(frame) == len(rows) - 1 > 1
    for i, row in enumerate(rows[1:]):
        for name, cell in zip(rows[0], row):
            value = frame[name].iloc[i]
            if name == "event_kinds":
                assert value == cell
            else:
                assert struct.pack("<d", float(value)) == struct.pack("<d", float(cell)), (i, name)
    assert frame["p"].dtype == np.int64 and frame["p"].tolist() == list(range(1, len(frame) + 1))


def test_events_are_the_counted_events_of_the_start_up():
    r = stickslip.run(ROOT / "examples" / "scenes" / "stick_heavy.toml")
    events = r.events()
    assert events.attrs["omitted"] == 0
    counted = {k: v for k, v in r.to_dict()["events"].items() if v}
    assert events["kind"].value_counts().to_dict() == counted
    # time = (period - 1) T + phase, events in time order
    assert np.all(np.diff(events["time"].to_numpy()) >= 0)
    assert np.allclose(events["time"], (events["period"] - 1) * r.period + events["phase"], rtol=1e-15, atol=0)


def test_signal_equals_cli_signal_json():
    scene = ROOT / "examples" / "scenes" / "harmonics.toml"
    same(stickslip.signal(scene), json.loads(cli("signal", scene, "--json").stdout))


def test_characteristic_equals_cli_characteristic_json():
    expected = json.loads(cli("characteristic", "--json", "--quiet", "--from", "-0.1", "--to", "0.1").stdout)
    got = stickslip.characteristic(range=(-0.1, 0.1))
    assert TIMING & set(got) == TIMING & set(expected)
    same(without_timing(got), without_timing(expected))


def test_compare_of_the_exact_trajectory_passes_with_zero_error(tmp_path):
    r = stickslip.run(None)
    frame = r.trajectory(np.linspace(0.0, 20 * r.period, 2001))
    report = stickslip.compare(None, frame[["t", "x_S", "v_S"]])
    # The same exact solution on both sides: the verdict passes.
    assert report["pass"] is True
    # The same numbers from a file through the command line.
    frame[["t", "x_S", "v_S"]].to_csv(tmp_path / "mine.csv", index=False, float_format="%.17g")
    (tmp_path / "scene.toml").write_text(cli("default-scene").stdout)
    p = cli("compare", tmp_path / "scene.toml", tmp_path / "mine.csv", "--json", ok=False)
    expected = json.loads(p.stdout)
    assert report["pass"] == expected["pass"]


BAD = [
    ("[motor]\nslider_mass = -1.0\n", []),
    ("[motor]\nslider_mas = 1e-3\n", []),
    ("[signal]\nkind = \"fourier\"\nstroke = 25e-6\nsqrt_kappa = 6\nkappa = 36\n", []),
    ("", ["motor.mu_dynamic=0.5"]),
]


@pytest.mark.parametrize("text,sets", BAD, ids=["negative", "unknown-key", "two-drives", "override"])
def test_bad_input_raises_scene_error_with_the_cli_message(tmp_path, text, sets):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    args = [a for s in sets for a in ("--set", s)]
    message = cli_error("run", path, *args)
    overrides = {}
    for s in sets:
        key, value = s.split("=", 1)
        overrides[key] = float(value)
    with pytest.raises(stickslip.SceneError) as e:
        stickslip.run(str(path), **overrides)
    assert str(e.value) == message
    assert isinstance(e.value, ValueError)
    assert "\n" not in str(e.value)


def test_missing_scene_file_raises_scene_error_with_the_cli_message(tmp_path):
    path = tmp_path / "nothing.toml"
    message = cli_error("run", path)
    with pytest.raises(stickslip.SceneError, match="^" + message.split(":")[0]) as e:
        stickslip.run(path)
    assert str(e.value) == message


def test_bad_sweep_axis_raises_scene_error():
    with pytest.raises(stickslip.SceneError, match="axes.level"):
        stickslip.sweep(None, {"level": [6, 6]})
    with pytest.raises(stickslip.SceneError, match="shard"):
        stickslip.sweep(None, {"level": [6]}, shard=(4, 3))


def test_bad_times_raise_scene_error():
    r = stickslip.run(None)
    with pytest.raises(stickslip.SceneError, match=r"times\[1\]"):
        r.trajectory([0.0, float("nan")])
    with pytest.raises(stickslip.SceneError, match=r"times\[2\]"):
        r.trajectory([0.0, 2e-5, 1e-5])


def test_help_of_run_explains_scene_overrides_and_result():
    text = stickslip.run.__doc__
    for word in ("scene", "overrides", "SceneError", "to_dict", "trajectory"):
        assert word in text
