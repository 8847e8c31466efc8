//! Tests of the volume elements' terms of `Φ` and of the passes that
//! evaluate them.

use super::*;
use crate::linear::cg::BlockJacobi;
use crate::linear::cholesky::SparseCholesky;
use crate::linear::filter::Filter;
use crate::minimize::terms::{Terms, assembled};
use hooke_core::SystemBuilder;

/// Two tetrahedra sharing a face, of moduli `moduli`, on five
/// particles of 0.5 kg, with springs of 50 N/m and damping `damping`
/// between the pairs `springs`; then `finish` (gravity, damping) and
/// the build. Also returns positions where the first element is
/// inverted (its apex through the shared face).
pub(in crate::minimize::terms) fn two_tets(
    springs: impl IntoIterator<Item = (usize, usize)>,
    damping: f64,
    moduli: [f64; 2],
    finish: impl FnOnce(&mut SystemBuilder),
) -> (System, Vec<Vec3>) {
    let mut b = SystemBuilder::new();
    let rest = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.2, 0.0, 0.9],
        [0.3, 0.8, 0.2],
        [0.4, -0.9, 0.3],
    ];
    let p: Vec<usize> = rest.iter().map(|&x| b.particle(0.5, x)).collect();
    for (i, j) in springs {
        b.spring(p[i], p[j], 50.0).damping(damping);
    }
    b.tet([p[0], p[1], p[2], p[3]], moduli[0]);
    b.tet([p[0], p[1], p[2], p[4]], moduli[1]);
    finish(&mut b);
    let system = b.build().unwrap();
    let mut x = system.initial_positions().to_vec();
    x[3] = Vec3::new(0.35, -0.3, 0.25);
    (system, x)
}

/// [`two_tets`] with springs on some of their edges, gravity and air
/// damping, and a second vertex moved too.
pub(in crate::minimize::terms) fn system() -> (System, Vec<Vec3>) {
    let springs = [(0, 1), (1, 2), (2, 3), (3, 4)];
    let (system, mut x) = two_tets(springs, 0.3, [2e3, 5e2], |b| {
        b.gravity([0.0, -9.81, 0.0]).air_damping(0.1);
    });
    x[1] += Vec3::new(0.2, 0.1, -0.1);
    (system, x)
}

/// [`system`] at velocities `v` about `x̃` with `βh = 0.02`, and the
/// predictor's velocities `ṽ`.
pub(in crate::minimize::terms) struct Fixture {
    pub(in crate::minimize::terms) system: System,
    pub(in crate::minimize::terms) x_tilde: Vec<Vec3>,
    pub(in crate::minimize::terms) v: Vec<Vec3>,
    pub(in crate::minimize::terms) v_tilde: Vec<Vec3>,
    pub(in crate::minimize::terms) beta_h: f64,
}

impl Fixture {
    pub(in crate::minimize::terms) fn new() -> Self {
        let (system, x_tilde) = system();
        let n = system.particle_count();
        Self {
            system,
            x_tilde,
            v: (0..n)
                .map(|i| Vec3::new(0.3 * i as f64, -0.2, 0.1 * (i as f64).sin()))
                .collect(),
            v_tilde: (0..n)
                .map(|i| Vec3::new(0.1, 0.2 * i as f64, 0.0))
                .collect(),
            beta_h: 0.02,
        }
    }

    /// `x̃ + βh v`.
    pub(in crate::minimize::terms) fn positions(&self, v: &[Vec3]) -> Vec<Vec3> {
        let beta_h = self.beta_h;
        self.x_tilde
            .iter()
            .zip(v)
            .map(|(x, v)| x + beta_h * v)
            .collect()
    }

    /// The point `v` with positions `x`, compressed springs `compressed`.
    pub(in crate::minimize::terms) fn at<'a>(
        &'a self,
        x: &'a [Vec3],
        v: &'a [Vec3],
        compressed: CompressedSprings,
    ) -> At<'a> {
        At {
            x,
            v,
            v_tilde: &self.v_tilde,
            beta_h: self.beta_h,
            displacement: None,
            compressed,
        }
    }

    /// `Φ(v)` with the terms' frozen directions.
    fn phi(&self, terms: &mut Terms, v: &[Vec3]) -> f64 {
        let x = self.positions(v);
        let at = self.at(&x, v, CompressedSprings::Clamped);
        terms.value(&self.system, &at).value
    }

    /// The terms, begun at a step from `x̃`: the dampers' directions are
    /// frozen there.
    pub(in crate::minimize::terms) fn terms(&self) -> Terms {
        let mut terms = Terms::new(&self.system).unwrap();
        let step = StepStart {
            x: &self.x_tilde,
            v: &self.v,
            time: 0.0,
            h: self.beta_h,
            beta_h: self.beta_h,
        };
        terms.begin(&self.system, &step);
        terms
    }
}

/// Asserts that `b` is minus the gradient of `phi` at `v` (central
/// differences).
fn assert_gradient(mut phi: impl FnMut(&[Vec3]) -> f64, v: &[Vec3], b: &[Vec3]) {
    let h = 1e-6;
    for i in 0..v.len() {
        for c in 0..3 {
            let (mut plus, mut minus) = (v.to_vec(), v.to_vec());
            plus[i][c] += h;
            minus[i][c] -= h;
            let numeric = (phi(&plus) - phi(&minus)) / (2.0 * h);
            assert!(
                (numeric + b[i][c]).abs() < 1e-6 * (1.0 + numeric.abs()),
                "∂Φ/∂v[{i}][{c}] = {numeric}, −b = {}",
                -b[i][c]
            );
        }
    }
}

/// The quasi-Newton step's passes ([`Terms::gradient`]) give the value
/// and magnitude of [`Terms::value`] and minus the gradient of `Φ` in the
/// velocities (central differences), with damped springs along frozen
/// directions, volume elements (one inverted), gravity and air damping.
#[test]
fn one_pass_gives_the_potential_and_its_gradient() {
    let f = Fixture::new();
    let (system, v) = (&f.system, &f.v);
    let x = f.positions(v);
    let at = f.at(&x, v, CompressedSprings::Clamped);
    let mut terms = f.terms();
    let mut b = vec![Vec3::zeros(); system.particle_count()];
    let both = terms.gradient(system, &at, &mut b);
    let alone = terms.value(system, &at);
    assert!((both.value - alone.value).abs() <= 1e-12 * alone.value.abs());
    assert!((both.magnitude - alone.magnitude).abs() <= 1e-12 * alone.magnitude);
    assert_gradient(|v| f.phi(&mut terms, v), v, &b);
}

/// The assembled right-hand side at a Newton iterate is minus the
/// gradient of `Φ` in the velocities (central differences of
/// [`Terms::value`]), and the matrix holds `β²h²` times each
/// element's Hessian between its vertices: the exact one with exact
/// springs, the projected one with clamped springs, and the
/// Gauss–Newton one for Baraff & Witkin's step (one element inverted,
/// where the three differ).
#[test]
fn volume_terms_are_the_potentials_derivatives() {
    let f = Fixture::new();
    let (system, beta_h) = (&f.system, f.beta_h);
    let (n, v) = (system.particle_count(), &f.v);
    let x = f.positions(v);
    // Before any step, the first evaluation freezes the damping directions
    // at its positions, x.
    let mut terms = Terms::new(system).unwrap();
    let mut a = BlockMatrix::zeros(std::sync::Arc::clone(terms.pattern()));
    let mut jacobi = BlockJacobi::default();
    let mut b = vec![Vec3::zeros(); n];
    let at = f.at(&x, v, CompressedSprings::Exact);
    terms
        .assemble(system, &at, &mut a, &mut jacobi, &mut b, 0.0)
        .unwrap();
    assert_gradient(|v| f.phi(&mut terms, v), v, &b);
    let w: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new(1.0, -0.5 * i as f64, 0.25 + i as f64))
        .collect();
    let zero = vec![Vec3::zeros(); n];
    for (compressed, displacement, kind) in [
        (CompressedSprings::Exact, None, TetHessian::Exact),
        (CompressedSprings::Clamped, None, TetHessian::Projected),
        (
            CompressedSprings::Clamped,
            Some(&zero[..]),
            TetHessian::GaussNewton,
        ),
    ] {
        let at = At {
            displacement,
            ..f.at(&x, v, compressed)
        };
        terms
            .assemble(system, &at, &mut a, &mut jacobi, &mut b, 0.0)
            .unwrap();
        let mut with = vec![Vec3::zeros(); n];
        a.apply(&w, &mut with);
        let mut springs_only = a.clone();
        springs_only.clear_extra();
        let mut without = vec![Vec3::zeros(); n];
        springs_only.apply(&w, &mut without);
        let mut expected = vec![Vec3::zeros(); n];
        for t in system.tets() {
            let hessian = t.derivatives(&x, kind).hessian;
            for (p, &i) in t.vertices.iter().enumerate() {
                for (q, &j) in t.vertices.iter().enumerate() {
                    expected[i] +=
                        beta_h * beta_h * hessian.fixed_view::<3, 3>(3 * p, 3 * q) * w[j];
                }
            }
        }
        for i in 0..n {
            let error = (with[i] - without[i] - expected[i]).norm();
            assert!(
                error < 1e-9 * expected[i].norm().max(1.0),
                "{kind:?}: row {i} off by {error}"
            );
        }
    }
}

/// Where every pair of an element's vertices is joined by a spring,
/// the Cholesky factor holds the elements' blocks and solves the
/// assembled system exactly.
#[test]
fn the_factor_solves_a_system_with_elements_on_springs() {
    let every_pair_but_3_4 = (0..5)
        .flat_map(|i| (i + 1..5).map(move |j| (i, j)))
        .filter(|&pair| pair != (3, 4));
    let (system, x) = two_tets(every_pair_but_3_4, 0.0, [2e4, 5e3], |_| {});
    let n = system.particle_count();
    let v = vec![Vec3::zeros(); n];
    let at = At {
        x: &x,
        v: &v,
        v_tilde: &v,
        beta_h: 0.1,
        displacement: None,
        compressed: CompressedSprings::Clamped,
    };
    let (a, rhs) = assembled(&mut Terms::new(&system).unwrap(), &system, &at);
    let filters = vec![Filter::Free; n];
    let mut factor = SparseCholesky::new(&a).unwrap();
    let mut solution = vec![Vec3::zeros(); n];
    factor.solve(&a, &filters, &rhs, &mut solution).unwrap();
    assert!(factor.is_complete());
    let mut product = vec![Vec3::zeros(); n];
    a.apply(&solution, &mut product);
    let scale = rhs.iter().map(|r| r.norm()).fold(0.0, f64::max);
    for (ax, r) in product.iter().zip(&rhs) {
        assert!((ax - r).norm() < 1e-10 * scale, "{ax} against {r}");
    }
}
