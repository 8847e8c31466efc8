//! The contact configurations of the cases, each placed at a random
//! place and orientation with one pair at a random gap within the contact
//! distance `d̂` (none for [`Contact::Far`]), and the velocities that give
//! the pair's tangential relative speed its friction regime.
//!
//! Each configuration brings one pair within `d̂`, the others' primitives
//! kept at least `2(d̂ + ξ)` apart (`ξ` the thickness), but for nearly
//! parallel edges, whose ends may come within reach of the other edge and
//! its triangle. Of two triangles, the lower one's far corner is pinned.

use hooke_core::{Obstacle, Path, Shape as Geometry, Vec3};

use super::kinds::{Contact, Curvature, Draws, Friction, Parts, Shape};

/// A contact configuration placed in a case.
pub(super) struct Contacting {
    /// Where the pair is, and the normal of its contact there.
    pub(super) point: Vec3,
    pub(super) up: Vec3,
    /// The pair's gap at the step's start.
    pub(super) gap: f64,
    /// The speed of the pair's relative motion.
    pub(super) relative: f64,
    pub(super) curvature: Curvature,
    /// The lever through which the rounding of the coordinates moves the
    /// pair's gap beyond their own size, m: for edges at an angle `θ`,
    /// half the upper edge over `sin θ`, as the direction of their common
    /// normal carries a rounding error of `ε / sin θ`; zero otherwise.
    pub(super) lever: f64,
    /// More about the configuration, for messages.
    pub(super) detail: String,
}

/// The relative velocity of a pair with contact normal `n`: tangential at
/// a speed in the `friction` regime about the sticking speed `ε = d̂ / 1 s`
/// (any regime without friction), and normal at up to `ε/2`.
fn relative(friction: Friction, n: Vec3, d_hat: f64, draws: &mut Draws) -> Vec3 {
    let (lo, hi) = match friction {
        Friction::None => (0.0, 8.0),
        Friction::Sticking => (0.0, 0.8),
        Friction::Sliding => (1.25, 8.0),
    };
    let speed = d_hat * draws.range(lo, hi);
    speed * draws.tangent(n) + d_hat * draws.range(-0.5, 0.5) * n
}

/// A friction coefficient in the regime: zero without friction.
fn coefficient(friction: Friction, draws: &mut Draws) -> f64 {
    if friction == Friction::None {
        0.0
    } else {
        draws.range(0.1, 1.0)
    }
}

/// A surface's thickness: zero or up to `d̂`.
fn thickness(d_hat: f64, draws: &mut Draws) -> f64 {
    if draws.flip() {
        0.0
    } else {
        draws.range(0.0, d_hat)
    }
}

/// Adds the triangle `corners` with its velocities as a surface of
/// `thickness` and friction `mu`, its edges on springs; returns its
/// particles.
fn triangle(
    parts: &mut Parts,
    corners: [Vec3; 3],
    velocities: [Vec3; 3],
    (thickness, mu): (f64, f64),
    draws: &mut Draws,
) -> [usize; 3] {
    let p = [0, 1, 2].map(|k| {
        let mass = draws.log_range(1e-2, 1.0);
        parts.particle(mass, corners[k], corners[k], velocities[k])
    });
    parts
        .builder
        .surface(&[p])
        .thickness(thickness)
        .friction(mu);
    parts.springs(&[(p[0], p[1]), (p[1], p[2]), (p[2], p[0])], draws);
    p
}

/// Places `contact` with `friction` for the contact distance `d̂` and a
/// step with `β` = `beta` in `parts`.
pub(super) fn place(
    (contact, friction): (Contact, Friction),
    (d_hat, beta): (f64, f64),
    parts: &mut Parts,
    draws: &mut Draws,
) -> Contacting {
    let origin = draws.vector(0.1);
    let rotation = draws.rotation();
    let frame = |p: Vec3| origin + rotation * p;
    let up = rotation * Vec3::y();
    let gap = d_hat * draws.log_range(0.02, 0.9);
    let slow = |draws: &mut Draws| draws.vector(d_hat);
    match contact {
        Contact::Far | Contact::PointTriangle => {
            // The lower triangle in the plane y = 0, the upper one's first
            // corner over a point inside it, its others far above.
            let (xi_a, xi_b) = (thickness(d_hat, draws), thickness(d_hat, draws));
            let lower = [[-0.3, -0.2], [0.3, -0.2], [0.0, 0.35]]
                .map(|[x, z]| Vec3::new(x, 0.0, z) + draws.range(-0.05, 0.05) * Vec3::x());
            let weights = [0, 1, 2].map(|_| draws.range(0.2, 0.6));
            let total: f64 = weights.iter().sum();
            let inside: Vec3 = (0..3).map(|k| weights[k] / total * lower[k]).sum();
            let far = contact == Contact::Far;
            let height = if far { 0.2 } else { gap + 0.5 * (xi_a + xi_b) };
            let tip = inside + height * Vec3::y();
            let upper = [
                tip,
                tip + Vec3::new(0.15, 0.3, 0.05) + draws.vector(0.03),
                tip + Vec3::new(-0.12, 0.3, -0.1) + draws.vector(0.03),
            ];
            let v_lower = slow(draws);
            let rel = relative(friction, up, d_hat, draws);
            let v_upper = [v_lower + rel, slow(draws), slow(draws)];
            let mu = (coefficient(friction, draws), coefficient(friction, draws));
            triangle(parts, upper.map(frame), v_upper, (xi_a, mu.0), draws);
            let lower = triangle(parts, lower.map(frame), [v_lower; 3], (xi_b, mu.1), draws);
            parts.builder.pin(lower[2]);
            if far {
                let floor = Geometry::Plane {
                    point: frame(-0.2 * Vec3::y()),
                    normal: up,
                };
                parts.builder.obstacle(Obstacle::new(floor));
            }
            Contacting {
                point: frame(tip),
                up,
                gap: if far { d_hat } else { gap },
                relative: rel.norm(),
                curvature: if far {
                    Curvature::Exact
                } else {
                    Curvature::Positive
                },
                lever: 0.0,
                detail: String::new(),
            }
        }
        Contact::CrossingEdges | Contact::ParallelEdges => {
            // The lower edge along x at y = 0, its triangle below it; the
            // upper edge turned by θ about y at the height of the gap, its
            // triangle above it: the edges' closest points are their
            // midpoints.
            let (xi_a, xi_b) = (thickness(d_hat, draws), thickness(d_hat, draws));
            let xi = 0.5 * (xi_a + xi_b);
            // The upper edge the shorter, so that its ends lie over the
            // lower edge's inside, well clear of the ends (where the
            // distance of a point to the lower triangle changes region),
            // at `½L sin θ` from it.
            let length = draws.range(0.6, 1.0);
            let shorter = length * draws.range(0.5, 0.8);
            let apart = 3.0 * (d_hat + xi) / (0.5 * shorter);
            let sin = match contact {
                Contact::CrossingEdges => draws.range(0.3, 1.0),
                _ if draws.flip() => draws.log_range(apart, 0.03),
                _ => draws.log_range(1e-4, 0.03),
            };
            let along = Vec3::new((1.0 - sin * sin).sqrt(), 0.0, sin);
            let mid = (gap + xi) * Vec3::y();
            let half = 0.5 * shorter;
            let lower = [
                -0.5 * length * Vec3::x(),
                0.5 * length * Vec3::x(),
                Vec3::new(draws.range(-0.1, 0.1), -0.3, draws.range(0.05, 0.15)),
            ];
            let upper = [
                mid - half * along,
                mid + half * along,
                mid + Vec3::new(draws.range(-0.1, 0.1), 0.3, draws.range(-0.15, -0.05)),
            ];
            let v_lower = slow(draws);
            let rel = relative(friction, up, d_hat, draws);
            let v_upper = v_lower + rel;
            let mu = (coefficient(friction, draws), coefficient(friction, draws));
            let velocities = [v_upper, v_upper, slow(draws)];
            triangle(parts, upper.map(frame), velocities, (xi_a, mu.0), draws);
            let velocities = [v_lower, v_lower, slow(draws)];
            let lower = triangle(parts, lower.map(frame), velocities, (xi_b, mu.1), draws);
            parts.builder.pin(lower[2]);
            Contacting {
                point: frame(mid),
                up,
                gap,
                relative: rel.norm(),
                curvature: if half * sin > 2.0 * (d_hat + xi) {
                    Curvature::Positive
                } else {
                    Curvature::Above
                },
                lever: half / sin,
                detail: format!(", sin θ = {sin:.3e}"),
            }
        }
        Contact::Obstacle(_) | Contact::SlidingPlane | Contact::RisingSphere => {
            let (shape, curvature) = obstacle(contact, origin, up, draws);
            // From a point farther from `origin` than any solid reaches,
            // along the normal to the gap.
            let outside = origin + 0.8 * draws.direction();
            let (phi, n) = shape.distance(outside);
            // The particle alone, or a corner of a triangle reaching away
            // from the obstacle, offset by half its surface's thickness.
            let surface = draws.flip().then(|| thickness(d_hat, draws));
            let p = outside + (gap + surface.map_or(0.0, |xi| 0.5 * xi) - phi) * n;
            let p = clear(&shape, p);
            let n = shape.distance(p).1;
            // A plane slides along itself, its particle carried along at
            // the step's start; a sphere rises along the normal, its
            // particle moving with it over the step (`βh v = h u`), the
            // friction's relative velocity `v − u` then the same in its
            // tangent plane.
            let speed = draws.range(0.1, 1.0);
            let (path, carried) = match contact {
                Contact::SlidingPlane => {
                    let velocity = speed * draws.tangent(n);
                    (Path::Linear { velocity }, velocity)
                }
                Contact::RisingSphere => {
                    let velocity = speed * n;
                    (Path::Linear { velocity }, velocity / beta)
                }
                _ => (Path::Fixed, Vec3::zeros()),
            };
            let rel = relative(friction, n, d_hat, draws);
            let mu = coefficient(friction, draws);
            match surface {
                None => {
                    let mass = draws.log_range(1e-2, 1.0);
                    parts.particle(mass, p, p, carried + rel);
                }
                Some(xi) => {
                    let t = draws.tangent(n);
                    let corners = [p, p + 0.3 * n + 0.15 * t, p + 0.3 * n - 0.12 * t];
                    let velocities = [carried + rel, slow(draws), slow(draws)];
                    triangle(parts, corners, velocities, (xi, mu), draws);
                }
            }
            parts
                .builder
                .obstacle(Obstacle::new(shape).friction(mu).moving(path));
            Contacting {
                point: p,
                up: n,
                gap,
                relative: rel.norm(),
                curvature,
                lever: 0.0,
                detail: surface
                    .map_or_else(String::new, |xi| format!(", on a surface {xi:.3e} thick")),
            }
        }
    }
}

/// `p` moved, if need be, to keep a quarter of its distance from a box
/// away from where its closest feature changes from a face to an edge or
/// a corner, at the same distance: there the distance's curvature jumps
/// (from zero to one over the distance by an edge), which differences
/// across it do not resolve. Each coordinate of `p` in the box's frame
/// then lies that far from the face's extent, more than the particle
/// moves over the step (a tenth of its gap). Other shapes' distances have
/// no such jump within reach (a capsule's is the inverse of its radius at
/// most); `p` is left as it is.
fn clear(shape: &Geometry, p: Vec3) -> Vec3 {
    let Geometry::Box {
        center,
        half_extents,
        rotation,
    } = *shape
    else {
        return p;
    };
    let local = rotation.transpose() * (p - center);
    let mut q = local.abs() - half_extents;
    let distance = q.map(|c| c.max(0.0)).norm();
    let margin = 0.25 * distance;
    q.apply(|c| {
        if c.abs() < margin {
            *c = -margin;
        }
    });
    // The components left outside the extent grow to keep the distance.
    let scale = distance / q.map(|c| c.max(0.0)).norm();
    q.apply(|c| {
        if *c > 0.0 {
            *c *= scale;
        }
    });
    let sign = local.map(|c| if c < 0.0 { -1.0 } else { 1.0 });
    center + rotation * sign.component_mul(&(q + half_extents))
}

/// The obstacle of `contact` about `origin`, reaching at most 0.5 from
/// it (a plane through it, normal to `up`), and how its barrier's Hessian
/// relates to the exact one.
fn obstacle(contact: Contact, origin: Vec3, up: Vec3, draws: &mut Draws) -> (Geometry, Curvature) {
    let shape = match contact {
        Contact::Obstacle(shape) => shape,
        Contact::RisingSphere => Shape::Sphere,
        _ => Shape::Plane,
    };
    let solid = match shape {
        Shape::Plane => {
            let plane = Geometry::Plane {
                point: origin,
                normal: up,
            };
            return (plane, Curvature::Exact);
        }
        Shape::Sphere => Geometry::Sphere {
            center: origin,
            radius: draws.range(0.1, 0.4),
        },
        Shape::Box => Geometry::Box {
            center: origin,
            half_extents: Vec3::new(
                draws.range(0.05, 0.25),
                draws.range(0.05, 0.25),
                draws.range(0.05, 0.25),
            ),
            rotation: draws.rotation(),
        },
        Shape::Capsule => Geometry::Capsule {
            a: origin + draws.vector(0.25),
            b: origin + draws.vector(0.25),
            radius: draws.range(0.05, 0.2),
        },
    };
    (solid, Curvature::Positive)
}
