//! A Pareto front of two objectives by the epsilon-constraint method
//! (docs/model.md section 15).
//!
//! With objectives `A` and `B` (each with its sense, so both maximised
//! here): the search for `A` alone gives one end of the front, the search
//! for `B` alone the other. Between the values of `B` at the two ends,
//! `points - 2` evenly spaced levels `b_j` each give the problem
//! "optimise `A` subject to `B >= b_j`", refined from the front point found
//! for the level before and from the `B` optimum (the better feasible
//! result is kept). The front is the non-dominated set of all these
//! points, in order of `A`. Each point is a local result: the front found
//! is an inner approximation of the true one.

use super::objective::Objective;
use super::problem::Problem;
use super::search::{self, Found, SearchOptions};

/// One point of the front.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontPoint {
    /// The signal.
    pub found: Found,
    /// The two objectives as reported, in the order given.
    pub objectives: [f64; 2],
}

/// The reported values of both objectives of a found signal.
fn objectives_of(problem: &Problem, pair: [Objective; 2], found: &Found) -> Option<[f64; 2]> {
    let a = problem.reported(pair[0], &found.measured)?;
    let b = problem.reported(pair[1], &found.measured)?;
    Some([a, b])
}

/// True if `p` is at least as good as `q` in both objectives and better in
/// one.
fn dominates(pair: [Objective; 2], p: &[f64; 2], q: &[f64; 2]) -> bool {
    let s = [pair[0].sense(), pair[1].sense()];
    let ge = (0..2).all(|i| s[i] * p[i] >= s[i] * q[i]);
    let gt = (0..2).any(|i| s[i] * p[i] > s[i] * q[i]);
    ge && gt
}

/// The front of `first` (optimising `pair[0]`) and `second` (optimising
/// `pair[1]`, same signals otherwise), with the two single-objective
/// optima `end_a`, `end_b` already searched.
pub(super) fn front(
    first: &Problem,
    pair: [Objective; 2],
    end_a: &Found,
    end_b: &Found,
    points: usize,
    options: &SearchOptions,
) -> Vec<FrontPoint> {
    let mut candidates: Vec<Found> = vec![end_a.clone(), end_b.clone()];
    let b_of = |f: &Found| first.reported(pair[1], &f.measured);
    if let (Some(b_a), Some(b_b)) = (b_of(end_a), b_of(end_b)) {
        let sense = pair[1].sense();
        let (lo, hi) = (sense * b_a, sense * b_b);
        let mut previous = end_a.shape.clone();
        for j in 1..points.saturating_sub(1) {
            let level = lo + (hi - lo) * j as f64 / (points - 1) as f64;
            let mut problem = first.clone();
            problem.bound = Some((pair[1], level));
            let mut best: Option<Found> = None;
            for (i, start) in [previous.clone(), end_b.shape.clone()].iter().enumerate() {
                let (r, _) = search::refine(&problem, start, i, &options.local);
                if let Some(found) = r.best
                    && best
                        .as_ref()
                        .is_none_or(|b| search::better(&problem, &found.measured, &b.measured))
                {
                    best = Some(found);
                }
            }
            if let Some(found) = best {
                previous = found.shape.clone();
                candidates.push(found);
            }
        }
    }
    let valued: Vec<FrontPoint> = candidates
        .into_iter()
        .filter_map(|found| {
            objectives_of(first, pair, &found).map(|objectives| FrontPoint { found, objectives })
        })
        .collect();
    let mut front: Vec<FrontPoint> = Vec::new();
    for (i, p) in valued.iter().enumerate() {
        let dominated = valued
            .iter()
            .enumerate()
            .any(|(j, q)| j != i && dominates(pair, &q.objectives, &p.objectives));
        let repeated = front.iter().any(|f| f.objectives == p.objectives);
        if !dominated && !repeated {
            front.push(p.clone());
        }
    }
    let s = pair[0].sense();
    front.sort_by(|a, b| (s * b.objectives[0]).total_cmp(&(s * a.objectives[0])));
    front
}
