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
mod tests {
    use super::*;

    /// `M + h² Σₛ kₛ (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ` of the bench cloth, `side × side`
    /// particles of 1 kg in all, stretch / shear / bend springs of
    /// 5000 / 500 / 50 N/m, `h = 1/60 s`.
    fn cloth(side: usize) -> Csr {
        let n = side * side;
        let h2 = (1.0f64 / 60.0).powi(2);
        let mut rows: Vec<Vec<(u32, f64)>> =
            (0..n).map(|i| vec![(i as u32, 1.0 / n as f64)]).collect();
        let mut spring = |i: usize, j: usize, k: f64| {
            let w = h2 * k;
            for (r, c, v) in [(i, i, w), (j, j, w), (i, j, -w), (j, i, -w)] {
                match rows[r].iter_mut().find(|e| e.0 as usize == c) {
                    Some(e) => e.1 += v,
                    None => rows[r].push((c as u32, v)),
                }
            }
        };
        for y in 0..side {
            for x in 0..side {
                let i = y * side + x;
                for (dx, dy, k) in [
                    (1, 0, 5000.0),
                    (0, 1, 5000.0),
                    (1, 1, 500.0),
                    (2, 0, 50.0),
                    (0, 2, 50.0),
                ] {
                    if x + dx < side && y + dy < side {
                        spring(i, (y + dy) * side + x + dx, k);
                    }
                }
                if x >= 1 && y + 1 < side {
                    spring(i, (y + 1) * side + x - 1, 500.0);
                }
            }
        }
        let mut a = Csr {
            row_ptr: vec![0],
            ..Csr::default()
        };
        for mut row in rows {
            row.sort_unstable_by_key(|e| e.0);
            a.col_idx.extend(row.iter().map(|e| e.0));
            a.values.extend(row.iter().map(|e| e.1));
            a.row_ptr.push(a.col_idx.len());
        }
        a
    }

    fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    /// A vector that looks random in its index and `seed`.
    fn noise(n: usize, seed: usize) -> Vec<f64> {
        (0..n)
            .map(|i| ((i * 7919 + seed * 104_729) % 1000) as f64 / 500.0 - 1.0)
            .collect()
    }

    /// PCG on `a x = b` from zero with one V-cycle as the preconditioner, to
    /// `‖b − a x‖ ≤ 10⁻⁸ ‖b‖`; returns its iterations.
    fn pcg(amg: &mut ScalarAmg, a: &Csr, b: &[f64]) -> usize {
        let n = b.len();
        let (mut x, mut r, mut z, mut q) = (vec![0.0; n], b.to_vec(), vec![0.0; n], vec![0.0; n]);
        amg.apply(a, &r, &mut z);
        let mut p = z.clone();
        let mut rz = dot(&r, &z);
        let goal = 1e-8 * dot(b, b).sqrt();
        for iteration in 1..=200 {
            a.apply(&p, &mut q);
            let alpha = rz / dot(&p, &q);
            x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += alpha * pi);
            r.iter_mut().zip(&q).for_each(|(ri, qi)| *ri -= alpha * qi);
            if dot(&r, &r).sqrt() <= goal {
                // The recurrence's residual is the true one.
                a.apply(&x, &mut q);
                let true_residual: f64 = b
                    .iter()
                    .zip(&q)
                    .map(|(bi, qi)| (bi - qi).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(true_residual <= 2.0 * goal, "{true_residual} {goal}");
                return iteration;
            }
            amg.apply(a, &r, &mut z);
            let next = dot(&r, &z);
            p.iter_mut()
                .zip(&z)
                .for_each(|(pi, zi)| *pi = zi + next / rz * *pi);
            rz = next;
        }
        panic!("PCG did not converge in 200 iterations");
    }

    /// L-BFGS needs its `H₀⁻¹` to be one fixed symmetric positive-definite
    /// operator: `uᵀ B v = vᵀ B u` and `uᵀ B u > 0` for the cycle `B`.
    #[test]
    fn one_cycle_is_a_symmetric_positive_definite_operator() {
        let a = cloth(80);
        let mut amg = ScalarAmg::build(&a).unwrap();
        assert!(amg.unknowns(&a).len() >= 2, "{:?}", amg.unknowns(&a));
        let n = a.rows();
        let (u, v) = (noise(n, 1), noise(n, 2));
        let (mut bu, mut bv) = (vec![0.0; n], vec![0.0; n]);
        amg.apply(&a, &u, &mut bu);
        amg.apply(&a, &v, &mut bv);
        let (ubv, vbu) = (dot(&u, &bv), dot(&v, &bu));
        assert!(
            (ubv - vbu).abs() <= 1e-10 * ubv.abs().max(vbu.abs()),
            "{ubv} {vbu}"
        );
        assert!(dot(&u, &bu) > 0.0 && dot(&v, &bv) > 0.0);
    }

    /// Multigrid's point: PCG with one cycle takes about as many iterations
    /// on a mesh 16 times larger (Jacobi-preconditioned CG would take four
    /// times as many).
    #[test]
    fn iterations_barely_grow_with_the_mesh() {
        let mut counts = Vec::new();
        for side in [50, 200] {
            let a = cloth(side);
            let mut amg = ScalarAmg::build(&a).unwrap();
            counts.push(pcg(&mut amg, &a, &noise(a.rows(), 3)));
        }
        assert!(
            counts[1] <= 25 && counts[1] as f64 <= 1.5 * counts[0] as f64,
            "{counts:?}"
        );
    }

    /// Springs a thousand times softer than the masses make no connection
    /// strong; the hierarchy still coarsens (instead of factorizing the
    /// whole matrix), and PCG with it converges at once.
    #[test]
    fn a_matrix_without_strong_connections_still_coarsens() {
        let mut a = cloth(60);
        for i in 0..a.rows() {
            for k in a.row_ptr[i]..a.row_ptr[i + 1] {
                if a.col_idx[k] as usize != i {
                    a.values[k] *= 1e-7;
                }
            }
        }
        // Each diagonal is its mass plus the softened springs' weights.
        for i in 0..a.rows() {
            let off: f64 = (a.row_ptr[i]..a.row_ptr[i + 1])
                .filter(|&k| a.col_idx[k] as usize != i)
                .map(|k| -a.values[k])
                .sum();
            let diagonal = (a.row_ptr[i]..a.row_ptr[i + 1])
                .find(|&k| a.col_idx[k] as usize == i)
                .unwrap();
            a.values[diagonal] = 1.0 / 3600.0 + off;
        }
        let mut amg = ScalarAmg::build(&a).unwrap();
        assert!(amg.unknowns(&a).len() >= 2, "{:?}", amg.unknowns(&a));
        assert!(pcg(&mut amg, &a, &noise(a.rows(), 5)) <= 10);
    }

    /// A matrix within the coarsest level's size is factorized whole, and
    /// one application solves it.
    #[test]
    fn a_small_matrix_is_solved_exactly() {
        let a = cloth(20);
        let mut amg = ScalarAmg::build(&a).unwrap();
        assert_eq!(amg.unknowns(&a), [400]);
        let x = noise(400, 4);
        let mut b = vec![0.0; 400];
        a.apply(&x, &mut b);
        let mut solved = vec![0.0; 400];
        amg.apply(&a, &b, &mut solved);
        for (s, x) in solved.iter().zip(&x) {
            assert!((s - x).abs() < 1e-9, "{s} {x}");
        }
    }
}
