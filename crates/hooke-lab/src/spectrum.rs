//! The largest natural frequency of a system, `ω_max`, which sets every
//! explicit method's step limit `h < θ_limit / ω_max`.
//!
//! Linearised about the initial state and without damping, the free
//! particles obey `M u'' = −K u`, with `K` the sum of the stiffness of the
//! system's terms ([`Term::stiffness`](hooke_core::Term::stiffness): each
//! spring's `[[H_s, −H_s], [−H_s, H_s]]`, compressed springs' transverse
//! stiffness clamped at zero as in the implicit solver, and each volume
//! element's projected Hessian, `κ V₀ ∇J ∇Jᵀ` at rest), pinned particles'
//! rows and columns removed. Its natural frequencies are `ω² = eig(M⁻¹K)`.
//! [`omega_max`] finds the largest by power iteration on the symmetric
//! matrix `M^(−1/2) K M^(−1/2)` (same eigenvalues): the Rayleigh quotient
//! of the iterate rises monotonically to `ω_max²` from below. It stops when
//! the quotient changes by less than a relative `10⁻¹⁰` between iterations
//! or after [`MAX_ITERATIONS`], and also returns the Gershgorin bound (the
//! largest absolute row sum), an upper bound on `ω_max²`, so a caller can
//! see how tight the estimate is.

use hooke_core::term::Blocks;
use hooke_core::{Mat3, System, Vec3};
use hooke_implicit::Terms;

/// The power iteration's cap.
pub const MAX_ITERATIONS: usize = 2000;

/// `ω_max` and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spectrum {
    /// The estimate of the largest natural frequency, rad/s (zero for a
    /// system without free particles or stiffness; not a number for one
    /// too large for the implicit step's 32-bit indices).
    pub omega_max: f64,
    /// The Gershgorin upper bound on `ω_max`, rad/s.
    pub omega_bound: f64,
    /// Power iterations taken.
    pub iterations: usize,
}

/// The largest absolute row sum of `M^(−1/2) K M^(−1/2)`, `scale` holding
/// `M^(−1/2)`.
fn gershgorin(k: &Blocks, scale: &[f64]) -> f64 {
    let row_sum = |b: &Mat3, r: usize| (0..3).map(|c| b[(r, c)].abs()).sum::<f64>();
    let mut sums: Vec<[f64; 3]> = k
        .rows
        .iter()
        .zip(scale)
        .map(|(row, s)| std::array::from_fn(|r| row_sum(&row.to_mat3(), r) * s * s))
        .collect();
    for &(i, j, block) in &k.pairs {
        let weight = scale[i] * scale[j];
        for (at, block) in [(i, block), (j, block.transpose())] {
            for (r, sum) in sums[at].iter_mut().enumerate() {
                *sum += row_sum(&block, r) * weight;
            }
        }
    }
    sums.iter().flatten().copied().fold(0.0, f64::max)
}

/// The largest natural frequency of `system` at its initial state (see
/// the module docs).
///
/// ```
/// use hooke_core::reference::Oscillator;
/// // One free particle of mass 2 on a spring of stiffness 8: ω = 2 rad/s.
/// let system = Oscillator::undamped(2.0, 8.0).system()?;
/// let spectrum = hooke_lab::omega_max(&system);
/// assert!((spectrum.omega_max - 2.0).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[must_use]
pub fn omega_max(system: &System) -> Spectrum {
    let Ok(terms) = Terms::new(system) else {
        return Spectrum {
            omega_max: f64::NAN,
            omega_bound: f64::NAN,
            iterations: 0,
        };
    };
    let n = system.particle_count();
    let mut k = Blocks::new(n);
    for term in terms.iter() {
        term.stiffness(system, system.initial_positions(), &mut k);
    }
    // M^(−1/2), zero on pinned particles so that they drop out.
    let scale: Vec<f64> = system.inverse_masses().iter().map(|&w| w.sqrt()).collect();
    let bound = gershgorin(&k, &scale);

    // A start with a component along every mode that has one: a fixed,
    // irregular vector on the free particles.
    let mut x: Vec<Vec3> = (0..n)
        .map(|i| {
            let k = i as f64;
            Vec3::new(
                1.0 + (0.7 * k).sin(),
                1.0 + (1.3 * k + 0.5).cos(),
                1.0 + (2.1 * k + 1.0).sin(),
            ) * f64::from(u8::from(scale[i] > 0.0))
        })
        .collect();
    let (mut scaled, mut y) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
    let mut rayleigh = 0.0;
    let mut iterations = 0;
    for iteration in 1..=MAX_ITERATIONS {
        let norm = x.iter().map(Vec3::norm_squared).sum::<f64>().sqrt();
        if norm == 0.0 || !norm.is_finite() {
            break;
        }
        x.iter_mut().for_each(|v| *v /= norm);
        // y = M^(−1/2) K M^(−1/2) x.
        for ((s, xi), w) in scaled.iter_mut().zip(&x).zip(&scale) {
            *s = *w * xi;
        }
        k.apply(&scaled, &mut y);
        for (yi, w) in y.iter_mut().zip(&scale) {
            *yi *= *w;
        }
        let next: f64 = x.iter().zip(&y).map(|(a, b)| a.dot(b)).sum();
        iterations = iteration;
        let converged = (next - rayleigh).abs() <= 1e-10 * next.abs();
        rayleigh = next;
        std::mem::swap(&mut x, &mut y);
        if converged {
            break;
        }
    }
    Spectrum {
        omega_max: rayleigh.max(0.0).sqrt(),
        omega_bound: bound.sqrt(),
        iterations,
    }
}

#[cfg(test)]
mod tests {
    use hooke_core::reference::{Chain, Sheet};

    use super::*;

    /// `n` free masses `m` between two pinned ends, springs `k` along x:
    /// the largest axial frequency is `2√(k/m) sin(nπ / 2(n + 1))`
    /// ([`Chain::axial_frequencies`]), below the bound `2√(k/m)`.
    #[test]
    fn a_fixed_fixed_chain_matches_its_closed_form() {
        let (n, m, k) = (12, 0.5, 30.0);
        let chain = Chain::fixed_fixed(n + 2, m, k, 0.1);
        let spectrum = omega_max(&chain.system().unwrap());
        let expected = chain.axial_frequencies().unwrap()[n - 1];
        assert!(
            (spectrum.omega_max - expected).abs() < 1e-6 * expected,
            "{} against {expected}",
            spectrum.omega_max
        );
        assert!(spectrum.omega_bound >= expected);
        assert!(spectrum.omega_bound <= 2.0 * (k / m).sqrt() * (1.0 + 1e-12));
    }

    #[test]
    fn the_estimate_lies_below_the_bound_and_scales_with_root_stiffness() {
        let system = Sheet::new(8).system().unwrap();
        let soft = omega_max(&system);
        let stiff = omega_max(&system.with_stiffness_scale(100.0).unwrap());
        assert!(soft.omega_max > 0.0 && soft.omega_max <= soft.omega_bound);
        assert!((stiff.omega_max / soft.omega_max - 10.0).abs() < 1e-6);
    }
}
