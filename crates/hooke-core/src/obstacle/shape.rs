//! [`Shape`]: an obstacle's geometry — its signed distance and outward
//! normal, and how far a particle may move toward it (continuous collision
//! detection).
//!
//! A new shape is a variant here with its [`Shape::translated`],
//! [`Shape::distance`], [`Shape::reference_points`], [`Shape::bounds`],
//! checks and description; its continuous collision detection is
//! conservative advancement unless it has a closed form
//! ([`Shape::advance`]).

use std::fmt;

use crate::{Mat3, Vec3};

/// Iterations of conservative advancement before it settles for the
/// fraction reached.
const ADVANCEMENT_ITERATIONS: usize = 64;

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

    /// The largest `τ ∈ [0, 1]` such that a particle moving from `x` to
    /// `x + τ dx` keeps its signed distance from the shape at least
    /// `target < φ(x)`: exact for a plane (`φ` is linear along the motion)
    /// and a sphere (a quadratic's smaller root); conservative advancement
    /// for every other shape, whose signed distance is 1-Lipschitz, so that
    /// `φ(x + τ dx) ≥ target` for `τ ≤ (φ(x) − target)/|dx|` and each
    /// advance is safe. It stops once the room left is below 10⁻³ of the
    /// room at the start.
    ///
    /// ```
    /// use hooke_core::{Shape, Vec3};
    /// let floor = Shape::Plane { point: Vec3::zeros(), normal: Vec3::y() };
    /// // From 1 m above, straight down by 2 m, keeping 0.1 m: 0.9 of the way.
    /// let tau = floor.advance(Vec3::y(), -2.0 * Vec3::y(), 0.1);
    /// assert!((tau - 0.45).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn advance(&self, x: Vec3, dx: Vec3, target: f64) -> f64 {
        let length = dx.norm();
        if length == 0.0 {
            return 1.0;
        }
        match *self {
            Self::Plane { normal, .. } => {
                let rate = normal.normalize().dot(&dx);
                let phi = self.distance(x).0;
                if rate >= 0.0 {
                    1.0
                } else {
                    ((phi - target) / -rate).clamp(0.0, 1.0)
                }
            }
            Self::Sphere { center, radius } => {
                // |r + τ dx| = R with r = x − c, R = radius + target.
                let r = x - center;
                let reach = radius + target;
                let (a, b, c) = (
                    length * length,
                    2.0 * r.dot(&dx),
                    r.norm_squared() - reach * reach,
                );
                let discriminant = b * b - 4.0 * a * c;
                if b >= 0.0 || discriminant < 0.0 {
                    return 1.0;
                }
                // The smaller root, written to avoid cancellation.
                let q = -0.5 * (b - discriminant.sqrt());
                (c / q).clamp(0.0, 1.0)
            }
            _ => self.conservative_advance(x, dx, length, target),
        }
    }

    /// [`Shape::advance`] by conservative advancement: steps of
    /// `(φ − target)/|dx|` along the motion.
    fn conservative_advance(&self, x: Vec3, dx: Vec3, length: f64, target: f64) -> f64 {
        let mut tau = 0.0;
        let start = self.distance(x).0 - target;
        for _ in 0..ADVANCEMENT_ITERATIONS {
            let room = self.distance(x + tau * dx).0 - target;
            if room <= 1e-3 * start {
                break;
            }
            tau += room / length;
            if tau >= 1.0 {
                return 1.0;
            }
        }
        tau
    }

    /// The smallest axis-aligned box `(lo, hi)` holding the shape; `None`
    /// for a plane, which has none.
    ///
    /// ```
    /// use hooke_core::{Shape, Vec3};
    /// let ball = Shape::Sphere { center: Vec3::zeros(), radius: 2.0 };
    /// assert_eq!(ball.bounds(), Some((Vec3::repeat(-2.0), Vec3::repeat(2.0))));
    /// ```
    #[must_use]
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        match *self {
            Self::Plane { .. } => None,
            Self::Sphere { center, radius } => {
                let r = Vec3::repeat(radius);
                Some((center - r, center + r))
            }
            Self::Box {
                center,
                half_extents,
                rotation,
            } => {
                let reach = rotation.abs() * half_extents;
                Some((center - reach, center + reach))
            }
            Self::Capsule { a, b, radius } => {
                let r = Vec3::repeat(radius);
                Some((a.inf(&b) - r, a.sup(&b) + r))
            }
        }
    }

    /// The first thing wrong with the shape's parameters, if any: a point
    /// that is not finite, a radius or half extent that is not positive, a
    /// zero plane normal, a box turned by a matrix that is not a rotation.
    ///
    /// ```
    /// use hooke_core::{Shape, Vec3};
    /// let flat = Shape::Sphere { center: Vec3::zeros(), radius: 0.0 };
    /// assert_eq!(flat.problem(), Some("sphere radius must be positive and finite"));
    /// ```
    #[must_use]
    pub fn problem(&self) -> Option<&'static str> {
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

/// The shape in words, for a scene's description: "sphere at (0, 1, 0) of
/// radius 0.5 m".
///
/// ```
/// use hooke_core::{Shape, Vec3};
/// let ball = Shape::Sphere { center: Vec3::y(), radius: 0.5 };
/// assert_eq!(ball.to_string(), "sphere at (0, 1, 0) of radius 0.5 m");
/// ```
impl fmt::Display for Shape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = |v: Vec3| format!("({}, {}, {})", v.x, v.y, v.z);
        match *self {
            Self::Plane { point, normal } => {
                write!(f, "plane through {} with normal {}", v(point), v(normal))
            }
            Self::Sphere { center, radius } => {
                write!(f, "sphere at {} of radius {radius} m", v(center))
            }
            Self::Box {
                center,
                half_extents,
                ..
            } => write!(
                f,
                "box at {} with half extents {}",
                v(center),
                v(half_extents)
            ),
            Self::Capsule { a, b, radius } => {
                write!(f, "capsule from {} to {} of radius {radius} m", v(a), v(b))
            }
        }
    }
}
