//! The minimisers of the incremental potential `Φ`: Newton's method and
//! L-BFGS with their shared line search and stopping rule, and the terms of
//! `Φ` (inertia, gravity, air damping, springs, volume elements, contact
//! barriers and friction, and a system's own) as one list.

pub(crate) mod contact;
pub(crate) mod line_search;
pub(crate) mod newton;
pub(crate) mod quasi_newton;
pub(crate) mod terms;
