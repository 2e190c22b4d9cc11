//! The spring method against the weight and Newton methods (the paper's
//! section 5; docs/model.md section 17): what a spring against the slider
//! reads, over a log range of stiffnesses, tied and free-ended, beside the
//! stall force and the start-up force of the drive's characteristic.
//!
//! # What is computed
//!
//! For each stiffness `k` (log spaced, `options`) and each kind of spring
//! asked (tied, free-ended) the scene runs with that spring (`case`) and
//! the spring's reading over the steady orbit is collected: the mean,
//! largest and least spring force, the contact fraction, the orbit's
//! periods and the periods simulated. A case whose motion locks into no orbit (of up to
//! 64 periods) within `max_periods` periods from rest (default 20000) is a
//! row that says so, with the spring read over the 64 periods after them
//! and the range of a single period's mean force: not an error. The springs take the scene's own `[spring]`, if any: a tied one
//! its damping and preload, a free end its gap; without it (or for the
//! other kind) a tied spring without damping or preload and a free end at
//! gap 0. Every case runs on rayon's global pool, sharing one signal.
//!
//! Beside the readings, from the scene without its spring
//! ([`crate::characteristic::reference_forces`]):
//!
//! * the **weight method**: the stall force `F_stall`, the load at which
//!   `v_inf` reaches 0 (docs/model.md section 9);
//! * the **Newton method**: the start-up force, the largest `m_s a_p` of
//!   the start-up from rest at zero load.
//!
//! # Soft-spring limit
//!
//! With a tied spring the slider's mean velocity over a steady orbit is 0,
//! and the mean of its equation of motion gives
//! `<F_spring> = <F_f> + m_s g_t`. As `k -> 0` the spring's force varies
//! less and less over a period (its swing is `k` times the slider's
//! excursion), so the slider sees a nearly constant load `<F_spring>` and
//! that load must hold `v_inf` at 0: the mean force tends to the stall
//! force, with a difference of first order in `k`.
//!
//! Outputs (text, JSON, CSV) are in `table`; keys and columns in
//! docs/interface.md, "stickslip bench".

mod case;
mod options;
pub(crate) mod table;

use crate::characteristic::{self, CharacteristicError, ReferenceForces};
use crate::error::Num;
use crate::scene::Scene;
use crate::simulation::SignalCache;
use crate::spring::{Spring, SpringEnd};
pub use case::SpringCase;
pub use options::{
    BenchOptions, DEFAULT_FROM, DEFAULT_MAX_PERIODS, DEFAULT_POINTS, DEFAULT_TO, MAX_POINTS,
    SpringKinds,
};
use rayon::prelude::*;
use std::time::{Duration, Instant};
use thiserror::Error;

/// What goes wrong in a bench.
#[derive(Debug, Error)]
pub enum BenchError {
    /// An option out of its range.
    #[error("{flag} {value}: {requirement}")]
    Option {
        /// The option's flag.
        flag: &'static str,
        /// The value given.
        value: String,
        /// What it must satisfy.
        requirement: String,
    },
    /// The stall force or the start-up force could not be found.
    #[error("the weight and Newton methods: {0}")]
    Reference(#[from] CharacteristicError),
    /// A spring's run failed (a time limit, an internal limit).
    #[error("{kind} spring of stiffness {} N/m: {source}", Num(*stiffness))]
    Simulation {
        /// `tied` or `free`.
        kind: &'static str,
        /// The stiffness (N/m).
        stiffness: f64,
        /// The simulator's error.
        #[source]
        source: crate::error::Error,
    },
}

/// The readings at one stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchRow {
    /// `k` (N/m).
    pub stiffness: f64,
    /// The tied spring's case, if asked.
    pub tied: Option<SpringCase>,
    /// The free-ended spring's case, if asked.
    pub free: Option<SpringCase>,
}

/// A bench: the spring method's readings against stiffness, beside the
/// stall and start-up forces.
#[derive(Debug, Clone, PartialEq)]
pub struct Bench {
    /// The options it ran with.
    pub options: BenchOptions,
    /// The tied spring's damping `b` (N s/m) and preload `F_p` (N).
    pub tied_spring: (f64, f64),
    /// The free end's gap `x_gap` (m).
    pub free_gap: f64,
    /// The stall force (weight method) and the start-up force (Newton
    /// method) of the scene without its spring.
    pub reference: ReferenceForces,
    /// One row per stiffness, in increasing stiffness.
    pub rows: Vec<BenchRow>,
    /// Wall time of the whole bench.
    pub wall_time: Duration,
}

impl Bench {
    /// The stall force (N).
    pub fn stall_force(&self) -> f64 {
        self.reference.stall.force
    }

    /// The start-up force (N): the largest `m_s a_p` of the start-up.
    pub fn startup_force(&self) -> Option<f64> {
        self.reference.transient.map(|t| t.max_force)
    }

    /// Every case, row by row (tied before free).
    pub fn cases(&self) -> impl Iterator<Item = &SpringCase> {
        self.rows
            .iter()
            .flat_map(|r| r.tied.iter().chain(r.free.iter()))
    }
}

/// The springs of a bench: the tied spring's `(damping, preload)` and the
/// free end's gap, from the scene's `[spring]` (module docs).
fn spring_settings(scene: &Scene) -> ((f64, f64), f64) {
    match scene.spring {
        Some(Spring {
            damping,
            end: SpringEnd::Tied { preload },
            ..
        }) => ((damping, preload), 0.0),
        Some(Spring {
            end: SpringEnd::Free { gap },
            ..
        }) => ((0.0, 0.0), gap),
        None => ((0.0, 0.0), 0.0),
    }
}

/// The bench of `scene` (module docs).
pub fn bench(scene: &Scene, options: &BenchOptions) -> Result<Bench, BenchError> {
    let clock = Instant::now();
    options.validate()?;
    let ((damping, preload), gap) = spring_settings(scene);
    let mut bare = scene.clone();
    bare.spring = None;
    let stiffnesses = options.stiffnesses();
    let mut springs = Vec::new();
    for &k in &stiffnesses {
        if options.kinds.tied() {
            springs.push(Spring {
                stiffness: k,
                damping,
                end: SpringEnd::Tied { preload },
            });
        }
        if options.kinds.free() {
            springs.push(Spring {
                stiffness: k,
                damping: 0.0,
                end: SpringEnd::Free { gap },
            });
        }
    }
    let signals = SignalCache::default();
    let (reference, cases) = rayon::join(
        || characteristic::reference_forces(&bare),
        || {
            springs
                .par_iter()
                .map(|&spring| {
                    case::measure(scene, spring, options.max_periods, &signals).map_err(|source| {
                        BenchError::Simulation {
                            kind: match spring.end {
                                SpringEnd::Tied { .. } => "tied",
                                SpringEnd::Free { .. } => "free",
                            },
                            stiffness: spring.stiffness,
                            source,
                        }
                    })
                })
                .collect::<Result<Vec<_>, _>>()
        },
    );
    let reference = reference?;
    let mut cases = cases?.into_iter();
    let rows = stiffnesses
        .into_iter()
        .map(|stiffness| BenchRow {
            stiffness,
            tied: options.kinds.tied().then(|| cases.next()).flatten(),
            free: options.kinds.free().then(|| cases.next()).flatten(),
        })
        .collect();
    Ok(Bench {
        options: *options,
        tied_spring: (damping, preload),
        free_gap: gap,
        reference,
        rows,
        wall_time: clock.elapsed(),
    })
}
