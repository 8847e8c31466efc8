//! The springs' passes in race-free chunks (see the `springs` module):
//! the assembly's two, writing their blocks into the matrix's slots, and
//! the gradient's.

use hooke_core::{At, Potential, Spring, SymBlock, System, Vec3};

use super::{Springs, spring_potential};
use crate::linear::matrix::BlockMatrix;
use crate::linear::vector::{for_each_row, for_each_row2, spring_chunks};

impl Springs {
    /// Splits the pattern's slots into one contiguous chunk per thread,
    /// records the rows each chunk touches and sizes the chunks'
    /// right-hand-side accumulators; returns the chunk length. The slots are
    /// ordered by their lower row, so a chunk touches only the rows from its
    /// first slot's row to its last slot's row plus the pattern's bandwidth.
    fn chunks(&mut self, n: usize) -> usize {
        let pattern = &self.pattern;
        let m = pattern.slots();
        let chunk = m.div_ceil(spring_chunks(m)).max(1);
        let parts = m.div_ceil(chunk);
        self.rhs.resize(parts * n, Vec3::zeros());
        self.touched.clear();
        self.touched.extend((0..parts).map(|p| {
            let (first, last) = (p * chunk, ((p + 1) * chunk).min(m) - 1);
            pattern.row_of(first)..(pattern.row_of(last) + pattern.bandwidth() + 1).min(n)
        }));
        chunk
    }

    /// Adds each chunk's right-hand-side accumulator to `b`, and its
    /// diagonal blocks to `diagonal` if given.
    pub(super) fn gather(&self, n: usize, b: &mut [Vec3], diagonal: Option<&mut [SymBlock]>) {
        let (touched, rhs, diagonals) = (&self.touched, &self.rhs, &self.diagonals);
        let chunks = |i: usize| {
            touched
                .iter()
                .enumerate()
                .filter(move |(_, rows)| rows.contains(&i))
                .map(move |(p, _)| p * n + i)
        };
        match diagonal {
            Some(diagonal) => for_each_row2(diagonal, b, |i, d, bi| {
                for k in chunks(i) {
                    d.add_assign(&diagonals[k]);
                    *bi += rhs[k];
                }
            }),
            None => for_each_row(b, |i, bi| {
                for k in chunks(i) {
                    *bi += rhs[k];
                }
            }),
        }
    }

    /// Pass one of the assembly into `a` (see the module docs); `freeze`
    /// takes the dampers' directions from each spring's own at `at`.
    pub(super) fn assemble(
        &mut self,
        system: &System,
        at: &At<'_>,
        a: &mut BlockMatrix,
        freeze: bool,
    ) {
        let n = system.particle_count();
        let chunk = self.chunks(n);
        self.diagonals
            .resize(self.touched.len() * n, SymBlock::default());
        let (springs, pattern, touched) = (system.springs(), &self.pattern, &self.touched);
        let work = |p: usize,
                    blocks: &mut [SymBlock],
                    frozen: &mut [Vec3],
                    diagonal: &mut [SymBlock],
                    rhs: &mut [Vec3]| {
            diagonal[touched[p].clone()].fill(SymBlock::default());
            rhs[touched[p].clone()].fill(Vec3::zeros());
            for (k, (block, frozen)) in blocks.iter_mut().zip(frozen).enumerate() {
                let s = &springs[pattern.spring(p * chunk + k)];
                let shared;
                (*block, shared) = spring_terms(s, at, frozen, freeze);
                diagonal[s.i].add_assign(block);
                diagonal[s.j].add_assign(block);
                rhs[s.i] += at.beta_h * shared;
                rhs[s.j] -= at.beta_h * shared;
            }
        };
        let (blocks, directions) = (&mut a.springs, &mut self.directions);
        if cfg!(feature = "parallel") && self.touched.len() > 1 {
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                blocks
                    .par_chunks_mut(chunk)
                    .zip(directions.par_chunks_mut(chunk))
                    .zip(
                        self.diagonals
                            .par_chunks_mut(n)
                            .zip(self.rhs.par_chunks_mut(n)),
                    )
                    .enumerate()
                    .for_each(|(p, ((blocks, frozen), (diagonal, rhs)))| {
                        work(p, blocks, frozen, diagonal, rhs);
                    });
            }
        } else {
            let chunks = blocks
                .chunks_mut(chunk)
                .zip(directions.chunks_mut(chunk))
                .zip(self.diagonals.chunks_mut(n).zip(self.rhs.chunks_mut(n)));
            for (p, ((blocks, frozen), (diagonal, rhs))) in chunks.enumerate() {
                work(p, blocks, frozen, diagonal, rhs);
            }
        }
    }

    /// `b −= ∇Φ` of the springs at `at`, their dampers along the frozen
    /// directions, and their part of `Φ`: one pass over the springs in the
    /// chunks of the assembly, each spring's length computed once for its
    /// energy and its force, and one over the particles.
    pub(super) fn gradient_pass(
        &mut self,
        system: &System,
        at: &At<'_>,
        b: &mut [Vec3],
    ) -> Potential {
        let n = system.particle_count();
        let chunk = self.chunks(n);
        let (springs, pattern) = (system.springs(), &self.pattern);
        let (directions, touched) = (&self.directions, &self.touched);
        let (x, v, bh) = (at.x, at.v, at.beta_h);
        // Per chunk: its springs' shares of the right-hand side into its
        // accumulator, and their energy and its magnitude.
        let work = |p: usize, rhs: &mut [Vec3]| {
            rhs[touched[p].clone()].fill(Vec3::zeros());
            let (mut energy, mut magnitude) = (0.0, 0.0);
            for t in p * chunk..((p + 1) * chunk).min(pattern.slots()) {
                let s = &springs[pattern.spring(t)];
                let (xi, xj) = (x[s.i], x[s.j]);
                let (stretch, mut force) = s.stretch_and_force(xi, xj);
                let mut rate = 0.0;
                if s.damping > 0.0 {
                    let d = directions[t];
                    rate = d.dot(&(v[s.i] - v[s.j]));
                    force -= s.damping * rate * d;
                }
                let (e, m) = spring_potential(s, (xi, xj), stretch, rate, bh);
                energy += e;
                magnitude += m;
                rhs[s.i] += bh * force;
                rhs[s.j] -= bh * force;
            }
            (energy, magnitude)
        };
        let add = |a: (f64, f64), b: (f64, f64)| (a.0 + b.0, a.1 + b.1);
        #[cfg(feature = "parallel")]
        let (value, magnitude) = if self.touched.len() > 1 {
            use rayon::prelude::*;
            self.rhs
                .par_chunks_mut(n)
                .enumerate()
                .map(|(p, rhs)| work(p, rhs))
                .reduce(|| (0.0, 0.0), add)
        } else {
            work(0, &mut self.rhs)
        };
        #[cfg(not(feature = "parallel"))]
        let (value, magnitude) = self
            .rhs
            .chunks_mut(n)
            .enumerate()
            .map(|(p, rhs)| work(p, rhs))
            .fold((0.0, 0.0), add);
        self.gather(n, b, None);
        Potential { value, magnitude }
    }
}

/// A spring's block `K_s = β²h² H + βh c e eᵀ` and its right-hand-side
/// share `f − H u − c (e·(vᵢ − vⱼ)) e` at `at`, `e` its damper's direction
/// `frozen` — or, with `freeze`, its own direction `d` at `at`, frozen
/// there.
#[inline(always)]
pub(super) fn spring_terms(
    s: &Spring,
    at: &At<'_>,
    frozen: &mut Vec3,
    freeze: bool,
) -> (SymBlock, Vec3) {
    let (bh, bh2) = (at.beta_h, at.beta_h * at.beta_h);
    let (x, v) = (at.x, at.v);
    let h = s.linearize(x[s.i], x[s.j], at.compressed);
    let mut shared = h.force;
    if let Some(u) = at.displacement {
        shared -= h.apply(u[s.i] - u[s.j]);
    }
    // β²h² H = β²h² [(k_∥ − k_⊥) d dᵀ + k_⊥ I], plus βh c e eᵀ along the
    // damping direction e, which is d where frozen here.
    let mut along = bh2 * (h.axial - h.transverse);
    let mut damping = None;
    if s.damping > 0.0 {
        if freeze {
            *frozen = h.direction;
            along += bh * s.damping;
        } else {
            damping = Some(*frozen);
        }
        let e = *frozen;
        shared -= s.damping * e.dot(&(v[s.i] - v[s.j])) * e;
    }
    let mut block = SymBlock::rank_one_plus_identity(along, h.direction, bh2 * h.transverse);
    if let Some(e) = damping {
        block.add_assign(&SymBlock::rank_one_plus_identity(bh * s.damping, e, 0.0));
    }
    (block, shared)
}
