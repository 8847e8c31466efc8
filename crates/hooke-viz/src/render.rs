//! A small software renderer: a frame and its obstacles as a
//! [`Pixmap`], and [`save_png`] to store it.
//!
//! Everything is drawn as flat-shaded triangles and thin lines with the
//! painter's algorithm: planes first (they are floors and walls behind the
//! scene), then all other triangles and lines sorted by mean depth, far
//! first. A triangle's brightness is Lambert's law with ambient light,
//! `a + (1 - a)|n·l|`, two-sided so cloth looks the same from either side;
//! the light comes from over the viewer's left shoulder.

use std::fs::File;
use std::io::Write;
use std::path::Path;

use hooke_core::Vec3;
use tiny_skia::{
    Color, FillRule, GradientStop, LinearGradient, Paint, PathBuilder, Pixmap, Point, Rect,
    SpreadMode, Stroke, Transform,
};

use crate::camera::{Camera, Projected};
use crate::error::OutputError;
use crate::mesh::Mesh;
use crate::style::{Style, color};
use crate::tessellate::{Facet, Tone, tessellate};
use hooke_core::Shape;

/// Something to draw, already projected.
enum Item {
    Triangle([Projected; 3], Color),
    Line(Projected, Projected),
}

impl Item {
    fn depth(&self) -> f64 {
        match self {
            Self::Triangle(p, _) => (p[0].depth + p[1].depth + p[2].depth) / 3.0,
            Self::Line(a, b) => (a.depth + b.depth) * 0.5,
        }
    }
}

/// Draws frames with one camera and style.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Renderer {
    camera: Camera,
    style: Style,
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

    /// Draws `mesh` at `positions` among `obstacles`: triangles filled and
    /// shaded, edges as lines. Parts behind the eye are left out.
    ///
    /// # Errors
    ///
    /// [`OutputError::PositionCount`] or [`OutputError::NonFinitePosition`]
    /// for positions that do not fit the mesh, [`OutputError::InvalidShape`]
    /// for an obstacle that cannot be drawn.
    pub fn render(
        &self,
        mesh: &Mesh,
        positions: &[Vec3],
        obstacles: &[Shape],
    ) -> Result<Pixmap, OutputError> {
        mesh.check_frame(positions)?;
        for (index, shape) in obstacles.iter().enumerate() {
            crate::check_shape(shape, index)?;
        }
        let (width, height) = (self.camera.width(), self.camera.height());
        let mut pixmap = Pixmap::new(width, height).ok_or(OutputError::ImageSize {
            width,
            height,
            limit: crate::camera::MAX_IMAGE_SIDE,
        })?;
        self.background(&mut pixmap);

        let (focus, reach) = (self.camera.target(), self.camera.radius());
        let mut planes = Vec::new();
        let mut facets = Vec::new();
        for shape in obstacles {
            let out = match shape {
                Shape::Plane { .. } => &mut planes,
                _ => &mut facets,
            };
            tessellate(shape, focus, reach, out);
        }
        let corners = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        facets.extend(
            mesh.triangles()
                .iter()
                .filter_map(|t| Facet::new(corners(t), Tone::Body, None)),
        );

        let light = (self.camera.up() * 0.7 - self.camera.right() * 0.35 - self.camera.forward())
            .normalize();
        let mut items: Vec<Item> = facets
            .iter()
            .filter_map(|f| self.project(f, light))
            .collect();
        items.extend(mesh.edges().iter().filter_map(|&[a, b]| {
            let (a, b) = (positions[a as usize], positions[b as usize]);
            Some(Item::Line(self.camera.project(a)?, self.camera.project(b)?))
        }));
        let mut backdrop: Vec<Item> = planes
            .iter()
            .filter_map(|f| self.project(f, light))
            .collect();
        for list in [&mut backdrop, &mut items] {
            list.sort_by(|p, q| q.depth().total_cmp(&p.depth()));
        }
        for item in backdrop.iter().chain(&items) {
            self.draw(&mut pixmap, item);
        }
        Ok(pixmap)
    }

    fn background(&self, pixmap: &mut Pixmap) {
        let (w, h) = (pixmap.width() as f32, pixmap.height() as f32);
        let shader = LinearGradient::new(
            Point::from_xy(0.0, 0.0),
            Point::from_xy(0.0, h),
            vec![
                GradientStop::new(0.0, color(self.style.background_top, 1.0)),
                GradientStop::new(1.0, color(self.style.background_bottom, 1.0)),
            ],
            SpreadMode::Pad,
            Transform::identity(),
        )
        .unwrap_or_else(|| tiny_skia::Shader::SolidColor(color(self.style.background_top, 1.0)));
        let paint = Paint {
            shader,
            ..Paint::default()
        };
        if let Some(rect) = Rect::from_xywh(0.0, 0.0, w, h) {
            pixmap.fill_rect(rect, &paint, Transform::identity(), None);
        }
    }

    /// Projects and shades a facet lit from unit direction `light`, or
    /// `None` if it is behind the eye or turned away on a closed shape.
    fn project(&self, facet: &Facet, light: Vec3) -> Option<Item> {
        let eye = self.camera.eye();
        if !facet.two_sided && facet.normal.dot(&(facet.corners[0] - eye)) >= 0.0 {
            return None;
        }
        let [a, b, c] = facet.corners.map(|p| self.camera.project(p));
        let ambient = self.style.ambient.clamp(0.0, 1.0);
        let shade = ambient + (1.0 - ambient) * facet.normal.dot(&light).abs();
        let base = match facet.tone {
            Tone::Body => self.style.body,
            Tone::Obstacle => self.style.obstacle,
            Tone::Tile(bright) => self.style.floor[usize::from(!bright)],
        };
        Some(Item::Triangle([a?, b?, c?], color(base, shade)))
    }

    fn draw(&self, pixmap: &mut Pixmap, item: &Item) {
        let mut path = PathBuilder::new();
        let mut paint = Paint {
            anti_alias: true,
            ..Paint::default()
        };
        let point = |p: &Projected| (p.x as f32, p.y as f32);
        match item {
            Item::Triangle(corners, fill) => {
                let [a, b, c] = corners.each_ref().map(point);
                path.move_to(a.0, a.1);
                path.line_to(b.0, b.1);
                path.line_to(c.0, c.1);
                path.close();
                paint.set_color(*fill);
                let Some(path) = path.finish() else { return };
                pixmap.fill_path(
                    &path,
                    &paint,
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
                // A hairline in the fill colour closes the seams that
                // anti-aliasing leaves between neighbouring triangles.
                let seam = Stroke {
                    width: 0.5,
                    ..Stroke::default()
                };
                pixmap.stroke_path(&path, &paint, &seam, Transform::identity(), None);
            }
            Item::Line(a, b) => {
                let (a, b) = (point(a), point(b));
                path.move_to(a.0, a.1);
                path.line_to(b.0, b.1);
                paint.set_color(color(self.style.edge, 1.0));
                let width = self.style.line_width;
                if !(width > 0.0 && width.is_finite()) {
                    return;
                }
                let stroke = Stroke {
                    width,
                    ..Stroke::default()
                };
                if let Some(path) = path.finish() {
                    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
                }
            }
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
