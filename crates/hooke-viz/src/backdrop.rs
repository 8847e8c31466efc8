//! [`Backdrop`]: the background and the floors of a picture, drawn once for
//! a renderer so that each frame of a run is drawn over a copy of it, with
//! only the frame's own shadows added.
//!
//! A plane is drawn as checkered tiles (see `tessellate.rs`), lit by the
//! key and ambient light, and faded into the background behind it from
//! [`FOG`]`.0` framed radii from the scene over [`FOG`]`.1` more, so the
//! floor has no visible edge. Each sample remembers which plane it shows;
//! a frame's shadows then darken those samples by the share of the key
//! light they lose.

use hooke_core::{Shape, Vec3};

use crate::raster::{Canvas, SUPERSAMPLE};
use crate::render::{Palette, Renderer};
use crate::shadow::shadow_mask;
use crate::tessellate::{Facet, Tone, tessellate};

/// Distance from the scene, in framed radii, at which a floor starts to
/// fade into the background, and over which it fades out.
const FOG: (f64, f64) = (1.5, 3.5);

/// The background and the planes of a picture, drawn by
/// [`Renderer::backdrop`] for [`Renderer::render_over`].
#[derive(Clone)]
pub struct Backdrop {
    renderer: Renderer,
    planes: Vec<Shape>,
    canvas: Canvas,
    /// Which plane each sample shows, as its index in `planes` plus one; 0
    /// where none does.
    plane_of: Vec<u32>,
    /// For each plane, the share of a lit sample's colour that a full
    /// shadow removes: its key light's (shadows fall near the scene, where
    /// there is no fog).
    direct: Vec<f32>,
}

impl std::fmt::Debug for Backdrop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Backdrop")
            .field("renderer", &self.renderer)
            .field("planes", &self.planes)
            .finish_non_exhaustive()
    }
}

impl Backdrop {
    /// The background and the planes among `obstacles` as `renderer` draws
    /// them (the obstacles already checked).
    pub(crate) fn new(renderer: &Renderer, obstacles: &[Shape]) -> Self {
        let camera = renderer.camera();
        let palette = Palette::new(renderer.style());
        let mut canvas = Canvas::new(camera.width(), camera.height(), |t| palette.background(t));
        let (samples_wide, samples_high) = canvas.size();
        let mut plane_of = vec![0; samples_wide * samples_high];
        let planes: Vec<Shape> = obstacles
            .iter()
            .filter(|shape| matches!(shape, Shape::Plane { .. }))
            .copied()
            .collect();
        let (focus, reach) = (camera.target(), camera.radius());
        let light = renderer.light();
        let mut direct = Vec::with_capacity(planes.len());
        for (k, shape) in planes.iter().enumerate() {
            let Shape::Plane { point, normal } = *shape else {
                continue;
            };
            let normal = normal.normalize();
            let seen = if normal.dot(&(camera.eye() - point)) >= 0.0 {
                normal
            } else {
                -normal
            };
            let lit = renderer.intensity(seen, light, 0.0);
            direct.push(1.0 - renderer.intensity(seen, light, 1.0) / lit.max(f32::MIN_POSITIVE));
            let mut tiles = Vec::new();
            tessellate(shape, focus, reach, &mut tiles);
            let foot = focus - normal * (focus - point).dot(&normal);
            let id = u32::try_from(k + 1).unwrap_or(u32::MAX);
            for tile in &tiles {
                draw_tile(renderer, &mut canvas, tile, lit, foot, &palette, |i| {
                    plane_of[i] = id;
                });
            }
        }
        Self {
            renderer: *renderer,
            planes,
            canvas,
            plane_of,
            direct,
        }
    }

    /// Whether this backdrop is `renderer`'s for the planes among
    /// `obstacles`.
    pub(crate) fn fits(&self, renderer: &Renderer, obstacles: &[Shape]) -> bool {
        self.renderer == *renderer
            && obstacles
                .iter()
                .filter(|shape| matches!(shape, Shape::Plane { .. }))
                .eq(self.planes.iter())
    }

    /// A copy of the canvas with the shadows `casters` cast on each plane.
    pub(crate) fn shadowed(&self, renderer: &Renderer, casters: &[Facet]) -> Canvas {
        let mut canvas = self.canvas.clone();
        let strength = renderer.style().shadow.clamp(0.0, 1.0) as f32;
        let camera = renderer.camera();
        let (samples_wide, _) = canvas.size();
        let pixels_wide = samples_wide / SUPERSAMPLE;
        for (k, shape) in self.planes.iter().enumerate() {
            let Shape::Plane { point, normal } = *shape else {
                continue;
            };
            let plane = (point, normal.normalize());
            let Some(mask) = shadow_mask(camera, plane, renderer.light(), casters) else {
                continue;
            };
            let id = u32::try_from(k + 1).unwrap_or(u32::MAX);
            let share = strength * self.direct[k];
            for (index, _) in self.plane_of.iter().enumerate().filter(|&(_, &p)| p == id) {
                let (x, y) = (index % samples_wide, index / samples_wide);
                let shadow = mask[y / SUPERSAMPLE * pixels_wide + x / SUPERSAMPLE];
                if shadow > 0.0 {
                    canvas.darken(index, 1.0 - shadow * share);
                }
            }
        }
        canvas
    }
}

/// Draws a floor tile lit with intensity `lit`, faded into the background behind it with its
/// distance from `foot`; `drawn` is told every sample it covers. Light and
/// fade are computed at the corners and interpolated: a tile is small
/// beside the distance over which they change. A tile faded out entirely
/// is left out: the background's colours are there already.
fn draw_tile(
    renderer: &Renderer,
    canvas: &mut Canvas,
    tile: &Facet,
    lit: f32,
    foot: Vec3,
    palette: &Palette,
    mut drawn: impl FnMut(usize),
) {
    let camera = renderer.camera();
    let reach = camera.radius();
    let beyond = |p: &Vec3| (p - foot).norm() >= (FOG.0 + FOG.1) * reach;
    if tile.corners.iter().all(beyond) {
        return;
    }
    let Some(corners) = renderer.corners(tile) else {
        return;
    };
    let bright = matches!(tile.tone, Tone::Tile(true));
    let base = palette.floor[usize::from(!bright)];
    let height = f64::from(camera.height());
    let colors = [0, 1, 2].map(|k| {
        let p = tile.corners[k];
        let fog = (((p - foot).norm() / reach - FOG.0) / FOG.1).clamp(0.0, 1.0) as f32;
        let row = corners[k].y / SUPERSAMPLE as f64 / height;
        let behind = palette.background(row as f32);
        [0, 1, 2].map(|c| base[c] * lit + (behind[c] - base[c] * lit) * fog)
    });
    canvas.triangle(corners, |index, w| {
        drawn(index);
        [0, 1, 2].map(|c| {
            colors[0][c] * w[0] as f32 + colors[1][c] * w[1] as f32 + colors[2][c] * w[2] as f32
        })
    });
}
