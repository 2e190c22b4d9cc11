//! Running a sweep into its output file: one writer at a time (a lock
//! file), stale rows dropped, the missing cases run on a local pool of
//! worker threads and appended in case order as they finish, and a stop
//! on SIGINT/SIGTERM that leaves every finished row on disk.

use super::grid::{AxisValue, Case, Shard, Sweep, SweepAxis, SweepFormat};
use super::layout::{self, Layout, Parsed};
use super::table::{self, Cell, Column, Meta};
use crate::error::{Error, SweepError};
use crate::interrupt;
use crate::provenance::{VERSION, scene_hash};
use crate::simulation::{self, RunReport};
#[cfg(feature = "cli")]
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fs::{File, OpenOptions};
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, mpsc};

/// The result of one case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The case's index.
    pub index: usize,
    /// The case's axis values.
    pub values: Vec<(SweepAxis, AxisValue)>,
    /// The run.
    pub report: RunReport,
}

/// Runs `cases` in parallel (rayon's global pool) and returns their
/// results in the order of `cases`, whatever order they finish in. With
/// `progress`, a progress bar is drawn on stderr if it is a terminal.
pub fn run_cases(cases: &[Case], progress: bool) -> Vec<Result<CaseResult, Error>> {
    let bar = progress_bar(cases.len(), progress);
    let signals = simulation::SignalCache::default();
    let results = cases
        .par_iter()
        .map(|case| {
            let result = run_case_with(case, &signals);
            bar.inc(1);
            result
        })
        .collect();
    bar.finish_and_clear();
    results
}

/// Runs one case.
pub fn run_case(case: &Case) -> Result<CaseResult, Error> {
    run_case_with(case, &simulation::SignalCache::default())
}

/// Runs one case with its signal from `signals` (built there once for all
/// cases that share it).
fn run_case_with(case: &Case, signals: &simulation::SignalCache) -> Result<CaseResult, Error> {
    signals.run(&case.scene).map(|report| CaseResult {
        index: case.index,
        values: case.values.clone(),
        report,
    })
}

/// Without the command line there is no progress bar: a library caller
/// reports progress its own way.
#[cfg(not(feature = "cli"))]
struct ProgressBar;

#[cfg(not(feature = "cli"))]
impl ProgressBar {
    fn inc(&self, _: u64) {}
    fn finish_and_clear(&self) {}
}

#[cfg(not(feature = "cli"))]
fn progress_bar(_len: usize, _progress: bool) -> ProgressBar {
    ProgressBar
}

/// A progress bar on stderr if `progress` and stderr is a terminal.
#[cfg(feature = "cli")]
fn progress_bar(len: usize, progress: bool) -> ProgressBar {
    if !progress || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:40} {pos}/{len} cases, {elapsed} elapsed, about {eta} left",
    ) {
        bar.set_style(style);
    }
    bar
}

/// How [`execute`] runs a sweep.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Output file; valid rows in it are kept and not rerun.
    pub output: PathBuf,
    /// Run only this shard; `None`: every case.
    pub shard: Option<Shard>,
    /// Output format; `None`: the one the output's extension names
    /// ([`SweepFormat::from_path`]), else the sweep file's.
    pub format: Option<SweepFormat>,
    /// Write the `wall_time_s` column (the only one that differs between
    /// runs of the same sweep).
    pub timing: bool,
    /// Draw a progress bar on stderr (only if it is a terminal).
    pub progress: bool,
    /// Worker threads; `None`: every available CPU. Capped at the available
    /// parallelism and at the number of cases to run.
    pub jobs: Option<usize>,
}

impl SweepOptions {
    /// Timing on, progress on, the format from the file name or the sweep,
    /// one worker per available CPU.
    pub fn new(output: impl Into<PathBuf>) -> Self {
        Self {
            output: output.into(),
            shard: None,
            format: None,
            timing: true,
            progress: true,
            jobs: None,
        }
    }
}

/// What [`execute`] did.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Summary {
    /// Cases of the shard (all cases without one).
    pub cases: usize,
    /// Of those, found in the existing output and skipped.
    pub skipped: usize,
    /// Of those, run now and written.
    pub ran: usize,
    /// Of those run now, failed (written with a `failure`).
    pub failed: usize,
    /// Rows of the existing output dropped as stale (another program
    /// version, or a case whose scene or axis values changed) and rerun.
    pub stale: usize,
    /// Rows in the output file.
    pub rows: usize,
    /// Why rows were dropped, one sentence each.
    pub notes: Vec<String>,
    /// The signal that stopped the run early (2 = SIGINT, 15 = SIGTERM):
    /// the rows finished so far are in the file, and a rerun completes it.
    pub interrupted: Option<i32>,
}

/// The lock of an output file: `<output>.lock`, holding the process id of
/// the sweep writing the output, locked with the operating system's
/// advisory file lock, which ends with the process however it ends (so a
/// lock file left by a killed process does not block). Deleted when dropped.
struct OutputLock {
    path: PathBuf,
    _file: File,
}

impl OutputLock {
    fn path_for(output: &Path) -> PathBuf {
        let mut name = output.as_os_str().to_owned();
        name.push(".lock");
        PathBuf::from(name)
    }

    fn acquire(output: &Path) -> Result<OutputLock, SweepError> {
        let path = Self::path_for(output);
        let io = |source| SweepError::Write {
            path: path.display().to_string(),
            source,
        };
        loop {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(io)?;
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    let mut holder = String::new();
                    let _ = file.read_to_string(&mut holder);
                    return Err(SweepError::Output {
                        path: output.display().to_string(),
                        reason: format!(
                            "another stickslip sweep (process {}) is writing it (lock file {}); \
                             wait for it to finish or choose another --output",
                            holder.trim(),
                            path.display()
                        ),
                    });
                }
                Err(std::fs::TryLockError::Error(e)) => return Err(io(e)),
            }
            // The holder before us deletes the file before it unlocks it:
            // a lock on a file no longer at `path` is worth nothing.
            if !same_file(&file, &path) {
                continue;
            }
            interrupt::register(&path);
            file.set_len(0)
                .and_then(|()| write!(file, "{}", std::process::id()))
                .map_err(io)?;
            return Ok(OutputLock { path, _file: file });
        }
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Deleted while still locked (the file closes after this).
        let _ = std::fs::remove_file(&self.path);
        interrupt::unregister(&self.path);
    }
}

/// True if `file` is the file now at `path`.
#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// True if `file` is the file now at `path` (without inode numbers: if a
/// file is there).
#[cfg(not(unix))]
fn same_file(_file: &File, path: &Path) -> bool {
    path.exists()
}

/// Runs a sweep (or one shard of it) into `options.output`, as `stickslip
/// sweep` does (see the module docs of [`crate::sweep`]): valid rows of an
/// existing output are kept and their cases skipped, stale rows dropped and
/// rerun, the missing cases run in parallel and appended in case order as
/// they finish; at the end the rows are sorted by case. On SIGINT/SIGTERM
/// (with `crate::interrupt::install`) it stops taking new cases, writes
/// those in flight and returns with [`Summary::interrupted`] set.
pub fn execute(sweep: &Sweep, options: &SweepOptions) -> Result<Summary, SweepError> {
    let path = &options.output;
    let layout = Layout {
        format: options
            .format
            .or_else(|| SweepFormat::from_path(path))
            .unwrap_or(sweep.format()),
        meta: Meta::of(sweep),
        columns: table::column_kinds(sweep, options.timing),
    };
    let _lock = OutputLock::acquire(path)?;
    let mut summary = Summary::default();
    let kept = match std::fs::read_to_string(path) {
        Ok(text) => {
            let parsed = layout::parse(path, &text)?;
            let kept = keep_rows(sweep, &layout, path, parsed, &mut summary)?;
            let expected = file_text(&layout, &kept);
            if text != expected {
                write_atomically(path, &expected)?;
            }
            kept
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            write_atomically(path, &layout.head())?;
            BTreeMap::new()
        }
        Err(source) => {
            return Err(SweepError::Io {
                path: path.display().to_string(),
                source,
            });
        }
    };
    let shard = options.shard.unwrap_or(Shard { index: 1, count: 1 });
    summary.cases = shard.cases(sweep.len()).count();
    summary.skipped = kept.keys().filter(|c| shard.contains(**c)).count();
    let todo = summary.cases - summary.skipped;
    let available = std::thread::available_parallelism().map_or(1, usize::from);
    let jobs = options
        .jobs
        .unwrap_or(available)
        .min(available)
        .min(todo)
        .max(1);

    let mut file = OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(|source| SweepError::Write {
            path: path.display().to_string(),
            source,
        })?;
    let last_kept = kept.keys().next_back().copied();
    let mut first_new = None;
    let mut write_error = None;
    let bar = progress_bar(todo, options.progress);
    let pending_cases = Mutex::new(
        shard
            .cases(sweep.len())
            .filter(|c| !kept.contains_key(c))
            .enumerate(),
    );
    let stop = AtomicBool::new(false);
    let signals = simulation::SignalCache::default();
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::sync_channel::<(usize, usize, String, bool)>(4 * jobs);
        for _ in 0..jobs {
            let sender = sender.clone();
            let (pending_cases, stop, layout, signals) = (&pending_cases, &stop, &layout, &signals);
            scope.spawn(move || {
                loop {
                    if stop.load(Ordering::SeqCst) || interrupt::requested().is_some() {
                        break;
                    }
                    let next = pending_cases
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .next();
                    let Some((position, index)) = next else { break };
                    let Some(case) = sweep.case(index) else { break };
                    let result = signals.simulate(&case.scene);
                    let cells: Vec<Cell> = layout
                        .columns
                        .iter()
                        .map(|c| c.cell(&case, &result))
                        .collect();
                    let line = layout.render(&cells);
                    if sender
                        .send((position, index, line, result.is_err()))
                        .is_err()
                    {
                        break;
                    }
                }
            });
        }
        drop(sender);
        // Rows are written in the order the cases were taken, so the file
        // grows in case order; a row waits here only for slower earlier
        // cases still in flight.
        let mut waiting = BTreeMap::new();
        let mut next_position = 0;
        for (position, index, line, failed) in receiver {
            bar.inc(1);
            waiting.insert(position, (index, line, failed));
            while let Some((index, line, failed)) = waiting.remove(&next_position) {
                next_position += 1;
                if write_error.is_some() {
                    continue;
                }
                // One write of a whole line: the file is always a valid
                // prefix of rows.
                match file.write_all(format!("{line}\n").as_bytes()) {
                    Ok(()) => {
                        first_new.get_or_insert(index);
                        summary.ran += 1;
                        summary.failed += usize::from(failed);
                    }
                    Err(source) => {
                        stop.store(true, Ordering::SeqCst);
                        write_error = Some(SweepError::Write {
                            path: path.display().to_string(),
                            source,
                        });
                    }
                }
            }
        }
    });
    bar.finish_and_clear();
    if let Some(e) = write_error {
        return Err(e);
    }
    summary.rows = kept.len() + summary.ran;
    summary.interrupted = interrupt::requested();
    if summary.interrupted.is_none()
        && let (Some(last), Some(first)) = (last_kept, first_new)
        && first < last
    {
        sort_file(path, &layout)?;
    }
    Ok(summary)
}

/// The rows of an existing output that still hold: the output must have
/// this sweep's format and columns (else it is refused); rows of another
/// program version, of a case the sweep does not have, or whose axis values
/// or `scene_hash` differ from the case's are dropped (counted in
/// `summary.stale`, explained in `summary.notes`).
fn keep_rows(
    sweep: &Sweep,
    layout: &Layout,
    path: &Path,
    parsed: Parsed,
    summary: &mut Summary,
) -> Result<BTreeMap<usize, String>, SweepError> {
    let name = path.display().to_string();
    let bad = |reason: String| SweepError::Output {
        path: name.clone(),
        reason,
    };
    if let Some(format) = parsed.format
        && format != layout.format
    {
        return Err(bad(format!(
            "holds {} rows, the sweep writes {}; choose another --output",
            format.extension(),
            layout.format.extension()
        )));
    }
    if let Some(columns) = &parsed.columns
        && *columns != layout.columns
    {
        return Err(bad(format!(
            "has {} compared with what this sweep writes; delete it or choose another --output",
            table::column_difference(columns, &layout.columns)
        )));
    }
    let mut kept = BTreeMap::new();
    if parsed.rows.is_empty() {
        return Ok(kept);
    }
    match &parsed.meta {
        Some(meta) if meta.version == VERSION => {}
        other => {
            let by = other.as_ref().map_or_else(
                || "an older stickslip (no stickslip_version line)".to_owned(),
                |m| format!("stickslip {}", m.version),
            );
            summary.stale = parsed.rows.len();
            summary.notes.push(format!(
                "{name} was written by {by}, this is stickslip {VERSION}: its {} rows are recomputed",
                parsed.rows.len()
            ));
            return Ok(kept);
        }
    }
    let hash_at = layout.position(Column::SceneHash);
    for row in parsed.rows {
        let case = usize::try_from(row.case)
            .ok()
            .and_then(|index| sweep.case(index));
        let fresh = case.as_ref().is_some_and(|case| {
            layout.columns.iter().zip(&row.cells).all(|(column, cell)| {
                let Column::Axis(axis) = column else {
                    return true;
                };
                case.value(*axis).map(AxisValue::key) == cell.axis_key()
            }) && hash_at.is_some_and(|at| row.cells[at] == Cell::Text(scene_hash(&case.scene)))
        });
        let Some(case) = case.filter(|_| fresh) else {
            summary.stale += 1;
            continue;
        };
        let line = layout.render(&row.cells);
        if let Some(previous) = kept.insert(case.index, line.clone())
            && previous != line
        {
            return Err(bad(format!(
                "line {}: a second, different row for case {}",
                row.line, case.index
            )));
        }
    }
    if summary.stale > 0 {
        summary.notes.push(format!(
            "{} rows of {name} were computed with other parameters (another axis value or \
             scene_hash than the sweep's case): they are recomputed",
            summary.stale
        ));
    }
    Ok(kept)
}

/// The whole file: header, then the rows.
fn file_text(layout: &Layout, rows: &BTreeMap<usize, String>) -> String {
    let mut text = layout.head();
    for line in rows.values() {
        text.push_str(line);
        text.push('\n');
    }
    text
}

/// Rewrites the output with its rows sorted by case.
fn sort_file(path: &Path, layout: &Layout) -> Result<(), SweepError> {
    let text = std::fs::read_to_string(path).map_err(|source| SweepError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let parsed = layout::parse(path, &text)?;
    let rows: BTreeMap<usize, String> = parsed
        .rows
        .iter()
        .map(|r| (r.case as usize, layout.render(&r.cells)))
        .collect();
    write_atomically(path, &file_text(layout, &rows))
}

/// Writes `text` to `path` atomically ([`crate::output::write_atomically`]):
/// readers see the old file or the new one, never a part.
pub(super) fn write_atomically(path: &Path, text: &str) -> Result<(), SweepError> {
    crate::output::write_atomically(path, text.as_bytes()).map_err(|source| SweepError::Write {
        path: path.display().to_string(),
        source,
    })
}
