//! `hooke accuracy`: each integrator's error against a reference, its
//! order and its run time, as `accuracy.json`, `accuracy.csv` and the
//! work-precision and convergence plots.

use std::io::Write;
use std::path::Path;

use clap::Args;
use hooke_lab::accuracy::{ReferenceKind, Series as RunSeries, StepVariant};
use hooke_lab::{AccuracyOptions, AccuracyReport, Method, Shard, accuracy};
use hooke_viz::plot::{LogLogPlot, Reference, Series, write_log_log};

use super::files::{
    ACCURACY_JSON, CONVERGENCE_PNG, LabReport, RUN_COLUMNS, VARIANTS_PNG, WORK_PRECISION_PNG,
    run_row, write,
};
use super::{SceneArgs, Values};
use crate::cli_error::CliError;

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
    /// Backward Euler's step carried out in other ways, each compared with
    /// the same step converged to 1e-9 at each --variant-dt,
    /// comma-separated: newton:TOL, quasi-newton:TOL, linearized,
    /// fast-mass-spring:ITERATIONS, or none (default, when backward-euler
    /// is measured: newton:1e-2, newton:1e-4, quasi-newton:1e-2,
    /// quasi-newton:1e-3, linearized, fast-mass-spring:10,
    /// fast-mass-spring:100)
    #[arg(long, value_name = "LIST", value_delimiter = ',', value_parser = variant_arg)]
    variants: Option<Vec<VariantArg>>,
    /// The steps of the step variants in seconds (default: the scene's
    /// step).
    #[arg(long, value_name = "VALUES")]
    variant_dt: Option<Values>,
}

/// A step variant, or `none`.
#[derive(Debug, Clone, Copy)]
enum VariantArg {
    None,
    Variant(StepVariant),
}

fn variant_arg(text: &str) -> Result<VariantArg, String> {
    if text.trim() == "none" {
        Ok(VariantArg::None)
    } else {
        text.trim().parse().map(VariantArg::Variant)
    }
}

/// `hooke accuracy`: the whole measurement, or with `--shard` one part of
/// its runs written as a partial report.
pub(crate) fn accuracy_command(args: &AccuracyArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let scene = args.scene.scene()?;
    let mut options = AccuracyOptions::for_scene(&scene);
    options.settings = args.scene.settings(&scene)?;
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
    options.shard = args.scene.shard;
    options.variants = match &args.variants {
        Some(list) => list
            .iter()
            .filter_map(|v| match v {
                VariantArg::None => None,
                VariantArg::Variant(v) => Some(*v),
            })
            .collect(),
        None if options.methods.contains(&Method::BackwardEuler) => StepVariant::defaults(),
        None => Vec::new(),
    };
    if let Some(dts) = &args.variant_dt {
        options.variant_dts.clone_from(&dts.0);
    }
    writeln!(
        out,
        "{}: {} integrators, {} steps from {:.3e} s to {:.3e} s, {} s simulated, {} repeats, {} step variants{}",
        scene.name,
        options.methods.len(),
        options.dts.len(),
        options.dts.first().copied().unwrap_or(f64::NAN),
        options.dts.last().copied().unwrap_or(f64::NAN),
        options.duration,
        options.repeat,
        options.variants.len(),
        options
            .shard
            .map_or_else(String::new, |s| format!(", part {s}"))
    )?;
    let report = args
        .scene
        .measure("runs", |progress| accuracy(&scene, &options, progress))?;
    write(&report, &args.scene.out, out)
}

fn plot_series(series: Vec<RunSeries>) -> Vec<Series> {
    series
        .into_iter()
        .map(|s| Series {
            label: s.integrator.to_string(),
            points: s.points,
        })
        .collect()
}

/// Writes `accuracy.json`, `accuracy.csv` and the figures.
fn figures(report: &AccuracyReport, dir: &Path) -> Result<(), CliError> {
    let plot = |e| CliError::Plot(Box::new(e));
    write_log_log(
        &LogLogPlot {
            title: format!("{}: error against run time", report.scene),
            x_label: "wall time (s)".into(),
            y_label: "RMS error at the end (m)".into(),
            series: plot_series(report.work_precision())
                .into_iter()
                .chain(report.variant_series(|r| r.error_rms).into_iter().map(
                    |(variant, points)| Series {
                        label: format!("backward-euler {variant}"),
                        points,
                    },
                ))
                .collect(),
            reference: Some(Reference {
                y: TARGET_ERROR,
                label: "1 mm".into(),
            }),
        },
        &dir.join(WORK_PRECISION_PNG),
    )
    .map_err(plot)?;
    if !report.variants.is_empty() {
        write_log_log(
            &LogLogPlot {
                title: format!("{}: implicit step variants", report.scene),
                x_label: "wall time (s)".into(),
                y_label: "RMS distance from converged (m)".into(),
                series: report
                    .variant_series(|r| r.error_converged)
                    .into_iter()
                    .map(|(variant, points)| Series {
                        label: variant.to_string(),
                        points,
                    })
                    .collect(),
                reference: Some(Reference {
                    y: TARGET_ERROR,
                    label: "1 mm".into(),
                }),
            },
            &dir.join(VARIANTS_PNG),
        )
        .map_err(plot)?;
    }
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

/// Prints what the measurement found and where its files are.
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
        writeln!(
            out,
            "{:<18} {observed:>9} {expected:>9} {wall:>22}",
            name.name()
        )?;
    }
    print_variants(report, out)?;
    writeln!(
        out,
        "wrote {d}/{ACCURACY_JSON} (and .csv), {d}/{WORK_PRECISION_PNG}, {d}/{CONVERGENCE_PNG}{} \
         (and .svg)",
        if report.variants.is_empty() {
            String::new()
        } else {
            format!(" and {}/{VARIANTS_PNG}", dir.display())
        },
        d = dir.display()
    )
}

/// `"   N steps unconverged, M rejected"`, the parts that are not zero.
fn irregular(unconverged: usize, rejected: usize) -> String {
    let parts: Vec<String> = [(unconverged, "steps unconverged"), (rejected, "rejected")]
        .into_iter()
        .filter(|&(count, _)| count > 0)
        .map(|(count, what)| format!("{count} {what}"))
        .collect();
    if parts.is_empty() {
        String::new()
    } else {
        format!("   {}", parts.join(", "))
    }
}

/// The step variants' table: at each step, the converged step's own cost,
/// then each variant's iterations, wall time and distance from it.
fn print_variants(report: &AccuracyReport, out: &mut dyn Write) -> std::io::Result<()> {
    if report.variants.is_empty() {
        return Ok(());
    }
    let number = |e: Option<f64>| e.map_or_else(|| "-".to_owned(), |e| format!("{e:.2e}"));
    writeln!(
        out,
        "{:<28} {:>10} {:>12} {:>13} {:>14}",
        "backward-euler step", "its/step", "wall (s)", "from conv. (m)", "error at end (m)"
    )?;
    for c in &report.converged {
        writeln!(
            out,
            "{:<28} {:>10.1} {:>12.3e} {:>13} {:>14}   (h = {:.3e} s){}",
            "newton:1e-9 (converged)",
            c.iterations_per_step,
            c.wall_s,
            "0",
            number(c.error_rms),
            c.step,
            irregular(c.unconverged_steps, c.rejected_steps),
        )?;
        if let Some(failure) = &c.failure {
            writeln!(
                out,
                "  the converged step failed ({failure}): no variants at this step"
            )?;
        }
        for r in report
            .variants
            .iter()
            .filter(|r| r.dt.to_bits() == c.dt.to_bits())
        {
            writeln!(
                out,
                "{:<28} {:>10.1} {:>12.3e} {:>13} {:>14}{}{}",
                r.variant.to_string(),
                r.iterations_per_step,
                r.wall_s,
                number(r.error_converged),
                number(r.error_rms),
                irregular(r.unconverged_steps, r.rejected_steps),
                r.failure
                    .as_ref()
                    .map_or_else(String::new, |f| format!("   failed: {f}"))
            )?;
        }
    }
    Ok(())
}

impl LabReport for AccuracyReport {
    const JSON: &'static str = ACCURACY_JSON;
    const COLUMNS: &'static [&'static str] = RUN_COLUMNS;

    fn shard(&self) -> Option<Shard> {
        self.shard
    }

    fn note(&self) -> Option<&str> {
        self.note.as_deref()
    }

    fn rows(&self) -> Vec<Vec<String>> {
        self.runs.iter().map(run_row).collect()
    }

    fn figures(&self, dir: &Path) -> Result<(), CliError> {
        figures(self, dir)
    }

    fn print(&self, dir: &Path, out: &mut dyn Write) -> std::io::Result<()> {
        print_accuracy(self, dir, out)
    }
}
