//! [`CliError`]: why the `hooke` command could not do what it was asked.

use std::path::PathBuf;

use thiserror::Error;

use hooke_viz::OutputError;

/// A failure of a `hooke` command that leaves no usable result: invalid
/// input, or a file or directory that cannot be written. A run whose
/// integrator fails part-way is not one of these: it still writes its
/// frames and a [`Summary`](crate::Summary) saying what went wrong.
#[derive(Debug, Error)]
pub enum CliError {
    /// A scene file or built-in scene that cannot be read, naming the file,
    /// line and key.
    #[error(transparent)]
    SceneFile(#[from] hooke_scenes::file::SceneFileError),
    /// Writing a frame, picture or animation failed.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The scene's integrator parameters are out of range.
    #[error("integrator: {0}")]
    Parameter(#[from] hooke_core::ParameterError),
    /// A scene whose timing cannot be run.
    #[error("timing: {reason}")]
    InvalidTiming {
        /// What is wrong, naming the field.
        reason: &'static str,
    },
    /// The output directory could not be created.
    #[error("cannot create directory {}: {source}", path.display())]
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// `summary.json`, a report or its CSV table could not be written.
    #[error("cannot write {}: {source}", path.display())]
    WriteSummary {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Plot(Box<hooke_viz::PlotError>),
    /// A lab measurement that cannot be made.
    #[error(transparent)]
    Lab(#[from] hooke_lab::LabError),
    /// `--scale-stiffness` gives a stiffness the scene's springs cannot
    /// take.
    #[error("--scale-stiffness {scale}: {source}")]
    ScaleStiffness {
        /// The scale given.
        scale: f64,
        /// Why the scaled system is invalid.
        source: hooke_core::BuildError,
    },
    /// `--pcg-tolerance` with a `--solver` that is not a PCG iteration.
    #[error(
        "--pcg-tolerance: solver \"{solver}\" takes no tolerance; the PCG solvers do: {}",
        hooke_implicit::LinearSolver::iterative_names()
            .collect::<Vec<_>>()
            .join(", ")
    )]
    PcgTolerance {
        /// The solver given.
        solver: &'static str,
    },
    /// `--methods` names no integrator.
    #[error(
        "--methods: no integrator \"{name}\"; one of {}",
        hooke_scenes::Method::names()
    )]
    UnknownMethod {
        /// The name given.
        name: String,
    },
    /// A run stopped before its last step (its files were written).
    #[error("the run stopped after {steps} of {planned} steps: {reason}")]
    RunStopped {
        /// Steps taken.
        steps: usize,
        /// Steps planned.
        planned: usize,
        /// Why it stopped.
        reason: String,
    },
    /// A file or directory could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The path.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A partial report is not valid JSON of its kind.
    #[error("{}: not a partial report: {source}", path.display())]
    ParseReport {
        /// The file.
        path: PathBuf,
        /// What the parser said.
        source: serde_json::Error,
    },
    /// `hooke merge` found no partial report.
    #[error("no stability.shard-*.json or accuracy.shard-*.json in {}", dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", "))]
    NoPartials {
        /// The directories searched.
        dirs: Vec<PathBuf>,
    },
    /// The command's own output could not be printed.
    #[error("cannot print: {0}")]
    Print(#[from] std::io::Error),
}
