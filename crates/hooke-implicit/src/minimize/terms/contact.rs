//! The contact term of the incremental potential: the barriers of every
//! close pair and their friction, through the `contact` module.
//!
//! Friction stays inside this term: its lagged normal forces
//! `λ = κ|b'(g)|` and tangent bases come from the contact's own pair search
//! and barrier stiffness at the step's start, its work on moving obstacles
//! is part of theirs, and its majorizing model is the contact's answer to a
//! failed full step — a term of its own would read the contact term's state.

use hooke_core::term::TermClone;
use hooke_core::{At, Hessian, Potential, State, StepStart, System, Term, Vec3, When};

use crate::minimize::contact;

/// The contact terms of a system with obstacles or colliding surfaces (see
/// the `contact` module): `κ Σ b(g) + βh Σ D(v)`, a barrier.
#[derive(Debug, Default)]
pub(super) struct Contact {
    contact: contact::Contact,
}

impl Contact {
    /// Whether `system` has contact terms: obstacles or colliding surfaces.
    pub(super) fn present(system: &System) -> bool {
        contact::Contact::present(system)
    }
}

/// A copy starts afresh, as for a new system: its barrier stiffness and
/// pair lists are set up at its first step.
impl TermClone for Contact {
    fn clone_box(&self) -> Box<dyn Term> {
        Box::new(Self::default())
    }
}

impl Term for Contact {
    fn name(&self) -> &'static str {
        "contact"
    }

    /// The obstacles at the step's end, the lagged friction and the
    /// feasible start.
    fn begin(&mut self, system: &System, step: &StepStart<'_>) {
        self.contact.begin(system, step.x, step.time, step.h);
    }

    fn value(&mut self, system: &System, at: &At<'_>) -> Potential {
        let value = self.contact.value(system, at.x, at.v, at.beta_h);
        Potential {
            value,
            magnitude: value.abs(),
        }
    }

    fn add(&mut self, system: &System, at: &At<'_>, b: &mut [Vec3], mut hessian: &mut dyn Hessian) {
        self.contact
            .add(system, at.x, at.v, at.beta_h, b, &mut hessian);
    }

    /// The barriers' energy `κ Σ b(g)`, the obstacles where they are at the
    /// step's `when` end: at the start, as [`Term::begin`] measured it at
    /// the step's start positions (`x` is those; infinite terms of
    /// particles that started inside an obstacle left out), at the end at
    /// `x`. Its magnitude is left out: the energy test's allowance for
    /// rounding stays that of the bodies' own energies.
    fn energy(&mut self, system: &System, x: &[Vec3], _v: &[Vec3], when: When) -> Potential {
        let value = match when {
            When::Start => self.contact.start_energy(),
            When::End => self.contact.barrier_energy(system, x),
        };
        Potential {
            value,
            magnitude: 0.0,
        }
    }

    /// The moving obstacles' work through the barriers and friction.
    fn work(&mut self, system: &System, step: &StepStart<'_>, x: &[Vec3], v: &[Vec3]) -> f64 {
        self.contact
            .obstacle_work(system, (step.x, step.time), x, v)
    }

    /// None: the explicit integrators resolve contact at the end of each
    /// step ([`System::end_step`]).
    fn force(&self, _system: &System, _x: &[Vec3], _v: &[Vec3], _f: &mut [Vec3]) {}

    fn is_barrier(&self) -> bool {
        true
    }

    fn push_out(&mut self, system: &System, state: &mut State) -> usize {
        self.contact.push_out(system, state)
    }

    fn start(&self) -> Option<&[Vec3]> {
        Some(self.contact.start())
    }

    fn limit(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> f64 {
        self.contact.limit(system, x, dx)
    }

    fn truncate(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> Option<&[f64]> {
        Some(self.contact.truncate(system, x, dx))
    }

    fn take_detection(&mut self) -> (usize, f64) {
        self.contact.take_detection()
    }

    fn full_step_failed(&mut self) {
        self.contact.majorize_friction();
    }

    fn end_step(&mut self, system: &System, x: &[Vec3]) -> usize {
        self.contact.end_step(system, x)
    }
}
