//! A square cloth sheet: the workload examples and benchmarks share.

use crate::{BuildError, System, SystemBuilder};

/// An `n`×`n` grid of equal particles spanning `size`×`size` m in the
/// horizontal plane `y = height`, with the spring families of cloth:
///
/// - structural (stretch) springs between row and column neighbours,
///   `2n(n − 1)` of them;
/// - shear springs along both diagonals of every cell, `2(n − 1)²`;
/// - bending springs between particles two apart in a row or column,
///   `2n(n − 2)`;
///
/// all of stiffness `k`, damping `c` and rest length their initial length,
/// under gravity, pinned at the two corners of the first row. Its stiffest
/// mode has `ω ≈ 2√(Σk/m)` over the springs at a particle, which sets the
/// explicit integrators' step limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sheet {
    /// Particles per side `n` (at least 2).
    pub particles_per_side: usize,
    /// Side length in m.
    pub size: f64,
    /// Height `y` of the sheet's plane in m.
    pub height: f64,
    /// Total mass in kg, shared equally.
    pub mass: f64,
    /// Stiffness of every spring in N/m.
    pub stiffness: f64,
    /// Axial damping of every spring in N·s/m.
    pub damping: f64,
    /// Gravitational acceleration along −y in m/s².
    pub gravity: f64,
    /// Air damping `γ` in N·s/m (none if zero).
    pub air_damping: f64,
}

impl Sheet {
    /// A 1 m, 0.3 kg sheet of `n`×`n` particles at `y = 0` with 2000 N/m
    /// springs, light damping (`c = 0.01`, `γ = 10⁻⁴`) and standard gravity.
    #[must_use]
    pub fn new(particles_per_side: usize) -> Self {
        Self {
            particles_per_side,
            size: 1.0,
            height: 0.0,
            mass: 0.3,
            stiffness: 2000.0,
            damping: 0.01,
            gravity: 9.81,
            air_damping: 1e-4,
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
        let particle_mass = self.mass / (n * n) as f64;
        let mut b = SystemBuilder::new();
        for row in 0..n {
            for col in 0..n {
                b.particle(
                    particle_mass,
                    [col as f64 * spacing, self.height, row as f64 * spacing],
                );
            }
        }
        // (rows down, columns across): stretch, shear, and bending over two cells.
        const NEIGHBOURS: [(usize, isize); 6] = [(0, 1), (1, 0), (1, 1), (1, -1), (0, 2), (2, 0)];
        for row in 0..n {
            for col in 0..n {
                for (down, across) in NEIGHBOURS {
                    let (r, c) = (row + down, col.checked_add_signed(across));
                    if let Some(c) = c.filter(|&c| c < n && r < n) {
                        b.spring(self.index(row, col), self.index(r, c), self.stiffness)
                            .damping(self.damping);
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_families_match_the_hand_count() {
        // 3×3: 12 structural, 8 shear, 6 bending.
        assert_eq!(Sheet::new(3).spring_count(), 26);
        for n in [2, 3, 4, 7] {
            let sheet = Sheet::new(n);
            let system = sheet.system().unwrap();
            assert_eq!(system.springs().len(), sheet.spring_count(), "n = {n}");
            assert_eq!(system.pinned().collect::<Vec<_>>(), vec![0, n - 1]);
            let total: f64 = system.masses().iter().sum();
            assert!((total - sheet.mass).abs() < 1e-12);
        }
    }

    #[test]
    fn degenerate_sizes_are_errors_not_panics() {
        assert!(Sheet::new(0).system().is_err());
        assert!(Sheet::new(1).system().is_err());
    }
}
