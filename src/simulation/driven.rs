//! The steady state of a driven rod (docs/model.md section 16, "The
//! steady state"): the fixed point of the period map on the boundary
//! state `z = (x_R, v_R, v_S)`, found by Newton with the exact Jacobian,
//! and the start-up from rest followed into its attraction.
//!
//! ## Newton
//! Once the start-up's periods have had the same event counts for
//! [`STABLE`] periods in a row, Newton starts from its boundary state:
//!
//! ```text
//! z_(i+1) = z_i + (I - J(z_i))^(-1) (P(z_i) - z_i)
//! ```
//!
//! with `P(z_i)` a period of the engine from `z_i` and `J = dP/dz` the
//! exact Jacobian of that period, its event structure held
//! ([`crate::sensitivity::period_map_jacobian`]: every event time moves
//! by the implicit function theorem). It stops when the correction is
//! below `1e-13` of the scales (`x`: the signal's stroke, `v`: its largest
//! velocity), applied once more; where it does not converge in
//! [`NEWTON`] iterations, or a period holds a grazing, it is tried again
//! after twice as many periods of the start-up.
//!
//! ## The motion from rest decides
//! A fixed point is the steady state only if the motion from rest goes
//! to it. Its attraction is judged on the start-up's own periods, in the
//! scaled coordinates `e = S^(-1) (z - z*)`:
//! * the spectral radius of `J` is below 1, and `m` is the least number
//!   of periods with `||J^m|| <= 1/2` (at most [`WINDOW`]): over `m`
//!   periods the linearised map halves every deviation;
//! * the last `m + 1` periods of the start-up had the fixed point's event
//!   counts and boundary mode, and its deviation `m` periods ago went
//!   where the linearised map sends it, to within a quarter of itself:
//!   `||e_k - J^m e_(k-m)|| <= ||e_(k-m)|| / 4`. The `m`-period map then
//!   shrinks the deviation by at least `3/4` there;
//! * or the deviation is below `1e-12` (the start-up is at the fixed
//!   point within rounding).
//!
//! This is evidence measured along the motion (the nonlinear part of the
//! map is checked where the motion is, not bounded over a region), as the
//! exact repetition it replaces was. Without it (no fixed point found,
//! not attracting, never entered) the start-up runs on to an exact
//! repetition, as before.
//!
//! ## The fixed point's error
//! The engine's errors of one period, componentwise `delta` (rounding of
//! positions and velocities, `8 eps` per segment of the scales; the
//! slider's velocity bound `u` from event times and decisions, and the
//! rod's share of it, `u m_s / M`, since the same force jump acts on
//! both; a slider on a spring: its position carries `u T` more), and the
//! fixed point's residual `r`, are carried to every coordinate by its row
//! of `G = (I - J)^(-1)`: `|dz_i| <= sum_j |G_ij| (delta_j + r_j)`
//! ([`fixed_point_errors`]). The boundary velocity's, the last row, is
//! [`crate::analysis::SteadyState::boundary_bound`]; a spring's reading
//! takes them all (`spring_error.rs`).

use crate::actuator::DrivenRod;
use crate::analysis::error_estimate::rounding_velocity_of;
use crate::analysis::{Attracted, StatsObserver, StatsWanted};
use crate::engine::{DrivenState, EventCounts, PeriodEnd, PeriodEngine, PeriodStart};
use crate::error::SimulationError;
use crate::motor::Motor;
use crate::observer::Trajectory;
use crate::signal::Signal;
use nalgebra::{DMatrix, DVector};
use std::collections::VecDeque;

/// Periods with the same event counts before Newton is tried.
const STABLE: u32 = 8;

/// Newton iterations at most.
const NEWTON: u32 = 16;

/// Largest window `m` of the attraction test (periods).
const WINDOW: usize = 4096;

/// Scaled deviation below which the start-up is at the fixed point within
/// rounding.
const AT_FIXED_POINT: f64 = 1e-12;

/// Scaled Newton correction below which it has converged.
const CONVERGED: f64 = 1e-13;

/// A fixed point of the period map of a driven rod.
#[derive(Debug, Clone)]
pub(crate) struct FixedPoint {
    /// The boundary state, with the mode the period ends in.
    pub state: DrivenState,
    /// `dP/dz` there.
    pub jacobian: DMatrix<f64>,
    /// The spectral radius of `dP/dz`.
    pub radius: f64,
    /// Events of the period from it.
    pub events: EventCounts,
    /// `v_inf` of the period from it (m/s).
    pub v_inf: f64,
    /// Newton iterations.
    pub iterations: u32,
    /// The last correction of the slider's velocity (m/s).
    pub last_correction: f64,
    /// `|P(z) - z|` of the last evaluation, componentwise.
    pub residual: DVector<f64>,
    /// The window `m` and `J^m` in scaled coordinates.
    window: usize,
    power: DMatrix<f64>,
    /// `max_(j <= m) ||J^j||`, scaled: how far a deviation may grow on
    /// its way in.
    reach: f64,
}

/// The start-up's test for a driven rod ([`crate::analysis::transient_until`]).
pub(crate) struct Settle<'a> {
    /// The driven rod (its exact Jacobian); `None`: a slider on a spring
    /// against a rod that follows its signal (a Jacobian by differences).
    rod: Option<&'a DrivenRod>,
    motor: &'a Motor,
    period: f64,
    /// `(x, v)` scales: the stroke and the largest rod velocity.
    scale: (f64, f64),
    /// False: the fixed point is found, the start-up is never stopped.
    accept: bool,
    /// Also wait for `p_0.99`.
    startup: bool,
    reached_startup: bool,
    periods: u64,
    stable: u32,
    last_events: Option<EventCounts>,
    next_try: u64,
    /// Deviations of the last periods from the fixed point, scaled.
    deviations: VecDeque<DVector<f64>>,
    /// The fixed point, once found.
    pub fixed: Option<FixedPoint>,
    /// Periods run by Newton.
    pub evaluations: u64,
}

/// The coordinates of the period map: the rod's state and the slider's
/// velocity for a driven rod, the slider's position and velocity for a
/// slider on a spring against a rod that follows the signal (the same at
/// every period start), all four for a driven rod with a spring. The
/// slider's velocity comes last.
pub(super) fn vector(z: &DrivenState, driven: bool) -> DVector<f64> {
    match (z.slider, driven) {
        (Some(p), false) => DVector::from_vec(vec![p.x, z.slider_v]),
        (Some(p), true) => DVector::from_vec(vec![z.rod_x, z.rod_v, p.x, z.slider_v]),
        (None, _) => DVector::from_vec(vec![z.rod_x, z.rod_v, z.slider_v]),
    }
}

/// `z` with its coordinates set to `c` ([`vector`]) and its mode `mode`.
pub(super) fn with_coordinates(
    z: &DrivenState,
    c: &DVector<f64>,
    mode: crate::engine::Mode,
    driven: bool,
) -> DrivenState {
    match (z.slider, driven) {
        (Some(p), false) => DrivenState {
            slider_v: c[1],
            mode,
            slider: Some(crate::engine::SliderState { x: c[0], ..p }),
            ..*z
        },
        (Some(p), true) => DrivenState {
            rod_x: c[0],
            rod_v: c[1],
            slider_v: c[3],
            mode,
            slider: Some(crate::engine::SliderState { x: c[2], ..p }),
        },
        (None, _) => DrivenState {
            rod_x: c[0],
            rod_v: c[1],
            slider_v: c[2],
            mode,
            ..*z
        },
    }
}

/// The scales of `z`'s coordinates ([`vector`]) from the `(x, v)` scales:
/// the stroke and the largest rod velocity.
pub(super) fn coordinate_scales(z: &DrivenState, driven: bool, (x, v): (f64, f64)) -> DVector<f64> {
    match (z.slider, driven) {
        (Some(_), false) => DVector::from_vec(vec![x, v]),
        (Some(_), true) => DVector::from_vec(vec![x, v, x, v]),
        (None, _) => DVector::from_vec(vec![x, v, v]),
    }
}

/// The engine's errors of one period in each coordinate of `z`
/// ([`vector`]; module docs, "The fixed point's error"): `delta`, from
/// the velocity bound `u` of a period with `events` events, for the
/// driven rod `rod` (`None`: a prescribed rod) under `motor`.
pub(super) fn period_errors(
    (rod, motor): (Option<&DrivenRod>, &Motor),
    z: &DrivenState,
    signal: &Signal,
    u: f64,
    events: u64,
) -> DVector<f64> {
    let rounding_v = rounding_velocity_of(signal, events);
    let rounding_x = 8.0 * f64::EPSILON * (events as f64 + 2.0) * signal.position_scale();
    // A slider on a spring: its position carries the velocity error over
    // the period at most.
    let slider_x = rounding_x + u * signal.period();
    match (rod, z.slider.is_some()) {
        // The rod gets the share m_s / M of the slider's velocity error.
        (Some(rod), spring) => {
            let share = motor.params().slider_mass / rod.real().mass;
            let rod_part = [rounding_x, rounding_v + share * u];
            let slider_part = if spring {
                vec![slider_x, rounding_v + u]
            } else {
                vec![rounding_v + u]
            };
            let n = rod_part.len() + slider_part.len();
            DVector::from_iterator(n, rod_part.into_iter().chain(slider_part))
        }
        (None, _) => DVector::from_vec(vec![slider_x, rounding_v + u]),
    }
}

/// A bound on each coordinate of the fixed point `f`'s error from the
/// engine's errors of one period `delta` and the residual `r` it carries:
/// `|dz_i| <= sum_j |G_ij| (delta_j + r_j)`, `G = (I - J)^(-1)`;
/// infinite where `I - J` is singular.
pub(super) fn fixed_point_errors(f: &FixedPoint, delta: &DVector<f64>) -> DVector<f64> {
    let n = f.jacobian.nrows();
    let Some(g) = (DMatrix::identity(n, n) - &f.jacobian).try_inverse() else {
        return DVector::from_element(n, f64::INFINITY);
    };
    let carried = delta + &f.residual;
    DVector::from_fn(n, |i, _| {
        (0..n).map(|j| g[(i, j)].abs() * carried[j]).sum::<f64>()
    })
}

impl<'a> Settle<'a> {
    /// The test for `rod` under `motor` with `signal`'s scales; `accept`
    /// false only finds the fixed point; `startup`: the start-up also runs
    /// to `p_0.99`.
    pub(super) fn new(
        rod: Option<&'a DrivenRod>,
        motor: &'a Motor,
        signal: &Signal,
        accept: bool,
        startup: bool,
    ) -> Self {
        let v = signal.velocity_scale().max(f64::MIN_POSITIVE);
        let x = signal.position_scale().max(f64::MIN_POSITIVE);
        Self {
            rod,
            motor,
            period: signal.period(),
            scale: (x, v),
            accept,
            startup,
            reached_startup: false,
            periods: 0,
            stable: 0,
            last_events: None,
            next_try: 0,
            deviations: VecDeque::new(),
            fixed: None,
            evaluations: 0,
        }
    }

    /// The scales of `z`'s coordinates ([`vector`]).
    fn scales(&self, z: &DrivenState) -> DVector<f64> {
        coordinate_scales(z, self.rod.is_some(), self.scale)
    }

    /// [`vector`] of `z` for this test's rod.
    fn vector(&self, z: &DrivenState) -> DVector<f64> {
        vector(z, self.rod.is_some())
    }

    /// [`with_coordinates`] for this test's rod.
    fn with_coordinates(
        &self,
        z: &DrivenState,
        c: &DVector<f64>,
        mode: crate::engine::Mode,
    ) -> DrivenState {
        with_coordinates(z, c, mode, self.rod.is_some())
    }

    /// After period `end` of the start-up with `events`: whether it has
    /// entered the fixed point's attraction (module docs).
    pub(super) fn after_period<E: PeriodEngine>(
        &mut self,
        engine: &mut E,
        end: &PeriodEnd,
        events: &EventCounts,
    ) -> Result<Option<Attracted>, SimulationError> {
        self.periods += 1;
        let Some(z) = engine.boundary_state() else {
            return Ok(None);
        };
        self.stable = if self.last_events == Some(*events) {
            self.stable + 1
        } else {
            0
        };
        self.last_events = Some(*events);
        if self.fixed.is_none() && self.stable >= STABLE && self.periods >= self.next_try {
            self.fixed = self.newton(engine, z)?;
            engine.restart_from(z);
            if self.fixed.is_none() {
                self.next_try = 2 * self.periods;
            }
        }
        let Some(f) = &self.fixed else {
            return Ok(None);
        };
        let v_p = end.step / self.period;
        if f.v_inf != 0.0 && (v_p / f.v_inf) >= 0.99 {
            self.reached_startup = true;
        }
        if *events != f.events || z.mode != f.state.mode {
            self.deviations.clear();
            return Ok(None);
        }
        let e = (self.vector(&z) - self.vector(&f.state)).component_div(&self.scales(&z));
        self.deviations.push_back(e.clone());
        if self.deviations.len() > f.window + 1 {
            self.deviations.pop_front();
        }
        if !self.accept || (self.startup && !self.reached_startup && f.v_inf != 0.0) {
            return Ok(None);
        }
        let at = e.norm() <= AT_FIXED_POINT;
        let attracted = self.deviations.len() == f.window + 1 && {
            let first = &self.deviations[0];
            (&e - &f.power * first).norm() <= 0.25 * first.norm() + AT_FIXED_POINT
        };
        if !(at || attracted) {
            return Ok(None);
        }
        Ok(Some(Attracted {
            remaining: f.reach * e.norm() * self.scale.1,
            v_inf_error: (v_p - f.v_inf).abs(),
        }))
    }

    /// Newton on the period map from `z` (module docs); `None` where it
    /// does not converge, a period holds a grazing, or the fixed point is
    /// not attracting.
    fn newton<E: PeriodEngine>(
        &mut self,
        engine: &mut E,
        mut z: DrivenState,
    ) -> Result<Option<FixedPoint>, SimulationError> {
        let scales = self.scales(&z);
        let n = scales.len();
        for iteration in 1..=NEWTON {
            let Some((p, events, step, segments)) = self.period_from(engine, z)? else {
                return Ok(None);
            };
            // The exact Jacobian of a driven rod's period; with a spring,
            // differences.
            let exact = self.rod.filter(|_| z.slider.is_none());
            let jacobian = match exact {
                Some(rod) => match crate::sensitivity::period_map_jacobian(
                    rod,
                    self.motor,
                    self.period,
                    &segments,
                ) {
                    Ok(j) => DMatrix::from_fn(3, 3, |r, c| j[(r, c)]),
                    Err(_) => return Ok(None),
                },
                None => match self.differences(engine, &z, &scales, events)? {
                    Some(j) => j,
                    None => return Ok(None),
                },
            };
            let residual = self.vector(&p) - self.vector(&z);
            let Some(dz) = (DMatrix::identity(n, n) - &jacobian).lu().solve(&residual) else {
                return Ok(None);
            };
            if !dz.iter().all(|d| d.is_finite()) {
                return Ok(None);
            }
            let correction = dz.component_div(&scales).norm();
            z = self.with_coordinates(&p, &(self.vector(&z) + &dz), p.mode);
            if correction <= CONVERGED {
                return Ok(self.attracting(FixedPoint {
                    state: z,
                    jacobian,
                    radius: 0.0,
                    events,
                    v_inf: step / self.period,
                    iterations: iteration,
                    last_correction: dz[n - 1].abs(),
                    residual: residual.abs(),
                    window: 0,
                    power: DMatrix::identity(n, n),
                    reach: 1.0,
                }));
            }
        }
        Ok(None)
    }

    /// One period of the engine from `z`: the state it ends in, its
    /// events, the slider's step and its segments.
    #[allow(clippy::type_complexity)]
    fn period_from<E: PeriodEngine>(
        &mut self,
        engine: &mut E,
        z: DrivenState,
    ) -> Result<Option<(DrivenState, EventCounts, f64, Vec<crate::engine::Segment>)>, SimulationError>
    {
        engine.restart_from(z);
        let mut stats = StatsObserver::for_engine(&*engine, StatsWanted::default());
        let mut recorded = Trajectory::default();
        let end = engine.run_period(
            2,
            PeriodStart {
                velocity: z.slider_v,
                mode: Some(z.mode),
            },
            &mut (&mut stats, &mut recorded),
        )?;
        self.evaluations += 1;
        Ok(engine
            .boundary_state()
            .map(|p| (p, stats.last.events, end.step, recorded.segments)))
    }

    /// `dP/dz` by central differences of the engine's periods, steps of
    /// `1e-7` of the scales; `None` where a step changes the period's event
    /// counts (the map is not smooth across them).
    fn differences<E: PeriodEngine>(
        &mut self,
        engine: &mut E,
        z: &DrivenState,
        scales: &DVector<f64>,
        events: EventCounts,
    ) -> Result<Option<DMatrix<f64>>, SimulationError> {
        let n = scales.len();
        let c = self.vector(z);
        let mut jacobian = DMatrix::zeros(n, n);
        for j in 0..n {
            let h = 1e-7 * scales[j];
            let mut ends = Vec::with_capacity(2);
            for sign in [1.0, -1.0] {
                let mut shifted = c.clone();
                shifted[j] += sign * h;
                let Some((p, e, ..)) =
                    self.period_from(engine, self.with_coordinates(z, &shifted, z.mode))?
                else {
                    return Ok(None);
                };
                if e != events || p.mode != z.mode {
                    return Ok(None);
                }
                ends.push(self.vector(&p));
            }
            let column = (&ends[0] - &ends[1]) / (2.0 * h);
            jacobian.set_column(j, &column);
        }
        Ok(Some(jacobian))
    }

    /// `f` with its spectral radius and window, if it attracts: the
    /// spectral radius below 1 and `||J^m|| <= 1/2` for some `m <=`
    /// [`WINDOW`].
    fn attracting(&self, mut f: FixedPoint) -> Option<FixedPoint> {
        let scales = self.scales(&f.state);
        let n = scales.len();
        let scaled = DMatrix::from_fn(n, n, |r, c| f.jacobian[(r, c)] * scales[c] / scales[r]);
        f.radius = crate::numerics::spectral::spectral_radius(&scaled)?;
        if f.radius >= 1.0 {
            return None;
        }
        let mut power = DMatrix::identity(n, n);
        for m in 1..=WINDOW {
            power = &scaled * power;
            let norm = power.norm();
            f.reach = f.reach.max(norm);
            if norm <= 0.5 {
                f.window = m;
                f.power = power;
                return Some(f);
            }
        }
        None
    }

    /// The bound on the fixed point's boundary velocity (module docs, "The
    /// fixed point's error"), with `u` the engine's velocity bound of the
    /// steady period and `events` its events: the last coordinate of
    /// [`fixed_point_errors`].
    pub(super) fn boundary_bound(
        &self,
        f: &FixedPoint,
        signal: &Signal,
        u: f64,
        events: u64,
    ) -> f64 {
        let delta = period_errors((self.rod, self.motor), &f.state, signal, u, events);
        let dz = fixed_point_errors(f, &delta);
        dz[dz.len() - 1]
    }
}
