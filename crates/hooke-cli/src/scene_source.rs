//! Where a command's scene comes from: a scene file, a built-in scene or
//! the default one.

use std::path::Path;

use hooke_scenes::{Scene, builtin, file};

use crate::cli_error::CliError;

/// The built-in scene `hooke run` runs when given no scene: a free, stiff
/// cloth falling onto a sphere on a floor, with backward Euler.
pub const DEFAULT_SCENE: &str = "stiff-cloth";

/// The scene file at `path`, else the built-in scene `builtin`, else the
/// default scene.
pub(crate) fn load_scene(path: Option<&Path>, builtin: Option<&str>) -> Result<Scene, CliError> {
    Ok(match (path, builtin) {
        (Some(path), _) => file::load(path)?,
        (None, Some(name)) => builtin::load(name)?,
        (None, None) => builtin::load(DEFAULT_SCENE)?,
    })
}
