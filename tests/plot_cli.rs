//! `stickslip plot` through `cli::main_with`: a scene's figures, a sweep
//! output with failed and unsettled rows, print formats, and arguments
//! validated like scenes (one line, exit 1, nothing created).

use std::path::{Path, PathBuf};
mod common;

const SWEEP_CSV: &str = "# stickslip_version = 0.1.0, base_scene_hash = 0\n\
case,level,harmonics,sigma,v_inf,regime,failure\n\
0,3,2,false,0.03,slip-slip,\n\
1,3,3,false,0.02,slip-slip,\n\
2,3,4,false,,run-away,\n\
3,6,2,false,0.07,stick-slip,\n\
4,6,3,false,,,time limit reached\n\
5,6,4,false,0.05,slip-slip,\n";

/// `stickslip plot ARGS...` in this process.
fn cli(args: &[&str]) -> (u8, String, String) {
    let mut all = vec!["plot"];
    all.extend_from_slice(args);
    common::in_process(&all)
}

/// A fresh directory for one test.
fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stickslip-plot-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn listing(d: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_scene_plot_writes_the_figure_and_its_data_the_same_twice() {
    let d = dir("scene");
    let out = d.join("motion.svg");
    let args = [
        "examples/scenes/stick_heavy.toml",
        "-o",
        s(&out),
        "--periods",
        "1,2-3,last",
    ];
    let (code, stdout, err) = cli(&args);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("motion.svg") && stdout.contains("motion.svg.csv"));
    let first = std::fs::read(&out).unwrap();
    let csv = std::fs::read_to_string(d.join("motion.svg.csv")).unwrap();
    // The summary prints the caption the CSV holds, line for line.
    let printed: Vec<&str> = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("caption: "))
        .collect();
    let stored: Vec<&str> = csv
        .lines()
        .filter_map(|l| l.strip_prefix("# caption: "))
        .collect();
    assert!(!printed.is_empty(), "{stdout}");
    assert_eq!(printed, stored);
    for kind in ["stick_to_slip", "slip_to_stick"] {
        assert!(
            csv.contains(&format!(",event,0,{kind},")),
            "events of kind {kind} in the CSV"
        );
    }
    assert_eq!(cli(&args).0, 0);
    assert_eq!(
        std::fs::read(&out).unwrap(),
        first,
        "same inputs, same bytes"
    );
    for figure in ["startup", "timeline"] {
        let out = d.join(format!("{figure}.pdf"));
        let (code, _, err) = cli(&[
            "examples/scenes/stick_heavy.toml",
            "-o",
            s(&out),
            "--figure",
            figure,
        ]);
        assert_eq!(code, 0, "{err}");
        assert!(std::fs::read(&out).unwrap().starts_with(b"%PDF"));
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// Failed and unsettled rows are drawn (on the bottom edge, by reason)
/// and listed in the figure's CSV, never dropped.
#[test]
fn a_sweep_plot_shows_failed_and_unsettled_rows() {
    let d = dir("sweep");
    let input = d.join("grid.csv");
    std::fs::write(&input, SWEEP_CSV).unwrap();
    let out = d.join("v.svg");
    let (code, _, err) = cli(&[
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "v_inf",
        "--series",
        "level",
        "--ref-y",
        "0.06",
    ]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains(r#"data-label="failed (1, at the bottom)""#),
        "failed row drawn"
    );
    assert!(svg.contains(r#"data-label="run-away (1, at the bottom)""#));
    let csv = std::fs::read_to_string(d.join("v.svg.csv")).unwrap();
    let rows = csv.lines().filter(|l| !l.starts_with('#')).count() - 1;
    assert_eq!(rows, 6, "every input row in the figure's data");
    assert!(csv.contains(",failed\n") && csv.contains(",run-away\n"));
    // Log axes and facets.
    let out = d.join("log.png");
    let (code, _, err) = cli(&[
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "v_inf",
        "--facet",
        "level",
        "--log-y",
        "--dpi",
        "100",
    ]);
    assert_eq!(code, 0, "{err}");
    let png = std::fs::read(&out).unwrap();
    // Two facets: the double-column preset, 175 mm at 100 dpi.
    let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
    assert_eq!(width, (175.0_f64 / 25.4 * 100.0).round() as u32);
    std::fs::remove_dir_all(&d).unwrap();
}

/// Every bad argument is one line naming it, exit 1, and nothing is
/// written (the directory holds only the input afterwards).
#[test]
fn bad_arguments_are_one_line_and_create_nothing() {
    let d = dir("bad");
    let input = d.join("grid.csv");
    std::fs::write(&input, SWEEP_CSV).unwrap();
    let out = d.join("f.svg");
    let missing = d.join("no/such/dir/f.svg");
    let scene = "examples/scenes/paper_default.toml";
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![s(&input), "-o", s(&out), "--x", "harmonics", "--y", "nope"],
            "--y nope: no such column",
        ),
        (
            vec![s(&input), "-o", s(&out), "--x", "stroke", "--y", "v_inf"],
            "--x stroke: no such column",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--series",
                "sigmas",
            ],
            "--series sigmas",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--facet",
                "n",
            ],
            "--facet n",
        ),
        (
            vec![s(&input), "-o", s(&out), "--x", "level"],
            "needs --x AXIS and --y INDICATOR",
        ),
        (
            vec![s(&input), "-o", s(&missing), "--x", "level", "--y", "v_inf"],
            "does not exist",
        ),
        (
            vec![s(&input), "-o", "f.jpg", "--x", "level", "--y", "v_inf"],
            ".svg, .pdf or .png",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--font-size",
                "6",
            ],
            "--font-size 6",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--dpi",
                "0",
            ],
            "--dpi 0",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--width",
                "5",
            ],
            "--width 5",
        ),
        (
            vec![s(&input), "-o", s(&out), "--x", "sigma", "--y", "failure"],
            "is not a number",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--log-x",
                "--ref-x",
                "-1",
            ],
            "--log-x",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--y-unit",
                "ms",
            ],
            "--y-unit ms: v_inf is in m/s, not s",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--x-unit",
                "mm",
            ],
            "--x-unit mm: level is a ratio",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--y-unit",
                "furlong/s",
            ],
            "--y-unit furlong/s: not a unit",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf,level",
            ],
            "--y v_inf,level: columns on one axis share a unit",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--label",
                "v_inf",
            ],
            "--label v_inf: expected COLUMN=TEXT",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf",
                "--label",
                "v_inf=$v",
            ],
            "each $ closed",
        ),
        (
            vec![
                s(&input),
                "-o",
                s(&out),
                "--x",
                "level",
                "--y",
                "v_inf,v_inf",
            ],
            "--y v_inf,v_inf: names v_inf twice",
        ),
        (
            vec![scene, "-o", s(&out), "--y-unit", "ms"],
            "--y-unit: applies to a sweep output",
        ),
        (
            vec![scene, "-o", s(&out), "--x", "level"],
            "--x: applies to a sweep output",
        ),
        (vec![scene, "-o", s(&out), "--periods", "0"], "--periods 0"),
        (
            vec![scene, "-o", s(&out), "--periods", "3-1"],
            "runs backwards",
        ),
        (
            vec!["no_such_scene.toml", "-o", s(&out)],
            "no_such_scene.toml",
        ),
        (vec!["grid.jsonl", "-o", s(&out)], "sweep outputs as CSV"),
    ];
    for (args, expected) in cases {
        let (code, _, err) = cli(&args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(
            err.starts_with("stickslip: ") && err.lines().count() == 1,
            "{args:?}: {err}"
        );
        assert!(err.contains(expected), "{args:?}: {err}");
        assert_eq!(listing(&d), ["grid.csv"], "{args:?} created a file");
    }
    assert_eq!(
        std::fs::read_to_string(&input).unwrap(),
        SWEEP_CSV,
        "input untouched"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// A regime column is optional, and a column that is empty in a
/// row without failure or regime is drawn as "no value".
#[test]
fn a_sweep_without_regime_or_failure_columns_plots() {
    let d = dir("plain");
    let input = d.join("other_tool.csv");
    std::fs::write(&input, "level,harmonics,v_inf\n3,2,0.03\n3,3,\n3,4,0.02\n").unwrap();
    let out = d.join("p.svg");
    let (code, _, err) = cli(&[s(&input), "-o", s(&out), "--x", "harmonics", "--y", "v_inf"]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains(r#"data-label="no value (1, at the bottom)""#));
    std::fs::remove_dir_all(&d).unwrap();
}

/// A figure's data file is the figure's name with `.csv` appended
/// (docs/interface.md, `plot`): a sweep output plotted beside itself keeps
/// it (`grid.csv` to `grid.svg`, data `grid.svg.csv`), a PNG and a PDF of
/// one name keep their own data, and an output whose data file would be
/// the input is refused with nothing written.
#[test]
fn a_figure_data_file_never_overwrites_an_input_or_another_figure_data() {
    let d = dir("data_names");
    let input = d.join("grid.csv");
    std::fs::write(&input, SWEEP_CSV).unwrap();
    let axes = ["--x", "harmonics", "--y", "v_inf"];
    for name in ["grid.svg", "x.png", "x.pdf"] {
        let out = d.join(name);
        let mut args = vec![s(&input), "-o", s(&out)];
        args.extend(axes);
        let (code, _, err) = cli(&args);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(d.join(format!("{name}.csv")).exists(), "{name}");
    }
    assert_eq!(std::fs::read_to_string(&input).unwrap(), SWEEP_CSV);
    let png_data = std::fs::read_to_string(d.join("x.png.csv")).unwrap();
    let pdf_data = std::fs::read_to_string(d.join("x.pdf.csv")).unwrap();
    assert_eq!(png_data, pdf_data, "the same figure's data");
    // An input named like the figure's data file.
    let named = d.join("p.svg.csv");
    std::fs::write(&named, SWEEP_CSV).unwrap();
    let out = d.join("p.svg");
    let mut args = vec![s(&named), "-o", s(&out)];
    args.extend(axes);
    let (code, _, err) = cli(&args);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("refusing to overwrite an input") && err.lines().count() == 1,
        "{err}"
    );
    assert!(!out.exists());
    assert_eq!(std::fs::read_to_string(&named).unwrap(), SWEEP_CSV);
}

/// Start-up times and periods in seconds, as a sweep writes them.
const TIMES_CSV: &str = "case,harmonics,sigma,startup_time,period,regime,failure\n\
0,2,false,0.05,0.0004,slip-slip,\n\
1,3,false,0.02,0.0006,slip-slip,\n\
2,4,false,0.004,0.0008,slip-slip,\n\
3,2,true,0.03,0.0004,slip-slip,\n";

/// The figure's data rows (after its `#` lines and header) as cells.
fn data_rows(csv: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let split = |l: &str| l.split(',').map(str::to_owned).collect::<Vec<_>>();
    let header = split(lines.next().expect("a header"));
    (header, lines.map(split).collect())
}

/// `--y-unit ms` draws seconds times 1000 (1 s = 1000 ms): the figure's
/// data says the unit in its header and holds the drawn values, the axis
/// and the reference line's legend entry say ms.
#[test]
fn a_display_unit_scales_the_drawn_values_by_its_factor() {
    let d = dir("units");
    let input = d.join("times.csv");
    std::fs::write(&input, TIMES_CSV).unwrap();
    let out = d.join("t.svg");
    let (code, _, err) = cli(&[
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "startup_time",
        "--y-unit",
        "ms",
        "--log-y",
        "--ref-y",
        "10",
    ]);
    assert_eq!(code, 0, "{err}");
    let (header, rows) = data_rows(&std::fs::read_to_string(d.join("t.svg.csv")).unwrap());
    let y = header
        .iter()
        .position(|h| h == "y (ms)")
        .expect("y (ms) in the header");
    let x = header
        .iter()
        .position(|h| h == "x")
        .expect("x in the header");
    let drawn: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r[x].parse().unwrap(), r[y].parse().unwrap()))
        .collect();
    let given = [(2.0, 0.05), (3.0, 0.02), (4.0, 0.004), (2.0, 0.03)];
    assert_eq!(drawn.len(), given.len());
    for ((dx, dy), (gx, gy)) in drawn.iter().zip(given) {
        assert_eq!(*dx, gx, "x has no unit and is drawn as given");
        assert!((dy - 1000.0 * gy).abs() <= 1e-12 * dy, "{dy} ms for {gy} s");
    }
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("(ms)<"), "the axis says ms");
    assert!(!svg.contains("(s)<"), "and not s");
    assert!(
        svg.contains(r#"data-label="$Tp_{0.99}$ = 10 ms""#),
        "the reference line is named by its quantity and value"
    );
    // The same in ASCII: `us` is µs, a million per second.
    let out = d.join("us.svg");
    let (code, _, err) = cli(&[
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "period",
        "--y-unit",
        "us",
    ]);
    assert_eq!(code, 0, "{err}");
    let (header, rows) = data_rows(&std::fs::read_to_string(d.join("us.svg.csv")).unwrap());
    let y = header.iter().position(|h| h == "y (µs)").expect("y (µs)");
    let first: f64 = rows[0][y].parse().unwrap();
    assert!(
        (first - 400.0).abs() < 1e-9,
        "0.0004 s is 400 µs, not {first}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// Two `--y` columns of one unit share the axis, and the legend names
/// each by its description and symbol from the table of symbols.
#[test]
fn two_y_columns_of_one_unit_have_one_legend_entry_each() {
    let d = dir("two_y");
    let input = d.join("times.csv");
    std::fs::write(&input, TIMES_CSV).unwrap();
    let out = d.join("two.svg");
    let (code, _, err) = cli(&[
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "startup_time",
        "--y",
        "period",
        "--y-unit",
        "ms",
    ]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    let mut labels: Vec<&str> = svg
        .split("data-label=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .filter(|l| !l.is_empty())
        .collect();
    labels.sort_unstable();
    labels.dedup();
    let named = |key: &str| {
        let s = stickslip::symbol::symbol(key).unwrap();
        format!("{} {}", s.description, s.quantity)
    };
    assert_eq!(labels, [named("period"), named("startup_time")]);
    // Each column's rows in the figure's data, by name.
    let (header, rows) = data_rows(&std::fs::read_to_string(d.join("two.svg.csv")).unwrap());
    let column = header.iter().position(|h| h == "y_column").unwrap();
    for key in ["startup_time", "period"] {
        assert_eq!(rows.iter().filter(|r| r[column] == key).count(), 4, "{key}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// Several `--y` columns with `--series` name each pair (column, value)
/// in the legend; more pairs than the palette's eight colours are
/// refused, with nothing written.
#[test]
fn several_y_columns_with_series_are_pairs_up_to_eight() {
    let d = dir("pairs");
    let input = d.join("times.csv");
    std::fs::write(&input, TIMES_CSV).unwrap();
    let out = d.join("p.svg");
    let mut args = vec![
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "startup_time,period",
        "--series",
        "sigma",
    ];
    let (code, _, err) = cli(&args);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    for pair in [
        "$Tp_{0.99}$, without sigma factors",
        "$Tp_{0.99}$, with sigma factors",
        "$T$, without sigma factors",
        "$T$, with sigma factors",
    ] {
        assert!(svg.contains(&format!("data-label=\"{pair}\"")), "{pair}");
    }
    // Five values of `harmonics` times two columns: ten entries.
    let many = d.join("many.csv");
    let mut text = String::from("harmonics,sigma,startup_time,period\n");
    for n in 2..7 {
        text.push_str(&format!("{n},false,0.01,0.001\n{n},true,0.02,0.001\n"));
    }
    std::fs::write(&many, text).unwrap();
    let out = d.join("m.svg");
    args[0] = s(&many);
    args[2] = s(&out);
    args[3] = "--x";
    args[4] = "sigma";
    args[8] = "harmonics";
    let (code, _, err) = cli(&args);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("--series harmonics: 2 --y columns times 5 values make 10 legend entries")
            && err.lines().count() == 1,
        "{err}"
    );
    assert!(!out.exists() && !d.join("m.svg.csv").exists());
    std::fs::remove_dir_all(&d).unwrap();
}

/// `--label COLUMN=TEXT` names the column on its axis and in the panel
/// titles of its facets instead of the table of symbols.
#[test]
fn a_label_replaces_the_column_name_on_axes_and_panel_titles() {
    let d = dir("label");
    let input = d.join("times.csv");
    std::fs::write(&input, TIMES_CSV).unwrap();
    let out = d.join("l.svg");
    let (code, _, err) = cli(&[
        s(&input),
        "-o",
        s(&out),
        "--x",
        "harmonics",
        "--y",
        "startup_time",
        "--facet",
        "sigma",
        "--label",
        "harmonics=drive harmonics",
        "--label",
        "sigma=smoothing",
    ]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains(">drive harmonics</text>"),
        "axis named by --label"
    );
    assert!(!svg.contains("number of harmonics"), "not by the table");
    assert!(svg.contains(">without smoothing</text>"));
    assert!(svg.contains(">with smoothing</text>"));
    std::fs::remove_dir_all(&d).unwrap();
}
