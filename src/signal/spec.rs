//! What a scene asks for as the rod signal ([`SignalSpec`]) and the rules
//! its values obey ([`SignalSpec::validate`]; docs/interface.md
//! `[signal]`, `[voltage]`).

use super::{Drive, IdealShape};
use crate::error::ParamError;

/// What a scene asks for as the rod signal (validated by [`SignalSpec::validate`]).
#[derive(Debug, Clone, PartialEq)]
pub enum SignalSpec {
    /// The ideal signal (11).
    Ideal(IdealShape),
    /// The Fourier approximation of the ideal signal with `harmonics` terms.
    Fourier {
        /// The ideal signal being approximated.
        shape: IdealShape,
        /// Number of harmonics `n` (>= 1).
        harmonics: usize,
        /// Apply Lanczos sigma factors (15).
        sigma: bool,
    },
    /// An explicit harmonic series (8): `x_R = sum d_k sin(k w_0 t + phi_k)`.
    Harmonics {
        /// Fundamental frequency `f_0` in Hz.
        frequency: f64,
        /// `d_k` for `k = 1..`, in m.
        amplitudes: Vec<f64>,
        /// `phi_k` for `k = 1..`, in rad.
        phases: Vec<f64>,
        /// Scale all amplitudes so that max - min equals this stroke (m).
        scale_to_stroke: Option<f64>,
        /// Shift so that the minimum lies at `t = 0` with value 0.
        shift_to_minimum: bool,
    },
    /// The steady response of a driven rod's friction-free actuator to a
    /// voltage given in the scene's `[voltage]` table (docs/model.md
    /// section 16), as the scene computes it:
    /// `x_R = offset + sum_k (cosines_k cos(k w_0 t) + sines_k sin(k w_0 t))`,
    /// not shifted, not scaled.
    Response {
        /// Fundamental frequency `f_0` in Hz, the voltage's.
        frequency: f64,
        /// The constant term `x_0` (m).
        offset: f64,
        /// `A_k` for `k = 1..`, multiplying `cos(k w_0 t)` (m).
        cosines: Vec<f64>,
        /// `B_k` for `k = 1..`, multiplying `sin(k w_0 t)` (m).
        sines: Vec<f64>,
    },
}

/// Largest number of harmonics accepted: the certified root finder
/// (`numerics::trig_roots`, `O(n^2)`) is tested up to this degree.
pub const MAX_HARMONICS: usize = 256;

impl SignalSpec {
    /// The paper's default signal: `n = 2`, `sqrt(kappa) = 6`, sigma factors,
    /// continuous, stroke 25 um.
    pub fn paper_default() -> Self {
        Self::fourier(25e-6, 36.0, 2, true)
    }

    /// The Fourier approximation (8) of the continuous ideal signal with
    /// `n` harmonics, stroke `stroke` (m) and `kappa`.
    pub fn fourier(stroke: f64, kappa: f64, n: usize, sigma: bool) -> Self {
        SignalSpec::Fourier {
            shape: IdealShape::with_kappa(stroke, kappa, 1.0),
            harmonics: n,
            sigma,
        }
    }

    /// The ideal signal (11) with stroke `stroke` (m), `kappa` and
    /// `duty = t_1 / T`.
    pub fn ideal(stroke: f64, kappa: f64, duty: f64) -> Self {
        SignalSpec::Ideal(IdealShape::with_kappa(stroke, kappa, duty))
    }

    /// Checks every value; errors name the scene field.
    pub fn validate(&self) -> Result<(), ParamError> {
        match self {
            SignalSpec::Ideal(shape) => {
                if let Drive::FMax(f) = shape.drive {
                    return Err(ParamError::out_of_range(
                        "signal.f_max",
                        f,
                        "not used with kind = \"ideal\" (its spectrum has no highest \
                         frequency); give signal.frequency",
                    ));
                }
                shape.validate()
            }
            SignalSpec::Fourier {
                shape, harmonics, ..
            } => {
                shape.validate()?;
                if *harmonics == 0 || *harmonics > MAX_HARMONICS {
                    return Err(ParamError::out_of_range(
                        "signal.harmonics",
                        *harmonics as f64,
                        format!("must be an integer from 1 to {MAX_HARMONICS}"),
                    ));
                }
                Ok(())
            }
            SignalSpec::Harmonics {
                frequency,
                amplitudes,
                phases,
                scale_to_stroke,
                ..
            } => {
                ParamError::positive("signal.frequency", *frequency)?;
                if amplitudes.is_empty() || amplitudes.len() > MAX_HARMONICS {
                    return Err(ParamError::out_of_range(
                        "signal.amplitudes",
                        amplitudes.len() as f64,
                        format!("must list from 1 to {MAX_HARMONICS} amplitudes"),
                    ));
                }
                if phases.len() != amplitudes.len() {
                    return Err(ParamError::Inconsistent {
                        field: "signal.phases".to_owned(),
                        reason: format!(
                            "has {} entries but signal.amplitudes has {}",
                            phases.len(),
                            amplitudes.len()
                        ),
                    });
                }
                for (k, d) in amplitudes.iter().enumerate() {
                    ParamError::non_negative(&format!("signal.amplitudes[{k}]"), *d)?;
                }
                for (k, phi) in phases.iter().enumerate() {
                    ParamError::finite(&format!("signal.phases[{k}]"), *phi)?;
                }
                if amplitudes.iter().all(|d| *d == 0.0) {
                    return Err(ParamError::Inconsistent {
                        field: "signal.amplitudes".to_owned(),
                        reason: "all amplitudes are zero: the rod does not move".to_owned(),
                    });
                }
                if let Some(stroke) = scale_to_stroke {
                    ParamError::positive("signal.stroke", *stroke)?;
                }
                Ok(())
            }
            SignalSpec::Response {
                frequency,
                offset,
                cosines,
                sines,
            } => {
                // Built from a validated [voltage]; what fails here is the
                // response itself (an overflow), named by its table.
                ParamError::positive("voltage.frequency", *frequency)?;
                if cosines.is_empty() || cosines.len() > MAX_HARMONICS {
                    return Err(ParamError::out_of_range(
                        "voltage.amplitudes",
                        cosines.len() as f64,
                        format!("must list from 1 to {MAX_HARMONICS} amplitudes"),
                    ));
                }
                if sines.len() != cosines.len() {
                    return Err(ParamError::Inconsistent {
                        field: "voltage.phases".to_owned(),
                        reason: format!(
                            "the response has {} sines for {} cosines",
                            sines.len(),
                            cosines.len()
                        ),
                    });
                }
                let finite = std::iter::once(offset)
                    .chain(cosines)
                    .chain(sines)
                    .all(|x| x.is_finite());
                if !finite {
                    return Err(ParamError::Inconsistent {
                        field: "voltage".to_owned(),
                        reason: "the actuator's response to the voltage is beyond floating \
                                 point (alpha u / c overflows)"
                            .to_owned(),
                    });
                }
                if cosines.iter().chain(sines).all(|x| *x == 0.0) {
                    return Err(ParamError::Inconsistent {
                        field: "voltage.amplitudes".to_owned(),
                        reason: "the actuator's response has no harmonic: the rod does not move"
                            .to_owned(),
                    });
                }
                Ok(())
            }
        }
    }
}
