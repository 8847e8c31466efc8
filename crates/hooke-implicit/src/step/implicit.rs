//! [`Implicit`]: backward Euler and BDF2 on the assembled system.

use hooke_core::{History, ParameterError};

use crate::linear::solver::topology::Topology;
use crate::minimize::minimizer::Kept;
use crate::minimize::terms::Terms;
use crate::step::comparison::Comparison;
use crate::step::conditioning::LongestStep;
use crate::step::pins::Pins;
use crate::step::scheme::Scheme;
use crate::step::settings::ImplicitSettings;
use crate::step::work::Work;

/// An implicit integrator on the assembled mass-spring system.
///
/// # The converged step (default)
///
/// A step of `h` solves the scheme's nonlinear equations
/// `g(v) = M(v − ṽ) − βh f(x̃ + βh v, v) = 0` for the new velocity `v`
/// (`x = x̃ + βh v`; backward Euler: `β = 1`, `x̃ = xₙ`, `ṽ = vₙ`; BDF2: see
/// [`Scheme`]) by minimising the incremental potential whose gradient is `g`
/// (Gast, Schroeder, Stomakhin, Jiang & Teran, *Optimization Integrator for
/// Large Time Steps*, 2015; Li et al., *Incremental Potential Contact*,
/// 2020):
///
/// ```text
/// Φ(v) = ½‖v − ṽ‖²_M + V(x̃ + βh v) + βh R(v) + D(v)
/// ```
///
/// with `V` the spring and gravitational potential, `R` the dampers'
/// Rayleigh potential (directions frozen at the step's start) and `D` the
/// friction's dissipation potential. Newton's method starts at whichever of
/// `vₙ` and Baraff & Witkin's linearised solution (both with the velocity
/// changes of pins and contacts applied) has the lower `Φ`, and solves
/// `(M + βh C + β²h² K) δ = −g` with the exact spring and volume-element
/// Hessians where that system is positive definite, and with compressed
/// springs clamped and the elements' Hessians projected (each onto its
/// positive part) where it is not, so that every step descends. Every iterate, the first one included, is
/// accepted only through a line search that decreases `Φ` (Armijo,
/// extended with a watchdog step and extrapolation; see the
/// `line_search` module). It stops when the Newton decrement `λ = √(δᵀAδ)`,
/// which bounds the velocity error in the mass norm and whose square
/// halved estimates how far `Φ` is above its minimum, is small against the
/// step's velocity scale,
///
/// ```text
/// λ ≤ ε · max(‖v + δ − vₙ‖_M, ‖v + δ‖_M, βh‖g‖√(Σmᵢ)),   ‖u‖_M = √(Σ mᵢ|uᵢ|²),
/// ```
///
/// a rule without units that means the same at 10⁻² and 10¹² N/m or in a
/// millimetre scene (default `ε` = [`ImplicitSettings::NEWTON_TOLERANCE`], cap
/// [`ImplicitSettings::NEWTON_ITERATIONS`] linear solves; [`Implicit::with_newton`]),
/// or when a full Newton step would lower `Φ` by less than the rounding of
/// `Φ` itself — the precision floor that springs of 10¹² N/m reach, whose
/// forces carry `k` times the rounding of their ends' coordinates.
///
/// With an iterative linear solver the Newton steps are solved inexactly,
/// to the relative residual `η = min(0.1, ½ λ_rel)` of the last relative
/// decrement where that is looser than the solver's own tolerance (an
/// inexact Newton iteration; [`Implicit::with_inexact_newton`]); CG
/// preconditioned by a Cholesky factor with weak springs routed
/// ([`WeakSprings::Routed`](crate::WeakSprings)) stops at `min(η, 10⁻²)`,
/// standing in for a direct solve.
///
/// # Substeps: conditioning, rejection and the energy test
///
/// The step's matrix has condition number relative to `M` of at most
/// `1 + βhζ + β²h²ω²` (Gershgorin bounds of the damping and stiffness
/// rates); steps longer than the one at which it reaches
/// [`Implicit::MAX_CONDITION`] are taken in substeps, as rounding would
/// otherwise erase the inertia of the soft modes from the solve.
///
/// A converged step of backward Euler on a convex energy cannot gain energy,
/// but a spring's `½k(l − L)²` is not convex under compression, so each
/// backward-Euler step is also tested: `E(xₙ₊₁, vₙ₊₁) ≤ E(xₙ, vₙ) + W`, with
/// `E` the kinetic, elastic and gravitational energy of the free particles
/// and `W` the work of scripted pins and moving obstacles. A gain `ΔE` that
/// the free particles' kinetic energy `K` absorbs by scaling their
/// velocities by `s = √(1 − ΔE/K)` with `(1 − s)√(2K) ≤ ε · scale` (the
/// stopping rule's tolerance and velocity scale above: the scaled velocities
/// are as close to the exact step as any converged ones) is absorbed so;
/// the gains of a rolling body pressed onto a floor (the chord of each
/// step releases its compression, a Bregman term of the non-convex
/// potential) are of this kind, and shrink only as `h²` against the
/// dissipation's `h` (the `energy` module). A step that fails the test
/// otherwise, or whose Newton iteration does not converge within its cap,
/// is rejected and retried as two substeps of half the size, down to a floor
/// of `h / 2^k` (`k` = [`ImplicitSettings::MAX_HALVINGS`],
/// [`Implicit::with_max_halvings`]); after a substep whose Newton iteration
/// took at most a third of its cap, the size doubles again, up to the step
/// the caller asked for, which is always delivered whole. BDF2 keeps its
/// history across substeps of different sizes with its variable-step
/// coefficients (step ratio `ω = h/hₙ₋₁ ≤ 2`). Its two-step steps are not
/// held to the energy test: BDF2 lowers a norm of two consecutive states
/// (Dahlquist's G-stability), not the energy of each, so even on the linear
/// oscillator a correct step can gain a little energy; their gains are
/// reported in [`StepReport::energy_excess`](hooke_core::StepReport::energy_excess).
/// At the floor, a step is accepted as it is and counted in
/// [`StepReport::unconverged_steps`](hooke_core::StepReport::unconverged_steps)
/// (or, in [strict](Implicit::strict) mode, fails with
/// [`StepError::NoConvergence`](hooke_core::StepError::NoConvergence)); if a
/// backward-Euler step gained energy there, the last resort scales the free
/// particles' velocities so that the kinetic energy absorbs the excess,
/// counted in [`StepReport::energy_corrections`](hooke_core::StepReport::energy_corrections)
/// with the excess in `energy_excess`. Nothing is silent.
///
/// With [`Implicit::with_error_control`] the substeps are chosen by their
/// estimated local error instead (see the [`error_control`](crate::step::error_control)
/// module); rejection for convergence and energy works as above.
///
/// # The quasi-Newton step
///
/// With [`Minimizer::QuasiNewton`](crate::Minimizer::QuasiNewton) each iterate's direction is L-BFGS's,
/// `δ = −H ∇Φ`, from the last `m` curvature pairs around the constant
/// initial Hessian `H₀ = M + βh (γI + C₀) + β²h² L` (the `quasi_newton`
/// module); the iteration starts at `vₙ` (with the pins' prescribed
/// velocities), and the line search, the stopping rule, the energy test
/// and the substeps are the ones above. Its decrement `λ = √|∇Φ·δ|` is
/// measured in `H`'s norm, not the exact Hessian's: `H₀` bounds every
/// spring's Hessian from above, so `λ` underestimates the exact decrement
/// where the cloth is soft. Once `λ` meets `ε`, the stopping rule
/// evaluates `Φ` at the full step and scales `λ` by `√α*`, `α* ≥ 1` the
/// minimum of the quadratic through `Φ(v)`, the slope and `Φ(v + δ)`:
/// `α* λ²` is the decrement of the exact minimisation along `δ`, a lower
/// bound of Newton's. That bound sees only what `δ` holds; modes that `H₀`
/// makes far too stiff (a stiff cloth's swinging under a large step,
/// `k h²/m` beyond about 10³) stay unseen, and there the step still stops
/// short of the minimum: on a 12 × 12 sheet at 10⁴ N/m and `h = 1/60 s`,
/// stopped at `ε = 10⁻³`, its velocities lie 1.7 % from the converged
/// step's, and at 10⁶ N/m and `h = 0.1 s`, stopped at 10⁻², 94 % — use
/// Newton's step there. At the same `ε` the quasi-Newton step stops
/// farther from the minimum than Newton's (the work-precision table in
/// `benches/README.md` gives the errors). For the same reason its
/// precision floor is the last iterate lowering `Φ` by no more than
/// rounding, not the predicted decrease.
///
/// # The linearised step (Baraff & Witkin)
///
/// [`Implicit::linearized`] takes exactly Baraff & Witkin's step (*Large
/// Steps in Cloth Simulation*, SIGGRAPH 1998): one linear solve at the
/// current state,
///
/// ```text
/// (M + βh C + β²h² K) Δv = M(ṽ − vₙ) + βh [fₙ − K (x̃ − xₙ + βh vₙ)],
/// ```
///
/// for backward Euler `(M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀)`,
/// no line search, no rejection, no substeps. It is exact for linear
/// springs, but it cannot see the stretch `δ²/2L` of a spring rotated by
/// `δ` in one step: at large steps on stiff cloth it stores energy (up to
/// thousands of times the initial energy on a 24×24 cloth at 10⁴ N/m and
/// 0.1 s steps) before damping it out. Its energy gain is reported in
/// `energy_excess`, never corrected.
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
///     let report = integrator.step(&system, &mut state, 1.0 / 30.0)?;
///     assert_eq!(report.unconverged_steps, 0);
/// }
/// assert!(system.max_strain(&state)? < 0.01);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Implicit {
    /// What the integrator was built with; everything else is run-time
    /// state.
    pub(crate) settings: ImplicitSettings,
    /// The steps before, for BDF2 and the error estimates.
    pub(crate) history: History,
    /// The substep size to try first: the last accepted one, doubled.
    pub(crate) substep: f64,
    /// The size of the step before the last one, when the last one
    /// continued from it (for BDF2's error estimate).
    pub(crate) earlier: Option<f64>,
    pub(crate) topology: Option<Topology>,
    /// [`LinearSolver::Auto`](crate::LinearSolver::Auto)'s comparison on whole steps, while it lasts.
    pub(crate) comparison: Comparison,
    /// The longest substep the conditioning allows.
    pub(crate) longest: LongestStep,
    /// The terms of the last system stepped.
    pub(crate) terms: Option<Terms>,
    pub(crate) pins: Pins,
    /// What the minimisers keep from one (sub)step to the next.
    pub(crate) kept: Kept,
    pub(crate) work: Work,
}

impl Implicit {
    /// Backward Euler with the default [`ImplicitSettings`]: the automatic
    /// solver choice ([`LinearSolver::Auto`](crate::LinearSolver::Auto): sparse Cholesky on small
    /// systems, otherwise whichever solver a timed trial finds fastest),
    /// converged Newton steps, step rejection, fixed substeps.
    #[must_use]
    pub fn backward_euler() -> Self {
        Self::new(Scheme::BackwardEuler)
    }

    /// BDF2 with the default [`ImplicitSettings`].
    #[must_use]
    pub fn bdf2() -> Self {
        Self::new(Scheme::Bdf2)
    }

    /// The largest condition number `κ(h) = 1 + βhζ + β²h²ω²` of a step's
    /// matrix relative to the mass matrix (`ω²`, `ζ`: Gershgorin bounds of
    /// the stiffness and damping rates) at which a step is taken whole;
    /// longer steps are taken in substeps. At `κ = 10¹⁴` a solve keeps the
    /// soft modes' inertia to about 2 %.
    pub const MAX_CONDITION: f64 = 1e14;

    /// An integrator of the given scheme with the default
    /// [`ImplicitSettings`].
    #[must_use]
    pub fn new(scheme: Scheme) -> Self {
        Self::built(ImplicitSettings {
            scheme,
            ..ImplicitSettings::default()
        })
    }

    /// An integrator with `settings`.
    ///
    /// ```
    /// use hooke_implicit::{Implicit, ImplicitSettings, Minimizer};
    /// let settings = ImplicitSettings {
    ///     minimizer: Minimizer::quasi_newton(),
    ///     newton_tolerance: 1e-3,
    ///     ..ImplicitSettings::default()
    /// };
    /// let lbfgs = Implicit::with_settings(settings)?;
    /// assert_eq!(lbfgs.minimizer(), Minimizer::quasi_newton());
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] naming the setting out of range
    /// ([`ImplicitSettings::validate`]).
    pub fn with_settings(settings: ImplicitSettings) -> Result<Self, ParameterError> {
        settings.validate()?;
        Ok(Self::built(settings))
    }

    /// An integrator with `settings`, which are valid, and nothing built
    /// or measured yet.
    fn built(settings: ImplicitSettings) -> Self {
        Self {
            settings,
            history: History::default(),
            substep: f64::INFINITY,
            earlier: None,
            topology: None,
            comparison: Comparison::default(),
            longest: LongestStep::default(),
            terms: None,
            pins: Pins::default(),
            kept: Kept::default(),
            work: Work::default(),
        }
    }
}
