//! The particle graph of a [`Pattern`]: each particle's neighbours through
//! a spring, with the slot joining them. Multigrid reads the matrix's
//! couplings along it; sparse Cholesky orders and lays out the factor on it.

use crate::linear::pattern::Pattern;

/// Each particle's neighbours through a spring, in increasing order, with
/// the spring's slot: the block rows of `A` without the diagonal, in
/// compressed rows (both triangles).
#[derive(Debug, Default)]
pub(crate) struct Neighbours {
    ptr: Vec<usize>,
    entries: Vec<(u32, u32)>,
}

impl Neighbours {
    /// The neighbours in `pattern`.
    pub(crate) fn new(pattern: &Pattern) -> Self {
        let n = pattern.rows();
        let mut ptr = vec![0usize; n + 1];
        for i in 0..n {
            for t in pattern.upper(i) {
                ptr[i + 1] += 1;
                ptr[pattern.column(t) + 1] += 1;
            }
        }
        for i in 0..n {
            ptr[i + 1] += ptr[i];
        }
        let mut next = ptr.clone();
        let mut entries = vec![(0, 0); ptr[n]];
        // Rows in increasing order: a particle's lower neighbours arrive
        // first, in order, then its upper ones, in the pattern's order.
        for i in 0..n {
            for t in pattern.upper(i) {
                let j = pattern.column(t);
                entries[next[j]] = (i as u32, t as u32);
                next[j] += 1;
            }
            for t in pattern.upper(i) {
                entries[next[i]] = (pattern.column(t) as u32, t as u32);
                next[i] += 1;
            }
        }
        Self { ptr, entries }
    }

    /// The number of particles.
    pub(crate) fn particles(&self) -> usize {
        self.ptr.len() - 1
    }

    /// The neighbours of `i` and the slots joining them.
    #[inline]
    pub(crate) fn of(&self, i: usize) -> &[(u32, u32)] {
        &self.entries[self.ptr[i]..self.ptr[i + 1]]
    }

    /// Where each particle's neighbours start in [`Neighbours::entries`],
    /// and their end: `n + 1` offsets, so that a list with one value per
    /// entry (a strength mask, a weight) is read row by row.
    pub(crate) fn offsets(&self) -> &[usize] {
        &self.ptr
    }

    /// Every particle's neighbours and slots, row after row.
    pub(crate) fn entries(&self) -> &[(u32, u32)] {
        &self.entries
    }

    /// The bytes held.
    pub(crate) fn bytes(&self) -> usize {
        8 * self.ptr.len() + 8 * self.entries.len()
    }
}
