//! The analysis of a run (docs/model.md section 3; the paper's sections 6.1,
//! 6.2): per-period statistics, the start-up from rest, the fixed point of
//! the period map and the periodic steady state; the indicators are
//! computed from these.
//!
//! Per period `p` (`t` in `[(p-1)T, pT]`):
//! * step `x_p = x_S(pT) - x_S((p-1)T)`, mean velocity `v_p = x_p / T`;
//! * smoothness (16) `zeta_p = |v_p| / (max_p v_S - min_p v_S)`, with exact
//!   extrema: segment ends, and in stick the zeros of `a_R`;
//! * sliding distance `integral |v_R - v_S| dt`, exact per segment
//!   (`|delta(x_R - x_S)|`) plus `|delta x_R|` at rod jumps, giving the wear
//!   volume (17) `V_p / w = F_c x` this, the durability (18)
//!   `delta_p = x_p / (F_c integral |v_rel|)` and the friction energy (19)
//!   `W_f,p = mu_d F_c integral |v_rel|`;
//! * time in stick.
//!
//! **Steady state** is the periodic orbit of the period map
//! `P: v_S((p-1)T) -> v_S(pT)`. `P` is non-decreasing (two sliders on the
//! same rod never overtake each other), so the iterates from rest move
//! monotonically towards the nearest fixed point in the direction `P`
//! moves them. A zero of `g(v) = P(v) - v` is found by safeguarded Newton in
//! a bracket `g(lo) > 0 >= g(hi)` grown from the starting guess in that
//! direction, with `P'(v)` carried exactly through the period by the
//! engine. `g` need not be monotone (a stuck slider can be outrun by one
//! that slides), so a map with several fixed points may yield one the
//! start-up does not reach: the caller certifies it (`certificate`: a
//! covering of the gap between rest and the fixed point by pieces proven
//! free of fixed points) or finds the nearer one
//! ([`crate::Outcome::of_engine`]). The transient from rest can
//! be simulated until its own period-to-period changes have died out (with
//! Aitken's extrapolation); the two steady states must agree.
//!
//! **Start-up** `p_0.99` is the first period with `v_p >= 0.99 v_inf`
//! (for a slider that moves backwards, `v_p <= 0.99 v_inf`).

//!
//! * `stats`: the per-period statistics observer;
//! * [`transient`]: the start-up from rest;
//! * [`fixed_point`]: the period map's fixed point;
//! * `certificate`: the proof that a fixed point is the limit of the motion
//!   from rest, or the bracket of a nearer one;
//! * [`steady_state`]: the periodic orbit and its indicators.

pub(crate) mod certificate;
pub(crate) mod error_estimate;
mod fixed_point;
mod stats;
mod steady_state;
mod transient;

pub use error_estimate::ErrorEstimate;
pub use fixed_point::{FixedPoint, fixed_point, fixed_point_between};
pub use stats::{PeriodStats, StatsObserver, StatsWanted};
pub(crate) use steady_state::steady_state_at;
pub use steady_state::{SteadyIndicators, SteadyState, steady_state};
pub use transient::{AnalysisOptions, Convergence, Transient, transient};
pub(crate) use transient::{Attracted, transient_until};
