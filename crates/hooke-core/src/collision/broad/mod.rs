//! The broad phase: which pairs of surface primitives may be close.
//!
//! # Boxes
//!
//! Every primitive — a vertex, an edge, a triangle of a
//! [`CollisionMesh`] — gets the axis-aligned box `[lo, hi]` of its
//! particles' positions (at one configuration, or at both ends of a
//! straight-line motion), grown by `d/2` on every side for a search distance
//! `d`. Two primitives at distance `δ` have boxes at most `δ` apart along
//! each axis, so when `δ < d` their grown boxes overlap; for a motion
//! `x(τ) = x0 + τ (x1 − x0)`, every position of a primitive lies in the box
//! of its positions at both ends (a convex hull), so a pair that comes
//! within `d` at some `τ` also has overlapping boxes. The broad phase returns
//! *exactly* the pairs whose boxes overlap (closed boxes,
//! `loₐ ≤ hi_b` and `lo_b ≤ hiₐ` on each axis), minus those that share a
//! particle or whose groups do not collide ([`CollisionMesh::collides`]).
//!
//! # Grid
//!
//! The boxes are entered into a uniform grid of cell side
//! `h = 2.5 × (mean largest side of the triangles' boxes)`: a box lies in
//! the cells `⌊(lo − o)/h⌋ … ⌊(hi − o)/h⌋` per axis (`o` the lower corner
//! of all boxes), one to eight for a typical primitive. An entry is a `u64`,
//! the cell's key in the high bits and the box's index in the low bits: the
//! cell coordinates packed exactly when the grid fits, a hash of them
//! otherwise. Sorting the entries (a radix-friendly sort of plain integers)
//! brings each cell's boxes together, vertices before edges before
//! triangles; within a cell, vertices are paired with triangles and edges
//! with edges, and a pair is reported only in the cell holding the lower
//! corner of the boxes' intersection, `max(loₐ, lo_b)`. Both boxes cover
//! that cell, so each overlapping pair is found exactly once and the output
//! needs no deduplication; it is sorted, so it does not depend on the order
//! of work.
//!
//! A box covering more than 64 cells (a fast primitive in a swept search)
//! goes to a coarser level of the grid, with cells 4, 16, … times larger,
//! the first on which it covers at most 64 cells. Level `ℓ` holds its own
//! boxes and, in a second list, the boxes of the finer levels; a pair is
//! reported on the level of the coarser box. Every box thus costs at most
//! 64 entries, and a search with a few fast primitives costs a few more
//! sorts instead of a test of each fast primitive against every box.
//! Boxes with a non-finite corner (a diverged state) are tested against
//! every box.
//!
//! Why a grid: cloth primitives are all of about one size, so a grid with
//! one cell size finds the pairs with a handful of box tests per primitive,
//! and its whole build is one sort of integers, rebuilt from scratch at
//! every search (a bounding volume hierarchy would need refitting and its
//! traversal branches more; sort-and-sweep along one axis tests a whole
//! slab of a flat cloth, `O(n^{3/2})`). Why our own: parry3d's BVH, the
//! well-kept candidate, works in `f32` unless built for `f64` throughout,
//! and searches a tree against itself for a proximity query only; the
//! contact step needs `f64` boxes, a swept query over a motion, the
//! exclusion of pairs that share a particle or whose surfaces do not
//! collide, and sorted output, which here are one short module.
//!
//! # Parallelism
//!
//! With the `parallel` feature the boxes, the entries, the sort and the
//! pairing (by chunks of cells, each into its own buffer) run on rayon's
//! pool from [`PARALLEL_MIN_PRIMITIVES`] primitives on
//! ([`Parallelism::Auto`]); the result is the same set, sorted, either way.
//! The buffers are kept between calls, so searches allocate nothing once
//! their sizes have settled.

mod grid;
mod pairing;
mod parallel;

use crate::{Parallelism, Parameter, ParameterError, Vec3};

use super::surface::CollisionMesh;
use grid::{Grid, chunk_bounds, fill_boxes, fill_entries, level_of, make_grids};
use pairing::{Found, Scene, gather};
use parallel::{for_each, threads};

/// The most cells a box covers on its level of the grid.
const MAX_CELLS: u64 = 64;
/// The ratio of the cell sides of consecutive levels.
const LEVEL_RATIO: f64 = 4.0;
/// The most levels (a ratio of `4²⁴ ≈ 3·10¹⁴` between the cells of the first
/// and the last); boxes that fit none are tested against every box.
const MAX_LEVELS: usize = 24;
/// The cell side in units of the mean largest side of a triangle's box
/// (by default; [`BroadPhase::with_cell_factor`]). Which pairs a search
/// finds does not depend on it, its time does: against 1.5, a factor of
/// 2.5 took 0.83 of the searches' time in the default scene, 0.93 in the
/// cloth pile, 0.90 in two cloths and 0.90 on a 400 × 400 cloth
/// (`benches/README.md`).
pub const CELL_FACTOR: f64 = 2.5;
/// The level of a box tested against every box.
const WILD: u8 = u8::MAX;
/// Boxes per task when filling entries in parallel.
#[cfg(feature = "parallel")]
const GRAIN: usize = 4096;

/// The number of primitives (vertices, edges and triangles) from which
/// [`Parallelism::Auto`] searches in parallel.
pub const PARALLEL_MIN_PRIMITIVES: usize = 20_000;

/// Candidate pairs of primitives of a [`CollisionMesh`]:
/// `(vertex, triangle)`, the vertex an index into
/// [`CollisionMesh::vertices`], and `(edge, edge)` with the first smaller.
/// Never pairs sharing a particle, only pairs whose groups collide; each
/// list sorted, without duplicates.
#[derive(Debug, Clone, Default)]
pub struct Candidates {
    /// Point–triangle pairs `(vertex, triangle)`.
    pub point_triangle: Vec<(u32, u32)>,
    /// Edge–edge pairs `(e, f)`, `e < f`.
    pub edge_edge: Vec<(u32, u32)>,
}

/// The broad phase: a grid of the primitives' axis-aligned boxes (see the
/// [module documentation](self)). It keeps its buffers between calls, so
/// that calls after the first do not allocate once sizes settle.
///
/// ```
/// use hooke_core::Vec3;
/// use hooke_core::collision::{broad::{BroadPhase, Candidates}, surface::CollisionMesh};
/// let mut mesh = CollisionMesh::new();
/// mesh.add_surface(&[[0, 1, 2]], false);
/// mesh.add_surface(&[[3, 4, 5]], false);
/// // Two parallel triangles 1 cm apart.
/// let x: Vec<Vec3> = [0.0, 0.01]
///     .iter()
///     .flat_map(|&z| [Vec3::new(0.0, 0.0, z), Vec3::new(1.0, 0.0, z), Vec3::new(0.0, 1.0, z)])
///     .collect();
/// let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
/// broad.proximity(&mesh, &x, 0.02, &mut found);
/// assert_eq!(found.point_triangle.len(), 6);
/// broad.proximity(&mesh, &x, 0.005, &mut found);
/// assert!(found.point_triangle.is_empty() && found.edge_edge.is_empty());
/// ```
#[derive(Debug)]
pub struct BroadPhase {
    parallelism: Parallelism,
    /// The cell side in units of the mean largest side of a triangle's box.
    cell_factor: f64,
    /// `[lo, hi]` of every primitive: vertices, then edges, then triangles.
    boxes: Vec<[Vec3; 2]>,
    /// The grid level of every box, or [`WILD`].
    levels: Vec<u8>,
    grids: Vec<Grid>,
    /// Scratch: the first entry of every box.
    offsets: Vec<usize>,
    /// The entries of the boxes of the current level, and of the finer ones.
    own: Vec<u64>,
    finer: Vec<u64>,
    /// Where the pairing chunks start in `own`.
    bounds: Vec<usize>,
    /// The pairs found by each chunk.
    found: Vec<Found>,
}

/// Which primitives a search boxes: the boxes are vertices `0..v`, edges
/// `v..v + e`, triangles `v + e..`.
#[derive(Debug, Clone, Copy)]
struct Layout {
    vertices: usize,
    edges: usize,
    len: usize,
    triangles_only: bool,
}

impl Default for BroadPhase {
    fn default() -> Self {
        Self {
            parallelism: Parallelism::default(),
            cell_factor: CELL_FACTOR,
            boxes: Vec::new(),
            levels: Vec::new(),
            grids: Vec::new(),
            offsets: Vec::new(),
            own: Vec::new(),
            finer: Vec::new(),
            bounds: Vec::new(),
            found: Vec::new(),
        }
    }
}

impl BroadPhase {
    /// A broad phase that takes the given path (sequential without the
    /// `parallel` feature, whatever is asked).
    #[must_use]
    pub fn new(parallelism: Parallelism) -> Self {
        Self {
            parallelism,
            ..Self::default()
        }
    }

    /// The grid's cell side as `factor` times the mean largest side of
    /// the triangles' boxes ([`CELL_FACTOR`] by default): the pairs found
    /// are the same, only the time differs.
    ///
    /// # Errors
    /// [`ParameterError`] for a factor that is not finite and positive.
    ///
    /// ```
    /// use hooke_core::Parallelism;
    /// use hooke_core::collision::broad::BroadPhase;
    /// let narrow = BroadPhase::new(Parallelism::Sequential).with_cell_factor(1.5);
    /// assert!(narrow.is_ok());
    /// assert!(BroadPhase::default().with_cell_factor(0.0).is_err());
    /// ```
    pub fn with_cell_factor(mut self, factor: f64) -> Result<Self, ParameterError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(ParameterError::new(
                "broad phase",
                Parameter::CellFactor,
                factor,
                "finite and positive",
            ));
        }
        self.cell_factor = factor;
        Ok(self)
    }

    /// Pairs whose boxes around the positions `x`, grown by `distance/2` on
    /// every side, overlap: every pair closer than `distance` is among them.
    ///
    /// # Panics
    /// If a particle of the mesh has no position in `x`, or the mesh has
    /// more than `u32::MAX` primitives.
    pub fn proximity(
        &mut self,
        mesh: &CollisionMesh,
        x: &[Vec3],
        distance: f64,
        out: &mut Candidates,
    ) {
        self.swept(mesh, x, x, distance, out);
    }

    /// Pairs whose boxes swept from `x0` to `x1` (each primitive's box
    /// around its positions at both ends), grown by `distance/2` on every
    /// side, overlap: every pair that comes closer than `distance` on the
    /// straight-line motion is among them.
    ///
    /// # Panics
    /// As [`proximity`](Self::proximity).
    pub fn swept(
        &mut self,
        mesh: &CollisionMesh,
        x0: &[Vec3],
        x1: &[Vec3],
        distance: f64,
        out: &mut Candidates,
    ) {
        let parallel = self.search(mesh, x0, x1, distance, false);
        gather(
            parallel,
            &mut self.found,
            |f| &f.point_triangle,
            &mut out.point_triangle,
        );
        gather(
            parallel,
            &mut self.found,
            |f| &f.edge_edge,
            &mut out.edge_edge,
        );
    }

    /// Pairs of triangles `(s, t)`, `s < t`, not sharing a particle, whose
    /// boxes around `x`, grown by `distance/2`, overlap — whatever their
    /// groups (for reports such as
    /// [`intersecting_triangle_pairs`](super::intersect::intersecting_triangle_pairs));
    /// sorted.
    ///
    /// # Panics
    /// As [`proximity`](Self::proximity).
    pub fn triangle_pairs(
        &mut self,
        mesh: &CollisionMesh,
        x: &[Vec3],
        distance: f64,
        out: &mut Vec<(u32, u32)>,
    ) {
        let parallel = self.search(mesh, x, x, distance, true);
        gather(parallel, &mut self.found, |f| &f.triangles, out);
    }

    /// Boxes the primitives and pairs them into `self.found`; returns
    /// whether it ran in parallel.
    fn search(
        &mut self,
        mesh: &CollisionMesh,
        x0: &[Vec3],
        x1: &[Vec3],
        distance: f64,
        triangles_only: bool,
    ) -> bool {
        let (vertices, edges) = if triangles_only {
            (0, 0)
        } else {
            (mesh.vertices().len(), mesh.edges().len())
        };
        let layout = Layout {
            vertices,
            edges,
            len: vertices + edges + mesh.triangles().len(),
            triangles_only,
        };
        assert!(u32::try_from(layout.len).is_ok(), "at most 2³² primitives");
        let parallel = match self.parallelism {
            Parallelism::Auto => layout.len >= PARALLEL_MIN_PRIMITIVES,
            Parallelism::Sequential => false,
            Parallelism::Parallel => true,
        } && cfg!(feature = "parallel");
        let chunks = if parallel { 4 * threads() } else { 1 };
        self.found
            .resize_with(self.found.len().max(chunks), Found::default);
        for found in &mut self.found {
            found.point_triangle.clear();
            found.edge_edge.clear();
            found.triangles.clear();
        }
        if mesh.is_empty() {
            return parallel;
        }

        fill_boxes(
            &mut self.boxes,
            (mesh, &layout),
            (x0, x1),
            0.5 * distance,
            parallel,
        );
        make_grids(&self.boxes, &layout, self.cell_factor, &mut self.grids);
        let (grids, boxes) = (&self.grids, &self.boxes);
        self.levels.resize(layout.len, 0);
        for_each(parallel, &mut self.levels, |i, level| {
            *level = level_of(grids, &boxes[i]);
        });

        let scene = Scene {
            mesh,
            layout,
            boxes: &self.boxes,
        };
        let mut present = [false; MAX_LEVELS];
        let mut wild = false;
        for &level in &self.levels {
            match present.get_mut(usize::from(level)) {
                Some(p) => *p = true,
                None => wild = true,
            }
        }
        for (level, grid) in self.grids.iter().enumerate() {
            if !present[level] {
                continue;
            }
            let (level, levels) = (level as u8, &self.levels);
            let (offsets, own, finer) = (&mut self.offsets, &mut self.own, &mut self.finer);
            fill_entries(scene.boxes, levels, grid, offsets, own, parallel, |l| {
                l == level
            });
            finer.clear();
            if level > 0 {
                fill_entries(scene.boxes, levels, grid, offsets, finer, parallel, |l| {
                    l < level
                });
            }
            chunk_bounds(own, grid.id_bits, chunks, &mut self.bounds);
            let (own, finer, bounds) = (&*own, &*finer, &self.bounds);
            for_each(parallel, &mut self.found[..chunks], |c, found| {
                scene.pair_chunk(grid, own, finer, bounds[c]..bounds[c + 1], found);
            });
        }
        if wild {
            for (a, _) in self.levels.iter().enumerate().filter(|&(_, &l)| l == WILD) {
                scene.pair_wild(a, &self.levels, &mut self.found[0]);
            }
        }
        parallel
    }
}

#[cfg(test)]
pub(crate) mod tests;
