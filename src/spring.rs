//! The slider against a spring: the spring method of measuring an inertia
//! motor's force (the paper's section 5; docs/model.md section 17).
//!
//! ```text
//! slider: m_s a_S = F_f + m_s g_t - F_spring
//! tied spring:       F_spring = F_p + k (x_S - x_p) + b v_S     (always)
//! free-ended spring: F_spring = k (x_S - x_gap)  while x_S >= x_gap, else 0
//! stick (v_S = v_R): held while |F_f| = |m_s (a_R - g_t) + F_spring| <= mu_0 F_c
//! ```
//!
//! Positions are the slider's from its start (`x_S = 0` at `t = 0`); the
//! tied spring's preload `F_p` is its force there (`x_p = 0`). The spring is
//! massless. A free end carries no damping (a damped free end would need
//! the end's own state), so it is refused.
//!
//! In slip the slider in contact is a damped oscillator under a constant
//! force,
//!
//! ```text
//! m_s x'' + b x' + k x = F_mode,   F_mode = ±mu_d F_c + m_s g_t - F_p      (tied)
//!                                  F_mode = ±mu_d F_c + m_s g_t + k x_gap  (free end, in contact)
//! ```
//!
//! so `x_S = F_mode / k + y(s)` with `y'' + 2 sigma y' + omega_0^2 y = 0`,
//! `sigma = b / (2 m_s)`, `omega_0^2 = k / m_s`: the closed form the exact
//! engine's modes are made of ([`Spring::slip_equilibrium`],
//! [`Spring::oscillator`]).
//!
//! With the rod at rest, a tied spring without damping and `g_t = F_p = 0`
//! is the Coulomb-damped oscillator: each half swing moves the turning
//! point `2 mu_d F_c / k` towards the origin (`4 mu_d F_c / k` per cycle),
//! and the slider stops at the first turning point inside the band
//! `|k x| <= mu_0 F_c` ([`coulomb_turning_points`]).

use crate::error::{Num, ParamError};

/// How the spring meets the slider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpringEnd {
    /// Tied to the slider, pulling and pushing; `preload` (N) is its force
    /// at the slider's start position.
    Tied {
        /// `F_p` (N).
        preload: f64,
    },
    /// A free end `gap` (m) ahead of the slider's start: it pushes only
    /// while compressed.
    Free {
        /// `x_gap` (m), at least 0.
        gap: f64,
    },
}

/// A spring against the slider (`[spring]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// `k` (N/m), positive.
    pub stiffness: f64,
    /// `b` (N s/m), at least 0; only with a tied spring.
    pub damping: f64,
    /// Tied or free-ended.
    pub end: SpringEnd,
}

impl Spring {
    /// Checks the fields; an error names the field (`spring.stiffness`,
    /// ...) and the value.
    pub fn validate(&self) -> Result<(), ParamError> {
        ParamError::positive("spring.stiffness", self.stiffness)?;
        ParamError::non_negative("spring.damping", self.damping)?;
        match self.end {
            SpringEnd::Tied { preload } => {
                ParamError::finite("spring.preload", preload)?;
            }
            SpringEnd::Free { gap } => {
                ParamError::non_negative("spring.gap", gap)?;
                if self.damping != 0.0 {
                    return Err(ParamError::out_of_range(
                        "spring.damping",
                        self.damping,
                        format!(
                            "must be 0 for a free-ended spring (spring.tied = false): a damped \
                             free end would need the end's own state; tie the spring or set \
                             damping = 0 (stiffness {})",
                            Num(self.stiffness)
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// True if the spring pushes on the slider at position `x` (m): always
    /// when tied, at `x >= x_gap` for a free end.
    pub fn in_contact(&self, x: f64) -> bool {
        match self.end {
            SpringEnd::Tied { .. } => true,
            SpringEnd::Free { gap } => x >= gap,
        }
    }

    /// `F_spring` (N) at slider position `x` (m) and velocity `v` (m/s).
    pub fn force(&self, x: f64, v: f64) -> f64 {
        match self.end {
            SpringEnd::Tied { preload } => preload + self.stiffness * x + self.damping * v,
            SpringEnd::Free { gap } if x >= gap => self.stiffness * (x - gap),
            SpringEnd::Free { .. } => 0.0,
        }
    }

    /// `F_spring` (N) at `x` (m) and `v` (m/s) in contact, a free end's
    /// compression taken as `x - x_gap` whatever its sign: the force law of
    /// the contact mode.
    pub fn force_in_contact(&self, x: f64, v: f64) -> f64 {
        match self.end {
            SpringEnd::Tied { preload } => preload + self.stiffness * x + self.damping * v,
            SpringEnd::Free { gap } => self.stiffness * (x - gap),
        }
    }

    /// The slider's rest position (m) in contact under the constant force
    /// `f` (N, friction and `m_s g_t`): where `f = F_spring` at `v = 0`.
    pub fn slip_equilibrium(&self, f: f64) -> f64 {
        match self.end {
            SpringEnd::Tied { preload } => (f - preload) / self.stiffness,
            SpringEnd::Free { gap } => gap + f / self.stiffness,
        }
    }

    /// The oscillator of the slider of mass `m` (kg) on the spring.
    pub fn oscillator(&self, m: f64) -> SliderOscillator {
        SliderOscillator {
            sigma: self.damping / (2.0 * m),
            omega0: (self.stiffness / m).sqrt(),
        }
    }
}

/// The slider on the spring as a damped oscillator,
/// `y'' + 2 sigma y' + omega_0^2 y = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderOscillator {
    /// `sigma = b / (2 m_s)` (1/s).
    pub sigma: f64,
    /// `omega_0 = sqrt(k / m_s)` (rad/s).
    pub omega0: f64,
}

/// The turning points of the Coulomb-damped oscillator released at rest
/// at `x0` (m) on an undamped tied spring of stiffness `k` with the rod
/// at rest, sliding friction `f_d = mu_d F_c` and static `f_0 = mu_0 F_c`
/// (N): `x0` and then each next one `-(x_i - sign(x_i) 2 f_d / k)`, up to
/// and including the first with `|k x| <= f_0` (where the slider stays)
/// or a swing that cannot start (`|k x_i| <= f_d` after release needs no
/// further swing). A closed form for checks.
pub fn coulomb_turning_points(x0: f64, k: f64, f_d: f64, f_0: f64) -> Vec<f64> {
    let mut points = vec![x0];
    let mut x = x0;
    while (k * x).abs() > f_0 {
        // Sliding towards the origin, friction against the motion: the
        // swing is symmetric about the shifted centre sign(x) f_d / k.
        let centre = x.signum() * f_d / k;
        let next = 2.0 * centre - x;
        if next.signum() == x.signum() || next == 0.0 {
            // Stops on the same side (within the band by construction).
            points.push(next);
            break;
        }
        x = next;
        points.push(x);
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_free_end_with_damping_is_refused_naming_the_field() {
        let s = Spring {
            stiffness: 1e3,
            damping: 0.1,
            end: SpringEnd::Free { gap: 0.0 },
        };
        let e = s.validate().unwrap_err().to_string();
        assert!(e.starts_with("spring.damping = 0.1"), "{e}");
        assert!(!e.contains('\n'));
    }

    #[test]
    fn the_force_is_continuous_where_the_free_end_is_met() {
        let s = Spring {
            stiffness: 2e4,
            damping: 0.0,
            end: SpringEnd::Free { gap: 1e-5 },
        };
        assert_eq!(s.force(1e-5, 1.0), 0.0);
        assert_eq!(s.force(0.5e-5, 1.0), 0.0);
        // k (x - gap) at 1 um past the end.
        assert!((s.force(1.1e-5, 0.0) - 2e4 * 1e-6).abs() < 1e-15);
    }

    #[test]
    fn coulomb_amplitude_falls_by_four_friction_lengths_per_cycle() {
        // k = 1 kN/m, mu_d F_c = 0.1568 N, mu_0 F_c = 0.1736 N, released at
        // 1 mm: each half swing loses 2 f_d / k = 0.3136 mm.
        let (k, f_d, f_0) = (1e3, 0.1568, 0.1736);
        let p = coulomb_turning_points(1e-3, k, f_d, f_0);
        for w in p.windows(3) {
            let loss = w[0].abs() - w[2].abs();
            if (k * w[2]).abs() > f_0 {
                assert!((loss - 4.0 * f_d / k).abs() < 1e-15, "{p:?}");
            }
        }
        let last = *p.last().unwrap();
        assert!((k * last).abs() <= f_0, "{p:?}");
    }
}
