//! Exact sensitivities of the steady state (docs/model.md section 14):
//! `dv_inf / dtheta` for the motor's and the signal's parameters, from the
//! sensitivities of the event times carried through one period of the
//! periodic orbit and its fixed point.
//!
//! With `v*` the fixed point of the period map `P(v; theta)` and `x_inf =
//! X(v*; theta)` the step of the steady period,
//!
//! ```text
//! dv*/dtheta    = (dP/dtheta) / (1 - dP/dv)
//! dv_inf/dtheta = (dX/dtheta + dX/dv dv*/dtheta) / T - v_inf (d ln T / dtheta).
//! ```
//!
//! `dP/dv`, `dP/dtheta`, `dX/dv` and `dX/dtheta` come from a forward
//! propagation through the steady period's pieces in closed form
//! (`propagate`): slip pieces move with constant acceleration, stuck
//! pieces with the rod, and every event time moves by the implicit function
//! theorem on its condition (`v_rel = 0` ends a slip, `a_R = a_0^+-` ends a
//! stick, a rod jump or the period end moves with the signal).
//!
//! Where the event structure changes within [`NEAR`] (relative to the
//! parameter's scale) of the scene, the derivative is one-sided: the
//! derivative of the branch on each side is reported ([`Derivative`]), the
//! orbit's own exactly, the other side's exactly for a stick phase of
//! vanishing length (a kink of `v_inf`) and from a run [`ACROSS`] beyond
//! the change for the changes that move the orbit by a finite amount
//! (`structure`).
//!
//! The module is an observer of the steady period (`orbit`) above the
//! engine and below the run: [`of_steady_state`] takes the boundary
//! velocity of a steady state found by the run
//! ([`crate::analysis::SteadyState::boundary_velocity`]), so that `v_inf`
//! is not searched again; `RunReport::sensitivities` is the same
//! for a scene and its run.
//!
//! Files: `tangent` (a parameter direction), `parameter` (the scene's
//! fields and their directions), `harmonics` (amplitudes and phases
//! through stroke scaling and shift), `orbit` (the recorded period),
//! `propagate` (the tangents and the fixed point), `structure` (changes
//! of the event structure), `selection` (a nearer orbit that appears).

mod driven;
mod harmonics;
mod orbit;
mod parameter;
mod propagate;
mod selection;
mod structure;
mod tangent;

pub use driven::{ActuatorSensitivities, ActuatorSensitivity};
pub(crate) use driven::{of_driven_period, period_map_jacobian};
pub use parameter::{Parameter, VariedScene};
pub use structure::ChangeKind;

use crate::analysis;
use crate::engine::event::{EventEngine, EventOptions};
use crate::engine::{Event, PeriodEngine, PeriodStart};
use crate::error::{Error, SimulationError};
use crate::motor::{Motor, MotorParams};
use crate::signal::{Held, Signal, SignalSpec};
use orbit::Orbit;
use propagate::{Context, NoDerivative};

/// A change of the event structure closer than `NEAR` times the
/// parameter's scale ([`Parameter::scale`]) makes the derivative
/// one-sided.
pub const NEAR: f64 = 1e-9;

/// The other side of a change that moves the orbit by a finite amount is
/// evaluated this far (times the parameter's scale) beyond the change.
pub const ACROSS: f64 = 1e-11;

/// Where the event structure changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Change {
    /// What changes.
    pub kind: ChangeKind,
    /// Phase of the event in the steady period (s).
    pub phase: f64,
    /// The parameter value of the change, to first order.
    pub at: f64,
}

/// `dv_inf / dtheta`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Derivative {
    /// The event structure is the same on both sides: one derivative.
    Smooth(f64),
    /// The event structure changes at (or within [`NEAR`] of) the scene:
    /// the derivatives of the branches for smaller (`left`) and larger
    /// (`right`) values of the parameter; `None` where that side has no
    /// steady state (or it could not be evaluated).
    OneSided {
        /// For smaller values.
        left: Option<f64>,
        /// For larger values.
        right: Option<f64>,
        /// The change.
        change: Change,
    },
}

impl Derivative {
    /// The two-sided derivative, if there is one.
    pub fn value(&self) -> Option<f64> {
        match self {
            Derivative::Smooth(d) => Some(*d),
            Derivative::OneSided { .. } => None,
        }
    }

    /// The derivative for smaller values of the parameter.
    pub fn left(&self) -> Option<f64> {
        match self {
            Derivative::Smooth(d) => Some(*d),
            Derivative::OneSided { left, .. } => *left,
        }
    }

    /// The derivative for larger values of the parameter.
    pub fn right(&self) -> Option<f64> {
        match self {
            Derivative::Smooth(d) => Some(*d),
            Derivative::OneSided { right, .. } => *right,
        }
    }
}

/// The sensitivity to one parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensitivity {
    /// Which scene field.
    pub parameter: Parameter,
    /// Its value in the scene.
    pub value: f64,
    /// `dv_inf / dtheta`, in [`Parameter::unit`].
    pub derivative: Derivative,
}

/// The sensitivities of a steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensitivities {
    /// `v_inf` of the steady period they belong to (m/s): the run's, to
    /// the engine's event-time tolerance (the root finder starts from what
    /// the engine found before, so the last bits may differ).
    pub v_inf: f64,
    /// The boundary velocity `v*` (m/s).
    pub boundary_velocity: f64,
    /// `P'(v*)`.
    pub map_derivative: f64,
    /// The events of the steady period, phase 0 included.
    pub events: Vec<Event>,
    /// What every derivative holds of the drive: `kappa` (the period
    /// follows `a_0`) or the frequency (`SignalSpec::held`).
    pub held_fixed: Held,
    /// The drive frequency `f_0` (Hz) of the steady period.
    pub f0: f64,
    /// One entry per parameter, in the order asked for.
    pub entries: Vec<Sensitivity>,
}

impl Sensitivities {
    /// The entry of `parameter`, if it was computed.
    pub fn get(&self, parameter: Parameter) -> Option<&Sensitivity> {
        self.entries.iter().find(|s| s.parameter == parameter)
    }
}

impl From<NoDerivative> for Error {
    fn from(e: NoDerivative) -> Self {
        match e {
            NoDerivative::NotContracting(p) => SimulationError::NoSensitivity(format!(
                "the period map does not contract at its fixed point (P' = {p}), so the \
                 steady state does not follow the parameters smoothly"
            ))
            .into(),
        }
    }
}

/// The sensitivities of the steady state of a scene with this signal and
/// motor whose periodic orbit passes the period boundary with the slider
/// velocity `boundary_velocity` (as found by the run), for `parameters`
/// (e.g. [`Parameter::all_for`]; a parameter the signal does not have is
/// an error naming it).
pub fn of_steady_state(
    spec: &SignalSpec,
    params: &MotorParams,
    boundary_velocity: f64,
    parameters: &[Parameter],
) -> Result<Sensitivities, Error> {
    let (motor, signal, orbit) = steady_orbit(spec, params, boundary_velocity)?;
    let ctx = Context {
        signal: &signal,
        motor: &motor,
    };
    let candidates = structure::candidates(&ctx, &orbit);
    let by_v = ctx.by_velocity(&orbit);
    let reach = SELECTION_REACH * signal.velocity_scale();
    let selections = selection::selections(&ctx, &orbit, &candidates, &by_v.nodes, reach);
    let mut entries = Vec::with_capacity(parameters.len());
    for &parameter in parameters {
        let value = parameter.value(spec, params).ok_or_else(|| {
            crate::error::ParamError::Inconsistent {
                field: parameter.to_string(),
                reason: "the scene's signal has no such parameter".to_owned(),
            }
        })?;
        let dir = parameter.tangent(spec, &motor, &signal)?;
        let own = ctx.branch(&orbit, &orbit.pieces, &dir)?;
        let scale = parameter.scale(spec, &motor);
        let flags = candidates
            .iter()
            .map(|c| Flag {
                kind: c.kind,
                phase: c.phase,
                m: c.m,
                dm: c.derivative(&ctx, &orbit, &dir, &own.nodes),
                alternative: c.alternative.as_deref(),
            })
            .chain(selections.iter().map(|s| Flag {
                kind: s.kind,
                phase: s.phase,
                m: s.m,
                dm: s.derivative(&ctx, &orbit, &candidates, &dir, &own.by_theta),
                alternative: None,
            }))
            .filter(|f| f.m.abs() <= NEAR * scale * f.dm.abs() || !f.dm.is_finite())
            .collect::<Vec<Flag>>();
        let derivative = if flags.is_empty() && own.v_inf.is_finite() {
            Derivative::Smooth(own.v_inf)
        } else {
            one_sided(
                &ctx,
                &orbit,
                (spec, params),
                (parameter, value, scale),
                &dir,
                own.v_inf,
                &flags,
            )
        };
        entries.push(Sensitivity {
            parameter,
            value,
            derivative,
        });
    }
    Ok(Sensitivities {
        v_inf: orbit.v_inf(),
        boundary_velocity,
        map_derivative: orbit.map_derivative,
        events: orbit.events.clone(),
        held_fixed: spec.held(),
        f0: spec.f0(&motor),
        entries,
    })
}

/// The derivatives of `v_inf` of the branch of the steady orbit's own
/// event structure, one per parameter (non-finite where the branch has
/// none, e.g. at a tangential event), without looking for changes of the
/// structure nearby: [`of_steady_state`]'s [`Derivative::Smooth`] value
/// wherever that is smooth. Off a change (at any positive distance from
/// it) this is the derivative of `v_inf` at the scene; exactly on one it
/// is the one-sided derivative towards the side whose event structure the
/// orbit has.
pub(crate) fn own_branch(
    spec: &SignalSpec,
    params: &MotorParams,
    boundary_velocity: f64,
    parameters: &[Parameter],
) -> Result<Vec<f64>, Error> {
    let (motor, signal, orbit) = steady_orbit(spec, params, boundary_velocity)?;
    let ctx = Context {
        signal: &signal,
        motor: &motor,
    };
    parameters
        .iter()
        .map(|parameter| {
            let dir = parameter.tangent(spec, &motor, &signal)?;
            Ok(ctx.branch(&orbit, &orbit.pieces, &dir)?.v_inf)
        })
        .collect()
}

/// The scene's motor and signal and the steady orbit through
/// `boundary_velocity`, as both [`of_steady_state`] and [`own_branch`]
/// start from.
fn steady_orbit(
    spec: &SignalSpec,
    params: &MotorParams,
    boundary_velocity: f64,
) -> Result<(Motor, Signal, orbit::Orbit), Error> {
    let motor = Motor::new(*params)?;
    let signal = Signal::build(spec, &motor)?;
    let orbit = orbit::record(&signal, &motor, boundary_velocity)?;
    Ok((motor, signal, orbit))
}

/// Farthest a jump of the period map is looked for between rest and the
/// orbit (`selection`), relative to `max |v_R|`.
pub const SELECTION_REACH: f64 = 1e-2;

/// A change of the event structure near the scene, along one parameter.
#[derive(Debug, Clone, Copy)]
struct Flag<'a> {
    kind: ChangeKind,
    phase: f64,
    /// The oriented measure (> 0 on the orbit's side).
    m: f64,
    /// Its derivative along the parameter.
    dm: f64,
    /// The other side's pieces, for a change that keeps the orbit.
    alternative: Option<&'a [orbit::Piece]>,
}

/// The one-sided derivatives at the changes `flags`: the orbit's own
/// branch on its side, the other side from the alternative branch of a
/// single `stick_phase` change, else from runs beyond the changes.
fn one_sided(
    ctx: &Context,
    orbit: &Orbit,
    scene: (&SignalSpec, &MotorParams),
    (parameter, value, scale): (Parameter, f64, f64),
    dir: &tangent::Tangent,
    own: f64,
    flags: &[Flag],
) -> Derivative {
    let offsets: Vec<f64> = flags
        .iter()
        .map(|f| {
            if f.dm.is_finite() && f.dm != 0.0 {
                -f.m / f.dm
            } else {
                0.0
            }
        })
        .collect();
    let sides: Vec<f64> = flags.iter().map(|f| f.dm.signum()).collect();
    let kind = match flags.first() {
        Some(f) if flags.iter().all(|o| o.kind == f.kind) => f.kind,
        Some(_) => ChangeKind::Several,
        None => ChangeKind::Grazing,
    };
    let change = Change {
        kind,
        phase: flags.first().map_or(0.0, |f| f.phase),
        at: value + offsets.first().copied().unwrap_or(0.0),
    };
    let across = ACROSS * scale;
    let lo = offsets.iter().copied().fold(0.0, f64::min);
    let hi = offsets.iter().copied().fold(0.0, f64::max);
    let run_at = |v: f64| branch_at(scene, parameter, v);
    let side = sides.first().copied().unwrap_or(0.0);
    let one_side = own.is_finite() && side != 0.0 && sides.iter().all(|s| *s == side);
    let (left, right) = if one_side {
        // The orbit's branch holds on `side`; the other side's branch:
        let other = match flags {
            [
                Flag {
                    alternative: Some(alt),
                    ..
                },
            ] => ctx
                .branch(orbit, alt, dir)
                .ok()
                .map(|b| b.v_inf)
                .filter(|d| d.is_finite()),
            _ if side > 0.0 => run_at(value + lo - across),
            _ => run_at(value + hi + across),
        };
        if side > 0.0 {
            (other, Some(own))
        } else {
            (Some(own), other)
        }
    } else {
        (run_at(value + lo - across), run_at(value + hi + across))
    };
    Derivative::OneSided {
        left,
        right,
        change,
    }
}

/// The derivative of `v_inf` along `parameter` at the scene with the
/// parameter set to `value`, on the steady state the motion from rest
/// reaches there, without looking for changes of its event structure;
/// `None` if there is none.
///
/// Next to a change that moves the orbit by a finite amount the period map
/// is discontinuous and may have a further fixed point close to the one
/// the motion from rest reaches; a search for fixed points could land on
/// either, so the start-up is simulated until it has converged
/// ([`analysis::transient`]) and the fixed point is taken where it
/// ends, as the run's slow path does.
fn branch_at(
    (spec, params): (&SignalSpec, &MotorParams),
    parameter: Parameter,
    value: f64,
) -> Option<f64> {
    let VariedScene {
        signal: spec,
        motor: params,
    } = parameter.apply(spec, params, value);
    let motor = Motor::new(params).ok()?;
    let signal = Signal::build(&spec, &motor).ok()?;
    let boundary_velocity = from_rest(&signal, &motor)?;
    let orbit = orbit::record(&signal, &motor, boundary_velocity).ok()?;
    let ctx = Context {
        signal: &signal,
        motor: &motor,
    };
    let dir = parameter.tangent(&spec, &motor, &signal).ok()?;
    let branch = ctx.branch(&orbit, &orbit.pieces, &dir).ok()?;
    branch.v_inf.is_finite().then_some(branch.v_inf)
}

/// Periods a start-up from rest may take in [`from_rest`].
pub const FROM_REST_PERIODS: u64 = 20_000;

/// The boundary velocity of the periodic orbit the motion from rest
/// converges to, if it does within [`FROM_REST_PERIODS`]: the start-up's
/// own convergence test ([`analysis::transient`]), or its last boundary
/// velocities within rounding of each other (a stuck orbit can alternate
/// between two neighbouring floating-point numbers).
pub fn from_rest(signal: &Signal, motor: &Motor) -> Option<f64> {
    let mut engine = EventEngine::new(signal, motor, EventOptions::default());
    let options = analysis::AnalysisOptions {
        max_periods: FROM_REST_PERIODS,
        ..Default::default()
    };
    let transient = analysis::transient(
        &mut engine,
        &options,
        analysis::StatsWanted::default(),
        &mut (),
    )
    .ok()?;
    let rounding = 8.0 * f64::EPSILON * signal.velocity_scale();
    let tail =
        &transient.boundary_velocities[transient.boundary_velocities.len().saturating_sub(4)..];
    let settled = tail.len() == 4 && tail.windows(2).all(|w| (w[1] - w[0]).abs() <= rounding);
    if !(transient.converged || settled) || transient.run_away.is_some() {
        return None;
    }
    let seed = transient.final_velocity;
    let reach = transient.remaining.unwrap_or(0.0) + transient.v_inf_error.unwrap_or(0.0);
    let v_star = match analysis::fixed_point(&mut engine, seed) {
        Ok(p) if (p.velocity - seed).abs() <= reach => p.velocity,
        _ => seed,
    };
    let before = engine
        .run_period(
            2,
            PeriodStart {
                velocity: v_star,
                mode: None,
            },
            &mut (),
        )
        .ok()?;
    Some(before.velocity)
}
