//! [`Summary`]: what a run did, measured, as written to `summary.json`.

use std::path::PathBuf;

use hooke_core::Named;
use hooke_implicit::LinearSolver;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize};

/// The measurements of one run, written to `summary.json` in the output
/// directory.
///
/// Times are wall-clock times of this machine. Energies are the total
/// mechanical energy `T + V_springs + V_gravity` in joules (see
/// [`hooke_core::Energy`]). Counts that only implicit integrators have are
/// `null` (`None`) for explicit ones. Numbers that are not finite are
/// written as `null`, which only happens when a run failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// The scene's name.
    pub scene: String,
    /// The integrator's name, e.g. `"backward-euler"`.
    pub integrator: String,
    /// The settings of an implicit integrator (`None` for the others),
    /// written as the keys of the scene file's `[integrator]` table with
    /// every enum by its table's name: each key that applies to the run's
    /// solver and step, defaults included (`weak_springs` the one used;
    /// `rtol` and `atol` only with error control). See
    /// [`ImplicitSettings::keys`](hooke_implicit::ImplicitSettings::keys).
    #[serde(default, with = "crate::settings_keys")]
    pub implicit_settings: Option<hooke_implicit::ImplicitSettings>,
    /// Step size, s.
    pub dt: f64,
    /// Steps taken (fewer than [`steps_planned`](Self::steps_planned) if
    /// the run failed).
    pub steps: usize,
    /// Steps the scene asked for: its duration over `dt`.
    pub steps_planned: usize,
    /// Simulated time reached, s.
    pub time: f64,
    /// PLY frames written.
    pub frames: usize,
    /// The frame `preview.png` shows (from 0): the bodies resting on the
    /// obstacles (see [`run`](crate::run)); `None` if no frame was written.
    pub preview_frame: Option<usize>,
    /// The simulated time of that frame, s.
    pub preview_time: Option<f64>,
    /// Particles in the system.
    pub particles: usize,
    /// Springs in the system.
    pub springs: usize,
    /// Wall time of the whole run, output included, s.
    pub wall_s: f64,
    /// Wall time spent inside the integrator's steps, s.
    pub simulation_s: f64,
    /// Wall time spent writing the frames, the preview and the animation,
    /// s.
    pub output_s: f64,
    /// Median wall time of one step, ms.
    pub step_ms_median: f64,
    /// Longest wall time of one step, ms.
    pub step_ms_max: f64,
    /// Iterations of the iterative linear solver per step, on average
    /// (0 for a direct solver); `None` if the integrator solves no linear
    /// systems.
    pub linear_iterations_mean: Option<f64>,
    /// Newton iterations per step, on average (1 for linearised steps);
    /// `None` for integrators without them.
    pub newton_iterations_mean: Option<f64>,
    /// Linear systems solved.
    pub linear_solves: usize,
    /// The linear solver of the last solve, its name in the one table of
    /// solver names, [`LinearSolver`]'s [`Named::TABLE`] (`"cholesky"`, `"pcg"`,
    /// `"amg"`: what `solver = "auto"` chose); `None` if the integrator
    /// solves no linear systems.
    #[serde(default, deserialize_with = "solver_name")]
    pub linear_solver: Option<SolverName>,
    /// Linear solves that stopped at their iteration cap.
    pub unconverged_solves: usize,
    /// Steps (or substeps) the integrator accepted: more than
    /// [`steps`](Self::steps) where steps were split, after a rejection,
    /// for conditioning or by error control.
    pub substeps: usize,
    /// Substeps rejected and retried shorter.
    pub rejected_steps: usize,
    /// Most Newton iterations one (sub)step took; `None` for integrators
    /// without them.
    pub newton_iterations_max: Option<usize>,
    /// Largest final Newton residual of a step (relative, see
    /// `hooke_implicit::Implicit`); `None` for integrators without Newton
    /// iterations.
    pub newton_residual_max: Option<f64>,
    /// Steps accepted without converging because their substeps had
    /// reached the floor; each one is named by a warning.
    pub unconverged_steps: usize,
    /// Steps whose energy gain was removed by the implicit methods' last
    /// resort.
    pub energy_corrections: usize,
    /// Largest energy gain of one step beyond the work of external forces
    /// as the implicit integrator measured it, J; `None` for integrators
    /// that do not measure it.
    pub energy_excess_max: Option<f64>,
    /// Largest energy gain `E(t) − E(0) − W(t)` over the steps, J, with
    /// `E` kinetic plus elastic energy and `W` the work of gravity and
    /// scripted pins (see `hooke_lab::EnergyBudget`): at most zero for the
    /// exact motion, whose dissipation only lowers it; zero for a run that
    /// stopped before its first step.
    pub energy_gain: f64,
    /// When [`energy_gain`](Self::energy_gain) was reached, s.
    pub energy_gain_time: f64,
    /// What went wrong without stopping the run, one line each: steps that
    /// did not converge, linear solves stopped at their cap, energy
    /// corrected or gained; `hooke run` prints them.
    pub warnings: Vec<String>,
    /// Proximity queries of the implicit methods' contact — searches of
    /// its pair list, by proximity or swept along a motion
    /// (`StepReport::proximity_queries`); `None` for other integrators.
    pub proximity_queries: Option<usize>,
    /// The share of the stepping time ([`simulation_s`](Self::simulation_s))
    /// the implicit methods' collision detection took: its searches and its
    /// checks of motions (CCD); `None` for other integrators.
    pub detection_share: Option<f64>,
    /// Particles whose motion the implicit methods' per-particle contact
    /// bounds cut (`contact_limit = "particles"`), per Newton iteration on
    /// average; `None` for other integrators.
    pub truncated_particles_mean: Option<f64>,
    /// Most particles one Newton iteration cut; `None` for other
    /// integrators.
    pub truncated_particles_max: Option<usize>,
    /// Newton iterations whose cut step did not lower `Φ` enough and fell
    /// back to the global collision limit; `None` for other integrators.
    pub bound_fallbacks: Option<usize>,
    /// Most contacts at the end of one step as the integrator counts them
    /// (`StepReport::contacts`): particles on or within the contact
    /// distance of an obstacle, and for the implicit methods also the
    /// pairs of surface primitives within the contact distance.
    pub contacts_max: usize,
    /// The contact distance `d̂` of the system's collision surfaces, m
    /// (see `docs/scene-format.md`); `None` for a system without collision
    /// surfaces (then the three fields below are `None` too).
    pub contact_distance: Option<f64>,
    /// Most pairs of surface primitives that may collide — a point and a
    /// triangle, or two edges, of two surfaces or of one that collides
    /// with itself — within the contact distance at once, in the initial
    /// state or after a step: pairs whose distance less their thickness
    /// `(ξ₁ + ξ₂)/2` is below `d̂`, where the implicit methods' barrier
    /// acts.
    pub close_pairs_max: Option<usize>,
    /// The smallest distance between two such primitives within the
    /// contact distance over the initial state and the state after every
    /// step, m: positive as long as no surface passed through another or
    /// itself; `None` when no pair came within the contact distance (or
    /// the system has no collision surfaces).
    pub smallest_distance: Option<f64>,
    /// Pairs of triangles sharing no particle that pass through each other
    /// (an edge of one crosses the other) in the last state, whatever
    /// their surfaces and whether they may collide: 0 when no surface ends
    /// tangled in itself or another. `None` without collision surfaces or
    /// for a last state that is not finite.
    pub intersecting_triangle_pairs: Option<usize>,
    /// [`Summary::intersecting_triangle_pairs`] by the bodies whose
    /// surfaces the triangles belong to: an entry for every pair of bodies
    /// (or body with itself) with any, in the order of the surfaces; empty
    /// when there are none, `None` where that count is.
    #[serde(default)]
    pub intersections: Option<Vec<Intersections>>,
    /// Most volume elements inverted at once — tets whose signed volume
    /// ratio `J = V/V₀` is at most 0 (see `hooke_core::Tet`) — in the
    /// initial state or after a step; `None` for a system without volume
    /// elements (no lattice, tet mesh or layered body). Elements whose
    /// volume energy is off (`volume = false`) are counted too.
    pub inverted_elements_max: Option<usize>,
    /// The smallest volume ratio `J = V/V₀` of a volume element over the
    /// initial state and the state after every step: 1 at rest, below 0
    /// once an element turned inside out; `None` without volume elements.
    pub volume_ratio_min: Option<f64>,
    /// Energy of the initial state, J.
    pub energy_initial: f64,
    /// Energy of the last state, J.
    pub energy_final: f64,
    /// Largest energy over the written frames, J (the last state is one
    /// of them unless the run diverged).
    pub energy_max: f64,
    /// Largest spring strain `|l − L|/L` over the written frames.
    pub max_strain: f64,
    /// Whether every state of the run stayed finite: `false` when a step
    /// produced a NaN or infinite value and the run stopped there.
    pub finite: bool,
    /// Why the run stopped early, or `None` if it ran to the end.
    pub error: Option<String>,
    /// The directory the files were written to.
    pub out: PathBuf,
}

/// The intersecting triangle pairs between the surfaces of two bodies, or
/// of one body with itself, in the last state of a run
/// ([`Summary::intersections`]).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Intersections {
    /// The bodies, by their names in the scene (the same name twice for a
    /// body passing through itself).
    pub bodies: [String; 2],
    /// How many pairs of their triangles intersect.
    pub pairs: usize,
    /// Whether the contact model keeps these surfaces apart: `false` only
    /// for a body with itself whose `self_collision` is off, where
    /// intersections are allowed.
    pub collide: bool,
}

/// A linear solver's name, an entry of [`LinearSolver`]'s table
/// ([`Named::TABLE`]). (A name for the type, so that serde reads it as the
/// table's entry instead of borrowing it from the input.)
pub type SolverName = &'static str;

/// A solver's name read as its entry of [`LinearSolver`]'s table; a name
/// not in the table is an error.
fn solver_name<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<SolverName>, D::Error> {
    Option::<String>::deserialize(deserializer)?
        .map(|name| {
            LinearSolver::from_name(&name)
                .map(LinearSolver::name)
                .ok_or_else(|| {
                    D::Error::custom(format!(
                        "got \"{name}\", expected {}",
                        LinearSolver::quoted_names()
                    ))
                })
        })
        .transpose()
}

/// The median of `values` (the mean of the middle two for an even count),
/// or 0 for none. NaNs sort last.
pub(crate) fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    match sorted.len() {
        0 => 0.0,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::median;

    #[test]
    fn median_of_odd_even_and_empty() {
        assert_relative_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_relative_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_relative_eq!(median(&[]), 0.0);
    }
}
