//! The springs' term of the incremental potential: their elastic energy
//! and, along directions frozen at the step's start, their dampers'
//! Rayleigh potential.
//!
//! Each spring `s = (i, j)` adds `½k(l − L)² + ½βh c (e·(vᵢ − vⱼ))²` to `Φ`,
//! `e` its damper's direction at the step's start (Baraff & Witkin's
//! Jacobian leaves out the damping force's dependence on positions); to
//! Newton's matrix the block `K_s = β²h² H_s + βh c e eᵀ`, `H_s = k_∥ d dᵀ +
//! k_⊥ (I − d dᵀ)` the factored Hessian `hooke-core` returns, on both ends'
//! diagonals and as `−K_s` between them; and to the right-hand side
//! `±βh [f_s − H_s (uᵢ − uⱼ)]` at a linearisation with displacement `u`.
//!
//! Assembly takes two race-free passes. Pass one splits the pattern's
//! slots into one contiguous chunk per thread; each chunk writes its
//! springs' blocks into their slots and scatters them, with their
//! right-hand-side shares, into accumulators of its own, so no two threads
//! write the same memory. Pass two, per particle, adds the chunks'
//! accumulators to the diagonal block and the right-hand side. The
//! gradient alone takes the same chunks, each spring's length computed
//! once for its energy and its force.

use std::ops::Range;
use std::sync::Arc;

use hooke_core::{
    At, CompressedSprings, Hessian, Potential, Spring, StepStart, SymBlock, System, Term, Vec3,
    When,
};

mod passes;

use crate::linear::matrix::BlockMatrix;
use crate::linear::pattern::Pattern;
use crate::linear::vector::{for_each_row, sum2};
use passes::spring_terms;

/// The springs of a system, with the scratch of their passes.
#[derive(Debug, Clone)]
pub(super) struct Springs {
    /// The springs' slots.
    pattern: Arc<Pattern>,
    /// Whether a spring has a damper.
    damped: bool,
    /// Per chunk of slots: its sums into each particle's diagonal block
    /// and right-hand side, and the rows its springs reach.
    diagonals: Vec<SymBlock>,
    rhs: Vec<Vec3>,
    touched: Vec<Range<usize>>,
    /// Per slot: the damper's direction, frozen at the step's start.
    directions: Vec<Vec3>,
    /// Whether `directions` hold the current step's.
    frozen: bool,
    /// The positions of the step's start, where the directions are taken
    /// (kept where a spring has a damper).
    start: Vec<Vec3>,
}

impl Springs {
    /// The springs of `system`, in the slots of `pattern`.
    pub(super) fn new(system: &System, pattern: Arc<Pattern>) -> Self {
        Self {
            damped: system.springs().iter().any(|s| s.damping > 0.0),
            directions: vec![Vec3::zeros(); pattern.slots()],
            pattern,
            diagonals: Vec::new(),
            rhs: Vec::new(),
            touched: Vec::new(),
            frozen: false,
            start: Vec::new(),
        }
    }

    /// Freezes the dampers' directions `d = (xᵢ − xⱼ)/|xᵢ − xⱼ|` for the
    /// step, unless they are: at the step's start or, before any step, at
    /// the positions `x` of the first evaluation.
    fn freeze(&mut self, system: &System, x: &[Vec3]) {
        if std::mem::replace(&mut self.frozen, true) || !self.damped {
            return;
        }
        let x = if self.start.is_empty() {
            x
        } else {
            &self.start
        };
        let (springs, pattern) = (system.springs(), &self.pattern);
        for_each_row(&mut self.directions, |t, d| {
            let s = &springs[pattern.spring(t)];
            if s.damping > 0.0 {
                *d = s
                    .linearize(x[s.i], x[s.j], CompressedSprings::Clamped)
                    .direction;
            }
        });
    }
}

/// A spring's terms of `Φ` with its ends at `(xᵢ, xⱼ)`, stretched by
/// `l − L` and its ends parting at the rate `d·(vᵢ − vⱼ)` along the
/// frozen damping direction: `½k(l − L)² + ½βh c (d·(vᵢ − vⱼ))²`, and that
/// plus `k |l − L| (|xᵢ| + |xⱼ|)`, the energy the rounding of its ends'
/// coordinates puts into it (divided by ε).
#[inline]
fn spring_potential(
    s: &Spring,
    (xi, xj): (Vec3, Vec3),
    stretch: f64,
    rate: f64,
    beta_h: f64,
) -> (f64, f64) {
    let mut e = 0.5 * s.stiffness * stretch * stretch;
    if s.damping > 0.0 {
        e += 0.5 * beta_h * s.damping * rate * rate;
    }
    let rounding = s.stiffness * stretch.abs() * (xi.amax() + xj.amax());
    (e, e + rounding)
}

impl Term for Springs {
    fn name(&self) -> &'static str {
        "springs"
    }

    /// Marks the dampers' directions to be frozen at the step's start: in
    /// the first assembly's own pass where that is Baraff & Witkin's
    /// linearisation there, otherwise in a pass of their own before the
    /// first evaluation.
    fn begin(&mut self, _system: &System, step: &StepStart<'_>) {
        self.frozen = false;
        if self.damped {
            self.start.clear();
            self.start.extend_from_slice(step.x);
        }
    }

    fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        self.freeze(system, at.x);
        let (springs, pattern, directions) = (system.springs(), &self.pattern, &self.directions);
        let (x, v) = (at.x, at.v);
        let (value, magnitude) = sum2(pattern.slots(), |t| {
            let s = &springs[pattern.spring(t)];
            let (xi, xj) = (x[s.i], x[s.j]);
            let stretch = (xi - xj).norm() - s.rest_length;
            let rate = if s.damping > 0.0 {
                directions[t].dot(&(v[s.i] - v[s.j]))
            } else {
                0.0
            };
            spring_potential(s, (xi, xj), stretch, rate, at.beta_h)
        });
        Potential { value, magnitude }
    }

    /// One pass over the springs for `Φ` and `−∇Φ` (see `passes`); `b`
    /// gets the assembly's right-hand side at an iterate to the bit.
    fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        self.freeze(system, at.x);
        self.gradient_pass(system, at, b)
    }

    /// The blocks go into the matrix's slots where `hessian` is the step's
    /// [`BlockMatrix`] (see the module docs), spring by spring otherwise.
    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian) {
        // Baraff & Witkin's linearisation, the first assembly of a step
        // that takes it, lies at the step's start: its own pass takes the
        // dampers' directions there.
        let freeze = !self.frozen && at.displacement.is_some();
        if freeze {
            self.frozen = true;
        } else {
            self.freeze(system, at.x);
        }
        let n = system.particle_count();
        if let Some(a) = hessian
            .as_any_mut()
            .and_then(|a| a.downcast_mut::<BlockMatrix>())
        {
            debug_assert_eq!(a.pattern.slots(), self.pattern.slots());
            self.assemble(system, at, a, freeze);
            self.gather(n, b, Some(&mut a.diagonal));
            return;
        }
        let (springs, pattern) = (system.springs(), &self.pattern);
        for (t, frozen) in self.directions.iter_mut().enumerate() {
            let s = &springs[pattern.spring(t)];
            let (block, shared) = spring_terms(s, at, frozen, freeze);
            b[s.i] += at.beta_h * shared;
            b[s.j] -= at.beta_h * shared;
            hessian.add_row(s.i, block);
            hessian.add_row(s.j, block);
            hessian.add_pair(s.i, s.j, -block.to_mat3());
        }
    }

    /// `Σ ½k(l − L)²`.
    fn energy(&mut self, system: &System, x: &[Vec3], _v: &[Vec3], _when: When) -> Potential {
        let e = system
            .springs()
            .iter()
            .map(|s| s.energy(x[s.i], x[s.j]))
            .sum();
        Potential::non_negative(e)
    }

    /// The work of scripted pins through the springs at them, by the
    /// trapezoid rule: `−½(∇ₚV(xₙ) + ∇ₚV(xₙ₊₁))·(xₚ,ₙ₊₁ − xₚ,ₙ)` at each
    /// scripted pin `p`.
    fn work(&mut self, system: &System, step: &StepStart<'_>, x: &[Vec3], _v: &[Vec3]) -> f64 {
        let paths = system.pin_paths();
        if paths.is_empty() {
            return 0.0;
        }
        let x0 = step.x;
        let mut work = 0.0;
        for s in system.springs() {
            for (p, q, sign) in [(s.i, s.j, 1.0), (s.j, s.i, -1.0)] {
                if !paths.iter().any(|(i, _)| *i == p) {
                    continue;
                }
                // ∇ₚV is minus the elastic force on p.
                let (a, b) = if sign > 0.0 { (p, q) } else { (q, p) };
                let f0 = sign * s.elastic_force(x0[a], x0[b]);
                let f1 = sign * s.elastic_force(x[a], x[b]);
                work -= 0.5 * (f0 + f1).dot(&(x[p] - x0[p]));
            }
        }
        work
    }

    fn force(&self, system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        system.add_spring_forces(x, v, f);
    }

    /// `k wᵢ (wᵢ + wⱼ)` and `c wᵢ (wᵢ + wⱼ)` at each end `i`: a clamped
    /// stiffness block has norm at most `k`.
    fn rates(&self, system: &System, w: &[f64], stiffness: &mut [f64], damping: &mut [f64]) {
        for s in system.springs() {
            let (a, b) = (w[s.i], w[s.j]);
            stiffness[s.i] += s.stiffness * a * (a + b);
            stiffness[s.j] += s.stiffness * b * (a + b);
            damping[s.i] += s.damping * a * (a + b);
            damping[s.j] += s.damping * b * (a + b);
        }
    }

    /// Each spring's block `H`, compressed springs clamped.
    fn stiffness(&self, system: &System, x: &[Vec3], k: &mut dyn Hessian) {
        for s in system.springs() {
            let h = s.stiffness_block(x[s.i], x[s.j], CompressedSprings::Clamped);
            let block = SymBlock::symmetric_part(&h);
            k.add_row(s.i, block);
            k.add_row(s.j, block);
            k.add_pair(s.i, s.j, -h);
        }
    }
}
