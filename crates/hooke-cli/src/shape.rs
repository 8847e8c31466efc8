//! [`Shape`]: the obstacles a picture shows beside the bodies.

use hooke_core::Vec3;
use nalgebra::Rotation3;

use crate::bounds::Bounds;
use crate::error::OutputError;

/// A rigid obstacle as drawn: spheres, infinite planes, oriented boxes and
/// capsules.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A ball.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius, positive.
        radius: f64,
    },
    /// The infinite plane through `point` with the given normal; drawn as a
    /// checkered square under the scene's footprint.
    Plane {
        /// Any point on the plane.
        point: Vec3,
        /// Normal, nonzero (need not be unit length).
        normal: Vec3,
    },
    /// A box with the given half extents along its own axes, which are the
    /// columns of `rotation`.
    Box {
        /// Centre.
        center: Vec3,
        /// Half the side lengths, each positive.
        half_extents: Vec3,
        /// Orientation: world = `rotation` * local.
        rotation: Rotation3<f64>,
    },
    /// The points within `radius` of the segment from `a` to `b`.
    Capsule {
        /// One end of the axis.
        a: Vec3,
        /// The other end of the axis.
        b: Vec3,
        /// Radius, positive.
        radius: f64,
    },
}

impl Shape {
    /// The box holding the shape, or `None` for a plane.
    #[must_use]
    pub fn bounds(&self) -> Option<Bounds> {
        match *self {
            Self::Sphere { center, radius } => {
                let r = Vec3::repeat(radius);
                Some(Bounds::new(center - r, center + r))
            }
            Self::Plane { .. } => None,
            Self::Box {
                center,
                half_extents,
                rotation,
            } => {
                let reach = rotation.matrix().abs() * half_extents;
                Some(Bounds::new(center - reach, center + reach))
            }
            Self::Capsule { a, b, radius } => {
                let r = Vec3::repeat(radius);
                Some(Bounds::new(a - r, a + r).union(Bounds::new(b - r, b + r)))
            }
        }
    }

    /// Checks that the shape can be drawn; `index` is its place in the
    /// obstacle list, for the error.
    ///
    /// # Errors
    ///
    /// [`OutputError::InvalidShape`] for non-finite data, a radius or half
    /// extent that is not positive, or a zero plane normal.
    pub fn check(&self, index: usize) -> Result<(), OutputError> {
        let fail = |reason| Err(OutputError::InvalidShape { index, reason });
        let finite = |v: &Vec3| v.iter().all(|c| c.is_finite());
        let positive = |r: f64| r.is_finite() && r > 0.0;
        match self {
            Self::Sphere { center, radius } => {
                if !finite(center) {
                    return fail("sphere centre is not finite");
                }
                if !positive(*radius) {
                    return fail("sphere radius must be positive and finite");
                }
            }
            Self::Plane { point, normal } => {
                if !finite(point) || !finite(normal) {
                    return fail("plane point or normal is not finite");
                }
                if normal.norm() <= f64::MIN_POSITIVE {
                    return fail("plane normal is zero");
                }
            }
            Self::Box {
                center,
                half_extents,
                rotation,
            } => {
                if !finite(center) || !rotation.matrix().iter().all(|c| c.is_finite()) {
                    return fail("box centre or rotation is not finite");
                }
                if !half_extents.iter().all(|&h| positive(h)) {
                    return fail("box half extents must be positive and finite");
                }
            }
            Self::Capsule { a, b, radius } => {
                if !finite(a) || !finite(b) {
                    return fail("capsule axis is not finite");
                }
                if !positive(*radius) {
                    return fail("capsule radius must be positive and finite");
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    #[test]
    fn rotated_box_bounds_cover_its_corners() {
        let rotation = Rotation3::from_axis_angle(&Vec3::z_axis(), std::f64::consts::FRAC_PI_4);
        let b = Shape::Box {
            center: Vec3::zeros(),
            half_extents: Vec3::new(1.0, 1.0, 0.5),
            rotation,
        }
        .bounds()
        .unwrap();
        assert_relative_eq!(
            b.max(),
            Vec3::new(2f64.sqrt(), 2f64.sqrt(), 0.5),
            epsilon = 1e-12
        );
    }

    #[test]
    fn invalid_shapes_name_their_index() {
        let bad = Shape::Capsule {
            a: Vec3::zeros(),
            b: Vec3::x(),
            radius: -1.0,
        };
        assert!(matches!(
            bad.check(4),
            Err(OutputError::InvalidShape { index: 4, .. })
        ));
        let flat = Shape::Plane {
            point: Vec3::zeros(),
            normal: Vec3::zeros(),
        };
        assert!(flat.check(0).is_err());
        let ball = Shape::Sphere {
            center: Vec3::zeros(),
            radius: 1.0,
        };
        assert!(ball.check(0).is_ok());
    }
}
