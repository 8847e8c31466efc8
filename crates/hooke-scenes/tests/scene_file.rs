//! The TOML scene format: every shipped and built-in scene loads and
//! builds, files say what the scene holds, and each kind of malformed file
//! is an error naming the file, the line and the key.

mod common;

use std::path::{Path, PathBuf};

use hooke_core::{Path as Motion, Shape, Vec3};
use hooke_explicit::DormandPrince;
use hooke_implicit::{
    ErrorControl, FastMassSpring, Implicit, ImplicitSettings, LinearSolver, Minimizer, PcgSettings,
    Scheme,
};
use hooke_scenes::file::{self, ErrorKind};
use hooke_scenes::{IntegratorSpec, builtin};

use common::{CLOTH, error_at, parse};

/// The shipped scene files.
fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

#[test]
fn every_shipped_scene_loads_and_builds() {
    let mut count = 0;
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = file::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(scene.system.particle_count() > 0, "{}", path.display());
            scene.integrator.build().unwrap();
            count += 1;
        }
    }
    assert_eq!(count, builtin::NAMES.len());
}

#[test]
fn every_builtin_loads_like_its_file() {
    for (name, description) in builtin::NAMES {
        assert!(!description.is_empty());
        let scene = builtin::load(name).unwrap_or_else(|e| panic!("{e}"));
        let from_file = file::load(&scenes_dir().join(format!("{name}.toml"))).unwrap();
        assert_eq!(scene.name, *name);
        assert_eq!(
            scene.system.particle_count(),
            from_file.system.particle_count()
        );
        assert_eq!(
            scene.system.springs().len(),
            from_file.system.springs().len()
        );
        assert_eq!(scene.bodies, from_file.bodies);
    }
}

/// `docs/scene-format.md` shows shipped scenes under headings naming their
/// files (`` ### …: `scenes/NAME.toml` ``): each shown text is the file's.
#[test]
fn the_format_documents_shipped_scenes_as_they_are() {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let docs = std::fs::read_to_string(docs).unwrap();
    let mut shown = 0;
    for section in docs.split("\n### ").skip(1) {
        let heading = section.lines().next().unwrap();
        let Some(name) = heading
            .strip_suffix(".toml`")
            .and_then(|h| h.rsplit_once("`scenes/"))
            .map(|(_, name)| name)
        else {
            continue;
        };
        let body = section
            .split_once("```toml\n")
            .and_then(|(_, rest)| rest.split_once("```"))
            .map(|(body, _)| body)
            .unwrap_or_else(|| panic!("no TOML block under {heading}"));
        let file = std::fs::read_to_string(scenes_dir().join(format!("{name}.toml"))).unwrap();
        assert!(
            body == file,
            "{heading}: the docs show another text than the file"
        );
        shown += 1;
    }
    assert!(shown >= 10, "{shown} scenes shown");
}

/// Where `docs/scene-format.md` prints a default beside the constant that
/// holds it (`` `ImplicitSettings::NEWTON_TOLERANCE` (`1e-4`) ``), the printed value
/// is the constant's.
#[test]
fn the_format_prints_the_defaults_the_constants_hold() {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let docs = std::fs::read_to_string(docs).unwrap();
    let constants: [(&str, f64); 10] = [
        ("Minimizer::HISTORY", Minimizer::HISTORY as f64),
        (
            "ImplicitSettings::NEWTON_ITERATIONS",
            ImplicitSettings::NEWTON_ITERATIONS as f64,
        ),
        (
            "ImplicitSettings::NEWTON_TOLERANCE",
            ImplicitSettings::NEWTON_TOLERANCE,
        ),
        (
            "ImplicitSettings::MAX_HALVINGS",
            f64::from(ImplicitSettings::MAX_HALVINGS),
        ),
        ("Implicit::MAX_CONDITION", Implicit::MAX_CONDITION),
        ("DormandPrince::RTOL", DormandPrince::RTOL),
        ("DormandPrince::ATOL", DormandPrince::ATOL),
        ("ErrorControl::RELATIVE", ErrorControl::RELATIVE),
        ("ErrorControl::ABSOLUTE", ErrorControl::ABSOLUTE),
        (
            "FastMassSpring::ITERATIONS",
            FastMassSpring::ITERATIONS as f64,
        ),
    ];
    for (name, value) in constants {
        let quoted = format!("`{name}`");
        let mut printed = docs.match_indices(&quoted).peekable();
        assert!(printed.peek().is_some(), "{name} is not in the format");
        for (at, _) in printed {
            let after = &docs[at + name.len() + 2..];
            let Some(shown) = after
                .trim_start_matches([',', ' ', '('])
                .strip_prefix('`')
                .and_then(|rest| rest.split(['`', ' ']).next())
            else {
                continue;
            };
            let shown: f64 = shown
                .parse()
                .unwrap_or_else(|_| panic!("{name}: `{shown}` is not a number"));
            assert_eq!(
                shown.to_bits(),
                value.to_bits(),
                "the format prints {name} as {shown}, it holds {value}"
            );
        }
    }
}

#[test]
fn an_unknown_builtin_lists_the_names() {
    let message = builtin::load("nope").unwrap_err().to_string();
    assert!(message.contains("\"nope\""), "{message}");
    for (name, _) in builtin::NAMES {
        assert!(message.contains(name), "{message}");
    }
}

#[test]
fn the_default_scene_drops_a_free_40_by_40_cloth_onto_a_sphere_on_a_floor() {
    let (name, _) = builtin::NAMES[0];
    let scene = builtin::load(name).unwrap();
    assert_eq!(name, "stiff-cloth");
    assert_eq!(scene.system.particle_count(), 1600);
    assert_eq!(
        scene.bodies[0].triangles.len(),
        2 * 39 * 39,
        "a 40 × 40 grid"
    );
    assert_eq!(scene.system.pinned().count(), 0);
    let shapes: Vec<_> = scene.system.obstacles().iter().map(|o| o.shape).collect();
    let &[
        Shape::Sphere { center, radius },
        Shape::Plane { point, normal },
    ] = &shapes[..]
    else {
        panic!("{shapes:?}");
    };
    // The sphere rests on the floor, and the cloth starts above it.
    assert!((center.y - radius - point.y).abs() < 1e-12 && normal == Vec3::y());
    let positions = scene.system.initial_positions();
    assert!(positions.iter().all(|x| x.y > center.y + radius));
    assert!((3.0..=5.0).contains(&scene.timing.duration));
    assert!((scene.timing.dt - 1.0 / 60.0).abs() < 1e-15);
    // Backward Euler at the library's defaults: no solver or tolerance key.
    assert_eq!(
        scene.integrator,
        IntegratorSpec::implicit(Scheme::BackwardEuler)
    );
}

#[test]
fn every_explicit_method_needs_steps_100_times_below_the_default_scenes() {
    // The Rayleigh quotient of any displacement u bounds the highest
    // frequency from below: ω_max² ≥ uᵀKu / uᵀMu, with K = Σ k d dᵀ per
    // spring at rest (the cloth starts unstretched). Take neighbouring
    // columns moving opposite ways along x.
    let scene = builtin::load("stiff-cloth").unwrap();
    let system = &scene.system;
    let x = system.initial_positions();
    let u = |i: usize| {
        if i % 40 % 2 == 0 {
            Vec3::x()
        } else {
            -Vec3::x()
        }
    };
    let stiffness: f64 = system
        .springs()
        .iter()
        .map(|s| {
            let d = (x[s.i] - x[s.j]).normalize();
            assert!((s.rest_length - (x[s.i] - x[s.j]).norm()).abs() < 1e-12);
            s.stiffness * (u(s.i) - u(s.j)).dot(&d).powi(2)
        })
        .sum();
    let inertia: f64 = system.masses().iter().sum();
    let omega_max = (stiffness / inertia).sqrt();
    // RK4, the most tolerant explicit method, is stable up to h ω = 2√2.
    let rk4_limit = 2.0 * 2f64.sqrt() / omega_max;
    assert!(
        rk4_limit <= scene.timing.dt / 100.0,
        "ω_max ≥ {omega_max:.3e} rad/s: RK4 stable up to {rk4_limit:.3e} s"
    );
}

#[test]
fn a_cloth_file_says_what_the_scene_holds() {
    let scene = parse(
        r#"
        name = "sheet"
        [simulation]
        duration = 2.0
        dt = 0.005
        frame_rate = 25
        [integrator]
        method = "bdf2"
        solver = "pcg"
        tolerance = 1e-7
        max_iterations = 300
        newton_iterations = 4
        [world]
        gravity = [0.0, -3.0, 0.0]
        [[bodies]]
        type = "cloth"
        columns = 40
        rows = 40
        stretch = { stiffness = 5e3 }
        pins = ["top-left", 1599]
        [[bodies.moving_pins]]
        particle = "top-right"
        velocity = [0.0, 0.5, 0.0]
        [[obstacles]]
        shape = "sphere"
        center = [0.5, -0.5, 0.5]
        radius = 0.25
        friction = 0.4
        restitution = 0.1
        [[obstacles]]
        shape = "box"
        center = [0.0, -2.0, 0.0]
        half_extents = [1.0, 0.5, 1.0]
        keyframes = [[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 1.0, 0.0]]
        "#,
    )
    .unwrap();
    assert_eq!(scene.name, "sheet");
    assert_eq!(scene.system.particle_count(), 1600);
    assert_eq!(scene.bodies[0].triangles.len(), 2 * 39 * 39);
    assert_eq!(
        (scene.timing.steps(), scene.timing.steps_per_frame()),
        (400, 8)
    );
    assert_eq!(
        scene.integrator,
        IntegratorSpec::Implicit(ImplicitSettings {
            scheme: Scheme::Bdf2,
            solver: LinearSolver::Pcg(PcgSettings::new(1e-7, 300).unwrap()),
            newton_iterations: 4,
            ..ImplicitSettings::default()
        })
    );
    let pinned: Vec<usize> = scene.system.pinned().collect();
    assert_eq!(pinned, [0, 39, 1599]);
    assert_eq!(
        scene.system.initial_velocities()[39],
        Vec3::new(0.0, 0.5, 0.0)
    );
    let obstacles = scene.system.obstacles();
    assert_eq!(obstacles.len(), 2);
    assert!(
        matches!(obstacles[0].shape, Shape::Sphere { radius, .. } if (radius - 0.25).abs() < 1e-15)
    );
    assert_eq!(
        (obstacles[0].friction, obstacles[0].restitution),
        (0.4, 0.1)
    );
    assert!(matches!(&obstacles[1].path, Motion::Keyframes(k) if k.len() == 2));
}

#[test]
fn an_unknown_key_is_named_with_its_line() {
    let error = error_at(&format!("{CLOTH}colums = 3\n"), 7, "bodies[0].colums");
    assert!(matches!(*error.kind, ErrorKind::Schema(_)));
    assert!(error.to_string().contains("unknown field `colums`"));
    error_at(
        "[simulation]\nduration = 1.0\nsteps = 3\n",
        3,
        "simulation.steps",
    );
}

#[test]
fn a_wrong_type_is_named_with_its_line() {
    let text = CLOTH.replace("stiffness = 100.0", "stiffness = \"stiff\"");
    let error = error_at(&text, 6, "bodies[0].stretch.stiffness");
    assert!(error.to_string().contains("expected f64"), "{error}");
    error_at(
        &format!("[world]\ngravity = [0.0, -9.81]\n{CLOTH}"),
        2,
        "world.gravity",
    );
}

#[test]
fn a_missing_key_is_named_with_its_table_line() {
    let text = CLOTH.replace("rows = 3\n", "");
    let error = error_at(&text, 2, "bodies[0].rows");
    assert!(
        error.to_string().contains("missing field `rows`"),
        "{error}"
    );
    error_at("[[bodies]]\ncolumns = 3\n", 1, "bodies[0].type");
}

#[test]
fn invalid_values_are_named_with_their_lines() {
    let text = CLOTH.replace("stiffness = 100.0", "stiffness = -5.0");
    let error = error_at(&text, 6, "bodies[0].stretch.stiffness");
    assert!(error.to_string().contains("got -5"), "{error}");
    error_at(
        &format!("[simulation]\ndt = 0.0\n{CLOTH}"),
        2,
        "simulation.dt",
    );
    error_at(
        &CLOTH.replace("columns = 4", "columns = 0"),
        4,
        "bodies[0].columns",
    );
    error_at(
        &format!("{CLOTH}[[obstacles]]\nshape = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\n"),
        10,
        "obstacles[0].radius",
    );
    error_at(
        &format!("{CLOTH}[[obstacles]]\nshape = \"plane\"\nnormal = [0, 0, 0]\n"),
        9,
        "obstacles[0].normal",
    );
    error_at(
        &format!(
            "{CLOTH}[[bodies.moving_pins]]\nparticle = 0\nkeyframes = [[1, 0, 0, 0], [0, 1, 1, 1]]\n"
        ),
        9,
        "bodies[0].moving_pins[0].keyframes[1]",
    );
    error_at(
        &format!("[integrator]\nmethod = \"pcg-euler\"\nnewton_iterations = 0\n{CLOTH}"),
        2,
        "integrator.method",
    );
    error_at(
        &format!("[integrator]\nnewton_iterations = 0\n{CLOTH}"),
        2,
        "integrator.newton_iterations",
    );
    error_at(
        &format!("[integrator]\nsolver = \"pcg\"\ntolerance = 2.0\n{CLOTH}"),
        3,
        "integrator.tolerance",
    );
    error_at(
        &format!("[integrator]\nmethod = \"rk4\"\nrtol = 1e-3\n{CLOTH}"),
        3,
        "integrator.rtol",
    );
    error_at(
        "[[bodies]]\ntype = \"rope\"\nstart = [0, 0, 0]\nend = [1, 0, 0]\nsegments = 2\nrest_length_fraction = -0.5\n",
        6,
        "bodies[0].rest_length_fraction",
    );
}

#[test]
fn the_oscillator_scenes_have_linear_springs_at_one_radian_per_second() {
    // A zero-length spring pulls the bob towards the anchor with −k x,
    // whatever the bob's position: check the force against that at a point
    // off the axis, and the frequency √(k/m) = 1 rad/s.
    for name in ["oscillator", "damped-oscillator"] {
        let scene = builtin::load(name).unwrap();
        let system = &scene.system;
        let spring = system.springs()[0];
        assert!(spring.rest_length.abs() < f64::MIN_POSITIVE, "{name}");
        let x = Vec3::new(0.3, -1.7, 0.4);
        let force = spring.elastic_force(x, Vec3::zeros());
        assert!((force + x * spring.stiffness).norm() < 1e-15, "{name}");
        let omega = (spring.stiffness / system.masses()[1]).sqrt();
        assert!((omega - 1.0).abs() < 1e-15, "{name}: ω = {omega}");
    }
}

#[test]
fn bad_enum_names_list_the_choices() {
    let error = error_at(
        &CLOTH.replace("\"cloth\"", "\"sheet\""),
        3,
        "bodies[0].type",
    );
    assert!(error.to_string().contains("\"tet-mesh\""), "{error}");
    let error = error_at(
        &format!("{CLOTH}pins = [\"top-middle\"]\n"),
        7,
        "bodies[0].pins[0]",
    );
    assert!(error.to_string().contains("\"bottom-right\""), "{error}");
    let error = error_at(
        &format!("{CLOTH}plane = \"diagonal\"\n"),
        7,
        "bodies[0].plane",
    );
    assert!(error.to_string().contains("\"vertical\""), "{error}");
}

#[test]
fn a_pin_out_of_range_is_named_with_its_line() {
    let error = error_at(&format!("{CLOTH}pins = [0, 12]\n"), 7, "bodies[0].pins[1]");
    assert!(error.to_string().contains("below 12"), "{error}");
    error_at(
        "[[bodies]]\ntype = \"rope\"\nstart = [0, 0, 0]\nend = [1, 0, 0]\nsegments = 2\npins = [\"end\", \"middle\"]\n",
        6,
        "bodies[0].pins[1]",
    );
}

#[test]
fn a_missing_mesh_file_is_named_with_its_line() {
    let text = "[[bodies]]\ntype = \"obj\"\n\nmesh = \"meshes/none.obj\"\n";
    let error = file::parse(text, &scenes_dir().join("broken.toml")).unwrap_err();
    assert_eq!(
        (error.line, error.key.as_str()),
        (Some(4), "bodies[0].mesh")
    );
    let message = error.to_string();
    assert!(
        message.contains("broken.toml:4: bodies[0].mesh: "),
        "{message}"
    );
    assert!(message.contains("none.obj"), "{message}");
    let text = "[[bodies]]\ntype = \"tet-mesh\"\nmesh = \"meshes/none\"\n";
    let error = file::parse(text, &scenes_dir().join("broken.toml")).unwrap_err();
    assert_eq!(
        (error.line, error.key.as_str()),
        (Some(3), "bodies[0].mesh")
    );
}

#[test]
fn mesh_paths_are_relative_to_the_scene_file() {
    let text = "[[bodies]]\ntype = \"tet-mesh\"\nmesh = \"meshes/bracket.node\"\nedges = { modulus = 10 }\n";
    let scene = file::parse(text, &scenes_dir().join("any.toml")).unwrap();
    assert_eq!(scene.system.particle_count(), 60);
    assert!(file::parse(text, Path::new("elsewhere/any.toml")).is_err());
}

#[test]
fn syntax_errors_and_unreadable_files_name_the_file() {
    let error = parse("[simulation\n").unwrap_err();
    assert!(matches!(*error.kind, ErrorKind::Syntax(_)));
    assert_eq!(error.line, Some(1));
    let missing = scenes_dir().join("no-such-scene.toml");
    let error = file::load(&missing).unwrap_err();
    assert!(matches!(*error.kind, ErrorKind::Io(_)));
    assert!(error.to_string().contains("no-such-scene.toml"));
}

#[test]
fn a_scene_without_bodies_is_an_error() {
    let error = parse("[simulation]\nduration = 1.0\n").unwrap_err();
    assert_eq!(error.key, "bodies");
}

#[test]
fn the_mesh_scenes_pin_the_vertices_their_comments_name() {
    let tube = builtin::load("obj-tube").unwrap();
    let positions = tube.system.initial_positions();
    let pinned: Vec<usize> = tube.system.pinned().collect();
    assert_eq!(pinned.len(), 12);
    assert!(pinned.iter().all(|&p| (positions[p].y - 1.0).abs() < 1e-9));
    let bracket = builtin::load("tet-bracket").unwrap();
    let positions = bracket.system.initial_positions();
    let pinned: Vec<usize> = bracket.system.pinned().collect();
    assert_eq!(pinned.len(), 6);
    assert!(pinned.iter().all(|&p| (positions[p].y - 0.7).abs() < 1e-9));
    let ball = builtin::load("layered-ball").unwrap();
    assert_eq!(ball.system.particle_count(), 2 * 42);
}

#[test]
fn the_default_scene_steps_stably_at_its_own_dt() {
    let scene = builtin::load("stiff-cloth").unwrap();
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = scene.system.initial_state();
    for _ in 0..10 {
        integrator
            .step(&scene.system, &mut state, scene.timing.dt)
            .unwrap();
    }
    let top = scene.system.initial_positions()[0].y;
    assert!(
        state
            .positions()
            .iter()
            .all(|x| x.iter().all(|c| c.is_finite()))
    );
    // After 10 steps a corner has fallen, but by no more than
    // backward Euler's free fall, h² g (1 + 2 + … + 10) = 55 h² g.
    let fall = top - state.positions()[1599].y;
    let free_fall = 55.0 * scene.timing.dt.powi(2) * 9.81;
    assert!(fall > 0.01 && fall < free_fall, "{fall} vs {free_fall}");
}

#[test]
fn counts_beyond_the_particle_limit_are_errors() {
    let error = error_at(
        &CLOTH.replace("rows = 3", "rows = 4000000000"),
        5,
        "bodies[0].rows",
    );
    assert!(
        error.to_string().contains("at most 1000000 particles"),
        "{error}"
    );
    error_at(
        "[[bodies]]\ntype = \"lattice\"\ncells = [18446744073709551615, 2, 2]\n",
        3,
        "bodies[0].cells",
    );
    error_at(
        "[[bodies]]\ntype = \"rope\"\nstart = [0, 0, 0]\nend = [1, 0, 0]\nsegments = 18446744073709551615\n",
        5,
        "bodies[0].segments",
    );
}
