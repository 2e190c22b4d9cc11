//! Numerical tools with no physics in them; everything above builds on
//! them and they depend on nothing else in the crate.
//!
//! * [`trig_roots`]: every root of a real trigonometric polynomial in its
//!   period, certified (none missed), in `O(n^2)`.
//! * [`bracket`]: one root in a sign-changing bracket, safeguarded Newton.
//! * [`compensated`]: Neumaier's compensated sum.
//! * [`line_fit`]: least-squares lines and log-log slopes.

pub mod bracket;
pub mod compensated;
pub mod line_fit;
pub mod trig_roots;

pub use compensated::CompensatedSum;
