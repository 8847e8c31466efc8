//! A chain hanging under gravity, with its exact rest configuration.

use crate::{BuildError, System, SystemBuilder, Vec3};

/// `n` equal particles joined by `n − 1` equal springs, the top one pinned at
/// the origin, hanging along −y under gravity `g`.
///
/// At rest every particle is in equilibrium, so the spring below particle
/// `s` carries the weight of all particles below it:
///
/// ```text
/// T_s = m g (n − 1 − s),   l_s = L + T_s / k,   y_{s+1} = y_s − l_s.
/// ```
///
/// [`HangingChain::system`] starts the chain unstretched (every spring at its
/// rest length), so it has to fall and settle into that configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HangingChain {
    /// Number of particles `n`, the pinned one included.
    pub particles: usize,
    /// Mass of each particle `m` in kg.
    pub particle_mass: f64,
    /// Stiffness of each spring `k` in N/m.
    pub stiffness: f64,
    /// Rest length of each spring `L` in m.
    pub segment_length: f64,
    /// Gravitational acceleration `g` in m/s² (pointing along −y).
    pub gravity: f64,
    /// Axial damping `c` of each spring in N·s/m.
    pub spring_damping: f64,
    /// Air damping `γ` in N·s/m (none if zero).
    pub air_damping: f64,
}

impl HangingChain {
    /// An undamped chain under standard gravity, 9.81 m/s².
    #[must_use]
    pub fn new(particles: usize, particle_mass: f64, stiffness: f64, segment_length: f64) -> Self {
        Self {
            particles,
            particle_mass,
            stiffness,
            segment_length,
            gravity: 9.81,
            spring_damping: 0.0,
            air_damping: 0.0,
        }
    }

    /// The same chain with spring damping `c` and air damping `γ`.
    #[must_use]
    pub fn damped(self, spring_damping: f64, air_damping: f64) -> Self {
        Self {
            spring_damping,
            air_damping,
            ..self
        }
    }

    /// The system, particle `s` at `(0, −s L, 0)`, particle 0 pinned.
    ///
    /// # Errors
    /// A [`BuildError`] for invalid masses, stiffness, lengths or damping.
    pub fn system(&self) -> Result<System, BuildError> {
        let mut b = SystemBuilder::new();
        for s in 0..self.particles {
            b.particle(
                self.particle_mass,
                [0.0, -(s as f64) * self.segment_length, 0.0],
            );
        }
        for s in 1..self.particles {
            b.spring(s - 1, s, self.stiffness)
                .rest_length(self.segment_length)
                .damping(self.spring_damping);
        }
        if self.particles > 0 {
            b.pin(0);
        }
        b.gravity([0.0, -self.gravity, 0.0]);
        if self.air_damping > 0.0 {
            b.air_damping(self.air_damping);
        }
        b.build()
    }

    /// Tension `T_s = m g (n − 1 − s)` in the spring between particles `s`
    /// and `s + 1`, in N.
    #[must_use]
    pub fn tension(&self, segment: usize) -> f64 {
        let below = self.particles.saturating_sub(segment + 1);
        self.particle_mass * self.gravity * below as f64
    }

    /// Exact rest positions of all particles.
    #[must_use]
    pub fn rest_positions(&self) -> Vec<Vec3> {
        let mut y = 0.0;
        (0..self.particles)
            .map(|s| {
                if s > 0 {
                    y -= self.segment_length + self.tension(s - 1) / self.stiffness;
                }
                Vec3::new(0.0, y, 0.0)
            })
            .collect()
    }
}
