//! [`Bounds`]: axis-aligned boxes around what a picture has to show.

use hooke_core::Vec3;

use hooke_core::Shape;

/// An axis-aligned bounding box, `min <= max` componentwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    min: Vec3,
    max: Vec3,
}

impl Bounds {
    /// The box with corners `a` and `b`, in either order.
    #[must_use]
    pub fn new(a: Vec3, b: Vec3) -> Self {
        Self {
            min: a.inf(&b),
            max: a.sup(&b),
        }
    }

    /// The smallest box holding all `points`, or `None` if there are none.
    #[must_use]
    pub fn of_points(points: &[Vec3]) -> Option<Self> {
        let (first, rest) = points.split_first()?;
        Some(
            rest.iter()
                .fold(Self::new(*first, *first), |b, &p| b.union(Self::new(p, p))),
        )
    }

    /// The box around a frame's positions and the finite obstacles
    /// (spheres, boxes, capsules; planes are unbounded and left out), or
    /// `None` if there is nothing finite to frame.
    ///
    /// To keep a camera still over a run, frame the union of the first and
    /// last frames: `a.union(b)`.
    #[must_use]
    pub fn of_scene(positions: &[Vec3], obstacles: &[Shape]) -> Option<Self> {
        obstacles
            .iter()
            .filter_map(crate::shape_bounds)
            .chain(Self::of_points(positions))
            .reduce(Self::union)
    }

    /// The smallest box holding both.
    #[must_use]
    pub fn union(self, other: Self) -> Self {
        Self {
            min: self.min.inf(&other.min),
            max: self.max.sup(&other.max),
        }
    }

    /// The corner with the smallest coordinates.
    #[must_use]
    pub fn min(&self) -> Vec3 {
        self.min
    }

    /// The corner with the largest coordinates.
    #[must_use]
    pub fn max(&self) -> Vec3 {
        self.max
    }

    /// The centre of the box.
    #[must_use]
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Half the diagonal: the radius of the smallest sphere about
    /// [`center`](Self::center) that holds the box.
    #[must_use]
    pub fn radius(&self) -> f64 {
        (self.max - self.min).norm() * 0.5
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    #[test]
    fn points_and_obstacles_are_framed_but_planes_are_not() {
        let points = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 2.0, -1.0)];
        let obstacles = [
            Shape::Sphere {
                center: Vec3::new(3.0, 0.0, 0.0),
                radius: 0.5,
            },
            Shape::Plane {
                point: Vec3::new(0.0, -100.0, 0.0),
                normal: Vec3::y(),
            },
        ];
        let b = Bounds::of_scene(&points, &obstacles).unwrap();
        assert_relative_eq!(b.min(), Vec3::new(0.0, -0.5, -1.0));
        assert_relative_eq!(b.max(), Vec3::new(3.5, 2.0, 0.5));
        assert_relative_eq!(b.center(), Vec3::new(1.75, 0.75, -0.25));
        assert!(Bounds::of_scene(&[], &obstacles[1..]).is_none());
    }
}
