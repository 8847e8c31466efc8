//! The step's control: [`Implicit`](crate::Implicit) and its settings, the
//! caller's step delivered in substeps that shrink on rejection and grow
//! back (`substeps`) within the conditioning limit (`conditioning`), and
//! one attempt at a substep as the list of its stages (`attempt`): the
//! scheme's predictor (`predictor`), the linear solver's topology, the
//! scripted pins (`pins`), the terms' start, the starting candidates with
//! Baraff & Witkin's linearised solve (`start`), the minimisation by the
//! minimiser the settings name (the `minimize` module), the energy test
//! (`energy`), the local error estimate (`error_control`) and the commit.

pub(crate) mod attempt;
pub(crate) mod builders;
pub(crate) mod comparison;
pub(crate) mod conditioning;
pub(crate) mod energy;
pub mod error_control;
pub(crate) mod implicit;
pub(crate) mod pins;
pub(crate) mod predictor;
pub(crate) mod scheme;
pub(crate) mod settings;
pub(crate) mod start;
pub(crate) mod substeps;
pub(crate) mod work;
