//! The gravitational term `−Σ mᵢ g·xᵢ` of the incremental potential.

use hooke_core::{At, Hessian, Potential, System, Term, Vec3, When};

use crate::linear::vector::{for_each_row, sum2, sum2_rows};

/// Uniform gravity `g`: the potential `V = −Σ mᵢ g·xᵢ`, force `mᵢ g`, linear
/// in the positions, so without Hessian or stiffness.
#[derive(Debug, Clone, Copy)]
pub(super) struct Gravity {
    g: Vec3,
}

impl Gravity {
    /// Gravity of acceleration `g`, m/s².
    pub(super) fn new(g: Vec3) -> Self {
        Self { g }
    }
}

impl Term for Gravity {
    fn name(&self) -> &'static str {
        "gravity"
    }

    fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        let (masses, x, g) = (system.masses(), at.x, self.g);
        let (value, magnitude) = sum2(x.len(), |i| {
            let e = -masses[i] * g.dot(&x[i]);
            (e, e.abs())
        });
        Potential { value, magnitude }
    }

    /// The value and `b += βh mᵢ g` in one pass over the particles.
    fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        let (masses, x, bh, g) = (system.masses(), at.x, at.beta_h, self.g);
        let (value, magnitude) = sum2_rows(b, |i, bi| {
            *bi += bh * masses[i] * g;
            let e = -masses[i] * g.dot(&x[i]);
            (e, e.abs())
        });
        Potential { value, magnitude }
    }

    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], _hessian: &mut dyn Hessian) {
        let (masses, bh, g) = (system.masses(), at.beta_h, self.g);
        for_each_row(b, |i, bi| *bi += bh * masses[i] * g);
    }

    /// The free particles' potential `−Σ mᵢ g·xᵢ`.
    fn energy(&mut self, system: &System, x: &[Vec3], _v: &[Vec3], _when: When) -> Potential {
        let mut sum = Potential::ZERO;
        for i in (0..x.len()).filter(|&i| !system.is_pinned(i)) {
            let e = -system.masses()[i] * self.g.dot(&x[i]);
            sum += Potential {
                value: e,
                magnitude: e.abs(),
            };
        }
        sum
    }

    fn force(&self, system: &System, _x: &[Vec3], _v: &[Vec3], f: &mut [Vec3]) {
        for (fi, m) in f.iter_mut().zip(system.masses()) {
            *fi += *m * self.g;
        }
    }
}
