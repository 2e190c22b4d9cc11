#!/usr/bin/env python3
"""Independent reference: the slider of an inertia drive against a spring.

What it computes
----------------
The rod's motion x_R(t) is prescribed (docs/model.md section 1, the rod as an
input): a finite Fourier series read from the JSON that `stickslip signal
--json` prints (docs/interface.md), committed next to this script as
``spring_reference_signal_<scene>.json``::

    x_R(t) = offset + sum_k amplitude_k sin(k w0 t + phase_k),   w0 = 2 pi / period

(amplitudes and phases already carry the sigma factors, the stroke scaling and
the time shift: x_R(0) = 0, v_R(0) = 0, max - min = stroke; the script checks
all three). The motor (slider mass m_s, contact force F_c, mu_0, mu_d, g_t) is
read from the ``[motor]`` table of ``spring_reference_scene.toml``, the output
of `stickslip default-scene`.

The slider (mass m_s, position x_S, velocity v_S) obeys

    m_s a_S = F_f + m_s g_t - F_spring
    slip:  F_f = mu_d F_c sign(v_R - v_S)
    stick: v_S = v_R, held while |F_f| = |m_s (a_R - g_t) + F_spring| <= mu_0 F_c

    tied spring:       F_spring = F_p + k (x_S - x_p) + b v_S        (always)
    free-ended spring: F_spring = k (x_S - gap) while x_S >= gap, else 0

with the transitions of docs/model.md section 1: a stuck slider slips forward
(backward) when the friction force needed to hold it, f = m_s (a_R - g_t) +
F_spring, exceeds +mu_0 F_c (falls below -mu_0 F_c); a slipping slider, when
v_rel = v_R - v_S reaches zero, sticks if |f| <= mu_0 F_c there, else slips
the other way (a reversal). The slider starts at rest at x_S = 0 with the rod
at rest at x_R(0) = 0; the mode at t = 0+ follows from f(0) like any stick
phase.

Method (no code, formula or closed form of the Rust engine is used)
-------------------------------------------------------------------
Time is kept as (period index, phase tau in [0, T)); the rod is evaluated at
the phase.

* Slip: the state (x_S, v_S) and the running integrals of x_S, F_spring and
  of the contact indicator are integrated numerically with scipy's
  ``solve_ivp`` (method DOP853, relative tolerance ``rtol``, absolute
  tolerances ``rtol`` times the scales x_scale = mu_0 F_c / k (position),
  v_scale = max |v_R| (velocity), their products with T for the integrals;
  ``max_step`` = T / (32 n)). Terminal events: v_rel = 0 crossing in the
  direction that ends the slip; for a free-ended spring x_S = gap (contact
  made or lost, so no step straddles the kink of the force). Non-terminal
  events dF_spring/dt = 0 give the force's extrema. Every event is located by
  scipy's root finder on the step's dense output. solve_ivp runs in the
  period's units, u = tau / T, because its event location works to an
  absolute 4 eps in its time variable (in seconds that would be 9e-16 s, an
  error a_R * 9e-16 s ~ 4e-11 m/s in v_rel at every event). v_S is continuous
  across every event and is kept as integrated.
* Stick: no ODE, x_S = x_R + c. The exit is the first tau where
  |f(tau)| > mu_0 F_c, found by a certified scan: a grid of 4096 cells per
  period, a cell being free of crossings when h(a) + h(b) > L (b - a) for
  h = mu_0 F_c - |f| > 0 at both ends and L a Lipschitz bound of f
  (m_s sum (k w0)^3 d_k + k sum (k w0) d_k + b sum (k w0)^2 d_k); cells
  without that certificate are halved down to 1e-10 T, and a sign change is
  located with ``brentq`` (xtol 1e-16 T, rtol 4 eps). Contact changes of a
  free-ended spring and the force extrema in stick are found the same way.
  The integrals of x_S and F_spring over a stick piece use the antiderivative
  of the Fourier series.
* Steady state: the period map (state at tau = 0 -> state one period later)
  is iterated from rest. After every period the boundary state is compared
  with those q = 1..4 periods earlier in the scaled norm
  max(|dx| / x_scale, |dv| / v_scale); once the smallest q with a change
  below ``switch_tol`` = 1e-6 is found, the fixed point of the q-fold map is
  polished by Newton's method with a finite-difference Jacobian (step 1e-6
  of the scale) until the Newton step is below 1e-13, and its eigenvalues
  (the orbit's Floquet multipliers) are reported: all inside the unit circle
  means an attracting q-periodic orbit. ``periods_to_steady`` is the number
  of periods from rest after which the boundary state is within 1e-9 (scaled)
  of that fixed point: counted while the run from rest goes on, else
  extrapolated with the largest multiplier (then marked ``extrapolated``).
* The steady orbit (q periods from the fixed point) gives the time averages
  of F_spring and x_S, the largest and smallest F_spring, the contact
  fraction, and the events by kind. The orbit is then checked on a grid of
  4000 n q points: v_rel keeps the slip's sign inside every slip piece and
  |f| <= mu_0 F_c inside every stick piece.
* Error of mean_force: every case runs at rtol and at 100 rtol; the relative
  difference of the two mean forces is reported as ``rel_err_est`` (a bound
  for the rtol run, whose own error is about a hundredth of it for a method
  of order 8).

A free slider (k = 0, no spring) is run first as a check of the signal and of
the friction law: its mean velocity over a steady period must be the
no-load velocity of docs/model.md section 6 (0.297137 m/s), which the script
prints but does not assume.

Rerun
-----
From the repository root (numpy and scipy needed; about ten minutes on one
core)::

    python3 tests/data/spring_reference.py            # writes tests/data/spring_reference.csv
    python3 tests/data/spring_reference.py --quick    # two cases, prints only

To regenerate the inputs (the script never calls the binary)::

    stickslip default-scene > tests/data/spring_reference_scene.toml
    stickslip signal --json > tests/data/spring_reference_signal_default.json
    stickslip signal --json --set signal.harmonics=3 --set signal.sqrt_kappa=2 \
        > tests/data/spring_reference_signal_n3_sqrtkappa2.json
"""

import argparse
import datetime
import json
import math
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

HERE = Path(__file__).resolve().parent
EPS = np.finfo(float).eps


class Rod:
    """x_R(t) = offset + sum d_k sin(k w0 t + phi_k), evaluated at a phase."""

    def __init__(self, signal):
        self.T = float(signal["period"])
        self.w0 = 2.0 * math.pi / self.T
        self.c0 = float(signal["offset"])
        h = signal["harmonics"]
        self.n = max(int(x["k"]) for x in h)
        self.kw = np.array([int(x["k"]) * self.w0 for x in h])
        self.d = np.array([float(x["amplitude"]) for x in h])
        self.phi = np.array([float(x["phase"]) for x in h])
        self.stroke = float(signal["stroke"])

    def deriv(self, t, order):
        """order-th time derivative of x_R at t (scalar or array)."""
        t = np.asarray(t, dtype=float)
        arg = np.multiply.outer(t, self.kw) + self.phi + order * (math.pi / 2.0)
        val = np.sin(arg) @ (self.d * self.kw**order)
        if order == 0:
            val = val + self.c0
        return val if val.ndim else float(val)

    def x(self, t):
        return self.deriv(t, 0)

    def v(self, t):
        return self.deriv(t, 1)

    def a(self, t):
        return self.deriv(t, 2)

    def antideriv(self, t):
        """A primitive of x_R."""
        t = np.asarray(t, dtype=float)
        arg = np.multiply.outer(t, self.kw) + self.phi
        val = -np.cos(arg) @ (self.d / self.kw) + self.c0 * t
        return val if val.ndim else float(val)

    def bound(self, order):
        """sum_k d_k (k w0)^order: a bound of |order-th derivative| (order >= 1)."""
        return float(np.sum(self.d * self.kw**order))


class Spring:
    def __init__(self, kind, k, b=0.0, preload=0.0, anchor=0.0, gap=0.0):
        self.kind, self.k, self.b = kind, float(k), float(b)
        self.preload, self.anchor, self.gap = float(preload), float(anchor), float(gap)
        if kind == "free" and (b != 0.0 or preload != 0.0):
            raise ValueError("a free-ended spring has no damping and no preload here")

    def force(self, x, v):
        if self.kind == "tied":
            return self.preload + self.k * (x - self.anchor) + self.b * v
        if self.kind == "free":
            return self.k * np.maximum(x - self.gap, 0.0)
        return 0.0 * x  # "none": the free slider

    def rate(self, x, v, a):
        """dF_spring/dt."""
        if self.kind == "tied":
            return self.k * v + self.b * a
        if self.kind == "free":
            return np.where(x >= self.gap, self.k * v, 0.0)
        return 0.0 * x

    def contact(self, x):
        if self.kind == "free":
            return np.where(x >= self.gap, 1.0, 0.0)
        return 1.0 + 0.0 * x


def first_sign_change(h, a, b, lip, n_cells, t_min, xtol):
    """First t in (a, b] where h changes sign from its sign at a (h(a) != 0).

    Cells [u, w] with h(u), h(w) of the starting sign and |h(u)| + |h(w)| >
    lip (w - u) cannot hold a zero (lip bounds |h'|); other cells are halved,
    down to t_min, and a sign change is located with brentq. A zero that
    does not change the sign (a tangency) is not an exit. Returns None when h
    keeps its sign.
    """
    ts = np.linspace(a, b, n_cells + 1)
    hs = np.asarray(h(ts), dtype=float)
    s0 = 1.0 if hs[0] >= 0.0 else -1.0

    def cell(u, w, hu, hw):
        if hw * s0 < 0.0:
            if w - u <= t_min:
                return brentq(h, u, w, xtol=xtol, rtol=4 * EPS) if hu * s0 > 0.0 else u
        elif hu * s0 > 0.0 and abs(hu) + abs(hw) > lip * (w - u):
            return None
        elif w - u <= t_min:
            return None
        m = 0.5 * (u + w)
        hm = float(h(m))
        r = cell(u, m, hu, hm)
        return r if r is not None else cell(m, w, hm, hw)

    for i in range(n_cells):
        r = cell(ts[i], ts[i + 1], hs[i], hs[i + 1])
        if r is not None:
            return r
    return None


def all_sign_changes(h, a, b, lip, n_cells, t_min, xtol):
    """Every sign change of h in (a, b), in order (same certificate as above)."""
    out = []
    t = a
    while True:
        ht = float(h(t))
        if ht == 0.0:
            t = t + t_min
            continue
        r = first_sign_change(h, t, b, lip, n_cells, t_min, xtol)
        if r is None or r >= b:
            return out
        out.append(r)
        # step just past the root so that h there has the new sign
        t = r + max(xtol, 64 * EPS * abs(r))
        while float(h(t)) * ht > 0.0 and t < b:
            t = t + max(xtol, 64 * EPS * abs(t))
        if t >= b:
            return out


class Stats:
    """Accumulates one period (or q periods) of the motion."""

    def __init__(self):
        self.int_x = 0.0
        self.int_f = 0.0
        self.int_contact = 0.0
        self.f_max = -math.inf
        self.f_min = math.inf
        self.events = {"stick_slip": 0, "slip_stick": 0, "reversal": 0, "contact": 0}
        self.pieces = []  # (kind, tau0, tau1, data) for the orbit check

    def force_sample(self, f):
        f = np.atleast_1d(f)
        self.f_max = max(self.f_max, float(np.max(f)))
        self.f_min = min(self.f_min, float(np.min(f)))


class Simulator:
    N_CELLS = 4096

    def __init__(self, rod, motor, spring, rtol):
        self.rod, self.spring, self.rtol = rod, spring, rtol
        self.m = motor["slider_mass"]
        self.fc = motor["contact_force"]
        self.f0 = motor["mu_static"] * self.fc  # static friction limit
        self.fd = motor["mu_dynamic"] * self.fc  # sliding friction
        self.gt = motor["extra_acceleration"]
        T = rod.T
        self.v_scale = float(np.max(np.abs(rod.v(np.linspace(0, T, 20001)))))
        self.x_scale = self.f0 / spring.k if spring.k > 0 else rod.stroke
        atol_x = rtol * self.x_scale
        atol_v = rtol * self.v_scale
        self.atol = np.array([atol_x, atol_v, atol_x * T, rtol * self.f0 * T, rtol * T])
        self.max_step = T / (32 * rod.n)
        self.t_min = 1e-10 * T
        self.xtol = 1e-16 * T
        k, b = spring.k, spring.b
        # Lipschitz bounds (in tau) of f = m (a_R - g_t) + F(x_R + c, v_R) and of F'
        self.lip_f = self.m * rod.bound(3) + k * rod.bound(1) + b * rod.bound(2)
        self.lip_df = k * rod.bound(2) + b * rod.bound(3)

    # ---- the friction force needed to stick -------------------------------
    def needed(self, tau, x, v):
        return self.m * (self.rod.a(tau) - self.gt) + self.spring.force(x, v)

    # ---- one slip piece ------------------------------------------------------
    def slip(self, tau0, y0, s, tau_end, st):
        """Integrate slip in direction s from tau0; returns (tau, y, why)."""
        sp, rod, m, fd, gt = self.spring, self.rod, self.m, self.fd, self.gt

        # solve_ivp runs in the period's units (u = tau / T): its event
        # location works to an absolute tolerance of 4 eps in u
        T = rod.T

        def rhs(u, y):
            x, v = y[0], y[1]
            f = sp.force(x, v)
            return [T * v, T * (s * fd + m * gt - f) / m, T * x, T * f, T * sp.contact(x)]

        def ev_vrel(u, y):
            return rod.v(u * T) - y[1]

        ev_vrel.terminal = True
        ev_vrel.direction = -s
        events = [ev_vrel]
        if sp.kind == "free":
            x0, v0 = y0[0], y0[1]
            if x0 == sp.gap:
                # on the edge: contact is being made if the slider moves (or,
                # at rest, accelerates) towards the spring
                moving = v0 if v0 != 0.0 else s * fd + m * gt
                direction = -1.0 if moving > 0 else 1.0
            else:
                direction = -1.0 if x0 > sp.gap else 1.0

            def ev_contact(u, y):
                return y[0] - sp.gap

            ev_contact.terminal = True
            ev_contact.direction = direction
            events.append(ev_contact)

        def ev_fext(u, y):
            x, v = y[0], y[1]
            a = (s * fd + m * gt - sp.force(x, v)) / m
            return sp.rate(x, v, a)

        ev_fext.terminal = False
        if sp.kind != "none":
            events.append(ev_fext)
        y0 = np.array([y0[0], y0[1], 0.0, 0.0, 0.0])
        sol = solve_ivp(
            rhs,
            (tau0 / T, tau_end / T),
            y0,
            method="DOP853",
            rtol=self.rtol,
            atol=self.atol,
            events=events,
            max_step=self.max_step / T,
            dense_output=st is not None and st.pieces is not None,
        )
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        y1 = sol.y[:, -1]
        tau1 = tau_end if sol.status == 0 else sol.t[-1] * T
        why = "end"
        if sol.status == 1:
            if len(sol.t_events[0]):
                why = "vrel"
            else:
                why = "contact"
        if st is not None:
            st.int_x += y1[2]
            st.int_f += y1[3]
            st.int_contact += y1[4]
            st.force_sample(sp.force(np.array([y0[0], y1[0]]), np.array([y0[1], y1[1]])))
            fe = sol.y_events[-1] if sp.kind != "none" else []
            if len(fe):
                st.force_sample(sp.force(fe[:, 0], fe[:, 1]))
            if st.pieces is not None:
                st.pieces.append(("slip", tau0, tau1, (s, lambda tau: sol.sol(tau / T))))
        return tau1, y1[:2], why

    # ---- one stick piece -----------------------------------------------------
    def stick(self, tau0, c, tau_end, st):
        """Stick from tau0 with x_S = x_R + c; returns (tau, s or 0 if none)."""
        rod, sp, f0 = self.rod, self.spring, self.f0

        def h(t):
            return f0 - np.abs(self.needed(t, rod.x(t) + c, rod.v(t)))

        tau1 = first_sign_change(h, tau0, tau_end, self.lip_f, self.N_CELLS, self.t_min, self.xtol)
        s = 0
        if tau1 is None:
            tau1 = tau_end
        else:
            s = 1 if self.needed(tau1, rod.x(tau1) + c, rod.v(tau1)) > 0 else -1
        if st is not None:
            self.stick_integrals(tau0, tau1, c, st)
            if st.pieces is not None:
                st.pieces.append(("stick", tau0, tau1, c))
        return tau1, s

    def stick_integrals(self, t0, t1, c, st):
        rod, sp = self.rod, self.spring
        n_cells = max(8, int(self.N_CELLS * (t1 - t0) / rod.T))
        if t1 <= t0:
            return
        ix = rod.antideriv(t1) - rod.antideriv(t0) + c * (t1 - t0)
        st.int_x += ix
        # force extrema inside: zeros of dF/dt
        ends = [t0, t1]
        if sp.kind != "none":
            ext = all_sign_changes(
                lambda t: sp.rate(rod.x(t) + c, rod.v(t), rod.a(t)),
                t0, t1, self.lip_df, n_cells, self.t_min, self.xtol,
            )
            ends += ext
        tt = np.array(ends)
        st.force_sample(sp.force(rod.x(tt) + c, rod.v(tt)))
        if sp.kind == "tied":
            st.int_f += sp.preload * (t1 - t0) + sp.k * (ix - sp.anchor * (t1 - t0)) + sp.b * (
                rod.x(t1) - rod.x(t0)
            )
            st.int_contact += t1 - t0
        elif sp.kind == "free":
            cuts = all_sign_changes(
                lambda t: rod.x(t) + c - sp.gap, t0, t1, rod.bound(1), n_cells, self.t_min, self.xtol
            )
            st.events["contact"] += len(cuts)
            pts = [t0] + cuts + [t1]
            for u, w in zip(pts[:-1], pts[1:]):
                mid = 0.5 * (u + w)
                if rod.x(mid) + c >= sp.gap:
                    ixs = rod.antideriv(w) - rod.antideriv(u) + (c - sp.gap) * (w - u)
                    st.int_f += sp.k * ixs
                    st.int_contact += w - u

    # ---- one period ------------------------------------------------------------
    def period(self, state, st=None):
        """state = (mode, x, v) at tau = 0; mode 'stick' or +1 / -1 (slip)."""
        rod, T = self.rod, self.rod.T
        mode, x, v = state
        tau = 0.0
        while tau < T:
            if mode == "stick":
                c = x - rod.x(tau)
                tau, s = self.stick(tau, c, T, st)
                x = rod.x(tau) + c
                v = rod.v(tau)
                if s != 0:
                    mode = s
                    if st is not None:
                        st.events["stick_slip"] += 1
            else:
                tau, y, why = self.slip(tau, (x, v), mode, T, st)
                x, v = float(y[0]), float(y[1])
                if why == "vrel":
                    # v_S is kept as integrated (continuous across the event)
                    f = self.needed(tau, x, v)
                    if abs(f) <= self.f0:
                        mode = "stick"
                        if st is not None:
                            st.events["slip_stick"] += 1
                    else:
                        new = 1 if f > 0 else -1
                        if new == mode:
                            raise RuntimeError(f"v_rel = 0 at tau = {tau} without a change of mode")
                        mode = new
                        if st is not None:
                            st.events["reversal"] += 1
                elif why == "contact":
                    x = self.spring.gap
                    if st is not None:
                        st.events["contact"] += 1
        if mode == "stick":
            v = rod.v(0.0)
        return (mode, x, v)

    def start_state(self):
        f = self.needed(0.0, 0.0, 0.0)
        if abs(f) <= self.f0:
            return ("stick", 0.0, 0.0)
        return (1 if f > 0 else -1, 0.0, 0.0)

    def distance(self, s1, s2):
        if s1[0] != s2[0]:
            return math.inf
        return max(abs(s1[1] - s2[1]) / self.x_scale, abs(s1[2] - s2[2]) / self.v_scale)

    # ---- the steady state ----------------------------------------------------------
    def map_q(self, state, q):
        for _ in range(q):
            state = self.period(state)
        return state

    def newton(self, state, q, tol=1e-13, max_iter=12):
        """Fixed point of the q-fold period map near state; returns (state, multipliers)."""
        mode = state[0]
        stuck = mode == "stick"
        sc = np.array([self.x_scale]) if stuck else np.array([self.x_scale, self.v_scale])

        def unpack(u):
            return (mode, float(u[0]), self.rod.v(0.0) if stuck else float(u[1]))

        def F(u):
            s1 = self.map_q(unpack(u), q)
            if s1[0] != mode:
                return None
            out = np.array([s1[1]]) if stuck else np.array([s1[1], s1[2]])
            return out

        u = np.array([state[1]]) if stuck else np.array([state[1], state[2]])
        J = None
        for it in range(max_iter):
            Pu = F(u)
            if Pu is None:
                return None, None
            r = Pu - u
            dim = len(u)
            J = np.zeros((dim, dim))
            for j in range(dim):
                du = np.zeros(dim)
                du[j] = 1e-6 * sc[j]
                Pp = F(u + du)
                Pm = F(u - du)
                if Pp is None or Pm is None:
                    return None, None
                J[:, j] = (Pp - Pm) / (2 * du[j])
            step = np.linalg.solve(J - np.eye(dim), -r)
            u = u + step
            if np.max(np.abs(step) / sc) < tol:
                break
        return unpack(u), np.linalg.eigvals(J)

    def steady(self, max_periods, switch_tol=1e-6, steady_tol=1e-9, q_max=4):
        """Run from rest, detect the orbit's period q, polish its fixed point."""
        state = self.start_state()
        hist = [state]
        q_found = None
        p = 0
        while p < max_periods:
            state = self.period(state)
            p += 1
            hist.append(state)
            for q in range(1, q_max + 1):
                if p >= q and self.distance(hist[p], hist[p - q]) < switch_tol:
                    q_found = q
                    break
            if q_found:
                break
        if not q_found:
            return dict(q=None, periods_run=p, hist=hist)
        fixed, mult = self.newton(hist[p], q_found)
        if fixed is None:
            return dict(q=None, periods_run=p, hist=hist, note="newton left the mode")
        orbit = [fixed]
        for j in range(1, q_found):
            orbit.append(self.period(orbit[-1]))
        # the orbit's least period: a divisor d of q with P^d(fixed) = fixed
        for d in range(1, q_found):
            if q_found % d == 0 and self.distance(orbit[d], fixed) < 1e-8:
                fixed, mult = self.newton(fixed, d)
                q_found = d
                orbit = orbit[:d]
                break
        # periods to steady: keep running from rest until within steady_tol
        lam = float(np.max(np.abs(mult)))
        extrapolated = False

        def dist_orbit(s):
            return min(self.distance(s, o) for o in orbit)

        p_steady = None
        for i, s in enumerate(hist):
            if dist_orbit(s) < steady_tol:
                p_steady = i
                break
        extra = 0
        while p_steady is None and extra < max_periods and lam < 0.9999:
            state = self.period(state)
            p += 1
            extra += 1
            if dist_orbit(state) < steady_tol:
                p_steady = p
        if p_steady is None:
            d = dist_orbit(state)
            p_steady = p + math.ceil(math.log(d / steady_tol) / -math.log(lam))
            extrapolated = True
        return dict(
            q=q_found, periods_run=p, fixed=fixed, multipliers=mult,
            p_steady=p_steady, extrapolated=extrapolated, last=state,
        )

    def orbit_stats(self, fixed, q):
        st = Stats()
        state = fixed
        for _ in range(q):
            state = self.period(state, st)
        T = self.rod.T * q
        return st, state

    def check_orbit(self, st, q):
        """On a fine grid: v_rel keeps its sign in slip, |f| <= mu_0 F_c in stick."""
        rod = self.rod
        worst_slip = math.inf
        worst_stick = -math.inf
        for kind, t0, t1, data in st.pieces:
            if t1 - t0 <= 0:
                continue
            nn = max(3, int(4000 * rod.n * (t1 - t0) / rod.T))
            tt = np.linspace(t0, t1, nn)[1:-1]
            if len(tt) == 0:
                continue
            if kind == "slip":
                s, dense = data
                vrel = rod.v(tt) - dense(tt)[1]
                worst_slip = min(worst_slip, float(np.min(s * vrel)) / self.v_scale)
            else:
                c = data
                f = self.needed(tt, rod.x(tt) + c, rod.v(tt))
                worst_stick = max(worst_stick, float(np.max(np.abs(f))) / self.f0)
        return worst_slip, worst_stick


def load_inputs():
    scene = tomllib.loads((HERE / "spring_reference_scene.toml").read_text())
    motor = {k: float(v) for k, v in scene["motor"].items()}
    signals = {}
    for name in ("default", "n3_sqrtkappa2"):
        sig = json.loads((HERE / f"spring_reference_signal_{name}.json").read_text())
        rod = Rod(sig)
        tt = np.linspace(0.0, rod.T, 200001)
        xs = rod.x(tt)
        checks = (abs(rod.x(0.0)), abs(rod.v(0.0)), abs(xs.max() - xs.min() - rod.stroke))
        if checks[0] > 1e-12 * rod.stroke or checks[1] > 1e-9 or checks[2] > 1e-6 * rod.stroke:
            raise SystemExit(f"signal {name}: x_R(0), v_R(0), stroke check failed: {checks}")
        signals[name] = rod
    return motor, signals


def run_case(rod, motor, spring, rtol, max_periods, orbit_from=None):
    """The steady orbit of one case; with orbit_from (a run_case result) only
    its fixed point is polished again at this rtol (no run from rest)."""
    t_start = time.process_time()
    sim = Simulator(rod, motor, spring, rtol)
    if orbit_from is None:
        res = sim.steady(max_periods)
    else:
        fixed, mult = sim.newton(orbit_from["fixed"], orbit_from["q"])
        res = dict(q=orbit_from["q"] if fixed is not None else None, fixed=fixed,
                   multipliers=mult, periods_run=0, p_steady=None, extrapolated=False)
    out = dict(rtol=rtol)
    if res["q"] is None:
        out.update(q=None, periods_run=res["periods_run"], cpu=time.process_time() - t_start)
        return out
    q = res["q"]
    st = Stats()
    st.pieces = []
    state = res["fixed"]
    for _ in range(q):
        state = sim.period(state, st)
    Tq = rod.T * q
    worst_slip, worst_stick = sim.check_orbit(st, q)
    closure = sim.distance(state, res["fixed"])
    out.update(
        q=q,
        periods_run=res["periods_run"],
        p_steady=res["p_steady"],
        extrapolated=res["extrapolated"],
        multipliers=res["multipliers"],
        mean_force=st.int_f / Tq,
        max_force=st.f_max,
        min_force=st.f_min,
        mean_position=st.int_x / Tq,
        contact_fraction=st.int_contact / Tq,
        events=dict(st.events),
        closure=closure,
        worst_slip=worst_slip,
        worst_stick=worst_stick,
        fixed=res["fixed"],
        cpu=time.process_time() - t_start,
    )
    return out


def free_slider_check(rod, motor, rtol, periods=300):
    """Steady mean velocity of the slider without spring: `periods` periods
    from rest, then the secant method on the period map of v_S."""
    sim = Simulator(rod, motor, Spring("none", 0.0), rtol)
    state = sim.start_state()
    for _ in range(periods):
        state = sim.period(state)
    mode = state[0]

    def resid(v):
        s1 = sim.period((mode, 0.0, v))
        return s1[2] - v, s1[1]

    v0, v1 = state[2], state[2] * (1 + 1e-6) + 1e-9
    r0, _ = resid(v0)
    for _ in range(30):
        r1, _ = resid(v1)
        if r1 == r0:
            break
        v0, v1, r0 = v1, v1 - r1 * (v1 - v0) / (r1 - r0), r1
        if abs(v1 - v0) < 1e-15 * sim.v_scale:
            break
    return resid(v1)[1] / rod.T


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rtol", type=float, default=1e-12)
    ap.add_argument("--quick", action="store_true", help="two cases, print only")
    ap.add_argument("--max-periods", type=int, default=20000)
    ap.add_argument("--output", default=str(HERE / "spring_reference.csv"))
    args = ap.parse_args()
    motor, signals = load_inputs()
    wall0 = time.time()

    cases = []
    tied_k = [1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6]
    for scene in ("default", "n3_sqrtkappa2"):
        for k in tied_k:
            cases.append((scene, Spring("tied", k)))
    for gap in (0.0, 10e-6):
        for k in (1e4, 1e5, 1e6):
            cases.append(("default", Spring("free", k, gap=gap)))
    if args.quick:
        cases = [cases[4], cases[-1]]

    for name, rod in signals.items():
        t0 = time.process_time()
        v = free_slider_check(rod, motor, args.rtol)
        print(f"# check: free slider (no spring), scene {name}: steady mean velocity "
              f"{v:.12f} m/s (cpu {time.process_time() - t0:.1f} s)")
    rows = []
    for scene, spring in cases:
        rod = signals[scene]
        fine = run_case(rod, motor, spring, args.rtol, args.max_periods)
        coarse = (
            run_case(rod, motor, spring, 100 * args.rtol, args.max_periods, orbit_from=fine)
            if fine["q"] else dict(q=None)
        )
        row = dict(scene=scene, spring=spring, fine=fine, coarse=coarse)
        rows.append(row)
        report(row)
        sys.stdout.flush()
    wall = time.time() - wall0
    print(f"# wall time {wall:.1f} s")
    if not args.quick:
        write_csv(args.output, rows, args.rtol, wall)


def report(row):
    sp, f, c = row["spring"], row["fine"], row["coarse"]
    head = f"{row['scene']:14s} {sp.kind:5s} k={sp.k:8.0e} gap={sp.gap:7.1e}"
    if f["q"] is None:
        print(f"{head} no orbit of period <= 4 within {f['periods_run']} periods (cpu {f['cpu']:.1f} s)")
        return
    rel = abs(f["mean_force"] - c["mean_force"]) / abs(f["mean_force"]) if c["q"] else math.nan
    print(
        f"{head} q={f['q']} F_mean={f['mean_force']:.12e} N max={f['max_force']:.6e} "
        f"min={f['min_force']:.6e} x_mean={f['mean_position']:.6e} contact={f['contact_fraction']:.6f} "
        f"p_steady={f['p_steady']}{'(extrap)' if f['extrapolated'] else ''} run={f['periods_run']} "
        f"events={f['events']} |mult|={np.abs(f['multipliers']).round(6).tolist()} "
        f"closure={f['closure']:.1e} slipmargin={f['worst_slip']:.2e} stick|f|/F0={f['worst_stick']:.6f} "
        f"rel_diff(100x rtol)={rel:.2e} cpu={f['cpu']:.1f}+{c['cpu']:.1f} s"
    )


def write_csv(path, rows, rtol, wall):
    cols = [
        "scene", "spring", "k", "b", "gap", "preload", "mean_force", "max_force", "min_force",
        "mean_position", "contact_fraction", "orbit_period", "periods_to_steady",
        "stick_slip", "slip_stick", "reversal", "contact_changes", "max_floquet_modulus",
        "rel_err_est",
    ]
    lines = [
        "# Reference: the slider of the paper's motor (docs/model.md section 6) against a spring,",
        "# prescribed rod; steady orbit from rest. Columns in SI units (N, m, N/m, N s/m).",
        f"# Provenance: tests/data/spring_reference.py (numpy {np.__version__}, scipy {scipy.__version__},",
        f"# Python {sys.version.split()[0]}), {datetime.date.today().isoformat()}, solve_ivp DOP853 rtol {rtol:g};",
        "# inputs spring_reference_scene.toml ([motor]) and spring_reference_signal_<scene>.json.",
        "# rel_err_est = |mean_force(rtol) - mean_force(100 rtol)| / mean_force (a bound of its error).",
        "# orbit_period in drive periods (empty: no orbit of period <= 4 found); periods_to_steady:",
        "# periods from rest until the boundary state is within 1e-9 (scaled) of the orbit.",
        "# Events are per orbit (orbit_period drive periods); contact_changes counts contact made or lost.",
        f"# Wall time of the run that wrote this file: {wall:.0f} s.",
        ",".join(cols),
    ]
    for row in rows:
        sp, f, c = row["spring"], row["fine"], row["coarse"]
        if f["q"] is None:
            vals = [row["scene"], sp.kind, sp.k, sp.b, sp.gap, sp.preload] + [""] * 13
            vals[12] = ""
        else:
            rel = abs(f["mean_force"] - c["mean_force"]) / abs(f["mean_force"]) if c["q"] else ""
            ev = f["events"]
            vals = [
                row["scene"], sp.kind, sp.k, sp.b, sp.gap, sp.preload,
                f"{f['mean_force']:.15e}", f"{f['max_force']:.15e}", f"{f['min_force']:.15e}",
                f"{f['mean_position']:.15e}", f"{f['contact_fraction']:.15e}",
                f["q"], f["p_steady"], ev["stick_slip"], ev["slip_stick"], ev["reversal"],
                ev["contact"], f"{float(np.max(np.abs(f['multipliers']))):.6f}",
                f"{rel:.2e}" if rel != "" else "",
            ]
        lines.append(",".join(str(v) for v in vals))
    tmp = Path(path).with_suffix(".csv.tmp")
    tmp.write_text("\n".join(lines) + "\n")
    tmp.replace(path)


if __name__ == "__main__":
    main()
