//! The minimisation of each implicit (sub)step's incremental potential
//! `Φ`, in three parts that only import downward:
//!
//! - **what is minimised**: the terms of `Φ` as one list (`terms`:
//!   inertia, gravity, air damping, springs, volume elements, contact
//!   barriers and friction, and a system's own), with contact's pairs and
//!   barriers (`contact`), and `Φ` of one step over its velocities
//!   (`objective`: the predictor, the decrement, the limit on a motion);
//! - **how**: a minimiser is a [`Descent`](descent::Descent) — its
//!   directions — and the line search, the stopping rule and collision
//!   detection's bound on every motion are shared (`line_search`). Newton's
//!   method solves the assembled system with the step's linear solver
//!   (`newton`); L-BFGS applies its two-loop recursion around a
//!   prefactored initial Hessian kept across steps (`lbfgs`,
//!   `quasi_newton`); the linearised step is Newton's method stopped after
//!   one iteration;
//! - **which**: the [`Minimizer`](minimizer::Minimizer) setting names each
//!   one in its one table and builds its implementation
//!   (`Minimizer::minimize`), the one place that picks.
//!
//! A new minimiser is its own file implementing `Descent` (its test beside
//! it), one `mod` line here, and in `minimizer.rs` its variant, its name in
//! the table, its properties and the arm that builds it.

pub(crate) mod bounds;
pub(crate) mod contact;
pub(crate) mod descent;
pub(crate) mod lbfgs;
pub(crate) mod line_search;
pub(crate) mod minimizer;
pub(crate) mod newton;
pub(crate) mod objective;
pub(crate) mod quasi_newton;
pub(crate) mod terms;
