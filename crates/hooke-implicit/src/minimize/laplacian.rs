//! The constant scalar matrix of fast mass-spring and of the quasi-Newton
//! step's initial Hessian: the masses plus a weighted graph Laplacian of the
//! springs, the same for the three coordinates, over the free particles
//! only, factorized by faer's sparse Cholesky or, where that factor would
//! be large, applied approximately by one multigrid V-cycle.

use hooke_core::{Named, Spring, StepError, System, Vec3};

use crate::linear::amg::coarse::ScalarCholesky;
use crate::linear::amg::csr::Csr;
use crate::linear::amg::scalar::ScalarAmg;
use crate::linear::cholesky::{Routes, SpringRoute};
use crate::linear::pattern::Pattern;
use crate::linear::vector::for_each_row;
use crate::{LinearSolver, PcgSettings, WeakSprings};

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

/// The matrix's pattern over the free particles and where each spring's
/// term goes in its values.
#[derive(Debug)]
struct Layout {
    a: Csr,
    /// Per free particle, its diagonal entry in `a`'s values.
    diagonal: Vec<u32>,
    /// Per spring, the entries `(i, i), (j, j), (i, j), (j, i)` of `a`'s
    /// values it adds to (`u32::MAX` where an end is pinned, and all four
    /// for a routed spring).
    entries: Vec<[u32; 4]>,
    /// The routed springs: each one's index, the entries of its two legs
    /// (as in `entries`) and their weights.
    routed: Vec<(u32, [[u32; 4]; 2], [f64; 2])>,
}

impl Layout {
    /// The layout of `system`'s matrix over the unknowns `unknown`
    /// (`u32::MAX` for a pinned particle) with the springs `routes` carried
    /// on their legs (sorted by spring); `None` beyond 32-bit indices.
    fn new(system: &System, unknown: &[u32], routes: &[SpringRoute]) -> Option<Self> {
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
mod tests {
    use super::*;
    use hooke_core::Mat3;

    use crate::linear::cholesky::tests::stiff_and_weak_grid;
    use crate::linear::vector::dot;

    /// `H₀` at `h = 0.05` s for the grid with weak springs as `weak` says.
    fn matrix(system: &System, weak: WeakSprings) -> Laplacian {
        let weights = (0.05, |s: &Spring| 0.05 * s.damping + 0.0025 * s.stiffness);
        Laplacian::new(system, weights, (0, &[]), (Inverse::Factor, weak), 0.0).unwrap()
    }

    fn entries(laplacian: &Laplacian) -> usize {
        match &laplacian.solver {
            Solver::Factor(factor) => factor.entries(),
            Solver::Multigrid(..) => unreachable!("a factor was asked for"),
        }
    }

    /// `A y`, coordinate by coordinate (nothing is pinned).
    fn product(a: &Csr, y: &[Vec3]) -> Vec<Vec3> {
        let mut b = vec![Vec3::zeros(); y.len()];
        let (mut column, mut out) = (vec![0.0; y.len()], vec![0.0; y.len()]);
        for c in 0..3 {
            column.iter_mut().zip(y).for_each(|(x, y)| *x = y[c]);
            a.apply(&column, &mut out);
            b.iter_mut().zip(&out).for_each(|(b, o)| b[c] = *o);
        }
        b
    }

    /// With the grid's bending springs routed, `H₀` becomes a matrix `P` at
    /// least the whole one `A` that equals it on affine fields, with a
    /// smaller factor: for `b = A y`, `P⁻¹ b` is `y` itself where `y` is
    /// affine, and for any `y`, `bᵀP⁻¹b ≤ bᵀA⁻¹b = yᵀA y` — strictly
    /// where the field bends. The columns' spacing grows along the rows, so
    /// the legs of a route differ in length and each weight must go to its
    /// own leg for the affine fields to come back.
    #[test]
    fn routed_weak_springs_make_a_smaller_majorizer_exact_on_affine_fields() {
        let n = 12;
        let system = stiff_and_weak_grid(n, 0.1);
        let (kept, mut routed) = (
            matrix(&system, WeakSprings::Kept),
            matrix(&system, WeakSprings::Routed),
        );
        let (whole, carried) = (entries(&kept), entries(&routed));
        assert!(4 * carried < 3 * whole, "{carried} against {whole}");
        let gradient = Mat3::new(0.3, -1.2, 0.5, 0.7, 0.2, -0.4, 1.1, 0.6, -0.9);
        let affine: Vec<Vec3> = system
            .initial_positions()
            .iter()
            .map(|x| gradient * x + Vec3::new(0.1, -0.2, 0.3))
            .collect();
        let mut x = product(&kept.layout.a, &affine);
        routed.apply_inverse_in_place(&mut x);
        let size = affine.iter().map(|y| y.norm()).fold(0.0, f64::max);
        for (i, (x, y)) in x.iter().zip(&affine).enumerate() {
            assert!(
                (x - y).norm() < 1e-9 * size,
                "particle {i}: {x:?} against {y:?}"
            );
        }
        let bent: Vec<Vec3> = system
            .initial_positions()
            .iter()
            .map(|p| Vec3::new((3.0 * p.x).sin(), (p.x * p.z).cos(), (2.0 * p.z).sin()))
            .collect();
        let b = product(&kept.layout.a, &bent);
        let mut x = b.clone();
        routed.apply_inverse_in_place(&mut x);
        let (majorized, whole) = (dot(&b, &x), dot(&b, &bent));
        assert!(
            majorized < whole * (1.0 - 1e-9),
            "{majorized} against {whole}"
        );
    }
}
