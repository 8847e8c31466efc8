//! The terms a system declares beyond the built-in ones
//! ([`SystemBuilder::term`]), which every case's system carries
//! ([`declare`]): the property test reaches them through the list of
//! terms like any other, so a term declared there is checked in every
//! case with no other change. The library's [`Wind`] is one; two of the
//! test's own show the same for any term: a potential, and a dissipation
//! potential lagged at the step's start as a wind lags its triangles'
//! normals.

use hooke_core::{
    At, Hessian, Potential, StepStart, SymBlock, System, SystemBuilder, Term, Vec3, When, Wind,
};

use super::kinds::Draws;

/// Declares the system's own terms in `builder`: an [`Anchor`] holding
/// the particle `anchored` near its position `x`, a [`Drag`] about
/// `origin`, a point away from every particle, and a [`Wind`] on
/// `triangles`.
pub(super) fn declare(
    builder: &mut SystemBuilder,
    (anchored, x): (usize, Vec3),
    (origin, triangles): (Vec3, &[[usize; 3]]),
    draws: &mut Draws,
) {
    builder.term(Anchor {
        i: anchored,
        p: x + draws.vector(0.05),
        k: draws.log_range(1.0, 1e3),
    });
    builder.term(Drag {
        c: draws.log_range(1e-2, 1.0),
        w: draws.vector(1.0),
        o: origin,
        directions: Vec::new(),
    });
    builder.term(Wind::new(
        draws.vector(3.0),
        draws.log_range(1e-2, 1.0),
        triangles.to_vec(),
    ));
}

/// A linear spring from particle `i` to the fixed point `p`:
/// `V = ½k|xᵢ − p|²`. In `Φ`, at `x = x̃ + βh v`, its gradient in the
/// velocities is `βh k (xᵢ − p)` and its Hessian `β²h² k I`; at a
/// linearisation with displacement `u` the right-hand side also gets
/// `−βh k uᵢ`.
#[derive(Debug, Clone)]
struct Anchor {
    i: usize,
    p: Vec3,
    k: f64,
}

impl Anchor {
    fn potential(&self, x: &[Vec3]) -> Potential {
        Potential::non_negative(0.5 * self.k * (x[self.i] - self.p).norm_squared())
    }
}

impl Term for Anchor {
    fn name(&self) -> &'static str {
        "anchor"
    }

    fn value(&mut self, _: &System, at: &At<'_>) -> Potential {
        self.potential(at.x)
    }

    fn add(&mut self, _: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        let bh = at.beta_h;
        b[self.i] -= bh * self.k * (at.x[self.i] - self.p);
        if let Some(u) = at.displacement {
            b[self.i] -= bh * self.k * u[self.i];
        }
        hessian.add_row(self.i, SymBlock::scaled_identity(bh * bh * self.k));
    }

    fn energy(&mut self, _: &System, x: &[Vec3], _: &[Vec3], _: When) -> Potential {
        self.potential(x)
    }

    fn force(&self, _: &System, x: &[Vec3], _: &[Vec3], f: &mut [Vec3]) {
        f[self.i] -= self.k * (x[self.i] - self.p);
    }
}

/// Drag against a medium moving at `w`, along each particle's direction
/// from the point `o`, frozen at the step's start: the dissipation
/// potential `R = ½c Σᵢ (dᵢ·(vᵢ − w))²`, `dᵢ = (xᵢ − o)/|xᵢ − o|` at `xₙ`.
/// In `Φ` it is `βh R`, of gradient `βh c (dᵢ·(vᵢ − w)) dᵢ` and Hessian
/// `βh c dᵢ dᵢᵀ`.
#[derive(Debug, Clone)]
struct Drag {
    c: f64,
    w: Vec3,
    o: Vec3,
    /// The directions `dᵢ` of the current step.
    directions: Vec<Vec3>,
}

impl Drag {
    /// The unit vector from `o` to `x`.
    fn direction(&self, x: &Vec3) -> Vec3 {
        (x - self.o).normalize()
    }

    /// `dᵢ·(vᵢ − w)` along the frozen directions.
    fn rates<'a>(&'a self, v: &'a [Vec3]) -> impl Iterator<Item = (usize, f64)> + 'a {
        (0..v.len()).map(|i| (i, self.directions[i].dot(&(v[i] - self.w))))
    }
}

impl Term for Drag {
    fn name(&self) -> &'static str {
        "drag"
    }

    /// The directions at the step's start.
    fn begin(&mut self, _: &System, step: &StepStart<'_>) {
        self.directions = step.x.iter().map(|x| self.direction(x)).collect();
    }

    fn value(&mut self, _: &System, at: &At<'_>) -> Potential {
        let r: f64 = self.rates(at.v).map(|(_, r)| 0.5 * self.c * r * r).sum();
        Potential::non_negative(at.beta_h * r)
    }

    fn add(&mut self, _: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        let bh = at.beta_h;
        for (i, r) in self.rates(at.v) {
            let d = self.directions[i];
            b[i] -= bh * self.c * r * d;
            hessian.add_row(i, SymBlock::rank_one_plus_identity(bh * self.c, d, 0.0));
        }
    }

    fn energy(&mut self, _: &System, _: &[Vec3], _: &[Vec3], _: When) -> Potential {
        Potential::ZERO
    }

    /// `−c (dᵢ·(vᵢ − w)) dᵢ` along the directions at `x`.
    fn force(&self, _: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        for ((fi, xi), vi) in f.iter_mut().zip(x).zip(v) {
            let d = self.direction(xi);
            *fi -= self.c * d.dot(&(vi - self.w)) * d;
        }
    }
}
