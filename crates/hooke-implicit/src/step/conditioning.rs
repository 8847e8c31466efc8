//! How large a step the linear systems can take before rounding erases the
//! mass matrix from them.
//!
//! The matrix of a step, `A = M + βh C + β²h² K`, has condition number
//! relative to `M` of at most `κ(h) = 1 + βh ζ + β²h² ω²`, with `ω²` and `ζ`
//! the block-Gershgorin bounds on `M^(−1/2) K M^(−1/2)` and
//! `M^(−1/2) C M^(−1/2)`:
//!
//! ```text
//! ω² ≤ maxᵢ Σ_{s ∋ i} k_s wᵢ (wᵢ + wⱼ),   ζ ≤ maxᵢ [γ wᵢ² + Σ_{s ∋ i} c_s wᵢ (wᵢ + wⱼ)],
//! ```
//!
//! `wᵢ = 1/√mᵢ` (zero for pinned particles), valid in every state because a
//! spring's clamped stiffness block has norm at most `k`. Each term of the
//! step's potential adds its rates so ([`Term::rates`](hooke_core::Term::rates)):
//! a volume element its Hessian at rest, `κ V₀ ∇J ∇Jᵀ`, as
//! `wₐ Σ_b κ V₀ |∇ₐJ| |∇_bJ| w_b` at each vertex `a` (its Hessian grows
//! with the deformation, so this one holds near rest only). A solve with
//! `κ(h) ≫ 1/ε` cannot see the inertia of the stiff system's soft modes (at
//! 10¹² N/m, 0.1 mg particles and 1 s steps, `κ ≈ 10¹⁷`): its Newton steps
//! carry rounding errors as large as the motion. Steps are therefore cut
//! into substeps no longer than the `h` at which `κ(h)` reaches
//! [`Implicit::MAX_CONDITION`](crate::Implicit::MAX_CONDITION).

use hooke_core::System;

use crate::minimize::terms::Terms;

/// The longest substep of the last system stepped, kept until the system
/// changes.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub(crate) struct LongestStep {
    /// The system's id and its longest step.
    cached: Option<(u64, f64)>,
}

impl LongestStep {
    /// The longest step of `system`, whose terms are `terms`, at which
    /// `κ(h)` reaches `condition` (see [`Rates::longest_step`]).
    pub(crate) fn get(&mut self, system: &System, terms: &Terms, condition: f64) -> f64 {
        match self.cached {
            Some((id, longest)) if id == system.id() => longest,
            _ => {
                let longest = Rates::new(system, terms).longest_step(condition);
                self.cached = Some((system.id(), longest));
                longest
            }
        }
    }
}

/// The bounds `ω²` (1/s²) and `ζ` (1/s) of `system`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rates {
    stiffness: f64,
    damping: f64,
}

impl Rates {
    /// The bounds of `system`, whose terms are `terms` (see the module
    /// docs).
    pub(crate) fn new(system: &System, terms: &Terms) -> Self {
        let w: Vec<f64> = system.inverse_masses().iter().map(|v| v.sqrt()).collect();
        let (mut stiffness, mut damping) = (vec![0.0; w.len()], vec![0.0; w.len()]);
        for t in terms.iter() {
            t.rates(system, &w, &mut stiffness, &mut damping);
        }
        Self {
            stiffness: stiffness.into_iter().fold(0.0, f64::max),
            damping: damping.into_iter().fold(0.0, f64::max),
        }
    }

    /// The longest step `h` with `h ζ + h² ω² ≤ κ − 1` (`β ≤ 1`), infinite
    /// for a system without springs or damping.
    pub(crate) fn longest_step(&self, condition: f64) -> f64 {
        let (w2, z, c) = (self.stiffness, self.damping, condition - 1.0);
        if w2 > 0.0 {
            2.0 * c / (z + (z * z + 4.0 * w2 * c).sqrt())
        } else if z > 0.0 {
            c / z
        } else {
            f64::INFINITY
        }
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use hooke_core::reference::Oscillator;

    use super::*;

    /// The bounds of `system`'s terms.
    fn rates(system: &System) -> Rates {
        Rates::new(system, &Terms::new(system).unwrap())
    }

    #[test]
    fn an_oscillator_reaches_the_condition_at_its_frequency() {
        // One free mass m on a spring k to a pin: M⁻¹K = k/m = ω², and the
        // bound is exact, so h²ω² = κ − 1 at the longest step.
        let system = Oscillator::undamped(2.0, 8.0).system().unwrap();
        let rates = rates(&system);
        let h = rates.longest_step(1e6 + 1.0);
        assert_relative_eq!(h * h * 4.0, 1e6, max_relative = 1e-12);
    }

    #[test]
    fn damping_shortens_the_longest_step() {
        let undamped = rates(&Oscillator::undamped(2.0, 8.0).system().unwrap());
        let damped = rates(&Oscillator::damped(2.0, 8.0, 3.0).system().unwrap());
        let (a, b) = (undamped.longest_step(1e8), damped.longest_step(1e8));
        assert!(b < a);
        // h ζ + h² ω² = κ − 1 holds at the damped longest step.
        assert_relative_eq!(b * 1.5 + b * b * 4.0, 1e8 - 1.0, max_relative = 1e-12);
    }
}
