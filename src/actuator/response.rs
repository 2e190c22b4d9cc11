//! The rod's motion in one mode: the closed-form solution of the actuator
//! equation with a constant extra force and, in stick, the slider's mass
//! (docs/model.md section 16).
//!
//! In every mode the rod obeys
//!
//! ```text
//! M_m x'' + d x' + c x = alpha u(t) + F_m,
//! ```
//!
//! with the real actuator's `d`, `c`, `alpha` and, by mode (reaction on):
//!
//! | mode | `M_m` | `F_m` |
//! | --- | --- | --- |
//! | slip, direction `s` | `M` | `-s mu_d F_c` |
//! | stick | `M + m_s` | `m_s g_t` |
//!
//! and `M_m = M`, `F_m = 0` in every mode without the reaction. Its
//! solution is the sum of
//!
//! * the *particular* periodic solution: harmonic by harmonic
//!   `X_k = alpha U_k / (c - M_m (k w)^2 + i d k w)`, plus the constant
//!   `(alpha u_0 + F_m) / c`, kept as a [`FourierSignal`];
//! * a free damped oscillation `h'' + 2 sigma h' + omega_0^2 h = 0` with
//!   `sigma = d / (2 M_m)`, `omega_0^2 = c / M_m`, whose initial values
//!   are the rod's state minus the particular solution's at the segment
//!   start.

use super::Voltage;
use crate::power::ActuatorParams;
use crate::signal::FourierSignal;

/// The rod's equation in one mode, solved.
#[derive(Debug, Clone)]
pub(crate) struct ModeResponse {
    /// The moving mass `M_m` (kg).
    pub mass: f64,
    /// The constant extra force `F_m` (N).
    pub force: f64,
    /// `d / (2 M_m)` (1/s).
    pub sigma: f64,
    /// `sqrt(c / M_m)` (rad/s).
    pub omega0: f64,
    /// The periodic particular solution.
    pub particular: FourierSignal,
    /// Whether the rod has a free oscillation of its own: false for a rod
    /// that follows its signal whatever acts on it
    /// ([`ModeResponse::prescribed`]).
    pub free: bool,
}

impl ModeResponse {
    /// The response of `actuator` carrying `mass` (kg) with the extra force
    /// `force` (N) to `voltage`.
    pub(crate) fn new(actuator: &ActuatorParams, mass: f64, force: f64, voltage: &Voltage) -> Self {
        let w = voltage.omega();
        let alpha = actuator.transfer_factor;
        let (mut cos, mut sin) = (Vec::new(), Vec::new());
        for (k, (p, q)) in voltage.harmonics().enumerate() {
            let kw = (k + 1) as f64 * w;
            // U_k = P_k - i Q_k; X_k = alpha U_k / Z_k, Z_k = zr + i zi.
            let (zr, zi) = (actuator.stiffness - mass * kw * kw, actuator.damping * kw);
            let norm = zr * zr + zi * zi;
            let (ur, ui) = (alpha * p, -alpha * q);
            let (xr, xi) = ((ur * zr + ui * zi) / norm, (ui * zr - ur * zi) / norm);
            cos.push(xr);
            sin.push(-xi);
        }
        let c0 = (alpha * voltage.offset() + force) / actuator.stiffness;
        let particular = FourierSignal::from_coefficients(voltage.period(), c0, cos, sin);
        Self {
            mass,
            force,
            sigma: actuator.damping / (2.0 * mass),
            omega0: (actuator.stiffness / mass).sqrt(),
            particular,
            free: true,
        }
    }

    /// A rod that follows `signal` whatever acts on it (the paper's
    /// prescribed rod): the particular solution is the signal, there is no
    /// free oscillation. `sigma` and `omega0` are the signal's fundamental
    /// (they only set the scale of the free part's zero terms).
    pub(crate) fn prescribed(signal: &FourierSignal) -> Self {
        Self {
            mass: 1.0,
            force: 0.0,
            sigma: signal.omega(),
            omega0: signal.omega(),
            particular: signal.clone(),
            free: false,
        }
    }

    /// The rod's acceleration (m/s^2) at phase `tau` in state `(x, v)`,
    /// from the equation of motion itself.
    pub(crate) fn acceleration(
        &self,
        actuator: &ActuatorParams,
        voltage: &Voltage,
        tau: f64,
        x: f64,
        v: f64,
    ) -> f64 {
        let u = voltage.value(tau)[0];
        (actuator.transfer_factor * u + self.force - actuator.damping * v - actuator.stiffness * x)
            / self.mass
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The particular solution satisfies its own equation at every phase
    /// (residual at the rounding of the largest term), for a mass and a
    /// force different from the actuator's.
    #[test]
    fn particular_solution_satisfies_the_mode_equation() {
        let actuator = ActuatorParams::default();
        let voltage =
            Voltage::from_amplitudes(9448.8, &[120.0, 40.0, 5.0], &[0.2, -1.0, 2.5], 30.0);
        let mass = actuator.mass + 1.4e-3;
        let force = 0.157;
        let r = ModeResponse::new(&actuator, mass, force, &voltage);
        for i in 0..40 {
            let tau = voltage.period() * i as f64 / 40.0;
            let st = r.particular.state(tau);
            let a = r.acceleration(&actuator, &voltage, tau, st.x, st.v);
            let scale = actuator.transfer_factor * 200.0 / mass;
            assert!((a - st.a).abs() <= 1e-12 * scale, "{a} against {}", st.a);
        }
    }

    /// With the actuator's own mass and no force, the response to the
    /// designed voltage is the signal (the inverse of (23) undone).
    #[test]
    fn response_to_the_designed_voltage_is_the_signal() {
        let actuator = ActuatorParams::default();
        let signal = FourierSignal::from_coefficients(
            1.0 / 9448.8,
            12.5e-6,
            vec![-10e-6, 1.5e-6],
            vec![4e-6, -2e-6],
        );
        let voltage = Voltage::designed(&signal, &actuator);
        let r = ModeResponse::new(&actuator, actuator.mass, 0.0, &voltage);
        for i in 0..20 {
            let tau = signal.period() * i as f64 / 20.0;
            let (a, b) = (signal.state(tau), r.particular.state(tau));
            assert!(
                (a.x - b.x).abs() <= 1e-15 * 25e-6,
                "x {} against {}",
                a.x,
                b.x
            );
            assert!((a.v - b.v).abs() <= 1e-14, "v {} against {}", a.v, b.v);
        }
    }
}
