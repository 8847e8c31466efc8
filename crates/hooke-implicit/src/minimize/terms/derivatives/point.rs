//! The point of a case's `Φ` that the checks evaluate, and the central
//! differences about it.

use hooke_core::{At, CompressedSprings, Potential, Term, Vec3};
use nalgebra::DMatrix;

use super::cases::Case;
use super::dense::Dense;

/// The point of a case's `Φ` the checks evaluate.
pub(super) struct Point<'a> {
    pub(super) case: &'a Case,
    /// The positions `x` at the point.
    pub(super) x: Vec<Vec3>,
    pub(super) beta_h: f64,
    /// The steps of the central differences in the positions and in the
    /// velocities.
    pub(super) dx: f64,
    pub(super) dv: f64,
    /// The relative error the rounding of the coordinates may put into a
    /// difference in the positions.
    pub(super) coordinate_rounding: f64,
}

/// Which way a central difference moves the point: the positions or the
/// velocities, coordinate `k` by `delta`.
#[derive(Debug, Clone, Copy)]
pub(super) enum Move {
    Position(usize, f64),
    Velocity(usize, f64),
}

impl Point<'_> {
    pub(super) fn particles(&self) -> usize {
        self.x.len()
    }

    /// `f` at the point moved `by`, with `βh` = `s` and `how` = (the
    /// Hessian's mode, the displacement of a linearisation).
    pub(super) fn at<R>(
        &self,
        s: f64,
        by: Option<Move>,
        how: (CompressedSprings, Option<&[Vec3]>),
        f: impl FnOnce(&At<'_>) -> R,
    ) -> R {
        let (mut x, mut v) = (self.x.clone(), self.case.v.clone());
        match by {
            Some(Move::Position(k, delta)) => x[k / 3][k % 3] += delta,
            Some(Move::Velocity(k, delta)) => v[k / 3][k % 3] += delta,
            None => {}
        }
        f(&At {
            x: &x,
            v: &v,
            v_tilde: &self.case.v_tilde,
            beta_h: s,
            displacement: how.1,
            compressed: how.0,
        })
    }

    pub(super) fn value(&self, term: &mut dyn Term, s: f64, by: Option<Move>) -> Potential {
        let how = (CompressedSprings::Exact, None);
        self.at(s, by, how, |at| term.value(&self.case.system, at))
    }

    /// `b` (from zero) and the Hessian that [`Term::add`] writes.
    pub(super) fn add(
        &self,
        term: &mut dyn Term,
        s: f64,
        by: Option<Move>,
        how: (CompressedSprings, Option<&[Vec3]>),
    ) -> (Vec<Vec3>, DMatrix<f64>) {
        let n = self.particles();
        let (mut b, mut hessian) = (vec![Vec3::zeros(); n], Dense::new(n));
        self.at(s, by, how, |at| {
            term.add(&self.case.system, at, &mut b, &mut hessian);
        });
        (b, hessian.0)
    }

    /// The derivative in the velocities of `f` at `βh` = `s` along
    /// coordinate `k`, by the chain rule through `x = x̃ + βh v`:
    /// `s ∂f/∂xₖ + ∂f/∂vₖ`, each partial derivative by differences in its
    /// own variable with its own step ([`richardson`]). `f` gives the
    /// point's values moved `by` as a vector; so does the derivative.
    pub(super) fn difference(
        &self,
        s: f64,
        k: usize,
        mut f: impl FnMut(Move) -> Vec<f64>,
    ) -> Vec<f64> {
        let x = richardson(self.dx, |delta| f(Move::Position(k, delta)));
        let v = richardson(self.dv, |delta| f(Move::Velocity(k, delta)));
        x.iter().zip(&v).map(|(x, v)| s * x + v).collect()
    }

    /// How much the rounding of values of magnitude `magnitude` may move
    /// a [`Point::difference`] at `βh` = `s`, beyond the rounding of the
    /// coordinates.
    pub(super) fn rounding(&self, s: f64, magnitude: f64) -> f64 {
        8.0 * f64::EPSILON * magnitude * (s / self.dx + 1.0 / self.dv)
    }
}

/// The largest magnitude among `values`.
pub(super) fn largest_of<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    values.into_iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// `−b` as the gradient's `3n` coordinates.
pub(super) fn flat(b: &[Vec3]) -> Vec<f64> {
    b.iter().flat_map(|b| b.iter().map(|c| -c)).collect()
}

/// The derivative at zero of the function `f` of one variable, by
/// Richardson's extrapolation of its central differences with steps `δ`
/// and `2δ`, `(4 D(δ) − D(2δ))/3`, `D(δ) = (f(δ) − f(−δ))/2δ`: of error
/// `O(δ⁴)`. A central difference's own error `δ² f‴/6` would dominate by
/// a pair near the contact distance, whose barrier's slope vanishes there
/// as the square of the distance to it while its third derivative does
/// not.
fn richardson(delta: f64, mut f: impl FnMut(f64) -> Vec<f64>) -> Vec<f64> {
    let mut central = |h: f64| {
        let (plus, minus) = (f(h), f(-h));
        plus.iter()
            .zip(&minus)
            .map(|(p, m)| (p - m) / (2.0 * h))
            .collect::<Vec<f64>>()
    };
    let (near, far) = (central(delta), central(2.0 * delta));
    near.iter()
        .zip(&far)
        .map(|(n, f)| (4.0 * n - f) / 3.0)
        .collect()
}
