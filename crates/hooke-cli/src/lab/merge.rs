//! `hooke merge`: the partial reports of a sharded `hooke stability` or
//! `hooke accuracy` combined into the files an unsharded run writes.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use hooke_lab::{AccuracyReport, StabilityReport};

use super::files::{ACCURACY_JSON, STABILITY_JSON, read_partials, write};
use crate::cli_error::CliError;

/// `hooke merge`'s arguments.
#[derive(Debug, Args)]
pub(crate) struct MergeArgs {
    /// Directories holding the partial reports (`stability.shard-I-of-N.json`,
    /// `accuracy.shard-I-of-N.json`) of every part.
    #[arg(value_name = "DIR", required = true)]
    dirs: Vec<PathBuf>,
    /// The directory to write the merged reports and figures into.
    #[arg(long, value_name = "DIR", default_value = "hooke-out")]
    out: PathBuf,
}

/// `hooke merge`: merges the stability parts and the accuracy parts found
/// in the directories, whichever there are.
pub(crate) fn merge_command(args: &MergeArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let stability: Vec<(PathBuf, StabilityReport)> = read_partials(&args.dirs, STABILITY_JSON)?;
    let accuracy: Vec<(PathBuf, AccuracyReport)> = read_partials(&args.dirs, ACCURACY_JSON)?;
    if stability.is_empty() && accuracy.is_empty() {
        return Err(CliError::NoPartials {
            dirs: args.dirs.clone(),
        });
    }
    if !stability.is_empty() {
        writeln!(out, "merging {} stability parts", stability.len())?;
        let report = StabilityReport::merge(stability.into_iter().map(|(_, r)| r).collect())?;
        write(&report, &args.out, out)?;
    }
    if !accuracy.is_empty() {
        writeln!(out, "merging {} accuracy parts", accuracy.len())?;
        let report = AccuracyReport::merge(accuracy.into_iter().map(|(_, r)| r).collect())?;
        write(&report, &args.out, out)?;
    }
    Ok(())
}
