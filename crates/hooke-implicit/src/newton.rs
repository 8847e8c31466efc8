//! One attempt at an implicit (sub)step: the scheme's coefficients, the
//! linearised solve or Newton's method with its line search, the energy
//! test, and the commit of an accepted step. [`Implicit`]'s docs give the
//! equations.

use hooke_core::{CompressedSprings, State, StepError, StepReport, System, Vec3};

use crate::assembly::Linearization;
use crate::energy::{energy, obstacle_work, pin_work, rounding};
use crate::implicit::{Implicit, Scheme};
use crate::solver::{Solve, topology};
use crate::vector::{dot, for_each_row, for_each_row2};

/// What became of an attempt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// Committed to the state; `easy` when Newton took at most a third of
    /// its cap, so the next substep may be longer.
    Accepted { easy: bool },
    /// Not converged or gaining energy above the floor: the state, the
    /// contacts and the history are as before.
    Rejected,
}

/// How Newton's method ended.
struct Newton {
    converged: bool,
    iterations: usize,
    /// The last step `‖δ‖∞` relative to the step's velocity scale.
    residual: f64,
}

/// The shortest fraction of a Newton step the line search tries.
const MIN_STEP: f64 = 1e-6;

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
        // Variable-step BDF2 with step ratio ω = h/hₙ₋₁:
        // x − (1+ω)²/(1+2ω) xₙ + ω²/(1+2ω) xₙ₋₁ = (1+ω)/(1+2ω) h v; it
        // (re)starts with a backward-Euler step.
        let ratio = previous
            .map(|last| h / last)
            .filter(|&omega| self.scheme == Scheme::Bdf2 && omega <= 2.0 + 1e-9);
        let (beta, current, past) = ratio.map_or((1.0, 1.0, 0.0), |omega| {
            let d = 1.0 + 2.0 * omega;
            (
                (1.0 + omega) / d,
                (1.0 + omega).powi(2) / d,
                omega * omega / d,
            )
        });
        let beta_h = beta * h;
        let masses = system.masses();
        let w = &mut self.work;
        for i in 0..x0.len() {
            w.x_tilde[i] = current * x0[i] - past * w.x_prev[i];
            w.v_tilde[i] = current * v0[i] - past * w.v_prev[i];
            w.u[i] = w.x_tilde[i] - x0[i] + beta_h * v0[i];
            w.inertia[i] = masses[i] * (w.v_tilde[i] - v0[i]);
        }
        if previous.is_none() {
            w.dv.fill(Vec3::zeros());
        }
        self.saved_contacts.clone_from(&self.contacts);

        let (compressed, solver, strict) = (self.compressed, self.solver, self.strict);
        let topology = topology(&mut self.topology, solver, system)?;
        let solve = Solve {
            system,
            solver,
            strict,
            time,
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
            displacement: Some(&w.u),
            inertia: &w.inertia,
            beta_h,
            compressed,
            freeze_directions: true,
        };
        solve.assemble(&mut self.assembler, topology, &lin, &mut w.b)?;
        if constrained {
            contacts.prescribe(topology.matrix(), &mut w.b);
            contacts.add_friction(topology, v0, &mut w.b);
        }
        solve.solve(topology, &w.b, &mut w.dv, &mut w.pcg, report)?;
        let prescribed = &contacts.prescribed;
        let z = |i: usize| {
            if constrained {
                prescribed[i]
            } else {
                Vec3::zeros()
            }
        };
        for_each_row(&mut w.v, |i, v| *v = v0[i] + w.dv[i] + z(i));
        let newton = if self.linearized {
            if constrained {
                let (matrix, filters) = topology.matrix_and_filters_mut();
                contacts.release(matrix, &w.dv, &w.b, filters);
            }
            Newton {
                converged: true,
                iterations: 1,
                residual: 0.0,
            }
        } else {
            // Newton starts where Φ is lower: at the linearised step's
            // velocities or at vₙ with the prescribed velocity changes
            // applied. Every Newton step then lies in the free directions.
            for_each_row2(&mut w.x, &mut w.trial, |i, x, t| {
                *t = v0[i] + z(i);
                *x = w.x_tilde[i] + beta_h * *t;
            });
            let at_start = self.assembler.potential(
                system,
                topology.pattern(),
                &w.x,
                &w.trial,
                &w.v_tilde,
                beta_h,
            );
            for_each_row(&mut w.x, |i, x| *x = w.x_tilde[i] + beta_h * w.v[i]);
            let linearized = self.assembler.potential(
                system,
                topology.pattern(),
                &w.x,
                &w.v,
                &w.v_tilde,
                beta_h,
            );
            if !(linearized < at_start) {
                std::mem::swap(&mut w.v, &mut w.trial);
            }
            let mut newton = Newton {
                converged: false,
                iterations: 0,
                residual: f64::INFINITY,
            };
            for _ in 0..self.newton_iterations {
                for_each_row2(&mut w.x, &mut w.inertia, |i, x, inertia| {
                    *x = w.x_tilde[i] + beta_h * w.v[i];
                    *inertia = -masses[i] * (w.v[i] - w.v_tilde[i]);
                });
                // The exact Hessian where the system it gives is positive
                // definite (quadratic convergence), the clamped one otherwise.
                // The exact Hessian where the system it gives is positive
                // definite (quadratic convergence), the clamped one otherwise.
                let tries: &[CompressedSprings] = match compressed {
                    CompressedSprings::Clamped => {
                        &[CompressedSprings::Exact, CompressedSprings::Clamped]
                    }
                    CompressedSprings::Exact => &[CompressedSprings::Exact],
                };
                for (t, &hessian) in tries.iter().enumerate() {
                    let lin = Linearization {
                        positions: &w.x,
                        velocities: &w.v,
                        displacement: None,
                        inertia: &w.inertia,
                        beta_h,
                        compressed: hessian,
                        freeze_directions: false,
                    };
                    w.delta.fill(Vec3::zeros());
                    let last = t + 1 == tries.len();
                    let solved = solve
                        .assemble(&mut self.assembler, topology, &lin, &mut w.b)
                        .and_then(|()| {
                            if constrained {
                                contacts.add_friction(topology, &w.v, &mut w.b);
                            }
                            solve.solve(topology, &w.b, &mut w.delta, &mut w.pcg, report)
                        });
                    match solved {
                        Err(StepError::NotPositiveDefinite { .. }) if !last => continue,
                        Err(e) => return Err(e),
                        // A direction that does not descend is retried clamped.
                        Ok(()) if !last && dot(&w.b, &w.delta) <= 0.0 => continue,
                        Ok(()) => break,
                    }
                }
                if constrained {
                    let (matrix, filters) = topology.matrix_and_filters_mut();
                    contacts.release(matrix, &w.delta, &w.b, filters);
                }
                newton.iterations += 1;
                let (mut step, mut scale) = (0.0_f64, 0.0_f64);
                for i in 0..w.v.len() {
                    let next = w.v[i] + w.delta[i];
                    step = step.max(w.delta[i].amax());
                    scale = scale.max((next - v0[i]).amax()).max(next.amax());
                }
                newton.residual = if step > 0.0 { step / scale } else { 0.0 };
                if step <= self.newton_tolerance * scale {
                    for_each_row(&mut w.v, |i, v| *v += w.delta[i]);
                    newton.converged = true;
                    break;
                }
                // Backtracking (Armijo) on Φ along δ; the slope is ∇Φ·δ = −bᵀδ.
                let slope = -dot(&w.b, &w.delta);
                let dissipation = |c: &crate::contact::Contacts, v: &[Vec3]| {
                    if constrained { c.dissipation(v) } else { 0.0 }
                };
                let pattern = topology.pattern();
                let start = self
                    .assembler
                    .potential(system, pattern, &w.x, &w.v, &w.v_tilde, beta_h)
                    + dissipation(contacts, &w.v);
                let mut alpha = 1.0;
                let accepted = loop {
                    for_each_row(&mut w.trial, |i, t| *t = w.v[i] + alpha * w.delta[i]);
                    for_each_row(&mut w.x, |i, x| *x = w.x_tilde[i] + beta_h * w.trial[i]);
                    let value = self
                        .assembler
                        .potential(system, pattern, &w.x, &w.trial, &w.v_tilde, beta_h)
                        + dissipation(contacts, &w.trial);
                    if value <= start + 1e-4 * alpha * slope {
                        break true;
                    }
                    alpha *= 0.5;
                    if alpha < MIN_STEP {
                        break false;
                    }
                };
                if !accepted {
                    // Φ cannot decrease: converged if its slope is at the
                    // rounding level of Φ, stalled otherwise.
                    for_each_row(&mut w.x, |i, x| *x = w.x_tilde[i] + beta_h * w.v[i]);
                    let magnitude = energy(system, &w.x, &w.v).1 + start.abs();
                    newton.converged = slope.abs() <= rounding(magnitude);
                    break;
                }
                std::mem::swap(&mut w.v, &mut w.trial);
            }
            newton
        };
        for_each_row(&mut w.x, |i, x| *x = w.x_tilde[i] + beta_h * w.v[i]);

        // The energy test.
        let (before, magnitude_before) = energy(system, x0, v0);
        let (after, magnitude_after) = energy(system, &w.x, &w.v);
        let mut work = pin_work(system, x0, &w.x);
        if constrained && !system.obstacles().is_empty() {
            work += obstacle_work(
                system,
                contacts.held(),
                &w.x,
                &w.v,
                &w.v_tilde,
                beta_h,
                &mut w.trial,
            );
        }
        let excess = after - before - work - rounding(magnitude_before.max(magnitude_after));
        report.newton_iterations += newton.iterations;
        report.newton_iterations_max = report.newton_iterations_max.max(newton.iterations);
        if !self.linearized && !at_floor && (!newton.converged || excess > 0.0) {
            self.contacts.clone_from(&self.saved_contacts);
            self.history = saved_history;
            return Ok(Outcome::Rejected);
        }
        report.newton_residual = report.newton_residual.max(newton.residual);
        if !newton.converged {
            if strict {
                return Err(StepError::NoConvergence {
                    time,
                    iterations: newton.iterations,
                    residual: newton.residual,
                });
            }
            report.unconverged_steps += 1;
        }
        if excess > 0.0 {
            report.energy_excess = report.energy_excess.max(excess);
            if !self.linearized {
                // The last resort: the free particles' kinetic energy
                // absorbs the excess (all of it, if it is large enough).
                let kinetic: f64 = (0..w.v.len())
                    .filter(|&i| !system.is_pinned(i))
                    .map(|i| 0.5 * masses[i] * w.v[i].norm_squared())
                    .sum();
                let factor = if kinetic > 0.0 {
                    ((kinetic - excess).max(0.0) / kinetic).sqrt()
                } else {
                    1.0
                };
                for (i, v) in w.v.iter_mut().enumerate() {
                    if !system.is_pinned(i) {
                        *v *= factor;
                    }
                }
                report.energy_corrections += 1;
            }
        }
        state.commit(&mut w.x, &mut w.v, end.unwrap_or(time + h))?;
        // The buffers swapped out of the state hold xₙ, vₙ: BDF2's next history.
        std::mem::swap(&mut w.x_prev, &mut w.x);
        std::mem::swap(&mut w.v_prev, &mut w.v);
        self.history.record(system, state, h);
        report.accepted_steps += 1;
        report.contacts = system.end_step(state);
        Ok(Outcome::Accepted {
            easy: 3 * newton.iterations <= self.newton_iterations,
        })
    }
}
