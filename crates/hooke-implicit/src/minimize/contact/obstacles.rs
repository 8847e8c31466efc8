//! The obstacles during one step: where each one is at the step's start
//! and end, each particle's offset from them, and the repairs of positions
//! that lie inside one — which come before any pair, whose barrier is
//! infinite there.

use hooke_core::{Obstacle, Shape, State, System, Vec3};

/// Where the obstacles are: at the step's start or at its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum At {
    /// Along the path at the step's start (the friction is lagged there,
    /// and the energy test's start is measured there).
    Start,
    /// At the step's end: the barrier of every iterate acts against them
    /// there.
    End,
}

/// The obstacles during one step.
#[derive(Debug, Clone, Default)]
pub(crate) struct Obstacles {
    /// Each obstacle's shape at rest.
    rest: Vec<Shape>,
    /// Each obstacle's offset along its path at the step's start.
    start: Vec<Vec3>,
    /// Each obstacle's shape at the end of the step.
    end: Vec<Shape>,
    /// Each obstacle's displacement over the step.
    moved: Vec<Vec3>,
    /// Each particle's offset `ξ/2` from obstacles (half its surface's
    /// thickness).
    offset: Vec<f64>,
}

impl Obstacles {
    /// Places the obstacles of `system` for a step from `time` to
    /// `time + h`; `fresh` for a system not seen before.
    pub(super) fn begin(&mut self, system: &System, time: f64, h: f64, fresh: bool) {
        self.end.clear();
        self.moved.clear();
        for o in system.obstacles() {
            let offset = o.path.offset(time + h);
            self.end.push(o.shape.translated(offset));
            self.moved.push(offset - o.path.offset(time));
        }
        self.place_start(system, time);
        if fresh {
            self.offset = vec![0.0; system.particle_count()];
            let mesh = system.surfaces();
            for (k, &p) in mesh.vertices().iter().enumerate() {
                self.offset[p] = 0.5 * system.surface_thickness(mesh.vertex_group(k));
            }
        }
    }

    /// Places the obstacles of the step's start at `time`.
    pub(super) fn place_start(&mut self, system: &System, time: f64) {
        self.rest.clear();
        self.start.clear();
        for o in system.obstacles() {
            self.rest.push(o.shape);
            self.start.push(o.path.offset(time));
        }
    }

    /// The number of obstacles.
    pub(super) fn len(&self) -> usize {
        self.end.len()
    }

    /// Whether there are none.
    pub(super) fn is_empty(&self) -> bool {
        self.end.is_empty()
    }

    /// Each obstacle's displacement over the step.
    pub(super) fn moved(&self) -> &[Vec3] {
        &self.moved
    }

    /// Particle `i`'s offset `ξ/2` from the obstacles.
    pub(super) fn offset(&self, i: usize) -> f64 {
        self.offset[i]
    }

    /// Obstacle `k`'s shape at the step's end.
    pub(super) fn shape(&self, k: usize) -> &Shape {
        &self.end[k]
    }

    /// Obstacle `k`'s offset from its rest placement `at` the start or the
    /// end of the step.
    pub(super) fn placed(&self, k: usize, at: At) -> Vec3 {
        match at {
            At::Start => self.start[k],
            At::End => self.start[k] + self.moved[k],
        }
    }

    /// The gap `g` of particle `i` at `x` to obstacle `k` where it is `at`,
    /// and the outward normal.
    pub(super) fn gap(&self, k: usize, i: usize, x: Vec3, at: At) -> (f64, Vec3) {
        let (phi, n) = match at {
            At::Start => self.rest[k].distance(x - self.start[k]),
            At::End => self.end[k].distance(x),
        };
        (phi - self.offset[i], n)
    }

    /// The gap of particle `i` at `x` to obstacle `o` at time `t`.
    fn gap_at(&self, o: &Obstacle, i: usize, x: Vec3, t: f64) -> (f64, Vec3) {
        let (phi, n) = o.distance(x, t);
        (phi - self.offset[i], n)
    }

    /// Moves every free particle of `state` that lies inside an obstacle,
    /// or within its offset of one, out along the normal to half the
    /// contact distance `d̂`; returns how many moves it made. A state with
    /// nothing to move is left untouched.
    pub(super) fn push_out(&self, system: &System, state: &mut State, activation: f64) -> usize {
        let time = state.time();
        let inside = |i: usize, x: &Vec3| {
            !system.is_pinned(i)
                && system
                    .obstacles()
                    .iter()
                    .any(|o| self.gap_at(o, i, *x, time).0 <= 0.0)
        };
        let Some(first) = state
            .positions()
            .iter()
            .enumerate()
            .position(|(i, x)| inside(i, x))
        else {
            return 0;
        };
        let mut moved = 0;
        for (i, x) in state.positions_mut().iter_mut().enumerate().skip(first) {
            if system.is_pinned(i) {
                continue;
            }
            for o in system.obstacles() {
                let (gap, normal) = self.gap_at(o, i, *x, time);
                if gap <= 0.0 {
                    *x += (0.5 * activation - gap) * normal;
                    moved += 1;
                }
            }
        }
        moved
    }

    /// Sets `start` to the feasible positions a step from `x0` at `time`
    /// starts from: every free particle within the contact distance `d̂` of
    /// a moving obstacle carried along by its displacement over the step
    /// (the first such obstacle's), then pushed out of every obstacle it
    /// lies inside at the step's end, to half the contact distance.
    pub(super) fn feasible_start(
        &self,
        system: &System,
        (x0, time): (&[Vec3], f64),
        activation: f64,
        start: &mut Vec<Vec3>,
    ) {
        start.clear();
        start.extend_from_slice(x0);
        for (i, x) in start.iter_mut().enumerate() {
            if system.is_pinned(i) {
                continue;
            }
            for (k, o) in system.obstacles().iter().enumerate() {
                let moved = self.moved[k];
                if moved != Vec3::zeros() && self.gap_at(o, i, x0[i], time).0 < activation {
                    *x += moved;
                    break;
                }
            }
            for k in 0..self.len() {
                let (gap, normal) = self.gap(k, i, *x, At::End);
                if gap <= 0.0 {
                    *x += (0.5 * activation - gap) * normal;
                }
            }
        }
    }
}
