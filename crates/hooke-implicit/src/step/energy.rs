//! The energy test of an implicit step.
//!
//! With `E` the sum of the terms' energies (`hooke_core::term`: the free
//! particles' kinetic energy, gravity's potential, the springs', the
//! volume elements' and the contact barriers' energies —
//!
//! ```text
//! E = Σ_free ½ mᵢ|vᵢ|² − Σ_free mᵢ g·xᵢ + Σ_s ½ k (l − L)² + Σ_t ½ κ V₀ (J − 1)² + κ Σ b(g)
//! ```
//!
//! for the built-in ones), the exact motion obeys `E(t + h) ≤ E(t) + W`,
//! where `W` is the work external agents did on the system through the
//! terms during the step; dampers and friction only remove energy. A step
//! is accepted when
//!
//! ```text
//! E(xₙ₊₁, vₙ₊₁) ≤ E(xₙ, vₙ) + W + 10³ ε |E|,
//! ```
//!
//! with `|E|` the sum of the terms' magnitudes and `ε` the machine epsilon:
//! the rounding of the sums. `W` is estimated by the trapezoid rule for
//! pins, `½(∇ₚV(xₙ) + ∇ₚV(xₙ₊₁))·(xₚ,ₙ₊₁ − xₚ,ₙ)` over the springs and
//! elements at each scripted pin `p`, and as the contact forces times the
//! obstacle's displacement for moving obstacles (the `contact` module); it
//! is zero in the common case of fixed pins and resting obstacles.
//!
//! A converged backward-Euler step changes the energy by
//!
//! ```text
//! E(xₙ₊₁, vₙ₊₁) − E(xₙ, vₙ) = W − ½‖vₙ₊₁ − vₙ‖²_M − D_V(xₙ, xₙ₊₁) − (dissipation),
//! D_V(xₙ, xₙ₊₁) = V(xₙ) − V(xₙ₊₁) − ∇V(xₙ₊₁)·(xₙ − xₙ₊₁),
//! ```
//!
//! and gains energy only where the potential `V` is not convex along the
//! step, `D_V < 0`. For a rolling body pressed onto a floor, the springs and
//! elements are compressed and the straight chord `xₙ₊₁ − xₙ = h vₙ₊₁` of
//! each rotation also stretches them, releasing some of that stress: the
//! gain grows as `h²`, the dissipation as `h`, so that halving the step
//! removes it only at tiny steps. So a gain `ΔE > 0` beyond the allowance
//! above also passes when the free particles' kinetic energy `K` can absorb
//! it, their velocities scaled by `s = √(1 − ΔE/K)`, with a change no
//! larger than the velocity error the Newton iteration's stopping rule
//! accepts (its decrement bounds `‖δ‖_M ≤ λ ≤ η · scale`, `η` the Newton
//! tolerance):
//!
//! ```text
//! (1 − s) ‖v‖_M = (1 − s) √(2K) ≤ η · max(‖vₙ₊₁ − vₙ‖_M, ‖vₙ₊₁‖_M, βh‖g‖√(Σmᵢ)).
//! ```
//!
//! The step is then taken with its velocities so scaled: it gains nothing,
//! and it is as close to the exact step as any converged one.

use hooke_core::{StepStart, System, Vec3, When};

use crate::minimize::objective::velocity_scale;
use crate::minimize::terms::Terms;

/// The energy test of a step: its gain and how the kinetic energy would
/// absorb it (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EnergyTest {
    /// `E(xₙ₊₁, vₙ₊₁) − E(xₙ, vₙ) − W` beyond the rounding; a gain where
    /// positive.
    pub(crate) excess: f64,
    /// Whether the step is held to the test: converged backward-Euler
    /// steps are, BDF2's two-step steps and the linearised step only
    /// report a gain.
    pub(crate) held: bool,
    /// The factor `s` on the free particles' velocities that absorbs a
    /// gain (1 without one).
    pub(crate) factor: f64,
    /// Whether that scaling moves the velocities by no more than the
    /// stopping rule's tolerance of their scale, in a converged step.
    pub(crate) within_tolerance: bool,
}

impl EnergyTest {
    /// Tests the step of `system` from `step` to `(x, v)` by its `terms`'
    /// energies and work; `held` as [`EnergyTest::held`], `converged`
    /// whether the minimisation met the stopping rule with tolerance
    /// `tolerance`.
    pub(crate) fn new(
        (system, terms): (&System, &mut Terms),
        step: &StepStart<'_>,
        (x, v): (&[Vec3], &[Vec3]),
        held: bool,
        (converged, tolerance): (bool, f64),
    ) -> Self {
        let before = terms.energy(system, step.x, step.v, When::Start);
        let after = terms.energy(system, x, v, When::End);
        let work = terms.work(system, step, x, v);
        let excess =
            after.value - before.value - work - rounding(before.magnitude.max(after.magnitude));
        let (factor, within_tolerance) = if excess > 0.0 {
            let (factor, shift) = absorption(system, v, excess);
            let scale = velocity_scale(system, v.iter().copied(), step.v, step.beta_h);
            (factor, converged && shift <= tolerance * scale)
        } else {
            (1.0, false)
        };
        Self {
            excess,
            held,
            factor,
            within_tolerance,
        }
    }

    /// Whether the step fails the test: held to it and gaining energy that
    /// the kinetic energy does not absorb within the tolerance.
    pub(crate) fn fails(&self) -> bool {
        self.held && self.excess > 0.0 && !self.within_tolerance
    }
}

/// The largest gain `E(x₁, v₁) − E(x₀, v₀)` a step may show from rounding.
fn rounding(magnitude: f64) -> f64 {
    1e3 * f64::EPSILON * magnitude
}

/// How the free particles' kinetic energy `K` absorbs a gain `ΔE ≥ 0`: the
/// factor `s = √(max(K − ΔE, 0)/K)` (1 where `K = 0`) that scales their
/// velocities, and how far that moves them in the mass norm,
/// `‖(1 − s) v‖_M = (1 − s)√(2K)` — infinite where `K < ΔE`, which no
/// scaling absorbs.
fn absorption(system: &System, v: &[Vec3], excess: f64) -> (f64, f64) {
    if excess <= 0.0 {
        return (1.0, 0.0);
    }
    let masses = system.masses();
    let kinetic: f64 = (0..v.len())
        .filter(|&i| !system.is_pinned(i))
        .map(|i| 0.5 * masses[i] * v[i].norm_squared())
        .sum();
    if kinetic < excess {
        return (0.0, f64::INFINITY);
    }
    let factor = ((kinetic - excess) / kinetic).sqrt();
    (factor, (1.0 - factor) * (2.0 * kinetic).sqrt())
}
