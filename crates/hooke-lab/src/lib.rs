//! Measurements of mass-spring integrators on a user's scene.

pub mod plot;
