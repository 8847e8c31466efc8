//! Solves with the factor: of the filtered system that was factorized,
//! and as a preconditioner of PCG on a later matrix of the same pattern.

use std::cell::RefCell;

use faer::dyn_stack::MemStack;
use faer::sparse::linalg::cholesky::LltRef;
use faer::{Conj, MatMut};
use hooke_core::Vec3;

use super::{CholeskyError, SparseCholesky};
use crate::linear::cg::{self, PcgError, PcgInfo, PcgSettings, PcgWorkspace, Preconditioner};
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;

impl SparseCholesky {
    /// Solves `(S A S + I − S) x = S b`, the filtered system, into `x`.
    ///
    /// # Errors
    /// [`CholeskyError::NotPositiveDefinite`] if the filtered matrix is not
    /// positive definite.
    pub fn solve(
        &mut self,
        a: &BlockMatrix,
        filters: &[Filter],
        b: &[Vec3],
        x: &mut [Vec3],
    ) -> Result<(), CholeskyError> {
        self.factorize(a, filters)?;
        self.solve_factored(filters, b, x);
        Ok(())
    }

    /// `x = S L⁻ᵀ L⁻¹ S b` with the factor `L Lᵀ` of the last
    /// [`SparseCholesky::factorize`] (zero before the first): the solution
    /// of the filtered system that was factorized, and for a later matrix
    /// of the same pattern (a later Newton iteration, a later step) a
    /// preconditioner ([`SparseCholesky::preconditioner`]).
    pub fn solve_factored(&mut self, filters: &[Filter], b: &[Vec3], x: &mut [Vec3]) {
        let dofs = self.rhs.len();
        for (i, (bi, f)) in b.iter().zip(filters).enumerate() {
            let k = 3 * self.order[i] as usize;
            self.rhs[k..k + 3].copy_from_slice(f.apply(*bi).as_slice());
        }
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.rhs, dofs, 1),
            self.par,
            MemStack::new(&mut self.solve_memory),
        );
        for (i, (xi, f)) in x.iter_mut().zip(filters).enumerate() {
            let k = 3 * self.order[i] as usize;
            *xi = f.apply(Vec3::from_column_slice(&self.rhs[k..k + 3]));
        }
    }

    /// Solves the filtered system of `a` with the last factor: directly
    /// where it is of the whole matrix ([`SparseCholesky::is_complete`],
    /// `None`), otherwise by PCG on `a` from zero, preconditioned by it, to
    /// `settings` (PCG's outcome).
    pub(crate) fn solve_filtered(
        &mut self,
        (a, filters): (&BlockMatrix, &[Filter]),
        b: &[Vec3],
        x: &mut [Vec3],
        settings: PcgSettings,
        workspace: &mut PcgWorkspace,
    ) -> Option<Result<PcgInfo, PcgError>> {
        if self.is_complete() {
            self.solve_factored(filters, b, x);
            return None;
        }
        x.fill(Vec3::zeros());
        let preconditioner = self.preconditioner(filters);
        Some(cg::solve(
            a,
            &preconditioner,
            filters,
            b,
            x,
            settings,
            workspace,
        ))
    }

    /// The last factor as a PCG preconditioner for the filters `filters`:
    /// `P⁻¹ r = S L⁻ᵀ L⁻¹ S r`, symmetric positive definite whatever matrix
    /// was factorized, and exact for that one.
    pub fn preconditioner<'a>(&'a mut self, filters: &'a [Filter]) -> FactorPreconditioner<'a> {
        FactorPreconditioner {
            cholesky: RefCell::new(self),
            filters,
        }
    }
}

/// A factor of an earlier matrix preconditioning PCG:
/// [`SparseCholesky::preconditioner`].
#[derive(Debug)]
pub struct FactorPreconditioner<'a> {
    cholesky: RefCell<&'a mut SparseCholesky>,
    filters: &'a [Filter],
}

impl Preconditioner for FactorPreconditioner<'_> {
    fn apply(&self, r: &[Vec3], z: &mut [Vec3]) {
        self.cholesky
            .borrow_mut()
            .solve_factored(self.filters, r, z);
    }
}
