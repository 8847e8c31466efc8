//! The runner end to end on small scenes built in code: the files it
//! writes, PLY frames read back by an independent parser, the summary's
//! fields, and a run that blows up ending gracefully.

use std::ops::ControlFlow;
use std::path::Path;

use hooke_cli::{ANIMATION_FILE, PREVIEW_FILE, RunOptions, SUMMARY_FILE, Summary, USD_FILE, run};
use hooke_core::{ObserveFn, Obstacle, Shape, State, StepInfo, System, SystemBuilder, Vec3};
use hooke_scenes::{
    Body, Cloth, Corner, ExplicitMethod, IntegratorSpec, Rope, Scene, SceneBody, Springs, Timing,
};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};
use serde_json::Value;

/// Every field `summary.json` promises.
const REQUIRED: [&str; 13] = [
    "scene",
    "integrator",
    "dt",
    "steps",
    "particles",
    "springs",
    "wall_s",
    "step_ms_median",
    "linear_iterations_mean",
    "energy_initial",
    "energy_final",
    "max_strain",
    "finite",
];

/// An 8×8 cloth pinned at two corners above a sphere, with backward Euler.
fn cloth_on_sphere(duration: f64) -> Scene {
    let cloth = Cloth::grid(8, 8)
        .size(1.0, 1.0)
        .stretch(Springs::per_spring(2e3).damping(0.5))
        .shear(500.0)
        .bend(50.0)
        .pin_corners([Corner::TopLeft, Corner::TopRight])
        .offset([-0.5, 0.4, -0.5])
        .build()
        .unwrap();
    let sphere = Obstacle::new(Shape::Sphere {
        center: Vec3::zeros(),
        radius: 0.3,
    });
    cloth_scene("cloth on sphere", &cloth, sphere.friction(0.3), duration)
}

/// `cloth` above `obstacle` under gravity, with backward Euler at 1/60 s
/// and 30 frames a second.
fn cloth_scene(name: &str, cloth: &Body, obstacle: Obstacle, duration: f64) -> Scene {
    let mut builder = SystemBuilder::new();
    let placement = cloth.add_to(&mut builder);
    builder.gravity([0.0, -9.81, 0.0]);
    builder.obstacle(obstacle);
    Scene {
        name: name.into(),
        system: builder.build().unwrap(),
        bodies: vec![SceneBody {
            name: "cloth".into(),
            placement,
            triangles: placement.triangles(cloth),
            segments: Vec::new(),
        }],
        integrator: IntegratorSpec::backward_euler(),
        timing: Timing {
            duration,
            dt: 1.0 / 60.0,
            frame_rate: 30.0,
        },
    }
}

/// A rope pinned at one end, swinging down under gravity, with an explicit
/// method; it has segments and no triangles.
fn swinging_rope() -> Scene {
    let rope = Rope::between([0.0, 1.0, 0.0], [1.0, 1.0, 0.0], 10)
        .stretch(Springs::per_spring(500.0).damping(0.1))
        .build()
        .unwrap();
    let mut builder = SystemBuilder::new();
    let placement = rope.add_to(&mut builder);
    builder.pin(placement.first);
    builder.gravity([0.0, -9.81, 0.0]);
    builder.obstacle(Obstacle::new(Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    }));
    Scene {
        name: "swinging rope".into(),
        system: builder.build().unwrap(),
        bodies: vec![SceneBody {
            name: "rope".into(),
            placement,
            triangles: Vec::new(),
            segments: rope.segments().to_vec(),
        }],
        integrator: IntegratorSpec::Explicit(ExplicitMethod::VelocityVerlet),
        timing: Timing {
            duration: 0.2,
            dt: 1e-3,
            frame_rate: 50.0,
        },
    }
}

/// Two particles joined by a very stiff spring, stretched, with explicit
/// Euler at a step far beyond its stability limit: no body, so the spring
/// is drawn as an edge.
fn exploding_spring() -> Scene {
    let mut builder = SystemBuilder::new();
    let a = builder.particle(1.0, [0.0, 0.0, 0.0]);
    let b = builder.particle(1.0, [1.5, 0.0, 0.0]);
    builder.spring(a, b, 1e6).rest_length(1.0);
    Scene {
        name: "exploding spring".into(),
        system: builder.build().unwrap(),
        bodies: Vec::new(),
        integrator: IntegratorSpec::Explicit(ExplicitMethod::ExplicitEuler),
        timing: Timing {
            duration: 100.0,
            dt: 0.1,
            frame_rate: 10.0,
        },
    }
}

/// Parses every frame file in `dir`, checking vertex count, finiteness and
/// the face and edge counts; returns how many there were.
fn check_frames(dir: &Path, vertices: usize, faces: usize, edges: usize) -> usize {
    let mut frames: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ply"))
        .collect();
    frames.sort();
    for (index, path) in frames.iter().enumerate() {
        assert_eq!(path, &dir.join(hooke_viz::frame_file_name(index)));
        let mut file = std::fs::File::open(path).unwrap();
        let ply = Parser::<DefaultElement>::new().read_ply(&mut file).unwrap();
        let positions = &ply.payload["vertex"];
        assert_eq!(positions.len(), vertices, "{}", path.display());
        for vertex in positions {
            for name in ["x", "y", "z"] {
                let Property::Float(c) = vertex[name] else {
                    panic!("{name} is not a float");
                };
                assert!(c.is_finite(), "{} {name} = {c}", path.display());
            }
        }
        let count = |element: &str| ply.payload.get(element).map_or(0, Vec::len);
        assert_eq!((count("face"), count("edge")), (faces, edges));
    }
    frames.len()
}

/// Reads `summary.json` as JSON, checks that every required field is there
/// and that the numbers among them are finite, and returns it typed.
fn read_summary(dir: &Path) -> (Value, Summary) {
    let text = std::fs::read_to_string(dir.join(SUMMARY_FILE)).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    for field in REQUIRED {
        let value = json.get(field).unwrap_or_else(|| panic!("{field} missing"));
        if let Some(number) = value.as_f64() {
            assert!(number.is_finite(), "{field} = {number}");
        }
    }
    (json.clone(), serde_json::from_value(json).unwrap())
}

#[test]
fn cloth_on_sphere_writes_frames_pictures_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let scene = cloth_on_sphere(0.2);
    let mut calls = Vec::new();
    let mut progress = ObserveFn(|_: &System, _: &State, step: &StepInfo| {
        calls.push(step.index);
        ControlFlow::Continue(())
    });
    let summary = run(&scene, &RunOptions::new(&out), &mut progress).unwrap();

    // 12 steps of 1/60 s, a frame every 2 steps: frames 0..=6.
    assert_eq!(
        (summary.steps, summary.steps_planned, summary.frames),
        (12, 12, 7)
    );
    assert_eq!(calls.last(), Some(&12));
    assert_eq!(calls.len(), 12);
    assert_eq!(check_frames(&out, 64, 2 * 7 * 7, 0), 7);
    for file in [PREVIEW_FILE, ANIMATION_FILE] {
        assert!(
            std::fs::metadata(out.join(file)).unwrap().len() > 0,
            "{file}"
        );
    }
    let preview = image_size(&out.join(PREVIEW_FILE));
    assert_eq!(preview, (960, 720));

    let (json, read) = read_summary(&out);
    assert_eq!(
        (read.scene, read.steps),
        (summary.scene.clone(), summary.steps)
    );
    assert_eq!(json["scene"], "cloth on sphere");
    assert_eq!(json["integrator"], "backward-euler");
    assert_eq!(json["finite"], true);
    assert!(json["error"].is_null());
    assert!(json["linear_iterations_mean"].is_number());
    assert_eq!(
        (summary.particles, summary.springs),
        (64, scene.system.springs().len())
    );
    assert!(summary.energy_max >= summary.energy_initial);
    assert!(summary.contacts_max > 0, "the cloth reached the sphere");
    assert!(summary.max_strain > 0.0 && summary.max_strain < 0.5);
    assert!(summary.step_ms_median > 0.0 && summary.wall_s > 0.0);
    assert!(summary.newton_iterations_mean.is_some_and(|n| n >= 1.0));
}

#[test]
fn explicit_run_has_no_linear_iterations_and_draws_segments() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rope");
    let summary = run(&swinging_rope(), &RunOptions::new(&out).gif(false), &mut ()).unwrap();
    assert_eq!(summary.steps, 200);
    assert_eq!(summary.frames, 11);
    assert_eq!(check_frames(&out, 11, 0, 10), 11);
    assert!(!out.join(ANIMATION_FILE).exists());
    assert!(out.join(PREVIEW_FILE).exists());
    let (json, _) = read_summary(&out);
    assert!(json["linear_iterations_mean"].is_null());
    assert!(json["newton_iterations_mean"].is_null());
    assert_eq!(json["integrator"], "velocity-verlet");
    assert_eq!(json["finite"], true);
}

#[test]
fn the_usd_animation_samples_every_frame_and_can_be_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rope");
    let summary = run(&swinging_rope(), &RunOptions::new(&out).gif(false), &mut ()).unwrap();
    let text = std::fs::read_to_string(out.join(USD_FILE)).unwrap();
    // 200 steps of 1 ms, a frame every 20: time codes 0..=10 at 50 a second.
    for line in [
        "startTimeCode = 0",
        "endTimeCode = 10",
        "timeCodesPerSecond = 50",
        "upAxis = \"Y\"",
        "def BasisCurves \"rope\"",
        "int[] curveVertexCounts = [11]",
        "def Mesh \"plane\"",
    ] {
        assert!(text.contains(line), "{line}");
    }
    let samples: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.contains("points.timeSamples"))
        .skip(1)
        .take_while(|l| !l.trim().starts_with('}'))
        .collect();
    assert_eq!(samples.len(), summary.frames);
    // The last frame's points are the last PLY frame's, as f32.
    let last = hooke_viz::read_ply(
        &out.join(hooke_viz::frame_file_name(10)),
        &hooke_viz::scene_mesh(&swinging_rope()).unwrap(),
    )
    .unwrap();
    let written: Vec<f32> = samples[10]
        .trim_start_matches(|c| c != '[')
        .trim_matches(['[', ']', ','])
        .split(['(', ')', ','])
        .filter_map(|c| c.trim().parse().ok())
        .collect();
    let frame: Vec<f32> = last
        .iter()
        .flat_map(|p| p.iter().map(|&c| c as f32))
        .collect();
    assert_eq!(written, frame);

    let out = dir.path().join("without");
    run(
        &swinging_rope(),
        &RunOptions::new(&out).gif(false).usd(false),
        &mut (),
    )
    .unwrap();
    assert!(out.join(SUMMARY_FILE).exists() && !out.join(USD_FILE).exists());
}

#[test]
fn a_run_that_blows_up_ends_with_finite_false_and_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("boom");
    let summary = run(&exploding_spring(), &RunOptions::new(&out), &mut ()).unwrap();
    assert!(!summary.finite);
    let error = summary.error.as_deref().expect("an error");
    assert!(error.starts_with("diverged: particle"), "{error}");
    assert!(summary.steps < summary.steps_planned);
    // The last good state is the final frame, and everything was written.
    let frames = check_frames(&out, 2, 0, 1);
    assert_eq!(frames, summary.frames);
    assert!(out.join(PREVIEW_FILE).exists() && out.join(ANIMATION_FILE).exists());
    let text = std::fs::read_to_string(out.join(SUMMARY_FILE)).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["finite"], false);
    for field in REQUIRED {
        assert!(json.get(field).is_some(), "{field} missing");
    }
}

#[test]
fn a_second_run_replaces_the_frames_of_the_first() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("again");
    let options = RunOptions::new(&out).gif(false);
    run(&cloth_on_sphere(0.2), &options, &mut ()).unwrap();
    let summary = run(&cloth_on_sphere(0.1), &options, &mut ()).unwrap();
    assert_eq!(summary.frames, 4);
    assert_eq!(check_frames(&out, 64, 98, 0), 4);
}

#[test]
fn invalid_timing_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = cloth_on_sphere(0.2);
    scene.timing.dt = 0.0;
    let error = run(&scene, &RunOptions::new(dir.path()), &mut ()).unwrap_err();
    assert_eq!(error.to_string(), "timing: dt must be positive and finite");
}

/// Width and height of a PNG file, from its IHDR chunk.
fn image_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

#[test]
fn converged_backward_euler_gains_no_energy_and_warns_of_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let summary = run(
        &cloth_on_sphere(0.5),
        &RunOptions::new(dir.path()).gif(false),
        &mut (),
    )
    .unwrap();
    assert_eq!(summary.warnings, Vec::<String>::new());
    assert_eq!(
        (summary.unconverged_steps, summary.energy_corrections),
        (0, 0)
    );
    assert!(summary.energy_gain <= 1e-9 * summary.energy_initial.abs().max(1.0));
    assert!(summary.substeps >= summary.steps);
    assert!(summary.newton_residual_max.is_some_and(f64::is_finite));
    assert!(
        summary.newton_iterations_max >= summary.newton_iterations_mean.map(|m| m.ceil() as usize)
    );
}

#[test]
fn steps_accepted_unconverged_are_warned_of_and_strict_mode_stops_the_run() {
    let mut scene = cloth_on_sphere(0.2);
    let IntegratorSpec::Implicit(settings) = &mut scene.integrator else {
        unreachable!("the scene is implicit")
    };
    (settings.newton_iterations, settings.max_halvings) = (1, 0);
    let dir = tempfile::tempdir().unwrap();
    let summary = run(&scene, &RunOptions::new(dir.path()).gif(false), &mut ()).unwrap();
    assert!(summary.error.is_none());
    assert_eq!(summary.unconverged_steps, summary.steps);
    let warning = summary
        .warnings
        .iter()
        .find(|w| w.contains("did not converge"))
        .expect("a warning");
    assert!(
        warning.starts_with("12 steps did not converge, the first ending at t = 0.0167 s"),
        "{warning}"
    );
    let (json, _) = read_summary(dir.path());
    assert_eq!(
        json["warnings"].as_array().map(Vec::len),
        Some(summary.warnings.len())
    );

    let IntegratorSpec::Implicit(settings) = &mut scene.integrator else {
        unreachable!("the scene is implicit")
    };
    settings.strict = true;
    let summary = run(&scene, &RunOptions::new(dir.path()).gif(false), &mut ()).unwrap();
    assert_eq!(summary.steps, 0);
    let error = summary.error.expect("strict mode fails the first step");
    assert!(
        error.contains("t = 0") && error.contains("residual"),
        "{error}"
    );
}

#[test]
fn explicit_euler_creating_energy_is_warned_of() {
    let mut scene = swinging_rope();
    scene.integrator = IntegratorSpec::Explicit(ExplicitMethod::ExplicitEuler);
    let dir = tempfile::tempdir().unwrap();
    let summary = run(&scene, &RunOptions::new(dir.path()).gif(false), &mut ()).unwrap();
    assert!(summary.energy_gain > 0.0);
    assert!(
        summary
            .warnings
            .iter()
            .any(|w| w.starts_with("energy rose")),
        "{:?}",
        summary.warnings
    );
    assert_eq!(
        (summary.newton_iterations_max, summary.energy_excess_max),
        (None, None)
    );
}

/// A free 8×8 cloth dropped off-centre onto a frictionless sphere, with no
/// floor: it lands, slides off and falls away.
fn cloth_sliding_off() -> Scene {
    let cloth = Cloth::grid(8, 8)
        .size(0.6, 0.6)
        .stretch(Springs::per_spring(2e3).damping(0.5))
        .shear(500.0)
        .bend(50.0)
        .offset([-0.05, 0.35, -0.3])
        .build()
        .unwrap();
    let sphere = Obstacle::new(Shape::Sphere {
        center: Vec3::zeros(),
        radius: 0.3,
    });
    cloth_scene("cloth sliding off", &cloth, sphere, 1.5)
}

/// The positions of frame `index` in `dir`, read by the independent parser.
fn frame_positions(dir: &Path, index: usize) -> Vec<Vec3> {
    let mut file = std::fs::File::open(dir.join(hooke_viz::frame_file_name(index))).unwrap();
    let ply = Parser::<DefaultElement>::new().read_ply(&mut file).unwrap();
    let float = |p: &Property| match p {
        Property::Float(c) => f64::from(*c),
        other => panic!("not a float: {other:?}"),
    };
    ply.payload["vertex"]
        .iter()
        .map(|v| Vec3::new(float(&v["x"]), float(&v["y"]), float(&v["z"])))
        .collect()
}

#[test]
fn the_preview_shows_the_cloth_on_the_sphere_not_after_it_slid_off() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("slide");
    let summary = run(
        &cloth_sliding_off(),
        &RunOptions::new(&out).gif(false),
        &mut (),
    )
    .unwrap();
    let preview = summary.preview_frame.unwrap();
    // Particles within 5 mm of the sphere's surface, from the frame files.
    let touching = |index| {
        frame_positions(&out, index)
            .iter()
            .filter(|x| x.norm() - 0.3 < 5e-3)
            .count()
    };
    let last = summary.frames - 1;
    assert_eq!(touching(last), 0, "the cloth has slid off by the end");
    assert!(preview < last);
    assert!(
        touching(preview) > 0,
        "frame {preview} shows the cloth on the sphere"
    );

    // The picture is that frame, seen by a camera framing it and the sphere.
    let positions = frame_positions(&out, preview);
    let sphere = [Shape::Sphere {
        center: Vec3::zeros(),
        radius: 0.3,
    }];
    let bounds = hooke_viz::Bounds::of_scene(&positions, &sphere).unwrap();
    let camera = hooke_viz::Camera::new(&bounds, 960, 720, &hooke_viz::View::default()).unwrap();
    let mesh = hooke_viz::Mesh::new(64, placement_triangles(), Vec::new()).unwrap();
    let expected = hooke_viz::Renderer::new(camera)
        .render(&mesh, &positions, &sphere)
        .unwrap();
    let written = hooke_viz::Pixmap::load_png(out.join(PREVIEW_FILE)).unwrap();
    assert!(
        written.data() == expected.data(),
        "preview is frame {preview}"
    );
}

/// The triangles of the 8×8 cloth of [`cloth_sliding_off`].
fn placement_triangles() -> Vec<[u32; 3]> {
    let scene = cloth_sliding_off();
    scene.bodies[0]
        .triangles
        .iter()
        .map(|t| t.map(|v| u32::try_from(v).unwrap()))
        .collect()
}

#[test]
fn the_output_time_is_measured_apart_from_the_simulation() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("times");
    let summary = run(&cloth_on_sphere(0.2), &RunOptions::new(&out), &mut ()).unwrap();
    assert!(summary.simulation_s > 0.0 && summary.output_s > 0.0);
    assert!(summary.simulation_s + summary.output_s <= summary.wall_s);
}

#[test]
fn the_default_scene_lands_and_drapes_without_gaining_energy_or_overstretching() {
    // Its first second and a half: the fall, the landing and the drape
    // (the whole run is the main job, `cargo run --release`).
    let mut scene = hooke_scenes::builtin::load(hooke_cli::DEFAULT_SCENE).unwrap();
    scene.timing.duration = 1.5;
    let dir = tempfile::tempdir().unwrap();
    let summary = run(&scene, &RunOptions::new(dir.path()).gif(false), &mut ()).unwrap();
    assert_eq!(summary.steps, 90);
    assert!(summary.warnings.is_empty(), "{:?}", summary.warnings);
    assert!(
        summary.contacts_max > 100,
        "it lands on the sphere and the floor"
    );
    assert!(summary.energy_gain <= 0.0, "{}", summary.energy_gain);
    assert!(summary.energy_max <= summary.energy_initial);
    assert!(summary.energy_final < 0.6 * summary.energy_initial);
    assert!(summary.max_strain <= 0.25, "{}", summary.max_strain);
}
