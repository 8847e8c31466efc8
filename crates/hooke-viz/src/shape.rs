//! What a picture needs of an obstacle's [`Shape`] beyond the model: the
//! box that holds it and a check that it can be drawn.

use hooke_core::Shape;

use crate::bounds::Bounds;
use crate::error::OutputError;

/// The box holding `shape`, or `None` for a plane
/// ([`Shape::bounds`]).
///
/// ```
/// use hooke_core::{Shape, Vec3};
/// let ball = Shape::Sphere { center: Vec3::zeros(), radius: 2.0 };
/// let bounds = hooke_viz::shape_bounds(&ball).expect("a ball is finite");
/// assert_eq!(bounds.max(), Vec3::repeat(2.0));
/// ```
#[must_use]
pub fn shape_bounds(shape: &Shape) -> Option<Bounds> {
    shape.bounds().map(|(lo, hi)| Bounds::new(lo, hi))
}

/// Checks that `shape` can be drawn — that its parameters are valid
/// ([`Shape::problem`]); `index` is its place in the obstacle list, for
/// the error.
///
/// # Errors
///
/// [`OutputError::InvalidShape`] for non-finite data, a radius or half
/// extent that is not positive, a zero plane normal or a box turned by a
/// matrix that is not a rotation.
pub fn check_shape(shape: &Shape, index: usize) -> Result<(), OutputError> {
    shape.problem().map_or(Ok(()), |reason| {
        Err(OutputError::InvalidShape { index, reason })
    })
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use hooke_core::Vec3;
    use nalgebra::Rotation3;

    use super::*;

    #[test]
    fn rotated_box_bounds_cover_its_corners() {
        let rotation = Rotation3::from_axis_angle(&Vec3::z_axis(), std::f64::consts::FRAC_PI_4);
        let b = shape_bounds(&Shape::Box {
            center: Vec3::zeros(),
            half_extents: Vec3::new(1.0, 1.0, 0.5),
            rotation: rotation.into_inner(),
        })
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
            check_shape(&bad, 4),
            Err(OutputError::InvalidShape { index: 4, .. })
        ));
        let flat = Shape::Plane {
            point: Vec3::zeros(),
            normal: Vec3::zeros(),
        };
        assert!(check_shape(&flat, 0).is_err());
        let ball = Shape::Sphere {
            center: Vec3::zeros(),
            radius: 1.0,
        };
        assert!(check_shape(&ball, 0).is_ok());
    }
}
