//! The constant scalar matrix of fast mass-spring and of the quasi-Newton
//! step's initial Hessian: the masses plus a weighted graph Laplacian of the
//! springs, the same for the three coordinates, over the free particles
//! only, factorized by faer's sparse Cholesky or, where that factor would
//! be large, applied approximately by one multigrid V-cycle.

use hooke_core::{Named, Spring, StepError, System, Vec3};

mod layout;

use crate::linear::amg::coarse::ScalarCholesky;
use crate::linear::amg::scalar::ScalarAmg;
use crate::linear::cg::PcgSettings;
use crate::linear::cholesky::{Routes, WeakSprings};
use crate::linear::pattern::Pattern;
use crate::linear::solver::LinearSolver;
use crate::linear::vector::for_each_row;
use layout::Layout;

/// How a [`Laplacian`] applies its inverse.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Inverse {
    /// Exactly, by a sparse Cholesky factor.
    Factor,
    /// Approximately, by one V-cycle of smoothed-aggregation multigrid
    /// (the `amg` module's `scalar` hierarchy): a fixed symmetric
    /// positive-definite operator, in memory and time linear in the
    /// particles.
    Multigrid,
    /// The factor while the whole matrix's (every spring in place) holds
    /// at most [`FACTOR_ENTRIES_PER_UNKNOWN`] entries per free particle,
    /// multigrid beyond.
    #[default]
    Auto,
}

impl LinearSolver {
    /// How the quasi-Newton step applies `H₀⁻¹` under this setting:
    /// multigrid for [`LinearSolver::Amg`], the factor or multigrid by the
    /// factor's size for [`LinearSolver::Auto`], the factor otherwise.
    pub(crate) fn initial_hessian_inverse(self) -> Inverse {
        match self {
            Self::Amg(_) => Inverse::Multigrid,
            Self::Auto => Inverse::Auto,
            Self::Pcg(_) | Self::Cholesky | Self::LaggedCholesky(_) => Inverse::Factor,
        }
    }
}

/// The largest Cholesky factor of the whole matrix [`Inverse::Auto`] keeps,
/// in entries per free particle (8 bytes each). The bench cloth's factor
/// holds 44, 77, 102, 121 and 141 entries per particle at 50², 100², 200²,
/// 400² and 700² particles; with multigrid instead, L-BFGS to `1e-2` took
/// 11.85 against 11.2 iterations a step and 1.07× the time at 100², 12.45
/// against 11.25 iterations and 0.74× the time at 200² (20 steps,
/// `examples/million_cloth.rs`). With the weak springs routed the factor
/// holds 23, 31, 51, 58 and 65 entries per particle at those sizes, and
/// against it multigrid (on the whole matrix) still took 0.8 of the time
/// at 200² and 0.8–1.0 at 400² (four steps to `5e-3`), in less memory: the
/// size of the whole matrix's factor keeps deciding.
pub(crate) const FACTOR_ENTRIES_PER_UNKNOWN: usize = 96;

/// The inverse in use: the factor, or the hierarchy with the scratch of a
/// cycle's solution.
#[derive(Debug)]
enum Solver {
    Factor(ScalarCholesky),
    Multigrid(Option<ScalarAmg>, Vec<f64>),
}

/// `(M + a Γ + Σₛ wₛ (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ)_ff` for one system: `M` the
/// masses, `Γ = γ I` the air damping, `wₛ` a weight per spring, `f` the
/// free particles (pins are removed unknowns). The pattern and its symbolic
/// analysis are built once per system; [`Laplacian::refactor`] renews the
/// values and the numeric factor for new weights.
///
/// With [`WeakSprings::Routed`] and a factor (multigrid keeps every
/// spring: on the routed matrix one V-cycle did less, 61 iterations
/// against 29 in one step of the million-particle cloth), a weak spring `(i, j)` that the routes of
/// the system's Cholesky factor carry on two stiff springs through a middle
/// particle `m` (see `linear::cholesky::routes`) adds `(1 + t) wₛ` on
/// `(i, m)` and `(1 + 1/t) wₛ` on `(m, j)` instead of its own term, `t`
/// the legs' rest-length ratio. Since `(a + b)² ≤ (1 + t) a² + (1 + 1/t) b²`
/// for every `t > 0`, the matrix is then at least the whole one and equals
/// it on fields that strain each path uniformly (affine ones on a regular
/// grid), and its pattern has the stiff springs' sparsity: a cloth's
/// factor loses its bending springs' fill.
#[derive(Debug)]
pub(crate) struct Laplacian {
    system: u64,
    /// The key of the weights last factorized (a step size's bits); `None`
    /// when the factor holds an extra diagonal or failed.
    key: Option<u64>,
    /// Per particle, its unknown (`u32::MAX` for a pinned one).
    pub(crate) unknown: Vec<u32>,
    layout: Layout,
    solver: Solver,
    /// The three coordinates of a right-hand side, then of the solution,
    /// one after the other (coordinate `c` of free particle `u` at
    /// `c · free + u`).
    pub(crate) rhs: Vec<f64>,
}

impl Laplacian {
    /// The pattern of `system`'s matrix, its symbolic analysis and its
    /// factor (or multigrid hierarchy, as `inverse` chooses) for the
    /// air-damping coefficient `air`, the spring weights `weight`, `key`
    /// and the extra diagonal `extra` (see [`Laplacian::refactor`]; at
    /// `time`, for the errors), with weak springs as `weak` says.
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] beyond 32-bit indices,
    /// [`StepError::NotPositiveDefinite`] if the matrix is not.
    pub(crate) fn new(
        system: &System,
        (air, weight): (f64, impl Fn(&Spring) -> f64),
        (key, extra): (u64, &[f64]),
        (inverse, weak): (Inverse, WeakSprings),
        time: f64,
    ) -> Result<Self, StepError> {
        let too_large = || StepError::SystemTooLarge {
            particles: system.particle_count(),
            springs: system.springs().len(),
        };
        let mut unknown = vec![u32::MAX; system.particle_count()];
        let mut count = 0u32;
        for (i, u) in unknown.iter_mut().enumerate() {
            if !system.is_pinned(i) {
                *u = count;
                count += 1;
            }
        }
        let free = count as usize;
        // `auto` chooses by the size of the whole matrix's factor (its
        // threshold was measured on it), and the factor it keeps is routed
        // if asked; multigrid keeps every spring, as it converged worse on
        // the routed matrix (`benches/README.md`).
        let whole = || Layout::new(system, &unknown, &[]).ok_or_else(too_large);
        let routed = || -> Result<(Layout, Solver), StepError> {
            let pattern = Pattern::new(system)?;
            let routes = Routes::new(system, &pattern).by_spring(system, &pattern);
            let layout = Layout::new(system, &unknown, &routes).ok_or_else(too_large)?;
            let factor = ScalarCholesky::new(&layout.a).ok_or_else(too_large)?;
            Ok((layout, Solver::Factor(factor)))
        };
        let multigrid = || Solver::Multigrid(None, vec![0.0; free]);
        let (layout, solver) = match (inverse, weak) {
            (Inverse::Multigrid, _) => (whole()?, multigrid()),
            (Inverse::Factor, WeakSprings::Routed) => routed()?,
            (Inverse::Factor, WeakSprings::Kept) => {
                let layout = whole()?;
                let factor = ScalarCholesky::new(&layout.a).ok_or_else(too_large)?;
                (layout, Solver::Factor(factor))
            }
            (Inverse::Auto, weak) => {
                let layout = whole()?;
                let fits = |f: &ScalarCholesky| f.entries() <= FACTOR_ENTRIES_PER_UNKNOWN * free;
                match (ScalarCholesky::new(&layout.a).filter(fits), weak) {
                    (None, _) => (layout, multigrid()),
                    (Some(factor), WeakSprings::Kept) => (layout, Solver::Factor(factor)),
                    (Some(factor), WeakSprings::Routed) => {
                        drop((factor, layout));
                        routed()?
                    }
                }
            }
        };
        let mut laplacian = Self {
            system: system.id(),
            key: None,
            unknown,
            layout,
            solver,
            rhs: vec![0.0; 3 * free],
        };
        laplacian.refactor(system, (air, weight), (key, extra), time)?;
        Ok(laplacian)
    }

    /// Whether this is `system`'s matrix factorized for `key`.
    pub(crate) fn matches(&self, system: &System, key: u64) -> bool {
        self.system == system.id() && self.key == Some(key)
    }

    /// Whether this is `system`'s pattern.
    pub(crate) fn is_for(&self, system: &System) -> bool {
        self.system == system.id()
    }

    /// Fills the matrix with new weights (on the same system's pattern),
    /// adds `extra[i]` to each free particle `i`'s diagonal (none for an
    /// empty `extra`) and factorizes it (or builds its hierarchy).
    ///
    /// # Errors
    /// [`StepError::NotPositiveDefinite`] if the matrix is not.
    pub(crate) fn refactor(
        &mut self,
        system: &System,
        (air, weight): (f64, impl Fn(&Spring) -> f64),
        (key, extra): (u64, &[f64]),
        time: f64,
    ) -> Result<(), StepError> {
        let layout = &mut self.layout;
        let values = &mut layout.a.values;
        values.fill(0.0);
        let shift = air * system.air_damping().unwrap_or(0.0);
        let mut free = layout.diagonal.iter();
        for (i, &m) in system.masses().iter().enumerate() {
            if self.unknown[i] != u32::MAX {
                let added = extra.get(i).copied().unwrap_or(0.0);
                let k = *free.next().expect("one diagonal a free particle");
                values[k as usize] = m + shift + added;
            }
        }
        let mut add = |entries: &[u32; 4], w: f64| {
            for (k, &e) in entries.iter().enumerate() {
                if e != u32::MAX {
                    values[e as usize] += if k < 2 { w } else { -w };
                }
            }
        };
        for (s, entries) in system.springs().iter().zip(&layout.entries) {
            add(entries, weight(s));
        }
        for (spring, legs, weights) in &layout.routed {
            let w = weight(&system.springs()[*spring as usize]);
            for (entries, t) in legs.iter().zip(weights) {
                add(entries, t * w);
            }
        }
        self.key = None;
        let not_positive_definite = || StepError::NotPositiveDefinite {
            time,
            particle: None,
        };
        match &mut self.solver {
            Solver::Factor(cholesky) => cholesky
                .factorize(&self.layout.a)
                .map_err(|()| not_positive_definite())?,
            Solver::Multigrid(amg, _) => {
                // The old hierarchy goes before the new one is built, so
                // that the two are never held together.
                *amg = None;
                *amg = Some(ScalarAmg::build(&self.layout.a).map_err(|_| not_positive_definite())?);
            }
        }
        self.key = extra.is_empty().then_some(key);
        Ok(())
    }

    /// The name of the linear solver applying the inverse, for the step
    /// report: `"cholesky"` or `"amg"`.
    pub(crate) fn solver_name(&self) -> &'static str {
        match self.solver {
            Solver::Factor(_) => LinearSolver::Cholesky.name(),
            Solver::Multigrid(..) => LinearSolver::Amg(PcgSettings::default()).name(),
        }
    }

    /// Solves the matrix's system for the three columns of `rhs` in place:
    /// in one pass over the factor, or by a V-cycle for each.
    pub(crate) fn solve(&mut self) {
        match &mut self.solver {
            Solver::Factor(cholesky) => cholesky.solve(&mut self.rhs),
            Solver::Multigrid(amg, x) => {
                let amg = amg.as_mut().expect("built at every refactor");
                for column in self.rhs.chunks_exact_mut(x.len().max(1)) {
                    amg.apply(&self.layout.a, column, x);
                    column.copy_from_slice(x);
                }
            }
        }
    }

    /// `q ← A⁻¹ q` on the free particles; pinned rows become zero.
    pub(crate) fn apply_inverse_in_place(&mut self, q: &mut [Vec3]) {
        let free = self.rhs.len() / 3;
        for (qi, &u) in q.iter().zip(&self.unknown) {
            if u != u32::MAX {
                for (c, value) in qi.iter().enumerate() {
                    self.rhs[c * free + u as usize] = *value;
                }
            }
        }
        self.solve();
        let (unknown, rhs) = (&self.unknown, &self.rhs);
        for_each_row(q, |i, qi| {
            let u = unknown[i];
            *qi = if u == u32::MAX {
                Vec3::zeros()
            } else {
                Vec3::from_fn(|c, _| rhs[c * free + u as usize])
            };
        });
    }
}

#[cfg(test)]
mod tests;
