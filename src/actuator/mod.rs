//! The actuator in the loop (docs/model.md section 16): a rod driven by a
//! voltage through the actuator's equation (23), on which the friction
//! acts back.
//!
//! ```text
//! rod:    M a_R + d v_R + c x_R = alpha u(t) - F_f
//! slider: m_s a_S = F_f + m_s g_t
//! slip:   F_f = mu_d F_c sign(v_R - v_S)
//! stick:  v_S = v_R,  (M + m_s) a_R + d v_R + c x_R = alpha u(t) + m_s g_t,
//!         held while |F_f| = |m_s (a_R - g_t)| <= mu_0 F_c
//! ```
//!
//! * [`RodModel`]: what a scene says about the rod (`[actuator] rod`,
//!   `reaction`, `[actuator.real]`).
//! * [`Voltage`] (`voltage.rs`): the voltage, designed as the inverse of
//!   (23) for the scene's signal or given.
//! * [`GivenVoltage`] (`given.rs`): a voltage given in the scene's
//!   `[voltage]` table, and the friction-free actuator's response to it,
//!   the rod's reference motion.
//! * `response.rs`: the rod's closed-form motion in each mode.
//! * [`VoltageDescription`] (`description.rs`): the designed voltage for a
//!   signal generator, as `stickslip signal --voltage` prints it.
//! * [`DrivenRod`]: all of it built for one motor, what the engines use.
//!
//! Without the reaction the rod obeys (23) in every mode, and the slider
//! follows the friction law against that rod. With it, the stuck system's
//! acceleration decides stick and slip: a stuck slider needs the friction
//! `F* = m_s (a_R^stick - g_t)`, and the band `|F*| <= mu_0 F_c` is the
//! band `[a_0^-, a_0^+]` of `a_R^stick`, the rod's acceleration in the
//! stick equation. In forward slip `v_rel' = (M + m_s)/(M m_s) (F* - mu_d F_c)`,
//! so the law of docs/model.md section 1 carries over with `a_R`
//! replaced by `a_R^stick`.

mod description;
mod given;
mod response;
mod voltage;

pub use description::{VoltageDescription, VoltageHarmonic};
pub use given::GivenVoltage;
pub(crate) use response::ModeResponse;
pub use voltage::Voltage;

use crate::error::ParamError;
use crate::motor::Motor;
use crate::power::ActuatorParams;

/// How the rod moves.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum RodModel {
    /// The rod follows the signal whatever acts on it (the paper's model).
    #[default]
    Prescribed,
    /// The actuator is driven by a voltage and the rod obeys its equation.
    Driven(DrivenSpec),
}

/// A driven rod as a scene gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenSpec {
    /// The friction acts back on the rod (`[actuator] reaction`, default
    /// true).
    pub reaction: bool,
    /// The actuator actually driven, where it differs from the one the
    /// voltage was designed for (`[actuator.real]`).
    pub real: RealActuator,
}

impl Default for DrivenSpec {
    fn default() -> Self {
        Self {
            reaction: true,
            real: RealActuator::default(),
        }
    }
}

/// The real actuator's parameters where they differ from the design
/// (`None`: as designed).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RealActuator {
    /// `M` (kg).
    pub mass: Option<f64>,
    /// `d` (N s/m).
    pub damping: Option<f64>,
    /// `c` (N/m).
    pub stiffness: Option<f64>,
    /// `alpha` (N/V).
    pub transfer_factor: Option<f64>,
}

impl RealActuator {
    /// The real actuator: `design` with the given fields replaced.
    /// Errors name the field (`actuator.real.mass`, ...).
    pub fn apply(&self, design: &ActuatorParams) -> Result<ActuatorParams, ParamError> {
        let field = |name: &str, value: Option<f64>, default: f64| match value {
            Some(v) => ParamError::positive(&format!("actuator.real.{name}"), v),
            None => Ok(default),
        };
        Ok(ActuatorParams {
            mass: field("mass", self.mass, design.mass)?,
            damping: field("damping", self.damping, design.damping)?,
            stiffness: field("stiffness", self.stiffness, design.stiffness)?,
            transfer_factor: field(
                "transfer_factor",
                self.transfer_factor,
                design.transfer_factor,
            )?,
            capacitance: design.capacitance,
        })
    }

    /// True if no field differs from the design.
    pub fn is_design(&self) -> bool {
        *self == RealActuator::default()
    }
}

/// What loads the rod in a mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Load {
    /// Forward slip: the friction `-mu_d F_c` on the rod.
    SlipForward,
    /// Backward slip: `+mu_d F_c`.
    SlipBackward,
    /// Stick: the slider's mass rides on the rod, with `m_s g_t`.
    Stuck,
}

/// A driven rod, built for one motor and voltage.
#[derive(Debug, Clone)]
pub struct DrivenRod {
    design: ActuatorParams,
    real: ActuatorParams,
    reaction: bool,
    voltage: Voltage,
    /// Forward slip, backward slip, stick (all equal without reaction).
    responses: [ModeResponse; 3],
}

impl DrivenRod {
    /// The rod of `spec` driven by `voltage`, designed for `design`, under
    /// `motor`'s slider.
    pub fn new(
        spec: &DrivenSpec,
        design: &ActuatorParams,
        voltage: Voltage,
        motor: &Motor,
    ) -> Result<Self, ParamError> {
        let real = spec.real.apply(design)?;
        let m = real.mass;
        let responses = if spec.reaction {
            let ms = motor.params().slider_mass;
            let friction = motor.mu_d() * motor.contact_force();
            [
                ModeResponse::new(&real, m, -friction, &voltage),
                ModeResponse::new(&real, m, friction, &voltage),
                ModeResponse::new(&real, m + ms, ms * motor.g_t(), &voltage),
            ]
        } else {
            let free = ModeResponse::new(&real, m, 0.0, &voltage);
            [free.clone(), free.clone(), free]
        };
        Ok(Self {
            design: *design,
            real,
            reaction: spec.reaction,
            voltage,
            responses,
        })
    }

    /// The actuator the voltage was designed for.
    pub fn design(&self) -> &ActuatorParams {
        &self.design
    }

    /// The actuator driven.
    pub fn real(&self) -> &ActuatorParams {
        &self.real
    }

    /// Whether the friction acts back on the rod.
    pub fn reaction(&self) -> bool {
        self.reaction
    }

    /// The voltage.
    pub fn voltage(&self) -> &Voltage {
        &self.voltage
    }

    /// The rod's solved equation under `load`.
    pub(crate) fn response(&self, load: Load) -> &ModeResponse {
        match load {
            Load::SlipForward => &self.responses[0],
            Load::SlipBackward => &self.responses[1],
            Load::Stuck => &self.responses[2],
        }
    }

    /// The rod's acceleration (m/s^2) under `load` at phase `tau` in state
    /// `(x, v)`: from the equation of motion.
    pub(crate) fn acceleration(&self, load: Load, tau: f64, x: f64, v: f64) -> f64 {
        self.response(load)
            .acceleration(&self.real, &self.voltage, tau, x, v)
    }
}
