//! The first zero of an exponential-trigonometric function after a given
//! time, certified: none is missed.
//!
//! # The function class
//!
//! ```text
//! f(s) = p0 + p1 s + p2 s² + Σ_{k=1..n} (a_k cos kθ + b_k sin kθ) + y(s),   θ = w (phi + s),
//! ```
//!
//! for local times `s >= 0`, where `y = y_1 + y_2` is a sum of at most two
//! damped oscillators, each solving `y_i'' + 2σ_i y_i' + ω_i² y_i = 0`
//! (`σ_i >= 0`, `ω_i > 0`; under-, critically or over-damped, each with its
//! own constants) with `y_i(0)`, `y_i'(0)` given ([`DampedOscillator`],
//! closed forms in `oscillator.rs`). Between events, a rod driven through a
//! damped linear actuator has its relative velocity and acceleration of
//! this form, and a slider on a spring adds the second oscillator.
//! [`ExpTrig::eval`] gives `f`, `f'`, `f''` in `O(n)`: one `sin_cos` and
//! the angle-addition recurrence for the harmonics, the closed forms for
//! the oscillators.
//!
//! # Bounds
//!
//! **(B) Derivatives on a piece** `[x, x + 2h]`, `x >= 0`:
//! * harmonics: each is `hypot(a_k, b_k) cos(kθ - δ_k)`, so
//!   `|T^(j)| <= M_j = Σ_k hypot(a_k, b_k) (k w)^j`;
//! * quadratic: `P'' = 2 p2`, `P''' = 0`;
//! * oscillators: for every solution `u` of an oscillator's equation,
//!   `E_u = ω0² u² + u'²` has `E_u' = -4σ u'² <= 0`, and each `y^(j)` is a
//!   solution; so for `s >= x`,
//!   `|y^(j)(s)| <= Y_j(x) = min(sqrt(E_{j-1}(x)), sqrt(E_j(x)) / ω0)`, with
//!   `E_j = ω0² (y^(j))² + (y^(j+1))²` from `y, y'` at `x` and
//!   `y^(j+1) = -2σ y^(j) - ω0² y^(j-1)` (each `|y^(i)(x)|` enlarged by its
//!   rounding bound). One bound for every regime; an undamped oscillator
//!   attains it. With two oscillators `Y_j` is the sum of their bounds
//!   (`|y_1^(j) + y_2^(j)| <= |y_1^(j)| + |y_2^(j)|`).
//!
//! So `B_j = M_j + Y_j(x)` (plus `2 |p2|` for `j = 2`) bounds `|f^(j)|` on
//! the piece, `j = 2, 3, 4`.
//!
//! **(R) Rounding.** `η_j` ([`ExpTrig::eval_error_bound`], and `j = 3`)
//! bounds the error of a computed `f^(j)(s)` for `s` in `[0, s_max]`. It
//! adds, term by term:
//! * the recurrence: `e^{ikθ}` to `5 k ε` (one `sin_cos`, `k` complex
//!   products), then the products and the sum over `n` harmonics:
//!   `ε Σ_k (5k + n + 8) (|a_k| + |b_k|) (k w)^j`;
//! * the phase: `θ = w (phi + s)` carries a relative error `2ε`, which moves
//!   `f^(j)` by at most `2ε (|phi| + s_max) M_{j+1}` (taken as `2.5ε`);
//! * the quadratic's Horner steps: `4ε (|p0| + |p1| s + |p2| s²)`,
//!   `3ε (|p1| + 2|p2| s)`;
//! * the oscillator: `(8 + ν s_max) ε (U_j + G V_j)`, doubled
//!   ([`DampedOscillator::rounding`]: `U_j`, `V_j` the sizes of its
//!   coefficients, `G` the bound of its second basis function, `ν s_max`
//!   the phase of an under-damped one); `j = 3` through the recurrence;
//!   each oscillator's, summed;
//! * the sum of the three parts: `4ε` times their sizes;
//!
//! all doubled. Against a term-by-term evaluation (each harmonic from its
//! own `sin_cos(kθ)`) the measured difference stays below 8 % of `η_j`
//! (`examples/exp_trig_roots.rs`, 2000 random functions of up to 40
//! harmonics). That `η` bounds the rounding is the one assumption below;
//! each step of its derivation is a standard floating-point bound.
//!
//! # Method
//!
//! 0. *Scaling.* The coefficients are scaled by a power of two (exact) to
//!    a largest one in `[1, 2)`; the band is `τ = max(tol, 4 η0)`.
//! 1. *Pieces, left to right from `s_a`.* The first has the width `1/Ω`,
//!    `Ω` the largest of the top harmonic's `k w` and the oscillators'
//!    fastest rates (`ω0`, or `σ + β` over-damped); each next one is 1.25
//!    times the last (1.5 after an excluded one); a piece no test decides
//!    is halved and its left half tried next, down to a half-width
//!    `h_min = max(1e-10 / Ω, 16 ε (|phi| + s_b))`, below which it is a
//!    *cluster*. The walk stops at the first event, so its cost is that of
//!    the stretch walked.
//! 2. *Classes.* One evaluation of `f, ..., f'''` at the midpoint `m`
//!    (half-width `h`), with `A_j = |f̂^(j)(m)| + η_j` and
//!    `a_j = |f̂^(j)(m)| - η_j`; by Taylor's theorem at `m` and (B),
//!    `sup |f'''| <= U3 = min(B3, A3 + B4 h)` and
//!    `sup |f''| <= U2 = min(B2, A2 + A3 h + B4 h²/2, A2 + U3 h)` on the
//!    piece, and
//!    * (E) *excluded*: `|f| > τ` on the piece if `L0 > τ`, where `L0` is the
//!      largest of `a0 - A1 h - min(U2 h²/2, A2 h²/2 + U3 h³/6)` (Taylor),
//!      `a0 - 2 (M0 + Y0) - |P'(m)| h - |p2| h²` (the quadratic dominates:
//!      `|f| >= |P| - |T| - |y|`), and, when `f(m)` and `f''` have one sign,
//!      `a0 - A1² / (2 L2)` (the least value of a convex function);
//!    * (M) *monotone*: `f' != 0` if `L1 = a1 - min(U2 h, A2 h + U3 h²/2) > 0`;
//!    * (C) *convex*: `f''` keeps the sign of `f̂''(m)` if `L2 = a2 - U3 h > 0`;
//!
//!    each less `8ε` times its terms (its own rounding). The bounds hold for
//!    the true `f`: every computed value enters with its rounding bound.
//! 3. *Resolution*, with the walk's *state*: what it knows of `f` left of
//!    the piece.
//!    * `Clear`: looking for an event.
//!    * `Pending(z)`: `f` crossed zero at `z` and has stayed within the band
//!      `|f| <= τ` since, without a critical point. It becomes the
//!      transversal event `z` when `f` leaves the band (or at `s_b`), a
//!      tangency if `f` turns inside the band first.
//!    * `Departing`: `f` has stayed within the band since `s_a`, where the
//!      caller handled an event ([`Start::AfterEvent`]).
//!
//!    A *monotone stretch* `[u, v]` (a monotone piece, or one side of the
//!    critical point of a convex one) with computed end values: in `Clear`
//!    it holds a zero iff the ends have opposite certain signs (`|f̂| > η0`)
//!    or `f̂(v)` is at the rounding level (the zero is at `v`, and is this
//!    stretch's; a left end at that level is a zero found by the stretch
//!    before, or `s_a` itself). The zero comes from a bracketed Newton
//!    solve ([`bracket::solve`], to `|f̂| <= η0`): an event if
//!    `|f̂(v)| > τ`, else `Pending`. In `Pending` or `Departing`,
//!    `|f̂(v)| > τ` means `f` left the band (and moves away from it to `v`):
//!    the pending zero is the event; a departure ends. Where the model's
//!    enclosures of `f(u)`, `f(v)` decide (ends of one strict sign in
//!    `Clear`; an end certainly beyond or within the band otherwise), the
//!    ends are not evaluated.
//!
//!    A *convex piece* (`f''` of sign `σ`): `f'` is monotone; if it has one
//!    certain sign at the end where it is nearest zero, the piece is
//!    monotone. In `Clear`, `σ f` is at most its larger end value, so ends
//!    certainly beyond the band on the side `-σ` exclude the piece. Else
//!    the zero `c` of `f'` (bracketed Newton on `f'`; an end where
//!    `|f̂'| <= η1` is `c`), and the stretches `[x, c]`, `[c, r]` around
//!    the *critical point* `c`: with `|f̂(c)| <= τ`, `Clear` gives the
//!    tangency `c` (at `s_a` itself, a departure starts), `Pending` the
//!    tangency `c` (its crossing was inside `c`'s band), `Departing` goes
//!    on; with `|f̂(c)| > τ`, `f` has left the band before `c`.
//!
//!    An *excluded piece* has `f` beyond the band: a pending zero is the
//!    event, a departure ends. A *cluster* is sampled at nine points: in
//!    `Clear`, the first certain sign change gives a bracketed solve and a
//!    transversal event; without one, the sample of least `|f̂|` is a
//!    tangency if `|f|` could be within the band anywhere on the cluster
//!    (`|f̂| - η0 - sup|f'| (r - x)/16 <= τ`, `sup|f'|` from the model; at
//!    `s_a` itself, a departure starts), else there is no event. A pending
//!    zero followed by a cluster is reported; a departure ends at a cluster
//!    whose end is beyond the band.
//!
//! # Contract
//!
//! [`ExpTrig::first_zero`]`(s_a, s_b, tol, start)` returns the first event
//! of `f` in `(s_a, s_b]`, or `None`; `τ = max(tol, 4 η0)`:
//! * [`Crossing::Transversal`] `{ s, rising }`: `f` changes sign at `s`,
//!   `|f̂(s)| <= η0` (or within the time resolution), so `s` is within
//!   `~η0 / |f'(s)|` of the zero; `rising` is the sign of `f'`.
//! * [`Crossing::Tangency`] `{ s }`: a critical point of `f` (a zero of
//!   `f'` to its rounding level) with `|f(s)| <= τ`: `f` touches zero. The
//!   band stretch around it, where `|f| <= τ`, belongs to it: a dip through
//!   zero by less than `τ` is one tangency, by more two transversal zeros
//!   (the grazing rule of docs/model.md section 8, "Why no event is
//!   missed"). A zero of `f` that is followed, within the band and before
//!   `f` leaves it, by a critical point is that tangency.
//! * The interval is open at `s_a` and closed at `s_b`: a zero at `s_b`
//!   is reported, a zero at `s_a` (`|f̂(s_a)| <= η0`) is not, so
//!   consecutive intervals report each zero once. A zero whose band
//!   stretch reaches past `s_b` without a critical point is reported.
//! * [`Start::AfterEvent`] with `|f̂(s_a)| <= τ`: the caller has just
//!   handled an event at `s_a` (possibly with other coefficients: a new
//!   segment). The *departure*, the stretch from `s_a` on which `|f| <= τ`,
//!   belongs to that event: its zeros and critical points are not events,
//!   and the search starts where `|f|` first exceeds `τ`; `None` if it
//!   never does in `(s_a, s_b]`. A restart at a computed zero (whose
//!   computed `f` may have either sign) or at a tangency therefore does
//!   not find it again, and needs no nudge in time. With `|f̂(s_a)| > τ`,
//!   or [`Start::Clear`], there is no departure.
//! * Tolerances below `4 η0` are raised to it. The result does not depend
//!   on the scale of `f` (the power-of-two scaling is exact).
//! * Input outside the class gives `None`, never a panic or a NaN
//!   ([`ExpTrig::first_zero_counting`] lists it).
//!
//! # No event is missed
//!
//! The pieces cover `(s_a, s_b]`: each is classified or halved, its left
//! half tried next and the rest covered after. Each class is proved by
//! (B) and (R): an excluded piece has no point with `|f| <= τ`, so neither
//! zero nor tangency; a monotone one at most one zero and no critical
//! point; a convex one at most one critical point, with `f` monotone on
//! either side. On a monotone stretch the certain signs at its ends are
//! the true ones, so a sign change is seen, and the bracketed solve keeps
//! a sign-changing bracket, so it returns that zero. A zero within the
//! rounding of a stretch end is attributed once, to the stretch that ends
//! there. The critical point of a convex piece is the zero of the monotone
//! `f'` in a sign-changing bracket, or an end within `η1 / min |f''|` of
//! it. The states follow `f` along each stretch, where it is monotone: a
//! band left within a stretch is not re-entered in it. So every zero and
//! every critical point in the band is seen, in order of time, and the
//! first the contract calls an event is returned.
//!
//! Where the answer rests on rounding rather than on the bounds: values
//! within `η` of zero or of `±τ` are decided by the computed value (a
//! near-tangency at the band's edge, two zeros closer than
//! `~sqrt(η0 / |f''|)`); and a cluster, which arises only where `f`, `f'`
//! and `f''` are all within the bounds' slack over a width `2 h_min` (a
//! root of multiplicity three or more, or `f` flat in the band): the
//! samples report a sign change or a touch there, and a cluster without
//! either is proved free of the band by the slope bound.
//!
//! # Cost
//!
//! `O(n)` per evaluation. On random functions of up to 15 harmonics with
//! an oscillator (`examples/exp_trig_roots.rs`), a search from one event
//! to the next takes about 17 evaluations, 7 pieces and 2 halvings, about
//! 3 µs; [`Work`] counts them for the caller. Where there is no event the
//! walk covers `(s_a, s_b]` in pieces of about `1/Ω` (longer where `|f|`
//! stays well above the band), so its cost grows with `Ω (s_b - s_a)`:
//! the caller keeps the interval short (a segment, at most a period).

use super::bracket;
use super::power_of_two::ldexp;

mod oscillator;
mod walk;

pub(crate) use oscillator::DampedOscillator;
use oscillator::Regime;

/// Machine epsilon.
const EPS: f64 = f64::EPSILON;

/// `f(s) = p0 + p1 s + p2 s² + Σ_k (a_k cos kθ + b_k sin kθ) + y(s)`,
/// `θ = w (phi + s)`, `y` the sum of at most two [`DampedOscillator`]s
/// (module documentation).
/// `a[k-1]`, `b[k-1]` belong to harmonic `k`; a shorter slice counts as
/// padded with zeros.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ExpTrig {
    /// `[p0, p1, p2]`.
    pub poly: [f64; 3],
    /// Fundamental angular frequency `w > 0` (rad/s).
    pub w: f64,
    /// Time (s) of `s = 0` within the period `2π / w`.
    pub phi: f64,
    /// Cosine coefficients.
    pub a: Vec<f64>,
    /// Sine coefficients.
    pub b: Vec<f64>,
    /// The damped oscillators' parts, each if any (their sum is `y`).
    pub osc: [Option<DampedOscillator>; 2],
}

/// An event of [`ExpTrig::first_zero`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Crossing {
    /// `f` changes sign at `s`: from negative to positive if `rising`.
    Transversal {
        /// The zero.
        s: f64,
        /// Whether `f` goes from negative to positive.
        rising: bool,
    },
    /// `f` has a critical point at `s` with `|f(s)| <= τ` (the band:
    /// `tol`, at least the rounding level): it touches zero, and any
    /// crossings within the band around `s` belong to this touch.
    Tangency {
        /// The critical point.
        s: f64,
    },
}

impl Crossing {
    /// The time of the event.
    pub(crate) fn s(&self) -> f64 {
        match *self {
            Crossing::Transversal { s, .. } | Crossing::Tangency { s } => s,
        }
    }
}

/// What the caller knows at the start `s_a` of a search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Start {
    /// Nothing: `s_a` is any time.
    Clear,
    /// The caller has just handled an event at `s_a` (a zero or touch of
    /// `f`, possibly of other coefficients): while `|f| <= tol` from `s_a`
    /// on, `f` is still at that event (module documentation, "Contract").
    AfterEvent,
}

/// Work done by searches, summed over calls.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Work {
    /// Evaluations of `f` with its derivatives (the `O(n)` passes).
    pub evaluations: u64,
    /// Pieces classified (excluded, monotone, convex or a cluster).
    pub pieces: u64,
    /// Pieces halved because no test decided them.
    pub subdivisions: u64,
    /// Pieces at the smallest width that no test decided.
    pub clusters: u64,
    /// The caller's budget of evaluations over all searches counting here
    /// (0: none). A search that finds it spent stops without an answer
    /// and sets [`Work::exhausted`].
    pub budget: u64,
    /// A search stopped on the budget: its `None` is no answer.
    pub exhausted: bool,
}

impl ExpTrig {
    /// `p0 + p1 s + p2 s² + y(s)`: no harmonics (`w` sets the walk's
    /// scale where there is no oscillator).
    pub(crate) fn local(poly: [f64; 3], w: f64, osc: Option<DampedOscillator>) -> ExpTrig {
        ExpTrig {
            poly,
            w,
            phi: 0.0,
            a: Vec::new(),
            b: Vec::new(),
            osc: [osc, None],
        }
    }

    /// The oscillators present.
    fn oscillators(&self) -> impl Iterator<Item = &DampedOscillator> {
        self.osc.iter().flatten()
    }

    /// `f'` in the same class: the polynomial's, each harmonic's
    /// (`a_k cos + b_k sin` gives `k w (b_k cos - a_k sin)`) and the
    /// oscillator's derivative.
    pub(crate) fn derivative(&self) -> ExpTrig {
        let [_, p1, p2] = self.poly;
        let (a, b) = self
            .pairs()
            .enumerate()
            .map(|(i, (a, b))| {
                let kw = (i + 1) as f64 * self.w;
                (kw * b, -kw * a)
            })
            .unzip();
        ExpTrig {
            poly: [p1, 2.0 * p2, 0.0],
            w: self.w,
            phi: self.phi,
            a,
            b,
            osc: self.osc.map(|o| o.map(|o| o.derivative())),
        }
    }

    /// Number of harmonics (the longer of `a`, `b`).
    fn harmonics(&self) -> usize {
        self.a.len().max(self.b.len())
    }

    /// `(a_k, b_k)` for `k = 1..=n`, the shorter slice padded with zeros.
    fn pairs(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        (0..self.harmonics()).map(|i| {
            (
                self.a.get(i).copied().unwrap_or(0.0),
                self.b.get(i).copied().unwrap_or(0.0),
            )
        })
    }

    /// `f(s)`, `f'(s)`, `f''(s)`: one `sin_cos` and the angle-addition
    /// recurrence for the harmonics, the closed form for the oscillator.
    pub(crate) fn eval(&self, s: f64) -> [f64; 3] {
        let [f, df, d2f, _] = self.eval4(s);
        [f, df, d2f]
    }

    /// `f` and its first three derivatives at `s`.
    pub(crate) fn eval4(&self, s: f64) -> [f64; 4] {
        let osc = self
            .osc
            .each_ref()
            .map(|o| o.as_ref().map(|o| (o, o.regime())));
        self.eval4_with(self.poly, osc, |x| x, s).0
    }

    /// [`ExpTrig::eval4`] of the function whose quadratic is `poly`, whose
    /// oscillators are `osc` and whose harmonic coefficients are `scale`d
    /// (the finder's exactly scaled copy, without copying the harmonics);
    /// also each oscillator's `y, y', y''` at `s` (zero without one).
    fn eval4_with(
        &self,
        [p0, p1, p2]: [f64; 3],
        osc: [Option<(&DampedOscillator, Regime)>; 2],
        scale: impl Fn(f64) -> f64 + Copy,
        s: f64,
    ) -> ([f64; 4], [[f64; 3]; 2]) {
        let mut out = [p0 + s * (p1 + s * p2), p1 + 2.0 * p2 * s, 2.0 * p2, 0.0];
        let theta = self.w * (self.phi + s);
        let trig = if self.a.len() == self.b.len() {
            let pairs = self.a.iter().zip(&self.b).map(|(&a, &b)| (a, b));
            harmonic_sums(pairs.map(|(a, b)| (scale(a), scale(b))), self.w, theta)
        } else {
            harmonic_sums(
                self.pairs().map(|(a, b)| (scale(a), scale(b))),
                self.w,
                theta,
            )
        };
        let mut y3 = [[0.0; 3]; 2];
        for (i, o) in osc.into_iter().enumerate() {
            let Some((o, regime)) = o else { continue };
            let [y, dy, d2y] = o.eval_in(regime, s);
            y3[i] = [y, dy, d2y];
            let d3y = -2.0 * o.sigma * d2y - o.omega0 * o.omega0 * dy;
            for (j, v) in [y, dy, d2y, d3y].into_iter().enumerate() {
                out[j] += v;
            }
        }
        for (o, t) in out.iter_mut().zip(trig) {
            *o += t;
        }
        (out, y3)
    }

    /// Bounds on the rounding errors of the computed `f(s)`, `f'(s)`,
    /// `f''(s)` ([`ExpTrig::eval`]) for every `s` in `[0, s_max]`: the
    /// rounding level `η` (module documentation, "Bounds", (R)).
    pub(crate) fn eval_error_bound(&self, s_max: f64) -> [f64; 3] {
        let [e0, e1, e2, _] = self.rounding(s_max);
        [e0, e1, e2]
    }

    /// The larger of the rounding levels `η0` on `[0, s_max]`
    /// ([`ExpTrig::eval_error_bound`]) of `self` and `other`. Where they
    /// differ only in the quadratic (two levels of one function), the parts
    /// they share are computed once.
    pub(crate) fn larger_rounding_level(&self, other: &ExpTrig, s_max: f64) -> f64 {
        let shared = self.w == other.w
            && self.phi == other.phi
            && self.a == other.a
            && self.b == other.b
            && self.osc == other.osc;
        if !shared {
            return self.eval_error_bound(s_max)[0].max(other.eval_error_bound(s_max)[0]);
        }
        let m = self.harmonic_bounds();
        let osc = summed(oscillator_parts(&self.osc, s_max));
        let mine = self.rounding_with(s_max, self.poly, &m, osc, |x| x)[0];
        let theirs = self.rounding_with(s_max, other.poly, &m, osc, |x| x)[0];
        mine.max(theirs)
    }

    /// `Σ_k hypot(a_k, b_k) (k w)^j`, `j < 6`: bounds on `|T^(j)|`.
    pub(crate) fn harmonic_bounds(&self) -> [f64; 6] {
        self.harmonic_bounds_with(|x| x)
    }

    /// [`ExpTrig::harmonic_bounds`] with the harmonic coefficients `scale`d.
    fn harmonic_bounds_with(&self, scale: impl Fn(f64) -> f64) -> [f64; 6] {
        let mut m = [0.0; 6];
        for (k, (a, b)) in self.pairs().map(|(a, b)| (scale(a), scale(b))).enumerate() {
            let (q, size) = (
                (k + 1) as f64 * self.w,
                oscillator::norm(a.abs(), b.abs()) * (1.0 + 2.0 * EPS),
            );
            let mut t = size;
            for mj in &mut m {
                *mj += t;
                t *= q;
            }
        }
        m
    }

    /// Rounding bounds of `f^(j)`, `j <= 3`, on `[0, s_max]` (module
    /// documentation, "Bounds", (R)).
    fn rounding(&self, s_max: f64) -> [f64; 4] {
        let m = self.harmonic_bounds();
        let osc = summed(oscillator_parts(&self.osc, s_max));
        self.rounding_with(s_max, self.poly, &m, osc, |x| x)
    }

    /// [`ExpTrig::rounding`] of the function whose quadratic is `poly`,
    /// whose harmonic coefficients are `scale`d (with their bounds `m`) and
    /// whose oscillators have together the rounding and derivative bounds
    /// `osc` on `[0, s_max]` ([`DampedOscillator::rounding_and_bounds`],
    /// [`summed`]).
    fn rounding_with(
        &self,
        s_max: f64,
        poly: [f64; 3],
        m: &[f64; 6],
        (osc_err, osc_size): ([f64; 7], [f64; 7]),
        scale: impl Fn(f64) -> f64,
    ) -> [f64; 4] {
        let s = s_max.abs();
        let n = self.harmonics() as f64;
        let [p0, p1, p2] = poly.map(f64::abs);
        let mut recurrence = [0.0; 4];
        for (k, (a, b)) in self.pairs().map(|(a, b)| (scale(a), scale(b))).enumerate() {
            let (k, size) = ((k + 1) as f64, a.abs() + b.abs());
            let q = k * self.w;
            let weight = (5.0 * k + n + 8.0) * size;
            let mut t = weight;
            for r in &mut recurrence {
                *r += t;
                t *= q;
            }
        }
        let phase = 2.5 * (self.phi.abs() + s);
        let poly_size = [p0 + s * (p1 + s * p2), p1 + 2.0 * p2 * s, 2.0 * p2, 0.0];
        let poly_err = [4.0 * poly_size[0], 3.0 * poly_size[1], 0.0, 0.0];
        let mut eta = [0.0; 4];
        for j in 0..4 {
            let sizes = poly_size[j] + m[j] + osc_size[j];
            eta[j] = 2.0
                * (EPS * (recurrence[j] + phase * m[j + 1] + poly_err[j] + 4.0 * sizes)
                    + osc_err[j]);
        }
        eta
    }

    /// The first event of `f` in `(s_a, s_b]` ([`ExpTrig::first_zero_counting`]
    /// without the counters).
    pub(crate) fn first_zero(
        &self,
        s_a: f64,
        s_b: f64,
        tol: f64,
        start: Start,
    ) -> Option<Crossing> {
        self.first_zero_counting(s_a, s_b, tol, start, &mut Work::default())
    }

    /// The first event of `f` in `(s_a, s_b]`: the earliest transversal
    /// zero or tangency (a critical point with `|f| <= tol`), certified:
    /// none is missed (module documentation, "Contract" and "No event is
    /// missed"). `tol` below the rounding level `4 η` is raised to it.
    /// `start` says whether the caller has just handled an event at `s_a`.
    /// Adds the work done to `work`.
    ///
    /// `None` when there is no event, and for input outside the function
    /// class: non-finite values, `w <= 0` with harmonics present, an
    /// invalid oscillator, `s_a < 0`, `s_b <= s_a`, a NaN `tol`, or an `f`
    /// that is constant.
    pub(crate) fn first_zero_counting(
        &self,
        s_a: f64,
        s_b: f64,
        tol: f64,
        start: Start,
        work: &mut Work,
    ) -> Option<Crossing> {
        let prepared = self.prepare(s_a, s_b, tol)?;
        walk::Walk::new(&prepared, s_a, s_b, work).run(start)
    }

    /// Finite coefficients in the function class.
    fn is_valid(&self) -> bool {
        let finite = self
            .poly
            .iter()
            .chain(&self.a)
            .chain(&self.b)
            .chain([&self.phi])
            .all(|x| x.is_finite());
        let harmonics = self.pairs().any(|(a, b)| a != 0.0 || b != 0.0);
        finite
            && (!harmonics || (self.w.is_finite() && self.w > 0.0))
            && self.oscillators().all(DampedOscillator::is_valid)
    }

    /// The search's data: `f` scaled by a power of two (exact) to a largest
    /// coefficient in `[1, 2)`, its bounds, and the band. `None` for input
    /// outside the class or a constant `f`. The scaled harmonics are not
    /// copied: [`walk::Prepared::eval4`] scales them as it goes, with the
    /// same products as a scaled copy.
    fn prepare(&self, s_a: f64, s_b: f64, tol: f64) -> Option<walk::Prepared<'_>> {
        let times_ok = s_a.is_finite() && s_b.is_finite() && s_a >= 0.0 && s_b > s_a;
        if !times_ok || tol.is_nan() || !self.is_valid() {
            return None;
        }
        let osc = self.osc.map(|o| o.filter(|o| o.y0 != 0.0 || o.y1 != 0.0));
        let largest = self
            .poly
            .iter()
            .chain(&self.a)
            .chain(&self.b)
            .chain(osc.iter().flatten().flat_map(|o| [&o.y0, &o.y1]))
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        if largest == 0.0 {
            return None;
        }
        let scale = Scale::new(-(largest.log2().floor() as i32));
        let by = |x: f64| scale.apply(x);
        let poly = self.poly.map(by);
        let osc = osc.map(|o| {
            o.map(|o| DampedOscillator {
                y0: by(o.y0),
                y1: by(o.y1),
                ..o
            })
        });
        let constant = poly[1] == 0.0
            && poly[2] == 0.0
            && osc.iter().all(Option::is_none)
            && self.pairs().all(|(a, b)| by(a) == 0.0 && by(b) == 0.0);
        if constant {
            return None;
        }
        let bounds = self.harmonic_bounds_with(by);
        let osc_parts = oscillator_parts(&osc, s_b);
        let eta = self.rounding_with(s_b, poly, &bounds, summed(osc_parts), by);
        let osc_err = osc_parts.map(|p| p.map_or([0.0; 7], |(err, _)| err));
        let tau = by(tol.max(0.0)).max(4.0 * eta[0]);
        let finite = eta
            .iter()
            .chain(&bounds)
            .chain(osc_err.iter().flatten())
            .all(|x| x.is_finite());
        finite.then_some(walk::Prepared {
            f: self,
            scale,
            poly,
            osc,
            regime: osc.map(|o| o.map(|o| o.regime())),
            bounds,
            eta,
            osc_err,
            tau,
        })
    }
}

/// Each oscillator's rounding and derivative bounds on `[0, s_max]`
/// ([`DampedOscillator::rounding_and_bounds`]).
fn oscillator_parts(
    osc: &[Option<DampedOscillator>; 2],
    s_max: f64,
) -> [Option<([f64; 7], [f64; 7])>; 2] {
    osc.map(|o| o.map(|o| o.rounding_and_bounds(s_max.abs())))
}

/// The oscillators' rounding and derivative bounds added term by term
/// (zero without any): the bounds of their sum.
fn summed(parts: [Option<([f64; 7], [f64; 7])>; 2]) -> ([f64; 7], [f64; 7]) {
    let (mut err, mut size) = ([0.0; 7], [0.0; 7]);
    for (e, b) in parts.into_iter().flatten() {
        for j in 0..7 {
            err[j] += e[j];
            size[j] += b[j];
        }
    }
    (err, size)
}

/// Multiplication by `2^e`: [`ldexp`], with the factor computed once.
#[derive(Debug, Clone, Copy)]
struct Scale {
    e: i32,
    /// `2^e`, where [`ldexp`] multiplies by it in one step.
    factor: f64,
}

impl Scale {
    fn new(e: i32) -> Self {
        Scale {
            e,
            factor: 2f64.powi(e),
        }
    }

    /// `x · 2^e`, the same operation as `ldexp(x, e)`.
    fn apply(self, x: f64) -> f64 {
        if self.e.abs() <= 1000 {
            x * self.factor
        } else {
            ldexp(x, self.e)
        }
    }
}

/// `Σ_k (a_k cos kθ + b_k sin kθ)` and its first three derivatives in `s`
/// (`dθ/ds = w`), one `sin_cos` and the angle-addition recurrence.
fn harmonic_sums(pairs: impl Iterator<Item = (f64, f64)>, w: f64, theta: f64) -> [f64; 4] {
    let (s1, c1) = theta.sin_cos();
    let (mut ck, mut sk) = (1.0, 0.0);
    let mut t = [0.0; 4];
    for (k, (ak, bk)) in pairs.enumerate() {
        let c = ck * c1 - sk * s1;
        sk = sk * c1 + ck * s1;
        ck = c;
        let q = (k + 1) as f64 * w;
        let even = ak * ck + bk * sk;
        let odd = bk * ck - ak * sk;
        t[0] += even;
        t[1] += q * odd;
        t[2] -= q * q * even;
        t[3] -= q * q * q * odd;
    }
    t
}

#[cfg(test)]
mod cases;
#[cfg(test)]
mod tests;
