//! The reference motion the runs are measured against: the closed form of
//! a single oscillator, or a fine classical Runge–Kutta run with a
//! Richardson estimate of its own error.

use std::cmp::Ordering;
use std::ops::ControlFlow;

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use hooke_core::reference::Oscillator;
use hooke_core::{ObserveFn, Path, Simulation, State, StepInfo, System, Vec3};
use hooke_scenes::ExplicitMethod;

use crate::LabError;
use crate::{Method, Settings};

/// Relative size below which a component across the axis counts as zero.
const ACROSS: f64 = 1e-12;

/// A scene that is one bob on one spring to a fixed anchor, moving along
/// the spring's axis: its motion in closed form.
///
/// With `e` the unit vector from the anchor to the bob at `t = 0` and
/// `x(t)` the bob's distance from the anchor along `e`, a spring of
/// stiffness `k`, rest length `L` and damping `c` and gravity `g` give, as
/// long as the bob stays on the anchor's side (`x > 0`, always true for
/// `L = 0`, whose force `−k x e` is linear everywhere),
///
/// ```text
/// m x'' = −k (x − L) − c x' + m g·e.
/// ```
///
/// About the equilibrium `x* = L + m (g·e)/k` the displacement
/// `u = x − x*` obeys `m u'' + c u' + k u = 0` with `u(0) = x(0) − x*`,
/// `u'(0) = v(0)·e`, which [`Oscillator::solution`] solves. Since
/// `½ m u'² + ½ k u²` never grows (its rate is `−c u'²`),
/// `|u| ≤ A = √(u(0)² + m u'(0)²/k)`, so `x* > A` guarantees `x > 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialOscillator {
    /// The anchor's index.
    pub anchor: usize,
    /// The bob's index.
    pub bob: usize,
    /// The anchor's position, m.
    pub origin: Vec3,
    /// The unit vector `e` from the anchor to the bob at `t = 0`.
    pub axis: Vec3,
    /// The equilibrium distance `x*` along the axis, m.
    pub equilibrium: f64,
    /// The displacement's equation and initial conditions.
    pub oscillator: Oscillator,
}

impl AxialOscillator {
    /// The closed form of `system` if it is such an oscillator: two
    /// particles, the anchor pinned at rest without a scripted path, one
    /// spring of positive stiffness between them, no obstacles, no air
    /// damping, gravity and the bob's initial velocity along the axis (up
    /// to a relative 10⁻¹²), and `x* > A` for a spring of positive rest
    /// length.
    #[must_use]
    pub fn of(system: &System) -> Option<Self> {
        let [spring] = system.springs() else {
            return None;
        };
        let anchor_pinned = |a: usize, b: usize| system.is_pinned(a) && !system.is_pinned(b);
        let (anchor, bob) = if anchor_pinned(spring.i, spring.j) {
            (spring.i, spring.j)
        } else if anchor_pinned(spring.j, spring.i) {
            (spring.j, spring.i)
        } else {
            return None;
        };
        let scripted = system
            .pin_paths()
            .iter()
            .any(|(_, path)| !matches!(path, Path::Fixed));
        let x = system.initial_positions();
        let v = system.initial_velocities();
        if system.particle_count() != 2
            || scripted
            || !system.obstacles().is_empty()
            || system.air_damping().is_some_and(|gamma| gamma != 0.0)
            || v[anchor] != Vec3::zeros()
            || spring.stiffness.partial_cmp(&0.0) != Some(Ordering::Greater)
        {
            return None;
        }
        let offset = x[bob] - x[anchor];
        let length = offset.norm();
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        let axis = offset / length;
        let along = |w: Vec3| {
            let a = w.dot(&axis);
            ((w - a * axis).norm() <= ACROSS * w.norm()).then_some(a)
        };
        let g = along(system.gravity().unwrap_or_else(Vec3::zeros))?;
        let v0 = along(v[bob])?;
        let (m, k) = (system.masses()[bob], spring.stiffness);
        let equilibrium = spring.rest_length + m * g / k;
        let u0 = length - equilibrium;
        let amplitude = (u0 * u0 + m * v0 * v0 / k).sqrt();
        if spring.rest_length > 0.0
            && equilibrium.partial_cmp(&amplitude) != Some(Ordering::Greater)
        {
            return None;
        }
        Some(Self {
            anchor,
            bob,
            origin: x[anchor],
            axis,
            equilibrium,
            oscillator: Oscillator {
                mass: m,
                stiffness: k,
                damping: spring.damping,
                displacement: u0,
                velocity: v0,
            },
        })
    }

    /// The bob's position at time `t`, `origin + (x* + u(t)) e`.
    #[must_use]
    pub fn bob_position(&self, t: f64) -> Vec3 {
        self.origin + (self.equilibrium + self.oscillator.displacement(t)) * self.axis
    }

    /// Every particle's position at time `t`.
    pub(crate) fn positions(&self, t: f64) -> Vec<Vec3> {
        let mut x = vec![self.origin; 2];
        x[self.bob] = self.bob_position(t);
        x
    }
}

/// The positions of a run at each checkpoint.
pub(crate) type Checkpoints = Vec<Vec<Vec3>>;

/// `√(Σ_free |aᵢ − bᵢ|² / n_free)`, the RMS over the free particles.
pub(crate) fn rms(free: &[usize], a: &[Vec3], b: &[Vec3]) -> f64 {
    if free.is_empty() {
        return 0.0;
    }
    let sum: f64 = free.iter().map(|&i| (a[i] - b[i]).norm_squared()).sum();
    (sum / free.len() as f64).sqrt()
}

/// Classical Runge–Kutta's order, which the Richardson estimate assumes at
/// most.
const RK4_ORDER: f64 = 4.0;

/// A numerical reference: classical Runge–Kutta at step `h` (the
/// reference), `2h` and `4h`, all landing on the checkpoints.
///
/// With `D₁ = max_k ‖x_{2h}(t_k) − x_h(t_k)‖` and
/// `D₂ = max_k ‖x_{4h}(t_k) − x_{2h}(t_k)‖` (RMS over the free particles),
/// the observed order is `p = log₂(D₂/D₁)` and the estimated error of the
/// reference
///
/// ```text
/// ε_ref = D₁ / (2^q − 1),   q = min(p, 4),
/// ```
///
/// Richardson's estimate for a method of order `q` (for `x_h − x ≈ C hᵠ`,
/// `x_{2h} − x_h ≈ (2ᵠ − 1) C hᵠ`). Taking `q` no larger than the observed
/// `p` keeps the estimate honest where the motion is not smooth (contacts)
/// and the reference converges more slowly than fourth order. Where the
/// differences do not shrink (`p ≤ 0`) they are rounding or an
/// unconverged reference, and the estimate is `D₁`: either way no smaller
/// error can be measured against it, which is what the runs' `resolved`
/// flag then says.
#[derive(Debug, Clone)]
pub(crate) struct Numerical {
    /// The reference's positions at the checkpoints.
    pub checkpoints: Checkpoints,
    /// The reference's step `h`, s.
    pub step: f64,
    /// `ε_ref`, m.
    pub estimated_error: f64,
    /// `p`, when `D₁` and `D₂` are positive.
    pub observed_order: Option<f64>,
}

/// The method of numerical references.
pub(crate) const REFERENCE_METHOD: Method = Method::Explicit(ExplicitMethod::Rk4);

/// Runs the numerical reference with a step of at most `requested` that
/// divides the frame interval into a multiple of four steps; the three runs
/// go in parallel with the `parallel` feature.
pub(crate) fn numerical(
    system: &System,
    free: &[usize],
    duration: f64,
    frames: usize,
    requested: f64,
) -> Result<Numerical, LabError> {
    let interval = duration / frames as f64;
    let coarse_per_frame = steps_per_interval(interval, 4.0 * requested);
    let levels = [4, 2, 1];
    let solve = |&factor: &usize| -> Result<Checkpoints, LabError> {
        let per_frame = coarse_per_frame * (4 / factor);
        let step = interval / per_frame as f64;
        let mut integrator = Settings::default().build(REFERENCE_METHOD, None)?;
        let mut checkpoints = Vec::with_capacity(frames);
        let mut state = system.initial_state();
        let mut record = ObserveFn(|_: &System, state: &State, _: &StepInfo| {
            checkpoints.push(state.positions().to_vec());
            ControlFlow::Continue(())
        });
        let run = Simulation::new(system, &mut integrator)
            .observe(per_frame, &mut record)
            .run_to_end(&mut state, step, per_frame * frames);
        match run.failure() {
            None => Ok(checkpoints),
            Some(error) => Err(LabError::Reference {
                method: REFERENCE_METHOD.name(),
                dt: step,
                reason: error.to_string(),
            }),
        }
    };
    #[cfg(feature = "parallel")]
    let runs = levels
        .par_iter()
        .map(solve)
        .collect::<Result<Vec<_>, _>>()?;
    #[cfg(not(feature = "parallel"))]
    let runs = levels.iter().map(solve).collect::<Result<Vec<_>, _>>()?;
    let largest = |a: &Checkpoints, b: &Checkpoints| {
        a.iter()
            .zip(b)
            .map(|(x, y)| rms(free, x, y))
            .fold(0.0, f64::max)
    };
    let (d2, d1) = (largest(&runs[0], &runs[1]), largest(&runs[1], &runs[2]));
    let observed_order = (d1 > 0.0 && d2 > 0.0).then(|| (d2 / d1).log2());
    let estimated_error = match observed_order {
        _ if d1 == 0.0 => 0.0,
        Some(p) if p > 0.0 => d1 / (2f64.powf(p.min(RK4_ORDER)) - 1.0),
        Some(_) => d1,
        None => d1 / (2f64.powf(RK4_ORDER) - 1.0),
    };
    // The finest level comes last.
    let finest = runs.into_iter().next_back().unwrap_or_default();
    Ok(Numerical {
        checkpoints: finest,
        step: interval / (4 * coarse_per_frame) as f64,
        estimated_error,
        observed_order,
    })
}

/// The number of steps of at most `dt` in `interval`, `⌈interval/dt⌉`
/// (at least one; a ratio within a relative 10⁻⁹ above an integer counts
/// as that integer, so rounding in `dt` does not add a step).
pub(crate) fn steps_per_interval(interval: f64, dt: f64) -> usize {
    let ratio = interval / dt;
    ((ratio * (1.0 - 1e-9)).ceil() as usize).max(1)
}
