use super::*;

/// SplitMix64: a small deterministic generator for the tests.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform on `0..n`.
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// Uniform on `[lo, hi)`.
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }

    /// Uniform in the cube `[−scale, scale)³`.
    pub(crate) fn vec3(&mut self, scale: f64) -> Vec3 {
        Vec3::new(
            self.uniform(-scale, scale),
            self.uniform(-scale, scale),
            self.uniform(-scale, scale),
        )
    }

    /// A random unit vector.
    pub(crate) fn unit(&mut self) -> Vec3 {
        loop {
            let v = self.vec3(1.0);
            let n = v.norm();
            if n > 0.1 && n < 1.0 {
                return v / n;
            }
        }
    }

    pub(crate) fn sign(&mut self) -> f64 {
        if self.next_u64() & 1 == 0 { 1.0 } else { -1.0 }
    }
}

pub(crate) fn stack(x: &[Vec3; 4]) -> Vec12 {
    Vec12::from_fn(|i, _| x[i / 3][i % 3])
}

pub(crate) fn unstack(x: &Vec12) -> [Vec3; 4] {
    std::array::from_fn(|k| x.fixed_rows::<3>(3 * k).into())
}

/// Checks `f`'s gradient against central differences of its value and its
/// Hessian against central differences of its gradient, relative to the
/// largest entry (at least `floor`).
pub(crate) fn check_derivatives(
    f: impl Fn(&Vec12) -> Derivatives,
    x: &Vec12,
    h: f64,
    tol: f64,
    floor: f64,
) {
    let d = f(x);
    let mut grad = Vec12::zeros();
    let mut hess = Mat12::zeros();
    for i in 0..12 {
        let mut xp = *x;
        xp[i] += h;
        let mut xm = *x;
        xm[i] -= h;
        let (fp, fm) = (f(&xp), f(&xm));
        grad[i] = (fp.value - fm.value) / (2.0 * h);
        hess.set_column(i, &((fp.gradient - fm.gradient) / (2.0 * h)));
    }
    let gs = d.gradient.amax().max(floor);
    let hs = d.hessian.amax().max(floor);
    let ge = (grad - d.gradient).amax();
    let he = (hess - d.hessian).amax();
    assert!(
        ge <= tol * gs,
        "gradient error {ge:e} (scale {gs:e}) at {x}"
    );
    assert!(he <= tol * hs, "Hessian error {he:e} (scale {hs:e}) at {x}");
    let asym = (d.hessian - d.hessian.transpose()).amax();
    assert!(asym <= 1e-12 * hs, "asymmetric Hessian");
}

fn pt(x: &Vec12) -> Derivatives {
    let [p, a, b, c] = unstack(x);
    point_triangle_squared(p, a, b, c)
}

fn ee(x: &Vec12) -> Derivatives {
    let [a0, a1, b0, b1] = unstack(x);
    edge_edge_squared(a0, a1, b0, b1)
}

/// A triangle with no angle below ~10°.
pub(crate) fn triangle(rng: &mut Rng) -> [Vec3; 3] {
    loop {
        let t = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
        let ok = (0..3).all(|i| {
            let (u, v) = (t[(i + 1) % 3] - t[i], t[(i + 2) % 3] - t[i]);
            u.cross(&v).norm() > 0.2 * u.norm() * v.norm()
        });
        if ok {
            return t;
        }
    }
}

/// A point in the face, an edge or a vertex region (`kind` 0, 1, 2).
pub(crate) fn point_triangle_config(rng: &mut Rng, kind: usize) -> [Vec3; 4] {
    let [a, b, c] = triangle(rng);
    let n = (b - a).cross(&(c - a)).normalize();
    let h = rng.uniform(-1.0, 1.0);
    let p = match kind {
        0 => {
            let beta = rng.uniform(0.1, 0.8);
            let gamma = rng.uniform(0.05, 0.9 - beta);
            a + beta * (b - a) + gamma * (c - a) + h * n
        }
        1 => {
            let q = a + rng.uniform(0.1, 0.9) * (b - a);
            let mut out = (b - a).cross(&n).normalize();
            if out.dot(&(c - q)) > 0.0 {
                out = -out;
            }
            q + rng.uniform(0.05, 1.0) * out + h * n
        }
        _ => {
            let out = -((b - a).normalize() + (c - a).normalize()).normalize();
            a + rng.uniform(0.05, 1.0) * out + h * n
        }
    };
    [p, a, b, c]
}

/// Skew edges whose closest points are interior.
pub(crate) fn skew_edges(rng: &mut Rng, min_sin: f64) -> [Vec3; 4] {
    loop {
        let (e0, e1) = (rng.vec3(1.0), rng.vec3(1.0));
        let n = e0.cross(&e1);
        if e0.norm() < 0.3 || e1.norm() < 0.3 || n.norm() < min_sin * e0.norm() * e1.norm() {
            continue;
        }
        let qa = rng.vec3(1.0);
        let qb = qa - rng.sign() * rng.uniform(0.01, 1.0) * n.normalize();
        let a0 = qa - rng.uniform(0.1, 0.9) * e0;
        let b0 = qb - rng.uniform(0.1, 0.9) * e1;
        return [a0, a0 + e0, b0, b0 + e1];
    }
}

/// An endpoint against an edge interior (`interior`) or against an
/// endpoint, shuffled by the pair's symmetries.
pub(crate) fn endpoint_edges(rng: &mut Rng, interior: bool) -> [Vec3; 4] {
    loop {
        let (b0, e1) = (rng.vec3(1.0), rng.vec3(1.0));
        let mut u = rng.vec3(1.0);
        let e0 = rng.vec3(1.0);
        if interior {
            u -= e1 * (u.dot(&e1) / e1.norm_squared());
        }
        let margin = 0.2 * u.norm();
        if e1.norm() < 0.3 || u.norm() < 0.05 || e0.dot(&u) < margin * e0.norm() {
            continue;
        }
        if !interior && e1.dot(&u) > -margin * e1.norm() {
            continue;
        }
        let base = if interior {
            b0 + rng.uniform(0.1, 0.9) * e1
        } else {
            b0
        };
        let a0 = base + u;
        let mut x = [a0, a0 + e0, b0, b0 + e1];
        if rng.sign() > 0.0 {
            x.swap(0, 1);
        }
        if rng.sign() > 0.0 {
            x.swap(2, 3);
        }
        if rng.sign() > 0.0 {
            x = [x[2], x[3], x[0], x[1]];
        }
        return x;
    }
}

/// Edges at angle `θ ≈ angle` (`0` for parallel); `overlap` puts them side
/// by side, otherwise end to end.
pub(crate) fn near_parallel_edges(rng: &mut Rng, angle: f64, overlap: bool) -> [Vec3; 4] {
    let e0 = rng.unit() * rng.uniform(0.5, 1.5);
    let mut v = rng.unit();
    v -= e0 * (v.dot(&e0) / e0.norm_squared());
    let v = v.normalize();
    let e1 = (e0.normalize() + angle * v).normalize() * rng.uniform(0.5, 1.5) * rng.sign();
    let a0 = rng.vec3(1.0);
    let side = rng.uniform(0.05, 0.5) * v.cross(&e0).normalize();
    let along = if overlap {
        0.5 * e0
    } else {
        (1.2 + 0.5 * e1.norm() / e0.norm()) * e0
    };
    let mid = a0 + along + side;
    [a0, a0 + e0, mid - 0.5 * e1, mid + 0.5 * e1]
}

#[test]
fn point_triangle_derivatives_match_finite_differences_in_every_region() {
    let mut rng = Rng::new(1);
    for kind in 0..3 {
        for _ in 0..30 {
            let x = point_triangle_config(&mut rng, kind);
            check_derivatives(pt, &stack(&x), 1e-6, 1e-6, 1.0);
        }
    }
}

#[test]
fn edge_edge_derivatives_match_finite_differences_for_skew_edges() {
    let mut rng = Rng::new(2);
    for _ in 0..50 {
        let x = skew_edges(&mut rng, 0.2);
        check_derivatives(ee, &stack(&x), 1e-6, 1e-6, 1.0);
    }
}

#[test]
fn edge_edge_derivatives_match_finite_differences_at_endpoints() {
    let mut rng = Rng::new(3);
    for interior in [true, false] {
        for _ in 0..40 {
            let x = endpoint_edges(&mut rng, interior);
            check_derivatives(ee, &stack(&x), 1e-6, 1e-6, 1.0);
        }
    }
}

#[test]
fn edge_edge_derivatives_match_finite_differences_for_nearly_parallel_edges() {
    let mut rng = Rng::new(4);
    for _ in 0..30 {
        // Line–line type, derivatives of order 1/θ.
        let x = near_parallel_edges(&mut rng, 1e-2, true);
        check_derivatives(ee, &stack(&x), 1e-7, 1e-5, 1.0);
        // Parallel and nearly parallel end to end: endpoint–endpoint.
        for angle in [0.0, 1e-9] {
            let x = near_parallel_edges(&mut rng, angle, false);
            check_derivatives(ee, &stack(&x), 1e-6, 1e-6, 1.0);
        }
    }
}

#[test]
fn parallel_edges_side_by_side_take_an_endpoint_type_with_finite_derivatives() {
    let mut rng = Rng::new(5);
    for angle in [0.0, 1e-9, 1e-7] {
        for _ in 0..20 {
            let x = near_parallel_edges(&mut rng, angle, true);
            let d = ee(&stack(&x));
            assert!(
                d.gradient
                    .iter()
                    .chain(d.hessian.iter())
                    .all(|v| v.is_finite())
            );
            assert!(d.hessian.amax() < 1e3, "{}", d.hessian.amax());
            let w = edge_edge_closest(x[0], x[1], x[2], x[3]).weights;
            let endpoint = w.iter().any(|&v| v.abs() >= 1.0);
            assert!(endpoint, "{w:?}");
        }
    }
}

fn brute_force(x: &[Vec3; 4], triangle: bool) -> (f64, Vec3) {
    const N: usize = 300;
    let mut best = (f64::INFINITY, Vec3::zeros());
    for i in 0..=N {
        for j in 0..=N {
            let (u, v) = (i as f64 / N as f64, j as f64 / N as f64);
            let r = if triangle {
                if i + j > N {
                    continue;
                }
                x[0] - (x[1] + u * (x[2] - x[1]) + v * (x[3] - x[1]))
            } else {
                x[0] + u * (x[1] - x[0]) - (x[2] + v * (x[3] - x[2]))
            };
            if r.norm_squared() < best.0 {
                best = (r.norm_squared(), r);
            }
        }
    }
    best
}

fn check_against_brute_force(x: &[Vec3; 4], triangle: bool) {
    let closest = if triangle {
        point_triangle_closest(x[0], x[1], x[2], x[3])
    } else {
        edge_edge_closest(x[0], x[1], x[2], x[3])
    };
    let w = closest.weights;
    let r: Vec3 = (0..4).map(|k| w[k] * x[k]).sum();
    assert!((r.norm_squared() - closest.squared).abs() <= 1e-12);
    let (sq, rb) = brute_force(x, triangle);
    // The grid is within δ of any point of the primitives; |r − r*|² ≤
    // d²(r) − d*² for the projection of 0 onto a convex set.
    let spacing = (0..4).map(|k| x[k].norm()).sum::<f64>() * 2.0 / 300.0;
    let d = closest.squared.sqrt();
    assert!(closest.squared <= sq + 1e-12, "{} > {sq}", closest.squared);
    assert!(sq <= closest.squared + 2.0 * d * spacing + spacing * spacing);
    assert!((r - rb).norm() <= (2.0 * d * spacing + spacing * spacing).sqrt() + 1e-9);
    if triangle {
        assert!((w[0] - 1.0).abs() < 1e-15 && (w[1] + w[2] + w[3] + 1.0).abs() < 1e-12);
        assert!(w[1..].iter().all(|&v| (-1.0..=0.0).contains(&v)));
    } else {
        assert!((w[0] + w[1] - 1.0).abs() < 1e-12 && (w[2] + w[3] + 1.0).abs() < 1e-12);
        assert!(w[..2].iter().all(|&v| (0.0..=1.0).contains(&v)));
        assert!(w[2..].iter().all(|&v| (-1.0..=0.0).contains(&v)));
    }
}

#[test]
fn closest_points_match_brute_force_minimisation() {
    let mut rng = Rng::new(6);
    for i in 0..60 {
        let pt = if i < 15 {
            [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)]
        } else {
            point_triangle_config(&mut rng, i % 3)
        };
        check_against_brute_force(&pt, true);
        let ee = match i % 5 {
            0 => [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)],
            1 => skew_edges(&mut rng, 0.2),
            2 => endpoint_edges(&mut rng, i % 2 == 0),
            3 => near_parallel_edges(&mut rng, 0.0, true),
            _ => near_parallel_edges(&mut rng, 1e-9, i % 2 == 0),
        };
        check_against_brute_force(&ee, false);
    }
}

#[test]
fn squared_distance_value_equals_closest_squared() {
    let mut rng = Rng::new(7);
    for _ in 0..200 {
        let x = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
        let c = point_triangle_closest(x[0], x[1], x[2], x[3]);
        assert!((pt(&stack(&x)).value - c.squared).abs() <= 1e-15 * c.squared);
        let c = edge_edge_closest(x[0], x[1], x[2], x[3]);
        assert!((ee(&stack(&x)).value - c.squared).abs() <= 1e-15 * c.squared);
    }
}

/// The value-only distances are the closest points' squared distances
/// bit for bit, on general configurations and on the ones that take
/// each branch: every region of a triangle, skew, touching and
/// (nearly) parallel edges, and degenerate primitives.
#[test]
fn value_only_squared_distances_are_the_closest_points_bit_for_bit() {
    let mut rng = Rng::new(9);
    let same = |x: &[Vec3; 4]| {
        let [p, a, b, c] = *x;
        assert_eq!(
            point_triangle_squared_distance(p, a, b, c).to_bits(),
            point_triangle_closest(p, a, b, c).squared.to_bits(),
            "{x:?}"
        );
        assert_eq!(
            edge_edge_squared_distance(p, a, b, c).to_bits(),
            edge_edge_closest(p, a, b, c).squared.to_bits(),
            "{x:?}"
        );
    };
    for i in 0..600 {
        same(&[rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)]);
        same(&point_triangle_config(&mut rng, i % 3));
        same(&skew_edges(&mut rng, 0.2));
        same(&endpoint_edges(&mut rng, i % 2 == 0));
        same(&near_parallel_edges(&mut rng, 0.0, true));
        same(&near_parallel_edges(&mut rng, 1e-9, i % 2 == 0));
        let [p, a, b] = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
        let t = rng.uniform(-0.5, 1.5);
        for x in [
            [p, a, b, a + t * (b - a)],
            [p, a, a, a],
            [p, p, a, b],
            [p, a, b, b],
            [p, p, a, a],
        ] {
            same(&x);
        }
    }
}

#[test]
fn degenerate_primitives_give_finite_derivatives_and_true_distances() {
    let mut rng = Rng::new(8);
    for _ in 0..20 {
        let [p, a, b] = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
        let t = rng.uniform(-0.5, 1.5);
        let cases = [
            [p, a, b, a + t * (b - a)], // flat triangle
            [p, a, a, a],               // triangle collapsed to a point
            [p, p, a, b],               // zero-length first edge
            [p, a, b, b],               // zero-length second edge
            [p, p, a, a],               // both
        ];
        for (i, x) in cases.iter().enumerate() {
            let tri = i < 2;
            let d = if tri { pt(&stack(x)) } else { ee(&stack(x)) };
            assert!(d.value.is_finite());
            assert!(
                d.gradient
                    .iter()
                    .chain(d.hessian.iter())
                    .all(|v| v.is_finite())
            );
            check_against_brute_force(x, tri);
        }
    }
}

#[test]
fn mollifier_derivatives_match_finite_differences() {
    let mut rng = Rng::new(9);
    let mollifier = |x: &Vec12, eps: f64| {
        let [a0, a1, b0, b1] = unstack(x);
        edge_edge_mollifier(a0, a1, b0, b1, eps)
    };
    for _ in 0..40 {
        let (angle, overlap) = (rng.uniform(0.005, 0.03), rng.sign() > 0.0);
        let x = near_parallel_edges(&mut rng, angle, overlap);
        let eps = mollifier_threshold(x[0], x[1], x[2], x[3]);
        let m = mollifier(&stack(&x), eps);
        assert!(m.value > 0.0 && m.value < 1.0, "{}", m.value);
        let scale = 1.0 / eps;
        check_derivatives(|y| mollifier(y, eps), &stack(&x), 1e-7, 1e-5, scale);
    }
}

#[test]
fn mollifier_is_one_with_zero_derivatives_above_its_threshold() {
    let mut rng = Rng::new(10);
    let x = skew_edges(&mut rng, 0.5);
    let eps = mollifier_threshold(x[0], x[1], x[2], x[3]);
    let m = edge_edge_mollifier(x[0], x[1], x[2], x[3], eps);
    assert_eq!(m, Derivatives::constant(1.0));
    // C¹ at c = ε: m → 1 and m' → 0 from below.
    let (a0, a1, b0) = (Vec3::zeros(), Vec3::x(), Vec3::new(0.0, 0.0, 1.0));
    let b1 = b0 + Vec3::new(1.0, 1e-3, 0.0);
    let c = (a1 - a0).cross(&(b1 - b0)).norm_squared();
    let below = edge_edge_mollifier(a0, a1, b0, b1, c * (1.0 + 1e-9));
    let half = edge_edge_mollifier(a0, a1, b0, b1, 2.0 * c);
    assert!((below.value - 1.0).abs() < 1e-12);
    assert!(below.gradient.amax() <= 1e-8 * half.gradient.amax());
}
