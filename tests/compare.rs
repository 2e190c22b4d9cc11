//! `stickslip compare` against fixtures from an independent fixed-step
//! simulation of the paper's motor (tests/data/compare/generate.py, which
//! shares no code with the engines; scipy's savemat wrote the MAT files):
//! per-period series and first-period samples at 21 steps, and the
//! exports users make (trajectories only, of a run stopped before its
//! start-up ends; Simulink's "Structure with time", "Array", a matrix
//! with named columns).

mod common;

use common::in_process as cli;

const DIR: &str = "tests/data/compare";
const RESOLUTIONS: [u32; 21] = [
    500, 561, 629, 706, 792, 889, 998, 1119, 1256, 1409, 1581, 1774, 1991, 2233, 2506, 2812, 3155,
    3540, 3972, 4456, 5000,
];

fn file(name: &str) -> String {
    format!("{DIR}/{name}")
}

fn json(args: &[&str]) -> (u8, serde_json::Value) {
    let mut all = vec!["compare", "examples/scenes/paper_default.toml"];
    all.extend_from_slice(args);
    all.push("--json");
    let (code, out, err) = cli(&all);
    assert!(code <= 1, "compare failed: {err}");
    (code, serde_json::from_str(&out).unwrap())
}

/// The fixture's own last v_p, read directly (the user's v_inf).
fn fixture_v_inf(name: &str) -> f64 {
    let text = std::fs::read_to_string(file(name)).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "v_p").unwrap();
    lines
        .filter_map(|l| l.split(',').nth(col).filter(|c| !c.is_empty()))
        .next_back()
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn v_inf_errors_equal_the_directly_computed_ones() {
    // Our v_inf from `run --json` (the event engine), the user's from the
    // fixture's own last v_p.
    let (_, out, _) = cli(&["run", "examples/scenes/paper_default.toml", "--json"]);
    let v_inf = serde_json::from_str::<serde_json::Value>(&out).unwrap()["v_inf"]
        .as_f64()
        .unwrap();
    for s in [500, 1581, 5000] {
        let name = format!("fixed_{s}.csv");
        let (_, report) = json(&[&file(&name)]);
        let reported = report["files"][0]["errors"]["v_inf"]["absolute"]
            .as_f64()
            .unwrap();
        let direct = (fixture_v_inf(&name) - v_inf).abs();
        assert!(
            (reported - direct).abs() <= 0.01 * direct,
            "{name}: {reported} vs {direct}"
        );
    }
}

#[test]
fn event_times_of_a_fixed_step_result_are_found_between_samples_and_none_is_missed() {
    for s in [500, 5000] {
        let (_, report) = json(&[&file(&format!("fixed_{s}.csv"))]);
        let f = &report["files"][0];
        let step = f["step"].as_f64().unwrap();
        // h = T / (2 s): the generator's step (n = 2 harmonics).
        let period = report["period"].as_f64().unwrap();
        approx::assert_relative_eq!(step, period / (2.0 * s as f64), max_relative = 1e-6);
        let e = &f["events"];
        assert!(e["exact"].as_u64().unwrap() >= 1);
        assert_eq!(e["missed"], 0);
        assert_eq!(e["spurious"], 0);
        let max = e["max_time_error"].as_f64().unwrap();
        // The first period's event ends the slip from rest, which the
        // generator integrates exactly (constant acceleration a_d, exact
        // at its nodes): the zero of v_rel between the samples is the
        // exact event to the error of the quadratic through three slip
        // samples, O(h^3); shown at the step after it, it would be off by
        // up to one step.
        assert!(max <= 0.01 * step, "{s}: {max} vs step {step}");
    }
}

#[test]
fn the_order_over_a_decade_of_steps_is_one() {
    let files: Vec<String> = RESOLUTIONS
        .iter()
        .map(|s| file(&format!("fixed_{s}.csv")))
        .collect();
    let args: Vec<&str> = files.iter().map(String::as_str).collect();
    let (code, report) = json(&args);
    // The coarse files miss the default tolerance 1e-3: a failed verdict.
    assert_eq!(code, 1);
    let fit = &report["convergence"]["v_inf"];
    assert_eq!(fit["points"], 21);
    assert_eq!(fit["supported"], true);
    // First order: events are placed to one step (docs/model.md section 12).
    let q = fit["order"].as_f64().unwrap();
    assert!((q - 1.0).abs() <= 0.35, "order {q}");
    assert!(fit["step_for_tolerance"].as_f64().unwrap() > 0.0);
}

#[test]
fn csv_and_mat_twins_give_identical_reports() {
    let (_, csv) = json(&[&file("fixed_5000.csv")]);
    let (_, mat) = json(&[&file("fixed_5000.mat")]);
    let mut a = csv["files"][0].clone();
    let mut b = mat["files"][0].clone();
    a["file"] = serde_json::Value::Null;
    b["file"] = serde_json::Value::Null;
    assert_eq!(a, b);
    // The rod of the independent rebuild matches ours to rounding.
    assert_eq!(a["rod"]["matches"], true);
}

#[test]
fn a_rod_without_the_shift_is_recognised() {
    let (_, report) = json(&[&file("rod_no_shift.csv"), &file("fixed_5000.csv")]);
    let rod = &report["files"][0]["rod"];
    assert_eq!(rod["matches"], false);
    assert_eq!(rod["diagnosis"], serde_json::json!(["missing_shift"]));
}

#[test]
fn a_rod_with_the_wrong_phase_is_recognised() {
    let (_, report) = json(&[&file("rod_wrong_phase.csv"), &file("fixed_5000.csv")]);
    assert_eq!(
        report["files"][0]["rod"]["diagnosis"],
        serde_json::json!(["wrong_phase"])
    );
}

#[test]
fn a_rod_without_stroke_scaling_is_recognised() {
    let (_, report) = json(&[&file("rod_unscaled.csv"), &file("fixed_5000.csv")]);
    assert_eq!(
        report["files"][0]["rod"]["diagnosis"],
        serde_json::json!(["scaling"])
    );
}

fn bad(content: &str, ext: &str) -> String {
    let dir = std::env::temp_dir().join(format!("stickslip-compare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("bad{}.{ext}", content.len()));
    std::fs::write(&path, content).unwrap();
    let (code, out, err) = cli(&[
        "compare",
        "examples/scenes/paper_default.toml",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 3, "bad input exits 3: {out}{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

#[test]
fn bad_data_names_file_column_and_row() {
    let e = bad("t,v_S\n0,0\n1e-6,nan\n", "csv");
    assert!(
        e.contains("column v_S, row 2 (line 3)") && e.contains("NaN"),
        "{e}"
    );
    let e = bad("t,v_S\n0,0\n0,1\n", "csv");
    assert!(
        e.contains("column t, row 2") && e.contains("repeats"),
        "{e}"
    );
    let e = bad("t,v_S\n1e-6,0\n0,1\n", "csv");
    assert!(e.contains("column t, row 2") && e.contains("before"), "{e}");
    let e = bad("t,v_S\n0,x\n", "csv");
    assert!(e.contains("column v_S, row 1") && e.contains("`x`"), "{e}");
    let e = bad("a,b\n0,0\n", "csv");
    assert!(e.contains("nothing to compare"), "{e}");
    let e = bad("t,v_S\n0,0\n1e9,0\n", "csv");
    assert!(e.contains("after the simulated span"), "{e}");
    let e = bad("t,v_S\n-1e-6,0\n0,0\n", "csv");
    assert!(e.contains("before the simulated span"), "{e}");
    let e = bad("not a mat file", "mat");
    assert!(e.contains("not a MATLAB Level 5 MAT-file"), "{e}");
}

#[test]
fn the_figure_format_follows_the_extension() {
    let dir = std::env::temp_dir().join(format!("stickslip-cmp-fig-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (ext, magic) in [
        ("svg", b"<svg".as_slice()),
        ("pdf", b"%PDF".as_slice()),
        ("png", b"\x89PNG".as_slice()),
    ] {
        let path = dir.join(format!("cmp.{ext}"));
        let (code, _, err) = cli(&[
            "compare",
            "examples/scenes/paper_default.toml",
            &file("fixed_5000.csv"),
            "--figure",
            path.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{err}");
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(magic), "{ext}");
    }
}

#[test]
fn trajectory_export_is_the_closed_form_at_the_given_times() {
    let dir = std::env::temp_dir().join(format!("stickslip-traj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let traj = dir.join("t.csv");
    let (code, _, err) = cli(&[
        "run",
        "--trajectory",
        traj.to_str().unwrap(),
        "--sample-rate",
        "1e6",
        "--periods",
        "1..1",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&traj).unwrap();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    // The start-up begins in forward slip from rest (a_R(0+) > a_0), so
    // until the first event v_S = a_d t and x_S = a_d t^2 / 2 with
    // a_d = mu_d F_c / m_s = 112 m/s^2 (docs/model.md sections 1, 6).
    let a_d = 0.1568 / 1.4e-3;
    let r = &rows[5];
    let t: f64 = r[0].parse().unwrap();
    approx::assert_relative_eq!(r[5].parse::<f64>().unwrap(), a_d * t, max_relative = 1e-12);
    approx::assert_relative_eq!(
        r[4].parse::<f64>().unwrap(),
        0.5 * a_d * t * t,
        max_relative = 1e-12
    );
    assert_eq!(r[6], "slip_forward");
}
