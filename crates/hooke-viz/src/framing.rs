//! [`run_bounds`]: the box a run's camera frames, chosen before the first
//! step so that the camera stays still while the bodies move.

use hooke_core::{System, Vec3};

use crate::bounds::Bounds;
use crate::scene_mesh::obstacles_at;
use hooke_core::Shape;

/// The box a camera keeps in view over a run of `system` lasting
/// `duration` seconds, or `None` if there is nothing finite to frame.
///
/// The run has not happened yet, so the box is an estimate from what is
/// known before it: the initial positions, the finite obstacles where they
/// are at the start and at the end, and how far gravity can carry the
/// bodies. Under gravity `g` the initial box is swept along `ĝ = g/|g|` by
/// a drop `d`:
///
/// - a plane the bodies fall towards (normal `n` with `ĝ·n < 0`) stops them
///   where the first corner of the initial box meets it, at
///   `d = φ / (−ĝ·n)` with `φ` that corner's height above the plane;
/// - pinned bodies hang at most their own size below where they start, so
///   with pins `d` is also at most the longest side of the initial box.
///
/// A body in free fall with neither pins nor a floor is framed where it
/// starts.
///
/// ```
/// use hooke_core::{Obstacle, Shape, SystemBuilder, Vec3};
/// let mut b = SystemBuilder::new();
/// b.particle(1.0, [0.0, 2.0, 0.0]);
/// b.particle(1.0, [1.0, 2.0, 0.0]);
/// b.gravity([0.0, -9.81, 0.0]);
/// b.obstacle(Obstacle::new(Shape::Plane { point: Vec3::zeros(), normal: Vec3::y() }));
/// let bounds = hooke_viz::run_bounds(&b.build()?, 1.0).expect("two particles");
/// assert_eq!(bounds.min(), Vec3::zeros()); // down to the floor
/// assert_eq!(bounds.max(), Vec3::new(1.0, 2.0, 0.0));
/// # Ok::<(), hooke_core::BuildError>(())
/// ```
#[must_use]
pub fn run_bounds(system: &System, duration: f64) -> Option<Bounds> {
    let start = obstacles_at(system, 0.0);
    let end = obstacles_at(system, duration);
    let obstacles = Bounds::of_scene(&[], &start).into_iter();
    let obstacles = obstacles.chain(Bounds::of_scene(&[], &end));
    let Some(bodies) = Bounds::of_points(system.initial_positions()) else {
        return obstacles.reduce(Bounds::union);
    };
    let swept = match system.gravity().and_then(|g| g.try_normalize(0.0)) {
        Some(down) => {
            let drop = drop_distance(system, &start, &bodies, down);
            Bounds::new(bodies.min() + drop * down, bodies.max() + drop * down)
        }
        None => bodies,
    };
    Some(obstacles.fold(bodies.union(swept), Bounds::union))
}

/// How far along the unit vector `down` the box `bodies` is expected to
/// fall: to the nearest of the planes among `obstacles` below it, and with
/// pins at most its longest side.
fn drop_distance(system: &System, obstacles: &[Shape], bodies: &Bounds, down: Vec3) -> f64 {
    let corners = (0..8).map(|k| {
        let pick = |axis: usize| {
            if k >> axis & 1 == 0 {
                bodies.min()[axis]
            } else {
                bodies.max()[axis]
            }
        };
        Vec3::new(pick(0), pick(1), pick(2))
    });
    let floor = obstacles
        .iter()
        .filter_map(|shape| match *shape {
            Shape::Plane { point, normal } => {
                let n = normal.try_normalize(0.0)?;
                let approach = -down.dot(&n);
                (approach > 0.0).then_some((point, n, approach))
            }
            _ => None,
        })
        .flat_map(|(point, n, approach)| {
            corners
                .clone()
                .map(move |c| ((c - point).dot(&n) / approach).max(0.0))
        })
        .fold(f64::INFINITY, f64::min);
    let hanging = if system.pinned().next().is_some() {
        (bodies.max() - bodies.min()).max()
    } else {
        f64::INFINITY
    };
    let drop = floor.min(hanging);
    if drop.is_finite() { drop } else { 0.0 }
}
