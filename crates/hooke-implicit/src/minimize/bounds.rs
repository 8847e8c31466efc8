//! How contact bounds each iterate's motion ([`ContactLimit`]): every
//! particle as far as its own contacts allow, or the whole step as far as
//! the first pair to touch allows.
//!
//! A barrier's `Φ` is infinite where a gap closes, so every motion a
//! minimiser tries is first checked by continuous collision detection
//! (CCD): it keeps every pair at least a tenth of its gap (the contact
//! module's `KEEP`). With one step length `α` for the whole body, the
//! first pair that would touch sets the step of every particle — the "TOI
//! locking" of Zheng, Luo & Li (2025): on the default scene the landing
//! cloth's worst step spent its first 19 Newton iterations at
//! `α = 0.045–0.86`, each finding the next row of particles to meet the
//! sphere. [`ContactLimit::Particles`] cuts each particle's own motion
//! instead (the contact module's `truncate`): a particle whose pairs CCD
//! stops moves as far as they allow, every other particle all the way.
//!
//! **The guarantee.** A particle against an obstacle is the only moving
//! primitive of its pair, so its own fraction keeps the pair's clearance;
//! a point–triangle or edge–edge pair's four fractions are cut, round by
//! round, until CCD stops no pair along the cut motion. The cut motion,
//! and every point `v + α s∘δ`, `α ∈ [0, 1]`, the line search tries on
//! it, keeps every pair at least a tenth of its gap, exactly as a step
//! bounded by the global limit does: no iterate crosses, and `Φ` stays
//! finite.
//!
//! **Newton with bounded steps.** The cut direction `s∘δ` is no longer
//! Newton's, and its slope `∇Φ·(s∘δ) = Σᵢ sᵢ ∇ᵢΦ·δᵢ` need not be negative
//! (the particles cut are the ones pressing into a contact, and the
//! others may owe their share of the decrease to them); on a stiff cloth
//! it mostly is not worth taking either, as the particles stopped and
//! their neighbours moving on stretch the springs between them. The cut
//! step is taken only where it descends and its whole length meets the
//! Armijo condition `Φ(v + s∘δ) ≤ Φ(v) + c ∇Φ·(s∘δ)` (that `Φ` then
//! serves the line search, which may extend it); otherwise the iteration
//! falls back to the global limit along `δ` itself ([`StepReport`]'s
//! `bound_fallbacks` counts these). Backtracking along a cut step that
//! fails at full length took longer than the global limit (on the default
//! scene, 65 Newton iterations in the worst step, at `α` down to
//! 0.002). An iterate whose step was cut is not converged: the stopping
//! rule holds only where the whole Newton step was taken.
//!
//! **The start.** The step's second starting point, the inertial
//! predictor, is cut the same way ([`bound_start`]): each particle as far
//! towards it as its own contacts allow, so that the step starts already
//! touching what it will touch, and free elsewhere.
//!
//! **Measured** (the default scene, `stiff-cloth`, 210 steps of 1/60 s,
//! both limits in one build): 4.58 Newton iterations a step on average
//! against 4.95, the worst step 41 against 41, 0.96–0.98 of the global
//! limit's CPU time (farm-bench, 3 pairs alternated, two runs; the
//! benches' README has the table); the worst step's first phase
//! — iterations cut short by collision detection — falls from 19
//! iterations to 7, while its second, about 30 nearly full Newton steps
//! converging linearly as the landing front buckles, stays. The cut step
//! passes the Armijo test in few iterations (0.15 particles cut an
//! iteration on average, 45 fallbacks in the run): most of the gain is
//! the cut start. On the scenes where surfaces meet it is a loss:
//! `cloth-pile` 9.72 iterations a step against 7.87 (145 fallbacks, 1.45
//! times the CPU time), `two-cloths` 7.66 against 7.05 and a worst step of
//! 64 against 46 (1.17 times). The
//! cut step fails for the reason Newton's step needed cutting: the
//! direction was solved without the contacts it runs into, and holding
//! the stopped particles while the rest of a stiff cloth moves on
//! stretches the springs between them. Solving the Newton system again
//! with the stopped particles held (PCG on the constrained matrix,
//! preconditioned by the step's factor, up to four rounds as the cut
//! grows) left the default scene at 4.95 iterations a step and 44 in the
//! worst: the global limit stays the default.
//!
//! **Where the landing steps' iterations go.** The three costliest steps
//! of the default scene (t = 0.283, 0.3 and 0.317 s) are the cloth's
//! hanging sides reaching the floor: in the worst, the particles within
//! 1 cm of the floor go from 5 to 236 over its iterations, and 99 % of
//! each direction's `‖δ‖²` lies away from the sphere. Every one of its
//! directions is solved with compressed springs clamped (the exact
//! Hessian is indefinite), `Φ` falls 1.2–1.7 times what the model
//! predicts along its full steps, and successive directions point the
//! same way (cosine 0.88–0.998). Per-particle bounds move iterations from
//! the first phase to the second rather than remove them: those three
//! steps take 34, 40 and 34 iterations against 40, 38 and 32 under the
//! global limit. On this stiff sheet what remains is Newton's method on a
//! sheet that buckles as it lands. On a softer one contact is the cost:
//! with the stretch and shear springs 100 times softer the same step
//! spends 24 of its 26 iterations cut short by collision detection (two
//! full steps after), and per-particle bounds take the first simulated
//! second from 11.35 Newton iterations a step to 9.07 (worst 41 to 30,
//! stepping 5.78 s to 4.97 s; one run each). The worst step of that
//! second stays at 41–70 iterations for stretch and shear scaled by
//! 0.01–10, without friction (46) and with the bending 100 times softer
//! (45).
//!
//! **What the second phase's model misses.** Split term by term along
//! each full step of that worst step's second phase (iterations 20–39),
//! the model `∇Φ·δ + ½ δᵀAδ` predicts the inertia's, gravity's and the
//! air damping's change to three digits and the contact's, a tenth of
//! the springs', within about a third; the springs' excess is the
//! compressed ones': about 1 900 of the 3 042 shear springs and 720 of
//! the 3 120 stretch springs are shorter than at rest, and the
//! compressed shear springs fall 1.6–10 times what their clamped model
//! predicts (twice at most iterations), the compressed stretch springs
//! fall where it has them rise, while the stretched ones fall at most
//! 1.4 times the prediction. The clamp drops their negative transverse
//! stiffness `k(1 − L/l)`, so the model is stiffer than `Φ` across every
//! compressed spring, and the step is too short in the directions that
//! relieve the compression; the exact Hessian is indefinite there, and none of the models tried (a
//! fraction of the negative stiffness, a shift, a trust region on the
//! exact Hessian, secant corrections: `benches/README.md`) steps further
//! along them without being cut back. Neither did two variants measured
//! with this split: stretch and shear springs that resist no compression
//! at all (a different material) make the run worse, 6.39 iterations a
//! step and 61 at most (the sheet folds more and touches more); and a
//! full step extended as far as collision detection allows when the
//! doubling to `α = 2` is cut (`Φ` along these directions is lowest
//! around `α` = 1.5, with a particle through the floor by `α` = 2–3)
//! gives 4.82 a step and the same 41 at most. The same holds for the
//! sheet with every spring 100 times stiffer at `h` = 0.1 s (33.8
//! iterations a step): its costly steps, 23–97 iterations each between
//! t = 0.1 and 1 s, are cut short by collision detection in 14–26 % of
//! their iterations up to t = 0.2 s and in at most 4 % after.

use hooke_core::{Named, Potential, StepReport, System, Vec3};

use crate::linear::vector::for_each_row;
use crate::minimize::descent::Descent;
use crate::minimize::line_search::{ARMIJO, Iterates};
use crate::minimize::objective::Objective;
use crate::minimize::terms::Terms;

/// How contact bounds each iterate's motion in an implicit step with
/// barriers (the `bounds` module).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactLimit {
    /// Each particle moves as far as its own contacts allow (per-particle
    /// bounds) where that lowers `Φ` enough, the global limit otherwise: a
    /// body landing on an obstacle stops where it touches and moves on
    /// elsewhere. Fewer Newton iterations on the default scene (4.58 a step
    /// against 4.95), more on the cloth pile and the two cloths (the module
    /// docs).
    Particles,
    /// The whole step moves as far as the first pair to touch allows (one
    /// step length from the earliest time of impact). The default: it took
    /// as long or less on every contact scene measured.
    #[default]
    Global,
}

impl Named for ContactLimit {
    /// `"particles"` and `"global"`, as scene files (`contact_limit`) and
    /// reports spell them.
    const TABLE: &'static [(Self, &'static str)] =
        &[(Self::Particles, "particles"), (Self::Global, "global")];
}

/// The bound on a direction ([`bound`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Bound {
    /// The longest fraction of the (possibly cut) step the line search may
    /// take.
    pub(crate) limit: f64,
    /// The slope `∇Φ·δ` of the step the line search takes.
    pub(crate) slope: f64,
    /// Whether particles' motions were cut: the iterate cannot stop there.
    pub(crate) truncated: bool,
    /// `Φ` at the end of the cut step, where it was evaluated.
    pub(crate) full: Option<Potential>,
}

/// What the bounds did in one minimisation, for the step's report: the
/// integrator's [`ContactLimit`], the particles cut (summed over the
/// iterations, and the most in one) and the iterations that fell back to
/// the global limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Bounds {
    pub(crate) limit: ContactLimit,
    pub(crate) truncated: usize,
    pub(crate) truncated_max: usize,
    pub(crate) fallbacks: usize,
}

impl Bounds {
    /// Bounds under `limit`, nothing counted yet.
    pub(crate) fn new(limit: ContactLimit) -> Self {
        Self {
            limit,
            ..Self::default()
        }
    }

    /// Adds the counts to `report`.
    pub(crate) fn report(&self, report: &mut StepReport) {
        report.truncated_particles += self.truncated;
        report.truncated_particles_max = report.truncated_particles_max.max(self.truncated_max);
        report.bound_fallbacks += self.fallbacks;
    }
}

/// Bounds the direction `δ` (in `it.delta`) from `it.v`, whose slope is
/// `slope` and where `Φ` is `current`, as the objective's
/// [`ContactLimit`] says: without barriers the whole step; under
/// [`ContactLimit::Global`] the fraction of it collision detection allows;
/// under [`ContactLimit::Particles`], each particle's motion cut to what
/// its contacts allow (`δ` becomes `s∘δ`) where the whole cut step meets
/// the Armijo condition `Φ(v + s∘δ) ≤ Φ(v) + c ∇Φ·(s∘δ)` — its `Φ` then
/// goes with the bound, for the line search to reuse — and otherwise the
/// global fraction of `δ` (the module docs).
pub(crate) fn bound<D: Descent>(
    descent: &mut D,
    phi: &mut Objective<'_>,
    it: &mut Iterates,
    slope: f64,
    current: f64,
) -> Bound {
    let whole = Bound {
        limit: 1.0,
        slope,
        truncated: false,
        full: None,
    };
    if phi.bounds.limit == ContactLimit::Global || !phi.terms.has_barrier() {
        return Bound {
            limit: phi.limit(&it.v, &it.delta, 1.0),
            ..whole
        };
    }
    phi.positions(&it.v);
    let beta_h = phi.beta_h;
    let delta = &it.delta;
    for_each_row(phi.motion, |i, m| *m = beta_h * delta[i]);
    let scale = phi.terms.truncate(phi.system, phi.x, phi.motion);
    let truncated = scale.iter().filter(|&&s| s < 1.0).count();
    if truncated == 0 {
        return whole;
    }
    for_each_row(&mut it.look, |i, c| *c = scale[i] * delta[i]);
    let cut_slope = descent.slope(&it.look);
    if cut_slope < 0.0 {
        let (v, cut) = (&it.v, &it.look);
        for_each_row(&mut it.trial, |i, t| *t = v[i] + cut[i]);
        let full = descent.value(phi, &it.trial);
        if full.value <= current + ARMIJO * cut_slope {
            std::mem::swap(&mut it.delta, &mut it.look);
            phi.bounds.truncated += truncated;
            phi.bounds.truncated_max = phi.bounds.truncated_max.max(truncated);
            return Bound {
                slope: cut_slope,
                truncated: true,
                full: Some(full),
                ..whole
            };
        }
        descent.discard();
    }
    phi.bounds.fallbacks += 1;
    Bound {
        limit: phi.limit(&it.v, &it.delta, 1.0),
        ..whole
    }
}

/// The second starting point of a step with barriers, `trial = v + t`
/// (the inertial predictor, `t` its change from the feasible start `v`),
/// bounded as `limit` says: `v + τ t` with the fraction `τ` of the motion
/// `βh t` from the start's positions `x` that collision detection allows,
/// or `v + s∘t`, each particle as far as its own contacts allow — a start
/// already touching what the step will touch, and free elsewhere.
pub(crate) fn bound_start(
    terms: &mut Terms,
    system: &System,
    limit: ContactLimit,
    (x, motion): (&[Vec3], &[Vec3]),
    (v, trial): (&[Vec3], &mut [Vec3]),
) {
    match limit {
        ContactLimit::Global => {
            let tau = terms.limit(system, x, motion);
            for_each_row(trial, |i, t| *t = v[i] + tau * *t);
        }
        ContactLimit::Particles => {
            let scale = terms.truncate(system, x, motion);
            for_each_row(trial, |i, t| *t = v[i] + scale[i] * *t);
        }
    }
}
