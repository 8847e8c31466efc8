//! The layout vocabulary of a cloth grid: its [`Corner`]s, [`Edge`]s and
//! [`Plane`], pins named by them, and the optional rotation.

use nalgebra::{Rotation3, Unit};

use crate::error::{SceneError, finite, finite_vector};

/// A corner of the grid: top is row 0, left is column 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    /// Row 0, column 0.
    TopLeft,
    /// Row 0, last column.
    TopRight,
    /// Last row, column 0.
    BottomLeft,
    /// Last row, last column.
    BottomRight,
}

/// A side of the grid: top is row 0, left is column 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edge {
    /// Row 0.
    Top,
    /// The last row.
    Bottom,
    /// Column 0.
    Left,
    /// The last column.
    Right,
}

/// The plane the cloth lies in before any rotation; columns run along +x.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Plane {
    /// The x–z plane at y = 0, rows running along +z (a table cloth).
    #[default]
    Horizontal,
    /// The x–y plane at z = 0, rows running down −y from row 0 at y = 0
    /// (a curtain).
    Vertical,
}

/// A pin request of a [`crate::Cloth`], resolved once the grid is known.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Pin {
    /// One corner.
    Corner(Corner),
    /// A whole side.
    Edge(Edge),
    /// A particle by index.
    Particle(usize),
}

impl Pin {
    /// The particles pinned on a grid of `nx` columns and `ny` rows, particle
    /// `row · nx + column`.
    pub(crate) fn particles(self, nx: usize, ny: usize) -> Vec<usize> {
        let index = |row: usize, col: usize| row * nx + col;
        match self {
            Self::Particle(p) => vec![p],
            Self::Corner(Corner::TopLeft) => vec![index(0, 0)],
            Self::Corner(Corner::TopRight) => vec![index(0, nx - 1)],
            Self::Corner(Corner::BottomLeft) => vec![index(ny - 1, 0)],
            Self::Corner(Corner::BottomRight) => vec![index(ny - 1, nx - 1)],
            Self::Edge(Edge::Top) => (0..nx).map(|c| index(0, c)).collect(),
            Self::Edge(Edge::Bottom) => (0..nx).map(|c| index(ny - 1, c)).collect(),
            Self::Edge(Edge::Left) => (0..ny).map(|r| index(r, 0)).collect(),
            Self::Edge(Edge::Right) => (0..ny).map(|r| index(r, nx - 1)).collect(),
        }
    }
}

/// The rotation by `angle` about `axis`, both checked.
pub(crate) fn rotation(axis: [f64; 3], angle: f64) -> Result<Rotation3<f64>, SceneError> {
    let axis = finite_vector("rotation axis", axis)?;
    let angle = finite("rotation angle", angle)?;
    let axis = Unit::try_new(axis, f64::MIN_POSITIVE).ok_or(SceneError::InvalidVector {
        field: "rotation axis",
        value: axis.into(),
        requirement: "non-zero",
    })?;
    Ok(Rotation3::from_axis_angle(&axis, angle))
}
