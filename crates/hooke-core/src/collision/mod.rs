//! Contact between the surfaces of a system's bodies, and the barrier that
//! every kind of contact pair shares: the geometry that the implicit step's
//! barrier terms and its continuous collision detection are built from
//! (an obstacle's own is its [`Shape`](crate::Shape)'s).
//!
//! - [`distance`]: point–triangle and edge–edge distances with their
//!   gradients and Hessians, the edge–edge mollifier;
//! - [`barrier`]: the smooth log barrier of Li et al. (*Incremental
//!   Potential Contact*, 2020) with its stiffness ([`barrier::Barrier`]),
//!   on a gap or a surface pair's coordinates, and the projection of a
//!   pair's Hessian onto its positive part;
//! - [`ccd`]: additive continuous collision detection (Li, Kaufman &
//!   Jiang, *Codimensional Incremental Potential Contact*, 2021);
//! - [`surface`]: a system's collision surfaces (triangles, their edges and
//!   vertices);
//! - [`broad`]: the broad phase, a spatial hash of the primitives' boxes;
//! - [`intersect`]: exact triangle–triangle intersection, for reports.

pub mod barrier;
pub mod broad;
pub mod ccd;
pub mod distance;
pub mod intersect;
pub mod surface;
