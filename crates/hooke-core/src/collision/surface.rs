//! [`CollisionMesh`]: the collision surfaces of a system — triangles grouped
//! by body, their unique edges and the particles on them.
//!
//! Contact in the implicit step is a sum over pairs of surface primitives
//! (Li et al., *Incremental Potential Contact*, 2020, §4): a vertex against
//! a triangle and an edge against an edge. Both kinds come from the
//! triangles alone: the edges are the triangles' sides, each listed once per
//! surface, and the vertices are the particles on some triangle. Every
//! primitive remembers its *group* — the surface (body) it belongs to — so
//! that the broad phase can leave out the pairs within a body that does not
//! collide with itself.
//!
//! Assumptions, which the mesh does not check
//! ([`SystemBuilder`](crate::SystemBuilder) does): a particle lies on one
//! surface at most (bodies share no particles), and a triangle names three
//! different particles.

/// The collision surfaces of a system: triangles (particle indices) grouped
/// by body, with their unique edges and the particles on them.
///
/// Each [`add_surface`](CollisionMesh::add_surface) is a new group. The
/// primitives are numbered across groups: triangles in the order added,
/// edges group by group (sorted within a group), vertices sorted by
/// particle index.
///
/// ```
/// use hooke_core::collision::surface::CollisionMesh;
/// let mut mesh = CollisionMesh::new();
/// // A square of two triangles, and a single triangle of another body.
/// let cloth = mesh.add_surface(&[[0, 1, 2], [1, 3, 2]], true);
/// let other = mesh.add_surface(&[[4, 5, 6]], false);
/// assert_eq!(mesh.edges().len(), 5 + 3);
/// assert_eq!(mesh.vertices(), &[0, 1, 2, 3, 4, 5, 6]);
/// assert!(mesh.collides(cloth, cloth) && mesh.collides(cloth, other));
/// assert!(!mesh.collides(other, other));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CollisionMesh {
    triangles: Vec<[usize; 3]>,
    triangle_groups: Vec<u32>,
    edges: Vec<[usize; 2]>,
    edge_groups: Vec<u32>,
    vertices: Vec<usize>,
    vertex_groups: Vec<u32>,
    /// Per group: whether it collides with itself.
    self_collision: Vec<bool>,
    /// Per group: whether it has a triangle.
    nonempty: Vec<bool>,
}

impl CollisionMesh {
    /// An empty mesh.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one body's surface: its triangles in system particle indices,
    /// and whether pairs of primitives within it collide (self-collision).
    /// Each call is a new group; returns its index (0, 1, …).
    ///
    /// The surface's edges are the sides `{a, b}`, `{b, c}`, `{c, a}` of its
    /// triangles, stored once each with the smaller index first; its
    /// vertices are the particles on its triangles. Costs `O(m log m)` for
    /// `m` triangles, plus a merge of the vertex list when the new particles
    /// do not all come after those already on the mesh.
    pub fn add_surface(&mut self, triangles: &[[usize; 3]], self_collision: bool) -> usize {
        let group = self.self_collision.len();
        let tag = u32::try_from(group).expect("fewer than 2³² surfaces");
        self.self_collision.push(self_collision);
        self.nonempty.push(!triangles.is_empty());

        self.triangles.extend_from_slice(triangles);
        self.triangle_groups
            .extend(std::iter::repeat_n(tag, triangles.len()));

        let start = self.edges.len();
        self.edges.extend(
            triangles
                .iter()
                .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]].map(|[p, q]| [p.min(q), p.max(q)])),
        );
        self.edges[start..].sort_unstable();
        let unique = dedup_len(&mut self.edges[start..]);
        self.edges.truncate(start + unique);
        self.edge_groups.resize(self.edges.len(), tag);

        let mut vertices: Vec<usize> = triangles.iter().flatten().copied().collect();
        vertices.sort_unstable();
        vertices.dedup();
        if self
            .vertices
            .last()
            .is_none_or(|&last| vertices.first().is_none_or(|&p| p > last))
        {
            self.vertex_groups
                .extend(std::iter::repeat_n(tag, vertices.len()));
            self.vertices.extend(vertices);
        } else {
            let old: Vec<(usize, u32)> = self
                .vertices
                .iter()
                .copied()
                .zip(self.vertex_groups.iter().copied())
                .collect();
            self.vertices.clear();
            self.vertex_groups.clear();
            let (mut i, mut j) = (0, 0);
            while i < old.len() || j < vertices.len() {
                if j == vertices.len() || (i < old.len() && old[i].0 <= vertices[j]) {
                    self.vertices.push(old[i].0);
                    self.vertex_groups.push(old[i].1);
                    i += 1;
                } else {
                    self.vertices.push(vertices[j]);
                    self.vertex_groups.push(tag);
                    j += 1;
                }
            }
        }
        group
    }

    /// The triangles, in particle indices, in the order added.
    #[must_use]
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// The unique undirected edges of the triangles, smaller particle index
    /// first, once per group: group by group, sorted within a group.
    #[must_use]
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.edges
    }

    /// The particles on some triangle, sorted (each once, since a particle
    /// lies on one surface).
    #[must_use]
    pub fn vertices(&self) -> &[usize] {
        &self.vertices
    }

    /// The number of groups (calls of [`add_surface`](Self::add_surface)),
    /// empty ones included.
    #[must_use]
    pub fn group_count(&self) -> usize {
        self.self_collision.len()
    }

    /// Whether group `g` collides with itself.
    ///
    /// # Panics
    /// If there is no group `g`.
    #[must_use]
    pub fn self_collides(&self, g: usize) -> bool {
        self.self_collision[g]
    }

    /// The group of triangle `t`.
    ///
    /// # Panics
    /// If there is no triangle `t`.
    #[must_use]
    pub fn triangle_group(&self, t: usize) -> usize {
        self.triangle_groups[t] as usize
    }

    /// The group of edge `e` (an index into [`edges`](Self::edges)).
    ///
    /// # Panics
    /// If there is no edge `e`.
    #[must_use]
    pub fn edge_group(&self, e: usize) -> usize {
        self.edge_groups[e] as usize
    }

    /// The group of vertex `v` (an index into [`vertices`](Self::vertices),
    /// not a particle index).
    ///
    /// # Panics
    /// If there is no vertex `v`.
    #[must_use]
    pub fn vertex_group(&self, v: usize) -> usize {
        self.vertex_groups[v] as usize
    }

    /// Whether primitives of groups `g` and `h` may collide: different
    /// groups always, the same group only if it self-collides.
    ///
    /// # Panics
    /// If `g == h` and there is no such group.
    #[must_use]
    pub fn collides(&self, g: usize, h: usize) -> bool {
        g != h || self.self_collision[g]
    }

    /// Whether the mesh has no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Whether any pair of primitives at all can collide: some group with a
    /// triangle self-collides, or two groups have triangles.
    #[must_use]
    pub fn has_pairs(&self) -> bool {
        let mut groups = self.nonempty.iter().zip(&self.self_collision);
        let mut nonempty = 0;
        groups.any(|(&has, &own)| {
            nonempty += usize::from(has);
            has && (own || nonempty >= 2)
        })
    }
}

/// Moves the distinct runs of a sorted slice to its front; returns their
/// number.
fn dedup_len<T: PartialEq + Copy>(items: &mut [T]) -> usize {
    let mut kept = 0;
    for i in 0..items.len() {
        if kept == 0 || items[i] != items[kept - 1] {
            items[kept] = items[i];
            kept += 1;
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_are_unique_per_group_and_vertices_sorted() {
        let mut mesh = CollisionMesh::new();
        let g = mesh.add_surface(&[[3, 1, 2], [1, 3, 4]], false);
        let h = mesh.add_surface(&[[0, 5, 6]], true);
        assert_eq!((g, h), (0, 1));
        assert_eq!(
            mesh.edges(),
            &[
                [1, 2],
                [1, 3],
                [1, 4],
                [2, 3],
                [3, 4],
                [0, 5],
                [0, 6],
                [5, 6]
            ]
        );
        assert_eq!(mesh.vertices(), &[0, 1, 2, 3, 4, 5, 6]);
        let groups: Vec<usize> = (0..7).map(|v| mesh.vertex_group(v)).collect();
        assert_eq!(groups, [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!((mesh.edge_group(4), mesh.edge_group(5)), (0, 1));
        assert_eq!((mesh.triangle_group(1), mesh.triangle_group(2)), (0, 1));
        assert_eq!(mesh.group_count(), 2);
        assert!(mesh.self_collides(1) && !mesh.self_collides(0));
    }

    #[test]
    fn pairs_need_a_self_colliding_surface_or_two_surfaces() {
        let mut mesh = CollisionMesh::new();
        assert!(mesh.is_empty() && !mesh.has_pairs());
        mesh.add_surface(&[[0, 1, 2]], false);
        assert!(!mesh.is_empty() && !mesh.has_pairs());
        mesh.add_surface(&[], true);
        assert!(!mesh.has_pairs(), "an empty surface has nothing to collide");
        mesh.add_surface(&[[3, 4, 5]], false);
        assert!(mesh.has_pairs());
        let mut own = CollisionMesh::new();
        own.add_surface(&[[0, 1, 2]], true);
        assert!(own.has_pairs());
        assert!(own.collides(0, 0) && !mesh.collides(0, 0) && mesh.collides(0, 2));
    }
}
