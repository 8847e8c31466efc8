//! The perspective camera: centring, foreshortening, orientation, framing.

use approx::assert_relative_eq;
use hooke_core::Vec3;
use hooke_viz::{Bounds, Camera, OutputError, View};

fn scene() -> Bounds {
    Bounds::new(Vec3::new(-1.0, 0.0, -0.5), Vec3::new(2.0, 1.5, 0.5))
}

fn camera(width: u32, height: u32) -> Camera {
    Camera::new(&scene(), width, height, &View::default()).unwrap()
}

#[test]
fn target_projects_to_the_image_centre() {
    let cam = camera(640, 480);
    assert_relative_eq!(cam.target(), scene().center());
    let p = cam.project(cam.target()).unwrap();
    assert_relative_eq!(p.x, 320.0, epsilon = 1e-9);
    assert_relative_eq!(p.y, 240.0, epsilon = 1e-9);
    assert_relative_eq!(p.depth, (cam.eye() - cam.target()).norm(), epsilon = 1e-9);
}

#[test]
fn farther_points_project_smaller() {
    let cam = camera(640, 480);
    let offset = cam.right() * 0.5;
    let near = cam.target() - cam.forward() * 1.0;
    let far = cam.target() + cam.forward() * 3.0;
    let spread = |base: Vec3| {
        let (a, b) = (
            cam.project(base).unwrap(),
            cam.project(base + offset).unwrap(),
        );
        b.x - a.x
    };
    assert!(spread(near) > spread(cam.target()));
    assert!(spread(cam.target()) > spread(far));
    assert!(spread(far) > 0.0);
}

#[test]
fn up_stays_up_and_right_stays_right() {
    let cam = camera(640, 480);
    let centre = cam.project(cam.target()).unwrap();
    let above = cam.project(cam.target() + Vec3::y()).unwrap();
    assert!(above.y < centre.y, "+y must appear higher in the image");
    assert_relative_eq!(cam.up().y, 25f64.to_radians().cos(), epsilon = 1e-12);
    assert_relative_eq!(cam.right().y, 0.0, epsilon = 1e-12);
    let right = cam.project(cam.target() + cam.right()).unwrap();
    assert!(right.x > centre.x);
}

#[test]
fn eye_sits_at_the_view_direction() {
    let cam = camera(640, 480);
    let d = (cam.eye() - cam.target()).normalize();
    let (az, el) = (35f64.to_radians(), 25f64.to_radians());
    assert_relative_eq!(
        d,
        Vec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos()),
        epsilon = 1e-12
    );
}

/// The box's corners fill `fill` of the limiting side exactly and never
/// leave the image.
#[test]
fn scene_fills_eighty_percent_of_the_limiting_side() {
    for (w, h) in [(640, 480), (300, 900), (500, 500)] {
        let cam = camera(w, h);
        let (b, c) = (scene(), cam.target());
        let corners = (0..8).map(|k| {
            let pick = |bit, lo: f64, hi: f64| if k & bit == 0 { lo } else { hi };
            let (lo, hi) = (b.min(), b.max());
            Vec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            )
        });
        let (mut dx, mut dy) = (0.0f64, 0.0f64);
        for p in corners {
            let q = cam.project(p).unwrap();
            let origin = cam.project(c).unwrap();
            dx = dx.max((q.x - origin.x).abs() / (f64::from(w) * 0.5));
            dy = dy.max((q.y - origin.y).abs() / (f64::from(h) * 0.5));
        }
        assert_relative_eq!(dx.max(dy), 0.8, epsilon = 1e-9);
    }
}

#[test]
fn a_single_point_is_framed_without_failing() {
    let p = Vec3::new(1.0, 2.0, 3.0);
    let cam = Camera::new(&Bounds::new(p, p), 100, 100, &View::default()).unwrap();
    let q = cam.project(p).unwrap();
    assert_relative_eq!(q.x, 50.0, epsilon = 1e-9);
    assert!(q.depth > 0.0);
}

#[test]
fn points_behind_the_eye_do_not_project() {
    let cam = camera(640, 480);
    assert!(cam.project(cam.eye() - cam.forward()).is_none());
}

#[test]
fn bad_views_and_sizes_are_rejected() {
    let view = |f: fn(&mut View)| {
        let mut v = View::default();
        f(&mut v);
        Camera::new(&scene(), 64, 64, &v)
    };
    for bad in [
        view(|v| v.elevation_degrees = 90.0),
        view(|v| v.fov_degrees = 0.0),
        view(|v| v.fill = 1.5),
        view(|v| v.fill = f64::NAN),
        view(|v| v.azimuth_degrees = f64::INFINITY),
    ] {
        assert!(matches!(bad, Err(OutputError::InvalidView { .. })));
    }
    assert!(matches!(
        Camera::new(&scene(), 0, 10, &View::default()),
        Err(OutputError::ImageSize {
            width: 0,
            height: 10,
            ..
        })
    ));
}
