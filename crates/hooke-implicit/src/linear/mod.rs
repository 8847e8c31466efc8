//! The linear algebra: the 3×3-block matrix and its pattern, the
//! per-particle filters, PCG, sparse Cholesky, smoothed-aggregation
//! multigrid, and the choice among them for each Newton step's system.

pub mod amg;
pub mod cg;
pub(crate) mod cholesky;
pub(crate) mod filter;
pub(crate) mod laplacian;
pub(crate) mod matrix;
pub(crate) mod neighbours;
pub(crate) mod pattern;
pub(crate) mod solver;
pub(crate) mod vector;
