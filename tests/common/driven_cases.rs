//! Random driven scenes and their runs, for the dense scans of
//! `driven_scan.rs` (`tests/driven_events.rs`, `examples/driven_events.rs`):
//! a scene ([`DrivenCase`]) is built through the library (motor, signal,
//! the voltage designed for it, the driven rod) and run for a few periods
//! from rest with [`DrivenEngine`], every segment and event recorded
//! ([`Record`]).

#![allow(dead_code)] // each includer uses a part

use stickslip::MotorParams;
use stickslip::actuator::{DrivenRod, DrivenSpec, RealActuator, Voltage};
use stickslip::engine::{
    DrivenEngine, Event, EventOptions, Observer, PeriodEngine, PeriodStart, Segment,
};
use stickslip::motor::Motor;
use stickslip::power::ActuatorParams;
use stickslip::signal::{Signal, SignalSpec};

/// A small deterministic generator (SplitMix64).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.uniform(0.0, 1.0) < p
    }

    /// Uniform in `1..=n`.
    pub fn upto(&mut self, n: usize) -> usize {
        1 + (self.next() % n as u64) as usize
    }
}

/// A driven scene: motor, signal, actuator.
#[derive(Debug, Clone)]
pub struct DrivenCase {
    pub motor: MotorParams,
    pub signal: SignalSpec,
    pub design: ActuatorParams,
    pub spec: DrivenSpec,
}

impl DrivenCase {
    /// A random scene: `a_0` from 30 to 1000 m/s^2, slider mass 0.3 to 10 g
    /// (0.1 to 3 times the actuator's), `mu_d / mu_0` in `[0.2, 1]` (15 %
    /// exactly 1, 5 % `mu_d = 0`), `g_t` within `0.8 a_d` half the time;
    /// `kappa` from 0.5 to 20 (log-uniform; 40 % of the scenes below 1.5);
    /// a `fourier` signal (60 %, with or without sigma factors) or random
    /// `harmonics` (amplitudes falling like `1/k^2`) shifted to their
    /// minimum, at the frequency of the `fourier` signal of that `kappa`,
    /// `n` from 1 to 8; each real actuator parameter as designed or up to
    /// 20 % off; the reaction on in two cases of three.
    pub fn random(rng: &mut Rng) -> Self {
        let a0 = 10f64.powf(rng.uniform(1.5, 3.0));
        let slider_mass = 10f64.powf(rng.uniform(-3.5, -2.0));
        let mu_static = rng.uniform(0.05, 0.5);
        let ratio = if rng.chance(0.15) {
            1.0
        } else if rng.chance(0.06) {
            0.0
        } else {
            rng.uniform(0.2, 1.0)
        };
        let contact_force = a0 * slider_mass / mu_static;
        let a_d = ratio * a0;
        let g_t = if rng.chance(0.5) {
            0.0
        } else {
            rng.uniform(-0.8, 0.8) * a_d
        };
        let motor = MotorParams {
            slider_mass,
            contact_force,
            mu_static,
            mu_dynamic: ratio * mu_static,
            extra_acceleration: g_t,
        };
        // Stick phases need a low kappa: two scenes in five below 1.5.
        let top = if rng.chance(0.4) { 1.5f64 } else { 20.0 };
        let kappa = 10f64.powf(rng.uniform(0.5f64.log10(), top.log10()));
        let n = rng.upto(8);
        let stroke = 25e-6 * 10f64.powf(rng.uniform(-0.5, 0.5));
        let fourier = SignalSpec::fourier(stroke, kappa, n, rng.chance(0.5));
        let signal = if rng.chance(0.6) {
            fourier
        } else {
            let period = Motor::new(motor)
                .ok()
                .and_then(|m| Signal::build(&fourier, &m).ok())
                .map_or(1e-3, |s| s.period());
            // Falling like the ideal signal's, 1/k^2, so that kappa
            // stays what it says.
            let mut amplitudes: Vec<f64> = (1..=n)
                .map(|k| rng.uniform(0.0, 1e-5) / (k * k) as f64)
                .collect();
            amplitudes[0] += 5e-6;
            let phases = (0..n)
                .map(|_| rng.uniform(-std::f64::consts::PI, std::f64::consts::PI))
                .collect();
            SignalSpec::Harmonics {
                frequency: 1.0 / period,
                amplitudes,
                phases,
                scale_to_stroke: Some(stroke),
                shift_to_minimum: true,
            }
        };
        let design = ActuatorParams::default();
        let mut off = |value: f64| rng.chance(0.5).then(|| value * rng.uniform(0.8, 1.2));
        let real = RealActuator {
            mass: off(design.mass),
            damping: off(design.damping),
            stiffness: off(design.stiffness),
            transfer_factor: off(design.transfer_factor),
        };
        let spec = DrivenSpec {
            reaction: rng.chance(2.0 / 3.0),
            real,
        };
        Self {
            motor,
            signal,
            design,
            spec,
        }
    }
}

/// What an engine run hands its observer, in order.
#[derive(Debug, Clone)]
pub enum Item {
    Segment(Segment),
    Event(Event),
}

/// Records segments and events.
#[derive(Debug, Default)]
pub struct Record {
    pub items: Vec<Item>,
}

impl Observer for Record {
    fn segment(&mut self, segment: &Segment, _signal: &Signal) {
        self.items.push(Item::Segment(*segment));
    }

    fn event(&mut self, event: &Event) {
        self.items.push(Item::Event(*event));
    }
}

/// A scene built: the motor, signal and rod the engine runs on.
pub struct Built {
    pub motor: Motor,
    pub signal: Signal,
    pub rod: DrivenRod,
}

impl DrivenCase {
    /// The library's motor, signal, voltage and rod for this case.
    pub fn build(&self) -> Result<Built, String> {
        let motor = Motor::new(self.motor).map_err(|e| e.to_string())?;
        let signal = Signal::build(&self.signal, &motor).map_err(|e| e.to_string())?;
        let Signal::Fourier(series) = &signal else {
            return Err("not a series".to_owned());
        };
        let voltage = Voltage::designed(series, &self.design);
        let rod =
            DrivenRod::new(&self.spec, &self.design, voltage, &motor).map_err(|e| e.to_string())?;
        Ok(Built { motor, signal, rod })
    }
}

/// Runs `periods` periods from rest with the driven engine, recording
/// them; also returns the engine's zero-velocity tolerance.
pub fn record(built: &Built, periods: u64) -> Result<(Record, f64), String> {
    let options = EventOptions::default();
    let mut engine = DrivenEngine::new(
        &built.signal,
        &built.rod,
        &built.motor,
        options.velocity_tolerance,
        20_000,
    );
    let mut record = Record::default();
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    for p in 1..=periods {
        let end = engine
            .run_period(p, start, &mut record)
            .map_err(|e| e.to_string())?;
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    Ok((record, engine.zero_velocity_tolerance()))
}

impl DrivenCase {
    /// The case with its contact force multiplied by `factor`.
    pub fn with_contact_scaled(&self, factor: f64) -> Self {
        let mut case = self.clone();
        case.motor.contact_force *= factor;
        case
    }

    /// The engine's events in `periods` periods from rest, by kind
    /// (`None` if the case does not build or run).
    fn event_count(&self, periods: u64) -> Option<u64> {
        let built = self.build().ok()?;
        let (record, _) = record(&built, periods).ok()?;
        Some(
            record
                .items
                .iter()
                .filter(|i| matches!(i, Item::Event(_)))
                .count() as u64,
        )
    }

    /// Two cases at adjacent contact forces (to a relative `1e-15`) between
    /// which the engine's event count over `periods` periods changes: the
    /// count changes where an event appears or vanishes, at a grazing, a
    /// touch of a band edge, or a period end. Searched from this case's
    /// force upwards in steps of 5 % up to twice it, then by bisection.
    pub fn at_count_change(&self, periods: u64) -> Option<(Self, Self)> {
        let base = self.event_count(periods)?;
        let mut hi = None;
        for i in 1..=15 {
            let factor = 1.05f64.powi(i);
            if self.with_contact_scaled(factor).event_count(periods)? != base {
                hi = Some(factor);
                break;
            }
        }
        let (mut lo, mut hi) = (hi? / 1.05, hi?);
        while hi - lo > 1e-15 * hi {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.with_contact_scaled(mid).event_count(periods)? == base {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some((self.with_contact_scaled(lo), self.with_contact_scaled(hi)))
    }
}
