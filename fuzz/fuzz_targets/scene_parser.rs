//! Feeds arbitrary UTF-8 text to the scene-file parser, which must return
//! a scene or an error and never panic. The scene is named as if it lay in
//! the repository's `scenes/` folder, so mesh paths mutated from the
//! shipped scenes still find their files.

#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let file = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/fuzz.toml"));
        let _ = hooke_scenes::file::parse(text, file);
    }
});
