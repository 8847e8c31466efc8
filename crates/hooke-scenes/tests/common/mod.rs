//! What the scene tests share: parsing a text as `test.toml`, checking
//! where an error points, a small cloth, and two tets.

use std::path::Path;

use hooke_scenes::TetMesh;
use hooke_scenes::file::{self, SceneFileError};

/// `text` parsed as the scene file `test.toml`.
#[allow(dead_code)] // the mesh tests parse no scene files
pub fn parse(text: &str) -> Result<hooke_scenes::Scene, SceneFileError> {
    file::parse(text, Path::new("test.toml"))
}

/// Parses `text`, expects an error, and checks its file, line and key, in
/// the fields and in the message.
#[allow(dead_code)] // not every scene-file test checks errors
pub fn error_at(text: &str, line: usize, key: &str) -> SceneFileError {
    let error = parse(text).expect_err("the scene should be rejected");
    let message = error.to_string();
    assert_eq!(error.file, Path::new("test.toml"), "{message}");
    assert_eq!(error.line, Some(line), "{message}");
    assert_eq!(error.key, key, "{message}");
    assert!(
        message.starts_with(&format!("test.toml:{line}: {key}: ")),
        "{message}"
    );
    error
}

/// A 4 × 3 cloth body table.
#[allow(dead_code)] // the mesh tests parse no scene files
pub const CLOTH: &str = r#"
[[bodies]]
type = "cloth"
columns = 4
rows = 3
stretch = { stiffness = 100.0 }
"#;

/// Two unit-corner tets sharing the face (1, 2, 3), on either side of it.
#[allow(dead_code)] // only the mesh and volume tests build tets
pub fn two_tets() -> TetMesh {
    TetMesh::new(
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
        ],
        [[0, 1, 2, 3], [4, 1, 3, 2]],
    )
}
