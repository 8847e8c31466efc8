//! The multigrid smoother: Chebyshev iteration preconditioned by the
//! inverses of a level's diagonal node blocks (3x3 on the particles, 6x6 on
//! the aggregates of the coarse levels).

use super::bsr::{Block, for_each_block, zero};
use crate::linear::vector::PARALLEL_MIN_PARTICLES;

/// The inverses of the diagonal `N × N` blocks `A_II` of a level, one per
/// node.
#[derive(Debug, Default)]
pub(crate) struct BlockInverse<const N: usize> {
    values: Vec<Block<N, N>>,
}

impl<const N: usize> BlockInverse<N> {
    /// Storage for the blocks of `nodes` nodes.
    pub(crate) fn new(nodes: usize) -> Self {
        Self {
            values: vec![zero(); nodes],
        }
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        8 * N * N * self.values.len()
    }

    /// Inverts every node's block, read by `block(I, out)`; returns the
    /// first node whose block is not positive definite, if any.
    pub(crate) fn refill(&mut self, block: impl Fn(usize, &mut Block<N, N>)) -> Result<(), usize> {
        for (node, out) in self.values.iter_mut().enumerate() {
            block(node, out);
            invert_spd(out).ok_or(node)?;
        }
        Ok(())
    }

    /// `z = D⁻¹ r`.
    pub(crate) fn apply(&self, r: &[f64], z: &mut [f64]) {
        for_each_block(z, N, PARALLEL_MIN_PARTICLES, |node, zi| {
            let ri = &r[N * node..N * (node + 1)];
            for (za, row) in zi.iter_mut().zip(&self.values[node]) {
                *za = row.iter().zip(ri).map(|(m, x)| m * x).sum();
            }
        });
    }
}

/// Inverts the symmetric positive-definite block `m` in place (Cholesky
/// `L Lᵀ`, then `L⁻ᵀ L⁻¹`); `None` if it is not positive definite.
fn invert_spd<const N: usize>(m: &mut Block<N, N>) -> Option<()> {
    let mut l: Block<N, N> = zero();
    for j in 0..N {
        let d = m[j][j] - (0..j).map(|p| l[j][p] * l[j][p]).sum::<f64>();
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        l[j][j] = d.sqrt();
        for i in j + 1..N {
            let s = m[i][j] - (0..j).map(|p| l[i][p] * l[j][p]).sum::<f64>();
            l[i][j] = s / l[j][j];
        }
    }
    // Column c of L⁻¹ by forward substitution, as row c of w; then
    // M⁻¹ = L⁻ᵀ L⁻¹, (M⁻¹)_ij = Σ_p w_ip w_jp.
    let mut w: Block<N, N> = zero();
    for (c, column) in w.iter_mut().enumerate() {
        for i in c..N {
            let s =
                if i == c { 1.0 } else { 0.0 } - (c..i).map(|p| l[i][p] * column[p]).sum::<f64>();
            column[i] = s / l[i][i];
        }
    }
    for (i, row) in m.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = (i.max(j)..N).map(|p| w[i][p] * w[j][p]).sum();
        }
    }
    Some(())
}

/// An estimate of the largest eigenvalue of `D⁻¹A` (`A` applied by `apply`,
/// `D⁻¹` by `inverse`), the generalized Rayleigh quotient
/// `λ = yᵀAy / yᵀDy` of the `iterations`-th power iterate `y = (D⁻¹A)ᵏ x₀`.
/// It never exceeds the largest eigenvalue and approaches it from below.
/// `x` is the start on entry — a pseudo-random vector, rich in every
/// eigenvector, when empty — and the last iterate on return, the warm
/// start of the next estimate for a matrix with nearly the same spectrum.
pub(crate) fn largest_eigenvalue(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    inverse: &dyn Fn(&[f64], &mut [f64]),
    x: &mut Vec<f64>,
    n: usize,
    iterations: usize,
) -> f64 {
    if x.len() != n {
        *x = (0..n).map(scrambled).collect();
    }
    let mut z = vec![0.0; n];
    let mut y = vec![0.0; n];
    let mut lambda = 0.0;
    apply(x, &mut z);
    for _ in 0..iterations {
        inverse(&z, &mut y);
        let yz: f64 = y.iter().zip(&z).map(|(a, b)| a * b).sum();
        apply(&y, x);
        let yay: f64 = y.iter().zip(x.iter()).map(|(a, b)| a * b).sum();
        if !(yz > 0.0 && yay.is_finite()) {
            break;
        }
        lambda = yay / yz;
        let norm = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        // z = A y / ‖y‖, the product at the next iterate y / ‖y‖.
        z.iter_mut()
            .zip(x.iter())
            .for_each(|(zi, xi)| *zi = xi / norm);
        x.iter_mut().zip(&y).for_each(|(xi, yi)| *xi = yi / norm);
    }
    lambda
}

/// A value in `[−1, 1)` that looks random in `i`: the power method's start,
/// rich in every eigenvector (a smooth start has almost nothing of the
/// highest ones, which the method must find).
fn scrambled(i: usize) -> f64 {
    let mut h = (i as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
    h = (h ^ (h >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    h ^= h >> 31;
    (h >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// A Chebyshev smoother for `A x = b`, preconditioned by `D⁻¹`, of the
/// given degree, whose polynomial is smallest on `[λ_max/ratio, λ_max]` of
/// `D⁻¹A` (Adams, Brezina, Hu & Tuminaro, *Parallel multigrid smoothing:
/// polynomial versus Gauss–Seidel*, J. Comput. Phys. 188, 2003).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Chebyshev {
    pub(crate) low: f64,
    pub(crate) high: f64,
    pub(crate) degree: usize,
}

/// The vectors a smoothing sweep works in.
#[derive(Debug, Default)]
pub(crate) struct Sweep {
    pub(crate) r: Vec<f64>,
    pub(crate) d: Vec<f64>,
    pub(crate) z: Vec<f64>,
    pub(crate) q: Vec<f64>,
}

impl Chebyshev {
    /// Improves `x` (zero on entry when `zero`) towards `A x = b` by the
    /// Chebyshev iteration (Saad, *Iterative Methods for Sparse Linear
    /// Systems*, Alg. 12.1) with `θ = (high + low)/2`, `δ = (high − low)/2`:
    ///
    /// ```text
    /// r = b − A x,  d = D⁻¹r / θ,  ρ = δ/θ
    /// repeat: x += d,  r −= A d,  ρ' = 1/(2θ/δ − ρ),
    ///         d = ρ'ρ d + (2ρ'/δ) D⁻¹ r,  ρ = ρ'
    /// ```
    ///
    /// The sweep is a fixed polynomial in `D⁻¹A`, so a pre- and a
    /// post-smoothing sweep make a symmetric V-cycle.
    pub(crate) fn smooth(
        &self,
        apply: &mut dyn FnMut(&[f64], &mut [f64]),
        inverse: &dyn Fn(&[f64], &mut [f64]),
        b: &[f64],
        x: &mut [f64],
        zero: bool,
        sweep: &mut Sweep,
    ) {
        let Sweep { r, d, z, q } = sweep;
        let theta = 0.5 * (self.high + self.low);
        let delta = 0.5 * (self.high - self.low);
        if zero {
            r.copy_from_slice(b);
        } else {
            apply(x, q);
            r.iter_mut()
                .zip(b.iter().zip(q.iter()))
                .for_each(|(ri, (bi, qi))| *ri = bi - qi);
        }
        inverse(r, z);
        d.iter_mut()
            .zip(z.iter())
            .for_each(|(di, zi)| *di = zi / theta);
        let mut rho = delta / theta;
        for k in 0..self.degree {
            x.iter_mut().zip(d.iter()).for_each(|(xi, di)| *xi += di);
            if k + 1 == self.degree {
                break;
            }
            apply(d, q);
            r.iter_mut().zip(q.iter()).for_each(|(ri, qi)| *ri -= qi);
            inverse(r, z);
            let next = 1.0 / (2.0 * theta / delta - rho);
            let (a, c) = (next * rho, 2.0 * next / delta);
            d.iter_mut()
                .zip(z.iter())
                .for_each(|(di, zi)| *di = a * *di + c * zi);
            rho = next;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_inverse_inverts_and_refuses_indefinite_blocks() {
        let mut inverse = BlockInverse::<2>::new(2);
        let blocks = [[[4.0, 1.0], [1.0, 3.0]], [[2.0, 0.0], [0.0, 4.0]]];
        inverse.refill(|i, out| *out = blocks[i]).unwrap();
        let mut z = vec![0.0; 4];
        inverse.apply(&[5.0, 4.0, 1.0, 2.0], &mut z);
        // [[4, 1], [1, 3]] (1, 1) = (5, 4).
        for (zi, expected) in z.iter().zip([1.0, 1.0, 0.5, 0.5]) {
            assert!((zi - expected).abs() < 1e-14);
        }
        let indefinite = [[[1.0, 0.0], [0.0, 1.0]], [[1.0, 2.0], [2.0, 1.0]]];
        assert_eq!(inverse.refill(|i, out| *out = indefinite[i]), Err(1));
    }

    /// The 1-D Laplacian tridiag(−1, 2, −1) of size n has eigenvalues
    /// 2 − 2 cos(kπ/(n+1)); with D = 2I the largest of D⁻¹A is
    /// 1 + cos(π/(n+1)), and a Chebyshev sweep on [λ/30, λ] reduces the
    /// error's high-frequency part.
    #[test]
    fn power_iteration_and_chebyshev_on_the_laplacian() {
        let n = 50;
        let mut apply = |x: &[f64], y: &mut [f64]| {
            for i in 0..n {
                let left = if i > 0 { x[i - 1] } else { 0.0 };
                let right = if i + 1 < n { x[i + 1] } else { 0.0 };
                y[i] = 2.0 * x[i] - left - right;
            }
        };
        let mut inverse = BlockInverse::<1>::new(n);
        inverse.refill(|_, out| out[0][0] = 2.0).unwrap();
        let exact = 1.0 + (std::f64::consts::PI / (n as f64 + 1.0)).cos();
        let estimate = largest_eigenvalue(
            &mut apply,
            &|r, z| inverse.apply(r, z),
            &mut Vec::new(),
            n,
            30,
        );
        assert!(
            estimate <= exact + 1e-12 && estimate > 0.95 * exact,
            "{estimate}"
        );
        let smoother = Chebyshev {
            low: exact / 30.0,
            high: exact,
            degree: 3,
        };
        // The error of x = 0 against the solution of A x = A e, for an
        // oscillating e (high frequencies): each sweep of degree 3 shrinks
        // them by at most 1/T₃(θ/δ) = 0.596 on [λ/30, λ], three by 0.21.
        let e: Vec<f64> = (0..n)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let mut b = vec![0.0; n];
        apply(&e, &mut b);
        let mut x = vec![0.0; n];
        let mut sweep = Sweep {
            r: vec![0.0; n],
            d: vec![0.0; n],
            z: vec![0.0; n],
            q: vec![0.0; n],
        };
        for k in 0..3 {
            smoother.smooth(
                &mut apply,
                &|r, z| inverse.apply(r, z),
                &b,
                &mut x,
                k == 0,
                &mut sweep,
            );
        }
        let error = x
            .iter()
            .zip(&e)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        let bound = (4.0f64 * (31.0f64 / 29.0).powi(3) - 3.0 * 31.0 / 29.0).powi(-3);
        assert!(error < 1.05 * bound * (n as f64).sqrt(), "{error} {bound}");
    }
}
