//! Certified isolation of the real roots of a trigonometric polynomial:
//! subdivision with Taylor models of bounded error, then one bracketed solve
//! per isolated root. The method, the error bounds and the proof that no root
//! is missed are in the documentation of the parent module; the names here
//! (`g`, `e`, `δ_0`, `u_0`, ...) follow it.

use std::f64::consts::{PI, TAU};
use std::sync::OnceLock;

use super::{EPS, NEWTON_ITERS, TrigPoly, WithDerivative, WithTwoDerivatives};
use crate::numerics::taylor;

/// Terms of a Taylor model: orders `j < ORDER`.
const ORDER: usize = 24;
/// Bound on `n r`, degree times the half-width of a top-level interval: the
/// remainder `(n r)^ORDER / ORDER!` is then below `3e-17`.
const NR: f64 = 2.0;
/// Safety factor applied to every rounding bound.
const SAFETY: f64 = 2.0;
/// Relative overlap of neighbouring top-level intervals (covers the rounding
/// of their centres).
const OVERLAP: f64 = 1.0e-9;
/// Half-width (radians) below which a piece without a certificate is not
/// bisected further but handed to the cluster rule.
const FLOOR: f64 = 6.0e-8;
/// Iterations of the bracketed solver (bisection alone needs at most 64).
const MAX_ITERS: usize = 100;
/// Interior samples of an unresolved cluster.
const CLUSTER_SAMPLES: usize = 8;
/// `γ` of the rounding of the Taylor shift (module docs of the parent, (R4)).
const GAMMA: f64 = SAFETY * (2 * ORDER + 4) as f64 * EPS;
/// Rounding of a Horner pass over a shifted model, relative to its mass.
const HORNER: f64 = SAFETY * 2.0 * ORDER as f64 * EPS;

/// Coefficients of a Taylor model in its scaled variable.
pub(super) type Coeffs = [f64; ORDER];

/// Candidate roots (not wrapped, possibly repeated) of the normalised `p`,
/// whose terms above degree `n` are negligible; `eta` its rounding level.
/// Also returns, for each top-level interval `i` (centre `(i + 1/2) 2π/N`),
/// a bound on `max |p|` over it: `Σ_j |g_j| + δ_0` of its model (module
/// docs of the parent, step 1: the model plus its error bound covers `p`).
pub(super) fn candidates(p: &TrigPoly, n: usize, eta: f64) -> (Vec<Candidate>, Vec<f64>, Models) {
    Finder::new(p, n, eta).run(None)
}

/// [`candidates`] with the level-independent part of the work given
/// (`shared` from [`Shared::new`] for a polynomial with the same
/// normalised harmonics and degree `n`; only `c0` may differ): the same
/// values, to the bit, without its cost.
pub(super) fn candidates_with(
    p: &TrigPoly,
    n: usize,
    eta: f64,
    shared: &Shared,
) -> (Vec<Candidate>, Vec<f64>, Models) {
    Finder::new(p, n, eta).run(Some(shared))
}

/// What [`candidates_with`] shares between polynomials that differ only in
/// `c0`: the top-level models' sums over the harmonics (without `c0`), and
/// the subdivision of every top-level interval. Of the tests (E), (M), (C)
/// only (E) depends on `c0` (module docs of the parent, step 2): a piece's
/// shifted model differs between levels only in its constant term `e_0`,
/// which is `g_0 + X` with `X` the same for every level (the Taylor shift
/// adds `g_0` in its very last operation), and (M), (C) read only `e_1`,
/// `e_2`, ... So each piece keeps its shifted model, `X`, and its (M)/(C)
/// class; its halves are made the first time a level needs them and kept
/// for the next. A level then tests only (E) and resolves its own pieces.
#[derive(Debug)]
pub(super) struct Shared {
    sums: Vec<Coeffs>,
    trees: Vec<Node>,
}

impl Shared {
    /// The shared part for the normalised `p` of degree `n` (its `c0` is
    /// not used).
    pub(super) fn new(p: &TrigPoly, n: usize) -> Self {
        let finder = Finder::new(p, n, 0.0);
        let h = TAU / finder.count as f64;
        let sums: Vec<Coeffs> = (0..finder.count)
            .map(|i| finder.harmonic_sums((i as f64 + 0.5) * h))
            .collect();
        let trees = sums.iter().map(|g| finder.node(g, 0.0, 1.0)).collect();
        Self { sums, trees }
    }
}

/// A candidate root `theta` (not wrapped) and, where the solve that found
/// it evaluated `p` there, the computed `p'(theta)`
/// ([`TrigPoly::eval_with_derivative`], the same bits).
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    pub(super) theta: f64,
    pub(super) slope: Option<f64>,
}

/// The top-level Taylor models of a run, kept for the merge: each model
/// `q_i` with a bound `unc_i` on `|p(θ) - q_i(s(θ))|` that includes the
/// rounding of `s` and of the Horner pass (module docs of the parent,
/// step 4).
#[derive(Debug, Clone)]
pub(super) struct Models {
    r: f64,
    h: f64,
    g: Vec<Coeffs>,
    unc: Vec<f64>,
}

impl Models {
    /// Whether `|p(θ)| > margin` is certain from the model of the interval
    /// holding `θ` (any real `θ`, reduced to `[0, 2π)` first).
    pub(super) fn exceeds(&self, theta: f64, margin: f64) -> bool {
        let t = theta.rem_euclid(TAU);
        let i = ((t / self.h) as usize).min(self.g.len() - 1);
        let m = (i as f64 + 0.5) * self.h;
        let s = (t - m) / self.r;
        s.abs() <= 1.0 && horner(&self.g[i], s).0.abs() - self.unc[i] > margin
    }
}

/// What a Taylor model certifies on a piece besides (E), which depends on
/// the level.
#[derive(Debug, Clone, Copy)]
enum Class {
    /// `|p'| > 0`: at most one root.
    Monotone,
    /// `|p''| ≥ mu_u` (in the scaled variable): at most two roots.
    Convex { mu_u: f64 },
    /// Nothing certified.
    Undecided,
}

/// A piece `s ∈ [c - ρ, c + ρ]` of a top-level interval with its shifted
/// model `e` (all but `e_0`, module docs of the parent, step 2), what the
/// model certifies whatever the level, and its halves once made.
#[derive(Debug)]
struct Node {
    c: f64,
    rho: f64,
    /// `e_1, e_2, ...` of the shifted model; `e[0]` is not used.
    e: Coeffs,
    /// `e_0 = g_0 + x` (`None`: `e_0 = g_0`, the unshifted top level).
    x: Option<f64>,
    /// `Σ_{i≥1} |e_i|`.
    s0: f64,
    /// Bound on the error of `q'` (module docs, `U_1`).
    unc1: f64,
    class: Class,
    halves: OnceLock<Box<[Node; 2]>>,
}

/// A piece `θ = centre + half · u`, `u ∈ [-1, 1]`, with its model
/// `q(u) = Σ e_i u^i`: `|p(θ(u)) - q(u)| ≤ unc0` and
/// `|half · p'(θ(u)) - q'(u)| ≤ unc1` (computed `q`, `q'` included).
struct Piece {
    centre: f64,
    half: f64,
    e: Coeffs,
    unc0: f64,
    unc1: f64,
}

impl Piece {
    fn theta(&self, u: f64) -> f64 {
        self.centre + self.half * u
    }
}

struct Finder<'a> {
    /// The normalised polynomial, all its terms (full evaluations).
    p: &'a TrigPoly,
    /// Degree of the models.
    n: usize,
    /// Half-width of the top-level intervals.
    r: f64,
    /// Number of top-level intervals.
    count: usize,
    /// `(k r)^j / j!` (row `k - 1`).
    powers: Vec<Coeffs>,
    /// `δ_0, δ_1, δ_2`: model error bounds of `p`, `d/ds p`, `d²/ds² p`.
    delta: [f64; 3],
    /// Rounding level of [`TrigPoly::eval`] (`η`).
    eta: f64,
    /// Rounding level of the computed `p'`.
    eta1: f64,
}

impl<'a> Finder<'a> {
    fn new(p: &'a TrigPoly, n: usize, eta: f64) -> Self {
        let count = ((PI * n as f64 / NR).ceil() as usize).max(3);
        let r = 0.5 * TAU / count as f64 * (1.0 + OVERLAP);
        let powers = taylor::powers::<ORDER>(n, r);
        let mut delta = [0.0; 3];
        let mut eta1 = 0.0;
        let mut value_sum = p.c0.abs();
        for (k, t) in (1..=n).zip(&powers) {
            let x = k as f64 * r;
            let mass = p.a[k - 1].abs() + p.b[k - 1].abs();
            // Lagrange remainders of orders ORDER, ORDER-1, ORDER-2 of the
            // k-th term and its s-derivatives: mass · x^ORDER / (ORDER-i)!
            let tail = t[ORDER - 1] * x / ORDER as f64 * mass;
            // rounding of the k-th term of every g_j (module docs, (R1)-(R3))
            let round = EPS * (5.0 * k as f64 + n as f64 + 3.0 * ORDER as f64 + 6.0) * mass;
            let (mut s0, mut s1, mut s2) = (0.0, 0.0, 0.0);
            for (j, &tj) in t.iter().enumerate() {
                let j = j as f64;
                s0 += tj;
                s1 += j * tj;
                s2 += j * (j - 1.0) * tj;
            }
            let kk = ORDER as f64;
            delta[0] += tail + round * s0;
            delta[1] += tail * kk + round * s1;
            delta[2] += tail * kk * (kk - 1.0) + round * s2;
            value_sum += mass * s0;
            eta1 += (k as f64).powf(1.5) * mass;
        }
        // the terms above degree n, left out of the models
        for k in n + 1..=p.a.len() {
            let x = k as f64 * r;
            let mass = p.a[k - 1].abs() + p.b[k - 1].abs();
            delta[0] += mass;
            delta[1] += mass * x;
            delta[2] += mass * x * x;
            eta1 += (k as f64).powf(1.5) * mass;
        }
        // rounding of g_0 + c0
        delta[0] += EPS * value_sum;
        Self {
            p,
            n,
            r,
            count,
            powers,
            delta: delta.map(|d| SAFETY * d),
            eta,
            eta1: 16.0 * EPS * eta1,
        }
    }

    fn run(&self, shared: Option<&Shared>) -> (Vec<Candidate>, Vec<f64>, Models) {
        let mut out = Vec::new();
        let mut unresolved = Vec::new();
        let mut bounds = Vec::with_capacity(self.count);
        let mut kept = Models {
            r: self.r,
            h: TAU / self.count as f64,
            g: Vec::with_capacity(self.count),
            unc: Vec::with_capacity(self.count),
        };
        // the sum's own rounding (ORDER terms) is below `ORDER ε` of it
        let inflate = 1.0 + 2.0 * ORDER as f64 * EPS;
        let h = TAU / self.count as f64;
        for i in 0..self.count {
            let m = (i as f64 + 0.5) * h;
            let mut g = match shared {
                Some(shared) => shared.sums[i],
                None => self.harmonic_sums(m),
            };
            g[0] += self.p.c0;
            let mass: f64 = g.iter().map(|x| x.abs()).sum();
            bounds.push((mass + self.delta[0]) * inflate);
            // model error, the Horner pass (2 ORDER ε of the mass) and the
            // rounding of s = (θ - m)/r (4 ε (2π + 1)/r times Σ j |g_j|)
            let slope: f64 = g.iter().enumerate().map(|(j, x)| j as f64 * x.abs()).sum();
            let rounding =
                2.0 * ORDER as f64 * EPS * mass + 4.0 * EPS * (TAU + 1.0) / self.r * slope;
            kept.g.push(g);
            kept.unc.push(self.delta[0] + SAFETY * rounding);
            let own;
            let top = match shared {
                Some(shared) => &shared.trees[i],
                None => {
                    own = self.node(&g, 0.0, 1.0);
                    &own
                }
            };
            self.walk(top, &g, mass, m, &mut out, &mut unresolved);
        }
        self.resolve_clusters(unresolved, &mut out);
        (out, bounds, kept)
    }

    /// The pieces of the top-level interval centred at `m` with model `g`
    /// (this level's `g_0`) of coefficient mass `mass = Σ_j |g_j|`, from its tree `top`: test (E) with this level's
    /// `e_0`, then the piece's (M)/(C) class, halves made when first needed.
    fn walk(
        &self,
        top: &Node,
        g: &Coeffs,
        mass: f64,
        m: f64,
        out: &mut Vec<Candidate>,
        unresolved: &mut Vec<(f64, f64)>,
    ) {
        // rounding of the shift (module docs, (R4)): Σ_i i^l err_i ≤ γ ρ^l G_l
        let t0 = GAMMA * mass;
        let mut stack = vec![top];
        while let Some(node) = stack.pop() {
            let e0 = match node.x {
                Some(x) => g[0] + x,
                None => g[0],
            };
            let unc0 = self.delta[0] + t0 + HORNER * (e0.abs() + node.s0);
            if e0.abs() - node.s0 > unc0 {
                continue;
            }
            let mut e = node.e;
            e[0] = e0;
            let piece = Piece {
                centre: m + self.r * node.c,
                half: self.r * node.rho,
                e,
                unc0,
                unc1: node.unc1,
            };
            match node.class {
                Class::Monotone => self.resolve_monotone(&piece, out),
                Class::Convex { mu_u } => self.resolve_convex(&piece, mu_u, out),
                Class::Undecided if piece.half <= FLOOR => {
                    unresolved.push((piece.theta(-1.0), piece.theta(1.0)));
                }
                Class::Undecided => {
                    let (c, rho) = (node.c, 0.5 * node.rho);
                    let halves = node.halves.get_or_init(|| {
                        Box::new([self.node(g, c - rho, rho), self.node(g, c + rho, rho)])
                    });
                    stack.push(&halves[0]);
                    stack.push(&halves[1]);
                }
            }
        }
    }

    /// `g_j = r^j p^{(j)}(m) / j!`, `j < ORDER`: the Taylor coefficients of
    /// `s ↦ p(m + r s) - c0`, from one `sin_cos` and the rotation
    /// recurrence (the model is this plus `c0` in `g_0`).
    fn harmonic_sums(&self, m: f64) -> Coeffs {
        taylor::harmonic_sums(&self.p.a[..self.n], &self.p.b[..self.n], &self.powers, m)
    }

    /// The piece `s ∈ [c - ρ, c + ρ]` of a top-level interval with model
    /// `g` (whose `g_0` is not read): its shifted model and what (M) and
    /// (C) certify (module docs, step 2).
    fn node(&self, g: &Coeffs, c: f64, rho: f64) -> Node {
        let (e, x) = shift(g, c, rho);
        let (mut g1, mut g2) = (0.0, 0.0);
        let (mut s0, mut s1, mut s2) = (0.0, 0.0, 0.0);
        for i in 1..ORDER {
            let fi = i as f64;
            let (x, y) = (e[i].abs(), g[i].abs());
            g1 += fi * y;
            g2 += fi * (fi - 1.0) * y;
            s0 += x;
            if i >= 2 {
                s1 += fi * x;
            }
            if i >= 3 {
                s2 += fi * (fi - 1.0) * x;
            }
        }
        let (t1, t2) = (GAMMA * rho * g1, GAMMA * rho * rho * g2);
        let [_, d1, d2] = self.delta;
        let (e1, e2) = (e[1].abs(), 2.0 * e[2].abs());
        let unc1 = rho * d1 + t1 + HORNER * (e1 + s1);
        let unc2 = rho * rho * d2 + t2 + HORNER * (e2 + s2);
        let class = if e1 - s1 > unc1 {
            Class::Monotone
        } else if e2 - s2 > unc2 {
            Class::Convex {
                mu_u: e2 - s2 - unc2,
            }
        } else {
            Class::Undecided
        };
        Node {
            c,
            rho,
            e,
            x,
            s0,
            unc1,
            class,
            halves: OnceLock::new(),
        }
    }

    /// Sign of `p` at `θ`: from the model value `q` if `|q| > unc`, else from
    /// a full evaluation if that is above `η`; `0.0` at rounding level.
    fn sign_at(&self, q: f64, unc: f64, theta: f64) -> f64 {
        if q.abs() > unc {
            return q.signum();
        }
        let v = self.p.eval(theta);
        if v.abs() > self.eta { v.signum() } else { 0.0 }
    }

    /// A root at rounding level near `theta`: Newton on `p`, kept if it
    /// reaches `|p| ≤ η + |p'| ulp`.
    fn try_newton(&self, theta: f64, out: &mut Vec<Candidate>) {
        let t = self.p.newton(theta);
        if let Some(slope) = self.p.slope_if_zero_at(t, self.eta) {
            out.push(Candidate {
                theta: t,
                slope: Some(slope),
            });
        }
    }

    /// The root of `p` in `[lo, hi]` (signs `s_lo`, `-s_lo` at the ends,
    /// monotone between), from a model estimate `guess`.
    fn solve(&self, lo: f64, hi: f64, s_lo: f64, guess: f64) -> Candidate {
        let (theta, _, slope) = bracketed(
            |t| {
                let w = self.p.eval_with_derivative(t);
                (w.value, w.derivative)
            },
            lo,
            hi,
            s_lo,
            guess,
        );
        Candidate {
            theta,
            slope: slope.is_finite().then_some(slope),
        }
    }

    /// A piece where `p` is strictly monotone (test (M)): one root if the
    /// signs at its ends differ, a rounding-level candidate at an end where
    /// `p` is at rounding level, else none.
    fn resolve_monotone(&self, piece: &Piece, out: &mut Vec<Candidate>) {
        let (lo, hi) = (piece.theta(-1.0), piece.theta(1.0));
        let qa = horner(&piece.e, -1.0).0;
        let qb = horner(&piece.e, 1.0).0;
        let sa = self.sign_at(qa, piece.unc0, lo);
        let sb = self.sign_at(qb, piece.unc0, hi);
        if sa * sb < 0.0 {
            let u = bracketed(|u| horner(&piece.e, u), -1.0, 1.0, sa, 0.0).0;
            out.push(self.solve(lo, hi, sa, piece.theta(u)));
            return;
        }
        if sa == 0.0 {
            self.try_newton(lo, out);
        }
        if sb == 0.0 {
            self.try_newton(hi, out);
        }
    }

    /// A piece where `p''` keeps its sign (test (C)): `p` has one extremum
    /// `θ_c` (or none, then it is monotone) and at most one root on each side.
    fn resolve_convex(&self, piece: &Piece, mu_u: f64, out: &mut Vec<Candidate>) {
        let (lo, hi) = (piece.theta(-1.0), piece.theta(1.0));
        let da = horner(&piece.e, -1.0).1;
        let db = horner(&piece.e, 1.0).1;
        let (known_a, known_b) = (da.abs() > piece.unc1, db.abs() > piece.unc1);
        if known_a && known_b && da.signum() == db.signum() {
            // p' keeps its sign: p is monotone on the piece
            self.resolve_monotone(piece, out);
            return;
        }
        // the critical point: model estimate, then Newton on p'
        let uc = if da.signum() != db.signum() {
            bracketed(|u| horner2(&piece.e, u), -1.0, 1.0, da.signum(), 0.0).0
        } else if da.abs() < db.abs() {
            -1.0
        } else {
            1.0
        };
        let tc = self.critical_point(piece.theta(uc), lo, hi);
        let WithDerivative {
            value: pc,
            derivative: dpc,
        } = self.p.eval_with_derivative(tc);
        if pc.abs() <= self.eta {
            // extremum at rounding level: a tangency, reported once
            out.push(Candidate {
                theta: tc,
                slope: None,
            });
            return;
        }
        // second-order bound: min over the piece of σ p ≥ σ p(θ_c) - p'(θ_c)²/(2μ)
        let sigma = piece.e[2].signum();
        let mu = mu_u / (piece.half * piece.half);
        let shortfall = (dpc.abs() + self.eta1).powi(2) / (2.0 * mu);
        if sigma * pc > self.eta + shortfall {
            return;
        }
        // p(θ_c) is clearly nonzero: at most one root on each side of θ_c
        let sc = pc.signum();
        for u_end in [-1.0, 1.0] {
            let end = piece.theta(u_end);
            let q_end = horner(&piece.e, u_end).0;
            let s_end = self.sign_at(q_end, piece.unc0, end);
            if s_end == -sc {
                let (ul, uh) = if u_end < uc { (u_end, uc) } else { (uc, u_end) };
                let s_low = if u_end < uc { s_end } else { sc };
                let u = bracketed(|u| horner(&piece.e, u), ul, uh, s_low, 0.5 * (ul + uh)).0;
                let (tl, th) = if end < tc { (end, tc) } else { (tc, end) };
                out.push(self.solve(tl, th, s_low, piece.theta(u)));
            } else if s_end == 0.0 {
                self.try_newton(end, out);
            }
        }
    }

    /// Newton on `p'` from `theta`, kept inside `[lo, hi]`.
    fn critical_point(&self, theta: f64, lo: f64, hi: f64) -> f64 {
        let mut x = theta;
        for _ in 0..NEWTON_ITERS {
            let WithTwoDerivatives {
                first: d1,
                second: d2,
                ..
            } = self.p.eval_with_two_derivatives(x);
            let next = (x - d1 / d2).clamp(lo, hi);
            if !next.is_finite() {
                break;
            }
            let done = (next - x).abs() <= 2.0 * EPS * x.abs().max(1.0);
            x = next;
            if done {
                break;
            }
        }
        x
    }

    /// Pieces narrower than [`FLOOR`] without a certificate (a root of
    /// multiplicity three or more, or `p`, `p'`, `p''` all at model-error
    /// level), joined into clusters: a root for each certified sign change
    /// between samples, and the sample of smallest `|p|` if it is at rounding
    /// level.
    fn resolve_clusters(&self, mut pieces: Vec<(f64, f64)>, out: &mut Vec<Candidate>) {
        pieces.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut clusters: Vec<(f64, f64)> = Vec::new();
        for (lo, hi) in pieces {
            match clusters.last_mut() {
                Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
                _ => clusters.push((lo, hi)),
            }
        }
        for (lo, hi) in clusters {
            let samples: Vec<(f64, f64)> = (0..=CLUSTER_SAMPLES)
                .map(|i| {
                    let t = lo + (hi - lo) * i as f64 / CLUSTER_SAMPLES as f64;
                    (t, self.p.eval(t))
                })
                .collect();
            for w in samples.windows(2) {
                let ((t0, v0), (t1, v1)) = (w[0], w[1]);
                if v0.abs() > self.eta && v1.abs() > self.eta && v0.signum() != v1.signum() {
                    out.push(self.solve(t0, t1, v0.signum(), 0.5 * (t0 + t1)));
                }
            }
            if let Some(&(t, _)) = samples
                .iter()
                .min_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            {
                self.try_newton(t, out);
            }
        }
    }
}

/// Coefficients of `u ↦ q(c + ρ u)` for `q(s) = Σ g_j s^j`: Taylor shift by
/// repeated synthetic division (Horner), then scaling by powers of `ρ`
/// (exact: `ρ` is a power of two). `e_0` is left out: it is `g_0 + X`, the
/// very last operation of the first pass, and `X` is returned instead
/// (`None` for `c = 0`, where `e_0 = g_0`), so that one shift serves every
/// `g_0`.
fn shift(g: &Coeffs, c: f64, rho: f64) -> (Coeffs, Option<f64>) {
    let mut e = *g;
    let mut x = None;
    if c != 0.0 {
        for i in 0..ORDER - 1 {
            for j in (i.max(1)..ORDER - 1).rev() {
                e[j] += c * e[j + 1];
            }
            if i == 0 {
                x = Some(c * e[1]);
            }
        }
    }
    let mut w = rho;
    for v in e.iter_mut().skip(1) {
        *v *= w;
        w *= rho;
    }
    e[0] = f64::NAN;
    (e, x)
}

/// `(q(u), q'(u))` by Horner's rule.
fn horner(e: &Coeffs, u: f64) -> (f64, f64) {
    let (mut v, mut d) = (0.0, 0.0);
    for &x in e.iter().rev() {
        d = d * u + v;
        v = v * u + x;
    }
    (v, d)
}

/// `(q'(u), q''(u))` by Horner's rule.
fn horner2(e: &Coeffs, u: f64) -> (f64, f64) {
    let (mut v, mut d, mut dd) = (0.0, 0.0, 0.0);
    for &x in e.iter().rev() {
        dd = dd * u + 2.0 * d;
        d = d * u + v;
        v = v * u + x;
    }
    (d, dd)
}

/// Zero of `f` on `[lo, hi]` where `f(lo)` has the sign `sign_lo` and `f(hi)`
/// the opposite one: Newton from `x0`, bisection whenever a step would leave
/// the shrinking bracket or is not at least halving the step before last
/// (rtsafe). Returns the iterate of smallest `|f|`, with `|f|` and `f'`
/// there (`f' = NaN` if `f` was never evaluated).
fn bracketed(
    f: impl Fn(f64) -> (f64, f64),
    lo: f64,
    hi: f64,
    sign_lo: f64,
    x0: f64,
) -> (f64, f64, f64) {
    let (mut lo, mut hi) = (lo, hi);
    let mut x = if x0 > lo && x0 < hi {
        x0
    } else {
        0.5 * (lo + hi)
    };
    let mut best = (x, f64::INFINITY, f64::NAN);
    let (mut step, mut step_before) = (hi - lo, hi - lo);
    for _ in 0..MAX_ITERS {
        let (fx, dfx) = f(x);
        if fx.abs() < best.1 {
            best = (x, fx.abs(), dfx);
        }
        if fx == 0.0 || fx.is_nan() {
            break;
        }
        if fx * sign_lo > 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let tol = 2.0 * EPS * x.abs().max(1.0);
        if (fx / dfx).abs() <= tol {
            break;
        }
        let newton = x - fx / dfx;
        let next = if newton > lo && newton < hi && (2.0 * fx).abs() <= (step_before * dfx).abs() {
            newton
        } else {
            0.5 * (lo + hi)
        };
        (step_before, step) = (step, next - x);
        if step.abs() <= tol {
            break;
        }
        x = next;
    }
    best
}
