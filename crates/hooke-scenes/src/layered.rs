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
/// triangle `(a, b, c)` and its copy, averaged over the six ways to cut it
/// into three tets. For an order `(p, q, r)` of the corners, and `v'` the
/// copy of `v`, the cut is `(p, q, r, p')`, `(q, r, p', q')` and
/// `(r, p', q', r')`; each of the six orders is one cut, weighted `1/6`
/// ([`Body::tet_weights`]). A tet on the whole triangle or its whole copy
/// belongs to two cuts (weight `1/3`, six such), the others to one (`1/6`,
/// six): twelve tets a prism, whose weighted volumes sum to the shell's.
/// Any single cut depends on the order of the corners, and a body of
/// such prisms is chiral: the built-in layered ball, dropped straight onto
/// a floor, landed turning and rolled 0.27 m away in 3 s. The average
/// treats the three corners alike, and the same ball lands and bounces in
/// place, like its springs alone.
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
    /// assert_eq!((body.tets().len(), body.volume_modulus()), (12, 1e4));
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
        let (tets, weights) = prism_tets(&mesh.triangles, n, &positions)?;
        let springs = springs.into_springs();
        Body::from_parts(
            masses,
            positions,
            springs,
            self.pins,
            (triangles, false),
            Vec::new(),
        )?
        .with_weighted_tets(tets, weights, self.volume)
    }
}

/// The twelve tets of each triangle's prism between the surface
/// (particles `0..n`) and its copy (`n..2n`) and their weights, the six
/// cuts of [`Layered`] averaged, each oriented to a positive volume at
/// `positions`. A tet that is flat at rest (a copied corner in the plane
/// of a triangle whose corner's normal lies in it) has no volume to keep
/// and is left out; the prism's weighted volume is unchanged.
///
/// # Errors
/// [`SceneError::DegenerateElement`] naming the triangle whose prism is
/// flat (all twelve tets are).
fn prism_tets(
    triangles: &[[usize; 3]],
    n: usize,
    positions: &[Vec3],
) -> Result<(Vec<[usize; 4]>, Vec<f64>), SceneError> {
    let mut tets = Vec::with_capacity(12 * triangles.len());
    let mut weights = Vec::with_capacity(12 * triangles.len());
    for (index, &[a, b, c]) in triangles.iter().enumerate() {
        // On the triangle and one copied corner, or on the copy and one
        // corner: in two cuts each. On an edge, the copy of the opposite
        // corner and the copy of one end of the edge: in one cut.
        let triangle = [[a, b, c, n + a], [a, b, c, n + b], [a, b, c, n + c]];
        let copy = [
            [n + a, n + b, n + c, a],
            [n + a, n + b, n + c, b],
            [n + a, n + b, n + c, c],
        ];
        let sides = [
            [a, b, n + c, n + a],
            [b, c, n + a, n + b],
            [c, a, n + b, n + c],
            [b, a, n + c, n + b],
            [c, b, n + a, n + c],
            [a, c, n + b, n + a],
        ];
        let weighted = triangle.iter().chain(&copy).map(|t| (t, 1.0 / 3.0));
        let before = tets.len();
        let mut largest: f64 = 0.0;
        for (&tet, weight) in weighted.chain(sides.iter().map(|t| (t, 1.0 / 6.0))) {
            let corners = tet.map(|p| positions[p]);
            largest = largest.max(signed_volume(corners).abs());
            if !is_flat(corners) {
                tets.push(positively_oriented(tet, positions));
                weights.push(weight);
            }
        }
        if tets.len() == before {
            return Err(SceneError::DegenerateElement {
                element: Element::Prism(index),
                measure: largest,
            });
        }
    }
    Ok((tets, weights))
}
