//! The finest level: the filtered system matrix `Â = S A S + I − S` read
//! from the [`BlockMatrix`] without copying it.

use hooke_core::{Mat3, Vec3};

use super::aggregation::Graph;
use super::bsr::{Block, Bsr, for_each_block, for_each_row_slice, zero};
use super::prolongation::MODES;
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;
use crate::linear::neighbours::Neighbours;
use crate::linear::vector::{PARALLEL_MIN_PARTICLES, for_each_row};

/// `S_i M S_j` for filters `S_i`, `S_j`.
fn sandwich(m: Mat3, left: Filter, right: Filter) -> Mat3 {
    match (left, right) {
        (Filter::Free, Filter::Free) => m,
        _ => left.matrix() * m * right.matrix(),
    }
}

/// The diagonal block `Â_ii = S_i A_ii S_i + I − S_i`.
pub(crate) fn diagonal_block(a: &BlockMatrix, filters: &[Filter], i: usize) -> Mat3 {
    let f = filters[i];
    match f {
        Filter::Free => a.diagonal(i),
        _ => sandwich(a.diagonal(i), f, f) + Mat3::identity() - f.matrix(),
    }
}

/// The block `Â_ij = S_i A_ij S_j` of the slot between `i` and `j`: the
/// spring's `−K_s` and any contact or element block between the two.
fn coupling_block(a: &BlockMatrix, filters: &[Filter], i: usize, j: usize, slot: usize) -> Mat3 {
    let block = a.slot_block(slot);
    let block = if i < j { block } else { block.transpose() };
    sandwich(block, filters[i], filters[j])
}

/// `y = Â x` on flat vectors, through the block product: `y = S A S x +
/// (I − S) x`; `xs`, `ys` are scratch.
pub(crate) fn apply(
    a: &BlockMatrix,
    filters: &[Filter],
    x: &[f64],
    y: &mut [f64],
    xs: &mut [Vec3],
    ys: &mut [Vec3],
) {
    for_each_row(xs, |i, xi| {
        *xi = filters[i].apply(Vec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]));
    });
    a.apply(xs, ys);
    let ys = &*ys;
    for_each_block(y, 3, PARALLEL_MIN_PARTICLES, |i, yi| {
        let f = filters[i];
        let xi = Vec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        yi.copy_from_slice((f.apply(ys[i]) + xi - f.apply(xi)).as_slice());
    });
}

/// The particle graph with the norms of `Â`'s blocks.
pub(crate) fn graph(a: &BlockMatrix, filters: &[Filter], neighbours: &Neighbours) -> Graph {
    let n = a.rows();
    let mut g = Graph {
        ptr: neighbours.offsets().to_vec(),
        adj: neighbours.entries().iter().map(|&(j, _)| j).collect(),
        weight: Vec::with_capacity(neighbours.entries().len()),
        diagonal: (0..n)
            .map(|i| diagonal_block(a, filters, i).norm())
            .collect(),
    };
    for i in 0..n {
        for &(j, slot) in neighbours.of(i) {
            g.weight
                .push(coupling_block(a, filters, i, j as usize, slot as usize).norm());
        }
    }
    g
}

/// The near-null space of `Â`: per particle, the filtered rigid-body
/// modes at `positions` about their centroid `c`,
/// `S_i [I | (e_x × r_i) (e_y × r_i) (e_z × r_i)]` with `r_i = x_i − c`.
pub(crate) fn rigid_modes(positions: &[Vec3], filters: &[Filter]) -> Vec<Block<3, MODES>> {
    let n = positions.len().max(1);
    let centroid = positions.iter().sum::<Vec3>() / n as f64;
    positions
        .iter()
        .zip(filters)
        .map(|(x, f)| {
            let r = x - centroid;
            let columns = [
                Vec3::x(),
                Vec3::y(),
                Vec3::z(),
                Vec3::x().cross(&r),
                Vec3::y().cross(&r),
                Vec3::z().cross(&r),
            ]
            .map(|column| f.apply(column));
            std::array::from_fn(|a| std::array::from_fn(|c| columns[c][a]))
        })
        .collect()
}

/// The scalar diagonal of `Â_F` (see [`multiply_into`]).
pub(crate) fn filtered_diagonal(
    a: &BlockMatrix,
    filters: &[Filter],
    neighbours: &Neighbours,
    strong: &[bool],
) -> Vec<f64> {
    (0..a.rows())
        .flat_map(|i| {
            let start = neighbours.offsets()[i];
            let mut d = diagonal_block(a, filters, i);
            for (k, &(j, slot)) in neighbours.of(i).iter().enumerate() {
                if !strong[start + k] {
                    d += coupling_block(a, filters, i, j as usize, slot as usize);
                }
            }
            [d[(0, 0)], d[(1, 1)], d[(2, 2)]]
        })
        .collect()
}

/// The pattern of `Â P` for a prolongator `P` from the particles: block
/// row `i` holds the block columns of the rows of `i` and of its
/// neighbours — of its strong neighbours only when `strong` marks them per
/// entry of [`Neighbours`].
pub(crate) fn product_pattern(
    neighbours: &Neighbours,
    p: &Bsr<3, MODES>,
    strong: Option<&[bool]>,
) -> Bsr<3, MODES> {
    let n = neighbours.particles();
    let mut marker = vec![usize::MAX; p.cols];
    let mut out = Bsr {
        cols: p.cols,
        row_ptr: Vec::with_capacity(n + 1),
        ..Bsr::default()
    };
    out.row_ptr.push(0);
    for i in 0..n {
        let start = neighbours.offsets()[i];
        let first = out.col_idx.len();
        let others = neighbours
            .of(i)
            .iter()
            .enumerate()
            .filter(|&(k, _)| strong.is_none_or(|s| s[start + k]))
            .map(|(_, &(j, _))| j as usize);
        for j in std::iter::once(i).chain(others) {
            for &c in p.row(j).0 {
                if marker[c as usize] != i {
                    marker[c as usize] = i;
                    out.col_idx.push(c);
                }
            }
        }
        out.col_idx[first..].sort_unstable();
        out.row_ptr.push(out.col_idx.len());
    }
    out.values = vec![zero(); out.col_idx.len()];
    out
}

/// Refills `out` (pattern from [`product_pattern`] with the same `strong`)
/// with `Â P`, particles in parallel; with `strong`, with `Â_F P` instead,
/// `Â_F` the filtered matrix of smoothed aggregation (Vaněk, Mandel &
/// Brezina 1996): the weak blocks `Â_ij` are dropped and added to the
/// diagonal block `Â_ii`, so that `Â_F` and `Â` agree on translations.
pub(crate) fn multiply_into(
    a: &BlockMatrix,
    filters: &[Filter],
    neighbours: &Neighbours,
    p: &Bsr<3, MODES>,
    strong: Option<&[bool]>,
    out: &mut Bsr<3, MODES>,
) {
    let Bsr {
        row_ptr,
        col_idx,
        values,
        ..
    } = out;
    let fill = |position: &mut Vec<u32>, i: usize, values: &mut [Block<3, MODES>]| {
        position.resize(p.cols, 0);
        values.fill(zero());
        for (k, &c) in col_idx[row_ptr[i]..row_ptr[i + 1]].iter().enumerate() {
            position[c as usize] = k as u32;
        }
        let mut add = |j: usize, block: Mat3| {
            let block: Block<3, 3> =
                std::array::from_fn(|r| std::array::from_fn(|c| block[(r, c)]));
            let (cols, blocks) = p.row(j);
            for (&col, pb) in cols.iter().zip(blocks) {
                super::bsr::add_product(&mut values[position[col as usize] as usize], &block, pb);
            }
        };
        let start = neighbours.offsets()[i];
        let mut diagonal = diagonal_block(a, filters, i);
        for (k, &(j, slot)) in neighbours.of(i).iter().enumerate() {
            let block = coupling_block(a, filters, i, j as usize, slot as usize);
            if strong.is_none_or(|s| s[start + k]) {
                add(j as usize, block);
            } else {
                diagonal += block;
            }
        }
        add(i, diagonal);
    };
    for_each_row_slice(values, row_ptr, fill);
}
