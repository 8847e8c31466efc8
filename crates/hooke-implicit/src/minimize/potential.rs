//! The terms of the incremental potential `Φ` per particle and per spring,
//! which the assembly's `Φ` and the quasi-Newton step's `Φ` with its
//! gradient both sum.

use hooke_core::{Spring, System, Vec3};

use crate::linear::vector::sum2;

/// The particles' terms of `Φ` at positions `x` and velocities `v`,
/// `Σ ½ mᵢ|vᵢ − ṽᵢ|² − mᵢ g·xᵢ + ½βh γ |vᵢ|²`, and the sum of their
/// magnitudes.
pub(crate) fn particles_potential(
    system: &System,
    x: &[Vec3],
    v: &[Vec3],
    v_tilde: &[Vec3],
    beta_h: f64,
) -> (f64, f64) {
    let masses = system.masses();
    let g = system.gravity().unwrap_or_else(Vec3::zeros);
    let gamma = system.air_damping().unwrap_or(0.0);
    sum2(x.len(), |i| {
        let m = masses[i];
        let inertia = 0.5 * m * (v[i] - v_tilde[i]).norm_squared();
        let gravitational = -m * g.dot(&x[i]);
        let air = 0.5 * beta_h * gamma * v[i].norm_squared();
        (
            inertia + gravitational + air,
            inertia + gravitational.abs() + air,
        )
    })
}

/// A spring's terms of `Φ` with its ends at `(xᵢ, xⱼ)`, stretched by
/// `l − L` and its ends parting at the rate `d·(vᵢ − vⱼ)` along the
/// frozen damping direction: `½k(l − L)² + ½βh c (d·(vᵢ − vⱼ))²`, and that
/// plus `k |l − L| (|xᵢ| + |xⱼ|)`, the energy the rounding of its ends'
/// coordinates puts into it (divided by ε).
#[inline]
pub(crate) fn spring_potential(
    s: &Spring,
    (xi, xj): (Vec3, Vec3),
    stretch: f64,
    rate: f64,
    beta_h: f64,
) -> (f64, f64) {
    let mut e = 0.5 * s.stiffness * stretch * stretch;
    if s.damping > 0.0 {
        e += 0.5 * beta_h * s.damping * rate * rate;
    }
    let rounding = s.stiffness * stretch.abs() * (xi.amax() + xj.amax());
    (e, e + rounding)
}
