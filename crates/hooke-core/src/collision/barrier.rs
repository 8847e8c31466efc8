//! The log barrier of Incremental Potential Contact (Li et al., *Incremental
//! Potential Contact*, SIGGRAPH 2020, §4) on a pair's gap, and the projection
//! of its Hessian onto the positive semi-definite cone.
//!
//! A pair at distance `d` with thickness `ξ` (Li, Kaufman & Jiang,
//! *Codimensional Incremental Potential Contact*, 2021, §3) has gap
//! `g = d − ξ`; its contact energy is `κ b(g)` with
//!
//! ```text
//! b(g) = −(g − d̂)² ln(g/d̂)   for 0 < g < d̂,      b(g) = 0   for g ≥ d̂,
//! ```
//!
//! `d̂` the activation distance: C² at `d̂` (`b = b' = b'' = 0` there) and
//! `b → ∞` as `g → 0`, so no minimiser of an incremental potential containing
//! it has an intersection. Since `d = √(d²)` and the distance routines of
//! [`distance`](super::distance) return `d²` with its derivatives,
//!
//! ```text
//! ∇g  = ∇d² / (2d),
//! ∇²g = ∇²d² / (2d) − ∇d² ∇d²ᵀ / (4d³),
//! ∇²b = b''(g) ∇g ∇gᵀ + b'(g) ∇²g = (b'' − b'/d) ∇g ∇gᵀ + b'/(2d) ∇²d².
//! ```
//!
//! Newton's method needs a positive semi-definite Hessian; as in IPC each
//! pair's 12×12 Hessian is projected with [`project_positive`] (once, after
//! any mollifier has been applied; on the 9-dimensional complement of the
//! rigid translations, which every pair Hessian annihilates).

use super::distance::Derivatives;
use crate::Mat12;
use nalgebra::{Const, DefaultAllocator, DimDiff, DimSub, SMatrix, U1, allocator::Allocator};

/// IPC's barrier `b(d) = −(d − d̂)² ln(d/d̂)` for `0 < d < d̂`, `0` for
/// `d ≥ d̂`, with its first two derivatives:
///
/// ```text
/// b'(d)  = −2 (d − d̂) ln(d/d̂) − (d − d̂)²/d,
/// b''(d) = −2 ln(d/d̂) − 4 (d − d̂)/d + (d − d̂)²/d².
/// ```
///
/// `b` is C² at `d̂` and goes to `∞` as `d → 0`; `b' ≤ 0 ≤ b''` on `(0, d̂)`.
/// Returns `(b, b', b'')` at `d`; `d ≤ 0` returns `(∞, −∞, ∞)`.
/// `activation` is `d̂ > 0`.
#[must_use]
pub fn barrier(d: f64, activation: f64) -> (f64, f64, f64) {
    if d <= 0.0 {
        return (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    }
    if d >= activation {
        return (0.0, 0.0, 0.0);
    }
    let e = d - activation;
    let l = (d / activation).ln();
    (
        -e * e * l,
        -2.0 * e * l - e * e / d,
        -2.0 * l - 4.0 * e / d + e * e / (d * d),
    )
}

/// Projects a symmetric matrix onto the positive semi-definite cone, the
/// nearest PSD matrix in the Frobenius norm: with `M = Q Λ Qᵀ`,
/// `M₊ = Q max(Λ, 0) Qᵀ` (Teran et al., *Robust Quasistatic Finite Elements
/// and Flesh Simulation*, SCA 2005; used per pair by IPC, §5). Only the lower
/// triangle of `m` is read; the result is exactly symmetric.
#[must_use]
pub fn project_positive<const N: usize>(m: &SMatrix<f64, N, N>) -> SMatrix<f64, N, N>
where
    Const<N>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<N>, U1>>,
{
    let mut eigen = m.symmetric_eigen();
    eigen.eigenvalues.iter_mut().for_each(|l| *l = l.max(0.0));
    let p = eigen.recompose();
    (p + p.transpose()) * 0.5
}

/// `D` with its Hessian projected by [`project_pair`] (an infinite value has
/// zero derivatives and is left as is).
fn projected(mut d: Derivatives) -> Derivatives {
    if d.value.is_finite() {
        d.hessian = project_pair(&d.hessian);
    }
    d
}

/// An orthonormal basis `U = V ⊗ I₃` (12×9) of the complement of the rigid
/// translations `1 ⊗ e_c`, with `V` the 4×3 Helmert basis orthogonal to
/// `(1, 1, 1, 1)`.
fn translation_complement() -> SMatrix<f64, 12, 9> {
    const S2: f64 = std::f64::consts::FRAC_1_SQRT_2;
    const S6: f64 = 0.408_248_290_463_863_1; // 1/√6
    const S12: f64 = 0.288_675_134_594_812_9; // 1/√12
    const V: [[f64; 3]; 4] = [
        [S2, S6, S12],
        [-S2, S6, S12],
        [0.0, -2.0 * S6, S12],
        [0.0, 0.0, -3.0 * S12],
    ];
    let mut u = SMatrix::<f64, 12, 9>::zeros();
    for (k, row) in V.iter().enumerate() {
        for (i, v) in row.iter().enumerate() {
            for c in 0..3 {
                u[(3 * k + c, 3 * i + c)] = *v;
            }
        }
    }
    u
}

/// [`project_positive`] for a pair's Hessian. A function of the pair's
/// relative positions (every distance, barrier and mollifier) has
/// `H (1 ⊗ e_c) = 0`; then `H = U (UᵀHU) Uᵀ` and `H₊ = U (UᵀHU)₊ Uᵀ` exactly,
/// a 9×9 eigenproblem instead of 12×12 (about 1.4 times faster in all). Other
/// matrices
/// take the full projection.
fn project_pair(h: &Mat12) -> Mat12 {
    let tol = 1e-10 * h.amax();
    let invariant = (0..12).all(|i| {
        (0..3).all(|c| (h[(i, c)] + h[(i, 3 + c)] + h[(i, 6 + c)] + h[(i, 9 + c)]).abs() <= tol)
    });
    if !invariant {
        return project_positive(h);
    }
    let u = translation_complement();
    let p = u * project_positive(&(u.transpose() * h * u)) * u.transpose();
    (p + p.transpose()) * 0.5
}

/// The barrier of a pair at gap `g = √(d²) − ξ` (`ξ` the thickness, `d̂` the
/// activation distance): value `b(g)`, gradient `b'(g) ∇g` and Hessian
/// `b''(g) ∇g ∇gᵀ + b'(g) ∇²g` projected onto the PSD cone, from the squared
/// distance's [`Derivatives`] (module docs).
///
/// `None` when `g ≥ d̂` (the pair is inactive). A pair at `g ≤ 0` is
/// infeasible: the value is `∞` with zero gradient and Hessian.
#[must_use]
pub fn pair_barrier(squared: &Derivatives, thickness: f64, activation: f64) -> Option<Derivatives> {
    pair_barrier_exact(squared, thickness, activation).map(projected)
}

/// [`pair_barrier`] before the projection of its Hessian.
pub(crate) fn pair_barrier_exact(
    squared: &Derivatives,
    thickness: f64,
    activation: f64,
) -> Option<Derivatives> {
    let d = squared.value.max(0.0).sqrt();
    let g = d - thickness;
    if g >= activation {
        return None;
    }
    if g <= 0.0 {
        return Some(Derivatives::constant(f64::INFINITY));
    }
    let (b, db, ddb) = barrier(g, activation);
    let grad_g = squared.gradient / (2.0 * d);
    let mut hessian = squared.hessian * (db / (2.0 * d));
    hessian.ger(ddb - db / d, &grad_g, &grad_g, 1.0);
    Some(Derivatives {
        value: b,
        gradient: grad_g * db,
        hessian,
    })
}

/// The edge–edge barrier times the mollifier `m` of
/// [`edge_edge_mollifier`](super::distance::edge_edge_mollifier) (Li et al.
/// 2020, §4.3):
///
/// ```text
/// value m b,   gradient m ∇b + b ∇m,
/// Hessian m ∇²b + ∇m ∇bᵀ + ∇b ∇mᵀ + b ∇²m,
/// ```
///
/// with `b` the unprojected [`pair_barrier`]; the sum is projected onto the
/// PSD cone once, at the end. `None` when the gap is at least `d̂`; `∞` (zero
/// derivatives) when it is `≤ 0`, whatever `m`.
#[must_use]
pub fn mollified_pair_barrier(
    squared: &Derivatives,
    mollifier: &Derivatives,
    thickness: f64,
    activation: f64,
) -> Option<Derivatives> {
    mollified_pair_barrier_exact(squared, mollifier, thickness, activation).map(projected)
}

/// [`mollified_pair_barrier`] before the projection of its Hessian.
pub(crate) fn mollified_pair_barrier_exact(
    squared: &Derivatives,
    mollifier: &Derivatives,
    thickness: f64,
    activation: f64,
) -> Option<Derivatives> {
    let b = pair_barrier_exact(squared, thickness, activation)?;
    if !b.value.is_finite() {
        return Some(b);
    }
    let m = mollifier;
    let mut hessian: Mat12 = b.hessian * m.value + m.hessian * b.value;
    hessian.ger(1.0, &m.gradient, &b.gradient, 1.0);
    hessian.ger(1.0, &b.gradient, &m.gradient, 1.0);
    Some(Derivatives {
        value: m.value * b.value,
        gradient: b.gradient * m.value + m.gradient * b.value,
        hessian,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::distance::tests::{
        Rng, check_derivatives, near_parallel_edges, point_triangle_config, skew_edges, stack,
        unstack,
    };
    use crate::collision::distance::{
        edge_edge_closest, edge_edge_mollifier, edge_edge_squared, mollifier_threshold,
        point_triangle_closest, point_triangle_squared,
    };
    use crate::{Vec3, Vec12};

    const XI: f64 = 0.05;
    const DHAT: f64 = 0.2;

    #[test]
    fn barrier_derivatives_match_finite_differences() {
        let h = 1e-7;
        for i in 1..100 {
            let d = DHAT * f64::from(i) / 100.0;
            let (_, db, ddb) = barrier(d, DHAT);
            let (bp, dbp, _) = barrier(d + h, DHAT);
            let (bm, dbm, _) = barrier(d - h, DHAT);
            let tol = 1e-6 * (1.0 + ddb);
            assert!(((bp - bm) / (2.0 * h) - db).abs() <= tol, "b' at {d}");
            assert!(((dbp - dbm) / (2.0 * h) - ddb).abs() <= tol, "b'' at {d}");
            assert!(db < 0.0 && ddb > 0.0);
        }
    }

    #[test]
    fn barrier_is_c2_at_activation_and_infinite_at_contact() {
        for delta in [1e-3, 1e-5, 1e-7] {
            let (b, db, ddb) = barrier(DHAT * (1.0 - delta), DHAT);
            // b ≈ d̂² δ³, b' ≈ −3 d̂ δ², b'' ≈ 6 δ.
            assert!(b.abs() <= 1.1 * DHAT * DHAT * delta.powi(3));
            assert!(db.abs() <= 3.1 * DHAT * delta.powi(2));
            assert!(ddb.abs() <= 6.1 * delta);
        }
        assert_eq!(barrier(DHAT, DHAT), (0.0, 0.0, 0.0));
        assert_eq!(barrier(2.0 * DHAT, DHAT), (0.0, 0.0, 0.0));
        let inf = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        assert_eq!(barrier(0.0, DHAT), inf);
        assert_eq!(barrier(-1.0, DHAT), inf);
        assert!(barrier(1e-300, DHAT).0 > 1e-2);
    }

    /// Moves the first primitive along `r` until the distance is `d`; the
    /// closest points stay the same.
    fn at_distance(mut x: [Vec3; 4], triangle: bool, d: f64) -> [Vec3; 4] {
        let c = if triangle {
            point_triangle_closest(x[0], x[1], x[2], x[3])
        } else {
            edge_edge_closest(x[0], x[1], x[2], x[3])
        };
        let r: Vec3 = (0..4).map(|k| c.weights[k] * x[k]).sum();
        let shift = r.normalize() * (d - r.norm());
        x[0] += shift;
        if !triangle {
            x[1] += shift;
        }
        x
    }

    fn squared(x: &Vec12, triangle: bool) -> Derivatives {
        let [a, b, c, d] = unstack(x);
        if triangle {
            point_triangle_squared(a, b, c, d)
        } else {
            edge_edge_squared(a, b, c, d)
        }
    }

    /// Random active pairs: point–triangle in every region and skew edges.
    fn active_pairs(rng: &mut Rng) -> Vec<(Vec12, bool)> {
        let mut pairs = Vec::new();
        for i in 0..60 {
            let triangle = i % 4 != 3;
            let x = if triangle {
                point_triangle_config(rng, i % 3)
            } else {
                skew_edges(rng, 0.2)
            };
            let d = XI + DHAT * rng.uniform(0.05, 0.95);
            pairs.push((stack(&at_distance(x, triangle, d)), triangle));
        }
        pairs
    }

    fn min_eigenvalue(m: &Mat12) -> f64 {
        m.symmetric_eigen().eigenvalues.min()
    }

    #[test]
    fn pair_barrier_derivatives_match_finite_differences() {
        let mut rng = Rng::new(11);
        for (x, triangle) in active_pairs(&mut rng) {
            let f =
                |y: &Vec12| pair_barrier_exact(&squared(y, triangle), XI, DHAT).expect("active");
            check_derivatives(f, &x, 1e-7, 1e-5, 1.0);
        }
    }

    #[test]
    fn projected_pair_hessian_is_positive_and_exact_where_already_positive() {
        // A barrier Hessian is indefinite almost everywhere (`b' < 0` bends it
        // down across `∇g`), so "already PSD" is checked on projected ones.
        let mut rng = Rng::new(12);
        for (x, triangle) in active_pairs(&mut rng) {
            let s = squared(&x, triangle);
            let exact = pair_barrier_exact(&s, XI, DHAT).expect("active");
            let projected = pair_barrier(&s, XI, DHAT).expect("active");
            assert_eq!(projected.value.to_bits(), exact.value.to_bits());
            assert_eq!(projected.gradient, exact.gradient);
            let norm = exact.hessian.norm();
            assert!(min_eigenvalue(&projected.hessian) >= -1e-9 * norm);
            if min_eigenvalue(&exact.hessian) >= 0.0 {
                assert!((projected.hessian - exact.hessian).amax() <= 1e-12 * norm);
            }
            let again = project_positive(&projected.hessian);
            assert!((again - projected.hessian).amax() <= 1e-12 * norm);
        }
    }

    #[test]
    fn projection_keeps_positive_matrices_and_clamps_negative_eigenvalues() {
        let mut rng = Rng::new(13);
        for _ in 0..20 {
            let a = Mat12::from_fn(|_, _| rng.uniform(-1.0, 1.0));
            let psd = a * a.transpose();
            let p = project_positive(&psd);
            assert!((p - psd).amax() <= 1e-12 * psd.amax());
            let sym = a + a.transpose();
            let p = project_positive(&sym);
            assert!(min_eigenvalue(&p) >= -1e-12 * sym.norm());
            assert!((project_positive(&p) - p).amax() <= 1e-12 * sym.norm());
            // M₊ − M = Q max(−Λ, 0) Qᵀ is positive semi-definite.
            assert!(min_eigenvalue(&(p - sym)) >= -1e-12 * sym.norm());
        }
        let q = nalgebra::Rotation3::from_scaled_axis(Vec3::new(0.3, -1.2, 0.7)).into_inner();
        let m = q * nalgebra::Matrix3::from_diagonal(&Vec3::new(3.0, -2.0, 1.0)) * q.transpose();
        let want = q * nalgebra::Matrix3::from_diagonal(&Vec3::new(3.0, 0.0, 1.0)) * q.transpose();
        assert!((project_positive(&m) - want).amax() <= 1e-14 * 3.0 * 4.0);
    }

    #[test]
    fn pair_projection_on_the_translation_complement_equals_the_full_projection() {
        let mut rng = Rng::new(17);
        let u = translation_complement();
        let identity = SMatrix::<f64, 9, 9>::identity();
        assert!((u.transpose() * u - identity).amax() <= 1e-15);
        for (x, triangle) in active_pairs(&mut rng) {
            let h = pair_barrier_exact(&squared(&x, triangle), XI, DHAT)
                .expect("active")
                .hessian;
            let full = project_positive(&h);
            assert!((project_pair(&h) - full).amax() <= 1e-11 * h.amax());
        }
        // Not translation invariant: the full projection.
        let a = Mat12::from_fn(|_, _| rng.uniform(-1.0, 1.0));
        let m = a + a.transpose();
        assert_eq!(project_pair(&m), project_positive(&m));
    }

    #[test]
    fn pair_barrier_is_none_beyond_activation_and_infinite_at_contact() {
        let mut rng = Rng::new(14);
        let x = point_triangle_config(&mut rng, 0);
        let far = at_distance(x, true, XI + DHAT * 1.01);
        let s = point_triangle_squared(far[0], far[1], far[2], far[3]);
        assert!(pair_barrier(&s, XI, DHAT).is_none());
        for d in [XI * 0.999, XI * 0.5, 0.0] {
            let near = at_distance(x, true, d.max(1e-300));
            let s = point_triangle_squared(near[0], near[1], near[2], near[3]);
            let b = pair_barrier(&s, XI, DHAT).expect("infeasible, not inactive");
            assert!(b.value.is_infinite() && b.value > 0.0);
            assert_eq!(b.gradient, Vec12::zeros());
        }
    }

    /// Nearly parallel edges at an active distance, with their mollifier
    /// threshold (the mollifier is active).
    fn mollified_pairs(rng: &mut Rng) -> Vec<(Vec12, f64)> {
        (0..30)
            .map(|_| {
                let angle = rng.uniform(0.01, 0.03);
                let x = near_parallel_edges(rng, angle, true);
                let x = at_distance(x, false, XI + DHAT * rng.uniform(0.05, 0.95));
                let eps = mollifier_threshold(x[0], x[1], x[2], x[3]);
                (stack(&x), eps)
            })
            .collect()
    }

    fn mollified(y: &Vec12, eps: f64, exact: bool) -> Option<Derivatives> {
        let [a0, a1, b0, b1] = unstack(y);
        let s = edge_edge_squared(a0, a1, b0, b1);
        let m = edge_edge_mollifier(a0, a1, b0, b1, eps);
        if exact {
            mollified_pair_barrier_exact(&s, &m, XI, DHAT)
        } else {
            mollified_pair_barrier(&s, &m, XI, DHAT)
        }
    }

    #[test]
    fn mollified_pair_barrier_derivatives_match_finite_differences() {
        let mut rng = Rng::new(15);
        for (x, eps) in mollified_pairs(&mut rng) {
            let [a0, a1, b0, b1] = unstack(&x);
            let m = edge_edge_mollifier(a0, a1, b0, b1, eps).value;
            assert!(m > 0.0 && m < 1.0);
            let f = |y: &Vec12| mollified(y, eps, true).expect("active");
            check_derivatives(f, &x, 1e-7, 1e-5, 1.0);
            let exact = f(&x);
            let p = mollified(&x, eps, false).expect("active");
            assert!(min_eigenvalue(&p.hessian) >= -1e-9 * exact.hessian.norm());
            let full = project_positive(&exact.hessian);
            assert!((p.hessian - full).amax() <= 1e-11 * exact.hessian.amax());
        }
    }

    #[test]
    fn mollified_barrier_equals_the_barrier_for_crossing_edges() {
        let mut rng = Rng::new(16);
        let x = at_distance(skew_edges(&mut rng, 0.5), false, XI + 0.5 * DHAT);
        let eps = mollifier_threshold(x[0], x[1], x[2], x[3]);
        let s = edge_edge_squared(x[0], x[1], x[2], x[3]);
        let m = edge_edge_mollifier(x[0], x[1], x[2], x[3], eps);
        assert_eq!(
            mollified_pair_barrier(&s, &m, XI, DHAT),
            pair_barrier(&s, XI, DHAT)
        );
    }
}
