"""The Python snippets of ``stickslip signal`` evaluate to the JSON's values.

``stickslip signal --voltage --python`` defines ``u(t)`` with numpy, and
``stickslip signal --python`` defines ``x_R(t)`` and ``v_R(t)``. Each is
run here and evaluated at many times (an array, and a scalar), and
compared with the same series rebuilt from the command's ``--json`` with
Python's ``math`` (an independent evaluation: scalar, term by term), to
rounding of the largest term (``1e-13`` of the amplitude sum). The
snippets need numpy, which is why this test lives here and not with the
Rust tests. The binary is found as ``cli_binary`` says; without it these
tests fail: they never skip.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from cli_binary import ROOT, cli

SCENES = {
    "default": [],
    "harmonics": [ROOT / "examples" / "scenes" / "harmonics.toml"],
    # x_R(0) != 0: the voltage of a signal not at rest at t = 0.
    "unshifted": [
        ROOT / "examples" / "scenes" / "harmonics.toml",
        "--set",
        "signal.shift_to_minimum=false",
    ],
}


def series(obj: dict, t: float, derivative: int = 0) -> float:
    """``c0 + sum_k a_k sin(k w t + phi_k)`` (or its first derivative)."""
    w = 2 * math.pi / obj["period"]
    total = obj["offset"] if derivative == 0 else 0.0
    for h in obj["harmonics"]:
        kw = h["k"] * w
        arg = kw * t + h["phase"]
        total += h["amplitude"] * (math.sin(arg) if derivative == 0 else kw * math.cos(arg))
    return total


def snippet(*args: object) -> dict:
    namespace: dict = {}
    exec(cli("signal", *args, "--python").stdout, namespace)
    return namespace


def times(period: float) -> np.ndarray:
    # Three periods, so that the snippet's periodicity is checked too.
    return np.linspace(0.0, 3.0 * period, 301)


def agree(got, expected: list, scale: float, what: str) -> None:
    got = np.asarray(got, dtype=float)
    assert got.shape == (len(expected),), (what, got.shape)
    worst = max(abs(g - e) for g, e in zip(got.tolist(), expected))
    assert worst <= 1e-13 * scale, (what, worst, scale)


@pytest.mark.parametrize("scene", list(SCENES.values()), ids=list(SCENES))
def test_voltage_snippet_evaluates_to_the_json_voltage(scene):
    v = json.loads(cli("signal", *scene, "--voltage", "--json").stdout)
    ns = snippet(*scene, "--voltage")
    scale = abs(v["offset"]) + sum(h["amplitude"] for h in v["harmonics"])
    t = times(v["period"])
    agree(ns["u"](t), [series(v, x) for x in t.tolist()], scale, "u")
    # A scalar gives a scalar.
    t1 = 0.37 * v["period"]
    assert np.ndim(ns["u"](t1)) == 0
    assert abs(float(ns["u"](t1)) - series(v, t1)) <= 1e-13 * scale
    assert ns["u_peak"] == v["peak"] and ns["u_rms"] == v["rms"]
    assert ns["T"] == v["period"] and ns["u0"] == v["offset"]


@pytest.mark.parametrize("scene", list(SCENES.values()), ids=list(SCENES))
def test_signal_snippet_evaluates_to_the_json_signal(scene):
    x = json.loads(cli("signal", *scene, "--json").stdout)
    ns = snippet(*scene)
    t = times(x["period"])
    amplitudes = sum(h["amplitude"] for h in x["harmonics"])
    speeds = sum(h["k"] * h["amplitude"] for h in x["harmonics"]) * 2 * math.pi / x["period"]
    agree(ns["x_R"](t), [series(x, s) for s in t.tolist()], abs(x["offset"]) + amplitudes, "x_R")
    agree(ns["v_R"](t), [series(x, s, 1) for s in t.tolist()], speeds, "v_R")
