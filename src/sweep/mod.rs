//! Parameter sweeps: a grid of scenes run in parallel, one output row per
//! case, shardable over a job array and resumable.
//!
//! A sweep file (TOML) names a base scene and the axes to vary; the grid is
//! the cartesian product of the axes. Every case is checked with
//! [`Scene::validate`] when the sweep is loaded, before anything runs or is
//! written. `stickslip sweep FILE` runs the grid (or one shard of it) with
//! rayon and writes one CSV or JSON-lines row per case; `stickslip merge`
//! joins shard outputs.
//!
//! # Format
//!
//! ```toml
//! base = "../scenes/paper_default.toml"   # relative to the sweep file;
//!                                         # omitted: Scene::default()
//! [axes]                      # each a non-empty list without repeats
//! level = [3, 6, 9, 12, 15]   # f_max level L = n sqrt(kappa) (37): sqrt_kappa = L / n
//! harmonics = [2, 3, 4]       # n
//! sigma = [false, true]       # Lanczos sigma factors (15)
//!
//! [outputs]                   # optional
//! indicators = ["v_inf", "startup_time"]   # default: the base scene's
//! format = "csv"              # "csv" | "jsonl"; an output named *.csv or *.jsonl
//!                             # overrides it                   (default "csv")
//! ```
//!
//! The axes, in their fixed order (the first varies slowest):
//!
//! | axis | sets | values |
//! | --- | --- | --- |
//! | `level` | `sqrt(kappa) = level / n` (37), fourier signals | > 0 |
//! | `sqrt_kappa` | `signal.sqrt_kappa` | > 0 |
//! | `kappa` | `signal.kappa` | > 0 |
//! | `frequency` | `signal.frequency`, the drive frequency `f_0` (Hz) | > 0 |
//! | `f_max` | `signal.f_max = n f_0` (Hz), fourier signals | > 0 |
//! | `harmonics` | `signal.harmonics`, fourier signals | integers 1..=256 |
//! | `sigma` | `signal.sigma`, fourier signals | booleans |
//! | `stroke` | `signal.stroke` (or the `scale_to_stroke` target of kind = "harmonics") | > 0 |
//! | `duty` | `signal.duty` | (0, 1] |
//! | `mu_static` | `motor.mu_static` | >= 0 |
//! | `mu_dynamic` | `motor.mu_dynamic` | >= 0 |
//! | `contact_force` | `motor.contact_force` | > 0 |
//! | `slider_mass` | `motor.slider_mass` | > 0 |
//! | `extra_acceleration` | `motor.extra_acceleration` | finite |
//! | `spring.stiffness` | `spring.stiffness`, `k` (N/m) | > 0 |
//! | `spring.damping` | `spring.damping`, `b` (N s/m) | >= 0; 0 with a free end |
//! | `spring.gap` | `spring.gap`, `x_gap` (m), a free end | >= 0 |
//! | `spring.preload` | `spring.preload`, `F_p` (N), a tied spring | finite |
//!
//! The `spring.*` axes (TOML's dotted keys, `spring.stiffness = [...]`
//! under `[axes]`, or an `[axes.spring]` table) vary the base scene's
//! `[spring]` (docs/model.md section 17) and need one: `spring.gap` only
//! on a free end and `spring.preload` only on a tied spring, as the
//! `[spring]` table takes them.
//!
//! At most one of `level`, `sqrt_kappa`, `kappa`, `frequency` and `f_max`
//! may be given: each replaces the base scene's drive
//! ([`crate::signal::Drive`]), which is then held as given (a base given
//! by `frequency` keeps `f_0` along a `slider_mass` axis, one given by
//! `kappa` retunes it); `level` takes `n` from the `harmonics` axis, or
//! from the base scene without one.
//! Axes that do not fit the base signal (`harmonics` with `kind = "ideal"`)
//! are errors. The `base` scene's `[outputs] trajectory` and `events` are
//! ignored: a sweep writes one row per case.
//!
//! # Cases
//!
//! Case `i` (`0 <= i < N`, `N` the product of the axis lengths) takes the
//! values of a mixed-radix number in the axis order above, the last axis
//! varying fastest, like nested loops. The index depends on the sweep file
//! only, so shards, reruns and merges agree on it.
//!
//! # Output
//!
//! The first line is a header naming the program and the base scene:
//!
//! * CSV: `# stickslip_version = 0.1.0, base_scene_hash = 0123456789abcdef`,
//!   then the line of column names (read it with `comment='#'` in pandas);
//! * JSON lines: `{"base_scene_hash":"0123456789abcdef","stickslip_version":"0.1.0"}`,
//!   an object without a `case` key (skip it when reading rows).
//!
//! `base_scene_hash` is [`crate::provenance::scene_hash`] of the base scene
//! with the sweep's indicators. Then one row per case, sorted by case, with
//! the columns
//!
//! * `case`, then one column per axis (in the order above), then
//!   `scene_hash`: the fingerprint of the case's resolved scene (every
//!   parameter, not only the axis values), and `regime`: the outcome
//!   ([`crate::simulation::Outcome::regime`]; empty only for a failed run);
//! * each requested indicator under its `docs/interface.md` name, in the order
//!   of [`Indicator::ALL`]; `stiction_fraction` (the start-up from rest, as
//!   in `stickslip run --json`) is followed by `stiction_fraction_steady`
//!   and `velocity_per_power` by `apparent_power` (VA); empty without a
//!   steady state;
//! * with a `[spring]` in the base scene only, its reading (as in
//!   `stickslip run --json`): `spring_force_mean`, `spring_force_max`,
//!   `spring_force_min` (N), `spring_position_mean` (m),
//!   `contact_fraction`, `orbit_periods` (empty where no orbit locked),
//!   `spring_reading_periods`, and where no orbit locked
//!   `spring_force_mean_range_low` and `spring_force_mean_range_high` (N,
//!   the least and largest mean force of a single period); with a spring
//!   `error_v_inf` is empty (`v_inf` does not apply);
//! * `f0` (Hz): the case's drive frequency, from its scene (also in the
//!   row of a failed case); `period` (s), `startup_periods`, `periods_simulated`, `events_total`
//!   (events of the start-up), `last_v_p` (m/s, for `run-away` and
//!   `not_converged`), `wall_time_s`, `setup_time_s` and
//!   `simulation_time_s` (left out with [`SweepOptions::timing`] `= false`, so
//!   that the same sweep gives the same bytes), `error_v_inf` (estimated
//!   absolute error of `v_inf`), and `failure` (empty, or why the case's
//!   run failed; the row then holds nothing else but the case's columns).
//!
//! Numbers are written with the shortest digits that read back to the same
//! `f64`: Rust's `{}` (`{:e}` below `1e-4` and from `1e16`) in CSV,
//! serde_json's in JSON lines.
//! Values that do not exist (a start-up that was not reached, an infinite
//! smoothness) are empty in CSV and `null` in JSON lines. A JSON-lines row
//! is one object with the keys in column order.
//!
//! # Shards, reruns, merging
//!
//! A [`Shard`] `i/N` (`1 <= i <= N`, 1-based like Slurm's
//! `--array=1-N`) takes the cases with `index % N == i - 1`.
//!
//! If the output file exists, it must have the sweep's format and columns
//! (else it is refused and left alone). Its rows are kept, and their cases
//! not rerun, when the file's `stickslip_version` is this program's and the
//! row's axis values (compared exactly) and `scene_hash` are those of the
//! sweep's case; every other row is dropped and its case rerun, with a
//! message saying how many and why. So a rerun after the base scene, an
//! axis value or the program changed never keeps old numbers. A case that
//! failed is kept with its `failure` and not rerun.
//!
//! One sweep writes an output at a time: `OUTPUT.lock` holds the writer's
//! process id under an operating-system file lock (released however the
//! process ends, so a lock file left by a killed process does not block);
//! a second sweep on the same output is refused.
//!
//! Rows are appended, one whole line per write, as cases finish, in case
//! order (a finished case waits only for earlier cases still running), so
//! the file is always a header and complete rows. On SIGINT or SIGTERM
//! (`crate::interrupt`) the sweep takes no new case, writes the ones
//! running and stops (the CLI exits 130 or 143). A rerun keeps those rows
//! (a last line without its end is dropped), runs the rest, and at the end
//! rewrites the file sorted by case if the kept and new rows interleave:
//! the result equals an uninterrupted run row for row, and byte for byte
//! with [`SweepOptions::timing`] `= false`. Rewrites go through a temporary file
//! renamed over the output, never leaving half a file.
//!
//! The grid is never held in memory: a case is made from its index
//! ([`Sweep::case`]), so memory grows with the rows in flight and the rows
//! of an existing output, not with the number of cases (at most
//! [`MAX_CASES`]). Worker threads: `jobs` (default and maximum the
//! available parallelism), never more than the cases to run.
//!
//! [`merge`] joins shard outputs into a new file (never one of its inputs):
//! the same header line and columns in every input, every line complete
//! and every cell one a sweep could have written (no `NaN`, case indices
//! below [`MAX_CASES`]), each case in one input only; errors name the
//! input and the line (and the column), and nothing is written. The rows
//! are rewritten as a sweep writes them, sorted by case.
//!
//! ```sh
//! # One Slurm job array, 16 shards; a rerun of the array skips finished cases.
//! #SBATCH --array=1-16
//! stickslip sweep grid.toml --quiet --no-timing \
//!     --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT" \
//!     -j "$SLURM_CPUS_PER_TASK" -o "grid.$SLURM_ARRAY_TASK_ID.csv"
//! # Afterwards:
//! stickslip merge -o grid.csv grid.*.csv
//! ```
//!
//! # Library use
//!
//! ```
//! use stickslip::Scene;
//! use stickslip::sweep::{self, SweepAxis, Sweep};
//! use std::path::Path;
//!
//! let text = "[axes]\nlevel = [6]\nharmonics = [2, 3]\n[outputs]\nindicators = [\"v_inf\"]\n";
//! let sweep = Sweep::from_toml_str(text, "<string>", Path::new("."))?;
//! let cases = sweep.cases();
//! assert_eq!(cases.len(), 2);
//! assert_eq!(cases[1].value(SweepAxis::Harmonics).and_then(|v| v.as_f64()), Some(3.0));
//! // level 6 at n = 3: sqrt(kappa) = 2
//! assert_eq!(cases[1].scene.signal, Scene::from_toml_str(
//!     "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nsqrt_kappa = 2\nharmonics = 3\nsigma = true",
//!     "<string>",
//! )?.signal);
//! let results = sweep::run_cases(&cases, false);
//! let v_inf: Vec<f64> = results
//!     .iter()
//!     .map(|r| r.as_ref().unwrap().report.indicators.v_inf)
//!     .collect();
//! assert!(v_inf[0] > v_inf[1]); // n = 2 is fastest at equal f_max (section 7)
//! # Ok::<(), stickslip::Error>(())
//! ```
//!
//! [`load`] reads a sweep file, [`Sweep::cases`] lists its cases,
//! [`run_cases`] runs any of them in parallel and returns the results in the
//! order given (deterministic, whatever the thread count), and
//! [`execute`] is what `stickslip sweep` does: shard, skip, run, write.

mod axis;
mod execute;
mod grid;
mod layout;
mod merge;
mod spring_columns;
mod table;

pub use execute::{CaseResult, Summary, SweepOptions, execute, run_case, run_cases};
pub use grid::{
    AxesTable, AxisKey, AxisValue, Case, MAX_CASES, Shard, SpringAxesTable, Sweep, SweepAxis,
    SweepFile, SweepFormat, SweepOutputsTable, load, load_with,
};
pub use merge::{MISSING_LISTED, MergeSummary, merge};

#[cfg(doc)]
use crate::{indicator::Indicator, scene::Scene};
