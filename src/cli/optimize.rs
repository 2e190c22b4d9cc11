//! `stickslip optimize [SCENE] -o BEST.toml`: the best rod signal of `n`
//! harmonics for an objective at the scene's stroke and highest frequency
//! (see [`crate::optimize`], docs/interface.md), written as a runnable
//! scene; the report as text or JSON; optionally a figure of the optimal
//! against the sigma signal, and for `n = 2` the `v_inf` map over the
//! design plane as CSV and as a heat map.
//!
//! Every argument is checked before the search runs: the formats and
//! directories of the outputs, that no output is the scene or another
//! output, the scene, its `[optimize]` table and the flags; a failure is
//! one line and writes nothing.

use super::{Failure, SceneOptions, Streams, refuse_outputs, write_out};
use crate::optimize::map::{self, MapGrid};
use crate::optimize::{self, OptimizeTable, Overrides, Settings, output};
use crate::plot::{ImageFormat, Preset, optimize as figures};
use crate::scene::{self, Scene};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `optimize`.
#[derive(Args)]
pub(crate) struct OptimizeArgs {
    /// Scene file (TOML), with an optional [optimize] table; omitted: the
    /// built-in default scene.
    scene: Option<PathBuf>,
    /// The best signal as a runnable scene (TOML, written atomically).
    #[arg(short, long, value_name = "BEST.toml")]
    output: PathBuf,
    /// Number of harmonics n, 2 to 16 (overrides optimize.harmonics).
    #[arg(long, allow_negative_numbers = true)]
    harmonics: Option<i64>,
    /// v_inf, velocity_per_power, durability, smoothness or startup_time;
    /// two separated by a comma give a Pareto front.
    #[arg(long)]
    objective: Option<String>,
    /// The frequency kept fixed: f_max (= n f_0, the paper's comparison)
    /// or f0.
    #[arg(long, value_name = "f_max|f0")]
    keep: Option<String>,
    /// Seed of the global stage.
    #[arg(long)]
    seed: Option<u64>,
    /// Print one JSON object instead of the summary.
    #[arg(long)]
    json: bool,
    /// Leave out the wall time, so that the same seed prints the same
    /// bytes.
    #[arg(long)]
    no_timing: bool,
    /// Also draw the optimal against the sigma rod signal (.svg, .pdf or
    /// .png; its data beside it as .csv).
    #[arg(long, value_name = "FILE")]
    figure: Option<PathBuf>,
    /// n = 2: also write v_inf over the plane of amplitude ratio and
    /// relative phase as CSV.
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// n = 2: also draw that map as a heat map (.svg, .pdf or .png; its data
    /// beside it as .csv).
    #[arg(long, value_name = "FILE")]
    map_figure: Option<PathBuf>,
    /// n = 2: the map's grid, RATIOSxPHASES (default 81x96).
    #[arg(long, value_name = "RxP", value_parser = parse_grid)]
    map_grid: Option<(usize, usize)>,
    /// Worker threads (default: every available CPU); the result does not
    /// depend on it.
    #[arg(short, long, value_parser = clap::value_parser!(u32).range(1..))]
    jobs: Option<u32>,
    #[command(flatten)]
    options: SceneOptions,
    #[command(flatten)]
    set: super::SceneSet,
}

/// `--map-grid RxP`: two integers from 2 to 2000.
fn parse_grid(text: &str) -> Result<(usize, usize), String> {
    let parse = |s: &str| {
        s.trim()
            .parse::<usize>()
            .ok()
            .filter(|n| (2..=2000).contains(n))
    };
    match text.split_once(['x', 'X']) {
        Some((a, b)) => parse(a).zip(parse(b)),
        None => None,
    }
    .ok_or_else(|| format!("\"{text}\": expected RATIOSxPHASES, two integers from 2 to 2000"))
}

/// The directory of an output must exist.
fn check_directory(flag: &str, path: &Path) -> Result<(), Failure> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_owned(),
        _ => PathBuf::from("."),
    };
    if dir.is_dir() {
        Ok(())
    } else {
        Err(format!(
            "{flag} {}: the directory {} does not exist",
            path.display(),
            dir.display()
        ))
    }
}

/// Every output (with the CSV beside each figure): none may be an input
/// or another output, every directory must exist, figures need a known
/// format.
fn check_outputs(args: &OptimizeArgs) -> Result<(), Failure> {
    let mut outputs: Vec<(&str, PathBuf)> = vec![("-o", args.output.clone())];
    for (flag, figure) in [
        ("--figure", &args.figure),
        ("--map-figure", &args.map_figure),
    ] {
        if let Some(path) = figure {
            ImageFormat::of(path).map_err(|_| {
                format!(
                    "{flag} {}: the extension must be .svg, .pdf or .png",
                    path.display()
                )
            })?;
            outputs.push((flag, path.clone()));
            outputs.push((flag, crate::plot::data_path(path)));
        }
    }
    if let Some(path) = &args.map {
        outputs.push(("--map", path.clone()));
    }
    let inputs: Vec<&Path> = args.scene.iter().map(PathBuf::as_path).collect();
    for (flag, path) in &outputs {
        check_directory(flag, path)?;
    }
    let paths: Vec<&Path> = outputs.iter().map(|(_, p)| p.as_path()).collect();
    refuse_outputs(&paths, &inputs)?;
    Ok(())
}

/// The scene (with the `--set` overrides) and its `[optimize]` table.
fn load(path: Option<&Path>, set: &super::SceneSet) -> Result<(Scene, OptimizeTable), Failure> {
    match path {
        None => Ok((super::load_scene(None, set)?, OptimizeTable::default())),
        Some(p) => {
            let origin = scene::origin_of(p);
            let text = scene::read_input(p)
                .map_err(|e| format!("cannot read scene file {origin}: {e}"))?;
            let scene = Scene::from_toml_str_with(&text, &origin, &set.overrides()?)
                .map_err(|e| e.to_string())?;
            let table = optimize::spec::read_table(&text, &origin).map_err(|e| e.to_string())?;
            Ok((scene, table))
        }
    }
}

pub(crate) fn optimize(args: OptimizeArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    check_outputs(&args)?;
    let (mut scene, table) = load(args.scene.as_deref(), &args.set)?;
    args.options.apply(&mut scene, streams);
    let overrides = Overrides {
        harmonics: args.harmonics,
        objective: args.objective.clone(),
        keep: args.keep.clone(),
        seed: args.seed,
    };
    let settings = Settings::resolve(&table, &overrides, &scene).map_err(|e| e.to_string())?;
    let wants_map = args.map.is_some() || args.map_figure.is_some();
    if wants_map && settings.harmonics != 2 {
        return Err(format!(
            "--map: the map is of the plane of n = 2 harmonics, and n = {}",
            settings.harmonics
        ));
    }
    if args.map_grid.is_some() && !wants_map {
        return Err("--map-grid: applies with --map or --map-figure".to_owned());
    }
    // Fails early on a scene the problem cannot be built from.
    settings
        .problem(&scene, settings.objectives[0])
        .map_err(|e| e.to_string())?;
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(j) = args.jobs {
        pool = pool.num_threads(j as usize);
    }
    let pool = pool
        .build()
        .map_err(|e| format!("cannot start worker threads: {e}"))?;
    let clock = Instant::now();
    let (found, written, grid) = pool.install(|| -> Result<_, Failure> {
        let found = optimize::optimize(&scene, &settings).map_err(|e| e.to_string())?;
        let written = output::write_up(&found).map_err(|e| e.to_string())?;
        let grid = wants_map.then(|| {
            let mut grid = MapGrid::default();
            if let Some((r, p)) = args.map_grid {
                grid.ratios = r;
                grid.phases = p;
            }
            map::map(&found, grid)
        });
        Ok((found, written, grid))
    })?;
    let elapsed = (!args.no_timing).then(|| clock.elapsed());
    crate::output::write_atomically(&args.output, written.text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    if let Some(path) = &args.figure {
        let figure = figures::signal_figure(&found, &name_of(path)).map_err(|e| e.to_string())?;
        figure
            .write(path, &Preset::SingleColumn.style(), 300.0)
            .map_err(|e| e.to_string())?;
    }
    if let Some(m) = &grid {
        if let Some(path) = &args.map {
            crate::output::write_atomically(path, m.csv().as_bytes())
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        }
        if let Some(path) = &args.map_figure {
            let figure = figures::map_figure(m, &name_of(path)).map_err(|e| e.to_string())?;
            figure
                .write(path, &Preset::SingleColumn.style(), 300.0)
                .map_err(|e| e.to_string())?;
        }
    }
    let text = if args.json {
        let mut t = serde_json::to_string_pretty(&output::to_json(&found, &written, elapsed))
            .map_err(|e| e.to_string())?;
        t.push('\n');
        t
    } else {
        let mut t = output::to_text(&found, &written, elapsed);
        t.push_str(&format!("wrote {}\n", args.output.display()));
        t
    };
    write_out(streams, &text)
}

/// A figure's name: its file stem.
fn name_of(path: &Path) -> String {
    path.file_stem()
        .map_or("figure".to_owned(), |s| s.to_string_lossy().into_owned())
}
