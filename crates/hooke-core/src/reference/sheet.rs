//! A square cloth sheet: the workload the tests, examples and benchmarks
//! share, in the variants they use.

use crate::{BuildError, State, System, SystemBuilder};

/// An `n`×`n` grid of particles spanning `size`×`size` m in the horizontal
/// plane `y = height`, with the spring families of cloth:
///
/// - structural (stretch) springs between row and column neighbours,
///   `2n(n − 1)` of them;
/// - shear springs along both diagonals of every cell, `2(n − 1)²`;
/// - bending springs between particles two apart in a row or column,
///   `2n(n − 2)`;
///
/// all of stiffness `k`, damping `c` and rest length their initial length
/// unless [`Sheet::shear`] or [`Sheet::bend`] give a family its own, under
/// gravity, pinned at the two corners of the first row. With one stiffness
/// its stiffest mode has `ω ≈ 2√(Σk/m)` over the springs at a particle,
/// which sets the explicit integrators' step limit.
///
/// The named variants are the workloads that several tests, examples and
/// benchmarks share: [`Sheet::new`], [`Sheet::cloth`] (the solver
/// benchmarks' cloth), [`Sheet::conservative`] (the table of extreme
/// stiffness and step) and [`Sheet::with_stiffness_ratio`] (a sheet as stiff
/// as a step makes it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sheet {
    /// Particles per side `n` (at least 2).
    pub particles_per_side: usize,
    /// Side length in m.
    pub size: f64,
    /// Height `y` of the sheet's plane in m.
    pub height: f64,
    /// Total mass in kg.
    pub mass: f64,
    /// Whether the mass is lumped from the cells, a quarter of each cell's
    /// mass to each of its corners (an edge particle then holds half an
    /// interior particle's mass, a corner a quarter, as in
    /// `hooke_scenes::Cloth`), rather than shared equally.
    pub lumped: bool,
    /// Stiffness of the stretch springs, and of every family without its
    /// own, in N/m.
    pub stiffness: f64,
    /// Axial damping of the stretch springs, and of every family without
    /// its own, in N·s/m.
    pub damping: f64,
    /// The shear springs' own stiffness and damping (`None`: `stiffness`
    /// and `damping`).
    pub shear: Option<SpringFamily>,
    /// The bending springs' own stiffness and damping (`None`: `stiffness`
    /// and `damping`).
    pub bend: Option<SpringFamily>,
    /// Gravitational acceleration along −y in m/s².
    pub gravity: f64,
    /// Air damping `γ` in N·s/m (none if zero).
    pub air_damping: f64,
}

/// The stiffness and damping of one family of a [`Sheet`]'s springs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringFamily {
    /// Stiffness in N/m.
    pub stiffness: f64,
    /// Axial damping in N·s/m.
    pub damping: f64,
}

impl Sheet {
    /// A 1 m, 0.3 kg sheet of `n`×`n` particles at `y = 0` with 2000 N/m
    /// springs, light damping (`c = 0.01`, `γ = 10⁻⁴`) and standard gravity,
    /// its mass shared equally.
    #[must_use]
    pub fn new(particles_per_side: usize) -> Self {
        Self {
            particles_per_side,
            size: 1.0,
            height: 0.0,
            mass: 0.3,
            lumped: false,
            stiffness: 2000.0,
            damping: 0.01,
            shear: None,
            bend: None,
            gravity: 9.81,
            air_damping: 1e-4,
        }
    }

    /// The cloth of the solver benchmarks and of the tests that measure the
    /// linear solvers and minimisers on it: 1 m, 1 kg lumped from the
    /// cells, stretch / shear / bending springs of 5000 / 500 / 50 N/m, the
    /// stretch and shear springs damped by `damping` (N·s/m) and the
    /// bending ones undamped, no air damping, standard gravity.
    ///
    /// ```
    /// use hooke_core::reference::Sheet;
    /// let system = Sheet::cloth(3, 0.05).system()?;
    /// let masses = system.masses();
    /// assert_eq!((masses[0], masses[1], masses[4]), (1.0 / 16.0, 1.0 / 8.0, 1.0 / 4.0));
    /// let bending = system.springs().iter().filter(|s| s.stiffness == 50.0);
    /// assert!(bending.clone().count() == 6 && bending.clone().all(|s| s.damping == 0.0));
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    #[must_use]
    pub fn cloth(particles_per_side: usize, damping: f64) -> Self {
        Self {
            mass: 1.0,
            lumped: true,
            stiffness: 5000.0,
            damping,
            shear: Some(SpringFamily {
                stiffness: 500.0,
                damping,
            }),
            bend: Some(SpringFamily {
                stiffness: 50.0,
                damping: 0.0,
            }),
            air_damping: 0.0,
            ..Self::new(particles_per_side)
        }
    }

    /// A 24×24 sheet of 0.1 kg, every spring of stiffness `k`, pinned 1 m
    /// up and undamped: the exact motion keeps its energy, which starts at
    /// `m g h` = 0.981 J ([`Sheet::initial_energy`]), so whatever it gains
    /// is the integrator's. The cloth of the table of extreme stiffness and
    /// step (10⁻² … 10¹² N/m, 10⁻⁴ … 1 s).
    #[must_use]
    pub fn conservative(stiffness: f64) -> Self {
        Self {
            mass: 0.1,
            stiffness,
            damping: 0.0,
            air_damping: 0.0,
            height: 1.0,
            ..Self::new(24)
        }
    }

    /// The same sheet with every spring as stiff as `k h²/m = ratio` makes
    /// it at the step `h` (s), `m` the particle mass shared equally: the
    /// sheet's stiffness measured in the steps an implicit integrator
    /// takes (explicit ones need `h ≲ 2/ω ≈ √(m/k)`).
    #[must_use]
    pub fn with_stiffness_ratio(self, ratio: f64, h: f64) -> Self {
        let n = self.particles_per_side;
        let particle_mass = self.mass / (n * n) as f64;
        Self {
            stiffness: ratio * particle_mass / (h * h),
            ..self
        }
    }

    /// Index of the particle in `row` and `col`.
    #[must_use]
    pub fn index(&self, row: usize, col: usize) -> usize {
        row * self.particles_per_side + col
    }

    /// Number of springs, `2n(n − 1) + 2(n − 1)² + 2n(n − 2)`.
    #[must_use]
    pub fn spring_count(&self) -> usize {
        let n = self.particles_per_side;
        if n < 2 {
            return 0;
        }
        2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n - 2)
    }

    /// The energy at the start, `m g h`: the sheet starts at rest with
    /// every spring at its rest length, so all of it is gravity's.
    #[must_use]
    pub fn initial_energy(&self) -> f64 {
        self.mass * self.gravity * self.height
    }

    /// `system`'s initial state (this sheet's) with the sheet waved out of
    /// its plane, at rest: `y = height + 0.02 sin 7x cos 5z` (m). A flat
    /// sheet has no stiffness across its plane, so a step from it solves
    /// trivially there; the wave's springs are stretched and turned.
    #[must_use]
    pub fn wavy(&self, system: &System) -> State {
        let mut state = system.initial_state();
        for x in state.positions_mut() {
            x.y = self.height + 0.02 * (7.0 * x.x).sin() * (5.0 * x.z).cos();
        }
        state
    }

    /// The system. A particle's springs are added together, to its
    /// neighbours further along the grid.
    ///
    /// # Errors
    /// A [`BuildError`] for fewer than two particles per side (the corner
    /// pins name particles that do not exist, or the spacing is not finite)
    /// or invalid parameters.
    pub fn system(&self) -> Result<System, BuildError> {
        let n = self.particles_per_side;
        let spacing = self.size / n.saturating_sub(1) as f64;
        let mut b = SystemBuilder::new();
        for row in 0..n {
            for col in 0..n {
                b.particle(
                    self.particle_mass(row, col),
                    [col as f64 * spacing, self.height, row as f64 * spacing],
                );
            }
        }
        let stretch = SpringFamily {
            stiffness: self.stiffness,
            damping: self.damping,
        };
        let (shear, bend) = (self.shear.unwrap_or(stretch), self.bend.unwrap_or(stretch));
        // (rows down, columns across): stretch, shear, and bending over two cells.
        let neighbours: [(usize, isize, SpringFamily); 6] = [
            (0, 1, stretch),
            (1, 0, stretch),
            (1, 1, shear),
            (1, -1, shear),
            (0, 2, bend),
            (2, 0, bend),
        ];
        for row in 0..n {
            for col in 0..n {
                for (down, across, family) in neighbours {
                    let (r, c) = (row + down, col.checked_add_signed(across));
                    if let Some(c) = c.filter(|&c| c < n && r < n) {
                        b.spring(self.index(row, col), self.index(r, c), family.stiffness)
                            .damping(family.damping);
                    }
                }
            }
        }
        b.pin(0).pin(n.saturating_sub(1));
        b.gravity([0.0, -self.gravity, 0.0]);
        if self.air_damping > 0.0 {
            b.air_damping(self.air_damping);
        }
        b.build()
    }

    /// The mass of the particle in `row` and `col`: an equal share, or
    /// lumped from the cells it touches.
    fn particle_mass(&self, row: usize, col: usize) -> f64 {
        let n = self.particles_per_side;
        if !self.lumped {
            return self.mass / (n * n) as f64;
        }
        let cell_mass = self.mass / (n.saturating_sub(1) * n.saturating_sub(1)) as f64;
        let touching = |k: usize| usize::from(k > 0) + usize::from(k + 1 < n);
        cell_mass * (touching(row) * touching(col)) as f64 / 4.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_families_match_the_hand_count() {
        // 3×3: 12 structural, 8 shear, 6 bending.
        assert_eq!(Sheet::new(3).spring_count(), 26);
        for n in [2, 3, 4, 7] {
            for sheet in [Sheet::new(n), Sheet::cloth(n, 0.05)] {
                let system = sheet.system().unwrap();
                assert_eq!(system.springs().len(), sheet.spring_count(), "n = {n}");
                assert_eq!(system.pinned().collect::<Vec<_>>(), vec![0, n - 1]);
                let total: f64 = system.masses().iter().sum();
                assert!((total - sheet.mass).abs() < 1e-12);
            }
        }
    }

    /// Each family's springs have its stiffness and damping, told apart by
    /// their rest lengths: the grid's spacing `s`, `√2 s` and `2 s`.
    #[test]
    fn every_family_has_its_own_springs() {
        let sheet = Sheet::cloth(5, 0.05);
        let s = 0.25;
        for spring in sheet.system().unwrap().springs() {
            let (k, c) = match spring.rest_length / s {
                l if (l - 1.0).abs() < 1e-12 => (5000.0, 0.05),
                l if (l - 2f64.sqrt()).abs() < 1e-12 => (500.0, 0.05),
                l if (l - 2.0).abs() < 1e-12 => (50.0, 0.0),
                l => panic!("a spring {l} cells long"),
            };
            assert!((spring.stiffness - k).abs() < 1e-12 && (spring.damping - c).abs() < 1e-15);
        }
    }

    /// The stiffness ratio is `k h²/m` for the particle mass `m`, and the
    /// conservative sheet starts with the energy `m g h` of its height.
    #[test]
    fn named_variants_say_what_they_are() {
        let stiff = Sheet::new(10).with_stiffness_ratio(1e6, 0.1);
        let m = stiff.mass / 100.0;
        assert!((stiff.stiffness * 0.01 / m - 1e6).abs() < 1e-6);
        let sheet = Sheet::conservative(1e4);
        let system = sheet.system().unwrap();
        let energy = system.energy(&system.initial_state()).unwrap();
        assert!((energy.total() - 0.981).abs() < 1e-12);
        assert!((sheet.initial_energy() - energy.total()).abs() < 1e-12);
    }

    #[test]
    fn degenerate_sizes_are_errors_not_panics() {
        for n in [0, 1] {
            assert!(Sheet::new(n).system().is_err());
            assert!(Sheet::cloth(n, 0.0).system().is_err());
        }
    }
}
