//! The constant scalar matrix of fast mass-spring and of the quasi-Newton
//! step's initial Hessian: the masses plus a weighted graph Laplacian of the
//! springs, the same for the three coordinates, over the free particles
//! only, factorized by faer's sparse Cholesky or, where that factor would
//! be large, applied approximately by one multigrid V-cycle.

use hooke_core::{Spring, StepError, System, Vec3};

use crate::linear::amg::coarse::ScalarCholesky;
use crate::linear::amg::csr::Csr;
use crate::linear::amg::scalar::ScalarAmg;
use crate::linear::vector::for_each_row;
use crate::{LinearSolver, PcgSettings};

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
    /// The factor while it holds at most [`FACTOR_ENTRIES_PER_UNKNOWN`]
    /// entries per free particle, multigrid beyond.
    #[default]
    Auto,
}

/// The largest Cholesky factor [`Inverse::Auto`] keeps, in entries per
/// free particle (8 bytes each). The bench cloth's factor holds 44, 77,
/// 102, 121 and 141 entries per particle at 50², 100², 200², 400² and
/// 700² particles; with multigrid instead, L-BFGS to `1e-2` took 11.85
/// against 11.2 iterations a step and 1.07× the time at 100², 12.45
/// against 11.25 iterations and 0.74× the time at 200² (20 steps,
/// `examples/million_cloth.rs`).
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
#[derive(Debug)]
pub(crate) struct Laplacian {
    system: u64,
    /// The key of the weights last factorized (a step size's bits); `None`
    /// when the factor holds an extra diagonal or failed.
    key: Option<u64>,
    /// Per particle, its unknown (`u32::MAX` for a pinned one).
    pub(crate) unknown: Vec<u32>,
    a: Csr,
    /// Per free particle, its diagonal entry in `a`'s values.
    diagonal: Vec<u32>,
    /// Per spring, the entries `(i, i), (j, j), (i, j), (j, i)` of `a`'s
    /// values it adds to (`u32::MAX` where an end is pinned).
    entries: Vec<[u32; 4]>,
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
    /// `time`, for the errors).
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] beyond 32-bit indices,
    /// [`StepError::NotPositiveDefinite`] if the matrix is not.
    pub(crate) fn new(
        system: &System,
        (air, weight): (f64, impl Fn(&Spring) -> f64),
        (key, extra): (u64, &[f64]),
        inverse: Inverse,
        time: f64,
    ) -> Result<Self, StepError> {
        let n = system.particle_count();
        let too_large = || StepError::SystemTooLarge {
            particles: n,
            springs: system.springs().len(),
        };
        let mut unknown = vec![u32::MAX; n];
        let mut count = 0u32;
        for (i, u) in unknown.iter_mut().enumerate() {
            if !system.is_pinned(i) {
                *u = count;
                count += 1;
            }
        }
        let free = count as usize;
        // (row, column) of both triangles, with the particles' diagonals.
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(free + 2 * system.springs().len());
        pairs.extend((0..count).map(|u| (u, u)));
        for s in system.springs() {
            let (ui, uj) = (unknown[s.i], unknown[s.j]);
            if ui != u32::MAX && uj != u32::MAX {
                pairs.push((ui, uj));
                pairs.push((uj, ui));
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        if pairs.len() >= u32::MAX as usize {
            return Err(too_large());
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
        let diagonal = (0..count).map(|u| at(u, u)).collect();
        let entries = system
            .springs()
            .iter()
            .map(|s| {
                let (ui, uj) = (unknown[s.i], unknown[s.j]);
                let off = |r, c| {
                    if ui == u32::MAX || uj == u32::MAX {
                        u32::MAX
                    } else {
                        at(r, c)
                    }
                };
                [at(ui, ui), at(uj, uj), off(ui, uj), off(uj, ui)]
            })
            .collect();
        let multigrid = || Solver::Multigrid(None, vec![0.0; free]);
        let solver = match inverse {
            Inverse::Multigrid => multigrid(),
            Inverse::Factor => Solver::Factor(ScalarCholesky::new(&a).ok_or_else(too_large)?),
            Inverse::Auto => match ScalarCholesky::new(&a) {
                Some(f) if f.entries() <= FACTOR_ENTRIES_PER_UNKNOWN * free => Solver::Factor(f),
                _ => multigrid(),
            },
        };
        let mut laplacian = Self {
            system: system.id(),
            key: None,
            unknown,
            a,
            diagonal,
            entries,
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
        let values = &mut self.a.values;
        values.fill(0.0);
        let shift = air * system.air_damping().unwrap_or(0.0);
        let mut free = self.diagonal.iter();
        for (i, &m) in system.masses().iter().enumerate() {
            if self.unknown[i] != u32::MAX {
                let added = extra.get(i).copied().unwrap_or(0.0);
                let k = *free.next().expect("one diagonal a free particle");
                values[k as usize] = m + shift + added;
            }
        }
        for (s, entries) in system.springs().iter().zip(&self.entries) {
            let w = weight(s);
            for (k, &e) in entries.iter().enumerate() {
                if e != u32::MAX {
                    values[e as usize] += if k < 2 { w } else { -w };
                }
            }
        }
        self.key = None;
        let not_positive_definite = || StepError::NotPositiveDefinite {
            time,
            particle: None,
        };
        match &mut self.solver {
            Solver::Factor(cholesky) => cholesky
                .factorize(&self.a)
                .map_err(|()| not_positive_definite())?,
            Solver::Multigrid(amg, _) => {
                // The old hierarchy goes before the new one is built, so
                // that the two are never held together.
                *amg = None;
                *amg = Some(ScalarAmg::build(&self.a).map_err(|_| not_positive_definite())?);
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
                    amg.apply(&self.a, column, x);
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
