#!/usr/bin/env python3
"""Independent fixed-step simulation of the paper's motor for the tests of
`stickslip compare`.

It shares no code with stickslip: the rod signal is rebuilt here from the
formulas of docs/model.md section 2 (Fourier coefficients (12)-(14) of the
continuous ideal signal, sigma factors (15), stroke scaling, shift of the
minimum to t = 0) and the slider is moved by an explicit fixed-step
stick-slip integrator in the style of the paper's own simulations.

Scene: the default scene (docs/model.md section 6): m_s = 1.4 g, F_c = 1 N,
mu_0 = 0.1736, mu_d = 0.1568; fourier signal, n = 2 harmonics, sigma
factors, sqrt(kappa) = 6, stroke 25 um, duty 1.

Outputs, for every resolution S (steps per period of the highest harmonic,
step h = T / (n S)):

  fixed_S.csv   columns t, x_S, v_S over the first period (every step,
                t = 0 .. T) and the per-period series p, v_p of the whole
                run (PERIODS periods); the shorter columns end early, with
                empty cells below. fixed_5000.csv also has x_R.
  fixed_5000.mat  the same variables as fixed_5000.csv, written by
                scipy.io.savemat (a MATLAB Level 5 file).
  rod_no_shift.csv, rod_wrong_phase.csv, rod_unscaled.csv
                t, x_R of one period of a wrongly built rod signal: the
                series without the shift of the minimum to t = 0, with the
                phases of the harmonics negated, and without stroke scaling.

Exports as users make them (`python3 generate.py exports` writes only
these; `main` below says how each is laid out):

  trajectory_500.csv  the S = 500 run stopped after EXPORT_PERIODS = 300
                periods, before its start-up ends (p_0.99 = 388): only the
                trajectories t, x_S, v_S, every EXPORT_EVERY = 13th step
                (a "To Workspace" block with decimation 13) and at the stop
                time, so that most period ends fall between samples. The same run as
                fixed_500.csv: its v_p of period 300 is that file's.
  simulink_500.mat  the same samples as Simulink's "Structure with time"
                writes them from two "To Workspace" blocks named x_S and
                v_S (each a struct with time, signals.values,
                signals.dimensions, signals.label, blockName), with tout.
  simulink_array.mat  the first period of the S = 500 run in Simulink's
                "Array" layout (simout = [t, x_S, v_S], one row a sample)
                and as a matrix with named columns (data with colheaders,
                as MATLAB's importdata returns it).
  simulink_scope.mat  the same first period as a Scope's "Structure with
                time": ScopeData with time and a struct array of two
                signals labelled x_S and v_S.

Run once with `python3 generate.py` in this directory (needs numpy and
scipy); it takes a few minutes. The files committed were written with
numpy 2.4.6 and scipy 1.17.1 (the exports) and by earlier versions (the
rest).
"""
import sys

import math

import numpy as np
import scipy.io

# The paper's motor (docs/model.md section 6).
M_S = 1.4e-3
F_C = 1.0
MU_0 = 0.1736
MU_D = 0.1568
A_0 = MU_0 * F_C / M_S  # break-away acceleration
A_D = MU_D * F_C / M_S  # sliding acceleration

# The default signal.
N_HARM = 2
KAPPA = 36.0
STROKE = 25e-6

# Twenty-one resolutions spread evenly over a decade on a log scale: a
# fixed-step error scatters with where the events fall on the time grid,
# so an observed order needs many of them.
RESOLUTIONS = [round(500 * 10 ** (k / 20)) for k in range(21)]
# The start-up has converged to rounding well before (docs/model.md
# section 6: p_0.99 = 388).
PERIODS = 1200


def coefficients():
    """a_k, b_k of the continuous ideal signal (12)-(14) with t_1 = T, times
    the sigma factors (15); the period T."""
    a_r = KAPPA * A_0
    period = math.sqrt(2.0 * STROKE / a_r)  # t_1 = T for duty 1
    a, b = [], []
    for k in range(1, N_HARM + 1):
        sigma = math.sin(k * math.pi / (N_HARM + 1)) / (k * math.pi / (N_HARM + 1))
        a.append(sigma * a_r * period**2 / (2.0 * math.pi**2 * k**2))
        b.append(sigma * -a_r * period**2 / (2.0 * math.pi * k))
    return np.array(a), np.array(b), period


def series(a, b, period, t, derivative=0):
    """sum_k a_k cos(k w t) + b_k sin(k w t), or its derivative."""
    w = 2.0 * math.pi / period
    out = np.zeros_like(t, dtype=float)
    for k in range(1, len(a) + 1):
        kw = k * w
        c, s = np.cos(kw * t), np.sin(kw * t)
        if derivative == 0:
            out += a[k - 1] * c + b[k - 1] * s
        elif derivative == 1:
            out += kw * (-a[k - 1] * s + b[k - 1] * c)
        else:
            out += kw * kw * (-a[k - 1] * c - b[k - 1] * s)
    return out


def velocity_roots(a, b, period):
    """All zeros of v_R in one period: sign changes on a fine grid, then
    bisection to rounding."""
    grid = np.linspace(0.0, period, 20001)
    v = series(a, b, period, grid, 1)
    roots = []
    for i in range(len(grid) - 1):
        if v[i] == 0.0 or v[i] * v[i + 1] < 0.0:
            lo, hi = grid[i], grid[i + 1]
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                vm = series(a, b, period, np.array([mid]), 1)[0]
                vl = series(a, b, period, np.array([lo]), 1)[0]
                if vl * vm <= 0.0:
                    hi = mid
                else:
                    lo = mid
                if hi - lo <= 1e-17 * period:
                    break
            roots.append(0.5 * (lo + hi))
    return roots


class Rod:
    """The rod signal x_R(t) = offset + sum_k a_k cos(k w (t + shift)) +
    b_k sin(k w (t + shift)), built like docs/model.md section 2."""

    def __init__(self, scale=True, shift=True, phase_sign=1.0):
        a, b, period = coefficients()
        if phase_sign < 0:
            # d_k sin(k w t + phi_k) -> d_k sin(k w t - phi_k): with
            # d sin(x + phi) = a cos x + b sin x (a = d sin phi, b = d cos phi)
            # negating phi negates a.
            a = -a
        self.period = period
        extrema = velocity_roots(a, b, period)
        values = series(a, b, period, np.array(extrema))
        if scale:
            factor = STROKE / (values.max() - values.min())
            a, b = a * factor, b * factor
            values = values * factor
        i_min = int(np.argmin(values))
        self.shift = extrema[i_min] if shift else 0.0
        self.offset = -values[i_min] if shift else 0.0
        self.a, self.b = a, b

    def x(self, t):
        return self.offset + series(self.a, self.b, self.period, t + self.shift)

    def v(self, t):
        return series(self.a, self.b, self.period, t + self.shift, 1)

    def acc(self, t):
        return series(self.a, self.b, self.period, t + self.shift, 2)


# The exports (see the module doc).
EXPORT_RESOLUTION = 500
EXPORT_PERIODS = 300
EXPORT_EVERY = 13


def simulate(rod, steps_per_harmonic, periods, every=1, record_periods=1):
    """Explicit fixed-step stick-slip integration from rest.

    Per step of length h from t_i to t_{i+1}:
    * stick: the slider follows the rod (x_S and v_S take the rod's
      increments); it breaks away at the first step point where a_R lies
      outside [-a_0, a_0], slipping in the direction of a_R;
    * slip: constant acceleration +-a_d in the direction of v_R - v_S at
      t_i; when v_R - v_S changes sign over the step it sticks if
      |a_R(t_{i+1})| <= a_0 (and v_S snaps to v_R), else it slips on the
      other way.
    Returns the samples (t, x_S, v_S) of the first `record_periods`
    periods at every `every`-th step (t = k h for step k) and at their
    end (a logged run ends with its stop time), the per-period
    mean velocities v_p = (x_S(pT) - x_S((p-1)T)) / T and the rod
    positions of the first period.
    """
    n = N_HARM * steps_per_harmonic
    period = rod.period
    h = period / n
    t_grid = np.arange(n + 1) * h
    x_r = rod.x(t_grid).tolist()
    v_r = rod.v(t_grid).tolist()
    a_r = rod.acc(t_grid).tolist()
    x_s, v_s = 0.0, 0.0
    if abs(a_r[0]) <= A_0:
        mode = 0
    else:
        mode = 1 if a_r[0] > 0 else -1
    samples_t, samples_x, samples_v = [0.0], [x_s], [v_s]
    v_p = []
    half_h2 = 0.5 * h * h
    for p in range(periods):
        x_start = x_s
        for i in range(n):
            if mode == 0:
                x_s += x_r[i + 1] - x_r[i]
                v_s = v_r[i + 1]
                a_next = a_r[i + 1]
                if a_next > A_0:
                    mode = 1
                elif a_next < -A_0:
                    mode = -1
            else:
                acc = A_D if mode > 0 else -A_D
                x_s += v_s * h + acc * half_h2
                v_s += acc * h
                rel = v_r[i + 1] - v_s
                if (rel <= 0.0) if mode > 0 else (rel >= 0.0):
                    a_next = a_r[i + 1]
                    if abs(a_next) <= A_0:
                        mode = 0
                        v_s = v_r[i + 1]
                    else:
                        mode = -mode
            k = p * n + i + 1
            last = p == record_periods - 1 and i == n - 1
            if p < record_periods and (k % every == 0 or last):
                samples_t.append(k * h)
                samples_x.append(x_s)
                samples_v.append(v_s)
        v_p.append((x_s - x_start) / period)
    return (
        np.array(samples_t),
        np.array(samples_x),
        np.array(samples_v),
        np.array(v_p),
        x_r,
    )


def write_columns(path, columns, fmt="%.17g"):
    """CSV with a header; shorter columns end early (empty cells)."""
    names = list(columns)
    rows = max(len(c) for c in columns.values())
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for i in range(rows):
            cells = []
            for name in names:
                col = columns[name]
                cells.append(fmt % col[i] if i < len(col) else "")
            f.write(",".join(cells) + "\n")


def simulink_struct(name, t, values):
    """A "To Workspace" block's "Structure with time" (scipy writes a dict
    as a MATLAB struct, a str as a char array)."""
    return {
        "time": t.reshape(-1, 1),
        "signals": {
            "values": values.reshape(-1, 1),
            "dimensions": 1.0,
            "label": "",
        },
        "blockName": f"stickslip_check/{name}",
    }


def exports(rod):
    t, x_s, v_s, v_p, _ = simulate(
        rod, EXPORT_RESOLUTION, EXPORT_PERIODS, EXPORT_EVERY, EXPORT_PERIODS
    )
    write_columns(
        f"trajectory_{EXPORT_RESOLUTION}.csv", {"t": t, "x_S": x_s, "v_S": v_s}, "%.15g"
    )
    scipy.io.savemat(
        f"simulink_{EXPORT_RESOLUTION}.mat",
        {
            "x_S": simulink_struct("x_S", t, x_s),
            "v_S": simulink_struct("v_S", t, v_s),
            "tout": t.reshape(-1, 1),
        },
        do_compression=True,
        oned_as="column",
    )
    print(f"exports: v_p({EXPORT_PERIODS}) = {float(v_p[-1])!r} m/s")
    t, x_s, v_s, _, _ = simulate(rod, EXPORT_RESOLUTION, 1)
    scipy.io.savemat(
        "simulink_array.mat",
        {
            "simout": np.column_stack([t, x_s, v_s]),
            "table": {
                "data": np.column_stack([t, x_s, v_s]),
                "colheaders": np.array(["t", "x_S", "v_S"], dtype=object).reshape(1, 3),
            },
        },
        do_compression=True,
    )
    signals = np.empty((1, 2), dtype=[("values", object), ("dimensions", object), ("label", object)])
    signals[0, 0] = (x_s.reshape(-1, 1), 1.0, "x_S")
    signals[0, 1] = (v_s.reshape(-1, 1), 1.0, "v_S")
    scipy.io.savemat(
        "simulink_scope.mat",
        {
            "ScopeData": {
                "time": t.reshape(-1, 1),
                "signals": signals,
                "blockName": "stickslip_check/Scope",
            }
        },
        do_compression=True,
    )


def main():
    rod = Rod()
    if sys.argv[1:] == ["exports"]:
        exports(rod)
        return
    exports(rod)
    for s in RESOLUTIONS:
        t, x_s, v_s, v_p, x_r = simulate(rod, s, PERIODS)
        columns = {"t": t, "x_S": x_s, "v_S": v_s}
        if s == 5000:
            columns["x_R"] = np.array(x_r)
        columns["p"] = np.arange(1, PERIODS + 1, dtype=float)
        columns["v_p"] = v_p
        # The file with a MAT twin keeps every bit (17 digits); the others
        # keep 10, far below the errors they carry.
        write_columns(f"fixed_{s}.csv", columns, "%.17g" if s == 5000 else "%.10g")
        if s == 5000:
            scipy.io.savemat(
                "fixed_5000.mat",
                {k: np.asarray(v, dtype=float) for k, v in columns.items()},
                do_compression=True,
            )
        print(f"S = {s}: v_p({PERIODS}) = {float(v_p[-1])!r} m/s")
    # Wrongly built rod signals, one period at 500 steps per harmonic.
    t = np.arange(N_HARM * 500 + 1) * (rod.period / (N_HARM * 500))
    for name, wrong in [
        ("rod_no_shift", Rod(shift=False)),
        ("rod_wrong_phase", Rod(phase_sign=-1.0)),
        ("rod_unscaled", Rod(scale=False)),
    ]:
        write_columns(f"{name}.csv", {"t": t, "x_R": wrong.x(t)}, "%.12g")


if __name__ == "__main__":
    main()
