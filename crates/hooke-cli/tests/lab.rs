//! `hooke stability` and `hooke accuracy` end to end on the oscillator
//! scenes: the JSON has the documented fields and agrees with theory, the
//! figures are PNG images, and bad options are errors naming the option.

mod common;

use std::path::Path;
use std::process::ExitCode;

use common::hooke;
use hooke_core::Named;
use serde_json::Value;

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn assert_png(path: &Path) {
    let image = hooke_viz::Pixmap::load_png(path).unwrap();
    assert!(
        image.width() >= 600 && image.height() >= 400,
        "{}",
        path.display()
    );
}

#[test]
fn stability_writes_cells_limits_and_the_heat_map() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lab");
    let (code, stdout, stderr) = hooke(&[
        "stability",
        "--builtin",
        "oscillator",
        "--methods",
        "symplectic-euler,rk4,backward-euler",
        "--stiffness",
        "1:100:3",
        "--dt",
        "1e-3:1e-1:3",
        "--duration",
        "0.1",
        "--limit",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let report = json(&out.join("stability.json"));
    assert_eq!(report["scene"], "oscillator");
    assert!((report["energy_bound"].as_f64().unwrap() - 10.0).abs() < 1e-12);
    assert!((report["omega_max"].as_f64().unwrap() - 1.0).abs() < 1e-9);
    let cells = report["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 3 * 3 * 3);
    for cell in cells {
        for key in [
            "integrator",
            "stiffness_scale",
            "dt",
            "stable",
            "max_energy_ratio",
            "max_energy_gain",
            "h_omega",
            "wall_s",
        ] {
            assert!(cell.get(key).is_some(), "{key} in {cell}");
        }
        // Backward Euler damps the oscillator: it never gains energy.
        if cell["integrator"] == "backward-euler" {
            let gain = cell["max_energy_gain"].as_f64().unwrap();
            assert!(gain <= 1e-9, "{cell}");
            assert!(cell["max_energy_ratio"].as_f64().unwrap() <= 1.0 + 1e-9);
        }
        // Symplectic Euler is stable exactly below h·ω = 2.
        if cell["integrator"] == "symplectic-euler" {
            let h_omega = cell["h_omega"].as_f64().unwrap();
            assert_eq!(cell["stable"].as_bool(), Some(h_omega < 2.0), "{cell}");
        }
    }
    let limits = report["limits"].as_array().unwrap();
    let limit = |name: &str| {
        limits
            .iter()
            .find(|l| l["integrator"] == name)
            .and_then(|l| l["h_omega_limit"].as_f64())
    };
    assert!((limit("symplectic-euler").unwrap() / 2.0 - 1.0).abs() < 0.02);
    assert!((limit("rk4").unwrap() / 8f64.sqrt() - 1.0).abs() < 0.02);
    assert_eq!(limit("backward-euler"), None);
    assert!(stdout.contains("stability.png"), "{stdout}");
    assert_png(&out.join("stability.png"));
    let csv = std::fs::read_to_string(out.join("stability.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let gain = header.iter().position(|&c| c == "max_energy_gain").unwrap();
    assert_eq!(header[gain - 1], "max_energy_ratio");
    for (row, cell) in csv.lines().skip(1).zip(cells) {
        let field = row.split(',').nth(gain).unwrap();
        let reported = cell["max_energy_gain"].as_f64().unwrap();
        assert!((field.parse::<f64>().unwrap() - reported).abs() <= 1e-12 * reported.abs());
    }
}

#[test]
fn accuracy_writes_runs_orders_and_both_plots() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lab");
    let (code, stdout, stderr) = hooke(&[
        "accuracy",
        "--builtin",
        "damped-oscillator",
        "--methods",
        "velocity-verlet,backward-euler,dormand-prince",
        "--dt",
        "0.001:0.008:4",
        "--tolerances",
        "1e-4,1e-6",
        "--repeat",
        "1",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let report = json(&out.join("accuracy.json"));
    assert_eq!(report["scene"], "damped-oscillator");
    assert_eq!(report["reference"]["kind"], "analytic");
    for key in ["method", "dt", "estimated_error"] {
        assert!(report["reference"].get(key).is_some(), "reference.{key}");
    }
    let runs = report["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 4 + 4 + 2);
    for run in runs {
        for key in [
            "integrator",
            "dt",
            "tolerance",
            "steps",
            "error_rms",
            "error_max",
            "wall_s",
            "force_evaluations",
            "linear_iterations",
        ] {
            assert!(run.get(key).is_some(), "{key} in {run}");
        }
        assert!(run["error_rms"].as_f64().unwrap() > 0.0, "{run}");
    }
    let order = |name: &str| {
        report["orders"]
            .as_array()
            .unwrap()
            .iter()
            .find(|o| o["integrator"] == name)
            .and_then(|o| o["observed_order"].as_f64())
    };
    assert!((order("velocity-verlet").unwrap() - 2.0).abs() < 0.15);
    assert!((order("backward-euler").unwrap() - 1.0).abs() < 0.15);
    assert_png(&out.join("work_precision.png"));
    assert_png(&out.join("convergence.png"));
    // Backward Euler is measured, so its default step variants run at the
    // scene's step beside its converged step.
    let variants = report["variants"].as_array().unwrap();
    assert_eq!(variants.len(), 7);
    assert_eq!(variants[0]["variant"], "newton:1e-2");
    for run in variants {
        for key in [
            "dt",
            "step",
            "error_converged",
            "error_rms",
            "wall_s",
            "iterations_per_step",
            "unconverged_steps",
            "rejected_steps",
        ] {
            assert!(run.get(key).is_some(), "{key} in {run}");
        }
    }
    assert_eq!(report["converged"].as_array().unwrap().len(), 1);
    assert!(stdout.contains("newton:1e-9 (converged)"), "{stdout}");
    assert_png(&out.join("variants.png"));
}

#[test]
fn bad_lab_options_are_errors_naming_them() {
    for (args, expected) in [
        (
            vec!["stability", "--builtin", "oscillator", "--methods", "rk5"],
            "rk5",
        ),
        (
            vec![
                "stability",
                "--builtin",
                "oscillator",
                "--energy-bound",
                "0.5",
            ],
            "energy bound",
        ),
        (
            vec!["stability", "--builtin", "oscillator", "--duration", "0"],
            "duration",
        ),
        (
            vec!["accuracy", "--builtin", "oscillator", "--repeat", "0"],
            "repeat",
        ),
        (
            vec![
                "accuracy",
                "--builtin",
                "oscillator",
                "--scale-stiffness=-2",
            ],
            "scale-stiffness",
        ),
        (
            vec![
                "stability",
                "--builtin",
                "oscillator",
                "--solver",
                "cholesky",
                "--pcg-tolerance",
                "1e-3",
            ],
            "--pcg-tolerance: solver \"cholesky\" takes no tolerance",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let mut args = args;
        args.extend(["--out", dir.path().to_str().unwrap(), "-q"]);
        let (code, _, stderr) = hooke(&args);
        assert_eq!(code, ExitCode::FAILURE, "{args:?}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    // A malformed range is refused while the arguments are parsed.
    let (code, _, stderr) = hooke(&["stability", "--dt", "0:1:3"]);
    assert_eq!(code, ExitCode::from(2));
    assert!(stderr.contains("FIRST:LAST:COUNT"), "{stderr}");
    // So is a step variant that is not one.
    let (code, _, stderr) = hooke(&["accuracy", "--variants", "linearized,newton:abc"]);
    assert_eq!(code, ExitCode::from(2));
    assert!(
        stderr.contains("\"newton:abc\": a tolerance must be a number > 0"),
        "{stderr}"
    );
}

/// `--solver` offers every value of the scene file's `solver` key, and
/// only those, in every lab command.
#[test]
fn every_lab_command_offers_the_scene_files_solvers() {
    let names: Vec<_> = hooke_implicit::LinearSolver::names().collect();
    let listed = format!("[possible values: {}]", names.join(", "));
    for command in ["stability", "accuracy"] {
        let (code, stdout, _) = hooke(&[command, "--help"]);
        assert_eq!(code, ExitCode::SUCCESS);
        let line = stdout
            .lines()
            .find(|l| l.trim_start().starts_with("--solver"))
            .unwrap();
        assert!(line.ends_with(&listed), "{command}: {line}");
        let (code, _, stderr) = hooke(&[command, "--solver", "multigrid"]);
        assert_eq!(code, ExitCode::from(2), "{command}: {stderr}");
        for name in &names {
            assert!(stderr.contains(name), "{command}: {stderr}");
        }
    }
    // Each parses as the scene file reads it; a PCG iteration takes the
    // tolerance, and --pcg-tolerance needs a --solver.
    for name in names {
        let dir = tempfile::tempdir().unwrap();
        let mut args = vec![
            "stability",
            "--builtin",
            "oscillator",
            "--methods",
            "backward-euler",
            "--stiffness",
            "1",
            "--dt",
            "0.1",
            "--duration",
            "1",
            "--min-steps",
            "10",
            "--solver",
            name,
            "--out",
            dir.path().to_str().unwrap(),
            "-q",
        ];
        let tolerance = hooke_implicit::LinearSolver::iterative_names().any(|n| n == name);
        if tolerance {
            args.extend(["--pcg-tolerance", "1e-9"]);
        }
        let (code, stdout, stderr) = hooke(&args);
        assert_eq!(code, ExitCode::SUCCESS, "{name}: {stdout}\n{stderr}");
        let report = json(&dir.path().join("stability.json"));
        assert_eq!(report["cells"][0]["stable"], true, "{name}");
    }
    let (code, _, stderr) = hooke(&["accuracy", "--pcg-tolerance", "1e-3"]);
    assert_eq!(code, ExitCode::from(2));
    assert!(stderr.contains("--solver"), "{stderr}");
}
