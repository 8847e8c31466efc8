//! One finite-difference property test over every term of `Φ`.
//!
//! For random small systems at random states (the `cases` module), each
//! term of [`Terms::new`] — whichever terms the list holds, a system's own
//! among them — is set up as a step sets it up: [`Terms::begin`] at the
//! step's start `(xₙ, vₙ)`, then [`Terms::limit`] along the motion from the
//! feasible start to the point checked, `v` with `x = x̃ + βh v`,
//! `x̃ = xₙ`. At that point, with the lagged data fixed (friction's normal
//! forces and bases, the pair lists, the dampers' directions):
//!
//! - the gradient it gives (`b −= ∇Φ_term`, by [`Term::add`] with either
//!   Hessian and by [`Term::gradient`], whose value is [`Term::value`]'s)
//!   is the central differences of its value;
//! - the Hessian it writes with [`CompressedSprings::Exact`] is the
//!   central differences of its gradient. A barrier writes each pair's
//!   positive part in either mode: its Hessian is split by the powers of
//!   `βh` into the inertia's, the dissipation potentials' (friction) and
//!   the potentials' parts (`M`, `βh C`, `β²h² K`; see
//!   [`hooke_core::term`]), the first two exact and the barriers' compared
//!   as the case's [`Curvature`](cases::Curvature) says;
//! - after a failed full step ([`Term::full_step_failed`]), each part of
//!   the Hessian it writes is at least the exact one (friction's
//!   majorizing model);
//! - the Hessian it writes with [`CompressedSprings::Clamped`] is positive
//!   semidefinite;
//! - at Baraff & Witkin's linearisation with a displacement `u`, its
//!   right-hand side gains `−βh K u`, `β²h² K` the potentials' part of the
//!   Hessian it writes there (barriers, which a step never linearises,
//!   left out).
//!
//! A central difference in the velocities is taken by the chain rule
//! through `x = x̃ + βh v`, `∂/∂v = βh ∂/∂x + ∂/∂v` at fixed `x̃`, each
//! partial derivative a central difference in its own variable: the
//! positions step a fraction [`STEP`] of the shortest length over which
//! the case's terms change (its pair's gap), and at least [`FLOOR`] of the
//! largest coordinate, so that the rounding of the coordinates stays
//! below a ten-millionth of a difference (more for nearly parallel edges,
//! whose common normal the rounding turns by `ε / sin θ`: the tolerances
//! allow for it); the velocities step [`STEP`] of the friction's sticking
//! speed. The tolerances are relative to the largest entry of what is
//! compared, plus the rounding of the values differenced.

mod cases;
mod checks;
mod contacts;
mod dense;
mod kinds;
mod own_terms;
mod point;

use std::fmt;

use hooke_core::{StepStart, Vec3};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

use super::Terms;
use cases::Case;
use checks::{definite, gradient, hessian, linearisation};
use kinds::{CONTACTS, Contact, Draws, FRICTIONS, Friction};
use point::Point;

/// A central difference's step, as a fraction of the length or speed
/// over which the terms change: its truncation error is about `STEP²`
/// relative.
const STEP: f64 = 1e-4;

/// The least step in the positions, as a fraction of the largest
/// coordinate: the rounding of a coordinate then moves a difference by
/// at most `ε / FLOOR ≈ 10⁻⁷` of itself.
const FLOOR: f64 = 2e-9;

/// The number of random draws each case takes its parameters from: more
/// than a case needs (it would take them again from the first).
const DRAWS: usize = 200;

/// The draws of every case. A failure's report shows their number alone:
/// its message names the case and its parameters, and proptest keeps the
/// seed that draws them again.
#[derive(Clone)]
struct Sample(Vec<Vec<f64>>);

impl fmt::Debug for Sample {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} cases' random draws", self.0.len())
    }
}

/// Every check on every term of `case`'s `Φ`.
fn check(case: &Case) -> Result<(), TestCaseError> {
    let system = &case.system;
    let fail = |message: String| TestCaseError::fail(format!("{}:\n{message}", case.label));
    let mut terms = Terms::new(system).expect("a small system");
    let beta_h = case.beta * case.h;
    let mut state = system.initial_state();
    state.positions_mut().copy_from_slice(&case.x0);
    state.velocities_mut().copy_from_slice(&case.v0);
    if terms.push_out(system, &mut state) > 0 {
        return Err(fail("a particle starts inside an obstacle".to_owned()));
    }
    let step = StepStart {
        x: &case.x0,
        v: &case.v0,
        time: 0.0,
        h: case.h,
        beta_h,
    };
    terms.begin(system, &step);
    // The point, reached from the step's feasible start as a line search
    // reaches its points.
    let x: Vec<Vec3> = (case.x0.iter().zip(&case.v))
        .map(|(x, v)| x + beta_h * v)
        .collect();
    let start = terms.start().unwrap_or(&case.x0).to_vec();
    let motion: Vec<Vec3> = x.iter().zip(&start).map(|(x, s)| x - s).collect();
    let tau = terms.limit(system, &start, &motion);
    if tau < 1.0 {
        return Err(fail(format!("the motion to the point is cut to {tau}")));
    }
    let reach = x.iter().map(|x| x.amax()).fold(0.0, f64::max);
    let dx = (STEP * case.length).max(FLOOR * reach);
    let point = Point {
        case,
        x,
        beta_h,
        dx,
        dv: STEP * case.speed,
        coordinate_rounding: 4.0 * f64::EPSILON * (reach + case.lever) / dx,
    };
    let mut reached = [0.0; 2];
    for term in &mut terms.list {
        let term = term.as_mut();
        let name = term.name();
        let named = |message: String| fail(format!("{name}: {message}"));
        gradient(term, &point).map_err(named)?;
        definite(term, &point).map_err(named)?;
        if !term.is_barrier() {
            linearisation(term, &point).map_err(named)?;
        }
        let parts = hessian(term, &point).map_err(named)?;
        reached = [0, 1].map(|k| reached[k] + parts[k]);
    }
    // The checks saw what the case meant to show them.
    let near = case.contact != Contact::Far;
    let rubbing = near && case.friction != Friction::None;
    let present = |part: f64| part > 1e-9;
    if present(reached[0]) != rubbing || present(reached[1]) != near {
        return Err(fail(format!(
            "the barriers' Hessian has parts in βh and β²h² of {:.1e} and {:.1e} of its size, \
             where the case has {} pair within reach{}",
            reached[0],
            reached[1],
            if near { "a" } else { "no" },
            if rubbing { ", with friction" } else { "" }
        )));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 8,
        max_shrink_iters: 64,
        ..ProptestConfig::default()
    })]

    /// Every term of `Φ` against the central differences of its value and
    /// gradient, in every contact configuration and friction regime (see
    /// the module docs).
    #[test]
    fn every_term_matches_finite_differences(
        sample in prop::collection::vec(
            prop::collection::vec(0.0..1.0f64, DRAWS),
            CONTACTS.len() * FRICTIONS.len(),
        ).prop_map(Sample)
    ) {
        let mut configurations = CONTACTS
            .iter()
            .flat_map(|&contact| FRICTIONS.iter().map(move |&friction| (contact, friction)));
        for (draws, (contact, friction)) in sample.0.iter().zip(&mut configurations) {
            let case = Case::new(contact, friction, &mut Draws::new(draws));
            check(&case)?;
        }
    }
}
