//! [`Shell`]: a triangle surface (for example an imported OBJ) with springs
//! on its edges and bending springs across them.

use crate::body::Body;
use crate::error::SceneError;
use crate::material::{Mass, Springs};
use crate::mesh::{MeshEdge, TriangleMesh, lump};
use crate::spring::{Family, SpringSet, validate_families};

/// A surface of triangles made into a body: one particle per vertex,
/// [`Family::Edge`] springs on the unique edges and [`Family::Bend`]
/// springs across every edge two triangles share, joining the two corners
/// opposite it (unless that pair is joined already).
///
/// ```
/// use hooke_scenes::{Family, Shell, TriangleMesh};
/// let quad = TriangleMesh::new(
///     [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     [[0, 1, 2], [0, 2, 3]],
/// );
/// let shell = Shell::new(quad).edges(1e3).bend(10.0).pin(0).build()?;
/// assert_eq!(shell.springs_of(Family::Edge).count(), 5);
/// assert_eq!(shell.springs_of(Family::Bend).count(), 1); // corner 1 to corner 3
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Shell {
    mesh: TriangleMesh,
    mass: Mass,
    edges: Option<Springs>,
    bend: Option<Springs>,
    pins: Vec<usize>,
}

impl Shell {
    /// A shell of `mesh`, 0.2 kg/m², with no springs until a family is set.
    pub fn new(mesh: TriangleMesh) -> Self {
        Self {
            mesh,
            mass: Mass::Density(0.2),
            edges: None,
            bend: None,
            pins: Vec::new(),
        }
    }

    /// Total mass, or areal density in kg/m²; lumped a third of each
    /// triangle's mass to each corner.
    ///
    /// ```
    /// use hooke_scenes::{Mass, Shell, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert_eq!(Shell::new(tri).mass(Mass::Total(3.0)).build()?.masses(), [1.0; 3]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn mass(mut self, mass: Mass) -> Self {
        self.mass = mass;
        self
    }

    /// Springs on the unique triangle edges.
    ///
    /// ```
    /// use hooke_scenes::{Shell, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert_eq!(Shell::new(tri).edges(1e3).build()?.springs().len(), 3);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn edges(mut self, springs: impl Into<Springs>) -> Self {
        self.edges = Some(springs.into());
        self
    }

    /// Bending springs across shared edges, between the opposite corners.
    ///
    /// ```
    /// use hooke_scenes::{Shell, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert!(Shell::new(tri).bend(5.0).build()?.springs().is_empty()); // nothing shared
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn bend(mut self, springs: impl Into<Springs>) -> Self {
        self.bend = Some(springs.into());
        self
    }

    /// Pins vertex `particle`.
    ///
    /// ```
    /// use hooke_scenes::{Shell, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert_eq!(Shell::new(tri).pin(2).build()?.pins(), [2]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin(mut self, particle: usize) -> Self {
        self.pins.push(particle);
        self
    }

    /// Validates the mesh and parameters and builds the body, whose surface
    /// is the mesh's triangles.
    ///
    /// # Errors
    /// [`SceneError`] for a mesh with no triangles, a vertex that is not
    /// finite or not used, a triangle naming a missing vertex or of zero
    /// area, an edge shared by more than two triangles, a mass or spring
    /// parameter out of range, or a pin out of range.
    pub fn build(self) -> Result<Body, SceneError> {
        let mesh = self.mesh;
        let areas = mesh.checked_areas()?;
        let edges = mesh.edges()?;
        let total = self.mass.total(areas.iter().sum())?;
        validate_families(&[(Family::Edge, self.edges), (Family::Bend, self.bend)])?;
        let mut springs = SpringSet::new(&mesh.vertices);
        for MeshEdge { ends: [a, b], .. } in &edges {
            springs.add(*a, *b, Family::Edge, self.edges)?;
        }
        for MeshEdge { opposite, .. } in &edges {
            if let [c, d] = opposite[..] {
                springs.add(c, d, Family::Bend, self.bend)?;
            }
        }
        let masses = lump(mesh.vertices.len(), &mesh.triangles, &areas, total);
        let springs = springs.into_springs();
        Body::from_parts(
            masses,
            mesh.vertices,
            springs,
            self.pins,
            (mesh.triangles, true),
            Vec::new(),
        )
    }
}
