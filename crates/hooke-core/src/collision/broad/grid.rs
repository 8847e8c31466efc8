//! The grid of the broad phase: the primitives' boxes, the grid's levels,
//! the cells a box covers, and the sorted entries `key << id_bits | box` of
//! each level.

use std::ops::Range;

#[cfg(feature = "parallel")]
use super::GRAIN;
use super::parallel::{for_each, sort};
use super::{LEVEL_RATIO, Layout, MAX_CELLS, MAX_LEVELS, WILD};
use crate::Vec3;
use crate::collision::surface::CollisionMesh;

/// Sets `boxes` to the primitives' boxes over `x0` and `x1`, grown by
/// `grow`.
pub(super) fn fill_boxes(
    boxes: &mut Vec<[Vec3; 2]>,
    (mesh, layout): (&CollisionMesh, &Layout),
    (x0, x1): (&[Vec3], &[Vec3]),
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
    boxes.resize(layout.len, [Vec3::zeros(); 2]);
    let (vertices, rest) = boxes.split_at_mut(layout.vertices);
    let (edges, triangles) = rest.split_at_mut(layout.edges);
    if !layout.triangles_only {
        for_each(parallel, vertices, |v, b| *b = bound(&[mesh.vertices()[v]]));
        for_each(parallel, edges, |e, b| *b = bound(&mesh.edges()[e]));
    }
    for_each(parallel, triangles, |t, b| *b = bound(&mesh.triangles()[t]));
}

/// Sets `grids` to the levels of the grid over `boxes`: cells `cell_factor` times the mean
/// largest side of the triangles' boxes, then `4` times larger, up to
/// the size of the scene.
pub(super) fn make_grids(
    boxes: &[[Vec3; 2]],
    layout: &Layout,
    cell_factor: f64,
    grids: &mut Vec<Grid>,
) {
    let finite = |b: &[Vec3; 2]| b[0].iter().chain(b[1].iter()).all(|c| c.is_finite());
    let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
    let (mut sum, mut count) = (0.0, 0usize);
    for (i, b) in boxes.iter().enumerate().filter(|(_, b)| finite(b)) {
        lo = lo.inf(&b[0]);
        hi = hi.sup(&b[1]);
        if i >= layout.vertices + layout.edges {
            sum += (b[1] - b[0]).max();
            count += 1;
        }
    }
    grids.clear();
    if lo.x > hi.x {
        return;
    }
    let scene = (hi - lo).max();
    let mean = sum / count.max(1) as f64;
    let mut side = if mean > 0.0 {
        cell_factor * mean
    } else {
        scene.max(1.0)
    };
    let id_bits = bits(layout.len as u64);
    while grids.len() < MAX_LEVELS {
        grids.push(Grid::new(lo, hi, side, id_bits));
        if side >= scene {
            break;
        }
        side *= LEVEL_RATIO;
    }
}

/// One level of the grid.
#[derive(Debug, Clone, Copy)]
pub(super) struct Grid {
    origin: Vec3,
    inverse: f64,
    /// The number of cells along each axis (at most `2³¹ − 1`: beyond,
    /// cells merge, as they do under a hash).
    cells: [i32; 3],
    /// The bits of the `x` and `y` cell coordinates in an exact key; `None`
    /// when the key is a hash.
    pub(super) exact: Option<[u32; 2]>,
    /// The bits of a box index in an entry.
    pub(super) id_bits: u32,
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
    pub(super) fn cell(&self, p: &Vec3) -> [i32; 3] {
        std::array::from_fn(|k| {
            (((p[k] - self.origin[k]) * self.inverse) as i32).clamp(0, self.cells[k] - 1)
        })
    }

    /// The key of cell `c`, in the low `64 − id_bits` bits.
    #[inline]
    pub(super) fn key(&self, [i, j, k]: [i32; 3]) -> u64 {
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
    pub(super) fn decode(&self, key: u64) -> Option<[i32; 3]> {
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
pub(super) fn bits(n: u64) -> u32 {
    64 - n.saturating_sub(1).leading_zeros()
}

/// The first level on which a box covers at most [`MAX_CELLS`] cells, or
/// [`WILD`].
pub(super) fn level_of(grids: &[Grid], b: &[Vec3; 2]) -> u8 {
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
pub(super) fn fill_entries(
    boxes: &[[Vec3; 2]],
    levels: &[u8],
    grid: &Grid,
    offsets: &mut Vec<usize>,
    entries: &mut Vec<u64>,
    parallel: bool,
    keep: impl Fn(u8) -> bool + Sync,
) {
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
pub(super) fn emit_range(
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
pub(super) fn chunk_bounds(entries: &[u64], id_bits: u32, chunks: usize, bounds: &mut Vec<usize>) {
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
