//! Additive continuous collision detection (ACCD: Li, Kaufman & Jiang,
//! *Codimensional Incremental Potential Contact*, SIGGRAPH 2021, §4 and
//! Algorithm 1): the largest conservative step along a line search direction
//! that keeps a pair of primitives apart.
//!
//! The four points move on straight lines `xₖ(τ) = xₖ + τ Δxₖ`, `τ ∈ [0, 1]`.
//! Subtracting the mean displacement (distances are translation invariant),
//! the gap `g(τ) = d(τ) − ξ` changes at most at the rate
//!
//! ```text
//! l_p = max_{k ∈ first} |Δxₖ| + max_{k ∈ second} |Δxₖ|,
//! ```
//!
//! since a closest point is a convex combination of its primitive's vertices.
//! So from a time `τ` with gap `g` the pair cannot touch before `τ + g/l_p`.
//! ACCD advances by `τ_l = (1 − s) g₀/l_p` first, then by `τ_l = 0.9 g/l_p`
//! from the gap `g` just measured, and stops (returning the last accepted `τ`)
//! as soon as the gap would fall below `s g₀`: the line search then never
//! brings a pair closer than the fraction `s` (`keep`) of its starting gap,
//! and the returned `τ` is conservative by construction (every step is at most
//! 90 % of the time to contact). The gap is evaluated as
//! `(d² − ξ²)/(d + ξ)`, from the squared distances of
//! [`distance`](super::distance).
//!
//! Here a pair whose first step already covers the motion,
//! `(1 − s) g₀ ≥ l_p`, returns `τ = 1` without a second distance; the last
//! step is clamped to end at `τ = 1` (the motion is never
//! extrapolated past the step), each position is recomputed from `xₖ + τ Δxₖ`
//! (no drift), and the loop stops after 10⁶ steps with the `τ` reached (still
//! conservative; a pair needs that many only when it starts very close and
//! moves fast relative to its gap).

use super::distance::{edge_edge_squared_distance, point_triangle_squared_distance};
use crate::Vec3;

/// The cap on ACCD's steps.
const MAX_ITERATIONS: usize = 1_000_000;

/// The largest `τ ∈ [0, 1]` found by ACCD (conservative) such that the gap
/// `d − ξ` of point `x[0]` and triangle `(x[1], x[2], x[3])` stays positive on
/// `[0, τ]` and, unless `τ = 1`, the gap at `τ` is at least `s (d₀ − ξ)`, `d₀`
/// the distance at `τ = 0`, `s = keep ∈ (0, 1)` (e.g. `0.1`). Returns `1.0`
/// when the pair never comes that close during the step, `0.0` when it starts
/// at a gap `≤ 0`.
///
/// `l_p = |Δp| + max(|Δa|, |Δb|, |Δc|)` after subtracting the mean
/// displacement (module docs).
#[must_use]
pub fn point_triangle_ccd(x: [Vec3; 4], dx: [Vec3; 4], thickness: f64, keep: f64) -> f64 {
    accd(&x, &dx, 1, thickness, keep, |y| {
        point_triangle_squared_distance(y[0], y[1], y[2], y[3])
    })
}

/// The largest `τ ∈ [0, 1]` found by ACCD (conservative) such that the gap
/// `d − ξ` of edges `(x[0], x[1])` and `(x[2], x[3])` stays positive on
/// `[0, τ]` and, unless `τ = 1`, the gap at `τ` is at least `s (d₀ − ξ)`, `d₀`
/// the distance at `τ = 0`, `s = keep ∈ (0, 1)` (e.g. `0.1`). Returns `1.0`
/// when the pair never comes that close during the step, `0.0` when it starts
/// at a gap `≤ 0`.
///
/// `l_p = max(|Δa₀|, |Δa₁|) + max(|Δb₀|, |Δb₁|)` after subtracting the mean
/// displacement (module docs).
#[must_use]
pub fn edge_edge_ccd(x: [Vec3; 4], dx: [Vec3; 4], thickness: f64, keep: f64) -> f64 {
    accd(&x, &dx, 2, thickness, keep, |y| {
        edge_edge_squared_distance(y[0], y[1], y[2], y[3])
    })
}

/// `d − ξ` as `(d² − ξ²)/(d + ξ)`.
fn gap(squared: f64, thickness: f64) -> f64 {
    let sum = squared.sqrt() + thickness;
    if sum > 0.0 {
        (squared - thickness * thickness) / sum
    } else {
        0.0
    }
}

/// ACCD (Algorithm 1 of Li, Kaufman & Jiang 2021) for a pair whose first
/// primitive is points `0..split`.
fn accd(
    x: &[Vec3; 4],
    dx: &[Vec3; 4],
    split: usize,
    thickness: f64,
    keep: f64,
    squared: impl Fn(&[Vec3; 4]) -> f64,
) -> f64 {
    let gap_at = |tau: f64| {
        let y: [Vec3; 4] = std::array::from_fn(|k| x[k] + dx[k] * tau);
        gap(squared(&y), thickness)
    };
    let gap0 = gap_at(0.0);
    if gap0.is_nan() || gap0 <= 0.0 {
        return 0.0;
    }
    let mean = (dx[0] + dx[1] + dx[2] + dx[3]) / 4.0;
    let largest = |range: std::ops::Range<usize>| {
        range.map(|k| (dx[k] - mean).norm()).fold(0.0_f64, f64::max)
    };
    let lp = largest(0..split) + largest(split..4);
    if lp.is_nan() {
        return 0.0;
    }
    if lp <= 0.0 {
        return 1.0;
    }
    let target = keep * gap0;
    let mut tau = 0.0;
    let mut step = (1.0 - keep) * gap0 / lp;
    // The whole motion in the first step: the gap stays above
    // `gap0 − lp ≥ keep gap0` throughout.
    if step >= 1.0 {
        return 1.0;
    }
    for _ in 0..MAX_ITERATIONS {
        let next = (tau + step).min(1.0);
        let g = gap_at(next);
        // The first step cannot fall below the target but by rounding.
        if g <= 0.0 || (tau > 0.0 && g < target) {
            return tau;
        }
        if next >= 1.0 {
            return 1.0;
        }
        tau = next;
        step = 0.9 * g / lp;
    }
    tau
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::distance::tests::Rng;
    use crate::collision::distance::{edge_edge_closest, point_triangle_closest};

    const KEEP: f64 = 0.1;

    fn gap_of(x: &[Vec3; 4], dx: &[Vec3; 4], tau: f64, xi: f64, triangle: bool) -> f64 {
        let y: [Vec3; 4] = std::array::from_fn(|k| x[k] + dx[k] * tau);
        let squared = if triangle {
            point_triangle_closest(y[0], y[1], y[2], y[3]).squared
        } else {
            edge_edge_closest(y[0], y[1], y[2], y[3]).squared
        };
        squared.sqrt() - xi
    }

    fn ccd(x: [Vec3; 4], dx: [Vec3; 4], xi: f64, triangle: bool) -> f64 {
        if triangle {
            point_triangle_ccd(x, dx, xi, KEEP)
        } else {
            edge_edge_ccd(x, dx, xi, KEEP)
        }
    }

    /// `τ ∈ [0, 1]`, the gap positive on a dense sampling of `[0, τ]`, and at
    /// least `s g₀` at `τ` unless `τ = 1`.
    fn check_conservative(x: [Vec3; 4], dx: [Vec3; 4], xi: f64, triangle: bool) -> f64 {
        let tau = ccd(x, dx, xi, triangle);
        assert!((0.0..=1.0).contains(&tau));
        let g0 = gap_of(&x, &dx, 0.0, xi, triangle);
        for i in 0..=2000 {
            let t = tau * f64::from(i) / 2000.0;
            assert!(
                gap_of(&x, &dx, t, xi, triangle) > 0.0,
                "contact at {t} ≤ {tau}"
            );
        }
        if tau < 1.0 {
            let g = gap_of(&x, &dx, tau, xi, triangle);
            assert!(g >= KEEP * g0 * (1.0 - 1e-9), "gap {g} < {KEEP} × {g0}");
        }
        tau
    }

    /// A rigid motion, so that the cases are not axis-aligned.
    fn place(x: [Vec3; 4], dx: [Vec3; 4]) -> ([Vec3; 4], [Vec3; 4]) {
        let q = nalgebra::Rotation3::from_scaled_axis(Vec3::new(0.4, -0.9, 1.3));
        let shift = Vec3::new(0.3, -2.0, 0.7);
        (x.map(|p| q * p + shift), dx.map(|v| q * v))
    }

    fn triangle_at_origin() -> [Vec3; 3] {
        [Vec3::zeros(), Vec3::x(), Vec3::y()]
    }

    #[test]
    fn point_tunnelling_through_a_triangle_stops_above_it() {
        let [a, b, c] = triangle_at_origin();
        // From 1 cm above to 1 m below within one step.
        let (x, dx) = place(
            [Vec3::new(0.2, 0.2, 0.01), a, b, c],
            [
                Vec3::new(0.0, 0.0, -1.01),
                Vec3::zeros(),
                Vec3::zeros(),
                Vec3::zeros(),
            ],
        );
        let tau = check_conservative(x, dx, 0.0, true);
        let crossing = 0.01 / 1.01;
        assert!(
            tau > 0.5 * crossing && tau < crossing,
            "{tau} vs {crossing}"
        );
    }

    #[test]
    fn head_on_approach_with_thickness_is_not_too_conservative() {
        let [a, b, c] = triangle_at_origin();
        let up = Vec3::new(0.0, 0.0, 0.5);
        let (xi, h) = (1e-3, 0.01);
        let (x, dx) = place(
            [Vec3::new(0.3, 0.3, h), a, b, c],
            [Vec3::new(0.0, 0.0, -1.0), up, up, up],
        );
        let tau = check_conservative(x, dx, xi, true);
        // The gap h − ξ closes at relative speed 1.5.
        let contact = (h - xi) / 1.5;
        assert!(tau > 0.5 * contact && tau < contact, "{tau} vs {contact}");
    }

    #[test]
    fn edges_crossing_at_high_speed_stop_before_contact() {
        let down = Vec3::new(0.0, 0.0, -2.0);
        for xi in [0.0, 1e-3] {
            let (x, dx) = place(
                [
                    Vec3::new(-1.0, 0.0, 0.01),
                    Vec3::new(1.0, 0.0, 0.01),
                    Vec3::new(0.0, -1.0, 0.0),
                    Vec3::new(0.0, 1.0, 0.0),
                ],
                [down, down, Vec3::zeros(), Vec3::zeros()],
            );
            let tau = check_conservative(x, dx, xi, false);
            let contact = (0.01 - xi) / 2.0;
            assert!(tau > 0.5 * contact && tau < contact, "{tau} vs {contact}");
        }
    }

    #[test]
    fn separating_parallel_and_still_pairs_return_one() {
        let [a, b, c] = triangle_at_origin();
        let zero = Vec3::zeros();
        let x = [Vec3::new(0.2, 0.2, 0.01), a, b, c];
        let away = [Vec3::new(0.0, 0.0, 1.0), zero, zero, zero];
        let along = [Vec3::new(0.5, 0.0, 0.0), zero, zero, zero];
        let together = [Vec3::new(0.3, -0.1, 2.0); 4];
        for dx in [away, along, together, [zero; 4]] {
            let (x, dx) = place(x, dx);
            assert!(point_triangle_ccd(x, dx, 1e-3, KEEP) >= 1.0);
        }
        let e = [
            Vec3::zeros(),
            Vec3::x(),
            Vec3::new(0.0, 0.0, 0.05),
            Vec3::new(1.0, 0.0, 0.05),
        ];
        let slide = Vec3::new(3.0, 0.0, 0.0);
        let lift = Vec3::new(0.0, 0.0, 1.0);
        for dx in [[zero, zero, slide, slide], [zero, zero, lift, lift]] {
            let (x, dx) = place(e, dx);
            assert!(edge_edge_ccd(x, dx, 0.0, KEEP) >= 1.0);
        }
    }

    #[test]
    fn pairs_starting_in_contact_return_zero() {
        let [a, b, c] = triangle_at_origin();
        let x = [Vec3::new(0.2, 0.2, 0.0005), a, b, c];
        let dx = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::zeros(),
            Vec3::zeros(),
            Vec3::zeros(),
        ];
        assert!(point_triangle_ccd(x, dx, 1e-3, KEEP) <= 0.0);
        let x = [
            Vec3::zeros(),
            Vec3::x(),
            Vec3::new(0.5, -1.0, 0.0),
            Vec3::new(0.5, 1.0, 0.0),
        ];
        assert!(edge_edge_ccd(x, [Vec3::zeros(); 4], 0.0, KEEP) <= 0.0);
    }

    #[test]
    fn returned_step_is_conservative_on_random_motions() {
        let mut rng = Rng::new(21);
        let mut stopped = 0;
        for i in 0..200 {
            let triangle = i % 2 == 0;
            let x: [Vec3; 4] = std::array::from_fn(|_| rng.vec3(1.0));
            let dx: [Vec3; 4] = std::array::from_fn(|_| rng.vec3(2.0));
            let xi = if i % 4 < 2 { 0.0 } else { 0.01 };
            if gap_of(&x, &dx, 0.0, xi, triangle) <= 0.0 {
                continue;
            }
            if check_conservative(x, dx, xi, triangle) < 1.0 {
                stopped += 1;
            }
        }
        assert!(stopped > 20, "only {stopped} motions came close");
    }
}
