//! The built-in scenes: the TOML files of the repository's `scenes/`
//! folder, compiled into the library with their meshes, so they load
//! without the repository at hand.
//!
//! ```
//! let scene = hooke_scenes::builtin::load("stiff-cloth")?;
//! assert!(scene.system.particle_count() >= 1600);
//! assert!(hooke_scenes::builtin::load("no-such-scene").is_err());
//! # Ok::<(), hooke_scenes::file::SceneFileError>(())
//! ```

use std::path::Path;

use crate::Scene;
use crate::file::{ErrorKind, Meshes, SceneFileError, parse_with};

/// Each scene: name, one-line description, and its file's text.
const SCENES: [(&str, &str, &str); 13] = [
    (
        "stiff-cloth",
        "the default: a free, stiff 40 × 40 cloth falls onto a sphere on a floor and drapes over it (backward Euler, dt = 1/60 s)",
        include_str!("../../../scenes/stiff-cloth.toml"),
    ),
    (
        "oscillator",
        "one particle on a linear spring to a pinned anchor, ω = 1 rad/s, released above its equilibrium (closed-form solution)",
        include_str!("../../../scenes/oscillator.toml"),
    ),
    (
        "damped-oscillator",
        "the oscillator with a damped spring, ζ = 0.1 (closed-form solution)",
        include_str!("../../../scenes/damped-oscillator.toml"),
    ),
    (
        "chain",
        "a hanging chain: pinned at both ends, sagging under gravity",
        include_str!("../../../scenes/chain.toml"),
    ),
    (
        "cloth-on-sphere",
        "a soft cloth draped over a sphere with friction",
        include_str!("../../../scenes/cloth-on-sphere.toml"),
    ),
    (
        "jelly-cube",
        "a volumetric lattice cube dropped on a floor",
        include_str!("../../../scenes/jelly-cube.toml"),
    ),
    (
        "swinging-rope",
        "a rope whose top end is moved back and forth by a scripted pin",
        include_str!("../../../scenes/swinging-rope.toml"),
    ),
    (
        "tet-bracket",
        "an L-shaped tetrahedral mesh (TetGen) pinned at one end, bending under gravity",
        include_str!("../../../scenes/tet-bracket.toml"),
    ),
    (
        "layered-ball",
        "a layered model of a ball bouncing on a floor",
        include_str!("../../../scenes/layered-ball.toml"),
    ),
    (
        "obj-tube",
        "a tube surface from an OBJ file hanging from its top ring, hit by a moving capsule",
        include_str!("../../../scenes/obj-tube.toml"),
    ),
    (
        "cloth-pile",
        "a 30 × 30 cloth dropped edge-down onto a floor folds onto itself into a pile (self-collision)",
        include_str!("../../../scenes/cloth-pile.toml"),
    ),
    (
        "two-cloths",
        "two 25 × 25 cloths, one turned against the other, fall onto a sphere, the upper onto the lower (surfaces colliding)",
        include_str!("../../../scenes/two-cloths.toml"),
    ),
    (
        "soft-cube",
        "two soft jelly cubes dropped from 1.5 m, one with the default volume energy (it recovers), one with springs only (it can stay inverted)",
        include_str!("../../../scenes/soft-cube.toml"),
    ),
];

/// The meshes the built-in scenes use, by their path relative to the scene.
const MESHES: [(&str, &str); 4] = [
    (
        "meshes/bracket.node",
        include_str!("../../../scenes/meshes/bracket.node"),
    ),
    (
        "meshes/bracket.ele",
        include_str!("../../../scenes/meshes/bracket.ele"),
    ),
    (
        "meshes/icosphere.obj",
        include_str!("../../../scenes/meshes/icosphere.obj"),
    ),
    (
        "meshes/tube.obj",
        include_str!("../../../scenes/meshes/tube.obj"),
    ),
];

/// Every built-in scene's name and a one-line description; the first is
/// the default scene.
pub const NAMES: &[(&str, &str)] = &[
    (SCENES[0].0, SCENES[0].1),
    (SCENES[1].0, SCENES[1].1),
    (SCENES[2].0, SCENES[2].1),
    (SCENES[3].0, SCENES[3].1),
    (SCENES[4].0, SCENES[4].1),
    (SCENES[5].0, SCENES[5].1),
    (SCENES[6].0, SCENES[6].1),
    (SCENES[7].0, SCENES[7].1),
    (SCENES[8].0, SCENES[8].1),
    (SCENES[9].0, SCENES[9].1),
    (SCENES[10].0, SCENES[10].1),
    (SCENES[11].0, SCENES[11].1),
    (SCENES[12].0, SCENES[12].1),
];

/// The built-in scene `name` (see [`NAMES`]); errors name it as
/// `scenes/<name>.toml`.
///
/// # Errors
/// A [`SceneFileError`] listing the names if there is no such scene.
pub fn load(name: &str) -> Result<Scene, SceneFileError> {
    let file = format!("scenes/{name}.toml");
    match SCENES.iter().find(|(n, _, _)| *n == name) {
        Some((_, _, text)) => parse_with(text, Path::new(&file), Meshes::Embedded(&MESHES)),
        None => Err(SceneFileError {
            file: file.into(),
            line: None,
            key: String::new(),
            kind: Box::new(ErrorKind::Invalid {
                value: format!("no built-in scene \"{name}\""),
                expected: format!(
                    "one of {}",
                    NAMES
                        .iter()
                        .map(|(n, _)| format!("\"{n}\""))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }),
        }),
    }
}
