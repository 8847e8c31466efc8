//! The pattern of the scalar matrix over the free particles, and where
//! each spring's term goes in its values.

use hooke_core::System;

use crate::linear::amg::csr::Csr;
use crate::linear::cholesky::SpringRoute;

/// The matrix's pattern over the free particles and where each spring's
/// term goes in its values.
#[derive(Debug)]
pub(super) struct Layout {
    /// The matrix in compressed rows (its values refilled at every
    /// factorization).
    pub(super) a: Csr,
    /// Per free particle, its diagonal entry in `a`'s values.
    pub(super) diagonal: Vec<u32>,
    /// Per spring, the entries `(i, i), (j, j), (i, j), (j, i)` of `a`'s
    /// values it adds to (`u32::MAX` where an end is pinned, and all four
    /// for a routed spring).
    pub(super) entries: Vec<[u32; 4]>,
    /// The routed springs: each one's index, the entries of its two legs
    /// (as in `entries`) and their weights.
    pub(super) routed: Vec<(u32, [[u32; 4]; 2], [f64; 2])>,
}

impl Layout {
    /// The layout of `system`'s matrix over the unknowns `unknown`
    /// (`u32::MAX` for a pinned particle) with the springs `routes` carried
    /// on their legs (sorted by spring); `None` beyond 32-bit indices.
    pub(super) fn new(system: &System, unknown: &[u32], routes: &[SpringRoute]) -> Option<Self> {
        let free = unknown.iter().filter(|&&u| u != u32::MAX).count();
        let is_routed = |k: usize| routes.binary_search_by_key(&k, |r| r.spring).is_ok();
        // (row, column) of both triangles, with the particles' diagonals.
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(free + 2 * system.springs().len());
        pairs.extend((0..free as u32).map(|u| (u, u)));
        for (k, s) in system.springs().iter().enumerate() {
            let (ui, uj) = (unknown[s.i], unknown[s.j]);
            if ui != u32::MAX && uj != u32::MAX && !is_routed(k) {
                pairs.push((ui, uj));
                pairs.push((uj, ui));
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        if pairs.len() >= u32::MAX as usize {
            return None;
        }
        let mut a = Csr {
            row_ptr: vec![0; free + 1],
            col_idx: pairs.iter().map(|&(_, c)| c).collect(),
            values: vec![0.0; pairs.len()],
        };
        for &(r, _) in &pairs {
            a.row_ptr[r as usize + 1] += 1;
        }
        for r in 0..free {
            a.row_ptr[r + 1] += a.row_ptr[r];
        }
        let at = |r: u32, c: u32| -> u32 {
            if r == u32::MAX || c == u32::MAX {
                return u32::MAX;
            }
            let row = a.row_ptr[r as usize]..a.row_ptr[r as usize + 1];
            let k = row.start
                + a.col_idx[row]
                    .binary_search(&c)
                    .expect("every spring's entries are in the pattern");
            k as u32
        };
        let diagonal = (0..free as u32).map(|u| at(u, u)).collect();
        // The entries a term between particles `i` and `j` adds to.
        let between = |i: usize, j: usize| {
            let (ui, uj) = (unknown[i], unknown[j]);
            let off = |r, c| {
                if ui == u32::MAX || uj == u32::MAX {
                    u32::MAX
                } else {
                    at(r, c)
                }
            };
            [at(ui, ui), at(uj, uj), off(ui, uj), off(uj, ui)]
        };
        let entries = system
            .springs()
            .iter()
            .enumerate()
            .map(|(k, s)| {
                if is_routed(k) {
                    [u32::MAX; 4]
                } else {
                    between(s.i, s.j)
                }
            })
            .collect();
        let routed = routes
            .iter()
            .map(|r| {
                let s = &system.springs()[r.spring];
                let legs = [between(s.i, r.middle), between(r.middle, s.j)];
                (r.spring as u32, legs, r.weights)
            })
            .collect();
        Some(Self {
            a,
            diagonal,
            entries,
            routed,
        })
    }
}
