//! `volume` in scene files: on by default for lattices, tet meshes and
//! layered bodies, off or set per body, its errors naming the body's key
//! and line; and the built-in `soft-cube`, which shows both.

mod common;

use std::path::Path;

use approx::assert_relative_eq;
use hooke_scenes::file::ErrorKind;
use hooke_scenes::{Lattice, Springs, builtin};

use common::{CLOTH, error_at, parse};

/// A 2 × 2 × 2 lattice body table whose line 7 is `extra`.
fn lattice(extra: &str) -> String {
    format!(
        r#"
[[bodies]]
type = "lattice"
cells = [2, 2, 2]
size = [0.2, 0.2, 0.2]
edges = {{ modulus = 30.0 }}
{extra}
"#
    )
}

/// The modulus of the volume elements of the scene `text`, checking that
/// its one body has 48 of them sharing it.
fn modulus(text: &str) -> f64 {
    let scene = parse(text).unwrap_or_else(|e| panic!("{e}"));
    let tets = scene.system.tets();
    assert_eq!(tets.len(), 6 * 8);
    assert!(
        tets.iter()
            .all(|t| t.modulus.to_bits() == tets[0].modulus.to_bits())
    );
    assert_eq!(scene.bodies[0].placement.tet_range(), 0..48);
    tets[0].modulus
}

#[test]
fn volume_is_on_by_default_off_or_a_modulus_per_body() {
    let springs = Lattice::cubes(2, 2, 2)
        .size([0.2; 3])
        .edges(Springs::modulus(30.0))
        .build()
        .unwrap()
        .spring_bulk_modulus();
    assert!(springs > 0.0);
    assert_relative_eq!(modulus(&lattice("")), springs, max_relative = 1e-12);
    assert_relative_eq!(
        modulus(&lattice("volume = true")),
        springs,
        max_relative = 1e-12
    );
    assert_relative_eq!(modulus(&lattice("volume = false")), 0.0);
    assert_relative_eq!(modulus(&lattice("volume = { modulus = 500.0 }")), 500.0);
    assert_relative_eq!(modulus(&lattice("volume = { modulus = 0 }")), 0.0);
}

#[test]
fn tet_meshes_and_layered_bodies_take_volume_too() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    // The layered body's first element is on a whole triangle of its
    // surface, in two of its prism's six cuts: a third of the modulus.
    for (table, elements, share) in [
        (
            "type = \"tet-mesh\"\nmesh = \"meshes/bracket\"\nedges = { modulus = 3000.0 }",
            108,
            1.0,
        ),
        (
            "type = \"layered\"\nmesh = \"meshes/icosphere.obj\"\nthickness = 0.04\nsurface = { stiffness = 3000.0 }",
            12 * 80,
            1.0 / 3.0,
        ),
    ] {
        for (setting, expected) in [("", None), ("volume = { modulus = 2e3 }", Some(2e3))] {
            let text = format!("[[bodies]]\n{table}\n{setting}\n");
            let scene = hooke_scenes::file::parse(&text, &dir.join("test.toml"))
                .unwrap_or_else(|e| panic!("{e}"));
            let tets = scene.system.tets();
            assert_eq!(tets.len(), elements, "{table}");
            match expected {
                Some(kappa) => assert_relative_eq!(tets[0].modulus, share * kappa),
                None => assert!(tets[0].modulus > 0.0, "{table}"),
            }
        }
    }
}

#[test]
fn a_bad_modulus_is_named_with_its_body_key_and_line() {
    for bad in ["-5.0", "nan", "inf", "-inf"] {
        let error = error_at(
            &lattice(&format!("volume = {{ modulus = {bad} }}")),
            7,
            "bodies[0].volume.modulus",
        );
        let message = error.to_string();
        assert!(
            matches!(*error.kind, ErrorKind::Invalid { .. }),
            "{message}"
        );
        assert!(message.contains("(Pa)"), "{message}");
    }
    // The second body's, after a cloth.
    let text = format!(
        "{CLOTH}{}",
        lattice("volume = { modulus = -1.0 }").trim_start()
    );
    error_at(&text, 12, "bodies[1].volume.modulus");
}

#[test]
fn a_malformed_volume_is_named_with_its_key_and_line() {
    let error = error_at(
        &lattice("volume = { modulus = 5.0, damping = 1.0 }"),
        7,
        "bodies[0].volume.damping",
    );
    let message = error.to_string();
    assert!(matches!(*error.kind, ErrorKind::Schema(_)), "{message}");
    assert!(message.contains("unknown field `damping`"), "{message}");
    let message = error_at(&lattice("volume = \"soft\""), 7, "bodies[0].volume").to_string();
    assert!(message.contains("`true`, `false` or a table"), "{message}");
    let message = error_at(&lattice("volume = {}"), 7, "bodies[0].volume.modulus").to_string();
    assert!(message.contains("missing field `modulus`"), "{message}");
}

#[test]
fn volume_on_a_body_without_volume_elements_is_an_error() {
    let rope = "\n[[bodies]]\ntype = \"rope\"\nstart = [0, 0, 0]\nend = [1, 0, 0]\nsegments = 2\n";
    for (body, line) in [(CLOTH, 7), (rope, 7)] {
        for setting in ["volume = false", "volume = { modulus = 10.0 }"] {
            let message =
                error_at(&format!("{body}{setting}\n"), line, "bodies[0].volume").to_string();
            assert!(message.contains("without volume elements"), "{message}");
            assert!(
                message.contains("only `lattice`, `tet-mesh` and `layered`"),
                "{message}"
            );
        }
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let shell = "[[bodies]]\ntype = \"obj\"\nmesh = \"meshes/tube.obj\"\nedges = { stiffness = 10.0 }\nvolume = true\n";
    let error = hooke_scenes::file::parse(shell, &dir.join("test.toml")).unwrap_err();
    assert_eq!(
        (error.line, error.key.as_str()),
        (Some(5), "bodies[0].volume")
    );
}

#[test]
fn soft_cube_drops_the_jelly_cube_softened_with_and_without_volume() {
    let scene = builtin::load("soft-cube").unwrap();
    let jelly = builtin::load("jelly-cube").unwrap();
    let names: Vec<&str> = scene.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["with-volume", "springs-only"]);
    assert_relative_eq!(scene.timing.duration, 3.0);
    assert_relative_eq!(scene.timing.dt, jelly.timing.dt);
    assert_eq!(scene.integrator, jelly.integrator);
    let jelly_springs = jelly.system.springs();
    let springs = scene.system.springs();
    assert_eq!(springs.len(), 2 * jelly_springs.len());
    let initial = scene.system.initial_state();
    for (n, body) in scene.bodies.iter().enumerate() {
        // Jelly-cube's moduli divided by ten, its damping kept.
        for (s, j) in springs[n * jelly_springs.len()..].iter().zip(jelly_springs) {
            assert_relative_eq!(s.stiffness, j.stiffness / 10.0, max_relative = 1e-12);
            assert_relative_eq!(s.damping, j.damping);
        }
        // Dropped from 1.5 m, side by side at x = ∓0.35 m.
        let x = &initial.positions()[body.placement.range()];
        let lowest = x.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        let centre = x.iter().map(|p| p.x).sum::<f64>() / x.len() as f64;
        assert_relative_eq!(lowest, 1.5, epsilon = 1e-12);
        assert_relative_eq!(centre, [-0.35, 0.35][n], epsilon = 1e-12);
        assert_eq!(body.placement.tet_count, 6 * 216);
    }
    // 6³ cells of a = 5 cm: 3·6·7² edges (E = 30 N), 6·6²·7 face
    // diagonals (15 N), 4·6³ body diagonals (10 N), k L² = E L, around
    // V = (0.3 m)³.
    let a: f64 = 0.05;
    let sum = 882.0 * 30.0 * a + 1512.0 * 15.0 * a * 2f64.sqrt() + 864.0 * 10.0 * a * 3f64.sqrt();
    let expected = sum / (9.0 * 0.3f64.powi(3));
    let tets = scene.system.tets();
    let [with, without] = [0, 1].map(|n| &tets[scene.bodies[n].placement.tet_range()]);
    assert!(
        with.iter()
            .all(|t| (t.modulus - expected).abs() < 1e-9 * expected)
    );
    assert!(without.iter().all(|t| t.modulus == 0.0));
}
