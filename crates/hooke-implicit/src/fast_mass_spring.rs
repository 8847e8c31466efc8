//! [`FastMassSpring`]: Liu, Bargteil, O'Brien & Kavan, *Fast Simulation of
//! Mass-Spring Systems* (SIGGRAPH Asia 2013) — backward Euler by
//! local/global iterations on a constant, prefactored matrix.
//!
//! It is an integrator of its own beside [`Implicit`](crate::Implicit),
//! not a minimiser of the implicit step's `Φ`: it minimises its own
//! objective over the positions, split into a constant quadratic and a
//! projection per spring, for a fixed number of iterations without a line
//! search, a stopping rule, an energy test or substeps, and resolves
//! contacts after the step as the explicit methods do — the paper's method
//! as published, which the lab measures against the implicit step. Inside
//! the implicit step its matrix is the quasi-Newton minimiser's initial
//! Hessian ([`Minimizer::QuasiNewton`](crate::Minimizer::QuasiNewton)).

use hooke_core::{
    Integrator, Named, Parameter, ParameterError, State, StepBuffers, StepError, StepReport,
    System, Vec3,
};

use crate::linear::cholesky::WeakSprings;
use crate::linear::laplacian::{Inverse, Laplacian};
use crate::linear::solver::LinearSolver;

/// Backward Euler for springs as Liu et al. (2013) solve it.
///
/// A backward-Euler step minimises over the new positions
///
/// ```text
/// g(x) = ½ (x − y)ᵀ M (x − y) + h² E(x) − h² xᵀ f_ext,   y = xₙ + h vₙ,
/// ```
///
/// (`∇g = 0` is `M(x − xₙ − h vₙ) = h² f(x)`, the scheme with
/// `vₙ₊₁ = (x − xₙ)/h`). Each spring's energy is written with an auxiliary
/// direction `dₛ` of the rest length, `½k(|xᵢ − xⱼ| − L)² = min_{|d| = L}
/// ½k |xᵢ − xⱼ − d|²`, and `g` is minimised alternately over the `d` (the
/// local step: `dₛ = L (xᵢ − xⱼ)/|xᵢ − xⱼ|`, spring by spring) and over `x`
/// (the global step: one solve with the constant matrix
/// `M + h² L`, `L = Σₛ kₛ (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ`, the same for the three
/// coordinates):
///
/// ```text
/// (M + h² L) x = M y + h² (J d + f_ext),   J d = Σₛ kₛ (eᵢ − eⱼ) dₛᵀ.
/// ```
///
/// Each iteration lowers `g`; the fixed point is the backward-Euler step,
/// approached linearly (the rate worsens with the stiffness: the paper
/// takes a fixed, small number of iterations, 10 by default here, and
/// accepts the error). `M + h² L` depends on the topology, masses,
/// stiffnesses and `h` only, so it is factorized (faer's sparse Cholesky,
/// `n × n` for `n` free particles) once and every iteration costs a local
/// step and three triangular solve pairs.
///
/// Volume elements ([`hooke_core::Tet`]) and the system's own terms
/// ([`System::terms`]) have no such splitting into a constant quadratic and
/// a projection; their forces at the current iterate (its velocities
/// `(x − xₙ)/h`) join `f_ext` in the global step. The fixed point is still
/// the backward-Euler step; the matrix stays constant, so where they are
/// stiffer than the springs the iteration converges slowly or not at all.
///
/// Pinned particles are removed unknowns: they move with their path's
/// velocity (at rest for plain pins), and their springs' terms move to the
/// right-hand side. Gravity is the external force; spring and air damping
/// are not part of this scheme (the paper damps separately) and are left
/// out. Obstacles are not part of the solve either: contacts are resolved
/// after each step, as for the explicit methods ([`System::end_step`]).
#[derive(Debug)]
pub struct FastMassSpring {
    iterations: usize,
    matrix: Option<Laplacian>,
    out: StepBuffers,
    y: Vec<Vec3>,
    d: Vec<Vec3>,
    /// The volume elements' and the system's own terms' forces at the
    /// current iterate.
    forces: Vec<Vec3>,
}

impl FastMassSpring {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "fast-mass-spring";
    /// The default number of local/global iterations per step (the paper's).
    pub const ITERATIONS: usize = 10;

    /// The method with `iterations` local/global iterations per step.
    ///
    /// ```
    /// let integrator = hooke_implicit::FastMassSpring::new(10)?;
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] for zero iterations.
    pub fn new(iterations: usize) -> Result<Self, ParameterError> {
        if iterations == 0 {
            return Err(ParameterError::new(
                Self::NAME,
                Parameter::Iterations,
                0.0,
                "at least 1",
            ));
        }
        Ok(Self {
            iterations,
            matrix: None,
            out: StepBuffers::default(),
            y: Vec::new(),
            d: Vec::new(),
            forces: Vec::new(),
        })
    }

    /// The local/global iterations per step.
    #[must_use]
    pub fn iterations(&self) -> usize {
        self.iterations
    }
}

impl Default for FastMassSpring {
    /// [`FastMassSpring::ITERATIONS`] iterations.
    fn default() -> Self {
        Self {
            iterations: Self::ITERATIONS,
            matrix: None,
            out: StepBuffers::default(),
            y: Vec::new(),
            d: Vec::new(),
            forces: Vec::new(),
        }
    }
}

impl Integrator for FastMassSpring {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let Self {
            iterations,
            matrix,
            out,
            y,
            d,
            forces,
        } = self;
        out.begin(Self::NAME, system, state, dt, [&mut *y])?;
        d.resize(system.springs().len(), Vec3::zeros());
        let weights = (0.0, |s: &hooke_core::Spring| dt * dt * s.stiffness);
        match matrix {
            Some(m) if m.matches(system, dt.to_bits()) => {}
            Some(m) if m.is_for(system) => {
                m.refactor(system, weights, (dt.to_bits(), &[]), state.time())?;
            }
            _ => {
                *matrix = Some(Laplacian::new(
                    system,
                    weights,
                    (dt.to_bits(), &[]),
                    // Its fixed point minimises Φ only with each spring's
                    // own term in the matrix, as in its right-hand side.
                    (Inverse::Factor, WeakSprings::Kept),
                    state.time(),
                )?);
            }
        }
        let prefactored = matrix.as_mut().expect("factorized above");
        let (x0, v0, time) = (state.positions(), state.velocities(), state.time());
        let gravity = system.gravity().unwrap_or_else(Vec3::zeros);
        let masses = system.masses();
        for (i, yi) in y.iter_mut().enumerate() {
            *yi = x0[i] + dt * v0[i];
        }
        for &(i, ref path) in system.pin_paths() {
            y[i] = x0[i] + dt * path.velocity(time + dt);
        }
        let x = &mut out.x;
        x.copy_from_slice(y);
        let h2 = dt * dt;
        for _ in 0..*iterations {
            for (s, ds) in system.springs().iter().zip(d.iter_mut()) {
                let e = x[s.i] - x[s.j];
                let length = e.norm();
                *ds = if length > 0.0 {
                    e * (s.rest_length / length)
                } else {
                    Vec3::zeros()
                };
            }
            forces.clear();
            forces.resize(x.len(), Vec3::zeros());
            system.add_volume_forces(x, forces);
            if !system.terms().is_empty() {
                for ((v, xi), x0i) in out.v.iter_mut().zip(x.iter()).zip(x0) {
                    *v = (xi - x0i) / dt;
                }
                for term in system.terms() {
                    term.force(system, x, &out.v, forces);
                }
            }
            // The three coordinates' right-hand sides, one after the other,
            // solved in one pass over the factor.
            let rhs = &mut prefactored.rhs;
            let free = rhs.len() / 3;
            for c in 0..3 {
                let rhs = &mut rhs[c * free..(c + 1) * free];
                for (i, &u) in prefactored.unknown.iter().enumerate() {
                    if u != u32::MAX {
                        rhs[u as usize] =
                            masses[i] * (y[i][c] + h2 * gravity[c]) + h2 * forces[i][c];
                    }
                }
                for (s, ds) in system.springs().iter().zip(d.iter()) {
                    let w = h2 * s.stiffness;
                    let (ui, uj) = (prefactored.unknown[s.i], prefactored.unknown[s.j]);
                    if ui != u32::MAX {
                        rhs[ui as usize] += w * ds[c];
                        if uj == u32::MAX {
                            rhs[ui as usize] += w * y[s.j][c];
                        }
                    }
                    if uj != u32::MAX {
                        rhs[uj as usize] -= w * ds[c];
                        if ui == u32::MAX {
                            rhs[uj as usize] += w * y[s.i][c];
                        }
                    }
                }
            }
            prefactored.solve();
            let rhs = &prefactored.rhs;
            for (xi, &u) in x.iter_mut().zip(&prefactored.unknown) {
                if u != u32::MAX {
                    *xi = Vec3::from_fn(|c, _| rhs[c * free + u as usize]);
                }
            }
        }
        for ((v, xi), x0i) in out.v.iter_mut().zip(x.iter()).zip(x0) {
            *v = (xi - x0i) / dt;
        }
        let report = StepReport {
            accepted_steps: 1,
            force_evaluations: *iterations,
            newton_iterations: *iterations,
            newton_iterations_max: *iterations,
            linear_solves: *iterations,
            linear_solver: LinearSolver::Cholesky.name(),
            ..StepReport::default()
        };
        out.finish(system, state, dt, report)
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Implicit, LinearSolver};
    use hooke_core::reference::Sheet;

    /// Liu's fixed point is the backward-Euler step: from a moving, stretched
    /// sheet, the difference to a converged backward-Euler step (Newton to
    /// 10⁻¹² on the same undamped system) shrinks as the local/global
    /// iterations grow.
    #[test]
    fn iterations_converge_to_the_backward_euler_step() {
        let system = Sheet {
            stiffness: 500.0,
            damping: 0.0,
            air_damping: 0.0,
            ..Sheet::new(8)
        }
        .system()
        .unwrap();
        let mut start = system.initial_state();
        for (k, x) in start.positions_mut().iter_mut().enumerate() {
            *x *= 1.03;
            x.y = 0.01 * (0.9 * k as f64).sin();
        }
        for (k, v) in start.velocities_mut().iter_mut().enumerate() {
            *v = Vec3::new(0.2 * (k as f64).cos(), -0.3, 0.1);
        }
        let h = 1.0 / 60.0;
        let mut reference = start.clone();
        Implicit::backward_euler()
            .with_solver(LinearSolver::Cholesky)
            .with_newton(100, 1e-12)
            .unwrap()
            .with_max_halvings(0)
            .step(&system, &mut reference, h)
            .unwrap();
        let errors: Vec<f64> = [1, 10, 100, 2000]
            .into_iter()
            .map(|iterations| {
                let mut state = start.clone();
                FastMassSpring::new(iterations)
                    .unwrap()
                    .step(&system, &mut state, h)
                    .unwrap();
                state
                    .positions()
                    .iter()
                    .zip(reference.positions())
                    .map(|(p, q)| (p - q).norm())
                    .fold(0.0, f64::max)
            })
            .collect();
        // Linear convergence, slow on a stiff sheet (about 0.995 per
        // iteration here): 10 iterations leave 60 % of one iteration's
        // error, 2 000 reach 10⁻⁶ m.
        assert!(
            errors.windows(2).all(|w| w[1] < 0.7 * w[0]),
            "errors {errors:?}"
        );
        assert!(
            errors[3] < 1e-6 && errors[3] < 1e-3 * errors[2],
            "errors {errors:?}"
        );
    }

    #[test]
    fn zero_iterations_is_an_error() {
        assert!(FastMassSpring::new(0).is_err());
    }
}
