//! The motor: slider mass, contact force and Coulomb friction, expressed as
//! accelerations of the slider (docs/model.md section 1).
//!
//! * break-away acceleration `a_0 = mu_0 F_c / m_s` (the largest rod
//!   acceleration a stuck slider can follow),
//! * sliding acceleration `a_d = mu_d F_c / m_s`,
//! * an optional constant extra acceleration `g_t` (load force, incline),
//!   which makes the stick band asymmetric: `a_0^+ = a_0 + g_t`,
//!   `a_0^- = -a_0 + g_t`, and the sliding accelerations `±a_d + g_t`.
//!
//! All values in SI units. A [`Motor`] is only built from validated
//! parameters ([`Motor::new`]); its fields are private so that it cannot
//! hold `mu_d > mu_0` or a non-positive mass.

use crate::error::{Num, ParamError};

/// Physical parameters of the motor, as given in a scene (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorParams {
    /// Slider mass `m_s` in kg (> 0).
    pub slider_mass: f64,
    /// Contact (normal) force `F_c` in N (> 0).
    pub contact_force: f64,
    /// Static friction coefficient `mu_0` (>= 0).
    pub mu_static: f64,
    /// Dynamic friction coefficient `mu_d` (`0 <= mu_d <= mu_0`).
    pub mu_dynamic: f64,
    /// Constant extra slider acceleration `g_t` in m/s^2.
    pub extra_acceleration: f64,
}

impl Default for MotorParams {
    /// The paper's example motor (docs/model.md section 6): `m_s = 1.4 g`,
    /// `F_c = 1 N`, `a_0 = 124 m/s^2`, `a_d ≈ 112 m/s^2`.
    fn default() -> Self {
        Self {
            slider_mass: 1.4e-3,
            contact_force: 1.0,
            mu_static: 0.1736,
            mu_dynamic: 0.1568,
            extra_acceleration: 0.0,
        }
    }
}

/// The slider's friction contact in acceleration form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motor {
    params: MotorParams,
    a_0: f64,
    a_d: f64,
}

impl Motor {
    /// Validates the parameters (finite; positive mass and force;
    /// `0 <= mu_d <= mu_0`) and builds the motor. Errors name the scene
    /// field (`motor.slider_mass`, ...) and the value.
    pub fn new(params: MotorParams) -> Result<Self, ParamError> {
        ParamError::positive("motor.slider_mass", params.slider_mass)?;
        ParamError::positive("motor.contact_force", params.contact_force)?;
        ParamError::non_negative("motor.mu_static", params.mu_static)?;
        ParamError::non_negative("motor.mu_dynamic", params.mu_dynamic)?;
        ParamError::finite("motor.extra_acceleration", params.extra_acceleration)?;
        if params.mu_dynamic > params.mu_static {
            return Err(ParamError::out_of_range(
                "motor.mu_dynamic",
                params.mu_dynamic,
                format!(
                    "must not exceed motor.mu_static = {}",
                    Num(params.mu_static)
                ),
            ));
        }
        let a_0 = params.mu_static * params.contact_force / params.slider_mass;
        let a_d = params.mu_dynamic * params.contact_force / params.slider_mass;
        if !a_0.is_finite() {
            return Err(overflow(&params, a_0));
        }
        // a_d <= a_0, so a_d is finite too.
        Ok(Self { params, a_0, a_d })
    }

    /// The parameters this motor was built from.
    pub fn params(&self) -> &MotorParams {
        &self.params
    }

    /// Break-away acceleration `a_0 = mu_0 F_c / m_s` (m/s^2).
    pub fn a_0(&self) -> f64 {
        self.a_0
    }

    /// Sliding acceleration magnitude `a_d = mu_d F_c / m_s` (m/s^2).
    pub fn a_d(&self) -> f64 {
        self.a_d
    }

    /// Extra constant acceleration `g_t` (m/s^2).
    pub fn g_t(&self) -> f64 {
        self.params.extra_acceleration
    }

    /// Upper stick threshold `a_0^+ = a_0 + g_t`.
    pub fn a_0_plus(&self) -> f64 {
        self.a_0 + self.g_t()
    }

    /// Lower stick threshold `a_0^- = -a_0 + g_t`.
    pub fn a_0_minus(&self) -> f64 {
        -self.a_0 + self.g_t()
    }

    /// Slider acceleration while the rod is faster (`SlipForward`): `a_d + g_t`.
    pub fn slip_forward_acceleration(&self) -> f64 {
        self.a_d + self.g_t()
    }

    /// Slider acceleration while the rod is slower (`SlipBackward`): `-a_d + g_t`.
    pub fn slip_backward_acceleration(&self) -> f64 {
        -self.a_d + self.g_t()
    }

    /// Contact force `F_c` (N).
    pub fn contact_force(&self) -> f64 {
        self.params.contact_force
    }

    /// Dynamic friction coefficient `mu_d`.
    pub fn mu_d(&self) -> f64 {
        self.params.mu_dynamic
    }
}

/// The error for a break-away acceleration `a_0 = mu_0 F_c / m_s` that
/// overflows, blamed on the input that makes it overflow: the mass when
/// `mu_0 F_c` is finite (a tiny `m_s`), else the larger of `mu_0` and `F_c`.
fn overflow(params: &MotorParams, a_0: f64) -> ParamError {
    let numerator = params.mu_static * params.contact_force;
    let (field, value, others) = if numerator.is_finite() {
        (
            "motor.slider_mass",
            params.slider_mass,
            format!(
                "motor.mu_static = {} and motor.contact_force = {}",
                Num(params.mu_static),
                Num(params.contact_force)
            ),
        )
    } else if params.contact_force >= params.mu_static {
        (
            "motor.contact_force",
            params.contact_force,
            format!(
                "motor.mu_static = {} and motor.slider_mass = {}",
                Num(params.mu_static),
                Num(params.slider_mass)
            ),
        )
    } else {
        (
            "motor.mu_static",
            params.mu_static,
            format!(
                "motor.contact_force = {} and motor.slider_mass = {}",
                Num(params.contact_force),
                Num(params.slider_mass)
            ),
        )
    };
    ParamError::out_of_range(
        field,
        value,
        format!(
            "with {others} gives the break-away acceleration a_0 = mu_0 F_c / m_s = {} m/s^2, \
             which is not representable",
            Num(a_0)
        ),
    )
}

impl Default for Motor {
    /// The paper's example motor.
    fn default() -> Self {
        Self::new(MotorParams::default()).expect("the default motor parameters are valid")
    }
}
