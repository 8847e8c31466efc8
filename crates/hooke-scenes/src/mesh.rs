//! Meshes as plain data — [`TriangleMesh`] and [`TetMesh`] — and the checks
//! and measures (areas, volumes, boundary, lumped masses) the builders take
//! from them.

use std::collections::HashMap;

use hooke_core::Vec3;

use crate::error::{Element, SceneError, count};

/// Elements whose area (volume) is below this fraction of their longest
/// edge squared (cubed) count as degenerate.
const DEGENERATE: f64 = 1e-12;

/// A triangle surface: vertex positions and triangles indexing them
/// (counter-clockwise seen from outside on a closed surface).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriangleMesh {
    /// Vertex positions in m.
    pub vertices: Vec<Vec3>,
    /// Corner indices of each triangle.
    pub triangles: Vec<[usize; 3]>,
}

/// A tetrahedral mesh: vertex positions and tets indexing them. All tets
/// must share one orientation (the sign of `det(b − a, c − a, d − a)`),
/// either one.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TetMesh {
    /// Vertex positions in m.
    pub vertices: Vec<Vec3>,
    /// Corner indices of each tetrahedron.
    pub tets: Vec<[usize; 4]>,
}

/// An edge of a triangle mesh and the corners opposite it.
pub(crate) struct MeshEdge {
    /// The edge's ends.
    pub(crate) ends: [usize; 2],
    /// The third corner of each triangle sharing the edge (one or two).
    pub(crate) opposite: Vec<usize>,
}

impl TriangleMesh {
    /// A mesh from positions and triangles.
    ///
    /// ```
    /// let quad = hooke_scenes::TriangleMesh::new(
    ///     [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     [[0, 1, 2], [0, 2, 3]],
    /// );
    /// assert_eq!(quad.vertices.len(), 4);
    /// ```
    #[must_use]
    pub fn new(
        vertices: impl IntoIterator<Item = [f64; 3]>,
        triangles: impl IntoIterator<Item = [usize; 3]>,
    ) -> Self {
        Self {
            vertices: vertices.into_iter().map(Vec3::from).collect(),
            triangles: triangles.into_iter().collect(),
        }
    }

    /// Checks the mesh and returns each triangle's area.
    pub(crate) fn checked_areas(&self) -> Result<Vec<f64>, SceneError> {
        count("mesh triangles", self.triangles.len(), 1)?;
        check_elements(&self.vertices, &self.triangles, Element::Triangle)?;
        self.triangles
            .iter()
            .enumerate()
            .map(|(n, &t)| {
                let [a, b, c] = t.map(|i| self.vertices[i]);
                let area = 0.5 * (b - a).cross(&(c - a)).norm();
                let longest = longest_edge(&t.map(|i| self.vertices[i]));
                if area > DEGENERATE * longest * longest {
                    Ok(area)
                } else {
                    Err(SceneError::DegenerateElement {
                        element: Element::Triangle(n),
                        measure: area,
                    })
                }
            })
            .collect()
    }

    /// The unique edges in order of first use, each with the corners
    /// opposite it in the one or two triangles that share it.
    pub(crate) fn edges(&self) -> Result<Vec<MeshEdge>, SceneError> {
        let mut index: HashMap<(usize, usize), usize> = HashMap::new();
        let mut edges: Vec<MeshEdge> = Vec::new();
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b, opposite) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let n = *index.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    edges.push(MeshEdge {
                        ends: [a, b],
                        opposite: Vec::new(),
                    });
                    edges.len() - 1
                });
                edges[n].opposite.push(opposite);
                if edges[n].opposite.len() > 2 {
                    return Err(SceneError::NonManifoldEdge {
                        a: a.min(b),
                        b: a.max(b),
                        triangles: edges[n].opposite.len(),
                    });
                }
            }
        }
        Ok(edges)
    }
}

impl TetMesh {
    /// A mesh from positions and tetrahedra.
    ///
    /// ```
    /// let tet = hooke_scenes::TetMesh::new(
    ///     [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ///     [[0, 1, 2, 3]],
    /// );
    /// assert_eq!(tet.tets.len(), 1);
    /// ```
    #[must_use]
    pub fn new(
        vertices: impl IntoIterator<Item = [f64; 3]>,
        tets: impl IntoIterator<Item = [usize; 4]>,
    ) -> Self {
        Self {
            vertices: vertices.into_iter().map(Vec3::from).collect(),
            tets: tets.into_iter().collect(),
        }
    }

    /// Checks the mesh and returns each tet's unsigned volume and the
    /// orientation (+1 or −1) they share.
    pub(crate) fn checked_volumes(&self) -> Result<(Vec<f64>, f64), SceneError> {
        count("mesh tets", self.tets.len(), 1)?;
        check_elements(&self.vertices, &self.tets, Element::Tet)?;
        let mut sign = 0.0;
        let mut volumes = Vec::with_capacity(self.tets.len());
        for (n, &t) in self.tets.iter().enumerate() {
            let corners = t.map(|i| self.vertices[i]);
            let volume = signed_volume(corners);
            if is_flat(corners) {
                return Err(SceneError::DegenerateElement {
                    element: Element::Tet(n),
                    measure: volume.abs(),
                });
            }
            if n == 0 {
                sign = volume.signum();
            } else if (volume > 0.0) != (sign > 0.0) {
                return Err(SceneError::InvertedTet { tet: n, volume });
            }
            volumes.push(volume.abs());
        }
        Ok((volumes, sign))
    }

    /// Faces used by exactly one tet, oriented outward, for a mesh whose
    /// tets have orientation `sign`.
    pub(crate) fn boundary_faces(&self, sign: f64) -> Vec<[usize; 3]> {
        // Outward faces of a positively oriented tet (a, b, c, d).
        const FACES: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let mut uses: HashMap<[usize; 3], (usize, [usize; 3])> = HashMap::new();
        let mut order = Vec::new();
        for t in &self.tets {
            for f in FACES {
                let mut face = f.map(|k| t[k]);
                if sign < 0.0 {
                    face.swap(1, 2);
                }
                let mut key = face;
                key.sort_unstable();
                let entry = uses.entry(key).or_insert_with(|| {
                    order.push(key);
                    (0, face)
                });
                entry.0 += 1;
            }
        }
        order
            .iter()
            .filter_map(|key| {
                let (count, face) = uses[key];
                (count == 1).then_some(face)
            })
            .collect()
    }
}

/// The six edges of a tet as pairs of corner numbers.
pub(crate) const TET_EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// `det(b − a, c − a, d − a) / 6`.
pub(crate) fn signed_volume([a, b, c, d]: [Vec3; 4]) -> f64 {
    (b - a).cross(&(c - a)).dot(&(d - a)) / 6.0
}

/// Whether a tet with these corners is degenerate: its volume at most
/// [`DEGENERATE`] times its longest edge cubed (the threshold
/// [`hooke_core::Tet::at_rest`] rejects too).
pub(crate) fn is_flat(corners: [Vec3; 4]) -> bool {
    signed_volume(corners).abs() <= DEGENERATE * longest_edge(&corners).powi(3)
}

fn longest_edge(corners: &[Vec3]) -> f64 {
    let mut longest: f64 = 0.0;
    for (k, p) in corners.iter().enumerate() {
        for q in &corners[k + 1..] {
            longest = longest.max((p - q).norm());
        }
    }
    longest
}

/// Finite vertices, indices in range, every vertex used.
fn check_elements<const K: usize>(
    vertices: &[Vec3],
    elements: &[[usize; K]],
    element: fn(usize) -> Element,
) -> Result<(), SceneError> {
    if let Some((vertex, v)) = vertices
        .iter()
        .enumerate()
        .find(|(_, v)| !v.iter().all(|c| c.is_finite()))
    {
        return Err(SceneError::NonFiniteVertex {
            vertex,
            value: (*v).into(),
        });
    }
    let mut used = vec![false; vertices.len()];
    for (n, e) in elements.iter().enumerate() {
        for &vertex in e {
            *used
                .get_mut(vertex)
                .ok_or_else(|| SceneError::VertexOutOfRange {
                    element: element(n),
                    vertex,
                    vertices: vertices.len(),
                })? = true;
        }
    }
    match used.iter().position(|&u| !u) {
        Some(vertex) => Err(SceneError::UnusedVertex { vertex }),
        None => Ok(()),
    }
}

/// Particle masses from element measures: `total` shared out in proportion
/// to each element's measure, each element's share split equally over its
/// `K` corners.
pub(crate) fn lump<const K: usize>(
    vertices: usize,
    elements: &[[usize; K]],
    measures: &[f64],
    total: f64,
) -> Vec<f64> {
    let sum: f64 = measures.iter().sum();
    let mut masses = vec![0.0; vertices];
    for (e, &measure) in elements.iter().zip(measures) {
        for &v in e {
            masses[v] += total * measure / sum / K as f64;
        }
    }
    masses
}
