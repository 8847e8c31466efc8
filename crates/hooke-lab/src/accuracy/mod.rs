//! Error against run time, and the observed order of convergence.
//!
//! # Runs
//!
//! The run time `T` is split into `F` frame intervals ending at the
//! checkpoints ("written frames") `t_k = T k / F`, `k = 1…F`. A fixed-step
//! method asked for a step `dt` takes the largest step that divides a frame
//! interval, `h = (T/F) / ⌈(T/F)/dt⌉ ≤ dt`, so it lands on every
//! checkpoint; the report gives both `dt` and `h` (`step`). Adaptive
//! Dormand–Prince is called once per frame interval (its own substeps
//! inside) for each tolerance; its `step` is the mean accepted substep
//! `T / steps`.
//!
//! # Error
//!
//! On the free (unpinned) particles, with `x` the run and `x̂` the
//! reference,
//!
//! ```text
//! e(t) = √( Σ_free |xᵢ(t) − x̂ᵢ(t)|² / n_free ),
//! error_rms = e(T),   error_max = max_k e(t_k).
//! ```
//!
//! Both are `null` for a run that failed (a non-finite state, a solver
//! that broke down) or whose error is not finite.
//!
//! # Reference
//!
//! **Analytic** where the scene is a single oscillator moving along its
//! spring ([`AxialOscillator`]); its estimated error is the rounding of the
//! closed form, `ε·X`, with `ε` the machine epsilon and `X` the largest
//! distance of a free particle from the origin. Otherwise **numerical**:
//! classical Runge–Kutta at a step `h_ref` (by default
//! `min(0.5/ω_max, dt_min/4)`, `ω_max` from [`omega_max`]
//! and `dt_min` the smallest `dt`), checked against runs at `2h_ref` and
//! `4h_ref` by Richardson's estimate (see [`ReferenceReport`]). The
//! reference is reported `converged` when its estimated error is at most a
//! tenth of the smallest `error_rms` measured; each run is marked
//! `resolved` when its `error_rms` is at least ten times the reference's
//! estimated error, and only resolved runs are plotted (and count in the
//! least wall time to an error), so every error plotted lies at least ten
//! times above the reference's own.
//!
//! # Scenes whose surfaces collide
//!
//! The reference, classical Runge–Kutta, cannot keep surfaces apart
//! ([`Method::resolves_surface_contact`](crate::Method::resolves_surface_contact)),
//! and errors measured against a reference must be errors of one motion.
//! So on a scene whose surfaces collide only through self-collision, the
//! reference and every run — the implicit methods' too — take the system
//! without self-collision, and the report's `note` says so; on a scene
//! where surfaces of different bodies collide the measurement cannot be
//! made ([`LabError::SurfaceContact`]).
//!
//! # Observed order
//!
//! For each method, the slope of the least-squares line through
//! `(ln h, ln error_max)` over its runs in the *asymptotic range*:
//!
//! ```text
//! 100 · max(ε_ref, N ε X)  <  error_max  <  S / 100,   h ω_max ≤ 1,
//! ```
//!
//! where `ε_ref` is the reference's estimated error, `N` the run's steps
//! (`N ε X` bounds the rounding error accumulated over `N` steps), and `S`
//! the size of the motion: the largest RMS displacement of the free
//! particles from their initial positions at a checkpoint of the reference.
//! Above the ceiling the error is no longer small against the motion
//! (phase errors of a radian, growth near a stability limit); below the
//! floor the reference's error or rounding dominates. Above `h ω_max = 1`
//! the fastest modes are not resolved: an implicit method damps them out
//! and its error against the reference stalls at their amplitude (on the
//! stiff cloth backward Euler's error falls by only 2.4× over the 11× in
//! `h` from `hω_max = 0.47` to `5.2`). The fit uses `error_max` rather than
//! `error_rms` because one oscillation's error at one instant can pass
//! near zero: on `damped-oscillator`, backward Euler's error at the end
//! time falls from 1.6 mm to 1.1 mm as `h` grows from 0.05 to 0.09 s,
//! while its largest error over the frames grows from 77 to 126 mm. At least three runs
//! must lie in the range, else the order is `null`. For Dormand–Prince, `h`
//! is its mean substep and the order only indicative.
//!
//! # Step variants
//!
//! With [`AccuracyOptions::variants`], backward Euler's step is also run
//! carried out in each of those ways — Newton or L-BFGS to a tolerance,
//! linearised, fast mass-spring at a fixed iteration count — at each of
//! [`AccuracyOptions::variant_dts`], and each run is compared with the same
//! step converged tightly: what stopping early costs, against what it
//! saves in run time ([`variants`]).
//!
//! # Timing
//!
//! Each run is repeated `repeat` times and its wall time is the median of
//! the repeats' time inside the steps ([`Run::wall`](hooke_core::Run::wall));
//! the reference is not timed. The runs go one after another, so that no
//! two compete for the cores (the integrators may use them all on large
//! systems); only the three reference runs, which are not timed, run in
//! parallel with the `parallel` feature. A run that failed is not
//! repeated.
//!
//! # Example
//!
//! ```
//! use hooke_lab::{AccuracyOptions, Method, accuracy};
//! let scene = hooke_scenes::builtin::load("damped-oscillator")?;
//! let mut options = AccuracyOptions::for_scene(&scene);
//! options.methods = vec![Method::from_name("velocity-verlet").unwrap()];
//! options.dts = vec![0.01, 0.02, 0.04];
//! options.repeat = 1;
//! let report = accuracy(&scene, &options, &|_, _| {})?;
//! let order = report.orders[0].observed_order.unwrap();
//! assert!((order - 2.0).abs() < 0.05);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod fit;
mod measure;
mod options;
mod order;
mod reference;
mod report;
pub mod variants;

use hooke_scenes::Scene;

use measure::{jobs, largest_distance, measure, reference};
pub use options::{AccuracyOptions, ReferenceChoice};
pub(crate) use order::conclude;
pub use reference::AxialOscillator;
use reference::REFERENCE_METHOD;
use reference::rms;
pub use report::{AccuracyReport, Order, ReferenceKind, ReferenceReport, Run, Series};
pub use variants::{ConvergedRun, StepVariant, VariantRun};

use crate::LabError;
use crate::spectrum::omega_max;
use crate::surfaces::Systems;

/// Measures `options.methods` on `scene` (see the module docs), calling
/// `progress(done, total)` after the reference and after each run. With
/// [`AccuracyOptions::shard`] it makes only that part's runs and returns a
/// partial report, for [`merge`](crate::merge).
///
/// # Errors
/// [`LabError::Invalid`] naming an option out of range,
/// [`LabError::Parameter`] for a method parameter out of range,
/// [`LabError::Reference`] if the numerical reference run fails,
/// [`LabError::SurfaceContact`] for a scene whose bodies' surfaces collide
/// with each other.
pub fn accuracy(
    scene: &Scene,
    options: &AccuracyOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<AccuracyReport, LabError> {
    options.check()?;
    let systems = Systems::new(scene.system.clone());
    let system = systems.common().ok_or(LabError::SurfaceContact {
        reference: REFERENCE_METHOD.name(),
    })?;
    let note = scene.system.has_surface_contact().then(|| {
        format!(
            "measured without self-collision: the reference ({}) cannot keep surfaces apart, \
             so it and every run, the implicit methods' too, take the scene with \
             self-collision turned off (its bodies may pass through themselves)",
            REFERENCE_METHOD.name()
        )
    });
    let free: Vec<usize> = (0..system.particle_count())
        .filter(|&i| !system.is_pinned(i))
        .collect();
    let omega = omega_max(system).omega_max;
    let interval = options.duration / options.frames as f64;
    let mut jobs = jobs(options, interval);
    if let Some(shard) = options.shard {
        jobs = shard.deal(&jobs);
    }
    let with_variants = options.shard.is_none_or(|s| s.index == 0) && !options.variants.is_empty();
    let variant_runs = if with_variants {
        options.variant_dts.len() * (options.variants.len() + 1)
    } else {
        0
    };
    let total = jobs.len() + 1 + variant_runs;
    let (checkpoints, reference) = reference(system, &free, options, omega)?;
    progress(1, total);
    let mut runs = Vec::with_capacity(jobs.len());
    for (done, job) in jobs.iter().enumerate() {
        runs.push(measure(system, &free, job, options, &checkpoints)?);
        progress(done + 2, total);
    }
    let (converged, variants) = if with_variants {
        let mut done = jobs.len() + 1;
        variants::measure_variants(system, &free, options, &checkpoints, &mut || {
            done += 1;
            progress(done, total);
        })?
    } else {
        (Vec::new(), Vec::new())
    };
    let initial = system.initial_positions();
    let mut report = AccuracyReport {
        scene: scene.name.clone(),
        duration: options.duration,
        frames: options.frames,
        repeat: options.repeat,
        methods: options.methods.clone(),
        dts: options.dts.clone(),
        tolerances: options.tolerances.clone(),
        omega_max: omega,
        motion_scale: checkpoints
            .iter()
            .map(|x| rms(&free, x, initial))
            .fold(0.0, f64::max),
        position_scale: largest_distance(&free, &checkpoints),
        reference,
        runs,
        orders: Vec::new(),
        converged,
        variants,
        note,
        shard: options.shard,
    };
    if report.shard.is_none() {
        conclude(&mut report);
    }
    Ok(report)
}
