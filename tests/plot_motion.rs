//! A scene's motion figure (`src/plot/motion.rs`): the data behind it is
//! the exact motion, continuous where the physics is.

use stickslip::Scene;
use stickslip::SignalSpec;
use stickslip::plot::motion::{self, Row, Span, parse_periods};

/// The stick-heavy scene of `examples/scenes/stick_heavy.toml`.
fn stick_heavy() -> Scene {
    Scene {
        signal: SignalSpec::fourier(25e-6, 0.36, 5, true),
        ..Scene::default()
    }
}

/// `(t, x_slider, v_slider)` of the sample rows of the figure's CSV.
fn samples(csv: &str) -> Vec<(f64, f64, f64)> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(csv.as_bytes());
    reader
        .records()
        .map(|r| r.unwrap())
        .filter(|r| &r[1] == "sample")
        .map(|r| {
            (
                r[4].parse().unwrap(),
                r[6].parse().unwrap(),
                r[8].parse().unwrap(),
            )
        })
        .collect()
}

/// Regression: the slider's displacement over a span of several periods
/// jumped back to 0 at each period boundary (the engine counts positions
/// from each period's start). The slider moves continuously: two samples
/// at the same time (a segment's end and the next one's start) have the
/// same position, and between samples the position changes by no more
/// than the largest speed allows.
#[test]
fn multi_period_span_carries_the_slider_position() {
    let f = motion::motion(
        &stick_heavy(),
        &[Span::Periods(2, 4)],
        &[Row::Displacement],
        "m",
    )
    .unwrap();
    let rows = samples(&f.csv);
    let v_max = rows.iter().map(|r| r.2.abs()).fold(0.0, f64::max);
    let mut boundaries = 0;
    for w in rows.windows(2) {
        let (dt, dx) = (w[1].0 - w[0].0, (w[1].1 - w[0].1).abs());
        assert!(dt >= 0.0, "time runs forward");
        assert!(
            dx <= v_max * dt * 1.001 + 1e-15,
            "jump of {dx:e} m at t = {:e} s",
            w[1].0
        );
        if dt == 0.0 {
            boundaries += 1;
        }
    }
    assert!(boundaries > 3, "segment boundaries were compared");
    // Three periods of forward motion: the end lies well above the start.
    assert!(rows.last().unwrap().1 > 2.0 * rows.iter().map(|r| r.1).fold(f64::MIN, f64::max) / 3.0);
}

#[test]
fn periods_parse_as_documented() {
    assert_eq!(
        parse_periods("1,2-3,last").unwrap(),
        [Span::Periods(1, 1), Span::Periods(2, 3), Span::Steady]
    );
    assert_eq!(parse_periods("steady").unwrap(), [Span::Steady]);
    for bad in ["0", "3-1", "x", "1,2,3,4,5", "", "1-"] {
        let e = parse_periods(bad).unwrap_err();
        assert!(e.starts_with(&format!("--periods {bad}:")), "{e}");
    }
}

/// A scene without a steady state still plots its numbered periods; the
/// steady period is a one-line error naming the outcome.
#[test]
fn a_run_away_scene_has_no_steady_period() {
    let mut scene = stick_heavy();
    scene.motor.extra_acceleration = 1e4;
    let numbered = motion::motion(&scene, &[Span::Periods(1, 2)], &[Row::Velocity], "m");
    assert!(numbered.is_ok(), "{:?}", numbered.err());
    let e = motion::motion(&scene, &[Span::Steady], &[Row::Velocity], "m")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no steady state") && e.contains("run-away"),
        "{e}"
    );
}
