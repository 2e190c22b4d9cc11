//! One search of a [`Problem`]: the global stage, the local refinements
//! from its best distinct points, and the result (docs/model.md
//! section 15).
//!
//! The reported optimum is the best *feasible* signal any run of the
//! search evaluated ([`Problem::feasible`] on the values the run reports),
//! whether a global sample, a line-search trial or an accepted step; the
//! central-difference runs of a gradient (where it takes any) only give
//! slopes. Since the seeds (the sigma and the plain Fourier signal) are
//! evaluated in the global stage, the optimum is never worse than the
//! better of them (when feasible).
//!
//! Each refinement maximises the merit of [`Problem::merit`] with the
//! penalty weight `mu = 10`; if its last point still violates a limit,
//! it goes on from there with `mu` ten times larger, up to `1e4`. The
//! refinements are independent, run in parallel, and their results are
//! gathered in start order, so the outcome does not depend on the thread
//! count.
//!
//! **Local optima.** Which refinement ends are the same optimum is decided
//! on their rod signals and merits (`distinct`); the count is of the
//! optima the refinements found, not a proof that there are no others.

use super::gradient::coordinate_gradient;
use super::local::{self, LocalOptions, Stop};
use super::params::Shape;
use super::problem::{Measured, Problem};
use rayon::prelude::*;
use std::cell::RefCell;

/// Global-stage points closer than this are not both taken as starts.
pub(super) const START_SEPARATION: f64 = 0.05;

/// A signal the search evaluated, with what its run reported.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    /// The shape.
    pub shape: Shape,
    /// Its run's values.
    pub measured: Measured,
}

/// One point of the history: the best feasible objective after some runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryPoint {
    /// `"global"` or `"local"`.
    pub stage: &'static str,
    /// The refinement (from 0), for the local stage.
    pub start: Option<usize>,
    /// The step of the refinement (0 for the global stage).
    pub iteration: usize,
    /// Runs of this stage or refinement so far.
    pub evaluations: u64,
    /// The merit of the point reached.
    pub merit: f64,
    /// The best feasible objective (as reported) of this stage or
    /// refinement so far.
    pub best: Option<f64>,
}

/// One local refinement.
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// Where it started.
    pub from: Shape,
    /// Where it ended (the last accepted point).
    pub to: Shape,
    /// The merit there.
    pub merit: f64,
    /// Why it stopped.
    pub stop: Stop,
    /// Accepted steps.
    pub iterations: usize,
    /// Simulator runs it made (central differences included).
    pub evaluations: u64,
    /// Gradients it took (each one computation of the exact sensitivities
    /// on the steady period of a run already made, plus the central
    /// differences of the quantities without them).
    pub gradients: u64,
    /// Its best feasible evaluated signal.
    pub best: Option<Found>,
}

/// The result of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct Search {
    /// The best feasible signal evaluated.
    pub best: Option<Found>,
    /// Points of the global stage (seeds included).
    pub samples: usize,
    /// The refinements, in start order.
    pub refinements: Vec<Refinement>,
    /// Distinct local optima among the refinements' ends.
    pub local_optima: usize,
    /// All simulator runs.
    pub evaluations: u64,
    /// All gradients the refinements took (each one computation of the exact
    /// sensitivities, plus the central differences of the quantities without
    /// them).
    pub gradients: u64,
    /// The history: the global stage, then every step of every refinement.
    pub history: Vec<HistoryPoint>,
}

/// How a search proceeds.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchOptions {
    /// Points of the Latin hypercube.
    pub samples: usize,
    /// Refinements at most.
    pub local_starts: usize,
    /// The local method's settings.
    pub local: LocalOptions,
    /// The seed.
    pub seed: u64,
}

/// `true` if `a` is a better feasible result than `b` for `problem`: by
/// the objective as reported, ties by the searched value.
pub(super) fn better(problem: &Problem, a: &Measured, b: &Measured) -> bool {
    let o = problem.objective;
    let key = |m: &Measured| {
        (
            problem
                .reported(o, m)
                .map_or(f64::NEG_INFINITY, |x| o.sense() * x),
            o.sense() * o.searched(&m.values),
        )
    };
    let (ka, kb) = (key(a), key(b));
    ka.0 > kb.0 || (ka.0 == kb.0 && ka.1 > kb.1)
}

fn keep_best(problem: &Problem, best: &mut Option<Found>, candidate: Found) {
    if !problem.feasible(&candidate.measured) {
        return;
    }
    let replace = match best {
        None => true,
        Some(b) => better(problem, &candidate.measured, &b.measured),
    };
    if replace {
        *best = Some(candidate);
    }
}

/// The reported objective of a found signal.
fn objective_of(problem: &Problem, found: &Option<Found>) -> Option<f64> {
    found
        .as_ref()
        .and_then(|f| problem.reported(problem.objective, &f.measured))
}

struct State {
    evaluations: u64,
    gradients: u64,
    best: Option<Found>,
    /// The last evaluated point and its run, for the gradient there.
    last: Option<(Vec<f64>, Result<Measured, String>)>,
    history: Vec<HistoryPoint>,
}

/// One refinement from `start` (number `index`), with the penalty weight
/// raised while its end violates a limit (module docs), and the history of
/// its steps.
pub(super) fn refine(
    problem: &Problem,
    start: &Shape,
    index: usize,
    options: &LocalOptions,
) -> (Refinement, Vec<HistoryPoint>) {
    let constrained = problem.objective != super::Objective::VInf
        || problem.bound.is_some()
        || !problem.limits.is_empty();
    let state = RefCell::new(State {
        evaluations: 0,
        gradients: 0,
        best: None,
        last: None,
        history: Vec::new(),
    });
    let measure = |z: &[f64]| -> Result<Measured, String> {
        let mut s = state.borrow_mut();
        if let Some((at, m)) = &s.last
            && at.as_slice() == z
        {
            return m.clone();
        }
        let shape = Shape::from_coordinates(z);
        let m = problem.evaluate(&shape);
        s.evaluations += 1;
        if let Ok(measured) = &m {
            keep_best(
                problem,
                &mut s.best,
                Found {
                    shape,
                    measured: *measured,
                },
            );
        }
        s.last = Some((z.to_vec(), m.clone()));
        m
    };
    let mut z = start.coordinates();
    let mut mu = 10.0;
    let mut iterations = 0;
    let (mut merit, mut stop);
    loop {
        let value = |z: &[f64]| measure(z).map_or(f64::NEG_INFINITY, |m| problem.merit(&m, mu));
        let gradient = |z: &[f64]| -> Option<Vec<f64>> {
            let m = measure(z).ok()?;
            let shape = Shape::from_coordinates(z);
            let grads = coordinate_gradient(problem, &shape, &m);
            let mut s = state.borrow_mut();
            s.gradients += 1;
            s.evaluations += grads.runs;
            drop(s);
            let grads = grads.values.ok()?;
            Some(
                grads
                    .iter()
                    .map(|dv| problem.merit_derivative(&m, dv, mu))
                    .collect(),
            )
        };
        let on_step = |_: usize, f: f64| {
            iterations += 1;
            let mut s = state.borrow_mut();
            let best = objective_of(problem, &s.best);
            let evaluations = s.evaluations;
            s.history.push(HistoryPoint {
                stage: "local",
                start: Some(index),
                iteration: iterations,
                evaluations,
                merit: f,
                best,
            });
        };
        let f0 = value(&z);
        let result = local::maximise(&z, f0, value, gradient, on_step, options);
        z = result.z;
        merit = result.value;
        stop = result.stop;
        let feasible_end = matches!(measure(&z), Ok(m) if problem.feasible(&m));
        if !constrained || feasible_end || mu >= 1e4 || iterations >= options.max_iterations {
            break;
        }
        mu *= 10.0;
    }
    let s = state.into_inner();
    let refinement = Refinement {
        from: start.clone(),
        to: Shape::from_coordinates(&z),
        merit,
        stop,
        iterations,
        evaluations: s.evaluations,
        gradients: s.gradients,
        best: s.best,
    };
    (refinement, s.history)
}

/// The search: `seeds` and the Latin hypercube evaluated, refinements from
/// the best distinct points (module docs).
pub(super) fn search(problem: &Problem, seeds: &[Shape], options: &SearchOptions) -> Search {
    let n = problem.harmonics;
    let mut shapes: Vec<Shape> = seeds.to_vec();
    shapes.extend(super::global::samples(n, options.samples, options.seed));
    let measured: Vec<Result<Measured, String>> =
        shapes.par_iter().map(|s| problem.evaluate(s)).collect();
    let merits: Vec<f64> = measured
        .iter()
        .map(|m| {
            m.as_ref()
                .map_or(f64::NEG_INFINITY, |m| problem.merit(m, 10.0))
        })
        .collect();
    let mut best = None;
    for (shape, m) in shapes.iter().zip(&measured) {
        if let Ok(m) = m {
            keep_best(
                problem,
                &mut best,
                Found {
                    shape: shape.clone(),
                    measured: *m,
                },
            );
        }
    }
    let global_best = objective_of(problem, &best);
    let mut history = vec![HistoryPoint {
        stage: "global",
        start: None,
        iteration: 0,
        evaluations: shapes.len() as u64,
        merit: merits.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        best: global_best,
    }];
    let starts = super::global::starts(&shapes, &merits, options.local_starts, START_SEPARATION);
    let runs: Vec<(Refinement, Vec<HistoryPoint>)> = starts
        .par_iter()
        .enumerate()
        .map(|(i, &s)| refine(problem, &shapes[s], i, &options.local))
        .collect();
    let mut refinements = Vec::with_capacity(runs.len());
    let mut evaluations = shapes.len() as u64;
    let mut gradients = 0;
    for (r, h) in runs {
        evaluations += r.evaluations;
        gradients += r.gradients;
        if let Some(found) = r.best.clone() {
            keep_best(problem, &mut best, found);
        }
        history.extend(h);
        refinements.push(r);
    }
    Search {
        best,
        samples: shapes.len(),
        local_optima: super::distinct::local_optima(&refinements),
        refinements,
        evaluations,
        gradients,
        history,
    }
}
