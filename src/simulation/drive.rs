//! The driver of a simulation (the procedure of the module docs of
//! [`crate::simulation`]): the fixed point, the start-up when an indicator
//! needs it, the check that the two agree, and the error estimates.

use super::certified::{Search, bracketed_v_inf, certified_limit, covering_search};
use super::driven::{FixedPoint, Settle};
use super::spring_error::{Boundary, reading_error};
use super::spring_reading::{orbit_periods, orbit_reading, unlocked_reading};
use super::{
    CertificateKind, Outcome, RunReport, SteadyStateCertificate, SteadyStateCheck, Unsettled,
};
use crate::actuator::DrivenRod;
use crate::analysis::certificate::CERTIFIED_REACH;
use crate::analysis::error_estimate::{
    established_bound, estimate_errors, startup_error, v_inf_error,
};
use crate::analysis::{self, AnalysisOptions, Convergence, StatsWanted, SteadyState, Transient};
use crate::engine::Direction;
use crate::engine::{Event, PeriodEngine, PeriodStart};
use crate::error::{Error, SimulationError};
use crate::indicator::Indicator;
use crate::motor::Motor;
use crate::observer::{EventLog, Trajectory};
use crate::power::{self};
use crate::scene::Scene;
use crate::signal::Signal;
use std::time::{Duration, Instant};

/// True if the orbit from rest, up to period `periods`, went past the fixed
/// point `v_star` (beyond its bound) in the direction it moves: then the
/// fixed point is not the limit (see the module docs, 2.).
fn orbit_passes(transient: &Transient, periods: u64, v_star: f64, bound: f64) -> bool {
    let seen = &transient.boundary_velocities
        [..(periods as usize).min(transient.boundary_velocities.len())];
    if v_star >= 0.0 {
        seen.iter().any(|u| *u > v_star + bound)
    } else {
        seen.iter().any(|u| *u < v_star - bound)
    }
}

/// The simulation of `scene` on `engine`; `rod` is the driven rod of an
/// engine whose period map acts on the rod's state as well
/// ([`PeriodEngine::boundary_state`]): its fixed point is then found by
/// Newton ([`super::driven`]).
pub(super) fn simulate_timed<E: PeriodEngine>(
    engine: E,
    scene: &Scene,
    motor: &Motor,
    rod: Option<&DrivenRod>,
    setup_clock: Instant,
) -> Result<Outcome, Error> {
    let setup_time = setup_clock.elapsed();
    let clock = Instant::now();
    let mut engine = crate::simulation::budget::TimeBudget::new(engine, scene.run.time_limit_s);
    let requested = scene.outputs.indicators.clone();
    let wants = |i: Indicator| requested.contains(&i);
    let signal = engine.signal().clone();
    let period = signal.period();
    let wanted = StatsWanted {
        smoothness: wants(Indicator::Smoothness),
        sliding: wants(Indicator::Durability) || wants(Indicator::FrictionEnergy),
        stiction: wants(Indicator::StictionFraction),
        slip_time: false,
    };
    let mut trajectory = scene.outputs.trajectory.then(Trajectory::default);
    let mut event_log = scene.outputs.events.then(EventLog::default);
    let mut options = AnalysisOptions {
        max_periods: scene.run.max_periods,
        ..Default::default()
    };
    let verify = scene.run.verify_steady_state;
    // The start-up from rest is simulated only for what needs it: the
    // start-up time, the start-up's stiction fraction, its event log and
    // the cross-check of verify_steady_state (module docs, "Only what the
    // scene asks for").
    let needs_startup = verify
        || wants(Indicator::StartupTime)
        || wants(Indicator::StictionFraction)
        || scene.outputs.events;
    // Periods run from chosen velocities: the fixed-point searches, the
    // covering of the certificate and the steady-state periods.
    let mut map_evaluations = 0;
    let mut certificate = SteadyStateCertificate {
        kind: CertificateKind::Orbit,
        evaluations: 0,
        other_fixed_point: None,
    };
    // Fast path: the period map's fixed point from rest (the first period
    // from rest moves the slider exactly as the map does from v = 0), used
    // only when established and certified as the limit of the motion from
    // rest: from rest, or from the start-up's last point when the start-up
    // is simulated up to p_0.99 (on to convergence with
    // verify_steady_state). See the module docs.
    let mut rest_fixed_point = None;
    // The covering's bounds on the certified limit's v_inf.
    let mut v_inf_bounds = None;
    // An engine that carries the rod's state has no period map of the
    // slider velocity alone: the motion from rest decides.
    let rod_state = engine.carries_rod_state();
    let fast = if engine.steady_state_from_transient() || rod_state {
        None
    } else {
        let before = engine.counters().periods;
        let found = match analysis::steady_state(&mut engine, 0.0, wanted, &mut trajectory) {
            Ok(steady) => Some((steady, 0.0)),
            Err(SimulationError::NoSteadyState { direction, .. }) => {
                let growing = direction == "growing";
                match covering_search(&mut engine, motor, growing, wanted, &mut trajectory)? {
                    Search::Found(steady, free_to, evaluations) => {
                        certificate.evaluations += evaluations;
                        Some((steady, free_to))
                    }
                    Search::RunAway(final_velocity, evaluations) if !needs_startup => {
                        let state = Unsettled {
                            period: signal.period(),
                            f_max: signal.f_max(),
                            requested: requested.to_vec(),
                            periods_simulated: 0,
                            last_v_p: None,
                            final_velocity,
                            v_inf_bounds: (None, None),
                            work: engine.counters(),
                            certificate_evaluations: Some(evaluations),
                            setup_time,
                            simulation_time: clock.elapsed(),
                            wall_time: setup_time + clock.elapsed(),
                            spring: None,
                        };
                        let direction = if growing {
                            Direction::Forward
                        } else {
                            Direction::Backward
                        };
                        return Ok(Outcome::RunAway { direction, state });
                    }
                    Search::RunAway(..) | Search::Nothing => None,
                }
            }
            Err(_) => None,
        };
        map_evaluations += engine.counters().periods - before;
        let established = found.and_then(|(steady, free_to)| {
            established_bound(&signal, &steady).map(|b| (steady, b, free_to))
        });
        match established {
            Some((steady, bound, free_to)) if !needs_startup => {
                rest_fixed_point = Some((steady.boundary_velocity, steady.v_inf));
                let before = engine.counters().periods;
                let certified = certified_limit(
                    &mut engine,
                    motor,
                    free_to,
                    (steady, bound),
                    wanted,
                    &mut trajectory,
                    &mut certificate,
                )?;
                map_evaluations += engine.counters().periods - before;
                certified.map(|(steady, bounds)| {
                    v_inf_bounds = Some(bounds);
                    (steady, None)
                })
            }
            Some((steady, bound, _)) => {
                rest_fixed_point = Some((steady.boundary_velocity, steady.v_inf));
                // p_0.99 exists only where |v_inf| exceeds its error.
                let v_error = v_inf_error(&signal, &steady, bound);
                options.stop_at_startup =
                    (!verify && steady.v_inf.abs() > v_error).then_some(steady.v_inf);
                // The cross-check's own limit rests on a repetition, not on
                // an extrapolation.
                options.ratio_rule = !verify;
                let transient = analysis::transient(&mut engine, &options, wanted, &mut event_log)?;
                // Judge on what a run without verification sees: the
                // periods up to p_0.99.
                let seen = transient
                    .startup_periods(steady.v_inf)
                    .unwrap_or(transient.periods());
                let settled_elsewhere = transient.converged
                    && transient.periods() <= seen
                    && (transient.v_inf() - steady.v_inf).abs()
                        > bound + transient.v_inf_error.unwrap_or(0.0);
                let passes = orbit_passes(&transient, seen, steady.boundary_velocity, bound);
                // The orbit covers what lies behind its last point; the
                // covering goes on from there.
                let last = transient
                    .boundary_velocities
                    .get((seen as usize).saturating_sub(1))
                    .or(transient.boundary_velocities.last())
                    .copied()
                    .unwrap_or(0.0);
                if transient.run_away.is_some() {
                    Some((steady, Some(transient)))
                } else if settled_elsewhere || passes {
                    None
                } else {
                    let before = engine.counters().periods;
                    let certified = certified_limit(
                        &mut engine,
                        motor,
                        last,
                        (steady, bound),
                        wanted,
                        &mut trajectory,
                        &mut certificate,
                    )?;
                    map_evaluations += engine.counters().periods - before;
                    certified.map(|(steady, bounds)| {
                        v_inf_bounds = Some(bounds);
                        (steady, Some(transient))
                    })
                }
            }
            None => None,
        }
    };
    let from_orbit = fast.is_none();
    let mut newton = false;
    // Newton's fixed point: a spring's reading carries its error.
    let mut newton_fixed: Option<FixedPoint> = None;
    let (steady, transient) = match fast {
        Some(found) => found,
        None => {
            // The orbit from rest decides. A limit the contraction ratios
            // extrapolated is taken only where the covering certifies it
            // from the orbit's last point; otherwise the start-up runs on,
            // from rest, until its boundary state repeats.
            options.stop_at_startup = None;
            let mut settled = None;
            let rules: &[bool] = if rod_state {
                &[false]
            } else {
                &[!verify, false]
            };
            for &ratio_rule in rules {
                options.ratio_rule = ratio_rule;
                event_log = scene.outputs.events.then(EventLog::default);
                trajectory = scene.outputs.trajectory.then(Trajectory::default);
                // Newton on the period map where the engine can start a
                // period from any boundary state: a driven rod, or a slider
                // on a spring.
                let mut settle = (rod.is_some() || scene.spring.is_some())
                    .then(|| Settle::new(rod, motor, &signal, !verify, needs_startup));
                let transient = match settle.as_mut() {
                    Some(settle) => analysis::transient_until(
                        &mut engine,
                        &options,
                        wanted,
                        &mut event_log,
                        |engine, end, events| settle.after_period(engine, end, events),
                    )?,
                    None => analysis::transient(&mut engine, &options, wanted, &mut event_log)?,
                };
                if transient.run_away.is_some() || !transient.converged {
                    // A slider on a spring that did not lock: what the
                    // spring reads over the periods that follow.
                    let reading = if transient.run_away.is_none() && scene.spring.is_some() {
                        unlocked_reading(&mut engine, transient.periods())?
                    } else {
                        None
                    };
                    let mut outcome = unsettled(
                        &engine,
                        &signal,
                        &requested,
                        &transient,
                        rest_fixed_point,
                        (setup_time, clock.elapsed()),
                    );
                    if let Outcome::NotConverged(state) = &mut outcome {
                        state.spring = reading;
                    }
                    return Ok(outcome);
                }
                if let Some(settle) = &settle {
                    map_evaluations += settle.evaluations;
                }
                if let Some((settle, fixed)) = settle
                    .as_ref()
                    .and_then(|s| s.fixed.as_ref().map(|f| (s, f)))
                    && (transient.converged_by == Some(Convergence::Attracted) || verify)
                {
                    // The fixed point Newton found, which the start-up
                    // entered the attraction of (or, verifying, which the
                    // start-up ran on to its own limit beside).
                    let before = engine.counters().periods;
                    newton_fixed = Some(fixed.clone());
                    engine.restart_from(fixed.state);
                    let mut steady = analysis::steady_state_at(
                        &mut engine,
                        PeriodStart {
                            velocity: fixed.state.slider_v,
                            mode: Some(fixed.state.mode),
                        },
                        (Some(fixed.radius), fixed.iterations, fixed.last_correction),
                        wanted,
                        &mut trajectory,
                    )?;
                    map_evaluations += engine.counters().periods - before;
                    steady.boundary_bound = steady.velocity_uncertainty.map(|u| {
                        settle.boundary_bound(fixed, &signal, u, steady.stats.events.total())
                    });
                    if transient.converged_by == Some(Convergence::Attracted) {
                        certificate.kind = CertificateKind::Attracted;
                    }
                    newton = true;
                    settled = Some((steady, Some(transient)));
                    break;
                }
                let before = engine.counters().periods;
                let mut steady = orbit_steady(&mut engine, &transient, wanted, &mut trajectory)?;
                map_evaluations += engine.counters().periods - before;
                if rod_state {
                    // No derivative of a one-dimensional map: the contraction
                    // the start-up showed stands in for it in the error
                    // estimate.
                    steady.map_derivative = measured_contraction(
                        &transient.boundary_velocities,
                        signal.velocity_scale(),
                    );
                }
                if transient.converged_by != Some(Convergence::Ratio) {
                    certificate.kind = CertificateKind::Orbit;
                    settled = Some((steady, Some(transient)));
                    break;
                }
                let Some(bound) = established_bound(&signal, &steady) else {
                    continue;
                };
                let before = engine.counters().periods;
                let certified = certified_limit(
                    &mut engine,
                    motor,
                    transient.final_velocity,
                    (steady, bound),
                    wanted,
                    &mut trajectory,
                    &mut certificate,
                )?;
                map_evaluations += engine.counters().periods - before;
                // The certified orbit must also move the slider as the
                // start-up does: where the fixed point sits on a change of
                // the event structure, the two sides of it differ in v_inf.
                if let Some((steady, bounds)) = certified.filter(|(steady, _)| {
                    (steady.v_inf - transient.v_inf()).abs()
                        <= transient.v_inf_error.unwrap_or(0.0)
                            + v_inf_error(&signal, steady, CERTIFIED_REACH * bound)
                }) {
                    v_inf_bounds = Some(bounds);
                    settled = Some((steady, Some(transient)));
                    break;
                }
            }
            settled.expect("the start-up without the ratio rule converges by repetition")
        }
    };
    if let Some(t) = transient.as_ref().filter(|t| t.run_away.is_some()) {
        return Ok(unsettled(
            &engine,
            &signal,
            &requested,
            t,
            rest_fixed_point,
            (setup_time, clock.elapsed()),
        ));
    }
    // Newton's fixed point is not the start-up's own limit.
    let from_orbit = from_orbit && !newton;
    let indicators = steady.indicators(motor, period);
    let mut error = estimate_errors(
        &signal,
        &steady,
        transient.as_ref(),
        &indicators,
        motor.contact_force(),
        (from_orbit, certificate.kind == CertificateKind::Covering),
    );
    if error.v_inf.is_none() && steady.stats.events.grazing > 0 && !rod_state {
        // A grazing in the steady orbit gives no engine bound; a bracket
        // of the limit from rest by points away from it gives one.
        let before = engine.counters().periods;
        if let Some((lo, hi)) = bracketed_v_inf(&mut engine, motor, &steady, &mut certificate)? {
            let v = indicators.v_inf;
            error.v_inf = Some((v - lo).max(hi - v).max(0.0));
        }
        map_evaluations += engine.counters().periods - before;
    }
    if let (Some((lo, hi)), Some(e)) = (v_inf_bounds, error.v_inf) {
        // The limit's v_inf lies between the covering's ends' (also where
        // it jumps with the boundary velocity); the estimate covers them.
        let v = indicators.v_inf;
        error.v_inf = Some(e.max(v - lo).max(hi - v));
    }
    let startup_periods = transient
        .as_ref()
        .filter(|_| error.v_inf.is_none_or(|e| indicators.v_inf.abs() > e))
        .and_then(|t| t.startup_periods(steady.v_inf));
    error.startup_time = transient
        .as_ref()
        .and_then(|t| startup_error(period, &steady, t, startup_periods, error.v_inf));
    // A driven rod: one more steady period, recorded, gives the rod's
    // deviation and the current the amplifier delivers.
    let drive = if rod_state {
        let mut recorded = Trajectory::default();
        let start = PeriodStart {
            velocity: steady.boundary_velocity,
            mode: None,
        };
        engine.run_period(2, start, &mut recorded)?;
        map_evaluations += 1;
        // A driven rod keeps its period even where the profile is not
        // resolved (its searches spent their budget: model section 16).
        let profile = engine.drive_profile(&recorded.segments);
        let driven = matches!(scene.rod, crate::actuator::RodModel::Driven(_));
        (driven || profile.is_some()).then_some((profile, recorded.segments))
    } else {
        None
    };
    // A spring against the slider: what it reads over the orbit, and the
    // reading's error.
    let spring = if rod_state && engine.boundary_state().is_some_and(|z| z.slider.is_some()) {
        let periods = transient
            .as_ref()
            .map_or(1, |t| orbit_periods(t, signal.velocity_scale()));
        map_evaluations += periods;
        match orbit_reading(&mut engine, periods)? {
            Some(orbit) => {
                let boundary = match &newton_fixed {
                    Some(f) => Boundary::Newton(f),
                    None => Boundary::Repetition,
                };
                let (error, evaluations) =
                    reading_error(&mut engine, &orbit, boundary, (rod, motor), &signal)?;
                map_evaluations += evaluations;
                Some(orbit.reading(error))
            }
            None => None,
        }
    } else {
        None
    };
    let (drive, driven_period) = match drive {
        Some((profile, segments)) => (profile, Some(segments)),
        None => (None, None),
    };
    let power = match (&scene.actuator, &signal) {
        (Some(actuator), Signal::Fourier(s)) if wants(Indicator::VelocityPerPower) => {
            let mut p = power::input_power(s, actuator);
            if let Some(d) = &drive {
                // The voltage is the designed one; the current is the
                // actual rod's (21).
                p.u_rms = d.voltage_rms;
                p.i_rms = d.current_rms;
                p.apparent_power = d.voltage_rms * d.current_rms;
            }
            Some(p)
        }
        _ => None,
    };
    if let Some(p) = &power {
        // S (35) is a closed form of the signal: only v_inf carries error.
        error.velocity_per_power = error.v_inf.map(|dv| dv / p.apparent_power);
    }
    let span = startup_periods.unwrap_or(transient.as_ref().map_or(0, Transient::periods));
    let mut stiction_fraction_transient = None;
    let mut event_log_omitted = 0;
    let mut steady_state_check = None;
    if let Some(transient) = &transient {
        stiction_fraction_transient = (wanted.stiction && span > 0)
            .then(|| transient.stick_time(span) / (span as f64 * period));
        if error.stiction_fraction.is_some() {
            // Every start or end of a stick phase in the start-up may be off
            // by the engine's event-time uncertainty; the sum is rounded per
            // period.
            let e = transient.events(span);
            let transitions = (e.stick_to_slip + e.slip_to_stick + e.jump) as f64;
            error.stiction_fraction = Some(
                16.0 * f64::EPSILON * (e.total() as f64 + 2.0)
                    + transitions * steady.event_time_uncertainty / (span.max(1) as f64 * period),
            );
        }
        steady_state_check = verify.then(|| SteadyStateCheck {
            v_inf_transient: transient.converged.then(|| transient.v_inf()),
            difference: transient
                .converged
                .then(|| transient.v_inf() - indicators.v_inf),
            tolerance: error.v_inf.zip(transient.v_inf_error).map(|(a, b)| a + b),
            periods: transient.periods(),
        });
        // Events of the start-up beyond the log's capacity: counted, not
        // kept.
        if let Some(log) = &event_log {
            let logged = log.events.iter().filter(|e| e.period <= span).count();
            event_log_omitted = transient.events(span).total().saturating_sub(logged as u64);
        }
    }
    let event_log: Option<Vec<Event>> =
        event_log.map(|l| l.events.into_iter().filter(|e| e.period <= span).collect());
    let simulation_time = clock.elapsed();
    Ok(Outcome::Steady(Box::new(RunReport {
        period,
        f_max: signal.f_max(),
        requested,
        indicators,
        startup_periods,
        stiction_fraction_transient,
        power,
        error,
        work: engine.counters(),
        map_evaluations,
        setup_time,
        simulation_time,
        wall_time: setup_time + simulation_time,
        steady_state_check,
        certificate,
        event_log_omitted,
        event_log,
        trajectory: trajectory.map(|t| t.segments),
        transient,
        steady,
        drive,
        driven_period,
        spring,
    })))
}

/// The contraction per period the start-up showed near its limit: the
/// largest ratio of successive changes of the boundary velocity over the
/// last 16 periods whose changes lie well above rounding and below the
/// start-up's large moves (between `1e-12` and `1e-4` of the velocity
/// scale); 1 (no contraction shown, no bound) where there are none.
fn measured_contraction(boundary: &[f64], scale: f64) -> f64 {
    let changes: Vec<f64> = boundary.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    let usable = |c: f64| c > 1e-12 * scale && c < 1e-4 * scale;
    let ratios: Vec<f64> = changes
        .windows(2)
        .filter(|c| usable(c[0]) && usable(c[1]))
        .map(|c| c[1] / c[0])
        .collect();
    let last = &ratios[ratios.len().saturating_sub(16)..];
    if last.is_empty() {
        return 1.0;
    }
    last.iter().copied().fold(0.0, f64::max).min(1.0)
}

/// What is known about a start-up without an established limit: its last
/// `v_p` bounds `v_inf` on the side it came from (the orbit and its `v_p`
/// are monotone), an established fixed point beyond it on the other side.
fn unsettled<E: PeriodEngine>(
    engine: &E,
    signal: &Signal,
    requested: &[Indicator],
    transient: &Transient,
    rest_fixed_point: Option<(f64, f64)>,
    (setup_time, simulation_time): (Duration, Duration),
) -> Outcome {
    let last_v_p = transient.mean_velocities.last().copied();
    let u = transient.final_velocity;
    let beyond = |w: f64| {
        rest_fixed_point
            .filter(|(v, _)| (v - u) * w >= 0.0)
            .map(|(_, m)| m)
    };
    let v_inf_bounds = if u > 0.0 {
        (last_v_p, beyond(1.0))
    } else if u < 0.0 {
        (beyond(-1.0), last_v_p)
    } else {
        (None, None)
    };
    let state = Unsettled {
        period: signal.period(),
        f_max: signal.f_max(),
        requested: requested.to_vec(),
        periods_simulated: transient.periods(),
        last_v_p,
        final_velocity: u,
        v_inf_bounds,
        work: engine.counters(),
        certificate_evaluations: None,
        setup_time,
        simulation_time,
        wall_time: setup_time + simulation_time,
        spring: None,
    };
    match transient.run_away {
        Some(direction) => Outcome::RunAway { direction, state },
        None => Outcome::NotConverged(state),
    }
}

/// The steady state at the limit of a converged start-up: the fixed point
/// searched from its last boundary velocity if it lies within the
/// start-up's own bound, else the last boundary velocity itself.
fn orbit_steady<E: PeriodEngine>(
    engine: &mut E,
    transient: &Transient,
    wanted: StatsWanted,
    trajectory: &mut Option<Trajectory>,
) -> Result<SteadyState, Error> {
    let seed = transient.final_velocity;
    let reach = transient.remaining.unwrap_or(0.0) + transient.v_inf_error.unwrap_or(0.0);
    *trajectory = trajectory.as_ref().map(|_| Trajectory::default());
    // The orbit's own boundary state: the mode it ends a period in is part
    // of it (a map evaluation from the same velocity may decide a
    // zero-velocity start differently).
    let start = |velocity| PeriodStart {
        velocity,
        mode: Some(transient.final_mode),
    };
    if transient.converged_by == Some(Convergence::Exact) || engine.carries_rod_state() {
        return Ok(analysis::steady_state_at(
            engine,
            start(seed),
            (None, 0, 0.0),
            wanted,
            trajectory,
        )?);
    }
    Ok(match analysis::fixed_point(engine, seed) {
        Ok(p) if (p.velocity - seed).abs() <= reach => analysis::steady_state_at(
            engine,
            start(p.velocity),
            (Some(p.map_derivative), p.iterations, p.last_correction),
            wanted,
            trajectory,
        )?,
        _ => analysis::steady_state_at(
            engine,
            start(seed),
            (None, 0, transient.remaining.unwrap_or(0.0)),
            wanted,
            trajectory,
        )?,
    })
}
