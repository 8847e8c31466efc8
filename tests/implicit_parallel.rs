//! Above `PARALLEL_MIN_PARTICLES` the assembly and the matrix-vector product
//! run in parallel, and above `PARALLEL_MIN_ELEMENTS` the volume elements'
//! blocks; they agree with sequential computations done here from the
//! spring and element formulas and with faer's scalar sparse product.
#![cfg(feature = "parallel")]

use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::{Accum, MatMut, MatRef, Par};
use hooke::core::{At, CompressedSprings, StepStart, TetHessian};
use hooke::implicit::Terms;
use hooke::implicit::internals::{
    BlockJacobi, BlockMatrix, PARALLEL_MIN_ELEMENTS, PARALLEL_MIN_PARTICLES, Pattern,
};
use hooke::prelude::*;
use hooke::scenes::{Lattice, TetSplit, Volume};

#[test]
fn parallel_assembly_and_product_match_sequential_computations() {
    let side = (PARALLEL_MIN_PARTICLES as f64).sqrt().ceil() as usize + 1;
    let system = Sheet {
        damping: 0.3,
        air_damping: 0.02,
        ..Sheet::new(side)
    }
    .system()
    .unwrap();
    let n = system.particle_count();
    let mut state = system.initial_state();
    for (k, x) in state.positions_mut().iter_mut().enumerate() {
        *x *= 1.0 + 0.1 * (k as f64 * 0.37).sin();
    }
    for (k, v) in state.velocities_mut().iter_mut().enumerate() {
        *v = Vec3::new((k as f64).cos(), (k as f64 * 0.3).sin(), 0.2);
    }
    let (x, v) = (state.positions(), state.velocities());
    let h = 0.01;
    let u: Vec<Vec3> = v.iter().map(|vi| h * vi).collect();
    let mut a = BlockMatrix::zeros(Pattern::new(&system).unwrap());
    let (mut jacobi, mut b) = (BlockJacobi::default(), vec![Vec3::zeros(); n]);
    let at = At {
        x,
        v,
        v_tilde: v,
        beta_h: h,
        displacement: Some(&u),
        compressed: CompressedSprings::Clamped,
    };
    Terms::new(&system)
        .unwrap()
        .assemble(&system, &at, &mut a, &mut jacobi, &mut b, 0.0)
        .unwrap();

    // Sequentially, from the spring formulas: A = M + hC + h²K, b = h(f − K u).
    let masses = system.masses();
    let gamma = system.air_damping().unwrap();
    let mut diagonal: Vec<_> = masses
        .iter()
        .map(|&m| (m + h * gamma) * hooke::core::Mat3::identity())
        .collect();
    let mut rhs: Vec<Vec3> = (0..n)
        .map(|i| h * (masses[i] * Vec3::new(0.0, -9.81, 0.0) - gamma * v[i]))
        .collect();
    for (s, spring) in system.springs().iter().enumerate() {
        let (i, j) = (spring.i, spring.j);
        let k = h * h * spring.stiffness_block(x[i], x[j], CompressedSprings::Clamped)
            + h * spring.damping_block(x[i], x[j]);
        assert!(
            (a.spring_block(s) - k).norm() <= 1e-12 * k.norm().max(1e-300),
            "spring {s}"
        );
        diagonal[i] += k;
        diagonal[j] += k;
        let stiffness = spring.stiffness_block(x[i], x[j], CompressedSprings::Clamped);
        let share = h * (spring.force(x[i], x[j], v[i], v[j]) - stiffness * (u[i] - u[j]));
        rhs[i] += share;
        rhs[j] -= share;
    }
    for i in 0..n {
        assert!(
            (a.diagonal(i) - diagonal[i]).norm() <= 1e-12 * diagonal[i].norm(),
            "diagonal {i}"
        );
        assert!(
            (b[i] - rhs[i]).norm() <= 1e-10 * (1.0 + rhs[i].norm()),
            "rhs {i}: {:?} vs {:?}",
            b[i],
            rhs[i]
        );
    }

    // The parallel block product against faer's sequential scalar product.
    let mut y = vec![Vec3::zeros(); n];
    a.apply(v, &mut y);
    let flat: Vec<f64> = v.iter().flat_map(|vi| vi.iter().copied()).collect();
    let mut expected = vec![0.0; 3 * n];
    let scalar = a.to_scalar();
    sparse_dense_matmul(
        MatMut::from_column_major_slice_mut(&mut expected, 3 * n, 1),
        Accum::Replace,
        scalar.as_ref(),
        MatRef::from_column_major_slice(&flat, 3 * n, 1),
        1.0,
        Par::Seq,
    );
    for i in 0..n {
        let e = Vec3::from_column_slice(&expected[3 * i..3 * i + 3]);
        assert!(
            (y[i] - e).norm() <= 1e-10 * (1.0 + e.norm()),
            "product row {i}: {:?} vs {e:?}",
            y[i]
        );
    }
}

/// A tet lattice with more than [`PARALLEL_MIN_ELEMENTS`] elements, its
/// vertices moved (some elements compressed, some stretched): the assembled
/// step at a Newton iterate holds `h²` times each element's projected
/// Hessian and `−h` times its gradient, summed here element by element.
#[test]
fn parallel_element_blocks_match_sequential_sums() {
    // The lattice with its elements, and without them for the springs'
    // share of the product.
    let [system, springs_only] = [Volume::Auto, Volume::Off].map(|volume| {
        let lattice = Lattice::tets(12, 12, 12, TetSplit::Six)
            .size([0.3, 0.3, 0.3])
            .edges(1e3)
            .volume(volume)
            .build()
            .unwrap();
        let mut builder = SystemBuilder::new();
        lattice.add_to(&mut builder);
        builder.build().unwrap()
    });
    assert!(system.tets().len() >= PARALLEL_MIN_ELEMENTS);
    let n = system.particle_count();
    let x: Vec<Vec3> = system
        .initial_positions()
        .iter()
        .enumerate()
        .map(|(k, p)| p + 0.01 * Vec3::new((k as f64).sin(), (1.7 * k as f64).cos(), 0.0))
        .collect();
    let v = vec![Vec3::zeros(); n];
    let h = 0.01;
    let at = At {
        x: &x,
        v: &v,
        v_tilde: &v,
        beta_h: h,
        displacement: None,
        compressed: CompressedSprings::Clamped,
    };
    let step = StepStart {
        x: &x,
        v: &v,
        time: 0.0,
        h,
        beta_h: h,
    };
    let [a, a_springs] = [&system, &springs_only].map(|system| {
        let mut a = BlockMatrix::zeros(Pattern::new(system).unwrap());
        let (mut jacobi, mut b) = (BlockJacobi::default(), vec![Vec3::zeros(); n]);
        let mut terms = Terms::new(system).unwrap();
        terms.begin(system, &step);
        terms
            .assemble(system, &at, &mut a, &mut jacobi, &mut b, 0.0)
            .unwrap();
        (a, b)
    });
    let ((a, b), (springs_only, _)) = (a, a_springs);
    let w: Vec<Vec3> = (0..n)
        .map(|k| Vec3::new(1.0, (k as f64).cos(), 0.1 * k as f64))
        .collect();
    let (mut with, mut without) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
    a.apply(&w, &mut with);
    springs_only.apply(&w, &mut without);
    let (mut product, mut rhs) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
    for s in system.springs() {
        let share = h * s.elastic_force(x[s.i], x[s.j]);
        rhs[s.i] += share;
        rhs[s.j] -= share;
    }
    for t in system.tets() {
        let d = t.derivatives(&x, TetHessian::Projected);
        for (p, &i) in t.vertices.iter().enumerate() {
            rhs[i] -= h * d.gradient[p];
            for (q, &j) in t.vertices.iter().enumerate() {
                product[i] += h * h * d.hessian.fixed_view::<3, 3>(3 * p, 3 * q) * w[j];
            }
        }
    }
    for i in 0..n {
        let error = (with[i] - without[i] - product[i]).norm();
        assert!(
            error <= 1e-10 * (1.0 + product[i].norm()),
            "product row {i} off by {error}"
        );
        let error = (b[i] - rhs[i]).norm();
        assert!(
            error <= 1e-10 * (1.0 + rhs[i].norm()),
            "rhs {i} off by {error}"
        );
    }
}
