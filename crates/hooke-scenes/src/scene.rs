//! [`Scene`]: everything a run needs — the system, what its bodies look like,
//! the integrator and the timing.

use hooke_core::{Integrator, ParameterError, System};
use hooke_explicit::{
    Beeman, DormandPrince, ExplicitEuler, Gear, Heun, Leapfrog, Midpoint, PositionVerlet, Rk4,
    SymplecticEuler, VelocityVerlet,
};
use hooke_implicit::{Implicit, LinearSolver, PcgSettings, Scheme};

use crate::body::Placement;

/// A simulation ready to run: a [`System`], the surfaces and segments of
/// its bodies for writing frames, the integrator to use and how long to run.
#[derive(Debug, Clone)]
pub struct Scene {
    /// A name for reports.
    pub name: String,
    /// The system to integrate.
    pub system: System,
    /// The bodies in the system, for output.
    pub bodies: Vec<SceneBody>,
    /// The integrator and its parameters.
    pub integrator: IntegratorSpec,
    /// Duration, step and frame rate.
    pub timing: Timing,
}

/// A body placed in a scene's system.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneBody {
    /// The body's name.
    pub name: String,
    /// Where its particles are in the system.
    pub placement: Placement,
    /// Surface triangles, in system particle indices.
    pub triangles: Vec<[usize; 3]>,
    /// Segments to draw for bodies without a surface (ropes), in system
    /// particle indices.
    pub segments: Vec<[usize; 2]>,
}

/// How long a scene runs and how often it is written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Simulated duration, s.
    pub duration: f64,
    /// Step size, s (the first try, for adaptive integrators).
    pub dt: f64,
    /// Frames written per simulated second.
    pub frame_rate: f64,
}

impl Timing {
    /// Number of steps: `duration / dt`, rounded to the nearest integer.
    #[must_use]
    pub fn steps(&self) -> usize {
        (self.duration / self.dt).round() as usize
    }

    /// Steps between written frames (at least 1).
    #[must_use]
    pub fn steps_per_frame(&self) -> usize {
        ((1.0 / (self.frame_rate * self.dt)).round() as usize).max(1)
    }
}

/// A fixed-step explicit method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ExplicitMethod {
    /// [`ExplicitEuler`].
    ExplicitEuler,
    /// [`SymplecticEuler`].
    SymplecticEuler,
    /// [`Leapfrog`].
    Leapfrog,
    /// [`VelocityVerlet`].
    VelocityVerlet,
    /// [`PositionVerlet`].
    PositionVerlet,
    /// [`Midpoint`].
    Midpoint,
    /// [`Heun`].
    Heun,
    /// [`Rk4`].
    Rk4,
    /// [`Beeman`].
    Beeman,
    /// [`Gear`].
    Gear,
}

impl ExplicitMethod {
    /// Every method, in the order of the `hooke-explicit` table.
    pub const ALL: [Self; 10] = [
        Self::ExplicitEuler,
        Self::SymplecticEuler,
        Self::Leapfrog,
        Self::VelocityVerlet,
        Self::PositionVerlet,
        Self::Midpoint,
        Self::Heun,
        Self::Rk4,
        Self::Beeman,
        Self::Gear,
    ];

    /// The name scene files and reports use, e.g. `"velocity-verlet"` (the
    /// integrator's [`Integrator::name`]).
    #[must_use]
    pub fn name(self) -> &'static str {
        self.build().name()
    }

    /// A new integrator.
    #[must_use]
    pub fn build(self) -> Box<dyn Integrator + Send> {
        match self {
            Self::ExplicitEuler => Box::new(ExplicitEuler::new()),
            Self::SymplecticEuler => Box::new(SymplecticEuler::new()),
            Self::Leapfrog => Box::new(Leapfrog::new()),
            Self::VelocityVerlet => Box::new(VelocityVerlet::new()),
            Self::PositionVerlet => Box::new(PositionVerlet::new()),
            Self::Midpoint => Box::new(Midpoint::new()),
            Self::Heun => Box::new(Heun::new()),
            Self::Rk4 => Box::new(Rk4::new()),
            Self::Beeman => Box::new(Beeman::new()),
            Self::Gear => Box::new(Gear::new()),
        }
    }
}

/// The linear solver of an implicit integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolverSpec {
    /// Filtered PCG to a relative residual `tolerance`, at most
    /// `max_iterations` iterations.
    Pcg {
        /// Relative residual to stop at.
        tolerance: f64,
        /// Iteration cap.
        max_iterations: usize,
    },
    /// Sparse Cholesky.
    Cholesky,
}

/// Which integrator a scene runs, with its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntegratorSpec {
    /// A fixed-step explicit method.
    Explicit(ExplicitMethod),
    /// Adaptive Dormand–Prince 5(4) with relative and absolute tolerances.
    Adaptive {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
    /// Backward Euler or BDF2.
    Implicit {
        /// The scheme.
        scheme: Scheme,
        /// The linear solver.
        solver: SolverSpec,
        /// Baraff & Witkin's linearised step instead of the converged one.
        linearized: bool,
        /// Cap on Newton iterations per (sub)step.
        newton_iterations: usize,
        /// Relative Newton tolerance `ε` (see `hooke_implicit::Implicit`).
        newton_tolerance: f64,
    },
}

impl IntegratorSpec {
    /// Backward Euler with sparse Cholesky and converged Newton steps at
    /// the integrator's default cap and tolerance: the default of scenes.
    #[must_use]
    pub fn backward_euler() -> Self {
        Self::Implicit {
            scheme: Scheme::BackwardEuler,
            solver: SolverSpec::Cholesky,
            linearized: false,
            newton_iterations: Implicit::NEWTON_ITERATIONS,
            newton_tolerance: Implicit::NEWTON_TOLERANCE,
        }
    }

    /// A new integrator with these parameters.
    ///
    /// ```
    /// use hooke_scenes::IntegratorSpec;
    /// let integrator = IntegratorSpec::backward_euler().build()?;
    /// assert_eq!(integrator.name(), "backward-euler");
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] naming the parameter that is out of range.
    pub fn build(&self) -> Result<Box<dyn Integrator + Send>, ParameterError> {
        Ok(match *self {
            Self::Explicit(method) => method.build(),
            Self::Adaptive { rtol, atol } => Box::new(DormandPrince::new(rtol, atol)?),
            Self::Implicit {
                scheme,
                solver,
                linearized,
                newton_iterations,
                newton_tolerance,
            } => {
                let solver = match solver {
                    SolverSpec::Pcg {
                        tolerance,
                        max_iterations,
                    } => LinearSolver::Pcg(PcgSettings::new(tolerance, max_iterations)?),
                    SolverSpec::Cholesky => LinearSolver::Cholesky,
                };
                let implicit = Implicit::new(scheme)
                    .with_solver(solver)
                    .with_newton(newton_iterations, newton_tolerance)?;
                Box::new(if linearized {
                    implicit.linearized()
                } else {
                    implicit
                })
            }
        })
    }
}
