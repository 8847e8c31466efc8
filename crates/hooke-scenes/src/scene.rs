//! [`Scene`]: everything a run needs — the system, what its bodies look like,
//! the integrator and the timing.

use hooke_core::System;

use crate::IntegratorSpec;
use crate::body::Placement;

/// A simulation ready to run: a [`System`], the surfaces and segments of
/// its bodies for writing frames, the integrator to use and how long to run.
#[derive(Debug, Clone)]
pub struct Scene {
    /// A name for reports.
    pub name: String,
    /// The system to integrate.
    pub system: System,
    /// The bodies in the system, for output.
    pub bodies: Vec<SceneBody>,
    /// The integrator and its parameters.
    pub integrator: IntegratorSpec,
    /// Duration, step and frame rate.
    pub timing: Timing,
}

/// A body placed in a scene's system.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneBody {
    /// The body's name.
    pub name: String,
    /// Where its particles are in the system.
    pub placement: Placement,
    /// Surface triangles, in system particle indices.
    pub triangles: Vec<[usize; 3]>,
    /// Segments to draw for bodies without a surface (ropes), in system
    /// particle indices.
    pub segments: Vec<[usize; 2]>,
}

/// How long a scene runs and how often it is written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Simulated duration, s.
    pub duration: f64,
    /// Step size, s (the first try, for adaptive integrators).
    pub dt: f64,
    /// Frames written per simulated second.
    pub frame_rate: f64,
}

impl Timing {
    /// Number of steps: `duration / dt`, rounded to the nearest integer.
    #[must_use]
    pub fn steps(&self) -> usize {
        (self.duration / self.dt).round() as usize
    }

    /// Steps between written frames (at least 1).
    #[must_use]
    pub fn steps_per_frame(&self) -> usize {
        ((1.0 / (self.frame_rate * self.dt)).round() as usize).max(1)
    }
}
