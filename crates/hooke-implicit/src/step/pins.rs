//! Scripted pins in the implicit step (Baraff & Witkin 1998, §5).
//!
//! A pinned particle is a removed unknown: its filter is `Sᵢ = 0`, so the
//! solve leaves its velocity change where it is prescribed. A scripted pin's
//! velocity change is prescribed as `zᵢ = pᵢ'(t + h) − vᵢ`, so it ends the
//! step at its path's velocity; the solve is for the free part `y` of
//! `Δv = y + z`, from `S A y = S (b − A z)`.

use hooke_core::{System, Vec3};

use crate::linear::matrix::BlockMatrix;

/// The prescribed velocity changes of a step's scripted pins.
#[derive(Debug, Clone, Default)]
pub(crate) struct Pins {
    /// The prescribed velocity changes `z` (zero for other particles).
    pub(crate) prescribed: Vec<Vec3>,
    /// Scratch for `A z`.
    product: Vec<Vec3>,
}

impl Pins {
    /// Prescribes the velocity changes of `system`'s scripted pins over a
    /// step of `h` from the velocities `v` at `time`; returns whether there
    /// are any.
    pub(crate) fn begin(&mut self, system: &System, v: &[Vec3], time: f64, h: f64) -> bool {
        let n = v.len();
        self.prescribed.clear();
        self.prescribed.resize(n, Vec3::zeros());
        self.product.resize(n, Vec3::zeros());
        for (i, path) in system.pin_paths() {
            self.prescribed[*i] = path.velocity(time + h) - v[*i];
        }
        !system.pin_paths().is_empty()
    }

    /// Makes the solve's unknown the free part `y` of `Δv = y + z`: `b ← b −
    /// A z`.
    pub(crate) fn prescribe(&mut self, a: &BlockMatrix, b: &mut [Vec3]) {
        a.apply(&self.prescribed, &mut self.product);
        for (bi, azi) in b.iter_mut().zip(&self.product) {
            *bi -= azi;
        }
    }
}
