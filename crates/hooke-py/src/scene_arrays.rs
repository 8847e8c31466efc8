//! `Scene.from_arrays`: a scene built from numpy arrays through the same
//! [`SystemBuilder`] calls a scene file's bodies make, so that the same
//! particles, springs, pins, surface and obstacles give the same system.

use hooke_core::{SystemBuilder, Vec3};
use hooke_scenes::{IntegratorSpec, Method, Placement, Scene, SceneBody, Timing};
use pyo3::prelude::*;

use crate::convert::Reader;
use crate::errors::{SceneError, scene_error, settings_error};
use crate::obstacles;

/// The arrays of `Scene.from_arrays`.
pub(crate) struct Arrays<'a, 'py> {
    pub(crate) positions: &'a Bound<'py, PyAny>,
    pub(crate) masses: &'a Bound<'py, PyAny>,
    pub(crate) springs: Option<&'a Bound<'py, PyAny>>,
    pub(crate) stiffness: Option<&'a Bound<'py, PyAny>>,
    pub(crate) rest_lengths: Option<&'a Bound<'py, PyAny>>,
    pub(crate) damping: Option<&'a Bound<'py, PyAny>>,
    pub(crate) velocities: Option<&'a Bound<'py, PyAny>>,
    pub(crate) pins: Option<&'a Bound<'py, PyAny>>,
    pub(crate) triangles: Option<&'a Bound<'py, PyAny>>,
    pub(crate) obstacles: Option<&'a Bound<'py, PyAny>>,
}

/// Everything else `Scene.from_arrays` takes.
pub(crate) struct World<'a> {
    pub(crate) self_collision: bool,
    pub(crate) gravity: (f64, f64, f64),
    pub(crate) air_damping: f64,
    pub(crate) contact_distance: Option<f64>,
    pub(crate) integrator: &'a str,
    pub(crate) timing: Timing,
    pub(crate) name: &'a str,
}

fn reader(name: &str) -> Reader {
    Reader {
        name: name.to_owned(),
        make: SceneError::new_err,
    }
}

/// The scene the arrays describe: one body of every particle, drawn with
/// its triangles, or without any with its springs as segments.
///
/// # Errors
/// A `hooke.SceneError` naming the argument and the row, particle, spring
/// or obstacle at fault; a `hooke.SettingsError` for an unknown integrator.
pub(crate) fn scene_from_arrays(arrays: &Arrays<'_, '_>, world: &World<'_>) -> PyResult<Scene> {
    let Timing {
        dt,
        duration,
        frame_rate,
    } = world.timing;
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(dt) && ok(frame_rate) && duration.is_finite() && duration >= 0.0) {
        return Err(scene_error(format!(
            "timing: dt = {dt}, frame_rate = {frame_rate} must be positive and finite, \
             duration = {duration} finite and not negative"
        )));
    }
    let positions = reader("positions").vectors(arrays.positions, None)?;
    let n = positions.len();
    let masses = reader("masses").per_item(arrays.masses, n)?;
    let velocities = match arrays.velocities {
        Some(v) => reader("velocities").vectors(v, Some(n))?,
        None => vec![Vec3::zeros(); n],
    };
    let springs = match arrays.springs {
        Some(s) => reader("springs").indices::<2>(s, n)?,
        None => Vec::new(),
    };
    let m = springs.len();
    let stiffness = match (arrays.stiffness, m) {
        (Some(k), _) => reader("stiffness").per_item(k, m)?,
        (None, 0) => Vec::new(),
        (None, _) => return Err(scene_error("stiffness: required with springs")),
    };
    let rest_lengths = arrays
        .rest_lengths
        .map(|l| reader("rest_lengths").per_item(l, m))
        .transpose()?;
    let damping = match arrays.damping {
        Some(c) => reader("damping").per_item(c, m)?,
        None => vec![0.0; m],
    };
    let pins = match arrays.pins {
        Some(p) => reader("pins").indices::<1>(p, n)?,
        None => Vec::new(),
    };
    let triangles = match arrays.triangles {
        Some(t) => reader("triangles").indices::<3>(t, n)?,
        None => Vec::new(),
    };
    let method = Method::from_name(world.integrator).ok_or_else(|| {
        settings_error(format!(
            "integrator: got \"{}\", expected one of {}",
            world.integrator,
            Method::names()
        ))
    })?;

    let mut builder = SystemBuilder::new();
    for ((&mass, &x), &v) in masses.iter().zip(&positions).zip(&velocities) {
        builder.particle_with_velocity(mass, x, v);
    }
    for (s, &[i, j]) in springs.iter().enumerate() {
        let entry = builder.spring(i, j, stiffness[s]);
        entry.damping(damping[s]);
        if let Some(lengths) = &rest_lengths {
            entry.rest_length(lengths[s]);
        }
    }
    for &[p] in &pins {
        builder.pin(p);
    }
    if !triangles.is_empty() {
        builder
            .surface(&triangles)
            .self_collision(world.self_collision);
    }
    let gravity = Vec3::new(world.gravity.0, world.gravity.1, world.gravity.2);
    if gravity.norm() > 0.0 || !gravity.iter().all(|c| c.is_finite()) {
        builder.gravity(gravity);
    }
    if world.air_damping != 0.0 {
        builder.air_damping(world.air_damping);
    }
    if let Some(d) = world.contact_distance {
        builder.contact_distance(d);
    }
    if let Some(list) = arrays.obstacles {
        for (k, item) in list.try_iter()?.enumerate() {
            builder.obstacle(obstacles::from_dict(k, &item?)?);
        }
    }
    let system = builder.build().map_err(scene_error)?;
    let segments = if triangles.is_empty() {
        springs
    } else {
        Vec::new()
    };
    Ok(Scene {
        name: world.name.to_owned(),
        system,
        bodies: vec![SceneBody {
            name: world.name.to_owned(),
            placement: Placement {
                first: 0,
                count: n,
                first_tet: 0,
                tet_count: 0,
            },
            triangles,
            segments,
        }],
        integrator: IntegratorSpec::new(method),
        timing: world.timing,
    })
}
