//! Kinematic obstacles: [`Shape`]s that particles cannot enter, moved along a
//! scripted [`Path`], with restitution and Coulomb friction.

mod path;
mod shape;

pub use path::Path;
pub use shape::Shape;

use crate::Vec3;

/// A kinematic obstacle: a [`Shape`] moving along a [`Path`], with a
/// coefficient of restitution `e` (0: contacts are inelastic, 1: elastic)
/// and a Coulomb friction coefficient `μ`.
///
/// ```
/// use hooke_core::{Obstacle, Shape, Vec3};
/// let floor = Obstacle::new(Shape::Plane { point: Vec3::zeros(), normal: Vec3::y() })
///     .friction(0.4)
///     .restitution(0.2);
/// assert_eq!(floor.distance(Vec3::new(3.0, -0.1, 2.0), 0.0).0, -0.1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    /// The geometry at rest.
    pub shape: Shape,
    /// How it moves.
    pub path: Path,
    /// Coefficient of restitution `e ∈ [0, 1]`.
    pub restitution: f64,
    /// Coulomb friction coefficient `μ ≥ 0`.
    pub friction: f64,
}

impl Obstacle {
    /// A fixed, frictionless, inelastic obstacle.
    #[must_use]
    pub fn new(shape: Shape) -> Self {
        Self {
            shape,
            path: Path::Fixed,
            restitution: 0.0,
            friction: 0.0,
        }
    }

    /// Sets the coefficient of restitution `e ∈ [0, 1]`.
    ///
    /// ```
    /// # use hooke_core::{Obstacle, Shape, Vec3};
    /// let bouncy = Obstacle::new(Shape::Sphere { center: Vec3::zeros(), radius: 1.0 }).restitution(0.9);
    /// ```
    #[must_use]
    pub fn restitution(mut self, e: f64) -> Self {
        self.restitution = e;
        self
    }

    /// Sets the Coulomb friction coefficient `μ ≥ 0`.
    ///
    /// ```
    /// # use hooke_core::{Obstacle, Shape, Vec3};
    /// let rough = Obstacle::new(Shape::Sphere { center: Vec3::zeros(), radius: 1.0 }).friction(0.6);
    /// ```
    #[must_use]
    pub fn friction(mut self, mu: f64) -> Self {
        self.friction = mu;
        self
    }

    /// Moves the obstacle along `path`.
    ///
    /// ```
    /// # use hooke_core::{Obstacle, Path, Shape, Vec3};
    /// let rising = Obstacle::new(Shape::Sphere { center: Vec3::zeros(), radius: 1.0 })
    ///     .moving(Path::Linear { velocity: Vec3::new(0.0, 0.1, 0.0) });
    /// ```
    #[must_use]
    pub fn moving(mut self, path: Path) -> Self {
        self.path = path;
        self
    }

    /// The signed distance of `x` from the obstacle's surface at time `t`
    /// (negative inside) and the outward normal there.
    #[must_use]
    pub fn distance(&self, x: Vec3, t: f64) -> (f64, Vec3) {
        self.shape.distance(x - self.path.offset(t))
    }

    /// The obstacle's velocity at time `t`, m/s.
    #[must_use]
    pub fn velocity(&self, t: f64) -> Vec3 {
        self.path.velocity(t)
    }

    /// The first thing wrong with the obstacle's parameters, if any.
    pub(crate) fn problem(&self) -> Option<&'static str> {
        self.shape
            .problem()
            .or_else(|| self.path.problem())
            .or_else(|| {
                (!(0.0..=1.0).contains(&self.restitution))
                    .then_some("restitution must be in [0, 1]")
            })
            .or_else(|| {
                (!(self.friction.is_finite() && self.friction >= 0.0))
                    .then_some("friction must be finite and non-negative")
            })
    }
}
