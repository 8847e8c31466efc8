//! One attempt at an implicit (sub)step, as the list of its stages: the
//! predictor, the linear solver's topology, the pins, the start of the
//! terms (contact's pairs, the dampers' directions), the starting
//! candidates (Baraff & Witkin's linearised solve among them), the
//! minimisation, the energy test, the error estimate, and the commit of
//! an accepted step. [`Implicit`]'s docs give the equations.

use hooke_core::{State, StepError, StepReport, StepStart, System, Vec3};

use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::{Topology, topology};
use crate::linear::vector::for_each_row;
use crate::minimize::bounds::Bounds;
use crate::minimize::line_search::Outcome as Minimized;
use crate::minimize::minimizer::{Kept, Rules, Start};
use crate::minimize::newton::Linear;
use crate::minimize::objective::Objective;
use crate::minimize::terms::Terms;
use crate::step::energy::EnergyTest;
use crate::step::implicit::Implicit;
use crate::step::predictor::{Coefficients, Predictor};
use crate::step::settings::ImplicitSettings;
use crate::step::start::candidates;
use crate::step::work::Work;

/// What became of an attempt; `error` is the estimated local error and the
/// order of the estimate, where error control is on and the history allows
/// an estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Outcome {
    /// Committed to the state; `easy` when the minimisation took at most a
    /// third of its cap, so the next substep may be longer.
    Accepted {
        easy: bool,
        error: Option<(f64, u32)>,
    },
    /// Not converged, gaining energy or above the error tolerance, above
    /// the floor: the state, the contacts and the history are as before.
    Rejected { error: Option<(f64, u32)> },
}

impl Implicit {
    /// Attempts a step of `h` from `state`, ending at `end` (or `t + h`).
    /// `at_floor` accepts the step whatever its convergence and energy (the
    /// last resort then applies).
    ///
    /// # Errors
    /// Assembly and solver errors; [`StepError::NoConvergence`] in strict
    /// mode for a step accepted at the floor without converging.
    pub(crate) fn attempt(
        &mut self,
        system: &System,
        state: &mut State,
        h: f64,
        end: Option<f64>,
        at_floor: bool,
        report: &mut StepReport,
    ) -> Result<Outcome, StepError> {
        let (settings, saved_history) = (self.settings, self.history);
        let previous = self.history.take(system, state);
        let c = Coefficients::new(settings.scheme, h, previous);
        let step = StepStart {
            x: state.positions(),
            v: state.velocities(),
            time: state.time(),
            h,
            beta_h: c.beta * h,
        };
        let work = &mut self.work;
        work.predict(&step, c, previous.is_some());
        let terms = Terms::of(&mut self.terms, system)?;
        let topology = topology_for(&mut self.topology, &settings, (system, terms))?;
        let pinned = self.pins.begin(system, step.v, step.time, h);
        terms.begin(system, &step);
        let start = candidates(
            &settings,
            (system, terms),
            &step,
            (&mut self.pins, pinned),
            topology,
            work,
            report,
        )?;
        let outcome = minimize(
            (&settings, &mut self.kept),
            (system, terms),
            (&step, start),
            topology,
            work,
            report,
        )?;
        let two_step = c.past > 0.0;
        let converges = settings.minimizer.converges();
        let energy = EnergyTest::new(
            (system, terms),
            &step,
            (&work.x, &work.iterates.v),
            converges && !two_step,
            (outcome.converged, settings.newton_tolerance),
        );
        report.newton_iterations += outcome.iterations;
        report.newton_iterations_max = report.newton_iterations_max.max(outcome.iterations);
        let error = settings.error_control.and_then(|control| {
            let past = [
                (&work.x_prev[..], previous),
                (&work.x_earlier[..], self.earlier),
            ];
            control.estimate(two_step, h, (step.x, &work.x), past)
        });
        let too_large = error.is_some_and(|(err, _)| err > 1.0);
        if converges && !at_floor && (!outcome.converged || energy.fails() || too_large) {
            self.history = saved_history;
            return Ok(Outcome::Rejected { error });
        }
        let strict = settings.strict.then_some(step.time);
        account(
            system,
            (outcome, energy),
            strict,
            &mut work.iterates.v,
            report,
        )?;
        let touching = terms.end_step(system, &work.x);
        self.commit(system, state, (h, end, previous), report)?;
        // The pairs within the contact distance, and the particles the end
        // of the step pushes out of an obstacle (none, as no iterate
        // crosses one).
        report.contacts = touching + system.end_step(state);
        Ok(Outcome::Accepted {
            easy: 3 * outcome.iterations <= settings.newton_iterations,
            error,
        })
    }

    /// Commits an accepted step of `h` (after one of `previous`) to
    /// `state` at `end` (or `t + h`): the step's end from the work buffers,
    /// the history moved on for BDF2 and the error estimates.
    ///
    /// # Errors
    /// [`StepError`] from [`State::commit`] for a step that is not finite.
    fn commit(
        &mut self,
        system: &System,
        state: &mut State,
        (h, end, previous): (f64, Option<f64>, Option<f64>),
        report: &mut StepReport,
    ) -> Result<(), StepError> {
        let work = &mut self.work;
        let (x, v) = (&mut work.x, &mut work.iterates.v);
        state.commit(x, v, end.unwrap_or(state.time() + h))?;
        // The buffers swapped out of the state hold xₙ, vₙ: BDF2's next
        // history, after xₙ₋₁ moves to the error estimate's.
        if previous.is_some() {
            std::mem::swap(&mut work.x_earlier, &mut work.x_prev);
        }
        self.earlier = previous;
        std::mem::swap(&mut work.x_prev, x);
        std::mem::swap(&mut work.v_prev, v);
        self.history.record(system, state, h);
        report.accepted_steps += 1;
        Ok(())
    }
}

/// Accounts an accepted step in `report`: the minimisation's residual, a
/// step accepted unconverged (an error in strict mode, `strict` holding
/// the step's time), and
/// a gain in energy, which the kinetic energy absorbs where the step is
/// held to the energy test — within the stopping rule's tolerance, or at
/// the floor as the last resort (all of the kinetic energy, if the gain is
/// as large) — by scaling the free particles' velocities `v`.
///
/// # Errors
/// [`StepError::NoConvergence`] in strict mode for a step that did not
/// converge.
fn account(
    system: &System,
    (outcome, energy): (Minimized, EnergyTest),
    strict: Option<f64>,
    v: &mut [Vec3],
    report: &mut StepReport,
) -> Result<(), StepError> {
    report.newton_residual = report.newton_residual.max(outcome.residual);
    if !outcome.converged {
        if let Some(time) = strict {
            return Err(StepError::NoConvergence {
                time,
                iterations: outcome.iterations,
                residual: outcome.residual,
            });
        }
        report.unconverged_steps += 1;
    }
    if energy.excess > 0.0 {
        report.energy_excess = report.energy_excess.max(energy.excess);
        if energy.held {
            for_each_row(v, |i, v| {
                if !system.is_pinned(i) {
                    *v *= energy.factor;
                }
            });
            if !energy.within_tolerance {
                report.energy_corrections += 1;
            }
        }
    }
    Ok(())
}

/// The linear solver's topology for `system` under `settings`
/// ([`topology`]): the solver's matrix, filters and factor or hierarchy
/// for a minimiser that assembles Newton's matrix, the springs' pattern
/// alone for one that does not.
///
/// # Errors
/// [`StepError::SystemTooLarge`] and factorization errors.
fn topology_for<'t>(
    cached: &'t mut Option<Topology>,
    settings: &ImplicitSettings,
    (system, terms): (&System, &Terms),
) -> Result<&'t mut Topology, StepError> {
    let solver = settings.minimizer.assembles().then_some(settings.solver);
    let factoring = (settings.weak_springs_used(), settings.supernodes);
    topology(
        cached,
        solver,
        (settings.amg_renewal, factoring),
        (system, terms.pattern()),
    )
}

/// Minimises the (sub)step's `Φ` from its starting candidates `start` by
/// the minimiser the settings name
/// ([`Minimizer::minimize`](crate::Minimizer::minimize)), with the
/// step's linear solver on `topology`, and leaves the step's end
/// `x = x̃ + βh v` in the work's positions, `v` in its iterate.
///
/// # Errors
/// Assembly, factorization and solver errors.
fn minimize(
    (settings, kept): (&ImplicitSettings, &mut Kept),
    (system, terms): (&System, &mut Terms),
    (step, start): (&StepStart<'_>, Start),
    topology: &mut Topology,
    work: &mut Work,
    report: &mut StepReport,
) -> Result<Minimized, StepError> {
    let linear = Linear {
        solve: Solve::new(system, settings.strict, step.time),
        topology,
        pcg: &mut work.pcg,
        b: &mut work.b,
        report,
    };
    let Predictor {
        x_tilde,
        v_tilde,
        u,
    } = &mut work.predictor;
    // The displacement `u` served the linearised solve only: its buffer
    // is the minimisation's motion scratch.
    let mut phi = Objective {
        system,
        terms,
        x_tilde,
        v_tilde,
        beta_h: step.beta_h,
        compressed: settings.compressed,
        x: &mut work.x,
        motion: u,
        bounds: Bounds::new(settings.contact_limit),
    };
    let rules = Rules {
        iterations: settings.newton_iterations,
        tolerance: settings.newton_tolerance,
        inexact: settings.inexact_newton,
        solver: settings.solver,
        weak_springs: settings.weak_springs_used(),
    };
    let it = &mut work.iterates;
    let outcome =
        settings
            .minimizer
            .minimize(rules, kept, &mut phi, linear, it, (step.v, start))?;
    phi.bounds.report(report);
    let (v, beta_h) = (&it.v, step.beta_h);
    for_each_row(&mut work.x, |i, x| *x = x_tilde[i] + beta_h * v[i]);
    Ok(outcome)
}
