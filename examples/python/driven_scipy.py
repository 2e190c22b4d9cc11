"""The driven rod (docs/model.md section 16) solved by a general-purpose
stiff solver with event location, beside the exact engine: a benchmark,
not a test.

    python3 examples/python/driven_scipy.py [--scene FILE] [--set KEY=VALUE ...]
        [--no-reaction] [--method LSODA] [--rtol 1e-10]
        [--periods N | --engine-periods] [--binary path/to/stickslip]

The scene (by default examples/scenes/paper_default.toml, the paper's
default; ``--set`` changes a field as ``stickslip run --set`` does) is
run with ``[actuator] rod = "driven"`` (and ``reaction = false`` with
``--no-reaction``) by ``stickslip run --json``,
which gives ``v_inf``, the periods its start-up took and its wall time,
and by ``stickslip signal --voltage --json``, which gives the voltage
``u(t) = u0 + sum_k u_k sin(k w t + phi_k)``. The script then solves

    slip, direction s:  M x'' + d x' + c x = alpha u(t) - s mu_d F_c,  v_S' = s a_d + g_t
    stick:              (M + m_s) x'' + d x' + c x = alpha u(t) + m_s g_t,  v_S = x'
    (without the reaction the rod's equation is M x'' + d x' + c x = alpha u(t) in every mode)

with ``scipy.integrate.solve_ivp`` (LSODA by default, which detects
stiffness; or Radau, BDF; ``rtol = 1e-10``,
``atol`` the same relative to the stroke and the velocity ``stroke w``),
from rest, as a state machine over the modes: each mode is integrated up
to its first event, located by solve_ivp on its dense output (slip: the
zero of ``v_rel = x' - v_S``; stick: the stuck system's acceleration
leaving ``[a_0^-, a_0^+]``), and the integration restarts there in the
mode the friction law of docs/model.md section 1 gives (``a_st`` for
``a_R``), and at every period start. It runs until the mean velocity per
period has settled (to ``1e-6`` relative over the last 20 periods), or
``--periods N``, or as many periods as the exact engine simulated
(``--engine-periods``), and prints its wall time, the periods, events and
its ``v_inf`` (the last period's mean velocity) against the engine's.

The binary: ``--binary``, else ``$CARGO_TARGET_DIR/release/stickslip``,
else ``target/release/stickslip`` (``cargo build --release`` first).
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[2]
STICK, FORWARD, BACKWARD = "stick", "forward", "backward"


def binary(given):
    if given:
        return Path(given)
    target = Path(os.environ.get("CARGO_TARGET_DIR") or ROOT / "target")
    return target / "release" / "stickslip"


def stickslip(bin_path, *args):
    """Runs the binary and returns its JSON and the process wall time."""
    start = time.perf_counter()
    out = subprocess.run([str(bin_path), *args, "--json"], capture_output=True, text=True)
    elapsed = time.perf_counter() - start
    if out.returncode != 0:
        sys.exit(f"stickslip {' '.join(args)} failed: {out.stderr.strip()}")
    return json.loads(out.stdout), elapsed


class Model:
    """The driven rod and the slider of a scene, as `stickslip run` read it."""

    def __init__(self, scene, voltage):
        motor, act = scene["motor"], scene["actuator"]
        real = act.get("real", {})
        self.M = real.get("mass", act["mass"])
        self.d = real.get("damping", act["damping"])
        self.c = real.get("stiffness", act["stiffness"])
        self.alpha = real.get("transfer_factor", act["transfer_factor"])
        self.reaction = act.get("reaction", True)
        ms, fc = motor["slider_mass"], motor["contact_force"]
        self.ms, self.g = ms, motor["extra_acceleration"]
        self.friction = motor["mu_dynamic"] * fc
        a0, ad = motor["mu_static"] * fc / ms, self.friction / ms
        self.a_plus, self.a_minus = a0 + self.g, -a0 + self.g
        self.slip = {FORWARD: ad + self.g, BACKWARD: -ad + self.g}
        self.period = voltage["period"]
        self.w = 2.0 * np.pi / self.period
        self.u0 = voltage["offset"]
        self.k = np.array([h["k"] for h in voltage["harmonics"]], dtype=float)
        self.uk = np.array([h["amplitude"] for h in voltage["harmonics"]])
        self.phik = np.array([h["phase"] for h in voltage["harmonics"]])

    def u(self, t):
        return self.u0 + float(np.dot(self.uk, np.sin(self.k * self.w * t + self.phik)))

    def mass_force(self, mode):
        """The rod's mass and the constant force on it in `mode`."""
        if not self.reaction:
            return self.M, 0.0
        if mode == STICK:
            return self.M + self.ms, self.ms * self.g
        sign = 1.0 if mode == FORWARD else -1.0
        return self.M, -sign * self.friction

    def a_rod(self, mode, t, x, v):
        m, f = self.mass_force(mode)
        return (self.alpha * self.u(t) + f - self.d * v - self.c * x) / m

    def rhs(self, mode):
        if mode == STICK:

            def f(t, y):
                a = self.a_rod(STICK, t, y[0], y[1])
                return [y[1], a, y[1], a]

        else:
            a_s = self.slip[mode]

            def f(t, y):
                return [y[1], self.a_rod(mode, t, y[0], y[1]), y[3], a_s]

        return f

    def events(self, mode):
        """The terminal events of `mode`, each with the mode it leads to
        (None: decided by the band at the event)."""
        if mode == STICK:

            def up(t, y):
                return self.a_rod(STICK, t, y[0], y[1]) - self.a_plus

            def down(t, y):
                return self.a_rod(STICK, t, y[0], y[1]) - self.a_minus

            up.terminal, up.direction = True, 1.0
            down.terminal, down.direction = True, -1.0
            return [(up, FORWARD), (down, BACKWARD)]

        def zero(t, y):
            return y[1] - y[3]

        zero.terminal = True
        zero.direction = -1.0 if mode == FORWARD else 1.0
        return [(zero, None)]

    def at_rest(self, t, y):
        """The mode of a slider at rest on the rod: the band of a_st."""
        a = self.a_rod(STICK, t, y[0], y[1])
        if a > self.a_plus:
            return FORWARD
        if a < self.a_minus:
            return BACKWARD
        return STICK


def simulate(model, method, rtol, periods, settle, stroke):
    scales = np.array([stroke, stroke * model.w, stroke, stroke * model.w])
    atol = rtol * scales
    y = np.zeros(4)
    mode = model.at_rest(0.0, y)
    t, events, velocities = 0.0, 0, []
    p = 0
    while p < periods:
        p += 1
        end = p * model.period
        x_start = y[2]
        while t < end:
            evs = model.events(mode)
            sol = solve_ivp(
                model.rhs(mode),
                (t, end),
                y,
                method=method,
                rtol=rtol,
                atol=atol,
                events=[e for e, _ in evs],
            )
            if sol.status == -1:
                sys.exit(f"solve_ivp failed at t = {t}: {sol.message}")
            hit = [i for i, te in enumerate(sol.t_events) if len(te) > 0]
            if not hit:
                t, y = end, sol.y[:, -1].copy()
                continue
            i = min(hit, key=lambda j: sol.t_events[j][0])
            t, y = sol.t_events[i][0], sol.y_events[i][0].copy()
            events += 1
            after = evs[i][1] or model.at_rest(t, y)
            if after == STICK:
                y[3] = y[1]
            mode = after
        velocities.append((y[2] - x_start) / model.period)
        if settle and len(velocities) > 20:
            last = velocities[-21:]
            if max(abs(v - last[-1]) for v in last) <= 1e-6 * abs(last[-1]):
                break
    return velocities, events


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=str(ROOT / "examples/scenes/paper_default.toml"))
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    parser.add_argument("--no-reaction", action="store_true")
    parser.add_argument("--method", default="LSODA")
    parser.add_argument("--rtol", type=float, default=1e-10)
    parser.add_argument("--periods", type=int)
    parser.add_argument("--engine-periods", action="store_true")
    parser.add_argument("--binary")
    args = parser.parse_args()
    bin_path = binary(args.binary)
    sets = [a for kv in args.set for a in ("--set", kv)] + ["--set", "actuator.rod=driven"]
    if args.no_reaction:
        sets += ["--set", "actuator.reaction=false"]
    run, process = stickslip(bin_path, "run", args.scene, *sets)
    voltage, _ = stickslip(bin_path, "signal", args.scene, "--voltage", *sets)
    scene = run["scene"]
    model = Model(scene, voltage)
    engine_periods = run["work"]["periods"]
    periods = args.periods or (engine_periods if args.engine_periods else 1_000_000)
    settle = args.periods is None and not args.engine_periods
    start = time.perf_counter()
    velocities, events = simulate(
        model, args.method, args.rtol, periods, settle, scene["signal"]["stroke"]
    )
    wall = time.perf_counter() - start
    v_scipy, v_exact = velocities[-1], run["v_inf"]
    reaction = "without" if args.no_reaction else "with"
    print(f"{Path(args.scene).name}, rod driven {reaction} the reaction")
    print(
        f"  stickslip run: v_inf = {v_exact:.12e} m/s, {engine_periods} periods, "
        f"{run['work']['events']} events; run {run['wall_time_s'] * 1e3:.1f} ms, "
        f"whole process {process * 1e3:.1f} ms"
    )
    print(
        f"  scipy solve_ivp ({args.method}, rtol {args.rtol:g}): v_inf = {v_scipy:.12e} m/s "
        f"(last period's mean velocity), {len(velocities)} periods, {events} events; "
        f"{wall:.2f} s"
    )
    print(
        f"  v_inf differs by {abs(v_scipy - v_exact) / abs(v_exact):.2e} (relative); "
        f"time per period {wall / len(velocities) * 1e3:.2f} ms against "
        f"{run['wall_time_s'] / engine_periods * 1e6:.2f} us; whole run {wall / run['wall_time_s']:.0f} "
        f"times the engine's"
    )


if __name__ == "__main__":
    main()
