//! The binary under faults of its surroundings and of its input (issues 8
//! and 16): closed or full standard output, an output path that is the
//! input, endless or huge inputs, absurd work, the wall-clock budget,
//! warnings, and usage errors. Each test spawns the real binary and is
//! named after the item it guards.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn stickslip() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_stickslip"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn run(args: &[&str]) -> Output {
    stickslip().args(args).output().expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// A fresh folder for one test's files.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "stickslip-cli-faults-{}-{test}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A scene whose JSON (with its event log of 40 000 reversals) is several
/// MB: far more than a pipe buffers, so a writer must meet a closed pipe.
const LONG_LOG: &str = r#"
[signal]
kind = "fourier"
harmonics = 2
sigma = true
kappa = 1e6
stroke = 25e-6
[run]
max_periods = 20000
[outputs]
indicators = ["v_inf"]
events = true
"#;

/// The scene the CLI fuzzer found running past 20 s.
const SLOW_SCENE: &str = r#"
[motor]
slider_mass = 0.1257
contact_force = 19301.6
mu_static = 0.0751
mu_dynamic = 0.0102
[signal]
kind = "fourier"
harmonics = 42
kappa = 37087171.5
stroke = 2.29e-7
"#;

#[test]
fn a_closed_output_pipe_ends_the_command_quietly() {
    let dir = temp_dir("pipe");
    let scene = write(&dir, "long_log.toml", LONG_LOG);
    let mut child = stickslip()
        .args(["run", "--quiet", "--json"])
        .arg(&scene)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Like `head -c 10`: read ten bytes, then close the pipe.
    let mut head = [0u8; 10];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    let o = child.wait_with_output().unwrap();
    assert_eq!(head[0], b'{');
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    std::fs::remove_dir_all(dir).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_is_a_one_line_error() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = stickslip()
        .args(["run", "--json"])
        .stdout(full)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("stickslip: cannot write to standard output: No space left on device"),
        "{err}"
    );
}

#[test]
fn an_output_over_an_input_is_refused() {
    let dir = temp_dir("overwrite");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/paper_default.toml"),
    )
    .unwrap();
    let scene = write(&dir, "scene.toml", &text);
    let other_spelling = dir.join(".").join("scene.toml");
    for output in [&scene, &other_spelling] {
        let o = stickslip()
            .arg("run")
            .arg(&scene)
            .args(["--json", "-o"])
            .arg(output)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1));
        let err = stderr(&o);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("refusing to overwrite an input"), "{err}");
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
    }
    // Another output beside it is written.
    let out = dir.join("result.json");
    let o = stickslip()
        .arg("run")
        .arg(&scene)
        .args(["--json", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&out).unwrap().starts_with('{'));
    std::fs::remove_dir_all(dir).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn input_size_dev_zero_is_refused() {
    let clock = Instant::now();
    let o = run(&["run", "/dev/zero"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        "stickslip: cannot read scene file /dev/zero: the file holds more than 1048576 \
         bytes; input files are limited to 1048576 bytes (1 MiB)\n"
    );
    assert!(clock.elapsed() < Duration::from_secs(10));
}

#[test]
fn input_size_fifty_megabytes_of_newlines_refused_with_size() {
    let dir = temp_dir("size");
    let scene = dir.join("newlines.toml");
    std::fs::write(&scene, vec![b'\n'; 50 << 20]).unwrap();
    let o = stickslip().arg("run").arg(&scene).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("the file holds 52428800 bytes"), "{err}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn work_limit_check_with_absurd_steps_is_refused() {
    for steps in ["4294967295", "1000000000"] {
        let clock = Instant::now();
        let o = run(&["check", "--steps", steps]);
        assert_eq!(o.status.code(), Some(1));
        let err = stderr(&o);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!("stickslip: --steps = {steps}: gives ")),
            "{err}"
        );
        assert!(err.contains("above the limit of 100000000"), "{err}");
        assert!(clock.elapsed() < Duration::from_secs(10));
    }
}

#[test]
fn work_limit_fixed_engine_with_absurd_steps_is_refused() {
    let dir = temp_dir("fixed");
    let scene = write(
        &dir,
        "fixed.toml",
        "[run]\nengine = \"fixed\"\nsteps_per_harmonic = 4294967295\n",
    );
    let o = stickslip().arg("run").arg(&scene).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains(
            "run.steps_per_harmonic = 4294967295: gives 8589934590 fixed steps per period"
        ),
        "{err}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn time_limit_slow_scene_stops_at_the_budget() {
    let dir = temp_dir("budget");
    let scene = write(&dir, "slow.toml", SLOW_SCENE);
    let clock = Instant::now();
    let o = stickslip()
        .arg("run")
        .arg(&scene)
        .args(["--quiet", "--time-limit", "1"])
        .output()
        .unwrap();
    assert!(clock.elapsed() < Duration::from_secs(15));
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("stickslip: time limit of 1 s reached after "),
        "{err}"
    );
    // The scene's own budget does the same.
    let limited = write(
        &dir,
        "slow_limited.toml",
        &format!("{SLOW_SCENE}[run]\ntime_limit_s = 0.5\n"),
    );
    let o = stickslip()
        .arg("run")
        .arg(&limited)
        .arg("--quiet")
        .output()
        .unwrap();
    assert!(stderr(&o).starts_with("stickslip: time limit of 0.5 s reached after "));
    // A bad budget is a usage error naming the option.
    let o = run(&["run", "--time-limit", "-3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--time-limit = -3: must be positive"));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn plausibility_warnings_on_stderr_and_the_run_goes_on() {
    let dir = temp_dir("warnings");
    let scene = write(
        &dir,
        "stroke_25.toml",
        "[signal]\nkind = \"fourier\"\nharmonics = 2\nsigma = true\nsqrt_kappa = 6\nstroke = 25\n",
    );
    let warning = "stickslip: warning: signal.stroke = 25 m is above 1 mm; strokes are in \
                   metres (25 um = 2.5e-5 m)\n";
    for command in ["run", "check"] {
        let o = stickslip()
            .arg(command)
            .arg(&scene)
            .args(if command == "check" {
                &["--steps", "50"][..]
            } else {
                &["--json"][..]
            })
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(stderr(&o), warning);
        assert!(!o.stdout.is_empty());
    }
    let o = stickslip()
        .arg("run")
        .arg(&scene)
        .arg("--quiet")
        .output()
        .unwrap();
    assert!(o.status.success());
    assert_eq!(stderr(&o), "");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn usage_errors_say_what_was_wrong_and_exit_2() {
    for (args, first_line) in [
        (
            &["run", "--bogus"][..],
            "error: unexpected argument '--bogus' found",
        ),
        (
            &["merge"][..],
            "error: the following required arguments were not provided:",
        ),
        (
            &["check", "--steps"][..],
            "error: a value is required for '--steps <STEPS>' but none was supplied",
        ),
    ] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = stderr(&o);
        assert_eq!(err.lines().next(), Some(first_line), "{err}");
        // Clap's usage text follows, without colour codes.
        assert!(
            err.contains("Usage: stickslip") || err.contains("--help"),
            "{err}"
        );
        assert!(!err.contains('\u{1b}'), "{err}");
        assert!(o.stdout.is_empty());
    }
}

/// A long run on an interactive terminal says how far it got,
/// every 2 s, on standard error. `script` (util-linux) gives the run a
/// terminal; without one (as in every other test) nothing is printed.
#[test]
fn progress_a_long_run_on_a_terminal_reports_progress() {
    let dir = temp_dir("progress");
    let scene = write(&dir, "slow.toml", SLOW_SCENE);
    let command = format!(
        "{} run {} --time-limit 2.5",
        env!("CARGO_BIN_EXE_stickslip"),
        scene.display()
    );
    let o = std::process::Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
        .expect("script (util-linux) runs");
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("stickslip: running: ") && text.contains("periods simulated in 2 s"),
        "{text}"
    );
    // Without a terminal: no progress line.
    let o = stickslip()
        .arg("run")
        .arg(&scene)
        .args(["--time-limit", "2.5"])
        .output()
        .unwrap();
    assert!(!stderr(&o).contains("running:"), "{}", stderr(&o));
}
