//! The `hooke` command line: [`main`] for the binary and [`run_cli`], the
//! same with its arguments and output streams passed in.

use std::ffi::OsString;
use std::io::Write;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use hooke_core::{ObserveFn, State, StepInfo, System};
use hooke_scenes::{Scene, builtin, file};
use indicatif::{ProgressBar, ProgressStyle};

use crate::cli_error::CliError;
use crate::describe::{describe, step_text};
use crate::lab::{
    AccuracyArgs, MergeArgs, StabilityArgs, accuracy_command, merge_command, stability_command,
};
use crate::run_options::{ANIMATION_FILE, PREVIEW_FILE, RunOptions, SUMMARY_FILE, USD_FILE};
use crate::runner::run;
use crate::scene_source::load_scene;
use crate::summary::Summary;

/// Simulate mass-spring systems and measure what each integrator costs.
///
/// Without a command, `hooke` runs: `hooke` alone runs the default scene
/// and writes its frames and pictures to hooke-out/.
#[derive(Debug, Parser)]
#[command(name = "hooke", version, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a scene and write its frames, preview.png, animation.gif,
    /// animation.usda and summary.json.
    Run(RunArgs),
    /// List the built-in scenes.
    Scenes,
    /// Validate a scene file and print what it contains.
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
    },
    /// Map which integrators stay stable at which stiffness and timestep;
    /// write stability.json and stability.png.
    Stability(Box<StabilityArgs>),
    /// Measure each integrator's error against a reference, its observed
    /// order and its run time; write accuracy.json, work_precision.png and
    /// convergence.png.
    Accuracy(Box<AccuracyArgs>),
    /// Combine the partial reports of `stability --shard` or `accuracy
    /// --shard` runs into the reports and figures of the whole sweep.
    Merge(MergeArgs),
}

#[derive(Debug, Args)]
struct RunArgs {
    /// A scene file (TOML); without it (and without --builtin), the default
    /// scene, stiff-cloth.
    #[arg(value_name = "SCENE")]
    scene: Option<PathBuf>,
    /// Run the built-in scene NAME instead (see `hooke scenes`).
    #[arg(long, value_name = "NAME", conflicts_with = "scene")]
    builtin: Option<String>,
    /// The directory to write into; created if missing.
    #[arg(long, value_name = "DIR", default_value = "hooke-out")]
    out: PathBuf,
    /// Do not write animation.gif.
    #[arg(long)]
    no_gif: bool,
    /// Do not write animation.usda.
    #[arg(long)]
    no_usd: bool,
    /// Simulated seconds to run instead of the scene's own duration.
    #[arg(long, value_name = "SECONDS")]
    duration: Option<f64>,
    /// Draw preview.png of the frame nearest this simulated time instead
    /// of the frame where the bodies rest on the obstacles.
    #[arg(long, value_name = "SECONDS")]
    preview_time: Option<f64>,
    /// Show no progress bar.
    #[arg(long, short)]
    quiet: bool,
}

/// The `hooke` binary: [`run_cli`] with the process's arguments, standard
/// output and standard error.
#[must_use]
pub fn main() -> ExitCode {
    run_cli(
        std::env::args_os(),
        &mut std::io::stdout(),
        &mut std::io::stderr(),
    )
}

/// Runs the `hooke` command line `args` (the first being the program name)
/// and returns its exit code: success, 1 when the command failed (an
/// invalid scene, a run that stopped early, a file that could not be
/// written) with `error: ...` on `err`, or 2 for arguments that do not
/// parse. Results go to `out`; the progress bar of `hooke run` is drawn on
/// the terminal's standard error only when that is a terminal.
///
/// ```
/// let mut out = Vec::new();
/// let code = hooke_cli::run_cli(["hooke", "scenes"], &mut out, &mut std::io::sink());
/// assert_eq!(code, std::process::ExitCode::SUCCESS);
/// assert!(String::from_utf8(out)?.contains("stiff-cloth"));
/// # Ok::<(), std::string::FromUtf8Error>(())
/// ```
pub fn run_cli<I, T>(args: I, out: &mut dyn Write, err: &mut dyn Write) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(error) => {
            let to: &mut dyn Write = if error.use_stderr() { err } else { out };
            // Nothing more can be said if the terminal cannot be written to.
            let _ = write!(to, "{}", error.render());
            return ExitCode::from(u8::try_from(error.exit_code()).unwrap_or(2));
        }
    };
    let result = match cli.command {
        None => run_command(&cli.run, out),
        Some(Command::Run(args)) => run_command(&args, out),
        Some(Command::Scenes) => list_scenes(out),
        Some(Command::Check { scene }) => check(&scene, out),
        Some(Command::Stability(args)) => stability_command(&args, out),
        Some(Command::Accuracy(args)) => accuracy_command(&args, out),
        Some(Command::Merge(args)) => merge_command(&args, out),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            let _ = writeln!(err, "error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// `hooke run`: an error message when the command failed, including a run
/// that stopped early.
fn run_command(args: &RunArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let scene = run_scene(args)?;
    let steps = scene.timing.steps();
    writeln!(
        out,
        "{}: {} particles, {} springs; {steps} steps of {}",
        scene.name,
        scene.system.particle_count(),
        scene.system.springs().len(),
        step_text(scene.timing.dt)
    )?;
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(steps as u64)
    };
    if let Ok(style) =
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} steps, eta {eta}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    let options = RunOptions::new(&args.out)
        .gif(!args.no_gif)
        .usd(!args.no_usd)
        .preview_time(args.preview_time);
    let mut progress = ObserveFn(|_: &System, _: &State, step: &StepInfo| {
        bar.set_position(step.index as u64);
        ControlFlow::Continue(())
    });
    let summary = run(&scene, &options, &mut progress);
    bar.finish_and_clear();
    let summary = summary?;
    report(&summary, !args.no_gif, !args.no_usd, out)?;
    match summary.error {
        Some(reason) => Err(CliError::RunStopped {
            steps: summary.steps,
            planned: summary.steps_planned,
            reason,
        }),
        None => Ok(()),
    }
}

fn run_scene(args: &RunArgs) -> Result<Scene, CliError> {
    let mut scene = load_scene(args.scene.as_deref(), args.builtin.as_deref())?;
    if let Some(duration) = args.duration {
        scene.timing.duration = duration;
    }
    Ok(scene)
}

/// Prints what a run did and where its files are.
fn report(summary: &Summary, gif: bool, usd: bool, out: &mut dyn Write) -> std::io::Result<()> {
    // A direct solver takes no linear iterations: they are named only
    // when an iterative one took some.
    let newton = summary.newton_iterations_mean.unwrap_or(0.0);
    let solver = match summary.linear_iterations_mean {
        Some(iterations) if iterations > 0.0 => {
            format!(", {newton:.1} Newton and {iterations:.1} linear iterations per step")
        }
        Some(_) => format!(", {newton:.1} Newton iterations per step"),
        None => String::new(),
    };
    writeln!(
        out,
        "{}: {} steps to t = {:.3} s, {:.3} ms per step (median){solver}",
        summary.integrator, summary.steps, summary.time, summary.step_ms_median
    )?;
    // Stepping time per simulated second: at most 1 is real time.
    let pace = if summary.time > 0.0 {
        format!(
            " ({:.2} s per simulated second, longest step {:.1} ms)",
            summary.simulation_s / summary.time,
            summary.step_ms_max
        )
    } else {
        String::new()
    };
    writeln!(
        out,
        "wall {:.2} s: simulation {:.2} s{pace}, frames and pictures {:.2} s",
        summary.wall_s, summary.simulation_s, summary.output_s
    )?;
    writeln!(
        out,
        "energy {:.4} J -> {:.4} J (at most {:.4} J), max strain {:.2} %, at most {} contacts",
        summary.energy_initial,
        summary.energy_final,
        summary.energy_max,
        100.0 * summary.max_strain,
        summary.contacts_max
    )?;
    if let Some(line) = contact_line(summary) {
        writeln!(out, "{line}")?;
    }
    if let Some(line) = volume_line(summary) {
        writeln!(out, "{line}")?;
    }
    for warning in &summary.warnings {
        writeln!(out, "warning: {warning}")?;
    }
    let dir = summary.out.display();
    writeln!(out, "wrote {} frames: {dir}/frame_*.ply", summary.frames)?;
    match (summary.preview_frame, summary.preview_time) {
        (Some(frame), Some(time)) => {
            writeln!(
                out,
                "picture: {dir}/{PREVIEW_FILE} (frame {frame}, t = {time:.3} s)"
            )?;
            if gif {
                writeln!(out, "animation: {dir}/{ANIMATION_FILE}")?;
            }
            if usd {
                writeln!(out, "usd: {dir}/{USD_FILE}")?;
            }
        }
        _ => writeln!(out, "pictures: none, no frame was written")?,
    }
    writeln!(out, "summary: {dir}/{SUMMARY_FILE}")
}

/// `contact: ...`, how close the collision surfaces came, for a run of a
/// system that has any.
fn contact_line(summary: &Summary) -> Option<String> {
    let pairs = summary.close_pairs_max?;
    let distance = summary.contact_distance.unwrap_or(f64::NAN);
    let closest = summary.smallest_distance.map_or_else(
        || format!("none within the contact distance {distance:.3e} m"),
        |d| format!("smallest distance {d:.3e} m (contact distance {distance:.3e} m)"),
    );
    let end = summary
        .intersecting_triangle_pairs
        .map_or_else(String::new, |n| {
            let by_body = summary
                .intersections
                .iter()
                .flatten()
                .map(|i| {
                    let [a, b] = &i.bodies;
                    let which = if a == b {
                        format!("{a} with itself")
                    } else {
                        format!("{a} and {b}")
                    };
                    let allowed = if i.collide {
                        ""
                    } else {
                        ", self-collision off"
                    };
                    format!("{which}: {}{allowed}", i.pairs)
                })
                .collect::<Vec<_>>();
            let by_body = if by_body.is_empty() {
                String::new()
            } else {
                format!(" ({})", by_body.join("; "))
            };
            format!(", {n} intersecting triangle pairs at the end{by_body}")
        });
    Some(format!(
        "contact: at most {pairs} close pairs, {closest}{end}"
    ))
}

/// `volume: ...`, how far the volume elements were crushed, for a run of a
/// system that has any.
fn volume_line(summary: &Summary) -> Option<String> {
    let inverted = summary.inverted_elements_max?;
    let ratio = summary.volume_ratio_min.unwrap_or(f64::NAN);
    Some(format!(
        "volume: at most {inverted} elements inverted at once, smallest volume ratio {ratio:.3}"
    ))
}

/// `hooke scenes`.
fn list_scenes(out: &mut dyn Write) -> Result<(), CliError> {
    let width = builtin::NAMES.iter().map(|(name, _)| name.len()).max();
    let listing = builtin::NAMES.iter().try_for_each(|(name, description)| {
        writeln!(
            out,
            "{name:<width$}  {description}",
            width = width.unwrap_or(0)
        )
    });
    Ok(listing?)
}

/// `hooke check`.
fn check(path: &Path, out: &mut dyn Write) -> Result<(), CliError> {
    let text = describe(&file::load(path)?)?;
    write!(out, "{text}")?;
    Ok(writeln!(out, "{}: ok", path.display())?)
}
