//! Scalar compressed-row matrices: the input of the sparse Cholesky of
//! [`ScalarCholesky`](super::coarse::ScalarCholesky), and the operators and
//! transfers of the scalar multigrid (`scalar` module), with their products.

use crate::linear::vector::for_each_row;

/// A real sparse matrix in compressed rows with 32-bit column indices,
/// columns sorted within each row.
#[derive(Debug, Default)]
pub(crate) struct Csr {
    pub(crate) row_ptr: Vec<usize>,
    pub(crate) col_idx: Vec<u32>,
    pub(crate) values: Vec<f64>,
}

impl Csr {
    /// Number of rows.
    pub(crate) fn rows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// Bytes held by the index and value arrays.
    pub(crate) fn bytes(&self) -> usize {
        8 * self.row_ptr.len() + 4 * self.col_idx.len() + 8 * self.values.len()
    }

    /// `y = A x`, by rows in parallel for a long `y`.
    pub(crate) fn apply(&self, x: &[f64], y: &mut [f64]) {
        for_each_row(y, |i, yi| {
            *yi = (self.row_ptr[i]..self.row_ptr[i + 1])
                .map(|k| self.values[k] * x[self.col_idx[k] as usize])
                .sum();
        });
    }

    /// The product `A B` of `B` with `columns` columns, columns sorted
    /// within each row (Gustavson's row-by-row product).
    pub(crate) fn product(&self, b: &Csr, columns: usize) -> Csr {
        let mut c = Csr {
            row_ptr: Vec::with_capacity(self.rows() + 1),
            ..Csr::default()
        };
        c.row_ptr.push(0);
        // Per column, its position in the current row of `c` (if at or
        // after the row's start).
        let mut at = vec![usize::MAX; columns];
        let mut row: Vec<(u32, f64)> = Vec::new();
        for i in 0..self.rows() {
            row.clear();
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                let (j, v) = (self.col_idx[k] as usize, self.values[k]);
                for m in b.row_ptr[j]..b.row_ptr[j + 1] {
                    let col = b.col_idx[m];
                    let slot = &mut at[col as usize];
                    if *slot < row.len() && row[*slot].0 == col {
                        row[*slot].1 += v * b.values[m];
                    } else {
                        *slot = row.len();
                        row.push((col, v * b.values[m]));
                    }
                }
            }
            row.sort_unstable_by_key(|e| e.0);
            c.col_idx.extend(row.iter().map(|e| e.0));
            c.values.extend(row.iter().map(|e| e.1));
            c.row_ptr.push(c.col_idx.len());
        }
        c
    }

    /// `Aᵀ`, for `A` with `columns` columns.
    pub(crate) fn transpose(&self, columns: usize) -> Csr {
        let mut row_ptr = vec![0usize; columns + 1];
        for &j in &self.col_idx {
            row_ptr[j as usize + 1] += 1;
        }
        for j in 0..columns {
            row_ptr[j + 1] += row_ptr[j];
        }
        let mut next = row_ptr.clone();
        let mut col_idx = vec![0u32; self.col_idx.len()];
        let mut values = vec![0.0; self.values.len()];
        for i in 0..self.rows() {
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col_idx[k] as usize;
                col_idx[next[j]] = i as u32;
                values[next[j]] = self.values[k];
                next[j] += 1;
            }
        }
        Csr {
            row_ptr,
            col_idx,
            values,
        }
    }
}
