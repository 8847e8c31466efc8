//! Scalar compressed-row matrices: the input of the sparse Cholesky of
//! [`ScalarCholesky`](super::coarse::ScalarCholesky).

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
}
