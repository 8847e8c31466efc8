//! The inertia term `½‖v − ṽ‖²_M` of the incremental potential.

use hooke_core::{At, Hessian, Potential, System, Term, Vec3, When};

use crate::linear::vector::{for_each_row, sum2, sum2_rows};

/// The inertia `½ Σ mᵢ |vᵢ − ṽᵢ|²`: gradient `M(v − ṽ)`, Hessian the mass
/// matrix `M`. Its part of the energy is the free particles' kinetic
/// energy `½ Σ mᵢ |vᵢ|²`; it is no force.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Inertia;

impl Term for Inertia {
    fn name(&self) -> &'static str {
        "inertia"
    }

    fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        let (masses, v, v_tilde) = (system.masses(), at.v, at.v_tilde);
        let (value, magnitude) = sum2(v.len(), |i| {
            let e = 0.5 * masses[i] * (v[i] - v_tilde[i]).norm_squared();
            (e, e)
        });
        Potential { value, magnitude }
    }

    /// The value and `b += M(ṽ − v)` in one pass over the particles.
    fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        let (masses, v, v_tilde) = (system.masses(), at.v, at.v_tilde);
        let (value, magnitude) = sum2_rows(b, |i, bi| {
            *bi += masses[i] * (v_tilde[i] - v[i]);
            let e = 0.5 * masses[i] * (v[i] - v_tilde[i]).norm_squared();
            (e, e)
        });
        Potential { value, magnitude }
    }

    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        let (masses, v, v_tilde) = (system.masses(), at.v, at.v_tilde);
        for_each_row(b, |i, bi| *bi += masses[i] * (v_tilde[i] - v[i]));
        hessian.add_identity(masses.len(), &|i| masses[i]);
    }

    fn energy(&mut self, system: &System, _x: &[Vec3], v: &[Vec3], _when: When) -> Potential {
        let kinetic: f64 = (0..v.len())
            .filter(|&i| !system.is_pinned(i))
            .map(|i| 0.5 * system.masses()[i] * v[i].norm_squared())
            .sum();
        Potential::non_negative(kinetic)
    }

    fn force(&self, _system: &System, _x: &[Vec3], _v: &[Vec3], _f: &mut [Vec3]) {}
}
