//! Per-particle truncation: no pair of any kind crosses, or comes closer
//! than the kept fraction of its gap, along a truncated motion, however
//! fast; and the particles no pair stops move all the way.

use hooke_core::{Shape, System, Vec3};

use crate::minimize::contact::KEEP;
use crate::minimize::contact::obstacles::At;
use crate::minimize::contact::pair::{Geometry, Pair};
use crate::minimize::contact::pairs::surface::SurfacePart;
use crate::minimize::contact::tests::{sheets_over, uniform};

/// The gap of a surface pair at `x`.
fn gap(pair: &Pair, x: &[Vec3]) -> f64 {
    pair.distance(x) - pair.thickness
}

/// The two sheets of `sheets_over` 3 mm above a floor, the upper one's
/// particles (the second 36) moved by `upper(i, x)` and the lower one's
/// by `lower(i, x)`, truncated per particle: asserts that at 40 evenly
/// spaced points of the truncated motion every surface pair of the
/// sheets within 3 cm, and every particle against the floor, keeps more
/// than [`KEEP`] of its gap at the start; returns each particle's
/// fraction and the global limit of the whole motion.
fn truncated(
    upper: impl Fn(usize, Vec3) -> Vec3,
    lower: impl Fn(usize, Vec3) -> Vec3,
) -> (System, Vec<f64>, f64) {
    let (system, x0, everything, mut contact) = sheets_over(Shape::Plane {
        point: Vec3::new(0.0, -3e-3, 0.0),
        normal: Vec3::y(),
    });
    let dx: Vec<Vec3> = x0
        .iter()
        .enumerate()
        .map(|(i, &x)| if i < 36 { lower(i, x) } else { upper(i, x) })
        .collect();
    let global = contact.limit(&system, &x0, &dx);
    let scale = contact.truncate(&system, &x0, &dx).to_vec();
    let geometry = Geometry::new(&system, &contact.obstacles, At::End);
    let floor = |i: usize, x: &[Vec3]| {
        Pair::obstacle(&system, &contact.obstacles, (i as u32, 0))
            .gap(&geometry, x)
            .0
    };
    let pairs: Vec<Pair> = SurfacePart::pairs(&system, &everything).collect();
    assert!(pairs.len() > 100, "{} pairs", pairs.len());
    for step in 1..=40 {
        let t = f64::from(step) / 40.0;
        let x: Vec<Vec3> = x0
            .iter()
            .zip(&dx)
            .zip(&scale)
            .map(|((x, d), s)| x + t * s * d)
            .collect();
        for pair in &pairs {
            let (start, now) = (gap(pair, &x0), gap(pair, &x));
            assert!(
                now > KEEP * start,
                "{:?} at {t}: {now} of {start}",
                pair.particles
            );
        }
        for i in 0..x0.len() {
            let (start, now) = (floor(i, &x0), floor(i, &x));
            assert!(now > KEEP * start, "particle {i} at {t}: {now} of {start}");
        }
    }
    (system, scale, global)
}

/// A point driven through a triangle at high speed: the left half of the
/// upper sheet is driven 5 cm down in one motion — 25 times its gap to
/// the lower sheet, through it and the floor — while its right half
/// slides 1 cm along the sheets and the lower sheet stays. The driven
/// particles stop short of the lower sheet; the global limit stops the
/// whole motion at once, while the particles of the sliding half move all
/// the way, but for those sharing a pair with a driven one.
#[test]
fn a_point_driven_through_a_triangle_stops_and_the_rest_moves_on() {
    let (_, scale, global) = truncated(
        |_, x| {
            if x.x < 0.0 {
                Vec3::new(0.0, -0.05, 0.0)
            } else {
                Vec3::new(0.01, 0.0, 0.0)
            }
        },
        |_, _| Vec3::zeros(),
    );
    assert!(global < 0.05, "the global limit is {global}");
    let upper = &scale[36..];
    let stopped = upper.iter().filter(|&&s| s < 0.05).count();
    let whole = upper.iter().filter(|&&s| s >= 1.0).count();
    assert!(stopped >= 12, "{stopped} particles stopped");
    assert!(whole >= 12, "{whole} particles moved all the way");
}

/// Edges driven past each other at high speed: the two sheets, each
/// particle in its own pseudo-random direction besides, are sheared
/// against each other by 8 cm and pressed together by 4 cm in one motion,
/// so that the edges of one sweep across the edges of the other. No
/// pair, edge–edge or point–triangle, and no particle against the floor
/// comes closer than the kept fraction of its gap.
#[test]
fn edges_driven_past_each_other_at_high_speed_never_cross() {
    let jitter = |seed: u64| {
        let mut unit = uniform(seed);
        let all: Vec<Vec3> = (0..72)
            .map(|_| 4e-3 * Vec3::new(unit(), unit(), unit()))
            .collect();
        move |i: usize| all[i]
    };
    let (upper, lower) = (jitter(5), jitter(6));
    let (_, scale, _) = truncated(
        |i, _| Vec3::new(0.04, -0.02, 0.01) + upper(i),
        |i, _| Vec3::new(-0.04, 0.02, -0.01) + lower(i),
    );
    assert!(scale.iter().any(|&s| s < 1.0));
}
