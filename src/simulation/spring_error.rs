//! The error of a spring's reading over a steady orbit (docs/model.md
//! section 17, "The reading's error"): every figure `R` (the force's mean,
//! largest and least value, the position's mean, the contact fraction) is
//! reported with an estimate that is the sum of four parts.
//!
//! * **The boundary state.** The orbit starts from a boundary state `z`
//!   (the coordinates of the period map: `(x_S, v_S)`, with a driven rod
//!   `(x_R, v_R, x_S, v_S)`) known within `dz_j` in each coordinate. The
//!   engine's errors of one period `delta` (`driven.rs`: rounding, and
//!   the velocity bound `u` of the events' times and decisions) and the
//!   residuals `r` are carried through every row of `G = (I - J)^(-1)`,
//!   `dz_i = sum_j |G_ij| (delta_j + r_j)`:
//!   - from Newton's fixed point, with its Jacobian `J` of one period and
//!     its residual; the periods the engine ran from the fixed point to
//!     the orbit's start add the distance they moved the state (measured);
//!   - from an exact repetition of the start-up (an orbit of `k` periods,
//!     no Newton), with the Jacobian of the orbit's `k`-period map from
//!     the differences below (their end states), `k delta` for its
//!     periods' errors; none where a difference changes the event
//!     structure or its spectral radius is not below 1.
//!
//!   `r` also holds the orbit's own closure `|P^k(z) - z|`, and the
//!   engine's errors over the orbit's `k` periods add `k delta` (a state
//!   error made inside the orbit counted as one at its start: first
//!   order). The reading's sensitivity to `z` comes from central
//!   differences of whole orbits from `z ± h_j e_j` (steps
//!   `h_j = 1e-7` of the scales, as Newton's Jacobian; `2n` orbits):
//!   `(R(z + h_j e_j) - R(z - h_j e_j)) / 2h_j` where both keep the
//!   orbit's event structure (its events' kinds in order and the mode it
//!   ends in), else the larger one-sided slope. The part is
//!   `2 sum_j |dR/dz_j| dz_j`: the first-order change, doubled for the
//!   terms it leaves out (the second order, the differences' own error,
//!   the errors inside the orbit taken as errors of its start).
//! * **The quadrature** of the means: the Gauss-Legendre sums against the
//!   same sums on pieces halved (`spring_profile.rs`).
//! * **Rounding**: a few `eps` of the magnitudes of the terms summed
//!   (`spring_profile.rs`).
//! * **Event times**: the largest or least value where it lies at an event
//!   moves with the event's time error `dt` at the force's rate there; the
//!   contact fraction by `dt` per contact made or lost, over `kT`.
//!
//! No bound holds through a grazing (the engine's velocity bound is
//! infinite), and none is invented where no orbit locked (the range of a
//! single period's mean is what the run knows there).

use super::driven::{
    FixedPoint, coordinate_scales, fixed_point_errors, period_errors, vector, with_coordinates,
};
use super::spring_reading::{OrbitRun, run_orbit};
use crate::actuator::DrivenRod;
use crate::engine::{PeriodEngine, SpringProfile};
use crate::error::Error;
use crate::motor::Motor;
use crate::signal::Signal;
use nalgebra::{DMatrix, DVector};

/// One figure's error estimate by source (in the figure's unit).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReadingErrorParts {
    /// The orbit's boundary state: twice the first-order change
    /// `sum_j |dR/dz_j| dz_j`.
    pub boundary_state: f64,
    /// The quadrature of a mean: `|Q_p - Q_2p| / kT`.
    pub quadrature: f64,
    /// Rounding.
    pub rounding: f64,
    /// Event times: a largest or least value at an event, the contact
    /// fraction's contacts made or lost.
    pub event_times: f64,
}

impl ReadingErrorParts {
    /// The estimate: the sum of the parts.
    pub fn total(&self) -> f64 {
        self.boundary_state + self.quadrature + self.rounding + self.event_times
    }
}

/// The error estimate of a spring's reading over a steady orbit, figure
/// by figure (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpringReadingError {
    /// Of `spring_force_mean` (N).
    pub force_mean: ReadingErrorParts,
    /// Of `spring_force_max` (N).
    pub force_max: ReadingErrorParts,
    /// Of `spring_force_min` (N).
    pub force_min: ReadingErrorParts,
    /// Of `spring_position_mean` (m).
    pub position_mean: ReadingErrorParts,
    /// Of `contact_fraction`.
    pub contact_fraction: ReadingErrorParts,
}

impl SpringReadingError {
    /// The parts of each figure, in the order `spring_force_mean`,
    /// `spring_force_max`, `spring_force_min`, `spring_position_mean`,
    /// `contact_fraction`.
    pub fn figures(&self) -> [ReadingErrorParts; 5] {
        [
            self.force_mean,
            self.force_max,
            self.force_min,
            self.position_mean,
            self.contact_fraction,
        ]
    }
}

/// Where the orbit's boundary state came from.
pub(super) enum Boundary<'a> {
    /// Newton's fixed point of the period map.
    Newton(&'a FixedPoint),
    /// An exact repetition of the start-up.
    Repetition,
}

/// The reading's figures, in [`SpringReadingError::figures`]' order.
fn figures(p: &SpringProfile) -> [f64; 5] {
    [
        p.force_mean,
        p.force_max,
        p.force_min,
        p.position_mean,
        p.contact_fraction,
    ]
}

/// Relative step of the differences (of the coordinates' scales).
const STEP: f64 = 1e-7;

/// The error estimate of the reading over `orbit` (module docs), whose
/// boundary state came from `boundary`; `rod` and `motor` as the period
/// map's ([`super::driven`]). `None` where no bound holds. Also the
/// periods the differences ran.
pub(super) fn reading_error<E: PeriodEngine>(
    engine: &mut E,
    orbit: &OrbitRun,
    boundary: Boundary,
    (rod, motor): (Option<&DrivenRod>, &Motor),
    signal: &Signal,
) -> Result<(Option<SpringReadingError>, u64), Error> {
    let u = orbit.velocity_uncertainty;
    if !u.is_finite() {
        return Ok((None, 0));
    }
    let driven = rod.is_some();
    let z = vector(&orbit.start, driven);
    let evaluations = 2 * z.len() as u64 * orbit.periods;
    let delta = period_errors((rod, motor), &orbit.start, signal, u, orbit.events);
    let closure = (vector(&orbit.end, driven) - &z).abs();
    let k = orbit.periods as f64;
    let differences = differences(engine, orbit, driven, signal)?;
    // Leave the engine where the orbit ended.
    engine.restart_from(orbit.end);
    let Some(Differences { slopes, jacobian }) = differences else {
        return Ok((None, evaluations));
    };
    let dz = match boundary {
        // The periods from the fixed point to the orbit's start moved the
        // state by what they measured.
        Boundary::Newton(f) => {
            fixed_point_errors(f, &(&delta + &closure)) + (&z - vector(&f.state, driven)).abs()
        }
        // The k-period map's fixed point, as Newton's, with the engine's
        // errors of k periods.
        Boundary::Repetition => {
            match jacobian.and_then(|j| repetition_errors(&j, &(&delta * k + &closure))) {
                Some(dz) => dz,
                None => return Ok((None, evaluations)),
            }
        }
    };
    // The engine's own errors over the orbit's periods.
    let dz = dz + &delta * k;
    if !dz.iter().all(|d| d.is_finite()) {
        return Ok((None, evaluations));
    }
    let boundary_state = |i: usize| {
        2.0 * slopes
            .iter()
            .zip(dz.iter())
            .map(|(s, d)| s[i].abs() * d)
            .sum::<f64>()
    };
    let b = &orbit.profile.bounds;
    let dt = orbit.event_time_uncertainty;
    let duration = signal.period() * k;
    let part = |i: usize, quadrature: f64, event_times: f64| ReadingErrorParts {
        boundary_state: boundary_state(i),
        quadrature,
        rounding: b.rounding[i],
        event_times,
    };
    let error = SpringReadingError {
        force_mean: part(0, b.quadrature[0], 0.0),
        force_max: part(1, 0.0, dt * b.extreme_rates[0]),
        force_min: part(2, 0.0, dt * b.extreme_rates[1]),
        position_mean: part(3, b.quadrature[1], 0.0),
        contact_fraction: part(4, 0.0, dt * b.contact_changes as f64 / duration),
    };
    let finite = error.figures().iter().all(|p| p.total().is_finite());
    Ok((finite.then_some(error), evaluations))
}

/// `|dz_i| <= sum_j |G_ij| carried_j` with `G = (I - J)^(-1)` for the
/// orbit's map `J` (a repetition's `k`-period map); `None` where its
/// spectral radius is not below 1 (no contraction to carry errors by).
fn repetition_errors(jacobian: &DMatrix<f64>, carried: &DVector<f64>) -> Option<DVector<f64>> {
    let n = jacobian.nrows();
    let radius = crate::numerics::spectral::spectral_radius(jacobian)?;
    if radius >= 1.0 {
        return None;
    }
    let g = (DMatrix::identity(n, n) - jacobian).try_inverse()?;
    Some(DVector::from_fn(n, |i, _| {
        (0..n).map(|j| g[(i, j)].abs() * carried[j]).sum::<f64>()
    }))
}

/// The central differences of whole orbits from the boundary state.
struct Differences {
    /// `dR/dz_j` of every figure, for each coordinate `j`.
    slopes: Vec<[f64; 5]>,
    /// The orbit's map `dP^k/dz`, where every difference kept the orbit's
    /// event structure.
    jacobian: Option<DMatrix<f64>>,
}

/// [`Differences`] of the orbit's reading and end state for each
/// coordinate `j` of its boundary state (module docs); `None` where an
/// orbit of the differences has no reading.
fn differences<E: PeriodEngine>(
    engine: &mut E,
    orbit: &OrbitRun,
    driven: bool,
    signal: &Signal,
) -> Result<Option<Differences>, Error> {
    let start = &orbit.start;
    let z = vector(start, driven);
    let n = z.len();
    let scale = (
        signal.position_scale().max(f64::MIN_POSITIVE),
        signal.velocity_scale().max(f64::MIN_POSITIVE),
    );
    let scales = coordinate_scales(start, driven, scale);
    let here = figures(&orbit.profile);
    let mut slopes = Vec::with_capacity(n);
    let mut jacobian = Some(DMatrix::zeros(n, n));
    for j in 0..n {
        let h = STEP * scales[j];
        let mut sides = Vec::with_capacity(2);
        for sign in [1.0, -1.0] {
            let mut shifted = z.clone();
            shifted[j] += sign * h;
            let from = with_coordinates(start, &shifted, start.mode, driven);
            let Some(run) = run_orbit(engine, from, orbit.periods)? else {
                return Ok(None);
            };
            let held = run.kinds == orbit.kinds && run.end.mode == orbit.end.mode;
            sides.push((figures(&run.profile), vector(&run.end, driven), held));
        }
        let (plus, minus) = (&sides[0], &sides[1]);
        let held = plus.2 && minus.2;
        slopes.push(std::array::from_fn(|i| {
            if held {
                (plus.0[i] - minus.0[i]) / (2.0 * h)
            } else {
                (plus.0[i] - here[i])
                    .abs()
                    .max((here[i] - minus.0[i]).abs())
                    / h
            }
        }));
        jacobian = jacobian.filter(|_| held).map(|mut m| {
            m.set_column(j, &((&plus.1 - &minus.1) / (2.0 * h)));
            m
        });
    }
    Ok(Some(Differences { slopes, jacobian }))
}
