//! [`Hessian`]: where a term writes its Hessian blocks.

use std::any::Any;

use crate::{Mat3, SymBlock};

/// Where a [`Term`](super::Term) writes the 3 × 3 blocks of its Hessian:
/// a minimiser's assembled matrix, the diagonal blocks alone (the
/// quasi-Newton step's stand-in for stiff terms), a collection of blocks
/// (the lab's spectrum), or nowhere — `()`, for the gradient alone.
///
/// A term with a faster path into a sink it knows by type (the springs and
/// volume elements into the implicit step's block matrix) finds it through
/// [`Hessian::as_any_mut`] and takes the generic path otherwise.
pub trait Hessian {
    /// Adds the symmetric block `B` to particle `i`'s diagonal block.
    fn add_row(&mut self, i: usize, block: SymBlock);

    /// Adds `B` at `(i, j)` and `Bᵀ` at `(j, i)`, `i ≠ j`.
    fn add_pair(&mut self, i: usize, j: usize, block: Mat3);

    /// Adds `sᵢ I`, `sᵢ = scale(i)`, to the diagonal block of each of the
    /// `n` particles: the Hessian of a term that acts on each particle
    /// alike in every direction (the mass matrix, air damping), which an
    /// assembled matrix can keep apart from the other blocks.
    fn add_identity(&mut self, n: usize, scale: &(dyn Fn(usize) -> f64 + Sync)) {
        for i in 0..n {
            self.add_row(i, SymBlock::scaled_identity(scale(i)));
        }
    }

    /// The sink as [`Any`], for a term's faster path into a sink it knows;
    /// `None` for a sink that offers none.
    fn as_any_mut(&mut self) -> Option<&mut dyn Any> {
        None
    }
}

/// No blocks: the gradient alone.
impl Hessian for () {
    fn add_row(&mut self, _: usize, _: SymBlock) {}

    fn add_pair(&mut self, _: usize, _: usize, _: Mat3) {}

    fn add_identity(&mut self, _: usize, _: &(dyn Fn(usize) -> f64 + Sync)) {}
}

/// A sink through a reference to it, so that code generic over sinks also
/// takes `&mut dyn Hessian`.
impl<H: Hessian + ?Sized> Hessian for &mut H {
    fn add_row(&mut self, i: usize, block: SymBlock) {
        (**self).add_row(i, block);
    }

    fn add_pair(&mut self, i: usize, j: usize, block: Mat3) {
        (**self).add_pair(i, j, block);
    }

    fn add_identity(&mut self, n: usize, scale: &(dyn Fn(usize) -> f64 + Sync)) {
        (**self).add_identity(n, scale);
    }

    fn as_any_mut(&mut self) -> Option<&mut dyn Any> {
        (**self).as_any_mut()
    }
}
