//! The terms of a system's incremental potential `Φ` as one list
//! ([`Terms`]), which every part of the implicit step iterates: the
//! assembly of Newton's system, `Φ` in the line search, the quasi-Newton
//! step's gradient, the energy test, the conditioning bound, and the
//! contact's hooks. [`hooke_core::term`] gives the interface and its
//! equations; each term here is one file.

mod air_damping;
mod assemble;
mod contact;
#[cfg(test)]
mod derivatives;
mod gravity;
mod inertia;
mod springs;
mod volume;

use std::sync::Arc;

use hooke_core::{At, Hessian, Potential, State, StepError, StepStart, System, Term, Vec3, When};

use crate::linear::pattern::Pattern;
use air_damping::AirDamping;
use contact::Contact;
use gravity::Gravity;
use inertia::Inertia;
use springs::Springs;
use volume::Volume;

#[cfg(test)]
pub(crate) use assemble::{assembled, linearised_step, step_from};
pub use volume::PARALLEL_MIN_ELEMENTS;

/// The terms of a system's incremental potential `Φ`, in the order a step
/// sums them: the inertia, gravity and air damping if the system declares
/// them, its springs and volume elements if it has any, its own terms
/// ([`System::terms`], copies the step lags its state in), and contact if
/// it has obstacles or colliding surfaces. A system pays for what it
/// declares only.
///
/// Summing in this order, each term adding in place, gives Newton's
/// right-hand side and matrix to the bit as one fused pass over the
/// particles did, and the quasi-Newton step's gradient the same bits as
/// Newton's right-hand side at the same point.
///
/// ```
/// use hooke_core::reference::Sheet;
/// use hooke_implicit::Terms;
///
/// let system = Sheet::new(4).system()?;
/// let terms = Terms::new(&system)?;
/// let names: Vec<_> = terms.iter().map(|t| t.name()).collect();
/// assert_eq!(names, ["inertia", "gravity", "air damping", "springs"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Terms {
    /// The system the terms are for.
    system: u64,
    /// The springs' sparsity pattern (empty rows without springs), shared
    /// with the step's matrix.
    pattern: Arc<Pattern>,
    list: Vec<Box<dyn Term>>,
    /// Whether a term is a barrier ([`Term::is_barrier`]).
    barrier: bool,
    /// Each particle's fraction of the last truncated motion
    /// ([`Terms::truncate`]).
    scale: Vec<f64>,
}

impl Terms {
    /// The terms of `system`'s `Φ` (see [`Terms`]).
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] if the particles or the springs do not
    /// fit the pattern's 32-bit indices.
    pub fn new(system: &System) -> Result<Self, StepError> {
        let pattern = Arc::new(Pattern::new(system)?);
        let mut list: Vec<Box<dyn Term>> = vec![Box::new(Inertia)];
        if let Some(g) = system.gravity() {
            list.push(Box::new(Gravity::new(g)));
        }
        if let Some(gamma) = system.air_damping() {
            list.push(Box::new(AirDamping::new(gamma)));
        }
        if !system.springs().is_empty() {
            list.push(Box::new(Springs::new(system, Arc::clone(&pattern))));
        }
        if system.tets().iter().any(|t| t.modulus > 0.0) {
            list.push(Box::new(Volume::new(system, &pattern)));
        }
        list.extend(system.terms().iter().cloned());
        if Contact::present(system) {
            list.push(Box::new(Contact::default()));
        }
        let barrier = list.iter().any(|t| t.is_barrier());
        Ok(Self {
            system: system.id(),
            pattern,
            list,
            barrier,
            scale: Vec::new(),
        })
    }

    /// The terms for `system`: `cached` if they are its, otherwise new ones
    /// in their place.
    ///
    /// # Errors
    /// As [`Terms::new`].
    pub(crate) fn of<'a>(
        cached: &'a mut Option<Terms>,
        system: &System,
    ) -> Result<&'a mut Terms, StepError> {
        if cached.as_ref().is_none_or(|t| t.system != system.id()) {
            *cached = Some(Self::new(system)?);
        }
        Ok(cached.as_mut().expect("set above"))
    }

    /// The terms, in the order they are summed.
    pub fn iter(&self) -> impl Iterator<Item = &dyn Term> {
        self.list.iter().map(|t| &**t)
    }

    /// The springs' sparsity pattern, which the step's matrix shares.
    pub(crate) fn pattern(&self) -> &Arc<Pattern> {
        &self.pattern
    }

    /// Whether a term is a barrier ([`Term::is_barrier`]): the step starts
    /// from feasible positions and limits every motion.
    pub(crate) fn has_barrier(&self) -> bool {
        self.barrier
    }

    /// Starts a (sub)step ([`Term::begin`]).
    pub fn begin(&mut self, system: &System, step: &StepStart<'_>) {
        for t in &mut self.list {
            t.begin(system, step);
        }
    }

    /// `Φ` at `at` and its magnitude for rounding, infinite where a
    /// barrier's gap is not positive.
    pub fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        self.list
            .iter_mut()
            .fold(Potential::ZERO, |sum, t| sum + t.value(system, at))
    }

    /// `Φ` at `at`, as [`Terms::value`], and `b = −∇Φ` without the
    /// barriers' terms, which the minimiser adds only at the points it
    /// keeps: each smooth term's value and gradient come from one pass,
    /// while a barrier's gradient, from its pairs' projected Hessians,
    /// costs several of its values.
    pub fn gradient(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3]) -> Potential {
        b.fill(Vec3::zeros());
        self.list.iter_mut().fold(Potential::ZERO, |sum, t| {
            sum + if t.is_barrier() {
                t.value(system, at)
            } else {
                t.gradient(system, at, b)
            }
        })
    }

    /// Adds the barriers' terms at `at` to `b` and `hessian`
    /// ([`Term::add`]), completing [`Terms::gradient`]'s `b`.
    pub(crate) fn add_barriers(
        &mut self,
        system: &System,
        at: &At<'_>,
        b: &mut [Vec3],
        hessian: &mut dyn Hessian,
    ) {
        for t in self.list.iter_mut().filter(|t| t.is_barrier()) {
            t.add(system, at, b, hessian);
        }
    }

    /// The energy `E` at `(x, v)` at the step's `when` end and its
    /// magnitude for rounding ([`Term::energy`]).
    pub(crate) fn energy(
        &mut self,
        system: &System,
        x: &[Vec3],
        v: &[Vec3],
        when: When,
    ) -> Potential {
        self.list
            .iter_mut()
            .fold(Potential::ZERO, |sum, t| sum + t.energy(system, x, v, when))
    }

    /// The work external agents did over the step from `step` to `(x, v)`
    /// ([`Term::work`]).
    pub(crate) fn work(
        &mut self,
        system: &System,
        step: &StepStart<'_>,
        x: &[Vec3],
        v: &[Vec3],
    ) -> f64 {
        self.list
            .iter_mut()
            .map(|t| t.work(system, step, x, v))
            .sum()
    }

    /// Moves `state` to where every barrier is finite before a step
    /// ([`Term::push_out`]); returns how many particles moved.
    pub(crate) fn push_out(&mut self, system: &System, state: &mut State) -> usize {
        self.barriers().map(|t| t.push_out(system, state)).sum()
    }

    /// The feasible positions a barrier gives the step to start from
    /// ([`Term::start`]).
    pub(crate) fn start(&self) -> Option<&[Vec3]> {
        self.list.iter().find_map(|t| t.start())
    }

    /// The largest `τ ∈ [0, 1]` along the motion from `x` to `x + τ dx`
    /// that every barrier allows ([`Term::limit`]).
    pub(crate) fn limit(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> f64 {
        self.barriers()
            .map(|t| t.limit(system, x, dx))
            .fold(1.0, f64::min)
    }

    /// Each particle's fraction `sᵢ ∈ [0, 1]` of the motion from `x` by
    /// `dx` that every barrier allows ([`Term::truncate`]), the smallest of
    /// theirs; all 1 without barriers.
    pub(crate) fn truncate(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> &[f64] {
        let scale = &mut self.scale;
        scale.clear();
        scale.resize(x.len(), 1.0);
        for t in self.list.iter_mut().filter(|t| t.is_barrier()) {
            if let Some(own) = t.truncate(system, x, dx) {
                scale.iter_mut().zip(own).for_each(|(s, o)| *s = s.min(*o));
            }
        }
        &self.scale
    }

    /// The collision detection the terms ran since the last call
    /// ([`Term::take_detection`]): proximity queries and seconds.
    pub(crate) fn take_detection(&mut self) -> (usize, f64) {
        self.barriers()
            .map(|t| t.take_detection())
            .fold((0, 0.0), |(q, s), (tq, ts)| (q + tq, s + ts))
    }

    /// Tells the terms that a full Newton step failed
    /// ([`Term::full_step_failed`]).
    pub(crate) fn full_step_failed(&mut self) {
        for t in &mut self.list {
            t.full_step_failed();
        }
    }

    /// Ends an accepted step at `x` ([`Term::end_step`]); returns the
    /// contacts the terms hold there.
    pub(crate) fn end_step(&mut self, system: &System, x: &[Vec3]) -> usize {
        self.list.iter_mut().map(|t| t.end_step(system, x)).sum()
    }

    /// The barrier terms.
    fn barriers(&mut self) -> impl Iterator<Item = &mut Box<dyn Term>> {
        self.list.iter_mut().filter(|t| t.is_barrier())
    }
}

/// Checks a residual `b`.
///
/// # Errors
/// [`StepError::NonFiniteSystem`] at `time` naming the first free particle
/// whose residual is not finite.
pub(crate) fn check_finite(system: &System, b: &[Vec3], time: f64) -> Result<(), StepError> {
    let bad = (0..b.len()).find(|&i| !system.is_pinned(i) && !b[i].iter().all(|c| c.is_finite()));
    match bad {
        None => Ok(()),
        Some(particle) => Err(StepError::NonFiniteSystem { time, particle }),
    }
}

#[cfg(test)]
mod tests;
