//! Scenes whose surfaces collide: which system each method runs on.
//!
//! Only the implicit methods keep colliding surfaces apart
//! ([`Method::resolves_surface_contact`]); the others refuse a system with
//! surface contact at their first step. When the scene's surfaces collide
//! only within one body (self-collision), the lab runs those methods on the
//! system without self-collision
//! ([`System::without_self_collision`]), where the body may pass through
//! itself, and says so in the report's `note`. When surfaces of different
//! bodies collide, nothing can take that contact away: those methods are
//! not applicable, and their cells say why.

use hooke_core::{StepError, System};

use crate::Method;

/// A system and, when its surfaces collide only within single bodies, the
/// same system without self-collision.
#[derive(Debug, Clone)]
pub(crate) struct Systems {
    full: System,
    /// The system without self-collision, when its surfaces then do not
    /// collide at all.
    reduced: Option<System>,
}

/// What a method runs on.
#[derive(Debug, Clone)]
pub(crate) enum Target<'a> {
    /// This system.
    Runs(&'a System),
    /// Nothing: the method cannot run the scene; the error its first step
    /// returns.
    NotApplicable(String),
}

impl Systems {
    /// `system` and, if its surfaces collide, the same without
    /// self-collision when that leaves no surface contact.
    pub(crate) fn new(system: System) -> Self {
        let reduced = system
            .has_surface_contact()
            .then(|| system.without_self_collision())
            .filter(|s| !s.has_surface_contact());
        Self {
            full: system,
            reduced,
        }
    }

    /// The system `method` runs on, or why it cannot run at all.
    pub(crate) fn target(&self, method: Method) -> Target<'_> {
        if !self.full.has_surface_contact() || method.resolves_surface_contact() {
            return Target::Runs(&self.full);
        }
        match &self.reduced {
            Some(reduced) => Target::Runs(reduced),
            None => Target::NotApplicable(
                StepError::SurfaceContactUnsupported {
                    integrator: method.name(),
                }
                .to_string(),
            ),
        }
    }

    /// The system every method can run: the whole one, or the one without
    /// self-collision; `None` when surfaces of different bodies collide.
    pub(crate) fn common(&self) -> Option<&System> {
        if self.full.has_surface_contact() {
            self.reduced.as_ref()
        } else {
            Some(&self.full)
        }
    }

    /// What the report says of `methods` on this scene, if anything: which
    /// of them ran without self-collision, or cannot run it.
    pub(crate) fn note(&self, methods: &[Method]) -> Option<String> {
        if !self.full.has_surface_contact() {
            return None;
        }
        let refusing: Vec<&str> = methods
            .iter()
            .filter(|m| !m.resolves_surface_contact())
            .map(|m| m.name())
            .collect();
        if refusing.is_empty() {
            return None;
        }
        let names = refusing.join(", ");
        Some(match self.reduced {
            Some(_) => format!(
                "explicit methods run without self-collision: {names} cannot keep surfaces \
                 apart, so they run on the scene with self-collision turned off (its bodies \
                 may pass through themselves)"
            ),
            None => format!(
                "surfaces of different bodies collide: {names} cannot keep surfaces apart, \
                 even without self-collision, and are not applicable"
            ),
        })
    }
}
