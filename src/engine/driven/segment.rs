//! One mode's closed-form motion and its event functions
//! (docs/model.md section 16): the rod's state after `s` seconds, the
//! relative velocity in slip and the stuck system's acceleration as
//! exponential-trigonometric functions of `s`, and their first zeros.

use super::super::{Direction, Kinematics, WorkCounters};
use super::slider::SliderMotion;
use crate::actuator::ModeResponse;
use crate::numerics::exp_trig::{Crossing, DampedOscillator, ExpTrig, Start};
use crate::signal::FourierSignal;

/// A mode's particular solution and free oscillation, ready to build event
/// functions.
#[derive(Debug, Clone)]
pub(super) struct ModeFunctions {
    particular: FourierSignal,
    sigma: f64,
    omega0: f64,
    /// The rod has a free oscillation (a driven rod); without (a prescribed
    /// rod) it follows the particular solution, its free part zero.
    has_free: bool,
    w: f64,
    /// Velocity of the particular solution: cos and sin coefficients.
    vel: [Vec<f64>; 2],
    /// Acceleration of the particular solution: cos and sin coefficients.
    acc: [Vec<f64>; 2],
}

/// The next start of a search after a touch or an inward crossing at `s`
/// found from `from`: `s`, or a few ulps of the time beyond `from` where
/// the finder reported its own start again, so that the search always
/// moves on.
fn progress(from: f64, s: f64, time: f64) -> f64 {
    s.max(from + 4.0 * f64::EPSILON * time)
}

/// The tolerance within which the stuck system's acceleration counts as
/// on a band edge in the stick search, for `upper = a_st - a_0^+` and
/// `lower = a_st - a_0^-` over `span`: four times their rounding bound (the
/// root finder's own floor).
pub(super) fn band_tolerance(upper: &ExpTrig, lower: &ExpTrig, span: f64) -> f64 {
    4.0 * upper.larger_rounding_level(lower, span)
}

/// How a stick phase ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum StickExit {
    /// At the period end, still stuck.
    PeriodEnd,
    /// The stuck system's acceleration leaves the band after `s` seconds,
    /// towards slip `to`.
    Leaves { s: f64, to: Direction },
}

/// The first zero of `v_rel` in a slip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SlipZero {
    /// Seconds after the segment start.
    pub s: f64,
    /// `v_rel` only touches zero (a grazing).
    pub tangency: bool,
    /// A bound on the error of `s` (s).
    pub time_error: f64,
}

impl ModeFunctions {
    pub(super) fn new(response: &ModeResponse) -> Self {
        let p = response.particular.clone();
        let w = p.omega();
        let c = p.coefficients();
        let n = c.cosines.len();
        let mut vel = [Vec::with_capacity(n), Vec::with_capacity(n)];
        let mut acc = [Vec::with_capacity(n), Vec::with_capacity(n)];
        for (k, (a, b)) in c.cosines.iter().zip(c.sines).enumerate() {
            let kw = (k + 1) as f64 * w;
            // x = a cos + b sin; v = kw (b cos - a sin); a = -(kw)^2 (a cos + b sin).
            vel[0].push(kw * b);
            vel[1].push(-kw * a);
            acc[0].push(-kw * kw * a);
            acc[1].push(-kw * kw * b);
        }
        Self {
            particular: p,
            sigma: response.sigma,
            omega0: response.omega0,
            has_free: response.free,
            w,
            vel,
            acc,
        }
    }

    /// These functions with the particular solution's constant moved by
    /// `shift` (m): a constant force `c_m shift` more in the mode's
    /// equation, `c_m` its stiffness.
    pub(super) fn shifted(&self, shift: f64) -> Self {
        let p = &self.particular;
        let c = p.coefficients();
        Self {
            particular: FourierSignal::from_coefficients(
                p.period(),
                p.offset() + shift,
                c.cosines.to_vec(),
                c.sines.to_vec(),
            ),
            ..self.clone()
        }
    }

    /// The particular solution.
    pub(super) fn particular(&self) -> &FourierSignal {
        &self.particular
    }

    /// The particular solution's velocity: cos and sin coefficients.
    pub(super) fn velocity_coefficients(&self) -> &[Vec<f64>; 2] {
        &self.vel
    }

    /// The particular solution's acceleration: cos and sin coefficients.
    pub(super) fn acceleration_coefficients(&self) -> &[Vec<f64>; 2] {
        &self.acc
    }

    /// The free oscillation at the segment start `tau` for the rod state
    /// `rod`.
    pub(super) fn free_at(&self, tau: f64, rod: Kinematics) -> DampedOscillator {
        self.free(tau, rod)
    }

    /// The free oscillation `h` at the segment start `tau` for the rod
    /// state `rod`.
    fn free(&self, tau: f64, rod: Kinematics) -> DampedOscillator {
        if !self.has_free {
            return DampedOscillator {
                sigma: self.sigma,
                omega0: self.omega0,
                y0: 0.0,
                y1: 0.0,
            };
        }
        let p = self.particular.state(tau);
        DampedOscillator {
            sigma: self.sigma,
            omega0: self.omega0,
            y0: rod.x - p.x,
            y1: rod.v - p.v,
        }
    }

    /// The rod `s` seconds after `tau`, from `rod` at `tau`.
    pub(super) fn rod_at(&self, tau: f64, rod: Kinematics, s: f64) -> Kinematics {
        if s == 0.0 {
            return rod;
        }
        let [h, dh, _] = self.free(tau, rod).eval(s);
        let p = self.particular.state(tau + s);
        Kinematics {
            x: p.x + h,
            v: p.v + dh,
        }
    }

    /// `a_R(tau + s) - level` of this mode for the rod state `(x, v)` at
    /// `tau`: in stick the stuck system's acceleration against a band edge,
    /// in slip `v_rel' = a_R - a_s`.
    pub(super) fn band_function(&self, tau: f64, x: f64, v: f64, level: f64) -> ExpTrig {
        let [f] = self.band_functions(tau, x, v, [level]);
        f
    }

    /// [`ModeFunctions::band_function`] at each of `levels`, the free
    /// oscillation computed once.
    pub(super) fn band_functions<const N: usize>(
        &self,
        tau: f64,
        x: f64,
        v: f64,
        levels: [f64; N],
    ) -> [ExpTrig; N] {
        let free = self.free(tau, Kinematics { x, v });
        let acceleration = free.derivative().derivative();
        levels.map(|level| ExpTrig {
            poly: [-level, 0.0, 0.0],
            w: self.w,
            phi: tau,
            a: self.acc[0].clone(),
            b: self.acc[1].clone(),
            osc: [Some(acceleration), None],
        })
    }

    /// `[a_st - a_0^+, a_st - a_0^-]` for the rod state `(x, v)` at `tau`
    /// and the band `[lo, hi]` (this being the stick mode's functions): the
    /// functions the stick search follows, whose values at `s = 0` also
    /// decide the band where a stick phase may start.
    pub(super) fn edge_functions(
        &self,
        tau: f64,
        x: f64,
        v: f64,
        [lo, hi]: [f64; 2],
    ) -> [ExpTrig; 2] {
        self.band_functions(tau, x, v, [hi, lo])
    }

    /// The zeros of the rod's acceleration in `(0, span)` after `tau`
    /// (this being the stick mode's functions): where a stuck slider's
    /// velocity has its extrema.
    pub(super) fn acceleration_zeros(&self, tau: f64, rod: Kinematics, span: f64) -> Vec<f64> {
        let f = self.band_function(tau, rod.x, rod.v, 0.0);
        let tol = f.eval_error_bound(span)[0];
        let mut zeros = Vec::new();
        let (mut from, mut start) = (0.0, Start::Clear);
        while let Some(c) = f.first_zero(from, span, tol, start) {
            let s = c.s();
            if s <= from || s >= span {
                break;
            }
            zeros.push(s);
            from = s;
            start = Start::AfterEvent;
        }
        zeros
    }

    /// `v_rel(s) = v_R(tau + s) - v_S - a_s s`.
    fn v_rel(&self, tau: f64, rod: Kinematics, slider: &SliderMotion) -> ExpTrig {
        let (poly, slider_osc) = slider.negative_velocity();
        // The rod's free oscillation (none for a prescribed rod) and a
        // slider's on a spring.
        let rod_osc = self.has_free.then(|| self.free(tau, rod).derivative());
        let osc = [rod_osc.or(slider_osc), rod_osc.and(slider_osc)];
        ExpTrig {
            poly,
            w: self.w,
            phi: tau,
            a: self.vel[0].clone(),
            b: self.vel[1].clone(),
            osc,
        }
    }

    /// Whether the rod has a free oscillation of its own.
    pub(super) fn has_free(&self) -> bool {
        self.has_free
    }

    /// Where a stick phase that starts at `tau` with the rod at `rod` ends
    /// within `span`: the first time the stuck system's acceleration leaves
    /// `[lo, hi]`. Touching an edge from inside, or crossing back in,
    /// keeps the slider stuck.
    ///
    /// `[upper, lower]` are `a_st - a_0^+` and `a_st - a_0^-` over the
    /// stick from `tau` ([`ModeFunctions::edge_functions`], or with a
    /// spring's force the slider's `stuck_functions`).
    pub(super) fn stick_exit(
        [upper, lower]: [ExpTrig; 2],
        tau: f64,
        span: f64,
        counters: &mut WorkCounters,
    ) -> StickExit {
        let tol = band_tolerance(&upper, &lower, span);
        // A stick phase that starts on an edge (within `tol`) moving inwards
        // or along it starts at that decision: the search goes on from it.
        // One that starts there moving outwards was decided inside the band
        // beyond the value's rounding (the engine's band decision): it ends
        // where `a_st` reaches the edge, too close for the search to
        // resolve, so by the Taylor polynomial of `a_st` at the start; if
        // that turns back before the edge, the start is a touch.
        let mut starts = [Start::Clear; 2];
        for (k, (f, to)) in [(&upper, Direction::Forward), (&lower, Direction::Backward)]
            .into_iter()
            .enumerate()
        {
            let [value, slope, curvature] = f.eval(0.0);
            if value.abs() > tol {
                continue;
            }
            starts[k] = Start::AfterEvent;
            let eta1 = f.eval_error_bound(0.0)[1];
            // Depth inside the band, outward slope and curvature.
            let sign = to.sign();
            let (depth, p, q) = ((-sign * value).max(0.0), sign * slope, sign * curvature);
            let outward = p > eta1 || (p.abs() <= eta1 && q > 0.0);
            let disc = p * p + 2.0 * q * depth;
            if outward && disc >= 0.0 {
                // The smaller positive root of -depth + p s + q s^2 / 2.
                let s = 2.0 * depth / (p + disc.sqrt());
                return StickExit::Leaves { s: s.min(span), to };
            }
        }
        let mut from = 0.0;
        loop {
            counters.root_iterations += 1;
            let up = upper.first_zero(from, span, tol, starts[0]);
            let down = lower.first_zero(from, span, tol, starts[1]);
            // After a touch or an inward crossing the search goes on from
            // it, which it has just handled.
            starts = [Start::AfterEvent; 2];
            let at = |c: &Option<Crossing>| match c {
                Some(Crossing::Transversal { s, .. } | Crossing::Tangency { s }) => *s,
                None => f64::INFINITY,
            };
            let (first, leaves) = if at(&up) <= at(&down) {
                (up, Direction::Forward)
            } else {
                (down, Direction::Backward)
            };
            match first {
                None => return StickExit::PeriodEnd,
                Some(Crossing::Transversal { s, rising }) => {
                    let outward = match leaves {
                        Direction::Forward => rising,
                        Direction::Backward => !rising,
                    };
                    if outward {
                        return StickExit::Leaves { s, to: leaves };
                    }
                    from = progress(from, s, tau + span);
                }
                Some(Crossing::Tangency { s }) => from = progress(from, s, tau + span),
            }
            if from >= span {
                return StickExit::PeriodEnd;
            }
        }
    }

    /// The first zero of `v_rel` within `span` after `tau`, for a slider
    /// at velocity `v_s` with slip acceleration `a_s`; `departure`: the
    /// slip leaves `v_rel = 0` at `tau`, which is not a zero again.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn slip_zero(
        &self,
        tau: f64,
        rod: Kinematics,
        slider: &SliderMotion,
        span: f64,
        tol_v: f64,
        (dir, departure): (Direction, bool),
        counters: &mut WorkCounters,
    ) -> Option<SlipZero> {
        let f = self.v_rel(tau, rod, slider);
        counters.root_iterations += 1;
        // A departure from a zero of v_rel at rounding level is left by
        // the finder's open start; only one that starts farther (a grazing
        // the slider slides on from) is skipped as the event it was. A
        // v_rel that turns back within tol_v is then a tangency: a grazing.
        let eta = f.eval_error_bound(span)[0];
        let rounding = 4.0 * eta;
        let start = if departure && f.eval(0.0)[0].abs() > rounding {
            Start::AfterEvent
        } else {
            Start::Clear
        };
        let time_error = 4.0 * f64::EPSILON * (tau + span);
        let found = f.first_zero(0.0, span, tol_v, start);
        // The first event must end the slip the way it goes: a zero where
        // v_rel falls in forward slip (rises in backward), or v_rel keeps
        // its sign to the end. Otherwise v_rel turned back within the
        // departure and crossed zero there: the first extremum of v_rel
        // (a zero of v_rel' = a_R - a_s) decides, a grazing where
        // |v_rel| <= tol_v, else the search goes on from it.
        let expected = dir.sign();
        let consistent = match found {
            None => f.eval(span)[0] * expected >= -tol_v,
            Some(Crossing::Transversal { rising, .. }) => rising == (expected < 0.0),
            Some(Crossing::Tangency { .. }) => true,
        };
        let found = if consistent {
            found
        } else {
            counters.root_iterations += 1;
            // v_rel' = a_R - a_S.
            let slope = f.derivative();
            let tol = 4.0 * slope.eval_error_bound(span)[0];
            match slope.first_zero(0.0, span, tol, Start::Clear) {
                Some(c) if f.eval(c.s())[0].abs() <= tol_v => Some(Crossing::Tangency { s: c.s() }),
                Some(c) => f.first_zero(c.s(), span, tol_v, Start::Clear),
                None => found,
            }
        };
        found.map(|c| match c {
            // Where v_rel is known to within its rounding level eta only,
            // its zero is known to within eta / |v_rel'| beyond the
            // solver's own tolerance.
            Crossing::Transversal { s, .. } => SlipZero {
                s,
                tangency: false,
                time_error: time_error + {
                    let slope = f.eval(s)[1].abs();
                    if slope > 0.0 {
                        eta / slope
                    } else {
                        f64::INFINITY
                    }
                },
            },
            Crossing::Tangency { s } => SlipZero {
                s,
                tangency: true,
                time_error,
            },
        })
    }
}
