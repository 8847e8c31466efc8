//! Scenes whose surfaces collide, end to end: `hooke run` reports how
//! close the surfaces came in `summary.json` and its last lines, refuses
//! them with an explicit method, and the lab runs such methods without
//! self-collision or reports them not applicable.

mod common;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use common::hooke;
use serde_json::Value;

/// A 4 × 4 cloth table, 0.1 m wide, at height `y`, with `extra` keys.
fn cloth(y: f64, extra: &str) -> String {
    format!(
        "[[bodies]]\ntype = \"cloth\"\ncolumns = 4\nrows = 4\nsize = [0.1, 0.1]\n\
         offset = [0.0, {y}, 0.0]\nstretch = {{ stiffness = 50.0 }}\n{extra}\n"
    )
}

/// A scene file in `dir` named `name`: no gravity, `method`, 1/100 s
/// steps, and `bodies`.
fn scene(dir: &Path, name: &str, method: &str, bodies: &str) -> PathBuf {
    let text = format!(
        "[simulation]\nduration = 0.05\ndt = 0.01\nframe_rate = 100.0\n\n\
         [integrator]\nmethod = \"{method}\"\n\n\
         [world]\ngravity = [0.0, 0.0, 0.0]\ncontact_distance = 5e-3\n\n{bodies}"
    );
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// `hooke run` on `file` into `out` with the options `extra`, without the
/// animation or a progress bar.
fn run(file: &Path, out: &Path, extra: &[&str]) -> (ExitCode, String, String) {
    let mut args = vec![
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-gif",
        "-q",
    ];
    args.extend_from_slice(extra);
    hooke(&args)
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Two cloths 3 mm apart, within the 5 mm contact distance.
fn two_cloths() -> String {
    cloth(0.0, "") + &cloth(3e-3, "")
}

#[test]
fn a_run_with_colliding_surfaces_reports_how_close_they_came() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "stack", "backward-euler", &two_cloths());
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&file, &out, &["--duration", "0.03"]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let summary = json(&out.join("summary.json"));
    assert!((summary["contact_distance"].as_f64().unwrap() - 5e-3).abs() < 1e-15);
    // Every particle of the upper cloth over the lower's triangles, at least.
    let pairs = summary["close_pairs_max"].as_u64().unwrap();
    assert!(pairs >= 16, "{summary}");
    let smallest = summary["smallest_distance"].as_f64().unwrap();
    assert!(smallest > 0.0 && smallest <= 3e-3 + 1e-12, "{smallest}");
    assert_eq!(summary["intersecting_triangle_pairs"].as_u64(), Some(0));
    assert_eq!(summary["intersections"], serde_json::json!([]), "{summary}");
    let line = stdout
        .lines()
        .find(|l| l.starts_with("contact: "))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(
        line.contains(&format!("at most {pairs} close pairs")),
        "{line}"
    );
    assert!(
        line.ends_with("0 intersecting triangle pairs at the end"),
        "{line}"
    );
}

#[test]
fn a_run_without_surfaces_has_null_contact_fields_and_no_contact_line() {
    let dir = tempfile::tempdir().unwrap();
    let rope = "[[bodies]]\ntype = \"rope\"\nstart = [0, 0, 0]\nend = [1, 0, 0]\nsegments = 3\n\
                stretch = { stiffness = 10.0 }\n";
    let file = scene(dir.path(), "rope", "velocity-verlet", rope);
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&file, &out, &[]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let summary = json(&out.join("summary.json"));
    for key in [
        "contact_distance",
        "close_pairs_max",
        "smallest_distance",
        "intersecting_triangle_pairs",
        "intersections",
    ] {
        assert!(summary[key].is_null(), "{key} in {summary}");
    }
    assert!(!stdout.contains("contact: "), "{stdout}");
}

#[test]
fn a_self_colliding_cloth_far_from_itself_has_no_smallest_distance() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "one", "backward-euler", &cloth(0.0, ""));
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&file, &out, &[]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let summary = json(&out.join("summary.json"));
    assert_eq!(summary["close_pairs_max"].as_u64(), Some(0));
    assert!(summary["smallest_distance"].is_null(), "{summary}");
    assert!(
        stdout.contains("none within the contact distance"),
        "{stdout}"
    );
}

#[test]
fn an_explicit_method_refuses_a_self_colliding_scene_with_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "one", "velocity-verlet", &cloth(0.0, ""));
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&file, &out, &[]);
    assert_eq!(code, ExitCode::FAILURE, "{stdout}\n{stderr}");
    let reason = "velocity-verlet cannot keep surfaces from passing through each other";
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(stderr.contains(reason), "{stderr}");
    let summary = json(&out.join("summary.json"));
    assert!(
        summary["error"].as_str().unwrap().contains(reason),
        "{summary}"
    );
    assert_eq!(summary["steps"].as_u64(), Some(0));
    // Without self-collision the same cloth runs.
    let file = scene(
        dir.path(),
        "loose",
        "velocity-verlet",
        &cloth(0.0, "self_collision = false"),
    );
    let (code, stdout, stderr) = run(&file, &out, &[]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
}

/// `hooke stability` on `file`: two methods, one cell each.
fn stability(file: &Path, out: &Path) -> (ExitCode, String, String) {
    hooke(&[
        "stability",
        file.to_str().unwrap(),
        "--methods",
        "symplectic-euler,backward-euler",
        "--stiffness",
        "1",
        "--dt",
        "1e-3",
        "--duration",
        "0.005",
        "--min-steps",
        "5",
        "--limit",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ])
}

#[test]
fn stability_runs_explicit_methods_without_self_collision_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "one", "backward-euler", &cloth(0.0, ""));
    let out = dir.path().join("lab");
    let (code, stdout, stderr) = stability(&file, &out);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let notes: Vec<&str> = stdout.lines().filter(|l| l.starts_with("note: ")).collect();
    assert_eq!(notes.len(), 1, "{stdout}");
    assert!(
        notes[0].contains("explicit methods run without self-collision"),
        "{stdout}"
    );
    let report = json(&out.join("stability.json"));
    assert!(
        report["note"]
            .as_str()
            .unwrap()
            .contains("symplectic-euler")
    );
    for cell in report["cells"].as_array().unwrap() {
        assert_eq!(cell["applicable"], true, "{cell}");
        assert_eq!(cell["stable"], true, "{cell}");
        assert!(cell["stopped"].is_null(), "{cell}");
    }
    assert_eq!(report["limits"].as_array().unwrap().len(), 2);
}

#[test]
fn stability_reports_explicit_methods_not_applicable_when_bodies_collide() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "two", "backward-euler", &two_cloths());
    let out = dir.path().join("lab");
    let (code, stdout, stderr) = stability(&file, &out);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    assert!(stdout.contains("not applicable"), "{stdout}");
    let report = json(&out.join("stability.json"));
    assert!(report["note"].as_str().unwrap().contains("not applicable"));
    let cells = report["cells"].as_array().unwrap();
    let explicit = cells
        .iter()
        .find(|c| c["integrator"] == "symplectic-euler")
        .unwrap();
    assert_eq!(explicit["applicable"], false, "{explicit}");
    assert_eq!(explicit["stable"], false, "{explicit}");
    assert_eq!(explicit["steps"], 0, "{explicit}");
    let reason = explicit["stopped"].as_str().unwrap();
    assert!(
        reason.contains("symplectic-euler cannot keep surfaces from passing through each other"),
        "{reason}"
    );
    let implicit = cells
        .iter()
        .find(|c| c["integrator"] == "backward-euler")
        .unwrap();
    assert_eq!(implicit["applicable"], true, "{implicit}");
    // The limit search leaves the method that cannot run out.
    let limits = report["limits"].as_array().unwrap();
    assert_eq!(limits.len(), 1);
    assert_eq!(limits[0]["integrator"], "backward-euler");
    let csv = std::fs::read_to_string(out.join("stability.csv")).unwrap();
    assert!(
        csv.lines().next().unwrap().ends_with(",applicable"),
        "{csv}"
    );
}

/// `hooke accuracy` on `file` with two methods and two steps.
fn accuracy(file: &Path, out: &Path) -> (ExitCode, String, String) {
    hooke(&[
        "accuracy",
        file.to_str().unwrap(),
        "--methods",
        "symplectic-euler,backward-euler",
        "--dt",
        "5e-3,1e-2",
        "--duration",
        "0.02",
        "--frames",
        "2",
        "--repeat",
        "1",
        "--reference-dt",
        "1e-3",
        "--out",
        out.to_str().unwrap(),
        "-q",
    ])
}

#[test]
fn accuracy_measures_a_self_colliding_scene_without_self_collision() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "one", "backward-euler", &cloth(0.0, ""));
    let out = dir.path().join("lab");
    let (code, stdout, stderr) = accuracy(&file, &out);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    assert_eq!(
        stdout.lines().filter(|l| l.starts_with("note: ")).count(),
        1,
        "{stdout}"
    );
    let report = json(&out.join("accuracy.json"));
    assert!(
        report["note"]
            .as_str()
            .unwrap()
            .contains("without self-collision")
    );
    for run in report["runs"].as_array().unwrap() {
        assert!(run["failure"].is_null(), "{run}");
    }
}

#[test]
fn accuracy_on_colliding_bodies_is_an_error_naming_why() {
    let dir = tempfile::tempdir().unwrap();
    let file = scene(dir.path(), "two", "backward-euler", &two_cloths());
    let (code, stdout, stderr) = accuracy(&file, &dir.path().join("lab"));
    assert_eq!(code, ExitCode::FAILURE, "{stdout}\n{stderr}");
    assert!(
        stderr.contains("surfaces of different bodies collide"),
        "{stderr}"
    );
}

/// A shell of two triangles passing through each other, with
/// self-collision off, held still (no gravity) by an explicit method: the
/// summary counts the one intersecting pair and names the body, with
/// itself, where the contact model does not keep it apart, and the last
/// lines say so.
#[test]
fn intersecting_triangles_are_reported_by_body() {
    let dir = tempfile::tempdir().unwrap();
    // A triangle in the plane z = 0 and one through it along z.
    let obj = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0.02 0.02 -0.05\nv 0.03 0.02 0.05\n\
               v 0.02 0.03 0.05\nf 1 2 3\nf 4 5 6\n";
    std::fs::write(dir.path().join("crossed.obj"), obj).unwrap();
    let body = "[[bodies]]\ntype = \"obj\"\nname = \"crossed\"\nmesh = \"crossed.obj\"\n\
                edges = { stiffness = 10.0 }\nself_collision = false\n";
    let file = scene(dir.path(), "crossed", "velocity-verlet", body);
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&file, &out, &[]);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let summary = json(&out.join("summary.json"));
    assert_eq!(summary["intersecting_triangle_pairs"].as_u64(), Some(1));
    let expected: Value = serde_json::json!([
        { "bodies": ["crossed", "crossed"], "pairs": 1, "collide": false }
    ]);
    assert_eq!(summary["intersections"], expected, "{summary}");
    let line = stdout
        .lines()
        .find(|l| l.starts_with("contact: "))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(
        line.ends_with(
            "1 intersecting triangle pairs at the end (crossed with itself: 1, self-collision off)"
        ),
        "{line}"
    );
}
