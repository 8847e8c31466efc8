//! Collision between surfaces in bodies and scene files: which bodies
//! collide and how by default, the keys `self_collision`, `thickness` (and
//! a layered body's `contact_thickness`) and `[world] contact_distance`,
//! their errors, and the built-in scenes made for them.

mod common;

use std::path::Path;

use approx::assert_relative_eq;
use hooke_core::{Shape, Vec3};
use hooke_scenes::file::ErrorKind;
use hooke_scenes::{
    Cloth, Lattice, Layered, Rope, Shell, Solid, TetMesh, TetSplit, TriangleMesh, builtin,
};

use common::{CLOTH, error_at, parse};

/// A rope body table.
const ROPE: &str = r#"
[[bodies]]
type = "rope"
start = [0, 1, 0]
end = [1, 1, 0]
segments = 4
stretch = { stiffness = 100.0 }
"#;

/// A 2 × 2 × 2 lattice body table.
const LATTICE: &str = r#"
[[bodies]]
type = "lattice"
cells = [2, 2, 2]
edges = { stiffness = 100.0 }
"#;

#[test]
fn cloth_and_shells_collide_with_themselves_and_volumes_do_not() {
    let square = TriangleMesh::new(
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        [[0, 1, 2], [0, 2, 3]],
    );
    let tet = TetMesh::new(
        [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [[0, 1, 2, 3]],
    );
    let bodies = [
        ("cloth", Cloth::grid(3, 3).build().unwrap(), true),
        ("shell", Shell::new(square.clone()).build().unwrap(), true),
        ("lattice", Lattice::cubes(1, 1, 1).build().unwrap(), false),
        (
            "tet lattice",
            Lattice::tets(1, 1, 1, TetSplit::Five).build().unwrap(),
            false,
        ),
        ("solid", Solid::new(tet).build().unwrap(), false),
        ("layered", Layered::new(square, 0.1).build().unwrap(), false),
    ];
    for (name, body, self_collision) in bodies {
        let c = body.collision();
        assert!(c.surface, "{name}");
        assert_eq!(c.self_collision, self_collision, "{name}");
        assert_relative_eq!(c.thickness, 0.0);
        let system = body.system([0.0; 3]).unwrap();
        assert_eq!(system.surface_count(), 1, "{name}");
        assert_eq!(
            system.surfaces().triangles().len(),
            body.triangles().len(),
            "{name}"
        );
        assert_eq!(system.has_surface_contact(), self_collision, "{name}");
    }
    let rope = Rope::between([0.0; 3], [1.0, 0.0, 0.0], 3).build().unwrap();
    assert!(!rope.collision().surface);
    let rope = rope.self_collision(true).surface_collision(true);
    assert_eq!(rope.system([0.0; 3]).unwrap().surface_count(), 0);
}

#[test]
fn a_body_without_surface_collision_adds_no_surface() {
    let cloth = Cloth::grid(3, 3).build().unwrap().surface_collision(false);
    assert!(!cloth.collision().surface);
    let system = cloth.system([0.0; 3]).unwrap();
    assert_eq!(system.surface_count(), 0);
    assert!(!system.has_surface_contact());
}

#[test]
fn a_negative_body_thickness_is_a_build_error() {
    let error = Cloth::grid(3, 3)
        .build()
        .unwrap()
        .thickness(-1e-3)
        .system([0.0; 3])
        .unwrap_err();
    assert!(error.to_string().contains("thickness"), "{error}");
}

#[test]
fn scene_files_default_to_the_bodies_own_collision() {
    let scene = parse(&format!("{CLOTH}{LATTICE}{ROPE}")).unwrap();
    let system = &scene.system;
    // The cloth and the lattice have surfaces; the rope has none.
    assert_eq!(system.surface_count(), 2);
    let mesh = system.surfaces();
    assert!(mesh.collides(0, 0), "cloth with itself");
    assert!(!mesh.collides(1, 1), "lattice with itself");
    assert!(mesh.collides(0, 1), "cloth with lattice");
    assert_relative_eq!(system.surface_thickness(0), 0.0);
    assert_relative_eq!(system.surface_thickness(1), 0.0);
    // The builder's default: at most a quarter of the mean edge, at most
    // 10⁻³ of the scene's size.
    let d = system.contact_distance();
    assert!(d > 0.0 && d <= 0.25 * 0.5 && d <= 2e-3, "{d}");
}

#[test]
fn scene_files_set_self_collision_thickness_and_contact_distance() {
    let text = format!(
        "[world]\ncontact_distance = 5e-4\n{CLOTH}self_collision = false\nthickness = 2e-3\n\
         {LATTICE}self_collision = true\nthickness = 1e-3\n"
    );
    let scene = parse(&text).unwrap();
    let system = &scene.system;
    assert_relative_eq!(system.contact_distance(), 5e-4);
    assert!(!system.surfaces().collides(0, 0));
    assert!(system.surfaces().collides(1, 1));
    assert_relative_eq!(system.surface_thickness(0), 2e-3);
    assert_relative_eq!(system.surface_thickness(1), 1e-3);
    // One cloth without self-collision has nothing to collide with.
    let alone = parse(&format!("{CLOTH}self_collision = false\n")).unwrap();
    assert!(!alone.system.has_surface_contact());
}

#[test]
fn a_layered_body_takes_its_contact_thickness_apart_from_its_layers() {
    let layered = format!(
        "[[bodies]]\ntype = \"layered\"\nmesh = \"{}\"\nthickness = 0.05\n\
         contact_thickness = 1e-3\nself_collision = true\n",
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes/meshes/icosphere.obj")
            .display()
    );
    let scene = parse(&layered).unwrap();
    assert_relative_eq!(scene.system.surface_thickness(0), 1e-3);
    assert!(scene.system.has_surface_contact());
    let error = error_at(
        &layered.replace("contact_thickness = 1e-3", "contact_thickness = -1.0"),
        5,
        "bodies[0].contact_thickness",
    );
    assert!(error.to_string().contains("got -1"), "{error}");
}

#[test]
fn collision_keys_on_a_rope_are_errors_naming_the_body_and_key() {
    for (key, value) in [("self_collision", "true"), ("thickness", "0.001")] {
        let error = error_at(
            &format!("{CLOTH}{ROPE}{key} = {value}\n"),
            14,
            &format!("bodies[1].{key}"),
        );
        assert!(matches!(*error.kind, ErrorKind::Invalid { .. }), "{error}");
        assert!(error.to_string().contains("rope"), "{error}");
    }
}

#[test]
fn bad_collision_values_are_named_with_their_lines() {
    let error = error_at(
        &format!("{CLOTH}thickness = -0.5\n"),
        7,
        "bodies[0].thickness",
    );
    assert!(
        error
            .to_string()
            .contains("got -0.5, expected a finite number ≥ 0 (m)"),
        "{error}"
    );
    error_at(
        &format!("{CLOTH}thickness = nan\n"),
        7,
        "bodies[0].thickness",
    );
    let error = error_at(
        &format!("{CLOTH}self_collision = \"yes\"\n"),
        7,
        "bodies[0].self_collision",
    );
    assert!(matches!(*error.kind, ErrorKind::Schema(_)), "{error}");
    for bad in ["0.0", "-1e-3", "inf"] {
        let error = error_at(
            &format!("[world]\ncontact_distance = {bad}\n{CLOTH}"),
            2,
            "world.contact_distance",
        );
        assert!(
            error
                .to_string()
                .contains("expected a finite number > 0 (m)"),
            "{error}"
        );
    }
}

#[test]
fn cloth_pile_stands_a_turned_self_colliding_cloth_on_a_corner_above_a_floor() {
    let scene = builtin::load("cloth-pile").unwrap();
    let system = &scene.system;
    assert_eq!(system.particle_count(), 900);
    assert_eq!(system.surface_count(), 1);
    assert!(
        system.has_surface_contact(),
        "the cloth collides with itself"
    );
    assert_eq!(system.pinned().count(), 0);
    let floor = system.obstacles().iter().find_map(|o| match o.shape {
        Shape::Plane { point, normal } if normal == Vec3::y() => Some(point.y),
        _ => None,
    });
    let x = system.initial_positions();
    let lowest = x.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let drop = lowest - floor.expect("a floor");
    assert!((0.25..=0.35).contains(&drop), "{drop} m");
    // Nearly vertical: leaning a few degrees out of the vertical plane,
    // and turned about 30° within it, so one corner is lowest.
    let (row, column) = ((x[1] - x[0]).normalize(), (x[30] - x[0]).normalize());
    let lean = row.cross(&column).normalize().y.abs().asin().to_degrees();
    assert!((1.0..=5.0).contains(&lean), "{lean}°");
    let turn = row.y.abs().asin().to_degrees();
    assert!((25.0..=35.0).contains(&turn), "{turn}°");
    let corners = [x[0].y, x[29].y, x[870].y, x[899].y];
    assert_eq!(corners.iter().filter(|&&y| y - lowest < 1e-9).count(), 1);
    assert_relative_eq!(scene.timing.dt, 1.0 / 60.0, max_relative = 1e-12);
    assert_eq!(
        scene.integrator,
        hooke_scenes::IntegratorSpec::backward_euler()
    );
}

#[test]
fn two_cloths_stack_one_turned_cloth_above_another_over_the_sphere() {
    let scene = builtin::load("two-cloths").unwrap();
    let system = &scene.system;
    assert_eq!(scene.bodies.len(), 2);
    assert_eq!(system.surface_count(), 2);
    assert!(system.surfaces().collides(0, 1));
    assert!(system.has_surface_contact());
    // Without self-collision the two cloths still collide.
    assert!(system.without_self_collision().has_surface_contact());
    let x = system.initial_positions();
    let heights = |body: usize| {
        let r = scene.bodies[body].placement.range();
        x[r].iter()
            .map(|p| p.y)
            .fold((f64::INFINITY, 0.0), |(lo, hi), y| {
                (lo.min(y), f64::max(hi, y))
            })
    };
    let ((lower_lo, lower_hi), (upper_lo, _)) = (heights(0), heights(1));
    assert!(lower_hi - lower_lo < 1e-12, "the lower cloth lies flat");
    assert!(upper_lo > lower_hi + 0.05, "the upper cloth starts above");
    let sphere = system.obstacles().iter().find_map(|o| match o.shape {
        Shape::Sphere { center, radius } => Some((center, radius)),
        _ => None,
    });
    let (center, radius) = sphere.expect("a sphere");
    assert!(lower_lo > center.y + radius);
    // The upper cloth is turned: its first row does not run along x.
    let upper = scene.bodies[1].placement.first;
    let row = (x[upper + 1] - x[upper]).normalize();
    assert!(row.dot(&Vec3::x()).abs() < 0.9, "{row}");
}
