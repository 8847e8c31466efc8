//! Newton's system from the terms: `A δ = b` with `A = M + βh C + β²h² K`
//! the sum of the terms' Hessians and `b` of their `−∇Φ` (see
//! [`hooke_core::term`]), assembled into the step's [`BlockMatrix`].
//!
//! At a Newton iterate `x = x̃ + βh v` this is Newton's step on `Φ`. At
//! Baraff & Witkin's linearisation about the step's start `(xₙ, vₙ)`, with
//! the displacement `u = x̃ + βh vₙ − xₙ` (`h vₙ` for backward Euler), it is
//!
//! ```text
//! (M + βh C + β²h² K) Δv = M(ṽ − vₙ) + βh [f(xₙ, vₙ) − K u],
//! ```
//!
//! for backward Euler `(M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀)`.

use std::sync::atomic::{AtomicUsize, Ordering};

use hooke_core::{At, StepError, SymBlock, System, Vec3};

use super::Terms;
use crate::linear::cg::BlockJacobi;
use crate::linear::matrix::BlockMatrix;
use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::for_each_row3;

impl Terms {
    /// Fills `a`, its block-Jacobi inverse and `b` with the terms at `at`
    /// (see the module docs) at time `time`: each term adds itself in
    /// turn, the barriers last. The diagonal blocks are checked before the
    /// barriers add theirs, which, projected onto their positive part,
    /// would hide an indefinite block of the springs' or elements' exact
    /// Hessians; the block-Jacobi inverses of the rows the barriers add to
    /// are then renewed. `a` must have the system's pattern and every
    /// slice one entry per particle.
    ///
    /// ```
    /// use hooke_core::{At, CompressedSprings, Vec3, reference::Sheet};
    /// use hooke_implicit::Terms;
    /// use hooke_implicit::internals::{BlockJacobi, BlockMatrix, Pattern};
    ///
    /// let system = Sheet::new(4).system()?;
    /// let state = system.initial_state();
    /// let n = system.particle_count();
    /// let mut a = BlockMatrix::zeros(Pattern::new(&system)?);
    /// let (mut jacobi, mut b) = (BlockJacobi::default(), vec![Vec3::zeros(); n]);
    /// let h = 0.01;
    /// let u: Vec<Vec3> = state.velocities().iter().map(|v| h * v).collect();
    /// let at = At {
    ///     x: state.positions(),
    ///     v: state.velocities(),
    ///     v_tilde: state.velocities(),
    ///     beta_h: h,
    ///     displacement: Some(&u),
    ///     compressed: CompressedSprings::Clamped,
    /// };
    /// Terms::new(&system)?.assemble(&system, &at, &mut a, &mut jacobi, &mut b, 0.0)?;
    /// // At rest under gravity the right-hand side is h·m·g.
    /// assert!((b[5] - h * system.masses()[5] * Vec3::new(0.0, -9.81, 0.0)).norm() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`StepError::NonFiniteSystem`] naming the first particle whose row or
    /// right-hand side is not finite, or [`StepError::NotPositiveDefinite`]
    /// naming the first free particle whose diagonal block is not positive
    /// definite (then neither is the matrix).
    ///
    /// # Panics
    /// If `a` or a slice does not match the system's size.
    pub fn assemble(
        &mut self,
        system: &System,
        at: &At<'_>,
        a: &mut BlockMatrix,
        jacobi: &mut BlockJacobi,
        b: &mut [Vec3],
        time: f64,
    ) -> Result<(), StepError> {
        let n = system.particle_count();
        a.clear();
        b.fill(Vec3::zeros());
        jacobi.inverses.resize(n, SymBlock::default());
        for t in self.list.iter_mut().filter(|t| !t.is_barrier()) {
            t.add(system, at, b, a);
        }
        // A principal block of a positive-definite matrix is positive
        // definite; for a free particle the check also yields the
        // block-Jacobi inverse. A pinned particle's row is filtered out.
        let non_finite = AtomicUsize::new(usize::MAX);
        let not_definite = AtomicUsize::new(usize::MAX);
        for_each_row3(
            &mut a.diagonal,
            &mut jacobi.inverses,
            b,
            |i, block, inverse, bi| {
                if !(block.is_finite() && bi.iter().all(|c| c.is_finite())) {
                    non_finite.fetch_min(i, Ordering::Relaxed);
                }
                match block.inverse_if_positive_definite() {
                    Some(inv) => *inverse = inv,
                    None if system.is_pinned(i) => *inverse = SymBlock::default(),
                    None => {
                        not_definite.fetch_min(i, Ordering::Relaxed);
                    }
                }
            },
        );
        match (non_finite.into_inner(), not_definite.into_inner()) {
            (usize::MAX, usize::MAX) => {
                let assembled = a.extra_rows.len();
                for t in self.list.iter_mut().filter(|t| t.is_barrier()) {
                    t.add(system, at, b, a);
                }
                for &(i, _) in &a.extra_rows[assembled..] {
                    let i = i as usize;
                    if let Some(inverse) = a.diagonal[i].inverse_if_positive_definite() {
                        jacobi.inverses[i] = inverse;
                    }
                }
                Ok(())
            }
            (usize::MAX, particle) => Err(StepError::NotPositiveDefinite {
                time,
                particle: Some(particle),
            }),
            (particle, _) => Err(StepError::NonFiniteSystem { time, particle }),
        }
    }
}

impl Solve<'_> {
    /// Assembles `terms` at `at` into the topology's matrix and `b`.
    ///
    /// # Errors
    /// As [`Terms::assemble`].
    pub(crate) fn assemble(
        self,
        terms: &mut Terms,
        topology: &mut Topology,
        at: &At<'_>,
        b: &mut [Vec3],
    ) -> Result<(), StepError> {
        let (matrix, jacobi) = topology.system_mut();
        terms.assemble(self.system, at, matrix, jacobi, b, self.time)
    }
}

/// Baraff & Witkin's linearised step of `h` from `state` without a
/// predictor (`ṽ = vₙ`, so no inertia term), compressed springs clamped,
/// with the displacement `u = h vₙ` it fills: for tests.
#[cfg(test)]
pub(crate) fn step_from<'a>(state: &'a hooke_core::State, h: f64, u: &'a mut Vec<Vec3>) -> At<'a> {
    *u = state.velocities().iter().map(|v| h * v).collect();
    At {
        x: state.positions(),
        v: state.velocities(),
        v_tilde: state.velocities(),
        beta_h: h,
        displacement: Some(u),
        compressed: hooke_core::CompressedSprings::Clamped,
    }
}

/// `terms` assembled at `at` into a new matrix on their pattern, and the
/// right-hand side: for tests.
#[cfg(test)]
pub(crate) fn assembled(
    terms: &mut Terms,
    system: &System,
    at: &At<'_>,
) -> (BlockMatrix, Vec<Vec3>) {
    let mut a = BlockMatrix::zeros(std::sync::Arc::clone(terms.pattern()));
    let mut b = vec![Vec3::zeros(); system.particle_count()];
    terms
        .assemble(system, at, &mut a, &mut BlockJacobi::default(), &mut b, 0.0)
        .unwrap();
    (a, b)
}

/// [`step_from`] assembled: its matrix, on the pattern of `system`'s
/// springs, and right-hand side.
#[cfg(test)]
pub(crate) fn linearised_step(
    system: &System,
    state: &hooke_core::State,
    h: f64,
) -> (BlockMatrix, Vec<Vec3>) {
    let mut u = Vec::new();
    let at = step_from(state, h, &mut u);
    assembled(&mut Terms::new(system).unwrap(), system, &at)
}
