//! [`FrameWriter`]: the observer that writes a run's PLY frames, its
//! animation and, at the end, its preview.

use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

use hooke_core::{Observer, Run, State, StepInfo, System, Vec3};

use hooke_viz::{
    AnimationWriter, Bounds, Camera, MAX_GIF_FRAMES, Mesh, OutputError, Renderer, View,
    obstacles_at, save_png, write_frame,
};

use crate::runner::{ANIMATION_FILE, PREVIEW_FILE};

/// The animation being written and the renderer of its pictures.
struct Animation {
    writer: AnimationWriter,
    renderer: Renderer,
    /// Every how many written frames one is pictured.
    stride: usize,
}

impl Animation {
    /// An animation of about `frames` frames at `frame_rate` per simulated
    /// second, subsampled here (rather than in the writer) so that frames
    /// left out are not rendered at all.
    fn new(
        dir: &Path,
        bounds: &Bounds,
        (width, height): (u32, u32),
        frame_rate: f64,
        frames: usize,
    ) -> Result<Self, OutputError> {
        let stride = frames.div_ceil(MAX_GIF_FRAMES).max(1);
        let camera = Camera::new(bounds, width, height, &View::default())?;
        let writer = AnimationWriter::new(
            &dir.join(ANIMATION_FILE),
            width,
            height,
            frame_rate / stride as f64,
            frames.div_ceil(stride),
        )?;
        Ok(Self {
            writer,
            renderer: Renderer::new(camera),
            stride,
        })
    }
}

/// Writes the state at the start, after every observed step and at the end
/// (if the last step was not observed) as `frame_NNNNN.ply`, pictures every
/// `stride`-th frame into the animation, and renders the last frame
/// written into the preview when the run ends. A state beyond what a frame
/// file holds (see [`beyond_frame_range`]) is not written. The first error
/// stops the run and is kept for [`FrameWriter::into_result`].
pub(crate) struct FrameWriter {
    dir: PathBuf,
    mesh: Mesh,
    bounds: Bounds,
    preview_size: (u32, u32),
    animation: Option<Animation>,
    frames: usize,
    /// Positions and time of the last written frame.
    last_positions: Vec<Vec3>,
    last_time: f64,
    error: Option<OutputError>,
}

impl FrameWriter {
    /// A writer into `dir` of a run of about `frames` frames at
    /// `frame_rate`, with an animation of `gif_size` if asked for.
    pub(crate) fn new(
        dir: &Path,
        mesh: Mesh,
        bounds: Bounds,
        preview_size: (u32, u32),
        gif: Option<((u32, u32), f64, usize)>,
    ) -> Result<Self, OutputError> {
        let animation = gif
            .map(|(size, frame_rate, frames)| {
                Animation::new(dir, &bounds, size, frame_rate, frames)
            })
            .transpose()?;
        Ok(Self {
            dir: dir.to_path_buf(),
            mesh,
            bounds,
            preview_size,
            animation,
            frames: 0,
            last_positions: Vec::new(),
            last_time: 0.0,
            error: None,
        })
    }

    /// The frames written, or the first error.
    pub(crate) fn into_result(self) -> Result<usize, OutputError> {
        self.error.map_or(Ok(self.frames), Err)
    }

    fn frame(&mut self, system: &System, state: &State) -> Result<(), OutputError> {
        let positions = state.positions();
        write_frame(&self.dir, self.frames, &self.mesh, positions)?;
        if let Some(animation) = &mut self.animation {
            if self.frames % animation.stride == 0 {
                let obstacles = obstacles_at(system, state.time());
                let picture = animation
                    .renderer
                    .render(&self.mesh, positions, &obstacles)?;
                animation.writer.push(&picture)?;
            }
        }
        self.frames += 1;
        self.last_positions.clear();
        self.last_positions.extend_from_slice(positions);
        self.last_time = state.time();
        Ok(())
    }

    /// Writes `state` unless it is beyond range or the writer has failed.
    fn try_frame(&mut self, system: &System, state: &State) -> ControlFlow<()> {
        if self.error.is_none() && beyond_frame_range(state).is_none() {
            if let Err(error) = self.frame(system, state) {
                self.error = Some(error);
            }
        }
        if self.error.is_some() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    /// The last frame, the preview and the end of the animation.
    fn close(&mut self, system: &System) -> Result<(), OutputError> {
        let (width, height) = self.preview_size;
        let camera = Camera::new(&self.bounds, width, height, &View::default())?;
        let picture = Renderer::new(camera).render(
            &self.mesh,
            &self.last_positions,
            &obstacles_at(system, self.last_time),
        )?;
        save_png(&picture, &self.dir.join(PREVIEW_FILE))?;
        if let Some(animation) = self.animation.take() {
            animation.writer.finish()?;
        }
        Ok(())
    }
}

impl Observer for FrameWriter {
    fn start(&mut self, system: &System, state: &State) {
        let _ = self.try_frame(system, state);
    }

    fn observe(&mut self, system: &System, state: &State, _step: &StepInfo) -> ControlFlow<()> {
        self.try_frame(system, state)
    }

    fn finish(&mut self, system: &System, state: &State, _run: &Run) {
        if self.last_time.to_bits() != state.time().to_bits() {
            let _ = self.try_frame(system, state);
        }
        if self.error.is_none() {
            self.error = self.close(system).err();
        }
    }
}

/// The first particle whose position a frame file cannot hold: not finite,
/// or beyond the largest single-precision number.
pub(crate) fn beyond_frame_range(state: &State) -> Option<usize> {
    let limit = f64::from(f32::MAX);
    state
        .positions()
        .iter()
        .position(|p| !p.iter().all(|c| c.abs() <= limit))
}
