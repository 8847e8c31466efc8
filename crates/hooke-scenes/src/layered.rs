//! [`Layered`]: the layered model — a surface, a copy of it moved inward,
//! and springs between the two.

use hooke_core::Vec3;

use crate::body::Body;
use crate::error::{Element, SceneError, positive};
use crate::material::{Mass, Springs};
use crate::mesh::{MeshEdge, TriangleMesh, is_flat, lump, signed_volume};
use crate::spring::{Family, SpringSet, validate_families};
use crate::volume::{Volume, positively_oriented};

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
/// Volume elements ([`Body::tets`], see [`Volume`]): the prism between each
/// triangle `(a, b, c)` and its copy is cut into three tets. With the
/// corners sorted by index, `v₀ < v₁ < v₂`, and `v'` the copy of `v`, they
/// are `(v₀, v₁, v₂, v₀')`, `(v₁, v₂, v₀', v₁')` and `(v₂, v₀', v₁', v₂')`:
/// the diagonal of the side face over the edge `(vᵢ, vⱼ)`, `vᵢ < vⱼ`,
/// always joins `vⱼ` to `vᵢ'`, so two prisms sharing that face cut it
/// alike and the tets fill the shell between the layers without gaps or
/// overlaps.
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
    volume: Volume,
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
            volume: Volume::Auto,
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

    /// The modulus of the prisms' volume elements (default
    /// [`Volume::Auto`]: the bulk modulus `κ = Σ k L² / (9 V)` of the
    /// body's springs, see [`Volume`] for why).
    ///
    /// ```
    /// use hooke_scenes::{Layered, TriangleMesh, Volume};
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// let body = Layered::new(tri, 0.1).surface(1e3).volume(Volume::Modulus(1e4)).build()?;
    /// assert_eq!((body.tets().len(), body.volume_modulus()), (3, 1e4));
    /// // The prism under a right triangle of area ½, 0.1 deep.
    /// assert!((body.rest_volume() - 0.05).abs() < 1e-12);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn volume(mut self, volume: Volume) -> Self {
        self.volume = volume;
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
    /// more than two triangles, a vertex whose normal vanishes, a prism
    /// between the layers that is flat, a mass, spring parameter or volume
    /// modulus out of range, or a pin out of range.
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
        let tets = prism_tets(&mesh.triangles, n, &positions)?;
        let springs = springs.into_springs();
        Body::from_parts(
            masses,
            positions,
            springs,
            self.pins,
            (triangles, false),
            Vec::new(),
        )?
        .with_tets(tets, self.volume)
    }
}

/// The three tets of each triangle's prism between the surface (particles
/// `0..n`) and its copy (`n..2n`), split by the vertex-index rule of
/// [`Layered`], each oriented to a positive volume at `positions`.
///
/// # Errors
/// [`SceneError::DegenerateElement`] naming the triangle whose prism has a
/// flat tet.
fn prism_tets(
    triangles: &[[usize; 3]],
    n: usize,
    positions: &[Vec3],
) -> Result<Vec<[usize; 4]>, SceneError> {
    let mut tets = Vec::with_capacity(3 * triangles.len());
    for (index, triangle) in triangles.iter().enumerate() {
        let mut v = *triangle;
        v.sort_unstable();
        let [v0, v1, v2] = v;
        for tet in [
            [v0, v1, v2, n + v0],
            [v1, v2, n + v0, n + v1],
            [v2, n + v0, n + v1, n + v2],
        ] {
            let corners = tet.map(|p| positions[p]);
            if is_flat(corners) {
                return Err(SceneError::DegenerateElement {
                    element: Element::Prism(index),
                    measure: signed_volume(corners).abs(),
                });
            }
            tets.push(positively_oriented(tet, positions));
        }
    }
    Ok(tets)
}
