//! Prolongators: the tentative one from the near-null space on each
//! aggregate, and its Jacobi smoothing.

use super::aggregation::ISOLATED;
use super::csr::Csr;

/// Modes of the near-null space: three translations and three rotations.
pub(crate) const MODES: usize = 6;

/// The tentative prolongator of an aggregation and the coarse near-null
/// space.
#[derive(Debug)]
pub(crate) struct Tentative {
    /// `T`: per aggregate, an orthonormal basis of the near-null space's
    /// restriction to the aggregate's unknowns.
    pub(crate) t: Csr,
    /// The coarse nodes (one per aggregate) and their unknowns: as many as
    /// the aggregate's basis has vectors (at most six).
    pub(crate) node_ptr: Vec<usize>,
    /// The coarse near-null space `R`, with `B|_aggregate = Q R`.
    pub(crate) modes: Vec<[f64; MODES]>,
}

/// `T` and the coarse near-null space from the near-null space `modes` (one
/// row per unknown), the nodes' unknowns `node_ptr`, and the aggregation.
///
/// On each aggregate the rows of `B` are orthonormalised column by column
/// (Gram–Schmidt, twice for accuracy): `B|_a = Q_a R_a`, and a column whose
/// remainder is below `10⁻¹⁰` of the aggregate's largest column is dropped
/// — constrained unknowns (their rows of `B` filtered to zero) or
/// aggregates too small to carry all six modes have fewer coarse unknowns.
pub(crate) fn tentative(
    modes: &[[f64; MODES]],
    node_ptr: &[usize],
    agg: &[u32],
    aggregates: usize,
) -> Tentative {
    let nodes = node_ptr.len() - 1;
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
    // Per unknown: its aggregate's first coarse unknown and count, and its
    // column of Q.
    let dofs = node_ptr[nodes];
    let mut q = vec![[0.0; MODES]; dofs];
    let mut coarse_ptr = vec![0usize];
    let mut coarse_modes = Vec::new();
    let mut columns_of = vec![(0usize, 0usize); dofs];
    for a in 0..aggregates {
        let rows: Vec<usize> = members[start[a]..start[a + 1]]
            .iter()
            .flat_map(|&node| node_ptr[node]..node_ptr[node + 1])
            .collect();
        let column = |c: usize| -> Vec<f64> { rows.iter().map(|&r| modes[r][c]).collect() };
        let scale = (0..MODES)
            .map(|c| column(c).iter().map(|v| v * v).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let mut basis: Vec<Vec<f64>> = Vec::new();
        let mut r = Vec::new();
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
            r.push(coefficients);
        }
        let first = *coarse_ptr.last().expect("starts with 0");
        let k = basis.len();
        for (row_in, &row) in rows.iter().enumerate() {
            for (j, b) in basis.iter().enumerate() {
                q[row][j] = b[row_in];
            }
            columns_of[row] = (first, k);
        }
        // Row j of R: the coefficients of the coarse unknown j.
        coarse_modes.extend((0..k).map(|j| std::array::from_fn(|c| r[c][j])));
        coarse_ptr.push(first + k);
    }
    let mut t = Csr {
        cols: *coarse_ptr.last().expect("starts with 0"),
        row_ptr: Vec::with_capacity(dofs + 1),
        ..Csr::default()
    };
    t.row_ptr.push(0);
    for (&(first, k), q_row) in columns_of.iter().zip(&q) {
        t.col_idx.extend((first..first + k).map(|c| c as u32));
        t.values.extend_from_slice(&q_row[..k]);
        t.row_ptr.push(t.col_idx.len());
    }
    Tentative {
        t,
        node_ptr: coarse_ptr,
        modes: coarse_modes,
    }
}

/// The smoothed prolongator `P = (I − ω D⁻¹A) T` with `D = diag(A)` and
/// `ω = 4/(3 λ_max(D⁻¹A))`, from `at = A T`, whose pattern holds `T`'s.
pub(crate) fn smooth(t: &Csr, at: &Csr, diagonal: &[f64], omega: f64) -> Csr {
    let mut p = at.clone();
    for (row, d) in diagonal.iter().enumerate() {
        let scale = -omega / d;
        let (start, end) = (p.row_ptr[row], p.row_ptr[row + 1]);
        p.values[start..end].iter_mut().for_each(|v| *v *= scale);
        let (cols, vals) = t.row(row);
        for (&c, &v) in cols.iter().zip(vals) {
            let k = p
                .position(row, c as usize)
                .expect("A T holds T's pattern: A's diagonal is nonzero");
            p.values[k] += v;
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
        let node_ptr = [0, 3, 6, 9];
        let tent = tentative(&modes, &node_ptr, &[0, 0, 1], 2);
        assert_eq!(tent.node_ptr, [0, 5, 8]);
        // TᵀT = I and T R = B.
        let t = &tent.t;
        let dense = |row: usize| {
            let mut out = vec![0.0; t.cols];
            let (cols, vals) = t.row(row);
            cols.iter()
                .zip(vals)
                .for_each(|(&c, &v)| out[c as usize] = v);
            out
        };
        for i in 0..t.cols {
            for j in 0..t.cols {
                let g: f64 = (0..9).map(|r| dense(r)[i] * dense(r)[j]).sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((g - expected).abs() < 1e-12, "({i}, {j}): {g}");
            }
        }
        for (row, mode) in modes.iter().enumerate() {
            for (c, &expected) in mode.iter().enumerate() {
                let tr: f64 = (0..t.cols).map(|k| dense(row)[k] * tent.modes[k][c]).sum();
                assert!((tr - expected).abs() < 1e-12, "row {row}, mode {c}");
            }
        }
    }
}
