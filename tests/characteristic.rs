//! The force-velocity characteristic (`stickslip characteristic`,
//! `src/characteristic/`): the stall force converged on the exact `v_inf`,
//! closed forms of the held band, the load's sign convention and the
//! start-up force, the scaling law, the holding force, the datasheet rule,
//! and the command line's bad input and outputs.

mod common;

use common::{assert_rel, scratch, stickslip};
use std::process::Output;
use std::sync::OnceLock;
use stickslip::Indicator;
use stickslip::Outcome;
use stickslip::SignalSpec;
use stickslip::characteristic::StallKind;
use stickslip::characteristic::{self, Characteristic, CharacteristicOptions, LoadAxis, LoadMark};
use stickslip::{Scene, motor::Motor, signal::Signal};

/// The characteristic of the default scene with the default options,
/// computed once for the tests that read it.
fn default_characteristic() -> &'static Characteristic {
    static C: OnceLock<Characteristic> = OnceLock::new();
    C.get_or_init(|| {
        characteristic::characteristic(&Scene::default(), &CharacteristicOptions::default())
            .expect("the default scene has a characteristic")
    })
}

/// Options that sample little: for tests that need the stall force, the
/// held band or the largest power, which do not depend on the sampling.
fn coarse(range: (f64, f64)) -> CharacteristicOptions {
    CharacteristicOptions {
        range: Some(range),
        tolerance: 0.5,
        max_evaluations: 20,
        ..CharacteristicOptions::default()
    }
}

/// `(v_inf, error)` of `scene` at load `force` (N), run directly with
/// `g_t = -F / m_s`, not through the characteristic's evaluator.
fn v_inf_at(scene: &Scene, force: f64) -> (f64, f64) {
    let mut s = scene.clone();
    s.motor.extra_acceleration = -force / s.motor.slider_mass;
    s.outputs.indicators = vec![Indicator::VInf];
    let report = stickslip::run(&s, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .expect("a steady state");
    (
        report.indicators.v_inf,
        report.error.v_inf.expect("an error estimate"),
    )
}

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test scene").expect("a valid scene")
}

#[test]
fn stall_force_of_the_default_scene_is_converged() {
    // docs/model.md section 9: the stall force is where v_inf becomes 0.
    // Converged to 1e-9 relative: v_inf at the reported force lies within
    // its own error estimate, and v_inf has opposite signs, beyond their
    // error estimates, 1e-9 relative on either side (runs made directly,
    // independent of the root finder's evaluations).
    let c = default_characteristic();
    let s = &c.stall;
    assert_eq!(s.kind, StallKind::Crossing);
    let v = s.at.v_inf.unwrap();
    let e = s.at.error.unwrap();
    assert!(
        v.abs() <= e,
        "v_inf(F_stall) = {v:e} beyond its error {e:e}"
    );
    assert!(s.relative_width() <= 1e-9, "bracket {:?}", s.bracket);
    let scene = Scene::default();
    let (below, e_below) = v_inf_at(&scene, s.force * (1.0 - 1e-9));
    let (above, e_above) = v_inf_at(&scene, s.force * (1.0 + 1e-9));
    assert!(
        below > e_below,
        "v_inf below the stall force: {below:e} ± {e_below:e}"
    );
    assert!(
        above < -e_above,
        "v_inf above the stall force: {above:e} ± {e_above:e}"
    );
    // The drive moves forward at no load (the paper's 0.297 m/s, section 7),
    // so the stall force is a load against it.
    assert!(s.force > 0.0 && c.drive == 1);
    assert_rel(
        c.no_load.v_inf.unwrap(),
        0.297137063156,
        1e-11,
        "no-load speed",
    );
}

#[test]
fn holding_force_is_mu_0_f_c_and_the_datasheet_follows_the_vendor_rule() {
    // Holding force at rest mu_0 F_c (docs/model.md section 9, closed form);
    // recommended load half the stall force (the vendor rule).
    let c = default_characteristic();
    let m = Scene::default().motor;
    assert_eq!(c.holding_force, m.mu_static * m.contact_force);
    let d = &c.datasheet;
    assert_eq!(d.holding_force, c.holding_force);
    assert_eq!(d.stall_force, Some(c.stall.force));
    assert_eq!(d.recommended_load, Some(c.stall.force / 2.0));
    assert_eq!(d.max_speed, c.no_load.v_inf.unwrap());
    let p = c.max_power.as_ref().unwrap();
    assert_eq!(d.max_output_power, Some(p.power));
    // The largest power is no smaller than F v_inf at any point between 0
    // and the stall force (it is their maximum, refined).
    for point in &c.points {
        let e = &point.evaluation;
        if e.load > 0.0 && e.load < c.stall.force {
            assert!(e.output_power().unwrap() <= p.power, "{e:?}");
        }
    }
    // Another motor: mu_0 = 0.3, F_c = 2.5 N.
    let mut scene = Scene::default();
    scene.motor.mu_static = 0.3;
    scene.motor.contact_force = 2.5;
    let c2 = characteristic::characteristic(&scene, &coarse((0.0, 0.1))).unwrap();
    assert_eq!(c2.holding_force, 0.3 * 2.5);
}

#[test]
fn stall_force_scales_with_contact_force_and_not_with_mass() {
    // docs/model.md section 5: scaling every acceleration by r (F_c times r
    // at fixed m_s, mu and kappa) scales times by 1/sqrt(r) and velocities
    // by sqrt(r); the load's g_t = -F/m_s scales with the others, so the
    // stall force scales by r, the no-load speed by sqrt(r) and the power
    // F v_inf by r^(3/2). With m_s times r at fixed F_c (accelerations over
    // r) the stall force stays and the speed falls by sqrt(r).
    let base = Scene::default();
    let c = characteristic::characteristic(&base, &coarse((0.0, 0.02))).unwrap();
    let mut strong = base.clone();
    strong.motor.contact_force *= 4.0;
    let cs = characteristic::characteristic(&strong, &coarse((0.0, 0.08))).unwrap();
    assert_rel(
        cs.stall.force,
        4.0 * c.stall.force,
        1e-9,
        "stall force, F_c x 4",
    );
    assert_rel(
        cs.no_load.v_inf.unwrap(),
        2.0 * c.no_load.v_inf.unwrap(),
        1e-12,
        "speed",
    );
    let (p, ps) = (c.max_power.unwrap().power, cs.max_power.unwrap().power);
    assert_rel(ps, 8.0 * p, 1e-9, "largest power, F_c x 4");
    let mut heavy = base.clone();
    heavy.motor.slider_mass *= 4.0;
    let ch = characteristic::characteristic(&heavy, &coarse((0.0, 0.02))).unwrap();
    assert_rel(ch.stall.force, c.stall.force, 1e-9, "stall force, m_s x 4");
    assert_rel(
        ch.no_load.v_inf.unwrap(),
        0.5 * c.no_load.v_inf.unwrap(),
        1e-12,
        "speed",
    );
    assert_rel(
        ch.max_power.unwrap().power,
        0.5 * p,
        1e-9,
        "largest power, m_s x 4",
    );
}

/// A scene whose rod moves as `x_R = d_1 sin(w t + pi/2) + d_2 sin(2 w t + pi/2)`
/// at 1 kHz, shifted to start at rest, not scaled.
fn two_cosines(d1: f64, d2: f64) -> Scene {
    scene(&format!(
        "[signal]\nkind = \"harmonics\"\nfrequency = 1000.0\namplitudes = [{d1:e}, {d2:e}]\n\
         phases = [1.5707963267948966, 1.5707963267948966]\nscale_to_stroke = false\n\
         shift_to_minimum = true\n"
    ))
}

#[test]
fn held_band_of_a_sinusoid_is_the_closed_form() {
    // One harmonic: a_R = -A cos(w t), A = d w^2. The slider follows the rod
    // throughout while a_R stays in the stick band [-a_0 + g_t, a_0 + g_t]
    // (docs/model.md section 1), i.e. for |g_t| <= a_0 - A: loads
    // |F| <= mu_0 F_c - m_s A. A sinusoid is its own mirror image (section
    // 7), so there is no drive at zero load and the stall force is 0.
    let d = 3.0e-6;
    let scene = two_cosines(d, 0.0);
    let signal = Signal::build(&scene.signal, &Motor::new(scene.motor).unwrap()).unwrap();
    let w = 2.0 * std::f64::consts::PI / signal.period();
    let m = scene.motor;
    let edge = m.mu_static * m.contact_force - m.slider_mass * d * w * w;
    assert!(edge > 0.0, "the band exists: A < a_0");
    let c = characteristic::characteristic(&scene, &coarse((-0.15, 0.15))).unwrap();
    assert_eq!(c.stall.kind, StallKind::NoDrive);
    assert_eq!(c.stall.force, 0.0);
    let band = c.held_band.expect("a held band");
    let tol = 1e-9 * c.holding_force;
    assert!(
        (band.upper - edge).abs() <= tol,
        "upper {} vs {edge}",
        band.upper
    );
    assert!(
        (band.lower + edge).abs() <= tol,
        "lower {} vs {}",
        band.lower,
        -edge
    );
    // Outside the band the load wins: backwards above it, forwards below.
    assert!(v_inf_at(&scene, band.above).0 < 0.0);
    assert!(v_inf_at(&scene, band.below).0 > 0.0);
}

#[test]
fn a_drive_held_by_a_band_stalls_at_the_band_edge() {
    // a_R = -A (cos w t + cos(2 w t) / 4) has min -5A/4 (at w t = 0) and max
    // 3A/4 (at w t = pi). With A = 0.9 a_0 the rod's swing 2A fits the band
    // width 2 a_0 but its minimum does not fit [-a_0, a_0]: the drive moves
    // at no load and is held still (section 1's band) from the load where
    // -a_0 + g_t = -5A/4 up to where a_0 + g_t = 3A/4:
    // F from m_s (5A/4 - a_0) to m_s (a_0 - 3A/4); the first is the stall
    // force.
    let motor = Motor::default();
    let w = 2.0 * std::f64::consts::PI * 1000.0;
    let amplitude = 0.9 * motor.a_0();
    let scene = two_cosines(amplitude / (w * w), amplitude / (16.0 * w * w));
    let m_s = scene.motor.slider_mass;
    let lower = m_s * (1.25 * amplitude - motor.a_0());
    let upper = m_s * (motor.a_0() - 0.75 * amplitude);
    let c = characteristic::characteristic(&scene, &coarse((0.0, 0.06))).unwrap();
    assert_eq!(c.drive, 1, "moves forward at no load");
    assert_eq!(c.stall.kind, StallKind::Held);
    let tol = 1e-9 * lower;
    assert!(
        (c.stall.force - lower).abs() <= tol,
        "stall {} vs {lower}",
        c.stall.force
    );
    assert_eq!(c.stall.at.v_inf, Some(0.0), "held still at the stall force");
    let band = c.held_band.unwrap();
    assert_eq!(band.lower, c.stall.force);
    assert!(
        (band.upper - upper).abs() <= 1e-9 * upper,
        "upper {} vs {upper}",
        band.upper
    );
    assert!(
        c.points
            .iter()
            .any(|p| p.marks.contains(&LoadMark::HeldEdge))
    );
}

#[test]
fn the_load_enters_as_minus_f_over_m() {
    // Ideal continuous signal, kappa = 4 (docs/model.md section 7): after
    // the jump the slider slips backward with -a_d + g_t until the rod
    // overtakes it at t*, then forward with a_d + g_t. Periodicity gives
    // t* = T (a_d + g_t) / (2 a_d), the boundary velocity
    // u = (a_R + a_d - g_t) t*, and the step
    // x = t*^2 (a_R + (a_d - g_t)/2) + a_R t* (T - t*) + (a_d + g_t)(T - t*)^2 / 2,
    // v_inf = x / T (T (2 a_R + a_d) / 4 at g_t = 0), valid for |g_t| < a_d.
    // With g_t = -F/m_s a load F > 0 slows the slider.
    let sc = Scene {
        signal: SignalSpec::ideal(25e-6, 4.0, 1.0),
        actuator: None,
        ..Scene::default()
    };
    let motor = Motor::new(sc.motor).unwrap();
    let (a_r, a_d) = (4.0 * motor.a_0(), motor.a_d());
    let t = match &sc.signal {
        SignalSpec::Ideal(shape) => shape.times(&motor).period,
        _ => unreachable!(),
    };
    let closed = |g: f64| {
        let ts = t * (a_d + g) / (2.0 * a_d);
        let r = t - ts;
        (ts * ts * (a_r + 0.5 * (a_d - g)) + a_r * ts * r + 0.5 * (a_d + g) * r * r) / t
    };
    let c = characteristic::characteristic(&sc, &coarse((-0.1, 0.1))).unwrap();
    let mut checked = 0;
    for p in &c.points {
        let e = &p.evaluation;
        let g = e.extra_acceleration;
        assert_eq!(g, -e.load / sc.motor.slider_mass);
        let v = e.v_inf.unwrap();
        let expected = closed(g);
        assert!(
            (v - expected).abs() <= e.error.unwrap() + 1e-14 * expected.abs(),
            "F = {}: {v:e} vs {expected:e}",
            e.load
        );
        checked += 1;
    }
    assert!(checked >= 17, "{checked} points");
    // v_inf -> 0 only as g_t -> -a_d, where sliding friction can no longer
    // hold the load and the slider runs away: the stall force is that
    // limit, m_s a_d = mu_d F_c.
    assert_eq!(c.stall.kind, StallKind::RunAway);
    let limit = sc.motor.mu_dynamic * sc.motor.contact_force;
    assert!((c.stall.force - limit).abs() <= 1e-9 * c.holding_force);
    assert!(c.stall.force <= limit + 1e-9 * c.holding_force);
}

#[test]
fn startup_force_of_the_ideal_signals() {
    // The start-up from rest at zero load (docs/model.md section 7): with
    // kappa <= 1 the slider sticks through period 1, v_1 = x_Rmax / T =
    // a_R T / 2, so m_s v_1 / (T/2) = m_s kappa a_0 = kappa mu_0 F_c; with
    // kappa > 1 it slips forward with a_d through period 1, v_1 = a_d T / 2,
    // giving m_s a_d = mu_d F_c. The largest per-period force is at least
    // the initial one.
    let m = Scene::default().motor;
    for (kappa, expected) in [
        (0.5, 0.5 * m.mu_static * m.contact_force),
        (4.0, m.mu_dynamic * m.contact_force),
    ] {
        let sc = Scene {
            signal: SignalSpec::ideal(25e-6, kappa, 1.0),
            ..Scene::default()
        };
        let c = characteristic::characteristic(&sc, &coarse((0.0, 0.01))).unwrap();
        let t = c.transient.expect("a start-up");
        assert_rel(t.initial_force, expected, 1e-12, "initial start-up force");
        assert!(t.max_force >= t.initial_force);
    }
}

#[test]
fn a_mirrored_drive_has_the_mirrored_characteristic() {
    // Mirroring (docs/model.md section 7): the signal -x_R(t) with -g_t
    // gives exactly -v_inf. Without the shift to the minimum both signals
    // keep their time origin, so the start-up mirrors too: the mirrored
    // drive moves backwards, stalls at -F_stall, delivers the same largest
    // power at -F, and a start-up measurement reports the opposite force.
    let harmonics = |phases: [f64; 2]| {
        scene(&format!(
            "[signal]\nkind = \"harmonics\"\nfrequency = 1574.8\namplitudes = [8.4e-6, 2.0e-6]\n\
             phases = [{:?}, {:?}]\nscale_to_stroke = false\nshift_to_minimum = false\n",
            phases[0], phases[1]
        ))
    };
    let phases = [2.833423582473808, 2.9837614633016343];
    let pi = std::f64::consts::PI;
    let forward = harmonics(phases);
    let backward = harmonics([phases[0] - pi, phases[1] - pi]);
    let cf = characteristic::characteristic(&forward, &coarse((-0.05, 0.05))).unwrap();
    let cb = characteristic::characteristic(&backward, &coarse((-0.05, 0.05))).unwrap();
    assert_eq!((cf.drive, cb.drive), (1, -1));
    assert_rel(
        cb.no_load.v_inf.unwrap(),
        -cf.no_load.v_inf.unwrap(),
        1e-12,
        "no-load speed",
    );
    assert_rel(cb.stall.force, -cf.stall.force, 1e-9, "stall force");
    let (pf, pb) = (cf.max_power.unwrap(), cb.max_power.unwrap());
    assert_rel(pb.power, pf.power, 1e-9, "largest power");
    let (tf, tb) = (cf.transient.unwrap(), cb.transient.unwrap());
    assert_rel(tb.initial_force, -tf.initial_force, 1e-9, "start-up force");
    // The datasheet states magnitudes: the same for both.
    let (sf, sb) = (
        cf.datasheet.stall_force.unwrap(),
        cb.datasheet.stall_force.unwrap(),
    );
    assert_rel(sb, sf, 1e-9, "datasheet stall force");
    for p in &cf.points {
        let (v, e) = v_inf_at(&backward, -p.evaluation.load);
        let expected = -p.evaluation.v_inf.unwrap();
        assert!(
            (v - expected).abs() <= e + p.evaluation.error.unwrap(),
            "F = {}",
            p.evaluation.load
        );
    }
}

#[test]
fn v_inf_does_not_increase_with_the_load() {
    // The comparison argument (docs/model.md section 3 applied to g_t): a
    // slider pushed harder never overtakes one pushed less.
    let c = default_characteristic();
    let steady: Vec<_> = c
        .points
        .iter()
        .filter_map(|p| {
            p.evaluation
                .v_inf
                .map(|v| (p.x, v, p.evaluation.error.unwrap_or(0.0)))
        })
        .collect();
    assert!(steady.len() > 40, "{} points", steady.len());
    for w in steady.windows(2) {
        assert!(w[1].1 <= w[0].1 + w[0].2 + w[1].2, "{w:?}");
    }
    // The curve ends where the slider runs away, within [mu_d F_c, mu_0 F_c]
    // in magnitude (docs/model.md section 9 and the holding-force argument
    // of src/characteristic/domain.rs).
    let m = Scene::default().motor;
    for limit in [c.run_away_below.unwrap(), c.run_away_above.unwrap()] {
        let f = limit.load().abs();
        assert!(f >= m.mu_dynamic * m.contact_force * (1.0 - 1e-9) && f <= c.holding_force);
        assert_eq!(limit.first_unsteady.regime, "run-away");
        assert!(limit.width() <= 1e-9 * c.holding_force);
    }
}

#[test]
fn incline_loads_are_the_weight_component() {
    // F = m_s g sin(theta); the paper's slider (1.4 g) weighs 0.0137 N, less
    // than the stall force, so the drive climbs at every angle, and at rest
    // it holds on any incline since mu_0 F_c > m_s g.
    let sc = Scene::default();
    let options = CharacteristicOptions {
        axis: LoadAxis::Incline,
        tolerance: 0.5,
        max_evaluations: 20,
        ..CharacteristicOptions::default()
    };
    let c = characteristic::characteristic(&sc, &options).unwrap();
    let weight = sc.motor.slider_mass * characteristic::G;
    for p in &c.points {
        let f = p.evaluation.load;
        assert!(
            (f - weight * p.x.to_radians().sin()).abs() <= 1e-15,
            "{p:?}"
        );
    }
    let up = c
        .points
        .iter()
        .find(|p| p.x == 90.0)
        .expect("theta = 90 deg");
    assert_eq!(up.evaluation.load, weight);
    assert!(up.evaluation.v_inf.unwrap() > 0.0);
    let i = c.incline.unwrap();
    assert_eq!(i.stall_angle, None);
    assert_eq!(i.holding_angle, 90.0);
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn bad_input_is_one_line_naming_the_flag_or_field() {
    let dir = scratch("characteristic", "bad_input");
    let frictionless = dir.join("frictionless.toml");
    std::fs::write(
        &frictionless,
        "[motor]\nslider_mass = 1.4e-3\ncontact_force = 1.0\nmu_static = 0.0\nmu_dynamic = 0.0\n",
    )
    .unwrap();
    let frictionless = frictionless.to_str().unwrap();
    let figure = dir.join("f.gif");
    for (args, expected) in [
        (
            vec!["--tolerance", "0"],
            "--tolerance 0: must be from 1e-6 to 0.5",
        ),
        (
            vec!["--from", "0.1", "--to", "0"],
            "--to 0: must be above --from 0.1",
        ),
        (
            vec!["--load", "incline", "--from", "-100"],
            "--from -100: must be an angle from -90 to 90 degrees",
        ),
        (
            vec!["--max-evaluations", "5"],
            "--max-evaluations 5: must be at least 20",
        ),
        (
            vec![frictionless],
            "motor.mu_static = 0: must be positive for a characteristic",
        ),
        (vec!["--figure", figure.to_str().unwrap()], "f.gif"),
    ] {
        let mut all = vec!["characteristic"];
        all.extend(args.iter().copied());
        let o = stickslip(&all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{all:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{all:?}: {err}");
        assert!(
            err.starts_with("stickslip: ") && err.contains(expected),
            "{all:?}: {err}"
        );
        assert!(o.stdout.is_empty());
    }
    assert!(!figure.exists());
    // A usage error (unknown value of --load) is clap's, exit 2.
    assert_eq!(
        stickslip(&["characteristic", "--load", "spring"])
            .status
            .code(),
        Some(2)
    );
}

#[test]
fn outputs_never_overwrite_the_input_or_each_other() {
    let dir = scratch("characteristic", "outputs");
    let scene_path = dir.join("scene.toml");
    let text = "[signal]\nkind = \"ideal\"\nstroke = 25e-6\nkappa = 0.5\nduty = 1.0\n";
    std::fs::write(&scene_path, text).unwrap();
    let s = scene_path.to_str().unwrap();
    let o = stickslip(&["characteristic", s, "-o", s]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("refusing to overwrite an input"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(&scene_path).unwrap(), text);
    let svg = dir.join("c.svg");
    // The figure's data file: its name with `.csv` appended.
    let csv = dir.join("c.svg.csv");
    let o = stickslip(&[
        "characteristic",
        s,
        "--figure",
        svg.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("named as two outputs"),
        "{}",
        stderr(&o)
    );
    assert!(!svg.exists() && !csv.exists());
    // Written: the table as CSV (by the extension), the figure and its CSV.
    let table = dir.join("table.csv");
    let o = stickslip(&[
        "characteristic",
        s,
        "--tolerance",
        "0.1",
        "--figure",
        svg.to_str().unwrap(),
        "-o",
        table.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let t = std::fs::read_to_string(&table).unwrap();
    assert!(t.starts_with("# stickslip_version"), "{t}");
    assert!(
        t.lines()
            .nth(2)
            .unwrap()
            .starts_with("load,extra_acceleration,regime,v_inf")
    );
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    // The figure's data is the table under the caption's line (what the
    // figure does not draw: no-load speed, stall force, ...).
    let data = std::fs::read_to_string(&csv).unwrap();
    let (caption, rest) = data.split_once('\n').unwrap();
    assert!(
        caption.starts_with("# caption: ") && caption.contains("stall force"),
        "{caption}"
    );
    assert_eq!(rest, t, "the figure's data is the table");
    assert_eq!(std::fs::read_to_string(&scene_path).unwrap(), text);
}

/// Object keys at every depth.
fn json_keys(value: &serde_json::Value, keys: &mut std::collections::BTreeSet<String>) {
    match value {
        serde_json::Value::Object(map) => {
            for (key, inner) in map {
                keys.insert(key.clone());
                json_keys(inner, keys);
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|i| json_keys(i, keys)),
        _ => {}
    }
}

#[test]
fn every_json_key_is_documented() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/interface.md"))
        .expect("docs/interface.md");
    let section = doc
        .split("### `stickslip characteristic")
        .nth(1)
        .expect("docs/interface.md has a section on stickslip characteristic");
    let dir = scratch("characteristic", "keys");
    let held = dir.join("held.toml");
    std::fs::write(
        &held,
        "[signal]\nkind = \"harmonics\"\nfrequency = 300.0\namplitudes = [12.5e-6]\nphases = [0.0]\n",
    )
    .unwrap();
    let mut keys = std::collections::BTreeSet::new();
    for args in [
        vec!["characteristic", "--json", "--tolerance", "0.1"],
        vec![
            "characteristic",
            "--json",
            "--tolerance",
            "0.1",
            "--load",
            "incline",
        ],
        vec![
            "characteristic",
            held.to_str().unwrap(),
            "--json",
            "--tolerance",
            "0.1",
        ],
    ] {
        let o = stickslip(&args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(!text.contains("NaN"));
        let v: serde_json::Value = serde_json::from_str(&text).expect("one JSON object");
        json_keys(&v, &mut keys);
    }
    for expected in [
        "stall",
        "held_band",
        "datasheet",
        "recommended_load",
        "unit",
        "slope",
    ] {
        assert!(keys.contains(expected), "no `{expected}` printed");
    }
    // The scene's own keys are documented with the scene files.
    let scene_keys: std::collections::BTreeSet<String> = {
        let mut k = std::collections::BTreeSet::new();
        let table: toml::Value = toml::from_str(&Scene::default().to_toml()).unwrap();
        let v = serde_json::to_value(table).unwrap();
        json_keys(&v, &mut k);
        k
    };
    let missing: Vec<&String> = keys
        .iter()
        .filter(|k| !scene_keys.contains(*k) && !section.contains(&format!("`{k}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "undocumented keys of characteristic --json: {missing:?}"
    );
}

#[test]
fn the_scene_s_own_extra_acceleration_is_replaced_by_the_load() {
    // The load is the characteristic's axis: a scene's own g_t (here one
    // that makes the slider run away, docs/model.md section 9) is replaced.
    let mut sc = Scene::default();
    sc.motor.extra_acceleration = 500.0;
    let c = characteristic::characteristic(&sc, &coarse((0.0, 0.02))).unwrap();
    assert_eq!(c.replaced_extra_acceleration, 500.0);
    assert_eq!(c.no_load.extra_acceleration, 0.0);
    assert!(matches!(
        stickslip::run(&sc, &stickslip::RunOptions::default()).unwrap(),
        Outcome::RunAway { .. }
    ));
}

/// The exact slopes of the default characteristic against central
/// differences of the exact `v_inf(F)` (step `1e-6 mu_0 F_c`): where the
/// event structure is the same on both sides they agree to 1e-5 relative
/// (the difference quotient's own error is about 1e-6 plus the truncation
/// `h^2 v''' / 6`); at a one-sided point, the one-sided differences match
/// the one-sided slopes.
#[test]
fn exact_slopes_match_differences_of_v_inf() {
    let c = default_characteristic();
    let scene = Scene::default();
    let h = 1e-6 * 0.1736;
    let (mut smooth, mut one_sided) = (0, 0);
    for p in c.points.iter().step_by(7) {
        let f = p.evaluation.load;
        if p.evaluation.v_inf.is_none() || p.evaluation.regime == "stuck" {
            continue;
        }
        let (lo, mid, hi) = (
            v_inf_at(&scene, f - h).0,
            v_inf_at(&scene, f).0,
            v_inf_at(&scene, f + h).0,
        );
        match (p.slope.value, p.slope.left, p.slope.right) {
            (Some(s), _, _) => {
                smooth += 1;
                let d = (hi - lo) / (2.0 * h);
                assert!(
                    (s - d).abs() <= 1e-5 * d.abs().max(1e-3),
                    "F = {f}: {s} vs {d}"
                );
            }
            (None, Some(l), Some(r)) => {
                one_sided += 1;
                let (dl, dr) = ((mid - lo) / h, (hi - mid) / h);
                assert!(
                    (l - dl).abs() <= 1e-3 * dl.abs().max(1e-3),
                    "F = {f}: left {l} vs {dl}"
                );
                assert!(
                    (r - dr).abs() <= 1e-3 * dr.abs().max(1e-3),
                    "F = {f}: right {r} vs {dr}"
                );
            }
            _ => {}
        }
    }
    assert!(smooth >= 8, "{smooth} smooth points checked");
    eprintln!("{smooth} smooth and {one_sided} one-sided slopes checked");
}

/// The default scene without sliding friction (`mu_dynamic = 0`, as
/// `stickslip default-scene` with that one line changed): a slider that
/// slips feels no friction, so the period map is neutral (`P' = 1`)
/// wherever it slips. At zero load the slider slips from rest on and keeps
/// its velocity 0 (`v_inf = 0` exactly, no drive, no slope); any load makes
/// it drift by `g_t T` per period until it meets the rod where the rod's
/// velocity has an extremum (`a_R = 0`, inside the stick band), sticks and
/// is carried there: `v_inf` jumps from 0 to that extremum. The search from
/// rest cannot see that band; the covering from rest finds it (or proves
/// that the slider runs away) without simulating the start-up, which takes
/// up to `1e6` periods and more next to zero load. The characteristic is
/// complete, and the work it takes is bounded.
#[test]
fn a_drive_without_sliding_friction_has_a_complete_characteristic_in_bounded_runs() {
    let dir = scratch("characteristic", "no_sliding_friction");
    let mut scene = Scene::default();
    scene.motor.mu_dynamic = 0.0;
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene.to_toml()).unwrap();
    // The premise, from a run of its own: at zero load the slider never
    // sticks (no stick event from rest, none in the steady period), so its
    // acceleration is +-a_d + g_t = 0 throughout (docs/model.md section 1)
    // and its velocity stays at its initial 0: v_inf = 0 exactly, on a map
    // that is neutral there.
    let mut at_rest = scene.clone();
    at_rest.outputs.indicators = vec![Indicator::VInf, Indicator::StartupTime];
    let Outcome::Steady(r) = stickslip::run(&at_rest, &stickslip::RunOptions::default()).unwrap()
    else {
        panic!("no steady state at zero load");
    };
    let startup = r.transient.as_ref().expect("the start-up was simulated");
    let events = startup.events(startup.periods());
    assert_eq!(events.stick_to_slip + events.slip_to_stick, 0, "{events:?}");
    assert_eq!(r.steady.stats.events.slip_to_stick, 0);
    assert_eq!(r.steady.map_derivative, 1.0);
    assert_eq!(r.indicators.v_inf, 0.0);

    let json = dir.join("c.json");
    let figure = dir.join("c.svg");
    let clock = std::time::Instant::now();
    let o = stickslip(&[
        "characteristic",
        path.to_str().unwrap(),
        "-o",
        json.to_str().unwrap(),
        "--figure",
        figure.to_str().unwrap(),
        "-q",
    ]);
    let wall = clock.elapsed();
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    eprintln!(
        "mu_dynamic = 0: {} in {:.2} s (process)",
        v["evaluations"],
        wall.as_secs_f64()
    );

    // No drive: the stall force is 0 and the datasheet follows from
    // v_inf(0) = 0; the holding force is mu_0 F_c (closed form).
    assert_eq!(v["no_load_speed"], 0.0);
    assert_eq!(v["stall"]["kind"], "no-drive");
    assert_eq!(v["stall"]["force"], 0.0);
    assert!(v["held_band"].is_null(), "slipping is not held");
    let d = &v["datasheet"];
    assert_eq!(d["max_speed"]["value"], 0.0);
    assert_eq!(d["stall_force"]["value"], 0.0);
    assert_eq!(d["recommended_load"]["value"], 0.0);
    assert_eq!(d["max_output_power"]["value"], 0.0);
    assert_eq!(
        d["holding_force"]["value"].as_f64(),
        Some(scene.motor.mu_static * scene.motor.contact_force)
    );

    // The point at zero load: a steady state without a slope, absent in
    // JSON (null) and CSV (empty cells), method `unavailable`.
    let points = v["points"].as_array().unwrap();
    let zero: Vec<&serde_json::Value> = points.iter().filter(|p| p["load"] == 0.0).collect();
    assert_eq!(zero.len(), 1, "{points:?}");
    let zero = zero[0];
    assert_eq!(zero["v_inf"], 0.0);
    assert_eq!(zero["regime"], "slip-slip");
    assert_eq!(zero["slope_method"], "unavailable");
    // Loads next to 0 on both sides have a steady state, caught at an
    // extremum of the rod's velocity: the rod's velocity range (the
    // signal's) holds the pulling side's; the pushing side's is a local
    // maximum, found here on a fine grid of the rod's velocity.
    let motor = Motor::new(scene.motor).unwrap();
    let signal = Signal::build(&scene.signal, &motor).unwrap();
    let samples = 200_000;
    let rod: Vec<f64> = (0..=samples)
        .map(|i| signal.velocity(signal.period() * i as f64 / samples as f64))
        .collect();
    let extrema: Vec<f64> = rod
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) <= 0.0)
        .map(|w| w[1])
        .collect();
    let near_zero: Vec<&serde_json::Value> = points
        .iter()
        .filter(|p| p["load"] != 0.0 && !p["v_inf"].is_null())
        .collect();
    assert!(near_zero.len() >= 8, "{points:?}");
    for p in &near_zero {
        let v = p["v_inf"].as_f64().unwrap();
        // Within the stick band around the extremum: the slider is released
        // where |a_R - g_t| reaches a_0, `(a_0)^2 / (2 |d a_R / dt|)` below
        // it, a few 1e-5 m/s here.
        let nearest = extrema
            .iter()
            .map(|e| (e - v).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest < 1e-4,
            "v_inf {v} is {nearest} m/s from an extremum of v_R"
        );
        assert_eq!(p["regime"], "stick-slip", "{p}");
    }
    // Both ends of the curve are run-aways proven next to zero load (not a
    // start-up that did not converge), within 1e-3 of the range.
    for side in ["above", "below"] {
        let end = &v["run_away"][side];
        assert_eq!(end["regime"], "run-away", "{side}: {end}");
        let load = end["load"].as_f64().unwrap();
        assert!(load != 0.0 && load.abs() < 1e-3 * 0.1736, "{side}: {end}");
    }
    let marks: Vec<&str> = zero["marks"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|m| m.as_str())
        .collect();
    assert!(marks.contains(&"no_load"), "{marks:?}");
    for key in ["slope", "slope_left", "slope_right"] {
        assert!(zero[key].is_null(), "{key} at zero load: {}", zero[key]);
    }
    let csv = std::fs::read_to_string(stickslip::plot::data_path(&figure)).unwrap();
    let header: Vec<&str> = csv
        .lines()
        .find(|l| l.starts_with("load,"))
        .unwrap()
        .split(',')
        .collect();
    let row: Vec<&str> = csv
        .lines()
        .find(|l| l.starts_with("0,"))
        .expect("a CSV row at zero load")
        .split(',')
        .collect();
    let cell = |name: &str| row[header.iter().position(|h| *h == name).unwrap()];
    for name in ["slope", "slope_left", "slope_right"] {
        assert_eq!(cell(name), "", "{name}");
    }
    assert_eq!(cell("slope_method"), "unavailable");
    // Every other point with a steady state has its slope, exact or
    // one-sided: the sampling did not depend on the one that is missing.
    for p in points
        .iter()
        .filter(|p| p["load"] != 0.0 && !p["v_inf"].is_null())
    {
        assert!(
            p["slope_method"] == "exact" || p["slope_method"] == "one_sided",
            "{p}"
        );
    }

    // The work. v_inf evaluations: the 17 grid loads (zero among them);
    // each end of the curve a bisection from a grid step mu_0 F_c / 8 to
    // 1e-9 mu_0 F_c, at most ceil(log2(1.25e8)) = 27 halvings; the
    // refinement of the jumps (at zero load on both sides, and where the
    // extremum that catches the slider changes), at most 2 midpoints per
    // halving of a steady stretch (narrower than 4.4e-5 N, the widest found
    // here) down to 1e-6 of the range, ceil(log2(4.4e-5 / 3.5e-7)) = 7
    // halvings for each of 3 jumps; no stall search, held band or largest
    // power without drive.
    let n = &v["evaluations"];
    let bound = 17 + 2 * 27 + 3 * 2 * 7;
    assert!(n["v_inf"].as_u64().unwrap() <= bound, "{n}");
    assert_eq!(n["stall"], 0);
    assert_eq!(n["max_power"], 0);
    // Every load is decided by the covering or the search, none by a
    // start-up that runs to run.max_periods.
    assert_eq!(n["not_converged"], 0, "{n}");
}

/// Significant digits of a decimal number as printed (`0.0358685` has 6).
fn significant_digits(number: &str) -> usize {
    let mantissa = number.split(['e', 'E']).next().unwrap_or(number);
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').len()
}

/// The place value of a printed number's last digit (`0.0358` -> 1e-4,
/// `1.25e-3` -> 1e-5).
fn last_digit_place(number: &str) -> f64 {
    let mut parts = number.split(['e', 'E']);
    let mantissa = parts.next().unwrap_or(number);
    let exponent: i32 = parts.next().map_or(0, |e| e.parse().unwrap());
    let decimals = mantissa.split('.').nth(1).map_or(0, str::len) as i32;
    10f64.powi(exponent - decimals)
}

#[test]
fn the_summary_prints_no_digit_its_estimates_do_not_resolve() {
    // Every `VALUE ± ERROR` of the summary and the datasheet block stops
    // at the error's first digit (format_with_error): no printed digit is
    // worth less than a tenth of the error. No number shows more than the
    // 15 significant digits of a double computed through a few operations.
    let o = stickslip(&["characteristic", "examples/scenes/paper_default.toml"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let summary: Vec<&str> = text.lines().take_while(|l| !l.contains("F (N)")).collect();
    assert!(summary.iter().any(|l| l.starts_with("stall force")));
    let mut with_error = 0;
    for line in &summary {
        let words: Vec<&str> = line
            .split_whitespace()
            .map(|w| w.trim_matches(|c: char| c == ',' || c == '(' || c == ')'))
            .collect();
        for (i, w) in words.iter().enumerate() {
            if w.parse::<f64>().is_ok() && w.chars().any(|c| c.is_ascii_digit()) {
                assert!(significant_digits(w) <= 15, "{w} in: {line}");
            }
            if *w == "±" {
                let error: f64 = words[i + 1].parse().unwrap();
                assert!(
                    last_digit_place(words[i - 1]) >= error / 10.0,
                    "{} ± {error} shows digits below the error: {line}",
                    words[i - 1]
                );
                with_error += 1;
            }
        }
    }
    // No-load speed, stall force and its v_inf, the largest power and its
    // v_inf, two curve ends, four datasheet entries.
    assert!(
        with_error >= 11,
        "{with_error} estimates in:\n{}",
        summary.join("\n")
    );
}
