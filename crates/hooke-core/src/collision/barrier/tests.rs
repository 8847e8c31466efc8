use super::projection::{project_pair, translation_complement};
use super::*;
use crate::collision::distance::tests::{
    Rng, check_derivatives, near_parallel_edges, point_triangle_config, skew_edges, stack, unstack,
};
use crate::collision::distance::{
    edge_edge_closest, edge_edge_mollifier, edge_edge_squared, mollifier_threshold,
    point_triangle_closest, point_triangle_squared,
};
use crate::{Vec3, Vec12};

const XI: f64 = 0.05;
const DHAT: f64 = 0.2;
/// The barrier per unit stiffness with activation distance `DHAT`.
const B: Barrier = Barrier {
    stiffness: 1.0,
    activation: DHAT,
};

/// `(b, b', b'')` at `d`.
fn barrier(d: f64) -> (f64, f64, f64) {
    B.unit(d)
}

#[test]
fn barrier_derivatives_match_finite_differences() {
    let h = 1e-7;
    for i in 1..100 {
        let d = DHAT * f64::from(i) / 100.0;
        let (_, db, ddb) = barrier(d);
        let (bp, dbp, _) = barrier(d + h);
        let (bm, dbm, _) = barrier(d - h);
        let tol = 1e-6 * (1.0 + ddb);
        assert!(((bp - bm) / (2.0 * h) - db).abs() <= tol, "b' at {d}");
        assert!(((dbp - dbm) / (2.0 * h) - ddb).abs() <= tol, "b'' at {d}");
        assert!(db < 0.0 && ddb > 0.0);
    }
}

#[test]
fn barrier_is_c2_at_activation_and_infinite_at_contact() {
    for delta in [1e-3, 1e-5, 1e-7] {
        let (b, db, ddb) = barrier(DHAT * (1.0 - delta));
        // b ≈ d̂² δ³, b' ≈ −3 d̂ δ², b'' ≈ 6 δ.
        assert!(b.abs() <= 1.1 * DHAT * DHAT * delta.powi(3));
        assert!(db.abs() <= 3.1 * DHAT * delta.powi(2));
        assert!(ddb.abs() <= 6.1 * delta);
    }
    assert_eq!(barrier(DHAT), (0.0, 0.0, 0.0));
    assert_eq!(barrier(2.0 * DHAT), (0.0, 0.0, 0.0));
    let inf = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    assert_eq!(barrier(0.0), inf);
    assert_eq!(barrier(-1.0), inf);
    assert!(barrier(1e-300).0 > 1e-2);
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
        let f = |y: &Vec12| B.pair_exact(&squared(y, triangle), XI).expect("active");
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
        let exact = B.pair_exact(&s, XI).expect("active");
        let projected = B.pair(&s, XI).expect("active");
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
    let identity = nalgebra::SMatrix::<f64, 9, 9>::identity();
    assert!((u.transpose() * u - identity).amax() <= 1e-15);
    for (x, triangle) in active_pairs(&mut rng) {
        let h = B
            .pair_exact(&squared(&x, triangle), XI)
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
    assert!(B.pair(&s, XI).is_none());
    for d in [XI * 0.999, XI * 0.5, 0.0] {
        let near = at_distance(x, true, d.max(1e-300));
        let s = point_triangle_squared(near[0], near[1], near[2], near[3]);
        let b = B.pair(&s, XI).expect("infeasible, not inactive");
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
        B.mollified_pair_exact(&s, &m, XI)
    } else {
        B.mollified_pair(&s, &m, XI)
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
    assert_eq!(B.mollified_pair(&s, &m, XI), B.pair(&s, XI));
}
