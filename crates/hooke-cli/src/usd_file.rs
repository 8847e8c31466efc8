//! [`write_usd`]: the frames of a run, read back from their PLY files, as
//! one USD animation.

use std::path::Path;
use std::time::{Duration, Instant};

use hooke_scenes::{Scene, Timing};
use hooke_viz::{AnimationFrame, Mesh, OutputError, frame_file_name, read_ply, write_usda};

use crate::frames::FrameInfo;
use crate::run_options::USD_FILE;

/// Writes [`USD_FILE`] into `dir` from the `frames` written there, and
/// returns the wall time it took. Frame `k`, taken after `n` steps, gets
/// the time code `n / every` (`every` steps per frame, `n` counted as the
/// frame's time over the step): the frames fall on whole time codes at
/// `1 / (every · dt)` codes per second — the scene's frame rate where a
/// frame is a whole number of steps — and a last frame off that grid
/// between two.
///
/// # Errors
/// [`OutputError`] for a frame that cannot be read back or a file that
/// cannot be written.
pub(crate) fn write_usd(
    dir: &Path,
    scene: &Scene,
    mesh: &Mesh,
    frames: &[FrameInfo],
) -> Result<Duration, OutputError> {
    let started = Instant::now();
    let Timing { dt, frame_rate, .. } = scene.timing;
    let every = scene.timing.steps_per_frame() as f64;
    let rate = 1.0 / (every * dt);
    // The scene's own rate where it is the frames' rate up to rounding.
    let rate = if (rate - frame_rate).abs() <= 1e-9 * frame_rate {
        frame_rate
    } else {
        rate
    };
    let animation: Vec<AnimationFrame> = frames
        .iter()
        .map(|f| AnimationFrame {
            time_code: (f.time / dt).round() / every,
            time: f.time,
        })
        .collect();
    write_usda(&dir.join(USD_FILE), scene, &animation, rate, &mut |k| {
        read_ply(&dir.join(frame_file_name(k)), mesh)
    })?;
    Ok(started.elapsed())
}
