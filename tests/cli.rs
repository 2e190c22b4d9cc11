//! The command line: the default scene, JSON keys of docs/interface.md, and
//! bad input giving a one-line reason with a non-zero exit.

use std::process::{Command, Output};

fn stickslip(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

#[test]
fn no_arguments_run_the_default_scene() {
    let o = stickslip(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    // v_inf of the paper's example, section 7: 0.297 m/s.
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("v_inf"))
        .unwrap();
    let value: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!((value - 0.297).abs() < 0.002, "{line}");
    assert!(text.contains("wall time") && text.contains("reversal"));
}

#[test]
fn json_has_the_interface_keys() {
    let o = stickslip(&["run", "examples/scenes/paper_default.toml", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(!text.contains("NaN") && !text.contains("nan"));
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for key in [
        "v_inf",
        "startup_time",
        "startup_periods",
        "smoothness",
        "durability",
        "friction_energy",
        "stiction_fraction",
        "apparent_power",
        "velocity_per_power",
        "period",
        "f0",
        "periods_simulated",
        "events",
        "wall_time_s",
        "error_estimate",
        "regime",
        "stickslip_version",
        "scene",
        "scene_hash",
        "setup_time_s",
        "simulation_time_s",
    ] {
        assert!(v.get(key).is_some(), "missing key {key}");
    }
    for kind in [
        "stick_to_slip",
        "slip_to_stick",
        "reversal",
        "grazing",
        "jump",
        "contact_start",
        "contact_end",
    ] {
        assert!(v["events"][kind].is_u64(), "events.{kind}");
    }
    // The JSON repeats the library's numbers: v_inf / S = velocity_per_power.
    let ratio = v["v_inf"].as_f64().unwrap() / v["apparent_power"].as_f64().unwrap();
    let vpp = v["velocity_per_power"].as_f64().unwrap();
    assert!((ratio - vpp).abs() <= 1e-15 * vpp);
    // Every reported indicator has an error estimate below 1e-9 relative.
    for name in ["v_inf", "smoothness", "durability", "velocity_per_power"] {
        let value = v[name].as_f64().unwrap();
        let err = v["error_estimate"][name].as_f64().unwrap();
        assert!(err >= 0.0 && err < 1e-9 * value.abs(), "{name}: ± {err}");
    }
}

#[test]
fn only_requested_indicators_are_reported() {
    let dir = std::env::temp_dir().join(format!("stickslip-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("only_v.toml");
    std::fs::write(&path, "[outputs]\nindicators = [\"v_inf\"]\n").unwrap();
    let o = stickslip(&["run", path.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!(v.get("v_inf").is_some());
    for absent in [
        "smoothness",
        "durability",
        "startup_time",
        "velocity_per_power",
    ] {
        assert!(v.get(absent).is_none(), "{absent} was not asked for");
    }
}

#[test]
fn bad_input_exits_non_zero_with_one_line_naming_the_field() {
    let dir = std::env::temp_dir().join(format!("stickslip-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "mass.toml",
            "[motor]\nslider_mass = -1.0\ncontact_force = 1.0\nmu_static = 0.2\nmu_dynamic = 0.1\n",
            "motor.slider_mass",
        ),
        (
            "nan.toml",
            "[motor]\nslider_mass = 1e-3\ncontact_force = nan\nmu_static = 0.2\nmu_dynamic = 0.1\n",
            "motor.contact_force",
        ),
        (
            "mu.toml",
            "[motor]\nslider_mass = 1e-3\ncontact_force = 1.0\nmu_static = 0.1\nmu_dynamic = 0.2\n",
            "motor.mu_dynamic",
        ),
        (
            "n0.toml",
            "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nkappa = 1.0\nharmonics = 0\n",
            "signal.harmonics",
        ),
        (
            "unknown.toml",
            "[motor]\nslider_mass = 1e-3\ncontact_force = 1.0\nmu_static = 0.2\nmu_dynamic = 0.1\ncolour = 3\n",
            "colour",
        ),
        ("broken.toml", "[motor\nslider_mass = ", "broken.toml"),
    ];
    for (name, text, field) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let o = stickslip(&["run", path.to_str().unwrap(), "--json"]);
        assert!(!o.status.success(), "{name} was accepted");
        assert!(stdout(&o).is_empty(), "{name}: no partial output");
        let err = stderr(&o);
        assert_eq!(err.trim_end().lines().count(), 1, "{name}: {err}");
        assert!(err.contains(field), "{name}: {err}");
    }
    let o = stickslip(&["run", "no/such/scene.toml"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("no/such/scene.toml"));
}
