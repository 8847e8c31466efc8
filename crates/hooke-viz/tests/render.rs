//! Pictures of known scenes: what covers which pixels, and PNG output.

use std::f64::consts::PI;

use approx::assert_relative_eq;
use hooke_core::{Shape, Vec3};
use hooke_viz::{Bounds, Camera, Mesh, OutputError, Pixmap, Renderer, Rgb, Style, View, save_png};

const BACKGROUND: Rgb = [250, 250, 250];

fn plain() -> Style {
    Style {
        background_top: BACKGROUND,
        background_bottom: BACKGROUND,
        ..Style::default()
    }
}

fn rgb(pixmap: &Pixmap, x: u32, y: u32) -> Rgb {
    let c = pixmap.pixel(x, y).unwrap().demultiply();
    [c.red(), c.green(), c.blue()]
}

fn covered(pixmap: &Pixmap) -> usize {
    (0..pixmap.height())
        .flat_map(|y| (0..pixmap.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| rgb(pixmap, x, y) != BACKGROUND)
        .count()
}

/// Looking straight down -z at a triangle in the xy-plane.
fn facing_view() -> View {
    View {
        azimuth_degrees: 0.0,
        elevation_degrees: 0.0,
        ..View::default()
    }
}

fn triangle() -> (Mesh, Vec<Vec3>) {
    let mesh = Mesh::new(3, vec![[0, 1, 2]], Vec::new()).unwrap();
    let positions = vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    (mesh, positions)
}

#[test]
fn a_facing_triangle_covers_the_centre_and_not_the_corners() {
    let (mesh, positions) = triangle();
    let bounds = Bounds::of_points(&positions).unwrap();
    let camera = Camera::new(&bounds, 200, 160, &facing_view()).unwrap();
    let picture = Renderer::new(camera)
        .with_style(plain())
        .render(&mesh, &positions, &[])
        .unwrap();
    let centre = rgb(&picture, 100, 80);
    assert_ne!(centre, BACKGROUND);
    // Lit head-on, a facing triangle is the body colour dimmed by less than half.
    let body = Style::default().body;
    assert!(
        centre[0] > body[0] / 2 && centre[0] <= body[0],
        "{centre:?}"
    );
    for (x, y) in [(0, 0), (199, 0), (0, 159), (199, 159)] {
        assert_eq!(rgb(&picture, x, y), BACKGROUND, "corner ({x}, {y})");
    }
}

#[test]
fn a_sphere_renders_as_a_disc_of_its_projected_radius() {
    let center = Vec3::new(0.5, 1.0, -2.0);
    let radius = 0.75;
    let sphere = [Shape::Sphere { center, radius }];
    let bounds = Bounds::of_scene(&[], &sphere).unwrap();
    let camera = Camera::new(&bounds, 240, 240, &View::default()).unwrap();
    let empty = Mesh::new(0, Vec::new(), Vec::new()).unwrap();
    let picture = Renderer::new(camera)
        .with_style(plain())
        .render(&empty, &[], &sphere)
        .unwrap();

    // The silhouette of a sphere centred on the axis is a circle of radius
    // F tan(asin(r / D)).
    let distance = (camera.eye() - center).norm();
    let expected = camera.focal() * (radius / distance).asin().tan();
    let measured = (covered(&picture) as f64 / PI).sqrt();
    assert_relative_eq!(measured, expected, max_relative = 0.02);
    assert_ne!(rgb(&picture, 120, 120), BACKGROUND);
    let edge = (120.0 + expected * 1.1) as u32;
    assert_eq!(rgb(&picture, edge, 120), BACKGROUND);
}

#[test]
fn nearer_triangles_are_painted_over_farther_obstacles() {
    let (mesh, positions) = triangle();
    let behind = [Shape::Sphere {
        center: Vec3::new(0.0, 0.0, -3.0),
        radius: 0.4,
    }];
    let bounds = Bounds::of_scene(&positions, &behind).unwrap();
    let camera = Camera::new(&bounds, 200, 200, &facing_view()).unwrap();
    let picture = Renderer::new(camera)
        .with_style(plain())
        .render(&mesh, &positions, &behind)
        .unwrap();
    let centre = camera.project(Vec3::zeros()).unwrap();
    let [r, g, b] = rgb(&picture, centre.x as u32, centre.y as u32);
    // The body colour is orange (red > blue); the obstacle is blue-grey.
    assert!(r > b && r > g, "{:?}", [r, g, b]);
}

#[test]
fn a_floor_fills_the_lower_image_and_ropes_draw_lines() {
    let rope = Mesh::new(2, Vec::new(), vec![[0, 1]]).unwrap();
    let positions = [Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.0, 1.5, 0.0)];
    let floor = [Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    }];
    let bounds = Bounds::of_scene(&positions, &floor).unwrap();
    let camera = Camera::new(&bounds, 160, 120, &View::default()).unwrap();
    let style = Style {
        line_width: 3.0,
        ..plain()
    };
    let picture = Renderer::new(camera)
        .with_style(style)
        .render(&rope, &positions, &floor)
        .unwrap();
    assert_ne!(rgb(&picture, 80, 118), BACKGROUND, "floor under the scene");
    assert_eq!(rgb(&picture, 80, 1), BACKGROUND, "sky above the horizon");
    let mid = camera.project(Vec3::new(0.0, 1.0, 0.0)).unwrap();
    assert_eq!(
        rgb(&picture, mid.x as u32, mid.y as u32),
        Style::default().edge
    );
}

#[test]
fn bad_input_is_a_typed_error() {
    let (mesh, positions) = triangle();
    let camera = Camera::new(
        &Bounds::of_points(&positions).unwrap(),
        32,
        32,
        &View::default(),
    )
    .unwrap();
    let renderer = Renderer::new(camera);
    let bad_sphere = [
        Shape::Plane {
            point: Vec3::zeros(),
            normal: Vec3::y(),
        },
        Shape::Sphere {
            center: Vec3::zeros(),
            radius: 0.0,
        },
    ];
    assert!(matches!(
        renderer.render(&mesh, &positions, &bad_sphere),
        Err(OutputError::InvalidShape { index: 1, .. })
    ));
    assert!(matches!(
        renderer.render(&mesh, &positions[..2], &[]),
        Err(OutputError::PositionCount { .. })
    ));
}

#[test]
fn png_round_trips_and_unwritable_paths_name_the_file() {
    let (mesh, positions) = triangle();
    let bounds = Bounds::of_points(&positions).unwrap();
    let camera = Camera::new(&bounds, 64, 48, &facing_view()).unwrap();
    let picture = Renderer::new(camera)
        .render(&mesh, &positions, &[])
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("preview.png");
    save_png(&picture, &path).unwrap();
    let loaded = Pixmap::load_png(&path).unwrap();
    assert_eq!(loaded.data(), picture.data());

    let nowhere = dir.path().join("no such dir").join("preview.png");
    let err = save_png(&picture, &nowhere).unwrap_err();
    assert!(matches!(&err, OutputError::Create { path, .. } if *path == nowhere));
    assert!(err.to_string().contains("no such dir"));
}

/// A horizontal square of side `2 half` at height `y`, its triangles
/// counter-clockwise seen from +y (front up).
fn square(half: f64, y: f64) -> (Mesh, Vec<Vec3>) {
    let mesh = Mesh::new(4, vec![[0, 1, 2], [0, 2, 3]], Vec::new()).unwrap();
    let positions = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)]
        .map(|(x, z)| Vec3::new(x * half, y, z * half))
        .to_vec();
    (mesh, positions)
}

fn luma([r, g, b]: Rgb) -> f64 {
    0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b)
}

#[test]
fn the_floor_is_darker_in_a_clothes_shadow_than_away_from_it() {
    let (cloth, positions) = square(0.3, 0.6);
    let bare = Mesh::new(4, Vec::new(), Vec::new()).unwrap();
    let floor = [Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    }];
    let framed = [Vec3::new(-1.2, 0.0, -1.2), Vec3::new(1.2, 0.6, 1.2)];
    let camera = Camera::new(
        &Bounds::of_points(&framed).unwrap(),
        320,
        240,
        &View::default(),
    )
    .unwrap();
    let renderer = Renderer::new(camera);
    let shaded = renderer.render(&cloth, &positions, &floor).unwrap();
    let empty = renderer.render(&bare, &positions, &floor).unwrap();

    // Where the key light casts the square's centre onto the floor, and the
    // point as far on the other side of the square's foot, out of shadow.
    let light = renderer.light();
    assert!(light.y > 0.0);
    let centre = Vec3::new(0.0, 0.6, 0.0);
    let cast = centre - light * (centre.y / light.y);
    let lit = -cast;
    assert!(cast.xz().norm() > 0.3, "the shadow falls beside the square");
    let pixel = |p: Vec3| {
        let q = camera.project(p).unwrap();
        (q.x as u32, q.y as u32)
    };
    let (x, y) = pixel(cast);
    let (in_shadow, bare_floor) = (rgb(&shaded, x, y), rgb(&empty, x, y));
    // Floor, not cloth (orange: red far above blue), and darker than the
    // same floor without the square above it.
    assert!(
        i32::from(in_shadow[0]) - i32::from(in_shadow[2]) < 40,
        "{in_shadow:?}"
    );
    assert!(
        luma(in_shadow) < 0.8 * luma(bare_floor),
        "{in_shadow:?} against {bare_floor:?}"
    );
    let (x, y) = pixel(lit);
    assert_eq!(rgb(&shaded, x, y), rgb(&empty, x, y), "no shadow there");
}

#[test]
fn the_front_and_the_back_of_a_surface_have_their_own_colours() {
    let (cloth, positions) = square(0.5, 0.0);
    let style = Style {
        body: [200, 40, 40],
        body_back: [40, 40, 200],
        ..plain()
    };
    for (elevation, front) in [(40.0, true), (-40.0, false)] {
        let view = View {
            elevation_degrees: elevation,
            ..View::default()
        };
        let camera = Camera::new(&Bounds::of_points(&positions).unwrap(), 160, 120, &view).unwrap();
        let picture = Renderer::new(camera)
            .with_style(style)
            .render(&cloth, &positions, &[])
            .unwrap();
        let [r, _, b] = rgb(&picture, 80, 60);
        assert_eq!(r > b, front, "elevation {elevation}: {:?}", [r, b]);
    }
}

#[test]
fn a_cloth_resting_on_a_sphere_is_drawn_in_front_of_it() {
    // A small square touching the top of the sphere, seen from above: its
    // corners lie inside the sphere's surface by less than a millimetre,
    // where sorting whole triangles by depth goes wrong.
    let radius = 0.5;
    let (cloth, positions) = square(0.05, radius);
    let sphere = [Shape::Sphere {
        center: Vec3::zeros(),
        radius,
    }];
    let view = View {
        elevation_degrees: 60.0,
        ..View::default()
    };
    let camera = Camera::new(&Bounds::of_scene(&[], &sphere).unwrap(), 200, 200, &view).unwrap();
    let picture = Renderer::new(camera)
        .with_style(plain())
        .render(&cloth, &positions, &sphere)
        .unwrap();
    let top = camera.project(Vec3::new(0.0, radius, 0.0)).unwrap();
    let [r, g, b] = rgb(&picture, top.x as u32, top.y as u32);
    assert!(r > b && r > g, "{:?}", [r, g, b]);
}
