//! [`Layered`]: the layered model — a surface, a copy of it moved inward,
//! and springs between the two.

use hooke_core::Vec3;

use crate::body::Body;
use crate::error::{SceneError, positive};
use crate::material::{Mass, Springs};
use crate::mesh::{MeshEdge, TriangleMesh, lump};
use crate::spring::{Family, SpringSet, validate_families};

/// A surface of `n` vertices copied to an inner layer, `2n` particles:
/// vertex `v` is particle `v`, its copy particle `n + v`, at
///
/// ```text
/// x'ᵥ = xᵥ − t n̂ᵥ,   n̂ᵥ = Σ (b − a) × (c − a) / |Σ (b − a) × (c − a)|
/// ```
///
/// with `t` the thickness and the sum over the triangles `(a, b, c)` at `v`
/// (the area-weighted vertex normal, outward for counter-clockwise
/// triangles). Springs: [`Family::Edge`] on every surface edge of both
/// layers, [`Family::Link`] from each vertex to its copy, and
/// [`Family::Cross`] from each end of a surface edge to the copy of the
/// other end — so the layer pair resists shear as well as stretch, which a
/// single surface of springs does not. The thickness should be smaller than
/// the surface's radius of curvature, or the inner layer folds over itself.
///
/// ```
/// use hooke_scenes::{Family, Layered, TriangleMesh};
/// let tet = TriangleMesh::new(
///     [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// );
/// let body = Layered::new(tet, 0.1).surface(1e3).links(1e3).cross(5e2).build()?;
/// assert_eq!(body.particle_count(), 8);
/// assert_eq!(body.springs_of(Family::Edge).count(), 2 * 6);
/// assert_eq!(body.springs_of(Family::Link).count(), 4);
/// assert_eq!(body.springs_of(Family::Cross).count(), 2 * 6);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Layered {
    mesh: TriangleMesh,
    thickness: f64,
    mass: Mass,
    surface: Option<Springs>,
    links: Option<Springs>,
    cross: Option<Springs>,
    pins: Vec<usize>,
}

impl Layered {
    /// A layered body of `mesh` with its inner layer `thickness` m inside,
    /// 1000 kg/m³, with no springs until a family is set.
    pub fn new(mesh: TriangleMesh, thickness: f64) -> Self {
        Self {
            mesh,
            thickness,
            mass: Mass::Density(1000.0),
            surface: None,
            links: None,
            cross: None,
            pins: Vec::new(),
        }
    }

    /// Total mass, or density in kg/m³ of the shell between the layers
    /// (area × thickness); each vertex's lumped share (a third of each
    /// triangle's) is split equally between it and its copy.
    ///
    /// ```
    /// use hooke_scenes::{Layered, Mass, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// let body = Layered::new(tri, 0.1).mass(Mass::Total(6.0)).build()?;
    /// assert_eq!(body.masses(), [1.0; 6]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn mass(mut self, mass: Mass) -> Self {
        self.mass = mass;
        self
    }

    /// Springs on the surface edges of both layers.
    ///
    /// ```
    /// use hooke_scenes::{Layered, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert_eq!(Layered::new(tri, 0.1).surface(1e3).build()?.springs().len(), 6);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn surface(mut self, springs: impl Into<Springs>) -> Self {
        self.surface = Some(springs.into());
        self
    }

    /// Springs from each vertex to its copy, of rest length the thickness.
    ///
    /// ```
    /// use hooke_scenes::{Layered, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// let body = Layered::new(tri, 0.25).links(1e3).build()?;
    /// assert!(body.springs().iter().all(|s| (s.rest_length - 0.25).abs() < 1e-12));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn links(mut self, springs: impl Into<Springs>) -> Self {
        self.links = Some(springs.into());
        self
    }

    /// Springs from each end of a surface edge to the other end's copy.
    ///
    /// ```
    /// use hooke_scenes::{Layered, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert_eq!(Layered::new(tri, 0.1).cross(1e3).build()?.springs().len(), 6);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn cross(mut self, springs: impl Into<Springs>) -> Self {
        self.cross = Some(springs.into());
        self
    }

    /// Pins particle `particle` (`v` for a surface vertex, `n + v` for its
    /// copy).
    ///
    /// ```
    /// use hooke_scenes::{Layered, TriangleMesh};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// assert_eq!(Layered::new(tri, 0.1).pin(0).pin(3).build()?.pins(), [0, 3]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin(mut self, particle: usize) -> Self {
        self.pins.push(particle);
        self
    }

    /// Validates the mesh and parameters and builds the body. Its surface
    /// is the outer triangles and the inner ones reversed (facing the
    /// space inside the inner layer).
    ///
    /// # Errors
    /// [`SceneError`] for a thickness that is not finite and positive, a
    /// mesh with no triangles, a vertex that is not finite or not used, a
    /// triangle naming a missing vertex or of zero area, an edge shared by
    /// more than two triangles, a vertex whose normal vanishes, a mass or
    /// spring parameter out of range, or a pin out of range.
    pub fn build(self) -> Result<Body, SceneError> {
        let thickness = positive("layer thickness", self.thickness)?;
        let mesh = self.mesh;
        let areas = mesh.checked_areas()?;
        let edges = mesh.edges()?;
        let total = self.mass.total(areas.iter().sum::<f64>() * thickness)?;
        validate_families(&[
            (Family::Edge, self.surface),
            (Family::Link, self.links),
            (Family::Cross, self.cross),
        ])?;
        let n = mesh.vertices.len();
        let mut normals = vec![Vec3::zeros(); n];
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.vertices[i]);
            let weighted = (b - a).cross(&(c - a));
            for &v in t {
                normals[v] += weighted;
            }
        }
        let mut positions = mesh.vertices.clone();
        for (vertex, normal) in normals.iter().enumerate() {
            let unit = normal
                .try_normalize(f64::MIN_POSITIVE)
                .ok_or(SceneError::ZeroNormal { vertex })?;
            positions.push(mesh.vertices[vertex] - thickness * unit);
        }
        let mut springs = SpringSet::new(&positions);
        for layer in [0, n] {
            for MeshEdge { ends: [a, b], .. } in &edges {
                springs.add(layer + a, layer + b, Family::Edge, self.surface)?;
            }
        }
        for v in 0..n {
            springs.add(v, n + v, Family::Link, self.links)?;
        }
        for MeshEdge { ends: [a, b], .. } in &edges {
            springs.add(*a, n + b, Family::Cross, self.cross)?;
            springs.add(*b, n + a, Family::Cross, self.cross)?;
        }
        let shares = lump(n, &mesh.triangles, &areas, total);
        let masses = shares.iter().chain(&shares).map(|m| m / 2.0).collect();
        let inner = mesh
            .triangles
            .iter()
            .map(|&[a, b, c]| [n + a, n + c, n + b]);
        let triangles = mesh.triangles.iter().copied().chain(inner).collect();
        let springs = springs.into_springs();
        Body::from_parts(
            masses,
            positions,
            springs,
            self.pins,
            (triangles, false),
            Vec::new(),
        )
    }
}
