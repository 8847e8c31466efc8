//! The scalar hierarchy on the bench cloth's `H₀`: one cycle is a fixed
//! symmetric positive-definite operator, and PCG with it barely slows as
//! the mesh grows.

use hooke_core::reference::Sheet;

use super::*;

/// `M + h² Σₛ kₛ (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ` of the solver benchmarks' cloth
/// ([`Sheet::cloth`]) of `side × side` particles, `h = 1/60 s`, its pinned
/// particles kept.
fn cloth(side: usize) -> Csr {
    let system = Sheet::cloth(side, 0.0).system().unwrap();
    let h2 = (1.0f64 / 60.0).powi(2);
    let mut rows: Vec<Vec<(u32, f64)>> = system
        .masses()
        .iter()
        .enumerate()
        .map(|(i, &m)| vec![(i as u32, m)])
        .collect();
    for s in system.springs() {
        let w = h2 * s.stiffness;
        for (r, c, v) in [(s.i, s.i, w), (s.j, s.j, w), (s.i, s.j, -w), (s.j, s.i, -w)] {
            match rows[r].iter_mut().find(|e| e.0 as usize == c) {
                Some(e) => e.1 += v,
                None => rows[r].push((c as u32, v)),
            }
        }
    }
    let mut a = Csr {
        row_ptr: vec![0],
        ..Csr::default()
    };
    for mut row in rows {
        row.sort_unstable_by_key(|e| e.0);
        a.col_idx.extend(row.iter().map(|e| e.0));
        a.values.extend(row.iter().map(|e| e.1));
        a.row_ptr.push(a.col_idx.len());
    }
    a
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// A vector that looks random in its index and `seed`.
fn noise(n: usize, seed: usize) -> Vec<f64> {
    (0..n)
        .map(|i| ((i * 7919 + seed * 104_729) % 1000) as f64 / 500.0 - 1.0)
        .collect()
}

/// PCG on `a x = b` from zero with one V-cycle as the preconditioner, to
/// `‖b − a x‖ ≤ 10⁻⁸ ‖b‖`; returns its iterations.
fn pcg(amg: &mut ScalarAmg, a: &Csr, b: &[f64]) -> usize {
    let n = b.len();
    let (mut x, mut r, mut z, mut q) = (vec![0.0; n], b.to_vec(), vec![0.0; n], vec![0.0; n]);
    amg.apply(a, &r, &mut z);
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let goal = 1e-8 * dot(b, b).sqrt();
    for iteration in 1..=200 {
        a.apply(&p, &mut q);
        let alpha = rz / dot(&p, &q);
        x.iter_mut().zip(&p).for_each(|(xi, pi)| *xi += alpha * pi);
        r.iter_mut().zip(&q).for_each(|(ri, qi)| *ri -= alpha * qi);
        if dot(&r, &r).sqrt() <= goal {
            // The recurrence's residual is the true one.
            a.apply(&x, &mut q);
            let true_residual: f64 = b
                .iter()
                .zip(&q)
                .map(|(bi, qi)| (bi - qi).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(true_residual <= 2.0 * goal, "{true_residual} {goal}");
            return iteration;
        }
        amg.apply(a, &r, &mut z);
        let next = dot(&r, &z);
        p.iter_mut()
            .zip(&z)
            .for_each(|(pi, zi)| *pi = zi + next / rz * *pi);
        rz = next;
    }
    panic!("PCG did not converge in 200 iterations");
}

/// L-BFGS needs its `H₀⁻¹` to be one fixed symmetric positive-definite
/// operator: `uᵀ B v = vᵀ B u` and `uᵀ B u > 0` for the cycle `B`.
#[test]
fn one_cycle_is_a_symmetric_positive_definite_operator() {
    let a = cloth(80);
    let mut amg = ScalarAmg::build(&a).unwrap();
    assert!(amg.unknowns(&a).len() >= 2, "{:?}", amg.unknowns(&a));
    let n = a.rows();
    let (u, v) = (noise(n, 1), noise(n, 2));
    let (mut bu, mut bv) = (vec![0.0; n], vec![0.0; n]);
    amg.apply(&a, &u, &mut bu);
    amg.apply(&a, &v, &mut bv);
    let (ubv, vbu) = (dot(&u, &bv), dot(&v, &bu));
    assert!(
        (ubv - vbu).abs() <= 1e-10 * ubv.abs().max(vbu.abs()),
        "{ubv} {vbu}"
    );
    assert!(dot(&u, &bu) > 0.0 && dot(&v, &bv) > 0.0);
}

/// Multigrid's point: PCG with one cycle takes about as many iterations
/// on a mesh 16 times larger (Jacobi-preconditioned CG would take four
/// times as many).
#[test]
fn iterations_barely_grow_with_the_mesh() {
    let mut counts = Vec::new();
    for side in [50, 200] {
        let a = cloth(side);
        let mut amg = ScalarAmg::build(&a).unwrap();
        counts.push(pcg(&mut amg, &a, &noise(a.rows(), 3)));
    }
    assert!(
        counts[1] <= 25 && counts[1] as f64 <= 1.5 * counts[0] as f64,
        "{counts:?}"
    );
}

/// Springs a thousand times softer than the masses make no connection
/// strong; the hierarchy still coarsens (instead of factorizing the
/// whole matrix), and PCG with it converges at once.
#[test]
fn a_matrix_without_strong_connections_still_coarsens() {
    let mut a = cloth(60);
    for i in 0..a.rows() {
        for k in a.row_ptr[i]..a.row_ptr[i + 1] {
            if a.col_idx[k] as usize != i {
                a.values[k] *= 1e-7;
            }
        }
    }
    // Each diagonal is its mass plus the softened springs' weights.
    for i in 0..a.rows() {
        let off: f64 = (a.row_ptr[i]..a.row_ptr[i + 1])
            .filter(|&k| a.col_idx[k] as usize != i)
            .map(|k| -a.values[k])
            .sum();
        let diagonal = (a.row_ptr[i]..a.row_ptr[i + 1])
            .find(|&k| a.col_idx[k] as usize == i)
            .unwrap();
        a.values[diagonal] = 1.0 / 3600.0 + off;
    }
    let mut amg = ScalarAmg::build(&a).unwrap();
    assert!(amg.unknowns(&a).len() >= 2, "{:?}", amg.unknowns(&a));
    assert!(pcg(&mut amg, &a, &noise(a.rows(), 5)) <= 10);
}

/// A matrix within the coarsest level's size is factorized whole, and
/// one application solves it.
#[test]
fn a_small_matrix_is_solved_exactly() {
    let a = cloth(20);
    let mut amg = ScalarAmg::build(&a).unwrap();
    assert_eq!(amg.unknowns(&a), [400]);
    let x = noise(400, 4);
    let mut b = vec![0.0; 400];
    a.apply(&x, &mut b);
    let mut solved = vec![0.0; 400];
    amg.apply(&a, &b, &mut solved);
    for (s, x) in solved.iter().zip(&x) {
        assert!((s - x).abs() < 1e-9, "{s} {x}");
    }
}
