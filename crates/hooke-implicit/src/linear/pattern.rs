//! The sparsity pattern of a spring system's matrix, built once per topology.

use std::ops::Range;

use hooke_core::{StepError, System};

/// Which blocks of the `3n × 3n` matrix `A = M + βh C + β²h² K` can be
/// nonzero, and where each spring's block is stored.
///
/// The diagonal block of every particle can be nonzero and, for every spring
/// `(i, j)`, the blocks `(i, j)` and `(j, i)`. Each spring's block is stored
/// once, in a *slot*: the slots are ordered by the spring's lower endpoint,
/// then its higher one, so the springs of block row `r` whose other end lies
/// beyond `r` — the upper triangle of the row — occupy a contiguous range of
/// slots ([`Pattern::upper`]). A product then streams through the blocks in
/// storage order, whatever order the scene declared its springs in.
///
/// The pattern depends on the springs' endpoints only, so it is built once
/// and every step refills values. A scene without springs has empty rows; no
/// term it does not declare enters the pattern.
#[derive(Debug, Clone)]
pub struct Pattern {
    /// Per row `r`, the slots `row_start[r]..row_start[r + 1]`.
    row_start: Vec<u32>,
    /// Per slot: the spring's higher endpoint.
    pub(crate) column: Vec<u32>,
    /// Per slot: the spring stored there.
    spring: Vec<u32>,
    /// Per spring: its slot.
    slot: Vec<u32>,
    /// The largest `column − row` over the slots (0 without springs).
    bandwidth: usize,
}

impl Pattern {
    /// The pattern of `system`'s springs.
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] if the particles or the springs do not
    /// fit 32-bit indices.
    pub fn new(system: &System) -> Result<Self, StepError> {
        let (particles, springs) = (system.particle_count(), system.springs().len());
        if u32::try_from(particles).is_err() || u32::try_from(springs).is_err() {
            return Err(StepError::SystemTooLarge { particles, springs });
        }
        // Bucket the springs by their lower endpoint, then sort each row's
        // few springs by their higher one.
        let ends = |s: &hooke_core::Spring| (s.i.min(s.j), s.i.max(s.j));
        let mut row_start = vec![0u32; particles + 1];
        for s in system.springs() {
            row_start[ends(s).0 + 1] += 1;
        }
        for r in 0..particles {
            row_start[r + 1] += row_start[r];
        }
        let mut next: Vec<u32> = row_start[..particles].to_vec();
        let mut spring = vec![0u32; springs];
        for (k, s) in system.springs().iter().enumerate() {
            let row = ends(s).0;
            // Both fit: checked above.
            spring[next[row] as usize] = k as u32;
            next[row] += 1;
        }
        let mut column = vec![0u32; springs];
        let mut slot = vec![0u32; springs];
        let mut bandwidth = 0;
        for row in 0..particles {
            let slots = row_start[row] as usize..row_start[row + 1] as usize;
            spring[slots.clone()].sort_unstable_by_key(|&k| ends(&system.springs()[k as usize]).1);
            for t in slots {
                let k = spring[t] as usize;
                let col = ends(&system.springs()[k]).1;
                column[t] = col as u32;
                slot[k] = t as u32;
                bandwidth = bandwidth.max(col - row);
            }
        }
        Ok(Self {
            row_start,
            column,
            spring,
            slot,
            bandwidth,
        })
    }

    /// Number of block rows (particles).
    #[must_use]
    pub fn rows(&self) -> usize {
        self.row_start.len() - 1
    }

    /// Number of slots: one per spring.
    #[must_use]
    pub fn slots(&self) -> usize {
        self.column.len()
    }

    /// The slots of the springs whose lower endpoint is `row`, sorted by
    /// their higher endpoint.
    #[inline]
    #[must_use]
    pub fn upper(&self, row: usize) -> Range<usize> {
        self.row_start[row] as usize..self.row_start[row + 1] as usize
    }

    /// The lower endpoint of the spring in `slot`.
    #[must_use]
    pub fn row_of(&self, slot: usize) -> usize {
        self.row_start
            .partition_point(|&start| start as usize <= slot)
            - 1
    }

    /// The higher endpoint of the spring in `slot`.
    #[inline]
    #[must_use]
    pub fn column(&self, slot: usize) -> usize {
        self.column[slot] as usize
    }

    /// The spring stored in `slot`.
    #[inline]
    #[must_use]
    pub fn spring(&self, slot: usize) -> usize {
        self.spring[slot] as usize
    }

    /// The slot of `spring`.
    #[inline]
    #[must_use]
    pub fn slot(&self, spring: usize) -> usize {
        self.slot[spring] as usize
    }

    /// The slot of the spring between particles `i` and `j`, if one joins
    /// them.
    #[must_use]
    pub fn slot_between(&self, i: usize, j: usize) -> Option<usize> {
        let (row, col) = (i.min(j), i.max(j));
        let slots = self.upper(row);
        let start = slots.start;
        self.column[slots]
            .binary_search(&u32::try_from(col).ok()?)
            .ok()
            .map(|k| start + k)
    }

    /// The largest distance `|i − j|` between the ends of a spring: every
    /// block lies within this many block rows of the diagonal.
    #[must_use]
    pub fn bandwidth(&self) -> usize {
        self.bandwidth
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hooke_core::SystemBuilder;

    #[test]
    fn slots_are_ordered_by_lower_then_higher_endpoint() {
        let mut b = SystemBuilder::new();
        for k in 0..4 {
            b.particle(1.0, [k as f64, 0.0, 0.0]);
        }
        b.spring(2, 0, 1.0);
        b.spring(3, 0, 1.0);
        b.spring(1, 2, 1.0);
        b.spring(0, 1, 1.0);
        let pattern = Pattern::new(&b.build().unwrap()).unwrap();
        assert_eq!(pattern.rows(), 4);
        assert_eq!(pattern.slots(), 4);
        let row = |r: usize| -> Vec<(usize, usize)> {
            pattern
                .upper(r)
                .map(|t| (pattern.column(t), pattern.spring(t)))
                .collect()
        };
        assert_eq!(row(0), vec![(1, 3), (2, 0), (3, 1)]);
        assert_eq!(row(1), vec![(2, 2)]);
        assert!(row(2).is_empty() && row(3).is_empty());
        for s in 0..4 {
            assert_eq!(pattern.spring(pattern.slot(s)), s);
        }
        assert_eq!(pattern.bandwidth(), 3);
        assert_eq!(pattern.slot_between(2, 0), Some(pattern.slot(0)));
        assert_eq!(pattern.slot_between(1, 2), Some(pattern.slot(2)));
        assert_eq!(pattern.slot_between(1, 3), None);
        assert_eq!(
            (0..4).map(|t| pattern.row_of(t)).collect::<Vec<_>>(),
            [0, 0, 0, 1]
        );
    }
}
