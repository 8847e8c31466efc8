//! A chain of particles laid out in a row: a pendulum when one end is
//! pinned, with closed-form axial frequencies when both are.

use std::f64::consts::PI;

use crate::{BuildError, System, SystemBuilder};

/// `n` particles in a row along +x, `spacing` apart at height `y =
/// height`, each joined to the next by a spring of stiffness `k`, damping
/// `c` and rest length `L` (the spacing unless given), the first particle
/// pinned — and the last, if [`Chain::pin_last`] — released from rest under
/// gravity `g` along −y.
///
/// With one end pinned it is a pendulum chain that swings through large
/// angles; every other particle may be far lighter than its neighbours
/// ([`Chain::odd_particle_mass`]), which makes the system stiff in a way no
/// uniform stiffness does. With both ends pinned, equal masses `m` and no
/// gravity, its `N = n − 2` free particles move along the chain in the
/// modes of a fixed–fixed string of masses,
///
/// ```text
/// ω_j = 2 √(k/m) sin(j π / 2(N + 1)),   j = 1 … N,
/// ```
///
/// ([`Chain::axial_frequencies`]), whatever the rest length: the axial
/// stiffness of a spring is `k` at any tension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
    /// Number of particles `n`, the pinned ones included.
    pub particles: usize,
    /// Mass `m` of each particle (each even-numbered one, where
    /// [`Chain::odd_particle_mass`] is given) in kg.
    pub particle_mass: f64,
    /// The mass of the odd-numbered particles in kg, where it differs from
    /// [`Chain::particle_mass`].
    pub odd_particle_mass: Option<f64>,
    /// Distance between neighbours along x in m.
    pub spacing: f64,
    /// Height `y` of the row in m.
    pub height: f64,
    /// Stiffness `k` of each spring in N/m.
    pub stiffness: f64,
    /// Axial damping `c` of each spring in N·s/m.
    pub damping: f64,
    /// Rest length `L` of each spring in m (`None`: the spacing).
    pub rest_length: Option<f64>,
    /// Whether the last particle is pinned as well as the first.
    pub pin_last: bool,
    /// Gravitational acceleration `g` in m/s² along −y (none if zero).
    pub gravity: f64,
}

impl Chain {
    /// An undamped pendulum chain of equal masses `m` (kg), `spacing` (m)
    /// apart at `y = 0`, on springs of stiffness `k` (N/m) at their rest
    /// length, its first particle pinned, under standard gravity, 9.81 m/s².
    #[must_use]
    pub fn pendulum(particles: usize, particle_mass: f64, stiffness: f64, spacing: f64) -> Self {
        Self {
            particles,
            particle_mass,
            odd_particle_mass: None,
            spacing,
            height: 0.0,
            stiffness,
            damping: 0.0,
            rest_length: None,
            pin_last: false,
            gravity: 9.81,
        }
    }

    /// A chain of equal masses `m` (kg), `spacing` (m) apart, on springs of
    /// stiffness `k` (N/m) at their rest length, pinned at both ends,
    /// without gravity: the fixed–fixed chain of
    /// [`Chain::axial_frequencies`].
    #[must_use]
    pub fn fixed_fixed(particles: usize, particle_mass: f64, stiffness: f64, spacing: f64) -> Self {
        Self {
            pin_last: true,
            gravity: 0.0,
            ..Self::pendulum(particles, particle_mass, stiffness, spacing)
        }
    }

    /// The builder holding the chain, for a test to add to (an obstacle,
    /// say) before it builds: particle `s` at `(s · spacing, height, 0)`.
    #[must_use]
    pub fn builder(&self) -> SystemBuilder {
        let mut b = SystemBuilder::new();
        for s in 0..self.particles {
            let mass = match self.odd_particle_mass {
                Some(odd) if s % 2 == 1 => odd,
                _ => self.particle_mass,
            };
            b.particle(mass, [self.spacing * s as f64, self.height, 0.0]);
        }
        for s in 1..self.particles {
            let spring = b.spring(s - 1, s, self.stiffness).damping(self.damping);
            if let Some(rest_length) = self.rest_length {
                spring.rest_length(rest_length);
            }
        }
        if self.particles > 0 {
            b.pin(0);
        }
        if self.pin_last && self.particles > 1 {
            b.pin(self.particles - 1);
        }
        if self.gravity != 0.0 {
            b.gravity([0.0, -self.gravity, 0.0]);
        }
        b
    }

    /// The system ([`Chain::builder`], built).
    ///
    /// # Errors
    /// A [`BuildError`] for invalid masses, stiffness, lengths or damping.
    pub fn system(&self) -> Result<System, BuildError> {
        self.builder().build()
    }

    /// The angular frequencies of the axial modes of a chain pinned at both
    /// ends with equal masses, `2 √(k/m) sin(j π / 2(N + 1))` for the
    /// `N = n − 2` free particles, lowest first; `None` for a chain with an
    /// end free or unequal masses.
    ///
    /// ```
    /// use hooke_core::reference::Chain;
    /// // Three free masses: ω² = (2 − √2, 2, 2 + √2) k/m.
    /// let omega = Chain::fixed_fixed(5, 1.0, 1.0, 0.1).axial_frequencies().unwrap();
    /// let expected = [2.0 - 2f64.sqrt(), 2.0, 2.0 + 2f64.sqrt()].map(f64::sqrt);
    /// assert!(omega.iter().zip(expected).all(|(w, e)| (w - e).abs() < 1e-12));
    /// ```
    #[must_use]
    pub fn axial_frequencies(&self) -> Option<Vec<f64>> {
        if !self.pin_last || self.odd_particle_mass.is_some() {
            return None;
        }
        let free = self.particles.saturating_sub(2);
        let scale = 2.0 * (self.stiffness / self.particle_mass).sqrt();
        let modes = 2.0 * (free + 1) as f64;
        Some(
            (1..=free)
                .map(|j| scale * (j as f64 * PI / modes).sin())
                .collect(),
        )
    }
}
