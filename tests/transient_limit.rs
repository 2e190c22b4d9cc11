//! The limit of the start-up from rest (`src/analysis/transient.rs`,
//! docs/model.md section 10): an orbit whose boundary velocity lands on a
//! few floating-point values within rounding of each other, in a period
//! map made locally constant by a stick phase, has an established limit
//! after a bounded number of periods instead of running to
//! `run.max_periods`.

use stickslip::analysis::{self, AnalysisOptions, StatsWanted};
use stickslip::{Outcome, Scene, engine::EventEngine, engine::EventOptions};

/// The paper's motor (docs/model.md section 6) on the plain Fourier signal
/// of 2 harmonics with `kappa = 0.2`, loaded at its stall force
/// `F = 0.04320095773417103 N` (the `stall.force`, kind `crossing`, that
/// `stickslip characteristic` reports for this scene at zero load), so
/// `g_t = -F / m_s = -30.857826952979305 m/s^2`. Every steady period has a
/// stick phase, so the period map is locally constant (`P' = 0`), and the
/// boundary velocity computed along the orbit alternates between two
/// doubles 6 units in the last place apart (checked below): it never
/// repeats exactly. `run.max_periods` is the default, 10^6.
const STALLED: &str = "\
[motor]
slider_mass = 0.0014
contact_force = 1.0
mu_static = 0.1736
mu_dynamic = 0.1568
extra_acceleration = -30.857826952979305

[signal]
kind = \"fourier\"
stroke = 25e-6
kappa = 0.2
harmonics = 2
sigma = false

[run]
verify_steady_state = true

[outputs]
indicators = [\"v_inf\", \"startup_time\"]
";

/// Periods the start-up from rest needs here: period 1 already ends on the
/// orbit (its stick phase makes the slider forget that it started at rest;
/// checked below), and the limit is established after two more periods
/// whose boundary velocity repeated within the rounding bound where the map
/// derivative is 0 (the criterion of `analysis::transient`).
const PERIODS_BOUND: u64 = 3;

fn stalled() -> Scene {
    Scene::from_toml_str(STALLED, "the stalled scene").expect("a valid scene")
}

/// The rounding bound of a velocity at the end of a period with `events`
/// events: 8 eps per segment (`events + 2` segments) of `max |v_R|`
/// (docs/model.md section 11).
fn rounding_bound(max_rod_velocity: f64, events: u64) -> f64 {
    8.0 * f64::EPSILON * (events as f64 + 2.0) * max_rod_velocity
}

#[test]
fn an_orbit_repeating_within_rounding_reaches_its_limit_in_three_periods() {
    let scene = stalled();
    let stickslip::scene::BuiltScene { signal, motor } = scene.build().expect("the scene builds");
    let mut engine = EventEngine::new(&signal, &motor, EventOptions::default());
    // As in a run, the fixed point is searched from rest first. The
    // engine's root finder refines its models of the signal lazily, so the
    // last bits of a period depend on what it computed before: on a fresh
    // engine this orbit happens to repeat exactly from period 1 on, after
    // the search it alternates (checked below).
    analysis::fixed_point(&mut engine, 0.0).expect("the search from rest runs");
    let options = AnalysisOptions {
        max_periods: scene.run.max_periods,
        ..AnalysisOptions::default()
    };
    let t = analysis::transient(&mut engine, &options, StatsWanted::default(), &mut ())
        .expect("the start-up runs");
    let u = &t.boundary_velocities;
    assert!(t.converged, "no limit after {} periods", t.periods());
    assert!(
        t.periods() <= PERIODS_BOUND,
        "{} periods (bound {PERIODS_BOUND}): {u:?}",
        t.periods()
    );
    // The case this is about: the boundary velocity did not repeat
    // exactly, but within the rounding bound of each period.
    let scale = signal.velocity_scale();
    assert!(
        u.windows(2).any(|w| w[0] != w[1]),
        "the orbit repeated exactly, it no longer shows the case: {u:?}"
    );
    for (k, w) in u.windows(2).enumerate() {
        let events = t.period_events[k + 1].total();
        assert!(
            (w[1] - w[0]).abs() <= rounding_bound(scale, events),
            "period {}: change {:e} beyond rounding",
            k + 2,
            w[1] - w[0]
        );
    }
    // The stated distance to the limit is the rounding width of the last
    // period (P' = 0 there).
    let last_events = t.period_events.last().unwrap().total();
    assert_eq!(t.remaining, Some(rounding_bound(scale, last_events)));
}

#[test]
fn a_stalled_slider_is_reported_with_v_inf_zero_and_a_verified_start_up() {
    let scene = stalled();
    let stickslip::scene::BuiltScene { signal, motor: _ } =
        scene.build().expect("the scene builds");
    let outcome =
        stickslip::run(&scene, &stickslip::RunOptions::default()).expect("the scene runs");
    let Outcome::Steady(r) = &outcome else {
        panic!("no steady state: {}", outcome.regime());
    };
    let v = r.indicators.v_inf;
    let e = r.error.v_inf.expect("an error estimate");
    // The load is the stall force: v_inf is 0 within its estimate
    // (docs/model.md section 9, the stall of kind `crossing`).
    assert!(v.abs() <= e, "v_inf = {v:e} ± {e:e}");
    assert_eq!(outcome.regime(), "stick-slip");
    // The period map is constant near the orbit: a stick phase.
    assert_eq!(r.steady.map_derivative, 0.0);
    let check = r.steady_state_check.expect("verify_steady_state is set");
    assert!(
        check.periods <= PERIODS_BOUND,
        "the start-up ran {} periods (bound {PERIODS_BOUND})",
        check.periods
    );
    assert_eq!(check.agrees(), Some(true), "{check:?}");
    let t = r.transient.as_ref().expect("the start-up was simulated");
    let u = &t.boundary_velocities;
    assert!(
        u.windows(2).any(|w| w[0] != w[1]),
        "the orbit repeated exactly, it no longer shows the case: {u:?}"
    );
    // Period 1 from rest already ends on the orbit: within the rounding
    // bound of the steady state's boundary velocity.
    let first = t.boundary_velocities[0];
    let bound = rounding_bound(signal.velocity_scale(), t.period_events[0].total());
    assert!(
        (first - r.steady.boundary_velocity).abs() <= bound,
        "period 1 ends at {first:e}, the orbit at {:e}",
        r.steady.boundary_velocity
    );
    // The work: at most the start-up's bound, plus the periods run from
    // chosen velocities (fixed-point search, its certificate, the steady
    // period).
    assert!(
        r.work.periods <= PERIODS_BOUND + r.map_evaluations,
        "{} periods, {} of them map evaluations",
        r.work.periods,
        r.map_evaluations
    );
}
