//! One attempt at an implicit (sub)step: the scheme's coefficients, Baraff
//! & Witkin's linearised solve, Newton's method from the better of two
//! starting points, the energy test, and the commit of an accepted step.
//! [`Implicit`]'s docs give the equations.

use hooke_core::{State, StepError, StepReport, System, Vec3};

use crate::assembly::Linearization;
use crate::energy::{energy, obstacle_work, pin_work, rounding};
use crate::implicit::{Implicit, Scheme, Work};
use crate::newton::{self, Iterates, Newton};
use crate::solver::{Solve, topology};
use crate::vector::for_each_row;

/// What became of an attempt; `error` is the estimated local error and the
/// order of the estimate, where error control is on and the history allows
/// an estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Outcome {
    /// Committed to the state; `easy` when Newton took at most a third of
    /// its cap, so the next substep may be longer.
    Accepted {
        easy: bool,
        error: Option<(f64, u32)>,
    },
    /// Not converged, gaining energy or above the error tolerance, above
    /// the floor: the state, the contacts and the history are as before.
    Rejected { error: Option<(f64, u32)> },
}

/// The coefficients of a step of `h` after one of `previous`:
/// `x = x̃ + βh v` and `v = ṽ + βh M⁻¹ f(x, v)` with
/// `x̃ = a xₙ − b xₙ₋₁`, `ṽ = a vₙ − b vₙ₋₁`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Coefficients {
    beta: f64,
    current: f64,
    past: f64,
}

impl Coefficients {
    /// Backward Euler (`β = a = 1`, `b = 0`), or variable-step BDF2 with
    /// step ratio `ω = h/hₙ₋₁ ≤ 2`: `β = (1+ω)/(1+2ω)`,
    /// `a = (1+ω)²/(1+2ω)`, `b = ω²/(1+2ω)` (for `ω = 1` the familiar
    /// `2/3, 4/3, 1/3`). BDF2 (re)starts with a backward-Euler step.
    fn new(scheme: Scheme, h: f64, previous: Option<f64>) -> Self {
        let ratio = previous
            .map(|last| h / last)
            .filter(|&omega| scheme == Scheme::Bdf2 && omega <= 2.0 + 1e-9);
        ratio.map_or(
            Self {
                beta: 1.0,
                current: 1.0,
                past: 0.0,
            },
            |omega| {
                let d = 1.0 + 2.0 * omega;
                Self {
                    beta: (1.0 + omega) / d,
                    current: (1.0 + omega).powi(2) / d,
                    past: omega * omega / d,
                }
            },
        )
    }
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
        let saved_history = self.history;
        let previous = self.history.take(system, state);
        let time = state.time();
        let (x0, v0) = (state.positions(), state.velocities());
        let c = Coefficients::new(self.scheme, h, previous);
        let beta_h = c.beta * h;
        let masses = system.masses();
        let Work {
            b,
            dv,
            delta,
            v,
            x,
            trial,
            ahead,
            look,
            x_tilde,
            v_tilde,
            u,
            inertia,
            x_prev,
            v_prev,
            x_earlier,
            pcg,
            ..
        } = &mut self.work;
        for i in 0..x0.len() {
            x_tilde[i] = c.current * x0[i] - c.past * x_prev[i];
            v_tilde[i] = c.current * v0[i] - c.past * v_prev[i];
            u[i] = x_tilde[i] - x0[i] + beta_h * v0[i];
            inertia[i] = masses[i] * (v_tilde[i] - v0[i]);
        }
        if previous.is_none() {
            dv.fill(Vec3::zeros());
        }
        self.saved_contacts.clone_from(&self.contacts);

        let (compressed, solver, strict) = (self.compressed, self.solver, self.strict);
        let topology = topology(&mut self.topology, solver, self.amg_renewal, system)?;
        let solve = Solve {
            system,
            strict,
            time,
            forcing: 0.0,
        };
        let contacts = &mut self.contacts;
        let constrained = (!system.obstacles().is_empty() || !system.pin_paths().is_empty())
            && contacts.begin(
                system,
                x0,
                v0,
                state.touching(),
                time,
                h,
                self.contact_margin,
                topology.matrix_and_filters_mut().1,
            );
        // Baraff & Witkin's linearised step: the whole step when linearised,
        // otherwise the first candidate for Newton's starting point.
        let lin = Linearization {
            positions: x0,
            velocities: v0,
            displacement: Some(u),
            inertia,
            beta_h,
            compressed,
            freeze_directions: true,
        };
        solve.assemble(&mut self.assembler, topology, &lin, b)?;
        if constrained {
            contacts.prescribe(topology.matrix(), b);
            contacts.add_friction(topology, v0, b);
        }
        solve.solve(topology, x0, b, dv, pcg, report)?;
        let z = |i: usize| {
            if constrained {
                contacts.prescribed[i]
            } else {
                Vec3::zeros()
            }
        };
        for_each_row(v, |i, v| *v = v0[i] + dv[i] + z(i));
        for_each_row(trial, |i, t| *t = v0[i] + z(i));
        if constrained {
            let (matrix, filters) = topology.matrix_and_filters_mut();
            contacts.release(matrix, dv, b, filters);
        }
        let mut newton = Newton {
            system,
            solve,
            topology,
            assembler: &mut self.assembler,
            contacts,
            constrained,
            compressed,
            x_tilde,
            v_tilde,
            beta_h,
            x,
            inertia,
            b,
            pcg,
            report,
            inexact: self.inexact_newton,
        };
        let outcome = if self.linearized {
            newton::Outcome {
                converged: true,
                iterations: 1,
                residual: 0.0,
            }
        } else {
            // Newton starts where Φ is lower: at the linearised step's
            // velocities or at vₙ with the prescribed velocity changes
            // applied. Every Newton step then lies in the free directions.
            let linearized = newton.potential(v);
            let at_start = newton.potential(trial);
            let start = if at_start.value < linearized.value {
                std::mem::swap(v, trial);
                at_start
            } else {
                linearized
            };
            let mut iterates = Iterates {
                v,
                delta,
                trial,
                ahead,
                look,
            };
            let mut outcome = newton.minimize(
                &mut iterates,
                v0,
                start,
                self.newton_iterations,
                self.newton_tolerance,
            )?;
            // Particles the converged step carries into an obstacle are held
            // on its surface and the iteration goes on, until none is.
            while outcome.converged && !system.obstacles().is_empty() {
                newton.positions(iterates.v);
                let held = newton.hold_penetrating((x0, v0), iterates.v, time, h);
                if held == 0 {
                    break;
                }
                let start = newton.potential(iterates.v);
                let more = newton.minimize(
                    &mut iterates,
                    v0,
                    start,
                    self.newton_iterations.saturating_sub(outcome.iterations),
                    self.newton_tolerance,
                )?;
                outcome = newton::Outcome {
                    iterations: outcome.iterations + more.iterations,
                    ..more
                };
            }
            outcome
        };
        let constrained = newton.constrained;
        for_each_row(x, |i, x| *x = x_tilde[i] + beta_h * v[i]);

        // The energy test.
        let (before, magnitude_before) = energy(system, x0, v0);
        let (after, magnitude_after) = energy(system, x, v);
        let two_step = c.past > 0.0;
        let mut work = pin_work(system, x0, x);
        if constrained && !system.obstacles().is_empty() {
            work += obstacle_work(system, self.contacts.held(), x, v, v_tilde, beta_h, trial);
        }
        let excess = after - before - work - rounding(magnitude_before.max(magnitude_after));
        // Converged backward-Euler steps are held to the energy test; BDF2's
        // two-step steps and the linearised step only report a gain.
        let tested = !self.linearized && !two_step;
        report.newton_iterations += outcome.iterations;
        report.newton_iterations_max = report.newton_iterations_max.max(outcome.iterations);
        let error = self.error_control.and_then(|control| {
            let order = if two_step { 2 } else { 1 };
            let earlier = self.earlier.unwrap_or(f64::NAN);
            let past = [(&x_prev[..], previous?), (&x_earlier[..], earlier)];
            let known = if self.earlier.is_some() { 2 } else { 1 };
            control
                .error(two_step, h, (x0, x), &past[..known])
                .map(|err| (err, order))
        });
        let too_large = error.is_some_and(|(err, _)| err > 1.0);
        if !self.linearized
            && !at_floor
            && (!outcome.converged || (tested && excess > 0.0) || too_large)
        {
            self.contacts.clone_from(&self.saved_contacts);
            self.history = saved_history;
            return Ok(Outcome::Rejected { error });
        }
        report.newton_residual = report.newton_residual.max(outcome.residual);
        if !outcome.converged {
            if strict {
                return Err(StepError::NoConvergence {
                    time,
                    iterations: outcome.iterations,
                    residual: outcome.residual,
                });
            }
            report.unconverged_steps += 1;
        }
        if excess > 0.0 {
            report.energy_excess = report.energy_excess.max(excess);
            if tested {
                absorb(system, v, excess);
                report.energy_corrections += 1;
            }
        }
        state.commit(x, v, end.unwrap_or(time + h))?;
        // The buffers swapped out of the state hold xₙ, vₙ: BDF2's next
        // history, after xₙ₋₁ moves to the error estimate's.
        if previous.is_some() {
            std::mem::swap(x_earlier, x_prev);
        }
        self.earlier = previous;
        std::mem::swap(x_prev, x);
        std::mem::swap(v_prev, v);
        self.history.record(system, state, h);
        report.accepted_steps += 1;
        // The particles the step held on obstacles, and those the end of the
        // step pushes out of one.
        report.contacts = self.contacts.held().count() + system.end_step(state);
        Ok(Outcome::Accepted {
            easy: 3 * outcome.iterations <= self.newton_iterations,
            error,
        })
    }
}

/// The last resort for a step that gained `excess` J at the substep floor:
/// the free particles' kinetic energy absorbs it (all of it, if it is
/// large enough), their velocities scaled by one factor.
fn absorb(system: &System, v: &mut [Vec3], excess: f64) {
    let masses = system.masses();
    let kinetic: f64 = (0..v.len())
        .filter(|&i| !system.is_pinned(i))
        .map(|i| 0.5 * masses[i] * v[i].norm_squared())
        .sum();
    let factor = if kinetic > 0.0 {
        ((kinetic - excess).max(0.0) / kinetic).sqrt()
    } else {
        1.0
    };
    for (i, v) in v.iter_mut().enumerate() {
        if !system.is_pinned(i) {
            *v *= factor;
        }
    }
}
