//! Energy, dissipated power and strain of a state, for energy-balance checks
//! and observers.
//!
//! With gravity, the springs and the volume elements as the only forces
//! besides the dampers, and pins at rest, the total energy obeys
//!
//! ```text
//! d/dt (T + V_springs + V_volume + V_gravity) = −P_dissipation,
//! T = Σ ½ mᵢ|vᵢ|²,   V_springs = Σ ½ k (l − L)²,   V_gravity = −Σ mᵢ g·xᵢ,
//! V_volume = Σ_tets ½ κ V₀ (J − 1)²,
//! P_dissipation = Σ_springs c ((vᵢ − vⱼ)·d)² + Σ_free γ |vᵢ|²  ≥ 0,
//! ```
//!
//! so `E(t) + ∫₀ᵗ P dt = E(0)` holds for the exact motion, and the gap is a
//! measure of an integrator's energy error. The system's own terms
//! ([`System::terms`]) add their energy to `E` and their dissipation to
//! `P`; a term driven from outside (a wind) also does work `W(t)` on the
//! particles, and then `E(t) + ∫₀ᵗ P dt = E(0) + W(t)`.

use crate::{State, StepError, System, When};

/// The parts of a state's mechanical energy, in joules.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energy {
    /// Kinetic energy `Σ ½ mᵢ |vᵢ|²`.
    pub kinetic: f64,
    /// Elastic energy of the springs `Σ ½ k (l − L)²` and of the volume
    /// elements `Σ ½ κ V₀ (J − 1)²`.
    pub elastic: f64,
    /// Gravitational potential `−Σ mᵢ g·xᵢ` (zero without gravity).
    pub gravitational: f64,
    /// The energy of the system's own terms ([`System::terms`]; zero
    /// without them).
    pub terms: f64,
}

impl Energy {
    /// Kinetic plus elastic plus gravitational energy, plus the terms'.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.kinetic + self.elastic + self.gravitational + self.terms
    }
}

impl System {
    /// The energy of `state`.
    ///
    /// ```
    /// # use hooke_core::SystemBuilder;
    /// let mut b = SystemBuilder::new();
    /// let p = b.particle_with_velocity(2.0, [0.0, 1.0, 0.0], [3.0, 0.0, 0.0]);
    /// b.gravity([0.0, -10.0, 0.0]);
    /// let system = b.build()?;
    /// let e = system.energy(&system.initial_state())?;
    /// assert_eq!(e.kinetic, 9.0);         // ½·2·3²
    /// assert_eq!(e.gravitational, 20.0);  // −2·(−10)·1
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`StepError::StateMismatch`] for a state of another size.
    pub fn energy(&self, state: &State) -> Result<Energy, StepError> {
        self.check_state(state)?;
        let (x, v) = (state.positions(), state.velocities());
        let kinetic = self
            .masses
            .iter()
            .zip(v)
            .map(|(m, vi)| 0.5 * m * vi.norm_squared())
            .sum();
        let elastic = self
            .springs
            .iter()
            .map(|s| s.energy(x[s.i], x[s.j]))
            .chain(self.tets.iter().map(|t| t.energy(x)))
            .sum();
        let gravitational = self.gravity.map_or(0.0, |g| {
            -self
                .masses
                .iter()
                .zip(x)
                .map(|(m, xi)| m * g.dot(xi))
                .sum::<f64>()
        });
        // A term evaluates with scratch of its own (a step lags state in its
        // copies), so the system's terms are evaluated on copies: a system
        // without terms allocates nothing.
        let terms = self
            .terms
            .iter()
            .map(|t| t.clone_box().energy(self, x, v, When::End).value)
            .sum();
        Ok(Energy {
            kinetic,
            elastic,
            gravitational,
            terms,
        })
    }

    /// Power `P ≥ 0` removed by spring dampers, air damping and the
    /// system's own terms ([`System::terms`]) in `state`,
    ///
    /// ```text
    /// P = Σ_springs c ((vᵢ − vⱼ)·d)² + Σ_free γ |vᵢ|² + Σ_terms P_term,
    /// ```
    ///
    /// each term's as it gives it ([`Term::dissipation_power`](crate::Term::dissipation_power); for a
    /// [`Wind`](crate::Wind), `Σ_T c A ((v_T − w)·n)²`). Air damping on
    /// pinned particles is resisted by the pin and not counted. A term's
    /// external work (a wind's) is not a dissipation and is not in `P`, so
    /// with such terms `E(t) + ∫₀ᵗ P dt` is `E(0)` plus that work.
    ///
    /// # Errors
    /// [`StepError::StateMismatch`] for a state of another size.
    pub fn dissipation_power(&self, state: &State) -> Result<f64, StepError> {
        self.check_state(state)?;
        let (x, v) = (state.positions(), state.velocities());
        let springs: f64 = self
            .springs
            .iter()
            .map(|s| s.dissipation_power(x[s.i], x[s.j], v[s.i], v[s.j]))
            .sum();
        let air = self.air_damping.map_or(0.0, |gamma| {
            gamma
                * v.iter()
                    .zip(&self.pinned)
                    .filter(|&(_, &pinned)| !pinned)
                    .map(|(vi, _)| vi.norm_squared())
                    .sum::<f64>()
        });
        let terms: f64 = self
            .terms
            .iter()
            .map(|t| t.dissipation_power(self, x, v))
            .sum();
        Ok(springs + air + terms)
    }

    /// Largest absolute strain `|l − L|/L` over the springs with positive rest
    /// length (0 if there are none).
    ///
    /// # Errors
    /// [`StepError::StateMismatch`] for a state of another size.
    pub fn max_strain(&self, state: &State) -> Result<f64, StepError> {
        self.check_state(state)?;
        let x = state.positions();
        Ok(self
            .springs
            .iter()
            .filter_map(|s| s.strain(x[s.i], x[s.j]))
            .fold(0.0, |max, e| max.max(e.abs())))
    }
}
