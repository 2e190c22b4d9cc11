//! Optimal drive signals (`stickslip optimize`, docs/model.md section 15):
//! the best rod signal of `n` harmonics for an objective, at the scene's
//! stroke and highest frequency.
//!
//! The paper compares the Fourier series of the ideal signal with and
//! without sigma factors at equal `f_max`; both are two points of a space
//! of `2n - 2` shapes (the relative amplitudes and phases of harmonics
//! `1..n`; the overall scale and the time origin are fixed by the stroke
//! scaling and the shift). This module searches that space.
//!
//! One idea per file:
//!
//! * `params`: the parametrisation ([`Shape`], [`HarmonicSeries`]);
//! * `problem`: stroke, frequency, limits, one evaluation, the merit;
//! * `objective`: the objectives and the values they are made of;
//! * [`gradient`]: sensitivities to the signal's parameters (exact for
//!   `v_inf`, `S` and `U`, central differences for smoothness, durability
//!   and the start-up; the one place derivatives come from);
//! * `global`: the seeded Latin hypercube and the choice of starts;
//! * `local`: BFGS with a weak Wolfe line search (nonsmooth optima);
//! * `search`: the two stages together, the best feasible result;
//! * `distinct`: which refinement ends are the same local optimum;
//! * `pareto`: a front of two objectives;
//! * `map`: the `v_inf` map over the plane of `n = 2`;
//! * `output`: the written scene, the comparison, text and JSON;
//! * `spec`: the `[optimize]` table and the flags.
//!
//! # What is guaranteed, and what is not
//!
//! * The written signal has the stroke exactly (its scene scales it, to
//!   rounding), harmonics `1..n` of `f_0` with `n f_0 <= f_max`, and the
//!   `v_inf` reported is that of `stickslip run` on the written scene, with
//!   its error estimate: the optimiser evaluates exactly the scene it
//!   writes.
//! * The result is never worse than any signal the search evaluated, the
//!   sigma and plain Fourier signals of the same `n` and `f_max` among
//!   them (when they satisfy the limits).
//! * It is a local optimum at best: the global stage is a finite sample,
//!   the local stage stops where it cannot improve, and the count of local
//!   optima is of those found (`distinct`). `v_inf` has kinks where the
//!   event structure of the steady orbit changes; the optima seen lie on
//!   them, where no gradient exists: the search takes the derivative of
//!   the side of the point's own orbit there ([`gradient`]).
//! * The same scene, settings and seed give the same result, bit for bit,
//!   on any number of threads.

mod distinct;
mod global;
pub(crate) mod gradient;
mod local;
pub(crate) mod map;
mod objective;
pub(crate) mod output;
mod params;
mod pareto;
mod problem;
mod search;
pub(crate) mod spec;

pub use gradient::{Param, gradient, gradient_by_differences};
pub use objective::{Objective, Values};
pub use params::{HarmonicSeries, Shape};
pub use problem::{Limits, Measured, Problem};
pub use search::{Found, Search, SearchOptions};
pub use spec::{Keep, OptimizeTable, Overrides, Settings};

use crate::error::{Error, ParamError};
use crate::scene::Scene;
use crate::signal::{Signal, SignalSpec};
use local::LocalOptions;

/// A paper signal at the same `n`, stroke and `f_max`, for comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// `"sigma"` or `"fourier"`.
    pub name: &'static str,
    /// Its signal.
    pub spec: SignalSpec,
    /// Its shape (a seed of the search).
    pub shape: Shape,
    /// What its search run reported.
    pub measured: Result<Measured, String>,
}

/// Everything one optimisation found.
#[derive(Debug, Clone)]
pub struct Optimum {
    /// The settings.
    pub settings: Settings,
    /// The problem of the first objective.
    pub problem: Problem,
    /// The sigma and the plain Fourier signal (without friction, where
    /// they do not exist, none).
    pub references: Vec<Reference>,
    /// The search of the first objective.
    pub search: Search,
    /// The best feasible signal of the first objective (for a Pareto
    /// front, the front's point best in it).
    pub best: Found,
    /// The Pareto front, for two objectives.
    pub front: Option<Vec<pareto::FrontPoint>>,
}

/// The paper's signals at the problem's `n`, stroke and `f_0`.
pub fn references(problem: &Problem) -> Result<Vec<Reference>, Error> {
    let motor = crate::motor::Motor::new(problem.base.motor)?;
    let mut out = Vec::new();
    for (name, sigma) in [("sigma", true), ("fourier", false)] {
        let Some(spec) = problem.reference_spec(sigma) else {
            continue;
        };
        let Signal::Fourier(signal) = Signal::build(&spec, &motor)? else {
            continue;
        };
        out.push(Reference {
            name,
            shape: Shape::of_series(&signal.amplitudes(), &signal.phases()),
            measured: problem.measure(spec.clone()),
            spec,
        });
    }
    Ok(out)
}

/// Sets the merit's units of `problem` from the sigma signal (module docs
/// of `problem`): the objective's and `v_inf`'s magnitudes there, or
/// `x_hat f_0` (a velocity of the signal) where they are zero or missing.
pub fn set_units(problem: &mut Problem, references: &[Reference]) {
    let natural = problem.stroke * problem.f0;
    let sigma = references
        .iter()
        .find(|r| r.name == "sigma")
        .and_then(|r| r.measured.as_ref().ok());
    let positive = |x: f64| (x.is_finite() && x != 0.0).then_some(x.abs());
    problem.v_ref = sigma
        .and_then(|m| positive(m.values.v_inf))
        .unwrap_or(natural);
    problem.scale = sigma
        .and_then(|m| positive(problem.objective.searched(&m.values)))
        .unwrap_or(match problem.objective {
            Objective::VInf => natural,
            _ => 1.0,
        });
}

/// Runs the optimisation `settings` describe on `scene` (module docs).
pub fn optimize(scene: &Scene, settings: &Settings) -> Result<Optimum, Error> {
    let first = settings.objectives[0];
    let second = settings.objectives.get(1).copied();
    let mut problem = settings.problem(scene, first)?;
    problem.also = second;
    let references = references(&problem)?;
    set_units(&mut problem, &references);
    let seeds: Vec<Shape> = references.iter().map(|r| r.shape.clone()).collect();
    let options = SearchOptions {
        samples: settings.samples,
        local_starts: settings.local_starts,
        local: LocalOptions {
            max_iterations: settings.max_iterations,
            ..LocalOptions::default()
        },
        seed: settings.seed,
    };
    let found = search::search(&problem, &seeds, &options);
    let none_feasible = |o: Objective| -> Error {
        ParamError::Inconsistent {
            field: "optimize".to_owned(),
            reason: format!(
                "no signal the search evaluated for {o} satisfies the limits \
                 (or has a steady state): relax the limits or raise optimize.samples"
            ),
        }
        .into()
    };
    let mut best = found.best.clone().ok_or_else(|| none_feasible(first))?;
    let front = match second {
        None => None,
        Some(b) => {
            let mut other = settings.problem(scene, b)?;
            other.also = Some(first);
            set_units(&mut other, &references);
            let end_b = search::search(&other, &seeds, &options)
                .best
                .ok_or_else(|| none_feasible(b))?;
            let front = pareto::front(
                &problem,
                [first, b],
                &best,
                &end_b,
                settings.pareto_points,
                &options,
            );
            // The front's first point is the best found in the first
            // objective (the search for the second may have found a
            // better one).
            if let Some(top) = front.first() {
                best = top.found.clone();
            }
            Some(front)
        }
    };
    Ok(Optimum {
        settings: settings.clone(),
        problem,
        references,
        search: found,
        best,
        front,
    })
}
