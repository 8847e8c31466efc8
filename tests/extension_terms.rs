//! A term a scene adds beyond its springs, elements, gravity and air
//! damping ([`SystemBuilder::term`]) is seen by every integrator: the
//! implicit step minimises it and holds it to the energy test, the explicit
//! integrators feel its force, the energy and the spectrum count it.

use hooke::core::term::{At, Hessian, Potential, Term, When};
use hooke::core::{BuildError, SymBlock};
use hooke::implicit::{FastMassSpring, Minimizer};
use hooke::prelude::*;

/// A linear spring of stiffness `k` from particle `i` to the fixed point
/// `p`: `V = ½k|xᵢ − p|²`, force `−k(xᵢ − p)`, stiffness `k I`.
#[derive(Debug, Clone)]
struct Anchor {
    i: usize,
    p: Vec3,
    k: f64,
}

impl Anchor {
    fn potential(&self, x: &[Vec3]) -> Potential {
        Potential::non_negative(0.5 * self.k * (x[self.i] - self.p).norm_squared())
    }
}

impl Term for Anchor {
    fn name(&self) -> &'static str {
        "anchor"
    }

    fn problem(&self, system: &System) -> Option<String> {
        let n = system.particle_count();
        (self.i >= n).then(|| format!("particle {} is out of range ({n} particles)", self.i))
    }

    fn value(&mut self, _: &System, at: &At<'_>) -> Potential {
        self.potential(at.x)
    }

    /// `b −= βh k (xᵢ − p)`, `−βh k uᵢ` more at a linearisation, and the
    /// Hessian `β²h² k I`.
    fn add(&mut self, _: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        let bh = at.beta_h;
        b[self.i] -= bh * self.k * (at.x[self.i] - self.p);
        if let Some(u) = at.displacement {
            b[self.i] -= bh * self.k * u[self.i];
        }
        hessian.add_row(self.i, SymBlock::scaled_identity(bh * bh * self.k));
    }

    fn energy(&mut self, _: &System, x: &[Vec3], _: &[Vec3], _: When) -> Potential {
        self.potential(x)
    }

    fn force(&self, _: &System, x: &[Vec3], _: &[Vec3], f: &mut [Vec3]) {
        f[self.i] -= self.k * (x[self.i] - self.p);
    }

    fn rates(&self, _: &System, w: &[f64], stiffness: &mut [f64], _: &mut [f64]) {
        stiffness[self.i] += self.k * w[self.i] * w[self.i];
    }

    fn stiffness(&self, _: &System, _: &[Vec3], k: &mut dyn Hessian) {
        k.add_row(self.i, SymBlock::scaled_identity(self.k));
    }
}

/// A uniform force field `F` on every particle: `V = −Σ F·xᵢ`.
#[derive(Debug, Clone)]
struct Field(Vec3);

impl Field {
    fn potential(&self, x: &[Vec3]) -> Potential {
        x.iter().fold(Potential::ZERO, |sum, xi| {
            let e = -self.0.dot(xi);
            sum + Potential {
                value: e,
                magnitude: e.abs(),
            }
        })
    }
}

impl Term for Field {
    fn name(&self) -> &'static str {
        "field"
    }

    fn value(&mut self, _: &System, at: &At<'_>) -> Potential {
        self.potential(at.x)
    }

    fn add(&mut self, _: &System, at: &At<'_>, b: &mut [Vec3], _: &mut dyn Hessian) {
        for bi in b {
            *bi += at.beta_h * self.0;
        }
    }

    fn energy(&mut self, _: &System, x: &[Vec3], _: &[Vec3], _: When) -> Potential {
        self.potential(x)
    }

    fn force(&self, _: &System, _: &[Vec3], _: &[Vec3], f: &mut [Vec3]) {
        for fi in f {
            *fi += self.0;
        }
    }
}

const MASS: f64 = 0.5;
const STIFFNESS: f64 = 50.0;
const GRAVITY: [f64; 3] = [0.0, -9.81, 0.0];

/// The point the anchor pulls towards, and the field.
fn anchor_point() -> Vec3 {
    Vec3::new(0.3, 1.0, -0.2)
}

fn field() -> Vec3 {
    Vec3::new(2.0, 0.5, -1.0)
}

/// A particle of mass `m` held by the anchor `k` at `p` under gravity and
/// the field, starting at rest at `p`: its equilibrium is
/// `x* = p + (m g + F)/k`, about which it swings at `ω = √(k/m)`.
fn system() -> System {
    let mut b = SystemBuilder::new();
    let i = b.particle(MASS, anchor_point());
    b.gravity(GRAVITY);
    b.term(Field(field()));
    b.term(Anchor {
        i,
        p: anchor_point(),
        k: STIFFNESS,
    });
    b.build().unwrap()
}

fn equilibrium() -> Vec3 {
    anchor_point() + (MASS * Vec3::from(GRAVITY) + field()) / STIFFNESS
}

/// Backward Euler damps the swing by `1/√(1 + (hω)²)` a step; at `hω = 5`
/// thirty steps leave the particle at the equilibrium of gravity, the field
/// and the anchor, with Newton's method and with L-BFGS (which sees the
/// terms through their gradient alone, and whose initial Hessian, the
/// mass matrix, lacks the anchor's stiffness), each converged to 10⁻¹⁰.
/// Every step converges and passes the energy test: the terms' energies
/// are counted, so the field's work shows as the fall of its potential,
/// not as a gain.
#[test]
fn the_implicit_step_comes_to_rest_where_the_terms_balance() {
    let system = system();
    let h = 5.0 / (STIFFNESS / MASS).sqrt();
    for minimizer in [Minimizer::Newton, Minimizer::quasi_newton()] {
        let mut state = system.initial_state();
        let mut integrator = Implicit::backward_euler()
            .with_minimizer(minimizer)
            .with_newton(100, 1e-10)
            .unwrap();
        for _ in 0..30 {
            let report = integrator.step(&system, &mut state, h).unwrap();
            assert_eq!(report.unconverged_steps, 0, "{minimizer:?}");
            assert_eq!(report.energy_corrections, 0, "{minimizer:?}");
            assert_eq!(report.rejected_steps, 0, "{minimizer:?}");
        }
        let x = state.positions()[0];
        let offset = (equilibrium() - anchor_point()).norm();
        assert!(
            (x - equilibrium()).norm() < 1e-8 * offset,
            "{minimizer:?}: {x} against {}",
            equilibrium()
        );
    }
}

/// Velocity Verlet swings the particle about the equilibrium as the
/// undamped oscillator does, `x(t) = x* + (p − x*) cos ωt`, and keeps the
/// energy, the terms' included, to the order of `(ω dt)²`; the spectrum
/// finds `ω` from the anchor's stiffness alone.
#[test]
fn explicit_integrators_the_energy_and_the_spectrum_see_the_terms() {
    let system = system();
    let omega = (STIFFNESS / MASS).sqrt();
    let spectrum = hooke::lab::omega_max(&system);
    assert!((spectrum.omega_max - omega).abs() < 1e-9 * omega);

    let mut state = system.initial_state();
    let start = system.energy(&state).unwrap();
    let expected_start =
        -field().dot(&anchor_point()) - MASS * Vec3::from(GRAVITY).dot(&anchor_point());
    assert!((start.terms - (-field().dot(&anchor_point()))).abs() < 1e-15);
    assert!((start.total() - expected_start).abs() < 1e-12);

    let dt = 1e-3;
    let mut integrator = VelocityVerlet::new();
    let mut drift: f64 = 0.0;
    for _ in 0..1000 {
        integrator.step(&system, &mut state, dt).unwrap();
        let energy = system.energy(&state).unwrap().total();
        drift = drift.max((energy - start.total()).abs());
    }
    let t = state.time();
    let exact = equilibrium() + (anchor_point() - equilibrium()) * (omega * t).cos();
    let amplitude = (anchor_point() - equilibrium()).norm();
    let x = state.positions()[0];
    assert!((x - exact).norm() < 1e-3 * amplitude, "{x} against {exact}");
    let scale = 0.5 * STIFFNESS * amplitude * amplitude;
    assert!(drift < 1e-4 * scale, "energy drift {drift} of {scale}");
}

/// Fast mass-spring takes the terms' forces at each iterate, as it does
/// the volume elements': a free particle under gravity and the field moves
/// as backward Euler moves it under the constant acceleration
/// `a = g + F/m`, `x_N = x₀ + h² a N(N + 1)/2`.
#[test]
fn fast_mass_spring_feels_the_terms() {
    let mut b = SystemBuilder::new();
    b.particle(MASS, anchor_point());
    b.gravity(GRAVITY);
    b.term(Field(field()));
    let system = b.build().unwrap();
    let mut state = system.initial_state();
    let mut integrator = FastMassSpring::default();
    let (h, steps) = (0.01, 20);
    for _ in 0..steps {
        integrator.step(&system, &mut state, h).unwrap();
    }
    let a = Vec3::from(GRAVITY) + field() / MASS;
    let n = steps as f64;
    let expected = anchor_point() + h * h * a * n * (n + 1.0) / 2.0;
    let x = state.positions()[0];
    assert!((x - expected).norm() < 1e-12, "{x} against {expected}");
}

/// A term that does not fit the system is named at the build.
#[test]
fn a_term_naming_a_missing_particle_is_refused() {
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0; 3]);
    b.term(Anchor {
        i: 3,
        p: Vec3::zeros(),
        k: 1.0,
    });
    let error = b.build().unwrap_err();
    assert!(
        matches!(
            error,
            BuildError::InvalidTerm {
                term: 0,
                name: "anchor",
                ..
            }
        ),
        "{error}"
    );
}
