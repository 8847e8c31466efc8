//! The cases of the property test: small random systems at random
//! states, each holding every kind of term and one contact configuration.
//!
//! Every system has a body of two volume elements sharing a face, the
//! first inverted, on damped springs that are stretched and compressed,
//! one vertex pinned; gravity and air damping; the test's own terms
//! ([`own_terms`](super::own_terms)); and one [`Contact`] configuration
//! with one [`Friction`] regime, the body well away from it.

use hooke_core::{Mat3, System, SystemBuilder, Vec3};
use nalgebra::Rotation3;

use super::contacts::{self, Contacting};
use super::own_terms;

/// What a case puts within the contact distance `d̂`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Contact {
    /// Two triangles and a plane, all farther apart than `d̂`.
    Far,
    /// A vertex of one triangle over the inside of another.
    PointTriangle,
    /// Two triangles' edges crossing at an angle.
    CrossingEdges,
    /// Two triangles' edges crossing nearly parallel, where the
    /// mollifier fades their barrier.
    ParallelEdges,
    /// A particle, alone or a vertex of a triangle, near an obstacle.
    Obstacle(Shape),
    /// A particle on a plane that slides along itself.
    SlidingPlane,
    /// A particle on a sphere that rises along the normal at it.
    RisingSphere,
}

/// An obstacle's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Shape {
    Plane,
    Sphere,
    Box,
    Capsule,
}

/// Every contact configuration, each checked in every regime of friction.
pub(super) const CONTACTS: [Contact; 10] = [
    Contact::Far,
    Contact::PointTriangle,
    Contact::CrossingEdges,
    Contact::ParallelEdges,
    Contact::Obstacle(Shape::Plane),
    Contact::Obstacle(Shape::Sphere),
    Contact::Obstacle(Shape::Box),
    Contact::Obstacle(Shape::Capsule),
    Contact::SlidingPlane,
    Contact::RisingSphere,
];

/// The friction of the contact, by the tangential relative speed `|s|`
/// of its pair against the sticking speed `ε`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Friction {
    /// No friction (`μ = 0`).
    None,
    /// `|s| < ε`.
    Sticking,
    /// `|s| > ε`.
    Sliding,
}

pub(super) const FRICTIONS: [Friction; 3] = [Friction::None, Friction::Sticking, Friction::Sliding];

/// How the barriers' part of a barrier term's Hessian (its part in
/// `β²h²`) relates to the exact one, given the pairs a case brings within
/// `d̂`: each pair's Hessian is projected onto its positive part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Curvature {
    /// Exact: no pair, or only pairs whose Hessian has no negative part
    /// (a particle against a plane).
    Exact,
    /// The exact one's positive part: pairs on disjoint sets of
    /// particles.
    Positive,
    /// Above the exact one (the difference positive semidefinite): pairs
    /// sharing particles, each projected on its own.
    Above,
}

/// Uniform numbers in `[0, 1)`, handed out in turn (round again if the
/// case needs more than there are).
pub(super) struct Draws<'a> {
    values: &'a [f64],
    next: usize,
}

impl<'a> Draws<'a> {
    pub(super) fn new(values: &'a [f64]) -> Self {
        Self { values, next: 0 }
    }

    pub(super) fn unit(&mut self) -> f64 {
        let u = self.values[self.next % self.values.len()];
        self.next += 1;
        u
    }

    pub(super) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Log-uniform in `[lo, hi)`.
    pub(super) fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        lo * (hi / lo).powf(self.unit())
    }

    pub(super) fn flip(&mut self) -> bool {
        self.unit() < 0.5
    }

    /// A unit vector, uniform on the sphere.
    pub(super) fn direction(&mut self) -> Vec3 {
        let z = self.range(-1.0, 1.0);
        let azimuth = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).sqrt();
        Vec3::new(r * azimuth.cos(), r * azimuth.sin(), z)
    }

    /// A vector of length below `size`.
    pub(super) fn vector(&mut self, size: f64) -> Vec3 {
        self.range(0.0, size) * self.direction()
    }

    /// A unit vector normal to the unit vector `n`.
    pub(super) fn tangent(&mut self, n: Vec3) -> Vec3 {
        loop {
            let d = self.direction();
            let t = d - d.dot(&n) * n;
            if t.norm() > 0.1 {
                return t.normalize();
            }
        }
    }

    pub(super) fn rotation(&mut self) -> Mat3 {
        let axis = self.direction();
        let angle = self.range(0.0, std::f64::consts::PI);
        Rotation3::from_scaled_axis(angle * axis).into_inner()
    }
}

/// A system under construction with the state of a case: each
/// particle's position and velocity at the step's start.
pub(super) struct Parts {
    pub(super) builder: SystemBuilder,
    pub(super) x: Vec<Vec3>,
    pub(super) v: Vec<Vec3>,
}

impl Parts {
    /// A particle of `mass` at rest at `rest`, at `x` with velocity `v`.
    pub(super) fn particle(&mut self, mass: f64, rest: Vec3, x: Vec3, v: Vec3) -> usize {
        self.x.push(x);
        self.v.push(v);
        self.builder.particle(mass, rest)
    }

    /// Springs of random stiffness, damped or not, between `pairs`.
    pub(super) fn springs(&mut self, pairs: &[(usize, usize)], draws: &mut Draws) {
        for &(i, j) in pairs {
            let stiffness = draws.log_range(10.0, 1e4);
            let damping = if draws.flip() {
                draws.range(0.0, 2.0)
            } else {
                0.0
            };
            self.builder.spring(i, j, stiffness).damping(damping);
        }
    }
}

/// One case: a system, the step's start, and the point of its `Φ` the
/// checks evaluate.
pub(super) struct Case {
    pub(super) contact: Contact,
    pub(super) friction: Friction,
    /// What the case is, for messages.
    pub(super) label: String,
    pub(super) system: System,
    /// `xₙ` and `vₙ`.
    pub(super) x0: Vec<Vec3>,
    pub(super) v0: Vec<Vec3>,
    /// The velocities `v` of the point and the predictor's `ṽ`.
    pub(super) v: Vec<Vec3>,
    pub(super) v_tilde: Vec<Vec3>,
    pub(super) h: f64,
    pub(super) beta: f64,
    /// The shortest length and the lowest speed over which a term
    /// changes (the smallest gap, the sticking speed): the finite
    /// differences' steps are fractions of them.
    pub(super) length: f64,
    pub(super) speed: f64,
    /// The lever through which the rounding of the coordinates moves a
    /// gap, beyond their own size ([`Contacting::lever`]).
    pub(super) lever: f64,
    pub(super) curvature: Curvature,
}

/// The body's rest positions, m, before its scale and rotation: two
/// elements `[0, 1, 2, 3]` and `[0, 1, 2, 4]` sharing a face.
const BODY: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.2, 0.0, 0.9],
    [0.3, 0.8, 0.2],
    [0.4, -0.9, 0.3],
];

/// Where vertex 3 goes to invert the first element: through the shared
/// face.
const INVERTED: [f64; 3] = [0.35, -0.3, 0.25];

/// Every pair of the body's vertices but `(3, 4)`.
const BODY_SPRINGS: [(usize, usize); 9] = [
    (0, 1),
    (0, 2),
    (0, 3),
    (0, 4),
    (1, 2),
    (1, 3),
    (1, 4),
    (2, 3),
    (2, 4),
];

impl Case {
    /// The case `contact` with `friction`, its parameters from `draws`.
    pub(super) fn new(contact: Contact, friction: Friction, draws: &mut Draws) -> Self {
        let d_hat = draws.log_range(2e-4, 1e-3);
        let mut parts = Parts {
            builder: SystemBuilder::new(),
            x: Vec::new(),
            v: Vec::new(),
        };
        let beta = if draws.flip() { 1.0 } else { 2.0 / 3.0 };
        let near = contacts::place((contact, friction), (d_hat, beta), &mut parts, draws);
        let Contacting {
            point,
            up,
            gap,
            relative,
            curvature,
            lever,
            ref detail,
        } = near;
        // The body, well away from the contact.
        let base = point + 0.8 * up + draws.vector(0.1);
        let (scale, rotation) = (0.25, draws.rotation());
        let body: Vec<usize> = (0..BODY.len())
            .map(|k| {
                let rest = base + scale * rotation * Vec3::from(BODY[k]);
                let moved = if k == 3 { INVERTED } else { BODY[k] };
                let x = base + scale * rotation * Vec3::from(moved) + draws.vector(0.01);
                let mass = draws.log_range(1e-2, 1.0);
                parts.particle(mass, rest, x, draws.vector(0.5))
            })
            .collect();
        let springs = BODY_SPRINGS.map(|(i, j)| (body[i], body[j]));
        parts.springs(&springs, draws);
        for vertices in [[0, 1, 2, 3], [0, 1, 2, 4]] {
            let modulus = draws.log_range(1e2, 1e5);
            parts.builder.tet(vertices.map(|k| body[k]), modulus);
        }
        parts.builder.pin(body[4]);
        let anchored = body[0];
        own_terms::declare(
            &mut parts.builder,
            (anchored, parts.x[anchored]),
            point - up,
            draws,
        );
        parts
            .builder
            .gravity(9.81 * draws.direction())
            .air_damping(draws.log_range(1e-3, 0.5))
            .contact_distance(d_hat);
        let system = parts.builder.build().expect("a valid system");
        let n = system.particle_count();
        let v_tilde = (0..n).map(|_| draws.vector(0.5)).collect();
        // A step short enough that the pair's gap changes by a tenth at
        // most.
        let speed = d_hat;
        let h = (0.1 * gap / (beta * relative.max(speed))).min(1e-2);
        let length = if contact == Contact::Far {
            d_hat
        } else {
            0.5 * gap
        };
        let label = format!(
            "{contact:?} with {friction:?} friction{detail}: d̂ = {d_hat:.3e}, \
             gap {gap:.3e}, relative speed {relative:.3e}, h = {h:.3e}, β = {beta:.3}"
        );
        Self {
            contact,
            friction,
            label,
            system,
            x0: parts.x,
            v0: parts.v.clone(),
            v: parts.v,
            v_tilde,
            h,
            beta,
            length,
            speed,
            lever,
            curvature,
        }
    }
}
