//! Scalar compressed-row matrices for the multigrid hierarchy: products with
//! vectors and with each other, whose patterns are computed once and whose
//! values are refilled in place.

/// Rows from which a product runs in parallel: a row of a coarse operator
/// or a prolongator costs tens to hundreds of multiply-adds, so far fewer
/// rows than a vector operation's [`PARALLEL_MIN_PARTICLES`] pay for the
/// workers.
///
/// [`PARALLEL_MIN_PARTICLES`]: crate::PARALLEL_MIN_PARTICLES
#[cfg(feature = "parallel")]
const PARALLEL_MIN_ROWS: usize = 2048;

/// A real sparse matrix in compressed rows with 32-bit column indices,
/// columns sorted within each row.
#[derive(Debug, Clone, Default)]
pub(crate) struct Csr {
    pub(crate) cols: usize,
    pub(crate) row_ptr: Vec<usize>,
    pub(crate) col_idx: Vec<u32>,
    pub(crate) values: Vec<f64>,
}

impl Csr {
    /// Number of rows.
    pub(crate) fn rows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// The entries of row `i`: their columns and values.
    #[inline]
    pub(crate) fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let r = self.row_ptr[i]..self.row_ptr[i + 1];
        (&self.col_idx[r.clone()], &self.values[r])
    }

    /// Bytes held by the index and value arrays.
    pub(crate) fn bytes(&self) -> usize {
        8 * self.row_ptr.len() + 4 * self.col_idx.len() + 8 * self.values.len()
    }

    /// The position of entry `(i, j)` in `values`, if it is in the pattern.
    pub(crate) fn position(&self, i: usize, j: usize) -> Option<usize> {
        let start = self.row_ptr[i];
        self.col_idx[start..self.row_ptr[i + 1]]
            .binary_search(&(j as u32))
            .ok()
            .map(|k| start + k)
    }

    /// `y = self · x`, rows in parallel for large matrices.
    pub(crate) fn apply(&self, x: &[f64], y: &mut [f64]) {
        let row = |i: usize| {
            let (cols, vals) = self.row(i);
            cols.iter().zip(vals).map(|(&j, v)| v * x[j as usize]).sum()
        };
        for_each_scalar(y, |i, yi| *yi = row(i));
    }

    /// The pattern of `self · other` with zero values, and per entry of the
    /// product nothing more: [`Csr::multiply_into`] refills it.
    pub(crate) fn product_pattern(&self, other: &Self) -> Self {
        let mut marker = vec![usize::MAX; other.cols];
        let mut row_ptr = Vec::with_capacity(self.rows() + 1);
        let mut col_idx = Vec::new();
        row_ptr.push(0);
        for i in 0..self.rows() {
            let start = col_idx.len();
            for &k in self.row(i).0 {
                for &j in other.row(k as usize).0 {
                    if marker[j as usize] != i {
                        marker[j as usize] = i;
                        col_idx.push(j);
                    }
                }
            }
            col_idx[start..].sort_unstable();
            row_ptr.push(col_idx.len());
        }
        Self {
            cols: other.cols,
            values: vec![0.0; col_idx.len()],
            row_ptr,
            col_idx,
        }
    }

    /// Refills `product`, whose pattern is [`Csr::product_pattern`] of
    /// `self` and `other`, with `self · other`, rows in parallel; each
    /// worker scatters into its row through a map from column to position.
    pub(crate) fn multiply_into(&self, other: &Self, product: &mut Self) {
        let Self {
            row_ptr,
            col_idx,
            values,
            cols,
        } = product;
        let fill = |position: &mut Vec<u32>, i: usize, out: &mut [f64]| {
            position.resize(*cols, 0);
            out.fill(0.0);
            for (p, &c) in col_idx[row_ptr[i]..row_ptr[i + 1]].iter().enumerate() {
                position[c as usize] = p as u32;
            }
            let (ks, avs) = self.row(i);
            for (&k, &a) in ks.iter().zip(avs) {
                let (js, bvs) = other.row(k as usize);
                for (&j, &b) in js.iter().zip(bvs) {
                    out[position[j as usize] as usize] += a * b;
                }
            }
        };
        for_each_row_slice(values, row_ptr, fill);
    }

    /// The transpose.
    pub(crate) fn transpose(&self) -> Self {
        let mut count = vec![0usize; self.cols + 1];
        for &j in &self.col_idx {
            count[j as usize + 1] += 1;
        }
        for j in 0..self.cols {
            count[j + 1] += count[j];
        }
        let row_ptr = count.clone();
        let mut col_idx = vec![0u32; self.col_idx.len()];
        let mut values = vec![0.0; self.values.len()];
        for i in 0..self.rows() {
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col_idx[k] as usize;
                col_idx[count[j]] = i as u32;
                values[count[j]] = self.values[k];
                count[j] += 1;
            }
        }
        Self {
            cols: self.rows(),
            row_ptr,
            col_idx,
            values,
        }
    }
}

/// Calls `f(i, &mut out[i])` for every `i`, in parallel for long vectors
/// (each `f` being a row of a product).
pub(crate) fn for_each_scalar(out: &mut [f64], f: impl Fn(usize, &mut f64) + Sync + Send) {
    #[cfg(feature = "parallel")]
    if out.len() >= PARALLEL_MIN_ROWS {
        use rayon::prelude::*;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(PARALLEL_MIN_ROWS / 2)
            .for_each(|(i, o)| f(i, o));
        return;
    }
    for (i, o) in out.iter_mut().enumerate() {
        f(i, o);
    }
}

/// Calls `f(scratch, i, values[ptr[i]..ptr[i + 1]])` for every row `i`, in
/// parallel for long arrays, with a scratch vector per worker.
pub(crate) fn for_each_row_slice(
    values: &mut [f64],
    ptr: &[usize],
    f: impl Fn(&mut Vec<u32>, usize, &mut [f64]) + Sync + Send,
) {
    let rows = ptr.len() - 1;
    #[cfg(feature = "parallel")]
    if rows >= PARALLEL_MIN_ROWS {
        use rayon::prelude::*;
        let threads = rayon::current_num_threads().max(1);
        let chunk = rows.div_ceil(4 * threads);
        let mut pieces = Vec::with_capacity(rows.div_ceil(chunk));
        let mut rest = values;
        for start in (0..rows).step_by(chunk) {
            let end = (start + chunk).min(rows);
            let (piece, tail) = rest.split_at_mut(ptr[end] - ptr[start]);
            pieces.push((start..end, piece));
            rest = tail;
        }
        pieces
            .into_par_iter()
            .for_each_init(Vec::new, |scratch, (range, piece)| {
                let base = ptr[range.start];
                for i in range {
                    f(scratch, i, &mut piece[ptr[i] - base..ptr[i + 1] - base]);
                }
            });
        return;
    }
    let mut scratch = Vec::new();
    for i in 0..rows {
        let (start, end) = (ptr[i], ptr[i + 1]);
        f(&mut scratch, i, &mut values[start..end]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dense(m: &Csr) -> Vec<Vec<f64>> {
        let mut d = vec![vec![0.0; m.cols]; m.rows()];
        for (i, row) in d.iter_mut().enumerate() {
            let (cols, vals) = m.row(i);
            for (&j, &v) in cols.iter().zip(vals) {
                row[j as usize] += v;
            }
        }
        d
    }

    fn matrix(rows: usize, cols: usize, seed: u64) -> Csr {
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize
        };
        let mut m = Csr {
            cols,
            row_ptr: vec![0],
            ..Csr::default()
        };
        for _ in 0..rows {
            let mut js: Vec<u32> = (0..3).map(|_| (next() % cols) as u32).collect();
            js.sort_unstable();
            js.dedup();
            for j in js {
                m.col_idx.push(j);
                m.values.push((next() % 1000) as f64 / 100.0 - 5.0);
            }
            m.row_ptr.push(m.col_idx.len());
        }
        m
    }

    #[test]
    fn products_and_transposes_match_dense_arithmetic() {
        let (a, b) = (matrix(7, 5, 1), matrix(5, 6, 2));
        let mut c = a.product_pattern(&b);
        a.multiply_into(&b, &mut c);
        let (da, db, dc) = (dense(&a), dense(&b), dense(&c));
        for i in 0..7 {
            for j in 0..6 {
                let expected: f64 = (0..5).map(|k| da[i][k] * db[k][j]).sum();
                assert!((dc[i][j] - expected).abs() < 1e-12, "({i}, {j})");
            }
        }
        let t = a.transpose();
        let dt = dense(&t);
        for i in 0..7 {
            for j in 0..5 {
                assert!((dt[j][i] - da[i][j]).abs() < 1e-15);
            }
        }
        let x: Vec<f64> = (0..5).map(|k| k as f64 - 1.5).collect();
        let mut y = vec![0.0; 7];
        a.apply(&x, &mut y);
        for i in 0..7 {
            let expected: f64 = (0..5).map(|k| da[i][k] * x[k]).sum();
            assert!((y[i] - expected).abs() < 1e-12);
        }
    }
}
