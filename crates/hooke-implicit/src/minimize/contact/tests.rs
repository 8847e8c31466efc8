//! The contact model as one: a particle–obstacle pair's barrier against
//! finite differences, the one limit on every kind of pair, and the pair
//! list's obstacle pairs across steps.

use hooke_core::collision::barrier::Barrier;
use hooke_core::collision::broad::{BroadPhase, Candidates};
use hooke_core::{Mat3, Obstacle, Path, Shape, System, SystemBuilder, Vec3};

use super::obstacles::{At, Obstacles};
use super::pair::{Geometry, Kind, Pair};
use super::{Contact, KEEP};
use crate::linear::matrix::HessianBlocks;
use hooke_core::SymBlock;

/// Adds to `b` an `n × n` sheet of particles of 1 g, `spacing` apart
/// along x and z from `corner`, as a surface of two triangles a cell.
pub(super) fn sheet(b: &mut SystemBuilder, n: usize, spacing: f64, corner: Vec3) {
    let indices: Vec<usize> = (0..n * n)
        .map(|k| {
            let (i, j) = ((k / n) as f64, (k % n) as f64);
            b.particle(1e-3, corner + spacing * Vec3::new(i, 0.0, j))
        })
        .collect();
    let at = |i: usize, j: usize| indices[i * n + j];
    let mut triangles = Vec::new();
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    b.surface(&triangles);
}

/// Pseudo-random numbers in `[−½, ½)` from `seed`.
pub(super) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut seed = seed;
    move || {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        (seed >> 11) as f64 / (1_u64 << 53) as f64 - 0.5
    }
}

/// Two 6 × 6 sheets, 20 cm wide, 2 mm apart, around the vertical axis,
/// with a contact distance of 1 mm, over an obstacle of `shape`; their
/// rest positions, every pair of their surfaces within 3 cm (the tests'
/// motions move a particle 1.2 cm at most, so that pairs farther apart
/// keep more than a tenth of their gap), and their contact set up for a
/// step of 10 ms.
pub(super) fn sheets_over(shape: Shape) -> (System, Vec<Vec3>, Candidates, Contact) {
    let mut b = SystemBuilder::new();
    for height in [0.0, 2e-3] {
        sheet(&mut b, 6, 0.04, Vec3::new(0.3 * height - 0.1, height, -0.1));
    }
    b.contact_distance(1e-3);
    b.obstacle(Obstacle::new(shape));
    let system = b.build().unwrap();
    let x0 = system.initial_positions().to_vec();
    let mut everything = Candidates::default();
    BroadPhase::default().proximity(system.surfaces(), &x0, 0.03, &mut everything);
    let mut contact = Contact::default();
    contact.begin(&system, &x0, 0.0, 1e-2);
    (system, x0, everything, contact)
}

/// One shape of each kind, turned off the axes, whose top lies at `top`
/// near the origin (a box's top face tilted by a few thousandths).
fn shapes(top: f64) -> [Shape; 4] {
    let rotation = Mat3::from(nalgebra::Rotation3::from_euler_angles(0.005, 0.5, -0.005));
    let half_extents = Vec3::new(0.5, 0.2, 0.4);
    [
        Shape::Plane {
            point: Vec3::new(0.0, top, 0.0),
            normal: Vec3::new(0.01, 1.0, -0.005),
        },
        Shape::Sphere {
            center: Vec3::new(0.1, top - 0.4, 0.1),
            radius: 0.4,
        },
        Shape::Box {
            center: Vec3::new(0.0, top - half_extents.y * rotation[(1, 1)], 0.0),
            half_extents,
            rotation,
        },
        Shape::Capsule {
            a: Vec3::new(-0.3, top - 0.15, 0.05),
            b: Vec3::new(0.5, top - 0.15, 0.15),
            radius: 0.15,
        },
    ]
}

/// The blocks added on one particle's diagonal, summed.
struct Diagonal {
    particle: usize,
    block: Mat3,
}

impl HessianBlocks for Diagonal {
    fn add_row(&mut self, i: usize, block: SymBlock) {
        if i == self.particle {
            self.block += block.to_mat3();
        }
    }

    fn add_pair(&mut self, _: usize, _: usize, _: Mat3) {}
}

/// A particle's barrier against an obstacle of each shape, on a surface
/// of thickness 2 cm (its offset 1 cm) and on none: its value's central
/// differences give its gradient, and its gradient's give the Hessian
/// less the curvature term `κ b'(g) ∇²φ` that the projection leaves out
/// (`∇²φ` from the differences of the shape's normal; zero for a plane) —
/// which leaves the projected Hessian exact along the normal and positive
/// semidefinite.
#[test]
fn a_particle_obstacle_barrier_matches_finite_differences() {
    let d_hat = 0.1;
    let barrier = Barrier {
        stiffness: 3.0,
        activation: d_hat,
    };
    let mut unit = uniform(21);
    for shape in shapes(0.0) {
        let mut b = SystemBuilder::new();
        let corners = [Vec3::new(2.0, 2.0, 2.0), Vec3::new(2.1, 2.0, 2.0)];
        let on: Vec<usize> = [corners[0], corners[1], Vec3::new(2.0, 2.0, 2.1)]
            .iter()
            .map(|&p| b.particle(1e-3, p))
            .collect();
        b.surface(&[[on[0], on[1], on[2]]]).thickness(0.02);
        let free = b.particle(1e-3, Vec3::new(-2.0, 2.0, 2.0));
        b.obstacle(Obstacle::new(shape));
        b.contact_distance(d_hat);
        let system = b.build().unwrap();
        let mut obstacles = Obstacles::default();
        obstacles.begin(&system, 0.0, 0.0, true);
        let geometry = Geometry::new(&system, &obstacles, At::End);
        for (trial, i) in [on[0], free].into_iter().cycle().take(40).enumerate() {
            let pair = Pair::obstacle(&system, &obstacles, (i as u32, 0));
            // From a point outside, along the normal to a gap within d̂.
            let mut x = system.initial_positions().to_vec();
            let y = 1.2 * Vec3::new(unit(), unit(), unit()).normalize();
            let (phi, normal) = shape.distance(y);
            if phi <= 0.0 {
                continue;
            }
            let gap = d_hat * (0.05 + 0.9 * (unit() + 0.5));
            x[i] = y + (gap + pair.thickness - phi) * normal;
            let (g, n) = pair.gap(&geometry, &x);
            assert!((g - gap).abs() < 1e-12, "{shape:?}: gap {g}, wanted {gap}");
            let gradient = |x: &[Vec3]| {
                let mut b = vec![Vec3::zeros(); x.len()];
                let mut a = Diagonal {
                    particle: i,
                    block: Mat3::zeros(),
                };
                assert!(pair.add(&geometry, x, (&barrier, (1.0, 1.0)), &mut b, &mut a));
                (-b[i], a.block)
            };
            let (grad, hessian) = gradient(&x);
            let h = 1e-7;
            let mut differences = Mat3::zeros();
            let mut curvature = Mat3::zeros();
            for c in 0..3 {
                let (mut plus, mut minus) = (x.clone(), x.clone());
                plus[i][c] += h;
                minus[i][c] -= h;
                let slope = (pair.energy(&geometry, &plus, &barrier)
                    - pair.energy(&geometry, &minus, &barrier))
                    / (2.0 * h);
                let scale = grad.norm();
                assert!(
                    (slope - grad[c]).abs() <= 1e-6 * scale,
                    "{shape:?} #{trial}: ∂b/∂x{c} = {}, differences {slope}",
                    grad[c]
                );
                differences.set_column(c, &((gradient(&plus).0 - gradient(&minus).0) / (2.0 * h)));
                let normals = pair.gap(&geometry, &plus).1 - pair.gap(&geometry, &minus).1;
                curvature.set_column(c, &(normals / (2.0 * h)));
            }
            let slope = barrier.unit(g).1;
            let left_out = slope * 0.5 * (curvature + curvature.transpose());
            let scale = hessian.norm();
            assert!(
                (hessian - (differences - left_out)).norm() <= 1e-5 * scale,
                "{shape:?} #{trial}: Hessian {hessian}, differences {differences}, left out {left_out}"
            );
            assert!((hessian * n - differences * n).norm() <= 1e-5 * scale);
            assert!(hessian.symmetric_eigenvalues().min() >= -1e-12 * scale);
        }
    }
}

/// The gap of `pair` at `x`, and at `x` moved by `t dx`.
fn gaps(pair: &Pair, geometry: &Geometry, x: &[Vec3], dx: &[Vec3], t: f64) -> (f64, f64) {
    let moved: Vec<Vec3> = x.iter().zip(dx).map(|(x, d)| x + t * d).collect();
    (pair.gap(geometry, x).0, pair.gap(geometry, &moved).0)
}

/// The one limit on every kind of pair: two sheets 2 mm apart, 3 mm above
/// an obstacle of each shape, moved down by 2 to 8 mm and each particle
/// by up to 4 d̂ in its own direction besides: along the motion the limit
/// allows, every point–triangle, edge–edge and particle–obstacle pair
/// keeps at least a tenth of its gap, and pairs of each kind come close
/// to that bound (each kind has stopped some of the motions).
#[test]
fn the_one_limit_keeps_every_kind_of_pair_at_its_kept_fraction() {
    for shape in shapes(-3e-3) {
        let (system, x0, everything, mut contact) = sheets_over(shape);
        let d_hat = system.contact_distance();
        let mut unit = uniform(31);
        let mut closest = [f64::INFINITY; 3];
        for case in 0..12 {
            let drop = 2e-3 + 6e-3 * f64::from(case) / 12.0;
            let dx: Vec<Vec3> = x0
                .iter()
                .map(|_| 4.0 * d_hat * Vec3::new(unit(), unit(), unit()) - drop * Vec3::y())
                .collect();
            let tau = contact.limit(&system, &x0, &dx);
            assert!(tau > 0.0, "{shape:?}, drop {drop}: τ = {tau}");
            let geometry = Geometry::new(&system, &contact.obstacles, At::End);
            let point_triangle = everything
                .point_triangle
                .iter()
                .map(|&vt| Pair::point_triangle(&system, vt));
            let edge_edge = everything
                .edge_edge
                .iter()
                .map(|&ef| Pair::edge_edge(&system, ef));
            let particles =
                (0..x0.len() as u32).map(|i| Pair::obstacle(&system, &contact.obstacles, (i, 0)));
            for pair in point_triangle.chain(edge_edge).chain(particles) {
                let kind = match pair.kind {
                    Kind::PointTriangle => 0,
                    Kind::EdgeEdge => 1,
                    Kind::Obstacle(_) => 2,
                };
                for step in 1..=10 {
                    let t = tau * f64::from(step) / 10.0;
                    let (start, gap) = gaps(&pair, &geometry, &x0, &dx, t);
                    // A plane's and a sphere's CCD are exact: they stop at
                    // the kept fraction itself, but for rounding.
                    assert!(
                        gap >= KEEP * start * (1.0 - 1e-12),
                        "{shape:?}, drop {drop}: {:?} from {start} to {gap} at {t}",
                        pair.particles
                    );
                    closest[kind] = closest[kind].min(gap / start);
                }
            }
        }
        assert!(
            closest.iter().all(|&c| c < 0.5),
            "{shape:?}: the kinds came to {closest:?} of their gaps"
        );
    }
}

/// A falling rope of free particles (no collision surface) with its top
/// pinned, over a floor and a sphere that rises through it: at every step,
/// after the step's set-up (the obstacles at the step's start) and at
/// every point of each motion the limit allowed (at its end), the list
/// holds every free particle's pair with every obstacle within the
/// contact distance, and no pinned particle's.
#[test]
fn the_list_holds_the_obstacle_pairs_within_the_contact_distance_across_steps() {
    let mut b = SystemBuilder::new();
    let n = 40;
    let rope: Vec<usize> = (0..n)
        .map(|k| b.particle(1e-2, Vec3::new(0.02 * k as f64 - 0.4, 0.05, 0.0)))
        .collect();
    for k in 1..n {
        b.spring(rope[k - 1], rope[k], 100.0);
    }
    b.pin(rope[0]);
    b.contact_distance(2e-3);
    b.obstacle(Obstacle::new(Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    }));
    b.obstacle(
        Obstacle::new(Shape::Sphere {
            center: Vec3::new(0.1, -0.1, 0.0),
            radius: 0.08,
        })
        .moving(Path::Linear {
            velocity: Vec3::new(0.0, 0.5, 0.0),
        }),
    );
    let system = b.build().unwrap();
    let d_hat = system.contact_distance();
    let mut contact = Contact::default();
    let mut x = system.initial_positions().to_vec();
    let mut unit = uniform(41);
    let h = 0.01;
    let mut close = 0;
    let mut check = |contact: &Contact, x: &[Vec3], at: At| {
        let geometry = Geometry::new(&system, &contact.obstacles, at);
        let listed: Vec<(usize, Kind)> = contact
            .pairs
            .obstacle_pairs(&geometry)
            .map(|pair| (pair.particles[0], pair.kind))
            .collect();
        for i in 0..x.len() {
            for k in 0..2 {
                let pair = Pair::obstacle(&system, &contact.obstacles, (i as u32, k as u32));
                let found = listed.contains(&(i, Kind::Obstacle(k)));
                if system.is_pinned(i) {
                    assert!(!found, "pinned particle {i} listed");
                } else if pair.gap(&geometry, x).0 < d_hat {
                    close += 1;
                    assert!(found, "particle {i} within d̂ of obstacle {k}, not listed");
                }
            }
        }
    };
    for step in 0..60 {
        let time = f64::from(step) * h;
        contact.begin(&system, &x, time, h);
        check(&contact, &x, At::Start);
        let start = contact.start().to_vec();
        let dx: Vec<Vec3> = (0..start.len())
            .map(|i| {
                let fall = Vec3::new(0.0, -0.4, 0.0) + 0.2 * Vec3::new(unit(), unit(), unit());
                if system.is_pinned(i) {
                    Vec3::zeros()
                } else {
                    h * fall
                }
            })
            .collect();
        let tau = contact.limit(&system, &start, &dx);
        for point in 0..=4 {
            let t = tau * f64::from(point) / 4.0;
            let y: Vec<Vec3> = start.iter().zip(&dx).map(|(x, d)| x + t * d).collect();
            check(&contact, &y, At::End);
        }
        x = start.iter().zip(&dx).map(|(x, d)| x + tau * d).collect();
        contact.end_step(&system, &x);
        check(&contact, &x, At::End);
    }
    assert!(close > 1000, "{close} pairs within d̂");
}
