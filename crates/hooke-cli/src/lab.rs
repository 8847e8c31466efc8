//! `hooke stability` and `hooke accuracy`: the lab's measurements from the
//! command line, written as JSON and PNG into `--out DIR`.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use hooke_lab::accuracy::{ReferenceKind, Series as RunSeries};
use hooke_lab::{
    AccuracyOptions, AccuracyReport, LabError, Method, Range, StabilityOptions, StabilityReport,
    accuracy, stability,
};
use hooke_scenes::Scene;
use hooke_scenes::SolverSpec;
use hooke_viz::plot::{
    Cell, HeatMapPanel, HeatMaps, LogLogPlot, Reference, Series, write_heat_maps, write_log_log,
};
use indicatif::{ProgressBar, ProgressStyle};

use crate::cli::load_scene;
use crate::cli_error::CliError;
use crate::runner::write_json;

/// Values given on the command line as a comma-separated list of numbers
/// and log-spaced ranges `FIRST:LAST:COUNT`, e.g. `1e-3:1e-1:9` or
/// `0.01,0.02,0.05`; kept sorted, without repeats.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Values(Vec<f64>);

impl std::str::FromStr for Values {
    type Err = LabError;

    fn from_str(text: &str) -> Result<Self, LabError> {
        let mut values = Vec::new();
        for part in text.split(',') {
            values.extend(part.parse::<Range>()?.values());
        }
        values.sort_by(f64::total_cmp);
        values.dedup();
        Ok(Self(values))
    }
}

/// `stability.json`.
pub const STABILITY_JSON: &str = "stability.json";
/// `stability.png`.
pub const STABILITY_PNG: &str = "stability.png";

/// Which scene a lab command measures.
#[derive(Debug, Args)]
pub(crate) struct SceneArgs {
    /// A scene file (TOML); without it (and without --builtin), the default
    /// scene, stiff-cloth.
    #[arg(value_name = "SCENE")]
    scene: Option<PathBuf>,
    /// Measure the built-in scene NAME instead (see `hooke scenes`).
    #[arg(long, value_name = "NAME", conflicts_with = "scene")]
    builtin: Option<String>,
    /// Integrators to measure, comma-separated (default: all).
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    methods: Vec<String>,
    /// The directory to write into; created if missing.
    #[arg(long, value_name = "DIR", default_value = "hooke-out")]
    out: PathBuf,
    /// Show no progress bar.
    #[arg(long, short)]
    quiet: bool,
    /// Multiply every spring's stiffness by SCALE first.
    #[arg(long = "scale-stiffness", value_name = "SCALE")]
    scale_stiffness: Option<f64>,
    /// The implicit methods' linear solver (default: the scene's, else
    /// cholesky).
    #[arg(long, value_name = "SOLVER")]
    solver: Option<SolverArg>,
    /// The relative residual PCG stops at, with --solver pcg.
    #[arg(long, value_name = "TOL", default_value_t = 1e-6)]
    pcg_tolerance: f64,
    /// The implicit methods' cap on Newton iterations per (sub)step
    /// (default: the scene's, else the integrator's).
    #[arg(long, value_name = "N")]
    newton: Option<usize>,
    /// The implicit methods take Baraff and Witkin's linearised step (one
    /// solve, no line search, no rejection) instead of converged ones.
    #[arg(long)]
    linearized: bool,
}

/// `--solver`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum SolverArg {
    /// Sparse Cholesky.
    Cholesky,
    /// Block-Jacobi PCG to the relative residual --pcg-tolerance.
    Pcg,
}

impl SceneArgs {
    fn scene(&self) -> Result<Scene, String> {
        let mut scene = load_scene(self.scene.as_deref(), self.builtin.as_deref())
            .map_err(|e| e.to_string())?;
        if let Some(scale) = self.scale_stiffness {
            scene.system = scene
                .system
                .with_stiffness_scale(scale)
                .map_err(|e| format!("--scale-stiffness {scale}: {e}"))?;
        }
        Ok(scene)
    }

    /// The lab's method settings for `scene`, with `--solver` and
    /// `--newton` and `--linearized` applied.
    fn settings(&self, scene: &Scene) -> hooke_lab::Settings {
        let mut settings = hooke_lab::Settings::from_scene(&scene.integrator);
        match self.solver {
            Some(SolverArg::Cholesky) => settings.solver = SolverSpec::Cholesky,
            Some(SolverArg::Pcg) => {
                settings.solver = SolverSpec::Pcg {
                    tolerance: self.pcg_tolerance,
                    max_iterations: 1000,
                };
            }
            None => {}
        }
        if let Some(n) = self.newton {
            settings.newton_iterations = n;
        }
        settings.linearized |= self.linearized;
        settings
    }

    /// The methods named, or `all` when none is.
    fn methods(&self, all: &[Method]) -> Result<Vec<Method>, String> {
        if self.methods.is_empty() {
            return Ok(all.to_vec());
        }
        self.methods
            .iter()
            .map(|name| {
                Method::from_name(name.trim()).ok_or_else(|| {
                    format!(
                        "--methods: no integrator \"{name}\"; one of {}",
                        Method::ALL.map(Method::name).join(", ")
                    )
                })
            })
            .collect()
    }

    /// Runs `measure` with a progress bar of `what` (hidden with
    /// `--quiet`) fed by its progress callback.
    fn measure<R>(
        &self,
        what: &str,
        measure: impl FnOnce(&(dyn Fn(usize, usize) + Sync)) -> Result<R, LabError>,
    ) -> Result<R, String> {
        let bar = if self.quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::new(0)
        };
        if let Ok(style) = ProgressStyle::with_template(&format!(
            "{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {what}, eta {{eta}}"
        )) {
            bar.set_style(style.progress_chars("=> "));
        }
        let result = measure(&|done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        });
        bar.finish_and_clear();
        result.map_err(|e| e.to_string())
    }
}

/// `hooke stability`'s arguments.
#[derive(Debug, Args)]
pub(crate) struct StabilityArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Stiffness scales applied to every spring, FIRST:LAST:COUNT
    /// (log-spaced) or a comma-separated list.
    #[arg(long, value_name = "VALUES", default_value = "1e0:1e9:19")]
    stiffness: Values,
    /// Timesteps in seconds, FIRST:LAST:COUNT (log-spaced) or a list.
    #[arg(long, value_name = "VALUES", default_value = "1e-5:1e-1:13")]
    dt: Values,
    /// Simulated seconds per cell.
    #[arg(long, value_name = "SECONDS", default_value_t = 1.0)]
    duration: f64,
    /// Fewest steps per cell.
    #[arg(long, value_name = "N", default_value_t = 1000)]
    min_steps: usize,
    /// A cell is stable while its energy stays below this many times its
    /// initial energy plus the work done on it.
    #[arg(long, value_name = "FACTOR", default_value_t = hooke_lab::stability::DEFAULT_ENERGY_BOUND)]
    energy_bound: f64,
    /// Also search each integrator's largest stable timestep (within the
    /// --dt range) at the --limit-stiffness scale.
    #[arg(long)]
    limit: bool,
    /// The stiffness scale of the --limit search.
    #[arg(long, value_name = "SCALE", default_value_t = 1.0)]
    limit_stiffness: f64,
}

/// `hooke stability`.
pub(crate) fn stability_command(args: &StabilityArgs, out: &mut dyn Write) -> Result<(), String> {
    let scene = args.scene.scene()?;
    let mut options = StabilityOptions::for_scene(&scene);
    options.settings = args.scene.settings(&scene);
    options.methods = args.scene.methods(&Method::ALL)?;
    options.scales.clone_from(&args.stiffness.0);
    options.dts.clone_from(&args.dt.0);
    options.duration = args.duration;
    options.min_steps = args.min_steps;
    options.energy_bound = args.energy_bound;
    options.limit_scale = args.limit.then_some(args.limit_stiffness);
    let print = |e: std::io::Error| CliError::from(e).to_string();
    writeln!(
        out,
        "{}: {} integrators × {} stiffness scales × {} timesteps{}",
        scene.name,
        options.methods.len(),
        options.scales.len(),
        options.dts.len(),
        if args.limit {
            format!(
                ", and each integrator's step limit at scale {}",
                args.limit_stiffness
            )
        } else {
            String::new()
        }
    )
    .map_err(print)?;
    let report = args
        .scene
        .measure("cells", |progress| stability(&scene, &options, progress))?;
    write_stability(&report, &args.scene.out).map_err(|e| e.to_string())?;
    print_stability(&report, &args.scene.out, out).map_err(print)
}

fn create_dir(dir: &Path) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).map_err(|source| CliError::CreateDir {
        path: dir.to_path_buf(),
        source,
    })
}

fn write_stability(report: &StabilityReport, dir: &Path) -> Result<(), CliError> {
    create_dir(dir)?;
    write_json(&dir.join(STABILITY_JSON), report)?;
    let path = dir.join(STABILITY_PNG);
    write_heat_maps(&heat_maps(report), &path).map_err(|e| CliError::Plot(Box::new(e)))
}

/// One heat-map panel per integrator, in the report's order.
fn heat_maps(report: &StabilityReport) -> HeatMaps {
    let mut panels: Vec<HeatMapPanel> = Vec::new();
    for cell in &report.cells {
        if panels.last().is_none_or(|p| p.title != cell.integrator) {
            panels.push(HeatMapPanel {
                title: cell.integrator.to_owned(),
                dts: Vec::new(),
                scales: Vec::new(),
                cells: Vec::new(),
            });
        }
        if let Some(panel) = panels.last_mut() {
            if !panel.dts.contains(&cell.dt) {
                panel.dts.push(cell.dt);
            }
            if !panel.scales.contains(&cell.stiffness_scale) {
                panel.scales.push(cell.stiffness_scale);
            }
            panel.cells.push(Cell {
                stable: cell.stable,
                max_energy_ratio: cell.max_energy_ratio,
            });
        }
    }
    HeatMaps {
        title: format!(
            "{}: stable cells (energy within {}x budget) and h·ω_max = 2",
            report.scene, report.energy_bound
        ),
        panels,
        omega_max: Some(report.omega_max),
    }
}

fn print_stability(
    report: &StabilityReport,
    dir: &Path,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    writeln!(
        out,
        "ω_max = {:.6e} rad/s at stiffness scale 1 (Gershgorin bound {:.6e})",
        report.omega_max, report.omega_max_bound
    )?;
    writeln!(
        out,
        "{:<18} {:>14} {:>16}",
        "integrator", "stable cells", "largest stable hω"
    )?;
    let mut names: Vec<&str> = report.cells.iter().map(|c| c.integrator).collect();
    names.dedup();
    for name in names {
        let cells = report.cells.iter().filter(|c| c.integrator == name);
        let (stable, total, largest) = cells.fold((0, 0, None::<f64>), |(s, t, l), c| {
            let l = if c.stable {
                Some(l.map_or(c.h_omega, |l| l.max(c.h_omega)))
            } else {
                l
            };
            (s + usize::from(c.stable), t + 1, l)
        });
        let largest = largest.map_or_else(|| "-".to_owned(), |l| format!("{l:.4}"));
        writeln!(
            out,
            "{name:<18} {:>14} {largest:>16}",
            format!("{stable}/{total}")
        )?;
    }
    if let Some(limits) = &report.limits {
        writeln!(
            out,
            "step limits at stiffness scale {}:",
            limits.first().map_or(1.0, |l| l.stiffness_scale)
        )?;
        writeln!(
            out,
            "{:<18} {:>16} {:>14}",
            "integrator", "max stable dt", "hω limit"
        )?;
        for limit in limits {
            let (dt, h_omega) = match (limit.max_stable_dt, limit.h_omega_limit) {
                (Some(dt), Some(h)) => (format!("{dt:.6e}"), format!("{h:.4}")),
                _ if limit.searched_up_to > limit.searched_down_to => (
                    format!("≥ {:.3e}", limit.searched_up_to),
                    "none found".to_owned(),
                ),
                _ => (format!("< {:.3e}", limit.searched_down_to), "-".to_owned()),
            };
            writeln!(out, "{:<18} {dt:>16} {h_omega:>14}", limit.integrator)?;
        }
    }
    writeln!(
        out,
        "wrote {}/{STABILITY_JSON} and {}/{STABILITY_PNG}",
        dir.display(),
        dir.display()
    )
}

/// `accuracy.json`.
pub const ACCURACY_JSON: &str = "accuracy.json";
/// `work_precision.png`.
pub const WORK_PRECISION_PNG: &str = "work_precision.png";
/// `convergence.png`.
pub const CONVERGENCE_PNG: &str = "convergence.png";
/// The error target the command reports each method's cheapest run for,
/// m.
const TARGET_ERROR: f64 = 1e-3;

/// `hooke accuracy`'s arguments.
#[derive(Debug, Args)]
pub(crate) struct AccuracyArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Timesteps of the fixed-step methods in seconds, FIRST:LAST:COUNT
    /// (log-spaced) or a list (default: 13 over three decades, chosen from
    /// the scene's step and its fastest frequency).
    #[arg(long, value_name = "VALUES")]
    dt: Option<Values>,
    /// Tolerances of the adaptive method (default 1e-3:1e-9:7).
    #[arg(long, value_name = "VALUES")]
    tolerances: Option<Values>,
    /// Simulated seconds (default: the scene's duration).
    #[arg(long, value_name = "SECONDS")]
    duration: Option<f64>,
    /// Checkpoints at which the error is measured, evenly spaced.
    #[arg(long, value_name = "N", default_value_t = 10)]
    frames: usize,
    /// Timed repeats of each run; the wall time is their median.
    #[arg(long, value_name = "N", default_value_t = 3)]
    repeat: usize,
    /// The numerical reference's step in seconds (default: a quarter of
    /// the smallest --dt, at most 0.5/ω_max).
    #[arg(long, value_name = "SECONDS")]
    reference_dt: Option<f64>,
}

/// `hooke accuracy`.
pub(crate) fn accuracy_command(args: &AccuracyArgs, out: &mut dyn Write) -> Result<(), String> {
    let scene = args.scene.scene()?;
    let mut options = AccuracyOptions::for_scene(&scene);
    options.settings = args.scene.settings(&scene);
    options.methods = args.scene.methods(&options.methods)?;
    if let Some(dts) = &args.dt {
        options.dts.clone_from(&dts.0);
    }
    if let Some(tolerances) = &args.tolerances {
        options.tolerances.clone_from(&tolerances.0);
    }
    if let Some(duration) = args.duration {
        options.duration = duration;
    }
    options.frames = args.frames;
    options.repeat = args.repeat;
    options.reference_dt = args.reference_dt;
    let print = |e: std::io::Error| CliError::from(e).to_string();
    writeln!(
        out,
        "{}: {} integrators, {} steps from {:.3e} s to {:.3e} s, {} s simulated, {} repeats",
        scene.name,
        options.methods.len(),
        options.dts.len(),
        options.dts.first().copied().unwrap_or(f64::NAN),
        options.dts.last().copied().unwrap_or(f64::NAN),
        options.duration,
        options.repeat
    )
    .map_err(print)?;
    let report = args
        .scene
        .measure("runs", |progress| accuracy(&scene, &options, progress))?;
    write_accuracy(&report, &args.scene.out).map_err(|e| e.to_string())?;
    print_accuracy(&report, &args.scene.out, out).map_err(print)
}

fn plot_series(series: Vec<RunSeries>) -> Vec<Series> {
    series
        .into_iter()
        .map(|s| Series {
            label: s.integrator.to_owned(),
            points: s.points,
        })
        .collect()
}

fn write_accuracy(report: &AccuracyReport, dir: &Path) -> Result<(), CliError> {
    create_dir(dir)?;
    write_json(&dir.join(ACCURACY_JSON), report)?;
    let plot = |e| CliError::Plot(Box::new(e));
    write_log_log(
        &LogLogPlot {
            title: format!("{}: error against run time", report.scene),
            x_label: "wall time (s)".into(),
            y_label: "RMS error at the end (m)".into(),
            series: plot_series(report.work_precision()),
            reference: Some(Reference {
                y: TARGET_ERROR,
                label: "1 mm".into(),
            }),
        },
        &dir.join(WORK_PRECISION_PNG),
    )
    .map_err(plot)?;
    write_log_log(
        &LogLogPlot {
            title: format!("{}: convergence", report.scene),
            x_label: "step h (s)".into(),
            y_label: "largest RMS error (m)".into(),
            series: plot_series(report.convergence()),
            reference: None,
        },
        &dir.join(CONVERGENCE_PNG),
    )
    .map_err(plot)
}

fn print_accuracy(report: &AccuracyReport, dir: &Path, out: &mut dyn Write) -> std::io::Result<()> {
    let reference = &report.reference;
    writeln!(
        out,
        "reference: {} ({}{}), estimated error {:.2e} m{}",
        match reference.kind {
            ReferenceKind::Analytic => "analytic",
            ReferenceKind::Numerical => "numerical",
        },
        reference.method,
        reference
            .dt
            .map_or_else(String::new, |dt| format!(" at {dt:.3e} s")),
        reference.estimated_error,
        if reference.converged {
            ""
        } else {
            " — NOT well below the smallest error measured"
        }
    )?;
    writeln!(
        out,
        "{:<18} {:>9} {:>9} {:>22}",
        "integrator", "order", "expected", "least wall time to 1 mm"
    )?;
    for (name, wall) in report.least_wall_time(TARGET_ERROR) {
        let order = report.orders.iter().find(|o| o.integrator == name);
        let observed = order
            .and_then(|o| o.observed_order)
            .map_or_else(|| "-".to_owned(), |p| format!("{p:.3}"));
        let expected = order.map_or_else(|| "-".to_owned(), |o| o.expected_order.to_string());
        let wall = wall.map_or_else(|| "not reached".to_owned(), |w| format!("{w:.3e} s"));
        writeln!(out, "{name:<18} {observed:>9} {expected:>9} {wall:>22}")?;
    }
    writeln!(
        out,
        "wrote {d}/{ACCURACY_JSON}, {d}/{WORK_PRECISION_PNG} and {d}/{CONVERGENCE_PNG}",
        d = dir.display()
    )
}
