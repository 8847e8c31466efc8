//! `hooke stability`, `hooke accuracy` and `hooke merge`: the lab's
//! measurements from the command line, written as JSON, CSV, PNG and SVG
//! into `--out DIR`, whole or (with `--shard I/N`) in parts to merge.

mod accuracy;
mod files;
mod merge;
mod stability;

use std::path::PathBuf;

use clap::Args;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use hooke_core::Named;
use hooke_implicit::{LinearSolver, PcgSettings};
use hooke_lab::{LabError, Method, Range, Shard};
use hooke_scenes::Scene;
use indicatif::{ProgressBar, ProgressStyle};

use crate::cli_error::CliError;
use crate::scene_source::load_scene;

pub(crate) use accuracy::{AccuracyArgs, accuracy_command};
pub(crate) use merge::{MergeArgs, merge_command};
pub(crate) use stability::{StabilityArgs, stability_command};

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
    /// Run only part I of N of the sweep (0 ≤ I < N; cells dealt in turn)
    /// and write a partial report, for `hooke merge`.
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
    /// Multiply every spring's stiffness by SCALE first.
    #[arg(long = "scale-stiffness", value_name = "SCALE")]
    scale_stiffness: Option<f64>,
    /// The implicit methods' linear solver, any value of the scene file's
    /// `solver` key (default: the scene's, if it runs an implicit method,
    /// else the library's, auto).
    #[arg(long, value_name = "SOLVER", value_parser = solver_parser())]
    solver: Option<LinearSolver>,
    /// The relative residual at which the --solver stops, when it is a PCG
    /// iteration (default: PCG's own).
    #[arg(long, value_name = "TOL", requires = "solver")]
    pcg_tolerance: Option<f64>,
    /// The implicit methods' cap on Newton iterations per (sub)step
    /// (default: the scene's, else the integrator's).
    #[arg(long, value_name = "N")]
    newton: Option<usize>,
    /// The implicit methods take Baraff and Witkin's linearised step (one
    /// solve, no line search, no rejection) instead of converged ones.
    #[arg(long)]
    linearized: bool,
}

/// `--solver`'s values: the names of the scene file's `solver` key, from
/// its table ([`Named::TABLE`]), each read as that solver at PCG's
/// default settings.
fn solver_parser() -> impl TypedValueParser<Value = LinearSolver> {
    PossibleValuesParser::new(LinearSolver::names()).try_map(|name| {
        LinearSolver::from_name(&name).ok_or_else(|| format!("no solver \"{name}\""))
    })
}

impl SceneArgs {
    fn scene(&self) -> Result<Scene, CliError> {
        let mut scene = load_scene(self.scene.as_deref(), self.builtin.as_deref())?;
        if let Some(scale) = self.scale_stiffness {
            scene.system = scene
                .system
                .with_stiffness_scale(scale)
                .map_err(|source| CliError::ScaleStiffness { scale, source })?;
        }
        Ok(scene)
    }

    /// The lab's method settings for `scene`, with `--solver`,
    /// `--pcg-tolerance`, `--newton` and `--linearized` set on its
    /// implicit settings.
    ///
    /// # Errors
    /// [`CliError::PcgTolerance`] for `--pcg-tolerance` with a solver that
    /// is not a PCG iteration, [`LabError::Parameter`] for one out of range.
    fn settings(&self, scene: &Scene) -> Result<hooke_lab::Settings, CliError> {
        let mut settings = hooke_lab::Settings::from_scene(&scene.integrator);
        let implicit = &mut settings.implicit;
        if let Some(solver) = self.solver {
            implicit.solver = match self.pcg_tolerance {
                None => solver,
                Some(tolerance) if solver.pcg().is_some() => {
                    let pcg = PcgSettings::new(tolerance, PcgSettings::default().max_iterations())
                        .map_err(LabError::from)?;
                    solver.with_pcg(pcg)
                }
                Some(_) => {
                    return Err(CliError::PcgTolerance {
                        solver: solver.name(),
                    });
                }
            };
        }
        if let Some(n) = self.newton {
            implicit.newton_iterations = n;
        }
        if self.linearized {
            implicit.minimizer = hooke_implicit::Minimizer::Linearized;
        }
        Ok(settings)
    }

    /// The methods named, or `all` when none is.
    fn methods(&self, all: &[Method]) -> Result<Vec<Method>, CliError> {
        if self.methods.is_empty() {
            return Ok(all.to_vec());
        }
        self.methods
            .iter()
            .map(|name| {
                Method::from_name(name.trim())
                    .ok_or_else(|| CliError::UnknownMethod { name: name.clone() })
            })
            .collect()
    }

    /// Runs `measure` with a progress bar of `what` (hidden with
    /// `--quiet`) fed by its progress callback.
    fn measure<R>(
        &self,
        what: &str,
        measure: impl FnOnce(&(dyn Fn(usize, usize) + Sync)) -> Result<R, LabError>,
    ) -> Result<R, CliError> {
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
        Ok(result?)
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    /// A command of the lab's scene arguments alone.
    #[derive(Debug, Parser)]
    struct Lab {
        #[command(flatten)]
        scene: SceneArgs,
    }

    /// The settings `args` give the built-in oscillator, or why `args` do
    /// not parse.
    fn settings(args: &[&str]) -> Result<Result<hooke_lab::Settings, CliError>, clap::Error> {
        let scene = hooke_scenes::builtin::load("oscillator").unwrap();
        let lab = Lab::try_parse_from(std::iter::once("lab").chain(args.iter().copied()))?;
        Ok(lab.scene.settings(&scene))
    }

    #[test]
    fn solver_names_the_scene_files_solver_and_pcg_tolerance_sets_its_tolerance() {
        let pcg = PcgSettings::default();
        let solver = |args: &[&str]| settings(args).unwrap().unwrap().implicit.solver;
        // The oscillator runs velocity Verlet: the implicit methods take
        // the library's default solver.
        assert_eq!(solver(&[]), LinearSolver::default());
        for name in LinearSolver::names() {
            let expected = LinearSolver::from_name(name).unwrap();
            assert_eq!(solver(&["--solver", name]), expected);
            let tightened = settings(&["--solver", name, "--pcg-tolerance", "1e-9"]).unwrap();
            match expected.pcg() {
                Some(_) => assert_eq!(
                    tightened.unwrap().implicit.solver,
                    expected.with_pcg(PcgSettings::new(1e-9, pcg.max_iterations()).unwrap())
                ),
                None => assert!(
                    matches!(tightened, Err(CliError::PcgTolerance { solver }) if solver == name)
                ),
            }
        }
        assert!(settings(&["--solver", "multigrid"]).is_err());
        assert!(settings(&["--pcg-tolerance", "1e-9"]).is_err());
    }
}
