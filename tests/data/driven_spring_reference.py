#!/usr/bin/env python3
"""Independent reference: a driven rod, the slider against a spring.

What it computes
----------------
The rod is not prescribed: the actuator (docs/model.md section 16) is driven
by a voltage, read from the JSON that `stickslip signal --voltage --json`
prints (docs/interface.md), committed next to this script as
``driven_spring_reference_voltage_<signal>.json``::

    u(t) = u_0 + sum_k u_k sin(k w0 t + phi_k),   w0 = 2 pi / period

The real actuator (mass M, damping d, stiffness c, transfer factor alpha:
``[actuator.real]`` of ``driven_spring_reference_scene.toml``, falling back
to ``[actuator]``), the motor (slider mass m, contact force F_c, mu_0, mu_d,
g_t: ``[motor]``) come from that scene; each case says its signal
(sqrt(kappa) = 2 or 0.5: which voltage), its spring and whether the friction
acts back on the rod (the reaction). Equations::

    slip in direction s (s = sign(v_R - v_S)), friction on the slider s mu_d F_c:
        rod:    M a_R = alpha u - d v_R - c x_R - s mu_d F_c     (reaction on)
                M a_R = alpha u - d v_R - c x_R                  (reaction off)
        slider: m a_S = s mu_d F_c + m g_t - F_spring(x_S, v_S)
    stick (x_S = x_R + delta, v_S = v_R):
        (M + m) a_R = alpha u - d v_R - c x_R + m g_t - F_spring(x_R + delta, v_R)   (on)
        M a_R       = alpha u - d v_R - c x_R                                        (off)
        held while |F*| <= mu_0 F_c,  F* = m (a_R - g_t) + F_spring   (the friction needed)

    tied spring:       F_spring = F_p + k x_S + b v_S          (always)
    free-ended spring: F_spring = k (x_S - gap) while x_S >= gap, else 0

Transitions (docs/model.md sections 1 and 16): a stuck slider slips in
direction sign(F*) when |F*| exceeds mu_0 F_c; a slipping slider at
v_rel = v_R - v_S = 0 sticks if |F*| <= mu_0 F_c there (F* with the stuck
system's acceleration at that state), else slips the other way (a reversal).
Rod and slider start at rest at x_R = x_S = 0 when the voltage is switched on
at t = 0; the mode at t = 0+ follows from F*(0) like any stick phase.

Method (no code, formula or closed form of the Rust engine is used)
-------------------------------------------------------------------
Time is kept as (period index, phase tau in [0, T)); the voltage is
evaluated at the phase.

* Every piece between events, slip or stick, is integrated numerically by
  scipy's ``solve_ivp`` (DOP853, relative tolerance ``rtol`` = 3e-14, just
  above scipy's floor of 100 eps, absolute tolerances ``rtol`` times the
  scales: the stroke for x_R, min(stroke,
  mu_0 F_c / k) for x_S, max |v_R| of the signal for the velocities, their
  products with T, and mu_0 F_c T, for the running integrals of x_S and
  F_spring; ``max_step`` = T / (32 n)). Slip integrates (x_R, v_R, x_S,
  v_S), stick (x_R, v_R) with x_S = x_R + delta. solve_ivp runs in the
  period's units u = tau / T, so that its event location (an absolute
  4 eps in its time variable) is exact to rounding.
* Terminal events, located by scipy's root finder on the step's dense
  output: in slip v_rel = 0 in the direction that ends the slip; in stick
  F* = +mu_0 F_c rising and F* = -mu_0 F_c falling; for a free-ended spring
  x_S = gap (contact made or lost: no step straddles the kink of the force).
  Non-terminal events dF_spring/dt = 0 give the force's extrema. v_S is
  kept as integrated across every event.
* Steady state: the period map (state (x_R, v_R, x_S, v_S) and mode at
  tau = 0 -> the same one period later) is iterated from rest. After every
  period the boundary state is compared with those q = 1..4 periods earlier
  in the scaled norm; once the smallest q with a change below
  ``switch_tol`` = 1e-6 is found, the fixed point of the q-fold map is
  polished by Newton's method with a central finite-difference Jacobian
  (step 1e-6 of the scales) until the Newton step is below 1e-13 of the
  scales; of its iterates the one with the least residual is kept (near the
  fixed point the computed map is rough at the level of its error). A
  boundary in stick has v_S = v_R and three coordinates; without a spring
  x_S is left out (it is neutral). The Jacobian's eigenvalues
  are the orbit's Floquet multipliers; all inside the unit circle means an
  attracting q-periodic orbit. ``periods_to_steady``: the periods from rest
  until the boundary state is within 1e-9 (scaled) of the orbit.
* The steady orbit (q periods from the fixed point) gives the time averages
  of F_spring and x_S, the largest and smallest F_spring, the contact and
  stick fractions, and the events by kind. The orbit is then checked on a
  grid of 4000 n q points: v_rel keeps the slip's sign inside every slip
  piece, |F*| <= mu_0 F_c inside every stick piece, and a free end's
  contact flag agrees with x_S >= gap.
* No orbit: where none of period <= 4 appears within ``--max-periods``
  (4000) periods from rest, the case is read over its first ``--from-rest``
  (10) periods from rest instead, and checked on the same grid.
* Error: every orbit is polished again, and read, at 10 and 100 rtol (a
  reading from rest is repeated at both); ``rel_err_est`` is the largest
  relative difference of the mean force (the mean velocity without a
  spring) from the rtol run, ``extrema_err_est`` that of the largest and
  least force (relative to the largest |force|), ``fraction_err_est`` that
  of the contact and stick fractions: bounds for the rtol run. Why rtol is
  as tight as scipy allows: the friction a stuck slider needs, F* ~ 0.2 N,
  is the small difference of the rod's forces (c x_R m / (M + m) ~ 200 N),
  so the rod's relative error reaches F*, and the stick exits, a thousand
  times larger.

Checks that do not depend on the spring (printed, and the free sliders
written to the csv for tests/driven_spring_reference.rs):

* the voltage: the designed ``[actuator]`` without friction, integrated from
  rest over one period under u(t), follows the signal that `stickslip signal
  --json` prints (``driven_spring_reference_signal_<signal>.json``) and ends
  at rest at x_R = 0;
* the free slider (no spring) on the driven rod: its mean velocity over the
  steady orbit is the project's v_inf.

Rerun
-----
From the repository root (numpy and scipy needed)::

    python3 tests/data/driven_spring_reference.py          # writes tests/data/driven_spring_reference.csv
    python3 tests/data/driven_spring_reference.py --quick  # two cases, prints only

To regenerate the inputs (the script never calls the binary)::

    S=tests/data/driven_spring_reference_scene.toml
    stickslip signal $S --voltage --json > tests/data/driven_spring_reference_voltage_sqrtkappa2.json
    stickslip signal $S --json > tests/data/driven_spring_reference_signal_sqrtkappa2.json
    stickslip signal $S --set signal.sqrt_kappa=0.5 --voltage --json \\
        > tests/data/driven_spring_reference_voltage_sqrtkappa0_5.json
    stickslip signal $S --set signal.sqrt_kappa=0.5 --json \\
        > tests/data/driven_spring_reference_signal_sqrtkappa0_5.json
"""

import argparse
import datetime
import json
import math
import sys
import time
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np
import scipy
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
SIGNALS = {"sqrtkappa2": 2.0, "sqrtkappa0_5": 0.5}


class Series:
    """offset + sum_k a_k sin(k w0 t + phi_k) and its derivatives."""

    def __init__(self, data):
        self.T = float(data["period"])
        self.w0 = 2.0 * math.pi / self.T
        self.c0 = float(data["offset"])
        h = data["harmonics"]
        self.n = max(int(x["k"]) for x in h)
        self.terms = [
            (int(x["k"]) * self.w0, float(x["amplitude"]), float(x["phase"])) for x in h
        ]

    def __call__(self, t):
        return self.c0 + sum(a * math.sin(kw * t + p) for kw, a, p in self.terms)

    def deriv(self, t, order):
        t = np.asarray(t, dtype=float)
        val = sum(
            a * kw**order * np.sin(kw * t + p + order * math.pi / 2) for kw, a, p in self.terms
        )
        return val + (self.c0 if order == 0 else 0.0)


class Spring:
    def __init__(self, kind, k=0.0, b=0.0, preload=0.0, gap=0.0):
        self.kind, self.k, self.b, self.preload, self.gap = kind, k, b, preload, gap

    def force(self, x, v, contact):
        if self.kind == "tied":
            return self.preload + self.k * x + self.b * v
        if self.kind == "free" and contact:
            # x_S >= gap in contact (to the rounding of the event that began it)
            return self.k * max(x - self.gap, 0.0)
        return 0.0

    def rate(self, v, a, contact):
        """dF_spring/dt."""
        if self.kind == "tied" or (self.kind == "free" and contact):
            return self.k * v + self.b * a
        return 0.0

    def label(self):
        if self.kind == "none":
            return "none"
        if self.kind == "tied":
            return f"tied k={self.k:.0e} Fp={self.preload} b={self.b}"
        return f"free k={self.k:.0e} gap={self.gap:.0e}"


class Stats:
    def __init__(self, keep_pieces=False):
        self.int_f = 0.0
        self.int_x = 0.0
        self.t_contact = 0.0
        self.t_stick = 0.0
        self.f_max = -math.inf
        self.f_min = math.inf
        self.events = Counter()
        self.pieces = [] if keep_pieces else None

    def sample(self, f):
        f = np.atleast_1d(f)
        if f.size:
            self.f_max = max(self.f_max, float(np.max(f)))
            self.f_min = min(self.f_min, float(np.min(f)))


class Simulator:
    """One case: voltage, real actuator, motor, spring, reaction."""

    def __init__(self, case, inputs, rtol):
        volt = inputs["voltage"][case["signal"]]
        sig = inputs["signal"][case["signal"]]
        self.u = volt
        self.T = volt.T
        motor = inputs["motor"]
        self.m = motor["slider_mass"]
        self.fd = motor["mu_dynamic"] * motor["contact_force"]
        self.f0 = motor["mu_static"] * motor["contact_force"]
        self.gt = motor["extra_acceleration"]
        act = inputs["actuator_real"]
        self.M, self.d, self.c, self.alpha = act["mass"], act["damping"], act["stiffness"], act[
            "transfer_factor"
        ]
        self.reaction = case["reaction"]
        self.spring = case["spring"]
        self.rtol = rtol
        stroke = float(sig["stroke"])
        tt = np.linspace(0.0, self.T, 20001)
        self.v_scale = float(np.max(np.abs(Series(sig).deriv(tt, 1))))
        self.xr_scale = stroke
        k = self.spring.k
        self.xs_scale = min(stroke, self.f0 / k) if k > 0 else stroke
        T = self.T
        self.atol_slip = rtol * np.array(
            [self.xr_scale, self.v_scale, self.xs_scale, self.v_scale, self.f0 * T,
             self.xs_scale * T]
        )
        self.atol_stick = rtol * np.array(
            [self.xr_scale, self.v_scale, self.f0 * T, self.xs_scale * T]
        )
        self.max_step = 1.0 / (32 * volt.n)  # in u = tau / T
        self.n = volt.n

    # ---- forces and accelerations --------------------------------------------
    def rod_drive(self, t, x, v):
        return self.alpha * self.u(t) - self.d * v - self.c * x

    def a_stuck(self, t, xr, vr, fs):
        """The rod's acceleration with the slider stuck on it, spring force fs."""
        if self.reaction:
            return (self.rod_drive(t, xr, vr) + self.m * self.gt - fs) / (self.M + self.m)
        return self.rod_drive(t, xr, vr) / self.M

    def needed(self, t, xr, vr, xs, contact):
        """F*: the friction that holds the slider on the rod at this state."""
        fs = self.spring.force(xs, vr, contact)
        return self.m * (self.a_stuck(t, xr, vr, fs) - self.gt) + fs

    # ---- one slip piece -------------------------------------------------------
    def slip(self, tau0, y0, s, contact, st):
        T, sp, m, M = self.T, self.spring, self.m, self.M
        fric = s * self.fd
        rod_f = -fric if self.reaction else 0.0

        def rhs(u, y):
            t = u * T
            xr, vr, xs, vs = y[0], y[1], y[2], y[3]
            f = sp.force(xs, vs, contact)
            ar = (self.rod_drive(t, xr, vr) + rod_f) / M
            as_ = (fric + m * self.gt - f) / m
            return [T * vr, T * ar, T * vs, T * as_, T * f, T * xs]

        def ev_vrel(u, y):
            return y[1] - y[3]

        ev_vrel.terminal = True
        ev_vrel.direction = -s
        events = [ev_vrel]
        if sp.kind == "free":

            def ev_contact(u, y):
                return y[2] - sp.gap

            ev_contact.terminal = True
            ev_contact.direction = -1.0 if contact else 1.0
            events.append(ev_contact)
        if sp.kind == "tied" or (sp.kind == "free" and contact):

            def ev_fext(u, y):
                f = sp.force(y[2], y[3], contact)
                return sp.rate(y[3], (fric + m * self.gt - f) / m, contact)

            ev_fext.terminal = False
            events.append(ev_fext)
        y0 = np.array([y0[0], y0[1], y0[2], y0[3], 0.0, 0.0])
        sol = self.integrate(rhs, tau0, y0, self.atol_slip, events, st)
        y1 = sol.y[:, -1]
        tau1 = T if sol.status == 0 else sol.t[-1] * T
        why = "end"
        if sol.status == 1:
            why = "vrel" if len(sol.t_events[0]) else "contact"
        if st is not None:
            st.int_f += y1[4]
            st.int_x += y1[5]
            st.t_contact += (tau1 - tau0) if contact else 0.0
            st.sample([sp.force(y0[2], y0[3], contact), sp.force(y1[2], y1[3], contact)])
            if len(events) > 1 and events[-1].__name__ == "ev_fext":
                for ye in sol.y_events[-1]:
                    st.sample(sp.force(ye[2], ye[3], contact))
            if st.pieces is not None:
                st.pieces.append(("slip", tau0, tau1, (s, contact, sol.sol)))
        return tau1, y1[:4], why

    # ---- one stick piece ------------------------------------------------------
    def stick(self, tau0, xr0, vr0, delta, contact, st):
        T, sp, m = self.T, self.spring, self.m

        def parts(u, y):
            t = u * T
            fs = sp.force(y[0] + delta, y[1], contact)
            a = self.a_stuck(t, y[0], y[1], fs)
            return fs, a

        def rhs(u, y):
            fs, a = parts(u, y)
            return [T * y[1], T * a, T * fs, T * (y[0] + delta)]

        def ev_hi(u, y):
            fs, a = parts(u, y)
            return self.f0 - (m * (a - self.gt) + fs)

        def ev_lo(u, y):
            fs, a = parts(u, y)
            return self.f0 + (m * (a - self.gt) + fs)

        ev_hi.terminal = ev_lo.terminal = True
        ev_hi.direction = ev_lo.direction = -1.0
        events = [ev_hi, ev_lo]
        if sp.kind == "free":

            def ev_contact(u, y):
                return y[0] + delta - sp.gap

            ev_contact.terminal = True
            ev_contact.direction = -1.0 if contact else 1.0
            events.append(ev_contact)
        has_fext = sp.kind == "tied" or (sp.kind == "free" and contact)
        if has_fext:

            def ev_fext(u, y):
                fs, a = parts(u, y)
                return sp.rate(y[1], a, contact)

            ev_fext.terminal = False
            events.append(ev_fext)
        y0 = np.array([xr0, vr0, 0.0, 0.0])
        sol = self.integrate(rhs, tau0, y0, self.atol_stick, events, st)
        y1 = sol.y[:, -1]
        tau1 = T if sol.status == 0 else sol.t[-1] * T
        why = "end"
        if sol.status == 1:
            why = "hi" if len(sol.t_events[0]) else "lo" if len(sol.t_events[1]) else "contact"
        if st is not None:
            st.int_f += y1[2]
            st.int_x += y1[3]
            st.t_stick += tau1 - tau0
            st.t_contact += (tau1 - tau0) if contact else 0.0
            st.sample([sp.force(xr0 + delta, vr0, contact),
                       sp.force(y1[0] + delta, y1[1], contact)])
            if has_fext:
                for ye in sol.y_events[-1]:
                    st.sample(sp.force(ye[0] + delta, ye[1], contact))
            if st.pieces is not None:
                st.pieces.append(("stick", tau0, tau1, (delta, contact, sol.sol)))
        return tau1, y1[:2], why

    def integrate(self, rhs, tau0, y0, atol, events, st):
        sol = solve_ivp(
            rhs,
            (tau0 / self.T, 1.0),
            y0,
            method="DOP853",
            rtol=self.rtol,
            atol=atol,
            events=events,
            max_step=self.max_step,
            dense_output=st is not None and st.pieces is not None,
        )
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        return sol

    # ---- one period -------------------------------------------------------------
    def period(self, state, st=None):
        """state = (mode, x_R, v_R, x_S, v_S, contact) at tau = 0; mode is
        'stick' or +1 / -1 (slip)."""
        T = self.T
        mode, xr, vr, xs, vs, contact = state
        tau = 0.0
        pieces = 0
        while tau < T:
            pieces += 1
            if pieces > 10000:
                raise RuntimeError("more than 10000 pieces in a period")
            if mode == "stick":
                delta = xs - xr
                tau, y, why = self.stick(tau, xr, vr, delta, contact, st)
                xr, vr = float(y[0]), float(y[1])
                xs, vs = xr + delta, vr
                if why in ("hi", "lo"):
                    mode = 1 if why == "hi" else -1
                    if st is not None:
                        st.events["stick_slip"] += 1
                elif why == "contact":
                    contact = not contact
                    if st is not None:
                        st.events["contact_start" if contact else "contact_end"] += 1
            else:
                tau, y, why = self.slip(tau, (xr, vr, xs, vs), mode, contact, st)
                xr, vr, xs, vs = (float(v) for v in y)
                if why == "vrel":
                    f = self.needed(tau, xr, vr, xs, contact)
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
                    xs = self.spring.gap
                    contact = not contact
                    if st is not None:
                        st.events["contact_start" if contact else "contact_end"] += 1
        if mode == "stick":
            vs = vr
        return (mode, xr, vr, xs, vs, contact)

    def start_state(self):
        """Rod and slider at rest at 0; a free end at gap 0 counts as in
        contact if the slider's first motion is into it."""
        sp = self.spring
        contact = sp.kind == "tied"
        if sp.kind == "free" and sp.gap == 0.0:
            f = self.needed(0.0, 0.0, 0.0, 0.0, False)
            if abs(f) <= self.f0:
                a = self.a_stuck(0.0, 0.0, 0.0, 0.0)
            else:
                a = ((1 if f > 0 else -1) * self.fd + self.m * self.gt) / self.m
            contact = a >= 0
        f = self.needed(0.0, 0.0, 0.0, 0.0, contact)
        mode = "stick" if abs(f) <= self.f0 else (1 if f > 0 else -1)
        return (mode, 0.0, 0.0, 0.0, 0.0, contact)

    # ---- coordinates of the boundary state -------------------------------------
    def coords(self, state):
        mode, xr, vr, xs, vs, _ = state
        u = [xr, vr]
        sc = [self.xr_scale, self.v_scale]
        if self.spring.kind != "none":
            u.append(xs)
            sc.append(self.xs_scale)
        if mode != "stick":
            u.append(vs)
            sc.append(self.v_scale)
        return np.array(u), np.array(sc)

    def unpack(self, mode, u, contact_hint):
        xr, vr = float(u[0]), float(u[1])
        i = 2
        xs = 0.0
        if self.spring.kind != "none":
            xs = float(u[2])
            i = 3
        vs = vr if mode == "stick" else float(u[i])
        contact = contact_hint
        if self.spring.kind == "free" and xs != self.spring.gap:
            contact = xs > self.spring.gap
        return (mode, xr, vr, xs, vs, contact)

    def distance(self, s1, s2):
        if s1[0] != s2[0] or s1[5] != s2[5]:
            return math.inf
        u1, sc = self.coords(s1)
        u2, _ = self.coords(s2)
        return float(np.max(np.abs(u1 - u2) / sc))

    # ---- the steady state --------------------------------------------------------
    def map_q(self, state, q, shift=True):
        x0 = state[3]
        for _ in range(q):
            state = self.period(state)
        if self.spring.kind == "none" and shift:
            # without a spring x_S is neutral: the map acts on the rest
            state = (state[0], state[1], state[2], x0, state[4], state[5])
        return state

    def newton(self, state, q, tol=1e-13, max_iter=12):
        """Fixed point of the q-fold period map near state; returns
        (state, multipliers, last scaled step). Of the iterates, the one
        with the least scaled residual is returned: near the fixed point
        the map computed at a finite tolerance is rough at the level of its
        error, and the last step may land on a rougher point."""
        mode, contact = state[0], state[5]
        u, sc = self.coords(state)

        def F(w):
            s1 = self.map_q(self.unpack(mode, w, contact), q)
            if s1[0] != mode:
                return None
            return self.coords(s1)[0]

        J = None
        last = math.inf
        best = (math.inf, u)
        for it in range(max_iter + 1):
            Pu = F(u)
            if Pu is None:
                return None, None, last
            r = Pu - u
            res = float(np.max(np.abs(r) / sc))
            if res < best[0]:
                best = (res, u)
            if it == max_iter or last < tol:
                break
            dim = len(u)
            J = np.zeros((dim, dim))
            for j in range(dim):
                du = np.zeros(dim)
                du[j] = 1e-6 * sc[j]
                Pp, Pm = F(u + du), F(u - du)
                if Pp is None or Pm is None:
                    return None, None, last
                J[:, j] = (Pp - Pm) / (2 * du[j])
            step = np.linalg.solve(J - np.eye(dim), -r)
            u = u + step
            last = float(np.max(np.abs(step) / sc))
        return self.unpack(mode, best[1], contact), np.linalg.eigvals(J), last

    def steady(self, max_periods, switch_tol=1e-6, steady_tol=1e-9, q_max=4):
        """Run from rest, detect the orbit's period q, polish its fixed point."""
        state = self.start_state()
        hist = [state]
        q_found = None
        p = 0
        while p < max_periods:
            state = self.map_q(state, 1, shift=False)
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
        fixed, mult, last = self.newton(hist[p], q_found)
        if fixed is None:
            return dict(q=None, periods_run=p, hist=hist, note="newton left the mode")
        orbit = [fixed]
        for _ in range(1, q_found):
            orbit.append(self.map_q(orbit[-1], 1))
        for d in range(1, q_found):
            if q_found % d == 0 and self.distance(orbit[d], fixed) < 1e-8:
                fixed, mult, last = self.newton(fixed, d)
                q_found = d
                orbit = orbit[:d]
                break
        lam = float(np.max(np.abs(mult)))

        def dist_orbit(s):
            if self.spring.kind == "none":
                return min(self.distance(s, (o[0], o[1], o[2], s[3], o[4], o[5])) for o in orbit)
            return min(self.distance(s, o) for o in orbit)

        p_steady = None
        for i, s in enumerate(hist):
            if dist_orbit(s) < steady_tol:
                p_steady = i
                break
        extrapolated = False
        extra = 0
        while p_steady is None and extra < max_periods and lam < 0.9999:
            state = self.map_q(state, 1, shift=False)
            p += 1
            extra += 1
            if dist_orbit(state) < steady_tol:
                p_steady = p
        if p_steady is None:
            d = dist_orbit(state)
            p_steady = p + math.ceil(math.log(d / steady_tol) / -math.log(lam))
            extrapolated = True
        return dict(
            q=q_found, periods_run=p, fixed=fixed, multipliers=mult, newton_step=last,
            p_steady=p_steady, extrapolated=extrapolated,
        )

    def check_orbit(self, st):
        """On a fine grid: v_rel keeps the slip's sign, |F*| <= mu_0 F_c in
        stick, a free end's contact flag agrees with x_S >= gap."""
        T, sp = self.T, self.spring
        worst_slip, worst_stick, contact_ok = math.inf, -math.inf, True
        for kind, t0, t1, data in st.pieces:
            if t1 - t0 <= 0:
                continue
            nn = max(3, int(4000 * self.n * (t1 - t0) / T))
            tt = np.linspace(t0, t1, nn)[1:-1]
            if len(tt) == 0:
                continue
            if kind == "slip":
                s, contact, dense = data
                y = dense(tt / T)
                worst_slip = min(worst_slip, float(np.min(s * (y[1] - y[3]))) / self.v_scale)
                xs = y[2]
            else:
                delta, contact, dense = data
                y = dense(tt / T)
                xs = y[0] + delta
                f = [self.needed(t, a, b, a + delta, contact) for t, a, b in zip(tt, y[0], y[1])]
                worst_stick = max(worst_stick, float(np.max(np.abs(f))) / self.f0)
            if sp.kind == "free":
                contact_ok &= bool(np.all((xs >= sp.gap) == contact))
        return worst_slip, worst_stick, contact_ok


def load_inputs():
    scene = tomllib.loads((HERE / "driven_spring_reference_scene.toml").read_text())
    motor = {k: float(v) for k, v in scene["motor"].items()}
    act = scene["actuator"]
    designed = {k: float(act[k]) for k in ("mass", "damping", "stiffness", "transfer_factor")}
    real = dict(designed)
    real.update({k: float(v) for k, v in act.get("real", {}).items()})
    voltage, signal = {}, {}
    for name in SIGNALS:
        v = json.loads((HERE / f"driven_spring_reference_voltage_{name}.json").read_text())
        s = json.loads((HERE / f"driven_spring_reference_signal_{name}.json").read_text())
        for key in ("mass", "damping", "stiffness", "transfer_factor"):
            if float(v["actuator"][key]) != designed[key]:
                raise SystemExit(f"voltage {name}: actuator.{key} is not the scene's")
        voltage[name] = Series(v)
        signal[name] = s
    return dict(motor=motor, designed=designed, actuator_real=real, voltage=voltage,
                signal=signal)


def voltage_check(inputs, name, rtol):
    """The designed actuator without friction, from rest under u(t) for one
    period, against the signal; returns the largest deviation / stroke."""
    volt, sig = inputs["voltage"][name], inputs["signal"][name]
    act = inputs["designed"]
    M, d, c, alpha = act["mass"], act["damping"], act["stiffness"], act["transfer_factor"]
    T = volt.T
    xr = Series(sig)
    stroke = float(sig["stroke"])

    def rhs(u, y):
        t = u * T
        return [T * y[1], T * (alpha * volt(t) - d * y[1] - c * y[0]) / M]

    tt = np.linspace(0.0, 1.0, 257)
    vmax = float(np.max(np.abs(xr.deriv(tt * T, 1))))
    sol = solve_ivp(rhs, (0.0, 1.0), [0.0, 0.0], method="DOP853", rtol=rtol,
                    atol=[rtol * stroke, rtol * vmax], t_eval=tt, max_step=1 / (32 * volt.n))
    dx = float(np.max(np.abs(sol.y[0] - xr.deriv(tt * T, 0)))) / stroke
    dv = float(np.max(np.abs(sol.y[1] - xr.deriv(tt * T, 1)))) / vmax
    return dx, dv, abs(sol.y[0, -1]) / stroke, abs(sol.y[1, -1]) / vmax


def read(sim, start, periods):
    """What the spring reads over `periods` periods from `start`, checked on
    a fine grid."""
    st = Stats(keep_pieces=True)
    state = start
    for _ in range(periods):
        state = sim.period(state, st)
    Tq = sim.T * periods
    worst_slip, worst_stick, contact_ok = sim.check_orbit(st)
    return state, dict(
        mean_force=st.int_f / Tq,
        max_force=st.f_max,
        min_force=st.f_min,
        mean_position=st.int_x / Tq,
        contact_fraction=st.t_contact / Tq,
        stick_fraction=st.t_stick / Tq,
        mean_velocity=(state[3] - start[3]) / Tq,
        events=dict(st.events),
        worst_slip=worst_slip,
        worst_stick=worst_stick,
        contact_ok=contact_ok,
    )


def run_case(case, inputs, rtol, max_periods, orbit_from=None):
    """The steady orbit of one case; with orbit_from (a run_case result) its
    fixed point is only polished again, and read, at this rtol."""
    t_start = time.process_time()
    sim = Simulator(case, inputs, rtol)
    if orbit_from is None:
        res = sim.steady(max_periods)
    else:
        fixed, mult, last = sim.newton(orbit_from["fixed"], orbit_from["q"])
        res = dict(q=orbit_from["q"] if fixed is not None else None, fixed=fixed,
                   multipliers=mult, newton_step=last, periods_run=0, p_steady=None,
                   extrapolated=False)
    out = dict(rtol=rtol, reading="orbit")
    if res["q"] is None:
        out.update(q=None, periods_run=res["periods_run"], cpu=time.process_time() - t_start)
        return out
    q = res["q"]
    state, values = read(sim, res["fixed"], q)
    if sim.spring.kind == "none":
        state = (state[0], state[1], state[2], res["fixed"][3], state[4], state[5])
    out.update(values)
    out.update(
        q=q,
        reading_periods=q,
        periods_run=res["periods_run"],
        p_steady=res["p_steady"],
        extrapolated=res["extrapolated"],
        multipliers=res["multipliers"],
        newton_step=res["newton_step"],
        closure=sim.distance(state, res["fixed"]),
        fixed=res["fixed"],
        cpu=time.process_time() - t_start,
    )
    return out


def run_from_rest(case, inputs, rtol, periods):
    """The first `periods` periods from rest, for a case without an orbit."""
    t_start = time.process_time()
    sim = Simulator(case, inputs, rtol)
    _, values = read(sim, sim.start_state(), periods)
    out = dict(rtol=rtol, reading="from_rest", reading_periods=periods, q=None)
    out.update(values)
    out["cpu"] = time.process_time() - t_start
    return out


def cases():
    """The cases: signal, spring, reaction."""
    out = []

    def add(name, spring, signal="sqrtkappa2", reaction=True):
        out.append(dict(name=name, signal=signal, spring=spring, reaction=reaction))

    add("free_slider", Spring("none"))
    add("free_slider_sqrtkappa0_5", Spring("none"), signal="sqrtkappa0_5")
    for k in (1e3, 1e5, 1e6):
        add(f"tied_{k:.0e}", Spring("tied", k))
    add("tied_1e+05_preload_damping", Spring("tied", 1e5, b=0.5, preload=0.05))
    for gap in (0.0, 5e-6):
        for k in (1e5, 1e6):
            add(f"free_{k:.0e}_gap_{gap * 1e6:g}um", Spring("free", k, gap=gap))
    add("stick_tied_1e+04", Spring("tied", 1e4), signal="sqrtkappa0_5")
    add("stick_tied_1e+05", Spring("tied", 1e5), signal="sqrtkappa0_5")
    add("stick_free_1e+04", Spring("free", 1e4), signal="sqrtkappa0_5")
    add("reaction_off_tied_1e+05", Spring("tied", 1e5), reaction=False)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rtol", type=float, default=3e-14)
    ap.add_argument("--quick", action="store_true", help="two cases, print only")
    ap.add_argument("--only", help="run only the cases whose name contains this")
    ap.add_argument("--max-periods", type=int, default=4000)
    ap.add_argument("--from-rest", type=int, default=10,
                    help="periods from rest read where no orbit is found")
    ap.add_argument("--output", default=str(HERE / "driven_spring_reference.csv"))
    args = ap.parse_args()
    inputs = load_inputs()
    wall0 = time.time()
    for name in SIGNALS:
        dx, dv, x1, v1 = voltage_check(inputs, name, args.rtol)
        print(f"# check: voltage {name}: the designed actuator from rest follows the signal to "
              f"{dx:.1e} of the stroke, {dv:.1e} of max |v_R|; at T: x_R {x1:.1e}, v_R {v1:.1e}")
    todo = cases()
    if args.quick:
        todo = [todo[2], todo[-3]]
    if args.only:
        todo = [c for c in todo if args.only in c["name"]]
    rows = []
    for case in todo:
        fine = run_case(case, inputs, args.rtol, args.max_periods)
        if fine["q"]:
            coarse = [
                run_case(case, inputs, f * args.rtol, args.max_periods, orbit_from=fine)
                for f in (10, 100)
            ]
        else:
            # no orbit: the first periods from rest instead
            searched = fine["periods_run"]
            fine = run_from_rest(case, inputs, args.rtol, args.from_rest)
            fine["searched"] = searched
            coarse = [run_from_rest(case, inputs, f * args.rtol, args.from_rest) for f in (10, 100)]
        row = dict(case=case, fine=fine, coarse=coarse)
        rows.append(row)
        report(row)
        sys.stdout.flush()
    wall = time.time() - wall0
    print(f"# wall time {wall:.1f} s")
    if not args.quick and not args.only:
        write_csv(args.output, rows, args.rtol, wall)


def rel_err(row):
    """The largest relative difference of the mean force (the mean velocity
    without a spring) between the rtol run and those at 10 and 100 rtol."""
    f = row["fine"]
    key = "mean_velocity" if row["case"]["spring"].kind == "none" else "mean_force"
    diffs = [abs(f[key] - c[key]) / abs(f[key]) for c in row["coarse"] if key in c]
    return max(diffs) if diffs else math.nan


def err_est(row):
    """The largest differences between the rtol run and those at 10 and 100
    rtol: of the largest and least force (relative to the largest |force|)
    and of the contact and stick fractions."""
    f = row["fine"]
    scale = max(abs(f["max_force"]), abs(f["min_force"])) or 1.0
    ext = max((abs(f[k] - c[k]) / scale for c in row["coarse"] for k in ("max_force", "min_force")
               if k in c), default=math.nan)
    frac = max((abs(f[k] - c[k]) for c in row["coarse"]
                for k in ("contact_fraction", "stick_fraction") if k in c), default=math.nan)
    return ext, frac


def report(row):
    case, f = row["case"], row["fine"]
    head = f"{case['name']:28s} {case['signal']:13s} {case['spring'].label()}"
    common = (
        f"F_mean={f['mean_force']:.12e} N max={f['max_force']:.6e} min={f['min_force']:.6e} "
        f"x_mean={f['mean_position']:.6e} v_mean={f['mean_velocity']:.12e} "
        f"contact={f['contact_fraction']:.6f} stick={f['stick_fraction']:.6f} events={f['events']} "
        f"slipmargin={f['worst_slip']:.2e} stick|F*|/F0={f['worst_stick']:.6f} "
        f"contact_ok={f['contact_ok']} rel_err_est={rel_err(row):.2e} "
        f"extrema_err_est={err_est(row)[0]:.2e} fraction_err_est={err_est(row)[1]:.2e} "
        f"cpu={f['cpu']:.1f}+{sum(c.get('cpu', 0) for c in row['coarse']):.1f} s"
    )
    if f["reading"] == "from_rest":
        print(f"{head} no orbit of period <= 4 within {f['searched']} periods; "
              f"the first {f['reading_periods']} periods from rest: {common}")
        return
    print(
        f"{head} q={f['q']} p_steady={f['p_steady']}{'(extrap)' if f['extrapolated'] else ''} "
        f"run={f['periods_run']} |mult|={np.abs(f['multipliers']).round(6).tolist()} "
        f"newton_step={f['newton_step']:.1e} closure={f['closure']:.1e} {common}"
    )


COLS = [
    "case", "signal", "sqrt_kappa", "reaction", "spring", "k", "b", "preload", "gap",
    "reading", "reading_periods", "mean_force", "max_force", "min_force", "mean_position",
    "contact_fraction", "stick_fraction", "mean_velocity", "orbit_period", "periods_to_steady",
    "stick_slip", "slip_stick", "reversal", "contact_start", "contact_end",
    "max_floquet_modulus", "rel_err_est", "extrema_err_est", "fraction_err_est",
]


def write_csv(path, rows, rtol, wall):
    lines = [
        "# Reference: a driven rod (docs/model.md section 16) with the slider against a spring",
        "# (section 17). Columns in SI units (N, m, m/s, N/m, N s/m).",
        f"# Provenance: tests/data/driven_spring_reference.py (numpy {np.__version__}, scipy "
        f"{scipy.__version__},",
        f"# Python {sys.version.split()[0]}), {datetime.date.today().isoformat()}, solve_ivp "
        f"DOP853 rtol {rtol:g}; inputs",
        "# driven_spring_reference_scene.toml and driven_spring_reference_voltage_<signal>.json.",
        "# reading = orbit: over the steady orbit of orbit_period drive periods (periods_to_steady:",
        "# periods from rest until the boundary state is within 1e-9, scaled, of it); reading =",
        "# from_rest: no orbit of period <= 4 within periods_to_steady periods from rest, read",
        "# over the first reading_periods periods from rest instead. Events over the reading.",
        "# rel_err_est: the largest |value(rtol) - value(c rtol)| / |value|, c = 10 and 100, of",
        "# mean_force (mean_velocity without a spring): a bound of its error; extrema_err_est",
        "# the same of max_force and min_force relative to the largest |force|, fraction_err_est",
        "# of contact_fraction and stick_fraction (absolute).",
        f"# Wall time of the run that wrote this file: {wall:.0f} s.",
        ",".join(COLS),
    ]
    for row in rows:
        case, f = row["case"], row["fine"]
        sp = case["spring"]
        none = sp.kind == "none"
        ev = f["events"]
        rel = rel_err(row)
        orbit = f["reading"] == "orbit"

        def num(x, keep=not none):
            return f"{x:.15e}" if keep else ""

        vals = [
            case["name"], case["signal"], SIGNALS[case["signal"]], str(case["reaction"]).lower(),
            sp.kind, sp.k, sp.b, sp.preload, sp.gap, f["reading"], f["reading_periods"],
            num(f["mean_force"]), num(f["max_force"]), num(f["min_force"]),
            num(f["mean_position"]), num(f["contact_fraction"]), num(f["stick_fraction"], True),
            num(f["mean_velocity"], none), f["q"] if orbit else "",
            f["p_steady"] if orbit else f["searched"],
            ev.get("stick_slip", 0), ev.get("slip_stick", 0), ev.get("reversal", 0),
            ev.get("contact_start", 0), ev.get("contact_end", 0),
            f"{float(np.max(np.abs(f['multipliers']))):.6f}" if orbit else "",
            f"{rel:.2e}", f"{err_est(row)[0]:.2e}", f"{err_est(row)[1]:.2e}",
        ]
        lines.append(",".join(str(v) for v in vals))
    tmp = Path(path).with_suffix(".csv.tmp")
    tmp.write_text("\n".join(lines) + "\n")
    tmp.replace(path)


if __name__ == "__main__":
    main()
