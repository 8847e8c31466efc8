//! The files of the lab's commands: names, JSON reports with a CSV table
//! beside each, and the partial reports of sharded sweeps.

use std::fmt::Display;
use std::path::{Path, PathBuf};

use hooke_lab::Shard;
use hooke_lab::accuracy::Run;
use hooke_lab::stability::Cell;
use serde::de::DeserializeOwned;

use crate::cli_error::CliError;
use crate::runner::write_json;

/// `stability.json`.
pub const STABILITY_JSON: &str = "stability.json";
/// `stability.png` (and `stability.svg`).
pub const STABILITY_PNG: &str = "stability.png";
/// `accuracy.json`.
pub const ACCURACY_JSON: &str = "accuracy.json";
/// `work_precision.png` (and `.svg`).
pub const WORK_PRECISION_PNG: &str = "work_precision.png";
/// `convergence.png` (and `.svg`).
pub const CONVERGENCE_PNG: &str = "convergence.png";
/// `variants.png` (and `.svg`).
pub const VARIANTS_PNG: &str = "variants.png";

/// Creates `dir` if it is missing.
pub(super) fn create_dir(dir: &Path) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).map_err(|source| CliError::CreateDir {
        path: dir.to_path_buf(),
        source,
    })
}

/// The partial report of `shard` of the report `name` (`stability.json`):
/// `stability.shard-I-of-N.json`.
fn partial_name(name: &str, shard: Shard) -> String {
    let stem = name.trim_end_matches(".json");
    format!("{stem}.shard-{}-of-{}.json", shard.index, shard.count)
}

/// The partial reports of `name` in `dirs`, read and parsed, with their
/// paths.
pub(super) fn read_partials<R: DeserializeOwned>(
    dirs: &[PathBuf],
    name: &str,
) -> Result<Vec<(PathBuf, R)>, CliError> {
    let stem = name.trim_end_matches(".json");
    let mut found = Vec::new();
    for dir in dirs {
        let entries = std::fs::read_dir(dir).map_err(|source| CliError::Read {
            path: dir.clone(),
            source,
        })?;
        let mut paths: Vec<PathBuf> = entries
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|path| {
                path.file_name()
                    .and_then(|n| n.to_str())
                    .and_then(|n| n.strip_prefix(stem)?.strip_prefix(".shard-"))
                    .is_some_and(|rest| rest.ends_with(".json"))
            })
            .collect();
        paths.sort();
        for path in paths {
            let text = std::fs::read_to_string(&path).map_err(|source| CliError::Read {
                path: path.clone(),
                source,
            })?;
            let report = serde_json::from_str(&text).map_err(|source| CliError::ParseReport {
                path: path.clone(),
                source,
            })?;
            found.push((path, report));
        }
    }
    Ok(found)
}

/// Writes `report` as `dir/name` and `rows` as the CSV table beside it
/// (`name` with the extension `csv`).
fn write_report(
    dir: &Path,
    name: &str,
    report: &impl serde::Serialize,
    header: &[&str],
    rows: impl Iterator<Item = Vec<String>>,
) -> Result<(), CliError> {
    create_dir(dir)?;
    let path = dir.join(name);
    write_json(&path, report)?;
    let mut text = csv_line(header.iter().map(ToString::to_string));
    for row in rows {
        text += &csv_line(row);
    }
    let csv = path.with_extension("csv");
    std::fs::write(&csv, text).map_err(|source| CliError::WriteSummary { path: csv, source })
}

/// A report of the lab as the commands write it.
pub(super) trait LabReport: serde::Serialize {
    /// The whole report's file name, e.g. `stability.json`.
    const JSON: &'static str;
    /// The columns of its CSV table.
    const COLUMNS: &'static [&'static str];
    /// The part of the sweep it holds, if it is partial.
    fn shard(&self) -> Option<Shard>;
    /// What it did differently on a scene whose surfaces collide.
    fn note(&self) -> Option<&str>;
    /// The rows of its CSV table.
    fn rows(&self) -> Vec<Vec<String>>;
    /// Draws its figures into `dir`.
    fn figures(&self, dir: &Path) -> Result<(), CliError>;
    /// Prints what it found and where its files are.
    fn print(&self, dir: &Path, out: &mut dyn std::io::Write) -> std::io::Result<()>;
}

/// Writes `report` into `dir`: a partial one as `NAME.shard-I-of-N.json`
/// with its CSV, a whole one as its JSON, CSV and figures, then says what
/// it wrote on `out`, after its note, if it has one.
pub(super) fn write<R: LabReport>(
    report: &R,
    dir: &Path,
    out: &mut dyn std::io::Write,
) -> Result<(), CliError> {
    if let Some(note) = report.note() {
        writeln!(out, "note: {note}")?;
    }
    let rows = report.rows().into_iter();
    if let Some(shard) = report.shard() {
        let name = partial_name(R::JSON, shard);
        write_report(dir, &name, report, R::COLUMNS, rows)?;
        return Ok(writeln!(out, "wrote {}/{name}", dir.display())?);
    }
    write_report(dir, R::JSON, report, R::COLUMNS, rows)?;
    report.figures(dir)?;
    Ok(report.print(dir, out)?)
}

/// One CSV line; a field with a comma, a quote or a line break is quoted.
fn csv_line(fields: impl IntoIterator<Item = String>) -> String {
    let quoted: Vec<String> = fields
        .into_iter()
        .map(|f| {
            if f.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", f.replace('"', "\"\""))
            } else {
                f
            }
        })
        .collect();
    quoted.join(",") + "\n"
}

/// A number as CSV writes it: empty when absent (JSON's `null`).
fn field(value: Option<impl Display>) -> String {
    value.map_or_else(String::new, |v| v.to_string())
}

/// The columns of `stability.csv`.
pub(super) const CELL_COLUMNS: &[&str] = &[
    "integrator",
    "stiffness_scale",
    "dt",
    "stable",
    "max_energy_ratio",
    "max_energy_gain",
    "h_omega",
    "wall_s",
    "steps",
    "stopped",
    "applicable",
];

/// A row of `stability.csv`.
pub(super) fn cell_row(c: &Cell) -> Vec<String> {
    vec![
        c.integrator.to_string(),
        c.stiffness_scale.to_string(),
        c.dt.to_string(),
        c.stable.to_string(),
        c.max_energy_ratio.to_string(),
        c.max_energy_gain.to_string(),
        c.h_omega.to_string(),
        c.wall_s.to_string(),
        c.steps.to_string(),
        field(c.stopped.as_ref()),
        c.applicable.to_string(),
    ]
}

/// The columns of `accuracy.csv`.
pub(super) const RUN_COLUMNS: &[&str] = &[
    "integrator",
    "dt",
    "step",
    "tolerance",
    "steps",
    "error_rms",
    "error_max",
    "wall_s",
    "force_evaluations",
    "linear_iterations",
    "linear_solves",
    "failure",
    "resolved",
];

/// A row of `accuracy.csv`.
pub(super) fn run_row(r: &Run) -> Vec<String> {
    vec![
        r.integrator.to_string(),
        field(r.dt),
        r.step.to_string(),
        field(r.tolerance),
        r.steps.to_string(),
        field(r.error_rms),
        field(r.error_max),
        r.wall_s.to_string(),
        r.force_evaluations.to_string(),
        r.linear_iterations.to_string(),
        r.linear_solves.to_string(),
        field(r.failure.as_ref()),
        r.resolved.to_string(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_with_separators_are_quoted() {
        let line = csv_line(["a".into(), "b,c".into(), "say \"hi\"".into(), String::new()]);
        assert_eq!(line, "a,\"b,c\",\"say \"\"hi\"\"\",\n");
        assert_eq!(field(None::<f64>), "");
        assert_eq!(
            partial_name(STABILITY_JSON, Shard { index: 1, count: 3 }),
            "stability.shard-1-of-3.json"
        );
    }
}
