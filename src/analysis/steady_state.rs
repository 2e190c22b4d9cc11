//! The periodic steady state (docs/model.md section 3): the orbit through
//! the fixed point of the period map, simulated for one period with the
//! statistics observer attached, and its indicators (16), (18), (19).

use super::fixed_point::{FixedPoint, fixed_point};
use super::stats::{PeriodStats, StatsObserver, StatsWanted};
use crate::engine::Observer;
use crate::engine::{PeriodEngine, PeriodStart};
use crate::error::SimulationError;
use crate::motor::Motor;

/// The periodic steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyState {
    /// Slider velocity at the period boundary on the periodic orbit (m/s).
    pub boundary_velocity: f64,
    /// `P'` at the fixed point (0 if the orbit sticks).
    pub map_derivative: f64,
    /// Steady-state velocity `v_inf = x_inf / T` (m/s).
    pub v_inf: f64,
    /// Statistics of one steady-state period.
    pub stats: PeriodStats,
    /// Newton/bisection iterations of the fixed-point search.
    pub iterations: u32,
    /// Size of the last fixed-point correction (m/s).
    pub last_correction: f64,
    /// `|P(v*) - v*|` at the fixed point found (m/s): zero to rounding
    /// unless event-time tolerances make `P` ragged.
    pub residual: f64,
    /// Bound on the velocity error one steady-state period introduces
    /// through the engine's tolerances (m/s), if the engine states one.
    pub velocity_uncertainty: Option<f64>,
    /// Bound on the error of each event time (s).
    pub event_time_uncertainty: f64,
    /// Where the period map acts on more than the slider's velocity (a
    /// driven rod, docs/model.md section 16): a bound on the boundary
    /// velocity's error from the fixed point's residual and one period's
    /// errors in every component, carried through `(I - dP/dz)^(-1)`. It
    /// replaces the one-dimensional `/ (1 - P')` of the error estimate
    /// (`analysis/error_estimate.rs`).
    pub boundary_bound: Option<f64>,
}

/// The steady state reached from `guess`, with one period observed by
/// `observer`.
pub fn steady_state<E: PeriodEngine, O: Observer>(
    engine: &mut E,
    guess: f64,
    wanted: StatsWanted,
    observer: &mut O,
) -> Result<SteadyState, SimulationError> {
    let FixedPoint {
        velocity: v_star,
        map_derivative,
        iterations,
        last_correction,
    } = fixed_point(engine, guess)?;
    steady_state_at(
        engine,
        PeriodStart {
            velocity: v_star,
            mode: None,
        },
        (Some(map_derivative), iterations, last_correction),
        wanted,
        observer,
    )
}

/// The periodic orbit through the boundary state `start` (a velocity
/// `v_star`, and the mode the slider ends the previous period in when the
/// start-up that reached it says so; without, it follows from the
/// velocity), with one period observed by `observer`; `(P'(v_star),
/// iterations, last correction)` come from the search that found it (or
/// from the start-up that reached it).
pub(crate) fn steady_state_at<E: PeriodEngine, O: Observer>(
    engine: &mut E,
    start: PeriodStart,
    (map_derivative, iterations, last_correction): (Option<f64>, u32, f64),
    wanted: StatsWanted,
    observer: &mut O,
) -> Result<SteadyState, SimulationError> {
    // One unobserved period gives the mode the orbit has at its period
    // boundary, so that the observed period reports the transition at
    // phase 0 like every other.
    let v_star = start.velocity;
    let before = engine.run_period(2, start, &mut ())?;
    // The regime and the error estimate need the stick and slip times and
    // the sliding distance of this one period, whatever else is wanted.
    let mut stats = StatsObserver::for_engine(
        &*engine,
        StatsWanted {
            stiction: true,
            slip_time: true,
            sliding: true,
            ..wanted
        },
    );
    let end = engine.run_period(
        2,
        PeriodStart {
            velocity: before.velocity,
            mode: Some(before.mode),
        },
        &mut (&mut stats, observer),
    )?;
    let period = engine.signal().period();
    Ok(SteadyState {
        boundary_velocity: before.velocity,
        residual: (before.velocity - v_star).abs(),
        map_derivative: map_derivative.unwrap_or(before.map_derivative),
        v_inf: end.step / period,
        stats: stats.last,
        iterations,
        last_correction,
        velocity_uncertainty: engine.last_velocity_uncertainty(),
        event_time_uncertainty: engine.event_time_uncertainty(),
        boundary_bound: None,
    })
}

/// Indicators derived from a steady-state period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyIndicators {
    /// `v_inf` (m/s).
    pub v_inf: f64,
    /// Smoothness `zeta_inf` (16).
    pub smoothness: f64,
    /// Durability `delta_inf` (18), 1/N.
    pub durability: f64,
    /// Friction energy per period `W_f` (19), J.
    pub friction_energy: f64,
    /// Time in stick / period in steady state.
    pub stiction_fraction: f64,
}

impl SteadyState {
    /// The paper's indicators for this steady state and motor.
    pub fn indicators(&self, motor: &Motor, period: f64) -> SteadyIndicators {
        let s = &self.stats;
        let spread = s.v_max - s.v_min;
        let wear_force = motor.contact_force() * s.sliding_distance;
        SteadyIndicators {
            v_inf: self.v_inf,
            // 0/0 (no motion at all) is undefined, reported as none.
            smoothness: if spread > 0.0 {
                self.v_inf.abs() / spread
            } else if self.v_inf != 0.0 {
                f64::INFINITY
            } else {
                f64::NAN
            },
            durability: if wear_force > 0.0 {
                s.step / wear_force
            } else {
                f64::INFINITY
            },
            friction_energy: motor.mu_d() * wear_force,
            stiction_fraction: s.stick_time / period,
        }
    }
}
