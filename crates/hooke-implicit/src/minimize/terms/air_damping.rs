//! The air-damping term `½βh γ Σ|vᵢ|²` of the incremental potential.

use hooke_core::{At, Hessian, Potential, System, Term, Vec3, When};

use crate::linear::vector::{for_each_row, sum2, sum2_rows};

/// Air damping `γ`: the force `−γ vᵢ` on every particle, the dissipation
/// potential `R = ½γ Σ|vᵢ|²` (times `βh` in `Φ`), Hessian `βh γ I`. It
/// stores no energy, and adds `γ wᵢ²` to the damping rate of each particle.
#[derive(Debug, Clone, Copy)]
pub(super) struct AirDamping {
    gamma: f64,
}

impl AirDamping {
    /// Air damping of coefficient `γ`, N·s/m.
    pub(super) fn new(gamma: f64) -> Self {
        Self { gamma }
    }
}

impl Term for AirDamping {
    fn name(&self) -> &'static str {
        "air damping"
    }

    fn value(&mut self, _system: &System, at: &At<'_>) -> Potential {
        let (v, bh, gamma) = (at.v, at.beta_h, self.gamma);
        let (value, magnitude) = sum2(v.len(), |i| {
            let e = 0.5 * bh * gamma * v[i].norm_squared();
            (e, e)
        });
        Potential { value, magnitude }
    }

    /// The value and `b −= βh γ v` in one pass over the particles.
    fn gradient(&mut self, _system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        let (v, bh, gamma) = (at.v, at.beta_h, self.gamma);
        let (value, magnitude) = sum2_rows(b, |i, bi| {
            *bi -= bh * gamma * v[i];
            let e = 0.5 * bh * gamma * v[i].norm_squared();
            (e, e)
        });
        Potential { value, magnitude }
    }

    fn add(&mut self, _system: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        let (v, bh, gamma) = (at.v, at.beta_h, self.gamma);
        for_each_row(b, |i, bi| *bi -= bh * gamma * v[i]);
        let air = bh * gamma;
        hessian.add_identity(v.len(), &|_| air);
    }

    fn energy(&mut self, _system: &System, _x: &[Vec3], _v: &[Vec3], _when: When) -> Potential {
        Potential::ZERO
    }

    fn force(&self, _system: &System, _x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        for (fi, vi) in f.iter_mut().zip(v) {
            *fi -= self.gamma * vi;
        }
    }

    fn rates(&self, _system: &System, w: &[f64], _stiffness: &mut [f64], damping: &mut [f64]) {
        for (d, w) in damping.iter_mut().zip(w) {
            *d += self.gamma * w * w;
        }
    }
}
