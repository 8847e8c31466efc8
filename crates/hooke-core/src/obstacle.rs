//! Kinematic obstacles: [`Shape`]s that particles cannot enter, moved along a
//! scripted [`Path`], with restitution and Coulomb friction.

use crate::{Mat3, Vec3};

/// The geometry of an obstacle in its rest placement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// The half-space below the plane through `point` with normal `normal`
    /// (any length; particles are kept on the side it points to).
    Plane {
        /// A point on the plane, m.
        point: Vec3,
        /// The outward normal.
        normal: Vec3,
    },
    /// A solid ball.
    Sphere {
        /// Centre, m.
        center: Vec3,
        /// Radius, m.
        radius: f64,
    },
    /// A solid box: `center + rotation · p` for `|pₖ| ≤ half_extentsₖ`.
    Box {
        /// Centre, m.
        center: Vec3,
        /// Half the side lengths along the box's own axes, m.
        half_extents: Vec3,
        /// The box's axes as the columns of a rotation matrix.
        rotation: Mat3,
    },
    /// The points within `radius` of the segment from `a` to `b`.
    Capsule {
        /// One end of the axis, m.
        a: Vec3,
        /// The other end, m.
        b: Vec3,
        /// Radius, m.
        radius: f64,
    },
}

impl Shape {
    /// The same shape moved by `offset`, as a moving obstacle is at the time
    /// its path is displaced by `offset`.
    ///
    /// ```
    /// use hooke_core::{Shape, Vec3};
    /// let ball = Shape::Sphere { center: Vec3::zeros(), radius: 1.0 };
    /// let moved = ball.translated(Vec3::x());
    /// assert_eq!(moved, Shape::Sphere { center: Vec3::x(), radius: 1.0 });
    /// ```
    #[must_use]
    pub fn translated(&self, offset: Vec3) -> Self {
        match *self {
            Self::Plane { point, normal } => Self::Plane {
                point: point + offset,
                normal,
            },
            Self::Sphere { center, radius } => Self::Sphere {
                center: center + offset,
                radius,
            },
            Self::Box {
                center,
                half_extents,
                rotation,
            } => Self::Box {
                center: center + offset,
                half_extents,
                rotation,
            },
            Self::Capsule { a, b, radius } => Self::Capsule {
                a: a + offset,
                b: b + offset,
                radius,
            },
        }
    }

    /// The signed distance `φ(x)` from the surface (negative inside) and the
    /// outward unit normal `n = ∇φ` there.
    ///
    /// ```
    /// use hooke_core::{Shape, Vec3};
    /// let ball = Shape::Sphere { center: Vec3::zeros(), radius: 1.0 };
    /// let (phi, n) = ball.distance(Vec3::new(0.0, 0.5, 0.0));
    /// assert!((phi + 0.5).abs() < 1e-15 && (n - Vec3::y()).norm() < 1e-15);
    /// ```
    #[must_use]
    pub fn distance(&self, x: Vec3) -> (f64, Vec3) {
        match *self {
            Self::Plane { point, normal } => {
                let n = normal.normalize();
                ((x - point).dot(&n), n)
            }
            Self::Sphere { center, radius } => ball(x - center, radius),
            Self::Capsule { a, b, radius } => {
                let axis = b - a;
                let length2 = axis.norm_squared();
                let s = if length2 > 0.0 {
                    ((x - a).dot(&axis) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                ball(x - (a + s * axis), radius)
            }
            Self::Box {
                center,
                half_extents,
                rotation,
            } => {
                let p = rotation.transpose() * (x - center);
                let q = p.abs() - half_extents;
                let sign = p.map(|c| if c < 0.0 { -1.0 } else { 1.0 });
                let outside = q.map(|c| c.max(0.0));
                let distance = outside.norm();
                let local = if distance > 0.0 {
                    sign.component_mul(&outside) / distance
                } else {
                    let axis = q.imax();
                    let mut n = Vec3::zeros();
                    n[axis] = sign[axis];
                    n
                };
                let phi = if distance > 0.0 { distance } else { q.max() };
                (phi, rotation * local)
            }
        }
    }

    /// Two points that span the shape's extent where it has one (a plane's
    /// point twice): for the scale of a scene.
    #[must_use]
    pub fn reference_points(&self) -> (Vec3, Vec3) {
        match *self {
            Self::Plane { point, .. } => (point, point),
            Self::Sphere { center, radius } => {
                (center.add_scalar(-radius), center.add_scalar(radius))
            }
            Self::Box {
                center,
                half_extents,
                rotation,
            } => {
                let reach = (rotation.abs() * half_extents).norm();
                (center.add_scalar(-reach), center.add_scalar(reach))
            }
            Self::Capsule { a, b, radius } => {
                (a.inf(&b).add_scalar(-radius), a.sup(&b).add_scalar(radius))
            }
        }
    }

    /// The first thing wrong with the shape's parameters, if any.
    fn problem(&self) -> Option<&'static str> {
        let finite = |v: &Vec3| v.iter().all(|c| c.is_finite());
        let positive = |r: f64| r.is_finite() && r > 0.0;
        match self {
            Self::Plane { point, normal } => {
                if !finite(point) {
                    Some("plane point must be finite")
                } else if !(finite(normal) && normal.norm() > 0.0) {
                    Some("plane normal must be finite and non-zero")
                } else {
                    None
                }
            }
            Self::Sphere { center, radius } => {
                if !finite(center) {
                    Some("sphere center must be finite")
                } else if !positive(*radius) {
                    Some("sphere radius must be positive and finite")
                } else {
                    None
                }
            }
            Self::Box {
                center,
                half_extents,
                rotation,
            } => {
                if !finite(center) {
                    Some("box center must be finite")
                } else if !half_extents.iter().all(|&h| positive(h)) {
                    Some("box half_extents must be positive and finite")
                } else if !((rotation.transpose() * rotation - Mat3::identity()).norm() < 1e-9
                    && rotation.determinant() > 0.0)
                {
                    Some("box rotation must be a rotation matrix")
                } else {
                    None
                }
            }
            Self::Capsule { a, b, radius } => {
                if !(finite(a) && finite(b)) {
                    Some("capsule ends a and b must be finite")
                } else if !positive(*radius) {
                    Some("capsule radius must be positive and finite")
                } else {
                    None
                }
            }
        }
    }
}

/// Distance and normal for a ball of `radius` around the origin, at offset
/// `r` from its centre; the normal is `+y` at the centre itself.
fn ball(r: Vec3, radius: f64) -> (f64, Vec3) {
    let length = r.norm();
    let n = if length > 0.0 { r / length } else { Vec3::y() };
    (length - radius, n)
}

/// A scripted motion: the offset of an obstacle (or a pinned particle) from
/// its rest placement as a function of time.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Path {
    /// No motion.
    #[default]
    Fixed,
    /// Offset `u t`: constant velocity `u` in m/s.
    Linear {
        /// The velocity, m/s.
        velocity: Vec3,
    },
    /// Piecewise-linear offsets through `(time, offset)` keyframes with
    /// increasing times; constant before the first and after the last.
    Keyframes(Vec<(f64, Vec3)>),
}

impl Path {
    /// The offset at time `t`, m.
    ///
    /// ```
    /// use hooke_core::{Path, Vec3};
    /// let path = Path::Keyframes(vec![(0.0, Vec3::zeros()), (2.0, Vec3::new(0.0, 1.0, 0.0))]);
    /// assert_eq!(path.offset(1.0), Vec3::new(0.0, 0.5, 0.0));
    /// assert_eq!(path.offset(5.0), Vec3::new(0.0, 1.0, 0.0));
    /// ```
    #[must_use]
    pub fn offset(&self, t: f64) -> Vec3 {
        match self {
            Self::Fixed => Vec3::zeros(),
            Self::Linear { velocity } => t * velocity,
            Self::Keyframes(keys) => match Self::segment(keys, t) {
                Some((k, s)) => keys[k].1 + s * (keys[k + 1].1 - keys[k].1),
                None if keys.first().is_some_and(|(t0, _)| t < *t0) => keys[0].1,
                None => keys.last().map_or_else(Vec3::zeros, |(_, x)| *x),
            },
        }
    }

    /// The velocity at time `t` (on a keyframe, that of the segment after
    /// it), m/s.
    #[must_use]
    pub fn velocity(&self, t: f64) -> Vec3 {
        match self {
            Self::Fixed => Vec3::zeros(),
            Self::Linear { velocity } => *velocity,
            Self::Keyframes(keys) => Self::segment(keys, t).map_or_else(Vec3::zeros, |(k, _)| {
                (keys[k + 1].1 - keys[k].1) / (keys[k + 1].0 - keys[k].0)
            }),
        }
    }

    /// The keyframe segment `k` with `tₖ ≤ t < tₖ₊₁` and the fraction of it
    /// covered at `t`.
    fn segment(keys: &[(f64, Vec3)], t: f64) -> Option<(usize, f64)> {
        let k = keys.partition_point(|(tk, _)| *tk <= t).checked_sub(1)?;
        let (t0, t1) = (keys[k].0, keys.get(k + 1)?.0);
        Some((k, (t - t0) / (t1 - t0)))
    }

    /// The first thing wrong with the path, if any.
    pub(crate) fn problem(&self) -> Option<&'static str> {
        match self {
            Self::Fixed => None,
            Self::Linear { velocity } => {
                (!velocity.iter().all(|c| c.is_finite())).then_some("path velocity must be finite")
            }
            Self::Keyframes(keys) => {
                if keys.is_empty() {
                    Some("path keyframes must not be empty")
                } else if !keys
                    .iter()
                    .all(|(t, x)| t.is_finite() && x.iter().all(|c| c.is_finite()))
                {
                    Some("path keyframes must be finite")
                } else if !keys.windows(2).all(|w| w[0].0 < w[1].0) {
                    Some("path keyframe times must increase")
                } else {
                    None
                }
            }
        }
    }
}

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
