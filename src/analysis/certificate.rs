//! The certificate that a fixed point of the period map is the limit of the
//! motion from rest (docs/model.md section 3, "The certificate").
//!
//! With `P` the period map and `g(v) = P(v) - v`, the orbit from rest
//! `u_0 = 0, u_(k+1) = P(u_k)` is monotone (`P` is non-decreasing) and its
//! limit is the fixed point nearest to rest in the direction it moves. A
//! fixed point `v*` found by a search is that limit iff no fixed point lies
//! between the orbit (or rest) and `v*`. This module proves it, or finds
//! the nearer one, by covering the gap with pieces `[a, b]` that are shown
//! free of fixed points; below for a rising orbit (`g > 0` towards `v*`),
//! the falling one is its mirror image.
//!
//! **Monotone step.** `P(a) > b` makes `[a, b]` free: for `w` there
//! `P(w) >= P(a) > b >= w`. This advances no faster than the orbit.
//!
//! **Growth bound.** Two sliders starting a period at `w_1 < w_2` keep
//! their order at every instant; their velocity difference `D(t)` changes
//! by the difference of their accelerations (`y = a_R - g_t`, stick band
//! `|y| <= a_0`, slip accelerations `g_t +- a_d`):
//!
//! | upper slider | lower slider | `D'` |
//! | --- | --- | --- |
//! | same mode as the lower one | | `0` |
//! | slips backward (above the rod) | slips forward (below) | `-2 a_d` |
//! | stuck | slips forward | `y - a_d` |
//! | slips backward | stuck | `-y - a_d` |
//!
//! `D` grows only while one slider is stuck and the other slides away, with
//! `a_d < |y| <= a_0`. Hence `P(w_2) - P(w_1) <= (w_2 - w_1) + G` with
//! `G = integral max(D', 0) dt`: the map is 1-Lipschitz upwards but for the
//! growth; the friction law makes `0 <= P' <= 1` wherever `P` is smooth
//! (each slip reversal multiplies `P'` by `a_rel+ / a_rel-` in `(0, 1]`,
//! a stick phase by 0), and `G` bounds the upward jumps that a stick
//! phase appearing between `w_1` and `w_2` adds (with `mu_0 = mu_d`
//! there are none: `G = 0`).
//!
//! For all `w_1 < w_2` in `[a, b]` the growth windows lie inside those of
//! the two ends: the upper one stuck and the lower one below the rod needs
//! `a` below the rod and `b` not below it (sliders between `a` and `b` lie
//! between them), and likewise for the other row. So
//!
//! ```text
//! G(w_1, w_2) <= G_ab = integral over {a below, b not below} of (y - a_d)+ 1{y <= a_0}
//!                     + integral over {a not above, b above} of (-y - a_d)+ 1{y >= -a_0},
//! ```
//!
//! computed from the modes of the two ends' periods (each event time
//! widened by the engine's event-time uncertainty) and rigorous bounds of
//! `a_R` on sub-intervals ([`Signal::acceleration_range`]). Then
//! `g(w) >= g(b) - G_ab` on `[a, b]`, and **`g(b) > G_ab` makes `[a, b]`
//! free**. Computed map values carry the engine's bound on one period's
//! velocity error plus a rounding bound; every comparison is made beyond
//! them.
//!
//! **The covering.** From the start `a = from` (rest, or the last point of
//! the simulated orbit, which covers what lies behind it) to
//! `c = v* - 2 bound` (`bound` the engine's bound on the fixed point, and
//! `[c, v*]` within the reported error, see [`CERTIFIED_REACH`]), a piece `[a, b]` that is free advances `a` to `b`;
//! one that is not is halved. A point `b` with `g(b) <= 0` beyond rounding
//! proves a fixed point in `[a, b]` (`P` maps `[a, b]` into itself, Tarski):
//! nearer than `v*`, and the first one beyond `a`, since everything up to
//! `a` is free. The search stops at a budget of map evaluations; then the
//! orbit from rest decides.

use crate::engine::{Direction, Mode, Observer, PeriodEngine, PeriodStart, Segment};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::signal::Signal;

/// A stretch of a period in one mode.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Stretch {
    start: f64,
    end: f64,
    mode: Mode,
}

/// Records the modes of a period, joining consecutive segments of one mode.
#[derive(Debug, Default)]
struct ModeRecorder {
    stretches: Vec<Stretch>,
}

impl Observer for ModeRecorder {
    fn segment(&mut self, s: &Segment, _signal: &Signal) {
        if let Some(last) = self.stretches.last_mut()
            && last.mode == s.mode
        {
            last.end = s.end;
            return;
        }
        self.stretches.push(Stretch {
            start: s.start,
            end: s.end,
            mode: s.mode,
        });
    }
}

/// A map evaluation `P(v)` with a bound on its error and the modes of its
/// period.
#[derive(Debug, Clone)]
struct Probe {
    v: f64,
    p: f64,
    /// The step `x_S(T) - x_S(0)` of the period (m).
    step: f64,
    /// Bound on `|computed P(v) - P(v)|` (infinite through a grazing).
    error: f64,
    stretches: Vec<Stretch>,
}

/// Evaluates `P(v)` with its modes.
fn probe<E: PeriodEngine>(engine: &mut E, v: f64) -> Result<Probe, SimulationError> {
    let mut recorder = ModeRecorder::default();
    let end = engine.run_period(
        2,
        PeriodStart {
            velocity: v,
            mode: None,
        },
        &mut recorder,
    )?;
    let signal = engine.signal();
    let rounding =
        8.0 * f64::EPSILON * (recorder.stretches.len() as f64 + 2.0) * signal.velocity_scale();
    let error = engine
        .last_velocity_uncertainty()
        .map_or(f64::INFINITY, |u| u + rounding);
    Ok(Probe {
        v,
        p: end.velocity,
        step: end.step,
        error: if error.is_nan() { f64::INFINITY } else { error },
        stretches: recorder.stretches,
    })
}

/// The friction constants the growth bound needs.
#[derive(Debug, Clone, Copy)]
struct Friction {
    a_0: f64,
    a_d: f64,
    g_t: f64,
}

/// Largest number of acceleration evaluations one growth bound spends on
/// sharpening its windows; past it the coarse bounds stand.
const GROWTH_EVALUATIONS: u32 = 64;

/// The growth bound `G_ab` of the module docs for the ends `lower` (`a`)
/// and `upper` (`b`, `a < b`) of a piece, with event times uncertain by
/// `eps`. A bound below `enough` is returned as soon as one is found
/// (the caller needs no sharper one).
fn growth_bound(
    signal: &Signal,
    friction: Friction,
    lower: &Probe,
    upper: &Probe,
    eps: f64,
    enough: f64,
) -> f64 {
    let period = signal.period();
    // The bound rests on the modes of the whole period; an engine that
    // hands out no segments gives none, and a period that held a decision
    // no error bound survives (a grazing) may have its modes wrong.
    let usable = |x: &Probe| covers(&x.stretches, period) && x.error.is_finite();
    if !(usable(lower) && usable(upper)) {
        return f64::INFINITY;
    }
    if friction.a_0 <= friction.a_d {
        // mu_0 = mu_d: D' <= 0 in every row of the table.
        return 0.0;
    }
    // Breakpoints: every change of mode of either end, widened by eps.
    let mut points = vec![0.0, period];
    for s in lower.stretches.iter().chain(&upper.stretches) {
        for t in [s.start, s.end] {
            if t > 0.0 && t < period {
                points.push((t - eps).max(0.0));
                points.push((t + eps).min(period));
            }
        }
    }
    points.sort_by(f64::total_cmp);
    points.dedup();
    // The windows where a row of growth may apply, with the rows.
    let mut windows = Vec::new();
    let (mut lower_at, mut upper_at) = (0, 0);
    for w in points.windows(2) {
        let (p, q) = (w[0], w[1]);
        let (l_stick, l_forward, _) = possible(&lower.stretches, &mut lower_at, (p, q), eps);
        let (u_stick, _, u_backward) = possible(&upper.stretches, &mut upper_at, (p, q), eps);
        // Row "upper stuck, lower forward": a below, b not below.
        let rises = l_forward && (u_stick || u_backward);
        // Row "upper backward, lower stuck": a not above, b above.
        let falls = (l_stick || l_forward) && u_backward;
        if q > p && (rises || falls) {
            windows.push((p, q, rises, falls));
        }
    }
    // First without evaluating a_R: D' <= a_0 - a_d throughout. Only where
    // that is not below `enough` are the windows sharpened.
    let coarse: f64 =
        windows.iter().map(|w| w.1 - w.0).sum::<f64>() * (friction.a_0 - friction.a_d);
    if coarse < enough {
        return coarse;
    }
    let mut budget = GROWTH_EVALUATIONS;
    let at_end = |t: f64| signal.acceleration(t.min(period * (1.0 - f64::EPSILON)));
    windows
        .iter()
        .map(|&(p, q, rises, falls)| {
            window_growth(
                signal,
                friction,
                (p, q),
                (at_end(p), at_end(q)),
                (rises, falls),
                &mut budget,
            )
        })
        .sum()
}

/// The modes `(stick, forward, backward)` a slider may have somewhere in
/// `[p, q]`: those of the stretches that reach into `[p - eps, q + eps]`.
/// `from` is a cursor into `stretches` for windows taken in increasing
/// order: the first stretch that may still reach a window.
fn possible(
    stretches: &[Stretch],
    from: &mut usize,
    (p, q): (f64, f64),
    eps: f64,
) -> (bool, bool, bool) {
    while *from < stretches.len() && stretches[*from].end + eps <= p {
        *from += 1;
    }
    let (mut stick, mut forward, mut backward) = (false, false, false);
    for s in stretches[*from..].iter().take_while(|s| s.start - eps < q) {
        if s.end + eps > p {
            match s.mode {
                Mode::Stick => stick = true,
                Mode::Slip(Direction::Forward) => forward = true,
                Mode::Slip(Direction::Backward) => backward = true,
            }
        }
    }
    (stick, forward, backward)
}

/// True if the stretches cover the period `[0, T]` without a gap.
fn covers(stretches: &[Stretch], period: f64) -> bool {
    stretches.first().is_some_and(|s| s.start == 0.0)
        && stretches.last().is_some_and(|s| s.end == period)
        && stretches.windows(2).all(|w| w[0].end == w[1].start)
}

/// `integral max(D', 0)` over the window `[p, q]` bounded from above, with
/// the rows that may apply there; the window is halved while halving can
/// sharpen the bound and the evaluation budget lasts.
fn window_growth(
    signal: &Signal,
    f: Friction,
    (p, q): (f64, f64),
    (a_p, a_q): (f64, f64),
    (rises, falls): (bool, bool),
    budget: &mut u32,
) -> f64 {
    let (lo, hi) = signal.acceleration_range(p, q, a_p, a_q);
    let (y_lo, y_hi) = (lo - f.g_t, hi - f.g_t);
    // Upper stuck (|y| <= a_0), lower slipping forward: D' = y - a_d.
    let c_rise = if rises && y_lo <= f.a_0 {
        (y_hi.min(f.a_0) - f.a_d).max(0.0)
    } else {
        0.0
    };
    // Upper slipping backward, lower stuck: D' = -y - a_d.
    let c_fall = if falls && y_hi >= -f.a_0 {
        (-(y_lo.max(-f.a_0)) - f.a_d).max(0.0)
    } else {
        0.0
    };
    let c = c_rise.max(c_fall);
    let coarse = c * (q - p);
    if c == 0.0 || *budget == 0 {
        return coarse;
    }
    let m = 0.5 * (p + q);
    if m <= p || m >= q {
        return coarse;
    }
    // Halving helps where the range of a_R on the window, not the
    // acceleration itself, puts it into the growth band.
    if (hi - lo) <= 0.25 * (f.a_0 - f.a_d) && (y_lo > f.a_d || y_hi < -f.a_d) {
        return coarse;
    }
    *budget -= 1;
    let a_m = signal.acceleration(m);
    let halves = window_growth(signal, f, (p, m), (a_p, a_m), (rises, falls), budget)
        + window_growth(signal, f, (m, q), (a_m, a_q), (rises, falls), budget);
    halves.min(coarse)
}

/// The covering ends at `v* - 2 bound`, not at `v* - bound`: at the end,
/// `g` must be positive beyond the error of its computed value, which the
/// fixed point's bound holds once and its double holds with that margin.
/// The limit from rest is then proven within `2 bound` of `v*`, and the
/// reported error is taken over that reach.
pub(crate) const CERTIFIED_REACH: f64 = 2.0;

/// What the covering found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Verdict {
    /// No fixed point between the start and `v* - 2 bound`, and a point at
    /// `v* + 2 bound` that the map moves back.
    Certified,
    /// A fixed point lies between the velocities `near` and `far`, and none
    /// between the start and `near`: it is nearer than `v*`. `near = far`
    /// when the start itself is moved back beyond rounding.
    Nearer {
        /// The end towards the start (`g` moves it towards `v*`).
        near: f64,
        /// The other end (`g` there points back, beyond rounding).
        far: f64,
    },
    /// No fixed point between the start and the covering's end, and the
    /// point beyond it is moved on, away from the start, beyond rounding:
    /// nothing closes the interval there (with `bound = 0` and the end at
    /// the rod's extreme velocity, the first step of a proof that the
    /// slider runs away).
    Open {
        /// `P` at the point beyond the end (m/s).
        beyond: f64,
    },
    /// Neither within the budget of map evaluations.
    Undecided,
}

/// The outcome of [`certify`] and the map evaluations it took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Covering {
    pub(crate) verdict: Verdict,
    pub(crate) evaluations: u32,
    /// When certified: bounds `(lo, hi)` on the mean velocity `v_inf` of
    /// the limit from rest (m/s). The limit's boundary velocity lies
    /// between the two ends `v* -+ 2 bound`, and a slider that starts a
    /// period faster stays ahead through it, so its step lies between the
    /// ends' steps; each is widened by the end's velocity error bound.
    /// This holds also where `v_inf` jumps with the boundary velocity.
    pub(crate) v_inf_bounds: Option<(f64, f64)>,
}

/// The covering of the module docs between `from` (rest, or a point of the
/// orbit from rest) and `v_star - 2 bound` ([`CERTIFIED_REACH`], on the
/// side of `from`), with at most `budget` map evaluations, closed by a
/// point `v_star + 2 bound` that the map moves back: `P` then maps the
/// interval between the covering's end and that point into itself, so the
/// limit from rest lies within `2 bound` of `v_star`.
pub(crate) fn certify<E: PeriodEngine>(
    engine: &mut E,
    motor: &Motor,
    from: f64,
    v_star: f64,
    bound: f64,
    budget: u32,
) -> Result<Covering, SimulationError> {
    let reach = CERTIFIED_REACH * bound;
    certify_between(engine, motor, from, v_star, (reach, reach), budget)
}

/// [`certify`] with the covering's end `v_star - below` and the closing
/// point `v_star + above` (on the side of `from`, and beyond `v_star`)
/// given apart: a closing point farther out brackets the limit from rest
/// also where the map pushes on past `v_star` (a fixed point at a jump of
/// the map, where a grazing decides between two outcomes).
pub(crate) fn certify_between<E: PeriodEngine>(
    engine: &mut E,
    motor: &Motor,
    from: f64,
    v_star: f64,
    (below, above): (f64, f64),
    budget: u32,
) -> Result<Covering, SimulationError> {
    // The orbit from rest moves from 0 towards its limit, so the direction
    // is the sign of v*, whatever side of v* its last point `from` lies on
    // within rounding.
    let s = if v_star > 0.0 {
        1.0
    } else if v_star < 0.0 {
        -1.0
    } else if from == 0.0 {
        // At rest, and the search found the map leaves rest where it is.
        return Ok(Covering {
            verdict: Verdict::Certified,
            evaluations: 0,
            v_inf_bounds: None,
        });
    } else {
        return Ok(Covering {
            verdict: Verdict::Undecided,
            evaluations: 0,
            v_inf_bounds: None,
        });
    };
    let target = v_star - s * below;
    let mut evaluations = 0;
    // The end beyond v*: a point there that the map moves back proves a
    // fixed point between the covering's end `target` and it; the steps of
    // the two ends bound the limit's v_inf.
    let period = engine.signal().period();
    let closes = |engine: &mut E,
                  evaluations: &mut u32,
                  end: Option<Probe>|
     -> Result<(Verdict, Option<(f64, f64)>), SimulationError> {
        let end = match end {
            Some(end) => end,
            None => {
                *evaluations += 1;
                probe(engine, target)?
            }
        };
        let beyond = probe(engine, v_star + s * above)?;
        *evaluations += 1;
        if s * (beyond.p - beyond.v) > beyond.error {
            return Ok((Verdict::Open { beyond: beyond.p }, None));
        }
        if s * (beyond.p - beyond.v) + beyond.error >= 0.0 {
            return Ok((Verdict::Undecided, None));
        }
        let mean = |x: &Probe, side: f64| x.step / period + side * x.error;
        let (a, b) = (mean(&end, -s), mean(&beyond, s));
        Ok((Verdict::Certified, Some((a.min(b), a.max(b)))))
    };
    if (target - from) * s <= 0.0 {
        // The start lies within the reach of v*: it must not be moved back
        // (then the map sends the interval from it to the closing point
        // into itself).
        let start = probe(engine, from)?;
        evaluations += 1;
        if s * (start.p - start.v) + start.error < 0.0 {
            return Ok(Covering {
                verdict: Verdict::Undecided,
                evaluations,
                v_inf_bounds: None,
            });
        }
        let (verdict, v_inf_bounds) = closes(engine, &mut evaluations, None)?;
        return Ok(Covering {
            verdict,
            evaluations,
            v_inf_bounds,
        });
    }
    let friction = Friction {
        a_0: motor.a_0(),
        a_d: motor.a_d(),
        g_t: motor.g_t(),
    };
    // Mode boundaries are widened by the engine's event-time uncertainty
    // with a margin of 256 for what the root finder's exit on a small
    // residual and the period's velocity error move a crossing.
    let eps = 256.0 * engine.event_time_uncertainty();
    let mut left = probe(engine, from)?;
    evaluations += 1;
    // Progress of a probe towards v_star, and whether it is proven positive
    // or proven not positive.
    let progress = |x: &Probe| s * (x.p - x.v);
    if progress(&left) <= left.error {
        // The start itself is not moved towards v_star beyond rounding.
        return Ok(Covering {
            verdict: if progress(&left) + left.error <= 0.0 {
                Verdict::Nearer {
                    near: from,
                    far: from,
                }
            } else {
                Verdict::Undecided
            },
            evaluations,
            v_inf_bounds: None,
        });
    }
    let end = probe(engine, target)?;
    evaluations += 1;
    let mut stack = vec![end.clone()];
    while let Some(right) = stack.last() {
        // Monotone step: P(left) beyond right.
        let monotone = s * (left.p - right.v) > left.error;
        let free = monotone || {
            let g_right = progress(right) - right.error;
            g_right > 0.0 && {
                let (lower, upper) = if s > 0.0 {
                    (&left, right)
                } else {
                    (right, &left)
                };
                g_right > growth_bound(engine.signal(), friction, lower, upper, eps, g_right)
            }
        };
        if free {
            left = stack.pop().expect("the stack holds right");
            continue;
        }
        if progress(right) + right.error <= 0.0 {
            return Ok(Covering {
                verdict: Verdict::Nearer {
                    near: left.v,
                    far: right.v,
                },
                evaluations,
                v_inf_bounds: None,
            });
        }
        let m = 0.5 * (left.v + right.v);
        if evaluations >= budget || m == left.v || m == right.v {
            return Ok(Covering {
                verdict: Verdict::Undecided,
                evaluations,
                v_inf_bounds: None,
            });
        }
        stack.push(probe(engine, m)?);
        evaluations += 1;
    }
    let (verdict, v_inf_bounds) = closes(engine, &mut evaluations, Some(end))?;
    Ok(Covering {
        verdict,
        evaluations,
        v_inf_bounds,
    })
}

#[cfg(test)]
mod tests;
