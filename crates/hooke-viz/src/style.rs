//! [`Style`]: the colours, light and line width of a picture.

use tiny_skia::Color;

/// An sRGB colour, 8 bits a channel.
pub type Rgb = [u8; 3];

/// Colours, light and line width of a picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    /// Background at the top of the image, blending into `background_bottom`.
    pub background_top: Rgb,
    /// Background at the bottom of the image.
    pub background_bottom: Rgb,
    /// Triangles of the bodies.
    pub body: Rgb,
    /// Edges of the bodies.
    pub edge: Rgb,
    /// Spheres, boxes and capsules.
    pub obstacle: Rgb,
    /// The light and the dark tiles of planes.
    pub floor: [Rgb; 2],
    /// Share of the light that reaches every surface, clamped to [0, 1].
    pub ambient: f64,
    /// Width of edge lines in pixels; zero, negative or NaN draws no lines.
    pub line_width: f32,
}

impl Default for Style {
    fn default() -> Self {
        Self {
            background_top: [236, 241, 248],
            background_bottom: [196, 207, 222],
            body: [226, 118, 52],
            edge: [38, 44, 66],
            obstacle: [118, 140, 172],
            floor: [[214, 214, 206], [170, 170, 164]],
            ambient: 0.35,
            line_width: 1.5,
        }
    }
}

/// `rgb` scaled by `shade` in [0, 1], opaque.
pub(crate) fn color(rgb: Rgb, shade: f64) -> Color {
    let [r, g, b] = rgb.map(|c| (f64::from(c) * shade.clamp(0.0, 1.0)).round() as u8);
    Color::from_rgba8(r, g, b, 255)
}
