//! Baraff–Witkin's modified preconditioned conjugate gradient: constraints
//! act through per-particle filters inside the loop.

use hooke_core::{Parameter, ParameterError, SymBlock, Vec3};

use crate::linear::filter::{Filter, project};
use crate::linear::matrix::BlockMatrix;
use crate::linear::vector::{dot, for_each_row};

/// A symmetric positive-definite linear operator on per-particle 3-vectors.
pub trait Operator {
    /// Number of particles (block rows).
    fn rows(&self) -> usize;
    /// `y = A x`.
    fn apply(&self, x: &[Vec3], y: &mut [Vec3]);
}

impl Operator for BlockMatrix {
    fn rows(&self) -> usize {
        BlockMatrix::rows(self)
    }

    fn apply(&self, x: &[Vec3], y: &mut [Vec3]) {
        BlockMatrix::apply(self, x, y);
    }
}

/// An approximation `P ≈ A` whose inverse is cheap to apply.
pub trait Preconditioner {
    /// `z = P⁻¹ r`.
    fn apply(&self, r: &[Vec3], z: &mut [Vec3]);
}

/// Block-Jacobi preconditioner: `P = blockdiag(A)`, applied with the inverses
/// of the 3x3 diagonal blocks, which [`Terms::assemble`](crate::Terms::assemble)
/// fills as it assembles `A`.
#[derive(Debug, Clone, Default)]
pub struct BlockJacobi {
    pub(crate) inverses: Vec<SymBlock>,
}

impl Preconditioner for BlockJacobi {
    fn apply(&self, r: &[Vec3], z: &mut [Vec3]) {
        for_each_row(z, |i, zi| *zi = self.inverses[i].mul(r[i]));
    }
}

/// Stopping rule of [`solve`]: stop when the filtered residual
/// `‖S(b − A x)‖₂ ≤ tolerance · ‖S b‖₂`, or after `max_iterations`.
///
/// A filtered residual below `8 ε ‖b‖₂` (`ε` the machine epsilon) counts as
/// converged too: projecting `b − A x` rounds its free part at that level,
/// so it is as small as the filter can make it, and going on from it
/// follows rounding errors. (A constrained particle whose force lies along
/// its constraint, a resting or steadily sliding contact, has `‖S b‖` far
/// below `‖b‖`.)
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcgSettings {
    pub(crate) tolerance: f64,
    pub(crate) max_iterations: usize,
}

impl PcgSettings {
    /// Relative residual `tolerance` in `(0, 1)` and an iteration cap of at
    /// least one.
    ///
    /// # Errors
    /// [`ParameterError`] for a tolerance outside `(0, 1)` or a zero cap.
    pub fn new(tolerance: f64, max_iterations: usize) -> Result<Self, ParameterError> {
        if !(tolerance > 0.0 && tolerance < 1.0) {
            return Err(ParameterError::new(
                "pcg",
                Parameter::Tolerance,
                tolerance,
                "in (0, 1)",
            ));
        }
        if max_iterations == 0 {
            return Err(ParameterError::new(
                "pcg",
                Parameter::MaxIterations,
                0.0,
                "at least 1",
            ));
        }
        Ok(Self {
            tolerance,
            max_iterations,
        })
    }

    /// The relative residual tolerance.
    #[must_use]
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// These settings with the tolerance raised to `forcing` where that is
    /// looser (an inexact Newton iteration's forcing term; `0` keeps them).
    #[must_use]
    pub(crate) fn loosened(self, forcing: f64) -> Self {
        Self {
            tolerance: self.tolerance.max(forcing),
            ..self
        }
    }

    /// The iteration cap.
    #[must_use]
    pub fn max_iterations(&self) -> usize {
        self.max_iterations
    }
}

impl PcgSettings {
    /// The default: relative residual `1e-6`, at most 1000 iterations.
    pub const DEFAULT: Self = Self {
        tolerance: 1e-6,
        max_iterations: 1000,
    };
}

impl Default for PcgSettings {
    /// [`PcgSettings::DEFAULT`].
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcgInfo {
    /// Iterations taken.
    pub iterations: usize,
    /// Final relative residual `‖S(b − A x)‖/‖S b‖` (as updated by the
    /// recurrence).
    pub residual: f64,
}

/// A solve that did not reach its tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PcgError {
    /// The iteration cap was reached; `x` holds the last iterate.
    NoConvergence(PcgInfo),
    /// A search direction had non-positive or non-finite curvature `cᵀAc`:
    /// the filtered operator is not positive definite (or not finite).
    NotPositiveDefinite(PcgInfo),
}

/// The vectors [`solve`] works in, kept between solves so that a solve does
/// not allocate.
#[derive(Debug, Clone, Default)]
pub struct PcgWorkspace {
    r: Vec<Vec3>,
    c: Vec<Vec3>,
    q: Vec<Vec3>,
    s: Vec<Vec3>,
}

/// Solves `A x = b` in the subspace the filters leave free, with the
/// constrained components of `x` prescribed as zero (Baraff & Witkin, *Large
/// Steps in Cloth Simulation*, 1998, §5.3):
///
/// ```text
/// x ← S x,  r = S(b − A x),  c = S P⁻¹ r,  δ = rᵀ c
/// repeat:  q = S A c,  α = δ / cᵀq,  x += α c,  r −= α q,
///          s = P⁻¹ r,  δ' = rᵀ s,  c = S(s + (δ'/δ) c),  δ = δ'
/// ```
///
/// `x` is the initial guess on entry (a warm start) and the solution on
/// return.
///
/// # Errors
/// [`PcgError::NoConvergence`] at the iteration cap (with `x` the last
/// iterate) and [`PcgError::NotPositiveDefinite`] on non-positive curvature.
///
/// # Panics
/// If `filters`, `b` or `x` does not have one entry per row of `a`.
pub fn solve(
    a: &impl Operator,
    preconditioner: &impl Preconditioner,
    filters: &[Filter],
    b: &[Vec3],
    x: &mut [Vec3],
    settings: PcgSettings,
    workspace: &mut PcgWorkspace,
) -> Result<PcgInfo, PcgError> {
    let n = a.rows();
    assert!(
        filters.len() == n && b.len() == n && x.len() == n,
        "one entry per particle"
    );
    let PcgWorkspace { r, c, q, s } = workspace;
    for buffer in [&mut *r, &mut *c, &mut *q, &mut *s] {
        buffer.resize(n, Vec3::zeros());
    }
    project(filters, x);
    let b_norm = crate::linear::vector::sum(n, |i| filters[i].apply(b[i]).norm_squared()).sqrt();
    let rounding = 8.0 * f64::EPSILON * dot(b, b).sqrt();
    if b_norm == 0.0 {
        x.fill(Vec3::zeros());
        return Ok(PcgInfo {
            iterations: 0,
            residual: 0.0,
        });
    }
    a.apply(x, q);
    for_each_row(r, |i, ri| *ri = filters[i].apply(b[i] - q[i]));
    preconditioner.apply(r, s);
    for_each_row(c, |i, ci| *ci = filters[i].apply(s[i]));
    let mut delta = dot(r, c);
    let mut info = PcgInfo {
        iterations: 0,
        residual: dot(r, r).sqrt() / b_norm,
    };
    while info.residual > settings.tolerance && info.residual * b_norm > rounding {
        if info.iterations == settings.max_iterations {
            return Err(PcgError::NoConvergence(info));
        }
        a.apply(c, q);
        project(filters, q);
        let curvature = dot(c, q);
        if !(curvature > 0.0 && curvature.is_finite()) {
            return Err(PcgError::NotPositiveDefinite(info));
        }
        let alpha = delta / curvature;
        for_each_row(x, |i, xi| *xi += alpha * c[i]);
        for_each_row(r, |i, ri| *ri -= alpha * q[i]);
        preconditioner.apply(r, s);
        let delta_next = dot(r, s);
        let ratio = delta_next / delta;
        for_each_row(c, |i, ci| *ci = filters[i].apply(s[i] + ratio * *ci));
        delta = delta_next;
        info.iterations += 1;
        info.residual = dot(r, r).sqrt() / b_norm;
    }
    Ok(info)
}
