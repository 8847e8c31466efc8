//! [`TetSplit`]: the ways a lattice cube is cut into tetrahedra.

/// How each cube of a tetrahedral [`crate::Lattice`] is split.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TetSplit {
    /// Five tets: four corner tets of volume 1/6 around a central one of
    /// volume 1/3; the split alternates with the parity of `i + j + k` so
    /// that neighbouring cubes share face diagonals. No body diagonals.
    Five,
    /// Six tets of volume 1/6 around the body diagonal from corner
    /// `(0, 0, 0)` to `(1, 1, 1)` (the Kuhn split); every cube alike.
    Six,
}

/// The tets of one cube as corner numbers `c = x + 2y + 4z`.
pub(crate) fn cell_tets(split: TetSplit, odd: bool) -> Vec<[usize; 4]> {
    match (split, odd) {
        // Paths 0 → (0,0,0) + e_a → + e_b → (1,1,1) over the axis orders.
        (TetSplit::Six, _) => [
            [1, 2, 4],
            [1, 4, 2],
            [2, 1, 4],
            [2, 4, 1],
            [4, 1, 2],
            [4, 2, 1],
        ]
        .iter()
        .map(|[a, b, c]| [0, *a, a + b, a + b + c])
        .collect(),
        (TetSplit::Five, false) => vec![
            [0, 3, 5, 6],
            [1, 0, 3, 5],
            [2, 0, 3, 6],
            [4, 0, 5, 6],
            [7, 3, 5, 6],
        ],
        (TetSplit::Five, true) => vec![
            [1, 2, 4, 7],
            [0, 1, 2, 4],
            [3, 1, 2, 7],
            [5, 1, 4, 7],
            [6, 2, 4, 7],
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::signed_volume;
    use hooke_core::Vec3;

    #[test]
    fn every_split_fills_the_unit_cube_exactly() {
        let corner = |c: usize| Vec3::new((c & 1) as f64, (c >> 1 & 1) as f64, (c >> 2) as f64);
        for (split, odd, count) in [
            (TetSplit::Five, false, 5),
            (TetSplit::Five, true, 5),
            (TetSplit::Six, false, 6),
        ] {
            let tets = cell_tets(split, odd);
            assert_eq!(tets.len(), count);
            let volumes: Vec<f64> = tets
                .iter()
                .map(|t| signed_volume(t.map(corner)).abs())
                .collect();
            assert!(volumes.iter().all(|&v| v > 0.1), "{split:?} {volumes:?}");
            assert!((volumes.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        }
    }
}
