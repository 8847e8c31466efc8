//! The volume elements' term of the incremental potential: each element's
//! energy `½ κ V₀ (J − 1)²` ([`Tet`]).

use hooke_core::{
    At, CompressedSprings, Hessian, Mat3, Potential, StepStart, SymBlock, System, TET_PAIRS, Term,
    Tet, TetHessian, Vec3, When,
};

use crate::linear::matrix::BlockMatrix;
use crate::linear::pattern::Pattern;
use crate::linear::vector::{for_each_row, for_each_row2};

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

impl ElementTerms {
    /// Sets this to element `t`'s share at `at` with its Hessian of kind
    /// `kind`.
    #[inline]
    fn evaluate(&mut self, t: &Tet, at: &At<'_>, kind: TetHessian) {
        let bh = at.beta_h;
        let d = t.blocks(at.x, kind, bh * bh);
        let block = |p: usize, q: usize| match p.cmp(&q) {
            std::cmp::Ordering::Equal => d.diagonal[p],
            std::cmp::Ordering::Less => d.pairs[pair_index(p, q)],
            std::cmp::Ordering::Greater => d.pairs[pair_index(q, p)].transpose(),
        };
        for p in 0..4 {
            self.rhs[p] = -bh * d.gradient[p];
            if let Some(u) = at.displacement {
                // `−βh H u` with the blocks' `β²h² H`.
                for (q, &j) in t.vertices.iter().enumerate() {
                    self.rhs[p] -= block(p, q) * u[j] / bh;
                }
            }
            self.diagonal[p] = SymBlock::symmetric_part(&d.diagonal[p]);
        }
        self.pairs = d.pairs;
    }
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

/// The volume elements of a system (those with a modulus), with the
/// buffers of their passes.
#[derive(Debug, Clone)]
pub(super) struct Volume {
    /// Per element, when they are evaluated in parallel: its blocks and
    /// right-hand-side shares.
    #[cfg(feature = "parallel")]
    element_terms: Vec<ElementTerms>,
    /// Per element: the pattern's slot between each pair of its vertices,
    /// if a spring joins them.
    slots: Vec<[Option<usize>; 6]>,
    /// Per particle: the elements' diagonal blocks, those plus the bounds
    /// of their blocks outside the pattern, and their right-hand-side
    /// shares.
    rows: Vec<SymBlock>,
    diagonals: Vec<SymBlock>,
    rhs: Vec<Vec3>,
}

impl Volume {
    /// The volume elements of `system`, whose springs' slots are `pattern`'s.
    pub(super) fn new(system: &System, pattern: &Pattern) -> Self {
        Self {
            #[cfg(feature = "parallel")]
            element_terms: Vec::new(),
            slots: system
                .tets()
                .iter()
                .map(|t| TET_PAIRS.map(|(p, q)| pattern.slot_between(t.vertices[p], t.vertices[q])))
                .collect(),
            rows: Vec::new(),
            diagonals: Vec::new(),
            rhs: Vec::new(),
        }
    }

    /// Adds the elements' blocks between their vertices to `a` and gathers
    /// their diagonal blocks and right-hand-side shares per particle
    /// (`rows`, `diagonals`, `rhs`). The elements' blocks are added to the
    /// matrix in element order: each as it is evaluated below
    /// [`PARALLEL_MIN_ELEMENTS`] elements, after all are evaluated in
    /// parallel from there on, so both paths give the same sums.
    fn assemble(&mut self, system: &System, at: &At<'_>, kind: TetHessian, a: &mut BlockMatrix) {
        let tets = system.tets();
        let n = system.particle_count();
        // The elements' diagonal blocks are summed per particle into one
        // row block for the product; the diagonal the preconditioners see
        // also gets the bounds of the blocks outside the springs' pattern.
        let (rows, diagonals, rhs) = (&mut self.rows, &mut self.diagonals, &mut self.rhs);
        rows.clear();
        rows.resize(n, SymBlock::default());
        diagonals.clear();
        diagonals.resize(n, SymBlock::default());
        rhs.clear();
        rhs.resize(n, Vec3::zeros());
        let mut scatter = |t: &Tet, terms: &ElementTerms, slots: &[Option<usize>; 6]| {
            if t.modulus <= 0.0 {
                return;
            }
            for (p, &i) in t.vertices.iter().enumerate() {
                rhs[i] += terms.rhs[p];
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
        let evaluate = |t: &Tet, terms: &mut ElementTerms| {
            if t.modulus > 0.0 {
                terms.evaluate(t, at, kind);
            }
        };
        let slots = &self.slots;
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
    }
}

impl Term for Volume {
    fn name(&self) -> &'static str {
        "volume elements"
    }

    /// `Σ ½ κ V₀ (J − 1)²` and the magnitude of [`element_energy`].
    fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        elements(system).fold(Potential::ZERO, |sum, t| {
            sum + element_energy(t, t.volume_ratio(at.x), at.x)
        })
    }

    /// The value and `b += βh f`, each element's deformation computed once
    /// for both; `b` gets the assembly's right-hand side at an iterate to
    /// the bit.
    fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        let (x, bh, rhs) = (at.x, at.beta_h, &mut self.rhs);
        rhs.clear();
        rhs.resize(system.particle_count(), Vec3::zeros());
        let sum = elements(system).fold(Potential::ZERO, |sum, t| {
            let (j, forces) = t.ratio_and_forces(x);
            for (&i, f) in t.vertices.iter().zip(forces) {
                rhs[i] += bh * f;
            }
            sum + element_energy(t, j, x)
        });
        let rhs = &self.rhs;
        for_each_row(b, |i, bi| *bi += rhs[i]);
        sum
    }

    /// Each element's Hessian ([`TetHessian`]) is the exact one with
    /// [`CompressedSprings::Exact`]; with [`CompressedSprings::Clamped`] the
    /// projected one at a Newton iterate, and the Gauss–Newton one for
    /// Baraff & Witkin's step (a `displacement`): that step is a starting
    /// point for Newton's method, which corrects it, or the whole step of
    /// the linearised integrator, and the Gauss–Newton Hessian, exact at
    /// rest, costs a tenth of the projection. The blocks go into the step's
    /// [`BlockMatrix`] by its slots where `hessian` is one, element by
    /// element otherwise.
    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        let kind = match (at.compressed, at.displacement) {
            (CompressedSprings::Exact, _) => TetHessian::Exact,
            (CompressedSprings::Clamped, None) => TetHessian::Projected,
            (CompressedSprings::Clamped, Some(_)) => TetHessian::GaussNewton,
        };
        if let Some(a) = hessian
            .as_any_mut()
            .and_then(|a| a.downcast_mut::<BlockMatrix>())
        {
            self.assemble(system, at, kind, a);
            let (diagonals, rhs) = (&self.diagonals, &self.rhs);
            for_each_row2(&mut a.diagonal, b, |i, d, bi| {
                d.add_assign(&diagonals[i]);
                *bi += rhs[i];
            });
            return;
        }
        let mut terms = ElementTerms::default();
        for t in elements(system) {
            terms.evaluate(t, at, kind);
            for (p, &i) in t.vertices.iter().enumerate() {
                b[i] += terms.rhs[p];
                hessian.add_row(i, terms.diagonal[p]);
            }
            for (&(p, q), &pair) in TET_PAIRS.iter().zip(&terms.pairs) {
                hessian.add_pair(t.vertices[p], t.vertices[q], pair);
            }
        }
    }

    /// `Σ ½ κ V₀ (J − 1)²`.
    fn energy(&mut self, system: &System, x: &[Vec3], _v: &[Vec3], _when: When) -> Potential {
        let e = elements(system)
            .map(|t| element_energy(t, t.volume_ratio(x), x).value)
            .fold(0.0, |sum, e| sum + e);
        Potential::non_negative(e)
    }

    /// The work of scripted pins through the elements at them, by the
    /// trapezoid rule, as the springs' ([`Term::work`]).
    fn work(&mut self, system: &System, step: &StepStart<'_>, x: &[Vec3], _v: &[Vec3]) -> f64 {
        let paths = system.pin_paths();
        if paths.is_empty() {
            return 0.0;
        }
        let moving = |&p: &usize| paths.iter().any(|(i, _)| *i == p);
        let x0 = step.x;
        let mut work = 0.0;
        for t in elements(system).filter(|t| t.vertices.iter().any(moving)) {
            // The elements' forces are minus ∇ₚV.
            let (f0, f1) = (t.forces(x0), t.forces(x));
            for (a, p) in t.vertices.iter().enumerate() {
                if moving(p) {
                    work -= 0.5 * (f0[a] + f1[a]).dot(&(x[*p] - x0[*p]));
                }
            }
        }
        work
    }

    fn force(&self, system: &System, x: &[Vec3], _v: &[Vec3], f: &mut [Vec3]) {
        system.add_volume_forces(x, f);
    }

    /// Each element's Hessian at rest, `κ V₀ ∇J ∇Jᵀ`, as
    /// `wₐ Σ_b κ V₀ |∇ₐJ| |∇_bJ| w_b` at each vertex `a`: it grows with the
    /// deformation, so this bound holds near rest only.
    fn rates(&self, system: &System, w: &[f64], stiffness: &mut [f64], _damping: &mut [f64]) {
        for t in system.tets() {
            let gradient = t.volume_gradient(system.initial_positions());
            let reach: f64 = gradient
                .iter()
                .zip(t.vertices)
                .map(|(g, i)| g.norm() * w[i])
                .sum();
            for (g, i) in gradient.iter().zip(t.vertices) {
                stiffness[i] += t.modulus * t.rest_volume * g.norm() * w[i] * reach;
            }
        }
    }

    /// Each element's projected Hessian.
    fn stiffness(&self, system: &System, x: &[Vec3], k: &mut dyn Hessian) {
        for t in elements(system) {
            let h = t.derivatives(x, TetHessian::Projected).hessian;
            let block = |a: usize, b: usize| h.fixed_view::<3, 3>(3 * a, 3 * b).into_owned();
            for (a, &i) in t.vertices.iter().enumerate() {
                k.add_row(i, SymBlock::symmetric_part(&block(a, a)));
            }
            for &(a, b) in &TET_PAIRS {
                k.add_pair(t.vertices[a], t.vertices[b], block(a, b));
            }
        }
    }
}

/// The elements with a modulus.
fn elements(system: &System) -> impl Iterator<Item = &Tet> {
    system.tets().iter().filter(|t| t.modulus > 0.0)
}

/// An element's energy `½ κ V₀ (J − 1)²` at volume ratio `j` and positions
/// `x`, and its magnitude: that plus `κ V₀ |J − 1| |∇J| max|x|` (with
/// `|∇J| ≈ V₀^(−1/3)`), the energy the rounding of its vertices'
/// coordinates puts into it (divided by ε).
fn element_energy(t: &Tet, j: f64, x: &[Vec3]) -> Potential {
    let (stiffness, change) = (t.modulus * t.rest_volume, j - 1.0);
    let e = 0.5 * stiffness * change * change;
    let reach = t.vertices.iter().map(|&i| x[i].amax()).fold(0.0, f64::max);
    Potential {
        value: e,
        magnitude: e + stiffness * change.abs() * t.gradient_scale() * reach,
    }
}

#[cfg(test)]
pub(super) mod tests;
