//! Smoothed-aggregation multigrid on a scalar symmetric positive-definite
//! matrix in compressed rows — the quasi-Newton step's initial Hessian
//! `H₀ = M + βh C₀ + β²h² L` (the masses plus a weighted graph Laplacian of
//! the springs) on meshes where its Cholesky factor would not fit.
//!
//! The same construction as the 3x3-block hierarchy (module docs of
//! [`amg`](super)), with the constant vector as the near-null space (the
//! one motion a graph Laplacian does not resist):
//!
//! 1. aggregates by strength of connection `|a_ij| ≥ θ √(a_ii a_jj)`;
//! 2. the tentative prolongator `T`, one column per aggregate, `1/√|𝒜|` on
//!    its nodes (a node without strong neighbours is left to the smoother);
//! 3. the smoothed prolongator `P = (I − ω D⁻¹A) T`, `ω = 4/(3 λ_max(D⁻¹A))`,
//!    and the Galerkin operator `A_c = Pᵀ A P`,
//!
//! down to at most [`COARSE_UNKNOWNS`] unknowns, which faer's sparse
//! Cholesky factorizes. One application is one V-cycle with a Chebyshev
//! sweep preconditioned by `D⁻¹` before and after the coarse correction:
//! the same polynomial on both sides, so the cycle is a fixed symmetric
//! positive-definite operator, as L-BFGS needs of its `H₀⁻¹`.

use super::aggregation::{Graph, ISOLATED, aggregate};
use super::coarse::ScalarCholesky;
use super::csr::Csr;
use super::level::{chebyshev, estimate_largest, smoothing_weight_for};
use super::smoother::{BlockInverse, Chebyshev, Sweep};

/// The most unknowns of the coarsest level, which is factorized.
pub(crate) const COARSE_UNKNOWNS: usize = 2000;

/// The strength threshold `θ` of the aggregation: a spring whose weight is
/// below this fraction of its ends' diagonals (a bend spring beside the
/// stretch springs of a cloth) does not join its ends into one aggregate.
const STRENGTH: f64 = 0.08;

/// The Chebyshev degree of each smoothing sweep.
const DEGREE: usize = 2;

/// A coarsening that keeps more than this fraction of a level's unknowns
/// ends the hierarchy there.
const MIN_REDUCTION: f64 = 0.8;

/// The hierarchy of a scalar matrix `A` (which the caller keeps and passes
/// to every application): the levels above the coarsest, finest first, and
/// the coarsest's factor.
#[derive(Debug)]
pub(crate) struct ScalarAmg {
    levels: Vec<ScalarLevel>,
    coarsest: ScalarCholesky,
}

/// One level above the coarsest: its smoother, the transfers to the next
/// level, the next level's operator and the vectors of a cycle.
#[derive(Debug)]
struct ScalarLevel {
    inverse: BlockInverse<1>,
    smoother: Chebyshev,
    p: Csr,
    r: Csr,
    /// The next level's operator `Pᵀ A P`.
    coarse: Csr,
    residual: Vec<f64>,
    coarse_b: Vec<f64>,
    coarse_x: Vec<f64>,
    sweep: Sweep,
}

/// Why a hierarchy could not be built: a diagonal entry or the coarsest
/// level is not positive definite, or the coarsest level does not fit
/// 32-bit indices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotBuilt;

impl ScalarAmg {
    /// Builds the hierarchy of `a`.
    ///
    /// # Errors
    /// [`NotBuilt`] if a level's diagonal is not positive or the coarsest
    /// level is not positive definite or too large.
    pub(crate) fn build(a: &Csr) -> Result<Self, NotBuilt> {
        let mut levels: Vec<ScalarLevel> = Vec::new();
        loop {
            let current = levels.last().map_or(a, |l| &l.coarse);
            let n = current.rows();
            if n <= COARSE_UNKNOWNS {
                break;
            }
            let level = ScalarLevel::build(current)?;
            if level.coarse.rows() == 0 || level.coarse.rows() as f64 > MIN_REDUCTION * n as f64 {
                break;
            }
            levels.push(level);
        }
        let coarse = levels.last().map_or(a, |l| &l.coarse);
        let mut coarsest = ScalarCholesky::new(coarse).ok_or(NotBuilt)?;
        coarsest.factorize(coarse).map_err(|()| NotBuilt)?;
        Ok(Self { levels, coarsest })
    }

    /// The levels' unknowns, finest first, the coarsest included.
    #[cfg(test)]
    pub(crate) fn unknowns(&self, a: &Csr) -> Vec<usize> {
        std::iter::once(a.rows())
            .chain(self.levels.iter().map(|l| l.coarse.rows()))
            .collect()
    }

    /// `x ≈ A⁻¹ b` by one V-cycle (exactly, for a matrix without coarser
    /// levels); `a` is the matrix the hierarchy was built for.
    pub(crate) fn apply(&mut self, a: &Csr, b: &[f64], x: &mut [f64]) {
        cycle(&mut self.levels, &mut self.coarsest, a, b, x);
    }
}

/// One V-cycle from `levels[0]`, whose operator is `a`; the coarsest
/// level's solve where there is none.
fn cycle(
    levels: &mut [ScalarLevel],
    coarsest: &mut ScalarCholesky,
    a: &Csr,
    b: &[f64],
    x: &mut [f64],
) {
    let Some((level, rest)) = levels.split_first_mut() else {
        x.copy_from_slice(b);
        coarsest.solve(x);
        return;
    };
    let ScalarLevel {
        inverse,
        smoother,
        p,
        r,
        coarse,
        residual,
        coarse_b,
        coarse_x,
        sweep,
    } = level;
    let inverse = |r: &[f64], z: &mut [f64]| inverse.apply(r, z);
    x.fill(0.0);
    smoother.smooth(&mut |x, y| a.apply(x, y), &inverse, b, x, true, sweep);
    a.apply(x, residual);
    residual
        .iter_mut()
        .zip(b)
        .for_each(|(ri, bi)| *ri = bi - *ri);
    r.apply(residual, coarse_b);
    cycle(rest, coarsest, coarse, coarse_b, coarse_x);
    p.apply(coarse_x, residual);
    x.iter_mut()
        .zip(residual.iter())
        .for_each(|(xi, c)| *xi += c);
    smoother.smooth(&mut |x, y| a.apply(x, y), &inverse, b, x, false, sweep);
}

impl ScalarLevel {
    /// The level of `a`: aggregates, smoother, transfers and the Galerkin
    /// operator of the next level.
    fn build(a: &Csr) -> Result<Self, NotBuilt> {
        let n = a.rows();
        let mut diagonal = vec![0.0; n];
        let mut graph = Graph {
            ptr: Vec::with_capacity(n + 1),
            ..Graph::default()
        };
        graph.ptr.push(0);
        for (i, d) in diagonal.iter_mut().enumerate() {
            for k in a.row_ptr[i]..a.row_ptr[i + 1] {
                let j = a.col_idx[k];
                if j as usize == i {
                    *d = a.values[k];
                } else {
                    graph.adj.push(j);
                    graph.weight.push(a.values[k].abs());
                }
            }
            graph.ptr.push(graph.adj.len());
        }
        let mut inverse = BlockInverse::<1>::new(n);
        inverse
            .refill(|i, out| out[0][0] = diagonal[i])
            .map_err(|_| NotBuilt)?;
        graph.diagonal.clone_from(&diagonal);
        // Where no connection is strong (springs far softer than the
        // masses), every neighbour counts: the level still coarsens.
        let (agg, count) = match aggregate(&graph, STRENGTH) {
            (_, count) if count == 0 || count as f64 > MIN_REDUCTION * n as f64 => {
                aggregate(&graph, 0.0)
            }
            strong => strong,
        };
        drop(graph);
        let t = tentative(&agg, count);
        let lambda = estimate_largest(&mut |x, y| a.apply(x, y), &|r, z| inverse.apply(r, z), n);
        let omega = smoothing_weight_for(lambda);
        // P = T − ω D⁻¹ A T: A T holds T's entries (A's diagonal is positive).
        let mut p = a.product(&t, count);
        for i in 0..n {
            let w = omega * diagonal[i].recip();
            for k in p.row_ptr[i]..p.row_ptr[i + 1] {
                let own = if p.col_idx[k] == agg[i] {
                    t.values[t.row_ptr[i]]
                } else {
                    0.0
                };
                p.values[k] = own - w * p.values[k];
            }
        }
        let r = p.transpose(count);
        let coarse = r.product(&a.product(&p, count), count);
        Ok(Self {
            inverse,
            smoother: chebyshev(lambda, DEGREE),
            residual: vec![0.0; n],
            coarse_b: vec![0.0; count],
            coarse_x: vec![0.0; count],
            sweep: Sweep {
                r: vec![0.0; n],
                d: vec![0.0; n],
                z: vec![0.0; n],
                q: vec![0.0; n],
            },
            p,
            r,
            coarse,
        })
    }
}

/// `T`: row `i` holds `1/√|𝒜|` in the column of its aggregate `𝒜`, or
/// nothing for an isolated node.
fn tentative(agg: &[u32], count: usize) -> Csr {
    let mut sizes = vec![0usize; count];
    for &g in agg.iter().filter(|&&g| g != ISOLATED) {
        sizes[g as usize] += 1;
    }
    let mut t = Csr {
        row_ptr: Vec::with_capacity(agg.len() + 1),
        col_idx: Vec::with_capacity(agg.len()),
        values: Vec::with_capacity(agg.len()),
    };
    t.row_ptr.push(0);
    for &g in agg {
        if g != ISOLATED {
            t.col_idx.push(g);
            t.values.push((sizes[g as usize] as f64).sqrt().recip());
        }
        t.row_ptr.push(t.col_idx.len());
    }
    t
}

#[cfg(test)]
mod tests;
