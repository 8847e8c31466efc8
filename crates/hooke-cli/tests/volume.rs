//! Volume elements in a run's report: `summary.json`'s most inverted
//! elements and smallest volume ratio, read back; `null` without volume
//! elements; the `volume:` line of `hooke run` and the elements `hooke
//! check` lists per body.

mod common;

use std::path::Path;
use std::process::ExitCode;

use hooke_cli::{RunOptions, SUMMARY_FILE, Summary, run};
use hooke_core::SystemBuilder;
use hooke_scenes::{ExplicitMethod, IntegratorSpec, Scene, Timing};
use serde_json::Value;

use common::hooke;

/// A scene of one volume element, modulus 0 (it measures only): a unit
/// corner tet whose base is pinned in the plane `y = 0` and whose apex
/// starts at `y = 1` moving down at 1 m/s, without gravity, so that at
/// time `t` its volume ratio is `J = 1 − t`.
fn apex_through_the_base(duration: f64) -> Scene {
    let mut b = SystemBuilder::new();
    let base = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]].map(|x| b.particle(1.0, x));
    let apex = b.particle_with_velocity(1.0, [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    for p in base {
        b.pin(p);
    }
    b.tet([base[0], base[1], base[2], apex], 0.0);
    Scene {
        name: "apex through the base".into(),
        system: b.build().unwrap(),
        bodies: Vec::new(),
        integrator: IntegratorSpec::Explicit(ExplicitMethod::SymplecticEuler),
        timing: Timing {
            duration,
            dt: 0.01,
            frame_rate: 10.0,
        },
    }
}

/// `summary.json` in `dir` as JSON and read back as a [`Summary`].
fn read_summary(dir: &Path) -> (Value, Summary) {
    let text = std::fs::read_to_string(dir.join(SUMMARY_FILE)).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    (json.clone(), serde_json::from_value(json).unwrap())
}

#[test]
fn the_summary_gives_the_most_inverted_elements_and_the_smallest_ratio() {
    let dir = tempfile::tempdir().unwrap();
    for (duration, inverted, smallest) in [(0.5, 0, 0.5), (2.5, 1, -1.5)] {
        let out = dir.path().join(format!("{duration}"));
        let scene = apex_through_the_base(duration);
        let summary = run(&scene, &RunOptions::new(&out).gif(false), &mut ()).unwrap();
        assert_eq!(summary.inverted_elements_max, Some(inverted));
        let ratio = summary.volume_ratio_min.unwrap();
        assert!(
            (ratio - smallest).abs() < 1e-9,
            "J = {ratio} at {duration} s"
        );
        let (json, read) = read_summary(&out);
        assert_eq!(json["inverted_elements_max"], inverted);
        assert!(json["volume_ratio_min"].is_number());
        assert_eq!(read, summary);
    }
}

#[test]
fn a_system_without_volume_elements_reports_null() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (code, stdout, err) = hooke(&[
        "run",
        "--builtin",
        "oscillator",
        "--duration",
        "0.1",
        "--out",
        out.to_str().unwrap(),
        "--no-gif",
        "--quiet",
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    let (json, read) = read_summary(&out);
    assert!(json["inverted_elements_max"].is_null(), "{json}");
    assert!(json["volume_ratio_min"].is_null(), "{json}");
    assert_eq!(
        (read.inverted_elements_max, read.volume_ratio_min),
        (None, None)
    );
    assert!(!stdout.contains("volume:"), "{stdout}");
}

/// A 2 × 2 × 2 lattice cube resting on a floor, its volume energy `volume`.
fn resting_cube(dir: &Path, volume: &str) -> String {
    let path = dir.join("cube.toml");
    let text = format!(
        r#"name = "resting cube"

[simulation]
duration = 0.1
dt = 0.025
frame_rate = 40.0

[[bodies]]
type = "lattice"
name = "cube"
cells = [2, 2, 2]
size = [0.2, 0.2, 0.2]
origin = [-0.1, 0.001, -0.1]
edges = {{ modulus = 300.0, damping = 0.5 }}
face_diagonals = {{ modulus = 150.0 }}
{volume}

[[obstacles]]
shape = "plane"
"#
    );
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn run_prints_the_volume_line_and_check_lists_the_elements() {
    let dir = tempfile::tempdir().unwrap();
    let scene = resting_cube(dir.path(), "volume = { modulus = 1234.5 }");
    let (code, stdout, err) = hooke(&["check", &scene]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    assert!(
        stdout.contains(
            "cube: 27 particles (0..27), 48 triangles, 48 volume elements (modulus 1.2345e3 Pa)"
        ),
        "{stdout}"
    );
    let out = dir.path().join("out");
    let (code, stdout, err) = hooke(&[
        "run",
        &scene,
        "--out",
        out.to_str().unwrap(),
        "--no-gif",
        "--quiet",
    ]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    let (_, summary) = read_summary(&out);
    assert_eq!(summary.inverted_elements_max, Some(0));
    let ratio = summary.volume_ratio_min.unwrap();
    assert!(ratio > 0.5 && ratio <= 1.0 + 1e-9, "{ratio}");
    let line = stdout
        .lines()
        .find(|l| l.starts_with("volume: "))
        .unwrap_or_else(|| panic!("no volume line in {stdout}"));
    assert_eq!(
        line,
        format!("volume: at most 0 elements inverted at once, smallest volume ratio {ratio:.3}")
    );

    let off = resting_cube(dir.path(), "volume = false");
    let (code, stdout, err) = hooke(&["check", &off]);
    assert_eq!(code, ExitCode::SUCCESS, "{err}");
    assert!(
        stdout
            .contains("48 volume elements (modulus 0: volume energy off, inversion measured only)"),
        "{stdout}"
    );
}

#[test]
fn a_preview_time_draws_the_frame_nearest_it() {
    let dir = tempfile::tempdir().unwrap();
    let scene = apex_through_the_base(1.0);
    let out = dir.path().join("out");
    let options = RunOptions::new(&out).gif(false).preview_time(Some(0.42));
    let summary = run(&scene, &options, &mut ()).unwrap();
    assert_eq!(summary.preview_frame, Some(4));
    assert!((summary.preview_time.unwrap() - 0.4).abs() < 1e-9);
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        let options = RunOptions::new(&out).preview_time(Some(bad));
        assert!(run(&scene, &options, &mut ()).is_err(), "{bad}");
    }
}
