//! [`describe`]: a scene in words, as `hooke check` prints it.

use std::fmt::Write;

use hooke_core::{Named, Obstacle, Path, System, Vec3};
use hooke_implicit::{AutoSettings, ImplicitSettings, LinearSolver, Minimizer, PcgSettings};
use hooke_scenes::{IntegratorSpec, Scene, SceneBody};

use crate::cli_error::CliError;
use crate::runner::check_timing;

/// What `scene` contains, one fact a line: its particles and springs, its
/// bodies with what each draws and its volume elements with their modulus
/// (see `hooke_scenes::Volume`), its obstacles, its collision surfaces (how
/// many collide with themselves, their thickness and the contact
/// distance), the system's own terms by name (a wind; see
/// `hooke_core::System::terms`), the integrator with its parameters (an implicit one's
/// settings also as the scene file's keys, every default included) and
/// the timing with the number of steps and frames.
///
/// ```
/// use hooke_scenes::{Cloth, IntegratorSpec, Scene, SceneBody, Timing};
/// let mut builder = hooke_core::SystemBuilder::new();
/// let cloth = Cloth::grid(4, 4).stretch(1e3).build()?;
/// let placement = cloth.add_to(&mut builder);
/// let scene = Scene {
///     name: "small cloth".into(),
///     system: builder.build()?,
///     bodies: vec![SceneBody {
///         name: "cloth".into(),
///         placement,
///         triangles: placement.triangles(&cloth),
///         segments: Vec::new(),
///     }],
///     integrator: IntegratorSpec::backward_euler(),
///     timing: Timing { duration: 1.0, dt: 0.01, frame_rate: 25.0 },
/// };
/// let text = hooke_cli::describe(&scene)?;
/// assert!(text.contains("particles   16"));
/// assert!(text.contains("100 steps"));
/// assert!(text.contains("surfaces    1 (1 colliding with itself)"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`CliError::Parameter`] for integrator parameters out of range and
/// [`CliError::InvalidTiming`] for a timing that cannot be run: the checks
/// a run would fail first.
pub fn describe(scene: &Scene) -> Result<String, CliError> {
    check_timing(&scene.timing)?;
    let integrator = scene.integrator.build()?;
    let system = &scene.system;
    let mut text = String::new();
    let mut line = |label: &str, value: String| {
        // Writing to a String cannot fail.
        let _ = writeln!(text, "{label:<11} {value}");
    };
    line("scene", scene.name.clone());
    line(
        "particles",
        format!(
            "{} ({} pinned)",
            system.particle_count(),
            system.pinned().count()
        ),
    );
    line("springs", system.springs().len().to_string());
    line(
        "gravity",
        system
            .gravity()
            .map_or_else(|| "none".to_owned(), |g| format!("{} m/s²", vector(g))),
    );
    if let Some(gamma) = system.air_damping() {
        line("air damping", format!("{gamma} kg/s"));
    }
    line("bodies", scene.bodies.len().to_string());
    for body in &scene.bodies {
        line("", body_line(system, body));
    }
    line("obstacles", system.obstacles().len().to_string());
    for obstacle in system.obstacles() {
        line("", obstacle_line(obstacle));
    }
    if let Some(surfaces) = surfaces_line(system) {
        line("surfaces", surfaces);
    }
    if !system.terms().is_empty() {
        let names: Vec<&str> = system.terms().iter().map(|t| t.name()).collect();
        line("terms", names.join(", "));
    }
    line(
        "integrator",
        format!(
            "{}{}",
            integrator.name(),
            integrator_parameters(&scene.integrator, system.particle_count())
        ),
    );
    if let IntegratorSpec::Implicit(settings) = &scene.integrator {
        line("settings", settings_line(settings));
    }
    let timing = scene.timing;
    let (steps, every) = (timing.steps(), timing.steps_per_frame());
    line(
        "timing",
        format!(
            "{} s at dt = {}: {steps} steps",
            timing.duration,
            step_text(timing.dt)
        ),
    );
    let cadence = if every == 1 {
        "every step".to_owned()
    } else {
        format!("every {every} steps")
    };
    line(
        "frames",
        format!(
            "{} at {} per second ({cadence})",
            steps / every + 1,
            timing.frame_rate
        ),
    );
    Ok(text)
}

fn body_line(system: &System, body: &SceneBody) -> String {
    let range = body.placement.range();
    let mut parts = vec![format!(
        "{} particles ({}..{})",
        body.placement.count, range.start, range.end
    )];
    if !body.triangles.is_empty() {
        parts.push(format!("{} triangles", body.triangles.len()));
    }
    if !body.segments.is_empty() {
        parts.push(format!("{} segments", body.segments.len()));
    }
    let tets = system
        .tets()
        .get(body.placement.tet_range())
        .unwrap_or_default();
    if let Some(first) = tets.first() {
        // A body's elements share one modulus (`Body::add_to`).
        let modulus = if first.modulus > 0.0 {
            format!("modulus {:.4e} Pa", first.modulus)
        } else {
            "modulus 0: volume energy off, inversion measured only".to_owned()
        };
        parts.push(format!("{} volume elements ({modulus})", tets.len()));
    }
    format!("{}: {}", body.name, parts.join(", "))
}

/// The collision surfaces: how many, how many collide with themselves,
/// the thickest and the contact distance; `None` without any.
fn surfaces_line(system: &System) -> Option<String> {
    let count = system.surface_count();
    if count == 0 {
        return None;
    }
    let mesh = system.surfaces();
    let selfish = (0..count).filter(|&g| mesh.collides(g, g)).count();
    let thickest = (0..count)
        .map(|g| system.surface_thickness(g))
        .fold(0.0, f64::max);
    let thickness = if thickest > 0.0 {
        format!(", thickness up to {thickest} m")
    } else {
        String::new()
    };
    Some(format!(
        "{count} ({selfish} colliding with itself{thickness}), contact distance {:.3e} m",
        system.contact_distance()
    ))
}

fn obstacle_line(obstacle: &Obstacle) -> String {
    let shape = &obstacle.shape;
    let motion = match &obstacle.path {
        Path::Fixed => "fixed".to_owned(),
        Path::Linear { velocity } => format!("moving at {} m/s", vector(*velocity)),
        Path::Keyframes(keys) => format!("moving through {} keyframes", keys.len()),
    };
    format!(
        "{shape}, {motion}, friction {}, restitution {}",
        obstacle.friction, obstacle.restitution
    )
}

/// The parameters of `spec` for a system of `particles` particles.
fn integrator_parameters(spec: &IntegratorSpec, particles: usize) -> String {
    match *spec {
        IntegratorSpec::Explicit(_) => String::new(),
        IntegratorSpec::Adaptive { rtol, atol } => format!(", rtol {rtol}, atol {atol}"),
        IntegratorSpec::FastMassSpring { iterations } => {
            format!(", {iterations} local/global iterations per step")
        }
        IntegratorSpec::Implicit(settings) => implicit_parameters(&settings, particles),
    }
}

/// The implicit step of `settings` for a system of `particles` particles:
/// the solver and the minimiser by their names with what they do, and
/// the substeps.
fn implicit_parameters(settings: &ImplicitSettings, particles: usize) -> String {
    let ImplicitSettings {
        solver,
        minimizer,
        newton_iterations,
        newton_tolerance,
        max_halvings,
        strict,
        error_control,
        ..
    } = *settings;
    let substeps = match error_control {
        Some(control) => format!(
            "error-controlled substeps to rtol {:e}, atol {:e} m",
            control.relative(),
            control.absolute()
        ),
        None => format!("rejected steps halved at most {max_halvings} times"),
    };
    let strict = if strict { ", strict" } else { "" };
    let pcg = |what: &str, pcg: PcgSettings| {
        format!(
            "{what} to {:e} in at most {} iterations",
            pcg.tolerance(),
            pcg.max_iterations()
        )
    };
    let trial = AutoSettings::DEFAULT.trial_particles;
    let what = match solver {
        LinearSolver::Cholesky => "sparse Cholesky".to_owned(),
        LinearSolver::Auto if particles < trial => {
            format!("sparse Cholesky (below {trial} particles)")
        }
        LinearSolver::Auto => "sparse Cholesky, multigrid PCG or block-Jacobi PCG, \
             whichever a timed trial at the first solve (and, when two come close, \
             the next two steps) finds fastest"
            .to_owned(),
        LinearSolver::Amg(settings) => pcg("multigrid PCG", settings),
        LinearSolver::Pcg(settings) => pcg("block-Jacobi PCG", settings),
        LinearSolver::LaggedCholesky(settings) => {
            pcg("PCG with a lagged Cholesky factor", settings)
        }
    };
    let solver_text = format!("{}: {what}", solver.name());
    let step = minimizer.name();
    match minimizer {
        Minimizer::Linearized => {
            format!(", {solver_text}, {step}: Baraff-Witkin, one solve")
        }
        Minimizer::Newton => format!(
            ", {solver_text}, {step}: at most {newton_iterations} Newton iterations to a relative {newton_tolerance:e}, {substeps}{strict}"
        ),
        Minimizer::QuasiNewton { history, carried } => format!(
            ", {step}: L-BFGS (history {history}, {carried} carried into the next step, initial Hessian the spring Laplacian, {}), at most {newton_iterations} iterations to a relative {newton_tolerance:e}, {substeps}{strict}",
            initial_hessian(solver)
        ),
    }
}

/// Every implicit setting as the scene file's `[integrator]` table writes
/// it, `key = value`, the defaults included
/// ([`ImplicitSettings::keys`]), but the scheme (the method's name).
fn settings_line(settings: &ImplicitSettings) -> String {
    settings
        .keys()
        .into_iter()
        .filter(|&(key, _)| key != "scheme")
        .map(|(key, value)| format!("{key} = {value}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// How the quasi-Newton step applies its initial Hessian's inverse under
/// the `solver` setting.
fn initial_hessian(solver: LinearSolver) -> &'static str {
    match solver {
        LinearSolver::Amg(_) => "applied by one multigrid V-cycle",
        LinearSolver::Auto => {
            "factored, or applied by one multigrid V-cycle where the factor is large"
        }
        _ => "factored",
    }
}

/// A step size for people: `1/60 s` when it is the reciprocal of a whole
/// number, otherwise the seconds with six significant digits.
pub(crate) fn step_text(dt: f64) -> String {
    let per_second = dt.recip().round();
    if per_second >= 1.0 && (per_second * dt - 1.0).abs() < 1e-9 {
        format!("1/{per_second} s")
    } else {
        format!("{dt:.6e} s")
    }
}

fn vector(v: Vec3) -> String {
    format!("({}, {}, {})", v.x, v.y, v.z)
}
