//! The spring's force, stiffness block and damping block checked against
//! finite differences of its energy and force, over random springs that are
//! stretched, compressed, or nearly collapsed.

use hooke::core::{CompressedSprings, Mat3, Spring, Vec3};
use proptest::prelude::*;

/// A spring whose current length is `ratio` times its rest length, in a random
/// direction, at a random place.
fn configuration(ratio: impl Strategy<Value = f64>) -> impl Strategy<Value = (Spring, Vec3, Vec3)> {
    (
        1e-2..1e4f64,
        0.1..10.0f64,
        0.0..5.0f64,
        ratio,
        (-1.0..1.0f64, 0.0..std::f64::consts::TAU),
        prop::array::uniform3(-10.0..10.0f64),
    )
        .prop_map(
            |(stiffness, rest_length, damping, ratio, (cos_polar, azimuth), xj)| {
                let sin_polar = (1.0 - cos_polar * cos_polar).sqrt();
                let d = Vec3::new(
                    sin_polar * azimuth.cos(),
                    sin_polar * azimuth.sin(),
                    cos_polar,
                );
                let xj = Vec3::from(xj);
                let spring = Spring {
                    i: 0,
                    j: 1,
                    stiffness,
                    rest_length,
                    damping,
                };
                (spring, xj + ratio * rest_length * d, xj)
            },
        )
}

fn any_configuration() -> impl Strategy<Value = (Spring, Vec3, Vec3)> {
    prop_oneof![
        configuration(1.0..3.0f64),   // stretched
        configuration(0.05..1.0f64),  // compressed
        configuration(1e-4..1e-2f64), // nearly collapsed
    ]
}

/// The relative error a central difference with step `eps` inherits from
/// the rounding of coordinates as large as those of `xi` and `xj`: each
/// shifted point is off by up to an ulp of its coordinates, a fraction
/// `ε |x| / eps` of the step. A nearly collapsed spring far from the origin
/// (a length of 10⁻⁵ at coordinates near 10) takes steps of 10⁻¹⁰, where
/// this reaches 2·10⁻⁵.
fn rounding(xi: Vec3, xj: Vec3, eps: f64) -> f64 {
    2.0 * f64::EPSILON * xi.amax().max(xj.amax()) / eps
}

/// Central difference of `g` at `x` along each axis with step `eps`, as the
/// columns of a matrix (for a vector `g`) — the Jacobian.
fn jacobian(g: impl Fn(Vec3) -> Vec3, x: Vec3, eps: f64) -> Mat3 {
    Mat3::from_columns(&[0, 1, 2].map(|c| {
        let e = Vec3::ith(c, eps);
        (g(x + e) - g(x - e)) / (2.0 * eps)
    }))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// `fᵢ = −∂E/∂xᵢ` and `fⱼ = −fᵢ`.
    #[test]
    fn force_is_minus_energy_gradient((s, xi, xj) in any_configuration()) {
        let l = (xi - xj).norm();
        let eps = 1e-4 * l;
        let gradient = Vec3::from_fn(|c, _| {
            let e = Vec3::ith(c, eps);
            (s.energy(xi + e, xj) - s.energy(xi - e, xj)) / (2.0 * eps)
        });
        let force = s.elastic_force(xi, xj);
        let scale = s.stiffness * s.rest_length.max(l);
        let tolerance = (1e-6 + rounding(xi, xj, eps)) * scale;
        prop_assert!((force + gradient).norm() <= tolerance, "force {force:?}, −∇E {:?}", -gradient);
        let on_j = -s.elastic_force(xj, xi);
        prop_assert!((force - on_j).norm() <= 1e-12 * scale);
    }

    /// With the exact Jacobian, `∂fᵢ/∂xᵢ = −H` and `∂fᵢ/∂xⱼ = H`.
    #[test]
    fn stiffness_block_is_the_force_jacobian((s, xi, xj) in any_configuration()) {
        let h = s.stiffness_block(xi, xj, CompressedSprings::Exact);
        let eps = 1e-5 * (xi - xj).norm();
        let d_xi = jacobian(|x| s.elastic_force(x, xj), xi, eps);
        let d_xj = jacobian(|x| s.elastic_force(xi, x), xj, eps);
        let tolerance = (1e-6 + rounding(xi, xj, eps)) * h.norm() + 1e-9 * s.stiffness;
        prop_assert!((d_xi + h).norm() <= tolerance, "H = {h}, −∂f/∂xi = {}", -d_xi);
        prop_assert!((d_xj - h).norm() <= tolerance, "H = {h}, ∂f/∂xj = {d_xj}");
    }

    /// `∂fᵢ/∂vᵢ = −c d dᵀ`; the damping force is linear in velocity.
    #[test]
    fn damping_block_is_the_velocity_jacobian(
        (s, xi, xj) in any_configuration(),
        vi in prop::array::uniform3(-5.0..5.0f64),
        vj in prop::array::uniform3(-5.0..5.0f64),
    ) {
        let (vi, vj) = (Vec3::from(vi), Vec3::from(vj));
        let d = s.damping_block(xi, xj);
        let d_vi = jacobian(|v| s.damping_force(xi, xj, v, vj), vi, 1e-3);
        prop_assert!((d_vi + d).norm() <= 1e-9 * (1.0 + d.norm()), "D = {d}, −∂f/∂vi = {}", -d_vi);
        let total = s.force(xi, xj, vi, vj);
        let parts = s.elastic_force(xi, xj) + s.damping_force(xi, xj, vi, vj);
        prop_assert!((total - parts).norm() <= 1e-12 * (1.0 + parts.norm()));
        let dissipated = s.dissipation_power(xi, xj, vi, vj);
        let rate = -s.damping_force(xi, xj, vi, vj).dot(&(vi - vj));
        prop_assert!((dissipated - rate).abs() <= 1e-12 * (1.0 + rate.abs()) && dissipated >= 0.0);
    }

    /// The clamped block is symmetric positive semi-definite everywhere and
    /// equals the exact one wherever the spring is not compressed.
    #[test]
    fn clamped_block_is_symmetric_positive_semidefinite((s, xi, xj) in any_configuration()) {
        let clamped = s.stiffness_block(xi, xj, CompressedSprings::Clamped);
        prop_assert!((clamped - clamped.transpose()).norm() <= 1e-12 * clamped.norm());
        let smallest = clamped.symmetric_eigenvalues().min();
        prop_assert!(smallest >= -1e-12 * s.stiffness, "smallest eigenvalue {smallest}");
        if (xi - xj).norm() >= s.rest_length {
            let exact = s.stiffness_block(xi, xj, CompressedSprings::Exact);
            prop_assert!((clamped - exact).norm() <= 1e-12 * exact.norm());
        }
    }
}
