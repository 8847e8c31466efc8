//! The USD animation's obstacles: each shape as its USD prim, placed where
//! the model has it, a moving one sampled at every frame.

use hooke_core::{Mat3, Obstacle, Path, Shape, SystemBuilder, Vec3};
use hooke_scenes::{IntegratorSpec, Placement, Scene, SceneBody, Timing};
use hooke_viz::{AnimationFrame, OutputError, write_usda};

/// Three particles in one triangle, above a box turned 90° about y, a
/// capsule along x and a sphere rising at 1 m/s.
fn scene() -> Scene {
    let mut b = SystemBuilder::new();
    for x in [[0.0, 2.0, 0.0], [1.0, 2.0, 0.0], [0.0, 2.0, 1.0]] {
        b.particle(1.0, x);
    }
    b.gravity([0.0, 0.0, -9.81]);
    let turn = Mat3::new(0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0);
    b.obstacle(Obstacle::new(Shape::Box {
        center: Vec3::new(0.0, -1.0, 0.0),
        half_extents: Vec3::new(0.5, 0.25, 2.0),
        rotation: turn,
    }));
    b.obstacle(Obstacle::new(Shape::Capsule {
        a: Vec3::new(-1.0, 0.5, 0.0),
        b: Vec3::new(1.0, 0.5, 0.0),
        radius: 0.1,
    }));
    b.obstacle(
        Obstacle::new(Shape::Sphere {
            center: Vec3::new(3.0, 0.0, 0.0),
            radius: 0.5,
        })
        .moving(Path::Linear {
            velocity: Vec3::y(),
        }),
    );
    Scene {
        name: "shapes".into(),
        system: b.build().unwrap(),
        bodies: vec![SceneBody {
            name: "sheet 1".into(),
            placement: Placement {
                first: 0,
                count: 3,
                first_tet: 0,
                tet_count: 0,
            },
            triangles: vec![[0, 1, 2]],
            segments: Vec::new(),
        }],
        integrator: IntegratorSpec::backward_euler(),
        timing: Timing {
            duration: 1.0,
            dt: 0.5,
            frame_rate: 2.0,
        },
    }
}

fn write(scene: &Scene, frames: &[AnimationFrame]) -> Result<String, OutputError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("animation.usda");
    let x = scene.system.initial_positions().to_vec();
    write_usda(&path, scene, frames, 2.0, &mut |_| Ok(x.clone()))?;
    Ok(std::fs::read_to_string(path).unwrap())
}

#[test]
fn shapes_become_usd_prims_placed_as_in_the_model() {
    let frames = [0.0, 1.0, 2.0].map(|k| AnimationFrame {
        time_code: k,
        time: 0.5 * k,
    });
    let text = write(&scene(), &frames).unwrap();
    for line in [
        // Gravity along −z makes z the up axis.
        "upAxis = \"Z\"",
        "def Mesh \"sheet_1\"",
        "int[] faceVertexIndices = [0, 1, 2]",
        "def Cube \"box\"",
        "double size = 2",
        "double3 xformOp:scale = (0.5, 0.25, 2)",
        "double3 xformOp:translate = (0, -1, 0)",
        "uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:orient\", \"xformOp:scale\"]",
        "def Capsule \"capsule\"",
        "double height = 2",
        "double3 xformOp:translate = (0, 0.5, 0)",
        "def Sphere \"sphere\"",
        "2: (3, 1, 0),",
    ] {
        assert!(text.contains(line), "{line} in\n{text}");
    }
    // The box's quaternion turns its x axis onto the model's −z; the
    // capsule's turns z onto x.
    let quaternions: Vec<[f64; 4]> = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("quatd xformOp:orient = "))
        .map(|q| {
            let v: Vec<f64> = q
                .trim_matches(['(', ')'])
                .split(", ")
                .map(|c| c.parse().unwrap())
                .collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect();
    let rotate = |[w, x, y, z]: [f64; 4], v: Vec3| {
        nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)) * v
    };
    assert_eq!(quaternions.len(), 2);
    assert!((rotate(quaternions[0], Vec3::x()) + Vec3::z()).norm() < 1e-12);
    assert!((rotate(quaternions[1], Vec3::z()) - Vec3::x()).norm() < 1e-12);
}

#[test]
fn an_animation_needs_frames_and_its_bodies_own_particles() {
    assert!(matches!(
        write(&scene(), &[]),
        Err(OutputError::EmptyAnimation { .. })
    ));
    let mut stray = scene();
    stray.bodies[0].triangles = vec![[0, 1, 3]];
    let frame = [AnimationFrame {
        time_code: 0.0,
        time: 0.0,
    }];
    assert!(matches!(
        write(&stray, &frame),
        Err(OutputError::VertexOutOfRange { vertex: 3, .. })
    ));
}
