//! Stability maps: which integrators stay stable at which stiffness and
//! timestep, and the largest stable timestep of each.
//!
//! A *cell* runs one method on the scene's system with every spring's
//! stiffness multiplied by a scale `s`, at one step `dt`, for
//! `max(duration / dt, min_steps)` steps, watched by an
//! [`EnergyBudget`](crate::EnergyBudget): with `E` the kinetic energy of
//! the free particles plus the elastic energy (and the energy of the
//! system's own terms) and `W` the work of gravity, scripted pins and the
//! terms' external agents (a wind), the run's *energy gain* and *energy ratio* are
//!
//! ```text
//! G(t) = E(t) − E(0) − W(t),       ratio(t) = 1 + G(t) / (E(0) + max_{s≤t} W(s)).
//! ```
//!
//! The exact motion has `G ≤ 0` (zero without dissipation) and a ratio of
//! at most one. A cell is **stable** when every step succeeds with a finite
//! state and the ratio never exceeds `energy_bound` (default
//! [`DEFAULT_ENERGY_BOUND`]):
//!
//! ```text
//! E(t) − E(0) − W(t) ≤ (energy_bound − 1) · (E(0) + max_{s≤t} W(s))   at every step.
//! ```
//!
//! Each cell reports the largest ratio, `max_energy_ratio`, and the
//! largest gain in joules, `max_energy_gain = max_t G(t)`. A cell stops at
//! the first step that breaks the bound, so an unstable cell's
//! `max_energy_ratio` is the first ratio above the bound (and its gain the
//! gain at that step), not the largest the run would have reached.
//!
//! Each cell also records `h·ω_max`, where `ω_max(s) = √s · ω_max(1)` is the
//! largest natural frequency of the linearised system ([`omega_max`]):
//! methods bounded on the undamped oscillator up to `hω = θ_limit`
//! ([`Method::oscillator_stability`]) are stable below that line and
//! blow up above it.
//!
//! # Scenes whose surfaces collide
//!
//! The implicit methods run such a scene as it is. The others cannot keep
//! surfaces apart ([`Method::resolves_surface_contact`]): where only
//! self-collision makes the contact (one cloth), they run the system
//! without it, and the report's `note` says so; where surfaces of
//! different bodies collide, their cells are not `applicable`: not stable,
//! no steps, `stopped` giving the error their first step returns. The limit
//! search leaves such methods out.
//!
//! # On the oscillator
//!
//! On the `oscillator` scene (one bob, `m = 1` kg, on a zero-length spring
//! of stiffness `k`, under gravity `g`) the gain is the energy of the
//! oscillation about the equilibrium `y* = −mg/k` and nothing else: with
//! `u = y − y*`, `E = ½mv² + ½ky² = E_osc + ½ky*² − mg u` where
//! `E_osc = ½mv² + ½ku²`, and gravity's work is `W = mg (u(0) − u)`, so
//!
//! ```text
//! G(t) = E_osc(t) − E_osc(0).
//! ```
//!
//! A linear one-step method multiplies `w = u + i v/ω` by its
//! amplification factor `R(iθ)`, `θ = hω`, at each step, so after `n`
//! steps `G = E_osc(0) (|R|²ⁿ − 1)`: explicit Euler's `R = 1 + iθ` gives
//! `(1 + θ²)ⁿ − 1`, midpoint's and Heun's `R = 1 + iθ − θ²/2` give
//! `(1 + θ⁴/4)ⁿ − 1`. The ratio divides that by `E(0) + max W`, which
//! includes the energy of the bob's place in the spring's field; the gain
//! in joules is the measure to compare with theory (the test
//! `the_reported_gain_is_the_theorys_at_every_stiffness`).
//!
//! # The bound and the limit it finds
//!
//! Below its limit a symplectic method's energy oscillates rather than
//! grows, but the oscillation widens as `hω` approaches the limit: for
//! symplectic Euler the energy of an oscillation released at rest reaches
//! `R = 1 / (1 − hω/2)` times its start. On the `oscillator` scene at
//! stiffness scale 1 (released at rest 1 m above its equilibrium,
//! `E_osc(0) = E(0) = ½` J) the discrete motion's ratio reaches the bound
//! of 10 only above `hω ≈ 1.997` (`R ≈ 730`): the limits found lie within
//! 0.2 % of theory. A tighter bound reports the point where the energy
//! error becomes large rather than where the motion starts to grow.

mod cell;
mod limit;

#[cfg(feature = "parallel")]
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use hooke_scenes::Scene;

use crate::spectrum::{Spectrum, omega_max};
use crate::surfaces::{Systems, Target};
use crate::{LabError, Method, Range, Settings, Shard};
use cell::cell_steps;
pub use cell::{CellRun, run_cell};
pub use limit::LIMIT_SEARCH_H_OMEGA;
use limit::limits;

/// The default energy bound of a stable cell.
pub const DEFAULT_ENERGY_BOUND: f64 = 10.0;

/// What to sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityOptions {
    /// The methods, in report order.
    pub methods: Vec<Method>,
    /// Stiffness scales.
    pub scales: Vec<f64>,
    /// Timesteps, s.
    pub dts: Vec<f64>,
    /// Simulated time per cell, s.
    pub duration: f64,
    /// Fewest steps per cell.
    pub min_steps: usize,
    /// The energy bound of a stable cell.
    pub energy_bound: f64,
    /// The methods' parameters.
    pub settings: Settings,
    /// Also bisect for each method's largest stable step at this stiffness
    /// scale, searching the range of `dts`.
    pub limit_scale: Option<f64>,
    /// Run only this part of the cells and limit searches: the report is
    /// then partial, for [`merge`](crate::merge).
    pub shard: Option<Shard>,
}

impl StabilityOptions {
    /// Every method; stiffness scales 10⁰…10⁹ (19 points), steps
    /// 10⁻⁵…10⁻¹ s (13 points), 1 s per cell and at least 1000 steps,
    /// energy bound 10, the scene's own implicit and adaptive parameters,
    /// no limit search.
    #[must_use]
    pub fn for_scene(scene: &Scene) -> Self {
        Self {
            methods: Method::ALL.to_vec(),
            scales: Range::new(1.0, 1e9, 19).values(),
            dts: Range::new(1e-5, 1e-1, 13).values(),
            duration: 1.0,
            min_steps: 1000,
            energy_bound: DEFAULT_ENERGY_BOUND,
            settings: Settings::from_scene(&scene.integrator),
            limit_scale: None,
            shard: None,
        }
    }

    fn check(&self) -> Result<(), LabError> {
        let (positive, at_least_one) = (LabError::positive, LabError::at_least_one);
        at_least_one("methods", self.methods.len())?;
        at_least_one("stiffness scales", self.scales.len())?;
        at_least_one("dt values", self.dts.len())?;
        for &s in &self.scales {
            positive("stiffness scale", s)?;
        }
        for &dt in &self.dts {
            positive("dt", dt)?;
        }
        positive("duration", self.duration)?;
        if !(self.energy_bound.is_finite() && self.energy_bound >= 1.0) {
            return Err(LabError::Invalid {
                name: "energy bound",
                value: self.energy_bound.to_string(),
                expected: "a finite number of at least 1",
            });
        }
        self.limit_scale
            .map_or(Ok(()), |s| positive("limit stiffness scale", s))
    }
}

/// One run of the sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    /// The method.
    pub integrator: Method,
    /// The stiffness scale.
    pub stiffness_scale: f64,
    /// The step, s.
    pub dt: f64,
    /// Whether the run stayed finite and within the energy bound.
    pub stable: bool,
    /// The largest energy ratio `1 + G(t) / A(t)` seen: one for the exact
    /// motion, above one by the largest fraction of its allowance the
    /// energy gained (see [`EnergyBudget`](crate::EnergyBudget); `null` in
    /// JSON once it was not finite).
    #[serde(deserialize_with = "crate::json::number")]
    pub max_energy_ratio: f64,
    /// The largest energy gain `G(t) = E(t) − E(0) − W(t)` seen, J: at
    /// most zero for the exact motion, positive where the method created
    /// energy; infinite once the energy was not finite, −∞ when no step
    /// succeeded (`null` in JSON in both cases, read back as infinity).
    #[serde(deserialize_with = "crate::json::number")]
    pub max_energy_gain: f64,
    /// `dt · ω_max` at this stiffness.
    pub h_omega: f64,
    /// Wall time inside the integrator's steps, s.
    pub wall_s: f64,
    /// Steps taken (fewer than planned when the run stopped early).
    pub steps: usize,
    /// Why the run stopped early, if it did (or why the method is not
    /// applicable).
    pub stopped: Option<String>,
    /// Whether the method can run the scene: `false` for a method that
    /// cannot keep surfaces apart on a scene where surfaces of different
    /// bodies collide (the cell is then not stable, took no steps, and its
    /// `max_energy_ratio` and `max_energy_gain` are `null`).
    #[serde(default = "applicable")]
    pub applicable: bool,
}

/// The default of [`Cell::applicable`] in reports written before it.
fn applicable() -> bool {
    true
}

/// A method's largest stable step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Limit {
    /// The method.
    pub integrator: Method,
    /// The stiffness scale searched at.
    pub stiffness_scale: f64,
    /// The largest stable step found, s: `null` when every step up to
    /// `searched_up_to` was stable, or when even the smallest was not.
    pub max_stable_dt: Option<f64>,
    /// `max_stable_dt · ω_max`.
    pub h_omega_limit: Option<f64>,
    /// The largest step tried, s.
    pub searched_up_to: f64,
    /// The smallest step tried, s.
    pub searched_down_to: f64,
}

/// The sweep's results; serialises to `stability.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StabilityReport {
    /// The scene's name.
    pub scene: String,
    /// The energy bound of a stable cell.
    pub energy_bound: f64,
    /// Simulated time per cell, s.
    pub duration: f64,
    /// Fewest steps per cell.
    pub min_steps: usize,
    /// The methods swept, in report order.
    pub methods: Vec<Method>,
    /// The stiffness scales swept.
    pub stiffness_scales: Vec<f64>,
    /// The steps swept, s.
    pub dts: Vec<f64>,
    /// `ω_max` at stiffness scale 1, rad/s.
    pub omega_max: f64,
    /// Gershgorin upper bound on `ω_max` at scale 1, rad/s.
    pub omega_max_bound: f64,
    /// Every cell, by method, then stiffness scale, then step.
    pub cells: Vec<Cell>,
    /// Each method's largest stable step, when a limit search was asked
    /// for (methods that are not applicable left out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<Vec<Limit>>,
    /// What the sweep did differently on a scene whose surfaces collide:
    /// which methods ran without self-collision or are not applicable.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// The part of the cells (and limit searches) this report holds, if it
    /// is partial (see [`merge`](crate::merge)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<Shard>,
}

/// Runs the sweep (and the limit search, if asked for) on `scene`,
/// calling `progress(done, total)` as cells finish; cells run in parallel
/// with the `parallel` feature.
///
/// # Errors
/// [`LabError`] naming an option out of range, a stiffness scale the
/// scene's springs cannot take, or a method parameter out of range.
pub fn stability(
    scene: &Scene,
    options: &StabilityOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<StabilityReport, LabError> {
    options.check()?;
    let spectrum: Spectrum = omega_max(&scene.system);
    let systems = options
        .scales
        .iter()
        .map(|&s| Ok(Systems::new(scene.system.with_stiffness_scale(s)?)))
        .collect::<Result<Vec<_>, LabError>>()?;

    let mut jobs: Vec<(Method, usize, f64)> = options
        .methods
        .iter()
        .flat_map(|&m| {
            (0..options.scales.len())
                .flat_map(move |k| options.dts.iter().map(move |&dt| (m, k, dt)))
        })
        .collect();
    if let Some(shard) = options.shard {
        jobs = shard.deal(&jobs);
    }
    let total = jobs.len();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let cell = |&(method, k, dt): &(Method, usize, f64)| -> Result<Cell, LabError> {
        let scale = options.scales[k];
        let steps = cell_steps(options.duration, options.min_steps, dt);
        let run = match systems[k].target(method) {
            Target::Runs(system) => Ok(run_cell(
                system,
                method,
                &options.settings,
                dt,
                steps,
                options.energy_bound,
            )?),
            Target::NotApplicable(reason) => Err(reason),
        };
        let finished = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress(finished, total);
        let h_omega = dt * spectrum.omega_max * scale.sqrt();
        Ok(match run {
            Ok(run) => Cell {
                integrator: method,
                stiffness_scale: scale,
                dt,
                stable: run.stable,
                max_energy_ratio: run.max_energy_ratio,
                max_energy_gain: run.max_energy_gain,
                h_omega,
                wall_s: run.wall_s,
                steps: run.steps,
                stopped: run.stopped,
                applicable: true,
            },
            Err(reason) => Cell {
                integrator: method,
                stiffness_scale: scale,
                dt,
                stable: false,
                max_energy_ratio: f64::INFINITY,
                max_energy_gain: f64::INFINITY,
                h_omega,
                wall_s: 0.0,
                steps: 0,
                stopped: Some(reason),
                applicable: false,
            },
        })
    };
    // Cells differ in cost by orders of magnitude (an adaptive method at
    // 10⁹ times the stiffness against a blow-up in three steps): one cell
    // per task lets an idle thread take the next expensive one.
    #[cfg(feature = "parallel")]
    let cells = jobs
        .par_iter()
        .with_max_len(1)
        .map(cell)
        .collect::<Result<Vec<_>, _>>()?;
    #[cfg(not(feature = "parallel"))]
    let cells = jobs.iter().map(cell).collect::<Result<Vec<_>, _>>()?;

    let limits = match options.limit_scale {
        Some(scale) => Some(limits(scene, options, scale, spectrum.omega_max)?),
        None => None,
    };
    let note = Systems::new(scene.system.clone()).note(&options.methods);
    Ok(StabilityReport {
        scene: scene.name.clone(),
        energy_bound: options.energy_bound,
        duration: options.duration,
        min_steps: options.min_steps,
        methods: options.methods.clone(),
        stiffness_scales: options.scales.clone(),
        dts: options.dts.clone(),
        omega_max: spectrum.omega_max,
        omega_max_bound: spectrum.omega_bound,
        cells,
        limits,
        note,
        shard: options.shard,
    })
}
