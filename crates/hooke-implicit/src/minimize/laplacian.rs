//! The constant scalar matrix of fast mass-spring and of the quasi-Newton
//! step's initial Hessian: the masses plus a weighted graph Laplacian of the
//! springs, the same for the three coordinates, over the free particles
//! only, factorized by faer's sparse Cholesky.

use hooke_core::{Spring, StepError, System, Vec3};

use crate::linear::amg::coarse::ScalarCholesky;
use crate::linear::amg::csr::Csr;
use crate::linear::vector::for_each_row;

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
    diagonal: Vec<usize>,
    /// Per spring, the entries `(i, i), (j, j), (i, j), (j, i)` of `a`'s
    /// values it adds to (`usize::MAX` where an end is pinned).
    entries: Vec<[usize; 4]>,
    cholesky: ScalarCholesky,
    /// The three coordinates of a right-hand side, then of the solution,
    /// one after the other (coordinate `c` of free particle `u` at
    /// `c · free + u`).
    pub(crate) rhs: Vec<f64>,
}

impl Laplacian {
    /// The pattern of `system`'s matrix, its symbolic analysis and its
    /// factor for the air-damping coefficient `air`, the spring weights
    /// `weight`, `key` and the extra diagonal `extra` (see
    /// [`Laplacian::refactor`]; at `time`, for the errors).
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] beyond 32-bit indices,
    /// [`StepError::NotPositiveDefinite`] if the matrix is not.
    pub(crate) fn new(
        system: &System,
        (air, weight): (f64, impl Fn(&Spring) -> f64),
        (key, extra): (u64, &[f64]),
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
        let at = |r: u32, c: u32| {
            if r == u32::MAX || c == u32::MAX {
                return usize::MAX;
            }
            let row = a.row_ptr[r as usize]..a.row_ptr[r as usize + 1];
            row.start
                + a.col_idx[row]
                    .binary_search(&c)
                    .expect("every spring's entries are in the pattern")
        };
        let diagonal = (0..count).map(|u| at(u, u)).collect();
        let entries = system
            .springs()
            .iter()
            .map(|s| {
                let (ui, uj) = (unknown[s.i], unknown[s.j]);
                let off = |r, c| {
                    if ui == u32::MAX || uj == u32::MAX {
                        usize::MAX
                    } else {
                        at(r, c)
                    }
                };
                [at(ui, ui), at(uj, uj), off(ui, uj), off(uj, ui)]
            })
            .collect();
        let cholesky = ScalarCholesky::new(&a).ok_or_else(too_large)?;
        let mut laplacian = Self {
            system: system.id(),
            key: None,
            unknown,
            a,
            diagonal,
            entries,
            cholesky,
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
    /// empty `extra`) and factorizes it.
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
                values[*free.next().expect("one diagonal a free particle")] = m + shift + added;
            }
        }
        for (s, entries) in system.springs().iter().zip(&self.entries) {
            let w = weight(s);
            for (k, &e) in entries.iter().enumerate() {
                if e != usize::MAX {
                    values[e] += if k < 2 { w } else { -w };
                }
            }
        }
        self.key = None;
        self.cholesky
            .factorize(&self.a)
            .map_err(|()| StepError::NotPositiveDefinite {
                time,
                particle: None,
            })?;
        self.key = extra.is_empty().then_some(key);
        Ok(())
    }

    /// Solves the matrix's system for the three columns of `rhs` in place,
    /// in one pass over the factor.
    pub(crate) fn solve(&mut self) {
        self.cholesky.solve(&mut self.rhs);
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
