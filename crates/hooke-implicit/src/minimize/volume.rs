//! The volume elements' terms of a linearised step and their energy.

use hooke_core::{CompressedSprings, Mat3, System, TET_PAIRS, Tet, TetHessian, Vec3};

use super::linearization::Linearization;
use crate::linear::block::SymBlock;
use crate::linear::matrix::BlockMatrix;

/// The index in [`TET_PAIRS`] of the pair `(p, q)`, `p < q`.
fn pair_index(p: usize, q: usize) -> usize {
    match (p, q) {
        (0, q) => q - 1,
        (1, q) => q + 1,
        _ => 5,
    }
}

/// One element's share of a linearised step: `β²h²` times its Hessian's
/// diagonal blocks (symmetrised) and blocks between its vertices, and its
/// right-hand-side shares `−βh (∇E + H u)` at its four vertices.
#[derive(Debug, Clone, Copy, Default)]
struct ElementTerms {
    diagonal: [SymBlock; 4],
    pairs: [Mat3; 6],
    rhs: [Vec3; 4],
}

/// Element count from which the elements' blocks are evaluated in parallel
/// (with the `parallel` feature): an element's exact Hessian takes a few
/// tens of nanoseconds, its projected one about a microsecond, against the
/// tens of microseconds of waking the workers, and in parallel each
/// element's blocks are stored and read back to be added into the matrix
/// (in element order, serially), where the serial path adds them as they
/// are made. Measured on 2 cores, a whole assembly at a Newton iterate of
/// the jelly cube's lattice (exact element Hessians), median of seven:
/// 4 374 elements 0.45 ms serially, 0.48 ms in parallel; 10 368 elements
/// 1.11 ms and 0.89 ms; 82 944 elements 18.6 ms and 18.9 ms.
pub const PARALLEL_MIN_ELEMENTS: usize = 8192;

/// The volume elements' share of a linearised step, with their buffers.
#[derive(Debug, Clone, Default)]
pub(crate) struct VolumeTerms {
    /// Per element, when they are evaluated in parallel: its blocks and
    /// right-hand-side shares.
    #[cfg(feature = "parallel")]
    element_terms: Vec<ElementTerms>,
    /// Per element of the system identified by the first entry: the
    /// pattern's slot between each pair of its vertices, if a spring joins
    /// them.
    element_slots: (u64, Vec<[Option<usize>; 6]>),
    /// Per particle: the elements' diagonal blocks, and those plus the
    /// bounds of their blocks outside the pattern.
    rows: Vec<SymBlock>,
    pub(crate) diagonals: Vec<SymBlock>,
}

impl VolumeTerms {
    /// Adds the volume elements' blocks between their vertices to `a` and
    /// gathers their diagonal blocks and right-hand-side shares per
    /// particle; returns whether the system has elements with a modulus.
    ///
    /// Each element's Hessian ([`TetHessian`]) is the exact one with
    /// [`CompressedSprings::Exact`]; with [`CompressedSprings::Clamped`] the
    /// projected one at a Newton iterate, and the Gauss–Newton one for
    /// Baraff & Witkin's step (a `displacement`): that step is a starting
    /// point for Newton's method, which corrects it, or the whole step of
    /// the linearised integrator, and the Gauss–Newton Hessian, exact at
    /// rest, costs a tenth of the projection. The elements' blocks are
    /// added to the matrix in element order: each as it is evaluated below
    /// [`PARALLEL_MIN_ELEMENTS`] elements, after all are evaluated in
    /// parallel from there on, so both paths give the same sums.
    pub(crate) fn add(
        &mut self,
        volume_rhs: &mut Vec<Vec3>,
        system: &System,
        lin: &Linearization<'_>,
        a: &mut BlockMatrix,
    ) -> bool {
        let tets = system.tets();
        if tets.iter().all(|t| t.modulus <= 0.0) {
            return false;
        }
        let n = system.particle_count();
        let (bh, bh2) = (lin.beta_h, lin.beta_h * lin.beta_h);
        let kind = match (lin.compressed, lin.displacement) {
            (CompressedSprings::Exact, _) => TetHessian::Exact,
            (CompressedSprings::Clamped, None) => TetHessian::Projected,
            (CompressedSprings::Clamped, Some(_)) => TetHessian::GaussNewton,
        };
        let evaluate = |t: &Tet, terms: &mut ElementTerms| {
            if t.modulus <= 0.0 {
                return;
            }
            let d = t.blocks(lin.positions, kind, bh2);
            let block = |p: usize, q: usize| match p.cmp(&q) {
                std::cmp::Ordering::Equal => d.diagonal[p],
                std::cmp::Ordering::Less => d.pairs[pair_index(p, q)],
                std::cmp::Ordering::Greater => d.pairs[pair_index(q, p)].transpose(),
            };
            for p in 0..4 {
                terms.rhs[p] = -bh * d.gradient[p];
                if let Some(u) = lin.displacement {
                    // `−βh H u` with the blocks' `β²h² H`.
                    for (q, &j) in t.vertices.iter().enumerate() {
                        terms.rhs[p] -= block(p, q) * u[j] / bh;
                    }
                }
                terms.diagonal[p] = SymBlock::symmetric_part(&d.diagonal[p]);
            }
            terms.pairs = d.pairs;
        };
        if self.element_slots.0 != system.id() || self.element_slots.1.len() != tets.len() {
            self.element_slots.0 = system.id();
            self.element_slots.1.clear();
            self.element_slots.1.extend(tets.iter().map(|t| {
                TET_PAIRS.map(|(p, q)| a.pattern.slot_between(t.vertices[p], t.vertices[q]))
            }));
        }
        // The elements' diagonal blocks are summed per particle into one
        // row block for the product; the diagonal the preconditioners see
        // also gets the bounds of the blocks outside the springs' pattern.
        let (rows, diagonals) = (&mut self.rows, &mut self.diagonals);
        rows.clear();
        rows.resize(n, SymBlock::default());
        diagonals.clear();
        diagonals.resize(n, SymBlock::default());
        volume_rhs.clear();
        volume_rhs.resize(n, Vec3::zeros());
        let mut scatter = |t: &Tet, terms: &ElementTerms, slots: &[Option<usize>; 6]| {
            if t.modulus <= 0.0 {
                return;
            }
            for (p, &i) in t.vertices.iter().enumerate() {
                volume_rhs[i] += terms.rhs[p];
                rows[i].add_assign(&terms.diagonal[p]);
            }
            for ((&(p, q), &pair), &slot) in TET_PAIRS.iter().zip(&terms.pairs).zip(slots) {
                let (i, j) = (t.vertices[p], t.vertices[q]);
                if slot.is_none() {
                    let bound = SymBlock::scaled_identity(pair.norm());
                    diagonals[i].add_assign(&bound);
                    diagonals[j].add_assign(&bound);
                }
                a.add_extra_pair_at(i, j, pair, slot);
            }
        };
        let slots = &self.element_slots.1;
        if cfg!(feature = "parallel") && tets.len() >= PARALLEL_MIN_ELEMENTS {
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                self.element_terms
                    .resize(tets.len(), ElementTerms::default());
                self.element_terms
                    .par_iter_mut()
                    .zip(tets.par_iter())
                    .with_min_len(PARALLEL_MIN_ELEMENTS / 4)
                    .for_each(|(terms, t)| evaluate(t, terms));
                for ((t, terms), slots) in tets.iter().zip(&self.element_terms).zip(slots) {
                    scatter(t, terms, slots);
                }
            }
        } else {
            let mut terms = ElementTerms::default();
            for (t, slots) in tets.iter().zip(slots) {
                evaluate(t, &mut terms);
                scatter(t, &terms, slots);
            }
        }
        for (i, (row, diagonal)) in self.rows.iter().zip(&mut self.diagonals).enumerate() {
            if *row != SymBlock::default() {
                diagonal.add_assign(row);
                a.extra_rows.push((i as u32, *row));
            }
        }
        true
    }
}

/// The volume elements' energy `Σ ½ κ V₀ (J − 1)²` at positions `x`, and the
/// sum of the energies plus the energy the rounding of the vertices'
/// coordinates puts into them (see [`element_energy`]).
pub(crate) fn volume_energy(system: &System, x: &[Vec3]) -> (f64, f64) {
    elements(system).fold((0.0, 0.0), |(energy, rounding), t| {
        let (e, r) = element_energy(t, t.volume_ratio(x), x);
        (energy + e, rounding + r)
    })
}

/// [`volume_energy`], and the elements' forces added to `f`, each element's
/// deformation gradient computed once for both.
pub(crate) fn volume_energy_and_forces(system: &System, x: &[Vec3], f: &mut [Vec3]) -> (f64, f64) {
    elements(system).fold((0.0, 0.0), |(energy, rounding), t| {
        let (j, forces) = t.ratio_and_forces(x);
        for (&i, fi) in t.vertices.iter().zip(forces) {
            f[i] += fi;
        }
        let (e, r) = element_energy(t, j, x);
        (energy + e, rounding + r)
    })
}

/// The elements with a modulus.
fn elements(system: &System) -> impl Iterator<Item = &Tet> {
    system.tets().iter().filter(|t| t.modulus > 0.0)
}

/// An element's energy `½ κ V₀ (J − 1)²` at volume ratio `j` and positions
/// `x`, and that plus `κ V₀ |J − 1| |∇J| max|x|` (with `|∇J| ≈ V₀^(−1/3)`),
/// the energy the rounding of its vertices' coordinates puts into it
/// (divided by ε).
fn element_energy(t: &Tet, j: f64, x: &[Vec3]) -> (f64, f64) {
    let (stiffness, change) = (t.modulus * t.rest_volume, j - 1.0);
    let e = 0.5 * stiffness * change * change;
    let reach = t.vertices.iter().map(|&i| x[i].amax()).fold(0.0, f64::max);
    (e, e + stiffness * change.abs() * t.gradient_scale() * reach)
}

#[cfg(test)]
mod tests;
