//! The `[actuator]`, `[actuator.real]` and `[voltage]` tables of a scene
//! file as written, and the actuator and rod model they give
//! (docs/interface.md; docs/model.md section 16).

use crate::actuator::{DrivenSpec, RealActuator, RodModel};
use crate::error::ParamError;
use crate::power::ActuatorParams;
use serde::{Deserialize, Serialize};

/// The `[actuator]` table: the five parameters of (23), (21), all
/// required, and how the rod moves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActuatorTable {
    /// `M`, kg.
    pub mass: f64,
    /// `d`, N s/m.
    pub damping: f64,
    /// `c`, N/m.
    pub stiffness: f64,
    /// `alpha`, N/V.
    pub transfer_factor: f64,
    /// `C`, F.
    pub capacitance: f64,
    /// `"prescribed"` (default) or `"driven"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod: Option<RodKind>,
    /// Driven rod: the friction acts back on it (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reaction: Option<bool>,
    /// Driven rod: `[actuator.real]`, the actuator actually driven.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub real: Option<RealTable>,
}

/// The rod `kind` of `[actuator] rod`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RodKind {
    /// The rod follows the signal.
    Prescribed,
    /// The rod obeys the actuator's equation under the voltage.
    Driven,
}

/// The `[voltage]` table: the voltage driving the rod, given directly,
/// `u = offset + sum_k amplitudes_k sin(k 2 pi frequency t + phases_k)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VoltageTable {
    /// `f`, Hz.
    pub frequency: f64,
    /// `u_k`, V.
    pub amplitudes: Vec<f64>,
    /// `phi_k`, rad.
    pub phases: Vec<f64>,
    /// `u_0`, V (default 0).
    #[serde(default)]
    pub offset: f64,
}

/// The `[actuator.real]` table: the actuator driven, where it differs
/// from the one the voltage was designed for.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RealTable {
    /// `M`, kg.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// `d`, N s/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// `c`, N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// `alpha`, N/V.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transfer_factor: Option<f64>,
}

/// The actuator's parameters and the rod model of an `[actuator]` table;
/// `voltage`: the scene gives `[voltage]`, which makes the rod driven
/// unless `rod` says otherwise (refused by `Scene::validate`, as is a
/// `[voltage]` without `[actuator]`).
pub(super) fn actuator_of(
    table: Option<ActuatorTable>,
    voltage: bool,
) -> Result<(Option<ActuatorParams>, RodModel), ParamError> {
    let Some(t) = table else {
        return Ok((None, RodModel::Prescribed));
    };
    let default_rod = if voltage {
        RodKind::Driven
    } else {
        RodKind::Prescribed
    };
    let params = ActuatorParams {
        mass: t.mass,
        damping: t.damping,
        stiffness: t.stiffness,
        transfer_factor: t.transfer_factor,
        capacitance: t.capacitance,
    };
    let rod = match t.rod.unwrap_or(default_rod) {
        RodKind::Driven => RodModel::Driven(DrivenSpec {
            reaction: t.reaction.unwrap_or(true),
            real: t.real.map_or_else(RealActuator::default, |r| RealActuator {
                mass: r.mass,
                damping: r.damping,
                stiffness: r.stiffness,
                transfer_factor: r.transfer_factor,
            }),
        }),
        RodKind::Prescribed => {
            let driven_only = if t.reaction.is_some() {
                Some("actuator.reaction")
            } else if t.real.is_some() {
                Some("actuator.real")
            } else {
                None
            };
            if let Some(field) = driven_only {
                return Err(ParamError::Inconsistent {
                    field: field.to_owned(),
                    reason: "applies only to a driven rod (actuator.rod = \"driven\")".to_owned(),
                });
            }
            RodModel::Prescribed
        }
    };
    Ok((Some(params), rod))
}

/// The `[actuator]` table of a scene's actuator and rod.
pub(super) fn actuator_table(
    params: Option<ActuatorParams>,
    rod: &RodModel,
) -> Option<ActuatorTable> {
    let p = params?;
    let (kind, reaction, real) = match rod {
        RodModel::Prescribed => (None, None, None),
        RodModel::Driven(spec) => (
            Some(RodKind::Driven),
            Some(spec.reaction),
            (!spec.real.is_design()).then_some(RealTable {
                mass: spec.real.mass,
                damping: spec.real.damping,
                stiffness: spec.real.stiffness,
                transfer_factor: spec.real.transfer_factor,
            }),
        ),
    };
    Some(ActuatorTable {
        mass: p.mass,
        damping: p.damping,
        stiffness: p.stiffness,
        transfer_factor: p.transfer_factor,
        capacitance: p.capacitance,
        rod: kind,
        reaction,
        real,
    })
}
