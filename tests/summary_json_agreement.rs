//! The readable summary and `run --json` say the same about every
//! indicator: a value in one is a value in the other, and what is unknown
//! in one (`null`) is `none` in the other (docs/interface.md section 3),
//! over scenes where indicators are undefined (no sliding friction, a
//! stuck slider, no motion) or infinite.

mod common;

use common::stickslip;

const INDICATORS: [&str; 7] = [
    "v_inf",
    "startup_time",
    "smoothness",
    "durability",
    "friction_energy",
    "stiction_fraction",
    "velocity_per_power",
];

/// The value column of an indicator's line in the summary.
fn text_value<'a>(text: &'a str, name: &str) -> Option<&'a str> {
    text.lines().find_map(|l| {
        let mut words = l.split_whitespace();
        (words.next() == Some(name)).then(|| words.next()).flatten()
    })
}

#[test]
fn summary_and_json_agree_on_what_is_unknown() {
    let scenes = [
        "examples/scenes/paper_default.toml",
        "examples/scenes/ideal_stick_slip.toml",
        "examples/scenes/ideal_discrete.toml",
        "examples/scenes/stick_heavy.toml",
        "examples/scenes/harmonics.toml",
    ];
    let mut checked = 0;
    let mut unknown = 0;
    for scene in scenes {
        for mu_dynamic in [None, Some("0")] {
            for load in ["0", "-5", "5"] {
                let mut args = vec!["run", scene, "-q"];
                let set_mu = mu_dynamic.map(|m| format!("motor.mu_dynamic={m}"));
                let set_load = format!("motor.extra_acceleration={load}");
                if let Some(s) = &set_mu {
                    args.extend(["--set", s.as_str()]);
                }
                args.extend(["--set", set_load.as_str()]);
                let text = stickslip(&args);
                assert!(text.status.success(), "{args:?}");
                let text = String::from_utf8(text.stdout).unwrap();
                args.push("--json");
                let json = stickslip(&args);
                let json: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
                for name in INDICATORS {
                    let Some(value) = json.get(name) else {
                        continue;
                    };
                    let Some(shown) = text_value(&text, name) else {
                        // No steady state: the summary lists no indicator
                        // and the JSON has null.
                        assert!(value.is_null(), "{args:?} {name}: {value}");
                        assert!(text.contains("indicators: none"), "{args:?}");
                        continue;
                    };
                    checked += 1;
                    if value.is_null() {
                        unknown += 1;
                    }
                    // `startup_time` says why it is unknown.
                    let none = shown == "none" || shown == "not";
                    assert_eq!(
                        value.is_null(),
                        none,
                        "{args:?}: {name} is {value} in JSON and {shown} in the summary"
                    );
                    if let Some(e) = json["error_estimate"].get(name) {
                        let line = text
                            .lines()
                            .find(|l| l.split_whitespace().next() == Some(name))
                            .unwrap();
                        if e.is_null() && !value.is_null() {
                            assert!(
                                line.contains("± unknown") && !line.contains("(exact)"),
                                "{args:?}: {name} has no estimate in JSON: {line}"
                            );
                        }
                        if e.as_f64() == Some(0.0) {
                            assert!(line.contains("(exact)"), "{args:?}: {line}");
                        }
                    }
                }
            }
        }
    }
    // The set must hold undefined indicators, or the check says nothing.
    assert!(
        checked > 100 && unknown > 5,
        "{checked} checked, {unknown} unknown"
    );
}
