//! A small software renderer: a frame and its obstacles as a
//! [`Pixmap`], and [`save_png`] to store it.
//!
//! Triangles are filled into a depth-tested, supersampled canvas (see
//! `raster.rs`), so a cloth lying on a sphere or a floor is drawn in front
//! of it wherever it is. Shading is per sample, in linear light, from the
//! normal interpolated between a triangle's corners (the mean of the
//! normals of the triangles around each vertex of a body; the exact
//! surface normal on spheres and capsules), so folds read as smooth
//! curves rather than facets:
//!
//! `I = a (0.55 + 0.45 (1 + n·y)/2) + (1 − a) max(0, n·l) (1 − s σ)`,
//!
//! with `a` the ambient share ([`Style::ambient`]) lit more from the sky
//! than from the ground, `l` the key light ([`Renderer::light`]), from
//! above, over the viewer's left shoulder, and `σ` the share of that light
//! a floor point cannot see (its soft shadow, see `shadow.rs`) weighed by
//! [`Style::shadow`]. Bodies are two-sided: the side a triangle's
//! counter-clockwise normal points to is drawn in [`Style::body`], the
//! other side, lit with the flipped normal, in [`Style::body_back`], so a
//! fold that shows the underside of a cloth stands out. Planes are a
//! checkered floor that fades into the background with distance from the
//! scene.

use std::fs::File;
use std::io::Write;
use std::path::Path;

use hooke_core::Vec3;
use tiny_skia::Pixmap;

use crate::camera::Camera;
use crate::error::OutputError;
use crate::raster::{Canvas, Linear, SUPERSAMPLE, Vertex, to_linear};
use crate::style::{Rgb, Style};
use crate::tessellate::{Facet, Tone};

/// Draws frames with one camera and style.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Renderer {
    camera: Camera,
    style: Style,
}

/// The colours of a picture in linear light.
pub(crate) struct Palette {
    body: [Linear; 2],
    obstacle: Linear,
    pub(crate) floor: [Linear; 2],
    sky: [Linear; 2],
    pub(crate) edge: Linear,
}

impl Palette {
    pub(crate) fn new(style: &Style) -> Self {
        let linear = |rgb: Rgb| rgb.map(to_linear);
        Self {
            body: [linear(style.body), linear(style.body_back)],
            obstacle: linear(style.obstacle),
            floor: style.floor.map(linear),
            sky: [
                linear(style.background_top),
                linear(style.background_bottom),
            ],
            edge: linear(style.edge),
        }
    }

    /// The background at height `t` in the image, 0 at the top and 1 at
    /// the bottom.
    pub(crate) fn background(&self, t: f32) -> Linear {
        let [top, bottom] = self.sky;
        [0, 1, 2].map(|c| top[c] + (bottom[c] - top[c]) * t.clamp(0.0, 1.0))
    }
}

impl Renderer {
    /// A renderer with the default [`Style`].
    #[must_use]
    pub fn new(camera: Camera) -> Self {
        Self {
            camera,
            style: Style::default(),
        }
    }

    /// The same renderer with another style.
    #[must_use]
    pub fn with_style(self, style: Style) -> Self {
        Self { style, ..self }
    }

    /// The camera.
    #[must_use]
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The style.
    #[must_use]
    pub fn style(&self) -> &Style {
        &self.style
    }

    /// Unit vector towards the key light: from above (+y), from the
    /// viewer's left and a little from behind the viewer,
    /// `l ∝ 0.8 y − 0.7 r + 0.35 h`, with `r` the camera's right and `h`
    /// the horizontal direction towards the eye. Light grazing from the
    /// side makes folds read; shadows fall on the floor to the right of
    /// and behind what casts them, where the camera sees them.
    #[must_use]
    pub fn light(&self) -> Vec3 {
        let back = -self.camera.forward();
        let towards_eye = Vec3::new(back.x, 0.0, back.z)
            .try_normalize(1e-9)
            .unwrap_or(self.camera.up());
        (Vec3::y() * 0.8 - self.camera.right() * 0.7 + towards_eye * 0.35).normalize()
    }

    /// Projects `p` onto the canvas, or `None` if it is behind the eye.
    fn vertex(&self, p: Vec3) -> Option<Vertex> {
        let q = self.camera.project(p)?;
        Some(Vertex {
            x: q.x * SUPERSAMPLE as f64,
            y: q.y * SUPERSAMPLE as f64,
            inv_depth: 1.0 / q.depth,
        })
    }

    /// The light a surface of unit normal `n` (turned towards the viewer)
    /// reflects, a fraction `shadowed` of its key light blocked.
    pub(crate) fn intensity(&self, n: Vec3, light: Vec3, shadowed: f64) -> f32 {
        let ambient = self.style.ambient.clamp(0.0, 1.0);
        let sky = 0.5 * (1.0 + n.y);
        let direct = n.dot(&light).max(0.0) * (1.0 - shadowed);
        (ambient * (0.55 + 0.45 * sky) + (1.0 - ambient) * direct) as f32
    }

    /// Draws a body or obstacle facet; a closed shape's facet turned away
    /// from the eye is left out.
    pub(crate) fn surface(&self, canvas: &mut Canvas, facet: &Facet, palette: &Palette) {
        let eye = self.camera.eye();
        let facing = facet.normal.dot(&(eye - facet.corners[0])) > 0.0;
        if !facing && !facet.two_sided {
            return;
        }
        let Some(corners) = self.corners(facet) else {
            return;
        };
        let (side, base) = match facet.tone {
            Tone::Body => {
                let side = if facing { 1.0 } else { -1.0 };
                (side, palette.body[usize::from(!facing)])
            }
            _ => (1.0, palette.obstacle),
        };
        let light = self.light();
        let normals = facet.corner_normals.map(|n| n * side);
        canvas.triangle(corners, |_, w| {
            let n = (normals[0] * w[0] + normals[1] * w[1] + normals[2] * w[2])
                .try_normalize(1e-12)
                .unwrap_or(facet.normal * side);
            let i = self.intensity(n, light, 0.0);
            base.map(|c| c * i)
        });
    }

    /// A facet's corners on the canvas, or `None` if one is behind the eye.
    pub(crate) fn corners(&self, facet: &Facet) -> Option<[Vertex; 3]> {
        let [a, b, c] = facet.corners.map(|p| self.vertex(p));
        Some([a?, b?, c?])
    }

    /// Draws the segment `a`–`b` as a band of [`Style::line_width`] pixels.
    pub(crate) fn line(&self, canvas: &mut Canvas, a: Vec3, b: Vec3, color: Linear) {
        let width = f64::from(self.style.line_width) * SUPERSAMPLE as f64;
        if !(width > 0.0 && width.is_finite()) {
            return;
        }
        let (Some(p), Some(q)) = (self.vertex(a), self.vertex(b)) else {
            return;
        };
        let (dx, dy) = (q.x - p.x, q.y - p.y);
        let length = dx.hypot(dy);
        if length <= f64::EPSILON {
            return;
        }
        let (nx, ny) = (-dy / length * width * 0.5, dx / length * width * 0.5);
        let shift = |v: Vertex, s: f64| Vertex {
            x: v.x + nx * s,
            y: v.y + ny * s,
            ..v
        };
        let band = [shift(p, -1.0), shift(p, 1.0), shift(q, 1.0), shift(q, -1.0)];
        for corners in [[band[0], band[1], band[2]], [band[0], band[2], band[3]]] {
            canvas.triangle(corners, |_, _| color);
        }
    }
}

/// Writes `pixmap` to `path` as a PNG file.
///
/// # Errors
///
/// [`OutputError::Encode`], [`OutputError::Create`] or
/// [`OutputError::Write`], each naming `path`.
pub fn save_png(pixmap: &Pixmap, path: &Path) -> Result<(), OutputError> {
    let bytes = pixmap.encode_png().map_err(|source| OutputError::Encode {
        path: path.to_path_buf(),
        format: "PNG",
        source: Box::new(source),
    })?;
    let mut file = File::create(path).map_err(|source| OutputError::Create {
        path: path.to_path_buf(),
        source,
    })?;
    file.write_all(&bytes).map_err(|source| OutputError::Write {
        path: path.to_path_buf(),
        source,
    })
}
