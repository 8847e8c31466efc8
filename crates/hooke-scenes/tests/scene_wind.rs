//! `[world] wind` in scene files: the term it adds acts on every body's
//! surface triangles, a scene without it (or without drag) has none, and
//! each malformed value is an error naming its key and line.

mod common;

use hooke_core::Vec3;
use hooke_scenes::file::ErrorKind;

use common::{CLOTH, error_at, parse};

/// A 2 × 2 × 2 lattice body table, a cube of side 0.5 m away from the
/// cloth.
const LATTICE: &str = r#"
[[bodies]]
type = "lattice"
cells = [2, 2, 2]
size = [0.5, 0.5, 0.5]
origin = [3.0, 0.0, 0.0]
edges = { stiffness = 100.0 }
"#;

/// A rope body table: no triangles.
const ROPE: &str = r#"
[[bodies]]
type = "rope"
start = [0, 1, 0]
end = [1, 1, 0]
segments = 4
stretch = { stiffness = 100.0 }
"#;

/// The total wind force on a scene at rest, `Σ_T c A (w·n) n`.
fn total_force(text: &str) -> Vec3 {
    let scene = parse(text).unwrap();
    let system = &scene.system;
    let state = system.initial_state();
    let mut f = vec![Vec3::zeros(); system.particle_count()];
    for term in system.terms() {
        term.force(system, state.positions(), state.velocities(), &mut f);
    }
    f.iter().sum()
}

/// At rest in the wind `w`, the horizontal 1 m² cloth feels `c (w·ŷ) ŷ`
/// on its two faces' worth of triangles, and the cube of side `s`, a
/// closed surface whose faces' `A n nᵀ` sum to `2 s² I`, feels `2 c s² w`;
/// the rope, with no triangles, nothing.
#[test]
fn the_wind_acts_on_every_bodys_surface() {
    let (w, c, s) = (Vec3::new(1.0, 2.0, -0.5), 0.3, 0.5);
    let world = format!(
        "[world]\ngravity = [0.0, 0.0, 0.0]\nwind = {{ velocity = [{}, {}, {}], drag = {c} }}\n",
        w.x, w.y, w.z
    );
    let scene = parse(&format!("{world}{CLOTH}{LATTICE}{ROPE}")).unwrap();
    let names: Vec<_> = scene.system.terms().iter().map(|t| t.name()).collect();
    assert_eq!(names, ["wind"]);
    let expected = c * w.y * Vec3::y() + 2.0 * c * s * s * w;
    let force = total_force(&format!("{world}{CLOTH}{LATTICE}{ROPE}"));
    assert!(
        (force - expected).norm() < 1e-12,
        "{force} against {expected}"
    );
}

#[test]
fn no_wind_or_no_drag_adds_no_term() {
    for world in [
        "",
        "[world]\nair_damping = 0.1\n",
        "[world]\nwind = { velocity = [1.0, 0.0, 0.0], drag = 0.0 }\n",
    ] {
        let scene = parse(&format!("{world}{CLOTH}")).unwrap();
        assert!(scene.system.terms().is_empty(), "{world}");
    }
}

#[test]
fn a_bad_wind_is_named_with_its_line() {
    let wind = |table: &str| format!("[world]\nwind = {table}\n{CLOTH}");
    let error = error_at(
        &wind("{ velocity = [1.0, 0.0, 0.0], drag = -0.5 }"),
        2,
        "world.wind.drag",
    );
    assert!(error.to_string().contains("got -0.5"), "{error}");
    assert!(error.to_string().contains("N·s/m³"), "{error}");
    error_at(
        &wind("{ velocity = [nan, 0.0, 0.0], drag = 0.5 }"),
        2,
        "world.wind.velocity",
    );
    error_at(
        &wind("{ velocity = [1.0, 0.0], drag = 0.5 }"),
        2,
        "world.wind.velocity",
    );
    let error = error_at(
        &wind("{ velocity = [1.0, 0.0, 0.0] }"),
        2,
        "world.wind.drag",
    );
    assert!(matches!(*error.kind, ErrorKind::Schema(_)));
    assert!(
        error.to_string().contains("missing field `drag`"),
        "{error}"
    );
    let error = error_at(
        &wind("{ velocity = [1.0, 0.0, 0.0], drag = 0.5, speed = 2.0 }"),
        2,
        "world.wind.speed",
    );
    assert!(
        error.to_string().contains("unknown field `speed`"),
        "{error}"
    );
}
