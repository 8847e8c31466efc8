//! [`FrameWriter`]: the observer that writes a run's PLY frames as it goes
//! and notes, for each, what the choice of the preview needs.

use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use hooke_core::{Observer, Run, State, StepInfo, System};
use hooke_viz::{Bounds, Mesh, OutputError, write_frame};

/// What the runner knows of a written frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FrameInfo {
    /// Simulated time, s.
    pub time: f64,
    /// Kinetic energy, J.
    pub kinetic: f64,
    /// Particles within the contact distance of an obstacle.
    pub contacts: usize,
    /// The box around the particles as the frame file holds them (in
    /// single precision), `None` for a system without any.
    pub bounds: Option<Bounds>,
}

/// Writes the state at the start, after every observed step and at the end
/// (if the last step was not observed) as `frame_NNNNN.ply`, with a
/// [`FrameInfo`] each. A state beyond what a frame file holds (see
/// [`beyond_frame_range`]) is not written. The first error stops the run
/// and is kept for [`FrameWriter::into_result`].
pub(crate) struct FrameWriter {
    dir: PathBuf,
    mesh: Mesh,
    /// A particle this close to an obstacle's surface (or inside it) is in
    /// contact, m.
    contact_distance: f64,
    frames: Vec<FrameInfo>,
    /// Wall time spent writing.
    wall: Duration,
    error: Option<OutputError>,
}

impl FrameWriter {
    /// A writer into `dir` of frames of `mesh`, counting particles within
    /// `contact_distance` of an obstacle as in contact.
    pub(crate) fn new(dir: &Path, mesh: Mesh, contact_distance: f64) -> Self {
        Self {
            dir: dir.to_path_buf(),
            mesh,
            contact_distance,
            frames: Vec::new(),
            wall: Duration::ZERO,
            error: None,
        }
    }

    /// The mesh, what was learnt of each frame written and the wall time
    /// spent writing them, or the first error.
    pub(crate) fn into_result(self) -> Result<(Mesh, Vec<FrameInfo>, Duration), OutputError> {
        match self.error {
            Some(error) => Err(error),
            None => Ok((self.mesh, self.frames, self.wall)),
        }
    }

    fn frame(&mut self, system: &System, state: &State) -> Result<(), OutputError> {
        let positions = state.positions();
        write_frame(&self.dir, self.frames.len(), &self.mesh, positions)?;
        let t = state.time();
        let contacts = positions
            .iter()
            .filter(|&&x| {
                system
                    .obstacles()
                    .iter()
                    .any(|o| o.distance(x, t).0 <= self.contact_distance)
            })
            .count();
        self.frames.push(FrameInfo {
            time: t,
            kinetic: system.energy(state).map_or(f64::NAN, |e| e.kinetic),
            contacts,
            bounds: positions
                .iter()
                .map(|p| {
                    let stored = p.map(|c| f64::from(c as f32));
                    Bounds::new(stored, stored)
                })
                .reduce(Bounds::union),
        });
        Ok(())
    }

    /// Writes `state` unless it is beyond range or the writer has failed.
    fn try_frame(&mut self, system: &System, state: &State) -> ControlFlow<()> {
        let started = Instant::now();
        if self.error.is_none() && beyond_frame_range(state).is_none() {
            if let Err(error) = self.frame(system, state) {
                self.error = Some(error);
            }
        }
        self.wall += started.elapsed();
        if self.error.is_some() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
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
        let last = self.frames.last().map(|f| f.time.to_bits());
        if last != Some(state.time().to_bits()) {
            let _ = self.try_frame(system, state);
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
