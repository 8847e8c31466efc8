//! [`Wind`]: the drag of a uniform wind on a system's surfaces, a term of
//! the model ([`Term`]).

use crate::{At, Hessian, Potential, StepStart, SymBlock, System, Term, Vec3, When};

/// A uniform wind of velocity `w` (m/s) dragging, with the coefficient `c`
/// (N·s/m³, per unit area), on a set of triangles. It joins a system as
/// one of its terms ([`SystemBuilder::term`](crate::SystemBuilder::term));
/// the scene file's `[world] wind` gives it every body's surface
/// triangles.
///
/// # The dissipation potential
///
/// Air moving at the uniform velocity `w` pushes on each triangle `T` of
/// the surfaces it is given, of area `A` and unit normal `n`, against the
/// normal component of the triangle's velocity relative to the air: with
/// `v_T = (v_a + v_b + v_c)/3` the mean of its vertices' velocities and
/// `c` the drag coefficient per unit area (N·s/m³), the dissipation
/// potential
///
/// ```text
/// R(v) = Σ_T ½ c A ((v_T − w)·n)²
/// ```
///
/// gives the force `F_T = −c A ((v_T − w)·n) n` on the triangle, a third of
/// it on each vertex,
///
/// ```text
/// fᵢ = −∇ᵥᵢR = −Σ_{T ∋ i} ⅓ c A ((v_T − w)·n) n.
/// ```
///
/// A sheet at rest facing the wind feels the pressure `c (w·n)` per unit
/// area; one moving with it, none. The drag is linear in the relative
/// velocity, a model of slow flow or of the quadratic drag linearised
/// about the wind's speed; it acts on both faces alike, so a closed
/// surface feels it on its lee side as well.
///
/// # Lagged over a step
///
/// In an implicit step each triangle's `A` and `n` are those at the step's
/// start ([`Term::begin`]), so that `R` is a convex quadratic in `v` and
/// enters `Φ` as `βh R(v)`, as air damping does: its gradient is
/// `βh ∇ᵥR`, and its Hessian, exact and positive semidefinite,
///
/// ```text
/// βh ∇²ᵥR = βh Σ_T (c A / 9) (1 1ᵀ ⊗ n nᵀ),
/// ```
///
/// the block `βh (c A / 9) n nᵀ` at every ordered pair `(i, j)` of `T`'s
/// vertices, `i = j` included. The blocks between vertices that no spring
/// joins go where the assembled matrix keeps contact's and volume
/// elements' ([`Hessian::add_pair`]). Before its first step a term takes
/// the triangles at the system's initial positions. The explicit
/// integrators evaluate the force at their current state, with the
/// triangles' current areas and normals ([`Term::force`]).
///
/// # Energy and work
///
/// A dissipation potential stores no energy, but moving air does work on
/// the surfaces: at the power `F_T·v_T = F_T·(v_T − w) + F_T·w`, of which
/// the first part, `−c A ((v_T − w)·n)² ≤ 0`, is dissipated and the second
/// is the wind's. A converged backward-Euler step from `(x₀, v₀)` to
/// `(x₁, v₁)` on a convex potential changes the energy by at most
/// `−h v₁·∇ᵥR(v₁)` (`hooke_implicit`'s energy test), and
///
/// ```text
/// v·∇ᵥR(v) = Σ_T c A ((v_T − w)·n)(v_T·n) = Σ_T c A ((v_T − w)·n)² − Σ_T F_T·w,
/// ```
///
/// so `E(x₁, v₁) − E(x₀, v₀) ≤ W` with the wind's work over the step
///
/// ```text
/// W = h Σ_T F_T(v₁)·w       (Term::work),
/// ```
///
/// the drag at the step's end velocities with the lagged triangles. Without
/// it, a cloth the wind sets moving would gain energy at every step.
///
/// # Conditioning
///
/// With `wᵢ = 1/√mᵢ`, the absolute row sums of `M^(−1/2) C M^(−1/2)` at
/// particle `i` are at most `wᵢ Σ_{T ∋ i} (c A / 9)(w_a + w_b + w_c)`,
/// each block `(c A / 9) n nᵀ` having norm `c A / 9` ([`Term::rates`]). The
/// areas are taken at the system's initial positions: the bound holds
/// while no triangle grows beyond its initial area, as a volume element's
/// holds near rest.
///
/// # Example
///
/// ```
/// use hooke_core::{SystemBuilder, Vec3, Wind};
///
/// // A triangle of 1/2 m² facing +z in a 2 m/s wind along +z.
/// let mut b = SystemBuilder::new();
/// let t = [
///     b.particle(0.1, [0.0, 0.0, 0.0]),
///     b.particle(0.1, [1.0, 0.0, 0.0]),
///     b.particle(0.1, [0.0, 1.0, 0.0]),
/// ];
/// b.term(Wind::new([0.0, 0.0, 2.0], 0.6, vec![t]));
/// let system = b.build()?;
/// let state = system.initial_state();
/// let mut f = vec![Vec3::zeros(); 3];
/// system.terms()[0].force(&system, state.positions(), state.velocities(), &mut f);
/// // c A (w·n) = 0.6 · 0.5 · 2 N on the triangle, a third on each vertex.
/// assert!((f[0] - Vec3::new(0.0, 0.0, 0.2)).norm() < 1e-15);
/// # Ok::<(), hooke_core::BuildError>(())
/// ```
#[derive(Debug, Clone)]
pub struct Wind {
    /// The air's velocity `w`, m/s.
    velocity: Vec3,
    /// The drag coefficient `c`, N·s/m³.
    drag: f64,
    /// The triangles it acts on, by particle.
    triangles: Vec<[usize; 3]>,
    /// Per triangle, its `c A` and `n` at the start of the step (empty
    /// before the first).
    lagged: Vec<Face>,
}

/// A triangle's drag `c A` (N·s/m) and unit normal `n` (zero for a
/// triangle of no area).
#[derive(Debug, Clone, Copy)]
struct Face {
    /// `c A`, N·s/m.
    drag: f64,
    /// `n`.
    normal: Vec3,
}

impl Face {
    /// The face of the triangle `t` at positions `x` under the drag
    /// coefficient `c`.
    fn at(t: [usize; 3], x: &[Vec3], c: f64) -> Self {
        let [a, b, d] = t.map(|i| x[i]);
        let twice_area = (b - a).cross(&(d - a));
        let norm = twice_area.norm();
        let normal = if norm > 0.0 {
            twice_area / norm
        } else {
            Vec3::zeros()
        };
        Self {
            drag: 0.5 * c * norm,
            normal,
        }
    }

    /// `(v_T − w)·n`, the normal speed of the triangle `t` relative to
    /// the wind `w` at velocities `v`: the force on the triangle is
    /// `−c A` times it times `n`.
    fn speed(&self, t: [usize; 3], v: &[Vec3], w: Vec3) -> f64 {
        let mean = (v[t[0]] + v[t[1]] + v[t[2]]) / 3.0;
        (mean - w).dot(&self.normal)
    }
}

impl Wind {
    /// A wind of velocity `w` m/s dragging with the coefficient `c`
    /// N·s/m³ on `triangles` (by particle index). `w` must be finite, `c`
    /// finite and non-negative, and each triangle three distinct particles
    /// of the system ([`Term::problem`]).
    #[must_use]
    pub fn new(velocity: impl Into<Vec3>, drag: f64, triangles: Vec<[usize; 3]>) -> Self {
        Self {
            velocity: velocity.into(),
            drag,
            triangles,
            lagged: Vec::new(),
        }
    }

    /// Takes each triangle's `c A` and `n` at `x`, reusing the buffer.
    fn lag(&mut self, x: &[Vec3]) {
        let c = self.drag;
        self.lagged.clear();
        self.lagged
            .extend(self.triangles.iter().map(|&t| Face::at(t, x, c)));
    }

    /// Lags the triangles at `system`'s initial positions if no step has
    /// begun.
    fn lag_before_first_step(&mut self, system: &System) {
        if self.lagged.len() != self.triangles.len() {
            self.lag(system.initial_positions());
        }
    }

    /// `βh R(v)` with the lagged triangles, and `b −= βh ∇ᵥR` if `b` is
    /// given.
    fn potential(&mut self, system: &System, at: &At<'_>, mut b: Option<&mut [Vec3]>) -> Potential {
        let (w, bh) = (self.velocity, at.beta_h);
        self.lag_before_first_step(system);
        let mut value = 0.0;
        for (&t, face) in self.triangles.iter().zip(&self.lagged) {
            let s = face.speed(t, at.v, w);
            value += 0.5 * bh * face.drag * s * s;
            if let Some(b) = b.as_deref_mut() {
                let share = (bh * face.drag * s / 3.0) * face.normal;
                for i in t {
                    b[i] -= share;
                }
            }
        }
        Potential::non_negative(value)
    }
}

impl Term for Wind {
    fn name(&self) -> &'static str {
        "wind"
    }

    fn problem(&self, system: &System) -> Option<String> {
        let w = self.velocity;
        if !w.iter().all(|c| c.is_finite()) {
            return Some(format!(
                "velocity [{}, {}, {}] m/s is not finite",
                w.x, w.y, w.z
            ));
        }
        if !(self.drag.is_finite() && self.drag >= 0.0) {
            return Some(format!("drag {} N·s/m³ is not finite and ≥ 0", self.drag));
        }
        let n = system.particle_count();
        self.triangles.iter().enumerate().find_map(|(k, t)| {
            if let Some(&i) = t.iter().find(|&&i| i >= n) {
                Some(format!(
                    "triangle {k} names particle {i}, out of range ({n} particles)"
                ))
            } else if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                Some(format!("triangle {k} repeats a particle: {t:?}"))
            } else {
                None
            }
        })
    }

    fn begin(&mut self, _system: &System, step: &StepStart<'_>) {
        self.lag(step.x);
    }

    fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        self.potential(system, at, None)
    }

    /// The value and `b −= βh ∇ᵥR` in one pass over the triangles.
    fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        self.potential(system, at, Some(b))
    }

    /// `b −= βh ∇ᵥR` and the blocks `βh (c A / 9) n nᵀ` of each triangle,
    /// three on the diagonal and three between its vertices.
    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        self.potential(system, at, Some(b));
        let bh = at.beta_h;
        for (&[i, j, k], face) in self.triangles.iter().zip(&self.lagged) {
            let s = bh * face.drag / 9.0;
            let row = SymBlock::rank_one_plus_identity(s, face.normal, 0.0);
            for p in [i, j, k] {
                hessian.add_row(p, row);
            }
            let pair = s * face.normal * face.normal.transpose();
            for (p, q) in [(i, j), (j, k), (i, k)] {
                hessian.add_pair(p, q, pair);
            }
        }
    }

    fn energy(&mut self, _system: &System, _x: &[Vec3], _v: &[Vec3], _when: When) -> Potential {
        Potential::ZERO
    }

    /// `W = h Σ_T F_T(v)·w` with the lagged triangles (see [`Wind`]).
    fn work(&mut self, system: &System, step: &StepStart<'_>, _x: &[Vec3], v: &[Vec3]) -> f64 {
        let w = self.velocity;
        self.lag_before_first_step(system);
        let power: f64 = self
            .triangles
            .iter()
            .zip(&self.lagged)
            .map(|(&t, face)| -face.drag * face.speed(t, v, w) * face.normal.dot(&w))
            .sum();
        step.h * power
    }

    /// The drag with each triangle's area and normal at `x`.
    fn force(&self, _system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        for &t in &self.triangles {
            let face = Face::at(t, x, self.drag);
            let share = (face.drag * face.speed(t, v, self.velocity) / 3.0) * face.normal;
            for i in t {
                f[i] -= share;
            }
        }
    }

    /// `P = Σ_T c A ((v_T − w)·n)² = −Σ_T F_T·(v_T − w)` with each
    /// triangle's area and normal at `x`: the drag's power `Σ_T F_T·v_T`
    /// less the wind's `Σ_T F_T·w`, negated (see [`Wind`]).
    fn dissipation_power(&self, _system: &System, x: &[Vec3], v: &[Vec3]) -> f64 {
        self.triangles
            .iter()
            .map(|&t| {
                let face = Face::at(t, x, self.drag);
                let s = face.speed(t, v, self.velocity);
                face.drag * s * s
            })
            .sum()
    }

    /// `wᵢ Σ_{T ∋ i} (c A / 9)(w_a + w_b + w_c)` on the damping rates, the
    /// areas at the initial positions.
    fn rates(&self, system: &System, w: &[f64], _stiffness: &mut [f64], damping: &mut [f64]) {
        let x = system.initial_positions();
        for &t in &self.triangles {
            let face = Face::at(t, x, self.drag);
            let sum: f64 = t.iter().map(|&i| w[i]).sum();
            for i in t {
                damping[i] += w[i] * face.drag / 9.0 * sum;
            }
        }
    }
}

#[cfg(test)]
mod tests;
