//! What the scene-file tests share: parsing a text as `test.toml` and a
//! small cloth.

use std::path::Path;

use hooke_scenes::file::{self, SceneFileError};

/// `text` parsed as the scene file `test.toml`.
pub fn parse(text: &str) -> Result<hooke_scenes::Scene, SceneFileError> {
    file::parse(text, Path::new("test.toml"))
}

/// A 4 × 3 cloth body table.
pub const CLOTH: &str = r#"
[[bodies]]
type = "cloth"
columns = 4
rows = 3
stretch = { stiffness = 100.0 }
"#;
