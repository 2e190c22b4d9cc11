//! The slope `d v_inf / d F` of the characteristic at a load (m/(s N)).
//!
//! **Placeholder.** The exact derivative is `dv*/dg_t` carried through the
//! period map (docs/model.md section 9, "Sensitivities"), with
//! `d v_inf / d F = -(1 / m_s) d v_inf / d g_t`; until the engine provides
//! it, [`slope_at`] is a central difference, and it is the only place to
//! change when the exact derivative is available:
//!
//! ```text
//! slope = (v_inf(F + h) - v_inf(F - h)) / (2 h),    h = 1e-6 mu_0 F_c,
//! ```
//!
//! one-sided (`(v_inf(F) - v_inf(F - h)) / h` or the mirror) where one
//! neighbour has no steady state, and `None` where neither has. Its error
//! is about `h^2 |v'''| / 6` plus `e / h` with `e` the error estimate of
//! `v_inf` (a few 1e-13 m/s for the paper's motor, so about 1e-6
//! relative), and it averages the two one-sided slopes across a kink
//! (where the event structure changes). [`SlopeMethod`] says which
//! formula gave each value.

use super::CharacteristicError;
use super::evaluate::{Evaluator, Purpose};

/// How the slopes are found, as outputs state it.
pub(super) const DESCRIPTION: &str = "central differences with step 1e-6 mu_0 F_c (one-sided at the ends of the curve), a placeholder for the exact derivative";

/// Step of the difference, relative to the holding force `mu_0 F_c`.
pub(super) const RELATIVE_STEP: f64 = 1e-6;

/// How a slope was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlopeMethod {
    /// `(v(F + h) - v(F - h)) / (2 h)`.
    CentralDifference,
    /// A one-sided difference: one neighbour had no steady state.
    OneSidedDifference,
    /// No slope: no neighbour had a steady state.
    None,
}

impl SlopeMethod {
    /// The name in outputs.
    pub fn name(self) -> &'static str {
        match self {
            SlopeMethod::CentralDifference => "central_difference",
            SlopeMethod::OneSidedDifference => "one_sided_difference",
            SlopeMethod::None => "none",
        }
    }
}

/// A slope and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slope {
    /// `d v_inf / d F` (m/(s N)).
    pub value: Option<f64>,
    /// The formula used.
    pub method: SlopeMethod,
}

/// `d v_inf / d F` at `load` (N); `holding_force` is `mu_0 F_c` (see the
/// module docs: a placeholder for the exact derivative).
pub(super) fn slope_at(
    ev: &Evaluator,
    load: f64,
    holding_force: f64,
) -> Result<Slope, CharacteristicError> {
    let h = RELATIVE_STEP * holding_force;
    let v = |f: f64| -> Result<Option<f64>, CharacteristicError> {
        Ok(ev.at(f, Purpose::Slope)?.v_inf)
    };
    let (left, here, right) = (v(load - h)?, v(load)?, v(load + h)?);
    Ok(match (left, here, right) {
        (Some(l), _, Some(r)) => Slope {
            value: Some((r - l) / (2.0 * h)),
            method: SlopeMethod::CentralDifference,
        },
        (Some(l), Some(c), None) => Slope {
            value: Some((c - l) / h),
            method: SlopeMethod::OneSidedDifference,
        },
        (None, Some(c), Some(r)) => Slope {
            value: Some((r - c) / h),
            method: SlopeMethod::OneSidedDifference,
        },
        _ => Slope {
            value: None,
            method: SlopeMethod::None,
        },
    })
}
