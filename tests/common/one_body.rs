//! A driven actuator in closed form, written out independently of the
//! crate's own (`tests/driven_fixed_step.rs`, `tests/fixed_step_spring.rs`).

use stickslip::actuator::DrivenRod;
use stickslip::engine::Kinematics;

/// `m x'' + d x' + c x = alpha u(t) + force` under the voltage of a rod,
/// in closed form: the periodic particular solution (harmonic balance,
/// `X_k = alpha U_k / (c - m (k w)^2 + i d k w)`, `U_k = P_k - i Q_k`)
/// plus the damped free oscillation that meets a given state
/// (underdamped), written out independently of the crate's own.
pub struct Oscillator {
    mass: f64,
    damping: f64,
    stiffness: f64,
    constant: f64,
    omega: f64,
    harmonics: Vec<(f64, f64)>,
}

impl Oscillator {
    pub fn new(rod: &DrivenRod, [mass, damping, stiffness, force]: [f64; 4]) -> Self {
        let voltage = rod.voltage();
        let omega = voltage.omega();
        let alpha = rod.real().transfer_factor;
        let harmonics = voltage
            .harmonics()
            .enumerate()
            .map(|(i, (p, q))| {
                let kw = (i + 1) as f64 * omega;
                let (zr, zi) = (stiffness - mass * kw * kw, damping * kw);
                let (ur, ui) = (alpha * p, -alpha * q);
                let norm = zr * zr + zi * zi;
                ((ur * zr + ui * zi) / norm, (ui * zr - ur * zi) / norm)
            })
            .collect();
        Self {
            mass,
            damping,
            stiffness,
            constant: (alpha * voltage.offset() + force) / stiffness,
            omega,
            harmonics,
        }
    }

    pub fn particular(&self, t: f64) -> Kinematics {
        let (mut x, mut v) = (self.constant, 0.0);
        for (i, (xr, xi)) in self.harmonics.iter().enumerate() {
            let kw = (i + 1) as f64 * self.omega;
            let (s, c) = (kw * t).sin_cos();
            x += xr * c - xi * s;
            v += kw * (-xr * s - xi * c);
        }
        Kinematics { x, v }
    }

    pub fn advance(&self, state: Kinematics, t0: f64, t1: f64) -> Kinematics {
        let sigma = self.damping / (2.0 * self.mass);
        let omega0_sq = self.stiffness / self.mass;
        let wd = (omega0_sq - sigma * sigma).sqrt();
        assert!(wd > 0.0, "underdamped");
        let p0 = self.particular(t0);
        let (h0, dh0) = (state.x - p0.x, state.v - p0.v);
        let tau = t1 - t0;
        let (s, c) = (wd * tau).sin_cos();
        let e = (-sigma * tau).exp();
        let h = e * (h0 * c + (dh0 + sigma * h0) / wd * s);
        let dh = e * (dh0 * c - (sigma * dh0 + omega0_sq * h0) / wd * s);
        let p1 = self.particular(t1);
        Kinematics {
            x: p1.x + h,
            v: p1.v + dh,
        }
    }
}
