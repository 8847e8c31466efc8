//! The sparsity pattern of a spring system's matrix, built once per topology.

use hooke_core::{StepError, System};

/// One off-diagonal block of a block row: the column (particle) and the spring
/// that couples the two.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Entry {
    column: u32,
    spring: u32,
}

impl Entry {
    /// The column's particle.
    #[inline]
    #[must_use]
    pub fn column(self) -> usize {
        self.column as usize
    }

    /// The spring that couples this row to [`Entry::column`].
    #[inline]
    #[must_use]
    pub fn spring(self) -> usize {
        self.spring as usize
    }
}

/// Which blocks of the `3n × 3n` matrix `A = M + βh C + β²h² K` can be
/// nonzero: the diagonal block of every particle and, for every spring
/// `(i, j)`, the blocks `(i, j)` and `(j, i)`.
///
/// Block row `i` lists one [`Entry`] per spring at `i`, sorted by column. The
/// pattern depends on the springs' endpoints only, so it is built once and
/// every step refills values. A scene without springs has empty rows; no term
/// it does not declare enters the pattern.
#[derive(Debug, Clone)]
pub struct Pattern {
    row_start: Vec<u32>,
    entries: Vec<Entry>,
}

impl Pattern {
    /// The pattern of `system`'s springs.
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] if the particles or the entries (two per
    /// spring) do not fit 32-bit indices.
    pub fn new(system: &System) -> Result<Self, StepError> {
        let (particles, springs) = (system.particle_count(), system.springs().len());
        let too_large = || StepError::SystemTooLarge { particles, springs };
        if u32::try_from(particles).is_err() || u32::try_from(2 * springs).is_err() {
            return Err(too_large());
        }
        let mut counts = vec![0u32; particles + 1];
        for s in system.springs() {
            counts[s.i + 1] += 1;
            counts[s.j + 1] += 1;
        }
        let mut row_start = counts;
        for p in 0..particles {
            row_start[p + 1] += row_start[p];
        }
        let mut next: Vec<usize> = row_start.iter().map(|&r| r as usize).collect();
        let mut entries = vec![
            Entry {
                column: 0,
                spring: 0
            };
            2 * springs
        ];
        for (k, s) in system.springs().iter().enumerate() {
            // Both fit: checked above.
            let k = k as u32;
            entries[next[s.i]] = Entry {
                column: s.j as u32,
                spring: k,
            };
            next[s.i] += 1;
            entries[next[s.j]] = Entry {
                column: s.i as u32,
                spring: k,
            };
            next[s.j] += 1;
        }
        let mut pattern = Self { row_start, entries };
        for row in 0..particles {
            let range = pattern.range(row);
            pattern.entries[range].sort_unstable_by_key(|e| e.column);
        }
        Ok(pattern)
    }

    /// Number of block rows (particles).
    #[must_use]
    pub fn rows(&self) -> usize {
        self.row_start.len() - 1
    }

    /// Number of stored off-diagonal entries (twice the springs).
    #[must_use]
    pub fn entry_count(&self) -> usize {
        self.entries.len()
    }

    /// The off-diagonal entries of block row `row`, sorted by column.
    #[inline]
    #[must_use]
    pub fn row(&self, row: usize) -> &[Entry] {
        &self.entries[self.range(row)]
    }

    fn range(&self, row: usize) -> std::ops::Range<usize> {
        self.row_start[row] as usize..self.row_start[row + 1] as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hooke_core::SystemBuilder;

    #[test]
    fn rows_list_each_spring_once_per_end_sorted_by_column() {
        let mut b = SystemBuilder::new();
        for k in 0..4 {
            b.particle(1.0, [k as f64, 0.0, 0.0]);
        }
        b.spring(2, 0, 1.0);
        b.spring(0, 3, 1.0);
        b.spring(1, 2, 1.0);
        let pattern = Pattern::new(&b.build().unwrap()).unwrap();
        assert_eq!(pattern.rows(), 4);
        assert_eq!(pattern.entry_count(), 6);
        let row0: Vec<_> = pattern
            .row(0)
            .iter()
            .map(|e| (e.column(), e.spring()))
            .collect();
        assert_eq!(row0, vec![(2, 0), (3, 1)]);
        let row2: Vec<_> = pattern
            .row(2)
            .iter()
            .map(|e| (e.column(), e.spring()))
            .collect();
        assert_eq!(row2, vec![(0, 0), (1, 2)]);
        assert!(pattern.row(3).iter().all(|e| e.column() == 0));
    }
}
