//! The terms of the model: each part of the incremental potential an
//! implicit step minimises, and of the energy and forces every integrator
//! sees, as one type behind one interface, [`Term`].
//!
//! # The incremental potential
//!
//! A step of length `h` of backward Euler (`β = 1`) or BDF2 (`β = 2/3` at a
//! constant step) solves `M(v − ṽ) = βh f(x, v)`, `x = x̃ + βh v`, for the
//! new velocities `v` (`x̃`, `ṽ` the scheme's predictors) by minimising
//!
//! ```text
//! Φ(v) = Σ_terms Φ_term(v),
//! ```
//!
//! whose gradient is the residual `M(v − ṽ) − βh f`. Each term is one of
//!
//! - the inertia `½‖v − ṽ‖²_M`;
//! - a potential `V(x̃ + βh v)` (springs `½k(l − L)²`, volume elements,
//!   gravity `−Σ mᵢ g·xᵢ`, contact barriers), whose gradient in `v` is
//!   `βh ∇ₓV = −βh f` and Hessian `β²h² ∇²ₓV = β²h² K`;
//! - a dissipation potential times `βh`, `βh R(v)` (dampers along their
//!   directions frozen at the step's start, air damping `½γ|v|²`, friction,
//!   wind), whose gradient is `βh ∇ᵥR = −βh f` and Hessian `βh C`.
//!
//! So a term gives, at a point [`At`]: its value `Φ_term`
//! ([`Term::value`]); `b −= ∇Φ_term`, which summed over the terms makes
//! `b = −∇Φ = M(ṽ − v) + βh f` ([`Term::gradient`]); and with it its
//! Hessian `∇²Φ_term`, exact or a positive-semidefinite stand-in, written
//! into whatever the minimiser builds ([`Term::add`], [`Hessian`]) — summed,
//! Newton's matrix `A = M + βh C + β²h² K`. At Baraff & Witkin's
//! linearisation about a point `X` off `x̃ + βh v` (the step's start, with
//! the displacement `u = x̃ + βh V − X` of [`At::displacement`]) each
//! potential's right-hand side also gets `−βh K u`.
//!
//! # The energy test
//!
//! A converged backward-Euler step on a convex energy cannot gain energy,
//! so each step is tested: with
//!
//! ```text
//! E(x, v) = Σ_terms E_term(x, v)
//! ```
//!
//! — the free particles' kinetic energy `½‖v‖²_M` (the inertia's part), the
//! potentials' values, nothing for a dissipation potential
//! ([`Term::energy`]) — and `W = Σ_terms W_term`, the work external agents
//! did over the step through the terms (scripted pins through springs and
//! volume elements, moving obstacles through contact, a wind;
//! [`Term::work`]), a step is accepted when
//! `E(xₙ₊₁, vₙ₊₁) ≤ E(xₙ, vₙ) + W` up to rounding.
//!
//! # The conditioning bound
//!
//! `A` has condition number relative to `M` of at most
//! `1 + βh ζ + β²h² ω²`, with `ω²` and `ζ` the block-Gershgorin bounds on
//! `M^(−1/2) K M^(−1/2)` and `M^(−1/2) C M^(−1/2)`: with `wᵢ = 1/√mᵢ`
//! (zero for pinned particles),
//!
//! ```text
//! ω² ≤ maxᵢ Σ_terms sᵢ,   ζ ≤ maxᵢ Σ_terms dᵢ,
//! ```
//!
//! each term adding to `sᵢ` and `dᵢ` a bound on the absolute row sums of
//! its blocks at particle `i`, valid in every state the step reaches
//! ([`Term::rates`]): a spring `(i, j)` of stiffness `k` and damping `c`
//! adds `k wᵢ (wᵢ + wⱼ)` and `c wᵢ (wᵢ + wⱼ)` at `i`, air damping `γ wᵢ²`.
//!
//! # The explicit integrators
//!
//! They integrate `M x'' = Σ_terms f_term(x, v)` ([`Term::force`]). The
//! [`System`]'s own springs, volume elements, gravity and air
//! damping are summed by [`ForceEvaluator`](crate::ForceEvaluator)'s fused
//! passes; the terms a scene declares beyond them
//! ([`SystemBuilder::term`](crate::SystemBuilder::term),
//! [`System::terms`](crate::System::terms)) through this interface, as
//! [`System::energy`](crate::System::energy) sums their energies.

mod blocks;
mod hessian;
mod point;
mod potential;

use std::fmt;

pub use blocks::Blocks;
pub use hessian::Hessian;
pub use point::{At, StepStart, When};
pub use potential::Potential;

use crate::{State, System, Vec3};

/// One term of the model: a part of the incremental potential `Φ`, of the
/// energy and of the forces (see the [module docs](self) for the
/// equations). An implicit step holds its terms as a list and sums them;
/// a scene's own terms join through [`SystemBuilder::term`](crate::SystemBuilder::term).
///
/// The required methods are a term's value, its gradient and Hessian, its
/// energy and its force; the rest default to a term that lags nothing,
/// does no external work, adds nothing to the conditioning bound or the
/// spectrum and is finite everywhere. A term that is infinite outside a
/// feasible set (a barrier, [`Term::is_barrier`]) gives the hooks a step
/// needs to stay inside it.
pub trait Term: fmt::Debug + Send + Sync + TermClone {
    /// The term's name for reports and errors: `"springs"`, `"contact"`, ….
    fn name(&self) -> &'static str;

    /// What is wrong with the term in `system` (a particle out of range, a
    /// parameter out of its domain), if anything:
    /// [`SystemBuilder::build`](crate::SystemBuilder::build) reports it.
    fn problem(&self, _system: &System) -> Option<String> {
        None
    }

    /// Starts a (sub)step: takes what the term lags over the step at its
    /// start.
    fn begin(&mut self, _system: &System, _step: &StepStart<'_>) {}

    /// `Φ_term` at `at` and its magnitude for rounding; infinite where a
    /// barrier's gap is not positive.
    fn value(&mut self, system: &System, at: &At<'_>) -> Potential;

    /// `b −= ∇Φ_term` at `at`, the gradient in the velocities, and
    /// `Φ_term` there ([`Term::value`]): what a minimiser without a matrix
    /// needs. By default [`Term::add`] into no matrix, then the value; a
    /// term overrides it where one pass gives both.
    fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        self.add(system, at, b, &mut ());
        self.value(system, at)
    }

    /// `b −= ∇Φ_term` at `at` (with `−βh K u` for a potential at a
    /// linearisation with displacement `u`) and `hessian += ∇²Φ_term`, exact
    /// or its positive-semidefinite stand-in as [`At::compressed`] says.
    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], hessian: &mut dyn Hessian);

    /// The term's part of the energy `E` at positions `x` and velocities
    /// `v`, at the step's `when` end (zero for a dissipation potential),
    /// and its magnitude for rounding.
    fn energy(&mut self, system: &System, x: &[Vec3], v: &[Vec3], when: When) -> Potential;

    /// The work external agents did on the particles through the term over
    /// the step from `step` to `(x, v)`, J: scripted pins moving a spring's
    /// end, obstacles moving under contact, moving air.
    fn work(&mut self, _system: &System, _step: &StepStart<'_>, _x: &[Vec3], _v: &[Vec3]) -> f64 {
        0.0
    }

    /// Adds the term's force `f = −∇ₓV − ∇ᵥR` at `(x, v)` to `f`, for the
    /// explicit integrators (nothing for the inertia, and for contact,
    /// which they resolve at the end of each step).
    fn force(&self, system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]);

    /// The power `P ≥ 0` the term dissipates at `(x, v)`, W: for a
    /// dissipation potential `R` of a velocity relative to a moving
    /// medium, `−Σᵢ fᵢ·(vᵢ − wᵢ)`, where `wᵢ` is the medium's velocity at
    /// particle `i`. The force's power `Σᵢ fᵢ·vᵢ` alone does not tell it:
    /// it is `−P`, plus the external agents' power, minus the rate of
    /// change of the term's energy (a wind's drag both dissipates and
    /// does work), so each term says what it dissipates. By default zero,
    /// for a term that dissipates nothing.
    fn dissipation_power(&self, _system: &System, _x: &[Vec3], _v: &[Vec3]) -> f64 {
        0.0
    }

    /// Adds to each particle's `stiffness` and `damping` rates a bound on
    /// the absolute row sums of the term's `M^(−1/2) K M^(−1/2)` and
    /// `M^(−1/2) C M^(−1/2)` at it, `w` holding `1/√mᵢ` (zero for pinned
    /// particles), valid in every state a step reaches: the conditioning
    /// bound of the module docs. A barrier, unbounded near its support,
    /// adds nothing.
    fn rates(&self, _system: &System, _w: &[f64], _stiffness: &mut [f64], _damping: &mut [f64]) {}

    /// Adds the term's stiffness `K = ∇²ₓV` at positions `x` (its
    /// positive-semidefinite stand-in) to `k`: the linearised undamped
    /// motion `M u'' = −K u` whose frequencies bound the explicit steps.
    fn stiffness(&self, _system: &System, _x: &[Vec3], _k: &mut dyn Hessian) {}

    /// Whether the term is a barrier: infinite outside a feasible set of
    /// positions, so that a step starts inside it ([`Term::push_out`],
    /// [`Term::start`]), every motion is limited to stay there
    /// ([`Term::limit`]), and the quasi-Newton step's initial Hessian takes
    /// its diagonal blocks, which grow without bound near its support.
    fn is_barrier(&self) -> bool {
        false
    }

    /// Moves the free particles of `state` where the term is infinite to
    /// where it is finite (a particle inside an obstacle, out along the
    /// normal), before a step; returns how many it moved.
    fn push_out(&mut self, _system: &System, _state: &mut State) -> usize {
        0
    }

    /// Feasible positions for the step [`Term::begin`] started to start
    /// from, where the start itself is not.
    fn start(&self) -> Option<&[Vec3]> {
        None
    }

    /// The largest `τ ∈ [0, 1]` such that the term stays finite, with room
    /// to spare, along the motion from `x` to `x + τ dx`. A barrier's
    /// [`Term::value`] and [`Term::add`] may require their point to lie on
    /// the motion last checked.
    fn limit(&mut self, _system: &System, _x: &[Vec3], _dx: &[Vec3]) -> f64 {
        1.0
    }

    /// Each particle's fraction `sᵢ ∈ [0, 1]` of the motion from `x` by
    /// `dx` such that the term stays finite, with room to spare, along the
    /// motion from `x` to `x + s∘dx` (`(s∘dx)ᵢ = sᵢ dxᵢ`): [`Term::limit`]
    /// per particle, so that a particle the term does not stop moves all
    /// the way. `None` for a term that stops no motion. As after
    /// [`Term::limit`], a barrier's [`Term::value`] and [`Term::add`] may
    /// require their point to lie on the motion last checked.
    fn truncate(&mut self, _system: &System, _x: &[Vec3], _dx: &[Vec3]) -> Option<&[f64]> {
        None
    }

    /// The collision detection the term ran since the last call: its
    /// proximity queries and the time its searches and checks of motions
    /// took, in seconds. None for a term without contact.
    fn take_detection(&mut self) -> (usize, f64) {
        (0, 0.0)
    }

    /// Tells the term that a full Newton step of its model failed the line
    /// search: a term with a model that cannot overshoot its minimum (the
    /// friction's majorizing one) turns to it for the rest of the step.
    fn full_step_failed(&mut self) {}

    /// Ends an accepted step at positions `x`; returns the number of
    /// contacts the term holds there (for
    /// [`StepReport::contacts`](crate::StepReport::contacts)).
    fn end_step(&mut self, _system: &System, _x: &[Vec3]) -> usize {
        0
    }
}

/// A copy of a boxed [`Term`]: every term implements it through [`Clone`],
/// so that a [`System`] holding terms can be cloned and a step can take its
/// own copies of them to lag state in.
pub trait TermClone {
    /// A boxed copy of the term.
    fn clone_box(&self) -> Box<dyn Term>;
}

impl<T: Term + Clone + 'static> TermClone for T {
    fn clone_box(&self) -> Box<dyn Term> {
        Box::new(self.clone())
    }
}

impl Clone for Box<dyn Term> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}
