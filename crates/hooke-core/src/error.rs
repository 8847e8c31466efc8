//! Errors: [`BuildError`] for a system that fails validation, [`StepError`]
//! for a step that cannot be taken or would leave a non-finite state,
//! [`ParameterError`] for an integrator or solver setting out of range.

use thiserror::Error;

/// Which spring parameter a [`BuildError::InvalidSpringParameter`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpringParameter {
    /// The stiffness `k`.
    Stiffness,
    /// The rest length `L`.
    RestLength,
    /// The axial damping `c`.
    Damping,
}

impl std::fmt::Display for SpringParameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Stiffness => "stiffness",
            Self::RestLength => "rest length",
            Self::Damping => "damping",
        })
    }
}

/// Which per-particle vector a [`BuildError::NonFiniteParticle`] or a
/// [`StepError::NonFinite`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A position.
    Position,
    /// A velocity.
    Velocity,
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Position => "position",
            Self::Velocity => "velocity",
        })
    }
}

/// A system description that cannot be simulated, naming the culprit.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BuildError {
    /// A mass that is zero, negative, NaN or infinite.
    #[error("particle {particle}: mass must be positive and finite, got {mass}")]
    InvalidMass {
        /// Index of the particle.
        particle: usize,
        /// The offending mass.
        mass: f64,
    },
    /// A position or velocity with a NaN or infinite component.
    #[error("particle {particle}: initial {quantity} is not finite: {value:?}")]
    NonFiniteParticle {
        /// Index of the particle.
        particle: usize,
        /// Position or velocity.
        quantity: Quantity,
        /// The offending vector.
        value: [f64; 3],
    },
    /// A spring endpoint that names no particle.
    #[error(
        "spring {spring}: endpoint {endpoint} is out of range (the system has {particles} particles)"
    )]
    SpringEndpointOutOfRange {
        /// Index of the spring.
        spring: usize,
        /// The offending endpoint.
        endpoint: usize,
        /// Number of particles in the system.
        particles: usize,
    },
    /// A spring from a particle to itself.
    #[error("spring {spring}: both ends are particle {particle}")]
    SelfSpring {
        /// Index of the spring.
        spring: usize,
        /// The particle at both ends.
        particle: usize,
    },
    /// A second spring between the same two particles.
    #[error("spring {spring}: duplicates spring {first} between particles {i} and {j}")]
    DuplicateSpring {
        /// Index of the duplicate.
        spring: usize,
        /// Index of the spring it duplicates.
        first: usize,
        /// One end.
        i: usize,
        /// The other end.
        j: usize,
    },
    /// A negative, NaN or infinite stiffness, rest length or damping.
    #[error("spring {spring}: {parameter} must be finite and non-negative, got {value}")]
    InvalidSpringParameter {
        /// Index of the spring.
        spring: usize,
        /// Which parameter.
        parameter: SpringParameter,
        /// The offending value.
        value: f64,
    },
    /// A pin on a particle that does not exist.
    #[error("pin on particle {particle} is out of range (the system has {particles} particles)")]
    PinOutOfRange {
        /// The requested particle.
        particle: usize,
        /// Number of particles in the system.
        particles: usize,
    },
    /// A gravity vector with a NaN or infinite component.
    #[error("gravity is not finite: {value:?}")]
    NonFiniteGravity {
        /// The offending vector.
        value: [f64; 3],
    },
    /// An air-damping coefficient that is negative, NaN or infinite.
    #[error("air damping must be finite and non-negative, got {value}")]
    InvalidAirDamping {
        /// The offending coefficient.
        value: f64,
    },
    /// A scripted pin whose path is invalid.
    #[error("pin on particle {particle}: {problem}")]
    InvalidPinPath {
        /// The pinned particle.
        particle: usize,
        /// What is wrong, naming the field.
        problem: &'static str,
    },
    /// A collision surface is invalid.
    #[error("surface {surface}: {problem}")]
    InvalidSurface {
        /// Index of the surface, in the order added.
        surface: usize,
        /// What is wrong.
        problem: String,
    },
    /// A volume element that names a particle that does not exist, repeats
    /// one, has no rest volume or an invalid modulus.
    #[error("volume element {tet}: {problem}")]
    InvalidTet {
        /// Index of the element, in the order added.
        tet: usize,
        /// What is wrong.
        problem: String,
    },
    /// The contact distance is not positive and finite.
    #[error("contact distance must be positive and finite, got {value}")]
    InvalidContactDistance {
        /// The value given, m.
        value: f64,
    },
    /// An obstacle with an invalid shape, path, restitution or friction.
    #[error("obstacle {obstacle}: {problem}")]
    InvalidObstacle {
        /// Index of the obstacle.
        obstacle: usize,
        /// What is wrong, naming the field.
        problem: &'static str,
    },
    /// A term ([`SystemBuilder::term`](crate::SystemBuilder::term)) that
    /// does not fit the system.
    #[error("term {term} ({name}): {problem}")]
    InvalidTerm {
        /// Index of the term, in the order added.
        term: usize,
        /// The term's name ([`Term::name`](crate::Term::name)).
        name: &'static str,
        /// What is wrong.
        problem: String,
    },
}

/// A step that could not be taken. The state is left as it was before the
/// step.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StepError {
    /// A time step that is zero, negative, NaN or infinite.
    #[error("time step must be positive and finite, got {dt}")]
    InvalidTimestep {
        /// The offending step.
        dt: f64,
    },
    /// A state whose particle count differs from the system's.
    #[error("state has {state} particles but the system has {system}")]
    StateMismatch {
        /// Particles in the state.
        state: usize,
        /// Particles in the system.
        system: usize,
    },
    /// The step produced a NaN or infinite position or velocity.
    #[error("non-finite {quantity} of particle {particle} at t = {time}")]
    NonFinite {
        /// Time at the end of the failed step.
        time: f64,
        /// First particle found with a non-finite value.
        particle: usize,
        /// Position or velocity.
        quantity: Quantity,
    },
    /// An adaptive integrator could not meet its tolerance with any step size
    /// representable at this time.
    #[error("step size {step} underflowed at t = {time}")]
    StepSizeUnderflow {
        /// Time at which the step was attempted.
        time: f64,
        /// The rejected step size.
        step: f64,
    },
    /// The linear system of an implicit step has a NaN or infinite entry.
    #[error("non-finite linear system at particle {particle} at t = {time}")]
    NonFiniteSystem {
        /// Time at the start of the failed step.
        time: f64,
        /// First particle whose row is not finite.
        particle: usize,
    },
    /// The linear system of an implicit step is not positive definite (for
    /// example under compression with the exact stiffness blocks).
    #[error("linear system is not positive definite{} at t = {time}", particle.map_or(String::new(), |p| format!(" at particle {p}")))]
    NotPositiveDefinite {
        /// Time at the start of the failed step.
        time: f64,
        /// The particle whose diagonal block failed, where known.
        particle: Option<usize>,
    },
    /// A linear solve in strict mode stopped at its iteration cap.
    #[error(
        "linear solver did not converge in {iterations} iterations (relative residual {residual:.3e}) at t = {time}"
    )]
    NoConvergence {
        /// Time at the start of the failed step.
        time: f64,
        /// Iterations taken.
        iterations: usize,
        /// Relative residual reached.
        residual: f64,
    },
    /// An integrator that does not minimise the incremental potential was
    /// given a system whose surfaces collide.
    #[error(
        "{integrator} cannot keep surfaces from passing through each other: a system with self-collision or several colliding surfaces needs an implicit step that minimises the incremental potential (backward-euler or bdf2, not linearized)"
    )]
    SurfaceContactUnsupported {
        /// The integrator's name.
        integrator: &'static str,
    },
    /// A system too large for a solver's 32-bit indices.
    #[error("{particles} particles and {springs} springs exceed the solver's 32-bit indices")]
    SystemTooLarge {
        /// Particles in the system.
        particles: usize,
        /// Springs in the system.
        springs: usize,
    },
    /// An adaptive integrator needed more substeps than allowed to cover one
    /// requested step.
    #[error("{substeps} substeps did not reach the end of the step at t = {time}")]
    TooManySubsteps {
        /// Time reached when the integrator gave up.
        time: f64,
        /// Substeps taken.
        substeps: usize,
    },
}

/// Which integrator or solver setting a [`ParameterError`] is about; it
/// displays as its [`Parameter::name`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parameter {
    /// Dormand–Prince's relative tolerance, `rtol`.
    Rtol,
    /// Dormand–Prince's absolute tolerance, `atol`.
    Atol,
    /// The fast mass-spring method's local/global iterations per step.
    Iterations,
    /// A PCG solve's relative residual tolerance.
    Tolerance,
    /// A PCG solve's iteration cap.
    MaxIterations,
    /// The implicit step's cap on Newton iterations.
    NewtonIterations,
    /// The implicit step's relative Newton tolerance.
    NewtonTolerance,
    /// Error control's relative tolerance.
    RelativeTolerance,
    /// Error control's absolute tolerance.
    AbsoluteTolerance,
    /// Multigrid's strength-of-connection threshold.
    Strength,
    /// Multigrid's threshold of the matrix that smooths the finest
    /// prolongator.
    Filter,
    /// Multigrid's Chebyshev degree of each smoothing sweep.
    SmootherDegree,
    /// Multigrid's Chebyshev degree on the finest level.
    FineDegree,
    /// The largest number of unknowns multigrid solves directly.
    CoarseUnknowns,
    /// The broad phase's cell side over the triangles' mean box side.
    CellFactor,
}

impl Parameter {
    /// The setting's name in messages: `"rtol"`, `"newton_tolerance"`,
    /// `"relative tolerance"` …
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Rtol => "rtol",
            Self::Atol => "atol",
            Self::Iterations => "iterations",
            Self::Tolerance => "tolerance",
            Self::MaxIterations => "max_iterations",
            Self::NewtonIterations => "newton_iterations",
            Self::NewtonTolerance => "newton_tolerance",
            Self::RelativeTolerance => "relative tolerance",
            Self::AbsoluteTolerance => "absolute tolerance",
            Self::Strength => "strength",
            Self::Filter => "filter",
            Self::SmootherDegree => "smoother_degree",
            Self::FineDegree => "fine_degree",
            Self::CoarseUnknowns => "coarse_unknowns",
            Self::CellFactor => "cell factor",
        }
    }
}

impl std::fmt::Display for Parameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// An integrator or solver parameter outside its valid range.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{integrator}: {parameter} must be {requirement}, got {value}")]
pub struct ParameterError {
    /// The integrator's or solver's name.
    pub integrator: &'static str,
    /// The parameter.
    pub parameter: Parameter,
    /// The value given.
    pub value: f64,
    /// What the value must be.
    pub requirement: &'static str,
}

impl ParameterError {
    /// An error for `parameter` of `integrator`, which must be `requirement`
    /// but is `value`.
    #[must_use]
    pub fn new(
        integrator: &'static str,
        parameter: Parameter,
        value: f64,
        requirement: &'static str,
    ) -> Self {
        Self {
            integrator,
            parameter,
            value,
            requirement,
        }
    }
}
