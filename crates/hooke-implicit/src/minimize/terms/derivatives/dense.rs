//! A term's Hessian written out as a dense matrix, and what the checks
//! ask of such matrices: their largest entry, their smallest eigenvalue,
//! their positive part, and a matrix's parts by the powers of `βh`.

use hooke_core::{Hessian, Mat3, SymBlock};
use nalgebra::{DMatrix, Matrix3};

/// A Hessian in the `3n` velocities as a dense matrix: particle `i`'s
/// coordinates in rows and columns `3i..3i + 3`.
#[derive(Debug, Clone)]
pub(super) struct Dense(pub(super) DMatrix<f64>);

impl Dense {
    /// Zero, for `n` particles.
    pub(super) fn new(n: usize) -> Self {
        Self(DMatrix::zeros(3 * n, 3 * n))
    }

    fn add_block(&mut self, i: usize, j: usize, block: &Mat3) {
        let mut view = self.0.fixed_view_mut::<3, 3>(3 * i, 3 * j);
        view += block;
    }
}

impl Hessian for Dense {
    fn add_row(&mut self, i: usize, block: SymBlock) {
        self.add_block(i, i, &block.to_mat3());
    }

    fn add_pair(&mut self, i: usize, j: usize, block: Mat3) {
        self.add_block(i, j, &block);
        self.add_block(j, i, &block.transpose());
    }
}

/// The largest entry of `m` in absolute value.
pub(super) fn largest(m: &DMatrix<f64>) -> f64 {
    m.amax()
}

/// The smallest eigenvalue of the symmetric part of `m`, and the particle
/// whose coordinates hold the largest part of its eigenvector.
pub(super) fn smallest_eigenvalue(m: &DMatrix<f64>) -> (f64, usize) {
    let eigen = (0.5 * (m + m.transpose())).symmetric_eigen();
    let k = eigen.eigenvalues.imin();
    let vector = eigen.eigenvectors.column(k);
    (eigen.eigenvalues[k], vector.iamax() / 3)
}

/// The positive part of the symmetric part of `m`: its eigenvalues below
/// zero set to zero.
pub(super) fn positive_part(m: &DMatrix<f64>) -> DMatrix<f64> {
    let mut eigen = (0.5 * (m + m.transpose())).symmetric_eigen();
    eigen.eigenvalues.apply(|l| *l = l.max(0.0));
    eigen.recompose()
}

/// The ratios `r` of `βh` at which a matrix `P(r βh) = P₀ + r βh P₁ +
/// r²β²h² P₂` is sampled to recover its parts.
pub(super) const RATIOS: [f64; 3] = [0.5, 1.0, 2.0];

/// The parts `[P₀, βh P₁, β²h² P₂]` at `βh` of a matrix quadratic in
/// `βh`, from its `samples` at [`RATIOS`] times `βh` (the inertia, the
/// dissipation potentials' and the potentials' parts of a term's Hessian;
/// see [`hooke_core::term`]), and how much each part magnifies an error
/// in the samples (the sum of its weights' magnitudes).
pub(super) fn parts(samples: &[DMatrix<f64>; 3]) -> [(DMatrix<f64>, f64); 3] {
    let vandermonde = Matrix3::from_fn(|k, power| RATIOS[k].powi(power as i32));
    let weights = vandermonde
        .try_inverse()
        .expect("distinct ratios give an invertible Vandermonde matrix");
    [0, 1, 2].map(|power| {
        let mut part = DMatrix::zeros(samples[0].nrows(), samples[0].ncols());
        for (k, sample) in samples.iter().enumerate() {
            part += weights[(power, k)] * sample;
        }
        let magnification = weights.row(power).iter().map(|w| w.abs()).sum();
        (part, magnification)
    })
}
