//! The pictures of a run, drawn once it is over from its frames on disk:
//! the preview of the frame that shows the bodies resting on the obstacles
//! (the drape of a cloth), and the animation, both seen by a camera that
//! frames that resting place.
//!
//! Drawing after the run lets the camera frame where the bodies ended up,
//! which is not known while they fall, and lets the animation's pictures
//! be drawn and quantised in parallel; the frames are read back from their
//! files one at a time, so no more than a few are held in memory.

use std::path::Path;
use std::time::{Duration, Instant};

use hooke_core::{System, Vec3};
use hooke_viz::{
    AnimationWriter, Backdrop, Bounds, Camera, EncodedFrame, MAX_GIF_FRAMES, Mesh, OutputError,
    Pixmap, Renderer, View, frame_file_name, obstacles_at, read_ply, save_png,
};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::frames::FrameInfo;
use crate::run_options::{ANIMATION_FILE, PREVIEW_FILE, RunOptions};

/// A frame whose contacts are at least this share of the run's most is
/// resting on the obstacles. (A falling cloth touches most at the moment
/// it lands, when it is spread widest; resting, it touches less.)
pub(crate) const RESTING_CONTACTS: f64 = 0.5;

/// Most pictures per second of simulated time the animation shows: enough
/// for the motion to read, few enough that drawing them stays a small part
/// of a run.
pub(crate) const MAX_GIF_FPS: f64 = 15.0;

/// Pictures the animation draws and encodes at once.
const BATCH: usize = 8;

/// The frame the preview shows: of the frames whose particles in contact
/// with an obstacle number at least [`RESTING_CONTACTS`] of the most any
/// frame has, the one with the least kinetic energy (the later one on a
/// tie) — the bodies resting on the obstacles, as still as they get, even
/// if they later slide off. Without any contact, the last frame. `None`
/// when no frame was written.
///
/// ```text
/// contacts  0  40  95 100 100  30
/// kinetic   0   9   3   2   5   1     -> frame 3
/// ```
pub(crate) fn preview_frame(frames: &[FrameInfo]) -> Option<usize> {
    let most = frames.iter().map(|f| f.contacts).max()?;
    if most == 0 {
        return Some(frames.len() - 1);
    }
    let resting = RESTING_CONTACTS * most as f64;
    frames
        .iter()
        .enumerate()
        .filter(|(_, f)| f.contacts as f64 >= resting)
        .min_by(|(i, a), (j, b)| a.kinetic.total_cmp(&b.kinetic).then(j.cmp(i)))
        .map(|(i, _)| i)
}

/// The frame written nearest the simulated time `time` (the earlier of
/// two as near); `None` when no frame was written.
pub(crate) fn nearest_frame(frames: &[FrameInfo], time: f64) -> Option<usize> {
    frames
        .iter()
        .enumerate()
        .min_by(|(i, a), (j, b)| {
            (a.time - time)
                .abs()
                .total_cmp(&(b.time - time).abs())
                .then(i.cmp(j))
        })
        .map(|(i, _)| i)
}

/// The box the camera frames: the bodies at the preview frame and the
/// finite obstacles there (their resting place); for a run without
/// contacts, where nothing rests, every frame's bodies instead, so that
/// the whole motion stays in view.
fn framed(system: &System, frames: &[FrameInfo], preview: usize) -> Option<Bounds> {
    let obstacles = obstacles_at(system, frames[preview].time);
    let bodies = if frames.iter().any(|f| f.contacts > 0) {
        frames[preview].bounds
    } else {
        frames.iter().filter_map(|f| f.bounds).reduce(Bounds::union)
    };
    bodies
        .into_iter()
        .chain(Bounds::of_scene(&[], &obstacles))
        .reduce(Bounds::union)
}

/// Draws frame `index` of `dir` with `renderer` over `backdrop` (drawn
/// anew if its floor has moved).
fn draw(
    dir: &Path,
    mesh: &Mesh,
    system: &System,
    (renderer, backdrop): (&Renderer, &Backdrop),
    (index, frame): (usize, &FrameInfo),
) -> Result<Pixmap, OutputError> {
    let positions = read_ply(&dir.join(frame_file_name(index)), mesh)?;
    let obstacles = obstacles_at(system, frame.time);
    renderer.render_over(backdrop, mesh, &positions, &obstacles)
}

/// What [`write_pictures`] drew.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pictures {
    /// The frame the preview shows.
    pub preview: usize,
    /// Its simulated time, s.
    pub preview_time: f64,
    /// Wall time spent drawing and writing.
    pub wall: Duration,
}

/// Writes [`PREVIEW_FILE`] (of the [`preview_frame`], or the
/// [`nearest_frame`] to [`RunOptions::preview_time`]) and, if asked for,
/// [`ANIMATION_FILE`] into `dir` from the `frames` written there; `None`
/// if there are none.
///
/// The animation shows every `s`-th of the `n` frames written at
/// `frame_rate`, `s = max(⌈n / MAX_GIF_FRAMES⌉, ⌈frame_rate / MAX_GIF_FPS⌉)`,
/// each for `s` frame periods, so it plays in about real time.
pub(crate) fn write_pictures(
    dir: &Path,
    mesh: &Mesh,
    system: &System,
    frames: &[FrameInfo],
    frame_rate: f64,
    options: &RunOptions,
) -> Result<Option<Pictures>, OutputError> {
    let started = Instant::now();
    let chosen = match options.preview_time {
        Some(time) => nearest_frame(frames, time),
        None => preview_frame(frames),
    };
    let Some(preview) = chosen else {
        return Ok(None);
    };
    let bounds = framed(system, frames, preview)
        .unwrap_or_else(|| Bounds::new(Vec3::zeros(), Vec3::zeros()));
    let obstacles = obstacles_at(system, frames[preview].time);
    let renderer = |(width, height)| -> Result<_, OutputError> {
        let renderer = Renderer::new(Camera::new(&bounds, width, height, &View::default())?);
        Ok((renderer, renderer.backdrop(&obstacles)?))
    };
    let (still, still_backdrop) = renderer(options.preview_size)?;
    let picture = draw(
        dir,
        mesh,
        system,
        (&still, &still_backdrop),
        (preview, &frames[preview]),
    )?;
    save_png(&picture, &dir.join(PREVIEW_FILE))?;

    if options.gif {
        let stride = frames
            .len()
            .div_ceil(MAX_GIF_FRAMES)
            .max((frame_rate / MAX_GIF_FPS).ceil() as usize)
            .max(1);
        let shown: Vec<_> = frames.iter().enumerate().step_by(stride).collect();
        let (width, height) = options.gif_size;
        let mut writer = AnimationWriter::new(
            &dir.join(ANIMATION_FILE),
            width,
            height,
            frame_rate / stride as f64,
            shown.len(),
        )?;
        let (moving, backdrop) = renderer(options.gif_size)?;
        for batch in shown.chunks(BATCH) {
            let writer_ref = &writer;
            let encode = |&frame: &(usize, &FrameInfo)| -> Result<EncodedFrame, OutputError> {
                let picture = draw(dir, mesh, system, (&moving, &backdrop), frame)?;
                writer_ref.encode(&picture)
            };
            #[cfg(feature = "parallel")]
            let encoded: Vec<_> = batch.par_iter().map(encode).collect();
            #[cfg(not(feature = "parallel"))]
            let encoded: Vec<_> = batch.iter().map(encode).collect();
            for frame in encoded {
                writer.push_encoded(frame?)?;
            }
        }
        writer.finish()?;
    }
    Ok(Some(Pictures {
        preview,
        preview_time: frames[preview].time,
        wall: started.elapsed(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(contacts: &[usize], kinetic: &[f64]) -> Vec<FrameInfo> {
        contacts
            .iter()
            .zip(kinetic)
            .enumerate()
            .map(|(i, (&contacts, &kinetic))| FrameInfo {
                time: i as f64,
                kinetic,
                contacts,
                bounds: None,
            })
            .collect()
    }

    #[test]
    fn the_preview_is_the_stillest_of_the_frames_resting_most_fully() {
        let run = frames(&[0, 40, 95, 100, 100, 30], &[0.0, 9.0, 3.0, 2.0, 5.0, 1.0]);
        // Frame 5 is stiller but has slid off; frame 0 is still but in
        // the air.
        assert_eq!(preview_frame(&run), Some(3));
        let tie = frames(&[0, 100, 100], &[0.0, 2.0, 2.0]);
        assert_eq!(preview_frame(&tie), Some(2));
    }

    #[test]
    fn a_preview_time_picks_the_nearest_frame() {
        let run = frames(&[0, 5, 9, 9], &[1.0, 0.0, 2.0, 3.0]);
        assert_eq!(nearest_frame(&run, 1.2), Some(1));
        assert_eq!(nearest_frame(&run, 1.5), Some(1)); // the earlier of two
        assert_eq!(nearest_frame(&run, 10.0), Some(3));
        assert_eq!(nearest_frame(&[], 1.0), None);
    }

    #[test]
    fn without_contacts_the_preview_is_the_last_frame() {
        assert_eq!(
            preview_frame(&frames(&[0, 0, 0], &[1.0, 0.0, 2.0])),
            Some(2)
        );
        assert_eq!(preview_frame(&[]), None);
    }
}
