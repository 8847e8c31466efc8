//! [`Solid`]: a tetrahedral mesh with springs on its edges.

use crate::body::Body;
use crate::error::SceneError;
use crate::material::{Mass, Springs};
use crate::mesh::{TET_EDGES, TetMesh, lump};
use crate::spring::{Family, SpringSet, validate_families};
use crate::volume::{Volume, positively_oriented};

/// A tetrahedral mesh made into a body: one particle per vertex,
/// [`Family::Edge`] springs on the unique tet edges, each tet's mass
/// (density × volume) split equally over its four corners, and the faces
/// used by exactly one tet as its outward surface. The mesh's tets are
/// the body's volume elements ([`Body::tets`], reordered where needed to a
/// positive volume), of the modulus [`Solid::volume`] sets.
///
/// ```
/// use hooke_scenes::{Mass, Solid, TetMesh};
/// let tet = TetMesh::new(
///     [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     [[0, 1, 2, 3]],
/// );
/// let solid = Solid::new(tet).mass(Mass::Density(600.0)).edges(1e4).build()?;
/// assert_eq!(solid.springs().len(), 6);
/// assert_eq!(solid.triangles().len(), 4);
/// assert!((solid.total_mass() - 100.0).abs() < 1e-12); // 600 kg/m³ × 1/6 m³
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Solid {
    mesh: TetMesh,
    mass: Mass,
    edges: Option<Springs>,
    volume: Volume,
    pins: Vec<usize>,
}

impl Solid {
    /// A solid of `mesh`, 1000 kg/m³, with no springs until edges are set.
    pub fn new(mesh: TetMesh) -> Self {
        Self {
            mesh,
            mass: Mass::Density(1000.0),
            edges: None,
            volume: Volume::Auto,
            pins: Vec::new(),
        }
    }

    /// Total mass, or density in kg/m³.
    ///
    /// ```
    /// use hooke_scenes::{Mass, Solid, TetMesh};
    /// let tet = TetMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [[0, 1, 2, 3]]);
    /// assert_eq!(Solid::new(tet).mass(Mass::Total(2.0)).build()?.masses(), [0.5; 4]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn mass(mut self, mass: Mass) -> Self {
        self.mass = mass;
        self
    }

    /// Springs on the unique tet edges.
    ///
    /// ```
    /// use hooke_scenes::{Solid, Springs, TetMesh};
    /// let tet = TetMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [[0, 1, 2, 3]]);
    /// let solid = Solid::new(tet).edges(Springs::modulus(10.0)).build()?;
    /// assert_eq!(solid.springs()[0].stiffness, 10.0); // edge 0–1 has length 1
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn edges(mut self, springs: impl Into<Springs>) -> Self {
        self.edges = Some(springs.into());
        self
    }

    /// The modulus of the volume elements (default [`Volume::Auto`]: the
    /// bulk modulus `κ = Σ k L² / (9 V)` of the edge springs, see
    /// [`Volume`] for why).
    ///
    /// ```
    /// use hooke_scenes::{Solid, TetMesh, Volume};
    /// let tet = TetMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [[0, 1, 2, 3]]);
    /// let solid = Solid::new(tet).edges(1e3).volume(Volume::Off).build()?;
    /// assert_eq!((solid.tets(), solid.volume_modulus()), (&[[0, 1, 2, 3]][..], 0.0));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn volume(mut self, volume: Volume) -> Self {
        self.volume = volume;
        self
    }

    /// Pins vertex `particle`.
    ///
    /// ```
    /// use hooke_scenes::{Solid, TetMesh};
    /// let tet = TetMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [[0, 1, 2, 3]]);
    /// assert_eq!(Solid::new(tet).pin(3).build()?.pins(), [3]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin(mut self, particle: usize) -> Self {
        self.pins.push(particle);
        self
    }

    /// Validates the mesh and parameters and builds the body.
    ///
    /// # Errors
    /// [`SceneError`] for a mesh with no tets, a vertex that is not finite
    /// or not used, a tet naming a missing vertex, of zero volume, or
    /// oriented opposite to tet 0, a mass, spring parameter or volume
    /// modulus out of range, or a pin out of range.
    pub fn build(self) -> Result<Body, SceneError> {
        let mesh = self.mesh;
        let (volumes, sign) = mesh.checked_volumes()?;
        let total = self.mass.total(volumes.iter().sum())?;
        validate_families(&[(Family::Edge, self.edges)])?;
        let mut springs = SpringSet::new(&mesh.vertices);
        for t in &mesh.tets {
            for (c, d) in TET_EDGES {
                springs.add(t[c], t[d], Family::Edge, self.edges)?;
            }
        }
        let masses = lump(mesh.vertices.len(), &mesh.tets, &volumes, total);
        let triangles = mesh.boundary_faces(sign);
        let springs = springs.into_springs();
        let tets = mesh
            .tets
            .iter()
            .map(|&t| positively_oriented(t, &mesh.vertices))
            .collect();
        Body::from_parts(
            masses,
            mesh.vertices,
            springs,
            self.pins,
            (triangles, false),
            Vec::new(),
        )?
        .with_tets(tets, self.volume)
    }
}
