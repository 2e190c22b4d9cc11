//! `stickslip sweep FILE` and `stickslip merge`: a sweep file's grid, run in
//! parallel into one CSV or JSON-lines file, and the joining of shards.

use super::{Failure, Streams};
use crate::interrupt;
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
    /// Leave out the timing columns (wall_time_s, setup_time_s,
    /// simulation_time_s): the same sweep then writes the same bytes.
    #[arg(long)]
    no_timing: bool,
    /// No progress bar and no plausibility warnings.
    #[arg(short, long)]
    quiet: bool,
    /// Worker threads (default and maximum: the available CPUs; never more
    /// than the cases to run).
    #[arg(short, long, value_parser = clap::value_parser!(u32).range(1..))]
    jobs: Option<u32>,
    /// Overrides of the base scene, before the axes are applied.
    #[command(flatten)]
    set: super::SceneSet,
}

/// Arguments of `merge`.
#[derive(Args)]
pub(crate) struct MergeArgs {
    /// The merged file (written atomically; it may not be one of the inputs).
    #[arg(short, long, required = true)]
    output: PathBuf,
    /// Sweep outputs with the same header line and columns.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Merge even when cases of the sweep are in no input (a shard missing
    /// or unfinished); they are listed in a warning.
    #[arg(long)]
    allow_partial: bool,
}

/// Runs the sweep; `Ok` holds the exit status: 0, or 130/143 when a
/// signal stopped it (the rows finished so far are in the output).
pub(crate) fn sweep(args: SweepArgs, streams: &mut Streams<'_>) -> Result<u8, Failure> {
    let sweep = sweep::load_with(&args.file, &args.set.overrides()?).map_err(|e| e.to_string())?;
    let output = args
        .output
        .unwrap_or_else(|| sweep.default_output(args.shard));
    let inputs: Vec<&std::path::Path> = std::iter::once(args.file.as_path())
        .chain(sweep.base_path())
        .collect();
    super::refuse_output_over_input(&output, &inputs)?;
    if !args.quiet {
        super::print_warnings(sweep.base(), streams);
    }
    let options = sweep::SweepOptions {
        shard: args.shard,
        timing: !args.no_timing,
        progress: !args.quiet,
        jobs: args.jobs.map(|j| j as usize),
        ..sweep::SweepOptions::new(&output)
    };
    let s = {
        // The first signal stops the sweep between cases, not the process.
        let _deferral = interrupt::defer();
        sweep::execute(&sweep, &options).map_err(|e| e.to_string())?
    };
    for note in &s.notes {
        let _ = writeln!(streams.err, "stickslip: {note}");
    }
    if let Some(signal) = s.interrupted {
        let name = if signal == 15 { "SIGTERM" } else { "SIGINT" };
        let _ = writeln!(
            streams.err,
            "stickslip: stopped by {name}: {} rows are in {} ({} written now, {} cases of {} not run); \
             rerun the same command to complete it",
            s.rows,
            output.display(),
            s.ran,
            s.cases - s.skipped - s.ran,
            s.cases
        );
        return Ok(interrupt::exit_status(signal));
    }
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
    Ok(0)
}

pub(crate) fn merge(args: MergeArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let s =
        sweep::merge(&args.output, &args.inputs, args.allow_partial).map_err(|e| e.to_string())?;
    let _ = writeln!(
        streams.err,
        "stickslip: {} rows in {}",
        s.rows,
        args.output.display()
    );
    if s.missing > 0 {
        let more = if s.missing > s.first_missing.len() as u64 {
            ", ..."
        } else {
            ""
        };
        let listed: Vec<String> = s.first_missing.iter().map(u64::to_string).collect();
        let _ = writeln!(
            streams.err,
            "stickslip: warning: {} cases of the sweep are in no input: [{}{more}]",
            s.missing,
            listed.join(", ")
        );
    }
    Ok(())
}
