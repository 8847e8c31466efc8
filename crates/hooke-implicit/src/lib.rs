//! Implicit integration of mass-spring systems on an assembled sparse
//! system: backward Euler in the style of Baraff & Witkin (1998) and BDF2,
//! solved by constraint-filtered PCG or sparse Cholesky.
//!
//! Stiff springs limit every explicit method to `h < 2/ω_max`; a linearly
//! implicit step is stable at any step size (see [`Implicit`] for the
//! equations). Per step:
//!
//! 1. **Assembly** ([`Assembler`]): the spring Hessian
//!    blocks `H` and damping blocks `c d dᵀ` from `hooke-core` are combined
//!    into `A = M + βh C + β²h² K` and the right-hand side, in two parallel
//!    passes that never allocate: one per spring, one per block row. The
//!    [`Pattern`] comes from the topology and is built once.
//! 2. **Solve**: [`cg::solve`] (Baraff–Witkin's modified PCG, block-Jacobi
//!    preconditioned, pins and other per-particle constraints acting through
//!    the [`Filter`] inside the loop) or [`SparseCholesky`] (faer, symbolic
//!    analysis reused) on the same filtered system.
//! 3. Optional **Newton iterations** with a backtracking line search on the
//!    incremental potential.
//!
//! # Storage
//!
//! The matrix is symmetric and made of 3x3 blocks: one diagonal block per
//! particle, and for each spring the same block `−K_s` at `(i, j)` and
//! `(j, i)`. [`BlockMatrix`] stores each `K_s` once, with 32-bit
//! `(column, spring)` entries per block row, so a matrix-vector product moves
//! about `72 + 16` bytes per spring, against `18 × 16` for a scalar
//! compressed-column matrix with 64-bit indices (faer's `SparseColMat`). The
//! benchmark `cargo bench --bench implicit -- spmv` compares the two on cloth;
//! the measured table is in `benches/README.md`.
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

mod assembly;
pub mod cg;
mod cholesky;
mod filter;
mod implicit;
mod matrix;
mod pattern;
mod vector;

pub use assembly::{Assembler, Linearization};
pub use cg::{BlockJacobi, PcgSettings};
pub use cholesky::SparseCholesky;
pub use filter::Filter;
pub use implicit::{Implicit, LinearSolver, Scheme};
pub use matrix::BlockMatrix;
pub use pattern::{Entry, Pattern};
pub use vector::PARALLEL_MIN_PARTICLES;
