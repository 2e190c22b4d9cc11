//! The slope `d v_inf / d F` of the characteristic at a load (m/(s N)),
//! exact: the sensitivity `d v_inf / d g_t` of the steady state carried
//! through the period map's fixed point ([`crate::sensitivity`],
//! docs/model.md section 14), with `g_t = -F / m_s`:
//!
//! ```text
//! d v_inf / d F = -(1 / m_s) d v_inf / d g_t.
//! ```
//!
//! Where the event structure of the steady period changes at the load (a
//! stick phase appears, a grazing, the edge of the held band) the slope
//! is one-sided: `left` (towards smaller loads) and `right` (towards
//! larger loads) are reported and `slope` is empty. Increasing `F`
//! decreases `g_t`, so the left slope in `F` is the right derivative in
//! `g_t`. Without a steady state there is no slope. No extra simulation is
//! run: the derivative is carried through the steady period already found.
//!
//! Where the period map does not contract at the fixed point (`P' = 1`:
//! with `mu_dynamic = 0` a slider that slips throughout feels no friction
//! and keeps whatever velocity it has, so every velocity of its slip range
//! is a fixed point), `v_inf` does not follow the load smoothly, not even
//! from one side (any load makes the slider drift by `g_t T` per period
//! until it sticks or runs away, so `v_inf` jumps there): the point has a
//! steady state but no slope ([`SlopeMethod::Unavailable`]). That is a
//! property of the point, not an error: the rest of the characteristic is
//! computed as before (nothing else depends on the slopes).

use super::CharacteristicError;
use super::evaluate::Evaluator;
use crate::error::{Error, SimulationError};
use crate::sensitivity::{self, Derivative, Parameter};

/// How the slopes are found, as outputs state it.
pub(super) const DESCRIPTION: &str = "the exact sensitivity of the steady state (docs/model.md section 14), one-sided where the event structure changes";

/// How a slope was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlopeMethod {
    /// The exact derivative; `v_inf` is smooth in the load here.
    Exact,
    /// The event structure changes at this load: exact one-sided slopes.
    OneSided,
    /// No slope: no steady state.
    None,
    /// A steady state without a slope: the period map does not contract at
    /// its fixed point (`P' = 1`, e.g. with `mu_dynamic = 0`, where the
    /// slider slips without friction), so `v_inf` does not follow the load
    /// smoothly there, not even from one side.
    Unavailable,
}

impl SlopeMethod {
    /// The name in outputs.
    pub fn name(self) -> &'static str {
        match self {
            SlopeMethod::Exact => "exact",
            SlopeMethod::OneSided => "one_sided",
            SlopeMethod::None => "none",
            SlopeMethod::Unavailable => "unavailable",
        }
    }
}

/// A slope and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slope {
    /// `d v_inf / d F` (m/(s N)) where `v_inf` is smooth in the load.
    pub value: Option<f64>,
    /// Towards smaller loads (m/(s N)).
    pub left: Option<f64>,
    /// Towards larger loads (m/(s N)).
    pub right: Option<f64>,
    /// How it was found.
    pub method: SlopeMethod,
}

impl Slope {
    /// No slope (no steady state).
    pub(super) const NONE: Slope = Slope {
        value: None,
        left: None,
        right: None,
        method: SlopeMethod::None,
    };

    /// No slope at a steady state whose period map does not contract.
    pub(super) const UNAVAILABLE: Slope = Slope {
        value: None,
        left: None,
        right: None,
        method: SlopeMethod::Unavailable,
    };
}

/// `d v_inf / d F` at `load` (N), from the steady state found there.
pub(super) fn slope_at(ev: &Evaluator, load: f64) -> Result<Slope, CharacteristicError> {
    let Some(boundary_velocity) = ev.boundary_velocity(load) else {
        return Ok(Slope::NONE);
    };
    let scene = ev.scene_at(load);
    let found = match sensitivity::of_steady_state(
        &scene.signal,
        &scene.motor,
        boundary_velocity,
        &[Parameter::ExtraAcceleration],
    ) {
        Ok(found) => found,
        // A neutral map (P' = 1 at the fixed point): no derivative exists.
        Err(Error::Simulation(SimulationError::NoSensitivity(_))) => return Ok(Slope::UNAVAILABLE),
        Err(source) => return Err(CharacteristicError::Simulation { load, source }),
    };
    let Some(entry) = found.get(Parameter::ExtraAcceleration) else {
        return Ok(Slope::NONE);
    };
    let per_force = |d: Option<f64>| d.map(|d| -d / ev.slider_mass()).map(|s| s + 0.0);
    Ok(match entry.derivative {
        Derivative::Smooth(d) => {
            let s = per_force(Some(d));
            Slope {
                value: s,
                left: s,
                right: s,
                method: SlopeMethod::Exact,
            }
        }
        ref d @ Derivative::OneSided { .. } => Slope {
            value: None,
            left: per_force(d.right()),
            right: per_force(d.left()),
            method: SlopeMethod::OneSided,
        },
    })
}
