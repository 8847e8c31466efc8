//! One attempt at an implicit (sub)step: the scheme's coefficients, the
//! starting candidates (Baraff & Witkin's linearised solve among them),
//! the minimisation by the minimiser the settings name from the better of
//! them, the energy test, and the commit of an accepted step.
//! [`Implicit`]'s docs give the equations.

use hooke_core::{At, State, StepError, StepReport, StepStart, System, Vec3, When};

use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::topology;
use crate::linear::vector::for_each_row;
use crate::minimize::minimizer::{Rules, Start};
use crate::minimize::newton::Linear;
use crate::minimize::objective::{Objective, velocity_scale};
use crate::minimize::terms::Terms;
use crate::step::energy::{absorption, rounding};
use crate::step::implicit::Implicit;
use crate::step::scheme::Scheme;
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
        let settings = self.settings;
        let linearized = !settings.minimizer.converges();
        let previous = self.history.take(system, state);
        let time = state.time();
        let (x0, v0) = (state.positions(), state.velocities());
        let c = Coefficients::new(settings.scheme, h, previous);
        let beta_h = c.beta * h;
        let Work {
            b,
            dv,
            iterates: it,
            x,
            x_tilde,
            v_tilde,
            u,
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
        }
        if previous.is_none() {
            dv.fill(Vec3::zeros());
        }

        let (compressed, strict) = (settings.compressed, settings.strict);
        let terms = Terms::of(&mut self.terms, system)?;
        let topology = topology(
            &mut self.topology,
            settings.minimizer.assembles().then_some(settings.solver),
            (
                settings.amg_renewal,
                (settings.weak_springs_used(), settings.supernodes),
            ),
            (system, terms.pattern()),
        )?;
        let mut linear = Linear {
            solve: Solve::new(system, strict, time),
            topology,
            pcg,
            b,
            report: &mut *report,
        };
        let pinned = self.pins.begin(system, v0, time, h);
        let step = StepStart {
            x: x0,
            v: v0,
            time,
            h,
            beta_h,
        };
        terms.begin(system, &step);
        // The starting candidates: the first in `v`, a second in `trial`
        // (none for a minimiser that assembles no matrix, without
        // barriers). Without barriers, the first is Baraff & Witkin's
        // linearised step; the quasi-Newton step starts from vₙ.
        let start = if let Some(start) = terms.start() {
            // The feasible positions of the step's start and the inertial
            // predictor vₙ + z as far towards it as no pair comes closer
            // than a tenth of its gap.
            let prescribed = &self.pins.prescribed;
            for_each_row(&mut it.v, |i, v| {
                *v = if system.is_pinned(i) {
                    v0[i] + prescribed[i]
                } else {
                    (start[i] - x_tilde[i]) / beta_h
                };
            });
            let (v, ahead) = (&it.v, &mut it.ahead);
            for_each_row(&mut it.trial, |i, t| *t = v0[i] + prescribed[i] - v[i]);
            for_each_row(x, |i, x| *x = x_tilde[i] + beta_h * v[i]);
            let trial = &it.trial;
            for_each_row(ahead, |i, a| *a = beta_h * trial[i]);
            let tau = terms.limit(system, x, ahead);
            for_each_row(&mut it.trial, |i, t| *t = v[i] + tau * *t);
            Start::Feasible
        } else if !settings.minimizer.assembles() {
            let prescribed = &self.pins.prescribed;
            for_each_row(&mut it.v, |i, v| *v = v0[i] + prescribed[i]);
            Start::Current
        } else {
            let at = At {
                x: x0,
                v: v0,
                v_tilde,
                beta_h,
                displacement: Some(u),
                compressed,
            };
            linear.assemble(terms, &at)?;
            if pinned {
                self.pins.prescribe(linear.topology.matrix(), linear.b);
            }
            linear.solve(x0, dv)?;
            let prescribed = &self.pins.prescribed;
            for_each_row(&mut it.v, |i, v| *v = v0[i] + dv[i] + prescribed[i]);
            for_each_row(&mut it.trial, |i, t| *t = v0[i] + prescribed[i]);
            Start::Linearized
        };
        let mut phi = Objective {
            system,
            terms: &mut *terms,
            x_tilde,
            v_tilde,
            beta_h,
            compressed,
            x,
            motion: u,
        };
        let rules = Rules {
            iterations: settings.newton_iterations,
            tolerance: settings.newton_tolerance,
            inexact: settings.inexact_newton,
            solver: settings.solver,
            weak_springs: settings.weak_springs_used(),
        };
        let outcome = settings.minimizer.minimize(
            rules,
            &mut self.kept,
            &mut phi,
            linear,
            it,
            (v0, start),
        )?;
        let v = &mut it.v;
        for_each_row(x, |i, x| *x = x_tilde[i] + beta_h * v[i]);

        // The energy test.
        let before = terms.energy(system, x0, v0, When::Start);
        let after = terms.energy(system, x, v, When::End);
        let two_step = c.past > 0.0;
        let work = terms.work(system, &step, x, v);
        let excess =
            after.value - before.value - work - rounding(before.magnitude.max(after.magnitude));
        // Converged backward-Euler steps are held to the energy test; BDF2's
        // two-step steps and the linearised step only report a gain. A gain
        // that the kinetic energy absorbs by moving the velocities less
        // than the stopping rule's tolerance passes (the `energy` module).
        let tested = !linearized && !two_step;
        let (factor, within_tolerance) = if excess > 0.0 {
            let (factor, shift) = absorption(system, v, excess);
            let scale = velocity_scale(system, v.iter().copied(), v0, beta_h);
            (
                factor,
                outcome.converged && shift <= settings.newton_tolerance * scale,
            )
        } else {
            (1.0, false)
        };
        report.newton_iterations += outcome.iterations;
        report.newton_iterations_max = report.newton_iterations_max.max(outcome.iterations);
        let error = settings.error_control.and_then(|control| {
            let order = if two_step { 2 } else { 1 };
            let earlier = self.earlier.unwrap_or(f64::NAN);
            let past = [(&x_prev[..], previous?), (&x_earlier[..], earlier)];
            let known = if self.earlier.is_some() { 2 } else { 1 };
            control
                .error(two_step, h, (x0, x), &past[..known])
                .map(|err| (err, order))
        });
        let too_large = error.is_some_and(|(err, _)| err > 1.0);
        if !linearized
            && !at_floor
            && (!outcome.converged || (tested && excess > 0.0 && !within_tolerance) || too_large)
        {
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
                // The kinetic energy absorbs the gain: within the Newton
                // tolerance, or at the floor as the last resort (all of
                // the kinetic energy, if the gain is as large).
                for_each_row(v, |i, v| {
                    if !system.is_pinned(i) {
                        *v *= factor;
                    }
                });
                if !within_tolerance {
                    report.energy_corrections += 1;
                }
            }
        }
        let touching = terms.end_step(system, x);
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
        // The pairs within the contact distance, and the particles the end
        // of the step pushes out of an obstacle (none, as no iterate
        // crosses one).
        report.contacts = touching + system.end_step(state);
        Ok(Outcome::Accepted {
            easy: 3 * outcome.iterations <= settings.newton_iterations,
            error,
        })
    }
}
