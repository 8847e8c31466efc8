//! The implicit settings a run used, as `summary.json` reports them and
//! `hooke check` prints them: the scene file's keys, every enum by its
//! table's name, the defaults included.

mod common;

use std::path::Path;
use std::process::ExitCode;

use hooke_cli::{SUMMARY_FILE, Summary};
use hooke_implicit::{ImplicitSettings, LinearSolver, Minimizer, Scheme, Supernodes};
use serde_json::{Value, json};

use common::hooke;

/// A 5×5 cloth pinned at two corners, not colliding with itself (so that
/// an explicit method runs it), run for 0.05 s with `integrator` as its
/// `[integrator]` table.
fn scene(dir: &Path, integrator: &str) -> String {
    let path = dir.join("scene.toml");
    let text = format!(
        "name = \"settings\"\n\n[simulation]\nduration = 0.05\ndt = 0.01\n\n\
         [integrator]\n{integrator}\n\n[world]\ngravity = [0.0, -9.81, 0.0]\n\n\
         [[bodies]]\ntype = \"cloth\"\ncolumns = 5\nrows = 5\n\
         stretch = {{ stiffness = 1e3 }}\npins = [\"top-left\", \"top-right\"]\n\
         self_collision = false\n"
    );
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

/// Runs the scene file at `path` into `dir/out` and returns its summary,
/// as JSON and typed.
fn run(dir: &Path, path: &str) -> (Value, Summary) {
    let out = dir.join("out");
    let (code, _, err) = hooke(&[
        "run",
        path,
        "--out",
        out.to_str().unwrap(),
        "-q",
        "--no-gif",
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    let text = std::fs::read_to_string(out.join(SUMMARY_FILE)).unwrap();
    (
        serde_json::from_str(&text).unwrap(),
        serde_json::from_str(&text).unwrap(),
    )
}

#[test]
fn summary_json_reports_every_implicit_setting_the_run_used() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(
        dir.path(),
        "method = \"bdf2\"\nsolver = \"cholesky\"\nsupernodes = \"faer\"\nnewton_tolerance = 1e-4",
    );
    let (json, summary) = run(dir.path(), &path);
    assert_eq!(
        json["implicit_settings"],
        json!({
            "scheme": "bdf2",
            "solver": "cholesky",
            "step": "newton",
            "newton_iterations": 100,
            "newton_tolerance": 1e-4,
            "inexact_newton": true,
            "weak_springs": "kept",
            "supernodes": "faer",
            "max_halvings": 10,
            "strict": false,
            "compressed_springs": "clamped",
            "contact_limit": "global",
        })
    );
    // Read back, the report is the settings the scene file gave, the
    // weak springs as the run used them.
    assert_eq!(
        summary.implicit_settings,
        Some(ImplicitSettings {
            scheme: Scheme::Bdf2,
            solver: LinearSolver::Cholesky,
            supernodes: Supernodes::Faer,
            newton_tolerance: 1e-4,
            weak_springs: Some(ImplicitSettings::default().weak_springs_used()),
            ..ImplicitSettings::default()
        })
    );
    assert_eq!(json["linear_solver"], "cholesky");

    // The quasi-Newton step reports its history, a PCG iteration its
    // tolerance and cap; the keys that do not apply are left out.
    let path = scene(
        dir.path(),
        "step = \"quasi-newton\"\nhistory = 3\nsolver = \"pcg\"\nmax_iterations = 40",
    );
    let (json, summary) = run(dir.path(), &path);
    let settings = &json["implicit_settings"];
    assert_eq!(
        (
            &settings["step"],
            &settings["history"],
            &settings["carried_pairs"]
        ),
        (&json!("quasi-newton"), &json!(3), &json!(1))
    );
    assert_eq!(
        (&settings["tolerance"], &settings["max_iterations"]),
        (&json!(1e-6), &json!(40))
    );
    for absent in ["supernodes", "amg_renewal", "inexact_newton", "rtol"] {
        assert!(settings.get(absent).is_none(), "{absent} in {settings}");
    }
    let read = summary.implicit_settings.unwrap();
    assert_eq!(
        read.minimizer,
        Minimizer::QuasiNewton {
            history: 3,
            carried: 1
        }
    );

    // An explicit method has none.
    let path = scene(dir.path(), "method = \"rk4\"");
    let (json, summary) = run(dir.path(), &path);
    assert_eq!(json["implicit_settings"], Value::Null);
    assert_eq!(summary.implicit_settings, None);
}

/// A summary whose settings name what the settings do not take is not
/// read as one.
#[test]
fn a_summary_with_an_unknown_setting_is_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(dir.path(), "");
    let (mut json, _) = run(dir.path(), &path);
    json["implicit_settings"]["solver"] = json!("multigrid");
    let error = serde_json::from_value::<Summary>(json)
        .unwrap_err()
        .to_string();
    assert!(error.contains("solver: got \"multigrid\""), "{error}");
}

/// `hooke check` prints every implicit setting as the scene file writes
/// it, the defaults included.
#[test]
fn check_prints_every_implicit_setting_as_the_scene_file_writes_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(
        dir.path(),
        "solver = \"amg\"\namg_renewal = \"smoother-only\"",
    );
    let (code, out, err) = hooke(&["check", &path]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    let line = out
        .lines()
        .find_map(|l| l.strip_prefix("settings    "))
        .unwrap_or_else(|| panic!("no settings line in\n{out}"));
    assert_eq!(
        line,
        "solver = \"amg\", tolerance = 1e-6, max_iterations = 1000, step = \"newton\", \
         newton_iterations = 100, newton_tolerance = 0.005, inexact_newton = true, \
         amg_renewal = \"smoother-only\", max_halvings = 10, strict = false, \
         compressed_springs = \"clamped\", contact_limit = \"global\""
    );
    assert!(
        out.contains("amg: multigrid PCG to 1e-6 in at most 1000 iterations, newton: "),
        "{out}"
    );
}
