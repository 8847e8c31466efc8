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
//! the rounding of the sums, nothing more. `W` is estimated by the
//! trapezoid rule for pins, `½(∇ₚV(xₙ) + ∇ₚV(xₙ₊₁))·(xₚ,ₙ₊₁ − xₚ,ₙ)` over the
//! springs and elements at each scripted pin `p`, and as
//! the contact forces times the obstacle's displacement for moving
//! obstacles (the `contact` module, which also adds the barrier's energy to
//! `E`); it is zero in the common case of fixed pins and resting obstacles.

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
    let volume = crate::assembly::volume_energy(system, x).0;
    (value + volume, magnitude + volume)
}

/// The largest gain `E(x₁, v₁) − E(x₀, v₀)` a step may show from rounding.
pub(crate) fn rounding(magnitude: f64) -> f64 {
    1e3 * f64::EPSILON * magnitude
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
