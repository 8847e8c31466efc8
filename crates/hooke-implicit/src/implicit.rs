//! [`Implicit`]: backward Euler and BDF2 on the assembled system.

use hooke_core::{
    CompressedSprings, History, Integrator, ParameterError, State, StepError, StepReport, System,
    Vec3, check_step,
};

use crate::assembly::{Assembler, Linearization};
use crate::cg::PcgWorkspace;
use crate::contact::Contacts;
use crate::solver::{LinearSolver, Solve, Topology, topology};
use crate::vector::{dot, for_each_row, for_each_row2};

/// The time discretisation. Both are implicit, A-stable and L-stable: stiff
/// modes are damped, never amplified, at any step size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// Backward Euler, first order:
    /// `xₙ₊₁ = xₙ + h vₙ₊₁`, `vₙ₊₁ = vₙ + h M⁻¹ f(xₙ₊₁, vₙ₊₁)`.
    /// On the undamped oscillator one step multiplies the amplitude by
    /// `1/√(1 + (hω)²)`.
    BackwardEuler,
    /// The second-order backward differentiation formula:
    /// `xₙ₊₁ = (4xₙ − xₙ₋₁)/3 + (2/3)h vₙ₊₁`,
    /// `vₙ₊₁ = (4vₙ − vₙ₋₁)/3 + (2/3)h M⁻¹ f(xₙ₊₁, vₙ₊₁)`.
    /// Second order; it starts (and restarts, whenever the state, the system
    /// or `h` changes) with one backward-Euler step. Its amplitude error per
    /// step on the undamped oscillator is `O((hω)⁴)` (Choi & Ko, *Stable but
    /// Responsive Cloth*, SIGGRAPH 2002; Hairer & Wanner, *Solving Ordinary
    /// Differential Equations II*, §V.1).
    Bdf2,
}

/// A linearly implicit integrator on the assembled mass-spring system
/// (Baraff & Witkin, *Large Steps in Cloth Simulation*, SIGGRAPH 1998).
///
/// Each step linearises the forces at the current state and solves
///
/// ```text
/// (M + βh C + β²h² K) Δv = M(ṽ − vₙ) + βh [fₙ − K (x̃ − xₙ + βh vₙ)]
/// ```
///
/// for `Δv = vₙ₊₁ − vₙ`, with `K` the spring stiffness matrix (compressed
/// springs clamped by default), `C` the damping matrix, and `β`, `x̃`, `ṽ`
/// given by the [`Scheme`] (backward Euler: `β = 1`, `x̃ = xₙ`, `ṽ = vₙ`,
/// which is exactly `(M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀)`).
/// Pinned particles act through the filter of the linear solver: their
/// velocity does not change.
///
/// With `newton_iterations > 1` the step goes on to Newton iterations on the
/// scheme's nonlinear equations `g(v) = M(v − ṽ) − βh f(x̃ + βh v, v) = 0`
/// (damping directions frozen at the step's start), each solve followed by a
/// backtracking (Armijo) line search on the incremental potential whose
/// gradient is `g`. They stop once a Newton step `δ = −J⁻¹ g` changes no
/// velocity component by more than the tolerance (in m/s): the residual
/// measured in velocity units, as in Li et al., *Incremental Potential
/// Contact*, SIGGRAPH 2020.
///
/// ```
/// use hooke_core::{Integrator, reference::Sheet};
/// use hooke_implicit::Implicit;
///
/// // A stiff sheet at 30 steps per second, far beyond any explicit method.
/// let system = Sheet { stiffness: 1e6, ..Sheet::new(10) }.system()?;
/// let mut state = system.initial_state();
/// let mut integrator = Implicit::backward_euler();
/// for _ in 0..30 {
///     integrator.step(&system, &mut state, 1.0 / 30.0)?;
/// }
/// assert!(system.max_strain(&state)? < 0.01);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Implicit {
    scheme: Scheme,
    solver: LinearSolver,
    newton_iterations: usize,
    newton_tolerance: f64,
    strict: bool,
    compressed: CompressedSprings,
    history: History,
    topology: Option<Topology>,
    assembler: Assembler,
    contacts: Contacts,
    contact_margin: f64,
    work: Work,
}

/// Per-particle buffers, kept so that a step does not allocate.
#[derive(Debug, Default)]
struct Work {
    b: Vec<Vec3>,
    /// The first solve's `Δv`, kept as the next step's warm start.
    dv: Vec<Vec3>,
    /// A Newton correction.
    delta: Vec<Vec3>,
    v: Vec<Vec3>,
    x: Vec<Vec3>,
    trial: Vec<Vec3>,
    x_tilde: Vec<Vec3>,
    v_tilde: Vec<Vec3>,
    u: Vec<Vec3>,
    inertia: Vec<Vec3>,
    /// BDF2's `xₙ₋₁`, `vₙ₋₁`.
    x_prev: Vec<Vec3>,
    v_prev: Vec<Vec3>,
    pcg: PcgWorkspace,
}

impl Implicit {
    /// Backward Euler with PCG, one linearised step, clamped compressed
    /// springs, non-strict.
    #[must_use]
    pub fn backward_euler() -> Self {
        Self::new(Scheme::BackwardEuler)
    }

    /// BDF2 with the same defaults as [`Implicit::backward_euler`].
    #[must_use]
    pub fn bdf2() -> Self {
        Self::new(Scheme::Bdf2)
    }

    /// An integrator of the given scheme with the defaults.
    #[must_use]
    pub fn new(scheme: Scheme) -> Self {
        Self {
            scheme,
            solver: LinearSolver::default(),
            newton_iterations: 1,
            newton_tolerance: 1e-3,
            strict: false,
            compressed: CompressedSprings::Clamped,
            history: History::default(),
            topology: None,
            assembler: Assembler::default(),
            contacts: Contacts::default(),
            contact_margin: 1e-4,
            work: Work::default(),
        }
    }

    /// Uses `solver` for the linear systems.
    ///
    /// ```
    /// use hooke_implicit::{Implicit, LinearSolver};
    /// let integrator = Implicit::backward_euler().with_solver(LinearSolver::Cholesky);
    /// ```
    #[must_use]
    pub fn with_solver(mut self, solver: LinearSolver) -> Self {
        self.solver = solver;
        self.topology = None;
        self
    }

    /// Takes up to `max_iterations` Newton steps (1 = the linearised step),
    /// stopping once a step changes no velocity component by more than
    /// `tolerance` m/s.
    ///
    /// ```
    /// let integrator = hooke_implicit::Implicit::backward_euler().with_newton(8, 1e-6)?;
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] for zero iterations or a tolerance that is not
    /// positive and finite.
    pub fn with_newton(
        mut self,
        max_iterations: usize,
        tolerance: f64,
    ) -> Result<Self, ParameterError> {
        if max_iterations == 0 {
            return Err(ParameterError::new(
                self.name(),
                "newton_iterations",
                0.0,
                "at least 1",
            ));
        }
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(ParameterError::new(
                self.name(),
                "newton_tolerance",
                tolerance,
                "positive and finite",
            ));
        }
        self.newton_iterations = max_iterations;
        self.newton_tolerance = tolerance;
        Ok(self)
    }

    /// In strict mode a linear solve that stops at its iteration cap fails the
    /// step with [`StepError::NoConvergence`]; otherwise (the default) its
    /// approximate solution is used and counted in
    /// [`StepReport::unconverged_solves`].
    #[must_use]
    pub fn strict(mut self, strict: bool) -> Self {
        self.strict = strict;
        self
    }

    /// How compressed springs' stiffness blocks are treated (clamped by
    /// default, which keeps the matrix positive definite).
    #[must_use]
    pub fn with_compressed_springs(mut self, compressed: CompressedSprings) -> Self {
        self.compressed = compressed;
        self
    }

    /// Particles within `margin` m of an obstacle that approach or rest on
    /// it are constrained in the step's solve (default 0.1 mm; see the crate
    /// docs on contacts).
    ///
    /// ```
    /// let integrator = hooke_implicit::Implicit::backward_euler().with_contact_margin(1e-3)?;
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] for a margin that is negative or not finite.
    pub fn with_contact_margin(mut self, margin: f64) -> Result<Self, ParameterError> {
        if !(margin.is_finite() && margin >= 0.0) {
            return Err(ParameterError::new(
                self.name(),
                "contact_margin",
                margin,
                "finite and non-negative",
            ));
        }
        self.contact_margin = margin;
        Ok(self)
    }

    /// The scheme.
    #[must_use]
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }
}

impl Integrator for Implicit {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        check_step(system, state, dt)?;
        let continues = self.history.take_same_step(system, state, dt);
        let n = state.len();
        let w = &mut self.work;
        for buffer in [
            &mut w.b,
            &mut w.dv,
            &mut w.delta,
            &mut w.v,
            &mut w.x,
            &mut w.trial,
            &mut w.x_tilde,
            &mut w.v_tilde,
            &mut w.u,
            &mut w.inertia,
            &mut w.x_prev,
            &mut w.v_prev,
        ] {
            buffer.resize(n, Vec3::zeros());
        }
        let time = state.time();
        let (x0, v0) = (state.positions(), state.velocities());
        let bdf2 = self.scheme == Scheme::Bdf2 && continues;
        let beta_h = if bdf2 { 2.0 / 3.0 * dt } else { dt };
        let masses = system.masses();
        for i in 0..n {
            (w.x_tilde[i], w.v_tilde[i]) = if bdf2 {
                (
                    (4.0 * x0[i] - w.x_prev[i]) / 3.0,
                    (4.0 * v0[i] - w.v_prev[i]) / 3.0,
                )
            } else {
                (x0[i], v0[i])
            };
            w.u[i] = w.x_tilde[i] - x0[i] + beta_h * v0[i];
            w.inertia[i] = masses[i] * (w.v_tilde[i] - v0[i]);
        }
        if !continues {
            w.dv.fill(Vec3::zeros());
        }

        let mut report = StepReport {
            accepted_steps: 1,
            ..StepReport::default()
        };
        let (compressed, solver, strict) = (self.compressed, self.solver, self.strict);
        let topology = topology(&mut self.topology, solver, system)?;
        let w = &mut self.work;
        let lin = Linearization {
            positions: x0,
            velocities: v0,
            displacement: Some(&w.u),
            inertia: &w.inertia,
            beta_h,
            compressed,
            freeze_directions: true,
        };
        let solve = Solve {
            system,
            solver,
            strict,
            time,
        };
        let contacts = &mut self.contacts;
        let constrained = (!system.obstacles().is_empty() || !system.pin_paths().is_empty())
            && contacts.begin(
                system,
                x0,
                v0,
                state.touching(),
                time,
                dt,
                self.contact_margin,
                topology.matrix_and_filters_mut().1,
            );
        solve.assemble(&mut self.assembler, topology, &lin, &mut w.b)?;
        if constrained {
            contacts.prescribe(topology.matrix(), &mut w.b);
            contacts.add_friction(topology, v0, &mut w.b);
        }
        solve.solve(topology, &w.b, &mut w.dv, &mut w.pcg, &mut report)?;
        if constrained {
            for_each_row(&mut w.v, |i, v| {
                *v = v0[i] + w.dv[i] + contacts.prescribed[i]
            });
            let (matrix, filters) = topology.matrix_and_filters_mut();
            contacts.release(matrix, &w.dv, &w.b, filters);
        } else {
            for_each_row(&mut w.v, |i, v| *v = v0[i] + w.dv[i]);
        }

        for _ in 1..self.newton_iterations {
            for_each_row2(&mut w.x, &mut w.inertia, |i, x, inertia| {
                *x = w.x_tilde[i] + beta_h * w.v[i];
                *inertia = -masses[i] * (w.v[i] - w.v_tilde[i]);
            });
            let lin = Linearization {
                positions: &w.x,
                velocities: &w.v,
                displacement: None,
                inertia: &w.inertia,
                beta_h,
                compressed,
                freeze_directions: false,
            };
            w.delta.fill(Vec3::zeros());
            solve.assemble(&mut self.assembler, topology, &lin, &mut w.b)?;
            if constrained {
                self.contacts.add_friction(topology, &w.v, &mut w.b);
            }
            solve.solve(topology, &w.b, &mut w.delta, &mut w.pcg, &mut report)?;
            if constrained {
                let (matrix, filters) = topology.matrix_and_filters_mut();
                self.contacts.release(matrix, &w.delta, &w.b, filters);
            }
            // The Newton step J⁻¹(−g) measures the residual in velocity units.
            let step = w.delta.iter().map(|d| d.amax()).fold(0.0, f64::max);
            report.newton_residual = step;
            if step <= self.newton_tolerance {
                for_each_row(&mut w.v, |i, v| *v += w.delta[i]);
                break;
            }
            // Backtracking (Armijo) on Φ along δ; the slope is ∇Φ·δ = −bᵀδ.
            let slope = -dot(&w.b, &w.delta);
            let start = self.assembler.potential(
                system,
                topology.pattern(),
                &w.x,
                &w.v,
                &w.v_tilde,
                beta_h,
            ) + if constrained {
                self.contacts.dissipation(&w.v)
            } else {
                0.0
            };
            let mut alpha = 1.0;
            let accepted = loop {
                for_each_row(&mut w.trial, |i, t| *t = w.v[i] + alpha * w.delta[i]);
                for_each_row(&mut w.x, |i, x| *x = w.x_tilde[i] + beta_h * w.trial[i]);
                let value = self.assembler.potential(
                    system,
                    topology.pattern(),
                    &w.x,
                    &w.trial,
                    &w.v_tilde,
                    beta_h,
                ) + if constrained {
                    self.contacts.dissipation(&w.trial)
                } else {
                    0.0
                };
                if value <= start + 1e-4 * alpha * slope {
                    break true;
                }
                alpha *= 0.5;
                if alpha < 1e-6 {
                    break false;
                }
            };
            if !accepted {
                break;
            }
            std::mem::swap(&mut w.v, &mut w.trial);
        }
        report.newton_iterations = report.linear_solves;

        for i in 0..n {
            w.x[i] = w.x_tilde[i] + beta_h * w.v[i];
        }
        state.commit(&mut w.x, &mut w.v, time + dt)?;
        // The buffers swapped out of the state hold xₙ, vₙ: BDF2's next history.
        std::mem::swap(&mut w.x_prev, &mut w.x);
        std::mem::swap(&mut w.v_prev, &mut w.v);
        self.history.record(system, state, dt);
        report.contacts = system.end_step(state);
        Ok(report)
    }

    fn name(&self) -> &'static str {
        match self.scheme {
            Scheme::BackwardEuler => "backward-euler",
            Scheme::Bdf2 => "bdf2",
        }
    }
}
