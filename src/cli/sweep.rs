//! `stickslip sweep FILE` and `stickslip merge`: a sweep file's grid, run in
//! parallel into one CSV or JSON-lines file, and the joining of shards.

use super::{Failure, Streams};
use crate::sweep::{self, Shard};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `sweep`.
#[derive(Args)]
pub(crate) struct SweepArgs {
    /// Sweep file (TOML).
    file: PathBuf,
    /// Output file; rows already in it are kept and not rerun. Default:
    /// <sweep name>.csv (or .jsonl), <sweep name>.<i>-of-<N>.csv for a shard.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Run only shard i of N (i from 1): the cases with index % N == i - 1.
    #[arg(long, value_name = "i/N")]
    shard: Option<Shard>,
    /// Leave out the wall_time_s column: the same sweep then writes the same bytes.
    #[arg(long)]
    no_timing: bool,
    /// No progress bar.
    #[arg(short, long)]
    quiet: bool,
    /// Worker threads (default: every available CPU).
    #[arg(short, long)]
    jobs: Option<usize>,
}

/// Arguments of `merge`.
#[derive(Args)]
pub(crate) struct MergeArgs {
    /// The merged file (written atomically).
    output: PathBuf,
    /// Sweep outputs with the same columns.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
}

pub(crate) fn sweep(args: SweepArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    if let Some(jobs) = args.jobs {
        rayon::ThreadPoolBuilder::new()
            .num_threads(jobs)
            .build_global()
            .map_err(|e| e.to_string())?;
    }
    let sweep = sweep::load(&args.file).map_err(|e| e.to_string())?;
    let output = args
        .output
        .unwrap_or_else(|| sweep.default_output(args.shard));
    let options = sweep::Options {
        shard: args.shard,
        timing: !args.no_timing,
        progress: !args.quiet,
        ..sweep::Options::new(&output)
    };
    let s = sweep::execute(&sweep, &options).map_err(|e| e.to_string())?;
    let _ = writeln!(
        streams.err,
        "stickslip: {} cases{}: {} already written, {} run, {} failed; {} rows in {}",
        s.cases,
        args.shard.map_or(String::new(), |sh| format!(
            " in shard {sh} (of {})",
            sweep.len()
        )),
        s.skipped,
        s.ran,
        s.failed,
        s.rows,
        output.display()
    );
    if s.failed > 0 {
        let _ = writeln!(
            streams.err,
            "stickslip: warning: see the failure column for why cases failed"
        );
    }
    Ok(())
}

pub(crate) fn merge(args: MergeArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let s = sweep::merge(&args.output, &args.inputs).map_err(|e| e.to_string())?;
    let _ = writeln!(
        streams.err,
        "stickslip: {} rows in {}",
        s.rows,
        args.output.display()
    );
    if !s.missing.is_empty() {
        let _ = writeln!(
            streams.err,
            "stickslip: warning: {} cases missing below the last one: {:?}",
            s.missing.len(),
            s.missing
        );
    }
    Ok(())
}
