//! [`Mesh`]: the topology of what is drawn and written, fixed for a run, so
//! that each frame passes only its positions.

use hooke_core::Vec3;

use crate::error::{OutputError, Primitive};

/// The vertex count, triangles and edges of the bodies of a scene.
///
/// Triangles are surfaces (cloth, the hull of a volumetric body); edges are
/// lines (ropes, lattices without a hull). A mesh may hold both, either or
/// neither (a point cloud). Indices are validated once, here; every frame is
/// then checked only for its length and finiteness.
///
/// ```
/// use hooke_viz::Mesh;
/// let rope = Mesh::new(3, Vec::new(), vec![[0, 1], [1, 2]])?;
/// assert_eq!(rope.edges().len(), 2);
/// # Ok::<(), hooke_viz::OutputError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mesh {
    vertex_count: usize,
    triangles: Vec<[u32; 3]>,
    edges: Vec<[u32; 2]>,
}

impl Mesh {
    /// A mesh of `vertex_count` vertices with the given triangles and edges.
    ///
    /// # Errors
    ///
    /// [`OutputError::VertexOutOfRange`] if a triangle or edge names a vertex
    /// `>= vertex_count`; [`OutputError::TooManyVertices`] if `vertex_count`
    /// exceeds `i32::MAX`, the largest index a PLY `int` holds.
    pub fn new(
        vertex_count: usize,
        triangles: Vec<[u32; 3]>,
        edges: Vec<[u32; 2]>,
    ) -> Result<Self, OutputError> {
        if i32::try_from(vertex_count).is_err() {
            return Err(OutputError::TooManyVertices {
                vertices: vertex_count,
            });
        }
        check_indices(Primitive::Triangle, &triangles, vertex_count)?;
        check_indices(Primitive::Edge, &edges, vertex_count)?;
        Ok(Self {
            vertex_count,
            triangles,
            edges,
        })
    }

    /// Number of vertices, which is the number of positions every frame has.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// The triangles, as vertex indices.
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The edges, as vertex indices.
    #[must_use]
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// Checks that `positions` is a frame of this mesh: one finite position
    /// per vertex.
    ///
    /// # Errors
    ///
    /// [`OutputError::PositionCount`] or [`OutputError::NonFinitePosition`].
    pub fn check_frame(&self, positions: &[Vec3]) -> Result<(), OutputError> {
        if positions.len() != self.vertex_count {
            return Err(OutputError::PositionCount {
                expected: self.vertex_count,
                found: positions.len(),
            });
        }
        match positions
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            Some(vertex) => Err(OutputError::NonFinitePosition {
                vertex,
                value: positions[vertex].into(),
            }),
            None => Ok(()),
        }
    }
}

fn check_indices<const N: usize>(
    primitive: Primitive,
    items: &[[u32; N]],
    vertices: usize,
) -> Result<(), OutputError> {
    for (index, item) in items.iter().enumerate() {
        if let Some(&vertex) = item.iter().find(|&&v| v as usize >= vertices) {
            return Err(OutputError::VertexOutOfRange {
                primitive,
                index,
                vertex,
                vertices,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_out_of_range_triangle_vertex() {
        let err = Mesh::new(3, vec![[0, 1, 2], [1, 2, 3]], Vec::new()).unwrap_err();
        assert!(matches!(
            err,
            OutputError::VertexOutOfRange {
                primitive: Primitive::Triangle,
                index: 1,
                vertex: 3,
                vertices: 3
            }
        ));
    }

    #[test]
    fn rejects_out_of_range_edge_vertex() {
        let err = Mesh::new(2, Vec::new(), vec![[0, 2]]).unwrap_err();
        assert!(matches!(
            err,
            OutputError::VertexOutOfRange {
                primitive: Primitive::Edge,
                index: 0,
                vertex: 2,
                ..
            }
        ));
    }

    #[test]
    fn frame_must_match_vertex_count_and_be_finite() {
        let mesh = Mesh::new(2, Vec::new(), vec![[0, 1]]).unwrap();
        assert!(matches!(
            mesh.check_frame(&[Vec3::zeros()]),
            Err(OutputError::PositionCount {
                expected: 2,
                found: 1
            })
        ));
        let bad = [Vec3::zeros(), Vec3::new(0.0, f64::NAN, 0.0)];
        assert!(matches!(
            mesh.check_frame(&bad),
            Err(OutputError::NonFinitePosition { vertex: 1, .. })
        ));
        assert!(mesh.check_frame(&[Vec3::zeros(), Vec3::x()]).is_ok());
    }
}
