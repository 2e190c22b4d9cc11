//! Numerical tools with no physics in them; everything above builds on
//! them and they depend on nothing else in the crate.
//!
//! * `trig_roots`: every root of a real trigonometric polynomial in its
//!   period, certified (none missed), in `O(n^2)`.
//! * `bracket`: one root in a sign-changing bracket, safeguarded Newton.
//! * `exp_trig`: the first zero of a quadratic plus a harmonic series plus
//!   one or two free damped oscillators after a given time, certified
//!   (none missed).
//! * `spectral`: the spectral radius of a small matrix, `None` rather than
//!   a run without end on input the Schur iteration cannot take.
//! * `compensated`: Neumaier's compensated sum.
//! * `contour`: contour lines and superlevel regions of gridded values
//!   (marching squares).
//! * `line_fit`: least-squares lines and log-log slopes.
//! * `quadrature`: Gauss-Legendre rules.
//! * `dual`: forward-mode derivatives (dual numbers).
//! * `power_of_two`: exact scaling by powers of two.
//! * `taylor`: Taylor coefficients of a harmonic series about a point.

pub(crate) mod bracket;
mod compensated;
pub(crate) mod contour;
pub(crate) mod dual;
pub(crate) mod exp_trig;
pub(crate) mod line_fit;
mod power_of_two;
pub(crate) mod quadrature;
pub(crate) mod spectral;
pub(crate) mod taylor;
pub(crate) mod trig_roots;

pub use compensated::CompensatedSum;
pub use trig_roots::{LevelRoots, RootsAndEnvelope, TrigPoly, WithDerivative, WithTwoDerivatives};
