//! The line search and stopping rule that every minimiser shares
//! ([`minimize`]): a [`Descent`]'s directions iterated to convergence, every
//! iterate accepted through the Armijo condition, full steps extended
//! where the model undershoots, collision detection bounding every motion;
//! and the better of two starting points ([`start`]).

use hooke_core::{Potential, StepError, Vec3};

use crate::linear::vector::for_each_row;
use crate::minimize::bounds::bound;
use crate::minimize::descent::Descent;
use crate::minimize::objective::Objective;

/// The sufficient-decrease constant `c` of the Armijo condition
/// `Φ(v + αδ) ≤ Φ(v) + c α ∇Φ·δ`.
pub(crate) const ARMIJO: f64 = 1e-4;

/// The longest multiple of a direction the line search tries.
const MAX_EXTRAPOLATION: f64 = 64.0;

/// The shortest fraction of a direction the line search tries.
const MIN_STEP: f64 = 1e-6;

/// How a minimisation ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Outcome {
    /// Whether the iterate meets the stopping rule.
    pub(crate) converged: bool,
    /// Directions taken (look-ahead steps included): for Newton's method
    /// its linear solves.
    pub(crate) iterations: usize,
    /// The last relative Newton decrement ([`Objective::decrement`]).
    pub(crate) residual: f64,
}

/// The iteration's buffers, one velocity per particle each: the iterate,
/// its step, a trial point, and the look-ahead step and point of the
/// watchdog.
#[derive(Debug, Default)]
pub(crate) struct Iterates {
    pub(crate) v: Vec<Vec3>,
    pub(crate) delta: Vec<Vec3>,
    pub(crate) trial: Vec<Vec3>,
    pub(crate) ahead: Vec<Vec3>,
    pub(crate) look: Vec<Vec3>,
}

/// The starting point of the iteration: `it.v`, or `it.trial` (swapped
/// into `it.v`) if `second` and lower in `Φ`; returns `Φ` there.
fn start<D: Descent>(
    descent: &mut D,
    phi: &mut Objective<'_>,
    it: &mut Iterates,
    second: bool,
) -> Potential {
    let first = descent.value(phi, &it.v);
    if !second {
        return first;
    }
    let second = descent.value(phi, &it.trial);
    if second.value < first.value {
        std::mem::swap(&mut it.v, &mut it.trial);
        second
    } else {
        descent.discard();
        first
    }
}

/// Minimises `Φ` by `descent`'s directions from the better of the
/// starting points in `it.v` and, if `second`, `it.trial` ([`start`]) in
/// at most `max_iterations` directions (for Newton's method, linear
/// solves), `v0` being the step's initial velocity; leaves the last
/// iterate in `it.v`. The iteration stops when the relative Newton decrement
/// ([`Objective::decrement`]) is at most `tolerance`, or when a full
/// step would lower `Φ` by no more than the rounding of `Φ` itself,
/// `½|∇Φ·δ| ≤ rounding(Φ)` (stiff springs, whose forces carry the
/// rounding of their ends' coordinates times `k`, reach that floor
/// first). Where the model does not have `Φ`'s curvature
/// ([`Descent::EXACT_CURVATURE`]: the quasi-Newton step), `λ`, measured in
/// the model's norm, is first scaled by the curvature along `δ`
/// ([`curvature_correction`], one evaluation of `Φ` at the full step,
/// which the line search then reuses).
///
/// Every iterate is accepted through the Armijo condition
/// `Φ(v + αδ) ≤ Φ(v) + 10⁻⁴ α ∇Φ·δ`:
///
/// - a full step that meets it is extended where the model is stiffer
///   than `Φ` and the step undershoots (a clamped compressed spring,
///   the quartic energy of a flat sheet bending, the quasi-Newton
///   step's initial Hessian `kI` per spring, stiff across a spring
///   where `Φ` is soft), if the quadratic through `Φ(v)`, the slope and
///   `Φ(v + δ)` has its minimum `α*` beyond 1.5 or is not convex.
///   Newton's step doubles `α` (up to 64) while `Φ` keeps falling.
///   L-BFGS's undershoots at almost every iteration, by far more (on
///   the 50 × 50 cloth of the `work_precision` bench, `α*` has a median
///   of 3.5 and reaches 9): it tries `α = min(α*, 64)` once and keeps
///   it if `Φ` is lower there, one evaluation where doubling took
///   three, and doubles below `α*` only if not. Collision detection
///   checks each extension's motion from the last point only, which
///   keeps its cost, growing with the motion, to the step that is
///   tried;
/// - a full step that fails it gets the watchdog: one more step
///   from the full step's end, accepted if that point meets the Armijo
///   condition relative to the iterate (Chamberlain, Powell, Lemaréchal &
///   Pedersen, *The watchdog technique*, 1982; Nocedal & Wright,
///   *Numerical Optimization*, §15.6). A stiff spring rotated along a
///   straight line is stretched by `δ²/2L`, which the second step
///   removes, so a rotating stiff body is not held to the steps its
///   stretch allows;
/// - otherwise the step backtracks by halves, and Newton's model of
///   the friction turns to the majorizing one for the rest of the step
///   (see the contact module's `friction`): contacts brought to rest
///   through `s = 0` by the exact model, whose friction force is
///   constant while they slide, are what makes a full step fail where
///   a body lands. A line search that finds no decrease down to
///   `α = 10⁻⁶` ends the iteration unconverged.
///
/// Each direction is taken knowing the last relative decrement
/// ([`Descent::iteration`]), to which Newton's inexact solves tighten.
///
/// # Errors
/// Assembly and solver errors.
pub(crate) fn minimize<D: Descent>(
    descent: &mut D,
    phi: &mut Objective<'_>,
    it: &mut Iterates,
    (v0, second): (&[Vec3], bool),
    (max_iterations, tolerance): (usize, f64),
) -> Result<Outcome, StepError> {
    let mut current = start(descent, phi, it, second);
    // Φ before the last accepted iterate (for the quasi-Newton floor).
    let mut previous = f64::INFINITY;
    let mut outcome = Outcome {
        converged: false,
        iterations: 0,
        residual: f64::INFINITY,
    };
    while outcome.iterations < max_iterations {
        descent.iteration(outcome.residual);
        let slope = descent.direction(phi, &it.v, &mut it.delta)?;
        outcome.iterations += 1;
        outcome.residual = phi.decrement(slope, &it.v, &it.delta, v0);
        // The longest fraction of δ (cut per particle, where it was)
        // collision detection allows.
        let bound = bound(descent, phi, it, slope, current.value);
        let (limit, slope) = (bound.limit, bound.slope);
        // A quasi-Newton step's model overestimates the curvature of
        // soft modes and so its predicted decrease; it is at the floor
        // only once the last iterate lowered Φ by no more than rounding.
        let floor = 0.5 * slope.abs() <= current.rounding()
            && (D::EXACT_CURVATURE || previous - current.value <= current.rounding());
        // The full step's Φ, once the quasi-Newton stopping rule needed it.
        let mut evaluated = bound.full;
        if limit >= 1.0 && !bound.truncated && (outcome.residual <= tolerance || floor) {
            if D::EXACT_CURVATURE || floor || outcome.residual == 0.0 {
                add(&mut it.v, &it.delta);
                outcome.converged = true;
                break;
            }
            combine(&mut it.trial, &it.v, 1.0, &it.delta);
            let full = descent.value(phi, &it.trial);
            outcome.residual *= curvature_correction(current.value, slope, full.value);
            if outcome.residual <= tolerance {
                std::mem::swap(&mut it.v, &mut it.trial);
                outcome.converged = true;
                break;
            }
            evaluated = Some(full);
        }
        previous = current.value;
        let sufficient =
            |value: Potential, alpha: f64| value.value <= current.value + ARMIJO * alpha * slope;
        if limit >= 1.0 {
            let full = evaluated.unwrap_or_else(|| {
                combine(&mut it.trial, &it.v, 1.0, &it.delta);
                descent.value(phi, &it.trial)
            });
            if sufficient(full, 1.0) {
                current = extend(descent, phi, it, current.value, slope, full);
                std::mem::swap(&mut it.v, &mut it.trial);
                continue;
            }
            if outcome.iterations < max_iterations {
                descent.direction(phi, &it.trial, &mut it.ahead)?;
                outcome.iterations += 1;
                if phi.limit(&it.trial, &it.ahead, 1.0) >= 1.0 {
                    combine(&mut it.look, &it.trial, 1.0, &it.ahead);
                    let ahead = descent.value(phi, &it.look);
                    if sufficient(ahead, 1.0) {
                        current = ahead;
                        std::mem::swap(&mut it.v, &mut it.look);
                        continue;
                    }
                }
                // The contact candidates are the look-ahead's: check
                // the step's own motion again for the backtracking.
                phi.limit(&it.v, &it.delta, 1.0);
            }
            phi.terms.full_step_failed();
        }
        let mut alpha = if limit >= 1.0 { 0.5 } else { limit };
        loop {
            combine(&mut it.trial, &it.v, alpha, &it.delta);
            let value = descent.value(phi, &it.trial);
            if sufficient(value, alpha) {
                current = value;
                break;
            }
            alpha *= 0.5;
            if alpha < MIN_STEP {
                return Ok(outcome);
            }
        }
        std::mem::swap(&mut it.v, &mut it.trial);
    }
    Ok(outcome)
}

/// Extends an accepted full step `it.trial = v + δ`, where `Φ` fell
/// from `start` (with slope `∇Φ·δ`) to `full`, as [`minimize`]
/// describes: if the minimum `α*` of the quadratic model lies beyond
/// 1.5 (or the model is not convex), by doublings up to 64 where the
/// model has `Φ`'s curvature (Newton's step), otherwise (the quasi-Newton
/// step) to `α*` (at most 64) and, if `Φ` is not lower there, by
/// doublings below it. Leaves the lowest point tried in
/// `it.trial` and returns `Φ` there.
fn extend<D: Descent>(
    descent: &mut D,
    phi: &mut Objective<'_>,
    it: &mut Iterates,
    start: f64,
    slope: f64,
    full: Potential,
) -> Potential {
    let mut current = full;
    let minimum = model_minimum(start, slope, full.value).map(|m| m.min(MAX_EXTRAPOLATION));
    let doubling_below = match minimum {
        Some(alpha) if alpha <= 1.5 => return current,
        Some(alpha) if !D::EXACT_CURVATURE => {
            if let Some(further) = further(descent, phi, it, alpha, 1.0, current) {
                return further;
            }
            alpha
        }
        _ => 2.0 * MAX_EXTRAPOLATION,
    };
    let mut alpha = 2.0;
    while alpha < doubling_below {
        match further(descent, phi, it, alpha, 0.5 * alpha, current) {
            Some(further) => current = further,
            None => break,
        }
        alpha *= 2.0;
    }
    current
}

/// Tries `v + αδ` beyond the point `it.trial = v + α₀δ` where `Φ` is
/// `current`: if collision detection allows the motion `(α − α₀)δ` from
/// there and `Φ` is lower at `v + αδ`, that point becomes `it.trial`
/// and its `Φ` is returned; otherwise `None`, `it.trial` as it was.
fn further<D: Descent>(
    descent: &mut D,
    phi: &mut Objective<'_>,
    it: &mut Iterates,
    alpha: f64,
    from: f64,
    current: Potential,
) -> Option<Potential> {
    let reach = alpha - from;
    if phi.limit(&it.trial, &it.delta, reach) < reach {
        return None;
    }
    combine(&mut it.look, &it.v, alpha, &it.delta);
    let further = descent.value(phi, &it.look);
    if further.value < current.value {
        std::mem::swap(&mut it.trial, &mut it.look);
        Some(further)
    } else {
        descent.discard();
        None
    }
}

/// Where the quadratic through `Φ(0) = start`, its slope `∇Φ·δ` and
/// `Φ(1) = end` along a step has its minimum, `−slope / 2(end − start −
/// slope)`; `None` where that quadratic is not convex.
fn model_minimum(start: f64, slope: f64, end: f64) -> Option<f64> {
    let curvature = end - start - slope;
    (curvature > 0.0).then(|| -slope / (2.0 * curvature))
}

/// The factor by which a quasi-Newton step's decrement, measured in `H₀`'s
/// norm, underestimates the decrement along its direction `δ`:
/// `√max(1, α*)`, `α*` the minimum of the quadratic through `Φ(0) =
/// start`, the slope `∇Φ·δ` and `Φ(1) = end` ([`model_minimum`]); infinite
/// where that quadratic is not convex.
///
/// `δ = −H∇Φ` makes `λ² = |∇Φ·δ| = δᵀH⁻¹δ`, while `Φ`'s own curvature along
/// `δ` is `δᵀAδ ≈ 2(end − start − slope) = |∇Φ·δ| / α*`, so the decrement
/// of the exact minimisation along `δ`, `(∇Φ·δ)² / δᵀAδ`, is `α* λ²` — a
/// lower bound of Newton's `∇Φᵀ A⁻¹ ∇Φ` (Cauchy–Schwarz in `A`'s norm).
/// Where `H` is far stiffer than `Φ` (a stiff cloth's bending and
/// swinging modes under `H₀`'s `kI` per spring, a large step), `λ` alone
/// reads a body that has barely started to move as converged.
fn curvature_correction(start: f64, slope: f64, end: f64) -> f64 {
    model_minimum(start, slope, end).map_or(f64::INFINITY, |alpha| alpha.max(1.0).sqrt())
}

/// `v += δ`.
fn add(v: &mut [Vec3], delta: &[Vec3]) {
    for_each_row(v, |i, v| *v += delta[i]);
}

/// `out = v + α δ`.
fn combine(out: &mut [Vec3], v: &[Vec3], alpha: f64, delta: &[Vec3]) {
    for_each_row(out, |i, o| *o = v[i] + alpha * delta[i]);
}
