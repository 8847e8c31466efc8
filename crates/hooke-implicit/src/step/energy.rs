//! The energy test of an implicit step: the mechanical energy of the free
//! particles, the springs and the volume elements, and the work external
//! agents did on them.
//!
//! With
//!
//! ```text
//! E = Σ_free ½ mᵢ|vᵢ|² − Σ_free mᵢ g·xᵢ + Σ_s ½ k (l − L)² + Σ_t ½ κ V₀ (J − 1)²
//! ```
//!
//! (gravity and the volume elements are part of the potential), the exact
//! motion obeys `E(t + h) ≤ E(t) + W`,
//! where `W` is the work that scripted pins and moving obstacles did on the
//! system during the step; dampers and friction only remove energy. A
//! step is accepted when
//!
//! ```text
//! E(xₙ₊₁, vₙ₊₁) ≤ E(xₙ, vₙ) + W + 10³ ε |E|,
//! ```
//!
//! with `|E|` the sum of the terms' magnitudes and `ε` the machine epsilon:
//! the rounding of the sums. `W` is estimated by the trapezoid rule for
//! pins, `½(∇ₚV(xₙ) + ∇ₚV(xₙ₊₁))·(xₚ,ₙ₊₁ − xₚ,ₙ)` over the springs and
//! elements at each scripted pin `p`, and as the contact forces times the
//! obstacle's displacement for moving obstacles (the `contact` module,
//! which also adds the barrier's energy to `E`); it is zero in the common
//! case of fixed pins and resting obstacles.
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

use hooke_core::{System, Vec3};

/// The step's energy `E(x, v)` and the sum of its terms' magnitudes.
pub(crate) fn energy(system: &System, x: &[Vec3], v: &[Vec3]) -> (f64, f64) {
    let g = system.gravity().unwrap_or_else(Vec3::zeros);
    let (mut value, mut magnitude) = (0.0, 0.0);
    for (i, &m) in system.masses().iter().enumerate() {
        if system.is_pinned(i) {
            continue;
        }
        let kinetic = 0.5 * m * v[i].norm_squared();
        let gravitational = -m * g.dot(&x[i]);
        value += kinetic + gravitational;
        magnitude += kinetic + gravitational.abs();
    }
    for s in system.springs() {
        let e = s.energy(x[s.i], x[s.j]);
        value += e;
        magnitude += e;
    }
    let volume = crate::minimize::volume::volume_energy(system, x).0;
    (value + volume, magnitude + volume)
}

/// The largest gain `E(x₁, v₁) − E(x₀, v₀)` a step may show from rounding.
pub(crate) fn rounding(magnitude: f64) -> f64 {
    1e3 * f64::EPSILON * magnitude
}

/// How the free particles' kinetic energy `K` absorbs a gain `ΔE ≥ 0`: the
/// factor `s = √(max(K − ΔE, 0)/K)` (1 where `K = 0`) that scales their
/// velocities, and how far that moves them in the mass norm,
/// `‖(1 − s) v‖_M = (1 − s)√(2K)` — infinite where `K < ΔE`, which no
/// scaling absorbs.
pub(crate) fn absorption(system: &System, v: &[Vec3], excess: f64) -> (f64, f64) {
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

/// The work scripted pins did on the system over a step from `x0` to `x1`,
/// by the trapezoid rule on the springs and volume elements attached to
/// them.
pub(crate) fn pin_work(system: &System, x0: &[Vec3], x1: &[Vec3]) -> f64 {
    if system.pin_paths().is_empty() {
        return 0.0;
    }
    let mut work = 0.0;
    for s in system.springs() {
        for (p, q, sign) in [(s.i, s.j, 1.0), (s.j, s.i, -1.0)] {
            if !system.pin_paths().iter().any(|(i, _)| *i == p) {
                continue;
            }
            // ∇ₚV is minus the elastic force on p.
            let (a, b) = if sign > 0.0 { (p, q) } else { (q, p) };
            let f0 = sign * s.elastic_force(x0[a], x0[b]);
            let f1 = sign * s.elastic_force(x1[a], x1[b]);
            work -= 0.5 * (f0 + f1).dot(&(x1[p] - x0[p]));
        }
    }
    for t in system.tets().iter().filter(|t| t.modulus > 0.0) {
        let moving = |&p: &usize| system.pin_paths().iter().any(|(i, _)| *i == p);
        if !t.vertices.iter().any(moving) {
            continue;
        }
        // The elements' forces are minus ∇ₚV.
        let (f0, f1) = (t.forces(x0), t.forces(x1));
        for (a, p) in t.vertices.iter().enumerate() {
            if moving(p) {
                work -= 0.5 * (f0[a] + f1[a]).dot(&(x1[*p] - x0[*p]));
            }
        }
    }
    work
}
