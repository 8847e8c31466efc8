//! [`Cloth`]: a rectangular grid of particles with stretch, shear and
//! bending springs.

use hooke_core::Vec3;
use nalgebra::Rotation3;

use crate::body::Body;
use crate::error::{SceneError, count, finite_vector, grid_points, positive};
use crate::grid::{Corner, Edge, Pin, Plane, rotation};
use crate::material::{Mass, Springs};
use crate::spring::{Family, SpringSet, validate_families};

/// A rectangular cloth of `columns × rows` particles, particle
/// `row · columns + column`, built into a [`Body`].
///
/// ```
/// use hooke_scenes::{Cloth, Corner, Family, Springs};
/// let cloth = Cloth::grid(40, 40)
///     .size(1.0, 1.0)
///     .stretch(5e3)
///     .shear(Springs::per_spring(1e3).damping(0.01))
///     .bend(50.0)
///     .pin_corners([Corner::TopLeft, Corner::TopRight])
///     .build()?;
/// assert_eq!(cloth.springs_of(Family::Stretch).count(), 2 * 40 * 39);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Cloth {
    columns: usize,
    rows: usize,
    width: f64,
    height: f64,
    mass: Mass,
    stretch: Option<Springs>,
    shear: Option<Springs>,
    bend: Option<Springs>,
    pins: Vec<Pin>,
    plane: Plane,
    rotation: Option<([f64; 3], f64)>,
    offset: [f64; 3],
}

impl Cloth {
    /// A grid of `columns × rows` particles (at least 2 × 2), 1 m × 1 m,
    /// 0.2 kg/m², horizontal, with no springs until a family is set.
    pub fn grid(columns: usize, rows: usize) -> Self {
        Self {
            columns,
            rows,
            width: 1.0,
            height: 1.0,
            mass: Mass::Density(0.2),
            stretch: None,
            shear: None,
            bend: None,
            pins: Vec::new(),
            plane: Plane::Horizontal,
            rotation: None,
            offset: [0.0; 3],
        }
    }

    /// Width (along the rows) and height (along the columns) in m.
    ///
    /// ```
    /// let cloth = hooke_scenes::Cloth::grid(3, 2).size(2.0, 0.5).build()?;
    /// assert_eq!(cloth.positions()[5], hooke_core::Vec3::new(2.0, 0.0, 0.5));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn size(mut self, width: f64, height: f64) -> Self {
        (self.width, self.height) = (width, height);
        self
    }

    /// Total mass, or areal density in kg/m²; lumped a quarter of each
    /// cell's mass to each of its corners.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Mass};
    /// let cloth = Cloth::grid(3, 3).mass(Mass::Total(0.8)).build()?;
    /// assert_eq!(cloth.masses()[4], 0.2); // the centre touches all 4 cells
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn mass(mut self, mass: Mass) -> Self {
        self.mass = mass;
        self
    }

    /// Structural springs between row and column neighbours:
    /// `rows (columns − 1) + columns (rows − 1)` of them.
    ///
    /// ```
    /// let cloth = hooke_scenes::Cloth::grid(4, 3).stretch(1e3).build()?;
    /// assert_eq!(cloth.springs().len(), 3 * 3 + 4 * 2);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn stretch(mut self, springs: impl Into<Springs>) -> Self {
        self.stretch = Some(springs.into());
        self
    }

    /// Shear springs on both diagonals of every cell:
    /// `2 (columns − 1)(rows − 1)` of them.
    ///
    /// ```
    /// let cloth = hooke_scenes::Cloth::grid(4, 3).shear(1e2).build()?;
    /// assert_eq!(cloth.springs().len(), 2 * 3 * 2);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn shear(mut self, springs: impl Into<Springs>) -> Self {
        self.shear = Some(springs.into());
        self
    }

    /// Bending springs between particles two apart in a row or column:
    /// `rows (columns − 2) + columns (rows − 2)` of them.
    ///
    /// ```
    /// let cloth = hooke_scenes::Cloth::grid(4, 3).bend(10.0).build()?;
    /// assert_eq!(cloth.springs().len(), 3 * 2 + 4 * 1);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn bend(mut self, springs: impl Into<Springs>) -> Self {
        self.bend = Some(springs.into());
        self
    }

    /// Pins the named corners.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Corner};
    /// let cloth = Cloth::grid(3, 2).pin_corners([Corner::TopRight, Corner::BottomLeft]).build()?;
    /// assert_eq!(cloth.pins(), [2, 3]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin_corners(mut self, corners: impl IntoIterator<Item = Corner>) -> Self {
        self.pins.extend(corners.into_iter().map(Pin::Corner));
        self
    }

    /// Pins every particle of one side.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Edge};
    /// let cloth = Cloth::grid(3, 3).pin_edge(Edge::Left).build()?;
    /// assert_eq!(cloth.pins(), [0, 3, 6]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin_edge(mut self, edge: Edge) -> Self {
        self.pins.push(Pin::Edge(edge));
        self
    }

    /// Pins particle `row · columns + column`.
    ///
    /// ```
    /// let cloth = hooke_scenes::Cloth::grid(3, 3).pin(4).build()?;
    /// assert_eq!(cloth.pins(), [4]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin(mut self, particle: usize) -> Self {
        self.pins.push(Pin::Particle(particle));
        self
    }

    /// The plane the grid is laid out in.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Plane};
    /// let curtain = Cloth::grid(2, 2).plane(Plane::Vertical).build()?;
    /// assert_eq!(curtain.positions()[3], hooke_core::Vec3::new(1.0, -1.0, 0.0));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn plane(mut self, plane: Plane) -> Self {
        self.plane = plane;
        self
    }

    /// Rotates the laid-out grid by `angle` radians about `axis` through the
    /// origin (right-hand rule), before the offset.
    ///
    /// ```
    /// use std::f64::consts::FRAC_PI_2;
    /// let cloth = hooke_scenes::Cloth::grid(2, 2).rotate([0.0, 0.0, 1.0], FRAC_PI_2).build()?;
    /// assert!((cloth.positions()[1] - nalgebra::Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-12);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn rotate(mut self, axis: [f64; 3], angle: f64) -> Self {
        self.rotation = Some((axis, angle));
        self
    }

    /// Translates the cloth by `offset` m, after any rotation.
    ///
    /// ```
    /// let cloth = hooke_scenes::Cloth::grid(2, 2).offset([0.0, 2.0, 0.0]).build()?;
    /// assert_eq!(cloth.positions()[0], hooke_core::Vec3::new(0.0, 2.0, 0.0));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn offset(mut self, offset: [f64; 3]) -> Self {
        self.offset = offset;
        self
    }

    /// Validates the description and builds the body: two surface triangles
    /// per cell, counter-clockwise seen from +y (horizontal) or +z
    /// (vertical) before rotation.
    ///
    /// # Errors
    /// [`SceneError`] naming the first bad field: fewer than 2 columns or
    /// rows, a size, mass or spring parameter that is not finite and
    /// positive (non-negative for springs), a rotation axis that is zero or
    /// not finite, or a pin on a particle the grid does not have.
    pub fn build(self) -> Result<Body, SceneError> {
        let (nx, ny) = (
            count("cloth columns", self.columns, 2)?,
            count("cloth rows", self.rows, 2)?,
        );
        let particles = grid_points("cloth grid", &[nx, ny], 0)?;
        let dx = positive("cloth width", self.width)? / (nx - 1) as f64;
        let dy = positive("cloth height", self.height)? / (ny - 1) as f64;
        let total = self.mass.total(self.width * self.height)?;
        validate_families(&[
            (Family::Stretch, self.stretch),
            (Family::Shear, self.shear),
            (Family::Bend, self.bend),
        ])?;
        let rotation = match self.rotation {
            Some((axis, angle)) => rotation(axis, angle)?,
            None => Rotation3::identity(),
        };
        let offset = finite_vector("cloth offset", self.offset)?;
        let index = |row: usize, col: usize| row * nx + col;
        let mut positions = Vec::with_capacity(particles);
        let mut masses = Vec::with_capacity(particles);
        let cell_mass = total / ((nx - 1) * (ny - 1)) as f64;
        for row in 0..ny {
            for col in 0..nx {
                let (u, v) = (col as f64 * dx, row as f64 * dy);
                let local = match self.plane {
                    Plane::Horizontal => Vec3::new(u, 0.0, v),
                    Plane::Vertical => Vec3::new(u, -v, 0.0),
                };
                positions.push(rotation * local + offset);
                let cells = [row > 0, row + 1 < ny].iter().filter(|&&r| r).count()
                    * [col > 0, col + 1 < nx].iter().filter(|&&c| c).count();
                masses.push(cell_mass * cells as f64 / 4.0);
            }
        }
        let mut springs = SpringSet::new(&positions);
        // Neighbours of each family as (rows down, columns across).
        let families = [
            (Family::Stretch, self.stretch, [(0, 1), (1, 0)]),
            (Family::Shear, self.shear, [(1, 1), (1, -1)]),
            (Family::Bend, self.bend, [(0, 2), (2, 0)]),
        ];
        for (family, params, neighbours) in families {
            for row in 0..ny {
                for col in 0..nx {
                    for (down, across) in neighbours {
                        let (r, c) = (row + down, col.checked_add_signed(across));
                        if let Some(c) = c.filter(|&c| c < nx && r < ny) {
                            springs.add(index(row, col), index(r, c), family, params)?;
                        }
                    }
                }
            }
        }
        let mut triangles = Vec::with_capacity(2 * (nx - 1) * (ny - 1));
        for row in 0..ny - 1 {
            for col in 0..nx - 1 {
                let (a, b) = (index(row, col), index(row, col + 1));
                let (c, d) = (index(row + 1, col + 1), index(row + 1, col));
                triangles.extend([[a, c, b], [a, d, c]]);
            }
        }
        let pins = self
            .pins
            .iter()
            .flat_map(|pin| pin.particles(nx, ny))
            .collect();
        let springs = springs.into_springs();
        Body::from_parts(
            masses,
            positions,
            springs,
            pins,
            (triangles, true),
            Vec::new(),
        )
    }
}
