//! `stickslip bench`: the spring method's reading against stiffness beside
//! the stall force (weight method), its outputs and its refusals.

mod common;

use common::{data_text, in_process, scratch};
use stickslip::Scene;
use stickslip::bench::{self, BenchOptions, SpringKinds};

/// The independent reference's mean force of the tied spring at `k` on
/// the default signal (tests/data/spring_reference.csv, scipy).
fn reference_mean_force(k: f64) -> f64 {
    let text = data_text("spring_reference.csv");
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let headers = reader.headers().unwrap().clone();
    let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let (scene, spring, stiffness, mean) =
        (col("scene"), col("spring"), col("k"), col("mean_force"));
    reader
        .records()
        .map(Result::unwrap)
        .find(|r| {
            &r[scene] == "default" && &r[spring] == "tied" && r[stiffness].parse::<f64>() == Ok(k)
        })
        .unwrap_or_else(|| panic!("the reference has the tied spring at {k} N/m"))[mean]
        .parse()
        .unwrap()
}

/// Soft-spring limit (module docs of `stickslip::bench`): with a tied
/// spring the mean spring force balances the mean friction force, and as
/// k -> 0 the slider sees a constant load that must hold it, so the mean
/// force tends to the stall force with a difference of first order in k.
/// Checked over three decades, 10 to 1e4 N/m: the relative difference
/// over k is one constant (to 1 %), and that constant is the independent
/// reference's at 1 kN/m (scipy, 1.75e-7 relative there).
#[test]
fn tied_mean_force_tends_to_the_stall_force_in_proportion_to_the_stiffness() {
    let options = BenchOptions {
        from: 10.0,
        to: 1e4,
        points: 4,
        kinds: SpringKinds::Tied,
        ..BenchOptions::default()
    };
    let b = bench::bench(&Scene::default(), &options).unwrap();
    let stall = b.stall_force();
    let reference_slope = (reference_mean_force(1e3) - stall) / stall / 1e3;
    assert!(
        (1.7e-10..1.8e-10).contains(&reference_slope),
        "the reference's 1.75e-7 at 1 kN/m: {reference_slope:e}"
    );
    let ks: Vec<f64> = b.rows.iter().map(|r| r.stiffness).collect();
    assert_eq!(ks, [10.0, 100.0, 1e3, 1e4], "exact decades");
    for r in &b.rows {
        let reading = r.tied.as_ref().unwrap().reading.unwrap();
        let d = (reading.profile.force_mean - stall) / stall;
        let slope = d / r.stiffness;
        assert!(
            (slope / reference_slope - 1.0).abs() < 0.01,
            "k = {}: (F_mean - F_stall) / F_stall = {d:e}, {slope:e} per N/m against {reference_slope:e}",
            r.stiffness
        );
    }
    assert!(b.rows.iter().all(|r| r.free.is_none()), "only tied springs");
}

/// A free end at gap 0 that never loses contact is the tied spring (the
/// reference's free springs at 1e4 and 1e5 N/m read the tied ones'
/// forces); the ratio columns are the force over the stall force; every
/// value of the JSON and the CSV is finite.
#[test]
fn json_and_csv_hold_every_column_with_finite_values() {
    let (code, out, err) = in_process(&[
        "bench", "--from", "1e4", "--to", "1e5", "--points", "2", "--json", "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let stall = v["stall_force"].as_f64().unwrap();
    assert!(v["startup_force"].as_f64().unwrap() > stall);
    for key in [
        "stickslip_version",
        "scene_hash",
        "scene",
        "stall_kind",
        "holding_force",
    ] {
        assert!(!v[key].is_null(), "{key}");
    }
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for row in rows {
        for end in ["tied", "free"] {
            let c = &row[end];
            for key in [
                "force_mean",
                "force_max",
                "force_min",
                "force_mean_over_stall",
                "force_max_over_stall",
                "position_mean",
                "contact_fraction",
                "orbit_periods",
                "periods_simulated",
            ] {
                assert!(
                    c[key].as_f64().is_some_and(f64::is_finite),
                    "{end} {key}: {c}"
                );
            }
            let mean = c["force_mean"].as_f64().unwrap();
            assert_eq!(c["force_mean_over_stall"].as_f64().unwrap(), mean / stall);
            assert!(c["force_min"].as_f64().unwrap() <= mean);
            assert!(mean <= c["force_max"].as_f64().unwrap());
        }
        let (tied, free) = (&row["tied"]["force_mean"], &row["free"]["force_mean"]);
        let (tied, free) = (tied.as_f64().unwrap(), free.as_f64().unwrap());
        assert!((tied - free).abs() < 1e-12 * tied, "{tied} {free}");
        assert_eq!(row["free"]["contact_fraction"].as_f64(), Some(1.0));
    }

    let dir = scratch("bench", "csv");
    let path = dir.join("bench.csv");
    let (code, out, err) = in_process(&[
        "bench",
        "--from",
        "1e4",
        "--to",
        "1e5",
        "--points",
        "2",
        "--quiet",
        "-o",
        path.to_str().unwrap(),
    ]);
    assert_eq!((code, out.as_str()), (0, ""), "{err}");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let headers: Vec<String> = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_owned)
        .collect();
    assert_eq!(
        headers,
        [
            "stiffness",
            "spring",
            "regime",
            "force_mean",
            "force_max",
            "force_min",
            "force_mean_over_stall",
            "force_max_over_stall",
            "position_mean",
            "contact_fraction",
            "orbit_periods",
            "periods_simulated",
            "certificate",
            "note",
        ]
    );
    let records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), 4, "two stiffnesses, tied and free");
    for r in &records {
        for (name, cell) in headers.iter().zip(r.iter()) {
            if !["spring", "regime", "certificate", "note"].contains(&name.as_str()) {
                let x: f64 = cell.parse().unwrap_or_else(|_| panic!("{name} = {cell:?}"));
                assert!(x.is_finite(), "{name}");
            }
        }
        assert_eq!(&r[13], "", "a steady orbit needs no note");
    }
}

/// Bad options: one line naming the option and the value, exit 1,
/// nothing on the output stream and no file written.
#[test]
fn bad_options_are_refused_in_one_line_naming_the_option() {
    let dir = scratch("bench", "refused");
    let out_path = dir.join("b.json");
    let o = out_path.to_str().unwrap();
    for (args, names) in [
        (vec!["--from", "0"], ["--from", "0"]),
        (vec!["--from", "-5"], ["--from", "-5"]),
        (vec!["--to", "inf"], ["--to", "inf"]),
        (vec!["--from", "1e5", "--to", "1e3"], ["--to", "1000"]),
        (vec!["--points", "0"], ["--points", "0"]),
        (vec!["--points", "20000"], ["--points", "20000"]),
        (vec!["--figure", "x.txt"], ["--figure", "x.txt"]),
        (
            vec!["--set", "motor.slider_mass=-1"],
            ["motor.slider_mass", "-1"],
        ),
    ] {
        let mut all = vec!["bench", "-o", o];
        all.extend(&args);
        let (code, out, err) = in_process(&all);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("stickslip: "), "{err}");
        for name in names {
            assert!(err.contains(name), "{args:?}: {err} names {name}");
        }
        assert!(!out_path.exists(), "{args:?}: nothing written");
    }
    let (code, _, err) = in_process(&["bench", "--tied", "--free"]);
    assert_eq!(code, 2, "a usage error: {err}");
}
