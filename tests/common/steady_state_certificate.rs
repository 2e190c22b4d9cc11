//! The cases of the steady-state certificate (test support, shared by
//! `tests/steady_state_certificate.rs` and
//! `examples/steady_state_certificate.rs`).
//!
//! `v_inf` is, by definition, the limit of the motion from rest
//! (docs/model.md section 3, the paper's 6.1): the mean velocities `v_p` of
//! the start-up from `v_S(0) = 0` converge to it. The run finds it faster,
//! as a fixed point of the period map `P` (docs/model.md section 10), and
//! `P` may have several fixed points close together where a stick phase
//! appears in the steady orbit or the orbit's events change.
//!
//! The expected value of every case is therefore the independent one: the
//! motion from rest, simulated here period by period with the event
//! engine alone ([`motion_from_rest`]: no fixed-point search, no
//! convergence test) until its boundary state (velocity and mode) repeats
//! exactly, so that the orbit is periodic from there on and its `v_p` is
//! the limit (docs/model.md section 3). The run's own cross-check
//! (`run.verify_steady_state = true`, `v_inf_transient`, docs/model.md
//! section 10) must agree with it as well: its start-up stops at a
//! convergence test on the contraction, which a slow passage past a
//! near-fixed point can satisfy before the orbit has settled.
//!
//! Two families of scenes:
//!
//! * the optima `stickslip optimize` writes ([`optimum_cases`]): the
//!   default scene at four `sqrt(kappa)`, with the paper's Table 1
//!   actuator, optimised for three objectives at `n = 2, 3, 4` (seed 1,
//!   `keep = "f_max"`); optima sit on kinks of `v_inf`, where the event
//!   structure of the steady orbit changes (module docs of
//!   `stickslip::optimize`);
//! * random scenes placed on a change of the event structure
//!   ([`random_family`], [`structure_change`]): a bisection along the load,
//!   `kappa` or one harmonic amplitude to where the steady orbit starts to
//!   stick or its events per period change, checked there and on both
//!   sides.

// Each user (the test, the benchmark example) reads a different part.
#![allow(dead_code)]

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::collections::{HashMap, VecDeque};
use std::time::{Duration, Instant};
use stickslip::optimize::{self, Objective, OptimizeTable, Overrides, Settings};
use stickslip::{
    Indicator, MotorParams, Outcome, engine::EventCounts, motor::Motor, power::ActuatorParams,
};
use stickslip::{Scene, SignalSpec, signal::Signal};
use stickslip::{
    engine::EventEngine, engine::EventOptions, engine::Mode, engine::PeriodEngine,
    engine::PeriodStart,
};

/// The paper's Table 1 actuator (docs/model.md section 4), as the
/// `[actuator]` table of `examples/scenes/optimize.toml` writes it:
/// `velocity_per_power` needs its apparent power.
pub fn table1_actuator() -> ActuatorParams {
    ActuatorParams {
        mass: 3.2e-3,
        damping: 9.50,
        stiffness: 24.6e6,
        transfer_factor: 1.985,
        capacitance: 800e-9,
    }
}

// ---------------------------------------------------------------------
// The expected value: the motion from rest
// ---------------------------------------------------------------------

/// The rounding allowed per period, relative to `max |v_R|`: the engine's
/// zero-velocity tolerance (docs/model.md section 1, about 450 units in the
/// last place of the largest rod velocity), also the start-up's
/// convergence tolerance (docs/model.md section 10).
pub const REST_TOLERANCE: f64 = 1e-13;

/// Longest cycle of boundary states recognised: the computed period map
/// is monotone only to rounding, so where it contracts slowly an orbit may
/// settle on a cycle of neighbouring floating-point numbers instead of one
/// (13 states seen at `P' = 0.992`).
const CYCLE: u64 = 1024;

/// The limit of the motion from rest, simulated by [`motion_from_rest`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rest {
    /// The mean `v_p` over the periodic orbit the motion settled on (m/s).
    pub v_inf: f64,
    /// What it may be off by (m/s): the spread of `v_p` over that cycle,
    /// plus the rounding of one period, `u = REST_TOLERANCE max |v_R|`,
    /// carried to the limit by the contraction, `u / (1 - P')`, with the
    /// engine's exact map derivative `P'` on the cycle (as the error
    /// estimate of docs/model.md section 11 does): where the map contracts
    /// slowly, rounding may stall the orbit anywhere that close to the
    /// fixed point. A mean velocity moves no more than the boundary
    /// velocity it starts from (two sliders never overtake each other).
    pub tolerance: f64,
    /// Periods simulated until a boundary state repeated.
    pub periods: u64,
}

/// The motion from rest (`v_S(0) = 0`, docs/model.md section 1), period by
/// period with the event engine until a boundary state (velocity and mode)
/// repeats exactly, one to [`CYCLE`] periods later: the motion is periodic
/// from there on, and its limit is the mean `v_p` of that cycle
/// (docs/model.md section 3). `None` if no state repeats within
/// `run.max_periods` periods, or the map does not contract on the cycle
/// (`P' >= 1`, no tolerance can be given).
pub fn motion_from_rest(scene: &Scene) -> Option<Rest> {
    let motor = Motor::new(scene.motor).expect("valid motor");
    let signal = Signal::build(&scene.signal, &motor).expect("a signal");
    let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
    let period = signal.period();
    let mut start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    // A boundary state, with 0 and -0 as one velocity.
    let key = |v: f64, mode: Mode| (if v == 0.0 { 0 } else { v.to_bits() }, mode);
    // The last CYCLE periods: (state, v_p, P'), oldest first, and the
    // period in which each of their states was last seen.
    let mut window: VecDeque<((u64, Mode), f64, f64)> = VecDeque::new();
    let mut seen: HashMap<(u64, Mode), u64> = HashMap::new();
    for p in 1..=scene.run.max_periods {
        let end = engine.run_period(p, start, &mut ()).expect("a period runs");
        let v_p = end.step / period;
        let state = key(end.velocity, end.mode);
        if let Some(&q) = seen.get(&state) {
            // Periods q + 1 ..= p form the cycle: the last p - q - 1 of the
            // window and this one.
            let skip = window.len() - (p - q - 1) as usize;
            let cycle: Vec<(f64, f64)> = window
                .iter()
                .skip(skip)
                .map(|w| (w.1, w.2))
                .chain([(v_p, end.map_derivative)])
                .collect();
            let lo = cycle.iter().map(|c| c.0).fold(f64::INFINITY, f64::min);
            let hi = cycle.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
            let slope = cycle.iter().map(|c| c.1).fold(0.0, f64::max);
            if slope >= 1.0 {
                return None;
            }
            let rounding = REST_TOLERANCE * signal.velocity_scale();
            return Some(Rest {
                v_inf: cycle.iter().map(|c| c.0).sum::<f64>() / cycle.len() as f64,
                tolerance: (hi - lo) + rounding / (1.0 - slope),
                periods: p,
            });
        }
        window.push_back((state, v_p, end.map_derivative));
        seen.insert(state, p);
        if window.len() as u64 > CYCLE {
            let (old, ..) = window.pop_front().expect("a full window");
            if seen.get(&old) == Some(&(p - CYCLE)) {
                seen.remove(&old);
            }
        }
        start = PeriodStart {
            velocity: end.velocity,
            mode: Some(end.mode),
        };
    }
    None
}

// ---------------------------------------------------------------------
// The runs of one scene
// ---------------------------------------------------------------------

/// What a run with default settings reports for a scene, beside the limit
/// of its motion from rest and the run's own cross-check.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The scene as run (`run.verify_steady_state = false`).
    /// The steady orbit holds a grazing: a zero of `v_rel` decided within
    /// the engine's tolerance, through which no error bound holds
    /// (docs/model.md section 11).
    pub grazing: bool,
    pub scene: Scene,
    /// `regime` of the run with default settings.
    pub regime: &'static str,
    /// Its `v_inf` (m/s), with a steady state.
    pub v_inf: Option<f64>,
    /// Its error estimate of `v_inf` (m/s), when one holds.
    pub estimate: Option<f64>,
    /// The expected value: the limit of the motion from rest
    /// ([`motion_from_rest`]).
    pub rest: Option<Rest>,
    /// `v_inf_transient` of the same scene with
    /// `run.verify_steady_state = true`: the run's own start-up limit.
    pub v_inf_transient: Option<f64>,
    /// That limit's own error estimate (m/s): the part of
    /// [`stickslip::simulation::SteadyStateCheck::tolerance`] that is the start-up's
    /// (the other part is the fixed point's estimate).
    pub transient_tolerance: Option<f64>,
    /// `steady_state_check.agrees` of the verifying run.
    pub check_agrees: Option<bool>,
    /// `v_inf` the verifying run itself reports.
    pub v_inf_verified: Option<f64>,
}

/// How a [`Comparison`] came out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// `v_inf` is the limit of the motion from rest, and so is the
    /// verifying run's (or it reports none), which does not claim a
    /// disagreement.
    Agrees,
    /// `v_inf` is not the limit of the motion from rest.
    Disagrees,
    /// `v_inf` is the limit of the motion from rest, but the verifying
    /// run's start-up limit is not, or it reports a disagreement.
    CheckWrong,
    /// The motion from rest repeated no state within `run.max_periods`
    /// (or the map does not contract on its cycle): the expected value is
    /// missing, which is a failure, not a pass.
    NoExpectedValue,
    /// No steady state, or (for [`Comparison::verdict`]) one without an
    /// error estimate: not established.
    NotEstablished,
}

impl Verdict {
    /// The name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Agrees => "agrees",
            Verdict::Disagrees => "DISAGREES",
            Verdict::CheckWrong => "CHECK WRONG",
            Verdict::NoExpectedValue => "NO LIMIT FROM REST",
            Verdict::NotEstablished => "not established",
        }
    }
}

impl Comparison {
    /// Runs `scene` with `run.verify_steady_state` off (the settings a user
    /// runs with) and on, and simulates its motion from rest.
    pub fn of(scene: &Scene) -> Comparison {
        let mut plain = scene.clone();
        plain.run.verify_steady_state = false;
        let outcome =
            stickslip::run(&plain, &stickslip::RunOptions::default()).expect("a valid scene runs");
        let mut verifying = scene.clone();
        verifying.run.verify_steady_state = true;
        let checked = stickslip::run(&verifying, &stickslip::RunOptions::default())
            .expect("a valid scene runs");
        let report = outcome.report();
        let (check, transient) = match &checked {
            Outcome::Steady(r) => (r.steady_state_check, r.transient.as_ref()),
            _ => (None, None),
        };
        Comparison {
            grazing: report.is_some_and(|r| r.steady.stats.events.grazing > 0),
            regime: outcome.regime(),
            v_inf: report.map(|r| r.indicators.v_inf),
            estimate: report.and_then(|r| r.error.v_inf),
            rest: motion_from_rest(&plain),
            v_inf_transient: check.and_then(|c| c.v_inf_transient),
            transient_tolerance: transient
                .and_then(|t| t.v_inf_error)
                .or(check.and_then(|c| c.tolerance)),
            check_agrees: check.and_then(|c| c.agrees()),
            v_inf_verified: checked.report().map(|r| r.indicators.v_inf),
            scene: plain,
        }
    }

    /// `|v_inf - limit from rest|` (m/s), when both exist.
    pub fn difference(&self) -> Option<f64> {
        Some((self.v_inf? - self.rest?.v_inf).abs())
    }

    /// What the difference may be: the run's own estimate of `v_inf` (0
    /// where it states none) plus the tolerance of the limit from rest.
    pub fn allowed(&self) -> f64 {
        self.estimate.unwrap_or(0.0) + self.rest.map_or(0.0, |r| r.tolerance)
    }

    /// True if the verifying run's start-up limit is that of the motion
    /// from rest within both tolerances, or it reports none.
    pub fn check_limit_right(&self) -> bool {
        match (self.v_inf_transient, self.rest) {
            (Some(t), Some(r)) => {
                (t - r.v_inf).abs() <= self.transient_tolerance.unwrap_or(0.0) + r.tolerance
            }
            _ => true,
        }
    }

    /// A steady state with an error estimate (docs/model.md section 11).
    pub fn established(&self) -> bool {
        self.v_inf.is_some() && self.estimate.is_some()
    }

    /// The verdict on an established steady state (others are
    /// [`Verdict::NotEstablished`]).
    pub fn verdict(&self) -> Verdict {
        if !self.established() {
            return Verdict::NotEstablished;
        }
        self.judge()
    }

    /// The verdict whether or not an estimate exists: a steady state
    /// without one must equal the limit from rest within that limit's own
    /// tolerance (the written optima, where every steady state counts).
    pub fn strict_verdict(&self) -> Verdict {
        if self.v_inf.is_none() {
            return Verdict::NotEstablished;
        }
        self.judge()
    }

    fn judge(&self) -> Verdict {
        match self.difference() {
            None => Verdict::NoExpectedValue,
            Some(d) if d > self.allowed() => Verdict::Disagrees,
            _ if !self.check_limit_right() || self.check_agrees == Some(false) => {
                Verdict::CheckWrong
            }
            _ => Verdict::Agrees,
        }
    }

    /// One line: the reported and the expected values.
    pub fn describe(&self) -> String {
        let value = |x: Option<f64>| x.map_or("none".to_owned(), |x| format!("{x:?}"));
        let small = |x: Option<f64>| x.map_or("none".to_owned(), |x| format!("{x:.1e}"));
        format!(
            "{}: v_inf {} ± {} m/s; motion from rest {} ± {} m/s ({} periods), difference {} m/s \
             (allowed {:.1e}); with the check on: v_inf {}, start-up limit {} ± {} m/s, agrees {}",
            self.regime,
            value(self.v_inf),
            small(self.estimate),
            value(self.rest.map(|r| r.v_inf)),
            small(self.rest.map(|r| r.tolerance)),
            self.rest
                .map_or("no repetition in".to_owned(), |r| r.periods.to_string()),
            small(self.difference()),
            self.allowed(),
            value(self.v_inf_verified),
            value(self.v_inf_transient),
            small(self.transient_tolerance),
            self.check_agrees
                .map_or("none".to_owned(), |a| a.to_string()),
        )
    }
}

// ---------------------------------------------------------------------
// The written optima
// ---------------------------------------------------------------------

/// One optimisation: `n` harmonics at the `f_max` of the default scene's
/// signal with `sqrt(kappa)` (`keep = "f_max"`), for `objective`, seed 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OptimumCase {
    /// Harmonics of the optimised signal.
    pub harmonics: usize,
    /// `sqrt(kappa)` of the scene's (`n = 2`, sigma) signal.
    pub sqrt_kappa: f64,
    /// What is optimised.
    pub objective: Objective,
}

impl std::fmt::Display for OptimumCase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "n = {}, sqrt_kappa = {}, objective {}",
            self.harmonics,
            self.sqrt_kappa,
            self.objective.name()
        )
    }
}

/// The 36 optimisations: `n` in {2, 3, 4}, `sqrt(kappa)` in
/// {1.5, 3, 4.5, 6}, objectives `v_inf`, `velocity_per_power`,
/// `durability`.
pub fn optimum_cases() -> Vec<OptimumCase> {
    let mut cases = Vec::new();
    for harmonics in [2, 3, 4] {
        for sqrt_kappa in [1.5, 3.0, 4.5, 6.0] {
            for objective in [
                Objective::VInf,
                Objective::VelocityPerPower,
                Objective::Durability,
            ] {
                cases.push(OptimumCase {
                    harmonics,
                    sqrt_kappa,
                    objective,
                });
            }
        }
    }
    cases
}

/// The scene optimised: the default scene (the paper's motor, `n = 2`,
/// sigma factors, stroke 25 um, every indicator) with `sqrt(kappa)` and the
/// Table 1 actuator.
pub fn optimum_base_scene(sqrt_kappa: f64) -> Scene {
    let scene = Scene {
        signal: SignalSpec::fourier(25e-6, sqrt_kappa * sqrt_kappa, 2, true),
        actuator: Some(table1_actuator()),
        ..Scene::default()
    };
    scene.validate().expect("a valid scene");
    scene
}

/// A written optimum and its comparison.
#[derive(Debug, Clone)]
pub struct OptimumResult {
    /// The optimisation.
    pub case: OptimumCase,
    /// The scene file `stickslip optimize -o` writes, as text.
    pub written: String,
    /// `v_inf` the optimiser reports for it.
    pub v_inf_search: f64,
    /// The written scene run with default settings and with the check,
    /// beside its motion from rest.
    pub comparison: Comparison,
    /// Time of the optimisation.
    pub optimise_time: Duration,
    /// Time of the comparison ([`Comparison::of`]).
    pub check_time: Duration,
}

/// Optimises one case through the library as `stickslip optimize` does
/// (`src/cli/optimize.rs`), writes the best scene as the command writes it
/// (`src/optimize/output.rs`: the base scene with the series as its signal
/// and the indicators the objective needs, as TOML text read back) and
/// compares that scene's `v_inf` with its motion from rest.
pub fn run_optimum_case(case: OptimumCase) -> OptimumResult {
    let scene = optimum_base_scene(case.sqrt_kappa);
    let overrides = Overrides {
        harmonics: Some(case.harmonics as i64),
        objective: Some(case.objective.name().to_owned()),
        keep: Some("f_max".to_owned()),
        seed: Some(1),
    };
    let settings =
        Settings::resolve(&OptimizeTable::default(), &overrides, &scene).expect("valid settings");
    let clock = Instant::now();
    let found = optimize::optimize(&scene, &settings).expect("an optimum");
    let optimise_time = clock.elapsed();
    let problem = &found.problem;
    let mut best = problem.written_scene(&found.best.shape.series(problem.stroke));
    let mut wanted = best.outputs.indicators.clone();
    wanted.extend(problem.indicators());
    best.outputs.indicators = Indicator::ALL
        .into_iter()
        .filter(|i| wanted.contains(i))
        .collect();
    let written = best.to_toml();
    let read = Scene::from_toml_str(&written, "<written optimum>").expect("the scene reads back");
    let clock = Instant::now();
    let comparison = Comparison::of(&read);
    OptimumResult {
        case,
        written,
        v_inf_search: found.best.measured.values.v_inf,
        comparison,
        optimise_time,
        check_time: clock.elapsed(),
    }
}

// ---------------------------------------------------------------------
// Random scenes at changes of the event structure
// ---------------------------------------------------------------------

/// The parameter a family of scenes varies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Knob {
    /// The extra acceleration `g_t` (m/s^2, docs/model.md section 9).
    Load,
    /// `kappa` of the Fourier signal (docs/model.md section 2).
    Kappa,
    /// A factor on the amplitude `d_k` of harmonic `k` (1-based) of the
    /// signal written as `kind = "harmonics"` (scaled to the stroke and
    /// shifted, docs/model.md section 2).
    Amplitude(usize),
}

/// A random scene and the parameter to vary.
#[derive(Debug, Clone)]
pub struct Family {
    /// The scene (a Fourier signal; for [`Knob::Amplitude`] the same
    /// signal as an explicit series).
    pub base: Scene,
    /// What varies.
    pub knob: Knob,
}

/// Seed of the `index`-th random scene: each scene has its own stream, so
/// the first scenes are the same in the test and in the benchmark.
pub fn scene_seed(index: u64) -> u64 {
    0x57ea_d700_0000 + index
}

/// The `index`-th random scene: the paper's motor with a random
/// `mu_dynamic / mu_static` in [0.5, 1] and a random load within 60 % of
/// sliding friction, a Fourier signal with `n` in 2..=6, `sqrt(kappa)` in
/// [1, 8] and sigma factors or not, stroke 25 um, and either every
/// indicator (with the Table 1 actuator) or `v_inf` alone: the two ways a
/// run decides its steady state (docs/model.md section 10). The knob is
/// drawn among the load, `kappa` and one harmonic amplitude.
pub fn random_family(index: u64) -> Family {
    let mut rng = ChaCha8Rng::seed_from_u64(scene_seed(index));
    let n = rng.random_range(2..=6usize);
    let sqrt_kappa = rng.random_range(1.0..=8.0f64);
    let sigma = rng.random::<bool>();
    let ratio = rng.random_range(0.5..=1.0f64);
    let load = rng.random_range(-0.6..=0.6f64);
    let every_indicator = rng.random::<bool>();
    let knob = match rng.random_range(0..3u32) {
        0 => Knob::Load,
        1 => Knob::Kappa,
        _ => Knob::Amplitude(rng.random_range(1..=n)),
    };
    let paper = MotorParams::default();
    let mut motor = MotorParams {
        mu_dynamic: ratio * paper.mu_static,
        ..paper
    };
    let a_d = Motor::new(motor).expect("valid motor").a_d();
    motor.extra_acceleration = load * a_d;
    let mut scene = Scene {
        motor,
        signal: SignalSpec::fourier(25e-6, sqrt_kappa * sqrt_kappa, n, sigma),
        ..Scene::default()
    };
    if every_indicator {
        scene.actuator = Some(table1_actuator());
    } else {
        scene.actuator = None;
        scene.outputs.indicators = vec![Indicator::VInf];
    }
    if let Knob::Amplitude(_) = knob {
        scene.signal = as_series(&scene);
    }
    scene.validate().expect("a valid random scene");
    Family { base: scene, knob }
}

/// The scene's Fourier signal as an explicit series: the amplitudes and
/// phases of the built (scaled, shifted) signal, scaled to the same stroke
/// and shifted again, which leaves it as it is (docs/model.md section 2).
fn as_series(scene: &Scene) -> SignalSpec {
    let motor = Motor::new(scene.motor).expect("valid motor");
    let Signal::Fourier(signal) = Signal::build(&scene.signal, &motor).expect("a signal") else {
        panic!("a Fourier signal builds a harmonic series");
    };
    SignalSpec::Harmonics {
        frequency: signal.f0(),
        amplitudes: signal.amplitudes(),
        phases: signal.phases(),
        scale_to_stroke: Some(25e-6),
        shift_to_minimum: true,
    }
}

impl Family {
    /// The range the knob is varied over.
    fn range(&self, knob: Knob) -> (f64, f64) {
        match knob {
            Knob::Load => {
                let a_d = Motor::new(self.base.motor).expect("valid motor").a_d();
                (-0.9 * a_d, 0.9 * a_d)
            }
            Knob::Kappa => (1.0, 64.0),
            Knob::Amplitude(_) => (0.0, 2.0),
        }
    }

    /// The points a change is first looked for at: 17 across the range
    /// (for `kappa`, equally spaced in `sqrt(kappa)`).
    fn scan(&self, knob: Knob) -> Vec<f64> {
        let (lo, hi) = self.range(knob);
        let m = 16;
        (0..=m)
            .map(|i| {
                let s = i as f64 / m as f64;
                match knob {
                    Knob::Kappa => {
                        let (a, b) = (lo.sqrt(), hi.sqrt());
                        let r = a + s * (b - a);
                        r * r
                    }
                    _ => lo + s * (hi - lo),
                }
            })
            .collect()
    }

    /// The scene with the knob at `x`. The amplitude knob works on the
    /// explicit series, so a family of the amplitude knob varies
    /// [`Knob::Amplitude`] alone; the other two work on either signal.
    pub fn at(&self, knob: Knob, x: f64) -> Scene {
        let mut scene = self.base.clone();
        match (knob, &mut scene.signal) {
            (Knob::Load, _) => scene.motor.extra_acceleration = x,
            (Knob::Kappa, SignalSpec::Fourier { shape, .. }) => {
                shape.drive = stickslip::signal::Drive::Kappa(x)
            }
            (Knob::Amplitude(k), SignalSpec::Harmonics { amplitudes, .. }) => {
                amplitudes[k - 1] *= x;
            }
            (knob, spec) => panic!("knob {knob:?} does not apply to {spec:?}"),
        }
        scene
    }

    /// The knobs to try, the drawn one first: the load applies to every
    /// scene, `kappa` to the Fourier signal, the amplitude to the series.
    fn knobs(&self) -> Vec<Knob> {
        let mut knobs = vec![self.knob];
        let other = match self.knob {
            Knob::Amplitude(_) => [Knob::Load, Knob::Load],
            _ => [Knob::Load, Knob::Kappa],
        };
        for k in other {
            if !knobs.contains(&k) {
                knobs.push(k);
            }
        }
        knobs
    }
}

/// The event structure of a scene's steady state: whether the steady
/// orbit sticks (`stiction_fraction_steady > 0`, docs/model.md section 3)
/// and the events of one steady period; `None` without a steady state.
/// From a `v_inf`-only run (docs/model.md section 10: the steady period is
/// observed whatever is asked).
pub fn structure(scene: &Scene) -> Option<(bool, EventCounts)> {
    let mut quick = scene.clone();
    quick.outputs.indicators = vec![Indicator::VInf];
    quick.actuator = None;
    quick.run.verify_steady_state = false;
    let outcome =
        stickslip::run(&quick, &stickslip::RunOptions::default()).expect("a valid scene runs");
    outcome
        .report()
        .map(|r| (r.indicators.stiction_fraction > 0.0, r.steady.stats.events))
}

/// A change of the event structure found along a knob.
#[derive(Debug, Clone)]
pub struct Change {
    /// The knob.
    pub knob: Knob,
    /// The last value with the structure of one side and the first with
    /// the other, as close as bisection gets them.
    pub bracket: (f64, f64),
    /// Whether the change is a stick phase appearing (or vanishing).
    pub stick_onset: bool,
    /// The scenes checked: at both ends of the bracket and at its middle.
    pub points: Vec<Scene>,
}

/// Bisects along the family's knobs to a change of the steady state's
/// event structure, preferring the onset of a stick phase; `None` if the
/// structure is the same at every scanned point of every knob tried.
pub fn structure_change(family: &Family, index: u64) -> Option<Change> {
    let mut rng = ChaCha8Rng::seed_from_u64(scene_seed(index) ^ 0x00b1_5ec7);
    for knob in family.knobs() {
        let xs = family.scan(knob);
        let sigs: Vec<_> = xs.iter().map(|x| structure(&family.at(knob, *x))).collect();
        let pairs: Vec<usize> = (0..xs.len() - 1)
            .filter(|i| sigs[*i].is_some() && sigs[i + 1].is_some() && sigs[*i] != sigs[i + 1])
            .collect();
        if pairs.is_empty() {
            continue;
        }
        let onset: Vec<usize> = pairs
            .iter()
            .copied()
            .filter(|i| sigs[*i].map(|s| s.0) != sigs[i + 1].map(|s| s.0))
            .collect();
        let pool = if onset.is_empty() { &pairs } else { &onset };
        let i = pool[rng.random_range(0..pool.len())];
        let (mut lo, mut hi) = (xs[i], xs[i + 1]);
        let (sig_lo, mut sig_hi) = (sigs[i], sigs[i + 1]);
        // To 1e-12 of the range, or until the middle is an end.
        let width = 1e-12 * (xs[xs.len() - 1] - xs[0]).abs();
        for _ in 0..200 {
            let mid = lo + 0.5 * (hi - lo);
            if (hi - lo).abs() <= width || mid == lo || mid == hi {
                break;
            }
            let s = structure(&family.at(knob, mid));
            if s == sig_lo {
                lo = mid;
            } else {
                hi = mid;
                sig_hi = s;
            }
        }
        let stick_onset = sig_lo.map(|s| s.0) != sig_hi.map(|s| s.0);
        let mid = lo + 0.5 * (hi - lo);
        return Some(Change {
            knob,
            bracket: (lo, hi),
            stick_onset,
            points: [lo, mid, hi]
                .into_iter()
                .map(|x| family.at(knob, x))
                .collect(),
        });
    }
    None
}

/// What the random scenes gave.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    /// Random scenes drawn.
    pub scenes: usize,
    /// Of those, scenes with a change of the event structure found.
    pub with_change: usize,
    /// Of those, changes where a stick phase appears.
    pub stick_onsets: usize,
    /// Points checked (three per change).
    pub points: usize,
    /// Points with a steady state and an error estimate.
    pub established: usize,
    /// Points with a steady state but no error estimate.
    pub without_estimate: usize,
    /// Points without a steady state (run-away, not converged).
    pub without_steady_state: usize,
    /// Established points whose `v_inf` is the limit of the motion from
    /// rest, and whose cross-check says so.
    pub agreeing: usize,
    /// Established points whose `v_inf` is not that limit.
    pub disagreeing: usize,
    /// Established points whose `v_inf` is that limit but whose
    /// cross-check's start-up limit is not, or which report a
    /// disagreement.
    pub check_wrong: usize,
    /// Established points whose motion from rest repeated no state.
    pub without_limit: usize,
    /// Every failing established point, with the scene index.
    pub failures: Vec<(u64, Comparison)>,
    /// Largest `|v_inf - limit from rest|` over established points (m/s).
    pub largest_difference: f64,
}

impl Tally {
    /// The first failing point of each scene with one, at most `count`
    /// of them: the scene index, the comparison and the scene as TOML.
    pub fn first_failures(&self, count: usize) -> Vec<String> {
        let mut seen = Vec::new();
        let mut shown = Vec::new();
        for (i, c) in &self.failures {
            if seen.contains(i) || shown.len() == count {
                continue;
            }
            seen.push(*i);
            shown.push(format!(
                "# random scene {i}, {}: {}\n{}",
                c.verdict().name(),
                c.describe(),
                c.scene.to_toml()
            ));
        }
        shown
    }

    /// The scenes with a failing point.
    pub fn failing_scenes(&self) -> Vec<u64> {
        let mut scenes: Vec<u64> = self.failures.iter().map(|f| f.0).collect();
        scenes.dedup();
        scenes
    }

    /// Established points over points checked.
    pub fn share(&self) -> f64 {
        self.established as f64 / self.points.max(1) as f64
    }

    /// One line of counts.
    pub fn summary(&self) -> String {
        format!(
            "{} scenes, {} with a change of the event structure ({} stick onsets); {} points, \
             {} established ({:.1} %; {} without an error estimate, {} without a steady state); \
             of those, {} are the limit of the motion from rest, {} are not, {} are but their \
             cross-check is wrong, {} without a limit from rest; largest difference {:.3e} m/s",
            self.scenes,
            self.with_change,
            self.stick_onsets,
            self.points,
            self.established,
            100.0 * self.share(),
            self.without_estimate,
            self.without_steady_state,
            self.agreeing,
            self.disagreeing,
            self.check_wrong,
            self.without_limit,
            self.largest_difference
        )
    }
}

/// The checks of random scene `index`: its change of structure (if any)
/// and the comparison at each of its points.
pub fn check_random_scene(index: u64) -> (Option<Change>, Vec<Comparison>) {
    let family = random_family(index);
    let Some(change) = structure_change(&family, index) else {
        return (None, Vec::new());
    };
    let comparisons = change.points.iter().map(Comparison::of).collect();
    (Some(change), comparisons)
}

/// Adds one scene's checks to the tally.
pub fn tally(t: &mut Tally, index: u64, change: Option<&Change>, comparisons: &[Comparison]) {
    t.scenes += 1;
    let Some(change) = change else {
        return;
    };
    t.with_change += 1;
    t.stick_onsets += usize::from(change.stick_onset);
    for c in comparisons {
        t.points += 1;
        if c.v_inf.is_none() {
            t.without_steady_state += 1;
        } else if c.estimate.is_none() {
            t.without_estimate += 1;
        }
        if !c.established() {
            continue;
        }
        t.established += 1;
        if let Some(d) = c.difference() {
            t.largest_difference = t.largest_difference.max(d);
        }
        match c.verdict() {
            Verdict::Agrees => t.agreeing += 1,
            v => {
                match v {
                    Verdict::Disagrees => t.disagreeing += 1,
                    Verdict::CheckWrong => t.check_wrong += 1,
                    _ => t.without_limit += 1,
                }
                t.failures.push((index, c.clone()));
            }
        }
    }
}
