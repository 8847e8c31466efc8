//! Prolongators: the tentative one from the near-null space on each
//! aggregate, and its Jacobi smoothing.

use super::aggregation::ISOLATED;
use super::bsr::{Block, Bsr, zero};

/// Modes of the near-null space: three translations and three rotations.
/// Every coarse node (aggregate) has this many unknowns.
pub(crate) const MODES: usize = 6;

/// The tentative prolongator of an aggregation of nodes of `N` unknowns
/// and the coarse near-null space.
#[derive(Debug)]
pub(crate) struct Tentative<const N: usize> {
    /// `T`: per aggregate, an orthonormal basis of the near-null space's
    /// restriction to the aggregate's unknowns, one `N × 6` block per node.
    pub(crate) t: Bsr<N, MODES>,
    /// The coarse near-null space `R`, with `B|_aggregate = Q R`: per
    /// aggregate, row `j` holds the modes of its coarse unknown `j`.
    pub(crate) modes: Vec<Block<MODES, MODES>>,
}

/// `T` and the coarse near-null space from the near-null space `modes` (the
/// `N × 6` rows of `B` of each node) and the aggregation.
///
/// On each aggregate the rows of `B` are orthonormalised column by column
/// (Gram–Schmidt, twice for accuracy): `B|_a = Q_a R_a`, and a column whose
/// remainder is below `10⁻¹⁰` of the aggregate's largest column is dropped
/// — constrained unknowns (their rows of `B` filtered to zero) or
/// aggregates too small to carry all six modes span fewer. Every aggregate
/// keeps six coarse unknowns: a dropped column leaves a zero column of `T`
/// (and a zero row of `R_a`), an unknown that the coarse operator does not
/// couple: the Galerkin refill gives it a unit diagonal.
pub(crate) fn tentative<const N: usize>(
    modes: &[Block<N, MODES>],
    agg: &[u32],
    aggregates: usize,
) -> Tentative<N> {
    // Members of each aggregate, in node order.
    let mut start = vec![0usize; aggregates + 1];
    for &a in agg {
        if a != ISOLATED {
            start[a as usize + 1] += 1;
        }
    }
    for a in 0..aggregates {
        start[a + 1] += start[a];
    }
    let mut next = start.clone();
    let mut members = vec![0usize; start[aggregates]];
    for (node, &a) in agg.iter().enumerate() {
        if a != ISOLATED {
            members[next[a as usize]] = node;
            next[a as usize] += 1;
        }
    }
    let mut blocks: Vec<Block<N, MODES>> = vec![zero(); modes.len()];
    let mut coarse_modes = Vec::with_capacity(aggregates);
    for a in 0..aggregates {
        let nodes = &members[start[a]..start[a + 1]];
        let column = |c: usize| -> Vec<f64> {
            nodes
                .iter()
                .flat_map(|&node| modes[node].iter().map(move |row| row[c]))
                .collect()
        };
        let scale = (0..MODES)
            .map(|c| column(c).iter().map(|v| v * v).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let mut basis: Vec<Vec<f64>> = Vec::new();
        let mut r: Block<MODES, MODES> = zero();
        for c in 0..MODES {
            let mut v = column(c);
            let mut coefficients = [0.0; MODES];
            for _ in 0..2 {
                for (k, b) in basis.iter().enumerate() {
                    let p: f64 = b.iter().zip(&v).map(|(x, y)| x * y).sum();
                    v.iter_mut().zip(b).for_each(|(vi, bi)| *vi -= p * bi);
                    coefficients[k] += p;
                }
            }
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm > 1e-10 * scale && norm > 0.0 {
                coefficients[basis.len()] = norm;
                v.iter_mut().for_each(|x| *x /= norm);
                basis.push(v);
            }
            // Column c of R: the coefficients of B's column c.
            for (row, &coefficient) in r.iter_mut().zip(&coefficients) {
                row[c] = coefficient;
            }
        }
        for (m, &node) in nodes.iter().enumerate() {
            for (j, b) in basis.iter().enumerate() {
                for (row, block_row) in blocks[node].iter_mut().enumerate() {
                    block_row[j] = b[N * m + row];
                }
            }
        }
        coarse_modes.push(r);
    }
    let mut t = Bsr {
        cols: aggregates,
        row_ptr: Vec::with_capacity(modes.len() + 1),
        col_idx: Vec::with_capacity(modes.len()),
        values: Vec::with_capacity(modes.len()),
    };
    t.row_ptr.push(0);
    for (&a, block) in agg.iter().zip(blocks) {
        if a != ISOLATED {
            t.col_idx.push(a);
            t.values.push(block);
        }
        t.row_ptr.push(t.col_idx.len());
    }
    Tentative {
        t,
        modes: coarse_modes,
    }
}

/// The smoothed prolongator `P = (I − ω D⁻¹A) T` with `D = diag(A)` (one
/// entry per unknown) and `ω = 4/(3 λ_max(D⁻¹A))`, from `at = A T`, whose
/// pattern holds `T`'s.
pub(crate) fn smooth<const N: usize>(
    t: &Bsr<N, MODES>,
    at: &Bsr<N, MODES>,
    diagonal: &[f64],
    omega: f64,
) -> Bsr<N, MODES> {
    let mut p = at.clone();
    for (node, d) in diagonal.chunks_exact(N).enumerate() {
        let (start, end) = (p.row_ptr[node], p.row_ptr[node + 1]);
        for block in &mut p.values[start..end] {
            for (row, &dr) in block.iter_mut().zip(d) {
                row.iter_mut().for_each(|v| *v *= -omega / dr);
            }
        }
        let (cols, blocks) = t.row(node);
        for (&c, tb) in cols.iter().zip(blocks) {
            let k = p
                .position(node, c as usize)
                .expect("A T holds T's pattern: A's diagonal is nonzero");
            for (row, t_row) in p.values[k].iter_mut().zip(tb) {
                row.iter_mut().zip(t_row).for_each(|(v, tv)| *v += tv);
            }
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two aggregates of two 3-D nodes: the first carries the six rigid
    /// modes of two points, which span only five directions (a rotation
    /// about the line through them moves neither), the second one node with
    /// every mode filtered out but translations.
    #[test]
    fn tentative_prolongator_is_orthonormal_and_reproduces_the_modes() {
        let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        let mut modes = Vec::new();
        for p in points {
            for a in 0..3 {
                let mut row = [0.0; MODES];
                row[a] = 1.0;
                // Columns 3..5: e_x × p, e_y × p, e_z × p.
                let cross = [[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]];
                for w in 0..3 {
                    row[3 + w] = cross[w][a];
                }
                modes.push(row);
            }
        }
        for row in &mut modes[6..] {
            row[3..].fill(0.0);
        }
        let blocks: Vec<Block<3, MODES>> = modes
            .chunks_exact(3)
            .map(|rows| [rows[0], rows[1], rows[2]])
            .collect();
        let tent = tentative(&blocks, &[0, 0, 1], 2);
        assert_eq!(tent.t.cols, 2);
        // Columns of T as dense rows of 12 coarse unknowns.
        let dense = |row: usize| {
            let mut out = [0.0; 2 * MODES];
            let (cols, blocks) = tent.t.row(row / 3);
            for (&c, block) in cols.iter().zip(blocks) {
                for (k, v) in block[row % 3].iter().enumerate() {
                    out[MODES * c as usize + k] = *v;
                }
            }
            out
        };
        // TᵀT = I on the 5 + 3 unknowns the modes span, 0 on the padding.
        let spanned = [1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
        for (i, &on) in spanned.iter().enumerate() {
            for j in 0..2 * MODES {
                let g: f64 = (0..9).map(|r| dense(r)[i] * dense(r)[j]).sum();
                let expected = if i == j { on } else { 0.0 };
                assert!((g - expected).abs() < 1e-12, "({i}, {j}): {g}");
            }
        }
        // T R = B.
        for (row, mode) in modes.iter().enumerate() {
            for (c, &expected) in mode.iter().enumerate() {
                let tr: f64 = (0..2 * MODES)
                    .map(|k| dense(row)[k] * tent.modes[k / MODES][k % MODES][c])
                    .sum();
                assert!((tr - expected).abs() < 1e-12, "row {row}, mode {c}");
            }
        }
    }
}
