//! The quasi-Newton directions of [`Minimizer::QuasiNewton`](crate::Minimizer):
//! L-BFGS on the incremental potential `Φ` with a constant, prefactored
//! initial Hessian (Liu, Bouaziz & Kavan, *Quasi-Newton Methods for
//! Real-time Simulation of Hyperelastic Materials*, ACM TOG 2017).
//!
//! The initial Hessian is the scalar matrix
//!
//! ```text
//! H₀ = M + βh (γ I + C₀) + β²h² L,   L = Σₛ kₛ (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ,   C₀ = Σₛ cₛ (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ,
//! ```
//!
//! the same for the three coordinates and on the free particles only (pins
//! are removed unknowns): the step's matrix `M + βh C + β²h² K` with every
//! spring's stiffness block `kₛ[d dᵀ + (1 − L/l)(I − d dᵀ)]` and damping
//! block `cₛ d dᵀ` replaced by their upper bounds `kₛ I` and `cₛ I` — the
//! matrix of fast mass-spring, so it depends on the topology, the moduli
//! and `βh` only and is factorized once per step size. By default the
//! factored `H₀` carries each weak spring of `L` (a cloth's bending
//! spring, joined to its ends' common neighbour by two springs ten times
//! stiffer) on those two instead
//! ([`WeakSprings::Routed`](crate::WeakSprings); the `laplacian` module has
//! the bound): `H₀` is then larger still, equal to the whole one on
//! uniform strain, and its factor has half the entries, so an iteration
//! costs less for about the same progress (`benches/README.md`). Where the
//! whole matrix's factor would be large, one V-cycle of smoothed-aggregation
//! multigrid on the whole matrix (`linear::amg::scalar`) stands for `H₀⁻¹`
//! instead: a fixed symmetric positive-definite operator, as the two-loop
//! recursion needs. An iteration costs
//! one gradient of `Φ`, the two-loop recursion over the last `m` pairs
//! `sₖ = vₖ₊₁ − vₖ`, `yₖ = ∇Φ(vₖ₊₁) − ∇Φ(vₖ)` (Nocedal & Wright,
//! *Numerical Optimization*, Algorithm 7.4) and three pairs of triangular
//! solves with `H₀`'s factor; no 3×3-block matrix is assembled, and the
//! gradient comes from the line search's passes over the terms that
//! evaluated `Φ` at the accepted point (`Terms::gradient`). A pair
//! with `sᵀy ≤ 0` (where `Φ` is not convex along `s`: compressed springs,
//! inverted volume elements) carries no curvature and is skipped, so the
//! implied Hessian stays positive definite and every direction descends.
//! A (sub)step starts its history with the newest pair of the last one
//! ([`Minimizer::CARRIED`](crate::Minimizer::CARRIED)): its correction is
//! mostly along the cloth's slow modes (the swing), which `H₀`'s `kI` per
//! spring makes far too stiff and which the next step's correction
//! follows too. The pair describes the last step's `Φ`, whose Hessian
//! differs from the next one's by the springs' motion over a step. The
//! history starts empty where `H₀` changes (`βh`, the contact terms'
//! stand-in).
//!
//! Contact barriers are far stiffer than springs near their pairs, and a
//! history of a few pairs cannot learn them: on a 10×10 cloth landing on
//! a sphere, L-BFGS on `H₀` alone took 2 500–5 000 iterations a step
//! where Newton took 20. So in a (sub)step with barrier terms, `H₀` gains
//! a diagonal stand-in for them at the step's starting point — each
//! particle's trace of its diagonal block of the barriers' projected
//! Hessian (an upper bound of the block's largest eigenvalue, exact for a
//! particle against one obstacle) — and is factorized afresh.

use hooke_core::{Named, StepError, SymBlock, System, Vec3};

use crate::linear::cholesky::WeakSprings;
use crate::linear::laplacian::{Inverse, Laplacian};
use crate::linear::solver::LinearSolver;
use crate::linear::vector::{dot, for_each_row};

/// The quasi-Newton state of an integrator: `H₀`'s factor and the curvature
/// pairs of the current (sub)step.
#[derive(Debug, Default)]
pub(crate) struct QuasiNewton {
    laplacian: Option<Laplacian>,
    /// How `H₀⁻¹` is applied and where weak springs go, for a new pattern.
    inverse: (Inverse, WeakSprings),
    /// The pairs `(s, y, 1/sᵀy)`, oldest first from `first`, a ring of
    /// `history` entries of which `len` hold pairs; the buffers are
    /// allocated as pairs arrive, so a long history costs only what the
    /// iterations fill.
    history: usize,
    s: Vec<Vec<Vec3>>,
    y: Vec<Vec<Vec3>>,
    rho: Vec<f64>,
    first: usize,
    len: usize,
    /// The two-loop recursion's coefficients.
    alpha: Vec<f64>,
    /// Whether `last_v` holds the last iterate whose gradient was taken,
    /// and `last_g` that gradient.
    has_last: bool,
    last_v: Vec<Vec3>,
    last_g: Vec<Vec3>,
    /// `∇Φ` at the current iterate, pinned rows zero.
    g: Vec<Vec3>,
    /// `βh` and whether `H₀` still needs the contact terms' stand-in, in a
    /// (sub)step with contact.
    beta_h: f64,
    pending: bool,
    /// Per particle, the contact terms' stand-in on `H₀`'s diagonal.
    stand_in: Vec<f64>,
}

impl QuasiNewton {
    /// Starts a (sub)step of `system` with `βh = beta_h` keeping `history`
    /// pairs, `H₀⁻¹` applied as `inverse` says and its weak springs where
    /// `weak` puts them (see [`Laplacian`]): factorizes `H₀` unless it is
    /// factorized for this `βh`, and starts the history with the newest
    /// `carried` pairs of the last (sub)step where `H₀` and the history's
    /// length are as they were, empty otherwise.
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] or [`StepError::NotPositiveDefinite`]
    /// from the factorization.
    ///
    /// With `contact`, the factorization waits for the first direction,
    /// which brings the contact terms' Hessian for the stand-in.
    pub(crate) fn begin(
        &mut self,
        system: &System,
        (beta_h, contact): (f64, bool),
        (history, carried, inverse): (usize, usize, (Inverse, WeakSprings)),
        time: f64,
    ) -> Result<(), StepError> {
        if self.inverse != inverse {
            self.laplacian = None;
            self.inverse = inverse;
        }
        self.beta_h = beta_h;
        self.pending = contact;
        let factorized = self
            .laplacian
            .as_ref()
            .is_some_and(|l| l.matches(system, beta_h.to_bits()));
        if !contact && !factorized {
            self.factorize(system, &[], time)?;
        }
        let carry = factorized && !contact && self.history == history;
        let n = system.particle_count();
        self.history = history;
        for buffers in [&mut self.s, &mut self.y] {
            buffers.truncate(history);
            for b in buffers.iter_mut() {
                b.resize(n, Vec3::zeros());
            }
        }
        for b in [&mut self.last_v, &mut self.last_g, &mut self.g] {
            b.resize(n, Vec3::zeros());
        }
        self.rho.truncate(history);
        self.alpha.truncate(history);
        if carry && history > 0 {
            let kept = self.len.min(carried);
            self.first = (self.first + self.len - kept) % history;
            self.len = kept;
        } else {
            self.first = 0;
            self.len = 0;
        }
        self.has_last = false;
        Ok(())
    }

    /// The name of the linear solver applying `H₀⁻¹` (see
    /// [`Laplacian::solver_name`]).
    pub(crate) fn solver_name(&self) -> &'static str {
        self.laplacian
            .as_ref()
            .map_or(LinearSolver::Cholesky.name(), Laplacian::solver_name)
    }

    /// Whether `H₀` waits for the contact terms' stand-in
    /// ([`QuasiNewton::add_stand_in`]).
    pub(crate) fn pending(&self) -> bool {
        self.pending
    }

    /// Factorizes `H₀` with the stand-in for the contact terms whose
    /// diagonal blocks are `blocks` (particle, block), at `time`.
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] or [`StepError::NotPositiveDefinite`]
    /// from the factorization.
    pub(crate) fn add_stand_in(
        &mut self,
        system: &System,
        blocks: &[(u32, SymBlock)],
        time: f64,
    ) -> Result<(), StepError> {
        self.pending = false;
        let mut stand_in = std::mem::take(&mut self.stand_in);
        stand_in.clear();
        stand_in.resize(system.particle_count(), 0.0);
        for (i, block) in blocks {
            stand_in[*i as usize] += block.to_mat3().trace().max(0.0);
        }
        let factorized = self.factorize(system, &stand_in, time);
        self.stand_in = stand_in;
        factorized
    }

    /// Factorizes `H₀` for the current `βh` with the extra diagonal
    /// `extra` (none if empty), on the pattern kept for `system` or a new
    /// one.
    fn factorize(&mut self, system: &System, extra: &[f64], time: f64) -> Result<(), StepError> {
        let (beta_h, key) = (self.beta_h, (self.beta_h.to_bits(), extra));
        match &mut self.laplacian {
            Some(l) if l.is_for(system) => l.refactor(system, weights(beta_h), key, time),
            slot => {
                *slot = Some(Laplacian::new(
                    system,
                    weights(beta_h),
                    key,
                    self.inverse,
                    time,
                )?);
                Ok(())
            }
        }
    }

    /// The quasi-Newton step `δ = −H ∇Φ` at the iterate `v`, where `b` holds
    /// `−∇Φ(v)`; returns the slope `∇Φ·δ` (negative unless `∇Φ = 0`). The
    /// pair from the last iterate whose direction was taken to `v` joins
    /// the history first, if it carries curvature. Pinned rows of `δ` are
    /// zero.
    pub(crate) fn direction(
        &mut self,
        system: &System,
        b: &[Vec3],
        v: &[Vec3],
        delta: &mut [Vec3],
    ) -> f64 {
        for_each_row(&mut self.g, |i, g| {
            *g = if system.is_pinned(i) {
                Vec3::zeros()
            } else {
                -b[i]
            };
        });
        let history = self.history;
        if self.has_last && history > 0 {
            let slot = (self.first + self.len) % history;
            if slot == self.s.len() {
                self.s.push(vec![Vec3::zeros(); v.len()]);
                self.y.push(vec![Vec3::zeros(); v.len()]);
                self.rho.push(0.0);
                self.alpha.push(0.0);
            }
            let (s, y) = (&mut self.s[slot], &mut self.y[slot]);
            let (last_v, last_g, g) = (&self.last_v, &self.last_g, &self.g);
            for_each_row(s, |i, s| *s = v[i] - last_v[i]);
            for_each_row(y, |i, y| *y = g[i] - last_g[i]);
            let curvature = dot(s, y);
            let full = self.len == history;
            if curvature > 0.0 && curvature.is_finite() {
                self.rho[slot] = curvature.recip();
                if full {
                    self.first = (self.first + 1) % history;
                } else {
                    self.len += 1;
                }
            } else if full {
                // The skipped pair overwrote the oldest one.
                self.first = (self.first + 1) % history;
                self.len -= 1;
            }
        }
        self.has_last = true;
        self.last_v.copy_from_slice(v);
        self.last_g.copy_from_slice(&self.g);
        let slope = self.two_loop(delta);
        if slope < 0.0 {
            return slope;
        }
        // Rounding in a nearly flat history: start it afresh from H₀.
        self.len = 0;
        self.two_loop(delta)
    }

    /// `δ = −H g` by the two-loop recursion over the stored pairs with
    /// `H₀⁻¹` in the middle; returns `g·δ`.
    fn two_loop(&mut self, delta: &mut [Vec3]) -> f64 {
        let history = self.history;
        let order = |k: usize| (self.first + k) % history.max(1);
        delta.copy_from_slice(&self.g);
        for k in (0..self.len).rev() {
            let t = order(k);
            let a = self.rho[t] * dot(&self.s[t], delta);
            self.alpha[t] = a;
            let y = &self.y[t];
            for_each_row(delta, |i, d| *d -= a * y[i]);
        }
        let laplacian = self.laplacian.as_mut().expect("factorized in begin");
        laplacian.apply_inverse_in_place(delta);
        for k in 0..self.len {
            let t = order(k);
            let beta = self.rho[t] * dot(&self.y[t], delta);
            let (a, s) = (self.alpha[t], &self.s[t]);
            for_each_row(delta, |i, d| *d += (a - beta) * s[i]);
        }
        for_each_row(delta, |_, d| *d = -*d);
        dot(&self.g, delta)
    }
}

/// `H₀`'s air-damping coefficient and spring weights for `βh`:
/// `βh γ` and `βh cₛ + β²h² kₛ`.
fn weights(beta_h: f64) -> (f64, impl Fn(&hooke_core::Spring) -> f64) {
    (beta_h, move |s: &hooke_core::Spring| {
        beta_h * s.damping + beta_h * beta_h * s.stiffness
    })
}

#[cfg(test)]
mod tests {
    use hooke_core::reference::Sheet;

    use super::*;

    /// Fills the history with `count` pairs of a convex quadratic
    /// (`∇Φ = v`, so `y = s`): directions at `count + 1` iterates.
    fn fill(quasi: &mut QuasiNewton, system: &System, count: usize) {
        let n = system.particle_count();
        let mut delta = vec![Vec3::zeros(); n];
        for k in 0..=count {
            let v: Vec<Vec3> = (0..n).map(|i| Vec3::repeat((k * n + i) as f64)).collect();
            let b: Vec<Vec3> = v.iter().map(|v| -v).collect();
            quasi.direction(system, &b, &v, &mut delta);
        }
    }

    /// The newest `carried` pairs start the next (sub)step's history while
    /// `H₀` is the same; a new `βh`, contact terms (whose stand-in changes
    /// `H₀`) or a new history length start it empty.
    #[test]
    fn the_newest_pairs_are_carried_only_while_the_initial_hessian_stays() {
        let system = Sheet::new(4).system().unwrap();
        let mut quasi = QuasiNewton::default();
        let start = |q: &mut QuasiNewton, beta_h: f64, contact: bool, history: usize| {
            q.begin(
                &system,
                (beta_h, contact),
                (history, 2, (Inverse::Factor, WeakSprings::Kept)),
                0.0,
            )
            .unwrap();
        };
        start(&mut quasi, 0.01, false, 5);
        fill(&mut quasi, &system, 4);
        assert_eq!(quasi.len, 4);
        start(&mut quasi, 0.01, false, 5);
        assert_eq!(quasi.len, 2);
        // The carried pairs are the newest: s = v₄ − v₃.
        let newest = (quasi.first + quasi.len - 1) % 5;
        let n = system.particle_count() as f64;
        assert!((quasi.s[newest][0] - Vec3::repeat(n)).norm() < 1e-12);
        fill(&mut quasi, &system, 1);
        assert_eq!(quasi.len, 3);
        for (beta_h, contact, history) in [(0.02, false, 5), (0.01, true, 5), (0.01, false, 4)] {
            start(&mut quasi, 0.01, false, 5);
            fill(&mut quasi, &system, 3);
            start(&mut quasi, beta_h, contact, history);
            assert_eq!(
                quasi.len, 0,
                "βh {beta_h}, contact {contact}, history {history}"
            );
        }
    }

    /// Steps of one size `h` keep one factor of `H₀`, and so their carried
    /// pair, also where the clock's rounding makes the time left in a step
    /// differ from `h` (`t + h − t ≠ h`).
    #[test]
    fn steps_of_one_size_keep_one_initial_hessian() {
        use hooke_core::Integrator;

        use crate::{Implicit, Minimizer};

        let system = Sheet::new(4).system().unwrap();
        let mut integrator = Implicit::backward_euler().with_minimizer(Minimizer::quasi_newton());
        let mut state = system.initial_state();
        let h = 0.1;
        let mut rounded = 0;
        for _ in 0..30 {
            let t = state.time();
            if ((t + h) - t).to_bits() != h.to_bits() {
                rounded += 1;
            }
            integrator.step(&system, &mut state, h).unwrap();
            let laplacian = integrator.kept.quasi.laplacian.as_ref().unwrap();
            assert!(laplacian.matches(&system, h.to_bits()), "after t = {t}");
        }
        assert!(rounded > 10, "{rounded} steps rounded");
    }
}
