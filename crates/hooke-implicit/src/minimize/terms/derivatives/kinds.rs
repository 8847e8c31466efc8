//! What the property test's cases are made of: the contact
//! configurations and friction regimes a case can hold, the random draws
//! that pick its parameters, and the system under construction.

use hooke_core::{Mat3, SystemBuilder, Vec3};
use nalgebra::Rotation3;

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
