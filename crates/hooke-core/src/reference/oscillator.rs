//! The harmonic oscillator, undamped or damped, with its exact solution.

use crate::{BuildError, System, SystemBuilder};

/// One particle (the bob) on a spring of rest length zero to a pinned anchor
/// at the origin, moving along the x axis.
///
/// A zero rest length makes the spring force exactly linear, `−k x`, for any
/// amplitude, and along the axis the spring's damping is exactly `−c v`, so
/// the bob's displacement `u(t)` obeys
///
/// ```text
/// m u'' + c u' + k u = 0,   ω = √(k/m),   ζ = c / (2√(k m)),
/// ```
///
/// whose solution [`Oscillator::displacement`] gives in closed form for the
/// underdamped (`ζ < 1`), critically damped and overdamped (`ζ > 1`) cases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oscillator {
    /// Mass of the bob `m` in kg.
    pub mass: f64,
    /// Spring stiffness `k` in N/m.
    pub stiffness: f64,
    /// Spring damping `c` in N·s/m.
    pub damping: f64,
    /// Initial displacement `u(0)` in m.
    pub displacement: f64,
    /// Initial velocity `u'(0)` in m/s.
    pub velocity: f64,
}

impl Oscillator {
    /// Index of the pinned anchor in [`Oscillator::system`].
    pub const ANCHOR: usize = 0;
    /// Index of the bob in [`Oscillator::system`].
    pub const BOB: usize = 1;

    /// An undamped oscillator released from rest at `u(0) = 1` m.
    #[must_use]
    pub fn undamped(mass: f64, stiffness: f64) -> Self {
        Self::damped(mass, stiffness, 0.0)
    }

    /// A damped oscillator released from rest at `u(0) = 1` m.
    #[must_use]
    pub fn damped(mass: f64, stiffness: f64, damping: f64) -> Self {
        Self {
            mass,
            stiffness,
            damping,
            displacement: 1.0,
            velocity: 0.0,
        }
    }

    /// Natural angular frequency `ω = √(k/m)` in rad/s.
    #[must_use]
    pub fn omega(&self) -> f64 {
        (self.stiffness / self.mass).sqrt()
    }

    /// Damping ratio `ζ = c / (2√(k m))`.
    #[must_use]
    pub fn damping_ratio(&self) -> f64 {
        self.damping / (2.0 * (self.stiffness * self.mass).sqrt())
    }

    /// The system: anchor (pinned, index [`Self::ANCHOR`]) at the origin and
    /// bob (index [`Self::BOB`]) at `(u(0), 0, 0)` with velocity
    /// `(u'(0), 0, 0)`. The anchor's mass is irrelevant and set equal to the
    /// bob's.
    ///
    /// # Errors
    /// A [`BuildError`] for a non-positive mass or a negative stiffness or
    /// damping.
    pub fn system(&self) -> Result<System, BuildError> {
        let mut b = SystemBuilder::new();
        let anchor = b.particle(self.mass, [0.0; 3]);
        let bob = b.particle_with_velocity(
            self.mass,
            [self.displacement, 0.0, 0.0],
            [self.velocity, 0.0, 0.0],
        );
        b.pin(anchor);
        b.spring(anchor, bob, self.stiffness)
            .rest_length(0.0)
            .damping(self.damping);
        b.build()
    }

    /// Exact displacement `u(t)` and velocity `u'(t)`.
    #[must_use]
    pub fn solution(&self, t: f64) -> (f64, f64) {
        let (w, z) = (self.omega(), self.damping_ratio());
        let (u0, v0) = (self.displacement, self.velocity);
        const CRITICAL_BAND: f64 = 1e-9;
        if z < 1.0 - CRITICAL_BAND {
            let wd = w * (1.0 - z * z).sqrt();
            let (a, b) = (u0, (v0 + z * w * u0) / wd);
            let (s, c) = (wd * t).sin_cos();
            let e = (-z * w * t).exp();
            (
                e * (a * c + b * s),
                e * ((b * wd - z * w * a) * c - (a * wd + z * w * b) * s),
            )
        } else if z > 1.0 + CRITICAL_BAND {
            let root = w * (z * z - 1.0).sqrt();
            let (r1, r2) = (-z * w + root, -z * w - root);
            let a = (v0 - r2 * u0) / (r1 - r2);
            let b = u0 - a;
            let (e1, e2) = ((r1 * t).exp(), (r2 * t).exp());
            (a * e1 + b * e2, a * r1 * e1 + b * r2 * e2)
        } else {
            let b = v0 + w * u0;
            let e = (-w * t).exp();
            (e * (u0 + b * t), e * (b - w * (u0 + b * t)))
        }
    }

    /// Exact displacement `u(t)`.
    #[must_use]
    pub fn displacement(&self, t: f64) -> f64 {
        self.solution(t).0
    }

    /// Exact energy `½ m u'² + ½ k u²` at time `t`.
    #[must_use]
    pub fn energy(&self, t: f64) -> f64 {
        let (u, v) = self.solution(t);
        0.5 * self.mass * v * v + 0.5 * self.stiffness * u * u
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Checks `m u'' + c u' + k u = 0` by central differences of the velocity,
    /// and the initial conditions, for each damping regime.
    #[test]
    fn solution_satisfies_the_equation_and_initial_conditions() {
        for damping in [0.0, 0.3, 4.0, 10.0] {
            let o = Oscillator {
                mass: 2.0,
                stiffness: 8.0,
                damping,
                displacement: 0.7,
                velocity: -1.1,
            };
            let (u0, v0) = o.solution(0.0);
            assert_relative_eq!(u0, 0.7, epsilon = 1e-12);
            assert_relative_eq!(v0, -1.1, epsilon = 1e-12);
            let h = 1e-5;
            for t in [0.1, 0.9, 2.5] {
                let (u, v) = o.solution(t);
                let accel = (o.solution(t + h).1 - o.solution(t - h).1) / (2.0 * h);
                let position_rate = (o.solution(t + h).0 - o.solution(t - h).0) / (2.0 * h);
                assert_relative_eq!(position_rate, v, epsilon = 1e-8);
                assert_relative_eq!(
                    o.mass * accel + damping * v + o.stiffness * u,
                    0.0,
                    epsilon = 1e-7
                );
            }
        }
    }
}
