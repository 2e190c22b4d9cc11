"""Overhead of the Python package over the Rust library and the command line.

    python examples/python/bench.py [path/to/stickslip]

Prints medians and their differences (a benchmark, not a test):

* ``stickslip.run`` of the default scene (given as ``default_scene()``,
  a dict, and as None) against the same run in Rust in the same process
  (``simulate(&Scene::default())``); the aim is at most 50 us more;
* ``stickslip.sweep`` of the section-7 grid (examples/sweeps/section7.toml,
  70 cases) against ``stickslip sweep`` of that file; the aim is at most
  10 % more time.
"""

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import stickslip
from stickslip import _stickslip

ROOT = Path(__file__).resolve().parents[2]


def median_time(f, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    target = Path(os.environ.get("CARGO_TARGET_DIR") or ROOT / "target")
    binary = Path(sys.argv[1]) if len(sys.argv) > 1 else target / "release" / "stickslip"

    repeats = 2000
    scene = stickslip.default_scene()
    for _ in range(50):
        stickslip.run(scene)
    rust = _stickslip.time_default_run(repeats)
    py_dict = median_time(lambda: stickslip.run(scene), repeats)
    py_none = median_time(lambda: stickslip.run(), repeats)
    py_value = median_time(lambda: stickslip.run(scene).v_inf, repeats)
    print(f"run, default scene ({repeats} runs each, medians):")
    print(f"  Rust simulate(&Scene::default())  {rust * 1e6:8.1f} us")
    print(f"  stickslip.run(default_scene())    {py_dict * 1e6:8.1f} us  (+{(py_dict - rust) * 1e6:.1f} us)")
    print(f"  stickslip.run()                   {py_none * 1e6:8.1f} us  (+{(py_none - rust) * 1e6:.1f} us)")
    print(f"  stickslip.run(...).v_inf          {py_value * 1e6:8.1f} us  (+{(py_value - rust) * 1e6:.1f} us)")

    sweep_file = ROOT / "examples" / "sweeps" / "section7.toml"
    base = ROOT / "examples" / "scenes" / "paper_default.toml"
    axes = {"level": [3, 6, 9, 12, 15], "harmonics": [2, 3, 4, 5, 6, 7, 8], "sigma": [False, True]}
    indicators = ["v_inf", "startup_time", "smoothness", "durability",
                  "friction_energy", "stiction_fraction", "velocity_per_power"]
    with tempfile.TemporaryDirectory() as tmp:
        def cli():
            out = Path(tmp) / "section7.csv"
            if out.exists():
                out.unlink()
            subprocess.run(
                [str(binary), "sweep", str(sweep_file), "--no-timing", "--quiet", "-o", str(out)],
                check=True,
                stderr=subprocess.DEVNULL,
            )

        def python():
            stickslip.sweep(base, axes, indicators=indicators, timing=False)

        cli()
        python()
        sweeps = 7
        t_cli = median_time(cli, sweeps)
        t_py = median_time(python, sweeps)
    print(f"sweep, section-7 grid (70 cases, {sweeps} sweeps each, medians):")
    print(f"  stickslip sweep (command line)    {t_cli * 1e3:8.1f} ms")
    print(f"  stickslip.sweep (Python)          {t_py * 1e3:8.1f} ms  ({(t_py / t_cli - 1) * 100:+.1f} %)")


if __name__ == "__main__":
    main()
