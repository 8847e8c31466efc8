//! The pairing of the broad phase: within each cell of a level, the boxes
//! that overlap, each pair recorded once, in the cell of its boxes'
//! intersection's lower corner.

use std::ops::Range;

use super::grid::Grid;
use super::parallel::sort;
use super::{Layout, WILD};
use crate::Vec3;
use crate::collision::surface::CollisionMesh;

/// One chunk's pairs, and its scratch.
#[derive(Debug, Default)]
pub(super) struct Found {
    pub(super) point_triangle: Vec<(u32, u32)>,
    pub(super) edge_edge: Vec<(u32, u32)>,
    pub(super) triangles: Vec<(u32, u32)>,
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

/// What pairing reads.
#[derive(Clone, Copy)]
pub(super) struct Scene<'a> {
    pub(super) mesh: &'a CollisionMesh,
    pub(super) layout: Layout,
    pub(super) boxes: &'a [[Vec3; 2]],
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
    pub(super) fn pair_chunk(
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
    pub(super) fn pair_wild(&self, a: usize, levels: &[u8], found: &mut Found) {
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
pub(super) fn gather(
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
