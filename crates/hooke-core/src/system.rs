//! [`System`]: the topology and parameters of a mass-spring system, immutable
//! while stepping.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::collision::surface::CollisionMesh;
use crate::{
    BuildError, Obstacle, Path, Spring, SpringParameter, State, StepError, Term, Tet, Vec3,
};

static NEXT_SYSTEM_ID: AtomicU64 = AtomicU64::new(1);

/// Particles, springs and global force terms, validated by
/// [`crate::SystemBuilder`] and immutable afterwards.
///
/// The equations of motion are `M x'' = f(x, v)` with `M` diagonal and
///
/// ```text
/// fᵢ = Σ_springs fᵢ^spring  +  mᵢ g  −  γ vᵢ
/// ```
///
/// plus the forces of the volume elements ([`Tet`]) and of the system's own
/// [`Term`]s ([`System::terms`]), where gravity `g` and air damping `γ` are
/// present only if the system declares them. A pinned particle has zero
/// acceleration: it keeps its initial velocity (zero unless one was given),
/// whatever force acts on it.
#[derive(Debug, Clone)]
pub struct System {
    pub(crate) id: u64,
    pub(crate) masses: Vec<f64>,
    /// `1/mᵢ`, or 0 for pinned particles.
    pub(crate) inverse_masses: Vec<f64>,
    pub(crate) pinned: Vec<bool>,
    pub(crate) initial_positions: Vec<Vec3>,
    pub(crate) initial_velocities: Vec<Vec3>,
    pub(crate) springs: Vec<Spring>,
    pub(crate) tets: Vec<Tet>,
    pub(crate) gravity: Option<Vec3>,
    pub(crate) air_damping: Option<f64>,
    pub(crate) obstacles: Vec<Obstacle>,
    /// Scripted pins, sorted by particle.
    pub(crate) pin_paths: Vec<(usize, Path)>,
    pub(crate) surfaces: CollisionMesh,
    /// Per surface (group of `surfaces`): its thickness, m, and friction
    /// coefficient.
    pub(crate) surface_properties: Vec<[f64; 2]>,
    pub(crate) contact_distance: f64,
    /// The terms declared beyond the springs, volume elements, gravity and
    /// air damping.
    pub(crate) terms: Vec<Box<dyn Term>>,
}

/// The state of a system's volume elements ([`System::inversion`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inversion {
    /// Elements with volume ratio `J ≤ 0` (or not a number).
    pub inverted: usize,
    /// The smallest volume ratio `J = V/V₀`.
    pub smallest_ratio: f64,
}

pub(crate) fn fresh_system_id() -> u64 {
    NEXT_SYSTEM_ID.fetch_add(1, Ordering::Relaxed)
}

impl System {
    /// A number that identifies this system within the process (a clone
    /// shares it), for caches keyed on the system, such as a solver's
    /// sparsity pattern.
    #[must_use]
    pub fn id(&self) -> u64 {
        self.id
    }

    /// Number of particles.
    #[must_use]
    pub fn particle_count(&self) -> usize {
        self.masses.len()
    }

    /// Particle masses `mᵢ` in kg.
    #[must_use]
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }

    /// Inverse masses `1/mᵢ`, with 0 for pinned particles: `aᵢ = fᵢ/mᵢ` for
    /// free particles and 0 for pinned ones.
    #[must_use]
    pub fn inverse_masses(&self) -> &[f64] {
        &self.inverse_masses
    }

    /// Whether particle `i` is pinned; `false` for an index out of range.
    #[must_use]
    pub fn is_pinned(&self, i: usize) -> bool {
        self.pinned.get(i).copied().unwrap_or(false)
    }

    /// The scripted pins: each pinned particle that moves along a path, in
    /// increasing order of particle.
    #[must_use]
    pub fn pin_paths(&self) -> &[(usize, Path)] {
        &self.pin_paths
    }

    /// What every integrator does at the end of a step: moves the scripted
    /// pins to their paths at the state's time, then resolves contacts with
    /// the obstacles ([`System::resolve_contacts`]); returns the number of
    /// contacts. Does nothing for a system with neither.
    ///
    /// Placing a scripted pin does not count as editing the state: the other
    /// particles' history stays valid.
    pub fn end_step(&self, state: &mut State) -> usize {
        if !self.pin_paths.is_empty() {
            let t = state.time();
            let (positions, velocities) = state.pins_mut();
            for (i, path) in &self.pin_paths {
                positions[*i] = self.initial_positions[*i] + path.offset(t);
                velocities[*i] = path.velocity(t);
            }
        }
        self.resolve_contacts(state)
    }

    /// Indices of the pinned particles, in increasing order.
    pub fn pinned(&self) -> impl Iterator<Item = usize> + '_ {
        self.pinned
            .iter()
            .enumerate()
            .filter_map(|(i, &p)| p.then_some(i))
    }

    /// The springs, in the order they were added.
    #[must_use]
    pub fn springs(&self) -> &[Spring] {
        &self.springs
    }

    /// The volume elements, in the order they were added.
    #[must_use]
    pub fn tets(&self) -> &[Tet] {
        &self.tets
    }

    /// Adds the forces of the volume elements at positions `x` to `f`
    /// (those of modulus 0 have none).
    ///
    /// # Panics
    /// If an element names a particle beyond `x` or `f`.
    pub fn add_volume_forces(&self, x: &[Vec3], f: &mut [Vec3]) {
        for t in self.tets.iter().filter(|t| t.modulus > 0.0) {
            for (&i, fi) in t.vertices.iter().zip(t.forces(x)) {
                f[i] += fi;
            }
        }
    }

    /// How many volume elements are inverted (volume ratio `J ≤ 0`) at
    /// positions `x`, and the smallest `J`; `None` for a system without
    /// volume elements.
    ///
    /// # Panics
    /// If `x` does not have one entry per particle.
    #[must_use]
    pub fn inversion(&self, x: &[Vec3]) -> Option<Inversion> {
        assert_eq!(x.len(), self.particle_count(), "one position per particle");
        self.tets
            .iter()
            .map(|t| t.volume_ratio(x))
            .fold(None, |acc, j| {
                let Inversion {
                    inverted,
                    smallest_ratio,
                } = acc.unwrap_or(Inversion {
                    inverted: 0,
                    smallest_ratio: f64::INFINITY,
                });
                Some(Inversion {
                    inverted: inverted + usize::from(j <= 0.0 || j.is_nan()),
                    smallest_ratio: smallest_ratio.min(j),
                })
            })
    }

    /// The terms the system declares beyond its springs, volume elements,
    /// gravity and air damping ([`SystemBuilder::term`](crate::SystemBuilder::term)),
    /// in the order they were added: every integrator includes them, the
    /// explicit ones through [`Term::force`], the implicit ones in the
    /// potential they minimise. A step evaluates its own copies
    /// ([`Term::clone_box`](crate::term::TermClone::clone_box)), in which it
    /// lags what the terms lag.
    #[must_use]
    pub fn terms(&self) -> &[Box<dyn Term>] {
        &self.terms
    }

    /// Gravitational acceleration `g`, if the system has gravity.
    #[must_use]
    pub fn gravity(&self) -> Option<Vec3> {
        self.gravity
    }

    /// Air-damping coefficient `γ` (force `−γ vᵢ` on every particle), if the
    /// system has air damping.
    #[must_use]
    pub fn air_damping(&self) -> Option<f64> {
        self.air_damping
    }

    /// Initial positions, as given to the builder.
    #[must_use]
    pub fn initial_positions(&self) -> &[Vec3] {
        &self.initial_positions
    }

    /// Initial velocities, as given to the builder (zero where none was
    /// given).
    #[must_use]
    pub fn initial_velocities(&self) -> &[Vec3] {
        &self.initial_velocities
    }

    /// Checks that `state` has one entry per particle of this system.
    ///
    /// # Errors
    /// [`StepError::StateMismatch`] otherwise.
    pub fn check_state(&self, state: &State) -> Result<(), StepError> {
        if state.len() == self.particle_count() {
            Ok(())
        } else {
            Err(StepError::StateMismatch {
                state: state.len(),
                system: self.particle_count(),
            })
        }
    }

    /// This system with every spring's stiffness and every volume
    /// element's modulus multiplied by `factor`: the same particles, rest
    /// lengths, damping, forces, terms and obstacles, as a new system with
    /// its own [`System::id`]. The natural frequencies of the undamped
    /// system scale as `√factor` where its springs and elements hold all
    /// its stiffness.
    ///
    /// ```
    /// # use hooke_core::reference::Oscillator;
    /// let system = Oscillator::undamped(1.0, 4.0).system()?;
    /// let stiffer = system.with_stiffness_scale(100.0)?;
    /// assert_eq!(stiffer.springs()[0].stiffness, 400.0);
    /// assert_ne!(stiffer.id(), system.id());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`BuildError::InvalidSpringParameter`] naming the first spring whose
    /// scaled stiffness is negative, NaN or infinite (a `factor` that is
    /// negative or not finite, or one that overflows a stiffness);
    /// [`BuildError::InvalidTet`] likewise for a volume element's modulus.
    pub fn with_stiffness_scale(&self, factor: f64) -> Result<Self, BuildError> {
        let mut scaled = self.clone();
        scaled.id = fresh_system_id();
        for (spring, s) in scaled.springs.iter_mut().enumerate() {
            let value = s.stiffness * factor;
            if !(value.is_finite() && value >= 0.0) {
                return Err(BuildError::InvalidSpringParameter {
                    spring,
                    parameter: SpringParameter::Stiffness,
                    value,
                });
            }
            s.stiffness = value;
        }
        for (tet, t) in scaled.tets.iter_mut().enumerate() {
            let value = t.modulus * factor;
            if !(value.is_finite() && value >= 0.0) {
                return Err(BuildError::InvalidTet {
                    tet,
                    problem: format!("scaled modulus must be finite and non-negative, got {value}"),
                });
            }
            t.modulus = value;
        }
        Ok(scaled)
    }

    /// A fresh state at the initial positions and velocities, at `t = 0`.
    #[must_use]
    pub fn initial_state(&self) -> State {
        State::new(
            self.initial_positions.clone(),
            self.initial_velocities.clone(),
        )
    }
}
