//! The `hooke` command line in-process through `run_cli`: listing the
//! built-in scenes, checking shipped and malformed scene files, running a
//! small scene file end to end, and failing with a message, never a panic.

mod common;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use hooke_cli::{SUMMARY_FILE, Summary};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::DefaultElement;

use common::hooke;

fn shipped(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    path.to_str().unwrap().to_owned()
}

/// A 6×6 cloth over a sphere; with `method = "explicit-euler"` and a big
/// step, a scene that blows up.
fn small_scene(dir: &Path, method: &str, dt: f64, duration: f64) -> PathBuf {
    let path = dir.join(format!("{method}.toml"));
    let text = format!(
        r#"name = "small {method}"

[simulation]
duration = {duration}
dt = {dt}
frame_rate = 30.0

[integrator]
method = "{method}"

[world]
gravity = [0.0, -9.81, 0.0]

[[bodies]]
type = "cloth"
name = "cloth"
columns = 6
rows = 6
size = [1.0, 1.0]
plane = "horizontal"
offset = [-0.5, 0.5, -0.5]
mass = 0.2
stretch = {{ stiffness = 1e5 }}
pins = ["top-left", "top-right"]
self_collision = false  # explicit methods refuse a cloth that collides with itself

[[obstacles]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 0.3
"#
    );
    std::fs::write(&path, text).unwrap();
    path
}

fn read_summary(dir: &Path) -> Summary {
    let text = std::fs::read_to_string(dir.join(SUMMARY_FILE)).unwrap();
    serde_json::from_str(&text).unwrap()
}

#[test]
fn scenes_lists_the_built_in_scenes() {
    let (code, out, _) = hooke(&["scenes"]);
    assert_eq!(code, ExitCode::SUCCESS);
    for name in [
        "stiff-cloth",
        "oscillator",
        "chain",
        "damped-oscillator",
        "cloth-on-sphere",
        "jelly-cube",
    ] {
        assert!(
            out.lines().any(|line| line.starts_with(name)),
            "{name} in\n{out}"
        );
    }
}

#[test]
fn check_describes_a_shipped_scene() {
    let (code, out, err) = hooke(&["check", &shipped("cloth-on-sphere.toml")]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    assert!(out.contains("scene       cloth-on-sphere"), "{out}");
    assert!(out.contains("particles   900"), "{out}");
    assert!(out.contains("sphere at"), "{out}");
    assert!(out.contains("integrator  backward-euler"), "{out}");
    assert!(out.contains("240 steps"), "{out}");
    assert!(out.trim_end().ends_with(": ok"), "{out}");
}

/// `solver = "auto"` (the default) is described as what it does at the
/// scene's size: the factorization below the trial's particle count, a
/// timed trial from there on.
#[test]
fn check_says_what_the_automatic_solver_does_at_the_scenes_size() {
    let threshold = hooke_implicit::AutoSettings::DEFAULT.trial_particles;
    let dir = tempfile::tempdir().unwrap();
    // cloth-on-sphere has 900 particles and no solver key; a square cloth
    // of `side` columns and rows has side² particles.
    let side = (threshold as f64).sqrt().ceil() as usize;
    assert!(side * side >= threshold && 900 < threshold);
    let path = dir.path().join("large.toml");
    let text = format!(
        "name = \"large\"\n\n[[bodies]]\ntype = \"cloth\"\nname = \"cloth\"\n\
         columns = {side}\nrows = {side}\nsize = [1.0, 1.0]\nmass = 1.0\n\
         stretch = {{ stiffness = 100.0 }}\n"
    );
    std::fs::write(&path, text).unwrap();
    for (scene, expected) in [
        (
            shipped("cloth-on-sphere.toml"),
            format!("auto: sparse Cholesky (below {threshold} particles)"),
        ),
        (
            path.to_str().unwrap().to_owned(),
            "auto: sparse Cholesky, multigrid PCG or block-Jacobi PCG, whichever a timed trial"
                .to_owned(),
        ),
    ] {
        let (code, out, err) = hooke(&["check", &scene]);
        assert_eq!(code, ExitCode::SUCCESS, "{err}");
        assert!(out.contains(&expected), "{out}");
    }
}

/// A scene's own terms are listed by name, on a line that a scene without
/// them does not have.
#[test]
fn check_lists_the_scenes_own_terms() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("windy.toml");
    let text = "name = \"windy\"\n\n[world]\n\
                wind = { velocity = [0.0, 0.0, 2.0], drag = 0.5 }\n\n\
                [[bodies]]\ntype = \"cloth\"\nname = \"cloth\"\n\
                columns = 4\nrows = 4\nsize = [1.0, 1.0]\nmass = 1.0\n\
                stretch = { stiffness = 100.0 }\n";
    std::fs::write(&path, text).unwrap();
    let (code, out, err) = hooke(&["check", path.to_str().unwrap()]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    assert!(out.contains("\nterms       wind\n"), "{out}");
    let (code, out, err) = hooke(&["check", &shipped("cloth-on-sphere.toml")]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    assert!(!out.contains("\nterms "), "{out}");
}

#[test]
fn check_rejects_a_malformed_file_with_its_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, "name = \"bad\"\n\n[simulation]\ndt = -1.0\n").unwrap();
    let (code, out, err) = hooke(&["check", path.to_str().unwrap()]);
    assert_eq!(code, ExitCode::FAILURE);
    assert!(out.is_empty(), "{out}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(err.contains("bad.toml:4: simulation.dt"), "{err}");
}

#[test]
fn check_of_a_missing_file_fails_with_a_message() {
    let (code, _, err) = hooke(&["check", "/nonexistent/scene.toml"]);
    assert_eq!(code, ExitCode::FAILURE);
    assert!(err.contains("/nonexistent/scene.toml"), "{err}");
}

#[test]
fn run_writes_frames_and_summary_of_a_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_scene(dir.path(), "backward-euler", 1.0 / 60.0, 0.1);
    let out = dir.path().join("out");
    let (code, stdout, err) = hooke(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    let summary = read_summary(&out);
    assert_eq!(
        (summary.scene.as_str(), summary.steps),
        ("small backward-euler", 6)
    );
    // The report: steps and their cost, where the time went, energy in and
    // out, strain, and which frame the picture shows.
    let line = |start: &str| {
        stdout
            .lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no line {start:?} in {stdout}"))
    };
    let steps = line("backward-euler: 6 steps to t = 0.100 s, ");
    assert!(steps.contains("ms per step (median)"), "{steps}");
    assert!(steps.ends_with("Newton iterations per step"), "{steps}");
    assert!(line("wall ").contains(" s: simulation "), "{stdout}");
    let pace = format!(
        "({:.2} s per simulated second, longest step {:.1} ms)",
        summary.simulation_s / summary.time,
        summary.step_ms_max
    );
    assert!(line("wall ").contains(&pace), "{stdout}");
    assert!(line("energy ").contains(" J -> "), "{stdout}");
    assert!(line("energy ").contains("max strain"), "{stdout}");
    let frame = summary.preview_frame.unwrap();
    assert!(
        line("picture: ").ends_with(&format!(
            "preview.png (frame {frame}, t = {:.3} s)",
            summary.preview_time.unwrap()
        )),
        "{stdout}"
    );
    assert!(!stdout.contains("warning:"), "{stdout}");
    assert!(summary.finite && summary.error.is_none());
    assert_eq!(summary.frames, 4);
    for frame in 0..summary.frames {
        let path = out.join(hooke_viz::frame_file_name(frame));
        let mut file = std::fs::File::open(&path).unwrap();
        let ply = Parser::<DefaultElement>::new().read_ply(&mut file).unwrap();
        assert_eq!(ply.payload["vertex"].len(), 36);
        assert_eq!(ply.payload["face"].len(), 50);
    }
    assert!(out.join("animation.gif").exists() && out.join("preview.png").exists());
}

#[test]
fn run_of_a_builtin_without_subcommand_and_without_gif() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("osc");
    let (code, _, err) = hooke(&[
        "--builtin",
        "oscillator",
        "--duration",
        "0.5",
        "--no-gif",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    let summary = read_summary(&out);
    assert_eq!((summary.scene.as_str(), summary.steps), ("oscillator", 50));
    assert!(summary.linear_iterations_mean.is_none());
    assert!(!out.join("animation.gif").exists());
}

#[test]
fn a_run_that_blows_up_fails_with_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_scene(dir.path(), "explicit-euler", 0.05, 10.0);
    let out = dir.path().join("boom");
    let (code, _, err) = hooke(&[scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(code, ExitCode::FAILURE);
    assert!(err.starts_with("error: the run stopped after"), "{err}");
    let summary = read_summary(&out);
    assert!(!summary.finite);
    assert!(summary.error.is_some());
}

#[test]
fn unknown_builtin_and_bad_arguments_fail_without_panicking() {
    let (code, _, err) = hooke(&["run", "--builtin", "no-such-scene"]);
    assert_eq!(code, ExitCode::FAILURE);
    assert!(err.contains("no built-in scene \"no-such-scene\""), "{err}");
    assert!(err.contains("\"stiff-cloth\""), "{err}");

    let (code, _, err) = hooke(&["run", "--no-such-flag"]);
    assert_eq!(code, ExitCode::from(2));
    assert!(err.contains("--no-such-flag"), "{err}");

    let (code, _, err) = hooke(&["run", "a.toml", "--builtin", "oscillator"]);
    assert_eq!(code, ExitCode::from(2), "{err}");

    let dir = tempfile::tempdir().unwrap();
    let (code, _, err) = hooke(&[
        "--builtin",
        "oscillator",
        "--duration=-1",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(code, ExitCode::FAILURE);
    assert!(err.contains("duration"), "{err}");
}
