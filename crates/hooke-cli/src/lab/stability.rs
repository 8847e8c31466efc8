//! `hooke stability`: which integrators stay stable at which stiffness and
//! step, as `stability.json`, `stability.csv` and the heat maps.

use std::io::Write;
use std::path::Path;

use clap::Args;
use hooke_lab::{Method, Shard, StabilityOptions, StabilityReport, stability};
use hooke_viz::plot::{Cell, HeatMapPanel, HeatMaps, write_heat_maps};

use super::files::{CELL_COLUMNS, LabReport, STABILITY_JSON, STABILITY_PNG, cell_row, write};
use super::{SceneArgs, Values};
use crate::cli_error::CliError;

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
    /// A cell is stable while its energy ratio 1 + G/(E(0) + max W) stays
    /// at or below FACTOR, where G = E − E(0) − W is the energy gained over
    /// the initial energy E(0) plus the work W of gravity, pins and the
    /// system's own terms (a wind).
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

/// `hooke stability`: the whole sweep, or with `--shard` one part of it
/// written as a partial report.
pub(crate) fn stability_command(args: &StabilityArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let scene = args.scene.scene()?;
    let mut options = StabilityOptions::for_scene(&scene);
    options.settings = args.scene.settings(&scene)?;
    options.methods = args.scene.methods(&Method::ALL)?;
    options.scales.clone_from(&args.stiffness.0);
    options.dts.clone_from(&args.dt.0);
    options.duration = args.duration;
    options.min_steps = args.min_steps;
    options.energy_bound = args.energy_bound;
    options.limit_scale = args.limit.then_some(args.limit_stiffness);
    options.shard = args.scene.shard;
    writeln!(
        out,
        "{}: {} integrators × {} stiffness scales × {} timesteps{}{}",
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
        },
        options
            .shard
            .map_or_else(String::new, |s| format!(", part {s}"))
    )?;
    let report = args
        .scene
        .measure("cells", |progress| stability(&scene, &options, progress))?;
    write(&report, &args.scene.out, out)
}

/// Writes `stability.json`, `stability.csv` and the figure.
fn figures(report: &StabilityReport, dir: &Path) -> Result<(), CliError> {
    let path = dir.join(STABILITY_PNG);
    write_heat_maps(&heat_maps(report), &path).map_err(|e| CliError::Plot(Box::new(e)))
}

/// One heat-map panel per integrator, in the report's order, leaving out
/// the integrators that are not applicable (unless no other is).
fn heat_maps(report: &StabilityReport) -> HeatMaps {
    let mut panels: Vec<HeatMapPanel> = Vec::new();
    let any_applicable = report.cells.iter().any(|c| c.applicable);
    for cell in &report.cells {
        if any_applicable && !cell.applicable {
            continue;
        }
        if panels
            .last()
            .is_none_or(|p| p.title != cell.integrator.name())
        {
            panels.push(HeatMapPanel {
                title: cell.integrator.to_string(),
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
            "{}: stable cells (energy ratio at most {}) and h·ω_max = 2",
            report.scene, report.energy_bound
        ),
        panels,
        omega_max: Some(report.omega_max),
    }
}

/// Prints what the sweep found and where its files are.
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
    let mut names: Vec<Method> = report.cells.iter().map(|c| c.integrator).collect();
    names.dedup();
    for name in names {
        let cells = report.cells.iter().filter(|c| c.integrator == name);
        if cells.clone().all(|c| !c.applicable) {
            writeln!(out, "{:<18} {:>14}", name.name(), "not applicable")?;
            continue;
        }
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
            "{:<18} {:>14} {largest:>16}",
            name.name(),
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
            writeln!(
                out,
                "{:<18} {dt:>16} {h_omega:>14}",
                limit.integrator.name()
            )?;
        }
    }
    writeln!(
        out,
        "wrote {d}/{STABILITY_JSON} (and .csv) and {d}/{STABILITY_PNG} (and .svg)",
        d = dir.display()
    )
}

impl LabReport for StabilityReport {
    const JSON: &'static str = STABILITY_JSON;
    const COLUMNS: &'static [&'static str] = CELL_COLUMNS;

    fn shard(&self) -> Option<Shard> {
        self.shard
    }

    fn note(&self) -> Option<&str> {
        self.note.as_deref()
    }

    fn rows(&self) -> Vec<Vec<String>> {
        self.cells.iter().map(cell_row).collect()
    }

    fn figures(&self, dir: &Path) -> Result<(), CliError> {
        figures(self, dir)
    }

    fn print(&self, dir: &Path, out: &mut dyn Write) -> std::io::Result<()> {
        print_stability(self, dir, out)
    }
}
