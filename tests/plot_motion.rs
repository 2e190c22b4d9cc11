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

/// The paper's motor with a load acceleration `g_t`, driven by the
/// default signal (rod accelerations far beyond the stick band).
fn loaded(g_t: f64) -> Scene {
    let mut scene = Scene::default();
    scene.motor.extra_acceleration = g_t;
    scene
}

/// `a_0 = mu_0 F_c / m_s` of the scene's motor (docs/model.md section 1).
fn a_0(scene: &Scene) -> f64 {
    let m = &scene.motor;
    m.mu_static * m.contact_force / m.slider_mass
}

/// Columns of the figure's CSV sample rows by header name.
fn column(csv: &str, name: &str) -> Vec<f64> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(csv.as_bytes());
    let at = reader
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("column {name}"));
    reader
        .records()
        .map(|r| r.unwrap())
        .filter(|r| &r[1] == "sample")
        .map(|r| r[at].parse().unwrap())
        .collect()
}

/// The acceleration row shows the stick band `g_t ± a_0`: where the rod's
/// acceleration reaches far beyond it, the row spans `BAND_SPAN = 3`
/// half-widths on either side of `g_t` (with `a_0` in closed form from the
/// motor's parameters), and the slider's acceleration, which the model
/// keeps inside the band (the rod's in stick, `±a_d + g_t` in slip), lies
/// in the row whole.
#[test]
fn the_acceleration_row_is_drawn_on_the_stick_bands_scale() {
    for g_t in [0.0, 40.0] {
        let scene = loaded(g_t);
        let a_0 = a_0(&scene);
        let f = motion::motion(
            &scene,
            &[Span::Periods(1, 1), Span::Periods(3, 3)],
            &[Row::Acceleration],
            "m",
        )
        .unwrap();
        let rod = column(&f.csv, "a_rod_m_per_s2");
        let slider = column(&f.csv, "a_slider_m_per_s2");
        let rod_reach = rod.iter().map(|a| (a - g_t).abs()).fold(0.0, f64::max);
        assert!(
            rod_reach > 10.0 * a_0,
            "the rod leaves the band: {rod_reach}"
        );
        assert_eq!(f.plot.panels.len(), 2);
        for panel in &f.plot.panels {
            let (lo, hi) = panel.y.range;
            let want = (g_t - 3.0 * a_0, g_t + 3.0 * a_0);
            assert!(
                (lo - want.0).abs() < 1e-9 * a_0 && (hi - want.1).abs() < 1e-9 * a_0,
                "g_t = {g_t}: range {lo} … {hi}, want {want:?}"
            );
        }
        for a in &slider {
            assert!(
                (a - g_t).abs() <= a_0 * (1.0 + 1e-9),
                "g_t = {g_t}: slider acceleration {a} outside the band"
            );
        }
        // The slider slips both ways (±a_d + g_t): the row shows more
        // than a flat line.
        let (lo, hi) = slider
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), a| (l.min(*a), h.max(*a)));
        assert!(hi - lo > a_0, "g_t = {g_t}: slider from {lo} to {hi}");
    }
}

/// A figure of one column names its span without a panel letter; with
/// several columns each carries its letter; rows below the first carry no
/// title.
#[test]
fn panel_letters_only_where_there_are_several_columns() {
    let rows = [Row::Velocity, Row::Acceleration];
    let one = motion::motion(&stick_heavy(), &[Span::Periods(1, 1)], &rows, "m").unwrap();
    let titles: Vec<Option<&str>> = one.plot.panels.iter().map(|p| p.title.as_deref()).collect();
    assert_eq!(titles, [Some("$p$ = 1"), None]);
    let two = motion::motion(
        &stick_heavy(),
        &[Span::Periods(1, 1), Span::Steady],
        &rows,
        "m",
    )
    .unwrap();
    let titles: Vec<Option<&str>> = two.plot.panels.iter().map(|p| p.title.as_deref()).collect();
    assert_eq!(
        titles,
        [
            Some("(a) $p$ = 1"),
            Some("(b) $p$\u{a0}→\u{a0}∞"),
            None,
            None
        ]
    );
}

/// `v_inf` is drawn after (over) the slider's velocity in the steady
/// column, in a colour of its own, and only there.
#[test]
fn v_inf_is_drawn_over_the_steady_slider_velocity() {
    let f = motion::motion(
        &Scene::default(),
        &[Span::Periods(1, 1), Span::Steady],
        &[Row::Velocity],
        "m",
    )
    .unwrap();
    let labels = |i: usize| -> Vec<&str> {
        f.plot.panels[i]
            .series
            .iter()
            .filter_map(|s| s.label.as_deref())
            .collect()
    };
    assert!(!labels(0).contains(&"$v_∞$"), "{:?}", labels(0));
    let steady = &f.plot.panels[1].series;
    let at = |label: &str| {
        steady
            .iter()
            .position(|s| s.label.as_deref() == Some(label))
    };
    let (v_inf, slider) = (at("$v_∞$").unwrap(), at("slider").unwrap());
    assert_eq!(v_inf, steady.len() - 1, "drawn last");
    assert!(v_inf > slider);
    assert_ne!(steady[v_inf].look.color, steady[slider].look.color);
    // At the steady state's v_inf (the run's report).
    let report = stickslip::run(&Scene::default(), &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .unwrap();
    assert_eq!(steady[v_inf].pieces[0][0].1, report.indicators.v_inf);
}

/// The start-up figure runs past `p_0.99` of the run's report, so its
/// mark lies inside the frame, and the periods after it continue the
/// start-up (not a restart from rest): each mean velocity is within 1 %
/// of `v_inf` and they keep approaching it.
#[test]
fn the_startup_runs_past_the_end_of_the_start_up_and_keeps_approaching_v_inf() {
    let scene = Scene::default();
    let report = stickslip::run(&scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .unwrap();
    let p99 = report.startup_periods.expect("a start-up");
    let v_inf = report.indicators.v_inf;
    let f = motion::startup(&scene, "s").unwrap();
    let end = motion::startup_end(p99);
    assert!(end >= p99 + 3 && end as f64 >= 1.2 * p99 as f64, "{end}");
    let panel = &f.plot.panels[0];
    assert!(panel.x.range.1 >= end as f64, "{:?}", panel.x.range);
    let mark = panel
        .series
        .iter()
        .find(|s| s.label.as_deref() == Some("$p_{0.99}$"))
        .expect("the p_0.99 mark");
    assert_eq!(mark.pieces[0][0].0, p99 as f64);
    assert!(panel.x.range.1 - p99 as f64 > 2.0);
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(f.csv.as_bytes());
    let rows: Vec<(u64, f64)> = reader
        .records()
        .map(|r| r.unwrap())
        .map(|r| (r[0].parse().unwrap(), r[1].parse().unwrap()))
        .collect();
    assert_eq!(rows.last().unwrap().0, end);
    let after: Vec<f64> = rows.iter().filter(|r| r.0 >= p99).map(|r| r.1).collect();
    assert_eq!(after.len() as u64, end - p99 + 1);
    for w in after.windows(2) {
        assert!(
            w[1] / v_inf >= 0.99 && w[1] / v_inf <= 1.0 + 1e-9,
            "{} of {v_inf}",
            w[1]
        );
        assert!(
            w[1] >= w[0] - 1e-12 * v_inf,
            "approaching: {} then {}",
            w[0],
            w[1]
        );
    }
}
