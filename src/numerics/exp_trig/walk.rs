//! The left-to-right walk of [`super::ExpTrig::first_zero`]: pieces, their
//! classes and their resolution (module documentation of [`super`],
//! "Method").

use super::{Crossing, DampedOscillator, EPS, ExpTrig, Regime, Scale, Start, Work, bracket};

/// What a search needs besides the function: `f` scaled by a power of two
/// ([`ExpTrig::prepare`]), its bounds and its band.
pub(super) struct Prepared<'f> {
    /// `f` unscaled; its harmonics are scaled as they are used.
    pub f: &'f ExpTrig,
    /// The power of two.
    pub scale: Scale,
    /// The scaled quadratic.
    pub poly: [f64; 3],
    /// The scaled oscillators (`None` also where `f`'s is zero).
    pub osc: [Option<DampedOscillator>; 2],
    /// Their regimes.
    pub regime: [Option<Regime>; 2],
    /// `M_j = Σ_k hypot(a_k, b_k) (k w)^j`, `j < 6`.
    pub bounds: [f64; 6],
    /// Rounding bounds `η_j` of the computed `f^(j)`, `j <= 3`, on `[0, s_b]`.
    pub eta: [f64; 4],
    /// Rounding bounds of each oscillator's computed derivatives, `j <= 6`.
    pub osc_err: [[f64; 7]; 2],
    /// The band `τ`: `|f| <= τ` at a critical point is a tangency.
    pub tau: f64,
}

impl Prepared<'_> {
    /// The scaled `f` and its first three derivatives at `s`, and its
    /// oscillators' `y, y', y''`: the values, bit for bit, of
    /// [`ExpTrig::eval4`] on the scaled copy.
    fn eval4(&self, s: f64) -> ([f64; 4], [[f64; 3]; 2]) {
        let scale = self.scale;
        self.f
            .eval4_with(self.poly, self.oscillators(), move |x| scale.apply(x), s)
    }

    /// Each oscillator with its regime.
    fn oscillators(&self) -> [Option<(&DampedOscillator, Regime)>; 2] {
        [0, 1].map(|i| self.osc[i].as_ref().zip(self.regime[i]))
    }
}

/// Computed `f`, `f'`, `f''`, `f'''` at `s`, and each oscillator's
/// `y, y', y''`.
#[derive(Debug, Clone, Copy)]
struct Point {
    s: f64,
    d: [f64; 4],
    y: [[f64; 3]; 2],
}

/// How many of the last points the walk keeps: a halved piece's left half
/// ends at the midpoint just evaluated, and a piece's right end is the
/// next one's left end.
const RECENT: usize = 4;

/// What the walk knows about `f` left of the current piece.
#[derive(Debug, Clone, Copy, PartialEq)]
enum State {
    /// Looking for an event.
    Clear,
    /// `f` crossed zero at `z` and has stayed within the band since,
    /// without a critical point: the crossing is reported when `f` leaves
    /// the band, a tangency if `f` turns inside it first.
    Pending { z: f64, rising: bool },
    /// `f` has stayed within the band since the event at `s_a`.
    Departing,
}

/// The class of a piece (module documentation, "Method").
#[derive(Debug, Clone, Copy, PartialEq)]
enum Class {
    /// `|f| > τ` on the piece.
    Excluded,
    /// `f' != 0` on the piece, with this sign.
    Monotone { rising: bool },
    /// `f'' != 0` on the piece, with the sign `sigma` (±1).
    Convex { sigma: f64 },
    /// None of the above could be shown.
    Unresolved,
}

/// The Taylor model of `f` on a piece `[m - h, m + h]`: the computed
/// derivatives at `m`, their rounding bounds, and bounds on `|f''|` and
/// `|f'''|` over the piece.
#[derive(Debug, Clone, Copy)]
struct Model {
    m: f64,
    h: f64,
    d: [f64; 4],
    eta: [f64; 4],
    up2: f64,
    up3: f64,
}

impl Model {
    /// An interval holding `f(t)`, for `t` in the piece.
    fn value(&self, t: f64) -> (f64, f64) {
        let (d, e) = (self.d, self.eta);
        let dt = t - self.m;
        let a = dt.abs();
        let center = d[0] + dt * (d[1] + 0.5 * dt * d[2]);
        let terms = d[0].abs() + a * (d[1].abs() + 0.5 * a * d[2].abs());
        let radius = e[0]
            + a * (e[1] + a * (0.5 * e[2] + a * self.up3 / 6.0))
            + 4.0 * EPS * terms
            + EPS * a * (d[1].abs() + e[1] + self.up2 * a);
        (center - radius, center + radius)
    }

    /// An interval holding `f'(t)`, for `t` in the piece.
    fn slope(&self, t: f64) -> (f64, f64) {
        let (d, e) = (self.d, self.eta);
        let dt = t - self.m;
        let a = dt.abs();
        let center = d[1] + dt * d[2];
        let radius = e[1]
            + a * (e[2] + 0.5 * a * self.up3)
            + 4.0 * EPS * (d[1].abs() + a * d[2].abs())
            + EPS * a * (d[2].abs() + e[2] + self.up3 * a);
        (center - radius, center + radius)
    }
}

/// The sign of an interval: ±1 if it excludes zero, else 0.
fn interval_sign((lo, hi): (f64, f64)) -> i8 {
    if lo > 0.0 {
        1
    } else if hi < 0.0 {
        -1
    } else {
        0
    }
}

/// One search ([`Walk::run`]).
pub(super) struct Walk<'a> {
    p: &'a Prepared<'a>,
    lo: f64,
    hi: f64,
    /// Time resolution of a root (the rounding of the phase).
    t_tol: f64,
    /// Smallest half-width of a piece before it is a cluster.
    h_min: f64,
    /// Width of the first piece.
    width0: f64,
    work: &'a mut Work,
    /// The last points evaluated.
    recent: [Point; RECENT],
    /// The bits of their times (`u64::MAX`, a NaN no time has, where there
    /// is none yet).
    recent_s: [u64; RECENT],
    /// Where the next point evaluated goes in `recent`.
    next_recent: usize,
}

impl<'a> Walk<'a> {
    pub(super) fn new(p: &'a Prepared<'a>, lo: f64, hi: f64, work: &'a mut Work) -> Self {
        let f = p.f;
        let top = f
            .pairs()
            .enumerate()
            .filter(|&(_, (a, b))| p.scale.apply(a) != 0.0 || p.scale.apply(b) != 0.0)
            .last()
            .map_or(0.0, |(i, _)| (i + 1) as f64 * f.w);
        let osc_rate = p.osc.iter().flatten().fold(0.0_f64, |r, o| {
            r.max(if o.sigma > o.omega0 {
                o.sigma + ((o.sigma - o.omega0) * (o.sigma + o.omega0)).sqrt()
            } else {
                o.omega0
            })
        });
        let rate = top.max(osc_rate).max(1.0 / (hi - lo));
        let resolution = 2.0 * EPS * (f.phi.abs() + hi.abs());
        Walk {
            p,
            lo,
            hi,
            t_tol: resolution,
            h_min: (1e-10 / rate).max(8.0 * resolution),
            width0: (1.0 / rate).min(hi - lo),
            work,
            recent: [Point {
                s: f64::NAN,
                d: [0.0; 4],
                y: [[0.0; 3]; 2],
            }; RECENT],
            recent_s: [u64::MAX; RECENT],
            next_recent: 0,
        }
    }

    fn tau(&self) -> f64 {
        self.p.tau
    }

    fn eta(&self) -> [f64; 4] {
        self.p.eta
    }

    /// `f` and three derivatives at `s`: one of the last points, or an
    /// evaluation, counted.
    fn point(&mut self, s: f64) -> Point {
        if let Some(p) = self.recent(s) {
            return p;
        }
        self.work.evaluations += 1;
        let (d, y) = self.p.eval4(s);
        let p = Point { s, d, y };
        self.remember(p);
        p
    }

    /// Keeps `p` among the last points, in place of the oldest.
    fn remember(&mut self, p: Point) {
        self.recent[self.next_recent] = p;
        self.recent_s[self.next_recent] = p.s.to_bits();
        self.next_recent = (self.next_recent + 1) % RECENT;
    }

    /// The point at exactly `s` among the last ones evaluated.
    fn recent(&self, s: f64) -> Option<Point> {
        let bits = s.to_bits();
        (0..RECENT)
            .find(|&i| self.recent_s[i] == bits)
            .map(|i| self.recent[i])
    }

    /// The point at `x`: `left` if it is there, else a new evaluation.
    fn left_point(&mut self, left: Option<Point>, x: f64) -> Point {
        match left {
            Some(p) if p.s == x => p,
            _ => self.point(x),
        }
    }

    /// The sign of a computed value, 0 at the rounding level `η0`.
    fn sign(&self, v: f64) -> i8 {
        if v > self.eta()[0] {
            1
        } else if v < -self.eta()[0] {
            -1
        } else {
            0
        }
    }

    /// Bounds on `|y^(j)|`, `j <= 4`, for `s >= x`: each oscillator's,
    /// summed (zero without one).
    fn osc_bounds(&self, x: f64) -> [f64; 5] {
        let mut out = [0.0; 5];
        let recent = self.recent(x);
        for (i, osc) in self.p.oscillators().into_iter().enumerate() {
            let Some((o, regime)) = osc else { continue };
            let y = recent.map_or_else(|| o.eval_in(regime, x), |p| p.y[i]);
            let u = o.extend::<6>(&y);
            let b = o.derivative_bounds::<5>(&u, &self.p.osc_err[i][..6]);
            for (o, b) in out.iter_mut().zip(b) {
                *o += b;
            }
        }
        out
    }

    /// The first event in `(lo, hi]` (module documentation, "Method").
    pub(super) fn run(mut self, start: Start) -> Option<Crossing> {
        let first = self.point(self.lo);
        let mut state = match start {
            Start::AfterEvent if first.d[0].abs() <= self.tau() => State::Departing,
            _ => State::Clear,
        };
        let mut left = Some(first);
        let mut x = self.lo;
        let mut width = self.width0;
        let mut y = (x, self.osc_bounds(x));
        while x < self.hi {
            if self.work.budget > 0 && self.work.evaluations >= self.work.budget {
                self.work.exhausted = true;
                return None;
            }
            let mut r = if self.hi - x <= 1.25 * width {
                self.hi
            } else {
                x + width
            };
            if r <= x {
                r = self.hi;
            }
            if y.0 != x {
                y = (x, self.osc_bounds(x));
            }
            let (class, model) = self.classify(x, r, &y.1);
            if class == Class::Unresolved && r - x > 2.0 * self.h_min {
                self.work.subdivisions += 1;
                width = 0.5 * (r - x);
                continue;
            }
            self.work.pieces += 1;
            let event = match class {
                Class::Excluded => {
                    left = None;
                    self.leave_band(&mut state)
                }
                Class::Monotone { rising } => {
                    self.monotone_piece(&mut state, &mut left, (x, r), rising, &model)
                }
                Class::Convex { sigma } => {
                    self.convex_piece(&mut state, &mut left, (x, r), sigma, &model)
                }
                Class::Unresolved => {
                    self.work.clusters += 1;
                    self.cluster(&mut state, &mut left, (x, r), &model)
                }
            };
            if event.is_some() {
                return event;
            }
            // Excluded pieces may grow faster than resolved ones; both
            // slowly enough that few next pieces need halving.
            let growth = if class == Class::Excluded { 1.5 } else { 1.25 };
            width = growth * (r - x);
            x = r;
        }
        match state {
            State::Pending { z, rising } => Some(Crossing::Transversal { s: z, rising }),
            _ => None,
        }
    }

    /// The class of the piece `[x, r]` and its model, from one evaluation
    /// at the midpoint and the bounds `y` on the oscillator from `x` on.
    fn classify(&mut self, x: f64, r: f64, y: &[f64; 5]) -> (Class, Model) {
        let m = 0.5 * (x + r);
        let h = (m - x).max(r - m) * (1.0 + 4.0 * EPS);
        let d = self.point(m).d;
        let e = self.eta();
        let poly = self.p.poly;
        let mj = &self.p.bounds;
        let safe = 1.0 + 1e-10;
        let b2 = (mj[2] + y[2] + 2.0 * poly[2].abs()) * safe;
        let b3 = (mj[3] + y[3]) * safe;
        let b4 = (mj[4] + y[4]) * safe;
        // upper bounds at m, lower bounds at m
        let up: [f64; 4] = std::array::from_fn(|j| d[j].abs() + e[j]);
        let low: [f64; 3] = std::array::from_fn(|j| d[j].abs() - e[j]);
        let up3 = b3.min(up[3] + b4 * h);
        let up2 = b2
            .min(up[2] + h * (up[3] + 0.5 * b4 * h))
            .min(up[2] + up3 * h);
        let l2 = low[2] - up3 * h - 8.0 * EPS * (up[2] + up3 * h);
        let l1 =
            low[1] - (up2 * h).min(h * (up[2] + 0.5 * up3 * h)) - 8.0 * EPS * (up[1] + up2 * h);
        let margin0 = 8.0 * EPS * (up[0] + h * (up[1] + up2 * h));
        let taylor =
            low[0] - up[1] * h - (0.5 * up2 * h * h).min(h * h * (0.5 * up[2] + up3 * h / 6.0));
        let [_, p1, p2] = poly;
        let poly_slope = p1.abs() + 2.0 * p2.abs() * (m.abs() + h);
        let poly = low[0] - 2.0 * (mj[0] + y[0]) - h * (poly_slope + p2.abs() * h);
        let convex = if l2 > 0.0 && d[0] * d[2] > 0.0 {
            low[0] - up[1] * up[1] / (2.0 * l2)
        } else {
            f64::NEG_INFINITY
        };
        let l0 = taylor.max(poly).max(convex) - margin0;
        let class = if l0 > self.tau() {
            Class::Excluded
        } else if l1 > 0.0 {
            Class::Monotone { rising: d[1] > 0.0 }
        } else if l2 > 0.0 {
            Class::Convex {
                sigma: d[2].signum(),
            }
        } else {
            Class::Unresolved
        };
        let model = Model {
            m,
            h,
            d,
            eta: e,
            up2,
            up3,
        };
        (class, model)
    }

    /// `f` has left the band (or never was in it): a pending crossing is
    /// reported, a departure ends.
    fn leave_band(&self, state: &mut State) -> Option<Crossing> {
        match *state {
            State::Pending { z, rising } => Some(Crossing::Transversal { s: z, rising }),
            State::Departing => {
                *state = State::Clear;
                None
            }
            State::Clear => None,
        }
    }

    /// A piece on which `f` is monotone. The model decides without
    /// evaluating where it can (no sign change; the band certainly left or
    /// certainly not); else the ends are evaluated ([`Walk::monotone`]).
    fn monotone_piece(
        &mut self,
        state: &mut State,
        left: &mut Option<Point>,
        (x, r): (f64, f64),
        rising: bool,
        model: &Model,
    ) -> Option<Crossing> {
        let tau = self.tau();
        let end = model.value(r);
        match *state {
            State::Clear => {
                let start = match *left {
                    Some(p) if p.s == x => (p.d[0] - self.eta()[0], p.d[0] + self.eta()[0]),
                    _ => model.value(x),
                };
                let sign = interval_sign(start);
                if sign != 0 && sign == interval_sign(end) {
                    *left = None;
                    return None;
                }
            }
            State::Pending { .. } | State::Departing => {
                if end.0 > tau || end.1 < -tau {
                    *left = None;
                    return self.leave_band(state);
                }
                if end.0 >= -tau && end.1 <= tau {
                    *left = None;
                    return None;
                }
            }
        }
        let a = self.left_point(*left, x);
        let b = self.point(r);
        *left = Some(b);
        self.monotone(state, &a, &b, rising)
    }

    /// `f` monotone from `a` to `b` (direction `rising`).
    fn monotone(
        &mut self,
        state: &mut State,
        a: &Point,
        b: &Point,
        rising: bool,
    ) -> Option<Crossing> {
        let tau = self.tau();
        let fb = b.d[0];
        match *state {
            State::Departing => {
                if fb.abs() > tau {
                    *state = State::Clear;
                }
                None
            }
            State::Pending { .. } => {
                if fb.abs() > tau {
                    self.leave_band(state)
                } else {
                    None
                }
            }
            State::Clear => {
                let (sa, sb) = (self.sign(a.d[0]), self.sign(fb));
                if sa == 0 || sb == sa {
                    return None;
                }
                let z = if sb == 0 {
                    // the zero is at b within rounding: one Newton step
                    let step = if b.d[1] != 0.0 { fb / b.d[1] } else { 0.0 };
                    (b.s - step).clamp(a.s, b.s)
                } else {
                    self.solve_value(a, b)
                };
                let z = z.max(self.lo.next_up()).min(b.s);
                if fb.abs() > tau {
                    Some(Crossing::Transversal { s: z, rising })
                } else {
                    *state = State::Pending { z, rising };
                    None
                }
            }
        }
    }

    /// The zero of `f` between `a` and `b`, whose computed values have
    /// opposite signs (bracketed Newton, [`bracket::solve`]).
    fn solve_value(&mut self, a: &Point, b: &Point) -> f64 {
        let p = self.p;
        let mut last = None;
        let root = bracket::solve(
            |t| {
                let (d, y) = p.eval4(t);
                last = Some(Point { s: t, d, y });
                (d[0], d[1])
            },
            (a.s, b.s),
            (a.d[0], b.d[0]),
            self.t_tol,
            self.eta()[0],
            None,
        );
        self.work.evaluations += u64::from(root.iterations);
        if let Some(point) = last {
            self.remember(point);
        }
        root.t
    }

    /// A piece on which `f''` has the sign `sigma`: `f'` is monotone, so
    /// `f` has at most one critical point `c`; the piece is resolved as
    /// the monotone stretches `[x, c]`, `[c, r]` and the critical point.
    fn convex_piece(
        &mut self,
        state: &mut State,
        left: &mut Option<Point>,
        (x, r): (f64, f64),
        sigma: f64,
        model: &Model,
    ) -> Option<Crossing> {
        // f' has one sign on the piece if it has that sign at the end where
        // it is closest to zero
        let (sx, sr) = (interval_sign(model.slope(x)), interval_sign(model.slope(r)));
        let up = if sigma > 0.0 { 1 } else { -1 };
        if sx == up || sr == -up {
            let rising = if sx == up { sigma > 0.0 } else { sigma < 0.0 };
            return self.monotone_piece(state, left, (x, r), rising, model);
        }
        if *state == State::Clear {
            // f'' of sign σ: σ f is at most its larger end value, so ends
            // beyond the band on the side -σ hold f beyond it in between.
            let tau = self.tau();
            let (vx, vr) = (model.value(x), model.value(r));
            let beyond = if sigma > 0.0 {
                vx.1 < -tau && vr.1 < -tau
            } else {
                vx.0 > tau && vr.0 > tau
            };
            if beyond {
                *left = None;
                return None;
            }
        }
        let a = self.left_point(*left, x);
        let b = self.point(r);
        *left = Some(b);
        let eta1 = self.eta()[1];
        let (da, db) = (sigma * a.d[1], sigma * b.d[1]);
        if da > eta1 || db < -eta1 {
            let rising = if da > eta1 { sigma > 0.0 } else { sigma < 0.0 };
            return self.monotone(state, &a, &b, rising);
        }
        let c = if da < -eta1 && db > eta1 {
            let p = self.p;
            let mut last = None;
            let root = bracket::solve(
                |t| {
                    let (d, y) = p.eval4(t);
                    last = Some(Point { s: t, d, y });
                    (d[1], d[2])
                },
                (x, r),
                (a.d[1], b.d[1]),
                self.t_tol,
                eta1,
                None,
            );
            self.work.evaluations += u64::from(root.iterations);
            if let Some(point) = last {
                self.remember(point);
            }
            self.point(root.t)
        } else if a.d[1].abs() <= b.d[1].abs() {
            a
        } else {
            b
        };
        if c.s > a.s
            && let Some(event) = self.monotone(state, &a, &c, sigma < 0.0)
        {
            return Some(event);
        }
        if let Some(event) = self.critical(state, &c) {
            return Some(event);
        }
        if c.s < b.s {
            return self.monotone(state, &c, &b, sigma > 0.0);
        }
        None
    }

    /// A critical point `c` of `f`: a tangency if `|f(c)| <= τ` (unless the
    /// walk is departing from the event at `s_a`).
    fn critical(&mut self, state: &mut State, c: &Point) -> Option<Crossing> {
        let inside = c.d[0].abs() <= self.tau();
        match *state {
            State::Clear if inside => {
                if c.s > self.lo {
                    return Some(Crossing::Tangency { s: c.s });
                }
                // a critical point at s_a itself: f leaves it as from an event
                *state = State::Departing;
                None
            }
            State::Pending { .. } if inside => Some(Crossing::Tangency { s: c.s }),
            State::Pending { .. } | State::Departing if !inside => self.leave_band(state),
            _ => None,
        }
    }

    /// A piece at the smallest width that no test decided: nine samples
    /// (module documentation, "Method").
    fn cluster(
        &mut self,
        state: &mut State,
        left: &mut Option<Point>,
        (x, r): (f64, f64),
        model: &Model,
    ) -> Option<Crossing> {
        let first = self.left_point(*left, x);
        let mut samples = vec![first];
        for i in 1..=8 {
            let s = if i == 8 {
                r
            } else {
                x + (r - x) * (i as f64 / 8.0)
            };
            let p = self.point(s);
            samples.push(p);
        }
        let last = samples[8];
        *left = Some(last);
        match *state {
            State::Pending { z, rising } => Some(Crossing::Transversal { s: z, rising }),
            State::Departing => {
                if last.d[0].abs() > self.tau() {
                    *state = State::Clear;
                }
                None
            }
            State::Clear => {
                let mut signed: Option<Point> = None;
                for p in &samples {
                    let sign = self.sign(p.d[0]);
                    if sign == 0 {
                        continue;
                    }
                    if let Some(q) = signed
                        && self.sign(q.d[0]) != sign
                    {
                        let z = self.solve_value(&q, p).max(self.lo.next_up());
                        return Some(Crossing::Transversal {
                            s: z,
                            rising: sign > 0,
                        });
                    }
                    signed = Some(*p);
                }
                // every point is within (r - x)/16 of a sample, where f
                // differs from it by at most sup |f'| times that
                let slope = model.d[1].abs() + self.eta()[1] + model.up2 * model.h;
                let spread = self.eta()[0] + slope * (r - x) / 16.0;
                let best = samples
                    .iter()
                    .min_by(|p, q| p.d[0].abs().total_cmp(&q.d[0].abs()))?;
                if best.d[0].abs() - spread > self.tau() {
                    return None;
                }
                if best.s > self.lo {
                    return Some(Crossing::Tangency { s: best.s });
                }
                // the touch is at s_a itself: f leaves it as from an event
                *state = State::Departing;
                None
            }
        }
    }
}
