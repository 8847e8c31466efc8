use super::svd::signed_svd;
use super::*;

/// A tet with a non-trivial rest shape, modulus 1000 Pa.
fn tet() -> (Tet, [Vec3; 4]) {
    let rest = [
        Vec3::new(0.1, 0.0, 0.05),
        Vec3::new(1.1, 0.2, 0.0),
        Vec3::new(0.3, 0.9, 0.1),
        Vec3::new(0.2, 0.3, 1.2),
    ];
    (Tet::at_rest([0, 1, 2, 3], 1000.0, rest).unwrap(), rest)
}

/// Configurations: at rest, stretched and sheared, nearly flat (the apex
/// almost in the base's plane), inverted (the apex through the base).
fn configurations() -> Vec<(&'static str, [Vec3; 4])> {
    let (_, rest) = tet();
    let stretched = rest.map(|p| Vec3::new(1.3 * p.x + 0.2 * p.y, 0.9 * p.y, 1.1 * p.z));
    let base_normal = (rest[1] - rest[0]).cross(&(rest[2] - rest[0])).normalize();
    let height = (rest[3] - rest[0]).dot(&base_normal);
    let mut flat = rest;
    flat[3] -= 0.999 * height * base_normal;
    let mut inverted = rest;
    inverted[3] -= 1.6 * height * base_normal;
    vec![
        ("rest", rest),
        ("stretched", stretched),
        ("nearly flat", flat),
        ("inverted", inverted),
    ]
}

fn flat(x: &[Vec3; 4]) -> [f64; 12] {
    let mut out = [0.0; 12];
    for (a, p) in x.iter().enumerate() {
        out[3 * a..3 * a + 3].copy_from_slice(p.as_slice());
    }
    out
}

fn shifted(x: &[Vec3; 4], k: usize, by: f64) -> [Vec3; 4] {
    let mut y = *x;
    y[k / 3][k % 3] += by;
    y
}

/// The signed SVD reproduces its matrices, with rotations, for general,
/// inverted, flat and degenerate matrices.
#[test]
fn the_signed_svd_reproduces_its_matrices() {
    let mut rng = crate::collision::distance::tests::Rng::new(3);
    let mut cases: Vec<Mat3> = (0..100)
        .map(|_| Mat3::from_fn(|_, _| rng.uniform(-2.0, 2.0)))
        .collect();
    cases.push(Mat3::identity());
    cases.push(Mat3::from_diagonal(&Vec3::new(1.0, 1.0, -1.0)));
    cases.push(Mat3::from_diagonal(&Vec3::new(2.0, 0.5, 0.0)));
    cases.push(Vec3::new(1.0, 2.0, 3.0) * Vec3::new(0.5, -1.0, 0.2).transpose());
    cases.push(Mat3::zeros());
    for f in cases {
        let (u, sigma, v) = signed_svd(&f);
        let scale = f.norm().max(1.0);
        assert!((u * Mat3::from_diagonal(&sigma) * v.transpose() - f).norm() < 1e-12 * scale);
        for r in [u, v] {
            assert!((r.transpose() * r - Mat3::identity()).norm() < 1e-12);
            assert!((r.determinant() - 1.0).abs() < 1e-12);
        }
        assert!(sigma[0] >= sigma[1] - 1e-12 && sigma[1] >= sigma[2].abs() - 1e-12);
        assert!(sigma[2] * f.determinant() >= -1e-12);
    }
}

#[test]
fn rest_volume_and_orientation() {
    let (t, rest) = tet();
    let expected = (rest[1] - rest[0])
        .cross(&(rest[2] - rest[0]))
        .dot(&(rest[3] - rest[0]))
        / 6.0;
    assert!((t.rest_volume - expected).abs() < 1e-15);
    assert!((t.volume_ratio(&rest) - 1.0).abs() < 1e-14);
    let mirrored = Tet::at_rest([0, 1, 3, 2], 1.0, [rest[0], rest[1], rest[3], rest[2]]).unwrap();
    assert_eq!(mirrored.vertices, [0, 1, 2, 3]);
    assert!(Tet::at_rest([0, 1, 2, 3], 1.0, [rest[0], rest[1], rest[2], rest[0]]).is_none());
}

/// The gradient against central differences of the energy, the exact
/// Hessian against central differences of the gradient, in every
/// configuration.
#[test]
fn gradient_and_hessian_match_finite_differences() {
    let (t, _) = tet();
    for (name, x) in configurations() {
        let d = t.derivatives(&x, TetHessian::Exact);
        assert!((d.energy - t.energy(&x)).abs() <= 1e-12 * d.energy.max(1.0));
        let j = t.deformation(&x).determinant();
        assert!((t.volume_ratio(&x) - j).abs() <= 1e-13, "{name}: J ≠ det F");
        let forces = t.forces(&x);
        let h = 1e-6;
        let scale = d.hessian.amax();
        for k in 0..12 {
            let (plus, minus) = (shifted(&x, k, h), shifted(&x, k, -h));
            let numeric = (t.energy(&plus) - t.energy(&minus)) / (2.0 * h);
            let analytic = d.gradient[k / 3][k % 3];
            assert!(
                (numeric - analytic).abs() <= 1e-6 * scale,
                "{name}: ∂E/∂x[{k}] = {analytic}, differences give {numeric}"
            );
            assert!((forces[k / 3][k % 3] + analytic).abs() <= 1e-12 * scale);
            let (gp, gm) = (
                flat(&t.derivatives(&plus, TetHessian::Exact).gradient),
                flat(&t.derivatives(&minus, TetHessian::Exact).gradient),
            );
            for l in 0..12 {
                let numeric = (gp[l] - gm[l]) / (2.0 * h);
                assert!(
                    (numeric - d.hessian[(l, k)]).abs() <= 1e-6 * scale,
                    "{name}: H[{l}, {k}] = {}, differences give {numeric}",
                    d.hessian[(l, k)]
                );
            }
        }
    }
}

/// The projected Hessian is positive semidefinite on random
/// deformations, inverted ones included, and equals the exact one at
/// rest (where the exact one is); the Gauss–Newton Hessian has the one
/// eigenvalue `κ V₀ |∇J|²` and zeros, and equals the exact one at rest
/// too.
#[test]
fn projected_and_gauss_newton_hessians_are_positive_semidefinite() {
    let (t, rest) = tet();
    let mut rng = crate::collision::distance::tests::Rng::new(7);
    for _ in 0..200 {
        let x = rest.map(|p| p + Vec3::from_fn(|_, _| rng.uniform(-0.6, 0.6)));
        let h = t.derivatives(&x, TetHessian::Projected).hessian;
        let exact = t.derivatives(&x, TetHessian::Exact).hessian;
        let eigen = nalgebra::SymmetricEigen::new(h).eigenvalues;
        let scale = exact.amax();
        assert!(
            eigen.min() >= -1e-10 * scale,
            "eigenvalue {} at J = {}",
            eigen.min(),
            t.volume_ratio(&x)
        );
        // Only the negative part is removed: the difference is negative
        // semidefinite.
        let removed = nalgebra::SymmetricEigen::new(exact - h).eigenvalues;
        assert!(removed.max() <= 1e-10 * scale);
        let gauss_newton = t.derivatives(&x, TetHessian::GaussNewton).hessian;
        let mut eigen = nalgebra::SymmetricEigen::new(gauss_newton).eigenvalues;
        eigen.as_mut_slice().sort_by(f64::total_cmp);
        let dj = t.volume_gradient(&x);
        let expected = t.modulus * t.rest_volume * dj.iter().map(Vec3::norm_squared).sum::<f64>();
        assert!((eigen[11] - expected).abs() <= 1e-10 * expected);
        assert!(eigen.rows(0, 11).amax() <= 1e-10 * expected);
    }
    let exact = t.derivatives(&rest, TetHessian::Exact).hessian;
    for kind in [TetHessian::Projected, TetHessian::GaussNewton] {
        let at_rest = t.derivatives(&rest, kind).hessian;
        assert!((at_rest - exact).amax() <= 1e-12 * exact.amax(), "{kind:?}");
    }
}

/// An inverted element's force raises its volume, a compressed one's
/// too, a stretched one's lowers it.
#[test]
fn forces_push_toward_the_rest_volume() {
    let (t, rest) = tet();
    for (name, x) in configurations().into_iter().skip(1) {
        let j = t.volume_ratio(&x);
        let f = t.forces(&x);
        let step = 1e-7;
        let moved: [Vec3; 4] = std::array::from_fn(|a| x[a] + step * f[a]);
        let change = t.volume_ratio(&moved) - j;
        assert!(
            change * (1.0 - j) > 0.0,
            "{name}: J = {j} moved by {change}"
        );
    }
    assert!(t.forces(&rest).iter().all(|f| f.norm() < 1e-10));
}
