//! The minimisers of the incremental potential `Φ`: Newton's method and
//! L-BFGS with their shared line search and stopping rule, the terms of `Φ`
//! (springs, volume elements, contact barriers and friction) and their
//! assembly, and Liu et al.'s fast mass-spring step.

pub(crate) mod assembly;
pub(crate) mod contact;
pub(crate) mod fast_mass_spring;
pub(crate) mod line_search;
pub(crate) mod linearization;
pub(crate) mod newton;
pub(crate) mod potential;
pub(crate) mod quasi_newton;
pub(crate) mod residual;
pub(crate) mod volume;
