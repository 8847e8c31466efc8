//! A frame drawn over its [`Backdrop`]: the bodies' and obstacles' facets
//! shaded onto the floor's picture with their shadows, and the edges.

use hooke_core::{Shape, Vec3};
use tiny_skia::Pixmap;

use crate::backdrop::Backdrop;
use crate::camera::MAX_IMAGE_SIDE;
use crate::error::OutputError;
use crate::mesh::Mesh;
use crate::render::{Palette, Renderer};
use crate::tessellate::{Facet, Tone, tessellate};

impl Renderer {
    /// Draws `mesh` at `positions` among `obstacles`: triangles filled and
    /// shaded, edges as lines, planes as a floor with the soft shadows of
    /// everything else. Parts behind the eye are left out.
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
        self.render_over(&self.backdrop(obstacles)?, mesh, positions, obstacles)
    }

    /// The background and the planes among `obstacles` (the floor), drawn
    /// once so that many frames can be drawn over them with
    /// [`render_over`](Self::render_over): the floor of a run's frames
    /// does not change while its bodies move.
    ///
    /// # Errors
    ///
    /// [`OutputError::InvalidShape`] for an obstacle that cannot be drawn,
    /// [`OutputError::ImageSize`] for a picture too large to allocate.
    pub fn backdrop(&self, obstacles: &[Shape]) -> Result<Backdrop, OutputError> {
        for (index, shape) in obstacles.iter().enumerate() {
            crate::check_shape(shape, index)?;
        }
        Ok(Backdrop::new(self, obstacles))
    }

    /// As [`render`](Self::render), over `backdrop` if it was drawn by this
    /// renderer for the same planes (otherwise over a new one): the same
    /// picture, without drawing the floor again.
    ///
    /// # Errors
    ///
    /// As [`render`](Self::render).
    pub fn render_over(
        &self,
        backdrop: &Backdrop,
        mesh: &Mesh,
        positions: &[Vec3],
        obstacles: &[Shape],
    ) -> Result<Pixmap, OutputError> {
        mesh.check_frame(positions)?;
        for (index, shape) in obstacles.iter().enumerate() {
            crate::check_shape(shape, index)?;
        }
        let fresh;
        let backdrop = if backdrop.fits(self, obstacles) {
            backdrop
        } else {
            fresh = Backdrop::new(self, obstacles);
            &fresh
        };
        let palette = Palette::new(self.style());
        let (focus, reach) = (self.camera().target(), self.camera().radius());
        let mut facets = body_facets(mesh, positions);
        for shape in obstacles {
            if !matches!(shape, Shape::Plane { .. }) {
                tessellate(shape, focus, reach, &mut facets);
            }
        }
        let mut canvas = backdrop.shadowed(self, &facets);
        for facet in &facets {
            self.surface(&mut canvas, facet, &palette);
        }
        for &[a, b] in mesh.edges() {
            self.line(
                &mut canvas,
                positions[a as usize],
                positions[b as usize],
                palette.edge,
            );
        }
        let (width, height) = (self.camera().width(), self.camera().height());
        canvas.resolve().ok_or(OutputError::ImageSize {
            width,
            height,
            limit: MAX_IMAGE_SIDE,
        })
    }
}

/// The facets of a body mesh, each corner carrying its vertex normal: the
/// normalised sum of the (area-weighted) normals of the triangles around
/// the vertex.
fn body_facets(mesh: &Mesh, positions: &[Vec3]) -> Vec<Facet> {
    let corners = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
    let mut normals = vec![Vec3::zeros(); positions.len()];
    for t in mesh.triangles() {
        let [a, b, c] = corners(t);
        let area_normal = (b - a).cross(&(c - a));
        for &v in t {
            normals[v as usize] += area_normal;
        }
    }
    mesh.triangles()
        .iter()
        .filter_map(|t| {
            let facet = Facet::new(corners(t), Tone::Body, None)?;
            let at = t.map(|v| {
                normals[v as usize]
                    .try_normalize(1e-300)
                    .unwrap_or(facet.normal)
            });
            Some(facet.smooth(at))
        })
        .collect()
}
