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

use std::ops::Range;

use crate::{Parallelism, Parameter, ParameterError, Vec3};

use super::surface::CollisionMesh;

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

/// One chunk's pairs, and its scratch.
#[derive(Debug, Default)]
struct Found {
    point_triangle: Vec<(u32, u32)>,
    edge_edge: Vec<(u32, u32)>,
    triangles: Vec<(u32, u32)>,
    /// The boxes of the cell being paired.
    items: Vec<Item>,
    /// The overlapping boxes of one scan.
    hits: Vec<u32>,
}

/// A box in a cell, with the cell of its lower corner.
#[derive(Debug, Clone, Copy, Default)]
struct Item {
    lo: [f64; 3],
    hi: [f64; 3],
    cell: [i32; 3],
    id: u32,
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

        self.fill_boxes(mesh, &layout, x0, x1, 0.5 * distance, parallel);
        self.make_grids(&layout);
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
            fill_entries(&scene, levels, grid, offsets, own, parallel, |l| l == level);
            finer.clear();
            if level > 0 {
                fill_entries(&scene, levels, grid, offsets, finer, parallel, |l| {
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

    /// Sets `self.boxes` to the primitives' boxes over `x0` and `x1`, grown
    /// by `grow`.
    fn fill_boxes(
        &mut self,
        mesh: &CollisionMesh,
        layout: &Layout,
        x0: &[Vec3],
        x1: &[Vec3],
        grow: f64,
        parallel: bool,
    ) {
        let bound = |points: &[usize]| {
            let (mut lo, mut hi) = (
                x0[points[0]].inf(&x1[points[0]]),
                x0[points[0]].sup(&x1[points[0]]),
            );
            for &p in &points[1..] {
                lo = lo.inf(&x0[p]).inf(&x1[p]);
                hi = hi.sup(&x0[p]).sup(&x1[p]);
            }
            [lo.add_scalar(-grow), hi.add_scalar(grow)]
        };
        self.boxes.resize(layout.len, [Vec3::zeros(); 2]);
        let (vertices, rest) = self.boxes.split_at_mut(layout.vertices);
        let (edges, triangles) = rest.split_at_mut(layout.edges);
        if !layout.triangles_only {
            for_each(parallel, vertices, |v, b| *b = bound(&[mesh.vertices()[v]]));
            for_each(parallel, edges, |e, b| *b = bound(&mesh.edges()[e]));
        }
        for_each(parallel, triangles, |t, b| *b = bound(&mesh.triangles()[t]));
    }

    /// The levels of the grid: cells the cell factor times the mean
    /// largest side of the triangles' boxes, then `4` times larger, up to
    /// the size of the scene.
    fn make_grids(&mut self, layout: &Layout) {
        let finite = |b: &[Vec3; 2]| b[0].iter().chain(b[1].iter()).all(|c| c.is_finite());
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        let (mut sum, mut count) = (0.0, 0usize);
        for (i, b) in self.boxes.iter().enumerate().filter(|(_, b)| finite(b)) {
            lo = lo.inf(&b[0]);
            hi = hi.sup(&b[1]);
            if i >= layout.vertices + layout.edges {
                sum += (b[1] - b[0]).max();
                count += 1;
            }
        }
        self.grids.clear();
        if lo.x > hi.x {
            return;
        }
        let scene = (hi - lo).max();
        let mean = sum / count.max(1) as f64;
        let mut side = if mean > 0.0 {
            self.cell_factor * mean
        } else {
            scene.max(1.0)
        };
        let id_bits = bits(layout.len as u64);
        while self.grids.len() < MAX_LEVELS {
            self.grids.push(Grid::new(lo, hi, side, id_bits));
            if side >= scene {
                break;
            }
            side *= LEVEL_RATIO;
        }
    }
}

/// One level of the grid.
#[derive(Debug, Clone, Copy)]
struct Grid {
    origin: Vec3,
    inverse: f64,
    /// The number of cells along each axis (at most `2³¹ − 1`: beyond,
    /// cells merge, as they do under a hash).
    cells: [i32; 3],
    /// The bits of the `x` and `y` cell coordinates in an exact key; `None`
    /// when the key is a hash.
    exact: Option<[u32; 2]>,
    /// The bits of a box index in an entry.
    id_bits: u32,
}

impl Grid {
    fn new(lo: Vec3, hi: Vec3, side: f64, id_bits: u32) -> Self {
        let inverse = 1.0 / side;
        let cells = ((hi - lo) * inverse).map(|s| (s as i32).saturating_add(1));
        let [bx, by, bz] = cells.map(|c| bits(c as u64)).into();
        Self {
            origin: lo,
            inverse,
            cells: cells.into(),
            exact: (bx + by + bz <= 64 - id_bits).then_some([bx, by]),
            id_bits,
        }
    }

    /// The cell of `p`, `⌊(p − o)/h⌋` clamped to the grid: monotone, so
    /// overlapping boxes keep overlapping cell ranges. (`p ≥ o` but for
    /// rounding, so truncation is the floor, and cheaper.)
    #[inline]
    fn cell(&self, p: &Vec3) -> [i32; 3] {
        std::array::from_fn(|k| {
            (((p[k] - self.origin[k]) * self.inverse) as i32).clamp(0, self.cells[k] - 1)
        })
    }

    /// The key of cell `c`, in the low `64 − id_bits` bits.
    #[inline]
    fn key(&self, [i, j, k]: [i32; 3]) -> u64 {
        match self.exact {
            Some([bx, by]) => i as u64 | (j as u64) << bx | (k as u64) << (bx + by),
            None => {
                let h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
                    ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
                    ^ (k as u64).wrapping_mul(0x1656_67B1_9E37_79F9);
                (h ^ h >> 29).wrapping_mul(0xBF58_476D_1CE4_E5B9) >> self.id_bits
            }
        }
    }

    /// The cell of an exact key.
    fn decode(&self, key: u64) -> Option<[i32; 3]> {
        let [bx, by] = self.exact?;
        let field = |shift: u32, bits: u32| ((key >> shift) & ((1 << bits) - 1)) as i32;
        Some([field(0, bx), field(bx, by), (key >> (bx + by)) as i32])
    }

    /// The cells a box covers, saturating.
    fn count(&self, b: &[Vec3; 2]) -> u64 {
        let (lo, hi) = (self.cell(&b[0]), self.cell(&b[1]));
        (0..3).fold(1u64, |n, k| n.saturating_mul((hi[k] - lo[k] + 1) as u64))
    }
}

/// The bits needed for the numbers `0..n`.
fn bits(n: u64) -> u32 {
    64 - n.saturating_sub(1).leading_zeros()
}

/// The first level on which a box covers at most [`MAX_CELLS`] cells, or
/// [`WILD`].
fn level_of(grids: &[Grid], b: &[Vec3; 2]) -> u8 {
    if !b[0].iter().chain(b[1].iter()).all(|c| c.is_finite()) {
        return WILD;
    }
    grids
        .iter()
        .position(|g| g.count(b) <= MAX_CELLS)
        .map_or(WILD, |l| l as u8)
}

/// Sets `entries` to the sorted entries `key << id_bits | box` of the boxes
/// whose level passes `keep`.
#[allow(clippy::too_many_arguments)]
fn fill_entries(
    scene: &Scene,
    levels: &[u8],
    grid: &Grid,
    offsets: &mut Vec<usize>,
    entries: &mut Vec<u64>,
    parallel: bool,
    keep: impl Fn(u8) -> bool + Sync,
) {
    let boxes = scene.boxes;
    offsets.resize(boxes.len() + 1, 0);
    for_each(parallel, &mut offsets[1..], |i, n| {
        *n = if keep(levels[i]) {
            grid.count(&boxes[i]) as usize
        } else {
            0
        };
    });
    for i in 1..offsets.len() {
        offsets[i] += offsets[i - 1];
    }
    entries.resize(offsets[boxes.len()], 0);
    let emit = |i: usize, out: &mut [u64]| {
        if out.is_empty() {
            return; // Not kept.
        }
        let (lo, hi) = (grid.cell(&boxes[i][0]), grid.cell(&boxes[i][1]));
        let mut n = 0;
        for k in lo[2]..=hi[2] {
            for j in lo[1]..=hi[1] {
                for c in lo[0]..=hi[0] {
                    out[n] = grid.key([c, j, k]) << grid.id_bits | i as u64;
                    n += 1;
                }
            }
        }
    };
    emit_range(parallel, 0..boxes.len(), offsets, entries, &emit);
    sort(parallel, entries);
    if grid.exact.is_none() {
        // Two cells of one box may share a hash.
        entries.dedup();
    }
}

/// Writes the entries of the boxes `range` into `out`, which starts at
/// `offsets[range.start]`; in parallel by halves.
#[cfg_attr(not(feature = "parallel"), allow(unused_variables))]
fn emit_range(
    parallel: bool,
    range: Range<usize>,
    offsets: &[usize],
    out: &mut [u64],
    emit: &(impl Fn(usize, &mut [u64]) + Sync),
) {
    #[cfg(feature = "parallel")]
    if parallel && range.len() > GRAIN {
        let mid = range.start + range.len() / 2;
        let (left, right) = out.split_at_mut(offsets[mid] - offsets[range.start]);
        rayon::join(
            || emit_range(true, range.start..mid, offsets, left, emit),
            || emit_range(true, mid..range.end, offsets, right, emit),
        );
        return;
    }
    let base = offsets[range.start];
    for i in range {
        emit(i, &mut out[offsets[i] - base..offsets[i + 1] - base]);
    }
}

/// Splits the sorted `entries` into `chunks` runs of whole cells.
fn chunk_bounds(entries: &[u64], id_bits: u32, chunks: usize, bounds: &mut Vec<usize>) {
    bounds.clear();
    bounds.push(0);
    for c in 1..chunks {
        let mut at = (c * entries.len() / chunks).max(bounds[c - 1]);
        if at > 0 && at < entries.len() {
            let key = entries[at - 1] >> id_bits;
            at += entries[at..].partition_point(|&e| e >> id_bits == key);
        }
        bounds.push(at.min(entries.len()));
    }
    bounds.push(entries.len());
}

/// What pairing reads.
#[derive(Clone, Copy)]
struct Scene<'a> {
    mesh: &'a CollisionMesh,
    layout: Layout,
    boxes: &'a [[Vec3; 2]],
}

impl Scene<'_> {
    fn overlap(&self, a: usize, b: usize) -> bool {
        let ([lo, hi], [lo2, hi2]) = (&self.boxes[a], &self.boxes[b]);
        (0..3).all(|k| lo[k] <= hi2[k] && lo2[k] <= hi[k])
    }

    /// Records boxes `a < b` if they are an admissible pair.
    fn record(&self, a: usize, b: usize, found: &mut Found) {
        let Layout {
            vertices, edges, ..
        } = self.layout;
        let mesh = self.mesh;
        let shared = |p: &[usize], q: &[usize]| p.iter().any(|i| q.contains(i));
        if self.layout.triangles_only {
            if !shared(&mesh.triangles()[a], &mesh.triangles()[b]) {
                found.triangles.push((a as u32, b as u32));
            }
        } else if a < vertices {
            let t = b - vertices - edges;
            if !mesh.triangles()[t].contains(&mesh.vertices()[a])
                && mesh.collides(mesh.vertex_group(a), mesh.triangle_group(t))
            {
                found.point_triangle.push((a as u32, t as u32));
            }
        } else {
            let (e, f) = (a - vertices, b - vertices);
            if !shared(&mesh.edges()[e], &mesh.edges()[f])
                && mesh.collides(mesh.edge_group(e), mesh.edge_group(f))
            {
                found.edge_edge.push((e as u32, f as u32));
            }
        }
    }

    /// Pairs the cells whose entries in `own` lie in `range`: each cell's
    /// own boxes with each other and with the finer boxes of the cell.
    fn pair_chunk(
        &self,
        grid: &Grid,
        own: &[u64],
        finer: &[u64],
        range: Range<usize>,
        found: &mut Found,
    ) {
        let shift = grid.id_bits;
        let key = |e: u64| e >> shift;
        let (mut i, mut s) = (range.start, 0);
        if i < range.end {
            s = finer.partition_point(|&e| key(e) < key(own[i]));
        }
        while i < range.end {
            let cell = key(own[i]);
            let end = i + own[i..range.end].partition_point(|&e| key(e) == cell);
            while s < finer.len() && key(finer[s]) < cell {
                s += 1;
            }
            let start = s;
            while s < finer.len() && key(finer[s]) == cell {
                s += 1;
            }
            self.pair_cell(grid, cell, &own[i..end], &finer[start..s], found);
            i = end;
        }
    }

    /// Pairs one cell: vertices with triangles and edges with edges (or
    /// triangles with triangles), own boxes with own and with finer ones.
    ///
    /// A pair belongs to the cell `max(cellₐ, cell_b)` of its lower
    /// corners, so only pairs in which, along each axis, one of the boxes
    /// starts in this cell are tested. The cell's boxes are copied side by
    /// side, each kind sorted by the axes along which it starts here (a
    /// mask `m`), and groups `m`, `m'` are tested only if `m | m' = 0b111`.
    /// (With hashed keys the cell is unknown: all are tested, and the
    /// owner cell checked per pair.)
    fn pair_cell(&self, grid: &Grid, cell: u64, own: &[u64], finer: &[u64], found: &mut Found) {
        let mask = (1u64 << grid.id_bits) - 1;
        let Layout {
            vertices,
            edges,
            triangles_only,
            ..
        } = self.layout;
        let here = grid.decode(cell);
        let corner = |lo: &Vec3| {
            let c = grid.cell(lo);
            let starts = here.map_or(7, |h| {
                (0..3).fold(0, |m, k| m | usize::from(c[k] == h[k]) << k)
            });
            (starts, c)
        };
        let (mut items, mut hits) = (
            std::mem::take(&mut found.items),
            std::mem::take(&mut found.hits),
        );
        items.clear();
        let mut groups = [[0; 9]; 6];
        let blocks = [own, finer].map(|b| (b, split_kinds(b, mask, [vertices, vertices + edges])));
        let ranges = blocks
            .iter()
            .flat_map(|(b, kinds)| kinds.clone().map(|r| &b[r]));
        for (group, block) in groups.iter_mut().zip(ranges) {
            let mut counts = [0; 8];
            for &e in block {
                counts[corner(&self.boxes[(e & mask) as usize][0]).0] += 1;
            }
            group[0] = items.len();
            for m in 0..8 {
                group[m + 1] = group[m] + counts[m];
            }
            items.resize(group[8], Item::default());
            let mut next = *group;
            for &e in block {
                let id = (e & mask) as usize;
                let [lo, hi] = self.boxes[id];
                let (m, cell) = corner(&lo);
                items[next[m]] = Item {
                    lo: lo.into(),
                    hi: hi.into(),
                    cell,
                    id: id as u32,
                };
                next[m] += 1;
            }
        }
        let [ov, oe, ot, fv, fe, ft] = groups;
        let mut pair = |x: &[usize; 9], y: &[usize; 9], same: bool| {
            for mx in 0..8 {
                for my in if same { mx..8 } else { 0..8 } {
                    if mx | my != 7 {
                        continue;
                    }
                    let ys = &items[y[my]..y[my + 1]];
                    for (n, a) in items[x[mx]..x[mx + 1]].iter().enumerate() {
                        let others = if same && mx == my { &ys[n + 1..] } else { ys };
                        self.scan(grid, cell, here.is_none(), a, others, &mut hits, found);
                    }
                }
            }
        };
        if triangles_only {
            pair(&ot, &ot, true);
            pair(&ot, &ft, false);
        } else {
            pair(&ov, &ot, false);
            pair(&ov, &ft, false);
            pair(&ot, &fv, false);
            pair(&oe, &oe, true);
            pair(&oe, &fe, false);
        }
        (found.items, found.hits) = (items, hits);
    }

    /// Tests box `a` against `others`: records each overlapping pair
    /// (whose intersection's lower corner lies in `cell`, i.e. whose cell
    /// `max(cellₐ, cell_b)` is `cell`, if `check`). The overlapping boxes
    /// are first listed without branches.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn scan(
        &self,
        grid: &Grid,
        cell: u64,
        check: bool,
        a: &Item,
        others: &[Item],
        hits: &mut Vec<u32>,
        found: &mut Found,
    ) {
        if hits.len() < others.len() {
            hits.resize(others.len(), 0);
        }
        let mut n = 0;
        for (j, b) in others.iter().enumerate() {
            let overlap = (a.lo[0] <= b.hi[0])
                & (b.lo[0] <= a.hi[0])
                & (a.lo[1] <= b.hi[1])
                & (b.lo[1] <= a.hi[1])
                & (a.lo[2] <= b.hi[2])
                & (b.lo[2] <= a.hi[2]);
            hits[n] = j as u32;
            n += usize::from(overlap);
        }
        for &j in &hits[..n] {
            let b = &others[j as usize];
            if !check || grid.key(std::array::from_fn(|k| a.cell[k].max(b.cell[k]))) == cell {
                let (a, b) = (a.id.min(b.id) as usize, a.id.max(b.id) as usize);
                self.record(a, b, found);
            }
        }
    }

    /// Pairs the box `a`, which is on no level, with every box.
    fn pair_wild(&self, a: usize, levels: &[u8], found: &mut Found) {
        let Layout {
            vertices,
            edges,
            len,
            triangles_only,
        } = self.layout;
        let triangles = vertices + edges..len;
        let others = if triangles_only || a < vertices {
            triangles
        } else if a < vertices + edges {
            vertices..vertices + edges
        } else {
            0..vertices
        };
        for b in others {
            if b != a && !(levels[b] == WILD && b < a) && self.overlap(a, b) {
                self.record(a.min(b), a.max(b), found);
            }
        }
    }
}

/// A cell's entries (sorted) split into vertices, edges and triangles, by
/// the first edge's and the first triangle's box index.
fn split_kinds(block: &[u64], mask: u64, [edges, triangles]: [usize; 2]) -> [Range<usize>; 3] {
    let v = block.partition_point(|&e| ((e & mask) as usize) < edges);
    let t = block.partition_point(|&e| ((e & mask) as usize) < triangles);
    [0..v, v..t, t..block.len()]
}

/// Sets `out` to the sorted pairs of all chunks.
fn gather(
    parallel: bool,
    found: &mut [Found],
    pick: impl Fn(&Found) -> &Vec<(u32, u32)>,
    out: &mut Vec<(u32, u32)>,
) {
    out.clear();
    for f in found.iter() {
        out.extend_from_slice(pick(f));
    }
    sort(parallel, out);
    out.dedup();
}

/// Calls `f(i, &mut items[i])` for every item, on rayon's pool if
/// `parallel`.
#[cfg_attr(not(feature = "parallel"), allow(unused_variables))]
fn for_each<T: Send>(parallel: bool, items: &mut [T], f: impl Fn(usize, &mut T) + Sync + Send) {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        let grain = if items.len() > GRAIN { 1024 } else { 1 };
        items
            .par_iter_mut()
            .enumerate()
            .with_min_len(grain)
            .for_each(|(i, item)| f(i, item));
        return;
    }
    for (i, item) in items.iter_mut().enumerate() {
        f(i, item);
    }
}

/// Sorts, on rayon's pool if `parallel`.
#[cfg_attr(not(feature = "parallel"), allow(unused_variables))]
fn sort<T: Ord + Send>(parallel: bool, items: &mut [T]) {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        items.par_sort_unstable();
        return;
    }
    items.sort_unstable();
}

/// The threads of rayon's pool (1 without the `parallel` feature).
fn threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads().max(1);
    #[cfg(not(feature = "parallel"))]
    1
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::collision::distance::tests::Rng;

    /// A flat `n × n` grid cloth of the given spacing in the plane `z = 0`,
    /// two triangles per square.
    pub(crate) fn cloth(n: usize, spacing: f64) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let x = (0..n * n)
            .map(|p| Vec3::new((p % n) as f64, (p / n) as f64, 0.0) * spacing)
            .collect();
        let triangles = (0..n - 1)
            .flat_map(|j| (0..n - 1).map(move |i| j * n + i))
            .flat_map(|p| [[p, p + 1, p + n + 1], [p, p + n + 1, p + n]])
            .collect();
        (x, triangles)
    }

    /// Folds a cloth of `cloth` about the line `x = at` over a half cylinder
    /// of `radius`; beyond the fold the sheet comes back at height `2 r`,
    /// sinking by `dip` per unit length (through the lower sheet if
    /// `dip > 0`).
    pub(crate) fn fold(x: &mut [Vec3], at: f64, radius: f64, dip: f64) {
        for p in x {
            let s = p.x - at;
            if s <= 0.0 {
                continue;
            }
            let arc = std::f64::consts::PI * radius;
            let (u, z) = if s < arc {
                (
                    radius * (s / radius).sin(),
                    radius * (1.0 - (s / radius).cos()),
                )
            } else {
                (-(s - arc), 2.0 * radius - dip * (s - arc))
            };
            *p = Vec3::new(at + u, p.y, z);
        }
    }

    /// A random triangle soup: `count` triangles of particles `first..`, on
    /// a random walk of steps `step` in the cube `[0, 1]³`, each triangle of
    /// a particle and two of the next few (so triangles share particles).
    pub(crate) fn soup(
        rng: &mut Rng,
        first: usize,
        count: usize,
        step: f64,
    ) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let particles = count + 8;
        let mut at = Vec3::new(
            rng.uniform(0.0, 1.0),
            rng.uniform(0.0, 1.0),
            rng.uniform(0.0, 1.0),
        );
        let x: Vec<Vec3> = (0..particles)
            .map(|_| {
                at = (at + rng.vec3(1.0) * step).map(|c| c.clamp(0.0, 1.0));
                at
            })
            .collect();
        let triangles = (0..count)
            .map(|i| {
                let j = i + 1 + rng.below(3);
                let k = j + 1 + rng.below(3);
                [i, j, k].map(|p| p + first)
            })
            .collect();
        (x, triangles)
    }

    fn box_of(points: &[usize], x0: &[Vec3], x1: &[Vec3], distance: f64) -> [Vec3; 2] {
        let lo = points.iter().fold(Vec3::repeat(f64::INFINITY), |m, &p| {
            m.inf(&x0[p]).inf(&x1[p])
        });
        let hi = points
            .iter()
            .fold(Vec3::repeat(f64::NEG_INFINITY), |m, &p| {
                m.sup(&x0[p]).sup(&x1[p])
            });
        [
            lo.add_scalar(-0.5 * distance),
            hi.add_scalar(0.5 * distance),
        ]
    }

    fn boxes_overlap(a: &[Vec3; 2], b: &[Vec3; 2]) -> bool {
        (0..3).all(|k| a[0][k] <= b[1][k] && b[0][k] <= a[1][k])
    }

    fn shares(p: &[usize], q: &[usize]) -> bool {
        p.iter().any(|i| q.contains(i))
    }

    /// Every admissible pair whose boxes overlap, by testing all pairs.
    fn brute(mesh: &CollisionMesh, x0: &[Vec3], x1: &[Vec3], distance: f64) -> Candidates {
        let vb: Vec<_> = mesh
            .vertices()
            .iter()
            .map(|&p| box_of(&[p], x0, x1, distance))
            .collect();
        let eb: Vec<_> = mesh
            .edges()
            .iter()
            .map(|e| box_of(e, x0, x1, distance))
            .collect();
        let tb: Vec<_> = mesh
            .triangles()
            .iter()
            .map(|t| box_of(t, x0, x1, distance))
            .collect();
        let mut out = Candidates::default();
        for (v, &p) in mesh.vertices().iter().enumerate() {
            for (t, tri) in mesh.triangles().iter().enumerate() {
                if !tri.contains(&p)
                    && mesh.collides(mesh.vertex_group(v), mesh.triangle_group(t))
                    && boxes_overlap(&vb[v], &tb[t])
                {
                    out.point_triangle.push((v as u32, t as u32));
                }
            }
        }
        for (e, a) in mesh.edges().iter().enumerate() {
            for (f, b) in mesh.edges().iter().enumerate().skip(e + 1) {
                if !shares(a, b)
                    && mesh.collides(mesh.edge_group(e), mesh.edge_group(f))
                    && boxes_overlap(&eb[e], &eb[f])
                {
                    out.edge_edge.push((e as u32, f as u32));
                }
            }
        }
        out
    }

    /// The squared distance from `p` to the triangle `abc` (Ericson,
    /// *Real-Time Collision Detection*, §5.1.5).
    fn point_triangle(p: Vec3, [a, b, c]: [Vec3; 3]) -> f64 {
        let (ab, ac, ap) = (b - a, c - a, p - a);
        let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
        let closest = if d1 <= 0.0 && d2 <= 0.0 {
            a
        } else {
            let bp = p - b;
            let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
            let cp = p - c;
            let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
            let (va, vb, vc) = (d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2);
            if d3 >= 0.0 && d4 <= d3 {
                b
            } else if d6 >= 0.0 && d5 <= d6 {
                c
            } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
                a + ab * (d1 / (d1 - d3))
            } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
                a + ac * (d2 / (d2 - d6))
            } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
                b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))
            } else {
                let s = 1.0 / (va + vb + vc);
                a + ab * (vb * s) + ac * (vc * s)
            }
        };
        (p - closest).norm_squared()
    }

    /// The squared distance between the segments `p0p1` and `q0q1`: the
    /// least over a fine sampling of one segment of the distance to the
    /// other (the closest point on a segment by projection), refined.
    fn segment_segment(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> f64 {
        let to_q = |p: Vec3| {
            let d = q1 - q0;
            let t = if d.norm_squared() > 0.0 {
                ((p - q0).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (q0 + d * t)).norm_squared()
        };
        // The distance to a segment is convex along the other segment:
        // ternary search.
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..100 {
            let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if to_q(p0 + (p1 - p0) * a) < to_q(p0 + (p1 - p0) * b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        to_q(p0 + (p1 - p0) * (0.5 * (lo + hi)))
    }

    #[test]
    fn test_distances_agree_with_sampling() {
        let mut rng = Rng::new(11);
        for _ in 0..200 {
            let [p, a, b, c] = [(); 4].map(|()| rng.vec3(1.0));
            let mut sampled = f64::INFINITY;
            let mut segments = f64::INFINITY;
            for i in 0..=60 {
                for j in 0..=60 - i {
                    let (u, v) = (f64::from(i) / 60.0, f64::from(j) / 60.0);
                    sampled = sampled.min((a + (b - a) * u + (c - a) * v - p).norm_squared());
                }
                for j in 0..=60 {
                    let (u, v) = (f64::from(i) / 60.0, f64::from(j) / 60.0);
                    segments = segments.min((p + (a - p) * u - b - (c - b) * v).norm_squared());
                }
            }
            let exact = point_triangle(p, [a, b, c]);
            assert!(
                exact <= sampled + 1e-12 && sampled.sqrt() - exact.sqrt() < 0.05,
                "{exact} {sampled}"
            );
            let exact = segment_segment(p, a, b, c);
            assert!(
                exact <= segments + 1e-12 && segments.sqrt() - exact.sqrt() < 0.05,
                "{exact} {segments}"
            );
        }
    }

    fn check(mesh: &CollisionMesh, found: &Candidates, expected: &Candidates) {
        for list in [&found.point_triangle, &found.edge_edge] {
            assert!(
                list.windows(2).all(|w| w[0] < w[1]),
                "sorted, no duplicates"
            );
        }
        for &(e, f) in &found.edge_edge {
            assert!(e < f);
            let (a, b) = (mesh.edges()[e as usize], mesh.edges()[f as usize]);
            assert!(!shares(&a, &b));
            assert!(mesh.collides(mesh.edge_group(e as usize), mesh.edge_group(f as usize)));
        }
        for &(v, t) in &found.point_triangle {
            assert!(!mesh.triangles()[t as usize].contains(&mesh.vertices()[v as usize]));
            assert!(mesh.collides(
                mesh.vertex_group(v as usize),
                mesh.triangle_group(t as usize)
            ));
        }
        assert_eq!(
            found.point_triangle, expected.point_triangle,
            "point–triangle pairs"
        );
        assert_eq!(found.edge_edge, expected.edge_edge, "edge–edge pairs");
    }

    /// Every pair closer than `distance` is a candidate. (Pairs whose
    /// points are `distance` apart along an axis are skipped: they are at
    /// least that far apart.)
    fn check_distances(
        mesh: &CollisionMesh,
        x: &[Vec3],
        distance: f64,
        found: &Candidates,
    ) -> usize {
        let apart = |p: &[usize], q: &[usize]| {
            (0..3).any(|k| {
                let range = |s: &[usize]| {
                    s.iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
                            (lo.min(x[i][k]), hi.max(x[i][k]))
                        })
                };
                let ((a, b), (c, d)) = (range(p), range(q));
                c - b >= distance || a - d >= distance
            })
        };
        let mut close = 0;
        for (v, &p) in mesh.vertices().iter().enumerate() {
            for (t, tri) in mesh.triangles().iter().enumerate() {
                if !tri.contains(&p)
                    && mesh.collides(mesh.vertex_group(v), mesh.triangle_group(t))
                    && !apart(&[p], tri)
                    && point_triangle(x[p], tri.map(|q| x[q])) < distance * distance
                {
                    close += 1;
                    assert!(
                        found
                            .point_triangle
                            .binary_search(&(v as u32, t as u32))
                            .is_ok()
                    );
                }
            }
        }
        for (e, &[a, b]) in mesh.edges().iter().enumerate() {
            for (f, &[c, d]) in mesh.edges().iter().enumerate().skip(e + 1) {
                if !shares(&[a, b], &[c, d])
                    && mesh.collides(mesh.edge_group(e), mesh.edge_group(f))
                    && !apart(&[a, b], &[c, d])
                    && segment_segment(x[a], x[b], x[c], x[d]) < distance * distance
                {
                    close += 1;
                    assert!(found.edge_edge.binary_search(&(e as u32, f as u32)).is_ok());
                }
            }
        }
        close
    }

    /// Two random soups (one self-colliding by `seed`) and a folded cloth.
    fn scene(seed: u64, size: usize) -> (CollisionMesh, Vec<Vec3>) {
        let mut rng = Rng::new(seed);
        let mut mesh = CollisionMesh::new();
        let mut x = Vec::new();
        for own in [seed % 2 == 0, seed % 3 == 0] {
            let (y, triangles) = soup(&mut rng, x.len(), size, 0.08);
            mesh.add_surface(&triangles, own);
            x.extend(y);
        }
        let (mut y, triangles) = cloth(12, 0.05);
        fold(&mut y, 0.3, 0.02, 0.0);
        let first = x.len();
        mesh.add_surface(
            &triangles
                .iter()
                .map(|t| t.map(|p| p + first))
                .collect::<Vec<_>>(),
            true,
        );
        x.extend(y.iter().map(|p| p + Vec3::new(0.2, 0.2, 0.4)));
        (mesh, x)
    }

    /// Whatever the cell side, from boxes eight cells wide to a few in a
    /// cell.
    #[test]
    fn proximity_finds_exactly_the_overlapping_boxes_on_soups_and_a_folded_cloth() {
        for factor in [0.25, 1.5, CELL_FACTOR, 8.0] {
            let mut broad = BroadPhase::new(Parallelism::Sequential)
                .with_cell_factor(factor)
                .unwrap();
            let mut found = Candidates::default();
            for seed in 0..6 {
                let (mesh, x) = scene(seed, 150);
                for distance in [0.0, 0.01, 0.05] {
                    broad.proximity(&mesh, &x, distance, &mut found);
                    check(&mesh, &found, &brute(&mesh, &x, &x, distance));
                    if distance > 0.0 {
                        let close = check_distances(&mesh, &x, distance, &found);
                        let listed = found.point_triangle.len() + found.edge_edge.len();
                        assert!(close > 0 && close <= listed, "factor {factor}");
                    }
                }
            }
        }
    }

    #[test]
    fn folded_cloth_pairs_across_the_fold_and_not_within_a_surface_without_self_collision() {
        let (mut x, triangles) = cloth(20, 0.1);
        fold(&mut x, 1.0, 0.04, 0.0);
        let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
        for own in [true, false] {
            let mut mesh = CollisionMesh::new();
            mesh.add_surface(&triangles, own);
            broad.proximity(&mesh, &x, 0.1, &mut found);
            check(&mesh, &found, &brute(&mesh, &x, &x, 0.1));
            if own {
                // The sheets are 8 cm apart across the fold.
                let close = check_distances(&mesh, &x, 0.1, &found);
                assert!(close > 100, "{close}");
            } else {
                assert!(found.point_triangle.is_empty() && found.edge_edge.is_empty());
            }
        }
    }

    #[test]
    fn swept_boxes_with_fast_and_huge_motions_match_brute_force() {
        // Cells small enough that the fast motions go to coarser levels.
        let mut broad = BroadPhase::new(Parallelism::Sequential)
            .with_cell_factor(1.5)
            .unwrap();
        let mut found = Candidates::default();
        for seed in 0..4 {
            let (mesh, x0) = scene(seed, 120);
            let mut rng = Rng::new(100 + seed);
            let x1: Vec<Vec3> = x0
                .iter()
                .map(|p| {
                    let r = rng.uniform(0.0, 1.0);
                    // Most move a little, some across the scene, a few far.
                    let reach = if r < 0.8 {
                        0.01
                    } else if r < 0.97 {
                        0.5
                    } else {
                        50.0
                    };
                    p + rng.vec3(1.0) * reach
                })
                .collect();
            broad.swept(&mesh, &x0, &x1, 0.01, &mut found);
            assert!(broad.levels.iter().any(|&l| l > 0), "coarser levels in use");
            check(&mesh, &found, &brute(&mesh, &x0, &x1, 0.01));
        }
    }

    #[test]
    fn non_finite_positions_are_tested_against_every_box() {
        let (mesh, mut x) = scene(3, 100);
        x[5] = Vec3::new(f64::NAN, 0.0, 0.0);
        x[40] = Vec3::new(f64::INFINITY, 0.5, 0.5);
        x[41] = Vec3::new(0.5, f64::NEG_INFINITY, 0.5);
        let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
        broad.proximity(&mesh, &x, 0.02, &mut found);
        assert!(broad.levels.contains(&WILD));
        check(&mesh, &found, &brute(&mesh, &x, &x, 0.02));
    }

    #[test]
    fn a_scene_too_wide_for_exact_keys_hashes_its_cells() {
        let (mut mesh, mut x) = scene(1, 100);
        // A lone triangle, and a second one touching it, 10¹² m away.
        let n = x.len();
        mesh.add_surface(&[[n, n + 1, n + 2]], false);
        mesh.add_surface(&[[n + 3, n + 4, n + 5]], false);
        for k in 0..6 {
            x.push(
                Vec3::repeat(1e12)
                    + Vec3::new(
                        0.01 * f64::from(k % 3),
                        0.005 * f64::from(k / 3),
                        0.01 * f64::from(k),
                    ),
            );
        }
        let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
        broad.proximity(&mesh, &x, 0.02, &mut found);
        assert!(broad.grids[0].exact.is_none());
        check(&mesh, &found, &brute(&mesh, &x, &x, 0.02));
        let far = mesh.triangles().len() as u32 - 2;
        assert!(found.point_triangle.iter().any(|&(_, t)| t >= far));
    }

    #[test]
    fn triangle_pairs_match_brute_force_whatever_the_groups() {
        let (mesh, x) = scene(4, 150);
        let (mut broad, mut pairs) = (BroadPhase::default(), Vec::new());
        broad.triangle_pairs(&mesh, &x, 0.01, &mut pairs);
        let boxes: Vec<_> = mesh
            .triangles()
            .iter()
            .map(|t| box_of(t, &x, &x, 0.01))
            .collect();
        let mut expected = Vec::new();
        for (s, a) in mesh.triangles().iter().enumerate() {
            for (t, b) in mesh.triangles().iter().enumerate().skip(s + 1) {
                if !shares(a, b) && boxes_overlap(&boxes[s], &boxes[t]) {
                    expected.push((s as u32, t as u32));
                }
            }
        }
        assert_eq!(pairs, expected);
    }

    #[test]
    fn an_empty_mesh_has_no_pairs() {
        let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
        found.edge_edge.push((0, 1));
        broad.proximity(&CollisionMesh::new(), &[], 0.1, &mut found);
        assert!(found.point_triangle.is_empty() && found.edge_edge.is_empty());
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn parallel_and_sequential_searches_agree() {
        let (mut x0, triangles) = cloth(90, 0.01);
        fold(&mut x0, 0.45, 0.004, 0.0);
        let mut rng = Rng::new(7);
        let x1: Vec<Vec3> = x0
            .iter()
            .map(|p| {
                p + rng.vec3(1.0)
                    * if rng.uniform(0.0, 1.0) < 0.99 {
                        0.005
                    } else {
                        0.3
                    }
            })
            .collect();
        let mut mesh = CollisionMesh::new();
        mesh.add_surface(&triangles, true);
        assert!(
            mesh.vertices().len() + mesh.edges().len() + mesh.triangles().len()
                >= PARALLEL_MIN_PRIMITIVES
        );
        let mut results = Vec::new();
        for parallelism in [
            Parallelism::Sequential,
            Parallelism::Parallel,
            Parallelism::Auto,
        ] {
            let (mut broad, mut near, mut swept, mut pairs) = (
                BroadPhase::new(parallelism),
                Candidates::default(),
                Candidates::default(),
                Vec::new(),
            );
            broad.proximity(&mesh, &x0, 0.01, &mut near);
            broad.swept(&mesh, &x0, &x1, 0.001, &mut swept);
            broad.triangle_pairs(&mesh, &x0, 0.0, &mut pairs);
            assert!(!near.edge_edge.is_empty() && !swept.point_triangle.is_empty());
            results.push((
                near.point_triangle,
                near.edge_edge,
                swept.point_triangle,
                swept.edge_edge,
                pairs,
            ));
        }
        assert!(results[0] == results[1] && results[1] == results[2]);
    }
}
