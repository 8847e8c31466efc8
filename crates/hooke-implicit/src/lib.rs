//! Implicit integration of mass-spring systems on an assembled sparse
//! system: backward Euler in the style of Baraff & Witkin (1998) and BDF2,
//! solved by constraint-filtered PCG or sparse Cholesky.
//!
//! Stiff springs limit every explicit method to `h < 2/ω_max`; an implicit
//! step is stable at any step size (see [`Implicit`] for the equations).
//! Per step:
//!
//! 1. **Assembly** ([`Terms`]): each term of the step's potential — the
//!    inertia, gravity, air damping, the springs (their Hessian blocks `H`
//!    and damping blocks `c d dᵀ` from `hooke-core`, in two parallel passes
//!    that never allocate: one per spring, one per block row), volume
//!    elements, contact and the system's own terms — adds itself into
//!    `A = M + βh C + β²h² K` and the right-hand side. The `Pattern` comes
//!    from the topology and is built once.
//! 2. **Solve** ([`LinearSolver`]): `cg::solve` (Baraff–Witkin's modified
//!    PCG, pins and other per-particle constraints acting through the
//!    `Filter` inside the loop) preconditioned by block-Jacobi, by a
//!    smoothed-aggregation multigrid V-cycle (`Amg`, the `amg` module) or
//!    by a lagged Cholesky factor, or `SparseCholesky` (faer, symbolic
//!    analysis reused) on the same filtered system; by default
//!    ([`LinearSolver::Auto`]) Cholesky for small systems and, for larger
//!    ones, whichever of Cholesky, multigrid and block-Jacobi PCG a timed
//!    trial finds fastest.
//! 3. **Newton iterations to convergence** on the incremental potential
//!    `Φ`, every iterate accepted through a line search that lowers `Φ`,
//!    stopped by a scale-free rule on the Newton decrement (default
//!    relative [`ImplicitSettings::NEWTON_TOLERANCE`], at most
//!    [`ImplicitSettings::NEWTON_ITERATIONS`] solves); iterative solves stop at a
//!    forcing term that tightens with the decrement (inexact Newton).
//! 4. **Acceptance**: a step that does not converge, or a backward-Euler
//!    step that gains energy beyond the work of external forces, is
//!    rejected and retried as halved substeps, growing back afterwards;
//!    optionally ([`Implicit::with_error_control`]) the substeps follow a
//!    local error estimate. Everything that fell short is counted in the
//!    [`StepReport`](hooke_core::StepReport).
//!
//! Instead of Newton's method, [`Minimizer::QuasiNewton`] minimises the
//! same `Φ` by L-BFGS with the springs' prefactored stiffness Laplacian as
//! its initial Hessian (Liu, Bouaziz & Kavan 2017): no 3×3-block matrix,
//! three pairs of triangular solves and about two passes over the springs
//! (each giving `Φ` and its gradient) an iteration, the same line search,
//! stopping rule, energy test and substeps. [`Minimizer::Linearized`] is
//! Newton's method stopped after one iteration: Baraff & Witkin's step.
//!
//! Everything that configures a step — the scheme, the minimiser and its
//! stopping rule, the solver, the substeps — is one plain
//! [`ImplicitSettings`] with the library's defaults, which scene files,
//! the lab, the command line and `summary.json` set and report by the same
//! keys ([`ImplicitSettings::from_keys`], [`ImplicitSettings::keys`]), each
//! enum by the names of its one table ([`Named`](hooke_core::Named)).
//!
//! Beside [`Implicit`], [`FastMassSpring`] takes backward-Euler steps the
//! way Liu et al. (2013) do: a fixed number of local/global iterations on a
//! constant, prefactored matrix, converging to the same step. It is an
//! integrator of its own, not a minimiser of the implicit step's `Φ`: no
//! line search, stopping rule, energy test or substeps, contacts resolved
//! after the step.
//!
//! # Layout
//!
//! Three layers, each importing only the ones below it:
//!
//! - `linear`: the block matrix and its pattern, the per-particle filters,
//!   PCG, sparse Cholesky, multigrid, the scalar Laplacian, and the choice
//!   among the solvers;
//! - `minimize`: what a step minimises — its terms as one list ([`Terms`],
//!   contact's barriers and friction among them) and `Φ` over the step's
//!   velocities — and how: a minimiser is one `Descent` (its directions:
//!   Newton's method on the assembled system, L-BFGS on its prefactored
//!   `H₀`), and one line search with its stopping rule and collision
//!   detection's bound iterates any of them; [`Minimizer`] names each and
//!   is the one place that builds its implementation;
//! - `step`: [`Implicit`] and its [`ImplicitSettings`], the caller's step
//!   in substeps, and one attempt at a substep as the list of its stages —
//!   the scheme's predictor, the solver's topology, the pins, the terms'
//!   start, the starting candidates (the linearised solve among them), the
//!   minimisation, the energy test, the error estimate and the commit.
//!
//! [`FastMassSpring`] stands beside `step` on `linear` alone.
//!
//! # Stability, measured
//!
//! Backward Euler and BDF2 are A- and L-stable: no step size makes a linear
//! problem grow, and stiff modes are damped. On nonlinear springs that is
//! not enough: Baraff & Witkin's single linearisation
//! ([`Implicit::linearized`]) cannot see the stretch `δ²/2L` of a spring
//! rotated by `δ` in one step, and on a 24×24 cloth pinned at two corners
//! (0.981 J to start) it peaks at 7.3·10³ J at 10⁴ N/m and 0.1 s steps and at
//! 3.3·10²¹ J at 10¹² N/m and 1 s steps. The converged default never rises
//! above the initial energy (relative 10⁻⁹) on that cloth at any stiffness
//! in 10⁻² … 10¹² N/m and any step in 10⁻⁴ … 1 s, with every step
//! converged; BDF2 stays within 5 % of it; the tests
//! `implicit_robust.rs` hold both, with a tet-lattice cube dropped onto a
//! floor and a chain with a 10⁶ mass ratio between neighbours. The price is
//! paid where the problem is hard: a 1 s step at 10¹² N/m takes thousands
//! of substeps, because rounding limits how far one solve can see
//! (`Implicit::MAX_CONDITION`).
//!
//! # Contact and scripted pins
//!
//! Contact is part of the potential the converged step minimises (Li et
//! al., *Incremental Potential Contact*, 2020): every particle close to an
//! obstacle and every close pair of surface primitives — a point and a
//! triangle, two edges, of one cloth folding onto itself or of two bodies —
//! adds a smooth log barrier on its gap, `κ b(g)`, and a lagged friction
//! potential to `Φ`. Newton's method sees their gradients and Hessians
//! (projected onto their positive parts), and continuous collision
//! detection bounds every line search, so no iterate ever crosses an
//! obstacle or a surface and `Φ` keeps one shape through the iteration
//! (contacts never switch on and off as constraints). The `contact` module
//! gives the equations, the barrier stiffness, the friction's smoothing
//! speed and the handling of moving obstacles; restitution applies to the
//! explicit integrators' contact response only. With contact the
//! linearised step is one Newton step from the feasible start, bounded by
//! collision detection.
//!
//! Pins are removed unknowns: a pinned particle's filter removes it from
//! the conjugate-gradient iteration (or from the Cholesky system), and a
//! scripted pin's velocity change is prescribed, `Δv = y + z` with
//! `S A y = S (b − A z)`, so it ends the step at its path's velocity.
//!
//! # Storage
//!
//! The matrix is symmetric and made of symmetric 3x3 blocks: one diagonal
//! block per particle, and for each spring the same block `−K_s` at `(i, j)`
//! and `(j, i)`. `BlockMatrix` stores each `K_s` once as the six entries of
//! a `SymBlock`, in the `Pattern`'s slot order (springs by their lower
//! endpoint), and multiplies spring by spring, `y = M̃x + Σ_s ±K_s (xᵢ − xⱼ)`:
//! 52 bytes and nine multiply-adds per spring, against `18 × 16` bytes for
//! a scalar compressed-column matrix with 64-bit indices (faer's
//! `SparseColMat`). Measured with `cargo bench --bench implicit -- spmv` on
//! cloth sheets, the block product is 3.0–5.1× faster than faer's at every
//! size from 1 024 to 65 536 particles (1.52 ms against 6.35 ms at 256²), so
//! the crate keeps it and uses faer for the sparse Cholesky factorization.
//! It executes 54 instructions per spring and at 256² reaches 41 % of the
//! machine's STREAM bandwidth; `benches/README.md` says why.
//! The full table and the analysis are in `benches/README.md`.
//!
//! ```
//! use hooke_core::{Integrator, reference::Oscillator};
//! use hooke_implicit::{Implicit, LinearSolver};
//!
//! // One backward-Euler step shrinks the oscillator's amplitude by 1/√(1 + (hω)²).
//! let oscillator = Oscillator::undamped(1.0, 100.0); // ω = 10 rad/s
//! let system = oscillator.system()?;
//! let mut state = system.initial_state();
//! let mut integrator = Implicit::backward_euler().with_solver(LinearSolver::Cholesky);
//! integrator.step(&system, &mut state, 0.1)?; // hω = 1
//! let bob = Oscillator::BOB;
//! let (x, v) = (state.positions()[bob].x, state.velocities()[bob].x);
//! let amplitude = (x * x + v * v / 100.0).sqrt();
//! assert!((amplitude - 1.0 / 2f64.sqrt()).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod fast_mass_spring;
mod linear;
mod minimize;
mod step;

pub use fast_mass_spring::FastMassSpring;
pub use linear::cg::PcgSettings;
pub use linear::cholesky::{Supernodes, WeakSprings};
pub use linear::solver::{AmgRenewal, AutoSettings, LinearSolver};
pub use minimize::bounds::ContactLimit;
pub use minimize::minimizer::Minimizer;
pub use minimize::terms::Terms;
pub use step::error_control::{self, ErrorControl};
pub use step::implicit::Implicit;
pub use step::scheme::Scheme;
pub use step::settings::ImplicitSettings;
pub use step::settings::keys::{KeyError, KeyProblem, KeyValue};

/// The building blocks of a step — the block matrix and its pattern, the
/// filters, PCG, sparse Cholesky and multigrid — for the
/// workspace's tests and benchmarks. Not part of the supported API: an
/// integrator is configured through [`Implicit`] and [`LinearSolver`].
#[doc(hidden)]
pub mod internals {
    pub use crate::linear::amg::{self, Amg, AmgInfo, AmgSettings};
    pub use crate::linear::cg::{self, BlockJacobi};
    pub use crate::linear::cholesky::{
        CholeskyError, CholeskyInfo, FactorPreconditioner, FillOrdering, SparseCholesky,
    };
    pub use crate::linear::filter::{Filter, pin_filters};
    pub use crate::linear::matrix::BlockMatrix;
    pub use crate::linear::pattern::Pattern;
    pub use crate::linear::vector::PARALLEL_MIN_PARTICLES;
    pub use crate::minimize::terms::PARALLEL_MIN_ELEMENTS;
    pub use hooke_core::SymBlock;
}
