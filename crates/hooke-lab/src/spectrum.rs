//! The largest natural frequency of a system, `ω_max`, which sets every
//! explicit method's step limit `h < θ_limit / ω_max`.
//!
//! Linearised about the initial state and without damping, the free
//! particles obey `M u'' = −K u`, with `K` the stiffness matrix
//! `Σ_s [[H_s, −H_s], [−H_s, H_s]]` (pinned particles' rows and columns
//! removed, compressed springs' transverse stiffness clamped at zero as in
//! the implicit solver), plus each volume element's Hessian at the initial
//! state, `κ V₀ ∇J ∇Jᵀ` at rest. Its natural frequencies are
//! `ω² = eig(M⁻¹K)`.
//! [`omega_max`] finds the largest by power iteration on the symmetric
//! matrix `M^(−1/2) K M^(−1/2)` (same eigenvalues): the Rayleigh quotient of
//! the iterate rises monotonically to `ω_max²` from below. It stops when the
//! quotient changes by less than a relative `10⁻¹⁰` between iterations or
//! after [`MAX_ITERATIONS`], and also returns the Gershgorin bound
//! (the largest absolute row sum), an upper bound on `ω_max²`, so a caller
//! can see how tight the estimate is.

use hooke_core::{CompressedSprings, Mat12, System, TetHessian, Vec3};

/// The power iteration's cap.
pub const MAX_ITERATIONS: usize = 2000;

/// `ω_max` and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spectrum {
    /// The estimate of the largest natural frequency, rad/s (zero for a
    /// system without free particles or springs).
    pub omega_max: f64,
    /// The Gershgorin upper bound on `ω_max`, rad/s.
    pub omega_bound: f64,
    /// Power iterations taken.
    pub iterations: usize,
}

/// `y = M^(−1/2) K M^(−1/2) x` on the free particles (`x` and `y` zero on
/// pinned ones).
fn apply(system: &System, blocks: &Blocks, scale: &[f64], x: &[Vec3], y: &mut [Vec3]) {
    y.iter_mut().for_each(|v| *v = Vec3::zeros());
    for (s, h) in system.springs().iter().zip(&blocks.springs) {
        let d = h * (x[s.i] * scale[s.i] - x[s.j] * scale[s.j]);
        y[s.i] += d * scale[s.i];
        y[s.j] -= d * scale[s.j];
    }
    for (t, h) in system.tets().iter().zip(&blocks.tets) {
        for (a, &i) in t.vertices.iter().enumerate() {
            for (b, &j) in t.vertices.iter().enumerate() {
                y[i] += scale[i] * (h.fixed_view::<3, 3>(3 * a, 3 * b) * x[j]) * scale[j];
            }
        }
    }
}

/// The springs' stiffness blocks and the volume elements' Hessians at the
/// initial state.
struct Blocks {
    springs: Vec<hooke_core::Mat3>,
    tets: Vec<Mat12>,
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
    let n = system.particle_count();
    let x0 = system.initial_positions();
    let blocks = Blocks {
        springs: system
            .springs()
            .iter()
            .map(|s| s.stiffness_block(x0[s.i], x0[s.j], CompressedSprings::Clamped))
            .collect(),
        tets: system
            .tets()
            .iter()
            .map(|t| t.derivatives(x0, TetHessian::Projected).hessian)
            .collect(),
    };
    // M^(−1/2), zero on pinned particles so that they drop out.
    let scale: Vec<f64> = system.inverse_masses().iter().map(|&w| w.sqrt()).collect();

    let mut row_sums = vec![0.0; 3 * n];
    for (s, h) in system.springs().iter().zip(&blocks.springs) {
        for r in 0..3 {
            let row: f64 = (0..3).map(|c| h[(r, c)].abs()).sum();
            let (a, b) = (scale[s.i], scale[s.j]);
            row_sums[3 * s.i + r] += row * a * (a + b);
            row_sums[3 * s.j + r] += row * b * (a + b);
        }
    }
    for (t, h) in system.tets().iter().zip(&blocks.tets) {
        for (a, &i) in t.vertices.iter().enumerate() {
            for r in 0..3 {
                row_sums[3 * i + r] += (0..12)
                    .map(|c| h[(3 * a + r, c)].abs() * scale[i] * scale[t.vertices[c / 3]])
                    .sum::<f64>();
            }
        }
    }
    let bound = row_sums.iter().copied().fold(0.0, f64::max);

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
    let mut y = vec![Vec3::zeros(); n];
    let mut rayleigh = 0.0;
    let mut iterations = 0;
    for iteration in 1..=MAX_ITERATIONS {
        let norm = x.iter().map(Vec3::norm_squared).sum::<f64>().sqrt();
        if norm == 0.0 || !norm.is_finite() {
            break;
        }
        x.iter_mut().for_each(|v| *v /= norm);
        apply(system, &blocks, &scale, &x, &mut y);
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
