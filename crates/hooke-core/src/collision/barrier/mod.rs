//! [`Barrier`]: the log barrier of Incremental Potential Contact (Li et al.,
//! *Incremental Potential Contact*, SIGGRAPH 2020, §4) on a pair's gap, with
//! its stiffness, and its derivatives in a pair's coordinates.
//!
//! Every kind of contact pair — a particle and an obstacle, a point and a
//! triangle, two edges — at distance `d` with thickness `ξ` (Li, Kaufman &
//! Jiang, *Codimensional Incremental Potential Contact*, 2021, §3) has gap
//! `g = d − ξ`; its contact energy is `κ b(g)` with
//!
//! ```text
//! b(g) = −(g − d̂)² ln(g/d̂)   for 0 < g < d̂,      b(g) = 0   for g ≥ d̂,
//! ```
//!
//! `d̂` the activation distance: C² at `d̂` (`b = b' = b'' = 0` there) and
//! `b → ∞` as `g → 0`, so no minimiser of an incremental potential containing
//! it has an intersection. Since `d = √(d²)` and the distance routines of
//! [`distance`](super::distance) return `d²` with its derivatives,
//!
//! ```text
//! ∇g  = ∇d² / (2d),
//! ∇²g = ∇²d² / (2d) − ∇d² ∇d²ᵀ / (4d³),
//! ∇²b = b''(g) ∇g ∇gᵀ + b'(g) ∇²g = (b'' − b'/d) ∇g ∇gᵀ + b'/(2d) ∇²d².
//! ```
//!
//! Newton's method needs a positive semi-definite Hessian; as in IPC each
//! surface pair's 12×12 Hessian is projected with [`project_positive`]
//! (once, after any mollifier has been applied; on the 9-dimensional
//! complement of the rigid translations, which every pair Hessian
//! annihilates). A particle's barrier against an obstacle needs no
//! eigensolve: its Hessian `b''(g) n nᵀ + b'(g) ∇²φ` has `b' < 0` and, the
//! signed distance `φ` of a convex shape being convex, `∇²φ ⪰ 0`, so its
//! positive part is `b''(g) n nᵀ`.

mod projection;

pub use projection::project_positive;

use super::distance::Derivatives;
use crate::Mat12;
use projection::project_pair;

/// IPC's barrier with its stiffness: the energy `κ b(g)` of a pair at gap
/// `g`, with
///
/// ```text
/// b(g)   = −(g − d̂)² ln(g/d̂),
/// b'(g)  = −2 (g − d̂) ln(g/d̂) − (g − d̂)²/g,
/// b''(g) = −2 ln(g/d̂) − 4 (g − d̂)/g + (g − d̂)²/g²
/// ```
///
/// for `0 < g < d̂`, `0` for `g ≥ d̂`: `b` is C² at `d̂` and goes to `∞` as
/// `g → 0`; `b' ≤ 0 ≤ b''` on `(0, d̂)`. A sum of pair terms is taken as
/// `κ Σ b`, the stiffness applied once.
///
/// ```
/// use hooke_core::collision::barrier::Barrier;
/// // A particle of 0.1 N at rest on a floor at half of d̂ = 1 mm.
/// let barrier = Barrier::resting(0.1, 1e-3);
/// assert!((barrier.force(0.5e-3) - 0.1).abs() < 1e-15);
/// assert_eq!(barrier.unit(1e-3), (0.0, 0.0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Barrier {
    /// The stiffness `κ`, N/m (the energy of a pair is `κ b(g)`, `b` in m²).
    pub stiffness: f64,
    /// The activation distance `d̂ > 0`, m: a pair whose gap is at least
    /// `d̂` has no term.
    pub activation: f64,
}

impl Barrier {
    /// The barrier with activation distance `d̂` whose stiffness holds a
    /// particle of weight `W` at rest at half of it: the force
    /// `κ |b'(d̂/2)|` equals `W`, `κ = W / |b'(d̂/2)|`. A heavier load
    /// settles closer, where the barrier is stiffer.
    #[must_use]
    pub fn resting(weight: f64, activation: f64) -> Self {
        let unit = Self {
            stiffness: 1.0,
            activation,
        };
        Self {
            stiffness: weight / unit.unit(0.5 * activation).1.abs(),
            activation,
        }
    }

    /// `(b, b', b'')` at gap `g`: the barrier per unit stiffness and its
    /// first two derivatives; `g ≤ 0` gives `(∞, −∞, ∞)`.
    #[must_use]
    pub fn unit(&self, g: f64) -> (f64, f64, f64) {
        let activation = self.activation;
        if g <= 0.0 {
            return (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        }
        if g >= activation {
            return (0.0, 0.0, 0.0);
        }
        let e = g - activation;
        let l = (g / activation).ln();
        (
            -e * e * l,
            -2.0 * e * l - e * e / g,
            -2.0 * l - 4.0 * e / g + e * e / (g * g),
        )
    }

    /// Whether a pair at gap `g` has a term: `g < d̂` (a gap that is not a
    /// number has none).
    #[must_use]
    pub fn active(&self, g: f64) -> bool {
        g < self.activation
    }

    /// The normal force `−κ b'(g) ≥ 0` of a pair at gap `g`, N.
    #[must_use]
    pub fn force(&self, g: f64) -> f64 {
        -self.stiffness * self.unit(g).1
    }

    /// The barrier (per unit stiffness) of a pair at gap `g = √(d²) − ξ`
    /// (`ξ` the thickness): value `b(g)`, gradient `b'(g) ∇g` and Hessian
    /// `b''(g) ∇g ∇gᵀ + b'(g) ∇²g` projected onto the PSD cone, from the
    /// squared distance's [`Derivatives`] (module docs).
    ///
    /// `None` when `g ≥ d̂` (the pair is inactive). A pair at `g ≤ 0` is
    /// infeasible: the value is `∞` with zero gradient and Hessian.
    #[must_use]
    pub fn pair(&self, squared: &Derivatives, thickness: f64) -> Option<Derivatives> {
        self.pair_exact(squared, thickness).map(projected)
    }

    /// [`Barrier::pair`] before the projection of its Hessian.
    pub(crate) fn pair_exact(&self, squared: &Derivatives, thickness: f64) -> Option<Derivatives> {
        let d = squared.value.max(0.0).sqrt();
        let g = d - thickness;
        if g >= self.activation {
            return None;
        }
        if g <= 0.0 {
            return Some(Derivatives::constant(f64::INFINITY));
        }
        let (b, db, ddb) = self.unit(g);
        let grad_g = squared.gradient / (2.0 * d);
        let mut hessian = squared.hessian * (db / (2.0 * d));
        hessian.ger(ddb - db / d, &grad_g, &grad_g, 1.0);
        Some(Derivatives {
            value: b,
            gradient: grad_g * db,
            hessian,
        })
    }

    /// The edge–edge barrier times the mollifier `m` of
    /// [`edge_edge_mollifier`](super::distance::edge_edge_mollifier) (Li et
    /// al. 2020, §4.3):
    ///
    /// ```text
    /// value m b,   gradient m ∇b + b ∇m,
    /// Hessian m ∇²b + ∇m ∇bᵀ + ∇b ∇mᵀ + b ∇²m,
    /// ```
    ///
    /// with `b` the unprojected [`Barrier::pair`]; the sum is projected onto
    /// the PSD cone once, at the end. `None` when the gap is at least `d̂`;
    /// `∞` (zero derivatives) when it is `≤ 0`, whatever `m`.
    #[must_use]
    pub fn mollified_pair(
        &self,
        squared: &Derivatives,
        mollifier: &Derivatives,
        thickness: f64,
    ) -> Option<Derivatives> {
        self.mollified_pair_exact(squared, mollifier, thickness)
            .map(projected)
    }

    /// [`Barrier::mollified_pair`] before the projection of its Hessian.
    pub(crate) fn mollified_pair_exact(
        &self,
        squared: &Derivatives,
        mollifier: &Derivatives,
        thickness: f64,
    ) -> Option<Derivatives> {
        let b = self.pair_exact(squared, thickness)?;
        if !b.value.is_finite() {
            return Some(b);
        }
        let m = mollifier;
        let mut hessian: Mat12 = b.hessian * m.value + m.hessian * b.value;
        hessian.ger(1.0, &m.gradient, &b.gradient, 1.0);
        hessian.ger(1.0, &b.gradient, &m.gradient, 1.0);
        Some(Derivatives {
            value: m.value * b.value,
            gradient: b.gradient * m.value + m.gradient * b.value,
            hessian,
        })
    }
}

/// `D` with its Hessian projected by [`project_pair`] (an infinite value has
/// zero derivatives and is left as is).
fn projected(mut d: Derivatives) -> Derivatives {
    if d.value.is_finite() {
        d.hessian = project_pair(&d.hessian);
    }
    d
}

#[cfg(test)]
mod tests;
