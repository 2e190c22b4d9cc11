//! A mock engine with a known period map, shared by the tests of the
//! fixed-point logic.

use stickslip::error::SimulationError;
use stickslip::signal::Signal;
use stickslip::{
    engine::Direction, engine::Mode, engine::PeriodEngine, engine::PeriodStart,
    engine::WorkCounters,
};
use stickslip::{engine::Observer, engine::PeriodEnd};

/// A period map with three fixed points, for the analysis with any engine:
/// in units `x = v / a`, `g(x) = P(x) - x` is 0.2 (rising gently) up to
/// `x = 0.5`, falls linearly to 0 at `x = 1`, is negative on `(1, 2)`,
/// positive on `(2, 2.5)` and negative beyond: fixed points 1, 2 and 2.5
/// (with `close`: 1, 1.004 and 1.005). `P' = 1 + g' >= 0.59` everywhere,
/// so `P` is monotone, as the event engine's map is. A search from rest is
/// sent by Newton's step out of its bracket and bisects onto the far fixed
/// point; the orbit from rest stops at 1.
pub struct ThreeFixedPoints {
    pub signal: Signal,
    pub a: f64,
    pub periods: u64,
    /// Fixed points at 1, 1.004 and 1.005 (a pair close to the far one)
    /// instead of 1, 2 and 2.5.
    pub close: bool,
}

impl ThreeFixedPoints {
    fn g(&self, x: f64) -> (f64, f64) {
        if self.close && x > 1.0 {
            return if x <= 1.004 {
                (-50.0 * (x - 1.0) * (1.004 - x), -50.0 * (2.004 - 2.0 * x))
            } else if x <= 1.005 {
                (50.0 * (x - 1.004) * (1.005 - x), 50.0 * (2.009 - 2.0 * x))
            } else {
                (-0.3 * (x - 1.005), -0.3)
            };
        }
        if x <= 0.5 {
            (0.2 + 0.01 * x, 0.01)
        } else if x <= 1.0 {
            (0.41 * (1.0 - x), -0.41)
        } else if x <= 2.0 {
            (-0.2 * (x - 1.0) * (2.0 - x), -0.2 * (3.0 - 2.0 * x))
        } else if x <= 2.5 {
            (0.2 * (x - 2.0) * (2.5 - x), 0.2 * (4.5 - 2.0 * x))
        } else {
            (-0.3 * (x - 2.5), -0.3)
        }
    }
}

impl PeriodEngine for ThreeFixedPoints {
    fn signal(&self) -> &Signal {
        &self.signal
    }

    fn run_period<O: Observer>(
        &mut self,
        period: u64,
        start: PeriodStart,
        observer: &mut O,
    ) -> Result<PeriodEnd, SimulationError> {
        self.periods += 1;
        let x = start.velocity / self.a;
        let (g, dg) = self.g(x);
        let end = PeriodEnd {
            period,
            step: start.velocity * self.signal.period(),
            velocity: (x + g) * self.a,
            mode: Mode::Slip(Direction::Forward),
            map_derivative: 1.0 + dg,
        };
        observer.period_end(&end);
        Ok(end)
    }

    fn counters(&self) -> WorkCounters {
        WorkCounters {
            periods: self.periods,
            ..WorkCounters::default()
        }
    }

    fn zero_velocity_tolerance(&self) -> f64 {
        0.0
    }

    fn last_velocity_uncertainty(&self) -> Option<f64> {
        Some(0.0)
    }
}
